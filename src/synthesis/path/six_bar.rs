//! Path generation by a Stephenson III six-bar with prescribed timing.
//!
//! Why this six-bar: a Stephenson III is a four-bar O1–A–B–O3 whose coupler carries a third
//! hinge C, and a dyad C–E–O5 hung between C and a third frame pivot O5, the tracer point P
//! on the dyad's link CE. Its positions are the four-bar's (crank, RRR dyad A–B–O3, C as a
//! coupler point) followed by one more RRR dyad C–E–O5 and P as a point of CE: the engine's
//! own blocks in their own order, each closed-form, no loop closure to iterate (a Watt II
//! would need the rocker's angle as a second crank, a Stephenson I/II a triad). The engine
//! analyses its description as a crank and two RRR groups.
//!
//! Fifteen dimensions: O1 (2), the frame's angle and length O1O3, the crank, coupler and
//! rocker, C on the coupler (along A→B, across to its left), O5 (2), CE, O5E, P on CE (along
//! C→E, across); the two assembly modes; θ0, the crank angle of the first point's Δφ = 0.
//! Sixteen continuous unknowns and two equations a point: at least 8 points.
//!
//! The search is the four-bar's with prescribed timing: differential evolution
//! (DE/current-to-pbest/1/bin, dithered F) in normalised units, each candidate evaluated at
//! its prescribed angles and over the range between them (both dyads must assemble with
//! |sin γ| ≥ sin \[γ\] at every sample, so the tracer reaches the points on one circuit and
//! branch, in order: no circuit, branch or order defect), Levenberg–Marquardt polishes of the
//! best member and a few random ones every generation, and the best candidates of each run
//! polished by Levenberg–Marquardt, a near miss then followed to the points by continuation
//! (Levenberg–Marquardt alone stalls there: eight precision points make the misses'
//! Jacobian ill-conditioned, its smallest singular value about 1e-6 of its largest; in the
//! budget's second half the run's best near miss is also followed within the run), and
//! checked whole (every 1° of the range).

use super::{
    continuation, evolve, levenberg_marquardt, min_max, normalised, normalize_angle, range_samples,
    Budget, PathDesign, PathOptions, PathRequirement, Progress, Rng, Timing, CHECK_STEP,
    INFEASIBLE, POLISHED, SEARCH_STEP, V,
};
use crate::error::{Error, Result};
use crate::kinematics::batch::coupler_point;
use crate::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use crate::linkage::{Input, Joint, Link, Linkage, NamedPoint, Output};
use crate::synthesis::{check, Report, Synthesis};
use nalgebra::Point2;
use std::cell::Cell;
use std::f64::consts::TAU;
use std::time::Instant;

/// The dimensions (15), then the two modes' genes and θ0.
const DIMS: usize = 15;
const GENES: usize = DIMS + 3;
/// The genes that are angles: the frame's, θ0.
const WRAP: [usize; 2] = [2, GENES - 1];
/// Random members polished (Lamarckian) every generation, besides the best: a polish at the
/// n points costs n/`positions` of an evaluation a residual, so that where the search alone
/// stalls in sixteen dimensions, many short polishes are cheap.
const LUCKY: usize = 5;
/// The mean miss (path sizes) below which the run's best member is a near miss, followed
/// to the points by continuation within the run.
const NEAR: f64 = 1e-3;
/// The fewest points: 16 unknowns, two equations a point.
const MIN_POINTS: usize = 8;
/// The unknowns the box `max_size` bounds: O1 (0, 1), the frame's length and the five
/// links (3–6, 11, 12), C's offsets (7, 8), O5 (9, 10) and P's offsets (13, 14).
const BOXED: [usize; 14] = [0, 1, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14];

/// One Stephenson III six-bar (any units).
#[derive(Debug, Clone, Copy)]
struct SixBar {
    o1: Point2<f64>,
    o3: Point2<f64>,
    o5: Point2<f64>,
    a: f64,
    b: f64,
    c: f64,
    /// C on the coupler, (along, across)/AB.
    uv_c: [f64; 2],
    ce: f64,
    e5: f64,
    /// P on CE, (along, across)/CE.
    uv_p: [f64; 2],
    mode1: Branch,
    mode2: Branch,
}

