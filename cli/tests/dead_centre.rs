//! A two-input run that reaches a dead centre (issue 27): the program prints the rows up to
//! it and the stop line naming the dyad, exit 0.

mod common;
use common::{assert_success, tmm};

/// The five-bar robot with one motor of 1 N·m runs from rest into a dead centre of its
/// coupler dyad at t ≈ 0.6498 s (the library's `Outcome::DeadCentre`, located to 10⁻¹² s;
/// RK4 at h and h/4 and Dormand–Prince agree to 10⁻⁹ s, tests/linkage/dynamics.rs): the
/// program prints the rows up to there, the last at that time, and a line naming the dyad
/// and its determinant, where it printed an error.
#[test]
fn a_two_input_run_into_a_dead_centre_prints_its_rows_and_the_stop() {
    let r = tmm(&[
        "dynamics",
        "five-bar-robot",
        "--run",
        "0.65",
        "--motor",
        "1,0",
    ]);
    assert_success(&r, "a run into a dead centre");
    let last = r
        .stdout
        .lines()
        .filter_map(|l| l.split_whitespace().next()?.parse::<f64>().ok())
        .next_back()
        .expect("rows");
    assert!((last - 0.6498).abs() < 1e-4, "{last}: {}", r.stdout);
    assert!(
        r.stdout.contains("dead centre at t = 0.649792")
            && r.stdout.contains("coupler 2, coupler 3"),
        "{}",
        r.stdout
    );
}
