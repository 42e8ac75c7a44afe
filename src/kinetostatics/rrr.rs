//! The RRR dyad: the group of the 2nd class, 1st kind (seed program SR1).
//!
//! Link 2 joins A (its hinge with link 1) to B; link 3 joins C (its hinge with link 4) to B.
//! Unknown: R12 at A, R43 at C and R23 at B. Derivation (seed 000, §1.3.1, re-derived):
//! split R12 and R43 into components along the links (n, along A→B and C→B) and across them
//! (τ, turned +90°). The moment of link 2 about B contains only R12's τ part:
//! −l_AB·R12τ + M2(B) = 0, so R12τ = M2(B)/l_AB; likewise R43τ = M3(B)/l_CB. The group's force
//! balance R12ⁿ·u2 + R43ⁿ·u3 = −(R12τ·u2⊥ + R43τ·u3⊥ + F2 + F3) is a 2×2 system with
//! determinant u2 × u3 = sin(φ3 − φ2), which vanishes when A, B, C are collinear (a dead
//! point). Finally R23 = −(R43 + F3) from link 3.

use super::conditioning::{ensure_finite, finite_sum, Conditioning};
use crate::angle::{cross, perp, unit};
use crate::error::{all_finite, finite2, length, positive, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};

const WHAT: &str = "RRR dyad";
const MEASURE: &str = "sin(phi3 - phi2)";

/// An RRR dyad in Cartesian form: three hinge centres and the resultant load on each link.
///
/// # Examples
/// A symmetric dyad, A = (0, 0), B = (1, 1), C = (2, 0) m, carries 100 N straight down at B,
/// applied to link 3. Neither link carries a moment about B, so both reactions lie along the
/// links and by symmetry share the load: R12 = (50, 50) N, R43 = (−50, 50) N, and link 2, a
/// two-force member, passes R12 on to link 3: R23 = R12.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::RrrDyad, Load};
/// let b = Point2::new(1.0, 1.0);
/// let dyad = RrrDyad {
///     a: Point2::new(0.0, 0.0),
///     b,
///     c: Point2::new(2.0, 0.0),
///     load2: Load::zero(b),
///     load3: Load::force_at(b, Vector2::new(0.0, -100.0)),
/// };
/// let r = dyad.solve()?;
/// assert_relative_eq!(r.r12, Vector2::new(50.0, 50.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r43, Vector2::new(-50.0, 50.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r23, r.r12, epsilon = 1e-12);
/// assert_relative_eq!(r.conditioning.measure, 1.0, epsilon = 1e-12); // links at right angles
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SR1")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrDyad {
    /// The hinge of link 2 with link 1.
    pub a: Point2<f64>,
    /// The hinge of links 2 and 3.
    pub b: Point2<f64>,
    /// The hinge of link 3 with link 4 (often the frame).
    pub c: Point2<f64>,
    /// The resultant load on link 2 (external plus inertia).
    pub load2: Load,
    /// The resultant load on link 3 (external plus inertia).
    pub load3: Load,
}

/// The reactions in the joints of an RRR dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrReactions {
    /// R12, the force of link 1 on link 2 at A, N.
    pub r12: Vector2<f64>,
    /// R43, the force of link 4 on link 3 at C, N.
    pub r43: Vector2<f64>,
    /// R23, the force of link 2 on link 3 at B, N (R32 = −R23).
    pub r23: Vector2<f64>,
    /// R12's algebraic component along A→B (the seeds' R12ⁿ), N.
    pub r12_n: f64,
    /// R12's algebraic component along A→B turned +90° (the seeds' R12τ), N.
    pub r12_t: f64,
    /// R43's algebraic component along C→B (the seeds' R43ⁿ), N.
    pub r43_n: f64,
    /// R43's algebraic component along C→B turned +90° (the seeds' R43τ), N.
    pub r43_t: f64,
    /// The measure sin(φ3 − φ2) and the amplification 1/|sin(φ3 − φ2)|.
    pub conditioning: Conditioning,
}

impl RrrDyad {
    /// Solves the dyad for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) when A = B or C = B (`l_AB`, `l_CB`);
    /// - [`Error::Singular`](crate::Error::Singular) with `sin(phi3 - phi2)` when A, B and C are
    ///   collinear to working precision (a dead point: the normal components are indeterminate).
    #[inline]
    pub fn solve(&self) -> Result<RrrReactions> {
        match self.fast() {
            Some(r) => Ok(r),
            None => self.solve_checked(),
        }
    }

