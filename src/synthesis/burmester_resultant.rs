#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Burmester's points of five poses by elimination: every candidate circle point is a root of
//! one polynomial in one unknown, so none can be stepped over (the points are then polished in
//! `pose_newton`).
//!
//! The equations. A dyad (centre point G, circle point z in pose 1) fits the poses when its
//! four difference-quotient equations hold (`PoseEquations::pencil`): B(z)·(G, 1)ᵀ = 0, B a
//! 4×3 matrix whose entries are affine in z (the |z|² terms cancel). For a given z these are
//! four lines in G (the perpendicular bisectors of z's positions); a Burmester point is a z
//! where they meet, rank B(z) ≤ 2, G spanning the null space.
//!
//! The count. Homogenised (z = (x : y : w)), B is a 4×3 matrix of linear forms on the plane;
//! its rank-≤2 locus is finite and of degree C(4, 2) = 6 (the Porteous count for the maximal
//! minors of an m×n matrix of linear forms, m = 4, n = 3: C(m, n − 1)). Two of the six are the
//! circular points (1 : ±i : 0): there R(α)·(1, i) = e^{−iα}(1, i), so every row's first two
//! entries (−2·(R(δ) − I)·R_i·z/s) are multiples of (1, i) and B has rank ≤ 2. So five poses
//! have at most four finite Burmester points, real or complex: a real four-bar's two dyads
//! are two of them.
//!
//! The elimination. Two 3×3 minors sharing two rows (rows a, b, c and a, b, d) are cubics
//! M₁(x, y), M₂(x, y) (z in a frame turned by a fixed angle, so that no leading coefficient
//! vanishes but on a set of measure zero). They meet in 9 points (Bézout): the 6 of the locus
//! and the 3 where rows a and b alone are dependent (spurious). The resultant in y,
//! Res_y(M₁, M₂)(x) (the 6×6 Sylvester determinant of their coefficients in y), has a root at
//! the x of each finite meeting point: its degree is 9 − 2 = 7, the circular points being the
//! meeting points at infinity ((1 : ±i : 0) projects from (0 : 1 : 0) to x = ∞), so the
//! coefficients of x⁸ and x⁹ vanish (they are computed, and found at rounding). Its
//! coefficients come from its values at 16 points on the unit circle (interpolated by a
//! discrete Fourier transform: exact for degree < 16, each value a determinant of numbers of
//! order one, the rows first orthonormalised). Its roots, all of them, are the eigenvalues
//! of the companion matrix (balanced); at each root's real part the two cubics' roots in y
//! (again eigenvalues) give the candidate circle points: real roots, near-real pairs (a
//! double root split by rounding) and complex ones alike, since Newton's method on the
//! original equations decides. The spurious points either fail to converge or converge to a
//! true point; a second elimination (another frame, minors sharing the other two rows)
//! yields every point again from different spurious companions, so one ill-placed root
//! cannot hide a point.

use super::pose_newton::PoseEquations;
use nalgebra::{Complex, DMatrix, Matrix3, Matrix4x3, Matrix6, Schur, Vector2};
use std::f64::consts::TAU;

type C = Complex<f64>;
type V = Vector2<f64>;

/// The pencil B0 + x·Bx + y·By in a frame turned by `turn` (u = R(turn)·(x, y)).
#[derive(Debug, Clone, Copy)]
struct Frame {
    b: [Matrix4x3<f64>; 3],
    turn: f64,
}

impl Frame {
    fn new(b: &[Matrix4x3<f64>; 3], turn: f64) -> Self {
        let (s, c) = turn.sin_cos();
        // u_x = c·x − s·y, u_y = s·x + c·y.
        Self {
            b: [b[0], b[1] * c + b[2] * s, b[2] * c - b[1] * s],
            turn,
        }
    }

    /// The frame's (x, y) back in the pencil's u.
    fn unturn(&self, x: f64, y: f64) -> V {
        let (s, c) = self.turn.sin_cos();
        V::new(c * x - s * y, s * x + c * y)
    }

