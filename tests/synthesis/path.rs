//! Path generation recovers known four-bars: targets are the coupler points of a random
//! crank-rocker (seeded), with prescribed timing, without it, and as a closed curve; the best
//! design must meet them to a mean miss ≤ 1e-6 of the path's size, as the engine analyses it
//! (the original or a cognate: any four-bar through the points passes). `TMM_SYNTH_CASES`
//! sets the number of cases per kind (1 by default; CI runs more); the worst and mean misses
//! are printed.

use nalgebra::{Point2, Vector2};
use std::f64::consts::TAU;
use std::time::{Duration, Instant};
use tmm::kinematics::batch::{four_bar_positions, CrankAngles, FourBarDims, Lane, Positions};
use tmm::kinematics::{Branch, Motion};
use tmm::linkage::Plan;
use tmm::synthesis::{
    path_generator, six_bar_path_generator, slider_crank_path_generator, PathOptions,
    PathRequirement, Timing,
};

pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(super) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

fn cases() -> usize {
    env_or("TMM_SYNTH_CASES", 1)
}

fn env_or(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

pub(super) fn centroid_size(pts: &[[f64; 2]]) -> ([f64; 2], f64) {
    let n = pts.len() as f64;
    let c = pts
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    let size = pts
        .iter()
        .map(|p| (p[0] - c[0]).hypot(p[1] - c[1]))
        .fold(0.0, f64::max);
    (c, size)
}

/// The coupler points at `phis` of a random crank-rocker that keeps γ ≥ 41° over a full
/// turn, links within a ratio of 8 and pivots within 4 path sizes of the points' centroid
/// (inside the search's default bounds); drawn again until one does.
fn target(rng: &mut Rng, phis: &[f64]) -> Vec<[f64; 2]> {
    loop {
        let d = FourBarDims {
            o: Point2::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2)),
            c: Point2::new(rng.range(0.3, 0.8), rng.range(-0.2, 0.2)),
            l_oa: rng.range(0.08, 0.25),
            l_ab: rng.range(0.3, 0.9),
            l_cb: rng.range(0.3, 0.9),
            branch: if rng.unit() < 0.5 {
                Branch::Plus
            } else {
                Branch::Minus
            },
            coupler: Vector2::new(rng.range(-0.3, 0.6), rng.range(-0.4, 0.4)),
        };
        let turn = CrankAngles::turn(720);
        let mut out = Positions::new(turn.len());
        four_bar_positions(&d, &turn, out.columns_mut()).unwrap();
        let sin_g = 41f64.to_radians().sin();
        let good =
            (0..turn.len()).all(|i| out.status[i] == Lane::Ok && out.measure[i].abs() >= sin_g);
        let l = [(d.c - d.o).norm(), d.l_oa, d.l_ab, d.l_cb];
        let (mn, mx) = l
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if !good || mx / mn > 8.0 {
            continue;
        }
        let angles = CrankAngles::new(phis);
        let mut out = Positions::new(phis.len());
        four_bar_positions(&d, &angles, out.columns_mut()).unwrap();
        let pts: Vec<[f64; 2]> = (0..phis.len()).map(|i| [out.p_x[i], out.p_y[i]]).collect();
        let (c, size) = centroid_size(&pts);
        let far = [d.o, d.c]
            .iter()
            .map(|q| (q.x - c[0]).hypot(q.y - c[1]))
            .chain(l)
            .chain([d.coupler.norm()])
            .fold(0.0, f64::max);
        if far < 4.0 * size {
            return pts;
        }
    }
}

