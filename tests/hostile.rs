//! Adversarial tests: every public entry point of kinematics, kinetostatics, load and
//! dynamics keeps its promise under hostile input. Bad input gives an `Error`: never a panic,
//! never an `Ok` holding a NaN or an infinity; every run is bounded.
//!
//! Entry points covered by the generated sweeps (`sweep_*` tests):
//!
//! - kinematics: `crank`, `rrr_dyad`, `rrp_dyad`, `rpr_dyad`, `solve_contour`,
//!   `solve_contour_position`, `contour_residual`, `cycle`, `cycle_angles`,
//!   `try_cycle_angles`, `coupler_curve`, `assembly_range`, `extreme_positions`,
//!   `Strokes::new`, `Strokes::plan_positions`, `Strokes::try_plan_positions`,
//!   `Strokes::working_in` (on hand-built strokes too),
//!   `transfer_functions`, `differentiate`, `differentiate_periodic`, `integrate_trapezoid`;
//! - kinetostatics: `RrrDyad::solve`, `RrpDyad::solve`, `RprDyad::solve`,
//!   `CouplingDrive::solve`, `GearDrive::solve`, `passive::PaperGroup::solve`;
//! - load: `Load::inertia`;
//! - dynamics: `accelerations`, `powers`, `kinetic_energy`, `christoffel_terms`,
//!   `FiniteIncrement`/`Rk4`/`Dopri5` `step` and `advance`, `Dopri5::advance_dense`,
//!   `DenseOutput::at`, `run` (with requested times, breakpoints and kinks),
//!   `Trajectory::push`,
//!   `Table::new`, `Table::at`, `LinearMotor::from_nominal`, `LinearMotor::torque`,
//!   `Servo::torque`, `FiveBar::kinematics`, `FiveBar::point_masses`,
//!   `CoaxialPropellers::exact`, `CoaxialPropellers::drift_acceleration`,
//!   `DecoupledRpArm::closed_form`, `LandingGear::phi_h`.
//!
//! - overflowing data: `IndicatorDiagram::force`, `RprSeed::to_dyad`, `PaperGroup::geometry`,
//!   `PaperGroup::loads`, `FiveBar` (`inertia`, `inertia_derivatives`, `potential`,
//!   `potential_gradient`, `forces`, `terms`), `RpArm` and `DecoupledRpArm` (`inertia`,
//!   `inertia_derivatives`, `damping`);
//! - a user's system: the defaults of `LagrangeSystem` (`inertia_derivatives`,
//!   `potential_gradient`, `terms`) on steep and huge inertia and potential.
//!
//! 61 entry points. The number of generated cases per sweep is `TMM_HOSTILE_CASES`
//! (default 200; run with a larger number in release, for example
//! `TMM_HOSTILE_CASES=100000 cargo test --release --test tmm hostile::`).

#![allow(clippy::field_reassign_with_default)]

use std::fmt::Debug;
use std::panic::{catch_unwind, AssertUnwindSafe};

use nalgebra::{Matrix2, Point2, Vector2};
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar, LandingGear, LinearMotor, RpArm};
use tmm::dynamics::{
    accelerations, christoffel_terms, kinetic_energy, powers, run, Beyond, Dopri5, FiniteIncrement,
    LagrangeSystem, Rk4, RunOptions, RunResult, State, Stepper, Table, Trajectory,
};
use tmm::kinematics::{
    assembly_range, contour_residual, coupler_curve, crank, cycle, cycle_angles, differentiate,
    differentiate_periodic, extreme_positions, integrate_trapezoid, rpr_dyad, rrp_dyad, rrr_dyad,
    solve_contour, solve_contour_position, transfer_functions, try_cycle_angles, Branch, Extreme,
    ExtremeKind, Guide, LoopVector, Motion, PointMotion, Rotation, Strokes,
};
use tmm::kinetostatics::passive::{PaperGroup, Stiffness};
use tmm::kinetostatics::{CouplingDrive, GearDrive, RprDyad, RrpDyad, RrrDyad};
use tmm::{Error, Load};

// ---------------------------------------------------------------------------------------
// Generators and checks
// ---------------------------------------------------------------------------------------

use crate::common::hostile_gen;
use hostile_gen::{cases, has_non_finite, Gen};

/// Runs one case: no panic, and an `Ok` holds only finite numbers. Returns the result.
fn check<T: Debug>(entry: &str, case: &dyn Debug, f: impl FnOnce() -> tmm::Result<T>) {
    let r = catch_unwind(AssertUnwindSafe(f));
    match r {
        Err(_) => panic!("{entry} panicked on {case:?}"),
        Ok(Ok(v)) => {
            let s = format!("{v:?}");
            assert!(
                !has_non_finite(&s),
                "{entry} returned a non-finite Ok on {case:?}: {s}"
            );
        }
        Ok(Err(e)) => {
            // The message renders too (no panic in Display).
            let _ = e.to_string();
        }
    }
}

/// As [`check`] for a function without `Result`.
fn check_plain<T: Debug>(entry: &str, case: &dyn Debug, f: impl FnOnce() -> T) {
    check(entry, case, || Ok(f()));
}

fn sweep(seed: u64, mut body: impl FnMut(&mut Gen)) {
    let mut g = Gen::new(seed);
    for _ in 0..cases() {
        body(&mut g);
    }
}

// ---------------------------------------------------------------------------------------
// Sweeps: kinematics
// ---------------------------------------------------------------------------------------

#[test]
fn sweep_kinematic_blocks() {
    sweep(1, |g| {
        let (o, l, phi) = (g.p(), g.len(), g.motion());
        check("crank", &(o, l, phi), || crank(o, l, phi));
        let (a, c, l2, l3, b) = (g.pm(), g.pm(), g.len(), g.len(), g.branch());
        check("rrr_dyad", &(a, c, l2, l3, b), || rrr_dyad(a, c, l2, l3, b));
        let guide = Guide {
            point: g.pm(),
            angle: g.motion(),
        };
        check("rrp_dyad", &(a, guide, l2, b), || rrp_dyad(a, guide, l2, b));
        check("rpr_dyad", &(a, c), || rpr_dyad(a, c));
        // Ordinary dyads driven hard: huge speeds, coincident and collinear points.
        let a = PointMotion::new(Point2::origin(), g.v(), g.v());
        let c = PointMotion::fixed(Point2::new(g.len(), 0.0));
        check("rrr_dyad", &(a, c), || {
            rrr_dyad(a, c, 1.0, 1.0, Branch::Plus)
        });
        check("rpr_dyad", &(a, a), || rpr_dyad(a, a));
    });
}

