//! A hostile sweep of [`LinkageSystem`] with joint friction: every bundled linkage that makes a
//! machine, a random coefficient f ∈ [0, 0.5] on pins of random radius (sometimes a hostile
//! coefficient or radius), a random start (sometimes hostile numbers), random motors and each
//! integrator (RK4, Dopri5, the finite-increment method). Every run must end within its
//! budget with either finite rows and a stop it names (the final time, stuck, jammed) or a
//! clear error, never a panic, a NaN or an infinity.
//!
//! `TMM_HOSTILE_CASES` runs (default 24 here: each is a run with friction solves at every
//! evaluation, so the quick default is smaller than the other sweeps'); a long sweep:
//! `TMM_HOSTILE_CASES=100000 cargo test --release --test tmm linkage::hostile_friction`.

use std::panic::{catch_unwind, AssertUnwindSafe};

use nalgebra::Vector2;
use tmm::dynamics::{run, Dopri5, FiniteIncrement, Outcome, Rk4, RunOptions, RunResult, State};
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, Friction, Linkage, Plan};

use crate::common::hostile_gen::{has_non_finite, Gen};

/// The runs of the sweep: `TMM_HOSTILE_CASES`, 24 when it is not set.
fn cases() -> usize {
    std::env::var("TMM_HOSTILE_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(24)
}

/// The bundled linkages that make a machine, with their size.
fn machines() -> Vec<(Linkage, f64)> {
    bundled::all()
        .into_iter()
        .filter(|l| LinkageSystem::from_linkage(l).is_ok())
        .map(|l| {
            let size = Plan::new(&l).unwrap().size();
            (l, size)
        })
        .collect()
}

/// A run's options: 0.02 s in steps of 10⁻³ s (fixed-step methods), bounded budgets.
fn options(g: &mut Gen) -> RunOptions {
    let mut opts = RunOptions::until(0.02, 1e-3);
    opts.max_steps = 400;
    opts.max_evaluations = 4000;
    if g.next().is_multiple_of(8) {
        opts.t_end = g.f();
    }
    opts
}

/// One run with method number `m`.
fn run_with(
    sys: &LinkageSystem,
    m: u64,
    start: State,
    opts: &RunOptions,
) -> tmm::Result<RunResult> {
    match m % 3 {
        0 => run(sys, &Rk4, start, opts),
        1 => run(sys, &Dopri5::new(1e-7)?, start, opts),
        _ => run(sys, &FiniteIncrement, start, opts),
    }
}

/// What a run returned is a clear result: finite rows within the budget and a named stop, or
/// an error with a message.
fn check(r: &tmm::Result<RunResult>, opts: &RunOptions, what: &str) -> &'static str {
    match r {
        Ok(r) => {
            let text = format!("{r:?}");
            assert!(!has_non_finite(&text), "{what}: a NaN or inf in {text}");
            assert!(!r.trajectory.is_empty(), "{what}: no rows");
            assert!(r.steps <= opts.max_steps, "{what}: {} steps", r.steps);
            let last = *r.trajectory.t().last().unwrap();
            assert_eq!(last, r.last.t, "{what}: the last row is the last state");
            match r.outcome {
                Outcome::FinalTime => {
                    assert!((last - opts.t_end).abs() <= 1e-9 * opts.t_end.abs().max(1.0));
                    "final time"
                }
                Outcome::Stuck { t, .. } => {
                    assert!(t <= opts.t_end && t == last, "{what}: stuck at {t}");
                    "stuck"
                }
                Outcome::Jammed { t, value, .. } => {
                    assert!(t <= opts.t_end + 1e-9 && t >= last, "{what}: jam at {t}");
                    assert!(value <= 1.5e-8, "{what}: det {value}");
                    "jammed"
                }
                ref o => panic!("{what}: a run without a watch ends {o:?}"),
            }
        }
        Err(e) => {
            let text = e.to_string();
            assert!(
                !text.is_empty() && !text.contains("panicked"),
                "{what}: {e:?}"
            );
            "error"
        }
    }
}

#[test]
fn hostile_runs_of_linkages_with_friction_end_with_a_reason() {
    let all = machines();
    assert!(all.len() >= 5, "{} machines", all.len());
    let mut g = Gen::new(24);
    let mut counts = std::collections::BTreeMap::<&str, usize>::new();
    for case in 0..cases() {
        let (l, size) = &all[case % all.len()];
        let mut l = l.clone();
        let hostile = g.next().is_multiple_of(6);
        let (f, r) = if hostile {
            (g.f(), g.f())
        } else {
            (0.5 * g.unit(), size * (0.002 + 0.05 * g.unit()))
        };
        l.friction = Some(Friction::pin(f, r));
        let what = format!("{} case {case}: f {f:e}, pin {r:e}", l.name);
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            let sys = match LinkageSystem::from_linkage(&l) {
                Ok(s) => s,
                Err(e) => {
                    assert!(hostile, "{what}: ordinary friction refused: {e}");
                    return "refused";
                }
            };
            let plan = sys.plan().clone();
            let n = plan.input_count();
            let reference = plan.reference_inputs();
            // A crank turns by up to ±1 rad from its reference, a slider by ±0.2 of the size.
            let span = |k: usize| {
                if plan.input_is_crank() || k == 1 {
                    1.0
                } else {
                    0.2 * size
                }
            };
            let mut q = Vector2::zeros();
            let mut qd = Vector2::zeros();
            for k in 0..n {
                q[k] = reference[k] + span(k) * (2.0 * g.unit() - 1.0);
                qd[k] = if g.next().is_multiple_of(4) {
                    0.0
                } else {
                    span(k) * 20.0 * (2.0 * g.unit() - 1.0)
                };
            }
            if g.next().is_multiple_of(7) {
                q[0] = g.f();
                qd[n - 1] = g.f();
            }
            let mut sys = sys;
            let mut motors = [0.0; 2];
            for (k, motor) in motors.iter_mut().enumerate().take(n) {
                let m = if g.next().is_multiple_of(9) {
                    g.f()
                } else {
                    50.0 * size * (2.0 * g.unit() - 1.0)
                };
                *motor = m;
                sys = match sys.with_motor(k, Motor::Constant(m)) {
                    Ok(s) => s,
                    Err(_) => return "refused",
                };
            }
            let opts = options(&mut g);
            let start = State::new(0.0, q, qd);
            let m = g.next();
            let what = format!(
                "{what}, q {q:?}, q' {qd:?}, motors {motors:?}, method {}",
                m % 3
            );
            check(&run_with(&sys, m, start, &opts), &opts, &what)
        }))
        .unwrap_or_else(|_| panic!("panicked: {what}"));
        *counts.entry(outcome).or_default() += 1;
    }
    println!("hostile runs with friction: {counts:?}");
    // The sweep meets ordinary motion, not only refusals.
    assert!(
        counts.get("final time").copied().unwrap_or(0) + counts.get("stuck").copied().unwrap_or(0)
            > 0,
        "{counts:?}"
    );
}
