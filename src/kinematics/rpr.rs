//! The RPR dyad (group of the 2nd class, 3rd kind; the seeds' SR3): a rod 2 hinged at A that
//! slides through a rocking cylinder (or slotted block) 3 hinged at E (the seeds' name for the
//! pivot, as in the RPR's reactions, [`RprDyad`](crate::kinetostatics::RprDyad); their C is the
//! cylinder's mouth).

use super::contour::{in_group, solve_contour, Branch, LoopVector};
use super::link::LinkMotion;
use super::motion::{Motion, PointMotion};
use crate::angle::{direction, normalize, perp, unit};
use crate::error::{computed_all, Result};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// A and E count as one point when closer than this many units of the larger coordinate:
/// the rounding of the points themselves (the reactions' RPR uses 8ε on its scale).
const SAME_POINT: f64 = 16.0 * f64::EPSILON;

/// The solved RPR dyad. The rod and the cylinder turn together (same ω, ε).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprState {
    /// The rod 2: origin A, angle φ2 = direction of A→E (into the cylinder, the seed's φ2).
    pub link2: LinkMotion,
    /// The cylinder 3: origin E, angle = direction of E→A (φ2 + π), so that its points
    /// towards A are at positive `along` distances.
    pub link3: LinkMotion,
    /// The distance l_EA with its rate and acceleration: the rod's sliding in the cylinder
    /// (positive rate: the rod comes out, A moves away from E).
    pub slide: Motion,
}

impl RprState {
    /// The velocity of the rod's point relative to the cylinder's coinciding point: ṡ along
    /// E→A.
    #[must_use]
    pub fn relative_velocity(&self) -> Vector2<f64> {
        self.slide.rate * self.link3.unit()
    }

    /// The relative (sliding) acceleration s̈ along E→A.
    #[must_use]
    pub fn relative_acceleration(&self) -> Vector2<f64> {
        self.slide.accel * self.link3.unit()
    }

    /// The Coriolis acceleration 2·ω × v_rel of the rod's points relative to the cylinder
    /// (the relative velocity turned 90° in the sense of ω).
    #[must_use]
    pub fn coriolis(&self) -> Vector2<f64> {
        2.0 * self.link3.omega * perp(self.relative_velocity())
    }
}

/// Positions, velocities and accelerations of an RPR dyad: a rod hinged at A sliding through
/// a cylinder hinged at E, with the cylinder's axis through E (no offset).
///
/// The unknowns are the polar coordinates of A about E (the contour's polar case), so the
/// solution is unique and the velocity system has determinant 1; the conditioning is the
/// length l_EA itself (ω = v⊥/l_EA), and the dyad is singular only when A reaches E.
///
/// # Examples
/// A crank pin at A = (0, 0.1) moving at 1 m/s along −x, the cylinder pivot at E = (0.3, 0.1):
/// l_EA = 0.3 m, the rod points along +x (φ2 = 0), the pin slides away from E at 1 m/s and the
/// rod does not turn.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{rpr_dyad, PointMotion};
/// let a = PointMotion::new(Point2::new(0.0, 0.1), Vector2::new(-1.0, 0.0), Vector2::zeros());
/// let e = PointMotion::fixed(Point2::new(0.3, 0.1));
/// let d = rpr_dyad(a, e)?;
/// assert_relative_eq!(d.slide.value, 0.3, epsilon = 1e-15);
/// assert_relative_eq!(d.slide.rate, 1.0, epsilon = 1e-15);
/// assert_eq!(d.link2.angle, 0.0);
/// assert_relative_eq!(d.link2.omega, 0.0, epsilon = 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// Non-finite input ([`Error::NonFinite`](crate::Error::NonFinite)), or
/// [`Error::Singular`](crate::Error::Singular) with `measure = "l_EA"` when A coincides with E
/// (closer than 16ε of their coordinates' size, where the axis's direction is rounding noise).
#[doc(alias = "SR3")]
#[inline]
pub fn rpr_dyad(a: PointMotion, e: PointMotion) -> Result<RprState> {
    match rpr_fast(a, e) {
        Some(s) => Ok(s),
        None => rpr_checked(a, e),
    }
}

