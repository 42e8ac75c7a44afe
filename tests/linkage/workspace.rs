//! The workspace of the five-bar's end effector against an independent dense grid solve:
//! for every point of a fine x–y grid, closed-form inverse kinematics (two circle
//! intersections per leg, the assembly mode of the reference pose) decides whether B reaches
//! it; the computed boundary lies between reached and unreached grid points, every point of
//! the dense grid that borders the unreached lies near the computed boundary, and the filled
//! region agrees with the grid away from the boundary. The serial singular curves lie where
//! a leg is stretched or folded (|OB| = l1 ± l2, |DB| = l4 ± l3), the assembly curves where
//! the couplers are in line (|AC| = l2 + l3). Bad requests get errors naming the field.

use super::two_inputs::{circles, wide_five_bar, FiveBar};
use tmm::linkage::{bundled, Linkage, Plan, Singularity, Workspace, WorkspaceOptions};
use tmm::nalgebra::Point2;
use tmm::Error;

/// The distance from `p` to the nearest segment of the polylines.
fn distance(p: Point2<f64>, lines: &[Vec<Point2<f64>>]) -> f64 {
    let mut best = f64::INFINITY;
    for l in lines {
        for w in l.windows(2) {
            let (a, b) = (w[0], w[1]);
            let ab = b - a;
            let t = if ab.norm_squared() > 0.0 {
                ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            best = best.min((a + t * ab - p).norm());
        }
    }
    best
}

/// The workspace of B against the dense grid of inverse kinematics; returns (the largest
/// distance of a dense-grid boundary point from the computed boundary, its tolerance).
fn check_against_inverse_kinematics(linkage: &Linkage, ws: &Workspace) -> (f64, f64) {
    let five = FiveBar::of(linkage);
    let r = &ws.region;
    let h = r.cell / 2.0;
    // The tolerance: a raster cell (the boundary's own resolution) and a dense-grid step.
    let tol = 1.5 * r.cell + 2.0 * h;
    // Each boundary vertex has reached and unreached dense-grid points within tol.
    // (Sampled four times finer than the grid below: between two circles that touch, a
    // cusp of the reach is thinner than a grid step.)
    let near = |p: Point2<f64>, want: bool| {
        let k = (4.0 * tol / h).ceil() as i32;
        (-k..=k).any(|i| {
            (-k..=k).any(|j| {
                let q = p + tmm::nalgebra::Vector2::new(f64::from(i), f64::from(j)) * (h / 4.0);
                (q - p).norm() <= tol && five.reaches(q) == want
            })
        })
    };
    let mut vertices = 0;
    for l in &ws.boundary {
        assert_eq!(l.first(), l.last(), "a closed outline");
        for &p in l.iter().step_by(3) {
            assert!(
                near(p, true) && near(p, false),
                "boundary point {p} is not on the edge of the reach"
            );
            vertices += 1;
        }
    }
    assert!(vertices > 50, "{vertices}");
    // The dense grid: every reached point next to an unreached one lies near the boundary,
    // and away from the boundary the region holds exactly the reached points.
    let (nx, ny) = (
        (r.nx as f64 * r.cell / h) as usize,
        (r.ny as f64 * r.cell / h) as usize,
    );
    let at = |i: usize, j: usize| {
        r.origin + tmm::nalgebra::Vector2::new(i as f64 + 0.25, j as f64 + 0.25) * h
    };
    let mut worst = 0.0f64;
    let (mut inside, mut checked) = (0, 0);
    for j in 1..ny - 1 {
        for i in 1..nx - 1 {
            let p = at(i, j);
            let reach = five.reaches(p);
            let edge = reach
                && [(i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)]
                    .iter()
                    .any(|&(a, b)| !five.reaches(at(a, b)));
            let d = distance(p, &ws.boundary);
            if edge {
                worst = worst.max(d);
            }
            if d > tol {
                assert_eq!(
                    r.contains(p),
                    reach,
                    "{p}: region against inverse kinematics"
                );
                checked += 1;
                inside += usize::from(reach);
            }
        }
    }
    assert!(checked > 10_000 && inside > 1000, "{checked} {inside}");
    println!(
        "{}: {vertices} boundary vertices checked, {checked} grid points off the boundary agree; \
         dense-grid boundary at most {worst:.2e} m from the computed one (tolerance {tol:.2e} m, \
         raster cell {:.2e} m)",
        linkage.name, r.cell
    );
    (worst, tol)
}

#[test]
fn the_five_bar_workspace_boundary_agrees_with_a_dense_inverse_kinematics_grid() {
    let linkage = bundled::five_bar_robot();
    let plan = Plan::new(&linkage).unwrap();
    let ws = plan.workspace("B", &WorkspaceOptions::default()).unwrap();
    let (worst, tol) = check_against_inverse_kinematics(&linkage, &ws);
    assert!(worst <= tol, "{worst} > {tol}");
    // The serial singular curves: a leg stretched or folded, to the last bits.
    let five = FiveBar::of(&linkage);
    let l = five.l;
    let mut serial = 0;
    for c in ws.singular.iter().filter(|c| c.kind == Singularity::Serial) {
        for (p, q) in c.points.iter().zip(&c.inputs) {
            let (ob, db) = ((p - five.o).norm(), (p - five.d).norm());
            let off = [
                ob - (l[0] + l[1]),
                ob - (l[1] - l[0]).abs(),
                db - (l[2] + l[3]),
                db - (l[2] - l[3]).abs(),
            ]
            .iter()
            .fold(f64::INFINITY, |m, x| m.min(x.abs()));
            assert!(off < 1e-9, "{p} is {off} m off a stretched or folded leg");
            assert!((five.forward(q[0], q[1]).unwrap() - p).norm() < 1e-12);
            serial += 1;
        }
    }
    assert!(serial > 100, "{serial}");
    // The isolated singular inputs in closed form: the couplers folded onto each other (the
    // crank pins meet, A = C, where the circles (O, l1) and (D, l4) cross; B then sweeps the
    // circle of radius l2 about them). (Stretched in line, |AC| = l2 + l3 at q = (π, 0) here,
    // B stays continuous: a small loop of inputs about it maps to a small loop, no curve.)
    let angle = |v: tmm::nalgebra::Vector2<f64>| v.y.atan2(v.x);
    let poles: Vec<([f64; 2], Point2<f64>)> = circles(five.o, l[0], five.d, l[3])
        .into_iter()
        .flatten()
        .map(|p| ([angle(p - five.o), angle(p - five.d)], p))
        .collect();
    // Inputs compared a turn apart.
    let gap = |a: [f64; 2], b: [f64; 2]| {
        let w = |x: f64| x - std::f64::consts::TAU * (x / std::f64::consts::TAU).round();
        w(a[0] - b[0]).hypot(w(a[1] - b[1]))
    };
    let mut folded = 0;
    let mut found = vec![false; poles.len()];
    let (mut worst_pole, mut worst_radius) = (0.0f64, 0.0f64);
    for c in ws
        .singular
        .iter()
        .filter(|c| c.kind == Singularity::Isolated)
    {
        // The inputs lie on a small circle about the engine's pole: its centre from three of
        // them (the circumcentre).
        let n = c.inputs.len();
        assert!(n >= 3, "{n}");
        // (A whole loop ends where it starts: three points a third of it apart.)
        let [p1, p2, p3] =
            [c.inputs[0], c.inputs[n / 3], c.inputs[2 * n / 3]].map(|q| Point2::new(q[0], q[1]));
        let (b, cc) = (p2 - p1, p3 - p1);
        let dd = 2.0 * (b.x * cc.y - b.y * cc.x);
        let centre = p1
            + tmm::nalgebra::Vector2::new(
                cc.y * b.norm_squared() - b.y * cc.norm_squared(),
                b.x * cc.norm_squared() - cc.x * b.norm_squared(),
            ) / dd;
        let radius = (p1 - centre).norm();
        let q = [centre.x, centre.y];
        let (k, &(pole, pin)) = poles
            .iter()
            .enumerate()
            .min_by(|x, y| gap(q, x.1 .0).total_cmp(&gap(q, y.1 .0)))
            .unwrap();
        let off = gap(q, pole);
        // The closed-form singular input lies inside the loop of inputs the curve is traced
        // along (the curve is the image of a loop about it).
        assert!(
            off < radius,
            "{q:?}: {off} from the pole {pole:?}, loop radius {radius}"
        );
        // The engine refines the singular input to full precision.
        assert!(off < 1e-12, "{q:?}: {off} rad from the pole {pole:?}");
        found[k] = true;
        worst_pole = worst_pole.max(off);
        worst_radius = worst_radius.max(radius);
        for (p, qk) in c.points.iter().zip(&c.inputs) {
            // Every point is B at its inputs (closed-form forward kinematics)...
            let exact = five.forward(qk[0], qk[1]).unwrap();
            assert!((p - exact).norm() < 1e-12, "{p} vs {exact}");
            // ...and on the circle of radius l2 about the pins' meeting point to
            // within how far the pin A moved from it: |A(q) − A*| ≤ l1·|q − q*|.
            let bound = l[0] * (gap(*qk, pole) + 1e-12);
            assert!(((p - pin).norm() - l[1]).abs() <= bound, "{p}: {bound}");
            folded += 1;
        }
    }
    println!(
        "isolated singular inputs: the engine's poles within {worst_pole:.1e} rad of the closed \
         form (loops of radius ≤ {worst_radius:.1e} rad); {folded} points on the folded circles"
    );
    assert!(found.iter().all(|&f| f), "{poles:?}: found {found:?}");
    assert!(
        folded > 300,
        "{folded} points on the circles of the folded couplers"
    );
}

#[test]
fn a_five_bar_that_stops_assembling_has_its_assembly_curves_and_boundary_right() {
    let linkage = wide_five_bar();
    let plan = Plan::new(&linkage).unwrap();
    let ws = plan
        .workspace("B", &WorkspaceOptions::default().with_samples(151))
        .unwrap();
    let (worst, tol) = check_against_inverse_kinematics(&linkage, &ws);
    assert!(worst <= tol, "{worst} > {tol}");
    let five = FiveBar::of(&linkage);
    let mut n = 0;
    for c in ws
        .singular
        .iter()
        .filter(|c| c.kind == Singularity::Assembly)
    {
        for q in &c.inputs {
            let (a, cc) = five.cranks(q[0], q[1]);
            assert!(((a - cc).norm() - (five.l[1] + five.l[2])).abs() < 1e-9);
            n += 1;
        }
    }
    assert!(n > 20, "{n}");
}

#[test]
fn bad_workspace_requests_are_refused_naming_the_field() {
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let o = WorkspaceOptions::default();
    let e = plan.workspace("Z", &o).unwrap_err();
    assert!(e.to_string().contains("\"Z\""), "{e}");
    let e = Plan::new(&bundled::four_bar())
        .unwrap()
        .workspace("B", &o)
        .unwrap_err();
    assert!(
        matches!(&e, Error::Description { item, .. } if item == "field second_input"),
        "{e}"
    );
    for (samples, resolution) in [(0, 100), (3000, 100), (100, 2), (100, 1 << 20)] {
        let e = plan
            .workspace(
                "B",
                &o.clone().with_samples(samples).with_resolution(resolution),
            )
            .unwrap_err();
        assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
    }
    let e = plan
        .workspace("B", &o.clone().with_range(1, 0.0, f64::NAN))
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::NonFinite {
                name: "end of an input range",
                ..
            }
        ),
        "{e}"
    );
    let e = plan
        .workspace("B", &o.clone().with_range(0, 1.0, 1.0))
        .unwrap_err();
    assert!(matches!(e, Error::NonPositive { .. }), "{e}");
    let e = plan
        .workspace("B", &o.clone().with_range(0, -1e308, 1e308))
        .unwrap_err();
    assert!(matches!(e, Error::Overflow { .. }), "{e}");
    // Inputs where the linkage never assembles: the couplers of the wide five-bar cannot
    // meet with crank 1 at 180° and crank 4 at 0°.
    let wide = Plan::new(&wide_five_bar()).unwrap();
    let pi = std::f64::consts::PI;
    let nowhere = o
        .clone()
        .with_samples(8)
        .with_range(0, pi - 0.01, pi + 0.01)
        .with_range(1, -0.01, 0.01);
    let e = wide.workspace("B", &nowhere).unwrap_err();
    assert!(
        matches!(&e, Error::Description { item, .. } if item == "ranges"),
        "{e}"
    );
    // A joint on the frame stands still: its workspace is a point, a cell or so.
    let still = plan
        .workspace("O", &o.clone().with_samples(16).with_resolution(16))
        .unwrap();
    assert!(
        still.region.area() <= 4.0 * still.region.cell.powi(2),
        "{}",
        still.region.area()
    );
    assert!(still.singular.is_empty());
    // A range given by hand: a smaller workspace, inside the whole one.
    let whole = plan.workspace("B", &o.clone().with_samples(61)).unwrap();
    let r = plan.reference_inputs();
    let part = plan
        .workspace(
            "B",
            &o.with_samples(61)
                .with_range(0, r[0] - 0.3, r[0] + 0.3)
                .with_range(1, r[1] - 0.3, r[1] + 0.3),
        )
        .unwrap();
    assert!(part.region.area() < 0.5 * whole.region.area());
    // Every cell the smaller range fills is in the whole workspace: filled there too, or
    // within the two rasters' resolution of the whole one's boundary.
    let r = &part.region;
    let mut inside = 0;
    for iy in 0..r.ny {
        for ix in 0..r.nx {
            if !r.cells[iy * r.nx + ix] {
                continue;
            }
            let c = r.centre(ix, iy);
            let edge = distance(c, &whole.boundary);
            assert!(
                whole.region.contains(c) || edge <= 1.5 * (whole.region.cell + r.cell),
                "cell ({ix}, {iy}) at {c} is {edge} m outside the whole workspace"
            );
            inside += 1;
        }
    }
    assert!(inside > 10, "{inside}");
}

