//! The equation of motion of a described linkage: A(q), ∂A/∂q, Q and B from the exact
//! transfer functions of the kinematic solve.

use nalgebra::{Matrix2, Point2, Vector2};

use super::drive::{Damper, DamperPlan, Motor};
use super::friction::{FrictionJoint, StateFriction};
use super::transfer::{self, Transfer};
use crate::dynamics::{
    checked_inertia, christoffel_terms, kink_slots, LagrangeSystem, LagrangeTerms,
};
use crate::error::{computed_all, finite, finite2, Error, Result};
use crate::kinematics::Motion;
use crate::linkage::plan::Pose;
use crate::linkage::solve::loads::{apply, LoadSite};
use crate::linkage::{Linkage, Plan};
use crate::Load;

/// Everything Lagrange's equations need at one state of a [`LinkageSystem`].
///
/// For a linkage with one input the second coordinate is a decoupled unit mass that nothing
/// drives (A₂₂ = 1, A₁₂ = 0, Q₂ = 0): it stays at rest, and the first row is the textbook's
/// equation of the machine reduced to its input, J_red(φ)·ε + ½·J_red′(φ)·ω² = M_red.
///
/// # Examples
/// The five-bar robot's inertia matrix is symmetric and positive-definite:
/// ```
/// use nalgebra::Vector2;
/// use tmm::linkage::{bundled, dynamics::LinkageSystem};
/// let sys = LinkageSystem::from_linkage(&bundled::five_bar_robot())?;
/// let q = Vector2::new(2.0, 1.1);
/// let t = sys.split_terms(&q, &Vector2::new(1.0, -1.0))?;
/// let a = t.inertia;
/// assert_eq!(a[(0, 1)], a[(1, 0)]);
/// assert!(a[(0, 0)] > 0.0 && a.determinant() > 0.0);
/// assert_eq!(t.forces(), t.drives + t.loads);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Terms {
    /// The generalized inertia A(q) of T = ½ q̇ᵀ A q̇ (kg·m² for crank angles, kg for slides):
    /// for one input A₁₁ is the reduced moment of inertia J_red.
    pub inertia: Matrix2<f64>,
    /// [∂A/∂q₁, ∂A/∂q₂].
    pub inertia_derivatives: [Matrix2<f64>; 2],
    /// The generalized forces of the motors on the inputs (N·m, or N for a slider).
    pub drives: Vector2<f64>,
    /// The generalized forces of gravity and of the description's loads (for one input, the
    /// reduced moment of the loads M_red).
    pub loads: Vector2<f64>,
    /// The matrix B of Rayleigh's dissipation function Φ = ½ q̇ᵀ B q̇.
    pub damping: Matrix2<f64>,
    /// The generalized forces of the joints' Coulomb friction, Q_f (zero without friction or
    /// at rest): solved with q̈ (see [`LinkageSystem::split_terms`]); their power
    /// Q_f·q̇ = −Σ P_lost.
    pub friction: Vector2<f64>,
}

impl Terms {
    /// All applied generalized forces: drives, loads and the joints' friction (not the
    /// viscous −B q̇).
    #[must_use]
    pub fn forces(&self) -> Vector2<f64> {
        let f = self.drives + self.loads;
        if self.friction == Vector2::zeros() {
            // Bit for bit the frictionless sum (−0 + 0 would be +0).
            f
        } else {
            f + self.friction
        }
    }
}

