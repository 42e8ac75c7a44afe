//! The adaptive embedded Runge–Kutta method of Dormand and Prince, order 5(4).

use nalgebra::{Vector2, Vector4};

use super::stepper::{
    check_result, check_step, handed_acceleration, pack, rhs, unpack, Advance, ContinuousExtension,
    Handover, Stepper,
};
use super::system::{LagrangeSystem, State};
use crate::error::{positive, Error, Result};

// The Dormand–Prince tableau (Hairer, Nørsett & Wanner, Solving ODEs I, table 5.2).
const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights (the last row of A: the method is "first same as last").
const B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
/// The coefficients dᵢ of the continuous extension (Hairer, Nørsett & Wanner, §II.6, and
/// their code DOPRI5's CONTD5): see [`dense_weights`].
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The weights bᵢ(θ) of the fourth-order continuous extension,
/// y(t₀ + θh) = y₀ + h·Σ bᵢ(θ)·kᵢ over the seven stages (k₇ = f(t₀ + h, y₁)):
///
/// ```text
/// bᵢ(θ) = θ·bᵢ + θ(1−θ)·(δᵢ₁ − bᵢ) + θ²(1−θ)·(2bᵢ − δᵢ₁ − δᵢ₇) + θ²(1−θ)²·dᵢ
/// ```
///
/// The first three terms are the cubic Hermite interpolant of y₀, y₁ and the slopes k₁, k₇
/// (written in the fifth-order weights bᵢ, whose sum with k is (y₁ − y₀)/h); the last adds
/// the quartic term that makes the extension of order 4. The unit tests check the eight
/// order conditions of order 4 for these weights at several θ, and that bᵢ(1) are the
/// fifth-order weights; the integration tests observe the order on an exact solution.
pub(crate) fn dense_weights(theta: f64) -> [f64; 7] {
    let mut w = [0.0; 7];
    let (t, u) = (theta, 1.0 - theta);
    for (i, wi) in w.iter_mut().enumerate() {
        let d1 = if i == 0 { 1.0 } else { 0.0 };
        let d7 = if i == 6 { 1.0 } else { 0.0 };
        *wi = t * B[i]
            + t * u * (d1 - B[i])
            + t * t * u * (2.0 * B[i] - d1 - d7)
            + t * t * u * u * D[i];
    }
    w
}

/// The continuous extension ("dense output") of one accepted step of [`Dopri5`]: the state
/// anywhere inside the step, of order 4, from the step's seven stages and no further
/// evaluation. [`run`](super::run) uses it to record the requested
/// [`times`](super::RunOptions::times) without stepping onto them.
///
/// # Examples
/// One step of the spin-down ω(t) = 2·e^(−t/2) of the [`Dopri5`] example, read at its middle:
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{Dopri5, LagrangeSystem, State, Stepper};
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
/// let s = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
/// let (adv, dense) = Dopri5::new(1e-10).unwrap().advance_dense(&Rotor, &s, 0.1, None).unwrap();
/// let dense = dense.unwrap();
/// assert_eq!((dense.start(), dense.end()), (0.0, adv.state.t));
/// let mid = dense.at(0.5 * adv.state.t).unwrap();
/// assert_eq!(mid.t, 0.5 * adv.state.t);
/// assert!((mid.qd[0] - 2.0 * (-0.25 * adv.state.t).exp()).abs() < 1e-10);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseOutput {
    t0: f64,
    t1: f64,
    h: f64,
    y0: Vector4<f64>,
    y1: Vector4<f64>,
    k: Stages,
}

impl DenseOutput {
    /// The time at the start of the step, s.
    #[must_use]
    pub fn start(&self) -> f64 {
        self.t0
    }

    /// The time at the end of the step, s.
    #[must_use]
    pub fn end(&self) -> f64 {
        self.t1
    }

