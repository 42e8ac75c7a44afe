//! A square linear system in reusable buffers: LU with partial pivoting done in place, by
//! nalgebra's own elimination steps written out on the column-major storage (the same
//! pivots, the same operations in the same order, so the same bits as `DMatrix::lu` and
//! `LU::solve`: l = a·(1/d), then a ← (−u)·l + a), so that repeated solves of one size
//! allocate nothing and pay no view bookkeeping per column; and the reciprocal 1-norm
//! condition estimate of the factorised matrix (Hager's method, as LAPACK's `dlacon`).

use nalgebra::{DMatrix, DVector};

/// A square system's matrix (factorised in place), its right-hand side (then solution) and
/// the row swaps of the factorisation.
#[derive(Debug, Clone, Default)]
pub(super) struct Linear {
    pub k: DMatrix<f64>,
    pub f: DVector<f64>,
    swaps: Vec<(usize, usize)>,
    /// The caller's per-unknown-block buffer (a group's link rotations at the current
    /// iterate), kept here so one workspace serves a whole solve.
    pub rot: Vec<nalgebra::Vector2<f64>>,
    /// Work vectors of the condition estimate.
    x: DVector<f64>,
    sign: Vec<f64>,
}

impl Linear {
    /// Sizes the buffers for `n` unknowns (allocating only when the size changes).
    pub(super) fn size(&mut self, n: usize) {
        if self.k.shape() != (n, n) {
            self.k = DMatrix::zeros(n, n);
            self.f = DVector::zeros(n);
        }
    }

    /// Factorises `k` in place, as `LU::new` does.
    pub(super) fn factorise(&mut self) {
        let n = self.k.nrows();
        self.swaps.clear();
        let a = self.k.as_mut_slice();
        for i in 0..n {
            // The pivot: the first entry of largest magnitude at or below the diagonal
            // (`icamax`: a NaN never wins a comparison).
            let col = &a[i * n..(i + 1) * n];
            let (mut piv, mut max) = (i, col[i].abs());
            for (r, v) in col.iter().enumerate().skip(i + 1) {
                if v.abs() > max {
                    (piv, max) = (r, v.abs());
                }
            }
            let diag = col[piv];
            if diag == 0.0 {
                continue;
            }
            if piv != i {
                self.swaps.push((i, piv));
                for c in 0..n {
                    a.swap(c * n + i, c * n + piv);
                }
            }
            let inv = 1.0 / diag;
            for v in &mut a[i * n + i + 1..(i + 1) * n] {
                *v *= inv;
            }
            let (left, right) = a.split_at_mut((i + 1) * n);
            let l = &left[i * n + i + 1..];
            for col in right.chunks_exact_mut(n) {
                let u = -col[i];
                for (y, &x) in col[i + 1..].iter_mut().zip(l) {
                    *y += u * x;
                }
            }
        }
    }

    /// Solves the factorised system for the right-hand side in `f`, in place, as
    /// `LU::solve_mut` does; false when the matrix is singular.
    pub(super) fn solve(&mut self) -> bool {
        for &(i, piv) in &self.swaps {
            self.f.swap_rows(i, piv);
        }
        lu_solve(&self.k, self.f.as_mut_slice())
    }

