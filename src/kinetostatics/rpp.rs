//! The RPP dyad: link 2 hinged to link 1 at A, link 3 sliding on a guide of link 4, and a
//! sliding pair between links 2 and 3 (the sine mechanism, or Scotch yoke: a block on the
//! crank pin in the slot of a yoke that slides in the frame).
//!
//! Derivation. Let u be the unit direction of link 4's guide and v that of the slide between
//! links 2 and 3, and B the point of link 3 where the slide's line through A crosses the guide
//! (any point of the guide's line would do: B is only the pole of R43's moment). Without friction each sliding pair pushes along its normal
//! only, with a line of action that need not pass through any joint (it carries a couple too):
//! R32 = R32ⁿ·v⊥ (link 3 on link 2) and R43 = R43ⁿ·u⊥ (link 4 on link 3). The hinge A carries
//! R12 through A. Link 3's force balance R43ⁿ·u⊥ − R32ⁿ·v⊥ = −F3 is a 2×2 system with
//! determinant u⊥ × (−v⊥) = −(u × v) = −sin α, α the angle from the guide to the slide; by
//! Cramer R43ⁿ = −(F3 × v⊥)/sin α and R32ⁿ = (u⊥ × F3)/sin α. It vanishes only when the slide
//! is parallel to the guide (then links 2 and 3 could slide together along the guide; no
//! working mechanism passes through this, α being a constant of the design). Link 2's force
//! balance gives R12 = −(F2 + R32). Link 2's moment about A, where R12 has none, gives the
//! moment of R32 about A: K32 = −M2(A), so R32 crosses the slide's line through A at
//! h32 = K32/R32ⁿ from A along v. Link 3's moment about B, with R23 = −R32 whose moment about B
//! is −(K32 + (A − B) × R32), gives the moment of R43 about B:
//! K43 = K32 + (A − B) × R32 − M3(B), so R43 crosses the guide's line through B at
//! h43 = K43/R43ⁿ from B along u.

use super::conditioning::{ensure_finite, Conditioning};
use crate::angle::{cross, perp};
use crate::error::{finite2, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};

const WHAT: &str = "RPP dyad";
const MEASURE: &str = "sin(alpha)";

/// An RPP dyad in Cartesian form: the hinge A, a point B on the guide, the directions of the
/// guide and of the slide between links 2 and 3, and the resultant load on each link.
///
/// # Examples
/// A Scotch yoke held still: the crank pin A = (0.1, 0.05) m carries the block 2 in the
/// vertical slot of the yoke 3, which slides along the x axis of the frame; B = (0.1, 0) is
/// where the slot crosses the axis. The yoke carries (−200, −30) N at (0.3, 0): a piston
/// force and its weight. The frame guide can only push vertically: R43 = (0, 30) N; the slot
/// only horizontally: R32 = (−200, 0) N (the yoke pushes the block back), and the pin takes
/// it: R12 = (200, 0) N. The yoke's moments about B: the load −0.2·30 = −6 N·m, the block's
/// push R23 = (200, 0) at A −0.05·200 = −10 N·m, so R43 acts 16/30 m ahead of B.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::RppDyad, Load};
/// let a = Point2::new(0.1, 0.05);
/// let r = RppDyad {
///     a,
///     b: Point2::new(0.1, 0.0),
///     guide: Vector2::new(1.0, 0.0),
///     slot: Vector2::new(0.0, 1.0),
///     load2: Load::zero(a),
///     load3: Load::force_at(Point2::new(0.3, 0.0), Vector2::new(-200.0, -30.0)),
/// }
/// .solve()?;
/// assert_relative_eq!(r.r43, Vector2::new(0.0, 30.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r32, Vector2::new(-200.0, 0.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r12, Vector2::new(200.0, 0.0), epsilon = 1e-12);
/// assert_relative_eq!(r.moment43, 16.0, epsilon = 1e-12);
/// assert_relative_eq!(r.offset43.unwrap(), 16.0 / 30.0, epsilon = 1e-12);
/// assert_eq!(r.offset32, Some(0.0)); // the block is unloaded: R32 acts through A
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppDyad {
    /// The hinge of link 2 with link 1.
    pub a: Point2<f64>,
    /// A point of link 3 on the guide, from which R43's offset is measured (the kinematic
    /// block's B: where the slide's line through A crosses the guide).
    pub b: Point2<f64>,
    /// The direction of link 4's guide, along which link 3 slides (any non-zero length).
    pub guide: Vector2<f64>,
    /// The direction of the slide between links 2 and 3 (any non-zero length, not parallel to
    /// the guide).
    pub slot: Vector2<f64>,
    /// The resultant load on link 2.
    pub load2: Load,
    /// The resultant load on link 3.
    pub load3: Load,
}

