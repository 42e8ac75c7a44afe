//! The RRP dyad (group of the 2nd class, 2nd kind; the seeds' SR2): link 2 = A B, and a
//! slider 3 hinged to it at B that slides along a guide.

use super::contour::{in_group, solve_contour, Branch, LoopVector, SINGULAR_DETERMINANT};
use super::link::LinkMotion;
use super::motion::{Motion, PointMotion};
use crate::angle::{cross, direction, normalize, perp, unit};
use crate::error::{computed_all, positive, Result};
use nalgebra::{Point2, Vector2};
use std::f64::consts::PI;

/// A straight guide: a point G on it and its direction angle φ4, both with their motion.
///
/// A fixed guide (a cylinder bore, a frame slot) is [`Guide::fixed`]. A guide cut in a
/// moving link (a slotted lever) moves with that link: G's velocity and acceleration are
/// those of the link's point at G, and the angle turns with the link's ω and ε; then the
/// slider's acceleration has a Coriolis part 2·ω4·v_rel.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Guide {
    /// A point of the guide line, with its motion.
    pub point: PointMotion,
    /// The direction angle φ4 of the guide, rad, with its rate and acceleration.
    pub angle: Motion,
}

impl Guide {
    /// A fixed guide through `point` along the direction angle `angle` (rad).
    #[must_use]
    pub fn fixed(point: Point2<f64>, angle: f64) -> Self {
        Self {
            point: PointMotion::fixed(point),
            angle: Motion::fixed(angle),
        }
    }

    /// The guide cut along a link: through the link point at `p`, along the link's direction
    /// plus `offset_angle` (0 for a slot along the link).
    #[must_use]
    pub fn on_link(link: &LinkMotion, p: Point2<f64>, offset_angle: f64) -> Self {
        Self {
            point: link.motion_of(p),
            angle: Motion::new(link.angle + offset_angle, link.omega, link.epsilon),
        }
    }

    /// The unit vector along the guide.
    #[must_use]
    pub fn unit(&self) -> Vector2<f64> {
        unit(self.angle.value)
    }
}

/// The solved RRP dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpState {
    /// The joint B (the slider's hinge) with its absolute velocity and acceleration.
    pub b: PointMotion,
    /// Link 2: origin A, angle φ2 = direction of A→B, ω2, ε2.
    pub link2: LinkMotion,
    /// The slider 3: origin B, angle = the guide's direction φ4 in [0, 2π), with the guide's
    /// ω and ε.
    pub link3: LinkMotion,
    /// The slider's coordinate along the guide, s = (B − G)·e(φ4), with its relative
    /// velocity ṡ and relative acceleration s̈ (relative to the guide).
    pub slide: Motion,
    /// cos(φ2 − φ4): the conditioning of the dyad. It vanishes when link 2 is perpendicular
    /// to the guide (a dead point).
    pub det: f64,
}

/// Positions, velocities and accelerations of an RRP dyad: link A B of length `l_ab` whose
/// end B slides along `guide`.
///
/// `branch`: [`Branch::Plus`] puts B ahead of the foot F of the perpendicular from A to the
/// guide ((B − F)·e(φ4) ≥ 0, so cos(φ2 − φ4) ≥ 0), [`Branch::Minus`] behind it.
///
/// # Examples
/// A central slider-crank: crank 0.1 m at 90°, so A = (0, 0.1); connecting rod 0.2 m; guide
/// along +x through O. On the `Plus` branch B = (√0.03, 0) and s = √0.03 m.
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{rrp_dyad, Branch, Guide, PointMotion};
/// let a = PointMotion::fixed(Point2::new(0.0, 0.1));
/// let d = rrp_dyad(a, Guide::fixed(Point2::origin(), 0.0), 0.2, Branch::Plus)?;
/// assert_relative_eq!(d.slide.value, 0.03f64.sqrt(), epsilon = 1e-15);
/// assert_relative_eq!(d.link2.angle.to_degrees(), 330.0, epsilon = 1e-12);
/// assert_relative_eq!(d.det, (30f64.to_radians()).cos(), epsilon = 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - bad input: [`Error::NonFinite`](crate::Error::NonFinite), [`Error::NonPositive`](crate::Error::NonPositive);
/// - [`Error::NotAssemblable`](crate::Error::NotAssemblable) with `group = "RRP dyad"` when A
///   is farther than l_AB from the guide line (`gap` by how much);
/// - [`Error::Singular`](crate::Error::Singular) with `measure = "cos(phi2 - phi4)"` when
///   link 2 is perpendicular to the guide.
#[doc(alias = "SR2")]
#[inline]
pub fn rrp_dyad(a: PointMotion, guide: Guide, l_ab: f64, branch: Branch) -> Result<RrpState> {
    match rrp_fast(a, guide, l_ab, branch) {
        Some(s) => Ok(s),
        None => rrp_checked(a, guide, l_ab, branch),
    }
}

