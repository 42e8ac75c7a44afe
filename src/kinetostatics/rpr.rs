//! The RPR dyad: the group of the 2nd class, 3rd kind (seed program SR3): a rod (or piston
//! with its rod) 2 hinged to link 1 at A slides in a cylinder (or slotted link) 3 hinged to
//! link 4 at E. The two links turn together; the sliding axis has the unit direction u.
//!
//! Derivation (seed 000, §1.3.3, re-derived; docs/errata.md#e3, #e4, #e5, #n6, #n7). Without friction the
//! sliding pair carries no force along u: R32 = R32ⁿ·u⊥, at an unknown arm h32 from A along
//! the axis. Link 2's force balance along u gives at once R12 · u = −F2 · u. Write
//! A − E = a·u + b·u⊥; the whole group's moment about E, a·R12τ − b·R12ⁿ + M2(E) + M3(E) = 0,
//! gives R12τ, dividing by a = −l_EA (l_EA = (E − A)·u, which is the distance EA when the axis
//! passes through E, as in the seed). So the group is singular when l_EA = 0. Link 2's force
//! balance across u gives R32ⁿ = −F2 · u⊥ − R12τ, its moment about A gives the couple of R32
//! about A, h32·R32ⁿ = −M2(A), and the cylinder's force balance gives R43 = R32 − F3.
//!
//! The seed's 1.35 misprints γ2 for γ3 in the moment of F3 (docs/errata.md#e4); the derivation above
//! does not use it.

use super::conditioning::{ensure_finite, finite_sum, Conditioning};
use crate::angle::{perp, unit};
use crate::error::{all_finite, finite2, length, positive, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};

const WHAT: &str = "RPR dyad";
const MEASURE: &str = "l_EA";

/// An RPR dyad in Cartesian form: the hinge A of the rod, the pivot E of the cylinder, the
/// direction of the sliding axis, and the resultant load on each link.
///
/// # Examples
/// A hydraulic cylinder pivoted at E = (0, 0) pushes a lever at A = (−0.5, 0) m; the axis
/// points from A to E, u = (1, 0). The rod carries a 300 N weight at S2 = (−0.35, 0) and the
/// cylinder nothing. Moments about E: the weight turns the group by (−0.35)·(−300) = +105 N·m,
/// so R12's arm 0.5 m needs −0.5·R12y = −105, R12 = (0, 210) N. The cylinder takes the other
/// 90 N, R32 = (0, 90) N, and the rod's moment about A, 0.15·300 = 45 N·m, puts it at
/// h32 = 45/90 = 0.5 m from A, that is, at E. The cylinder passes it on: R43 = R32.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::RprDyad, Load};
/// let r = RprDyad {
///     a: Point2::new(-0.5, 0.0),
///     e: Point2::new(0.0, 0.0),
///     axis: Vector2::new(1.0, 0.0),
///     load2: Load::force_at(Point2::new(-0.35, 0.0), Vector2::new(0.0, -300.0)),
///     load3: Load::zero(Point2::new(0.0, 0.0)),
/// }
/// .solve()?;
/// assert_relative_eq!(r.r12, Vector2::new(0.0, 210.0), epsilon = 1e-9);
/// assert_relative_eq!(r.r32, Vector2::new(0.0, 90.0), epsilon = 1e-9);
/// assert_relative_eq!(r.arm.unwrap(), 0.5, epsilon = 1e-12);
/// assert_relative_eq!(r.r43, r.r32, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SR3")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprDyad {
    /// The hinge of the rod 2 with link 1.
    pub a: Point2<f64>,
    /// The pivot of the cylinder 3 on link 4 (often the frame).
    pub e: Point2<f64>,
    /// The direction of the sliding axis (any non-zero length). In the seed it points from A
    /// towards E (φ2).
    pub axis: Vector2<f64>,
    /// The resultant load on the rod 2.
    pub load2: Load,
    /// The resultant load on the cylinder 3.
    pub load3: Load,
}

