//! Path generation: a four-bar (or an offset slider-crank) whose coupler point passes through
//! given points (with or without prescribed crank angles) or traces a closed curve, by a
//! seeded global search.
//!
//! The slider-crank ([`slider`]) is searched as the four-bar with prescribed timing is, over
//! all its dimensions (eight, a gene of the four-bar's nine unused), for every timing: without
//! timing each candidate's turn is matched to the targets by the nearest positions.
//!
//! With prescribed timing the search is differential evolution (DE/current-to-pbest/1/bin
//! with dithered F) over the nine dimensions of a four-bar with a coupler point, its assembly
//! mode and the first crank angle θ0, each candidate evaluated at its prescribed angles and
//! over the range between them in one batch ([`four_bar_positions`]).
//!
//! Without it (free timing, a closed curve) the search runs over the *shapes* of four-bars
//! only — five ratios and the mode — and places each candidate's coupler curve on the targets
//! by the similarity that fits best, in closed form ([`shape`]): four of the nine dimensions
//! need no search, and the crank angles at the targets come with the placement.
//!
//! A candidate must assemble on its one branch over the whole input range it needs, keep the
//! transmission angle at or above \[γ\] there, keep its link ratio and size within bounds, and
//! meet the points in their order (no order defect); otherwise it is penalised or refused.
//! The best candidates are polished by Levenberg–Marquardt on the exact misses (the crank
//! angle at each point an unknown unless prescribed), which converges quadratically where the
//! points can be met exactly; every few generations the best one is polished, and the search
//! ends as soon as enough distinct designs meet the points to the tolerance.

mod assign;
mod evolve;
mod shape;
mod six_bar;
mod slider;

pub use six_bar::six_bar_path_generator;

use super::four_bar::FourBar;
use super::{Options, Synthesis, MAX_LINK_RATIO};
use crate::error::{Error, Result};
use crate::kinematics::batch::{
    coupler_point, four_bar_positions, CrankAngles, FourBarDims, Lane, Positions,
};
use crate::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use crate::linkage::NamedPoint;
use nalgebra::{DMatrix, DVector, Point2, Vector2};
use std::cell::Cell;
use std::f64::consts::TAU;
use std::time::{Duration, Instant};

type V = Vector2<f64>;

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
    /// crank and rod), in (1, [`MAX_LINK_RATIO`](super::MAX_LINK_RATIO)]. Default 10.
    pub max_link_ratio: f64,
    /// The largest link length and distance of a pivot from the points' centroid, in units of
    /// the path's size (the largest distance of a point from the centroid). Default 5. The
    /// four-bar's and slider-crank's designs keep it; the six-bar's search keeps it, but its
    /// polish may end outside it.
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
    /// candidate is feasible: a penalty then).
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

/// splitmix64.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Genes: O1 (2), frame angle, frame, crank, coupler, rocker, coupler point (along, across),
/// the branch's sign (its sign), θ0 (prescribed timing only). Normalised units.
const BASE: usize = 10;
const INFEASIBLE: f64 = 1e3;
/// How many of the best candidates are polished.
const POLISHED: usize = 8;
/// The most target points: the polish's Jacobian without prescribed timing is dense, of
/// 2n rows and n + 9 columns.
const MAX_POINTS: usize = 500;
/// The largest population, and the most crank positions per turn (memory).
const MAX_POPULATION: usize = 100_000;
/// Every how many generations the best member is polished within the evolution.
const MEMETIC: usize = 5;
/// Generations without improvement that end a run of the differential evolution.
const STAGNATION: usize = 40;
/// The share of the evaluation budget kept for the polish of the shape search's last run:
/// without it a run that creeps on until the budget is spent leaves no evaluation to turn
/// its best candidates into designs.
const POLISH_SHARE: f64 = 0.1;

/// The search's budget, shared by the global stage and the polish, and wall-clock time.
/// Its unit is a candidate evaluation of the global stage: the positions it solves (a turn
/// of `positions` without prescribed timing; with it, the points and the samples of the
/// range between them). Everything else is counted by the positions it solves in that
/// unit: the polish's evaluation of a candidate at the n target points counts as n of them,
/// a whole check of a design as the points and the range sampled every 1°.
struct Budget {
    used: Cell<f64>,
    max: usize,
    /// The share of `max` the global stage leaves to the polish of its last run.
    reserve: f64,
    /// The positions one evaluation solves ([`positions_per_evaluation`]).
    per_eval: f64,
    /// What one evaluation of the polish counts.
    polish: f64,
    /// What the whole check of a polished design counts (at most): the polish always leaves
    /// that much for it.
    check: f64,
    start: Instant,
    max_time: Duration,
}

impl Budget {
    /// Whether `k` more evaluations fit, in number and in time.
    fn fits(&self, k: f64) -> bool {
        self.used.get() + k <= self.max as f64 && self.start.elapsed() < self.max_time
    }
    /// Whether `n` more evaluations fit, in number and in time.
    fn room(&self, n: usize) -> bool {
        self.fits(n as f64)
    }
    /// Whether `n` more evaluations fit in the global stage's share: the polish of the last
    /// run's best candidates always has [`POLISH_SHARE`] of the budget left.
    fn room_search(&self, n: usize) -> bool {
        self.used.get() + n as f64 <= self.max as f64 - self.reserve && self.room(n)
    }
    fn add(&self, n: usize) {
        self.used.set(self.used.get() + n as f64);
    }
    /// Takes `k` evaluations if they fit: `false` (nothing taken) when they do not.
    fn charge(&self, k: f64) -> bool {
        let ok = self.fits(k);
        if ok {
            self.used.set(self.used.get() + k);
        }
        ok
    }
    /// Counts `k` positions solved (a whole check: taken even past the budget, whose
    /// polish left room for it).
    fn add_positions(&self, k: usize) {
        self.used.set(self.used.get() + k as f64 / self.per_eval);
    }
    /// The evaluations spent, rounded up.
    fn used(&self) -> usize {
        self.used.get().ceil() as usize
    }
    /// Takes one evaluation of the polish, leaving room for the whole check of its result:
    /// `false` when the budget (of evaluations or time) is spent.
    fn take_polish(&self) -> bool {
        let ok = self.fits(self.polish + self.check);
        if ok {
            self.used.set(self.used.get() + self.polish);
        }
        ok
    }
}

/// The search's samples of the range between prescribed crank angles, rad apart.
const SEARCH_STEP: f64 = 0.035;
/// The whole check's samples of a design's range, rad apart (1°).
const CHECK_STEP: f64 = 0.0175;

