//! Instant centres (Aronhold–Kennedy) against the velocities: at the centre of links i and j
//! their velocity fields agree (a finite centre), or the two links translate relative to
//! each other across the centre's direction with equal angular velocities (a centre at
//! infinity). Over every bundled and gallery linkage at many positions, a parallelogram whose
//! coupler translates, and a slider-crank.

use nalgebra::{Point2, Vector2};
use std::f64::consts::TAU;
use tmm::kinematics::Motion;
use tmm::linkage::{
    bundled, Centre, Course, Found, GroupKind, Input, Inputs, InstantCentre, Joint, Link, Linkage,
    Plan,
};
use tmm::mechanism::{Mechanism, SliderCrank};

/// The largest disagreement of the centres with the velocities at `m`, relative to the
/// velocities' scale, and how many centres each method found.
fn check(plan: &Plan, m: Motion, name: &str) -> (f64, [usize; 3]) {
    let k = plan.kinematics(m).unwrap();
    let ics: Vec<InstantCentre> = plan.instant_centres(&k.pose()).unwrap();
    let n = plan.link_names().len();
    assert_eq!(ics.len(), n * (n - 1) / 2, "{}", plan.name());
    let motions: Vec<_> = (0..n).map(|l| k.link_motion(l).unwrap()).collect();
    let w_max = motions.iter().map(|m| m.omega.abs()).fold(0.0, f64::max);
    let v_scale = w_max * plan.size()
        + motions
            .iter()
            .map(|m| m.origin.v.norm())
            .fold(0.0, f64::max);
    let (mut worst, mut count) = (0.0f64, [0; 3]);
    for ic in &ics {
        let [i, j] = ic.links.map(|l| l.index());
        count[match ic.found {
            Found::Joint => 0,
            Found::Kennedy => 1,
            Found::Velocities => 2,
        }] += 1;
        let (mi, mj) = (motions[i], motions[j]);
        match ic.centre {
            Centre::At(p) => {
                assert!(p.x.is_finite() && p.y.is_finite(), "{ic:?}");
                let gap = (mi.motion_of(p).v - mj.motion_of(p).v).norm();
                // Far centres (nearly parallel lines) carry their distance into the check.
                let far = 1.0 + (p - k.link_motion(0).unwrap().origin.p).norm() / plan.size();
                worst = worst.max(gap / (v_scale * far));
            }
            Centre::Infinite(d) => {
                assert!((d.norm() - 1.0).abs() < 1e-12, "{name} at {m:?}: {ic:?}");
                let q = mi.origin.p;
                let rel = mi.motion_of(q).v - mj.motion_of(q).v;
                worst = worst
                    .max((mi.omega - mj.omega).abs() * plan.size() / v_scale)
                    .max(rel.dot(&d).abs() / v_scale);
            }
        }
    }
    (worst, count)
}

/// How far the centres are from where the engine's link velocities at `k` put them: the
/// relative velocity of the two links at a finite centre (a far one carries its distance),
/// their relative angular velocity and the relative velocity along the lines through a centre
/// at infinity, over the velocities' scale.
fn against_engine(plan: &Plan, k: &tmm::linkage::Kinematics<'_>, ics: &[InstantCentre]) -> f64 {
    let n = plan.link_names().len();
    let motions: Vec<_> = (0..n).map(|l| k.link_motion(l).unwrap()).collect();
    let w_max = motions.iter().map(|m| m.omega.abs()).fold(0.0, f64::max);
    let v_scale = w_max * plan.size()
        + motions
            .iter()
            .map(|m| m.origin.v.norm())
            .fold(0.0, f64::max);
    let mut worst = 0.0f64;
    for ic in ics {
        let [i, j] = ic.links.map(|l| l.index());
        let (mi, mj) = (motions[i], motions[j]);
        match ic.centre {
            Centre::At(p) => {
                let gap = (mi.motion_of(p).v - mj.motion_of(p).v).norm();
                let far = 1.0 + (p - motions[0].origin.p).norm() / plan.size();
                worst = worst.max(gap / (v_scale * far));
            }
            Centre::Infinite(d) => {
                let q = mi.origin.p;
                let rel = mi.motion_of(q).v - mj.motion_of(q).v;
                worst = worst
                    .max((mi.omega - mj.omega).abs() * plan.size() / v_scale)
                    .max(rel.dot(&d).abs() / v_scale);
            }
        }
    }
    worst
}

