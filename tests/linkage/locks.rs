//! A rocking input at and near its locks: there the driven dyad is at its dead point, and the
//! kinetostatics is refused (`Error::Singular` naming the group) wherever the position's own
//! rounding leaves the determinant less than six digits; elsewhere the balance agrees with an
//! independent closed form (a four-bar driven from its rocker) or with its finite limit
//! (Peaucellier's, 20 N × dy_P/dφ).

use tmm::kinematics::Motion;
use tmm::linkage::{
    bundled, Course, Input, Joint, Link, Linkage, LoadSpec, Plan, DEAD_POINT_RELATIVE_ERROR,
};
use tmm::Error;

/// The distances inside a lock at which the analysis is tried: at the lock, then 10⁻¹³,
/// 10⁻¹⁰ and 10⁻⁶ rad inside.
const INSIDE: [f64; 4] = [0.0, 1e-13, 1e-10, 1e-6];

/// `true` for the refusal of a dyad at its dead point, naming its group.
fn refused_at_dead_point(e: &Error) -> bool {
    matches!(e, Error::In { part, source } if part.starts_with("group")
        && matches!(**source, Error::Singular { what, .. } if what.contains("dead point")))
}

/// The inputs at `d` rad inside each lock (lower lock + d, upper lock − d), at rest.
fn near_locks(plan: &Plan, d: f64) -> [Motion; 2] {
    let (lo, hi) = plan
        .lock_positions(plan.reference_input())
        .unwrap()
        .unwrap();
    [Motion::fixed(lo + d), Motion::fixed(hi - d)]
}

/// B where the circles about `a` (radius `ra`) and `q` (radius `rq`) meet, on the side `s`
/// (±1) of the line a → q.
fn circles(a: [f64; 2], ra: f64, q: [f64; 2], rq: f64, s: f64) -> [f64; 2] {
    let (dx, dy) = (q[0] - a[0], q[1] - a[1]);
    let l = dx.hypot(dy);
    let x = 0.5 * (l + (ra - rq) * (ra + rq) / l);
    let h = (ra * ra - x * x).max(0.0).sqrt();
    [
        a[0] + (x * dx - s * h * dy) / l,
        a[1] + (x * dy + s * h * dx) / l,
    ]
}

/// A four-bar with its input link (`r1`) about O = (0, 0) and its output link (`r3`) about
/// Q = (`d`, 0), coupler `r2`, B on the side `side` of A → Q, at rest at the input angle
/// `phi`, loaded by `force` at the coupler's midpoint and the couple `m3` on the output link:
/// its balancing moment by virtual power, Mb·ω1 + F·v_P + M3·ω3 = 0 (ω1 = 1), from its own
/// positions (circle against circle) and its velocity equations (the loop's derivative
/// dotted with e(θ) and e(ψ)).
struct FourBar {
    r1: f64,
    r2: f64,
    r3: f64,
    d: f64,
    side: f64,
    force: [f64; 2],
    m3: f64,
}

impl FourBar {
    fn balance(&self, phi: f64) -> f64 {
        let a = [self.r1 * phi.cos(), self.r1 * phi.sin()];
        let b = circles(a, self.r2, [self.d, 0.0], self.r3, self.side);
        let theta = (b[1] - a[1]).atan2(b[0] - a[0]);
        let psi = b[1].atan2(b[0] - self.d);
        // r1·ω1·sin(θ − φ) = r3·ω3·sin(θ − ψ); r1·ω1·sin(ψ − φ) + r2·ω2·sin(ψ − θ) = 0.
        let w3 = self.r1 * (phi - theta).sin() / (self.r3 * (psi - theta).sin());
        let w2 = -self.r1 * (psi - phi).sin() / (self.r2 * (psi - theta).sin());
        let (px, py) = (0.5 * (b[0] - a[0]), 0.5 * (b[1] - a[1]));
        let vp = [
            -self.r1 * phi.sin() - w2 * py,
            self.r1 * phi.cos() + w2 * px,
        ];
        -(self.force[0] * vp[0] + self.force[1] * vp[1] + self.m3 * w3)
    }
}

/// B's side (±1) of the line from A to Q = (`d`, 0) in the plan's reference pose.
fn side_of(plan: &Plan, d: f64) -> f64 {
    let k = plan
        .kinematics(Motion::fixed(plan.reference_input()))
        .unwrap();
    let (a, b) = (k.joint("A").unwrap().p, k.joint("B").unwrap().p);
    ((d - a.x) * (b.y - a.y) - (0.0 - a.y) * (b.x - a.x)).signum()
}

