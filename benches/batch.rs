//! Benches of batch evaluation (`tmm::kinematics::batch`): one four-bar over N crank
//! positions, and many candidate four-bars at one position, against the scalar blocks and the
//! hand yardstick of `kinematics.rs` (the four-bar's positions, velocities and accelerations
//! written by hand, with its `sin_cos` and two `atan2`).
//!
//! Printed ratios (`yardstick | …` lines), each measured side by side in alternating rounds:
//! - batch positions per position / hand kernel per position (goal ≤ 0.5);
//! - batch positions, velocities and accelerations per position / hand kernel;
//! - one candidate over 360 positions / 360 single-position scalar solves (goal ≤ 2; the
//!   synthesis case, with the angles' sines and cosines made once per search);
//! - with `--features rayon`: the parallel batch / the serial one.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::batch::{
    coupler_point, four_bar_motions, four_bar_positions, four_bars_at, CrankAngles, FourBarColumns,
    FourBarDims, Positions, Rates,
};
use tmm::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};

#[path = "common/yardstick.rs"]
mod yardstick;

const L1: f64 = 0.1;
const L2: f64 = 0.35;
const L3: f64 = 0.3;
const C: Point2<f64> = Point2::new(0.4, 0.05);

fn dims() -> FourBarDims {
    FourBarDims {
        o: Point2::origin(),
        c: C,
        l_oa: L1,
        l_ab: L2,
        l_cb: L3,
        branch: Branch::Plus,
        coupler: Vector2::new(0.2, 0.1),
    }
}

/// Input angles from a fixed-seed linear congruential generator (as in `kinematics.rs`).
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

/// The hand yardstick of `kinematics.rs`: B, v_B, a_B and (φ2, ω2, ε2), (φ3, ω3, ε3).
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

/// The hand kernel over `angles`, summed.
fn hand(angles: &[f64]) -> f64 {
    let mut acc = 0.0;
    for &phi in angles {
        acc += four_bar_by_hand(black_box(phi), 10.0, 1.0)[11];
    }
    acc
}

/// The scalar blocks, one position at a time: B and the coupler point.
fn scalar(d: &FourBarDims, angles: &[f64]) -> f64 {
    let uv = d.coupler_uv();
    let mut acc = 0.0;
    for &phi in angles {
        let a = crank(d.o, d.l_oa, Motion::fixed(black_box(phi))).unwrap().a;
        let r = rrr_dyad(a, PointMotion::fixed(d.c), d.l_ab, d.l_cb, d.branch).unwrap();
        acc += coupler_point(a.p, r.b.p, uv).y;
    }
    acc
}

fn per_position(c: &mut Criterion) {
    let d = dims();
    let mut g = c.benchmark_group("batch_four_bar");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    for n in [360usize, 4096] {
        let phi = seeded_angles(n);
        let angles = CrankAngles::new(&phi);
        let mut out = Positions::new(n);
        let mut rates = Rates::new(n);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("hand_kernel", n), &phi, |b, phi| {
            b.iter(|| black_box(hand(phi)));
        });
        g.bench_with_input(BenchmarkId::new("scalar_blocks", n), &phi, |b, phi| {
            b.iter(|| black_box(scalar(&d, phi)));
        });
        g.bench_function(BenchmarkId::new("batch_positions", n), |b| {
            b.iter(|| four_bar_positions(black_box(&d), &angles, out.columns_mut()).unwrap());
        });
        g.bench_function(BenchmarkId::new("batch_motions", n), |b| {
            b.iter(|| {
                four_bar_motions(
                    black_box(&d),
                    &angles,
                    10.0,
                    1.0,
                    out.columns_mut(),
                    rates.columns_mut(),
                )
                .unwrap()
            });
        });
    }
    g.finish();

    let n = 360;
    let phi = seeded_angles(n);
    let angles = CrankAngles::new(&phi);
    let mut out = Positions::new(n);
    let mut rates = Rates::new(n);
    let positions = yardstick::print_ratio(
        "batch positions per position / hand kernel",
        n as u32,
        || four_bar_positions(black_box(&d), &angles, out.columns_mut()).unwrap(),
        || hand(&phi),
    );
    let mut out2 = Positions::new(n);
    yardstick::print_ratio(
        "batch positions+velocities+accelerations / hand kernel",
        n as u32,
        || {
            four_bar_motions(
                black_box(&d),
                &angles,
                10.0,
                1.0,
                out2.columns_mut(),
                rates.columns_mut(),
            )
            .unwrap()
        },
        || hand(&phi),
    );
    let mut out3 = Positions::new(n);
    let turn = CrankAngles::turn(n);
    let candidate = yardstick::print_ratio(
        "one candidate over 360 positions / 360 scalar solves",
        n as u32,
        || four_bar_positions(black_box(&d), &turn, out3.columns_mut()).unwrap(),
        || scalar(&d, turn.phi()),
    );
    println!("batch | positions/hand {positions:.3} (goal <= 0.5), candidate/scalar {candidate:.3} (goal <= 2)");
}

fn candidates(c: &mut Criterion) {
    let n = 1024;
    let mut bars = FourBarColumns::default();
    for (k, phi) in seeded_angles(n).iter().enumerate() {
        let mut d = dims();
        d.l_oa = 0.05 + 0.05 * phi / std::f64::consts::TAU;
        d.l_ab += 0.01 * (k % 7) as f64;
        bars.push(&d);
    }
    let mut out = Positions::new(n);
    let mut g = c.benchmark_group("batch_candidates");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20)
        .throughput(Throughput::Elements(n as u64));
    g.bench_function(BenchmarkId::from_parameter(n), |b| {
        b.iter(|| four_bars_at(black_box(&bars), 0.7, out.columns_mut()).unwrap());
    });
    g.finish();
}

#[cfg(feature = "rayon")]
fn parallel(_c: &mut Criterion) {
    use tmm::kinematics::batch::par_four_bar_positions;
    let n = 1 << 18;
    let d = dims();
    let angles = CrankAngles::new(&seeded_angles(n));
    let (mut a, mut b) = (Positions::new(n), Positions::new(n));
    yardstick::print_ratio(
        "rayon batch / serial batch (2^18 positions)",
        n as u32,
        || par_four_bar_positions(black_box(&d), &angles, a.columns_mut()).unwrap(),
        || four_bar_positions(black_box(&d), &angles, b.columns_mut()).unwrap(),
    );
}

#[cfg(not(feature = "rayon"))]
fn parallel(_c: &mut Criterion) {}

criterion_group!(benches, per_position, candidates, parallel);
criterion_main!(benches);
