//! The dynamics of a described linkage (issue 16): two independent routes through the crate
//! agree, energy balances, the flywheel keeps the δ it was designed for, the five-bar robot
//! built from a description is the hand-modelled one, and bad input is an error.

use std::f64::consts::{PI, TAU};

use nalgebra::{Matrix2, Point2, Vector2};
use tmm::dynamics::machines::{FiveBar, LinearMotor};
use tmm::dynamics::{run, LagrangeSystem, Outcome, Rk4, RunOptions, State, Trajectory};
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{Damper, LinkageSystem, Motor, RunUpOptions};
use tmm::linkage::{bundled, At, Inputs, Linkage, LoadSpec, Mass, Plan};
use tmm::mechanism::{Compressor, Mechanism, RockingCylinder, SixBar, SliderCrank};
use tmm::{Error, Load};

/// The bundled linkages with masses and one crank input, and the course compressor.
fn one_input_linkages() -> Vec<(&'static str, Linkage)> {
    vec![
        ("four-bar", bundled::four_bar()),
        ("geared four-bar", bundled::geared_four_bar()),
        ("Watt six-bar", bundled::watt_six_bar()),
        ("Stephenson six-bar", bundled::stephenson_six_bar()),
        ("shaper", bundled::shaper()),
        (
            "compressor",
            Compressor::course_example().linkage().unwrap(),
        ),
        (
            "slider-crank",
            SliderCrank::course_example().linkage().unwrap(),
        ),
        (
            "geared slider-crank",
            SliderCrank::geared_example().linkage().unwrap(),
        ),
        (
            "rocking cylinder",
            RockingCylinder::course_example().linkage().unwrap(),
        ),
        ("six-bar", SixBar::course_example().linkage().unwrap()),
    ]
}

fn five_bar_system(fb: &FiveBar) -> LinkageSystem {
    LinkageSystem::from_linkage(&bundled::five_bar_robot())
        .unwrap()
        .with_motor(0, Motor::Servo(fb.drive1))
        .unwrap()
        .with_motor(1, Motor::Servo(fb.drive4))
        .unwrap()
}

fn max_abs(m: &Matrix2<f64>) -> f64 {
    m.iter().fold(0.0, |a, v| a.max(v.abs()))
}

/// A(q), ∂A/∂q and Q of the five-bar robot described as a linkage equal those of the
/// hand-written `FiveBar` over its workspace. Both are sums of a handful of products of
/// well-conditioned transfer functions (|sin(φ3 − φ2)| ≥ 0.2 here): rounding differences are
/// some 10⁻¹⁵ of the largest term, so 10⁻¹² relative leaves a margin of 100 and still fails
/// on any wrong term (a misplaced mass changes A by 10⁻²).
#[test]
fn five_bar_terms_equal_the_hand_model() {
    let fb = FiveBar::default();
    let sys = five_bar_system(&fb);
    let (mut worst_a, mut worst_da, mut worst_q, mut cases) = (0.0f64, 0.0f64, 0.0f64, 0);
    for i in 0..9 {
        for k in 0..9 {
            let q = Vector2::new(
                (95.0 + 6.0 * f64::from(i)).to_radians(),
                (35.0 + 6.0 * f64::from(k)).to_radians(),
            );
            let kin = fb.kinematics(&q).unwrap();
            assert!(kin.sin_phi3_minus_phi2.abs() > 0.2);
            let qd = Vector2::new(1.5 - 0.3 * f64::from(i), 0.2 * f64::from(k) - 0.7);
            let t = sys.split_terms(&q, &qd).unwrap();
            let a = fb.inertia(&q).unwrap();
            let da = fb.inertia_derivatives(&q).unwrap();
            let forces = fb.forces(0.0, &q, &qd).unwrap();
            worst_a = worst_a.max(max_abs(&(t.inertia - a)) / max_abs(&a));
            let da_scale = max_abs(&da[0]).max(max_abs(&da[1]));
            worst_da = worst_da.max(
                max_abs(&(t.inertia_derivatives[0] - da[0]))
                    .max(max_abs(&(t.inertia_derivatives[1] - da[1])))
                    / da_scale,
            );
            let q_scale = forces.amax().max(fb.m_on);
            worst_q = worst_q.max((t.forces() - forces).amax() / q_scale);
            cases += 1;
        }
    }
    println!(
        "five-bar over {cases} states: A {worst_a:.1e}, dA/dq {worst_da:.1e}, Q {worst_q:.1e}"
    );
    assert!(worst_a <= 1e-12, "A differs by {worst_a:e}");
    assert!(worst_da <= 1e-12, "dA/dq differs by {worst_da:e}");
    assert!(worst_q <= 1e-12, "Q differs by {worst_q:e}");
}

/// The couplers as rigid bodies with their own J_S and centres off the middle: the hand
/// model's exact variant (`j_s2`, `j_s3` set) equals the description with those masses.
#[test]
fn five_bar_with_rigid_couplers_equals_the_hand_model() {
    let fb = FiveBar {
        l_as2: 0.1,
        l_bs3: 0.08,
        j_s2: Some(0.004),
        j_s3: Some(0.006),
        ..FiveBar::default()
    };
    let mut l = bundled::five_bar_robot();
    let at = |n: &str| {
        let j = l.joints.iter().find(|j| j.name == n).unwrap();
        Vector2::new(j.at[0], j.at[1])
    };
    let (a, b, c) = (at("A"), at("B"), at("C"));
    let s2 = a + 0.1 * (b - a).normalize();
    let s3 = b + 0.08 * (c - b).normalize();
    l.links[2].mass = Some(Mass::new(0.6, 0.004, At::Coords([s2.x, s2.y])));
    l.links[3].mass = Some(Mass::new(0.6, 0.006, At::Coords([s3.x, s3.y])));
    let sys = LinkageSystem::from_linkage(&l)
        .unwrap()
        .with_motor(0, Motor::Servo(fb.drive1))
        .unwrap()
        .with_motor(1, Motor::Servo(fb.drive4))
        .unwrap();
    let mut worst = 0.0f64;
    for (p1, p4) in [
        (100.0, 50.0),
        (120.0, 60.0),
        (140.0, 80.0),
        (110.0, 40.0),
        (130.0, 75.0),
    ] {
        let q = Vector2::new(f64::to_radians(p1), f64::to_radians(p4));
        let t = sys.split_terms(&q, &Vector2::new(0.3, 1.2)).unwrap();
        let a = fb.inertia(&q).unwrap();
        let da = fb.inertia_derivatives(&q).unwrap();
        worst = worst
            .max(max_abs(&(t.inertia - a)) / max_abs(&a))
            .max(max_abs(&(t.inertia_derivatives[0] - da[0])) / max_abs(&da[0]))
            .max(max_abs(&(t.inertia_derivatives[1] - da[1])) / max_abs(&da[1]));
    }
    assert!(worst <= 1e-12, "{worst:e}");
}

/// With gravity the hand model takes it through its potential, the linkage as a load: Q of
/// the linkage is the hand model's Q − ∇Π.
#[test]
fn five_bar_gravity_is_the_potential_gradient() {
    let fb = FiveBar {
        gravity: 9.81,
        ..FiveBar::default()
    };
    let mut l = bundled::five_bar_robot();
    l.gravity = [0.0, -9.81];
    let sys = LinkageSystem::from_linkage(&l)
        .unwrap()
        .with_motor(0, Motor::Servo(fb.drive1))
        .unwrap()
        .with_motor(1, Motor::Servo(fb.drive4))
        .unwrap();
    let mut worst = 0.0f64;
    for (p1, p4) in [(100.0, 50.0), (120.0, 60.0), (140.0, 80.0), (110.0, 40.0)] {
        let q = Vector2::new(f64::to_radians(p1), f64::to_radians(p4));
        let qd = Vector2::new(0.4, -0.9);
        let hand = fb.forces(0.0, &q, &qd).unwrap() - fb.potential_gradient(&q).unwrap();
        let t = sys.split_terms(&q, &qd).unwrap();
        worst = worst.max((t.forces() - hand).amax() / hand.amax());
    }
    assert!(worst <= 1e-12, "gravity differs by {worst:e}");
}

