//! The one interface behind which the integrators sit.

use nalgebra::{Vector2, Vector4};

use super::system::{accelerations_inline, LagrangeSystem, State};
use crate::error::{positive, Error, Result};

/// The state as one first-order vector y = (q₁, q₂, q̇₁, q̇₂).
#[inline]
pub(crate) fn pack(s: &State) -> Vector4<f64> {
    Vector4::new(s.q[0], s.q[1], s.qd[0], s.qd[1])
}

/// The inverse of [`pack`].
#[inline]
pub(crate) fn unpack(t: f64, y: &Vector4<f64>) -> State {
    State::new(t, Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]))
}

/// The first-order right-hand side ẏ = (q̇, q̈(t, q, q̇)). Always inlined: a stage of a
/// step then calls [`accelerations`] directly, with no wrapper call returning a `Result` on
/// the way (the wrapper cost a few per cent of a run on a cheap right-hand side).
#[inline(always)]
pub(crate) fn rhs<S: LagrangeSystem + ?Sized>(
    sys: &S,
    t: f64,
    y: &Vector4<f64>,
) -> Result<Vector4<f64>> {
    let q = Vector2::new(y[0], y[1]);
    let qd = Vector2::new(y[2], y[3]);
    let a = accelerations_inline(sys, t, &q, &qd)?;
    Ok(Vector4::new(qd[0], qd[1], a[0], a[1]))
}

/// The handed-on accelerations at a step's start when there are finite ones: a method whose
/// first stage is q̈ there takes them instead of evaluating (a non-finite pair counts as
/// none handed on).
#[inline(always)]
pub(crate) fn handed_acceleration(from: Option<Handover>) -> Option<Vector2<f64>> {
    from.and_then(|f| f.acceleration)
        .filter(|a| a[0].is_finite() && a[1].is_finite())
}

/// A fixed-step method's accepted step: exactly `h`, the same `h` proposed next, nothing
/// handed on.
#[inline(always)]
pub(crate) fn fixed_step(state: State, h: f64, evaluations: usize) -> Advance {
    Advance {
        state,
        h_next: h,
        evaluations,
        handover: Handover::default(),
    }
}

/// Checks the step size (finite, positive) and the start state (finite).
#[inline]
pub(crate) fn check_step(s: &State, h: f64) -> Result<()> {
    positive("step size h", h)?;
    if s.is_finite() {
        Ok(())
    } else {
        Err(Error::NonFiniteState { time: s.t })
    }
}

/// Checks that a state produced by a step is finite; the error names its time.
#[inline]
pub(crate) fn check_result(s: State) -> Result<State> {
    if s.is_finite() {
        Ok(s)
    } else {
        Err(Error::NonFiniteState { time: s.t })
    }
}

/// What an accepted step hands on to the next step, which starts from its end state.
///
/// An adaptive method remembers more than the state between steps: Dormand–Prince's last
/// stage is the next step's first ("first same as last"), and its step-size controller uses
/// the error of the step before as well as the error of the current one (a PI controller,
/// see [`Dopri5`](super::Dopri5)). The stepper itself holds no state (it is `Copy` and may be
/// shared between runs), so the caller carries this from one [`Advance`] to the next call of
/// [`Stepper::advance_from`] or [`Stepper::advance_dense`]; [`run`](super::run) does.
///
/// The default (both `None`) is what a first step knows: nothing.
///
/// # Breaking change
/// Before the PI controller, [`Advance`] carried the accelerations alone (a field
/// `end_acceleration`) and `advance_from`/`advance_dense` took `Option<Vector2<f64>>`: write
/// `adv.handover.acceleration` for the former and pass `Some(adv.handover)` (or
/// `Some(Handover { acceleration: Some(a), ..Handover::default() })`) for the latter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Handover {
    /// The accelerations q̈ at the end state when the method evaluated them anyway (the last
    /// stage of Dormand–Prince), else `None`. They save the next step its first evaluation,
    /// so they must belong to the state the next step starts from exactly: a caller that moves
    /// the end (snaps its time onto a breakpoint, where the forces may jump) sets them to
    /// `None`.
    pub acceleration: Option<Vector2<f64>>,
    /// The error norm of the accepted step (at most 1; see [`Dopri5`](super::Dopri5)), the
    /// memory of a PI step-size controller; `None` for a fixed-step method. A value that is
    /// not finite and non-negative is ignored (treated as `None`).
    pub error_norm: Option<f64>,
}

