//! Lagrange's equations of the 2nd kind for a machine with two generalized coordinates.
//!
//! With the kinetic energy T = ½ q̇ᵀ A(q) q̇, a potential Π(q) and Rayleigh's dissipation
//! function Φ = ½ q̇ᵀ B(q) q̇ (seed 003, eqs. 1–7), Lagrange's equations
//! d/dt ∂T/∂q̇ᵢ − ∂T/∂qᵢ + ∂Π/∂qᵢ + ∂Φ/∂q̇ᵢ = Qᵢ become
//!
//! ```text
//! A(q) q̈ = Q(t, q, q̇) − c(q, q̇) − ∇Π(q) − B(q) q̇,
//! cᵢ = Σⱼₖ Γᵢⱼₖ q̇ⱼ q̇ₖ,   Γᵢⱼₖ = ½ (∂Aᵢⱼ/∂qₖ + ∂Aᵢₖ/∂qⱼ − ∂Aⱼₖ/∂qᵢ)   (Christoffel symbols)
//! ```
//!
//! derived once here for any A(q). For two coordinates this is exactly the corrected set of
//! seed 003's coefficients A0…A44, B0…B44 (docs/errata.md#d11): the seed's (35)–(36) misprint five
//! of them, this form cannot.

use nalgebra::{Matrix2, Vector2};

use super::switch::SwitchLoads;

use crate::error::{computed_all, finite, finite2, Error, Result};

/// The state of a 2-DOF machine: time, generalized coordinates and their rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Time t, s.
    pub t: f64,
    /// Generalized coordinates q (rad for angles, m for slides).
    pub q: Vector2<f64>,
    /// Generalized speeds q̇.
    pub qd: Vector2<f64>,
}

impl State {
    /// A state from its parts.
    #[must_use]
    pub fn new(t: f64, q: Vector2<f64>, qd: Vector2<f64>) -> Self {
        Self { t, q, qd }
    }

    /// The machine at rest at `q`, at t = 0.
    #[must_use]
    pub fn at_rest(q: Vector2<f64>) -> Self {
        Self::new(0.0, q, Vector2::zeros())
    }

    /// `true` when t, q and q̇ are all finite.
    #[must_use]
    #[inline]
    pub fn is_finite(&self) -> bool {
        [self.t, self.q[0], self.q[1], self.qd[0], self.qd[1]]
            .iter()
            .fold(true, |ok, v| ok & v.is_finite())
    }
}

/// Relative step of the numerical fallbacks (see [`LagrangeSystem::inertia_derivatives`]).
const FD_STEP: f64 = 2e-4;

/// Fourth-order central difference of `f` along coordinate `k` at `q`:
/// f'(x) ≈ [f(x−2ε) − 8 f(x−ε) + 8 f(x+ε) − f(x+2ε)] / (12 ε), with ε = 2·10⁻⁴·max(1, |qₖ|).
/// The truncation error is ε⁴/30·f⁽⁵⁾ and the rounding error about 10⁻¹⁶·|f|/ε: about
/// 10⁻¹² relative for a function that varies on a scale of one unit of qₖ, more where it
/// varies faster (near a singular position).
///
/// What a user's system hands the fallback is checked, since nothing downstream of a public
/// default method would: a non-finite q or sample of `f` is [`Error::NonFinite`] naming
/// `what.0`, a derivative that overflows from finite samples (values near f64's limit,
/// divided by 12ε) is [`Error::Overflow`] naming `what.1`.
fn central_difference<T, F>(
    q: &Vector2<f64>,
    k: usize,
    what: (&'static str, &'static str),
    values: fn(&T) -> &[f64],
    mut f: F,
) -> Result<T>
where
    T: std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
    F: FnMut(&Vector2<f64>) -> Result<T>,
{
    finite2(["q1", "q2"], *q)?;
    let eps = FD_STEP * q[k].abs().max(1.0);
    let mut at = |d: f64| {
        let mut p = *q;
        p[k] += d;
        let v = f(&p)?;
        for &x in values(&v) {
            finite(what.0, x)?;
        }
        Ok::<T, Error>(v)
    };
    let m2 = at(-2.0 * eps)?;
    let m1 = at(-eps)?;
    let p1 = at(eps)?;
    let p2 = at(2.0 * eps)?;
    let d = ((m2 - p2) + (p1 - m1) * 8.0) * (1.0 / (12.0 * eps));
    computed_all(what.1, values(&d).iter())?;
    Ok(d)
}

/// An error of the numerical fallbacks as the equations at time `t` report it: a sample of A
/// or Π that is not finite (a motion diverging to where they overflow, or a user's NaN) is a
/// non-finite state at t, as every other non-finite term is there; any other error as it is.
#[cold]
fn at_time(e: Error, t: f64) -> Error {
    match e {
        Error::NonFinite { name, .. } if name == INERTIA_FD.0 || name == POTENTIAL_FD.0 => {
            Error::NonFiniteState { time: t }
        }
        e => e,
    }
}

