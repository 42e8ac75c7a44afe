//! Kinetostatics with Coulomb friction: each dyad's friction solve beside its frictionless
//! closed form, over the same batch of seeded dyads (the ratio is measured side by side, and
//! printed as `ratio | …` lines from interleaved rounds, the median of 31), and the RRR dyad
//! across friction coefficients (`BenchmarkId::from_parameter`): the Newton steps grow with
//! the friction's feedback on itself; and a whole four-bar's analysis with and without.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::{Duration, Instant};
use tmm::kinetostatics::friction::{
    Hinge, PrpFriction, PrpJoints, PrpRates, RppFriction, RppJoints, RppRates, RprFriction,
    RprJoints, RprRates, RrpFriction, RrpJoints, RrpRates, RrrFriction, RrrJoints, RrrRates, Slide,
};
use tmm::kinetostatics::{PrpDyad, RppDyad, RprDyad, RrpDyad};

const BATCH: usize = 256;

#[path = "common/dyads.rs"]
mod dyads;
use dyads::Rng;

/// The friction blocks over the shared seeded dyads.
impl Rng {
    fn rate(&mut self) -> f64 {
        let s = if self.unit() < 0.5 { -1.0 } else { 1.0 };
        s * self.range(0.5, 10.0)
    }
    fn hinge(&mut self, f: f64) -> Hinge {
        Hinge::pin(self.range(0.01, 0.05), f).unwrap()
    }
    fn rrr(&mut self, f: f64) -> RrrFriction {
        RrrFriction {
            dyad: self.rrr_dyad(),
            joints: RrrJoints {
                a: self.hinge(f),
                b: self.hinge(f),
                c: self.hinge(f),
            },
            rates: RrrRates {
                omega1: self.rate(),
                omega2: self.rate(),
                omega3: self.rate(),
                omega4: self.rate(),
            },
        }
    }
    fn rrp(&mut self, f: f64) -> RrpFriction {
        RrpFriction {
            dyad: RrpDyad {
                a: self.a(),
                b: self.b(),
                guide: Vector2::new(1.0, self.range(0.5, 1.5)),
                load2: self.load(),
                load3: self.load(),
            },
            joints: RrpJoints {
                a: self.hinge(f),
                b: self.hinge(f),
                guide: Slide::new(f).unwrap(),
            },
            rates: RrpRates {
                omega1: self.rate(),
                omega2: self.rate(),
                omega4: self.rate(),
                slide: self.rate(),
            },
        }
    }
    fn rpr(&mut self, f: f64) -> RprFriction {
        let (a, e) = (self.a(), self.c());
        RprFriction {
            dyad: RprDyad {
                a,
                e,
                axis: e - a + Vector2::new(0.0, self.range(-0.2, 0.2)),
                load2: self.load(),
                load3: self.load(),
            },
            joints: RprJoints {
                a: self.hinge(f),
                slide: Slide::new(f).unwrap(),
                e: self.hinge(f),
            },
            rates: RprRates {
                omega1: self.rate(),
                omega: self.rate(),
                omega4: self.rate(),
                slide: self.rate(),
            },
        }
    }
    fn prp(&mut self, f: f64) -> PrpFriction {
        PrpFriction {
            dyad: PrpDyad {
                b: self.b(),
                guide2: Vector2::new(1.0, self.range(-0.2, 0.2)),
                guide3: Vector2::new(self.range(-0.3, 0.3), 1.0),
                load2: self.load(),
                load3: self.load(),
            },
            joints: PrpJoints {
                guide2: Slide::new(f).unwrap(),
                b: self.hinge(f),
                guide3: Slide::new(f).unwrap(),
            },
            rates: PrpRates {
                omega1: self.rate(),
                omega4: self.rate(),
                slide2: self.rate(),
                slide3: self.rate(),
            },
        }
    }
    fn rpp(&mut self, f: f64) -> RppFriction {
        let a = self.a();
        RppFriction {
            dyad: RppDyad {
                a,
                b: Point2::new(a.x, 0.0),
                guide: Vector2::new(1.0, self.range(-0.2, 0.2)),
                slot: Vector2::new(self.range(-0.3, 0.3), 1.0),
                load2: self.load(),
                load3: self.load(),
            },
            joints: RppJoints {
                a: self.hinge(f),
                slot: Slide::new(f).unwrap(),
                guide: Slide::new(f).unwrap(),
            },
            rates: RppRates {
                omega1: self.rate(),
                omega4: self.rate(),
                slot: self.rate(),
                slide: self.rate(),
            },
        }
    }
}

/// The median over 301 interleaved rounds of (time of `with`) / (time of `without`), each
/// round one pass of each (a batch short beside the scheduler's slice, so that on a loaded
/// machine a preemption spoils a few rounds, not the median); `round` is the round's index.
fn interleaved_ratio(without: &mut dyn FnMut(usize), with: &mut dyn FnMut(usize)) -> f64 {
    let mut ratios = Vec::new();
    for round in 0..301 {
        let t0 = Instant::now();
        without(round);
        let t1 = Instant::now();
        with(round);
        let t2 = Instant::now();
        ratios.push((t2 - t1).as_secs_f64() / (t1 - t0).as_secs_f64());
    }
    ratios.sort_by(f64::total_cmp);
    ratios[150]
}

