//! The five-bar's workspace outline located to the last digits, against closed-form inverse
//! kinematics (`FiveBar::reaches`, independent of the engine): outline points have reached
//! and unreached points within 10⁻⁹ of the linkage's size (those on the image of the
//! couplers in line, where the position itself carries εL²/|AC| of rounding, within 2·10⁻⁵
//! of it — 3.6e-7 m measured; at most one in twenty left at the fill's own outline, within
//! two cells), and the area inside the outline equals the reach's area by an independent
//! row-by-row solve (each row's reach intervals bisected on the inverse kinematics) to 10⁻³
//! at the default resolution, and closer at a finer one (plus what the points left at the
//! fill's outline may move).

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

/// The outline points of `ws` against the edge of the reach (r the distance to it, found by
/// doubling from 10⁻⁹ of the size): `exact` within 10⁻⁹ of the size; `near` within
/// `near·size` (the image of the couplers in line, where the engine refuses the rates within
/// rounding of the dyad's dead point: not on a serial curve); `kept`, the points where no
/// decision settled the pair of cells and the fill's own outline stayed, within two raster
/// cells (the fill within about a cell, and half a cell between centres). Returns (points,
/// near, kept, the largest r of the near ones, of the kept ones).
fn on_the_edge(
    five: &FiveBar,
    ws: &Workspace,
    size: f64,
    near: f64,
) -> (usize, usize, usize, f64, f64) {
    let l = five.l;
    let (mut n, mut near_n, mut kept, mut worst_near, mut worst_kept) = (0, 0, 0, 0.0f64, 0.0f64);
    for line in &ws.boundary {
        for &p in line {
            n += 1;
            if edge_within(five, p, 1e-9 * size) {
                continue;
            }
            let mut r = 1e-9 * size;
            while !edge_within(five, p, r) && r < size {
                r *= 2.0;
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
            if r <= near * size && !serial {
                near_n += 1;
                worst_near = worst_near.max(r);
            } else {
                // (At most two cells: asserted by the caller, after its report.)
                kept += 1;
                worst_kept = worst_kept.max(r);
            }
        }
    }
    (n, near_n, kept, worst_near, worst_kept)
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
    let (n, near, kept, worst_near, worst_kept) = on_the_edge(&five, &ws, size, 2e-5);
    let r = &ws.region;
    let lo = r.origin;
    let hi = r.origin + Vector2::new(r.nx as f64, r.ny as f64) * r.cell;
    let exact = reach_area(&five, lo, hi, 4000, 2000);
    let outline = ws.area();
    let raster = r.area();
    let rel = (outline - exact).abs() / exact;
    // A kept point is at most two cells off, and moves the two chords it ends (a cell or so
    // long each, √2 at most) by at most that: 2·2·√2 < 6 cells² of area each.
    let kept_allowance = kept as f64 * 6.0 * r.cell * r.cell / exact;
    println!(
        "{} at resolution {resolution}: {n} outline points; {} on the edge of the reach within \
         1e-9 of the size, {near} within {worst_near:.1e} m (couplers in line), {kept} left at \
         the fill's outline (within {worst_kept:.1e} m, cell {:.1e} m); area inside the \
         outline {outline:.9e}, independent {exact:.9e} (relative {rel:.2e}, allowed \
         {area_tol:.0e} + {kept_allowance:.1e}); raster cells {raster:.6e} ({:+.2e})",
        linkage.name,
        n - near - kept,
        r.cell,
        (raster - exact) / exact
    );
    assert!(n > 200, "{n}");
    assert!(
        worst_kept <= 2.0 * r.cell,
        "an outline point {worst_kept:e} m from the edge"
    );
    // The fill's outline stays only where no decision settles a pair: a few points.
    assert!(
        kept * 20 <= n,
        "{kept} of {n} points left at the fill's outline"
    );
    assert!(rel < area_tol + kept_allowance, "{rel:e}");
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
