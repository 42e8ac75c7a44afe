//! tmm's steppers beside a well-kept ODE crate, ode_solvers (its `Rk4` and `Dopri5`), on the
//! same right-hand side: `tmm::dynamics::accelerations` of the coaxial-propeller drive, of
//! the five-bar robot and of a cheap linear two-mass oscillator (where the integrators' own
//! work is a large part of the time), packed as y = (q1, q2, q̇1, q̇2). The two integrate the same problem at
//! the same step size (RK4) or the same tolerance (rtol = atol, Dormand–Prince), in one
//! group per machine, so the ratio is measured side by side. Before timing, each pair's
//! evaluation counts and final-time errors (against a reference run at a tolerance of 10⁻¹⁴)
//! are printed, so that the times compare equal work at equal accuracy; for Dormand–Prince
//! also across tolerances 10⁻⁵…10⁻¹² (its step-size controller decides the work, and one
//! tolerance alone can be lucky or unlucky for either). ode_solvers stores every step it takes
//! (it has no "final state only" mode); tmm's run is told to record nothing on the way.
//!
//! The ratios are printed twice: in wall time (`yardstick | …`, the fastest of alternating
//! rounds) and in this thread's CPU time (`cpu | …`, which a loaded machine inflates less).
//!
//! With `TMM_PEERS_BARE=1` the RK4 runs are also timed against a bare loop of `Rk4::step`
//! calls (and a run of one step against one step): what `run` costs beyond the stepping, a
//! fixed part per call (recording the start and the end, checking the options) and a part per
//! step.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Matrix2, Vector2};
use ode_solvers::dop_shared::OutputType;
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar};
use tmm::dynamics::{accelerations, run, Dopri5, LagrangeSystem, Rk4, RunOptions, State};

#[path = "common/yardstick.rs"]
mod yardstick;

#[path = "common/cpu_ratio.rs"]
mod cpu_ratio;

type Y = ode_solvers::Vector4<f64>;

/// A tmm machine as an ode_solvers system.
struct Peer<'a, S>(&'a S);

impl<S: LagrangeSystem> ode_solvers::System<f64, Y> for Peer<'_, S> {
    fn system(&self, t: f64, y: &Y, dy: &mut Y) {
        let (q, qd) = (Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]));
        // A failure (none on these runs) becomes a NaN, which ends the comparison visibly.
        let a = accelerations(self.0, t, &q, &qd).unwrap_or(Vector2::repeat(f64::NAN));
        *dy = Y::new(qd[0], qd[1], a[0], a[1]);
    }
}

/// Two masses (2 and 1.5 kg, coupled through a mass term of 0.3) on springs and dampers under
/// constant forces: A q̈ + B q̇ + K q = f with everything constant, the cheapest right-hand
/// side a machine has.
struct Oscillator;

impl LagrangeSystem for Oscillator {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(2.0, 0.3, 0.3, 1.5))
    }
    fn inertia_derivatives(&self, _: &Vector2<f64>) -> tmm::Result<[Matrix2<f64>; 2]> {
        Ok([Matrix2::zeros(); 2])
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(1.0, -0.5))
    }
    fn potential_gradient(&self, q: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Matrix2::new(3.0, 0.5, 0.5, 2.0) * q)
    }
    fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(0.4, 0.1, 0.1, 0.2))
    }
}

/// The same job as the peer's: no kinks located (the five-bar's servo switches are), no
/// trajectory kept.
fn options(t_end: f64, h: f64) -> RunOptions {
    RunOptions {
        record_every: usize::MAX,
        locate_kinks: false,
        ..RunOptions::until(t_end, h)
    }
}

fn tmm_rk4<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, h: f64) -> (State, usize) {
    let r = run(sys, &Rk4, s0, &options(t_end, h)).expect("runs");
    (r.last, r.evaluations)
}

fn tmm_dopri<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, tol: f64) -> (State, usize) {
    let dp = Dopri5::new(tol).expect("positive tolerance");
    let r = run(sys, &dp, s0, &options(t_end, 1e-3 * t_end)).expect("runs");
    (r.last, r.evaluations)
}

