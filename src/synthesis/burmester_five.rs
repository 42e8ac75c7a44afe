#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Burmester's points of five poses: every candidate from the elimination
//! (`burmester_resultant`), polished on the difference-quotient equations (`pose_newton`),
//! the duplicates merged and the count checked.

use super::burmester::{check_poses, v, Dyad, Pose};
use super::burmester_resultant::{self, Candidates};
use super::burmester_two_angle;
use super::pose_newton::{Accuracy, PoseEquations};
use super::pose_order;
use crate::error::{Error, Result};

/// Burmester's points of five poses: the dyads that carry the coupler through all five (at
/// most four; none for some poses).
///
/// Derivation (in `burmester_resultant`): a dyad (centre point G, circle point z in the first
/// pose) fits the poses when four equations, each bilinear in G and z, hold; for a given z
/// they are four lines in G that must meet, so z makes a 4×3 matrix of affine entries drop
/// rank. That locus has six points, two of them the circular points at infinity, so at most
/// four finite ones. Eliminating G and then one coordinate of z leaves a polynomial of degree
/// seven in the other, whose every root (its companion matrix's eigenvalues) is tried: no
/// point can be stepped over, as a scan of the curves could
/// ([`burmester_points_by_scan`](super::burmester_points_by_scan), kept as a cross-check).
/// Each candidate is polished by Newton's method on equations written as difference
/// quotients (exact when poses nearly coincide) and kept if it fits all five poses to 1e-9
/// of its size.
///
/// # Examples
/// Five poses of the coupler of a four-bar: its two dyads are among Burmester's points.
/// ```
/// use tmm::synthesis::{burmester_points, Pose};
/// // The coupler of the crank-rocker O1 = (0, 0), A, B, O3 = (0.4, 0): five poses read off
/// // its motion (A on the crank of 0.1 m; B on the rocker of 0.3 m; coupler 0.35 m).
/// let (a, b, c, d) = (0.1, 0.35, 0.3, 0.4);
/// // The pose: the coupler point P, 0.1 m left of the middle of AB, and the angle of AB.
/// let pose = |phi: f64| {
///     let (ax, ay) = (a * phi.cos(), a * phi.sin());
///     let (vx, vy) = (d - ax, -ay);
///     let e = vx.hypot(vy);
///     let along = (b * b - c * c + e * e) / (2.0 * e);
///     let h = (b * b - along * along).sqrt();
///     let (bx, by) = (ax + along * vx / e - h * vy / e, ay + along * vy / e + h * vx / e);
///     let (ux, uy) = ((bx - ax) / b, (by - ay) / b);
///     Pose::new([ax + 0.5 * b * ux - 0.1 * uy, ay + 0.5 * b * uy + 0.1 * ux], uy.atan2(ux))
/// };
/// let poses = [0.3, 0.9, 1.6, 2.4, 3.0].map(pose);
/// let points = burmester_points(&poses)?;
/// // The crank O1A (centre (0, 0)) and the rocker O3B (centre (0.4, 0)) are among them.
/// let near = |x: f64, y: f64| points.iter().any(|p| (p.centre[0] - x).hypot(p.centre[1] - y) < 1e-8);
/// assert!(near(0.0, 0.0) && near(0.4, 0.0));
/// assert!(points.len() <= 4);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses,
/// for poses that all turn about one point (every coupler point then keeps its distance
/// from it: a continuum of dyads), for other degenerate poses that more than four dyads
/// fit, for poses whose dyads form a continuum (e.g. a pure translation along five points of
/// one circle; the message says "infinitely many"), and for poses whose every elimination degenerates (the points cannot
/// be counted: the message says so). Poses with exactly two distinct angles are solved in
/// closed form (at most two dyads). A dyad more than 10⁶ times longer than the poses' extent (from the first pose) is
/// not returned: it is a slider's dyad (the bisectors meeting at infinity) found to rounding.
pub fn burmester_points(poses: &[Pose; 5]) -> Result<Vec<Dyad>> {
    check_poses(poses)?;
    pose_order::not_about_one_point(poses)?;
    let equations = PoseEquations::new(poses);
    match burmester_resultant::candidates(&equations) {
        Candidates::Found(found) => {
            let starts = found
                .into_iter()
                .map(|(centre, circle)| Dyad { centre, circle });
            kept(&equations, poses, starts)
        }
        // Every elimination degenerates (the minors share a factor). Poses with two angles
        // only do this; they are solved in closed form (`burmester_two_angle`). Others are
        // not known to: refused, naming the degeneracy.
        Candidates::Degenerate => match burmester_two_angle::points(poses) {
            Some(points) => {
                let points = points?;
                let extent = poses
                    .iter()
                    .map(|p| (v(p.at) - v(poses[0].at)).norm())
                    .fold(0.0, f64::max);
                // As for every count: a slider's dyad (10⁶ extents long) is not returned.
                Ok(points
                    .into_iter()
                    .filter(|d| d.length() <= 1e6 * extent)
                    .collect())
            }
            None => Err(Error::NoMechanism {
                method: "Burmester's points",
                problem: "every elimination of the five poses' equations degenerates (each \
                          pair of 3×3 minors shares a factor, in both directions): the points \
                          cannot be counted"
                    .to_owned(),
            }),
        },
        Candidates::Continuum(problem) => Err(Error::NoMechanism {
            method: "Burmester's points",
            problem,
        }),
    }
}