/// One accepted step of a [`Stepper`].
///
/// # Breaking change
/// The field `end_acceleration: Option<Vector2<f64>>` became
/// [`handover`](Self::handover)`.acceleration`, beside the error norm the step-size controller
/// now carries from step to step (see [`Handover`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Advance {
    /// The state at the end of the step.
    pub state: State,
    /// The step size proposed for the next step (the same h for fixed-step methods).
    pub h_next: f64,
    /// Evaluations of the accelerations spent (rejected trial steps included).
    pub evaluations: usize,
    /// What the step hands on to the next one: passed to the next
    /// [`Stepper::advance_from`] as `Some(handover)`, the accelerations at
    /// [`state`](Self::state) save that step its first evaluation and the error norm informs
    /// its step-size control. Fixed-step methods hand on nothing (the default).
    pub handover: Handover,
}

/// The continuous extension ("dense output") of one accepted step: the state anywhere in the
/// step without stepping there. A method that has one names it as its [`Stepper::Dense`] and
/// returns it from [`Stepper::advance_dense`]; [`run`](super::run) reads it to record the
/// requested [`times`](super::RunOptions::times) and to find where a kink's argument crosses
/// its node, knowing of no method in particular.
///
/// # Breaking change
/// [`Stepper::advance_dense`] returned `Option<DenseOutput>` (Dormand–Prince's extension, the
/// one concrete type) for every method; it returns `Option<Self::Dense>`, and an implementor of
/// [`Stepper`] names its extension (`type Dense = NoExtension;` for a method without one).
///
/// # Examples
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{ContinuousExtension, Dopri5, LagrangeSystem, State, Stepper};
/// struct Coasting;
/// impl LagrangeSystem for Coasting {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::identity())
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::zeros())
///     }
/// }
/// /// The state halfway through a step, from any method's extension.
/// fn halfway<E: ContinuousExtension>(e: &E) -> tmm::Result<State> {
///     e.at(0.5 * (e.start() + e.end()))
/// }
/// let s = State::new(0.0, Vector2::zeros(), Vector2::new(3.0, 0.0));
/// let (adv, dense) = Dopri5::new(1e-9).unwrap().advance_dense(&Coasting, &s, 0.5, None).unwrap();
/// let mid = halfway(&dense.unwrap()).unwrap();
/// assert!((mid.q[0] - 1.5 * adv.state.t).abs() < 1e-12);
/// ```
pub trait ContinuousExtension {
    /// The time at the start of the step, s.
    fn start(&self) -> f64;

    /// The time at the end of the step, s.
    fn end(&self) -> f64;

    /// The state at time `t` in [[`start`](Self::start), [`end`](Self::end)], carrying `t`
    /// exactly.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `t`; [`Error::OutOfRange`] for `t` outside the
    /// step; [`Error::NonFiniteState`] when the interpolated state overflows.
    fn at(&self, t: f64) -> Result<State>;

    /// Moves the end time to `t1`, the end state staying the step's: [`run`](super::run)
    /// snaps a step's end onto a breakpoint or the final time when they differ by rounding,
    /// and reads the extension up to the snapped end (a time past the step's own end by that
    /// rounding is given by the same polynomial).
    fn set_end(&mut self, t1: f64);
}

/// The continuous extension of a method that has none ([`Rk4`](super::Rk4),
/// [`FiniteIncrement`](super::FiniteIncrement)): a type with no values, so that such a
/// method's [`Stepper::advance_dense`] can only return `None`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoExtension {}

impl ContinuousExtension for NoExtension {
    fn start(&self) -> f64 {
        match *self {}
    }
    fn end(&self) -> f64 {
        match *self {}
    }
    fn at(&self, _: f64) -> Result<State> {
        match *self {}
    }
    fn set_end(&mut self, _: f64) {
        match *self {}
    }
}

/// An integrator of Lagrange's equations.
///
/// Fixed-step methods implement [`step`](Self::step) only; an adaptive method also overrides
/// [`advance`](Self::advance), which chooses the step size from a requested accuracy, and
/// [`is_adaptive`](Self::is_adaptive); a method with a continuous extension overrides
/// [`advance_dense`](Self::advance_dense) and [`has_dense_output`](Self::has_dense_output),
/// and names its extension as [`Dense`](Self::Dense).
pub trait Stepper {
    /// The step's continuous extension that [`advance_dense`](Self::advance_dense) returns:
    /// [`NoExtension`] for a method without one (then `advance_dense` gives `None`).
    type Dense: ContinuousExtension;

    /// A short name, for tables and charts.
    fn name(&self) -> &'static str;

    /// The order of accuracy of the global error (1 for finite increments, 4 for RK4, 5 for
    /// Dormand–Prince).
    fn order(&self) -> u32;

    /// Evaluations of the accelerations in one [`step`](Self::step).
    fn evaluations_per_step(&self) -> usize;

