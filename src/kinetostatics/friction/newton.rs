//! Newton's method on any number of joint pressures, with the continuation in the friction
//! coefficients: the equations m = ψ(V0 + t·D·m) of the [module](super) for a group of n
//! joints (a triad's six hinges, a general group's), by an n×n LU per step. A dyad's 3×3
//! iteration ([`super::solver`]) is written out for speed and falls back on this one's
//! continuation.

use super::{sign, Convergence, Iteration};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};

/// Below this det(I − J) the friction's feedback amplifies the rounding of the reactions by
/// more than 1/√ε ≈ 7·10⁷: the group is treated as self-locking.
pub(super) const LOCKED_BELOW: f64 = 1.5e-8;

/// The smallest continuation step before the continuation gives up.
pub(super) const SMALLEST_STEP: f64 = 1.0 / 4096.0;

/// The Newton steps allowed from the frictionless start before the continuation takes over.
pub(crate) const DIRECT_STEPS: usize = 16;

/// The Newton steps allowed at one continuation step before it is halved.
pub(super) const STEPS_PER_STAGE: usize = 12;

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
    pub(super) fn eval(self, x: f64, y: f64) -> (f64, [f64; 2]) {
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

pub(super) fn budget_error(what: &'static str, limit: usize, t: f64) -> Error {
    Error::In {
        part: format!("{what}: friction iteration (t is the share of the friction reached)"),
        source: Box::new(Error::Budget {
            what: "Newton step",
            limit,
            time: t,
        }),
    }
}

/// The friction equations of a group of n joints: each joint's reaction as a pair of
/// numbers, V(m) = V0 + t·D·m, and each joint's pressure law.
#[derive(Debug, Clone)]
pub(crate) struct Pressures {
    /// The frictionless reactions, a pair per joint.
    pub v0: Vec<[f64; 2]>,
    /// `d[j][k]`: joint k's pair per newton of joint j's pressure (the coefficient and the
    /// sign of the motion folded in).
    pub d: Vec<Vec<[f64; 2]>>,
    /// The joints' pressure laws.
    pub laws: Vec<Pressure>,
    /// The joints whose friction load is not zero.
    pub active: Vec<bool>,
    /// The load scale, N.
    pub scale: f64,
}

/// The pressures and the reactions at the solution.
#[derive(Debug, Clone)]
pub(crate) struct SolvedMany {
    pub m: Vec<f64>,
    pub v: Vec<[f64; 2]>,
    pub convergence: Convergence,
}

/// Why a Newton run stopped short.
enum Stop {
    /// det(I − J) at or below the threshold, or not converged within the steps allowed,
    /// with det(I − J) and J's diagonal.
    Short(f64, Vec<f64>),
    /// The whole budget used.
    Budget,
}

/// One evaluation at m: the reactions, the pressures and J = ∂ψ/∂m.
struct Eval {
    v: Vec<[f64; 2]>,
    psi: Vec<f64>,
    jac: DMatrix<f64>,
}

/// max_k |ψ_k − m_k|, NaN when any is.
fn residual(psi: &[f64], m: &[f64]) -> f64 {
    psi.iter()
        .zip(m)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, |s, x| if x > s || x.is_nan() { x } else { s })
}

impl Pressures {
    fn n(&self) -> usize {
        self.v0.len()
    }

    fn eval(&self, t: f64, m: &[f64]) -> Eval {
        let n = self.n();
        let mut v = self.v0.clone();
        for (col, &mj) in self.d.iter().zip(m) {
            let w = t * mj;
            for (vk, dk) in v.iter_mut().zip(col) {
                vk[0] += w * dk[0];
                vk[1] += w * dk[1];
            }
        }
        let mut psi = vec![0.0; n];
        let mut jac = DMatrix::zeros(n, n);
        for k in (0..n).filter(|&k| self.active[k]) {
            let (p, g) = self.laws[k].eval(v[k][0], v[k][1]);
            psi[k] = p;
            for (j, dj) in self.d.iter().enumerate() {
                jac[(k, j)] = t * (g[0] * dj[k][0] + g[1] * dj[k][1]);
            }
        }
        Eval { v, psi, jac }
    }

