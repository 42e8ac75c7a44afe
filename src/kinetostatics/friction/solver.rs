//! Newton's method on a dyad's three joint pressures, written out for 3×3, with the
//! continuation in the friction coefficients of [`super::newton`] as the fallback (see the
//! [module](super) for the equations).

pub(crate) use super::newton::Pressure;
use super::newton::{Pressures, DIRECT_STEPS, LOCKED_BELOW};
use super::{Convergence, Iteration};
use crate::error::Result;
use nalgebra::Vector3;

/// A dyad's friction equations: the reactions V(m) = V0 + t·D·m as three pairs of numbers,
/// one pair per joint, and each joint's pressure law.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Problem {
    /// The frictionless reactions.
    pub v0: [f64; 6],
    /// D's columns: the reactions' response to each joint's friction load per newton of
    /// pressure (with the coefficient and the sign of the motion folded in).
    pub d: [[f64; 6]; 3],
    /// The joints' pressure laws.
    pub laws: [Pressure; 3],
    /// The joints whose friction load is not zero.
    pub active: [bool; 3],
    /// The load scale, N.
    pub scale: f64,
}

/// The pressures and the reactions at the solution.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Solved {
    pub m: [f64; 3],
    pub v: [f64; 6],
    pub convergence: Convergence,
}

impl Solved {
    /// Converged by the direct Newton (no continuation) in `steps` steps.
    #[inline(always)]
    fn direct(m: [f64; 3], v: [f64; 6], steps: usize, det: f64, residual: f64) -> Self {
        Self {
            m,
            v,
            convergence: Convergence {
                iterations: steps,
                continued: false,
                det,
                residual,
            },
        }
    }
}

impl Problem {
    /// The pressures of the reactions `v`.
    #[inline(always)]
    fn pressures(&self, v: &[f64; 6]) -> [f64; 3] {
        let mut psi = [0.0; 3];
        for k in 0..3 {
            if self.active[k] {
                psi[k] = self.laws[k].of(v[2 * k], v[2 * k + 1]);
            }
        }
        psi
    }

