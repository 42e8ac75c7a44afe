//! Extreme (dead-centre) positions of an output link, the working and idle strokes, and the
//! plans of a course project.

use super::motion::Motion;
use crate::angle::normalize;
use crate::error::{computed, finite, positive, Error, Result};
use std::f64::consts::TAU;

/// Whether an extreme of the output is its largest or its smallest value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ExtremeKind {
    /// A maximum of the output (s″ < 0 or φ″ < 0 there).
    Max,
    /// A minimum of the output.
    Min,
}

/// An extreme position of the output: where its first transfer function vanishes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Extreme {
    /// The input angle φ1 there, in [0, 2π).
    pub input: f64,
    /// The output's transfer functions there: `value` = the extreme value, `rate` = the first
    /// transfer function (zero to rounding), `accel` = the second.
    pub output: Motion,
    /// Maximum or minimum.
    pub kind: ExtremeKind,
}

/// The direction in which the input crank turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Rotation {
    /// Counter-clockwise: the input angle increases.
    Ccw,
    /// Clockwise: the input angle decreases.
    Cw,
}

impl Rotation {
    fn sign(self) -> f64 {
        match self {
            Self::Ccw => 1.0,
            Self::Cw => -1.0,
        }
    }
}

/// Finds the extreme positions of an output over a full turn of the input.
///
/// `transfer` maps an input angle φ1 to the output's transfer functions (value, first,
/// second), usually `|phi| transfer_functions(chain, phi)`. The first transfer function is
/// sampled at `samples` equally spaced angles; every sign change is refined by a safeguarded
/// Newton iteration (Newton steps on φ′ with φ″ as its derivative, falling back to bisection
/// whenever a step would leave the bracket), to the last bits of φ1. A root exactly at a
/// sample is kept as it is. Extremes closer together than the sampling step can be missed;
/// 360 samples suit ordinary linkages.
///
/// # Examples
/// The central slider-crank's slider (crank 0.1 m, rod 0.3 m, guide along +x) is farthest out
/// at φ1 = 0 (s = 0.4 m) and nearest at φ1 = π (s = 0.2 m):
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{
///     crank, extreme_positions, rrp_dyad, transfer_functions, Branch, ExtremeKind, Guide,
/// };
/// let slider = |phi: f64| {
///     transfer_functions(|input| {
///         let c = crank(Point2::origin(), 0.1, input)?;
///         Ok(rrp_dyad(c.a, Guide::fixed(Point2::origin(), 0.0), 0.3, Branch::Plus)?.slide)
///     }, phi)
/// };
/// let ext = extreme_positions(slider, 36)?;
/// assert_eq!(ext.len(), 2);
/// let max = ext.iter().find(|e| e.kind == ExtremeKind::Max).unwrap();
/// let min = ext.iter().find(|e| e.kind == ExtremeKind::Min).unwrap();
/// assert_relative_eq!(max.output.value, 0.4, epsilon = 1e-15);
/// assert_relative_eq!(min.input, std::f64::consts::PI, epsilon = 1e-14);
/// assert_relative_eq!(min.output.value, 0.2, epsilon = 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::OutOfRange`] for fewer than 3 samples or more than
/// [`MAX_POSITIONS`](super::MAX_POSITIONS); [`Error::NonFinite`] for an output that is not
/// finite; the output's error at any sample (a
/// mechanism that cannot make full turns has no cycle to search).
pub fn extreme_positions<F>(mut transfer: F, samples: usize) -> Result<Vec<Extreme>>
where
    F: FnMut(f64) -> Result<Motion>,
{
    if !(3..=super::MAX_POSITIONS).contains(&samples) {
        return Err(Error::OutOfRange {
            name: "samples",
            value: samples as f64,
            min: 3.0,
            max: super::MAX_POSITIONS as f64,
            ends: crate::Ends::Closed,
        });
    }
    let step = TAU / samples as f64;
    let at = |k: usize| k as f64 * step;
    let values = (0..samples)
        .map(|k| {
            let m = transfer(at(k))?;
            m.validate(["output", "output rate", "output accel"])?;
            Ok(m)
        })
        .collect::<Result<Vec<_>>>()?;
    let mut out = Vec::new();
    for k in 0..samples {
        let (f0, f1) = (values[k], values[(k + 1) % samples]);
        let root = if f0.rate == 0.0 {
            // A root on a sample: count it once, and only where the sign really changes.
            let prev = values[(k + samples - 1) % samples].rate;
            if opposite(prev, f1.rate) {
                Some((at(k), f0))
            } else {
                None
            }
        } else if opposite(f0.rate, f1.rate) {
            Some(refine(&mut transfer, at(k), f0, at(k) + step, f1)?)
        } else {
            None
        };
        if let Some((x, m)) = root {
            out.push(Extreme {
                input: normalize(x),
                output: m,
                kind: if f0.rate > 0.0 || f1.rate < 0.0 {
                    ExtremeKind::Max
                } else {
                    ExtremeKind::Min
                },
            });
        }
    }
    Ok(out)
}

/// Whether `a` and `b` are of opposite signs, each nonzero (a product of two tiny slopes
/// would underflow to zero and hide the change).
fn opposite(a: f64, b: f64) -> bool {
    a != 0.0 && b != 0.0 && (a > 0.0) != (b > 0.0)
}

/// Safeguarded Newton on the first transfer function inside the bracket [a, b].
fn refine<F>(
    transfer: &mut F,
    mut a: f64,
    fa: Motion,
    mut b: f64,
    fb: Motion,
) -> Result<(f64, Motion)>
where
    F: FnMut(f64) -> Result<Motion>,
{
    let a_positive = fa.rate > 0.0;
    // Start from the secant point: inside the bracket and good for a simple root.
    let mut x = a - fa.rate * (b - a) / (fb.rate - fa.rate);
    if !(x > a && x < b) {
        // Rates whose quotient overflows or underflows: bisect first.
        x = 0.5 * (a + b);
    }
    let mut best = if fa.rate.abs() < fb.rate.abs() {
        (a, fa)
    } else {
        (b, fb)
    };
    for _ in 0..100 {
        let m = transfer(x)?;
        finite("first transfer function", m.rate)?;
        if m.rate.abs() <= best.1.rate.abs() {
            best = (x, m);
        }
        if m.rate == 0.0 {
            return Ok((x, m));
        }
        if (m.rate > 0.0) == a_positive {
            a = x;
        } else {
            b = x;
        }
        let newton = x - m.rate / m.accel;
        let mid = 0.5 * (a + b);
        let next = if m.accel != 0.0 && newton > a.min(b) && newton < a.max(b) {
            newton
        } else {
            mid
        };
        if next == x || (b - a).abs() <= 2.0 * f64::EPSILON * x.abs().max(1.0) {
            break;
        }
        x = next;
    }
    Ok(best)
}

/// The working and idle strokes of an output with two extreme positions.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Strokes {
    /// The input angle at the beginning of the working stroke (in [0, 2π)).
    pub start: f64,
    /// The input angle at its end, the beginning of the idle stroke.
    pub end: f64,
    /// The working-stroke angle: the larger of the two angles the crank turns through between
    /// the extreme positions (the slower stroke under uniform rotation).
    pub working_angle: f64,
    /// The idle-stroke angle, 2π − working angle.
    pub idle_angle: f64,
    /// The time ratio of the strokes, working/idle ≥ 1 (the coefficient of the average speed
    /// of the return stroke, under uniform rotation of the crank).
    pub time_ratio: f64,
    /// The sense in which the crank turns.
    pub rotation: Rotation,
    /// The output's stroke: the distance between its extreme values (a slider's stroke
    /// length in m, or a rocker's swing in rad).
    pub stroke: f64,
    /// Whether the output's value grows during the working stroke (it starts at the
    /// minimum).
    pub working_rises: bool,
}