    /// Newton from `m` at the friction factor `t`, at most `limit` steps; the solution with
    /// its evaluation and det(I − J) there.
    fn newton(
        &self,
        t: f64,
        mut m: Vec<f64>,
        limit: usize,
        tol: f64,
        used: &mut usize,
        budget: usize,
    ) -> std::result::Result<(Vec<f64>, Eval, f64), Stop> {
        let n = self.n();
        let mut steps = 0;
        loop {
            let e = self.eval(t, &m);
            let diag: Vec<f64> = e.jac.diagonal().iter().copied().collect();
            let lu = (DMatrix::identity(n, n) - &e.jac).lu();
            let det = lu.determinant();
            // A NaN det (from non-finite reactions) counts as locked too.
            if det.is_nan() || det <= LOCKED_BELOW {
                return Err(Stop::Short(det, diag));
            }
            // Converged at the previous step: the residual is the next step's size up to
            // the factor 1/det, and rounding is amplified by as much.
            let r = residual(&e.psi, &m);
            if steps > 0 && r.is_finite() && r <= tol / det.min(1.0) {
                return Ok((m, e, det));
            }
            if *used >= budget {
                return Err(Stop::Budget);
            }
            if steps >= limit {
                return Err(Stop::Short(det, diag));
            }
            let g = DVector::from_iterator(n, e.psi.iter().zip(&m).map(|(p, q)| p - q));
            let Some(delta) = lu.solve(&g) else {
                return Err(Stop::Short(det, diag));
            };
            *used += 1;
            steps += 1;
            for (mk, dk) in m.iter_mut().zip(delta.iter()) {
                *mk += dk;
            }
            if !m.iter().all(|x| x.is_finite()) {
                return Err(Stop::Short(det, diag));
            }
        }
    }

    /// The frictionless pressures ψ(V0).
    fn start(&self) -> Vec<f64> {
        (0..self.n())
            .map(|k| {
                if self.active[k] {
                    self.laws[k].of(self.v0[k][0], self.v0[k][1])
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// Solves m = ψ(V0 + D·m): Newton from the frictionless pressures, and where that does
    /// not converge with det(I − J) > 0, the continuation. `name(k)` names joint k in a
    /// self-locking error.
    pub(crate) fn solve(
        &self,
        options: &Iteration,
        what: &'static str,
        name: &dyn Fn(usize) -> String,
    ) -> Result<SolvedMany> {
        let tol = options.tolerance * self.scale;
        let m0 = self.start();
        if !self.active.iter().any(|&a| a) {
            return Ok(SolvedMany {
                m: m0,
                v: self.v0.clone(),
                convergence: Convergence::NONE,
            });
        }
        let mut used = 0;
        let limit = DIRECT_STEPS.min(options.budget);
        match self.newton(1.0, m0.clone(), limit, tol, &mut used, options.budget) {
            Ok((m, e, det)) => Ok(SolvedMany {
                convergence: Convergence {
                    iterations: used,
                    continued: false,
                    det,
                    residual: residual(&e.psi, &m),
                },
                m,
                v: e.v,
            }),
            Err(_) => self.continued(m0, used, tol, options.budget, what, name),
        }
    }

    /// The continuation: the friction switched on gradually (a factor t from 0 to 1 on every
    /// coefficient, Newton at each step, the step halved where Newton fails), so that the
    /// solution found is the one connected to the frictionless one. Self-locking where the
    /// step falls below [`SMALLEST_STEP`]: the joint with the largest own feedback J_kk is
    /// named.
    pub(crate) fn continued(
        &self,
        m0: Vec<f64>,
        mut used: usize,
        tol: f64,
        budget: usize,
        what: &'static str,
        name: &dyn Fn(usize) -> String,
    ) -> Result<SolvedMany> {
        if used >= budget {
            return Err(budget_error(what, budget, 1.0));
        }
        let (mut t, mut m, mut h) = (0.0_f64, m0, 0.25_f64);
        loop {
            let t1 = (t + h).min(1.0);
            match self.newton(t1, m.clone(), STEPS_PER_STAGE, tol, &mut used, budget) {
                Ok((m1, e, det)) => {
                    if t1 >= 1.0 {
                        return Ok(SolvedMany {
                            convergence: Convergence {
                                iterations: used,
                                continued: true,
                                det,
                                residual: residual(&e.psi, &m1),
                            },
                            m: m1,
                            v: e.v,
                        });
                    }
                    (t, m, h) = (t1, m1, (2.0 * h).min(0.5));
                }
                Err(Stop::Budget) => return Err(budget_error(what, budget, t)),
                Err(Stop::Short(det, diag)) => {
                    h /= 2.0;
                    if h < SMALLEST_STEP && !(det.is_nan() || det <= LOCKED_BELOW) {
                        // The determinant stayed regular: the continuation ran out of steps
                        // (an iterate overflowed or Newton stalled), which is not a lock.
                        return Err(budget_error(what, budget, t));
                    }
                    if h < SMALLEST_STEP {
                        let k = (0..self.n())
                            .filter(|&k| self.active[k])
                            .max_by(|&i, &j| diag[i].total_cmp(&diag[j]))
                            .unwrap_or(0);
                        return Err(Error::In {
                            part: format!("{} self-locks", name(k)),
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
