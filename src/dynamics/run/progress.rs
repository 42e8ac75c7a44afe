//! What a run carries from step to step, and the bookkeeping of an accepted step: its counts
//! against the budgets, its end snapped onto the final time, its recorded row.

use super::options::RunOptions;
use crate::dynamics::stepper::{Advance, Handover};
use crate::dynamics::system::{LagrangeSystem, State};
use crate::dynamics::trajectory::Trajectory;
use crate::error::{Error, Result};

/// What every loop of a run carries from step to step.
#[derive(Clone, Copy)]
pub(super) struct Progress {
    /// The state the next step starts from.
    pub(super) s: State,
    /// The state the step to `s` started from (`s` itself at the start): where a run goes
    /// back to when the system refuses `s` itself (see
    /// [`Runner`](super::step_loop::Runner)'s location of a dead centre).
    pub(super) prev: State,
    /// The step size the method takes (or proposed) next.
    pub(super) h: f64,
    /// What the last step handed on for the next one: q̈ at `s` when it gave them
    /// (Dormand–Prince's last stage, or a recorded row) and its error norm (the step-size
    /// controller's memory).
    pub(super) hand: Handover,
    /// Accepted steps taken.
    pub(super) steps: usize,
    /// Evaluations spent.
    pub(super) evaluations: usize,
    /// Grid steps left until the next recorded one (a countdown rather than a division per
    /// step: every `record_every`-th grid step is recorded).
    pub(super) until_record: usize,
    /// The next step's q̈ at its start came from a recorded row: an evaluation the run counts
    /// when that step is taken (so that counts do not depend on recording).
    pub(super) row_handed: bool,
}

/// The end of a step under way, before the run has looked at it.
pub(super) struct StepEnd<D> {
    /// The state at the step's end.
    pub(super) s1: State,
    /// The step's continuous extension, when it was asked for and the method has one.
    pub(super) dense: Option<D>,
    /// What the step hands on to the next one.
    pub(super) hand: Handover,
    /// The method's proposal for the next step, unless the run shortened this one.
    pub(super) h_next: Option<f64>,
}

/// An error when one more row (other than the end's) would leave no row for the end.
pub(super) fn row_budget(len: usize, opts: &RunOptions, t: f64, t_tol: f64) -> Result<()> {
    if len + 1 >= opts.max_rows && (opts.t_end - t) > t_tol {
        return Err(Error::Budget {
            what: "recorded row",
            limit: opts.max_rows,
            time: t,
        });
    }
    Ok(())
}

/// Takes an accepted step from `s`: checks that it advanced, counts it and its evaluations
/// (with the one a recorded row handed to it, if any), and returns its end and handover.
#[inline(always)]
pub(super) fn accept(
    s: &State,
    adv: &Advance,
    steps: &mut usize,
    evaluations: &mut usize,
    row_handed: &mut bool,
) -> Result<(State, Handover)> {
    advanced(s.t, adv.state.t)?;
    *steps += 1;
    *evaluations = evaluations
        .saturating_add(adv.evaluations)
        .saturating_add(usize::from(std::mem::take(row_handed)));
    Ok((adv.state, adv.handover))
}

/// A step end within rounding of the final time is put on it exactly; q̈ handed on belong to
/// the unsnapped time and are dropped.
#[inline(always)]
pub(super) fn snap_to_end(opts: &RunOptions, t_tol: f64, s1: &mut State, hand1: &mut Handover) {
    if (opts.t_end - s1.t).abs() <= t_tol && s1.t != opts.t_end {
        s1.t = opts.t_end;
        hand1.acceleration = None;
    }
}

/// Records the step end `s1` as a row (one row stays free for the run's end) and, to a
/// method that takes them, hands the row's q̈ on to the step that starts there when the step
/// before handed none. Returns whether it did (the run then counts that evaluation with the
/// next step).
#[allow(clippy::too_many_arguments)]
pub(super) fn record_end<S: LagrangeSystem + ?Sized>(
    sys: &S,
    opts: &RunOptions,
    t_tol: f64,
    takes_rows: bool,
    s1: &State,
    hand1: &mut Handover,
    traj: &mut Trajectory,
    buf: &mut Vec<f64>,
) -> Result<bool> {
    row_budget(traj.len(), opts, s1.t, t_tol)?;
    let a = traj.push_with(sys, s1, buf)?;
    if takes_rows && hand1.acceleration.is_none() {
        hand1.acceleration = Some(a);
        return Ok(true);
    }
    Ok(false)
}

/// The step and evaluation budgets, checked before a step from time `t`.
#[inline]
pub(super) fn budgets(opts: &RunOptions, steps: usize, evaluations: usize, t: f64) -> Result<()> {
    if steps >= opts.max_steps {
        return Err(Error::Budget {
            what: "step",
            limit: opts.max_steps,
            time: t,
        });
    }
    if evaluations >= opts.max_evaluations {
        return Err(Error::Budget {
            what: "evaluation",
            limit: opts.max_evaluations,
            time: t,
        });
    }
    Ok(())
}

/// A step too short to change t (h below the rounding of t) would repeat for ever.
#[inline]
fn advanced(t0: f64, t1: f64) -> Result<()> {
    if t1 <= t0 || t1.is_nan() {
        return Err(Error::Singular {
            what: "run",
            measure: "time advanced by a step (h below the rounding of t)",
            value: t1 - t0,
        });
    }
    Ok(())
}