/// The entries of a matrix, for [`central_difference`].
fn matrix_values(m: &Matrix2<f64>) -> &[f64] {
    m.as_slice()
}

/// A number as a slice of one, for [`central_difference`].
fn scalar_values(x: &f64) -> &[f64] {
    std::slice::from_ref(x)
}

/// What the numerical derivatives of A name: a sample, the result.
const INERTIA_FD: (&str, &str) = (
    "inertia matrix A(q) (sampled for its numerical derivatives)",
    "numerical derivatives of the inertia matrix dA/dq",
);

/// What the numerical gradient of Π names: a sample, the result.
const POTENTIAL_FD: (&str, &str) = (
    "potential energy (sampled for its numerical gradient)",
    "numerical gradient of the potential energy",
);

/// Every term of Lagrange's equations at one state (t, q, q̇), as
/// [`LagrangeSystem::terms`] gives them together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LagrangeTerms {
    /// The inertia matrix A(q) (as [`LagrangeSystem::inertia`]).
    pub inertia: Matrix2<f64>,
    /// [∂A/∂q₁, ∂A/∂q₂] (as [`LagrangeSystem::inertia_derivatives`]).
    pub inertia_derivatives: [Matrix2<f64>; 2],
    /// The generalized forces Q(t, q, q̇) (as [`LagrangeSystem::forces`]).
    pub forces: Vector2<f64>,
    /// ∇Π(q) (as [`LagrangeSystem::potential_gradient`]).
    pub potential_gradient: Vector2<f64>,
    /// B(q) of Rayleigh's dissipation function (as [`LagrangeSystem::damping`]).
    pub damping: Matrix2<f64>,
}

/// A machine with two degrees of freedom described by Lagrange's equations of the 2nd kind.
///
/// Implement [`inertia`](Self::inertia) and [`forces`](Self::forces); everything else has a
/// default. The accelerations follow from [`accelerations`]. A machine whose terms share one
/// costly evaluation (the kinematics of a linkage) overrides [`terms`](Self::terms) as well,
/// so that a state costs that evaluation once.
pub trait LagrangeSystem {
    /// Names of the two generalized coordinates (used as column names).
    fn coordinate_names(&self) -> [&'static str; 2] {
        ["q1", "q2"]
    }

    /// The inertia matrix A(q) of T = ½ q̇ᵀ A q̇ (I11, I14, I44 in seed 003). It must be
    /// symmetric; only its symmetric part is used.
    ///
    /// # Errors
    /// When the machine cannot be assembled at `q` (or a configuration is singular).
    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>>;

