//! Hostile sweeps of what the last sessions added to the engine and its dynamics: springs and
//! dampers with hostile data (`Plan::new`, `analyse`, `LinkageSystem::terms` and a short
//! run), joint friction with hostile f, radii and slider lengths in the kinetostatics
//! (`analyse`, `lost_power`) and in a `LinkageSystem`, the triad six-bar with link lengths
//! that make it barely assemblable, and two-input runs (the five-bar robot under hostile
//! motors, starts and steps, by each method). Each gives an `Error` or finite numbers, never
//! a panic, and every run ends within its budget. `cases()` calls per entry point, shared
//! among the sweeps' kinds by their cost (a run takes some hundred solves: a tenth of the
//! calls).

use super::{no_panic, Gen};
use crate::common::hostile_gen::{cases, has_non_finite};
use nalgebra::Vector2;
use tmm::dynamics::{
    run, Dopri5, FiniteIncrement, LagrangeSystem, Outcome, Rk4, RunOptions, State,
};
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, Anchor, At, Friction, Linkage, LoadSpec, Plan};
use tmm::Error;

/// An `Ok` holds only finite numbers (its `Debug` rendering), an error renders a message.
fn finite<T: std::fmt::Debug>(r: &tmm::Result<T>, what: &str) {
    match r {
        Ok(v) => {
            let s = format!("{v:?}");
            assert!(!has_non_finite(&s), "{what}: {s}");
        }
        Err(e) => assert!(!e.to_string().is_empty(), "{what}"),
    }
}

/// A short bounded run of `sys` by method `k` from `start`: ends within its budgets, its
/// rows and outcome finite, or an error that is not a spent budget of a run that could not
/// end otherwise.
fn short_run(sys: &LinkageSystem, k: u64, start: State, h: f64, what: &str) {
    let mut ro = RunOptions::until(start.t + 0.02, h);
    ro.max_steps = 400;
    ro.max_evaluations = 8000;
    let r = no_panic(what, || match k % 3 {
        0 => run(sys, &Rk4, start, &ro),
        1 => run(sys, &Dopri5::new(1e-7).unwrap(), start, &ro),
        _ => run(sys, &FiniteIncrement, start, &ro),
    });
    if let Ok(r) = &r {
        assert!(r.steps <= ro.max_steps, "{what}: {} steps", r.steps);
        assert!(!r.trajectory.is_empty(), "{what}");
    }
    finite(&r, what);
}

/// A hostile number half the time, else `ordinary`.
fn or_hostile(g: &mut Gen, ordinary: f64) -> f64 {
    if g.next().is_multiple_of(2) {
        ordinary
    } else {
        g.f()
    }
}

/// The bundled four-bar with a spring from the frame to the rocker's joint B and a damper
/// from the crank's pin A to O3, their data hostile: the plan, an analysis at a hostile
/// input, the machine's terms at a hostile state, a short run.
#[test]
fn sweep_springs_and_dampers() {
    let mut g = Gen::new(0x8b_0001);
    for case in 0..cases() {
        let mut l = bundled::four_bar();
        l.loads.push(LoadSpec::Spring {
            name: "s".into(),
            ends: [
                Anchor::on(
                    "frame",
                    At::Coords([or_hostile(&mut g, 0.1), or_hostile(&mut g, 0.4)]),
                ),
                Anchor::on("rocker", At::name("B")),
            ],
            stiffness: {
                let o = 500.0 * g.unit();
                or_hostile(&mut g, o)
            },
            free_length: {
                let o = 0.3 * g.unit();
                or_hostile(&mut g, o)
            },
            preload: {
                let o = 10.0 * (g.unit() - 0.5);
                or_hostile(&mut g, o)
            },
        });
        l.loads.push(LoadSpec::Damper {
            name: "d".into(),
            ends: [Anchor::on("crank", At::name("A")), Anchor::named("O3")],
            c: {
                let o = 5.0 * g.unit();
                or_hostile(&mut g, o)
            },
        });
        let what = format!("case {case}: {:?}", &l.loads[l.loads.len() - 2..]);
        let plan = no_panic(&what, || Plan::new(&l));
        finite(&plan.as_ref().map(|_| ()).map_err(Clone::clone), &what);
        let Ok(plan) = plan else { continue };
        let m = Motion::new(or_hostile(&mut g, 0.7), or_hostile(&mut g, 10.0), g.f());
        let a = no_panic(&what, || plan.analyse(m).map(|a| format!("{a:?}")));
        finite(&a, &what);
        if !case.is_multiple_of(10) {
            continue;
        }
        let Ok(sys) = LinkageSystem::from_linkage(&l) else {
            continue;
        };
        terms_and_a_short_run(&sys, &mut g, &what);
    }
}

