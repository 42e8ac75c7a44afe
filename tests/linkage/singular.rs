//! Positions at a dead centre: a four-bar stretched straight (its coupler and rocker along
//! one line) at an input angle where that happens exactly; `Plan::position` returns the
//! position (closed to 1e-12 of the size, the joint on the line) and the rates as the
//! singular measure, while a regular position gives the full kinematics unchanged.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use tmm::kinematics::Motion;
use tmm::linkage::{Joint, Link, Linkage, Plan};
use tmm::Error;

/// Crank O P of length 1 about O = (0, 0), coupler P B of 2 and rocker B Q of 1 about
/// Q = (−2, 0), drawn at φ = `phi` with B to the left of P → Q: at φ = 0 the pin P = (1, 0)
/// is 3 = 2 + 1 from Q, and the dyad is stretched straight (B = (−1, 0)); |PQ| ≤ 3 for every
/// φ, so the crank turns through it.
fn stretched(phi: f64) -> Linkage {
    let (s, c) = phi.sin_cos();
    let (dx, dy) = (-2.0 - c, -s);
    let l = dx.hypot(dy);
    let x = 0.5 * (l + 3.0 / l);
    let h = (4.0 - x * x).sqrt();
    let b = [c + (x * dx - h * dy) / l, s + (x * dy + h * dx) / l];
    Linkage {
        name: "stretched four-bar".into(),
        joints: vec![
            Joint::revolute("O", [0.0, 0.0]),
            Joint::revolute("P", [c, s]),
            Joint::revolute("B", b),
            Joint::revolute("Q", [-2.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O", "Q"]),
            Link::new("crank", &["O", "P"]),
            Link::new("coupler", &["P", "B"]),
            Link::new("rocker", &["B", "Q"]),
        ],
        ..Linkage::default()
    }
}

#[test]
fn the_position_at_an_exact_dead_centre_with_the_rates_singular() {
    let plan = Plan::new(&stretched(0.5)).unwrap();
    let size = plan.size();
    let full = plan.kinematics(Motion::new(0.0, 1.5, 0.0));
    assert!(full.is_err());
    let at = plan.position(Motion::new(0.0, 1.5, 0.0)).unwrap();
    let k = at.pose();
    let (p, b) = (k.joint("P").unwrap().p, k.joint("B").unwrap().p);
    let closure = (0..plan.joint_names().len())
        .map(|j| {
            let [l0, l1] = plan.joint_links(j).unwrap();
            (k.joint_on(j, l0).unwrap().p - k.joint_on(j, l1).unwrap().p).norm()
        })
        .fold(0.0, f64::max);
    println!("dead centre: B = {b:?}, closure {closure:.1e}");
    assert!(closure <= 1e-12 * size, "{closure:e}");
    // B on the line P Q, 2 from P: (−1, 0) to the accuracy of a double root (√ε of the
    // size).
    assert!((p - nalgebra::Point2::new(1.0, 0.0)).norm() < 1e-15);
    assert!(
        (b - nalgebra::Point2::new(-1.0, 0.0)).norm() < 1e-7 * size,
        "{b:?}"
    );
    match at.rates() {
        Err(Error::In { part, source }) => {
            assert!(part.contains("coupler"), "{part}");
            assert!(
                matches!(*source, Error::Singular { measure: "sin(phi3 - phi2)", value, .. } if value.abs() < 1e-7),
                "{source}"
            );
        }
        other => panic!("{other:?}"),
    }
    // Away from the dead centre the position is the full kinematics, bit for bit.
    let m = Motion::new(FRAC_PI_2, 1.5, -0.5);
    let at = plan.position(m).unwrap();
    let k = plan.kinematics(m).unwrap();
    let r = at.rates().unwrap();
    for j in 0..plan.joint_names().len() {
        assert_eq!(r.joint(j).unwrap(), k.joint(j).unwrap());
    }
}

/// Crank O P of length 1, rod P B of 4, slider B on the guide y = −3 of the frame, drawn at
/// φ = 0.5 with B ahead of P along the guide. The pin's distance from the guide, 3 + sin φ,
/// reaches the rod's length only at φ = π/2: there the rod stands across the guide (its
/// circle touches the guide's line), B = (0, −3), and the crank turns through it.
fn touching_slider_crank() -> Linkage {
    let (s, c) = 0.5f64.sin_cos();
    let bx = c + (16.0 - (s + 3.0) * (s + 3.0)).sqrt();
    Linkage {
        name: "slider-crank touching its guide".into(),
        joints: vec![
            Joint::revolute("O", [0.0, 0.0]),
            Joint::revolute("P", [c, s]),
            Joint::revolute("B", [bx, -3.0]),
            Joint::prismatic("G", [bx, -3.0], "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O", "G"]),
            Link::new("crank", &["O", "P"]),
            Link::new("rod", &["P", "B"]),
            Link::new("slider", &["B", "G"]),
        ],
        ..Linkage::default()
    }
}

#[test]
fn the_position_of_an_rrp_dyad_across_its_guide_with_the_rates_singular() {
    let plan = Plan::new(&touching_slider_crank()).unwrap();
    let m = Motion::new(FRAC_PI_2, 1.5, 0.0);
    assert!(plan.kinematics(m).is_err());
    let at = plan.position(m).unwrap();
    let k = at.pose();
    let b = k.joint("B").unwrap().p;
    let p = k.joint("P").unwrap().p;
    println!(
        "RRP across its guide: B = {b:?}, |PB| − 4 = {:.1e}",
        (b - p).norm() - 4.0
    );
    // The tangent point: under P on the guide, the rod's length to rounding.
    assert!(
        (b - nalgebra::Point2::new(0.0, -3.0)).norm() < 1e-12,
        "{b:?}"
    );
    assert!(((b - p).norm() - 4.0).abs() < 1e-12);
    assert!(k.link("rod").unwrap().value.sin() < -1.0 + 1e-15);
    match at.rates() {
        Err(Error::In { part, source }) => {
            assert!(part.contains("rod"), "{part}");
            assert!(
                matches!(*source, Error::Singular { measure: "cos(phi2 - phi4)", value, .. } if value.abs() < 1e-12),
                "{source}"
            );
        }
        other => panic!("{other:?}"),
    }
    // Near it, the closed form: the position is the full kinematics', bit for bit.
    let m = Motion::new(1.2, 1.5, -0.5);
    let r = plan.position(m).unwrap();
    let k = plan.kinematics(m).unwrap();
    for j in 0..plan.joint_names().len() {
        assert_eq!(r.rates().unwrap().joint(j).unwrap(), k.joint(j).unwrap());
    }
}

/// A slider-crank driven by its slider: crank O A of `R` about O, rod A B of `L`, B on the
/// guide y = `E` of the frame, drawn with the crank at 1 rad (above the guide's line).
const R: f64 = 0.05;
const L: f64 = 0.2;
const E: f64 = 0.02;

fn piston_driven() -> (Linkage, f64) {
    let (s, c) = 1.0f64.sin_cos();
    let a = [R * c, R * s];
    let xb = a[0] + (L * L - (E - a[1]).powi(2)).sqrt();
    let mut l = Linkage {
        name: "piston-driven slider-crank".into(),
        joints: vec![
            Joint::revolute("O", [0.0, 0.0]),
            Joint::revolute("A", a),
            Joint::revolute("B", [xb, E]),
            Joint::prismatic("P", [xb, E], "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O", "P"]),
            Link::new("crank", &["O", "A"]),
            Link::new("rod", &["A", "B"]),
            Link::new("piston", &["B", "P"]),
        ],
        ..Linkage::default()
    };
    l.input = tmm::linkage::Input::crank("piston");
    (l, xb)
}

