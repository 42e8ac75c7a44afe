//! Adversarial tests of the linkage engine's public entry points: descriptions with hostile
//! numbers or broken structure, hostile inputs at every position, hostile outputs and cycle
//! sizes, and malformed description files. Each gives an `Error` or a finite result: never a
//! panic, never an `Ok` holding a NaN or an infinity.
//!
//! Entry points: `Plan::new`, `Linkage::from_json`, `Plan::analyse`, `Plan::kinematics`,
//! `Analysis::power_check`, `worst_residual`, every reaction, joint and point accessor (by
//! name, and by index with indices out of range: `link_motion`, `link`, `joint_on`,
//! `joint`, `point`, `guide_direction`, `slide`, `reaction`, `free_body`, `residual`;
//! `Plan::point_local`,
//! `is_prismatic`, `joint_links`, `guide_link`),
//! `Plan::output`, `Plan::transfer`, `Plan::extremes`, `Plan::strokes`,
//! `Plan::lock_positions`, `uniform_inputs`, `Table::to_text`, `Analysis::transmission_angle`,
//! `Plan::min_transmission_angle`, `kinematics::grashof`; `linkage::dynamics::LinkageSystem`
//! (`from_linkage`, `with_motor`, `with_inertia`, `with_damper`, `terms`, `inverse_dynamics`,
//! `reduced`, `flywheel`, `turn`, `run_up`, `run_up_from` and `dynamics::run` by each
//! method on the four-bar and the Scotch yoke thrown at random speeds under random motors,
//! half of them stopping, sticking or turning back: each ends with a finite turn or a named
//! reason); `draw::{scheme, forces, animation, plan_view, diagram}`
//! and `Course::new` with hostile inputs and styles, every SVG written scanned for a
//! non-finite number; on every bundled linkage and on every ready
//! mechanism's description; and the ready mechanisms (`FourBar`, `SliderCrank`, `Compressor`,
//! `SixBar`, `RockingCylinder`: `plan`, `strokes`, `linkage`, `grashof`) with every public
//! field hostile; every `Ok` plan is checked finite whole (link data, joints, points, loads).
//! Planning is linear: `Plan::decomposition_work` on random descriptions of up to 10⁴ joints
//! in random and last-first order, its exponent fitted over the sizes.
//!
//! `TMM_HOSTILE_CASES` (default 200) is the number of calls each entry point gets in its
//! sweep, whatever the number of linkages it is spread over ([`shares`]): CI's run at 10⁵
//! calls each entry point 10⁵ times with hostile arguments. Where a case is a whole
//! linkage's work (its plan, its pictures, its cycle scans), the calls are shared among the
//! linkages by the cost of one of their solves, so that the cheap linkages take most of them.

use std::panic::{catch_unwind, AssertUnwindSafe};
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{
    bundled, try_course_inputs, try_uniform_inputs, uniform_inputs, At, JointKind, Linkage,
    LoadSpec, Output, Plan, Table,
};
use tmm::mechanism::{Compressor, FourBar, Mechanism, RockingCylinder, SixBar, SliderCrank};
use tmm::{Ends, Error};

use crate::common::chains::{fitted_exponent, random_linkage};
use crate::common::hostile_gen;
use hostile_gen::{cases, has_non_finite, ok_finite, Gen};

fn linkages() -> Vec<Linkage> {
    let mut all = bundled::all();
    all.extend([
        FourBar::course_example().linkage().unwrap(),
        SliderCrank::course_example().linkage().unwrap(),
        Compressor::course_example().linkage().unwrap(),
        SixBar::course_example().linkage().unwrap(),
        RockingCylinder::course_example().linkage().unwrap(),
    ]);
    all
}

/// How many of `total` calls of an entry point fall to each of `linkages`: shared in
/// proportion to the inverse cost of one of its solves (a linkage of dyads 1, one with a
/// triad 1/10, one with a group above the 3rd class, solved by Newton's method, 1/100), each
/// rounded up, so that together they make at least `total` and each linkage gets at least
/// one.
fn shares(total: usize, linkages: &[Linkage]) -> Vec<usize> {
    use tmm::linkage::GroupKind;
    let weight = |l: &Linkage| {
        let plan = Plan::new(l).unwrap();
        let kinds: Vec<GroupKind> = plan.groups().iter().map(|g| g.kind).collect();
        if kinds.contains(&GroupKind::General) {
            0.01
        } else if kinds.contains(&GroupKind::Triad) {
            0.1
        } else {
            1.0
        }
    };
    let weights: Vec<f64> = linkages.iter().map(weight).collect();
    let sum: f64 = weights.iter().sum();
    #[allow(clippy::cast_precision_loss)]
    let shares = weights
        .iter()
        .map(|w| ((total as f64 * w / sum).ceil() as usize).max(1))
        .collect();
    shares
}

/// The linkages with each one's share of `cases()` calls.
fn shared(linkages: Vec<Linkage>) -> impl Iterator<Item = (Linkage, usize)> {
    let n = shares(cases(), &linkages);
    linkages.into_iter().zip(n)
}

/// Runs `f`, failing the test on a panic, with `what` to replay it.
fn no_panic<T>(what: &str, f: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| panic!("panicked: {what}"))
}

/// Everything an analysis returns must be finite once it is `Ok`.
fn check_position(plan: &Plan, input: Motion, what: &str) {
    let Ok(a) = plan.analyse(input) else { return };
    let mut shown = format!("{:?}", a.balances()[0]);
    for j in 0..plan.joint_names().len() {
        shown += &format!("{:?}{:?}", a.reaction(j).unwrap(), a.joint(j).unwrap());
    }
    for k in 0..plan.point_names().len() {
        shown += &format!("{:?}", a.point(k).unwrap());
    }
    for k in 0..plan.link_names().len() {
        shown += &format!("{:?}", a.link(k).unwrap());
    }
    shown += &format!("{:?}{:?}", a.conditioning(), a.applied_loads());
    assert!(!has_non_finite(&shown), "{what}: {input:?} gave {shown}");
    if let Ok(p) = a.power_check() {
        assert!(
            p.chain.is_finite() && p.virtual_power.is_finite(),
            "{what}: {p:?}"
        );
    }
    assert!(a.worst_residual().is_finite(), "{what}: residual");
}

#[test]
fn hostile_inputs_at_a_position() {
    let mut g = Gen::new(11);
    for (l, n) in shared(linkages()) {
        let plan = Plan::new(&l).unwrap();
        for _ in 0..n {
            let input = g.motion();
            let what = format!("{} at {input:?}", l.name);
            no_panic(&what, || check_position(&plan, input, &what));
        }
    }
}

/// A hostile number in one place of a description.
fn corrupt(l: &mut Linkage, g: &mut Gen) {
    let x = g.f();
    match g.next() % 8 {
        0 => {
            let j = (g.next() % l.joints.len() as u64) as usize;
            l.joints[j].at[(g.next() % 2) as usize] = x;
        }
        1 => {
            let j = (g.next() % l.joints.len() as u64) as usize;
            if let JointKind::Prismatic { direction, .. } = &mut l.joints[j].kind {
                direction[(g.next() % 2) as usize] = x;
            } else {
                l.joints[j].at[0] += x;
            }
        }
        2 => {
            let k = (g.next() % l.links.len() as u64) as usize;
            if let Some(m) = &mut l.links[k].mass {
                match g.next() % 3 {
                    0 => m.m = x,
                    1 => m.j = x,
                    _ => m.centre = At::Coords([x, g.f()]),
                }
            }
        }
        3 => l.gravity = [x, g.f()],
        4 => {
            for load in &mut l.loads {
                match load {
                    LoadSpec::Force { force, .. } => force[0] = x,
                    LoadSpec::Moment { moment, .. } => *moment = x,
                    LoadSpec::Resistance { forward, .. } => *forward = x,
                    LoadSpec::Indicator { head, .. } => *head = x,
                    LoadSpec::Spring { stiffness, .. } => *stiffness = x,
                    LoadSpec::Damper { c, .. } => *c = x,
                    LoadSpec::TorsionSpring { preload, .. } => *preload = x,
                }
            }
        }
        5 => {
            // A structural fault: a joint dropped from a link, or a link dropped.
            let k = (g.next() % l.links.len() as u64) as usize;
            if g.next().is_multiple_of(2) {
                l.links[k].joints.pop();
            } else {
                l.links.remove(k);
            }
        }
        6 => {
            // Every coordinate scaled: a huge or tiny linkage.
            for j in &mut l.joints {
                j.at = [j.at[0] * x, j.at[1] * x];
            }
        }
        _ => {
            let j = (g.next() % l.joints.len() as u64) as usize;
            let k = (g.next() % l.joints.len() as u64) as usize;
            l.joints[j].name = l.joints[k].name.clone();
        }
    }
}

