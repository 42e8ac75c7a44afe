//! Kinematics of planar linkages of the 2nd class by closed vector contours, group by group
//! (seed 001).
//!
//! A mechanism of the 2nd class is an input link with Assur dyads attached one after another.
//! Each dyad closes one vector contour with two unknown scalars ([`solve_contour`]); its
//! block takes the known joints with their velocities and accelerations and gives the
//! dyad's state, so a mechanism is a short chain of calls in the order the groups are
//! attached (the seed's group-wise method):
//!
//! - [`crank`]: the input link (φ1, ω1, ε1) → the crank pin;
//! - [`rrr_dyad`] (SR1), [`rrp_dyad`] (SR2), [`rpr_dyad`] (SR3): joint points, link angles,
//!   ω and ε of each link, the slider's coordinate with its relative velocity and
//!   acceleration, and [`LinkMotion::motion_of`] for any point of a link (centres of mass,
//!   coupler points). Their outputs are what [`Load::inertia`](crate::Load::inertia) and the
//!   kinetostatic solvers take;
//! - [`prp_dyad`] (two sliders hinged together, each on a guide of a known link) and
//!   [`rpp_dyad`] (a link hinged at A sliding in a link that slides on a guide, as in the
//!   Scotch yoke): the two slides with their relative velocities and accelerations and the
//!   Coriolis terms on turning guides;
//! - transfer functions ([`transfer_functions`], [`Motion::at_input_speed`]);
//! - a cycle of positions ([`cycle`]), where a linkage locks ([`assembly_range`]), extreme
//!   positions ([`extreme_positions`]), the strokes and the 12 plans ([`Strokes`]), Grashof's
//!   classification of a four-bar ([`grashof`]);
//! - tabulated functions: [`differentiate`] (three-point) and [`integrate_trapezoid`].
//!
//! Every block reports its conditioning (`det`: sin(φ3 − φ2) for RRR, cos(φ2 − φ4) for RRP):
//! velocities grow like 1/det near a dead point, and at a dead point the block returns
//! [`Error::Singular`](crate::Error::Singular) instead of an infinity. A position that cannot
//! be assembled is [`Error::NotAssemblable`](crate::Error::NotAssemblable) with the gap.
//! PRP and RPP report sin(φg3 − φg2) (the angle between the two guides) and sin α (between
//! the slide and the guide, a constant of the design) the same way; they always assemble.
//!
//! # Example: a crank-rocker four-bar
//! Frame O C = 0.4 m along +x, crank 0.1 m, coupler 0.35 m, rocker 0.3 m, the crank at 60°
//! turning at 10 rad/s. The coupler's midpoint S2 gets its acceleration for the inertia load;
//! the rocker's ω3 equals φ3′·ω1.
//! ```
//! use nalgebra::Point2;
//! use approx::assert_relative_eq;
//! use tmm::kinematics::{crank, rrr_dyad, transfer_functions, Branch, Motion, PointMotion};
//! let c = PointMotion::fixed(Point2::new(0.4, 0.0));
//! let input = Motion::new(60f64.to_radians(), 10.0, 0.0);
//! let a = crank(Point2::origin(), 0.1, input)?.a;
//! let d = rrr_dyad(a, c, 0.35, 0.3, Branch::Plus)?;
//! // Loop closure: |AB| and |CB| are the link lengths.
//! assert_relative_eq!((d.b.p - a.p).norm(), 0.35, epsilon = 1e-15);
//! assert_relative_eq!((d.b.p - c.p).norm(), 0.3, epsilon = 1e-15);
//! let s2 = d.link2.point_at(0.175, 0.0);
//! let inertia = tmm::Load::inertia(s2.p, 1.2, s2.a, 0.012, d.link2.epsilon)?;
//! assert_relative_eq!(inertia.force, -1.2 * s2.a);
//! let phi3 = transfer_functions(
//!     |m| Ok(rrr_dyad(crank(Point2::origin(), 0.1, m)?.a, c, 0.35, 0.3, Branch::Plus)?.link3.angle_motion()),
//!     input.value,
//! )?;
//! assert_relative_eq!(d.link3.omega, phi3.rate * 10.0, epsilon = 1e-12);
//! # Ok::<(), tmm::Error>(())
//! ```

mod assur;
pub mod batch;
mod contour;
mod crank;
mod cycle;
mod extreme;
mod fast_angle;
mod fold;
mod fold_point;
mod grashof;
mod link;
mod lu_work;
mod motion;
mod numeric;
mod prp;
mod rpp;
mod rpr;
mod rrp;
mod rrr;
mod transfer;
mod triad;
mod triad_fast;
mod triad_newton;
mod triad_slider;
mod triad_slider_fast;
mod trig_cubic;
mod trig_roots;

pub use assur::{GroupMotion, GroupPose, GroupReactions, GroupWork, HingeEnd, HingedGroup};

pub use contour::{
    contour_residual, solve_contour, solve_contour_position, Branch, ContourCase, ContourSolution,
    LoopVector, Part, SINGULAR_DETERMINANT,
};
pub use crank::{crank, CrankState};
pub use cycle::{
    assembly_range, coupler_curve, cycle, cycle_angles, try_cycle_angles, ISOLATED_GAP,
    MAX_POSITIONS,
};
pub use extreme::{extreme_positions, Extreme, ExtremeKind, Rotation, Strokes};
pub use fold::SINGULAR_BRANCH;
pub(crate) use fold::{Leg, Legs};
pub use grashof::{grashof, Grashof};
pub(crate) use link::frame_offset;
pub use link::LinkMotion;
pub use motion::{Motion, PointMotion};
pub use numeric::{differentiate, differentiate_periodic, integrate_trapezoid};
pub use prp::{prp_dyad, PrpState};
pub use rpp::{rpp_dyad, RppState};
pub(crate) use rpr::rpr_rates;
pub use rpr::{rpr_dyad, RprState};
pub(crate) use rrp::rrp_rates;
pub use rrp::{rrp_dyad, Guide, RrpState};
pub(crate) use rrr::rrr_rates;
pub use rrr::{rrr_dyad, RrrState};
pub use transfer::transfer_functions;
pub(crate) use triad::ensure_off_branch;
pub use triad::{
    triad, triad_modes, triad_rates, triad_tracked, AssemblyModes, TriadDims, TriadModes,
    TriadPose, TriadState, MAX_TRIAD_MODES, SINGULAR_TRIAD,
};
pub use triad_slider::{
    slider_triad, slider_triad_continued, slider_triad_modes, slider_triad_position,
    slider_triad_rates, slider_triad_tracked, SliderTriadDims, SliderTriadModes, SlidingPair,
    MAX_SLIDER_TRIAD_MODES,
};
