//! The seed's problem in the seed's notation: link lengths l1…l4, force magnitudes with the
//! angles α1…α4, and the reactions as normal (n) and tangential (t) components.
//!
//! The figures of the paper are lost; the geometry and the load directions follow the
//! reconstruction in docs/errata.md#passive-geometry, under which eqs. 5–11, both printed bending moments
//! and the paper's static check hold identically.

use super::force_method::{solve, Solution, Stiffness};
use super::geometry::{Geometry, Link};
use super::loads::{LinkLoad, Loads};
use crate::error::{finite, positive, Result};
use nalgebra::Vector2;

/// The seed's group with a parallel coupler, in its notation (SI units, radians).
///
/// Link 3 is a straight bar B–K–D–E inclined at α4 with the frame hinge E at its upper end,
/// BD = l3, DE = l4, K the middle of BD. Links 1 (AB, length l1) and 2 (CD, length l2) are
/// horizontal with A and C on the left. F1 acts at the middle of AB along α1 + π, F2 at the
/// middle of CD along π − α2, F3 at K along α4 + α3, and the couple M (counter-clockwise) on
/// link 3 at E.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PaperGroup {
    /// F1, N.
    pub f1: f64,
    /// F2, N.
    pub f2: f64,
    /// F3, N.
    pub f3: f64,
    /// M, N·m.
    pub m: f64,
    /// l1 = AB, m.
    pub l1: f64,
    /// l2 = CD, m.
    pub l2: f64,
    /// l3 = BD, m.
    pub l3: f64,
    /// l4 = DE, m.
    pub l4: f64,
    /// α1, rad.
    pub alpha1: f64,
    /// α2, rad.
    pub alpha2: f64,
    /// α3 (from link 3), rad.
    pub alpha3: f64,
    /// α4 (link 3 from +x), rad.
    pub alpha4: f64,
}

/// The seed's results, in its notation (N), plus the full [`Solution`].
///
/// Normal and tangential components: at A and C, n is +x and t is +y; at E, n points from E
/// into the bar (−u, u = (cos α4, sin α4)) and t is (sin α4, −cos α4).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PaperResult {
    /// X̄_AF: the x force of the frame on link 1 at A in the loaded state, N (eq. 5).
    pub x_af: f64,
    /// X̄_EF: the n component at E in the loaded state, N (eq. 6).
    pub x_ef: f64,
    /// Ȳ_EF: the t component at E in the loaded state, N (eq. 7).
    pub y_ef: f64,
    /// δ11, m/N (eq. 4).
    pub delta11: f64,
    /// Δ1F, m (eq. 4).
    pub delta1f: f64,
    /// X̄1, N (eq. 8).
    pub x1: f64,
    /// R01ⁿ = X̄_A, N (eq. 9).
    pub r01n: f64,
    /// R01ᵗ = Ȳ_A, N (eq. 9).
    pub r01t: f64,
    /// R02ⁿ = X̄_C = X̄1, N (eq. 10).
    pub r02n: f64,
    /// R02ᵗ = Ȳ_C, N, measured upward (eq. 10; the paper prints +129.9 for −129.9, see
    /// docs/errata.md#p4).
    pub r02t: f64,
    /// R03ⁿ = X̄_E, N (eq. 11).
    pub r03n: f64,
    /// R03ᵗ = Ȳ_E, N (eq. 11).
    pub r03t: f64,
    /// Everything else: the hinge forces at B and D, the diagrams.
    pub solution: Solution,
}

impl PaperGroup {
    /// The seed's numerical example: F1 = 250 N, F2 = 300 N, F3 = 200 N, M = 40 N·m,
    /// l1 = l2 = 200 mm, l3 = 100 mm, l4 = 250 mm, α1 = α2 = α4 = 60°, α3 = 75°.
    #[must_use]
    pub fn example() -> Self {
        Self {
            f1: 250.0,
            f2: 300.0,
            f3: 200.0,
            m: 40.0,
            l1: 0.2,
            l2: 0.2,
            l3: 0.1,
            l4: 0.25,
            alpha1: 60f64.to_radians(),
            alpha2: 60f64.to_radians(),
            alpha3: 75f64.to_radians(),
            alpha4: 60f64.to_radians(),
        }
    }

    /// The geometry (A, B, C, D, E).
    ///
    /// # Errors
    /// A non-finite number, or a non-positive length; [`Error::Overflow`](crate::Error::Overflow)
    /// when the lengths are too large for the points or the links' lengths to be finite.
    pub fn geometry(&self) -> Result<Geometry> {
        positive("l1", self.l1)?;
        positive("l2", self.l2)?;
        positive("l3", self.l3)?;
        positive("l4", self.l4)?;
        finite("alpha4", self.alpha4)?;
        let g = Geometry::seed(self.l1, self.l2, self.l3, self.l4, self.alpha4);
        let lengths = [Link::Ab, Link::Cd, Link::Bde].map(|k| g.length(k));
        crate::error::computed_all(
            "passive group's geometry",
            [g.a, g.b, g.c, g.d, g.e]
                .iter()
                .flat_map(|p| p.coords.iter())
                .chain(lengths.iter()),
        )?;
        Ok(g)
    }

