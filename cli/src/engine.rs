//! The one place where the program calls the library: a description file in, the program's
//! plain data ([`crate::model`]) out. Every entry point of `tmm` the program uses is named
//! here (and in its parts below), so that a change of the library's API is adapted there
//! alone.

mod reduced;
pub mod synth;
mod two_inputs;

use tmm::draw::{self, Course, Diagram, Style};
use tmm::kinematics::{grashof, Grashof, Motion, Rotation};
use tmm::kinetostatics::friction::Efficiency;
use tmm::linkage::{
    course_inputs, uniform_inputs, Drive, Inputs, LinkId, Linkage, ModeOptions, ModeSearch, Output,
    Plan, Tabulate, TwoInputCourse, MULTISTART_SOLVES_PER_START,
};

use crate::budget;
use crate::model::{
    typed, Column, DiagramKind, DynamicsRequest, Failure, GroupInfo, InputInfo, InputKind,
    ModesInfo, PictureKind, PictureRequest, Positions, Range, StrokeInfo, Structure, TableData,
    TwoInputDynamics,
};

/// The most groups whose assembly modes `tmm check` combines one by one.
const MODES_ENUMERATED_GROUPS: usize = 16;

/// The largest input angle the program takes, rad. An `f64` near 10⁹ is spaced 1.2·10⁻⁷
/// apart, so a larger angle (`--at 1e300`) names a crank position no better than to a tenth
/// of a microradian — at 10¹⁶ not even to a turn: such an angle is refused rather than
/// silently rounded to some other position.
pub const MAX_ANGLE: f64 = tmm::linkage::MAX_INPUT_COORDINATE;

/// An input angle typed in degrees after `option`, in rad: a finite number within
/// ±[`MAX_ANGLE`], or a sentence naming the option.
pub fn typed_angle(option: &str, degrees: f64) -> Result<f64, Failure> {
    let rad = degrees.to_radians();
    if rad.abs() <= MAX_ANGLE {
        return Ok(rad);
    }
    Err(Failure::new(format!(
        "{option} {}: an input angle must be a finite number within ±10⁹ rad \
         (±5.7·10¹⁰°), where an f64 still holds it to 10⁻⁷ rad",
        typed(degrees)
    ))
    .hint("give the angle in degrees within a few turns of zero"))
}

/// An input coordinate typed after `option`, in the input's unit: an angle in degrees (a
/// crank's, see [`typed_angle`]) in rad, or a slide in metres, finite and within ±10⁹ m.
pub fn typed_coordinate(option: &str, crank: bool, typed: f64) -> Result<f64, Failure> {
    if crank {
        return typed_angle(option, typed);
    }
    if typed.abs() <= tmm::linkage::MAX_INPUT_COORDINATE {
        return Ok(typed);
    }
    Err(Failure::new(format!(
        "{option} {}: a slider's input coordinate must be a finite number of metres within \
         ±10⁹ m",
        crate::model::typed(typed)
    ))
    .hint("give the slide in metres, within the slider's travel (`tmm check` shows it)"))
}

/// The largest input speed accepted, rad/s: far above any machine's, and small enough that
/// its revolutions per minute and every rate of a position stay finite.
pub const MAX_SPEED: f64 = 1e9;

/// A speed asked for: finite, within ±[`MAX_SPEED`].
fn check_speed(speed: f64) -> Result<(), Failure> {
    if speed.is_finite() && speed.abs() <= MAX_SPEED {
        Ok(())
    } else {
        Err(Failure::new(format!(
            "the speed must be finite and within ±{MAX_SPEED:e} rad/s, got {}",
            typed(speed)
        ))
        .hint("give --speed in rad/s"))
    }
}

/// The rotor and the motors of a dynamics request, each named by its option: a rotor finite
/// and not negative, every motor's a and b finite.
fn check_machine(request: &DynamicsRequest) -> Result<(), Failure> {
    let rotor = request.rotor;
    if !(rotor.is_finite() && rotor >= 0.0) {
        return Err(Failure::new(format!(
            "--rotor {}: a rotor's moment of inertia must be finite and not negative",
            typed(rotor)
        ))
        .hint("give --rotor J in kg·m², 0 for none"));
    }
    for (option, motor) in [("--motor", request.motor), ("--motor2", request.motor2)] {
        if let Some((a, b)) = motor
            && !(a.is_finite() && b.is_finite())
        {
            return Err(Failure::new(format!(
                "{option} {},{}: a motor's a and b must be finite numbers",
                typed(a),
                typed(b)
            ))
            .hint("give a in N·m and b in N·m·s/rad, for example --motor 60,2"));
        }
    }
    Ok(())
}

/// The library's error as a person reads it: its `Display` text.
fn failure(e: &tmm::Error) -> Failure {
    Failure::new(e.to_string())
}

/// An error of the description itself, with where to read the format.
fn description_failure(e: &tmm::Error) -> Failure {
    let f = failure(e);
    match e {
        tmm::Error::Description { .. } => {
            f.hint("the file format is described in docs/linkage-format.md")
        }
        _ => f,
    }
}

/// The positions a picture over the cycle solves, at most about: the course's search for
/// the output's extremes on 360 positions and their refinement, then an animation's 360
/// frames or the plan's and the diagram's positions and paths.
const PICTURE_POSITIONS: f64 = 1000.0;