/// The coupler points at `phis` of a random offset slider-crank (seeded) whose rod keeps
/// γ ≥ 41° over a full turn (crank + |offset| ≤ rod·cos 41°), the rod within 8 cranks,
/// its pivot and dimensions within 4 path sizes of the points' centroid (inside the search's
/// default bounds). The positions by hand: the crank pin A = O1 + r(cos φ, sin φ) at the
/// distance h = r·sin(φ − α) − e from the guide, the slider's pin B = A − h·n ± √(l² − h²)·u.
fn slider_target(rng: &mut Rng, phis: &[f64]) -> Vec<[f64; 2]> {
    loop {
        let o = Vector2::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2));
        let alpha = rng.range(0.0, TAU);
        let (u, n) = (
            Vector2::new(alpha.cos(), alpha.sin()),
            Vector2::new(-alpha.sin(), alpha.cos()),
        );
        let (e, r, l) = (
            rng.range(-0.15, 0.15),
            rng.range(0.08, 0.25),
            rng.range(0.3, 0.9),
        );
        let sign = if rng.unit() < 0.5 { 1.0 } else { -1.0 };
        let (along, across) = (rng.range(-0.3, 0.6), rng.range(-0.4, 0.4));
        if r + e.abs() > l * 41f64.to_radians().cos() || l > 8.0 * r {
            continue;
        }
        let pts: Vec<[f64; 2]> = phis
            .iter()
            .map(|phi| {
                let a = o + r * Vector2::new(phi.cos(), phi.sin());
                let h = r * (phi - alpha).sin() - e;
                let b = a - h * n + sign * (l * l - h * h).sqrt() * u;
                let w = (b - a) / l;
                let p = a + along * w + across * Vector2::new(-w.y, w.x);
                [p.x, p.y]
            })
            .collect();
        let (c, size) = centroid_size(&pts);
        let far = [
            (o.x - c[0]).hypot(o.y - c[1]),
            r,
            l,
            e.abs(),
            along.abs(),
            across.abs(),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        if far < 4.0 * size {
            return pts;
        }
    }
}

/// Which synthesis a recovery runs.
#[derive(Clone, Copy, Debug)]
pub(super) enum Mechanism {
    FourBar,
    SliderCrank,
    /// The Stephenson III six-bar (prescribed timing only).
    SixBar,
}

/// Synthesises `req` and returns the best design's mean miss in path sizes, measured by the
/// engine on the design's description at its crank angles.
fn recover(req: &PathRequirement, seed: u64, mechanism: Mechanism) -> (f64, usize) {
    let opts = PathOptions::default()
        .with_seed(seed)
        .with_population(match mechanism {
            Mechanism::SixBar => 60,
            _ => 40,
        })
        // The six-bar's polish (16 unknowns, its Jacobian's 32 residuals an iteration, the
        // continuation) is most of its search, and counted in full since session 8 (a
        // residual at the 8 points counted 8/360 of an evaluation, where an evaluation
        // solves 73 positions: 8/73). With 2 million the first six seeded cases recover in
        // release (case 3 spends 1.84 million; case 5, which missed at the former 400 000,
        // 1.5 million).
        // The four-bar's and slider-crank's polish with prescribed timing is counted in full
        // since session 8 too (2.7× what it was): 1.1 million buys the work 400 000 did
        // (four-bar prescribed-timing case 97 spends its whole budget at 400 000 counted in
        // full, and recovers with 1.1 million).
        .with_max_evaluations(match mechanism {
            Mechanism::SixBar => 2_000_000,
            _ => 1_100_000,
        })
        .with_max_time(Duration::from_secs(600))
        .with_designs(1);
    let mut evaluations = 0;
    let count = |p: &tmm::synthesis::Progress| {
        evaluations = p.evaluations;
        true
    };
    let designs = match mechanism {
        Mechanism::FourBar => path_generator(req, &opts, count),
        Mechanism::SliderCrank => slider_crank_path_generator(req, &opts, count),
        Mechanism::SixBar => six_bar_path_generator(req, &opts, count),
    };
    // A search that returns no design at all is a missed case, counted with the others (it
    // used to end the sweep there, leaving the later cases unrun).
    let designs = match designs {
        Ok(d) => d,
        Err(e) => {
            println!("no design: {e}");
            return (f64::INFINITY, evaluations);
        }
    };
    let (_, size) = centroid_size(&req.points);
    let best = &designs[0];
    let plan = Plan::new(&best.synthesis.linkage).unwrap();
    let mut sum = 0.0;
    for (phi, t) in best.crank_angles.iter().zip(&req.points) {
        let q = plan
            .kinematics(Motion::fixed(*phi))
            .unwrap()
            .point("P")
            .unwrap()
            .p;
        sum += (q.x - t[0]).hypot(q.y - t[1]);
    }
    let engine = sum / req.points.len() as f64;
    assert!(
        (engine - best.mean_error).abs() <= 1e-10 * size,
        "engine {engine:e} vs reported {:e}",
        best.mean_error
    );
    if let Mechanism::SixBar = mechanism {
        // γ_min as reported keeps the default [γ] = 40°.
        let gamma = best.synthesis.report.min_transmission_angle;
        assert!(gamma >= 40f64.to_radians() - 1e-12, "γ_min {gamma}");
        // And through the engine, not the search's own pose: each RRR dyad's |sin(φ3 − φ2)|
        // (the sine of its transmission angle) over the crank angles the points span, every
        // 0.1°. The search samples every 1°, so the engine's finer minimum may lie a little
        // lower, never far.
        if let Timing::Prescribed(d) = &req.timing {
            let theta0 = best.crank_angles[0] - d[0];
            let (lo, hi) = d
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            let steps = ((hi - lo) / 0.1f64.to_radians()).ceil() as usize;
            let mut sine = f64::INFINITY;
            for k in 0..=steps {
                let phi = theta0 + lo + (hi - lo) * k as f64 / steps as f64;
                let kin = plan.kinematics(Motion::fixed(phi)).unwrap();
                for det in kin.group_determinants() {
                    sine = sine.min(det.abs());
                }
            }
            let engine = sine.min(1.0).asin();
            let slack = 0.5f64.to_radians();
            assert!(
                engine >= 40f64.to_radians() - slack && (engine - gamma).abs() <= slack,
                "γ_min by the engine {engine} against the reported {gamma}"
            );
        }
    }
    (engine / size, evaluations)
}