#[test]
fn sweep_contours() {
    sweep(2, |g| {
        let mut vs = Vec::new();
        for _ in 0..(g.next() % 4) {
            vs.push(LoopVector::fixed(g.v()));
        }
        match g.next() % 4 {
            0 => vs.push(LoopVector::unknown()),
            1 => {
                vs.push(LoopVector::unknown_angle(g.len()));
                vs.push(LoopVector::unknown_angle(g.len()));
            }
            2 => {
                vs.push(LoopVector::unknown_angle(g.len()));
                vs.push(LoopVector::unknown_length(g.motion()));
            }
            _ => {
                vs.push(LoopVector::unknown_length(g.motion()));
                vs.push(LoopVector::unknown_length(g.motion()));
            }
        }
        let b = g.branch();
        check("solve_contour", &vs, || solve_contour(&vs, b));
        check("solve_contour_position", &vs, || {
            solve_contour_position(&vs, b)
        });
        let x = [g.f(), g.f()];
        check("contour_residual", &(&vs, x), || contour_residual(&vs, x));
    });
}

#[test]
fn sweep_cycles_and_strokes() {
    let sizes = [0usize, 1, 2, 3, 12, 1 << 25, 1 << 62, usize::MAX];
    sweep(3, |g| {
        let n = sizes[(g.next() % sizes.len() as u64) as usize];
        let start = g.f();
        let big = n > 1 << 20;
        if !big {
            check_plain("cycle_angles", &(n, start), || cycle_angles(n, start));
            check("try_cycle_angles", &(n, start), || {
                try_cycle_angles(n, start)
            });
        } else {
            assert!(try_cycle_angles(n, start).is_err() || n <= tmm::kinematics::MAX_POSITIONS);
            assert!(cycle_angles(n, start).is_empty());
        }
        let l = g.len();
        let f = |phi: f64| Ok(crank(Point2::origin(), l, Motion::unit_speed(phi))?.a.p);
        if !big {
            check("cycle", &(n, start, l), || cycle(n, start, f));
            check("coupler_curve", &(n, start, l), || {
                coupler_curve(n, start, f)
            });
        } else {
            assert!(cycle(n, start, f).is_err());
        }
        let (x, y) = (g.f(), g.f());
        let rot = if g.next().is_multiple_of(2) {
            Rotation::Ccw
        } else {
            Rotation::Cw
        };
        let e = |input, kind| Extreme {
            input,
            output: Motion::default(),
            kind,
        };
        let ex = [e(x, ExtremeKind::Min), e(y, ExtremeKind::Max)];
        check("Strokes::new", &ex, || Strokes::new(&ex, rot));
        if let Ok(s) = Strokes::new(&ex, rot) {
            if !big {
                check_plain("Strokes::plan_positions", &n, || s.plan_positions(n));
            }
            check("Strokes::try_plan_positions", &n, || {
                s.try_plan_positions(n)
            });
        }
        // Hand-built strokes: every public field hostile.
        let hand = Strokes {
            start: g.f(),
            end: g.f(),
            working_angle: g.f(),
            idle_angle: g.f(),
            time_ratio: g.f(),
            rotation: rot,
            stroke: g.f(),
            working_rises: g.next().is_multiple_of(2),
        };
        let rises = g.next().is_multiple_of(2);
        check("Strokes::working_in", &hand, || hand.working_in(rises));
        check("Strokes::try_plan_positions (hand-built)", &hand, || {
            hand.try_plan_positions(12)
        });
        let phi = g.f();
        let (lc, lr) = (g.len(), g.len());
        check("assembly_range", &(phi, lc, lr), || {
            assembly_range(phi, |p| {
                let a = crank(Point2::origin(), lc, Motion::fixed(p))?.a;
                rrr_dyad(
                    a,
                    PointMotion::fixed(Point2::new(0.3, 0.0)),
                    lr,
                    0.15,
                    Branch::Plus,
                )
            })
        });
        let samples = [0usize, 2, 3, 7, 36, usize::MAX][(g.next() % 6) as usize];
        let amp = g.f();
        check("extreme_positions", &(samples, amp), || {
            extreme_positions(
                |p| Ok(Motion::new(amp * p.sin(), amp * p.cos(), 0.0)),
                samples,
            )
        });
        let (p1, m) = (g.f(), g.motion());
        check("transfer_functions", &(p1, m), || {
            transfer_functions(|_| Ok(m), p1)
        });
    });
}

#[test]
fn sweep_numeric() {
    sweep(4, |g| {
        let n = (g.next() % 6) as usize;
        let y: Vec<f64> = (0..n).map(|_| g.f()).collect();
        let h = g.f();
        check("differentiate", &(&y, h), || differentiate(&y, h));
        check("differentiate_periodic", &(&y, h), || {
            differentiate_periodic(&y, h)
        });
        check("integrate_trapezoid", &(&y, h), || {
            integrate_trapezoid(&y, h)
        });
    });
}

// ---------------------------------------------------------------------------------------
// Sweeps: kinetostatics and loads
// ---------------------------------------------------------------------------------------

#[test]
fn sweep_kinetostatics() {
    sweep(5, |g| {
        let d = RrrDyad {
            a: g.p(),
            b: g.p(),
            c: g.p(),
            load2: g.load(),
            load3: g.load(),
        };
        check("RrrDyad::solve", &d, || d.solve());
        let d = RrpDyad {
            a: g.p(),
            b: g.p(),
            guide: g.v(),
            load2: g.load(),
            load3: g.load(),
        };
        check("RrpDyad::solve", &d, || d.solve());
        let d = RprDyad {
            a: g.p(),
            e: g.p(),
            axis: g.v(),
            load2: g.load(),
            load3: g.load(),
        };
        check("RprDyad::solve", &d, || d.solve());
        let loads = [g.load(), g.load()];
        let c = CouplingDrive { o1: g.p() };
        check("CouplingDrive::solve", &(c, loads), || c.solve(&loads));
        let gd = GearDrive::at_angle(g.p(), g.len(), g.f(), g.f());
        check("GearDrive::solve", &(gd, loads), || gd.solve(&loads));
        let (m, a, j, e, s) = (g.f(), g.v(), g.f(), g.f(), g.p());
        check("Load::inertia", &(m, a, j, e), || {
            Load::inertia(s, m, a, j, e)
        });
    });
}

#[test]
fn sweep_passive_group() {
    // The force method is heavier: a tenth of the cases.
    let mut g = Gen::new(6);
    for _ in 0..cases().div_ceil(10) {
        let mut p = PaperGroup::example();
        match g.next() % 4 {
            0 => p.l1 = g.len(),
            1 => p.f2 = g.f(),
            2 => p.alpha4 = g.f(),
            _ => p.m = g.f(),
        }
        let st = Stiffness {
            ei: [g.f(), g.len(), g.f()],
            ea: if g.next().is_multiple_of(2) {
                None
            } else {
                Some([g.f(), g.f(), g.f()])
            },
        };
        check("PaperGroup::solve", &(&p, st), || p.solve(&st));
    }
}

// ---------------------------------------------------------------------------------------
// Sweeps: dynamics
// ---------------------------------------------------------------------------------------

/// A hostile 2-DOF system: its numbers come from the generator.
#[derive(Debug, Clone, Copy)]
struct Hostile {
    m: [f64; 3],
    q: [f64; 2],
    b: f64,
    k: f64,
    w: f64,
}