/// A described linkage with one or two inputs as a machine the crate's integrators run: a
/// [`LagrangeSystem`] whose inertia, inertia derivatives and generalized forces come from the
/// linkage engine's kinematics (see the [module docs](super) for the formulas).
///
/// The inputs' coordinates are the generalized coordinates: q₁ the (first) input's crank
/// angle φ (rad, as [`Plan::reference_input`]) or slide s (m), q₂ the second input's, or a
/// decoupled coordinate at rest for a linkage with one input.
///
/// # Examples
/// The bundled four-bar under a linear motor: its reduced moment of inertia and the
/// generalized force at a state.
/// ```
/// use nalgebra::Vector2;
/// use tmm::dynamics::machines::LinearMotor;
/// use tmm::linkage::{bundled, dynamics::{LinkageSystem, Motor}};
/// let sys = LinkageSystem::from_linkage(&bundled::four_bar())?
///     .with_motor(0, Motor::Linear(LinearMotor { a: 40.0, b: 0.2 }))?;
/// let t = sys.split_terms(&Vector2::new(1.0, 0.0), &Vector2::new(10.0, 0.0))?;
/// assert!(t.inertia[(0, 0)] > 0.002); // more than the crank's own 0.002 kg·m²
/// assert_eq!(t.drives[0], 38.0);
/// assert_eq!((t.inertia[(1, 1)], t.loads[1]), (1.0, 0.0)); // the idle coordinate
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageSystem {
    plan: Plan,
    motors: [Motor; 2],
    extra: [f64; 2],
    dampers: Vec<DamperPlan>,
    /// The joints with friction (none for a frictionless plan).
    friction: Vec<FrictionJoint>,
}

/// The dynamics' site of the load interpreter: each load's generalized forces
/// Q_k = F·∂v_P/∂q̇_k + M·∂ω/∂q̇_k, its direction-dependent magnitudes read at the actual
/// rates Σ_k (∂r/∂q_k)·q̇_k.
struct Project<'a, 'p> {
    tr: &'a mut Transfer<'p>,
    q: &'a Vector2<f64>,
    qd: &'a Vector2<f64>,
    loads: &'a mut Vector2<f64>,
    /// Whether the rates at the actual q̇ are solved (once, for the first user's load).
    rates_solved: bool,
}

impl LoadSite for Project<'_, '_> {
    fn position(&self, link: usize, local: Vector2<f64>) -> Point2<f64> {
        self.tr.point(0, link, local).p
    }

    fn velocity(&self, link: usize, local: Vector2<f64>) -> Vector2<f64> {
        (0..self.tr.n)
            .map(|k| self.tr.vel(k, link, local) * self.qd[k])
            .sum()
    }

    fn angle(&self, link: usize) -> f64 {
        self.tr.kin.links[link].angle
    }

    fn omega(&self, link: usize) -> f64 {
        self.tr.rate(self.qd, |k| self.tr.omega(k, link))
    }

    fn slide_parts(&self, joint: usize) -> (usize, usize, Vector2<f64>) {
        self.tr.slide_parts(joint)
    }

    fn slide(&self, joint: usize, d: Vector2<f64>) -> (f64, f64) {
        // The positions are the same in every solve: the slide from the first.
        let [on, guide] = self.tr.slide_points(0, joint);
        let s = (on.p - guide.p).dot(&d);
        (
            s,
            self.tr.rate(self.qd, |k| self.tr.slide_rate(k, joint, d)),
        )
    }

    /// The position solved at the actual rates: the same positions, the transfer functions
    /// kept in `tr.rates` (a user's load sees the state's positions and velocities, and the
    /// accelerations of q̈ = 0).
    fn pose(&mut self) -> Result<Pose<'_>> {
        let tr = &mut *self.tr;
        if !self.rates_solved {
            let (q, qd) = (self.q, self.qd);
            let m = [Motion::new(q[0], qd[0], 0.0), Motion::new(q[1], qd[1], 0.0)];
            tr.kin.solve_rates(tr.chain, &m[..tr.n])?;
            self.rates_solved = true;
        }
        Ok(tr.kin.pose(tr.chain))
    }

    fn force_at_local(&mut self, link: usize, local: Vector2<f64>, force: Vector2<f64>) {
        for k in 0..self.tr.n {
            self.loads[k] += force.dot(&self.tr.vel(k, link, local));
        }
    }

    fn couple(&mut self, link: usize, moment: f64) {
        for k in 0..self.tr.n {
            self.loads[k] += moment * self.tr.omega(k, link);
        }
    }

    fn force_between(&mut self, on: usize, against: usize, p: Point2<f64>, force: Vector2<f64>) {
        let tr = &*self.tr;
        for k in 0..tr.n {
            self.loads[k] += force.dot(&(tr.vel_of(k, on, p) - tr.vel_of(k, against, p)));
        }
    }

    fn load(&mut self, link: usize, load: Load) {
        let tr = &*self.tr;
        for k in 0..tr.n {
            self.loads[k] +=
                load.force.dot(&tr.vel_of(k, link, load.point)) + load.moment * tr.omega(k, link);
        }
    }
}

