//! The pictures of a synthesis (feature `draw`): rendered by resvg, the marks of the targets
//! and poses where the picture's frame puts them, parsed back from the SVG, and drawn in
//! their colours on the rendered pixels.
#![cfg(feature = "draw")]

use crate::common::svg_scan::assert_finite_svg;
use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg;
use std::f64::consts::TAU;
use tmm::draw::{structural_error, synthesis_scheme, Picture, Style, Targets};
use tmm::kinematics::Motion;
use tmm::linkage::Plan;
use tmm::nalgebra::Point2;
use tmm::synthesis::{
    burmester, burmester_curves, centre_point, centre_point_curve, function_generator,
    path_generator, FunctionRequirement, Options, PathOptions, PathRequirement, Pose, Spacing,
    Timing,
};

fn render(svg: &str) -> Pixmap {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).expect("the SVG parses");
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).expect("a picture has a size");
    resvg::render(&tree, Transform::default(), &mut pixmap.as_mut());
    pixmap
}

/// The (data-x, data-y) of every element of class `class`, in document order.
fn marks(svg: &str, class: &str) -> Vec<[f64; 2]> {
    let attr = |tag: &str, name: &str| -> f64 {
        let k = tag.find(&format!("{name}=\"")).expect("the attribute") + name.len() + 2;
        tag[k..k + tag[k..].find('"').unwrap()].parse().unwrap()
    };
    svg.split('<')
        .filter(|tag| tag.contains(&format!("class=\"{class}\"")))
        .map(|tag| [attr(tag, "data-x"), attr(tag, "data-y")])
        .collect()
}

/// Checks each mark of `class` against the frame's pixel of `world` and that the rendered
/// pixel there has the mark's colour (`red`: red over blue, else blue over red).
fn placed(pic: &Picture, class: &str, world: &[[f64; 2]], red: bool) {
    assert_finite_svg(&pic.svg, class);
    let found = marks(&pic.svg, class);
    assert_eq!(found.len(), world.len(), "{class} marks");
    let pixmap = render(&pic.svg);
    for (m, w) in found.iter().zip(world) {
        let q = pic.frame.to_pixel(Point2::new(w[0], w[1]));
        assert!(
            (m[0] - q[0]).abs() <= 0.01 && (m[1] - q[1]).abs() <= 0.01,
            "{class} mark at {m:?}, frame says {q:?}"
        );
        assert!(
            q[0] > 0.0 && q[1] > 0.0 && q[0] < 800.0 && q[1] < 600.0,
            "{q:?} off the picture"
        );
        let px = pixmap
            .pixel(q[0].round() as u32, q[1].round() as u32)
            .expect("inside");
        let (r, b) = (i32::from(px.red()), i32::from(px.blue()));
        assert!(
            if red { r > b + 60 } else { b > r + 60 },
            "{class} at {q:?}: pixel {px:?}"
        );
    }
}

#[test]
fn a_path_generator_is_drawn_with_its_targets_and_path() {
    // Twelve points of a crank-rocker's coupler curve, synthesised back.
    let d = [0.5, 0.12, 0.45, 0.4];
    let points: Vec<[f64; 2]> = (0..12)
        .map(|k| {
            let phi = TAU * k as f64 / 12.0;
            let a = [d[1] * phi.cos(), d[1] * phi.sin()];
            let (ex, ey) = (d[0] - a[0], -a[1]);
            let e = ex.hypot(ey);
            let along = (d[2] * d[2] - d[3] * d[3] + e * e) / (2.0 * e);
            let h = (d[2] * d[2] - along * along).sqrt();
            let b = [
                a[0] + (along * ex - h * ey) / e,
                a[1] + (along * ey + h * ex) / e,
            ];
            let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
            [a[0] + 0.4 * ux - 0.3 * uy, a[1] + 0.4 * uy + 0.3 * ux]
        })
        .collect();
    let req = PathRequirement {
        points: points.clone(),
        timing: Timing::ClosedCurve,
    };
    let opts = PathOptions::default().with_population(40).with_designs(1);
    let best = &path_generator(&req, &opts, |_| true).unwrap()[0];
    assert!(best.mean_error < 1e-9, "{}", best.mean_error);
    let plan = Plan::new(&best.synthesis.linkage).unwrap();
    let pic = synthesis_scheme(
        &plan,
        Motion::fixed(best.crank_angles[0]),
        &Targets::points(&points, "P"),
        &Style::default(),
    )
    .unwrap();
    assert!(pic.svg.contains("class=\"path\""));
    placed(&pic, "target", &points, true);
    // A path that names nothing is refused by name.
    let mut bad = Targets::points(&points, "Q");
    assert!(synthesis_scheme(&plan, Motion::fixed(0.0), &bad, &Style::default()).is_err());
    bad.path = None;
    bad.points[3][1] = f64::NAN;
    assert!(matches!(
        synthesis_scheme(&plan, Motion::fixed(0.0), &bad, &Style::default()),
        Err(tmm::Error::NonFinite { .. })
    ));
}

