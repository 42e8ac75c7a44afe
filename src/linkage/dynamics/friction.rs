//! Coulomb friction in the joints as generalized forces of a [`LinkageSystem`].
//!
//! # The generalized friction force
//! Each joint j with friction has a relative rate ṙ_j (the relative angular velocity of a
//! hinge's two links, the sliding velocity of a slide) that is linear in q̇:
//! ṙ_j = Σ_k r_jk(q)·q̇_k, with the first-order transfer functions r_jk = ∂ṙ_j/∂q̇_k of the
//! same kinematic solve that gives A(q). The joint's friction load (a couple ρ·|R_j| in a
//! hinge, a force f·|N_j| along a slide) opposes ṙ_j, so its power is −|L_j|·|ṙ_j| and, by
//! virtual power, its generalized forces are
//!
//! ```text
//! Q_f,k = −Σ_j |L_j|·sgn(ṙ_j)·r_jk,        Σ_k Q_f,k·q̇_k = −Σ_j P_lost,j.
//! ```
//!
//! # Why an equation for q̈
//! |L_j| is ρ_j·|R_j| (or f_j·|N_j|), and the reactions hold the links' inertia loads, which
//! are affine in q̈: every link's acceleration is a = a₀(q, q̇) + Σ_k u_k(q)·q̈_k, so a
//! frictionless reaction is R = R₀ + R₁·q̈ for one input (R₀ at q̈ = 0, R₁ its response to a
//! unit q̈). With friction the reactions are the friction statics' (nonlinear, solved to
//! full precision by [`kinetostatics::friction`](crate::kinetostatics::friction)) at the
//! motion (q, q̇, q̈), so Lagrange's equations become a small nonlinear system for q̈:
//!
//! ```text
//! A(q)·q̈ = b + Q_f(q̈),      b = Q − c(q, q̇) − B·q̇,
//! ```
//!
//! solved here for the fixed point q̈ = F(q̈) = A⁻¹·(b + Q_f(q̈)) from the frictionless
//! q̈₀ = A⁻¹·b: for one input by the secant method on g(q̈) = q̈ − F(q̈) (superlinear; its
//! slope 1 − ∂Q_f/∂q̈ / A₁₁ is near 1 because a friction couple ρ·|R| is small beside the
//! inertia's lever), for two inputs by Newton's method on g with the Jacobian
//! I − A⁻¹·∂Q_f/∂q̈ from forward differences, refined by Broyden's update and with halved
//! steps where a step does not decrease ‖g‖. (The plain iteration q̈ ← F(q̈) converges only
//! with the factor ‖A⁻¹·∂Q_f/∂q̈‖, which is not small where A is: 0.64 on the bundled
//! five-bar with f = 0.3 on pins of 5 cm, which it could not run.) The iteration
//! stops when the residual ‖q̈ − F(q̈)‖ at an evaluated q̈ is at most [`FRICTION_TOLERANCE`]
//! of the acceleration scale ‖q̈₀‖ + ‖F(q̈₀) − q̈₀‖, and the Q_f of that q̈ is returned: the
//! integrators' q̈ = F(q̈) then lies within that tolerance of the solution.
//! [`FRICTION_BUDGET`] evaluations at most, else an error: where the friction's feedback
//! reaches the inertia the motion self-locks and no q̈ is found.
//!
//! # Jamming
//! Near a group's dead point (a dyad's links nearly in line) the friction statics itself has
//! no solution for the inertia loads of the frictionless q̈₀: the group self-locks under
//! them (its friction feedback det(I − J) has crossed zero). Then the motion jams (Painlevé's
//! case of Coulomb friction: no finite reactions carry it on): the evaluation is an
//! [`Error::Jammed`] with the time, the joint that self-locks and its det(I − J), within the
//! state, and a run ends there with the rows up to its last state
//! ([`Outcome::Jammed`](crate::dynamics::Outcome::Jammed)), the jam located by bisection on
//! the length of the step that met it (the shortest that jams, to the run's time tolerance).
//!
//! At rest (every ṙ_j = 0) there is no friction (the convention of
//! [`kinetostatics::friction`](crate::kinetostatics::friction)); whether the machine stays
//! at rest or breaks away is weighed by the velocity-sign switch of the input
//! ([`LagrangeSystem::switch_loads`](crate::dynamics::LagrangeSystem::switch_loads)).
//!
//! # What the reactions hold
//! The friction statics sees what the kinetostatics sees: the description's loads, the
//! weights, the inertia loads and the drive on the input link (motor, added inertia and the
//! input's own torque act on the input link as couples, or through the described gear pair).
//! A viscous damper ([`Damper`](super::Damper)) between two links other than the frame and
//! the input acts in the equation through B only: its forces are not among the joints'
//! pressures.
//!
//! # Reversals
//! Where ṙ_j changes sign with q̇ ≠ 0 (a rocker at its extreme position), Q_f has a kink (one
//! input: the term |L_j|·|r_j1|·sgn(q̇) is continuous) or a jump (two inputs); each
//! ṙ_j is reported to the integrators as a kink argument with the node 0
//! ([`LagrangeSystem::kinks`](crate::dynamics::LagrangeSystem::kinks)), so that a run steps
//! exactly onto it.