/// The reactions in the joints of an RPR dyad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprReactions {
    /// R12, the force of link 1 on the rod at A, N.
    pub r12: Vector2<f64>,
    /// R32, the resultant force of the cylinder on the rod, normal to the axis, N
    /// (R23 = −R32).
    pub r32: Vector2<f64>,
    /// R43, the force of link 4 on the cylinder at E, N.
    pub r43: Vector2<f64>,
    /// R12's algebraic component along the axis (R12ⁿ), N.
    pub r12_n: f64,
    /// R12's algebraic component across the axis, the axis turned +90° (R12τ), N.
    pub r12_t: f64,
    /// R32 as an algebraic value along the axis turned +90° (the seeds' R32), N.
    pub r32_n: f64,
    /// The moment of R32 about A, N·m (= h32·R32ⁿ = −M2(A)).
    pub couple: f64,
    /// h32: where R32's line of action crosses the axis, measured from A along the axis, m.
    /// `None` when R32 = 0 and the sliding pair carries a pure couple (docs/errata.md#n7).
    pub arm: Option<f64>,
    /// The measure l_EA (m) and the amplification ρ/|l_EA|, with ρ the largest distance of A
    /// and of the loads' points from E.
    pub conditioning: Conditioning,
}

/// The larger of two numbers that are not NaN (either when one is: see its use).
#[inline(always)]
fn wider(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

impl RprDyad {
    /// Solves the dyad for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) for a zero axis direction (`|axis|`);
    /// - [`Error::Singular`](crate::Error::Singular) with `l_EA` when A lies on the normal to
    ///   the axis through E, to working precision (for an axis through E: A at E).
    #[inline]
    pub fn solve(&self) -> Result<RprReactions> {
        match self.fast() {
            Some(r) => Ok(r),
            None => self.solve_checked(),
        }
    }

    /// The closed form on the axis vector as it is (not a unit vector): R12 = p·a + q·a⊥
    /// with p = −F2·a/|a|² and q from the group's moment about E, with every check folded
    /// into one test at the end (as [`RrrDyad`](super::RrrDyad)'s): `None` wherever
    /// [`solve_checked`](Self::solve_checked) fails, and near its thresholds, so that it
    /// decides there and names the cause.
    #[inline(always)]
    fn fast(&self) -> Option<RprReactions> {
        let (u, n) = (self.axis, perp(self.axis));
        let qa = u.norm_squared();
        let ea = self.a - self.e;
        let (along, across) = (ea.dot(&u), ea.dot(&n));
        // ρ², the largest squared distance from E, by plain comparisons: a NaN among them
        // comes from a non-finite point, which the test at the end rejects anyway (through a
        // moment or `along`), so `f64::max`'s care for NaN would only cost instructions.
        let rho_sq = wider(
            wider(
                (self.load2.point - self.e).norm_squared(),
                (self.load3.point - self.e).norm_squared(),
            ),
            ea.norm_squared(),
        );
        // 1/|axis|² and 1/along as one pair of divisions, |axis| and ρ as one pair of square
        // roots (one vector instruction each), both straight from the inputs so that neither
        // waits for the other; 1/|axis| is then one product.
        let inv = Vector2::repeat(1.0).component_div(&Vector2::new(qa, along));
        let (i_qa, i_along) = (inv.x, inv.y);
        let roots = Vector2::new(qa, rho_sq).map(f64::sqrt);
        let (la, rho) = (roots.x, roots.y);
        let f2 = self.load2.force;
        let m_e = self.load2.moment_about(self.e) + self.load3.moment_about(self.e);
        let p = -f2.dot(&u) * i_qa;
        let q = (across * p - m_e) * i_along;
        let k = -f2.dot(&n) * i_qa - q;
        let r12 = u * p + n * q;
        let r32 = n * k;
        let r43 = r32 - self.load3.force;
        let couple = 0.0 - self.load2.moment_about(self.a);

        let l_ea = -along * (la * i_qa);
        let (conditioning, regular) = Conditioning::fast(l_ea, la * i_along, rho);
        let (r12_n, r12_t, r32_n) = (p * la, q * la, k * la);
        // The inputs need no test of their own: a non-finite axis makes |axis|² non-finite,
        // a non-finite A or E (with a finite axis) the projection `along`, and a non-finite
        // load its moment about E or A (a product with an infinite factor is infinite or NaN,
        // and no sum makes it finite again), so r12_t or the couple, or R43 through F3.
        let ok = finite_sum([
            r12,
            r32,
            r43,
            Vector2::new(qa, along),
            Vector2::new(i_along, rho),
            Vector2::new(l_ea, couple),
            Vector2::new(r12_n, r12_t),
            Vector2::new(r32_n, conditioning.condition),
        ]) & (qa >= f64::MIN_POSITIVE)
            & regular;
        ok.then(|| RprReactions {
            r12,
            r32,
            r43,
            r12_n,
            r12_t,
            r32_n,
            couple,
            arm: Some(couple / r32_n).filter(|h| h.is_finite()),
            conditioning,
        })
    }

    /// The closed form checked step by step, naming what fails.
    #[cold]
    #[inline(never)]
    fn solve_checked(&self) -> Result<RprReactions> {
        self.validate()?;
        let u = self.axis / length("|axis|", self.axis)?;
        let n = perp(u);
        let ea = self.a - self.e;
        let (along, across) = (ea.dot(&u), ea.dot(&n));
        let l_ea = -along;
        let rho = [self.a, self.load2.point, self.load3.point]
            .iter()
            .map(|p| (p - self.e).norm())
            .fold(0.0, f64::max);
        crate::error::computed("distance of a point from E", rho)?;
        crate::error::computed("l_EA", l_ea)?;
        let conditioning = Conditioning::of(WHAT, MEASURE, l_ea, rho)?;

        let f2 = self.load2.force;
        let r12_n = -f2.dot(&u);
        let m_e = self.load2.moment_about(self.e) + self.load3.moment_about(self.e);
        let r12_t = (across * r12_n - m_e) / along;
        let r32_n = -f2.dot(&n) - r12_t;

        let r12 = u * r12_n + n * r12_t;
        let r32 = n * r32_n;
        let r43 = r32 - self.load3.force;
        let couple = 0.0 - self.load2.moment_about(self.a);
        ensure_finite(
            WHAT,
            MEASURE,
            l_ea / rho,
            &[
                r12.x, r12.y, r32.x, r32.y, r43.x, r43.y, r12_n, r12_t, r32_n, couple,
            ],
        )?;
        let arm = Some(couple / r32_n).filter(|h| h.is_finite());
        Ok(RprReactions {
            r12,
            r32,
            r43,
            r12_n,
            r12_t,
            r32_n,
            couple,
            arm,
            conditioning,
        })
    }

    fn validate(&self) -> Result<()> {
        finite2(["A.x", "A.y"], self.a.coords)?;
        finite2(["E.x", "E.y"], self.e.coords)?;
        finite2(["axis.x", "axis.y"], self.axis)?;
        self.load2.validate()?;
        self.load3.validate()
    }
}

/// An RPR dyad in the seeds' notation (program SR3): a rod of length l_AB (with its piston at
/// B) in a cylinder of length l_EC (its mouth at C), pivoted at E, with the piston at l_BC
/// inside the cylinder.
///
/// The points lie on the axis in the order A, C, B, E, so l_EA = l_AB − l_BC + l_EC (docs/errata.md#n6).
/// φ2 is the direction of the axis from A towards E. S2 lies at l_AS2 from A towards E, S3 at
/// l_ES3 from E towards A. F2, F3 act at S2, S3; M2, M3 are algebraic moments.
///
/// # Examples
/// The example of [`RprDyad`] in the seed's notation: l_AB = 0.3, l_BC = 0.1, l_EC = 0.3, so
/// l_EA = 0.5 m; φ2 = 0; F2 = 300 N along γ2 = 270° at l_AS2 = 0.15 m.
/// ```
/// use approx::assert_relative_eq;
/// use tmm::kinetostatics::RprSeed;
/// let r = RprSeed {
///     l_ab: 0.3, l_ec: 0.3, l_bc: 0.1, l_as2: 0.15, l_es3: 0.1, phi2: 0.0,
///     f2: 300.0, gamma2: 270f64.to_radians(), f3: 0.0, gamma3: 0.0, m2: 0.0, m3: 0.0,
/// }
/// .solve()?;
/// // (1.35), corrected: R12τ = [F2·l_ES2·sin(φ2 − γ2) + F3·l_ES3·sin(φ2 − γ3) + M2 + M3]/l_EA
/// //                         = 300·0.35·sin(−270°)/0.5 = 210 N.
/// assert_relative_eq!(r.r12_t, 210.0, epsilon = 1e-9);
/// assert_relative_eq!(r.r32_n, 90.0, epsilon = 1e-9);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SR3")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprSeed {
    /// l_AB, the length of the rod with its piston, m.
    pub l_ab: f64,
    /// l_EC, the length of the cylinder from its pivot to its mouth, m.
    pub l_ec: f64,
    /// l_BC, how far the piston is inside the cylinder, m.
    pub l_bc: f64,
    /// l_AS2, the distance of S2 from A along the rod, m.
    pub l_as2: f64,
    /// l_ES3, the distance of S3 from E along the cylinder, m.
    pub l_es3: f64,
    /// φ2, the direction angle of the axis from A towards E, rad.
    pub phi2: f64,
    /// F2, the magnitude of the resultant force on the rod (at S2), N.
    pub f2: f64,
    /// γ2, its direction angle, rad.
    pub gamma2: f64,
    /// F3, the magnitude of the resultant force on the cylinder (at S3), N.
    pub f3: f64,
    /// γ3, its direction angle, rad.
    pub gamma3: f64,
    /// M2, the resultant moment on the rod, N·m.
    pub m2: f64,
    /// M3, the resultant moment on the cylinder, N·m.
    pub m3: f64,
}

