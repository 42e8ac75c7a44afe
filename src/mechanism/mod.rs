//! Five ready mechanisms of course projects, each a plain struct of SI parameters that
//! becomes a [`Linkage`](crate::linkage::Linkage) for the [linkage engine](crate::linkage).
//!
//! Every ready mechanism has a constructor of realistic data (`course_example()`), and
//! implements [`Mechanism`] (bring it into scope: `use tmm::mechanism::Mechanism`):
//! - `linkage()`: its description — the joints in a reference pose computed from the
//!   parameters (at a crank angle where it assembles in the assembly modes its `branch`
//!   fields give, which the description also states in `modes`), named links with their
//!   masses ([`LinkMass`] converted to [`Mass`](crate::linkage::Mass)), its loads and its
//!   drive;
//! - `plan()`: that description planned ([`Plan::new`](crate::linkage::Plan::new)), ready to
//!   analyse any position with [`Plan::analyse`](crate::linkage::Plan::analyse): kinematics,
//!   loads, every joint's reaction, the balancing moment or force, and the checks
//!   ([`Analysis::power_check`](crate::linkage::Analysis::power_check),
//!   [`Analysis::worst_residual`](crate::linkage::Analysis::worst_residual));
//! - `strokes(rotation)`: the strokes of its output.
//!
//! | mechanism | groups | output | loads |
//! |-----------|--------|--------|-------|
//! | [`FourBar`] | crank + RRR | `rocker` | a moment resisting the rocker |
//! | [`SliderCrank`] | crank + RRP | piston slide `P` | an indicator diagram |
//! | [`Compressor`] | crank with two throws + RRP + RRP (seed 001) | slides `P1`, `P2` | two indicator diagrams |
//! | [`SixBar`] | crank + RRR + RRP (seed 001, fig. 2.10's type) | slider slide `Q` | a working-stroke resistance |
//! | [`RockingCylinder`] | crank + RPR | `cylinder` | the fluid's resistance to sliding |
//!
//! A failed position (a group at a dead point, or one that cannot be assembled) is an
//! [`Error::In`](crate::Error::In) naming the group, for that position only:
//! [`run_cycle`](crate::linkage::run_cycle) goes on past it. A mechanism of another layout is
//! a [`Linkage`](crate::linkage::Linkage) written directly.
//!
//! # Example
//! The course-project six-bar at 30° of its crank, and the two ways to its balancing moment:
//! ```
//! use tmm::kinematics::Motion;
//! use tmm::mechanism::{Mechanism, SixBar};
//! let plan = SixBar::course_example().plan()?;
//! let p = plan.analyse(Motion::new(30f64.to_radians(), 10.0, 0.0))?;
//! let check = p.power_check()?;
//! assert!(check.relative_error() < 1e-9);
//! assert!(p.worst_residual() < 1e-12);
//! assert!(p.reaction("Q")?.force.norm() > 0.0);
//! # Ok::<(), tmm::Error>(())
//! ```

mod compressor;
mod four_bar;
mod link;
mod ready;
mod rocking_cylinder;
mod six_bar;
mod slider_crank;

pub use compressor::Compressor;
pub use four_bar::FourBar;
pub use link::LinkMass;
pub use ready::Mechanism;
pub use rocking_cylinder::RockingCylinder;
pub use six_bar::SixBar;
pub use slider_crank::SliderCrank;

/// serde for the crate's types that this module stores (feature `serde`).
#[cfg(feature = "serde")]
pub(crate) mod serde_remote {
    /// [`Branch`](crate::kinematics::Branch) as "Plus" or "Minus".
    #[derive(serde::Serialize, serde::Deserialize)]
    #[serde(remote = "crate::kinematics::Branch")]
    pub(crate) enum BranchDef {
        Plus,
        Minus,
    }
}
