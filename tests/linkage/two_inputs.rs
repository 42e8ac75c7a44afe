//! Courses of two inputs on the bundled five-bar robot, against its closed-form kinematics
//! (two circle intersections, written here from the description's coordinates): over a
//! grid of a whole turn of both cranks the positions reported as not assembling are exactly
//! those where the closed form has no solution; along two input laws the coupler point's
//! velocity is the time derivative of its closed-form position, and the drives' power equals
//! the loads' by the principle of virtual power; bad courses get errors that name the field.

use std::f64::consts::TAU;
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, Inputs, Linkage, Plan, Table, TwoInputCourse, TwoInputShape};
use tmm::nalgebra::{Point2, Vector2};
use tmm::Error;

/// The five-bar O–A–B–C–D in closed form: crank 1 (O, A), coupler 2 (A, B), coupler 3
/// (C, B), crank 4 (D, C); the assembly mode is the side of the line AC on which B lies in
/// the reference pose.
pub(super) struct FiveBar {
    pub o: Point2<f64>,
    pub d: Point2<f64>,
    pub l: [f64; 4],
    /// +1 when B is to the left of A→C.
    pub mode: f64,
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The points where the circles (p, r) and (q, s) meet (none, or two, possibly equal).
pub(super) fn circles(p: Point2<f64>, r: f64, q: Point2<f64>, s: f64) -> Option<[Point2<f64>; 2]> {
    let pq = q - p;
    let d = pq.norm();
    if d == 0.0 || d > r + s || d < (r - s).abs() {
        return None;
    }
    let e = pq / d;
    let a = (r * r - s * s + d * d) / (2.0 * d);
    let h = (r * r - a * a).max(0.0).sqrt();
    let n = Vector2::new(-e.y, e.x);
    Some([p + a * e + h * n, p + a * e - h * n])
}

/// The bundled five-bar robot with its frame stretched to 0.35 m, so that the couplers
/// (0.25 m each) cannot always meet: drawn with its cranks at 100° and 80°.
pub(super) fn wide_five_bar() -> Linkage {
    let mut linkage = bundled::five_bar_robot();
    linkage.name = "wide five-bar".to_owned();
    let (c1, s1) = (100f64.to_radians().cos(), 100f64.to_radians().sin());
    let (c4, s4) = (80f64.to_radians().cos(), 80f64.to_radians().sin());
    let a = [0.15 * c1, 0.15 * s1];
    let c = [0.35 + 0.15 * c4, 0.15 * s4];
    let half = 0.5 * (c[0] - a[0]);
    let b = [
        0.5 * (a[0] + c[0]),
        a[1] + (0.25f64.powi(2) - half * half).sqrt(),
    ];
    for j in &mut linkage.joints {
        j.at = match j.name.as_str() {
            "A" => a,
            "B" => b,
            "C" => c,
            "D" => [0.35, 0.0],
            _ => j.at,
        };
    }
    linkage
}

impl FiveBar {
    pub fn of(linkage: &Linkage) -> Self {
        let at = |n: &str| {
            let j = linkage.joints.iter().find(|j| j.name == n).expect("joint");
            Point2::new(j.at[0], j.at[1])
        };
        let (o, a, b, c, d) = (at("O"), at("A"), at("B"), at("C"), at("D"));
        Self {
            o,
            d,
            l: [
                (a - o).norm(),
                (b - a).norm(),
                (b - c).norm(),
                (c - d).norm(),
            ],
            mode: cross(c - a, b - a).signum(),
        }
    }

    /// A and C at the crank angles.
    pub fn cranks(&self, q1: f64, q2: f64) -> (Point2<f64>, Point2<f64>) {
        (
            self.o + self.l[0] * Vector2::new(q1.cos(), q1.sin()),
            self.d + self.l[3] * Vector2::new(q2.cos(), q2.sin()),
        )
    }

    /// B at the crank angles, `None` where the couplers cannot meet.
    pub fn forward(&self, q1: f64, q2: f64) -> Option<Point2<f64>> {
        let (a, c) = self.cranks(q1, q2);
        let [b1, b2] = circles(a, self.l[1], c, self.l[2])?;
        Some(if cross(c - a, b1 - a) * self.mode > 0.0 {
            b1
        } else {
            b2
        })
    }