/// The reactions in the joints of an RPP dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppReactions {
    /// R12, the force of link 1 on link 2 at A, N.
    pub r12: Vector2<f64>,
    /// R32, the resultant force of link 3 on link 2 in their sliding pair, normal to the
    /// slide, N (R23 = −R32).
    pub r32: Vector2<f64>,
    /// R43, the force of link 4's guide on link 3, normal to the guide, N.
    pub r43: Vector2<f64>,
    /// R32 as an algebraic value along the slide's direction turned +90°, N.
    pub r32_n: f64,
    /// R43 as an algebraic value along the guide's direction turned +90°, N.
    pub r43_n: f64,
    /// The moment of R32 about A, N·m: −M2(A).
    pub moment32: f64,
    /// The moment of R43 about B, N·m.
    pub moment43: f64,
    /// h32: where R32's line of action crosses the slide's line through A, measured from A
    /// along the slide's direction, m. `None` when R32 = 0 and the pair carries a pure couple
    /// (`moment32`).
    pub offset32: Option<f64>,
    /// h43: where R43's line of action crosses the guide's line through B, measured from B
    /// along the guide's direction, m. `None` when R43 = 0 and the guide carries a pure couple
    /// (`moment43`).
    pub offset43: Option<f64>,
    /// The measure sin α = e(guide) × e(slot) and the amplification 1/|sin α|.
    pub conditioning: Conditioning,
}

impl RppDyad {
    /// Solves the dyad for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) for a zero direction (`|guide|`,
    ///   `|slot|`);
    /// - [`Error::Singular`](crate::Error::Singular) with `sin(alpha)` when the slide is
    ///   parallel to the guide to working precision, or when the reactions overflow there.
    #[must_use = "the reactions are the result"]
    pub fn solve(&self) -> Result<RppReactions> {
        self.validate()?;
        let u = crate::error::unit_direction("|guide|", self.guide)?;
        let v = crate::error::unit_direction("|slot|", self.slot)?;
        let (nu, nv) = (perp(u), perp(v));
        let det = cross(u, v);
        let conditioning = Conditioning::of(WHAT, MEASURE, det, 1.0)?;

        let f3 = self.load3.force;
        let r43_n = -cross(f3, nv) / det;
        let r32_n = cross(nu, f3) / det;
        let r43 = nu * r43_n;
        let r32 = nv * r32_n;
        let r12 = -(self.load2.force + r32);
        let moment32 = 0.0 - self.load2.moment_about(self.a);
        let moment43 = moment32 + cross(self.a - self.b, r32) - self.load3.moment_about(self.b);
        ensure_finite(
            WHAT,
            MEASURE,
            det,
            &[r12.x, r12.y, r32.x, r32.y, r43.x, r43.y, moment32, moment43],
        )?;
        Ok(RppReactions {
            r12,
            r32,
            r43,
            r32_n,
            r43_n,
            moment32,
            moment43,
            offset32: Some(moment32 / r32_n).filter(|h| h.is_finite()),
            offset43: Some(moment43 / r43_n).filter(|h| h.is_finite()),
            conditioning,
        })
    }

    fn validate(&self) -> Result<()> {
        finite2(["A.x", "A.y"], self.a.coords)?;
        finite2(["B.x", "B.y"], self.b.coords)?;
        finite2(["guide.x", "guide.y"], self.guide)?;
        finite2(["slot.x", "slot.y"], self.slot)?;
        self.load2.validate()?;
        self.load3.validate()
    }
}
