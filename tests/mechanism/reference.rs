//! The ready mechanisms built through the linkage engine agree with the hand-written chains
//! they replaced (kept in `tests/mechanism/hand/`, from commit e98753d) at 360 positions with
//! ω1 ≠ 0 and ε1 ≠ 0: every link's angle, ω and ε, every joint's position, velocity and
//! acceleration, every reaction and the balancing moment, to 1e-13 relative.

use super::hand;
use nalgebra::Vector2;
use tmm::kinematics::{LinkMotion, Motion, PointMotion};
use tmm::linkage::{Analysis, Drive};
use tmm::mechanism::{Compressor, FourBar, Mechanism, RockingCylinder, SixBar, SliderCrank};

const TOL: f64 = 1e-13;

/// The worst relative difference found, with what it was.
#[derive(Default)]
struct Worst {
    value: f64,
    what: String,
}

impl Worst {
    fn note(&mut self, what: &str, diff: f64, scale: f64) {
        let rel = diff / scale.max(f64::MIN_POSITIVE);
        assert!(rel.is_finite(), "{what}: not finite");
        if rel > self.value {
            self.value = rel;
            self.what = what.to_owned();
        }
    }
}

fn wrap(d: f64) -> f64 {
    let t = std::f64::consts::TAU;
    (d + 0.5 * t).rem_euclid(t) - 0.5 * t
}