/// RK4 runs of the two models from the same state with the same steps agree far better than
/// either agrees with the exact motion: the difference of the models is below the
/// integrator's own error, estimated by halving the step.
#[test]
fn five_bar_trajectories_agree_to_the_integrator_tolerance() {
    let fb = FiveBar::default();
    let sys = five_bar_system(&fb);
    let start = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    let end = |s: &dyn LagrangeSystem, h: f64| {
        let mut o = RunOptions::until(0.5, h);
        o.record_every = 1000;
        run(s, &Rk4, start, &o).unwrap().last
    };
    let hand = end(&fb, 2e-3);
    let hand_fine = end(&fb, 1e-3);
    let described = end(&sys, 2e-3);
    let diff = |a: &State, b: &State| (a.q - b.q).amax().max((a.qd - b.qd).amax());
    let models = diff(&hand, &described);
    let integrator = diff(&hand, &hand_fine);
    println!("five-bar at t = 0.5 s: models differ by {models:.1e}, the integrator's error {integrator:.1e}");
    assert!(integrator > 0.0);
    assert!(models <= 1e-3 * integrator, "{models:e} vs {integrator:e}");
}

/// The scale of a kinetostatic balance: Σ|P_i|/|q̇| (and |M_b|).
fn balance_scale(a: &tmm::linkage::Analysis<'_>) -> f64 {
    a.power_check().unwrap().scale
}

/// Inverse dynamics (Lagrange: J_red·ε + ½J_red′·ω² − M_red) and the kinetostatic balancing
/// moment (inertia loads, the groups from the last one back, the input link) are two
/// independent routes to the same driving moment. Both are sums of some 10–40 products
/// whose rounding is 10⁻¹⁶ each, amplified by the groups' conditioning (at most some 10²
/// away from dead points): 10⁻⁹ of the scale Σ|P_i|/|q̇| leaves a margin of 10³.
#[test]
fn inverse_dynamics_equals_the_balancing_moment() {
    let mut report = Vec::new();
    for (name, l) in one_input_linkages() {
        let plan = Plan::new(&l).unwrap();
        let sys = LinkageSystem::new(plan.clone()).unwrap();
        let mut worst = 0.0f64;
        let mut cases = 0;
        for (omega, eps) in [(10.0, 0.0), (-7.0, 25.0), (100.0, 0.0)] {
            for k in 0..72 {
                let phi = plan.reference_input() + f64::from(k) * TAU / 72.0;
                let a = plan.analyse(Motion::new(phi, omega, eps)).unwrap();
                let m = sys
                    .inverse_dynamics(
                        &Vector2::new(phi, 0.0),
                        &Vector2::new(omega, 0.0),
                        &Vector2::new(eps, 0.0),
                    )
                    .unwrap();
                let rel = (m[0] - a.balances()[0].value).abs() / balance_scale(&a);
                worst = worst.max(rel);
                cases += 1;
            }
        }
        report.push(format!("{name}: {worst:.1e} over {cases}"));
        assert!(worst <= 1e-9, "{name}: {worst:e}");
    }
    println!(
        "inverse dynamics vs balancing moment: {}",
        report.join("; ")
    );
}

/// A slider input (the slider-crank driven by its piston: the rod and crank an RRR group):
/// the generalized force is the driving force along the guide, N, and the routes agree as
/// for a crank, at 72 slides across the stroke away from the dead points.
#[test]
fn inverse_dynamics_of_a_slider_input() {
    let mut l = SliderCrank::course_example().linkage().unwrap();
    l.input = tmm::linkage::Input::crank("piston");
    l.groups.clear();
    l.modes.clear();
    // The indicator diagram needs the crank's turn for its dead centres: other loads instead.
    l.gravity = [0.0, -9.81];
    l.loads = vec![
        LoadSpec::Resistance {
            on: "crank".to_owned(),
            forward: 20.0,
            backward: 5.0,
            at: None,
        },
        LoadSpec::Force {
            link: "rod".to_owned(),
            at: At::name("A"),
            force: [30.0, -40.0],
        },
    ];
    let plan = Plan::new(&l).unwrap();
    assert!(!plan.input_is_crank());
    let sys = LinkageSystem::new(plan.clone()).unwrap();
    let (mut worst, mut cases) = (0.0f64, 0);
    for k in 0..400 {
        let s = -0.12 + 0.24 * f64::from(k) / 400.0;
        let (v, acc) = (1.5, -4.0);
        let Ok(a) = plan.analyse(Motion::new(s, v, acc)) else {
            continue;
        };
        if a.group_determinants()[0].abs() < 0.1 {
            continue;
        }
        let m = sys
            .inverse_dynamics(
                &Vector2::new(s, 0.0),
                &Vector2::new(v, 0.0),
                &Vector2::new(acc, 0.0),
            )
            .unwrap();
        worst = worst.max((m[0] - a.balances()[0].value).abs() / balance_scale(&a));
        cases += 1;
    }
    println!("slider input: {worst:.1e} over {cases} positions");
    assert!(cases >= 72, "{cases}");
    assert!(worst <= 1e-9, "{worst:e}");
}

/// A load added as a function of the state (a spring from a fixed point to B, a viscous
/// drag on the rocker) enters both routes the same way.
#[test]
fn inverse_dynamics_with_state_dependent_loads() {
    let mut plan = Plan::new(&bundled::four_bar()).unwrap();
    plan.add_load_fn("coupler", |a| {
        let b = a.joint("B")?;
        Ok(Load::force_at(
            b.p,
            -2000.0 * (b.p - Point2::new(0.5, 0.5)) - 30.0 * b.v,
        ))
    })
    .unwrap();
    plan.add_load_fn("rocker", |a| {
        let w = a.link("rocker")?.rate;
        Ok(Load::new(a.joint("O3")?.p, Vector2::zeros(), -0.8 * w))
    })
    .unwrap();
    let sys = LinkageSystem::new(plan.clone()).unwrap();
    let mut worst = 0.0f64;
    for k in 0..72 {
        let phi = f64::from(k) * TAU / 72.0;
        let a = plan.analyse(Motion::new(phi, 12.0, 0.0)).unwrap();
        let m = sys
            .inverse_dynamics(
                &Vector2::new(phi, 0.0),
                &Vector2::new(12.0, 0.0),
                &Vector2::zeros(),
            )
            .unwrap();
        worst = worst.max((m[0] - a.balances()[0].value).abs() / balance_scale(&a));
    }
    assert!(worst <= 1e-9, "{worst:e}");
}

/// Two inputs: the inverse dynamics of the five-bar robot gives both cranks' driving moments,
/// which the engine's kinetostatics with two balancing moments gives too.
#[test]
fn five_bar_inverse_dynamics_equals_both_balancing_moments() {
    let l = bundled::five_bar_robot();
    let plan = Plan::new(&l).unwrap();
    let sys = LinkageSystem::new(plan.clone()).unwrap();
    let mut worst = 0.0f64;
    for i in 0..8 {
        let q = Vector2::new(
            (100.0 + 5.0 * f64::from(i)).to_radians(),
            (45.0 + 4.0 * f64::from(i)).to_radians(),
        );
        let qd = Vector2::new(2.0 - 0.5 * f64::from(i), 1.0);
        let qdd = Vector2::new(3.0, -2.0 + f64::from(i));
        let a = plan
            .analyse(Inputs::two(
                Motion::new(q[0], qd[0], qdd[0]),
                Motion::new(q[1], qd[1], qdd[1]),
            ))
            .unwrap();
        assert!(a.worst_residual() < 1e-12);
        let m = sys.inverse_dynamics(&q, &qd, &qdd).unwrap();
        let b = Vector2::new(a.balances()[0].value, a.balances()[1].value);
        worst = worst.max((m - b).amax() / b.amax());
    }
    assert!(worst <= 1e-9, "{worst:e}");
}

