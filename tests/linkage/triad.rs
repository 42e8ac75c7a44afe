//! The triad (the Assur group of the 3rd class) in the engine, on the bundled six-bar with a
//! triad: closure, rates against finite differences, the whole linkage's Newton–Euler system,
//! virtual power, the mode kept round a turn (a group of a higher class: tests/linkage/general.rs).

use super::engine::lu_difference;
use crate::common::fd::plan_rates_vs_differences;
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

/// 72 positions round a turn, off the drawn one.
fn rates_vs_differences(plan: &Plan, w: f64, e: f64, h: f64) -> f64 {
    let phis: Vec<f64> = (0..72)
        .map(|k| plan.reference_input() + TAU * (f64::from(k) + 0.3) / 72.0)
        .collect();
    plan_rates_vs_differences(plan, &phis, w, e, h)
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

/// The six-bar with its triad given one sliding pair, as a description file: `outer`, the
/// rocker O2 B2 becomes a slider on a guide of the frame through O2; otherwise the joint B3
/// becomes a slide of rocker 5 along a guide of the ternary link.
fn slider_six_bar(outer: bool) -> tmm::linkage::Linkage {
    let (o2, b3) = if outer {
        (
            r#"{"name": "O2", "at": [0.47, 0.0], "kind": {"prismatic": {"guide": "frame", "direction": [0.3, 1.0]}}}"#,
            r#"{"name": "B3", "at": [0.27, 0.31]}"#,
        )
    } else {
        (
            r#"{"name": "O2", "at": [0.47, 0.0]}"#,
            r#"{"name": "B3", "at": [0.27, 0.31], "kind": {"prismatic": {"guide": "ternary", "direction": [1.0, 0.4]}}}"#,
        )
    };
    let text = format!(
        r#"{{
  "name": "six-bar with a sliding triad",
  "joints": [
    {{"name": "O1", "at": [0.0, 0.0]}},
    {{"name": "A", "at": [0.08, 0.0]}},
    {{"name": "B1", "at": [0.31, 0.17]}},
    {{"name": "B2", "at": [0.51, 0.3]}},
    {b3},
    {o2},
    {{"name": "O3", "at": [0.16, 0.54]}}
  ],
  "links": [
    {{"name": "frame", "joints": ["O1", "O2", "O3"]}},
    {{"name": "crank", "joints": ["O1", "A"], "mass": {{"m": 1.0, "j": 0.002, "centre": [0.0, 0.0]}}}},
    {{"name": "link 2", "joints": ["A", "B1"], "mass": {{"m": 1.2, "j": 0.00818, "centre": [0.195, 0.085]}}}},
    {{"name": "ternary", "joints": ["B1", "B2", "B3"], "mass": {{"m": 3.0, "j": 0.02, "centre": [0.363333, 0.26]}}}},
    {{"name": "rocker 4", "joints": ["O2", "B2"], "mass": {{"m": 1.5, "j": 0.01145, "centre": [0.49, 0.15]}}}},
    {{"name": "rocker 5", "joints": ["O3", "B3"], "mass": {{"m": 1.4, "j": 0.00758333, "centre": [0.215, 0.425]}}}}
  ],
  "input": {{"link": "crank", "drive": "coupling"}},
  "gravity": [0.0, -9.81],
  "loads": [
    {{"resistance": {{"on": "rocker 5", "forward": 20.0, "backward": 20.0}}}},
    {{"force": {{"link": "ternary", "at": "B2", "force": [-150.0, 50.0]}}}}
  ],
  "output": {{"angle": "rocker 5"}}
}}"#
    );
    serde_json::from_str(&text).unwrap()
}

/// Inputs where both sliding six-bars assemble: a band around the drawn crank angle.
fn slider_inputs(plan: &Plan, n: u32) -> Vec<f64> {
    (0..n)
        .map(|k| plan.reference_input() + 0.6 * (f64::from(k) / f64::from(n - 1) - 0.5))
        .collect()
}

#[test]
fn a_triad_with_a_sliding_pair_is_found_solved_and_balanced() {
    for outer in [true, false] {
        let plan = Plan::new(&slider_six_bar(outer)).unwrap();
        let g = &plan.groups()[0];
        assert_eq!(plan.groups().len(), 1);
        assert_eq!(g.kind, GroupKind::Triad);
        let names = |ks: &[usize]| -> Vec<String> {
            ks.iter().map(|&k| plan.link_names()[k].clone()).collect()
        };
        // The sliding leg first.
        let first = if outer { "rocker 4" } else { "rocker 5" };
        assert_eq!(names(&g.triad_links().unwrap())[1], first);
        let phis = slider_inputs(&plan, 25);
        // Rates against eighth-order differences of positions.
        let (w, e) = (3.0, -2.0);
        let fd = [1e-3, 2e-3, 4e-3].map(|h| plan_rates_vs_differences(&plan, &phis, w, e, h));
        let best = fd.iter().copied().fold(f64::INFINITY, f64::min);
        // Reactions against the whole linkage's Newton–Euler system, virtual power and every
        // link's equilibrium; the transmission angle stays positive.
        let (mut lu, mut vp, mut eq, mut mu) = (0.0f64, 0.0f64, 0.0f64, f64::INFINITY);
        let mut solver = plan.solver();
        for &phi in &phis {
            let a = solver.analyse(Motion::new(phi, 12.0, -7.0)).unwrap();
            lu = lu.max(lu_difference(&plan, a));
            vp = vp.max(a.power_check().unwrap().relative_error());
            eq = eq.max(a.worst_residual());
            mu = mu.min(a.kinematics().transmission_angle(0).unwrap());
        }
        println!(
            "six-bar with a sliding triad ({}): rates vs differences {:.1e}, {:.1e}, {:.1e} (h = 1, 2, 4e-3); LU {lu:.1e}, \
             virtual power {vp:.1e}, equilibrium {eq:.1e}, min transmission angle {:.1}°",
            if outer { "outer" } else { "inner" },
            fd[0],
            fd[1],
            fd[2],
            mu.to_degrees()
        );
        assert!(best < 1e-9, "{fd:?}");
        assert!(lu < 1e-11, "LU {lu:e}");
        assert!(vp < 1e-12, "virtual power {vp:e}");
        assert!(eq < 1e-12, "equilibrium {eq:e}");
        assert!(mu > 0.0 && mu <= std::f64::consts::FRAC_PI_2, "{mu}");
    }
}
