//! Springs, dampers and torsion springs in the description, and hinges of three links.
//!
//! References written here, independent of the engine's spring code: each element's law from
//! the geometry the springless linkage's kinematics gives, its power by 8th-order finite
//! differences of lengths and angles (the balancing moment it adds is T·dL/dφ, c·ω·(dL/dφ)²,
//! M·dΔθ/dφ), one LU solve of the whole linkage for the reactions, and in the dynamics the
//! energy T + V (V from the laws here) conserved, or lost at the damper's power c·L̇².

use super::engine::{fd8, lu_difference};
use std::f64::consts::TAU;
use tmm::dynamics::{run, Rk4, RunOptions, State};
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::LinkageSystem;
use tmm::linkage::{bundled, Anchor, At, Joint, Link, Linkage, LoadSpec, Plan};
use tmm::Error;

use nalgebra::Point2;

const ANCHOR: [f64; 2] = [0.2, 0.5];
const DAMPER_ANCHOR: [f64; 2] = [0.0, 0.4];

fn spring() -> LoadSpec {
    LoadSpec::Spring {
        name: "s".into(),
        ends: [Anchor::on("frame", At::Coords(ANCHOR)), Anchor::named("E")],
        stiffness: 800.0,
        free_length: 0.15,
        preload: 20.0,
    }
}

fn damper(c: f64) -> LoadSpec {
    LoadSpec::Damper {
        name: "d".into(),
        ends: [
            Anchor::on("frame", At::Coords(DAMPER_ANCHOR)),
            Anchor::on("rocker", At::name("B")),
        ],
        c,
    }
}

fn torsion() -> LoadSpec {
    LoadSpec::TorsionSpring {
        name: "t".into(),
        links: ["frame".into(), "rocker".into()],
        stiffness: 30.0,
        free_angle: None,
        preload: 1.5,
    }
}

/// The bundled four-bar with `loads` instead of its own.
fn four_bar_with(loads: Vec<LoadSpec>, gravity: [f64; 2]) -> Linkage {
    let mut l = bundled::four_bar();
    l.loads = loads;
    l.gravity = gravity;
    l
}

fn point(plan: &Plan, name: &str, phi: f64) -> Point2<f64> {
    plan.kinematics(Motion::fixed(phi))
        .unwrap()
        .point(name)
        .unwrap()
        .p
}

fn distance(plan: &Plan, phi: f64) -> f64 {
    (point(plan, "E", phi) - Point2::from(ANCHOR)).norm()
}

fn damper_length(plan: &Plan, phi: f64) -> f64 {
    let k = plan.kinematics(Motion::fixed(phi)).unwrap();
    (k.joint("B").unwrap().p - Point2::from(DAMPER_ANCHOR)).norm()
}

fn rocker(plan: &Plan, phi: f64) -> f64 {
    plan.kinematics(Motion::fixed(phi))
        .unwrap()
        .link("rocker")
        .unwrap()
        .value
}