/// For one input the centres are geometry: the same bits at rates 0, 1 and −3 (at rest too,
/// and at a rocking input's locks, where the engine's rates do not exist), each where the
/// engine's link velocities at unit rate agree, to 1e-12 over the smallest group conditioning
/// (the engine's rates carry its inverse). The centres Kennedy's theorem leaves open (read
/// off the chain's motion) are counted: some linkages have them at every position, and a
/// hinged four-bar never.
#[test]
fn one_input_centres_are_geometry_at_any_rate() {
    let mut report = Vec::new();
    let mut open_total = 0;
    for l in bundled::all().into_iter().chain(bundled::gallery()) {
        let plan = Plan::new(&l).unwrap();
        assert_eq!(plan.input_count(), 1, "{}", l.name);
        let n = plan.link_names().len();
        let course = Course::new(&plan, None, 144, 10.0).unwrap();
        let (mut worst, mut scaled, mut count, mut at_rest_only) = (0.0f64, 0.0f64, [0; 3], 0);
        let (mut open, mut most) = (None, 0);
        for m in &course.inputs {
            let rest = plan.kinematics(Motion::fixed(m.value)).unwrap();
            let ics = plan.instant_centres(&rest.pose()).unwrap();
            assert_eq!(ics.len(), n * (n - 1) / 2, "{}", l.name);
            let mut here = [0; 3];
            for ic in &ics {
                here[match ic.found {
                    Found::Joint => 0,
                    Found::Kennedy => 1,
                    Found::Velocities => 2,
                }] += 1;
                if let Centre::At(p) = ic.centre {
                    assert!(p.x.is_finite() && p.y.is_finite(), "{ic:?}");
                } else if let Centre::Infinite(d) = ic.centre {
                    assert!((d.norm() - 1.0).abs() < 1e-12, "{ic:?}");
                }
            }
            // Where two of Kennedy's lines coincide they fix nothing: more are open there.
            open = Some(open.map_or(here[2], |o: usize| o.min(here[2])));
            most = most.max(here[2]);
            count = [0, 1, 2].map(|i| count[i] + here[i]);
            let mut moving = 0;
            for rate in [1.0, -3.0] {
                // At a lock the engine's rates are singular: the centres stand at rest alone.
                let Ok(k) = plan.kinematics(Motion::new(m.value, rate, 0.0)) else {
                    continue;
                };
                moving += 1;
                assert_eq!(
                    plan.instant_centres(&k.pose()).unwrap(),
                    ics,
                    "{} at {} rad, rate {rate}",
                    l.name,
                    m.value
                );
                if rate == 1.0 {
                    // The engine's rates carry 1/conditioning (at a rocking input's lock ends
                    // it is ~1e-7): the check is to 1e-12 of the size divided by it.
                    let cond = k
                        .group_determinants()
                        .iter()
                        .zip(plan.groups())
                        .map(|(d, g)| match g.kind {
                            GroupKind::Rpr => d.abs() / plan.size(),
                            _ => d.abs(),
                        })
                        .fold(1.0, f64::min);
                    let w = against_engine(&plan, &k, &ics);
                    worst = worst.max(w);
                    scaled = scaled.max(w * cond);
                }
            }
            at_rest_only += usize::from(moving == 0);
        }
        let open = open.unwrap();
        open_total += open;
        report.push(format!(
            "{}: worst {worst:.1e}, times the conditioning {scaled:.1e}; found at joints {}, by Kennedy {}, by velocities {} \
             (at least {open} a position); {at_rest_only} positions with no rates",
            l.name, count[0], count[1], count[2]
        ));
        assert!(scaled < 1e-12, "{}", report.last().unwrap());
        let hinged = (0..plan.joint_names().len()).all(|j| !plan.is_prismatic(j).unwrap());
        if n == 4 && hinged {
            // A hinged four-bar's two secondary centres are each on two of Kennedy's lines
            // (with two sliding pairs, two centres at infinity fix no line).
            assert_eq!(most, 0, "{}", l.name);
        }
    }
    println!("{}", report.join("\n"));
    assert!(
        open_total > 0,
        "no linkage exercises the centres found by velocities"
    );
    let db = Plan::new(&bundled::double_butterfly()).unwrap();
    let k = db.kinematics(Motion::fixed(db.reference_input())).unwrap();
    assert!(db
        .instant_centres(&k.pose())
        .unwrap()
        .iter()
        .any(|c| c.found == Found::Velocities));
}

