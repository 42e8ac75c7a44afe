//! Stops and reversals of a machine with two inputs: the bundled five-bar with a resisting
//! couple on coupler 3. Each resistance is a switch of its own, its rate σ = c(q)·q̇ (ω₃);
//! where σ reaches zero the run weighs the couple that would hold it, and sticks or goes on.

use nalgebra::{Matrix3, Vector2, Vector3};
use tmm::dynamics::{run, Dopri5, LagrangeSystem, Outcome, Rk4, RunOptions, State};
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, Linkage, LoadSpec, Plan};

const LINK: &str = "coupler 3";

/// The bundled five-bar with its loads, plus a resistance of `r` N·m on coupler 3 (with
/// `keep` false, the loads cleared first).
fn five_bar(r: f64, keep: bool) -> Linkage {
    let mut l = bundled::five_bar_robot();
    if !keep {
        l.loads.clear();
    }
    if r > 0.0 {
        l.loads.push(LoadSpec::Resistance {
            on: LINK.to_owned(),
            forward: r,
            backward: r,
            at: None,
        });
    }
    l
}

/// Coupler 3's angular velocity and acceleration at the state (q, q̇) with q̈ = `qdd`.
fn omega3(plan: &Plan, q: &Vector2<f64>, qd: &Vector2<f64>, qdd: &Vector2<f64>) -> Motion {
    let k = plan
        .kinematics([
            Motion::new(q[0], qd[0], qdd[0]),
            Motion::new(q[1], qd[1], qdd[1]),
        ])
        .unwrap();
    k.link(LINK).unwrap()
}

/// The transfer functions c = ∂ω₃/∂q̇ at q.
fn c_at(plan: &Plan, q: &Vector2<f64>) -> Vector2<f64> {
    let z = Vector2::zeros();
    Vector2::new(
        omega3(plan, q, &Vector2::new(1.0, 0.0), &z).rate,
        omega3(plan, q, &Vector2::new(0.0, 1.0), &z).rate,
    )
}

#[test]
fn a_five_bar_at_rest_sticks_exactly_when_the_drive_is_below_the_resistance() {
    // Motors whose generalized forces are those of a couple μ on coupler 3 (τ = μ·c): the
    // couple that holds ω₃ at zero is −μ whatever the inertia, so the drive along the
    // switch is μ exactly; it sticks for |μ| ≤ 2 N·m, and breaks away with ω₃ of μ's sign.
    let plan = Plan::new(&five_bar(2.0, false)).unwrap();
    let q = Vector2::from_vec(plan.reference_inputs());
    let c = c_at(&plan, &q);
    assert!(c.norm() > 0.1, "c = {c:?}");
    for mu in [-2.5, -1.9, -0.5, 0.7, 1.999, 2.001, 3.0] {
        let sys = LinkageSystem::from_linkage(&five_bar(2.0, false))
            .unwrap()
            .with_motor(0, Motor::Constant(mu * c[0]))
            .unwrap()
            .with_motor(1, Motor::Constant(mu * c[1]))
            .unwrap();
        assert_eq!(sys.switches(), 1);
        let r = run(
            &sys,
            &Rk4,
            State::at_rest(q),
            &RunOptions::until(0.05, 1e-3),
        )
        .unwrap_or_else(|e| panic!("μ = {mu}: {e}"));
        if mu.abs() <= 2.0 {
            let Outcome::Stuck { t, switch, loads } = r.outcome else {
                panic!("μ = {mu}: {:?}", r.outcome)
            };
            assert_eq!((t, switch), (0.0, 0), "μ = {mu}");
            assert!(
                (loads.drive - mu).abs() <= 1e-12 * mu.abs(),
                "μ = {mu}: {loads:?}"
            );
            assert_eq!(
                (loads.forward, loads.backward, loads.unit),
                (2.0, 2.0, "N·m")
            );
            let msg = loads.stalled(t).to_string();
            assert!(msg.contains("below the resistance"), "{msg}");
        } else {
            assert!(
                matches!(r.outcome, Outcome::FinalTime),
                "μ = {mu}: {:?}",
                r.outcome
            );
            // It broke away the way μ pushes, and ω₃ kept that sign over the run.
            let tr = &r.trajectory;
            for k in 1..tr.t().len() {
                let (q, qd) = (
                    Vector2::new(tr.q()[0][k], tr.q()[1][k]),
                    Vector2::new(tr.qd()[0][k], tr.qd()[1][k]),
                );
                let w3 = c_at(&plan, &q).dot(&qd);
                assert!(w3 * mu > 0.0, "μ = {mu}, t = {}: ω₃ = {w3}", tr.t()[k]);
            }
        }
    }
}

