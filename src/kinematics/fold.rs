//! The normal form of a fold of a group of the 3rd class: where two of its assembly modes
//! merge (a branch point), its velocity system K is singular, and the closures G(x) = 0 in
//! x = (O, L_T·θ) (O the ternary link's reference point) behave along K′'s least singular
//! direction like a parabola. From it, the data's distance η from the branch point (the rule
//! that refuses rates and reactions there, [`SINGULAR_BRANCH`]) and the two modes of a fold
//! that the scan of the eliminated equation merged.
//!
//! Each leg i pushes the ternary link along one line: a unit vector w_i through the point
//! O + r_i, row i of K being (w_i, r_i × w_i). Its closure's second derivative G_i″(n, n) along
//! x(t) = (O + t·δO, θ + t·δθ) depends on the leg's kind:
//! - a hinged leg of length l (w = u along A → B, r = B − O): B moves by δB = δO + δθ·J·r and
//!   turns back by −δθ²·r, so (|B − A|)″ = (u⊥ · δB)²/l − δθ²·(u · r);
//! - a sliding leg whose guide is fixed (w = n, the guide's normal): its closure n·O − h is
//!   linear, G″ = 0;
//! - a sliding leg whose guide turns with the ternary link (w = n = d⊥, d the guide's
//!   direction, r = A − O with A the leg's hinge on its known link): the closure
//!   n(θ)·(O − A) + e has G′ = n·δO + δθ·d·r (d/dθ n = −d, d/dθ d = n) and
//!   G″ = δθ²·(n · r) − 2·δθ·(d · δO).

use crate::angle::{cross, perp};
use crate::error::{Error, Result};
use nalgebra::{Matrix3, Vector2, Vector3};

/// The name of the branch-point measure η in [`Error::Singular`] (see [`SINGULAR_BRANCH`]).
pub(super) const BRANCH_MEASURE: &str = "distance from a branch point/size";

/// At or below this η, the estimated distance of the data from the nearest branch (or dead)
/// point relative to the group's size, the rates of a group of the 3rd class (a
/// [`triad`](super::triad_rates) or a triad with a sliding pair,
/// [`slider_triad_rates`](super::slider_triad_rates)) and its reactions are
/// [`Error::Singular`]; its position is still returned.
///
/// Why a distance of the data, and why ε/(2τ) with τ = 1e-4 (ε the unit roundoff). K is the
/// Jacobian G′ of the three closures G(x) (for a hinged leg |B_i − A_i| − l_i) in
/// x = (O, L_T·θ) (scaled so that its columns are dimensionless: K′ = K·diag(1, 1, 1/L_T),
/// det K′ = μ). Near a branch point the closures have the normal form of a fold: along the
/// right singular vector n of K′'s smallest singular value σ, with m the left one and
/// κ = |m · G″(n, n)|,
/// - the fold (σ = 0) is ≈ σ/κ away in the pose, and the data are d ≈ σ²/(2κ) from it;
/// - a pose solved in floating point closes to ρ ≈ ε·s (s the size; the data themselves are
///   rounded by as much), so it is known only to δ ≈ ρ/σ along n; K changes by ≈ κ·δ over
///   that, and the rates K⁻¹·b, amplified by 1/σ, carry a relative error ≈ κ·ρ/σ² = ε·s/(2d).
///
/// So η = d/s = σ²/(2κs) ≤ ε/(2τ) means "the rates carry fewer than four digits". It holds
/// at every branch point computed in floating point, whatever its curvature: rounding puts
/// its data ≈ ε·s from the fold, η ≈ ε (≤ 11·ε seen over 2000 seeded branch points, 1e4
/// times below the threshold), where an absolute threshold on μ or σ (≈ c·√ε there, c the
/// fold's curvature ratio, spread over decades) cannot separate a branch point from a
/// regular pose near one. A regular pose whose data lie 1e-8 of the size off a branch point
/// (across the branch set) has η ≈ 1e-8 ≫ 1.1e-12 and keeps its rates (accurate to
/// ≈ ε/(2η) ≈ 1e-8). κ gains σ·|G″(n, n)| (the rates' part off n), which only makes η smaller
/// and keeps the rule where the fold degenerates (m · G″ = 0); near no fold it reduces to
/// σ ≤ ε/τ·s·|G″|, the absolute threshold of an ordinary ill-conditioned solve.
pub const SINGULAR_BRANCH: f64 = 1.1e-12;