    /// The minor of `rows` as a cubic in y at x: coefficients of y⁰..y³. By multilinearity in
    /// the rows, det(A_r + y·C_r) (A = B0 + x·Bx, C = By) sums the determinants with the rows
    /// of a subset S taken from C, each times y^|S|.
    fn cubic_in_y(&self, rows: [usize; 3], x: C) -> [C; 4] {
        let a = |r: usize, k: usize| C::new(self.b[0][(r, k)], 0.0) + x * self.b[1][(r, k)];
        let c = |r: usize, k: usize| C::new(self.b[2][(r, k)], 0.0);
        let mut out = [C::new(0.0, 0.0); 4];
        for mask in 0u32..8 {
            let m = Matrix3::from_fn(|i, k| {
                if mask >> i & 1 == 1 {
                    c(rows[i], k)
                } else {
                    a(rows[i], k)
                }
            });
            out[mask.count_ones() as usize] += m.determinant();
        }
        out
    }

    /// Res_y of the minors of `rows1` and `rows2` at x: the Sylvester determinant, and
    /// Hadamard's bound on it (the product of its rows' norms).
    fn resultant(&self, rows1: [usize; 3], rows2: [usize; 3], x: C) -> (C, f64) {
        let (f, g) = (self.cubic_in_y(rows1, x), self.cubic_in_y(rows2, x));
        let zero = C::new(0.0, 0.0);
        let m = Matrix6::from_fn(|i, k| {
            // Row i holds the coefficients (highest first) shifted right by i (mod 3).
            let (p, shift) = if i < 3 { (&f, i) } else { (&g, i - 3) };
            match k.checked_sub(shift) {
                Some(d) if d <= 3 => p[3 - d],
                _ => zero,
            }
        });
        let hadamard = m.row_iter().map(|r| r.norm()).product();
        (m.determinant(), hadamard)
    }
}

/// The number of points on the unit circle the resultant is interpolated from (a power of
/// two above its formal degree 9, so that coefficients 10..15 show the interpolation's
/// rounding).
const SAMPLES: usize = 16;

/// The coefficients (of x⁰..x¹⁵) of Res_y at unit-circle points, by the inverse DFT, and
/// the rounding noise below which they are zero (derivation): each sampled value is the
/// determinant of a 6×6 Sylvester matrix whose entries are the cubics' coefficients, sums of
/// eight 3×3 determinants of order-one numbers (a few ε each); LU's backward error (6ε of each
/// row, times the growth, small with pivoting) and the entries' own errors (≈ 48ε of each
/// row's size) perturb the determinant by at most Σ_rows δrow·(the other rows' product), i.e.
/// about 6·(6 + 48)ε ≤ 512ε of Hadamard's bound H = Π‖row‖; the DFT averages the samples
/// (no growth), so every coefficient is exact to 512ε·max H.
fn resultant_coefficients(
    frame: &Frame,
    rows1: [usize; 3],
    rows2: [usize; 3],
) -> ([C; SAMPLES], f64) {
    let n = SAMPLES as f64;
    let samples: [(C, f64); SAMPLES] = std::array::from_fn(|k| {
        frame.resultant(rows1, rows2, C::from_polar(1.0, TAU * k as f64 / n))
    });
    let noise = 512.0 * f64::EPSILON * samples.iter().map(|s| s.1).fold(0.0, f64::max);
    let coefficients = std::array::from_fn(|p| {
        samples
            .iter()
            .enumerate()
            .map(|(k, &(r, _))| r * C::from_polar(1.0, -TAU * (k * p % SAMPLES) as f64 / n))
            .sum::<C>()
            / n
    });
    (coefficients, noise)
}

/// Balances a square matrix by powers of two (Parlett and Reinsch: row and column norms made
/// alike by a diagonal similarity, which keeps the eigenvalues and lets the QR iteration find
/// the small ones next to large ones), at most 64 sweeps.
fn balance(m: &mut DMatrix<f64>) {
    let n = m.nrows();
    for _ in 0..64 {
        let mut done = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in (0..n).filter(|&j| j != i) {
                c += m[(j, i)].abs();
                r += m[(i, j)].abs();
            }
            if !(c > 0.0 && r > 0.0 && (c + r).is_finite()) {
                continue;
            }
            let (s, mut f) = (c + r, 1.0);
            while c < r / 2.0 {
                (f, c) = (2.0 * f, 4.0 * c);
            }
            while c > 2.0 * r {
                (f, c) = (0.5 * f, 0.25 * c);
            }
            if (c + r) / f < 0.95 * s {
                done = false;
                for j in 0..n {
                    m[(i, j)] /= f;
                    m[(j, i)] *= f;
                }
            }
        }
        if done {
            break;
        }
    }
}

