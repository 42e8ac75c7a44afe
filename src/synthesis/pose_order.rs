#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > y)` rejects NaN too, on purpose.
//! Conditioning of the scan for Burmester's points: which pose to take as the reference and
//! which as the curve's parameter (the polish of each point is in `pose_newton`); and the
//! refusal of poses that all turn about one point (for the count as well).
//!
//! The scan [`burmester_points_by_scan`](super::burmester_points_by_scan) walks the centre-point curve
//! of poses 1–4 in the crank's turn β2 from pose 1 to pose 2 and tests pose 5. When pose 2
//! nearly coincides with pose 1, every dyad turns by nearly the same small β2 between them,
//! so the whole curve is crowded into a sliver of the parameter that a grid over the turn
//! steps across; and a pair of near poses among the first four makes the standard form's
//! determinants small. A near pair costs least as pose 5, whose test only scales with the
//! gap. The answer does not depend on the order (a dyad fits the poses or not), only the
//! circle point is named in the first given pose, so the search may take the poses in the
//! order that spreads them best and carry each circle point back.

use super::burmester::{displace, v, Dyad, Pose};
use crate::error::{Error, Result};
use nalgebra::Vector2;

type V = Vector2<f64>;

/// How far apart two poses are, m: the distance of their points plus the arc their turn
/// sweeps at the poses' radius `r` (two poses at one place but turned are apart too).
fn gap(p: &Pose, q: &Pose, r: f64) -> f64 {
    (v(p.at) - v(q.at)).norm() + r * (2.0 * (0.5 * (p.angle - q.angle)).sin()).abs()
}

/// The order in which to search five poses: pose 5 the one whose absence leaves the other
/// four farthest apart (their closest pair as far as it can be), and of those four the
/// farthest pair first (reference and parameter), the other two in their given order.
pub(super) fn spread_order(poses: &[Pose; 5]) -> [usize; 5] {
    let centre = poses.iter().map(|p| v(p.at)).sum::<V>() / 5.0;
    let r = poses
        .iter()
        .map(|p| (v(p.at) - centre).norm())
        .fold(0.0, f64::max);
    let closest = |skip: usize| {
        let mut m = f64::INFINITY;
        for i in (0..5).filter(|&i| i != skip) {
            for j in (i + 1..5).filter(|&j| j != skip) {
                m = m.min(gap(&poses[i], &poses[j], r));
            }
        }
        m
    };
    // The first of equals wins, so that well spread poses keep their given order.
    let mut last = 4;
    for k in (0..4).rev() {
        if closest(k) > closest(last) {
            last = k;
        }
    }
    let four: Vec<usize> = (0..5).filter(|&i| i != last).collect();
    let (mut a, mut b, mut far) = (four[0], four[1], -1.0);
    for (x, &i) in four.iter().enumerate() {
        for &j in &four[x + 1..] {
            let g = gap(&poses[i], &poses[j], r);
            if g > far {
                (a, b, far) = (i, j, g);
            }
        }
    }
    let rest: Vec<usize> = four.into_iter().filter(|&i| i != a && i != b).collect();
    [a, b, rest[0], rest[1], last]
}

/// A dyad found with the poses taken from `first` carried to the given poses' first: its
/// circle point is the coupler point it names in `first`.
pub(super) fn renamed(dyad: Dyad, first: &Pose, poses: &[Pose; 5]) -> Dyad {
    Dyad {
        centre: dyad.centre,
        circle: xy(displace(first, &poses[0], v(dyad.circle))),
    }
}

fn xy(p: V) -> [f64; 2] {
    [p.x, p.y]
}

/// Refuses five poses that all turn about one point: the displacement from pose 1 to pose j
/// (a turn α_j ≠ 0) leaves one point fixed, its pole z_j = (P_j − e^{iα_j}·P_1)/(1 − e^{iα_j})
/// (complex numbers); when the four poles coincide, every coupler point moves on a circle
/// about that point and every one of them is a circle point: no finite set of dyads.
pub(super) fn not_about_one_point(poses: &[Pose; 5]) -> Result<()> {
    type C = nalgebra::Complex<f64>;
    let c = |p: [f64; 2]| C::new(p[0], p[1]);
    let p1 = c(poses[0].at);
    let size = poses
        .iter()
        .map(|p| (c(p.at) - p1).norm())
        .fold(0.0, f64::max);
    let mut poles = Vec::with_capacity(4);
    for p in &poses[1..] {
        let turn = C::from_polar(1.0, p.angle - poses[0].angle);
        let denominator = C::new(1.0, 0.0) - turn;
        // A translation has its pole at infinity: the poses do not turn about one point.
        if !(denominator.norm() > 1e-9) {
            return Ok(());
        }
        poles.push((c(p.at) - turn * p1) / denominator);
    }
    let first = poles[0];
    let spread = poles.iter().map(|z| (z - first).norm()).fold(0.0, f64::max);
    if spread <= 1e-9 * (size + (first - p1).norm()) {
        return Err(Error::NoMechanism {
            method: "Burmester's points",
            problem: format!(
                "the five poses all turn about one point ({:.6e}, {:.6e}): every coupler \
                 point keeps its distance from it, so every one is a circle point (a \
                 continuum of dyads, not a finite answer)",
                first.re, first.im
            ),
        });
    }
    Ok(())
}