impl Strokes {
    /// The strokes between two extreme positions (a maximum and a minimum) for a crank
    /// turning in the sense `rotation`. The working stroke is the larger angle, as in the
    /// seed (most machines work on the slower stroke).
    ///
    /// # Examples
    /// Extremes at 10° and 200° with a counter-clockwise crank: the crank turns 190° from the
    /// first to the second and 170° back, so the working stroke begins at 10°.
    /// ```
    /// use approx::assert_relative_eq;
    /// use tmm::kinematics::{Extreme, ExtremeKind, Motion, Rotation, Strokes};
    /// let e = |deg: f64, kind| Extreme { input: deg.to_radians(), output: Motion::default(), kind };
    /// let s = Strokes::new(&[e(10.0, ExtremeKind::Min), e(200.0, ExtremeKind::Max)], Rotation::Ccw)?;
    /// assert_relative_eq!(s.start.to_degrees(), 10.0, epsilon = 1e-12);
    /// assert_relative_eq!(s.working_angle.to_degrees(), 190.0, epsilon = 1e-12);
    /// assert_relative_eq!(s.time_ratio, 190.0 / 170.0, epsilon = 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Description`] unless there are exactly two extremes (an output that turns
    /// fully has none; one that swings back and forth more than once per turn has more);
    /// [`Error::NonFinite`] for an extreme's input angle or value that is not finite;
    /// [`Error::Singular`] when the two extremes lie at the same input angle (to rounding), so
    /// that there is no idle stroke.
    pub fn new(extremes: &[Extreme], rotation: Rotation) -> Result<Self> {
        let [e0, e1] = extremes else {
            let problem = if extremes.is_empty() {
                "the output has no extreme positions (it turns fully, or stands still): it has \
                 no strokes"
                    .to_owned()
            } else {
                format!(
                    "the output has {} extreme positions per turn of the crank; strokes need \
                     exactly two, a maximum and a minimum",
                    extremes.len()
                )
            };
            return Err(Error::Description {
                item: "strokes".to_owned(),
                problem,
            });
        };
        finite("extreme position's input angle", e0.input)?;
        finite("extreme position's input angle", e1.input)?;
        finite("extreme value of the output", e0.output.value)?;
        finite("extreme value of the output", e1.output.value)?;
        let sg = rotation.sign();
        // The angle the crank turns through from e0 to e1 in its own sense.
        let forward = normalize(sg * (e1.input - e0.input));
        let (start, end, working) = if forward >= TAU - forward {
            (e0.input, e1.input, forward)
        } else {
            (e1.input, e0.input, TAU - forward)
        };
        let idle = TAU - working;
        // Extremes at the same input angle (to rounding) have no idle stroke: no time ratio.
        if idle.is_nan() || idle <= 4.0 * f64::EPSILON * TAU {
            return Err(Error::Singular {
                what: "strokes",
                measure: "angle between the extreme positions",
                value: idle,
            });
        }
        let starts_at_min = |input: f64| {
            let first = if input == e0.input { e0 } else { e1 };
            first.kind == ExtremeKind::Min
        };
        let stroke = crate::error::computed(
            "the output's stroke",
            (e1.output.value - e0.output.value).abs(),
        )?;
        Ok(Self {
            start: normalize(start),
            end: normalize(end),
            working_angle: working,
            idle_angle: idle,
            time_ratio: working / idle,
            rotation,
            stroke,
            working_rises: starts_at_min(start),
        })
    }

