//! The positions of a course project's plans: the inputs of a cycle in the order the input
//! reaches them, the inputs of the output's extreme positions, and how the input moves — a
//! full turn, or rocking between the angles where the linkage locks.

use super::cycle::{course_inputs, uniform_inputs};
use super::description::Output;
use super::inputs::check_input_coordinate;
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
    /// The inputs of the extreme positions of the output (empty when there is none); for a
    /// rocking input, the two ends of its sweep, where every link reverses, with the positions
    /// between where the output stands still.
    pub extremes: Vec<Motion>,
    /// How the input moves over the course: a full turn, rocking over a range, or positions
    /// given by hand.
    pub sweep: Sweep,
}

/// How the input moves over a [`Course`].
///
/// # Examples
/// The bundled four-bar's crank turns fully:
/// ```
/// use tmm::linkage::{bundled, Course, Plan, Sweep};
/// let plan = Plan::new(&bundled::four_bar())?;
/// assert_eq!(Course::new(&plan, None, 12, 10.0)?.sweep, Sweep::Turn);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sweep {
    /// The crank turns fully: the course's positions cover one turn.
    Turn,
    /// The input rocks: from the angle `from` to the angle `to` and back, rad. For an input
    /// that cannot turn fully these are the angles where the linkage locks
    /// ([`Plan::lock_positions`]); the input stops and reverses there. The course folds
    /// back on the plan's assembly modes; a linkage carried on through its dead centres by
    /// its inertia runs the return on [`Plan::through`] the lock instead.
    Rocking {
        /// The angle where the course starts, and the input reverses to come back, rad.
        from: f64,
        /// The angle where the input reverses on the way out, rad.
        to: f64,
    },
    /// The positions were given by hand (a slider's positions, or any list of inputs).
    Given,
}

impl Course {
    /// `n` positions equally spaced over a turn of the crank turning at `speed` rad/s
    /// (negative: clockwise). With an `output`, they start at the beginning of its working
    /// stroke and its two extreme positions are kept; without, they start at the reference
    /// pose.
    ///
    /// An input that cannot turn fully (a rocker input: the linkage locks at two angles,
    /// [`Plan::lock_positions`]) rocks between its lock angles instead, as the mechanism runs:
    /// the course is [`Course::rocking`] from the lower lock to the upper one and back (from the
    /// upper for a negative `speed`), and [`Sweep::Rocking`] says so and holds the lock angles.
    /// Its extremes are the two locks, where every link reverses, and, with an `output`, the
    /// inputs between them where the output stands still (its first transfer function changes
    /// sign; found on 360 positions, each refined by bisection), in the order the input
    /// reaches them on the way out.
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
        if let Some((lo, hi)) = plan.lock_positions(plan.reference_input())? {
            let (from, to) = if speed < 0.0 { (hi, lo) } else { (lo, hi) };
            let mut course = Self::rocking_between(from, to, n, speed.abs());
            if let Some(output) = output {
                plan.output(output, Motion::fixed(plan.reference_input()))?;
                let w = if to > from { speed.abs() } else { -speed.abs() };
                let still = stationary(plan, output, from, to);
                course
                    .extremes
                    .splice(1..1, still.into_iter().map(|q| Motion::new(q, w, 0.0)));
            }
            return Ok(course);
        }
        let Some(output) = output else {
            return Ok(Self {
                inputs: uniform_inputs(n, plan.reference_input(), speed, 0.0),
                extremes: Vec::new(),
                sweep: Sweep::Turn,
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
            sweep: Sweep::Turn,
        })
    }

