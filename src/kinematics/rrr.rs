//! The RRR dyad (group of the 2nd class, 1st kind; the seeds' SR1): links 2 = A B and
//! 3 = C B joined at B, attached to known joints A and C.

use super::contour::{in_group, solve_contour, Branch, LoopVector};
use super::link::LinkMotion;
use super::motion::PointMotion;
use crate::angle::{normalize, unit};
use crate::error::{computed_all, positive, Result};
use std::f64::consts::PI;

/// The solved RRR dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrState {
    /// The inner joint B.
    pub b: PointMotion,
    /// Link 2: origin A, angle φ2 = direction of A→B, ω2, ε2.
    pub link2: LinkMotion,
    /// Link 3: origin C, angle φ3 = direction of C→B, ω3, ε3.
    pub link3: LinkMotion,
    /// sin(φ3 − φ2): the conditioning of the dyad. It vanishes when the links are collinear
    /// (a dead point); velocities and accelerations grow like its inverse.
    pub det: f64,
}

/// Positions, velocities and accelerations of an RRR dyad from the motions of its outer
/// joints A and C.
///
/// `branch`: [`Branch::Plus`] puts B to the left of the directed line A → C
/// (then sin(φ3 − φ2) > 0), [`Branch::Minus`] to the right.
///
/// # Examples
/// A four-bar with the frame O C = 0.3 m along +x, crank O A = 0.1 m at 0°: A = (0.1, 0),
/// so with A B = C B = 0.2 m the dyad is an isosceles triangle with B = (0.2, √0.03).
/// A at rest, so B is at rest too; the angles are 60° and 120°.
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{rrr_dyad, Branch, PointMotion};
/// let a = PointMotion::fixed(Point2::new(0.1, 0.0));
/// let c = PointMotion::fixed(Point2::new(0.3, 0.0));
/// let d = rrr_dyad(a, c, 0.2, 0.2, Branch::Plus)?;
/// assert_relative_eq!(d.b.p, Point2::new(0.2, 0.03f64.sqrt()), epsilon = 1e-15);
/// assert_relative_eq!(d.link2.angle.to_degrees(), 60.0, epsilon = 1e-12);
/// assert_relative_eq!(d.link3.angle.to_degrees(), 120.0, epsilon = 1e-12);
/// assert_relative_eq!(d.det, (60f64.to_radians()).sin(), epsilon = 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - [`Error::NonPositive`](crate::Error::NonPositive) / [`Error::NonFinite`](crate::Error::NonFinite) for bad input;
/// - [`Error::NotAssemblable`](crate::Error::NotAssemblable) with `group = "RRR dyad"` when
///   |AC| > l_AB + l_CB or |AC| < |l_AB − l_CB| (`gap` by how much);
/// - [`Error::Singular`](crate::Error::Singular) with `measure = "sin(phi3 - phi2)"` at a dead
///   point (links 2 and 3 collinear).
#[doc(alias = "SR1")]
pub fn rrr_dyad(
    a: PointMotion,
    c: PointMotion,
    l_ab: f64,
    l_cb: f64,
    branch: Branch,
) -> Result<RrrState> {
    a.validate(["A.x", "A.y", "v_A.x", "v_A.y", "a_A.x", "a_A.y"])?;
    c.validate(["C.x", "C.y", "v_C.x", "v_C.y", "a_C.x", "a_C.y"])?;
    positive("l_AB", l_ab)?;
    positive("l_CB", l_cb)?;
    let (ac, vac, aac) = (a.p - c.p, a.v - c.v, a.a - c.a);
    computed_all(
        "RRR dyad: A - C",
        ac.iter().chain(vac.iter()).chain(aac.iter()),
    )?;
    // The loop C → A → B → C: (A − C) + l_AB·e(φ2) + l_CB·e(φ3 + π) = 0.
    let loop_ = [
        LoopVector::Cartesian {
            r: a.p - c.p,
            v: a.v - c.v,
            a: a.a - c.a,
        },
        LoopVector::unknown_angle(l_ab),
        LoopVector::unknown_angle(l_cb),
    ];
    let s = solve_contour(&loop_, branch)
        .map_err(|e| in_group(e, "RRR dyad", "sin(phi3 - phi2)", -1.0))?;
    let [p2, p3] = s.unknowns;
    let link2 = LinkMotion {
        origin: a,
        angle: p2.value,
        omega: p2.rate,
        epsilon: p2.accel,
    };
    let link3 = LinkMotion {
        origin: c,
        angle: normalize(p3.value - PI),
        omega: p3.rate,
        epsilon: p3.accel,
    };
    let b = link2.motion_of(a.p + l_ab * unit(p2.value));
    computed_all(
        "RRR dyad",
        [
            b.p.x,
            b.p.y,
            b.v.x,
            b.v.y,
            b.a.x,
            b.a.y,
            link2.angle,
            link2.omega,
            link2.epsilon,
            link3.angle,
            link3.omega,
            link3.epsilon,
        ]
        .iter(),
    )?;
    Ok(RrrState {
        b,
        link2,
        link3,
        det: -s.determinant,
    })
}
