//! The group with a parallel coupler: a passive constraint, statically indeterminate once,
//! solved by the force method (seed 002, Ambartsumyants & Chizh).
//!
//! An Assur group of the 2nd class (links 1 = AB and 3 = B–D–E, hinged to the frame at A and
//! E) gets a second coupler 2 = CD parallel to AB, hinged to the frame at C and to link 3 at
//! D. The extra link brings two hinges (four force components) but only three equations: the
//! group is statically indeterminate once ([`indeterminacy`]: n = 3σ − p1 = 2p1 − 3m = 1), and
//! rigid-body statics cannot say how the load is shared between the two couplers. The force
//! method can:
//! release the hinge C along CD, call the frame's force there X1, and demand that C does not
//! move, δ11·X1 + Δ1F = 0, with δ11 and Δ1F from the bending (and, optionally, axial)
//! deformation of the links ([`solve`]).
//!
//! What the crate adds to the seed:
//! - any geometry and any loads of the type, not only the paper's figure: link 3 may be bent at
//!   D, the loads may sit anywhere on their links and carry couples, each link may carry a
//!   uniformly distributed load (then the moment diagrams are quadratic and Simpson's formula
//!   is what keeps the integrals exact);
//! - the axial flexibility of the links ([`Stiffness::ea`]): the seed's inextensible links are
//!   the limit EA → ∞, and the redundant is sensitive to it (for the seed's example
//!   X1 = −62.4 N inextensible, about −46 N at EA·L²/EI = 10³);
//! - the internal forces N, Q, M at any section of every link, their extremes and where they
//!   occur ([`Solution::internal`], [`Solution::extremes`]), for the real group and for the
//!   loaded and unit states of the method ([`State`]);
//! - how close the group is to a singular configuration ([`Solution::conditioning`], the same
//!   figure every kinetostatic solver of the crate reports, with [`Solution::arm_ratio`] and
//!   [`Solution::delta11_ratio`]).
//!
//! Checked against an independent direct-stiffness frame model (tests/kinetostatics/passive.rs): over 5000
//! random groups the hinge forces agree to 3e-11 of the largest force (inextensible links, where
//! the δ11 ratio is above 1e-9: closer to its singular threshold neither model keeps the digits) and
//! 6e-11 (with EA), the released hinge's gap is at round-off, and every link is in equilibrium
//! to 2e-15 of the loads.
//!
//! The paper's example, in its notation, is [`PaperGroup`]; its printed Δ1F, X1 and R01ⁿ
//! carry a rounding slip, and its R02ᵗ a sign (see the example there, and docs/errata.md#p4 and #p5).

mod diagrams;
mod force_method;
mod geometry;
pub mod indeterminacy;
mod integrate;
mod loads;
mod paper;
mod statics;

pub use diagrams::{DiagramExtremes, Extreme, InternalForces};
pub use force_method::{solve, Flexibility, Solution, State, Stiffness};
pub use geometry::{Geometry, Link, Side};
pub use integrate::simpson_product;
pub use loads::{LinkLoad, Loads};
pub use paper::{PaperGroup, PaperResult};
pub use statics::Reactions;