/// The slider sweeps its stroke out on the drawn mode and back on `plan.through(end)`, then
/// `through` the other end again: the crank it drives turns on in one sense, a whole turn
/// (−2π) over the two sweeps, with no step back or jump; at each dead centre the two modes
/// give one position. The stroke's ends are exact: B at √((L ± R)² − E²).
#[test]
fn a_slider_carries_its_crank_on_through_both_dead_centres() {
    let (linkage, xb) = piston_driven();
    let plan = Plan::new(&linkage).unwrap();
    let lo = ((L - R).powi(2) - E * E).sqrt() - xb;
    let hi = ((L + R).powi(2) - E * E).sqrt() - xb;
    let back = plan.through(Motion::fixed(hi)).unwrap();
    let again = back.through(Motion::fixed(lo)).unwrap();
    let branches = |p: &Plan| p.groups().iter().map(|g| g.branch).collect::<Vec<_>>();
    assert_ne!(branches(&back), branches(&plan));
    assert_eq!(branches(&again), branches(&plan));
    let crank = |p: &Plan, s: f64| {
        let at = p.position(Motion::fixed(s)).unwrap();
        let a = at.pose().joint("A").unwrap().p;
        (a.y.atan2(a.x), a)
    };
    // The dead centres: both modes give one position (a double root: to √ε of the size).
    for s in [lo, hi] {
        let (_, a) = crank(&plan, s);
        let (_, b) = crank(&back, s);
        assert!((a - b).norm() < 1e-7 * (R + L), "{s}: {a:?} vs {b:?}");
    }
    let n = 2000;
    let out = (0..=n).map(|k| (&plan, lo + (hi - lo) * f64::from(k) / f64::from(n)));
    let home = (1..=n).map(|k| (&back, hi - (hi - lo) * f64::from(k) / f64::from(n)));
    let (mut turned, mut last, mut widest) = (0.0f64, None::<f64>, 0.0f64);
    for (p, s) in out.chain(home) {
        let (phi, _) = crank(p, s);
        if let Some(prev) = last {
            let step = (phi - prev + PI).rem_euclid(TAU) - PI;
            assert!(step < 0.0, "the crank stepped back at s = {s}: {step:e}");
            widest = widest.max(-step);
            turned += step;
        }
        last = Some(phi);
    }
    println!("through both dead centres: turned {turned:.12} rad, widest step {widest:.3e}");
    assert!((turned + TAU).abs() < 1e-6, "{turned}");
    // No jump: the widest step is the slope near a dead centre (√ of the slide's step).
    assert!(widest < 0.1, "{widest}");
    // Away from a dead centre there is no mode to change, and the error names the dyad.
    match plan.through(Motion::fixed(0.5 * (lo + hi))) {
        Err(Error::Description { item, problem }) => {
            assert_eq!(item, "inputs");
            assert!(
                problem.contains("crank") && problem.contains("determinant"),
                "{problem}"
            );
        }
        other => panic!("{other:?}"),
    }
}