/// At the locks and 10⁻¹³, 10⁻¹⁰, 10⁻⁶ rad inside: refused (always at the locks and within
/// 10⁻¹⁰ rad), or the balance within [`DEAD_POINT_RELATIVE_ERROR`] of the closed form; the
/// largest difference.
fn refused_or_closed_form(plan: &Plan, four: &FourBar) -> f64 {
    let mut worst = 0.0f64;
    for d in INSIDE {
        for m in near_locks(plan, d) {
            match plan.analyse(m) {
                Err(e) => assert!(refused_at_dead_point(&e), "{d:e}: {e}"),
                Ok(an) => {
                    assert!(d > 1e-10, "{d:e}: not refused");
                    let (mb, expect) = (an.balance(0).unwrap().value, four.balance(m.value));
                    let err = ((mb - expect) / expect).abs();
                    println!("{d:e} inside: Mb {mb:.9e}, closed form {expect:.9e}");
                    assert!(err < DEAD_POINT_RELATIVE_ERROR, "{d:e}: {mb} vs {expect}");
                    worst = worst.max(err);
                }
            }
            // The kinematics at rest is still there: the position, every link at rest.
            assert!(plan.kinematics(m).is_ok());
        }
    }
    worst
}

/// A Grashof four-bar driven from its rocker: input O A (0.25 m) about O = (0, 0), coupler
/// A B (0.3 m), the crank Q B (0.1 m) about Q = (0.3, 0) driven, loaded by −1 N·m. The input
/// rocks: it locks where coupler and crank lie along one line.
fn rocker_driven() -> Linkage {
    let a = [0.0, 0.25];
    let b = circles(a, 0.3, [0.3, 0.0], 0.1, 1.0);
    Linkage {
        name: "four-bar driven from its rocker".into(),
        joints: vec![
            Joint::revolute("O", [0.0, 0.0]),
            Joint::revolute("A", a),
            Joint::revolute("B", b),
            Joint::revolute("Q", [0.3, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O", "Q"]),
            Link::new("rocker", &["O", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("crank", &["Q", "B"]),
        ],
        input: Input::crank("rocker"),
        loads: vec![LoadSpec::Moment {
            link: "crank".into(),
            moment: -1.0,
        }],
        ..Linkage::default()
    }
}

#[test]
fn a_rocker_driven_four_bar_at_its_locks_refuses_or_agrees_with_the_closed_form() {
    let plan = Plan::new(&rocker_driven()).unwrap();
    let four = FourBar {
        r1: 0.25,
        r2: 0.3,
        r3: 0.1,
        d: 0.3,
        side: side_of(&plan, 0.3),
        force: [0.0, 0.0],
        m3: -1.0,
    };
    let worst = refused_or_closed_form(&plan, &four);
    println!("rocker-driven four-bar: Mb against the closed form within {worst:.1e}");
    assert!(worst > 0.0, "10⁻⁶ rad inside is answered");
}

#[test]
fn chebyshev_at_its_locks_refuses_or_agrees_with_the_closed_form() {
    // A0 = (0, 0), B0 = (0.2, 0); crank 0.25, coupler 0.1 (P its midpoint, −30 N along x),
    // rocker 0.25 (−2 N·m).
    let plan = Plan::new(&bundled::chebyshev_straight_line()).unwrap();
    let four = FourBar {
        r1: 0.25,
        r2: 0.1,
        r3: 0.25,
        d: 0.2,
        side: side_of(&plan, 0.2),
        force: [-30.0, 0.0],
        m3: -2.0,
    };
    // The closed form is the engine's away from the locks too.
    let mid = plan.analyse(Motion::fixed(plan.reference_input())).unwrap();
    let expect = four.balance(plan.reference_input());
    assert!((mid.balance(0).unwrap().value - expect).abs() < 1e-12 * expect.abs());
    let worst = refused_or_closed_form(&plan, &four);
    println!("Chebyshev: Mb against the closed form within {worst:.1e}");
    assert!(worst > 0.0, "10⁻⁶ rad inside is answered");
}

#[test]
fn peaucellier_at_its_locks_is_refused_or_agrees_with_its_finite_limit() {
    let plan = Plan::new(&bundled::peaucellier_lipkin()).unwrap();
    // P = k·A/|A|² (A's inverse about O, k = l² − s²), A = O1 + r·e(φ): at rest the 20 N
    // downward on P needs Mb = −F·dP/dφ = 20·dy_P/dφ.
    let (r, k) = (0.045f64, 0.1f64 * 0.1 - 0.04 * 0.04);
    let limit = |phi: f64| {
        let (s, c) = phi.sin_cos();
        let a = [r + r * c, r * s];
        let da = [-r * s, r * c];
        let q = a[0] * a[0] + a[1] * a[1];
        let dot = a[0] * da[0] + a[1] * da[1];
        20.0 * k * (da[1] / q - 2.0 * a[1] * dot / (q * q))
    };
    let mut worst = 0.0f64;
    for d in INSIDE {
        for m in near_locks(&plan, d) {
            match plan.analyse(m) {
                Err(e) => assert!(refused_at_dead_point(&e) && d < 1e-6, "{d:e}: {e}"),
                Ok(an) => {
                    let (mb, expect) = (an.balance(0).unwrap().value, limit(m.value));
                    println!("Peaucellier, {d:e} inside: Mb {mb:.9} N·m, 20·dy_P/dφ {expect:.9}");
                    // The balance is a difference of reactions of 10⁴ N on arms of 0.1 m:
                    // six digits of those leave 10⁻⁵ of it.
                    assert!(
                        ((mb - expect) / expect).abs() < 1e-5,
                        "{d:e}: {mb} vs {expect}"
                    );
                    worst = worst.max(((mb - expect) / expect).abs());
                }
            }
        }
    }
    assert!((limit(plan.lock_positions(1.0).unwrap().unwrap().1) - 2.1).abs() < 1e-3);
    println!("Peaucellier: Mb against 20·dy_P/dφ within {worst:.1e}");
}

#[test]
fn a_rocking_course_shows_its_locks_with_their_kinematics_and_no_forces() {
    for l in [
        bundled::chebyshev_straight_line(),
        bundled::peaucellier_lipkin(),
    ] {
        let plan = Plan::new(&l).unwrap();
        let course = Course::new(&plan, None, 12, 10.0).unwrap();
        let results = plan.cycle(&course.inputs, |a| Ok(a.balance(0)?.value));
        for (m, r) in course.inputs.iter().zip(&results) {
            if m.rate == 0.0 {
                // A lock: the position and its (zero) rates, the forces refused.
                assert!(plan.kinematics(*m).is_ok());
                let e = r.as_ref().expect_err("refused at a lock");
                assert!(refused_at_dead_point(e), "{e}");
            } else {
                assert!(r.as_ref().is_ok_and(|mb| mb.is_finite()), "{r:?}");
            }
        }
    }
}

#[test]
fn the_kinematics_of_a_moving_input_at_its_lock_is_refused_and_its_position_given() {
    // At a lock the driven dyad's analogues are rounding over a determinant of rounding: a
    // moving input there has no rates to give (they grow as 1/√δ towards the lock), while
    // the position itself is exact and is given at rest.
    for plan in [
        Plan::new(&bundled::chebyshev_straight_line()).unwrap(),
        Plan::new(&bundled::peaucellier_lipkin()).unwrap(),
        Plan::new(&rocker_driven()).unwrap(),
    ] {
        for m in near_locks(&plan, 0.0) {
            let at_rest = plan.kinematics(m);
            assert!(at_rest.is_ok(), "{at_rest:?}");
            for moving in [
                Motion::new(m.value, 1.0, 0.0),
                Motion::new(m.value, 0.0, 1.0),
            ] {
                let e = plan.kinematics(moving).unwrap_err();
                assert!(refused_at_dead_point(&e), "{e}");
                let e = plan.solver().kinematics(moving).map(|_| ()).unwrap_err();
                assert!(refused_at_dead_point(&e), "{e}");
            }
        }
        // 10⁻⁶ rad inside the rates are answered, and grow like 1/√δ towards the lock:
        // from 10⁻⁴ to 10⁻⁶ rad the fastest link's ω grows by about 10 (√100).
        let fastest = |d: f64| {
            let m = near_locks(&plan, d)[0];
            let k = plan.kinematics(Motion::new(m.value, 1.0, 0.0)).unwrap();
            k.link_motions()
                .iter()
                .map(|l| l.omega.abs())
                .fold(0.0, f64::max)
        };
        let growth = fastest(1e-6) / fastest(1e-4);
        assert!(
            (5.0..20.0).contains(&growth),
            "ω grew {growth} for δ 100× smaller"
        );
    }
}