/// Runs `cases()` recoveries of requirements drawn by `make`; every one must succeed (the
/// failures are listed together at the end). The times are printed, never asserted.
fn recoveries(name: &str, seed: u64, make: impl Fn(&mut Rng) -> PathRequirement) {
    recoveries_of(name, seed, Mechanism::FourBar, make);
}

/// [`recoveries`] of the mechanism `mechanism`.
pub(super) fn recoveries_of(
    name: &str,
    seed: u64,
    mechanism: Mechanism,
    make: impl Fn(&mut Rng) -> PathRequirement,
) {
    let mut rng = Rng(seed);
    let n = cases();
    let (mut worst, mut sum, mut evals) = (0.0f64, 0.0, 0);
    let mut failed = Vec::new();
    let mut times = Vec::new();
    // `TMM_SYNTH_FIRST` skips the searches of the cases before it (their targets are still
    // drawn, so case k is the same case): to study one case.
    let first = env_or("TMM_SYNTH_FIRST", 0);
    // `TMM_SYNTH_JITTER` = k scales each target coordinate by (1 + k·2⁻⁵²): the same case
    // moved by a few ulps, which a search that hangs on the data's last bits would miss.
    let jitter = 1.0 + env_or("TMM_SYNTH_JITTER", 0) as f64 * f64::EPSILON;
    for case in 0..n {
        let mut req = make(&mut rng);
        req.points.iter_mut().flatten().for_each(|v| *v *= jitter);
        if case < first {
            continue;
        }
        let clock = Instant::now();
        let (e, ev) = recover(&req, case as u64, mechanism);
        let t = clock.elapsed().as_secs_f64();
        println!(
            "{name} case {case}: mean miss {e:.1e} of the path's size, {ev} evaluations, {t:.2} s"
        );
        if e.is_nan() || e > 1e-6 {
            failed.push((case, e));
        }
        worst = worst.max(e);
        sum += e;
        evals += ev;
        times.push(t);
    }
    let run = times.len().max(1);
    times.sort_by(f64::total_cmp);
    println!(
        "{name}: {} cases; worst mean miss {worst:.1e}, mean {:.1e} of the path's size; {} evaluations a case; time a case: median {:.2} s, worst {:.2} s",
        times.len(),
        sum / run as f64,
        evals / run,
        times.get(times.len() / 2).unwrap_or(&0.0),
        times.last().unwrap_or(&0.0),
    );
    assert!(
        failed.is_empty(),
        "{name}: cases missed (case, mean miss in path sizes): {failed:?}"
    );
}

/// `n` points of the mechanism `points` draws, `step` rad of the crank apart from a random
/// θ0: prescribed timing.
pub(super) fn prescribed(
    rng: &mut Rng,
    n: usize,
    step: f64,
    points: impl Fn(&mut Rng, &[f64]) -> Vec<[f64; 2]>,
) -> PathRequirement {
    let theta0 = rng.range(0.0, TAU);
    let delta: Vec<f64> = (0..n).map(|k| step * k as f64).collect();
    let phis: Vec<f64> = delta.iter().map(|d| theta0 + d).collect();
    PathRequirement {
        points: points(rng, &phis),
        timing: Timing::Prescribed(delta),
    }
}