/// The joints of one position: A, B, C, E, P.
struct Pose {
    a: Point2<f64>,
    b: Point2<f64>,
    c: Point2<f64>,
    e: Point2<f64>,
    p: Point2<f64>,
}

fn branch(s: f64) -> Branch {
    if s > 0.0 {
        Branch::Plus
    } else {
        Branch::Minus
    }
}

/// How far a dyad of the links `l1`, `l2` between points `d` apart is from assembling.
fn gap(d: f64, l1: f64, l2: f64) -> f64 {
    (d - (l1 + l2)).max((l1 - l2).abs() - d).max(0.0)
}

impl SixBar {
    /// From the dimensions `x[..15]` and the modes' signs.
    fn of(x: &[f64], s1: f64, s2: f64) -> Self {
        let o1 = Point2::new(x[0], x[1]);
        Self {
            o1,
            o3: o1 + x[3] * V::new(x[2].cos(), x[2].sin()),
            o5: Point2::new(x[9], x[10]),
            a: x[4],
            b: x[5],
            c: x[6],
            uv_c: [x[7] / x[5], x[8] / x[5]],
            ce: x[11],
            e5: x[12],
            uv_p: [x[13] / x[11], x[14] / x[11]],
            mode1: branch(s1),
            mode2: branch(s2),
        }
    }

    /// The pose at the crank angle `phi` and the smaller |sin γ| of the two dyads; where it
    /// does not assemble (or is singular), the shortfall: 1 + the gap, or 2.
    fn at(&self, phi: f64) -> std::result::Result<(Pose, f64), f64> {
        let a = crank(self.o1, self.a, Motion::fixed(phi))
            .map_err(|_| 2.0)?
            .a;
        let r1 = rrr_dyad(a, PointMotion::fixed(self.o3), self.b, self.c, self.mode1)
            .map_err(|_| 1.0 + gap((self.o3 - a.p).norm(), self.b, self.c).min(10.0))?;
        let c = coupler_point(a.p, r1.b.p, self.uv_c);
        let r2 = rrr_dyad(
            PointMotion::fixed(c),
            PointMotion::fixed(self.o5),
            self.ce,
            self.e5,
            self.mode2,
        )
        .map_err(|_| 1.0 + gap((self.o5 - c).norm(), self.ce, self.e5).min(10.0))?;
        let p = coupler_point(c, r2.b.p, self.uv_p);
        let m = r1.det.abs().min(r2.det.abs());
        if !(p.x + p.y + m).is_finite() {
            return Err(2.0);
        }
        Ok((
            Pose {
                a: a.p,
                b: r1.b.p,
                c,
                e: r2.b.p,
                p,
            },
            m,
        ))
    }
}

struct Problem<'a> {
    budget: Budget,
    /// The positions the engine's blocks solved for the search (each counted in `budget`).
    solved: Cell<usize>,
    targets: Vec<V>,
    delta: &'a [f64],
    sin_gamma: f64,
    ratio: f64,
    size: f64,
}

