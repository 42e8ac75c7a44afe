//! Scenario tests of the kinematics: whole cycles of real linkages, where they lock, their
//! extreme positions, the seed's compressor (2.10–2.14), the numerical formulas' orders, and
//! every error path.

use nalgebra::{Point2, Vector2};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use tmm::angle::{cross, normalize};
use tmm::kinematics::{
    assembly_range, coupler_curve, crank, cycle, cycle_angles, differentiate,
    differentiate_periodic, extreme_positions, integrate_trapezoid, rpr_dyad, rrp_dyad, rrr_dyad,
    solve_contour, transfer_functions, Branch, ExtremeKind, Guide, LoopVector, Motion, PointMotion,
    Rotation, Strokes,
};
use tmm::Error;

const O: Point2<f64> = Point2::new(0.0, 0.0);

/// A crank-rocker four-bar: frame O C, crank 1, coupler 2, rocker 3 (Grashof, crank shortest).
struct FourBar {
    c: Point2<f64>,
    l1: f64,
    l2: f64,
    l3: f64,
    branch: Branch,
}

impl FourBar {
    fn solve(&self, input: Motion) -> tmm::Result<(PointMotion, tmm::kinematics::RrrState)> {
        let a = crank(O, self.l1, input)?.a;
        let d = rrr_dyad(a, PointMotion::fixed(self.c), self.l2, self.l3, self.branch)?;
        Ok((a, d))
    }
    fn size(&self) -> f64 {
        self.l1 + self.l2 + self.l3 + self.c.coords.norm()
    }
}

const CRANK_ROCKER: FourBar = FourBar {
    c: Point2::new(0.4, 0.05),
    l1: 0.1,
    l2: 0.35,
    l3: 0.3,
    branch: Branch::Plus,
};

#[test]
fn crank_rocker_closes_and_keeps_its_branch_around_the_cycle() {
    for branch in [Branch::Plus, Branch::Minus] {
        let m = FourBar {
            branch,
            ..CRANK_ROCKER
        };
        let n = 3600;
        let states = cycle(n, 0.3, |phi| m.solve(Motion::new(phi, 12.0, -3.0))).unwrap();
        let mut worst = 0.0f64;
        let mut min_det = f64::INFINITY;
        let mut max_jump = 0.0f64;
        for (k, (a, d)) in states.iter().enumerate() {
            worst = worst
                .max(((d.b.p - a.p).norm() - m.l2).abs())
                .max(((d.b.p - m.c).norm() - m.l3).abs());
            // The assembly mode is geometric: B stays on the same side of A → C.
            let side = cross(m.c - a.p, d.b.p - a.p);
            assert_eq!(side > 0.0, branch == Branch::Plus, "branch flipped at {k}");
            min_det = min_det.min(d.det.abs());
            let next = &states[(k + 1) % n].1;
            let jump = normalize(next.link3.angle - d.link3.angle + PI) - PI;
            max_jump = max_jump.max(jump.abs());
        }
        assert!(worst <= 1e-12 * m.size(), "closure residual {worst:e}");
        assert!(
            min_det > 0.3,
            "the crank-rocker never nears a dead point: {min_det}"
        );
        // Continuous: the rocker moves by less than its ω bound times the step.
        assert!(
            max_jump < 0.01,
            "rocker jumps by {max_jump} rad between positions"
        );
    }
}

#[test]
fn slider_crank_closes_and_keeps_its_branch_around_the_cycle() {
    let (l1, l2, e) = (0.05, 0.2, 0.02);
    for branch in [Branch::Plus, Branch::Minus] {
        let guide = Guide::fixed(Point2::new(0.0, e), 0.0);
        let states = cycle(3600, 0.0, |phi| {
            let a = crank(O, l1, Motion::new(phi, 100.0, 0.0))?.a;
            Ok((a, rrp_dyad(a, guide, l2, branch)?))
        })
        .unwrap();
        for (a, d) in &states {
            assert!(((d.b.p - a.p).norm() - l2).abs() <= 1e-12 * (l1 + l2));
            assert!((d.b.p.y - e).abs() <= 1e-12 * (l1 + l2));
            // B stays ahead of (Plus) or behind (Minus) the foot of A on the guide.
            assert_eq!(d.b.p.x - a.p.x > 0.0, branch == Branch::Plus);
            assert!(d.det.abs() > 0.8);
            assert_eq!(d.det > 0.0, branch == Branch::Plus);
        }
    }
}

