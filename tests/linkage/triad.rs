//! The triad (the Assur group of the 3rd class) in the engine, on the bundled six-bar with a
//! triad: closure, rates against finite differences, the whole linkage's Newton–Euler system,
//! virtual power, the mode kept round a turn (a group of a higher class: tests/linkage/general.rs).

use super::engine::{fd8, lu_difference};
use std::f64::consts::TAU;
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, GroupKind, Plan};

fn plan() -> Plan {
    Plan::new(&bundled::six_bar_triad()).unwrap()
}

#[test]
fn the_six_bar_decomposes_into_one_triad() {
    let plan = plan();
    let g = &plan.groups()[0];
    assert_eq!(plan.groups().len(), 1);
    assert_eq!(g.kind, GroupKind::Triad);
    assert_eq!(g.kind.label(), "triad");
    let names =
        |ks: &[usize]| -> Vec<&str> { ks.iter().map(|&k| plan.link_names()[k].as_str()).collect() };
    assert_eq!(
        names(&g.triad_links().unwrap()),
        ["ternary", "link 2", "rocker 4", "rocker 5"]
    );
    let [outer, inner] = g.triad_joints().unwrap();
    let jn = |js: [usize; 3]| js.map(|j| plan.joint_names()[j].clone());
    assert_eq!(jn(outer), ["A", "O2", "O3"]);
    assert_eq!(jn(inner), ["B1", "B2", "B3"]);
    let k = plan
        .kinematics(Motion::fixed(plan.reference_input()))
        .unwrap();
    let mu = k.transmission_angle(0).unwrap();
    assert!(mu > 0.2 && mu <= std::f64::consts::FRAC_PI_2, "{mu}");
    assert!(k.group_determinants()[0].abs() > 0.1);
}

/// Over a turn of 360 positions by one solver: every joint closes (its point on each of its
/// two links) to 1e-12 of the size, no joint jumps between consecutive positions more than
/// three times the crank pin's step, the transmission angle stays away from zero, and each
/// position equals the one-shot analysis to the bit (every solve is a pure function of the
/// input: the mode nearest the reference mode, which is the continuous one all round).
#[test]
fn closure_and_the_mode_kept_round_a_turn() {
    let plan = plan();
    let size = plan.size();
    let n = 360;
    let step = 0.08 * TAU / f64::from(n);
    let mut solver = plan.solver();
    let joints = plan.joint_names().len();
    let mut last: Option<Vec<nalgebra::Point2<f64>>> = None;
    let (mut closure, mut jump, mut fresh) = (0.0f64, 0.0f64, 0.0f64);
    let (mut det_min, mut theta_min, mut theta_max) = (f64::INFINITY, f64::INFINITY, 0.0f64);
    let mut mu_min = f64::INFINITY;
    let ternary = plan.link_id("ternary").unwrap();
    for k in 0..=n {
        let phi = plan.reference_input() + TAU * f64::from(k) / f64::from(n);
        let a = solver.kinematics(Motion::new(phi, 10.0, 0.0)).unwrap();
        let mut now = Vec::with_capacity(joints);
        for j in 0..joints {
            let [p, q] = plan.joint_links(j).unwrap();
            let (pp, pq) = (a.joint_on(j, p).unwrap().p, a.joint_on(j, q).unwrap().p);
            closure = closure.max((pp - pq).norm() / size);
            now.push(pp);
        }
        if let Some(prev) = &last {
            for (p, q) in now.iter().zip(prev) {
                jump = jump.max((p - q).norm() / step);
            }
        }
        let one = plan.kinematics(Motion::new(phi, 10.0, 0.0)).unwrap();
        for (j, p) in now.iter().enumerate() {
            fresh = fresh.max((one.joint(j).unwrap().p - p).norm() / size);
        }
        det_min = det_min.min(a.group_determinants()[0].abs());
        mu_min = mu_min.min(a.transmission_angle(0).unwrap());
        let theta = a.link_motion(ternary).unwrap().angle;
        theta_min = theta_min.min(theta);
        theta_max = theta_max.max(theta);
        last = Some(now);
    }
    println!(
        "six-bar with a triad: closure {closure:.1e}, largest joint step {jump:.2} × the crank \
         pin's, one-shot vs solver {fresh:.1e}, min |det K|/L_T {det_min:.3}, min transmission \
         angle {:.1}°, ternary link {:.1}°..{:.1}°",
        mu_min.to_degrees(),
        theta_min.to_degrees(),
        theta_max.to_degrees()
    );
    assert!(closure <= 1e-12, "closure {closure:e}");
    assert!(jump < 3.0, "a joint jumped {jump} crank-pin steps");
    assert!(fresh == 0.0, "one-shot vs solver {fresh:e}");
    assert!(mu_min > 0.2, "{mu_min}");
    // Back where it started, in the same mode.
    assert!(det_min > 0.1, "{det_min}");
    assert!((theta_max - theta_min) < 0.3);
}

