//! Helpers shared by the subjects: the generator of hostile inputs, the scan of an SVG, the
//! random linkages of the planning tests.

pub mod chains;
pub mod fd;
pub mod hostile_gen;
pub mod svg_scan;