#[test]
fn hostile_descriptions_plan_or_err_and_then_solve_or_err() {
    let mut g = Gen::new(23);
    let mut scanned = 0;
    for (base, n) in shared(linkages()) {
        for case in 0..n {
            let mut l = base.clone();
            corrupt(&mut l, &mut g);
            let what = format!("{} case {case}", base.name);
            let Ok(plan) = no_panic(&what, || Plan::new(&l)) else {
                continue;
            };
            check_plan(&plan, &what);
            for k in 0..4 {
                let input = Motion::new(plan.reference_input() + 1.3 * f64::from(k), 5.0, 1.0);
                no_panic(&what, || check_position(&plan, input, &what));
            }
            // The scans of a cycle on the hostile description: its output's extremes and
            // strokes, and the input's lock positions.
            scanned += 1;
            no_panic(&what, || scans(&plan, l.output.as_ref(), g.f(), &what));
        }
    }
    assert!(scanned > 0);
}

/// The scans over a cycle of `plan` (`Plan::extremes` and `Plan::strokes` of `output`, or of
/// the last link's angle where the description names none, so that every case calls them; a
/// crank's `Plan::lock_positions` from `phi`): an error or finite numbers.
fn scans(plan: &Plan, output: Option<&Output>, phi: f64, what: &str) {
    {
        let out = &plan.output_or_last(output);
        if let Ok(e) = plan.extremes(out) {
            assert!(!has_non_finite(&format!("{e:?}")), "{what}: {e:?}");
        }
        let rotation = if phi.is_sign_negative() {
            Rotation::Cw
        } else {
            Rotation::Ccw
        };
        if let Ok(s) = plan.strokes(out, rotation) {
            assert!(!has_non_finite(&format!("{s:?}")), "{what}: {s:?}");
        }
    }
    if let Ok(Some(lock)) = plan.lock_positions(phi) {
        assert!(
            lock.0.is_finite() && lock.1.is_finite(),
            "{what}: {phi} {lock:?}"
        );
    }
}

#[test]
fn hostile_outputs_cycles_and_tables() {
    let mut g = Gen::new(37);
    for (l, share) in shared(linkages()) {
        let plan = Plan::new(&l).unwrap();
        let mut outputs = vec![
            Output::Angle("no such link".into()),
            Output::Slide("no such joint".into()),
            Output::X("nowhere".into()),
        ];
        outputs.extend(plan.link_names().iter().map(|n| Output::Angle(n.clone())));
        outputs.extend(plan.joint_names().iter().map(|n| Output::Y(n.clone())));
        // Below 10³ calls (the default run) every sixth real output, from a different first
        // one per linkage (angles and coordinates both among them over the linkages); CI's run
        // covers them all.
        let stride = if cases() < 1000 { 6 } else { 1 };
        let skip = l.name.len() % stride;
        let outputs: Vec<Output> = outputs
            .into_iter()
            .enumerate()
            .filter(|(i, _)| *i < 3 || (i - 3) % stride == skip)
            .map(|(_, o)| o)
            .collect();
        // The linkage's share of the calls: `output` and `transfer` at hostile inputs, the
        // outputs taken in turn, and the lock search from a hostile angle; each output's
        // extremes and strokes once (they depend on the output alone: on hostile
        // descriptions they are swept in `hostile_descriptions_plan_or_err_…`).
        for case in 0..share.max(outputs.len()) {
            let out = &outputs[case % outputs.len()];
            let (input, q, phi) = (g.motion(), g.f(), g.f());
            let what = format!("{} {out:?}", l.name);
            no_panic(&what, || {
                if let Ok(m) = plan.output(out, input) {
                    assert!(
                        !has_non_finite(&format!("{m:?}")),
                        "{what}: {input:?} {m:?}"
                    );
                }
                if let Ok(m) = plan.transfer(out, q) {
                    assert!(!has_non_finite(&format!("{m:?}")), "{what}: {q} {m:?}");
                }
                let first = case < outputs.len();
                scans(&plan, Some(out).filter(|_| first), phi, &what);
            });
        }
        for n in [0, 1, 2, 7, usize::MAX] {
            let (start, w) = (g.f(), g.f());
            let inputs = no_panic("uniform_inputs", || uniform_inputs(n, start, w, 0.0));
            assert!(inputs.len() <= n.min(1 << 24));
            let rows: Vec<_> = inputs.iter().take(8).map(|&i| plan.analyse(i)).collect();
            let table = Table::of(&rows);
            let text = no_panic("to_text", || table.to_text(usize::MAX));
            assert!(
                text.lines().count()
                    == if table.is_empty() {
                        0
                    } else {
                        table.columns.len()
                    }
            );
        }
    }
}

/// An input coordinate beyond ±10⁹ (rad, or m for a slider) names no position: a course
/// refuses it, naming the field; at the bound one still does.
#[test]
fn meaningless_input_angles_are_refused() {
    use tmm::linkage::{Course, TwoInputCourse, MAX_INPUT_COORDINATE};
    let max = MAX_INPUT_COORDINATE;
    // The reason for the bound: there neighbouring angles are 2⁻²³ ≈ 1.2·10⁻⁷ rad apart.
    let next = f64::from_bits(max.to_bits() + 1);
    assert_eq!(next - max, 2f64.powi(-23));
    let named = |r: tmm::Result<()>, field: &str| match r {
        Err(Error::OutOfRange {
            name, min, max: hi, ..
        }) => {
            assert_eq!((name, min, hi), (field, -max, max));
        }
        other => panic!("{field}: {other:?}"),
    };
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    // The four-bar's crank turns fully: a rocking course ending at the bound is a course.
    let course = Course::rocking(&plan, max - 1.0, max, 4, 1.0).unwrap();
    assert_eq!(course.inputs[2].value, max);
    assert!(course.check().is_ok());
    for (from, to, field) in [(1e300, 0.0, "from"), (0.0, -2e9, "to"), (next, 1.0, "from")] {
        named(Course::rocking(&plan, from, to, 4, 1.0).map(|_| ()), field);
    }
    named(Course::given(vec![Motion::fixed(-1e10)]).check(), "input");
    assert!(Course::given(vec![Motion::fixed(-max)]).check().is_ok());
    let grid = |first: [f64; 2]| TwoInputCourse::grid(first, [0.0, 1.0], [2, 2], [1.0, 1.0]);
    named(
        grid([0.0, 1e12]).map(|_| ()),
        "end of the first input's range",
    );
    assert!(grid([-max, max]).is_ok());
    // The lock search too (its 720 steps would vanish in the rounding of 10¹⁷ rad and every
    // sample "assemble"): the Peaucellier crank rocks, at its reference angle and at the bound.
    let peaucellier = Plan::new(&bundled::peaucellier_lipkin()).unwrap();
    let r = peaucellier.reference_input();
    let (lo, hi) = peaucellier.lock_positions(r).unwrap().unwrap();
    named(peaucellier.lock_positions(1e17).map(|_| ()), "phi");
    let turns = ((max - r) / std::f64::consts::TAU).floor() * std::f64::consts::TAU;
    let (lo2, hi2) = peaucellier.lock_positions(r + turns).unwrap().unwrap();
    assert!(
        (lo2 - turns - lo).abs() < 1e-6 && (hi2 - turns - hi).abs() < 1e-6,
        "{lo} {hi} vs {} {}",
        lo2 - turns,
        hi2 - turns
    );
    // A single solve too: the one-shot, a reused solver, the position and a two-input plan.
    named(plan.analyse(Motion::fixed(1e300)).map(|_| ()), "input");
    named(
        plan.solver().kinematics(Motion::fixed(-next)).map(|_| ()),
        "input",
    );
    named(plan.position(Motion::fixed(2e9)).map(|_| ()), "input");
    assert!(plan.analyse(Motion::fixed(max)).is_ok());
    let five = Plan::new(&bundled::five_bar_robot()).unwrap();
    let two = |a: f64, b: f64| {
        five.kinematics([Motion::fixed(a), Motion::fixed(b)])
            .map(|_| ())
    };
    named(two(1.0, 1e200), "second input");
    named(two(-1e200, 1.0), "input");
    // A range too wide for an f64 is still an overflow, before its ends are looked at.
    assert!(matches!(grid([-1e308, 1e308]), Err(Error::Overflow { .. })));
    let far = TwoInputCourse::laws(&[0.0], |_| Motion::fixed(0.0), |_| Motion::fixed(1e300));
    match far {
        Err(Error::In { part, source }) => {
            assert!(part.contains("second input's law"), "{part}");
            named(Err(*source), "input");
        }
        other => panic!("{other:?}"),
    }
}