    /// The partial derivatives [∂A/∂q₁, ∂A/∂q₂].
    ///
    /// The default is the documented numerical fallback: fourth-order central differences of
    /// [`inertia`](Self::inertia) with the step ε = 2·10⁻⁴·max(1, |qₖ|) in the units of qₖ
    /// (8 evaluations of A; about 10⁻¹² relative when A varies on a scale of one unit of qₖ,
    /// and within 10⁻⁸ of the analytic derivatives over the five-bar's workspace). Override it where the machine knows the
    /// derivatives (the five-bar from its second-order velocity analogs; constant-inertia
    /// gear drives with zeros).
    ///
    /// # Errors
    /// As [`inertia`](Self::inertia); for the default, [`Error::NonFinite`] for a non-finite
    /// q or a non-finite entry of A near q, [`Error::Overflow`] for a derivative that
    /// overflows (an A near f64's limit).
    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        let d = |k| central_difference(q, k, INERTIA_FD, matrix_values, |p| self.inertia(p));
        Ok([d(0)?, d(1)?])
    }

    /// The generalized forces Q(t, q, q̇) of the loads that are neither potential nor viscous
    /// (driving and resisting moments and forces), found from their virtual work.
    ///
    /// # Errors
    /// When a load cannot be evaluated (for example a table lookup out of range).
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>>;

    /// The potential energy Π(q), J (gravity, springs). Default: none.
    ///
    /// # Errors
    /// When the machine cannot be assembled at `q`.
    fn potential(&self, q: &Vector2<f64>) -> Result<f64> {
        let _ = q;
        Ok(0.0)
    }

    /// ∇Π(q), so that the potential forces are −∇Π. Default: fourth-order central
    /// differences of [`potential`](Self::potential) (as for the inertia derivatives).
    ///
    /// # Errors
    /// As [`potential`](Self::potential); for the default, [`Error::NonFinite`] for a
    /// non-finite q or Π near q, [`Error::Overflow`] for a gradient that overflows.
    fn potential_gradient(&self, q: &Vector2<f64>) -> Result<Vector2<f64>> {
        let d = |k| central_difference(q, k, POTENTIAL_FD, scalar_values, |p| self.potential(p));
        Ok(Vector2::new(d(0)?, d(1)?))
    }

    /// The matrix B(q) of Rayleigh's dissipation function Φ = ½ q̇ᵀ B q̇ (viscous friction,
    /// seed 003 eq. 6), so that the viscous generalized forces are −B q̇. Default: none.
    ///
    /// # Errors
    /// When the machine cannot be assembled at `q`.
    fn damping(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        let _ = q;
        Ok(Matrix2::zeros())
    }

    /// All the terms of the equations at the state (t, q, q̇) together: what
    /// [`accelerations`] needs, asked for once.
    ///
    /// The default calls [`inertia`](Self::inertia),
    /// [`inertia_derivatives`](Self::inertia_derivatives), [`forces`](Self::forces),
    /// [`potential_gradient`](Self::potential_gradient) and [`damping`](Self::damping) in
    /// this order, and checks each part before the next is evaluated as [`accelerations`]
    /// does (A symmetric positive-definite, then every other part finite), so that the first
    /// failure is the one reported. Override it where the parts share one evaluation (a
    /// linkage's kinematics): the override must give the same values as the separate methods
    /// and should report its failures in the same order; [`accelerations`] checks the parts
    /// again whatever an override returns.
    ///
    /// # Examples
    /// ```
    /// use nalgebra::{Matrix2, Vector2};
    /// use tmm::dynamics::LagrangeSystem;
    /// struct Spring;
    /// impl LagrangeSystem for Spring {
    ///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
    ///         Ok(Matrix2::new(2.0, 0.0, 0.0, 3.0))
    ///     }
    ///     fn forces(&self, _: f64, _: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
    ///         Ok(-qd)
    ///     }
    ///     fn potential(&self, q: &Vector2<f64>) -> tmm::Result<f64> {
    ///         Ok(0.5 * 4.0 * q[0] * q[0])
    ///     }
    /// }
    /// let q = Vector2::new(0.5, 0.0);
    /// let t = Spring.terms(0.0, &q, &Vector2::new(1.0, 2.0))?;
    /// assert_eq!(t.inertia, Spring.inertia(&q)?);
    /// assert_eq!(t.forces, Vector2::new(-1.0, -2.0));
    /// assert!((t.potential_gradient[0] - 2.0).abs() < 1e-10); // ∂(2 q₁²)/∂q₁ = 4 q₁
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// The first error of the separate methods; [`Error::NotPositiveDefinite`] (with t and q)
    /// when A(q) is not positive-definite, [`Error::Overflow`] when its determinant overflows;
    /// [`Error::NonFiniteState`] for a part that is not finite (a sample of A or Π that the
    /// numerical fallbacks take included).
    #[inline]
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        let non_finite = || Error::NonFiniteState { time: t };
        let inertia = self.inertia(q)?;
        checked_inertia(&inertia, t, q)?;
        let inertia_derivatives = self.inertia_derivatives(q).map_err(|e| at_time(e, t))?;
        let forces = self.forces(t, q, qd)?;
        if !all_finite(forces.as_slice()) {
            return Err(non_finite());
        }
        let potential_gradient = self.potential_gradient(q).map_err(|e| at_time(e, t))?;
        if !all_finite(potential_gradient.as_slice()) {
            return Err(non_finite());
        }
        let damping = self.damping(q)?;
        if !all_finite(damping.as_slice()) {
            return Err(non_finite());
        }
        Ok(LagrangeTerms {
            inertia,
            inertia_derivatives,
            forces,
            potential_gradient,
            damping,
        })
    }

    /// Names of the extra outputs of [`outputs`](Self::outputs) (for example the speed of
    /// every link of a gear drive). Default: none.
    fn output_names(&self) -> Vec<&'static str> {
        Vec::new()
    }

    /// Times at which the forces are not smooth (the nodes of a load tabulated in time), s.
    /// [`run`](super::run) steps exactly onto them, as onto
    /// [`RunOptions::breakpoints`](super::RunOptions::breakpoints), so that a kink (a change
    /// of slope) costs no order. A jump is only softened: the stages at the breakpoint see the
    /// one value the system gives there, which is the wrong side's for one of the two steps
    /// that meet there. Default: none.
    ///
    /// # Examples
    /// ```
    /// use nalgebra::{Matrix2, Vector2};
    /// use tmm::dynamics::LagrangeSystem;
    /// struct Kicked;
    /// impl LagrangeSystem for Kicked {
    ///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
    ///         Ok(Matrix2::identity())
    ///     }
    ///     fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
    ///         Ok(Vector2::new(if t < 0.5 { 0.0 } else { 1.0 }, 0.0))
    ///     }
    ///     fn breakpoints(&self) -> Vec<f64> {
    ///         vec![0.5]
    ///     }
    /// }
    /// assert_eq!(Kicked.breakpoints(), [0.5]);
    /// ```
    fn breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }

    /// The nodes of the system's kink arguments: `kinks()[k]` are the values of argument k
    /// (see [`kink_arguments`](Self::kink_arguments)) at which the forces are not smooth,
    /// for example the nodes of a load tabulated against the state (the landing gear's moment
    /// table against φ_H) or ±1 of a servo's demand over its limit (its clamps). Each argument
    /// has its own nodes (in any order, repeats allowed; an argument with none is never
    /// watched), so that switches of several loads are located each in its own right, however
    /// close in time. [`run`](super::run) finds, after each step, every argument that crossed
    /// one of its nodes, locates the earliest crossing inside the step and steps exactly onto
    /// it; the next step finds the next one. Default: none.
    ///
    /// # Breaking change
    /// This was one list of nodes of one scalar `kink_argument(t, q, q̇)`; a system with one
    /// argument now returns `vec![nodes]` and fills `out[0]`.
    ///
    /// # Examples
    /// Two clamped springs, each with a kink where its force saturates (|q_k| = 1): two
    /// arguments, q₁ and q₂, each with the nodes ±1.
    /// ```
    /// use nalgebra::{Matrix2, Vector2};
    /// use tmm::dynamics::{run, Dopri5, LagrangeSystem, Rk4, RunOptions, State};
    /// struct Clamped;
    /// impl LagrangeSystem for Clamped {
    ///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
    ///         Ok(Matrix2::identity())
    ///     }
    ///     fn forces(&self, _: f64, q: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
    ///         Ok(-q.map(|x| x.clamp(-1.0, 1.0)))
    ///     }
    ///     fn kinks(&self) -> Vec<Vec<f64>> {
    ///         vec![vec![-1.0, 1.0], vec![-1.0, 1.0]]
    ///     }
    ///     fn kink_arguments(
    ///         &self,
    ///         _: f64,
    ///         q: &Vector2<f64>,
    ///         _: &Vector2<f64>,
    ///         out: &mut [f64],
    ///     ) -> tmm::Result<()> {
    ///         // One entry per argument: refuse room for another number, never panic.
    ///         let [a, b] = out else {
    ///             return Err(tmm::Error::OutOfRange {
    ///                 name: "number of kink arguments",
    ///                 value: out.len() as f64,
    ///                 min: 2.0,
    ///                 max: 2.0,
    ///                 ends: tmm::Ends::Closed,
    ///             });
    ///         };
    ///         (*a, *b) = (q[0], q[1]);
    ///         Ok(())
    ///     }
    /// }
    /// // Both coordinates pass q = 1 going inwards, 1 ms apart: each switch is stepped onto.
    /// let start = State::new(0.0, Vector2::new(1.5, 1.501), Vector2::new(-1.0, -1.0));
    /// let mut opts = RunOptions::until(1.0, 0.1);
    /// let r = run(&Clamped, &Rk4, start, &opts)?;
    /// assert_eq!(r.steps, 12); // the grid's ten steps, the step 0.4 → 0.5 cut at each switch
    /// // An adaptive method records every step end: one lies exactly on each switch.
    /// let dp = run(&Clamped, &Dopri5::new(1e-8)?, start, &opts)?;
    /// let lands = |k: usize| dp.trajectory.q()[k].iter().any(|&q| (q - 1.0).abs() < 1e-12);
    /// assert!(lands(0) && lands(1));
    /// opts.locate_kinks = false; // stepped across: the grid t = 0.1·n only
    /// assert_eq!(run(&Clamped, &Rk4, start, &opts)?.steps, 10);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    fn kinks(&self) -> Vec<Vec<f64>> {
        Vec::new()
    }

    /// The kink arguments at a state: `out[k]` becomes argument k, whose nodes are
    /// [`kinks()[k]`](Self::kinks) (for the landing gear the one argument φ_H; for the
    /// five-bar each servo's demand over its limit). [`run`](super::run) passes exactly
    /// `kinks().len()` entries, each set to NaN before the call, and refuses a result that is
    /// not finite ([`Error::NonFiniteState`]): an argument the system leaves unset is an error,
    /// not a guess. All arguments are asked for at once, so that a system whose arguments
    /// share an evaluation (a linkage's kinematics) pays it once. Default: sets nothing (a
    /// machine without kinks is never asked).
    ///
    /// The systems of this crate refuse an `out` whose length is not the number of their
    /// arguments with [`Error::OutOfRange`], never a panic; a system of one's own should too.
    ///
    /// # Examples
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::dynamics::{machines::LandingGear, LagrangeSystem};
    /// let g = LandingGear::default();
    /// let q = Vector2::new(9.0, 27.0);
    /// let mut phi_h = [0.0];
    /// g.kink_arguments(0.0, &q, &Vector2::zeros(), &mut phi_h)?;
    /// assert_eq!(phi_h[0], g.phi_h(&q)?);
    /// assert!(g.kink_arguments(0.0, &q, &Vector2::zeros(), &mut [0.0; 2]).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// When the machine cannot be evaluated at this state, or `out` has the wrong length.
    fn kink_arguments(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        let _ = (t, q, qd, out);
        Ok(())
    }

    /// The number of the system's velocity-sign switches: resistances that oppose a speed
    /// σᵢ(t, q, q̇) (dry friction, a constant resisting moment on a link) and so jump where σᵢ
    /// changes sign. [`run`](super::run) locates every zero crossing of each σᵢ inside a step
    /// and steps exactly onto it (whether or not it locates the
    /// [`kinks`](Self::kinks)), then weighs the loads there
    /// ([`switch_loads`](Self::switch_loads)): where the resistance holds the drive the run
    /// ends, [`Outcome::Stuck`](super::Outcome::Stuck), instead of chattering about σ = 0
    /// with ever shorter steps; where it does not, the motion goes on (reverses). A start
    /// with σᵢ = 0 exactly is weighed too. Default: none.
    fn switches(&self) -> usize {
        0
    }

    /// The switch speeds σᵢ at a state into `out`: [`run`](super::run) passes exactly
    /// [`switches`](Self::switches) entries, each NaN before the call, and refuses a result
    /// that is not finite. Default: sets nothing (a system without switches is never asked).
    ///
    /// # Errors
    /// When the machine cannot be evaluated at this state, or `out` has the wrong length.
    fn switch_speeds(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        let _ = (t, q, qd, out);
        Ok(())
    }

    /// The generalized force of switch `i`'s resistance at a state as it is while σᵢ has the
    /// sign of `direction` (+1 or −1), whatever σᵢ is there: the part of
    /// [`forces`](Self::forces) that jumps with σᵢ's sign. Within a step [`run`](super::run)
    /// holds each resistance in the direction it had at the step's start (or, starting at
    /// σᵢ = 0, in the direction the motion breaks away), so that σᵢ passes zero smoothly and
    /// its crossing is located exactly rather than chattered about; where a stage's σᵢ has
    /// the other sign, the run replaces that side's force by this one.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a switch that does not exist (the default: none does); when
    /// the machine cannot be evaluated at this state.
    fn switch_force(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        direction: f64,
    ) -> Result<Vector2<f64>> {
        let _ = (t, q, qd, direction);
        Err(Error::OutOfRange {
            name: "switch index",
            value: i as f64,
            min: 0.0,
            max: self.switches() as f64 - 1.0,
            ends: crate::Ends::Closed,
        })
    }

    /// The loads along switch `i` at a state where its speed σᵢ vanishes (see
    /// [`SwitchLoads`]): the drive without the switch's own resistance, and the resistance's
    /// breakaway loads each way.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a switch that does not exist (the default: none does); when
    /// the machine cannot be evaluated at this state.
    fn switch_loads(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<SwitchLoads> {
        let _ = (t, q, qd);
        Err(Error::OutOfRange {
            name: "switch index",
            value: i as f64,
            min: 0.0,
            max: self.switches() as f64 - 1.0,
            ends: crate::Ends::Closed,
        })
    }

    /// The coordinate that switch `i` stops when its resistance holds it, where the run may
    /// go on with that coordinate held at rest: `Some(k)` when σᵢ is coordinate k's rate
    /// times a factor that does not vanish (σᵢ = cₖ(q)·q̇ₖ, an input's own bearing), so that
    /// σᵢ = 0 is q̇ₖ = 0 and holding it is q̈ₖ = 0. Then where σᵢ reaches zero and the
    /// resistance holds ([`SwitchLoads::holds`]) [`run`](super::run) sets q̇ₖ = 0 and goes on
    /// with row k of the equations replaced by q̈ₖ = 0 ([`held_terms`](Self::held_terms)), its
    /// generalized force a reaction, and releases the coordinate where the drive along σᵢ
    /// ([`switch_loads`](Self::switch_loads), evaluated with the coordinate held) leaves the
    /// breakaway loads: a kink located inside the step, after which the motion goes the
    /// drive's way. A hold that leaves the whole machine at rest goes on only when the loads
    /// change with time ([`forces_depend_on_time`](Self::forces_depend_on_time)); else the run
    /// ends [`Outcome::Stuck`](super::Outcome::Stuck) there, as it does for a switch without
    /// a coordinate. Default: `None` for every switch (a stick ends the run).
    fn switch_holds(&self, i: usize) -> Option<usize> {
        let _ = i;
        None
    }

    /// The terms of the equations for the motion with the coordinates `held[k]` at rest
    /// (q̇ₖ = 0 and q̈ₖ = 0): A, ∂A/∂q, ∇Π and B as [`terms`](Self::terms), and the applied
    /// forces Q *of that motion*. The held coordinates' rows are replaced by q̈ₖ = 0 in the
    /// run; the generalized force that holds coordinate k is the reaction
    /// μₖ = (A·q̈ + c + ∇Π + B·q̇ − Q)ₖ. Forces that depend on the accelerations (a linkage's
    /// joint friction, which the reactions carry) must be solved with q̈ₖ = 0 held here.
    /// Default: [`terms`](Self::terms), right for forces that depend on (t, q, q̇) only.
    ///
    /// # Errors
    /// As [`terms`](Self::terms).
    fn held_terms(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        held: [bool; 2],
    ) -> Result<LagrangeTerms> {
        let _ = held;
        self.terms(t, q, qd)
    }

    /// Whether the generalized forces at rest may change with time alone (a load or motor
    /// law of t): then a machine that comes to a whole rest held by its resistances
    /// ([`switch_holds`](Self::switch_holds)) is kept at rest and watched, and breaks away
    /// where the drive first leaves the breakaway loads; else nothing changes at rest and the
    /// run ends [`Outcome::Stuck`](super::Outcome::Stuck) (no chattering, bounded cost).
    /// Default: `false`.
    fn forces_depend_on_time(&self) -> bool {
        false
    }

    /// Extra outputs at a state, appended to `out` in the order of
    /// [`output_names`](Self::output_names).
    ///
    /// # Errors
    /// When the machine cannot be evaluated at this state.
    fn outputs(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        let _ = (t, q, qd, out);
        Ok(())
    }

    /// The number of the system's lock measures (see
    /// [`lock_measures`](Self::lock_measures)). Default: none, and [`run`](super::run)
    /// never asks for them (a run of such a system takes exactly the steps it took before
    /// the measures existed).
    fn locks(&self) -> usize {
        0
    }

    /// The lock measures at the position `q` into `out` (exactly [`locks`](Self::locks)
    /// entries, each NaN before the call): one number per lock (a described linkage's RRR or
    /// RRP dyad), positive away from it and at most zero in the band where the system
    /// refuses a state ([`Error::DeadCentre`]; for a linkage |det| − 10⁻³). A coarse step
    /// can carry the motion across a narrow band without any of its stages landing in it:
    /// a two-input linkage passes its dyad's dead centre where the measure, |det|, falls to
    /// zero and rises again in a V. [`run`](super::run) reads the measures at each step's
    /// ends with their rates along the motion; where a measure falls at the step's start
    /// and rises at its end, its lower end within the rates' difference times the step of
    /// zero (a V whose tip the step jumped), or a measure changes sign, it takes the step again in halves, down to where a step or state is refused, and
    /// locates the stop there as at any dead centre; where none is, the step stands as it
    /// was. Default: sets nothing.
    ///
    /// # Errors
    /// When the position cannot be evaluated, or `out` has the wrong length.
    fn lock_measures(&self, q: &Vector2<f64>, out: &mut [f64]) -> Result<()> {
        let _ = (q, out);
        Ok(())
    }
}