impl Budget {
    /// The budget of `max` evaluations and `max_time` from `start`, of a search whose global
    /// stage solves `per_eval` positions an evaluation, whose polish solves `points` and
    /// whose whole check `check` at most.
    fn new(
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
fn positions_per_evaluation(timing: &Timing, n: usize, positions: usize, step: f64) -> usize {
    match timing {
        Timing::Prescribed(delta) => n + range_samples(delta, step),
        _ => positions,
    }
}

/// How many samples, `step` rad apart at most, cover the range of the crank angles `delta`,
/// both ends included.
fn range_samples(delta: &[f64], step: f64) -> usize {
    let (mn, mx) = min_max(delta);
    ((mx - mn) / step).ceil().max(1.0) as usize + 1
}

/// The kind of mechanism a search synthesises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    FourBar,
    SliderCrank,
}

struct Problem {
    kind: Kind,
    budget: Budget,
    targets: Vec<V>,
    timing: Timing,
    sin_gamma: f64,
    ratio: f64,
    size: f64,
    turn: CrankAngles,
    angles: CrankAngles,
    out: Positions,
    phi: Vec<f64>,
    /// Free timing's ordered assignment ([`assign`]).
    assign: assign::Scratch,
}

fn dims_of(g: &[f64], sigma: f64) -> FourBarDims {
    let o = Point2::new(g[0], g[1]);
    FourBarDims {
        o,
        c: o + g[3] * V::new(g[2].cos(), g[2].sin()),
        l_oa: g[4],
        l_ab: g[5],
        l_cb: g[6],
        branch: if sigma > 0.0 {
            Branch::Plus
        } else {
            Branch::Minus
        },
        coupler: V::new(g[7], g[8]),
    }
}

/// The positions of the mechanism of the genes `g` (mode `sigma`) at `angles`, into `out`
/// (sized for them): a batch lane each.
fn fill(kind: Kind, g: &[f64], sigma: f64, angles: &CrankAngles, out: &mut Positions) {
    match kind {
        Kind::FourBar => {
            let _ = four_bar_positions(&dims_of(g, sigma), angles, out.columns_mut());
        }
        Kind::SliderCrank => slider::Slider::of(g, sigma).positions(angles, out),
    }
}

/// The coupler point of the genes `g` at the crank angle `phi`, exactly as [`fill`] gives
/// it, with the lane's measure.
fn point_of(kind: Kind, g: &[f64], sigma: f64, phi: f64) -> Option<(V, f64)> {
    match kind {
        Kind::FourBar => point_at(&dims_of(g, sigma), phi),
        Kind::SliderCrank => slider::Slider::of(g, sigma)
            .at(phi.cos(), phi.sin())
            .ok()
            .map(|(_, _, p, m)| (p, m)),
    }
}

/// The coupler point of `d` at the crank angle `phi` by the scalar blocks (exactly a batch
/// lane), with sin(φ3 − φ2).
fn point_at(d: &FourBarDims, phi: f64) -> Option<(V, f64)> {
    let a = crank(d.o, d.l_oa, Motion::fixed(phi)).ok()?.a;
    let r = rrr_dyad(a, PointMotion::fixed(d.c), d.l_ab, d.l_cb, d.branch).ok()?;
    Some((coupler_point(a.p, r.b.p, d.coupler_uv()).coords, r.det))
}

/// The shortest link a search tries, in path sizes: 2 % of the path, or a tenth of the
/// largest (`max_size`, `s`) when that is smaller, so that every link stays within `s`.
pub(super) fn shortest_link(s: f64) -> f64 {
    0.02_f64.min(0.1 * s)
}

impl Problem {
    fn genes(&self) -> usize {
        BASE + usize::from(matches!(self.timing, Timing::Prescribed(_)))
    }

    /// Lower and upper bounds of the genes.
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let s = self.size;
        let l = shortest_link(s);
        let (mut lo, mut hi) = match self.kind {
            Kind::FourBar => (
                vec![-s, -s, 0.0, l, l, l, l, -s, -s, -1.0],
                vec![s, s, TAU, s, s, s, s, s, s, 1.0],
            ),
            // The offset is signed, and gene 6 unused.
            Kind::SliderCrank => (
                vec![-s, -s, 0.0, -s, l, l, 0.0, -s, -s, -1.0],
                vec![s, s, TAU, s, s, s, 0.0, s, s, 1.0],
            ),
        };
        if self.genes() > BASE {
            lo.push(0.0);
            hi.push(TAU);
        }
        (lo, hi)
    }

    fn lengths_ok(&self, g: &[f64]) -> f64 {
        let l = match self.kind {
            Kind::FourBar => &g[3..7],
            Kind::SliderCrank => &g[4..6],
        };
        if self.kind == Kind::SliderCrank && !g[3].is_finite() {
            return INFEASIBLE * 10.0;
        }
        let (mn, mx) = l
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if mn.is_nan() || mn <= 0.0 || !l.iter().all(|x| x.is_finite()) {
            return INFEASIBLE * 10.0;
        }
        let excess = mx / mn / self.ratio - 1.0;
        if excess > 0.0 {
            INFEASIBLE + excess
        } else {
            0.0
        }
    }

    /// Whether the genes `g` are within `max_size` (the search's box): the pivot, the frame or
    /// the slider's offset, the links and the coupler point's offsets. A polish may pass
    /// outside on its way (its path is not constrained, so that it converges as fast as it
    /// can); the design it ends on must be inside.
    fn within_size(&self, g: &[f64]) -> bool {
        let l = match self.kind {
            Kind::FourBar => &g[3..7],
            Kind::SliderCrank => &g[4..6],
        };
        [g[0], g[1], g[3], g[7], g[8]]
            .iter()
            .chain(l)
            .all(|x| x.abs() <= self.size)
    }

    fn lane_ok(&self, i: usize) -> bool {
        self.lane_ok_in(&self.out, i)
    }

    fn lane_ok_in(&self, out: &Positions, i: usize) -> bool {
        out.status[i] == Lane::Ok && out.measure[i].abs() >= self.sin_gamma
    }

    /// How far lane `i` is from acceptable: the shortfall of |sin γ| below sin \[γ\], the gap
    /// (in path sizes) plus 1 where it does not assemble, 2 where it is singular or invalid.
    fn shortfall(out: &Positions, sin_gamma: f64, i: usize) -> f64 {
        let m = out.measure[i];
        match out.status[i] {
            Lane::Ok => (sin_gamma - m.abs()).max(0.0),
            Lane::NotAssemblable => 1.0 + m.abs().min(10.0),
            _ => 2.0,
        }
    }

    /// The penalty of an infeasible candidate: the mean shortfall over the lanes `lanes`.
    fn penalty(&self, lanes: impl Iterator<Item = usize>) -> f64 {
        self.penalty_in(&self.out, lanes)
    }

    fn penalty_in(&self, out: &Positions, lanes: impl Iterator<Item = usize>) -> f64 {
        let (mut sum, mut n) = (0.0, 0usize);
        for i in lanes {
            sum += Self::shortfall(out, self.sin_gamma, i);
            n += 1;
        }
        INFEASIBLE + sum / n.max(1) as f64
    }