    /// `n` positions of an input rocking from the angle `from` to `to` and back at |`speed`|
    /// rad/s: ⌊n/2⌋ + 1 equally spaced from `from` to `to` (both ends exactly), then the
    /// remaining ones equally spaced on the way back, ends left out. At the two ends the input
    /// reverses: their rate is zero (a rocking drive stops there), elsewhere ±|`speed|`; the
    /// accelerations are zero. The extremes are the two ends.
    ///
    /// A range the input cannot sweep is refused: it must lie within the lock positions
    /// through `from`, when the input cannot turn fully.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for `n` outside [1, [`MAX_POSITIONS`]]; [`Error::NonFinite`]
    /// for a non-finite `from`, `to` or `speed`, [`Error::OutOfRange`] (`"from"`, `"to"`) for
    /// an end beyond ±[`MAX_INPUT_COORDINATE`](super::MAX_INPUT_COORDINATE) rad,
    /// [`Error::NonPositive`] for a zero speed or an
    /// empty range (`from` = `to`); [`Error::Description`] for a slider input; the linkage's
    /// error at `from`; [`Error::OutOfRange`] (`"end of the rocking range"`) for a `to`
    /// beyond the lock positions.
    ///
    /// # Examples
    /// The bundled four-bar's crank rocking over a quarter turn, 8 positions:
    /// ```
    /// use tmm::linkage::{bundled, Course, Plan, Sweep};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let course = Course::rocking(&plan, 0.0, 1.5, 8, 10.0)?;
    /// let q: Vec<f64> = course.inputs.iter().map(|m| m.value).collect();
    /// assert_eq!(q[0], 0.0);
    /// assert_eq!(q[4], 1.5); // the turning point
    /// assert!(q[5] < 1.5 && q[7] > 0.0);
    /// assert_eq!((course.inputs[0].rate, course.inputs[1].rate, course.inputs[5].rate), (0.0, 10.0, -10.0));
    /// assert_eq!(course.sweep, Sweep::Rocking { from: 0.0, to: 1.5 });
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn rocking(plan: &Plan, from: f64, to: f64, n: usize, speed: f64) -> Result<Self> {
        check_count(n)?;
        crate::error::all_finite(&[("from", from), ("to", to), ("speed", speed)])?;
        check_input_coordinate("from", from)?;
        check_input_coordinate("to", to)?;
        if speed == 0.0 {
            return Err(Error::NonPositive {
                name: "|speed| of a course",
                value: speed,
            });
        }
        if from == to {
            return Err(Error::NonPositive {
                name: "|to − from| of a rocking course",
                value: 0.0,
            });
        }
        if !plan.input_is_crank() {
            return Err(Error::Description {
                item: "field input".to_owned(),
                problem: "a rocking course needs a crank (a rotating input); give a slider's \
                          positions as a Course by hand"
                    .to_owned(),
            });
        }
        if let Some((lo, hi)) = plan.lock_positions(from)?
            && !(lo..=hi).contains(&to)
        {
            return Err(Error::OutOfRange {
                name: "end of the rocking range",
                value: to,
                min: lo,
                max: hi,
                ends: crate::Ends::Closed,
            });
        }
        Ok(Self::rocking_between(from, to, n, speed.abs()))
    }

    /// The positions of [`Course::rocking`], the inputs checked.
    fn rocking_between(from: f64, to: f64, n: usize, speed: f64) -> Self {
        let w = if to > from { speed } else { -speed };
        let out = n / 2 + 1;
        let back = n.saturating_sub(out);
        let mut inputs = Vec::with_capacity(n);
        #[allow(clippy::cast_precision_loss)]
        for k in 0..out.min(n) {
            let m = if k == 0 {
                Motion::fixed(from)
            } else if k + 1 == out {
                Motion::fixed(to)
            } else {
                Motion::new(from + (to - from) * k as f64 / (out - 1) as f64, w, 0.0)
            };
            inputs.push(m);
        }
        #[allow(clippy::cast_precision_loss)]
        for k in 1..=back {
            inputs.push(Motion::new(
                to + (from - to) * k as f64 / (back + 1) as f64,
                -w,
                0.0,
            ));
        }
        Self {
            inputs,
            extremes: vec![Motion::fixed(from), Motion::fixed(to)],
            sweep: Sweep::Rocking { from, to },
        }
    }