    /// The state at time `t` in [start, end], carrying `t` exactly. At the ends it is the
    /// step's own start and end state.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `t`; [`Error::OutOfRange`] for `t` outside the
    /// step; [`Error::NonFiniteState`] when the interpolated state overflows.
    pub fn at(&self, t: f64) -> Result<State> {
        crate::error::finite("interpolation time", t)?;
        if t < self.t0 || t > self.t1 {
            return Err(Error::OutOfRange {
                name: "interpolation time (inside the step)",
                value: t,
                min: self.t0,
                max: self.t1,
                ends: crate::Ends::Closed,
            });
        }
        if t == self.t0 {
            return Ok(unpack(t, &self.y0));
        }
        if t == self.t1 {
            return Ok(unpack(t, &self.y1));
        }
        let w = dense_weights((t - self.t0) / self.h);
        let mut y = self.y0;
        for (wi, ki) in w.iter().zip(&self.k) {
            y += self.h * wi * ki;
        }
        check_result(unpack(t, &y))
    }
}

impl ContinuousExtension for DenseOutput {
    fn start(&self) -> f64 {
        DenseOutput::start(self)
    }
    fn end(&self) -> f64 {
        DenseOutput::end(self)
    }
    fn at(&self, t: f64) -> Result<State> {
        DenseOutput::at(self, t)
    }
    fn set_end(&mut self, t1: f64) {
        self.t1 = t1;
    }
}

/// The seven stages k₁…k₇ of a step (k₇ = f(t + h, y₁), the next step's k₁).
type Stages = [Vector4<f64>; 7];

/// Fifth- minus fourth-order weights: the local error estimate.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// The safety factor of the step-size control: the next step aims at err = 0.9⁵ ≈ 0.59 of
/// the tolerance rather than 1, so that most proposals are accepted.
const SAFETY: f64 = 0.9;
/// The proportional gain k_P of the PI controller (Hairer & Wanner's choice for DOPRI5).
const BETA: f64 = 0.04;
/// The exponent of the current error: integral plus proportional gain, 1/5 − 0.75·β.
const ALPHA: f64 = 0.2 - 0.75 * BETA;
/// The least factor h′/h (after a rejection or an accepted step alike).
const FAC_MIN: f64 = 0.2;
/// The greatest factor h′/h.
const FAC_MAX: f64 = 10.0;
/// The least error norm the controller remembers: errₙ₋₁^β must stay positive (an exact
/// step, err = 0, would otherwise make the next proposal zero).
const ERR_FLOOR: f64 = 1e-4;

/// The size a coordinate's relative tolerance is taken of, for a coordinate of magnitude
/// `size` (the larger at the step's two ends): `size`, but no more than one turn, 2π.
///
/// Relative to |q| itself, the tolerance on a crank that runs away would grow with the turns
/// it has made (10⁻⁸ of 10⁶ rad is 10⁻² rad a step): the motion within a turn, which the
/// machine's forces follow, would go unresolved. Capped, the control is the same for q and
/// q + 2πk beyond one turn (`tests/dynamics/runaway.rs`: the same steps from 7 rad and from
/// 10⁶ rad), and every coordinate within ±2π is weighed as it was.
#[inline]
fn coordinate_size(size: f64) -> f64 {
    size.min(std::f64::consts::TAU)
}

/// The factor h′/h after an accepted step with error norm `err` (in [0, 1]), given the error
/// norm of the previous accepted step when there is one (see [`Dopri5`]'s docs).
#[inline]
fn accepted_factor(err: f64, previous: Option<f64>) -> f64 {
    let factor = match previous.filter(|e| e.is_finite() && *e >= 0.0) {
        // err^(−α)·e^β as one exponential of two logarithms: the same factor to a few
        // ulps for one libm call less than two `powf` (a tenth of a step's own work on a
        // cheap right-hand side). err = 0 gives e^(+∞) = ∞, as err^(−α) did.
        Some(e) => SAFETY * (BETA * e.max(ERR_FLOOR).ln() - ALPHA * err.ln()).exp(),
        // No history: the elementary controller, whose full gain brings the caller's first
        // guess to the right size soonest.
        None => SAFETY * err.powf(-0.2),
    };
    // err = 0 (an exact step) makes the factor infinite: it is then FAC_MAX.
    factor.clamp(FAC_MIN, FAC_MAX)
}

