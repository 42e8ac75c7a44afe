//! Breakpoints, kinks and output at requested times (issue 11): Dormand–Prince meets its
//! tolerance across the kinks of the landing gear's moment table, requested times are
//! recorded bitwise, the continuous extension has order 4, and hostile times are refused.

use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::machines::LandingGear;
use tmm::dynamics::{
    run, Direction, Dopri5, FiniteIncrement, LagrangeSystem, Outcome, Reach, Rk4, RunOptions,
    RunResult, State, Stepper, Watch,
};
use tmm::Error;

/// The retraction (to φ_H max) with the state recorded at `times` only.
fn retract<S: LagrangeSystem, M: Stepper>(sys: &S, m: &M, h: f64, times: &[f64]) -> RunResult {
    retract_locating(sys, m, h, times, true)
}

/// As [`retract`], the table's nodes located or (`locate = false`) stepped across, as a run
/// saw them before they were reported.
fn retract_locating<S: LagrangeSystem, M: Stepper>(
    sys: &S,
    m: &M,
    h: f64,
    times: &[f64],
    locate: bool,
) -> RunResult {
    let g = LandingGear::default();
    let opts = RunOptions {
        record_every: usize::MAX,
        locate_kinks: locate,
        reach: Some(Reach {
            watch: Watch::Output(0),
            value: g.phi_h_max,
            direction: Direction::Rising,
        }),
        ..RunOptions::at_times(20.0, h, times.to_vec())
    };
    run(sys, m, State::at_rest(Vector2::zeros()), &opts).unwrap()
}

/// max over the rows at `times` and over (q, q̇) of |y − y_ref| / (tol·(1 + |y_ref|)): the
/// global error in the controller's own weighting, 1 = the tolerance.
fn weighted_error(r: &RunResult, reference: &RunResult, tol: f64, times: &[f64]) -> f64 {
    let (a, b) = (&r.trajectory, &reference.trajectory);
    let mut worst: f64 = 0.0;
    for &t in times {
        let i = a
            .t()
            .iter()
            .position(|&x| x == t)
            .expect("requested time recorded");
        let j = b
            .t()
            .iter()
            .position(|&x| x == t)
            .expect("requested time recorded");
        for c in 0..2 {
            for (got, want) in [(a.q()[c][i], b.q()[c][j]), (a.qd()[c][i], b.qd()[c][j])] {
                worst = worst.max((got - want).abs() / (tol * (1.0 + want.abs())));
            }
        }
    }
    worst
}

/// Dormand–Prince across the ten kinks of the landing gear's moment table, against a
/// reference at 10⁻¹⁴ (itself checked against RK4 with located kinks, and within 0.01 of the
/// tolerance of the runs at 10⁻¹³ and 10⁻¹⁵ at the 10⁻¹² level).
///
/// The bound asserted is the tolerance itself (weighted global error ≤ 1). Why it can hold
/// after hundreds of steps: the controller bounds the error estimate of the embedded
/// fourth-order solution, while the run carries the fifth-order one, whose local error is far
/// smaller; the motors' speed–torque slope damps speed errors, and q errors only add up.
/// Measured: 0.54, 0.48, 0.24, 0.27, 0.27 at 1e-8…1e-12 with the PI step-size controller
/// (0.34, 0.35, 0.35, 0.39, 0.46 with the elementary one before it). Without the kinks
/// reported (the step straddles a node, where the error estimate of a smooth method does not
/// see the error it makes) the same runs miss by 114, 68, 133, 61, 310 times the tolerance:
/// the test also asserts ≥ 10 there, so it shows what the breakpoints buy. The stop
/// (φ_H = φ_H max, located inside its step) is asserted to the tolerance in seconds:
/// measured 0.007–0.02·tol with the kinks, 3.7–63·tol without.
#[test]
fn landing_gear_dormand_prince_meets_its_tolerance_across_the_table_kinks() {
    let g = LandingGear::default();
    // Times across the whole retraction (about 7 s), many just after a table node.
    let times: Vec<f64> = (1..=130).map(|i| f64::from(i) * 0.05).collect();
    let reference = retract(&g, &Dopri5::new(1e-14).unwrap(), 1e-3, &times);
    let rk4 = retract(&g, &Rk4, 5e-5, &times);
    let e_rk4 = weighted_error(&rk4, &reference, 1e-12, &times);
    assert!(e_rk4 < 3.0, "the reference vs RK4: {e_rk4} × 1e-12");
    let stop = |r: &RunResult| match r.outcome {
        Outcome::Reached { t } => t,
        o => panic!("{o:?}"),
    };
    let t_ref = stop(&reference);
    assert!((stop(&rk4) - t_ref).abs() < 1e-10);
    for tol in [1e-8, 1e-9, 1e-10, 1e-11, 1e-12] {
        let dp = Dopri5::new(tol).unwrap();
        let with = retract(&g, &dp, 1e-3, &times);
        let without = retract_locating(&g, &dp, 1e-3, &times, false);
        let ew = weighted_error(&with, &reference, tol, &times);
        let en = weighted_error(&without, &reference, tol, &times);
        let (sw, sn) = ((stop(&with) - t_ref).abs(), (stop(&without) - t_ref).abs());
        eprintln!(
            "tol {tol:e}: with kinks {ew:.3} ({} steps, {} evaluations, stop off by {:.2e} tol), \
             without {en:.3} ({} steps, {} evaluations, stop off by {:.2e} tol)",
            with.steps,
            with.evaluations,
            sw / tol,
            without.steps,
            without.evaluations,
            sn / tol
        );
        assert!(ew <= 1.0, "tol {tol:e}: weighted global error {ew}");
        assert!(sw <= tol, "tol {tol:e}: stop off by {sw} s");
        assert!(en >= 10.0, "tol {tol:e}: without the kinks {en}");
    }
}

