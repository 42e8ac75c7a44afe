//! A run-up that never reaches a steady state says why, within its budget of turns.

use nalgebra::Vector2;
use tmm::dynamics::{Rk4, State};
use tmm::linkage::bundled;
use tmm::linkage::dynamics::{LinkageSystem, Motor, RunUpOptions};
use tmm::Error;

#[test]
fn a_run_up_that_runs_away_says_so() {
    // The four-bar without loads or gravity under a constant 2 N·m: every turn adds the
    // work 2π·2 J, so at the end of turn k (back at the start angle, the same J_red)
    // ½·J_red·ω_k² = 4πk exactly, and the mean speed grows for ever (like √k).
    let mut l = bundled::four_bar();
    l.loads.clear();
    l.gravity = [0.0, 0.0];
    let m = 2.0;
    let sys = LinkageSystem::from_linkage(&l)
        .unwrap()
        .with_motor(0, Motor::Constant(m))
        .unwrap();
    let phi0 = sys.plan().reference_input();
    let j = sys.reduced(phi0, 1.0).unwrap().inertia;
    let opts = RunUpOptions::new(2e-4).with_max_turns(10);
    // The turns as run_up takes them, one after the other.
    let mut s = State::at_rest(Vector2::new(phi0, 0.0));
    let mut means = Vec::new();
    for k in 1..=10 {
        let (turn, r) = sys.turn(&Rk4, s, &opts).unwrap();
        s = r.last;
        let exact = (2.0 * std::f64::consts::TAU * m * f64::from(k) / j).sqrt();
        assert!(
            (s.qd[0] - exact).abs() <= 1e-6 * exact,
            "turn {k}: ω {} vs {exact} from the work done",
            s.qd[0]
        );
        means.push(turn.omega_mean);
    }
    assert!(means.windows(2).all(|w| w[1] > w[0]), "{means:?}");
    let e = sys.run_up(&Rk4, &opts).unwrap_err();
    let Error::In { part, source } = &e else {
        panic!("{e}")
    };
    assert!(
        matches!(
            **source,
            Error::Budget {
                what: "turn",
                limit: 10,
                ..
            }
        ),
        "{e}"
    );
    assert!(
        part.contains("grew in each of the last 10 turns")
            && part.contains(&format!("from {:.6e} to {:.6e} rad/s", means[0], means[9])),
        "{e}"
    );
    // Fewer than 8 turns cannot tell a slow approach from none: the bare budget.
    let e = sys.run_up(&Rk4, &opts.with_max_turns(5)).unwrap_err();
    assert!(matches!(e, Error::Budget { limit: 5, .. }), "{e}");
}

/// The bundled four-bar under a constant 10⁴ N·m, against loads whose reduced moment stays
/// within tens of N·m: ½·J_red·ω² only grows, so the crank never turns back and no regime
/// repeats. A fixed step chosen for 10 rad/s spans a large part of a turn once the machine
/// runs fast: that turn is refused, naming the step and the largest one that would resolve
/// it (a thirty-second of the turn's period), instead of judged. A step that resolves every
/// turn sees the machine run away, and a smaller one sees the same.
#[test]
fn a_turn_the_fixed_step_cannot_resolve_is_refused_naming_the_step() {
    let sys = LinkageSystem::from_linkage(&bundled::four_bar())
        .unwrap()
        .with_motor(0, Motor::Constant(1e4))
        .unwrap();
    let coarse = std::f64::consts::TAU / 10.0 / 2000.0;
    let e = sys
        .run_up(&Rk4, &RunUpOptions::new(coarse).with_max_turns(30))
        .unwrap_err();
    let Error::OutOfRange {
        name, value, max, ..
    } = e
    else {
        panic!("{e}")
    };
    assert!(name.starts_with("step h"), "{name}");
    assert_eq!(value, coarse);
    // The refused turn was fast: fewer than 32 steps, so its period is under 32 h.
    assert!(max < value && max > 0.0, "{max} vs {value}");
    for h in [1e-5, 5e-6] {
        let e = sys
            .run_up(&Rk4, &RunUpOptions::new(h).with_max_turns(30))
            .unwrap_err();
        let Error::In { part, .. } = &e else {
            panic!("h = {h}: {e}")
        };
        assert!(part.contains("grew in each of the last"), "h = {h}: {e}");
    }
}
