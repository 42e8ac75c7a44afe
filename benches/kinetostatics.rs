//! Kinetostatics: each closed-form solver per call beside the general LU solve of the same
//! group (the ratio is measured side by side), and an RRR sweep over 10³..10⁶ positions to
//! show that the cost grows linearly with the number of positions.
//!
//! The yardsticks: the RRR, RRP and RPR reactions written by hand as straight Cartesian
//! closed forms (no validation, no unit vectors, no conditioning), checked against the
//! crate before timing, over the same batch of seeded dyads; the bench prints each ratio
//! tmm/yardstick (`yardstick | …` lines) and criterion times both in one group.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinetostatics::{CouplingDrive, GearDrive, PrpDyad, RppDyad, RprDyad, RrpDyad, RrrDyad};

#[path = "common/yardstick.rs"]
mod yardstick;

#[path = "common/dyads.rs"]
mod dyads;
use dyads::Rng;

#[path = "../tests/kinetostatics/general_solve.rs"]
#[allow(dead_code)]
mod general_solve;

fn per_call(c: &mut Criterion) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let rrr = rng.rrr_dyad();
    let rrp = RrpDyad {
        a: rrr.a,
        b: rrr.b,
        guide: Vector2::new(1.0, 0.2),
        load2: rng.load(),
        load3: rng.load(),
    };
    let rpr = RprDyad {
        a: rrr.a,
        e: rrr.c,
        axis: rrr.c - rrr.a,
        load2: rng.load(),
        load3: rng.load(),
    };
    // The two dyads with two sliding pairs, of the same size and loads as the RRP beside them.
    let prp = PrpDyad {
        b: rrr.b,
        guide2: Vector2::new(1.0, 0.2),
        guide3: Vector2::new(-0.3, 1.0),
        load2: rng.load(),
        load3: rng.load(),
    };
    let rpp = RppDyad {
        a: rrr.a,
        b: rrr.b,
        guide: Vector2::new(1.0, 0.2),
        slot: rrr.a - rrr.b,
        load2: rng.load(),
        load3: rng.load(),
    };
    let loads = [rng.load(), rng.load()];
    let o1 = Point2::origin();
    let gear = GearDrive::at_angle(o1, 0.2, 3.0, 0.35);

    let mut g = c.benchmark_group("kinetostatics_per_call");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    g.bench_function("rrr/closed_form", |b| b.iter(|| black_box(&rrr).solve()));
    g.bench_function("rrr/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rrr);
            general_solve::rrr(d.a, d.b, d.c, &d.load2, &d.load3)
        })
    });
    g.bench_function("rrp/closed_form", |b| b.iter(|| black_box(&rrp).solve()));
    g.bench_function("rrp/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rrp);
            general_solve::rrp(d.a, d.b, d.guide, &d.load2, &d.load3)
        })
    });
    g.bench_function("prp/closed_form", |b| b.iter(|| black_box(&prp).solve()));
    g.bench_function("prp/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&prp);
            general_solve::prp(d.b, d.guide2, d.guide3, &d.load2, &d.load3)
        })
    });
    g.bench_function("rpp/closed_form", |b| b.iter(|| black_box(&rpp).solve()));
    g.bench_function("rpp/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rpp);
            general_solve::rpp(d.a, d.b, d.guide, d.slot, &d.load2, &d.load3)
        })
    });
    g.bench_function("rpr/closed_form", |b| b.iter(|| black_box(&rpr).solve()));
    g.bench_function("rpr/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rpr);
            general_solve::rpr(d.a, d.e, d.axis, &d.load2, &d.load3)
        })
    });
    g.bench_function("coupling/closed_form", |b| {
        b.iter(|| CouplingDrive { o1 }.solve(black_box(&loads)))
    });
    g.bench_function("coupling/general_lu", |b| {
        b.iter(|| general_solve::coupling(o1, black_box(&loads)))
    });
    g.bench_function("gear/closed_form", |b| {
        b.iter(|| black_box(&gear).solve(black_box(&loads)))
    });
    g.finish();
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

fn perp(a: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-a.y, a.x)
}

