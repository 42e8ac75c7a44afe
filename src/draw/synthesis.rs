//! A synthesised linkage with what it was synthesised for: the target points of path
//! generation, the poses of motion generation, the path its coupler point traces over a turn,
//! and curves such as Burmester's centre-point and circle-point curves; and the structural
//! error of a function generator.

use super::diagrams::{pad, render};
use super::parts::{self, Pen};
use super::primitives::{self, r2, Labels};
use super::scene::{self, Extents, Pose, Topo};
use super::{Chart, Panel, Picture, Style};
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::Plan;
use crate::synthesis::{Dyad, FunctionGenerator, Pose as BodyPose};
use nalgebra::Point2;
use std::f64::consts::TAU;
use svg::node::element::path::Data;
use svg::node::element::{Group, Path};
use svg::Node;

/// What a synthesis asked for, to draw on its linkage (plain data; every field may be empty).
#[derive(Debug, Clone, Default, PartialEq)]
#[non_exhaustive]
pub struct Targets {
    /// Points the coupler point must pass, m: red crosses, numbered from 1.
    pub points: Vec<[f64; 2]>,
    /// Poses the coupler must take: a blue cross at the point and a bar along the angle.
    pub poses: Vec<BodyPose>,
    /// The joint or named point whose path over a turn of the crank is drawn (in
    /// [`Style::samples`] positions, broken where the linkage does not assemble).
    pub path: Option<String>,
    /// Polylines to draw thin and dashed, m (for example the centre-point and circle-point
    /// curves of [`centre_point_curve`](crate::synthesis::centre_point_curve)); a non-finite
    /// vertex breaks its line.
    pub curves: Vec<Vec<[f64; 2]>>,
}

impl Targets {
    /// The points `points`, and the path of `path`.
    #[must_use]
    pub fn points(points: &[[f64; 2]], path: &str) -> Self {
        Self {
            points: points.to_vec(),
            path: Some(path.to_owned()),
            ..Self::default()
        }
    }

    /// The poses `poses`.
    #[must_use]
    pub fn poses(poses: &[BodyPose]) -> Self {
        Self {
            poses: poses.to_vec(),
            ..Self::default()
        }
    }

    /// With the polylines `curves` added.
    #[must_use]
    pub fn with_curves(mut self, curves: Vec<Vec<[f64; 2]>>) -> Self {
        self.curves.extend(curves);
        self
    }

    /// With Burmester's curves added: for each run of dyads (as
    /// [`burmester_curves`](crate::synthesis::burmester_curves) gives them), the line of its
    /// centre points (the centre-point curve) and that of its circle points in the first pose
    /// (the circle-point curve).
    #[must_use]
    pub fn with_burmester_curves(mut self, runs: &[Vec<Dyad>]) -> Self {
        for run in runs {
            self.curves.push(run.iter().map(|d| d.centre).collect());
            self.curves.push(run.iter().map(|d| d.circle).collect());
        }
        self
    }
}

/// The structural error of a function generator over its whole range: y generated − y
/// wanted against x at [`Style::samples`] evenly spaced x (by the engine, as
/// [`FunctionGenerator::structural_error`]), its precision points marked and numbered on
/// the curve (where the error vanishes for exact precision points). One panel; the axes in
/// the units of x and y.
///
/// # Examples
/// The log10 generator of [`function_generator`](crate::synthesis::function_generator): the
/// curve is zero at its three precision points.
/// ```
/// use tmm::draw::{structural_error, Style};
/// use tmm::synthesis::{function_generator, FunctionRequirement, Options, Spacing};
/// let deg = f64::to_radians;
/// let need = FunctionRequirement {
///     x_range: [1.0, 2.0],
///     crank_range: [deg(-30.0), deg(30.0)],
///     rocker_range: [deg(0.0), deg(90.0)],
///     frame: 0.1,
///     spacing: Spacing::Chebyshev,
/// };
/// let g = function_generator(f64::log10, &need, &Options::default())?;
/// let chart = structural_error(&g, f64::log10, &Style::default())?;
/// let marks = &chart.panels[0].marks;
/// assert_eq!(marks.len(), 3);
/// assert!(marks.iter().all(|(_, m)| m[1].abs() < 1e-12));
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// The errors of [`Style::check`] and of [`FunctionGenerator::structural_error`] (with n =
/// [`Style::samples`]); [`Error::Drawing`] when the chart cannot be drawn.
pub fn structural_error<F: Fn(f64) -> f64>(
    generator: &FunctionGenerator,
    f: F,
    style: &Style,
) -> Result<Chart> {
    style.check()?;
    let curve = generator.structural_error(&f, style.samples.max(2))?;
    let at = generator.structural_error_at(&f, &generator.precision_x)?;
    let points: Vec<[f64; 2]> = curve.iter().map(|p| [p.x, p.error]).collect();
    let marks: Vec<(usize, [f64; 2])> = at
        .iter()
        .enumerate()
        .map(|(i, p)| (i + 1, [p.x, p.error]))
        .collect();
    let (lo, hi) = points
        .iter()
        .chain(marks.iter().map(|(_, m)| m))
        .fold((0.0f64, 0.0f64), |(lo, hi), p| (lo.min(p[1]), hi.max(p[1])));
    let [x0, x1] = generator.requirement.x_range;
    let mut panels = vec![Panel {
        title: "structural error of the function generator (precision points numbered)".to_owned(),
        x_label: "x".to_owned(),
        y_label: "y generated − y wanted".to_owned(),
        x_range: pad(x0.min(x1), x0.max(x1), 0.0),
        y_range: pad(lo, hi, 0.08),
        x_pixels: [0.0; 2],
        y_pixels: [0.0; 2],
        series: vec![("structural error".to_owned(), points)],
        marks,
    }];
    let svg = render(&mut panels, style, false)?;
    Ok(Chart { svg, panels })
}

