//! The RPP dyad (group of the 2nd class with one revolute pair, the outer one; the 5th kind in
//! Artobolevsky's numbering): link 2 hinged at A to a known link 1, link 3 sliding on a guide
//! of a known link 4, and a sliding pair between links 2 and 3. The sine mechanism (Scotch
//! yoke: a block on the crank pin in the slot of a yoke that slides in the frame) and the
//! tangent mechanism are of this kind.

use super::contour::{in_group, solve_contour, Branch, LoopVector};
use super::link::LinkMotion;
use super::motion::{Motion, PointMotion};
use super::prp::{finite_outputs, on_guide};
use super::rrp::Guide;
use crate::angle::{normalize, perp};
use crate::error::{finite, Error, Result};
use nalgebra::Vector2;

const GROUP: &str = "RPP dyad";
const MEASURE: &str = "sin(alpha)";

/// The solved RPP dyad. Links 2 and 3 turn with link 4 (ω2 = ω3 = ω4).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppState {
    /// B, the point of link 3 where the slide line through A crosses the guide, with its
    /// absolute velocity and acceleration.
    pub b: PointMotion,
    /// Link 2: origin A, angle = the slide's direction φg + α in [0, 2π), with link 4's ω
    /// and ε.
    pub link2: LinkMotion,
    /// Link 3: origin B, angle = the guide's direction φg in [0, 2π), with link 4's ω and ε.
    pub link3: LinkMotion,
    /// s2 = (A − B)·e(φg + α), where A is along link 3's slide from B, with the velocity and
    /// acceleration of link 2 relative to link 3.
    pub slide2: Motion,
    /// s3 = (B − G)·e(φg), link 3's coordinate along the guide, with its velocity and
    /// acceleration relative to link 4.
    pub slide3: Motion,
    /// sin α: the conditioning of the dyad (constant; zero only for a slide parallel to the
    /// guide).
    pub det: f64,
}

impl RppState {
    /// The velocity of link 2 relative to link 3: ṡ2 along e(φg + α).
    #[must_use]
    pub fn relative_velocity2(&self) -> Vector2<f64> {
        self.slide2.rate * self.link2.unit()
    }

    /// The velocity of link 3 relative to link 4: ṡ3 along e(φg).
    #[must_use]
    pub fn relative_velocity3(&self) -> Vector2<f64> {
        self.slide3.rate * self.link3.unit()
    }

    /// The Coriolis acceleration 2·ω3 × v_rel2 of link 2's points sliding in the turning link 3.
    #[must_use]
    pub fn coriolis2(&self) -> Vector2<f64> {
        2.0 * self.link3.omega * perp(self.relative_velocity2())
    }

    /// The Coriolis acceleration 2·ω4 × v_rel3 of link 3's points sliding on the turning guide.
    #[must_use]
    pub fn coriolis3(&self) -> Vector2<f64> {
        2.0 * self.link3.omega * perp(self.relative_velocity3())
    }
}