    /// The global stage's objective of the genes `g`.
    fn objective(&mut self, g: &[f64]) -> f64 {
        let p = self.lengths_ok(g);
        if p > 0.0 {
            return p;
        }
        let sigma = g[9];
        match &self.timing {
            Timing::Prescribed(delta) => {
                let theta0 = g[10];
                self.phi.clear();
                self.phi.extend(delta.iter().map(|&x| theta0 + x));
                let (mn, mx) = min_max(delta);
                let steps = range_samples(delta, SEARCH_STEP) - 1;
                for k in 0..=steps {
                    self.phi
                        .push(theta0 + mn + (mx - mn) * k as f64 / steps as f64);
                }
                self.angles.set(&self.phi);
                self.out.resize(self.phi.len());
                fill(self.kind, g, sigma, &self.angles, &mut self.out);
                let bad = (0..self.phi.len()).filter(|&i| !self.lane_ok(i)).count();
                if bad > 0 {
                    return self.penalty(0..self.phi.len());
                }
                let n = self.targets.len();
                (0..n)
                    .map(|i| (V::new(self.out.p_x[i], self.out.p_y[i]) - self.targets[i]).norm())
                    .sum::<f64>()
                    / n as f64
            }
            Timing::Free | Timing::ClosedCurve => {
                let m = self.turn.len();
                self.out.resize(m);
                fill(self.kind, g, sigma, &self.turn, &mut self.out);
                let ok: Vec<bool> = (0..m).map(|i| self.lane_ok(i)).collect();
                let closed = matches!(self.timing, Timing::ClosedCurve);
                let n_ok = ok.iter().filter(|&&b| b).count();
                if n_ok == 0 || (closed && n_ok < m) {
                    return self.penalty(0..m);
                }
                let Some(sum) =
                    self.assign
                        .ordered(&self.out.p_x[..m], &self.out.p_y[..m], &ok, &self.targets)
                else {
                    return self.penalty(0..m);
                };
                sum / self.targets.len() as f64
            }
        }
    }

    /// The polish's unknowns from the genes `g`: the genes without the branch's, then θ0
    /// (prescribed timing) or each point's crank angle (the nearest good sample of a turn).
    fn start_of(&mut self, g: &[f64]) -> (Vec<f64>, f64) {
        let sigma = if g[9] > 0.0 { 1.0 } else { -1.0 };
        let mut x: Vec<f64> = g[..9].to_vec();
        if let Timing::Prescribed(_) = self.timing {
            x.push(g[10]);
        } else {
            let m = self.turn.len();
            self.out.resize(m);
            self.budget.add(1);
            fill(self.kind, g, sigma, &self.turn, &mut self.out);
            // The targets' samples in order ([`assign`]) over the usable positions, else
            // over those that assemble (a start the polish may still mend).
            let usable: Vec<bool> = (0..m).map(|i| self.lane_ok(i)).collect();
            let assembles: Vec<bool> = (0..m).map(|i| self.out.status[i] == Lane::Ok).collect();
            let (px, py) = (&self.out.p_x[..m], &self.out.p_y[..m]);
            let found = self
                .assign
                .ordered(px, py, &usable, &self.targets)
                .is_some()
                || self
                    .assign
                    .ordered(px, py, &assembles, &self.targets)
                    .is_some();
            for k in 0..self.targets.len() {
                x.push(if found {
                    self.turn.phi()[self.assign.idx[k]]
                } else {
                    0.0
                });
            }
        }
        (x, sigma)
    }

    /// The genes of the polish's unknowns `x`.
    fn genes_of(&self, x: &[f64], sigma: f64) -> Vec<f64> {
        let mut g = x[..9].to_vec();
        g[2] = g[2].rem_euclid(TAU);
        g.push(sigma);
        if let Timing::Prescribed(_) = self.timing {
            g.push(x[9].rem_euclid(TAU));
        }
        g
    }

    /// Levenberg–Marquardt on the misses from `x` (the link ratio kept; the other
    /// constraints are checked on the result).
    fn lm(&self, x: Vec<f64>, sigma: f64, iterations: usize) -> Vec<f64> {
        let res = |x: &[f64]| {
            if self.budget.take_polish() {
                pb_residuals(self.kind, &self.targets, &self.timing, x, sigma)
            } else {
                None
            }
        };
        let mut accept = |x: &[f64]| self.lengths_ok(&gene_vec(x, sigma)) == 0.0;
        levenberg_marquardt(&res, &mut accept, x, self.separable(), iterations)
    }

    /// [`Problem::lm`] with every step also kept within `max_size` (the search's box).
    fn lm_within(&self, x: Vec<f64>, sigma: f64, iterations: usize) -> Vec<f64> {
        let res = |x: &[f64]| {
            if self.budget.take_polish() {
                pb_residuals(self.kind, &self.targets, &self.timing, x, sigma)
            } else {
                None
            }
        };
        let mut accept = |x: &[f64]| {
            let g = gene_vec(x, sigma);
            self.lengths_ok(&g) == 0.0 && self.within_size(&g)
        };
        levenberg_marquardt(&res, &mut accept, x, self.separable(), iterations)
    }

    fn angle_of(&self, x: &[f64], i: usize) -> f64 {
        match &self.timing {
            Timing::Prescribed(delta) => x[9] + delta[i],
            _ => x[9 + i],
        }
    }

    /// The whole check of a polished point: link ratio, and assembly with γ ≥ \[γ\] over the
    /// input range it needs (sampled every 1°, and at each target's angle).
    fn feasible(&mut self, x: &[f64], sigma: f64) -> bool {
        let mut scratch = (
            std::mem::take(&mut self.phi),
            std::mem::take(&mut self.angles),
            std::mem::take(&mut self.out),
        );
        let ok = self.feasible_in(x, sigma, &mut scratch);
        (self.phi, self.angles, self.out) = scratch;
        ok
    }

    /// [`Problem::feasible`] in the scratch space `phi`, `angles`, `out`.
    fn feasible_in(
        &self,
        x: &[f64],
        sigma: f64,
        (phi, angles, out): &mut (Vec<f64>, CrankAngles, Positions),
    ) -> bool {
        let g = gene_vec(x, sigma);
        if self.lengths_ok(&g) > 0.0 || !self.within_size(&g) {
            return false;
        }
        let phis: Vec<f64> = (0..self.targets.len())
            .map(|i| self.angle_of(x, i))
            .collect();
        let (start, span) = match self.timing {
            Timing::ClosedCurve => {
                if !once_round(&phis) {
                    return false;
                }
                (0.0, TAU)
            }
            Timing::Prescribed(_) => {
                let (mn, mx) = min_max(&phis);
                (mn, mx - mn)
            }
            Timing::Free => match ordered_arc(&phis) {
                Some(a) => a,
                None => return false,
            },
        };
        let steps = (span / CHECK_STEP).ceil().max(1.0) as usize;
        phi.clear();
        phi.extend_from_slice(&phis);
        phi.extend((0..=steps).map(|k| start + span * k as f64 / steps as f64));
        angles.set(phi);
        out.resize(phi.len());
        self.budget.add_positions(phi.len());
        fill(self.kind, &g, sigma, angles, out);
        (0..phi.len()).all(|i| self.lane_ok_in(out, i))
    }

