//! Kinematic synthesis: from a requirement to a [`Linkage`] description that the engine
//! ([`Plan::new`](crate::linkage::Plan::new)) analyses.
//!
//! Every method is exact (a closed form, or a linear system solved once) except where a free
//! parameter is chosen to maximise the smallest transmission angle: there a bounded 1-D search
//! (a dense scan, then golden section on the best sample's neighbours) picks it, and the
//! result is still exact for the requirement itself.
//!
//! - **By the time ratio and the stroke** ([`crank_rocker`], [`slider_crank`], [`shaper`]):
//!   the quick-return mechanisms from K = t_work/t_idle (the crank angle between the output's
//!   extreme positions is θ = π(K − 1)/(K + 1) away from a half turn) and the output's stroke
//!   or swing.
//! - **Through given positions** ([`crank_rocker_through`]): Freudenstein's equation at two
//!   or three pairs of crank and rocker angles.
//! - **Function generation** ([`function_generator`]): a four-bar whose rocker angle is a
//!   linear image of y = f(x) while the crank angle is a linear image of x; three precision
//!   points at Chebyshev spacing (exact) or least squares over N points; the structural error
//!   over the whole range by the engine ([`FunctionGenerator::structural_error`]).
//! - **Motion generation** (Burmester): dyads that carry a coupler through finitely
//!   separated poses — for three, the centre point of a chosen circle point ([`centre_point`])
//!   and the circle point of a chosen centre point ([`circle_point`]); for two, centre points
//!   on a bisector ([`centre_point_two`]); for four, the centre-point curve sampled
//!   ([`centre_point_curve`]; as lines to draw, [`burmester_curves`]); for five, Burmester's points ([`burmester_points`]) — and the
//!   four-bar of two dyads ([`four_bar_from_dyads`], [`burmester`]), checked for branch and
//!   order defects.
//!
//! Each answer is a [`Synthesis`]: the description and a [`Report`] of what the mechanism
//! achieves (the time ratio, the stroke or swing, the smallest transmission angle over the
//! motion and where it occurs, Grashof's class), computed in closed form from the dimensions
//! found — the tests analyse every description with the engine and compare.
//!
//! Conventions: SI units (m, rad); angles counter-clockwise from +x. A four-bar is built in
//! Freudenstein's frame unless its pivots are part of the requirement: the crank's pivot O1 at
//! the origin, the rocker's pivot O3 at (d, 0); the crank angle φ is the direction of O1→A, the
//! rocker angle ψ that of O3→B. Joint names: `O1`, `A`, `B`, `O3` (four-bar, links `frame`,
//! `crank`, `coupler`, `rocker`); `O1`, `A`, `B`, `P` (slider-crank, `P` the slider's
//! prismatic joint; links `frame`, `crank`, `rod`, `slider`); the shaper's are listed at
//! [`shaper`]. The descriptions carry no masses or loads: add them before a kinetostatic
//! analysis.
//!
//! Bad requirements (non-finite numbers, K ≤ 1, a swing outside (0, π), too few points,
//! coinciding poses) are errors naming the parameter. A requirement that no mechanism of the
//! kind meets is [`Error::Infeasible`] (with the nearest reachable value, so the message says
//! by how much it misses), [`Error::OutOfRange`] (with the feasible interval, for K), or
//! [`Error::NoMechanism`] (saying what came out instead: a negative length, a branch or an
//! order defect, a crank that does not turn fully). Lengths and coordinates, given and
//! found, lie within [`MIN_LENGTH`]..[`MAX_LENGTH`] (an error names the one that does not),
//! and a four-bar's links within a ratio of [`MAX_LINK_RATIO`];
//! no answer passes a dead point (γ_min > [`DEAD_POINT`] always); every answer's description
//! is solved by the engine at its reference pose before it is returned.
//!
//! # Example
//! A crank-rocker whose 0.3 m rocker swings 45° with K = 1.25, handed to the engine:
//! ```
//! use tmm::kinematics::Rotation;
//! use tmm::linkage::{Output, Plan};
//! use tmm::synthesis::{crank_rocker, CrankRockerRequirement, FrameChoice, Options};
//! let need = CrankRockerRequirement {
//!     rocker: 0.3,
//!     swing: 45f64.to_radians(),
//!     time_ratio: 1.25,
//!     frame: FrameChoice::BestTransmission,
//! };
//! let s = crank_rocker(&need, &Options::default())?;
//! println!("{}", s.report); // dimensions, K, swing, γ_min and where, Grashof's class
//! let plan = Plan::new(&s.linkage)?;
//! let (gamma, _) = plan.min_transmission_angle(0)?;
//! assert!((gamma - s.report.min_transmission_angle).abs() < 1e-10);
//! let strokes = plan.strokes(&Output::Angle("rocker".into()), Rotation::Ccw)?;
//! assert!((strokes.time_ratio - 1.25).abs() < 1e-10);
//! # Ok::<(), tmm::Error>(())
//! ```

