//! One position of a plan, one concept a file: the kinematic buffers (`state`), the
//! position pass (`position`), the rates-only pass (`rates`), the loads (`loads`), the
//! kinetostatics (`statics`) and the two checks (`checks`); a dyad on twin dyads' inner
//! joints in their frame (`twin`); the results `kinematics` and
//! `analysis`, and the entry points (`solver`).

pub(crate) mod analysis;
mod checks;
mod dead_point;
mod friction;
mod friction_groups;
mod general;
pub(crate) mod kinematics;
pub(crate) mod loads;
pub(crate) mod position;
mod rates;
mod reaction;
mod singular;
mod solver;
pub(crate) mod spare;
pub(crate) mod state;
mod statics;
pub(crate) mod triad;
mod twin;
pub(crate) mod unit_frame;

pub use analysis::Analysis;
pub use checks::PowerCheck;
pub use dead_point::DEAD_POINT_RELATIVE_ERROR;
pub use kinematics::Kinematics;
pub use reaction::{Balance, Reaction};
pub use singular::{Position, DEAD_CENTRE_DETERMINANT};
pub use solver::Solver;