    /// A course of positions given by hand ([`Sweep::Given`]), without extremes: a slider's
    /// positions, or any inputs.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{Course, Sweep};
    /// let course = Course::given(vec![Motion::new(0.01, 0.5, 0.0), Motion::new(0.02, 0.5, 0.0)]);
    /// assert_eq!(course.sweep, Sweep::Given);
    /// assert!(course.extremes.is_empty());
    /// ```
    #[must_use]
    pub fn given(inputs: Vec<Motion>) -> Self {
        Self {
            inputs,
            extremes: Vec::new(),
            sweep: Sweep::Given,
        }
    }

    /// The plans this course's positions are solved on when the mechanism runs on through
    /// its dead centres along the branch that continues smoothly ([`Plan::track`]): a
    /// parallelogram four-bar stays a parallelogram through 0 and 180°, where the plan's own
    /// modes would fold it into an antiparallelogram. A course that meets no dead centre
    /// (a crank-rocker's, a rocking input's, which reverses at its locks) has the plan
    /// itself for every position. [`Track::cycle`](super::Track::cycle) analyses the
    /// positions on them, [`Track::notes`](super::Track::notes) says where they changed.
    ///
    /// # Errors
    /// As [`Plan::track`].
    pub fn track(&self, plan: &Plan) -> Result<super::Track> {
        plan.track(&self.inputs)
    }

    /// Checks the course: at least one position, at most [`MAX_POSITIONS`], every input and
    /// extreme finite, every input within ±[`MAX_INPUT_COORDINATE`](super::MAX_INPUT_COORDINATE).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for no positions or too many, or (`"input"`) an input beyond
    /// ±10⁹; [`Error::NonFinite`] naming the first non-finite input, rate or acceleration.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::Course;
    /// let course = Course::given(vec![Motion::new(f64::NAN, 1.0, 0.0)]);
    /// assert!(course.check().is_err());
    /// ```
    pub fn check(&self) -> Result<()> {
        check_count(self.inputs.len())?;
        check_finite(&self.inputs)?;
        check_finite(&self.extremes)
    }
}

/// The inputs strictly between `from` and `to` where `output` stands still: where its first
/// transfer function changes sign between two of 360 positions (the middles of equal steps,
/// the locks at the ends left out), bisected to the last bits; in order from `from`.
/// Positions that cannot be solved are passed over.
fn stationary(plan: &Plan, output: &Output, from: f64, to: f64) -> Vec<f64> {
    const SAMPLES: u32 = 360;
    let slope = |q: f64| plan.transfer(output, q).ok().map(|m| m.rate);
    let mut found = Vec::new();
    let mut prev: Option<(f64, f64)> = None;
    for i in 0..SAMPLES {
        let q = from + (to - from) * (f64::from(i) + 0.5) / f64::from(SAMPLES);
        let Some(r) = slope(q) else {
            prev = None;
            continue;
        };
        if let Some((q0, r0)) = prev
            && (r0 > 0.0) != (r > 0.0)
        {
            let (mut a, mut b, up) = (q0, q, r0 > 0.0);
            loop {
                let m = 0.5 * (a + b);
                if m == a || m == b {
                    break;
                }
                match slope(m) {
                    Some(rm) if (rm > 0.0) == up => a = m,
                    Some(_) => b = m,
                    None => break,
                }
            }
            found.push(0.5 * (a + b));
        }
        prev = Some((q, r));
    }
    found
}

