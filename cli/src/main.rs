//! `tmm`: the theory of machines and mechanisms at the command line. A planar linkage
//! described as a JSON file (the format: docs/linkage-format.md) is checked, analysed over
//! its course, drawn as SVG and run as a machine.
//!
//! The program is three layers: the arguments and the output (this file and `report.rs`),
//! the program's own plain data (`model.rs`), and the one adapter to the library
//! (`engine.rs`), which alone names the library's types.

mod budget;
mod bundled;
mod design;
mod engine;
mod json_path;
mod model;
mod report;
mod synth;

use std::io::{IsTerminal as _, Write as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{ArgGroup, Parser, Subcommand, ValueEnum};

use model::{DiagramKind, DynamicsRequest, Failure, PictureKind, PictureRequest, Positions};

const EXAMPLES: &str = "\
Examples:
  tmm check linkages/four-bar.json               structure, range, Grashof, transmission angle
  tmm analyse linkages/shaper.json               the 12 course positions, every unit named
  tmm analyse shaper --at 0 45 90 --speed 6      a bundled file by its name, at three angles
  tmm analyse shaper --format csv > shaper.csv   the table for a spreadsheet
  tmm draw linkages/watt-six-bar.json --animate -o watt.svg
  tmm dynamics linkages/mechanism-compressor.json --run-up --flywheel 0.05
  tmm bundled                                    the descriptions built into tmm
  tmm synth shaper --stroke 0.3 -K 1.6 --centre-distance 0.25 -o my-shaper.json

A FILE that does not exist is looked up among the bundled descriptions (`tmm bundled`).
Units are SI (m, kg, s, N, N·m, rad) except where an option says degrees. A long run shows
its progress on a terminal (nothing when piped). Every run is bounded by counts taken from
the command and the file, never by the clock, so a command gives the same output on any
machine; one above its bound is refused before it starts, naming the option
(`tmm dynamics --help` states the bounds).";

/// The theory of machines and mechanisms at the command line: check, analyse, draw and run a
/// planar linkage described as a JSON file (format: docs/linkage-format.md).
#[derive(Parser)]
#[command(name = "tmm", version, after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The structure: mobility, Assur groups in attachment order, the crank's range (full turn,
    /// or rocking between lock angles), Grashof's class of a four-bar, the smallest
    /// transmission angle of each group, the output's strokes.
    #[command(after_help = "\
Examples:
  tmm check linkages/four-bar.json
  tmm check linkages/shaper.json --format json")]
    Check {
        /// The description file (JSON), or the name of a bundled one.
        file: String,
        /// The format on standard output.
        #[arg(long, value_enum, default_value_t = Report::Text)]
        format: Report,
    },

    /// The course table: positions, velocities and accelerations of every link and joint,
    /// the reaction in every joint and the balancing moment beside its value by virtual power,
    /// every column with its unit.
    #[command(
        group(ArgGroup::new("which").args(["positions", "course", "at"])),
        override_usage = "tmm analyse <FILE> [OPTIONS]",
        after_help = "\
Examples:
  tmm analyse linkages/shaper.json                   12 positions from the working stroke
  tmm analyse linkages/four-bar.json --positions 36  every 10° from the reference pose
  tmm analyse linkages/four-bar.json --at 0 90 180 --speed -5 --degrees
  tmm analyse linkages/shaper.json --format json
  tmm analyse linkages/shaper.json --only Mb omega --degrees
  tmm analyse linkages/shaper.json --csv shaper.csv
  tmm analyse linkages/five-bar-robot.json --at 120 60 110 70   two inputs: pairs φ1 φ2

Rows of the text table are quantities, columns positions. A position where the linkage cannot
be solved (a dead point, a pose that does not assemble) is left out with a warning on stderr.
With friction in the joints the table adds the power lost in each joint, their sum, the
drive's power and the instantaneous efficiency eta; eta has no value where the drive gives no
power (a dash, an empty CSV cell, null in JSON). Every other value is a number."
    )]
    Analyse {
        /// The description file (JSON), or the name of a bundled one.
        file: String,
        /// N positions equally spaced over the crank's turn from the reference pose (a crank
        /// that rocks: from lock to lock and back, the locks included; a slider: inside its
        /// travel); at most 100 000 (and 4·10⁸ / w for a linkage whose solve weighs
        /// w dyad solves: see `tmm dynamics --help`).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
        positions: Option<u32>,
        /// The 12 positions of a course project, from the start of the output's working
        /// stroke (the default).
        #[arg(long)]
        course: bool,
        /// The positions at these input angles, degrees (metres for a slider input); for a
        /// linkage with two inputs, pairs φ1 φ2.
        #[arg(long, value_name = "φ", num_args = 1.., allow_negative_numbers = true,
              value_parser = number_after_file)]
        at: Vec<f64>,
        /// The input speed ω, rad/s (negative: clockwise); the file's `speed` by default.
        #[arg(long, value_name = "ω", allow_negative_numbers = true)]
        speed: Option<f64>,
        /// Also write the table as CSV to this file.
        #[arg(long, value_name = "OUT")]
        csv: Option<PathBuf>,
        /// Only the columns whose names contain one of these texts (and the input's), for
        /// example `--only Mb omega`.
        #[arg(long, value_name = "TEXT", num_args = 1..)]
        only: Vec<String>,
        /// Angles (φ, transmission angles) in degrees; rates stay in rad/s and rad/s².
        #[arg(long)]
        degrees: bool,
        /// The format on standard output.
        #[arg(long, value_enum, default_value_t = Format::Table)]
        format: Format,
    },

    /// A picture as SVG: the kinematic scheme at a position (the default), the plan in the 12
    /// course positions with the paths of the joints, an animation of the cycle, the reactions
    /// as arrows, a diagram over the cycle, or the workspace of a point (two inputs).
    #[command(
        group(ArgGroup::new("picture")
            .args(["scheme", "plan", "animate", "forces", "diagram", "workspace"])),
        override_usage = "tmm draw <FILE> [--scheme [φ..] | --plan | --animate | --forces [φ..] | \
                          --diagram [KIND] | --workspace POINT] [OPTIONS] [-o OUT.svg]",
        after_help = "\
Examples:
  tmm draw linkages/shaper.json -o shaper.svg                 the scheme in the reference pose
  tmm draw linkages/shaper.json --scheme 60 -o shaper-60.svg  the scheme at φ = 60°
  tmm draw linkages/watt-six-bar.json --plan -o plan.svg
  tmm draw linkages/watt-six-bar.json --animate -o watt.svg   open it in a browser
  tmm draw linkages/four-bar.json --forces 30 -o forces.svg
  tmm draw linkages/four-bar.json --scheme 30 --centres -o centres.svg   instant centres
  tmm draw linkages/shaper.json --diagram kinematics -o ram.svg
  tmm draw linkages/peaucellier-lipkin.json --plan -o straight.svg   a rocking crank's range
  tmm draw linkages/five-bar-robot.json --scheme 110 70 -o robot.svg  two inputs: φ1 φ2
  tmm draw linkages/five-bar-robot.json --workspace B -o reach.svg
  tmm draw linkages/five-bar-robot.json --animate --along 120 60 90 60 90 90 -o path.svg
  tmm draw linkages/five-bar-robot.json --diagram balance --along 120 60 90 90 -o mb.svg

