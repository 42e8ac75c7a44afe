//! The seeds' method of finite increments (seed 003, eqs. 87–104 and 127–144).

use nalgebra::Vector2;

use super::stepper::{
    check_result, check_step, fixed_step, handed_acceleration, Advance, Handover, NoExtension,
    Stepper,
};
use super::system::{accelerations, LagrangeSystem, State};
use crate::error::Result;

/// The finite-increment method exactly as seed 003 states it: the acceleration found at the
/// start of each interval is held constant over it, so
///
/// ```text
/// Δq̇ = q̈ₙ·Δt,   q̇ₙ₊₁ = q̇ₙ + Δq̇,   qₙ₊₁ = qₙ + (q̇ₙ + ½ Δq̇)·Δt
/// ```
///
/// (eqs. 95–104 with the velocity at the start of the interval, docs/errata.md#d29). It is first-order
/// accurate (the velocity update is Euler's), needs one evaluation per step, and on the
/// damped oscillator x″ + 2ζωx′ + ω²x = 0 it is stable only for ωΔt < min(4ζ, 1/ζ): its
/// amplification matrix has determinant 1 − 2ζΩ + Ω²/2 (> 1 when Ω > 4ζ) and the eigenvalue
/// −1 at Ω = 1/ζ. Undamped motion (ζ = 0) gains energy at every step size.
///
/// # Examples
/// Constant acceleration is integrated exactly (the scheme is the kinematics of uniform
/// acceleration): a 2 kg slider pushed by 4 N from rest, after 10 steps of 0.1 s, has
/// v = 2 m/s and x = ½·2·1² = 1 m.
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{FiniteIncrement, LagrangeSystem, State, Stepper};
/// struct Slider;
/// impl LagrangeSystem for Slider {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::new(2.0, 0.0, 0.0, 1.0))
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::new(4.0, 0.0))
///     }
/// }
/// let mut s = State::at_rest(Vector2::zeros());
/// for _ in 0..10 {
///     s = FiniteIncrement.step(&Slider, &s, 0.1).unwrap();
/// }
/// assert!((s.qd[0] - 2.0).abs() < 1e-12 && (s.q[0] - 1.0).abs() < 1e-12);
/// ```
#[doc(alias = "finite increments")]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FiniteIncrement;

impl Stepper for FiniteIncrement {
    type Dense = NoExtension;

    fn name(&self) -> &'static str {
        "finite increments"
    }

    fn order(&self) -> u32 {
        1
    }

    fn evaluations_per_step(&self) -> usize {
        1
    }

    fn step<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<State> {
        check_step(s, h)?;
        let a = accelerations(sys, s.t, &s.q, &s.qd)?;
        increment(s, h, a)
    }

    /// As [`step`](Self::step), with the handed-on accelerations at `s` when there are
    /// finite ones (then no evaluation at all).
    fn advance_from<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
    ) -> Result<Advance> {
        let given = handed_acceleration(from);
        check_step(s, h)?;
        let a = match given {
            Some(a) => a,
            None => accelerations(sys, s.t, &s.q, &s.qd)?,
        };
        Ok(fixed_step(
            increment(s, h, a)?,
            h,
            usize::from(given.is_none()),
        ))
    }

    fn uses_start_acceleration(&self) -> bool {
        true
    }
}

/// The increments of one step of `h` from `s` under the accelerations `a` at `s`.
fn increment(s: &State, h: f64, a: Vector2<f64>) -> Result<State> {
    let dv = a * h;
    check_result(State::new(s.t + h, s.q + (s.qd + 0.5 * dv) * h, s.qd + dv))
}