/// A six-bar with a triad whose first leg's outer joint A1 rides a crank (r = 0.3 about
/// O = A1* + (0, 0.3)), drawn at φ = −π/2 − 0.05, built so that at φ = −π/2 (A1 = A1*) the
/// triad sits exactly at a branch point: the pose B1 = (0, 0), B2 = (1, 0), B3 = (0.4, 0.8)
/// with each leg A_i B_i along the line from B_i through P = (0.5, 2), so the three legs'
/// lines meet at P (det K = 0) and two of its modes merge there. The drawn pose is the mode
/// nearest that branch pose at the drawn angle (found by `triad_modes`).
fn triad_at_a_branch_point() -> (Linkage, [nalgebra::Point2<f64>; 3]) {
    use nalgebra::Point2;
    use tmm::kinematics::{triad_modes, TriadDims, TriadPose};
    let b = [
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.4, 0.8),
    ];
    let p = Point2::new(0.5, 2.0);
    let l = [1.1, 0.9, 0.7];
    let a: [Point2<f64>; 3] = std::array::from_fn(|i| b[i] - l[i] * (b[i] - p).normalize());
    let (r, o) = (0.3, a[0] + nalgebra::Vector2::new(0.0, 0.3));
    let phi = -FRAC_PI_2 - 0.05;
    let a1 = o + r * nalgebra::Vector2::new(phi.cos(), phi.sin());
    let dims = TriadDims::new(l, 1.0, 0.4, 0.8);
    let branch = TriadPose {
        b,
        theta: 0.0,
        phi: [0.0; 3],
        det: 0.0,
    };
    let drawn = *triad_modes([a1, a[1], a[2]], &dims)
        .unwrap()
        .nearest(&branch);
    let at = |q: Point2<f64>| [q.x, q.y];
    let linkage = Linkage {
        name: "triad at a branch point".into(),
        joints: vec![
            Joint::revolute("O", at(o)),
            Joint::revolute("A1", at(a1)),
            Joint::revolute("A2", at(a[1])),
            Joint::revolute("A3", at(a[2])),
            Joint::revolute("B1", at(drawn.b[0])),
            Joint::revolute("B2", at(drawn.b[1])),
            Joint::revolute("B3", at(drawn.b[2])),
        ],
        links: vec![
            Link::new("frame", &["O", "A2", "A3"]),
            Link::new("crank", &["O", "A1"]),
            Link::new("leg 1", &["A1", "B1"]),
            Link::new("leg 2", &["A2", "B2"]),
            Link::new("leg 3", &["A3", "B3"]),
            Link::new("ternary", &["B1", "B2", "B3"]),
        ],
        ..Linkage::default()
    };
    (linkage, b)
}

