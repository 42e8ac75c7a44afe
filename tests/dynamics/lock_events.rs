//! Locks and dead centres met by coarse fixed steps: the stop located as with a fine step.

use nalgebra::Vector2;
use tmm::dynamics::{run, Dopri5, Outcome, Rk4, RunOptions, RunResult, State};
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, LoadSpec};

/// The bundled four-bar driven from its rocker, its resistance taken off, a constant moment
/// `m` on the rocker.
fn rocker_driven(m: f64) -> LinkageSystem {
    let mut l = bundled::four_bar();
    l.input = tmm::linkage::Input::crank("rocker");
    l.groups.clear();
    l.modes.clear();
    l.loads
        .retain(|x| !matches!(x, LoadSpec::Resistance { .. }));
    LinkageSystem::from_linkage(&l)
        .unwrap()
        .with_motor(0, Motor::Constant(m))
        .unwrap()
}

/// The dead centre a run stopped at: its time, and the |det| of the dyad at the last state.
fn stop(sys: &LinkageSystem, r: &RunResult, what: &str) -> (f64, f64) {
    let Outcome::DeadCentre { t, dyad, value } = r.outcome else {
        panic!("{what}: {:?}", r.outcome)
    };
    assert!(value.abs() <= 1e-3, "{what}: {value}");
    let inputs: Vec<Motion> = (0..sys.dof()).map(|k| Motion::fixed(r.last.q[k])).collect();
    let k = match inputs.len() {
        1 => sys.plan().kinematics(inputs[0]).unwrap(),
        _ => sys.plan().kinematics([inputs[0], inputs[1]]).unwrap(),
    };
    (t, k.group_determinants()[dyad].abs())
}

/// The smallest |det| of the dyads over a two-input run's recorded rows, and whether a
/// dyad's det changed sign between rows.
fn rows_det(sys: &LinkageSystem, r: &RunResult) -> (f64, bool) {
    let tr = &r.trajectory;
    let mut least = f64::INFINITY;
    let mut prev: Option<Vec<f64>> = None;
    let mut flipped = false;
    for i in 0..tr.len() {
        let m = |k: usize| Motion::fixed(tr.q()[k][i]);
        let Ok(k) = sys.plan().kinematics([m(0), m(1)]) else {
            continue;
        };
        let d = k.group_determinants().to_vec();
        least = d.iter().fold(least, |a, x| a.min(x.abs()));
        if let Some(p) = &prev {
            flipped |= p.iter().zip(&d).any(|(a, b)| a * b < 0.0);
        }
        prev = Some(d);
    }
    (least, flipped)
}

/// The rocker-driven four-bar thrown towards its lock (as
/// `a_rocker_driven_four_bar_stops_at_its_lock_when_the_energy_equation_says`), by RK4 with
/// steps from 10⁻⁴ to 3·10⁻² s and a quarter of each: every run stops at a dead centre, its
/// located state's |det| within 0.1 % above the threshold 10⁻³ (the last accepted state at
/// the band's edge: bisecting on a longer step's refusal stopped some per cent short, and at
/// 3·10⁻² the run ended `Err(NotAssemblable)`, its stages jumping the band). The stop times
/// are printed against Dormand–Prince at 10⁻¹²: at 10⁻⁴ and 3·10⁻⁴ within 5·10⁻⁶ s; at
/// 7.5·10⁻³ and 7.5·10⁻⁴ the coarse path turns back short of the band (the reduced
/// inertia's derivative, unresolved) and meets it at 0.15 s (still open).
#[test]
fn a_coarse_step_locates_a_lock_at_the_bands_edge() {
    let start = |sys: &LinkageSystem| {
        State::new(
            0.0,
            Vector2::new(sys.plan().reference_input(), 0.0),
            Vector2::new(3.0, 0.0),
        )
    };
    let sys = rocker_driven(30.0);
    let dp = run(
        &sys,
        &Dopri5::new(1e-12).unwrap(),
        start(&sys),
        &RunOptions::until(5.0, 1e-3),
    )
    .unwrap();
    let (t_ref, _) = stop(&sys, &dp, "Dormand-Prince");
    for h in [3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4] {
        let r = run(&sys, &Rk4, start(&sys), &RunOptions::until(5.0, h)).unwrap();
        let (t, det) = stop(&sys, &r, &format!("RK4 {h}"));
        let r4 = run(&sys, &Rk4, start(&sys), &RunOptions::until(5.0, h / 4.0)).unwrap();
        let (t4, det4) = stop(&sys, &r4, &format!("RK4 {h}/4"));
        println!(
            "h {h:e}: t {t} (|det| {det:.6e}), h/4 {t4} (|det| {det4:.6e}); vs DP {:.2e}, {:.2e}",
            t - t_ref,
            t4 - t_ref
        );
        assert!(det > 1e-3 && det < 1.001e-3, "h {h}: |det| {det:e}");
        assert!(det4 > 1e-3 && det4 < 1.001e-3, "h {h}/4: |det| {det4:e}");
    }
}

