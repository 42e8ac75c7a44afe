//! The program's own plain data: what the engine adapter ([`crate::engine`]) hands to the
//! formatting ([`crate::report`]). Nothing here names a type of the library, so a change of the
//! library's spelling stays inside `engine.rs`.

/// A failure a person reads: one sentence, with the fix where one is known.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// What went wrong (the library's `Display` text, or the program's own sentence).
    pub message: String,
    /// How to fix it, when known.
    pub hint: Option<String>,
}

impl Failure {
    /// A failure without a hint.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: one_line(&message.into()),
            hint: None,
        }
    }

    /// The same failure with a hint.
    #[must_use]
    pub fn hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(one_line(&hint.into()));
        self
    }
}

/// A number a person typed, echoed in a message: as typed (the shortest text that reads back
/// to it) in the range people type, in scientific notation outside it — `1e308`, not its
/// 309 digits; `5e-324`, not 324 zeros.
pub fn typed(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || !a.is_finite() || (1e-4..1e9).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// `v` rounded to 5 significant digits: a value the program chooses (a default motor) as a
/// person would write it, so that the text echoed is the value used, and typing it back
/// (`--motor a,b`) repeats the run to the bit.
pub fn as_written(v: f64) -> f64 {
    if v.is_finite() {
        format!("{v:.4e}").parse().unwrap_or(v)
    } else {
        v
    }
}

/// A count (of steps) for a message, 4 significant digits; past f64's range, its bound
/// (never `inf`).
pub fn many(n: f64) -> String {
    if n.is_finite() {
        format!("{n:.3e}")
    } else {
        format!("more than {:.1e}", f64::MAX)
    }
}

/// A text on one line: line breaks and runs of spaces become one space.
fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The input of a linkage: a crank (angle) or a slider (length).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputKind {
    /// A crank, coordinate in rad.
    Crank,
    /// A slider, coordinate in m.
    Slider,
}

/// One input link.
#[derive(Debug, Clone, PartialEq)]
pub struct InputInfo {
    /// The input link's name.
    pub link: String,
    /// Crank or slider.
    pub kind: InputKind,
    /// How it is driven, in words ("coupling", "gear pair, pitch radius 0.15 m", …).
    pub drive: String,
    /// Its coordinate in the reference pose (rad or m).
    pub reference: f64,
}

/// One Assur group in attachment order.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupInfo {
    /// "RRR", "RRP", …
    pub kind: String,
    /// Its links: a dyad's two; a triad's ternary link, then its three legs; every link of a
    /// general group.
    pub links: Vec<String>,
    /// Its joints: a dyad's outer, inner, outer; a triad's or a general group's hinges
    /// between two of its links, then its joints to known links.
    pub joints: Vec<String>,
    /// How many of `joints` are a triad's or a general group's hinges between two of its
    /// links (`None` for a dyad).
    pub inner: Option<usize>,
    /// The library's name of the group (used in column names).
    pub name: String,
}

/// The range of a crank.
#[derive(Debug, Clone, PartialEq)]
pub enum Range {
    /// The crank turns fully.
    FullTurn,
    /// The crank rocks between two lock angles, rad (the smaller first).
    Rocking(f64, f64),
    /// A slider input travels between two slides, m (the smaller first).
    Travel(f64, f64),
    /// Not determined, and why (two inputs, an error).
    Unknown(String),
}

/// The working and idle strokes of the output.
#[derive(Debug, Clone, PartialEq)]
pub struct StrokeInfo {
    /// The output, in words ("angle of rocker", "slide of Q").
    pub output: String,
    /// The crank angle where the working stroke begins, rad.
    pub start: f64,
    /// The working-stroke angle, rad.
    pub working_angle: f64,
    /// The time ratio working/idle.
    pub time_ratio: f64,
    /// The stroke (m) or swing (rad) and its unit.
    pub stroke: f64,
    /// "m" or "rad".
    pub stroke_unit: &'static str,
}

/// The smallest transmission angle of a group and the crank angle where it occurs, rad.
pub type Extreme = (f64, f64);

