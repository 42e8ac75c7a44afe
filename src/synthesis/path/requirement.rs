//! What a path synthesis is asked for: the target points and their timing, and the search's
//! options.

use crate::synthesis::Options;
use std::time::Duration;

/// How the crank's angles at the target points are given.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Timing {
    /// Free: the crank may be at any angle at each point (path generation without prescribed
    /// timing), but meets the points in their order, turning one way by less than a turn.
    /// Nine dimensions and one angle per point: at least 9 points.
    Free,
    /// Prescribed: the crank has turned by `Δφ_i` (rad, one per point, the first usually 0)
    /// from an angle θ0 that the search chooses. Ten unknowns: at least 5 points.
    Prescribed(Vec<f64>),
    /// The points sample a closed curve, in order: the crank turns fully and the coupler
    /// point runs around the curve once per turn. At least 9 points.
    ClosedCurve,
}

/// A path-generation requirement: target points of the coupler point, m, and the timing.
#[derive(Debug, Clone, PartialEq)]
pub struct PathRequirement {
    /// The target points, m.
    pub points: Vec<[f64; 2]>,
    /// The crank's angles at them.
    pub timing: Timing,
}

/// The search's options.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PathOptions {
    /// \[γ\] and the options common to the synthesis methods.
    pub options: Options,
    /// The largest ratio of the longest to the shortest of the four links (a slider-crank's
    /// crank and rod), in (1, [`MAX_LINK_RATIO`](crate::synthesis::MAX_LINK_RATIO)]. Default 10.
    pub max_link_ratio: f64,
    /// The largest link length and distance of a pivot from the points' centroid, in units of
    /// the path's size (the largest distance of a point from the centroid). Default 5. Every
    /// design returned keeps it (the six-bar's box is listed at
    /// [`six_bar_path_generator`](super::six_bar_path_generator)).
    pub max_size: f64,
    /// The seed of the search (the same seed gives the same designs unless `max_time` cuts
    /// the search short).
    pub seed: u64,
    /// The population of the differential evolution. Default 120.
    pub population: usize,
    /// The budget of candidate evaluations, at least twice the population: a candidate over
    /// a turn of `positions` (with prescribed timing: at its prescribed angles and the range
    /// between them sampled every 0.035 rad) in the global stage. Every other solve counts by
    /// the positions it solves in that unit: in the polish (its Jacobian's columns and the
    /// six-bar's continuation included) a candidate at the n target points counts as n of
    /// them, a whole check of a design as the points and its range every 1°. Default
    /// 200 000.
    pub max_evaluations: usize,
    /// The budget of wall-clock time, positive, of the global stage and the polish alike
    /// (a polish that reaches it ends where it is, and its result is still checked whole).
    /// Default 60 s.
    pub max_time: Duration,
    /// How many distinct designs to return, best first, at least 1. Default 3.
    pub designs: usize,
    /// Crank positions per turn in the global stage. Default 360.
    pub positions: usize,
    /// The mean miss, in path sizes, at which a design counts as meeting the points: the
    /// search stops once `designs` designs do. Default 1e-9.
    pub tolerance: f64,
}

impl Default for PathOptions {
    fn default() -> Self {
        Self {
            options: Options::default(),
            max_link_ratio: 10.0,
            max_size: 5.0,
            seed: 23,
            population: 120,
            max_evaluations: 200_000,
            max_time: Duration::from_secs(60),
            designs: 3,
            positions: 360,
            tolerance: 1e-9,
        }
    }
}

impl PathOptions {
    /// With \[γ\] = `angle`, rad.
    #[must_use]
    pub fn with_min_transmission_angle(mut self, angle: f64) -> Self {
        self.options = self.options.with_min_transmission_angle(angle);
        self
    }
    /// With the largest link ratio `ratio`.
    #[must_use]
    pub fn with_max_link_ratio(mut self, ratio: f64) -> Self {
        self.max_link_ratio = ratio;
        self
    }
    /// With the size bound `size` (in path sizes).
    #[must_use]
    pub fn with_max_size(mut self, size: f64) -> Self {
        self.max_size = size;
        self
    }
    /// With the seed `seed`.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
    /// With the population `n`.
    #[must_use]
    pub fn with_population(mut self, n: usize) -> Self {
        self.population = n;
        self
    }
    /// With the evaluation budget `n`.
    #[must_use]
    pub fn with_max_evaluations(mut self, n: usize) -> Self {
        self.max_evaluations = n;
        self
    }
    /// With the time budget `t`.
    #[must_use]
    pub fn with_max_time(mut self, t: Duration) -> Self {
        self.max_time = t;
        self
    }
    /// Returning `k` designs.
    #[must_use]
    pub fn with_designs(mut self, k: usize) -> Self {
        self.designs = k;
        self
    }
}