/// The solves of the search of a crank's range (720 positions over a turn, then the
/// bisections to its lock angles) or a slider's travel (steps of 1/200 of the linkage's
/// size out to 4 sizes either way, then bisections), at most about.
const RANGE_SOLVES: f64 = 2000.0;

/// The solves of the library's scan of every group's transmission angle over a turn
/// (`Plan::min_transmission_angles`): one sweep of 720 positions for all groups, then each
/// group's golden-section search to 10⁻¹² rad (52 positions, counted as 80) of the groups it
/// hangs on alone.
const TRANSMISSION_SWEEP_SOLVES: f64 = 720.0;
const TRANSMISSION_REFINE_SOLVES: f64 = 80.0;

/// The work of one group's solve, in solves of a dyad (see [`crate::budget`]).
fn group_weight(g: &tmm::linkage::Group) -> f64 {
    use tmm::linkage::GroupKind;
    match g.kind {
        GroupKind::Triad => budget::TRIAD_WEIGHT,
        GroupKind::General => {
            budget::general_weight(g.general_links().map_or(0, |(_, inner, _)| inner.len()))
        }
        _ => 1.0,
    }
}

/// A planned linkage, ready for every subcommand.
pub struct Machine {
    linkage: Linkage,
    plan: Plan,
    range: std::cell::OnceCell<Range>,
}

/// Reads a description from JSON text and makes its plan.
///
/// # Errors
/// The library's message for a malformed description.
pub fn load(text: &str) -> Result<Machine, Failure> {
    let linkage = Linkage::from_json(text).map_err(|e| match &e {
        // JSON's reader names the line and column: name the field there too.
        tmm::Error::Description { item, problem } if item == "description file" => {
            let path = serde_json::from_str::<Linkage>(text)
                .err()
                .map(|j| crate::json_path::path_at(text, j.line(), j.column()))
                .unwrap_or_default();
            if path.is_empty() {
                description_failure(&e)
            } else {
                Failure::new(format!("{item}, field {path}: {problem}"))
                    .hint("the file format is described in docs/linkage-format.md")
            }
        }
        _ => description_failure(&e),
    })?;
    let plan = Plan::new(&linkage).map_err(|e| description_failure(&e))?;
    Ok(Machine {
        linkage,
        plan,
        range: std::cell::OnceCell::new(),
    })
}