    /// Solves m = ψ(V0 + D·m): Newton from the frictionless pressures, and where that does
    /// not converge with det(I − J) > 0, the continuation.
    #[inline(always)]
    pub(crate) fn solve(
        &self,
        options: &Iteration,
        what: &'static str,
        joints: [&'static str; 3],
    ) -> Result<Solved> {
        if self.laws == [Pressure::Hinge; 3] {
            self.direct::<true>(options, what, joints)
        } else {
            self.direct::<false>(options, what, joints)
        }
    }

    /// Newton from the frictionless pressures; `HINGES` when every joint is a hinge (the
    /// pressures are then three norms, computed side by side, and the gradients only when
    /// another step is needed).
    #[inline(always)]
    fn direct<const HINGES: bool>(
        &self,
        options: &Iteration,
        what: &'static str,
        joints: [&'static str; 3],
    ) -> Result<Solved> {
        let tol = options.tolerance * self.scale;
        let limit = DIRECT_STEPS.min(options.budget);
        let mask = self.active.map(|a| f64::from(u8::from(a)));
        let norms = |v: &[f64; 6]| {
            [0, 1, 2].map(|k| (v[2 * k] * v[2 * k] + v[2 * k + 1] * v[2 * k + 1]).sqrt())
        };
        let m0 = if HINGES {
            let r = norms(&self.v0);
            [0, 1, 2].map(|k| r[k] * mask[k])
        } else {
            self.pressures(&self.v0)
        };
        let mut m = m0;
        let (mut steps, mut det) = (0, 1.0_f64);
        loop {
            let mut v = self.v0;
            for (col, &mk) in self.d.iter().zip(&m) {
                for (vi, di) in v.iter_mut().zip(col) {
                    *vi += mk * di;
                }
            }
            let mut psi = [0.0; 3];
            let mut grad = [[0.0; 2]; 3];
            let mut r = [0.0; 3];
            if HINGES {
                r = norms(&v);
                psi = [0, 1, 2].map(|k| r[k] * mask[k]);
            } else {
                for k in 0..3 {
                    if self.active[k] {
                        (psi[k], grad[k]) = self.laws[k].eval(v[2 * k], v[2 * k + 1]);
                    }
                }
            }
            let residual = residual(&psi, &m);
            if steps > 0 && residual <= tol / det.min(1.0) {
                return Ok(Solved::direct(m, v, steps, det, residual));
            }
            if steps >= limit {
                break;
            }
            if HINGES {
                // A zero reaction has no direction: the NaN it gives makes det NaN, and the
                // continuation (whose pressure law handles it) takes over.
                let i = Vector3::repeat(1.0).component_div(&Vector3::from(r));
                grad = [0, 1, 2].map(|k| {
                    let s = i[k] * mask[k];
                    [v[2 * k] * s, v[2 * k + 1] * s]
                });
            }
            let mut a = [[0.0; 3]; 3];
            for k in 0..3 {
                for (j, dj) in self.d.iter().enumerate() {
                    a[k][j] = f64::from(u8::from(j == k))
                        - (grad[k][0] * dj[2 * k] + grad[k][1] * dj[2 * k + 1]);
                }
            }
            det = det3(&a);
            // A NaN det (from non-finite reactions) counts as locked too.
            if det.is_nan() || det <= LOCKED_BELOW {
                break;
            }
            let g = [psi[0] - m[0], psi[1] - m[1], psi[2] - m[2]];
            let delta = solve3(&a, det, &g);
            steps += 1;
            for k in 0..3 {
                m[k] += delta[k];
            }
            if !(m[0] + m[1] + m[2]).is_finite() {
                break;
            }
        }
        self.continued(m0, steps, tol, options.budget, what, joints)
    }

    /// The continuation, by the general solve's ([`Pressures::continued`]).
    #[cold]
    #[inline(never)]
    fn continued(
        &self,
        m0: [f64; 3],
        used: usize,
        tol: f64,
        budget: usize,
        what: &'static str,
        joints: [&'static str; 3],
    ) -> Result<Solved> {
        let many = Pressures {
            v0: (0..3)
                .map(|k| [self.v0[2 * k], self.v0[2 * k + 1]])
                .collect(),
            d: self
                .d
                .iter()
                .map(|col| (0..3).map(|k| [col[2 * k], col[2 * k + 1]]).collect())
                .collect(),
            laws: self.laws.to_vec(),
            active: self.active.to_vec(),
            scale: self.scale,
        };
        let s = many.continued(m0.to_vec(), used, tol, budget, what, &|k| {
            joints[k].to_owned()
        })?;
        Ok(Solved {
            m: [s.m[0], s.m[1], s.m[2]],
            v: [0, 1, 2, 3, 4, 5].map(|i| s.v[i / 2][i % 2]),
            convergence: s.convergence,
        })
    }
}

#[inline(always)]
fn residual(psi: &[f64; 3], m: &[f64; 3]) -> f64 {
    let r = [0, 1, 2].map(|k| (psi[k] - m[k]).abs());
    // Plain comparisons (f64::max's care for NaN costs a chain of instructions on the hot
    // path), with a NaN carried through by the sum: a NaN residual converges nowhere.
    wider(wider(r[0], r[1]), r[2]) + (r[0] + r[1] + r[2]) * 0.0
}

/// The larger of two numbers by a plain comparison.
#[inline(always)]
pub(crate) fn wider(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

#[inline(always)]
fn det3(a: &[[f64; 3]; 3]) -> f64 {
    a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
}

/// The adjugate of a 3×3 matrix (the transposed cofactors): a·adj = det·I.
#[inline(always)]
fn adjugate(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [
        [
            a[1][1] * a[2][2] - a[1][2] * a[2][1],
            a[0][2] * a[2][1] - a[0][1] * a[2][2],
            a[0][1] * a[1][2] - a[0][2] * a[1][1],
        ],
        [
            a[1][2] * a[2][0] - a[1][0] * a[2][2],
            a[0][0] * a[2][2] - a[0][2] * a[2][0],
            a[0][2] * a[1][0] - a[0][0] * a[1][2],
        ],
        [
            a[1][0] * a[2][1] - a[1][1] * a[2][0],
            a[0][1] * a[2][0] - a[0][0] * a[2][1],
            a[0][0] * a[1][1] - a[0][1] * a[1][0],
        ],
    ]
}

/// a⁻¹·g by Cramer's rule (the adjugate over det).
#[inline(always)]
fn solve3(a: &[[f64; 3]; 3], det: f64, g: &[f64; 3]) -> [f64; 3] {
    let c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    let c01 = a[0][2] * a[2][1] - a[0][1] * a[2][2];
    let c02 = a[0][1] * a[1][2] - a[0][2] * a[1][1];
    let c10 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    let c11 = a[0][0] * a[2][2] - a[0][2] * a[2][0];
    let c12 = a[0][2] * a[1][0] - a[0][0] * a[1][2];
    let c20 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    let c21 = a[0][1] * a[2][0] - a[0][0] * a[2][1];
    let c22 = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let i = 1.0 / det;
    [
        (c00 * g[0] + c01 * g[1] + c02 * g[2]) * i,
        (c10 * g[0] + c11 * g[1] + c12 * g[2]) * i,
        (c20 * g[0] + c21 * g[1] + c22 * g[2]) * i,
    ]
}

/// Newton for three hinges that all carry friction (the RRR dyad's usual case), written out:
/// the steps of [`Problem::solve`]'s, with row k of I − J and of the right-hand side
/// multiplied by r_k = |R_k| (row k of J is R_k·D_kj/r_k), so that the loop divides only in
/// Cramer's rule (det(I − J) = det/Π r_k). `None` where that does not converge with
/// det(I − J) > 0 within `limit` steps, or meets a zero reaction: the general solve decides
/// there.
#[inline(always)]
pub(crate) fn three_hinges(
    v0: &[f64; 6],
    d: &[[f64; 6]; 3],
    tol: f64,
    limit: usize,
) -> Option<Solved> {
    let norms = |v: &[f64; 6]| {
        [
            (v[0] * v[0] + v[1] * v[1]).sqrt(),
            (v[2] * v[2] + v[3] * v[3]).sqrt(),
            (v[4] * v[4] + v[5] * v[5]).sqrt(),
        ]
    };
    let mut m = norms(v0);
    // det(I − J) = scaled/product of the last step, kept as the pair so that the loop does
    // not wait for the division.
    let (mut scaled, mut product) = (1.0_f64, 1.0_f64);
    let mut steps = 0;
    loop {
        let mut v = [0.0; 6];
        for i in 0..6 {
            v[i] = v0[i] + m[0] * d[0][i] + m[1] * d[1][i] + m[2] * d[2][i];
        }
        let r = norms(&v);
        let g = [r[0] - m[0], r[1] - m[1], r[2] - m[2]];
        let residual = wider(wider(g[0].abs(), g[1].abs()), g[2].abs());
        if steps > 0 && residual * scaled.min(product) <= tol * product {
            let det = scaled / product;
            // A NaN anywhere in the reactions shows in their sum.
            let sum = v[0] + v[1] + v[2] + v[3] + v[4] + v[5];
            return sum
                .is_finite()
                .then_some(Solved::direct(m, v, steps, det, residual));
        }
        if steps >= limit {
            return None;
        }
        // Row k: r_k·e_k − R_k·D_kj.
        let mut a = [[0.0; 3]; 3];
        for (k, row) in a.iter_mut().enumerate() {
            let (x, y) = (v[2 * k], v[2 * k + 1]);
            for (j, aj) in row.iter_mut().enumerate() {
                *aj = -(x * d[j][2 * k] + y * d[j][2 * k + 1]);
            }
            row[k] += r[k];
        }
        let adj = adjugate(&a);
        scaled = a[0][0] * adj[0][0] + a[0][1] * adj[1][0] + a[0][2] * adj[2][0];
        product = r[0] * r[1] * r[2];
        // Also false for a NaN, and for a zero reaction (product 0).
        if !(scaled > LOCKED_BELOW * product && product > 0.0) {
            return None;
        }
        let rhs = [r[0] * g[0], r[1] * g[1], r[2] * g[2]];
        let i = 1.0 / scaled;
        let delta = adj.map(|row| (row[0] * rhs[0] + row[1] * rhs[1] + row[2] * rhs[2]) * i);
        steps += 1;
        m = [m[0] + delta[0], m[1] + delta[1], m[2] + delta[2]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cramer_solves_a_known_system() {
        let a = [[2.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 4.0]];
        let x = [1.0, -2.0, 0.5];
        let g = [
            2.0 * x[0] + x[1],
            x[0] + 3.0 * x[1] + x[2],
            x[1] + 4.0 * x[2],
        ];
        let y = solve3(&a, det3(&a), &g);
        for k in 0..3 {
            assert!((y[k] - x[k]).abs() < 1e-15);
        }
    }

    /// The inclined-plane slider in one unknown: m = |N0 − k·m| with N0 < 0 has the solution
    /// m = −N0/(1 − k) for k < 1, and none (self-locking) for k ≥ 1.
    #[test]
    fn one_slide_locks_where_its_feedback_reaches_one() {
        let problem = |k: f64| Problem {
            v0: [0.0, 0.0, -10.0, 0.0, 0.0, 0.0],
            d: [[0.0; 6], [0.0, 0.0, -k, 0.0, 0.0, 0.0], [0.0; 6]],
            laws: [Pressure::Hinge, Pressure::Normal, Pressure::Hinge],
            active: [false, true, false],
            scale: 10.0,
        };
        let names = ["a", "slide", "c"];
        let s = problem(0.5)
            .solve(&Iteration::default(), "test", names)
            .unwrap();
        assert!((s.m[1] - 20.0).abs() < 1e-13);
        assert!((s.convergence.det - 0.5).abs() < 1e-15);
        let e = problem(1.2)
            .solve(&Iteration::default(), "test", names)
            .unwrap_err();
        assert!(e.to_string().starts_with("slide self-locks"), "{e}");
    }

    /// Friction that relieves its own pressure (m = |N0 + k·m| with N0 < 0, k > 1): the
    /// direct Newton step jumps to the other sign, the continuation finds m = −N0/(1 + k).
    #[test]
    fn continuation_finds_the_branch_of_the_frictionless_solution() {
        let p = Problem {
            v0: [0.0, 0.0, -10.0, 0.0, 0.0, 0.0],
            d: [[0.0; 6], [0.0, 0.0, 3.0, 0.0, 0.0, 0.0], [0.0; 6]],
            laws: [Pressure::Hinge, Pressure::Normal, Pressure::Hinge],
            active: [false, true, false],
            scale: 10.0,
        };
        let s = p
            .solve(&Iteration::default(), "test", ["a", "b", "c"])
            .unwrap();
        assert!((s.m[1] - 2.5).abs() < 1e-13, "{:?}", s.m);
        assert!(s.convergence.det > 1.0);
    }
}
