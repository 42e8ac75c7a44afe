//! A square linear system in reusable buffers: nalgebra's LU with partial pivoting done in
//! place (the same elimination steps in the same order, so the same bits as `DMatrix::lu`
//! and `LU::solve`), so that repeated solves of one size allocate nothing.

use nalgebra::linalg::{gauss_step, gauss_step_swap};
use nalgebra::{DMatrix, DVector};

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
    pub(super) fn solve(&mut self) -> bool {
        for &(i, piv) in &self.swaps {
            self.f.swap_rows(i, piv);
        }
        let _ = self
            .k
            .solve_lower_triangular_with_diag_mut(&mut self.f, 1.0);
        self.k.solve_upper_triangular_mut(&mut self.f)
    }
}
