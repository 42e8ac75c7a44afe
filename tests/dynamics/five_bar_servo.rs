//! The five-bar's servos (issue 16): a demand that overflows saturates on the side of its
//! dominant term (never a silent 0), and the clamp at ±limit, a kink of the generalized
//! forces, is reported to the run, so that RK4 keeps its fourth order across a saturation.

use nalgebra::Vector2;
use tmm::dynamics::machines::{FiveBar, Servo};
use tmm::dynamics::{accelerations, run, LagrangeSystem, Rk4, RunOptions, State};
use tmm::Error;

/// The default robot from (120°, 60°) at rest, with crank 1's servo saturated at the start
/// (demand 20·(−20°) = −7 N·m against a 5 N·m limit) and crank 4's servo given a limit it
/// never reaches: one saturation switch, of crank 1, inside the run.
fn robot() -> FiveBar {
    let mut r = FiveBar::default();
    r.drive4.limit = 1e3;
    r
}

fn start() -> State {
    State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()))
}

/// The state at `t_end` by RK4 with `n` equal steps, the servos' switches located or
/// stepped across (as a run saw them before they were reported).
fn end(sys: &FiveBar, t_end: f64, n: u32, locate: bool) -> State {
    let mut opts = RunOptions::until(t_end, t_end / f64::from(n));
    opts.record_every = usize::MAX;
    opts.locate_kinks = locate;
    run(sys, &Rk4, start(), &opts).unwrap().last
}

