//! The dyads with two sliding pairs, PRP and RPP: against the general LU solve of their full
//! Newton–Euler systems, every link's equilibrium, the guides' reactions normal to the guides
//! and placed where their moments say, near and at their singularities, and the principle of
//! virtual power in a slotted-crank cross-slide and a Scotch yoke.

use super::general_solve;
use super::strategies::*;
use super::{cfg, is_singular, max_diff, power, residual, scale, PER_CONDITION, TIGHT};
use nalgebra::{Point2, Vector2};
use proptest::prelude::*;
use std::f64::consts::PI;
use tmm::angle::{perp, unit};
use tmm::kinematics::{crank, prp_dyad, rpp_dyad, Guide, Motion};
use tmm::kinetostatics::{CouplingDrive, PrpDyad, RppDyad};
use tmm::{Error, Load};

/// The line of action of a normal force `force` whose moment about `pole` is `moment`, placed
/// at `pole + h·dir`: its moment about the pole must be `moment` again.
fn offset_is_consistent(
    offset: Option<f64>,
    pole: Point2<f64>,
    dir: Vector2<f64>,
    force: Vector2<f64>,
    moment: f64,
    s: f64,
    len: f64,
) -> Result<(), TestCaseError> {
    match offset {
        Some(h) => {
            let at = pole + dir.normalize() * h;
            let k = Load::force_at(at, force).moment_about(pole);
            prop_assert!(
                (k - moment).abs() <= 1e-9 * s * len,
                "offset {h} gives {k}, not {moment}"
            );
        }
        // No offset only when there is no force to place: a pure couple.
        None => prop_assert!(force.norm() <= TIGHT * s, "no offset for {force:?}"),
    }
    Ok(())
}

// ----- PRP -----

fn prp_case(b: Point2<f64>, phi2: f64, d: f64, g2: RawLoad, g3: RawLoad) -> PrpDyad {
    PrpDyad {
        b,
        guide2: unit(phi2) * 0.7,
        guide3: unit(phi2 + d) * 1.3,
        load2: g2.at(b, 0.5),
        load3: g3.at(b, 0.3),
    }
}

/// (error against LU, largest equilibrium residual, condition), all relative to the largest
/// force (moments to the largest force times the size of the group).
fn prp_check(d: &PrpDyad) -> Result<(f64, f64, f64), TestCaseError> {
    let r = d.solve().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let (g, k12, k43) = general_solve::prp(d.b, d.guide2, d.guide3, &d.load2, &d.load3);
    let s = scale(&[d.load2.force, d.load3.force, r.r12, r.r43, r.r23]);
    let len = [d.load2.point, d.load3.point]
        .iter()
        .map(|p| (p - d.b).norm())
        .fold(1.0, f64::max);
    let err = (max_diff(&[r.r12, r.r43, r.r23], &g) / s)
        .max((r.moment12 - k12).abs() / (s * len))
        .max((r.moment43 - k43).abs() / (s * len));
    // Each guide pushes along its normal only.
    prop_assert!(r.r12.dot(&d.guide2).abs() <= TIGHT * s * d.guide2.norm());
    prop_assert!(r.r43.dot(&d.guide3).abs() <= TIGHT * s * d.guide3.norm());
    prop_assert!((r.r12 - perp(d.guide2.normalize()) * r.r12_n).norm() <= TIGHT * s);
    prop_assert!((r.r43 - perp(d.guide3.normalize()) * r.r43_n).norm() <= TIGHT * s);
    offset_is_consistent(r.offset12, d.b, d.guide2, r.r12, r.moment12, s, len)?;
    offset_is_consistent(r.offset43, d.b, d.guide3, r.r43, r.moment43, s, len)?;
    let res2 = residual(
        &[
            d.load2,
            Load::new(d.b, r.r12, r.moment12),
            Load::force_at(d.b, -r.r23),
        ],
        s,
        len,
    );
    let res3 = residual(
        &[
            d.load3,
            Load::new(d.b, r.r43, r.moment43),
            Load::force_at(d.b, r.r23),
        ],
        s,
        len,
    );
    Ok((err, res2.max(res3), r.conditioning.condition))
}