    /// One step of exactly `h` from `s` (no error control).
    ///
    /// # Errors
    /// [`Error::NonPositive`] for a step size that is not positive (or
    /// [`Error::NonFinite`] for a non-finite one), [`Error::NonFiniteState`] naming the time
    /// when the state stops being finite, and any error of the system.
    fn step<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<State>;

    /// One accepted step, at most `h` long. Fixed-step methods take exactly `h`.
    ///
    /// # Errors
    /// As [`step`](Self::step).
    #[inline(always)]
    fn advance<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<Advance> {
        Ok(fixed_step(
            self.step(sys, s, h)?,
            h,
            self.evaluations_per_step(),
        ))
    }

    /// As [`advance`](Self::advance), continuing from the step that ended at `s`: `from` is
    /// that step's [`Advance::handover`] (`None`, like `Some(Handover::default())`, for a first
    /// step). A method whose first stage is q̈ at `s` uses the handed-on accelerations instead
    /// of evaluating again (they must belong to `s` exactly), and an adaptive method's
    /// step-size controller uses the handed-on error norm; the default ignores both.
    ///
    /// # Breaking change
    /// `from` was `start_acceleration: Option<Vector2<f64>>`, the accelerations alone (see
    /// [`Handover`]).
    ///
    /// # Errors
    /// As [`step`](Self::step).
    #[inline(always)]
    fn advance_from<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
    ) -> Result<Advance> {
        let _ = from;
        self.advance(sys, s, h)
    }

    /// `true` for a method whose first stage is q̈ at the start state and that takes it from
    /// [`Handover::acceleration`] in [`advance_from`](Self::advance_from) (RK4, finite
    /// increments, Dormand–Prince); `false` (the default) otherwise. [`run`](super::run)
    /// evaluates q̈ at every recorded state for the trajectory anyway: to such a method it
    /// hands them on when the step before did not, saving the next step an evaluation (the
    /// run still counts it, once, among the evaluations the method used).
    ///
    /// # Examples
    /// ```
    /// use tmm::dynamics::{Rk4, Stepper};
    /// assert!(Rk4.uses_start_acceleration());
    /// ```
    fn uses_start_acceleration(&self) -> bool {
        false
    }

    /// `true` for a method that chooses its own step sizes (its [`Advance::h_next`] is a
    /// proposal); `false` (the default) for a fixed-step method. [`run`](super::run) keeps a
    /// fixed-step method on its grid t₀ + n·h: a step cut short at a breakpoint is followed by
    /// the rest of it.
    ///
    /// # Examples
    /// ```
    /// use tmm::dynamics::{Dopri5, Rk4, Stepper};
    /// assert!(Dopri5::new(1e-8).unwrap().is_adaptive() && !Rk4.is_adaptive());
    /// ```
    fn is_adaptive(&self) -> bool {
        false
    }

    /// `true` when [`advance_dense`](Self::advance_dense) gives the step's continuous
    /// extension; `false` (the default) otherwise. [`run`](super::run) records requested
    /// times by the extension when there is one, and steps onto them when there is not.
    ///
    /// # Examples
    /// ```
    /// use tmm::dynamics::{Dopri5, FiniteIncrement, Stepper};
    /// assert!(Dopri5::new(1e-8).unwrap().has_dense_output());
    /// assert!(!FiniteIncrement.has_dense_output());
    /// ```
    fn has_dense_output(&self) -> bool {
        false
    }

    /// As [`advance_from`](Self::advance_from), with the step's continuous extension when
    /// the method has one (the default has none: `None`).
    ///
    /// # Breaking change
    /// `from` was `start_acceleration: Option<Vector2<f64>>` (see [`Handover`]).
    ///
    /// # Examples
    /// ```
    /// use nalgebra::{Matrix2, Vector2};
    /// use tmm::dynamics::{LagrangeSystem, Rk4, State, Stepper};
    /// struct Free;
    /// impl LagrangeSystem for Free {
    ///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
    ///         Ok(Matrix2::identity())
    ///     }
    ///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
    ///         Ok(Vector2::zeros())
    ///     }
    /// }
    /// let s = State::new(0.0, Vector2::zeros(), Vector2::new(1.0, 0.0));
    /// let (adv, dense) = Rk4.advance_dense(&Free, &s, 0.5, None).unwrap();
    /// assert!(dense.is_none() && adv.state.q[0] == 0.5);
    /// ```
    ///
    /// # Errors
    /// As [`step`](Self::step).
    fn advance_dense<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
    ) -> Result<(Advance, Option<Self::Dense>)> {
        Ok((self.advance_from(sys, s, h, from)?, None))
    }
}
