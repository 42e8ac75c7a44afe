//! `Plan::assembly_modes`: every real assembly mode of a linkage at given inputs, against
//! independent counts — the double butterfly's six-link group by a reduction of its own (a
//! different driver and closing link from the library's, scanned at 2·10⁵ samples), a
//! four-bar's two, a six-bar's four, a triad's against the triad module's own solver — and
//! its refusals.

use nalgebra::{Point2, Vector2};
use std::f64::consts::TAU;
use tmm::kinematics::{triad_modes, Motion};
use tmm::linkage::{bundled, GroupKind, ModeOptions, ModeSearch, Plan};
use tmm::Error;

/// The drawn places of the double butterfly's joints, by name (read once).
fn drawn(name: &str) -> Point2<f64> {
    use std::sync::OnceLock;
    static AT: OnceLock<Vec<(String, Point2<f64>)>> = OnceLock::new();
    let at = AT.get_or_init(|| {
        bundled::double_butterfly()
            .joints
            .iter()
            .map(|j| (j.name.clone(), Point2::new(j.at[0], j.at[1])))
            .collect()
    });
    at.iter().find(|(n, _)| n == name).unwrap().1
}

/// `v` turned by `t`.
fn turn(v: Vector2<f64>, t: f64) -> Vector2<f64> {
    let (s, c) = t.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// The point where the circle round `a` of radius `ra` meets the circle round `b` of radius
/// `rb`, on side `sign` of a → b; `None` where they do not meet.
fn meet(a: Point2<f64>, ra: f64, b: Point2<f64>, rb: f64, sign: f64) -> Option<Point2<f64>> {
    // By the law of cosines at a: the angle between a → b and a → X.
    let d = (b - a).norm();
    let c = (ra * ra + d * d - rb * rb) / (2.0 * ra * d);
    if !(-1.0..=1.0).contains(&c) {
        return None;
    }
    let w = (b - a) / d;
    let along = turn(w, sign * c.acos());
    Some(a + ra * along)
}

/// The double butterfly's group at the reference input (the input link ACD as drawn, so C
/// and D are at their drawn places), reduced differently from the library: the driver is DHI
/// turning by θ about D, the dyads are IJ–BFJ (meeting at J) and CE–EFG (meeting at E), the
/// closing link GH. With the input turned by φ from the drawn pose, DHI turned by θ from
/// ACD's turn, returns the closure |G − H| − |G₀ − H₀| of branch choice `beta`, and the
/// turn of BFJ there.
fn independent(phi: f64, theta: f64, beta: usize) -> Option<(f64, f64)> {
    let p = drawn;
    // The input link ACD turned by φ from its drawn place about A.
    let a = p("A");
    let (b, c, d) = (p("B"), a + turn(p("C") - a, phi), a + turn(p("D") - a, phi));
    let theta = theta + phi;
    let h = d + turn(p("H") - p("D"), theta);
    let i = d + turn(p("I") - p("D"), theta);
    let s1 = if beta & 1 == 0 { 1.0 } else { -1.0 };
    let s2 = if beta & 2 == 0 { 1.0 } else { -1.0 };
    let j = meet(i, (p("J") - p("I")).norm(), b, (p("J") - p("B")).norm(), s1)?;
    let angle = |v: Vector2<f64>| v.y.atan2(v.x);
    let bfj = angle(j - b) - angle(p("J") - p("B"));
    let f = b + turn(p("F") - p("B"), bfj);
    let e = meet(c, (p("E") - p("C")).norm(), f, (p("E") - p("F")).norm(), s2)?;
    let efg = angle(e - f) - angle(p("E") - p("F"));
    let g = f + turn(p("G") - p("F"), efg);
    Some(((g - h).norm() - (p("G") - p("H")).norm(), bfj))
}

/// The turns of BFJ at every root of the independent reduction, by sign changes over
/// `samples` samples of θ on each branch choice, each bisected.
fn independent_roots(phi: f64, samples: usize) -> Vec<f64> {
    let mut roots = Vec::new();
    for beta in 0..4 {
        let at = |k: usize| TAU * k as f64 / samples as f64;
        for k in 0..samples {
            let (t0, t1) = (at(k), at(k + 1));
            let (Some((f0, _)), Some((f1, _))) =
                (independent(phi, t0, beta), independent(phi, t1, beta))
            else {
                continue;
            };
            if (f0 < 0.0) == (f1 < 0.0) {
                continue;
            }
            let (mut lo, mut hi, mut flo) = (t0, t1, f0);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                let Some((fm, _)) = independent(phi, mid, beta) else {
                    break;
                };
                if (fm < 0.0) == (flo < 0.0) {
                    (lo, flo) = (mid, fm);
                } else {
                    hi = mid;
                }
            }
            roots.push(independent(phi, lo, beta).unwrap().1);
        }
    }
    roots
}