/// The complex roots of the real polynomial Σ c_k x^k (leading zeros dropped): the
/// eigenvalues of its balanced companion matrix. Empty for a constant or a non-finite
/// polynomial, or when the QR iteration does not settle within its budget.
fn roots(c: &[f64]) -> Vec<C> {
    let Some(deg) = c.iter().rposition(|&x| x != 0.0) else {
        return Vec::new();
    };
    if deg == 0 || !c.iter().all(|x| x.is_finite()) {
        return Vec::new();
    }
    let lead = c[deg];
    let mut m = DMatrix::zeros(deg, deg);
    for k in 0..deg {
        // The first row −c_{deg−1−k}/c_deg, ones below the diagonal.
        m[(0, k)] = -c[deg - 1 - k] / lead;
        if k + 1 < deg {
            m[(k + 1, k)] = 1.0;
        }
    }
    if !m.iter().all(|x| x.is_finite()) {
        return Vec::new();
    }
    balance(&mut m);
    Schur::try_new(m, f64::EPSILON, 4000)
        .map(|s| s.complex_eigenvalues().iter().copied().collect())
        .unwrap_or_default()
}

/// The rows of the pencil (each a 9-vector of coefficients) replaced by an orthonormal basis
/// of their span (QR): an invertible mixing of the rows, so the rank-≤2 locus is the same,
/// and the minors are of order one whatever the poses' gaps. `None` when the rows are
/// dependent as functions (a continuum of dyads, or nothing to find).
fn orthonormal(b: &[Matrix4x3<f64>; 3]) -> Option<[Matrix4x3<f64>; 3]> {
    let m = nalgebra::SMatrix::<f64, 9, 4>::from_fn(|i, r| b[i / 3][(r, i % 3)]);
    let qr = m.qr();
    let diag = qr.r().diagonal();
    let largest = diag.amax();
    // Dependent to rounding: QR's backward error is a few ε of the largest column per
    // entry, over nine entries (512ε, the noise used for the resultant too).
    if !(diag.amin() > 512.0 * f64::EPSILON * largest) {
        return None;
    }
    let q = qr.q();
    Some(std::array::from_fn(|p| {
        Matrix4x3::from_fn(|r, k| q[(3 * p + k, r)])
    }))
}

/// The eliminations: (frame turn, rows of the first minor, rows of the second). The turns are
/// fixed (deterministic) and unrelated to any special angle; the two pairs of minors share
/// different rows, so their spurious meeting points differ.
const ELIMINATIONS: [(f64, [usize; 3], [usize; 3]); 2] = [
    (0.618_034, [0, 1, 2], [0, 1, 3]),
    (2.236_068, [2, 3, 0], [2, 3, 1]),
];

/// The other eliminations, tried when one of [`ELIMINATIONS`] degenerates: every pair of the
/// four minors (any two share two rows) in both frames (the other eliminating direction).
const OTHERS: [[usize; 3]; 4] = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];

/// What the elimination found.
#[derive(Debug, Clone)]
pub(super) enum Candidates {
    /// Candidate dyads (centre point, circle point in pose 1, m), to be polished: every
    /// finite point of the rank-≤2 locus is among them.
    Found(Vec<([f64; 2], [f64; 2])>),
    /// Every pair of minors, in both directions, has a resultant that vanishes identically
    /// (all its coefficients below their rounding noise): the minors share a component,
    /// which need not hold dyads (it may be complex, or at infinity), so the points are
    /// looked for another way (the caller's).
    Degenerate,
    /// The rows are dependent as functions of the circle point, and the remaining minor is
    /// not a non-zero constant: a curve of dyads (the message says which degeneracy).
    Continuum(String),
}

