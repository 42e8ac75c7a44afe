//! Kinetostatics: joint reactions of Assur groups, including the statically indeterminate group with a passive constraint.
pub mod passive;