/// Each element adds to the balancing moment exactly the moment its power asks for; the
/// reactions agree with the LU solve of the whole linkage and every link is in equilibrium.
#[test]
fn each_element_adds_its_power_to_the_balancing_moment() {
    let bare = Plan::new(&four_bar_with(vec![], [0.0, -9.81])).unwrap();
    let cases = [
        ("spring", spring()),
        ("damper", damper(3.0)),
        ("torsion", torsion()),
    ];
    let (omega, h) = (12.0, 1e-3);
    let theta0 = rocker(&bare, bare.reference_input());
    let mut report = Vec::new();
    for (what, load) in cases {
        let plan = Plan::new(&four_bar_with(vec![load], [0.0, -9.81])).unwrap();
        let (mut worst, mut lu, mut eq, mut vp) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for k in 0..72 {
            let phi = bare.reference_input() + TAU * f64::from(k) / 72.0;
            let m = Motion::new(phi, omega, -5.0);
            let a = plan.analyse(m).unwrap();
            let m0 = bare.analyse(m).unwrap().balance(0).unwrap().value;
            let added = a.balance(0).unwrap().value - m0;
            let expected = match what {
                "spring" => {
                    let l = distance(&bare, phi);
                    let dl = fd8(&|x| distance(&bare, x), phi, h).0;
                    (20.0 + 800.0 * (l - 0.15)) * dl
                }
                "damper" => {
                    let dl = fd8(&|x| damper_length(&bare, x), phi, h).0;
                    3.0 * omega * dl * dl
                }
                _ => {
                    let mut tau = rocker(&bare, phi) - theta0;
                    tau -= TAU * (tau / TAU).round();
                    let dtheta = fd8(&|x| rocker(&bare, x), phi, h).0;
                    (1.5 + 30.0 * tau) * dtheta
                }
            };
            worst = worst.max((added - expected).abs() / (1.0 + expected.abs()));
            lu = lu.max(lu_difference(&plan, &a));
            eq = eq.max(a.worst_residual());
            vp = vp.max(a.power_check().unwrap().relative_error());
        }
        report.push(format!(
            "{what}: moment vs power {worst:.1e}, LU {lu:.1e}, equilibrium {eq:.1e}, virtual power {vp:.1e}"
        ));
        assert!(worst < 1e-9, "{what}: {worst:e}");
        assert!(lu < 1e-11, "{what}: LU {lu:e}");
        assert!(eq < 1e-12, "{what}: equilibrium {eq:e}");
        assert!(vp < 1e-9, "{what}: virtual power {vp:e}");
    }
    println!("{}", report.join("\n"));
}

/// The springs' energy reading is the law's: ½k(L − L₀)² + F₀(L − L₀) and the torsion
/// spring's, from lengths and angles measured here.
#[test]
fn spring_energy_is_the_laws_integral() {
    let plan = Plan::new(&four_bar_with(vec![spring(), torsion()], [0.0; 2])).unwrap();
    let theta0 = rocker(&plan, plan.reference_input());
    for k in 0..24 {
        let phi = TAU * f64::from(k) / 24.0;
        let x = distance(&plan, phi) - 0.15;
        let mut tau = rocker(&plan, phi) - theta0;
        tau -= TAU * (tau / TAU).round();
        let expected = 20.0 * x + 400.0 * x * x + 1.5 * tau + 15.0 * tau * tau;
        let kin = plan.kinematics(Motion::fixed(phi)).unwrap();
        let got = plan.spring_energy(&kin.pose()).unwrap();
        assert!(
            (got - expected).abs() < 1e-12 * (1.0 + expected.abs()),
            "{got} {expected}"
        );
    }
}

/// A free run of the spring-loaded four-bar (no motor, no gravity) from rest, RK4 with the
/// step `h` to `t_end`: the change of T + V at the end, ∫ L̇² dt of the damper (Simpson),
/// the largest T and the largest |E(t) − E(0)| along the run.
fn energy_drift(loads: Vec<LoadSpec>, h: f64, t_end: f64) -> (f64, f64, f64, f64) {
    let sys = LinkageSystem::from_linkage(&four_bar_with(loads, [0.0; 2])).unwrap();
    let plan = sys.plan().clone();
    let start = State::at_rest(nalgebra::Vector2::new(plan.reference_input() + 0.3, 0.0));
    let r = run(&sys, &Rk4, start, &RunOptions::until(t_end, h)).unwrap();
    let tr = &r.trajectory;
    let [q, qd] = [tr.q()[0], tr.qd()[0]];
    let theta0 = rocker(&plan, plan.reference_input());
    let mut e = Vec::with_capacity(q.len());
    let mut lost = Vec::with_capacity(q.len());
    for (i, (&phi, &w)) in q.iter().zip(qd).enumerate() {
        let k = plan.kinematics(Motion::turning(phi, w)).unwrap();
        let x = (k.point("E").unwrap().p - Point2::from(ANCHOR)).norm() - 0.15;
        let mut tau = k.link("rocker").unwrap().value - theta0;
        tau -= TAU * (tau / TAU).round();
        let v = 20.0 * x + 400.0 * x * x + 1.5 * tau + 15.0 * tau * tau;
        e.push(tr.kinetic()[i] + v);
        // The damper's power c·L̇², L̇ from the joints' velocities.
        let b = k.joint("B").unwrap();
        let u = (b.p - Point2::from(DAMPER_ANCHOR)).normalize();
        let rate: f64 = u.dot(&b.v);
        lost.push(rate * rate);
    }
    let swing = tr.kinetic().iter().cloned().fold(0.0, f64::max);
    // ∫ L̇² dt by the trapezoid rule of the recorded steps refined by Simpson where even.
    let n = lost.len() - usize::from(lost.len() % 2 == 0);
    let mut integral = lost[0] + lost[n - 1];
    for (i, v) in lost.iter().enumerate().take(n - 1).skip(1) {
        integral += if i % 2 == 1 { 4.0 } else { 2.0 } * v;
    }
    integral *= h / 3.0;
    let worst = e[..n].iter().map(|x| (x - e[0]).abs()).fold(0.0, f64::max);
    (e[n - 1] - e[0], integral, swing, worst)
}