/// Ten points of the mechanism `points` draws, about 0.55–0.75 rad of the crank apart from
/// a random θ0, without timing.
fn free(rng: &mut Rng, points: impl Fn(&mut Rng, &[f64]) -> Vec<[f64; 2]>) -> PathRequirement {
    let theta0 = rng.range(0.0, TAU);
    let phis: Vec<f64> = (0..10)
        .map(|k| theta0 + 0.55 * k as f64 + rng.range(0.0, 0.2))
        .collect();
    PathRequirement {
        points: points(rng, &phis),
        timing: Timing::Free,
    }
}

#[test]
fn recovers_prescribed_timing() {
    recoveries("prescribed timing, 6 points", 2300, |rng| {
        prescribed(rng, 6, 0.9, target)
    });
}

#[test]
fn recovers_free_timing() {
    recoveries("free timing, 10 points", 2301, |rng| free(rng, target));
}

#[test]
fn recovers_a_closed_curve() {
    recoveries("closed curve, 24 points", 2302, |rng| {
        // Uneven steps of the crank: the points are not evenly spaced in crank angle.
        let mut phis = Vec::new();
        let mut phi = rng.range(0.0, TAU);
        for _ in 0..24 {
            phis.push(phi);
            phi += TAU / 24.0 * rng.range(0.7, 1.3);
        }
        let scale = TAU / (phi - phis[0]);
        let first = phis[0];
        let phis: Vec<f64> = phis.iter().map(|p| first + (p - first) * scale).collect();
        PathRequirement {
            points: target(rng, &phis),
            timing: Timing::ClosedCurve,
        }
    });
}

#[test]
fn recovers_slider_cranks_with_prescribed_timing() {
    recoveries_of(
        "slider-crank, prescribed timing, 6 points",
        2310,
        Mechanism::SliderCrank,
        |rng| prescribed(rng, 6, 0.9, slider_target),
    );
}

#[test]
fn recovers_slider_cranks_with_free_timing() {
    recoveries_of(
        "slider-crank, free timing, 10 points",
        2311,
        Mechanism::SliderCrank,
        |rng| free(rng, slider_target),
    );
}

#[test]
fn recovers_slider_cranks_on_a_closed_curve() {
    recoveries_of(
        "slider-crank, closed curve, 24 points",
        2312,
        Mechanism::SliderCrank,
        |rng| {
            let phis: Vec<f64> = (0..24).map(|k| TAU * k as f64 / 24.0).collect();
            PathRequirement {
                points: slider_target(rng, &phis),
                timing: Timing::ClosedCurve,
            }
        },
    );
}

/// A closed-curve requirement of 24 points (a recoverable one).
fn closed_target() -> PathRequirement {
    let phis: Vec<f64> = (0..24).map(|k| TAU * k as f64 / 24.0).collect();
    PathRequirement {
        points: target(&mut Rng(7), &phis),
        timing: Timing::ClosedCurve,
    }
}

/// One requirement of each timing: the closed curve, ten points without timing, six timed.
fn every_timing() -> [PathRequirement; 3] {
    let phis: Vec<f64> = (0..10).map(|k| 0.5 * k as f64).collect();
    let free = PathRequirement {
        points: target(&mut Rng(8), &phis),
        timing: Timing::Free,
    };
    let timed = PathRequirement {
        points: target(&mut Rng(9), &[0.0, 0.8, 1.6, 2.4, 3.2, 4.0]),
        timing: Timing::Prescribed(vec![0.0, 0.8, 1.6, 2.4, 3.2, 4.0]),
    };
    [closed_target(), free, timed]
}

