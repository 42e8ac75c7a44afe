//! The stop conditions a run checks after each step: a watched quantity reaching its value
//! (located inside the step), and a steady state (or a drift that can never become one).

use nalgebra::Vector2;

use super::locate::{locate, Allowance};
use super::options::{Direction, Reach, RunOptions, Steady, Watch};
use super::outcome::Outcome;
use crate::dynamics::stepper::{Handover, Stepper};
use crate::dynamics::system::{accelerations, LagrangeSystem, State};
use crate::error::{Error, Result};

/// The value of a watched quantity at `s` (`buf` holds the system's outputs).
fn watched<S: LagrangeSystem + ?Sized>(
    sys: &S,
    w: Watch,
    s: &State,
    buf: &mut Vec<f64>,
) -> Result<f64> {
    Ok(match w {
        Watch::Coordinate(i) => s.q[i],
        Watch::Speed(i) => s.qd[i],
        Watch::Output(i) => {
            buf.clear();
            sys.outputs(s.t, &s.q, &s.qd, buf)?;
            // A system whose outputs are fewer than its output names: an error, not a panic.
            *buf.get(i).ok_or(Error::OutOfRange {
                name: "watched output index (outputs given by the system)",
                value: i as f64,
                min: 0.0,
                max: buf.len() as f64 - 1.0,
                ends: crate::Ends::Closed,
            })?
        }
    })
}

fn crosses(d: Direction, g0: f64, g1: f64) -> bool {
    match d {
        Direction::Rising => g0 < 0.0 && g1 >= 0.0,
        Direction::Falling => g0 > 0.0 && g1 <= 0.0,
        Direction::Either => (g0 < 0.0 && g1 >= 0.0) || (g0 > 0.0 && g1 <= 0.0),
    }
}

/// A [`Reach`] condition with the watched quantity's distance from its value at the start of
/// the next step.
pub(super) struct ReachWatch {
    reach: Reach,
    g_prev: f64,
}

impl ReachWatch {
    /// The condition watched from the start `s`.
    pub(super) fn start<S: LagrangeSystem + ?Sized>(
        sys: &S,
        reach: Reach,
        s: &State,
        buf: &mut Vec<f64>,
    ) -> Result<Self> {
        let g_prev = watched(sys, reach.watch, s, buf)? - reach.value;
        Ok(Self { reach, g_prev })
    }

    /// The state at which the step `s` → `s1` reaches the value, located inside it
    /// (re-stepping from `s`, counted into `evaluations`), or `None`.
    pub(super) fn check<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        opts: &RunOptions,
        (s, s1): (&State, &State),
        buf: &mut Vec<f64>,
        evaluations: &mut usize,
    ) -> Result<Option<State>> {
        let r = self.reach;
        let g1 = watched(sys, r.watch, s1, buf)? - r.value;
        let mut hit = None;
        if crosses(r.direction, self.g_prev, g1) {
            let (located, resteps) = locate(
                sys,
                method,
                (s, self.g_prev),
                (s1, g1),
                None,
                Allowance::after(opts, *evaluations),
                |st| Ok(watched(sys, r.watch, st, buf)? - r.value),
            )?;
            *evaluations =
                evaluations.saturating_add(resteps.saturating_mul(method.evaluations_per_step()));
            hit = Some(located);
        }
        self.g_prev = g1;
        Ok(hit)
    }
}

/// A [`Steady`] condition with how long it has held, and the reference of a drift.
pub(super) struct SteadyWatch {
    steady: Steady,
    since: Option<f64>,
    drift_ref: Option<(f64, Vector2<f64>)>,
}

impl SteadyWatch {
    /// The condition, not yet holding.
    pub(super) fn new(steady: Steady) -> Self {
        Self {
            steady,
            since: None,
            drift_ref: None,
        }
    }

    /// The outcome when the state `s1` ends the run ([`Outcome::Steady`] or
    /// [`Outcome::Drifting`]), else `None`; `hand` gives q̈ at `s1` when the step evaluated
    /// them.
    #[inline]
    pub(super) fn check<S: LagrangeSystem + ?Sized>(
        &mut self,
        sys: &S,
        s1: &State,
        hand: Handover,
    ) -> Result<Option<Outcome>> {
        let st = self.steady;
        let acc = match hand.acceleration {
            Some(a) => a,
            None => accelerations(sys, s1.t, &s1.q, &s1.qd)?,
        };
        if acc.amax() <= st.tol {
            self.drift_ref = None;
            let since = *self.since.get_or_insert(s1.t);
            if s1.t - since >= st.hold {
                return Ok(Some(Outcome::Steady { t: s1.t }));
            }
        } else {
            self.since = None;
            match self.drift_ref {
                Some((t0, a0)) if (acc - a0).amax() <= st.tol => {
                    if s1.t - t0 >= st.hold {
                        return Ok(Some(Outcome::Drifting {
                            t: s1.t,
                            acceleration: acc,
                        }));
                    }
                }
                _ => self.drift_ref = Some((s1.t, acc)),
            }
        }
        Ok(None)
    }
}

/// A watch for the motion turning back: coordinate `i`'s speed, which moves in the direction
/// `d` (±1), passing zero to the other side. A speed exactly zero at a step's end (a switch
/// landed on) turns back only when the next step leaves it the other way.
pub(super) struct ReversalWatch {
    i: usize,
    d: f64,
    g_prev: f64,
}

impl ReversalWatch {
    /// The watch from the start `s`.
    pub(super) fn start((i, d): (usize, f64), s: &State) -> Self {
        Self {
            i,
            d,
            g_prev: d * s.qd[i],
        }
    }

    /// The state at which the step `s` → `s1` turns back, located inside it (re-stepping from
    /// `s`, counted into `evaluations`; the step's start when it leaves a zero speed the
    /// other way), or `None`.
    pub(super) fn check<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        opts: &RunOptions,
        (s, s1): (&State, &State),
        evaluations: &mut usize,
    ) -> Result<Option<State>> {
        let (i, d) = (self.i, self.d);
        let (g0, g1) = (self.g_prev, d * s1.qd[i]);
        self.g_prev = g1;
        if !(g0 >= 0.0 && g1 < 0.0) {
            return Ok(None);
        }
        if g0 == 0.0 {
            return Ok(Some(*s));
        }
        let (located, resteps) = locate(
            sys,
            method,
            (s, g0),
            (s1, g1),
            None,
            Allowance::after(opts, *evaluations),
            |st| Ok(d * st.qd[i]),
        )?;
        *evaluations =
            evaluations.saturating_add(resteps.saturating_mul(method.evaluations_per_step()));
        Ok(Some(located))
    }
}