/// Without a damper T + V is conserved to the integrator's error, which falls by about 2⁴
/// when the step halves (RK4).
#[test]
fn a_free_spring_loaded_linkage_keeps_its_energy() {
    let (_, _, swing, d1) = energy_drift(vec![spring(), torsion()], 2e-3, 1.0);
    let (_, _, _, d2) = energy_drift(vec![spring(), torsion()], 1e-3, 1.0);
    println!("energy drift {d1:.2e} J (h = 2 ms), {d2:.2e} J (1 ms); largest T {swing:.3} J");
    assert!(swing > 0.5, "the spring must move the linkage: T ≤ {swing}");
    assert!(d2.abs() < 1e-6 * swing, "{d2:e}");
    assert!(
        d2.abs() <= d1.abs() / 8.0 || d2.abs() < 1e-12 * swing,
        "{d1:e} -> {d2:e}"
    );
}

/// With a damper T + V falls by the damper's work ∫ c·L̇² dt (L̇ from the joints'
/// velocities here); the gap falls at least 2² when the step halves (RK4, Simpson).
#[test]
fn a_damper_takes_away_its_power() {
    let c = 0.8;
    let loads = vec![spring(), torsion(), damper(c)];
    let (d1, i1, swing, _) = energy_drift(loads.clone(), 2e-3, 1.0);
    let (d2, i2, _, _) = energy_drift(loads, 1e-3, 1.0);
    let (gap1, gap2) = ((d1 + c * i1).abs(), (d2 + c * i2).abs());
    println!(
        "energy lost {:.4} J, damper's work {:.4} J, gap {gap1:.1e} (h = 2 ms), {gap2:.1e} (1 ms)",
        -d2,
        c * i2
    );
    assert!(-d2 > 0.05 * swing, "the damper must take energy: {d2}");
    assert!(gap2 < 1e-7 * c * i2, "{gap2:e}");
    assert!(gap2 <= gap1 / 4.0 || gap2 < 1e-12, "{gap1:e} -> {gap2:e}");
}

fn described(e: Error) -> (String, String) {
    match e {
        Error::Description { item, problem } => (item, problem),
        other => panic!("not a description error: {other}"),
    }
}

