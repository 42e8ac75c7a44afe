//! The adapter's part for linkages with two inputs (a five-bar robot): the inputs of a
//! picture, the path of the plan and the animation in the plane of the inputs, the workspace
//! of a point, and the mass matrix over a grid of the inputs.

use std::f64::consts::PI;

use tmm::draw::{self, Diagram, Style};
use tmm::dynamics::machines::LinearMotor;
use tmm::dynamics::{run, LagrangeSystem, Outcome, Rk4, RunOptions, RunResult, State};
use tmm::kinematics::{assembly_range, Motion};
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{Inputs, Output, TwoInputCourse, TwoInputShape, WorkspaceOptions};

use super::{failure, Machine};

/// The most RK4 steps a run of two inputs may take (a recorded row each); fewer for a
/// linkage whose solve weighs more (see [`Machine::run_steps_budget`]).
const MAX_RUN_STEPS: f64 = 1e6;
use crate::budget;
use crate::model::{
    typed, DiagramKind, DynamicsRequest, Failure, HeldInput, HeldLoads, MassRow, Range,
    TwoInputDynamics, TwoInputRun,
};
use tmm::nalgebra::Vector2;

/// The nodes of the input grid of a workspace along each input (the library's default).
pub const WORKSPACE_SAMPLES: usize = 181;

impl Machine {
    /// Whether input `k` (0 or 1) is a crank (its coordinates in degrees at the command line).
    fn is_crank(&self, k: usize) -> bool {
        if k == 0 {
            self.plan.input_is_crank()
        } else {
            self.second_is_crank()
        }
    }

    /// A coordinate of input `k` as typed after `option` (degrees for a crank, m for a
    /// slider) in rad or m; an angle beyond ±[`MAX_ANGLE`](super::MAX_ANGLE) is refused.
    fn coordinate(&self, option: &str, k: usize, typed: f64) -> Result<f64, Failure> {
        super::typed_coordinate(option, self.is_crank(k), typed)
    }

    /// The inputs of a picture at one position: one coordinate per input as typed, or the
    /// reference pose for none; every input moving at `speed`.
    pub(super) fn inputs_at(
        &self,
        option: &str,
        typed: &[f64],
        speed: f64,
    ) -> Result<Inputs, Failure> {
        super::check_speed(speed)?;
        let n = self.plan.input_count();
        let reference = self.plan.reference_inputs();
        let value = |k: usize| match typed.get(k) {
            Some(&v) => self.coordinate(option, k, v),
            None => Ok(reference[k]),
        };
        if !typed.is_empty() && typed.len() != n {
            return Err(Failure::new(format!(
                "a position of this linkage is {} (one coordinate per input), and {} {} given",
                if n == 2 {
                    "a pair φ1 φ2"
                } else {
                    "one value φ"
                },
                typed.len(),
                if typed.len() == 1 { "was" } else { "were" }
            ))
            .hint(if n == 2 {
                format!("give both inputs, for example {option} 120 60 (degrees for a crank)")
            } else {
                "give the input's angle in degrees (metres for a slider)".to_owned()
            }));
        }
        let one = |k: usize| Ok::<_, Failure>(Motion::new(value(k)?, speed, 0.0));
        Ok(if n == 2 {
            Inputs::two(one(0)?, one(1)?)
        } else {
            Inputs::one(one(0)?)
        })
    }

    /// Each input's range with the other fixed at its reference value: a crank's full turn
    /// or its lock angles (the library's assembly range, followed from the reference pose), a
    /// slider's travel.
    pub(super) fn input_ranges(&self) -> Vec<Range> {
        let plan = &self.plan;
        let r = plan.reference_inputs();
        (0..2)
            .map(|k| {
                let at = |x: f64| {
                    let mut q = [Motion::fixed(r[0]), Motion::fixed(r[1])];
                    q[k] = Motion::fixed(x);
                    Inputs::two(q[0], q[1])
                };
                if !self.is_crank(k) {
                    return super::travel(plan.size(), r[k], |s| plan.kinematics(at(s)).is_ok());
                }
                let mut solver = plan.solver();
                match assembly_range(r[k], |x| solver.kinematics(at(x)).map(|_| ())) {
                    Ok(None) => Range::FullTurn,
                    Ok(Some((a, b))) => Range::Rocking(a.min(b), a.max(b)),
                    Err(e) => Range::Unknown(e.to_string()),
                }
            })
            .collect()
    }

