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