/// The smallest difference of two angles, rad.
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

#[test]
fn the_double_butterfly_has_eight_real_modes_at_its_reference_input_by_two_reductions() {
    let plan = Plan::new(&bundled::double_butterfly()).unwrap();
    let size = plan.size();
    let phi = plan.reference_input();
    let all = plan.assembly_modes(Motion::fixed(phi)).unwrap();
    let [group] = all.groups.as_slice() else {
        panic!("one group: {:?}", all.groups)
    };
    assert_eq!(group.kind, GroupKind::General);
    let names = plan.link_names();
    let ModeSearch::Reduction {
        driver, closing, ..
    } = group.search
    else {
        panic!("the butterfly's group reduces: {:?}", group.search)
    };
    println!(
        "library: driver {}, closing {}; modes {}",
        names[driver],
        names[closing],
        all.total()
    );
    // The test's reduction differs from the library's in driver and closing link.
    assert!(names[driver] != "DHI" && names[closing] != "GH");
    let roots = independent_roots(0.0, 200_000);
    println!(
        "independent reduction (DHI driven, GH closing, 2e5 samples): {} roots",
        roots.len()
    );
    assert_eq!(roots.len(), 8);
    assert_eq!(all.total(), roots.len());
    assert_eq!(group.count(), Some(8));
    assert!(all.is_product() && all.is_exhaustive());
    // Every mode closes to 1e-12 of the size, and the modes are the independent roots: the
    // turn of BFJ from its drawn angle matches one root each, one to one.
    let bfj = plan.link_id("BFJ").unwrap().index();
    let r = all.reference.expect("the engine's mode is one of them");
    // At the reference input the engine's mode is the drawn pose: BFJ has not turned.
    let bfj_now = all.modes[r].frames[bfj].1;
    let mut matched = vec![false; roots.len()];
    for m in &all.modes {
        assert!(m.gap <= 1e-12 * size, "gap {:e}", m.gap);
        // BFJ's frame angle turns with the link: its turn from the reference pose.
        let t = m.frames[bfj].1 - bfj_now;
        let hit = roots
            .iter()
            .position(|&r| angle_gap(r, t) < 1e-9)
            .unwrap_or_else(|| panic!("turn {t} of BFJ is no independent root: {roots:?}"));
        assert!(!matched[hit], "two modes at one root");
        matched[hit] = true;
    }
    assert!(matched.iter().all(|&m| m));
    assert!(roots.iter().any(|&t| angle_gap(t, 0.0) < 1e-12));
}

#[test]
fn the_double_butterflys_count_agrees_with_the_independent_reduction_round_its_range() {
    // Inputs from the drawn pose forward by 0.1 rad steps while the engine's mode assembles:
    // the library's count equals the independent reduction's at 2·10⁴ samples.
    let plan = Plan::new(&bundled::double_butterfly()).unwrap();
    let size = plan.size();
    let mut counts = Vec::new();
    for k in 0..8 {
        let phi = 0.1 * f64::from(k);
        let Ok(all) = plan.assembly_modes(Motion::fixed(plan.reference_input() + phi)) else {
            break;
        };
        for m in &all.modes {
            assert!(m.gap <= 1e-12 * size);
        }
        let own = independent_roots(phi, 20_000).len();
        assert_eq!(all.total(), own, "φ = reference + {phi}");
        counts.push(own);
    }
    println!("double butterfly, counts from the reference input by 0.1 rad: {counts:?}");
    assert!(counts.len() >= 3, "{counts:?}");
}

