//! The cost of a described linkage's equation of motion against one kinematic position of the
//! same linkage, side by side in one run (issue 16 asks for at most 2×): building A(q),
//! ∂A/∂q and Q at a state ([`LinkageSystem::terms`]) against the kinematics alone at one
//! input ([`Plan::kinematics`], which allocates its buffers as `terms` does). One input needs
//! one kinematic solve at unit input speed; two inputs need three (q̇ = e₁, e₂ and (1, 1)).
//! The states come from a seeded generator.
//!
//! Criterion reports each alone; the ratio the issue bounds is printed too, measured side by
//! side (`ratio terms / kinematic position: ...`): rounds that time a batch of each in turn,
//! the median of the rounds' ratios, so that a machine whose speed drifts (a shared core)
//! shifts both alike. Two inputs solve the positions once and only the rates at e₂ and (1, 1)
//! again ([`LinkageSystem::terms`]).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::Vector2;
use std::hint::black_box;
use std::time::{Duration, Instant};
use tmm::dynamics::machines::LinearMotor;
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, Linkage, Plan};
use tmm::mechanism::{Compressor, Mechanism};

/// A small linear congruential generator: the same states in every run.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The ratio (time of `terms`) / (time of `kin`), printed with its name: rounds that time a
/// short batch of each back to back, and for each the fastest batch of all rounds (on a
/// machine shared with other work a batch is only ever slowed down, so the fastest is the
/// cost itself), with the median of the rounds' own ratios beside it.
fn ratio(name: &str, mut kin: impl FnMut(), mut terms: impl FnMut()) -> f64 {
    const BATCH: u32 = 200;
    const ROUNDS: usize = 400;
    let time = |f: &mut dyn FnMut()| {
        let t0 = Instant::now();
        for _ in 0..BATCH {
            f();
        }
        t0.elapsed().as_secs_f64() / f64::from(BATCH)
    };
    // Warm up both.
    for _ in 0..10 {
        time(&mut kin);
        time(&mut terms);
    }
    let (mut best_k, mut best_t) = (f64::INFINITY, f64::INFINITY);
    let mut ratios: Vec<f64> = (0..ROUNDS)
        .map(|_| {
            let k = time(&mut kin);
            let t = time(&mut terms);
            best_k = best_k.min(k);
            best_t = best_t.min(t);
            t / k
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    let r = best_t / best_k;
    println!(
        "ratio terms / kinematic position: {name}: {r:.2}x ({:.0} ns / {:.0} ns fastest batches; \
         median of rounds {:.2}x)",
        best_t * 1e9,
        best_k * 1e9,
        ratios[ROUNDS / 2]
    );
    r
}

fn one_input(c: &mut Criterion) {
    let cases: [(&str, Linkage); 3] = [
        ("four-bar", bundled::four_bar()),
        ("Watt six-bar", bundled::watt_six_bar()),
        (
            "compressor",
            Compressor::course_example().linkage().unwrap(),
        ),
    ];
    let mut g = c.benchmark_group("linkage_dynamics");
    g.measurement_time(Duration::from_secs(3));
    for (name, l) in cases {
        let plan = Plan::new(&l).unwrap();
        let sys = LinkageSystem::new(plan.clone())
            .unwrap()
            .with_motor(0, Motor::Linear(LinearMotor { a: 50.0, b: 0.3 }))
            .unwrap();
        let mut rng = Lcg(16);
        let states: Vec<(f64, f64)> = (0..64)
            .map(|_| (rng.next() * std::f64::consts::TAU, 5.0 + 10.0 * rng.next()))
            .collect();
        let (mut i, mut j) = (0, 0);
        ratio(
            name,
            || {
                i = (i + 1) % states.len();
                let (phi, w) = states[i];
                black_box(
                    plan.kinematics(black_box(Motion::new(phi, w, 0.0)))
                        .unwrap(),
                );
            },
            || {
                j = (j + 1) % states.len();
                let (phi, w) = states[j];
                black_box(
                    sys.split_terms(black_box(&Vector2::new(phi, 0.0)), &Vector2::new(w, 0.0))
                        .unwrap(),
                );
            },
        );
        let mut k = 0;
        g.bench_with_input(
            BenchmarkId::new("kinematic position", name),
            &plan,
            |b, plan| {
                b.iter(|| {
                    k = (k + 1) % states.len();
                    let (phi, w) = states[k];
                    black_box(
                        plan.kinematics(black_box(Motion::new(phi, w, 0.0)))
                            .unwrap(),
                    );
                });
            },
        );
        let mut k = 0;
        g.bench_with_input(BenchmarkId::new("A, dA/dq, Q", name), &sys, |b, sys| {
            b.iter(|| {
                k = (k + 1) % states.len();
                let (phi, w) = states[k];
                black_box(
                    sys.split_terms(black_box(&Vector2::new(phi, 0.0)), &Vector2::new(w, 0.0))
                        .unwrap(),
                );
            });
        });
    }
    g.finish();
}

fn two_inputs(c: &mut Criterion) {
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let sys = LinkageSystem::new(plan.clone()).unwrap();
    let mut rng = Lcg(4);
    let states: Vec<Vector2<f64>> = (0..64)
        .map(|_| {
            Vector2::new(
                (100.0 + 40.0 * rng.next()).to_radians(),
                (40.0 + 40.0 * rng.next()).to_radians(),
            )
        })
        .collect();
    let (mut i, mut j) = (0, 0);
    ratio(
        "five-bar (2 inputs)",
        || {
            i = (i + 1) % states.len();
            let q = states[i];
            let m = [Motion::new(q[0], 1.0, 0.0), Motion::new(q[1], -1.0, 0.0)];
            black_box(plan.kinematics(black_box(m)).unwrap());
        },
        || {
            j = (j + 1) % states.len();
            black_box(
                sys.split_terms(black_box(&states[j]), &Vector2::new(1.0, -1.0))
                    .unwrap(),
            );
        },
    );
    let mut g = c.benchmark_group("linkage_dynamics");
    g.measurement_time(Duration::from_secs(3));
    let mut k = 0;
    g.bench_function(
        BenchmarkId::new("kinematic position", "five-bar (2 inputs)"),
        |b| {
            b.iter(|| {
                k = (k + 1) % states.len();
                let q = states[k];
                let m = [Motion::new(q[0], 1.0, 0.0), Motion::new(q[1], -1.0, 0.0)];
                black_box(plan.kinematics(black_box(m)).unwrap());
            });
        },
    );
    let mut k = 0;
    g.bench_function(
        BenchmarkId::new("A, dA/dq, Q", "five-bar (2 inputs)"),
        |b| {
            b.iter(|| {
                k = (k + 1) % states.len();
                black_box(
                    sys.split_terms(black_box(&states[k]), &Vector2::new(1.0, -1.0))
                        .unwrap(),
                );
            });
        },
    );
    g.finish();
}

criterion_group!(benches, one_input, two_inputs);
criterion_main!(benches);