/// The most vertices of all the [`Targets`] of one picture together (10⁵).
pub const MAX_TARGET_VERTICES: usize = 100_000;

/// The kinematic scheme of `plan` at `input` with `targets` drawn on it: the frame shows the
/// linkage, the targets, the traced path and the curves (the curves' vertices within 20 of
/// the linkage's size of its centre, so that a curve running off to infinity does not shrink
/// the picture to a dot).
///
/// The marks are placed by [`Picture::frame`]: a target point at `p` is the centre of its
/// cross, `frame.to_pixel(p)`.
///
/// # Errors
/// [`Error::NonFinite`] naming `targets.points` or `targets.poses` for a non-finite number;
/// [`Error::OutOfRange`] for more than [`MAX_TARGET_VERTICES`] vertices; the errors of
/// [`Style::check`]; [`Error::Description`] for a `path` that is neither a joint nor a point;
/// the engine's error when `input` cannot be solved.
///
/// # Examples
/// ```
/// use tmm::draw::{synthesis_scheme, Style, Targets};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::Plan;
/// use tmm::synthesis::{crank_rocker, CrankRockerRequirement, FrameChoice, Options};
/// let need = CrankRockerRequirement {
///     rocker: 0.3, swing: 0.8, time_ratio: 1.2, frame: FrameChoice::BestTransmission,
/// };
/// let s = crank_rocker(&need, &Options::default())?;
/// let plan = Plan::new(&s.linkage)?;
/// let b = plan.kinematics(Motion::fixed(0.0))?.joint("B")?.p;
/// let pic = synthesis_scheme(&plan, Motion::fixed(0.0), &Targets::points(&[[b.x, b.y]], "B"),
///     &Style::default())?;
/// assert!(pic.svg.contains("class=\"target\""));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn synthesis_scheme(
    plan: &Plan,
    input: Motion,
    targets: &Targets,
    style: &Style,
) -> Result<Picture> {
    style.check()?;
    check(targets)?;
    let a = plan.kinematics(input)?;
    let topo = Topo::new(plan);
    let pose = Pose::of(&a)?;
    let mut ext = Extents::new(&topo);
    ext.add(&topo, &pose);
    let mut cover = Vec::new();
    pose.cover(&topo, &ext, &mut cover);
    // The traced path over a turn.
    let mut traced: Vec<Option<Point2<f64>>> = Vec::new();
    if let Some(name) = &targets.path {
        let t = topo.tracer(name)?;
        let mut solver = plan.solver();
        for k in 0..style.samples {
            let m = Motion::fixed(input.value + TAU * k as f64 / style.samples as f64);
            let p = solver
                .kinematics(m)
                .ok()
                .and_then(|a| Pose::of(a).ok())
                .map(|q| q.tracer(&topo, t));
            traced.push(p);
        }
    }
    let (lo, hi) = bounds(&cover);
    let (centre, reach) = (
        nalgebra::center(&lo, &hi),
        20.0 * (hi - lo).norm().max(1e-9),
    );
    let near = |p: &Point2<f64>| (p - centre).norm() <= reach;
    cover.extend(traced.iter().flatten().copied().filter(near));
    cover.extend(targets.points.iter().map(|p| Point2::new(p[0], p[1])));
    cover.extend(targets.poses.iter().map(|p| Point2::new(p.at[0], p.at[1])));
    cover.extend(
        targets
            .curves
            .iter()
            .flatten()
            .map(|p| Point2::new(p[0], p[1]))
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .filter(near),
    );
    let frame = scene::fit_with_input(&topo, &pose, &mut cover, style)?;
    let map = |p: Point2<f64>| frame.to_pixel(p);
    let mut doc = primitives::document(style, &format!("{} — synthesis", plan.name()));
    let thin = (0.5 * style.line_width).max(0.5);
    for curve in &targets.curves {
        let pts: Vec<Option<Point2<f64>>> = curve
            .iter()
            .map(|p| Point2::new(p[0], p[1]))
            .map(|p| (p.x.is_finite() && p.y.is_finite() && near(&p)).then_some(p))
            .collect();
        if let Some(path) = polyline(&pts, &map, false) {
            doc.append(
                path.set("class", "curve")
                    .set("stroke", "#7a7a7a")
                    .set("stroke-width", r2(thin))
                    .set("stroke-dasharray", "6 3"),
            );
        }
    }
    if let Some(path) = polyline(&traced, &map, true) {
        doc.append(
            path.set("class", "path")
                .set("stroke", "#2a7f2a")
                .set("stroke-width", r2(thin)),
        );
    }
    doc.append(parts::ground(&topo, &pose, &ext, &frame, style));
    doc.append(parts::position(
        &topo,
        &pose,
        &ext,
        &frame,
        style,
        Pen::NORMAL,
    ));
    if let Some(arrow) = parts::input_arrow(&topo, &pose, &frame, style) {
        doc.append(arrow);
    }
    let size = 2.0 * style.hinge_radius + 2.0;
    let mut labels = Labels::default();
    let mut marks = Group::new();
    for (i, p) in targets.points.iter().enumerate() {
        let q = map(Point2::new(p[0], p[1]));
        marks.append(cross(q, size, "#d0202a", "target"));
        if style.labels {
            let at = labels.place([q[0] + size, q[1] - size], style);
            marks.append(primitives::text(&(i + 1).to_string(), at, 11.0, "#d0202a"));
        }
    }
    for (i, p) in targets.poses.iter().enumerate() {
        let q = map(Point2::new(p.at[0], p.at[1]));
        marks.append(cross(q, size, "#1f4fbf", "pose"));
        let bar = [
            q[0] + 3.0 * size * p.angle.cos(),
            q[1] - 3.0 * size * p.angle.sin(),
        ];
        marks.append(
            Path::new()
                .set(
                    "d",
                    Data::new()
                        .move_to((r2(q[0]), r2(q[1])))
                        .line_to((r2(bar[0]), r2(bar[1]))),
                )
                .set("stroke", "#1f4fbf")
                .set("stroke-width", r2(thin * 2.0)),
        );
        if style.labels {
            let at = labels.place([q[0] + size, q[1] + 2.0 * size], style);
            marks.append(primitives::text(&(i + 1).to_string(), at, 11.0, "#1f4fbf"));
        }
    }
    doc.append(marks);
    if style.labels {
        doc.append(parts::labels(&topo, &pose, &frame, style, &mut labels));
    }
    Ok(Picture {
        svg: primitives::finish(&doc)?,
        frame,
        force_scale: None,
    })
}

