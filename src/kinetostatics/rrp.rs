//! The RRP dyad: the group of the 2nd class, 2nd kind (seed program SR2): link 2 hinged to
//! link 1 at A and to the slider 3 at B; the slider moves along a guide of link 4.
//!
//! Derivation (seed 000, §1.3.2, re-derived; docs/errata.md#e2, #n3): without friction the guide pushes
//! on the slider along the guide's normal ν = g⊥ (g the guide's unit direction), with a
//! magnitude R43 and a line of action that need not pass through B. Link 2's moment about B
//! gives R12τ = M2(B)/l_AB as in the RRR dyad. The group's force balance
//! R12ⁿ·u2 + R43·ν = −(R12τ·u2⊥ + F2 + F3) is a 2×2 system with determinant
//! u2 × ν = u2 · g = cos(φ2 − φ4): it vanishes when link 2 stands perpendicular to the guide.
//! The slider's own moment about B fixes where R43 acts: its moment about B is −M3(B), so its
//! line of action lies at h43 = −M3(B)/R43 along the guide from B. The seed's h43 = 0 holds only
//! when the slider's load passes through B (N3). R23 = −(R43 + F3) from the slider.

use super::conditioning::{ensure_finite, finite_sum, Conditioning};
use crate::angle::{cross, perp, unit};
use crate::error::{all_finite, finite2, length, positive, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};

const WHAT: &str = "RRP dyad";
const MEASURE: &str = "cos(phi2 - phi4)";

/// An RRP dyad in Cartesian form: the hinges A and B, the direction of the slider's guide, and
/// the resultant load on each link.
///
/// # Examples
/// A slider-crank's connecting rod from A = (0.1, 0.1) to the piston pin B = (0.4, 0) m on a
/// horizontal guide; the gas pushes the piston with 1000 N towards −x, through B. Link 2 carries
/// no load, so it is a two-force member: R12 lies along the rod, and its x part balances the
/// gas force, R12 = (1000, −333.3) N; the guide takes the rest, R43 = (0, 333.3) N, through B.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::RrpDyad, Load};
/// let b = Point2::new(0.4, 0.0);
/// let r = RrpDyad {
///     a: Point2::new(0.1, 0.1),
///     b,
///     guide: Vector2::new(1.0, 0.0),
///     load2: Load::zero(b),
///     load3: Load::force_at(b, Vector2::new(-1000.0, 0.0)),
/// }
/// .solve()?;
/// assert_relative_eq!(r.r12, Vector2::new(1000.0, -1000.0 / 3.0), epsilon = 1e-9);
/// assert_relative_eq!(r.r43, Vector2::new(0.0, 1000.0 / 3.0), epsilon = 1e-9);
/// assert_eq!(r.offset, Some(0.0)); // through B
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SR2")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpDyad {
    /// The hinge of link 2 with link 1.
    pub a: Point2<f64>,
    /// The hinge of link 2 with the slider 3.
    pub b: Point2<f64>,
    /// The direction of the guide (any non-zero length; the seeds' angle φ4).
    pub guide: Vector2<f64>,
    /// The resultant load on link 2.
    pub load2: Load,
    /// The resultant load on the slider 3 (it may miss B and carry a moment).
    pub load3: Load,
}

/// The reactions in the joints of an RRP dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpReactions {
    /// R12, the force of link 1 on link 2 at A, N.
    pub r12: Vector2<f64>,
    /// R43, the force of the guide (link 4) on the slider, normal to the guide, N.
    pub r43: Vector2<f64>,
    /// R23, the force of link 2 on the slider at B, N (R32 = −R23).
    pub r23: Vector2<f64>,
    /// R12's algebraic component along A→B (R12ⁿ), N.
    pub r12_n: f64,
    /// R12's algebraic component along A→B turned +90° (R12τ), N.
    pub r12_t: f64,
    /// R43 as an algebraic value along the guide's direction turned +90° (the seeds' R43 along
    /// φ4 + π/2), N.
    pub r43_n: f64,
    /// The moment of R43 about B, N·m: −M3(B). Non-zero when the slider's load misses B.
    pub guide_moment: f64,
    /// h43: where R43's line of action crosses the guide line through B, measured from B along
    /// the guide direction, m. `None` when R43 = 0 and the guide carries a pure couple
    /// (`guide_moment`).
    pub offset: Option<f64>,
    /// The measure cos(φ2 − φ4) and the amplification 1/|cos(φ2 − φ4)|.
    pub conditioning: Conditioning,
}

