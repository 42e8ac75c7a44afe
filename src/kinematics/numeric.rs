//! Numerical differentiation and integration of tabulated functions (seed 001).
//!
//! The seed's three-point formulas on equally spaced nodes (step h):
//! - first node: y′₁ = (−y₃ + 4y₂ − 3y₁)/(2h), error (formula − exact) −h²/3·y‴;
//! - inner nodes: y′ᵢ = (yᵢ₊₁ − yᵢ₋₁)/(2h), error +h²/6·y‴;
//! - last node: y′ₙ = (3yₙ − 4yₙ₋₁ + yₙ₋₂)/(2h), error −h²/3·y‴;
//!
//! and the cumulative trapezoid rule Iᵢ = Iᵢ₋₁ + h/2·(yᵢ + yᵢ₋₁), I₁ = 0, which exceeds the
//! exact integral by h³/12·y″ per step (global order 2). All are second order. Applying the differentiation
//! twice (s → s′ → s″) loses one order at the two end nodes (the one-sided formula applied to
//! values that already carry the end error): use [`differentiate_periodic`] for a closed
//! cycle, or the analytic transfer functions, when s″ is needed at the ends.

use crate::error::{finite, positive, Error, Result};

fn check(y: &[f64], h: f64, min: usize) -> Result<()> {
    positive("h", h)?;
    if y.len() < min {
        return Err(Error::OutOfRange {
            name: "number of nodes",
            value: y.len() as f64,
            min: min as f64,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    for &v in y {
        finite("tabulated value", v)?;
    }
    Ok(())
}

/// The result, unless a finite input overflowed (a step of a few ulps, values near f64::MAX).
fn finite_result(name: &'static str, out: Vec<f64>) -> Result<Vec<f64>> {
    for &v in &out {
        crate::error::computed(name, v)?;
    }
    Ok(out)
}

/// The derivative of a function tabulated at equally spaced nodes (step `h`), by the
/// three-point formulas: central inside, one-sided second order at both ends.
///
/// # Examples
/// The formulas are exact for a parabola: y = x² on x = 0, 0.5, 1, 1.5 gives y′ = 2x.
/// ```
/// let d = tmm::kinematics::differentiate(&[0.0, 0.25, 1.0, 2.25], 0.5)?;
/// assert_eq!(d, vec![0.0, 1.0, 2.0, 3.0]);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::OutOfRange`] for fewer than 3 nodes; a non-positive or non-finite `h`, or a
/// non-finite value; [`Error::Overflow`] when the result overflows.
pub fn differentiate(y: &[f64], h: f64) -> Result<Vec<f64>> {
    check(y, h, 3)?;
    let n = y.len();
    let k = 0.5 / h;
    let mut d = Vec::with_capacity(n);
    d.push(k * (-y[2] + 4.0 * y[1] - 3.0 * y[0]));
    d.extend(y.windows(3).map(|w| k * (w[2] - w[0])));
    d.push(k * (3.0 * y[n - 1] - 4.0 * y[n - 2] + y[n - 3]));
    finite_result("derivative", d)
}

/// The derivative of a periodic function tabulated over one period at `y.len()` equally
/// spaced nodes (the last node is the one before the period closes): the central formula at
/// every node, wrapping around. Second order everywhere, so it can be applied twice.
///
/// # Examples
/// sin x at 4 nodes per period (h = π/2): the central difference gives sin h/h·cos x.
/// ```
/// use std::f64::consts::FRAC_PI_2;
/// let d = tmm::kinematics::differentiate_periodic(&[0.0, 1.0, 0.0, -1.0], FRAC_PI_2)?;
/// let k = 1.0 / FRAC_PI_2; // sin(π/2)/(π/2)
/// assert!((d[0] - k).abs() < 1e-15 && (d[2] + k).abs() < 1e-15 && d[1].abs() < 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`differentiate`].
pub fn differentiate_periodic(y: &[f64], h: f64) -> Result<Vec<f64>> {
    check(y, h, 3)?;
    let n = y.len();
    let k = 0.5 / h;
    finite_result(
        "derivative",
        (0..n)
            .map(|i| k * (y[(i + 1) % n] - y[(i + n - 1) % n]))
            .collect(),
    )
}

/// The running integral I(xᵢ) = ∫ from x₁ to xᵢ of a function tabulated at equally spaced
/// nodes (step `h`), by the trapezoid rule; the first value is 0.
///
/// # Examples
/// Exact for a straight line: ∫₀ˣ 2t dt = x² at x = 0, 1, 2.
/// ```
/// let i = tmm::kinematics::integrate_trapezoid(&[0.0, 2.0, 4.0], 1.0)?;
/// assert_eq!(i, vec![0.0, 1.0, 4.0]);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::OutOfRange`] for fewer than 2 nodes; a non-positive or non-finite `h`, or a
/// non-finite value; [`Error::Overflow`] when the result overflows.
pub fn integrate_trapezoid(y: &[f64], h: f64) -> Result<Vec<f64>> {
    check(y, h, 2)?;
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(y.len());
    out.push(0.0);
    for w in y.windows(2) {
        acc += 0.5 * h * (w[0] + w[1]);
        out.push(acc);
    }
    finite_result("integral", out)
}
