//! `tmm::linkage`: the engine against independent references (engine), the bundled description
//! files (files), hostile descriptions and inputs (hostile), and a described linkage's dynamics.

// The bundled linkages are read from their JSON files: the tests that use them need `serde`.
#[cfg(feature = "serde")]
mod dynamics;
#[cfg(feature = "serde")]
mod engine;
#[cfg(feature = "serde")]
mod examples_run;
mod files;
#[cfg(feature = "serde")]
mod friction;
#[cfg(feature = "serde")]
mod friction_stops;
#[cfg(feature = "serde")]
mod gallery;
#[cfg(feature = "serde")]
mod general;
#[cfg(feature = "serde")]
mod hostile;
#[cfg(feature = "serde")]
mod hostile_friction;
#[cfg(feature = "serde")]
mod instant_centres;
mod locks;
#[cfg(feature = "serde")]
mod modes;
mod planning;
#[cfg(feature = "serde")]
mod scale;
#[cfg(feature = "serde")]
mod scaled_tolerances;
mod singular;
#[cfg(feature = "serde")]
mod spares;
#[cfg(feature = "serde")]
mod springs;
mod strokes;
#[cfg(feature = "serde")]
mod table;
#[cfg(feature = "serde")]
mod table_row;
mod tracking;
#[cfg(feature = "serde")]
mod triad;
#[cfg(feature = "serde")]
mod twins;
#[cfg(feature = "serde")]
mod two_inputs;
#[cfg(feature = "serde")]
mod workspace;
#[cfg(feature = "serde")]
mod workspace_boundary;