/// The structure of a linkage: what `tmm check` reports.
#[derive(Debug, Clone, PartialEq)]
pub struct Structure {
    /// The linkage's name.
    pub name: String,
    /// Mobility by Chebyshev's formula.
    pub mobility: i64,
    /// The input links (one, or two).
    pub inputs: Vec<InputInfo>,
    /// The groups in attachment order.
    pub groups: Vec<GroupInfo>,
    /// The range of the (first) crank.
    pub range: Range,
    /// With two inputs, each input's range with the other fixed at its reference value
    /// (first input, second); empty with one input.
    pub input_ranges: Vec<Range>,
    /// Grashof's class, where the linkage is a four-bar.
    pub grashof: Option<String>,
    /// The smallest transmission angle of each group and the crank angle there (rad), or why
    /// it is not available.
    pub transmission: Vec<(String, Result<Extreme, String>)>,
    /// The strokes of the described output, or why there are none; `None` without an output.
    pub strokes: Option<Result<StrokeInfo, String>>,
    /// The real assembly modes at the reference input(s), or why they were not counted.
    pub modes: Result<ModesInfo, String>,
}

/// The real assembly modes at the reference input(s) (`Plan::mode_counts`,
/// `Plan::assembly_modes`).
#[derive(Debug, Clone, PartialEq)]
pub struct ModesInfo {
    /// Per group in attachment order: its name, its number of modes on the engine's
    /// assembly of the groups before it, and how they were found.
    pub groups: Vec<(String, usize, String)>,
    /// The number of assemblies of the whole linkage, every combination of the groups'
    /// modes enumerated, or why it was not (a budget).
    pub total: Result<usize, String>,
    /// Whether every count is exact (no group fell back to a multistart search).
    pub exhaustive: bool,
}

/// Which positions to tabulate.
#[derive(Debug, Clone, PartialEq)]
pub enum Positions {
    /// The course project's positions: `n` from the start of the working stroke.
    Course(usize),
    /// `n` equally spaced positions over the input's range from the reference pose.
    Uniform(usize),
    /// The given input coordinates (degrees for a crank, m for a slider).
    At(Vec<f64>),
}

/// A column of a table: name, unit and values.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// Its name without the unit, for example `phi(crank)`.
    pub name: String,
    /// Its unit, for example `rad`; empty when the library gave none.
    pub unit: String,
    /// One value per row; NaN where not available (only the efficiency `eta`, where the
    /// drive gives no power).
    pub values: Vec<f64>,
}

/// The course table: columns of equal length, and the positions that failed.
#[derive(Debug, Clone, PartialEq)]
pub struct TableData {
    /// The linkage's name.
    pub name: String,
    /// The columns.
    pub columns: Vec<Column>,
    /// The input coordinate of each failed position (rad or m) and why it failed.
    pub failures: Vec<(f64, String)>,
    /// Crank or slider (for printing the failed positions' coordinates).
    pub input: InputKind,
    /// Which positions were chosen, and why (a fallback taken), for a reader.
    pub notes: Vec<String>,
    /// The input speed, rad/s (m/s for a slider).
    pub speed: f64,
}

impl TableData {
    /// The table with the first column (the input) and the columns whose names contain one
    /// of `texts`.
    ///
    /// # Errors
    /// A text that no column's name contains (a misspelt `--only`), naming it and listing
    /// the columns there are.
    pub fn only(mut self, texts: &[String]) -> Result<Self, Failure> {
        let names: Vec<&str> = self.columns.iter().map(|c| c.name.as_str()).collect();
        if let Some(unknown) = texts
            .iter()
            .find(|t| !names.iter().any(|n| n.contains(t.as_str())))
        {
            return Err(Failure::new(format!(
                "--only {unknown:?}: no column's name contains it; the columns are {}",
                names.join(", ")
            ))
            .hint("give a part of a column's name, for example --only Mb omega"));
        }
        let mut k = 0;
        self.columns.retain(|c| {
            k += 1;
            k == 1 || texts.iter().any(|t| c.name.contains(t.as_str()))
        });
        Ok(self)
    }

    /// The table with every angle (unit `rad`) in degrees (unit `deg`); rates stay in rad/s.
    #[must_use]
    pub fn in_degrees(mut self) -> Self {
        for c in &mut self.columns {
            if c.unit == "rad" {
                c.unit = "deg".to_owned();
                for v in &mut c.values {
                    *v = v.to_degrees();
                }
            }
        }
        self
    }
}

/// A diagram over the cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiagramKind {
    /// The output's position, velocity, acceleration.
    Kinematics,
    /// The output's transfer functions.
    Transfer,
    /// The balancing moment or force.
    Balance,
    /// Every joint's reaction magnitude.
    Reactions,
    /// The hodograph of the crank pin's reaction.
    Hodograph,
}