    /// The closed form on the link vectors as they are (not unit vectors), with every check
    /// folded into one test at the end: R12 = n·AB + t·AB⊥ with t = M2(B)/|AB|², likewise
    /// R43 along CB, and Cramer's rule on AB × CB, so that the reactions wait for no square
    /// root; the lengths only scale the components and the conditioning. `None` wherever
    /// [`solve_checked`](Self::solve_checked) fails, and near its thresholds, so that it
    /// decides there and names the cause.
    #[inline(always)]
    fn fast(&self) -> Option<RrrReactions> {
        let ab = self.b - self.a;
        let cb = self.b - self.c;
        let (q2, q3) = (ab.norm_squared(), cb.norm_squared());
        // Pairs of divisions and of square roots, written so that each pair is one vector
        // instruction: the divider is what limits a batch of dyads.
        let q = Vector2::new(q2, q3);
        let i_q = Vector2::repeat(1.0).component_div(&q);
        let t = Vector2::new(
            self.load2.moment_about(self.b),
            self.load3.moment_about(self.b),
        )
        .component_mul(&i_q);
        let (t2, t3) = (t.x, t.y);
        let w = perp(ab) * t2 + perp(cb) * t3 + self.load2.force + self.load3.force;
        let d = cross(ab, cb);
        let i_d = 1.0 / d;
        let n2 = -cross(w, cb) * i_d;
        let n3 = -cross(ab, w) * i_d;
        let r12 = ab * n2 + perp(ab) * t2;
        let r43 = cb * n3 + perp(cb) * t3;
        let r23 = -(r43 + self.load3.force);

        let i_l = i_q.map(f64::sqrt);
        let (l2, l3) = (q2 * i_l.x, q3 * i_l.y);
        let l23 = l2 * l3;
        let det = d * (i_l.x * i_l.y);
        let (conditioning, regular) = Conditioning::fast(det, i_d * l23, 1.0);
        let (r12_n, r12_t, r43_n, r43_t) = (n2 * l2, t2 * l2, n3 * l3, t3 * l3);
        // The inputs need no test of their own: a non-finite coordinate makes |AB|² or |CB|²
        // non-finite, and a non-finite load makes its moment about B non-finite (a product
        // with an infinite factor is infinite or NaN, and no sum makes it finite again), so
        // r12_t or r43_t, or R23 through F3.
        let ok = finite_sum([
            r12,
            r43,
            r23,
            Vector2::new(q2, q3),
            Vector2::new(d, i_d),
            Vector2::new(r12_n, r12_t),
            Vector2::new(r43_n, r43_t),
            Vector2::new(det, 0.0),
        ]) & (q2 >= f64::MIN_POSITIVE)
            & (q3 >= f64::MIN_POSITIVE)
            & regular;
        ok.then_some(RrrReactions {
            r12,
            r43,
            r23,
            r12_n,
            r12_t,
            r43_n,
            r43_t,
            conditioning,
        })
    }

    /// The closed form checked step by step, naming what fails.
    #[cold]
    #[inline(never)]
    fn solve_checked(&self) -> Result<RrrReactions> {
        self.validate()?;
        let ab = self.b - self.a;
        let cb = self.b - self.c;
        let l2 = length("l_AB", ab)?;
        let l3 = length("l_CB", cb)?;
        let (u2, u3) = (ab / l2, cb / l3);
        let det = cross(u2, u3);
        let conditioning = Conditioning::of(WHAT, MEASURE, det, 1.0)?;

        let r12_t = self.load2.moment_about(self.b) / l2;
        let r43_t = self.load3.moment_about(self.b) / l3;
        let w = perp(u2) * r12_t + perp(u3) * r43_t + self.load2.force + self.load3.force;
        let r12_n = -cross(w, u3) / det;
        let r43_n = -cross(u2, w) / det;

        let r12 = u2 * r12_n + perp(u2) * r12_t;
        let r43 = u3 * r43_n + perp(u3) * r43_t;
        let r23 = -(r43 + self.load3.force);
        ensure_finite(
            WHAT,
            MEASURE,
            det,
            &[
                r12.x, r12.y, r43.x, r43.y, r23.x, r23.y, r12_n, r12_t, r43_n, r43_t,
            ],
        )?;
        Ok(RrrReactions {
            r12,
            r43,
            r23,
            r12_n,
            r12_t,
            r43_n,
            r43_t,
            conditioning,
        })
    }

    fn validate(&self) -> Result<()> {
        finite2(["A.x", "A.y"], self.a.coords)?;
        finite2(["B.x", "B.y"], self.b.coords)?;
        finite2(["C.x", "C.y"], self.c.coords)?;
        self.load2.validate()?;
        self.load3.validate()
    }
}

