//! The search's budget of evaluations and time, shared by the global stage, the polish and
//! the checks, and the samples each of them solves.

use super::angles::min_max;
use super::requirement::Timing;
use std::cell::Cell;
use std::time::{Duration, Instant};

/// The search's budget, shared by the global stage and the polish, and wall-clock time.
/// Its unit is a candidate evaluation of the global stage: the positions it solves (a turn
/// of `positions` without prescribed timing; with it, the points and the samples of the
/// range between them). Everything else is counted by the positions it solves in that
/// unit: the polish's evaluation of a candidate at the n target points counts as n of them,
/// a whole check of a design as the points and the range sampled every 1°.
pub(super) struct Budget {
    pub(super) used: Cell<f64>,
    pub(super) max: usize,
    /// The share of `max` the global stage leaves to the polish of its last run.
    pub(super) reserve: f64,
    /// The positions one evaluation solves ([`positions_per_evaluation`]).
    pub(super) per_eval: f64,
    /// What one evaluation of the polish counts.
    pub(super) polish: f64,
    /// What the whole check of a polished design counts (at most): the polish always leaves
    /// that much for it.
    pub(super) check: f64,
    pub(super) start: Instant,
    pub(super) max_time: Duration,
}

impl Budget {
    /// Whether `k` more evaluations fit, in number and in time.
    pub(super) fn fits(&self, k: f64) -> bool {
        self.used.get() + k <= self.max as f64 && self.start.elapsed() < self.max_time
    }
    /// Whether `n` more evaluations fit, in number and in time.
    pub(super) fn room(&self, n: usize) -> bool {
        self.fits(n as f64)
    }
    /// Whether `n` more evaluations fit in the global stage's share: the polish of the last
    /// run's best candidates always has [`POLISH_SHARE`] of the budget left.
    pub(super) fn room_search(&self, n: usize) -> bool {
        self.used.get() + n as f64 <= self.max as f64 - self.reserve && self.room(n)
    }
    pub(super) fn add(&self, n: usize) {
        self.used.set(self.used.get() + n as f64);
    }
    /// Takes `k` evaluations if they fit: `false` (nothing taken) when they do not.
    pub(super) fn charge(&self, k: f64) -> bool {
        let ok = self.fits(k);
        if ok {
            self.used.set(self.used.get() + k);
        }
        ok
    }
    /// Counts `k` positions solved (a whole check: taken even past the budget, whose
    /// polish left room for it).
    pub(super) fn add_positions(&self, k: usize) {
        self.used.set(self.used.get() + k as f64 / self.per_eval);
    }
    /// The evaluations spent, rounded up.
    pub(super) fn used(&self) -> usize {
        self.used.get().ceil() as usize
    }
    /// Takes one evaluation of the polish, leaving room for the whole check of its result:
    /// `false` when the budget (of evaluations or time) is spent.
    pub(super) fn take_polish(&self) -> bool {
        let ok = self.fits(self.polish + self.check);
        if ok {
            self.used.set(self.used.get() + self.polish);
        }
        ok
    }
}

/// The search's samples of the range between prescribed crank angles, rad apart.
pub(super) const SEARCH_STEP: f64 = 0.035;
/// The whole check's samples of a design's range, rad apart (1°).
pub(super) const CHECK_STEP: f64 = 0.0175;

impl Budget {
    /// The budget of `max` evaluations and `max_time` from `start`, of a search whose global
    /// stage solves `per_eval` positions an evaluation, whose polish solves `points` and
    /// whose whole check `check` at most.
    pub(super) fn new(
        max: usize,
        max_time: Duration,
        start: Instant,
        per_eval: usize,
        points: usize,
        check: usize,
    ) -> Self {
        let per_eval = per_eval.max(1) as f64;
        Self {
            used: Cell::new(0.0),
            max,
            reserve: 0.0,
            per_eval,
            polish: points as f64 / per_eval,
            check: check as f64 / per_eval,
            start,
            max_time,
        }
    }
}

/// The positions one evaluation of the global stage solves: a turn of `positions` without
/// prescribed timing; with it, the points and the range between them sampled every `step`
/// rad (as [`Problem::objective`] and the six-bar's search sample it).
pub(super) fn positions_per_evaluation(
    timing: &Timing,
    n: usize,
    positions: usize,
    step: f64,
) -> usize {
    match timing {
        Timing::Prescribed(delta) => n + range_samples(delta, step),
        _ => positions,
    }
}

/// How many samples, `step` rad apart at most, cover the range of the crank angles `delta`,
/// both ends included.
pub(super) fn range_samples(delta: &[f64], step: f64) -> usize {
    let (mn, mx) = min_max(delta);
    ((mx - mn) / step).ceil().max(1.0) as usize + 1
}
