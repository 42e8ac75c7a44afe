//! Benches of the kinematics: one four-bar position (positions only; positions, velocities
//! and accelerations), and a cycle of N positions for N = 10²…10⁵ (throughput per position,
//! so linear cost shows as a flat rate).
//!
//! The yardstick: the four-bar's positions, velocities and accelerations with the two link
//! angles, written by hand as a straight Cartesian closed form (no validation), checked
//! against the crate's crank + RRR dyad before timing; the bench prints the ratio
//! tmm/yardstick (a `yardstick | …` line) and criterion times both in one group.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::{
    crank, cycle, rrr_dyad, solve_contour_position, Branch, LoopVector, Motion, PointMotion,
};

#[path = "common/yardstick.rs"]
mod yardstick;

#[path = "common/four_bar.rs"]
#[allow(dead_code)] // `fold` serves batch.rs
mod hand_four_bar;
use hand_four_bar::{four_bar_by_hand, seeded_angles, C, L1, L2, L3};

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

fn four_bar_flat(phi: Motion) -> [f64; 12] {
    let s = four_bar(phi).expect("assembles");
    [
        s.b.p.x,
        s.b.p.y,
        s.b.v.x,
        s.b.v.y,
        s.b.a.x,
        s.b.a.y,
        s.link2.angle,
        s.link2.omega,
        s.link2.epsilon,
        s.link3.angle,
        s.link3.omega,
        s.link3.epsilon,
    ]
}

fn yardsticks(c: &mut Criterion) {
    let angles = seeded_angles(1024);
    for &phi in &angles {
        let a = four_bar_flat(Motion::new(phi, 10.0, 1.0));
        let b = four_bar_by_hand(phi, 10.0, 1.0);
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - y).abs() <= 1e-9 * (1.0 + y.abs()),
                "four-bar yardstick"
            );
        }
    }
    let tmm = || {
        angles
            .iter()
            .map(|&phi| {
                four_bar(black_box(Motion::new(phi, 10.0, 1.0)))
                    .map_or(0.0, |s| s.b.a.x + s.link2.angle + s.link3.epsilon)
            })
            .sum::<f64>()
    };
    let by_hand = || {
        angles
            .iter()
            .map(|&phi| {
                let r = four_bar_by_hand(black_box(phi), 10.0, 1.0);
                r[4] + r[6] + r[11]
            })
            .sum::<f64>()
    };
    yardstick::print_ratio(
        "four-bar positions, velocities, accelerations and both link angles",
        1024,
        tmm,
        by_hand,
    );
    let mut g = c.benchmark_group("four_bar_yardstick");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .throughput(Throughput::Elements(angles.len() as u64));
    g.bench_function("tmm", |b| b.iter(tmm));
    g.bench_function("yardstick", |b| b.iter(by_hand));
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

criterion_group!(benches, yardsticks, per_angle, cycles);
criterion_main!(benches);
