//! Burmester's points where the elimination degenerates: poses whose two cubics (3×3 minors
//! of the pencil) share a component, so that the resultant vanishes identically, and poses
//! whose equations are dependent. Each is checked against a closed form of its own.

use super::*;
use tmm::synthesis::{burmester_points, Dyad, Pose};

/// The circumcentre of three points (perpendicular bisectors' intersection, Cramer).
fn circumcentre(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> [f64; 2] {
    let (u, w) = ([q[0] - p[0], q[1] - p[1]], [r[0] - p[0], r[1] - p[1]]);
    let det = 2.0 * (u[0] * w[1] - u[1] * w[0]);
    let (uu, ww) = (u[0] * u[0] + u[1] * u[1], w[0] * w[0] + w[1] * w[1]);
    [
        p[0] + (uu * w[1] - ww * u[1]) / det,
        p[1] + (u[0] * ww - w[0] * uu) / det,
    ]
}

/// The dyads of five poses with two angles only, by hand (derivation): poses 1, 3, 5 at the
/// angle α and 2, 4 at β. Among 1, 3, 5 the coupler only translates, so the circle point's
/// positions are u + (P_k − P1), and the centre point is G = u + c − P1 (c the circumcentre of
/// P1, P3, P5), the radius ρ = |c − P1|. In poses 2 and 4 the circle point is at
/// P_k + R(u − P1) (R the turn β − α), so |P_k − c + (R − I)(u − P1)| = ρ: w = (R − I)(u − P1)
/// lies on the circles of radius ρ about c − P2 and c − P4 — two points, one or none. Then
/// u = P1 + (R − I)⁻¹w.
fn two_angle_dyads(p: &[[f64; 2]; 5], beta: f64, alpha: f64) -> Vec<Dyad> {
    let c = circumcentre(p[0], p[2], p[4]);
    let rho = dist(c, p[0]);
    let (m2, m4) = (
        [c[0] - p[1][0], c[1] - p[1][1]],
        [c[0] - p[3][0], c[1] - p[3][1]],
    );
    let e = dist(m2, m4);
    let along = 0.5 * e;
    let h2 = rho * rho - along * along;
    if h2 < 0.0 {
        return Vec::new();
    }
    let (ux, uy) = ((m4[0] - m2[0]) / e, (m4[1] - m2[1]) / e);
    let mut out = Vec::new();
    for s in [1.0, -1.0] {
        let h = s * h2.sqrt();
        let w = [m2[0] + along * ux - h * uy, m2[1] + along * uy + h * ux];
        // (R − I)⁻¹: R − I = [[c − 1, −s], [s, c − 1]], det = 2 − 2c.
        let (sn, cs) = (beta - alpha).sin_cos();
        let det = (cs - 1.0) * (cs - 1.0) + sn * sn;
        let r = [
            ((cs - 1.0) * w[0] + sn * w[1]) / det,
            (-sn * w[0] + (cs - 1.0) * w[1]) / det,
        ];
        let u = [p[0][0] + r[0], p[0][1] + r[1]];
        out.push(Dyad {
            centre: [u[0] + c[0] - p[0][0], u[1] + c[1] - p[0][1]],
            circle: u,
        });
    }
    out
}

/// Five poses with two angles only: every pair of minors has a resultant that vanishes
/// identically (10⁻⁵ of its rounding noise or less, in both directions; session 12's code
/// tried the roots of that rounding and kept whatever they polished to). The answer matches
/// the closed form above, both dyads to 10⁻⁹ of the poses' size and nothing else, and every
/// returned dyad fits the five poses evaluated directly (its length in each).
#[test]
fn two_angle_poses() {
    let mut next = xorshift(0x7A0A_4E11_5EED_0023);
    let (mut cases, mut worst) = (0, 0.0f64);
    for _ in 0..40 {
        let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
        let p: [[f64; 2]; 5] = std::array::from_fn(|_| [r(-0.5, 0.5), r(-0.5, 0.5)]);
        let (alpha, beta) = (r(-3.0, 3.0), r(-3.0, 3.0));
        if (0.5 * (beta - alpha)).sin().abs() < 0.1 {
            continue;
        }
        let angles = [alpha, beta, alpha, beta, alpha];
        let poses: [Pose; 5] = std::array::from_fn(|k| Pose::new(p[k], angles[k]));
        let want = two_angle_dyads(&p, beta, alpha);
        for w in &want {
            assert!(w.misfit(&poses) <= 1e-12 * (1.0 + w.length()), "{w:?}");
        }
        let got = burmester_points(&poses).unwrap_or_else(|e| panic!("{e}: {poses:?}"));
        let size = p.iter().map(|q| dist(*q, p[0])).fold(0.0, f64::max);
        // Dyads longer than 10⁶ poses' sizes are not returned (sliders' by rounding).
        let want: Vec<Dyad> = want
            .into_iter()
            .filter(|d| d.length() <= 1e6 * size)
            .collect();
        assert_eq!(got.len(), want.len(), "{got:?} against {want:?}; {poses:?}");
        for g in &got {
            assert!(g.misfit(&poses) <= 1e-12 * (size + g.length()), "{g:?}");
        }
        for w in &want {
            let m = got
                .iter()
                .map(|g| dist(g.centre, w.centre).max(dist(g.circle, w.circle)))
                .fold(f64::INFINITY, f64::min);
            let scale = size + w.length() + dist(w.centre, p[0]);
            assert!(
                m <= 1e-9 * scale,
                "{w:?} missed by {m:e}: {got:?}; {poses:?}"
            );
            worst = worst.max(m / scale);
        }
        cases += 1;
    }
    assert!(cases >= 30, "{cases}");
    eprintln!("two-angle poses: {cases} sets, worst miss {worst:.1e} of the size");
}

/// A pure translation with the five points on one circle: every coupler point moves on a
/// circle of that radius (a parallelogram's dyads), infinitely many: an error that says so.
/// Off the circle no finite dyad fits (five translates of a point are on one circle only if
/// the points are): an empty answer.
#[test]
fn translations_on_a_circle_are_a_continuum_and_off_it_have_no_dyad() {
    let (cx, cy, radius) = (0.3, -0.1, 0.5);
    let on: [Pose; 5] = std::array::from_fn(|k| {
        let t = 1.3 * k as f64 + 0.1;
        Pose::new([cx + radius * t.cos(), cy + radius * t.sin()], 0.7)
    });
    let e = burmester_points(&on).unwrap_err().to_string();
    assert!(e.contains("infinitely many"), "{e}");
    let mut off = on;
    off[3].at[0] += 0.05;
    assert_eq!(burmester_points(&off).unwrap(), Vec::<Dyad>::new());
    // The same with the angle off by whole turns (θ + 2πk is the same pose).
    let turned: [Pose; 5] = std::array::from_fn(|k| {
        Pose::new(
            on[k].at,
            on[k].angle + std::f64::consts::TAU * (k as f64 - 2.0),
        )
    });
    let e = burmester_points(&turned).unwrap_err().to_string();
    assert!(e.contains("infinitely many"), "{e}");
}
