//! The integration tests of `tmm`'s building blocks: kinematics, kinetostatics, dynamics, the
//! ready mechanisms, friction, units, the work-precision data, the architecture and the docs'
//! links, and the adversarial suite of the blocks (`hostile`). The engine over described
//! linkages is the other test binary, `tests/tmm.rs` (see there why there are two).
//!
//! Run one subject with a filter on its module path: `cargo test --test blocks dynamics::`,
//! `cargo test --test blocks hostile::` (`TMM_HOSTILE_CASES` sets its size).

mod architecture;
// Shared with `tests/tmm.rs`; each binary uses a part of it.
#[allow(dead_code)]
mod common;
mod docs_links;
mod dynamics;
mod errata;
mod friction;
mod hostile;
mod kinematics;
mod kinetostatics;
mod mechanism;
mod unit;
mod work_precision;