/// The RRR reactions by hand: R12 = n2·AB + t2·AB⊥ and R43 = n3·CB + t3·CB⊥ along the
/// unnormalised link vectors (no square root), the moments about B give t2 and t3, the
/// group's force balance n2 and n3 by Cramer's rule. Returns (R12, R43, R23).
#[inline]
fn rrr_by_hand(d: &RrrDyad) -> [Vector2<f64>; 3] {
    let (ab, cb) = (d.b - d.a, d.b - d.c);
    let m2 = d.load2.moment + cross(d.load2.point - d.b, d.load2.force);
    let m3 = d.load3.moment + cross(d.load3.point - d.b, d.load3.force);
    let t2 = m2 / ab.norm_squared();
    let t3 = m3 / cb.norm_squared();
    let w = perp(ab) * t2 + perp(cb) * t3 + d.load2.force + d.load3.force;
    let det = cross(ab, cb);
    let n2 = -cross(w, cb) / det;
    let n3 = -cross(ab, w) / det;
    let r12 = ab * n2 + perp(ab) * t2;
    let r43 = cb * n3 + perp(cb) * t3;
    [r12, r43, -(r43 + d.load3.force)]
}

/// The RRP reactions by hand (the guide's normal unnormalised). Returns (R12, R43, R23) and
/// the couple that places R43 on the guide (the moment of R43 about B, −M3(B)): a sliding
/// pair's reaction is a force and where it acts.
#[inline]
fn rrp_by_hand(d: &RrpDyad) -> ([Vector2<f64>; 3], f64) {
    let ab = d.b - d.a;
    let nu = perp(d.guide);
    let m2 = d.load2.moment + cross(d.load2.point - d.b, d.load2.force);
    let t2 = m2 / ab.norm_squared();
    let w = perp(ab) * t2 + d.load2.force + d.load3.force;
    let det = cross(ab, nu);
    let n2 = -cross(w, nu) / det;
    let k = -cross(ab, w) / det;
    let r12 = ab * n2 + perp(ab) * t2;
    let r43 = nu * k;
    let m3 = d.load3.moment + cross(d.load3.point - d.b, d.load3.force);
    ([r12, r43, -(r43 + d.load3.force)], -m3)
}

/// The RPR reactions by hand (the axis unnormalised). Returns (R12, R32, R43) and the couple
/// of R32 about A that places it on the axis (−M2(A)).
#[inline]
fn rpr_by_hand(d: &RprDyad) -> ([Vector2<f64>; 3], f64) {
    let (u, n) = (d.axis, perp(d.axis));
    let s = u.norm_squared();
    let ea = d.a - d.e;
    let (along, across) = (ea.dot(&u), ea.dot(&n));
    let f2 = d.load2.force;
    let m_e = d.load2.moment
        + cross(d.load2.point - d.e, f2)
        + d.load3.moment
        + cross(d.load3.point - d.e, d.load3.force);
    let p = -f2.dot(&u) / s;
    let q = (across * p - m_e) / along;
    let k = -f2.dot(&n) / s - q;
    let r32 = n * k;
    let m2a = d.load2.moment + cross(d.load2.point - d.a, f2);
    ([u * p + n * q, r32, r32 - d.load3.force], -m2a)
}

/// Every component of the three reactions, folded into one number. Both sides consume all
/// six (and a sliding pair's couple), so that neither the crate nor its yardstick is timed
/// with part of its job optimised away (a sum of three components let the compiler drop half
/// of the hand-written closed form, whereas the crate's folded finiteness test keeps all of
/// its own).
#[inline]
fn every(r: [Vector2<f64>; 3]) -> f64 {
    let s = r[0] + r[1] + r[2];
    s.x + s.y
}

fn close(a: [Vector2<f64>; 3], b: [Vector2<f64>; 3]) -> bool {
    let scale = a.iter().chain(&b).fold(1.0, |m: f64, v| m.max(v.norm()));
    a.iter()
        .zip(&b)
        .all(|(x, y)| (x - y).norm() <= 1e-9 * scale)
}

