//! Benchmarks of the force method for the group with a parallel coupler (seed 002).
//!
//! - one solve, bending only vs with axial flexibility;
//! - a sweep of N positions (α4 across 30°…150°, seeded loads): the cost must grow linearly;
//! - the extremes of the N, Q, M diagrams of all three links.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinetostatics::passive::{solve, Geometry, Link, LinkLoad, Loads, PaperGroup, Stiffness};

/// A small xorshift generator: the same inputs on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` positions of the seed's group: α4 sweeps 30°…150°, the loads are seeded.
fn positions(n: usize) -> Vec<(Geometry, Loads)> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    (0..n)
        .map(|i| {
            let a4 = (30.0 + 120.0 * i as f64 / n.max(1) as f64).to_radians();
            let p = PaperGroup {
                alpha4: a4,
                ..PaperGroup::example()
            };
            let g = p.geometry().expect("valid geometry");
            let mut loads = p.loads().expect("valid loads");
            loads.f1 = LinkLoad::force(
                0.2 * rng.next(),
                500.0 * (rng.next() - 0.5) * nalgebra::Vector2::new(1.0, 2.0),
            );
            loads.per_length[2] = nalgebra::Vector2::new(0.0, -100.0 * rng.next());
            (g, loads)
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let p = PaperGroup::example();
    let g = p.geometry().expect("valid geometry");
    let loads = p.loads().expect("valid loads");

    let mut one = c.benchmark_group("passive/solve");
    one.measurement_time(Duration::from_secs(2)).sample_size(20);
    for (name, st) in [
        ("bending_only", Stiffness::bending_only(1.0)),
        ("with_axial", Stiffness::with_axial(1.0, 1e4)),
    ] {
        one.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| solve(black_box(&g), black_box(&loads), black_box(&st)))
        });
    }
    one.finish();

    let mut sweep = c.benchmark_group("passive/positions");
    sweep
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    let st = Stiffness::with_axial(1.0, 1e4);
    for n in [10usize, 100, 1000] {
        let input = positions(n);
        sweep.throughput(Throughput::Elements(n as u64));
        sweep.bench_with_input(BenchmarkId::from_parameter(n), &input, |b, input| {
            b.iter(|| {
                input
                    .iter()
                    .map(|(g, l)| solve(g, l, &st).map_or(0.0, |s| s.x1))
                    .sum::<f64>()
            })
        });
    }
    sweep.finish();

    let s = solve(&g, &loads, &Stiffness::bending_only(1.0)).expect("solvable");
    let mut ex = c.benchmark_group("passive/extremes");
    ex.measurement_time(Duration::from_secs(2)).sample_size(20);
    ex.bench_function(BenchmarkId::from_parameter("all_links"), |b| {
        b.iter(|| Link::ALL.map(|link| black_box(&s).extremes(link)))
    });
    ex.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