/// The Burmester points among `starts` (dyads named in the first of `given`): each polished
/// on `equations` (a start that does not converge to rounding was not near a point), kept if
/// it fits the five poses to 1e-9 of its size and is not a slider's, duplicates merged; more
/// than four is an error (a continuum).
pub(super) fn kept(
    equations: &PoseEquations,
    given: &[Pose; 5],
    starts: impl Iterator<Item = Dyad>,
) -> Result<Vec<Dyad>> {
    // The poses' extent from the first given one (the scale of the fit and of duplicates).
    let extent = given
        .iter()
        .map(|p| (v(p.at) - v(given[0].at)).norm())
        .fold(0.0, f64::max);
    let mut out: Vec<(Dyad, Accuracy)> = Vec::new();
    for start in starts {
        let Some((dyad, accuracy)) = equations.polish(start) else {
            continue;
        };
        let scale = extent + dyad.length();
        // The same point reached from two starts: each polish is within its derived accuracy
        // of the root (`PoseEquations::accuracy`, from the Jacobian's conditioning at that
        // point), so two polishes of one root are within the sum of theirs; points farther
        // apart than that are distinct roots, however far out they lie. (The sum, not a
        // multiple of the larger: two polishes of one root have one Jacobian and so nearly one
        // accuracy; a nearly double root's accuracy is wide, and its neighbour's is just as
        // wide, since the Jacobian nearly vanishes at both.)
        let duplicate = out.iter().any(|(o, t)| {
            (v(o.centre) - v(dyad.centre)).norm() <= t.centre + accuracy.centre
                && (v(o.circle) - v(dyad.circle)).norm() <= t.circle + accuracy.circle
        });
        // A dyad a million times longer than the poses' extent is a slider's dyad (the
        // bisectors meeting at infinity) found only to rounding: not kept.
        let finite_dyad = dyad.length() <= 1e6 * extent;
        if dyad.misfit(given) <= 1e-9 * scale && !duplicate && finite_dyad {
            out.push((dyad, accuracy));
        }
    }
    let out: Vec<Dyad> = out.into_iter().map(|(d, _)| d).collect();
    // The rank-≤2 locus has at most four finite points (`burmester_resultant`); more means
    // the equations share a piece (for example poses that all turn about one point): a
    // continuum of dyads, not a finite answer.
    if out.len() > 4 {
        return Err(Error::NoMechanism {
            method: "Burmester's points",
            problem: format!(
                "the five poses are degenerate: {} distinct dyads fit them (at most four in \
                 general position), so the centre-point curves share a piece",
                out.len()
            ),
        });
    }
    Ok(out)
}
