//! Kinetostatics against an independent general solve, equilibrium residuals, the principle of
//! virtual power, the seeds' own (corrected) scalar formulas, and behaviour at singularities.

pub(crate) mod general_solve;
mod passive;
mod prismatic;
mod seed_formulas;
mod strategies;

use nalgebra::{Point2, Vector2};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use strategies::*;
use tmm::angle::{perp, unit};
use tmm::kinetostatics::*;
use tmm::{Error, Load};

const TIGHT: f64 = 1e-12;
/// The near-singular bound: error ≤ condition × this × scale.
const PER_CONDITION: f64 = 1e-14;

fn cfg(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        ..ProptestConfig::default()
    }
}

/// The largest force among the loads and reactions: the scale errors are measured against.
fn scale(forces: &[Vector2<f64>]) -> f64 {
    forces.iter().map(|f| f.norm()).fold(1e-300, f64::max)
}

fn max_diff(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max)
}

/// Force and moment residual of one link under a set of loads, relative to `scale` (and to
/// `scale·len` for the moment).
fn residual(loads: &[Load], scale: f64, len: f64) -> f64 {
    let pole = Point2::new(0.3, -0.7);
    let total = Load::sum_about(loads, pole);
    (total.force.norm() / scale).max(total.moment.abs() / (scale * len))
}

fn is_singular(e: &Error, measure: &str) -> bool {
    matches!(e, Error::Singular { measure: m, .. } if *m == measure)
}

// ----- RRR -----

fn rrr_case(
    b: Point2<f64>,
    l2: f64,
    l3: f64,
    phi2: f64,
    phi3: f64,
    g2: RawLoad,
    g3: RawLoad,
) -> RrrDyad {
    let a = b - unit(phi2) * l2;
    let c = b - unit(phi3) * l3;
    RrrDyad {
        a,
        b,
        c,
        load2: g2.at(a + (b - a) * 0.5, l2),
        load3: g3.at(c + (b - c) * 0.5, l3),
    }
}

