//! The plan of the mechanism: its course positions overlaid, the extreme positions bold, and
//! the paths of named points.

use super::parts::{self, Pen};
use super::primitives::{self, r2, Labels};
use super::scene::{self, Extents, Pose, Topo, Tracer};
use super::{Picture, Style};
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::{uniform_inputs, Course, Inputs, Plan, Sweep, TwoInputCourse, TwoInputShape};
use nalgebra::Point2;
use svg::node::element::path::Data;
use svg::node::element::Path;
use svg::Node;

/// The plan of the mechanism in the positions of `course`, overlaid: every position in light
/// colours and numbered from 0 at the input link's outer joint, the extreme positions bold
/// and black, and the paths (coupler curves) of the joints or named points in `paths`, each
/// over a whole turn of the crank in [`Style::samples`] positions (broken where the linkage
/// cannot be assembled) — over its sweep, from one lock to the other, for a rocking input
/// ([`Sweep::Rocking`](crate::linkage::Sweep::Rocking)).
///
/// A course of more than [`MAX_PLAN_POSITIONS`] positions is thinned: every k-th position is
/// drawn (k = ⌈n / [`MAX_PLAN_POSITIONS`]⌉, position 0 among them), each still numbered by
/// its place in the course; so are more extreme positions than that. The time is bounded by
/// the picture: at most [`MAX_PLAN_POSITIONS`] positions solved and drawn, twice that with
/// the extremes, [`Style::samples`] solves for the paths, and one pass over the course to
/// check it.
///
/// # Errors
/// [`Error::OutOfRange`] or [`Error::NonFinite`] naming the field of a bad style
/// ([`Style::check`]); the errors of [`Course::check`] (no positions, a non-finite input);
/// [`Error::Description`] for a name in `paths` that is neither a joint nor a point;
/// [`Error::In`] naming the course position that cannot be solved.
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
    let one = |m: &Motion| Some(Inputs::one(*m));
    let positions: Vec<Inputs> = course.inputs.iter().map(|&m| Inputs::one(m)).collect();
    let extremes: Vec<Inputs> = course.extremes.iter().map(|&m| Inputs::one(m)).collect();
    // The paths over a turn (a slider's input over the course's range).
    let samples: Vec<Option<Inputs>> = path_inputs(plan, course, style.samples)
        .iter()
        .map(one)
        .collect();
    draw_plan(plan, &positions, &extremes, &samples, paths, style)
}

/// The plan of a linkage with two inputs over the positions of `course`, overlaid and
/// numbered as in [`plan_view`] (no extreme positions), with the paths of the joints or named
/// points in `paths`: along a path course ([`TwoInputShape::Path`]) through its positions
/// in order, [`Style::samples`] positions in all with straight steps in the plane of the
/// inputs between the course's; over a grid, along each row of it (the second input
/// varying).
///
/// # Errors
/// As [`plan_view`]; the errors of [`TwoInputCourse::check`].
///
/// # Examples
/// ```
/// use tmm::draw::{plan_view_two, Style};
/// use tmm::linkage::{bundled, Plan, TwoInputCourse};
/// let plan = Plan::new(&bundled::five_bar_robot())?;
/// let course = TwoInputCourse::around_reference(&plan, 12, 1.0)?;
/// let pic = plan_view_two(&plan, &course, &["B"], &Style::default())?;
/// assert!(pic.svg.contains("plan in 12 positions"));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn plan_view_two(
    plan: &Plan,
    course: &TwoInputCourse,
    paths: &[&str],
    style: &Style,
) -> Result<Picture> {
    style.check()?;
    course.check()?;
    let q = &course.inputs;
    let mut samples = Vec::with_capacity(style.samples + q.len());
    match course.shape {
        TwoInputShape::Grid { n2, .. } => {
            // Each row in at most `samples / rows` positions, the pen lifted between rows.
            let rows = q.len() / n2.max(1);
            let per_row = (style.samples / rows.max(1)).max(2);
            for row in q.chunks(n2.max(1)).take(style.samples) {
                samples.extend(thin(row.len(), per_row).map(|k| Some(row[k])));
                samples.push(None);
            }
        }
        TwoInputShape::Path if q.len() > style.samples => {
            samples.extend(thin(q.len(), style.samples).map(|k| Some(q[k])));
        }
        TwoInputShape::Path => {
            let steps = (style.samples / q.len().max(1)).max(1);
            for w in q.windows(2) {
                for s in 0..steps {
                    #[allow(clippy::cast_precision_loss)]
                    let t = s as f64 / steps as f64;
                    samples.push(Some(between(w[0], w[1], t)));
                }
            }
            samples.extend(q.last().map(|&i| Some(i)));
        }
    }
    draw_plan(plan, q, &[], &samples, paths, style)
}

/// The inputs a fraction `t` of the way from `a` to `b`, motion by motion.
fn between(a: Inputs, b: Inputs, t: f64) -> Inputs {
    let mix = |m: Motion, n: Motion| {
        Motion::new(
            m.value + t * (n.value - m.value),
            m.rate + t * (n.rate - m.rate),
            m.accel + t * (n.accel - m.accel),
        )
    };
    match (a.as_slice(), b.as_slice()) {
        ([m1, m2], [n1, n2]) => Inputs::two(mix(*m1, *n1), mix(*m2, *n2)),
        _ => Inputs::one(mix(a.first(), b.first())),
    }
}