impl Problem<'_> {
    /// 0 where the six links keep the ratio bound, else a penalty above [`INFEASIBLE`].
    fn lengths_ok(&self, x: &[f64]) -> f64 {
        let l = [x[3], x[4], x[5], x[6], x[11], x[12]];
        if !x[..DIMS].iter().all(|v| v.is_finite()) || l.iter().any(|&v| v.is_nan() || v <= 0.0) {
            return INFEASIBLE * 10.0;
        }
        let (mn, mx) = min_max(&l);
        let excess = mx / mn / self.ratio - 1.0;
        if excess > 0.0 {
            INFEASIBLE + excess
        } else {
            0.0
        }
    }

    /// Whether the unknowns `x` are within the box `max_size` (path sizes): the pivots O1 and
    /// O5 (each coordinate from the points' centroid), the six lengths and the offsets of C
    /// and P (the search's bounds; the frame's angle and θ0 are free).
    fn within(&self, x: &[f64]) -> bool {
        BOXED.iter().all(|&k| x[k].abs() <= self.size)
    }

    /// The crank angles of the points and `step`-spaced samples of the range between them.
    fn angles(&self, theta0: f64, step: f64) -> Vec<f64> {
        let (mn, mx) = min_max(self.delta);
        let steps = range_samples(self.delta, step) - 1;
        self.delta
            .iter()
            .map(|d| theta0 + d)
            .chain((0..=steps).map(|k| theta0 + mn + (mx - mn) * k as f64 / steps as f64))
            .collect()
    }

    /// The mean miss of the unknowns `x` (dimensions, θ0) with the modes `s`, if every
    /// sample at `step` assembles with γ ≥ \[γ\]; else a penalty ≥ [`INFEASIBLE`].
    fn cost(&self, x: &[f64], s: [f64; 2], step: f64) -> f64 {
        let p = self.lengths_ok(x);
        if p > 0.0 {
            return p;
        }
        let m = SixBar::of(x, s[0], s[1]);
        let phis = self.angles(x[DIMS], step);
        self.solved.set(self.solved.get() + phis.len());
        let (mut miss, mut short, mut bad) = (0.0, 0.0, false);
        for (i, &phi) in phis.iter().enumerate() {
            match m.at(phi) {
                Ok((pose, g)) => {
                    short += (self.sin_gamma - g).max(0.0);
                    bad |= g < self.sin_gamma;
                    if let Some(t) = self.targets.get(i).filter(|_| i < self.delta.len()) {
                        miss += (pose.p.coords - t).norm();
                    }
                }
                Err(s) => {
                    short += s;
                    bad = true;
                }
            }
        }
        if bad {
            INFEASIBLE + short / phis.len() as f64
        } else {
            miss / self.delta.len() as f64
        }
    }

    fn objective(&self, g: &[f64]) -> f64 {
        self.budget.add(1);
        let (x, s) = split(g);
        // Outside the box (a Lamarckian polish that left it; the evolution's own trials stay
        // within its bounds, which are the box): refused, so that the population stays in
        // the box where the designs must end.
        if !self.within(&x) {
            return INFEASIBLE * 10.0;
        }
        self.cost(&x, s, SEARCH_STEP)
    }

    fn residuals(&self, x: &[f64], s: [f64; 2]) -> Option<Vec<f64>> {
        if !self.budget.take_polish() {
            return None;
        }
        let m = SixBar::of(x, s[0], s[1]);
        let mut r = Vec::with_capacity(2 * self.targets.len());
        for (t, d) in self.targets.iter().zip(self.delta) {
            self.solved.set(self.solved.get() + 1);
            let (pose, _) = m.at(x[DIMS] + d).ok()?;
            r.push(pose.p.x - t.x);
            r.push(pose.p.y - t.y);
        }
        Some(r)
    }

    /// Levenberg–Marquardt on the misses, the link ratio kept; if `within`, each step also
    /// kept within the other constraints (the box `max_size`, and assembly with γ ≥ \[γ\]
    /// over the range as the search samples it): a free polish that converges to a design
    /// the whole check refuses (outside the box, or the points met only past a dead point)
    /// is done again within them.
    fn lm(&self, x: Vec<f64>, s: [f64; 2], iterations: usize, within: bool) -> Vec<f64> {
        let res = |x: &[f64]| self.residuals(x, s);
        let mut accept = |x: &[f64]| {
            self.lengths_ok(x) == 0.0
                && (!within || self.within(x))
                && (!within
                    || self.budget.room(1) && {
                        self.budget.add(1);
                        self.cost(x, s, SEARCH_STEP) < INFEASIBLE
                    })
        };
        let n = x.len();
        levenberg_marquardt(&res, &mut accept, x, n, iterations)
    }

    /// [`continuation`] from the near miss `x` to the points, the link ratio kept.
    fn follow(&self, x: Vec<f64>, s: [f64; 2]) -> Vec<f64> {
        let res = |x: &[f64]| self.residuals(x, s);
        let mut accept = |x: &[f64]| self.lengths_ok(x) == 0.0;
        let n = x.len();
        continuation(&res, &mut accept, x, n, 400)
    }

    /// The whole check: the box `max_size`, the ratio, assembly with γ ≥ \[γ\] every 1° of
    /// the range; the mean miss where it passes, `None` where it does not (or the budget has
    /// no room for it).
    fn check(&self, x: &[f64], s: [f64; 2]) -> Option<f64> {
        if !self.within(x) || !self.budget.charge(self.budget.check) {
            return None;
        }
        Some(self.cost(x, s, CHECK_STEP)).filter(|&c| c < INFEASIBLE)
    }
}

