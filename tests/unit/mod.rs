//! The tests that lived beside their code in `src/` (`#[cfg(test)]` modules), moved here so
//! that `cargo test` compiles the library once (`[lib] test = false`): each checks the same
//! property through the public API. One file per source file, named after it.

mod angle;
mod error;
mod five_bar_check;
mod grashof;
mod indeterminacy;
mod indicator;
mod load;
mod passive_geometry;
mod simpson;
mod trajectory;
mod triad_modes;
mod workspace_region;