    /// Whether B can be reached in the plan's assembly mode: some crank pin A on both
    /// circles (O, l1), (B, l2) and some C on (D, l4), (B, l3) with B on the mode's side of
    /// A→C (inverse kinematics in closed form).
    #[allow(dead_code)] // used by the workspace tests
    pub fn reaches(&self, b: Point2<f64>) -> bool {
        let (Some(aa), Some(cc)) = (
            circles(self.o, self.l[0], b, self.l[1]),
            circles(self.d, self.l[3], b, self.l[2]),
        ) else {
            return false;
        };
        aa.iter()
            .any(|&a| cc.iter().any(|&c| cross(c - a, b - a) * self.mode > 0.0))
    }
}

#[test]
fn a_grid_over_two_whole_turns_reports_exactly_the_positions_that_do_not_assemble() {
    let linkage = wide_five_bar();
    let plan = Plan::new(&linkage).unwrap();
    let five = FiveBar::of(&linkage);
    // 47 steps a turn: no position lands exactly where the couplers are stretched straight.
    let n = 47;
    let last = TAU * f64::from(n - 1) / f64::from(n);
    let course = TwoInputCourse::grid(
        [0.0, last],
        [0.0, last],
        [n as usize, n as usize],
        [1.0, -0.5],
    )
    .unwrap();
    assert_eq!(course.shape, TwoInputShape::Grid { n1: 47, n2: 47 });
    let report = course.assembly(&plan);
    let mut expected_failures = 0;
    let mut worst = 0.0f64;
    let mut solver = plan.solver();
    for (k, i) in course.inputs.iter().enumerate() {
        let (q1, q2) = (i.first().value, i.get(1).unwrap().value);
        // Position i1·n2 + i2 holds the i1-th first input and the i2-th second.
        assert!((q1 - TAU * (k / 47) as f64 / 47.0).abs() < 1e-15);
        match five.forward(q1, q2) {
            None => {
                expected_failures += 1;
                let f = report
                    .failures
                    .iter()
                    .find(|f| f.index == k)
                    .expect("reported");
                assert_eq!(f.inputs, *i);
                assert!(
                    f.error.to_string().contains("cannot be assembled"),
                    "{}",
                    f.error
                );
            }
            Some(b) => {
                if let Some(f) = report.failures.iter().find(|f| f.index == k) {
                    panic!("position {k} reported: {}", f.error);
                }
                let p = solver.kinematics(*i).unwrap().joint("B").unwrap().p;
                worst = worst.max((p - b).norm());
            }
        }
    }
    assert!(expected_failures > 100, "{expected_failures}");
    assert_eq!(report.failures.len(), expected_failures);
    assert_eq!(report.solved + expected_failures, 47 * 47);
    assert!(worst < 1e-13 * plan.size(), "{worst}");
}

#[test]
fn along_two_laws_the_rates_and_the_table_agree_with_independent_references() {
    let linkage = bundled::five_bar_robot();
    let plan = Plan::new(&linkage).unwrap();
    let five = FiveBar::of(&linkage);
    let r = plan.reference_inputs();
    let (r0, r1) = (r[0], r[1]);
    let q1 = move |t: f64| r0 + 0.4 * (2.0 * t).sin();
    let q2 = move |t: f64| r1 + 0.3 * (3.0 * t).cos();
    let times: Vec<f64> = (0..40).map(|k| 0.05 * f64::from(k)).collect();
    let course = TwoInputCourse::laws(
        &times,
        |t| Motion::new(q1(t), 0.8 * (2.0 * t).cos(), -1.6 * (2.0 * t).sin()),
        |t| Motion::new(q2(t), -0.9 * (3.0 * t).sin(), -2.7 * (3.0 * t).cos()),
    )
    .unwrap();
    assert_eq!(course.shape, TwoInputShape::Path);
    assert!(course.assembly(&plan).failures.is_empty());
    let mut solver = plan.solver();
    let h = 1e-5;
    for (&t, &i) in times.iter().zip(&course.inputs) {
        let a = solver.analyse(i).unwrap();
        let b = a.joint("B").unwrap();
        let fd = (five.forward(q1(t + h), q2(t + h)).unwrap()
            - five.forward(q1(t - h), q2(t - h)).unwrap())
            / (2.0 * h);
        assert!(
            (b.v - fd).norm() < 1e-8 * (1.0 + fd.norm()),
            "t = {t}: {} against {fd}",
            b.v
        );
        let c = a.power_check().unwrap();
        assert!(c.relative_error() < 1e-12, "t = {t}: {c:?}");
    }
    let positions: Vec<_> = course.inputs.iter().map(|&i| plan.analyse(i)).collect();
    let table = Table::of(&positions);
    assert_eq!(table.len(), 40);
    let second = table.column("phi_in2 [rad]").unwrap();
    for (&t, &q) in times.iter().zip(second) {
        assert_eq!(q, q2(t));
    }
    // The drives' power is each balancing moment times its crank's rate, summed.
    let (mb1, mb2) = (
        table.column("Mb [N·m, + counter-clockwise]").unwrap(),
        table.column("Mb2 [N·m, + counter-clockwise]").unwrap(),
    );
    let (w1, w2) = (
        table.column("phi_in' [rad/s]").unwrap(),
        table.column("phi_in2' [rad/s]").unwrap(),
    );
    let (p, vp) = (
        table.column("drive power [W]").unwrap(),
        table.column("drive power by virtual power [W]").unwrap(),
    );
    for k in 0..40 {
        assert!((mb1[k] * w1[k] + mb2[k] * w2[k] - p[k]).abs() < 1e-12 * (1.0 + p[k].abs()));
        assert!(
            (p[k] - vp[k]).abs() < 1e-9 * (1.0 + p[k].abs()),
            "{} against {}",
            p[k],
            vp[k]
        );
    }
    assert!(table
        .column("Mb by virtual power [N·m, + counter-clockwise]")
        .is_none());
}

#[test]
fn the_path_about_the_reference_pose_is_a_closed_loop_that_assembles() {
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let course = TwoInputCourse::around_reference(&plan, 36, -3.0).unwrap();
    assert_eq!(course.inputs.len(), 36);
    let r = plan.reference_inputs();
    for (k, i) in course.inputs.iter().enumerate() {
        let (m1, m2) = (i.first(), i.get(1).unwrap());
        // A circle of radius 0.5 rad about the reference inputs, the rates its tangent.
        let (u, v) = (m1.value - r[0], m2.value - r[1]);
        assert!(((u * u + v * v).sqrt() - 0.5).abs() < 1e-12, "position {k}");
        assert!((u * m1.rate + v * m2.rate).abs() < 1e-12);
        assert!(((m1.rate.powi(2) + m2.rate.powi(2)).sqrt() - 1.5).abs() < 1e-12);
    }
    assert!(course.assembly(&plan).failures.is_empty());
}

#[test]
fn bad_courses_are_refused_naming_the_field() {
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let nan = f64::NAN;
    let e = TwoInputCourse::grid([0.0, nan], [0.0, 1.0], [3, 3], [1.0, 1.0]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::NonFinite {
                name: "end of the first input's range",
                ..
            }
        ),
        "{e}"
    );
    let e = TwoInputCourse::grid([0.0, 1.0], [0.0, 1.0], [3, 3], [1.0, f64::INFINITY]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::NonFinite {
                name: "rate of the second input",
                ..
            }
        ),
        "{e}"
    );
    let e = TwoInputCourse::grid([0.0, 1.0], [0.0, 1.0], [0, 3], [1.0, 1.0]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::OutOfRange {
                name: "number of positions",
                ..
            }
        ),
        "{e}"
    );
    let e = TwoInputCourse::grid([0.0, 1.0], [0.0, 1.0], [usize::MAX, 3], [1.0, 1.0]).unwrap_err();
    assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
    let e =
        TwoInputCourse::grid([0.0, 1.0], [0.0, 1.0], [1 << 13, 1 << 12], [1.0, 1.0]).unwrap_err();
    assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
    let e = TwoInputCourse::grid([-1e308, 1e308], [0.0, 1.0], [3, 3], [1.0, 1.0]).unwrap_err();
    assert!(matches!(e, Error::Overflow { .. }), "{e}");
    let fixed = |t: f64| Motion::fixed(t);
    let e = TwoInputCourse::laws(&[0.0, 1.0, 1.0], fixed, fixed).unwrap_err();
    assert!(
        matches!(&e, Error::Description { item, .. } if item == "times"),
        "{e}"
    );
    let e = TwoInputCourse::laws(&[0.0, nan], fixed, fixed).unwrap_err();
    assert!(matches!(e, Error::NonFinite { name: "time", .. }), "{e}");
    let e = TwoInputCourse::laws(&[], fixed, fixed).unwrap_err();
    assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
    let e = TwoInputCourse::laws(&[0.0, 1.0], fixed, |t| Motion::new(t, 1.0 / (t - 1.0), 0.0))
        .unwrap_err();
    assert!(
        e.to_string().contains("second input's law at t = 1 s"),
        "{e}"
    );
    let one = Plan::new(&bundled::four_bar()).unwrap();
    let e = TwoInputCourse::around_reference(&one, 12, 1.0).unwrap_err();
    assert!(
        matches!(&e, Error::Description { item, .. } if item == "field second_input"),
        "{e}"
    );
    for speed in [0.0, nan] {
        assert!(TwoInputCourse::around_reference(&plan, 12, speed).is_err());
        assert!(plan.default_course(None, 12, speed).is_err());
    }
    assert!(TwoInputCourse::around_reference(&plan, 0, 1.0).is_err());
    // A course built by hand is checked.
    let mut course = TwoInputCourse::grid([0.0, 1.0], [0.0, 1.0], [2, 2], [1.0, 1.0]).unwrap();
    assert!(course.check().is_ok());
    course.inputs.pop();
    assert!(course.check().unwrap_err().to_string().contains("2 × 2"));
    course.shape = TwoInputShape::Path;
    course.inputs[0] = Inputs::one(Motion::fixed(0.0));
    assert!(course.check().unwrap_err().to_string().contains("not two"));
    course.inputs[0] = Inputs::two(Motion::fixed(nan), Motion::fixed(0.0));
    assert!(matches!(
        course.check().unwrap_err(),
        Error::NonFinite { .. }
    ));
    // A position that cannot be solved is reported, not a panic.
    let wide = Plan::new(&wide_five_bar()).unwrap();
    let course =
        TwoInputCourse::grid([std::f64::consts::PI; 2], [0.0; 2], [1, 1], [0.0, 0.0]).unwrap();
    let report = course.assembly(&wide);
    assert_eq!((report.solved, report.failures.len()), (0, 1));
}

