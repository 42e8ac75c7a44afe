//! Burmester's points of five poses some of which nearly coincide: the search walks the
//! centre-point curve in the crank's turn to the second pose, so a second pose next to the
//! first crowds the whole curve into a sliver of its parameter. The poses are taken in the
//! order that spreads them best; the known four-bar must come back all the same.

use super::*;
use nalgebra::{Matrix2, Matrix4, Vector2};
use std::f64::consts::TAU;
use tmm::synthesis::{burmester_points, Dyad, Pose};

/// A pivot's allowed miss, m, for the dyad (centre point O, circle point A in pose 1) of
/// `poses` (derivation): the dyad solves g_j = |D_j(A) − O|² − |A − O|² = 0 (j = 2..5), and
/// rounding the poses (about 10 ulps each: the poses come from a hinge solve of about ten
/// operations) moves each g_j by up to 10ε·L·2L (∂g/∂P_j = 2(D_j − O), |D_j − O| ≤ L, the
/// size), so the root moves by up to |J⁻¹|·2·20εL² over the four rows, J the 4×4 Jacobian
/// of g in (O, A). Its smallest singular value carries the whole conditioning: poses a gap g
/// apart make two rows differ by O(g) (σ ~ g: the miss grows as ε/g), three within g make
/// it O(g²), two Burmester points about to merge make it small too. 25 to spare: 10³εL²/σ.
/// A pivot the search loses misses by 10⁻² or more.
pub(super) fn allowed_miss(poses: &[Pose; 5], own: &Dyad, size: f64) -> f64 {
    let (o, a) = (
        Vector2::new(own.centre[0], own.centre[1]),
        Vector2::new(own.circle[0], own.circle[1]),
    );
    let p1 = Vector2::new(poses[0].at[0], poses[0].at[1]);
    let mut jac = Matrix4::<f64>::zeros();
    for j in 1..5 {
        let (s, c) = (poses[j].angle - poses[0].angle).sin_cos();
        let turn = Matrix2::new(c, -s, s, c);
        let dj = Vector2::new(poses[j].at[0], poses[j].at[1]) + turn * (a - p1);
        let go = 2.0 * (a - o) - 2.0 * (dj - o);
        let ga = 2.0 * turn.transpose() * (dj - o) - 2.0 * (a - o);
        jac.row_mut(j - 1)
            .copy_from_slice(&[go.x, go.y, ga.x, ga.y]);
    }
    let sigma = jac.singular_values().min();
    1e3 * f64::EPSILON * size * size / sigma
}

/// The number of cases: `TMM_SYNTH_CASES` × 40 (CI's release sweep sets 100), at least
/// `least`.
pub(super) fn cases(least: usize) -> usize {
    std::env::var("TMM_SYNTH_CASES")
        .ok()
        .and_then(|s| s.parse::<usize>().ok())
        .map_or(least, |n| (40 * n).max(least))
}

/// Checks the points of five poses of the four-bar (frame d on the x axis from the origin,
/// crank a, coupler b, rocker c, mode σ) at the crank angles `phis` whose coupler point is
/// `along` of AB from A and `off` to its left (in units of b): at most four points, each
/// fits the five poses, both of the four-bar's dyads among them within [`allowed_miss`].
/// Returns (the worst pivot miss over its allowance, the number of points).
#[allow(clippy::too_many_arguments)]
fn recovered(
    (d, a, b, c): (f64, f64, f64, f64),
    sigma: f64,
    (along, off): (f64, f64),
    phis: &[f64; 5],
) -> (f64, usize) {
    let pose_of = |phi: f64| {
        let (pa, pb) = hinges(d, a, b, c, sigma, phi).unwrap();
        let (ux, uy) = ((pb[0] - pa[0]) / b, (pb[1] - pa[1]) / b);
        Pose::new(
            [
                pa[0] + along * b * ux - off * b * uy,
                pa[1] + along * b * uy + off * b * ux,
            ],
            uy.atan2(ux),
        )
    };
    let poses: [Pose; 5] = std::array::from_fn(|k| pose_of(phis[k]));
    let gap = phis
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let points = burmester_points(&poses)
        .unwrap_or_else(|e| panic!("{e}; crank angles {phis:?} (gap {gap:e}); poses {poses:?}"));
    assert!(points.len() <= 4, "{points:?}");
    let extent = poses
        .iter()
        .map(|p| dist(p.at, poses[0].at))
        .fold(0.0, f64::max);
    for p in &points {
        assert!(p.misfit(&poses) <= 1e-9 * (extent + p.length()), "{p:?}");
    }
    let size = d.max(b).max(c).max(extent);
    let (a1, b1) = hinges(d, a, b, c, sigma, phis[0]).unwrap();
    let mut worst: f64 = 0.0;
    for own in [
        Dyad {
            centre: [0.0, 0.0],
            circle: a1,
        },
        Dyad {
            centre: [d, 0.0],
            circle: b1,
        },
    ] {
        let miss = points
            .iter()
            .map(|p| dist(p.centre, own.centre).max(dist(p.circle, own.circle)))
            .fold(f64::INFINITY, f64::min);
        let allowed = allowed_miss(&poses, &own, size);
        assert!(
            miss <= allowed,
            "{own:?} missed by {miss:e} (allowed {allowed:e}) among {points:?}; crank angles \
             {phis:?} (gap {gap:e}); poses {poses:?}"
        );
        worst = worst.max(miss / allowed);
    }
    (worst, points.len())
}