/// Checks that `out` has room for exactly the `n` kink arguments of a system (see
/// [`LagrangeSystem::kink_arguments`]): an error naming both counts otherwise.
pub(crate) fn kink_slots(out: &[f64], n: usize) -> Result<()> {
    if out.len() == n {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name: "kink arguments asked for (the system's count)",
            value: out.len() as f64,
            min: n as f64,
            max: n as f64,
            ends: crate::Ends::Closed,
        })
    }
}

/// The velocity-dependent (Coriolis and centrifugal) terms cᵢ = Σⱼₖ Γᵢⱼₖ q̇ⱼ q̇ₖ with
/// Γᵢⱼₖ = ½(∂Aᵢⱼ/∂qₖ + ∂Aᵢₖ/∂qⱼ − ∂Aⱼₖ/∂qᵢ).
///
/// # Examples
/// A point mass m on a rotating arm in polar coordinates (r, θ): A = diag(m, m r²), and the
/// terms are (−m r θ̇², 2 m r ṙ θ̇): centrifugal and Coriolis.
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// let (m, r) = (2.0, 0.5);
/// let d_a = [Matrix2::new(0.0, 0.0, 0.0, 2.0 * m * r), Matrix2::zeros()];
/// let c = tmm::dynamics::christoffel_terms(&d_a, &Vector2::new(3.0, 4.0)).unwrap();
/// assert!((c[0] - (-m * r * 16.0)).abs() < 1e-12);
/// assert!((c[1] - 2.0 * m * r * 3.0 * 4.0).abs() < 1e-12);
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite derivative or speed; [`Error::Overflow`] when a term
/// overflows.
pub fn christoffel_terms(d_a: &[Matrix2<f64>; 2], qd: &Vector2<f64>) -> Result<Vector2<f64>> {
    for m in d_a {
        for &v in m.iter() {
            finite("dA/dq", v)?;
        }
    }
    finite2(["q1_dot", "q2_dot"], *qd)?;
    let mut c = Vector2::zeros();
    for i in 0..2 {
        let mut s = 0.0;
        for j in 0..2 {
            for k in 0..2 {
                let g = 0.5 * (d_a[k][(i, j)] + d_a[j][(i, k)] - d_a[i][(j, k)]);
                s += g * qd[j] * qd[k];
            }
        }
        c[i] = s;
    }
    computed_all("Christoffel terms", c.iter())?;
    Ok(c)
}

