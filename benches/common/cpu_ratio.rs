//! The ratio of two jobs in this thread's CPU time, measured side by side.
//!
//! On a shared machine the wall time of a round includes whatever ran in its place; the
//! fastest of many rounds (what `yardstick::print_ratio` keeps) filters that out only when
//! some rounds ran unpreempted, which long rounds on a busy machine never do. The CPU time the
//! thread itself spent does not count the time it waited. Linux keeps it per thread in
//! `/proc/thread-self/schedstat` (the first field, in ns), brought up to date when the thread
//! enters the scheduler: read after a `yield_now`, it is exact to the microsecond. Each job
//! runs in alternating rounds of about 10 ms of CPU, and the line gives both the fastest
//! rounds' ratio and the medians' (`cpu | …` lines).

use std::hint::black_box;
use std::time::Duration;

/// This thread's CPU time so far (user and system), or `None` where Linux's
/// `/proc/thread-self/schedstat` is not.
pub fn thread_cpu() -> Option<Duration> {
    // Entering the scheduler updates the thread's runtime; without it the figure lags by
    // up to a tick (4 ms).
    std::thread::yield_now();
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(Duration::from_nanos(
        s.split_whitespace().next()?.parse().ok()?,
    ))
}

/// The CPU time of `reps` calls of `f`, per call.
fn round<R>(f: &mut impl FnMut() -> R, reps: u32) -> Option<Duration> {
    let start = thread_cpu()?;
    for _ in 0..reps {
        black_box(f());
    }
    Some((thread_cpu()? - start) / reps)
}

/// Times `tmm` and `yardstick` (each doing `elements` jobs per call) in `rounds` alternating
/// rounds of CPU time, prints `cpu | {name}: tmm X ns, yardstick Y ns, ratio R (medians: …)`
/// per job from the fastest rounds of each, and returns that ratio (`None`, printing
/// nothing, where the thread's CPU time cannot be read).
pub fn print_cpu_ratio<A, B>(
    name: &str,
    elements: u32,
    rounds: usize,
    mut tmm: impl FnMut() -> A,
    mut yardstick: impl FnMut() -> B,
) -> Option<f64> {
    // Calibrate: about 10 ms of CPU per round of the slower of the two.
    let probe = round(&mut tmm, 3)?.max(round(&mut yardstick, 3)?);
    let reps = (1e-2 / probe.as_secs_f64().max(1e-9)).clamp(1.0, 1e7) as u32;
    let (mut t, mut y) = (Vec::new(), Vec::new());
    for _ in 0..rounds.max(1) {
        t.push(round(&mut tmm, reps)?);
        y.push(round(&mut yardstick, reps)?);
    }
    t.sort();
    y.sort();
    let per = |d: Duration| d.as_secs_f64() * 1e9 / f64::from(elements);
    let (tf, yf, tm, ym) = (
        per(t[0]),
        per(y[0]),
        per(t[t.len() / 2]),
        per(y[y.len() / 2]),
    );
    let ratio = tf / yf;
    println!(
        "cpu | {name}: tmm {tf:.1} ns, yardstick {yf:.1} ns, ratio tmm/yardstick {ratio:.3} \
         (medians {tm:.1} / {ym:.1} ns = {:.3}; {} rounds of {reps} calls each)",
        tm / ym,
        t.len()
    );
    Some(ratio)
}