use nalgebra::{Matrix2, Vector2};

use super::transfer::Transfer;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::kinetostatics::friction::sign;
use crate::linkage::{Inputs, Plan};

/// The fixed-point residual accepted, relative to the acceleration scale.
pub const FRICTION_TOLERANCE: f64 = 1e-12;

/// The evaluations of the friction statics allowed for one q̈.
pub const FRICTION_BUDGET: usize = 60;

/// Whether joint `j` of `plan` has friction (a nonzero ρ or f).
pub(super) fn has_friction(plan: &Plan, j: usize) -> bool {
    plan.friction
        .as_ref()
        .and_then(|fp| fp.get(j))
        .is_some_and(|f| f.hinge.rho != 0.0 || f.slide.f != 0.0)
}

/// One joint with friction: a hinge between two links, or a slide.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum FrictionJoint {
    /// A revolute joint (its index) between `links[0]` and `links[1]`: ṙ = ω₁ − ω₀.
    Hinge { joint: usize, links: [usize; 2] },
    /// A prismatic joint (its index): ṙ is the sliding link's velocity along the guide.
    Slide { joint: usize },
}

impl FrictionJoint {
    /// The joints of `plan` that have friction (none for a frictionless plan).
    pub(super) fn of(plan: &Plan) -> Vec<Self> {
        let Some(fp) = &plan.friction else {
            return Vec::new();
        };
        (0..fp.len())
            .filter(|&j| has_friction(plan, j))
            .map(|j| {
                let jp = &plan.chain.joints[j];
                if jp.prismatic.is_some() {
                    Self::Slide { joint: j }
                } else {
                    Self::Hinge {
                        joint: j,
                        links: jp.links,
                    }
                }
            })
            .collect()
    }

    /// The joint's index.
    pub(super) fn joint(self) -> usize {
        match self {
            Self::Hinge { joint, .. } | Self::Slide { joint } => joint,
        }
    }

    /// r_k = ∂ṙ/∂q̇_k, for k < n (0 beyond).
    pub(super) fn transfer(self, tr: &Transfer<'_>) -> [f64; 2] {
        [0, 1].map(|k| {
            if k >= tr.n {
                return 0.0;
            }
            match self {
                Self::Hinge { links, .. } => tr.omega(k, links[1]) - tr.omega(k, links[0]),
                Self::Slide { joint } => {
                    let d = tr.slide_parts(joint).2;
                    tr.slide_rate(k, joint, d)
                }
            }
        })
    }
}

