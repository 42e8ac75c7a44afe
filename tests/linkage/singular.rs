//! Positions at a dead centre: a four-bar stretched straight (its coupler and rocker along
//! one line) at an input angle where that happens exactly; `Plan::position` returns the
//! position (closed to 1e-12 of the size, the joint on the line) and the rates as the
//! singular measure, while a regular position gives the full kinematics unchanged.

use std::f64::consts::FRAC_PI_2;
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
