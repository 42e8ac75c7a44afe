//! Newton's method on a dyad's three joint pressures, with a continuation in the friction
//! coefficients as the fallback (see the [module](super) for the equations).

use super::{sign, Convergence, Iteration};
use crate::error::{Error, Result};
use nalgebra::Vector3;

/// Below this det(I − J) the friction's feedback amplifies the rounding of the reactions by
/// more than 1/√ε ≈ 7·10⁷: the group is treated as self-locking.
const LOCKED_BELOW: f64 = 1.5e-8;

/// The smallest continuation step before the continuation gives up.
const SMALLEST_STEP: f64 = 1.0 / 4096.0;

/// The Newton steps allowed from the frictionless start before the continuation takes over.
pub(crate) const DIRECT_STEPS: usize = 16;

/// The Newton steps allowed at one continuation step before it is halved.
const STEPS_PER_STAGE: usize = 12;

/// How a joint's pressure follows from its pair of reaction numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Pressure {
    /// A hinge: the pair is (R_x, R_y), the pressure |R|.
    Hinge,
    /// A slide that takes any couple: the pair is (N, K), the pressure |N|.
    Normal,
    /// A cocked slider: the pair is (N, K) with K about the reference point, the pressure
    /// |N1| + |N2| = max(|N|, |K − c·N|/h) for the middle c and half-length h.
    Ends {
        /// The slider's middle along the guide from the reference point, m.
        centre: f64,
        /// Half the slider's length, m.
        half: f64,
    },
}

impl Pressure {
    /// ψ, the pressure of a pair.
    #[inline]
    pub(crate) fn of(self, x: f64, y: f64) -> f64 {
        self.eval(x, y).0
    }

    /// ψ and its gradient with respect to the pair.
    #[inline(always)]
    fn eval(self, x: f64, y: f64) -> (f64, [f64; 2]) {
        match self {
            Self::Hinge => {
                let r = (x * x + y * y).sqrt();
                if r > 0.0 {
                    let i = 1.0 / r;
                    (r, [x * i, y * i])
                } else {
                    (0.0, [0.0, 0.0])
                }
            }
            Self::Normal => (x.abs(), [sign(x), 0.0]),
            Self::Ends { centre, half } => {
                let k = (y - centre * x) / half;
                if x.abs() >= k.abs() {
                    (x.abs(), [sign(x), 0.0])
                } else {
                    let s = sign(k) / half;
                    (k.abs(), [-s * centre, s])
                }
            }
        }
    }
}

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

/// Why a Newton run stopped short.
enum Stop {
    /// det(I − J) at or below the threshold, with J's diagonal.
    Locked(f64, [f64; 3]),
    /// Not converged within the steps allowed.
    Slow(f64, [f64; 3]),
    /// The whole budget used.
    Budget,
}

struct Eval {
    v: [f64; 6],
    psi: [f64; 3],
    jac: [[f64; 3]; 3],
}

impl Problem {
    #[inline(always)]
    fn eval(&self, t: f64, m: &[f64; 3]) -> Eval {
        let mut v = self.v0;
        for (col, &mk) in self.d.iter().zip(m) {
            let w = t * mk;
            for (vi, di) in v.iter_mut().zip(col) {
                *vi += w * di;
            }
        }
        let mut psi = [0.0; 3];
        let mut jac = [[0.0; 3]; 3];
        for k in 0..3 {
            if !self.active[k] {
                continue;
            }
            let (p, g) = self.laws[k].eval(v[2 * k], v[2 * k + 1]);
            psi[k] = p;
            for (jk, dj) in jac[k].iter_mut().zip(&self.d) {
                *jk = t * (g[0] * dj[2 * k] + g[1] * dj[2 * k + 1]);
            }
        }
        Eval { v, psi, jac }
    }

