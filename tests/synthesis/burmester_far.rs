//! Burmester's points far outside the poses and close together: a four-bar whose crank and
//! rocker are both 100 m long, their frame pivots 3 cm (or 1 cm) apart, carrying a coupler
//! whose poses span a few metres. Its two dyads are two distinct Burmester points about a
//! hundred pose-sizes away, a few centimetres apart; session 12's merge tolerance
//! (2¹⁰εM/σ, M the rows' largest magnitude) was 1.5–1.9 m there and merged them into one.
//! Each point's accuracy is now derived from its own Jacobian (`pose_newton`), a few 10⁻² m
//! at most, and both are kept.

use super::*;
use tmm::synthesis::{burmester_points, Dyad, Pose};

/// The poses of the four-bar O1 = (0, −r), A = (0, 0), B = b, O3 = (w, −r) with the crank
/// turned by `turns` (the coupler's point P = A, its angle that of AB), formed without
/// cancellation (the rounding of each pose a few ulps: the points are ill-conditioned, 10⁻¹⁰
/// of amplification, and a pose off by 10⁻¹³ moves them by centimetres):
/// A = (r sin φ, −2r sin²(φ/2)); B = A + |AB|·(cos ψ, sin ψ) with |B − O3| = |b − O3|, i.e.
/// 2|AB|·q·u(ψ) = −(|q|² − c² + |AB|²), q = A − O3, where |q|² − c² is formed as products of
/// differences ((A − b)·(q + b − O3)).
fn poses(r: f64, w: f64, b: [f64; 2], turns: [f64; 5]) -> [Pose; 5] {
    let lab = b[0].hypot(b[1]);
    let psi0 = b[1].atan2(b[0]);
    turns.map(|phi| {
        let h = (0.5 * phi).sin();
        let a = [r * phi.sin(), -2.0 * r * h * h];
        let q = [a[0] - w, a[1] + r];
        let diff = (a[0] - b[0]) * (q[0] + (b[0] - w)) + (a[1] - b[1]) * (q[1] + (b[1] + r));
        let cosine = -(diff + lab * lab) / (2.0 * lab * q[0].hypot(q[1]));
        let (alpha, spread) = (q[1].atan2(q[0]), cosine.clamp(-1.0, 1.0).acos());
        // The branch of B that starts at b.
        let near = |x: f64| (0.5 * (x - psi0)).sin().abs();
        let psi = if near(alpha + spread) < near(alpha - spread) {
            alpha + spread
        } else {
            alpha - spread
        };
        Pose::new(a, psi)
    })
}

#[test]
fn two_far_points_close_together_are_both_kept() {
    // (crank and rocker length r, frame pivots w apart, B, the crank's arc over the poses).
    for (r, w, b, arc) in [
        (100.0, 0.03, [0.2, 0.05], 1.6),
        (100.0, 0.01, [0.05, 0.0125], 5.0),
    ] {
        let t = arc / 1.6 / r;
        let poses = poses(r, w, b, [0.0, 0.3 * t, 0.7 * t, 1.2 * t, 1.6 * t]);
        let extent = poses
            .iter()
            .map(|p| dist(p.at, poses[0].at))
            .fold(0.0, f64::max);
        let own = [
            Dyad {
                centre: [0.0, -r],
                circle: [0.0, 0.0],
            },
            Dyad {
                centre: [w, -r],
                circle: b,
            },
        ];
        // Each own dyad fits the poses as generated (to their rounding, amplified).
        for d in &own {
            assert!(
                d.misfit(&poses) < 1e-12 * r,
                "{d:?}: {:e}",
                d.misfit(&poses)
            );
        }
        let points = burmester_points(&poses).unwrap();
        assert!(points.len() <= 4, "{points:?}");
        // The two are apart by w (centres) and |b| (circles); each is found well within a tenth of
        // that, by a point of its own (not one point between them).
        let apart = w.min(b[0].hypot(b[1]));
        let nearest = |d: &Dyad| {
            points
                .iter()
                .enumerate()
                .map(|(k, p)| (k, dist(p.centre, d.centre).max(dist(p.circle, d.circle))))
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .unwrap()
        };
        let (k0, m0) = nearest(&own[0]);
        let (k1, m1) = nearest(&own[1]);
        assert!(
            k0 != k1 && m0 < 0.1 * apart && m1 < 0.1 * apart,
            "r {r} w {w}: the crank within {m0:e} (point {k0}), the rocker within {m1:e} \
             (point {k1}) of {points:?}"
        );
        eprintln!(
            "far pair r {r} m, w {w} m, poses {extent:.2} m: {} points, crank within {m0:.1e}, \
             rocker within {m1:.1e} (apart {apart})",
            points.len()
        );
    }
}
