//! Burmester's points of five poses some of which nearly coincide: the search walks the
//! centre-point curve in the crank's turn to the second pose, so a second pose next to the
//! first crowds the whole curve into a sliver of its parameter. The poses are taken in the
//! order that spreads them best; the known four-bar must come back all the same.

use super::*;
use tmm::synthesis::{burmester_points, Dyad, Pose};

/// Five poses of random crank-rockers at crank angles drawn uniformly and sorted over a
/// spread of 0.8–4.5 rad, one of them moved 10⁻⁴…10⁻² rad from another: both of the
/// four-bar's dyads are among the points (to 1e-5 m on links of 0.05–0.6 m), every point fits
/// the five poses, and there are never more than four.
#[test]
#[ignore = "not yet: with a pair of poses 1e-4..1e-2 rad apart some cases still return extra near-duplicate points (6 'distinct' dyads at a gap of 5.8e-4) or miss a pivot by 1e-6; see CHANGELOG, session 10"]
fn a_four_bar_comes_back_from_poses_that_nearly_coincide() {
    let mut next = xorshift(0x2545_F491_4F6C_DD1D);
    let (mut cases, mut closest, mut worst) = (0usize, f64::INFINITY, 0.0f64);
    while cases < 150 {
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
        let gap = phis
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        // Poses a millionth of a radian apart are one pose to the accuracy asked.
        if gap < 1e-6 {
            continue;
        }
        let pose_of = |phi: f64| {
            let (pa, pb) = hinges(d, a, b, c, sigma, phi).unwrap();
            let (ux, uy) = ((pb[0] - pa[0]) / b, (pb[1] - pa[1]) / b);
            Pose::new(
                [
                    pa[0] + along * b * ux - off * uy,
                    pa[1] + along * b * uy + off * ux,
                ],
                uy.atan2(ux),
            )
        };
        let poses: [Pose; 5] = std::array::from_fn(|k| pose_of(phis[k]));
        let points = burmester_points(&poses, 2000)
            .unwrap_or_else(|e| panic!("{e}; crank gap {gap:e}; poses {poses:?}"));
        assert!(points.len() <= 4, "{points:?}");
        let extent = poses
            .iter()
            .map(|p| dist(p.at, poses[0].at))
            .fold(0.0, f64::max);
        for p in &points {
            assert!(p.misfit(&poses) <= 1e-9 * (extent + p.length()), "{p:?}");
        }
        let (a1, b1) = hinges(d, a, b, c, sigma, phis[0]).unwrap();
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
            // Two poses a gap g apart fix a point only to about ε/g² of the size (the five
            // equations are nearly four; the points fit the poses to rounding all the same):
            // 1.1e-6 m seen at a gap of 3.2e-4 rad; a point lost (as before the poses were
            // reordered) misses by 10⁻² or more.
            assert!(
                miss < 1e-5,
                "{own:?} missed by {miss:e} among {points:?}; crank gap {gap:e}; poses {poses:?}"
            );
            worst = worst.max(miss);
        }
        closest = closest.min(gap);
        cases += 1;
    }
    eprintln!(
        "Burmester, near poses: {cases} four-bars recovered (closest crank gap {closest:.1e} \
         rad), worst pivot {worst:.1e} m"
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
    let e = burmester_points(&poses, 2000).unwrap_err().to_string();
    assert!(
        e.contains("turn about one point") && e.contains("3.000000e-1"),
        "{e}"
    );
}