#[cfg(feature = "serde")]
#[test]
fn malformed_files_are_errors() {
    let text = include_str!("../../linkages/watt-six-bar.json");
    let mut g = Gen::new(41);
    for case in 0..cases() {
        let mut bytes = text.as_bytes().to_vec();
        match g.next() % 3 {
            0 => bytes.truncate((g.next() % bytes.len() as u64) as usize),
            1 => {
                let k = (g.next() % bytes.len() as u64) as usize;
                bytes[k] = b"{}[],:\"0-e9 x"[(g.next() % 13) as usize];
            }
            _ => {
                let k = (g.next() % bytes.len() as u64) as usize;
                bytes.insert(k, b"{}[],:\"0-e9 x"[(g.next() % 13) as usize]);
            }
        }
        let s = String::from_utf8_lossy(&bytes).into_owned();
        let what = format!("case {case}");
        if let Ok(l) = no_panic(&what, || Linkage::from_json(&s))
            && let Ok(plan) = no_panic(&what, || Plan::new(&l))
        {
            let input = Motion::new(plan.reference_input() + 0.4, 3.0, 0.0);
            no_panic(&what, || check_position(&plan, input, &what));
        }
    }
    // Numbers JSON cannot hold finitely.
    let huge = text.replacen("0.08", "1e999", 1);
    assert!(
        Linkage::from_json(&huge).is_err()
            || Plan::new(&Linkage::from_json(&huge).unwrap()).is_err()
    );
}

// ---- the rest of the linkage API: dynamics of a linkage, pictures, Grashof ------------

use nalgebra::Vector2;
#[cfg(feature = "draw")]
use tmm::draw::{self, Course, Diagram, Style};
use tmm::kinematics::grashof;
use tmm::linkage::dynamics::{Damper, LinkageSystem, Motor};

#[test]
fn hostile_dynamics_of_linkages() {
    let mut g = Gen::new(53);
    let with_systems: Vec<Linkage> = linkages()
        .into_iter()
        .filter(|l| LinkageSystem::from_linkage(l).is_ok())
        .collect();
    for (l, n) in shared(with_systems) {
        let sys = LinkageSystem::from_linkage(&l).unwrap();
        for case in 0..n {
            let (q, qd, qdd) = (g.v(), g.v(), g.v());
            let what = format!("{} case {case}: q {q:?} q' {qd:?} q'' {qdd:?}", l.name);
            no_panic(&what, || {
                if let Ok(t) = sys.split_terms(&q, &qd) {
                    assert!(!has_non_finite(&format!("{t:?}")), "{what}: {t:?}");
                }
                if let Ok(m) = sys.inverse_dynamics(&q, &qd, &qdd) {
                    assert!(m.iter().all(|x| x.is_finite()), "{what}: {m:?}");
                }
                if let Ok(r) = sys.reduced(q.x, qd.x) {
                    assert!(!has_non_finite(&format!("{r:?}")), "{what}: {r:?}");
                }
            });
            let (x, y) = (g.f(), g.f());
            let n = (g.next() % 40) as usize;
            no_panic(&what, || {
                if let Ok(f) = sys.flywheel(x, y, n) {
                    assert!(!has_non_finite(&format!("{f:?}")), "{what}: {f:?}");
                }
                let with = sys
                    .clone()
                    .with_motor(0, Motor::Constant(x))
                    .and_then(|s| s.with_inertia(0, y))
                    .and_then(|s| {
                        s.with_damper(&Damper::Link {
                            link: "crank".into(),
                            c: x,
                        })
                    });
                if let Ok(s) = with
                    && let Ok(t) = s.split_terms(&Vector2::new(0.3, 0.0), &Vector2::new(y, 0.0))
                {
                    assert!(!has_non_finite(&format!("{t:?}")), "{what}: {t:?}");
                }
            });
        }
    }
}

/// A turn's numbers are finite and consistent: a positive period, the mean speed 2π over it,
/// ω_min ≤ ω_max, the coefficient of fluctuation from them.
fn check_turn(t: &tmm::linkage::dynamics::Turn, what: &str) {
    assert!(!has_non_finite(&format!("{t:?}")), "{what}: {t:?}");
    assert!(t.period > 0.0, "{what}: {t:?}");
    assert_eq!(t.omega_mean, std::f64::consts::TAU / t.period, "{what}");
    assert!(
        0.0 <= t.omega_min && t.omega_min <= t.omega_max,
        "{what}: {t:?}"
    );
}

/// The bundled four-bar and the Scotch yoke (one crank, resistances that flip with its speed)
/// thrown at random speeds from random angles under random constant motors, each run by
/// Dormand–Prince (a random tolerance in [10⁻⁸, 10⁻⁴]), RK4 or finite increments (a random
/// step in [10^-3.5, 10⁻²] s: a smaller one costs more and finds nothing new). Half the cases
/// are the class of stops, sticks and reversals: a motor of up to ±55 N·m (either side of the
/// breakaway) and a throw of up to ±30 rad/s either way, so that the machine runs on, stops
/// and sticks, or stops and turns back (issue 27: thrown backwards against a forward motor,
/// Dormand–Prince integrated the runaway motion after the reversal until its step fell to
/// 10⁻¹²·t; before that, `turn(&Dopri5 { rtol: 1e-6, atol: 1e-6 }, (0, 17.25), max_turn_time
/// 0.95)` chattered about ω = 0 until ten million steps ran out). The rest are the issue's
/// throw and hostile numbers. Every `turn` ends with a turn (finite, consistent), stalled
/// (both loads named), turned back (at a finite time, within the turn) or another named
/// error, never an exhausted step budget nor, in the class, a step that falls to nothing;
/// `run_up_from` and `run_up` never return a turn of no duration or an infinite mean speed;
/// `run` ends within a budget of 10⁵ steps unless the machine turned that much. `cases()`
/// calls of each of `turn`, `run_up`, `run_up_from` and `run` over the two (one test each,
/// so that they run side by side), a third each method.
#[test]
fn turns_and_run_ups_of_the_four_bar_end_with_a_reason() {
    turns_and_run_ups_end_with_a_reason(&bundled::four_bar(), 67);
}

/// See [`turns_and_run_ups_of_the_four_bar_end_with_a_reason`].
#[test]
fn turns_and_run_ups_of_the_scotch_yoke_end_with_a_reason() {
    turns_and_run_ups_end_with_a_reason(&bundled::scotch_yoke(), 68);
}

/// Calls `$e` with `$m` bound to the method `$k` picks: Dormand–Prince `$dp`, RK4 or finite
/// increments.
macro_rules! by_method {
    ($k:expr, $dp:expr, $m:ident => $e:expr) => {
        match $k {
            0 => {
                let $m = &$dp;
                $e
            }
            1 => {
                let $m = &tmm::dynamics::Rk4;
                $e
            }
            _ => {
                let $m = &tmm::dynamics::FiniteIncrement;
                $e
            }
        }
    };
}

