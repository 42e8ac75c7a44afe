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
fn refused(e: &Error) -> bool {
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
/// halving: from the last accepted state, a step of the method over half the interval to
/// the earliest refused time (a step of an adaptive method may end sooner, by its error
/// control), its end checked by an evaluation unless the step evaluated it; an accepted end
/// becomes the new start, a refused step (or end) the new refused time; until the two are
/// within 10⁻¹² of max(1, |t|). `p` advances to the located state, its steps and evaluations
/// counted. Should `p.s` itself be refused (a method whose step ends on a state it does not
/// evaluate, met by the next step's first stage), the location starts from the step before.
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
    while hi - lo.t > tol {
        budgets(opts, p.steps, p.evaluations, lo.t)?;
        let h = 0.5 * (hi - lo.t);
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
                            hi = s1.t;
                            continue;
                        }
                        Err(e2) => return Err(e2),
                    }
                }
                (lo, hand) = (s1, hand1);
            }
            Err(e2) if refused(&e2) => {
                p.evaluations += method.evaluations_per_step();
                seen = e2.dead_centre().or(seen);
                hi = lo.t + h;
            }
            Err(e2) => return Err(e2),
        }
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
