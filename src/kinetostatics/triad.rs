//! The triad: the Assur group of the 3rd class with revolute joints.
//!
//! A ternary link T with the joints B1, B2, B3 is held by three binary links A_i B_i to known
//! joints A_i. Unknown: R_Ai, the force of the outer link on binary link i at A_i, and R_Bi,
//! the force of binary link i on the ternary link at B_i (twelve scalars; four links, twelve
//! equations). Derivation, as for the RRR dyad: split R_Ai into components along the link
//! (n, along A_i → B_i, unit vector u_i) and across it (τ, turned +90°). The moment of binary
//! link i about B_i contains only the τ part: −l_i·R_Aiτ + M_i(B_i) = 0, so
//! R_Aiτ = M_i(B_i)/l_i. The binary link's force balance gives R_Bi = R_Ai + F_i. The ternary
//! link's force balance and its moment about B1 are then three linear equations in the three
//! normal components:
//!
//! Σ n_i·u_i = −(F_T + Σ q_i),  Σ n_i·(r_i × u_i) = −(M_T(B1) + Σ r_i × q_i),
//!
//! with q_i = R_Aiτ·u_i⊥ + F_i and r_i = B_i − B1. Its matrix is the transpose of the triad's
//! velocity system K (rows (u_i, r_i × u_i), see
//! [`triad_rates`](crate::kinematics::triad_rates)): the same determinant, which vanishes when
//! the lines of the three binary links meet at one point (or are parallel), where the normal
//! components are indeterminate.

use super::conditioning::{ensure_finite, Conditioning};
use crate::angle::{cross, perp};
use crate::error::{finite2, length, Result};
use crate::Load;
use nalgebra::{Matrix3, Point2, Vector2, Vector3};

const WHAT: &str = "triad";
const MEASURE: &str = "det(velocity system)/L_T";

/// A triad in Cartesian form: the outer joints, the ternary link's joints and the resultant
/// load on each of the four links.
///
/// # Examples
/// The ternary link B1 = (−1, 0), B2 = (1, 0), B3 = (0, 1) m hangs on two vertical binary
/// links from A1 = (−1, 1) and A2 = (1, 1) and is held sideways by a horizontal one from
/// A3 = (1, 1); it carries 300 N down at its centroid (0, 1/3). The unloaded binary links are
/// two-force members; the horizontal one carries nothing, and the moment about the centroid
/// splits the weight equally between the vertical ones.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::Triad, Load};
/// let b = [Point2::new(-1.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// let a = [Point2::new(-1.0, 1.0), Point2::new(1.0, 1.0), Point2::new(1.0, 1.0)];
/// let g = Point2::new(0.0, 1.0 / 3.0);
/// let triad = Triad {
///     a,
///     b,
///     loads: [Load::zero(a[0]), Load::zero(a[1]), Load::zero(a[2])],
///     load_ternary: Load::force_at(g, Vector2::new(0.0, -300.0)),
/// };
/// let r = triad.solve()?;
/// // Unloaded binary links are two-force members: R_A = R_B, along the link.
/// for i in 0..3 {
///     assert_relative_eq!(r.r_a[i], r.r_b[i], epsilon = 1e-12);
///     assert_relative_eq!(r.r_a_t[i], 0.0, epsilon = 1e-12);
/// }
/// // The ternary link is in equilibrium: the three forces balance the load.
/// let sum = r.r_b[0] + r.r_b[1] + r.r_b[2];
/// assert_relative_eq!(sum, Vector2::new(0.0, 300.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r_b[0], Vector2::new(0.0, 150.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r_b[2], Vector2::zeros(), epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Triad {
    /// A1, A2, A3: the hinges of the binary links with the outer links.
    pub a: [Point2<f64>; 3],
    /// B1, B2, B3: the hinges of the binary links with the ternary link.
    pub b: [Point2<f64>; 3],
    /// The resultant load on each binary link A_i B_i (external plus inertia).
    pub loads: [Load; 3],
    /// The resultant load on the ternary link (external plus inertia).
    pub load_ternary: Load,
}

/// The reactions in the joints of a triad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadReactions {
    /// R_Ai, the force of the outer link on binary link i at A_i, N.
    pub r_a: [Vector2<f64>; 3],
    /// R_Bi, the force of binary link i on the ternary link at B_i, N (the ternary link
    /// pushes back with −R_Bi).
    pub r_b: [Vector2<f64>; 3],
    /// R_Ai's algebraic component along A_i → B_i, N.
    pub r_a_n: [f64; 3],
    /// R_Ai's algebraic component along A_i → B_i turned +90°, N.
    pub r_a_t: [f64; 3],
    /// The measure det K / L_T (as [`TriadPose::det`](crate::kinematics::TriadPose::det)) and
    /// the amplification 1/|det K / L_T|.
    pub conditioning: Conditioning,
}