impl LagrangeSystem for Hostile {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(self.m[0], self.m[1], self.m[1], self.m[2]))
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(
            self.q[0] * (self.w * t).sin() - self.k * q[0],
            self.q[1],
        ))
    }
    fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(self.b, 0.0, 0.0, self.b))
    }
    fn output_names(&self) -> Vec<&'static str> {
        vec!["x"]
    }
    fn outputs(
        &self,
        _: f64,
        q: &Vector2<f64>,
        _: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> tmm::Result<()> {
        out.push(q[0] * self.k);
        Ok(())
    }
}

fn hostile_system(g: &mut Gen) -> Hostile {
    Hostile {
        m: [g.len(), g.f() * 0.01, g.len()],
        q: [g.f(), g.f()],
        b: g.f(),
        k: g.f(),
        w: g.f(),
    }
}

fn small_budget(t_end: f64, h: f64) -> RunOptions {
    RunOptions {
        max_steps: 2_000,
        max_evaluations: 20_000,
        max_rows: 500,
        ..RunOptions::until(t_end, h)
    }
}

#[test]
fn sweep_dynamics_core() {
    sweep(7, |g| {
        let sys = hostile_system(g);
        let s = State::new(g.f(), g.v(), g.v());
        check("accelerations", &(sys, s), || {
            accelerations(&sys, s.t, &s.q, &s.qd)
        });
        check("powers", &(sys, s), || powers(&sys, s.t, &s.q, &s.qd));
        check("kinetic_energy", &(sys, s), || {
            kinetic_energy(&sys, &s.q, &s.qd)
        });
        let d = [
            Matrix2::new(g.f(), g.f(), g.f(), g.f()),
            Matrix2::new(g.f(), g.f(), g.f(), g.f()),
        ];
        check("christoffel_terms", &(d, s.qd), || {
            christoffel_terms(&d, &s.qd)
        });
        let h = g.f();
        check("FiniteIncrement::step", &(sys, s, h), || {
            FiniteIncrement.step(&sys, &s, h)
        });
        check("Rk4::step", &(sys, s, h), || Rk4.step(&sys, &s, h));
        let dp = Dopri5 {
            rtol: g.f(),
            atol: g.f(),
        };
        check("Dopri5::advance", &(sys, s, h, dp), || {
            dp.advance(&sys, &s, h)
        });
        let t = g.f();
        check(
            "Dopri5::advance_dense, DenseOutput::at",
            &(sys, s, h, dp, t),
            || {
                let (adv, dense) = dp.advance_dense(&sys, &s, h, None)?;
                let d = dense.expect("Dormand-Prince has a continuous extension");
                let mid = d.at(0.5 * (d.start() + d.end()))?;
                Ok((adv, mid, d.at(t).ok()))
            },
        );
        let mut tr = Trajectory::for_system(&sys);
        check("Trajectory::push", &(sys, s), || tr.push(&sys, &s));
        assert!(tr.q()[0].len() == tr.len() && tr.outputs()[0].len() == tr.len());
        check_plain("Trajectory::to_csv", &(sys, s), || tr.to_csv());
        check_plain("Trajectory::last_state", &(sys, s), || tr.last_state());
    });
}

/// A hostile system with hostile kinks: nodes and an argument from the generator.
#[derive(Debug, Clone, Copy)]
struct Kinked(Hostile, [f64; 2], f64);

