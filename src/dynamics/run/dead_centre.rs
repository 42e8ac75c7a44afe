//! A dead centre met inside a step: the last state the system accepts before the one it
//! refuses, located by halving steps of the method towards it.

use super::options::RunOptions;
use super::progress::{budgets, Progress};
use crate::dynamics::stepper::{Handover, Stepper};
use crate::dynamics::system::{accelerations, LagrangeSystem, State};
use crate::error::{Error, Result};

/// Whether the system refused a state at or beyond a dead centre: at it
/// ([`Error::DeadCentre`]), or past a lock where the position no longer assembles
/// ([`Error::NotAssemblable`]: a step that jumped the narrow band around the dead centre).
pub(super) fn refused(e: &Error) -> bool {
    e.dead_centre().is_some() || e.not_assemblable()
}

/// The stop located by [`locate`]: the last accepted state and the dead centre next to it.
pub(super) struct DeadCentre {
    /// The last state the system accepts.
    pub(super) last: State,
    /// The dyad (its index among the plan's groups).
    pub(super) dyad: usize,
    /// Its determinant at the nearest refused state.
    pub(super) value: f64,
}

/// Where the run met the error `e` in the step of `tried` seconds from `p.s`: when `e` is the
/// system refusing a state at or beyond a dead centre, the last state it accepts, located by
/// a walk of halved steps: from the last accepted state, a step of the method of length d
/// (at first half the interval to the refused time; a step of an adaptive method may end
/// sooner, by its error control), its end checked by an evaluation unless the step
/// evaluated it; an accepted end becomes the new start (and d doubles again, up to the
/// first half interval), a refused step (or end) halves d; until d is within 10⁻¹² of
/// max(1, |t|), never past the run's final time. `p` advances to the located state, its
/// steps and evaluations counted. Should `p.s` itself be refused (a method whose step ends
/// on a state it does not evaluate, met by the next step's first stage), the location
/// starts from the step before. Where every refusal on the way was a position that does
/// not assemble (the stages jumped the band of a lock), the dead centre is the one met
/// along the motion's direction from the located state ([`band_ahead`]).
///
/// `None` when `e` is another error, when the run's start itself is refused, or when no
/// refusal on the way named a dead centre (the position fails to assemble for another
/// reason): the run then ends with `e`.
///
/// # Errors
/// [`Error::Budget`] when the run's steps or evaluations run out; any other error of the
/// system or the method on the way.
pub(super) fn locate<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    opts: &RunOptions,
    p: &mut Progress,
    tried: f64,
    e: &Error,
) -> Result<Option<DeadCentre>> {
    if !refused(e) {
        return Ok(None);
    }
    let mut seen = e.dead_centre();
    let (mut lo, mut hand) = (p.s, p.hand);
    let mut hi = lo.t + tried.min(opts.t_end - lo.t);
    if hand.acceleration.is_none() {
        p.evaluations += 1;
        match accelerations(sys, lo.t, &lo.q, &lo.qd) {
            Ok(a) => {
                if method.uses_start_acceleration() {
                    hand.acceleration = Some(a);
                }
            }
            Err(e2) if refused(&e2) && p.prev.t < lo.t => {
                seen = e2.dead_centre().or(seen);
                (hi, lo, hand) = (lo.t, p.prev, Handover::default());
            }
            Err(e2) if refused(&e2) => return Ok(None),
            Err(e2) => return Err(e2),
        }
    }
    let tol = 1e-12 * lo.t.abs().max(1.0);
    // The walk: steps of the method from the last accepted state, of length d, halved where
    // a step (or its end) is refused and doubled again (up to the first interval) where it
    // is accepted, up to the run's final time. A refusal of a longer step from an earlier
    // state (one of its stages overshooting into the band) does not bound the path of the
    // shorter ones: bisecting on it stopped short of the band (by some per cent of the
    // threshold at a coarse step), or failed where the shorter steps pass the refused time
    // still short of the lock; the walk follows the shorter steps to where they too are
    // refused.
    let end = opts.t_end;
    let span = hi - lo.t;
    let mut d = 0.5 * span;
    // A walk that approaches the band ever more slowly (the motion grazing a lock, its speed
    // going to zero there) could creep on at tiny steps until the run's whole budget is
    // spent (seen at 10⁵ hostile rocking-input runs). Halving the distance takes two steps
    // (one accepted, one refused), so 2·log2(span/tol) + 2 suffice for a walk that closes in;
    // past four times that, the last accepted state is the located one.
    let mut walk = 8 * (span / tol).log2().max(1.0) as usize + 8;
    while d > tol && end - lo.t > tol && walk > 0 {
        walk -= 1;
        budgets(opts, p.steps, p.evaluations, lo.t)?;
        let h = d.min(end - lo.t);
        match method.advance_from(sys, &lo, h, Some(hand)) {
            Ok(adv) => {
                p.steps += 1;
                p.evaluations += adv.evaluations;
                let (s1, mut hand1) = (adv.state, adv.handover);
                if s1.t <= lo.t || s1.t.is_nan() {
                    break;
                }
                if hand1.acceleration.is_none() {
                    p.evaluations += 1;
                    match accelerations(sys, s1.t, &s1.q, &s1.qd) {
                        Ok(a) => {
                            if method.uses_start_acceleration() {
                                hand1.acceleration = Some(a);
                            }
                        }
                        Err(e2) if refused(&e2) => {
                            seen = e2.dead_centre().or(seen);
                            d = 0.5 * (s1.t - lo.t);
                            continue;
                        }
                        Err(e2) => return Err(e2),
                    }
                }
                (lo, hand) = (s1, hand1);
                d = (2.0 * d).min(span);
            }
            Err(e2) if refused(&e2) => {
                p.evaluations += method.evaluations_per_step();
                seen = e2.dead_centre().or(seen);
                d = 0.5 * h;
            }
            Err(e2) => return Err(e2),
        }
    }
    if seen.is_none() && d <= tol {
        // Every refusal was a position that does not assemble: the steps' stages jumped the
        // band (a coarse step reaches a lock at a speed the motion does not have there).
        // The dyad is named by the band met along the motion's direction from the last
        // accepted state.
        seen = band_ahead(sys, &lo, p);
    }
    let Some((dyad, value)) = seen else {
        return Ok(None);
    };
    (p.s, p.hand) = (lo, hand);
    Ok(Some(DeadCentre {
        last: lo,
        dyad,
        value,
    }))
}