impl Triad {
    /// Solves the triad for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) when A_i = B_i (`l_AiBi`) or the
    ///   ternary link's joints coincide (`L_T`);
    /// - [`Error::Singular`](crate::Error::Singular) with `distance from a branch point/size`
    ///   when the pose lies within rounding of a branch point of the group (that distance η
    ///   ≤ [`SINGULAR_BRANCH`](crate::kinematics::SINGULAR_BRANCH): the lines of the three
    ///   binary links meet at one point, and the normal forces would carry fewer than four
    ///   digits), the same rule as the rates'
    ///   ([`triad_rates`](crate::kinematics::triad_rates)); with `det(velocity system)/L_T`
    ///   when that determinant vanishes to working precision.
    pub fn solve(&self) -> Result<TriadReactions> {
        validate(&self.a, &self.b, &self.loads, &self.load_ternary)?;
        let names = ["l_A1B1", "l_A2B2", "l_A3B3"];
        let mut u = [Vector2::zeros(); 3];
        let mut l = [0.0; 3];
        for i in 0..3 {
            let leg = self.b[i] - self.a[i];
            l[i] = length(names[i], leg)?;
            u[i] = leg / l[i];
        }
        let r = [0, 1, 2].map(|i| self.b[i] - self.b[0]);
        let size = ternary_size(&self.b);
        if size > 0.0 {
            // (A zero L_T is named by LegLines.)
            crate::kinematics::ensure_off_branch(u, r, l, size)?;
        }
        let lines = LegLines::new(WHAT, &self.b, u, r)?;

        let t = [0, 1, 2].map(|i| self.loads[i].moment_about(self.b[i]) / l[i]);
        let q = [0, 1, 2].map(|i| perp(u[i]) * t[i] + self.loads[i].force);
        let f = -(self.load_ternary.force + q[0] + q[1] + q[2]);
        let m = -(self.load_ternary.moment_about(self.b[0])
            + (0..3).map(|i| cross(r[i], q[i])).sum::<f64>());
        let n = lines.solve(f, m);
        let r_a = [0, 1, 2].map(|i| u[i] * n[i] + perp(u[i]) * t[i]);
        let r_b = [0, 1, 2].map(|i| r_a[i] + self.loads[i].force);
        let values: Vec<f64> = r_a
            .iter()
            .chain(r_b.iter())
            .flat_map(|v| [v.x, v.y])
            .chain(n)
            .chain(t)
            .collect();
        ensure_finite(WHAT, MEASURE, lines.conditioning.measure, &values)?;
        Ok(TriadReactions {
            r_a,
            r_b,
            r_a_n: n,
            r_a_t: t,
            conditioning: lines.conditioning,
        })
    }
}

/// Checks the joints and the loads of a triad (either kind).
pub(super) fn validate(
    a: &[Point2<f64>; 3],
    b: &[Point2<f64>; 3],
    loads: &[Load; 3],
    load_ternary: &Load,
) -> Result<()> {
    for i in 0..3 {
        finite2(["A.x", "A.y"], a[i].coords)?;
        finite2(["B.x", "B.y"], b[i].coords)?;
        loads[i].validate()?;
    }
    load_ternary.validate()
}

/// L_T, the root-mean-square distance of the ternary link's joints `b` from their centroid.
pub(super) fn ternary_size(b: &[Point2<f64>; 3]) -> f64 {
    let g = (b[0].coords + b[1].coords + b[2].coords) / 3.0;
    let moment: f64 = b.iter().map(|p| (p.coords - g).norm_squared()).sum();
    (moment / 3.0).sqrt()
}

/// The ternary link's equilibrium under the legs' forces, shared by the triads: leg i pushes
/// it with s_i along the unit vector u_i on a line through B1 + r_i, so the equilibrium of
/// forces and of moments about B1 is Kᵀ·s = (f, m), Kᵀ's column i being (u_i, r_i × u_i):
/// the velocity system transposed (virtual work), with its conditioning det K / L_T.
pub(super) struct LegLines {
    kt: Matrix3<f64>,
    det: f64,
    pub(super) conditioning: Conditioning,
}

impl LegLines {
    /// Kᵀ of the ternary link with the joints `b`; [`Error::NonPositive`](crate::Error) when
    /// the joints coincide (`L_T`), [`Error::Singular`](crate::Error) as [`Conditioning::of`].
    pub(super) fn new(
        what: &'static str,
        b: &[Point2<f64>; 3],
        u: [Vector2<f64>; 3],
        r: [Vector2<f64>; 3],
    ) -> Result<Self> {
        let size = length("L_T", Vector2::new(ternary_size(b), 0.0))?;
        let kt = Matrix3::from_fn(|row, i| match row {
            0 => u[i].x,
            1 => u[i].y,
            _ => cross(r[i], u[i]),
        });
        let det = kt.determinant();
        let conditioning = Conditioning::of(what, MEASURE, det / size, 1.0)?;
        Ok(Self {
            kt,
            det,
            conditioning,
        })
    }

    /// s with Kᵀ·s = (f, m), by Cramer's rule.
    pub(super) fn solve(&self, f: Vector2<f64>, m: f64) -> [f64; 3] {
        let rhs = Vector3::new(f.x, f.y, m);
        [0, 1, 2].map(|i| {
            let mut k = self.kt;
            k.set_column(i, &rhs);
            k.determinant() / self.det
        })
    }
}