/// The slider-crank and the four-bar with friction in every joint (f, pin radius, ρ, the
/// slider's length and middle hostile): `analyse` and `lost_power` at hostile inputs; a
/// tenth also as a machine, its terms and a short run.
#[test]
fn sweep_joint_friction_data() {
    let mut g = Gen::new(0x8b_0002);
    let slider = {
        use tmm::mechanism::Mechanism;
        tmm::mechanism::SliderCrank::course_example()
            .linkage()
            .unwrap()
    };
    let four = bundled::four_bar();
    for case in 0..cases() {
        let mut l: Linkage = if case % 2 == 0 {
            slider.clone()
        } else {
            four.clone()
        };
        for j in &mut l.joints {
            let fr = match g.next() % 4 {
                0 => Friction::pin(or_hostile(&mut g, 0.15), or_hostile(&mut g, 0.01)),
                1 => Friction::circle(or_hostile(&mut g, 0.002)),
                2 => {
                    let mut f = Friction::slide(or_hostile(&mut g, 0.15));
                    f.length = Some(or_hostile(&mut g, 0.05));
                    f
                }
                _ => {
                    let mut f = Friction::pin(or_hostile(&mut g, 0.1), or_hostile(&mut g, 0.01));
                    f.length = Some(g.f());
                    f.centre = Some(g.f());
                    f
                }
            };
            j.friction = Some(fr);
        }
        let what = format!(
            "case {case}: {:?}",
            l.joints.iter().map(|j| j.friction).collect::<Vec<_>>()
        );
        let plan = no_panic(&what, || Plan::new(&l));
        finite(&plan.as_ref().map(|_| ()).map_err(Clone::clone), &what);
        let Ok(plan) = plan else { continue };
        let m = Motion::new(or_hostile(&mut g, 0.7), or_hostile(&mut g, 10.0), g.f());
        let a = no_panic(&what, || {
            plan.analyse(m).map(|a| (a.lost_power(), format!("{a:?}")))
        });
        finite(&a, &what);
        if !case.is_multiple_of(10) {
            continue;
        }
        let Ok(sys) = LinkageSystem::from_linkage(&l) else {
            continue;
        };
        let sys = sys
            .with_motor(
                0,
                Motor::Constant({
                    let o = 20.0 * (g.unit() - 0.5);
                    or_hostile(&mut g, o)
                }),
            )
            .unwrap_or_else(|_| LinkageSystem::from_linkage(&l).unwrap());
        terms_and_a_short_run(&sys, &mut g, &what);
    }
}

/// The triad six-bar with one link length scaled towards (or past) where the triad stops
/// assembling at its reference pose (factors 1 ± 10⁻ᵏ of a random length, and hostile):
/// `Plan::new`, then `kinematics` and `analyse` over a turn of 8 positions.
#[test]
fn sweep_barely_assemblable_triads() {
    let base = bundled::six_bar_triad();
    let mut g = Gen::new(0x8b_0003);
    for case in 0..cases().div_ceil(8) {
        let mut l = base.clone();
        // Move one joint of the triad (not the input's) a little or a lot.
        let j = 2 + (g.next() % (l.joints.len() as u64 - 2)) as usize;
        let eps = match g.next() % 3 {
            0 => 10f64.powi(-((g.next() % 17) as i32)),
            1 => g.f(),
            _ => 0.5 * (g.unit() - 0.5),
        };
        let axis = (g.next() % 2) as usize;
        let at = &mut l.joints[j].at;
        at[axis] += eps * at[axis].abs().max(0.1);
        let what = format!("case {case}: joint {j} moved by {eps:e} along {axis}");
        let plan = no_panic(&what, || Plan::new(&l));
        finite(&plan.as_ref().map(|_| ()).map_err(Clone::clone), &what);
        let Ok(plan) = plan else { continue };
        let phi0 = plan.reference_input();
        for i in 0..8 {
            let m = Motion::new(phi0 + f64::from(i) * 0.785, 1.0, 0.0);
            finite(
                &no_panic(&what, || plan.kinematics(m).map(|k| format!("{k:?}"))),
                &what,
            );
            finite(
                &no_panic(&what, || plan.analyse(m).map(|a| format!("{a:?}"))),
                &what,
            );
        }
    }
}