impl Machine {
    /// The work of one solve of the linkage's positions, in solves of a dyad (see
    /// [`crate::budget`]): each input, each dyad, each triad and each general group by its
    /// inner joints.
    pub fn solve_weight(&self) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let inputs = self.plan.input_count() as f64 * budget::INPUT_WEIGHT;
        let groups: f64 = self.plan.groups().iter().map(group_weight).sum();
        inputs + groups
    }

    /// The work of the library's scan of every group's transmission angle, in solves of
    /// the whole linkage: the sweep's 720 solves of it, then each group's refinement, which
    /// solves the group's ancestry alone (`Plan::group_ancestry`: the input and the groups it
    /// hangs on) [`TRANSMISSION_REFINE_SOLVES`] times. A general group is not refined.
    fn transmission_scan_solves(&self) -> f64 {
        let weights: Vec<f64> = self.plan.groups().iter().map(group_weight).collect();
        #[allow(clippy::cast_precision_loss)]
        let inputs = self.plan.input_count() as f64 * budget::INPUT_WEIGHT;
        let refined: f64 = (0..weights.len())
            .filter(|&g| self.plan.groups()[g].kind != tmm::linkage::GroupKind::General)
            .map(|g| {
                let chain = self.plan.group_ancestry(g).unwrap_or_default();
                inputs + chain.iter().map(|&h| weights[h]).sum::<f64>()
            })
            .sum();
        TRANSMISSION_SWEEP_SOLVES + TRANSMISSION_REFINE_SOLVES * refined / self.solve_weight()
    }

    /// The linkage's name.
    pub fn name(&self) -> &str {
        self.plan.name()
    }

    /// The name and a few words on the structure (mobility and groups), cheap to compute.
    pub fn structure_brief(&self) -> (String, String) {
        let kinds: Vec<&str> = self.plan.groups().iter().map(|g| g.kind.label()).collect();
        (
            self.name().to_owned(),
            format!(
                "mobility {}, groups {}",
                self.plan.mobility(),
                if kinds.is_empty() {
                    "none".to_owned()
                } else {
                    kinds.join(", ")
                }
            ),
        )
    }

    /// The number of inputs (1 or 2).
    pub fn input_count(&self) -> usize {
        self.plan.input_count()
    }

    /// The dynamics of a linkage with two inputs: the mass matrix and the loads'
    /// generalized forces over a grid of the inputs about the reference pose.
    ///
    /// # Errors
    /// A run-up or a flywheel asked for (a linkage with two inputs has no cycle of its own);
    /// see [`Machine::mass_matrix_grid`].
    pub fn dynamics_two(
        &self,
        request: &DynamicsRequest,
        progress: &mut dyn FnMut(&str),
    ) -> Result<TwoInputDynamics, Failure> {
        if request.run_up || !request.flywheel.is_empty() {
            return Err(Failure::new(
                "a run-up and a flywheel need one crank that turns fully, and a linkage with \
                 two inputs (mobility 2) has no cycle of its own: it moves as its two drives \
                 make it",
            )
            .hint("without --run-up and --flywheel, its mass matrix over a grid of the inputs"));
        }
        check_speed(request.speed)?;
        check_machine(request)?;
        let mut d = self.mass_matrix_grid(request.grid, request.span, request.rotor, progress)?;
        if let Some(t_end) = request.run {
            d.run = Some(self.run_two(request, t_end, progress)?);
        }
        Ok(d)
    }

    /// The input speed of the file (10 rad/s when it gives none).
    pub fn default_speed(&self) -> f64 {
        self.linkage.input_speed()
    }

    fn input_kind(&self) -> InputKind {
        if self.plan.input_is_crank() {
            InputKind::Crank
        } else {
            InputKind::Slider
        }
    }

    /// Fails for a linkage with two inputs, which has no single course.
    fn one_input(&self, what: &str) -> Result<(), Failure> {
        if self.plan.input_count() > 1 {
            return Err(Failure::new(format!(
                "{what} needs a linkage with one input, and this one has {} (mobility {})",
                self.plan.input_count(),
                self.plan.mobility()
            ))
            .hint("`tmm check` shows its structure, `tmm analyse --at φ1 φ2 …` its positions"));
        }
        Ok(())
    }

    /// The structure: mobility, groups, the input's range, Grashof's class, transmission
    /// angles and strokes.
    pub fn structure(&self) -> Structure {
        let plan = &self.plan;
        let links = plan.link_names();
        let joints = plan.joint_names();
        let refs = plan.reference_inputs();
        let mut inputs = vec![InputInfo {
            link: links[plan.input_links()[0].index()].clone(),
            kind: self.input_kind(),
            drive: drive_text(&self.linkage.input.drive, plan.input_is_crank()),
            reference: refs[0],
        }];
        if let (Some(k), Some(second)) = (
            plan.input_links().get(1).map(|k| k.index()),
            &self.linkage.second_input,
        ) {
            inputs.push(InputInfo {
                link: links[k].clone(),
                kind: if second_is_crank(&self.linkage, &second.link) {
                    InputKind::Crank
                } else {
                    InputKind::Slider
                },
                drive: drive_text(&second.drive, second_is_crank(&self.linkage, &second.link)),
                reference: refs.get(1).copied().unwrap_or(0.0),
            });
        }
        let groups = plan
            .groups()
            .iter()
            .map(|g| {
                let names = |ix: &[usize], of: &[String]| -> Vec<String> {
                    ix.iter().map(|&k| of[k].clone()).collect()
                };
                let (l, j, inner) = match (g.general_links(), g.triad_links(), g.triad_joints()) {
                    (Some((l, inner, outer)), ..) => (
                        names(l, links),
                        names(&[inner, outer].concat(), joints),
                        Some(inner.len()),
                    ),
                    // A triad: the ternary link and its three legs; the legs' hinges on the
                    // ternary link, then their joints to known links.
                    (None, Some(l), Some([outer, inner])) => (
                        names(&l, links),
                        names(&[inner, outer].concat(), joints),
                        Some(3),
                    ),
                    _ => (names(&g.links, links), names(&g.joints, joints), None),
                };
                GroupInfo {
                    kind: g.kind.label().to_owned(),
                    links: l,
                    joints: j,
                    inner,
                    name: g.name.clone(),
                }
            })
            .collect();
        let range = self.range();
        let full = matches!(range, Range::FullTurn);
        #[allow(clippy::cast_precision_loss)]
        let scanned = plan
            .groups()
            .iter()
            .filter(|g| g.kind != tmm::linkage::GroupKind::General)
            .count() as f64;
        let scans = budget::check(
            self.transmission_scan_solves(),
            self.solve_weight(),
            &format!("the scans of {scanned} groups' transmission angles"),
            "",
        );
        // Every group's minimum in one sweep of the turn (a loop over the groups would solve
        // the turn once per group: quadratic in their number).
        let minima = match (&scans, full) {
            (Ok(_), true) => Some(plan.min_transmission_angles().map_err(|e| e.to_string())),
            _ => None,
        };
        // A general group (above the 3rd class) has no transmission angle: no line.
        let transmission = plan
            .groups()
            .iter()
            .enumerate()
            .filter(|(_, group)| group.kind != tmm::linkage::GroupKind::General)
            .map(|(g, group)| {
                let value = if let Err(f) = &scans {
                    Err(format!("not computed: {}", f.message))
                } else if let Some(minima) = &minima {
                    match minima {
                        Ok(all) => all[g].as_ref().map(|m| *m).map_err(ToString::to_string),
                        Err(e) => Err(e.clone()),
                    }
                } else {
                    Err(match &range {
                        Range::Rocking(..) => "the crank does not turn fully".to_owned(),
                        Range::Travel(..) => "the input is a slider".to_owned(),
                        Range::Unknown(why) => why.clone(),
                        Range::FullTurn => unreachable!("handled above"),
                    })
                };
                (group.name.clone(), value)
            })
            .collect();
        let strokes = self.linkage.output.as_ref().map(|out| {
            if !full {
                return Err("strokes need a crank that turns fully".to_owned());
            }
            plan.strokes(out, rotation(self.default_speed()))
                .map(|s| StrokeInfo {
                    output: output_text(out),
                    start: s.start,
                    working_angle: s.working_angle,
                    time_ratio: s.time_ratio,
                    stroke: s.stroke,
                    stroke_unit: if matches!(out, Output::Angle(_)) {
                        "rad"
                    } else {
                        "m"
                    },
                })
                .map_err(|e| e.to_string())
        });
        Structure {
            name: self.name().to_owned(),
            mobility: plan.mobility(),
            inputs,
            groups,
            input_ranges: if plan.input_count() == 2 {
                self.input_ranges()
            } else {
                Vec::new()
            },
            range,
            grashof: self.grashof(),
            transmission,
            strokes,
            modes: self.modes(),
        }
    }

    /// The real assembly modes at the reference input(s): each group's count on the
    /// engine's assembly before it, and every combination enumerated up to 10⁴ assemblies.
    fn modes(&self) -> Result<ModesInfo, String> {
        let plan = &self.plan;
        let motions: Vec<Motion> = plan
            .reference_inputs()
            .into_iter()
            .map(Motion::fixed)
            .collect();
        let inputs = Inputs::from_slice(&motions).map_err(|e| e.to_string())?;
        let options = ModeOptions::default().with_max_modes(10_000);
        // A multistart search (a general group with no reduction) solves the group's closure
        // equations from each of its starts: weighed as solves of the linkage before it runs.
        let multistart = |searches: &[ModeSearch], times: &[f64]| {
            let mut solves = 0.0;
            for (s, t) in searches.iter().zip(times) {
                if let ModeSearch::Multistart { starts } = s {
                    #[allow(clippy::cast_precision_loss)]
                    let per = *starts as f64 * MULTISTART_SOLVES_PER_START as f64; // no usize overflow
                    solves += per * t;
                }
            }
            solves
        };
        let searches = plan.mode_searches(&options);
        let once = vec![1.0; searches.len()];
        budget::check(
            multistart(&searches, &once),
            self.solve_weight(),
            "the multistart search of a general group's assembly modes",
            "",
        )
        .map_err(|f| f.message)?;
        let groups = plan
            .mode_counts(inputs, &options)
            .map_err(|e| e.to_string())?;
        // The enumeration searches each group once per assembly of the groups before it.
        #[allow(clippy::cast_precision_loss)]
        let before: Vec<f64> = groups
            .iter()
            .scan(1.0, |p, g| {
                let here = *p;
                *p *= g.counts.first().copied().unwrap_or(0) as f64;
                Some(here)
            })
            .collect();
        let enumeration_fits = budget::check(
            multistart(&searches, &before),
            self.solve_weight(),
            "the enumeration's multistart searches",
            "",
        );
        let exhaustive = !groups
            .iter()
            .any(|g| matches!(g.search, ModeSearch::Multistart { .. }));
        let links = plan.link_names();
        let groups = groups
            .into_iter()
            .map(|g| {
                let how = match g.search {
                    ModeSearch::ClosedForm => "closed form, both branches".to_owned(),
                    ModeSearch::Triad => "every root of the triad's eliminated equation".to_owned(),
                    ModeSearch::Reduction {
                        driver,
                        closing,
                        samples,
                        branches,
                    } => format!(
                        "every root of one equation in {}'s angle, cut at {} ({branches} \
                         branch choices, {samples} samples each)",
                        links[driver], links[closing]
                    ),
                    ModeSearch::Multistart { starts } => {
                        format!("a multistart search of {starts} starts: at least this many")
                    }
                };
                (g.name, g.counts.first().copied().unwrap_or(0), how)
            })
            .collect();
        // Every combination is walked only for a linkage of a few groups: a long chain's
        // 2ⁿ assemblies would take `check` minutes to reach the cap, and its count is the
        // product of the groups' counts wherever those do not depend on the modes before.
        let n_groups = plan.groups().len();
        let total = if let Err(f) = enumeration_fits {
            Err(f.message)
        } else if n_groups <= MODES_ENUMERATED_GROUPS {
            plan.assembly_modes_with(inputs, &options)
                .map(|a| a.total())
                .map_err(|e| e.to_string())
        } else {
            Err(format!(
                "not enumerated: {n_groups} groups (combinations are walked for at most {MODES_ENUMERATED_GROUPS})"
            ))
        };
        Ok(ModesInfo {
            groups,
            total,
            exhaustive,
        })
    }

    /// Whether the crank turns fully, or between which angles it rocks; the slider's travel.
    fn range(&self) -> Range {
        self.range.get_or_init(|| self.find_range()).clone()
    }

    fn find_range(&self) -> Range {
        let plan = &self.plan;
        if plan.input_count() > 1 {
            return Range::Unknown(
                "two inputs move over a 2-D region of input pairs, with no single turn".to_owned(),
            );
        }
        if let Err(f) = budget::check(
            RANGE_SOLVES,
            self.solve_weight(),
            "the search of the input's range",
            "",
        ) {
            return Range::Unknown(f.message);
        }
        if !plan.input_is_crank() {
            return self.slider_travel();
        }
        match plan.lock_positions(plan.reference_input()) {
            Ok(None) => Range::FullTurn,
            Ok(Some((a, b))) => Range::Rocking(a.min(b), a.max(b)),
            Err(e) => Range::Unknown(e.to_string()),
        }
    }

    /// The travel of a slider input from its reference pose: the nearest slides, either way,
    /// where the linkage stops assembling (or meets a dead point), found by stepping out by
    /// 1/200 of the linkage's size and bisecting; at most 4 sizes either way. (The library
    /// finds lock positions of cranks only.)
    fn slider_travel(&self) -> Range {
        let plan = &self.plan;
        travel(plan.size(), plan.reference_input(), |s| {
            plan.kinematics(Motion::fixed(s)).is_ok()
        })
    }

    /// Grashof's class of a four-bar: one RRR group hinged to the crank and the frame.
    fn grashof(&self) -> Option<String> {
        let plan = &self.plan;
        let [g] = plan.groups() else { return None };
        if g.kind.label() != "RRR" || !plan.input_is_crank() || plan.input_count() != 1 {
            return None;
        }
        let input = plan.input_links()[0].index();
        let (a, c) = match g.known {
            [k, 0] if k == input => (g.joints[0], g.joints[2]),
            [0, k] if k == input => (g.joints[2], g.joints[0]),
            _ => return None,
        };
        let b = g.joints[1];
        let pivot = (0..plan.joint_names().len()).find(|&j| {
            plan.joint_links(j)
                .is_ok_and(|l| l.iter().any(|k| k.index() == input) && l.contains(&LinkId::FRAME))
        })?;
        let pose = plan
            .kinematics(Motion::fixed(plan.reference_input()))
            .ok()?;
        let p = |j: usize| pose.joint(j).ok().map(|m| m.p);
        let (o, a, b, c) = (p(pivot)?, p(a)?, p(b)?, p(c)?);
        let class = grashof(
            (c - o).norm(),
            (a - o).norm(),
            (b - a).norm(),
            (c - b).norm(),
        )
        .ok()?;
        Some(grashof_text(class).to_owned())
    }

    /// The inputs of the positions asked for.
    fn inputs(
        &self,
        positions: &Positions,
        speed: f64,
        notes: &mut Vec<String>,
    ) -> Result<Vec<Motion>, Failure> {
        self.one_input("a table of positions")?;
        check_speed(speed)?;
        let plan = &self.plan;
        let crank = plan.input_is_crank();
        let reference = plan.reference_input();
        let range = self.range();
        let spread = |n: usize, notes: &mut Vec<String>| -> Vec<Motion> {
            match range {
                // A rocking crank runs from lock to lock and back, as the mechanism does.
                Range::Rocking(lo, hi) if crank => match Course::new(plan, None, n, speed) {
                    Ok(course) => {
                        notes.push(format!(
                            "{n} positions of the crank rocking as the mechanism runs, from the \
                             lock angle {:.4}° to {:.4}° and back (at the locks it stops and \
                             reverses: rate 0 there, and the driven group at its dead point \
                             has no forces)",
                            if speed < 0.0 { hi } else { lo }.to_degrees(),
                            if speed < 0.0 { lo } else { hi }.to_degrees(),
                        ));
                        course.inputs
                    }
                    Err(e) => {
                        notes.push(format!("no rocking course ({e}): none tabulated"));
                        Vec::new()
                    }
                },
                Range::Rocking(lo, hi) | Range::Travel(lo, hi) => {
                    notes.push(format!(
                        "{n} positions equally spaced inside the {}",
                        if crank {
                            "lock angles"
                        } else {
                            "slider's travel"
                        }
                    ));
                    // Inside the ends, where the groups are at dead points, in the order a
                    // motion at `speed` meets them.
                    let h = (hi - lo) / n as f64;
                    let mut at: Vec<Motion> = (0..n)
                        .map(|k| Motion::new(lo + h * (k as f64 + 0.5), speed, 0.0))
                        .collect();
                    if speed < 0.0 {
                        at.reverse();
                    }
                    at
                }
                _ => {
                    notes.push(format!(
                        "{n} positions equally spaced over a turn from the reference pose"
                    ));
                    uniform_inputs(n, reference, speed, 0.0)
                }
            }
        };
        match positions {
            Positions::At(values) => values
                .iter()
                .map(|&v| Ok(Motion::new(typed_coordinate("--at", crank, v)?, speed, 0.0)))
                .collect(),
            Positions::Uniform(n) => Ok(spread(*n, notes)),
            Positions::Course(n) => match (&self.linkage.output, crank, &range) {
                (Some(out), true, Range::FullTurn) => match plan.strokes(out, rotation(speed)) {
                    Ok(s) => {
                        notes.push(format!(
                            "{n} course positions from the start of the working stroke of the \
                             {} at φ = {:.1}° (over {:.1}°, time ratio {:.4})",
                            output_text(out),
                            s.start.to_degrees(),
                            s.working_angle.to_degrees(),
                            s.time_ratio
                        ));
                        Ok(course_inputs(&s, *n, speed))
                    }
                    Err(e) => {
                        notes.push(format!("the output has no strokes ({e})"));
                        Ok(spread(*n, notes))
                    }
                },
                (_, true, Range::Rocking(lo, hi)) if speed.is_finite() && speed != 0.0 => {
                    let course = Course::new(plan, None, *n, speed).map_err(|e| failure(&e))?;
                    notes.push(format!(
                        "{n} positions of the crank rocking as the mechanism runs, from the lock \
                         angle {:.4}° to {:.4}° and back (at the locks it stops and reverses: \
                         rate 0 there)",
                        if speed < 0.0 { hi } else { lo }.to_degrees(),
                        if speed < 0.0 { lo } else { hi }.to_degrees(),
                    ));
                    Ok(course.inputs)
                }
                _ => Ok(spread(*n, notes)),
            },
        }
    }

    /// The table of the positions asked for, at the crank speed `speed`.
    ///
    /// # Errors
    /// Two inputs; no position could be analysed (the first position's error).
    pub fn table(
        &self,
        positions: &Positions,
        speed: f64,
        progress: &mut dyn FnMut(&str),
    ) -> Result<TableData, Failure> {
        let mut notes = Vec::new();
        let inputs: Vec<Vec<Motion>> = if self.plan.input_count() > 1 {
            self.input_pairs(positions, speed, &mut notes)?
        } else {
            self.inputs(positions, speed, &mut notes)?
                .into_iter()
                .map(|i| vec![i])
                .collect()
        };
        if inputs.is_empty() {
            return Err(Failure::new("no positions were asked for"));
        }
        let n = inputs.len();
        let weight = self.solve_weight();
        let (asked, fix) = match positions {
            Positions::At(_) => ("--at", "give fewer positions to --at"),
            _ => ("--positions", "give a smaller --positions N"),
        };
        #[allow(clippy::cast_precision_loss)]
        budget::check(
            n as f64,
            weight,
            &format!("{asked} with {n} positions"),
            &format!(
                "{fix}, at most {:.0} for this linkage",
                budget::most_solves(weight)
            ),
        )?;
        let inputs: Vec<Inputs> = inputs
            .iter()
            .map(|i| Inputs::from_slice(i))
            .collect::<tmm::Result<_>>()
            .map_err(|e| failure(&e))?;
        let mut report = |k: usize| {
            if k.is_multiple_of(5000) && n > 5000 {
                progress(&format!("position {} of {n}", k + 1));
            }
        };
        // A crank turning through a dead centre (a change point) runs on along the branch
        // that continues smoothly: the positions past it are solved on that branch.
        let one: Vec<Motion> = inputs.iter().map(|i| i.as_slice()[0]).collect();
        let track = (self.plan.input_count() == 1
            && self.plan.input_is_crank()
            && matches!(self.range(), Range::FullTurn))
        .then(|| self.plan.track(&one).ok())
        .flatten()
        .filter(|t| !t.crossings.is_empty());
        let results = match &track {
            Some(t) => {
                notes.extend(t.notes());
                t.analyse_each(&one, &mut report)
            }
            None => self.plan.analyse_each(&inputs, &mut report),
        };
        // With two inputs the library's row holds both inputs, both balances and the drives'
        // power beside its value by virtual power (W).
        let table = self.plan.course_table(&results);
        // The table leaves out a row holding a value that is not finite (a reaction or a
        // power that overflows under a huge load): such a position failed too, and says so.
        let kept = table.columns.first().map_or(0, |c| c.values.len());
        let analysed = results.iter().filter(|r| r.is_ok()).count();
        let second = self.second_is_crank();
        let mut failures = Vec::new();
        for (i, r) in inputs.iter().zip(&results) {
            let why = match r {
                Err(e) => e.to_string(),
                Ok(a) if kept < analysed => match a.row() {
                    Err(tmm::Error::In { part, .. }) => {
                        format!("its {part} is not finite (it overflows)")
                    }
                    Err(e) => e.to_string(),
                    Ok(_) => continue,
                },
                Ok(_) => continue,
            };
            let why = match i.as_slice().get(1) {
                // A position of two inputs is named by both.
                Some(m) => {
                    let kind = if second {
                        InputKind::Crank
                    } else {
                        InputKind::Slider
                    };
                    format!(
                        "with the second input at {}: {why}",
                        crate::report::input_text(kind, m.value)
                    )
                }
                None => why,
            };
            failures.push((i.as_slice()[0].value, why));
        }
        if kept == 0 {
            let first = failures.first().map_or("no row was kept", |f| f.1.as_str());
            return Err(Failure::new(format!(
                "no position could be analysed: {first}"
            )));
        }
        let mut columns: Vec<Column> = table
            .columns
            .into_iter()
            .map(|c| {
                let (name, unit) = split_unit(&c.name);
                Column {
                    name,
                    unit,
                    values: c.values,
                }
            })
            .collect();
        with_efficiency(&mut columns);
        Ok(TableData {
            name: self.name().to_owned(),
            columns,
            failures,
            input: self.input_kind(),
            notes,
            speed,
        })
    }

    fn second_is_crank(&self) -> bool {
        self.linkage
            .second_input
            .as_ref()
            .is_none_or(|s| second_is_crank(&self.linkage, &s.link))
    }

    /// The positions of a linkage with two inputs: `--at` values taken in pairs, or `n`
    /// positions round a loop about the reference pose (each input swinging about its
    /// reference value, the second a quarter period behind).
    fn input_pairs(
        &self,
        positions: &Positions,
        speed: f64,
        notes: &mut Vec<String>,
    ) -> Result<Vec<Vec<Motion>>, Failure> {
        check_speed(speed)?;
        let values = match positions {
            Positions::At(values) => values,
            Positions::Course(n) | Positions::Uniform(n) => {
                let course = TwoInputCourse::around_reference(&self.plan, *n, speed)
                    .map_err(|e| failure(&e))?;
                notes.push(format!(
                    "two inputs: {n} positions round a loop about the reference pose, each \
                     input swinging harmonically about its reference value, the second a \
                     quarter period behind (--at φ1 φ2 … for positions of your own)"
                ));
                return Ok(course
                    .inputs
                    .iter()
                    .map(|i| i.as_slice().to_vec())
                    .collect());
            }
        };
        if values.len() % 2 != 0 {
            return Err(Failure::new(format!(
                "a linkage with two inputs needs --at values in pairs (φ1 φ2), got {}",
                values.len()
            )));
        }
        let convert =
            |v: f64, crank: bool| Ok(Motion::new(typed_coordinate("--at", crank, v)?, speed, 0.0));
        let (first, second) = (self.plan.input_is_crank(), self.second_is_crank());
        values
            .chunks(2)
            .map(|p| Ok(vec![convert(p[0], first)?, convert(p[1], second)?]))
            .collect()
    }

    /// The course of the pictures over the cycle.
    fn course(&self, speed: f64) -> Result<Course, Failure> {
        let plan = &self.plan;
        if speed == 0.0 || !speed.is_finite() {
            return Err(Failure::new(format!(
                "a picture over the cycle needs an input that moves, and the speed is {}",
                typed(speed)
            ))
            .hint("give --speed, not zero"));
        }
        if plan.input_is_crank() && matches!(self.range(), Range::FullTurn | Range::Rocking(..)) {
            // An output without strokes (one that turns fully) still has a turn to draw; a
            // rocking crank sweeps from lock to lock and back.
            return Course::new(plan, self.linkage.output.as_ref(), 12, speed)
                .or_else(|e| Course::new(plan, None, 12, speed).map_err(|_| e))
                .map_err(|e| failure(&e));
        }
        Ok(Course::given(self.inputs(
            &Positions::Uniform(12),
            speed,
            &mut Vec::new(),
        )?))
    }

    /// The output of the diagrams: the described one, or the last link's angle.
    fn output(&self) -> Output {
        self.plan.output_or_last(self.linkage.output.as_ref())
    }

    /// A picture as SVG text.
    ///
    /// # Errors
    /// The library's error for the picture; a picture over the cycle of a linkage with two
    /// inputs (which has none); a workspace of a linkage with one input.
    pub fn draw(
        &self,
        request: &PictureRequest,
        progress: &mut dyn FnMut(&str),
    ) -> Result<String, Failure> {
        let plan = &self.plan;
        let style = Style::default();
        let speed = request.speed;
        let two = plan.input_count() == 2;
        if !two && !request.along.is_empty() {
            return Err(Failure::new(
                "--along gives a path in the plane of two inputs, and this linkage has one",
            )
            .hint("its plan and animation follow its own cycle"));
        }
        if !request.along.is_empty()
            && !matches!(
                request.kind,
                PictureKind::Plan | PictureKind::Animation | PictureKind::Diagram(_)
            )
        {
            return Err(Failure::new(
                "--along gives the path of --plan, --animate and --diagram, and none was asked for",
            ));
        }
        if !matches!(
            request.kind,
            PictureKind::Scheme(_) | PictureKind::Forces(_) | PictureKind::Workspace(_)
        ) {
            // A plan, an animation or a diagram: at most PICTURE_POSITIONS positions.
            budget::check(
                PICTURE_POSITIONS,
                self.solve_weight(),
                "a picture over the cycle",
                "draw the linkage at one position with --scheme φ instead",
            )?;
        }
        let paths = plan.traced_points();
        // A picture at one position: a pose that does not assemble is said with the option
        // and the value that asked for it.
        let at_position = |option: &str, at: &[f64], e: &tmm::Error| {
            let typed: Vec<String> = at.iter().map(|v| typed(*v)).collect();
            let asked = if typed.is_empty() {
                "the reference pose".to_owned()
            } else {
                format!("{option} {}", typed.join(" "))
            };
            Failure::new(format!("{asked}: {e}")).hint("`tmm check FILE` shows the input's range")
        };
        let svg = match &request.kind {
            PictureKind::Scheme(at) | PictureKind::Forces(at) => {
                let option = if matches!(request.kind, PictureKind::Forces(_)) {
                    "--forces"
                } else {
                    "--scheme"
                };
                let inputs = self.inputs_at(option, at, speed)?;
                return match request.kind {
                    PictureKind::Forces(_) => draw::forces(plan, inputs, &style),
                    _ if request.centres => draw::scheme_with_centres(plan, inputs, &style),
                    _ => draw::scheme(plan, inputs, &style),
                }
                .map(|p| p.svg)
                .map_err(|e| at_position(option, at, &e));
            }
            PictureKind::Workspace(point) => return self.workspace(point, &style, progress),
            PictureKind::Plan if two => {
                return self.plan_two(&request.along, speed, &paths, &style);
            }
            PictureKind::Animation if two => {
                return self.animation_two(&request.along, speed, &style);
            }
            PictureKind::Diagram(kind) if two => {
                return self.diagram_two(*kind, &request.along, speed);
            }
            PictureKind::Plan => {
                let course = self.course(speed)?;
                draw::plan_view(plan, &course, &paths, &style).map(|p| p.svg)
            }
            PictureKind::Animation => {
                let frames = match (plan.input_is_crank(), self.range()) {
                    (true, Range::FullTurn) => {
                        let start = self.course(speed)?.inputs[0].value;
                        uniform_inputs(360, start, speed, 0.0)
                    }
                    _ => {
                        // Rocking (or sliding) there and back.
                        let mut go =
                            self.inputs(&Positions::Uniform(90), speed, &mut Vec::new())?;
                        let back: Vec<Motion> = go.iter().rev().copied().collect();
                        go.extend(back);
                        go
                    }
                };
                draw::animation(plan, &frames, 4.0, &style).map(|p| p.svg)
            }
            PictureKind::Diagram(kind) => return self.diagram(*kind, speed),
        };
        svg.map_err(|e| failure(&e))
    }

    /// The (first) input link's joint off the frame, whose reaction the hodograph draws.
    fn crank_pin(&self) -> Result<String, Failure> {
        self.plan
            .crank_pin()
            .map(str::to_owned)
            .ok_or_else(|| Failure::new("the input link has no joint off the frame"))
    }

    /// A diagram over the cycle of a linkage with one input.
    fn diagram(&self, kind: DiagramKind, speed: f64) -> Result<String, Failure> {
        let plan = &self.plan;
        let course = self.course(speed)?;
        let style = Style::default();
        let tall = Style {
            height: 900,
            ..Style::default()
        };
        let (diagram, style) = match kind {
            DiagramKind::Kinematics => (Diagram::Kinematics(self.output()), &tall),
            DiagramKind::Transfer => (Diagram::Transfer(self.output()), &tall),
            DiagramKind::Balance => (Diagram::Balance, &style),
            DiagramKind::Reactions => (Diagram::Reactions, &style),
            DiagramKind::Hodograph => (Diagram::Hodograph(self.crank_pin()?), &style),
        };
        draw::diagram(plan, &course, &diagram, style)
            .map(|c| c.svg)
            .map_err(|e| failure(&e))
    }
}