/// The candidate dyads of Burmester's points of the poses behind `equations` (see
/// [`Candidates`]): every finite point of the rank-≤2 locus is among the found ones (see the
/// module's derivation), with spurious ones, to be polished and sorted by the caller. A
/// candidate whose bisectors meet at infinity (a slider's) has no finite centre and is left
/// out.
///
/// Degeneracies. A resultant vanishes identically when its two cubics share a factor. Five
/// poses with only two distinct angles do this (checked: every pair of minors, both
/// directions, 10⁻⁵ of the noise or less): the edges between poses of one angle are pure
/// translations, whose rows have no term in the circle point in their first two entries, and
/// every minor then shares a factor; their dyads are still finite (two at most: see the test
/// `two_angle_poses`). A pure translation makes the rows dependent as functions (each row is
/// Δ_r ⊗ (…) plus a constant): every minor is the constant det[Δ_r, Δ_r·σ_r] of three
/// rows, zero exactly when the five points lie on one circle, and then every coupler point is
/// a circle point (a continuum: the parallelogram's dyads); otherwise no finite dyad fits.
pub(super) fn candidates(equations: &PoseEquations) -> Candidates {
    let (origin, size, pencil) = equations.pencil();
    if !pencil.iter().all(|m| m.iter().all(|x| x.is_finite())) {
        return Candidates::Found(Vec::new());
    }
    let Some(b) = orthonormal(&pencil) else {
        return dependent_rows(&pencil);
    };
    // The standard pair of eliminations; where one degenerates, every other pair and
    // direction, until two have given candidates (so that one ill-placed root cannot hide a
    // point, as in the module's derivation).
    let standard = ELIMINATIONS.map(|(turn, rows1, rows2)| (turn, rows1, rows2));
    let mut others = Vec::new();
    for turn in [ELIMINATIONS[0].0, ELIMINATIONS[1].0] {
        for (i, &rows1) in OTHERS.iter().enumerate() {
            for &rows2 in &OTHERS[i + 1..] {
                others.push((turn, rows1, rows2));
            }
        }
    }
    let mut out = Vec::new();
    let mut used = 0;
    for (turn, rows1, rows2) in standard.into_iter().chain(others) {
        if used == 2 {
            break;
        }
        let frame = Frame::new(&b, turn);
        let (coefficients, noise) = resultant_coefficients(&frame, rows1, rows2);
        if coefficients.iter().all(|c| c.norm() <= noise) {
            continue;
        }
        used += 1;
        // Degree 7: x⁸ and x⁹ belong to the circular points (module docs).
        let real: Vec<f64> = coefficients[..8].iter().map(|c| c.re).collect();
        for x in roots(&real) {
            let x = x.re;
            for rows in [rows1, rows2] {
                let cubic: Vec<f64> = frame
                    .cubic_in_y(rows, C::new(x, 0.0))
                    .iter()
                    .map(|c| c.re)
                    .collect();
                for y in roots(&cubic) {
                    let u = frame.unturn(x, y.re);
                    if let Some(g) = centre(&pencil, u) {
                        out.push((
                            [origin.x + size * g.x, origin.y + size * g.y],
                            [origin.x + size * u.x, origin.y + size * u.y],
                        ));
                    }
                }
            }
        }
    }
    if used == 0 {
        Candidates::Degenerate
    } else {
        Candidates::Found(out)
    }
}

