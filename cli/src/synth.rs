//! `tmm synth`: the arguments of each kind of synthesis, the points file of path generation,
//! and where the description and the report go.

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

use crate::design::{Function, FunctionRequest, Kind, PathMechanism, PathRequest, Request, Timing};
use crate::model::Failure;
use crate::{clear_progress, engine, print, progress, report, write_file, Fail};

pub const EXAMPLES: &str = "\
Examples:
  tmm synth crank-rocker -K 1.25 --swing 45 --rocker 0.3 -o crank-rocker.json
  tmm synth slider-crank --stroke 0.2 -K 1.2 -o slider-crank.json
  tmm synth shaper --stroke 0.3 -K 1.6 --centre-distance 0.25 -o my-shaper.json
  tmm synth through --frame 0.4 --at 40,101.4 100,112.8 160,131.8 --min-transmission 0 -o through.json
  tmm synth function --function log10 --x 1,2 --crank -30,30 --rocker 0,90 --frame 0.1 -o log.json
  tmm synth path points.csv --seed 7 --budget 20000 -o path.json
  tmm synth six-bar timed.csv --min-transmission 17 --budget 400000 -o six-bar.json
  tmm check crank-rocker.json                    the engine's check of a design

Each kind writes the synthesised description (JSON, -o FILE) and prints its report: the
dimensions, K, the stroke or swing, the smallest transmission angle γ_min, Grashof's class,
the engine's check of the description written, and the misses at the requirement's points.
Without -o the description goes to standard output and the report to standard error, so
`tmm synth … > design.json` saves the one and shows the other.
Lengths in m, angles in degrees. A requirement no mechanism of the kind meets is one line on
stderr naming the parameter and by how much it misses, exit code 1.";

/// The options every kind takes.
#[derive(Args)]
pub struct Common {
    /// Write the description (JSON) to this file; the report then goes to standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// The smallest transmission angle the mechanism must keep, degrees (0: no requirement).
    #[arg(
        long,
        value_name = "γ",
        default_value_t = 40.0,
        allow_negative_numbers = true
    )]
    min_transmission: f64,
}

/// The kinds of synthesis.
#[derive(Subcommand)]
pub enum SynthKind {
    /// A crank-rocker from the time ratio K, the rocker's swing ψ and its length; the frame
    /// O1O3 given, or chosen where the smallest transmission angle is largest.
    #[command(after_help = "\
Examples:
  tmm synth crank-rocker -K 1.25 --swing 45 --rocker 0.3 -o crank-rocker.json
  tmm synth crank-rocker -K 1.25 --swing 45 --rocker 0.3 --frame 0.4 --min-transmission 30 -o longer.json

K = t_work/t_idle > 1: the crank turns 180° + θ during the working stroke and 180° − θ during
the idle one, θ = 180°(K − 1)/(K + 1). The crank's pivot lies on a circle through the
rocker's extreme positions; --frame picks the point at that distance from the rocker's pivot.")]
    CrankRocker {
        /// K, the time ratio of the rocker's strokes (> 1).
        #[arg(
            short = 'K',
            long = "time-ratio",
            value_name = "K",
            allow_negative_numbers = true
        )]
        time_ratio: f64,
        /// ψ, the rocker's swing between its extreme positions, degrees (0 < ψ < 180).
        #[arg(long, value_name = "ψ", allow_negative_numbers = true)]
        swing: f64,
        /// The rocker O3B, m.
        #[arg(long, value_name = "L", allow_negative_numbers = true)]
        rocker: f64,
        /// The frame O1O3, m (chosen for the largest γ_min without it).
        #[arg(long, value_name = "D", allow_negative_numbers = true)]
        frame: Option<f64>,
        #[command(flatten)]
        common: Common,
    },

    /// An offset slider-crank from the stroke H and the time ratio K; the guide's offset
    /// given, or chosen where the smallest transmission angle is largest.
    #[command(after_help = "\
Examples:
  tmm synth slider-crank --stroke 0.2 -K 1.2 -o slider-crank.json
  tmm synth slider-crank --stroke 0.2 -K 1.2 --offset 0.05 -o slider-crank.json