proptest! {
    #![proptest_config(cfg(3000))]
    #[test]
    fn prp_agrees_with_the_general_solve(
        b in point(), phi2 in direction(), d in well_shaped_angle(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let dyad = prp_case(b, phi2, d, g2, g3);
        let (err, res, cond) = prp_check(&dyad)?;
        prop_assert!(err <= TIGHT, "error {err:e}");
        prop_assert!(res <= TIGHT, "residual {res:e}");
        // The conditioning is the sine between the guides.
        prop_assert!((cond - 1.0 / d.sin().abs()).abs() <= 1e-12 * cond);
    }
}

proptest! {
    #![proptest_config(cfg(2000))]
    #[test]
    fn prp_near_parallel_guides_errs_or_reports_its_conditioning(
        b in point(), phi2 in direction(), tiny in tiny_angle(), flip in any::<bool>(),
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let d = prp_case(b, phi2, tiny + if flip { PI } else { 0.0 }, g2, g3);
        match d.solve() {
            Err(e) => prop_assert!(is_singular(&e, "sin(phi_g3 - phi_g2)"), "{e}"),
            Ok(_) => {
                let (err, _, cond) = prp_check(&d)?;
                prop_assert!(err <= cond * PER_CONDITION, "error {err:e} > {cond:e} x 1e-14");
            }
        }
    }
}

// ----- RPP -----

/// A guide along φ, the slide at α to it, A at `t` along the slide from B.
fn rpp_case(a: Point2<f64>, phi: f64, alpha: f64, t: f64, g2: RawLoad, g3: RawLoad) -> RppDyad {
    let (u, v) = (unit(phi), unit(phi + alpha));
    let b = a - v * t;
    RppDyad {
        a,
        b,
        guide: u * 0.6,
        slot: v * 1.7,
        load2: g2.at(a, 0.3),
        load3: g3.at(b, 0.5),
    }
}

fn rpp_check(d: &RppDyad) -> Result<(f64, f64, f64), TestCaseError> {
    let r = d.solve().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let (g, k32, k43) = general_solve::rpp(d.a, d.b, d.guide, d.slot, &d.load2, &d.load3);
    let s = scale(&[d.load2.force, d.load3.force, r.r12, r.r32, r.r43]);
    let len = [d.a, d.load2.point, d.load3.point]
        .iter()
        .map(|p| (p - d.b).norm())
        .fold(1.0, f64::max);
    let err = (max_diff(&[r.r12, r.r32, r.r43], &g) / s)
        .max((r.moment32 - k32).abs() / (s * len))
        .max((r.moment43 - k43).abs() / (s * len));
    prop_assert!(r.r32.dot(&d.slot).abs() <= TIGHT * s * d.slot.norm());
    prop_assert!(r.r43.dot(&d.guide).abs() <= TIGHT * s * d.guide.norm());
    prop_assert!((r.r32 - perp(d.slot.normalize()) * r.r32_n).norm() <= TIGHT * s);
    prop_assert!((r.r43 - perp(d.guide.normalize()) * r.r43_n).norm() <= TIGHT * s);
    offset_is_consistent(r.offset32, d.a, d.slot, r.r32, r.moment32, s, len)?;
    offset_is_consistent(r.offset43, d.b, d.guide, r.r43, r.moment43, s, len)?;
    let res2 = residual(
        &[
            d.load2,
            Load::force_at(d.a, r.r12),
            Load::new(d.a, r.r32, r.moment32),
        ],
        s,
        len,
    );
    let res3 = residual(
        &[
            d.load3,
            Load::new(d.b, r.r43, r.moment43),
            Load::new(d.a, -r.r32, -r.moment32),
        ],
        s,
        len,
    );
    Ok((err, res2.max(res3), r.conditioning.condition))
}

proptest! {
    #![proptest_config(cfg(3000))]
    #[test]
    fn rpp_agrees_with_the_general_solve(
        a in point(), phi in direction(), alpha in well_shaped_angle(), t in -1.5..1.5f64,
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let dyad = rpp_case(a, phi, alpha, t, g2, g3);
        let (err, res, cond) = rpp_check(&dyad)?;
        prop_assert!(err <= TIGHT, "error {err:e}");
        prop_assert!(res <= TIGHT, "residual {res:e}");
        prop_assert!((cond - 1.0 / alpha.sin().abs()).abs() <= 1e-12 * cond);
    }
}

proptest! {
    #![proptest_config(cfg(2000))]
    #[test]
    fn rpp_near_a_slide_parallel_to_the_guide_errs_or_reports_its_conditioning(
        a in point(), phi in direction(), tiny in tiny_angle(), flip in any::<bool>(),
        t in -1.5..1.5f64, g2 in raw_load(), g3 in raw_load(),
    ) {
        let d = rpp_case(a, phi, tiny + if flip { PI } else { 0.0 }, t, g2, g3);
        match d.solve() {
            Err(e) => prop_assert!(is_singular(&e, "sin(alpha)"), "{e}"),
            Ok(_) => {
                let (err, _, cond) = rpp_check(&d)?;
                prop_assert!(err <= cond * PER_CONDITION, "error {err:e} > {cond:e} x 1e-14");
            }
        }
    }
}

// ----- Whole mechanisms: the principle of virtual power -----

proptest! {
    #![proptest_config(cfg(1000))]
    /// A slotted crank drives a cross-slide: the crank's slot (at `delta` to the crank, off
    /// its centre line by `e`) carries the slider 2, hinged at B to the slider 3 on a fixed
    /// guide. The balancing moment on the crank from the group's reactions must make the
    /// total power of all loads zero, with the velocities from the kinematic block.
    #[test]
    fn slotted_crank_cross_slide_balances_by_virtual_power(
        phi1 in direction(), w1 in 1.0..100.0f64, delta in direction(), e in -0.2..0.2f64,
        gp in point(), d in well_shaped_angle(), g1 in raw_load(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let o1 = Point2::origin();
        let c = crank(o1, 0.3, Motion::new(phi1, w1, 0.0)).unwrap().link;
        let slot = Guide::on_link(&c, o1 + perp(unit(phi1 + delta)) * e, delta);
        let fixed = Guide::fixed(gp, phi1 + delta + d);
        let k = prp_dyad(slot, fixed).unwrap();
        let load1 = g1.at(o1, 0.3);
        let dyad = PrpDyad {
            b: k.b.p,
            guide2: slot.unit(),
            guide3: fixed.unit(),
            load2: g2.at(k.b.p, 0.2),
            load3: g3.at(k.b.p, 0.2),
        };
        let r = dyad.solve().unwrap();
        // The slider 2 pushes on the crank with −R12, at the moment −K12 about B.
        let m = CouplingDrive { o1 }.solve(&[load1, Load::new(k.b.p, -r.r12, -r.moment12)]).unwrap();
        let terms = [
            m.balancing_moment * w1,
            power(&load1, c.motion_of(load1.point).v, w1),
            power(&dyad.load2, k.link2.motion_of(dyad.load2.point).v, k.link2.omega),
            power(&dyad.load3, k.link3.motion_of(dyad.load3.point).v, k.link3.omega),
        ];
        prop_assert!(k.link3.omega == 0.0 && k.link2.omega == w1);
        let sum: f64 = terms.iter().sum();
        let size: f64 = terms.iter().map(|t| t.abs()).sum();
        prop_assert!(sum.abs() <= 1e-12 * size.max(1e-300) * r.conditioning.condition, "{terms:?}");
    }

    /// A Scotch yoke with its slot at any angle α to a fixed guide: the same check.
    #[test]
    fn scotch_yoke_balances_by_virtual_power(
        phi1 in direction(), l1 in 0.05..0.5f64, w1 in 1.0..100.0f64, gp in point(), phi4 in direction(),
        alpha in well_shaped_angle(), g1 in raw_load(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let o1 = Point2::origin();
        let cs = crank(o1, l1, Motion::new(phi1, w1, 0.0)).unwrap();
        let k = rpp_dyad(cs.a, Guide::fixed(gp, phi4), alpha).unwrap();
        let load1 = g1.at(o1, l1);
        let dyad = RppDyad {
            a: cs.a.p,
            b: k.b.p,
            guide: unit(phi4),
            slot: unit(phi4 + alpha),
            load2: g2.at(cs.a.p, 0.1),
            load3: g3.at(k.b.p, 0.4),
        };
        let r = dyad.solve().unwrap();
        let m = CouplingDrive { o1 }.solve(&[load1, Load::force_at(cs.a.p, -r.r12)]).unwrap();
        // Links 2 and 3 translate: every point of link 2 moves with A, of link 3 with B.
        let terms = [
            m.balancing_moment * w1,
            power(&load1, cs.link.motion_of(load1.point).v, w1),
            power(&dyad.load2, cs.a.v, 0.0),
            power(&dyad.load3, k.b.v, 0.0),
        ];
        let sum: f64 = terms.iter().sum();
        let size: f64 = terms.iter().map(|t| t.abs()).sum();
        prop_assert!(sum.abs() <= 1e-12 * size.max(1e-300) * r.conditioning.condition, "{terms:?}");
    }
}

// ----- Exact singularities and bad input -----

#[test]
fn parallel_guides_and_a_slide_along_the_guide_are_errors_naming_the_measure() {
    let o = Point2::origin();
    let z = |p| Load::force_at(p, Vector2::new(3.0, -4.0));
    // Parallel guides, also when opposite.
    for g3 in [Vector2::new(2.0, 0.0), Vector2::new(-0.5, 0.0)] {
        let e = PrpDyad {
            b: o,
            guide2: Vector2::new(1.0, 0.0),
            guide3: g3,
            load2: z(o),
            load3: z(o),
        }
        .solve()
        .unwrap_err();
        assert!(is_singular(&e, "sin(phi_g3 - phi_g2)"), "{e}");
    }
    // The slide along the guide.
    let e = RppDyad {
        a: Point2::new(0.0, 1.0),
        b: o,
        guide: Vector2::new(1.0, 1.0),
        slot: Vector2::new(-3.0, -3.0),
        load2: z(o),
        load3: z(o),
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "sin(alpha)"), "{e}");
    // Huge loads near the singularity overflow: an error naming the measure, never an infinity.
    let big = Load::force_at(o, Vector2::new(1e300, -1e300));
    let e = PrpDyad {
        b: o,
        guide2: Vector2::new(1.0, 0.0),
        guide3: unit(1e-12),
        load2: big,
        load3: big,
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "sin(phi_g3 - phi_g2)"), "{e}");
    let e = RppDyad {
        a: Point2::new(0.0, 1.0),
        b: o,
        guide: Vector2::new(1.0, 0.0),
        slot: unit(PI - 1e-12),
        load2: big,
        load3: big,
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "sin(alpha)"), "{e}");
    // Just off the singularity the result is finite and says how ill-conditioned it is.
    let r = PrpDyad {
        b: o,
        guide2: Vector2::new(1.0, 0.0),
        guide3: unit(1e-9),
        load2: z(o),
        load3: z(o),
    }
    .solve()
    .unwrap();
    assert!((r.conditioning.condition - 1e9).abs() <= 1.0);
    // The load along the guides, 2·3 N, has only the tiny angle to be balanced through.
    assert!((r.r43.norm() - 6e9).abs() <= 1e-3 * 6e9, "{:?}", r.r43);
}

