//! Benches of whole mechanisms: one analysis of the six-bar's plan (kinematics, inertia loads,
//! both groups' kinetostatics and the balancing moment) per position, with and without the
//! virtual-power check, reusing one set of buffers (`analyse_into`), and a cycle of N positions (36, 360, 3600; throughput per position, so a linear cost
//! shows as a flat rate), serial and, with `--features rayon`, parallel.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::Motion;
use tmm::linkage::{run_cycle, uniform_inputs};
use tmm::mechanism::{Mechanism, SixBar};

/// Input angles from a fixed-seed linear congruential generator (reproducible, no deps).
fn seeded_inputs(n: usize) -> Vec<Motion> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let phi = (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
            Motion::new(phi, 10.0, 2.0)
        })
        .collect()
}

fn per_position(c: &mut Criterion) {
    let m = SixBar::course_example().plan().unwrap();
    let inputs = seeded_inputs(256);
    let mut g = c.benchmark_group("six_bar_per_position");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20)
        .throughput(Throughput::Elements(inputs.len() as u64));
    g.bench_function("analyse", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &i in &inputs {
                acc += black_box(&m).analyse(black_box(i)).unwrap().balances()[0].value;
            }
            black_box(acc)
        });
    });
    g.bench_function("solver", |b| {
        let mut solver = m.solver();
        b.iter(|| {
            let mut acc = 0.0;
            for &i in &inputs {
                acc += solver.analyse(black_box(i)).unwrap().balances()[0].value;
            }
            black_box(acc)
        });
    });
    g.bench_function("analyse_and_virtual_power_check", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &i in &inputs {
                let p = black_box(&m).analyse(black_box(i)).unwrap();
                acc += p.power_check().unwrap().virtual_power;
            }
            black_box(acc)
        });
    });
    g.finish();
}

fn per_cycle(c: &mut Criterion) {
    let m = SixBar::course_example().plan().unwrap();
    let mut g = c.benchmark_group("six_bar_cycle");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(20);
    for n in [36usize, 360, 3600] {
        let inputs = uniform_inputs(n, 0.1, 10.0, 0.0);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &inputs, |b, inputs| {
            b.iter(|| black_box(run_cycle(black_box(inputs), |i| m.analyse(i))));
        });
        #[cfg(feature = "rayon")]
        g.bench_with_input(BenchmarkId::new("parallel", n), &inputs, |b, inputs| {
            b.iter(|| {
                black_box(tmm::linkage::run_cycle_parallel(black_box(inputs), |i| {
                    m.analyse(i)
                }))
            });
        });
    }
    g.finish();
}

criterion_group!(benches, per_position, per_cycle);
criterion_main!(benches);