/// The rows are dependent as functions of u: B(u) has rank ≤ 3 everywhere, and rank ≤ 2
/// where the minor of the independent rows vanishes. Its four 3×3 minors are sampled at
/// points of the circles |u| = 1 and 2 (the pencil's units: the poses' size); each is zero
/// to rounding where it is below 512ε of Hadamard's bound of its rows (as for the
/// resultant). A minor that is a non-zero constant (the same value at every sample, to that
/// noise) has no zeros: no finite dyad. One that vanishes everywhere, or varies (a curve of
/// zeros), makes a continuum.
fn dependent_rows(pencil: &[Matrix4x3<f64>; 3]) -> Candidates {
    let eps = f64::EPSILON;
    let mut values = Vec::new();
    for k in 0..16 {
        let radius = if k < 8 { 1.0 } else { 2.0 };
        let u = V::new(0.0, 0.0) + radius * V::new((0.7 * k as f64).cos(), (0.7 * k as f64).sin());
        let m = pencil[0] + pencil[1] * u.x + pencil[2] * u.y;
        for rows in OTHERS {
            let minor = Matrix3::from_fn(|i, c| m[(rows[i], c)]);
            let hadamard: f64 = minor.row_iter().map(|r| r.norm()).product();
            values.push((rows, minor.determinant(), 512.0 * eps * hadamard));
        }
    }
    let all_zero = values.iter().all(|(_, d, noise)| d.abs() <= *noise);
    let constant = OTHERS.iter().all(|rows| {
        let mine: Vec<(f64, f64)> = values
            .iter()
            .filter(|v| v.0 == *rows)
            .map(|v| (v.1, v.2))
            .collect();
        mine.iter()
            .all(|(d, noise)| (d - mine[0].0).abs() <= noise + mine[0].1)
    });
    if !all_zero && constant {
        return Candidates::Found(Vec::new());
    }
    Candidates::Continuum(if all_zero {
        "the difference-quotient equations are dependent and their rank condition holds for \
         every circle point (for a pure translation: the five points lie on one circle): \
         every coupler point is a circle point, infinitely many dyads (a continuum, not a \
         finite answer)"
            .to_owned()
    } else {
        "the difference-quotient equations are dependent: their rank condition is one \
         cubic curve, so the dyads form a curve (infinitely many, not a finite answer)"
            .to_owned()
    })
}

/// The centre point (in the pencil's units) of the circle point u: the null vector of B(u)
/// (its right singular vector of least singular value) made affine; `None` when it is at
/// infinity or not finite.
fn centre(b: &[Matrix4x3<f64>; 3], u: V) -> Option<V> {
    let m = b[0] + b[1] * u.x + b[2] * u.y;
    if !m.iter().all(|x| x.is_finite()) {
        return None;
    }
    let svd = nalgebra::SVD::try_new(m, false, true, f64::EPSILON, 1000)?;
    let vt = svd.v_t?;
    let (k, _) = svd.singular_values.argmin();
    let g = vt.row(k);
    let centre = V::new(g[0] / g[2], g[1] / g[2]);
    centre.iter().all(|c| c.is_finite()).then_some(centre)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::Pose;

    /// The formal degree is 9; the coefficients of x⁸ and x⁹ vanish (the circular points),
    /// and those of x¹⁰..x¹⁵ are the interpolation's rounding: all at rounding relative to
    /// the largest, on random poses.
    #[test]
    fn the_resultant_has_degree_seven() {
        let mut x: u64 = 0x1234_5678_9ABC_DEF1;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..50 {
            let poses: [Pose; 5] =
                std::array::from_fn(|_| Pose::new([next() - 0.5, next() - 0.5], 6.0 * next()));
            let eq = PoseEquations::new(&poses);
            let (_, _, pencil) = eq.pencil();
            let b = orthonormal(&pencil).unwrap();
            for (turn, r1, r2) in ELIMINATIONS {
                let (c, _) = resultant_coefficients(&Frame::new(&b, turn), r1, r2);
                let big = c.iter().map(|c| c.norm()).fold(0.0, f64::max);
                let high = c[8..].iter().map(|c| c.norm()).fold(0.0, f64::max);
                assert!(high <= 1e-12 * big, "{high:e} of {big:e}: {c:?}");
                assert!(c[7].norm() > 1e-6 * big, "{c:?}");
            }
        }
    }

    /// Roots of a polynomial with roots of very different sizes, found by the balanced
    /// companion matrix.
    #[test]
    fn roots_of_a_product_come_back() {
        let want = [1e-3, -2.0, 0.5, 1e3];
        // (x − r1)(x − r2)(x − r3)(x − r4), lowest first.
        let mut c = vec![1.0];
        for r in want {
            let mut next = vec![0.0; c.len() + 1];
            for (k, &ck) in c.iter().enumerate() {
                next[k + 1] += ck;
                next[k] -= r * ck;
            }
            c = next;
        }
        let got = roots(&c);
        for r in want {
            assert!(
                got.iter()
                    .any(|g| (g - C::new(r, 0.0)).norm() <= 1e-12 * r.abs().max(1.0)),
                "{r} not in {got:?}"
            );
        }
    }
}