/// Composite Simpson over equally spaced samples (an even number of intervals).
fn simpson(h: f64, y: &[f64]) -> f64 {
    assert!(y.len() % 2 == 1, "{} samples", y.len());
    let n = y.len() - 1;
    let mut s = y[0] + y[n];
    for (i, v) in y.iter().enumerate().take(n).skip(1) {
        s += if i % 2 == 1 { 4.0 } else { 2.0 } * v;
    }
    s * h / 3.0
}

fn energy_error(sys: &LinkageSystem, h: f64, t_end: f64) -> (f64, f64) {
    let start = State::at_rest(Vector2::new(sys.plan().reference_input(), 0.0));
    let r = run(sys, &Rk4, start, &RunOptions::until(t_end, h)).unwrap();
    let tr: &Trajectory = &r.trajectory;
    let net: Vec<f64> = tr
        .power_applied()
        .iter()
        .zip(tr.power_dissipated())
        .map(|(a, d)| a - d)
        .collect();
    let work = simpson(h, &net);
    let d_t = tr.kinetic().last().unwrap() - tr.kinetic()[0];
    let scale = simpson(
        h,
        &tr.power_applied()
            .iter()
            .map(|p| p.abs())
            .collect::<Vec<_>>(),
    );
    ((work - d_t).abs() / scale, d_t)
}

/// The change of kinetic energy equals the work of the motor, gravity, the coupler force and
/// the damper over a run from rest. RK4 and Simpson's rule are both of order 4: the balance's
/// error must fall by about 2⁴ when the step is halved (at least 8 allowed) and be small.
#[test]
fn energy_balance_over_a_run() {
    let mut l = bundled::four_bar();
    l.loads
        .retain(|x| !matches!(x, LoadSpec::Resistance { .. }));
    let sys = LinkageSystem::from_linkage(&l)
        .unwrap()
        .with_motor(0, Motor::Linear(LinearMotor { a: 30.0, b: 1.0 }))
        .unwrap()
        .with_inertia(0, 0.01)
        .unwrap()
        .with_damper(&Damper::Link {
            link: "rocker".to_owned(),
            c: 0.5,
        })
        .unwrap()
        .with_damper(&Damper::Joint {
            joint: "B".to_owned(),
            c: 0.2,
        })
        .unwrap();
    let (e1, dt) = energy_error(&sys, 2e-3, 1.0);
    let (e2, _) = energy_error(&sys, 1e-3, 1.0);
    println!(
        "energy balance: ΔT = {dt:.3} J, relative error {e1:.1e} (h = 2 ms), {e2:.1e} (h = 1 ms)"
    );
    assert!(dt > 1.0);
    assert!(e2 <= 1e-6, "{e2:e}");
    assert!(e2 <= e1 / 8.0 || e2 <= 1e-12, "{e1:e} -> {e2:e}");
}

/// The flywheel of the energy–mass method, added to the machine under the constant driving
/// moment it was designed with, gives the requested δ: one turn from the designed start is
/// integrated with 4000 RK4 steps (the integration error is some 10⁻¹⁰ of δ), and the
/// measured δ differs from the requested one by the design's discretisation: the work by the
/// trapezoidal rule over 3600 positions (errors of order (2π/3600)² ≈ 3·10⁻⁶ where the loads
/// are smooth, of order 2π/3600 ≈ 2·10⁻³ of a jump where a resistance switches on), and the
/// extremes sampled on that grid. Measured: at most 1.2·10⁻⁶ of δ over the four machines
/// and two δ each; asserted 10⁻⁵ (a design off by one grid step's work would miss it).
#[test]
fn flywheel_gives_the_required_delta() {
    let cases = [
        ("four-bar", bundled::four_bar(), 10.0),
        ("Watt six-bar", bundled::watt_six_bar(), 15.0),
        ("shaper", bundled::shaper(), 6.0),
        (
            "compressor",
            Compressor::course_example().linkage().unwrap(),
            Compressor::seed_speed(),
        ),
    ];
    let mut report = Vec::new();
    for (name, l, omega) in cases {
        let sys = LinkageSystem::from_linkage(&l).unwrap();
        for delta in [1.0 / 20.0, 1.0 / 50.0] {
            let f = sys.flywheel(delta, omega, 3600).unwrap();
            assert!(f.moment_of_inertia > 0.0, "{name}: {f:?}");
            let with = sys
                .clone()
                .with_motor(0, Motor::Constant(f.driving_moment))
                .unwrap()
                .with_inertia(0, f.moment_of_inertia)
                .unwrap();
            let start = State::new(
                0.0,
                Vector2::new(f.phi_start, 0.0),
                Vector2::new(f.omega_start.unwrap(), 0.0),
            );
            let mut opts = RunUpOptions::new(TAU / omega.abs() / 4000.0);
            opts.max_turn_time = 10.0 * TAU / omega.abs();
            let (turn, r) = with.turn(&Rk4, start, &opts).unwrap();
            let rel = (turn.delta / delta - 1.0).abs();
            // The turn closes: the designed start speed comes back.
            let back = (r.last.qd[0] / f.omega_start.unwrap() - 1.0).abs();
            let mid = 0.5 * (turn.omega_max + turn.omega_min) / omega.abs() - 1.0;
            report.push(format!(
                "{name} δ = 1/{:.0}: J_F = {:.4} (simplified {:.4}) kg·m², δ measured {:.6} (relative {:.1e}), mid-speed {mid:.1e}, time mean {:.1e}, closes {back:.1e}",
                1.0 / delta,
                f.moment_of_inertia,
                f.simplified,
                turn.delta,
                rel,
                turn.omega_mean / omega.abs() - 1.0,
            ));
            assert!(rel <= 1e-5, "{name}, δ = {delta}: measured {}", turn.delta);
            assert!(back <= 1e-6, "{name}: the turn does not close ({back:e})");
            assert!(
                mid.abs() <= 1e-3 * delta,
                "{name}: mean speed off by {mid:e}"
            );
        }
    }
    println!("{}", report.join("\n"));
}

/// The mean over a turn of the moment the motor gave along a recorded turn, ∮ M_d dφ / 2π
/// (the integrand M_d(ω)·ω over time), by the trapezoidal rule over the recorded steps with
/// one Richardson extrapolation (the rule over every second step gives the h² term), and the
/// same from every second and every fourth step: their difference bounds the error.
fn motor_mean_over_turn(sys: &LinkageSystem, t: &[f64], phi: &[f64], w: &[f64]) -> (f64, f64) {
    let f: Vec<f64> = (0..t.len())
        .map(|i| sys.motor(0).unwrap().moment(phi[i], w[i]).unwrap() * w[i])
        .collect();
    let trap = |step: usize| {
        let mut idx: Vec<usize> = (0..t.len()).step_by(step).collect();
        if *idx.last().unwrap() != t.len() - 1 {
            idx.push(t.len() - 1);
        }
        idx.windows(2)
            .map(|p| 0.5 * (f[p[0]] + f[p[1]]) * (t[p[1]] - t[p[0]]))
            .sum::<f64>()
    };
    let turned = (phi[phi.len() - 1] - phi[0]).abs();
    let (t1, t2, t4) = (trap(1), trap(2), trap(4));
    let fine = (4.0 * t1 - t2) / 3.0;
    let coarse = (4.0 * t2 - t4) / 3.0;
    (fine / turned, coarse / turned)
}