/// The five-bar robot as a two-input machine: hostile motors, starts and steps, by each
/// method; every run ends within its budget with finite rows and a named stop (a dead centre
/// located at the band's edge: the refused state's |det| ≤ 10⁻³), or an error.
#[test]
fn sweep_two_input_runs() {
    let base = LinkageSystem::from_linkage(&bundled::five_bar_robot()).unwrap();
    let q0 = base.plan().reference_inputs();
    let mut g = Gen::new(0x8b_0004);
    let (mut dead, mut fin, mut err) = (0, 0, 0);
    for case in 0..cases().div_ceil(10) {
        let m = [
            {
                let o = 4.0 * (g.unit() - 0.5);
                or_hostile(&mut g, o)
            },
            {
                let o = 4.0 * (g.unit() - 0.5);
                or_hostile(&mut g, o)
            },
        ];
        let sys = match base
            .clone()
            .with_motor(0, Motor::Constant(m[0]))
            .and_then(|s| s.with_motor(1, Motor::Constant(m[1])))
        {
            Ok(s) => s,
            Err(_) => continue,
        };
        let q = Vector2::new(or_hostile(&mut g, q0[0]), or_hostile(&mut g, q0[1]));
        let qd = Vector2::new(
            {
                let o = 10.0 * (g.unit() - 0.5);
                or_hostile(&mut g, o)
            },
            {
                let o = 10.0 * (g.unit() - 0.5);
                or_hostile(&mut g, o)
            },
        );
        let h = if g.next().is_multiple_of(8) {
            g.f()
        } else {
            10f64.powf(-4.0 + 2.5 * g.unit())
        };
        let k = g.next() % 3;
        let what = format!("case {case}: M {m:?}, q {q:?}, q̇ {qd:?}, h {h:e}, method {k}");
        let mut ro = RunOptions::until(0.1, h);
        ro.max_steps = 2000;
        ro.max_evaluations = 40_000;
        let r = no_panic(&what, || match k {
            0 => run(&sys, &Rk4, State::new(0.0, q, qd), &ro),
            1 => run(
                &sys,
                &Dopri5::new(1e-8).unwrap(),
                State::new(0.0, q, qd),
                &ro,
            ),
            _ => run(&sys, &FiniteIncrement, State::new(0.0, q, qd), &ro),
        });
        finite(&r, &what);
        match r {
            Ok(r) => match r.outcome {
                Outcome::DeadCentre { value, .. } => {
                    assert!(value.abs() <= 1e-3, "{what}: {value}");
                    dead += 1;
                }
                _ => fin += 1,
            },
            Err(Error::Budget { .. }) if h.is_finite() && h > 1e-4 => {
                panic!("{what}: a run of at most 1000 steps spent its budget")
            }
            Err(_) => err += 1,
        }
    }
    println!("two-input runs: dead centre {dead}, other ends {fin}, errors {err}");
}

/// The system's terms at a hostile state (a crank angle and speed about 0.7 rad, 10 rad/s),
/// and a short run from it: finite or an error, never a panic.
fn terms_and_a_short_run(sys: &LinkageSystem, g: &mut Gen, what: &str) {
    let (q, qd) = (
        Vector2::new(or_hostile(g, 0.7), 0.0),
        Vector2::new(or_hostile(g, 10.0), 0.0),
    );
    finite(&no_panic(what, || sys.terms(0.0, &q, &qd)), what);
    let k = g.next();
    short_run(sys, k, State::new(0.0, q, qd), 1e-3, what);
}