/// The landing gear recorded at unsorted, repeated requested times: each is recorded once,
/// carrying the requested value bitwise, in increasing order; Dormand–Prince's steps are the
/// same as without them (the values come from its continuous extension) and agree with the
/// reference to the tolerance; RK4 and finite increments step onto them.
#[test]
fn requested_times_are_recorded_bitwise_and_to_the_tolerance() {
    let g = LandingGear::default();
    let asked = vec![
        3.3,
        0.05,
        1.0,
        3.3,
        6.0,
        0.777_777_777_777_7,
        2.0 / 3.0,
        1e-9,
    ];
    let mut sorted = asked.clone();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    let tol = 1e-10;
    let dp = Dopri5::new(tol).unwrap();
    let reference = retract(&g, &Dopri5::new(1e-14).unwrap(), 1e-3, &sorted);
    let plain = retract(&g, &dp, 1e-3, &[]);
    let mut opts = RunOptions::at_times(20.0, 1e-3, asked.clone());
    opts.reach = Some(Reach {
        watch: Watch::Output(0),
        value: g.phi_h_max,
        direction: Direction::Rising,
    });
    let r = run(&g, &dp, State::at_rest(Vector2::zeros()), &opts).unwrap();
    let t = r.trajectory.t();
    assert!(t.windows(2).all(|w| w[0] < w[1]), "increasing, each once");
    for &x in &sorted {
        assert_eq!(t.iter().filter(|&&y| y == x).count(), 1, "t = {x}");
    }
    // Every step end and the requested times: nothing else.
    assert_eq!(r.trajectory.len(), 1 + r.steps + sorted.len());
    assert_eq!((r.steps, r.last), (plain.steps, plain.last));
    let e = weighted_error(&r, &reference, tol, &sorted);
    eprintln!("Dormand-Prince {tol:e}: requested times within {e:.3} of the tolerance");
    assert!(e <= 1.0, "{e}");

    for (name, r) in [
        ("RK4", run_fixed(&g, &Rk4, &asked)),
        ("finite increments", run_fixed(&g, &FiniteIncrement, &asked)),
    ] {
        let t = r.trajectory.t();
        // Only the start, the requested times and the end.
        let mut want = vec![0.0];
        want.extend(sorted.iter().filter(|&&x| x <= 2.0));
        want.push(2.0);
        assert_eq!(t, want, "{name}");
    }
}

fn run_fixed<M: Stepper>(g: &LandingGear, m: &M, times: &[f64]) -> RunResult {
    let opts = RunOptions {
        record_every: usize::MAX,
        ..RunOptions::at_times(
            2.0,
            1e-3,
            times.iter().copied().filter(|&t| t <= 2.0).collect(),
        )
    };
    run(g, m, State::at_rest(Vector2::zeros()), &opts).unwrap()
}