A central slider-crank has K = 1; the offset e > 0 puts the guide above the crank's pivot.
K < 3 (the crank angles of the strokes differ by less than 180°).")]
    SliderCrank {
        /// H, the slider's stroke, m.
        #[arg(long, value_name = "H", allow_negative_numbers = true)]
        stroke: f64,
        /// K, the time ratio of the strokes, 1 < K < 3.
        #[arg(
            short = 'K',
            long = "time-ratio",
            value_name = "K",
            allow_negative_numbers = true
        )]
        time_ratio: f64,
        /// e, the guide's offset above the crank's pivot, m (chosen for the largest γ_min
        /// without it).
        #[arg(long, value_name = "e", allow_negative_numbers = true)]
        offset: Option<f64>,
        #[command(flatten)]
        common: Common,
    },

    /// The shaper (quick-return mechanism with a slotted lever and a ram) from the ram's
    /// stroke H, the time ratio K and the distance O1O3 between the crank's and the lever's
    /// pivots.
    #[command(after_help = "\
Examples:
  tmm synth shaper --stroke 0.3 -K 1.6 --centre-distance 0.25 -o my-shaper.json
  tmm analyse my-shaper.json --format csv      its course table

The lever's swing equals θ = 180°(K − 1)/(K + 1), so the crank is O1O3·sin(θ/2); the
transmission angle of the ram is 90° − θ/2 at the ends of the stroke.")]
    Shaper {
        /// H, the ram's stroke, m.
        #[arg(long, value_name = "H", allow_negative_numbers = true)]
        stroke: f64,
        /// K, the time ratio of the ram's strokes (> 1).
        #[arg(
            short = 'K',
            long = "time-ratio",
            value_name = "K",
            allow_negative_numbers = true
        )]
        time_ratio: f64,
        /// O1O3, the lever's pivot below the crank's, m.
        #[arg(long, value_name = "D", allow_negative_numbers = true)]
        centre_distance: f64,
        #[command(flatten)]
        common: Common,
    },

    /// A crank-rocker whose rocker is at given angles ψ when the crank is at given angles φ
    /// (two or three pairs, Freudenstein's equation); with two pairs the crank's length is
    /// chosen where the smallest transmission angle is largest.
    #[command(
        visible_alias = "crank-rocker-through",
        after_help = "\
Examples:
  tmm synth through --frame 0.4 --at 40,101.4 100,112.8 160,131.8 --min-transmission 0 -o through.json
  tmm synth through --frame 0.4 --at 40,101.4 160,131.8 -o through2.json

Angles in degrees from the frame line O1→O3 (O1 at the origin, O3 at (frame, 0))."
    )]
    Through {
        /// The frame O1O3, m.
        #[arg(long, value_name = "D", allow_negative_numbers = true)]
        frame: f64,
        /// Pairs φ,ψ of crank and rocker angles, degrees (write −30° as 330).
        #[arg(long, value_name = "φ,ψ", num_args = 1.., required = true,
              value_parser = crate::parse_pair)]
        at: Vec<(f64, f64)>,
        #[command(flatten)]
        common: Common,
    },

    /// A four-bar function generator (Freudenstein): while the crank turns linearly with x
    /// over its range, the rocker turns linearly with y = f(x); exact at three Chebyshev
    /// points, or least squares over N points.
    #[command(after_help = "\
Examples:
  tmm synth function --function log10 --x 1,2 --crank -30,30 --rocker 0,90 --frame 0.1 -o log.json
  tmm synth function --function x^2 --x 1,2 --crank 180,270 --rocker 240,330 --frame 0.1 --least-squares 21 -o square.json

The report tabulates the structural error (y generated by the engine's rocker angle, mapped
back, against f(x)) across the range, and names its largest value.")]
    Function {
        /// f: log10, ln, exp, sqrt, sin, cos, tan (x in rad), 1/x, x^P (e.g. x^2).
        #[arg(long, value_name = "NAME", value_parser = Function::parse)]
        function: Function,
        /// x0,x1: the range of x.
        #[arg(long, value_name = "x0,x1", allow_hyphen_values = true, value_parser = crate::parse_pair)]
        x: (f64, f64),
        /// φ0,φ1: the crank's angles at x0 and x1, degrees from the frame line O1→O3.
        #[arg(long, value_name = "φ0,φ1", allow_hyphen_values = true, value_parser = crate::parse_pair)]
        crank: (f64, f64),
        /// ψ0,ψ1: the rocker's angles at f(x0) and f(x1), degrees.
        #[arg(long, value_name = "ψ0,ψ1", allow_hyphen_values = true, value_parser = crate::parse_pair)]
        rocker: (f64, f64),
        /// The frame O1O3, m.
        #[arg(long, value_name = "D", allow_negative_numbers = true)]
        frame: f64,
        /// Least squares over N points at Chebyshev spacing (three exact points without it).
        #[arg(long, value_name = "N")]
        least_squares: Option<usize>,
        #[command(flatten)]
        common: Common,
    },

    /// A four-bar whose coupler point P passes through target points read from a file, by a
    /// seeded global search (differential evolution, then a local polish).
    #[command(after_help = "\
