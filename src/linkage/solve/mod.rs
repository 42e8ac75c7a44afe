//! One position of a plan, one concept a file: the kinematic buffers (`state`), the
//! position pass (`position`), the rates-only pass (`rates`), the loads (`loads`), the
//! kinetostatics (`statics`) and the two checks (`checks`); `analysis` holds the
//! buffers of a whole analysis and reads its results.

pub(crate) mod analysis;
mod checks;
pub(crate) mod loads;
pub(crate) mod position;
mod rates;
pub(crate) mod state;
mod statics;

pub use analysis::{Analysis, Balance, Reaction};
pub use checks::PowerCheck;
