//! The PRP and RPP dyad blocks: velocities and accelerations against eighth-order central
//! differences of the positions along smooth input motions (a crank turning with ε ≠ 0, guides
//! that translate and turn), loop closure, the composition of accelerations with the Coriolis
//! term on turning guides, a Scotch yoke's closed form around a cycle, and the errors.

use super::strategies;

use nalgebra::{Point2, Vector2};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use strategies::{along, close, fd, halves, point, point_motion};
use tmm::angle::{perp, unit};
use tmm::kinematics::{
    crank, prp_dyad, rpp_dyad, Guide, LinkMotion, Motion, PointMotion, SINGULAR_DETERMINANT,
};
use tmm::Error;

/// The finite-difference step for rates of about `rate` (see kinematics_props.rs).
fn step(rate: f64) -> f64 {
    1e-4 / (1.0 + rate)
}
/// The agreement required of velocities and accelerations, relative.
const TOL: f64 = 1e-8;

/// An angle between 0.3 and π − 0.3 rad, either sign: well away from parallel.
fn crossing() -> impl Strategy<Value = f64> {
    (0.3..(PI - 0.3), any::<bool>()).prop_map(|(d, neg)| if neg { -d } else { d })
}

/// A link turning about `o` with angle φ + ω·t + ε·t²/2 (a crank: its points move on circles,
/// a smooth non-polynomial motion).
fn turning(o: Point2<f64>, phi: f64, w: f64, e: f64, t: f64) -> LinkMotion {
    crank(
        o,
        1.0,
        Motion::new(phi + w * t + 0.5 * e * t * t, w + e * t, e),
    )
    .unwrap()
    .link
}

/// A link whose reference point moves with constant acceleration and whose angle turns with
/// constant angular acceleration.
fn moving(g: PointMotion, beta: f64, w: f64, e: f64, t: f64) -> LinkMotion {
    LinkMotion {
        origin: along(g, t),
        angle: beta + w * t + 0.5 * e * t * t,
        omega: w + e * t,
        epsilon: e,
    }
}