/// What the sweep of [`turns_and_run_ups_end_with_a_reason`] saw of `turn`.
#[derive(Default, Debug)]
struct TurnCounts {
    turned: usize,
    stalled: usize,
    back: usize,
}

/// Checks what `turn` returned in a case of the sweep (`class`: in the class of stops and
/// reversals).
fn check_turn_end(
    r: Result<(tmm::linkage::dynamics::Turn, tmm::dynamics::RunResult), Error>,
    class: bool,
    counts: &mut TurnCounts,
    what: &str,
) {
    match r {
        Ok((t, _)) => {
            counts.turned += 1;
            check_turn(&t, what);
        }
        Err(Error::Stalled {
            drive, resistance, ..
        }) => {
            counts.stalled += 1;
            assert!(drive <= resistance, "{what}: {drive} vs {resistance}");
        }
        Err(e @ Error::TurnedBack { fraction, .. }) => {
            counts.back += 1;
            // Within the turn; a hostile start (10¹⁹ rad/s) may make several turns in the
            // one step that turns it back.
            assert!(
                fraction >= 0.0 && fraction.is_finite() && (!class || fraction < 1.0),
                "{what}: {e}"
            );
            assert!(!has_non_finite(&format!("{e:?}")), "{what}: {e:?}");
        }
        Err(e @ Error::Budget { .. }) => panic!("{what}: {e}"),
        Err(e @ Error::Singular { what: step, .. }) if class && step.starts_with("adaptive") => {
            panic!("{what}: {e}")
        }
        Err(_) => {}
    }
}

fn turns_and_run_ups_end_with_a_reason(l: &Linkage, seed: u64) {
    use nalgebra::Vector2;
    use tmm::dynamics::{run, Dopri5, RunOptions, State};
    use tmm::linkage::dynamics::RunUpOptions;
    let mut g = Gen::new(seed);
    let mut counts = TurnCounts::default();
    let base = LinkageSystem::from_linkage(l).unwrap();
    for case in 0..cases().div_ceil(2) {
        let class = g.next().is_multiple_of(2);
        let moment = match g.next() % 4 {
            _ if class => 110.0 * (g.unit() - 0.5),
            0 => 0.0,
            1 => g.f(),
            _ => 80.0 * (g.unit() - 0.3),
        };
        let Ok(sys) = base.clone().with_motor(0, Motor::Constant(moment)) else {
            continue;
        };
        let (phi, omega) = match g.next() % 4 {
            _ if class => (10.0 * (g.unit() - 0.5), 60.0 * (g.unit() - 0.5)),
            0 => (0.0, 17.25),
            1 => (g.f(), g.f()),
            _ => (10.0 * (g.unit() - 0.5), 60.0 * (g.unit() - 0.5)),
        };
        let start = State::new(0.0, Vector2::new(phi, 0.0), Vector2::new(omega, 0.0));
        let tol = 10f64.powf(-8.0 + 4.0 * g.unit());
        let h = 10f64.powf(-3.5 + 1.5 * g.unit());
        let opts = RunUpOptions::new(h)
            .with_max_turns(3)
            .with_max_turn_time(0.95);
        let dp = Dopri5 {
            rtol: tol,
            atol: tol,
        };
        let k = g.next() % 3;
        let what = format!(
            "{} case {case}: method {k}, M {moment}, start {start:?}, h {h}, tol {tol}",
            l.name
        );
        let r = no_panic(&what, || by_method!(k, dp, m => sys.turn(m, start, &opts)));
        check_turn_end(r, class, &mut counts, &what);
        for from_rest in [false, true] {
            let r = no_panic(&what, || {
                if from_rest {
                    by_method!(k, dp, m => sys.run_up(m, &opts))
                } else {
                    by_method!(k, dp, m => sys.run_up_from(m, start, &opts))
                }
            });
            match r {
                Ok(up) => up.turns.iter().for_each(|t| check_turn(t, &what)),
                Err(Error::Budget { what: budget, .. }) => assert_eq!(budget, "turn", "{what}"),
                Err(e @ Error::Singular { what: step, .. })
                    if class && step.starts_with("adaptive") =>
                {
                    panic!("{what}: {e}")
                }
                Err(_) => {}
            }
        }
        // A bare run of 0.3 s ends (stuck, at its final time or with a named error) well
        // within a budget of 10⁵ steps.
        let mut ro = RunOptions::until(0.3, h);
        ro.max_steps = 100_000;
        let r = no_panic(&what, || by_method!(k, dp, m => run(&sys, m, start, &ro)));
        match r {
            Ok(r) => {
                let shown = format!("{:?} {:?}", r.outcome, r.last);
                assert!(!has_non_finite(&shown), "{what}: {shown}");
            }
            // A run that turns more than 10⁵ steps can resolve (over 100 turns, at under
            // 1000 steps a turn: a fast start, or a huge motor that spins the crank up
            // ever faster) may use its budget on motion; any other run must not (that
            // is chattering at a stop). The turns made are measured by the same run up
            // to where the budget ran out, with room to get there.
            Err(e @ Error::Budget { limit, time, .. }) => {
                let mut again = RunOptions::until(time, h);
                again.max_steps = 10 * limit;
                let r = by_method!(k, dp, m => run(&sys, m, start, &again))
                    .unwrap_or_else(|e2| panic!("{what}: {e}, then {e2}"));
                let turns = (r.last.q[0] - start.q[0]).abs() / std::f64::consts::TAU;
                assert!(
                    turns > limit as f64 / 1000.0,
                    "{what}: {e} after {turns} turns"
                );
            }
            Err(_) => {}
        }
    }
    println!("{}: {counts:?}", l.name);
    assert!(
        counts.turned > 0 && counts.stalled > 0 && counts.back > 0,
        "{}: {counts:?}",
        l.name
    );
}

/// The bundled four-bar driven from its rocker (a rocking input), thrown from random angles
/// within its rocking range at random speeds under random constant moments, by each method
/// with a random step or tolerance, for up to 0.3 s: a run that reaches a lock ends `Ok`
/// with [`Outcome::DeadCentre`](tmm::dynamics::Outcome::DeadCentre) at the last state the
/// linkage accepts (its dyad's |det| above 10⁻³, just above in most runs; the refused
/// one's at most 10⁻³, finite), or stuck, or at its final time; any other end is a named error, never an
/// exhausted budget. A tenth of `cases()` runs (each is up to 3000 steps), a third each
/// method; both locks are met.
#[test]
fn runs_of_a_rocking_input_stop_at_its_locks() {
    use tmm::dynamics::{run, Dopri5, Outcome, RunOptions, State};
    let mut l = bundled::four_bar();
    l.input = tmm::linkage::Input::crank("rocker");
    l.groups.clear();
    l.modes.clear();
    let base = LinkageSystem::from_linkage(&l).unwrap();
    let plan = base.plan().clone();
    let (lo, hi) = plan
        .lock_positions(plan.reference_input())
        .unwrap()
        .unwrap();
    let mut g = Gen::new(71);
    let (mut locks, mut stuck, mut other, mut near) = ([0usize; 2], 0, 0, 0);
    for case in 0..cases().div_ceil(10) {
        let moment = 80.0 * (g.unit() - 0.5);
        let sys = base.clone().with_motor(0, Motor::Constant(moment)).unwrap();
        let phi = lo + (hi - lo) * (0.02 + 0.96 * g.unit());
        let start = State::new(
            0.0,
            Vector2::new(phi, 0.0),
            Vector2::new(20.0 * (g.unit() - 0.5), 0.0),
        );
        let tol = 10f64.powf(-10.0 + 5.0 * g.unit());
        let h = 10f64.powf(-4.0 + 2.0 * g.unit());
        let dp = Dopri5 {
            rtol: tol,
            atol: tol,
        };
        let k = g.next() % 3;
        let what =
            format!("case {case}: method {k}, M {moment}, start {start:?}, h {h}, tol {tol}");
        let mut ro = RunOptions::until(0.3, h);
        ro.max_steps = 100_000;
        let r = no_panic(&what, || by_method!(k, dp, m => run(&sys, m, start, &ro)));
        match r {
            Ok(r) => {
                let shown = format!("{:?} {:?}", r.outcome, r.last);
                assert!(!has_non_finite(&shown), "{what}: {shown}");
                match r.outcome {
                    Outcome::DeadCentre { t, dyad, value } => {
                        assert_eq!((t, dyad), (r.last.t, 0), "{what}");
                        assert!(value.abs() <= 1e-3, "{what}: {value}");
                        let det = plan
                            .kinematics(Motion::fixed(r.last.q[0]))
                            .unwrap()
                            .group_determinants()[0];
                        // Accepted; at the band's edge, unless a coarse fixed step left
                        // the motion near the lock (det ∝ √(φ_L − φ), where the equation
                        // is singular) on a path of its own.
                        assert!(det.abs() > 1e-3, "{what}: {det}");
                        near += usize::from(det.abs() < 1.01e-3);
                        locks[usize::from(r.last.q[0] > 0.5 * (lo + hi))] += 1;
                    }
                    Outcome::Stuck { .. } => stuck += 1,
                    _ => other += 1,
                }
            }
            Err(e @ Error::Budget { .. }) => panic!("{what}: {e}"),
            Err(e) => assert!(!has_non_finite(&e.to_string()), "{what}: {e}"),
        }
    }
    println!(
        "rocking input: locks {locks:?} ({near} within 1 % of the band's edge), stuck {stuck}, \
         other {other}"
    );
    assert!(locks[0] > 0 && locks[1] > 0, "{locks:?}");
    assert!(2 * near >= locks[0] + locks[1], "{near} of {locks:?}");
}

