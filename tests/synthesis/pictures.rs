//! The pictures of a synthesis (feature `draw`): rendered by resvg, the marks of the targets
//! and poses where the picture's frame puts them, parsed back from the SVG, and drawn in
//! their colours on the rendered pixels.
#![cfg(feature = "draw")]

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg;
use std::f64::consts::TAU;
use tmm::draw::{synthesis_scheme, Picture, Style, Targets};
use tmm::kinematics::Motion;
use tmm::linkage::Plan;
use tmm::nalgebra::Point2;
use tmm::synthesis::{
    burmester, centre_point, centre_point_curve, path_generator, Options, PathOptions,
    PathRequirement, Pose, Timing,
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