/// From rest under an induction motor the Watt six-bar settles: turn after turn the mean speed
/// grows towards a steady value below the motor's no-load speed, reached within the budget.
///
/// The run-up stops when two turns' mean speeds agree; that the machine is then in its steady
/// state is checked independently by the energy balance of a turn: in a periodic motion the
/// kinetic energy comes back, so the work of the motor over the turn equals the work of the
/// loads, ∮ M_d dφ = −∮ M_red dφ. The motor's side is read off the integrated motion (its
/// moment at the recorded speeds), the loads' side from the reduced moment of resistance over
/// a turn in φ ([`LinkageSystem::reduced_cycle`] at ω_m: the six-bar's resistance depends on
/// the direction of the motion only). The tolerance is the sum of what may separate them:
/// - the kinetic energy a turn may still gain at the run-up's tolerance: the mean speed
///   changing by tol·ω_m changes T by about J_red·ω²·tol, bounded by max J_red·ω_max²·tol
///   (twice that, for the turn-to-turn change not being the change within the turn), / 2π;
/// - the error of the loads' mean over 3600 positions (the resistance switches on and off
///   inside an interval): bounded by its difference from the mean over 1800;
/// - the quadrature of the motor's side (extrapolated trapezoids over the recorded steps):
///   bounded by its difference from the same over every second step (the steady turn is
///   integrated once more from its start at a tenth of the step for this);
/// - the integrator's error in the energy (RK4 at 5·10⁻⁵ s): 10⁻⁶ of the moment, far above
///   what the energy test above measures at such steps.
///
/// A turn started 20 % too slow from the same position misses the balance by far more: the
/// check tells a steady turn from one that is not.
#[test]
fn run_up_reaches_a_steady_state_within_its_budget() {
    let sys = LinkageSystem::from_linkage(&bundled::watt_six_bar())
        .unwrap()
        .with_motor(
            0,
            Motor::Linear(
                LinearMotor::from_nominal(40.0, 2.0 * PI * 25.0, 2.0 * PI * 24.0).unwrap(),
            ),
        )
        .unwrap()
        .with_inertia(0, 0.05)
        .unwrap();
    let mut opts = RunUpOptions::new(5e-4);
    opts.tol = 1e-7;
    opts.record_every = 10;
    let r = sys.run_up(&Rk4, &opts).unwrap();
    let n = r.turns.len();
    let last = r.turns[n - 1];
    println!(
        "run-up: {n} turns, steady ω_m = {:.4} rad/s, δ = {:.4}",
        last.omega_mean, last.delta
    );
    assert!(n >= 3);
    assert!((last.omega_mean - r.turns[n - 2].omega_mean).abs() <= opts.tol * last.omega_mean);
    assert!(last.omega_mean < 2.0 * PI * 25.0 && last.omega_mean > 2.0 * PI * 20.0);
    assert!(r.turns[0].omega_mean < r.turns[1].omega_mean);
    assert_eq!(r.t.len(), r.omega.len());

    // The energy balance of the steady turn, recorded at every step.
    opts.record_every = 1;
    let r = sys.run_up(&Rk4, &opts).unwrap();
    let last = *r.turns.last().unwrap();
    let tr = &r.steady.trajectory;
    let (phi, w) = (&tr.q()[0], &tr.qd()[0]);
    assert!((phi[phi.len() - 1] - phi[0] - TAU).abs() < 1e-9, "one turn");
    // The steady turn once more from its start, at a tenth of the step, for the quadrature.
    let steady = State::new(0.0, Vector2::new(phi[0], 0.0), Vector2::new(w[0], 0.0));
    let fine = opts.with_h(opts.h / 10.0);
    let (_, rf) = sys.turn(&Rk4, steady, &fine).unwrap();
    let tf = &rf.trajectory;
    let (motor, motor_2h) = motor_mean_over_turn(&sys, tf.t(), tf.q()[0], tf.qd()[0]);
    let loads_mean = |n: usize| {
        let c = sys.reduced_cycle(n, last.omega_mean).unwrap();
        c.iter().map(|x| x.loads).sum::<f64>() / n as f64
    };
    let (loads, loads_coarse) = (loads_mean(3600), loads_mean(1800));
    let turn_cycle = sys.reduced_cycle(360, last.omega_mean).unwrap();
    let j_max = turn_cycle.iter().map(|x| x.inertia).fold(0.0, f64::max);
    let unsteady = 2.0 * j_max * last.omega_max.powi(2) * opts.tol / TAU;
    let tol =
        unsteady + (loads - loads_coarse).abs() + (motor - motor_2h).abs() + 1e-6 * loads.abs();
    println!(
        "steady turn: motor's mean moment {motor:.7} N·m, loads' mean {loads:.7} N·m, \
         off by {:.2e} (tolerance {tol:.2e}: unsteady {unsteady:.1e}, loads' quadrature {:.1e}, \
         motor's quadrature {:.1e}); the motor at ω_m alone would give {:.4} N·m",
        motor + loads,
        (loads - loads_coarse).abs(),
        (motor - motor_2h).abs(),
        sys.motor(0).unwrap().moment(0.0, last.omega_mean).unwrap()
    );
    assert!(loads < 0.0, "the loads resist: {loads}");
    assert!((motor + loads).abs() <= tol, "{motor} vs {loads}");
    // The check has teeth: a turn from the same position 20 % too slow gains energy.
    let slow = State::new(
        0.0,
        Vector2::new(phi[0], 0.0),
        Vector2::new(0.8 * w[0], 0.0),
    );
    let (_, rs) = sys.turn(&Rk4, slow, &opts).unwrap();
    let ts = &rs.trajectory;
    let (m_slow, _) = motor_mean_over_turn(&sys, ts.t(), ts.q()[0], ts.qd()[0]);
    println!("a turn 20 % too slow: off by {:.2e}", m_slow + loads);
    assert!((m_slow + loads).abs() > 100.0 * tol, "{m_slow} vs {loads}");
    // The budget: too few turns is an error naming it, not an endless run.
    opts.max_turns = 2;
    let e = sys.run_up(&Rk4, &opts).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Budget {
                what: "turn",
                limit: 2,
                ..
            }
        ),
        "{e}"
    );
}

/// A machine that cannot turn (no motor, or one too weak for its loads) is an error, found
/// within the turn's time limit.
#[test]
fn a_machine_that_does_not_turn_is_an_error() {
    let mut l = bundled::four_bar();
    l.gravity = [0.0, 0.0];
    l.loads.clear();
    let idle = LinkageSystem::from_linkage(&l).unwrap();
    let mut opts = RunUpOptions::new(1e-3);
    opts.max_turn_time = 1.0;
    assert!(matches!(
        idle.run_up(&Rk4, &opts),
        Err(Error::Singular { .. })
    ));
    let weak = LinkageSystem::from_linkage(&bundled::four_bar())
        .unwrap()
        .with_motor(0, Motor::Constant(1.0))
        .unwrap();
    // Its resistances hold it at rest: the run-up says so at once, naming both loads.
    let e = weak.run_up(&Rk4, &opts).unwrap_err();
    let Error::Stalled {
        time,
        drive,
        resistance,
        unit: "N·m",
    } = e
    else {
        panic!("{e}")
    };
    let phi0 = weak.plan().reference_input();
    let at_rest = weak.reduced(phi0, 0.0).unwrap();
    assert_eq!(time, 0.0);
    assert!(
        (drive - (at_rest.loads + 1.0).abs()).abs() < 1e-12,
        "{drive}"
    );
    assert!(drive < resistance, "{e}");
}