impl LagrangeSystem for Kinked {
    fn inertia(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        self.0.inertia(q)
    }
    fn inertia_derivatives(&self, q: &Vector2<f64>) -> tmm::Result<[Matrix2<f64>; 2]> {
        self.0.inertia_derivatives(q)
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        self.0.forces(t, q, qd)
    }
    fn damping(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        self.0.damping(q)
    }
    fn breakpoints(&self) -> Vec<f64> {
        vec![self.1[1], self.2]
    }
    fn kinks(&self) -> Vec<Vec<f64>> {
        vec![self.1.to_vec(), vec![self.2, self.1[0]]]
    }
    fn kink_arguments(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> tmm::Result<()> {
        out[0] = q[0] * self.2 + qd[1] + t;
        out[1] = qd[0] * self.1[1] - q[1];
        Ok(())
    }
}

#[test]
fn sweep_runs_with_times_breakpoints_and_kinks() {
    // Its own generator for the times, so that the other sweeps' cases stay as they were.
    let (mut g, mut gt) = (Gen::new(18), Gen::new(19));
    for i in 0..cases() {
        let sys = Kinked(hostile_system(&mut g), [gt.f(), gt.f()], gt.f());
        let s = State::new(0.0, g.v() * 1e-3, g.v() * 1e-3);
        let mut opts = small_budget([1.0, 1e300, g.f()][i % 3], [0.01, 1e-9, g.f()][i % 3]);
        let n = (gt.next() % 5) as usize;
        opts.times = (0..n).map(|_| gt.f()).collect();
        if i % 2 == 0 {
            // Mostly in range, so that the runs get going.
            opts.times = opts.times.iter().map(|t| t.abs().min(1.0)).collect();
        }
        opts.breakpoints = (0..(gt.next() % 5)).map(|_| gt.f()).collect();
        let which = g.next() % 3;
        let started = std::time::Instant::now();
        check(
            "run (times, breakpoints, kinks)",
            &(sys, s, opts.clone(), which),
            || {
                let r: RunResult = match which {
                    0 => run(&sys, &FiniteIncrement, s, &opts),
                    1 => run(&sys, &Rk4, s, &opts),
                    _ => run(&sys, &Dopri5::new(1e-6)?, s, &opts),
                }?;
                // Every requested time up to the stop is recorded, once, in order.
                let t = r.trajectory.t();
                assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
                for &x in &opts.times {
                    if x <= r.last.t {
                        assert!(t.contains(&x), "{x} not in {t:?}");
                    }
                }
                Ok(r)
            },
        );
        assert!(started.elapsed().as_secs() < 5, "{sys:?} {opts:?}");
    }
}

#[test]
fn sweep_runs() {
    // Every case a run, each under a small budget (a case costs well under a millisecond).
    let mut g = Gen::new(8);
    for i in 0..cases() {
        let sys = hostile_system(&mut g);
        let s = State::new(0.0, g.v() * 1e-3, g.v() * 1e-3);
        let opts = small_budget([1.0, 1e300, g.f()][i % 3], [0.01, 1e-9, g.f()][i % 3]);
        let which = g.next() % 3;
        let started = std::time::Instant::now();
        check("run", &(sys, s, opts.clone(), which), || match which {
            0 => run(&sys, &FiniteIncrement, s, &opts),
            1 => run(&sys, &Rk4, s, &opts),
            _ => run(&sys, &Dopri5::new(1e-6)?, s, &opts),
        });
        assert!(started.elapsed().as_secs() < 5, "{sys:?} {opts:?}");
    }
}

#[test]
fn sweep_machines() {
    sweep(9, |g| {
        let (x, y, z) = (g.f(), g.f(), g.f());
        check("Table::new", &(x, y), || {
            Table::new(vec![0.0, x.abs(), 1e308], vec![y, z, -y], Beyond::HoldEnds)
        });
        let t = Table::new(vec![-1e308, 0.0, 1e308], vec![y, z, -y], Beyond::Error);
        if let Ok(t) = t {
            let x = g.f();
            check("Table::at", &x, || t.at(x));
        }
        let (m, ws, wn) = (g.f(), g.f(), g.f());
        check("LinearMotor::from_nominal", &(m, ws, wn), || {
            LinearMotor::from_nominal(m, ws, wn)
        });
        let motor = LinearMotor { a: g.f(), b: g.f() };
        let w = g.f();
        check("LinearMotor::torque", &(motor, w), || motor.torque(w));

        let mut fb = FiveBar::default();
        match g.next() % 5 {
            0 => fb.drive1.limit = g.f(),
            1 => fb.drive4.kp = g.f(),
            2 => fb.l_ab = g.len(),
            3 => fb.m_on = g.f(),
            _ => fb.j_s2 = Some(g.f()),
        }
        let q = Vector2::new(g.f(), g.f());
        let qd = g.v();
        check("Servo::torque", &(fb.drive1, q), || {
            fb.drive1.torque(q[0], qd[0])
        });
        check("FiveBar::point_masses", &fb, || fb.point_masses());
        check("FiveBar::kinematics", &(fb, q), || fb.kinematics(&q));
        check("FiveBar accelerations", &(fb, q), || {
            accelerations(&fb, 0.0, &q, &qd)
        });

        let mut cp = CoaxialPropellers::default();
        match g.next() % 4 {
            0 => cp.motor.b = g.f(),
            1 => cp.m_on4 = g.f(),
            2 => cp.i4 = g.len(),
            _ => cp.motor.a = g.f(),
        }
        let s = State::new(g.f(), g.v(), g.v());
        let t = g.f();
        check("CoaxialPropellers::exact", &(&cp, s, t), || cp.exact(&s, t));
        check("CoaxialPropellers::drift_acceleration", &cp, || {
            cp.drift_acceleration()
        });
        let mut arm = RpArm::default();
        arm.b1 = g.f();
        check("DecoupledRpArm::closed_form", &(arm, s, t), || {
            arm.decoupled().closed_form(&s, t)
        });
        let lg = LandingGear::default();
        check("LandingGear::phi_h", &q, || lg.phi_h(&q));
        check("LandingGear accelerations", &(q, qd), || {
            accelerations(&lg, 0.0, &q, &qd)
        });
    });
}

// ---------------------------------------------------------------------------------------
// Regressions: the reproductions of the issue
// ---------------------------------------------------------------------------------------

#[test]
fn repro_1_servo_with_nan_limit_is_an_error() {
    let mut fb = FiveBar::default();
    fb.drive1.limit = f64::NAN;
    let q = Vector2::new(1.7453292519943295, 1.3962634015954636);
    assert!(accelerations(&fb, 0.0, &q, &Vector2::zeros()).is_err());
    assert!(powers(&fb, 0.0, &q, &Vector2::zeros()).is_err());
    assert!(Trajectory::for_system(&fb)
        .push(&fb, &State::at_rest(q))
        .is_err());
    let s = State::at_rest(q);
    assert!(Rk4.step(&fb, &s, 1e-3).is_err());
    assert!(FiniteIncrement.step(&fb, &s, 1e-3).is_err());
    assert!(Dopri5::new(1e-6).unwrap().advance(&fb, &s, 1e-3).is_err());
    assert!(run(&fb, &Rk4, s, &RunOptions::until(0.1, 1e-3)).is_err());
    assert!(matches!(
        fb.drive1.torque(0.0, 0.0),
        Err(Error::NonFinite { .. })
    ));
    fb.drive1.limit = -1.0;
    assert!(matches!(
        fb.drive1.torque(0.0, 0.0),
        Err(Error::OutOfRange { .. })
    ));
}

#[test]
fn repro_2_trajectory_columns_cannot_desynchronise() {
    // The columns are private: a trajectory is built only by push, a whole row at a time.
    let tr = Trajectory::default();
    assert_eq!(tr.to_csv().lines().count(), 1);
    assert!(tr.last_state().is_none());
    assert!(tr.output("x").is_none());
    let sys = Hostile {
        m: [1.0, 0.0, 1.0],
        q: [1.0, 1.0],
        b: 0.0,
        k: 1.0,
        w: 1.0,
    };
    let mut tr = Trajectory::default();
    tr.push(&sys, &State::at_rest(Vector2::new(1.0, 0.0)))
        .unwrap();
    assert_eq!(tr.output("x"), Some(&[1.0][..]));
    assert_eq!(tr.to_csv().lines().count(), 2);
    tr.truncate(0);
    assert!(tr.is_empty() && tr.outputs()[0].is_empty());
}

#[test]
fn repro_3_huge_cycles_are_errors() {
    let f = |phi: f64| Ok(phi);
    assert!(matches!(
        cycle(1 << 62, 0.0, f),
        Err(Error::OutOfRange { .. })
    ));
    assert!(cycle_angles(usize::MAX, 0.0).is_empty());
    assert!(try_cycle_angles(usize::MAX, 0.0).is_err());
}

#[test]
fn repro_4_coincident_extremes_have_no_time_ratio() {
    let e = |kind| Extreme {
        input: 2.0,
        output: Motion::default(),
        kind,
    };
    for rot in [Rotation::Cw, Rotation::Ccw] {
        let r = Strokes::new(&[e(ExtremeKind::Min), e(ExtremeKind::Max)], rot);
        assert!(matches!(r, Err(Error::Singular { .. })), "{r:?}");
    }
}

#[test]
fn repro_5_dyads_and_contours_check_their_results() {
    let a = PointMotion::new(Point2::origin(), Vector2::new(0.0, 1e155), Vector2::zeros());
    let c = PointMotion::fixed(Point2::new(1.0, 0.0));
    let r = rrr_dyad(a, c, 1.0, 1.0, Branch::Plus);
    assert!(matches!(r, Err(Error::Overflow { .. })), "{r:?}");
    let vs = [
        LoopVector::fixed(Vector2::new(1e200, 0.0)),
        LoopVector::unknown(),
    ];
    let r = solve_contour_position(&vs, Branch::Plus);
    assert!(matches!(r, Err(Error::Overflow { .. })), "{r:?}");
}

#[test]
fn repro_6_passive_group_with_extreme_stiffness() {
    let r = PaperGroup::example().solve(&Stiffness {
        ei: [1e300, 5e-324, 1e-16],
        ea: None,
    });
    assert!(r.is_err(), "{r:?}");
}

#[test]
fn repro_7_side_outputs_overflow_as_overflow() {
    let big = Load::force_at(Point2::new(1e160, 0.0), Vector2::new(0.0, 1e160));
    let rrp = RrpDyad {
        a: Point2::new(-1.0, 1.0),
        b: Point2::origin(),
        guide: Vector2::new(1.0, 0.0),
        load2: Load::zero(Point2::origin()),
        load3: big,
    };
    let r = rrp.solve();
    assert!(matches!(r, Err(Error::Overflow { .. })), "{r:?}");
    let rpr = RprDyad {
        a: Point2::new(1.0, 0.0),
        e: Point2::origin(),
        axis: Vector2::new(-1.0, 0.0),
        load2: Load::force_at(Point2::new(1e160, 0.0), Vector2::new(0.0, 1e160)),
        load3: Load::zero(Point2::origin()),
    };
    assert!(rpr.solve().is_err());
    assert!(matches!(
        Load::inertia(Point2::origin(), 1e300, Vector2::new(1e308, 0.0), 0.0, 0.0),
        Err(Error::Overflow { .. })
    ));
    assert!(matches!(
        LinearMotor::from_nominal(1e308, 0.5, 1e-12),
        Err(Error::Overflow { .. })
    ));
    let mut cp = CoaxialPropellers::default();
    cp.motor.b = 5e-324;
    let d = cp.drift_acceleration().unwrap();
    assert!(d.iter().all(|v| v.is_finite()));
    let t = Table::new(vec![0.0, 1.0], vec![-1e308, 1e308], Beyond::Error).unwrap();
    let r = t.at(0.5);
    assert!(r.as_ref().map_or(true, |v| v.is_finite()), "{r:?}");
    // Finite coordinates whose distance overflows: overflow, not "must be finite".
    let d = RrrDyad {
        a: Point2::new(-1e154, -1e154),
        b: Point2::new(1e154, 1e154),
        c: Point2::new(1e154, 0.0),
        load2: Load::zero(Point2::origin()),
        load3: Load::zero(Point2::origin()),
    };
    assert!(matches!(d.solve(), Err(Error::Overflow { .. })));
    let mut arm = RpArm::default();
    arm.mp1 = f64::NAN;
    assert!(arm
        .forces(0.0, &Vector2::zeros(), &Vector2::zeros())
        .is_err());
}

#[test]
fn repro_8_run_checks_recorded_outputs() {
    let cp = CoaxialPropellers::default();
    let s = State::at_rest(Vector2::new(f64::MAX, 0.0));
    let r = run(&cp, &Rk4, s, &RunOptions::until(1.0, 0.1));
    assert!(r.is_err(), "{:?}", r.map(|r| r.last));
}

#[test]
fn repro_9_every_run_is_bounded() {
    let spring = |k: f64| Hostile {
        m: [1.0, 0.0, 1.0],
        q: [0.0, 0.0],
        b: 0.0,
        k,
        w: 0.0,
    };
    let s = State::at_rest(Vector2::new(1.0, 0.0));
    let budget = |r: tmm::Result<tmm::dynamics::RunResult>| matches!(r, Err(Error::Budget { time, .. }) if time.is_finite());
    // A fixed step of 1e-9 over 1 s, and t_end = 1e300.
    assert!(budget(run(&spring(1.0), &Rk4, s, &small_budget(1.0, 1e-9))));
    assert!(budget(run(
        &spring(1.0),
        &Rk4,
        s,
        &small_budget(1e300, 0.1)
    )));
    // A step below the rounding of t.
    assert!(run(&spring(1.0), &Rk4, s, &RunOptions::until(1.0, 5e-324)).is_err());
    // Dormand–Prince on a stiff spring.
    let dp = Dopri5::new(1e-9).unwrap();
    assert!(budget(run(&spring(1e12), &dp, s, &small_budget(1.0, 1e-3))));
    // A forcing sin(1e300·t).
    let mut f = spring(1.0);
    f.q = [1.0, 0.0];
    f.w = 1e300;
    assert!(budget(run(&f, &dp, s, &small_budget(1.0, 1e-3))));
    // The coaxial propellers to t_end = f64::MAX: memory bounded by the rows.
    let cp = CoaxialPropellers::default();
    let r = run(
        &cp,
        &Rk4,
        State::at_rest(Vector2::zeros()),
        &small_budget(f64::MAX, 1e-3),
    );
    assert!(r.is_err());
    // The default budgets exist and can be changed.
    let o = RunOptions::until(1.0, 0.1);
    assert_eq!(o.max_steps, RunOptions::DEFAULT_MAX_STEPS);
    assert!(o.max_evaluations > 0 && o.max_rows >= 2);
    let tiny = RunOptions { max_rows: 1, ..o };
    assert!(run(&spring(1.0), &Rk4, s, &tiny).is_err());
    // A run within its budgets ends with at most max_rows rows.
    let opts = RunOptions {
        max_rows: 50,
        record_every: 3,
        ..RunOptions::until(1.0, 0.01)
    };
    let r = run(&spring(1.0), &Rk4, s, &opts).unwrap();
    assert!(r.trajectory.len() <= 50);
}

#[test]
fn functions_without_result_cannot_give_nan() {
    assert!(cycle_angles(12, f64::NAN).is_empty());
    let lg = LandingGear::default();
    assert!(lg.phi_h(&Vector2::new(f64::NAN, 0.0)).is_err());
    let d = [Matrix2::from_element(f64::NAN), Matrix2::zeros()];
    assert!(christoffel_terms(&d, &Vector2::new(1.0, 1.0)).is_err());
    let m = LinearMotor {
        a: f64::NAN,
        b: 1.0,
    };
    assert!(m.torque(1.0).is_err());
    let mut fb = FiveBar::default();
    fb.m2 = f64::NAN;
    assert!(fb.point_masses().is_err());
}

#[test]
fn assembly_range_tells_a_branch_point_from_a_lock() {
    // Crank 0.125 m about O driving an RRP dyad of l = 0.1875 on a guide through (0, 0.0625)
    // along x: the crank turns fully; the two assembly modes touch at 270°.
    let mech = |phi: f64| {
        let a = crank(Point2::origin(), 0.125, Motion::unit_speed(phi))?.a;
        rrp_dyad(
            a,
            Guide::fixed(Point2::new(0.0, 0.0625), 0.0),
            0.1875,
            Branch::Plus,
        )
    };
    for start in [0.0, 0.1, -0.3, 1.0, 1.5 * std::f64::consts::PI] {
        let r = assembly_range(start, mech);
        assert_eq!(r, Ok(None), "from {start}");
    }
    // A real lock is still found.
    let c = PointMotion::fixed(Point2::new(0.3, 0.0));
    let r = assembly_range(0.0, |phi| {
        let a = crank(Point2::origin(), 0.2, Motion::fixed(phi))?.a;
        rrr_dyad(a, c, 0.08, 0.15, Branch::Plus)
    })
    .unwrap();
    assert!(r.is_some());
}

#[test]
fn coaxial_closed_form_holds_at_large_lambda_t() {
    // A stiff motor: λτ in the thousands. The exact motion composes with itself (the flow
    // property) to 1e-12 relative, which the old form lost to cancellation of terms ~2e7.
    let mut cp = CoaxialPropellers::default();
    cp.motor.b = 1200.0;
    cp.motor.a = 1200.0 * 1100.0;
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(-10.0, 10.0));
    let direct = cp.exact(&s0, 20.0).unwrap();
    let mid = cp.exact(&s0, 7.0).unwrap();
    let composed = cp.exact(&mid, 20.0).unwrap();
    for i in 0..2 {
        let scale = direct.q[i].abs().max(1.0);
        assert!(
            (direct.q[i] - composed.q[i]).abs() <= 1e-12 * scale,
            "q{i}: {} vs {}",
            direct.q[i],
            composed.q[i]
        );
        let scale = direct.qd[i].abs().max(1.0);
        assert!((direct.qd[i] - composed.qd[i]).abs() <= 1e-12 * scale);
    }
}

