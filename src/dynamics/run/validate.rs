//! Validation of a run's options and its start, before anything is evaluated.

use super::options::{RunOptions, Watch};
use crate::dynamics::system::{LagrangeSystem, State};
use crate::error::{finite, positive, Error, Result};

/// Checks the step, the final time, the record interval, the budgets, the start state, the
/// watched quantity and the steady-state condition of a run of `sys` from `start`.
///
/// # Errors
/// [`Error::NonPositive`]/[`Error::NonFinite`] for a bad step, final time (not after the
/// start), record interval, budget, reach value, steady tolerance or hold;
/// [`Error::OutOfRange`] for a row budget below 2 or a watched index that does not exist;
/// [`Error::NonFiniteState`] for a start that is not finite.
pub(super) fn check<S: LagrangeSystem + ?Sized>(
    sys: &S,
    start: &State,
    opts: &RunOptions,
) -> Result<()> {
    positive("step size h", opts.h)?;
    finite("t_end", opts.t_end)?;
    positive("t_end - t_start", opts.t_end - start.t)?;
    positive("record_every", opts.record_every as f64)?;
    positive("max_steps", opts.max_steps as f64)?;
    positive("max_evaluations", opts.max_evaluations as f64)?;
    // The start and the end are always recorded.
    if opts.max_rows < 2 {
        return Err(Error::OutOfRange {
            name: "max_rows",
            value: opts.max_rows as f64,
            min: 2.0,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    if !start.is_finite() {
        return Err(Error::NonFiniteState { time: start.t });
    }
    if let Some(r) = &opts.reach {
        finite("reach value", r.value)?;
        let (i, n) = match r.watch {
            Watch::Coordinate(i) | Watch::Speed(i) => (i, 2),
            Watch::Output(i) => (i, sys.output_names().len()),
        };
        if i >= n {
            return Err(Error::OutOfRange {
                name: "watched index",
                value: i as f64,
                min: 0.0,
                max: n as f64 - 1.0,
                ends: crate::Ends::Closed,
            });
        }
    }
    if let Some(st) = &opts.steady {
        positive("steady tolerance", st.tol)?;
        // Zero would also turn any two steps with equal accelerations into a drift verdict.
        positive("steady hold", st.hold)?;
    }
    Ok(())
}
