//! Benches of the triad (the Assur group of the 3rd class) beside the RRR dyad: one position
//! of each along a cycle of 1024 positions (throughput per position).
//!
//! - `rrr_dyad`: positions, velocities and accelerations of an RRR dyad (a four-bar's);
//! - `triad`: the same for a triad, the mode tracked from the previous position (the fast
//!   path, Newton's method on the closures with its certificate, `kinematics/triad_newton.rs`;
//!   the full bracket where the certificate fails);
//! - `triad_tracked`: the fast path's positions alone;
//! - `triad_modes`: every assembly mode by the certified scan (positions only);
//! - `triad_modes_nearest_rates`: the full path, every mode then the nearest's rates;
//! - `slider_triad`: the triad with a sliding pair (its first leg a slider on a fixed guide),
//!   positions, velocities and accelerations, the mode tracked from the previous position
//!   (its fast path as the triad's, on its own closures; every mode by the certified scan
//!   where it fails);
//! - `slider_triad_modes`: every assembly mode of the triad with a sliding pair.
//!
//! Before criterion runs, the ratio triad/RRR is measured in alternating rounds (both see the
//! same load on a shared machine; each one's fastest round kept) and printed as a
//! `triad | …` line; the goal is a ratio of at most 5.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::{Duration, Instant};
use tmm::kinematics::{
    rrr_dyad, slider_triad, slider_triad_modes, slider_triad_tracked, triad, triad_modes,
    triad_rates, triad_tracked, Branch, Guide, PointMotion, SliderTriadDims, SlidingPair,
    TriadDims, TriadPose,
};

const N: usize = 1024;

/// The four-bar's dyad inputs: the crank pin A (0.1 m crank at 10 rad/s, 1 rad/s²) and the
/// fixed joint C, links 0.35 and 0.3 m.
fn rrr_inputs() -> Vec<(PointMotion, PointMotion)> {
    let c = PointMotion::fixed(Point2::new(0.4, 0.05));
    (0..N)
        .map(|k| {
            let phi = std::f64::consts::TAU * k as f64 / N as f64;
            let (s, co) = phi.sin_cos();
            let r = 0.1 * Vector2::new(co, s);
            let perp = Vector2::new(-r.y, r.x);
            (
                PointMotion::new(Point2::from(r), 10.0 * perp, 1.0 * perp - 100.0 * r),
                c,
            )
        })
        .collect()
}

/// A triad (ternary link 0.5 m with B3 at (0.2, 0.35) m, legs 0.6, 0.55, 0.5 m) whose first
/// outer joint A1 turns on a crank at 10 rad/s (the largest crank of 0.05, 0.03, 0.02, 0.01 m
/// with which the triad assembles all round); each position with the previous position's pose.
fn triad_inputs() -> (TriadDims, Vec<([PointMotion; 3], TriadPose)>) {
    let dims = TriadDims::new([0.6, 0.55, 0.5], 0.5, 0.2, 0.35);
    let b = [
        Point2::new(0.0, 0.0),
        Point2::new(0.5, 0.0),
        Point2::new(0.2, 0.35),
    ];
    let leg = |i: usize, angle: f64| dims.l[i] * Vector2::new(angle.cos(), angle.sin());
    let a0 = [b[0] - leg(0, 1.4), b[1] - leg(1, 2.2), b[2] - leg(2, -2.0)];
    for radius in [0.05, 0.03, 0.02, 0.01] {
        let centre = a0[0] - Vector2::new(radius, 0.0);
        let at = |k: usize| -> [PointMotion; 3] {
            let phi = std::f64::consts::TAU * k as f64 / N as f64;
            let (s, co) = phi.sin_cos();
            let r = radius * Vector2::new(co, s);
            let perp = Vector2::new(-r.y, r.x);
            [
                PointMotion::new(centre + r, 10.0 * perp, -100.0 * r),
                PointMotion::fixed(a0[1]),
                PointMotion::fixed(a0[2]),
            ]
        };
        let p = |m: [PointMotion; 3]| m.map(|x| x.p);
        let first = TriadPose {
            b,
            theta: 0.0,
            phi: [0.0; 3],
            det: 0.0,
        };
        let mut prev = *triad_modes(p(at(0)), &dims)
            .expect("assembles")
            .nearest(&first);
        let mut out = Vec::with_capacity(N);
        for k in 1..=N {
            let a = at(k % N);
            out.push((a, prev));
            match triad(a, &dims, &prev) {
                Ok(s) => prev = s.pose(),
                Err(_) => break,
            }
        }
        if out.len() == N {
            println!("triad | crank radius {radius} m");
            return (dims, out);
        }
    }
    panic!("no crank radius assembles all round");
}

