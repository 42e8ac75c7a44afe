//! The integration tests of `tmm`'s engine over described linkages: linkages, groups of the 3rd
//! class, synthesis, pictures and batches. The building blocks (kinematics, kinetostatics,
//! dynamics, ready mechanisms, friction, units and their adversarial suite) are the other test
//! binary, `tests/blocks.rs`. Two binaries rather than one halve the longest compile of a cold
//! `cargo test`: the two front ends run side by side on two cores. The modules of each mirror
//! `src/`, so that the tests of a module are found under its name (`tests/linkage/` for
//! `src/linkage/`, …).
//!
//! Run one subject with a filter on its module path: `cargo test --test tmm linkage::`,
//! `cargo test --test tmm linkage::hostile::` (the adversarial suite of described linkages;
//! `TMM_HOSTILE_CASES` sets its size). Proptest keeps its regressions beside each source file
//! (`<file stem>.proptest-regressions`): the root is deliberately not named `main.rs`, which
//! would move them into a `proptest-regressions/` tree at the top of the repository.

mod batch;
// Shared with `tests/blocks.rs`; each binary uses a part of it.
#[allow(dead_code)]
mod common;
#[cfg(feature = "serde")] // it draws the bundled linkages
mod draw;
mod linkage;
mod synthesis;
mod triad;
mod triad_slider;