// ---------------------------------------------------------------------------------------
// Sweeps: finite data whose products overflow
// ---------------------------------------------------------------------------------------

#[test]
fn sweep_overflowing_data() {
    use tmm::dynamics::machines::DecoupledRpArm;
    use tmm::kinetostatics::RprSeed;
    use tmm::linkage::IndicatorDiagram;
    sweep(41, |g| {
        let d = IndicatorDiagram {
            area: g.f(),
            outward: vec![[0.0, g.f()], [g.f().abs().min(1.0), g.f()], [1.0, g.f()]],
            inward: vec![[g.f(), g.f()], [1.0, g.f()]],
        };
        let (s, sd, guide, head, crank_end) = (g.f(), g.f(), g.v(), g.f(), g.f());
        check("IndicatorDiagram::force", &(&d, s, sd, guide, head), || {
            d.force(s, sd, guide, head, crank_end)
        });
        check("IndicatorDiagram::force", &(&d, s, sd), || {
            d.force(s, sd, Vector2::new(0.0, 1.0), 0.3, 0.2)
        });

        let r = RprSeed {
            l_ab: g.len(),
            l_ec: g.len(),
            l_bc: g.f(),
            l_as2: g.f(),
            l_es3: g.f(),
            phi2: g.f(),
            f2: g.f(),
            gamma2: g.f(),
            f3: g.f(),
            gamma3: g.f(),
            m2: g.f(),
            m3: g.f(),
        };
        check("RprSeed::to_dyad", &r, || r.to_dyad());

        let mut p = PaperGroup::example();
        for _ in 0..2 {
            match g.next() % 6 {
                0 => p.l1 = g.len(),
                1 => p.l2 = g.f(),
                2 => p.l3 = g.f(),
                3 => p.l4 = g.len(),
                4 => p.alpha4 = g.f(),
                _ => p.f1 = g.f(),
            }
        }
        check("PaperGroup::geometry", &p, || p.geometry());
        check("PaperGroup::loads", &p, || p.loads());

        let mut fb = FiveBar::default();
        for _ in 0..2 {
            let x = g.f();
            match g.next() % 8 {
                0 => fb.m2 = x,
                1 => fb.m3 = x,
                2 => fb.j_s2 = Some(x),
                3 => fb.j_s3 = Some(x),
                4 => fb.gravity = x,
                5 => fb.m_on = x,
                6 => fb.i1 = x,
                _ => fb.l_as2 = x,
            }
        }
        let q = if g.next().is_multiple_of(2) {
            Vector2::new(2.0, 1.0)
        } else {
            Vector2::new(g.f(), g.f())
        };
        let qd = g.v();
        check("FiveBar::point_masses", &fb, || fb.point_masses());
        check("FiveBar::inertia", &(fb, q), || fb.inertia(&q));
        check("FiveBar::inertia_derivatives", &(fb, q), || {
            fb.inertia_derivatives(&q)
        });
        check("FiveBar::potential", &(fb, q), || fb.potential(&q));
        check("FiveBar::potential_gradient", &(fb, q), || {
            fb.potential_gradient(&q)
        });
        check("FiveBar::forces", &(fb, q, qd), || fb.forces(0.0, &q, &qd));
        check("FiveBar::terms", &(fb, q, qd), || fb.terms(0.0, &q, &qd));

        let mut arm = RpArm::default();
        for _ in 0..2 {
            let x = g.f();
            match g.next() % 6 {
                0 => arm.iz1 = x,
                1 => arm.iz2 = x,
                2 => arm.m2 = x,
                3 => arm.r0 = x,
                4 => arm.b1 = x,
                _ => arm.b2 = x,
            }
        }
        let q = Vector2::new(g.f(), g.f());
        check("RpArm::inertia", &(arm, q), || arm.inertia(&q));
        check("RpArm::inertia_derivatives", &(arm, q), || {
            arm.inertia_derivatives(&q)
        });
        check("RpArm::damping", &(arm, q), || arm.damping(&q));
        let dec: DecoupledRpArm = arm.decoupled();
        check("DecoupledRpArm::inertia", &(arm, q), || dec.inertia(&q));
        check("DecoupledRpArm::damping", &(arm, q), || dec.damping(&q));
        let s = State::new(0.0, g.v(), g.v());
        let t = g.f();
        check("DecoupledRpArm::closed_form", &(arm, s, t), || {
            dec.closed_form(&s, t)
        });
    });
}