#[test]
fn non_grashof_four_bar_reports_where_it_locks() {
    // s + l = 0.08 + 0.3 > p + q = 0.2 + 0.15: no link turns fully. The dyad closes while
    // |AC| ≤ l2 + l3, i.e. cos φ1 ≥ (l1² + d² − (l2 + l3)²)/(2·l1·d).
    let m = FourBar {
        c: Point2::new(0.3, 0.0),
        l1: 0.2,
        l2: 0.08,
        l3: 0.15,
        branch: Branch::Plus,
    };
    let d = 0.3;
    let lock = ((m.l1 * m.l1 + d * d - (m.l2 + m.l3).powi(2)) / (2.0 * m.l1 * d)).acos();
    let err = cycle(360, 0.0, |phi| m.solve(Motion::unit_speed(phi))).unwrap_err();
    let Error::In { part, source } = err else {
        panic!("expected the failing position, got {err:?}")
    };
    assert!(matches!(*source, Error::NotAssemblable { group: "RRR dyad", gap } if gap > 0.0));
    let reported: f64 = part
        .split("locks at phi1 = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .expect("the lock angle is in the message");
    assert!((reported - lock).abs() <= 1e-12, "{part} vs {lock}");
    let (lo, hi) = assembly_range(0.0, |phi| m.solve(Motion::unit_speed(phi)))
        .unwrap()
        .expect("the input cannot turn fully");
    assert!(
        (hi - lock).abs() <= 1e-12 && (lo + lock).abs() <= 1e-12,
        "{lo} {hi} {lock}"
    );
    // A crank-rocker's input turns fully.
    assert_eq!(
        assembly_range(0.0, |phi| CRANK_ROCKER.solve(Motion::unit_speed(phi))).unwrap(),
        None
    );
}

#[test]
fn offset_slider_crank_extremes_strokes_and_plans() {
    let (l1, l2, e) = (0.05, 0.2, 0.02);
    let guide = Guide::fixed(Point2::new(0.0, e), 0.0);
    let slider = |phi: f64| {
        transfer_functions(
            |input| Ok(rrp_dyad(crank(O, l1, input)?.a, guide, l2, Branch::Plus)?.slide),
            phi,
        )
    };
    let ext = extreme_positions(slider, 360).unwrap();
    assert_eq!(ext.len(), 2);
    // Closed forms: extended (crank along O B) and folded (crank opposite O B).
    let s_max = ((l1 + l2).powi(2) - e * e).sqrt();
    let s_min = ((l2 - l1).powi(2) - e * e).sqrt();
    let phi_ext = normalize(e.atan2(s_max));
    let phi_fold = normalize((-e).atan2(-s_min));
    for x in &ext {
        assert!(
            x.output.rate.abs() <= 1e-12 * l1,
            "s' = {:e}",
            x.output.rate
        );
        let (phi, s) = match x.kind {
            ExtremeKind::Max => (phi_ext, s_max),
            ExtremeKind::Min => (phi_fold, s_min),
        };
        assert!((x.input - phi).abs() <= 1e-12, "{} vs {phi}", x.input);
        assert!((x.output.value - s).abs() <= 1e-15);
    }
    // Strokes: with the crank turning CCW the crank goes from the extended to the folded
    // position through π + θ, θ = asin(e/(l2 − l1)) − asin(e/(l2 + l1)).
    let theta = (e / (l2 - l1)).asin() - (e / (l2 + l1)).asin();
    let s = Strokes::new(&ext, Rotation::Ccw).unwrap();
    assert!((s.working_angle - (PI + theta)).abs() <= 1e-12);
    assert!((s.time_ratio - (PI + theta) / (PI - theta)).abs() <= 1e-12);
    assert!((s.start - phi_ext).abs() <= 1e-12);
    // Clockwise, the longer way round starts at the folded position.
    let cw = Strokes::new(&ext, Rotation::Cw).unwrap();
    assert!(
        (cw.start - phi_fold).abs() <= 1e-12 && (cw.working_angle - s.working_angle).abs() <= 1e-12
    );
    // The 12 plans start at the beginning of the working stroke, 30° apart.
    let plans = s.plan_positions(12);
    assert_eq!(plans.len(), 12);
    assert_eq!(plans[0], s.start);
    for (k, p) in plans.iter().enumerate() {
        let want = normalize(s.start + k as f64 * TAU / 12.0);
        assert!((p - want).abs() <= 1e-14);
    }
    assert_eq!(cycle_angles(12, s.start), plans);
}

#[test]
fn crank_rocker_extremes_are_where_crank_and_coupler_are_collinear() {
    let m = &CRANK_ROCKER;
    let rocker =
        |phi: f64| transfer_functions(|input| Ok(m.solve(input)?.1.link3.angle_motion()), phi);
    let ext = extreme_positions(rocker, 360).unwrap();
    assert_eq!(ext.len(), 2);
    for x in &ext {
        assert!(x.output.rate.abs() <= 1e-12, "phi3' = {:e}", x.output.rate);
        let (_, d) = m.solve(Motion::fixed(x.input)).unwrap();
        let ob = d.b.p.coords.norm();
        let want = match x.kind {
            ExtremeKind::Max | ExtremeKind::Min => {
                if (ob - (m.l1 + m.l2)).abs() < (ob - (m.l2 - m.l1)).abs() {
                    m.l1 + m.l2
                } else {
                    m.l2 - m.l1
                }
            }
        };
        assert!((ob - want).abs() <= 1e-12, "|OB| = {ob}, want {want}");
    }
    // One extreme is the extended position, the other the folded one.
    let obs: Vec<f64> = ext
        .iter()
        .map(|x| m.solve(Motion::fixed(x.input)).unwrap().1.b.p.coords.norm())
        .collect();
    assert!((obs[0] - obs[1]).abs() > 0.1);
}

#[test]
fn coupler_points_move_with_the_coupler() {
    let m = &CRANK_ROCKER;
    let (along, across) = (0.2, 0.1);
    let curve = coupler_curve(720, 0.0, |phi| {
        Ok(m.solve(Motion::fixed(phi))?
            .1
            .link2
            .point_at(along, across)
            .p)
    })
    .unwrap();
    let states = cycle(720, 0.0, |phi| m.solve(Motion::fixed(phi))).unwrap();
    let (ra, rb) = (
        (along * along + across * across).sqrt(),
        ((m.l2 - along).powi(2) + across * across).sqrt(),
    );
    for (s, (a, d)) in curve.iter().zip(&states) {
        assert!(((s - a.p).norm() - ra).abs() <= 1e-14);
        assert!(((s - d.b.p).norm() - rb).abs() <= 1e-14);
        // On the left of A → B.
        assert!(cross(d.b.p - a.p, s - a.p) > 0.0);
    }
}

#[test]
fn six_bar_chain_closes_every_loop() {
    // Crank-rocker, then a slider on a horizontal guide driven from the rocker's tip D
    // (CD = 0.5 m along C → B) by a rod of 0.4 m: a shaper-like six-bar.
    let m = &CRANK_ROCKER;
    let guide = Guide::fixed(Point2::new(0.0, 0.6), 0.0);
    let states = cycle(1000, 0.0, |phi| {
        let (a, d) = m.solve(Motion::new(phi, 10.0, 0.0))?;
        let tip = d.link3.point_at(0.5, 0.0);
        Ok((a, d, tip, rrp_dyad(tip, guide, 0.4, Branch::Plus)?))
    })
    .unwrap();
    for (_, _, tip, s) in &states {
        assert!(((s.b.p - tip.p).norm() - 0.4).abs() <= 1e-12 * 2.0);
        assert!((s.b.p.y - 0.6).abs() <= 1e-12 * 2.0);
        // The slider's absolute velocity is along the fixed guide.
        assert!(s.b.v.y.abs() <= 1e-12 * s.b.v.norm().max(1.0));
    }
}

/// Seed 001's compressor: one crank, two slider-crank contours OABO and OCDO, guides along
/// y, angles clockwise from +y (the seed's convention, converted here at the edge).
#[test]
fn compressor_reproduces_seed_2_10_to_2_14_with_k1_k2() {
    let (l1, l2, l4, l_as2) = (0.06, 0.24, 0.24, 0.08);
    let omega1 = 960.0 * TAU / 60.0; // n1 = 960 rpm, clockwise (positive in the seed)
    let eps1 = 250.0; // a non-uniform input, to exercise K2
    let guide = Guide::fixed(O, FRAC_PI_2);
    let mut max_rel = 0.0f64;
    let mut printed_k1_error = 0.0f64;
    for k in 0..12 {
        let psi1 = k as f64 * TAU / 12.0 + 0.1; // seed angle, clockwise from +y
                                                // Crate convention: θ = π/2 − ψ, ω and ε change sign.
        let input = Motion::new(FRAC_PI_2 - psi1, -omega1, -eps1);
        let a = crank(O, l1, input).unwrap().a;
        let c = crank(
            O,
            l1,
            Motion::new(input.value + PI, input.rate, input.accel),
        )
        .unwrap()
        .a;
        for (pin, psi, l, d) in [
            (a, psi1, l2, rrp_dyad(a, guide, l2, Branch::Plus).unwrap()),
            (
                c,
                psi1 + PI,
                l4,
                rrp_dyad(c, guide, l4, Branch::Plus).unwrap(),
            ),
        ] {
            let _ = pin;
            // (2.10): φ2 = arcsin(−l1 sin φ1 / l2); l3 = l1 cos φ1 + l2 cos φ2.
            let phi2 = (-l1 * psi.sin() / l).asin();
            let l3 = l1 * psi.cos() + l * phi2.cos();
            // (2.11), (2.12).
            let w2 = -l1 * omega1 * psi.cos() / (l * phi2.cos());
            let v3 = -l1 * omega1 * psi.sin() - l * w2 * phi2.sin();
            // (2.13) with K2's ε1 term; (2.14) with K1's sign and K2's ε1 term.
            let e2 = (l1 * omega1 * omega1 * psi.sin() - l1 * eps1 * psi.cos()
                + l * w2 * w2 * phi2.sin())
                / (l * phi2.cos());
            let a3 = -l1 * omega1 * omega1 * psi.cos()
                - l1 * eps1 * psi.sin()
                - l * w2 * w2 * phi2.cos()
                - l * e2 * phi2.sin();
            let a3_printed = l1 * omega1 * omega1 * psi.cos()
                - l * w2 * w2 * phi2.cos()
                - l * e2 * phi2.sin()
                - l1 * eps1 * psi.sin();
            // The crate, converted back to the seed's convention.
            let got_phi2 = normalize(FRAC_PI_2 - d.link2.angle + PI) - PI;
            let pairs = [
                (got_phi2, phi2, 1.0),
                (d.slide.value, l3, l1),
                (-d.link2.omega, w2, omega1),
                (d.slide.rate, v3, l1 * omega1),
                (-d.link2.epsilon, e2, omega1 * omega1),
                (d.slide.accel, a3, l1 * omega1 * omega1),
            ];
            for (got, want, scale) in pairs {
                max_rel = max_rel.max((got - want).abs() / scale);
            }
            printed_k1_error =
                printed_k1_error.max((a3_printed - a3).abs() / (l1 * omega1 * omega1));
            if psi == psi1 {
                // S2 (K4): the coordinates and their derivatives.
                let s2 = d.link2.point_at(l_as2, 0.0);
                let x = l1 * psi.sin() + l_as2 * phi2.sin();
                let y = l1 * psi.cos() + l_as2 * phi2.cos();
                let vx = l1 * omega1 * psi.cos() + l_as2 * w2 * phi2.cos();
                let vy = -l1 * omega1 * psi.sin() - l_as2 * w2 * phi2.sin();
                let ax = -l1 * omega1 * omega1 * psi.sin() + l1 * eps1 * psi.cos()
                    - l_as2 * w2 * w2 * phi2.sin()
                    + l_as2 * e2 * phi2.cos();
                let ay = -l1 * omega1 * omega1 * psi.cos()
                    - l1 * eps1 * psi.sin()
                    - l_as2 * w2 * w2 * phi2.cos()
                    - l_as2 * e2 * phi2.sin();
                assert!((s2.p - Point2::new(x, y)).norm() <= 1e-15);
                assert!((s2.v - Vector2::new(vx, vy)).norm() <= 1e-12 * l1 * omega1);
                assert!((s2.a - Vector2::new(ax, ay)).norm() <= 1e-12 * l1 * omega1 * omega1);
            }
        }
    }
    assert!(max_rel <= 1e-12, "largest relative difference {max_rel:e}");
    // K1: the printed (2.14) is wrong by 2·l1·ω1²·cos φ1, up to twice the crank pin's
    // centripetal acceleration.
    assert!(printed_k1_error > 1.9, "{printed_k1_error}");

    // K3: the second contour on its own branch, the opposed cylinder (D below O). With the
    // pin C = −l1·(sin φ1, cos φ1) and D = (0, l5) on the guide, |D − C| = l4 gives
    // l5 = −l1 cos φ1 ∓ √(l4² − l1² sin² φ1); Minus is the lower root. Its rates by the chain
    // rule (φ̇1 = ω1, φ̈1 = ε1 in the seed's clockwise convention), with R = √(l4² − l1² sin² φ1):
    // dl5/dφ1 = l1 sin φ1 + l1² sin φ1 cos φ1 / R,
    // d²l5/dφ1² = l1 cos φ1 + l1² cos 2φ1 / R + (l1² sin φ1 cos φ1)² / R³.
    let mut k3 = 0.0f64;
    for k in 0..12 {
        let phi1 = k as f64 * TAU / 12.0 + 0.1;
        let input = Motion::new(FRAC_PI_2 - phi1 + PI, -omega1, -eps1);
        let c = crank(O, l1, input).unwrap().a;
        let (sn, cs) = phi1.sin_cos();
        let root = (l4 * l4 - l1 * l1 * sn * sn).sqrt();
        let l5 = -l1 * cs - root;
        let d1 = l1 * sn + l1 * l1 * sn * cs / root;
        let d2 = l1 * cs
            + l1 * l1 * (2.0 * phi1).cos() / root
            + (l1 * l1 * sn * cs).powi(2) / root.powi(3);
        let (v5, a5) = (omega1 * d1, eps1 * d1 + omega1 * omega1 * d2);
        let minus = rrp_dyad(c, guide, l4, Branch::Minus).unwrap();
        assert!(minus.slide.value < 0.0, "the opposed cylinder is below O");
        k3 = k3
            .max((minus.slide.value - l5).abs() / l1)
            .max((minus.slide.rate - v5).abs() / (l1 * omega1))
            .max((minus.slide.accel - a5).abs() / (l1 * omega1 * omega1));
        // Plus is the other root, above O: both contours on it put the pistons on one side.
        let plus = rrp_dyad(c, guide, l4, Branch::Plus).unwrap();
        k3 = k3.max((plus.slide.value - (-l1 * cs + root)).abs() / l1);
    }
    assert!(k3 <= 1e-12, "K3: largest relative difference {k3:e}");
}

/// Observed orders log2(e_h / e_{h/2}) over successive halvings.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn three_point_formulas_and_trapezoid_are_second_order() {
    // The offset slider-crank's s(φ1) over part of a turn (not a full period, so the
    // trapezoid rule shows its generic order, not the periodic super-convergence).
    let (l1, l2, e) = (0.05, 0.2, 0.02);
    let guide = Guide::fixed(Point2::new(0.0, e), 0.0);
    let s = |phi: f64| {
        transfer_functions(
            |input| Ok(rrp_dyad(crank(O, l1, input)?.a, guide, l2, Branch::Plus)?.slide),
            phi,
        )
        .unwrap()
    };
    let (x0, x1) = (0.2, 2.2);
    let mut e_inner = vec![];
    let mut e_ends = vec![];
    let mut e_trap = vec![];
    let mut e_twice_inner = vec![];
    let mut e_twice_ends = vec![];
    for n in [40usize, 80, 160, 320] {
        let h = (x1 - x0) / n as f64;
        let xs: Vec<f64> = (0..=n).map(|i| x0 + i as f64 * h).collect();
        let m: Vec<_> = xs.iter().map(|&x| s(x)).collect();
        let y: Vec<f64> = m.iter().map(|m| m.value).collect();
        let d = differentiate(&y, h).unwrap();
        let err = |i: usize| (d[i] - m[i].rate).abs();
        e_inner.push((1..n).map(err).fold(0.0, f64::max));
        e_ends.push(err(0).max(err(n)));
        let yp: Vec<f64> = m.iter().map(|m| m.rate).collect();
        let int = integrate_trapezoid(&yp, h).unwrap();
        e_trap.push(
            (0..=n)
                .map(|i| (int[i] - (y[i] - y[0])).abs())
                .fold(0.0, f64::max),
        );
        // s″ by differentiating twice (K11's surprise: first order at the end nodes).
        let dd = differentiate(&d, h).unwrap();
        let err2 = |i: usize| (dd[i] - m[i].accel).abs();
        e_twice_inner.push((2..n - 1).map(err2).fold(0.0, f64::max));
        e_twice_ends.push(err2(0).max(err2(n)));
    }
    for (name, errs, lo, hi) in [
        ("central", &e_inner, 1.9, 2.1),
        ("one-sided ends", &e_ends, 1.9, 2.1),
        ("trapezoid", &e_trap, 1.95, 2.05),
        ("twice, inside", &e_twice_inner, 1.9, 2.1),
        ("twice, at the ends", &e_twice_ends, 0.8, 1.2),
    ] {
        for p in orders(errs) {
            assert!(
                (lo..hi).contains(&p),
                "{name}: observed order {p} ({errs:?})"
            );
        }
    }
}