#[test]
fn a_four_bar_has_two_modes_and_a_six_bar_four() {
    for (l, n) in [
        (bundled::four_bar(), 2),
        (bundled::watt_six_bar(), 4),
        (bundled::stephenson_six_bar(), 4),
    ] {
        let plan = Plan::new(&l).unwrap();
        let all = plan
            .assembly_modes(Motion::fixed(plan.reference_input()))
            .unwrap();
        assert_eq!(all.total(), n, "{}", plan.name());
        assert!(all.is_product());
        assert!(all.reference.is_some());
        for m in &all.modes {
            assert!(m.gap <= 1e-12 * plan.size(), "{}: {:e}", plan.name(), m.gap);
        }
        // Two RRR dyads' modes are distinct: no two assemblies coincide.
        for (i, a) in all.modes.iter().enumerate() {
            for b in &all.modes[..i] {
                let far = a.frames.iter().zip(&b.frames).any(|(p, q)| {
                    (p.0 - q.0).norm() > 1e-6 * plan.size() || angle_gap(p.1, q.1) > 1e-6
                });
                assert!(far, "{}: two modes coincide", plan.name());
            }
        }
    }
}

#[test]
fn a_triads_count_is_the_triad_modules_own() {
    let plan = Plan::new(&bundled::six_bar_triad()).unwrap();
    let kin = plan
        .kinematics(Motion::fixed(plan.reference_input()))
        .unwrap();
    let all = plan
        .assembly_modes(Motion::fixed(plan.reference_input()))
        .unwrap();
    let mut expected = 1;
    for (g, group) in plan.groups().iter().enumerate() {
        let n = match group.kind {
            GroupKind::Triad => {
                let [outer, inner] = group.triad_joints().unwrap();
                let names = plan.joint_names();
                let a = outer.map(|j| kin.joint(names[j].as_str()).unwrap().p);
                let b = inner.map(|j| kin.joint(names[j].as_str()).unwrap().p);
                // The triad's dimensions from its pose at the reference input.
                let l = [0, 1, 2].map(|i| (b[i] - a[i]).norm());
                let u = (b[1] - b[0]) / (b[1] - b[0]).norm();
                let w = b[2] - b[0];
                let dims = tmm::kinematics::TriadDims::new(
                    l,
                    (b[1] - b[0]).norm(),
                    w.dot(&u),
                    u.x * w.y - u.y * w.x,
                );
                triad_modes(a, &dims).unwrap().len()
            }
            _ => 2,
        };
        assert_eq!(all.groups[g].count(), Some(n), "{}", group.name);
        expected *= n;
    }
    assert_eq!(all.total(), expected);
    assert!(all.reference.is_some());
    for m in &all.modes {
        assert!(m.gap <= 1e-12 * plan.size());
    }
}

#[test]
fn bad_inputs_are_refused_and_the_search_is_bounded() {
    let plan = Plan::new(&bundled::double_butterfly()).unwrap();
    let phi = plan.reference_input();
    assert!(plan.assembly_modes(Motion::fixed(f64::NAN)).is_err());
    assert!(plan
        .assembly_modes(tmm::linkage::Inputs::two(
            Motion::fixed(phi),
            Motion::fixed(0.0)
        ))
        .is_err());
    let e = plan
        .assembly_modes_with(Motion::fixed(phi), &ModeOptions::default().with_samples(3))
        .unwrap_err();
    assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
    let e = plan
        .assembly_modes_with(
            Motion::fixed(phi),
            &ModeOptions::default().with_max_modes(3),
        )
        .unwrap_err();
    assert!(matches!(e, Error::Budget { .. }), "{e}");
    // An input outside a rocking linkage's range: the group that cannot close is named.
    let cheb = Plan::new(&bundled::peaucellier_lipkin()).unwrap();
    let e = cheb
        .assembly_modes(Motion::fixed(cheb.reference_input() + 3.0))
        .unwrap_err();
    assert!(matches!(e, Error::In { .. }), "{e}");
    println!("{e}");
}