A linkage with two inputs is drawn at pairs φ1 φ2; its plan, animation and diagrams follow
a loop about the reference pose, or the path through the pairs of --along (a diagram's
abscissa is the length along that path in the plane of the inputs, and its balance diagram
plots both balancing moments M_b1 and M_b2). A rocking crank's plan,
animation and diagrams run between its lock angles."
    )]
    Draw {
        /// The description file (JSON), or the name of a bundled one.
        file: String,
        /// The kinematic scheme at the input angle φ, degrees (metres for a slider input; the
        /// reference pose without one); two values φ1 φ2 for a linkage with two inputs.
        #[arg(long, value_name = "φ", num_args = 0..=2, allow_negative_numbers = true,
              value_parser = number_after_file)]
        scheme: Option<Vec<f64>>,
        /// The scheme with the instant centres of every pair of links (Aronhold–Kennedy),
        /// labelled by the links' places in the file's `links` (I13: the 1st and 3rd written,
        /// counting from 0), with a key of the links' names.
        #[arg(long, conflicts_with_all = ["plan", "animate", "forces", "diagram", "workspace"])]
        centres: bool,
        /// The plan: the 12 course positions overlaid, the extreme positions bold, the paths of
        /// the joints and named points.
        #[arg(long)]
        plan: bool,
        /// An animation of the cycle (SMIL; plays in a browser).
        #[arg(long)]
        animate: bool,
        /// The reaction in every joint as an arrow, at the input angle φ, degrees (metres for a
        /// slider input; the reference pose without one); φ1 φ2 for two inputs.
        #[arg(long, value_name = "φ", num_args = 0..=2, allow_negative_numbers = true,
              value_parser = number_after_file)]
        forces: Option<Vec<f64>>,
        /// A diagram over the cycle (balance without a KIND); for two inputs, along their
        /// path (see --along).
        #[arg(long, visible_alias = "diagrams", value_enum, value_name = "KIND", num_args = 0..=1, default_missing_value = "balance")]
        diagram: Option<DiagramArg>,
        /// The region a joint or named point reaches as two inputs move (each crank over a
        /// whole turn), its outline and the singular curves.
        #[arg(long, value_name = "POINT")]
        workspace: Option<String>,
        /// Two inputs: the plan, the animation and the diagrams along the path through these
        /// pairs of input coordinates φ1 φ2 (degrees; metres for a slider), by straight steps.
        #[arg(long, value_name = "φ1 φ2", num_args = 1.., allow_negative_numbers = true,
              value_parser = number_after_file)]
        along: Vec<f64>,
        /// The input speed ω, rad/s (negative: clockwise); the file's `speed` by default. Not
        /// with --workspace, which is the region of positions.
        #[arg(long, value_name = "ω", allow_negative_numbers = true)]
        speed: Option<f64>,
        /// The SVG file to write (without it, standard output when that is a pipe or a
        /// file; refused on a terminal).
        #[arg(short, long, value_name = "OUT.svg")]
        output: Option<PathBuf>,
    },

    /// The linkage as a machine reduced to its crank: the reduced moment of inertia and moment
    /// over a turn (or a rocking crank's range), the run-up from rest under a motor to the
    /// steady state, and the flywheel for a coefficient of speed fluctuation δ; for two
    /// inputs, the mass matrix over a grid of the inputs.
    #[command(
        override_usage = "tmm dynamics <FILE> [OPTIONS]",
        after_help = "\
Examples:
  tmm dynamics linkages/watt-six-bar.json
  tmm dynamics linkages/mechanism-compressor.json --flywheel 0.05 0.02
  tmm dynamics linkages/four-bar.json --run-up --motor 60,2 --rotor 0.05
  tmm dynamics linkages/shaper.json --csv reduced.csv
  tmm dynamics linkages/watt-six-bar.json --flywheel 0.05 --format json
  tmm dynamics linkages/peaucellier-lipkin.json      a rocking crank: between its lock angles
  tmm dynamics linkages/five-bar-robot.json --grid 7 --span 20   two inputs: A(q) on 7 × 7
  tmm dynamics linkages/five-bar-robot.json --run 0.5 --motor 0.2,0.05 --motor2 -0.1,0.05