#[test]
fn periodic_differences_are_second_order_even_twice() {
    let (l1, l2) = (0.05, 0.2);
    let guide = Guide::fixed(O, 0.0);
    let mut e1 = vec![];
    let mut e2 = vec![];
    for n in [36usize, 72, 144, 288] {
        let h = TAU / n as f64;
        let m = cycle(n, 0.0, |phi| {
            transfer_functions(
                |input| Ok(rrp_dyad(crank(O, l1, input)?.a, guide, l2, Branch::Plus)?.slide),
                phi,
            )
        })
        .unwrap();
        let y: Vec<f64> = m.iter().map(|m| m.value).collect();
        let d = differentiate_periodic(&y, h).unwrap();
        let dd = differentiate_periodic(&d, h).unwrap();
        e1.push(
            m.iter()
                .zip(&d)
                .map(|(m, d)| (d - m.rate).abs())
                .fold(0.0, f64::max),
        );
        e2.push(
            m.iter()
                .zip(&dd)
                .map(|(m, d)| (d - m.accel).abs())
                .fold(0.0, f64::max),
        );
    }
    for p in orders(&e1).into_iter().chain(orders(&e2)) {
        assert!((1.9..2.1).contains(&p), "order {p}");
    }
}

#[test]
fn bad_inputs_are_errors_never_nan() {
    let a = PointMotion::fixed(Point2::new(0.1, 0.0));
    let c = PointMotion::fixed(Point2::new(0.3, 0.0));
    let nan_a = PointMotion::fixed(Point2::new(f64::NAN, 0.0));
    assert!(matches!(
        rrr_dyad(nan_a, c, 0.2, 0.2, Branch::Plus),
        Err(Error::NonFinite { name: "A.x", .. })
    ));
    assert!(matches!(
        rrr_dyad(a, c, 0.0, 0.2, Branch::Plus),
        Err(Error::NonPositive { name: "l_AB", .. })
    ));
    assert!(matches!(
        rrr_dyad(a, c, 0.2, -1.0, Branch::Plus),
        Err(Error::NonPositive { name: "l_CB", .. })
    ));
    assert!(matches!(
        crank(O, 0.1, Motion::new(0.0, f64::INFINITY, 0.0)),
        Err(Error::NonFinite { name: "omega1", .. })
    ));
    assert!(matches!(
        rrp_dyad(a, Guide::fixed(O, f64::NAN), 0.2, Branch::Plus),
        Err(Error::NonFinite { name: "phi4", .. })
    ));
    // Not assemblable, with the gap.
    match rrr_dyad(a, c, 0.05, 0.1, Branch::Plus) {
        Err(Error::NotAssemblable {
            group: "RRR dyad",
            gap,
        }) => assert!((gap - 0.05).abs() < 1e-15),
        other => panic!("{other:?}"),
    }
    match rrp_dyad(
        PointMotion::fixed(Point2::new(0.0, 0.3)),
        Guide::fixed(O, 0.0),
        0.2,
        Branch::Plus,
    ) {
        Err(Error::NotAssemblable {
            group: "RRP dyad",
            gap,
        }) => assert!((gap - 0.1).abs() < 1e-15),
        other => panic!("{other:?}"),
    }
    // Dead points: exactly collinear links, a rod perpendicular to the guide, A on C.
    match rrr_dyad(
        PointMotion::fixed(O),
        PointMotion::fixed(Point2::new(0.5, 0.0)),
        0.2,
        0.3,
        Branch::Plus,
    ) {
        Err(Error::Singular {
            what: "RRR dyad",
            measure: "sin(phi3 - phi2)",
            value,
        }) => {
            assert!(value.abs() <= 1e-12)
        }
        other => panic!("{other:?}"),
    }
    match rrp_dyad(
        PointMotion::fixed(Point2::new(0.0, 0.2)),
        Guide::fixed(O, 0.0),
        0.2,
        Branch::Plus,
    ) {
        Err(Error::Singular {
            what: "RRP dyad",
            measure: "cos(phi2 - phi4)",
            value,
        }) => {
            assert!(value.abs() <= 1e-12)
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        rpr_dyad(a, a),
        Err(Error::Singular {
            what: "RPR dyad",
            measure: "l_EA",
            ..
        })
    ));
    // A contour needs exactly two unknowns.
    let one = [
        LoopVector::fixed(Vector2::new(1.0, 0.0)),
        LoopVector::unknown_angle(1.0),
    ];
    assert!(
        matches!(solve_contour(&one, Branch::Plus), Err(Error::OutOfRange { value, .. }) if value == 1.0)
    );
    let parallel = [
        LoopVector::fixed(Vector2::new(1.0, 1.0)),
        LoopVector::unknown_length(Motion::fixed(0.3)),
        LoopVector::unknown_length(Motion::fixed(0.3 + PI)),
    ];
    assert!(matches!(
        solve_contour(&parallel, Branch::Plus),
        Err(Error::Singular { .. })
    ));
    assert!(matches!(
        cycle(0, 0.0, |_| Ok(())),
        Err(Error::OutOfRange { .. })
    ));
    assert!(differentiate(&[1.0, 2.0], 0.1).is_err());
    assert!(differentiate(&[1.0, 2.0, 3.0], 0.0).is_err());
    assert!(integrate_trapezoid(&[1.0, f64::NAN], 0.1).is_err());
}

