//! The input link: a crank turning about a fixed pivot.

use super::link::LinkMotion;
use super::motion::{Motion, PointMotion};
use crate::angle::{normalize, perp, unit};
use crate::error::{computed_all, finite2, positive, Result};
use nalgebra::{Point2, Vector2};

/// The state of a crank O A: its link motion (origin O) and the motion of its pin A.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CrankState {
    /// The crank pin A.
    pub a: PointMotion,
    /// The crank as a link: origin O, angle φ1, ω1, ε1.
    pub link: LinkMotion,
}

/// The input link: a crank of length `l_oa` about the fixed pivot `o`, at the angle
/// `phi.value` (rad, CCW from +x) turning at ω1 = `phi.rate` with ε1 = `phi.accel`.
///
/// A = O + l·e(φ1), v_A = l·ω1·e⊥(φ1), a_A = l·ε1·e⊥(φ1) − l·ω1²·e(φ1).
///
/// # Examples
/// A 0.05 m crank at 30° turning at 100 rad/s: |v_A| = 5 m/s, |a_A| = l·ω² = 500 m/s².
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{crank, Motion};
/// let c = crank(Point2::origin(), 0.05, Motion::new(30f64.to_radians(), 100.0, 0.0))?;
/// assert_relative_eq!(c.a.p.x, 0.05 * 3f64.sqrt() / 2.0, epsilon = 1e-15);
/// assert_relative_eq!(c.a.v.norm(), 5.0, epsilon = 1e-12);
/// assert_relative_eq!(c.a.a.norm(), 500.0, epsilon = 1e-10);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`](crate::Error::NonFinite) or
/// [`Error::NonPositive`](crate::Error::NonPositive) for a bad input, or
/// [`Error::Overflow`](crate::Error::Overflow) naming the pin's motion when
/// finite inputs overflow (for example l_OA·ω1² beyond f64::MAX).
#[inline]
pub fn crank(o: Point2<f64>, l_oa: f64, phi: Motion) -> Result<CrankState> {
    // The fast path: one sin_cos, every check folded into one test; the checked path below
    // names what fails.
    let (sin, cos) = phi.value.sin_cos();
    let r = Vector2::new(cos, sin) * l_oa;
    let link = LinkMotion {
        origin: PointMotion::fixed(o),
        angle: normalize(phi.value),
        omega: phi.rate,
        epsilon: phi.accel,
    };
    let a = PointMotion {
        p: o + r,
        v: phi.rate * perp(r),
        a: phi.accel * perp(r) - phi.rate * phi.rate * r,
    };
    let ok = super::rrr::all_finite([
        o.x, o.y, l_oa, phi.value, phi.rate, phi.accel, a.p.x, a.p.y, a.v.x, a.v.y, a.a.x, a.a.y,
    ]) & (l_oa > 0.0);
    if ok {
        Ok(CrankState { a, link })
    } else {
        crank_checked(o, l_oa, phi)
    }
}

#[cold]
#[inline(never)]
fn crank_checked(o: Point2<f64>, l_oa: f64, phi: Motion) -> Result<CrankState> {
    finite2(["O.x", "O.y"], o.coords)?;
    positive("l_OA", l_oa)?;
    phi.validate(["phi1", "omega1", "epsilon1"])?;
    let link = LinkMotion {
        origin: PointMotion::fixed(o),
        angle: normalize(phi.value),
        omega: phi.rate,
        epsilon: phi.accel,
    };
    let a = link.motion_of(o + l_oa * unit(phi.value));
    computed_all(
        "crank pin A (position, velocity, acceleration)",
        [a.p.x, a.p.y, a.v.x, a.v.y, a.a.x, a.a.y].iter(),
    )?;
    Ok(CrankState { a, link })
}
