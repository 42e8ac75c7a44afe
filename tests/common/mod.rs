//! Helpers shared by the subjects: the generator of hostile inputs, the scan of an SVG.

pub mod fd;
pub mod hostile_gen;
pub mod svg_scan;