#[test]
fn every_search_keeps_its_evaluation_budget_and_reports_progress() {
    let kinds = [Mechanism::FourBar, Mechanism::SliderCrank];
    for (req, mechanism) in every_timing()
        .into_iter()
        .flat_map(|r| kinds.map(|m| (r.clone(), m)))
    {
        // An impossible tolerance: the search runs until its budget is spent.
        let mut opts = PathOptions::default()
            .with_population(20)
            .with_max_evaluations(3000);
        opts.tolerance = 0.0;
        let (mut calls, mut last) = (0usize, 0usize);
        let count = |p: &tmm::synthesis::Progress| {
            assert!(p.evaluations >= last && p.best.is_finite());
            calls += 1;
            last = p.evaluations;
            true
        };
        let r = match mechanism {
            Mechanism::FourBar => path_generator(&req, &opts, count),
            Mechanism::SliderCrank => slider_crank_path_generator(&req, &opts, count),
            Mechanism::SixBar => six_bar_path_generator(&req, &opts, count),
        };
        assert!(calls > 0, "no progress reported");
        assert!(last <= 3000, "{last} evaluations past a budget of 3000");
        if let Ok(designs) = r {
            assert!(!designs.is_empty() && designs.len() <= opts.designs);
        }
        // A callback that says stop is called once, and the search ends there.
        let mut calls = 0;
        let stop = |_: &tmm::synthesis::Progress| {
            calls += 1;
            false
        };
        let _ = match mechanism {
            Mechanism::FourBar => path_generator(&req, &opts, stop),
            Mechanism::SliderCrank => slider_crank_path_generator(&req, &opts, stop),
            Mechanism::SixBar => six_bar_path_generator(&req, &opts, stop),
        };
        assert_eq!(calls, 1);
        // Too little time to evaluate anything: the error says so, with the budget.
        let none = opts.clone().with_max_time(Duration::from_nanos(1));
        match synthesise(mechanism, &req, &none) {
            Err(tmm::Error::NoMechanism { problem, .. }) => {
                assert!(
                    problem.contains("in 0 evaluations") && problem.contains("the budget: 3000"),
                    "{problem}"
                );
            }
            other => panic!("expected NoMechanism, got {other:?}"),
        }
    }
}

/// The points of `req` each moved by up to `by` of the path's size (seeded): no four-bar or
/// slider-crank passes through them exactly, so a search held to a tolerance of zero runs
/// its whole budget, restarting whenever a run stagnates.
pub(super) fn jittered(req: &PathRequirement, by: f64, seed: u64) -> PathRequirement {
    let (_, size) = centroid_size(&req.points);
    let mut rng = Rng(seed);
    PathRequirement {
        points: req
            .points
            .iter()
            .map(|p| {
                [
                    p[0] + by * size * rng.range(-1.0, 1.0),
                    p[1] + by * size * rng.range(-1.0, 1.0),
                ]
            })
            .collect(),
        timing: req.timing.clone(),
    }
}

/// The best reported through the progress callback of a whole search of `mechanism` on
/// `req` (tolerance zero, `budget` evaluations, a small population so that its runs
/// stagnate and restart from fresh populations): it must never rise from one call to the
/// next, and it ends no worse than the designs' objective allows (finite).
pub(super) fn best_never_rises(mechanism: Mechanism, req: &PathRequirement, budget: usize) {
    let mut opts = PathOptions::default()
        .with_population(12)
        .with_max_evaluations(budget)
        .with_designs(1);
    opts.tolerance = 0.0;
    let mut bests: Vec<f64> = Vec::new();
    let record = |p: &tmm::synthesis::Progress| {
        bests.push(p.best);
        true
    };
    let _ = match mechanism {
        Mechanism::FourBar => path_generator(req, &opts, record),
        Mechanism::SliderCrank => slider_crank_path_generator(req, &opts, record),
        Mechanism::SixBar => six_bar_path_generator(req, &opts, record),
    };
    assert!(!bests.is_empty(), "{mechanism:?}: no progress reported");
    for (k, w) in bests.windows(2).enumerate() {
        assert!(
            w[1] <= w[0],
            "{mechanism:?} {:?}: the best rose at call {}: {:e} after {:e}",
            req.timing,
            k + 1,
            w[1],
            w[0]
        );
    }
}

#[test]
fn the_best_reported_never_rises_across_restarts() {
    for req in every_timing() {
        let req = jittered(&req, 0.05, 3);
        for mechanism in [Mechanism::FourBar, Mechanism::SliderCrank] {
            best_never_rises(mechanism, &req, 20_000);
        }
    }
}

/// Runs the synthesis of `mechanism`.
fn synthesise(
    mechanism: Mechanism,
    req: &PathRequirement,
    opts: &PathOptions,
) -> tmm::Result<Vec<tmm::synthesis::PathDesign>> {
    match mechanism {
        Mechanism::FourBar => path_generator(req, opts, |_| true),
        Mechanism::SliderCrank => slider_crank_path_generator(req, opts, |_| true),
        Mechanism::SixBar => six_bar_path_generator(req, opts, |_| true),
    }
}

#[test]
fn bad_path_requirements_name_the_parameter() {
    bad_requirements_of(Mechanism::FourBar, 9);
    bad_requirements_of(Mechanism::SliderCrank, 8);
}