    /// The unknowns of the polish whose residuals each move every residual: the nine
    /// dimensions and θ0; the crank angle at each point (free timing) moves its own two.
    fn separable(&self) -> usize {
        if let Timing::Prescribed(_) = self.timing {
            10
        } else {
            9
        }
    }
}

fn gene_vec(x: &[f64], sigma: f64) -> Vec<f64> {
    let mut g = x[..9].to_vec();
    g.push(sigma);
    g.push(*x.get(9).unwrap_or(&0.0));
    g
}

fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        })
}

fn normalize_angle(a: f64) -> f64 {
    crate::angle::normalize(a)
}

/// The shortest arc (start, span) of the circle that holds every angle: the complement of
/// the largest gap between neighbours.
fn arc_of(phis: &[f64]) -> Option<(f64, f64)> {
    let mut a: Vec<f64> = phis.iter().map(|&p| normalize_angle(p)).collect();
    if a.is_empty() || a.iter().any(|x| !x.is_finite()) {
        return None;
    }
    a.sort_by(f64::total_cmp);
    let n = a.len();
    let (mut gap, mut after) = (a[0] + TAU - a[n - 1], 0);
    for i in 1..n {
        if a[i] - a[i - 1] > gap {
            gap = a[i] - a[i - 1];
            after = i;
        }
    }
    Some((a[after], TAU - gap))
}

/// The arc (start, span) the crank sweeps to reach the angles `phis` in their order, turning
/// one way by less than a turn: `None` when no sense does (an order defect).
fn ordered_arc(phis: &[f64]) -> Option<(f64, f64)> {
    let sweep = |sense: f64| -> f64 {
        phis.windows(2)
            .map(|w| (sense * (w[1] - w[0])).rem_euclid(TAU))
            .sum()
    };
    let n = phis.len();
    let (fwd, bwd) = (sweep(1.0), sweep(-1.0));
    if n == 0 {
        None
    } else if fwd < TAU {
        Some((phis[0], fwd))
    } else if bwd < TAU {
        Some((phis[n - 1], bwd))
    } else {
        None
    }
}

/// Whether the angles `phis`, taken cyclically in order, go round once in one sense: the
/// points of a closed curve met in order, once per turn.
fn once_round(phis: &[f64]) -> bool {
    let n = phis.len();
    [1.0, -1.0].into_iter().any(|sense: f64| {
        let sum: f64 = (0..n)
            .map(|i| (sense * (phis[(i + 1) % n] - phis[i])).rem_euclid(TAU))
            .sum();
        (sum - TAU).abs() < 1e-6
    })
}

/// The designs found so far, with what places them in the world.
struct Found {
    designs: Vec<PathDesign>,
    /// Each design's sorted link lengths (normalised), to tell designs apart.
    keys: Vec<[f64; 4]>,
    start: Instant,
    centre: V,
    scale: f64,
}

impl Found {
    /// How many designs meet the points to `tolerance` path sizes.
    fn good(&self, tolerance: f64) -> usize {
        self.designs
            .iter()
            .filter(|d| d.mean_error <= tolerance * self.scale)
            .count()
    }

    /// Polishes the genes `g` with the crank angles `phis` at the targets (Levenberg–Marquardt,
    /// `iterations`), and keeps the design when it passes the whole check (and, if
    /// `only_good`, meets the points to `tolerance`); of two designs with the same links
    /// (to 1e-4), the better one.
    fn adopt(
        &mut self,
        pb: &mut Problem,
        g: &[f64],
        phis: &[f64],
        iterations: usize,
        tolerance: f64,
        only_good: bool,
    ) -> Result<()> {
        let sigma = if g[9] > 0.0 { 1.0 } else { -1.0 };
        let mut x0 = g[..9].to_vec();
        x0.extend_from_slice(phis);
        let x = pb.lm(x0.clone(), sigma, iterations);
        // Levenberg–Marquardt keeps the link ratio only: where it steps out of the
        // constraints (γ, assembly, order), the unpolished start, which met them in the
        // search, is the design (no search that found a feasible candidate ends empty).
        let x = if pb.feasible(&x, sigma) {
            x
        } else if !only_good && pb.feasible(&x0, sigma) {
            x0
        } else {
            return Ok(());
        };
        let Some(design) = design_of(pb, &x, sigma, self.centre, self.scale)? else {
            return Ok(());
        };
        if only_good && design.mean_error > tolerance * self.scale {
            return Ok(());
        }
        let key = {
            let mut l = [x[3], x[4], x[5], x[6]];
            l.sort_by(f64::total_cmp);
            l
        };
        let same = self.keys.iter().position(|k| {
            k.iter()
                .zip(&key)
                .all(|(a, b)| (a - b).abs() <= 1e-4 * b.abs())
        });
        match same {
            Some(i) if self.designs[i].mean_error <= design.mean_error => {}
            Some(i) => {
                self.designs[i] = design;
                self.keys[i] = key;
            }
            None => {
                self.designs.push(design);
                self.keys.push(key);
            }
        }
        Ok(())
    }
}