/// Grashof's class in words, with the inequality that makes it.
fn grashof_text(class: Grashof) -> &'static str {
    match class {
        Grashof::CrankRocker => "crank-rocker (s + l < p + q, the crank the shortest)",
        Grashof::RockerCrank => "rocker-crank (s + l < p + q, the output the shortest)",
        Grashof::DoubleCrank => "double crank (s + l < p + q, the frame the shortest)",
        Grashof::DoubleRocker => "double rocker (s + l < p + q, the coupler the shortest)",
        Grashof::ChangePoint => "change point (s + l = p + q: it folds flat)",
        Grashof::TripleRocker => "triple rocker (s + l > p + q: no link turns fully)",
    }
}

fn rotation(speed: f64) -> Rotation {
    if speed < 0.0 {
        Rotation::Cw
    } else {
        Rotation::Ccw
    }
}

fn drive_text(drive: &Drive, crank: bool) -> String {
    if !crank {
        return "by a force along its guide".to_owned();
    }
    match drive {
        Drive::Coupling => "through a coupling (balancing moment)".to_owned(),
        Drive::Gear {
            pitch_radius,
            pressure_angle,
            ..
        } => format!(
            "through a gear pair (pitch radius {pitch_radius} m, pressure angle {:.1}°)",
            pressure_angle.to_degrees()
        ),
    }
}