#[test]
fn repro_overflowing_data_is_an_overflow() {
    use tmm::kinetostatics::RprSeed;
    use tmm::linkage::IndicatorDiagram;
    let overflow = |r: tmm::Result<String>, what: &str| {
        assert!(matches!(r, Err(Error::Overflow { .. })), "{what}: {r:?}");
    };
    // A load far out along the rod.
    let r = RprSeed {
        l_ab: 1e308,
        l_ec: 1e308,
        l_bc: 0.0,
        l_as2: -1e308,
        l_es3: 1e308,
        phi2: 0.0,
        f2: 1.0,
        gamma2: 0.0,
        f3: 1.0,
        gamma3: 0.0,
        m2: 0.0,
        m3: 0.0,
    };
    overflow(r.to_dyad().map(|d| format!("{d:?}")), "RprSeed::to_dyad");
    // The paper group with links too long for their sum.
    let p = PaperGroup {
        l3: 1.5e308,
        l4: 1.5e308,
        ..PaperGroup::example()
    };
    overflow(
        p.geometry().map(|g| format!("{g:?}")),
        "PaperGroup::geometry",
    );
    overflow(p.loads().map(|g| format!("{g:?}")), "PaperGroup::loads");
    // The five-bar's masses and ΔJ too large.
    let base = FiveBar::default();
    let fb = FiveBar {
        m2: f64::MAX,
        m3: f64::MAX,
        l_as2: base.l_ab,
        l_bs3: 0.0,
        ..base
    };
    overflow(
        fb.point_masses().map(|m| format!("{m:?}")),
        "FiveBar::point_masses",
    );
    let q = Vector2::new(2.0, 1.0);
    let fb = FiveBar {
        j_s2: Some(-1e308),
        j_s3: Some(1e308),
        ..FiveBar::default()
    };
    if let Ok(k) = fb.kinematics(&q) {
        let _ = k;
        let r = fb.inertia_derivatives(&q);
        assert!(
            r.as_ref()
                .map_or(true, |d| d.iter().all(|m| m.iter().all(|x| x.is_finite()))),
            "{r:?}"
        );
    }
    // The R–P arm: l² m2 and b1 r0² too large.
    let arm = RpArm {
        m2: 1e300,
        r0: 1e200,
        ..RpArm::default()
    };
    let q = Vector2::new(0.0, 1e10);
    overflow(arm.inertia(&q).map(|m| format!("{m:?}")), "RpArm::inertia");
    overflow(arm.damping(&q).map(|m| format!("{m:?}")), "RpArm::damping");
    let q = Vector2::new(0.0, 1e300);
    overflow(
        arm.inertia_derivatives(&q).map(|m| format!("{m:?}")),
        "RpArm::inertia_derivatives",
    );
    let dec = RpArm {
        iz1: 1e308,
        iz2: 1e308,
        ..RpArm::default()
    }
    .decoupled();
    overflow(
        dec.inertia(&q).map(|m| format!("{m:?}")),
        "DecoupledRpArm::inertia",
    );
    // The gas force: a NaN station, a negative area, a force p·A beyond f64.
    let d = IndicatorDiagram {
        area: 0.01,
        outward: vec![[0.0, 1e5], [f64::NAN, 1e5], [1.0, 0.0]],
        inward: vec![[0.0, 1e5], [1.0, 1e5]],
    };
    let g = Vector2::new(0.0, 1.0);
    // Moving away from the head: the outward branch, between its NaN station and its last.
    let e = d.force(0.25, -1.0, g, 0.3, 0.2).unwrap_err();
    assert!(
        matches!(e, Error::NonFinite { name, .. } if name.starts_with("indicator diagram")),
        "{e}"
    );
    let d = IndicatorDiagram {
        area: -0.01,
        outward: vec![[0.0, 1e5], [1.0, 0.0]],
        inward: vec![[0.0, 1e5], [1.0, 1e5]],
    };
    let e = d.force(0.25, 1.0, g, 0.3, 0.2).unwrap_err();
    assert!(
        matches!(
            e,
            Error::NonPositive {
                name: "piston area",
                ..
            }
        ),
        "{e}"
    );
    let d = IndicatorDiagram {
        area: 1e300,
        outward: vec![[0.0, 1e300], [1.0, 0.0]],
        inward: vec![[0.0, 1e300], [1.0, 1e300]],
    };
    overflow(
        d.force(0.25, -1.0, g, 0.3, 0.2).map(|f| format!("{f:?}")),
        "IndicatorDiagram::force",
    );
    let e = d
        .force(0.25, 1.0, Vector2::new(f64::NAN, 1.0), 0.3, 0.2)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e}");
}

