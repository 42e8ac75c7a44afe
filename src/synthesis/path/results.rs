//! What a path synthesis reports: its progress while it searches, and the designs it finds.

use crate::synthesis::Synthesis;
use std::time::Duration;

/// Where the search is, for a progress callback.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Progress {
    /// The generation of the differential evolution.
    pub generation: usize,
    /// Candidate evaluations so far.
    pub evaluations: usize,
    /// The best objective so far, in path sizes: the mean miss at the points with prescribed
    /// timing, the RMS miss of the best-placed coupler curve without (≥ 1000 while no
    /// candidate is feasible: a penalty then). The best over every run of the search: it
    /// never rises from one call to the next, restarts included.
    pub best: f64,
    /// Time since the start.
    pub elapsed: Duration,
}

/// One synthesised path generator.
#[derive(Debug, Clone, PartialEq)]
pub struct PathDesign {
    /// The description (joints `O1`, `A`, `B`, `O3`, the coupler point `P` on the coupler),
    /// posed at the crank angle of the first point, and its report.
    pub synthesis: Synthesis,
    /// The mean distance of the coupler point from the targets, m.
    pub mean_error: f64,
    /// The largest distance, m.
    pub max_error: f64,
    /// The crank angle (world, rad, the engine's input) at each target.
    pub crank_angles: Vec<f64>,
    /// The coupler point reached at each of them, m.
    pub coupler_points: Vec<[f64; 2]>,
}