/// An RRR dyad in the seeds' notation (program SR1): link lengths, direction angles, and loads
/// as magnitudes with direction angles.
///
/// φ2 is the direction of the vector AB and φ3 that of CB. The centres of mass lie on the
/// links at the distances l_BS2 and l_BS3 from B (docs/errata.md#e1). F2 and F3 act at S2 and S3; M2
/// and M3 are algebraic, counter-clockwise positive. All angles in radians, lengths in m.
///
/// # Examples
/// l_BA = 0.3 m, l_BC = 0.4 m, φ2 = 30°, φ3 = 120°, a 200 N force at S2 (l_BS2 = 0.15 m)
/// along γ2 = 270° and nothing on link 3. By hand, (1.5): R12τ = F2·l_BS2·sin(φ2 − γ2)/l_BA =
/// 200·0.15·sin(−240°)/0.3 = 86.60 N. Link 3 carries no load, so it is a two-force member:
/// R43τ = 0, and R43 lies along CB.
/// ```
/// use approx::assert_relative_eq;
/// use tmm::kinetostatics::RrrSeed;
/// let r = RrrSeed {
///     l_ba: 0.3, l_bs2: 0.15, l_bc: 0.4, l_bs3: 0.2,
///     phi2: 30f64.to_radians(), phi3: 120f64.to_radians(),
///     f2: 200.0, gamma2: 270f64.to_radians(), f3: 0.0, gamma3: 0.0, m2: 0.0, m3: 0.0,
/// }
/// .solve()?;
/// assert_relative_eq!(r.r12_t, 86.6025, epsilon = 1e-4);
/// assert_relative_eq!(r.r43_t, 0.0, epsilon = 1e-12);
/// // The force balance (1.9): with φ3 − φ2 = 90° the normal parts are plain projections of
/// // −(F2 + R12τ) = (43.30, 125) N on u2 = (cos 30°, sin 30°) and u3 = (cos 120°, sin 120°).
/// assert_relative_eq!(r.r12_n, 100.0, epsilon = 1e-10);
/// assert_relative_eq!(r.r43_n, 86.6025, epsilon = 1e-4);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SR1")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrSeed {
    /// l_BA, the length of link 2, m.
    pub l_ba: f64,
    /// l_BS2, the distance of S2 from B along link 2, m.
    pub l_bs2: f64,
    /// l_BC, the length of link 3, m.
    pub l_bc: f64,
    /// l_BS3, the distance of S3 from B along link 3, m.
    pub l_bs3: f64,
    /// φ2, the direction angle of the vector AB, rad.
    pub phi2: f64,
    /// φ3, the direction angle of the vector CB, rad.
    pub phi3: f64,
    /// F2, the magnitude of the resultant force on link 2 (at S2), N.
    pub f2: f64,
    /// γ2, its direction angle, rad.
    pub gamma2: f64,
    /// F3, the magnitude of the resultant force on link 3 (at S3), N.
    pub f3: f64,
    /// γ3, its direction angle, rad.
    pub gamma3: f64,
    /// M2, the resultant moment on link 2, N·m.
    pub m2: f64,
    /// M3, the resultant moment on link 3, N·m.
    pub m3: f64,
}

impl RrrSeed {
    /// The same dyad in Cartesian form, with B at the origin (reactions do not depend on where
    /// the dyad stands).
    ///
    /// # Errors
    /// Non-finite numbers, or non-positive link lengths.
    pub fn to_dyad(&self) -> Result<RrrDyad> {
        positive("l_BA", self.l_ba)?;
        positive("l_BC", self.l_bc)?;
        all_finite(&[
            ("l_BS2", self.l_bs2),
            ("l_BS3", self.l_bs3),
            ("phi2", self.phi2),
            ("phi3", self.phi3),
            ("F2", self.f2),
            ("gamma2", self.gamma2),
            ("F3", self.f3),
            ("gamma3", self.gamma3),
            ("M2", self.m2),
            ("M3", self.m3),
        ])?;
        let b = Point2::origin();
        let (u2, u3) = (unit(self.phi2), unit(self.phi3));
        Ok(RrrDyad {
            a: b - u2 * self.l_ba,
            b,
            c: b - u3 * self.l_bc,
            load2: Load::polar(b - u2 * self.l_bs2, self.f2, self.gamma2, self.m2),
            load3: Load::polar(b - u3 * self.l_bs3, self.f3, self.gamma3, self.m3),
        })
    }

    /// Solves the dyad; see [`RrrDyad::solve`].
    ///
    /// # Errors
    /// As [`RrrSeed::to_dyad`] and [`RrrDyad::solve`].
    pub fn solve(&self) -> Result<RrrReactions> {
        self.to_dyad()?.solve()
    }
}