A rocking crank has the reduced quantities over its range between the lock angles (at the
locks J_red is unbounded: the positions are the middles of equal steps between them); it has
no turn to run up or to even out with a flywheel. A linkage with two inputs has its mass
matrix A(q) (T = ½ q̇ᵀ A q̇) and the loads' generalized forces over a grid of the inputs,
and with --run the motion from rest under two motors, with the energy balance.

Without --motor the run-up uses an induction motor chosen from the machine: 4 % slip at the
speed asked for, and a nominal moment 10 % above the loads' mean (or a tenth of their peak,
for a machine whose loads average out). The step keeps RK4 well inside its stability limit.

Bounds, counted from the command and the file (never the clock, so the output is the same
on a quiet machine and a loaded one): a run-up takes RK4 steps of 1° of a turn at its top
speed (shorter where the motor's damping needs) and at most min(10⁶, 10⁸ / w) of them,
where w is the work of one solve of the linkage in solves of a dyad — 1 for each input and
each dyad, 16 for a triad, (2n)³/4 for a general group of n inner joints: 10⁶ for a
four-bar, 230 946 for the double butterfly (w = 433). A run of two inputs has the same
bound. Every other stage (the reduced quantities, each flywheel's 3 600 positions, the
grid) makes at most 4·10⁸ / w solves. A run or a stage that would need more is refused
before it starts, naming the option to change and the bound."
    )]
    Dynamics {
        /// The description file (JSON), or the name of a bundled one.
        file: String,
        /// Run the machine up from rest to its steady state (RK4).
        #[arg(long)]
        run_up: bool,
        /// Design the flywheel for these coefficients of speed fluctuation δ (0 < δ < 2).
        #[arg(long, value_name = "δ", num_args = 1.., allow_negative_numbers = true,
              value_parser = number_after_file)]
        flywheel: Vec<f64>,
        /// One input: the crank speed ω, rad/s (negative: clockwise); the file's `speed` by
        /// default.
        #[arg(long, value_name = "ω", allow_negative_numbers = true)]
        speed: Option<f64>,
        /// The motor of the run-up (with --run-up; for two inputs, of the first input with
        /// --run), M = a − b·|ω| in the sense of rotation: a in N·m, b in N·m·s/rad.
        #[arg(long, value_name = "a,b", value_parser = parse_pair, allow_hyphen_values = true)]
        motor: Option<(f64, f64)>,
        /// A rotor or flywheel on the crank, kg·m².
        #[arg(
            long,
            value_name = "J",
            default_value_t = 0.0,
            allow_negative_numbers = true
        )]
        rotor: f64,
        /// One input: positions over a turn (or a rocking crank's range) for the reduced
        /// quantities, 360 by default; at least 12, so that their means over the turn are
        /// means, not one or two samples.
        #[arg(long, value_name = "N",
              value_parser = clap::value_parser!(u32).range(12..=100_000))]
        positions: Option<u32>,
        /// Two inputs: the nodes of the grid along each input, 13 by default.
        #[arg(long, value_name = "N",
              value_parser = clap::value_parser!(u32).range(2..=401))]
        grid: Option<u32>,
        /// Two inputs: run from rest in the reference pose for T seconds under the motors
        /// (--motor on input 1, --motor2 on input 2, M = a − b·q̇, signed) and the loads (RK4).
        #[arg(long, value_name = "T", allow_negative_numbers = true)]
        run: Option<f64>,
        /// Two inputs: the motor of the second input, M = a − b·q̇₂: a in N·m, b in
        /// N·m·s/rad.
        #[arg(long, value_name = "a,b", value_parser = parse_pair, allow_hyphen_values = true)]
        motor2: Option<(f64, f64)>,
        /// Two inputs: the grid's half-width about the reference pose, degrees (metres for a
        /// slider input); 30° (a tenth of the linkage's size for a slider) by default.
        #[arg(long, value_name = "Δ", allow_negative_numbers = true)]
        span: Option<f64>,
        /// The format on standard output.
        #[arg(long, value_enum, default_value_t = Report::Text)]
        format: Report,
        /// Also write the reduced quantities over the turn as CSV to this file.
        #[arg(long, value_name = "OUT")]
        csv: Option<PathBuf>,
    },

    /// From a requirement to a linkage: a crank-rocker, an offset slider-crank or a shaper by
    /// the time ratio K and the stroke; a crank-rocker through given positions; a function
    /// generator; a path generator. Writes the description and reports what it achieves.
    #[command(after_help = synth::EXAMPLES)]
    Synth {
        #[command(subcommand)]
        kind: synth::SynthKind,
    },

    /// The descriptions built into tmm; with a NAME, print that description's JSON.
    #[command(after_help = "\
