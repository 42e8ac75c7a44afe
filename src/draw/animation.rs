//! An animated SVG of a linkage over its cycle (SMIL animation, no script).

use super::parts::{self, Pen};
use super::primitives::{self, r2, Labels};
use super::scene::{self, Extents, Pose, Topo};
use super::{Picture, Style};
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::{Inputs, Plan};
use nalgebra::{Point2, Vector2};
use std::fmt::Write;
use svg::node::element::{Animate, AnimateTransform, Group};
use svg::Node;

/// An animation of `plan` through the positions `inputs`, one frame per input, the whole
/// cycle lasting `seconds` and repeating; it plays in any browser by SMIL animation (no
/// script). Every link is drawn once, as in [`scheme`](super::scheme), and moved from frame
/// to frame by an `animateTransform` with one value per frame (`calcMode="discrete"`, so each
/// frame is a solved position, never an interpolation). A picture that does not animate shows
/// the first position, drawn with the returned [`Frame`](super::Frame).
///
/// Its text and time grow with the number of frames times the links and labels, each frame
/// a few numbers per link and label; at most [`MAX_FRAMES`](super::MAX_FRAMES) frames.
///
/// # Errors
/// [`Error::OutOfRange`] or [`Error::NonFinite`] naming the field of a bad style
/// ([`Style::check`]); [`Error::NonFinite`] or [`Error::OutOfRange`] for a duration outside
/// [10⁻³, 10⁶] s; [`Error::OutOfRange`] for no inputs or more than
/// [`MAX_FRAMES`](super::MAX_FRAMES); [`Error::NonFinite`] for a non-finite input; [`Error::In`] naming the position that cannot
/// be solved.
///
/// # Examples
/// 36 frames of the shaper, two seconds a turn:
/// ```
/// use tmm::draw::{animation, Style};
/// use tmm::linkage::{bundled, uniform_inputs, Plan};
/// let plan = Plan::new(&bundled::shaper())?;
/// let inputs = uniform_inputs(36, plan.reference_input(), 10.0, 0.0);
/// let pic = animation(&plan, &inputs, 2.0, &Style::default())?;
/// assert!(pic.svg.contains("animateTransform"));
/// assert!(animation(&plan, &[], 2.0, &Style::default()).is_err());
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn animation(plan: &Plan, inputs: &[Motion], seconds: f64, style: &Style) -> Result<Picture> {
    super::limits::check_count("number of positions", inputs.len())?;
    let inputs: Vec<Inputs> = inputs.iter().map(|&m| Inputs::one(m)).collect();
    animation_path(plan, &inputs, seconds, style)
}

