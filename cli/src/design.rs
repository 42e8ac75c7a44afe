//! The program's plain data of `tmm synth`: a requirement in (SI units, angles in rad), the
//! synthesised description and its report out. Like [`crate::model`], nothing here names a
//! type of the library: [`crate::engine::synth`] translates.

use crate::model::Structure;

/// What to synthesise, and the smallest transmission angle the answer must keep.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The kind of mechanism and its requirement.
    pub kind: Kind,
    /// \[γ\], rad (0 switches the requirement off).
    pub min_transmission: f64,
}

/// The kinds of synthesis, each with its requirement (lengths in m, angles in rad).
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// A crank-rocker whose rocker of length `rocker` swings `swing` with the time ratio
    /// `time_ratio`; the frame O1O3 given, or where γ_min is largest.
    CrankRocker {
        /// The rocker O3B, m.
        rocker: f64,
        /// ψ, rad.
        swing: f64,
        /// K.
        time_ratio: f64,
        /// O1O3, m; `None`: chosen for the largest γ_min.
        frame: Option<f64>,
    },
    /// An offset slider-crank of stroke H and time ratio K; the offset given or the best.
    SliderCrank {
        /// H, m.
        stroke: f64,
        /// K.
        time_ratio: f64,
        /// e, m; `None`: chosen for the largest γ_min.
        offset: Option<f64>,
    },
    /// The shaper (slotted lever and ram) of ram stroke H and time ratio K.
    Shaper {
        /// H, m.
        stroke: f64,
        /// K.
        time_ratio: f64,
        /// O1O3, m.
        centre_distance: f64,
    },
    /// A crank-rocker through two or three pairs of crank and rocker angles.
    Through {
        /// O1O3, m.
        frame: f64,
        /// (φ, ψ) pairs, rad, from the frame line O1→O3.
        positions: Vec<(f64, f64)>,
    },
    /// A four-bar function generator (Freudenstein) for y = f(x).
    Function(FunctionRequest),
    /// A four-bar (or a six-bar) whose point P passes through target points (a seeded
    /// search).
    Path(PathRequest),
}

/// A function generator's requirement: the crank's angle a linear image of x, the rocker's
/// one of y = f(x).
#[derive(Debug, Clone, PartialEq)]
pub struct FunctionRequest {
    /// f.
    pub function: Function,
    /// [x0, x1].
    pub x: [f64; 2],
    /// The crank angles at x0 and x1, rad.
    pub crank: [f64; 2],
    /// The rocker angles at f(x0) and f(x1), rad.
    pub rocker: [f64; 2],
    /// O1O3, m.
    pub frame: f64,
    /// `None`: three Chebyshev precision points; `Some(n)`: least squares over n points.
    pub least_squares: Option<usize>,
}

/// A path-generation requirement and the search's bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct PathRequest {
    /// The mechanism searched.
    pub mechanism: PathMechanism,
    /// The target points, m.
    pub points: Vec<[f64; 2]>,
    /// The crank's angles at the points.
    pub timing: Timing,
    /// The search's seed (the same seed, the same designs).
    pub seed: Option<u64>,
    /// Candidate evaluations of the global stage.
    pub budget: usize,
    /// A wall-clock bound of the search, s, when the user asks for one (`None`: the
    /// evaluations alone bound it, and the same request gives the same design anywhere).
    pub time: Option<f64>,
    /// How many distinct designs to look for.
    pub designs: usize,
}

/// The mechanisms of path generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathMechanism {
    /// A four-bar, P on its coupler.
    FourBar,
    /// A Stephenson III six-bar (a four-bar and a dyad hung from its coupler), P on the
    /// dyad's link CE; prescribed timing only.
    SixBar,
}

/// How the crank's angles at the target points are given.
#[derive(Debug, Clone, PartialEq)]
pub enum Timing {
    /// Free.
    Free,
    /// The crank's turn from the first point to each point, rad.
    Prescribed(Vec<f64>),
    /// The points sample a closed curve traced once per turn.
    Closed,
}

/// A function of a function generator, by name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Function {
    /// log10 x.
    Log10,
    /// ln x.
    Ln,
    /// eˣ.
    Exp,
    /// √x.
    Sqrt,
    /// sin x (x in rad).
    Sin,
    /// cos x (x in rad).
    Cos,
    /// tan x (x in rad).
    Tan,
    /// 1/x.
    Reciprocal,
    /// xᵖ.
    Power(f64),
}

impl Function {
    /// The names `parse` takes, for the help.
    pub const NAMES: &'static str = "log10, ln, exp, sqrt, sin, cos, tan, 1/x, x^P (e.g. x^2)";