fn check(targets: &Targets) -> Result<()> {
    let n = targets.points.len()
        + targets.poses.len()
        + targets.curves.iter().map(Vec::len).sum::<usize>();
    if n > MAX_TARGET_VERTICES {
        return Err(Error::OutOfRange {
            name: "targets (vertices)",
            value: n as f64,
            min: 0.0,
            max: MAX_TARGET_VERTICES as f64,
            ends: crate::Ends::Closed,
        });
    }
    for p in &targets.points {
        crate::error::finite2(["targets.points x", "targets.points y"], *p)?;
    }
    for p in &targets.poses {
        crate::error::finite2(["targets.poses x", "targets.poses y"], p.at)?;
        crate::error::finite("targets.poses angle", p.angle)?;
    }
    Ok(())
}

fn bounds(points: &[Point2<f64>]) -> (Point2<f64>, Point2<f64>) {
    points.iter().fold(
        (
            Point2::new(f64::INFINITY, f64::INFINITY),
            Point2::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        ),
        |(lo, hi), p| {
            (
                Point2::new(lo.x.min(p.x), lo.y.min(p.y)),
                Point2::new(hi.x.max(p.x), hi.y.max(p.y)),
            )
        },
    )
}

/// A cross of half-size `s` px at `q`, its class `class` (so a program finds the marks).
fn cross(q: [f64; 2], s: f64, colour: &str, class: &str) -> Path {
    let d = Data::new()
        .move_to((r2(q[0] - s), r2(q[1] - s)))
        .line_to((r2(q[0] + s), r2(q[1] + s)))
        .move_to((r2(q[0] - s), r2(q[1] + s)))
        .line_to((r2(q[0] + s), r2(q[1] - s)));
    Path::new()
        .set("d", d)
        .set("class", class)
        .set("data-x", r2(q[0]))
        .set("data-y", r2(q[1]))
        .set("stroke", colour)
        .set("stroke-width", 2)
        .set("fill", "none")
}

/// The polyline through the points (`None` breaks it), closed when `closed` and the ends
/// are both present; `None` when nothing is drawn.
fn polyline(
    pts: &[Option<Point2<f64>>],
    map: &dyn Fn(Point2<f64>) -> [f64; 2],
    closed: bool,
) -> Option<Path> {
    let mut d = Data::new();
    let (mut pen_down, mut any) = (false, false);
    for p in pts {
        match p {
            Some(p) => {
                let q = map(*p);
                d = if pen_down {
                    d.line_to((r2(q[0]), r2(q[1])))
                } else {
                    d.move_to((r2(q[0]), r2(q[1])))
                };
                pen_down = true;
                any = true;
            }
            None => pen_down = false,
        }
    }
    if closed
        && pts.last().is_some_and(Option::is_some)
        && let Some(Some(p)) = pts.first()
    {
        let q = map(*p);
        d = d.line_to((r2(q[0]), r2(q[1])));
    }
    any.then(|| Path::new().set("d", d).set("fill", "none"))
}
