//! The PRP dyad (group of the 2nd class with two outer sliding pairs; the 4th kind in
//! Artobolevsky's numbering): a slider 2 on a guide of a known link 1 and a slider 3 on a
//! guide of a known link 4, hinged to each other at B. The cross-slide (two sliders pinned
//! together, each in a guide of its own) and the slotted-crank drive of a slider (a block in a
//! slot of the crank, hinged to a slider on a frame guide) are of this kind.

use super::contour::{in_group, solve_contour, Branch, LoopVector};
use super::link::LinkMotion;
use super::motion::{Motion, PointMotion};
use super::rrp::Guide;
use crate::angle::{normalize, perp, unit};
use crate::error::{Error, Result};
use nalgebra::Vector2;
use std::f64::consts::PI;

const GROUP: &str = "PRP dyad";
const MEASURE: &str = "sin(phi_g3 - phi_g2)";

/// The solved PRP dyad. Each slider translates along its guide, so it turns with the link
/// that carries the guide: its angle, ω and ε are the guide's.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpState {
    /// The hinge B of the two sliders, with its absolute velocity and acceleration.
    pub b: PointMotion,
    /// The slider 2: origin B, angle = its guide's direction φg2 in [0, 2π), with the guide's
    /// ω and ε (those of link 1).
    pub link2: LinkMotion,
    /// The slider 3: origin B, angle = its guide's direction φg3 in [0, 2π), with the guide's
    /// ω and ε (those of link 4).
    pub link3: LinkMotion,
    /// s2 = (B − G2)·e(φg2), the slider 2's coordinate along its guide, with its velocity and
    /// acceleration relative to link 1.
    pub slide2: Motion,
    /// s3 = (B − G3)·e(φg3), the slider 3's coordinate along its guide, with its velocity and
    /// acceleration relative to link 4.
    pub slide3: Motion,
    /// sin(φg3 − φg2): the conditioning of the dyad. It vanishes when the guides are
    /// parallel; velocities and accelerations grow like its inverse.
    pub det: f64,
}

impl PrpState {
    /// The velocity of the slider 2 relative to link 1 (its guide): ṡ2 along e(φg2).
    #[must_use]
    pub fn relative_velocity2(&self) -> Vector2<f64> {
        self.slide2.rate * self.link2.unit()
    }

    /// The velocity of the slider 3 relative to link 4 (its guide): ṡ3 along e(φg3).
    #[must_use]
    pub fn relative_velocity3(&self) -> Vector2<f64> {
        self.slide3.rate * self.link3.unit()
    }

    /// The Coriolis acceleration 2·ω1 × v_rel2 of the slider 2 on the turning guide of link 1
    /// (the relative velocity turned 90° in the sense of ω1, doubled and scaled by ω1).
    #[must_use]
    pub fn coriolis2(&self) -> Vector2<f64> {
        2.0 * self.link2.omega * perp(self.relative_velocity2())
    }

    /// The Coriolis acceleration 2·ω4 × v_rel3 of the slider 3 on the turning guide of link 4.
    #[must_use]
    pub fn coriolis3(&self) -> Vector2<f64> {
        2.0 * self.link3.omega * perp(self.relative_velocity3())
    }
}

/// The motion of the point at `s` along a (possibly moving) guide, sliding along it with the
/// relative rate and acceleration of `s`: transport + relative + Coriolis.
pub(crate) fn on_guide(guide: &Guide, s: Motion) -> PointMotion {
    let (g, w) = (guide.point, guide.angle);
    let u = unit(w.value);
    let n = perp(u);
    PointMotion::new(
        g.p + s.value * u,
        g.v + s.rate * u + s.value * w.rate * n,
        g.a + (s.accel - s.value * w.rate * w.rate) * u
            + (s.value * w.accel + 2.0 * s.rate * w.rate) * n,
    )
}