#[test]
fn bad_springs_are_named_with_their_field() {
    let with = |load: LoadSpec| Plan::new(&four_bar_with(vec![load], [0.0; 2]));
    let mut bad = Vec::new();
    let LoadSpec::Spring { ends, .. } = spring() else {
        unreachable!()
    };
    let s = |stiffness: f64, free_length: f64, preload: f64, ends: [Anchor; 2]| LoadSpec::Spring {
        name: "s".into(),
        ends,
        stiffness,
        free_length,
        preload,
    };
    bad.push((
        with(s(-1.0, 0.1, 0.0, ends.clone())),
        "spring s",
        "stiffness",
    ));
    bad.push((
        with(s(1.0, f64::NAN, 0.0, ends.clone())),
        "spring s",
        "free_length",
    ));
    bad.push((
        with(s(1.0, 0.1, f64::INFINITY, ends.clone())),
        "spring s",
        "preload",
    ));
    let unknown = [ends[0].clone(), Anchor::named("Q")];
    bad.push((with(s(1.0, 0.1, 0.0, unknown)), "spring s", "\"Q\""));
    let ambiguous = [ends[0].clone(), Anchor::named("B")];
    bad.push((with(s(1.0, 0.1, 0.0, ambiguous)), "spring s", "`link`"));
    let foreign = [ends[0].clone(), Anchor::on("crank", At::name("B"))];
    bad.push((with(s(1.0, 0.1, 0.0, foreign)), "spring s", "does not hold"));
    let nowhere = [
        ends[0].clone(),
        Anchor {
            link: None,
            at: At::Coords([0.0, 1.0]),
        },
    ];
    bad.push((with(s(1.0, 0.1, 0.0, nowhere)), "spring s", "`link`"));
    let same = [Anchor::named("E"), Anchor::on("coupler", At::name("A"))];
    bad.push((with(s(1.0, 0.1, 0.0, same)), "spring s", "both ends"));
    bad.push((
        with(LoadSpec::Damper {
            name: String::new(),
            ends: ends.clone(),
            c: -0.5,
        }),
        "load 1 (damper)",
        "c must be ≥ 0",
    ));
    bad.push((
        with(LoadSpec::TorsionSpring {
            name: "t".into(),
            links: ["rocker".into(), "rocker".into()],
            stiffness: 1.0,
            free_angle: None,
            preload: 0.0,
        }),
        "torsion spring t",
        "itself",
    ));
    bad.push((
        with(LoadSpec::TorsionSpring {
            name: "t".into(),
            links: ["rocker".into(), "crank".into()],
            stiffness: 1.0,
            free_angle: Some(f64::NAN),
            preload: 0.0,
        }),
        "torsion spring t",
        "free_angle",
    ));
    for (r, item, word) in bad {
        let (i, p) = described(r.unwrap_err());
        assert_eq!(i, item, "{p}");
        assert!(p.contains(word), "{i}: {p} (wants {word})");
    }
}

/// A spring whose ends meet has no line of action: an error naming it, never a NaN.
#[test]
fn a_spring_whose_ends_meet_is_singular_by_name() {
    // Fastened at the crank's A and at the frame point where A passes at φ = π/2.
    let load = LoadSpec::Spring {
        name: "s".into(),
        ends: [
            Anchor::on("crank", At::name("A")),
            Anchor::on("frame", At::Coords([0.0, 0.1])),
        ],
        stiffness: 10.0,
        free_length: 0.0,
        preload: 1.0,
    };
    let plan = Plan::new(&four_bar_with(vec![load], [0.0; 2])).unwrap();
    let e = plan
        .analyse(Motion::turning(std::f64::consts::FRAC_PI_2, 1.0))
        .unwrap_err()
        .to_string();
    assert!(e.contains("spring s") && e.contains("distance"), "{e}");
    assert!(plan.analyse(Motion::turning(1.0, 1.0)).is_ok());
}

/// The four-bar's coupler and rocker meeting the extra link "arm" at one hinge B: written as
/// one joint of three links, it solves as the two coincident joints the engine used to need.
fn three_link_hinge(shared: bool) -> Linkage {
    let mut l = bundled::four_bar();
    l.loads.clear();
    let b = l.joints.iter().find(|j| j.name == "B").unwrap().at;
    l.joints.push(Joint::revolute("C", [0.55, 0.45]));
    l.joints.push(Joint::revolute("O5", [0.75, 0.1]));
    let hinge = if shared {
        "B"
    } else {
        l.joints.push(Joint::revolute("B2", b));
        l.links[3].joints.push("B2".into());
        "B2"
    };
    l.links.push(Link::new("arm", &[hinge, "C"]));
    l.links.push(Link::new("lever", &["O5", "C"]));
    l.links[0].joints.push("O5".into());
    l
}