/// The Christoffel terms of [`christoffel_terms`] for a q̇ known to be finite, with one check
/// of all the derivatives and of the result (`None` where [`christoffel_terms`] fails, for
/// which [`accelerations`] reports the same error: a non-finite state). The same sums in the
/// same order, so the same bits.
#[inline(always)]
fn christoffel_fast(d_a: &[Matrix2<f64>; 2], qd: &Vector2<f64>) -> Option<Vector2<f64>> {
    let mut c = Vector2::zeros();
    for i in 0..2 {
        let mut s = 0.0;
        for j in 0..2 {
            for k in 0..2 {
                let g = 0.5 * (d_a[k][(i, j)] + d_a[j][(i, k)] - d_a[i][(j, k)]);
                s += g * qd[j] * qd[k];
            }
        }
        c[i] = s;
    }
    let (d0, d1) = (&d_a[0], &d_a[1]);
    let ok = [
        d0[0], d0[1], d0[2], d0[3], d1[0], d1[1], d1[2], d1[3], c[0], c[1],
    ]
    .iter()
    .fold(true, |ok, v| ok & v.is_finite());
    ok.then_some(c)
}

/// Checks that A is symmetric positive-definite (A₁₁ > 0 and det A > 0) and returns its
/// symmetric part and determinant; the error says where (time and coordinates).
#[inline(always)]
pub(crate) fn checked_inertia(
    a: &Matrix2<f64>,
    t: f64,
    q: &Vector2<f64>,
) -> Result<(Matrix2<f64>, f64)> {
    let a12 = 0.5 * (a[(0, 1)] + a[(1, 0)]);
    let a = Matrix2::new(a[(0, 0)], a12, a12, a[(1, 1)]);
    let det = a[(0, 0)] * a[(1, 1)] - a12 * a12;
    // Relative test: a determinant that is rounding noise of the products counts as zero.
    let scale = (a[(0, 0)] * a[(1, 1)]).abs().max(a12 * a12);
    if a.iter().all(|x| x.is_finite()) && !scale.is_finite() {
        // Finite entries whose products overflow: too large for f64, not indefinite.
        return Err(crate::Error::Overflow {
            what: "the inertia matrix's determinant",
        });
    }
    if !(a[(0, 0)] > 0.0 && a[(1, 1)] > 0.0 && det > 1e-14 * scale && det.is_finite()) {
        return Err(not_positive_definite(t, q, det));
    }
    Ok((a, det))
}