    /// The path of a linkage with two inputs for the plan (`n` = 12 positions) and the
    /// animation: through the pairs `along` (as typed) by straight steps in the plane of the
    /// inputs, `n` positions equally spaced along it by its length there (both ends
    /// included); without pairs, the library's loop about the reference pose.
    pub(super) fn two_input_path(
        &self,
        along: &[f64],
        n: usize,
        speed: f64,
    ) -> Result<TwoInputCourse, Failure> {
        super::check_speed(speed)?;
        if along.is_empty() {
            return TwoInputCourse::around_reference(&self.plan, n, speed).map_err(|e| failure(&e));
        }
        if !along.len().is_multiple_of(2) || along.len() < 4 {
            return Err(Failure::new(format!(
                "--along takes pairs of input coordinates (φ1 φ2), at least two pairs, and \
                 {} value(s) were given",
                along.len()
            )));
        }
        let points: Vec<[f64; 2]> = along
            .chunks(2)
            .map(|p| {
                Ok([
                    self.coordinate("--along", 0, p[0])?,
                    self.coordinate("--along", 1, p[1])?,
                ])
            })
            .collect::<Result<_, Failure>>()?;
        let lengths: Vec<f64> = points
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .collect();
        let total: f64 = lengths.iter().sum();
        if !(total.is_finite() && total > 0.0) {
            return Err(Failure::new(format!(
                "the path given by --along has length {} in the plane of the inputs; it \
                 needs two different finite pairs",
                typed(total)
            )));
        }
        // Each position at its arc length s along the polyline; the inputs' rates are the
        // path's direction there times |speed| (the pictures need positions only).
        let mut inputs = Vec::with_capacity(n);
        for i in 0..n {
            #[allow(clippy::cast_precision_loss)]
            let mut s = total * i as f64 / (n - 1).max(1) as f64;
            let mut seg = 0;
            while seg + 1 < lengths.len() && s > lengths[seg] {
                s -= lengths[seg];
                seg += 1;
            }
            let (a, b, l) = (points[seg], points[seg + 1], lengths[seg]);
            let t = if l > 0.0 { (s / l).min(1.0) } else { 0.0 };
            let d = if l > 0.0 {
                [(b[0] - a[0]) / l, (b[1] - a[1]) / l]
            } else {
                [0.0, 0.0]
            };
            let at = |k: usize| Motion::new(a[k] + (b[k] - a[k]) * t, speed.abs() * d[k], 0.0);
            inputs.push(Inputs::two(at(0), at(1)));
        }
        let course = TwoInputCourse {
            inputs,
            shape: TwoInputShape::Path,
        };
        course.check().map_err(|e| failure(&e))?;
        Ok(course)
    }

    /// The plan of a linkage with two inputs along its path, with the paths of the joints
    /// off the frame and the named points.
    pub(super) fn plan_two(
        &self,
        along: &[f64],
        speed: f64,
        paths: &[&str],
        style: &Style,
    ) -> Result<String, Failure> {
        let course = self.two_input_path(along, 12, speed)?;
        draw::plan_view_two(&self.plan, &course, paths, style)
            .map(|p| p.svg)
            .map_err(|e| failure(&e))
    }

    /// An animation of a linkage with two inputs along its path: 180 frames there (and back
    /// again for a path given by `along`, so the animation loops without a jump).
    pub(super) fn animation_two(
        &self,
        along: &[f64],
        speed: f64,
        style: &Style,
    ) -> Result<String, Failure> {
        let mut frames = self.two_input_path(along, 180, speed)?.inputs;
        if !along.is_empty() {
            let back: Vec<Inputs> = frames.iter().rev().skip(1).copied().collect();
            frames.extend(back);
        }
        draw::animation_path(&self.plan, &frames, 4.0, style)
            .map(|p| p.svg)
            .map_err(|e| failure(&e))
    }