Examples:
  tmm bundled
  tmm bundled shaper > my-shaper.json")]
    Bundled {
        /// A bundled description's name.
        name: Option<String>,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum Format {
    /// Aligned text, one line per quantity.
    Table,
    /// Comma-separated values, one line per position.
    Csv,
    /// JSON: columns with names, units and values.
    Json,
}

#[derive(Clone, Copy, ValueEnum)]
enum Report {
    /// Text for a person.
    Text,
    /// JSON for a program.
    Json,
}

#[derive(Clone, Copy, ValueEnum)]
enum DiagramArg {
    /// The output's position, velocity and acceleration.
    Kinematics,
    /// The output's transfer functions.
    Transfer,
    /// The balancing moment (or force).
    Balance,
    /// The magnitude of every joint's reaction.
    Reactions,
    /// The hodograph of the crank pin's reaction.
    Hodograph,
}

/// clap's message for a mistake on the command line, on one line: its text before the usage
/// and the pointer to the help, without the `error:` label.
fn usage_error_line(text: &str) -> String {
    let lines: Vec<&str> = text
        .lines()
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    lines.join(" ").trim_start_matches("error: ").to_owned()
}

/// A number of an option that takes several (`--forces φ`, `--at φ…`): these options come
/// after the description file, or they would read its name as one of their numbers.
fn number_after_file(s: &str) -> Result<f64, String> {
    s.trim().parse::<f64>().map_err(|_| {
        format!(
            "\"{s}\" is not a number; the description file comes first, before the options \
             that take numbers (tmm draw FILE --forces φ -o OUT.svg)"
        )
    })
}

/// "60,2" → (60, 2).
fn parse_pair(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected two numbers a,b, got \"{s}\""))?;
    let num = |t: &str| {
        t.trim()
            .parse::<f64>()
            .map_err(|e| format!("\"{t}\" is not a number: {e}"))
    };
    Ok((num(a)?, num(b)?))
}