/// How a leg holds the ternary link, for its closure's curvature (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Leg {
    /// A binary link hinged at both ends, of this length.
    Hinged(f64),
    /// A slide on a guide that does not turn with the ternary link.
    FixedLine,
    /// A slide on a guide of the ternary link.
    TurningLine,
}

/// The three legs of a posed group of the 3rd class: each leg's line (unit vector `w` through
/// O + `r`), its kind, and the ternary link's size L_T.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Legs {
    pub w: [Vector2<f64>; 3],
    pub r: [Vector2<f64>; 3],
    pub kind: [Leg; 3],
    pub lt: f64,
}

/// The fold's normal form at a pose: σ, the left singular vector m, the right one
/// n = (δO, L_T·δθ), and the closures' curvature G″(n, n).
pub(crate) struct Fold {
    pub sigma: f64,
    pub m: Vector3<f64>,
    pub d_o: Vector2<f64>,
    pub d_theta: f64,
    pub curvature: Vector3<f64>,
}

impl Fold {
    /// q = m · G″(n, n), the fold's curvature across it.
    pub fn across(&self) -> f64 {
        self.m.dot(&self.curvature)
    }
}

impl Legs {
    /// The velocity system K: row i is (w_i, r_i × w_i).
    pub fn matrix(&self) -> Matrix3<f64> {
        let (w, r) = (&self.w, &self.r);
        Matrix3::new(
            w[0].x,
            w[0].y,
            cross(r[0], w[0]),
            w[1].x,
            w[1].y,
            cross(r[1], w[1]),
            w[2].x,
            w[2].y,
            cross(r[2], w[2]),
        )
    }

    /// G″(n, n) along (δO, δθ) (module docs).
    fn curvature(&self, d_o: Vector2<f64>, d_theta: f64) -> Vector3<f64> {
        Vector3::from_fn(|i, _| {
            let (w, r) = (self.w[i], self.r[i]);
            match self.kind[i] {
                Leg::Hinged(len) => {
                    let c = perp(w).dot(&(d_o + d_theta * perp(r)));
                    c * c / len - d_theta * d_theta * w.dot(&r)
                }
                Leg::FixedLine => 0.0,
                Leg::TurningLine => {
                    let d = Vector2::new(w.y, -w.x);
                    d_theta * d_theta * w.dot(&r) - 2.0 * d_theta * d.dot(&d_o)
                }
            }
        })
    }

    /// A bound of Σ|G_i″(n, n)| over unit n = (δO, L_T·δθ) and the size s (the longest leg
    /// or arm), from the arms' lengths `rn`: |δO| ≤ 1, |δθ| ≤ 1/L_T,
    /// |δO + δθ·J·r|² ≤ 1 + |r|²/L_T² (Cauchy–Schwarz) and |δθ|·|δO| ≤ 1/(2L_T).
    #[inline]
    fn curvature_bound_and_size(&self, rn: [f64; 3]) -> (f64, f64) {
        let il = 1.0 / self.lt;
        let il2 = il * il;
        let (mut bound, mut size) = (0.0, 0.0f64);
        for (i, &ri) in rn.iter().enumerate() {
            size = size.max(ri);
            bound += match self.kind[i] {
                Leg::Hinged(len) => {
                    size = size.max(len);
                    (1.0 + ri * ri * il2) / len + ri * il2
                }
                Leg::FixedLine => 0.0,
                Leg::TurningLine => ri * il2 + il,
            };
        }
        (bound, size)
    }

    /// The size s of the posed group: its longest leg or arm, m.
    #[inline]
    pub fn size(&self) -> f64 {
        self.curvature_bound_and_size(self.r.map(|r| r.norm())).1
    }

    /// Whether η is certainly above [`SINGULAR_BRANCH`], from cheap bounds (the fast paths'
    /// test; [`eta`](Self::eta) decides otherwise), `k` being [`matrix`](Self::matrix) and
    /// `mu` = det K / L_T: σ ≥ |det K′|/(σ₁σ₂) ≥ 2μ/‖K′‖_F², κ ≤ |G″|·(1 + σ) and
    /// σ ≤ ‖K′‖_F.
    #[inline]
    pub fn surely_regular(&self, k: &Matrix3<f64>, mu: f64) -> bool {
        self.surely_regular_arms(k, mu, self.r.map(|r| r.norm()))
    }

