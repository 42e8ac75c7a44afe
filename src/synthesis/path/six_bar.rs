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

use super::six_bar_problem::{Problem, SixBar, DIMS};
use super::six_bar_search::search;
use super::{
    normalised, normalize_angle, range_samples, Budget, PathDesign, PathOptions, PathRequirement,
    Progress, Timing, CHECK_STEP, SEARCH_STEP, V,
};
use crate::error::{Error, Result};
use crate::kinematics::Branch;
use crate::linkage::{Input, Joint, Link, Linkage, NamedPoint, Output};
use crate::synthesis::{check, Report, Synthesis};
use nalgebra::Point2;
use std::cell::Cell;
use std::f64::consts::TAU;
use std::time::Instant;

/// The fewest points: 16 unknowns, two equations a point.
const MIN_POINTS: usize = 8;

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