/// The rates against 8th-order central differences of positions (each a one-shot solve).
/// The step balances truncation (h⁸ times the 10th derivative) against rounding (about
/// 6.5·ε·|x|/h² in the second difference); the worst over three steps is reported and the
/// best must be below 1e-9 of the acceleration scale.
#[test]
fn velocities_and_accelerations_match_finite_differences_of_positions() {
    let plan = plan();
    let (w, e) = (3.0, -2.0);
    let mut best = f64::INFINITY;
    let mut report = Vec::new();
    for h in [2e-3, 4e-3, 8e-3] {
        let worst = rates_vs_differences(&plan, w, e, h);
        report.push(format!("h = {h:.0e}: {worst:.1e}"));
        best = best.min(worst);
    }
    println!(
        "six-bar with a triad: rates vs 8th-order differences {}",
        report.join(", ")
    );
    assert!(best < 1e-9, "{report:?}");
}

fn rates_vs_differences(plan: &Plan, w: f64, e: f64, h: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for k in 0..72 {
        let phi = plan.reference_input() + TAU * (f64::from(k) + 0.3) / 72.0;
        let a = plan.kinematics(Motion::new(phi, w, e)).unwrap();
        let pos = |x: f64| plan.kinematics(Motion::fixed(x)).unwrap();
        let scale = plan.size() * (w * w + e.abs());
        for j in 0..plan.joint_names().len() {
            for c in 0..2 {
                let f = |x: f64| pos(x).joint(j).unwrap().p[c];
                let (d1, d2) = fd8(&f, phi, h);
                let m = a.joint(j).unwrap();
                worst = worst.max((m.v[c] - d1 * w).abs() / scale);
                worst = worst.max((m.a[c] - (d2 * w * w + d1 * e)).abs() / scale);
            }
        }
        for li in 1..plan.link_names().len() {
            let base = a.link(li).unwrap().value;
            let f = |x: f64| {
                let v = pos(x).link(li).unwrap().value - base;
                v - TAU * (v / TAU).round()
            };
            let (d1, d2) = fd8(&f, phi, h);
            let m = a.link(li).unwrap();
            worst = worst.max((m.rate - d1 * w).abs() / (w * w + e.abs()));
            worst = worst.max((m.accel - (d2 * w * w + d1 * e)).abs() / (w * w + e.abs()));
        }
    }
    worst
}

#[test]
fn reactions_agree_with_the_whole_system_virtual_power_and_equilibrium() {
    let plan = plan();
    let (mut lu, mut vp, mut eq) = (0.0f64, 0.0f64, 0.0f64);
    let mut solver = plan.solver();
    for k in 0..72 {
        let phi = plan.reference_input() + TAU * f64::from(k) / 72.0;
        let a = solver.analyse(Motion::new(phi, 12.0, -7.0)).unwrap();
        lu = lu.max(lu_difference(&plan, a));
        vp = vp.max(a.power_check().unwrap().relative_error());
        eq = eq.max(a.worst_residual());
        // The one-shot analysis gives the same reactions.
        let one = plan.analyse(Motion::new(phi, 12.0, -7.0)).unwrap();
        for j in 0..plan.joint_names().len() {
            let (r1, r2) = (one.reaction(j).unwrap(), a.reaction(j).unwrap());
            assert!((r1.force - r2.force).norm() <= 1e-9 * r2.force.norm().max(1.0));
        }
    }
    println!("six-bar with a triad: LU {lu:.1e}, virtual power {vp:.1e}, equilibrium {eq:.1e}");
    assert!(lu < 1e-11, "LU {lu:e}");
    assert!(vp < 1e-12, "virtual power {vp:e}");
    assert!(eq < 1e-12, "equilibrium {eq:e}");
}
