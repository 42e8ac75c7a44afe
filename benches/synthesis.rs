//! Benches of kinematic synthesis: the closed forms against the searches that choose a free
//! parameter for the best transmission (a crank-rocker on its locus circle, a slider-crank's
//! offset), and Freudenstein's function generation over N least-squares points (3 to 3000,
//! throughput per point, so a linear cost shows as a flat rate), each from requirement to an
//! accepted description (the engine plans every answer); and the centre-point curve of four
//! poses over N samples, and Burmester's points of five poses over N samples.
//!
//! Path synthesis (`path_search`): one whole search that recovers a closed coupler curve
//! (24 points of the bench four-bar of `common/four_bar.rs`), and the search's cost per
//! candidate evaluation against 360 single-position scalar solves of that four-bar (goal
//! ≤ 2: a candidate is a shape over a turn of 360 positions, placed on the targets), printed
//! as a `yardstick |` line measured side by side. The search there runs its whole budget
//! (tolerance 0), so the count of evaluations is the budget, polish included. And one whole
//! six-bar search (`path_search/six_bar_8_points`): eight precision points of a known
//! Stephenson III six-bar to a design that meets them.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_6};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::batch::{four_bar_positions, CrankAngles, Positions};
use tmm::synthesis::{
    burmester, burmester_points, burmester_points_by_scan, centre_point_curve, crank_rocker,
    function_generator, path_generator, shaper, six_bar_path_generator, slider_crank,
    CrankRockerRequirement, FrameChoice, FunctionRequirement, OffsetChoice, Options, PathOptions,
    PathRequirement, Pose, ShaperRequirement, SliderCrankRequirement, Spacing, Timing,
};

#[path = "common/yardstick.rs"]
mod yardstick;

#[path = "common/four_bar.rs"]
#[allow(dead_code)] // the hand kernel is not used here
mod hand_four_bar;

#[path = "common/four_bar_setup.rs"]
mod four_bar_setup;
use four_bar_setup::{bench_dims, scalar};

fn quick_return(c: &mut Criterion) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut g = c.benchmark_group("synthesis_by_k");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    let need = CrankRockerRequirement {
        rocker: 0.3,
        swing: 0.8,
        time_ratio: 1.25,
        frame: FrameChoice::BestTransmission,
    };
    g.bench_function("crank_rocker_best_frame", |b| {
        b.iter(|| black_box(crank_rocker(black_box(&need), &loose).unwrap()));
    });
    let d = crank_rocker(&need, &loose)
        .unwrap()
        .report
        .dimension("frame")
        .unwrap();
    let given = CrankRockerRequirement {
        frame: FrameChoice::Length(1.02 * d),
        ..need
    };
    g.bench_function("crank_rocker_given_frame", |b| {
        b.iter(|| black_box(crank_rocker(black_box(&given), &loose).unwrap()));
    });
    for (name, offset) in [
        ("slider_crank_best_offset", OffsetChoice::BestTransmission),
        ("slider_crank_given_offset", OffsetChoice::Given(0.05)),
    ] {
        let need = SliderCrankRequirement {
            stroke: 0.2,
            time_ratio: 1.3,
            offset,
        };
        g.bench_function(name, |b| {
            b.iter(|| black_box(slider_crank(black_box(&need), &loose).unwrap()));
        });
    }
    let need = ShaperRequirement {
        stroke: 0.3,
        time_ratio: 1.6,
        centre_distance: 0.25,
    };
    g.bench_function("shaper", |b| {
        b.iter(|| black_box(shaper(black_box(&need), &loose).unwrap()));
    });
    let poses = [
        Pose::new([0.0, 0.0], 0.0),
        Pose::new([0.1, 0.05], 0.3),
        Pose::new([0.2, 0.05], 0.7),
    ];
    g.bench_function("burmester_three_poses", |b| {
        b.iter(|| {
            black_box(burmester(black_box(&poses), [-0.05, -0.1], [0.1, -0.08], &loose).unwrap())
        });
    });
    g.finish();
}