/// Five poses of random crank-rockers at crank angles drawn uniformly and sorted over a
/// spread of 0.8–4.5 rad, one of them moved 10⁻⁴…10⁻² rad from another (others may fall
/// close by chance: the allowance follows every gap): both of the four-bar's dyads are among
/// the points (to [`allowed_miss`], derived from the gaps' conditioning), every point fits the five poses,
/// and there are never more than four.
#[test]
fn a_four_bar_comes_back_from_poses_that_nearly_coincide() {
    let mut next = xorshift(0x2545_F491_4F6C_DD1D);
    let (mut done, mut closest, mut worst) = (0usize, f64::INFINITY, 0.0f64);
    let total = cases(150);
    while done < total {
        let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
        let (d, a, b, c) = (r(0.3, 0.6), r(0.05, 0.12), r(0.3, 0.6), r(0.25, 0.6));
        let sigma = if r(0.0, 1.0) < 0.5 { 1.0 } else { -1.0 };
        let (along, off, start, spread) = (r(0.2, 0.8), r(-0.2, 0.2), r(0.0, 6.0), r(0.8, 4.5));
        let mut phis: Vec<f64> = (0..5).map(|_| start + spread * r(0.0, 1.0)).collect();
        // And one pair 10⁻⁴…10⁻² rad apart for sure.
        let (k, near) = ((r(0.0, 4.0) as usize).min(3), 10f64.powf(r(-4.0, -2.0)));
        phis[k + 1] = phis[k] + near;
        if grashof(d, a, b, c).unwrap() != Grashof::CrankRocker {
            continue;
        }
        phis.sort_by(f64::total_cmp);
        let phis: [f64; 5] = phis.try_into().unwrap();
        let gap = phis
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        // Poses a millionth of a radian apart are one pose to the accuracy asked.
        if gap < 1e-6 {
            continue;
        }
        // The coupler point's offsets were drawn in metres on links of 0.3–0.6 m.
        let (w, _) = recovered((d, a, b, c), sigma, (along, off / b), &phis);
        worst = worst.max(w);
        closest = closest.min(gap);
        done += 1;
    }
    eprintln!(
        "Burmester, near poses: {done} four-bars recovered (closest crank gap {closest:.1e} \
         rad), worst pivot miss {worst:.1e} of its allowance"
    );
}

/// The reviewer's check: 400 random crank-rockers (frame 1, crank 0.1–0.6, coupler and
/// rocker 0.4–1.6, the coupler point anywhere within half a coupler of A), four crank angles
/// stratified over a spread of 0.8–4.5 rad and a fifth 10⁻⁶…10⁻² rad (log-uniform) from one
/// of them: the known four-bar is found every time.
#[test]
fn every_known_four_bar_is_found_with_two_poses_close_together() {
    let mut next = xorshift(0xB0B0_5EED_0000_0001);
    let (mut done, mut worst, mut most) = (0usize, 0.0f64, 0usize);
    let total = cases(400);
    while done < total {
        let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
        let (a, b, c) = (r(0.1, 0.6), r(0.4, 1.6), r(0.4, 1.6));
        let sigma = if r(0.0, 1.0) < 0.5 { 1.0 } else { -1.0 };
        let (along, off) = (r(-0.5, 0.5), r(-0.5, 0.5));
        let (start, spread) = (r(0.0, TAU), r(0.8, 4.5));
        let mut phis: Vec<f64> = (0..4)
            .map(|i| start + spread * (i as f64 + r(0.15, 0.85)) / 4.0)
            .collect();
        let (k, near) = ((r(0.0, 4.0) as usize).min(3), 10f64.powf(r(-6.0, -2.0)));
        phis.push(phis[k] + near);
        if grashof(1.0, a, b, c).unwrap() != Grashof::CrankRocker {
            continue;
        }
        phis.sort_by(f64::total_cmp);
        let phis: [f64; 5] = phis.try_into().unwrap();
        let (w, n) = recovered((1.0, a, b, c), sigma, (along, off), &phis);
        (worst, most) = (worst.max(w), most.max(n));
        done += 1;
    }
    eprintln!(
        "Burmester, reviewer's check: {done} four-bars found, worst pivot miss {worst:.1e} of \
         its allowance, at most {most} points"
    );
}

/// Five poses of a body turning about one fixed point: every coupler point keeps its
/// distance from that point, so every one is a circle point: refused, naming the point
/// (not an empty list of Burmester's points).
#[test]
fn poses_turning_about_one_point_are_refused_naming_it() {
    let (cx, cy) = (0.3, -0.2);
    let pose = |t: f64| {
        let (s, c) = t.sin_cos();
        let (x, y) = (0.5 - cx, 0.1 - cy);
        Pose::new([cx + c * x - s * y, cy + s * x + c * y], 0.4 + t)
    };
    let poses = [0.0, 0.3, 0.7, 1.2, 1.9].map(pose);
    let e = burmester_points(&poses).unwrap_err().to_string();
    assert!(
        e.contains("turn about one point") && e.contains("3.000000e-1"),
        "{e}"
    );
}
