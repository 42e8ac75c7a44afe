//! The Newton solves of a [`HingedGroup`] in reusable buffers: a [`GroupWork`] is sized at
//! its first solve and then reused, so tracking a group along a cycle allocates nothing but
//! the pose it returns. The factorisation is nalgebra's LU with partial pivoting done in the
//! workspace's matrix (the same elimination steps in the same order, so the same bits as
//! `DMatrix::lu` and `LU::solve`).

use super::assur::{GroupPose, HingedGroup, MAX_NEWTON};
use nalgebra::linalg::{gauss_step, gauss_step_swap};
use nalgebra::{DMatrix, DVector, Point2};

/// Reusable buffers for the Newton solves of one [`HingedGroup`] (any size; resized when the
/// group's size changes). `Default` allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct GroupWork {
    lin: Linear,
    q: DVector<f64>,
    guess: DVector<f64>,
    pts: Vec<Point2<f64>>,
    before: Vec<Point2<f64>>,
}

/// A square system's matrix (factorised in place), its right-hand side (then solution) and
/// the row swaps of the factorisation.
#[derive(Debug, Clone, Default)]
pub(super) struct Linear {
    pub k: DMatrix<f64>,
    pub f: DVector<f64>,
    swaps: Vec<(usize, usize)>,
}

impl Linear {
    /// Sizes the buffers for `n` unknowns (allocating only when the size changes).
    fn size(&mut self, n: usize) {
        if self.k.shape() != (n, n) {
            self.k = DMatrix::zeros(n, n);
            self.f = DVector::zeros(n);
        }
    }

    /// Factorises `k` in place, as `LU::new` does.
    fn factorise(&mut self) {
        let n = self.k.nrows();
        self.swaps.clear();
        for i in 0..n {
            let piv = self.k.view_range(i.., i).icamax() + i;
            let diag = self.k[(piv, i)];
            if diag == 0.0 {
                continue;
            }
            if piv != i {
                self.swaps.push((i, piv));
                self.k.columns_range_mut(..i).swap_rows(i, piv);
                gauss_step_swap(&mut self.k, diag, i, piv);
            } else {
                gauss_step(&mut self.k, diag, i);
            }
        }
    }

    /// Solves the factorised system for the right-hand side in `f`, in place, as
    /// `LU::solve_mut` does; false when the matrix is singular.
    fn solve(&mut self) -> bool {
        for &(i, piv) in &self.swaps {
            self.f.swap_rows(i, piv);
        }
        let _ = self
            .k
            .solve_lower_triangular_with_diag_mut(&mut self.f, 1.0);
        self.k.solve_upper_triangular_mut(&mut self.f)
    }
}

impl HingedGroup {
    /// Newton's method from `q` (in place): the first step's size when it converges (the step
    /// falls to rounding, 4ε of `size`) within `max` steps, each step no more than `size` and,
    /// once `contract` is set, each at most half the one before.
    pub(super) fn newton_in(
        &self,
        q: &mut DVector<f64>,
        lin: &mut Linear,
        outer: &[Point2<f64>],
        size: f64,
        max: usize,
        contract: bool,
    ) -> Option<f64> {
        lin.size(q.len());
        let mut first = None;
        let mut last = f64::INFINITY;
        for _ in 0..max {
            self.residual_into(q, outer, &mut lin.f);
            self.jacobian_into(q, 1.0, &mut lin.k);
            lin.factorise();
            lin.f.neg_mut();
            if !lin.solve() {
                return None;
            }
            let step = Self::step_norm(&lin.f, size);
            if !step.is_finite() || step > size {
                return None;
            }
            first.get_or_insert(step);
            *q += &lin.f;
            if step <= 4.0 * f64::EPSILON * size || (step >= last && step <= 1e-12 * size) {
                return Some(first.unwrap_or(0.0));
            }
            if contract && step > 1e-11 * size && step > 0.5 * last {
                return None;
            }
            last = step;
        }
        None
    }

    /// [`track`](Self::track) in the buffers of `work` (the same steps, the same bits).
    ///
    /// # Errors
    /// As [`track`](Self::track).
    pub fn track_in(
        &self,
        reference: &GroupPose,
        mut path: impl FnMut(f64, &mut [Point2<f64>]),
        size: f64,
        work: &mut GroupWork,
    ) -> crate::Result<GroupPose> {
        let GroupWork {
            lin,
            q,
            guess,
            pts,
            before,
        } = work;
        reference.write_q(q);
        lin.size(q.len());
        pts.clear();
        pts.resize(self.outer.len(), Point2::origin());
        before.clear();
        before.resize(self.outer.len(), Point2::origin());
        let (mut t, mut dt) = (0.0f64, 1.0f64);
        path(0.0, before);
        let base = 2 * self.inner.len();
        while t < 1.0 {
            let t1 = (t + dt).min(1.0);
            path(t1, pts);
            // Tangent predictor: K·Δq = (0 | ΔP).
            self.jacobian_into(q, 1.0, &mut lin.k);
            lin.f.fill(0.0);
            for (o, (p1, p0)) in pts.iter().zip(before.iter()).enumerate() {
                lin.f[base + 2 * o] = p1.x - p0.x;
                lin.f[base + 2 * o + 1] = p1.y - p0.y;
            }
            lin.factorise();
            let corrected = lin.solve() && {
                guess.clone_from(q);
                *guess += &lin.f;
                self.newton_in(guess, lin, pts, size, 12, true)
                    .is_some_and(|first| first <= 0.1 * size)
            };
            if corrected {
                std::mem::swap(q, guess);
                t = t1;
                before.copy_from_slice(pts);
                dt = (2.0 * dt).min(1.0);
            } else if dt > 1e-9 {
                dt *= 0.5;
            } else {
                let gap = self.residual(&GroupPose::from_q(q), pts);
                return Err(super::assur::no_assembly(gap));
            }
        }
        // Polish at the end: the corrector stopped at rounding already; one more solve
        // brings every hinge to the last bit the closure allows.
        guess.clone_from(q);
        if self
            .newton_in(guess, lin, pts, size, MAX_NEWTON, false)
            .is_none()
        {
            return Err(super::assur::no_assembly(
                self.residual(&GroupPose::from_q(q), pts),
            ));
        }
        Ok(GroupPose::from_q(guess))
    }
}