Examples:
  tmm synth path points.csv --seed 7 --budget 20000 -o path.json
  tmm analyse path.json --positions 72 --format csv > curve.csv   x(P), y(P): the coupler curve
  tmm synth path points.csv --closed --seed 3 --budget 20000 -o curve.json

The points file: CSV with x,y in m on each line (a header line and lines starting with # are
skipped), with an optional third column, the crank's turn from the first point in degrees
(prescribed timing: at least 5 points); or JSON, [[x, y], …] or {\"points\": [[x, y], …],
\"crank\": [Δφ, …]}. Free timing needs at least 9 points, and so does --closed (the points
sample a closed curve, traced once per turn); at most 500 points. The search stops at --budget
evaluations (200 000 by default, at most 2 000 000), a count, so the same command and --seed
give the same design on any machine; --time adds a wall-clock bound, and with it the design
may depend on the machine's load. Progress shows on a terminal, nothing when piped.")]
    Path {
        /// The points sample a closed curve: the crank turns fully and P runs around it once.
        #[arg(long)]
        closed: bool,
        #[command(flatten)]
        search: Search,
        #[command(flatten)]
        common: Common,
    },

    /// A Stephenson III six-bar whose point P passes through target points at given crank
    /// angles (prescribed timing), by a seeded global search (differential evolution, then
    /// local polishes).
    #[command(after_help = "\
Examples:
  tmm synth six-bar timed.csv --min-transmission 17 --budget 400000 -o six-bar.json
  tmm analyse six-bar.json --positions 72 --format csv > path.csv   x(P), y(P): P's path

The six-bar: a four-bar O1–A–B–O3 (the crank O1A driven), a hinge C on its coupler AB, a dyad
C–E–O5 to a third frame pivot O5, and P on the dyad's link CE: a crank and two RRR dyads,
which the engine analyses in closed form. The points file as for `tmm synth path`, with the
crank's turn from the first point in degrees (a third CSV column, or \"crank\" in JSON) and
at least 8 points: 15 dimensions and the crank's angle at the first point are unknown, two
equations a point. Both dyads keep the transmission angle at or above --min-transmission over
the crank's range between the points. The report lists the crank angles found at the points.")]
    SixBar {
        #[command(flatten)]
        search: Search,
        #[command(flatten)]
        common: Common,
    },
}

/// The most candidate evaluations `--budget` may ask of a path search: ten times the
/// default (a candidate costs about 85 µs over its turn of 360 positions on one core of the
/// 2-core test machine, so about three minutes).
const MAX_BUDGET: u64 = 2_000_000;

/// The options of the path searches.
#[derive(Args)]
pub struct Search {
    /// The target points (CSV or JSON, m).
    points: PathBuf,
    /// The search's seed (a fixed one without it: the same run gives the same design).
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    /// Candidate evaluations of the search (a candidate over a turn of 360 positions), at
    /// most 2 000 000: ten times the default, a few minutes of one core. The search's only
    /// bound unless --time is given, so the same command gives the same design on any
    /// machine.
    #[arg(long, value_name = "N", default_value_t = 200_000,
          value_parser = clap::value_parser!(u64).range(1..=MAX_BUDGET))]
    budget: u64,
    /// A wall-clock bound of the search, s, on top of --budget; none by default. With it,
    /// the design found depends on the machine's speed and load.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    time: Option<f64>,
    /// Distinct designs to look for (the best is written, the others reported).
    #[arg(long, value_name = "K", default_value_t = 3,
          value_parser = clap::value_parser!(u64).range(1..=20))]
    designs: u64,
}