    /// A diagram of a linkage with two inputs along its path (180 positions; the loop about
    /// the reference pose, or the path through the pairs of `along`): both balancing moments,
    /// the motion of the described output (without one, the x of the first joint on no input
    /// link and off the frame, the end point of a five-bar), the reactions, or the hodograph
    /// of the first crank's pin.
    pub(super) fn diagram_two(
        &self,
        kind: DiagramKind,
        along: &[f64],
        speed: f64,
    ) -> Result<String, Failure> {
        let style = Style::default();
        let tall = Style {
            height: 900,
            ..Style::default()
        };
        let (diagram, style) = match kind {
            DiagramKind::Kinematics => (Diagram::Kinematics(self.output_two()), &tall),
            DiagramKind::Transfer => {
                return Err(Failure::new(
                    "a transfer function is a derivative with respect to one input, and this \
                     linkage has two",
                )
                .hint("`--diagram kinematics` draws an output's motion along the path"));
            }
            DiagramKind::Balance => (Diagram::Balance, &style),
            DiagramKind::Reactions => (Diagram::Reactions, &style),
            DiagramKind::Hodograph => (Diagram::Hodograph(self.crank_pin()?), &style),
        };
        let course = self.two_input_path(along, 180, speed)?;
        draw::diagram_two(&self.plan, &course, &diagram, style)
            .map(|c| c.svg)
            .map_err(|e| failure(&e))
    }

    /// The output of a diagram of a linkage with two inputs: the described one, or the x of
    /// the first joint on no input link and off the frame (the last link's angle without one).
    fn output_two(&self) -> Output {
        if let Some(o) = &self.linkage.output {
            return o.clone();
        }
        match self.plan.end_joint() {
            Some(j) => Output::X(j.to_owned()),
            None => self.plan.output_or_last(None),
        }
    }

    /// The workspace of the joint or named point `point`: the region it reaches as both
    /// inputs move (each crank over a whole turn), its outline and the singular curves.
    pub(super) fn workspace(
        &self,
        point: &str,
        style: &Style,
        progress: &mut dyn FnMut(&str),
    ) -> Result<String, Failure> {
        let n = self.plan.input_count();
        if n != 2 {
            return Err(Failure::new(format!(
                "a workspace is the region a point reaches as two inputs move independently, \
                 and this linkage has {n} input, along which {point} only traces a path"
            ))
            .hint("`tmm draw FILE --plan` draws the paths of the joints and named points"));
        }
        if !(self.is_crank(0) && self.is_crank(1)) {
            return Err(Failure::new(
                "the workspace of a linkage with a slider input needs the slider's range, \
                 which the command line does not take yet; both inputs must be cranks",
            ));
        }
        #[allow(clippy::cast_precision_loss)]
        budget::check(
            (WORKSPACE_SAMPLES * WORKSPACE_SAMPLES) as f64,
            self.solve_weight(),
            &format!("the workspace ({WORKSPACE_SAMPLES} × {WORKSPACE_SAMPLES} input pairs)"),
            "draw the linkage at chosen input pairs with --scheme φ1 φ2 instead",
        )?;
        progress(&format!(
            "the workspace of {point} ({WORKSPACE_SAMPLES} × {WORKSPACE_SAMPLES} input pairs)"
        ));
        let options = WorkspaceOptions::default().with_samples(WORKSPACE_SAMPLES);
        let ws = self.plan.workspace(point, &options).map_err(|e| {
            let plan = &self.plan;
            let names: Vec<&str> = plan
                .joint_names()
                .iter()
                .chain(plan.point_names())
                .map(String::as_str)
                .collect();
            failure(&e).hint(format!(
                "--workspace takes a joint or a named point: {}",
                names.join(", ")
            ))
        })?;
        draw::workspace(&self.plan, &ws, style)
            .map(|p| p.svg)
            .map_err(|e| failure(&e))
    }

    /// The most RK4 steps a run of two inputs may take: [`MAX_RUN_STEPS`], or fewer where a
    /// step's 4 evaluations would take the run above [`budget::MAX_WORK`] — a count from
    /// the description alone.
    fn run_steps_budget(&self) -> f64 {
        MAX_RUN_STEPS
            .min(budget::most_solves(self.solve_weight()) / 4.0)
            .floor()
    }