#[test]
fn a_hinge_of_three_links_is_two_binary_joints() {
    let one = Plan::new(&three_link_hinge(true)).unwrap();
    let two = Plan::new(&three_link_hinge(false)).unwrap();
    assert_eq!(one.groups().len(), 2);
    for k in 0..36 {
        let m = Motion::new(f64::from(k) * TAU / 36.0, 7.0, 2.0);
        let (a, b) = (one.analyse(m).unwrap(), two.analyse(m).unwrap());
        for p in ["B", "C"] {
            let (x, y) = (a.joint(p).unwrap(), b.joint(p).unwrap());
            assert!(
                (x.p - y.p).norm() < 1e-15 && (x.v - y.v).norm() < 1e-12,
                "{p}"
            );
        }
        let (ma, mb) = (a.balance(0).unwrap().value, b.balance(0).unwrap().value);
        assert!((ma - mb).abs() < 1e-12 * (1.0 + mb.abs()), "{ma} {mb}");
        assert!(a.worst_residual() < 1e-12);
        assert!(lu_difference(&one, &a) < 1e-11);
    }
    // The hinge's part for the link that is not its centre's first partner is named for it.
    assert!(
        one.joint_names().iter().any(|n| n.starts_with("B:")),
        "{:?}",
        one.joint_names()
    );
}

#[test]
fn a_sliding_pair_of_three_links_is_refused_by_name() {
    let mut l = three_link_hinge(true);
    let b = l.joints.iter_mut().find(|j| j.name == "B").unwrap();
    *b = Joint::prismatic("B", b.at, "rocker", [1.0, 0.0]);
    let (item, problem) = described(Plan::new(&l).unwrap_err());
    assert_eq!(item, "joint B");
    assert!(problem.contains("prismatic"), "{problem}");
}

#[test]
fn springs_read_and_write_as_json() {
    let l = four_bar_with(vec![spring(), damper(1.0), torsion()], [0.0; 2]);
    let back = Linkage::from_json(&l.to_json().unwrap()).unwrap();
    assert_eq!(back, l);
    let text = r#"{"spring": {"ends": [{"link": "frame", "at": [0, 1]}, {"at": "E"}],
                   "stiffness": 5, "free_length": 0.2, "preload": 1}}"#;
    let s: LoadSpec = serde_json::from_str(text).unwrap();
    let LoadSpec::Spring {
        stiffness, ends, ..
    } = s
    else {
        panic!("{s:?}")
    };
    assert_eq!((stiffness, ends[1].link.clone()), (5.0, None));
    let typo =
        r#"{"spring": {"ends": [{"at": "E"}, {"at": "A"}], "stifness": 5, "free_length": 0}}"#;
    let e = serde_json::from_str::<LoadSpec>(typo)
        .unwrap_err()
        .to_string();
    assert!(e.contains("stifness"), "{e}");
}