    /// The loads.
    ///
    /// # Errors
    /// As [`PaperGroup::geometry`], or a non-finite load or angle.
    pub fn loads(&self) -> Result<Loads> {
        let g = self.geometry()?;
        for (name, v) in [
            ("F1", self.f1),
            ("F2", self.f2),
            ("F3", self.f3),
            ("M", self.m),
            ("alpha1", self.alpha1),
            ("alpha2", self.alpha2),
            ("alpha3", self.alpha3),
        ] {
            finite(name, v)?;
        }
        // docs/errata.md#passive-geometry: F1 at the middle of AB along α1 + π, F2 at the middle of CD along
        // π − α2, F3 at the middle K of BD along α4 + α3, the couple M on link 3 at E. These
        // directions make eqs. 5–11, both printed bending moments and the static check hold.
        let (a1, a2, a34) = (self.alpha1, self.alpha2, self.alpha4 + self.alpha3);
        Ok(Loads {
            f1: LinkLoad::force(0.5 * self.l1, -self.f1 * Vector2::new(a1.cos(), a1.sin())),
            f2: LinkLoad::force(0.5 * self.l2, self.f2 * Vector2::new(-a2.cos(), a2.sin())),
            f3: LinkLoad::force(0.5 * self.l3, self.f3 * Vector2::new(a34.cos(), a34.sin())),
            m: LinkLoad::couple(g.length(Link::Bde), self.m),
            per_length: [Vector2::zeros(); 3],
        })
    }

    /// Solves the seed's problem.
    ///
    /// # Examples
    /// The paper's example with the paper's model (bending only, one EI; EI = 1 N·m² so that
    /// δ11 and Δ1F read as δ11·EI and Δ1F·EI):
    /// ```
    /// use tmm::kinetostatics::passive::{PaperGroup, Stiffness};
    /// use approx::assert_abs_diff_eq;
    /// let r = PaperGroup::example().solve(&Stiffness::bending_only(1.0))?;
    /// // δ11·EI = l3²·l4²·sin²α4 / (3(l3 + l4)) (eq. 4); the paper prints 4.4645e-4 once and
    /// // uses 4.4643e-4 (docs/errata.md#p2).
    /// assert_abs_diff_eq!(r.delta11, 4.4643e-4, epsilon = 1e-8);
    /// assert_abs_diff_eq!(r.x_af, 282.45, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.y_ef, 197.56, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.x_ef, 74.24, epsilon = 0.005);
    /// // The paper prints Δ1F·EI = 0.02796, X1 = −62.6 N and R01n = 327.2 N: it rounded
    /// // Y_EF to 197.5 before forming M_z(D) = Y_EF·l4 − M, a difference that cancels most of
    /// // its digits (docs/errata.md#p5). With exact intermediates:
    /// assert_abs_diff_eq!(r.delta1f, 0.02787, epsilon = 5e-6);
    /// assert_abs_diff_eq!(r.x1, -62.43, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.r01n, 327.04, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.r01t, 108.25, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.r02n, r.x1, epsilon = 1e-12);
    /// // Measured upward, Y_C points down: the paper's +129.9 is its magnitude (docs/errata.md#p4).
    /// assert_abs_diff_eq!(r.r02t, -129.90, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.r03n, 65.32, epsilon = 0.005);
    /// assert_abs_diff_eq!(r.r03t, 213.00, epsilon = 0.005);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`solve`].
    pub fn solve(&self, stiffness: &Stiffness) -> Result<PaperResult> {
        let g = self.geometry()?;
        let loads = self.loads()?;
        let s = solve(&g, &loads, stiffness)?;
        let u = Vector2::new(self.alpha4.cos(), self.alpha4.sin());
        let en = -u;
        let et = Vector2::new(self.alpha4.sin(), -self.alpha4.cos());
        let r = &s.reactions;
        crate::error::computed_all(
            "passive group's table values",
            [
                s.loaded.r01.x,
                s.loaded.r03.dot(&en),
                s.loaded.r03.dot(&et),
                r.r03.dot(&en),
                r.r03.dot(&et),
            ]
            .iter(),
        )?;
        Ok(PaperResult {
            x_af: s.loaded.r01.x,
            x_ef: s.loaded.r03.dot(&en),
            y_ef: s.loaded.r03.dot(&et),
            delta11: s.delta11.total(),
            delta1f: s.delta1f.total(),
            x1: s.x1,
            r01n: r.r01.x,
            r01t: r.r01.y,
            r02n: r.r02.x,
            r02t: r.r02.y,
            r03n: r.r03.dot(&en),
            r03t: r.r03.dot(&et),
            solution: s,
        })
    }
}