fn y0(s: State) -> Y {
    Y::new(s.q[0], s.q[1], s.qd[0], s.qd[1])
}

fn peer_rk4<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, h: f64) -> (Y, u32) {
    let mut p = ode_solvers::Rk4::new(Peer(sys), s0.t, y0(s0), t_end, h);
    let stats = p.integrate().expect("integrates");
    (*p.y_out().last().expect("a state"), stats.num_eval)
}

fn peer_dopri<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, tol: f64) -> (Y, u32) {
    let mut p = ode_solvers::Dopri5::from_param(
        Peer(sys),
        s0.t,
        t_end,
        t_end,
        y0(s0),
        tol,
        tol,
        0.9,
        0.04,
        0.2,
        10.0,
        t_end,
        1e-3 * t_end,
        100_000,
        1000,
        OutputType::Sparse,
    );
    let stats = p.integrate().expect("integrates");
    (*p.y_out().last().expect("a state"), stats.num_eval)
}

/// The largest difference of the components of y = (q, q̇).
fn difference(a: &State, b: &Y) -> f64 {
    [a.q[0] - b[0], a.q[1] - b[1], a.qd[0] - b[2], a.qd[1] - b[3]]
        .iter()
        .fold(0.0, |m: f64, d| m.max(d.abs()))
}

/// The final state at a tolerance far below the compared ones: each method's error is its
/// distance to this.
fn reference<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64) -> Y {
    y0(tmm_dopri(sys, s0, t_end, 1e-14).0)
}

/// Dormand–Prince's evaluations and final errors, tmm beside ode_solvers, across tolerances
/// (printed), and the ratio of their total evaluations.
fn dopri_sweep<S: LagrangeSystem>(machine: &str, sys: &S, s0: State, t_end: f64, exact: &Y) {
    let (mut sum_tmm, mut sum_peer) = (0usize, 0usize);
    for k in 5..=12 {
        let tol = 10f64.powi(-k);
        let (a, na) = tmm_dopri(sys, s0, t_end, tol);
        let (b, nb) = peer_dopri(sys, s0, t_end, tol);
        let eb = (b - exact).amax();
        println!(
            "{machine}, Dormand-Prince tol = 1e-{k}: tmm {na} evaluations, error {:.2e}; \
             ode_solvers {nb}, error {eb:.2e}",
            difference(&a, exact)
        );
        (sum_tmm, sum_peer) = (sum_tmm + na, sum_peer + nb as usize);
    }
    println!(
        "{machine}, Dormand-Prince over tolerances 1e-5..1e-12: tmm {sum_tmm} evaluations, \
         ode_solvers {sum_peer} (ratio {:.3})",
        sum_tmm as f64 / sum_peer as f64
    );
}