#[test]
fn a_five_bar_with_a_resisted_coupler_stops_or_goes_on_within_a_bounded_run() {
    // The case of the round: motors 1 and −0.5 N·m, a 2 N·m resistance on coupler 3. Without
    // a switch per resistance the run chattered about ω₃ = 0 until its budget ran out. Now
    // the run ends, within few steps, and where it sticks the couple that holds ω₃ at zero,
    // from the constrained equations of motion solved by LU, equals the drive it reports.
    let with = five_bar(2.0, true);
    let plan = Plan::new(&with).unwrap();
    let motors = |l: &Linkage| {
        LinkageSystem::from_linkage(l)
            .unwrap()
            .with_motor(0, Motor::Constant(1.0))
            .unwrap()
            .with_motor(1, Motor::Constant(-0.5))
            .unwrap()
    };
    let (sys, free) = (motors(&with), motors(&five_bar(0.0, true)));
    let start = State::at_rest(Vector2::from_vec(plan.reference_inputs()));
    let opts = RunOptions::until(5.0, 1e-3);
    let mut stuck = 0;
    for (name, r) in [
        ("RK4", run(&sys, &Rk4, start, &opts)),
        (
            "Dormand-Prince",
            run(&sys, &Dopri5::new(1e-9).unwrap(), start, &opts),
        ),
    ] {
        let r = r.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(r.steps <= 6000, "{name}: {} steps", r.steps);
        match r.outcome {
            Outcome::Stuck {
                t,
                switch: 0,
                loads,
            } => {
                stuck += 1;
                let s = r.last;
                assert_eq!(s.t, t);
                let (q, qd) = (s.q, s.qd);
                let c = c_at(&plan, &q);
                assert!(
                    c.dot(&qd).abs() <= 1e-9 * qd.norm().max(1.0),
                    "{name}: {s:?}"
                );
                // [A −c; cᵀ 0]·[q̈; μ] = [Q̃ − Γ − B·q̇; −q̇ᵀHq̇], Q̃ without the resistance.
                let a = free.inertia(&q).unwrap();
                let rhs = free.forces(t, &q, &qd).unwrap()
                    - tmm::dynamics::christoffel_terms(&free.inertia_derivatives(&q).unwrap(), &qd)
                        .unwrap()
                    - free.damping(&q).unwrap() * qd;
                let h = omega3(&plan, &q, &qd, &Vector2::zeros()).accel;
                let m = Matrix3::new(
                    a[(0, 0)],
                    a[(0, 1)],
                    -c[0], //
                    a[(1, 0)],
                    a[(1, 1)],
                    -c[1], //
                    c[0],
                    c[1],
                    0.0,
                );
                let x = m
                    .lu()
                    .solve(&Vector3::new(rhs[0], rhs[1], -h))
                    .expect("the constrained system is regular");
                let mu = x[2];
                assert!(
                    (loads.drive + mu).abs() <= 1e-9 * mu.abs().max(1.0),
                    "{name}: drive {} vs the holding couple {mu}",
                    loads.drive
                );
                assert!(mu.abs() <= 2.0 && loads.holds(), "{name}: {loads:?}");
            }
            Outcome::FinalTime => {}
            o => panic!("{name}: {o:?}"),
        }
    }
    println!("five-bar with a resisted coupler: {stuck} of 2 runs stuck");
    // Both integrators end stuck today: a change that let them run on to the final time
    // would skip every check of the holding couple above.
    assert_eq!(
        stuck, 2,
        "the holding couple was checked in {stuck} of 2 runs"
    );
}