/// x″ = −ω²x (unit mass, the spring as a force): exact x = cos ωt from x = 1 at rest.
struct Oscillator {
    omega: f64,
}

impl LagrangeSystem for Oscillator {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, _: f64, q: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(-self.omega * self.omega * q)
    }
}

/// The continuous extension of one step from the exact state, against the exact solution
/// inside the step: its error falls as h⁵ (a local error of order 5: an interpolant of
/// order 4), at θ = 0.3, 0.5 and 0.8. Measured slopes 4.9–5.0.
#[test]
fn dense_output_has_order_four_on_the_harmonic_oscillator() {
    let osc = Oscillator { omega: 1.0 };
    let s0 = State::new(0.0, Vector2::new(1.0, 0.0), Vector2::zeros());
    // A tolerance so loose that every step is accepted as asked.
    let dp = Dopri5 {
        rtol: 1.0,
        atol: 1.0,
    };
    for theta in [0.3, 0.5, 0.8] {
        let mut errors = Vec::new();
        for h in [0.4, 0.2, 0.1, 0.05, 0.025] {
            let (adv, dense) = dp.advance_dense(&osc, &s0, h, None).unwrap();
            assert_eq!(adv.state.t, h);
            let d = dense.unwrap();
            let t = theta * h;
            let s = d.at(t).unwrap();
            assert_eq!(s.t, t);
            errors.push((s.q[0] - t.cos()).abs().max((s.qd[0] + t.sin()).abs()));
        }
        let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        eprintln!("θ = {theta}: errors {errors:?}, observed local orders {orders:.2?}");
        for p in orders {
            assert!((4.6..=5.4).contains(&p), "θ = {theta}: {p}");
        }
    }
    // Over a run: the requested times (not step ends) agree with cos t to the tolerance.
    let times: Vec<f64> = (1..100).map(|i| f64::from(i) * 0.1 + 0.013).collect();
    for tol in [1e-6, 1e-9, 1e-12] {
        let opts = RunOptions {
            record_every: usize::MAX,
            ..RunOptions::at_times(10.0, 0.1, times.clone())
        };
        let dp = Dopri5::new(tol).unwrap();
        let r = run(&osc, &dp, s0, &opts).unwrap();
        let steps = run(&osc, &dp, s0, &RunOptions::until(10.0, 0.1)).unwrap();
        let worst = |tr: &tmm::dynamics::Trajectory| {
            let mut worst: f64 = 0.0;
            for (i, &t) in tr.t().iter().enumerate() {
                for (got, want) in [(tr.q()[0][i], t.cos()), (tr.qd()[0][i], -t.sin())] {
                    worst = worst.max((got - want).abs() / (tol * (1.0 + want.abs())));
                }
            }
            worst
        };
        let (at_times, at_steps) = (worst(&r.trajectory), worst(&steps.trajectory));
        eprintln!(
            "oscillator, tol {tol:e}: weighted error at the requested times {at_times:.3}, \
             at the step ends {at_steps:.3}"
        );
        assert_eq!(r.trajectory.len(), times.len() + 2);
        assert!(
            at_times <= 1.2 * at_steps,
            "tol {tol:e}: {at_times} vs {at_steps}"
        );
    }
}

/// A push that starts growing at t = 0.5: x″ = max(0, t − 0.5), so x(1) = 0.5³/6 exactly.
struct Kicked {
    report: bool,
}

impl LagrangeSystem for Kicked {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new((t - 0.5).max(0.0), 0.0))
    }
    fn breakpoints(&self) -> Vec<f64> {
        if self.report {
            vec![0.5]
        } else {
            Vec::new()
        }
    }
}

