//! The pictures of `tmm::draw` against the analysis they draw, side by side in one run: a
//! 360-position animation of the Watt six-bar (kinematics at every frame, the SVG text)
//! beside the kinematics alone of the same 360 positions; the animation over 36, 360 and
//! 3600 frames, to show that its cost grows linearly with the number of frames; and the plan
//! over courses of 12 to 20 000 positions, to show that its cost stops growing at
//! `MAX_PLAN_POSITIONS` drawn positions (a longer course is thinned).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tmm::draw::{animation, plan_view, scheme, Style};
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, uniform_inputs, Course, Plan};

fn side_by_side(c: &mut Criterion) {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let inputs = uniform_inputs(360, plan.reference_input(), 10.0, 0.0);
    let style = Style::default();
    let mut g = c.benchmark_group("draw/watt six-bar, 360 positions");
    g.measurement_time(Duration::from_secs(5));
    g.bench_function("animation (SVG text)", |b| {
        b.iter(|| animation(black_box(&plan), black_box(&inputs), 4.0, &style).unwrap())
    });
    g.bench_function("kinematics alone", |b| {
        let mut solver = plan.solver();
        b.iter(|| {
            for &m in black_box(&inputs) {
                black_box(solver.kinematics(m).unwrap().joint(0).unwrap());
            }
        })
    });
    g.bench_function("full analysis (kinematics and reactions)", |b| {
        let mut solver = plan.solver();
        b.iter(|| {
            for &m in black_box(&inputs) {
                black_box(solver.analyse(m).unwrap().balances()[0]);
            }
        })
    });
    g.bench_function("one scheme", |b| {
        b.iter(|| scheme(black_box(&plan), Motion::new(1.0, 10.0, 0.0), &style).unwrap())
    });
    g.finish();
}

fn frames(c: &mut Criterion) {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let style = Style::default();
    let mut g = c.benchmark_group("draw/animation frames");
    g.measurement_time(Duration::from_secs(4));
    for n in [36usize, 360, 3600] {
        let inputs = uniform_inputs(n, plan.reference_input(), 10.0, 0.0);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::from_parameter(n), &inputs, |b, inputs| {
            b.iter(|| animation(&plan, black_box(inputs), 4.0, &style).unwrap())
        });
    }
    g.finish();
}

fn plan_positions(c: &mut Criterion) {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let style = Style::default();
    let mut g = c.benchmark_group("draw/plan course length");
    g.measurement_time(Duration::from_secs(4));
    for n in [12usize, 360, 3600, 20_000] {
        let course = Course::new(&plan, None, n, 10.0).unwrap();
        g.bench_with_input(BenchmarkId::from_parameter(n), &course, |b, course| {
            b.iter(|| plan_view(&plan, black_box(course), &["E"], &style).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, side_by_side, frames, plan_positions);
criterion_main!(benches);
