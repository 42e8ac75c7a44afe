//! One step of each stepper on each machine, and RK4 on the five-bar across step sizes.
//!
//! The yardstick: the Lagrange right-hand side of a small linear system (constant inertia,
//! damping and stiffness, a constant drive) written by hand as a bare Cramer solve of
//! A q̈ = Q − K q − B q̇, checked against `accelerations` before timing, over the same batch of
//! seeded states; the bench prints the ratio tmm/yardstick (a `yardstick | …` line).
//!
//! A run that records every step against the same job by hand: a loop of bare steps that
//! pushes each state onto a `Trajectory` (q̈, energies, powers and outputs per row). The run
//! hands each row's q̈ on to the next step as its first stage; the loop evaluates them twice.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar, LandingGear, RpArm};
use tmm::dynamics::{
    accelerations, run, Dopri5, FiniteIncrement, LagrangeSystem, Rk4, RunOptions, State, Stepper,
    Trajectory,
};

#[path = "common/yardstick.rs"]
mod yardstick;

/// A small linear machine: A q̈ + B q̇ + K q = f, all constant.
struct Linear {
    a: Matrix2<f64>,
    b: Matrix2<f64>,
    k: Matrix2<f64>,
    f: Vector2<f64>,
}

impl LagrangeSystem for Linear {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(self.a)
    }
    fn inertia_derivatives(&self, _: &Vector2<f64>) -> tmm::Result<[Matrix2<f64>; 2]> {
        Ok([Matrix2::zeros(); 2])
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(self.f)
    }
    fn potential_gradient(&self, q: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(self.k * q)
    }
    fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(self.b)
    }
}

/// The same right-hand side by hand: Cramer's rule on A q̈ = f − K q − B q̇.
#[inline]
fn linear_by_hand(s: &Linear, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
    let r = s.f - s.k * q - s.b * qd;
    let a = &s.a;
    let det = a[(0, 0)] * a[(1, 1)] - a[(0, 1)] * a[(1, 0)];
    Vector2::new(
        (r[0] * a[(1, 1)] - r[1] * a[(0, 1)]) / det,
        (r[1] * a[(0, 0)] - r[0] * a[(1, 0)]) / det,
    )
}

fn lagrange_yardstick(c: &mut Criterion) {
    let sys = Linear {
        a: Matrix2::new(2.0, 0.3, 0.3, 1.5),
        b: Matrix2::new(0.4, 0.1, 0.1, 0.2),
        k: Matrix2::new(50.0, -10.0, -10.0, 30.0),
        f: Vector2::new(1.0, -2.0),
    };
    let mut rng = Rng(11);
    let states: Vec<(Vector2<f64>, Vector2<f64>)> = (0..1024)
        .map(|_| {
            (
                Vector2::new(rng.next() - 0.5, rng.next() - 0.5),
                Vector2::new(rng.next() - 0.5, rng.next() - 0.5),
            )
        })
        .collect();
    for (q, qd) in &states {
        let a = accelerations(&sys, 0.0, q, qd).expect("regular");
        let b = linear_by_hand(&sys, q, qd);
        assert!(
            (a - b).norm() <= 1e-12 * (1.0 + b.norm()),
            "Lagrange yardstick"
        );
    }
    let tmm = || {
        states
            .iter()
            .map(|(q, qd)| accelerations(black_box(&sys), 0.0, q, qd).map_or(0.0, |a| a[0] + a[1]))
            .sum::<f64>()
    };
    let by_hand = || {
        states
            .iter()
            .map(|(q, qd)| {
                let a = linear_by_hand(black_box(&sys), q, qd);
                a[0] + a[1]
            })
            .sum::<f64>()
    };
    yardstick::print_ratio(
        "Lagrange right-hand side (linear, 2 DOF)",
        1024,
        tmm,
        by_hand,
    );
    let mut g = c.benchmark_group("lagrange_rhs_yardstick");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .throughput(criterion::Throughput::Elements(1024));
    g.bench_function("tmm", |b| b.iter(tmm));
    g.bench_function("yardstick", |b| b.iter(by_hand));
    g.finish();
}

/// A deterministic generator (SplitMix64) for the start states.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn one_step<S: LagrangeSystem>(c: &mut Criterion, machine: &str, sys: &S, s: State, h: f64) {
    let mut g = c.benchmark_group(format!("step/{machine}"));
    g.measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300))
        .sample_size(20);
    g.bench_function("finite increments", |b| {
        b.iter(|| FiniteIncrement.step(black_box(sys), black_box(&s), h))
    });
    g.bench_function("RK4", |b| {
        b.iter(|| Rk4.step(black_box(sys), black_box(&s), h))
    });
    let dp = Dopri5::new(1e-8).expect("positive tolerance");
    g.bench_function("Dormand-Prince (one accepted step)", |b| {
        b.iter(|| dp.advance(black_box(sys), black_box(&s), h))
    });
    g.finish();
}