/// The guide of `link` through its material point at (`p_along`, `p_across`) in the link's
/// frame, at `offset` to the link's direction.
fn guide_of(link: &LinkMotion, p_along: f64, p_across: f64, offset: f64) -> Guide {
    Guide {
        point: link.point_at(p_along, p_across),
        angle: Motion::new(link.angle + offset, link.omega, link.epsilon),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// PRP: the slider 2 in a slot of a turning crank (offset from its centre line and at an
    /// angle to it), the slider 3 on a guide of a link that translates and turns.
    #[test]
    fn prp_motion_matches_finite_differences(
        o1 in point(), phi1 in 0.0..TAU, w1 in -3.0..3.0f64, e1 in -5.0..5.0f64,
        p_along in -1.0..1.0f64, p_across in -0.3..0.3f64, off in 0.0..TAU,
        g3 in point_motion(), w3 in -3.0..3.0f64, e3 in -5.0..5.0f64, d in crossing(),
    ) {
        let link1 = |t| turning(o1, phi1, w1, e1, t);
        // Link 4's guide crosses guide 2 at the angle d at t = 0.
        let beta3 = phi1 + off + d;
        let link4 = |t| moving(g3, beta3, w3, e3, t);
        let guides = |t| (guide_of(&link1(t), p_along, p_across, off), guide_of(&link4(t), 0.0, 0.0, 0.0));
        let (gd2, gd3) = guides(0.0);
        let k = prp_dyad(gd2, gd3).unwrap();
        // Loop closure on both guides, and the conditioning is the sine between them.
        prop_assert!((gd2.point.p + k.slide2.value * gd2.unit() - k.b.p).norm() <= 1e-12 * (1.0 + k.b.p.coords.norm()));
        prop_assert!((gd3.point.p + k.slide3.value * gd3.unit() - k.b.p).norm() <= 1e-12 * (1.0 + k.b.p.coords.norm()));
        prop_assert!((k.det - d.sin()).abs() <= 1e-12);
        let at = |t: f64| {
            let (a, b) = guides(t);
            let e = prp_dyad(a, b).unwrap();
            [e.b.p.x, e.b.p.y, e.slide2.value, e.slide3.value,
             e.b.v.x, e.b.v.y, e.slide2.rate, e.slide3.rate]
        };
        let reach = 2.0 + (k.b.p - o1).norm() + (k.b.p - g3.p).norm();
        let sv = (g3.v.norm() + (w1.abs() + w3.abs()) * reach) / d.sin().abs();
        let sa = (g3.a.norm() + (e1.abs() + e3.abs()) * reach) / d.sin().abs() + sv * sv;
        let (d1, d2) = halves(fd(at, step(sv)));
        close([k.b.v.x, k.b.v.y, k.slide2.rate, k.slide3.rate], d1, sv, TOL, "velocity");
        close([k.b.a.x, k.b.a.y, k.slide2.accel, k.slide3.accel], d2, sa, TOL, "acceleration");
        // B seen from each guide's link: transport + relative (+ Coriolis for accelerations).
        for (link, rel_v, rel_a, cor) in [
            (link1(0.0), k.relative_velocity2(), k.slide2.accel * gd2.unit(), k.coriolis2()),
            (link4(0.0), k.relative_velocity3(), k.slide3.accel * gd3.unit(), k.coriolis3()),
        ] {
            let carried = link.motion_of(k.b.p);
            prop_assert!((carried.v + rel_v - k.b.v).norm() <= 1e-12 * sv.max(1.0));
            prop_assert!((carried.a + rel_a + cor - k.b.a).norm() <= 1e-11 * sa.max(1.0));
        }
        // Each slider turns with its guide's link.
        prop_assert!(k.link2.omega == w1 && k.link3.omega == w3);
        prop_assert!(k.link2.epsilon == e1 && k.link3.epsilon == e3);
    }

    /// RPP: the hinge A on a crank turning with ε ≠ 0; link 4's guide translates and turns;
    /// the slide at the angle α to it.
    #[test]
    fn rpp_motion_matches_finite_differences(
        o1 in point(), l1 in 0.2..1.0f64, phi1 in 0.0..TAU, w1 in -3.0..3.0f64, e1 in -5.0..5.0f64,
        g in point_motion(), beta in 0.0..TAU, w4 in -3.0..3.0f64, e4 in -5.0..5.0f64,
        alpha in crossing(),
    ) {
        let pin = |t: f64| crank(o1, l1, Motion::new(phi1 + w1 * t + 0.5 * e1 * t * t, w1 + e1 * t, e1)).unwrap().a;
        let link4 = |t| moving(g, beta, w4, e4, t);
        let guide = |t| guide_of(&link4(t), 0.0, 0.0, 0.0);
        let a = pin(0.0);
        let k = rpp_dyad(a, guide(0.0), alpha).unwrap();
        let (u, v) = (unit(beta), unit(beta + alpha));
        // Loop closure: B on the guide, A on the slide's line through B.
        prop_assert!((g.p + k.slide3.value * u - k.b.p).norm() <= 1e-12 * (1.0 + k.b.p.coords.norm()));
        prop_assert!((k.b.p + k.slide2.value * v - a.p).norm() <= 1e-12 * (1.0 + a.p.coords.norm()));
        prop_assert!((k.det - alpha.sin()).abs() <= 1e-14);
        let at = |t: f64| {
            let e = rpp_dyad(pin(t), guide(t), alpha).unwrap();
            [e.b.p.x, e.b.p.y, e.slide2.value, e.slide3.value,
             e.b.v.x, e.b.v.y, e.slide2.rate, e.slide3.rate]
        };
        let reach = 2.0 + (k.b.p - g.p).norm() + (a.p - k.b.p).norm();
        let sv = (l1 * w1.abs() + g.v.norm() + w4.abs() * reach) / alpha.sin().abs();
        let sa = (l1 * (e1.abs() + w1 * w1) + g.a.norm() + e4.abs() * reach) / alpha.sin().abs() + sv * sv;
        let (d1, d2) = halves(fd(at, step(sv)));
        close([k.b.v.x, k.b.v.y, k.slide2.rate, k.slide3.rate], d1, sv, TOL, "velocity");
        close([k.b.a.x, k.b.a.y, k.slide2.accel, k.slide3.accel], d2, sa, TOL, "acceleration");
        // A (given) is recovered as link 3's point at A plus the sliding of link 2 in link 3,
        // with the Coriolis term of sliding in the turning link 3.
        let a3 = k.link3.motion_of(a.p);
        prop_assert!((a3.v + k.relative_velocity2() - a.v).norm() <= 1e-12 * sv.max(1.0));
        prop_assert!((a3.a + k.slide2.accel * v + k.coriolis2() - a.a).norm() <= 1e-11 * sa.max(1.0));
        // B is link 4's point at B plus the sliding along the guide.
        let b4 = link4(0.0).motion_of(k.b.p);
        prop_assert!((b4.v + k.relative_velocity3() - k.b.v).norm() <= 1e-12 * sv.max(1.0));
        prop_assert!((b4.a + k.slide3.accel * u + k.coriolis3() - k.b.a).norm() <= 1e-11 * sa.max(1.0));
        // Links 2 and 3 turn with link 4; link 2 is the slide's direction.
        prop_assert!(k.link2.omega == w4 && k.link3.omega == w4 && k.link2.epsilon == e4);
        prop_assert!((k.link2.unit() - v).norm() <= 1e-14);
    }
}

#[test]
fn slot_turning_about_the_origin_shows_its_coriolis_term() {
    // A slot through the origin turning at ω (ε = 0), at θ = 30°, drives a slider 3 on the
    // fixed vertical guide x = c. B = (c, c·tan θ): ẏ = c·ω·sec²θ and ÿ = 2·c·ω²·sec²θ·tan θ;
    // along the slot s2 = c·sec θ, ṡ2 = c·ω·sec θ·tan θ.
    let (c, w, theta) = (0.4, 5.0, 30f64.to_radians());
    let slot = Guide {
        point: PointMotion::fixed(Point2::origin()),
        angle: Motion::new(theta, w, 0.0),
    };
    let k = prp_dyad(slot, Guide::fixed(Point2::new(c, -1.0), FRAC_PI_2)).unwrap();
    let sec = 1.0 / theta.cos();
    let tol = 1e-13;
    assert!((k.b.p - Point2::new(c, c * theta.tan())).norm() <= tol);
    assert!((k.b.v - Vector2::new(0.0, c * w * sec * sec)).norm() <= tol);
    let ay = 2.0 * c * w * w * sec * sec * theta.tan();
    assert!((k.b.a - Vector2::new(0.0, ay)).norm() <= tol * ay);
    assert!((k.slide2.value - c * sec).abs() <= tol);
    assert!((k.slide2.rate - c * w * sec * theta.tan()).abs() <= tol);
    // The slide on the fixed guide: s3 measured from (c, −1).
    assert!((k.slide3.value - (1.0 + c * theta.tan())).abs() <= tol);
    assert!((k.slide3.rate - c * w * sec * sec).abs() <= tol);
    // The Coriolis term is 2·ω·ṡ2 across the slot, and it matters: without it the composed
    // acceleration is off by its whole size.
    let cor = k.coriolis2();
    let expected = 2.0 * w * k.slide2.rate * perp(unit(theta));
    assert!((cor - expected).norm() <= tol * cor.norm());
    assert!(cor.norm() > 0.3 * ay);
    let transport = -w * w * k.b.p.coords; // the slot's point at B, turning about O
    assert!((transport + k.slide2.accel * unit(theta) + cor - k.b.a).norm() <= tol * ay);
    assert!((transport + k.slide2.accel * unit(theta) - k.b.a).norm() > 0.3 * ay);
    // The fixed guide adds no Coriolis term.
    assert_eq!(k.coriolis3(), Vector2::zeros());
}

#[test]
fn scotch_yoke_follows_its_closed_form_around_a_cycle() {
    // Crank r = 0.12 m at ω = 7 rad/s, ε = 3 rad/s²; the yoke slides along x, its slot at
    // α = 90°: s3 = r·cos φ, ṡ3 = −r·ω·sin φ, s̈3 = −r·ω²·cos φ − r·ε·sin φ; s2 = r·sin φ.
    let (r, w, e) = (0.12, 7.0, 3.0);
    let guide = Guide::fixed(Point2::origin(), 0.0);
    for i in 0..360 {
        let phi = f64::from(i).to_radians();
        let a = crank(Point2::origin(), r, Motion::new(phi, w, e))
            .unwrap()
            .a;
        let k = rpp_dyad(a, guide, FRAC_PI_2).unwrap();
        let (s, c) = phi.sin_cos();
        let want = [
            r * c,
            -r * w * s,
            -r * w * w * c - r * e * s,
            r * s,
            r * w * c,
            -r * w * w * s + r * e * c,
        ];
        let got = [
            k.slide3.value,
            k.slide3.rate,
            k.slide3.accel,
            k.slide2.value,
            k.slide2.rate,
            k.slide2.accel,
        ];
        for (g, x) in got.iter().zip(want) {
            assert!((g - x).abs() <= 1e-13, "φ = {i}°: {got:?} vs {want:?}");
        }
        // The yoke translates: B moves along x with ṡ3.
        assert_eq!(k.b.v.y, 0.0);
        assert!((k.b.v.x - k.slide3.rate).abs() <= 1e-15);
    }
    // A slot inclined at 60° makes the yoke move by the pin's x minus y·cot 60°.
    let a = crank(Point2::origin(), r, Motion::new(1.0, w, 0.0))
        .unwrap()
        .a;
    let k = rpp_dyad(a, guide, 60f64.to_radians()).unwrap();
    let cot = 1.0 / 60f64.to_radians().tan();
    assert!((k.slide3.value - (a.p.x - a.p.y * cot)).abs() <= 1e-14);
    assert!((k.slide3.rate - (a.v.x - a.v.y * cot)).abs() <= 1e-13);
    assert!((k.slide3.accel - (a.a.x - a.a.y * cot)).abs() <= 1e-12);
}

#[test]
fn parallel_slides_are_singular_and_near_them_rates_grow_like_one_over_det() {
    let a = PointMotion::new(
        Point2::new(0.1, 0.2),
        Vector2::new(1.0, -0.5),
        Vector2::zeros(),
    );
    let g = Guide::fixed(Point2::origin(), 0.3);
    for alpha in [0.0, PI, -PI, 1e-13, PI + 1e-13] {
        let e = rpp_dyad(a, g, alpha).unwrap_err();
        assert!(
            matches!(e, Error::Singular { what: "RPP dyad", measure: "sin(alpha)", value } if value.abs() <= SINGULAR_DETERMINANT),
            "{e}"
        );
    }
    // A guide that translates without turning (a turning one would also swing the far-away
    // crossing point, and its rates would grow like 1/det²).
    let moving = Guide {
        point: a,
        angle: Motion::fixed(0.7),
    };
    for other in [0.7, 0.7 + PI, 0.7 - 1e-13] {
        let e = prp_dyad(moving, Guide::fixed(Point2::new(0.0, 1.0), other)).unwrap_err();
        assert!(
            matches!(e, Error::Singular { what: "PRP dyad", measure: "sin(phi_g3 - phi_g2)", value } if value.abs() <= SINGULAR_DETERMINANT),
            "{e}"
        );
    }
    // Near parallel guides the slide rates grow like 1/det: rate·det tends to a limit.
    let mut products = vec![];
    for delta in [1e-3, 1e-5, 1e-7, 1e-9] {
        let k = prp_dyad(moving, Guide::fixed(Point2::new(0.0, 1.0), 0.7 + delta)).unwrap();
        assert!((k.det - delta.sin()).abs() <= 1e-15);
        products.push(k.slide3.rate * k.det);
    }
    let lim = products[3];
    assert!(lim.abs() > 0.1, "{products:?}");
    for p in &products {
        assert!((p - lim).abs() <= 0.01 * lim.abs(), "{products:?}");
    }
}

#[test]
fn bad_numbers_and_overflow_are_errors_never_nans() {
    let a = PointMotion::fixed(Point2::new(0.1, 0.2));
    let g = Guide::fixed(Point2::origin(), 0.0);
    assert!(matches!(
        rpp_dyad(a, g, f64::NAN),
        Err(Error::NonFinite { name: "alpha", .. })
    ));
    let mut bad = g;
    bad.angle.rate = f64::INFINITY;
    assert!(matches!(
        rpp_dyad(a, bad, 1.0),
        Err(Error::NonFinite {
            name: "omega_g",
            ..
        })
    ));
    assert!(matches!(
        prp_dyad(bad, g),
        Err(Error::NonFinite {
            name: "omega_g2",
            ..
        })
    ));
    assert!(matches!(
        prp_dyad(g, bad),
        Err(Error::NonFinite {
            name: "omega_g3",
            ..
        })
    ));
    let mut bad_a = a;
    bad_a.a.y = f64::NAN;
    assert!(matches!(
        rpp_dyad(bad_a, g, 1.0),
        Err(Error::NonFinite { name: "a_A.y", .. })
    ));
    // Finite inputs whose result overflows: guides 1e300 m apart crossing at 1e-10 rad.
    let far = Guide::fixed(Point2::new(0.0, 1e300), 1e-10);
    assert!(matches!(
        prp_dyad(g, far),
        Err(Error::NonFinite { .. } | Error::Overflow { .. })
    ));
    // A guide turning so fast that ω²·s overflows.
    let spin = Guide {
        point: PointMotion::fixed(Point2::origin()),
        angle: Motion::new(0.0, 1e200, 0.0),
    };
    let pin = PointMotion::fixed(Point2::new(1e120, 1.0));
    assert!(matches!(
        rpp_dyad(pin, spin, FRAC_PI_2),
        Err(Error::NonFinite { .. } | Error::Overflow { .. })
    ));
}