mod burmester;
mod burmester_five;
mod burmester_resultant;
mod burmester_scan;
mod burmester_two_angle;
mod centre_curve;
mod check;
mod four_bar;
mod freudenstein;
mod held;
mod path;
mod pose_newton;
mod pose_order;
mod quick_return;
mod search;

pub use burmester::{
    burmester, centre_point, centre_point_two, circle_point, four_bar_from_dyads, Dyad, Pose,
};
pub use burmester_five::burmester_points;
pub use burmester_scan::burmester_points_by_scan;
pub use centre_curve::{burmester_curves, centre_point_curve};
pub use freudenstein::{
    crank_rocker_through, freudenstein_coefficients, function_generator, FunctionGenerator,
    FunctionRequirement, Spacing, StructuralError,
};
pub use path::{
    path_generator, six_bar_path_generator, slider_crank_path_generator, PathDesign, PathOptions,
    PathRequirement, Progress, Timing,
};
pub use quick_return::{
    crank_rocker, shaper, slider_crank, CrankRockerRequirement, FrameChoice, OffsetChoice,
    ShaperRequirement, SliderCrankRequirement,
};

use crate::error::{Error, Result};
use crate::kinematics::Grashof;
use crate::linkage::Linkage;
use std::fmt;

/// The most points a least-squares fit, a structural error curve or a sampled centre-point
/// curve takes (10⁶): more would only allocate without changing the answer.
pub const MAX_POINTS: usize = 1_000_000;

/// Options common to the synthesis methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Options {
    /// \[γ\], the smallest transmission angle the mechanism must keep over its motion, rad, in
    /// [0, π/2]. Default 40° (0.698 rad), the usual engineering limit.
    pub min_transmission_angle: f64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            min_transmission_angle: 40f64.to_radians(),
        }
    }
}

impl Options {
    /// The options with \[γ\] = `angle`, rad (0 switches the requirement off).
    #[must_use]
    pub fn with_min_transmission_angle(mut self, angle: f64) -> Self {
        self.min_transmission_angle = angle;
        self
    }

    pub(crate) fn check(&self) -> Result<f64> {
        let g = crate::error::finite("min_transmission_angle", self.min_transmission_angle)?;
        if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&g) {
            return Err(Error::OutOfRange {
                name: "min_transmission_angle",
                value: g,
                min: 0.0,
                max: std::f64::consts::FRAC_PI_2,
                ends: crate::Ends::Closed,
            });
        }
        Ok(g)
    }
}

/// A synthesised mechanism: its description for the engine and what it achieves.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Synthesis {
    /// The description, in a reference pose where it assembles in the designed mode.
    pub linkage: Linkage,
    /// What the mechanism achieves.
    pub report: Report,
}

/// What a synthesised mechanism achieves, computed in closed form from its dimensions.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct Report {
    /// The kind of mechanism (for example `"crank-rocker"`).
    pub kind: &'static str,
    /// K, the time ratio of the output's strokes (the larger crank angle between the output's
    /// extreme positions over the smaller, ≥ 1), when the crank turns fully and the output
    /// has two extreme positions per turn.
    pub time_ratio: Option<f64>,
    /// The output's stroke (m, a slider) or swing (rad, a rocker) between its extreme
    /// positions, with `time_ratio`.
    pub stroke: Option<f64>,
    /// γ_min, the smallest transmission angle over the motion (a full turn of a crank that
    /// turns fully; the input's range otherwise), rad in [0, π/2].
    pub min_transmission_angle: f64,
    /// The input angle φ where γ_min occurs, rad in [0, 2π).
    pub min_transmission_at: f64,
    /// Grashof's class of a four-bar (`None` for other mechanisms).
    pub grashof: Option<Grashof>,
    /// The mechanism's dimensions by name (for example `("crank O1A", 0.1)`), m or rad as
    /// the name says.
    pub dimensions: Vec<(String, f64)>,
}

impl Report {
    /// The dimension whose name starts with `name` (for example `"crank"`).
    #[must_use]
    pub fn dimension(&self, name: &str) -> Option<f64> {
        self.dimensions
            .iter()
            .find(|(n, _)| n.starts_with(name))
            .map(|&(_, v)| v)
    }
}

