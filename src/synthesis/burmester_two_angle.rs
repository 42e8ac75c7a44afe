//! Burmester's points of five poses with only two distinct angles, in closed form: there
//! every pair of 3×3 minors of the pencil shares a factor (the edges between poses of one
//! angle are translations), so the elimination of `burmester_resultant` degenerates.
//!
//! Derivation. Let the poses of angle α be the set 𝒜, those of angle β the set ℬ, and a0 one
//! pose of 𝒜. Name a coupler point by z, where it is in pose a0. In a pose a of 𝒜 the coupler
//! is only translated: the point is at z + (P_a − P_a0). In a pose b of ℬ it is at
//! P_b + R(z − P_a0) (R the turn β − α). A dyad's centre point G is at one distance ρ from all
//! five positions.
//! - |𝒜| ≥ 3: the translates z + (P_a − P_a0) lie on one circle only if the points P_a do, and
//!   then G − z = c − P_a0 (c their circle's centre) and ρ its radius. Each pose b of ℬ then
//!   asks |P_b − c + (R − I)(z − P_a0)| = ρ: with w = (R − I)(z − P_a0) (R − I invertible for
//!   β ≠ α), w lies on the circle of radius ρ about c − P_b. Two poses in ℬ: two circles,
//!   two points w or none (concentric circles: P_b equal, coinciding poses, refused before);
//!   one pose in ℬ: a whole circle of w, a continuum of dyads.
//! - |𝒜| and |ℬ| are 3 and 2 up to naming, so swapping the names covers every split but
//!   4 + 1 (a continuum or nothing) and 5 + 0 (a translation, handled as dependent rows).

use super::burmester::{Dyad, Pose};
use crate::error::{Error, Result};
use nalgebra::{Matrix2, Vector2};

type V = Vector2<f64>;

fn v(p: [f64; 2]) -> V {
    V::new(p[0], p[1])
}

/// The two angles' groups when the poses have exactly two distinct angles (turns that are
/// whole turns apart are one angle: sin of half the difference below 10⁻¹²), the larger
/// group first; `None` otherwise.
fn groups(poses: &[Pose; 5]) -> Option<(Vec<usize>, Vec<usize>)> {
    let same = |i: usize, j: usize| (0.5 * (poses[i].angle - poses[j].angle)).sin().abs() <= 1e-12;
    let first: Vec<usize> = (0..5).filter(|&j| same(0, j)).collect();
    let rest: Vec<usize> = (0..5).filter(|&j| !same(0, j)).collect();
    if rest.is_empty() || !rest.iter().all(|&j| same(rest[0], j)) {
        return None;
    }
    Some(if first.len() >= rest.len() {
        (first, rest)
    } else {
        (rest, first)
    })
}

/// The circle through three points: (centre, radius); `None` when they are collinear.
fn circle(p: V, q: V, r: V) -> Option<(V, f64)> {
    let (u, w) = (q - p, r - p);
    let det = 2.0 * (u.x * w.y - u.y * w.x);
    let (uu, ww) = (u.norm_squared(), w.norm_squared());
    let c = p + V::new(uu * w.y - ww * u.y, u.x * ww - w.x * uu) / det;
    let sine = det / (2.0 * u.norm() * w.norm());
    (sine.abs() > 1e-12 && c.iter().all(|x| x.is_finite())).then(|| (c, (c - p).norm()))
}

/// Burmester's points of five poses with two distinct angles (module docs): `None` when the
/// poses have not exactly two angles; the dyads (at most two) otherwise, or an error for a
/// continuum.
pub(super) fn points(poses: &[Pose; 5]) -> Option<Result<Vec<Dyad>>> {
    let (a, b) = groups(poses)?;
    let continuum = |why: &str| {
        Some(Err(Error::NoMechanism {
            method: "Burmester's points",
            problem: format!(
                "the five poses have two angles only, {} at one and {} at the other, and {why}: \
                 infinitely many dyads (a continuum, not a finite answer)",
                a.len(),
                b.len()
            ),
        }))
    };
    let p = |k: usize| v(poses[k].at);
    let a0 = a[0];
    // The 𝒜 points on one circle, or no dyad at all (for four of them: all on the circle
    // through the first three, to the rounding of its radius).
    let Some((c, rho)) = circle(p(a[0]), p(a[1]), p(a[2])) else {
        return Some(Ok(Vec::new()));
    };
    if a[3..]
        .iter()
        .any(|&k| ((p(k) - c).norm() - rho).abs() > 1e-12 * (rho + (c - p(a0)).norm()))
    {
        return Some(Ok(Vec::new()));
    }
    if b.len() == 1 {
        return continuum("the first group's points lie on one circle");
    }
    let (m1, m2) = (c - p(b[0]), c - p(b[1]));
    let e = (m2 - m1).norm();
    let along = 0.5 * e;
    let h2 = rho * rho - along * along;
    // NaN fails both comparisons: no dyad then either.
    if h2.is_nan() || h2 < 0.0 || e.is_nan() || e <= 0.0 {
        return Some(Ok(Vec::new()));
    }
    let unit = (m2 - m1) / e;
    let normal = V::new(-unit.y, unit.x);
    let turn = poses[b[0]].angle - poses[a0].angle;
    let (s, co) = turn.sin_cos();
    // R − I without cancellation (cos δ − 1 = −2 sin²(δ/2)).
    let half = (0.5 * turn).sin();
    let rmi = Matrix2::new(-2.0 * half * half, -s, s, -2.0 * half * half);
    let inverse = rmi.try_inverse()?;
    let rotation = Matrix2::new(co, -s, s, co);
    let mut out = Vec::new();
    let signs: &[f64] = if h2 == 0.0 { &[1.0] } else { &[1.0, -1.0] };
    for &sign in signs {
        let w = m1 + along * unit + sign * h2.sqrt() * normal;
        let z = p(a0) + inverse * w;
        let centre = z + c - p(a0);
        // The circle point where it is in the first pose.
        let circle = if a.contains(&0) {
            z + (p(0) - p(a0))
        } else {
            p(0) + rotation * (z - p(a0))
        };
        if centre.iter().chain(circle.iter()).all(|x| x.is_finite()) {
            out.push(Dyad {
                centre: [centre.x, centre.y],
                circle: [circle.x, circle.y],
            });
        }
    }
    Some(Ok(out))
}