#[test]
fn finite_inputs_that_overflow_are_errors_never_infinities() {
    // A step of a few ulps or values near f64::MAX overflow the differences and the sums.
    let nf = |r: tmm::Result<Vec<f64>>| matches!(r, Err(Error::Overflow { .. }));
    assert!(nf(differentiate(&[1.0, 2.0, 4.0], 1e-320)));
    assert!(nf(differentiate(&[1e308, -1e308, 1e308], 1.0)));
    assert!(nf(differentiate_periodic(&[1e308, -1e308, 1e308], 1.0)));
    assert!(nf(integrate_trapezoid(&[1e308, 1e308, 1e308], 1.0)));
    // l_OA·ω1² beyond f64::MAX.
    assert!(matches!(
        crank(O, 1e300, Motion::new(0.0, 1e200, 0.0)),
        Err(Error::Overflow { .. })
    ));
    // A non-finite angle never reaches the user's closure.
    assert!(matches!(
        transfer_functions(Ok, f64::NAN),
        Err(Error::NonFinite { name: "phi1", .. })
    ));
    // Extremes built by hand with a NaN angle.
    let e = |input, kind| tmm::kinematics::Extreme {
        input,
        output: Motion::default(),
        kind,
    };
    let bad = [e(f64::NAN, ExtremeKind::Max), e(1.0, ExtremeKind::Min)];
    assert!(matches!(
        Strokes::new(&bad, Rotation::Ccw),
        Err(Error::NonFinite { .. })
    ));
}