/// With two inputs the centres depend on the ratio of the rates, not their scale; at rest
/// they are not defined (an error, not a NaN).
#[test]
fn two_input_centres_follow_the_rates_ratio() {
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let r = plan.reference_inputs();
    let at = |w1: f64, w2: f64| {
        let k = plan
            .kinematics(Inputs::two(
                Motion::turning(r[0], w1),
                Motion::turning(r[1], w2),
            ))
            .unwrap();
        let ics = plan.instant_centres(&k.pose());
        (k, ics)
    };
    let (k, ics) = at(1.0, -0.5);
    let ics = ics.unwrap();
    assert!(against_engine(&plan, &k, &ics) < 1e-12);
    let (_, scaled) = at(-4.0, 2.0);
    for (a, b) in ics.iter().zip(scaled.unwrap()) {
        match (a.centre, b.centre) {
            (Centre::At(p), Centre::At(q)) => assert!((p - q).norm() < 1e-12 * plan.size()),
            (Centre::Infinite(d), Centre::Infinite(e)) => assert!(d.perp(&e).abs() < 1e-12),
            other => panic!("{other:?}"),
        }
    }
    // A five-bar's five primary centres fix no line of Kennedy's twice: the five others are
    // all open.
    let open = ics.iter().filter(|c| c.found == Found::Velocities).count();
    assert_eq!(open, 5);
    let (_, rest) = at(0.0, 0.0);
    assert!(matches!(rest, Err(tmm::Error::Singular { .. })), "{rest:?}");
}