/// The five-bar robot, a motor on its first input only, runs into the dead centre of its
/// coupler dyad (as `a_run_into_a_dead_centre_of_two_inputs_stops_there_naming_the_dyad`),
/// at steps up to 40 times that test's: every run stops there, at the band's edge (at
/// h = 6.5·10⁻³ the steps jumped the band's V until the run read the lock measures at each
/// step's ends). The stop times converge to Dormand–Prince's at 10⁻¹² at RK4's order: from
/// h to h/4 the error falls at least eightfold at every h, and by 4³ and 4⁴/2 at the two
/// finest (measured: 10.4, 11.3, 14.8, 123, 295; 4⁴ = 256).
#[test]
fn a_coarse_step_into_a_two_input_dead_centre_stops_at_the_bands_edge() {
    let sys = LinkageSystem::from_linkage(&bundled::five_bar_robot())
        .unwrap()
        .with_motor(0, Motor::Constant(1.0))
        .unwrap();
    let q0 = Vector2::from_vec(sys.plan().reference_inputs());
    let dp = run(
        &sys,
        &Dopri5::new(1e-12).unwrap(),
        State::at_rest(q0),
        &RunOptions::until(0.65, 1e-3),
    )
    .unwrap();
    let (t_ref, _) = stop(&sys, &dp, "Dormand-Prince");
    let stop_at = |h: f64| {
        let r = run(&sys, &Rk4, State::at_rest(q0), &RunOptions::until(0.65, h)).unwrap();
        println!(
            "h {h:e}: {:?}, rows' least |det| and a flip {:?}",
            r.outcome,
            rows_det(&sys, &r)
        );
        let (t, det) = stop(&sys, &r, &format!("RK4 {h}"));
        assert!(det > 1e-3 && det < 1.001e-3, "h {h}: |det| {det:e}");
        t
    };
    let mut ratios = Vec::new();
    for n in [100.0, 200.0, 400.0, 1000.0, 4000.0] {
        let h = 0.65 / n;
        let (t, t4) = (stop_at(h), stop_at(h / 4.0));
        let (e, e4) = ((t - t_ref).abs(), (t4 - t_ref).abs());
        println!(
            "h {h:e}: t {t}, h/4 {t4}; vs DP {e:.2e}, {e4:.2e}, ratio {:.1}",
            e / e4
        );
        assert!(e4 <= e / 8.0, "h {h}: {e:e} then {e4:e}");
        ratios.push(e / e4);
    }
    assert!(ratios[3] >= 4f64.powi(3), "{ratios:?}");
    assert!(ratios[4] >= 0.5 * 4f64.powi(4), "{ratios:?}");
}

