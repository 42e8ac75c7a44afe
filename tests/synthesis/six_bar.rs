//! Six-bar path generation recovers known Stephenson III six-bars: targets are the tracer
//! points of a random six-bar (seeded) at prescribed crank angles, made here with the
//! engine's public blocks; the best design must meet them to a mean miss ≤ 1e-6 of the
//! path's size as the engine analyses its description (any six-bar through the points
//! passes). `TMM_SYNTH_CASES` sets the number of cases (1 by default; CI runs more). With
//! the budget counted in full (session 8) and 2 million evaluations, the first 6 in release
//! were recovered to 6e-15 of the path's size while the designs could end outside
//! `max_size`; held to the box (session 10), case 3 misses at 5.4e-6 (cases 0–2, 4, 5 are
//! recovered to 1.0e-15). Session 13, with the RRR dyad from the shorter link's pivot (its
//! last bits changed) the search meets cases 0, 5, 8, 9 of 0–9 (case 3's near miss, 3.0e-6:
//! polished freely it leaves the constraints, \[γ\] or assembly over the range).
//! `TMM_SYNTH_JITTER=k` moves every target coordinate by k ulps (see `recoveries_of`).

use super::path::{best_never_rises, centroid_size, prescribed, recoveries_of, Mechanism, Rng};
use nalgebra::Point2;
use tmm::kinematics::batch::coupler_point;
use tmm::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use tmm::synthesis::{six_bar_path_generator, PathOptions, PathRequirement, Progress, Timing};
use tmm::Error;

fn mode(rng: &mut Rng) -> Branch {
    if rng.unit() < 0.5 {
        Branch::Plus
    } else {
        Branch::Minus
    }
}

/// The tracer point of a six-bar at `phi` and the smaller |sin γ| of its two dyads: the
/// crank O1A, the dyad A–B–O3, C on the coupler, the dyad C–E–O5, P on CE.
#[allow(clippy::too_many_arguments)]
fn tracer(
    o1: Point2<f64>,
    o3: Point2<f64>,
    o5: Point2<f64>,
    l: [f64; 5],
    uv: [[f64; 2]; 2],
    modes: [Branch; 2],
    phi: f64,
) -> Option<(Point2<f64>, f64)> {
    let a = crank(o1, l[0], Motion::fixed(phi)).ok()?.a;
    let r1 = rrr_dyad(a, PointMotion::fixed(o3), l[1], l[2], modes[0]).ok()?;
    let c = coupler_point(a.p, r1.b.p, uv[0]);
    let r2 = rrr_dyad(
        PointMotion::fixed(c),
        PointMotion::fixed(o5),
        l[3],
        l[4],
        modes[1],
    )
    .ok()?;
    Some((
        coupler_point(c, r2.b.p, uv[1]),
        r1.det.abs().min(r2.det.abs()),
    ))
}

/// The tracer points at `phis` of a random six-bar whose two dyads keep γ ≥ 41° over the
/// range of `phis` (every 0.005 rad), links within a ratio of 8, pivots and dimensions
/// within 4 path sizes of the points' centroid (inside the search's default bounds); drawn
/// again until one does.
fn target(rng: &mut Rng, phis: &[f64]) -> Vec<[f64; 2]> {
    let sin_g = 41f64.to_radians().sin();
    loop {
        let o1 = Point2::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2));
        let o3 = Point2::new(rng.range(0.3, 0.8), rng.range(-0.2, 0.2));
        let o5 = Point2::new(rng.range(-0.5, 1.0), rng.range(0.2, 1.0));
        let l = [
            rng.range(0.08, 0.25),
            rng.range(0.3, 0.9),
            rng.range(0.3, 0.9),
            rng.range(0.3, 0.9),
            rng.range(0.3, 0.9),
        ];
        let uv = [
            [rng.range(-0.3, 1.0), rng.range(-0.6, 0.6)],
            [rng.range(-0.3, 1.0), rng.range(-0.6, 0.6)],
        ];
        let modes = [mode(rng), mode(rng)];
        let frame = (o3 - o1).norm();
        let all = [frame, l[0], l[1], l[2], l[3], l[4]];
        let (mn, mx) = all
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if mx / mn > 8.0 {
            continue;
        }
        let (lo, hi) = (phis[0], phis[phis.len() - 1]);
        let steps = ((hi - lo) / 0.005).ceil() as usize;
        let good = (0..=steps).all(|k| {
            tracer(
                o1,
                o3,
                o5,
                l,
                uv,
                modes,
                lo + (hi - lo) * k as f64 / steps as f64,
            )
            .is_some_and(|(_, g)| g >= sin_g)
        });
        if !good {
            continue;
        }
        let pts: Vec<[f64; 2]> = phis
            .iter()
            .map(|&phi| {
                let p = tracer(o1, o3, o5, l, uv, modes, phi).unwrap().0;
                [p.x, p.y]
            })
            .collect();
        let (c, size) = centroid_size(&pts);
        let from_c = |p: Point2<f64>| (p.x - c[0]).hypot(p.y - c[1]);
        let far = [from_c(o1), from_c(o5), frame]
            .into_iter()
            .chain(l)
            .chain([uv[0][0].abs() * l[1], uv[0][1].abs() * l[1]])
            .chain([uv[1][0].abs() * l[3], uv[1][1].abs() * l[3]])
            .fold(0.0, f64::max);
        if far < 4.0 * size {
            return pts;
        }
    }
}