/// A parallelogram four-bar: the coupler translates, so the centre of frame and coupler is at
/// infinity along the cranks (a direction, never a point at infinity); the two cranks turn
/// alike about distinct pivots, so theirs is at infinity along the frame.
#[test]
fn parallel_links_have_their_centre_at_infinity() {
    let (r, d) = (0.1, 0.3);
    let phi = 1.0f64;
    let a = [r * phi.cos(), r * phi.sin()];
    let l = Linkage {
        name: "parallelogram".into(),
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", a),
            Joint::revolute("B", [a[0] + d, a[1]]),
            Joint::revolute("O3", [d, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("rocker", &["O3", "B"]),
        ],
        input: Input::crank("crank"),
        ..Linkage::default()
    };
    let plan = Plan::new(&l).unwrap();
    // Up to the change point at φ = π (every link on one line), beyond which the mode read
    // off the pose is the crossed (antiparallel) one.
    for k in 1..18 {
        let phi = TAU * f64::from(k) / 36.0;
        let m = Motion::turning(phi, 3.0);
        let (worst, _) = check(&plan, m, "");
        assert!(worst < 1e-9, "{phi}: {worst:e}");
        let kin = plan.kinematics(m).unwrap();
        let ics = plan.instant_centres(&kin.pose()).unwrap();
        let find = |i: usize, j: usize| {
            ics.iter()
                .find(|c| c.links.map(|l| l.index()) == [i, j])
                .unwrap()
                .centre
        };
        let Centre::Infinite(d02) = find(0, 2) else {
            panic!("{phi}: {:?}", find(0, 2))
        };
        let along = Vector2::new(phi.cos(), phi.sin());
        assert!(d02.perp(&along).abs() < 1e-12, "{d02:?}");
        let Centre::Infinite(d13) = find(1, 3) else {
            panic!("{phi}: {:?}", find(1, 3))
        };
        assert!(d13.y.abs() < 1e-12, "{d13:?}");
    }
}

/// A slider's centre with its guide's link is at infinity across the guide.
#[test]
fn a_slider_has_its_centre_at_infinity_across_the_guide() {
    let l = SliderCrank::course_example().linkage().unwrap();
    let plan = Plan::new(&l).unwrap();
    let mut sliders = 0;
    for k in 0..72 {
        let phi = plan.reference_input() + TAU * (f64::from(k) + 0.5) / 72.0;
        let m = Motion::turning(phi, 5.0);
        let (worst, _) = check(&plan, m, "");
        assert!(worst < 1e-9, "{phi}: {worst:e}");
        let kin = plan.kinematics(m).unwrap();
        for ic in plan.instant_centres(&kin.pose()).unwrap() {
            if let (Found::Joint, Centre::Infinite(d)) = (ic.found, ic.centre) {
                let j = (0..plan.joint_names().len())
                    .find(|&j| {
                        plan.is_prismatic(j).unwrap()
                            && plan.joint_links(j).unwrap().map(|x| x.index())
                                == ic.links.map(|x| x.index())
                    })
                    .unwrap();
                assert!(kin.guide_direction(j).unwrap().dot(&d).abs() < 1e-12);
                sliders += 1;
            }
        }
    }
    assert_eq!(sliders, 72);
}

#[test]
fn a_pose_of_another_plan_is_refused() {
    let a = Plan::new(&bundled::four_bar()).unwrap();
    let b = Plan::new(&bundled::watt_six_bar()).unwrap();
    let k = b.kinematics(Motion::turning(0.3, 1.0)).unwrap();
    assert!(a.instant_centres(&k.pose()).is_err());
}

/// The scheme's opt-in layer rings every centre that lies on the picture at its pixel, with
/// its label, and the plain scheme has none.
#[cfg(feature = "draw")]
#[test]
fn the_scheme_draws_the_centres_on_request() {
    use tmm::draw::{scheme, scheme_with_centres, Style};
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let style = Style::default();
    let mut drawn = 0;
    for k in 0..12 {
        let m = Motion::turning(plan.reference_input() + TAU * f64::from(k) / 12.0, 10.0);
        let pic = scheme_with_centres(&plan, m, &style).unwrap();
        assert!(!scheme(&plan, m, &style)
            .unwrap()
            .svg
            .contains("instant-centres"));
        let kin = plan.kinematics(m).unwrap();
        for ic in plan.instant_centres(&kin.pose()).unwrap() {
            let Centre::At(p) = ic.centre else { continue };
            let [x, y] = pic.frame.to_pixel(p);
            let inside =
                (0.0..=pic.frame.width).contains(&x) && (0.0..=pic.frame.height).contains(&y);
            let label = ic.label(&plan).unwrap();
            let ring = format!(
                r#"cx="{}" cy="{}" fill="none""#,
                (x * 100.0).round() / 100.0,
                (y * 100.0).round() / 100.0
            );
            assert_eq!(pic.svg.contains(&ring), inside, "{label} at {p}");
            assert_eq!(pic.svg.contains(&format!("\n{label}\n")), inside, "{label}");
            drawn += usize::from(inside);
        }
    }
    assert!(drawn > 60, "{drawn}");
}

/// Where two lines p + t·u and q + s·v meet.
fn meet(p: Point2<f64>, u: Vector2<f64>, q: Point2<f64>, v: Vector2<f64>) -> Point2<f64> {
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    p + u * (cross(q - p, v) / cross(u, v))
}

/// The label of a drawn centre and its pixel: the `<text>` whose `data-links` names the two
/// links (either order), its x and y.
#[cfg(feature = "draw")]
fn drawn_label(svg: &str, a: &str, b: &str) -> Option<(String, [f64; 2])> {
    let attr = |tag: &str, name: &str| -> f64 {
        let k = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[k..k + tag[k..].find('"').unwrap()].parse().unwrap()
    };
    for links in [format!("{a}|{b}"), format!("{b}|{a}")] {
        let key = format!("data-links=\"{links}\"");
        if let Some(k) = svg.find(&key) {
            let start = svg[..k].rfind("<text").unwrap();
            let end = k + svg[k..].find("</text>").unwrap();
            let tag = &svg[start..end];
            let text = tag[tag.find('>').unwrap() + 1..].trim().to_owned();
            return Some((text, [attr(tag, "x"), attr(tag, "y")]));
        }
    }
    None
}

/// The centres carry the user's numbering of the links (their places in the file's `links`,
/// from 0), whatever order the plan keeps: a four-bar written rocker, coupler, frame, crank
/// labels its crank–rocker centre I03 and its frame–coupler centre I12, each where the closed
/// form puts it (the crank–rocker centre on the coupler's line A–B and the frame's O1–O3; the
/// frame–coupler centre on the crank's line O1–A and the rocker's O3–B), to 1e-9 of the size
/// at 24 crank angles; the scheme writes those labels at those points and a key of the
/// numbers. A slider-crank's frame–piston centre, at infinity across the guide, is not drawn;
/// its crank–piston centre (on A–B and on the normal to the guide through O) and its
/// frame–rod centre (on O–A and on the normal to the guide through B) are, labelled in the
/// file's numbering.
#[test]
fn centres_are_labelled_in_the_files_numbering_at_their_closed_forms() {
    let mut four_bar = bundled::four_bar();
    let order = ["rocker", "coupler", "frame", "crank"];
    four_bar
        .links
        .sort_by_key(|l| order.iter().position(|&n| n == l.name).unwrap());
    let plan = Plan::new(&four_bar).unwrap();
    assert_eq!(
        plan.link_names()[0],
        "frame",
        "the plan's own order differs"
    );
    for (k, name) in order.iter().enumerate() {
        assert_eq!(plan.link_number(*name).unwrap(), k);
    }
    let id = |n: &str| plan.link_id(n).unwrap();
    let find = |ics: &[InstantCentre], a: &str, b: &str| -> InstantCentre {
        *ics.iter()
            .find(|c| c.links.contains(&id(a)) && c.links.contains(&id(b)))
            .unwrap()
    };
    let size = plan.size();
    let (mut worst, mut drawn) = (0.0f64, 0);
    for k in 0..24 {
        let m = Motion::turning(plan.reference_input() + TAU * f64::from(k) / 24.0, 10.0);
        let kin = plan.kinematics(m).unwrap();
        let p = |j: &str| kin.joint(j).unwrap().p;
        let (o1, a, b, o3) = (p("O1"), p("A"), p("B"), p("O3"));
        let ics = plan.instant_centres(&kin.pose()).unwrap();
        for (x, y, label, want) in [
            ("crank", "rocker", "I03", meet(a, b - a, o1, o3 - o1)),
            ("frame", "coupler", "I12", meet(o1, a - o1, o3, b - o3)),
        ] {
            let ic = find(&ics, x, y);
            assert_eq!(ic.label(&plan).unwrap(), label);
            let Centre::At(got) = ic.centre else {
                panic!("{label} at infinity at {m:?}")
            };
            // A far centre (nearly parallel lines) carries its distance.
            let far = 1.0 + (want - o1).norm() / size;
            worst = worst.max((got - want).norm() / (size * far));
        }
        #[cfg(feature = "draw")]
        {
            let pic = tmm::draw::scheme_with_centres(&plan, m, &Default::default()).unwrap();
            assert!(pic
                .svg
                .contains("links: 0 rocker, 1 coupler, 2 frame, 3 crank"));
            for (x, y, label) in [("crank", "rocker", "I03"), ("frame", "coupler", "I12")] {
                let Centre::At(c) = find(&ics, x, y).centre else {
                    unreachable!()
                };
                let [px, py] = pic.frame.to_pixel(c);
                let on =
                    (0.0..=pic.frame.width).contains(&px) && (0.0..=pic.frame.height).contains(&py);
                match drawn_label(&pic.svg, x, y) {
                    Some((text, at)) => {
                        assert!(on, "{label} drawn off the picture");
                        assert_eq!(text, label);
                        // Beside its ring, 0.6 hinge radii up and right.
                        let r = 0.6 * tmm::draw::Style::default().hinge_radius;
                        assert!((at[0] - (px + r)).abs() < 0.006, "{label}: {at:?}");
                        assert!((at[1] - (py - r)).abs() < 0.006, "{label}: {at:?}");
                        drawn += 1;
                    }
                    None => assert!(!on, "{label} on the picture but not drawn"),
                }
            }
        }
    }
    assert!(worst < 1e-9, "{worst:e}");
    #[cfg(feature = "draw")]
    assert!(drawn >= 24, "labels drawn and checked: {drawn}");

    // The slider-crank, written piston, crank, frame, rod.
    let mut l = SliderCrank::course_example().linkage().unwrap();
    let plan0 = Plan::new(&l).unwrap();
    let crank = plan0.link_names()[plan0.input_links()[0].index()].clone();
    let frame = plan0.link_names()[0].clone();
    let slide = (0..plan0.joint_names().len())
        .find(|&j| plan0.is_prismatic(j).unwrap())
        .unwrap();
    let piston_id = plan0
        .joint_links(slide)
        .unwrap()
        .into_iter()
        .find(|x| x.index() != 0);
    let piston = plan0.link_names()[piston_id.unwrap().index()].clone();
    let rod = plan0
        .link_names()
        .iter()
        .find(|n| ![&crank, &frame, &piston].contains(n))
        .unwrap()
        .clone();
    let written = [&piston, &crank, &frame, &rod];
    l.links
        .sort_by_key(|x| written.iter().position(|n| **n == x.name).unwrap());
    let plan = Plan::new(&l).unwrap();
    let number = |n: &str| plan.link_number(n).unwrap();
    assert_eq!(
        [
            number(&piston),
            number(&crank),
            number(&frame),
            number(&rod)
        ],
        [0, 1, 2, 3]
    );
    let joint_of = |a: &str, b: &str| {
        let (a, b) = (plan.link_id(a).unwrap(), plan.link_id(b).unwrap());
        (0..plan.joint_names().len())
            .find(|&j| {
                let l = plan.joint_links(j).unwrap();
                l.contains(&a) && l.contains(&b)
            })
            .unwrap()
    };
    let (jo, ja, jb, js) = (
        joint_of(&crank, &frame),
        joint_of(&crank, &rod),
        joint_of(&rod, &piston),
        joint_of(&piston, &frame),
    );
    let mut worst = 0.0f64;
    for k in 0..24 {
        let m = Motion::turning(
            plan.reference_input() + TAU * (f64::from(k) + 0.5) / 24.0,
            5.0,
        );
        let kin = plan.kinematics(m).unwrap();
        let p = |j: usize| kin.joint(j).unwrap().p;
        let (o, a, b) = (p(jo), p(ja), p(jb));
        let guide = kin.guide_direction(js).unwrap();
        let normal = Vector2::new(-guide.y, guide.x);
        let ics = plan.instant_centres(&kin.pose()).unwrap();
        let find = |x: &str, y: &str| -> InstantCentre {
            let (x, y) = (plan.link_id(x).unwrap(), plan.link_id(y).unwrap());
            *ics.iter()
                .find(|c| c.links.contains(&x) && c.links.contains(&y))
                .unwrap()
        };
        let at_infinity = find(&frame, &piston);
        assert_eq!(at_infinity.label(&plan).unwrap(), "I02");
        let Centre::Infinite(d) = at_infinity.centre else {
            panic!("the frame–piston centre is at infinity")
        };
        assert!(d.dot(&guide).abs() < 1e-12);
        for (x, y, label, want) in [
            (&crank, &piston, "I01", meet(a, b - a, o, normal)),
            (&frame, &rod, "I23", meet(o, a - o, b, normal)),
        ] {
            let ic = find(x, y);
            assert_eq!(ic.label(&plan).unwrap(), label);
            let Centre::At(got) = ic.centre else {
                panic!("{label} at infinity")
            };
            let far = 1.0 + (want - o).norm() / plan.size();
            worst = worst.max((got - want).norm() / (plan.size() * far));
        }
        #[cfg(feature = "draw")]
        {
            let pic = tmm::draw::scheme_with_centres(&plan, m, &Default::default()).unwrap();
            assert!(drawn_label(&pic.svg, &frame, &piston).is_none());
            assert!(pic
                .svg
                .contains(&format!("links: 0 {piston}, 1 {crank}, 2 {frame}, 3 {rod}")));
        }
    }
    assert!(worst < 1e-9, "{worst:e}");
}