#[cfg(feature = "draw")]
#[test]
fn hostile_pictures() {
    use crate::common::svg_scan::assert_finite_svg;
    let mut g = Gen::new(59);
    let mut svgs = 0;
    for (l, n) in shared(bundled::all()) {
        let plan = Plan::new(&l).unwrap();
        for case in 0..n {
            let input = g.motion();
            let mut style = Style::default();
            match g.next() % 4 {
                0 => style.margin = g.f(),
                1 => style.line_width = g.f(),
                2 => style.hinge_radius = g.f(),
                _ => style.width = (g.next() % 5000) as u32,
            }
            let what = format!("{} case {case}: {input:?} {style:?}", l.name);
            no_panic(&what, || {
                let inputs = vec![input, g.motion()];
                let course = Course {
                    extremes: vec![g.motion()],
                    ..Course::given(inputs)
                };
                let pictures = [
                    ("scheme", draw::scheme(&plan, input, &style)),
                    ("forces", draw::forces(&plan, input, &style)),
                    (
                        "animation",
                        draw::animation(&plan, &[input, g.motion()], g.f(), &style),
                    ),
                    (
                        "plan_view",
                        draw::plan_view(&plan, &course, &["B", "nowhere"], &style),
                    ),
                ];
                if let Ok(chart) = draw::diagram(&plan, &course, &Diagram::Balance, &style) {
                    svgs += 1;
                    assert_finite_svg(&chart.svg, &format!("diagram of {what}"));
                    let numbers = format!("{:?}", chart.panels);
                    assert!(!has_non_finite(&numbers), "{what}: {numbers}");
                }
                for (name, pic) in pictures {
                    if let Ok(pic) = pic {
                        svgs += 1;
                        assert_finite_svg(&pic.svg, &format!("{name} of {what}"));
                        let numbers = format!("{:?} {:?}", pic.frame, pic.force_scale);
                        assert!(!has_non_finite(&numbers), "{what}: {numbers}");
                    }
                }
                let course = Course::new(&plan, l.output.as_ref(), (g.next() % 30) as usize, g.f());
                ok_finite(&course, &format!("Course::new of {what}"));
            });
        }
    }
    println!("{svgs} pictures drawn and scanned");
    assert!(svgs > 0 || cases() < 10);
}

#[test]
fn hostile_grashof_and_transmission_angles() {
    let mut g = Gen::new(61);
    for case in 0..cases() * 10 {
        let (a, b, c, d) = (g.len(), g.len(), g.len(), g.len());
        no_panic(&format!("grashof case {case}"), || {
            ok_finite(&grashof(a, b, c, d), &format!("grashof case {case}"));
        });
    }
    for l in linkages() {
        let plan = Plan::new(&l).unwrap();
        for k in [0, 1, 2, usize::MAX] {
            let what = format!("{} group {k}", l.name);
            no_panic(&what, || {
                if let Ok((mu, at)) = plan.min_transmission_angle(k) {
                    assert!(
                        (0.0..=std::f64::consts::FRAC_PI_2).contains(&mu),
                        "{what}: {mu}"
                    );
                    assert!(at.is_finite(), "{what}");
                }
                if let Ok(a) = plan.kinematics(Motion::fixed(plan.reference_input()))
                    && let Ok(mu) = a.transmission_angle(k)
                {
                    assert!(mu.is_finite(), "{what}");
                }
            });
        }
    }
}

/// One hostile field of a ready mechanism, then everything it offers: its plan, an analysis
/// at hostile and ordinary crank angles, its strokes, its description (and Grashof's test for
/// the four-bar). The structs' fields are public, so every one is set by hand here.
fn sweep_mechanism<M: std::fmt::Debug + Clone>(
    name: &str,
    base: &M,
    setters: &[fn(&mut M, f64)],
    seed: u64,
    run: impl Fn(&M, &str, &mut Gen),
) {
    let mut g = Gen::new(seed);
    for case in 0..cases() {
        let mut m = base.clone();
        // One field most of the time, sometimes two.
        for _ in 0..1 + usize::from(g.next().is_multiple_of(4)) {
            let k = (g.next() % setters.len() as u64) as usize;
            let v = if g.next().is_multiple_of(2) {
                g.f()
            } else {
                g.len()
            };
            setters[k](&mut m, v);
        }
        let what = format!("{name} case {case}: {m:?}");
        no_panic(&what, || run(&m, &what, &mut g));
    }
}

/// What every ready mechanism offers, checked as the other sweeps check the engine.
fn mechanism_checks(
    plan: tmm::Result<Plan>,
    strokes: impl Fn(Rotation) -> tmm::Result<tmm::kinematics::Strokes>,
    what: &str,
    g: &mut Gen,
) {
    // One sense of rotation a case (a scan of the cycle each): both over the sweep.
    let rot = if g.next().is_multiple_of(2) {
        Rotation::Ccw
    } else {
        Rotation::Cw
    };
    if let Ok(s) = strokes(rot) {
        assert!(!has_non_finite(&format!("{s:?}")), "{what}: {s:?}");
    }
    if let Ok(plan) = plan {
        check_plan(&plan, what);
        for input in [Motion::fixed(plan.reference_input()), g.motion()] {
            check_position(&plan, input, what);
        }
    }
}

/// A hostile number `v` in one of the mass data of a ready mechanism's links (chosen by `k`).
fn mass<const N: usize>(m: &mut [tmm::mechanism::LinkMass; N], k: usize, v: f64) {
    let lm = &mut m[k % N];
    match k / N % 4 {
        0 => lm.mass = v,
        1 => lm.inertia = v,
        2 => lm.along = v,
        _ => lm.across = v,
    }
}

/// A gear drive with the hostile number `v` in one of its data (chosen by `k`).
fn gear(d: &mut tmm::linkage::Drive, k: usize, v: f64) {
    let (mut r, mut a, mut p) = (0.1, 3.0, 0.35);
    match k % 3 {
        0 => r = v,
        1 => a = v,
        _ => p = v,
    }
    *d = tmm::linkage::Drive::Gear {
        pitch_radius: r,
        pitch_angle: a,
        pressure_angle: p,
    };
}

// The ready mechanisms, one test each (so that they run side by side): `cases()` hostile
// variants of each.