/// An animation of a linkage with two inputs along a path in the plane of its inputs: as
/// [`animation`], one frame per pair of input motions ([`Inputs::two`]; for example the
/// positions of a [`TwoInputCourse`](crate::linkage::TwoInputCourse) along two laws).
/// Positions of one input are animated as well.
///
/// # Errors
/// As [`animation`]; [`Error::In`] naming the frame whose number of motions is not the
/// linkage's number of inputs.
///
/// # Examples
/// The five-bar robot's end effector round a loop about its reference pose:
/// ```
/// use tmm::draw::{animation_path, Style};
/// use tmm::linkage::{bundled, Plan, TwoInputCourse};
/// let plan = Plan::new(&bundled::five_bar_robot())?;
/// let course = TwoInputCourse::around_reference(&plan, 48, 1.0)?;
/// let pic = animation_path(&plan, &course.inputs, 4.0, &Style::default())?;
/// assert!(pic.svg.contains("48 frames"));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn animation_path(
    plan: &Plan,
    inputs: &[Inputs],
    seconds: f64,
    style: &Style,
) -> Result<Picture> {
    style.check()?;
    super::limits::check_count("number of positions", inputs.len())?;
    for i in inputs {
        super::limits::check_inputs(i.as_slice())?;
    }
    crate::error::finite("seconds", seconds)?;
    if !(1e-3..=1e6).contains(&seconds) {
        return Err(Error::OutOfRange {
            name: "seconds",
            value: seconds,
            min: 1e-3,
            max: 1e6,
            ends: crate::Ends::Closed,
        });
    }
    let topo = Topo::new(plan);
    let mut solver = plan.solver();
    let mut poses = Vec::with_capacity(inputs.len());
    for (k, &m) in inputs.iter().enumerate() {
        let a = solver.kinematics(m).map_err(|e| Error::In {
            part: format!("frame {k}"),
            source: Box::new(e),
        })?;
        poses.push(Pose::of(a)?);
    }
    let mut ext = Extents::new(&topo);
    let mut cover = Vec::new();
    for p in &poses {
        ext.add(&topo, p);
    }
    for p in &poses {
        p.cover(&topo, &ext, &mut cover);
    }
    let frame = scene::fit_with_input(&topo, &poses[0], &mut cover, style)?;
    let first = &poses[0];
    let dur = format!("{seconds}s");
    let animate = |kind: &str, values: String| {
        AnimateTransform::new()
            .set("attributeName", "transform")
            .set("type", kind)
            .set("values", values)
            .set("dur", dur.as_str())
            .set("calcMode", "discrete")
            .set("repeatCount", "indefinite")
    };

    let title = format!("{} — {} frames over {seconds} s", plan.name(), poses.len());
    let mut doc = primitives::document(style, &title);
    doc.append(parts::ground(&topo, first, &ext, &frame, style));
    // Each moving link in its own frame at the first position, then carried by a translation
    // and a rotation per frame; the bodies first, the hinges above every body.
    let mut bodies = Group::new().set("class", "links");
    let mut hinges = Group::new().set("class", "hinges");
    for k in 1..topo.links() {
        let (o0, t0) = first.links[k];
        let (c0, s0) = (t0.cos(), t0.sin());
        let scale = frame.scale;
        let local = move |p: Point2<f64>| {
            let r: Vector2<f64> = p - o0;
            let (u, v) = (r.x * c0 + r.y * s0, -r.x * s0 + r.y * c0);
            [scale * u, -scale * v]
        };
        let mut translate = String::with_capacity(16 * poses.len());
        let mut rotate = String::with_capacity(8 * poses.len());
        for (i, p) in poses.iter().enumerate() {
            let (o, t) = p.links[k];
            let q = frame.to_pixel(o);
            let sep = if i == 0 { "" } else { ";" };
            let _ = write!(translate, "{sep}{},{}", r2(q[0]), r2(q[1]));
            let _ = write!(rotate, "{sep}{}", r2(-t.to_degrees()));
        }
        let q0 = frame.to_pixel(o0);
        let base_t = format!("translate({},{})", r2(q0[0]), r2(q0[1]));
        let base_r = format!("rotate({})", r2(-t0.to_degrees()));
        let carry = |inner: Group| {
            Group::new()
                .set("transform", base_t.as_str())
                .set("class", format!("link {}", plan.link_names()[k]))
                .add(animate("translate", translate.clone()))
                .add(
                    Group::new()
                        .set("transform", base_r.as_str())
                        .add(animate("rotate", rotate.clone()))
                        .add(inner),
                )
        };
        bodies.append(carry(parts::link_body(
            &topo,
            first,
            &ext,
            k,
            scale,
            style,
            Pen::NORMAL,
            &local,
        )));
        hinges.append(carry(parts::link_hinges(&topo, first, k, style, &local)));
    }
    doc.append(bodies);
    doc.append(hinges);
    if let Some(arrow) = parts::input_arrow(&topo, first, &frame, style) {
        doc.append(arrow);
    }
    if style.labels {
        // Each label follows its joint or point: its x and y animated frame by frame.
        let mut placed = Labels::default();
        let mut labels = Group::new().set("class", "labels");
        let names = topo.joint_names.iter().chain(&topo.point_names);
        for (n, name) in names.enumerate() {
            let at = |p: &Pose| {
                if n < topo.joint_names.len() {
                    p.at(&topo, n)
                } else {
                    p.points[n - topo.joint_names.len()]
                }
            };
            let q0 = frame.to_pixel(at(first));
            let l0 = placed.place(q0, style);
            let off = [l0[0] - q0[0], l0[1] - q0[1]];
            let mut xs = String::with_capacity(8 * poses.len());
            let mut ys = String::with_capacity(8 * poses.len());
            for (i, p) in poses.iter().enumerate() {
                let q = frame.to_pixel(at(p));
                let sep = if i == 0 { "" } else { ";" };
                let _ = write!(xs, "{sep}{}", r2(q[0] + off[0]));
                let _ = write!(ys, "{sep}{}", r2(q[1] + off[1]));
            }
            let anim = |attr: &str, values: String| {
                Animate::new()
                    .set("attributeName", attr)
                    .set("values", values)
                    .set("dur", dur.as_str())
                    .set("calcMode", "discrete")
                    .set("repeatCount", "indefinite")
            };
            labels.append(
                primitives::text(name, l0, 13.0, "#111111")
                    .add(anim("x", xs))
                    .add(anim("y", ys)),
            );
        }
        doc.append(labels);
    }
    Ok(Picture {
        svg: primitives::finish(&doc)?,
        frame,
        force_scale: None,
    })
}