/// The two servos' demands over their limits, the five-bar's kink arguments.
fn margins(r: &FiveBar, q: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<[f64; 2]> {
    let mut m = [0.0; 2];
    r.kink_arguments(0.0, q, qd, &mut m)?;
    Ok(m)
}

/// The difference of two states in q and q̇ (rad, rad/s), the larger of the two.
fn diff(a: &State, b: &State) -> f64 {
    (a.q - b.q).amax().max((a.qd - b.qd).amax())
}

/// The time of crank 1's saturation switch on the reference path, found from the servo's
/// own demand along a finely recorded run (a sign change of |demand| − limit).
fn switch_time(sys: &FiveBar, t_end: f64) -> Vec<f64> {
    let opts = RunOptions::until(t_end, t_end / 20_000.0);
    let r = run(sys, &Rk4, start(), &opts).unwrap();
    let tr = &r.trajectory;
    let (t, q, qd) = (tr.t(), tr.q(), tr.qd());
    let s = sys.drive1;
    let over: Vec<bool> = (0..t.len())
        .map(|i| (s.kp * (s.target - q[0][i]) - s.kd * qd[0][i]).abs() > s.limit)
        .collect();
    (1..t.len())
        .filter(|&i| over[i] != over[i - 1])
        .map(|i| t[i])
        .collect()
}

/// RK4 across a servo saturation: with the switch reported as a kink (the run steps onto
/// it), the observed order between successive halvings of h is 4 (the method's, as on a
/// smooth right-hand side); with the kink hidden the step that straddles the switch
/// integrates a function whose slope jumps, with a local error O(h²) once, and the global
/// error falls like h² only.
///
/// The reference is the run with kinks at h/64 of the finest run: its own error is below
/// (1/64)⁴ of that run's, so it does not set the observed orders. The window (0, 0.12 s) is
/// chosen so that the switch (about 0.05 s, checked below from the demand itself) is inside
/// and the run does not end near it.
#[test]
fn rk4_keeps_its_order_across_a_servo_saturation_when_the_switch_is_a_kink() {
    let sys = robot();
    let t_end = 0.12;
    let switches = switch_time(&sys, t_end);
    assert_eq!(switches.len(), 1, "one switch in the window: {switches:?}");
    assert!(
        switches[0] > 0.1 * t_end && switches[0] < 0.9 * t_end,
        "{switches:?}"
    );
    // The servo saturated at the start (M = −limit), following afterwards.
    let s0 = start();
    assert_eq!(sys.drive1.torque(s0.q[0], s0.qd[0]).unwrap(), -5.0);
    assert!(margins(&sys, &s0.q, &s0.qd).unwrap()[0] < 0.0);

    let ns = [40u32, 80, 160, 320];
    let reference = end(&sys, t_end, 64 * ns[ns.len() - 1], true);
    let with: Vec<f64> = ns
        .iter()
        .map(|&n| diff(&end(&sys, t_end, n, true), &reference))
        .collect();
    // Without the kink the error depends on where the switch falls inside its step, which
    // changes from one h to the next: the local orders scatter (measured 1.6, 0.1, 5.9 over
    // the halvings above), so the order is the least-squares slope over seven halvings (the
    // errors stay far above the reference's, about 10⁻¹⁷).
    let ns_hidden: Vec<u32> = (0..8).map(|k| 40 << k).collect();
    let without: Vec<f64> = ns_hidden
        .iter()
        .map(|&n| diff(&end(&sys, t_end, n, false), &reference))
        .collect();
    let orders = |e: &[f64]| -> Vec<f64> { e.windows(2).map(|w| (w[0] / w[1]).log2()).collect() };
    let pw = orders(&with);
    // The slope of log₂ e against the number of halvings.
    let m = without.len() as f64;
    let (sx, sy) = (0..without.len()).fold((0.0, 0.0), |(sx, sy), k| {
        (sx + k as f64, sy - without[k].log2())
    });
    let (sxx, sxy) = (0..without.len()).fold((0.0, 0.0), |(sxx, sxy), k| {
        let x = k as f64;
        (sxx + x * x, sxy - x * without[k].log2())
    });
    let slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    eprintln!("errors with kinks {with:?}, orders {pw:.2?}");
    eprintln!(
        "errors without {without:?}, orders {:.2?}, least-squares {slope:.2}",
        orders(&without)
    );
    for p in &pw {
        assert!((3.6..4.6).contains(p), "with the kink located: order {p}");
    }
    assert!(
        (1.5..2.5).contains(&slope),
        "without the kink: order {slope}"
    );
    // And the located kink pays: the finest run is far more accurate with it.
    assert!(with[3] * 100.0 < without[3], "{with:?} vs {without:?}");
}

/// A demand k_p·e − k_d·ω that overflows saturates at the limit on the side of its dominant
/// term, as the controller would push; equal and opposite overflowing terms have no side and
/// are an error. Never 0 (what ∞ − ∞ gave before).
#[test]
fn an_overflowing_demand_saturates_on_its_dominant_side() {
    let servo = |kp: f64, kd: f64| Servo {
        target: 0.0,
        kp,
        kd,
        limit: 5.0,
    };
    // k_p·e = 10³⁰⁰·10³⁰⁰ overflows forwards (e = target − φ = 10³⁰⁰), or backwards.
    assert_eq!(servo(1e300, 1.0).torque(-1e300, 0.0).unwrap(), 5.0);
    assert_eq!(servo(1e300, 1.0).torque(1e300, 0.0).unwrap(), -5.0);
    // e itself overflows: target − φ = 10³⁰⁸ + 10³⁰⁸.
    let far = Servo {
        target: 1e308,
        ..servo(2.0, 0.0)
    };
    assert_eq!(far.torque(-1e308, 0.0).unwrap(), 5.0);
    // k_p·e = +∞ and k_d·ω = −∞: both push forwards (−k_d·ω = +∞).
    assert_eq!(servo(1e300, 1e300).torque(-1e300, -1e300).unwrap(), 5.0);
    // Both overflow and oppose: the larger wins, as it would in a wider number system.
    // k_p·e = 10⁴⁰⁰ forwards against k_d·ω = 10³¹⁰ backwards.
    assert_eq!(servo(1e300, 1e10).torque(-1e100, 1e300).unwrap(), 5.0);
    assert_eq!(servo(1e10, 1e300).torque(-1e300, 1e100).unwrap(), -5.0);
    // The same sum that overflows only as a sum: 1.5·10³⁰⁸ + 1.5·10³⁰⁸.
    assert_eq!(servo(1.5, 1.5).torque(-1e308, -1e308).unwrap(), 5.0);
    // Equal and opposite: no direction.
    match servo(1e300, 1e300).torque(-1e300, 1e300) {
        Err(Error::Overflow { .. }) => {}
        other => panic!("{other:?}"),
    }
    // A finite demand is clamped as before, a small one passes.
    assert_eq!(servo(10.0, 1.0).torque(-1.0, 0.0).unwrap(), 5.0);
    assert_eq!(servo(10.0, 1.0).torque(-0.2, 1.0).unwrap(), 1.0);

    // Through the robot: a saturated overflowing servo drives with its limit, and the
    // accelerations are finite (the other servo at its target, at rest).
    let d = FiveBar::default();
    let r = FiveBar {
        drive1: Servo {
            target: 120f64.to_radians(),
            kp: 1e308,
            kd: 1e308,
            limit: 5.0,
        },
        drive4: Servo {
            target: 60f64.to_radians(),
            ..d.drive4
        },
        ..d
    };
    let q = Vector2::new(120f64.to_radians() - 1e-3, 60f64.to_radians());
    let qd = Vector2::new(-1e10, 0.0);
    let q_f = r.forces(0.0, &q, &qd).unwrap();
    let k = r.kinematics(&q).unwrap();
    assert_eq!(q_f[0], 5.0 - r.m_on * k.phi3_q[0]);
    let acc = accelerations(&r, 0.0, &q, &qd).unwrap();
    assert!(acc.iter().all(|a| a.is_finite()));
    // Its kink arguments: the saturated servo's demand at the clamp's cap 2 (the demand
    // k_d·ω = 1e10·k_d drives it forwards), the other's 0 (at its target and at rest).
    assert_eq!(margins(&r, &q, &qd).unwrap(), [2.0, 0.0]);
}

/// Each servo's kink argument (its demand over its limit) passes a node (±1) exactly where
/// its clamp switches: just inside and just outside the limit on either side, for each
/// servo alone.
#[test]
fn the_kink_argument_changes_sign_at_each_servos_switch() {
    let r = FiveBar::default();
    assert_eq!(r.kinks(), vec![vec![-1.0, 1.0], vec![-1.0, 1.0]]);
    let q0 = Vector2::new(r.drive1.target, r.drive4.target);
    // At the targets, at rest: no demand, both follow.
    assert_eq!(margins(&r, &q0, &Vector2::zeros()).unwrap(), [0.0, 0.0]);
    for (i, s) in [(0, r.drive1), (1, r.drive4)] {
        // k_d·ω = ±limit·(1 ± 10⁻⁶): just following, just saturated, either way.
        for f in [1.0 - 1e-6, 1.0 + 1e-6, -1.0 + 1e-6, -1.0 - 1e-6] {
            let mut qd = Vector2::zeros();
            qd[i] = f * s.limit / s.kd;
            let k = margins(&r, &q0, &qd).unwrap();
            // The demand −k_d·ω over the limit is −f.
            assert!((k[i] + f).abs() < 1e-12, "servo {i}, f = {f}: {k:?}");
            assert_eq!(k[1 - i], 0.0, "the other servo at its target, at rest");
            let m =
                r.forces(0.0, &q0, &qd).unwrap()[i] + r.m_on * r.kinematics(&q0).unwrap().phi3_q[i];
            assert!(
                (m.abs() - (f.abs().min(1.0) * s.limit)).abs() < 1e-12,
                "{m}"
            );
        }
    }
    // Far past the limit the argument stays at ±2 (a demand that overflows too).
    let fast = Vector2::new(1e300, -1e300);
    assert_eq!(margins(&r, &q0, &fast).unwrap(), [-2.0, 2.0]);
    // A servo with limit 0 never switches: its argument has no node (and is 0), the other
    // one's is located on its own.
    let mut z = r;
    z.drive1.limit = 0.0;
    assert_eq!(z.kinks(), vec![vec![], vec![-1.0, 1.0]]);
    let qd = Vector2::new(3.0, 2.0 * r.drive4.limit / r.drive4.kd);
    let m = margins(&z, &q0, &qd).unwrap();
    assert!(m[0] == 0.0 && m[1] == -2.0, "{m:?}");
    // Bad states are errors, not NaN; so is room for another number of arguments.
    assert!(margins(&r, &Vector2::new(f64::NAN, 0.0), &Vector2::zeros()).is_err());
    for n in [0, 1, 3] {
        let mut out = vec![0.0; n];
        let e = r.kink_arguments(0.0, &q0, &Vector2::zeros(), &mut out);
        assert!(matches!(e, Err(Error::OutOfRange { .. })), "{n}: {e:?}");
    }
}