#[test]
fn hostile_four_bars() {
    sweep_mechanism(
        "FourBar",
        &FourBar::course_example(),
        &[
            |m, v| m.o1.x = v,
            |m, v| m.o3.y = v,
            |m, v| m.l1 = v,
            |m, v| m.l2 = v,
            |m, v| m.l3 = v,
            |m, v| m.gravity = v,
            |m, v| m.resisting_moment = v,
            |m, v| mass(&mut m.mass, v.to_bits() as usize, v),
            |m, v| gear(&mut m.drive, v.to_bits() as usize, v),
        ],
        71,
        |m, what, g| {
            ok_finite(&m.linkage(), what);
            if let Ok(gr) = m.grashof() {
                assert!(!has_non_finite(&format!("{gr:?}")), "{what}: {gr:?}");
            }
            mechanism_checks(m.plan(), |r| m.strokes(r), what, g);
        },
    );
}

#[test]
fn hostile_slider_cranks() {
    sweep_mechanism(
        "SliderCrank",
        &SliderCrank::course_example(),
        &[
            |m, v| m.o1.y = v,
            |m, v| m.l1 = v,
            |m, v| m.l2 = v,
            |m, v| m.guide_point.x = v,
            |m, v| m.guide_angle = v,
            |m, v| m.gravity = v,
            |m, v| mass(&mut m.mass, v.to_bits() as usize, v),
            |m, v| {
                if let Some(d) = &mut m.diagram {
                    d.area = v;
                }
            },
            |m, v| {
                if let Some(d) = &mut m.diagram
                    && let Some(p) = d.outward.first_mut()
                {
                    p[(v.to_bits() % 2) as usize] = v;
                }
            },
            |m, v| gear(&mut m.drive, v.to_bits() as usize, v),
        ],
        72,
        |m, what, g| {
            ok_finite(&m.linkage(), what);
            mechanism_checks(m.plan(), |r| m.strokes(r), what, g);
        },
    );
}

#[test]
fn hostile_compressors() {
    sweep_mechanism(
        "Compressor",
        &Compressor::course_example(),
        &[
            |m, v| m.o1.x = v,
            |m, v| m.l1 = v,
            |m, v| m.throw_angle = v,
            |m, v| m.l2 = v,
            |m, v| m.l4 = v,
            |m, v| m.guide_point.y = v,
            |m, v| m.guide_angles[(v.to_bits() % 2) as usize] = v,
            |m, v| m.gravity = v,
            |m, v| mass(&mut m.mass, v.to_bits() as usize, v),
            |m, v| {
                if let Some(d) = &mut m.diagrams[(v.to_bits() % 2) as usize]
                    && let Some(p) = d.inward.last_mut()
                {
                    p[(v.to_bits() / 2 % 2) as usize] = v;
                }
            },
            |m, v| gear(&mut m.drive, v.to_bits() as usize, v),
        ],
        73,
        |m, what, g| {
            ok_finite(&m.linkage(), what);
            mechanism_checks(m.plan(), |r| m.strokes(r), what, g);
        },
    );
}

#[test]
fn hostile_six_bars() {
    sweep_mechanism(
        "SixBar",
        &SixBar::course_example(),
        &[
            |m, v| m.o1.x = v,
            |m, v| m.o2.y = v,
            |m, v| m.l1 = v,
            |m, v| m.l2 = v,
            |m, v| m.l3 = v,
            |m, v| m.c_along = v,
            |m, v| m.c_across = v,
            |m, v| m.l4 = v,
            |m, v| m.guide_point.x = v,
            |m, v| m.guide_angle = v,
            |m, v| m.gravity = v,
            |m, v| m.resistance = v,
            |m, v| m.working_direction = v,
            |m, v| mass(&mut m.mass, v.to_bits() as usize, v),
            |m, v| gear(&mut m.drive, v.to_bits() as usize, v),
        ],
        74,
        |m, what, g| {
            ok_finite(&m.linkage(), what);
            mechanism_checks(m.plan(), |r| m.strokes(r), what, g);
        },
    );
}

#[test]
fn hostile_rocking_cylinders() {
    sweep_mechanism(
        "RockingCylinder",
        &RockingCylinder::course_example(),
        &[
            |m, v| m.o1.y = v,
            |m, v| m.c.x = v,
            |m, v| m.l1 = v,
            |m, v| m.l_piston = v,
            |m, v| m.gravity = v,
            |m, v| m.force_in = v,
            |m, v| m.force_out = v,
            |m, v| mass(&mut m.mass, v.to_bits() as usize, v),
            |m, v| gear(&mut m.drive, v.to_bits() as usize, v),
        ],
        75,
        |m, what, g| {
            ok_finite(&m.linkage(), what);
            mechanism_checks(m.plan(), |r| m.strokes(r), what, g);
        },
    );
}

/// Asserts that `r` is the error of an index out of range: [`Error::OutOfRange`] called `name`
/// over `[0, len − 1]` holding `value`, or, for an empty collection (`len` 0), an
/// [`Error::Description`] naming the index and saying there are none.
#[track_caller]
fn assert_index_error<T: std::fmt::Debug>(
    r: tmm::Result<T>,
    name: &str,
    value: usize,
    len: usize,
    what: &str,
) {
    match r {
        Err(Error::OutOfRange {
            name: n,
            value: v,
            min,
            max,
            ends: Ends::Closed,
        }) if len > 0 => {
            assert_eq!(n, name, "{what}");
            assert_eq!(v, value as f64, "{what}");
            assert_eq!((min, max), (0.0, (len - 1) as f64), "{what}");
            let shown = r_display(n, v, min, max);
            assert!(shown.starts_with(name), "{what}: {shown}");
        }
        Err(Error::Description { item, problem }) if len == 0 => {
            assert_eq!(item, format!("{name} {value}"), "{what}");
            assert!(problem.contains("has no "), "{what}: {problem}");
        }
        other => panic!("{what}: expected an error for {name} {value} of {len}, got {other:?}"),
    }
}

/// The message of an index out of range, as the caller sees it.
fn r_display(name: &'static str, value: f64, min: f64, max: f64) -> String {
    Error::OutOfRange {
        name,
        value,
        min,
        max,
        ends: Ends::Closed,
    }
    .to_string()
}

