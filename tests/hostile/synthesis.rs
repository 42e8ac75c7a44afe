//! Hostile sweeps of the synthesis entry points the last sessions added or changed: path
//! generation (`path_generator`, `slider_crank_path_generator`, `six_bar_path_generator`)
//! with hostile points (NaN, ±inf, 1e308, 5e-324, duplicated, collinear), timings, budgets
//! (0, tiny, huge with a time limit of a few milliseconds), `max_size` and `max_link_ratio`
//! tiny or huge; the quick-return methods at K = 1 + 10⁻ᵏ and near their largest K; the
//! Burmester methods with poses that coincide or nearly so. Each call gives an `Error` or an
//! `Ok` whose every number is finite (a design's misses non-negative, its crank angles as
//! many as the points), never a panic, and every call ends: each search has a time budget
//! of at most 0.3 ms here (the polish and the checks of a design add theirs). `cases()` calls
//! per entry point (a quarter for the quick-return methods: see there).

use super::{check, sweep};
use crate::common::hostile_gen::{cases, Gen};
use std::f64::consts::PI;
use std::time::Duration;
use tmm::synthesis::{
    burmester, centre_point, centre_point_two, circle_point, crank_rocker, path_generator, shaper,
    six_bar_path_generator, slider_crank, slider_crank_path_generator, CrankRockerRequirement,
    FrameChoice, OffsetChoice, Options, PathDesign, PathOptions, PathRequirement, Pose,
    ShaperRequirement, SliderCrankRequirement, Timing,
};

/// A number of magnitude near 1 (or 0) most of the time; a hostile one otherwise.
fn mostly(g: &mut Gen, lo: f64, hi: f64) -> f64 {
    if g.next().is_multiple_of(6) {
        g.f()
    } else {
        lo + (hi - lo) * g.unit()
    }
}

/// Points for a path requirement: a sampled curve (an ellipse), sometimes with points
/// duplicated, collinear, all at one place, scaled by an extreme factor, or hostile.
fn points(g: &mut Gen, n: usize) -> Vec<[f64; 2]> {
    let (a, b) = (0.1 + g.unit(), 0.05 + 0.5 * g.unit());
    let mut p: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let t = 0.3 + 5.0 * i as f64 / n.max(1) as f64;
            [a * t.cos(), b * t.sin()]
        })
        .collect();
    match g.next() % 8 {
        0 => {
            // Duplicated points.
            for i in 1..p.len() {
                if g.next().is_multiple_of(2) {
                    p[i] = p[i - 1];
                }
            }
        }
        1 => {
            // Collinear.
            for (i, q) in p.iter_mut().enumerate() {
                *q = [0.1 * i as f64, 0.05 * i as f64];
            }
        }
        2 => {
            // One place, or nearly (a spread of 1e-300 to 1e-6).
            let eps = 10f64.powi(-((g.next() % 300) as i32) - 6);
            for (i, q) in p.iter_mut().enumerate() {
                *q = [0.2 + eps * i as f64, 0.3 - eps * (i % 3) as f64];
            }
        }
        3 => {
            // Scaled by an extreme factor.
            let s = [1e308, 1e154, 5e-324, 1e-154, 1e-300, -1e300, 1e200][(g.next() % 7) as usize];
            for q in &mut p {
                *q = [q[0] * s, q[1] * s];
            }
        }
        4 => {
            let i = (g.next() % n.max(1) as u64) as usize;
            if let Some(q) = p.get_mut(i) {
                q[(g.next() % 2) as usize] = g.f();
            }
        }
        _ => {}
    }
    p
}

/// A timing for `n` points: prescribed (steps of a random size, sometimes hostile, or not
/// increasing, or of the wrong count), free or a closed curve.
fn timing(g: &mut Gen, n: usize) -> Timing {
    match g.next() % 6 {
        0 => Timing::Free,
        1 => Timing::ClosedCurve,
        2 => Timing::Prescribed((0..n + (g.next() % 3) as usize).map(|_| g.f()).collect()),
        _ => {
            let step = mostly(g, 0.05, 1.2);
            let mut d: Vec<f64> = (0..n).map(|i| step * i as f64).collect();
            if g.next().is_multiple_of(5) {
                d.reverse();
            }
            Timing::Prescribed(d)
        }
    }
}

