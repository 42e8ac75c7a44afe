//! The general group (a rigid group of hinges with no closed form) in the engine, on the
//! bundled double butterfly: its decomposition, closure over the input's feasible range,
//! rates against 8th-order finite differences, reactions against one LU solve of the whole
//! linkage's Newton–Euler system, and the count of its real assembly modes at the reference
//! input by two independent searches; and a group of the 4th class solved the same way.

use super::engine::lu_difference;
use crate::common::fd::plan_rates_vs_differences;
use nalgebra::{DMatrix, DVector, Point2, Vector2};
use std::f64::consts::TAU;
use tmm::kinematics::{GroupPose, Motion};
use tmm::linkage::{bundled, GroupKind, Linkage, Plan};
use tmm::Error;

fn plan() -> Plan {
    Plan::new(&bundled::double_butterfly()).unwrap()
}

/// The input angles of a sweep of `n` + 1 positions: a whole turn from the reference when
/// the input turns fully, otherwise its feasible range (without its ends, where the group
/// locks).
fn sweep(plan: &Plan, n: u32) -> Vec<f64> {
    let phi0 = plan.reference_input();
    match plan.lock_positions(phi0).unwrap() {
        None => (0..=n)
            .map(|k| phi0 + TAU * f64::from(k) / f64::from(n))
            .collect(),
        Some((lo, hi)) => {
            let hi = if hi < lo { hi + TAU } else { hi };
            let margin = 1e-3 * (hi - lo);
            (0..=n)
                .map(|k| lo + margin + (hi - lo - 2.0 * margin) * f64::from(k) / f64::from(n))
                .collect()
        }
    }
}

#[test]
fn the_double_butterfly_is_one_general_group_of_six_links() {
    let plan = plan();
    assert_eq!(plan.groups().len(), 1);
    let g = &plan.groups()[0];
    assert_eq!(g.kind, GroupKind::General);
    let (links, inner, outer) = g.general_links().unwrap();
    let mut names: Vec<&str> = links
        .iter()
        .map(|&k| plan.link_names()[k].as_str())
        .collect();
    names.sort_unstable();
    assert_eq!(names, ["BFJ", "CE", "DHI", "EFG", "GH", "IJ"]);
    assert_eq!((inner.len(), outer.len()), (6, 3));
    let mut outer: Vec<&str> = outer
        .iter()
        .map(|&j| plan.joint_names()[j].as_str())
        .collect();
    outer.sort_unstable();
    assert_eq!(outer, ["B", "C", "D"]);
    println!(
        "double butterfly: feasible range {:?}",
        plan.lock_positions(plan.reference_input()).unwrap()
    );
}