impl RprSeed {
    /// The same dyad in Cartesian form, with E at the origin.
    ///
    /// # Errors
    /// Non-finite numbers, non-positive lengths, or l_EA = l_AB − l_BC + l_EC ≤ 0;
    /// [`Error::Overflow`](crate::Error::Overflow) when l_EA, a point of the dyad or a load
    /// overflows.
    pub fn to_dyad(&self) -> Result<RprDyad> {
        positive("l_AB", self.l_ab)?;
        positive("l_EC", self.l_ec)?;
        all_finite(&[
            ("l_BC", self.l_bc),
            ("l_AS2", self.l_as2),
            ("l_ES3", self.l_es3),
            ("phi2", self.phi2),
            ("F2", self.f2),
            ("gamma2", self.gamma2),
            ("F3", self.f3),
            ("gamma3", self.gamma3),
            ("M2", self.m2),
            ("M3", self.m3),
        ])?;
        let l_ea = positive(
            "l_EA",
            crate::error::computed("l_EA", self.l_ab - self.l_bc + self.l_ec)?,
        )?;
        let e = Point2::origin();
        let u = unit(self.phi2);
        let a = e - u * l_ea;
        let dyad = RprDyad {
            a,
            e,
            axis: u,
            load2: Load::polar(a + u * self.l_as2, self.f2, self.gamma2, self.m2),
            load3: Load::polar(e - u * self.l_es3, self.f3, self.gamma3, self.m3),
        };
        for (what, load) in [
            ("RPR dyad's load on the rod", dyad.load2),
            ("RPR dyad's load on the cylinder", dyad.load3),
        ] {
            crate::error::computed_all(
                what,
                [
                    load.point.x,
                    load.point.y,
                    load.force.x,
                    load.force.y,
                    load.moment,
                ]
                .iter(),
            )?;
        }
        crate::error::computed_all("RPR dyad's joint A", dyad.a.coords.iter())?;
        Ok(dyad)
    }

    /// Solves the dyad; see [`RprDyad::solve`].
    ///
    /// # Errors
    /// As [`RprSeed::to_dyad`] and [`RprDyad::solve`].
    pub fn solve(&self) -> Result<RprReactions> {
        self.to_dyad()?.solve()
    }
}