impl Search {
    /// The path request of `mechanism` with the points file read (named in a failure).
    fn request(
        self,
        mechanism: PathMechanism,
        closed: bool,
    ) -> Result<(String, PathRequest), Fail> {
        let label = self.points.display().to_string();
        let (targets, crank) = read_points(&self.points).map_err(|f| Fail::on(&label, f))?;
        let timing = match (closed, crank) {
            (true, Some(_)) => {
                return Err(Fail::on(
                    &label,
                    Failure::new(
                        "the points file gives crank angles, and --closed asks for a \
                         closed curve whose crank angles the search chooses",
                    )
                    .hint("drop --closed or the third column"),
                ));
            }
            (true, None) => Timing::Closed,
            (false, Some(c)) => Timing::Prescribed(c),
            (false, None) => Timing::Free,
        };
        let request = PathRequest {
            mechanism,
            points: targets,
            timing,
            seed: self.seed,
            budget: self.budget as usize,
            time: self.time,
            designs: self.designs as usize,
        };
        Ok((label, request))
    }
}

/// Runs one kind of synthesis.
pub fn run(kind: SynthKind) -> Result<(), Fail> {
    let (label, request, common) = request_of(kind)?;
    let designed = engine::synth::synthesise(&request, &mut progress);
    clear_progress();
    let designed = designed.map_err(|f| Fail::on(&label, f))?;
    let mut json = designed.json;
    if !json.ends_with('\n') {
        json.push('\n');
    }
    let text = report::design(&designed.report);
    match &common.output {
        Some(path) => {
            write_file(path, &json)?;
            print(&text);
            print(&format!("description written to {}\n", path.display()));
        }
        None => {
            print(&json);
            eprint!("{text}");
        }
    }
    Ok(())
}

fn pair((a, b): (f64, f64)) -> [f64; 2] {
    [a, b]
}

fn radians((a, b): (f64, f64)) -> [f64; 2] {
    [a.to_radians(), b.to_radians()]
}

/// The label of the failure, the request in SI units, and the common options.
fn request_of(kind: SynthKind) -> Result<(String, Request, Common), Fail> {
    let (label, kind, common) = match kind {
        SynthKind::CrankRocker {
            time_ratio,
            swing,
            rocker,
            frame,
            common,
        } => (
            "synth crank-rocker".to_owned(),
            Kind::CrankRocker {
                rocker,
                swing: swing.to_radians(),
                time_ratio,
                frame,
            },
            common,
        ),
        SynthKind::SliderCrank {
            stroke,
            time_ratio,
            offset,
            common,
        } => (
            "synth slider-crank".to_owned(),
            Kind::SliderCrank {
                stroke,
                time_ratio,
                offset,
            },
            common,
        ),
        SynthKind::Shaper {
            stroke,
            time_ratio,
            centre_distance,
            common,
        } => (
            "synth shaper".to_owned(),
            Kind::Shaper {
                stroke,
                time_ratio,
                centre_distance,
            },
            common,
        ),
        SynthKind::Through { frame, at, common } => (
            "synth through".to_owned(),
            Kind::Through {
                frame,
                positions: at
                    .into_iter()
                    .map(|(p, q)| (p.to_radians(), q.to_radians()))
                    .collect(),
            },
            common,
        ),
        SynthKind::Function {
            function,
            x,
            crank,
            rocker,
            frame,
            least_squares,
            common,
        } => (
            "synth function".to_owned(),
            Kind::Function(FunctionRequest {
                function,
                x: pair(x),
                crank: radians(crank),
                rocker: radians(rocker),
                frame,
                least_squares,
            }),
            common,
        ),
        SynthKind::Path {
            closed,
            search,
            common,
        } => {
            let (label, request) = search.request(PathMechanism::FourBar, closed)?;
            (label, Kind::Path(request), common)
        }
        SynthKind::SixBar { search, common } => {
            let (label, request) = search.request(PathMechanism::SixBar, false)?;
            (label, Kind::Path(request), common)
        }
    };
    let request = Request {
        kind,
        min_transmission: common.min_transmission.to_radians(),
    };
    Ok((label, request, common))
}

/// The target points (m) and, when given, the crank's turn at each (rad).
type Points = (Vec<[f64; 2]>, Option<Vec<f64>>);