/// A failure of the program on one file: printed as one line.
struct Fail {
    file: Option<String>,
    failure: Failure,
}

impl Fail {
    fn on(file: &str, failure: Failure) -> Self {
        Self {
            file: Some(file.to_owned()),
            failure,
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            eprintln!("tmm: {} (tmm --help)", usage_error_line(&e.to_string()));
            return ExitCode::from(2);
        }
        Err(e) => e.exit(),
    };
    let result = run(cli.command);
    clear_progress();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            let mut line = String::from("tmm: ");
            if let Some(file) = &f.file {
                line.push_str(file);
                line.push_str(": ");
            }
            line.push_str(&f.failure.message);
            if let Some(hint) = &f.failure.hint {
                line.push_str(" (");
                line.push_str(hint);
                line.push(')');
            }
            eprintln!("{line}");
            ExitCode::FAILURE
        }
    }
}

/// An I/O error in words, without the operating system's error number.
fn io_text(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file or directory".to_owned(),
        std::io::ErrorKind::PermissionDenied => "permission denied".to_owned(),
        std::io::ErrorKind::IsADirectory => "it is a directory".to_owned(),
        _ => e.to_string(),
    }
}

/// The largest description file read, bytes. A description of a thousand links is about
/// 300 kB; a larger file is not a description, and is refused before it is read.
const MAX_FILE_BYTES: u64 = 16 * 1024 * 1024;

/// A size in bytes for a person: "50.0 MB", "812 kB", "312 bytes".
fn size_text(bytes: u64) -> String {
    #[allow(clippy::cast_precision_loss)]
    let b = bytes as f64;
    if bytes >= 1024 * 1024 {
        format!("{:.1} MB", b / (1024.0 * 1024.0))
    } else if bytes >= 1024 {
        format!("{:.0} kB", b / 1024.0)
    } else {
        format!("{bytes} bytes")
    }
}

/// The description's text: the file, or a bundled description of that name. A directory, a
/// device or a socket is refused, and so is a file above [`MAX_FILE_BYTES`] — by its size
/// before it is read, or (a pipe) once that many bytes have come.
fn read(file: &str) -> Result<String, Fail> {
    use std::io::Read as _;
    if file.is_empty() {
        return Err(Fail {
            file: None,
            failure: Failure::new("the description file's name is empty")
                .hint("give a path to a JSON file, or a name from `tmm bundled`"),
        });
    }
    let fail = |message: String| Fail::on(file, Failure::new(message));
    let meta = match std::fs::metadata(file) {
        Ok(meta) => meta,
        Err(e) => {
            return match bundled::find(file) {
                Some(text) if !Path::new(file).exists() => Ok(text.to_owned()),
                _ => Err(Fail::on(
                    file,
                    Failure::new(format!("cannot read the file: {}", io_text(&e)))
                        .hint("`tmm bundled` lists the descriptions built into tmm"),
                )),
            };
        }
    };
    if meta.is_dir() {
        return Err(Fail::on(
            file,
            Failure::new("it is a directory, and a description is a JSON file")
                .hint("give a file in it, or a name from `tmm bundled`"),
        ));
    }
    if !meta.is_file() && !is_pipe(&meta) {
        return Err(fail(
            "it is not a file but a device or a socket, and a description is a JSON file"
                .to_owned(),
        ));
    }
    let too_large = |size: &str| {
        Fail::on(
            file,
            Failure::new(format!(
                "the file is {size}, above the {} a description may have",
                size_text(MAX_FILE_BYTES)
            ))
            .hint("a description is a JSON object of links and joints: a few kB"),
        )
    };
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(&format!(
            "{} ({} bytes)",
            size_text(meta.len()),
            meta.len()
        )));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(file)
        .and_then(|f| f.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| fail(format!("cannot read the file: {}", io_text(&e))))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(&format!(
            "more than {}",
            size_text(MAX_FILE_BYTES)
        )));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        fail(format!(
            "the file is not UTF-8 text (its byte {}, counting from 1, is not), and a \
             description is JSON",
            e.utf8_error().valid_up_to() + 1
        ))
    })?;
    // A byte-order mark (an editor's on Windows) is no part of the JSON.
    let text = match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_owned(),
        None => text,
    };
    if text.trim().is_empty() {
        return Err(Fail::on(
            file,
            Failure::new("the file is empty, and a description is a JSON object")
                .hint("`tmm bundled shaper > my.json` writes one to start from"),
        ));
    }
    Ok(text)
}

