//! A lock's band stepped across unseen: the system's lock measures
//! ([`LagrangeSystem::lock_measures`]) at the ends of each step, with their rates along the
//! motion, show a dip into the band between them that no evaluated state landed in; the
//! step is taken again in halves until a step or a state is refused there.

use super::dead_centre::refused;
use super::options::RunOptions;
use super::progress::{budgets, Progress};
use crate::dynamics::stepper::Stepper;
use crate::dynamics::system::{accelerations, LagrangeSystem, State};
use crate::error::{Error, Result};

/// The deepest halving of a step looked into (2⁻⁴⁸ of it: below the run's time tolerance
/// for any step the run takes).
const MAX_DEPTH: u32 = 48;

/// The sub-steps one flagged step may spend before it is left as it was: a band is found
/// within two sub-steps a halving (one flagged half a level), so a step that flags on and
/// on is a measure whose rates are steep without a band (four times the deepest search).
const MAX_SUBSTEPS: usize = 8 * MAX_DEPTH as usize;

/// The measures of a state, each with its rate along the motion (1/s).
type Measures = Vec<(f64, f64)>;

/// The lock measures at the ends of the run's steps: those at the state the next step
/// starts from, kept from the step before.
pub(super) struct BandWatch {
    /// The number of measures.
    n: usize,
    /// The state `at` belongs to.
    s: State,
    /// Its measures, `None` where the system could not evaluate them (no check then).
    at: Option<Measures>,
}

/// A refusal met inside a step by the finer walk: the last state accepted before it, the
/// length of the step from there that was refused (or whose end was), and the refusal.
pub(super) struct Refusal {
    pub(super) from: State,
    pub(super) h: f64,
    pub(super) error: Error,
}

impl BandWatch {
    /// The watch of a run of `sys` from `start`; `None` for a system without lock measures.
    pub(super) fn start<S: LagrangeSystem + ?Sized>(sys: &S, start: &State) -> Option<Self> {
        let n = sys.locks();
        (n > 0).then(|| Self {
            n,
            s: *start,
            at: measures(sys, n, start),
        })
    }

    /// Looks at the step from `s` to `s1`: when a measure's V (or a change of sign) lies
    /// between the two ends, the step is walked again from `s` in halves, each flagged half
    /// in halves again, until a sub-step (or its end state) is refused: that refusal. `None`
    /// when there is no dip or the finer walk meets no refusal (the step stands); `s1`'s
    /// measures are kept for the next step. Sub-steps spend `p`'s evaluations (within its
    /// budgets), not its steps.
    ///
    /// # Errors
    /// [`Error::Budget`] when the run's evaluations run out; any other error of the method
    /// or the system on the way.
    pub(super) fn check<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        opts: &RunOptions,
        p: &mut Progress,
        (s, s1): (&State, &State),
    ) -> Result<Option<Refusal>> {
        if self.s != *s {
            self.at = measures(sys, self.n, s);
        }
        let at1 = measures(sys, self.n, s1);
        let h = s1.t - s.t;
        let found = match (&self.at, &at1) {
            (Some(a), Some(b)) if dips(a, b, h) => {
                let mut left = MAX_SUBSTEPS;
                let mut walk = Walk {
                    sys,
                    method,
                    opts,
                    n: self.n,
                    left: &mut left,
                };
                walk.refusal(p, s, a, h, 0)?
            }
            _ => None,
        };
        (self.s, self.at) = (*s1, at1);
        Ok(found)
    }
}

/// The measures at `s` with their rates along its motion, by a difference over a move of
/// 10⁻⁷ of max(|q|, 1) along q̇ (forward, else backward where the forward position is
/// refused); rates 0 at rest. `None` where the system cannot evaluate them at `s` or on
/// either side.
fn measures<S: LagrangeSystem + ?Sized>(sys: &S, n: usize, s: &State) -> Option<Measures> {
    let at = |q| -> Option<Vec<f64>> {
        let mut out = vec![f64::NAN; n];
        sys.lock_measures(&q, &mut out).ok()?;
        out.iter().all(|x| x.is_finite()).then_some(out)
    };
    let g = at(s.q)?;
    let speed = s.qd.amax();
    if speed == 0.0 {
        return Some(g.into_iter().map(|x| (x, 0.0)).collect());
    }
    let dt = 1e-7 * s.q.amax().max(1.0) / speed;
    let (g2, dt) = match at(s.q + s.qd * dt) {
        Some(g2) => (g2, dt),
        None => (at(s.q - s.qd * dt)?, -dt),
    };
    let rates = g.iter().zip(&g2).map(|(a, b)| (b - a) / dt);
    let m: Measures = g.iter().copied().zip(rates).collect();
    m.iter().all(|(_, r)| r.is_finite()).then_some(m)
}