/// The unknowns (dimensions, θ0) and the modes' signs of the genes `g`.
fn split(g: &[f64]) -> (Vec<f64>, [f64; 2]) {
    let mut x = g[..DIMS].to_vec();
    x.push(g[DIMS + 2]);
    (x, [g[DIMS].signum(), g[DIMS + 1].signum()])
}

fn genes_of(x: &[f64], s: [f64; 2]) -> Vec<f64> {
    let mut g = x[..DIMS].to_vec();
    g[2] = g[2].rem_euclid(TAU);
    g.extend([s[0], s[1], x[DIMS].rem_euclid(TAU)]);
    g
}

impl PathRequirement {
    /// Eight points of a known Stephenson III six-bar at crank angles 0.3 rad apart (the
    /// first Δφ = 0, the crank then at 0.3 rad): a precision-point requirement for
    /// [`six_bar_path_generator`], the one its worked example, the `synthesis` example and the
    /// bench solve.
    ///
    /// The six-bar: O1 at the origin, the crank 0.1, the dyad A–B–O3 (coupler 0.3, rocker
    /// 0.25, O3 at (0.35, 0), mode +), C on the coupler at (0.5, 0.4) of AB (along, across),
    /// the dyad C–E–O5 (CE 0.25, O5E 0.2, O5 at (0.3, 0.35), mode −), P on CE at (0.6, −0.3)
    /// of CE; its transmission angle stays above 0.3 rad (17°) over the points, not 40°.
    ///
    /// # Errors
    /// None for these data: [`Error::NoMechanism`] if the six-bar did not assemble at a point.
    pub fn six_bar_example() -> Result<Self> {
        let m = SixBar {
            o1: Point2::origin(),
            o3: Point2::new(0.35, 0.0),
            o5: Point2::new(0.3, 0.35),
            a: 0.1,
            b: 0.3,
            c: 0.25,
            uv_c: [0.5, 0.4],
            ce: 0.25,
            e5: 0.2,
            uv_p: [0.6, -0.3],
            mode1: Branch::Plus,
            mode2: Branch::Minus,
        };
        let delta: Vec<f64> = (0..8).map(|k| 0.3 * f64::from(k)).collect();
        let points = delta
            .iter()
            .map(|d| {
                let p = m.at(0.3 + d).map_err(|_| Error::NoMechanism {
                    method: "path generation",
                    problem: format!("the example six-bar does not assemble at Δφ = {d} rad"),
                })?;
                Ok([p.0.p.x, p.0.p.y])
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            points,
            timing: Timing::Prescribed(delta),
        })
    }
}