/// The plan: `positions` light and numbered, `extremes` bold, the paths of `paths` through
/// `samples` (the pen lifted at a `None` and where the linkage cannot be assembled).
fn draw_plan(
    plan: &Plan,
    positions: &[Inputs],
    extremes: &[Inputs],
    samples: &[Option<Inputs>],
    paths: &[&str],
    style: &Style,
) -> Result<Picture> {
    let topo = Topo::new(plan);
    let tracers: Vec<Tracer> = paths
        .iter()
        .map(|n| topo.tracer(n))
        .collect::<Result<_>>()?;
    let mut solver = plan.solver();
    let mut solve = |m: Inputs, what: &str, k: usize| -> Result<Pose> {
        let a = solver.kinematics(m).map_err(|e| Error::In {
            part: format!("{what} {k}"),
            source: Box::new(e),
        })?;
        Pose::of(a)
    };
    let drawn = thin(positions.len(), MAX_PLAN_POSITIONS);
    let poses: Vec<Pose> = drawn
        .clone()
        .map(|k| solve(positions[k], "course position", k))
        .collect::<Result<_>>()?;
    let bold: Vec<Pose> = thin(extremes.len(), MAX_PLAN_POSITIONS)
        .map(|k| solve(extremes[k], "extreme position", k))
        .collect::<Result<_>>()?;
    let mut curves: Vec<Vec<Option<Point2<f64>>>> =
        vec![Vec::with_capacity(samples.len()); tracers.len()];
    for &m in samples {
        let pose = m.and_then(|m| solver.kinematics(m).ok().and_then(|a| Pose::of(a).ok()));
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
    let Some(first) = poses.first() else {
        return Err(Error::Drawing {
            what: "a plan".to_owned(),
            problem: "the course has no position".to_owned(),
        });
    };
    let frame = scene::fit_with_input(&topo, first, &mut cover, style)?;

    let title = if poses.len() < positions.len() {
        format!(
            "{} — plan in {} of {} positions",
            plan.name(),
            poses.len(),
            positions.len()
        )
    } else {
        format!("{} — plan in {} positions", plan.name(), poses.len())
    };
    let mut doc = primitives::document(style, &title);
    doc.append(parts::ground(&topo, first, &ext, &frame, style));
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
        doc.append(parts::position(&topo, p, &ext, &frame, style, light));
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
        doc.append(parts::position(&topo, p, &ext, &frame, style, heavy));
    }
    if let Some(arrow) = parts::input_arrow(&topo, first, &frame, style) {
        doc.append(arrow);
    }
    if style.labels {
        let mut placed = Labels::default();
        // The numbers of the positions at the input link's outer joint.
        if let Some(outer) = outer_joint(&topo) {
            for (k, p) in drawn.zip(&poses) {
                let q = placed.place(frame.to_pixel(p.on(&topo, outer, topo.input)), style);
                doc.append(primitives::text(&k.to_string(), q, 12.0, "#333333"));
            }
        }
        let first = if bold.is_empty() { first } else { &bold[0] };
        doc.append(parts::labels(&topo, first, &frame, style, &mut placed));
    }
    Ok(Picture {
        svg: primitives::finish(&doc)?,
        frame,
        force_scale: None,
    })
}

/// The most course positions one plan draws (and one diagram marks): a longer course is
/// thinned to every k-th position.
///
/// # Examples
/// A course of 20 000 positions is drawn as 358 of them, every 56th:
/// ```
/// use tmm::draw::{plan_view, Style, MAX_PLAN_POSITIONS};
/// use tmm::linkage::{bundled, Course, Plan};
/// let plan = Plan::new(&bundled::four_bar())?;
/// let course = Course::new(&plan, None, 20_000, 10.0)?;
/// let pic = plan_view(&plan, &course, &[], &Style { labels: false, ..Style::default() })?;
/// assert!(pic.svg.contains("plan in 358 of 20000 positions"));
/// assert!(358 <= MAX_PLAN_POSITIONS);
/// # Ok::<(), tmm::Error>(())
/// ```
pub const MAX_PLAN_POSITIONS: usize = 360;

/// The indices of at most `max` of `n` items: every ⌈n / max⌉-th, from 0.
pub(crate) fn thin(n: usize, max: usize) -> std::iter::StepBy<std::ops::Range<usize>> {
    (0..n).step_by(n.div_ceil(max.max(1)).max(1))
}

/// The input link's joint farthest from the frame (a crank's pin, a slider's hinge).
fn outer_joint(topo: &Topo) -> Option<usize> {
    topo.link_joints[topo.input]
        .iter()
        .copied()
        .find(|&j| !topo.joint_links[j].contains(&0))
}

/// `n` inputs over a turn from the course's first position in its sense of rotation; for a
/// rocking input, over its sweep from one end to the other (both ends included); for a
/// slider, over the range of the course's inputs.
pub(crate) fn path_inputs(plan: &Plan, course: &Course, n: usize) -> Vec<Motion> {
    let first = course.inputs[0];
    if let Sweep::Rocking { from, to } = course.sweep {
        // The way out; the way back retraces it.
        #[allow(clippy::cast_precision_loss)]
        return (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1).max(1) as f64;
                Motion::fixed(if i + 1 == n {
                    to
                } else {
                    from + t * (to - from)
                })
            })
            .collect();
    }
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