/// Whether `meta` is a pipe (`tmm check /dev/stdin < my.json`, a process substitution).
#[cfg(unix)]
fn is_pipe(meta: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::FileTypeExt as _;
    meta.file_type().is_fifo()
}

#[cfg(not(unix))]
fn is_pipe(_: &std::fs::Metadata) -> bool {
    false
}

fn load(file: &str) -> Result<engine::Machine, Fail> {
    let text = read(file)?;
    // JSON's reader takes an array for an object (its fields in order), and would say that
    // `[1, 2]` lacks a string where the name goes: say what a description is instead.
    if let Some(first) = text.trim_start().chars().next()
        && first != '{'
    {
        return Err(Fail::on(
            file,
            Failure::new(format!(
                "the file begins with `{first}`, and a description is a JSON object, \
                 {{\"name\": …, \"joints\": […], \"links\": […], \"input\": {{…}}}}"
            ))
            .hint("`tmm bundled shaper > my.json` writes one to start from; the format is in docs/linkage-format.md"),
        ));
    }
    engine::load(&text).map_err(|f| Fail::on(file, f))
}

/// Writes to standard output; a closed pipe (`tmm … | head`) ends the program quietly.
fn print(text: &str) {
    let mut out = std::io::stdout().lock();
    if out
        .write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .is_err()
    {
        std::process::exit(0);
    }
}

/// Refuses, before any work, a file to write that cannot be: a directory, or a file in a
/// directory that does not exist.
fn check_output(path: Option<&Path>) -> Result<(), Fail> {
    let Some(path) = path else { return Ok(()) };
    let fail = |message: String, hint: &str| Fail {
        file: Some(path.display().to_string()),
        failure: Failure::new(message).hint(hint),
    };
    if path.is_dir() {
        return Err(fail(
            "cannot write the file: it is a directory".to_owned(),
            "give the name of a file in it",
        ));
    }
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(fail(
            format!(
                "cannot write the file: the directory {} does not exist",
                dir.display()
            ),
            "make the directory first, or write into one that exists",
        )),
        _ => Ok(()),
    }
}

fn write_file(path: &Path, text: &str) -> Result<(), Fail> {
    std::fs::write(path, text).map_err(|e| Fail {
        file: Some(path.display().to_string()),
        failure: Failure::new(format!("cannot write the file: {}", io_text(&e))),
    })
}

/// Progress of a long run, on a terminal only, on one line that the next overwrites.
fn progress(what: &str) {
    let err = std::io::stderr();
    if err.is_terminal() {
        let _ = write!(err.lock(), "\r\x1b[Ktmm: {what}…");
    }
}

/// Clears the progress line, so that an error is the one line on stderr.
fn clear_progress() {
    let err = std::io::stderr();
    if err.is_terminal() {
        let _ = write!(err.lock(), "\r\x1b[K");
    }
}