impl Plan {
    /// The extreme positions of `output` over the range a rocking input sweeps (between its
    /// lock positions through the reference pose, [`Plan::lock_positions`]), in the order of
    /// the input angle: the output at both locks, where the input and with it every link
    /// reverses, and wherever it stands still in between (found on 360 positions, each refined
    /// by bisection; a maximum or minimum by the sign of its second transfer function).
    ///
    /// At a lock the output's transfer functions are unbounded (the input reverses at a dead
    /// point of its own): its `rate` and `accel` are reported as 0. Its `kind` there compares
    /// the lock's value with the output's next stationary value or other lock. `input` is the
    /// input angle as the range holds it (not reduced to [0, 2π)).
    ///
    /// # Errors
    /// [`Error::Description`] for an input that turns fully ([`Plan::extremes`] is for it) or
    /// a slider input; an unknown output; the linkage's errors at the locks.
    ///
    /// # Examples
    /// A crank rocking between its locks makes a four-bar's rocker swing between the values
    /// at the locks (the file `linkages/chebyshev-straight-line.json`):
    /// ```
    /// use tmm::linkage::{bundled, Output, Plan};
    /// let plan = Plan::new(&bundled::chebyshev_straight_line())?;
    /// let out = Output::Angle("rocker".into());
    /// let ext = plan.rocking_extremes(&out)?;
    /// let (lo, hi) = plan.lock_positions(plan.reference_input())?.unwrap();
    /// assert_eq!((ext[0].input, ext[ext.len() - 1].input), (lo, hi));
    /// assert!(plan.rocking_stroke(&out)? > 0.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn rocking_extremes(&self, output: &Output) -> Result<Vec<crate::kinematics::Extreme>> {
        use crate::kinematics::{Extreme, ExtremeKind};
        if !self.input_is_crank() {
            return Err(Error::Description {
                item: "field input".to_owned(),
                problem: "a slider input has no lock positions; its extremes are its own"
                    .to_owned(),
            });
        }
        let Some((from, to)) = self.lock_positions(self.reference_input())? else {
            return Err(Error::Description {
                item: "field input".to_owned(),
                problem: "the input turns fully: its output's extremes are Plan::extremes"
                    .to_owned(),
            });
        };
        let value = |q: f64| self.output(output, Motion::fixed(q)).map(|m| m.value);
        let mut ext = vec![Extreme {
            input: from,
            output: Motion::fixed(value(from)?),
            kind: ExtremeKind::Max,
        }];
        for q in stationary(self, output, from, to) {
            let m = self.transfer(output, q)?;
            ext.push(Extreme {
                input: q,
                output: m,
                kind: if m.accel < 0.0 {
                    ExtremeKind::Max
                } else {
                    ExtremeKind::Min
                },
            });
        }
        ext.push(Extreme {
            input: to,
            output: Motion::fixed(value(to)?),
            kind: ExtremeKind::Max,
        });
        // A lock is a maximum when the output comes down from it toward its neighbour.
        let n = ext.len();
        for (k, nb) in [(0, 1), (n - 1, n - 2)] {
            ext[k].kind = if ext[k].output.value >= ext[nb].output.value {
                ExtremeKind::Max
            } else {
                ExtremeKind::Min
            };
        }
        Ok(ext)
    }

    /// The stroke (or swing) of `output` over a rocking input's range: the largest of its
    /// extreme values ([`Plan::rocking_extremes`]) less the smallest.
    ///
    /// # Errors
    /// As [`Plan::rocking_extremes`].
    pub fn rocking_stroke(&self, output: &Output) -> Result<f64> {
        let ext = self.rocking_extremes(output)?;
        let values = ext.iter().map(|e| e.output.value);
        let hi = values.clone().fold(f64::NEG_INFINITY, f64::max);
        let lo = values.fold(f64::INFINITY, f64::min);
        crate::error::computed("the stroke of a rocking input's output", hi - lo)
    }
}

/// 1 ≤ n ≤ MAX_POSITIONS.
pub(crate) fn check_count(n: usize) -> Result<()> {
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

/// Every input, rate and acceleration finite, every input within ±
/// [`MAX_INPUT_COORDINATE`](super::MAX_INPUT_COORDINATE).
pub(crate) fn check_finite(inputs: &[Motion]) -> Result<()> {
    for m in inputs {
        crate::error::all_finite(&[
            ("input", m.value),
            ("input rate", m.rate),
            ("input acceleration", m.accel),
        ])?;
        check_input_coordinate("input", m.value)?;
    }
    Ok(())
}
