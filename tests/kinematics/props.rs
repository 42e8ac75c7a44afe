//! Property tests of the kinematic blocks on random well-conditioned mechanisms: velocities
//! and accelerations against eighth-order finite differences of the positions (1e-8
//! relative; the accelerations against differences of the solver's velocities, which were
//! checked against the positions), loop closure, transfer functions, and the two assembly modes.

use super::strategies;

use nalgebra::{Point2, Vector2};
use proptest::prelude::*;
use std::f64::consts::PI;
use strategies::{along, angle_diff, close, fd, halves, point, point_motion, vector};
use tmm::angle::{cross, unit};
use tmm::kinematics::{
    contour_residual, crank, rpr_dyad, rrp_dyad, rrr_dyad, solve_contour, Branch, Guide,
    LoopVector, Motion, Part, PointMotion,
};

/// The time step of the finite differences (s) for a motion whose rates are about `rate`
/// (1/s): 1e-4 of its time scale. Truncation then stays near (1e-4)^8 even where the
/// motion's higher derivatives are a hundred times steeper than `rate` suggests (near a
/// lock), and rounding near ε·10⁴ relative.
fn step(rate: f64) -> f64 {
    1e-4 / (1.0 + rate)
}
/// The agreement required of velocities and accelerations, relative.
const TOL: f64 = 1e-8;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// RRR with both outer joints moving: B, φ2, φ3 and a coupler point S against finite
    /// differences in time.
    #[test]
    fn rrr_motion_matches_finite_differences(
        a in point_motion(), c in point_motion(), b in point(),
        s_along in -0.5..1.5f64, s_across in -0.3..0.3f64,
    ) {
        let (l2, l3) = ((b - a.p).norm(), (b - c.p).norm());
        prop_assume!(l2 > 0.3 && l3 > 0.3);
        let sin = cross(b - a.p, b - c.p) / (l2 * l3);
        prop_assume!(sin.abs() > 0.3);
        let branch = if cross(c.p - a.p, b - a.p) > 0.0 { Branch::Plus } else { Branch::Minus };
        let d = rrr_dyad(a, c, l2, l3, branch).unwrap();
        // Position: the generating B is recovered, and the conditioning is sin(φ3 − φ2).
        prop_assert!((d.b.p - b).norm() <= 1e-12);
        prop_assert!((d.det - sin).abs() <= 1e-12);
        prop_assert!((d.det - (d.link3.angle - d.link2.angle).sin()).abs() <= 1e-12);
        let s = d.link2.point_at(s_along * l2, s_across);
        let at = |t: f64| {
            let e = rrr_dyad(along(a, t), along(c, t), l2, l3, branch).unwrap();
            let st = e.link2.point_at(s_along * l2, s_across);
            [e.b.p.x, e.b.p.y, angle_diff(e.link2.angle, d.link2.angle),
             angle_diff(e.link3.angle, d.link3.angle), st.p.x, st.p.y,
             e.b.v.x, e.b.v.y, e.link2.omega, e.link3.omega, st.v.x, st.v.y]
        };
        let lmin = l2.min(l3);
        let sv = (a.v.norm() + c.v.norm()) / lmin;
        let sa = (a.a.norm() + c.a.norm()) / lmin + sv * sv;
        let (d1, d2) = halves(fd(at, step(sv)));
        close([d.b.v.x, d.b.v.y, d.link2.omega, d.link3.omega, s.v.x, s.v.y], d1, sv, TOL, "velocity");
        close([d.b.a.x, d.b.a.y, d.link2.epsilon, d.link3.epsilon, s.a.x, s.a.y], d2, sa, TOL, "acceleration");
        // B as a point of link 3 moves the same way (the joint is shared).
        let b3 = d.link3.motion_of(d.b.p);
        prop_assert!((b3.v - d.b.v).norm() <= 1e-12 * sv.max(1.0));
        prop_assert!((b3.a - d.b.a).norm() <= 1e-11 * sa.max(1.0));
    }

    /// RRP on a moving, rotating guide (a slotted link): the slider's absolute acceleration
    /// carries the Coriolis term 2·ω4·ṡ, and everything matches finite differences.
    #[test]
    fn rrp_on_a_rotating_guide_matches_finite_differences(
        a in point_motion(), g in point_motion(), beta in 0.0..(2.0 * PI),
        w4 in -3.0..3.0f64, e4 in -5.0..5.0f64, s0 in -1.0..1.0f64,
    ) {
        let u = unit(beta);
        let b = g.p + s0 * u;
        let l2 = (b - a.p).norm();
        prop_assume!(l2 > 0.3);
        let cos = (b - a.p).dot(&u) / l2;
        prop_assume!(cos.abs() > 0.3);
        let branch = if cos >= 0.0 { Branch::Plus } else { Branch::Minus };
        let guide_at = |t: f64| Guide {
            point: along(g, t),
            angle: Motion::new(beta + w4 * t + 0.5 * e4 * t * t, w4 + e4 * t, e4),
        };
        let d = rrp_dyad(a, guide_at(0.0), l2, branch).unwrap();
        prop_assert!((d.b.p - b).norm() <= 1e-12);
        prop_assert!((d.slide.value - s0).abs() <= 1e-12);
        prop_assert!((d.det - cos).abs() <= 1e-12);
        let at = |t: f64| {
            let e = rrp_dyad(along(a, t), guide_at(t), l2, branch).unwrap();
            [e.b.p.x, e.b.p.y, angle_diff(e.link2.angle, d.link2.angle), e.slide.value,
             e.b.v.x, e.b.v.y, e.link2.omega, e.slide.rate]
        };
        let sv = (a.v.norm() + g.v.norm()) / 0.3 + w4.abs() * 2.0;
        let sa = (a.a.norm() + g.a.norm()) / 0.3 + e4.abs() * 2.0 + sv * sv;
        let (d1, d2) = halves(fd(at, step(sv)));
        close([d.b.v.x, d.b.v.y, d.link2.omega, d.slide.rate], d1, sv, TOL, "velocity");
        close([d.b.a.x, d.b.a.y, d.link2.epsilon, d.slide.accel], d2, sa, TOL, "acceleration");
        // The same acceleration composed on the guide: transport + relative + Coriolis.
        let r = d.b.p - g.p;
        let transport = g.a + e4 * tmm::angle::perp(r) - w4 * w4 * r;
        let composed = transport + d.slide.accel * u + 2.0 * w4 * d.slide.rate * tmm::angle::perp(u);
        prop_assert!((composed - d.b.a).norm() <= 1e-10 * sa.max(1.0));
    }

    /// RPR with both hinges moving: the axis angle, the sliding length and a point of the
    /// cylinder against finite differences.
    #[test]
    fn rpr_motion_matches_finite_differences(a in point_motion(), c in point_motion(), q in 0.0..1.0f64) {
        prop_assume!((a.p - c.p).norm() > 0.3);
        let d = rpr_dyad(a, c).unwrap();
        prop_assert!((a.p + d.slide.value * d.link2.unit() - c.p).norm() <= 1e-12);
        let q = q * d.slide.value; // a point of the cylinder: fixed along it
        let at = |t: f64| {
            let e = rpr_dyad(along(a, t), along(c, t)).unwrap();
            let p = e.link3.point_at(q, 0.1);
            [angle_diff(e.link2.angle, d.link2.angle), e.slide.value, p.p.x, p.p.y,
             e.link2.omega, e.slide.rate, p.v.x, p.v.y]
        };
        let p = d.link3.point_at(q, 0.1);
        let sv = (a.v.norm() + c.v.norm()) / 0.3;
        let sa = (a.a.norm() + c.a.norm()) / 0.3 + sv * sv;
        let (d1, d2) = halves(fd(at, step(sv)));
        close([d.link2.omega, d.slide.rate, p.v.x, p.v.y], d1, sv, TOL, "velocity");
        close([d.link2.epsilon, d.slide.accel, p.a.x, p.a.y], d2, sa, TOL, "acceleration");
        // The rod's hinge A, seen as a point of the cylinder plus the sliding: v_A = v_A3 + v_rel.
        let a3 = d.link3.motion_of(a.p);
        prop_assert!((a3.v + d.relative_velocity() - a.v).norm() <= 1e-12 * sv.max(1.0));
        prop_assert!(
            (a3.a + d.relative_acceleration() + d.coriolis() - a.a).norm() <= 1e-11 * sa.max(1.0)
        );
    }

    /// A four-bar's transfer functions against finite differences in the input angle, and
    /// ω = φ′·ω1, ε = φ″·ω1² + φ′·ε1 against a direct solve at (ω1, ε1).
    #[test]
    fn four_bar_transfer_functions(
        c in point(), l1 in 0.2..0.6f64, b in point(), phi in 0.0..(2.0 * PI),
        w1 in -50.0..50.0f64, e1 in -500.0..500.0f64,
    ) {
        let o = Point2::origin();
        let a0 = o + l1 * unit(phi);
        let (l2, l3) = ((b - a0).norm(), (b - c).norm());
        prop_assume!(l2 > 0.3 && l3 > 0.3 && (c - o).norm() > 0.2);
        prop_assume!((cross(b - a0, b - c) / (l2 * l3)).abs() > 0.3);
        let branch = if cross(c - a0, b - a0) > 0.0 { Branch::Plus } else { Branch::Minus };
        let cm = PointMotion::fixed(c);
        let chain = |m: Motion| -> tmm::Result<_> {
            let a = crank(o, l1, m)?.a;
            rrr_dyad(a, cm, l2, l3, branch)
        };
        let t = chain(Motion::unit_speed(phi)).unwrap();
        let at = |x: f64| {
            let e = chain(Motion::unit_speed(phi + x)).unwrap();
            [angle_diff(e.link3.angle, t.link3.angle), angle_diff(e.link2.angle, t.link2.angle), e.b.p.x, e.b.p.y,
             e.link3.omega, e.link2.omega, e.b.v.x, e.b.v.y]
        };
        // The scale of the first transfer functions (dimensionless; lengths are of unit size).
        let sv = t.link2.omega.abs().max(t.link3.omega.abs()).max(t.b.v.norm()).max(1.0);
        let (d1, d2) = halves(fd(at, step(sv)));
        close([t.link3.omega, t.link2.omega, t.b.v.x, t.b.v.y], d1, sv, TOL, "first transfer function");
        close([t.link3.epsilon, t.link2.epsilon, t.b.a.x, t.b.a.y], d2, sv * sv, TOL, "second transfer function");
        let real = chain(Motion::new(phi, w1, e1)).unwrap();
        let from_transfer = t.link3.angle_motion().at_input_speed(w1, e1);
        let scale = w1 * w1 + e1.abs() + w1.abs();
        prop_assert!((real.link3.omega - from_transfer.rate).abs() <= 1e-12 * scale);
        prop_assert!((real.link3.epsilon - from_transfer.accel).abs() <= 1e-12 * scale);
    }

    /// Both assembly modes close the loop to 1e-12 of the mechanism's size, and they are
    /// mirror images about the line A C.
    #[test]
    fn rrr_branches_are_mirror_images(a in point(), c in point(), l2 in 0.2..2.0f64, l3 in 0.2..2.0f64) {
        let (pa, pc) = (PointMotion::fixed(a), PointMotion::fixed(c));
        let plus = rrr_dyad(pa, pc, l2, l3, Branch::Plus);
        let minus = rrr_dyad(pa, pc, l2, l3, Branch::Minus);
        let dist = (c - a).norm();
        if dist > l2 + l3 || dist < (l2 - l3).abs() {
            let gap = (dist - l2 - l3).max((l2 - l3).abs() - dist);
            match plus {
                Err(tmm::Error::NotAssemblable { group, gap: g }) => {
                    prop_assert_eq!(group, "RRR dyad");
                    prop_assert!((g - gap).abs() <= 1e-12);
                }
                // Within rounding of the tangent position the dyad is singular instead.
                Err(tmm::Error::Singular { .. }) => prop_assert!(gap <= 1e-12),
                other => prop_assert!(false, "expected an error, got {:?}", other),
            }
            return Ok(());
        }
        let (Ok(p), Ok(m)) = (plus, minus) else { return Ok(()) };
        let size = dist + l2 + l3;
        for d in [&p, &m] {
            prop_assert!(((d.b.p - a).norm() - l2).abs() <= 1e-12 * size);
            prop_assert!(((d.b.p - c).norm() - l3).abs() <= 1e-12 * size);
        }
        prop_assert!(cross(c - a, p.b.p - a) >= 0.0 && cross(c - a, m.b.p - a) <= 0.0);
        // Reflect the Minus solution across the line A C.
        let e = (c - a) / dist;
        let r = m.b.p - a;
        let mirrored = a + 2.0 * r.dot(&e) * e - r;
        prop_assert!((mirrored - p.b.p).norm() <= 1e-11 * size);
        prop_assert!((p.det + m.det).abs() <= 1e-11);
    }

    /// The two-length contour (two slides, as in a PRP group) against finite differences.
    #[test]
    fn two_slide_contour_matches_finite_differences(
        k in vector(1.0), kv in vector(2.0), ka in vector(4.0),
        b1 in 0.0..(2.0 * PI), db in 0.5..(PI - 0.5), w in -3.0..3.0f64, e in -5.0..5.0f64,
    ) {
        let make = |t: f64| [
            LoopVector::Cartesian { r: k + kv * t + 0.5 * ka * t * t, v: kv + ka * t, a: ka },
            LoopVector::unknown_length(Motion::new(b1 + w * t + 0.5 * e * t * t, w + e * t, e)),
            LoopVector::unknown_length(Motion::fixed(b1 + db)),
        ];
        let s = solve_contour(&make(0.0), Branch::Plus).unwrap();
        let x = [s.unknowns[0].value, s.unknowns[1].value];
        prop_assert!(contour_residual(&make(0.0), x).unwrap().norm() <= 1e-12 * (1.0 + k.norm()));
        let at = |t: f64| {
            let u = solve_contour(&make(t), Branch::Plus).unwrap().unknowns;
            [u[0].value, u[1].value, u[0].rate, u[1].rate]
        };
        let sv = (kv.norm() + w.abs() * 3.0) / db.sin();
        let sa = (ka.norm() + e.abs() * 3.0) / db.sin() + sv * sv;
        let (d1, d2) = halves(fd(at, step(sv)));
        close([s.unknowns[0].rate, s.unknowns[1].rate], d1, sv, TOL, "rates");
        close([s.unknowns[0].accel, s.unknowns[1].accel], d2, sa, TOL, "accelerations");
    }

    /// The line–circle contour written directly: residual and the branch's meaning.
    #[test]
    fn line_circle_contour_closes(k in vector(1.0), a in 0.2..1.5f64, beta in 0.0..(2.0 * PI)) {
        let loop_ = [
            LoopVector::fixed(k),
            LoopVector::unknown_angle(a),
            LoopVector::Polar { length: Part::Unknown, angle: Part::Known(Motion::fixed(beta)) },
        ];
        for branch in [Branch::Plus, Branch::Minus] {
            match solve_contour(&loop_, branch) {
                Ok(s) => {
                    let x = [s.unknowns[0].value, s.unknowns[1].value];
                    prop_assert!(contour_residual(&loop_, x).unwrap().norm() <= 1e-12 * (1.0 + k.norm() + a));
                    let along_beta = (a * unit(x[0])).dot(&unit(beta));
                    prop_assert!(along_beta * branch.sign() >= -1e-12);
                }
                Err(tmm::Error::NotAssemblable { gap, .. }) => {
                    let q = tmm::angle::perp(unit(beta)).dot(&(-k));
                    prop_assert!((gap - (q.abs() - a)).abs() <= 1e-12);
                }
                Err(tmm::Error::Singular { value, .. }) => prop_assert!(value.abs() <= 1e-6),
                Err(other) => prop_assert!(false, "unexpected {:?}", other),
            }
        }
    }
}

#[test]
fn slider_velocity_direction_sanity() {
    // A fixed guide along +y through the origin, the pin A moving along +x at 1 m/s from
    // (−0.1, 0): B is dragged along the guide with AB·(v_B − v_A) = 0, so ṡ = (AB·x̂)/(AB·ŷ)·v_A.x.
    let a = PointMotion::new(
        Point2::new(-0.1, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::zeros(),
    );
    let d = rrp_dyad(
        a,
        Guide::fixed(Point2::origin(), 0.5 * PI),
        0.2,
        Branch::Plus,
    )
    .unwrap();
    let ab = d.b.p - a.p;
    assert!((d.slide.rate - ab.x / ab.y).abs() <= 1e-14);
}