fn check_input(n: usize, input: usize) -> Result<()> {
    if input < n {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name: "input index",
            value: input as f64,
            min: 0.0,
            max: n as f64 - 1.0,
            ends: crate::Ends::Closed,
        })
    }
}

impl LinkageSystem {
    /// The machine of a planned linkage, without motors, added inertia or dampers.
    ///
    /// # Errors
    /// None today (every plan has one or two inputs); kept fallible for checks to come.
    pub fn new(plan: Plan) -> Result<Self> {
        Ok(Self {
            friction: FrictionJoint::of(&plan),
            plan,
            motors: [Motor::None, Motor::None],
            extra: [0.0; 2],
            dampers: Vec::new(),
        })
    }

    /// Plans `linkage` and makes its machine.
    ///
    /// # Errors
    /// As [`Plan::new`].
    pub fn from_linkage(linkage: &Linkage) -> Result<Self> {
        Self::new(Plan::new(linkage)?)
    }

    /// The same machine with `motor` on input `input` (0 the first, 1 the second).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an input the linkage does not have; [`Error::NonFinite`]
    /// for a motor with a non-finite coefficient.
    pub fn with_motor(mut self, input: usize, motor: Motor) -> Result<Self> {
        check_input(self.dof(), input)?;
        motor.check()?;
        self.motors[input] = motor;
        Ok(self)
    }

    /// The same machine with the moment of inertia `j` added on input `input` (kg·m²; kg for
    /// a slider): a motor's rotor and gearing reduced to the input shaft, or a flywheel.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an input the linkage does not have; [`Error::NonFinite`]
    /// for a non-finite `j`, [`Error::OutOfRange`] when the total added inertia would be
    /// negative.
    pub fn with_inertia(mut self, input: usize, j: f64) -> Result<Self> {
        check_input(self.dof(), input)?;
        let total = self.extra[input] + finite("added moment of inertia", j)?;
        if !(total >= 0.0 && total.is_finite()) {
            return Err(Error::OutOfRange {
                name: "added moment of inertia (in total)",
                value: total,
                min: 0.0,
                max: f64::INFINITY,
                ends: crate::Ends::Closed,
            });
        }
        self.extra[input] = total;
        Ok(self)
    }

    /// The same machine with a viscous damper.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown link or joint, or a coefficient that is negative
    /// or not finite.
    pub fn with_damper(mut self, damper: &Damper) -> Result<Self> {
        let d = damper.resolve(&self.plan)?;
        self.dampers.push(d);
        Ok(self)
    }

    /// The linkage's plan.
    #[must_use]
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// Whether any joint has Coulomb friction ([`Plan::has_friction`]): then every evaluation
    /// of the forces solves for q̈ with the friction (see the [module docs](super)).
    #[must_use]
    pub fn has_joint_friction(&self) -> bool {
        !self.friction.is_empty()
    }

    /// The number of degrees of freedom (inputs): 1 or 2.
    #[must_use]
    pub fn dof(&self) -> usize {
        self.plan.input_count()
    }

    /// The motor on input `input`.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an input the linkage does not have.
    pub fn motor(&self, input: usize) -> Result<&Motor> {
        check_input(self.dof(), input)?;
        Ok(&self.motors[input])
    }

    /// The inertia added on input `input` by [`with_inertia`](Self::with_inertia).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an input the linkage does not have.
    pub fn added_inertia(&self, input: usize) -> Result<f64> {
        check_input(self.dof(), input)?;
        Ok(self.extra[input])
    }