/// The workspace picture rendered to pixels (resvg): the region's inside is filled, the
/// plane outside it is blank, and the serial singular curves are drawn where they are.
#[cfg(feature = "draw")]
#[test]
fn the_workspace_picture_shows_the_region_and_its_singular_curves_where_they_are() {
    use resvg::tiny_skia::{Pixmap, Transform};
    use resvg::usvg;
    use tmm::draw::{workspace, Style};
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let ws = plan
        .workspace(
            "B",
            &WorkspaceOptions::default()
                .with_samples(121)
                .with_resolution(160),
        )
        .unwrap();
    let pic = workspace(&plan, &ws, &Style::default()).unwrap();
    let tree = usvg::Tree::from_str(&pic.svg, &usvg::Options::default()).unwrap();
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).unwrap();
    resvg::render(&tree, Transform::default(), &mut pixmap.as_mut());
    if let Ok(dir) = std::env::var("TMM_DRAW_PNG") {
        std::fs::create_dir_all(&dir).unwrap();
        pixmap.save_png(format!("{dir}/workspace.png")).unwrap();
    }
    let rgb = |p: Point2<f64>| {
        let q = pic.frame.to_pixel(p);
        let (x, y) = (q[0].floor() as u32, q[1].floor() as u32);
        let c = pixmap.pixel(x, y).expect("on the picture");
        [c.red(), c.green(), c.blue()]
    };
    let r = &ws.region;
    // Cells whose neighbourhood of 7 × 7 cells is all in (or all out of) the region.
    let uniform = |ix: usize, iy: usize, want: bool| {
        (ix.saturating_sub(3)..=(ix + 3).min(r.nx - 1)).all(|i| {
            (iy.saturating_sub(3)..=(iy + 3).min(r.ny - 1)).all(|j| r.cells[j * r.nx + i] == want)
        })
    };
    let (mut fill, mut inside, mut blank, mut outside) = (0, 0, 0, 0);
    for iy in (0..r.ny).step_by(4) {
        for ix in (0..r.nx).step_by(4) {
            let c = rgb(r.centre(ix, iy));
            if uniform(ix, iy, true) {
                inside += 1;
                fill += usize::from(c == [0xbc, 0xd7, 0xf0]);
            } else if uniform(ix, iy, false) {
                outside += 1;
                blank += usize::from(c == [255, 255, 255]);
            }
        }
    }
    assert!(inside > 300 && outside > 50, "{inside} {outside}");
    // The linkage and the curves are drawn over the region: most of it still shows.
    assert!(fill * 10 >= inside * 8, "{fill} of {inside} filled");
    assert!(blank * 10 >= outside * 9, "{blank} of {outside} blank");
    let mut red = 0;
    let mut points = 0;
    for c in ws.singular.iter().filter(|c| c.kind == Singularity::Serial) {
        for &p in c.points.iter().step_by(5) {
            let [r, g, _] = rgb(p);
            points += 1;
            red += usize::from(r > 150 && g < 120);
        }
    }
    assert!(
        points > 20 && red * 10 >= points * 8,
        "{red} of {points} red"
    );
}