impl RrpDyad {
    /// Solves the dyad for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) when A = B (`l_AB`) or the guide
    ///   direction is zero (`|guide|`);
    /// - [`Error::Singular`](crate::Error::Singular) with `cos(phi2 - phi4)` when link 2 is
    ///   perpendicular to the guide to working precision.
    #[inline]
    pub fn solve(&self) -> Result<RrpReactions> {
        match self.fast() {
            Some(r) => Ok(r),
            None => self.solve_checked(),
        }
    }

    /// The closed form on AB and the guide as they are (not unit vectors), with every check
    /// folded into one test at the end (as [`RrrDyad`](super::RrrDyad)'s): `None` wherever
    /// [`solve_checked`](Self::solve_checked) fails, and near its thresholds, so that it
    /// decides there and names the cause.
    #[inline(always)]
    fn fast(&self) -> Option<RrpReactions> {
        let ab = self.b - self.a;
        let g = self.guide;
        let nu = perp(g);
        let q = Vector2::new(ab.norm_squared(), g.norm_squared());
        let (q2, qg) = (q.x, q.y);
        // 1/|AB|² and 1/|guide|² as one pair of divisions, |AB| and |guide| as one pair of
        // square roots (one vector instruction each), both straight from the inputs so that
        // neither waits for the other: the inverse lengths are then one product each.
        let i_q = Vector2::repeat(1.0).component_div(&q);
        let l = q.map(f64::sqrt);
        let m2 = self.load2.moment_about(self.b);
        let f = self.load2.force + self.load3.force;
        // d = AB × ν = AB·g, likewise from the inputs alone.
        let d = ab.dot(&g);
        let i_d = 1.0 / d;
        let t2 = m2 * i_q.x;
        // With w = t2·AB⊥ + F: w × ν = t2·(AB × g) + F·g, and AB × w = t2·|AB|² + AB × F,
        // whose first term is M2(B) itself, so that R43 waits for no division but 1/d.
        let n2 = -(t2 * cross(ab, g) + f.dot(&g)) * i_d;
        let k = -(m2 + cross(ab, f)) * i_d;
        let r12 = ab * n2 + perp(ab) * t2;
        let r43 = nu * k;
        let r23 = -(r43 + self.load3.force);
        let guide_moment = 0.0 - self.load3.moment_about(self.b);

        let i_l = l.component_mul(&i_q);
        let (l2, lg) = (l.x, l.y);
        let det = d * (i_l.x * i_l.y);
        let (conditioning, regular) = Conditioning::fast(det, i_d * (l2 * lg), 1.0);
        let (r12_n, r12_t, r43_n) = (n2 * l2, t2 * l2, k * lg);
        // The inputs need no test of their own: a non-finite coordinate makes |AB|² or
        // |guide|² non-finite, and a non-finite load makes its moment about B non-finite (a
        // product with an infinite factor is infinite or NaN, and no sum makes it finite
        // again), so r12_t or the guide's moment, or R23 through F3.
        let ok = finite_sum([
            r12,
            r43,
            r23,
            Vector2::new(q2, qg),
            Vector2::new(d, i_d),
            Vector2::new(r12_n, r12_t),
            Vector2::new(r43_n, guide_moment),
            Vector2::new(det, 0.0),
        ]) & (q2 >= f64::MIN_POSITIVE)
            & (qg >= f64::MIN_POSITIVE)
            & regular;
        ok.then(|| RrpReactions {
            r12,
            r43,
            r23,
            r12_n,
            r12_t,
            r43_n,
            guide_moment,
            offset: Some(guide_moment / r43_n).filter(|h| h.is_finite()),
            conditioning,
        })
    }

    /// The closed form checked step by step, naming what fails.
    #[cold]
    #[inline(never)]
    fn solve_checked(&self) -> Result<RrpReactions> {
        self.validate()?;
        let ab = self.b - self.a;
        let l2 = length("l_AB", ab)?;
        let g = self.guide / length("|guide|", self.guide)?;
        let (u2, nu) = (ab / l2, perp(g));
        let det = cross(u2, nu);
        let conditioning = Conditioning::of(WHAT, MEASURE, det, 1.0)?;

        let r12_t = self.load2.moment_about(self.b) / l2;
        let w = perp(u2) * r12_t + self.load2.force + self.load3.force;
        let r12_n = -cross(w, nu) / det;
        let r43_n = -cross(u2, w) / det;

        let r12 = u2 * r12_n + perp(u2) * r12_t;
        let r43 = nu * r43_n;
        let r23 = -(r43 + self.load3.force);
        let guide_moment = 0.0 - self.load3.moment_about(self.b);
        ensure_finite(
            WHAT,
            MEASURE,
            det,
            &[
                r12.x,
                r12.y,
                r43.x,
                r43.y,
                r23.x,
                r23.y,
                r12_n,
                r12_t,
                r43_n,
                guide_moment,
            ],
        )?;
        let offset = Some(guide_moment / r43_n).filter(|h| h.is_finite());
        Ok(RrpReactions {
            r12,
            r43,
            r23,
            r12_n,
            r12_t,
            r43_n,
            guide_moment,
            offset,
            conditioning,
        })
    }