/// Whether the second input link is hinged to the frame (a crank) rather than sliding on it.
fn second_is_crank(linkage: &Linkage, link: &str) -> bool {
    let frame = linkage.links.iter().find(|l| l.name == linkage.frame);
    let input = linkage.links.iter().find(|l| l.name == link);
    let (Some(frame), Some(input)) = (frame, input) else {
        return true;
    };
    input
        .joints
        .iter()
        .filter(|j| frame.joints.contains(j))
        .filter_map(|j| linkage.joints.iter().find(|x| &x.name == j))
        .all(|j| matches!(j.kind, tmm::linkage::JointKind::Revolute))
}

fn output_text(out: &Output) -> String {
    match out {
        Output::Angle(n) => format!("angle of {n}"),
        Output::Slide(n) => format!("slide of {n}"),
        Output::X(n) => format!("x of {n}"),
        Output::Y(n) => format!("y of {n}"),
    }
}

/// `"R12_x [N]"` → `("R12_x", "N")`.
/// Adds the instantaneous efficiency `eta` after the library's `P_drive [W]` column (a plan
/// with friction): η = (P_drive − P_lost)/P_drive as [`Efficiency`] gives it, where the drive
/// gives power, and NaN (printed as a dash, an empty CSV cell, JSON null) where it does not:
/// the library's table holds only the quantities defined at every position.
fn with_efficiency(columns: &mut Vec<Column>) {
    let find = |name: &str| columns.iter().position(|c| c.name == name && c.unit == "W");
    let (Some(d), Some(l)) = (find("P_drive"), find("P_lost")) else {
        return;
    };
    let values = columns[d]
        .values
        .iter()
        .zip(&columns[l].values)
        .map(|(&drive, &lost)| {
            Efficiency::new(drive, lost)
                .ok()
                .and_then(|e| e.eta)
                .filter(|eta| eta.is_finite())
                .unwrap_or(f64::NAN)
        })
        .collect();
    columns.insert(
        d + 1,
        Column {
            name: "eta".to_owned(),
            unit: "-".to_owned(),
            values,
        },
    );
}

fn split_unit(name: &str) -> (String, String) {
    match name.rfind(" [") {
        Some(k) if name.ends_with(']') => {
            (name[..k].to_owned(), name[k + 2..name.len() - 1].to_owned())
        }
        _ => (name.to_owned(), String::new()),
    }
}

/// The travel of a slider from `reference` over which `solves` holds: the nearest slides,
/// either way, where it stops (stepping out by 1/200 of `size` and bisecting); at most 4
/// sizes either way.
fn travel(size: f64, reference: f64, solves: impl Fn(f64) -> bool) -> Range {
    if !solves(reference) {
        return Range::Unknown("the reference pose does not solve".to_owned());
    }
    let step = size / 200.0;
    let edge = |sense: f64| {
        let mut good = reference;
        for k in 1..=800 {
            let s = reference + sense * step * f64::from(k);
            if !solves(s) {
                let (mut a, mut b) = (good, s);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if solves(m) {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                return a;
            }
            good = s;
        }
        good
    };
    Range::Travel(edge(-1.0), edge(1.0))
}