    /// The mass matrix A(q) and the loads' generalized forces at rest Q(q) of a linkage with
    /// two inputs over a grid of `n` × `n` input pairs about the reference pose, each input
    /// over ± `span` (as typed; 30° for a crank, a tenth of the size for a slider), with
    /// `rotor` (kg·m² or kg) added on the first input.
    ///
    /// # Errors
    /// A grid of fewer than 2 nodes a side; a span that is not positive and finite; no node
    /// of the grid assembles.
    pub(super) fn mass_matrix_grid(
        &self,
        n: usize,
        span: Option<f64>,
        rotor: f64,
        progress: &mut dyn FnMut(&str),
    ) -> Result<TwoInputDynamics, Failure> {
        let reference = self.plan.reference_inputs();
        let half = |k: usize| match span {
            // Checked below: positive, finite and at most half a turn.
            Some(v) if self.is_crank(k) => v.to_radians(),
            Some(v) => v,
            None if self.is_crank(k) => 30f64.to_radians(),
            None => 0.1 * self.plan.size(),
        };
        let halves = [half(0), half(1)];
        if let Some(bad) = halves.iter().find(|h| !(h.is_finite() && **h > 0.0)) {
            return Err(Failure::new(format!(
                "the span of the grid must be positive and finite, and it is {}",
                typed(span.unwrap_or(*bad))
            ))
            .hint("give --span in degrees (metres for a slider input)"));
        }
        if let Some(k) = (0..2).find(|&k| self.is_crank(k) && halves[k] > PI) {
            return Err(Failure::new(format!(
                "the span of the grid about crank {}'s reference angle is at most 180° (a \
                 whole turn), and it is {}°",
                k + 1,
                typed(span.unwrap_or_else(|| halves[k].to_degrees()))
            )));
        }
        let ranges = [0, 1].map(|k| [reference[k] - halves[k], reference[k] + halves[k]]);
        let sys = LinkageSystem::new(self.plan.clone())
            .and_then(|s| s.with_inertia(0, rotor))
            .map_err(|e| failure(&e))?;
        let weight = self.solve_weight();
        #[allow(clippy::cast_precision_loss)]
        budget::check(
            (n * n) as f64,
            weight,
            &format!("--grid {n} ({n} × {n} input pairs)"),
            &format!(
                "give --grid N with N² at most {:.0}",
                budget::most_solves(weight)
            ),
        )?;
        let mut rows = Vec::with_capacity(n * n);
        let mut skipped = 0;
        #[allow(clippy::cast_precision_loss)]
        let at = |r: [f64; 2], i: usize| r[0] + (r[1] - r[0]) * i as f64 / (n - 1) as f64;
        for i in 0..n {
            progress(&format!(
                "the mass matrix over {n} × {n} input pairs, row {} of {n}",
                i + 1
            ));
            for j in 0..n {
                let q = Vector2::new(at(ranges[0], i), at(ranges[1], j));
                match sys.split_terms(&q, &Vector2::zeros()) {
                    Ok(t) => rows.push(MassRow {
                        q: [q[0], q[1]],
                        a: [t.inertia[(0, 0)], t.inertia[(0, 1)], t.inertia[(1, 1)]],
                        loads: [t.loads[0], t.loads[1]],
                    }),
                    Err(_) => skipped += 1,
                }
            }
        }
        if rows.is_empty() {
            return Err(Failure::new(format!(
                "the linkage assembles at no node of the {n} × {n} grid about its reference pose"
            ))
            .hint("give a smaller --span"));
        }
        let unit = |k: usize| if self.is_crank(k) { "rad" } else { "m" };
        Ok(TwoInputDynamics {
            name: self.name().to_owned(),
            units: [unit(0), unit(1)],
            ranges,
            n,
            rows,
            skipped,
            run: None,
        })
    }

