//! Where the steppers fail: stability limits on x″ + 2ζωx′ + ω²x = 0 (finite increments) and
//! on a real negative eigenvalue (RK4), and divergence ending in an error that names the time.
//!
//! The finite-increment step on the oscillator, with Ω = ωh and y = h·x′, is linear:
//!
//! ```text
//! x⁺ = (1 − Ω²/2)·x + (1 − ζΩ)·y
//! y⁺ = −Ω²·x + (1 − 2ζΩ)·y
//! ```
//!
//! with trace τ = 2 − 2ζΩ − Ω²/2 and determinant δ = 1 − 2ζΩ + Ω²/2. By the Jury (Schur–Cohn)
//! conditions both eigenvalues lie inside the unit circle iff 1 − τ + δ = Ω² > 0,
//! 1 + τ + δ = 4(1 − ζΩ) > 0 (Ω < 1/ζ: an eigenvalue −1 appears at Ω = 1/ζ) and δ < 1
//! (Ω < 4ζ). So the method is stable exactly for Ω < min(4ζ, 1/ζ), and for ζ = 0 δ = 1 + Ω²/2
//! > 1 at every step: the derivation confirms the limits stated in the issue and the guide.

use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::{run, FiniteIncrement, LagrangeSystem, Rk4, RunOptions, State, Stepper};
use tmm::Error;

/// Two identical, uncoupled damped oscillators x″ + 2ζωx′ + ω²x = 0 (unit inertia).
struct Oscillator {
    omega: f64,
    zeta: f64,
}

impl LagrangeSystem for Oscillator {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::zeros())
    }
    // The spring as a potential, the damper as Rayleigh's function: the other two ways in.
    fn potential(&self, q: &Vector2<f64>) -> tmm::Result<f64> {
        Ok(0.5 * self.omega * self.omega * q.norm_squared())
    }
    fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity() * 2.0 * self.zeta * self.omega)
    }
}

/// The amplification matrix derived in the module docs, acting on (x, h·x′).
fn amplification(zeta: f64, big_omega: f64) -> Matrix2<f64> {
    let o = big_omega;
    Matrix2::new(
        1.0 - 0.5 * o * o,
        1.0 - zeta * o,
        -o * o,
        1.0 - 2.0 * zeta * o,
    )
}

fn spectral_radius(m: &Matrix2<f64>) -> f64 {
    let (tr, det) = (m.trace(), m.determinant());
    let disc = tr * tr - 4.0 * det;
    if disc >= 0.0 {
        ((tr + disc.sqrt()) / 2.0)
            .abs()
            .max(((tr - disc.sqrt()) / 2.0).abs())
    } else {
        det.sqrt()
    }
}

fn limit(zeta: f64) -> f64 {
    (4.0 * zeta).min(1.0 / zeta)
}

#[test]
fn the_derived_amplification_matrix_is_the_steppers() {
    for (zeta, o) in [(0.0, 0.3), (0.1, 0.35), (0.7, 1.2), (2.0, 0.4)] {
        let omega = 3.0;
        let h = o / omega;
        let sys = Oscillator { omega, zeta };
        let m = amplification(zeta, o);
        // Columns: x = 1, y = 0 and x = 0, y = 1 (x′ = 1/h).
        for (col, (x, v)) in [(1.0, 0.0), (0.0, 1.0 / h)].into_iter().enumerate() {
            let s = FiniteIncrement
                .step(
                    &sys,
                    &State::new(0.0, Vector2::new(x, 0.0), Vector2::new(v, 0.0)),
                    h,
                )
                .unwrap();
            assert!((s.q[0] - m[(0, col)]).abs() < 1e-9, "{zeta} {o}");
            assert!((s.qd[0] * h - m[(1, col)]).abs() < 1e-9, "{zeta} {o}");
        }
    }
}

#[test]
fn spectral_radius_crosses_one_exactly_at_min_4zeta_inverse_zeta() {
    for i in 1..=60 {
        let zeta = 0.05 * f64::from(i); // 0.05 … 3
        let lim = limit(zeta);
        assert!(
            spectral_radius(&amplification(zeta, lim * 0.999)) < 1.0,
            "ζ = {zeta}"
        );
        assert!(
            spectral_radius(&amplification(zeta, lim * 1.001)) > 1.0,
            "ζ = {zeta}"
        );
    }
    for i in 1..=300 {
        let o = 0.01 * f64::from(i);
        assert!(
            spectral_radius(&amplification(0.0, o)) > 1.0,
            "ζ = 0, Ω = {o}"
        );
    }
}

/// Amplitude √(x² + (x′/ω)²) of coordinate 0 after each step.
fn amplitudes(sys: &Oscillator, h: f64, n: usize) -> tmm::Result<Vec<f64>> {
    let mut s = State::new(0.0, Vector2::new(1.0, 0.5), Vector2::zeros());
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        s = FiniteIncrement.step(sys, &s, h)?;
        out.push(s.q[0].hypot(s.qd[0] / sys.omega));
    }
    Ok(out)
}