/// Options with hostile budgets (0, 1, huge), sizes, ratios, populations and designs; the
/// time budget at most 0.3 ms whatever the rest (so that the sweep ends), sometimes 0.
fn path_options(g: &mut Gen) -> PathOptions {
    let mut o = PathOptions::default()
        .with_population(4 + (g.next() % 16) as usize)
        .with_max_evaluations(match g.next() % 6 {
            0 => 0,
            1 => 1,
            2 => usize::MAX,
            3 => 1 << 40,
            _ => 50 + (g.next() % 400) as usize,
        })
        .with_max_time(Duration::from_micros(match g.next() % 8 {
            0 => 0,
            _ => 20 + g.next() % 280,
        }))
        .with_designs(match g.next() % 8 {
            0 => 0,
            1 => usize::MAX,
            _ => 1 + (g.next() % 3) as usize,
        })
        .with_seed(g.next());
    o.positions = match g.next() % 8 {
        0 => [0, 1, 2, usize::MAX][(g.next() % 4) as usize],
        _ => 12 + (g.next() % 60) as usize,
    };
    if g.next().is_multiple_of(3) {
        o.max_size = [
            1e-300,
            1e-6,
            0.01,
            1e6,
            1e300,
            f64::MAX,
            0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
        ][(g.next() % 10) as usize];
    }
    if g.next().is_multiple_of(3) {
        o.max_link_ratio =
            [1.0, 1.0 + 1e-15, 1.5, 999.0, 1e3, 1e3 + 1.0, f64::NAN, 0.5][(g.next() % 8) as usize];
    }
    if g.next().is_multiple_of(4) {
        o.tolerance = g.f();
    }
    if g.next().is_multiple_of(4) {
        o = o.with_min_transmission_angle(g.f());
    }
    o
}

/// A path search's designs are consistent: as many crank angles and points reached as
/// targets, misses non-negative (the mean at most the largest).
fn designs_consistent(n: usize, r: &tmm::Result<Vec<PathDesign>>, what: &str) {
    if let Ok(ds) = r {
        for d in ds {
            assert_eq!(d.crank_angles.len(), n, "{what}");
            assert_eq!(d.coupler_points.len(), n, "{what}");
            assert!(
                0.0 <= d.mean_error && d.mean_error <= d.max_error * (1.0 + 1e-12),
                "{what}: {} {}",
                d.mean_error,
                d.max_error
            );
        }
    }
}

/// Which path generator a sweep calls.
#[derive(Clone, Copy, Debug)]
enum Which {
    FourBar,
    SliderCrank,
    SixBar,
}

fn sweep_path(seed: u64, which: Which) {
    sweep(seed, |g| {
        let n = match g.next() % 10 {
            0 => (g.next() % 5) as usize,
            1 => 501,
            _ => 5 + (g.next() % 10) as usize,
        };
        let req = PathRequirement {
            points: points(g, n),
            timing: timing(g, n),
        };
        let opts = path_options(g);
        let what = format!("{which:?}: {req:?}, {opts:?}");
        let f = || match which {
            Which::FourBar => path_generator(&req, &opts, |_| true),
            Which::SliderCrank => slider_crank_path_generator(&req, &opts, |_| true),
            Which::SixBar => six_bar_path_generator(&req, &opts, |_| true),
        };
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f))
            .unwrap_or_else(|_| panic!("panicked: {what}"));
        designs_consistent(req.points.len(), &r, &what);
        check("path generator", &what, || r);
    });
}

#[test]
fn sweep_path_generator() {
    sweep_path(0x8a_0001, Which::FourBar);
}

#[test]
fn sweep_slider_crank_path_generator() {
    sweep_path(0x8a_0002, Which::SliderCrank);
}

#[test]
fn sweep_six_bar_path_generator() {
    sweep_path(0x8a_0003, Which::SixBar);
}

