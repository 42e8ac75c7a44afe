//! Running a machine until a stop condition: a final time, a watched quantity reaching a
//! value (located inside the step), or a steady state.
//!
//! One concept a file: [`options`] (what a run is asked) and [`outcome`] (what it ends
//! with); [`validate`] (the options and the start, checked before anything is evaluated);
//! [`schedule`] (the times a step must end on, the requested times, the grid of a fixed-step
//! method) with [`kinks`] (the nodes a step lands on) and [`stop_conditions`] (a watched
//! value reached, a steady state or a drift); the step loop, [`step_loop`], with its lean
//! variant [`lean`] for runs with nothing on the way, the bookkeeping of a step in
//! [`progress`], [`locate`] (a state inside a step, by re-stepping), [`left_of`] (the
//! system seen from the left of a breakpoint), [`dead_centre`] (the last state the system
//! accepts before a dead centre) and [`band`] (a lock's band a step carried the motion
//! across unseen).

mod band;
mod dead_centre;
mod frozen;
mod held;
mod kinks;
mod lean;
mod left_of;
mod locate;
mod options;
mod outcome;
mod progress;
mod schedule;
mod step_loop;
mod stop_conditions;
mod validate;

pub use options::{Direction, Reach, RunOptions, Steady, Watch};
pub use outcome::{Outcome, RunResult};

use super::stepper::Stepper;
use super::system::{LagrangeSystem, State};
#[cfg(doc)]
use crate::error::Error;
use crate::error::Result;
use std::cell::Cell;

use frozen::Frozen;
use held::Hold;
use schedule::Schedule;
use step_loop::Runner;

/// Runs `sys` from `start` with `method` until a stop condition of `opts`.
///
/// No step straddles a breakpoint: the run shortens the step that would cross one of the
/// times in [`RunOptions::breakpoints`] or [`LagrangeSystem::breakpoints`] so that it ends
/// exactly there. When a step carries one or more of the
/// [`LagrangeSystem::kink_arguments`] across a node of its own (argument k's nodes are
/// [`LagrangeSystem::kinks`]`()[k]`), the run finds the earliest of these crossings (from the
/// continuous extension by bisection when the method has one, else by locating each),
/// locates it inside the step (re-stepping from its start, regula falsi, to about 10⁻¹⁴ of
/// the argument's change over the step) and takes the step again to end there (with error
/// control for an adaptive method); the next step, starting on that node, finds the next
/// crossing. A fixed-step method then finishes the grid step it was taking, so its grid
/// t₀ + n·h stays. The states at [`RunOptions::times`] are recorded as that field says.
///
/// A system that refuses a state at a dead centre ([`Error::DeadCentre`]: a described
/// linkage whose dyad reaches it) ends the run with [`Outcome::DeadCentre`] at the last state
/// it accepts, located inside the step that met it (see there), its rows kept; so does one
/// whose step jumped past the dead centre to where the position no longer assembles, when
/// the location meets the dead centre on the way. A system with
/// [`LagrangeSystem::lock_measures`] has them read at the ends of every step: a step that
/// carried the motion across a band unseen (a measure's V between its ends) is walked again
/// in halves until a sub-step is refused, and the run ends there the same way; a step
/// whose finer walk meets no refusal stands.
///
/// # Errors
/// [`Error::NonPositive`]/[`Error::NonFinite`] for a bad step, final time, steady tolerance
/// or hold, or record interval; [`Error::NonFinite`] for a requested time, a breakpoint or a
/// kink node that is not finite; [`Error::OutOfRange`] for a requested time outside
/// [t_start, t_end] or a watched index that does not exist; [`Error::NonFiniteState`] when
/// a kink argument is not finite (or is left unset by the system);
/// [`Error::Singular`] when a step is too short to advance the time
/// (h below the rounding of t); [`Error::NonFiniteState`] naming the time when the motion
/// diverges (or a recorded quantity overflows); [`Error::Budget`] naming the time reached
/// when the steps, evaluations or rows of `opts` run out (or [`Error::OutOfRange`] for a row
/// budget below 2); [`Error::NonFinite`] or [`Error::OutOfRange`] naming the load when the
/// system's [`LagrangeSystem::switch_loads`] are not finite or a breakaway load is negative;
/// any error of the system or the method.
///
/// # Examples
/// A 1 kg slider pushed by 2 N from rest reaches x = 1 m at t = 1 s; with steps of 0.3 s the
/// crossing is still found at t = 1 s (inside the fourth step), not at t = 1.2 s:
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{run, Direction, LagrangeSystem, Outcome, Reach, Rk4, RunOptions, State, Watch};
/// struct Slider;
/// impl LagrangeSystem for Slider {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::identity())
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::new(2.0, 0.0))
///     }
/// }
/// let mut opts = RunOptions::until(5.0, 0.3);
/// opts.reach = Some(Reach { watch: Watch::Coordinate(0), value: 1.0, direction: Direction::Rising });
/// let r = run(&Slider, &Rk4, State::at_rest(Vector2::zeros()), &opts).unwrap();
/// let Outcome::Reached { t } = r.outcome else { panic!() };
/// assert!((t - 1.0).abs() < 1e-12 && (r.last.q[0] - 1.0).abs() < 1e-12);
/// ```
pub fn run<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    start: State,
    opts: &RunOptions,
) -> Result<RunResult> {
    validate::check(sys, &start, opts)?;
    let switches = sys.switches();
    if switches == 0 {
        let sched = Schedule::new(sys, method, start.t, opts)?;
        return Runner::start(sys, method, opts, start, sched, None)?.finish();
    }
    // Each switch's resistance held in one direction through a step; the coordinates its
    // switches hold at rest, with their release arguments.
    let modes = vec![Cell::new(0.0); switches];
    let hold = Hold::of(sys);
    let held = Frozen::new(sys, &modes, hold.as_ref());
    let sched = Schedule::new(&held, method, start.t, opts)?;
    Runner::start(&held, method, opts, start, sched, Some(&modes))?
        .holding(hold.as_ref())
        .finish()
}

/// [`run`], also ending where coordinate `i`'s speed, moving in the direction `d` (±1; from
/// rest, the direction it starts in), passes zero to the other side: the motion turns back
/// (located inside the step, to the method's own state; at a switch whose resistance holds
/// the motion the run ends [`Outcome::Stuck`] instead). Returns the result, its outcome
/// [`Outcome::Reached`] at the turning time when the motion turned back, and whether it did.
///
/// # Errors
/// As [`run`].
pub(crate) fn run_to_reversal<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    start: State,
    opts: &RunOptions,
    (i, d): (usize, f64),
) -> Result<(RunResult, bool)> {
    validate::check(sys, &start, opts)?;
    let switches = sys.switches();
    if switches == 0 {
        let sched = Schedule::new(sys, method, start.t, opts)?;
        return Runner::start(sys, method, opts, start, sched, None)?
            .ending_at_reversal((i, d))
            .finish_or_reversal();
    }
    let modes = vec![Cell::new(0.0); switches];
    let hold = Hold::of(sys);
    let held = Frozen::new(sys, &modes, hold.as_ref());
    let sched = Schedule::new(&held, method, start.t, opts)?;
    Runner::start(&held, method, opts, start, sched, Some(&modes))?
        .holding(hold.as_ref())
        .ending_at_reversal((i, d))
        .finish_or_reversal()
}