/// The RRP dyad in Cartesian form, with every check folded into one test at the end.
///
/// With g the guide's unit vector and g⊥ its normal, B = A + r2 with r2 = σ·c·g + q·g⊥,
/// q = g⊥·(G − A), c = √(l_AB² − q²) (the line–circle intersection of [`solve_contour`]).
/// Differentiating A + r2 − G − s·g = 0 gives ω2·r2⊥ − ṡ·g = (v_G − v_A) + s·ω4·g⊥, and once
/// more the same matrix with the centripetal, Coriolis and guide terms; its determinant is
/// D = r2·g = l_AB·cos(φ2 − φ4). One `sin_cos` (the guide's angle) and one `atan2` (φ2).
///
/// `None` wherever [`rrp_checked`] fails, and near its thresholds (the tangent case and the
/// dead point, each with a margin of 2), so that it decides there and names the cause.
#[inline]
fn rrp_fast(a: PointMotion, guide: Guide, l_ab: f64, branch: Branch) -> Option<RrpState> {
    let gp = guide.point;
    let beta = guide.angle;
    let (sin, cos) = beta.value.sin_cos();
    let g = Vector2::new(cos, sin);
    let n = perp(g);
    let d = gp.p - a.p;
    let dv = gp.v - a.v;
    let da = gp.a - a.a;
    let q = n.dot(&d);
    let c2 = (l_ab - q) * (l_ab + q);
    let tol = 16.0 * f64::EPSILON * (l_ab * l_ab + d.norm_squared());
    let c = c2.sqrt();
    let r2 = (branch.sign() * c) * g + q * n;
    let s = (r2 - d).dot(&g);
    let big_d = r2.dot(&g);
    let i_d = 1.0 / big_d;
    let (w4, e4) = (beta.rate, beta.accel);
    let [omega2, s_rate, epsilon2, s_accel] = rrp_rates(g, r2, s, i_d, (dv, da), (w4, e4));
    let det = big_d / l_ab;
    // Link 2's motion (its angle, one `atan2`, is taken only once the position is good) and
    // B as its point.
    let rod = LinkMotion {
        origin: a,
        angle: 0.0,
        omega: omega2,
        epsilon: epsilon2,
    };
    let b = rod.moving_at(a.p + r2, r2);
    let ok = super::rrr::all_finite([
        a.p.x, a.p.y, a.v.x, a.v.y, a.a.x, a.a.y, gp.p.x, gp.p.y, gp.v.x, gp.v.y, gp.a.x, gp.a.y,
        beta.value, w4, e4, l_ab, d.x, d.y, dv.x, dv.y, da.x, da.y, c, s, omega2, s_rate, epsilon2,
        s_accel, b.p.x, b.p.y, b.v.x, b.v.y, b.a.x, b.a.y, det,
    ]) & (l_ab > 0.0)
        & (c2 > 2.0 * tol)
        & (det.abs() > 2.0 * SINGULAR_DETERMINANT);
    ok.then(|| {
        let link2 = LinkMotion {
            angle: direction(r2),
            ..rod
        };
        let link3 = LinkMotion {
            origin: b,
            angle: normalize(beta.value),
            omega: w4,
            epsilon: e4,
        };
        RrpState {
            b,
            link2,
            link3,
            slide: Motion::new(s, s_rate, s_accel),
            det,
        }
    })
}