/// K = 1 + 10⁻ᵏ (k up to 17: at and below the rounding of 1), K just below its largest
/// feasible value (π(K−1)/(K+1) → π), and hostile: `crank_rocker`, `slider_crank`, `shaper`.
///
/// A quarter of `cases()` (each case is three designs, some 0.7 ms in all under load; at
/// CI's 10⁵ this is 2.5·10⁴ calls of each; `synthesis::hostile_requirements` sweeps the
/// three at `cases()` with ordinary K).
#[test]
fn sweep_quick_return_near_its_bounds() {
    let mut g = Gen::new(0x8a_0004);
    for _ in 0..cases().div_ceil(4) {
        let g = &mut g;
        let k = match g.next() % 4 {
            0 => 1.0 + 10f64.powi(-((g.next() % 18) as i32)),
            1 => 1.0 - 10f64.powi(-((g.next() % 18) as i32)),
            // θ = π − ε: K = (2π − ε)/ε.
            2 => {
                let eps = 10f64.powi(-((g.next() % 16) as i32));
                (2.0 * PI - eps) / eps
            }
            _ => g.f(),
        };
        let o = if g.next().is_multiple_of(4) {
            Options::default().with_min_transmission_angle(g.f())
        } else {
            Options::default()
        };
        let need = CrankRockerRequirement {
            rocker: mostly(g, 0.1, 1.0),
            swing: match g.next() % 4 {
                0 => PI - 10f64.powi(-((g.next() % 16) as i32)),
                1 => 10f64.powi(-((g.next() % 300) as i32)),
                _ => mostly(g, 0.1, 3.0),
            },
            time_ratio: k,
            frame: if g.next().is_multiple_of(2) {
                FrameChoice::Length(mostly(g, 0.2, 1.5))
            } else {
                FrameChoice::BestTransmission
            },
        };
        check("crank_rocker", &need, || crank_rocker(&need, &o));
        // The best-transmission offset as often as a given one, at every K drawn: below its
        // least K (about 1 + 1.3e-6, set by the link ratio) its refusal is one bisection of
        // θ (it was a scan of the feasible K, some 250 ms a call, and drawn rarely).
        let need = SliderCrankRequirement {
            stroke: mostly(g, 0.05, 1.0),
            time_ratio: k,
            offset: if g.next().is_multiple_of(2) {
                OffsetChoice::Given(mostly(g, 0.0, 0.5))
            } else {
                OffsetChoice::BestTransmission
            },
        };
        check("slider_crank", &need, || slider_crank(&need, &o));
        let need = ShaperRequirement {
            stroke: mostly(g, 0.05, 1.0),
            time_ratio: k,
            centre_distance: mostly(g, 0.01, 0.5),
        };
        check("shaper", &need, || shaper(&need, &o));
    }
}

/// Three poses of a coupler, some coinciding or nearly so (apart by 10⁻³⁰⁰ to 10⁻⁶ in place
/// and angle), some hostile: `centre_point`, `circle_point`, `centre_point_two`, `burmester`.
#[test]
fn sweep_burmester_with_near_coincident_poses() {
    sweep(0x8a_0005, |g| {
        let mut poses = [
            Pose::new([0.0, 0.0], 0.0),
            Pose::new([0.1, 0.05], 0.3),
            Pose::new([0.2, 0.05], 0.7),
        ];
        let eps = 10f64.powi(-((g.next() % 300) as i32) - 6);
        match g.next() % 5 {
            0 => poses[1] = poses[0],
            1 => {
                poses[1] = Pose::new([poses[0].at[0] + eps, poses[0].at[1]], poses[0].angle);
            }
            2 => poses[2] = Pose::new(poses[1].at, poses[1].angle + eps),
            3 => {
                let i = (g.next() % 3) as usize;
                poses[i] = Pose::new([g.f(), g.f()], g.f());
            }
            _ => {}
        }
        let c = [mostly(g, -0.5, 0.5), mostly(g, -0.5, 0.5)];
        let c2 = [mostly(g, -0.5, 0.5), mostly(g, -0.5, 0.5)];
        check("centre_point", &(poses, c), || centre_point(&poses, c));
        check("circle_point", &(poses, c), || circle_point(&poses, c));
        let two = [poses[0], poses[1]];
        let along = mostly(g, -1.0, 1.0);
        check("centre_point_two", &(two, c, along), || {
            centre_point_two(&two, c, along)
        });
        check("burmester", &(poses, c, c2), || {
            burmester(&poses, c, c2, &Options::default())
        });
    });
}