#[test]
fn a_burmester_four_bar_is_drawn_with_its_poses_and_curves() {
    let poses = [
        Pose::new([0.0, 0.0], 0.0),
        Pose::new([0.1, 0.05], 0.3),
        Pose::new([0.2, 0.05], 0.7),
    ];
    let loose = Options::default().with_min_transmission_angle(0.0);
    let s = burmester(&poses, [-0.05, -0.1], [0.1, -0.08], &loose).unwrap();
    let plan = Plan::new(&s.linkage).unwrap();
    let four = [poses[0], poses[1], poses[2], Pose::new([0.28, 0.0], 1.0)];
    let curve = centre_point_curve(&four, 720).unwrap();
    let centres: Vec<[f64; 2]> = curve.iter().map(|d| d.centre).collect();
    let circles: Vec<[f64; 2]> = curve.iter().map(|d| d.circle).collect();
    let targets = Targets::poses(&poses).with_curves(vec![centres, circles]);
    let style = Style {
        labels: false,
        ..Style::default()
    };
    // The crank's angle at the first pose: the linkage assembles there.
    let phi = centre_point(&poses, [-0.05, -0.1]).unwrap().angles(&poses)[0];
    let pic = synthesis_scheme(&plan, Motion::fixed(phi), &targets, &style).unwrap();
    assert_eq!(pic.svg.matches("class=\"curve\"").count(), 2);
    let at: Vec<[f64; 2]> = poses.iter().map(|p| p.at).collect();
    placed(&pic, "pose", &at, false);
}

/// The vertices of every path of class `class`, px, one list per path.
fn polylines(svg: &str, class: &str) -> Vec<Vec<[f64; 2]>> {
    svg.split('<')
        .filter(|tag| tag.contains(&format!("class=\"{class}\"")))
        .map(|tag| {
            let k = tag.find(" d=\"").expect("a path") + 4;
            let d = &tag[k..k + tag[k..].find('"').unwrap()];
            let nums: Vec<f64> = d
                .split(|c: char| c == ' ' || c == ',' || c.is_ascii_alphabetic())
                .filter(|t| !t.is_empty())
                .map(|t| t.parse().unwrap())
                .collect();
            nums.chunks(2).map(|c| [c[0], c[1]]).collect()
        })
        .collect()
}