// ---------------------------------------------------------------------------------------
// The trait's default methods on a user's system
// ---------------------------------------------------------------------------------------

/// A user's system with A = diag(a·(2 + sin(ν q₁)), 1) and Π = p·sin(ν q₂): only `inertia`,
/// `forces` and `potential` written, every derivative left to the trait's numerical defaults.
#[derive(Debug, Clone, Copy)]
struct Wild {
    a: f64,
    nu: f64,
    p: f64,
}

impl LagrangeSystem for Wild {
    fn inertia(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(
            self.a * (2.0 + (self.nu * q[0]).sin()),
            0.0,
            0.0,
            1.0,
        ))
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(-qd)
    }
    fn potential(&self, q: &Vector2<f64>) -> tmm::Result<f64> {
        Ok(self.p * (self.nu * q[1]).sin())
    }
}

#[test]
fn sweep_default_methods_of_a_users_system() {
    sweep(43, |g| {
        let sys = Wild {
            a: g.f(),
            nu: g.f(),
            p: g.f(),
        };
        let (q, qd) = (g.v(), g.v());
        check(
            "LagrangeSystem::inertia_derivatives (default)",
            &(sys, q),
            || sys.inertia_derivatives(&q),
        );
        check(
            "LagrangeSystem::potential_gradient (default)",
            &(sys, q),
            || sys.potential_gradient(&q),
        );
        check("LagrangeSystem::terms (default)", &(sys, q, qd), || {
            sys.terms(0.0, &q, &qd)
        });
        check("accelerations (defaults)", &(sys, q, qd), || {
            accelerations(&sys, 0.0, &q, &qd)
        });
    });
}

#[test]
fn repro_default_derivatives_overflow_as_overflow_and_name_non_finite_samples() {
    let q = Vector2::new(0.3, 0.2);
    // Ordinary data: the defaults are the derivatives (a·ν·cos(ν q₁), p·ν·cos(ν q₂)) to the
    // fallback's documented accuracy.
    let calm = Wild {
        a: 2.0,
        nu: 1.5,
        p: 3.0,
    };
    let d = calm.inertia_derivatives(&q).unwrap();
    let exact = 2.0 * 1.5 * (1.5 * 0.3_f64).cos();
    assert!((d[0][(0, 0)] - exact).abs() < 1e-10 * exact, "{d:?}");
    assert_eq!(d[1], Matrix2::zeros());
    let grad = calm.potential_gradient(&q).unwrap();
    let exact = 3.0 * 1.5 * (1.5 * 0.2_f64).cos();
    assert!(
        grad[0] == 0.0 && (grad[1] - exact).abs() < 1e-10 * exact,
        "{grad:?}"
    );
    // Finite samples whose differences overflow: with ν·ε = π/2 (ε = 2·10⁻⁴ at q = 0) the
    // samples at ±ε are ±1.5·10³⁰⁸, and their difference is beyond f64's range (the
    // gradient gave inf in an Ok).
    let (nu, zero) = (std::f64::consts::FRAC_PI_2 / 2e-4, Vector2::zeros());
    let steep = Wild {
        a: 1.0,
        nu,
        p: 1.5e308,
    };
    for r in [
        steep.potential_gradient(&zero).map(|_| ()),
        steep.terms(0.0, &zero, &q).map(|_| ()),
    ] {
        assert!(
            matches!(r, Err(Error::Overflow { what }) if what.contains("gradient of the potential")),
            "{r:?}"
        );
    }
    let steep = Wild {
        a: 5e307,
        nu,
        p: 0.0,
    };
    let r = steep.inertia_derivatives(&zero);
    assert!(
        matches!(r, Err(Error::Overflow { what }) if what.contains("inertia matrix")),
        "{r:?}"
    );
    // A user's A or Π that is not finite near q is named, not differenced into NaN.
    let nan = Wild {
        a: f64::NAN,
        nu: 1.0,
        p: f64::INFINITY,
    };
    let r = nan.inertia_derivatives(&q);
    assert!(
        matches!(r, Err(Error::NonFinite { name, .. }) if name.starts_with("inertia matrix")),
        "{r:?}"
    );
    let r = nan.potential_gradient(&q);
    assert!(
        matches!(r, Err(Error::NonFinite { name, .. }) if name.starts_with("potential energy")),
        "{r:?}"
    );
    let r = calm.inertia_derivatives(&Vector2::new(f64::NAN, 0.0));
    assert!(
        matches!(r, Err(Error::NonFinite { name: "q1", .. })),
        "{r:?}"
    );
}

// ---------------------------------------------------------------------------------------
// Stops and reversals: a resistance that flips sign with the speed
// ---------------------------------------------------------------------------------------

use crate::dynamics::scenarios::Ramp;
use tmm::dynamics::Outcome;