/// Eight points (as many as the six-bar's 16 unknowns allow: precision points) over 2.25 rad
/// of the crank from a random θ0.
fn requirement(rng: &mut Rng) -> PathRequirement {
    prescribed(rng, 8, 2.25 / 7.0, target)
}

#[test]
fn recovers_six_bars_with_prescribed_timing() {
    recoveries_of("six-bar, 8 points", 2310, Mechanism::SixBar, requirement);
}

#[test]
fn bad_six_bar_requirements_name_the_parameter() {
    let mut rng = Rng(7);
    let good = requirement(&mut rng);
    let opts = PathOptions::default();
    let name_of = |req: &PathRequirement, opts: &PathOptions| -> String {
        match six_bar_path_generator(req, opts, |_| true) {
            Err(Error::OutOfRange { name, .. }) | Err(Error::NonFinite { name, .. }) => {
                name.to_string()
            }
            other => panic!("expected an error naming the parameter, got {other:?}"),
        }
    };
    let free = PathRequirement {
        timing: Timing::Free,
        ..good.clone()
    };
    assert!(name_of(&free, &opts).starts_with("timing"));
    let mut few = good.clone();
    few.points.pop();
    if let Timing::Prescribed(d) = &mut few.timing {
        d.pop();
    }
    assert!(name_of(&few, &opts).starts_with("points"));
    let mut nan = good.clone();
    nan.points[3][1] = f64::NAN;
    assert!(name_of(&nan, &opts).starts_with("points"));
    let mut short = good.clone();
    if let Timing::Prescribed(d) = &mut short.timing {
        d.push(2.5);
    }
    assert!(name_of(&short, &opts).starts_with("timing"));
    let tiny = PathOptions::default().with_max_evaluations(10);
    assert!(name_of(&good, &tiny).starts_with("max_evaluations"));
    // A crank angle beyond ±10⁹ rad names no crank position (the design would be posed at
    // another angle than the one searched): refused, not answered with a wrong linkage.
    let mut far = good.clone();
    if let Timing::Prescribed(d) = &mut far.timing {
        d.iter_mut().for_each(|x| *x += 1e17);
    }
    assert!(name_of(&far, &opts).starts_with("timing"));
    // Two distinct points at one crank angle: no tracer is at two places at once.
    let mut twice = good.clone();
    if let Timing::Prescribed(d) = &mut twice.timing {
        d[5] = d[1];
    }
    match six_bar_path_generator(&twice, &opts, |_| true) {
        Err(Error::Description { item, problem }) => {
            assert!(
                item == "timing" && problem.contains("points 2 and 6"),
                "{problem}"
            )
        }
        other => panic!("expected the timing named, got {other:?}"),
    }
    let mut same = good.clone();
    same.points[4] = same.points[2];
    assert!(matches!(
        six_bar_path_generator(&same, &opts, |_| true),
        Err(Error::NoMechanism { .. })
    ));
}

#[test]
fn the_six_bar_search_keeps_its_budget() {
    let mut rng = Rng(11);
    let req = requirement(&mut rng);
    let budget = 3_000;
    let opts = PathOptions::default()
        .with_population(40)
        .with_max_evaluations(budget)
        .with_designs(1);
    let mut last: Option<Progress> = None;
    let mut calls = 0;
    let result = six_bar_path_generator(&req, &opts, |p| {
        calls += 1;
        if let Some(q) = &last {
            assert!(p.generation > q.generation && p.evaluations >= q.evaluations);
        }
        last = Some(*p);
        true
    });
    let last = last.expect("progress is reported");
    assert!(
        calls > 0 && last.evaluations <= budget,
        "{} > {budget}",
        last.evaluations
    );
    // A search cut that short either found a design (checked whole) or says so.
    match result {
        Ok(d) => assert!(d[0].mean_error.is_finite() && d[0].max_error >= d[0].mean_error),
        Err(Error::NoMechanism { problem, .. }) => assert!(problem.contains("evaluations")),
        Err(e) => panic!("{e}"),
    }
    // Stopped by the callback after its first generation: one generation only.
    let mut gens = 0;
    let _ = six_bar_path_generator(&req, &PathOptions::default(), |_| {
        gens += 1;
        false
    });
    assert_eq!(gens, 1);
}