/// Along two input laws q1(t), q2(t) (the bundled five-bar robot), every
/// joint's and point's velocity and acceleration and every link's angular velocity and
/// acceleration are the time derivatives of the engine's own positions along the laws, by
/// 8th-order central differences in t (truncation ~ (3h)⁸ with the laws' frequencies ≤ 3,
/// rounding ~ 6.5·ε·size/h² for the second derivative), to 1e-7 of their scales.
#[test]
fn along_two_laws_rates_and_accelerations_are_the_derivatives_of_the_positions() {
    use super::engine::fd8;
    for linkage in [bundled::five_bar_robot()] {
        let plan = Plan::new(&linkage).unwrap();
        let r = plan.reference_inputs();
        let (r0, r1) = (r[0], r[1]);
        let law1 = move |t: f64| {
            let (s, c) = (2.0 * t).sin_cos();
            Motion::new(r0 + 0.4 * s, 0.8 * c, -1.6 * s)
        };
        let law2 = move |t: f64| {
            let (s, c) = (3.0 * t).sin_cos();
            Motion::new(r1 + 0.3 * c, -0.9 * s, -2.7 * c)
        };
        let at = |t: f64| Inputs::two(law1(t), law2(t));
        let pos = |t: f64| {
            let still = |m: Motion| Motion::fixed(m.value);
            plan.kinematics(Inputs::two(still(law1(t)), still(law2(t))))
                .unwrap()
        };
        let h = 5e-3;
        let (mut worst, mut checked) = (0.0f64, 0);
        for k in 0..40 {
            let t = 0.05 * f64::from(k) + 0.013;
            let a = plan.kinematics(at(t)).unwrap();
            let (m1, m2) = (law1(t), law2(t));
            let w2 = m1.rate * m1.rate + m2.rate * m2.rate;
            let (vs, acs) = (
                plan.size() * (m1.rate.abs() + m2.rate.abs()),
                plan.size() * (w2 + m1.accel.abs() + m2.accel.abs()),
            );
            let mut compare = |v: f64, acc: f64, d: (f64, f64), scale: [f64; 2]| {
                worst = worst
                    .max((v - d.0).abs() / scale[0])
                    .max((acc - d.1).abs() / scale[1]);
                checked += 1;
            };
            for j in 0..plan.joint_names().len() {
                let m = a.joint(j).unwrap();
                for c in 0..2 {
                    let d = fd8(&|x| pos(x).joint(j).unwrap().p[c], t, h);
                    compare(m.v[c], m.a[c], d, [vs, acs]);
                }
            }
            for p in 0..plan.point_names().len() {
                let m = a.point(p).unwrap();
                for c in 0..2 {
                    let d = fd8(&|x| pos(x).point(p).unwrap().p[c], t, h);
                    compare(m.v[c], m.a[c], d, [vs, acs]);
                }
            }
            for li in 1..plan.link_names().len() {
                let m = a.link(li).unwrap();
                let f = |x: f64| {
                    let v = pos(x).link(li).unwrap().value - m.value;
                    v - TAU * (v / TAU).round()
                };
                let d = fd8(&f, t, h);
                let scale = [vs, acs].map(|s| s / plan.size());
                compare(m.rate, m.accel, d, scale);
            }
        }
        println!(
            "{}: {checked} rates and accelerations against 8th-order differences in t, \
             largest relative difference {worst:.1e}",
            linkage.name
        );
        assert!(checked > 40 * 10, "{checked}");
        assert!(worst < 1e-7, "{}: {worst:e}", linkage.name);
    }
}
