//! The linkage engine against independent references: one LU solve of the whole linkage's
//! Newton–Euler system (all links at once, written here), the principle of virtual power,
//! every link's equilibrium, 8th-order finite differences of positions, random linkages from
//! random poses, and bad descriptions.

use nalgebra::{DMatrix, DVector, Point2, Vector2};
use proptest::prelude::*;
use std::f64::consts::TAU;
use std::sync::atomic::{AtomicUsize, Ordering};
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, At, Drive, Input, Joint, Link, Linkage, LoadSpec, Mass, Plan};
use tmm::Error;

fn bundled_all() -> Vec<Linkage> {
    let all = bundled::all();
    // The list covers every kind of group the engine solves.
    let kinds: std::collections::BTreeSet<&str> = all
        .iter()
        .flat_map(|l| Plan::new(l).unwrap().groups().to_vec())
        .map(|g| g.kind.label())
        .collect();
    assert_eq!(kinds.len(), 7, "{kinds:?}");
    all
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The whole linkage's Newton–Euler system, solved by LU: unknowns are every joint's reaction
/// (of the joint's first link on its second: x and y at a hinge; the normal force and the couple
/// at a sliding pair, reduced to the joint's point on its second link) and the drive's
/// magnitude. Returns the largest difference from the engine's reactions and balance,
/// relative to the largest reaction.
pub(super) fn lu_difference(plan: &Plan, a: &tmm::linkage::Analysis<'_>) -> f64 {
    let nl = plan.link_names().len();
    let nj = plan.joint_names().len();
    let n_eq = 3 * (nl - 1);
    let mut m = DMatrix::<f64>::zeros(n_eq, n_eq);
    let mut rhs = DVector::<f64>::zeros(n_eq);
    let row = |k: usize| 3 * (k - 1);
    let pole = |k: usize| a.link_motion(k).unwrap().origin.p;
    // Applied loads go to the right-hand side.
    for &(k, l) in a.applied_loads() {
        let r = row(k);
        rhs[r] -= l.force.x;
        rhs[r + 1] -= l.force.y;
        rhs[r + 2] -= l.moment + cross(l.point - pole(k), l.force);
    }
    let mut col = 0;
    let mut cols = Vec::new();
    for j in 0..nj {
        let [p, q] = plan.joint_links(j).unwrap().map(usize::from);
        let at = a.joint_on(j, q).unwrap().p;
        // A unit unknown: force f and couple c on q (and −f, −c on p).
        let mut put = |col: usize, f: Vector2<f64>, c: f64| {
            for (k, s) in [(q, 1.0), (p, -1.0)] {
                if k == 0 {
                    continue;
                }
                let r = row(k);
                m[(r, col)] += s * f.x;
                m[(r + 1, col)] += s * f.y;
                m[(r + 2, col)] += s * (c + cross(at - pole(k), f));
            }
        };
        if plan.is_prismatic(j).unwrap() {
            let d = a.guide_direction(j).unwrap();
            put(col, Vector2::new(-d.y, d.x), 0.0);
            put(col + 1, Vector2::zeros(), 1.0);
        } else {
            put(col, Vector2::x(), 0.0);
            put(col + 1, Vector2::y(), 0.0);
        }
        cols.push(col);
        col += 2;
    }
    // The drive.
    let input = plan.input_links()[0].index();
    let b = a.balances()[0];
    let r = row(input);
    let crank_coupling = plan.input_is_crank() && b.force == Vector2::zeros();
    let drive_dir = if crank_coupling {
        m[(r + 2, col)] = 1.0;
        Vector2::zeros()
    } else {
        let d = if plan.input_is_crank() {
            b.force / b.force.norm()
        } else {
            a.guide_direction(
                (0..nj)
                    .find(|&j| {
                        let [p, q] = plan.joint_links(j).unwrap().map(usize::from);
                        [p, q].contains(&input) && [p, q].contains(&0)
                    })
                    .unwrap(),
            )
            .unwrap()
        };
        m[(r, col)] = d.x;
        m[(r + 1, col)] = d.y;
        m[(r + 2, col)] = cross(b.point - pole(input), d);
        d
    };
    assert_eq!(col + 1, n_eq, "unknowns = equations for W = 1");
    let x = m.lu().solve(&rhs).expect("the whole system is regular");
    let mut scale: f64 = 0.0;
    let mut worst: f64 = 0.0;
    for j in 0..nj {
        let [_, q] = plan.joint_links(j).unwrap().map(usize::from);
        let re = a.reaction(j).unwrap();
        let load = re.load_on(q).unwrap();
        let at = a.joint_on(j, q).unwrap().p;
        let (f, c) = if plan.is_prismatic(j).unwrap() {
            let d = a.guide_direction(j).unwrap();
            (x[cols[j]] * Vector2::new(-d.y, d.x), x[cols[j] + 1])
        } else {
            (Vector2::new(x[cols[j]], x[cols[j] + 1]), 0.0)
        };
        // The engine's couple about the same point.
        let c_engine = load.moment + cross(load.point - at, load.force);
        let arm = plan.size();
        scale = scale.max(f.norm()).max(load.force.norm());
        worst = worst
            .max((f - load.force).norm())
            .max((c - c_engine).abs() / arm);
    }
    let drive = x[col];
    let engine = if crank_coupling {
        b.value
    } else {
        b.force.dot(&drive_dir)
    };
    let drive_scale = if crank_coupling { plan.size() } else { 1.0 };
    scale = scale.max(drive.abs() / drive_scale);
    worst = worst.max((drive - engine).abs() / drive_scale);
    worst / scale
}

#[test]
fn bundled_linkages_agree_with_the_whole_system_virtual_power_and_equilibrium() {
    let mut report = Vec::new();
    for l in bundled_all() {
        let plan = Plan::new(&l).unwrap();
        let (mut lu, mut vp, mut eq) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..72 {
            let phi = plan.reference_input() + TAU * f64::from(k) / 72.0;
            let a = plan.analyse(Motion::new(phi, 12.0, -7.0)).unwrap();
            lu = lu.max(lu_difference(&plan, &a));
            vp = vp.max(a.power_check().unwrap().relative_error());
            eq = eq.max(a.worst_residual());
        }
        report.push(format!(
            "{}: LU {lu:.1e}, virtual power {vp:.1e}, equilibrium {eq:.1e}",
            l.name
        ));
        assert!(lu < 1e-11, "{}: LU {lu:e}", l.name);
        assert!(vp < 1e-9, "{}: virtual power {vp:e}", l.name);
        assert!(eq < 1e-12, "{}: equilibrium {eq:e}", l.name);
    }
    println!("{}", report.join("\n"));
}

/// Eighth-order central differences (shared: tests/common/fd.rs).
pub(super) use crate::common::fd::fd8;

#[test]
fn velocities_and_accelerations_match_finite_differences_of_positions() {
    for l in bundled_all() {
        let plan = Plan::new(&l).unwrap();
        let (w, e) = (3.0, -2.0);
        // The step balances truncation (h⁸ times the 10th derivative) against rounding
        // (≈ 6.5·δ/h² for positions of noise δ: the second difference's weights sum to 6.5);
        // the shaper's and the triads' positions carry a few ulps more rounding (the triads'
        // are a root of the eliminated equation, polished by Newton on the closures). The
        // sliding triad's angles scatter by δ ≤ 1.4e-15 rad from position to position
        // (measured by the 8th difference at a step of 1e-6 over the 72 positions; its
        // conditioning stays above 0.44), so at h = 2e-3 the rounding alone reaches
        // 6.5·1.4e-15/4e-6·ω²/(ω² + |ε|) ≈ 1.9e-9 of the scale (1.3e-9 measured), above the
        // limit; at 8e-3 it is 1.2e-10 (7.5e-11 measured), and the truncation (7.1e-10 at
        // 1.6e-2, so ≈ 2.8e-12 at 8e-3 by the h⁸ law) stays below it.
        let h = match l.name.as_str() {
            "shaper" => 4e-3,
            "six-bar with a triad" | "six-bar with a sliding triad" => 8e-3,
            _ => 2e-3,
        };
        let mut worst: f64 = 0.0;
        for k in 0..72 {
            let phi = plan.reference_input() + TAU * (f64::from(k) + 0.3) / 72.0;
            let a = plan.kinematics(Motion::new(phi, w, e)).unwrap();
            // The nine positions the stencil reads, solved once for every coordinate below.
            let stencil: Vec<_> = (-4..=4)
                .map(|k| {
                    plan.kinematics(Motion::fixed(phi + f64::from(k) * h))
                        .unwrap()
                })
                .collect();
            let pos = |x: f64| &stencil[(((x - phi) / h).round() + 4.0) as usize];
            for j in 0..plan.joint_names().len() {
                for (c, get) in [(0, 0usize), (1, 1)] {
                    let f = |x: f64| pos(x).joint(j).unwrap().p[get];
                    let (d1, d2) = fd8(&f, phi, h);
                    let m = a.joint(j).unwrap();
                    let (v, acc) = (m.v[c], m.a[c]);
                    let scale = plan.size() * (w * w + e.abs());
                    worst = worst.max((v - d1 * w).abs() / scale);
                    worst = worst.max((acc - (d2 * w * w + d1 * e)).abs() / scale);
                }
            }
            // The slide of every sliding pair, also on a turning guide (the shaper's lever), where
            // its acceleration carries the s·ω² term of the guide's rotation.
            for j in (0..plan.joint_names().len()).filter(|&j| plan.is_prismatic(j).unwrap()) {
                let f = |x: f64| pos(x).slide(j).unwrap().value;
                let (d1, d2) = fd8(&f, phi, h);
                let m = a.slide(j).unwrap();
                let scale = plan.size() * (w * w + e.abs());
                worst = worst.max((m.rate - d1 * w).abs() / scale);
                worst = worst.max((m.accel - (d2 * w * w + d1 * e)).abs() / scale);
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
        assert!(worst < 1e-9, "{}: {worst:e}", l.name);
    }
}

// ---- random linkages from random poses -------------------------------------------------

fn pt() -> impl Strategy<Value = [f64; 2]> {
    [-1.0..1.0f64, -1.0..1.0f64]
}

/// A Stephenson III or Watt six-bar (or a four-bar when `six` is false) through random poses.
fn random_linkage(points: Vec<[f64; 2]>, watt: bool, six: bool, masses: Vec<f64>) -> Linkage {
    let names = ["O1", "A", "B", "O3", "C", "D", "O5"];
    let joints: Vec<Joint> = names
        .iter()
        .zip(&points)
        .map(|(n, p)| Joint::revolute(n, *p))
        .collect();
    let mass = |k: usize, a: [f64; 2], b: [f64; 2]| Mass::rod(masses[k], a, b);
    let mut links = vec![
        Link::new("frame", &["O1", "O3"]),
        Link::new("crank", &["O1", "A"]).with_mass(mass(0, points[0], points[1])),
    ];
    if !six {
        links.push(Link::new("coupler", &["A", "B"]).with_mass(mass(1, points[1], points[2])));
        links.push(Link::new("rocker", &["O3", "B"]).with_mass(mass(2, points[3], points[2])));
    } else if watt {
        // C on the coupler, D free, O5 on the rocker: E→G and F→G of a Watt chain.
        links.push(Link::new("coupler", &["A", "B", "C"]).with_mass(mass(1, points[1], points[4])));
        links
            .push(Link::new("rocker", &["O3", "B", "O5"]).with_mass(mass(2, points[3], points[6])));
        links.push(Link::new("link 4", &["C", "D"]).with_mass(mass(3, points[4], points[5])));
        links.push(Link::new("link 5", &["O5", "D"]).with_mass(mass(4, points[6], points[5])));
    } else {
        links[0] = Link::new("frame", &["O1", "O3", "O5"]);
        links.push(Link::new("coupler", &["A", "B", "C"]).with_mass(mass(1, points[1], points[4])));
        links.push(Link::new("rocker", &["O3", "B"]).with_mass(mass(2, points[3], points[2])));
        links.push(Link::new("link 4", &["C", "D"]).with_mass(mass(3, points[4], points[5])));
        links.push(Link::new("link 5", &["O5", "D"]).with_mass(mass(4, points[6], points[5])));
    }
    let n = if six { 7 } else { 4 };
    let last = if six { "link 5" } else { "rocker" };
    Linkage {
        joints: joints.into_iter().take(n).collect(),
        links,
        input: Input::crank("crank"),
        loads: vec![
            LoadSpec::Moment {
                link: last.to_owned(),
                moment: masses[0] * 10.0 - 20.0,
            },
            LoadSpec::Force {
                link: "coupler".to_owned(),
                at: At::name("B"),
                force: [masses[1] * 30.0, -50.0],
            },
        ],
        ..Linkage::default()
    }
}

/// The random linkages tried and those compared with the LU solve (the rest refused by the
/// plan, by the analysis near a dead point, or as ill-conditioned).
static TRIED: AtomicUsize = AtomicUsize::new(0);
static COMPARED: AtomicUsize = AtomicUsize::new(0);

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn random_four_bars_and_six_bars_decompose_and_match_the_whole_system(
        points in prop::collection::vec(pt(), 7),
        masses in prop::collection::vec(0.1..5.0f64, 5),
        kind in 0..3usize,
        w in -20.0..20.0f64,
        e in -50.0..50.0f64,
    ) {
        let tried = TRIED.fetch_add(1, Ordering::Relaxed) + 1;
        // Most random poses are compared with LU: a change that made planning or the
        // analysis fail (or the conditioning blow up) would skip them and still pass.
        let compared = COMPARED.load(Ordering::Relaxed);
        prop_assert!(tried < 200 || compared * 2 >= tried, "only {} of {} cases compared", compared, tried);
        let l = random_linkage(points, kind == 1, kind > 0, masses);
        let plan = match Plan::new(&l) {
            Ok(p) => p,
            // A random pose may put a group exactly at a dead point: the error names it.
            Err(Error::Description { item, .. }) => { prop_assert!(item.starts_with("group")); return Ok(()); }
            Err(other) => return Err(TestCaseError::fail(format!("{other}"))),
        };
        prop_assert_eq!(plan.groups().len(), if kind == 0 { 1 } else { 2 });
        let a = plan.analyse(Motion::new(plan.reference_input(), w, e));
        // The reference pose always assembles; only a group too near a dead point may fail,
        // and then the error names the group.
        let a = match a {
            Ok(a) => a,
            Err(Error::In { part, .. }) => { prop_assert!(part.starts_with("group")); return Ok(()) }
            Err(other) => return Err(TestCaseError::fail(format!("{other}"))),
        };
        // Well-conditioned groups only: the closed forms are as good as LU there.
        let cond = a.conditioning().iter().map(|c| c.condition).fold(1.0, f64::max);
        prop_assume!(cond < 1e3);
        // The reactions come from moment balances whose arms are the links: a link much
        // shorter than the linkage divides the rounding of its coordinates (of the linkage's
        // size) by its own length. The groups' conditioning does not see that, so the bound
        // carries the ratio too.
        let at = |n: &str| l.joints.iter().find(|j| j.name == n).unwrap().at;
        let shortest = l
            .links
            .iter()
            .flat_map(|k| {
                k.joints.iter().flat_map(|p| {
                    k.joints.iter().filter(move |q| *q != p).map(move |q| {
                        let (p, q) = (at(p), at(q));
                        (p[0] - q[0]).hypot(p[1] - q[1])
                    })
                })
            })
            .fold(f64::INFINITY, f64::min);
        let cond = cond * (plan.size() / shortest).max(1.0);
        let d = lu_difference(&plan, &a);
        COMPARED.fetch_add(1, Ordering::Relaxed);
        prop_assert!(d < 1e-13 * cond.max(10.0), "LU {} at condition {}", d, cond);
        prop_assert!(a.worst_residual() < 1e-12 * cond.max(10.0));
        if w.abs() > 1e-3 {
            prop_assert!(a.power_check().unwrap().relative_error() < 1e-11 * cond.max(10.0));
        }
    }
}

// ---- bad descriptions ------------------------------------------------------------------

fn described(e: Error) -> (String, String) {
    match e {
        Error::Description { item, problem } => (item, problem),
        other => panic!("expected a description error, got {other}"),
    }
}

#[test]
fn bad_descriptions_name_the_joint_link_or_field() {
    let base = bundled::four_bar();
    let check = |l: Linkage, item: &str, words: &str| {
        let (i, p) = described(Plan::new(&l).unwrap_err());
        assert!(i.contains(item) && p.contains(words), "{i}: {p}");
    };
    let mut l = base.clone();
    l.links[2].joints[1] = "Bx".into();
    check(l, "link coupler", "unknown joint \"Bx\"");
    let mut l = base.clone();
    l.links[3].joints.pop();
    check(l, "link rocker", "at least two");
    // An output naming nothing is found when the plan is made, not when strokes are asked.
    let mut l = base.clone();
    l.output = Some(tmm::linkage::Output::Angle("nosuch".into()));
    check(l, "field output", "nosuch");
    let mut l = base.clone();
    l.output = Some(tmm::linkage::Output::Slide("B".into()));
    check(l, "field output", "B");
    let mut l = base.clone();
    l.output = Some(tmm::linkage::Output::Y("Q".into()));
    check(l, "field output", "Q");
    let mut l = base.clone();
    l.joints[2].kind = tmm::linkage::JointKind::Prismatic {
        guide: "rocker".into(),
        direction: [0.0, 0.0],
    };
    check(l, "joint B", "non-zero");
    let mut l = base.clone();
    l.joints[1].at[0] = f64::NAN;
    check(l, "joint A", "finite");
    let mut l = base.clone();
    l.links[3].mass = Some(Mass::new(-2.0, 0.0, At::name("B")));
    check(l, "link rocker", "mass.m must be ≥ 0");
    let mut l = base.clone();
    l.input = Input::crank("coupler");
    check(l, "link coupler", "joints with the frame");
    let mut l = base.clone();
    l.input.drive = Drive::Gear {
        pitch_radius: 0.1,
        pitch_angle: 0.0,
        pressure_angle: 2.0,
    };
    check(l, "input.drive", "pressure_angle");
    let mut l = base.clone();
    l.loads.push(LoadSpec::Force {
        link: "rocker".into(),
        at: At::name("Z"),
        force: [1.0, 0.0],
    });
    check(l, "load 3", "\"Z\"");
    // A joint listed by three links is a hinge of three; here one the structure refuses,
    // and the error says how the hinge was taken.
    let mut l = base.clone();
    l.links[0].joints.push("B".into());
    check(
        l,
        "linkage",
        "hinge B joins 3 links [frame, coupler, rocker]",
    );
    // A third link hinged to the frame and the coupler's point: W = 0.
    let mut l = base.clone();
    l.joints.push(Joint::revolute("X", [0.5, 0.5]));
    l.joints.push(Joint::revolute("Y", [0.2, 0.2]));
    l.links[0].joints.push("X".into());
    l.links.push(Link::new("extra", &["X", "Y"]));
    l.links[2].joints.push("Y".into());
    check(l, "linkage", "W = 0");
    // An RPR whose sliding axis misses a hinge: the pose cannot close.
    let mut s = bundled::shaper();
    if let tmm::linkage::JointKind::Prismatic { direction, .. } = &mut s.joints[2].kind {
        *direction = [0.1, 1.0];
    }
    check(s, "joint P", "must pass through both");
    // A mode for a joint that is no group's inner joint.
    let mut l = base.clone();
    l.modes.push(tmm::linkage::Mode {
        joint: "A".into(),
        branch: tmm::kinematics::Branch::Minus,
    });
    check(l, "mode for joint A", "inner joint");
    // A Scotch yoke whose slot is turned along the yoke's guide: the RPP's links could slide
    // together.
    let mut y = bundled::scotch_yoke();
    if let tmm::linkage::JointKind::Prismatic { direction, .. } = &mut y.joints[2].kind {
        *direction = [-2.0, 0.0];
    }
    check(y, "group (block, yoke) RPP", "sin(alpha)");
    // The slotted rocker's frame guide turned along the rocker's slot: parallel PRP guides.
    let mut r = bundled::slotted_rocker();
    let slot = match &r.joints[4].kind {
        tmm::linkage::JointKind::Prismatic { direction, .. } => *direction,
        _ => unreachable!(),
    };
    if let tmm::linkage::JointKind::Prismatic { direction, .. } = &mut r.joints[6].kind {
        *direction = slot;
    }
    check(r, "group (block, slider) PRP", "parallel guides");
    // Three sliding pairs in one group (the yoke's hinge A made a sliding pair).
    let mut y = bundled::scotch_yoke();
    y.joints[1].kind = tmm::linkage::JointKind::Prismatic {
        guide: "crank".into(),
        direction: [1.0, 1.0],
    };
    check(y, "group (block, yoke)", "PPP group");
}

#[test]
fn prismatic_groups_match_their_closed_forms_over_a_turn() {
    // Scotch yoke: the yoke follows the crank pin's x, x = r·cos φ; ẋ and ẍ by differentiation.
    let plan = Plan::new(&bundled::scotch_yoke()).unwrap();
    let (r, w, e) = (0.1, 7.0, -3.0);
    let mut worst: f64 = 0.0;
    for k in 0..72 {
        let phi = TAU * (f64::from(k) + 0.25) / 72.0;
        let a = plan.kinematics(Motion::new(phi, w, e)).unwrap();
        let s = a.slide("Q").unwrap();
        let (sin, cos) = phi.sin_cos();
        let exact = [r * cos - r, -r * w * sin, -r * (w * w * cos + e * sin)];
        for (got, want) in [s.value, s.rate, s.accel].into_iter().zip(exact) {
            worst = worst.max((got - want).abs() / (r * (w * w + e.abs())));
        }
        // The block rides the slot: its height is the pin's.
        worst = worst.max((a.joint("S").unwrap().p.y - r * sin).abs() / r);
    }
    assert!(worst < 1e-14, "Scotch yoke: {worst:e}");

    // Slotted rocker: the slider sits where the rocker's line crosses y = y_O3 + 0.2, so
    // x = x_O3 + 0.2·cot θ with θ the rocker's angle; ẋ = −0.2·θ̇/sin²θ.
    let plan = Plan::new(&bundled::slotted_rocker()).unwrap();
    let o3 = plan
        .kinematics(Motion::fixed(0.0))
        .unwrap()
        .joint("O3")
        .unwrap()
        .p;
    let mut worst: f64 = 0.0;
    for k in 0..72 {
        let phi = TAU * (f64::from(k) + 0.25) / 72.0;
        let a = plan.kinematics(Motion::new(phi, w, e)).unwrap();
        let b = a.joint("B").unwrap().p - o3;
        let theta = b.y.atan2(b.x);
        let rate = a.link("rocker").unwrap().rate;
        let f = a.joint("F").unwrap();
        worst = worst.max((f.p.x - (o3.x + 0.2 / theta.tan())).abs() / 0.2);
        worst = worst.max((f.p.y - (o3.y + 0.2)).abs() / 0.2);
        worst = worst.max((f.v.x + 0.2 * rate / theta.sin().powi(2)).abs() / (0.2 * w));
    }
    assert!(worst < 1e-13, "slotted rocker: {worst:e}");
}

#[test]
fn a_dead_point_in_a_cycle_is_an_error_naming_the_group_and_the_cycle_goes_on() {
    // A parallelogram four-bar: all links collinear at φ1 = 0 and π.
    let l = Linkage {
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", [0.0, 0.1]),
            Joint::revolute("B", [0.3, 0.1]),
            Joint::revolute("O3", [0.3, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("rocker", &["O3", "B"]),
        ],
        input: Input::crank("crank"),
        ..Linkage::default()
    };
    let plan = Plan::new(&l).unwrap();
    let e = plan.analyse(Motion::new(0.0, 1.0, 0.0)).unwrap_err();
    assert!(
        matches!(e, Error::In { ref part, .. } if part.contains("(coupler, rocker) RRR")),
        "{e}"
    );
    assert!(plan.analyse(Motion::new(1.0, 1.0, 0.0)).is_ok());
    let b = plan
        .analyse(Motion::new(1.0, 1.0, 0.0))
        .unwrap()
        .joint("B")
        .unwrap()
        .p;
    // The parallelogram keeps its mode: B = A + (0.3, 0).
    assert!((b - Point2::new(0.1f64.mul_add(1f64.cos(), 0.3), 0.1 * 1f64.sin())).norm() < 1e-14);
}

#[test]
fn strokes_and_lock_positions() {
    let plan = Plan::new(&bundled::shaper()).unwrap();
    let out = tmm::linkage::Output::Slide("Q".into());
    let s = plan.strokes(&out, tmm::kinematics::Rotation::Ccw).unwrap();
    // At the extremes the ram's first transfer function vanishes.
    for phi in [s.start, s.end] {
        assert!(plan.transfer(&out, phi).unwrap().rate.abs() < 1e-12);
    }
    assert!(s.time_ratio > 1.0);
    assert_eq!(plan.lock_positions(0.3).unwrap(), None);
    // The ram works against the cut while its slide falls (the resistance acts backward only),
    // and that is the slower stroke: the working stroke starts at the maximum.
    assert!(!s.working_rises);
    let at = |phi: f64| plan.transfer(&out, phi).unwrap().value;
    assert!(at(s.start) > at(s.end));
    // The stroke is the range of the slide, sampled densely around the turn: the samples fall
    // short of each true extreme by at most max|s″|·h²/8 (h the step), and never overshoot.
    let n = 20_000;
    let h = TAU / f64::from(n);
    let tf: Vec<_> = (0..n)
        .map(|k| plan.transfer(&out, h * f64::from(k)).unwrap())
        .collect();
    let (hi, lo) = tf.iter().fold((f64::MIN, f64::MAX), |(hi, lo), m| {
        (hi.max(m.value), lo.min(m.value))
    });
    let curvature = tf.iter().map(|m| m.accel.abs()).fold(0.0, f64::max);
    let short = s.stroke - (hi - lo);
    assert!(
        short >= -1e-12 && short <= 2.0 * curvature * h * h / 8.0,
        "stroke {} vs sampled range {}",
        s.stroke,
        hi - lo
    );
    // Cutting on the other stroke (forward): the working stroke is then the faster one.
    let mut other = bundled::shaper();
    other.loads[0] = LoadSpec::Resistance {
        on: "Q".into(),
        forward: 1500.0,
        backward: 0.0,
        at: None,
    };
    let o = Plan::new(&other)
        .unwrap()
        .strokes(&out, tmm::kinematics::Rotation::Ccw)
        .unwrap();
    assert!(o.working_rises);
    assert_eq!((o.start, o.end), (s.end, s.start));
    assert!((o.time_ratio * s.time_ratio - 1.0).abs() < 1e-12);
    // A crank's own angle turns fully: no strokes, and the error says so.
    let e = plan
        .strokes(
            &tmm::linkage::Output::Angle("crank".into()),
            tmm::kinematics::Rotation::Ccw,
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("no extreme positions"), "{e}");
}

#[test]
fn transmission_angles_match_the_law_of_cosines_and_their_classical_minimum() {
    // Four-bar: the angle γ between coupler AB and rocker O3B follows from the triangle A B O3:
    // cos γ = (b² + c² − |A O3|²)/(2bc); μ is γ folded into [0, π/2].
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    let (a, b, c) = (0.1f64, 0.35f64, 0.3f64);
    let o3 = Vector2::new(0.4, 0.05);
    let d = o3.norm();
    let fold = |g: f64| g.min(std::f64::consts::PI - g);
    let mut worst: f64 = 0.0;
    for k in 0..72 {
        let phi = TAU * (f64::from(k) + 0.5) / 72.0;
        let an = plan.kinematics(Motion::fixed(phi)).unwrap();
        let ao3 = (o3 - Vector2::new(a * phi.cos(), a * phi.sin())).norm();
        let gamma = ((b * b + c * c - ao3 * ao3) / (2.0 * b * c)).acos();
        worst = worst.max((an.transmission_angle(0).unwrap() - fold(gamma)).abs());
    }
    assert!(worst < 1e-13, "{worst:e}");
    // Its minimum lies where the crank lines up with the frame: |A O3| = d ∓ a.
    let at_line = |ao3: f64| fold(((b * b + c * c - ao3 * ao3) / (2.0 * b * c)).acos());
    let classical = at_line(d - a).min(at_line(d + a));
    let (mu_min, phi) = plan.min_transmission_angle(0).unwrap();
    assert!(
        (mu_min - classical).abs() < 1e-12,
        "{mu_min} vs {classical}"
    );
    let frame_dir = o3.y.atan2(o3.x);
    let off = (phi - frame_dir).rem_euclid(std::f64::consts::PI);
    assert!(off.min(std::f64::consts::PI - off) < 1e-6, "at {phi}");
    // The Scotch yoke's slot is square to its guide (μ = π/2); the slotted rocker's PRP angle
    // is the rocker's angle to the horizontal guide.
    let y = Plan::new(&bundled::scotch_yoke()).unwrap();
    let ya = y.kinematics(Motion::fixed(0.7)).unwrap();
    assert!((ya.transmission_angle(0).unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    let r = Plan::new(&bundled::slotted_rocker()).unwrap();
    let ra = r.kinematics(Motion::fixed(0.7)).unwrap();
    let theta = ra.link("rocker").unwrap().value;
    let expect = fold(theta.rem_euclid(std::f64::consts::PI));
    assert!((ra.transmission_angle(1).unwrap() - expect).abs() < 1e-13);
    assert!(ra.transmission_angle(2).is_err());
}

/// Every group's smallest transmission angle in one sweep equals the group-by-group search
/// bit for bit (the same positions, the same refinement), on every bundled crank linkage;
/// a group without one (a general group) keeps its error in its place.
#[test]
fn all_groups_transmission_minima_equal_each_groups_search() {
    let mut groups = 0;
    for l in bundled::all() {
        let plan = Plan::new(&l).unwrap();
        let Ok(all) = plan.min_transmission_angles() else {
            assert!(plan.min_transmission_angle(0).is_err(), "{}", l.name);
            continue;
        };
        assert_eq!(all.len(), plan.groups().len());
        for (g, got) in all.iter().enumerate() {
            match (got, plan.min_transmission_angle(g)) {
                (Ok(a), Ok(b)) => assert_eq!(*a, b, "{} group {g}", l.name),
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                (a, b) => panic!("{} group {g}: {a:?} against {b:?}", l.name),
            }
            groups += 1;
        }
    }
    assert!(groups >= 14, "{groups} groups compared");
}

/// A bad gear drive is named by the input it belongs to.
#[test]
fn a_bad_gear_drive_names_its_input() {
    let gear = tmm::linkage::Drive::Gear {
        pitch_radius: -0.1,
        pitch_angle: 0.0,
        pressure_angle: 0.35,
    };
    let mut l = tmm::linkage::bundled::five_bar_robot();
    l.second_input.as_mut().unwrap().drive = gear;
    let e = tmm::linkage::Plan::new(&l).unwrap_err().to_string();
    assert!(
        e.contains("second_input.drive") && e.contains("pitch_radius"),
        "{e}"
    );
    let mut l = tmm::linkage::bundled::five_bar_robot();
    l.input.drive = gear;
    let e = tmm::linkage::Plan::new(&l).unwrap_err().to_string();
    assert!(
        e.contains("field input.drive") && e.contains("pitch_radius"),
        "{e}"
    );
}

/// A four-bar whose input cannot turn fully (a triple rocker: input 0.6, coupler 0.5, rocker
/// 0.7 on a frame of 1.0 m; s + l = 1.6 > p + q = 1.2, Grashof fails), in the pose with the
/// input at 90°.
fn rocker_input_four_bar() -> Linkage {
    let (o1, a, o3): ([f64; 2], [f64; 2], [f64; 2]) = ([0.0, 0.0], [0.0, 0.6], [1.0, 0.0]);
    // B 0.5 from A and 0.7 from O3, below the line A→O3.
    let (ab, bo) = (0.5_f64, 0.7_f64);
    let d = ((o3[0] - a[0]).powi(2) + (o3[1] - a[1]).powi(2)).sqrt();
    let x = (ab * ab - bo * bo + d * d) / (2.0 * d);
    let h = (ab * ab - x * x).sqrt();
    let u = [(o3[0] - a[0]) / d, (o3[1] - a[1]) / d];
    let b = [a[0] + x * u[0] + h * u[1], a[1] + x * u[1] - h * u[0]];
    Linkage {
        name: "rocker-input four-bar".to_owned(),
        joints: vec![
            Joint::revolute("O1", o1),
            Joint::revolute("A", a),
            Joint::revolute("B", b),
            Joint::revolute("O3", o3),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("input", &["O1", "A"]).with_mass(Mass::rod(0.5, o1, a)),
            Link::new("coupler", &["A", "B"]).with_mass(Mass::rod(0.4, a, b)),
            Link::new("rocker", &["O3", "B"]).with_mass(Mass::rod(0.6, o3, b)),
        ],
        input: Input::crank("input"),
        loads: vec![LoadSpec::Resistance {
            on: "rocker".to_owned(),
            forward: 5.0,
            backward: 5.0,
            at: None,
        }],
        ..Linkage::default()
    }
}

#[test]
fn a_rocking_input_sweeps_exactly_between_its_lock_angles() {
    use tmm::linkage::{Course, Output, Sweep};
    let plan = Plan::new(&rocker_input_four_bar()).unwrap();
    // The locks, by hand: A, B and O3 in line, |A − O3| = 0.5 + 0.7, so
    // 0.6² + 1 − 2·0.6·cos φ = 1.2²: φ = ±acos(−0.08/1.2).
    let lock = (-0.08_f64 / 1.2).acos();
    for (speed, from, to) in [(10.0, -lock, lock), (-4.0, lock, -lock)] {
        for n in [1, 2, 3, 12, 13, 360] {
            let course =
                Course::new(&plan, Some(&Output::Angle("rocker".into())), n, speed).unwrap();
            let Sweep::Rocking { from: f, to: t } = course.sweep else {
                panic!("not rocking: {:?}", course.sweep);
            };
            assert!(
                (f - from).abs() < 1e-12 && (t - to).abs() < 1e-12,
                "{f} {t}"
            );
            assert_eq!(course.inputs.len(), n);
            // It starts at a lock, reaches the other (n ≥ 2) and comes back, every position
            // inside the range and assembled.
            assert_eq!(course.inputs[0].value, f);
            if n >= 2 {
                assert_eq!(course.inputs[n / 2].value, t);
            }
            let (lo, hi) = (f.min(t), f.max(t));
            for (k, m) in course.inputs.iter().enumerate() {
                assert!(lo <= m.value && m.value <= hi, "{k}: {m:?}");
                if m.rate == 0.0 {
                    // A lock: the driven dyad at its dead point, the forces refused, the
                    // position there.
                    let e = plan.analyse(*m).expect_err("refused at a lock");
                    assert!(e.to_string().contains("at its dead point"), "{k}: {e}");
                    assert!(plan.kinematics(*m).is_ok());
                } else {
                    let a = plan.analyse(*m).unwrap();
                    assert!(a.worst_residual() < 1e-9, "{k}: {}", a.worst_residual());
                }
                // The input moves towards `to` on the way out, back towards `from` after.
                let out = k < n / 2 + 1;
                let expect = if k == 0 || k == n / 2 {
                    0.0
                } else if out {
                    (t - f).signum() * speed.abs()
                } else {
                    -(t - f).signum() * speed.abs()
                };
                assert_eq!(m.rate, expect, "{k} of {n}");
            }
            // The extremes: the two locks, and between them where the rocker stands still;
            // the rocker's angle over the whole sweep lies between its values there.
            let e = &course.extremes;
            assert_eq!(e.len(), 3, "{e:?}"); // one turning point of the rocker on the way
            assert_eq!((e[0], e[2]), (Motion::fixed(f), Motion::fixed(t)));
            let rocker = Output::Angle("rocker".into());
            let psi = |q: f64| plan.transfer(&rocker, q).unwrap();
            for m in &e[1..e.len() - 1] {
                assert!(psi(m.value).rate.abs() < 1e-9, "{m:?}: {:?}", psi(m.value));
            }
            let at: Vec<f64> = e.iter().map(|m| psi(m.value).value).collect();
            let (lo_psi, hi_psi) = at
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            for k in 0..=1000 {
                let q = lo + (hi - lo) * f64::from(k) / 1000.0;
                let v = psi(q).value;
                assert!(lo_psi - 1e-12 <= v && v <= hi_psi + 1e-12, "{q}: {v}");
            }
        }
    }
    // Past a lock (10⁻⁹ rad beyond the hand-made angle) the linkage does not close.
    for q in [lock, -lock] {
        let beyond = q + q.signum() * 1e-9;
        assert!(plan.kinematics(Motion::fixed(beyond)).is_err());
    }
    // A user's range inside the locks; one past them is refused, naming its end.
    let c = Course::rocking(&plan, 0.0, 1.0, 8, 2.0).unwrap();
    assert_eq!(c.sweep, Sweep::Rocking { from: 0.0, to: 1.0 });
    assert_eq!(c.inputs[4].value, 1.0);
    let e = Course::rocking(&plan, 0.0, 2.0, 8, 2.0).unwrap_err();
    assert!(e.to_string().contains("end of the rocking range"), "{e}");
    assert!(Course::rocking(&plan, 0.0, 0.0, 8, 2.0).is_err());
    assert!(Course::rocking(&plan, 0.0, f64::NAN, 8, 2.0).is_err());
    assert!(Course::rocking(&plan, 3.0, 0.0, 8, 2.0).is_err()); // 3 rad does not assemble
                                                                // A crank that turns fully keeps its turn.
    let crank = Plan::new(&bundled::four_bar()).unwrap();
    assert_eq!(
        Course::new(&crank, None, 12, 1.0).unwrap().sweep,
        Sweep::Turn
    );
}

/// A Peaucellier–Lipkin inversor: the crank O1A (0.45 m) turns about O1 = (0.45, 0), so A's
/// circle passes through the pivot O of the two long links (1.0 m); the rhombus A–C–P–D has
/// sides of 0.4 m. OA·OP = 1.0² − 0.4² = 0.84 m², so P runs on the line x = 0.84/0.9 m. The
/// crank cannot turn fully: the linkage locks where |OA| = 1.0 − 0.4, at φ = ±2·acos(2/3).
/// Joints of three links are two coincident joints (the engine's joints join two links).
fn peaucellier_lipkin() -> Linkage {
    let r = 0.45_f64;
    let (long, side) = (1.0_f64, 0.4_f64);
    let phi = 1.0_f64;
    let a = [r + r * phi.cos(), r * phi.sin()];
    // C and D: where the circle about O of the long links meets the circle about A.
    let d = a[0].hypot(a[1]);
    let x = (long * long - side * side + d * d) / (2.0 * d);
    let h = (long * long - x * x).sqrt();
    let u = [a[0] / d, a[1] / d];
    let c = [x * u[0] - h * u[1], x * u[1] + h * u[0]];
    let dd = [x * u[0] + h * u[1], x * u[1] - h * u[0]];
    let p = [c[0] + dd[0] - a[0], c[1] + dd[1] - a[1]];
    Linkage {
        name: "Peaucellier–Lipkin inversor".to_owned(),
        joints: vec![
            Joint::revolute("O", [0.0, 0.0]),
            Joint::revolute("O'", [0.0, 0.0]),
            Joint::revolute("O1", [r, 0.0]),
            Joint::revolute("A", a),
            Joint::revolute("A'", a),
            Joint::revolute("C", c),
            Joint::revolute("C'", c),
            Joint::revolute("D", dd),
            Joint::revolute("D'", dd),
            Joint::revolute("P", p),
        ],
        links: vec![
            Link::new("frame", &["O", "O'", "O1"]),
            Link::new("crank", &["O1", "A", "A'"]),
            Link::new("long 1", &["O", "C"]),
            Link::new("long 2", &["O'", "D"]),
            Link::new("side AC", &["A", "C", "C'"]),
            Link::new("side AD", &["A'", "D", "D'"]),
            Link::new("side CP", &["C'", "P"]),
            Link::new("side DP", &["D'", "P"]),
        ],
        input: Input::crank("crank"),
        ..Linkage::default()
    }
}

#[test]
fn the_peaucellier_lipkin_crank_rocks_between_its_locks_and_draws_a_straight_line() {
    use tmm::linkage::{Course, Sweep};
    let plan = Plan::new(&peaucellier_lipkin()).unwrap();
    let lock = 2.0 * (2.0_f64 / 3.0).acos();
    let course = Course::new(&plan, None, 36, 5.0).unwrap();
    let Sweep::Rocking { from, to } = course.sweep else {
        panic!("{:?}", course.sweep)
    };
    assert!(
        (from + lock).abs() < 1e-12 && (to - lock).abs() < 1e-12,
        "{from} {to}"
    );
    for m in &course.inputs {
        let a = plan.kinematics(*m).unwrap();
        let p = a.joint("P").unwrap();
        // On the line x = 0.84/0.9 (to 1e-9 m at the locks, where the groups are singular).
        assert!((p.p.x - 0.84 / 0.9).abs() < 1e-9, "{m:?}: {}", p.p.x);
        // And its velocity along it.
        assert!(
            p.v.x.abs() <= 1e-6 * p.v.norm().max(1.0),
            "{m:?}: {:?}",
            p.v
        );
    }
}