fn rrr_check(d: &RrrDyad) -> Result<(f64, f64, f64), TestCaseError> {
    let r = d.solve().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let g = general_solve::rrr(d.a, d.b, d.c, &d.load2, &d.load3);
    let s = scale(&[d.load2.force, d.load3.force, r.r12, r.r43, r.r23]);
    let err = max_diff(&[r.r12, r.r43, r.r23], &g) / s;
    let len = [d.a, d.b, d.c]
        .iter()
        .map(|p| (p - d.b).norm())
        .fold(0.0, f64::max)
        .max(1.0);
    let res2 = residual(
        &[
            d.load2,
            Load::force_at(d.a, r.r12),
            Load::force_at(d.b, -r.r23),
        ],
        s,
        len,
    );
    let res3 = residual(
        &[
            d.load3,
            Load::force_at(d.c, r.r43),
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
    fn rrr_agrees_with_the_general_solve(
        b in point(), l2 in length(), l3 in length(), phi2 in direction(), d in well_shaped_angle(),
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let (err, res, _) = rrr_check(&rrr_case(b, l2, l3, phi2, phi2 + d, g2, g3))?;
        prop_assert!(err <= TIGHT, "error {err:e}");
        prop_assert!(res <= TIGHT, "residual {res:e}");
    }
}

proptest! {
    #![proptest_config(cfg(1500))]
    #[test]
    fn rrr_near_a_dead_point_errs_or_reports_its_conditioning(
        b in point(), l2 in length(), l3 in length(), phi2 in direction(), tiny in tiny_angle(),
        folded in any::<bool>(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let phi3 = phi2 + tiny + if folded { PI } else { 0.0 };
        let d = rrr_case(b, l2, l3, phi2, phi3, g2, g3);
        match d.solve() {
            Err(e) => prop_assert!(is_singular(&e, "sin(phi3 - phi2)"), "{e}"),
            Ok(_) => {
                let (err, _, cond) = rrr_check(&d)?;
                prop_assert!(err <= cond * PER_CONDITION, "error {err:e} > {cond:e} x 1e-14");
            }
        }
    }
}

// ----- RRP -----

fn rrp_case(b: Point2<f64>, l2: f64, phi2: f64, phi4: f64, g2: RawLoad, g3: RawLoad) -> RrpDyad {
    let a = b - unit(phi2) * l2;
    RrpDyad {
        a,
        b,
        guide: unit(phi4) * 0.7,
        load2: g2.at(a + (b - a) * 0.5, l2),
        load3: g3.at(b, 0.1),
    }
}

fn rrp_check(d: &RrpDyad) -> Result<(f64, f64, f64), TestCaseError> {
    let r = d.solve().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let (g, k) = general_solve::rrp(d.a, d.b, d.guide, &d.load2, &d.load3);
    let s = scale(&[d.load2.force, d.load3.force, r.r12, r.r43, r.r23]);
    let len = (d.a - d.b).norm().max(1.0);
    let err =
        (max_diff(&[r.r12, r.r43, r.r23], &g) / s).max((r.guide_moment - k).abs() / (s * len));
    // The guide's reaction acts at B + h·g (or is a couple): its moment about B is guide_moment.
    let guide_load = Load::new(d.b, r.r43, r.guide_moment);
    if let Some(h) = r.offset {
        let at = d.b + d.guide.normalize() * h;
        prop_assert!(
            (Load::force_at(at, r.r43).moment_about(d.b) - r.guide_moment).abs() <= 1e-9 * s * len
        );
    }
    let res2 = residual(
        &[
            d.load2,
            Load::force_at(d.a, r.r12),
            Load::force_at(d.b, -r.r23),
        ],
        s,
        len,
    );
    let res3 = residual(&[d.load3, guide_load, Load::force_at(d.b, r.r23)], s, len);
    prop_assert!(
        r.r43.dot(&d.guide).abs() <= TIGHT * s * d.guide.norm(),
        "R43 not normal to the guide"
    );
    Ok((err, res2.max(res3), r.conditioning.condition))
}

proptest! {
    #![proptest_config(cfg(3000))]
    #[test]
    fn rrp_agrees_with_the_general_solve(
        b in point(), l2 in length(), phi2 in direction(), d in away_from_right_angle(),
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let (err, res, _) = rrp_check(&rrp_case(b, l2, phi2, phi2 + d, g2, g3))?;
        prop_assert!(err <= TIGHT, "error {err:e}");
        prop_assert!(res <= TIGHT, "residual {res:e}");
    }
}

proptest! {
    #![proptest_config(cfg(1500))]
    #[test]
    fn rrp_near_a_perpendicular_rod_errs_or_reports_its_conditioning(
        b in point(), l2 in length(), phi2 in direction(), tiny in tiny_angle(), flip in any::<bool>(),
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let phi4 = phi2 + FRAC_PI_2 + tiny + if flip { PI } else { 0.0 };
        let d = rrp_case(b, l2, phi2, phi4, g2, g3);
        match d.solve() {
            Err(e) => prop_assert!(is_singular(&e, "cos(phi2 - phi4)"), "{e}"),
            Ok(_) => {
                let (err, _, cond) = rrp_check(&d)?;
                prop_assert!(err <= cond * PER_CONDITION, "error {err:e} > {cond:e} x 1e-14");
            }
        }
    }
}

// ----- RPR -----

/// A − E = −l_EA·u + offset·u⊥: an axis that may miss E by `offset`.
fn rpr_case(e: Point2<f64>, phi: f64, l_ea: f64, offset: f64, g2: RawLoad, g3: RawLoad) -> RprDyad {
    let u = unit(phi);
    let a = e - u * l_ea + perp(u) * offset;
    RprDyad {
        a,
        e,
        axis: u * 2.0,
        load2: g2.at(a + u * 0.3, 0.3),
        load3: g3.at(e - u * 0.3, 0.3),
    }
}

fn rpr_check(d: &RprDyad) -> Result<(f64, f64, f64), TestCaseError> {
    let r = d.solve().map_err(|e| TestCaseError::fail(e.to_string()))?;
    let (g, k) = general_solve::rpr(d.a, d.e, d.axis, &d.load2, &d.load3);
    let s = scale(&[d.load2.force, d.load3.force, r.r12, r.r32, r.r43]);
    let len = (d.a - d.e).norm().max(1.0);
    let err = (max_diff(&[r.r12, r.r32, r.r43], &g) / s).max((r.couple - k).abs() / (s * len));
    let slide = Load::new(d.a, r.r32, r.couple); // R32 with its moment about A
    let res2 = residual(&[d.load2, Load::force_at(d.a, r.r12), slide], s, len);
    let res3 = residual(
        &[
            d.load3,
            Load::force_at(d.e, r.r43),
            Load::new(d.a, -r.r32, -r.couple),
        ],
        s,
        len,
    );
    prop_assert!(
        r.r32.dot(&d.axis).abs() <= TIGHT * s * d.axis.norm(),
        "R32 has an axial part"
    );
    Ok((err, res2.max(res3), r.conditioning.condition))
}

proptest! {
    #![proptest_config(cfg(3000))]
    #[test]
    fn rpr_agrees_with_the_general_solve(
        e in point(), phi in direction(), l_ea in 0.1..2.0f64, neg in any::<bool>(), offset in -0.5..0.5f64,
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let l_ea = if neg { -l_ea } else { l_ea };
        let (err, res, _) = rpr_check(&rpr_case(e, phi, l_ea, offset, g2, g3))?;
        prop_assert!(err <= TIGHT, "error {err:e}");
        prop_assert!(res <= TIGHT, "residual {res:e}");
    }
}

proptest! {
    #![proptest_config(cfg(1500))]
    #[test]
    fn rpr_near_a_at_e_errs_or_reports_its_conditioning(
        e in point(), phi in direction(), tiny in tiny_angle(), offset in -0.5..0.5f64,
        g2 in raw_load(), g3 in raw_load(),
    ) {
        let d = rpr_case(e, phi, tiny, offset, g2, g3);
        match d.solve() {
            Err(err) => prop_assert!(is_singular(&err, "l_EA"), "{err}"),
            Ok(_) => {
                let (err, _, cond) = rpr_check(&d)?;
                prop_assert!(err <= cond * PER_CONDITION, "error {err:e} > {cond:e} x 1e-14");
            }
        }
    }
}

// ----- Input link -----

fn input_loads(o1: Point2<f64>, g1: RawLoad, r21: RawLoad) -> Vec<Load> {
    vec![g1.at(o1, 0.2), r21.at(o1, 0.4)]
}

proptest! {
    #![proptest_config(cfg(3000))]
    #[test]
    fn coupling_agrees_with_the_general_solve(o1 in point(), g1 in raw_load(), r21 in raw_load()) {
        let loads = input_loads(o1, g1, r21);
        let r = CouplingDrive { o1 }.solve(&loads).unwrap();
        let (g01, gm) = general_solve::coupling(o1, &loads);
        let s = scale(&[loads[0].force, loads[1].force, r.r01]).max(r.balancing_moment.abs());
        prop_assert!((r.r01 - g01).norm() <= TIGHT * s);
        prop_assert!((r.balancing_moment - gm).abs() <= TIGHT * s);
    }

    #[test]
    fn gear_agrees_with_the_general_solve_on_the_right_flank(
        o1 in point(), rw in 0.05..0.5f64, theta in direction(), alpha in 0.0..0.6f64,
        g1 in raw_load(), r21 in raw_load(),
    ) {
        let loads = input_loads(o1, g1, r21);
        let drive = GearDrive::at_angle(o1, rw, theta, alpha);
        let r = drive.solve(&loads).unwrap();
        gear_check(&drive, &loads, &r, TIGHT)?;
    }
}

fn gear_check(
    drive: &GearDrive,
    loads: &[Load],
    r: &GearBalance,
    tol: f64,
) -> Result<(), TestCaseError> {
    let theta = (drive.pitch_point - drive.o1)
        .y
        .atan2((drive.pitch_point - drive.o1).x);
    let mirrored = r.flank == Flank::Mirrored;
    let dir = unit(tmm::angle::line_of_action(
        theta - FRAC_PI_2,
        drive.pressure_angle,
        mirrored,
    ));
    let (g01, f) = general_solve::gear(drive.o1, drive.pitch_point, dir, loads);
    let s = scale(&[loads[0].force, loads[1].force, r.r01, r.force]);
    // A tooth force pushes: the general solve on the chosen flank must give F ≥ 0.
    prop_assert!(f >= -tol * s, "flank rule violated: F = {f}");
    prop_assert!(
        (r.force - dir * f).norm() <= tol * s,
        "{:?} vs {:?}",
        r.force,
        dir * f
    );
    prop_assert!((r.r01 - g01).norm() <= tol * s);
    // Both flanks push towards the centre.
    prop_assert!(r.force.dot(&(drive.o1 - drive.pitch_point)) >= -tol * s * 1.0);
    Ok(())
}

proptest! {
    #![proptest_config(cfg(1500))]
    #[test]
    fn gear_near_a_zero_arm_errs_or_reports_its_conditioning(
        o1 in point(), rw in 0.05..0.5f64, theta in direction(), tiny in tiny_angle(),
        g1 in raw_load(), r21 in raw_load(),
    ) {
        let loads = input_loads(o1, g1, r21);
        let drive = GearDrive::at_angle(o1, rw, theta, FRAC_PI_2 - tiny.abs());
        match drive.solve(&loads) {
            // π/2 − 10⁻¹⁷ rounds to π/2 itself, which is out of range.
            Err(e) => prop_assert!(
                is_singular(&e, "r_w cos(alpha_w)") || matches!(e, Error::OutOfRange { .. }),
                "{e}"
            ),
            Ok(r) => gear_check(&drive, &loads, &r, r.conditioning.condition * PER_CONDITION)?,
        }
    }
}

// ----- Whole mechanisms at one instant: the principle of virtual power -----

/// Velocities of a crank O1A (ω1) and an RRR dyad A–B–C with C fixed: ω2, ω3 from
/// v_A + ω2·(B − A)⊥ = ω3·(B − C)⊥.
fn rrr_velocities(
    o1: Point2<f64>,
    a: Point2<f64>,
    b: Point2<f64>,
    c: Point2<f64>,
    w1: f64,
) -> (f64, f64) {
    let va = perp(a - o1) * w1;
    let (p, q) = (perp(b - a), perp(b - c));
    // ω2·p − ω3·q = −v_A
    let det = -p.x * q.y + q.x * p.y;
    let w2 = (-va.x * -q.y - (-q.x) * -va.y) / det;
    let w3 = (p.x * -va.y - p.y * -va.x) / det;
    (w2, w3)
}

fn power(load: &Load, v_point: Vector2<f64>, omega: f64) -> f64 {
    load.force.dot(&v_point) + load.moment * omega
}

proptest! {
    #![proptest_config(cfg(1000))]
    #[test]
    fn four_bar_balancing_moment_equals_virtual_power(
        phi1 in direction(), l1 in 0.05..0.3f64, l2 in 0.3..1.0f64, phi2 in direction(), d in well_shaped_angle(),
        l3 in 0.3..1.0f64, w1 in 1.0..100.0f64, g1 in raw_load(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let o1 = Point2::origin();
        let a = o1 + unit(phi1) * l1;
        let b = a + unit(phi2) * l2;
        let c = b - unit(phi2 + d) * l3;
        let load1 = g1.at(o1, l1);
        let dyad = RrrDyad { a, b, c, load2: g2.at(a, l2), load3: g3.at(c, l3) };
        let r = dyad.solve().unwrap();
        let m = CouplingDrive { o1 }.solve(&[load1, Load::force_at(a, -r.r12)]).unwrap();
        let (w2, w3) = rrr_velocities(o1, a, b, c, w1);
        let v = |p: Point2<f64>, pivot: Point2<f64>, vp: Vector2<f64>, w: f64| vp + perp(p - pivot) * w;
        let va = v(a, o1, Vector2::zeros(), w1);
        let terms = [
            m.balancing_moment * w1,
            power(&load1, v(load1.point, o1, Vector2::zeros(), w1), w1),
            power(&dyad.load2, v(dyad.load2.point, a, va, w2), w2),
            power(&dyad.load3, v(dyad.load3.point, c, Vector2::zeros(), w3), w3),
        ];
        let sum: f64 = terms.iter().sum();
        let size: f64 = terms.iter().map(|t| t.abs()).sum();
        prop_assert!(sum.abs() <= 1e-12 * size.max(1e-300) * r.conditioning.condition, "{terms:?}");
    }

    #[test]
    fn slider_crank_through_a_gear_balances_by_virtual_power(
        phi1 in direction(), l1 in 0.05..0.3f64, l2 in 0.3..1.0f64, phi2 in direction(), d in away_from_right_angle(),
        w1 in 1.0..100.0f64, theta in direction(), alpha in 0.0..0.6f64,
        g1 in raw_load(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let o1 = Point2::origin();
        let a = o1 + unit(phi1) * l1;
        let b = a + unit(phi2) * l2;
        let g = unit(phi2 + d);
        let load1 = g1.at(o1, l1);
        let dyad = RrpDyad { a, b, guide: g, load2: g2.at(a, l2), load3: g3.at(b, 0.1) };
        let r = dyad.solve().unwrap();
        let drive = GearDrive::at_angle(o1, 0.2, theta, alpha);
        let bal = drive.solve(&[load1, Load::force_at(a, -r.r12)]).unwrap();
        // v_A + ω2·(B − A)⊥ = v_s·g
        let va = perp(a - o1) * w1;
        let p = perp(b - a);
        let det = -p.x * g.y + g.x * p.y; // [p, −g]
        let w2 = (-va.x * -g.y - (-g.x) * -va.y) / det;
        let vs = (p.x * -va.y - p.y * -va.x) / det;
        let vb = g * vs;
        let terms = [
            bal.force.dot(&(perp(drive.pitch_point - o1) * w1)),
            power(&load1, perp(load1.point - o1) * w1, w1),
            power(&dyad.load2, va + perp(dyad.load2.point - a) * w2, w2),
            power(&dyad.load3, vb, 0.0),
        ];
        let sum: f64 = terms.iter().sum();
        let size: f64 = terms.iter().map(|t| t.abs()).sum();
        prop_assert!(sum.abs() <= 1e-12 * size.max(1e-300) * r.conditioning.condition, "{terms:?}");
        // And the tooth force supplies what a coupling would.
        let m = CouplingDrive { o1 }.solve(&[load1, Load::force_at(a, -r.r12)]).unwrap();
        prop_assert!((m.balancing_moment - bal.balancing_moment).abs() <= 1e-12 * size.max(1.0));
    }

    #[test]
    fn rocking_cylinder_balances_by_virtual_power(
        phi1 in direction(), l1 in 0.05..0.3f64, e_dist in 0.4..1.5f64, e_dir in direction(),
        w1 in 1.0..100.0f64, g1 in raw_load(), g2 in raw_load(), g3 in raw_load(),
    ) {
        let o1 = Point2::origin();
        let a = o1 + unit(phi1) * l1;
        let e = o1 + unit(e_dir) * e_dist;
        let u = (e - a).normalize();
        let load1 = g1.at(o1, l1);
        let dyad = RprDyad { a, e, axis: u, load2: g2.at(a, 0.3), load3: g3.at(e, 0.3) };
        let r = dyad.solve().unwrap();
        let m = CouplingDrive { o1 }.solve(&[load1, Load::force_at(a, -r.r12)]).unwrap();
        // v_A = ω·(A − E)⊥ + v_rel·u, the rod and cylinder turning together with ω.
        let va = perp(a - o1) * w1;
        let p = perp(a - e);
        let det = p.x * u.y - u.x * p.y;
        let w = (va.x * u.y - u.x * va.y) / det;
        let terms = [
            m.balancing_moment * w1,
            power(&load1, perp(load1.point - o1) * w1, w1),
            power(&dyad.load2, va + perp(dyad.load2.point - a) * w, w),
            power(&dyad.load3, perp(dyad.load3.point - e) * w, w),
        ];
        let sum: f64 = terms.iter().sum();
        let size: f64 = terms.iter().map(|t| t.abs()).sum();
        prop_assert!(sum.abs() <= 1e-12 * size.max(1e-300) * r.conditioning.condition, "{terms:?}");
    }
}

// ----- The seed-notation adapters -----

proptest! {
    #![proptest_config(cfg(2000))]
    #[test]
    fn seed_adapters_agree_with_cartesian_solvers_and_corrected_seed_formulas(
        l_ba in length(), l_bs2 in 0.0..1.0f64, l_bc in length(), l_bs3 in 0.0..1.0f64,
        phi2 in direction(), d in well_shaped_angle(), dd in away_from_right_angle(),
        f2 in 0.0..1000.0f64, gamma2 in direction(), f3 in 0.0..1000.0f64, gamma3 in direction(),
        m2 in -200.0..200.0f64, m3 in -200.0..200.0f64, shift in point(),
    ) {
        // RRR: the adapter against a Cartesian dyad built here, away from the origin.
        let seed = RrrSeed { l_ba, l_bs2: l_bs2 * l_ba, l_bc, l_bs3: l_bs3 * l_bc, phi2, phi3: phi2 + d,
            f2, gamma2, f3, gamma3, m2, m3 };
        let rs = seed.solve().unwrap();
        let b = shift;
        let (u2, u3) = (unit(phi2), unit(phi2 + d));
        let cart = RrrDyad { a: b - u2 * l_ba, b, c: b - u3 * l_bc,
            load2: Load::polar(b - u2 * seed.l_bs2, f2, gamma2, m2),
            load3: Load::polar(b - u3 * seed.l_bs3, f3, gamma3, m3) }.solve().unwrap();
        let s = scale(&[rs.r12, rs.r43, rs.r23, unit(0.0) * f2, unit(0.0) * f3]);
        prop_assert!(max_diff(&[rs.r12, rs.r43, rs.r23], &[cart.r12, cart.r43, cart.r23]) <= 1e-11 * s);
        let f = seed_formulas::sr1(&seed);
        for (ours, theirs) in [(rs.r12_t, f.r12_t), (rs.r43_t, f.r43_t), (rs.r12_n, f.r12_n), (rs.r43_n, f.r43_n)] {
            prop_assert!((ours - theirs).abs() <= 1e-11 * s, "{ours} vs {theirs}");
        }

        // RRP.
        let seed = RrpSeed { l_ba, l_bs2: l_bs2 * l_ba, phi2, phi4: phi2 + dd, f2, gamma2, f3, gamma3, m2, m3: 0.0 };
        let rs = seed.solve().unwrap();
        let cart = RrpDyad { a: b - u2 * l_ba, b, guide: unit(phi2 + dd),
            load2: Load::polar(b - u2 * seed.l_bs2, f2, gamma2, m2),
            load3: Load::polar(b, f3, gamma3, 0.0) }.solve().unwrap();
        let s = scale(&[rs.r12, rs.r43, rs.r23, unit(0.0) * f2, unit(0.0) * f3]);
        prop_assert!(max_diff(&[rs.r12, rs.r43, rs.r23], &[cart.r12, cart.r43, cart.r23]) <= 1e-11 * s);
        let f = seed_formulas::sr2(&seed);
        for (ours, theirs) in [(rs.r12_t, f.0), (rs.r12_n, f.1), (rs.r43_n, f.2)] {
            prop_assert!((ours - theirs).abs() <= 1e-11 * s, "{ours} vs {theirs}");
        }
        prop_assert_eq!(rs.offset, Some(0.0)); // F3 through B and M3 = 0: the seed's h43 = 0

        // RPR: the points in the order A, C, B, E.
        let seed = RprSeed { l_ab: l_ba + 0.2, l_ec: l_bc + 0.2, l_bc: 0.1, l_as2: l_bs2 * l_ba,
            l_es3: l_bs3 * l_bc, phi2, f2, gamma2, f3, gamma3, m2, m3 };
        let rs = seed.solve().unwrap();
        let l_ea = seed.l_ab - seed.l_bc + seed.l_ec;
        let e = shift;
        let cart = RprDyad { a: e - u2 * l_ea, e, axis: u2,
            load2: Load::polar(e - u2 * (l_ea - seed.l_as2), f2, gamma2, m2),
            load3: Load::polar(e - u2 * seed.l_es3, f3, gamma3, m3) }.solve().unwrap();
        let s = scale(&[rs.r12, rs.r32, rs.r43, unit(0.0) * f2, unit(0.0) * f3]);
        prop_assert!(max_diff(&[rs.r12, rs.r32, rs.r43], &[cart.r12, cart.r32, cart.r43]) <= 1e-11 * s);
        let f = seed_formulas::sr3(&seed);
        for (ours, theirs) in [(rs.r12_t, f.0), (rs.r12_n, f.1), (rs.r32_n, f.2)] {
            prop_assert!((ours - theirs).abs() <= 1e-11 * s, "{ours} vs {theirs}");
        }
        if let (Some(h), Some(hs)) = (rs.arm, f.3) {
            // The arm is a couple over R32, and both sides compute their R32 through cancellation:
            // as R32 vanishes the arms lose digits without bound, so they are compared through the
            // couples they make with their own R32 (well conditioned on both sides).
            let moment_scale = s * (l_ea + 1.0);
            prop_assert!((h * rs.r32_n - hs * f.2).abs() <= 1e-11 * moment_scale, "{h} vs {hs}");
        }

        // Input link through a coupling (corrected 1.56) and through a gear (1.49 + flank rule).
        let phi1 = gamma2 + d;
        let c = CouplingSeed { l_o1a: l_ba, l_o1s1: seed.l_as2, phi1, f1: f2, gamma1: gamma2,
            r21: f3, gamma21: gamma3, m1: m2 }.solve().unwrap();
        let (mb, rs_gear) = seed_formulas::srwl(l_ba, seed.l_as2, 0.15, 0.35, phi1, f2, gamma2, f3, gamma3, m2);
        let s = f2.max(f3).max(1.0) * (1.0 + l_ba);
        prop_assert!((c.balancing_moment - mb).abs() <= 1e-11 * s);
        let gb = GearSeed { l_o1a: l_ba, l_o1s1: seed.l_as2, l_o1p: 0.15, alpha_w: 0.35, phi1, f1: f2,
            gamma1: gamma2, r21: f3, gamma21: gamma3, m1: m2 }.solve().unwrap();
        prop_assert!((gb.magnitude - rs_gear.0).abs() <= 1e-10 * s / 0.15);
        prop_assert!((tmm::angle::direction(gb.force) - rs_gear.1).abs() <= 1e-12 || gb.magnitude == 0.0);
    }
}

// ----- Bad input and exact singularities -----

#[test]
fn exact_dead_points_and_zero_arms_are_errors_naming_the_measure() {
    let o = Point2::origin();
    let z = |p| Load::force_at(p, Vector2::new(3.0, -4.0));
    // RRR stretched straight along x.
    let e = RrrDyad {
        a: Point2::new(-1.0, 0.0),
        b: o,
        c: Point2::new(2.0, 0.0),
        load2: z(o),
        load3: z(o),
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "sin(phi3 - phi2)"), "{e}");
    // RRP with the rod perpendicular to the guide.
    let e = RrpDyad {
        a: Point2::new(0.0, -1.0),
        b: o,
        guide: Vector2::new(1.0, 0.0),
        load2: z(o),
        load3: z(o),
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "cos(phi2 - phi4)"), "{e}");
    // RPR with A at E.
    let e = RprDyad {
        a: o,
        e: o,
        axis: Vector2::new(1.0, 0.0),
        load2: z(o),
        load3: z(o),
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "l_EA"), "{e}");
    // RPR whose axis misses E, with A on the normal to the axis through E.
    let e = RprDyad {
        a: Point2::new(0.0, 0.3),
        e: o,
        axis: Vector2::new(1.0, 0.0),
        load2: z(o),
        load3: z(o),
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "l_EA"), "{e}");
    // A gear with a pressure angle of 90° is out of range; one a hair below it has no arm.
    let g = GearDrive::at_angle(o, 0.1, 0.0, FRAC_PI_2);
    assert!(matches!(
        g.solve(&[z(Point2::new(0.1, 0.1))]),
        Err(Error::OutOfRange {
            name: "alpha_w",
            ..
        })
    ));
    let g = GearDrive::at_angle(o, 0.1, 0.0, FRAC_PI_2 - 1e-17);
    assert!(matches!(
        g.solve(&[z(Point2::new(0.1, 0.1))]),
        Err(Error::OutOfRange { .. } | Error::Singular { .. })
    ));
    let g = GearDrive::at_angle(o, 0.1, 0.0, FRAC_PI_2 - 4e-16);
    let e = g.solve(&[z(Point2::new(0.1, 0.1))]).unwrap_err();
    assert!(is_singular(&e, "r_w cos(alpha_w)"), "{e}");
}

#[test]
fn bad_numbers_are_errors_not_nans() {
    let o = Point2::origin();
    let p = Point2::new(1.0, 1.0);
    let ok = Load::force_at(o, Vector2::new(1.0, 0.0));
    let nan = Load::force_at(o, Vector2::new(f64::NAN, 0.0));
    let inf_pt = Point2::new(f64::INFINITY, 0.0);
    assert!(matches!(
        RrrDyad {
            a: inf_pt,
            b: o,
            c: p,
            load2: ok,
            load3: ok
        }
        .solve(),
        Err(Error::NonFinite { name: "A.x", .. })
    ));
    assert!(matches!(
        RrrDyad {
            a: p,
            b: o,
            c: Point2::new(1.0, -1.0),
            load2: nan,
            load3: ok
        }
        .solve(),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        RrrDyad {
            a: o,
            b: o,
            c: p,
            load2: ok,
            load3: ok
        }
        .solve(),
        Err(Error::NonPositive { name: "l_AB", .. })
    ));
    assert!(matches!(
        RrpDyad {
            a: p,
            b: o,
            guide: Vector2::zeros(),
            load2: ok,
            load3: ok
        }
        .solve(),
        Err(Error::NonPositive {
            name: "|guide|",
            ..
        })
    ));
    assert!(matches!(
        RprDyad {
            a: p,
            e: o,
            axis: Vector2::zeros(),
            load2: ok,
            load3: ok
        }
        .solve(),
        Err(Error::NonPositive { name: "|axis|", .. })
    ));
    assert!(matches!(
        CouplingDrive { o1: o }.solve(&[nan]),
        Err(Error::NonFinite { .. })
    ));
    let seed = RprSeed {
        l_ab: 0.1,
        l_ec: 0.1,
        l_bc: 0.3,
        l_as2: 0.0,
        l_es3: 0.0,
        phi2: 0.0,
        f2: 1.0,
        gamma2: 0.0,
        f3: 0.0,
        gamma3: 0.0,
        m2: 0.0,
        m3: 0.0,
    };
    assert!(matches!(
        seed.solve(),
        Err(Error::NonPositive { name: "l_EA", .. })
    ));
    let seed = RrrSeed {
        l_ba: -0.3,
        l_bs2: 0.0,
        l_bc: 0.4,
        l_bs3: 0.0,
        phi2: 0.0,
        phi3: 1.0,
        f2: 0.0,
        gamma2: 0.0,
        f3: 0.0,
        gamma3: 0.0,
        m2: 0.0,
        m3: 0.0,
    };
    assert!(matches!(
        seed.solve(),
        Err(Error::NonPositive { name: "l_BA", .. })
    ));
    // Huge loads near a dead point overflow: an error naming the measure, never an infinity.
    let big = Load::force_at(o, Vector2::new(1e300, 1e300));
    let e = RrrDyad {
        a: Point2::new(-1.0, 0.0),
        b: o,
        c: Point2::new(1.0, 1e-12),
        load2: big,
        load3: big,
    }
    .solve()
    .unwrap_err();
    assert!(is_singular(&e, "sin(phi3 - phi2)"), "{e}");
}
