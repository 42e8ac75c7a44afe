//! Helpers shared by the subjects: the generator of hostile inputs.

pub mod hostile_gen;