fn run(command: Command) -> Result<(), Fail> {
    match command {
        Command::Check { file, format } => {
            let m = load(&file)?;
            // The range's search and the transmission angles' scans: seconds for a large
            // linkage (within the budget of crate::budget).
            progress("the input's range, transmission angles and strokes");
            let s = m.structure();
            clear_progress();
            print(&match format {
                Report::Text => report::structure(&s),
                Report::Json => report::structure_json(&s),
            });
        }
        Command::Analyse {
            file,
            positions,
            course: _,
            at,
            speed,
            csv,
            only,
            degrees,
            format,
        } => {
            check_output(csv.as_deref())?;
            let m = load(&file)?;
            let which = match positions {
                Some(n) => Positions::Uniform(n as usize),
                None if !at.is_empty() => Positions::At(at),
                None => Positions::Course(12),
            };
            let speed = speed.unwrap_or_else(|| m.default_speed());
            let table = m.table(&which, speed, &mut progress);
            clear_progress();
            let mut table = table.map_err(|f| Fail::on(&file, f))?;
            if degrees {
                table = table.in_degrees();
            }
            if !only.is_empty() {
                table = table.only(&only).map_err(|f| Fail::on(&file, f))?;
            }
            for (input, e) in &table.failures {
                eprintln!(
                    "tmm: warning: {file}: position at {} left out: {e}",
                    report::input_text(table.input, *input)
                );
            }
            if let Some(path) = &csv {
                write_file(path, &report::table_csv(&table))?;
            }
            print(&match format {
                Format::Table => report::table_text(&table),
                Format::Csv => report::table_csv(&table),
                Format::Json => report::table_json(&table),
            });
        }
        Command::Draw {
            file,
            scheme,
            centres,
            plan,
            animate,
            forces,
            diagram,
            workspace,
            along,
            speed,
            output,
        } => {
            check_output(output.as_deref())?;
            // Some hundred kilobytes of SVG are no use on a terminal (and can upset it): a
            // picture goes to a file, or to a pipe or redirection that asked for it.
            if output.is_none() && std::io::stdout().is_terminal() {
                return Err(Fail::on(
                    &file,
                    Failure::new("an SVG picture is not written to the terminal")
                        .hint("give -o OUT.svg to write it to a file, or redirect: > out.svg"),
                ));
            }
            let m = load(&file)?;
            refuse_unused(
                &file,
                &[(
                    "--speed",
                    workspace.is_some() && speed.is_some(),
                    "does not change a workspace, the region of positions a point reaches",
                    "leave --speed out",
                )],
            )?;
            let picture = picture_kind(scheme, plan, animate, forces, diagram, workspace);
            let request = PictureRequest {
                kind: picture,
                speed: speed.unwrap_or_else(|| m.default_speed()),
                along,
                centres,
            };
            let svg = m.draw(&request, &mut progress);
            clear_progress();
            let svg = svg.map_err(|f| Fail::on(&file, f))?;
            match output {
                Some(path) => write_file(&path, &svg)?,
                None => print(&svg),
            }
        }
        Command::Dynamics {
            file,
            run_up,
            flywheel,
            speed,
            motor,
            rotor,
            positions,
            grid,
            span,
            run,
            motor2,
            format,
            csv,
        } => {
            check_output(csv.as_deref())?;
            let m = load(&file)?;
            let request = DynamicsRequest {
                speed: speed.unwrap_or_else(|| m.default_speed()),
                run_up,
                motor,
                rotor,
                flywheel,
                positions: positions.unwrap_or(360) as usize,
                grid: grid.unwrap_or(13) as usize,
                span,
                run,
                motor2,
            };
            let (one, two) = (m.input_count() == 1, m.input_count() == 2);
            refuse_unused(
                &file,
                &[
                    (
                        "--positions",
                        two && positions.is_some(),
                        "sets the positions over a turn of a linkage with one input, and this \
                         one has two inputs",
                        "--grid N sets the nodes of its grid",
                    ),
                    (
                        "--speed",
                        two && speed.is_some(),
                        "is the speed of a linkage with one input, and this one has two inputs, \
                         whose mass matrix is the same at every speed and whose run (--run) \
                         starts from rest",
                        "leave --speed out",
                    ),
                    (
                        "--motor",
                        two && motor.is_some() && run.is_none(),
                        "drives the first input during --run T, and no run was asked for",
                        "add --run T, in seconds",
                    ),
                    (
                        "--motor2",
                        two && motor2.is_some() && run.is_none(),
                        "drives the second input during --run T, and no run was asked for",
                        "add --run T, in seconds",
                    ),
                    (
                        "--motor",
                        one && motor.is_some() && !run_up,
                        "is the motor of the run-up, and no run-up was asked for",
                        "add --run-up",
                    ),
                    (
                        "--grid",
                        one && grid.is_some(),
                        "applies to a linkage with two inputs (the grid of its mass matrix), and \
                         this one has one input",
                        "--positions N sets the positions over its turn",
                    ),
                    (
                        "--span",
                        one && span.is_some(),
                        "applies to a linkage with two inputs (the half-width of its grid), and \
                         this one has one input",
                        "leave --span out",
                    ),
                    (
                        "--run",
                        one && run.is_some(),
                        "applies to a linkage with two inputs, and this one has one input",
                        "a machine with one input runs from rest with --run-up",
                    ),
                    (
                        "--motor2",
                        one && motor2.is_some(),
                        "drives the second input, and this linkage has one input",
                        "a machine with one input runs from rest with --run-up and --motor",
                    ),
                ],
            )?;
            dynamics(&file, &m, &request, format, csv.as_deref())?;
        }
        Command::Synth { kind } => synth::run(kind)?,
        Command::Bundled { name } => match name {
            Some(name) => match bundled::find(&name) {
                Some(text) => print(text),
                None => {
                    return Err(Fail {
                        file: None,
                        failure: Failure::new(format!(
                            "no bundled description is called \"{name}\""
                        ))
                        .hint("`tmm bundled` lists them"),
                    });
                }
            },
            None => {
                let mut o = String::new();
                for (name, text) in bundled::FILES {
                    let what = match engine::load(text) {
                        Ok(m) => summary(&m),
                        Err(f) => format!("(does not load: {})", f.message),
                    };
                    o.push_str(&format!("{name:<28} {what}\n"));
                }
                o.push_str(
                    "\nUse a name in place of FILE (`tmm check shaper`), or save one to edit: \
                     `tmm bundled shaper > my.json`.\n",
                );
                print(&o);
            }
        },
    }
    Ok(())
}