/// A Stephenson III six-bar whose tracer point `P` passes through the points of `req` at
/// the prescribed crank angles: the `opts.designs` best distinct designs found, best first,
/// each with its misses.
///
/// The six-bar is a four-bar O1–A–B–O3 whose coupler carries a third hinge C, and a dyad
/// C–E–O5 to a third frame pivot, `P` on its link CE: a crank and two RRR dyads, each in
/// closed form, so that a candidate costs two dyads a position. Its 15 dimensions, two
/// modes and θ0 are searched as [`path_generator`](super::path_generator)'s four-bar with
/// prescribed timing is (seeded differential evolution, Levenberg–Marquardt polishes); both
/// dyads must assemble with γ ≥ \[γ\] over the whole range between the prescribed angles
/// (no circuit, branch or order defect).
///
/// The description's joints: `O1`, `A`, `B`, `O3` (the four-bar), `C` on the coupler,
/// `E`, `O5` (the dyad), the tracer `P` on the link `CE`; its links `frame` (O1, O3, O5),
/// `crank`, `coupler` (A, B, C), `rocker`, `link CE` and `output` (O5, E), posed at the first
/// point's crank angle. `max_link_ratio` bounds the six lengths O1O3, O1A, AB, O3B, CE, O5E;
/// `max_size` (in path sizes) each coordinate of the pivots O1 and O5 from the points'
/// centroid, the six lengths and the offsets of C on AB and of P on CE (along and across):
/// a design outside that box is never returned (a polish that ends outside it is done
/// again with its steps kept inside). A box too small for the tracer to reach the farthest
/// point (its reach is below 4.65·`max_size` from the centroid) is refused.
///
/// # Example
/// Eight points (as many as the unknowns allow: a precision-point synthesis) of a known
/// six-bar at crank angles 0.3 rad apart ([`PathRequirement::six_bar_example`]): the
/// synthesis finds a six-bar through them (this one or another) to 1e-9 of the path's size,
/// and the engine, given its description, puts `P` on them.
/// ```
/// use tmm::kinematics::Motion;
/// use tmm::linkage::Plan;
/// use tmm::synthesis::{six_bar_path_generator, PathOptions, PathRequirement};
/// let req = PathRequirement::six_bar_example()?;
/// let opts = PathOptions::default().with_designs(1).with_min_transmission_angle(0.3);
/// let best = &six_bar_path_generator(&req, &opts, |_| true)?[0];
/// assert!(best.mean_error < 1e-10);
/// let plan = Plan::new(&best.synthesis.linkage)?;
/// for (phi, t) in best.crank_angles.iter().zip(&req.points) {
///     let p = plan.kinematics(Motion::fixed(*phi))?.point("P")?.p;
///     assert!((p.x - t[0]).hypot(p.y - t[1]) < 1e-9);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`path_generator`](super::path_generator), and [`Error::OutOfRange`] naming `timing`
/// when it is not prescribed, `points` for fewer than 8, or `max_size` for a box of at most
/// 1/(√2 + 1 + √5) ≈ 0.215 path sizes.
pub fn six_bar_path_generator(
    req: &PathRequirement,
    opts: &PathOptions,
    mut progress: impl FnMut(&Progress) -> bool,
) -> Result<Vec<PathDesign>> {
    let Timing::Prescribed(delta) = &req.timing else {
        return Err(Error::OutOfRange {
            name: "timing (the six-bar's must be prescribed)",
            value: f64::NAN,
            min: f64::NAN,
            max: f64::NAN,
            ends: crate::Ends::Closed,
        });
    };
    let gamma = super::check_requirement(super::Kind::FourBar, req, opts)?;
    if req.points.len() < MIN_POINTS {
        return Err(Error::OutOfRange {
            name: "points (a six-bar has 16 unknowns: at least 8 points)",
            value: req.points.len() as f64,
            min: MIN_POINTS as f64,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    // The box bounds the tracer's reach: from the centroid, |O5| ≤ √2·s (each coordinate
    // within s), |E − O5| = O5E ≤ s, and P − E = (along − CE)·u + across·n with along in
    // [−s, s], CE in (0, s], |across| ≤ s, so |P − E| < √5·s: |P| < (√2 + 1 + √5)·s, and
    // the farthest point is 1 path size away.
    let reach = std::f64::consts::SQRT_2 + 1.0 + 5f64.sqrt();
    if opts.max_size * reach <= 1.0 {
        return Err(Error::OutOfRange {
            name: "max_size (path sizes; within a box of s the six-bar's tracer reaches less than 4.65·s from the points' centroid, and the farthest point is 1 away)",
            value: opts.max_size,
            min: 1.0 / reach,
            max: f64::INFINITY,
            ends: crate::Ends::Open,
        });
    }
    let start = Instant::now();
    let (pts, centre, scale) = normalised(&req.points);
    let n = req.points.len();
    let pb = Problem {
        budget: Budget::new(
            opts.max_evaluations,
            opts.max_time,
            start,
            n + range_samples(delta, SEARCH_STEP),
            n,
            n + range_samples(delta, CHECK_STEP),
        ),
        solved: Cell::new(0),
        targets: pts.iter().map(|p| (p - centre) / scale).collect(),
        delta,
        sin_gamma: gamma.sin(),
        ratio: opts.max_link_ratio,
        size: opts.max_size,
    };
    let mut found: Vec<(Vec<f64>, [f64; 2], f64)> = Vec::new();
    search(&pb, opts, &mut found, &mut progress);
    let mut designs = Vec::new();
    let mut refused = None;
    for (x, s, _) in &found {
        // A design the engine refuses in the world's units (rounding there, a joint beyond
        // its range) is left out, the others kept; if none is left, why the last one went.
        match design(&pb, x, *s, centre, scale) {
            Ok(d) => designs.push(d),
            Err(e) => refused = Some(e),
        }
    }
    if designs.is_empty() {
        if let Some(e) = refused {
            return Err(e);
        }
        return Err(Error::NoMechanism {
            method: "path generation",
            problem: format!(
                "no six-bar met the constraints (γ ≥ {:.1}°, link ratio ≤ {}, within max_size = {} path sizes, assembly over the range) in {} evaluations and {:.3} s (the budget: {} evaluations, {:.3} s)",
                gamma.to_degrees(),
                opts.max_link_ratio,
                opts.max_size,
                pb.budget.used(),
                start.elapsed().as_secs_f64(),
                opts.max_evaluations,
                opts.max_time.as_secs_f64(),
            ),
        });
    }
    designs.sort_by(|a, b| a.mean_error.total_cmp(&b.mean_error));
    designs.truncate(opts.designs.max(1));
    Ok(designs)
}

/// Keeps the polished `x` among the distinct designs `found` (same six lengths to 1e-4: the
/// better of the two).
fn keep(found: &mut Vec<(Vec<f64>, [f64; 2], f64)>, x: Vec<f64>, s: [f64; 2], miss: f64) {
    let key = |x: &[f64]| {
        let mut l = [x[3], x[4], x[5], x[6], x[11], x[12]];
        l.sort_by(f64::total_cmp);
        l
    };
    let k = key(&x);
    let same = found.iter().position(|(y, _, _)| {
        key(y)
            .iter()
            .zip(&k)
            .all(|(a, b)| (a - b).abs() <= 1e-4 * b.abs())
    });
    match same {
        Some(i) if found[i].2 <= miss => {}
        Some(i) => found[i] = (x, s, miss),
        None => found.push((x, s, miss)),
    }
}

/// Runs of differential evolution from fresh populations, each until it stagnates, its best
/// candidates polished; until enough designs meet the points to the tolerance or the budget
/// is spent.
fn search(
    pb: &Problem,
    opts: &PathOptions,
    found: &mut Vec<(Vec<f64>, [f64; 2], f64)>,
    progress: &mut dyn FnMut(&Progress) -> bool,
) {
    let s = pb.size;
    let l = super::shortest_link(s);
    let mut lo = vec![-s, -s, 0.0, l, l, l, l, -s, -s, -s, -s, l, l, -s, -s];
    let mut hi = vec![s, s, TAU, s, s, s, s, s, s, s, s, s, s, s, s];
    lo.extend([-1.0, -1.0, 0.0]);
    hi.extend([1.0, 1.0, TAU]);
    let np = opts.population;
    let mut rng = Rng(opts.seed);
    let want = opts.designs.max(1);
    let good = |found: &[(Vec<f64>, [f64; 2], f64)]| {
        found.iter().filter(|d| d.2 <= opts.tolerance).count()
    };
    let mut generation = 0;
    let mut stopped = false;
    // The best over every run: a restart's fresh population starts worse, and the best
    // reported must never rise.
    let mut best_ever = f64::INFINITY;
    while !stopped && pb.budget.room(2 * np) {
        let mut pop = evolve::population(np, &lo, &hi, &mut rng);
        let mut fit: Vec<f64> = pop.iter().map(|g| pb.objective(g)).collect();
        let mut stagnation = evolve::Stagnation::new(1e-6);
        let mut followed = f64::INFINITY;
        while pb.budget.room(np) {
            generation += 1;
            evolve::generation(&mut pop, &mut fit, &lo, &hi, &WRAP, &mut rng, &mut |g| {
                pb.objective(g)
            });
            {
                // Lamarckian: the best member and a random one polished, where that is better.
                let best_i = (0..np)
                    .min_by(|&a, &b| fit[a].total_cmp(&fit[b]))
                    .unwrap_or(0);
                let lucky: Vec<usize> = (0..LUCKY).map(|_| rng.below(np)).collect();
                for (k, i) in std::iter::once(best_i).chain(lucky).enumerate() {
                    if fit[i] >= INFEASIBLE || !pb.budget.room(2) {
                        continue;
                    }
                    let (x, sg) = split(&pop[i]);
                    // In the budget's second half (the end-of-run continuation alone has
                    // not closed a near miss): the best member, a near miss half the last
                    // one followed, followed to the points before its polish.
                    let follow = k == 0
                        && pb.budget.used.get() > 0.5 * pb.budget.max as f64
                        && fit[i] < NEAR
                        && fit[i] < 0.5 * followed;
                    // Free to leave the box on its way (held inside, it stalls at the box's
                    // walls); a member polished out of the box is refused by the objective.
                    let x = if follow {
                        followed = fit[i];
                        pb.follow(x, sg)
                    } else {
                        x
                    };
                    let g = genes_of(&pb.lm(x, sg, 30, false), sg);
                    let f = pb.objective(&g);
                    if f < fit[i] {
                        pop[i] = g;
                        fit[i] = f;
                    }
                }
            }
            let best = fit.iter().copied().fold(f64::INFINITY, f64::min);
            best_ever = best_ever.min(best);
            if !progress(&Progress {
                generation,
                evaluations: pb.budget.used(),
                best: best_ever,
                elapsed: pb.budget.start.elapsed(),
            }) {
                stopped = true;
                break;
            }
            if stagnation.after(best) {
                break;
            }
        }
        let mut order: Vec<usize> = (0..np).filter(|&i| fit[i] < INFEASIBLE).collect();
        order.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]));
        for &i in order.iter().take(POLISHED) {
            if !pb.budget.room(2) {
                break;
            }
            let (x0, sg) = split(&pop[i]);
            let x = pb.lm(x0.clone(), sg, 200, false);
            let (mut x, mut miss) = if let Some(m) = pb.check(&x, sg) {
                (x, m)
            } else if let Some(m0) = pb.check(&x0, sg) {
                // The free polish ended outside the box or past a dead point: done again
                // within them (the range sampled as the search does). The whole check may
                // still refuse it, and the start (in the box) is the design then.
                let y = pb.lm(x0.clone(), sg, 200, true);
                match pb.check(&y, sg) {
                    Some(m) => (y, m),
                    None => (x0, m0),
                }
            } else {
                continue;
            };
            if miss > opts.tolerance {
                // A near miss where Levenberg–Marquardt stalled in a curved valley of the
                // ill-conditioned misses: followed down to the points by continuation.
                // Where it ends outside the box, the check refuses it.
                let y = pb.lm(pb.follow(x.clone(), sg), sg, 200, false);
                if let Some(m) = pb.check(&y, sg)
                    && m < miss
                {
                    (x, miss) = (y, m);
                }
            }
            keep(found, x, sg, miss);
        }
        if good(found) >= want {
            break;
        }
    }
}