/// The dead centre (dyad, determinant) met along the motion's direction from `lo`: the
/// positions q + δ·q̇ at lo's speeds, δ doubled from 10⁻¹⁶ s until the system refuses one,
/// then bisected (60 halvings) between the last accepted and the refused one; the first
/// refusal that names a dead centre. `None` when none does (the motion at rest, or another
/// refusal). Probes of the system only (each counted as an evaluation), not states of the
/// run.
fn band_ahead<S: LagrangeSystem + ?Sized>(
    sys: &S,
    lo: &State,
    p: &mut Progress,
) -> Option<(usize, f64)> {
    let mut probe = |delta: f64| -> Option<std::result::Result<(), Error>> {
        p.evaluations += 1;
        let q = lo.q + lo.qd * delta;
        match accelerations(sys, lo.t, &q, &lo.qd) {
            Ok(_) => Some(Ok(())),
            Err(e) if refused(&e) => Some(Err(e)),
            Err(_) => None,
        }
    };
    let (mut ok, mut bad) = (0.0, 1e-16);
    let mut first = loop {
        match probe(bad)? {
            Ok(()) if bad < 1e3 => (ok, bad) = (bad, 2.0 * bad),
            Ok(()) => return None,
            Err(e) => break e,
        }
    };
    for _ in 0..60 {
        if let Some(dc) = first.dead_centre() {
            return Some(dc);
        }
        let mid = 0.5 * (ok + bad);
        match probe(mid)? {
            Ok(()) => ok = mid,
            Err(e) => (bad, first) = (mid, e),
        }
    }
    first.dead_centre()
}