/// Every accessor by index of `Analysis` and `Plan`: each index in range gives `Ok` with what
/// the accessor by name (or the description) gives, and the indices len, len + 1 and
/// `usize::MAX` give an error naming the index and its range, never a panic.
#[test]
fn index_accessors_check_their_indices() {
    let mut without_points = 0;
    for l in linkages() {
        let plan = Plan::new(&l).unwrap();
        let motions: Vec<Motion> = plan
            .reference_inputs()
            .iter()
            .map(|&q| Motion::new(q, 1.5, -0.5))
            .collect();
        let a = plan
            .analyse(tmm::linkage::Inputs::from_slice(&motions).unwrap())
            .unwrap();
        let (nl, nj, np, ng) = (
            plan.link_names().len(),
            plan.joint_names().len(),
            plan.point_names().len(),
            plan.groups().len(),
        );
        if np == 0 {
            without_points += 1;
        }
        let desc_link = |k: usize| {
            l.links
                .iter()
                .find(|d| d.name == plan.link_names()[k])
                .unwrap_or_else(|| panic!("{}: link {k} not described", l.name))
        };
        // In range: the same as by name.
        for (k, name) in plan.link_names().iter().enumerate() {
            let what = format!("{}: link {name}", l.name);
            let by_name = a.link(name).unwrap();
            assert_eq!(a.link(k).unwrap(), by_name, "{what}");
            let m = a.link_motion(k).unwrap();
            assert_eq!(
                (m.omega, m.epsilon),
                (by_name.rate, by_name.accel),
                "{what}"
            );
            let r = a.residual(k).unwrap();
            if k > 0 {
                assert!(r < 1e-9, "{what}: residual {r:e}");
            }
            let body = a.free_body(k).unwrap();
            let joints = desc_link(k).joints.len();
            assert!(body.len() >= joints, "{what}: {} loads", body.len());
        }
        for (j, name) in plan.joint_names().iter().enumerate() {
            let what = format!("{}: joint {name}", l.name);
            let by_name = a.joint(name).unwrap();
            assert_eq!(a.joint(j).unwrap(), by_name, "{what}");
            assert_eq!(a.reaction(j).unwrap(), a.reaction(name).unwrap(), "{what}");
            // The reaction as a load: equal and opposite on its two links, refused on any
            // other link.
            let re = a.reaction(j).unwrap();
            let [p, q] = plan.joint_links(j).unwrap().map(usize::from);
            let (on_p, on_q) = (re.load_on(p).unwrap(), re.load_on(q).unwrap());
            assert_eq!(on_p.force, -on_q.force, "{what}");
            assert_eq!(on_p.moment, -on_q.moment, "{what}");
            assert!([p, q].contains(&re.on) && [p, q].contains(&re.by), "{what}");
            for k in (0..plan.link_names().len() + 2).filter(|k| ![p, q].contains(k)) {
                assert!(
                    matches!(re.load_on(k), Err(Error::Description { .. })),
                    "{what}: link {k}"
                );
            }
            let prismatic = plan.is_prismatic(j).unwrap();
            assert_eq!(prismatic, a.slide(name).is_ok(), "{what}");
            assert_eq!(plan.guide_link(j).unwrap().is_some(), prismatic, "{what}");
            let d = a.guide_direction(j).unwrap();
            let s = a.slide(j);
            if prismatic {
                assert!((d.norm() - 1.0).abs() < 1e-12, "{what}: {d:?}");
                assert_eq!(s.unwrap(), a.slide(name).unwrap(), "{what}");
            } else {
                assert_eq!(d.norm(), 0.0, "{what}");
                // A hinge has no slide: asked by index or by name, an error naming it.
                assert!(matches!(s, Err(Error::Description { .. })), "{what}");
            }
            let links = plan.joint_links(j).unwrap().map(usize::from);
            for (side, &k) in links.iter().enumerate() {
                assert!(
                    desc_link(k).joints.contains(name),
                    "{what}: side {side} is link {}, which does not list it",
                    plan.link_names()[k]
                );
                let on = a.joint_on(j, k).unwrap();
                // The joint's motion is its point on the sliding link (on the first link of a
                // hinge), to the bit; a hinge's two points coincide.
                let guide = plan.guide_link(j).unwrap();
                if guide.map_or(side == 0, |g| g.index() != k) {
                    assert_eq!(on, by_name, "{what}: side {side}");
                }
                let gap = (on.p - by_name.p).norm();
                assert!(prismatic || gap <= 1e-9 * plan.size(), "{what}: {gap:e}");
            }
            // A link in range that the joint does not join: named by both names.
            for k in (0..nl).filter(|k| !links.contains(k)) {
                match a.joint_on(j, k) {
                    Err(Error::Description { item, problem }) => {
                        assert_eq!(item, format!("joint {name}"), "{what}");
                        let link = &plan.link_names()[k];
                        assert!(
                            problem.contains(&format!("link {link}")),
                            "{what}: {problem}"
                        );
                    }
                    other => panic!("{what}: link {k}: {other:?}"),
                }
            }
            for k in [nl, nl + 1, usize::MAX] {
                assert_index_error(a.joint_on(j, k), "link index", k, nl, &what);
            }
        }
        for (k, name) in plan.point_names().iter().enumerate() {
            let what = format!("{}: point {name}", l.name);
            assert_eq!(a.point(k).unwrap(), a.point(name).unwrap(), "{what}");
            let (link, local) = plan.point_local(k).unwrap();
            let link = link.index();
            assert!(
                desc_link(link).points.iter().any(|p| &p.name == name),
                "{what}: on link {}",
                plan.link_names()[link]
            );
            let p = a.link_motion(link).unwrap().point_at(local.x, local.y).p;
            let gap = (p - a.point(name).unwrap().p).norm();
            assert!(gap <= 1e-9 * plan.size(), "{what}: {gap:e}");
        }
        for g in 0..ng {
            if plan.groups()[g].kind == tmm::linkage::GroupKind::General {
                // Not defined above the 3rd class: an error, not a number.
                let e = a.transmission_angle(g).unwrap_err().to_string();
                assert!(e.contains("3rd class"), "{e}");
                continue;
            }
            let mu = a.transmission_angle(g).unwrap();
            assert!(
                (0.0..=std::f64::consts::FRAC_PI_2).contains(&mu),
                "{}: {mu}",
                l.name
            );
        }
        // Out of range: an error naming the index, for every accessor.
        for i in [0, 1, usize::MAX] {
            let what = |f: &str, k: usize| format!("{}: {f}({k})", l.name);
            let k = nl.saturating_add(i);
            assert_index_error(
                a.link_motion(k),
                "link index",
                k,
                nl,
                &what("link_motion", k),
            );
            let w = what("link_angle_index", k);
            assert_index_error(a.link(k), "link index", k, nl, &w);
            assert_index_error(a.residual(k), "link index", k, nl, &what("residual", k));
            assert_index_error(a.free_body(k), "link index", k, nl, &what("free_body", k));
            let k = nj.saturating_add(i);
            let joint_index = |r, f: &str| assert_index_error(r, "joint index", k, nj, &what(f, k));
            joint_index(a.joint(k).map(|_| ()), "joint_motion");
            joint_index(a.joint_on(k, 0).map(|_| ()), "joint_on");
            joint_index(a.joint_on(k, 1).map(|_| ()), "joint_on");
            joint_index(a.joint_on(k, 0).map(|_| ()), "joint_index_on");
            joint_index(a.guide_direction(k).map(|_| ()), "guide_direction");
            joint_index(a.slide(k).map(|_| ()), "slide_index");
            joint_index(a.reaction(k).map(|_| ()), "reaction_index");
            joint_index(plan.is_prismatic(k).map(|_| ()), "is_prismatic");
            joint_index(plan.joint_links(k).map(|_| ()), "joint_links");
            joint_index(plan.guide_link(k).map(|_| ()), "guide_link");
            let k = np.saturating_add(i);
            assert_index_error(a.point(k), "point index", k, np, &what("point_motion", k));
            assert_index_error(
                plan.point_local(k),
                "point index",
                k,
                np,
                &what("point_local", k),
            );
            let k = ng.saturating_add(i);
            let w = what("transmission_angle", k);
            assert_index_error(a.transmission_angle(k), "group index", k, ng, &w);
            let w = what("min_transmission_angle", k);
            assert_index_error(plan.min_transmission_angle(k), "group index", k, ng, &w);
        }
    }
    assert!(
        without_points > 0,
        "no linkage without named points was tried"
    );
}

/// A solver belongs to the plan that made it (`plan.solver()`): one plan's buffers cannot be
/// handed to another, so the mistake `Plan::analyse_into` had to refuse at run time cannot be
/// written. A copy's solver solves the copy, to the bit of the original's one-shot analysis.
#[test]
fn a_solver_solves_the_plan_that_made_it() {
    let four = Plan::new(&bundled::four_bar()).unwrap();
    let input = Motion::new(four.reference_input(), 10.0, 0.0);
    let copy = four.clone();
    let mut solver = copy.solver();
    assert!(std::ptr::eq(solver.plan(), &copy));
    let b = solver.analyse(input).unwrap().balances()[0];
    let direct = four.analyse(input).unwrap();
    assert_eq!(b, direct.balances()[0]);
}

