//! A runaway: a rotor whose angle grows without bound (issue 27). Dormand–Prince's error
//! control must not loosen with the turns the rotor has made, nor may the run spend its
//! budget on them.

use std::f64::consts::TAU;

use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::{run, Dopri5, LagrangeSystem, Outcome, RunOptions, State};

/// A rotor of constant inertia J = 1 kg·m² under a constant moment M₀ and a ripple
/// M₁·cos Ωt (the second coordinate idle): J·q̈ = M₀ + M₁·cos Ωt, so that
/// q(t) = q₀ + ω₀t + M₀t²/2 + (M₁/Ω²)(1 − cos Ωt), q̇(t) = ω₀ + M₀t + (M₁/Ω)·sin Ωt.
struct Rotor {
    m0: f64,
    m1: f64,
    omega: f64,
}

impl Rotor {
    fn exact(&self, q0: f64, w0: f64, t: f64) -> (f64, f64) {
        let (m0, m1, w) = (self.m0, self.m1, self.omega);
        (
            q0 + w0 * t + 0.5 * m0 * t * t + m1 / (w * w) * (1.0 - (w * t).cos()),
            w0 + m0 * t + m1 / w * (w * t).sin(),
        )
    }
}

impl LagrangeSystem for Rotor {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(
            self.m0 + self.m1 * (self.omega * t).cos(),
            0.0,
        ))
    }
}

/// The worst error of the recorded angle and speed against the closed form, over the rows,
/// and the run's steps.
fn errors(rotor: &Rotor, q0: f64, w0: f64, t_end: f64, tol: f64) -> (f64, f64, usize) {
    let start = State::new(0.0, Vector2::new(q0, 0.0), Vector2::new(w0, 0.0));
    let mut opts = RunOptions::until(t_end, 1e-3);
    opts.max_steps = 1_000_000;
    let r = run(rotor, &Dopri5::new(tol).unwrap(), start, &opts).unwrap();
    assert_eq!(r.outcome, Outcome::FinalTime);
    let tr = &r.trajectory;
    let (mut dq, mut dw) = (0.0_f64, 0.0_f64);
    for i in 0..tr.len() {
        let (q, w) = rotor.exact(q0, w0, tr.t()[i]);
        dq = dq.max((tr.q()[0][i] - q).abs());
        dw = dw.max((tr.qd()[0][i] - w).abs());
    }
    (dq, dw, r.steps)
}

/// The rotor spun up from rest by a constant moment of 200 N·m to q = M₀t²/2 = 10⁶ rad in
/// 100 s (q̇ = 2·10⁴ rad/s). Dormand–Prince integrates a quadratic exactly, its error
/// estimate is rounding, and the run ends in a handful of steps growing tenfold, not by
/// spending its budget on the turns; every row is the closed form to the rounding of 10⁶ rad
/// (1.2·10⁻¹⁰) and of the speed.
#[test]
fn a_rotor_run_away_to_a_million_radians_is_exact_in_a_few_steps() {
    let rotor = Rotor {
        m0: 200.0,
        m1: 0.0,
        omega: 1.0,
    };
    for tol in [1e-6, 1e-10] {
        let (dq, dw, steps) = errors(&rotor, 0.0, 0.0, 100.0, tol);
        println!("tol {tol:e}: angle error {dq:.1e} rad, speed {dw:.1e} rad/s, {steps} steps");
        assert!(dq <= 1e-8 && dw <= 1e-10, "{dq:e} {dw:e}");
        assert!(steps <= 20, "{steps}");
    }
    // The same from 10⁶ rad at 10⁴ rad/s, back through zero to −10⁶ rad.
    let back = Rotor {
        m0: -200.0,
        ..rotor
    };
    let (dq, dw, steps) = errors(&back, 1e6, 1e4, 100.0, 1e-8);
    println!("thrown back from 1e6 rad: angle error {dq:.1e}, speed {dw:.1e}, {steps} steps");
    assert!(
        dq <= 1e-8 && dw <= 1e-10 && steps <= 20,
        "{dq:e} {dw:e} {steps}"
    );
}

/// The rotor at 50 rad/s with a ripple of 10⁻⁴ rad at 1 Hz (J·q̈ = M₁·cos Ωt), started at
/// 7 rad and at 10⁶ rad: the machine does not know how far it has turned, and the error
/// control must not either. With the angle's tolerance relative to |q| (10⁻⁸ of 10⁶ rad is
/// 10⁻² rad a step) the run from 10⁶ rad lets the angle's error go; with the angle's size
/// taken as at most one turn the two runs take the same steps, and both follow the closed
/// form to the tolerance (the far one up to the rounding of 10⁶ rad over its steps).
#[test]
fn a_rotor_a_million_radians_on_is_integrated_as_one_within_a_turn() {
    let tol = 1e-8;
    let rotor = Rotor {
        m0: 0.0,
        m1: 1e-4 * TAU * TAU,
        omega: TAU,
    };
    let w0 = 50.0;
    let (far_q, far_w, far_steps) = errors(&rotor, 1e6, w0, 20.0, tol);
    let (near_q, near_w, near_steps) = errors(&rotor, 7.0, w0, 20.0, tol);
    println!(
        "from 1e6 rad: angle error {far_q:.2e}, speed {far_w:.2e} in {far_steps} steps; from \
         7 rad: {near_q:.2e}, {near_w:.2e} in {near_steps}"
    );
    assert_eq!(far_steps, near_steps);
    assert!(
        near_q <= 100.0 * tol && near_w <= 100.0 * tol,
        "{near_q:e} {near_w:e}"
    );
    assert!(
        far_q <= 100.0 * tol && far_w <= 100.0 * tol,
        "{far_q:e} {far_w:e}"
    );
    assert!((far_q - near_q).abs() <= 1e-8, "{far_q:e} vs {near_q:e}");
}
