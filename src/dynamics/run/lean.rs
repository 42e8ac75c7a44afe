//! The lean step loop: a run's interior steps when nothing is stopped at or watched on the way.

use super::options::RunOptions;
use super::progress::{accept, budgets, record_end, snap_to_end, Progress};
use crate::dynamics::stepper::Stepper;
use crate::dynamics::system::LagrangeSystem;
use crate::dynamics::trajectory::Trajectory;
use crate::error::Result;

/// The interior steps of a run with nothing to stop at or watch on the way (no
/// breakpoints, requested times, kinks, reach or steady state): what the full loop of
/// [`run`](super::run) does for such a step, without carrying every feature's state through
/// each step (that cost some 50 ns a step, a tenth of a run on a cheap right-hand side). It
/// returns before the step that reaches the end, which is the full loop's.
///
/// A function of its own, kept out of line: inside a large body the compiler does not
/// inline the system's terms into the steps (on a linear system that tripled the cost of a
/// step); in this small one it does. Its state lives in locals, copied in and out of
/// `progress` once.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn lean_steps<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    opts: &RunOptions,
    t_tol: f64,
    takes_rows: bool,
    progress: &mut Progress,
    traj: &mut Trajectory,
    buf: &mut Vec<f64>,
) -> Result<()> {
    let Progress {
        mut s,
        mut prev,
        mut h,
        mut hand,
        mut steps,
        mut evaluations,
        mut until_record,
        mut row_handed,
    } = *progress;
    // An error ends the loop with the last accepted state written back, for the run to end
    // there (a jam, a dead centre) or to say where it failed.
    macro_rules! or_break {
        ($e:expr) => {
            match $e {
                Ok(v) => v,
                Err(e) => break Err(e),
            }
        };
    }
    let result = loop {
        let remaining = opts.t_end - s.t;
        // The end, or the step clamped onto it: the full loop's.
        if remaining <= t_tol || h >= remaining {
            break Ok(());
        }
        or_break!(budgets(opts, steps, evaluations, s.t));
        let adv = or_break!(method.advance_from(sys, &s, h, Some(hand)));
        let (mut s1, mut hand1) = or_break!(accept(
            &s,
            &adv,
            &mut steps,
            &mut evaluations,
            &mut row_handed
        ));
        snap_to_end(opts, t_tol, &mut s1, &mut hand1);
        let h_next = adv.h_next;
        until_record -= 1;
        if until_record == 0 {
            until_record = opts.record_every;
            row_handed = or_break!(record_end(
                sys, opts, t_tol, takes_rows, &s1, &mut hand1, traj, buf
            ));
        }
        h = h_next;
        hand = hand1;
        prev = s;
        s = s1;
    };
    *progress = Progress {
        s,
        prev,
        h,
        hand,
        steps,
        evaluations,
        until_record,
        row_handed,
    };
    result
}