/// Which picture to draw.
#[derive(Debug, Clone, PartialEq)]
pub enum PictureKind {
    /// The kinematic scheme at the inputs (one coordinate per input, degrees or m; the
    /// reference pose when empty).
    Scheme(Vec<f64>),
    /// The plan in the course positions with the joints' paths.
    Plan,
    /// An animation of the cycle.
    Animation,
    /// The reactions as arrows at the inputs (as for the scheme).
    Forces(Vec<f64>),
    /// A diagram over the cycle.
    Diagram(DiagramKind),
    /// The workspace of a joint or named point of a linkage with two inputs.
    Workspace(String),
}

/// A picture and how a linkage with two inputs moves in it.
#[derive(Debug, Clone, PartialEq)]
pub struct PictureRequest {
    /// Which picture.
    pub kind: PictureKind,
    /// The input speed, rad/s (m/s for a slider).
    pub speed: f64,
    /// For two inputs: the path of the plan and the animation through these pairs of input
    /// coordinates (degrees or m), `[φ1, φ2, φ1, φ2, …]`; empty for a loop about the
    /// reference pose.
    pub along: Vec<f64>,
    /// The scheme with the instant centres of every pair of links.
    pub centres: bool,
}

/// What `tmm dynamics` is asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsRequest {
    /// The crank speed, rad/s (its sign the sense of rotation).
    pub speed: f64,
    /// Run the machine up from rest under a motor.
    pub run_up: bool,
    /// A linear motor M = a − b·|ω| in the sense of rotation, N·m and N·m·s/rad; `None` for
    /// the default motor.
    pub motor: Option<(f64, f64)>,
    /// A rotor or flywheel added to the crank, kg·m².
    pub rotor: f64,
    /// The coefficients of speed fluctuation to design flywheels for.
    pub flywheel: Vec<f64>,
    /// Positions over a turn (or the rocking range) for the reduced quantities; for two
    /// inputs, see `grid`.
    pub positions: usize,
    /// Two inputs: the nodes of the grid along each input.
    pub grid: usize,
    /// Two inputs: run from rest for this many seconds under the motors.
    pub run: Option<f64>,
    /// Two inputs: the motor of the second input, M = a − b·q̇₂.
    pub motor2: Option<(f64, f64)>,
    /// Two inputs: the half-width of the grid about the reference pose (degrees for a crank,
    /// m for a slider); `None` for 30° (a tenth of the linkage's size for a slider).
    pub span: Option<f64>,
}

/// The machine reduced to its crank at one angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReducedRow {
    /// The crank angle, rad.
    pub phi: f64,
    /// The angle turned from the first position in the sense of rotation, rad.
    pub turned: f64,
    /// J_red, kg·m².
    pub inertia: f64,
    /// dJ_red/dφ, kg·m².
    pub inertia_derivative: f64,
    /// M_red of the loads, N·m.
    pub loads: f64,
}

/// One turn of a run-up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnRow {
    /// Its start, s.
    pub t_start: f64,
    /// Its duration, s.
    pub period: f64,
    /// Mean, max and min speed, rad/s (magnitudes).
    pub omega_mean: f64,
    /// Max speed, rad/s.
    pub omega_max: f64,
    /// Min speed, rad/s.
    pub omega_min: f64,
    /// Coefficient of speed fluctuation.
    pub delta: f64,
}

/// The run-up from rest.
#[derive(Debug, Clone, PartialEq)]
pub struct RunUpReport {
    /// The motor: a and b of M = a − b·|ω|.
    pub motor: (f64, f64),
    /// Whether the motor was chosen by the program.
    pub default_motor: bool,
    /// The step, s.
    pub step: f64,
    /// The turns.
    pub turns: Vec<TurnRow>,
    /// Steps and right-hand-side evaluations.
    pub steps: usize,
    /// Evaluations.
    pub evaluations: usize,
    /// The most steps the run-up could take (a count from the description alone).
    pub budget: usize,
}

/// A flywheel for a coefficient of speed fluctuation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlywheelRow {
    /// δ.
    pub delta: f64,
    /// J_F by the energy–mass method, kg·m².
    pub inertia: f64,
    /// J_F by the simplified formula, kg·m².
    pub simplified: f64,
    /// ΔE, J.
    pub energy_range: f64,
    /// The constant driving moment, N·m.
    pub driving_moment: f64,
}

