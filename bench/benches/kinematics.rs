//! Benches of the kinematics: one four-bar position (positions only; positions, velocities
//! and accelerations), and a cycle of N positions for N = 10²…10⁵ (throughput per position,
//! so linear cost shows as a flat rate).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::{
    crank, cycle, rrr_dyad, solve_contour_position, Branch, LoopVector, Motion, PointMotion,
};

const L1: f64 = 0.1;
const L2: f64 = 0.35;
const L3: f64 = 0.3;
const C: Point2<f64> = Point2::new(0.4, 0.05);

/// Input angles from a fixed-seed linear congruential generator (reproducible, no deps).
fn seeded_angles(n: usize) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU
        })
        .collect()
}

fn four_bar(phi: Motion) -> tmm::Result<tmm::kinematics::RrrState> {
    let a = crank(Point2::origin(), L1, phi)?.a;
    rrr_dyad(a, PointMotion::fixed(C), L2, L3, Branch::Plus)
}

fn per_angle(c: &mut Criterion) {
    let angles = seeded_angles(1024);
    let mut g = c.benchmark_group("four_bar_per_angle");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20)
        .throughput(Throughput::Elements(angles.len() as u64));
    g.bench_function("positions", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &phi in &angles {
                let a = L1 * Vector2::new(phi.cos(), phi.sin());
                let loop_ = [
                    LoopVector::fixed(a - C.coords),
                    LoopVector::unknown_angle(L2),
                    LoopVector::unknown_angle(L3),
                ];
                acc += solve_contour_position(black_box(&loop_), Branch::Plus).unwrap()[1];
            }
            black_box(acc)
        });
    });
    g.bench_function("positions_velocities_accelerations", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &phi in &angles {
                acc += four_bar(black_box(Motion::new(phi, 10.0, 1.0)))
                    .unwrap()
                    .link3
                    .epsilon;
            }
            black_box(acc)
        });
    });
    g.finish();
}

fn cycles(c: &mut Criterion) {
    let mut g = c.benchmark_group("four_bar_cycle");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(10);
    for n in [100usize, 360, 1_000, 10_000, 100_000] {
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| {
                cycle(black_box(n), 0.0, |phi| {
                    four_bar(Motion::new(phi, 10.0, 0.0))
                })
                .unwrap()
            });
        });
    }
    g.finish();
}

criterion_group!(benches, per_angle, cycles);
criterion_main!(benches);