/// The triad of [`triad_inputs`] with its first leg a slider on a fixed horizontal guide
/// through B1, its second outer joint A2 on a crank at 10 rad/s (the largest crank of 0.05,
/// 0.03, 0.02, 0.01 m with which it assembles all round).
type SliderInput = ([PointMotion; 2], TriadPose);

fn slider_inputs() -> (SliderTriadDims, Guide, Vec<SliderInput>) {
    let dims = SliderTriadDims {
        pair: SlidingPair::Outer { offset: 0.0 },
        l: [0.55, 0.5],
        l_b1b2: 0.5,
        b3_along: 0.2,
        b3_across: 0.35,
    };
    let guide = Guide::fixed(Point2::new(-1.0, 0.0), 0.0);
    let b = [
        Point2::new(0.0, 0.0),
        Point2::new(0.5, 0.0),
        Point2::new(0.2, 0.35),
    ];
    let leg = |l: f64, angle: f64| l * Vector2::new(angle.cos(), angle.sin());
    let a0 = [b[1] - leg(0.55, 2.2), b[2] - leg(0.5, -2.0)];
    for radius in [0.05, 0.03, 0.02, 0.01] {
        let centre = a0[0] - Vector2::new(radius, 0.0);
        let at = |k: usize| -> [PointMotion; 2] {
            let phi = std::f64::consts::TAU * k as f64 / N as f64;
            let (s, co) = phi.sin_cos();
            let r = radius * Vector2::new(co, s);
            let perp = Vector2::new(-r.y, r.x);
            [
                PointMotion::new(centre + r, 10.0 * perp, -100.0 * r),
                PointMotion::fixed(a0[1]),
            ]
        };
        let first = TriadPose {
            b,
            theta: 0.0,
            phi: [0.0; 3],
            det: 0.0,
        };
        let mut prev = first;
        let mut out = Vec::with_capacity(N);
        for k in 0..=N {
            let a = at(k % N);
            if k > 0 {
                out.push((a, prev));
            }
            match slider_triad(&guide, a, &dims, &prev) {
                Ok(s) => prev = s.pose(),
                Err(_) => break,
            }
        }
        if out.len() == N {
            println!("triad | slider triad: crank radius {radius} m");
            return (dims, guide, out);
        }
    }
    panic!("no crank radius assembles the slider triad all round");
}

/// The fastest of 300 alternating rounds of each, per position, and their ratio. Each round
/// lasts about 0.3 ms for either function (calibrated), so that a round of the slower one is
/// no likelier to be interrupted on a loaded machine than a round of the faster one.
fn print_ratio(name: &str, mut triad: impl FnMut() -> f64, mut rrr: impl FnMut() -> f64) {
    let round = |f: &mut dyn FnMut() -> f64, reps: u32| {
        let start = Instant::now();
        for _ in 0..reps {
            black_box(f());
        }
        start.elapsed() / reps
    };
    let reps = |f: &mut dyn FnMut() -> f64| {
        let probe = (0..5).map(|_| round(f, 1)).min().unwrap_or(Duration::MAX);
        (3e-4 / probe.as_secs_f64().max(1e-9)).clamp(1.0, 1e6) as u32
    };
    let (rt, rr) = (reps(&mut triad), reps(&mut rrr));
    let (mut bt, mut br) = (Duration::MAX, Duration::MAX);
    for _ in 0..300 {
        bt = bt.min(round(&mut triad, rt));
        br = br.min(round(&mut rrr, rr));
    }
    let per = |d: Duration| d.as_secs_f64() * 1e9 / N as f64;
    let (t, r) = (per(bt), per(br));
    println!(
        "triad | {name}: triad {t:.1} ns, RRR dyad {r:.1} ns, ratio triad/RRR {:.2}",
        t / r
    );
}