    /// The linkage with two inputs run from rest in its reference pose for `t_end` seconds
    /// under the motors of `request` (M = a − b·q̇ on each input, none where not given) and
    /// its loads, by RK4 with every step recorded.
    ///
    /// # Errors
    /// A duration outside [10⁻⁶, 10⁴] s; the run's error (a
    /// position that does not assemble or is singular, named with its time; the budget).
    pub(super) fn run_two(
        &self,
        request: &DynamicsRequest,
        t_end: f64,
        progress: &mut dyn FnMut(&str),
    ) -> Result<TwoInputRun, Failure> {
        // Below a microsecond nothing a linkage does can be seen in the rows (and the steps
        // would be far below the integrator's resolution of the time).
        if !(t_end.is_finite() && (1e-6..=1e4).contains(&t_end)) {
            return Err(Failure::new(format!(
                "the duration of the run must be between 10⁻⁶ s and 10⁴ s, and it is {} s",
                typed(t_end)
            ))
            .hint("give --run T in seconds"));
        }
        let f = |e: tmm::Error| failure(&e);
        let motors = [request.motor, request.motor2].map(|m| m.unwrap_or((0.0, 0.0)));
        let mut sys = LinkageSystem::new(self.plan.clone())
            .and_then(|s| s.with_inertia(0, request.rotor))
            .map_err(f)?;
        for (k, m) in [request.motor, request.motor2].into_iter().enumerate() {
            if let Some((a, b)) = m {
                sys = sys
                    .with_motor(k, Motor::Linear(LinearMotor { a, b }))
                    .map_err(f)?;
            }
        }
        let reference = self.plan.reference_inputs();
        let q0 = Vector2::new(reference[0], reference[1]);
        // 4000 steps at most, and RK4 well inside its stability limit (hλ ≈ −2.785) for the
        // motors' damping b/A at the start.
        let a0 = sys.inertia(&q0).map_err(f)?;
        let damping = (motors[0].1.abs() / a0[(0, 0)]).max(motors[1].1.abs() / a0[(1, 1)]);
        let h = (t_end / 4000.0).min(0.5 / damping.max(f64::MIN_POSITIVE));
        // A damping so strong that RK4's stable step is tiny makes the run stiff: refuse it
        // at once, naming the motor, rather than after a long run that spends its budget.
        let steps = t_end / h;
        let allowed = self.run_steps_budget();
        if steps.is_nan() || steps > allowed {
            // A damping of 10³⁰⁸ makes the stable step underflow: no `0e0 s`, no `inf steps`.
            let step = if h > 0.0 {
                format!("steps of {h:.3e} s or shorter")
            } else {
                "steps shorter than the least double".to_owned()
            };
            return Err(Failure::new(format!(
                "the motors' damping b = {} and {} N·m·s/rad make the run stiff: RK4 needs \
                 {step}, {} steps for {t_end:e} s, above the {allowed:e} allowed",
                crate::model::typed(motors[0].1),
                crate::model::typed(motors[1].1),
                crate::model::many(steps)
            ))
            .hint("give --motor / --motor2 a smaller b, or a shorter --run T"));
        }
        let mut opts = RunOptions::until(t_end, h);
        opts.record_every = 1;
        progress(&format!(
            "a run of {t_end} s from rest (RK4, h = {h:.3e} s)"
        ));
        // The run's own error (a pose beyond reach, a state that overflows) says what
        // happened; the options that set the run are what to change.
        let r = run(&sys, &Rk4, State::at_rest(q0), &opts).map_err(|e| {
            failure(&e).hint(
                "the run from rest under --motor and --motor2: give a shorter --run T, or \
                 motors that hold the linkage within its reach",
            )
        })?;
        // A stop that holds for good ends the rows early: say so, not just print fewer rows.
        let stopped = match &r.outcome {
            // A resistance (on a link or a slide: it stops with both inputs' rates) held
            // while an input still moves is where the run ends, not a rest. (An input held by
            // its own joint's friction is not an end: the run goes on, see `held_inputs`.)
            Outcome::Stuck { t, loads, switch } => {
                let moving: Vec<String> = (0..2)
                    .filter(|&k| r.last.qd[k] != 0.0)
                    .map(|k| format!("input {} at {:.4e} rad/s", k + 1, r.last.qd[k]))
                    .collect();
                Some(if moving.is_empty() {
                    loads.stalled(*t).to_string()
                } else {
                    format!(
                        "{}; the run ends there (switch {switch} held), with {} still moving: \
                         a motion with that resistance held is not modelled",
                        loads.stalled(*t),
                        moving.join(" and ")
                    )
                })
            }
            Outcome::DeadCentre { t, dyad, value } => Some(format!(
                "the linkage reaches a dead centre at t = {t:.6} s: {} has |det| = {:.3e} (at \
                 most 1e-3), where its inputs no longer describe the motion",
                self.plan
                    .groups()
                    .get(*dyad)
                    .map_or("?", |g| g.name.as_str()),
                value.abs()
            )),
            Outcome::Jammed { t, joint, value } => {
                let name = self.plan.joint_names().get(*joint);
                Some(format!(
                    "the linkage jams at t = {t:.6} s: joint {} self-locks, \
                     det(I - J) = {value:.3e}",
                    name.map_or("?", String::as_str)
                ))
            }
            _ => None,
        };
        let held = held_inputs(&sys, &r);
        let tr = &r.trajectory;
        let (t, q, qd) = (tr.t(), tr.q(), tr.qd());
        let (kinetic, power, lost) = (tr.kinetic(), tr.power_applied(), tr.power_dissipated());
        let rows: Vec<[f64; 7]> = (0..tr.len())
            .map(|i| {
                let p = power[i] - lost[i];
                [t[i], q[0][i], q[1][i], qd[0][i], qd[1][i], kinetic[i], p]
            })
            .collect();
        // The work of the applied loads less the dampers' losses, which the kinetic energy
        // gained from rest must equal: trapezoids over the recorded steps, an error of
        // order h².
        let work = rows
            .windows(2)
            .map(|w| 0.5 * (w[0][6] + w[1][6]) * (w[1][0] - w[0][0]))
            .sum();
        Ok(TwoInputRun {
            motors,
            step: h,
            steps: r.steps,
            evaluations: r.evaluations,
            rows,
            work,
            stopped,
            held,
        })
    }
}

