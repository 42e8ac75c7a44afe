//! Path generation: a four-bar (or an offset slider-crank) whose coupler point passes through
//! given points (with or without prescribed crank angles) or traces a closed curve, by a
//! seeded global search.
//!
//! The slider-crank ([`slider`]) is searched as the four-bar with prescribed timing is, over
//! all its dimensions (eight, a gene of the four-bar's nine unused), for every timing: without
//! timing each candidate's turn is matched to the targets by the sampled positions that meet
//! them in their order ([`assign`]), and its polish re-assigns a point met on the wrong pass of
//! the curve.
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
//!
//! The parts: [`requirement`] and [`results`] (the public types), [`validate`] (refusals),
//! [`budget`], [`problem`] (a candidate's mechanism, constraints and whole check),
//! [`objective`], [`polish`] with [`least_squares`] and [`nelder_mead`], [`timed`] and
//! [`shape`] (the two searches), [`design`] (the designs kept, in the world), [`angles`].

mod angles;
mod assign;
mod budget;
mod design;
mod evolve;
mod least_squares;
mod nelder_mead;
mod objective;
mod polish;
mod problem;
mod requirement;
mod results;
mod shape;
mod six_bar;
mod six_bar_problem;
mod six_bar_search;
mod slider;
mod timed;
mod validate;

pub use requirement::{PathOptions, PathRequirement, Timing};
pub use results::{PathDesign, Progress};
pub use six_bar::six_bar_path_generator;

// The names the search's parts (and the six-bar's) reach through this module.
use angles::{min_max, normalize_angle};
use budget::{positions_per_evaluation, range_samples, Budget, CHECK_STEP, SEARCH_STEP};
use design::Found;
use evolve::Rng;
use least_squares::{continuation, levenberg_marquardt};
use problem::{shortest_link, Problem};
use timed::search_timed;
use validate::{check_requirement, normalised};

use crate::error::{Error, Result};
use crate::kinematics::batch::{CrankAngles, Positions};
use nalgebra::Vector2;
use std::f64::consts::TAU;
use std::time::Instant;

type V = Vector2<f64>;

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
/// How many times the polish without timing re-assigns the points' crank angles.
const REASSIGNMENTS: usize = 2;

/// The share of the evaluation budget kept for the polish of the shape search's last run:
/// without it a run that creeps on until the budget is spent leaves no evaluation to turn
/// its best candidates into designs.
const POLISH_SHARE: f64 = 0.1;

/// The kind of mechanism a search synthesises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    FourBar,
    SliderCrank,
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
/// size cannot be squared in `f64`; [`Error::NoMechanism`] for a path so small that its
/// size's square underflows (the message says so), for coinciding points, or when no
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