    /// The reciprocal condition number in the 1-norm, 1/(‖A‖₁·‖A⁻¹‖₁), of A = K·D with D
    /// the diagonal `scale` (a column scaling: A's factors are K's with U's columns scaled,
    /// the same pivots), K factorised in place and `norm` = ‖A‖₁. ‖A⁻¹‖₁ is estimated by
    /// Hager's method with Higham's safeguard (at most five products with A⁻¹ and A⁻ᵀ, each two triangular solves):
    /// the estimate never exceeds ‖A⁻¹‖₁ and is almost always equal to it, so the result is
    /// at least the true reciprocal condition; within a factor n of σ_min/σ_max either way.
    /// 0 when a pivot is zero or a solve overflows.
    pub(super) fn rcond(&mut self, scale: &impl Fn(usize) -> f64, norm: f64) -> f64 {
        let n = self.k.nrows();
        if n == 0 || (0..n).any(|i| self.k[(i, i)] == 0.0) {
            return 0.0;
        }
        let mut x = std::mem::take(&mut self.x);
        let mut sign = std::mem::take(&mut self.sign);
        if x.len() != n {
            x = DVector::zeros(n);
        }
        x.fill(1.0 / n as f64);
        sign.clear();
        sign.resize(n, 0.0);
        let (mut est, mut last) = (0.0f64, 0);
        for iter in 0..5 {
            // x ← A⁻¹x = D⁻¹K⁻¹x.
            self.apply(x.as_mut_slice(), false, scale);
            let now: f64 = x.iter().map(|v| v.abs()).sum();
            if !now.is_finite() {
                est = f64::INFINITY;
                break;
            }
            if iter > 0 && now <= est {
                break;
            }
            est = now;
            for (s, v) in sign.iter_mut().zip(x.iter_mut()) {
                *s = if *v >= 0.0 { 1.0 } else { -1.0 };
                *v = *s;
            }
            // z = A⁻ᵀ·sign(A⁻¹x): where |z| is largest the next unit vector gains most;
            // once no entry beats zᵀx (x the unit vector of the last step) the estimate
            // is a local maximum.
            self.apply(x.as_mut_slice(), true, scale);
            let (j, zj) = x.iter().enumerate().fold((0, -1.0f64), |b, (i, v)| {
                if v.abs() > b.1 {
                    (i, v.abs())
                } else {
                    b
                }
            });
            if iter > 0 && zj <= x[last] {
                break;
            }
            x.fill(0.0);
            x[j] = 1.0;
            last = j;
        }
        // Higham's alternative vector guards against the rare matrix that fools the
        // iteration: x_i = (−1)^i (1 + i/(n−1)).
        for (i, v) in x.iter_mut().enumerate() {
            let t = if n > 1 {
                i as f64 / (n - 1) as f64
            } else {
                0.0
            };
            *v = if i % 2 == 0 { 1.0 + t } else { -(1.0 + t) };
        }
        self.apply(x.as_mut_slice(), false, scale);
        let alt = 2.0 * x.iter().map(|v| v.abs()).sum::<f64>() / (3.0 * n as f64);
        est = est.max(alt);
        self.x = x;
        self.sign = sign;
        let r = 1.0 / (norm * est);
        if r.is_finite() {
            r
        } else {
            0.0
        }
    }

    /// v ← D⁻¹K⁻¹v, or with `transpose` v ← K⁻ᵀD⁻¹v, by the factors in `k`.
    fn apply(&self, v: &mut [f64], transpose: bool, scale: &impl Fn(usize) -> f64) {
        let n = v.len();
        let a = self.k.as_slice();
        if transpose {
            for (i, x) in v.iter_mut().enumerate() {
                *x /= scale(i);
            }
            // Kᵀ = UᵀLᵀP: Uᵀ forward, Lᵀ (unit) back, then the swaps in reverse.
            for i in 0..n {
                let col = &a[i * n..i * n + i];
                let s: f64 = col.iter().zip(&v[..i]).map(|(u, x)| u * x).sum();
                v[i] = (v[i] - s) / a[i * n + i];
            }
            for i in (0..n).rev() {
                let col = &a[i * n + i + 1..(i + 1) * n];
                let s: f64 = col.iter().zip(&v[i + 1..]).map(|(l, x)| l * x).sum();
                v[i] -= s;
            }
            for &(i, piv) in self.swaps.iter().rev() {
                v.swap(i, piv);
            }
        } else {
            for &(i, piv) in &self.swaps {
                v.swap(i, piv);
            }
            lu_solve(&self.k, v);
            for (i, x) in v.iter_mut().enumerate() {
                *x /= scale(i);
            }
        }
    }
}

/// L·U·x = b in place (L unit lower, U upper, both in `k`), as nalgebra's
/// `solve_lower_triangular_with_diag_mut(b, 1)` then `solve_upper_triangular_mut`; false at
/// a zero pivot.
fn lu_solve(k: &DMatrix<f64>, b: &mut [f64]) -> bool {
    let n = b.len();
    let a = k.as_slice();
    for i in 0..n.saturating_sub(1) {
        let c = -b[i];
        for (y, &l) in b[i + 1..].iter_mut().zip(&a[i * n + i + 1..(i + 1) * n]) {
            *y += c * l;
        }
    }
    for i in (0..n).rev() {
        let d = a[i * n + i];
        if d == 0.0 {
            return false;
        }
        let c = b[i] / d;
        b[i] = c;
        let c = -c;
        for (y, &u) in b[..i].iter_mut().zip(&a[i * n..i * n + i]) {
            *y += c * u;
        }
    }
    true
}