    /// A, ∂A/∂q, the drives' and the loads' generalized forces and B at the state (q, q̇).
    ///
    /// One position of the kinematics at unit input rate gives every first- and second-order
    /// transfer function of a linkage with one input. Two inputs need the rates at q̇ = e₁,
    /// e₂ and (1, 1) (three quadratic forms for the three second-order transfer functions):
    /// the positions are solved once, and only the groups' linear velocity and acceleration
    /// problems again for e₂ and (1, 1). Loads added by [`Plan::add_load_fn`] get the rates
    /// once more at the actual q̇ (such a load sees the state's positions and velocities, and
    /// the accelerations of q̈ = 0).
    ///
    /// The trait's [`LagrangeSystem::terms`] (with the time, the drives and loads summed into
    /// Q) is the same evaluation.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite q or q̇; the kinematics' errors (a group that
    /// cannot be assembled or is at a dead point) wrapped in [`Error::In`]; a load's or a
    /// motor's error; [`Error::Overflow`] when a term overflows.
    pub fn split_terms(&self, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Terms> {
        self.evaluate(q, qd, true, None, None)
    }

    /// The terms at (q, q̇), the forces only when `forces`. With `inertia_at` = Some(t), A is
    /// also checked positive-definite (the error naming t) before the loads are evaluated:
    /// the order in which [`crate::dynamics::accelerations`] reports the first failure. The
    /// joints' friction is solved with q̈, or taken at `qdd` when given.
    pub(super) fn evaluate(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        forces: bool,
        inertia_at: Option<f64>,
        qdd: Option<&Vector2<f64>>,
    ) -> Result<Terms> {
        finite2(["q1", "q2"], *q)?;
        finite2(["q1_dot", "q2_dot"], *qd)?;
        let plan = &self.plan;
        let n = self.dof();
        let mut tr = Transfer::new(plan, n, q)?;
        let mut a = Matrix2::zeros();
        let mut da = [Matrix2::zeros(); 2];
        let mut loads = Vector2::zeros();
        for (l, lp) in plan.chain.links.iter().enumerate().skip(1) {
            if lp.mass == 0.0 && lp.inertia == 0.0 {
                continue;
            }
            let (m, j) = (lp.mass, lp.inertia);
            // The centre of mass's first- and second-order transfer functions u_i = ∂r_S/∂q_i,
            // u_ik = ∂²r_S/∂q_i∂q_k, and the link's w_i, w_ik.
            let p0 = tr.point(0, l, lp.centre);
            let (u0, w0) = (p0.v, tr.omega(0, l));
            let (u00, w00) = (p0.a, tr.rates[l].epsilon);
            if n == 1 {
                a[(0, 0)] += m * u0.dot(&u0) + j * w0 * w0;
                da[0][(0, 0)] += 2.0 * (m * u00.dot(&u0) + j * w00 * w0);
                if forces {
                    loads[0] += m * plan.gravity.dot(&u0);
                }
                continue;
            }
            let (p1, p2) = (tr.point(1, l, lp.centre), tr.point(2, l, lp.centre));
            let (u1, w1) = (p1.v, tr.omega(1, l));
            let (u11, w11) = (p1.a, tr.rates[tr.nl + l].epsilon);
            let u01 = 0.5 * (p2.a - u00 - u11);
            let w01 = 0.5 * (tr.rates[2 * tr.nl + l].epsilon - w00 - w11);
            a[(0, 0)] += m * u0.dot(&u0) + j * w0 * w0;
            a[(0, 1)] += m * u0.dot(&u1) + j * w0 * w1;
            a[(1, 1)] += m * u1.dot(&u1) + j * w1 * w1;
            // ∂A_ik/∂q_s = m (u_is·u_k + u_i·u_ks) + J (w_is w_k + w_i w_ks).
            da[0][(0, 0)] += 2.0 * (m * u00.dot(&u0) + j * w00 * w0);
            da[0][(0, 1)] += m * (u00.dot(&u1) + u0.dot(&u01)) + j * (w00 * w1 + w0 * w01);
            da[0][(1, 1)] += 2.0 * (m * u01.dot(&u1) + j * w01 * w1);
            da[1][(0, 0)] += 2.0 * (m * u01.dot(&u0) + j * w01 * w0);
            da[1][(0, 1)] += m * (u01.dot(&u1) + u0.dot(&u11)) + j * (w01 * w1 + w0 * w11);
            da[1][(1, 1)] += 2.0 * (m * u11.dot(&u1) + j * w11 * w1);
            if forces {
                loads[0] += m * plan.gravity.dot(&u0);
                loads[1] += m * plan.gravity.dot(&u1);
            }
        }
        // Symmetric by construction, to the last bit.
        a[(1, 0)] = a[(0, 1)];
        for da_s in &mut da {
            da_s[(1, 0)] = da_s[(0, 1)];
        }
        for i in 0..n {
            a[(i, i)] += self.extra[i];
        }
        if n == 1 {
            a[(1, 1)] = 1.0;
        }
        computed_all("generalized inertia A", a.iter())?;
        computed_all(
            "inertia derivatives dA/dq",
            da.iter().flat_map(|m| m.iter()),
        )?;
        // B needs positions and first-order transfer functions only (the solve at the actual
        // rates for custom loads below keeps both).
        let damping = self.damping_from(&tr);
        computed_all("damping matrix B", damping.iter())?;
        if let Some(t) = inertia_at {
            checked_inertia(&a, t, q)?;
        }
        let mut drives = Vector2::zeros();
        if forces {
            let mut site = Project {
                tr: &mut tr,
                q,
                qd,
                loads: &mut loads,
                rates_solved: false,
            };
            apply(plan, &mut site)?;
            for i in 0..n {
                drives[i] = self.motors[i].moment(q[i], qd[i])?;
            }
        }
        computed_all("generalized forces Q", loads.iter().chain(drives.iter()))?;
        let mut friction = Vector2::zeros();
        if forces
            && !self.friction.is_empty()
            && let Some(mut sf) = StateFriction::new(plan, &self.friction, &tr, q, qd)
        {
            friction = match qdd {
                Some(qdd) => sf.force(qdd)?,
                None => {
                    let b = loads + drives - christoffel_terms(&da, qd)? - damping * qd;
                    sf.solve(&a, &b, inertia_at.unwrap_or(0.0))?
                }
            };
            computed_all("joint friction Q_f", friction.iter())?;
        }
        Ok(Terms {
            inertia: a,
            inertia_derivatives: da,
            drives,
            loads,
            damping,
            friction,
        })
    }

    fn damping_from(&self, tr: &Transfer<'_>) -> Matrix2<f64> {
        let n = tr.n;
        let mut b = Matrix2::zeros();
        for d in &self.dampers {
            let (c, r): (f64, [f64; 2]) = match *d {
                DamperPlan::Link { link, c } => (
                    c,
                    [0, 1].map(|k| if k < n { tr.omega(k, link) } else { 0.0 }),
                ),
                DamperPlan::Hinge { links, c } => (
                    c,
                    [0, 1].map(|k| {
                        if k < n {
                            tr.omega(k, links[0]) - tr.omega(k, links[1])
                        } else {
                            0.0
                        }
                    }),
                ),
                DamperPlan::Slide { joint, c } => {
                    let d = tr.kin.pose(tr.chain).guide_direction_at(joint);
                    (
                        c,
                        [0, 1].map(|k| {
                            if k < n {
                                tr.slide_rate(k, joint, d)
                            } else {
                                0.0
                            }
                        }),
                    )
                }
            };
            for i in 0..n {
                for k in i..n {
                    b[(i, k)] += c * r[i] * r[k];
                }
            }
        }
        b[(1, 0)] = b[(0, 1)];
        b
    }

    /// The inverse dynamics: the generalized driving forces the inputs need for the motion
    /// (q, q̇, q̈), A·q̈ + c(q, q̇) + B·q̇ − Q_loads (c the Christoffel terms), the motors
    /// left out. For a linkage with one input the first component is the driving moment (or
    /// force); the second is q̈₂ of the idle coordinate.
    ///
    /// # Errors
    /// As [`split_terms`](Self::split_terms); [`Error::NonFinite`] for a non-finite q̈.
    ///
    /// # Examples
    /// At a steady motion it equals the kinetostatic balancing moment of the same position:
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, dynamics::LinkageSystem, Plan};
    /// let sys = LinkageSystem::from_linkage(&bundled::watt_six_bar())?;
    /// let m = sys.inverse_dynamics(&Vector2::new(0.7, 0.0), &Vector2::new(12.0, 0.0), &Vector2::zeros())?;
    /// let b = sys.plan().analyse(Motion::turning(0.7, 12.0))?.balance(0)?.value;
    /// assert!((m[0] - b).abs() < 1e-9 * b.abs());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn inverse_dynamics(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        qdd: &Vector2<f64>,
    ) -> Result<Vector2<f64>> {
        finite2(["q1_ddot", "q2_ddot"], *qdd)?;
        let t = self.evaluate(q, qd, true, None, Some(qdd))?;
        let c = christoffel_terms(&t.inertia_derivatives, qd)?;
        let mut m = t.inertia * qdd + c + t.damping * qd - t.loads;
        if t.friction != Vector2::zeros() {
            m -= t.friction;
        }
        computed_all("inverse dynamics", m.iter())?;
        Ok(m)
    }
}