fn positions(c: &mut Criterion) {
    let rrr = rrr_inputs();
    let (dims, tri) = triad_inputs();
    let fast = tri
        .iter()
        .filter(|(a, prev)| triad_tracked(a.map(|m| m.p), &dims, prev).is_some())
        .count();
    println!("triad | the fast path answers {fast} of {N} positions of the cycle");
    let rrr_all = || {
        rrr.iter()
            .map(|&(a, c)| {
                rrr_dyad(black_box(a), black_box(c), 0.35, 0.3, Branch::Plus)
                    .map_or(0.0, |d| d.b.a.x + d.link2.angle + d.link3.epsilon)
            })
            .sum::<f64>()
    };
    let triad_all = || {
        tri.iter()
            .map(|(a, prev)| {
                triad(black_box(*a), &dims, black_box(prev))
                    .map_or(0.0, |s| s.b[2].a.x + s.ternary.angle + s.binary[2].epsilon)
            })
            .sum::<f64>()
    };
    let modes_all = || {
        tri.iter()
            .map(|(a, _)| {
                triad_modes(black_box(a.map(|m| m.p)), &dims).map_or(0.0, |m| m.as_slice()[0].theta)
            })
            .sum::<f64>()
    };
    print_ratio(
        "positions, velocities, accelerations, mode tracked",
        triad_all,
        rrr_all,
    );
    print_ratio("every assembly mode (positions only)", modes_all, rrr_all);
    let (sdims, guide, sli) = slider_inputs();
    let slider_all = || {
        sli.iter()
            .map(|(a, prev)| {
                slider_triad(&guide, black_box(*a), &sdims, black_box(prev))
                    .map_or(0.0, |s| s.b[2].a.x + s.ternary.angle + s.binary[2].epsilon)
            })
            .sum::<f64>()
    };
    let slider_fast = sli
        .iter()
        .filter(|(a, prev)| slider_triad_tracked(&guide, [a[0].p, a[1].p], &sdims, prev).is_some())
        .count();
    println!("triad | with a sliding pair, the fast path answers {slider_fast} of {N} positions");
    print_ratio(
        "with a sliding pair: positions, velocities, accelerations, mode tracked",
        slider_all,
        rrr_all,
    );
    let mut g = c.benchmark_group("triad_vs_rrr");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20)
        .throughput(Throughput::Elements(N as u64));
    g.bench_function("rrr_dyad", |b| b.iter(rrr_all));
    g.bench_function("triad", |b| b.iter(triad_all));
    g.bench_function("triad_tracked", |b| {
        b.iter(|| {
            tri.iter()
                .map(|(a, prev)| {
                    triad_tracked(black_box(a.map(|m| m.p)), &dims, black_box(prev))
                        .map_or(0.0, |p| p.theta)
                })
                .sum::<f64>()
        })
    });
    g.bench_function("triad_modes", |b| b.iter(modes_all));
    g.bench_function("triad_modes_nearest_rates", |b| {
        b.iter(|| {
            tri.iter()
                .map(|(a, prev)| {
                    let modes = triad_modes(black_box(a.map(|m| m.p)), &dims).expect("assembles");
                    triad_rates(*a, &dims, modes.nearest(prev)).map_or(0.0, |s| s.ternary.epsilon)
                })
                .sum::<f64>()
        })
    });
    g.bench_function("slider_triad", |b| b.iter(slider_all));
    g.bench_function("slider_triad_modes", |b| {
        b.iter(|| {
            sli.iter()
                .map(|(a, _)| {
                    slider_triad_modes(&guide, black_box([a[0].p, a[1].p]), &sdims)
                        .map_or(0.0, |m| m.as_slice()[0].theta)
                })
                .sum::<f64>()
        })
    });
    g.finish();
}

criterion_group!(benches, positions);
criterion_main!(benches);
