//! Triads with one sliding pair (outer: a slider on the known link's guide; inner: a leg
//! sliding along the ternary link's guide), over `TMM_TRIAD_CASES` seeded random groups of
//! each kind (default 500; 10⁴ in CI): every assembly mode found (the count against an
//! independent dense scan of a different elimination — the ternary link's angle θ with B1 on
//! either intersection of the sliding leg's line with the second leg's circle, and the third
//! leg's closure as the function), every mode closed to 1e-12 of the size, rates against
//! eighth-order finite differences, and the reactions against one LU solve of the group's
//! full Newton–Euler system.

use crate::common::fd::{cases, fd, fd2, near_angle, Rng};
use nalgebra::{DMatrix, DVector, Point2, Vector2};
use std::f64::consts::TAU;
use tmm::angle::{cross, perp, unit};
use tmm::kinematics::{
    slider_triad_modes, slider_triad_rates, slider_triad_tracked, Guide, Motion, PointMotion,
    SliderTriadDims, SlidingPair, TriadPose,
};
use tmm::kinetostatics::{SlideAt, SliderTriad};
use tmm::{Error, Load};

fn n_cases() -> usize {
    cases("TMM_TRIAD_CASES", 500)
}

fn rotate(v: Vector2<f64>, theta: f64) -> Vector2<f64> {
    let (s, c) = theta.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// One random group: its dimensions, the first leg's known part (the guide, or A1) and
/// A2, A3; built from a random pose when `from_pose` (so at least that mode exists), else
/// with random outer joints.
#[derive(Clone, Copy)]
pub(crate) struct Case {
    pub dims: SliderTriadDims,
    pub first: Guide,
    pub a: [Point2<f64>; 2],
    pub generating: Option<[Point2<f64>; 3]>,
}

fn beta(dims: &SliderTriadDims) -> [Vector2<f64>; 3] {
    [
        Vector2::zeros(),
        Vector2::new(dims.l_b1b2, 0.0),
        Vector2::new(dims.b3_along, dims.b3_across),
    ]
}

pub(crate) fn random_case(rng: &mut Rng, inner: bool, from_pose: bool) -> Case {
    let offset = rng.range(-0.5, 0.5);
    let pair = if inner {
        SlidingPair::Inner {
            angle: rng.range(0.0, TAU),
            offset,
        }
    } else {
        SlidingPair::Outer { offset }
    };
    let dims = SliderTriadDims {
        pair,
        l: [rng.range(0.3, 2.0), rng.range(0.3, 2.0)],
        l_b1b2: rng.range(0.3, 1.5),
        b3_along: rng.range(-0.5, 1.5),
        b3_across: rng.range(-1.2, 1.2),
    };
    if !from_pose {
        let first = Guide::fixed(Point2::from(rng.vector(2.0)), rng.range(0.0, TAU));
        let a = [rng.vector(2.0), rng.vector(2.0)].map(Point2::from);
        return Case {
            dims,
            first,
            a,
            generating: None,
        };
    }
    let o = Point2::from(rng.vector(1.0));
    let theta = rng.range(0.0, TAU);
    let b = beta(&dims).map(|q| o + rotate(q, theta));
    let a = [1, 2].map(|k| b[k] - dims.l[k - 1] * unit(rng.range(0.0, TAU)));
    let s = rng.range(-1.0, 1.0);
    let first = match pair {
        SlidingPair::Outer { offset } => {
            let g = rng.range(0.0, TAU);
            let d = unit(g);
            Guide::fixed(o - offset * perp(d) + s * d, g)
        }
        SlidingPair::Inner { angle, offset } => {
            let d = unit(theta + angle);
            Guide::fixed(o + s * d + offset * perp(d), 0.0)
        }
    };
    Case {
        dims,
        first,
        a,
        generating: Some(b),
    }
}

/// The sliding leg's line n·O = h at the ternary link's angle θ, written out here.
fn line(c: &Case, theta: f64) -> (Vector2<f64>, f64) {
    let p = c.first.point.p.coords;
    match c.dims.pair {
        SlidingPair::Outer { offset } => {
            let n = perp(unit(c.first.angle.value));
            (n, n.dot(&p) + offset)
        }
        SlidingPair::Inner { angle, offset } => {
            let n = perp(unit(theta + angle));
            (n, n.dot(&p) - offset)
        }
    }
}

pub(crate) fn size(c: &Case) -> f64 {
    let b = beta(&c.dims);
    let mut s = c.dims.l[0]
        .max(c.dims.l[1])
        .max(b[1].norm())
        .max(b[2].norm());
    for p in [c.first.point.p, c.a[0], c.a[1]] {
        for q in [c.first.point.p, c.a[0], c.a[1]] {
            s = s.max((p - q).norm());
        }
    }
    s
}

/// The count of modes on a grid of n angles θ: B1 on either intersection σ = ± of the
/// sliding leg's line with the second leg's circle, g = |B3 − A3| − l3; roots are the sign
/// changes along each branch, plus one where the branches meet at the end of a run of
/// assemblable angles with opposite signs.
pub(crate) fn count_by_branches(c: &Case, n: usize) -> usize {
    let be = beta(&c.dims);
    let g = |theta: f64, sigma: f64| -> Option<f64> {
        let (nv, h) = line(c, theta);
        let c2 = c.a[0].coords - rotate(be[1], theta);
        let dist = h - nv.dot(&c2);
        let h2 = c.dims.l[0] * c.dims.l[0] - dist * dist;
        if h2.is_nan() || h2 < 0.0 {
            return None;
        }
        let o = c2 + dist * nv + sigma * h2.sqrt() * perp(nv);
        Some((o + rotate(be[2], theta) - c.a[1].coords).norm() - c.dims.l[1])
    };
    crate::triad::count_branch_roots(n, g)
}

/// The largest closure error of a mode: the sliding leg's line, the hinged legs' lengths, the
/// ternary link's shape.
fn closure(pose: &TriadPose, c: &Case) -> f64 {
    let be = beta(&c.dims);
    let o = pose.b[0];
    let (n, h) = line(c, pose.theta);
    let mut err = (n.dot(&o.coords) - h).abs();
    for (k, b) in be.iter().enumerate().skip(1) {
        err = err.max(((pose.b[k] - c.a[k - 1]).norm() - c.dims.l[k - 1]).abs());
        err = err.max((pose.b[k] - (o + rotate(*b, pose.theta))).norm());
    }
    err
}

fn check_count(c: &Case, found: usize, case: usize) {
    let coarse = 1 << 14;
    let mut n = coarse;
    loop {
        let by = count_by_branches(c, n);
        if by == found {
            return;
        }
        assert!(
            n == coarse,
            "case {case}: {found} modes found, {by} by the branches at {n} points; dims = {:?}, \
             first = {:?}, a = {:?}",
            c.dims,
            c.first.point.p,
            c.a
        );
        n *= 16;
    }
}

#[test]
fn slider_triad_modes_match_an_independent_count_and_close() {
    let n = n_cases();
    let mut rng = Rng(0x511D_E028);
    for inner in [false, true] {
        let mut histogram = [0usize; 13];
        let (mut worst, mut not_assemblable) = (0.0f64, 0);
        for case in 0..n {
            let c = random_case(&mut rng, inner, true);
            let s = size(&c);
            let modes = slider_triad_modes(&c.first, c.a, &c.dims)
                .unwrap_or_else(|e| panic!("case {case}: {e}"));
            histogram[modes.len()] += 1;
            for m in modes.as_slice() {
                let err = closure(m, &c) / s;
                assert!(err <= 1e-12, "case {case}: closure {err:e}");
                worst = worst.max(err);
            }
            let b = c.generating.unwrap();
            let generating = TriadPose {
                b,
                theta: 0.0,
                phi: [0.0; 3],
                det: 0.0,
            };
            let near = modes.nearest(&generating);
            let dist = near.distance_squared(&generating).sqrt() / s;
            let tol = if near.det.abs() > 1e-3 { 1e-10 } else { 1e-6 };
            assert!(
                dist <= tol,
                "case {case}: generating pose missed by {dist:e}"
            );
            check_count(&c, modes.len(), case);

            let c = random_case(&mut rng, inner, false);
            match slider_triad_modes(&c.first, c.a, &c.dims) {
                Ok(modes) => {
                    let s = size(&c);
                    for m in modes.as_slice() {
                        let err = closure(m, &c) / s;
                        assert!(err <= 1e-12, "free case {case}: closure {err:e}");
                        worst = worst.max(err);
                    }
                    check_count(&c, modes.len(), case);
                }
                Err(Error::NotAssemblable { group, gap }) => {
                    assert_eq!(group, "triad with a sliding pair");
                    assert!(gap > 0.0);
                    not_assemblable += 1;
                    check_count(&c, 0, case);
                }
                Err(e) => panic!("free case {case}: {e}"),
            }
        }
        println!(
            "triad with a sliding pair ({}): {n} groups from poses, modes 1..: {:?}; {n} free \
             groups, {not_assemblable} not assemblable; largest closure {worst:.2e} of the size",
            if inner { "inner" } else { "outer" },
            &histogram[1..]
        );
    }
}

/// The known parts moving along known paths: x(t) = x + v·t + a·t²/2 (the guide's angle too).
pub(crate) fn moved(first: &Guide, a: &[PointMotion; 2], t: f64) -> (Guide, [PointMotion; 2]) {
    let go =
        |m: &PointMotion| PointMotion::new(m.p + m.v * t + 0.5 * m.a * t * t, m.v + m.a * t, m.a);
    let g = first.angle;
    (
        Guide {
            point: go(&first.point),
            angle: Motion::new(
                g.value + g.rate * t + 0.5 * g.accel * t * t,
                g.rate + g.accel * t,
                g.accel,
            ),
        },
        a.map(|m| go(&m)),
    )
}

#[test]
fn slider_triad_rates_match_finite_differences() {
    let n = n_cases();
    let mut rng = Rng(0x5EED_5128);
    for inner in [false, true] {
        let (mut worst_v, mut worst_a, mut checked) = (0.0f64, 0.0f64, 0);
        let (mut tracked, mut tried) = (0, 0);
        for case in 0..n {
            let c = random_case(&mut rng, inner, true);
            let modes = slider_triad_modes(&c.first, c.a, &c.dims).unwrap();
            let first = Guide {
                point: PointMotion::new(c.first.point.p, rng.vector(1.0), rng.vector(1.0)),
                angle: Motion::new(
                    c.first.angle.value,
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                ),
            };
            let a =
                c.a.map(|p| PointMotion::new(p, rng.vector(1.0), rng.vector(1.0)));
            for base in modes.as_slice() {
                if base.det.abs() < 0.05 {
                    continue;
                }
                let s0 = slider_triad_rates(&first, a, &c.dims, base).unwrap();
                let s = size(&c);
                let turn = s0
                    .binary
                    .iter()
                    .map(|l| 1.0 + l.omega.abs())
                    .fold(1.0 + s0.ternary.omega.abs(), f64::max);
                let h = 2e-4 / turn;
                let mut poses = [*base; 9];
                let mut ok = true;
                for (j, pose) in poses.iter_mut().enumerate() {
                    let t = (j as f64 - 4.0) * h;
                    let (g, am) = moved(&first, &a, t);
                    let m = slider_triad_modes(&g, [am[0].p, am[1].p], &c.dims).unwrap();
                    *pose = *m.nearest(base);
                    // The fast path, when it answers, is the bracket's nearest mode.
                    tried += 1;
                    if let Some(fast) = slider_triad_tracked(&g, [am[0].p, am[1].p], &c.dims, base)
                    {
                        tracked += 1;
                        let off = fast.distance_squared(pose).sqrt();
                        assert!(
                            off <= 1e-12 * size(&c),
                            "case {case}: the fast path jumped modes by {off:e}: fast {fast:?}, full {pose:?}"
                        );
                    }
                    ok &= pose.distance_squared(base).sqrt() < 0.1;
                }
                if !ok {
                    continue;
                }
                // Velocities by differences of positions, accelerations by differences of the
                // exact velocities; relative to the largest velocity (and ω·size), acceleration
                // (and ε·size).
                let states = [0, 1, 2, 3, 4, 5, 6, 7, 8].map(|j| {
                    let t = (j as f64 - 4.0) * h;
                    let (g, am) = moved(&first, &a, t);
                    slider_triad_rates(&g, am, &c.dims, &poses[j]).unwrap()
                });
                let links = [s0.ternary, s0.binary[0], s0.binary[1], s0.binary[2]];
                let v_scale =
                    s0.b.iter()
                        .map(|m| m.v.norm())
                        .chain(links.iter().map(|l| l.omega.abs() * s))
                        .fold(1.0, f64::max);
                let a_scale =
                    s0.b.iter()
                        .map(|m| m.a.norm())
                        .chain(links.iter().map(|l| l.epsilon.abs() * s))
                        .fold(1.0, f64::max);
                let (mut ev, mut ea) = (0.0f64, 0.0f64);
                for i in 0..3 {
                    let v = fd2(&poses.map(|p| p.b[i].coords), h);
                    ev = ev.max((v - s0.b[i].v).norm());
                    let acc = fd2(&states.map(|s| s.b[i].v), h);
                    ea = ea.max((acc - s0.b[i].a).norm());
                }
                let th = poses.map(|p| near_angle(p.theta, base.theta));
                ev = ev.max((fd(&th, h) - s0.ternary.omega).abs() * s);
                let eps = fd(&states.map(|s| s.ternary.omega), h);
                ea = ea.max((eps - s0.ternary.epsilon).abs() * s);
                for k in 0..3 {
                    let phi = poses.map(|p| near_angle(p.phi[k], base.phi[k]));
                    ev = ev.max((fd(&phi, h) - s0.binary[k].omega).abs() * s);
                    let e = fd(&states.map(|s| s.binary[k].omega), h);
                    ea = ea.max((e - s0.binary[k].epsilon).abs() * s);
                }
                worst_v = worst_v.max(ev / v_scale);
                worst_a = worst_a.max(ea / a_scale);
                checked += 1;
            }
            assert!(
                worst_v <= 1e-8 && worst_a <= 1e-8,
                "case {case}: v {worst_v:e}, a {worst_a:e}"
            );
        }
        println!(
            "triad with a sliding pair ({}): rates of {checked} modes vs 8th-order differences: \
             velocities {worst_v:.1e}, accelerations {worst_a:.1e}; the fast path answered \
             {tracked} of {tried} positions, always the bracket's nearest mode",
            if inner { "inner" } else { "outer" }
        );
        assert!(checked > n / 2);
        // Steps of 2e-4 rad from a regular mode: the certificate holds nearly everywhere.
        assert!(tracked * 10 > tried * 9, "{tracked} of {tried}");
    }
}

/// The group's full Newton–Euler system, 12×12, solved by LU. Unknowns: R_A2, R_A3, R_B2,
/// R_B3, then the sliding pair's normal force N (along n, through B1 outer or A1 inner) and
/// couple C, then the leg's hinge force (R_B1 outer, R_A1 inner). Rows: force and moment
/// about the origin of links 1, 2, 3 and the ternary link.
fn general_solve(t: &SliderTriad) -> DVector<f64> {
    let mut m = DMatrix::<f64>::zeros(12, 12);
    let mut rhs = DVector::<f64>::zeros(12);
    let n = t.normal / t.normal.norm();
    // Adds the force (column `col`, or N·n for col 8) acting at p to link `row`'s equations.
    let put = |m: &mut DMatrix<f64>, row: usize, col: usize, p: Point2<f64>, sign: f64| {
        if col == 8 {
            m[(row, 8)] += sign * n.x;
            m[(row + 1, 8)] += sign * n.y;
            m[(row + 2, 8)] += sign * cross(p.coords, n);
        } else {
            m[(row, col)] += sign;
            m[(row + 1, col + 1)] += sign;
            m[(row + 2, col)] -= sign * p.y;
            m[(row + 2, col + 1)] += sign * p.x;
        }
    };
    for k in 1..3 {
        let row = 3 * k;
        let (ca, cb) = (2 * (k - 1), 4 + 2 * (k - 1));
        put(&mut m, row, ca, t.a[k], 1.0);
        put(&mut m, row, cb, t.b[k], -1.0);
        put(&mut m, 9, cb, t.b[k], 1.0);
    }
    match t.slide {
        SlideAt::Outer => {
            put(&mut m, 0, 8, t.b[0], 1.0);
            m[(2, 9)] = 1.0;
            put(&mut m, 0, 10, t.b[0], -1.0);
            put(&mut m, 9, 10, t.b[0], 1.0);
        }
        SlideAt::Inner => {
            put(&mut m, 0, 10, t.a[0], 1.0);
            put(&mut m, 0, 8, t.a[0], -1.0);
            m[(2, 9)] = -1.0;
            put(&mut m, 9, 8, t.a[0], 1.0);
            m[(11, 9)] = 1.0;
        }
    }
    for (row, load) in [
        (0, t.loads[0]),
        (3, t.loads[1]),
        (6, t.loads[2]),
        (9, t.load_ternary),
    ] {
        rhs[row] = -load.force.x;
        rhs[row + 1] = -load.force.y;
        rhs[row + 2] = -load.moment_about(Point2::origin());
    }
    m.lu().solve(&rhs).expect("regular group")
}

#[test]
fn slider_triad_reactions_match_the_general_solve() {
    let n = n_cases();
    let mut rng = Rng(0xF0CE_5128);
    for inner in [false, true] {
        let (mut worst, mut checked) = (0.0f64, 0);
        for case in 0..n {
            let c = random_case(&mut rng, inner, true);
            let modes = slider_triad_modes(&c.first, c.a, &c.dims).unwrap();
            for pose in modes.as_slice() {
                if pose.det.abs() < 0.05 {
                    continue;
                }
                let d = unit(pose.phi[0]);
                let load = |rng: &mut Rng, p: Point2<f64>| {
                    Load::new(
                        p + rng.vector(0.5),
                        rng.vector(100.0),
                        rng.range(-50.0, 50.0),
                    )
                };
                let a0 = if inner { c.first.point.p } else { pose.b[0] };
                let t = SliderTriad {
                    slide: if inner {
                        SlideAt::Inner
                    } else {
                        SlideAt::Outer
                    },
                    normal: perp(d) * rng.range(0.5, 2.0),
                    a: [a0, c.a[0], c.a[1]],
                    b: pose.b,
                    loads: [
                        load(&mut rng, a0),
                        load(&mut rng, c.a[0]),
                        load(&mut rng, c.a[1]),
                    ],
                    load_ternary: load(&mut rng, pose.b[0]),
                };
                let r = t.solve().unwrap_or_else(|e| panic!("case {case}: {e}"));
                let x = general_solve(&t);
                let v = |k: usize| Vector2::new(x[k], x[k + 1]);
                let nn = t.normal / t.normal.norm();
                let scale = 100.0 / pose.det.abs().min(1.0);
                let mut diff = (r.r_a[1] - v(0)).norm().max((r.r_a[2] - v(2)).norm());
                diff = diff.max((r.r_b[1] - v(4)).norm().max((r.r_b[2] - v(6)).norm()));
                diff = diff.max((r.normal_force - x[8]).abs());
                diff = diff.max((r.couple - x[9]).abs());
                if inner {
                    diff = diff.max((r.r_a[0] - v(10)).norm());
                    diff = diff.max((r.r_b[0] - nn * x[8]).norm());
                } else {
                    diff = diff.max((r.r_b[0] - v(10)).norm());
                    diff = diff.max((r.r_a[0] - nn * x[8]).norm());
                }
                worst = worst.max(diff / scale);
                checked += 1;
            }
        }
        println!(
            "triad with a sliding pair ({}): reactions of {checked} modes vs the 12×12 LU: \
             {worst:.1e} of the load scale",
            if inner { "inner" } else { "outer" }
        );
        assert!(worst < 1e-11, "{worst:e}");
    }
}

#[test]
fn slider_triad_names_bad_input() {
    let mut rng = Rng(7);
    let c = random_case(&mut rng, false, true);
    let mut bad = c.dims;
    bad.l[0] = -1.0;
    assert!(matches!(
        slider_triad_modes(&c.first, c.a, &bad),
        Err(Error::NonPositive { .. })
    ));
    let mut a = c.a;
    a[1].x = f64::NAN;
    assert!(matches!(
        slider_triad_modes(&c.first, a, &c.dims),
        Err(Error::NonFinite { .. })
    ));
    // Out of reach: A3 beyond everything.
    let mut a = c.a;
    a[1] = a[0] + Vector2::new(1e3, 0.0);
    assert!(matches!(
        slider_triad_modes(&c.first, a, &c.dims),
        Err(Error::NotAssemblable {
            group: "triad with a sliding pair",
            ..
        })
    ));
}
