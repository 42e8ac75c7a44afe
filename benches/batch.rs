//! Benches of batch evaluation (`tmm::kinematics::batch`): one four-bar over N crank
//! positions, and many candidate four-bars at one position, against the scalar blocks and the
//! hand yardstick of `common/four_bar.rs`, shared with `kinematics.rs` (the four-bar's
//! positions, velocities and accelerations written by hand, with its `sin_cos` and two
//! `atan2`, all twelve numbers consumed).
//!
//! Printed ratios (`yardstick | …` lines), each measured side by side in alternating rounds:
//! - batch positions per position / hand kernel per position (goal ≤ 0.5);
//! - batch positions, velocities and accelerations per position / hand kernel;
//! - one candidate over 360 positions / 360 single-position scalar solves (goal ≤ 2; the
//!   synthesis case, with the angles' sines and cosines made once per search);
//! - with `--features rayon`: the parallel batch / the serial one, and a population of
//!   candidates scored in parallel / serially (the synthesis case). One command, which skips
//!   the other groups and prints the `rayon |` lines:
//!   `TMM_BATCH=rayon cargo bench -p tmm-bench --bench batch --features rayon -- batch_rayon`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::batch::{
    four_bar_motions, four_bar_positions, four_bars_at, CrankAngles, FourBarColumns, Positions,
    Rates,
};

#[path = "common/yardstick.rs"]
mod yardstick;

#[path = "common/four_bar.rs"]
mod hand_four_bar;
use hand_four_bar::{four_bar_by_hand, seeded_angles};

#[path = "common/four_bar_setup.rs"]
mod four_bar_setup;
use four_bar_setup::{bench_dims as dims, scalar};

/// The hand kernel over `angles`, every one of its numbers consumed.
fn hand(angles: &[f64]) -> f64 {
    let mut acc = 0.0;
    for &phi in angles {
        acc += hand_four_bar::fold(four_bar_by_hand(black_box(phi), 10.0, 1.0));
    }
    acc
}

/// `TMM_BATCH=rayon` runs only the parallel group.
fn only_rayon() -> bool {
    std::env::var("TMM_BATCH").is_ok_and(|v| v == "rayon")
}

fn per_position(c: &mut Criterion) {
    if only_rayon() {
        return;
    }
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
    if only_rayon() {
        return;
    }
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

/// This process's CPU time so far, all threads, user and system (what `getrusage` reports,
/// read from Linux's `/proc/self/stat` in clock ticks of 10 ms, since the bench has no
/// `libc`); `None` where that file is not.
#[cfg(feature = "rayon")]
fn cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // After the command name in parentheses: state (field 3), ..., utime (14), stime (15).
    let fields: Vec<&str> = stat[stat.rfind(')')? + 2..].split_whitespace().collect();
    let ticks = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(Duration::from_millis(ticks * 10))
}

/// Runs `f` for about `secs` seconds of wall time: (wall, CPU time) per call.
#[cfg(feature = "rayon")]
fn wall_and_cpu<R>(secs: f64, mut f: impl FnMut() -> R) -> (Duration, Option<Duration>) {
    let (start, cpu0) = (std::time::Instant::now(), cpu_time());
    let mut calls = 0u32;
    while start.elapsed().as_secs_f64() < secs {
        black_box(f());
        calls += 1;
    }
    let wall = start.elapsed() / calls;
    let cpu = cpu0.zip(cpu_time()).map(|(a, b)| (b - a) / calls);
    (wall, cpu)
}

/// Prints one `rayon |` line: the speed-up of `par` over `serial` from the fastest
/// alternating rounds and from 2 s of each, with both one's wall and CPU time per call.
#[cfg(feature = "rayon")]
fn speed_up<A, B>(
    name: &str,
    elements: u32,
    mut par: impl FnMut() -> A,
    mut serial: impl FnMut() -> B,
) {
    let ratio = yardstick::print_ratio(name, elements, &mut par, &mut serial);
    let (par_wall, par_cpu) = wall_and_cpu(2.0, &mut par);
    let (ser_wall, ser_cpu) = wall_and_cpu(2.0, &mut serial);
    let ms = |t: Option<Duration>| t.map_or(f64::NAN, |t| t.as_secs_f64() * 1e3);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "rayon | {name}: {} cores, speed-up {:.2} (fastest rounds), {:.2} (2 s each): wall \
         {:.3} ms parallel vs {:.3} ms serial, CPU {:.3} ms vs {:.3} ms per call; load average {}",
        std::thread::available_parallelism().map_or(0, usize::from),
        1.0 / ratio,
        ser_wall.as_secs_f64() / par_wall.as_secs_f64(),
        par_wall.as_secs_f64() * 1e3,
        ser_wall.as_secs_f64() * 1e3,
        ms(par_cpu),
        ms(ser_cpu),
        load.trim()
    );
}

