//! Kinetostatics: each closed-form solver per call beside the general LU solve of the same
//! group (the ratio is measured side by side), and an RRR sweep over 10³..10⁶ positions to
//! show that the cost grows linearly with the number of positions.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinetostatics::{CouplingDrive, GearDrive, PrpDyad, RppDyad, RprDyad, RrpDyad, RrrDyad};
use tmm::Load;

#[path = "../../tests/kinetostatics/general_solve.rs"]
#[allow(dead_code)]
mod general_solve;

/// A small seeded generator (xorshift64*), so every run benches the same inputs.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn point(&mut self) -> Point2<f64> {
        Point2::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0))
    }
    fn load(&mut self) -> Load {
        Load::new(
            self.point(),
            Vector2::new(self.range(-500.0, 500.0), self.range(-500.0, 500.0)),
            self.range(-50.0, 50.0),
        )
    }
    fn rrr(&mut self) -> RrrDyad {
        RrrDyad {
            a: Point2::new(self.range(-1.0, -0.5), self.range(-0.2, 0.2)),
            b: Point2::new(self.range(-0.2, 0.2), self.range(0.5, 1.0)),
            c: Point2::new(self.range(0.5, 1.0), self.range(-0.2, 0.2)),
            load2: self.load(),
            load3: self.load(),
        }
    }
}

fn per_call(c: &mut Criterion) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let rrr = rng.rrr();
    let rrp = RrpDyad {
        a: rrr.a,
        b: rrr.b,
        guide: Vector2::new(1.0, 0.2),
        load2: rng.load(),
        load3: rng.load(),
    };
    let rpr = RprDyad {
        a: rrr.a,
        e: rrr.c,
        axis: rrr.c - rrr.a,
        load2: rng.load(),
        load3: rng.load(),
    };
    // The two dyads with two sliding pairs, of the same size and loads as the RRP beside them.
    let prp = PrpDyad {
        b: rrr.b,
        guide2: Vector2::new(1.0, 0.2),
        guide3: Vector2::new(-0.3, 1.0),
        load2: rng.load(),
        load3: rng.load(),
    };
    let rpp = RppDyad {
        a: rrr.a,
        b: rrr.b,
        guide: Vector2::new(1.0, 0.2),
        slot: rrr.a - rrr.b,
        load2: rng.load(),
        load3: rng.load(),
    };
    let loads = [rng.load(), rng.load()];
    let o1 = Point2::origin();
    let gear = GearDrive::at_angle(o1, 0.2, 3.0, 0.35);

    let mut g = c.benchmark_group("kinetostatics_per_call");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    g.bench_function("rrr/closed_form", |b| b.iter(|| black_box(&rrr).solve()));
    g.bench_function("rrr/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rrr);
            general_solve::rrr(d.a, d.b, d.c, &d.load2, &d.load3)
        })
    });
    g.bench_function("rrp/closed_form", |b| b.iter(|| black_box(&rrp).solve()));
    g.bench_function("rrp/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rrp);
            general_solve::rrp(d.a, d.b, d.guide, &d.load2, &d.load3)
        })
    });
    g.bench_function("prp/closed_form", |b| b.iter(|| black_box(&prp).solve()));
    g.bench_function("prp/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&prp);
            general_solve::prp(d.b, d.guide2, d.guide3, &d.load2, &d.load3)
        })
    });
    g.bench_function("rpp/closed_form", |b| b.iter(|| black_box(&rpp).solve()));
    g.bench_function("rpp/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rpp);
            general_solve::rpp(d.a, d.b, d.guide, d.slot, &d.load2, &d.load3)
        })
    });
    g.bench_function("rpr/closed_form", |b| b.iter(|| black_box(&rpr).solve()));
    g.bench_function("rpr/general_lu", |b| {
        b.iter(|| {
            let d = black_box(&rpr);
            general_solve::rpr(d.a, d.e, d.axis, &d.load2, &d.load3)
        })
    });
    g.bench_function("coupling/closed_form", |b| {
        b.iter(|| CouplingDrive { o1 }.solve(black_box(&loads)))
    });
    g.bench_function("coupling/general_lu", |b| {
        b.iter(|| general_solve::coupling(o1, black_box(&loads)))
    });
    g.bench_function("gear/closed_form", |b| {
        b.iter(|| black_box(&gear).solve(black_box(&loads)))
    });
    g.finish();
}

fn sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("kinetostatics_rrr_positions");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500));
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let mut rng = Rng(42);
        let dyads: Vec<RrrDyad> = (0..n).map(|_| rng.rrr()).collect();
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &dyads, |b, dyads| {
            b.iter(|| {
                dyads
                    .iter()
                    .map(|d| d.solve().map_or(0.0, |r| r.r12.x))
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, per_call, sweep);
criterion_main!(benches);
