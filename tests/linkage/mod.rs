//! `tmm::linkage`: the engine against independent references (engine), the bundled description
//! files (files), hostile descriptions and inputs (hostile), and a described linkage's dynamics.

mod dynamics;
mod engine;
mod files;
mod hostile;