/// `tmm dynamics`: the machine reduced to its crank, or the mass matrix and run of a linkage
/// with two inputs, printed in `format` (and the table written as CSV to `csv`).
fn dynamics(
    file: &str,
    m: &engine::Machine,
    request: &DynamicsRequest,
    format: Report,
    csv: Option<&Path>,
) -> Result<(), Fail> {
    if m.input_count() == 2 {
        let d = m.dynamics_two(request, &mut progress);
        clear_progress();
        let d = d.map_err(|f| Fail::on(file, f))?;
        if let Some(path) = csv {
            write_file(path, &report::mass_matrix_csv(&d))?;
        }
        print(&match format {
            Report::Text => report::mass_matrix(&d),
            Report::Json => report::mass_matrix_json(&d),
        });
        return Ok(());
    }
    let d = m.dynamics(request, &mut progress);
    clear_progress();
    let d = d.map_err(|f| Fail::on(file, f))?;
    if let Some(path) = csv {
        write_file(path, &report::reduced_csv(&d))?;
    }
    print(&match format {
        Report::Text => report::dynamics(&d),
        Report::Json => report::dynamics_json(&d),
    });
    Ok(())
}

/// Refuses the first option given where it would change nothing (it would be silently
/// ignored, its value unchecked): each entry is the option, whether it is given in vain, why
/// it changes nothing, and what to do instead.
fn refuse_unused(file: &str, options: &[(&str, bool, &str, &str)]) -> Result<(), Fail> {
    match options.iter().find(|o| o.1) {
        Some(&(option, _, why, fix)) => Err(Fail::on(
            file,
            Failure::new(format!("{option} {why}")).hint(fix),
        )),
        None => Ok(()),
    }
}

/// The picture the options of `tmm draw` ask for (clap lets one at most through).
fn picture_kind(
    scheme: Option<Vec<f64>>,
    plan: bool,
    animate: bool,
    forces: Option<Vec<f64>>,
    diagram: Option<DiagramArg>,
    workspace: Option<String>,
) -> PictureKind {
    if let Some(point) = workspace {
        PictureKind::Workspace(point)
    } else if plan {
        PictureKind::Plan
    } else if animate {
        PictureKind::Animation
    } else if let Some(at) = forces {
        PictureKind::Forces(at)
    } else if let Some(d) = diagram {
        PictureKind::Diagram(match d {
            DiagramArg::Kinematics => DiagramKind::Kinematics,
            DiagramArg::Transfer => DiagramKind::Transfer,
            DiagramArg::Balance => DiagramKind::Balance,
            DiagramArg::Reactions => DiagramKind::Reactions,
            DiagramArg::Hodograph => DiagramKind::Hodograph,
        })
    } else {
        PictureKind::Scheme(scheme.unwrap_or_default())
    }
}

/// One line about a planned linkage: its name and groups.
fn summary(m: &engine::Machine) -> String {
    let s = m.structure_brief();
    format!("{} — {}", s.0, s.1)
}