#[test]
fn finite_increments_bounded_just_below_the_limit_and_growing_just_above() {
    let omega = 10.0;
    for zeta in [0.05, 0.1, 0.3, 0.5, 1.0, 2.0] {
        let sys = Oscillator { omega, zeta };
        let lim = limit(zeta);
        let below = amplitudes(&sys, 0.97 * lim / omega, 20_000).unwrap();
        let worst = below.iter().fold(0.0f64, |m, a| m.max(*a));
        // Near ζ = ½ the two eigenvalues nearly coincide at −1: a transient of a few times
        // the start amplitude, then decay.
        assert!(
            worst < 20.0,
            "ζ = {zeta}: amplitude reached {worst} below the limit"
        );
        assert!(
            *below.last().unwrap() < 0.1,
            "ζ = {zeta}: no decay below the limit"
        );
        // Growth by more than 10³, or all the way to overflow (an error, never a NaN).
        let grew = match amplitudes(&sys, 1.03 * lim / omega, 40_000) {
            Ok(a) => *a.last().unwrap() > 1e3,
            Err(Error::NonFiniteState { time }) => time.is_finite(),
            Err(e) => panic!("{e}"),
        };
        assert!(grew, "ζ = {zeta}: no growth above the limit");
    }
}

#[test]
fn finite_increments_gain_energy_at_every_step_size_without_damping() {
    let omega = 10.0;
    let sys = Oscillator { omega, zeta: 0.0 };
    for o in [0.01, 0.05, 0.2, 0.5, 1.0] {
        let a = amplitudes(&sys, o / omega, 400).unwrap();
        // |λ|² = 1 + Ω²/2: the amplitude grows by (1 + Ω²/2)^(n/2).
        let expected = (1.0 + 0.5 * o * o).powf(200.0);
        let got = a[399];
        assert!(got > 1.0, "Ω = {o}: amplitude {got}");
        assert!(
            (got / expected).ln().abs() < 0.7,
            "Ω = {o}: {got} vs {expected}"
        );
    }
}

/// q̈ = λ·q̇ with λ = −c/m: the speed is y′ = λy, a real negative eigenvalue.
struct ViscousBrake {
    lambda: f64,
}

impl LagrangeSystem for ViscousBrake {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(2.0, 0.0, 0.0, 2.0))
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(2.0 * self.lambda * qd)
    }
}

#[test]
fn rk4_bounded_at_2_7_growing_at_2_9() {
    let sys = ViscousBrake { lambda: -50.0 };
    let r = |z: f64| 1.0 + z + z * z / 2.0 + z.powi(3) / 6.0 + z.powi(4) / 24.0;
    for (hl, grows) in [(2.7, false), (2.9, true)] {
        let h = hl / 50.0;
        let mut s = State::new(0.0, Vector2::zeros(), Vector2::new(1.0, -1.0));
        for _ in 0..200 {
            s = Rk4.step(&sys, &s, h).unwrap();
        }
        let expected = r(-hl).powi(200);
        assert!((s.qd[0] / expected - 1.0).abs() < 1e-9, "h|λ| = {hl}");
        if grows {
            assert!(s.qd[0].abs() > 1e10);
        } else {
            assert!(s.qd[0].abs() < 1e-9);
        }
    }
}

#[test]
fn divergence_ends_in_an_error_naming_the_time() {
    let sys = ViscousBrake { lambda: -50.0 };
    let h = 2.9 / 50.0;
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(1.0, -1.0));
    let e = run(&sys, &Rk4, s0, &RunOptions::until(1e4, h)).unwrap_err();
    let Error::NonFiniteState { time } = e else {
        panic!("{e}")
    };
    // |R(−2.9)| = 1.187…: overflow after about 4100 steps, i.e. near t = 240 s.
    assert!(time > 100.0 && time < 400.0, "diverged at t = {time}");
    // The message names the time to four significant digits (the field keeps it exactly).
    let shown: f64 = e.to_string()["non-finite state at t = ".len()..]
        .trim_end_matches(" s")
        .parse()
        .unwrap();
    assert!((shown - time).abs() <= 1e-3 * time, "{e}");

    let osc = Oscillator {
        omega: 10.0,
        zeta: 0.0,
    };
    let e = run(
        &osc,
        &FiniteIncrement,
        State::new(0.0, Vector2::new(1.0, 0.0), Vector2::zeros()),
        &RunOptions::until(1e6, 0.2),
    )
    .unwrap_err();
    assert!(
        matches!(e, Error::NonFiniteState { time } if time.is_finite() && time > 0.0),
        "{e}"
    );
}