    /// [`surely_regular`](Self::surely_regular) with the arms' lengths |r_i| given (a fast
    /// path knows them from the dimensions).
    #[inline]
    pub fn surely_regular_arms(&self, k: &Matrix3<f64>, mu: f64, arms: [f64; 3]) -> bool {
        let il2 = 1.0 / (self.lt * self.lt);
        let mut f2 = (k[(0, 2)] * k[(0, 2)] + k[(1, 2)] * k[(1, 2)] + k[(2, 2)] * k[(2, 2)]) * il2;
        for i in 0..3 {
            f2 += k[(i, 0)] * k[(i, 0)] + k[(i, 1)] * k[(i, 1)];
        }
        let sigma = 2.0 * mu.abs() / f2;
        let (bound, size) = self.curvature_bound_and_size(arms);
        sigma * sigma > 2.0 * SINGULAR_BRANCH * bound * (1.0 + f2.sqrt()) * size
    }

    /// The fold's normal form from the SVD of K′ = K·diag(1, 1, 1/L_T); `None` for a
    /// non-finite K.
    pub fn fold(&self, k: &Matrix3<f64>) -> Option<Fold> {
        let lt = self.lt;
        if !(k.iter().all(|x| x.is_finite()) && lt > 0.0) {
            return None;
        }
        let scaled = Matrix3::from_fn(|i, j| if j == 2 { k[(i, j)] / lt } else { k[(i, j)] });
        let svd = scaled.svd(true, true);
        let (u_l, v_t) = (svd.u?, svd.v_t?);
        let (j, sigma) = svd
            .singular_values
            .iter()
            .copied()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let (d_o, d_theta) = (Vector2::new(v_t[(j, 0)], v_t[(j, 1)]), v_t[(j, 2)] / lt);
        Some(Fold {
            sigma,
            m: u_l.column(j).into_owned(),
            d_o,
            d_theta,
            curvature: self.curvature(d_o, d_theta),
        })
    }

    /// η, the data's distance from the nearest branch point relative to the size:
    /// σ²/(2κs) with κ = |m · G″(n, n)| + σ·|G″(n, n)| ([`SINGULAR_BRANCH`]); NaN for a
    /// non-finite K.
    pub fn eta(&self, k: &Matrix3<f64>) -> f64 {
        let Some(f) = self.fold(k) else {
            return f64::NAN;
        };
        // κ: the fold's curvature across it (the left singular vector m), plus σ·|G″(n, n)|
        // for the part of the rates off n (which the error ρ/σ along n still turns by G″):
        // the rates' relative error is ≈ ρ·(|m·G″| + σ·|G″|)/σ², also where m·G″ vanishes.
        let kappa = f.across().abs() + f.sigma * f.curvature.norm();
        f.sigma * f.sigma / (2.0 * kappa * self.size())
    }

    /// The branch-point test, one rule for the rates and the reactions of a group of the 3rd
    /// class `what` (they solve K and Kᵀ and lose their digits alike): [`Error::Singular`]
    /// naming [`BRANCH_MEASURE`] when η ≤ [`SINGULAR_BRANCH`] (or is NaN).
    pub fn ensure_off_branch(&self, what: &'static str) -> Result<()> {
        let k = self.matrix();
        if self.surely_regular(&k, k.determinant() / self.lt) {
            return Ok(());
        }
        let eta = self.eta(&k);
        if eta.is_nan() || eta <= SINGULAR_BRANCH {
            return Err(Error::Singular {
                what,
                measure: BRANCH_MEASURE,
                value: eta,
            });
        }
        Ok(())
    }
}

/// The two steps t± along the fold's right singular direction that bring the closures `g`
/// (their values at a pose near the fold) to zero across it in the fold's normal form
/// G(x + t·n) ≈ G + σ·t·m + G″(n, n)·t²/2, i.e. t± = (−σ ± √(σ² − 2·q·(m·G)))/q with
/// q = m · G″(n, n); `None` when the model has no two real roots (the fold's other side).
pub(crate) fn split_steps(fold: &Fold, g: &Vector3<f64>) -> Option<[f64; 2]> {
    let (sigma, q) = (fold.sigma, fold.across());
    let disc = sigma * sigma - 2.0 * q * fold.m.dot(g);
    if !(disc > 0.0 && q != 0.0) {
        return None;
    }
    Some([-1.0, 1.0].map(|sign| (-sigma + sign * disc.sqrt()) / q))
}