/// The friction of one state (q, q̇): each joint's r_jk and sgn(ṙ_j), and the friction
/// statics to evaluate Q_f(q̈).
pub(super) struct StateFriction<'p> {
    joints: Vec<(usize, [f64; 2], f64)>,
    plan: &'p Plan,
    solver: crate::linkage::Solver<'p>,
    n: usize,
    q: Vector2<f64>,
    qd: Vector2<f64>,
    /// The evaluations of the friction statics made.
    pub(super) evaluations: usize,
}

impl<'p> StateFriction<'p> {
    /// The friction of the state, or `None` when every joint is at rest relative to its
    /// partner (no friction at all).
    pub(super) fn new(
        plan: &'p Plan,
        joints: &[FrictionJoint],
        tr: &Transfer<'_>,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Option<Self> {
        let joints: Vec<_> = joints
            .iter()
            .map(|fj| {
                let r = fj.transfer(tr);
                (fj.joint(), r, sign(r[0] * qd[0] + r[1] * qd[1]))
            })
            .filter(|j| j.2 != 0.0)
            .collect();
        (!joints.is_empty()).then(|| Self {
            joints,
            plan,
            solver: plan.solver(),
            n: tr.n,
            q: *q,
            qd: *qd,
            evaluations: 0,
        })
    }

    /// Q_f at the accelerations `qdd`: the friction statics of the motion (q, q̇, q̈).
    ///
    /// # Errors
    /// The friction statics' errors (a self-locking joint, named).
    pub(super) fn force(&mut self, qdd: &Vector2<f64>) -> Result<Vector2<f64>> {
        let m = |k: usize| Motion::new(self.q[k], self.qd[k], qdd[k]);
        let inputs = if self.n == 1 {
            Inputs::from(m(0))
        } else {
            Inputs::two(m(0), m(1))
        };
        self.evaluations += 1;
        let a = self.solver.analyse(inputs)?;
        let mut qf = Vector2::zeros();
        for &(j, r, s) in &self.joints {
            let load = a.friction(j)?.load.abs();
            qf[0] -= load * s * r[0];
            qf[1] -= load * s * r[1];
        }
        Ok(qf)
    }

    /// Solves A·q̈ = b + Q_f(q̈) (see the [module docs](self)) and returns Q_f at the
    /// solution.
    ///
    /// # Errors
    /// [`Error::Singular`] when A has no inverse; the friction statics' errors;
    /// [`Error::Budget`] (within [`Error::In`]) when [`FRICTION_BUDGET`] evaluations do not reach
    /// [`FRICTION_TOLERANCE`].
    pub(super) fn solve(
        &mut self,
        a: &Matrix2<f64>,
        b: &Vector2<f64>,
        time: f64,
    ) -> Result<Vector2<f64>> {
        let inv = a.try_inverse().ok_or(Error::Singular {
            what: "joint friction in the equation of motion",
            measure: "det A",
            value: a.determinant(),
        })?;
        if self.n == 2 {
            return self.solve_two(&inv, b, time);
        }
        let fixed = |qf: &Vector2<f64>| inv * (b + qf);
        let mut x = fixed(&Vector2::zeros());
        let mut qf = self.force(&x).map_err(|e| self.jammed(e, time, &x))?;
        let mut fx = fixed(&qf);
        let scale = x.norm() + (fx - x).norm();
        let tol = FRICTION_TOLERANCE * scale;
        // The previous point of the secant and its residual g = x − F(x).
        let mut prev: Option<(f64, f64)> = None;
        loop {
            let g = x - fx;
            let residual = g.norm();
            if residual <= tol {
                return Ok(qf);
            }
            if !residual.is_finite() || self.evaluations >= FRICTION_BUDGET {
                break;
            }
            let next = match prev {
                Some((x0, g0)) if g[0] != g0 => x[0] - g[0] * (x[0] - x0) / (g[0] - g0),
                _ => fx[0],
            };
            prev = Some((x[0], g[0]));
            x = Vector2::new(next, fx[1]);
            qf = self.force(&x)?;
            fx = fixed(&qf);
        }
        Err(self.not_found(time))
    }

