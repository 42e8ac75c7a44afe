//! The pictures of `tmm::draw`, rendered to pixels by resvg (pure Rust, no fonts: labels do
//! not render, the drawing does) and checked as a person would check them: the picture is
//! not blank, every hinge lands where the frame of the drawing says, the animation has one
//! frame per position and each frame is the solved position, and the diagrams' axes cover
//! the data.
//!
//! Set `TMM_DRAW_PNG=dir` to keep the rendered pictures as PNG files in `dir`.
#![cfg(feature = "draw")]

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg;
use std::f64::consts::TAU;
use tmm::draw::{
    animation, diagram, forces, plan_view, scheme, Diagram, Picture, Style, MAX_FRAMES,
    MAX_PLAN_POSITIONS,
};
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, uniform_inputs, Course, Linkage, Output, Plan};
use tmm::nalgebra::Point2;

use crate::common::svg_scan::assert_finite_svg;

fn render(svg: &str, name: &str) -> Pixmap {
    assert_finite_svg(svg, name);
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).expect("the SVG parses");
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).expect("a picture has a size");
    resvg::render(&tree, Transform::default(), &mut pixmap.as_mut());
    if let Ok(dir) = std::env::var("TMM_DRAW_PNG") {
        std::fs::create_dir_all(&dir).unwrap();
        pixmap.save_png(format!("{dir}/{name}.png")).unwrap();
    }
    pixmap
}