/// A kink at a breakpoint, given by the system or by the options: every method steps onto
/// it and is then exact (each piece of x is a polynomial of degree ≤ 3); a fixed-step method
/// stays on its grid. Without it RK4 misses by about 10⁻⁴.
#[test]
fn time_breakpoints_are_stepped_onto() {
    let s0 = State::at_rest(Vector2::zeros());
    let mut by_opts = RunOptions::until(1.0, 0.3);
    by_opts.breakpoints = vec![0.5, f64::MAX, -3.0, 0.5];
    let exact = 0.125 / 6.0;
    for (sys, opts) in [
        (Kicked { report: true }, RunOptions::until(1.0, 0.3)),
        (Kicked { report: false }, by_opts),
    ] {
        let r = run(&sys, &Rk4, s0, &opts).unwrap();
        assert_eq!(r.trajectory.t(), [0.0, 0.3, 0.6, 0.8999999999999999, 1.0]);
        assert!((r.last.q[0] - exact).abs() < 1e-15, "{}", r.last.q[0]);
        let r = run(&sys, &Dopri5::new(1e-8).unwrap(), s0, &opts).unwrap();
        assert!(r.trajectory.t().contains(&0.5));
        assert!((r.last.q[0] - exact).abs() < 1e-15, "{}", r.last.q[0]);
    }
    let r = run(
        &Kicked { report: false },
        &Rk4,
        s0,
        &RunOptions::until(1.0, 0.3),
    )
    .unwrap();
    eprintln!(
        "RK4 without the breakpoint: error {:.2e}",
        (r.last.q[0] - exact).abs()
    );
    assert!((r.last.q[0] - exact).abs() > 1e-5, "{}", r.last.q[0]);
}

/// A force that jumps at t = 0.5 (2 N before, −1 N from then on, written `if t < 0.5`) on a
/// unit mass at rest: x is a quadratic on each side, x(1) = 0.25 + 1·0.5 − 0.125 = 0.625,
/// ẋ(1) = 0.5. Every method steps onto the breakpoint and integrates up to it with the force
/// from before the jump, so each is exact to rounding; evaluated at the jump's new value in
/// the step's last stage, RK4 would miss ẋ by h·3/6.
struct Jump;

impl LagrangeSystem for Jump {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(if t < 0.5 { 2.0 } else { -1.0 }, 0.0))
    }
    fn breakpoints(&self) -> Vec<f64> {
        vec![0.5]
    }
}

#[test]
fn a_force_that_jumps_at_a_breakpoint_is_integrated_exactly() {
    let s0 = State::at_rest(Vector2::zeros());
    for h in [0.1, 0.3, 0.07] {
        let opts = RunOptions::until(1.0, h);
        let rk4 = run(&Jump, &Rk4, s0, &opts).unwrap().last;
        let dp = run(&Jump, &Dopri5::new(1e-10).unwrap(), s0, &opts).unwrap();
        for (name, last) in [("RK4", rk4), ("Dormand–Prince", dp.last)] {
            assert!(
                (last.q[0] - 0.625).abs() < 1e-14 && (last.qd[0] - 0.5).abs() < 1e-14,
                "{name}, h = {h}: x = {}, v = {}",
                last.q[0],
                last.qd[0]
            );
        }
        // No rejected steps around the jump: Dormand–Prince's error estimate sees no jump.
        assert!(
            dp.evaluations <= 6 * dp.steps + 2,
            "{} evaluations",
            dp.evaluations
        );
    }
}

/// A system whose kinks are not finite, or whose argument is not.
struct BadKinks {
    nodes: Vec<f64>,
    argument: f64,
}

impl LagrangeSystem for BadKinks {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(1.0, 0.0))
    }
    fn kinks(&self) -> Vec<Vec<f64>> {
        vec![self.nodes.clone()]
    }
    fn kink_arguments(
        &self,
        _: f64,
        q: &Vector2<f64>,
        _: &Vector2<f64>,
        out: &mut [f64],
    ) -> tmm::Result<()> {
        out[0] = q[0] * self.argument;
        Ok(())
    }
}

