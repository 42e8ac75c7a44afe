#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > y)` rejects NaN too, on purpose.
//! Conditioning of Burmester's points: which pose to take as the reference and which as the
//! curve's parameter, and a Newton polish of each point on the five poses' own equations.
//!
//! The search of [`burmester_points`](super::burmester_points) walks the centre-point curve
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
use nalgebra::{Matrix4, Vector2, Vector4};

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

/// The residuals g_j = |D_j(A) − O|² − |A − O|² (j = 2..5) of a dyad with centre point O and
/// circle point A (in pose 1), and their Jacobian in (O, A): ∂g/∂O = 2(A − O) − 2(D_j − O),
/// ∂g/∂A = 2R_jᵀ(D_j − O) − 2(A − O), R_j the coupler's turn from pose 1 to pose j.
fn equations(poses: &[Pose; 5], o: V, a: V) -> (Vector4<f64>, Matrix4<f64>) {
    let (mut g, mut jac) = (Vector4::zeros(), Matrix4::zeros());
    let e = a - o;
    for j in 1..5 {
        let d = displace(&poses[0], &poses[j], a) - o;
        let (s, c) = (poses[j].angle - poses[0].angle).sin_cos();
        // R_jᵀ d.
        let rt = V::new(c * d.x + s * d.y, -s * d.x + c * d.y);
        g[j - 1] = d.norm_squared() - e.norm_squared();
        let (go, ga) = (2.0 * (e - d), 2.0 * (rt - e));
        jac.row_mut(j - 1)
            .copy_from_slice(&[go.x, go.y, ga.x, ga.y]);
    }
    (g, jac)
}

/// The dyad polished by Newton's method on the five poses' equations, from the point the
/// search found: each step kept only while it lowers the largest misfit, so a point the
/// equations cannot improve (a singular Jacobian, rounding reached) comes back as it was.
pub(super) fn polished(dyad: Dyad, poses: &[Pose; 5]) -> Dyad {
    let mut best = dyad;
    let mut misfit = best.misfit(poses);
    for _ in 0..8 {
        let (o, a) = (v(best.centre), v(best.circle));
        let (g, jac) = equations(poses, o, a);
        let Some(step) = jac.lu().solve(&(-g)) else {
            break;
        };
        let next = Dyad {
            centre: [o.x + step[0], o.y + step[1]],
            circle: [a.x + step[2], a.y + step[3]],
        };
        let m = next.misfit(poses);
        if !(m < misfit)
            || next
                .centre
                .iter()
                .chain(&next.circle)
                .any(|x| !x.is_finite())
        {
            break;
        }
        (best, misfit) = (next, m);
    }
    best
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