macro_rules! side_by_side {
    ($g:expr, $name:literal, $batch:expr) => {{
        let batch = $batch;
        let mut without = || {
            for p in black_box(&batch) {
                black_box(p.dyad.solve().unwrap());
            }
        };
        let mut with = || {
            for p in black_box(&batch) {
                black_box(p.solve().unwrap());
            }
        };
        let iterations: usize = batch
            .iter()
            .map(|p| p.solve().unwrap().convergence.iterations)
            .sum();
        println!(
            "ratio | {} friction (f = 0.15) / frictionless = {:.2} (mean Newton steps {:.2})",
            $name,
            interleaved_ratio(&mut |_| without(), &mut |_| with()),
            iterations as f64 / batch.len() as f64
        );
        $g.bench_function(concat!($name, "/frictionless"), |b| b.iter(&mut without));
        $g.bench_function(concat!($name, "/friction"), |b| b.iter(&mut with));
    }};
}

fn per_call(c: &mut Criterion) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let f = 0.15;
    let mut g = c.benchmark_group("friction_side_by_side");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .throughput(Throughput::Elements(BATCH as u64));
    side_by_side!(g, "rrr", (0..BATCH).map(|_| rng.rrr(f)).collect::<Vec<_>>());
    side_by_side!(g, "rrp", (0..BATCH).map(|_| rng.rrp(f)).collect::<Vec<_>>());
    side_by_side!(g, "rpr", (0..BATCH).map(|_| rng.rpr(f)).collect::<Vec<_>>());
    side_by_side!(g, "prp", (0..BATCH).map(|_| rng.prp(f)).collect::<Vec<_>>());
    side_by_side!(g, "rpp", (0..BATCH).map(|_| rng.rpp(f)).collect::<Vec<_>>());
    g.finish();
}

fn across_coefficients(c: &mut Criterion) {
    let mut g = c.benchmark_group("friction_rrr_by_f");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .throughput(Throughput::Elements(BATCH as u64));
    for f in [0.0, 0.05, 0.15, 0.3] {
        let mut rng = Rng(0x2545_F491_4F6C_DD1D);
        let batch: Vec<_> = (0..BATCH).map(|_| rng.rrr(f)).collect();
        g.bench_with_input(BenchmarkId::from_parameter(f), &batch, |b, batch| {
            b.iter(|| {
                for p in black_box(batch) {
                    black_box(p.solve().unwrap());
                }
            })
        });
    }
    g.finish();
}

/// The whole four-bar (`bundled::four_bar`, its weights, inertia and resistance) at 360
/// positions of a turn, each position's full analysis (kinematics, loads, kinetostatics, the
/// balancing moment) with friction f = 0.15 in every pin (radius 2 % of its size) beside
/// the same without.
fn four_bar(c: &mut Criterion) {
    use tmm::kinematics::Motion;
    use tmm::linkage::{bundled, Friction, Plan};
    let base = bundled::four_bar();
    let free = Plan::new(&base).unwrap();
    let mut with = base.clone();
    with.friction = Some(Friction::pin(0.15, 0.02 * free.size()));
    let plan = Plan::new(&with).unwrap();
    let inputs: Vec<Motion> = (0..360)
        .map(|k| {
            let phi = free.reference_input() + std::f64::consts::TAU * f64::from(k) / 360.0;
            Motion::turning(phi, 10.0)
        })
        .collect();
    let (mut s0, mut s1) = (free.solver(), plan.solver());
    let mut without = || {
        for &m in black_box(&inputs) {
            black_box(s0.analyse(m).unwrap().balance(0).unwrap().value);
        }
    };
    let mut friction = || {
        for &m in black_box(&inputs) {
            black_box(s1.analyse(m).unwrap().balance(0).unwrap().value);
        }
    };
    // The interleaved rounds take 36 positions each (every tenth, from the round's).
    let (mut s2, mut s3) = (free.solver(), plan.solver());
    let tenth = |round: usize| inputs.iter().skip(round % 10).step_by(10);
    let ratio = interleaved_ratio(
        &mut |round| {
            for &m in tenth(round) {
                black_box(s2.analyse(m).unwrap().balance(0).unwrap().value);
            }
        },
        &mut |round| {
            for &m in tenth(round) {
                black_box(s3.analyse(m).unwrap().balance(0).unwrap().value);
            }
        },
    );
    println!("ratio | four-bar whole position friction (f = 0.15) / frictionless = {ratio:.2}");
    let mut g = c.benchmark_group("friction_four_bar");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500))
        .throughput(Throughput::Elements(inputs.len() as u64));
    g.bench_function("frictionless", |b| b.iter(&mut without));
    g.bench_function("friction", |b| b.iter(&mut friction));
    g.finish();
}

criterion_group!(benches, per_call, across_coefficients, four_bar);
criterion_main!(benches);