fn side_by_side<S: LagrangeSystem>(
    c: &mut Criterion,
    machine: &str,
    sys: &S,
    s0: State,
    t_end: f64,
    h: f64,
    tol: f64,
) {
    let exact = reference(sys, s0, t_end);
    let peer_error = |b: &Y| (b - exact).amax();
    let (a, na) = tmm_rk4(sys, s0, t_end, h);
    let (b, nb) = peer_rk4(sys, s0, t_end, h);
    println!(
        "{machine}, RK4 h = {h}: tmm {na} evaluations, error {:.2e}; ode_solvers {nb}, error {:.2e}",
        difference(&a, &exact),
        peer_error(&b)
    );
    let (a, na) = tmm_dopri(sys, s0, t_end, tol);
    let (b, nb) = peer_dopri(sys, s0, t_end, tol);
    println!(
        "{machine}, Dormand-Prince tol = {tol}: tmm {na} evaluations, error {:.2e}; ode_solvers {nb}, error {:.2e}",
        difference(&a, &exact),
        peer_error(&b)
    );
    dopri_sweep(machine, sys, s0, t_end, &exact);

    if std::env::var("TMM_PEERS_BARE").is_ok() {
        let bare = |sys: &S| {
            let mut st = s0;
            let n = (t_end / h).round() as usize;
            for _ in 0..n {
                st = tmm::dynamics::Stepper::step(&Rk4, sys, &st, h).expect("steps");
            }
            st
        };
        yardstick::print_ratio(
            &format!("{machine}, RK4 run (bare step loop as the yardstick)"),
            1,
            || tmm_rk4(black_box(sys), black_box(s0), t_end, h),
            || bare(black_box(sys)),
        );
        yardstick::print_ratio(
            &format!("{machine}, RK4 run of one step (one bare step as the yardstick)"),
            1,
            || tmm_rk4(black_box(sys), black_box(s0), h, h),
            || tmm::dynamics::Stepper::step(&Rk4, black_box(sys), &black_box(s0), h),
        );
        yardstick::print_ratio(
            &format!("{machine}, RK4 bare step loop (ode_solvers as the yardstick)"),
            1,
            || bare(black_box(sys)),
            || peer_rk4(black_box(sys), black_box(s0), t_end, h),
        );
    }
    yardstick::print_ratio(
        &format!("{machine}, RK4 (ode_solvers as the yardstick)"),
        1,
        || tmm_rk4(black_box(sys), black_box(s0), t_end, h),
        || peer_rk4(black_box(sys), black_box(s0), t_end, h),
    );
    yardstick::print_ratio(
        &format!("{machine}, Dormand-Prince (ode_solvers as the yardstick)"),
        1,
        || tmm_dopri(black_box(sys), black_box(s0), t_end, tol),
        || peer_dopri(black_box(sys), black_box(s0), t_end, tol),
    );
    // The same two ratios in this thread's CPU time (what a loaded machine does not inflate).
    cpu_ratio::print_cpu_ratio(
        &format!("{machine}, RK4 (ode_solvers as the yardstick)"),
        1,
        20,
        || tmm_rk4(black_box(sys), black_box(s0), t_end, h),
        || peer_rk4(black_box(sys), black_box(s0), t_end, h),
    );
    cpu_ratio::print_cpu_ratio(
        &format!("{machine}, Dormand-Prince (ode_solvers as the yardstick)"),
        1,
        20,
        || tmm_dopri(black_box(sys), black_box(s0), t_end, tol),
        || peer_dopri(black_box(sys), black_box(s0), t_end, tol),
    );
    let mut g = c.benchmark_group(format!("peers/{machine}"));
    g.measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300))
        .sample_size(20);
    g.bench_with_input(BenchmarkId::new("tmm RK4", h), &h, |bch, &h| {
        bch.iter(|| tmm_rk4(black_box(sys), black_box(s0), t_end, h))
    });
    g.bench_with_input(BenchmarkId::new("ode_solvers Rk4", h), &h, |bch, &h| {
        bch.iter(|| peer_rk4(black_box(sys), black_box(s0), t_end, h))
    });
    g.bench_with_input(BenchmarkId::new("tmm Dopri5", tol), &tol, |bch, &tol| {
        bch.iter(|| tmm_dopri(black_box(sys), black_box(s0), t_end, tol))
    });
    g.bench_with_input(
        BenchmarkId::new("ode_solvers Dopri5", tol),
        &tol,
        |bch, &tol| bch.iter(|| peer_dopri(black_box(sys), black_box(s0), t_end, tol)),
    );
    g.finish();
}

fn peers(c: &mut Criterion) {
    side_by_side(
        c,
        "linear oscillator 10 s",
        &Oscillator,
        State::at_rest(Vector2::zeros()),
        10.0,
        1e-2,
        1e-8,
    );
    side_by_side(
        c,
        "coaxial propellers 1 s",
        &CoaxialPropellers::default(),
        State::at_rest(Vector2::zeros()),
        1.0,
        1e-2,
        1e-8,
    );
    side_by_side(
        c,
        "five-bar 0.5 s",
        &FiveBar::default(),
        State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians())),
        0.5,
        1e-3,
        1e-8,
    );
}

criterion_group!(benches, peers);
criterion_main!(benches);