/// What `tmm dynamics` reports.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsReport {
    /// The linkage's name.
    pub name: String,
    /// The speed, rad/s.
    pub speed: f64,
    /// The rotor added to the crank, kg·m².
    pub rotor: f64,
    /// The lock angles of a rocking crank (rad, the smaller first): the reduced quantities
    /// are then over the range between them; `None` for a crank that turns fully.
    pub rocking: Option<(f64, f64)>,
    /// The reduced quantities over a turn, or over the rocking range.
    pub reduced: Vec<ReducedRow>,
    /// The run-up, when asked for.
    pub run_up: Option<RunUpReport>,
    /// The flywheels, when asked for.
    pub flywheels: Vec<FlywheelRow>,
}

/// The mass matrix of a linkage with two inputs at one pair of inputs: T = ½ q̇ᵀ A q̇.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassRow {
    /// The inputs' coordinates q₁, q₂ (rad or m).
    pub q: [f64; 2],
    /// A₁₁, A₁₂, A₂₂ (kg·m², kg·m or kg, by the inputs' kinds).
    pub a: [f64; 3],
    /// The generalized forces of the loads at rest, Q₁, Q₂ (N·m or N).
    pub loads: [f64; 2],
}

/// What `tmm dynamics` reports for a linkage with two inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct TwoInputDynamics {
    /// The linkage's name.
    pub name: String,
    /// The units of q₁ and q₂ ("rad" or "m").
    pub units: [&'static str; 2],
    /// The ranges of the grid, `[from, to]` of each input.
    pub ranges: [[f64; 2]; 2],
    /// The nodes along each input.
    pub n: usize,
    /// The nodes of the grid that assemble, the first input varying slowest.
    pub rows: Vec<MassRow>,
    /// The nodes that do not assemble.
    pub skipped: usize,
    /// The run from rest, when asked for.
    pub run: Option<TwoInputRun>,
}

/// A run of a linkage with two inputs from rest in its reference pose under two motors.
#[derive(Debug, Clone, PartialEq)]
pub struct TwoInputRun {
    /// The motors (a, b of M = a − b·q̇ on each input; zeros for none).
    pub motors: [(f64, f64); 2],
    /// The step of RK4, s.
    pub step: f64,
    /// Steps and right-hand-side evaluations.
    pub steps: usize,
    /// Evaluations.
    pub evaluations: usize,
    /// Each recorded row: t, q₁, q₂, q̇₁, q̇₂, T (J), and P (W) the power of the applied
    /// loads and motors less the dampers' losses.
    pub rows: Vec<[f64; 7]>,
    /// The work ∫ P dt by the trapezoidal rule, J.
    pub work: f64,
    /// Why the run ended before its time, if it did: a resistance or a joint's friction that
    /// holds the motion for good (the rows end there).
    pub stopped: Option<String>,
    /// Each stretch of the run where an input's own joint friction held it at rest while
    /// the other moved (in order of time).
    pub held: Vec<HeldInput>,
}

/// An input of a two-input run held at rest by the friction in its own joint (its pivot or
/// its slide) while the other input moves, and what held it: the load the held motion puts
/// on it, within the friction its joint can hold, where the hold begins and where it ends.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldInput {
    /// The input, 1 or 2.
    pub input: usize,
    /// Where it is held: rad for a crank, m for a slider.
    pub at: f64,
    /// When the hold begins and ends, s.
    pub from: f64,
    /// See [`from`](Self::from).
    pub until: f64,
    /// Whether it broke away at `until` (else the run ended with it held).
    pub released: bool,
    /// The loads that held it, where the system could weigh them (`None` where weighing a
    /// row of the hold failed: the hold is reported without them).
    pub loads: Option<HeldLoads>,
}

/// The loads on a held input at the first and last rows of its hold where the other input
/// moves.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldLoads {
    /// The times of those rows, s.
    pub weighed: [f64; 2],
    /// The load that would move the input there, along its rate (N·m or N).
    pub drive: [f64; 2],
    /// The friction its joint can hold against that load there (same unit, ≥ 0).
    pub breakaway: [f64; 2],
    /// The unit of the loads: "N·m" or "N".
    pub unit: &'static str,
}