/// Over the sweep by one solver: every joint closes (its point on each of its two links)
/// to 1e-12 of the size, no joint jumps between neighbouring positions more than ten times
/// the crank pin's step (one mode, followed continuously), each position equals the one-shot
/// solve to the bit, and the reference input gives back the drawn pose.
#[test]
fn closure_and_one_mode_over_the_range() {
    let plan = plan();
    let size = plan.size();
    let phis = sweep(&plan, 240);
    let step = (phis[1] - phis[0]).abs() * size;
    let mut solver = plan.solver();
    let nj = plan.joint_names().len();
    let (mut closure, mut jump, mut fresh) = (0.0f64, 0.0f64, 0.0f64);
    let mut last: Option<Vec<Point2<f64>>> = None;
    let mut cond_min = f64::INFINITY;
    for &phi in &phis {
        let a = solver.kinematics(Motion::new(phi, 2.0, 0.5)).unwrap();
        let mut now = Vec::with_capacity(nj);
        for j in 0..nj {
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
        cond_min = cond_min.min(a.group_determinants()[0]);
        let one = plan.kinematics(Motion::new(phi, 2.0, 0.5)).unwrap();
        for (j, p) in now.iter().enumerate() {
            fresh = fresh.max((one.joint(j).unwrap().p - p).norm());
        }
        last = Some(now);
    }
    let k = plan
        .kinematics(Motion::fixed(plan.reference_input()))
        .unwrap();
    let l = bundled::double_butterfly();
    let drawn = l
        .joints
        .iter()
        .enumerate()
        .map(|(j, joint)| (k.joint(j).unwrap().p - Point2::new(joint.at[0], joint.at[1])).norm())
        .fold(0.0, f64::max);
    println!(
        "double butterfly over {} positions: closure {closure:.1e}, largest joint step \
         {jump:.2} × the crank's, one-shot vs solver {fresh:.1e}, min σ_min/σ_max {cond_min:.2e}, \
         reference vs drawn {drawn:.1e}",
        phis.len()
    );
    assert!(closure <= 1e-12, "closure {closure:e}");
    assert!(jump < 10.0, "a joint jumped {jump} crank steps");
    assert!(fresh == 0.0, "one-shot vs solver {fresh:e}");
    assert!(drawn <= 1e-12 * size, "{drawn:e}");
}

/// The rates against 8th-order central differences of positions (each a one-shot solve),
/// relative to the scale of the accelerations; the best of three steps must be below 1e-8.
#[test]
fn velocities_and_accelerations_match_finite_differences_of_positions() {
    let plan = plan();
    let (w, e) = (3.0, -2.0);
    let phis = sweep(&plan, 24);
    let mut report = Vec::new();
    let mut best = f64::INFINITY;
    for h in [1e-3, 2e-3, 4e-3] {
        // Inside the range by 4h on each side: the differences need their 8 neighbours.
        let worst = plan_rates_vs_differences(&plan, &phis[1..phis.len() - 1], w, e, h);
        report.push(format!("h = {h:.0e}: {worst:.1e}"));
        best = best.min(worst);
    }
    println!(
        "double butterfly: rates vs 8th-order differences {}",
        report.join(", ")
    );
    assert!(best < 1e-8, "{report:?}");
}

#[test]
fn reactions_agree_with_the_whole_system_virtual_power_and_equilibrium() {
    let plan = plan();
    let (mut lu, mut vp, mut eq) = (0.0f64, 0.0f64, 0.0f64);
    let mut solver = plan.solver();
    let phis = sweep(&plan, 72);
    for &phi in &phis {
        let a = solver.analyse(Motion::new(phi, 2.0, -1.5)).unwrap();
        lu = lu.max(lu_difference(&plan, a));
        vp = vp.max(a.power_check().unwrap().relative_error());
        eq = eq.max(a.worst_residual());
    }
    println!(
        "double butterfly over {} positions: LU {lu:.1e}, virtual power {vp:.1e}, equilibrium \
         {eq:.1e}",
        phis.len()
    );
    assert!(lu < 1e-10, "LU {lu:e}");
    assert!(vp < 1e-10, "virtual power {vp:e}");
    assert!(eq < 1e-12, "equilibrium {eq:e}");
}

/// The double butterfly's group at the reference input, in the independent unknowns of a
/// loop-closure formulation: the six links' angles only. Each link's hinges are fixed
/// vectors in its frame; the three independent loops (B→…, written below from the known
/// points C, D, B) close. Returns the loops' residual and its Jacobian by central
/// differences of the residual (exact enough for Newton to converge quadratically to
/// rounding, the converged points being the exact roots).
struct Loops {
    /// Per link (CE, EFG, BFJ, DHI, GH, IJ), its hinges' vectors in the drawn pose.
    at: std::collections::HashMap<&'static str, Point2<f64>>,
}

impl Loops {
    fn new() -> Self {
        let l = bundled::double_butterfly();
        let mut at = std::collections::HashMap::new();
        for j in &l.joints {
            let name: &'static str = Box::leak(j.name.clone().into_boxed_str());
            at.insert(name, Point2::new(j.at[0], j.at[1]));
        }
        Self { at }
    }

    /// The vector from hinge `p` to hinge `q` of one link, in the drawn pose, turned by `t`.
    fn arm(&self, p: &str, q: &str, t: f64) -> Vector2<f64> {
        let v = self.at[q] - self.at[p];
        let (s, c) = t.sin_cos();
        Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
    }

    /// Three loops from the known C, D and B, each a chain of link arms (angles: turns of
    /// CE, EFG, BFJ, DHI, GH, IJ from the drawn pose):
    /// C→E→G→H→D, C→E→F→B, D→I→J→B.
    fn residual(&self, t: &[f64; 6]) -> [f64; 6] {
        let [ce, efg, bfj, dhi, gh, ij] = *t;
        let c = self.at["C"];
        let d = self.at["D"];
        let b = self.at["B"];
        let e = c + self.arm("C", "E", ce);
        let g = e + self.arm("E", "G", efg);
        let h = g + self.arm("G", "H", gh);
        let r1 = h - (d + self.arm("D", "H", dhi));
        let f = e + self.arm("E", "F", efg);
        let r2 = f - (b + self.arm("B", "F", bfj));
        let i = d + self.arm("D", "I", dhi);
        let j = i + self.arm("I", "J", ij);
        let r3 = j - (b + self.arm("B", "J", bfj));
        [r1.x, r1.y, r2.x, r2.y, r3.x, r3.y]
    }

    fn solve(&self, mut t: [f64; 6]) -> Option<[f64; 6]> {
        for _ in 0..80 {
            let r = self.residual(&t);
            let mut jac = DMatrix::<f64>::zeros(6, 6);
            let h = 1e-7;
            for c in 0..6 {
                let (mut tp, mut tm) = (t, t);
                tp[c] += h;
                tm[c] -= h;
                let (rp, rm) = (self.residual(&tp), self.residual(&tm));
                for row in 0..6 {
                    jac[(row, c)] = (rp[row] - rm[row]) / (2.0 * h);
                }
            }
            let dt = jac.lu().solve(&(-DVector::from_row_slice(&r)))?;
            let step = dt.amax();
            let cut = if step > 0.5 { 0.5 / step } else { 1.0 };
            for c in 0..6 {
                t[c] += cut * dt[c];
            }
            if step < 1e-14 {
                let r = self.residual(&t);
                return (r.iter().fold(0.0f64, |m, x| m.max(x.abs())) < 1e-12).then_some(t);
            }
        }
        None
    }
}

/// The real assembly modes of the double butterfly's group at the reference input, by the
/// library's search (random angles, origins by least squares, Newton on the full closure)
/// and, independently, by Newton on the six loop angles from a seeded grid of starts: both
/// find the same set of modes, every mode closes to 1e-12 of the size and is regular, the
/// drawn pose is one of them, and more starts find no more.
#[test]
fn every_real_assembly_mode_at_the_reference_input() {
    let plan = plan();
    let size = plan.size();
    let (block, outer, reference) = plan.groups()[0].general_block().unwrap();
    let library = block.modes(&outer, size, 2000, 7).unwrap();
    let more = block.modes(&outer, size, 6000, 99).unwrap();
    for m in &library {
        assert!(block.residual(m, &outer) <= 1e-12 * size);
        assert!(block.conditioning(m, size) > 1e-10);
    }
    // The loop angles' search: the turns of each link from the drawn pose.
    let loops = Loops::new();
    let mut roots: Vec<[f64; 6]> = Vec::new();
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let same = |a: &[f64; 6], b: &[f64; 6]| {
        a.iter().zip(b).all(|(x, y)| {
            let d = (x - y).rem_euclid(TAU);
            d.min(TAU - d) < 1e-7
        })
    };
    // The start after which no new root turned up: the margin of the independent search.
    let mut last_new = 0;
    for k in 0..2000 {
        let start: [f64; 6] = std::array::from_fn(|_| TAU * next());
        if let Some(t) = loops.solve(start)
            && !roots.iter().any(|r| same(r, &t))
        {
            roots.push(t);
            last_new = k + 1;
        }
    }
    println!(
        "double butterfly at the reference input: {} real assembly modes by the library's \
         search (2000 starts), {} with 6000 starts, {} by Newton on the loop angles (2000 \
         starts, the last new one at start {last_new})",
        library.len(),
        more.len(),
        roots.len()
    );
    assert_eq!(library.len(), more.len());
    assert_eq!(library.len(), roots.len());
    // The drawn pose (all turns zero) is a mode.
    assert!(roots.iter().any(|r| same(r, &[0.0; 6])));
    assert!(library
        .iter()
        .any(|m: &GroupPose| m.distance(reference, size) <= 1e-9 * size));
}

/// A group of the 4th class (the closed contour l2-l3-l4-l5, l3 hinged to the frame, l2 held
/// by l6 from the crank and l4 by l7 from the frame) is one general group: it closes and its
/// reactions agree with the whole system round its range; with one of its hinges made a
/// sliding pair it is refused, naming the links left over.
#[test]
fn a_group_of_the_4th_class_is_solved_and_one_with_a_slider_is_named() {
    let json = |kind: &str| {
        format!(
            r#"{{
      "name": "4th class",
      "joints": [
        {{"name": "O1", "at": [0.0, 0.0]}}, {{"name": "A", "at": [0.1, 0.0]}},
        {{"name": "P", "at": [0.3, 0.2]}}, {{"name": "Q", "at": [0.5, 0.2]}},
        {{"name": "R", "at": [0.6, 0.4]}}, {{"name": "S", "at": [0.5, 0.6]}},
        {{"name": "T", "at": [0.3, 0.5]}}, {{"name": "U", "at": [0.8, 0.5]}},
        {{"name": "V", "at": [0.9, 0.1]}}, {{"name": "W", "at": [0.6, 0.0]{kind}}}
      ],
      "links": [
        {{"name": "frame", "joints": ["O1", "V", "W"]}},
        {{"name": "crank", "joints": ["O1", "A"]}},
        {{"name": "l2", "joints": ["P", "Q", "T"], "mass": {{"m": 1.0, "j": 0.01, "centre": [0.4, 0.3]}}}},
        {{"name": "l3", "joints": ["Q", "R", "W"], "mass": {{"m": 1.0, "j": 0.01, "centre": [0.55, 0.2]}}}},
        {{"name": "l4", "joints": ["R", "S", "U"], "mass": {{"m": 1.0, "j": 0.01, "centre": [0.6, 0.5]}}}},
        {{"name": "l5", "joints": ["S", "T"], "mass": {{"m": 0.5, "j": 0.005, "centre": [0.4, 0.55]}}}},
        {{"name": "l6", "joints": ["A", "P"], "mass": {{"m": 0.5, "j": 0.005, "centre": [0.2, 0.1]}}}},
        {{"name": "l7", "joints": ["U", "V"], "mass": {{"m": 0.5, "j": 0.005, "centre": [0.85, 0.3]}}}}
      ],
      "input": {{"link": "crank"}},
      "gravity": [0.0, -9.81]
    }}"#
        )
    };
    let plan = Plan::new(&Linkage::from_json(&json("")).unwrap()).unwrap();
    assert_eq!(plan.groups().len(), 1);
    assert_eq!(plan.groups()[0].kind, GroupKind::General);
    let (mut lu, mut closure) = (0.0f64, 0.0f64);
    let phis = sweep(&plan, 36);
    for &phi in &phis {
        let a = plan.analyse(Motion::new(phi, 5.0, 1.0)).unwrap();
        lu = lu.max(lu_difference(&plan, &a));
        for j in 0..plan.joint_names().len() {
            let [p, q] = plan.joint_links(j).unwrap();
            let gap = (a.joint_on(j, p).unwrap().p - a.joint_on(j, q).unwrap().p).norm();
            closure = closure.max(gap / plan.size());
        }
    }
    println!(
        "4th-class group over {} positions: LU {lu:.1e}, closure {closure:.1e}",
        phis.len()
    );
    assert!(lu < 1e-10, "{lu:e}");
    assert!(closure <= 1e-12, "{closure:e}");

    let slid = json(r#", "kind": {"prismatic": {"guide": "frame", "direction": [1.0, 0.0]}}"#);
    let err = Plan::new(&Linkage::from_json(&slid).unwrap()).unwrap_err();
    let Error::Description { item, problem } = &err else {
        panic!("{err}");
    };
    assert_eq!(item, "linkage");
    assert!(
        problem.contains("links l2, l3, l4, l5, l6, l7"),
        "{problem}"
    );
}
