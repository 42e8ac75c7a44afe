//! The plan of a triad's sliding leg (a triad with one sliding pair): the block's dimensions
//! and where the known link carries the guide.

use crate::kinematics::SliderTriadDims;

/// The sliding leg of a triad with a sliding pair (always the triad's first leg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SliderLeg {
    /// The group's dimensions as [`slider_triad`](crate::kinematics::slider_triad) reads them.
    pub dims: SliderTriadDims,
    /// The outer pair's guide direction relative to its known link's frame, rad (its point is
    /// the triad's `a_local[0]`); zero for the inner pair.
    pub guide_offset: f64,
}
