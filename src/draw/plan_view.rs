//! The plan of the mechanism: its course positions overlaid, the extreme positions bold, and
//! the paths of named points.

use super::geometry::{self, r2, Extents, Labels, Pen, Pose, Topo, Tracer};
use super::{Course, Picture, Style};
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::{uniform_inputs, Plan};
use nalgebra::Point2;
use svg::node::element::path::Data;
use svg::node::element::Path;
use svg::Node;

/// The plan of the mechanism in the positions of `course`, overlaid: every position in light
/// colours and numbered from 0 at the input link's outer joint, the extreme positions bold
/// and black, and the paths (coupler curves) of the joints or named points in `paths`, each
/// over a whole turn of the crank in [`Style::samples`] positions (broken where the linkage
/// cannot be assembled).
///
/// # Errors
/// [`Error::Drawing`](crate::Error::Drawing) for a bad style; [`Error::OutOfRange`] for no
/// positions or more than [`MAX_FRAMES`](super::MAX_FRAMES); [`Error::Description`] for a
/// name in `paths` that is neither a joint nor a point; [`Error::In`] naming the course
/// position that cannot be solved.
///
/// # Examples
/// ```
/// use tmm::draw::{plan_view, Course, Style};
/// use tmm::linkage::{bundled, Output, Plan};
/// let plan = Plan::new(&bundled::watt_six_bar())?;
/// let course = Course::new(&plan, Some(&Output::Angle("link 5".into())), 12, 10.0)?;
/// let pic = plan_view(&plan, &course, &["E", "G"], &Style::default())?;
/// assert!(pic.svg.contains("<path"));
/// assert!(plan_view(&plan, &course, &["nowhere"], &Style::default()).is_err());
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn plan_view(plan: &Plan, course: &Course, paths: &[&str], style: &Style) -> Result<Picture> {
    style.check()?;
    course.check()?;
    let topo = Topo::new(plan);
    let tracers: Vec<Tracer> = paths
        .iter()
        .map(|n| topo.tracer(n))
        .collect::<Result<_>>()?;
    let mut solver = plan.solver();
    let mut solve = |m: Motion, what: &str, k: usize| -> Result<Pose> {
        let a = solver.kinematics(m).map_err(|e| Error::In {
            part: format!("{what} {k}"),
            source: Box::new(e),
        })?;
        Pose::of(a)
    };
    let poses: Vec<Pose> = course
        .inputs
        .iter()
        .enumerate()
        .map(|(k, &m)| solve(m, "course position", k))
        .collect::<Result<_>>()?;
    let bold: Vec<Pose> = course
        .extremes
        .iter()
        .enumerate()
        .map(|(k, &m)| solve(m, "extreme position", k))
        .collect::<Result<_>>()?;
    // The paths over a turn (a slider's input over the course's range).
    let samples = path_inputs(plan, course, style.samples);
    let mut curves: Vec<Vec<Option<Point2<f64>>>> =
        vec![Vec::with_capacity(samples.len()); tracers.len()];
    for &m in &samples {
        let pose = solver.kinematics(m).ok().and_then(|a| Pose::of(a).ok());
        for (c, &t) in curves.iter_mut().zip(&tracers) {
            c.push(pose.as_ref().map(|pose| pose.tracer(&topo, t)));
        }
    }
    let mut ext = Extents::new(&topo);
    for p in poses.iter().chain(&bold) {
        ext.add(&topo, p);
    }
    let mut cover = Vec::new();
    for p in poses.iter().chain(&bold) {
        p.cover(&topo, &ext, &mut cover);
    }
    cover.extend(curves.iter().flatten().flatten().copied());
    let frame = geometry::fit_with_input(&topo, &poses[0], &mut cover, style)?;

    let title = format!("{} — plan in {} positions", plan.name(), poses.len());
    let mut doc = geometry::document(style, &title);
    doc.append(geometry::ground(&topo, &poses[0], &ext, &frame, style));
    for (c, name) in curves.iter().zip(paths) {
        let mut d = Data::new();
        let mut pen_down = false;
        for p in c {
            match p {
                Some(p) => {
                    let q = frame.to_pixel(*p);
                    let xy = (r2(q[0]), r2(q[1]));
                    d = if pen_down {
                        d.line_to(xy)
                    } else {
                        d.move_to(xy)
                    };
                    pen_down = true;
                }
                None => pen_down = false,
            }
        }
        doc.append(
            Path::new()
                .set("d", d)
                .set("fill", "none")
                .set("stroke", "#555555")
                .set("stroke-width", 1.2)
                .set("stroke-dasharray", "5,3")
                .set("class", format!("path {name}")),
        );
    }
    let light = Pen {
        colour: None,
        width: 0.5,
        fill_opacity: 0.03,
        opacity: 0.6,
        hinge: 0.6,
        block_fill: false,
    };
    for p in &poses {
        doc.append(geometry::position(&topo, p, &ext, &frame, style, light));
    }
    let heavy = Pen {
        colour: Some("#000000"),
        width: 1.0,
        fill_opacity: 0.0,
        opacity: 1.0,
        hinge: 1.0,
        block_fill: false,
    };
    for p in &bold {
        doc.append(geometry::position(&topo, p, &ext, &frame, style, heavy));
    }
    if let Some(arrow) = geometry::input_arrow(&topo, &poses[0], &frame, style) {
        doc.append(arrow);
    }
    if style.labels {
        let mut placed = Labels::default();
        // The numbers of the positions at the input link's outer joint.
        if let Some(outer) = outer_joint(&topo) {
            for (k, p) in poses.iter().enumerate() {
                let q = placed.place(frame.to_pixel(p.on(&topo, outer, topo.input)), style);
                doc.append(geometry::text(&k.to_string(), q, 12.0, "#333333"));
            }
        }
        let first = if bold.is_empty() { &poses[0] } else { &bold[0] };
        doc.append(geometry::labels(&topo, first, &frame, style, &mut placed));
    }
    Ok(Picture {
        svg: doc.to_string(),
        frame,
        force_scale: None,
    })
}

/// The input link's joint farthest from the frame (a crank's pin, a slider's hinge).
fn outer_joint(topo: &Topo) -> Option<usize> {
    topo.link_joints[topo.input]
        .iter()
        .copied()
        .find(|&j| !topo.joint_links[j].contains(&0))
}

/// `n` inputs over a turn from the course's first position in its sense of rotation, or, for
/// a slider, over the range of the course's inputs.
pub(crate) fn path_inputs(plan: &Plan, course: &Course, n: usize) -> Vec<Motion> {
    let first = course.inputs[0];
    if plan.input_is_crank() {
        let w = if first.rate == 0.0 { 1.0 } else { first.rate };
        uniform_inputs(n, first.value, w, 0.0)
            .into_iter()
            .map(|m| Motion::new(m.value, first.rate, first.accel))
            .collect()
    } else {
        let lo = course
            .inputs
            .iter()
            .map(|m| m.value)
            .fold(f64::INFINITY, f64::min);
        let hi = course
            .inputs
            .iter()
            .map(|m| m.value)
            .fold(f64::NEG_INFINITY, f64::max);
        #[allow(clippy::cast_precision_loss)]
        (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1).max(1) as f64;
                Motion::new(lo + t * (hi - lo), first.rate, first.accel)
            })
            .collect()
    }
}