    /// The function named `name`.
    ///
    /// # Errors
    /// A sentence listing the names, for a name that is none of them.
    pub fn parse(name: &str) -> Result<Self, String> {
        Ok(match name.trim() {
            "log10" | "lg" => Self::Log10,
            "ln" | "log" => Self::Ln,
            "exp" => Self::Exp,
            "sqrt" => Self::Sqrt,
            "sin" => Self::Sin,
            "cos" => Self::Cos,
            "tan" => Self::Tan,
            "1/x" | "reciprocal" => Self::Reciprocal,
            other => match other.strip_prefix("x^").map(str::parse::<f64>) {
                Some(Ok(p)) if p.is_finite() => Self::Power(p),
                _ => {
                    return Err(format!(
                        "\"{name}\" is not a function tmm knows; the names are {}",
                        Self::NAMES
                    ));
                }
            },
        })
    }

    /// f(x).
    pub fn eval(self, x: f64) -> f64 {
        match self {
            Self::Log10 => x.log10(),
            Self::Ln => x.ln(),
            Self::Exp => x.exp(),
            Self::Sqrt => x.sqrt(),
            Self::Sin => x.sin(),
            Self::Cos => x.cos(),
            Self::Tan => x.tan(),
            Self::Reciprocal => 1.0 / x,
            Self::Power(p) => x.powf(p),
        }
    }

    /// Its name, as `parse` takes it.
    pub fn name(self) -> String {
        match self {
            Self::Log10 => "log10".to_owned(),
            Self::Ln => "ln".to_owned(),
            Self::Exp => "exp".to_owned(),
            Self::Sqrt => "sqrt".to_owned(),
            Self::Sin => "sin".to_owned(),
            Self::Cos => "cos".to_owned(),
            Self::Tan => "tan".to_owned(),
            Self::Reciprocal => "1/x".to_owned(),
            Self::Power(p) => format!("x^{p}"),
        }
    }

    /// f(x) written out: `log10(x)`, but `1/x` and `x^2` as they are.
    pub fn formula(self) -> String {
        match self {
            Self::Reciprocal | Self::Power(_) => self.name(),
            _ => format!("{}(x)", self.name()),
        }
    }
}

/// A synthesised mechanism: its description as JSON and what it achieves.
#[derive(Debug, Clone, PartialEq)]
pub struct Designed {
    /// The description file's text.
    pub json: String,
    /// The report.
    pub report: DesignReport,
}

/// One dimension of a design.
#[derive(Debug, Clone, PartialEq)]
pub struct Dimension {
    /// Its name (for example "crank O1A").
    pub name: String,
    /// Its value, m or rad.
    pub value: f64,
    /// Whether it is an angle (rad) rather than a length (m).
    pub angle: bool,
}

/// What a synthesised mechanism achieves: the synthesis's own figures (closed form), the
/// engine's check of the description written, and the misses at the requirement's points.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignReport {
    /// The kind, for example "crank-rocker".
    pub kind: String,
    /// The dimensions.
    pub dimensions: Vec<Dimension>,
    /// K, where the output has two extremes per turn.
    pub time_ratio: Option<f64>,
    /// The stroke (m) or swing (rad), with K.
    pub stroke: Option<f64>,
    /// Whether the output is an angle (the stroke is a swing in rad).
    pub angular_output: bool,
    /// γ_min and the crank angle where it occurs, rad.
    pub min_transmission: (f64, f64),
    /// Grashof's class of a four-bar, in words.
    pub grashof: Option<String>,
    /// The engine's structure of the written description (what `tmm check` prints).
    pub checked: Structure,
    /// How far the engine's motion of the description is from the requirement's points.
    pub misses: Option<Misses>,
    /// Lines on the method (precision points, coefficients, the other designs found).
    pub notes: Vec<String>,
}

/// The requirement's points against the engine's motion of the written description.
#[derive(Debug, Clone, PartialEq)]
pub struct Misses {
    /// What the rows are.
    pub title: String,
    /// The names of the wanted and reached values (for example ["x", "y"]).
    pub quantities: Vec<String>,
    /// Their unit: "m", "deg" (shown in degrees, held in rad) or "" for a pure number.
    pub unit: &'static str,
    /// The rows.
    pub rows: Vec<MissRow>,
}

/// One point of the requirement.
#[derive(Debug, Clone, PartialEq)]
pub struct MissRow {
    /// The input there, for example "φ = 40.0°" or "x = 1.25".
    pub at: String,
    /// The wanted values.
    pub wanted: Vec<f64>,
    /// The values the engine reaches; NaN where it does not assemble.
    pub reached: Vec<f64>,
    /// The distance between them (the largest difference, or the Euclidean distance of a
    /// point), in the rows' unit.
    pub miss: f64,
}