impl LinkageSystem {
    /// The inputs whose motors have switches, in input order: each servo (its clamp) and
    /// each tabulated motor (its table's nodes). One kink argument each.
    fn kinked_motors(&self) -> impl Iterator<Item = (usize, &Motor)> {
        self.motors[..self.dof()]
            .iter()
            .enumerate()
            .filter(|(_, m)| matches!(m, Motor::Servo(_) | Motor::Tabulated(_)))
    }
}

impl LagrangeSystem for LinkageSystem {
    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        Ok(self
            .evaluate(q, &Vector2::zeros(), false, None, None)?
            .inertia)
    }

    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        Ok(self
            .evaluate(q, &Vector2::zeros(), false, None, None)?
            .inertia_derivatives)
    }

    fn forces(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        Ok(self.split_terms(q, qd)?.forces())
    }

    /// A, ∂A/∂q, Q and B from one evaluation of the kinematics (one solve of the positions,
    /// with the rates at the other unit vectors for two inputs), reporting the first failure
    /// in the order of the separate methods: the kinematics, then A, ∂A/∂q and B overflowing,
    /// A not positive-definite, then a load or a motor, Q overflowing. No potential: gravity
    /// is one of the loads.
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        let all = self.evaluate(q, qd, true, Some(t), None)?;
        Ok(LagrangeTerms {
            inertia: all.inertia,
            inertia_derivatives: all.inertia_derivatives,
            forces: all.forces(),
            potential_gradient: Vector2::zeros(),
            damping: all.damping,
        })
    }

    fn damping(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        if self.dampers.is_empty() {
            return Ok(Matrix2::zeros());
        }
        Ok(self
            .evaluate(q, &Vector2::zeros(), false, None, None)?
            .damping)
    }

    /// The switches of the motors' characteristics, which are kinks of Q: one argument for
    /// each input driven by a servo (its demand over its limit, nodes ±1: the clamps, as
    /// [`FiveBar`](crate::dynamics::machines::FiveBar)'s; no node for a servo with limit 0,
    /// which never switches) or by a tabulated motor (its rate q̇, the nodes of its table), in
    /// input order. None for smooth motors. Each is located on its own, so a tabulated motor
    /// beside a servo, or two servos switching in one step, all have their switches stepped
    /// onto.
    ///
    /// Then one argument for each joint with friction: its relative rate ṙ_j, with the node
    /// 0 (where its friction reverses).
    fn kinks(&self) -> Vec<Vec<f64>> {
        self.kinked_motors()
            .map(|(_, m)| match m {
                Motor::Servo(s) => s.switch_nodes(),
                Motor::Tabulated(t) => t.xs().to_vec(),
                _ => Vec::new(),
            })
            .chain(self.friction.iter().map(|_| vec![0.0]))
            .collect()
    }

    /// The arguments of [`kinks`](Self::kinks), one per servo or tabulated motor in input
    /// order: a servo's demand over its limit (kept within [−2, 2], inside (−1, 1) while the
    /// servo follows its demand; 0 for limit 0), a tabulated motor's input rate q̇; then each
    /// friction joint's relative rate (rad/s, or m/s for a slide).
    ///
    /// # Errors
    /// A non-finite state; a servo's error; [`Error::OutOfRange`] when `out` has not one
    /// entry per argument.
    fn kink_arguments(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        let motors = self.kinked_motors().count();
        kink_slots(out, motors + self.friction.len())?;
        finite2(["q1", "q2"], *q)?;
        finite2(["q1_dot", "q2_dot"], *qd)?;
        let (by_motor, by_joint) = out.split_at_mut(motors);
        for (o, (i, m)) in by_motor.iter_mut().zip(self.kinked_motors()) {
            *o = match m {
                Motor::Servo(s) => s.switch_argument(q[i], qd[i])?.unwrap_or(0.0),
                _ => qd[i],
            };
        }
        if !self.friction.is_empty() {
            let tr = Transfer::new(&self.plan, self.dof(), q)?;
            for (o, fj) in by_joint.iter_mut().zip(&self.friction) {
                let r = fj.transfer(&tr);
                *o = r[0] * qd[0] + r[1] * qd[1];
            }
        }
        Ok(())
    }

    /// One switch, the input's rate, for a machine with one input and a resistance among its
    /// loads or friction in its joints; one per resistance for a machine with two inputs
    /// (see [`SwitchLoads`](crate::dynamics::SwitchLoads) and the module `stops`); none
    /// otherwise.
    fn switches(&self) -> usize {
        self.input_switches()
    }

    /// One per RRR or RRP dyad: where a run checks that no step carried the motion across
    /// a dyad's dead centre unseen.
    fn locks(&self) -> usize {
        transfer::dyad_count(&self.plan)
    }

    /// |det| − [`DEAD_CENTRE_DETERMINANT`](crate::linkage::DEAD_CENTRE_DETERMINANT) of each
    /// RRR or RRP dyad, in attachment order (one solve of the positions).
    fn lock_measures(&self, q: &Vector2<f64>, out: &mut [f64]) -> Result<()> {
        transfer::lock_measures(&self.plan, self.dof(), q, out)
    }

    /// The input's rate q̇₁, or with two inputs each resistance's rate (after checking that
    /// `out` has one entry per switch).
    fn switch_speeds(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        self.input_switch_speeds(q, qd, out)
    }

    /// The resistances' generalized force as it is while the switch's speed has the sign of
    /// `direction`.
    fn switch_force(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        direction: f64,
    ) -> Result<Vector2<f64>> {
        self.input_switch_force(i, t, q, qd, direction)
    }

    /// With one input its one switch holds the input; with two, an input's own joint
    /// friction holds that input (see the module `stops`).
    fn switch_holds(&self, i: usize) -> Option<usize> {
        self.input_switch_holds(i)
    }

    /// No: a described linkage's loads are constant and its motors laws of (q, q̇)
    /// ([`Motor`](super::Motor)), so a whole rest its friction holds is held for good (the
    /// run ends [`Outcome::Stuck`](crate::dynamics::Outcome::Stuck)). A rest that breaks away
    /// later under a load changing with time needs a system of one's own whose forces depend
    /// on t (`tests/dynamics/held_rest.rs`).
    fn forces_depend_on_time(&self) -> bool {
        false
    }

    /// The terms with the inputs `held` at rest: the joints' friction of the held motion.
    fn held_terms(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        held: [bool; 2],
    ) -> Result<LagrangeTerms> {
        self.input_held_terms(t, q, qd, held)
    }

    /// With one input, the drive on the input at rest and the resistances reduced to it;
    /// with two, the load that drives a resisted rate and the resistance.
    fn switch_loads(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<crate::dynamics::SwitchLoads> {
        self.input_switch_loads(i, t, q, qd)
    }

    /// The drives' and the loads' generalized forces, and for a linkage with friction the
    /// friction's (`friction_1`, `friction_2`).
    fn output_names(&self) -> Vec<&'static str> {
        let mut names = vec!["drive_1", "drive_2", "loads_1", "loads_2"];
        if !self.friction.is_empty() {
            names.extend(["friction_1", "friction_2"]);
        }
        names
    }

    fn outputs(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        let t = self.split_terms(q, qd)?;
        out.extend([t.drives[0], t.drives[1], t.loads[0], t.loads[1]]);
        if !self.friction.is_empty() {
            out.extend([t.friction[0], t.friction[1]]);
        }
        Ok(())
    }
}