impl fmt::Display for Report {
    /// The report as lines for a person: dimensions in mm, angles in degrees.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{}", self.kind)?;
        for (name, value) in &self.dimensions {
            if name.ends_with("(rad)") {
                writeln!(f, "  {name:<28} {:>10.4}°", value.to_degrees())?;
            } else {
                writeln!(f, "  {name:<28} {:>10.4} mm", value * 1e3)?;
            }
        }
        if let Some(k) = self.time_ratio {
            writeln!(f, "  time ratio K                 {k:>10.6}")?;
        }
        if let Some(s) = self.stroke {
            if self.kind.contains("slider") || self.kind.contains("shaper") {
                writeln!(f, "  stroke                       {:>10.4} mm", s * 1e3)?;
            } else {
                writeln!(
                    f,
                    "  swing                        {:>10.4}°",
                    s.to_degrees()
                )?;
            }
        }
        writeln!(
            f,
            "  min transmission angle       {:>10.4}° at φ = {:.3}°",
            self.min_transmission_angle.to_degrees(),
            self.min_transmission_at.to_degrees()
        )?;
        if let Some(g) = self.grashof {
            writeln!(f, "  Grashof class                {g}")?;
        }
        Ok(())
    }
}

/// π(K − 1)/(K + 1): the crank angle θ by which the two strokes of a quick-return mechanism
/// differ from a half turn each (they take π + θ and π − θ), for a time ratio K > 1.
pub(crate) fn crank_excess(k: f64) -> Result<f64> {
    let k = crate::error::finite("K", k)?;
    if k <= 1.0 {
        return Err(Error::OutOfRange {
            name: "K",
            value: k,
            min: 1.0,
            max: f64::INFINITY,
            ends: crate::Ends::Open,
        });
    }
    // (K − 1)/(K + 1) first: π·(K − 1) overflows for K near f64::MAX, the ratio never does.
    Ok(std::f64::consts::PI * ((k - 1.0) / (k + 1.0)))
}

/// K = (π + θ)/(π − θ), the inverse of [`crank_excess`].
pub(crate) fn time_ratio_of(theta: f64) -> f64 {
    (std::f64::consts::PI + theta) / (std::f64::consts::PI - theta)
}

/// The acute angle of `x` (rad in [0, π]) with a line: min(x, π − x).
pub(crate) fn acute(x: f64) -> f64 {
    x.min(std::f64::consts::PI - x)
}

/// Checks that γ_min meets \[γ\], and in any case exceeds [`DEAD_POINT`]:
/// [`Error::Infeasible`] otherwise (with what is reachable).
pub(crate) fn require_transmission(achieved: f64, required: f64) -> Result<()> {
    let required = required.max(DEAD_POINT);
    if achieved.is_nan() || achieved < required {
        Err(Error::Infeasible {
            parameter: "minimum transmission angle (rad)",
            required,
            reachable: if achieved.is_nan() { 0.0 } else { achieved },
        })
    } else {
        Ok(())
    }
}

/// The smallest γ_min any synthesised mechanism keeps, rad (10⁻⁶), even with \[γ\] = 0: a
/// mechanism whose transmission angle reaches zero passes a dead point, where the engine's
/// velocity system is singular and the crank cannot drive the output through it.
pub const DEAD_POINT: f64 = 1e-6;

/// The largest ratio of a synthesised four-bar's longest link to its shortest (10³): the
/// engine finds a hinge between a long and a short link to a relative precision of about
/// ε·(long/short)², so beyond this the answer could not be checked to 10⁻¹⁰.
pub const MAX_LINK_RATIO: f64 = 1e3;

/// The largest length or coordinate a synthesis takes or gives, m (10¹⁰⁰): far inside the
/// range where the engine's squares of lengths stay finite (about 1.3·10¹⁵⁴).
pub const MAX_LENGTH: f64 = 1e100;

/// The smallest length a synthesis takes, m (10⁻¹⁰⁰): far above the range where the
/// engine's squares of lengths underflow.
pub const MIN_LENGTH: f64 = 1e-100;

/// Checks a given length: finite, positive and within [[`MIN_LENGTH`], [`MAX_LENGTH`]].
pub(crate) fn length(name: &'static str, value: f64) -> Result<f64> {
    let v = crate::error::positive(name, value)?;
    if (MIN_LENGTH..=MAX_LENGTH).contains(&v) {
        Ok(v)
    } else {
        Err(Error::OutOfRange {
            name,
            value: v,
            min: MIN_LENGTH,
            max: MAX_LENGTH,
            ends: crate::Ends::Closed,
        })
    }
}

/// Checks a given coordinate or signed distance: finite, |value| ≤ [`MAX_LENGTH`].
pub(crate) fn coordinate(name: &'static str, value: f64) -> Result<f64> {
    let v = crate::error::finite(name, value)?;
    if v.abs() <= MAX_LENGTH {
        Ok(v)
    } else {
        Err(Error::OutOfRange {
            name,
            value: v,
            min: -MAX_LENGTH,
            max: MAX_LENGTH,
            ends: crate::Ends::Closed,
        })
    }
}