    /// The same strokes of an angle output read in [0, 2π) (a link's angle): the swing is the
    /// angle the output turns through from its minimum up to its maximum. The plain difference
    /// of the two readings is 2π minus the swing when the link swings across the reading's cut
    /// at 0 (the +x direction).
    pub(crate) fn of_angle(mut self, extremes: &[Extreme]) -> Self {
        if let [a, b] = extremes
            && a.kind != b.kind
        {
            let (min, max) = if a.kind == ExtremeKind::Min {
                (a, b)
            } else {
                (b, a)
            };
            self.stroke = normalize(max.output.value - min.output.value);
        }
        self
    }

    /// The same strokes with the working stroke in the direction the output works in: rising
    /// (`true`) or falling. A machine whose load resists the output in one direction only
    /// works in that direction, even when that is the faster stroke; then the time ratio is
    /// below 1.
    ///
    /// # Errors
    /// For hand-built strokes that [`Strokes::new`] never gives: [`Error::NonFinite`] for a
    /// non-finite field, [`Error::NonPositive`] for a stroke angle that is not positive (the
    /// time ratio would divide by it).
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::{Extreme, ExtremeKind, Motion, Rotation, Strokes};
    /// let e = |deg: f64, value, kind| Extreme { input: deg.to_radians(), output: Motion::fixed(value), kind };
    /// let s = Strokes::new(&[e(10.0, 0.0, ExtremeKind::Min), e(200.0, 0.3, ExtremeKind::Max)], Rotation::Ccw)?;
    /// assert!(s.working_rises && s.time_ratio > 1.0);
    /// let falling = s.working_in(false)?;
    /// assert_eq!(falling.start, s.end);
    /// assert!((falling.time_ratio - 170.0 / 190.0).abs() < 1e-12);
    /// assert_eq!(falling.stroke, 0.3);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn working_in(self, rises: bool) -> Result<Self> {
        finite("start of the working stroke", self.start)?;
        finite("end of the working stroke", self.end)?;
        finite("time ratio", self.time_ratio)?;
        finite("stroke", self.stroke)?;
        positive("working angle", self.working_angle)?;
        positive("idle angle", self.idle_angle)?;
        if rises == self.working_rises {
            return Ok(self);
        }
        Ok(Self {
            start: self.end,
            end: self.start,
            working_angle: self.idle_angle,
            idle_angle: self.working_angle,
            time_ratio: computed("time ratio", self.idle_angle / self.working_angle)?,
            working_rises: rises,
            ..self
        })
    }

    /// The input angles of `n` plans, equally spaced in the crank's sense of rotation from
    /// the beginning of the working stroke (n = 12 in a course project).
    ///
    /// Input that has no plans gives none: an empty vector for `n = 0`, `n` above
    /// [`MAX_POSITIONS`](super::MAX_POSITIONS) or a non-finite start (a hand-built value);
    /// [`try_plan_positions`](Self::try_plan_positions) says why.
    #[must_use]
    pub fn plan_positions(&self, n: usize) -> Vec<f64> {
        self.try_plan_positions(n).unwrap_or_default()
    }

    /// As [`plan_positions`](Self::plan_positions), with an error for input that has no plans.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite start; [`Error::OutOfRange`] for `n = 0` or `n`
    /// above [`MAX_POSITIONS`](super::MAX_POSITIONS).
    pub fn try_plan_positions(&self, n: usize) -> Result<Vec<f64>> {
        finite("start of the working stroke", self.start)?;
        super::cycle::check_positions(n)?;
        let step = self.rotation.sign() * TAU / n as f64;
        Ok((0..n)
            .map(|k| normalize(self.start + k as f64 * step))
            .collect())
    }
}
