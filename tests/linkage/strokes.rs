//! Strokes of an angle output do not depend on where the angle's reading is cut: a four-bar
//! turned as a whole about the origin has the same rocker swing and time ratio, also when
//! its rocker swings across the +x direction (where a link's angle, read in [0, 2π), jumps).

use std::f64::consts::TAU;
use tmm::kinematics::Rotation;
use tmm::linkage::{Input, Joint, Link, Linkage, Output, Plan};

fn four_bar(turn: f64) -> Linkage {
    let (s, c) = turn.sin_cos();
    let at = |x: f64, y: f64| [c * x - s * y, s * x + c * y];
    // A crank-rocker (crank 0.1, coupler 0.35, rocker 0.3, frame 0.4): Grashof, crank shortest.
    // B in the reference pose: where the coupler's circle about A(0.1, 0) meets the rocker's
    // about O3(0.4, 0), 0.3 apart.
    let (l2, l3, gap) = (0.35_f64, 0.3_f64, 0.3_f64);
    let x = (l2 * l2 - l3 * l3 + gap * gap) / (2.0 * gap);
    let b = [0.1 + x, (l2 * l2 - x * x).sqrt()];
    Linkage {
        name: "four-bar".into(),
        frame: "frame".into(),
        joints: vec![
            Joint::revolute("O1", at(0.0, 0.0)),
            Joint::revolute("A", at(0.1, 0.0)),
            Joint::revolute("B", at(b[0], b[1])),
            Joint::revolute("O3", at(0.4, 0.0)),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("rocker", &["O3", "B"]),
        ],
        input: Input::crank("crank"),
        ..Linkage::default()
    }
}

#[test]
fn a_rockers_swing_is_the_same_however_the_linkage_is_turned() {
    let swing = |turn: f64| {
        let plan = Plan::new(&four_bar(turn)).unwrap();
        plan.strokes(&Output::Angle("rocker".into()), Rotation::Ccw)
            .unwrap()
    };
    let reference = swing(0.0);
    // The swing by the cosine law at the two extremes (crank and coupler in line).
    let (a, b, c, d) = (0.1_f64, 0.35_f64, 0.3_f64, 0.4_f64);
    let at = |l: f64| ((c * c + d * d - l * l) / (2.0 * c * d)).acos();
    let exact = at(b + a) - at(b - a);
    // The crank's angle between the extremes, at O1 in the triangle O1 O3 B whose side O1B is
    // b + a (extended) or b − a (folded); the slower stroke turns the crank by π + θ.
    let at_crank = |l: f64| ((l * l + d * d - c * c) / (2.0 * l * d)).acos();
    let theta = at_crank(b - a) - at_crank(b + a);
    let ratio = (std::f64::consts::PI + theta) / (std::f64::consts::PI - theta);
    assert!(
        (reference.stroke - exact).abs() < 1e-12,
        "{} vs {exact}",
        reference.stroke
    );
    let mut crossed = 0;
    for k in 0..72 {
        let turn = TAU * f64::from(k) / 72.0;
        let s = swing(turn);
        assert!(
            (s.stroke - exact).abs() < 1e-12,
            "turned {turn}: swing {} vs {exact}",
            s.stroke
        );
        assert!(
            (s.time_ratio - ratio).abs() < 1e-12,
            "turned {turn}: time ratio {} vs {ratio} in closed form",
            s.time_ratio
        );
        // Count the turns at which the rocker's reading is cut inside its swing.
        let plan = Plan::new(&four_bar(turn)).unwrap();
        let e = plan.extremes(&Output::Angle("rocker".into())).unwrap();
        if (e[0].output.value - e[1].output.value).abs() > std::f64::consts::PI {
            crossed += 1;
        }
    }
    assert!(
        crossed > 0,
        "no turn put the rocker's swing across its reading's cut"
    );
}