/// One position of a mechanism, engine vs hand chain.
struct Position<'a, 'p> {
    a: &'a Analysis<'p>,
    links: Vec<(&'static str, LinkMotion)>,
    joints: Vec<(&'static str, PointMotion)>,
    /// (joint, by, on, force, moment about the joint's point)
    reactions: Vec<(&'static str, &'static str, &'static str, Vector2<f64>, f64)>,
    moment: f64,
    gear_force: Vector2<f64>,
}

impl Position<'_, '_> {
    fn compare(&self, w: &mut Worst, size: f64) {
        let a = self.a;
        let plan = a.plan();
        let at = a.inputs().first().value;
        // Links: angle (relative to 2π), ω, ε (relative to the largest ω, ε + ω²).
        let w_scale = self
            .links
            .iter()
            .map(|l| l.1.omega.abs())
            .fold(0.0, f64::max);
        let e_scale = self
            .links
            .iter()
            .map(|l| l.1.epsilon.abs())
            .fold(w_scale * w_scale, f64::max);
        for (name, h) in &self.links {
            let e = a.link(name).unwrap();
            w.note(
                &format!("{name} angle at {at}"),
                wrap(e.value - h.angle).abs(),
                1.0,
            );
            w.note(
                &format!("{name} ω at {at}"),
                (e.rate - h.omega).abs(),
                w_scale,
            );
            w.note(
                &format!("{name} ε at {at}"),
                (e.accel - h.epsilon).abs(),
                e_scale,
            );
        }
        let v_scale = self.joints.iter().map(|j| j.1.v.norm()).fold(0.0, f64::max);
        let a_scale = self.joints.iter().map(|j| j.1.a.norm()).fold(0.0, f64::max);
        for (name, h) in &self.joints {
            let e = a.joint(name).unwrap();
            w.note(&format!("{name} p at {at}"), (e.p - h.p).norm(), size);
            w.note(&format!("{name} v at {at}"), (e.v - h.v).norm(), v_scale);
            w.note(&format!("{name} a at {at}"), (e.a - h.a).norm(), a_scale);
        }
        let r_scale = self
            .reactions
            .iter()
            .map(|r| r.3.norm())
            .fold(0.0, f64::max);
        assert_eq!(
            self.reactions.len(),
            plan.joint_names().len(),
            "every joint compared"
        );
        for (joint, by, on, force, moment) in &self.reactions {
            let r = a.reaction(joint).unwrap();
            let (by, on) = (
                plan.link_id(by).unwrap().index(),
                plan.link_id(on).unwrap().index(),
            );
            let s = if (r.by, r.on) == (by, on) {
                1.0
            } else {
                assert_eq!((r.on, r.by), (by, on), "joint {joint} joins other links");
                -1.0
            };
            w.note(
                &format!("R {joint} at {at}"),
                (s * r.force - force).norm(),
                r_scale,
            );
            w.note(
                &format!("R {joint} moment at {at}"),
                (s * r.moment - moment).abs(),
                r_scale * size,
            );
        }
        let check = a.power_check().unwrap();
        let b = a.balances()[0];
        w.note(
            &format!("M_b at {at}"),
            (b.value - self.moment).abs(),
            check.scale,
        );
        w.note(
            &format!("F_b at {at}"),
            (b.force - self.gear_force).norm(),
            r_scale,
        );
        assert!(check.relative_error() < 1e-9 && a.worst_residual() < 1e-11);
    }
}

fn inputs(omega1: f64) -> Vec<Motion> {
    (0..360)
        .map(|k| {
            Motion::new(
                (f64::from(k) + 0.25).to_radians(),
                omega1,
                0.7 * omega1.abs() + 3.0,
            )
        })
        .collect()
}

fn report(name: &str, w: &Worst) {
    println!(
        "{name}: largest relative difference {:.3e} ({})",
        w.value, w.what
    );
    assert!(w.value < TOL, "{name}: {:.3e} at {}", w.value, w.what);
}

#[test]
fn the_four_bar_agrees_with_its_hand_chain() {
    let (m, h) = (
        FourBar::course_example(),
        hand::four_bar::FourBar::course_example(),
    );
    let plan = m.plan().unwrap();
    let mut w = Worst::default();
    for i in inputs(10.0) {
        let (a, p) = (plan.analyse(i).unwrap(), h.analyse(i).unwrap());
        Position {
            a: &a,
            links: vec![
                ("crank", p.crank.link),
                ("coupler", p.group23.link2),
                ("rocker", p.group23.link3),
            ],
            joints: vec![("A", p.crank.a), ("B", p.group23.b)],
            reactions: vec![
                ("O1", "frame", "crank", p.balance.r01, 0.0),
                ("A", "crank", "coupler", p.r12, 0.0),
                ("B", "coupler", "rocker", p.r23, 0.0),
                ("O3", "frame", "rocker", p.r03, 0.0),
            ],
            moment: p.balance.moment,
            gear_force: p.balance.force,
        }
        .compare(&mut w, plan.size());
    }
    report("four-bar", &w);
}

fn slider_crank(m: &SliderCrank, h: &hand::slider_crank::SliderCrank, name: &str) {
    let plan = m.plan().unwrap();
    let mut w = Worst::default();
    for i in inputs(150.0) {
        let (a, p) = (plan.analyse(i).unwrap(), h.analyse(i).unwrap());
        let s = a.slide("P").unwrap();
        w.note(
            "slide rate",
            (s.rate - p.group23.slide.rate).abs(),
            p.crank.a.v.norm(),
        );
        w.note(
            "slide accel",
            (s.accel - p.group23.slide.accel).abs(),
            p.crank.a.a.norm(),
        );
        Position {
            a: &a,
            links: vec![
                ("crank", p.crank.link),
                ("rod", p.group23.link2),
                ("piston", p.group23.link3),
            ],
            joints: vec![("A", p.crank.a), ("B", p.group23.b)],
            reactions: vec![
                ("O1", "frame", "crank", p.balance.r01, 0.0),
                ("A", "crank", "rod", p.r12, 0.0),
                ("B", "rod", "piston", p.r23, 0.0),
                ("P", "frame", "piston", p.r03, p.r03_moment),
            ],
            moment: p.balance.moment,
            gear_force: p.balance.force,
        }
        .compare(&mut w, plan.size());
    }
    report(name, &w);
}

#[test]
fn the_slider_crank_agrees_with_its_hand_chain() {
    slider_crank(
        &SliderCrank::course_example(),
        &hand::slider_crank::SliderCrank::course_example(),
        "slider-crank",
    );
}

#[test]
fn the_geared_slider_crank_agrees_with_its_hand_chain() {
    let m = SliderCrank::geared_example();
    assert!(matches!(m.drive, Drive::Gear { .. }));
    slider_crank(
        &m,
        &hand::slider_crank::SliderCrank::geared_example(),
        "geared slider-crank",
    );
}

#[test]
fn the_compressor_agrees_with_its_hand_chain() {
    let (m, h) = (
        Compressor::course_example(),
        hand::compressor::Compressor::course_example(),
    );
    let plan = m.plan().unwrap();
    let mut w = Worst::default();
    for i in inputs(Compressor::seed_speed()) {
        let (a, p) = (plan.analyse(i).unwrap(), h.analyse(i).unwrap());
        Position {
            a: &a,
            links: vec![
                ("crank", p.crank.link),
                ("rod 1", p.group23.link2),
                ("piston 1", p.group23.link3),
                ("rod 2", p.group45.link2),
                ("piston 2", p.group45.link3),
            ],
            joints: vec![
                ("A", p.crank.a),
                ("C", p.c),
                ("B", p.group23.b),
                ("D", p.group45.b),
            ],
            reactions: vec![
                ("O1", "frame", "crank", p.balance.r01, 0.0),
                ("A", "crank", "rod 1", p.r12, 0.0),
                ("B", "rod 1", "piston 1", p.r23, 0.0),
                ("P1", "frame", "piston 1", p.r03, p.wall_moments[0]),
                ("C", "crank", "rod 2", p.r14, 0.0),
                ("D", "rod 2", "piston 2", p.r45, 0.0),
                ("P2", "frame", "piston 2", p.r05, p.wall_moments[1]),
            ],
            moment: p.balance.moment,
            gear_force: p.balance.force,
        }
        .compare(&mut w, plan.size());
    }
    report("compressor", &w);
}

#[test]
fn the_six_bar_agrees_with_its_hand_chain() {
    let (m, h) = (
        SixBar::course_example(),
        hand::six_bar::SixBar::course_example(),
    );
    let plan = m.plan().unwrap();
    let mut w = Worst::default();
    let mut working = 0;
    for i in inputs(10.0) {
        let (a, p) = (plan.analyse(i).unwrap(), h.analyse(i).unwrap());
        working += usize::from(p.resistance.norm() > 0.0);
        Position {
            a: &a,
            links: vec![
                ("crank", p.crank.link),
                ("coupler", p.group23.link2),
                ("rocker", p.group23.link3),
                ("rod", p.group45.link2),
                ("slider", p.group45.link3),
            ],
            joints: vec![
                ("A", p.crank.a),
                ("B", p.group23.b),
                ("C", p.c),
                ("D", p.group45.b),
            ],
            reactions: vec![
                ("O1", "frame", "crank", p.balance.r01, 0.0),
                ("A", "crank", "coupler", p.r12, 0.0),
                ("B", "coupler", "rocker", p.r23, 0.0),
                ("O2", "frame", "rocker", p.r03, 0.0),
                ("C", "rocker", "rod", p.r34, 0.0),
                ("D", "rod", "slider", p.r45, 0.0),
                ("Q", "frame", "slider", p.r05, p.r05_moment),
            ],
            moment: p.balance.moment,
            gear_force: p.balance.force,
        }
        .compare(&mut w, plan.size());
    }
    assert!(
        working > 100 && working < 260,
        "both strokes visited: {working}"
    );
    report("six-bar", &w);
}

#[test]
fn the_rocking_cylinder_agrees_with_its_hand_chain() {
    let (m, h) = (
        RockingCylinder::course_example(),
        hand::rocking_cylinder::RockingCylinder::course_example(),
    );
    let plan = m.plan().unwrap();
    let mut w = Worst::default();
    for i in inputs(20.0) {
        let (a, p) = (plan.analyse(i).unwrap(), h.analyse(i).unwrap());
        let s = a.slide("Q").unwrap();
        w.note(
            "slide rate",
            (s.rate - p.group23.slide.rate).abs(),
            p.crank.a.v.norm(),
        );
        w.note(
            "slide accel",
            (s.accel - p.group23.slide.accel).abs(),
            p.crank.a.a.norm(),
        );
        let piston = a.point("P").unwrap();
        w.note("piston", (piston.p - p.fluid.point).norm(), plan.size());
        Position {
            a: &a,
            links: vec![
                ("crank", p.crank.link),
                ("rod", p.group23.link2),
                ("cylinder", p.group23.link3),
            ],
            joints: vec![("A", p.crank.a)],
            reactions: vec![
                ("O1", "frame", "crank", p.balance.r01, 0.0),
                ("A", "crank", "rod", p.r12, 0.0),
                ("Q", "cylinder", "rod", p.r32, p.r32_moment),
                ("C", "frame", "cylinder", p.r03, 0.0),
            ],
            moment: p.balance.moment,
            gear_force: p.balance.force,
        }
        .compare(&mut w, plan.size());
    }
    report("rocking cylinder", &w);
}
