//! The positions of a course project's plan: the inputs to draw and the extreme positions.

use super::frame::drawing;
use super::MAX_FRAMES;
use crate::error::{Error, Result};
use crate::kinematics::{Motion, Rotation};
use crate::linkage::{course_inputs, uniform_inputs, Output, Plan};

/// The positions of a plan of the mechanism: the inputs drawn (12 in a course project), in
/// the order the input reaches them, and the inputs of the output's extreme positions (drawn
/// bold). The diagrams ([`diagram`](super::diagram)) mark the same positions.
///
/// # Examples
/// The Watt six-bar's 12 positions from the start of link 5's working stroke:
/// ```
/// use tmm::draw::Course;
/// use tmm::linkage::{bundled, Output, Plan};
/// let plan = Plan::new(&bundled::watt_six_bar())?;
/// let course = Course::new(&plan, Some(&Output::Angle("link 5".into())), 12, 10.0)?;
/// assert_eq!(course.inputs.len(), 12);
/// assert_eq!(course.extremes.len(), 2);
/// assert_eq!(course.inputs[0], course.extremes[0]); // the plan starts at an extreme
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Course {
    /// The inputs of the positions, in the order the input reaches them (φ1, ω1, ε1 for a
    /// crank; s, ṡ, s̈ for a slider).
    pub inputs: Vec<Motion>,
    /// The inputs of the extreme positions of the output (empty when there is none).
    pub extremes: Vec<Motion>,
}

impl Course {
    /// `n` positions equally spaced over a turn of the crank turning at `speed` rad/s
    /// (negative: clockwise). With an `output`, they start at the beginning of its working
    /// stroke and its two extreme positions are kept; without, they start at the reference
    /// pose.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for `n` outside [1, [`MAX_FRAMES`]]; [`Error::NonFinite`] or
    /// [`Error::Drawing`] for a non-finite or zero speed; [`Error::Description`] for a slider
    /// input (give its positions as a `Course` by hand) or an unknown output; the errors of
    /// [`Plan::strokes`].
    ///
    /// # Examples
    /// A clockwise crank reaches its positions with decreasing angles:
    /// ```
    /// use tmm::draw::Course;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let course = Course::new(&plan, None, 4, -10.0)?;
    /// assert_eq!(course.inputs[0].value, plan.reference_input());
    /// assert!(course.inputs.iter().all(|m| m.rate == -10.0));
    /// assert!(Course::new(&plan, None, 0, 10.0).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn new(plan: &Plan, output: Option<&Output>, n: usize, speed: f64) -> Result<Self> {
        check_count("number of positions", n)?;
        crate::error::finite("speed", speed)?;
        if speed == 0.0 {
            return Err(drawing("a course", "the speed must not be zero"));
        }
        if !plan.input_is_crank() {
            return Err(Error::Description {
                item: "field input".to_owned(),
                problem: "a course over a turn needs a crank; give a slider's positions as a \
                          Course by hand"
                    .to_owned(),
            });
        }
        let Some(output) = output else {
            return Ok(Self {
                inputs: uniform_inputs(n, plan.reference_input(), speed, 0.0),
                extremes: Vec::new(),
            });
        };
        let rotation = if speed < 0.0 {
            Rotation::Cw
        } else {
            Rotation::Ccw
        };
        let strokes = plan.strokes(output, rotation)?;
        Ok(Self {
            inputs: course_inputs(&strokes, n, speed),
            extremes: vec![
                Motion::new(strokes.start, speed, 0.0),
                Motion::new(strokes.end, speed, 0.0),
            ],
        })
    }

    /// Checks the inputs: at least one, at most [`MAX_FRAMES`], all finite.
    pub(crate) fn check(&self) -> Result<()> {
        check_inputs(&self.inputs)?;
        check_finite(&self.extremes)
    }
}

/// 1 ≤ n ≤ MAX_FRAMES.
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

/// A bounded, non-empty list of finite inputs.
pub(crate) fn check_inputs(inputs: &[Motion]) -> Result<()> {
    check_count("number of positions", inputs.len())?;
    check_finite(inputs)
}

fn check_finite(inputs: &[Motion]) -> Result<()> {
    for m in inputs {
        crate::error::all_finite(&[
            ("input", m.value),
            ("input rate", m.rate),
            ("input acceleration", m.accel),
        ])?;
    }
    Ok(())
}