fn function_generation(c: &mut Criterion) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut g = c.benchmark_group("function_generator_least_squares");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    for n in [3usize, 30, 300, 3000] {
        let need = FunctionRequirement {
            x_range: [1.0, 2.0],
            crank_range: [-FRAC_PI_6, FRAC_PI_6],
            rocker_range: [0.0, FRAC_PI_2],
            frame: 0.1,
            spacing: Spacing::LeastSquares(n),
        };
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &need, |b, need| {
            b.iter(|| black_box(function_generator(f64::log10, black_box(need), &loose).unwrap()));
        });
    }
    g.finish();
    let poses = [
        Pose::new([0.0, 0.0], 0.0),
        Pose::new([0.1, 0.05], 0.3),
        Pose::new([0.2, 0.05], 0.7),
        Pose::new([0.28, 0.0], 1.0),
    ];
    let mut g = c.benchmark_group("centre_point_curve");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    for n in [36usize, 360, 3600] {
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| black_box(centre_point_curve(black_box(&poses), n).unwrap()));
        });
    }
    g.finish();
    let five = [
        poses[0],
        poses[1],
        poses[2],
        poses[3],
        Pose::new([0.33, -0.05], 1.2),
    ];
    let mut g = c.benchmark_group("burmester_points");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    // The elimination (every point, no samples) beside the scan it replaced.
    g.bench_function("count", |b| {
        b.iter(|| black_box(burmester_points(black_box(&five)).unwrap()));
    });
    for n in [360usize, 3600] {
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("scan", n), &n, |b, &n| {
            b.iter(|| black_box(burmester_points_by_scan(black_box(&five), n).unwrap()));
        });
    }
    g.finish();
}

/// 24 points of the bench four-bar's coupler curve, evenly spaced in crank angle.
fn closed_curve() -> PathRequirement {
    let turn = CrankAngles::turn(24);
    let mut out = Positions::new(24);
    four_bar_positions(&bench_dims(), &turn, out.columns_mut()).unwrap();
    PathRequirement {
        points: (0..24).map(|i| [out.p_x[i], out.p_y[i]]).collect(),
        timing: Timing::ClosedCurve,
    }
}

fn path_search(c: &mut Criterion) {
    let req = closed_curve();
    let opts = PathOptions::default().with_population(40).with_designs(1);
    let size = {
        let n = req.points.len() as f64;
        let m = req
            .points
            .iter()
            .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
        req.points
            .iter()
            .map(|p| (p[0] - m[0]).hypot(p[1] - m[1]))
            .fold(0.0, f64::max)
    };
    let mut evaluations = 0;
    let best = path_generator(&req, &opts, |p| {
        evaluations = p.evaluations;
        true
    })
    .unwrap();
    println!(
        "path search | closed curve of 24 points: mean miss {:.1e} of the path's size after about {evaluations} evaluations",
        best[0].mean_error / size
    );
    let mut g = c.benchmark_group("path_search");
    g.measurement_time(Duration::from_secs(10))
        .warm_up_time(Duration::from_secs(1))
        .sample_size(10);
    g.bench_function("closed_curve_24_points", |b| {
        b.iter(|| black_box(path_generator(black_box(&req), &opts, |_| true).unwrap()));
    });
    g.finish();
    // A fixed budget spent whole: the cost per evaluation.
    let budget = 2000;
    let mut spend = PathOptions::default()
        .with_population(20)
        .with_max_evaluations(budget)
        .with_designs(1);
    spend.tolerance = 0.0;
    let d = bench_dims();
    let turn: Vec<f64> = CrankAngles::turn(360).phi().to_vec();
    yardstick::print_ratio(
        "path search per candidate evaluation / 360 scalar solves (goal <= 2)",
        budget as u32,
        || path_generator(black_box(&req), &spend, |_| true),
        || {
            (0..budget)
                .map(|_| scalar(black_box(&d), &turn))
                .sum::<f64>()
        },
    );
}

/// One whole six-bar search, from the eight points to a design that meets them.
fn six_bar_search(c: &mut Criterion) {
    let req = PathRequirement::six_bar_example().unwrap();
    let opts = PathOptions::default()
        .with_designs(1)
        .with_min_transmission_angle(0.3);
    let mut evaluations = 0;
    let best = six_bar_path_generator(&req, &opts, |p| {
        evaluations = p.evaluations;
        true
    })
    .unwrap();
    println!(
        "six-bar search | 8 points: mean miss {:.1e} m after about {evaluations} evaluations",
        best[0].mean_error
    );
    let mut g = c.benchmark_group("path_search");
    g.measurement_time(Duration::from_secs(30))
        .warm_up_time(Duration::from_secs(1))
        .sample_size(10);
    g.bench_function("six_bar_8_points", |b| {
        b.iter(|| black_box(six_bar_path_generator(black_box(&req), &opts, |_| true).unwrap()));
    });
    g.finish();
}

criterion_group!(
    benches,
    quick_return,
    function_generation,
    path_search,
    six_bar_search
);
criterion_main!(benches);
