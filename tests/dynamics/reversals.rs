//! A machine thrown against its drive turns back: `turn` says where, `run_up_from` goes on.

use std::f64::consts::TAU;

use nalgebra::Vector2;
use tmm::dynamics::{
    run, Direction, Dopri5, FiniteIncrement, Outcome, Reach, Rk4, RunOptions, State, Stepper, Watch,
};
use tmm::linkage::bundled;
use tmm::linkage::dynamics::{Damper, LinkageSystem, Motor, RunUpOptions};
use tmm::Error;

use super::scenarios::simpson;

/// The angle φ_r < φ₀ at which the crank, thrown backwards at ω₀ < 0 from φ₀, comes to rest:
/// ½·J_red(φ₀)·ω₀² + ∫_φ₀^φ_r (M + M_red⁻(φ)) dφ = 0, with M_red⁻ the loads' reduced moment
/// while the crank turns backwards (no load depends on the speed's size) and M the motor's
/// constant moment; Simpson's rule and bisection over [φ₀ − 1, φ₀].
fn energy_rest_angle(sys: &LinkageSystem, m: f64, phi0: f64, w0: f64) -> f64 {
    let e0 = 0.5 * sys.reduced(phi0, w0).unwrap().inertia * w0 * w0;
    let energy = |phi: f64| {
        let n = 2000;
        let h = (phi - phi0) / f64::from(n);
        let (t, q): (Vec<f64>, Vec<f64>) = (0..=n)
            .map(|i| {
                let p = phi0 + h * f64::from(i);
                (p, m + sys.reduced(p, -1.0).unwrap().loads)
            })
            .unzip();
        e0 + simpson(&t, &q)
    };
    let (mut lo, mut hi) = (phi0 - 1.0, phi0);
    assert!(energy(lo) < 0.0);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if energy(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The time and angle at which `turn` said the crank turned back (its typed report, whose
/// fraction of the turn made agrees with the angle).
fn turned_back<M: Stepper>(sys: &LinkageSystem, method: &M, start: State, h: f64) -> (f64, f64) {
    let opts = RunUpOptions::new(h).with_max_turn_time(0.95);
    let e = sys.turn(method, start, &opts).unwrap_err();
    let Error::TurnedBack {
        time,
        angle,
        fraction,
        from_speed,
        from_time,
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!((from_speed, from_time), (start.qd[0], start.t), "{e}");
    assert_eq!(fraction, (angle - start.q[0]).abs() / TAU, "{e}");
    assert!(
        e.to_string().starts_with("the crank turned back at t = "),
        "{e}"
    );
    (time, angle)
}

/// The bundled four-bar thrown backwards at 17 rad/s against a forward motor of 35 or 55 N·m
/// (above the breakaway: the 40 N·m resistance on the rocker reduces to at most some
/// 15 N·m on the crank) decelerates, stops and turns forward (issue 27: Dormand–Prince at
/// 10⁻⁶ then integrated the runaway forward motion until its step fell to 10⁻¹²·t, 10⁶
/// steps later, and RK4 ran out its turn time). `turn` now ends where the crank turns back,
/// with each method: the angle where the energy equation says the crank comes to rest
/// (independent of any integrator), and the time of a fine RK4 run (h = 10⁻⁶ s) that watches
/// ω reach 0.
#[test]
fn a_four_bar_thrown_against_its_motor_turns_back_where_its_energy_runs_out() {
    let base = LinkageSystem::from_linkage(&bundled::four_bar()).unwrap();
    let (phi0, w0) = (0.0, -17.0);
    let start = State::new(0.0, Vector2::new(phi0, 0.0), Vector2::new(w0, 0.0));
    for m in [35.0, 55.0] {
        let sys = base.clone().with_motor(0, Motor::Constant(m)).unwrap();
        let phi_r = energy_rest_angle(&sys, m, phi0, w0);
        let mut fine = RunOptions::until(0.1, 1e-6);
        fine.reach = Some(Reach {
            watch: Watch::Speed(0),
            value: 0.0,
            direction: Direction::Rising,
        });
        fine.record_every = usize::MAX;
        let r = run(&sys, &Rk4, start, &fine).unwrap();
        let Outcome::Reached { t: t_r } = r.outcome else {
            panic!("{:?}", r.outcome)
        };
        assert!(
            (r.last.q[0] - phi_r).abs() < 1e-10,
            "{} vs {phi_r}",
            r.last.q[0]
        );
        let cases: [(&str, (f64, f64), f64, f64); 5] = [
            (
                "Dormand-Prince 1e-6",
                turned_back(&sys, &Dopri5::new(1e-6).unwrap(), start, 1e-3),
                1e-7,
                1e-7,
            ),
            (
                "Dormand-Prince 1e-10",
                turned_back(&sys, &Dopri5::new(1e-10).unwrap(), start, 1e-3),
                1e-10,
                1e-10,
            ),
            ("RK4 1e-4", turned_back(&sys, &Rk4, start, 1e-4), 1e-9, 1e-9),
            ("RK4 1e-3", turned_back(&sys, &Rk4, start, 1e-3), 1e-6, 1e-6),
            (
                "finite increments 1e-5",
                turned_back(&sys, &FiniteIncrement, start, 1e-5),
                1e-4,
                1e-4,
            ),
        ];
        for (name, (t, phi), t_tol, phi_tol) in cases {
            println!(
                "M {m}: {name} turned back at t = {t} (fine RK4 {t_r}: {:.1e}), φ = {phi} (energy {phi_r}: {:.1e})",
                t - t_r,
                phi - phi_r
            );
            assert!((t - t_r).abs() <= t_tol, "M {m}, {name}: t {t} vs {t_r}");
            assert!(
                (phi - phi_r).abs() <= phi_tol,
                "M {m}, {name}: φ {phi} vs {phi_r}"
            );
        }
    }
}

/// From the same backward throw, with a damper of 0.5 N·m·s/rad on the crank so that a
/// steady state exists (near 49 rad/s, approached by a factor of about e⁻¹ a turn),
/// `run_up_from` turns back and runs up forward to the steady state that `run_up` reaches
/// from rest: the same mean speed to the run-up's tolerance, every
/// turn forward, the recorded motion through ω = 0 at the turning time `turn` reports
/// (1.4e-8 apart at 10⁻⁸, in 6 turns each; at 10⁻⁶ the integrator's error on a turn's mean
/// speed, 2.5e-5, is above the run-up's tolerance).
#[test]
fn a_run_up_thrown_backwards_turns_back_and_reaches_the_steady_state_from_rest() {
    let sys = LinkageSystem::from_linkage(&bundled::four_bar())
        .unwrap()
        .with_motor(0, Motor::Constant(35.0))
        .unwrap()
        .with_damper(&Damper::Link {
            link: "crank".into(),
            c: 0.5,
        })
        .unwrap();
    let start = State::new(0.0, Vector2::new(0.0, 0.0), Vector2::new(-17.0, 0.0));
    let opts = RunUpOptions::new(1e-3).with_tol(1e-7);
    for (name, dp) in [
        ("1e-8", Dopri5::new(1e-8).unwrap()),
        ("1e-10", Dopri5::new(1e-10).unwrap()),
    ] {
        let (t_back, _) = turned_back(&sys, &dp, start, 1e-3);
        let up = sys.run_up_from(&dp, start, &opts).unwrap();
        let rest = sys.run_up(&dp, &opts).unwrap();
        let (a, b) = (
            up.turns.last().unwrap().omega_mean,
            rest.turns.last().unwrap().omega_mean,
        );
        println!(
            "{name}: thrown {a} rad/s in {} turns, from rest {b} in {}",
            up.turns.len(),
            rest.turns.len()
        );
        assert!((a - b).abs() <= 1e-6 * b, "{name}: {a} vs {b}");
        assert!(up
            .turns
            .iter()
            .all(|t| t.direction == 1.0 && t.t_start >= t_back));
        assert_eq!(up.turns[0].t_start, t_back, "{name}");
        let k = up.t.iter().position(|&t| t == t_back).unwrap();
        assert!(
            up.omega[..k].iter().all(|&w| w < 0.0) && up.omega[k].abs() < 1e-12,
            "{name}"
        );
    }
}
