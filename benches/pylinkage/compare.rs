//! The Rust side of the side-by-side run against pylinkage (`benches/pylinkage/run.sh`): a
//! crank-rocker's coupler curve sampled at 24 points is the target; `tmm`'s path synthesis
//! (closed curve, nothing of the original given) finds a four-bar through them. Writes the
//! target as JSON to the file named by the first argument (for the Python side) and prints
//! one line: the wall-clock time, the mean miss (m) and the evaluations, to the tolerance
//! given as the second argument (a mean miss, m; default 1e-9 of the path's size): the
//! median and the slowest of five runs (seeds 0 to 4).
//!
//! ```sh
//! cargo run --release -p tmm-bench --example pylinkage_target -- /tmp/target.json [TOL]
//! ```

use std::time::{Duration, Instant};
use tmm::kinematics::batch::{four_bar_positions, CrankAngles, FourBarDims, Positions};
use tmm::kinematics::Branch;
use tmm::synthesis::{path_generator, PathOptions, PathRequirement, Timing};

/// The original: O1 (0, 0), O3 (0.5, 0.05), crank 0.12, coupler 0.45, rocker 0.4 m, the
/// coupler point 0.2 m along AB and 0.15 m to its left.
fn original() -> FourBarDims {
    FourBarDims {
        o: nalgebra::Point2::new(0.0, 0.0),
        c: nalgebra::Point2::new(0.5, 0.05),
        l_oa: 0.12,
        l_ab: 0.45,
        l_cb: 0.4,
        branch: Branch::Plus,
        coupler: nalgebra::Vector2::new(0.2, 0.15),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let d = original();
    let turn = CrankAngles::turn(24);
    let mut out = Positions::new(turn.len());
    four_bar_positions(&d, &turn, out.columns_mut()).expect("the target's columns");
    let points: Vec<[f64; 2]> = (0..turn.len()).map(|i| [out.p_x[i], out.p_y[i]]).collect();
    if let Some(file) = args.get(1) {
        let json = format!(
            "{{\"o1\": [0.0, 0.0], \"o3\": [0.5, 0.05], \"crank\": 0.12, \"coupler\": 0.45, \"rocker\": 0.4, \"point\": [0.2, 0.15], \"points\": {points:?}}}"
        );
        std::fs::write(file, json).expect("the target file");
    }
    let n = points.len() as f64;
    let c = points
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    let size = points
        .iter()
        .map(|p| (p[0] - c[0]).hypot(p[1] - c[1]))
        .fold(0.0, f64::max);
    let tolerance = args
        .get(2)
        .and_then(|s| s.parse::<f64>().ok())
        .map_or(1e-9, |t| t / size);
    let req = PathRequirement {
        points,
        timing: Timing::ClosedCurve,
    };
    let mut runs: Vec<(Duration, f64, usize)> = Vec::new();
    for seed in 0..5 {
        let mut opts = PathOptions::default()
            .with_seed(seed)
            .with_population(40)
            .with_designs(1);
        opts.tolerance = tolerance;
        let mut evaluations = 0;
        let start = Instant::now();
        let designs = path_generator(&req, &opts, |p| {
            evaluations = p.evaluations;
            true
        })
        .expect("a design");
        let t = start.elapsed();
        let miss = designs[0].mean_error;
        println!(
            "tmm run {seed}: {:.4} s, mean miss {miss:.3e} m, {evaluations} evaluations",
            t.as_secs_f64()
        );
        runs.push((t, miss, evaluations));
    }
    runs.sort_by_key(|r| r.0);
    let ((t, miss, evaluations), slowest) = (runs[runs.len() / 2], runs[runs.len() - 1]);
    let worst = runs.iter().map(|r| r.1).fold(0.0, f64::max);
    println!(
        "tmm: median {:.4} s (slowest {:.4} s), mean miss {miss:.3e} m ({:.1e} of the path's size; worst of 5 {worst:.1e} m), {evaluations} evaluations",
        t.as_secs_f64(),
        slowest.0.as_secs_f64(),
        miss / size
    );
}