/// The bundled four-bar thrown at 17.25 rad/s with no motor (issue 27): its loads and the
/// rocker's resistance of 40 N·m bring it to rest within a turn, where the resistance holds
/// it. The run lands on ω = 0 and ends there, stuck, in a few dozen steps (it chattered
/// about ω = 0 until ten million steps ran out). The stop is where the energy equation says:
/// ½·J_red(φ₀)·ω₀² + ∫_φ₀^φ* M_red⁺(φ) dφ = 0, with M_red⁺ the loads' reduced moment while
/// the crank turns forward (no load depends on the speed's size), by Simpson's rule and
/// bisection; and the driving load there is below the breakaway, as the error says.
#[test]
fn four_bar_thrown_without_a_motor_stops_where_its_energy_runs_out() {
    use tmm::dynamics::{Direction, Dopri5, Outcome, Reach, Watch};
    let sys = LinkageSystem::from_linkage(&bundled::four_bar()).unwrap();
    let (phi0, w0) = (0.0, 17.25);
    let start = State::new(0.0, Vector2::new(phi0, 0.0), Vector2::new(w0, 0.0));
    let dp = Dopri5 {
        rtol: 1e-10,
        atol: 1e-10,
    };
    let mut opts = RunOptions::until(0.95, 1e-3);
    opts.reach = Some(Reach {
        watch: Watch::Coordinate(0),
        value: phi0 + TAU,
        direction: Direction::Rising,
    });
    let r = run(&sys, &dp, start, &opts).unwrap();
    let Outcome::Stuck {
        t,
        switch: 0,
        loads,
    } = r.outcome
    else {
        panic!("{:?}", r.outcome)
    };
    assert!(r.steps < 100, "{} steps", r.steps);
    // The energy equation's stop angle.
    let e0 = 0.5 * sys.reduced(phi0, w0).unwrap().inertia * w0 * w0;
    let work = |phi: f64| {
        let n = 2000;
        let h = (phi - phi0) / n as f64;
        let m: Vec<f64> = (0..=n)
            .map(|i| sys.reduced(phi0 + h * i as f64, 1.0).unwrap().loads)
            .collect();
        simpson(h, &m)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    assert!(e0 + work(hi) < 0.0);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if e0 + work(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let phi_stop = 0.5 * (lo + hi);
    let got = r.last.q[0];
    println!(
        "stopped at t = {t} s, φ = {got} (energy: {phi_stop}), {} steps",
        r.steps
    );
    assert!((got - phi_stop).abs() < 1e-10, "{got} vs {phi_stop}");
    // The loads there: the drive is the reduced moment at rest, below the breakaway.
    let rest = sys.reduced(got, 0.0).unwrap().loads;
    let forward = sys.reduced(got, 1.0).unwrap().loads;
    assert!((loads.drive - rest).abs() < 1e-12);
    assert!((loads.forward - (rest - forward)).abs() < 1e-9);
    assert!(loads.holds());
    // Through `turn`, as the issue ran it: an error naming both loads, at once.
    let turn_opts = RunUpOptions::new(1e-3).with_max_turn_time(0.95);
    let loose = Dopri5 {
        rtol: 1e-6,
        atol: 1e-6,
    };
    let e = sys.turn(&loose, start, &turn_opts).unwrap_err();
    let Error::Stalled {
        time,
        drive,
        resistance,
        ..
    } = e
    else {
        panic!("{e}")
    };
    assert!((time - t).abs() < 1e-6 && drive < resistance, "{e}");
    assert!(e.to_string().starts_with("stopped at t = 0.0221"), "{e}");
    // A motor of 3 N·m does not change the verdict: it stalls a little further on.
    let motored = sys.clone().with_motor(0, Motor::Constant(3.0)).unwrap();
    let r3 = run(&motored, &dp, start, &opts).unwrap();
    let Outcome::Stuck { loads: l3, .. } = r3.outcome else {
        panic!("{:?}", r3.outcome)
    };
    assert!(r3.last.q[0] > got && l3.holds());
    let drive3 = sys.reduced(r3.last.q[0], 0.0).unwrap().loads + 3.0;
    assert!((l3.drive - drive3).abs() < 1e-12);
}

/// Bad input is a `tmm::Error`, never a panic or a NaN.
#[test]
fn bad_input_is_an_error() {
    let sys = LinkageSystem::from_linkage(&bundled::four_bar()).unwrap();
    let z = Vector2::zeros();
    assert!(matches!(
        sys.split_terms(&Vector2::new(f64::NAN, 0.0), &z),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        sys.split_terms(&z, &Vector2::new(f64::INFINITY, 0.0)),
        Err(Error::NonFinite { .. })
    ));
    assert!(sys.clone().with_motor(1, Motor::Constant(1.0)).is_err());
    assert!(sys
        .clone()
        .with_motor(0, Motor::Constant(f64::NAN))
        .is_err());
    assert!(sys.clone().with_inertia(0, -1.0).is_err());
    assert!(sys.clone().with_inertia(0, f64::NAN).is_err());
    assert!(sys
        .clone()
        .with_damper(&Damper::Link {
            link: "nope".into(),
            c: 1.0
        })
        .is_err());
    assert!(sys
        .clone()
        .with_damper(&Damper::Joint {
            joint: "B".into(),
            c: -1.0
        })
        .is_err());
    for d in [0.0, -0.1, 2.0, f64::NAN] {
        assert!(sys.flywheel(d, 10.0, 360).is_err());
    }
    assert!(sys.flywheel(0.05, 0.0, 360).is_err());
    assert!(sys.flywheel(0.05, 10.0, 3).is_err());
    assert!(sys.reduced_cycle(0, 10.0).is_err());
    assert!(sys
        .inverse_dynamics(&z, &z, &Vector2::new(f64::NAN, 0.0))
        .is_err());
    let mut opts = RunUpOptions::new(1e-3);
    opts.tol = 0.0;
    assert!(sys.run_up(&Rk4, &opts).is_err());
    // Two inputs: the one-crank tools refuse, a pose that cannot assemble is an error.
    let five = LinkageSystem::from_linkage(&bundled::five_bar_robot()).unwrap();
    assert!(matches!(
        five.reduced(1.0, 1.0),
        Err(Error::Description { .. })
    ));
    assert!(five.flywheel(0.05, 10.0, 360).is_err());
    let far = five.split_terms(&Vector2::new(PI, 0.0), &z);
    assert!(far.is_err());
    let plan = five.plan();
    assert!(plan.kinematics(Motion::new(2.0, 1.0, 0.0)).is_err());
    assert!(plan.analyse(Motion::fixed(2.0)).is_err());
    // A second input on a linkage of mobility 1: the mobility does not match.
    let mut l = bundled::four_bar();
    l.second_input = Some(tmm::linkage::Input::crank("rocker"));
    let e = Plan::new(&l).unwrap_err().to_string();
    assert!(e.contains("W = 1"), "{e}");
    l.second_input = Some(tmm::linkage::Input::crank("crank"));
    assert!(Plan::new(&l).is_err());
}

/// The description with two inputs reads and writes as JSON; one input writes no
/// `second_input` field (the bundled files keep their form).
#[cfg(feature = "serde")]
#[test]
fn a_second_input_reads_and_writes_as_json() {
    let l = bundled::five_bar_robot();
    let text = l.to_json().unwrap();
    assert!(text.contains("second_input"));
    assert_eq!(Linkage::from_json(&text).unwrap(), l);
    assert!(!bundled::four_bar()
        .to_json()
        .unwrap()
        .contains("second_input"));
}

/// The largest difference between the link motions the rates-only pass gave (seen by a load
/// added as a function of the state, which `terms` evaluates after re-solving the rates at the
/// state's q̇ on the positions it solved once) and a full kinematic solve at the same inputs,
/// relative to the largest velocity and acceleration of the position; stored as f64 bits.
static WORST_RATES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

fn record_rates_difference(plan: &Plan, a: &tmm::linkage::Pose<'_>) -> tmm::Result<()> {
    let full = plan.kinematics(a.inputs())?;
    let n = plan.link_names().len();
    let (mut v_scale, mut a_scale, mut w_scale, mut e_scale) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for k in 0..n {
        let m = full.link_motion(k)?;
        v_scale = v_scale.max(m.origin.v.norm());
        a_scale = a_scale.max(m.origin.a.norm());
        w_scale = w_scale.max(m.omega.abs());
        e_scale = e_scale.max(m.epsilon.abs());
    }
    let mut worst = 0.0f64;
    for k in 0..n {
        let (x, y) = (a.link_motion(k)?, full.link_motion(k)?);
        // The positions are the same solve's: bitwise.
        assert_eq!((x.origin.p, x.angle), (y.origin.p, y.angle), "link {k}");
        worst = worst
            .max((x.origin.v - y.origin.v).norm() / v_scale.max(1e-300))
            .max((x.origin.a - y.origin.a).norm() / a_scale.max(1e-300))
            .max((x.omega - y.omega).abs() / w_scale.max(1e-300))
            .max((x.epsilon - y.epsilon).abs() / e_scale.max(1e-300));
    }
    WORST_RATES.fetch_max(worst.to_bits(), std::sync::atomic::Ordering::Relaxed);
    Ok(())
}

/// Two inputs solve the positions once and only the (linear) rate problems at the other unit
/// rates; a load added as a function of the state sees the rates re-solved at the state's q̇.
/// For every group kind (RRR, RRP, RPR, PRP, RPP, across the bundled linkages, the course
/// mechanisms and the five-bar robot with two inputs) those rates equal a full kinematic
/// solve's to rounding (10⁻¹³ of the position's largest), and the positions are bitwise the
/// same.
#[test]
fn the_rates_only_pass_equals_a_full_solve_for_every_group_kind() {
    use tmm::linkage::GroupKind;
    let mut linkages: Vec<(String, Linkage)> = bundled::all()
        .into_iter()
        .map(|l| (l.name.clone(), l))
        .collect();
    linkages.extend(
        one_input_linkages()
            .into_iter()
            .map(|(n, l)| (n.to_owned(), l)),
    );
    linkages.push(("five-bar robot".to_owned(), bundled::five_bar_robot()));
    let mut kinds = Vec::new();
    let mut states = 0;
    for (name, l) in linkages {
        let mut plan = Plan::new(&l).unwrap();
        kinds.extend(plan.groups().iter().map(|g| g.kind));
        let moving = plan.link_names()[1].clone();
        let kinematic = plan.clone();
        plan.add_load_fn(&moving, move |a| {
            record_rates_difference(&kinematic, a)?;
            Ok(Load::new(Point2::origin(), Vector2::zeros(), 0.0))
        })
        .unwrap();
        let refs = plan.reference_inputs();
        let two = refs.len() == 2;
        let sys = LinkageSystem::new(plan).unwrap();
        for k in 0..24 {
            let d = f64::from(k) * if two { 0.01 } else { TAU / 24.0 };
            let q = Vector2::new(refs[0] + d, if two { refs[1] - 0.5 * d } else { 0.0 });
            let qd = Vector2::new(7.0, if two { -3.0 } else { 0.0 });
            let inputs = [Motion::new(q[0], qd[0], 0.0), Motion::new(q[1], qd[1], 0.0)];
            let n = if two { 2 } else { 1 };
            if sys.split_terms(&q, &qd).is_ok() {
                states += 1;
            } else {
                // Only where the position cannot be solved at all.
                assert!(
                    sys.plan()
                        .kinematics(Inputs::from_slice(&inputs[..n]).unwrap())
                        .is_err(),
                    "{name} at {q:?}"
                );
            }
        }
    }
    let worst = f64::from_bits(WORST_RATES.load(std::sync::atomic::Ordering::Relaxed));
    println!("rates-only pass against full solves: {states} states, worst {worst:.1e}");
    for kind in [
        GroupKind::Rrr,
        GroupKind::Rrp,
        GroupKind::Rpr,
        GroupKind::Prp,
        GroupKind::Rpp,
    ] {
        assert!(kinds.contains(&kind), "{kind:?} not covered");
    }
    assert!(states >= 200, "{states}");
    assert!(worst <= 1e-13, "{worst:e}");
}

/// `LagrangeSystem::terms` gives every part at once from one kinematic evaluation (the
/// described linkages, the hand-written five-bar): the same values as the separate methods,
/// bitwise, and the accelerations from them are those of the separate parts by Cramer's rule.
#[test]
fn terms_at_once_equal_the_separate_methods() {
    let fb = FiveBar {
        gravity: 9.81,
        j_s2: Some(0.004),
        ..FiveBar::default()
    };
    let watt = LinkageSystem::from_linkage(&bundled::watt_six_bar())
        .unwrap()
        .with_motor(0, Motor::Linear(LinearMotor { a: 40.0, b: 0.2 }))
        .unwrap()
        .with_damper(&Damper::Link {
            link: "link 5".to_owned(),
            c: 0.3,
        })
        .unwrap();
    let robot = five_bar_system(&fb);
    let systems: [(&str, &dyn LagrangeSystem); 3] = [
        ("five-bar (hand)", &fb),
        ("five-bar (described)", &robot),
        ("Watt six-bar", &watt),
    ];
    for (name, sys) in systems {
        for k in 0..6 {
            let x = f64::from(k);
            let q = Vector2::new(1.9 + 0.05 * x, 1.2 - 0.04 * x);
            let qd = Vector2::new(2.0 - x, 0.5 * x - 1.0);
            let t = 0.1 * x;
            let all = sys.terms(t, &q, &qd).unwrap();
            assert_eq!(all.inertia, sys.inertia(&q).unwrap(), "{name}");
            assert_eq!(
                all.inertia_derivatives,
                sys.inertia_derivatives(&q).unwrap(),
                "{name}"
            );
            assert_eq!(all.forces, sys.forces(t, &q, &qd).unwrap(), "{name}");
            assert_eq!(all.damping, sys.damping(&q).unwrap(), "{name}");
            // The potential gradient: the hand five-bar's analytic one; the linkage has none
            // (gravity is one of its loads).
            let g = sys.potential_gradient(&q).unwrap();
            assert!(
                (all.potential_gradient - g).amax() <= 1e-9 * (1.0 + g.amax()),
                "{name}"
            );
            // The accelerations solve A q̈ = Q − c − ∇Π − B q̇ with the parts.
            let acc = tmm::dynamics::accelerations(sys, t, &q, &qd).unwrap();
            let c = tmm::dynamics::christoffel_terms(&all.inertia_derivatives, &qd).unwrap();
            let rhs = all.forces - c - all.potential_gradient - all.damping * qd;
            let res = all.inertia * acc - rhs;
            assert!(res.amax() <= 1e-12 * (1.0 + rhs.amax()), "{name}: {res:?}");
        }
    }
}

/// The default `terms` reports the first failure in the order `accelerations` always has:
/// A not positive-definite before a failing derivative or force, a non-finite force before a
/// failing potential.
#[test]
fn the_default_terms_reports_the_first_failure_first() {
    struct Broken {
        inertia: Matrix2<f64>,
        force: f64,
    }
    impl LagrangeSystem for Broken {
        fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
            Ok(self.inertia)
        }
        fn inertia_derivatives(&self, _: &Vector2<f64>) -> tmm::Result<[Matrix2<f64>; 2]> {
            Err(Error::Overflow { what: "dA/dq" })
        }
        fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
            Ok(Vector2::new(self.force, 0.0))
        }
        fn potential(&self, _: &Vector2<f64>) -> tmm::Result<f64> {
            Err(Error::Overflow { what: "potential" })
        }
    }
    let (q, qd) = (Vector2::zeros(), Vector2::zeros());
    let indefinite = Broken {
        inertia: Matrix2::new(1.0, 2.0, 2.0, 1.0),
        force: 1.0,
    };
    for r in [
        indefinite.terms(0.5, &q, &qd).map(|_| ()),
        tmm::dynamics::accelerations(&indefinite, 0.5, &q, &qd).map(|_| ()),
    ] {
        assert!(matches!(r, Err(Error::NotPositiveDefinite { .. })), "{r:?}");
    }
    let good = Broken {
        inertia: Matrix2::identity(),
        force: 1.0,
    };
    let r = tmm::dynamics::accelerations(&good, 0.5, &q, &qd);
    assert!(matches!(r, Err(Error::Overflow { what: "dA/dq" })), "{r:?}");
    // Derivatives that work, a NaN force and a failing potential: the NaN is named first.
    struct NanForce(Broken);
    impl LagrangeSystem for NanForce {
        fn inertia(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
            self.0.inertia(q)
        }
        fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
            self.0.forces(t, q, qd)
        }
        fn potential(&self, q: &Vector2<f64>) -> tmm::Result<f64> {
            self.0.potential(q)
        }
    }
    let nan = NanForce(Broken {
        inertia: Matrix2::identity(),
        force: f64::NAN,
    });
    let r = tmm::dynamics::accelerations(&nan, 0.5, &q, &qd);
    assert!(
        matches!(r, Err(Error::NonFiniteState { time }) if time == 0.5),
        "{r:?}"
    );
}