/// Every bad requirement and option refused by `mechanism`'s synthesis, naming what is bad;
/// `free` is the fewest points without timing.
fn bad_requirements_of(mechanism: Mechanism, free: usize) {
    let good = closed_target();
    let opts = PathOptions::default();
    let name = |req: &PathRequirement, opts: &PathOptions| match synthesise(mechanism, req, opts) {
        Err(tmm::Error::OutOfRange { name, .. } | tmm::Error::NonFinite { name, .. }) => {
            name.to_owned()
        }
        Err(tmm::Error::NoMechanism { problem, .. }) => problem,
        Err(tmm::Error::Overflow { what }) => format!("overflow: {what}"),
        Err(e) => format!("other: {e}"),
        Ok(_) => "ok".to_owned(),
    };
    let with = |points: Vec<[f64; 2]>, timing: Timing| PathRequirement { points, timing };
    let pts = good.points.clone();
    // Fewer points than unknowns: 9 (a slider-crank: 8) without timing, 5 with it.
    assert_eq!(
        name(&with(pts[..free - 1].to_vec(), Timing::ClosedCurve), &opts),
        "points"
    );
    assert_eq!(
        name(&with(pts[..free - 1].to_vec(), Timing::Free), &opts),
        "points"
    );
    assert_eq!(
        name(
            &with(
                pts[..4].to_vec(),
                Timing::Prescribed(vec![0.0, 0.1, 0.2, 0.3])
            ),
            &opts
        ),
        "points"
    );
    // Non-finite numbers.
    for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
        let mut p = pts.clone();
        p[5][0] = bad;
        assert_eq!(name(&with(p, Timing::Free), &opts), "points");
        let t = vec![0.0, 0.1, bad, 0.3, 0.4];
        assert_eq!(
            name(&with(pts[..5].to_vec(), Timing::Prescribed(t)), &opts),
            "timing"
        );
    }
    // One angle per point, spanning less than a turn.
    assert!(name(
        &with(pts[..5].to_vec(), Timing::Prescribed(vec![0.0; 4])),
        &opts
    )
    .starts_with("timing"));
    assert!(name(
        &with(
            pts[..5].to_vec(),
            Timing::Prescribed(vec![0.0, 1.0, 2.0, 3.0, 7.0])
        ),
        &opts
    )
    .starts_with("timing"));
    // Coinciding points are named.
    let mut same = pts.clone();
    same[9] = same[3];
    assert!(name(&with(same, Timing::ClosedCurve), &opts).contains("points 4 and 10 coincide"));
    // Bad options.
    for ratio in [1.0, 1001.0, f64::INFINITY, f64::NAN] {
        let bad = PathOptions::default().with_max_link_ratio(ratio);
        assert_eq!(name(&good, &bad), "max_link_ratio", "{ratio}");
    }
    let bad = PathOptions::default().with_max_size(f64::NAN);
    assert_eq!(name(&good, &bad), "max_size");
    let bad = PathOptions::default().with_population(3);
    assert_eq!(name(&good, &bad), "population");
    let mut bad = PathOptions::default();
    bad.positions = usize::MAX;
    assert_eq!(name(&good, &bad), "positions");
    bad = PathOptions::default();
    bad.tolerance = f64::NAN;
    assert_eq!(name(&good, &bad), "tolerance");
    // A budget of nothing is refused before the search, naming the budget.
    let bad = PathOptions::default().with_max_evaluations(0);
    assert!(name(&good, &bad).starts_with("max_evaluations"));
    let bad = PathOptions::default().with_max_time(Duration::ZERO);
    assert_eq!(name(&good, &bad), "max_time");
    // More points than the polish's dense Jacobian is sized for.
    let many: Vec<[f64; 2]> = (0..501)
        .map(|k| {
            let t = TAU * k as f64 / 501.0;
            [t.cos(), (2.0 * t).sin()]
        })
        .collect();
    assert_eq!(name(&with(many, Timing::ClosedCurve), &opts), "points");
    // Points whose squares overflow are an overflow; a spread too small to square
    // underflows (said so); neither is taken for coinciding points.
    for (at, spread, said) in [
        (1e300, 1e299, "overflow: points"),
        (0.0, 1e300, "overflow: points"),
        (0.0, 1e-170, "m underflows"),
    ] {
        let p: Vec<[f64; 2]> = pts
            .iter()
            .map(|q| [at + spread * q[0], at + spread * q[1]])
            .collect();
        let got = name(&with(p, Timing::ClosedCurve), &opts);
        assert!(got.contains(said), "at {at:e}, spread {spread:e}: {got}");
    }
    let bad = PathOptions::default().with_min_transmission_angle(2.0);
    assert_eq!(name(&good, &bad), "min_transmission_angle");
}