/// Whether a measure may dip into its band between two states `h` apart: it changes sign,
/// or its lower end lies within (|r₀| + |r₁|)·h of zero, so that at the rates of its ends
/// it could reach the band inside the step (or the next). A V whose tip lies between the
/// ends always passes (its lower end is within half its slopes' sum times h of the tip);
/// so does a step that closes in on a band faster than it resolves it, where a coarse
/// path runs past the band a finer one stops in. A measure far from its band at the
/// rates it changes passes never (a run that meets no lock is looked at only); a smooth
/// dip only while its depth is below its curvature times h², so halving a step that
/// dips without a band ends within a few halvings.
fn dips(a: &[(f64, f64)], b: &[(f64, f64)], h: f64) -> bool {
    a.iter().zip(b).any(|(&(g0, r0), &(g1, r1))| {
        let sign_change = (g0 > 0.0) != (g1 > 0.0);
        let near = g0 > 0.0 && g1 > 0.0 && g0.min(g1) < (r0.abs() + r1.abs()) * h;
        sign_change || near
    })
}

/// The finer walk of one flagged step: what it needs, and the sub-steps it has left.
struct Walk<'a, S: ?Sized, M> {
    sys: &'a S,
    method: &'a M,
    opts: &'a RunOptions,
    n: usize,
    left: &'a mut usize,
}

impl<S: LagrangeSystem + ?Sized, M: Stepper> Walk<'_, S, M> {
    /// The first refusal on the way from `s` (its measures `at_s`) over `h`: two sub-steps of
    /// the method of h/2 (an adaptive method's may end sooner: as many as it takes), each
    /// end's accelerations evaluated; a sub-step whose ends dip is walked again the same
    /// way, `depth + 1`. `None` when none is refused (or the walk's sub-steps run out).
    fn refusal(
        &mut self,
        p: &mut Progress,
        s: &State,
        at_s: &[(f64, f64)],
        h: f64,
        depth: u32,
    ) -> Result<Option<Refusal>> {
        let (sys, method) = (self.sys, self.method);
        let end = s.t + h;
        let tol = 1e-12 * s.t.abs().max(1.0);
        let (mut cur, mut at_cur) = (*s, at_s.to_vec());
        while end - cur.t > tol && *self.left > 0 {
            *self.left -= 1;
            budgets(self.opts, p.steps, p.evaluations, cur.t)?;
            let hs = (0.5 * h).min(end - cur.t);
            let adv = match method.advance_from(sys, &cur, hs, None) {
                Ok(adv) => adv,
                Err(e) if refused(&e) => {
                    p.evaluations += method.evaluations_per_step();
                    return Ok(Some(Refusal {
                        from: cur,
                        h: hs,
                        error: e,
                    }));
                }
                Err(e) => return Err(e),
            };
            p.evaluations += adv.evaluations + 1;
            let next = adv.state;
            if next.t <= cur.t || next.t.is_nan() {
                return Ok(None);
            }
            match accelerations(sys, next.t, &next.q, &next.qd) {
                Ok(_) => {}
                Err(e) if refused(&e) => {
                    return Ok(Some(Refusal {
                        from: cur,
                        h: next.t - cur.t,
                        error: e,
                    }))
                }
                Err(e) => return Err(e),
            }
            let Some(at_next) = measures(sys, self.n, &next) else {
                return Ok(None);
            };
            let hn = next.t - cur.t;
            if depth < MAX_DEPTH
                && hn > tol
                && dips(&at_cur, &at_next, hn)
                && let Some(r) = self.refusal(p, &cur, &at_cur, hn, depth + 1)?
            {
                return Ok(Some(r));
            }
            (cur, at_cur) = (next, at_next);
        }
        Ok(None)
    }
}