/// A described linkage driven by servos reports their clamps as kinks, as the hand-written
/// five-bar does (the same argument at every state), so RK4 keeps its fourth order across a
/// saturation; stepping across the switch instead costs two orders of accuracy. The robot
/// of the five-bar's own servo test: crank 1 saturated at the start, switching once at
/// about 0.05 s; crank 4's servo never saturates.
#[test]
fn servo_clamps_of_a_described_linkage_are_kinks() {
    let mut fb = FiveBar::default();
    fb.drive4.limit = 1e3;
    let sys = five_bar_system(&fb);
    assert_eq!(sys.kinks(), vec![vec![-1.0, 1.0], vec![-1.0, 1.0]]);
    for (a, b, w1, w4) in [
        (120.0, 60.0, 0.0, 0.0),
        (110.0, 70.0, 3.0, -2.0),
        (125.0, 50.0, -9.0, 1.0),
    ] {
        let q = Vector2::new(f64::to_radians(a), f64::to_radians(b));
        let qd = Vector2::new(w1, w4);
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        sys.kink_arguments(0.0, &q, &qd, &mut a).unwrap();
        fb.kink_arguments(0.0, &q, &qd, &mut b).unwrap();
        assert_eq!(a, b);
    }
    let s0 = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    let t_end = 0.12;
    let end = |n: u32, locate: bool| {
        let mut opts = RunOptions::until(t_end, t_end / f64::from(n));
        opts.record_every = usize::MAX;
        opts.locate_kinks = locate;
        run(&sys, &Rk4, s0, &opts).unwrap().last
    };
    let reference = end(64 * 160, true);
    let diff = |s: State| (s.q - reference.q).amax().max((s.qd - reference.qd).amax());
    let with: Vec<f64> = [40, 80, 160].iter().map(|&n| diff(end(n, true))).collect();
    for w in with.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((3.6..4.6).contains(&order), "order {order}: {with:?}");
    }
    let without = diff(end(160, false));
    assert!(with[2] * 100.0 < without, "{with:?} vs {without}");
}

