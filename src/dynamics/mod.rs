//! Dynamics of machines with two degrees of freedom (seed 003): Lagrange's equations of the
//! 2nd kind, three integrators behind one interface, stop conditions, and the seed's four
//! machines.
//!
//! - [`LagrangeSystem`]: a machine as its inertia matrix A(q) (I11, I14, I44 in the seed), the
//!   derivatives of A (analytic or a documented numerical fallback), the generalized forces
//!   Q(t, q, q̇), a potential Π(q) and Rayleigh's dissipation function; [`accelerations`]
//!   solves A q̈ = Q − c(q, q̇) − ∇Π − B q̇ with the Christoffel terms c, derived once.
//! - [`Stepper`]: [`FiniteIncrement`] (the seeds' method, order 1), [`Rk4`] (order 4) and
//!   [`Dopri5`] (adaptive, Dormand–Prince 5(4), asks for an accuracy instead of a step).
//! - [`run`]: stops at a final time, when a watched quantity reaches a value (located inside
//!   the step), or at a steady state, and says when a steady state can never come
//!   ([`Outcome::Drifting`]). The motion is recorded as a [`Trajectory`] (columns, CSV).
//!   Every step lands exactly on the breakpoints (times given in [`RunOptions::breakpoints`]
//!   or by the system) and on the kinks of the forces in the state (located inside the step,
//!   the earliest first where several arguments cross their nodes in one step: the landing
//!   gear's load-table nodes, each servo's clamp), so that no step straddles a kink; the state at
//!   requested [`RunOptions::times`] comes from Dormand–Prince's continuous extension
//!   ([`DenseOutput`]) or from fixed steps that end exactly there. A resistance that opposes
//!   a motion (a velocity-sign switch, [`LagrangeSystem::switches`]) is held in one direction
//!   through each step; the run lands on the zero of the speed it opposes and weighs the
//!   loads there ([`SwitchLoads`]): the motion reverses, or sticks and the run ends
//!   ([`Outcome::Stuck`]), instead of chattering about the zero.
//! - [`machines`]: the five-bar robot (§2), the R–P arm and its decoupled variant (§3), the
//!   landing-gear drive (§4) and the coaxial-propeller drive (§5), each with realistic
//!   default data.
//!
//! Errors, never NaN: a non-positive-definite inertia matrix ([`Error::NotPositiveDefinite`],
//! with the time and coordinates), a non-finite state ([`Error::NonFiniteState`], with the
//! time), a step that is not positive ([`Error::NonPositive`]), a table lookup outside its
//! range ([`Error::OutOfRange`]).
//!
//! [`Error::NotPositiveDefinite`]: crate::Error::NotPositiveDefinite
//! [`Error::NonFiniteState`]: crate::Error::NonFiniteState
//! [`Error::NonPositive`]: crate::Error::NonPositive
//! [`Error::OutOfRange`]: crate::Error::OutOfRange

mod dopri;
mod finite_increment;
pub mod machines;
mod rk4;
mod run;
mod stepper;
mod switch;
mod system;
mod table;
mod trajectory;

pub use dopri::{DenseOutput, Dopri5};
pub use finite_increment::FiniteIncrement;
pub use rk4::Rk4;
pub(crate) use run::run_to_reversal;
pub use run::{run, Direction, Outcome, Reach, RunOptions, RunResult, Steady, Watch};
pub use stepper::{Advance, ContinuousExtension, Handover, NoExtension, Stepper};
pub use switch::SwitchLoads;
pub use system::{
    accelerations, christoffel_terms, kinetic_energy, powers, LagrangeSystem, LagrangeTerms, State,
};
pub(crate) use system::{checked_inertia, kink_slots};
pub use table::{Beyond, Table};
pub use trajectory::Trajectory;