/// The factor h′/h after a rejected trial with error norm `err` (> 1, or NaN or ∞ for a trial
/// that overflowed), never a growth, given the step size and error norm of the trial rejected
/// just before it from the same start, if any (see [`Dopri5`]'s docs).
#[inline]
fn rejected_factor(h: f64, err: f64, before: Option<(f64, f64)>) -> f64 {
    if !err.is_finite() {
        return FAC_MIN;
    }
    // The exponent of err against h: 5 where the estimate follows its asymptotic law; the
    // one the last two trials showed when this is the second failure of the same step.
    let k = match before {
        Some((h0, e0)) if e0.is_finite() && h0 > h => {
            if e0 <= err {
                // A shorter trial no more accurate: no power law to follow.
                return FAC_MIN;
            }
            ((e0 / err).ln() / (h0 / h).ln()).clamp(1.0, 5.0)
        }
        _ => 5.0,
    };
    (SAFETY * err.powf(-1.0 / k)).clamp(FAC_MIN, 1.0)
}

/// Dormand–Prince 5(4): an embedded Runge–Kutta pair with error control, so that a user asks
/// for an accuracy instead of a step size.
///
/// Each step is accepted when the weighted RMS norm of the local error estimate,
/// err = √(mean((eᵢ / (atol + rtol·max(|yᵢ|, |ŷᵢ|)))²)) over y = (q, q̇), is at most 1,
/// where a coordinate's size max(|qᵢ|, |q̂ᵢ|) counts no more than one turn, 2π (the
/// accuracy of a machine's motion does not loosen with the turns it has made; the speeds are
/// weighed by their full size). The solution carried on is the fifth-order one. The global error is usually of the order of the
/// tolerance (the tests check it against exact solutions).
///
/// # Step-size control
/// The estimate e is the local error of the embedded fourth-order solution, so err ≈ φ·h⁵
/// with φ varying slowly along the motion. Asking the next step for err = 1 gives the
/// *elementary* (integral) controller h′ = h·err^(−1/5). It has two weaknesses: it reacts
/// to each step's error alone, so a noisy estimate makes a ragged step sequence, and where
/// the step size is limited by stability rather than accuracy (an oscillation faster than the
/// motion, as a servo's stiff loop) err no longer follows h⁵ and the full gain 1/5 makes the
/// step size oscillate between accepted and rejected steps, each rejection wasting six
/// evaluations. In logarithms, log h is the controller's output and log err the measured
/// deviation; the elementary controller is a pure integrator with gain 1/5. Adding a
/// proportional term on the change of log err and lowering the integral gain (Gustafsson's PI
/// controller, as Hairer & Wanner, Solving ODEs II, §IV.2, recommend for this pair):
///
/// ```text
/// log h′ = log h − k_I·log errₙ − k_P·(log errₙ − log errₙ₋₁)
///      h′ = h · 0.9 · errₙ^(−α) · errₙ₋₁^β,   α = k_I + k_P = 0.2 − 0.75β,  β = k_P = 0.04
/// ```
///
/// errₙ₋₁ is the error norm of the previous *accepted* step: when the errors grow from step to
/// step the factor errₙ₋₁^β/errₙ^β < 1 damps the growth of h before a rejection, and
/// when they fall it lets h grow sooner. The integral gain α − β = 0.13 < 1/5 is what keeps
/// the loop stable at the stability limit. The factor 0.9 aims a little below err = 1 so
/// that most proposals are accepted. The factor h′/h is limited to [0.2, 10]: a single
/// estimate is not trusted beyond that. Further:
/// - a rejected step is retried with h·max(0.2, 0.9·err^(−1/5)), the elementary controller
///   (the previous accepted step's error does not describe the failed one). Should the retry
///   fail too, the estimate is not following h⁵ there, typically because a kink of the forces
///   that no step was made to land on (a servo reaching its torque limit) lies inside the step,
///   where err grows only like h¹…h²; the two failed trials (h₁, err₁), (h₂, err₂) show the
///   exponent that holds, k = ln(err₁/err₂)/ln(h₁/h₂) (kept in [1, 5]), and the next trial
///   is h₂·max(0.2, 0.9·err₂^(−1/k)), where the fixed 1/5 creeps towards the kink one
///   rejection of six evaluations at a time (a force √t from t = 0, err ∝ h^2.5: four trials
///   for a first step of 0.1 s against six, `tests/dynamics/scenarios.rs`); a shorter trial that is no
///   more accurate gets the least factor, 0.2. The step accepted right after a rejection proposes no
///   longer a step than its own (the estimate just failed near there, so growing at once would
///   invite the next rejection);
/// - the previous error is handed on from step to step by the caller ([`Handover`]). Without
///   it (a first step, or a caller that does not pass it on) the proposal is the elementary
///   controller's h·0.9·err^(−1/5), whose full gain brings the caller's first guess to the
///   right size soonest. A remembered error is floored at 10⁻⁴ (an exact step, err = 0, would
///   otherwise make the next proposal zero).
///
/// On the five-bar robot's first 0.5 s at rtol = atol = 10⁻⁸ this takes 595 evaluations for
/// a final error of 5.1·10⁻⁹, where the elementary controller alone took 679 and ode_solvers'
/// Dopri5 (Hairer and Wanner's PI controller) takes 637 for 5.2·10⁻⁹ on the same right-hand
/// side (`benches/peers.rs` prints both; across tolerances the two spend the same).
///
/// A step that would fall below 10⁻¹²·max(1, |t|) ends in [`Error::Singular`] (the motion is
/// too stiff or singular for this tolerance).
///
/// # Examples
/// The spin-down ω(t) = 2·e^(−t/2) of the [`Rk4`](super::Rk4) example, asked for 1e-9:
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{Dopri5, LagrangeSystem, State, Stepper};
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
/// let dp = Dopri5::new(1e-9).unwrap();
/// let (mut s, mut h) = (State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0)), 0.1_f64);
/// while s.t < 1.0 {
///     let a = dp.advance(&Rotor, &s, h.min(1.0 - s.t)).unwrap();
///     (s, h) = (a.state, a.h_next);
/// }
/// assert!((s.qd[0] - 2.0 * (-0.5f64).exp()).abs() < 1e-8);
/// ```
#[doc(alias = "DOPRI5")]
#[doc(alias = "RK45")]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dopri5 {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (in the units of each q and q̇).
    pub atol: f64,
}

