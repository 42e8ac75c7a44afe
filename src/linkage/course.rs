//! The positions of a course project's plans: the inputs of a cycle in the order the input
//! reaches them, and the inputs of the output's extreme positions.

use super::cycle::{course_inputs, uniform_inputs, Output};
use super::plan::Plan;
use crate::error::{Error, Result};
use crate::kinematics::{Motion, Rotation, MAX_POSITIONS};

/// The positions of a cycle: the inputs of the plans (12 in a course project), in the order
/// the input reaches them, and the inputs of the output's extreme positions. The pictures of
/// `tmm::draw` draw a course (its extreme positions bold) and mark it on the diagrams.
///
/// # Examples
/// The Watt six-bar's 12 positions from the start of link 5's working stroke:
/// ```
/// use tmm::linkage::{bundled, Course, Output, Plan};
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
    /// [`Error::OutOfRange`] for `n` outside [1, [`MAX_POSITIONS`]]; [`Error::NonFinite`] for
    /// a non-finite speed, [`Error::NonPositive`] for a zero one; [`Error::Description`] for a
    /// slider input (give its positions as a `Course` by hand) or an unknown output; the
    /// errors of [`Plan::strokes`].
    ///
    /// # Examples
    /// A clockwise crank reaches its positions with decreasing angles:
    /// ```
    /// use tmm::linkage::{bundled, Course, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let course = Course::new(&plan, None, 4, -10.0)?;
    /// assert_eq!(course.inputs[0].value, plan.reference_input());
    /// assert!(course.inputs.iter().all(|m| m.rate == -10.0));
    /// assert!(Course::new(&plan, None, 0, 10.0).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn new(plan: &Plan, output: Option<&Output>, n: usize, speed: f64) -> Result<Self> {
        check_count(n)?;
        crate::error::finite("speed", speed)?;
        if speed == 0.0 {
            return Err(Error::NonPositive {
                name: "|speed| of a course (its sign is the sense of rotation)",
                value: speed,
            });
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

    /// Checks the course: at least one position, at most [`MAX_POSITIONS`], every input and
    /// extreme finite.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for no positions or too many; [`Error::NonFinite`] naming the
    /// first non-finite input, rate or acceleration.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::Course;
    /// let course = Course { inputs: vec![Motion::new(f64::NAN, 1.0, 0.0)], extremes: vec![] };
    /// assert!(course.check().is_err());
    /// ```
    pub fn check(&self) -> Result<()> {
        check_count(self.inputs.len())?;
        check_finite(&self.inputs)?;
        check_finite(&self.extremes)
    }
}

/// 1 ≤ n ≤ MAX_POSITIONS.
fn check_count(n: usize) -> Result<()> {
    if n == 0 || n > MAX_POSITIONS {
        #[allow(clippy::cast_precision_loss)]
        return Err(Error::OutOfRange {
            name: "number of positions",
            value: n as f64,
            min: 1.0,
            max: MAX_POSITIONS as f64,
            ends: crate::Ends::Closed,
        });
    }
    Ok(())
}

/// Every input, rate and acceleration finite.
pub(crate) fn check_finite(inputs: &[Motion]) -> Result<()> {
    for m in inputs {
        crate::error::all_finite(&[
            ("input", m.value),
            ("input rate", m.rate),
            ("input acceleration", m.accel),
        ])?;
    }
    Ok(())
}