/// The three dyads' reactions over one batch of seeded, well-shaped dyads, tmm beside its
/// yardstick. The batch (1024 dyads) stays in cache, so this times the arithmetic.
fn yardsticks(c: &mut Criterion) {
    const N: usize = 1024;
    let mut rng = Rng(0x5EED);
    let rrr: Vec<RrrDyad> = (0..N).map(|_| rng.rrr_dyad()).collect();
    let rrp: Vec<RrpDyad> = rrr
        .iter()
        .map(|d| RrpDyad {
            a: d.a,
            b: d.b,
            guide: Vector2::new(1.0, rng.range(-0.3, 0.3)),
            load2: d.load2,
            load3: d.load3,
        })
        .collect();
    let rpr: Vec<RprDyad> = rrr
        .iter()
        .map(|d| RprDyad {
            a: d.a,
            e: d.c,
            axis: d.c - d.a + Vector2::new(0.0, rng.range(-0.2, 0.2)),
            load2: d.load2,
            load3: d.load3,
        })
        .collect();
    // Each yardstick agrees with the crate before it is timed.
    for d in &rrr {
        let r = d.solve().expect("well-shaped");
        assert!(
            close([r.r12, r.r43, r.r23], rrr_by_hand(d)),
            "RRR yardstick"
        );
    }
    for d in &rrp {
        let r = d.solve().expect("well-shaped");
        assert!(
            close([r.r12, r.r43, r.r23], rrp_by_hand(d).0)
                && (r.guide_moment - rrp_by_hand(d).1).abs()
                    <= 1e-9 * r.guide_moment.abs().max(1.0),
            "RRP yardstick"
        );
    }
    for d in &rpr {
        let r = d.solve().expect("well-shaped");
        assert!(
            close([r.r12, r.r32, r.r43], rpr_by_hand(d).0)
                && (r.couple - rpr_by_hand(d).1).abs() <= 1e-9 * r.couple.abs().max(1.0),
            "RPR yardstick"
        );
    }
    let n = N as u32;
    let tmm_rrr = || {
        rrr.iter()
            .map(|d| {
                black_box(d)
                    .solve()
                    .map_or(0.0, |r| every([r.r12, r.r43, r.r23]))
            })
            .sum::<f64>()
    };
    let by_hand_rrr = || {
        rrr.iter()
            .map(|d| every(rrr_by_hand(black_box(d))))
            .sum::<f64>()
    };
    let tmm_rrp = || {
        rrp.iter()
            .map(|d| {
                black_box(d)
                    .solve()
                    .map_or(0.0, |r| every([r.r12, r.r43, r.r23]) + r.guide_moment)
            })
            .sum::<f64>()
    };
    let by_hand_rrp = || {
        rrp.iter()
            .map(|d| {
                let (r, m) = rrp_by_hand(black_box(d));
                every(r) + m
            })
            .sum::<f64>()
    };
    let tmm_rpr = || {
        rpr.iter()
            .map(|d| {
                black_box(d)
                    .solve()
                    .map_or(0.0, |r| every([r.r12, r.r32, r.r43]) + r.couple)
            })
            .sum::<f64>()
    };
    let by_hand_rpr = || {
        rpr.iter()
            .map(|d| {
                let (r, m) = rpr_by_hand(black_box(d));
                every(r) + m
            })
            .sum::<f64>()
    };
    yardstick::print_ratio("RRR reactions", n, tmm_rrr, by_hand_rrr);
    yardstick::print_ratio("RRP reactions", n, tmm_rrp, by_hand_rrp);
    yardstick::print_ratio("RPR reactions", n, tmm_rpr, by_hand_rpr);

    let mut g = c.benchmark_group("kinetostatics_yardsticks");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .throughput(Throughput::Elements(N as u64));
    g.bench_function("rrr/tmm", |b| b.iter(tmm_rrr));
    g.bench_function("rrr/yardstick", |b| b.iter(by_hand_rrr));
    g.bench_function("rrp/tmm", |b| b.iter(tmm_rrp));
    g.bench_function("rrp/yardstick", |b| b.iter(by_hand_rrp));
    g.bench_function("rpr/tmm", |b| b.iter(tmm_rpr));
    g.bench_function("rpr/yardstick", |b| b.iter(by_hand_rpr));
    g.finish();
}

fn sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("kinetostatics_rrr_positions");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500));
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let mut rng = Rng(42);
        let dyads: Vec<RrrDyad> = (0..n).map(|_| rng.rrr_dyad()).collect();
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &dyads, |b, dyads| {
            b.iter(|| {
                dyads
                    .iter()
                    .map(|d| d.solve().map_or(0.0, |r| r.r12.x))
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, yardsticks, per_call, sweep);
criterion_main!(benches);