impl Dopri5 {
    /// The method with `rtol = atol = tol`.
    ///
    /// # Errors
    /// [`Error::NonPositive`] when `tol` is not positive.
    pub fn new(tol: f64) -> Result<Self> {
        positive("tolerance", tol)?;
        Ok(Self {
            rtol: tol,
            atol: tol,
        })
    }

    /// Both tolerances finite and non-negative, at least one positive.
    #[inline]
    fn check(&self) -> Result<()> {
        for (name, v) in [("rtol", self.rtol), ("atol", self.atol)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::OutOfRange {
                    name,
                    value: v,
                    min: 0.0,
                    max: f64::INFINITY,
                    ends: crate::Ends::Closed,
                });
            }
        }
        positive("rtol + atol", self.rtol + self.atol)?;
        Ok(())
    }

    /// The weighted RMS norm of the error estimate `err` of the step y → y5 (see the type's
    /// docs). A component whose scale is zero (atol = 0 and yᵢ = ŷᵢ = 0) counts only if its
    /// error is not zero: 0/0 would otherwise reject every step of a machine with a
    /// coordinate at rest.
    ///
    /// A coordinate's size is taken no larger than one turn, 2π ([`coordinate_size`]): a
    /// machine's motion does not depend on how far it has turned, so neither may the
    /// accuracy asked of it.
    #[inline]
    fn error_norm(&self, y: &Vector4<f64>, y5: &Vector4<f64>, err: &Vector4<f64>) -> f64 {
        let mut sum = 0.0;
        for i in 0..4 {
            if err[i] != 0.0 {
                let size = y[i].abs().max(y5[i].abs());
                let size = if i < 2 { coordinate_size(size) } else { size };
                let sc = self.atol + self.rtol * size;
                sum += (err[i] / sc).powi(2);
            }
        }
        (sum / 4.0).sqrt()
    }

    /// The fifth-order solution of one step of exactly `h` from (t, y), whose first stage
    /// k1 = f(t, y) is `k[0]`, and the stages k2…k6 written into `k` (5 evaluations). The
    /// stages are written in place, not returned: a step moves no arrays of stages around.
    #[inline]
    fn solution<S: LagrangeSystem + ?Sized>(
        sys: &S,
        t: f64,
        y: &Vector4<f64>,
        h: f64,
        k: &mut Stages,
    ) -> Result<Vector4<f64>> {
        for i in 1..6 {
            let mut yi = *y;
            for (j, kj) in k.iter().enumerate().take(i) {
                yi += (h * A[i][j]) * kj;
            }
            k[i] = rhs(sys, t + C[i] * h, &yi)?;
        }
        let mut y5 = *y;
        for (b, ki) in B.iter().zip(&k[..6]) {
            y5 += (h * b) * ki;
        }
        Ok(y5)
    }

    /// One step of exactly `h` (k1 given in `k[0]`): the fifth-order solution and the error
    /// estimate, with the stages k2…k7 written into `k` (k7 = f(t + h, y5), the next step's
    /// k1; 6 evaluations).
    #[inline]
    fn trial<S: LagrangeSystem + ?Sized>(
        sys: &S,
        t: f64,
        y: &Vector4<f64>,
        h: f64,
        k: &mut Stages,
    ) -> Result<(Vector4<f64>, Vector4<f64>)> {
        let y5 = Self::solution(sys, t, y, h, k)?;
        // C[6] = 1: the last stage is taken at t + h, the time the accepted state carries.
        k[6] = rhs(sys, t + C[6] * h, &y5)?;
        let mut err = Vector4::zeros();
        for (e, ki) in E.iter().zip(k.iter()) {
            err += (h * e) * ki;
        }
        Ok((y5, err))
    }

    /// One accepted step (see [`Stepper::advance_from`]), its stages left in `k` for a
    /// continuous extension: the one body behind `advance_from` (which builds no extension,
    /// so that a run with no requested times pays nothing for one) and `advance_dense`.
    #[inline]
    fn accepted<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
        k: &mut Stages,
    ) -> Result<(Advance, Vector4<f64>, Vector4<f64>, f64)> {
        check_step(s, h)?;
        self.check()?;
        let given = handed_acceleration(from);
        let from = from.unwrap_or_default();
        let y = pack(s);
        let mut evaluations = match given {
            Some(a) => {
                k[0] = Vector4::new(y[2], y[3], a[0], a[1]);
                0
            }
            _ => {
                k[0] = rhs(sys, s.t, &y)?;
                1
            }
        };
        // The step the caller asks for is tried as it is; only a step the error control
        // shrinks below this is a sign of a singular or too stiff motion.
        let h_min = 1e-12 * s.t.abs().max(1.0);
        let mut h = h;
        let mut rejected = None;
        loop {
            // A trial that overflows is a rejected step, not yet a divergence.
            let norm = match Self::trial(sys, s.t, &y, h, k) {
                Ok((y5, err)) => {
                    let norm = self.error_norm(&y, &y5, &err);
                    // NaN and ∞ fail the test: such a trial is rejected.
                    if norm <= 1.0 {
                        evaluations += 6;
                        let mut grow = accepted_factor(norm, from.error_norm);
                        if rejected.is_some() {
                            grow = grow.min(1.0);
                        }
                        let state = check_result(unpack(s.t + h, &y5))?;
                        let adv = Advance {
                            state,
                            h_next: h * grow,
                            evaluations,
                            handover: Handover {
                                acceleration: Some(Vector2::new(k[6][2], k[6][3])),
                                error_norm: Some(norm),
                            },
                        };
                        return Ok((adv, y, y5, h));
                    }
                    norm
                }
                Err(Error::NonFiniteState { .. }) => f64::INFINITY,
                Err(e) => return Err(e),
            };
            evaluations += 6;
            let factor = rejected_factor(h, norm, rejected);
            rejected = Some((h, norm));
            h *= factor;
            if h < h_min {
                return Err(Error::Singular {
                    what: "adaptive step (Dormand-Prince)",
                    measure: "step size h",
                    value: h,
                });
            }
        }
    }
}