#[test]
fn bad_numbers_are_errors_not_nans() {
    let o = Point2::origin();
    let ok = Load::force_at(o, Vector2::new(1.0, 0.0));
    let nan = Load::force_at(o, Vector2::new(f64::NAN, 0.0));
    let prp = PrpDyad {
        b: o,
        guide2: Vector2::new(1.0, 0.0),
        guide3: Vector2::new(0.0, 1.0),
        load2: ok,
        load3: ok,
    };
    assert!(matches!(
        PrpDyad { load3: nan, ..prp }.solve(),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        PrpDyad {
            b: Point2::new(f64::INFINITY, 0.0),
            ..prp
        }
        .solve(),
        Err(Error::NonFinite { name: "B.x", .. })
    ));
    assert!(matches!(
        PrpDyad {
            guide3: Vector2::zeros(),
            ..prp
        }
        .solve(),
        Err(Error::NonPositive {
            name: "|guide3|",
            ..
        })
    ));
    let rpp = RppDyad {
        a: Point2::new(0.0, 1.0),
        b: o,
        guide: Vector2::new(1.0, 0.0),
        slot: Vector2::new(0.0, 1.0),
        load2: ok,
        load3: ok,
    };
    assert!(matches!(
        RppDyad { load2: nan, ..rpp }.solve(),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        RppDyad {
            slot: Vector2::new(0.0, f64::NAN),
            ..rpp
        }
        .solve(),
        Err(Error::NonFinite { name: "slot.y", .. })
    ));
    assert!(matches!(
        RppDyad {
            slot: Vector2::zeros(),
            ..rpp
        }
        .solve(),
        Err(Error::NonPositive { name: "|slot|", .. })
    ));
    // A load placed far away overflows its moment, not the forces: still an error.
    let far = Load::force_at(Point2::new(1e300, -1e300), Vector2::new(1e300, 1e300));
    assert!(RppDyad { load3: far, ..rpp }.solve().is_err());
    assert!(PrpDyad { load2: far, ..prp }.solve().is_err());
}