    /// Newton from `m` at the friction factor `t`, at most `limit` steps.
    fn newton(
        &self,
        t: f64,
        mut m: [f64; 3],
        limit: usize,
        tol: f64,
        used: &mut usize,
        budget: usize,
    ) -> std::result::Result<([f64; 3], Eval, f64), Stop> {
        let mut steps = 0;
        loop {
            let e = self.eval(t, &m);
            let a = minus_identity(&e.jac);
            let det = det3(&a);
            let diag = [e.jac[0][0], e.jac[1][1], e.jac[2][2]];
            // A NaN det (from non-finite reactions) counts as locked too.
            if det.is_nan() || det <= LOCKED_BELOW {
                return Err(Stop::Locked(det, diag));
            }
            if steps > 0 {
                // Converged at the previous step: this evaluation is the final one.
                let residual = residual(&e.psi, &m);
                if residual.is_finite() && last_small(&m, &e.psi, tol, det) {
                    return Ok((m, e, det));
                }
            }
            if *used >= budget {
                return Err(Stop::Budget);
            }
            if steps >= limit {
                return Err(Stop::Slow(det, diag));
            }
            let g = [e.psi[0] - m[0], e.psi[1] - m[1], e.psi[2] - m[2]];
            let delta = solve3(&a, det, &g);
            *used += 1;
            steps += 1;
            for k in 0..3 {
                m[k] += delta[k];
            }
            if !m.iter().all(|x| x.is_finite()) {
                return Err(Stop::Slow(det, diag));
            }
        }
    }

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
                return Ok(Solved {
                    m,
                    v,
                    convergence: Convergence {
                        iterations: steps,
                        continued: false,
                        det,
                        residual,
                    },
                });
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

    /// The continuation: switch the friction on gradually from the frictionless solution.
    #[cold]
    #[inline(never)]
    fn continued(
        &self,
        m0: [f64; 3],
        mut used: usize,
        tol: f64,
        budget: usize,
        what: &'static str,
        joints: [&'static str; 3],
    ) -> Result<Solved> {
        if used >= budget {
            return Err(budget_error(what, budget, 1.0));
        }
        let (mut t, mut m, mut h) = (0.0_f64, m0, 0.25_f64);
        loop {
            let t1 = (t + h).min(1.0);
            match self.newton(t1, m, STEPS_PER_STAGE, tol, &mut used, budget) {
                Ok((m1, e, det)) => {
                    if t1 >= 1.0 {
                        return Ok(Solved {
                            m: m1,
                            v: e.v,
                            convergence: Convergence {
                                iterations: used,
                                continued: true,
                                det,
                                residual: residual(&e.psi, &m1),
                            },
                        });
                    }
                    (t, m, h) = (t1, m1, (2.0 * h).min(0.5));
                }
                Err(Stop::Budget) => return Err(budget_error(what, budget, t)),
                Err(Stop::Locked(det, diag) | Stop::Slow(det, diag)) => {
                    h /= 2.0;
                    if h < SMALLEST_STEP {
                        let k = (0..3)
                            .filter(|&k| self.active[k])
                            .max_by(|&i, &j| diag[i].total_cmp(&diag[j]))
                            .unwrap_or(0);
                        return Err(Error::In {
                            part: format!("{} self-locks", joints[k]),
                            source: Box::new(Error::Singular {
                                what,
                                measure: "det(I - J)",
                                value: det,
                            }),
                        });
                    }
                }
            }
        }
    }
}

/// Converged: the step that led to `m` (m − previous) is not known here, so the test is on
/// the Newton residual ψ − m, which after a step is the size of the next step up to the
/// factor 1/det.
#[inline(always)]
fn last_small(m: &[f64; 3], psi: &[f64; 3], tol: f64, det: f64) -> bool {
    residual(psi, m) <= tol / det.min(1.0)
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

fn budget_error(what: &'static str, limit: usize, t: f64) -> Error {
    Error::In {
        part: format!("{what}: friction iteration (t is the share of the friction reached)"),
        source: Box::new(Error::Budget {
            what: "Newton step",
            limit,
            time: t,
        }),
    }
}

#[inline(always)]
fn minus_identity(j: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut a = [[0.0; 3]; 3];
    for r in 0..3 {
        for c in 0..3 {
            a[r][c] = if r == c { 1.0 } else { 0.0 } - j[r][c];
        }
    }
    a
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
            return sum.is_finite().then_some(Solved {
                m,
                v,
                convergence: Convergence {
                    iterations: steps,
                    continued: false,
                    det,
                    residual,
                },
            });
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