#[test]
fn near_a_dead_point_the_determinant_shows_the_amplification() {
    // A moves at 1 m/s away from C along the line C A of an RRR dyad that is nearly
    // stretched out (|AC| = l2 + l3 − δ), the one motion the stretched dyad cannot follow:
    // ω3 grows like 1/det, and ω3·det tends to a finite limit.
    let c = PointMotion::fixed(Point2::new(0.5, 0.0));
    let mut last_det = 1.0;
    let mut products = vec![];
    for delta in [1e-2, 1e-4, 1e-6, 1e-8] {
        let a = PointMotion::new(
            Point2::new(delta, 0.0),
            Vector2::new(-1.0, 0.0),
            Vector2::zeros(),
        );
        let d = rrr_dyad(a, c, 0.2, 0.3, Branch::Plus).unwrap();
        assert!(d.det.abs() < last_det);
        last_det = d.det.abs();
        assert!(d.link3.omega.is_finite());
        products.push(d.link3.omega * d.det);
    }
    assert!(last_det < 1e-3);
    let lim = products[products.len() - 1];
    for p in &products[1..] {
        assert!((p - lim).abs() <= 0.02 * lim.abs(), "{products:?}");
    }
}

#[test]
fn contour_unknowns_come_back_in_loop_order_whatever_the_order() {
    // The same line–circle loop written with the slide first and the link second: the
    // unknowns swap places, the geometry does not.
    let k = Vector2::new(-0.1, 0.05);
    let (a, beta) = (0.2, 0.3);
    let angle_first = [
        LoopVector::fixed(k),
        LoopVector::unknown_angle(a),
        LoopVector::unknown_length(Motion::new(beta, 2.0, -1.0)),
    ];
    let length_first = [
        LoopVector::fixed(k),
        LoopVector::unknown_length(Motion::new(beta, 2.0, -1.0)),
        LoopVector::unknown_angle(a),
    ];
    for branch in [Branch::Plus, Branch::Minus] {
        let p = solve_contour(&angle_first, branch).unwrap();
        let q = solve_contour(&length_first, branch).unwrap();
        for (x, y) in [
            (p.unknowns[0], q.unknowns[1]),
            (p.unknowns[1], q.unknowns[0]),
        ] {
            assert!((x.value - y.value).abs() <= 1e-15);
            assert!((x.rate - y.rate).abs() <= 1e-13);
            assert!((x.accel - y.accel).abs() <= 1e-12);
        }
        assert!((p.determinant + q.determinant).abs() <= 1e-15);
        // The branch: the link points forward (Plus) or backward (Minus) along the slide.
        let along = unit_of(p.unknowns[0].value).dot(&unit_of(beta));
        assert_eq!(along > 0.0, branch == Branch::Plus);
    }
    // Polar: Minus gives the same vector with a negative length and the opposite angle.
    let polar = [
        LoopVector::fixed(Vector2::new(0.3, -0.4)),
        LoopVector::unknown(),
    ];
    let p = solve_contour(&polar, Branch::Plus).unwrap().unknowns;
    let m = solve_contour(&polar, Branch::Minus).unwrap().unknowns;
    assert!((p[0].value - 0.5).abs() <= 1e-15 && (m[0].value + 0.5).abs() <= 1e-15);
    assert!((p[0].value * unit_of(p[1].value) - m[0].value * unit_of(m[1].value)).norm() <= 1e-15);
}

