//! The ratio of a hot path to its yardstick, measured side by side.
//!
//! A yardstick is the same job written by hand as a straight Cartesian closed form with no
//! validation, checked against the crate's result before it is timed. Criterion times both
//! in one group; this module also prints their ratio, measured by alternating short rounds
//! of the two (so that both see the same load on a shared machine) and keeping each one's
//! fastest round.

use std::hint::black_box;
use std::time::{Duration, Instant};

/// The fastest of `rounds` rounds of `reps` calls of `f`, per call.
fn round<R>(f: &mut impl FnMut() -> R, reps: u32) -> Duration {
    let start = Instant::now();
    for _ in 0..reps {
        black_box(f());
    }
    start.elapsed() / reps
}

/// Times `tmm` and `yardstick` (each doing `elements` jobs per call) in alternating rounds,
/// prints `name: tmm X ns, yardstick Y ns, ratio tmm/yardstick R` per job, and returns the
/// ratio.
pub fn print_ratio<A, B>(
    name: &str,
    elements: u32,
    mut tmm: impl FnMut() -> A,
    mut yardstick: impl FnMut() -> B,
) -> f64 {
    // Calibrate: about 2 ms per round of the slower of the two.
    let probe = round(&mut tmm, 10).max(round(&mut yardstick, 10));
    let reps = (2e-3 / probe.as_secs_f64().max(1e-9)).clamp(1.0, 1e7) as u32;
    let (mut best_t, mut best_y) = (Duration::MAX, Duration::MAX);
    for _ in 0..30 {
        best_t = best_t.min(round(&mut tmm, reps));
        best_y = best_y.min(round(&mut yardstick, reps));
    }
    let per = |d: Duration| d.as_secs_f64() * 1e9 / f64::from(elements);
    let (t, y) = (per(best_t), per(best_y));
    let ratio = t / y;
    println!(
        "yardstick | {name}: tmm {t:.1} ns, yardstick {y:.1} ns, ratio tmm/yardstick {ratio:.2}"
    );
    ratio
}
