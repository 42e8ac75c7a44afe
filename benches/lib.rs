//! `tmm-bench`: the criterion benches of `tmm` (one file per part beside this one), its
//! comparison with a peer ODE crate (`peers.rs`, ode_solvers) and the work-precision
//! charts of the README (`examples/work_precision.rs`, plotters).
//!
//! This package is a workspace member and is never published. It exists so that `cargo test`
//! in the root builds only what `tmm`'s tests need; criterion, plotters and ode_solvers (which
//! brings a second nalgebra) are built only by the commands that use them:
//!
//! ```text
//! cargo bench -p tmm-bench                      # all benches
//! cargo bench -p tmm-bench --bench peers        # tmm beside ode_solvers
//! cargo run --release -p tmm-bench --example work_precision docs/charts
//! ```
//!
//! The computations behind the charts live in the root's `tests/work_precision/`, where
//! `tests/work_precision/mod.rs` checks them without any of these dependencies.