#[test]
fn burmesters_curves_are_drawn_through_dyads_that_fit_the_four_poses() {
    let four = [
        Pose::new([0.0, 0.0], 0.0),
        Pose::new([0.1, 0.05], 0.3),
        Pose::new([0.2, 0.05], 0.7),
        Pose::new([0.28, 0.0], 1.0),
    ];
    let runs = burmester_curves(&four, 720).unwrap();
    // The runs hold the centre-point curve's samples, each a dyad for the four poses.
    let flat: Vec<_> = runs.concat();
    assert_eq!(flat.len(), centre_point_curve(&four, 720).unwrap().len());
    for d in &flat {
        assert!(d.misfit(&four) < 1e-9 * (1.0 + d.length()), "{d:?}");
    }
    let three = [four[0], four[1], four[2]];
    let loose = Options::default().with_min_transmission_angle(0.0);
    let s = burmester(&three, [-0.05, -0.1], [0.1, -0.08], &loose).unwrap();
    let plan = Plan::new(&s.linkage).unwrap();
    let phi = centre_point(&three, [-0.05, -0.1]).unwrap().angles(&three)[0];
    let style = Style {
        labels: false,
        ..Style::default()
    };
    let targets = Targets::poses(&four).with_burmester_curves(&runs);
    let pic = synthesis_scheme(&plan, Motion::fixed(phi), &targets, &style).unwrap();
    assert_finite_svg(&pic.svg, "Burmester's curves");
    render(&pic.svg);
    // Every vertex drawn is the pixel of a centre point or a circle point of a fitting dyad,
    // and consecutive vertices are neighbours on the curve (no line zigzags between the two
    // branches: the typical step is a few pixels).
    let pixels: Vec<[f64; 2]> = flat
        .iter()
        .flat_map(|d| [d.centre, d.circle])
        .map(|p| pic.frame.to_pixel(Point2::new(p[0], p[1])))
        .collect();
    let lines = polylines(&pic.svg, "curve");
    assert!(
        lines.len() >= 2 && lines.len() <= 2 * runs.len(),
        "{}",
        lines.len()
    );
    let (mut vertices, mut steps) = (0, Vec::new());
    for line in &lines {
        for (i, v) in line.iter().enumerate() {
            let on = pixels
                .iter()
                .any(|q| (q[0] - v[0]).abs() <= 0.01 && (q[1] - v[1]).abs() <= 0.01);
            assert!(on, "{v:?} is no dyad's pixel");
            if i > 0 {
                steps.push((v[0] - line[i - 1][0]).hypot(v[1] - line[i - 1][1]));
            }
            vertices += 1;
        }
    }
    assert!(vertices > 100, "{vertices}");
    steps.sort_by(f64::total_cmp);
    let median = steps[steps.len() / 2];
    assert!(median < 5.0, "a typical step of {median} px");
    placed(&pic, "pose", &four.map(|p| p.at), false);
}

#[test]
fn the_structural_error_vanishes_at_the_precision_points() {
    let deg = f64::to_radians;
    let need = FunctionRequirement {
        x_range: [1.0, 2.0],
        crank_range: [deg(-30.0), deg(30.0)],
        rocker_range: [deg(0.0), deg(90.0)],
        frame: 0.1,
        spacing: Spacing::Chebyshev,
    };
    let g = function_generator(f64::log10, &need, &Options::default()).unwrap();
    let style = Style {
        samples: 400,
        ..Style::default()
    };
    let chart = structural_error(&g, f64::log10, &style).unwrap();
    assert_finite_svg(&chart.svg, "structural error");
    render(&chart.svg);
    let panel = &chart.panels[0];
    // The marks: the three precision points, where the engine's y is the wanted one to
    // 1e-12 of the range of y.
    let range = 2f64.log10();
    assert_eq!(panel.marks.len(), 3);
    for ((k, m), x) in panel.marks.iter().zip(&g.precision_x) {
        assert_eq!(m[0], *x, "mark {k}");
        assert!(m[1].abs() < 1e-12 * range, "mark {k}: {:e}", m[1]);
    }
    // The curve is the engine's over the whole range, ends included, and changes sign
    // exactly once near each precision point (between the neighbouring samples).
    let curve = &panel.series[0].1;
    assert_eq!(curve.len(), 400);
    assert_eq!(curve[0][0], 1.0);
    assert_eq!(curve[399][0], 2.0);
    let again = g.structural_error(f64::log10, 400).unwrap();
    for (p, q) in curve.iter().zip(&again) {
        assert_eq!(p[1], q.error);
    }
    let changes: Vec<f64> = curve
        .windows(2)
        .filter(|w| w[0][1] * w[1][1] < 0.0)
        .map(|w| 0.5 * (w[0][0] + w[1][0]))
        .collect();
    assert_eq!(changes.len(), 3, "{changes:?}");
    for (c, x) in changes.iter().zip(&g.precision_x) {
        assert!(
            (c - x).abs() < 2.0 / 399.0,
            "a sign change at {c}, precision point {x}"
        );
    }
    // The marks land inside the plotting area where the panel's axes put them.
    let svg_marks = chart.svg.matches("<circle").count();
    assert!(svg_marks >= 3, "{svg_marks}");
    for (_, m) in &panel.marks {
        let [px, py] = panel.to_pixel(m[0], m[1]);
        assert!(px >= panel.x_pixels[0] - 0.5 && px <= panel.x_pixels[1] + 0.5);
        assert!(py <= panel.y_pixels[0] + 0.5 && py >= panel.y_pixels[1] - 0.5);
    }
}
