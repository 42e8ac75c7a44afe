//! The RRR dyad (group of the 2nd class, 1st kind; the seeds' SR1): links 2 = A B and
//! 3 = C B joined at B, attached to known joints A and C.

use super::contour::{in_group, solve_contour, Branch, LoopVector, SINGULAR_DETERMINANT};
use super::link::LinkMotion;
use super::motion::PointMotion;
use crate::angle::{cross, direction, normalize, perp, unit};
use crate::error::{computed_all, positive, Result};
use nalgebra::Vector2;
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
#[inline]
pub fn rrr_dyad(
    a: PointMotion,
    c: PointMotion,
    l_ab: f64,
    l_cb: f64,
    branch: Branch,
) -> Result<RrrState> {
    match rrr_fast(a, c, l_ab, l_cb, branch) {
        Some(s) => Ok(s),
        None => rrr_checked(a, c, l_ab, l_cb, branch),
    }
}

/// The RRR dyad in Cartesian form, with every check folded into one test at the end.
///
/// B = A + x·e + σ·h·e⊥ on the unit vector e from A to C (the circle–circle intersection of
/// [`solve_contour`]); the velocity and acceleration systems are solved on the link vectors
/// r2 = B − A and r3 = B − C, with D = r2 × r3 = l_AB·l_CB·sin(φ3 − φ2):
/// ω2 = (v_C − v_A)·r3/D, ω3 = (v_C − v_A)·r2/D, and likewise ε2, ε3 with the centripetal
/// terms. Each angle is one `atan2`, and nothing is rebuilt from an angle.
///
/// `None` wherever [`rrr_checked`] fails, and near its thresholds (the tangent case and the
/// dead point, each with a margin of 2), so that it decides there and names the cause.
#[inline]
fn rrr_fast(
    a: PointMotion,
    c: PointMotion,
    l_ab: f64,
    l_cb: f64,
    branch: Branch,
) -> Option<RrrState> {
    let d = c.p - a.p;
    let dv = c.v - a.v;
    let da = c.a - a.a;
    let l_sq = d.norm_squared();
    let l = l_sq.sqrt();
    // The same closed form as the contour's: x = (l² + a² − b²)/(2l), h² = a² − x², but
    // from the pivot of the shorter link: with q = (a² − b²)/l, its projection is x = (l + q)/2
    // from A or l − x = (l − q)/2 from C, and h² = (l_s − x_s)(l_s + x_s). Either carries
    // about ε·l of rounding, which enters h² times 2·x_s: from the longer link's pivot that is
    // ε·l·l_long against h² ~ l_short², so B near C (l_CB = l_AB/1000) lost 10⁻¹⁰ of the short
    // link's angle; from the shorter, ε·l·l_short, the rounding the data carry anyway.
    // Selects, not branches: as fast as the former closed form (a branch cost 10 %).
    let short_c = l_cb < l_ab;
    let q = (l_ab - l_cb) * (l_ab + l_cb) / l;
    // x, or −(l − x) along e from C.
    let along = 0.5 * (q + if short_c { -l } else { l });
    let ls = if short_c { l_cb } else { l_ab };
    let h2 = (ls - along) * (ls + along);
    let tol = 16.0 * f64::EPSILON * (l_ab * l_ab + l_cb * l_cb + l_sq);
    let h = h2.sqrt();
    let e = d / l;
    // The shorter link's vector from its own projection, the other's by adding or taking
    // off d = C − A.
    let v = along * e + (branch.sign() * h) * perp(e);
    let zero = Vector2::zeros();
    let r2 = v + if short_c { d } else { zero };
    let r3 = v - if short_c { zero } else { d };
    let big_d = cross(r2, r3);
    let det = big_d / (l_ab * l_cb);
    let i_d = 1.0 / big_d;
    let [omega2, omega3, epsilon2, epsilon3] = rrr_rates(r2, r3, i_d, dv, da);
    // Link 2's motion (its angle, one `atan2`, is taken only once the position is good) and
    // B as its point.
    let rod = LinkMotion {
        origin: a,
        angle: 0.0,
        omega: omega2,
        epsilon: epsilon2,
    };
    let b = rod.moving_at(a.p + r2, r2);
    let ok = all_finite([
        a.p.x, a.p.y, a.v.x, a.v.y, a.a.x, a.a.y, c.p.x, c.p.y, c.v.x, c.v.y, c.a.x, c.a.y, l_ab,
        l_cb, l_sq, dv.x, dv.y, da.x, da.y, h, omega2, omega3, epsilon2, epsilon3, b.p.x, b.p.y,
        b.v.x, b.v.y, b.a.x, b.a.y, det,
    ]) & (l_ab > 0.0)
        & (l_cb > 0.0)
        & (l_sq >= f64::MIN_POSITIVE)
        & (h2 > 2.0 * tol)
        & (det.abs() > 2.0 * SINGULAR_DETERMINANT);
    ok.then(|| RrrState {
        b,
        link2: LinkMotion {
            angle: direction(r2),
            ..rod
        },
        link3: LinkMotion {
            origin: c,
            angle: direction(r3),
            omega: omega3,
            epsilon: epsilon3,
        },
        det,
    })
}

/// The rates of an RRR dyad at a known position, [ω2, ω3, ε2, ε3]: the velocity and
/// acceleration systems on the link vectors r2 = B − A and r3 = B − C, with
/// `i_d` = 1/(r2 × r3), `dv` = v_C − v_A and `da` = a_C − a_A:
/// ω2 = dv·r3/D, ω3 = dv·r2/D, and ε2, ε3 likewise on da + ω2²·r2 − ω3²·r3. The closed form
/// and the engine's rates-only pass (positions kept, new input rates) share it.
#[inline(always)]
pub(crate) fn rrr_rates(
    r2: Vector2<f64>,
    r3: Vector2<f64>,
    i_d: f64,
    dv: Vector2<f64>,
    da: Vector2<f64>,
) -> [f64; 4] {
    let omega2 = dv.dot(&r3) * i_d;
    let omega3 = dv.dot(&r2) * i_d;
    let rhs = da + omega2 * omega2 * r2 - omega3 * omega3 * r3;
    let epsilon2 = rhs.dot(&r3) * i_d;
    let epsilon3 = rhs.dot(&r2) * i_d;
    [omega2, omega3, epsilon2, epsilon3]
}

/// `true` when every value is finite, by one test of their sum: a sum with an infinity or a
/// NaN among its terms is not finite. A sum of finite values can still overflow; then this
/// says `false` too and the checked path runs instead: the test may send a good case there,
/// never let a bad one through. Four partial sums, so that it is not one long chain.
#[inline(always)]
pub(crate) fn all_finite<const N: usize>(values: [f64; N]) -> bool {
    let mut acc = [0.0; 4];
    for (i, v) in values.iter().enumerate() {
        acc[i % 4] += v;
    }
    ((acc[0] + acc[1]) + (acc[2] + acc[3])).is_finite()
}

/// The RRR dyad through the general contour solver, checked step by step.
#[cold]
#[inline(never)]
fn rrr_checked(
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