/// The design in the world: the description posed at the first point's crank angle, its
/// misses and report (γ_min over the range, every 1°).
fn design(pb: &Problem, x: &[f64], s: [f64; 2], centre: V, scale: f64) -> Result<PathDesign> {
    // Lengths and offsets scale; the pivots O1 (0, 1) and O5 (9, 10) also move back to the
    // centroid; the frame's angle (2) and θ0 stay.
    let mut w = x.to_vec();
    for k in [0, 1, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14] {
        w[k] = x[k] * scale;
    }
    for (k, c) in [(0, centre.x), (1, centre.y), (9, centre.x), (10, centre.y)] {
        w[k] += c;
    }
    let m = SixBar::of(&w, s[0], s[1]);
    let phis: Vec<f64> = pb
        .delta
        .iter()
        .map(|d| normalize_angle(x[DIMS] + d))
        .collect();
    let no = |phi: f64| Error::NoMechanism {
        method: "path generation",
        problem: format!("the six-bar found does not assemble at the crank angle {phi} rad"),
    };
    let (mut sum, mut max, mut points) = (0.0, 0.0f64, Vec::new());
    for (phi, t) in phis.iter().zip(&pb.targets) {
        let (pose, _) = m.at(*phi).map_err(|_| no(*phi))?;
        let miss = (pose.p.coords - (t * scale + centre)).norm();
        sum += miss;
        max = max.max(miss);
        points.push([pose.p.x, pose.p.y]);
    }
    let (mut g_min, mut g_at) = (f64::INFINITY, phis[0]);
    for phi in pb.angles(x[DIMS], CHECK_STEP) {
        let (_, g) = m.at(phi).map_err(|_| no(phi))?;
        if g < g_min {
            (g_min, g_at) = (g, phi);
        }
    }
    let (pose, _) = m.at(phis[0]).map_err(|_| no(phis[0]))?;
    let xy = |p: Point2<f64>| [p.x, p.y];
    let mut ce = Link::new("link CE", &["C", "E"]);
    ce.points = vec![NamedPoint {
        name: "P".to_owned(),
        at: points[0],
    }];
    let linkage = Linkage {
        name: "six-bar path generator".to_owned(),
        joints: vec![
            Joint::revolute("O1", xy(m.o1)),
            Joint::revolute("A", xy(pose.a)),
            Joint::revolute("B", xy(pose.b)),
            Joint::revolute("O3", xy(m.o3)),
            Joint::revolute("C", xy(pose.c)),
            Joint::revolute("E", xy(pose.e)),
            Joint::revolute("O5", xy(m.o5)),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3", "O5"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("coupler", &["A", "B", "C"]),
            Link::new("rocker", &["O3", "B"]),
            ce,
            Link::new("output", &["O5", "E"]),
        ],
        input: Input::crank("crank"),
        output: Some(Output::Angle("output".to_owned())),
        ..Linkage::default()
    };
    let names = [
        "frame O1O3",
        "crank O1A",
        "coupler AB",
        "rocker O3B",
        "C along AB",
        "C across AB",
        "link CE",
        "output O5E",
        "P along CE",
        "P across CE",
    ];
    let values = [
        w[3], w[4], w[5], w[6], w[7], w[8], w[11], w[12], w[13], w[14],
    ];
    let report = Report {
        kind: "Stephenson III six-bar path generator",
        time_ratio: None,
        stroke: None,
        min_transmission_angle: g_min.clamp(0.0, 1.0).asin(),
        min_transmission_at: g_at.rem_euclid(TAU),
        grashof: None,
        dimensions: names
            .iter()
            .zip(values)
            .map(|(n, v)| ((*n).to_owned(), v))
            .collect(),
    };
    // The engine accepts it (its joints within the synthesis' range, its plan made and
    // solved at its reference pose), as every synthesis' answer.
    check::accepted(&linkage)?;
    let n = phis.len() as f64;
    Ok(PathDesign {
        synthesis: Synthesis { linkage, report },
        mean_error: sum / n,
        max_error: max,
        crank_angles: phis,
        coupler_points: points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every position the engine's blocks solve in the search — the global stage, the
    /// polishes' residuals and Jacobian columns, the continuation, the whole checks — is
    /// counted against the budget in its unit (the positions of one evaluation of the
    /// global stage), and the count never passes the budget: run with a tolerance of 0, the
    /// search spends its budget whole.
    #[test]
    fn every_position_solved_is_counted_against_the_budget() {
        let req = PathRequirement::six_bar_example().unwrap();
        let Timing::Prescribed(delta) = &req.timing else {
            unreachable!()
        };
        let mut opts = PathOptions::default()
            .with_population(20)
            .with_max_evaluations(20_000)
            .with_min_transmission_angle(0.3);
        opts.tolerance = 0.0;
        let (pts, centre, scale) = normalised(&req.points);
        let n = pts.len();
        let per_eval = n + range_samples(delta, SEARCH_STEP);
        let pb = Problem {
            budget: Budget::new(
                opts.max_evaluations,
                opts.max_time,
                Instant::now(),
                per_eval,
                n,
                n + range_samples(delta, CHECK_STEP),
            ),
            solved: Cell::new(0),
            targets: pts.iter().map(|p| (p - centre) / scale).collect(),
            delta,
            sin_gamma: 0.3f64.sin(),
            ratio: opts.max_link_ratio,
            size: opts.max_size,
        };
        let mut found = Vec::new();
        let mut last = 0;
        search(&pb, &opts, &mut found, &mut |p| {
            last = p.evaluations;
            true
        });
        let used = pb.budget.used.get();
        let solved = pb.solved.get() as f64 / per_eval as f64;
        assert!(used <= opts.max_evaluations as f64 && last <= opts.max_evaluations);
        assert!(
            solved <= used * (1.0 + 1e-12),
            "{solved} evaluations' positions solved, {used} counted"
        );
        // Spent: less than one generation's worth left.
        assert!(
            used > (opts.max_evaluations - 2 * opts.population) as f64,
            "{used}"
        );
    }
}
