//! Courses of a linkage with two inputs (a grid of input pairs, or a path along two input
//! laws), which of their positions assemble, and the course any linkage runs by default.

use super::course::{check_count, check_finite, Course};
use super::description::Output;
use super::inputs::{check_input_coordinate, Inputs};
use super::plan::{InputPlan, Plan};
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use std::f64::consts::{FRAC_PI_2, TAU};

/// The positions of a linkage with two inputs: pairs of input motions, over a grid or along a
/// path in time.
///
/// # Examples
/// The bundled five-bar robot's cranks swept over a 5 × 4 grid about the reference pose,
/// every position checked for assembly:
/// ```
/// use tmm::linkage::{bundled, Plan, TwoInputCourse};
/// let plan = Plan::new(&bundled::five_bar_robot())?;
/// let r = plan.reference_inputs();
/// let course = TwoInputCourse::grid([r[0] - 0.2, r[0] + 0.2], [r[1] - 0.2, r[1] + 0.2], [5, 4], [1.0, 0.0])?;
/// assert_eq!(course.inputs.len(), 20);
/// assert!(course.assembly(&plan).failures.is_empty());
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TwoInputCourse {
    /// The positions, each a pair of input motions (φ, ω, ε of a crank; s, ṡ, s̈ of a slider).
    pub inputs: Vec<Inputs>,
    /// How the positions are laid out.
    pub shape: TwoInputShape,
}

/// How the positions of a [`TwoInputCourse`] are laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TwoInputShape {
    /// A grid of `n1` values of the first input by `n2` of the second; position
    /// `i1 · n2 + i2` holds the first input's `i1`-th value and the second's `i2`-th (the
    /// second input varies fastest).
    Grid {
        /// The number of values of the first input.
        n1: usize,
        /// The number of values of the second input.
        n2: usize,
    },
    /// A path: the inputs in the order of time, as the two inputs' laws of motion give them.
    Path,
}

/// Which positions of a [`TwoInputCourse`] assemble: how many, and every one that does not,
/// with its error.
#[derive(Debug, Clone, PartialEq)]
pub struct Assembly {
    /// The number of positions that assemble.
    pub solved: usize,
    /// Every position that does not, in course order.
    pub failures: Vec<AssemblyFailure>,
}

/// A position of a course that cannot be solved, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct AssemblyFailure {
    /// Its place in the course.
    pub index: usize,
    /// Its inputs.
    pub inputs: Inputs,
    /// Why it cannot be solved (for example [`Error::NotAssemblable`] naming the group).
    pub error: Error,
}

impl TwoInputCourse {
    /// A grid of `n[0]` equally spaced values of the first input over `first` (both ends
    /// included; the lower end alone for `n[0]` = 1) by `n[1]` of the second over `second`,
    /// each input moving at the constant rate `rates[k]` (rad/s or m/s), no acceleration.
    /// The ranges may be given either way round.
    ///
    /// # Errors
    /// [`Error::NonFinite`] naming the first non-finite range end or rate;
    /// [`Error::Overflow`] for a range too wide for `f64`; [`Error::OutOfRange`] naming a range
    /// end beyond ±[`MAX_INPUT_COORDINATE`](super::MAX_INPUT_COORDINATE) (rad, or m for a slider), or
    /// (`"number of positions"`) for a count of 0 or more than
    /// [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS) positions in all.
    pub fn grid(first: [f64; 2], second: [f64; 2], n: [usize; 2], rates: [f64; 2]) -> Result<Self> {
        crate::error::all_finite(&[
            ("start of the first input's range", first[0]),
            ("end of the first input's range", first[1]),
            ("start of the second input's range", second[0]),
            ("end of the second input's range", second[1]),
            ("rate of the first input", rates[0]),
            ("rate of the second input", rates[1]),
        ])?;
        for r in [first, second] {
            crate::error::computed("width of an input range", r[1] - r[0])?;
        }
        for (name, end) in [
            ("start of the first input's range", first[0]),
            ("end of the first input's range", first[1]),
            ("start of the second input's range", second[0]),
            ("end of the second input's range", second[1]),
        ] {
            check_input_coordinate(name, end)?;
        }
        check_count(n[0])?;
        check_count(n[1])?;
        check_count(n[0].saturating_mul(n[1]))?;
        let at = |r: [f64; 2], n: usize, i: usize| {
            #[allow(clippy::cast_precision_loss)]
            if n == 1 || i == 0 {
                r[0]
            } else if i + 1 == n {
                r[1]
            } else {
                r[0] + (r[1] - r[0]) * i as f64 / (n - 1) as f64
            }
        };
        let mut inputs = Vec::with_capacity(n[0] * n[1]);
        for i1 in 0..n[0] {
            for i2 in 0..n[1] {
                inputs.push(Inputs::two(
                    Motion::new(at(first, n[0], i1), rates[0], 0.0),
                    Motion::new(at(second, n[1], i2), rates[1], 0.0),
                ));
            }
        }
        Ok(Self {
            inputs,
            shape: TwoInputShape::Grid { n1: n[0], n2: n[1] },
        })
    }

