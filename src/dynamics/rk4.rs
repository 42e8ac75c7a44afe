//! The classic fourth-order Runge–Kutta method.

use nalgebra::Vector2;

use super::stepper::{
    check_result, check_step, fixed_step, handed_acceleration, Advance, Handover, NoExtension,
    Stepper,
};
use super::system::{accelerations_inline as accelerations, LagrangeSystem, State};
use crate::error::{positive, Result};

/// Classic RK4 on the first-order form y = (q, q̇), ẏ = (q̇, q̈).
///
/// Fourth-order accurate with four evaluations per step. On ẏ = λy its amplification factor
/// is 1 + z + z²/2 + z³/6 + z⁴/24 (z = hλ); on the negative real axis it stays within the unit
/// circle for h|λ| up to ≈ 2.785 (for example 0.879 at 2.7, 1.187 at 2.9).
///
/// # Examples
/// A rotor of 0.5 kg·m² under a viscous moment −0.25·ω spins down from 2 rad/s:
/// ω(t) = 2·e^(−t/2). One second in ten steps agrees to 1e-7.
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{LagrangeSystem, Rk4, State, Stepper};
/// struct Rotor;
/// impl LagrangeSystem for Rotor {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::new(0.5, 0.0, 0.0, 1.0))
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::zeros())
///     }
///     fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::new(0.25, 0.0, 0.0, 0.0))
///     }
/// }
/// let mut s = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
/// for _ in 0..10 {
///     s = Rk4.step(&Rotor, &s, 0.1).unwrap();
/// }
/// assert!((s.qd[0] - 2.0 * (-0.5f64).exp()).abs() < 1e-7);
/// ```
#[doc(alias = "Runge-Kutta")]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Rk4;

impl Stepper for Rk4 {
    type Dense = NoExtension;

    fn name(&self) -> &'static str {
        "RK4"
    }

    fn order(&self) -> u32 {
        4
    }

    fn evaluations_per_step(&self) -> usize {
        4
    }

    #[inline]
    fn step<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<State> {
        // The start state needs no check of its own: the first evaluation refuses a
        // non-finite one with the same error (a non-finite state at s.t).
        positive("step size h", h)?;
        let a1 = accelerations(sys, s.t, &s.q, &s.qd)?;
        stages(sys, s, h, a1)
    }

    /// As [`step`](Self::step), its first stage taken from the handed-on accelerations at
    /// `s` when there are finite ones (three evaluations instead of four).
    #[inline(always)]
    fn advance_from<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
    ) -> Result<Advance> {
        let given = handed_acceleration(from);
        let a1 = match given {
            Some(a) => {
                check_step(s, h)?;
                a
            }
            None => {
                positive("step size h", h)?;
                accelerations(sys, s.t, &s.q, &s.qd)?
            }
        };
        let evaluations = 4 - usize::from(given.is_some());
        Ok(fixed_step(stages(sys, s, h, a1)?, h, evaluations))
    }

    fn uses_start_acceleration(&self) -> bool {
        true
    }
}

/// The step from `s` given q̈ at `s` (`a1`): the stages on (q, q̇) directly, y = (q, q̇),
/// k = (q̇, q̈), the same sums as on the packed y with nothing packed and unpacked.
#[inline(always)]
fn stages<S: LagrangeSystem + ?Sized>(
    sys: &S,
    s: &State,
    h: f64,
    a1: Vector2<f64>,
) -> Result<State> {
    let (t, q, v) = (s.t, s.q, s.qd);
    let half = 0.5 * h;
    let (q2, v2) = (q + half * v, v + half * a1);
    let a2 = accelerations(sys, t + half, &q2, &v2)?;
    let (q3, v3) = (q + half * v2, v + half * a2);
    let a3 = accelerations(sys, t + half, &q3, &v3)?;
    let (q4, v4) = (q + h * v3, v + h * a3);
    let a4 = accelerations(sys, t + h, &q4, &v4)?;
    let sixth = h / 6.0;
    let q1 = q + sixth * (v + 2.0 * v2 + 2.0 * v3 + v4);
    let v1 = v + sixth * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    check_result(State::new(t + h, q1, v1))
}