fn steps(c: &mut Criterion) {
    let mut rng = Rng(5);
    let jitter = |rng: &mut Rng| 0.1 * (rng.next() - 0.5);
    let fb = FiveBar::default();
    let s = State::new(
        0.0,
        Vector2::new(
            120f64.to_radians() + jitter(&mut rng),
            60f64.to_radians() + jitter(&mut rng),
        ),
        Vector2::new(jitter(&mut rng), jitter(&mut rng)),
    );
    one_step(c, "five-bar", &fb, s, 1e-3);
    let s = State::new(
        0.0,
        Vector2::new(rng.next(), 0.3 + jitter(&mut rng)),
        Vector2::new(rng.next(), rng.next()),
    );
    one_step(c, "R-P arm", &RpArm::default(), s, 1e-3);
    let s = State::new(
        0.0,
        Vector2::new(100.0 * rng.next(), 100.0 * rng.next()),
        Vector2::new(1000.0, 1000.0),
    );
    one_step(c, "landing gear", &LandingGear::default(), s, 1e-3);
    let s = State::new(
        0.0,
        Vector2::zeros(),
        Vector2::new(-60.0 * rng.next(), 70.0 * rng.next()),
    );
    one_step(
        c,
        "coaxial propellers",
        &CoaxialPropellers::default(),
        s,
        1e-3,
    );
}

/// The cost of a run grows linearly with the number of steps: RK4 over 0.1 s of the
/// five-bar with 10…1000 steps.
fn run_length(c: &mut Criterion) {
    let fb = FiveBar::default();
    let s0 = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    let mut g = c.benchmark_group("RK4 five-bar 0.1 s");
    g.measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300))
        .sample_size(10);
    for n in [10usize, 100, 1000] {
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| {
                let mut s = s0;
                for _ in 0..n {
                    s = Rk4
                        .step(&fb, &s, 0.1 / n as f64)
                        .expect("inside the workspace");
                }
                black_box(s)
            });
        });
    }
    g.finish();
}

/// A run recording every step against bare steps pushed onto a trajectory by hand (checked
/// equal, row by row, before timing): RK4 and finite increments on the five-bar, 0.1 s.
fn recorded_run(c: &mut Criterion) {
    let fb = FiveBar::default();
    let s0 = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    let (h, n) = (1e-3, 100usize);
    fn by_hand<M: Stepper>(m: &M, sys: &FiveBar, s0: State, h: f64, n: usize) -> Trajectory {
        let mut tr = Trajectory::for_system(sys);
        let mut s = s0;
        tr.push(sys, &s).expect("inside the workspace");
        for k in 1..=n {
            s = m.step(sys, &s, h).expect("inside the workspace");
            if k == n {
                s.t = n as f64 * h; // the run ends exactly on t_end
            }
            tr.push(sys, &s).expect("inside the workspace");
        }
        tr
    }
    fn by_run<M: Stepper>(m: &M, sys: &FiveBar, s0: State, h: f64, n: usize) -> Trajectory {
        let opts = RunOptions {
            locate_kinks: false,
            ..RunOptions::until(n as f64 * h, h)
        };
        run(sys, m, s0, &opts).expect("runs").trajectory
    }
    fn compare<M: Stepper>(m: &M, sys: &FiveBar, s0: State, h: f64, n: usize) {
        let (a, b) = (by_run(m, sys, s0, h, n), by_hand(m, sys, s0, h, n));
        assert_eq!(a.len(), b.len());
        let worst = a
            .q()
            .iter()
            .chain(a.qd().iter())
            .chain(a.qdd().iter())
            .zip(b.q().iter().chain(b.qd().iter()).chain(b.qdd().iter()))
            .flat_map(|(x, y)| x.iter().zip(y.iter()).map(|(u, v)| (u - v).abs()))
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-12,
            "{}: the run and the loop differ by {worst}",
            m.name()
        );
        yardstick::print_ratio(
            &format!(
                "five-bar {} run recording every step (bare steps + Trajectory::push as the \
                 yardstick)",
                m.name()
            ),
            1,
            || by_run(m, black_box(sys), black_box(s0), h, n),
            || by_hand(m, black_box(sys), black_box(s0), h, n),
        );
    }
    compare(&Rk4, &fb, s0, h, n);
    compare(&FiniteIncrement, &fb, s0, h, n);
    let mut g = c.benchmark_group("five-bar run recording every step, 0.1 s");
    g.measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300))
        .sample_size(10);
    g.bench_function("RK4 run", |b| b.iter(|| by_run(&Rk4, &fb, s0, h, n)));
    g.bench_function("RK4 by hand", |b| b.iter(|| by_hand(&Rk4, &fb, s0, h, n)));
    g.finish();
}

criterion_group!(benches, lagrange_yardstick, steps, run_length, recorded_run);
criterion_main!(benches);