/// The stretches of a two-input run where an input's own joint friction held it at rest
/// while the other moved ([`LagrangeSystem::switch_holds`]): the run sets a held input's rate
/// to an exact zero, so a hold is two or more rows running with that rate 0.0 (a start from
/// rest has one such row for an input that breaks away). Each is weighed by the system's own
/// [`LagrangeSystem::switch_loads`] (the load the held motion puts on the input against the
/// friction its joint can hold) at the first and last of its rows where the other input
/// moves; a hold whose other input never moves is left out (the run then ends stuck, and
/// says so).
fn held_inputs(sys: &LinkageSystem, r: &RunResult) -> Vec<HeldInput> {
    let tr = &r.trajectory;
    let (t, q, qd) = (tr.t(), tr.q(), tr.qd());
    let n = t.len();
    let mut held = Vec::new();
    for i in 0..sys.switches() {
        let Some(k) = sys.switch_holds(i).filter(|&k| k < 2) else {
            continue;
        };
        let mut a = 0;
        while a < n {
            if qd[k][a] != 0.0 {
                a += 1;
                continue;
            }
            let mut b = a;
            while b + 1 < n && qd[k][b + 1] == 0.0 {
                b += 1;
            }
            let moving: Vec<usize> = (a..=b).filter(|&j| qd[1 - k][j] != 0.0).collect();
            if let (true, Some(&first), Some(&last)) = (b > a, moving.first(), moving.last()) {
                let weigh = |j: usize| {
                    let (qj, qdj) = (
                        Vector2::new(q[0][j], q[1][j]),
                        Vector2::new(qd[0][j], qd[1][j]),
                    );
                    sys.switch_loads(i, t[j], &qj, &qdj)
                };
                // The run went through these rows, so their loads are there to weigh; should
                // one fail, the hold is still reported, without them.
                let loads = match (weigh(first), weigh(last)) {
                    (Ok(l0), Ok(l1)) => Some(HeldLoads {
                        weighed: [t[first], t[last]],
                        drive: [l0.drive, l1.drive],
                        breakaway: [l0.breakaway(), l1.breakaway()],
                        unit: l0.unit,
                    }),
                    _ => None,
                };
                held.push(HeldInput {
                    input: k + 1,
                    at: q[k][a],
                    from: t[a],
                    until: t[b],
                    released: b + 1 < n,
                    loads,
                });
            }
            a = b + 1;
        }
    }
    held.sort_by(|x, y| x.from.total_cmp(&y.from));
    held
}