/// The best the six-bar's search reports never rises, across its restarts too: on points a
/// six-bar meets exactly (its 16 unknowns fit 8 points whatever they are, jittered or not) a
/// run converges, stagnates and restarts.
#[test]
fn the_six_bar_best_reported_never_rises() {
    let req = requirement(&mut Rng(12));
    best_never_rises(Mechanism::SixBar, &req, 200_000);
}

/// The example requirement is the tracer of the six-bar its documentation names (made here
/// with the engine's public blocks), at crank angles 0.3 rad apart from 0.3 rad, and that
/// six-bar keeps γ above the 0.3 rad its worked example asks for over the points' span.
#[test]
fn the_six_bar_example_is_the_six_bar_it_names() {
    let req = PathRequirement::six_bar_example().unwrap();
    let Timing::Prescribed(delta) = &req.timing else {
        panic!("the example's timing is prescribed")
    };
    assert_eq!((delta.len(), req.points.len()), (8, 8));
    let at = |phi| {
        tracer(
            Point2::origin(),
            Point2::new(0.35, 0.0),
            Point2::new(0.3, 0.35),
            [0.1, 0.3, 0.25, 0.25, 0.2],
            [[0.5, 0.4], [0.6, -0.3]],
            [Branch::Plus, Branch::Minus],
            phi,
        )
        .unwrap()
    };
    for (k, (d, t)) in delta.iter().zip(&req.points).enumerate() {
        assert!((d - 0.3 * k as f64).abs() < 1e-15);
        let p = at(0.3 + d).0;
        assert!((p.x - t[0]).hypot(p.y - t[1]) < 1e-15, "point {k}");
    }
    let lowest = (0..=210)
        .map(|k| at(0.3 + 0.01 * k as f64).1)
        .fold(f64::INFINITY, f64::min);
    assert!(lowest > 0.3f64.sin(), "{lowest}");
}

/// `max_size` holds every returned design: in a box of 2 path sizes (less than half the
/// default 5, where the search's polishes end outside it most often) each design's pivots O1
/// and O5 lie within the box's coordinates of the points' centroid, its six lengths
/// (measured between the description's joints, so the report is not taken on trust) and the
/// offsets of C and P within the box, and its misses are what the engine gives. A box too
/// small for the tracer to reach the farthest point is refused naming `max_size`.
#[test]
fn six_bar_designs_keep_their_box() {
    let req = PathRequirement::six_bar_example().unwrap();
    let (c, size) = centroid_size(&req.points);
    let s = 2.0;
    let opts = PathOptions::default()
        .with_max_size(s)
        .with_min_transmission_angle(0.3)
        .with_max_evaluations(60_000)
        .with_designs(3);
    let designs = six_bar_path_generator(&req, &opts, |_| true).unwrap();
    let limit = s * size * (1.0 + 1e-12);
    for d in &designs {
        let l = &d.synthesis.linkage;
        let at = |name: &str| {
            let j = l.joints.iter().find(|j| j.name == name).unwrap();
            Point2::new(j.at[0], j.at[1])
        };
        for pivot in ["O1", "O5"] {
            let p = at(pivot);
            assert!(
                (p.x - c[0]).abs() <= limit && (p.y - c[1]).abs() <= limit,
                "{pivot} at {p:?}, the box {limit} about {c:?}"
            );
        }
        for (a, b) in [
            ("O1", "O3"),
            ("O1", "A"),
            ("A", "B"),
            ("O3", "B"),
            ("C", "E"),
            ("O5", "E"),
        ] {
            let len = (at(a) - at(b)).norm();
            assert!(len <= limit, "{a}{b} = {len}, the box {limit}");
        }
        // C on AB and P on CE, (along, across) each within the box.
        let offsets = |from: &str, to: &str, point: Point2<f64>| {
            let (f, t) = (at(from), at(to));
            let u = (t - f).normalize();
            let r = point - f;
            [r.dot(&u), u.x * r.y - u.y * r.x]
        };
        let p = l.links.iter().find(|k| k.name == "link CE").unwrap().points[0].at;
        for v in
            offsets("A", "B", at("C"))
                .into_iter()
                .chain(offsets("C", "E", Point2::new(p[0], p[1])))
        {
            assert!(v.abs() <= limit, "offset {v}, the box {limit}");
        }
        assert!(d.mean_error.is_finite() && d.max_error >= d.mean_error);
    }
    // The tracer of a box s reaches less than (√2 + 1 + √5)·s from the centroid.
    let tiny = PathOptions::default().with_max_size(0.2);
    match six_bar_path_generator(&req, &tiny, |_| true) {
        Err(Error::OutOfRange { name, min, .. }) => {
            assert!(name.starts_with("max_size"), "{name}");
            assert!((min - 1.0 / (2f64.sqrt() + 1.0 + 5f64.sqrt())).abs() < 1e-15);
        }
        other => panic!("expected max_size refused, got {other:?}"),
    }
}