    /// The two-input solve of g(q̈) = q̈ − A⁻¹·(b + Q_f(q̈)) = 0 (`inv` = A⁻¹): Newton's method
    /// with the Jacobian J = I − A⁻¹·∂Q_f/∂q̈ from forward differences, refined by Broyden's
    /// update while its steps keep decreasing ‖g‖ and taken afresh (with halved steps) when
    /// one does not.
    ///
    /// Why not the plain iteration q̈ ← F(q̈): its factor ‖A⁻¹·∂Q_f/∂q̈‖ is not small where A is
    /// (a five-bar near a singular pose, large pins): 0.64 was met on the bundled five-bar
    /// with f = 0.3 on pins of 5 cm, where 60 plain steps left the residual at 1.5·10⁻⁹ of
    /// the scale while Newton's method meets 10⁻¹² in about a dozen evaluations.
    fn solve_two(
        &mut self,
        inv: &Matrix2<f64>,
        b: &Vector2<f64>,
        time: f64,
    ) -> Result<Vector2<f64>> {
        let x0 = inv * b;
        let mut at = Root::new(self, inv, b, x0).map_err(|e| self.jammed(e, time, &x0))?;
        let scale = x0.norm() + at.g.norm();
        let tol = FRICTION_TOLERANCE * scale;
        // Forward-difference step: √ε of the acceleration scale.
        let dx = 1.5e-8 * scale;
        let mut jac: Option<(Matrix2<f64>, bool)> = None;
        loop {
            if at.g.norm() <= tol {
                // One more step of the last Jacobian, kept if it decreases ‖g‖: the root to
                // the iteration's precision rather than just within the tolerance, so that
                // the q̈ the integrators see is smooth in the state well below the
                // tolerance (a step-size control reads its roughness as error).
                let polished = jac
                    .and_then(|(j, _)| j.try_inverse())
                    .and_then(|ji| Root::new(self, inv, b, at.x - ji * at.g).ok())
                    .filter(|p| p.g.norm() < at.g.norm());
                return Ok(polished.map_or(at.qf, |p| p.qf));
            }
            if !at.g.norm().is_finite() || self.evaluations + 1 >= FRICTION_BUDGET {
                break;
            }
            let (j, fresh) = match jac {
                Some(j) => j,
                None => {
                    let mut j = Matrix2::zeros();
                    for k in 0..2 {
                        let mut xk = at.x;
                        xk[k] += dx;
                        let gk = Root::new(self, inv, b, xk)?.g;
                        j.set_column(k, &((gk - at.g) / dx));
                    }
                    (j, true)
                }
            };
            let Some(step) = j.try_inverse().map(|ji| -(ji * at.g)) else {
                return Err(Error::In {
                    part: self.state_text(),
                    source: Box::new(Error::Singular {
                        what: "the equation of motion with the joints' friction (self-locking)",
                        measure: "det(I − A⁻¹·∂Q_f/∂q̈)",
                        value: j.determinant(),
                    }),
                });
            };
            let mut t = 1.0;
            let accepted = loop {
                if self.evaluations >= FRICTION_BUDGET {
                    break None;
                }
                // A trial q̈ where the friction statics has no solution (a group self-locks
                // under those inertia loads) is a step too long, like one that does not
                // decrease ‖g‖.
                match Root::new(self, inv, b, at.x + step * t) {
                    Ok(trial) if trial.g.norm() < (1.0 - 1e-4 * t) * at.g.norm() => {
                        break Some(trial);
                    }
                    Ok(_) | Err(Error::In { .. } | Error::Singular { .. }) => {}
                    Err(e) => return Err(e),
                }
                if !fresh || t < 1e-3 {
                    break None;
                }
                t *= 0.5;
            };
            match accepted {
                Some(next) => {
                    // Broyden: J ← J + (y − J·s)·sᵀ/(sᵀs) meets the secant condition J·s = y.
                    let (s, y) = (next.x - at.x, next.g - at.g);
                    let upd = j + (y - j * s) * s.transpose() / s.norm_squared();
                    jac = upd.iter().all(|v| v.is_finite()).then_some((upd, false));
                    at = next;
                }
                None if fresh => break,
                None => jac = None,
            }
        }
        Err(self.not_found(time))
    }