/// Positions, velocities and accelerations of an RPP dyad: link 2 hinged at `a`, sliding in
/// link 3 along the direction that makes the angle `alpha` (rad, CCW) with `guide`, along
/// which link 3 slides on link 4.
///
/// The solution is unique (two lines meet), so there is no assembly mode; see the
/// figure and the offsets below.
///
/// # The geometry in words
/// ```text
///                  A ●   the hinge with link 1; link 2 (a block, or a slotted link) turns on it
///                    ║   the slide between links 2 and 3: direction φg + α, through A
///                    ║
///      G ────────────B═════════════▶  the guide of link 4: direction φg, through G
///                    └─ link 3 (the yoke) slides along the guide; B is a point of it
/// ```
/// The guide is the line that a point of link 3 traces on link 4: through a point G (with that
/// link-4 point's motion) along φg (with link 4's ω and ε), as a [`Guide`]. The sliding pair
/// between links 2 and 3 makes the constant angle α with the guide (α = π/2 for a Scotch
/// yoke): relative to link 3, A (a point of link 2, which only translates relative to link 3)
/// runs along the line through A with direction φg + α. Call B the point of link 3 where that
/// line crosses the guide: it is one material point of link 3, and it runs along the guide.
///
/// Neither sliding pair lets its links turn relative to each other, so links 2 and 3 both turn
/// with link 4 (ω2 = ω3 = ω4). Offsets need no parameter: a pin off the slot's axis or a slot
/// off the yoke's axis only moves B along link 3 (a reference point of link 3 at a distance d
/// from B along the guide is at s3 + d), and a guide off the line of a link is given through a
/// point of the shifted line ([`Guide::on_link`] at that point).
///
/// # The formulas
/// The loop A → G → B → A is (G − A) + s3·u + s2·v = 0 with u = e(φg), v = e(φg + α), the
/// contour's two-lines case: s3 = (d × v)/(u × v) and s2 = (u × d)/(u × v) for d = A − G. The
/// divisor is u × v = sin α, a constant of the design: the group is singular only if the slide
/// is parallel to the guide (then links 2 and 3 could slide together along it), never at some
/// position of a working mechanism. Differentiating once and twice gives the rates and the
/// accelerations through the same matrix; both directions turn at ω4, so the right sides carry
/// the centripetal −s·ω4²·e and the Coriolis 2·ṡ·ω4·e⊥ of each slide. B moves as the point at
/// s3 on the guide: v_B = v_G + s3·ω4·u⊥ + ṡ3·u, a_B = a_G + (s̈3 − s3·ω4²)·u +
/// (s3·ε4 + 2·ṡ3·ω4)·u⊥.
///
/// # Examples
/// A Scotch yoke: crank 0.1 m at φ1 = 30° turning at 10 rad/s, a yoke sliding along the x
/// axis, its slot vertical (α = 90°). The yoke follows the pin's x: s3 = r·cos φ1 and
/// ṡ3 = −r·ω1·sin φ1 = −0.5 m/s; the block rides up the slot with s2 = r·sin φ1 and
/// ṡ2 = r·ω1·cos φ1.
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use std::f64::consts::FRAC_PI_2;
/// use tmm::kinematics::{crank, rpp_dyad, Guide, Motion};
/// let phi1 = 30f64.to_radians();
/// let a = crank(Point2::origin(), 0.1, Motion::new(phi1, 10.0, 0.0))?.a;
/// let d = rpp_dyad(a, Guide::fixed(Point2::origin(), 0.0), FRAC_PI_2)?;
/// assert_relative_eq!(d.slide3.value, 0.1 * phi1.cos(), epsilon = 1e-15);
/// assert_relative_eq!(d.slide3.rate, -0.5, epsilon = 1e-14);
/// assert_relative_eq!(d.slide2.value, 0.05, epsilon = 1e-15);
/// assert_relative_eq!(d.slide2.rate, phi1.cos(), epsilon = 1e-14);
/// assert_relative_eq!(d.b.p, Point2::new(0.1 * phi1.cos(), 0.0), epsilon = 1e-15);
/// assert_eq!(d.det, 1.0);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite input, or naming the
///   output (`B.x`, `v_B.x`, `s3`, ...) when finite inputs overflow;
/// - [`Error::Singular`](crate::Error::Singular) with `what = "RPP dyad"` and
///   `measure = "sin(alpha)"` when the slide is parallel to the guide (|sin α| ≤
///   [`SINGULAR_DETERMINANT`](super::SINGULAR_DETERMINANT)).
///
/// The dyad is never [`Error::NotAssemblable`](crate::Error::NotAssemblable).
#[must_use = "the dyad's motion is the result"]
pub fn rpp_dyad(a: PointMotion, guide: Guide, alpha: f64) -> Result<RppState> {
    a.validate(["A.x", "A.y", "v_A.x", "v_A.y", "a_A.x", "a_A.y"])?;
    guide
        .point
        .validate(["G.x", "G.y", "v_G.x", "v_G.y", "a_G.x", "a_G.y"])?;
    guide.angle.validate(["phi_g", "omega_g", "epsilon_g"])?;
    finite("alpha", alpha)?;
    let (g, w) = (guide.point, guide.angle);
    let slide_dir = Motion::new(w.value + alpha, w.rate, w.accel);
    // The loop A → G → B → A: (G − A) + s3·e(φg) + s2·e(φg + α) = 0.
    let loop_ = [
        LoopVector::Cartesian {
            r: g.p - a.p,
            v: g.v - a.v,
            a: g.a - a.a,
        },
        LoopVector::unknown_length(w),
        LoopVector::unknown_length(slide_dir),
    ];
    // The contour's determinant is e(φg) × e(φg + α) = sin α.
    let s = solve_contour(&loop_, Branch::Plus).map_err(|e| match e {
        Error::Singular { value, .. } => Error::Singular {
            what: GROUP,
            measure: MEASURE,
            value,
        },
        other => in_group(other, GROUP, MEASURE, 1.0),
    })?;
    let [slide3, slide2] = s.unknowns;
    let b = on_guide(&guide, slide3);
    finite_outputs(
        &b,
        ["B.x", "B.y", "v_B.x", "v_B.y", "a_B.x", "a_B.y"],
        [
            (&slide2, ["s2", "v_rel2", "a_rel2"]),
            (&slide3, ["s3", "v_rel3", "a_rel3"]),
        ],
    )?;
    Ok(RppState {
        b,
        link2: LinkMotion {
            origin: a,
            angle: normalize(slide_dir.value),
            omega: w.rate,
            epsilon: w.accel,
        },
        link3: LinkMotion {
            origin: b,
            angle: normalize(w.value),
            omega: w.rate,
            epsilon: w.accel,
        },
        slide2,
        slide3,
        det: s.determinant,
    })
}