/// Reads a points file: JSON by its extension, CSV otherwise.
fn read_points(path: &Path) -> Result<Points, Failure> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::new(format!("cannot read the file: {}", crate::io_text(&e))))?;
    let json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let (points, crank) = if json {
        points_json(&text)?
    } else {
        points_csv(&text)?
    };
    if points.len() > MAX_TARGETS {
        return Err(Failure::new(format!(
            "{} target points, more than the {MAX_TARGETS} the search takes: its final polish \
             solves for the crank's angle at every point, a dense system whose cost grows with \
             the cube of their number",
            points.len()
        ))
        .hint(format!(
            "thin them: keep one point in {}",
            points.len().div_ceil(MAX_TARGETS)
        )));
    }
    Ok((points, crank))
}

/// The most target points `tmm synth path` takes. The library's search has no bound of its
/// own, and its polish (Levenberg–Marquardt over the link dimensions and one crank angle per
/// point, dense) is not cut by the time bound: 300 points took 17 s of CPU in a debug build,
/// 1000 more than 75 s without finishing. A path is given by a few dozen points.
const MAX_TARGETS: usize = 500;

fn points_csv(text: &str) -> Result<Points, Failure> {
    let mut points = Vec::new();
    let mut crank: Vec<f64> = Vec::new();
    let mut columns = None;
    let mut first = true;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let header = std::mem::replace(&mut first, false);
        let cells: Vec<&str> = line
            .split([',', ';', '\t'])
            .map(str::trim)
            .filter(|c| !c.is_empty())
            .collect();
        let numbers: Result<Vec<f64>, _> = cells.iter().map(|c| c.parse::<f64>()).collect();
        let Ok(numbers) = numbers else {
            if header {
                continue; // the first line may name the columns
            }
            let bad = cells
                .iter()
                .find(|c| c.parse::<f64>().is_err())
                .unwrap_or(&"");
            return Err(Failure::new(format!(
                "line {}: \"{bad}\" is not a number",
                k + 1
            )));
        };
        if !(2..=3).contains(&numbers.len()) {
            return Err(Failure::new(format!(
                "line {}: {} values, where x,y (m) or x,y,Δφ (m, m, degrees) are expected",
                k + 1,
                numbers.len()
            )));
        }
        match columns {
            None => columns = Some(numbers.len()),
            Some(c) if c != numbers.len() => {
                return Err(Failure::new(format!(
                    "line {}: {} values, where the lines before have {c}",
                    k + 1,
                    numbers.len()
                )));
            }
            Some(_) => {}
        }
        points.push([numbers[0], numbers[1]]);
        if let Some(d) = numbers.get(2) {
            crank.push(d.to_radians());
        }
    }
    if points.is_empty() {
        return Err(Failure::new(
            "no points in the file: lines of x,y in m are expected",
        ));
    }
    Ok((points, (columns == Some(3)).then_some(crank)))
}

fn points_json(text: &str) -> Result<Points, Failure> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| Failure::new(format!("not JSON: {e}")))?;
    let (list, crank) = match &v {
        serde_json::Value::Array(_) => (&v, None),
        serde_json::Value::Object(o) => (
            o.get("points")
                .ok_or_else(|| Failure::new("no field \"points\" (a list of [x, y] in m)"))?,
            o.get("crank"),
        ),
        _ => {
            return Err(Failure::new(
                "expected a list of [x, y] or an object with \"points\"",
            ));
        }
    };
    let number = |v: &serde_json::Value, what: &str| {
        v.as_f64()
            .ok_or_else(|| Failure::new(format!("{what}: {v} is not a number")))
    };
    let points = list
        .as_array()
        .ok_or_else(|| Failure::new("\"points\" is not a list of [x, y]"))?
        .iter()
        .enumerate()
        .map(|(k, p)| match p.as_array().map(Vec::as_slice) {
            Some([x, y]) => Ok([
                number(x, &format!("point {}", k + 1))?,
                number(y, &format!("point {}", k + 1))?,
            ]),
            _ => Err(Failure::new(format!(
                "point {}: {p} is not a pair [x, y]",
                k + 1
            ))),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let crank = crank
        .map(|c| {
            c.as_array()
                .ok_or_else(|| Failure::new("\"crank\" is not a list of angles in degrees"))?
                .iter()
                .enumerate()
                .map(|(k, d)| number(d, &format!("crank {}", k + 1)).map(f64::to_radians))
                .collect::<Result<Vec<_>, _>>()
        })
        .transpose()?;
    Ok((points, crank))
}