/// A torsion spring between links that turn fully relative to each other (the crank and the
/// frame), or whose free angle lies half a turn from where its links go, would have its twist
/// jump a turn (read in (−π, π]) and its energy not conserved: it is refused by name, with
/// the twist it reached; the same spring on the rocker, which swings less than half a turn
/// from its free angle, is taken.
#[test]
fn a_torsion_spring_that_would_pass_half_a_turn_is_refused_by_name() {
    let on = |links: [&str; 2], free_angle: Option<f64>| {
        Plan::new(&four_bar_with(
            vec![LoadSpec::TorsionSpring {
                name: "clock".into(),
                links: links.map(String::from),
                stiffness: 2.0,
                free_angle,
                preload: 0.0,
            }],
            [0.0; 2],
        ))
    };
    let (item, problem) = described(on(["frame", "crank"], None).unwrap_err());
    assert_eq!(item, "torsion spring clock", "{problem}");
    assert!(
        problem.contains("frame") && problem.contains("crank") && problem.contains("half a turn"),
        "{problem}"
    );
    let bare = Plan::new(&four_bar_with(vec![], [0.0; 2])).unwrap();
    // The rocker's swing, read here from its angles over a turn of the crank.
    let angles: Vec<f64> = (0..720)
        .map(|k| {
            let phi = TAU * f64::from(k) / 720.0;
            let k = bare.kinematics(Motion::fixed(phi)).unwrap();
            k.link("rocker").unwrap().value
        })
        .collect();
    let theta0 = rocker(&bare, bare.reference_input());
    let swing = angles
        .iter()
        .map(|a| {
            let d = a - theta0;
            (d - TAU * (d / TAU).round()).abs()
        })
        .fold(0.0, f64::max);
    assert!(swing < 2.0, "{swing}");
    assert!(on(["frame", "rocker"], None).is_ok());
    // Free half a turn from the reference pose: the twist starts at ±π.
    let k0 = bare
        .kinematics(Motion::fixed(bare.reference_input()))
        .unwrap();
    let rocker_angle = theta0 - k0.link("frame").unwrap().value;
    let (item, problem) = described(
        on(
            ["frame", "rocker"],
            Some(rocker_angle + std::f64::consts::PI),
        )
        .unwrap_err(),
    );
    assert_eq!(item, "torsion spring clock", "{problem}");
    // Free a quarter turn away, the twist stays within π/2 + the swing < π.
    assert!(on(["frame", "rocker"], Some(rocker_angle + 1.0)).is_ok());
}

/// A triple-rocker four-bar whose input crank rocks: crank O1A = 1, coupler AB = 1, rocker
/// O3B = 1 with O3 = (1.5, 0) m (s + l = 2.5 > p + q = 2), drawn at φ = 0.5; the crank locks
/// where |AO3| = 2, at φ = ±acos(−1/4), with `loads`.
fn triple_rocker(loads: Vec<LoadSpec>) -> Linkage {
    let (s, c) = 0.5f64.sin_cos();
    // B: 1 from A and from O3, left of A → O3.
    let (dx, dy) = (1.5 - c, -s);
    let l = dx.hypot(dy);
    let h = (1.0 - 0.25 * l * l).sqrt();
    let b = [c + 0.5 * dx - h * dy / l, s + 0.5 * dy + h * dx / l];
    Linkage {
        name: "triple rocker".into(),
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", [c, s]),
            Joint::revolute("B", b),
            Joint::revolute("O3", [1.5, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("rocker", &["B", "O3"]),
        ],
        loads,
        ..Linkage::default()
    }
}

/// The torsion spring's range is decided over the input's exact range: on a crank that rocks
/// between lock positions, a spring between the frame and the crank whose twist reaches
/// π − 0.1 + 0.002 rad exactly at the upper lock (the crank's angle there is the closed form
/// acos(−1/4)) is refused, and with 0.004 rad more free angle (π − 0.1 − 0.002 at the lock) it
/// is taken; the lock lies between the samples of a 720-step grid over the turn (5.8e-3 rad
/// past the last sample below it), which would read the first twist below π − 0.1.
#[test]
fn a_torsion_spring_is_checked_up_to_the_exact_lock_position() {
    let hi = (-0.25f64).acos();
    let bare = Plan::new(&triple_rocker(vec![])).unwrap();
    let (lo, up) = bare
        .lock_positions(bare.reference_input())
        .unwrap()
        .unwrap();
    assert!(
        (up - hi).abs() < 1e-9 && (lo + hi).abs() < 1e-9,
        "{lo} {up}"
    );
    let on = |free: f64| {
        Plan::new(&triple_rocker(vec![LoadSpec::TorsionSpring {
            name: "clock".into(),
            links: ["frame".into(), "crank".into()],
            stiffness: 2.0,
            free_angle: Some(free),
            preload: 0.0,
        }]))
    };
    let margin = 0.1;
    let (item, problem) = described(on(hi - (std::f64::consts::PI - margin + 0.002)).unwrap_err());
    assert_eq!(item, "torsion spring clock", "{problem}");
    assert!(problem.contains("half a turn"), "{problem}");
    assert!(on(hi - (std::f64::consts::PI - margin - 0.002)).is_ok());
}