#[cold]
#[inline(never)]
fn not_positive_definite(t: f64, q: &Vector2<f64>, det: f64) -> Error {
    Error::NotPositiveDefinite {
        at: format!("t = {t} s, q = ({}, {})", q[0], q[1]),
        det,
    }
}

/// The accelerations q̈ from A(q) q̈ = Q − c(q, q̇) − ∇Π − B q̇ (see the module docs).
///
/// # Errors
/// [`Error::NotPositiveDefinite`] when A(q) is not positive-definite (the message gives t and
/// q); [`Error::NonFiniteState`] when the state or the result is not finite; any error of the
/// system's own methods.
///
/// # Examples
/// A free body of mass 2 kg pushed by 10 N along q₁ and a 3 kg·m² rotor under 6 N·m:
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{accelerations, LagrangeSystem};
/// struct Two;
/// impl LagrangeSystem for Two {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::new(2.0, 0.0, 0.0, 3.0))
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::new(10.0, 6.0))
///     }
/// }
/// let a = accelerations(&Two, 0.0, &Vector2::zeros(), &Vector2::zeros()).unwrap();
/// assert!((a - Vector2::new(5.0, 2.0)).norm() < 1e-12);
/// ```
#[inline]
pub fn accelerations<S: LagrangeSystem + ?Sized>(
    sys: &S,
    t: f64,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> Result<Vector2<f64>> {
    accelerations_inline(sys, t, q, qd)
}

/// [`accelerations`], always inlined: the crate's integrators call it four to seven times
/// a step, and each call kept out of line returns its `Result` through memory (a per cent
/// or two of a step on the five-bar).
#[inline(always)]
pub(crate) fn accelerations_inline<S: LagrangeSystem + ?Sized>(
    sys: &S,
    t: f64,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> Result<Vector2<f64>> {
    // The terms stay where `terms` wrote them: only q̈ leave (moving the terms into a
    // returned pair, to drop them at once, cost some ten instructions an evaluation).
    if !all_finite(&[t, q[0], q[1], qd[0], qd[1]]) {
        return Err(Error::NonFiniteState { time: t });
    }
    accelerations_of(&sys.terms(t, q, qd)?, t, q, qd)
}

/// q̈ with the Lagrange terms they came from (checked as [`accelerations`] checks them).
#[inline(always)]
fn accelerations_and_terms<S: LagrangeSystem + ?Sized>(
    sys: &S,
    t: f64,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> Result<(Vector2<f64>, LagrangeTerms)> {
    if !all_finite(&[t, q[0], q[1], qd[0], qd[1]]) {
        return Err(Error::NonFiniteState { time: t });
    }
    let terms = sys.terms(t, q, qd)?;
    Ok((accelerations_of(&terms, t, q, qd)?, terms))
}

/// q̈ from the Lagrange terms at (t, q, q̇), the terms checked first.
#[inline(always)]
fn accelerations_of(
    terms: &LagrangeTerms,
    t: f64,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> Result<Vector2<f64>> {
    let non_finite = || Error::NonFiniteState { time: t };
    // One call for every part (a linkage evaluates its kinematics once). The default
    // `terms` checks each part before it evaluates the next, so that the first failure is
    // the one reported; the same checks run again here, in the same order, for an override:
    // a NaN a system lets through is named (as a non-finite state at t), not hidden in q̈.
    let (a, det) = checked_inertia(&terms.inertia, t, q)?;
    if !(all_finite(terms.forces.as_slice())
        & all_finite(terms.potential_gradient.as_slice())
        & all_finite(terms.damping.as_slice()))
    {
        return Err(non_finite());
    }
    let c = christoffel_fast(&terms.inertia_derivatives, qd).ok_or_else(non_finite)?;
    let rhs = terms.forces - c - terms.potential_gradient - terms.damping * qd;
    // Cramer's rule on the 2×2 system: the determinant is I11·I44 − I14² of the seed.
    let acc = Vector2::new(
        (rhs[0] * a[(1, 1)] - rhs[1] * a[(0, 1)]) / det,
        (rhs[1] * a[(0, 0)] - rhs[0] * a[(0, 1)]) / det,
    );
    if all_finite(acc.as_slice()) {
        Ok(acc)
    } else {
        Err(non_finite())
    }
}

/// What a recorded row needs of the Lagrange terms at a state.
pub(crate) struct RowTerms {
    /// q̈, as [`accelerations`].
    pub acceleration: Vector2<f64>,
    /// T = ½ q̇ᵀ A q̇, as [`kinetic_energy`].
    pub kinetic: f64,
    /// Q·q̇, as [`powers`].
    pub applied: f64,
    /// q̇ᵀ B q̇, as [`powers`].
    pub dissipated: f64,
}

/// q̈, the kinetic energy and the powers of a state from one evaluation of the terms (a
/// linkage evaluates its kinematics once for all four, not three times).
///
/// # Errors
/// As [`accelerations`]; [`Error::NonFiniteState`] for an energy or a power that overflows.
pub(crate) fn row_terms<S: LagrangeSystem + ?Sized>(sys: &S, s: &State) -> Result<RowTerms> {
    let (acceleration, terms) = accelerations_and_terms(sys, s.t, &s.q, &s.qd)?;
    let qd = &s.qd;
    let kinetic = 0.5 * qd.dot(&(terms.inertia * qd));
    let applied = terms.forces.dot(qd);
    let dissipated = qd.dot(&(terms.damping * qd));
    if all_finite(&[kinetic, applied, dissipated]) {
        Ok(RowTerms {
            acceleration,
            kinetic,
            applied,
            dissipated,
        })
    } else {
        Err(Error::NonFiniteState { time: s.t })
    }
}

/// `true` when every value is finite (one pass, no early exit).
#[inline(always)]
fn all_finite(v: &[f64]) -> bool {
    v.iter().fold(true, |ok, x| ok & x.is_finite())
}

/// Checks that q and q̇ are finite, naming the component that is not.
fn finite_q_qd(q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<()> {
    finite2(["q1", "q2"], *q)?;
    finite2(["q1_dot", "q2_dot"], *qd)
}

/// The kinetic energy T = ½ q̇ᵀ A(q) q̇, J.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite q or q̇ (or a T that overflows); as
/// [`LagrangeSystem::inertia`].
pub fn kinetic_energy<S: LagrangeSystem + ?Sized>(
    sys: &S,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> Result<f64> {
    finite_q_qd(q, qd)?;
    finite("kinetic energy T", 0.5 * qd.dot(&(sys.inertia(q)? * qd)))
}

/// The power balance at a state: the power Q·q̇ of the applied loads and the power
/// q̇ᵀ B q̇ = 2Φ lost to viscous friction, W. Along a motion,
/// d(T + Π)/dt = applied − dissipated.
///
/// It asks for Q and B only, not for [`LagrangeSystem::terms`]: the default `terms` would
/// also build A and its numerical derivatives (nine evaluations of A) and refuse an A that is
/// not positive-definite, neither of which a power needs.
///
/// # Errors
/// [`Error::NonFiniteState`] naming t for a non-finite t, q or q̇, or a power that
/// overflows; as [`LagrangeSystem::forces`] and [`LagrangeSystem::damping`].
pub fn powers<S: LagrangeSystem + ?Sized>(
    sys: &S,
    t: f64,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> Result<(f64, f64)> {
    let non_finite = Error::NonFiniteState { time: t };
    if !State::new(t, *q, *qd).is_finite() {
        return Err(non_finite);
    }
    let forces = sys.forces(t, q, qd)?;
    let damping = sys.damping(q)?;
    if !forces.iter().chain(damping.iter()).all(|v| v.is_finite()) {
        return Err(non_finite);
    }
    let applied = forces.dot(qd);
    let dissipated = qd.dot(&(damping * qd));
    if applied.is_finite() && dissipated.is_finite() {
        Ok((applied, dissipated))
    } else {
        Err(non_finite)
    }
}
