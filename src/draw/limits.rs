//! The bounds on what one picture draws.

use super::MAX_FRAMES;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::Course;

/// 1 ≤ n ≤ [`MAX_FRAMES`].
pub(crate) fn check_count(name: &'static str, n: usize) -> Result<()> {
    if n == 0 || n > MAX_FRAMES {
        #[allow(clippy::cast_precision_loss)]
        return Err(Error::OutOfRange {
            name,
            value: n as f64,
            min: 1.0,
            max: MAX_FRAMES as f64,
            ends: crate::Ends::Closed,
        });
    }
    Ok(())
}

/// A non-empty list of finite inputs, at most [`MAX_FRAMES`] of them.
pub(crate) fn check_inputs(inputs: &[Motion]) -> Result<()> {
    check_count("number of positions", inputs.len())?;
    for m in inputs {
        crate::error::all_finite(&[
            ("input", m.value),
            ("input rate", m.rate),
            ("input acceleration", m.accel),
        ])?;
    }
    Ok(())
}

/// A course one picture can draw: checked as [`Course::check`] does, with at most
/// [`MAX_FRAMES`] positions.
pub(crate) fn check_course(course: &Course) -> Result<()> {
    check_count("number of positions", course.inputs.len())?;
    course.check()
}