impl Stepper for Dopri5 {
    type Dense = DenseOutput;

    fn name(&self) -> &'static str {
        "Dormand-Prince 5(4)"
    }

    fn order(&self) -> u32 {
        5
    }

    /// Six: a step without error control needs no last stage (its weight in the
    /// fifth-order solution is zero).
    fn evaluations_per_step(&self) -> usize {
        6
    }

    fn step<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<State> {
        check_step(s, h)?;
        let y = pack(s);
        let mut k = [rhs(sys, s.t, &y)?; 7];
        let y5 = Self::solution(sys, s.t, &y, h, &mut k)?;
        check_result(unpack(s.t + h, &y5))
    }

    /// # Errors
    /// As [`step`](Stepper::step); [`Error::OutOfRange`] for a negative or non-finite
    /// tolerance; [`Error::Singular`] when the step size the accuracy needs falls below
    /// 10⁻¹²·max(1, |t|).
    fn advance<S: LagrangeSystem + ?Sized>(&self, sys: &S, s: &State, h: f64) -> Result<Advance> {
        self.advance_from(sys, s, h, None)
    }

    /// The first stage of a step is q̈ at its start, the same as the last stage of the step
    /// before ("first same as last"): given the handed-on accelerations, an accepted step
    /// costs six evaluations instead of seven. A rejected trial reuses them too. The handed-on
    /// error norm is the memory of the step-size controller (see the type's docs).
    ///
    /// # Errors
    /// As [`advance`](Stepper::advance).
    #[inline]
    fn advance_from<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
    ) -> Result<Advance> {
        let mut k = [Vector4::zeros(); 7];
        Ok(self.accepted(sys, s, h, from, &mut k)?.0)
    }

    fn uses_start_acceleration(&self) -> bool {
        true
    }

    fn is_adaptive(&self) -> bool {
        true
    }

    fn has_dense_output(&self) -> bool {
        true
    }

    /// As [`advance_from`](Stepper::advance_from), with the step's continuous extension
    /// (no further evaluation).
    ///
    /// # Errors
    /// As [`advance`](Stepper::advance).
    fn advance_dense<S: LagrangeSystem + ?Sized>(
        &self,
        sys: &S,
        s: &State,
        h: f64,
        from: Option<Handover>,
    ) -> Result<(Advance, Option<Self::Dense>)> {
        let mut k = [Vector4::zeros(); 7];
        let (adv, y0, y1, h) = self.accepted(sys, s, h, from, &mut k)?;
        let dense = DenseOutput {
            t0: s.t,
            t1: adv.state.t,
            h,
            y0,
            y1,
            k,
        };
        Ok((adv, Some(dense)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The eight order conditions of order 4 for the continuous weights bᵢ(θ): Σ bᵢ Φᵢ(θ)
    /// = θ^ρ/γ for every rooted tree of order ρ ≤ 4, with the stages' c and A (the seventh
    /// stage is k₇ = f(t₀ + h, y₁): c₇ = 1 and its row of A the fifth-order weights).
    #[test]
    fn dense_weights_meet_the_order_4_conditions() {
        let a = |i: usize, j: usize| if j < 6 { A[i][j] } else { 0.0 };
        let ac: Vec<f64> = (0..7)
            .map(|i| (0..7).map(|j| a(i, j) * C[j]).sum())
            .collect();
        let ac2: Vec<f64> = (0..7)
            .map(|i| (0..7).map(|j| a(i, j) * C[j] * C[j]).sum())
            .collect();
        let aac: Vec<f64> = (0..7)
            .map(|i| (0..7).map(|j| a(i, j) * ac[j]).sum())
            .collect();
        for theta in [0.1, 0.25, 0.5, 0.7, 0.9, 1.0] {
            let b = dense_weights(theta);
            let sum = |f: &dyn Fn(usize) -> f64| (0..7).map(|i| b[i] * f(i)).sum::<f64>();
            let t = theta;
            let conditions = [
                (sum(&|_| 1.0), t),
                (sum(&|i| C[i]), t * t / 2.0),
                (sum(&|i| C[i] * C[i]), t.powi(3) / 3.0),
                (sum(&|i| ac[i]), t.powi(3) / 6.0),
                (sum(&|i| C[i].powi(3)), t.powi(4) / 4.0),
                (sum(&|i| C[i] * ac[i]), t.powi(4) / 8.0),
                (sum(&|i| ac2[i]), t.powi(4) / 12.0),
                (sum(&|i| aac[i]), t.powi(4) / 24.0),
            ];
            for (k, (got, want)) in conditions.iter().enumerate() {
                assert!(
                    (got - want).abs() < 1e-14,
                    "θ = {t}, condition {k}: {got} vs {want}"
                );
            }
        }
        // At θ = 1 the extension is the fifth-order solution itself.
        for (w, b) in dense_weights(1.0).iter().zip(B) {
            assert!((w - b).abs() < 1e-15);
        }
    }
}