/// Review: `max_size` below the lengths' former floor (2 % of the path) was not kept, points
/// far from the origin were matched to rounding, and `designs = 0` returned one design.
#[test]
fn a_small_max_size_is_kept_far_points_and_no_designs_are_named() {
    let phis = [0.0, 0.8, 1.6, 2.4, 3.2, 4.0];
    let timed = PathRequirement {
        points: target(&mut Rng(9), &phis),
        timing: Timing::Prescribed(phis.to_vec()),
    };
    let (centre, size) = centroid_size(&timed.points);
    let box_size = 0.01 * size;
    // Designs exist in this box: a slider-crank with the crank 0.1·s, the rod s and no
    // offset keeps |h| ≤ 0.1·s ≤ s·cos 40° (γ ≥ 40° at every crank angle), a four-bar with
    // the frame s, the crank 0.1·s and coupler and rocker 0.9·s is a crank-rocker with
    // γ_min = arccos((0.81 + 0.81 − 0.9²)/1.62) = 60°. Both searches must return a design (the nearest to the
    // points they find; the slider-crank's returned none before session 9: its polish left
    // the box, and the member it started from was dropped), and the bound is checked on it.
    let opts = PathOptions::default()
        .with_population(20)
        .with_max_evaluations(20_000)
        .with_seed(23)
        .with_designs(1)
        .with_max_size(0.01);
    for mechanism in [Mechanism::FourBar, Mechanism::SliderCrank] {
        let designs = match synthesise(mechanism, &timed, &opts) {
            Ok(designs) => designs,
            Err(e) => panic!("{mechanism:?}: no design in the box: {e}"),
        };
        assert_eq!(designs.len(), 1);
        for d in &designs {
            within_box(mechanism, d, centre, box_size);
            // The coupler point stays within √2·s (O1) + s (the crank) + √2·s (AP) of the
            // centroid: it misses each point by at least the point's distance from the
            // centroid less that.
            let reach = (1.0 + 2.0 * std::f64::consts::SQRT_2) * box_size;
            let least = timed
                .points
                .iter()
                .map(|p| ((p[0] - centre[0]).hypot(p[1] - centre[1]) - reach).max(0.0))
                .sum::<f64>()
                / timed.points.len() as f64;
            assert!(
                d.mean_error >= least * (1.0 - 1e-12) && d.mean_error.is_finite(),
                "{mechanism:?}: mean miss {:e} below {least:e}",
                d.mean_error
            );
        }
    }
    // Ten million path sizes from the origin f64 cannot resolve the tolerance of 1e-9.
    let far = PathRequirement {
        points: timed
            .points
            .iter()
            .map(|p| [p[0] + 1e7 * size, p[1]])
            .collect(),
        ..timed.clone()
    };
    match synthesise(Mechanism::FourBar, &far, &PathOptions::default()) {
        Err(tmm::Error::NoMechanism { problem, .. }) => {
            assert!(problem.contains("centroid"), "{problem}");
        }
        other => panic!("expected the centroid named, got {other:?}"),
    }
    let none = PathOptions::default().with_designs(0);
    assert!(matches!(
        synthesise(Mechanism::FourBar, &timed, &none),
        Err(tmm::Error::OutOfRange {
            name: "designs",
            ..
        })
    ));
}

/// Every dimension `max_size` bounds, of the design `d` as the engine poses it at each of
/// its crank angles, within `s` m: the distance between any two joints of a moving link (the
/// crank, the coupler or rod, the rocker, the slider block) and, for a four-bar, the frame's
/// O1O3; each coordinate of the crank's pivot O1 from the points' centroid `centre`; the
/// coupler point P from A, whose offsets along and across AB are each within `s` (so within
/// √2·s of A).
fn within_box(mechanism: Mechanism, d: &tmm::synthesis::PathDesign, centre: [f64; 2], s: f64) {
    let l = &d.synthesis.linkage;
    let plan = Plan::new(l).unwrap();
    let slack = 1.0 + 1e-9;
    for &phi in &d.crank_angles {
        let k = plan.kinematics(Motion::fixed(phi)).unwrap();
        let at = |name: &str| k.joint(name).unwrap().p;
        for link in &l.links {
            if link.name == l.frame && !matches!(mechanism, Mechanism::FourBar) {
                continue;
            }
            for (i, a) in link.joints.iter().enumerate() {
                for b in &link.joints[i + 1..] {
                    let length = (at(a) - at(b)).norm();
                    assert!(
                        length <= s * slack,
                        "{mechanism:?} at {phi}: {} {a}{b} = {length} > {s}",
                        link.name
                    );
                }
            }
        }
        let o1 = at("O1");
        assert!(
            (o1.x - centre[0]).abs() <= s * slack && (o1.y - centre[1]).abs() <= s * slack,
            "{mechanism:?}: O1 {o1} from the centroid {centre:?}"
        );
        let p = k.point("P").unwrap().p;
        let ap = (p - at("A")).norm();
        assert!(
            ap <= std::f64::consts::SQRT_2 * s * slack,
            "{mechanism:?} at {phi}: AP = {ap} > √2·{s}"
        );
    }
}

