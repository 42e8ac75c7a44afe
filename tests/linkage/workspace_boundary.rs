//! The five-bar's workspace outline located to the last digits, against closed-form inverse
//! kinematics (`FiveBar::reaches`, independent of the engine): every outline point on a
//! serial curve has reached and unreached points within 10⁻⁹ of the linkage's size (those
//! on the image of the couplers in line, where the engine refuses the rates within rounding
//! of the dyad's dead point, within 2·10⁻⁵ of it), and the area inside the
//! outline equals the reach's area by an independent row-by-row solve (each row's reach
//! intervals bisected on the inverse kinematics) to 10⁻³ at the default resolution, and
//! closer at a finer one.

use super::two_inputs::{wide_five_bar, FiveBar};
use tmm::linkage::{bundled, Linkage, Plan, Workspace, WorkspaceOptions};
use tmm::nalgebra::{Point2, Vector2};

/// The area `five` reaches inside the box [lo, hi], by rows: at each of `rows` heights (the
/// midpoint rule), the reach's intervals along x, each end bisected between `cols` samples.
fn reach_area(five: &FiveBar, lo: Point2<f64>, hi: Point2<f64>, rows: usize, cols: usize) -> f64 {
    let dy = (hi.y - lo.y) / rows as f64;
    let dx = (hi.x - lo.x) / cols as f64;
    let mut area = 0.0;
    for r in 0..rows {
        let y = lo.y + (r as f64 + 0.5) * dy;
        let reach = |x: f64| five.reaches(Point2::new(x, y));
        // The exact end between x0 and x1 (where reach differs), bisected.
        let end = |mut a: f64, mut b: f64| {
            let ra = reach(a);
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                if m == a || m == b {
                    break;
                }
                if reach(m) == ra {
                    a = m;
                } else {
                    b = m;
                }
            }
            0.5 * (a + b)
        };
        let mut inside_from = None;
        let mut prev = reach(lo.x);
        assert!(!prev, "the box holds the reach");
        for c in 1..=cols {
            let x = lo.x + c as f64 * dx;
            let now = reach(x);
            if now != prev {
                let e = end(x - dx, x);
                match inside_from.take() {
                    None => inside_from = Some(e),
                    Some(s) => area += (e - s) * dy,
                }
            }
            prev = now;
        }
        assert!(inside_from.is_none() && !prev, "the box holds the reach");
    }
    area
}

/// Whether `p` has points reached and points not reached within `r` of it (64 directions,
/// and the point itself).
fn edge_within(five: &FiveBar, p: Point2<f64>, r: f64) -> bool {
    let mut any = [false; 2];
    any[usize::from(five.reaches(p))] = true;
    for k in 0..64 {
        let t = std::f64::consts::TAU * f64::from(k) / 64.0;
        any[usize::from(five.reaches(p + r * Vector2::new(t.cos(), t.sin())))] = true;
    }
    any[0] && any[1]
}

/// The outline points of `ws` against the edge of the reach: every point on a serial
/// curve (a leg stretched or folded, |OB| = l1 ± l2 or |DB| = l4 ± l3 to 10⁻⁶ of the size)
/// has the edge within `1e-9·size`; every other point (on the image of the couplers in
/// line, where the linkage stops assembling) within `assembly·size`. Returns (points, those
/// off the serial curves, the largest distance to the edge of those, by doubling).
fn on_the_edge(five: &FiveBar, ws: &Workspace, size: f64, assembly: f64) -> (usize, usize, f64) {
    let l = five.l;
    let (mut n, mut off, mut worst) = (0, 0, 0.0f64);
    for line in &ws.boundary {
        for &p in line {
            n += 1;
            if edge_within(five, p, 1e-9 * size) {
                continue;
            }
            let (ob, db) = ((p - five.o).norm(), (p - five.d).norm());
            let serial = [
                ob - (l[0] + l[1]),
                ob - (l[1] - l[0]).abs(),
                db - (l[2] + l[3]),
                db - (l[2] - l[3]).abs(),
            ]
            .iter()
            .any(|x| x.abs() <= 1e-6 * size);
            assert!(
                !serial,
                "{p}: on a serial curve, no edge of the reach within 1e-9 of the size"
            );
            let mut r = 1e-9 * size;
            while !edge_within(five, p, r) && r < size {
                r *= 2.0;
            }
            assert!(
                r <= assembly * size,
                "{p}: the edge of the reach is {r:e} m away"
            );
            off += 1;
            worst = worst.max(r);
        }
    }
    (n, off, worst)
}

fn check(linkage: &Linkage, resolution: usize, area_tol: f64) {
    let plan = Plan::new(linkage).unwrap();
    let ws = plan
        .workspace(
            "B",
            &WorkspaceOptions::default().with_resolution(resolution),
        )
        .unwrap();
    let five = FiveBar::of(linkage);
    let size = plan.size();
    let (n, off, worst) = on_the_edge(&five, &ws, size, 2e-5);
    assert!(n > 200, "{n}");
    let r = &ws.region;
    let lo = r.origin;
    let hi = r.origin + Vector2::new(r.nx as f64, r.ny as f64) * r.cell;
    let exact = reach_area(&five, lo, hi, 4000, 2000);
    let outline = ws.area();
    let raster = r.area();
    let rel = (outline - exact).abs() / exact;
    println!(
        "{} at resolution {resolution}: {n} outline points, all on the serial curves within \
         1e-9 of the size of the edge of the reach, {off} on the assembly curve within \
         {worst:.1e} m of it; area inside the outline {outline:.9e}, independent {exact:.9e} \
         (relative {rel:.2e}); raster cells {raster:.6e} ({:+.2e})",
        linkage.name,
        (raster - exact) / exact
    );
    assert!(rel < area_tol, "{rel:e}");
}

#[test]
fn the_five_bar_outline_lies_on_the_edge_of_the_reach_and_its_area_is_the_reachs() {
    check(&bundled::five_bar_robot(), 240, 1e-3);
}

#[test]
fn a_five_bar_that_stops_assembling_has_its_outline_on_the_edge_too() {
    check(&wide_five_bar(), 240, 1e-3);
}

#[test]
fn a_finer_raster_gives_the_area_closer() {
    check(&bundled::five_bar_robot(), 600, 2e-4);
}