fn unit_of(angle: f64) -> Vector2<f64> {
    tmm::angle::unit(angle)
}

/// The extremes of s·sin(x + 0.3) are at x = π/2 − 0.3 (max) and 3π/2 − 0.3 (min) whatever the
/// scale s: a slope of 10⁻¹⁷⁰ changes sign as surely as one of 1 (a product of two such slopes
/// would underflow to zero and lose both extremes).
#[test]
fn extremes_do_not_depend_on_the_output_scale() {
    for s in [1.0, 1e-150, 1e-170, 1e-300, 1e150] {
        let e = extreme_positions(
            |x: f64| {
                let (sn, cs) = (x + 0.3).sin_cos();
                Ok(Motion::new(s * sn, s * cs, -s * sn))
            },
            360,
        )
        .unwrap();
        assert_eq!(e.len(), 2, "scale {s:e}: {e:?}");
        let max = e.iter().find(|x| x.kind == ExtremeKind::Max).unwrap();
        let min = e.iter().find(|x| x.kind == ExtremeKind::Min).unwrap();
        assert!(
            (max.input - (FRAC_PI_2 - 0.3)).abs() < 1e-12,
            "{s:e}: {max:?}"
        );
        assert!(
            (min.input - (3.0 * FRAC_PI_2 - 0.3)).abs() < 1e-12,
            "{s:e}: {min:?}"
        );
        assert!((max.output.value / s - 1.0).abs() < 1e-15, "{s:e}: {max:?}");
    }
}

/// Equally spaced angles from any finite start: 10¹⁷ rad or f64::MAX as well as 0.3 give n
/// distinct angles a step of 2π/n apart (the start's rounding used to swallow the steps).
#[test]
fn cycle_angles_from_a_huge_start_are_equally_spaced() {
    for start in [0.3, 1e17, f64::MAX, -f64::MAX] {
        let a = cycle_angles(4, start);
        assert_eq!(a.len(), 4);
        for k in 0..4 {
            let d = normalize(a[(k + 1) % 4] - a[k]);
            assert!((d - FRAC_PI_2).abs() < 1e-12, "{start:e}: {a:?}");
        }
    }
}
