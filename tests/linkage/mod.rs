//! `tmm::linkage`: the engine against independent references (engine), the bundled description
//! files (files), hostile descriptions and inputs (hostile), and a described linkage's dynamics.

// The bundled linkages are read from their JSON files: the tests that use them need `serde`.
#[cfg(feature = "serde")]
mod dynamics;
#[cfg(feature = "serde")]
mod engine;
mod files;
#[cfg(feature = "serde")]
mod friction;
#[cfg(feature = "serde")]
mod general;
#[cfg(feature = "serde")]
mod hostile;
mod planning;
mod singular;
#[cfg(feature = "serde")]
mod triad;
