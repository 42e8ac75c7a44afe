//! The one interface behind which the integrators sit.

use nalgebra::{Vector2, Vector4};

use super::dopri::DenseOutput;
use super::system::{accelerations, LagrangeSystem, State};
use crate::error::{positive, Error, Result};

/// The state as one first-order vector y = (q₁, q₂, q̇₁, q̇₂).
pub(crate) fn pack(s: &State) -> Vector4<f64> {
    Vector4::new(s.q[0], s.q[1], s.qd[0], s.qd[1])
}

/// The inverse of [`pack`].
pub(crate) fn unpack(t: f64, y: &Vector4<f64>) -> State {
    State::new(t, Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]))
}

/// The first-order right-hand side ẏ = (q̇, q̈(t, q, q̇)).
pub(crate) fn rhs<S: LagrangeSystem + ?Sized>(
    sys: &S,
    t: f64,
    y: &Vector4<f64>,
) -> Result<Vector4<f64>> {
    let q = Vector2::new(y[0], y[1]);
    let qd = Vector2::new(y[2], y[3]);
    let a = accelerations(sys, t, &q, &qd)?;
    Ok(Vector4::new(qd[0], qd[1], a[0], a[1]))
}

/// Checks the step size (finite, positive) and the start state (finite).
pub(crate) fn check_step(s: &State, h: f64) -> Result<()> {
    positive("step size h", h)?;
    if s.is_finite() {
        Ok(())
    } else {
        Err(Error::NonFiniteState { time: s.t })
    }
}

/// Checks that a state produced by a step is finite; the error names its time.
pub(crate) fn check_result(s: State) -> Result<State> {
    if s.is_finite() {
        Ok(s)
    } else {
        Err(Error::NonFiniteState { time: s.t })
    }
}

/// One accepted step of a [`Stepper`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Advance {
    /// The state at the end of the step.
    pub state: State,
    /// The step size proposed for the next step (the same h for fixed-step methods).
    pub h_next: f64,
    /// Evaluations of the accelerations spent (rejected trial steps included).
    pub evaluations: usize,
    /// The accelerations q̈ at [`state`](Self::state) when the method evaluated them anyway
    /// (the last stage of Dormand–Prince: "first same as last"), else `None`. Passed to the
    /// next [`Stepper::advance_from`], they save that step its first evaluation.
    pub end_acceleration: Option<Vector2<f64>>,
}

/// An integrator of Lagrange's equations.
///
/// Fixed-step methods implement [`step`](Self::step) only; an adaptive method also overrides
/// [`advance`](Self::advance), which chooses the step size from a requested accuracy, and
/// [`is_adaptive`](Self::is_adaptive); a method with a continuous extension overrides
/// [`advance_dense`](Self::advance_dense) and [`has_dense_output`](Self::has_dense_output).
pub trait Stepper {
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
    fn advance<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<Advance> {
        Ok(Advance {
            state: self.step(sys, s, h)?,
            h_next: h,
            evaluations: self.evaluations_per_step(),
            end_acceleration: None,
        })
    }

    /// As [`advance`](Self::advance), given the accelerations q̈ at `s` when the caller has
    /// them (the [`end_acceleration`](Advance::end_acceleration) of the step that ended at
    /// `s`). A method whose first stage is q̈ at `s` uses them instead of evaluating again;
    /// the default ignores them. They must belong to `s` exactly.
    ///
    /// # Errors
    /// As [`step`](Self::step).
    fn advance_from<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        start_acceleration: Option<Vector2<f64>>,
    ) -> Result<Advance> {
        let _ = start_acceleration;
        self.advance(sys, s, h)
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
        start_acceleration: Option<Vector2<f64>>,
    ) -> Result<(Advance, Option<DenseOutput>)> {
        Ok((self.advance_from(sys, s, h, start_acceleration)?, None))
    }
}
