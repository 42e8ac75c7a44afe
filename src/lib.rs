//! # tmm — theory of machines and mechanisms
//!
//! Planar linkages of the 2nd class and gear drives: the force analysis (kinetostatics) of the
//! Assur dyads and of the input link, the kinematics of closed vector contours, and the
//! dynamics of machines with two degrees of freedom. Exact where the textbooks are exact,
//! honest where the mathematics breaks down (every singular configuration is an [`Error`] that
//! names the quantity that vanished), and fast: every solver is a pure function of plain data.
//!
//! ## Module map
//! - [`angle`]: direction angles (the seeds' UGL helpers), unit vectors, the 2-D cross product.
//! - [`load`]: a force at a point plus a moment; d'Alembert's inertia loads.
//! - [`kinematics`]: closed vector contours; the crank and the RRR, RRP, RPR, PRP, RPP dyad blocks;
//!   transfer functions, cycles, extreme positions; numerical differentiation and integration.
//! - [`dynamics`]: 2-DOF machines by Lagrange's equations; finite increments, RK4 and
//!   Dormand–Prince; the five-bar robot, the R–P arm, the landing-gear and coaxial-propeller drives.
//! - [`kinetostatics`]: joint reactions of the RRR, RRP, RPR, PRP and RPP dyads; the input link driven
//!   through a coupling (balancing moment) or a gear pair (balancing force).
//! - [`kinetostatics::passive`]: the group with a parallel coupler (a passive constraint), statically
//!   indeterminate once, solved by the force method; N, Q, M diagrams of its links.
//! - [`linkage`]: any linkage of the 2nd class as data, planned once and analysed per position.
//! - `draw` (feature `draw`): pictures of a linkage as SVG — the scheme, the plan of positions,
//!   an animation, force arrows, the diagrams over the cycle.
//! - [`linkage`]: any linkage of the 2nd class as data (one input, or two for mobility 2),
//!   planned once and analysed per position; [`linkage::dynamics`]: its equation of motion
//!   from the exact transfer functions, run-up under a motor, speed fluctuation, flywheel.
//! - [`synthesis`]: requirement → description: quick-return mechanisms by the time ratio and the
//!   stroke, Freudenstein's function generation, Burmester's motion generation.
//! - [`mechanism`]: five ready mechanisms as linkages (four-bar, slider-crank, compressor, six-bar,
//!   rocking cylinder), each a struct of parameters whose `linkage()` the engine plans.
//!
//! ## The seed programs
//! The crate grew from four Ukrainian and Russian course texts, called seed 000 to seed 003 in
//! its comments (kinetostatics, kinematics, passive constraints, dynamics of 2-DOF machines);
//! `docs/sources.md` in the repository names them, and `docs/errata.md` lists every misprint of
//! theirs that the crate corrects, each with its derivation and the test that checks it. Their
//! FORTRAN-era programs have short names, kept as documentation aliases, so searching the docs
//! for `SR1` finds the RRR dyad:
//!
//! | seed   | meaning                                     | in `tmm` |
//! |--------|---------------------------------------------|----------|
//! | SR1    | group of the 2nd class, 1st kind            | [`kinetostatics::RrrDyad`] |
//! | SR2    | group of the 2nd class, 2nd kind            | [`kinetostatics::RrpDyad`] (slider on a guide) |
//! | SR3    | group of the 2nd class, 3rd kind            | [`kinetostatics::RprDyad`] (rod in a rocking cylinder) |
//! | SRWL1  | input link driven through a gear pair       | [`kinetostatics::GearDrive`] (balancing force) |
//! | SRWL2  | input link driven through a coupling        | [`kinetostatics::CouplingDrive`] (balancing moment) |
//! | UGL2–4 | direction angles of vectors and lines       | [`angle::signed_direction`], [`angle::direction`], [`angle::line_of_action`] |
//!
//! ## Conventions
//! SI units (m, kg, s, N, N·m, rad); the plane frame has x to the right and y up; angles are
//! counter-clockwise from +x, and an angle the crate returns lies in [0, 2π). `R_ij` is the
//! force that link i exerts on link j, so `R_ji = −R_ij`. Links are numbered as in the seeds:
//! 1 the input link, 2 and 3 the dyad, 4 the link the dyad meets at its outer pair (often the
//! frame). Points are [`nalgebra::Point2`], vectors [`nalgebra::Vector2`].
//!
//! ## Optional features
//! - `serde`: serialization of the crate's plain-data types (inputs, results, tables).
//! - `rayon`: cycles of mechanism positions in parallel, bit-identical to the serial run.
//! - `draw` (on by default): pictures of any linkage as SVG ([`draw`]): the kinematic scheme,
//!   the plan in 12 positions, an animated cycle, reaction forces, and the diagrams.
//!
//! On docs.rs every item that needs a feature says so.

#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod angle;
#[cfg(feature = "draw")]
#[cfg_attr(docsrs, doc(cfg(feature = "draw")))]
pub mod draw;
pub mod dynamics;
pub mod error;
pub mod kinematics;
pub mod kinetostatics;
pub mod linkage;
pub mod load;
pub mod mechanism;
pub mod synthesis;

pub use error::{Ends, Error, Result};
pub use load::Load;

/// The linear algebra crate whose types appear in every signature of `tmm` (`Point2`,
/// `Vector2`, `Matrix2`). Re-exported so that a user builds those types from the very version
/// `tmm` was compiled against, without adding (and keeping in step) a dependency of their own:
/// `use tmm::nalgebra::{Point2, Vector2};`.
pub use nalgebra;

// The README's example is compiled and run as a doc test, so it cannot rot.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