/// The exact motion of the block on the ramp ([`Ramp`]) thrown at `v0` (x up the slope):
/// `(t₁, x₁, sticks)` where it first comes to rest, or `None` when it never does (it
/// slides down faster and faster); and x, v at a time `t` after the start.
fn ramp_exact(r: &Ramp, v0: f64, t: f64) -> (Option<(f64, f64, bool)>, f64, f64) {
    let pull = -r.slope_pull(); // down the slope, > 0
    let (m, f) = (r.m, r.friction);
    // Each piece has a constant acceleration: up the slope −(P + F)/m, down it (F − P)/m.
    let piece = |x0: f64, v: f64, a: f64, dt: f64| (x0 + v * dt + 0.5 * a * dt * dt, v + a * dt);
    if v0 > 0.0 {
        let a1 = (pull + f) / m;
        let (t1, x1) = (v0 / a1, v0 * v0 / (2.0 * a1));
        let sticks = f >= pull;
        let (x, v) = if t <= t1 {
            piece(0.0, v0, -a1, t)
        } else if sticks {
            (x1, 0.0)
        } else {
            piece(x1, 0.0, -(pull - f) / m, t - t1)
        };
        (Some((t1, x1, sticks)), x, v)
    } else if f > pull {
        let a1 = (f - pull) / m;
        let (t1, x1) = (-v0 / a1, -v0 * v0 / (2.0 * a1));
        let (x, v) = if t <= t1 {
            piece(0.0, v0, a1, t)
        } else {
            (x1, 0.0)
        };
        (Some((t1, x1, true)), x, v)
    } else {
        let (x, v) = piece(0.0, v0, (f - pull) / m, t);
        (None, x, v)
    }
}

/// Blocks of random mass on random ramps thrown up or down at random speeds, friction above
/// or below the slope's pull, run by RK4 (random step) and Dormand–Prince (random
/// tolerance) past the stop: each run lands on the zero of the speed and sticks there
/// (ending [`Outcome::Stuck`] at the exact time and place, the loads named) or reverses and
/// goes on exactly; no run chatters (a bounded number of steps). Accelerations are constant
/// on each piece, so both methods are exact up to rounding: the bound is 10⁻¹² of the
/// motion's scale. Then hostile numbers for every parameter: an error or a finite result.
#[test]
fn sweep_stops_and_reversals_of_a_block_on_a_ramp() {
    let (mut worst, mut stuck, mut reversed) = (0.0_f64, 0, 0);
    sweep(47, |g| {
        let m = 0.1 + 10.0 * g.unit();
        let alpha = 0.05 + 1.4 * g.unit();
        let pull = m * Ramp::G * alpha.sin();
        let friction = pull * 2.0 * g.unit();
        let v0 = (0.1 + 10.0 * g.unit())
            * if g.next().is_multiple_of(2) {
                1.0
            } else {
                -1.0
            };
        let r = Ramp { m, alpha, friction };
        let (stop, ..) = ramp_exact(&r, v0, 0.0);
        let t_end = stop.map_or(1.0, |(t1, ..)| t1 * (1.1 + 2.0 * g.unit()));
        let start = State::new(0.0, Vector2::zeros(), Vector2::new(v0, 0.0));
        let h = t_end * (0.003 + 0.2 * g.unit());
        let opts = RunOptions::until(t_end, h);
        let dp = Dopri5::new(10f64.powf(-12.0 + 6.0 * g.unit())).unwrap();
        let case = (r, v0, t_end, h);
        for (name, res, max_steps) in [
            ("RK4", run(&r, &Rk4, start, &opts), (t_end / h) as usize + 4),
            ("Dormand-Prince", run(&r, &dp, start, &opts), 400),
        ] {
            let res = res.unwrap_or_else(|e| panic!("{name} {case:?}: {e}"));
            assert!(
                res.steps <= max_steps,
                "{name} {case:?}: {} steps",
                res.steps
            );
            // The motion's scale: its largest speed and the longest way it went.
            let (_, x_end, v_end) = ramp_exact(&r, v0, res.last.t);
            let (vs, xs) = (v0.abs().max(v_end.abs()), 1.0 + x_end.abs() + v0 * v0);
            match (stop, res.outcome) {
                (
                    Some((t1, x1, true)),
                    Outcome::Stuck {
                        t,
                        switch: 0,
                        loads,
                    },
                ) => {
                    stuck += 1;
                    let e = ((t - t1) / t1)
                        .abs()
                        .max(((res.last.q[0] - x1) / xs).abs())
                        .max((res.last.qd[0] / vs).abs());
                    worst = worst.max(e);
                    assert!(e < 1e-12, "{name} {case:?}: stuck at {t}, {:?}", res.last);
                    assert!(loads.holds() && loads.drive == r.slope_pull(), "{loads:?}");
                    let msg = loads.stalled(t).to_string();
                    assert!(msg.contains("below the resistance"), "{msg}");
                }
                (Some((_, _, false)) | None, Outcome::FinalTime) => {
                    reversed += usize::from(stop.is_some());
                    let e = ((res.last.q[0] - x_end) / xs)
                        .abs()
                        .max(((res.last.qd[0] - v_end) / vs).abs());
                    worst = worst.max(e);
                    assert!(
                        e < 1e-12,
                        "{name} {case:?}: {:?} vs x {x_end}, v {v_end}",
                        res.last
                    );
                }
                (_, o) => panic!("{name} {case:?}: {o:?}, exact stop {stop:?}"),
            }
        }
        // Hostile numbers: an error or a finite result, within a small budget.
        let wild = Ramp {
            m: g.len(),
            alpha: g.f(),
            friction: g.f().abs(),
        };
        let s = State::new(0.0, Vector2::new(g.f(), 0.0), Vector2::new(g.f(), 0.0));
        let (t_end, h) = (g.len(), g.len());
        check("run (switches, RK4)", &(wild, s, t_end, h), || {
            run(&wild, &Rk4, s, &small_budget(t_end, h)).map(|r| (r.outcome, r.last))
        });
        check(
            "run (switches, Dormand-Prince)",
            &(wild, s, t_end, h),
            || run(&wild, &dp, s, &small_budget(t_end, h)).map(|r| (r.outcome, r.last)),
        );
    });
    println!("ramp: {stuck} runs stuck, {reversed} reversed; worst relative error {worst:.2e}");
    assert!(stuck > 0 && (reversed > 0 || cases() < 20));
}

/// The loads a system hands the run at a zero of its switch speed are checked: an infinite
/// or NaN breakaway load (friction `inf`, found by the sweep) or a negative one is an error
/// naming it, not a stuck run holding `inf` in its `Ok`.
#[test]
fn repro_switch_loads_are_checked() {
    let rest = State::at_rest(Vector2::zeros());
    let opts = RunOptions::until(1.0, 0.01);
    for (friction, bad) in [
        (f64::INFINITY, "forward breakaway load"),
        (f64::NAN, "forward breakaway load"),
        (-1.0, "forward breakaway load"),
    ] {
        let r = Ramp {
            m: 1.0,
            alpha: 0.1,
            friction,
        };
        let e = run(&r, &Rk4, rest, &opts).unwrap_err();
        let named = match &e {
            Error::NonFinite { name, .. } | Error::OutOfRange { name, .. } => name.contains(bad),
            _ => false,
        };
        assert!(named, "friction {friction}: {e}");
    }
}

// The entry points the sweeps above leave out.
mod synthesis;
mod uncovered;