/// A tabulated motor's characteristic M(q̇) has a kink at each node of its table: the run
/// is told them, with q̇ of its input as the argument.
#[test]
fn a_tabulated_motor_reports_its_nodes_as_kinks() {
    let table = tmm::dynamics::Table::new(
        vec![0.0, 50.0, 100.0, 150.0],
        vec![80.0, 70.0, 40.0, 0.0],
        tmm::dynamics::Beyond::HoldEnds,
    )
    .unwrap();
    let sys = LinkageSystem::from_linkage(&bundled::four_bar())
        .unwrap()
        .with_motor(0, Motor::Tabulated(table))
        .unwrap();
    assert_eq!(sys.kinks(), vec![vec![0.0, 50.0, 100.0, 150.0]]);
    let (q, qd) = (Vector2::new(1.0, 0.0), Vector2::new(73.5, 0.0));
    let mut rate = [0.0];
    sys.kink_arguments(0.0, &q, &qd, &mut rate).unwrap();
    assert_eq!(rate, [73.5]);
    // A smooth motor has none.
    let linear = LinkageSystem::from_linkage(&bundled::four_bar())
        .unwrap()
        .with_motor(0, Motor::Linear(LinearMotor { a: 40.0, b: 0.2 }))
        .unwrap();
    assert!(linear.kinks().is_empty());
}

/// A motor and an added inertia are read back on the inputs the linkage has, and asking
/// for an input it does not have is an error naming the index (not a silent `Motor::None`).
#[test]
fn motors_and_added_inertia_by_input_index() {
    let fb = FiveBar::default();
    let sys = five_bar_system(&fb).with_inertia(1, 0.25).unwrap();
    assert_eq!(sys.dof(), 2);
    assert!(matches!(sys.motor(0), Ok(Motor::Servo(s)) if *s == fb.drive1));
    assert!(matches!(sys.motor(1), Ok(Motor::Servo(s)) if *s == fb.drive4));
    assert_eq!(sys.added_inertia(0).unwrap(), 0.0);
    assert_eq!(sys.added_inertia(1).unwrap(), 0.25);
    let one = LinkageSystem::from_linkage(&bundled::four_bar()).unwrap();
    assert_eq!(one.dof(), 1);
    for (s, n) in [(&sys, 2usize), (&one, 1)] {
        for i in [n, n + 1, usize::MAX] {
            for e in [s.motor(i).err(), s.added_inertia(i).err()] {
                assert!(
                    matches!(e, Some(Error::OutOfRange { name: "input index", max, .. }) if max == n as f64 - 1.0),
                    "{e:?}"
                );
            }
        }
    }
}

