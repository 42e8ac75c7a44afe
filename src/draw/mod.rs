//! Pictures of any planned linkage, as SVG (feature `draw`).
//!
//! Every picture is a pure function of plain inputs — a [`Plan`](crate::linkage::Plan), the
//! input motions of the positions to draw and a [`Style`] — and returns the SVG text with the
//! mapping it used ([`Picture`] with its [`Frame`], or [`Chart`] with its [`Panel`]s), so that
//! a program (or a test) can find any point of the linkage on the picture:
//! - [`scheme`]: the kinematic scheme at one position — bars for binary links, filled polygons
//!   for ternary and larger ones, hinges as circles, sliders as blocks on their guides, hatched
//!   ground, joint labels, the input's sense of motion, one scale on both axes;
//! - [`plan_view`]: the plan of the mechanism — the positions of a [`Course`] overlaid and
//!   numbered, its extreme positions bold, the paths (coupler curves) of named points;
//! - [`animation`]: a whole cycle that plays in any browser, one frame per position, by SMIL
//!   animation (no script);
//! - [`workspace`]: the region a point of a linkage with two inputs reaches, its outline and
//!   its singular curves, over the linkage ([`Plan::workspace`](crate::linkage::Plan::workspace));
//!   [`plan_view_two`] and [`animation_path`] draw a linkage with two inputs along a path of
//!   its inputs, and [`scheme`] and [`forces`] take both inputs' motions;
//! - [`forces`]: the reaction in every joint as a scaled arrow on the scheme, with the
//!   balancing moment or force;
//! - [`diagram`]: the diagrams over the cycle ([`Diagram`]) — an output's position, velocity
//!   and acceleration or its transfer functions, the balancing moment, the reactions'
//!   magnitudes and the hodograph of one reaction — with SI units on every axis and the
//!   course positions marked; [`diagram_two`] draws them for a linkage with two inputs along
//!   a path of its inputs (both balancing moments, an output's motion, the reactions).
//!
//! Conventions: the plane of the linkage (m, x right, y up) maps to the picture (px, x right,
//! y down) by [`Frame`], one scale for both axes, so angles look as they are. On the diagrams
//! the input is plotted along its own sense of rotation: the abscissa is the angle the crank
//! has turned from the first course position, whichever way it turns.
//!
//! Bounds: every style value is checked ([`Style::check`]: finite, positive where it must be,
//! a line width and hinge radius at most a tenth of the picture's smaller side), every frame
//! is finite ([`Frame::fit`]), and no picture writes a non-finite number (a last pass over
//! its text makes sure, [`Error::Overflow`](crate::Error::Overflow) if one slipped through).
//! The time of a picture is bounded by what it shows: [`scheme`] and [`forces`] by the
//! linkage's joints and links; [`plan_view`] by at most [`MAX_PLAN_POSITIONS`] drawn
//! positions (a longer course is thinned) and [`Style::samples`] path positions; [`diagram`]
//! by [`Style::samples`] analyses and at most [`MAX_PLAN_POSITIONS`] marks; [`animation`] by
//! at most [`MAX_FRAMES`] frames. Only the check of a course's inputs passes over all of them.
//!
//! The pictures use the `svg` crate for the schemes and plotters' SVG back end for the
//! diagrams; no markup is written by hand.
//!
//! # Example
//! ```
//! use tmm::draw::{scheme, Style};
//! use tmm::kinematics::Motion;
//! use tmm::linkage::{bundled, Plan};
//! let plan = Plan::new(&bundled::watt_six_bar())?;
//! let picture = scheme(&plan, Motion::new(1.0, 10.0, 0.0), &Style::default())?;
//! assert!(picture.svg.starts_with("<svg"));
//! // Where joint B is on the picture, in pixels:
//! let b = plan.kinematics(Motion::new(1.0, 10.0, 0.0))?.joint("B")?.p;
//! let [x, y] = picture.frame.to_pixel(b);
//! assert!(x > 0.0 && x < 800.0 && y > 0.0 && y < 600.0);
//! # Ok::<(), tmm::Error>(())
//! ```

mod animation;
mod diagrams;
mod diagrams_two;
mod forces;
mod frame;
mod limits;
mod parts;
mod plan_view;
mod primitives;
mod scene;
mod scheme;
mod style;
mod synthesis;
mod workspace;

pub use animation::{animation, animation_path};
pub use diagrams::{diagram, Chart, Diagram, Panel};
pub use diagrams_two::diagram_two;
pub use forces::forces;
pub use frame::Frame;
pub use plan_view::{plan_view, plan_view_two, MAX_PLAN_POSITIONS};
pub use scheme::{scheme, scheme_with_centres};
pub use style::Style;
pub use synthesis::{structural_error, synthesis_scheme, Targets, MAX_TARGET_VERTICES};
pub use workspace::{workspace, ASSEMBLY_COLOUR, ISOLATED_COLOUR, SERIAL_COLOUR, WORKSPACE_FILL};

/// The course of positions the plan and the diagrams draw; it lives in [`crate::linkage`]
/// (formerly `tmm::draw::Course`) and is re-exported here beside the pictures that take it.
pub use crate::linkage::Course;

/// The most positions one picture draws (frames of an animation, positions of a plan,
/// samples of a curve or a diagram): beyond it the SVG text would grow past what a browser
/// plays smoothly.
///
/// # Examples
/// ```
/// use tmm::draw::{animation, Style, MAX_FRAMES};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::four_bar())?;
/// let too_many = vec![Motion::new(1.0, 10.0, 0.0); MAX_FRAMES + 1];
/// assert!(animation(&plan, &too_many, 1.0, &Style::default()).is_err());
/// # Ok::<(), tmm::Error>(())
/// ```
pub const MAX_FRAMES: usize = 20_000;

/// A drawn picture: its SVG text and the mapping from the plane of the linkage to its pixels.
///
/// # Examples
/// Written to a file as it is:
/// ```no_run
/// use tmm::draw::{scheme, Style};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::shaper())?;
/// let picture = scheme(&plan, Motion::new(0.3, 10.0, 0.0), &Style::default())?;
/// std::fs::write("shaper.svg", &picture.svg)?;
/// assert_eq!(picture.force_scale, None);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// The SVG document.
    pub svg: String,
    /// How the plane of the linkage (m) maps to the picture's pixels.
    pub frame: Frame,
    /// For a picture of forces ([`forces`]): the force an arrow one pixel long stands for, N
    /// per px. `None` for pictures without forces.
    pub force_scale: Option<f64>,
}
