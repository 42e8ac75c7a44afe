//! The PRP dyad: two sliders hinged together at B, the slider 2 on a guide of link 1 and the
//! slider 3 on a guide of link 4 (the cross-slide; the block and yoke of a Scotch yoke).
//!
//! Derivation. Without friction a guide pushes on its slider along the guide's normal only:
//! R12 = R12ⁿ·ν2 and R43 = R43ⁿ·ν3, with ν2 = u2⊥ and ν3 = u3⊥ the guides' unit directions
//! turned +90°, and with lines of action that need not pass through B (a sliding pair also
//! carries a couple). The hinge B carries R23 = −R32, through B. The group's force balance
//! R12ⁿ·ν2 + R43ⁿ·ν3 = −(F2 + F3) is a 2×2 system with determinant
//! ν2 × ν3 = u2 × u3 = sin(φg3 − φg2): by Cramer, R12ⁿ = −(F × ν3)/det and
//! R43ⁿ = −(ν2 × F)/det with F = F2 + F3. It vanishes when the guides are parallel: the
//! load's component along them has nothing to balance it. Each slider's moment about B then
//! fixes where its guide's reaction acts, since R23 has no moment there: the moment of R12
//! about B is −M2(B) and that of R43 is −M3(B). A normal force R at the moment K about B
//! crosses the line through B along its guide at h = K/Rⁿ from B (the moment of Rⁿ·ν acting at
//! B + h·u is h·Rⁿ). Finally R23 = −(R43 + F3) from the slider 3.
//!
//! The guides' positions do not enter: a frictionless sliding pair takes its normal force
//! wherever the balance of moments puts it. Only the guides' directions and B do.

use super::conditioning::{ensure_finite, Conditioning};
use crate::angle::{cross, perp};
use crate::error::{finite2, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};

const WHAT: &str = "PRP dyad";
const MEASURE: &str = "sin(phi_g3 - phi_g2)";

/// A PRP dyad in Cartesian form: the hinge B of the two sliders, the directions of their
/// guides, and the resultant load on each slider.
///
/// # Examples
/// A cross-slide: the slider 2 runs along a horizontal guide of link 1, the slider 3 along a
/// vertical guide of link 4, hinged at B = (0, 0). Link 3 carries (100, −50) N through B and
/// a couple of 5 N·m. The vertical guide can only push horizontally: R43 = (−100, 0) N; the
/// horizontal guide takes the vertical part: R12 = (0, 50) N, passed on through B:
/// R23 = (0, 50) N. The couple moves R43's line of action to h43 = −M3/R43ⁿ = −5/100 m along
/// the vertical guide (its moment about B, −5 N·m, balances M3); R12 acts through B.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::PrpDyad, Load};
/// let b = Point2::origin();
/// let r = PrpDyad {
///     b,
///     guide2: Vector2::new(1.0, 0.0),
///     guide3: Vector2::new(0.0, 1.0),
///     load2: Load::zero(b),
///     load3: Load::new(b, Vector2::new(100.0, -50.0), 5.0),
/// }
/// .solve()?;
/// assert_relative_eq!(r.r43, Vector2::new(-100.0, 0.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r12, Vector2::new(0.0, 50.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r23, Vector2::new(0.0, 50.0), epsilon = 1e-12);
/// assert_eq!(r.offset12, Some(0.0));
/// assert_relative_eq!(r.offset43.unwrap(), -0.05, epsilon = 1e-15);
/// assert_relative_eq!(r.conditioning.measure, 1.0); // guides at right angles
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpDyad {
    /// The hinge of the sliders 2 and 3.
    pub b: Point2<f64>,
    /// The direction of the guide of link 1 along which the slider 2 runs (any non-zero
    /// length; the angle φg2).
    pub guide2: Vector2<f64>,
    /// The direction of the guide of link 4 along which the slider 3 runs (any non-zero
    /// length; the angle φg3).
    pub guide3: Vector2<f64>,
    /// The resultant load on the slider 2 (it may miss B and carry a moment).
    pub load2: Load,
    /// The resultant load on the slider 3 (it may miss B and carry a moment).
    pub load3: Load,
}

/// The reactions in the joints of a PRP dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpReactions {
    /// R12, the force of link 1's guide on the slider 2, normal to that guide, N.
    pub r12: Vector2<f64>,
    /// R43, the force of link 4's guide on the slider 3, normal to that guide, N.
    pub r43: Vector2<f64>,
    /// R23, the force of the slider 2 on the slider 3 at B, N (R32 = −R23).
    pub r23: Vector2<f64>,
    /// R12 as an algebraic value along guide 2's direction turned +90°, N.
    pub r12_n: f64,
    /// R43 as an algebraic value along guide 3's direction turned +90°, N.
    pub r43_n: f64,
    /// The moment of R12 about B, N·m: −M2(B). Non-zero when the slider 2's load misses B.
    pub moment12: f64,
    /// The moment of R43 about B, N·m: −M3(B).
    pub moment43: f64,
    /// h12: where R12's line of action crosses the line through B along guide 2, measured
    /// from B along guide 2's direction, m. `None` when R12 = 0 and guide 2 carries a pure
    /// couple (`moment12`).
    pub offset12: Option<f64>,
    /// h43: where R43's line of action crosses the line through B along guide 3, measured
    /// from B along guide 3's direction, m. `None` when R43 = 0 and guide 3 carries a pure
    /// couple (`moment43`).
    pub offset43: Option<f64>,
    /// The measure sin(φg3 − φg2) and the amplification 1/|sin(φg3 − φg2)|.
    pub conditioning: Conditioning,
}

impl PrpDyad {
    /// Solves the dyad for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) for a zero guide direction
    ///   (`|guide2|`, `|guide3|`);
    /// - [`Error::Singular`](crate::Error::Singular) with `sin(phi_g3 - phi_g2)` when the
    ///   guides are parallel to working precision, or when the reactions overflow there.
    #[must_use = "the reactions are the result"]
    pub fn solve(&self) -> Result<PrpReactions> {
        self.validate()?;
        let u2 = crate::error::unit_direction("|guide2|", self.guide2)?;
        let u3 = crate::error::unit_direction("|guide3|", self.guide3)?;
        let (n2, n3) = (perp(u2), perp(u3));
        let det = cross(u2, u3);
        let conditioning = Conditioning::of(WHAT, MEASURE, det, 1.0)?;

        let f = self.load2.force + self.load3.force;
        let r12_n = -cross(f, n3) / det;
        let r43_n = -cross(n2, f) / det;
        let r12 = n2 * r12_n;
        let r43 = n3 * r43_n;
        let r23 = -(r43 + self.load3.force);
        let moment12 = 0.0 - self.load2.moment_about(self.b);
        let moment43 = 0.0 - self.load3.moment_about(self.b);
        ensure_finite(
            WHAT,
            MEASURE,
            det,
            &[r12.x, r12.y, r43.x, r43.y, r23.x, r23.y, moment12, moment43],
        )?;
        Ok(PrpReactions {
            r12,
            r43,
            r23,
            r12_n,
            r43_n,
            moment12,
            moment43,
            offset12: Some(moment12 / r12_n).filter(|h| h.is_finite()),
            offset43: Some(moment43 / r43_n).filter(|h| h.is_finite()),
            conditioning,
        })
    }

    fn validate(&self) -> Result<()> {
        finite2(["B.x", "B.y"], self.b.coords)?;
        finite2(["guide2.x", "guide2.y"], self.guide2)?;
        finite2(["guide3.x", "guide3.y"], self.guide3)?;
        self.load2.validate()?;
        self.load3.validate()
    }
}