/// Checks that a solved slide and point are finite (finite inputs can overflow).
pub(crate) fn finite_outputs(
    p: &PointMotion,
    p_names: [&'static str; 6],
    slides: [(&Motion, [&'static str; 3]); 2],
) -> Result<()> {
    for (m, names) in slides {
        m.validate(names)?;
    }
    p.validate(p_names)
}

/// Positions, velocities and accelerations of a PRP dyad: the slider 2 on `guide2` (a line of
/// link 1) and the slider 3 on `guide3` (a line of link 4), hinged together at B.
///
/// Each guide is the line B traces on its link (offsets: see below);
/// B is where they meet, so the solution is unique and there is no assembly mode. For a
/// guide cut in a moving link use [`Guide::on_link`]: then each slide's acceleration has the
/// Coriolis part [`PrpState::coriolis2`] / [`PrpState::coriolis3`].
///
/// # The geometry in words
/// ```text
///                       g3 (a line of link 4, direction φg3)
///                      /
///          G2 ───────[2]B──────────▶ g2 (a line of link 1, direction φg2)
///                    /[3]
///                  G3
/// ```
/// Each guide is the line that the hinge B traces on the link carrying it: through a point
/// G (with that link point's motion) along a direction φg (with the link's ω and ε). B is
/// where the two lines meet, so the position is always unique: B = G2 + s2·e(φg2) =
/// G3 + s3·e(φg3). A pin B off the axis of its slot (an offset e) traces the axis shifted
/// sideways by e: give the guide through a point of that shifted line
/// ([`Guide::on_link`] at that point, with the slot's angle to the link as its offset angle).
///
/// # The formulas
/// The loop G3 → G2 → B → G3 is (G2 − G3) + s2·e(φg2) − s3·e(φg3) = 0: two unknown lengths,
/// the contour's two-lines case. With u2 = e(φg2), u3 = e(φg3) and d = G3 − G2,
/// s2 = (d × u3)/(u2 × u3) and s3 = (d × u2)/(u2 × u3), and the divisor is
/// u2 × u3 = sin(φg3 − φg2): it vanishes when the guides are parallel (the sliders could then
/// slide together along them, or not meet at all). Differentiating the loop once gives
/// ṡ2·u2 − ṡ3·u3 = −(v_G2 + s2·ω2·u2⊥) + (v_G3 + s3·ω3·u3⊥): the same matrix, so ṡ2, ṡ3 and
/// likewise s̈2, s̈3 (whose right side carries the centripetal −s·ω²·u and the Coriolis
/// 2·ṡ·ω·u⊥ of each slide on its turning guide) are two more 2×2 solves with the same
/// divisor. B's absolute motion follows on guide 2: v_B = v_G2 + s2·ω2·u2⊥ + ṡ2·u2 and
/// a_B = a_G2 + (s̈2 − s2·ω2²)·u2 + (s2·ε2 + 2·ṡ2·ω2)·u2⊥.
///
/// # Examples
/// A vertical slot of link 1 through G2 = (0.3, 0) m that translates along +x at 1 m/s, and a
/// fixed guide at 45° through the origin. B is where x = 0.3 meets y = x: B = (0.3, 0.3),
/// s2 = 0.3 m and s3 = 0.3·√2 m. B, held on y = x and carried along at v_x = 1 m/s, moves at
/// (1, 1) m/s: 1 m/s up the slot and √2 m/s along the fixed guide.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, SQRT_2};
/// use tmm::kinematics::{prp_dyad, Guide, Motion, PointMotion};
/// let slot = Guide {
///     point: PointMotion::new(Point2::new(0.3, 0.0), Vector2::new(1.0, 0.0), Vector2::zeros()),
///     angle: Motion::fixed(FRAC_PI_2),
/// };
/// let d = prp_dyad(slot, Guide::fixed(Point2::origin(), FRAC_PI_4))?;
/// assert_relative_eq!(d.b.p, Point2::new(0.3, 0.3), epsilon = 1e-15);
/// assert_relative_eq!(d.slide2.value, 0.3, epsilon = 1e-15);
/// assert_relative_eq!(d.slide3.value, 0.3 * SQRT_2, epsilon = 1e-15);
/// assert_relative_eq!(d.b.v, Vector2::new(1.0, 1.0), epsilon = 1e-15);
/// assert_relative_eq!(d.slide2.rate, 1.0, epsilon = 1e-15);
/// assert_relative_eq!(d.slide3.rate, SQRT_2, epsilon = 1e-15);
/// assert_relative_eq!(d.det, -FRAC_PI_4.sin(), epsilon = 1e-15); // sin(45° − 90°)
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite input, or naming the
///   output (`B.x`, `v_B.x`, `s2`, ...) when finite inputs overflow;
/// - [`Error::Singular`](crate::Error::Singular) with `what = "PRP dyad"` and
///   `measure = "sin(phi_g3 - phi_g2)"` when the guides are parallel (|sin| ≤
///   [`SINGULAR_DETERMINANT`](super::SINGULAR_DETERMINANT)).
///
/// The dyad is never [`Error::NotAssemblable`](crate::Error::NotAssemblable): two lines that
/// are not parallel always meet.
#[must_use = "the dyad's motion is the result"]
pub fn prp_dyad(guide2: Guide, guide3: Guide) -> Result<PrpState> {
    guide2
        .point
        .validate(["G2.x", "G2.y", "v_G2.x", "v_G2.y", "a_G2.x", "a_G2.y"])?;
    guide2
        .angle
        .validate(["phi_g2", "omega_g2", "epsilon_g2"])?;
    guide3
        .point
        .validate(["G3.x", "G3.y", "v_G3.x", "v_G3.y", "a_G3.x", "a_G3.y"])?;
    guide3
        .angle
        .validate(["phi_g3", "omega_g3", "epsilon_g3"])?;
    let (g2, g3) = (guide2.point, guide3.point);
    let w3 = guide3.angle;
    // The loop G3 → G2 → B → G3: (G2 − G3) + s2·e(φg2) + s3·e(φg3 + π) = 0.
    let loop_ = [
        LoopVector::Cartesian {
            r: g2.p - g3.p,
            v: g2.v - g3.v,
            a: g2.a - g3.a,
        },
        LoopVector::unknown_length(guide2.angle),
        LoopVector::unknown_length(Motion::new(w3.value + PI, w3.rate, w3.accel)),
    ];
    // The contour's determinant is e(φg2) × e(φg3 + π) = −sin(φg3 − φg2).
    let s = solve_contour(&loop_, Branch::Plus).map_err(|e| match e {
        Error::Singular { value, .. } => Error::Singular {
            what: GROUP,
            measure: MEASURE,
            value: -value,
        },
        other => in_group(other, GROUP, MEASURE, -1.0),
    })?;
    let [slide2, slide3] = s.unknowns;
    let b = on_guide(&guide2, slide2);
    finite_outputs(
        &b,
        ["B.x", "B.y", "v_B.x", "v_B.y", "a_B.x", "a_B.y"],
        [
            (&slide2, ["s2", "v_rel2", "a_rel2"]),
            (&slide3, ["s3", "v_rel3", "a_rel3"]),
        ],
    )?;
    let link = |w: Motion| LinkMotion {
        origin: b,
        angle: normalize(w.value),
        omega: w.rate,
        epsilon: w.accel,
    };
    Ok(PrpState {
        b,
        link2: link(guide2.angle),
        link3: link(w3),
        slide2,
        slide3,
        det: -s.determinant,
    })
}