    fn validate(&self) -> Result<()> {
        finite2(["A.x", "A.y"], self.a.coords)?;
        finite2(["B.x", "B.y"], self.b.coords)?;
        finite2(["guide.x", "guide.y"], self.guide)?;
        self.load2.validate()?;
        self.load3.validate()
    }
}

/// An RRP dyad in the seeds' notation (program SR2).
///
/// φ2 is the direction of the vector AB, φ4 that of the guide. S2 lies on link 2 at l_BS2 from
/// B. F2 acts at S2 and F3 at B (the seed's slider load passes through B); M2 and, beyond the
/// seed, M3 are algebraic moments on links 2 and 3.
///
/// # Examples
/// l_BA = 0.25 m, φ2 = 0 (link 2 along the guide), φ4 = 0. A couple M2 = 10 N·m on link 2 must
/// be balanced by R12τ = M2/l_BA = 40 N across the link (1.24); the guide then takes the
/// vertical force, R43 = −40 N, and the slider's R43 acts through B.
/// ```
/// use approx::assert_relative_eq;
/// use tmm::kinetostatics::RrpSeed;
/// let r = RrpSeed {
///     l_ba: 0.25, l_bs2: 0.1, phi2: 0.0, phi4: 0.0,
///     f2: 0.0, gamma2: 0.0, f3: 0.0, gamma3: 0.0, m2: 10.0, m3: 0.0,
/// }
/// .solve()?;
/// assert_relative_eq!(r.r12_t, 40.0, epsilon = 1e-12);
/// assert_relative_eq!(r.r12_n, 0.0, epsilon = 1e-12);
/// assert_relative_eq!(r.r43_n, -40.0, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SR2")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpSeed {
    /// l_BA, the length of link 2, m.
    pub l_ba: f64,
    /// l_BS2, the distance of S2 from B along link 2, m.
    pub l_bs2: f64,
    /// φ2, the direction angle of the vector AB, rad.
    pub phi2: f64,
    /// φ4, the direction angle of the guide, rad.
    pub phi4: f64,
    /// F2, the magnitude of the resultant force on link 2 (at S2), N.
    pub f2: f64,
    /// γ2, its direction angle, rad.
    pub gamma2: f64,
    /// F3, the magnitude of the resultant force on the slider (through B), N.
    pub f3: f64,
    /// γ3, its direction angle, rad.
    pub gamma3: f64,
    /// M2, the resultant moment on link 2, N·m.
    pub m2: f64,
    /// M3, a moment on the slider (not in the seed; 0 there), N·m.
    pub m3: f64,
}

impl RrpSeed {
    /// The same dyad in Cartesian form, with B at the origin.
    ///
    /// # Errors
    /// Non-finite numbers, or a non-positive link length.
    pub fn to_dyad(&self) -> Result<RrpDyad> {
        positive("l_BA", self.l_ba)?;
        all_finite(&[
            ("l_BS2", self.l_bs2),
            ("phi2", self.phi2),
            ("phi4", self.phi4),
            ("F2", self.f2),
            ("gamma2", self.gamma2),
            ("F3", self.f3),
            ("gamma3", self.gamma3),
            ("M2", self.m2),
            ("M3", self.m3),
        ])?;
        let b = Point2::origin();
        let u2 = unit(self.phi2);
        Ok(RrpDyad {
            a: b - u2 * self.l_ba,
            b,
            guide: unit(self.phi4),
            load2: Load::polar(b - u2 * self.l_bs2, self.f2, self.gamma2, self.m2),
            load3: Load::polar(b, self.f3, self.gamma3, self.m3),
        })
    }

    /// Solves the dyad; see [`RrpDyad::solve`].
    ///
    /// # Errors
    /// As [`RrpSeed::to_dyad`] and [`RrpDyad::solve`].
    pub fn solve(&self) -> Result<RrpReactions> {
        self.to_dyad()?.solve()
    }
}