/// The rates of an RRP dyad at a known position, [ω2, ṡ, ε2, s̈]: on the guide's unit
/// vector `g` (turning at ω4, ε4 = `guide_rates`), the rod r2 = B − A, the slide `s` of B
/// from the guide's point G and `i_d` = 1/(r2·g), with (`dv`, `da`) = G's velocity and
/// acceleration less A's, differentiating A + r2 − G − s·g = 0 once and twice. The closed
/// form and the engine's rates-only pass (positions kept, new input rates) share it.
#[inline(always)]
pub(crate) fn rrp_rates(
    g: Vector2<f64>,
    r2: Vector2<f64>,
    s: f64,
    i_d: f64,
    (dv, da): (Vector2<f64>, Vector2<f64>),
    (w4, e4): (f64, f64),
) -> [f64; 4] {
    let n = perp(g);
    let rv = dv + (s * w4) * n;
    let omega2 = cross(g, rv) * i_d;
    let s_rate = -r2.dot(&rv) * i_d;
    let ra = da + (omega2 * omega2) * r2 + (2.0 * s_rate * w4 + s * e4) * n - (s * w4 * w4) * g;
    let epsilon2 = cross(g, ra) * i_d;
    let s_accel = -r2.dot(&ra) * i_d;
    [omega2, s_rate, epsilon2, s_accel]
}

/// The RRP dyad through the general contour solver, checked step by step.
#[cold]
#[inline(never)]
fn rrp_checked(a: PointMotion, guide: Guide, l_ab: f64, branch: Branch) -> Result<RrpState> {
    a.validate(["A.x", "A.y", "v_A.x", "v_A.y", "a_A.x", "a_A.y"])?;
    guide
        .point
        .validate(["G.x", "G.y", "v_G.x", "v_G.y", "a_G.x", "a_G.y"])?;
    guide.angle.validate(["phi4", "omega4", "epsilon4"])?;
    positive("l_AB", l_ab)?;
    let g = guide.point;
    let beta = guide.angle;
    let (ag, vag, aag) = (a.p - g.p, a.v - g.v, a.a - g.a);
    computed_all(
        "RRP dyad: A - G",
        ag.iter().chain(vag.iter()).chain(aag.iter()),
    )?;
    // The loop G → A → B → G: (A − G) + l_AB·e(φ2) + s·e(φ4 + π) = 0.
    let loop_ = [
        LoopVector::Cartesian {
            r: a.p - g.p,
            v: a.v - g.v,
            a: a.a - g.a,
        },
        LoopVector::unknown_angle(l_ab),
        LoopVector::unknown_length(Motion::new(beta.value + PI, beta.rate, beta.accel)),
    ];
    // The contour's Plus makes A→B point along e(φ4 + π), i.e. B behind F: the opposite.
    let s = solve_contour(&loop_, branch.flipped())
        .map_err(|e| in_group(e, "RRP dyad", "cos(phi2 - phi4)", 1.0))?;
    let [p2, slide] = s.unknowns;
    let link2 = LinkMotion {
        origin: a,
        angle: p2.value,
        omega: p2.rate,
        epsilon: p2.accel,
    };
    let b = link2.motion_of(a.p + l_ab * unit(p2.value));
    let link3 = LinkMotion {
        origin: b,
        angle: normalize(beta.value),
        omega: beta.rate,
        epsilon: beta.accel,
    };
    computed_all(
        "RRP dyad",
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
            slide.value,
            slide.rate,
            slide.accel,
        ]
        .iter(),
    )?;
    Ok(RrpState {
        b,
        link2,
        link3,
        slide,
        det: s.determinant,
    })
}