/// The darkness of the pixel nearest to `q`, over a white page (0 white, 255 black).
fn ink(p: &Pixmap, q: [f64; 2]) -> u8 {
    if !(q[0] >= 0.0 && q[1] >= 0.0) {
        return 0;
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let (x, y) = (q[0].floor() as u32, q[1].floor() as u32);
    p.pixel(x, y).map_or(0, |c| {
        // Premultiplied: over white the luminance is (r + g + b)/3 + 255 − a.
        let lum = (u16::from(c.red()) + u16::from(c.green()) + u16::from(c.blue())) / 3;
        #[allow(clippy::cast_possible_truncation)]
        let ink = u16::from(c.alpha()).saturating_sub(lum) as u8;
        ink
    })
}

/// The fraction of pixels that are not white.
fn inked(p: &Pixmap) -> f64 {
    let n = p
        .pixels()
        .iter()
        .filter(|c| {
            let c = c.demultiply();
            c.alpha() > 0 && (c.red() < 235 || c.green() < 235 || c.blue() < 235)
        })
        .count();
    #[allow(clippy::cast_precision_loss)]
    let f = n as f64 / p.pixels().len() as f64;
    f
}

/// Every bundled linkage (all five kinds of groups among them), planned.
fn plans() -> Vec<(String, Plan)> {
    bundled::all()
        .into_iter()
        .map(|l| (l.name.clone(), Plan::new(&l).unwrap()))
        .collect()
}

/// Every hinge of the position `input` drawn where `frame` puts it: a dark centre mark, a dark
/// ring at the hinge radius all round, and the white fill between.
fn assert_hinges(plan: &Plan, input: Motion, pic: &Picture, p: &Pixmap, style: &Style, what: &str) {
    let a = plan.kinematics(input).unwrap();
    let mut checked = 0;
    for (j, name) in plan.joint_names().iter().enumerate() {
        if plan.is_prismatic(j).unwrap() {
            continue;
        }
        let c = pic.frame.to_pixel(a.joint(j).unwrap().p);
        assert!(
            ink(p, c) > 120,
            "{what}: centre of hinge {name} at {c:?} is not drawn"
        );
        let r = style.hinge_radius;
        for k in 0..8 {
            let t = f64::from(k) * TAU / 8.0;
            let ring = [c[0] + r * t.cos(), c[1] + r * t.sin()];
            let near = (-1..=1)
                .flat_map(|dx| {
                    (-1..=1).map(move |dy| [ring[0] + f64::from(dx), ring[1] + f64::from(dy)])
                })
                .map(|q| ink(p, q))
                .max()
                .unwrap();
            assert!(
                near > 100,
                "{what}: ring of hinge {name} not drawn at {ring:?} (ink {})",
                ink(p, ring)
            );
        }
        checked += 1;
    }
    assert!(checked >= 2, "{what}: only {checked} hinges");
}

#[test]
fn every_scheme_shows_its_hinges_where_its_frame_says() {
    let style = Style::default();
    for (name, plan) in plans() {
        for k in 0..4 {
            let phi = plan.reference_input() + f64::from(k) * TAU / 4.0;
            let input = Motion::new(phi, 10.0, 0.0);
            let Ok(_) = plan.kinematics(input) else {
                continue;
            };
            let pic = scheme(&plan, input, &style).unwrap();
            let p = render(&pic.svg, &format!("scheme {name} {k}"));
            let f = inked(&p);
            assert!(f > 0.005 && f < 0.5, "{name}: {f} of the picture inked");
            assert_hinges(&plan, input, &pic, &p, &style, &name);
            // The corners, far from the linkage, stay white.
            assert_eq!(ink(&p, [2.0, 2.0]), 0);
            assert_eq!(ink(&p, [797.0, 597.0]), 0);
        }
    }
}

#[test]
fn a_scheme_draws_every_binary_link_as_a_bar_in_its_colour() {
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    let input = Motion::new(1.0, 10.0, 0.0);
    let pic = scheme(&plan, input, &Style::default()).unwrap();
    let p = render(&pic.svg, "four-bar bars");
    let a = plan.kinematics(input).unwrap();
    for (from, to) in [("O1", "A"), ("A", "B"), ("B", "O3")] {
        let m = nalgebra::center(&a.joint(from).unwrap().p, &a.joint(to).unwrap().p);
        let q = pic.frame.to_pixel(m);
        assert!(ink(&p, q) > 40, "bar {from}{to} not drawn at {q:?}");
    }
    // The frame is not a bar between the ground pivots: its middle stays white.
    let m = nalgebra::center(&a.joint("O1").unwrap().p, &a.joint("O3").unwrap().p);
    assert_eq!(ink(&p, pic.frame.to_pixel(m)), 0);
}

#[test]
fn a_ternary_link_is_a_filled_polygon_and_a_slider_a_block() {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let input = Motion::new(0.7, 10.0, 0.0);
    let pic = scheme(&plan, input, &Style::default()).unwrap();
    let p = render(&pic.svg, "watt ternary");
    let a = plan.kinematics(input).unwrap();
    // The centroid of the coupler's triangle A B E is inside its fill.
    let c = Point2::from(
        (a.joint("A").unwrap().p.coords
            + a.joint("B").unwrap().p.coords
            + a.joint("E").unwrap().p.coords)
            / 3.0,
    );
    assert!(ink(&p, pic.frame.to_pixel(c)) > 20);
    assert!(pic.svg.contains("<polygon"));

    let plan = Plan::new(&bundled::shaper()).unwrap();
    let input = Motion::new(1.0, 10.0, 0.0);
    let pic = scheme(&plan, input, &Style::default()).unwrap();
    let p = render(&pic.svg, "shaper blocks");
    let a = plan.kinematics(input).unwrap();
    // The ram's block: drawn around Q, white inside its outline, dark along it.
    let q = pic.frame.to_pixel(a.joint("Q").unwrap().p);
    let d = a.guide_direction(plan.joint_id("Q").unwrap()).unwrap();
    let half = 0.06 * plan.size() * pic.frame.scale;
    let edge = [q[0] + d.x * half, q[1] - d.y * half];
    let dark = (-2..=2).any(|i| ink(&p, [edge[0] + f64::from(i), edge[1]]) > 60);
    assert!(dark, "the ram's block has no end at {edge:?}");
}

#[test]
fn the_plan_draws_every_course_position_and_the_extremes_bold() {
    let style = Style::default();
    for (linkage, output, paths) in [
        (
            bundled::watt_six_bar(),
            Output::Angle("link 5".into()),
            vec!["E", "G"],
        ),
        (bundled::shaper(), Output::Slide("Q".into()), vec!["D"]),
    ] {
        let plan = Plan::new(&linkage).unwrap();
        let course = Course::new(&plan, Some(&output), 12, 10.0).unwrap();
        let pic = plan_view(&plan, &course, &paths, &style).unwrap();
        let p = render(&pic.svg, &format!("plan {}", plan.name()));
        assert!(inked(&p) > 0.01);
        // The hinges of the bold extreme positions, drawn last, hide what lies under them.
        let hidden: Vec<[f64; 2]> = course
            .extremes
            .iter()
            .flat_map(|&m| {
                let a = plan.kinematics(m).unwrap();
                (0..plan.joint_names().len())
                    .map(|j| pic.frame.to_pixel(a.joint(j).unwrap().p))
                    .collect::<Vec<_>>()
            })
            .collect();
        for (k, &m) in course.inputs.iter().enumerate() {
            let a = plan.kinematics(m).unwrap();
            for (j, name) in plan.joint_names().iter().enumerate() {
                let c = pic.frame.to_pixel(a.joint(j).unwrap().p);
                let r = style.hinge_radius + 1.0;
                if hidden.iter().any(|h| (h[0] - c[0]).hypot(h[1] - c[1]) < r) {
                    continue;
                }
                assert!(
                    ink(&p, c) > 30,
                    "position {k}: joint {name} not drawn at {c:?}"
                );
            }
        }
        // The extreme positions are bold: their links' middles are dark.
        for &m in &course.extremes {
            let a = plan.kinematics(m).unwrap();
            let l = plan.link_names().len();
            let mut dark = 0;
            for k in 1..l {
                let js: Vec<usize> = (0..plan.joint_names().len())
                    .filter(|&j| {
                        plan.joint_links(j).unwrap().map(usize::from).contains(&k)
                            && !plan.is_prismatic(j).unwrap()
                    })
                    .collect();
                if js.len() == 2 {
                    let mid =
                        nalgebra::center(&a.joint(js[0]).unwrap().p, &a.joint(js[1]).unwrap().p);
                    if ink(&p, pic.frame.to_pixel(mid)) > 150 {
                        dark += 1;
                    }
                }
            }
            assert!(
                dark >= 1,
                "{}: no bold link at the extreme {m:?}",
                plan.name()
            );
        }
        // The coupler curves: most of their points are on drawn (dashed) pixels.
        for name in &paths {
            let inputs = uniform_inputs(72, 0.0, 1.0, 0.0);
            let mut on = 0;
            for &m in &inputs {
                let c = pic
                    .frame
                    .to_pixel(plan.kinematics(m).unwrap().joint(name).unwrap().p);
                if (-1..=1).any(|d| {
                    ink(&p, [c[0] + f64::from(d), c[1]]) > 30
                        || ink(&p, [c[0], c[1] + f64::from(d)]) > 30
                }) {
                    on += 1;
                }
            }
            assert!(
                on >= 45,
                "{}: only {on} of 72 points of the path of {name} drawn",
                plan.name()
            );
        }
    }
}

/// The values of every `animate` and `animateTransform` in an SVG text.
fn animations(svg: &str) -> Vec<(String, Vec<String>)> {
    use svg::parser::Event;
    let mut out = Vec::new();
    for event in svg::read(svg).unwrap() {
        if let Event::Tag(name, _, attributes) = event
            && (name == "animate" || name == "animateTransform")
        {
            let values = attributes["values"].to_string();
            out.push((
                attributes["attributeName"].to_string(),
                values.split(';').map(str::to_owned).collect(),
            ));
            assert_eq!(attributes["calcMode"].to_string(), "discrete");
        }
    }
    out
}

#[test]
fn the_animation_has_one_frame_per_position_and_each_frame_is_solved() {
    let style = Style::default();
    for (linkage, n) in [(bundled::watt_six_bar(), 360), (bundled::shaper(), 7)] {
        let plan = Plan::new(&linkage).unwrap();
        let inputs = uniform_inputs(n, plan.reference_input(), 10.0, 0.0);
        let pic = animation(&plan, &inputs, 3.0, &style).unwrap();
        let anims = animations(&pic.svg);
        // A translation and a rotation for the bodies and for the hinges of every moving
        // link, x and y for every label.
        let links = plan.link_names().len() - 1;
        let labels = plan.joint_names().len() + plan.point_names().len();
        assert_eq!(anims.len(), 4 * links + 2 * labels);
        for (attr, values) in &anims {
            assert_eq!(
                values.len(),
                n,
                "{attr}: {} frames for {n} positions",
                values.len()
            );
        }
        // The still picture is the first position.
        let p = render(&pic.svg, &format!("animation {}", plan.name()));
        assert_hinges(&plan, inputs[0], &pic, &p, &style, "animation, first frame");
        // Every frame: each hinge carried by its link's translation and rotation lands on the
        // solved position.
        assert_frames(&plan, &inputs, &pic);
    }
}

/// Follows every hinge through the animation's transforms, frame by frame.
fn assert_frames(plan: &Plan, inputs: &[Motion], pic: &Picture) {
    use svg::parser::Event;
    // The hinge circles in the "hinges" layer, with the translate and rotate values of the
    // link groups around them.
    let mut in_hinges = false;
    let mut translate: Vec<[f64; 2]> = Vec::new();
    let mut rotate: Vec<f64> = Vec::new();
    // Each hinge: the translations and rotations of its link, and its centre in the link.
    type Carried = (Vec<[f64; 2]>, Vec<f64>, [f64; 2]);
    let mut circles: Vec<Carried> = Vec::new();
    for event in svg::read(&pic.svg).unwrap() {
        if let Event::Tag(name, kind, a) = event {
            match (name, kind) {
                ("g", svg::node::element::tag::Type::Start) => {
                    if a.get("class").is_some_and(|c| *c == "hinges") {
                        in_hinges = true;
                    }
                    if a.get("class").is_some_and(|c| *c == "labels") {
                        in_hinges = false;
                    }
                }
                ("animateTransform", _) if in_hinges => {
                    let values = a["values"].to_string();
                    if a["type"] == "translate" {
                        translate = values
                            .split(';')
                            .map(|v| {
                                let (x, y) = v.split_once(',').unwrap();
                                [x.parse().unwrap(), y.parse().unwrap()]
                            })
                            .collect();
                    } else {
                        rotate = values.split(';').map(|v| v.parse().unwrap()).collect();
                    }
                }
                ("circle", _) if in_hinges => {
                    let c = [
                        a["cx"].to_string().parse().unwrap(),
                        a["cy"].to_string().parse().unwrap(),
                    ];
                    if a["fill"] == "#ffffff" {
                        circles.push((translate.clone(), rotate.clone(), c));
                    }
                }
                _ => {}
            }
        }
    }
    let hinges: Vec<usize> = (0..plan.joint_names().len())
        .filter(|&j| !plan.is_prismatic(j).unwrap())
        .collect();
    assert_eq!(circles.len(), hinges.len(), "one circle per hinge");
    for (k, &m) in inputs.iter().enumerate() {
        let a = plan.kinematics(m).unwrap();
        let want: Vec<[f64; 2]> = hinges
            .iter()
            .map(|&j| pic.frame.to_pixel(a.joint(j).unwrap().p))
            .collect();
        for (t, r, c) in &circles {
            let (s, co) = r[k].to_radians().sin_cos();
            let q = [
                t[k][0] + c[0] * co - c[1] * s,
                t[k][1] + c[0] * s + c[1] * co,
            ];
            let best = want
                .iter()
                .map(|w| (w[0] - q[0]).hypot(w[1] - q[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                best < 0.2,
                "frame {k}: a hinge drawn at {q:?} is {best} px from every solved hinge"
            );
        }
    }
}

/// How far the red of an arrow runs from `from` along the unit direction `dir` (pixels),
/// allowing gaps of a few pixels.
fn red_run(p: &Pixmap, from: [f64; 2], dir: [f64; 2]) -> f64 {
    let red = |t: f64| {
        let q = [from[0] + dir[0] * t, from[1] + dir[1] * t];
        if q[0] < 0.0 || q[1] < 0.0 {
            return false;
        }
        p.pixel(q[0].floor() as u32, q[1].floor() as u32)
            .map(|c| c.demultiply())
            .is_some_and(|c| c.red() > 120 && c.green() < 90)
    };
    // The hinge's ring covers the arrow's first pixels, and links crossing it a few more.
    let mut last: Option<f64> = None;
    let mut t = 0.0;
    while t < f64::from(p.width() + p.height()) {
        if red(t) {
            last = Some(t);
        } else if last.is_some_and(|l| t - l > 6.0) {
            break;
        }
        t += 0.25;
    }
    last.unwrap_or(0.0)
}

#[test]
fn forces_are_arrows_to_scale_from_their_points() {
    let style = Style::default();
    for linkage in [bundled::watt_six_bar(), bundled::shaper()] {
        let plan = Plan::new(&linkage).unwrap();
        let input = Motion::new(1.2, 10.0, 0.0);
        let pic = forces(&plan, input, &style).unwrap();
        let p = render(&pic.svg, &format!("forces {}", plan.name()));
        let scale = pic.force_scale.unwrap();
        let a = plan.analyse(input).unwrap();
        let mut longest: f64 = 0.0;
        let mut drawn = Vec::new();
        for j in 0..plan.joint_names().len() {
            let r = a.reaction(j).unwrap();
            let len = r.force.norm() / scale;
            longest = longest.max(len);
            if len < 20.0 {
                continue;
            }
            // A point two thirds along the arrow is red.
            let from = pic.frame.to_pixel(r.point);
            let dir = [r.force.x / r.force.norm(), -r.force.y / r.force.norm()];
            let q = [from[0] + dir[0] * len * 0.66, from[1] + dir[1] * len * 0.66];
            let c = p
                .pixel(q[0].floor() as u32, q[1].floor() as u32)
                .unwrap()
                .demultiply();
            assert!(
                c.red() > 120 && c.green() < 90,
                "{}: the arrow of the reaction in {} is not at {q:?}",
                plan.name(),
                plan.joint_names()[j]
            );
            drawn.push((r.force.norm(), red_run(&p, from, dir)));
        }
        // To scale, measured on the pixels: the drawn length of an arrow is in the ratio of
        // its force to the longest one's. A red run only grows where another arrow continues
        // it, so no arrow may be shorter than that, and most (those drawn clear of others)
        // must match it within the pixels that anti-aliasing and the heads blur.
        drawn.sort_by(|a, b| b.0.total_cmp(&a.0));
        let (f0, l0) = drawn[0];
        let mut matched = 0;
        for &(f, l) in &drawn[1..] {
            let want = l0 * f / f0;
            assert!(
                l >= want - 3.0,
                "{}: an arrow of {f} N is {l} px long, {want} px by the longest ({f0} N, {l0} px)",
                plan.name()
            );
            matched += usize::from(l <= want + 3.0);
        }
        assert!(
            2 * matched >= drawn.len() - 1,
            "{}: only {matched} of {} arrows are to scale",
            plan.name(),
            drawn.len() - 1
        );
        // The largest arrow is 30 % of the linkage's size.
        let want = 0.3 * plan.size() * pic.frame.scale;
        assert!((longest - want).abs() < 1e-6 * want, "{longest} vs {want}");
    }
}

#[test]
fn diagrams_cover_their_data_with_si_units_and_mark_the_course() {
    let style = Style::default();
    for (linkage, output) in [
        (bundled::watt_six_bar(), Output::Angle("link 5".into())),
        (bundled::shaper(), Output::Slide("Q".into())),
    ] {
        let plan = Plan::new(&linkage).unwrap();
        let course = Course::new(&plan, Some(&output), 12, 10.0).unwrap();
        let kinds = [
            Diagram::Kinematics(output.clone()),
            Diagram::Transfer(output.clone()),
            Diagram::Balance,
            Diagram::Reactions,
            Diagram::Hodograph("A".into()),
        ];
        for (i, d) in kinds.iter().enumerate() {
            let chart = diagram(&plan, &course, d, &style).unwrap();
            let p = render(&chart.svg, &format!("diagram {} {i}", plan.name()));
            assert!(inked(&p) > 0.01, "{d:?} is blank");
            for panel in &chart.panels {
                for l in [&panel.x_label, &panel.y_label] {
                    assert!(
                        [", rad", ", m", ", N", "rad/s", "m/s", "/rad", "N·m"]
                            .iter()
                            .any(|u| l.contains(u)),
                        "no unit in {l}"
                    );
                    assert!(!l.contains("Nm") && !l.contains("N*m") && !l.contains("N m"));
                    assert!(chart.svg.contains(l.as_str()), "axis label {l} not written");
                }
                let n = panel.series.iter().map(|s| s.1.len()).sum::<usize>();
                assert!(n >= 360, "{d:?}: {n} points");
                for [x, y] in panel.series.iter().flat_map(|s| s.1.iter()) {
                    assert!(
                        panel.x_range[0] <= *x && *x <= panel.x_range[1],
                        "{d:?}: x {x} outside {:?}",
                        panel.x_range
                    );
                    assert!(
                        panel.y_range[0] <= *y && *y <= panel.y_range[1],
                        "{d:?}: y {y} outside {:?}",
                        panel.y_range
                    );
                }
                // The marks are drawn on the picture (black dots where the axes say).
                assert!(panel.marks.len() >= 12);
                for (k, m) in &panel.marks {
                    let q = panel.to_pixel(m[0], m[1]);
                    assert!(ink(&p, q) > 60, "{d:?}: mark {k} not drawn at {q:?}");
                }
            }
            if matches!(d, Diagram::Balance) {
                // The marks are the engine's values at the course positions.
                let panel = &chart.panels[0];
                for (k, m) in &panel.marks {
                    let want = plan.analyse(course.inputs[*k]).unwrap().balances()[0].value;
                    assert!((m[1] - want).abs() <= 1e-9 * want.abs().max(1.0));
                    assert!(panel.y_range[0] <= want && want <= panel.y_range[1]);
                }
                assert!(chart.svg.contains("N·m"));
            }
        }
    }
}

#[test]
fn a_clockwise_crank_is_plotted_along_its_own_sense() {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let out = Output::Angle("link 5".into());
    for speed in [10.0, -10.0] {
        let course = Course::new(&plan, Some(&out), 12, speed).unwrap();
        let chart = diagram(
            &plan,
            &course,
            &Diagram::Kinematics(out.clone()),
            &Style::default(),
        )
        .unwrap();
        let panel = &chart.panels[0];
        assert!(panel.x_label.contains(if speed < 0.0 {
            "clockwise"
        } else {
            "counter-clockwise"
        }));
        // Position k is reached after k twelfths of a turn: left to right, in the crank's sense.
        for (k, m) in &panel.marks {
            #[allow(clippy::cast_precision_loss)]
            let want = TAU * *k as f64 / 12.0;
            assert!((m[0] - want).abs() < 1e-9, "position {k} at x = {}", m[0]);
        }
        // The angle plotted against x is the angle at the input the crank reaches there.
        let first = course.inputs[0].value;
        for [x, y] in panel.series[0].1.iter().step_by(37) {
            let phi = first + speed.signum() * x;
            let want = plan
                .output(&out, Motion::new(phi, speed, 0.0))
                .unwrap()
                .value;
            let d = (y - want).rem_euclid(TAU);
            assert!(d < 1e-9 || TAU - d < 1e-9, "x = {x}: {y} vs {want}");
        }
    }
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let style = Style::default();
    let good = Motion::new(1.0, 10.0, 0.0);
    assert!(scheme(&plan, Motion::new(f64::NAN, 1.0, 0.0), &style).is_err());
    assert!(scheme(
        &plan,
        good,
        &Style {
            width: 0,
            ..Style::default()
        }
    )
    .is_err());
    assert!(scheme(
        &plan,
        good,
        &Style {
            margin: 400.0,
            ..Style::default()
        }
    )
    .is_err());
    assert!(scheme(
        &plan,
        good,
        &Style {
            hinge_radius: f64::INFINITY,
            ..Style::default()
        }
    )
    .is_err());
    assert!(animation(&plan, &[], 1.0, &style).is_err());
    assert!(animation(&plan, &[good], 0.0, &style).is_err());
    assert!(animation(&plan, &[good], f64::NAN, &style).is_err());
    let too_many = vec![good; MAX_FRAMES + 1];
    assert!(matches!(
        animation(&plan, &too_many, 1.0, &style),
        Err(tmm::Error::OutOfRange { .. })
    ));
    assert!(animation(&plan, &[Motion::new(1.0, f64::INFINITY, 0.0)], 1.0, &style).is_err());
    assert!(Course::new(&plan, None, 0, 10.0).is_err());
    assert!(Course::new(&plan, None, 12, 0.0).is_err());
    assert!(Course::new(&plan, Some(&Output::Angle("nothing".into())), 12, 10.0).is_err());
    let course = Course::new(&plan, None, 12, 10.0).unwrap();
    let empty = Course::given(vec![]);
    assert!(plan_view(&plan, &empty, &[], &style).is_err());
    assert!(plan_view(&plan, &course, &["Z"], &style).is_err());
    for d in [
        Diagram::Kinematics(Output::Angle("nothing".into())),
        Diagram::Transfer(Output::Slide("B".into())),
        Diagram::Kinematics(Output::X("nowhere".into())),
        Diagram::Hodograph("nowhere".into()),
    ] {
        let e = diagram(&plan, &course, &d, &style).unwrap_err();
        assert!(matches!(e, tmm::Error::Description { .. }), "{d:?}: {e}");
    }
    assert!(diagram(&plan, &empty, &Diagram::Balance, &style).is_err());
    assert!(diagram(
        &plan,
        &course,
        &Diagram::Balance,
        &Style {
            samples: 1,
            ..Style::default()
        }
    )
    .is_err());
    // A position that cannot be assembled is named.
    let mut l: Linkage = bundled::four_bar();
    l.joints[1].at = [0.2, 0.0];
    if let Ok(plan) = Plan::new(&l) {
        let inputs = uniform_inputs(36, 0.0, 1.0, 0.0);
        if let Err(e) = animation(&plan, &inputs, 1.0, &style) {
            assert!(e.to_string().contains("frame"), "{e}");
        }
    }
}

#[test]
fn a_slider_input_is_drawn_and_animated() {
    use tmm::linkage::{Input, Joint, Link};
    // A slider driving a crank through a rod (an inverted slider-crank).
    let l = Linkage {
        name: "slider-driven crank".into(),
        joints: vec![
            Joint::revolute("O", [0.0, 0.0]),
            Joint::revolute("A", [0.05, 0.086_602_540_378_443_87]),
            Joint::revolute("B", [0.3, 0.0]),
            Joint::prismatic("S", [0.3, 0.0], "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O", "S"]),
            Link::new("slider", &["S", "B"]),
            Link::new("rod", &["B", "A"]),
            Link::new("crank", &["O", "A"]),
        ],
        input: Input::crank("slider"),
        ..Linkage::default()
    };
    let plan = Plan::new(&l).unwrap();
    assert!(!plan.input_is_crank());
    let style = Style::default();
    let input = Motion::new(0.02, -0.5, 0.0);
    let pic = scheme(&plan, input, &style).unwrap();
    let p = render(&pic.svg, "slider input");
    assert_hinges(&plan, input, &pic, &p, &style, "slider input");
    // The slider's block sits on the hatched guide: the guide is drawn beside the block.
    let s = plan.kinematics(input).unwrap().joint("S").unwrap().p;
    let q = pic.frame.to_pixel(s);
    let half = 0.06 * plan.size() * pic.frame.scale;
    assert!(
        ink(&p, [q[0] + half + 6.0, q[1]]) > 60,
        "no guide beside the block"
    );
    let inputs: Vec<Motion> = (0..20)
        .map(|k| Motion::new(-0.05 + 0.005 * f64::from(k), 0.5, 0.0))
        .collect();
    let pic = animation(&plan, &inputs, 1.0, &style).unwrap();
    assert!(animations(&pic.svg).iter().all(|(_, v)| v.len() == 20));
    assert_frames(&plan, &inputs, &pic);
    let course = Course::given(inputs.clone());
    let chart = diagram(
        &plan,
        &course,
        &Diagram::Kinematics(Output::Angle("crank".into())),
        &style,
    )
    .unwrap();
    assert_eq!(chart.panels[0].x_label, "s1, m");
    assert!(plan_view(&plan, &course, &["A"], &style).is_ok());
    assert!(Course::new(&plan, None, 12, 1.0).is_err());
}

/// A generator of hostile numbers and choices, seeded (a linear congruential generator).
struct Hostile(u64);

impl Hostile {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 33
    }

    fn pick<T: Copy>(&mut self, from: &[T]) -> T {
        #[allow(clippy::cast_possible_truncation)]
        let i = self.next() as usize % from.len();
        from[i]
    }

    /// A hostile f64: non-finite, signed zeros, subnormals, tiny, ordinary and huge values.
    fn f(&mut self) -> f64 {
        let v = self.pick(&[
            f64::NAN,
            f64::INFINITY,
            0.0,
            5e-324,
            1e-310,
            1e-154,
            1e-16,
            0.3,
            1.0,
            2.5,
            5.0,
            40.0,
            60.0,
            61.0,
            1e3,
            1e16,
            1e154,
            1e300,
            f64::MAX,
        ]);
        if self.next().is_multiple_of(3) {
            -v
        } else {
            v
        }
    }

    fn style(&mut self) -> Style {
        let size = [0, 1, 15, 16, 17, 100, 300, 800, 10_000, 10_001, u32::MAX];
        let ordinary = !self.next().is_multiple_of(4);
        let mut style = Style {
            width: self.pick(&size),
            height: self.pick(&size),
            margin: self.f(),
            line_width: self.f(),
            hinge_radius: self.f(),
            labels: self.next().is_multiple_of(2),
            samples: self.pick(&[0, 1, 2, 3, 7, 40, MAX_FRAMES + 1]),
        };
        // Three styles in four hostile in one field only, so that pictures get drawn too.
        if ordinary {
            let keep = style.clone();
            style = Style {
                samples: 24,
                ..Style::default()
            };
            match self.next() % 5 {
                0 => style.margin = keep.margin,
                1 => style.line_width = keep.line_width,
                2 => style.hinge_radius = keep.hinge_radius,
                3 => (style.width, style.height) = (keep.width, keep.height),
                _ => {}
            }
        }
        style
    }
}

/// The four-bar scaled by `k` and moved by `shift` m: tiny, huge and far-off linkages.
fn four_bar_scaled(k: f64, shift: f64) -> Linkage {
    let mut l = bundled::four_bar();
    l.name = format!("four-bar ×{k:e} +{shift:e}");
    for j in &mut l.joints {
        j.at = [k * j.at[0] + shift, k * j.at[1] + shift];
    }
    for link in &mut l.links {
        for p in &mut link.points {
            p.at = [k * p.at[0] + shift, k * p.at[1] + shift];
        }
        link.mass = None;
    }
    l.loads.clear();
    l
}

#[test]
fn hostile_styles_and_inputs_give_errors_or_finite_pictures() {
    let mut plans: Vec<Plan> = plans().into_iter().map(|(_, p)| p).collect();
    for (k, shift) in [
        (1e-150, 0.0),
        (1e150, 0.0),
        (1.0, 1e15),
        (1e-3, 1e9),
        (1e-300, 1e-300),
    ] {
        if let Ok(p) = Plan::new(&four_bar_scaled(k, shift)) {
            plans.push(p);
        }
    }
    let mut g = Hostile(27);
    let (mut drawn, mut refused) = (0, 0);
    let mut tally = |name: &str, r: Result<String, tmm::Error>| match r {
        Ok(svg) => {
            assert_finite_svg(&svg, name);
            drawn += 1;
        }
        Err(e) => {
            assert!(!e.to_string().is_empty());
            refused += 1;
        }
    };
    for round in 0..480 {
        let plan = &plans[round % plans.len()];
        let style = g.style();
        let q0 = plan.reference_input();
        let motion = |g: &mut Hostile| {
            if !g.next().is_multiple_of(4) {
                Motion::new(q0 + 0.01 * f64::from(g.pick(&[0, 1, 5, 50])), g.f(), g.f())
            } else {
                Motion::new(g.f(), g.f(), g.f())
            }
        };
        let name = format!("round {round} {}", plan.name());
        let m = motion(&mut g);
        tally(&name, scheme(plan, m, &style).map(|p| p.svg));
        tally(&name, forces(plan, m, &style).map(|p| p.svg));
        let n = g.pick(&[1, 2, 12]);
        let inputs: Vec<Motion> = (0..n).map(|_| motion(&mut g)).collect();
        let seconds = g.f();
        tally(
            &name,
            animation(plan, &inputs, seconds, &style).map(|p| p.svg),
        );
        let course = match Course::new(plan, None, g.pick(&[0, 1, 5, 12]), g.f()) {
            Ok(c) => c,
            Err(_) => Course {
                extremes: vec![motion(&mut g)],
                ..Course::given(inputs)
            },
        };
        let paths: Vec<&str> = plan.joint_names().iter().map(String::as_str).collect();
        tally(
            &name,
            plan_view(plan, &course, &paths[..2], &style).map(|p| p.svg),
        );
        let d = g.pick(&[0, 1, 2]);
        let d = [
            Diagram::Balance,
            Diagram::Reactions,
            Diagram::Hodograph(paths[1].to_owned()),
        ][d]
            .clone();
        tally(&name, diagram(plan, &course, &d, &style).map(|c| c.svg));
    }
    eprintln!("{drawn} drawn, {refused} refused");
    // Both outcomes happen: the loop reaches the drawing, not only the checks.
    assert!(
        drawn > 100 && refused > 100,
        "{drawn} drawn, {refused} refused"
    );
}

#[test]
fn a_diagram_whose_values_span_more_than_f64_max_ends_with_finite_axes() {
    // The hostile double butterfly's diagram ran without end: a hodograph whose reaction
    // components reach beyond ±f64::MAX / 2 on both sides has an axis of infinite width, and
    // the chart's ticks, stepped across it, never advanced. The same happens to the four-bar
    // with heavy links turned fast: without loads or gravity its reactions are the inertia
    // forces alone, proportional to the links' masses and inertias (scaled by k together).
    let heavy = |k: f64| {
        let mut l = bundled::four_bar();
        l.loads.clear();
        l.gravity = [0.0, 0.0];
        for link in &mut l.links {
            if let Some(m) = &mut link.mass {
                (m.m, m.j) = (k * m.m, k * m.j);
            }
        }
        Plan::new(&l).unwrap()
    };
    let rx = |plan: &Plan, phi: f64, w: f64| {
        plan.analyse(Motion::new(phi, w, 0.0))
            .and_then(|s| s.reaction("O1"))
            .map(|r| r.force.x)
    };
    let phis: Vec<f64> = (0..360).map(|k| TAU * f64::from(k) / 360.0).collect();
    let w = 1e100;
    let unit = heavy(1.0);
    let (fmin, fmax) = phis
        .iter()
        .map(|&phi| rx(&unit, phi, w).unwrap())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    assert!(fmin < 0.0 && fmax > 0.0, "R_x spans [{fmin}, {fmax}]");
    // Both extremes at 1.5e308: their difference overflows.
    let plan = heavy(1.5e308 / fmax.min(-fmin));
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &phi in &phis {
        if let Ok(x) = rx(&plan, phi, w) {
            (lo, hi) = (lo.min(x), hi.max(x));
        }
    }
    assert!(
        lo < -f64::MAX / 2.0 && hi > f64::MAX / 2.0 && (hi - lo).is_infinite(),
        "R_x spans [{lo:e}, {hi:e}]"
    );
    let course = Course::new(&plan, None, 12, w).unwrap();
    // The reactions' magnitudes overflow wherever both components are that large: that
    // diagram may find no position to draw (an error); the hodograph draws its gaps.
    for d in [Diagram::Hodograph("O1".to_owned()), Diagram::Reactions] {
        let chart = match diagram(&plan, &course, &d, &Style::default()) {
            Ok(c) => c,
            Err(e) if d == Diagram::Reactions => {
                assert!(matches!(e, tmm::Error::In { .. }), "{e}");
                continue;
            }
            Err(e) => panic!("{d:?}: {e}"),
        };
        assert_finite_svg(&chart.svg, "a fast four-bar's diagram");
        for p in &chart.panels {
            for r in [p.x_range, p.y_range] {
                let width = r[1] - r[0];
                assert!(width.is_finite() && width > 0.0, "{d:?}: axis {r:?}");
            }
            // Every point drawn lies on the axes (the values beyond 1e300 are gaps).
            for q in p
                .series
                .iter()
                .flat_map(|(_, s)| s)
                .chain(p.marks.iter().map(|(_, m)| m))
            {
                assert!(
                    (p.x_range[0]..=p.x_range[1]).contains(&q[0])
                        && (p.y_range[0]..=p.y_range[1]).contains(&q[1])
                        && q.iter().all(|v| v.abs() <= 1e300),
                    "{d:?}: {q:?} outside {:?} × {:?}",
                    p.x_range,
                    p.y_range
                );
            }
        }
    }
}

#[test]
fn a_frame_is_finite_or_an_error() {
    use tmm::draw::Frame;
    // The case of issue 27: an upside-down box, a picture 10³⁰⁸ px high.
    let r = Frame::fit(
        Point2::new(5e-324, 1e16),
        Point2::new(1e-310, 1e12),
        1e-16,
        1e308,
        1e-154,
    );
    assert!(r.is_err(), "{r:?}");
    let mut g = Hostile(5);
    for _ in 0..5000 {
        let (lo, hi) = (Point2::new(g.f(), g.f()), Point2::new(g.f(), g.f()));
        let (w, h, m) = (g.f(), g.f(), g.f());
        if let Ok(f) = Frame::fit(lo, hi, w, h, m) {
            assert!(f.scale.is_finite() && f.scale > 0.0, "{f:?}");
            assert!(f.origin.iter().all(|o| o.is_finite()), "{f:?}");
            // The box's corners land inside the picture, its centre in the middle.
            for p in [lo, hi] {
                let q = f.to_pixel(p);
                assert!(q.iter().all(|x| x.is_finite()), "{f:?} {p:?}");
                assert!(
                    q[0] >= -1e-6 * w && q[0] <= w * (1.0 + 1e-9),
                    "{f:?} {p:?} {q:?}"
                );
                assert!(
                    q[1] >= -1e-6 * h && q[1] <= h * (1.0 + 1e-9),
                    "{f:?} {p:?} {q:?}"
                );
            }
        }
    }
}

#[test]
fn a_long_course_is_thinned_in_the_plan_and_on_the_diagrams() {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let course = Course::new(&plan, None, MAX_FRAMES, 10.0).unwrap();
    let style = Style::default();
    let pic = plan_view(&plan, &course, &["E"], &style).unwrap();
    assert_finite_svg(&pic.svg, "plan of 20 000");
    let drawn = MAX_FRAMES.div_ceil(MAX_FRAMES.div_ceil(MAX_PLAN_POSITIONS));
    assert!(drawn <= MAX_PLAN_POSITIONS);
    assert!(
        pic.svg
            .contains(&format!("plan in {drawn} of {MAX_FRAMES} positions")),
        "{}",
        &pic.svg[..300]
    );
    // The numbers of the drawn positions are their places in the course: 0, 56, 112, …
    let step = MAX_FRAMES.div_ceil(MAX_PLAN_POSITIONS);
    for k in [0, step, 2 * step, (drawn - 1) * step] {
        assert!(
            pic.svg.contains(&format!(">\n{k}\n</text>")),
            "no label {k}"
        );
    }
    assert!(!pic.svg.contains(&format!(">\n{}\n</text>", step + 1)));
    let chart = diagram(&plan, &course, &Diagram::Balance, &style).unwrap();
    assert_eq!(chart.panels[0].marks.len(), drawn);
    assert_eq!(chart.panels[0].marks[1].0, step);
}

#[test]
fn style_errors_name_the_field() {
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    let m = Motion::new(0.5, 10.0, 0.0);
    for (style, field) in [
        (
            Style {
                hinge_radius: 1e300,
                ..Style::default()
            },
            "style.hinge_radius",
        ),
        (
            Style {
                hinge_radius: f64::NAN,
                ..Style::default()
            },
            "style.hinge_radius",
        ),
        (
            Style {
                line_width: f64::MAX,
                ..Style::default()
            },
            "style.line_width",
        ),
        (
            Style {
                line_width: 0.0,
                ..Style::default()
            },
            "style.line_width",
        ),
        (
            Style {
                margin: -1.0,
                ..Style::default()
            },
            "style.margin",
        ),
        (
            Style {
                width: 10_001,
                ..Style::default()
            },
            "style.width",
        ),
        (
            Style {
                samples: 1,
                ..Style::default()
            },
            "style.samples",
        ),
    ] {
        let e = scheme(&plan, m, &style).unwrap_err();
        assert!(
            matches!(&e, tmm::Error::OutOfRange { name, .. } | tmm::Error::NonFinite { name, .. } if *name == field),
            "{field}: {e}"
        );
        assert!(e.to_string().contains(field), "{e}");
    }
    // The largest admitted stroke still draws, inside the picture.
    let big = Style {
        hinge_radius: 60.0,
        line_width: 60.0,
        ..Style::default()
    };
    let pic = scheme(&plan, m, &big).unwrap();
    render(&pic.svg, "largest strokes");
    let pic = forces(&plan, m, &big).unwrap();
    render(&pic.svg, "largest strokes, forces");
}

#[test]
fn a_rocking_input_is_drawn_over_its_sweep() {
    use tmm::linkage::{Input, Joint, Link, Sweep};
    // A four-bar whose input rocks (input 0.6, coupler 0.5, rocker 0.7, frame 1.0 m).
    let b = [0.340_082_014_076_741_3, 0.233_470_023_461_235_5];
    let l = Linkage {
        name: "rocker input".into(),
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", [0.0, 0.6]),
            Joint::revolute("B", b),
            Joint::revolute("O3", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("input", &["O1", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("rocker", &["O3", "B"]),
        ],
        input: Input::crank("input"),
        ..Linkage::default()
    };
    let plan = Plan::new(&l).unwrap();
    let out = Output::Angle("rocker".into());
    let course = Course::new(&plan, Some(&out), 12, 10.0).unwrap();
    let Sweep::Rocking { from, to } = course.sweep else {
        panic!("{:?}", course.sweep)
    };
    let style = Style::default();
    // The scheme at each lock, the plan of the whole sweep, the animation of the course.
    for m in &course.extremes {
        let pic = scheme(&plan, *m, &style).unwrap();
        let p = render(&pic.svg, "rocking scheme");
        assert_hinges(&plan, *m, &pic, &p, &style, "rocking scheme");
    }
    let pic = plan_view(&plan, &course, &["B"], &style).unwrap();
    let p = render(&pic.svg, "rocking plan");
    for &m in &course.inputs {
        let a = plan.kinematics(m).unwrap();
        let q = pic.frame.to_pixel(a.joint("A").unwrap().p);
        assert!(ink(&p, q) > 30, "A at {m:?} not drawn at {q:?}");
    }
    let pic = animation(&plan, &course.inputs, 2.0, &style).unwrap();
    render(&pic.svg, "rocking animation");
    assert_frames(&plan, &course.inputs, &pic);
    // The diagrams run over the sweep out and back: the abscissa spans twice the range, the
    // rocker's angle comes back to its start, and every course position is marked on it.
    for d in [Diagram::Kinematics(out.clone()), Diagram::Balance] {
        let chart = diagram(&plan, &course, &d, &style).unwrap();
        render(
            &chart.svg,
            &format!("rocking diagram {}", chart.panels.len()),
        );
        let p = &chart.panels[0];
        assert!((p.x_range[1] - 2.0 * (to - from).abs()).abs() < 1e-12);
        let pts = &p.series[0].1;
        if matches!(d, Diagram::Balance) {
            // The two locks (positions 0 and 6, at rest) have no balance: the driven group is
            // at its dead point there. Every other position is marked.
            let marked: Vec<usize> = p.marks.iter().map(|(k, _)| *k).collect();
            assert_eq!(marked, [1, 2, 3, 4, 5, 7, 8, 9, 10, 11]);
        } else {
            assert_eq!(p.marks.len(), 12);
            assert_eq!(p.marks[6].1[0], (to - from).abs()); // the turning point, half way
        }
        if matches!(d, Diagram::Balance) {
            // At the locks (both ends, and the turning point when a sample lands on it) the
            // driven group is at its dead point: no balance there, every other sample has one.
            assert!(
                style.samples - pts.len() <= 3,
                "{} of {}",
                pts.len(),
                style.samples
            );
        } else {
            assert_eq!(pts.len(), style.samples, "no position failed");
        }
        if matches!(d, Diagram::Kinematics(_)) {
            let (y0, y1) = (pts[0][1], pts[pts.len() - 1][1]);
            assert!((y0 - y1).abs() < 1e-2, "{y0} {y1}");
            // Every mark between the ends lies on the curve of the rocker's angle (at the
            // locks the curve is vertical: dψ/dφ grows without bound).
            let x = pts.iter().map(|q| q[0]).collect::<Vec<_>>();
            for (k, m) in p.marks.iter().filter(|(k, _)| *k != 0 && *k != 6) {
                let i = x.partition_point(|&v| v < m[0]).min(x.len() - 1);
                assert!(
                    (pts[i][1] - m[1]).abs() < 0.05,
                    "mark {k}: {m:?} vs {:?}",
                    pts[i]
                );
            }
        }
    }
}

/// Each element of class `balance`: its `data-input` and `data-value`.
fn balance_values(svg: &str) -> Vec<(usize, f64)> {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let key = format!("{name}=\"");
        let start = tag.find(&key)? + key.len();
        Some(tag[start..].split('"').next()?.to_owned())
    };
    svg.split('<')
        .filter(|tag| tag.contains("class=\"balance\""))
        .map(|tag| {
            let i = attr(tag, "data-input").expect("a balance names its input");
            let v = attr(tag, "data-value").expect("a balance gives its value");
            (i.parse().unwrap(), v.parse().unwrap())
        })
        .collect()
}

/// The number in the label that starts with `prefix` ("M_b1 = 1.234 N·m" → 1.234).
fn label_value(svg: &str, prefix: &str) -> f64 {
    let start = svg
        .find(prefix)
        .unwrap_or_else(|| panic!("no label {prefix:?}"))
        + prefix.len();
    let text = svg[start..].split(' ').next().unwrap();
    text.parse()
        .unwrap_or_else(|_| panic!("{prefix}{text}: not a number"))
}

#[test]
fn the_forces_of_a_two_input_linkage_show_both_balancing_moments() {
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let r = plan.reference_inputs();
    let style = Style::default();
    let mut checked = 0;
    for (k, (w1, w2)) in [(2.0, -1.0), (-3.0, 0.5), (1.0, 4.0)]
        .into_iter()
        .enumerate()
    {
        #[allow(clippy::cast_precision_loss)]
        let d = 0.3 * k as f64;
        let input = tmm::linkage::Inputs::two(
            Motion::new(r[0] + d, w1, 0.5),
            Motion::new(r[1] - d, w2, -0.5),
        );
        let a = plan.analyse(input).unwrap();
        let pic = forces(&plan, input, &style).unwrap();
        // Renders, with every number in it finite.
        let px = render(&pic.svg, &format!("five-bar forces {k}"));
        assert!(inked(&px) > 0.005);
        for token in ["NaN", "inf"] {
            assert!(!pic.svg.contains(token), "{token} in the picture");
        }
        let drawn = balance_values(&pic.svg);
        assert_eq!(drawn.len(), 2, "one balance per input: {drawn:?}");
        for i in 0..2 {
            let exact = a.balance(i).unwrap().value;
            assert!(exact.is_finite() && exact != 0.0, "{exact}");
            let (_, v) = drawn.iter().find(|(j, _)| *j == i).copied().unwrap();
            assert!(
                (v - exact).abs() <= 1e-9 * exact.abs(),
                "input {i}: drawn {v}, analysed {exact}"
            );
            // The visible label, to the digits it prints (3 decimals, or 4 significant
            // figures).
            let shown = label_value(&pic.svg, &format!("M_b{} = ", i + 1));
            assert!(
                (shown - exact).abs() <= 5.001e-4 * (exact.abs() + 1.0),
                "input {i}: label {shown}, analysed {exact}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 6);
}

/// A linkage with two inputs has its diagrams along a path of its inputs: every plotted value
/// is the one-shot analysis's own at that position (both balancing moments; the x of the end
/// point B, its velocity and acceleration at the path's rates), to 1e-9 of the values'
/// scale, and the abscissa is the length along the path in the plane of the inputs, summed
/// here independently. A grid, a transfer function and a linkage with one input are refused
/// by name.
#[test]
fn a_two_input_diagram_plots_the_analysis_along_the_path() {
    use tmm::draw::diagram_two;
    use tmm::linkage::TwoInputCourse;
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let n = 48;
    let course = TwoInputCourse::around_reference(&plan, n, 2.0).unwrap();
    let style = Style {
        samples: 360,
        ..Style::default()
    };
    let mut s = 0.0;
    let mut xs = vec![0.0];
    for w in course.inputs.windows(2) {
        let (a, b) = (w[0].as_slice(), w[1].as_slice());
        s += (b[0].value - a[0].value).hypot(b[1].value - a[1].value);
        xs.push(s);
    }
    let close = |got: f64, want: f64, scale: f64, what: &str| {
        assert!(
            (got - want).abs() <= 1e-9 * scale,
            "{what}: plotted {got}, analysed {want}"
        );
    };
    let mut compared = 0;
    // Both balancing moments.
    let chart = diagram_two(&plan, &course, &Diagram::Balance, &style).unwrap();
    assert_finite_svg(&chart.svg, "five-bar balance diagram");
    assert!(inked(&render(&chart.svg, "five-bar balance diagram")) > 0.005);
    let p = &chart.panels[0];
    assert_eq!(p.series.len(), 2);
    assert_eq!(p.y_label, "M_b1, M_b2, N·m");
    assert!(p.x_label.contains("rad"), "{}", p.x_label);
    let analyses: Vec<_> = course
        .inputs
        .iter()
        .map(|&i| plan.analyse(i).unwrap())
        .collect();
    let scale = analyses
        .iter()
        .flat_map(|a| [a.balance(0).unwrap().value, a.balance(1).unwrap().value])
        .fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for (i, (_, pts)) in p.series.iter().enumerate() {
        assert_eq!(pts.len(), n, "every position assembles and is plotted");
        for (k, q) in pts.iter().enumerate() {
            close(q[0], xs[k], xs[n - 1], "abscissa");
            close(q[1], analyses[k].balance(i).unwrap().value, scale, "M_b");
            compared += 1;
        }
    }
    assert_eq!(p.marks.len(), n);
    assert!(p.series.iter().flat_map(|(_, s)| s).all(|q| {
        p.y_range[0] <= q[1] && q[1] <= p.y_range[1] && p.x_range[0] <= q[0] && q[0] <= p.x_range[1]
    }));
    // Where the end point is and how it moves.
    let out = Output::X("B".into());
    let chart = diagram_two(&plan, &course, &Diagram::Kinematics(out), &style).unwrap();
    assert_eq!(chart.panels.len(), 3);
    for (panel, pick) in chart.panels.iter().zip([0, 1, 2]) {
        let want: Vec<f64> = analyses
            .iter()
            .map(|a| {
                let b = a.kinematics().joint("B").unwrap();
                [b.p.x, b.v.x, b.a.x][pick]
            })
            .collect();
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let pts = &panel.series[0].1;
        assert_eq!(pts.len(), n);
        for (q, w) in pts.iter().zip(&want) {
            close(q[1], *w, scale, &panel.y_label);
            compared += 1;
        }
    }
    assert_eq!(compared, 5 * n);
    // What has no meaning along a path of two inputs, or no second input.
    let refused = |r: tmm::Result<tmm::draw::Chart>, item: &str| match r {
        Err(tmm::Error::Description { item: i, .. }) => assert_eq!(i, item),
        other => panic!("expected a description error naming {item}: {other:?}"),
    };
    let r = plan.reference_inputs();
    let grid = TwoInputCourse::grid([r[0], r[0] + 0.1], [r[1], r[1] + 0.1], [3, 3], [1.0, 1.0]);
    refused(
        diagram_two(&plan, &grid.unwrap(), &Diagram::Balance, &style),
        "course",
    );
    let transfer = Diagram::Transfer(Output::X("B".into()));
    refused(diagram_two(&plan, &course, &transfer, &style), "course");
    let four = Plan::new(&bundled::four_bar()).unwrap();
    refused(
        diagram_two(&four, &course, &Diagram::Balance, &style),
        "field second_input",
    );
}

/// The friction diagram of a machine whose drive gives no power over part of its turn (the
/// four-bar with friction and no external loads, its inertia driving it back): the
/// efficiency's curve leaves a gap there, where η has no value, and the lost powers are
/// drawn at every sample.
#[test]
fn the_efficiency_curve_leaves_a_gap_where_the_drive_gives_no_power() {
    let mut l = bundled::four_bar();
    l.loads.clear();
    l.friction = Some(tmm::linkage::Friction::pin(0.15, 0.01));
    let plan = Plan::new(&l).unwrap();
    let course = Course::new(&plan, None, 12, 30.0).unwrap();
    let style = Style {
        samples: 90,
        ..Style::default()
    };
    // Where the drive gives no power, by the analyses themselves.
    let idle = (0..360)
        .filter(|&k| {
            let a = plan
                .analyse(Motion::turning(f64::from(k) * TAU / 360.0, 30.0))
                .unwrap();
            a.efficiency().unwrap().eta.is_none()
        })
        .count();
    assert!(idle > 0 && idle < 360, "{idle} of 360 positions idle");
    let chart = diagram(&plan, &course, &Diagram::Friction, &style).unwrap();
    assert_finite_svg(&chart.svg, "the friction diagram");
    let eta = &chart.panels[0].series[0].1;
    let lost = &chart.panels[1].series;
    // Every sample's lost powers are drawn (the samples cover the turn), η only at some.
    let n = lost[0].1.len();
    assert!(
        n + 1 >= style.samples && lost.iter().all(|(_, s)| s.len() == n),
        "lost powers drawn at {:?} of {} samples",
        lost.iter().map(|(_, s)| s.len()).collect::<Vec<_>>(),
        style.samples
    );
    assert!(
        !eta.is_empty() && eta.len() < n,
        "{} η points of {n}",
        eta.len()
    );
    assert!(eta.iter().all(|p| p[1].is_finite() && p[1] <= 1.0));
}
