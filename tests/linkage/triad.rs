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
pub(super) fn slider_six_bar(outer: bool) -> tmm::linkage::Linkage {
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
pub(super) fn slider_inputs(plan: &Plan, n: u32) -> Vec<f64> {
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

/// The bundled six-bar with a sliding triad (`linkages/six-bar-slider-triad.json`) over a
/// turn of 720 positions, against an independent solve of its group: for the ternary link
/// turned by ψ from the drawing, B1 is where link 2's circle about A meets the line that
/// puts B2 on the guide (either intersection σ = ±), and g(ψ, σ) = |B3 − O3| − l5; every
/// root on a grid of 7200 angles is refined by bisection, and the mode is followed from the
/// drawing by the smallest step. The engine's joints agree with the followed root, its slide
/// with B2's travel along the guide, and the slide's stroke (the file's reference figure) is
/// the followed root's.
#[test]
fn the_bundled_slider_triad_follows_an_independent_solve_round_a_turn() {
    use nalgebra::{Point2, Vector2};
    let plan = Plan::new(&bundled::six_bar_slider_triad()).unwrap();
    assert_eq!(plan.groups().len(), 1);
    assert_eq!(plan.groups()[0].kind, GroupKind::Triad);
    let size = plan.size();
    let p = |x: f64, y: f64| Point2::new(x, y);
    let (b1, b2, b3, o3) = (p(0.31, 0.17), p(0.51, 0.3), p(0.27, 0.31), p(0.16, 0.54));
    let (l1, l5) = ((b1 - p(0.08, 0.0)).norm(), (b3 - o3).norm());
    let d = Vector2::new(0.3, -0.04).normalize();
    let n = Vector2::new(-d.y, d.x);
    let h = n.dot(&b2.coords);
    let rot = |v: Vector2<f64>, psi: f64| {
        let (s, c) = psi.sin_cos();
        Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
    };
    // B1 at (ψ, σ) for the crank pin a, or None where the line misses the circle.
    let joint1 = |a: Point2<f64>, psi: f64, sigma: f64| -> Option<Point2<f64>> {
        let dist = h - n.dot(&(a.coords + rot(b2 - b1, psi)));
        let t2 = l1 * l1 - dist * dist;
        (t2 >= 0.0).then(|| a + dist * n + sigma * t2.sqrt() * d)
    };
    let g = |a: Point2<f64>, psi: f64, sigma: f64| {
        joint1(a, psi, sigma).map(|q| (q + rot(b3 - b1, psi) - o3).norm() - l5)
    };
    let roots = |a: Point2<f64>| -> Vec<(Point2<f64>, f64)> {
        let m = 7200;
        let mut out = Vec::new();
        for sigma in [1.0, -1.0] {
            for j in 0..m {
                let (x0, x1) = (
                    TAU * f64::from(j) / f64::from(m) - TAU / 2.0,
                    TAU * f64::from(j + 1) / f64::from(m) - TAU / 2.0,
                );
                let (Some(g0), Some(g1)) = (g(a, x0, sigma), g(a, x1, sigma)) else {
                    continue;
                };
                if (g0 < 0.0) == (g1 < 0.0) {
                    continue;
                }
                let (mut lo, mut hi, mut glo) = (x0, x1, g0);
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    match g(a, mid, sigma) {
                        Some(gm) if (gm < 0.0) == (glo < 0.0) => (lo, glo) = (mid, gm),
                        Some(_) => hi = mid,
                        None => break,
                    }
                }
                let psi = 0.5 * (lo + hi);
                if let Some(q) = joint1(a, psi, sigma) {
                    out.push((q, psi));
                }
            }
        }
        out
    };
    let phi0 = plan.reference_input();
    let mut followed = (b1, 0.0);
    let (mut worst, mut slide_off) = (0.0f64, 0.0f64);
    let (mut s_min, mut s_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut e_min, mut e_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let steps = 720;
    for k in 0..=steps {
        let phi = phi0 + TAU * f64::from(k) / f64::from(steps);
        let a = p(0.08 * phi.cos(), 0.08 * phi.sin());
        let all = roots(a);
        followed = *all
            .iter()
            .min_by(|x, y| {
                let dx = (x.0 - followed.0).norm() + (x.1 - followed.1).abs();
                let dy = (y.0 - followed.0).norm() + (y.1 - followed.1).abs();
                dx.total_cmp(&dy)
            })
            .expect("the group assembles round the turn");
        let kin = plan.kinematics(Motion::fixed(phi)).unwrap();
        let (q1, psi) = followed;
        let q = [q1, q1 + rot(b2 - b1, psi), q1 + rot(b3 - b1, psi)];
        for (name, qi) in ["B1", "B2", "B3"].iter().zip(q) {
            worst = worst.max((kin.joint(*name).unwrap().p - qi).norm());
        }
        let s = d.dot(&(q[1] - b2));
        let engine = kin.slide("S").unwrap().value;
        slide_off = slide_off.max((engine - s).abs());
        (s_min, s_max) = (s_min.min(s), s_max.max(s));
        (e_min, e_max) = (e_min.min(engine), e_max.max(engine));
    }
    println!(
        "bundled six-bar with a sliding triad over {steps} positions: joints vs the independent \
         solve {worst:.1e} m, slide {slide_off:.1e} m; stroke {:.6} m (independent {:.6} m), \
         slide from {s_min:.6} to {s_max:.6} m",
        e_max - e_min,
        s_max - s_min
    );
    assert!(worst <= 1e-9 * size, "joints off by {worst:e}");
    assert!(slide_off <= 1e-9 * size, "slide off by {slide_off:e}");
    // The reference figure of `bundled::six_bar_slider_triad`, to its six digits.
    assert!(
        (s_max - s_min - 0.238056).abs() < 1e-6,
        "stroke {}",
        s_max - s_min
    );
    assert!((s_min + 0.221899).abs() < 1e-6 && (s_max - 0.016157).abs() < 1e-6);
}
