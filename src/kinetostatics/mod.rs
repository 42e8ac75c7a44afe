//! Kinetostatics: the joint reactions of the Assur dyads of the 2nd class and of the input
//! link, by d'Alembert's principle (seed 000).
//!
//! Inertia loads are added to the external loads ([`Load::inertia`](crate::Load::inertia)),
//! and each group is then a static problem solved in closed form. The order of a whole
//! analysis is the seeds' (§1.2): the group attached last is solved first, its reactions are
//! applied (reversed, `R_ji = −R_ij`) to the group before it, and so on back to the input
//! link, which gives the balancing moment ([`CouplingDrive`]) or force ([`GearDrive`]).
//!
//! Every solver takes Cartesian points and one resultant [`Load`](crate::Load) per link, and
//! returns every reaction as a vector together with a [`Conditioning`]: the quantity its closed
//! form divides by, and how much that division amplifies rounding errors. An exactly singular
//! configuration (a dead point, a zero arm) is an [`Error::Singular`](crate::Error::Singular)
//! naming that quantity. The `*Seed` adapters take the seeds' notation (lengths along links,
//! angles, magnitudes with direction angles), so a textbook problem reads like the textbook.
//!
//! | group | solver | singular when |
//! |-------|--------|---------------|
//! | RRR (SR1) | [`RrrDyad`] | links 2 and 3 collinear: sin(φ3 − φ2) = 0 |
//! | RRP (SR2) | [`RrpDyad`] | link 2 perpendicular to the guide: cos(φ2 − φ4) = 0 |
//! | RPR (SR3) | [`RprDyad`] | the hinge A on the normal to the axis through E: l_EA = 0 |
//! | PRP | [`PrpDyad`] | the two guides parallel: sin(φg3 − φg2) = 0 |
//! | RPP | [`RppDyad`] | the slide parallel to the guide: sin α = 0 (a constant of the design) |
//! | gear input (SRWL1) | [`GearDrive`] | zero arm of the tooth force: r_w·cos α_w = 0 |
//! | coupling input (SRWL2) | [`CouplingDrive`] | never |
//! | triad (3rd class) | [`Triad`] | the three binary links' lines concurrent or parallel: det K = 0 |
//!
//! The group with a parallel coupler (seed 002), a passive constraint that makes it statically
//! indeterminate once, is solved by the force method in [`passive`].

mod conditioning;
mod coupling;
pub mod friction;
mod gear;
pub mod passive;
mod prp;
mod rpp;
mod rpr;
mod rrp;
mod rrr;
mod triad;
mod triad_slider;

pub use conditioning::Conditioning;
pub use coupling::{CouplingBalance, CouplingDrive, CouplingSeed};
pub use gear::{Flank, GearBalance, GearDrive, GearSeed};
pub use prp::{PrpDyad, PrpReactions};
pub use rpp::{RppDyad, RppReactions};
pub use rpr::{RprDyad, RprReactions, RprSeed};
pub use rrp::{RrpDyad, RrpReactions, RrpSeed};
pub use rrr::{RrrDyad, RrrReactions, RrrSeed};
pub use triad::{Triad, TriadReactions};
pub use triad_slider::{SlideAt, SliderTriad, SliderTriadReactions};
