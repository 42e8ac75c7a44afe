//! The integration tests of `tmm`: one test binary whose modules mirror `src/`, so that the
//! tests of a module are found under its name (`tests/linkage/` for `src/linkage/`, …) and the
//! build links one test binary instead of one per file.
//!
//! Run one subject with a filter on its module path: `cargo test --test tmm linkage::`,
//! `cargo test --test tmm hostile:: -- --skip linkage::` (the adversarial suite of the blocks;
//! `TMM_HOSTILE_CASES` sets its size). Proptest keeps its regressions beside each source file
//! (`<file stem>.proptest-regressions`): the root is deliberately not named `main.rs`, which
//! would move them into a `proptest-regressions/` tree at the top of the repository.

mod architecture;
mod batch;
mod common;
mod docs_links;
#[cfg(feature = "serde")] // it draws the bundled linkages
mod draw;
mod dynamics;
mod errata;
mod friction;
mod hostile;
mod kinematics;
mod kinetostatics;
mod linkage;
mod mechanism;
mod synthesis;
mod triad;
mod triad_fast;
mod triad_scale;
mod triad_slider;
mod triad_slider_branch;
mod triad_slider_stretch;
mod unit;
mod work_precision;