    /// A path along two laws of motion: at each time of `times` (s, increasing), the first
    /// input's motion `first(t)` and the second's `second(t)`.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"number of positions"`) for no times or more than
    /// [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS); [`Error::NonFinite`] naming a non-finite time;
    /// [`Error::Description`] (`"times"`) for times that do not increase;
    /// [`Error::In`] naming the law and the time where it gives a non-finite motion or an
    /// input beyond ±[`MAX_INPUT_COORDINATE`](super::MAX_INPUT_COORDINATE).
    ///
    /// # Examples
    /// Crank 1 of the five-bar turning at 1 rad/s while crank 4 rocks:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan, TwoInputCourse};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let r = plan.reference_inputs();
    /// let times: Vec<f64> = (0..50).map(|k| 0.01 * f64::from(k)).collect();
    /// let course = TwoInputCourse::laws(
    ///     &times,
    ///     |t| Motion::new(r[0] + t, 1.0, 0.0),
    ///     |t| Motion::new(r[1] + 0.1 * t.sin(), 0.1 * t.cos(), -0.1 * t.sin()),
    /// )?;
    /// assert!(course.assembly(&plan).failures.is_empty());
    /// assert!(TwoInputCourse::laws(&[0.0], |_| Motion::fixed(f64::NAN), |_| Motion::fixed(0.0)).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn laws(
        times: &[f64],
        first: impl Fn(f64) -> Motion,
        second: impl Fn(f64) -> Motion,
    ) -> Result<Self> {
        check_count(times.len())?;
        let mut inputs = Vec::with_capacity(times.len());
        let mut last = f64::NEG_INFINITY;
        for &t in times {
            crate::error::finite("time", t)?;
            if t <= last {
                return Err(Error::Description {
                    item: "times".to_owned(),
                    problem: format!("the times must increase; {t} s follows {last} s"),
                });
            }
            last = t;
            let (m1, m2) = (first(t), second(t));
            for (m, law) in [(m1, "first"), (m2, "second")] {
                check_finite(&[m]).map_err(|e| Error::In {
                    part: format!("the {law} input's law at t = {t} s"),
                    source: Box::new(e),
                })?;
            }
            inputs.push(Inputs::two(m1, m2));
        }
        Ok(Self {
            inputs,
            shape: TwoInputShape::Path,
        })
    }

    /// A closed path of `n` positions about the reference pose: each input swings
    /// harmonically about its reference value with the amplitude `a`, the second a quarter of
    /// a period behind the first (q₁ = q₁⁰ + a cos θ, q₂ = q₂⁰ + a sin θ, θ = ω t over one
    /// period, ω = `speed` rad/s), so the pair of inputs runs round a circle — every
    /// direction of the input plane taken once. The amplitude is the largest of 0.5 rad
    /// (a slider: a tenth of [`Plan::size`]) halved up to 12 times at which every position
    /// assembles.
    ///
    /// # Errors
    /// [`Error::Description`] (`"field second_input"`) for a linkage with one input;
    /// [`Error::OutOfRange`] for `n` outside [1, [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS)]; [`Error::NonFinite`] or
    /// [`Error::NonPositive`] for a non-finite or zero speed; the error of a position that
    /// does not assemble at the smallest amplitude.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan, TwoInputCourse};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let course = TwoInputCourse::around_reference(&plan, 24, 2.0)?;
    /// assert_eq!(course.inputs.len(), 24);
    /// assert!(course.assembly(&plan).failures.is_empty());
    /// assert!(TwoInputCourse::around_reference(&Plan::new(&bundled::four_bar())?, 24, 2.0).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn around_reference(plan: &Plan, n: usize, speed: f64) -> Result<Self> {
        need_two(plan)?;
        check_count(n)?;
        crate::error::finite("speed", speed)?;
        if speed == 0.0 {
            return Err(Error::NonPositive {
                name: "|speed| of a course",
                value: speed,
            });
        }
        let reference = plan.reference_inputs();
        let scale: Vec<f64> = plan
            .chain
            .inputs()
            .map(|ip| match ip {
                InputPlan::Crank { .. } => 0.5,
                InputPlan::Slider { .. } => 0.1 * plan.size(),
            })
            .collect();
        let mut last = None;
        for halving in 0..=12 {
            let a = 0.5f64.powi(halving);
            let law = |k: usize, phase: f64| {
                let (q0, amp) = (reference[k], a * scale[k]);
                move |t: f64| {
                    let th = speed * t + phase;
                    Motion::new(
                        q0 + amp * th.cos(),
                        -amp * speed * th.sin(),
                        -amp * speed * speed * th.cos(),
                    )
                }
            };
            #[allow(clippy::cast_precision_loss)]
            let times: Vec<f64> = (0..n)
                .map(|i| TAU / speed.abs() * i as f64 / n as f64)
                .collect();
            let course = Self::laws(&times, law(0, 0.0), law(1, -FRAC_PI_2))?;
            match course.assembly(plan).failures.into_iter().next() {
                None => return Ok(course),
                Some(f) => last = Some(f),
            }
        }
        let f = last.expect("the loop runs at least once");
        Err(Error::In {
            part: format!("position {} of a path about the reference pose", f.index),
            source: Box::new(f.error),
        })
    }

    /// Checks the course: 1 to [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS) positions, two finite motions in each, and
    /// a grid's counts matching its positions.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for no positions or too many; [`Error::Description`]
    /// (`"inputs"`) for a position with one motion or a grid whose counts do not match;
    /// [`Error::NonFinite`] naming the first non-finite input, rate or acceleration;
    /// [`Error::OutOfRange`] (`"input"`) for an input beyond
    /// ±[`MAX_INPUT_COORDINATE`](super::MAX_INPUT_COORDINATE).
    pub fn check(&self) -> Result<()> {
        check_count(self.inputs.len())?;
        if let TwoInputShape::Grid { n1, n2 } = self.shape
            && n1.checked_mul(n2) != Some(self.inputs.len())
        {
            return Err(Error::Description {
                item: "inputs".to_owned(),
                problem: format!(
                    "a grid of {n1} × {n2} positions holds {}",
                    self.inputs.len()
                ),
            });
        }
        for (k, i) in self.inputs.iter().enumerate() {
            if i.len() != 2 {
                return Err(Error::Description {
                    item: "inputs".to_owned(),
                    problem: format!("position {k} has {} motion(s), not two", i.len()),
                });
            }
            check_finite(i.as_slice())?;
        }
        Ok(())
    }

    /// Solves the position of every point of the course and reports which do not assemble
    /// (and why) instead of stopping at the first.
    #[must_use]
    pub fn assembly(&self, plan: &Plan) -> Assembly {
        let mut solver = plan.solver();
        let mut failures = Vec::new();
        for (index, &inputs) in self.inputs.iter().enumerate() {
            if let Err(error) = solver.kinematics(inputs) {
                failures.push(AssemblyFailure {
                    index,
                    inputs,
                    error,
                });
            }
        }
        Assembly {
            solved: self.inputs.len() - failures.len(),
            failures,
        }
    }
}