/// The five-bar robot under random constant motors on both inputs, thrown at random speeds,
/// by RK4 at a coarse step h and at h/16: where the fine run stops at a dead centre, the
/// coarse one must not run on past it (a band stepped across); it stops there too, or
/// within a few steps of it where the two paths differ by RK4's error. (Before the run read
/// the lock measures at each step's ends, 7 of 148 coarse runs went on past the band.)
#[test]
fn coarse_two_input_runs_do_not_step_across_a_dead_centre() {
    let base = LinkageSystem::from_linkage(&bundled::five_bar_robot()).unwrap();
    let q0 = Vector2::from_vec(base.plan().reference_inputs());
    let mut g = crate::common::hostile_gen::Gen::new(808);
    let (mut both, mut across, mut neither) = (0, 0, 0);
    for case in 0..200 {
        let m = [4.0 * (g.unit() - 0.5), 4.0 * (g.unit() - 0.5)];
        let sys = base
            .clone()
            .with_motor(0, Motor::Constant(m[0]))
            .unwrap()
            .with_motor(1, Motor::Constant(m[1]))
            .unwrap();
        let w = Vector2::new(20.0 * (g.unit() - 0.5), 20.0 * (g.unit() - 0.5));
        let h = 10f64.powf(-3.0 + 1.5 * g.unit());
        let start = State::new(0.0, q0, w);
        let t_end = 0.5;
        let coarse = run(&sys, &Rk4, start, &RunOptions::until(t_end, h));
        let fine = run(&sys, &Rk4, start, &RunOptions::until(t_end, h / 16.0));
        let (Ok(coarse), Ok(fine)) = (coarse, fine) else {
            continue;
        };
        let dead = |r: &RunResult| match r.outcome {
            Outcome::DeadCentre { t, .. } => Some(t),
            _ => None,
        };
        match (dead(&coarse), dead(&fine)) {
            (Some(_), Some(_)) => both += 1,
            (None, Some(t)) => {
                across += 1;
                println!(
                    "case {case}: M {m:?}, ω {w:?}, h {h:e}: fine stops at t {t}, coarse ends {:?} at {}",
                    coarse.outcome, coarse.last.t
                );
                println!(
                    "   coarse rows {:?}, fine rows {:?}",
                    rows_det(&sys, &coarse),
                    rows_det(&sys, &fine)
                );
            }
            _ => neither += 1,
        }
    }
    println!("two inputs: both stop {both}, coarse runs across {across}, other {neither}");
    assert_eq!(across, 0);
}

/// The lock walk's bound: a run that grazes its lock. The rocker-driven four-bar thrown
/// towards its lock against a moment of −30 N·m, at the speed (found by bisection with the
/// same RK4 step, 60 halvings) below which the motion turns back short of the band and above
/// which it reaches it: its kinetic energy dies where it reaches the band, so the walk that
/// locates the last accepted state closes in ever more slowly. The run ends `Ok` with
/// [`Outcome::DeadCentre`] at an accepted state (|det| > 10⁻³; the refused one's at most
/// 10⁻³) within the walk's bound, 8·log2(h/tol) + 8 steps past the grid step that met the
/// band (tol = 10⁻¹² of max(1, |t|)), never by the run's whole budget.
#[test]
fn a_run_grazing_its_lock_ends_within_the_walks_bound() {
    let sys = rocker_driven(-30.0);
    let plan = sys.plan().clone();
    let phi0 = plan.reference_input();
    let start = |w: f64| State::new(0.0, Vector2::new(phi0, 0.0), Vector2::new(w, 0.0));
    for h in [1e-3, 1e-4] {
        let mut opts = RunOptions::until(1.0, h);
        opts.max_steps = 1_000_000;
        let go = |w: f64| run(&sys, &Rk4, start(w), &opts).unwrap();
        // At the upper lock (the motion's way from the start), not the lower one it swings
        // back to.
        // A run that ends in an error has met the lock too (the final run must not).
        let reaches = |w: f64| match run(&sys, &Rk4, start(w), &opts) {
            Ok(r) => matches!(r.outcome, Outcome::DeadCentre { .. }) && r.last.q[0] > phi0,
            Err(_) => true,
        };
        let (mut lo, mut hi) = (0.0, 1.0);
        while !reaches(hi) {
            (lo, hi) = (hi, 2.0 * hi);
            assert!(hi < 1e3, "h {h}: no speed reaches the lock");
        }
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if reaches(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let r = go(hi);
        let Outcome::DeadCentre { t, value, .. } = r.outcome else {
            panic!("h {h}: {:?}", r.outcome)
        };
        assert_eq!(t, r.last.t);
        assert!(value.abs() <= 1e-3, "h {h}: {value}");
        let det = plan
            .kinematics(Motion::fixed(r.last.q[0]))
            .unwrap()
            .group_determinants()[0]
            .abs();
        assert!(det > 1e-3, "h {h}: the last state's |det| {det}");
        // The grid steps up to the one that met the band, then the walk.
        let grid = (r.last.t / h).ceil() as usize + 1;
        let tol = 1e-12 * t.abs().max(1.0);
        let bound = 8 * (h / tol).log2() as usize + 8;
        println!(
            "h {h:e}: ω₀ {hi} (bracket {:.1e}), stop t {t}, |det| {det:.6e}, q̇ {:.3e}, steps {} = grid {grid} + walk {} (bound {bound})",
            hi - lo,
            r.last.qd[0],
            r.steps,
            r.steps.saturating_sub(grid)
        );
        assert!(r.steps <= grid + bound, "h {h}: {} steps", r.steps);
    }
}