/// [γ] over the whole turn for a crank that turns fully: the engine (and the report) give
/// γ_min over the turn, so a search that checked it only over the targets' arc could return
/// a four-bar through the points that breaks [γ] elsewhere. Here the points are those of a
/// crank-rocker (frame 0.5, crank 0.15, coupler 0.5, rocker 0.4) whose γ is 44.0° at the crank
/// along the frame (|AO3| = d − a; cos μ = (b² + c² − e²)/(2bc) = 0.71875) and above 50° for
/// φ in [37.2°, 322.8°] (e² = 0.41 − 0.4·cos 50°, cos φ = (d² + a² − e²)/(2ad) = 0.7967),
/// ten points from 64° to 296°: with [γ] = 50° it meets [γ] at every point and between them,
/// not over the turn. Every design returned must meet [γ] over the turn by the engine.
#[test]
fn a_full_turn_crank_breaking_the_transmission_angle_outside_the_points_is_rejected() {
    let original = FourBarDims {
        o: Point2::new(0.0, 0.0),
        c: Point2::new(0.5, 0.0),
        l_oa: 0.15,
        l_ab: 0.5,
        l_cb: 0.4,
        branch: Branch::Plus,
        coupler: Vector2::new(0.2, 0.1),
    };
    let required = 50f64.to_radians();
    let phis: Vec<f64> = (0..10)
        .map(|k| 64f64.to_radians() + 0.45 * k as f64)
        .collect();
    let angles = CrankAngles::new(&phis);
    let mut out = Positions::new(phis.len());
    four_bar_positions(&original, &angles, out.columns_mut()).unwrap();
    // The original meets [γ] at the points and over their arc (it would pass an arc-only
    // check, with no miss at all), and breaks it over the turn.
    for k in 0..=400 {
        let phi = phis[0] + (phis[9] - phis[0]) * k as f64 / 400.0;
        let e2 = 0.25 + 0.0225 - 0.15 * phi.cos();
        let mu = ((0.41 - e2) / 0.4f64).acos();
        assert!(mu.min(std::f64::consts::PI - mu) > required, "{phi}");
    }
    let at_frame = ((0.41 - 0.35f64 * 0.35) / 0.4).acos();
    assert!((at_frame.to_degrees() - 44.05).abs() < 0.01 && at_frame < required);
    let req = PathRequirement {
        points: (0..phis.len()).map(|i| [out.p_x[i], out.p_y[i]]).collect(),
        timing: Timing::Free,
    };
    let opts = PathOptions::default()
        .with_min_transmission_angle(required)
        .with_seed(23)
        .with_max_evaluations(60_000)
        .with_designs(4);
    let designs = match path_generator(&req, &opts, |_| true) {
        Ok(d) => d,
        // No design met [γ] within the budget: rejected too.
        Err(tmm::Error::NoMechanism { .. }) => Vec::new(),
        Err(e) => panic!("{e}"),
    };
    for d in &designs {
        let report = &d.synthesis.report;
        assert!(
            report.min_transmission_angle >= required - 1e-9,
            "reported γ_min {} below [γ] {required}",
            report.min_transmission_angle
        );
        if report.grashof.is_some_and(|g| g.input_turns_fully()) {
            let plan = Plan::new(&d.synthesis.linkage).unwrap();
            let (gamma, at) = plan.min_transmission_angle(0).unwrap();
            assert!(
                gamma >= required - 1e-9,
                "the engine's γ_min over the turn {gamma} (at φ = {at}) below [γ] {required}, \
                 mean miss {:e}",
                d.mean_error
            );
        }
    }
    eprintln!(
        "[γ] over the turn: {} designs, misses {:?}",
        designs.len(),
        designs.iter().map(|d| d.mean_error).collect::<Vec<_>>()
    );
}
