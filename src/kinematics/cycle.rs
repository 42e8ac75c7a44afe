//! A cycle of the input link: N positions, coupler curves, and where a linkage locks.

use crate::angle::normalize;
use crate::error::{finite, Error, Result};
use nalgebra::Point2;
use std::f64::consts::TAU;

/// The most positions a cycle may have (2²⁴, about 16.8 million): a bound on the memory and
/// time of [`cycle`], [`try_cycle_angles`] and [`Strokes::try_plan_positions`](super::Strokes::try_plan_positions).
pub const MAX_POSITIONS: usize = 1 << 24;

/// Checks a number of positions: 1 ≤ n ≤ [`MAX_POSITIONS`].
pub(crate) fn check_positions(n: usize) -> Result<()> {
    if n == 0 || n > MAX_POSITIONS {
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

/// The input angles of `n` equally spaced positions over one turn, starting at `start`:
/// φk = start + k·2π/n (k = 0 … n−1), each in [0, 2π). With `n = 12` and `start` at the
/// beginning of the working stroke these are the 12 plans of a course project (see
/// [`Strokes::plan_positions`](super::Strokes::plan_positions) for a crank turning clockwise).
///
/// Input that has no angles gives none: an empty vector for `n = 0`, `n` above
/// [`MAX_POSITIONS`] or a non-finite `start` (never a NaN). [`try_cycle_angles`] says why.
#[must_use]
pub fn cycle_angles(n: usize, start: f64) -> Vec<f64> {
    try_cycle_angles(n, start).unwrap_or_default()
}

/// As [`cycle_angles`], with an error for input that has no angles.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `start`; [`Error::OutOfRange`] for `n = 0` or `n`
/// above [`MAX_POSITIONS`].
pub fn try_cycle_angles(n: usize, start: f64) -> Result<Vec<f64>> {
    finite("start angle", start)?;
    check_positions(n)?;
    let step = TAU / n as f64;
    // From the start brought into [0, 2π) first: at a start of 10¹⁷ rad and beyond, the
    // steps would be lost in the start's rounding and every angle the same.
    let start = normalize(start);
    Ok((0..n).map(|k| normalize(start + k as f64 * step)).collect())
}

/// Evaluates a mechanism at `n` equally spaced input angles over one turn, from `start`.
///
/// `mechanism` maps an input angle to whatever the caller needs (usually a short chain of
/// block calls with a fixed [`Branch`](super::Branch) per group: the assembly mode is an input
/// of every block, so it stays the same around the whole cycle). The cost is linear in `n`.
///
/// # Examples
/// A crank-rocker completes its cycle; the rocker's angle comes back after one turn:
/// ```
/// use nalgebra::Point2;
/// use tmm::kinematics::{crank, cycle, rrr_dyad, Branch, Motion, PointMotion};
/// let c = PointMotion::fixed(Point2::new(0.4, 0.0));
/// let rocker = |phi: f64| {
///     let a = crank(Point2::origin(), 0.1, Motion::unit_speed(phi))?.a;
///     Ok(rrr_dyad(a, c, 0.35, 0.3, Branch::Plus)?.link3.angle)
/// };
/// let angles = cycle(360, 0.0, rocker)?;
/// assert_eq!(angles.len(), 360);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::OutOfRange`] for `n = 0` or above [`MAX_POSITIONS`], [`Error::NonFinite`] for a
/// non-finite `start`. When a
/// position fails, [`Error::In`] names it and, when the linkage cannot be assembled there,
/// the input angle at which it locks (found by bisection to machine precision); the source is
/// the position's own error.
pub fn cycle<S, F>(n: usize, start: f64, mut mechanism: F) -> Result<Vec<S>>
where
    F: FnMut(f64) -> Result<S>,
{
    finite("start angle", start)?;
    check_positions(n)?;
    let step = TAU / n as f64;
    let mut out = Vec::with_capacity(n.min(4096));
    for k in 0..n {
        let phi = start + k as f64 * step;
        match mechanism(phi) {
            Ok(s) => out.push(s),
            Err(e) => {
                let mut part = format!("position {k} of {n} (phi1 = {} rad)", normalize(phi));
                if k > 0 && matches!(e, Error::NotAssemblable { .. } | Error::Singular { .. }) {
                    let lock = boundary(|x| mechanism(x).is_ok(), phi - step, phi);
                    part.push_str(&format!(
                        ": the linkage locks at phi1 = {} rad",
                        normalize(lock)
                    ));
                }
                return Err(Error::In {
                    part,
                    source: Box::new(e),
                });
            }
        }
    }
    Ok(out)
}

/// The trace of a point over one turn of the input: a coupler curve when the point belongs to
/// a coupler. `point` maps an input angle to the point (for a coupler point, for example
/// `rrr.link2.point_at(along, across).p`).
///
/// # Examples
/// The coupler point at the joint B of a crank-rocker traces an arc of the rocker's circle
/// (radius l_CB = 0.3 m about C):
/// ```
/// use nalgebra::Point2;
/// use tmm::kinematics::{coupler_curve, crank, rrr_dyad, Branch, Motion, PointMotion};
/// let c = PointMotion::fixed(Point2::new(0.4, 0.0));
/// let curve = coupler_curve(72, 0.0, |phi| {
///     let a = crank(Point2::origin(), 0.1, Motion::fixed(phi))?.a;
///     Ok(rrr_dyad(a, c, 0.35, 0.3, Branch::Plus)?.link2.point_at(0.35, 0.0).p)
/// })?;
/// assert!(curve.iter().all(|p| ((p - c.p).norm() - 0.3).abs() < 1e-12));
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`cycle`].
pub fn coupler_curve<F>(n: usize, start: f64, point: F) -> Result<Vec<Point2<f64>>>
where
    F: FnMut(f64) -> Result<Point2<f64>>,
{
    cycle(n, start, point)
}

/// The range of input angles, through `phi`, over which a mechanism can be assembled.
///
/// Returns `None` if the input can make full turns (the mechanism assembles at 720 equally
/// spaced angles from `phi`, a full turn being checked), otherwise `(lower, upper)` with
/// lower < phi < upper (not normalised, so the range is an interval): the two input angles at
/// which the linkage locks, to machine precision. A non-Grashof four-bar's input rocks between
/// them.
///
/// Only [`Error::NotAssemblable`] counts as "cannot assemble": a position that is
/// [`Error::Singular`] (a dead point, or an isolated branch point where the two assembly
/// modes touch) is assembled, only not solvable for its velocities. A failure that the
/// mechanism recovers from within [`ISOLATED_GAP`] rad (rounding at a tangent closure, where
/// the closure's discriminant touches zero) is an isolated branch point, not a lock, so the
/// answer does not depend on whether the scan happens to land on it.
///
/// # Examples
/// A non-Grashof four-bar (frame 0.3 m, crank 0.2 m, coupler 0.08 m, rocker 0.15 m): the
/// dyad closes while |AC| ≤ 0.23 m, so the input rocks between ±arccos(0.0771/0.12).
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{assembly_range, crank, rrr_dyad, Branch, Motion, PointMotion};
/// let c = PointMotion::fixed(Point2::new(0.3, 0.0));
/// let range = assembly_range(0.0, |phi| {
///     let a = crank(Point2::origin(), 0.2, Motion::fixed(phi))?.a;
///     rrr_dyad(a, c, 0.08, 0.15, Branch::Plus)
/// })?;
/// let (lo, hi) = range.expect("the crank cannot turn fully");
/// let lock = (0.0771f64 / 0.12).acos();
/// assert_relative_eq!(hi, lock, epsilon = 1e-12);
/// assert_relative_eq!(lo, -lock, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `phi`; the mechanism's own error if it fails at
/// `phi` itself (other than [`Error::Singular`]).
pub fn assembly_range<S, F>(phi: f64, mut mechanism: F) -> Result<Option<(f64, f64)>>
where
    F: FnMut(f64) -> Result<S>,
{
    finite("phi", phi)?;
    match mechanism(phi) {
        Ok(_) | Err(Error::Singular { .. }) => {}
        Err(e) => return Err(e),
    }
    const STEPS: usize = 720;
    let step = TAU / STEPS as f64;
    let mut ok = |x: f64| matches!(mechanism(x), Ok(_) | Err(Error::Singular { .. }));
    // A lock at the failure `x` (reached from `x - dir·step`), or None for an isolated point.
    let lock_at = |ok: &mut dyn FnMut(f64) -> bool, x: f64, dir: f64| -> Option<f64> {
        let scale = x.abs().max(1.0);
        let mut d = 1e-13 * scale;
        while d <= ISOLATED_GAP * scale {
            if ok(x + dir * d) {
                return None;
            }
            d *= 4.0;
        }
        Some(boundary(&mut *ok, x - dir * step, x))
    };
    let mut upper = None;
    for k in 1..=STEPS {
        let x = phi + k as f64 * step;
        if !ok(x)
            && let Some(b) = lock_at(&mut ok, x, 1.0)
        {
            upper = Some(b);
            break;
        }
    }
    let Some(upper) = upper else {
        return Ok(None);
    };
    let mut lower = upper - TAU;
    for k in 1..=STEPS {
        let x = phi - k as f64 * step;
        if !ok(x)
            && let Some(b) = lock_at(&mut ok, x, -1.0)
        {
            lower = b;
            break;
        }
    }
    Ok(Some((lower, upper)))
}

/// The widest gap in assembly (rad, relative to max(1, |φ|)) that [`assembly_range`] takes
/// for rounding at an isolated branch point rather than for a lock: 10⁻⁶.
pub const ISOLATED_GAP: f64 = 1e-6;

/// Bisection for the boundary between `good` (assembles) and `bad` (does not), to the last
/// bit of the input angle.
fn boundary<F: FnMut(f64) -> bool>(mut ok: F, mut good: f64, mut bad: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (good + bad);
        if mid == good || mid == bad {
            break;
        }
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}