/// A population of `count` candidate four-bars near `dims()` (some that cannot be assembled
/// over the whole turn), seeded.
#[cfg(feature = "rayon")]
fn population(count: usize) -> Vec<tmm::kinematics::batch::FourBarDims> {
    seeded_angles(count)
        .iter()
        .enumerate()
        .map(|(k, phi)| {
            let mut d = dims();
            d.l_oa = 0.05 + 0.06 * phi / std::f64::consts::TAU;
            d.l_ab += 0.01 * (k % 7) as f64;
            d.coupler.y += 0.002 * (k % 11) as f64;
            d
        })
        .collect()
}

/// The squared distance of the coupler point to a target curve (a circle of 0.1 m about
/// (0.3, 0.25)) summed over the solved lanes, plus a penalty per failed lane: one error
/// number per candidate, as a path synthesis scores it.
#[cfg(feature = "rayon")]
fn path_error(_: usize, p: &Positions) -> f64 {
    let mut e = 0.0;
    for i in 0..p.p_x.len() {
        let (x, y) = (p.p_x[i] - 0.3, p.p_y[i] - 0.25);
        let miss = (x * x + y * y).sqrt() - 0.1;
        e += if p.status[i] == tmm::kinematics::batch::Lane::Ok {
            miss * miss
        } else {
            1.0
        };
    }
    e
}

/// Rayon over batches (group `batch_rayon`):
/// - `par_four_bar_positions` against the serial batch on 2^18 positions of one four-bar,
///   the same lanes (checked bit for bit first);
/// - a population of 4096 candidates, each over 360 positions to one error number, by
///   `par_four_bar_scores` against `four_bar_scores` (checked equal first): the
///   compute-bound case a synthesis runs, each candidate's columns in a worker's cache.
///
/// Beside each ratio of wall times it prints each one's CPU time per call and the load
/// average, since on a shared machine a parallel speed-up is bounded by the cores the others
/// leave free: a speed-up below the core count with the parallel CPU time near the serial one
/// means the cores were busy, not that the work did not split.
#[cfg(feature = "rayon")]
fn parallel(c: &mut Criterion) {
    use tmm::kinematics::batch::{four_bar_scores, par_four_bar_positions, par_four_bar_scores};
    let n = 1 << 18;
    let d = dims();
    let angles = CrankAngles::new(&seeded_angles(n));
    let (mut a, mut b) = (Positions::new(n), Positions::new(n));
    par_four_bar_positions(&d, &angles, a.columns_mut()).unwrap();
    four_bar_positions(&d, &angles, b.columns_mut()).unwrap();
    for (x, y) in [(&a.b_x, &b.b_x), (&a.p_y, &b.p_y), (&a.measure, &b.measure)] {
        assert!(x
            .iter()
            .zip(y.iter())
            .all(|(p, q)| p.to_bits() == q.to_bits()));
    }
    assert_eq!(a.status, b.status);
    speed_up(
        "rayon batch / serial batch (2^18 positions)",
        n as u32,
        || par_four_bar_positions(black_box(&d), &angles, a.columns_mut()).unwrap(),
        || four_bar_positions(black_box(&d), &angles, b.columns_mut()).unwrap(),
    );
    let pop = population(4096);
    let turn = CrankAngles::turn(360);
    let serial = four_bar_scores(&pop, &turn, path_error);
    let par = par_four_bar_scores(&pop, &turn, path_error);
    assert!(serial
        .iter()
        .zip(&par)
        .all(|(p, q)| p.to_bits() == q.to_bits()));
    // Finite errors that tell the candidates apart.
    assert!(serial.iter().all(|e| e.is_finite()) && serial.iter().any(|&e| e != serial[0]));
    speed_up(
        "rayon scores / serial scores (4096 candidates x 360 positions)",
        (pop.len() * turn.len()) as u32,
        || par_four_bar_scores(black_box(&pop), &turn, path_error),
        || four_bar_scores(black_box(&pop), &turn, path_error),
    );
    let mut g = c.benchmark_group("batch_rayon");
    g.measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20)
        .throughput(Throughput::Elements(n as u64));
    g.bench_function("serial", |bch| {
        bch.iter(|| four_bar_positions(black_box(&d), &angles, b.columns_mut()).unwrap())
    });
    g.bench_function("rayon", |bch| {
        bch.iter(|| par_four_bar_positions(black_box(&d), &angles, a.columns_mut()).unwrap())
    });
    g.throughput(Throughput::Elements((pop.len() * turn.len()) as u64));
    g.bench_function("scores_serial", |bch| {
        bch.iter(|| four_bar_scores(black_box(&pop), &turn, path_error))
    });
    g.bench_function("scores_rayon", |bch| {
        bch.iter(|| par_four_bar_scores(black_box(&pop), &turn, path_error))
    });
    g.finish();
}

#[cfg(not(feature = "rayon"))]
fn parallel(_c: &mut Criterion) {}

criterion_group!(benches, per_position, candidates, parallel);
criterion_main!(benches);
