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
/// at steps up to 40 times that test's: every run stops there, at the band's edge.
#[test]
#[ignore = "issue 27, open: at h = 6.5e-3 the run ends FinalTime, its rows' least |det| 5.6e-3"]
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
    for n in [100.0, 200.0, 400.0, 1000.0, 4000.0] {
        let h = 0.65 / n;
        let r = run(&sys, &Rk4, State::at_rest(q0), &RunOptions::until(0.65, h)).unwrap();
        println!(
            "h {h:e}: {:?}, rows' least |det| and a flip {:?}",
            r.outcome,
            rows_det(&sys, &r)
        );
        let (t, det) = stop(&sys, &r, &format!("RK4 {h}"));
        println!("h {h:e}: t {t} (|det| {det:.6e}) vs DP {:.2e}", t - t_ref);
        assert!(det > 1e-3 && det < 1.001e-3, "h {h}: |det| {det:e}");
    }
}

/// The five-bar robot under random constant motors on both inputs, thrown at random speeds,
/// by RK4 at a coarse step h and at h/16: where the fine run stops at a dead centre, the
/// coarse one must not run on past it (a band stepped across); it stops there too, or
/// within a few steps of it where the two paths differ by RK4's error.
#[test]
#[ignore = "issue 27, open: 7 of 148 coarse runs end FinalTime where h/16 stops at a dead centre"]
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