/// Inputs of a cycle: `try_uniform_inputs` refuses what has no positions and names it; what
/// it gives is what `uniform_inputs` gives, n positions a step of 2π/n apart in the sense of
/// ω1, each at the asked speed and acceleration.
#[test]
fn cycle_inputs_refuse_what_has_no_positions() {
    use std::f64::consts::TAU;
    let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
    for x in bad {
        for (args, name) in [
            ((x, 1.0, 0.0), "start angle"),
            ((0.0, x, 0.0), "input speed omega1"),
            ((0.0, 1.0, x), "input acceleration epsilon1"),
        ] {
            match try_uniform_inputs(12, args.0, args.1, args.2) {
                Err(Error::NonFinite { name: n, .. }) => assert_eq!(n, name),
                other => panic!("{args:?}: {other:?}"),
            }
            assert!(uniform_inputs(12, args.0, args.1, args.2).is_empty());
        }
    }
    for n in [0, (1 << 24) + 1, usize::MAX] {
        assert!(matches!(
            try_uniform_inputs(n, 0.0, 1.0, 0.0),
            Err(Error::OutOfRange { .. })
        ));
    }
    for (n, start, w) in [
        (1, 0.3, 2.0),
        (7, -1.0, -3.0),
        (12, 100.0, 1e300),
        (5, 0.0, 0.0),
    ] {
        let m = try_uniform_inputs(n, start, w, 0.5).unwrap();
        assert_eq!(m, uniform_inputs(n, start, w, 0.5));
        assert_eq!(m.len(), n);
        let sense = if w < 0.0 { -1.0 } else { 1.0 };
        for (k, p) in m.iter().enumerate() {
            assert!((p.rate, p.accel) == (w, 0.5));
            // Angle k is start + k·(±2π/n), modulo a turn.
            let d = (p.value - start - sense * k as f64 * TAU / n as f64).rem_euclid(TAU);
            assert!(d.min(TAU - d) < 1e-12, "n = {n}, k = {k}: {}", p.value);
        }
    }
    // The course inputs, by the strokes of the shaper's ram, turning clockwise: 12 plans from
    // the start of the working stroke, the speed's sign that of the rotation.
    let plan = Plan::new(&bundled::shaper()).unwrap();
    let strokes = plan
        .strokes(&Output::Slide("Q".into()), Rotation::Cw)
        .unwrap();
    let c = try_course_inputs(&strokes, 12, 10.0).unwrap();
    assert_eq!(c.len(), 12);
    assert!(c.iter().all(|m| m.rate == -10.0 && m.accel == 0.0));
    let d = (c[0].value - strokes.start).rem_euclid(TAU);
    assert!(d.min(TAU - d) < 1e-12);
    assert!(matches!(
        try_course_inputs(&strokes, 12, f64::NAN),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        try_course_inputs(&strokes, 0, 1.0),
        Err(Error::OutOfRange { .. })
    ));
}

#[test]
fn planning_work_grows_linearly_whatever_the_order() {
    // Description files of up to 10⁴ joints, their joints and links in a random order and
    // last-first: the decomposition's work (adjacency entries visited, queue operations)
    // against the number of joints, fitted over the sizes.
    let mut g = Gen::new(91);
    for reversed in [false, true] {
        let mut points = Vec::new();
        for dyads in [10, 33, 100, 333, 1000, 3333] {
            let (l, _, _) = random_linkage(dyads, &mut g, reversed, false);
            let text = l.to_json().unwrap();
            let l = Linkage::from_json(&text).unwrap();
            let work = Plan::decomposition_work(&l).unwrap();
            let size = (l.joints.len() + l.links.len()) as f64;
            assert!(work as f64 <= 12.0 * size, "{}: work {work}", l.name);
            points.push((l.joints.len() as f64, work as f64));
        }
        let exponent = fitted_exponent(&points);
        assert!(
            exponent <= 1.2,
            "reversed {reversed}: exponent {exponent}, {points:?}"
        );
    }
    // The plans themselves are made, whatever the order, with one group per dyad (or, for
    // a chain that holds a dyad near its dead point, refused for a reference pose that
    // closes only to its conditioning).
    let mut made = 0;
    for case in 0..4 {
        let (l, _, _) = random_linkage(200, &mut g, case % 2 == 1, false);
        match Plan::new(&l) {
            Ok(plan) => {
                assert_eq!(plan.groups().len(), 200);
                made += 1;
            }
            Err(e) => assert!(
                e.to_string().contains("the reference pose does not close"),
                "{}: {e}",
                l.name
            ),
        }
    }
    assert!(made >= 2, "{made} of 4 plans made");
}

/// An `Ok` plan holds only finite numbers: its link data (centres of mass, sizes), joints,
/// points and loads.
fn check_plan(plan: &Plan, what: &str) {
    let shown = format!("{plan:?}");
    assert!(!has_non_finite(&shown), "{what}: the plan holds {shown}");
}

#[test]
fn plans_with_overflowing_centres_or_sizes_are_errors() {
    // Centres of mass and joints far out: the plan is an error naming the link or joint, or
    // it is finite.
    let far = [1e154, -1e154, 1e300, 1.7e308, -1.7e308, f64::MAX, 1e200];
    let mut plans = 0;
    for (k, &x) in far.iter().enumerate() {
        let mut m = FourBar::course_example();
        m.mass[k % 3].along = x;
        m.mass[(k + 1) % 3].across = -x;
        match m.plan() {
            Ok(p) => {
                plans += 1;
                check_plan(&p, &format!("four-bar, centre at {x}"));
            }
            Err(e) => assert!(
                matches!(&e, Error::Description { item, .. } if item.starts_with("link ")),
                "{x}: {e}"
            ),
        }
        let mut m = FourBar::course_example();
        m.o3.x = x;
        if let Ok(p) = m.plan() {
            check_plan(&p, &format!("four-bar, O3 at {x}"));
        }
        for l in linkages() {
            let mut l = l.clone();
            for link in &mut l.links {
                if let Some(mass) = &mut link.mass {
                    mass.centre = At::Coords([x, -x]);
                }
                if let Some(p) = link.points.first_mut() {
                    p.at = [-x, x];
                }
            }
            if let Ok(p) = Plan::new(&l) {
                check_plan(&p, &format!("{} with centres at {x}", l.name));
            }
        }
    }
    assert!(plans > 0);
}

#[test]
fn checks_of_an_ok_analysis_are_finite() {
    // Joints at 10³³ m (and beyond): an analysis is an error or its residuals are finite.
    for scale in [1e33, 1e100, 1e150, 1e152, 1e153, 1e154, 1e-150] {
        for l in linkages() {
            let mut l = l.clone();
            for j in &mut l.joints {
                j.at = [j.at[0] * scale, j.at[1] * scale];
            }
            for link in &mut l.links {
                for p in &mut link.points {
                    p.at = [p.at[0] * scale, p.at[1] * scale];
                }
                if let Some(m) = &mut link.mass
                    && let At::Coords(c) = &mut m.centre
                {
                    *c = [c[0] * scale, c[1] * scale];
                }
            }
            let Ok(plan) = Plan::new(&l) else { continue };
            check_plan(&plan, &l.name);
            for k in 0..6 {
                let input = Motion::new(plan.reference_input() + f64::from(k), 7.0, 3.0);
                let what = format!("{} scaled by {scale} at {input:?}", l.name);
                check_position(&plan, input, &what);
                if let Ok(a) = plan.analyse(input) {
                    for k in 0..plan.link_names().len() {
                        let r = a.residual(k).unwrap();
                        assert!(r.is_finite(), "{what}: link {k} residual {r}");
                    }
                }
            }
        }
    }
}

#[test]
fn a_load_function_that_returns_nan_or_huge_loads() {
    use nalgebra::{Point2, Vector2};
    let base = Plan::new(&bundled::four_bar()).unwrap();
    let input = Motion::new(base.reference_input() + 0.5, 10.0, 0.0);
    for (k, (force, at)) in [
        (f64::NAN, 0.0),
        (1.0, f64::NAN),
        (f64::INFINITY, 0.0),
        (1e300, 0.0),
        (1e300, 1e300),
        (f64::MAX, -f64::MAX),
        (1.0, 1e300),
    ]
    .into_iter()
    .enumerate()
    {
        let mut plan = base.clone();
        plan.add_load_fn("coupler", move |_| {
            Ok(tmm::Load::new(
                Point2::new(at, 0.0),
                Vector2::new(force, -force),
                force,
            ))
        })
        .unwrap();
        match plan.analyse(input) {
            Ok(_) => {
                assert!(force.is_finite() && at.is_finite(), "case {k}");
                check_position(&plan, input, &format!("load fn case {k}"));
            }
            Err(e) => {
                let s = e.to_string();
                if !(force.is_finite() && at.is_finite()) {
                    assert!(s.contains("coupler") && s.contains("load"), "case {k}: {s}");
                }
            }
        }
    }
}

// The sweeps of what the last sessions added (springs, joint friction, triads, two inputs).
mod added;
