//! One step of each stepper on each machine, and RK4 on the five-bar across step sizes.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::Vector2;
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar, LandingGear, RpArm};
use tmm::dynamics::{Dopri5, FiniteIncrement, LagrangeSystem, Rk4, State, Stepper};

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

criterion_group!(benches, steps, run_length);
criterion_main!(benches);