/// The five-bar robot with a motor on its first input only (1 N·m) and none on the second
/// runs from rest into a dead centre of its coupler dyad, where its two inputs no longer
/// describe the motion (the reduced inertia grows as 1/det²). A fixed-step run used to step
/// across it and return Ok with the kinetic energy 10⁸ times the work done; the run must
/// stop there ([`Outcome::DeadCentre`]), naming the dyad and its determinant, with its
/// rows kept; the stop is located to the integrator's accuracy (RK4 at h and h/4 and
/// Dormand–Prince at 10⁻¹⁰ agree on its time), and every state it passed before must
/// balance the energy (the kinetic energy gained equals the motor's work, to RK4's error).
#[test]
fn a_run_into_a_dead_centre_of_two_inputs_stops_there_naming_the_dyad() {
    let sys = LinkageSystem::from_linkage(&bundled::five_bar_robot())
        .unwrap()
        .with_motor(0, Motor::Linear(LinearMotor { a: 1.0, b: 0.0 }))
        .unwrap();
    let reference = sys.plan().reference_inputs();
    let q0 = Vector2::new(reference[0], reference[1]);
    let h = 0.65 / 4000.0;
    let stop = |r: &tmm::dynamics::RunResult| {
        let Outcome::DeadCentre { t, dyad, value } = r.outcome else {
            panic!("{:?}", r.outcome)
        };
        assert_eq!(r.last.t, t);
        assert_eq!(r.trajectory.t().last(), Some(&t));
        assert!(value.abs() <= 1e-3, "{value}");
        // The located state is the last the system accepts: its dyad just outside the band.
        let k = sys
            .plan()
            .kinematics([Motion::fixed(r.last.q[0]), Motion::fixed(r.last.q[1])])
            .unwrap();
        let det = k.group_determinants()[dyad];
        assert!(det.abs() > 1e-3 && det.abs() < 1.001e-3, "{det}");
        (t, dyad)
    };
    let coarse = run(&sys, &Rk4, State::at_rest(q0), &RunOptions::until(0.65, h)).unwrap();
    let (t, dyad) = stop(&coarse);
    let name = &sys.plan().groups()[dyad].name;
    assert!(name.contains("coupler") || name.contains("RRR"), "{name}");
    let fine = run(
        &sys,
        &Rk4,
        State::at_rest(q0),
        &RunOptions::until(0.65, h / 4.0),
    )
    .unwrap();
    let dp = run(
        &sys,
        &tmm::dynamics::Dopri5::new(1e-10).unwrap(),
        State::at_rest(q0),
        &RunOptions::until(0.65, h),
    )
    .unwrap();
    let (t_fine, t_dp) = (stop(&fine).0, stop(&dp).0);
    println!(
        "dead centre of {name} at t = {t} (RK4 h), {t_fine} (h/4), {t_dp} (Dormand-Prince \
         1e-10): {:.1e}, {:.1e}",
        t - t_dp,
        t_fine - t_dp
    );
    assert!((t - t_dp).abs() < 1e-6 && (t_fine - t_dp).abs() < 1e-8);
    assert!(coarse.trajectory.len() > 3000);
    // Up to shortly before the dead centre, the energy balances: the kinetic energy gained
    // equals the work of the applied loads less the losses (trapezoids over the steps).
    let mut opts = RunOptions::until(0.5, h);
    opts.record_every = 1;
    let r = run(&sys, &Rk4, State::at_rest(q0), &opts).unwrap();
    let tr = &r.trajectory;
    let (t, kinetic) = (tr.t(), tr.kinetic());
    let (applied, lost) = (tr.power_applied(), tr.power_dissipated());
    let p = |i: usize| applied[i] - lost[i];
    let work: f64 = (1..tr.len())
        .map(|i| 0.5 * (p(i - 1) + p(i)) * (t[i] - t[i - 1]))
        .sum();
    let gained = kinetic[tr.len() - 1] - kinetic[0];
    assert!(
        (gained - work).abs() <= 1e-6 * work.abs(),
        "kinetic energy {gained} against the work {work}"
    );
}

/// The bundled four-bar driven from its rocker (its resistance taken off; gravity and the
/// coupler's load kept), thrown at 3 rad/s under a constant moment of 30 N·m towards the
/// rocker's upper lock, where the crank and the coupler stretch into one line: the rocker
/// slows to rest there (the reduced inertia grows as 1/det², det ∝ √(φ_L − φ)) in a finite
/// time. The run stops where the dyad's |det| reaches 10⁻³ ([`Outcome::DeadCentre`]), rows
/// kept. Independently of any integrator: the lock φ_L from the closed-form lock positions;
/// the angle φ_s where |det| = 10⁻³ by bisection on the plan's kinematics; the time to reach
/// it from the energy equation ½J(φ)ω² = ½J(φ₀)ω₀² + ∫(M + M_red)dφ, t = ∫dφ/ω, in
/// u = √(φ_L − φ) (where dt/du is smooth) by Simpson's rule.
#[test]
fn a_rocker_driven_four_bar_stops_at_its_lock_when_the_energy_equation_says() {
    let mut l = bundled::four_bar();
    l.input = tmm::linkage::Input::crank("rocker");
    l.groups.clear();
    l.modes.clear();
    l.loads
        .retain(|x| !matches!(x, LoadSpec::Resistance { .. }));
    let (m, w0) = (30.0, 3.0);
    let sys = LinkageSystem::from_linkage(&l)
        .unwrap()
        .with_motor(0, Motor::Constant(m))
        .unwrap();
    let plan = sys.plan().clone();
    let phi0 = plan.reference_input();
    let (_, lock) = plan
        .lock_positions(phi0)
        .unwrap()
        .expect("the rocker rocks");
    assert!(lock > phi0);
    let det = |phi: f64| {
        plan.kinematics(Motion::fixed(phi))
            .map(|k| k.group_determinants()[0].abs())
            .unwrap_or(0.0)
    };
    // φ_s: |det| = 10⁻³ between the start and the lock, on the side that is accepted.
    let (mut a, mut b) = (phi0, lock);
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if det(mid) > 1e-3 {
            a = mid;
        } else {
            b = mid;
        }
    }
    let phi_s = a;
    // The energy equation in u = √(φ_L − φ): Simpson's rule for W at the even nodes, then
    // for t over them.
    let n: u32 = 4000;
    let (u0, us) = ((lock - phi0).sqrt(), (lock - phi_s).sqrt());
    let du = (us - u0) / f64::from(n);
    let nodes: Vec<(f64, f64, f64)> = (0..=n)
        .map(|i| {
            let u = u0 + du * f64::from(i);
            let r = sys.reduced(lock - u * u, 1.0).unwrap();
            // dφ/du = −2u.
            (u, r.inertia, (m + r.loads) * (-2.0 * u))
        })
        .collect();
    let e0 = 0.5 * nodes[0].1 * w0 * w0;
    let mut work = 0.0;
    let mut dt_du = Vec::new();
    for k in (0..nodes.len()).step_by(2) {
        if k > 0 {
            work += du / 3.0 * (nodes[k - 2].2 + 4.0 * nodes[k - 1].2 + nodes[k].2);
        }
        let (u, j, _) = nodes[k];
        let energy = e0 + work;
        assert!(energy > 0.0, "the rocker must reach its lock");
        dt_du.push(-2.0 * u / (2.0 * energy / j).sqrt());
    }
    let t_s: f64 = (2..dt_du.len())
        .step_by(2)
        .map(|i| 2.0 * du / 3.0 * (dt_du[i - 2] + 4.0 * dt_du[i - 1] + dt_du[i]))
        .sum();
    let start = State::new(0.0, Vector2::new(phi0, 0.0), Vector2::new(w0, 0.0));
    let cases: [(&str, tmm::dynamics::RunResult, f64); 4] = [
        (
            "Dormand-Prince 1e-10",
            run(
                &sys,
                &tmm::dynamics::Dopri5::new(1e-10).unwrap(),
                start,
                &RunOptions::until(5.0, 1e-3),
            )
            .unwrap(),
            1e-9,
        ),
        (
            "RK4 1e-4",
            run(&sys, &Rk4, start, &RunOptions::until(5.0, 1e-4)).unwrap(),
            1e-5,
        ),
        (
            "RK4 1e-5",
            run(&sys, &Rk4, start, &RunOptions::until(5.0, 1e-5)).unwrap(),
            1e-6,
        ),
        (
            "finite increments 1e-5",
            run(
                &sys,
                &tmm::dynamics::FiniteIncrement,
                start,
                &RunOptions::until(5.0, 1e-5),
            )
            .unwrap(),
            1e-3,
        ),
    ];
    for (name, r, _) in &cases {
        println!(
            "{name}: {:?} at {:?}, {} rows",
            r.outcome,
            r.last,
            r.trajectory.len()
        );
    }
    for (name, r, tol) in cases {
        let Outcome::DeadCentre { t, dyad, value } = r.outcome else {
            panic!("{name}: {:?}", r.outcome)
        };
        println!(
            "{name}: stopped at t = {t} (energy {t_s}: {:.1e}), φ = {} (φ_s {phi_s}: {:.1e}, \
             lock {lock}), |det| {value:e}, {} rows",
            t - t_s,
            r.last.q[0],
            r.last.q[0] - phi_s,
            r.trajectory.len()
        );
        assert_eq!(dyad, 0, "{name}");
        assert!(value.abs() <= 1e-3, "{name}: {value}");
        assert!((t - t_s).abs() <= tol, "{name}: t {t} vs {t_s}");
        assert!(
            (r.last.q[0] - phi_s).abs() <= tol,
            "{name}: φ {}",
            r.last.q[0]
        );
        assert!(r.trajectory.len() > 10, "{name}");
    }
}
