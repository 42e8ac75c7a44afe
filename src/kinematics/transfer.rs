//! First and second transfer functions (the seed's "analogues" of velocity and acceleration).
//!
//! An output coordinate φn(φ1) or sn(φ1) of a one-degree-of-freedom mechanism depends only on
//! the input coordinate. Its derivatives φ′ = dφn/dφ1, φ″ = d²φn/dφ1² (and s′, s″) are
//! properties of the geometry alone; the actual motion follows for any input law:
//! ω = φ′·ω1, ε = φ″·ω1² + φ′·ε1 (and v = s′·ω1, a = s″·ω1² + s′·ε1), see
//! [`Motion::at_input_speed`].
//!
//! Every block of this module is linear in the input's rate and acceleration in this way, so
//! the transfer functions are the block outputs for an input moving at unit speed without
//! acceleration ([`Motion::unit_speed`]). No separate derivation is needed, and none can drift
//! out of step with the velocity solution.

use super::motion::Motion;
use crate::error::{finite, Result};

/// The transfer functions of an output at the input coordinate `phi1`: `value` = the
/// position function, `rate` = the first transfer function, `accel` = the second.
///
/// `output` maps the input's motion to the output's motion (usually a short chain of block
/// calls); it is evaluated once with ω1 = 1, ε1 = 0.
///
/// # Examples
/// The central slider-crank's slider (crank r = 0.1 m, rod l = 0.3 m, guide along +x):
/// at φ1 = 90° the crank pin moves along −x at r·ω1 and the rod translates for an instant
/// (B and A have the same velocity), so s′ = −r and s = √(l² − r²).
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{crank, rrp_dyad, transfer_functions, Branch, Guide};
/// let slider = |input| {
///     let c = crank(Point2::origin(), 0.1, input)?;
///     Ok(rrp_dyad(c.a, Guide::fixed(Point2::origin(), 0.0), 0.3, Branch::Plus)?.slide)
/// };
/// let t = transfer_functions(slider, std::f64::consts::FRAC_PI_2)?;
/// assert_relative_eq!(t.value, 0.08f64.sqrt(), epsilon = 1e-15);
/// assert_relative_eq!(t.rate, -0.1, epsilon = 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite `phi1` or a non-finite
/// output; whatever `output` returns.
pub fn transfer_functions<F>(output: F, phi1: f64) -> Result<Motion>
where
    F: FnOnce(Motion) -> Result<Motion>,
{
    finite("phi1", phi1)?;
    let m = output(Motion::unit_speed(phi1))?;
    m.validate(["output", "output rate", "output accel"])?;
    Ok(m)
}