    /// The state, for the errors.
    fn state_text(&self) -> String {
        format!(
            "joint friction in the equation of motion at q = ({:e}, {:e}), q̇ = ({:e}, {:e})",
            self.q[0], self.q[1], self.qd[0], self.qd[1]
        )
    }

    /// The error of a motion that jams: the friction statics has no solution at the
    /// frictionless q̈ (`source` names the group and joint that self-lock): an
    /// [`Error::Jammed`] (a run's stop, [`Outcome::Jammed`](crate::dynamics::Outcome::Jammed))
    /// naming the joint, within the state; any other error of the statics as it is, within
    /// the state.
    fn jammed(&self, source: Error, time: f64, qdd: &Vector2<f64>) -> Error {
        let source = match self_locking(&source, self.plan.joint_names()) {
            Some((index, value)) => jam_error(self.plan, time, index, value),
            None => source,
        };
        Error::In {
            part: format!(
                "{} with the frictionless accelerations ({:e}, {:e})",
                self.state_text(),
                qdd[0],
                qdd[1]
            ),
            source: Box::new(source),
        }
    }

    /// The error of a q̈ not found within the budget.
    fn not_found(&self, time: f64) -> Error {
        Error::In {
            part: format!(
                "{}: q̈ not found (the friction's feedback may reach the inertia: self-locking)",
                self.state_text()
            ),
            source: Box::new(Error::Budget {
                what: "friction evaluation",
                limit: FRICTION_BUDGET,
                time,
            }),
        }
    }
}

/// The jam of `plan`'s joint `joint` at time `t` with the friction's feedback det(I − J) =
/// `value` ([`Error::Jammed`]).
pub(super) fn jam_error(plan: &Plan, t: f64, joint: usize, value: f64) -> Error {
    Error::Jammed {
        time: t,
        index: joint,
        joint: plan.joint_names().get(joint).cloned().unwrap_or_default(),
        measure: "det(I - J)",
        value,
    }
}

/// The joint (its index among `names`) whose self-locking `e` reports (a part "… joint
/// <name> self-locks …" around det(I − J), the measure that vanished), with that value. A
/// det(I − J) that is not a number (the reactions overflowed in the Newton step) is no
/// measured jam: the statics' error stands (a run's error, not a stop with a NaN in it).
fn self_locking(e: &Error, names: &[String]) -> Option<(usize, f64)> {
    let Error::In { part, source } = e else {
        return None;
    };
    if let (true, Error::Singular { value, .. }) = (part.contains(" self-locks"), source.as_ref()) {
        if !value.is_finite() {
            return None;
        }
        // The longest name that fits (a name may hold another).
        return names
            .iter()
            .enumerate()
            .filter(|(_, n)| part.contains(&format!("joint {n} self-locks")))
            .max_by_key(|(_, n)| n.len())
            .map(|(j, _)| (j, *value));
    }
    self_locking(source, names)
}

/// One point of the two-input solve: q̈, its Q_f and the residual g = q̈ − A⁻¹·(b + Q_f).
struct Root {
    x: Vector2<f64>,
    qf: Vector2<f64>,
    g: Vector2<f64>,
}

impl Root {
    fn new(
        sf: &mut StateFriction<'_>,
        inv: &Matrix2<f64>,
        b: &Vector2<f64>,
        x: Vector2<f64>,
    ) -> Result<Self> {
        let qf = sf.force(&x)?;
        let g = x - inv * (b + qf);
        Ok(Self { x, qf, g })
    }
}
