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

/// The four-bar by hand: B, v_B, a_B and (φ2, ω2, ε2), (φ3, ω3, ε3).
#[inline]
fn four_bar_by_hand(phi: f64, omega: f64, epsilon: f64) -> [f64; 12] {
    let perp = |v: Vector2<f64>| Vector2::new(-v.y, v.x);
    let (s, c) = phi.sin_cos();
    let r1 = L1 * Vector2::new(c, s);
    let (va, aa) = (omega * perp(r1), epsilon * perp(r1) - omega * omega * r1);
    let d = C.coords - r1;
    let l_sq = d.norm_squared();
    let l = l_sq.sqrt();
    let x = (l_sq + L2 * L2 - L3 * L3) / (2.0 * l);
    let h = (L2 * L2 - x * x).sqrt();
    let r2 = (x * d + h * perp(d)) / l;
    let r3 = r2 - d;
    let dd = r2.x * r3.y - r2.y * r3.x;
    let (w2, w3) = (-va.dot(&r3) / dd, -va.dot(&r2) / dd);
    let rhs = -aa + w2 * w2 * r2 - w3 * w3 * r3;
    let (e2, e3) = (rhs.dot(&r3) / dd, rhs.dot(&r2) / dd);
    let angle = |v: Vector2<f64>| {
        let t = v.y.atan2(v.x);
        if t < 0.0 {
            t + std::f64::consts::TAU
        } else {
            t
        }
    };
    let b = r1 + r2;
    let vb = va + w2 * perp(r2);
    let ab = aa + e2 * perp(r2) - w2 * w2 * r2;
    [
        b.x,
        b.y,
        vb.x,
        vb.y,
        ab.x,
        ab.y,
        angle(r2),
        w2,
        e2,
        angle(r3),
        w3,
        e3,
    ]
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