/// The course a linkage runs by default, of one input or two.
#[derive(Debug, Clone, PartialEq)]
pub enum AnyCourse {
    /// One input: see [`Course`].
    One(Course),
    /// Two inputs: see [`TwoInputCourse`].
    Two(TwoInputCourse),
}

impl AnyCourse {
    /// The inputs of every position, in course order.
    #[must_use]
    pub fn inputs(&self) -> Vec<Inputs> {
        match self {
            Self::One(c) => c.inputs.iter().map(|&m| Inputs::one(m)).collect(),
            Self::Two(c) => c.inputs.clone(),
        }
    }
}

impl Plan {
    /// The course of `n` positions a designer expects of this linkage at `speed` (rad/s or
    /// m/s; negative: the input turns clockwise): for a crank, [`Course::new`] (a turn from
    /// the start of the working stroke of `output`, or the rocking range of an input that
    /// cannot turn fully); for a slider input, `n` positions a hundredth of [`Plan::size`]
    /// apart from the reference pose along the sense of `speed`; for two inputs,
    /// [`TwoInputCourse::around_reference`].
    ///
    /// # Errors
    /// The errors of the course chosen.
    ///
    /// # Examples
    /// Every bundled linkage has its course:
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// for linkage in bundled::all().into_iter().chain([bundled::five_bar_robot()]) {
    ///     let plan = Plan::new(&linkage)?;
    ///     let course = plan.default_course(linkage.output.as_ref(), 12, 10.0)?;
    ///     assert_eq!(course.inputs().len(), 12);
    /// }
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn default_course(
        &self,
        output: Option<&Output>,
        n: usize,
        speed: f64,
    ) -> Result<AnyCourse> {
        crate::error::finite("speed", speed)?;
        if speed == 0.0 {
            return Err(Error::NonPositive {
                name: "|speed| of a course (its sign is the sense of motion)",
                value: speed,
            });
        }
        if self.input_count() == 2 {
            return Ok(AnyCourse::Two(TwoInputCourse::around_reference(
                self, n, speed,
            )?));
        }
        if self.input_is_crank() {
            return Ok(AnyCourse::One(Course::new(self, output, n, speed)?));
        }
        check_count(n)?;
        let step = speed.signum() * self.size() / 100.0;
        #[allow(clippy::cast_precision_loss)]
        let inputs = (0..n)
            .map(|k| Motion::new(self.reference_input() + step * k as f64, speed, 0.0))
            .collect();
        Ok(AnyCourse::One(Course::given(inputs)))
    }
}

/// A linkage with two inputs, or an error naming the missing field.
fn need_two(plan: &Plan) -> Result<()> {
    if plan.input_count() == 2 {
        Ok(())
    } else {
        Err(Error::Description {
            item: "field second_input".to_owned(),
            problem: "a course of two inputs needs a linkage with two inputs".to_owned(),
        })
    }
}