/// Nelder–Mead on `f` from `x0` with initial steps `step`, `max` evaluations; `f` says
/// `None` when the budget is spent, which ends the search at the best vertex so far.
fn nelder_mead(
    f: &mut dyn FnMut(&[f64]) -> Option<f64>,
    x0: &[f64],
    step: &[f64],
    max: usize,
) -> Vec<f64> {
    let spent = Cell::new(false);
    let mut f = |x: &[f64]| {
        f(x).unwrap_or_else(|| {
            spent.set(true);
            f64::INFINITY
        })
    };
    let n = x0.len();
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(n + 1);
    simplex.push((x0.to_vec(), f(x0)));
    for i in 0..n {
        let mut x = x0.to_vec();
        x[i] += step[i];
        let fx = f(&x);
        simplex.push((x, fx));
    }
    let mut evals = n + 1;
    while evals < max && !spent.get() {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        if (simplex[n].1 - simplex[0].1).abs() <= 1e-30 + 1e-15 * simplex[0].1.abs() {
            break;
        }
        let centroid: Vec<f64> = (0..n)
            .map(|j| simplex[..n].iter().map(|s| s.0[j]).sum::<f64>() / n as f64)
            .collect();
        let along = |t: f64| -> Vec<f64> {
            (0..n)
                .map(|j| centroid[j] + t * (simplex[n].0[j] - centroid[j]))
                .collect()
        };
        let xr = along(-1.0);
        let fr = f(&xr);
        evals += 1;
        if fr < simplex[0].1 {
            let xe = along(-2.0);
            let fe = f(&xe);
            evals += 1;
            simplex[n] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (xr, fr);
        } else {
            let xc = if fr < simplex[n].1 {
                along(-0.5)
            } else {
                along(0.5)
            };
            let fc = f(&xc);
            evals += 1;
            if fc < fr.min(simplex[n].1) {
                simplex[n] = (xc, fc);
            } else {
                let best = simplex[0].0.clone();
                for s in simplex.iter_mut().skip(1) {
                    for (v, b) in s.0.iter_mut().zip(&best) {
                        *v = b + 0.5 * (*v - b);
                    }
                    s.1 = f(&s.0);
                }
                evals += n;
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    simplex.swap_remove(0).0
}

/// The Jacobian of the residuals `r` at `x` by central differences.
///
/// The unknowns from `separable` on are the crank angles of the points, one each: angle k
/// moves only residuals 2(k − separable) and the next, so one pair of evaluations gives all
/// their columns. `None` where a residual cannot be evaluated (the budget is spent, or a
/// neighbour does not assemble).
fn jacobian(
    res: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    x: &[f64],
    m: usize,
    separable: usize,
) -> Option<DMatrix<f64>> {
    let n = x.len();
    let mut j = DMatrix::zeros(m, n);
    let step = |k: usize| 1e-7 * x[k].abs().max(1.0);
    for k in 0..separable.min(n) {
        let h = step(k);
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[k] += h;
        xm[k] -= h;
        let (rp, rm) = (res(&xp)?, res(&xm)?);
        for i in 0..m {
            j[(i, k)] = (rp[i] - rm[i]) / (2.0 * h);
        }
    }
    if separable < n {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        for k in separable..n {
            xp[k] += step(k);
            xm[k] -= step(k);
        }
        let (rp, rm) = (res(&xp)?, res(&xm)?);
        for k in separable..n {
            let h = step(k);
            for i in [2 * (k - separable), 2 * (k - separable) + 1] {
                j[(i, k)] = (rp[i] - rm[i]) / (2.0 * h);
            }
        }
    }
    Some(j)
}

/// Levenberg–Marquardt on the residuals, with a central-difference Jacobian ([`jacobian`]);
/// a step is taken only where `accept` agrees (the design stays feasible).
fn levenberg_marquardt(
    res: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    accept: &mut dyn FnMut(&[f64]) -> bool,
    x0: Vec<f64>,
    separable: usize,
    iterations: usize,
) -> Vec<f64> {
    let mut x = x0;
    let Some(mut r) = res(&x) else { return x };
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    let mut lambda = 1e-3;
    let n = x.len();
    for _ in 0..iterations {
        if cost < 1e-30 {
            break;
        }
        let Some(j) = jacobian(res, &x, r.len(), separable) else {
            return x;
        };
        let jt = j.transpose();
        let jtj = &jt * &j;
        let g = &jt * DVector::from_vec(r.clone());
        let mut improved = false;
        for _ in 0..12 {
            let mut a = jtj.clone();
            for k in 0..n {
                a[(k, k)] += lambda * (jtj[(k, k)] + 1e-12);
            }
            let Some(step) = a.lu().solve(&(-&g)) else {
                lambda *= 10.0;
                continue;
            };
            let xn: Vec<f64> = x.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            if let Some(rn) = res(&xn) {
                let cn: f64 = rn.iter().map(|v| v * v).sum();
                if cn < cost && accept(&xn) {
                    let small =
                        step.norm() <= 1e-15 * (1.0 + x.iter().map(|v| v * v).sum::<f64>().sqrt());
                    x = xn;
                    r = rn;
                    cost = cn;
                    lambda = (lambda / 10.0).max(1e-15);
                    improved = !small;
                    break;
                }
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    x
}

/// Continuation from a near miss to the points: the misses `r0` at `x0` are shrunk to zero
/// along the way, the targets of step s being the points plus (1 − s)·r0, and the root at
/// each s tracked by a tangent predictor and a chord-Newton corrector (the Jacobian of the
/// predictor's point).
///
/// Why: where the misses are a square system whose Jacobian is ill-conditioned (eight
/// precision points of a six-bar: the smallest singular value 1e-6 of the largest), the
/// root may lie far along a curved valley of the misses, where Levenberg–Marquardt creeps
/// by tiny damped steps and stalls; the continuation follows the valley instead. It stops
/// where a step of 1e-6 in s does not converge (a fold: no root of this branch), when
/// `accept` refuses a point, or after `steps` steps; the last point reached is returned.
fn continuation(
    res: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    accept: &mut dyn FnMut(&[f64]) -> bool,
    x0: Vec<f64>,
    separable: usize,
    steps: usize,
) -> Vec<f64> {
    let Some(r0) = res(&x0) else { return x0 };
    let r0 = DVector::from_vec(r0);
    let size = r0.norm();
    if !(size > 0.0 && size.is_finite()) {
        return x0;
    }
    let (mut x, mut s, mut ds) = (DVector::from_vec(x0), 0.0f64, 0.125f64);
    for _ in 0..steps {
        if s >= 1.0 || ds < 1e-6 {
            break;
        }
        let Some(j) = jacobian(res, x.as_slice(), r0.len(), separable) else {
            break;
        };
        let svd = j.clone().svd(true, true);
        let solve = |b: &DVector<f64>| svd.solve(b, 1e-14 * svd.singular_values.max());
        let Ok(tangent) = solve(&(-&r0)) else { break };
        let t = (s + ds).min(1.0);
        // The residuals of step t: Q(x) − T − (1 − t)·r0.
        let f =
            |y: &DVector<f64>| res(y.as_slice()).map(|q| DVector::from_vec(q) - (1.0 - t) * &r0);
        let mut y = &x + (t - s) * &tangent;
        let mut ok = false;
        for _ in 0..6 {
            let Some(fy) = f(&y) else { break };
            if fy.norm() <= 1e-3 * size * (1.0 - t) + 1e-14 * (1.0 + y.norm()) {
                ok = true;
                break;
            }
            let Ok(dy) = solve(&(-fy)) else { break };
            y += dy;
        }
        if ok && accept(y.as_slice()) {
            (x, s) = (y, t);
            ds *= 2.0;
        } else {
            ds /= 4.0;
        }
    }
    x.as_slice().to_vec()
}

fn check_requirement(kind: Kind, req: &PathRequirement, opts: &PathOptions) -> Result<f64> {
    let gamma = opts.options.check()?;
    for p in &req.points {
        crate::error::finite("points", p[0])?;
        crate::error::finite("points", p[1])?;
    }
    let n = req.points.len();
    if n > MAX_POINTS {
        return Err(Error::OutOfRange {
            name: "points",
            value: n as f64,
            min: 0.0,
            max: MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    // The unknowns without timing: a four-bar's nine dimensions, a slider-crank's eight
    // (O1, the guide's direction and offset, crank, rod, the coupler point), and an angle a
    // point, two equations a point.
    let free = match kind {
        Kind::FourBar => 9,
        Kind::SliderCrank => 8,
    };
    let (min, name) = match &req.timing {
        Timing::Free | Timing::ClosedCurve => (free, "points"),
        Timing::Prescribed(d) => {
            for &x in d {
                // Beyond ±10⁹ rad an angle no longer names one crank position (the design
                // would be re-posed at another crank angle than the one searched).
                crate::linkage::inputs::check_input_coordinate("timing", x)?;
            }
            if d.len() != n {
                return Err(Error::OutOfRange {
                    name: "timing (one crank angle per point)",
                    value: d.len() as f64,
                    min: n as f64,
                    max: n as f64,
                    ends: crate::Ends::Closed,
                });
            }
            let (mn, mx) = min_max(d);
            if mx - mn >= TAU {
                return Err(Error::OutOfRange {
                    name: "timing (span of the crank angles, rad)",
                    value: mx - mn,
                    min: 0.0,
                    max: TAU,
                    ends: crate::Ends::OpenAbove,
                });
            }
            // Two distinct points at one crank angle: no linkage's tracer is at two places
            // at once, and the search would only split the difference.
            let ends = (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j)));
            if let Some((i, j)) = ends
                .into_iter()
                .find(|&(i, j)| d[i] == d[j] && req.points[i] != req.points[j])
            {
                return Err(Error::Description {
                    item: "timing".to_owned(),
                    problem: format!(
                        "points {} and {} are at one crank angle {} rad but at distinct places: \
                         give each point its own crank angle",
                        i + 1,
                        j + 1,
                        d[i]
                    ),
                });
            }
            (5, "points")
        }
    };
    if n < min {
        return Err(Error::OutOfRange {
            name,
            value: n as f64,
            min: min as f64,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    let (pts, centre, size) = normalised(&req.points);
    // The engine squares lengths and coordinates: a path too large (or too small) for that
    // is no path of `f64` four-bars. A size of 0 is coinciding points, named below.
    let far = pts.iter().map(|p| p.norm()).fold(0.0, f64::max);
    if !(far * far).is_finite() || (size > 0.0 && size * size < f64::MIN_POSITIVE) {
        return Err(Error::Overflow {
            what: "points (their coordinates or the path's size)",
        });
    }
    for i in 0..n {
        for j in 0..i {
            if (pts[i] - pts[j]).norm() <= 1e-9 * size {
                return Err(Error::NoMechanism {
                    method: "path generation",
                    problem: format!("points {} and {} coincide", j + 1, i + 1),
                });
            }
        }
    }
    // Far from the origin, f64 cannot hold the points (nor the design's pivots) to the
    // tolerance: the misses reported would be rounding, not the design's.
    let resolution = centre.norm() * f64::EPSILON;
    if resolution > opts.tolerance.max(1e-12) * size {
        return Err(Error::NoMechanism {
            method: "path generation",
            problem: format!(
                "the points' centroid is {:e} m from the origin, {:.3e} path sizes: f64 \
                 resolves {resolution:.3e} m there, more than the tolerance ({:e} of the path's \
                 size {size:.3e} m); give the points in coordinates with the origin near them",
                centre.norm(),
                centre.norm() / size,
                opts.tolerance,
            ),
        });
    }
    // A ratio above the synthesis' bound could not be checked by the engine to 1e-10.
    for (name, v, lo, hi) in [
        ("max_link_ratio", opts.max_link_ratio, 1.0, MAX_LINK_RATIO),
        ("max_size", opts.max_size, 0.0, f64::INFINITY),
    ] {
        if v.is_nan() || v <= lo || v > hi || !v.is_finite() {
            return Err(Error::OutOfRange {
                name,
                value: v,
                min: lo,
                max: hi,
                ends: if hi.is_finite() {
                    crate::Ends::OpenBelow
                } else {
                    crate::Ends::Open
                },
            });
        }
    }
    if opts.designs == 0 {
        return Err(Error::OutOfRange {
            name: "designs",
            value: 0.0,
            min: 1.0,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    for (name, v) in [
        ("population", opts.population),
        ("positions", opts.positions),
    ] {
        if !(8..=MAX_POPULATION).contains(&v) {
            return Err(Error::OutOfRange {
                name,
                value: v as f64,
                min: 8.0,
                max: MAX_POPULATION as f64,
                ends: crate::Ends::Closed,
            });
        }
    }
    if !(opts.tolerance >= 0.0 && opts.tolerance.is_finite()) {
        return Err(Error::OutOfRange {
            name: "tolerance",
            value: opts.tolerance,
            min: 0.0,
            max: f64::INFINITY,
            ends: crate::Ends::OpenAbove,
        });
    }
    // The first population and one generation.
    let least = 2 * opts.population;
    if opts.max_evaluations < least {
        return Err(Error::OutOfRange {
            name: "max_evaluations (at least twice the population)",
            value: opts.max_evaluations as f64,
            min: least as f64,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    if opts.max_time.is_zero() {
        return Err(Error::OutOfRange {
            name: "max_time",
            value: 0.0,
            min: 0.0,
            max: f64::INFINITY,
            ends: crate::Ends::OpenBelow,
        });
    }
    Ok(gamma)
}

/// The points as vectors, their centroid and the path's size (the largest distance of a
/// point from the centroid), computed so that no sum overflows where the points do not.
fn normalised(points: &[[f64; 2]]) -> (Vec<V>, V, f64) {
    let pts: Vec<V> = points.iter().map(|p| V::new(p[0], p[1])).collect();
    let n = pts.len().max(1) as f64;
    let c = pts.iter().map(|p| p / n).sum::<V>();
    let size = pts
        .iter()
        .map(|p| (p.x - c.x).hypot(p.y - c.y))
        .fold(0.0, f64::max);
    (pts, c, size)
}

/// A four-bar whose coupler point passes through the points of `req` (or traces its closed
/// curve): the `opts.designs` best distinct designs found, best first, each with its misses.
///
/// `progress` is called once per generation of the global stage; returning `false` stops
/// the search there (the polish still runs).
///
/// # Errors
/// [`Error::NonFinite`] naming `points` or `timing`; [`Error::OutOfRange`] naming `points`
/// for fewer points than the unknowns need (9 free or on a closed curve, 5 with prescribed
/// timing) or more than 500, or naming a bad option (a budget of no evaluations or no time
/// among them); [`Error::Overflow`] naming `points` when their coordinates or the path's
/// size cannot be squared in `f64`; [`Error::NoMechanism`] for coinciding points, or when no
/// candidate met the constraints (γ, link ratio, assembly over the range) within the budget
/// (the message gives the evaluations and time spent, and the budget).
pub fn path_generator(
    req: &PathRequirement,
    opts: &PathOptions,
    progress: impl FnMut(&Progress) -> bool,
) -> Result<Vec<PathDesign>> {
    generate(Kind::FourBar, req, opts, progress)
}

/// An offset slider-crank whose coupler point — a point of the rod — passes through the
/// points of `req` (or traces its closed curve): the `opts.designs` best distinct designs
/// found, best first, each with its misses, as [`path_generator`] finds four-bars.
///
/// The design's joints are `O1` (the crank's pivot), `A` (crank–rod), `B` (rod–slider), `S`
/// (the slider's prismatic joint on the frame's guide, the output its slide), the coupler
/// point `P` on the rod. The dimensions searched are O1, the guide's direction and its
/// offset from O1, the crank, the rod and the coupler point (eight; with prescribed timing
/// also θ0) and the assembly mode, by differential evolution over all of them (no placement
/// by similarity), each candidate evaluated over a turn or at its prescribed angles; the
/// transmission angle is the rod's with the guide's normal, sin γ = √(l² − h²)/l for the
/// crank pin at the distance h from the guide. `max_link_ratio` bounds rod/crank and
/// crank/rod; `max_size` the crank, the rod, the offset, the coupler point's offsets and the
/// distance of O1 from the points' centroid.
///
/// # Example
/// Six points of a known slider-crank (crank 50 mm, rod 150 mm, the guide along +x at
/// 20 mm above the crank's pivot, the coupler point 40 mm along the rod and 30 mm to its
/// left) at crank angles 0.9 rad apart, by hand: the crank pin A = (r cos φ, r sin φ) lies
/// h = r sin φ − e from the guide, the slider's pin B = A + (√(l² − h²), −h), and
/// P = A + 0.04·w + 0.03·w⊥ with w = (B − A)/l. The synthesis finds a slider-crank through
/// them (this one or another) to 1e-11 m, and the engine, given its
/// description, puts `P` on them at the crank angles the design reports:
/// ```
/// use tmm::kinematics::Motion;
/// use tmm::linkage::Plan;
/// use tmm::synthesis::{slider_crank_path_generator, PathOptions, PathRequirement, Timing};
/// let (r, l, e) = (0.05, 0.15, 0.02);
/// let delta: Vec<f64> = (0..6).map(|k| 0.9 * k as f64).collect();
/// let points: Vec<[f64; 2]> = delta
///     .iter()
///     .map(|&phi: &f64| {
///         let a = [r * phi.cos(), r * phi.sin()];
///         let h = a[1] - e;
///         let b = [a[0] + (l * l - h * h).sqrt(), e];
///         let w = [(b[0] - a[0]) / l, (b[1] - a[1]) / l];
///         [a[0] + 0.04 * w[0] - 0.03 * w[1], a[1] + 0.04 * w[1] + 0.03 * w[0]]
///     })
///     .collect();
/// let req = PathRequirement { points: points.clone(), timing: Timing::Prescribed(delta) };
/// let opts = PathOptions::default().with_designs(1);
/// let designs = slider_crank_path_generator(&req, &opts, |_| true)?;
/// let best = &designs[0];
/// assert!(best.mean_error < 1e-11);
/// let plan = Plan::new(&best.synthesis.linkage)?;
/// for (phi, t) in best.crank_angles.iter().zip(&points) {
///     let p = plan.kinematics(Motion::fixed(*phi))?.point("P")?.p;
///     assert!((p.x - t[0]).hypot(p.y - t[1]) < 1e-11);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`path_generator`], with 8 points the fewest without timing.
pub fn slider_crank_path_generator(
    req: &PathRequirement,
    opts: &PathOptions,
    progress: impl FnMut(&Progress) -> bool,
) -> Result<Vec<PathDesign>> {
    generate(Kind::SliderCrank, req, opts, progress)
}

fn generate(
    kind: Kind,
    req: &PathRequirement,
    opts: &PathOptions,
    mut progress: impl FnMut(&Progress) -> bool,
) -> Result<Vec<PathDesign>> {
    let gamma = check_requirement(kind, req, opts)?;
    let start = Instant::now();
    let (pts, centre, scale) = normalised(&req.points);
    let targets: Vec<V> = pts.iter().map(|p| (p - centre) / scale).collect();
    let n = targets.len();
    let mut pb = Problem {
        kind,
        budget: Budget {
            // At least the first population and one generation stay in the search.
            reserve: match (kind, &req.timing) {
                (Kind::FourBar, Timing::Prescribed(_)) => 0.0,
                _ => (POLISH_SHARE * opts.max_evaluations as f64)
                    .min(opts.max_evaluations.saturating_sub(2 * opts.population) as f64),
            },
            ..Budget::new(
                opts.max_evaluations,
                opts.max_time,
                start,
                positions_per_evaluation(&req.timing, n, opts.positions, SEARCH_STEP),
                n,
                n + match &req.timing {
                    Timing::Prescribed(delta) => range_samples(delta, CHECK_STEP),
                    _ => (TAU / CHECK_STEP).ceil() as usize + 1,
                },
            )
        },
        targets,
        timing: req.timing.clone(),
        sin_gamma: gamma.sin(),
        ratio: opts.max_link_ratio,
        size: opts.max_size,
        turn: CrankAngles::turn(opts.positions),
        angles: CrankAngles::default(),
        out: Positions::default(),
        phi: Vec::new(),
        assign: assign::Scratch::default(),
    };
    let mut found = Found {
        designs: Vec::new(),
        keys: Vec::new(),
        start,
        centre,
        scale,
    };
    let evals = match (kind, &req.timing) {
        (Kind::FourBar, Timing::Free | Timing::ClosedCurve) => {
            shape::search(&mut pb, opts, &mut found, &mut progress)?
        }
        _ => search_timed(&mut pb, opts, &mut found, &mut progress)?,
    };
    let mut designs = found.designs;
    let want = opts.designs.max(1);
    if designs.is_empty() {
        return Err(Error::NoMechanism {
            method: "path generation",
            problem: format!(
                "no {} met the constraints (γ ≥ {:.1}°, link ratio ≤ {}, assembly over the range) in {evals} evaluations and {:.3} s (the budget: {} evaluations, {:.3} s)",
                match kind {
                    Kind::FourBar => "four-bar",
                    Kind::SliderCrank => "slider-crank",
                },
                gamma.to_degrees(),
                opts.max_link_ratio,
                start.elapsed().as_secs_f64(),
                opts.max_evaluations,
                opts.max_time.as_secs_f64(),
            ),
        });
    }
    designs.sort_by(|a, b| a.mean_error.total_cmp(&b.mean_error));
    designs.truncate(want);
    Ok(designs)
}

/// The search with prescribed timing: differential evolution over the ten genes (the nine
/// dimensions, the mode, θ0) with a Lamarckian Levenberg–Marquardt step every few
/// generations; the best candidates of each run polished by Nelder–Mead and
/// Levenberg–Marquardt. Returns the evaluations spent.
fn search_timed(
    pb: &mut Problem,
    opts: &PathOptions,
    found: &mut Found,
    progress: &mut dyn FnMut(&Progress) -> bool,
) -> Result<usize> {
    let (lo, hi) = pb.bounds();
    let np = opts.population;
    let mut rng = Rng(opts.seed);
    let start = found.start;
    let want = opts.designs.max(1);
    let mut generation = 0;
    let mut stopped = false;
    // Runs of differential evolution from fresh random populations, each until it stagnates,
    // its best candidates polished; until enough designs meet the points to `tolerance` or
    // the budget is spent.
    while !stopped && pb.budget.room_search(2 * np) {
        let mut pop = evolve::population(np, &lo, &hi, &mut rng);
        let mut fit: Vec<f64> = pop.iter().map(|g| pb.objective(g)).collect();
        pb.budget.add(np);
        let mut stagnation = evolve::Stagnation::new(1e-6);
        while pb.budget.room_search(np) {
            generation += 1;
            evolve::generation(&mut pop, &mut fit, &lo, &hi, &[2, 10], &mut rng, &mut |g| {
                pb.budget.add(1);
                pb.objective(g)
            });
            if generation % MEMETIC == 0 {
                // Lamarckian local search: the best member and a random one, polished by
                // Levenberg–Marquardt, replace themselves where that is better.
                let best_i = (0..np)
                    .min_by(|&a, &b| fit[a].total_cmp(&fit[b]))
                    .unwrap_or(0);
                for i in [best_i, rng.below(np)] {
                    if fit[i] >= INFEASIBLE || !pb.budget.room(2) {
                        continue;
                    }
                    let (x, sigma) = pb.start_of(&pop[i]);
                    let x = pb.lm(x, sigma, 30);
                    let g = pb.genes_of(&x, sigma);
                    let f = pb.objective(&g);
                    pb.budget.add(1);
                    // Only within the search's box: a member the polish took outside
                    // `max_size` would lead the population out of it, where no design is
                    // kept (with `max_size` 0.01 no design was found at all).
                    if f < fit[i] && pb.within_size(&g) {
                        pop[i] = g;
                        fit[i] = f;
                    }
                }
            }
            let best = fit.iter().copied().fold(f64::INFINITY, f64::min);
            let go_on = progress(&Progress {
                generation,
                evaluations: pb.budget.used(),
                best,
                elapsed: start.elapsed(),
            });
            if !go_on {
                stopped = true;
                break;
            }
            if stagnation.after(best) {
                break;
            }
        }
        // Polish the best candidates, best first, until enough distinct designs are found.
        let mut order: Vec<usize> = (0..np).filter(|&i| fit[i] < INFEASIBLE).collect();
        order.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]));
        for (rank, &i) in order.iter().enumerate() {
            if rank >= POLISHED {
                break;
            }
            if !pb.budget.room(2) {
                break;
            }
            let (x, sigma) = pb.start_of(&pop[i]);
            let step: Vec<f64> = x.iter().map(|v| 0.02 * v.abs().max(0.5)).collect();
            let xn = {
                let (kind, targets, timing, budget) =
                    (pb.kind, &pb.targets, &pb.timing, &pb.budget);
                let mut f = |x: &[f64]| {
                    if !budget.take_polish() {
                        return None;
                    }
                    Some(
                        pb_residuals(kind, targets, timing, x, sigma)
                            .map_or(f64::INFINITY, |r| r.iter().map(|v| v * v).sum()),
                    )
                };
                nelder_mead(&mut f, &x, &step, 200 * x.len())
            };
            let x0 = x.clone();
            let x = if pb.feasible(&xn, sigma) { xn } else { x };
            let x = pb.lm(x, sigma, 200);
            // Where the free polish ends outside the constraints (in a box too small to
            // reach the points it grows the links past `max_size`) and no design is found
            // yet, the polish again from the member, every step kept within the box; and the
            // member itself (feasible in the search) when that is refused too: a search that
            // found a feasible candidate leaves a design (with `max_size` 0.01 the
            // slider-crank's left none).
            let x = if pb.feasible(&x, sigma) {
                x
            } else if !found.designs.is_empty() {
                continue;
            } else {
                let y = pb.lm_within(x0.clone(), sigma, 200);
                if pb.feasible(&y, sigma) {
                    y
                } else if pb.feasible(&x0, sigma) {
                    x0
                } else {
                    continue;
                }
            };
            let mut g = x[..9].to_vec();
            g.push(sigma);
            found.adopt(pb, &g, &x[9..], 0, opts.tolerance, false)?;
        }
        if found.good(opts.tolerance) >= want {
            break;
        }
    }

    Ok(pb.budget.used())
}

fn pb_residuals(
    kind: Kind,
    targets: &[V],
    timing: &Timing,
    x: &[f64],
    sigma: f64,
) -> Option<Vec<f64>> {
    let g = gene_vec(x, sigma);
    let mut r = Vec::with_capacity(2 * targets.len());
    for (i, t) in targets.iter().enumerate() {
        let phi = match timing {
            Timing::Prescribed(delta) => x[9] + delta[i],
            _ => x[9 + i],
        };
        let (p, _) = point_of(kind, &g, sigma, phi)?;
        r.push(p.x - t.x);
        r.push(p.y - t.y);
    }
    Some(r)
}

/// The design in the world: the description posed at the first point's crank angle.
fn design_of(
    pb: &Problem,
    x: &[f64],
    sigma: f64,
    centre: V,
    scale: f64,
) -> Result<Option<PathDesign>> {
    if pb.kind == Kind::SliderCrank {
        return slider::design(pb, x, sigma, centre, scale);
    }
    let g = gene_vec(x, sigma);
    let mut d = dims_of(&g, sigma);
    d.o = Point2::from(centre + d.o.coords * scale);
    d.c = Point2::from(centre + d.c.coords * scale);
    d.l_oa *= scale;
    d.l_ab *= scale;
    d.l_cb *= scale;
    d.coupler *= scale;
    let n = pb.targets.len();
    let phis: Vec<f64> = (0..n).map(|i| normalize_angle(pb.angle_of(x, i))).collect();
    let mut points = Vec::with_capacity(n);
    let (mut sum, mut max) = (0.0, 0.0f64);
    for (i, &phi) in phis.iter().enumerate() {
        let Some((p, _)) = point_at(&d, phi) else {
            return Ok(None);
        };
        let miss = (p - (pb.targets[i] * scale + centre)).norm();
        sum += miss;
        max = max.max(miss);
        points.push([p.x, p.y]);
    }
    let delta = normalize_angle(x[2]);
    let fb = FourBar {
        o1: d.o.coords,
        delta,
        d: g[3] * scale,
        a: d.l_oa,
        b: d.l_ab,
        c: d.l_cb,
        sigma,
    };
    let (start, span) = match &pb.timing {
        Timing::ClosedCurve => (0.0, TAU - 1e-9),
        Timing::Prescribed(_) => {
            let (mn, mx) = min_max(&(0..n).map(|i| pb.angle_of(x, i)).collect::<Vec<_>>());
            (mn, mx - mn)
        }
        Timing::Free => ordered_arc(&phis).unwrap_or((0.0, 0.0)),
    };
    let mut report = fb.report(
        "path generator",
        Some((normalize_angle(start - delta), span.max(1e-9))),
    )?;
    report
        .dimensions
        .push(("coupler point along AB".to_owned(), d.coupler.x));
    report
        .dimensions
        .push(("coupler point across AB".to_owned(), d.coupler.y));
    let reference = phis[0];
    let linkage = fb.linkage(
        "path generator",
        normalize_angle(reference - delta),
        vec![NamedPoint {
            name: "P".to_owned(),
            at: points[0],
        }],
        None,
    )?;
    Ok(Some(PathDesign {
        synthesis: Synthesis { linkage, report },
        mean_error: sum / n as f64,
        max_error: max,
        crank_angles: phis,
        coupler_points: points,
    }))
}
