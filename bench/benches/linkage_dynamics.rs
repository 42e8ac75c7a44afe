//! The cost of a described linkage's equation of motion against one kinematic position of the
//! same linkage, side by side in one run (issue 16 asks for at most 2×): building A(q),
//! ∂A/∂q and Q at a state ([`LinkageSystem::terms`]) against the kinematics alone at one
//! input ([`Plan::kinematics`], which allocates its buffers as `terms` does). One input needs
//! one kinematic solve at unit input speed; two inputs need three (q̇ = e₁, e₂ and (1, 1)).
//! The states come from a seeded generator.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::Vector2;
use std::hint::black_box;
use std::time::Duration;
use tmm::dynamics::machines::LinearMotor;
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, Linkage, Plan};
use tmm::mechanism::Compressor;

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

fn one_input(c: &mut Criterion) {
    let cases: [(&str, Linkage); 3] = [
        ("four-bar", bundled::four_bar()),
        ("Watt six-bar", bundled::watt_six_bar()),
        ("compressor", Compressor::course_example().linkage()),
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
                    sys.terms(black_box(&Vector2::new(phi, 0.0)), &Vector2::new(w, 0.0))
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
                black_box(plan.kinematics_inputs(black_box(&m)).unwrap());
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
                    sys.terms(black_box(&states[k]), &Vector2::new(1.0, -1.0))
                        .unwrap(),
                );
            });
        },
    );
    g.finish();
}

criterion_group!(benches, one_input, two_inputs);
criterion_main!(benches);