/// The RPR dyad in Cartesian form, with every check folded into one test at the end: with
/// d = E − A = l·u, l̇ = (v_E − v_A)·u, ω = (v_E − v_A)·u⊥/l, l̈ = (a_E − a_A)·u + l·ω² and
/// ε = ((a_E − a_A)·u⊥ − 2·l̇·ω)/l (the polar case of [`solve_contour`]). `None` wherever
/// [`rpr_checked`] fails, which then names the cause.
#[inline]
fn rpr_fast(a: PointMotion, e: PointMotion) -> Option<RprState> {
    let d = e.p - a.p;
    let dv = e.v - a.v;
    let da = e.a - a.a;
    let l_sq = d.norm_squared();
    let l = l_sq.sqrt();
    let i_l = 1.0 / l;
    let u = d * i_l;
    let [l_rate, omega, l_accel, epsilon] = rpr_rates(u, l, i_l, dv, da);
    let ok = super::rrr::all_finite([
        a.p.x, a.p.y, a.v.x, a.v.y, a.a.x, a.a.y, e.p.x, e.p.y, e.v.x, e.v.y, e.a.x, e.a.y, l_sq,
        dv.x, dv.y, da.x, da.y, i_l, l_rate, omega, l_accel, epsilon,
    ]) & (l_sq >= f64::MIN_POSITIVE)
        // Twice the checked path's band of rounding (see `SAME_POINT`), so that nothing near
        // it is decided here.
        & (l_sq > 4.0 * SAME_POINT * SAME_POINT * a.p.coords.norm_squared().max(e.p.coords.norm_squared()));
    ok.then(|| RprState {
        link2: LinkMotion {
            origin: a,
            angle: direction(d),
            omega,
            epsilon,
        },
        link3: LinkMotion {
            origin: e,
            angle: direction(-d),
            omega,
            epsilon,
        },
        slide: Motion::new(l, l_rate, l_accel),
    })
}

/// The rates of an RPR dyad at a known position, [l̇, ω, l̈, ε]: on the axis's unit vector
/// `u` from A to E, its length `l` and `i_l` = 1/l, with `dv` = v_E − v_A and
/// `da` = a_E − a_A: l̇ = dv·u, ω = dv·u⊥/l, l̈ = da·u + l·ω², ε = (da·u⊥ − 2·l̇·ω)/l. The
/// closed form and the engine's rates-only pass (positions kept, new input rates) share it.
#[inline(always)]
pub(crate) fn rpr_rates(
    u: Vector2<f64>,
    l: f64,
    i_l: f64,
    dv: Vector2<f64>,
    da: Vector2<f64>,
) -> [f64; 4] {
    let n = perp(u);
    let l_rate = dv.dot(&u);
    let omega = dv.dot(&n) * i_l;
    let l_accel = da.dot(&u) + l * omega * omega;
    let epsilon = (da.dot(&n) - 2.0 * l_rate * omega) * i_l;
    [l_rate, omega, l_accel, epsilon]
}

/// The RPR dyad through the general contour solver, checked step by step.
#[cold]
#[inline(never)]
fn rpr_checked(a: PointMotion, e: PointMotion) -> Result<RprState> {
    a.validate(["A.x", "A.y", "v_A.x", "v_A.y", "a_A.x", "a_A.y"])?;
    e.validate(["E.x", "E.y", "v_E.x", "v_E.y", "a_E.x", "a_E.y"])?;
    let (ac, vac, aac) = (a.p - e.p, a.v - e.v, a.a - e.a);
    computed_all(
        "RPR dyad: A - E",
        ac.iter().chain(vac.iter()).chain(aac.iter()),
    )?;
    // A and E closer than their coordinates' rounding: the axis's direction is noise, and
    // ω = v⊥/l_EA would be ~1e16 times too large. Singular, as the reactions say too.
    let scale = a.p.coords.norm().max(e.p.coords.norm());
    if ac.norm() <= SAME_POINT * scale {
        return Err(crate::Error::Singular {
            what: "RPR dyad",
            measure: "l_EA",
            value: ac.norm(),
        });
    }
    // The loop E → A → E: (A − E) + l_EA·e(φ2) = 0, φ2 the direction of A→E.
    let loop_ = [
        LoopVector::Cartesian {
            r: a.p - e.p,
            v: a.v - e.v,
            a: a.a - e.a,
        },
        LoopVector::unknown(),
    ];
    let s = solve_contour(&loop_, Branch::Plus).map_err(|e| match e {
        crate::Error::Singular { value, .. } => crate::Error::Singular {
            what: "RPR dyad",
            measure: "l_EA",
            value,
        },
        other => in_group(other, "RPR dyad", "l_EA", 1.0),
    })?;
    let [slide, phi] = s.unknowns;
    let link2 = LinkMotion {
        origin: a,
        angle: phi.value,
        omega: phi.rate,
        epsilon: phi.accel,
    };
    let link3 = LinkMotion {
        origin: e,
        angle: normalize(phi.value + PI),
        omega: phi.rate,
        epsilon: phi.accel,
    };
    debug_assert!(
        (a.p + slide.value * unit(phi.value) - e.p).norm() <= 1e-9 * slide.value.max(1.0)
    );
    computed_all(
        "RPR dyad",
        [
            link2.angle,
            link2.omega,
            link2.epsilon,
            slide.value,
            slide.rate,
            slide.accel,
        ]
        .iter(),
    )?;
    Ok(RprState {
        link2,
        link3,
        slide,
    })
}