/// At the triad's branch point the full kinematics fail, `Plan::position` places the triad
/// (every joint closed to 1e-12 of the size, the joints at the constructed branch pose to
/// the accuracy of a double root, √ε of the size) and returns its rates as the vanished
/// measure det(velocity system)/L_T; just before it, where the two merging modes are still
/// apart, the full kinematics hold and the determinant shrinks as the square root of the
/// distance to the branch point (a double root: det ∝ √Δφ).
#[test]
fn the_position_of_a_triad_at_a_branch_point_with_the_rates_singular() {
    let (linkage, b) = triad_at_a_branch_point();
    let plan = Plan::new(&linkage).unwrap();
    let size = plan.size();
    let input = Motion::new(-FRAC_PI_2, 1.0, 0.0);
    assert!(plan.kinematics(input).is_err());
    let at = plan.position(input).unwrap();
    let k = at.pose();
    let closure = (0..plan.joint_names().len())
        .map(|j| {
            let [l0, l1] = plan.joint_links(j).unwrap();
            (k.joint_on(j, l0).unwrap().p - k.joint_on(j, l1).unwrap().p).norm()
        })
        .fold(0.0, f64::max);
    let off = ["B1", "B2", "B3"]
        .iter()
        .zip(b)
        .map(|(name, q)| (k.joint(*name).unwrap().p - q).norm())
        .fold(0.0, f64::max);
    println!("triad branch point: closure {closure:.1e}, off the branch pose {off:.1e}");
    assert!(closure <= 1e-12 * size, "{closure:e}");
    assert!(off <= 1e-7 * size, "{off:e}");
    let Err(Error::In { source, .. }) = at.rates() else {
        panic!("rates at a branch point: {:?}", at.rates().map(|_| ()))
    };
    let Error::Singular { measure, value, .. } = *source else {
        panic!("{source:?}")
    };
    assert_eq!(measure, "distance from a branch point/size");
    assert!(value <= tmm::kinematics::SINGULAR_BRANCH, "{value:e}");
    // Approaching the branch point: det ∝ √Δφ (a quadrupled distance doubles it).
    let det = |d: f64| {
        plan.kinematics(Motion::new(-FRAC_PI_2 - d, 1.0, 0.0))
            .unwrap()
            .group_determinants()[0]
            .abs()
    };
    for d in [1e-5, 1e-7] {
        let ratio = det(4.0 * d) / det(d);
        assert!((ratio - 2.0).abs() < 0.01, "Δφ {d:e}: ratio {ratio}");
    }
}