#[test]
fn hostile_times_breakpoints_and_kinks_give_errors_not_panics() {
    let s0 = State::at_rest(Vector2::zeros());
    let sys = Kicked { report: false };
    let methods = |opts: &RunOptions| {
        [
            run(&sys, &FiniteIncrement, s0, opts),
            run(&sys, &Rk4, s0, opts),
            run(&sys, &Dopri5::new(1e-8).unwrap(), s0, opts),
        ]
    };
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for r in methods(&RunOptions::at_times(1.0, 0.1, vec![0.5, bad])) {
            assert!(matches!(r, Err(Error::NonFinite { .. })), "{r:?}");
        }
        let mut o = RunOptions::until(1.0, 0.1);
        o.breakpoints = vec![bad];
        for r in methods(&o) {
            assert!(matches!(r, Err(Error::NonFinite { .. })), "{r:?}");
        }
    }
    for outside in [-1e-300, -1.0, 1.0 + 1e-15, 1e300] {
        for r in methods(&RunOptions::at_times(1.0, 0.1, vec![outside])) {
            assert!(matches!(r, Err(Error::OutOfRange { .. })), "{r:?}");
        }
    }
    // The ends themselves, repeats, any order: recorded once each.
    for r in methods(&RunOptions::at_times(
        1.0,
        0.1,
        vec![1.0, 0.0, 0.25, 1.0, 0.25],
    )) {
        let r = r.unwrap();
        let t = r.trajectory.t();
        assert!(t.windows(2).all(|w| w[0] < w[1]));
        assert!(t.contains(&0.25) && t[0] == 0.0 && t[t.len() - 1] == 1.0);
    }
    // Breakpoints as dense as the floating point allows, and a million of them: the run
    // ends in its budget, not a panic or a hang.
    let mut dense = vec![0.5_f64];
    for _ in 0..1000 {
        let x = *dense.last().unwrap();
        dense.push(x.next_up());
    }
    let mut many: Vec<f64> = (0..1_000_000).map(|i| f64::from(i) * 1e-6).collect();
    many.reverse();
    for bps in [dense, many] {
        let mut o = RunOptions {
            max_steps: 5000,
            ..RunOptions::until(1.0, 0.1)
        };
        o.breakpoints = bps;
        // Bounded by the step budget, not by a clock: every run ends within it.
        for r in methods(&o) {
            assert!(r.is_ok() || matches!(r, Err(Error::Budget { .. })), "{r:?}");
            if let Ok(r) = r {
                assert!(r.steps <= o.max_steps, "{} steps", r.steps);
            }
        }
    }
    // More requested times than rows: the row budget, naming the time reached.
    let o = RunOptions {
        max_rows: 100,
        ..RunOptions::at_times(1.0, 0.1, (1..1000).map(|i| f64::from(i) * 1e-3).collect())
    };
    for r in methods(&o) {
        assert!(
            matches!(r, Err(Error::Budget { what: "recorded row", time, .. }) if time < 0.2),
            "{r:?}"
        );
    }
    // Kinks that are not finite, an argument that is not.
    for (nodes, argument) in [(vec![0.1, f64::NAN], 1.0), (vec![0.1], f64::NAN)] {
        let b = BadKinks { nodes, argument };
        for r in [
            run(&b, &Rk4, s0, &RunOptions::until(1.0, 0.1)),
            run(
                &b,
                &Dopri5::new(1e-8).unwrap(),
                s0,
                &RunOptions::until(1.0, 0.1),
            ),
        ] {
            assert!(
                matches!(
                    r,
                    Err(Error::NonFinite { .. } | Error::NonFiniteState { .. })
                ),
                "{r:?}"
            );
        }
    }
    // Kinks at unsorted, repeated nodes are located all the same: x = t²/2 reaches each.
    let b = BadKinks {
        nodes: vec![0.3, 0.02, 0.3, -1.0],
        argument: 1.0,
    };
    for r in [
        run(&b, &Rk4, s0, &RunOptions::until(1.0, 0.25)).unwrap(),
        run(
            &b,
            &Dopri5::new(1e-8).unwrap(),
            s0,
            &RunOptions::until(1.0, 0.25),
        )
        .unwrap(),
    ] {
        assert!((r.last.q[0] - 0.5).abs() < 1e-14);
    }
    // They are located, not ignored: the same runs without kinks spend fewer evaluations
    // (locating a node re-steps from the step's start).
    let plain = BadKinks {
        nodes: Vec::new(),
        argument: 1.0,
    };
    for (with, without) in [
        (
            run(&b, &Rk4, s0, &RunOptions::until(1.0, 0.25)).unwrap(),
            run(&plain, &Rk4, s0, &RunOptions::until(1.0, 0.25)).unwrap(),
        ),
        (
            run(
                &b,
                &Dopri5::new(1e-8).unwrap(),
                s0,
                &RunOptions::until(1.0, 0.25),
            )
            .unwrap(),
            run(
                &plain,
                &Dopri5::new(1e-8).unwrap(),
                s0,
                &RunOptions::until(1.0, 0.25),
            )
            .unwrap(),
        ),
    ] {
        assert!(
            with.evaluations > without.evaluations,
            "{} vs {}",
            with.evaluations,
            without.evaluations
        );
    }
}
