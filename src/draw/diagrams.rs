//! The diagrams over a cycle, drawn by plotters' SVG back end.

use super::frame::drawing;
use super::plan_view::{path_inputs, thin, MAX_PLAN_POSITIONS};
use super::Style;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::{Course, Inputs, Kinematics, Output, Plan, Solver, Sweep};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::f64::consts::TAU;

/// A diagram over the cycle, for [`diagram`].
///
/// # Examples
/// Every diagram of the Watt six-bar's output, link 5:
/// ```
/// use tmm::draw::{diagram, Course, Diagram, Style};
/// use tmm::linkage::{bundled, Output, Plan};
/// let plan = Plan::new(&bundled::watt_six_bar())?;
/// let out = Output::Angle("link 5".into());
/// let course = Course::new(&plan, Some(&out), 12, 10.0)?;
/// let style = Style { samples: 72, ..Style::default() };
/// for d in [Diagram::Kinematics(out.clone()), Diagram::Transfer(out), Diagram::Balance,
///           Diagram::Reactions, Diagram::Hodograph("A".into()), Diagram::Friction] {
///     let chart = diagram(&plan, &course, &d, &style)?;
///     assert!(!chart.panels.is_empty());
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Diagram {
    /// The output's position, velocity and acceleration against the input (three panels), at
    /// the speed and acceleration of the course's inputs: rad, rad/s, rad/s² for an angle; m,
    /// m/s, m/s² for a slide or a coordinate.
    Kinematics(Output),
    /// The output's transfer functions against the input (three panels): its value and its
    /// first and second derivatives with respect to the input coordinate (for a crank: rad,
    /// rad/rad, rad/rad² for an angle; m, m/rad, m/rad² for a length).
    Transfer(Output),
    /// The balancing moment of a crank (N·m, counter-clockwise positive) or the driving force
    /// of a slider (N).
    Balance,
    /// The magnitude of the reaction in every joint, N, one line per joint.
    Reactions,
    /// The hodograph of the reaction in the named joint: the tip of R (the force of the
    /// joint's first link on its second, as [`Analysis::reaction`](crate::linkage::Analysis::reaction) gives it), R_y against
    /// R_x, N, over the cycle.
    Hodograph(String),
    /// The friction over the cycle (two panels): the instantaneous efficiency
    /// η = P_useful / P_drive ([`Analysis::efficiency`](crate::linkage::Analysis::efficiency)),
    /// dimensionless, and the power lost in each joint, W, one line per joint. A position
    /// where the drive takes no power (η undefined: the loads drive the machine) leaves a gap
    /// in the efficiency's curve, and the lost powers are drawn there.
    /// Without friction η = 1 and nothing is lost.
    Friction,
}

/// One panel of a [`Chart`]: its axes, what it plots and where on the picture.
///
/// # Examples
/// The three panels of an output's motion, with their units:
/// ```
/// use tmm::draw::{diagram, Course, Diagram, Style};
/// use tmm::linkage::{bundled, Output, Plan};
/// let plan = Plan::new(&bundled::shaper())?;
/// let out = Output::Slide("Q".into());
/// let course = Course::new(&plan, Some(&out), 12, 10.0)?;
/// let chart = diagram(&plan, &course, &Diagram::Kinematics(out), &Style::default())?;
/// let units: Vec<&str> = chart.panels.iter().map(|p| p.y_label.as_str()).collect();
/// assert_eq!(units, ["position, m", "velocity, m/s", "acceleration, m/s²"]);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// The panel's title.
    pub title: String,
    /// The abscissa's name and unit, for example `"φ1 turned counter-clockwise …, rad"`.
    pub x_label: String,
    /// The ordinate's name and unit, for example `"M_b, N·m"`.
    pub y_label: String,
    /// The range of the abscissa's axis.
    pub x_range: [f64; 2],
    /// The range of the ordinate's axis.
    pub y_range: [f64; 2],
    /// The plotting area on the picture, px: left and right edges.
    pub x_pixels: [f64; 2],
    /// The plotting area on the picture, px: bottom and top edges (y grows downwards).
    pub y_pixels: [f64; 2],
    /// The curves: a name and the points (x, y) plotted, in order (a failed position leaves a
    /// gap and no point).
    pub series: Vec<(String, Vec<[f64; 2]>)>,
    /// The marked course positions: the position's number, x and y, on the first curve (on
    /// every curve for [`Diagram::Reactions`]).
    pub marks: Vec<(usize, [f64; 2])>,
}

impl Panel {
    /// The pixel where the point (x, y) of the panel's axes lands.
    ///
    /// # Examples
    /// ```
    /// use tmm::draw::{diagram, Course, Diagram, Style};
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let course = Course::new(&plan, None, 12, 10.0)?;
    /// let chart = diagram(&plan, &course, &Diagram::Balance, &Style::default())?;
    /// let p = &chart.panels[0];
    /// let [left, bottom] = p.to_pixel(p.x_range[0], p.y_range[0]);
    /// assert_eq!([left, bottom], [p.x_pixels[0], p.y_pixels[0]]);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn to_pixel(&self, x: f64, y: f64) -> [f64; 2] {
        let tx = (x - self.x_range[0]) / (self.x_range[1] - self.x_range[0]);
        let ty = (y - self.y_range[0]) / (self.y_range[1] - self.y_range[0]);
        [
            self.x_pixels[0] + tx * (self.x_pixels[1] - self.x_pixels[0]),
            self.y_pixels[0] + ty * (self.y_pixels[1] - self.y_pixels[0]),
        ]
    }
}

/// A drawn diagram: its SVG text and its panels.
///
/// # Examples
/// ```
/// use tmm::draw::{diagram, Course, Diagram, Style};
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::four_bar())?;
/// let course = Course::new(&plan, None, 12, 10.0)?;
/// let chart = diagram(&plan, &course, &Diagram::Reactions, &Style::default())?;
/// assert_eq!(chart.panels[0].series.len(), plan.joint_names().len());
/// assert!(chart.svg.contains("|R|, N"));
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// The SVG document.
    pub svg: String,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
}

/// Draws `diagram` over the cycle of `course`: [`Style::samples`] positions over a turn of the
/// crank from the course's first position (for a slider, over the range of the course's
/// inputs), the course positions marked and numbered. The abscissa is the angle the crank
/// has turned from the course's first position in its own sense of rotation (so a clockwise
/// crank reads left to right as it turns), rad; for an input rocking between two angles
/// ([`Sweep::Rocking`]), the angle it has swept from the course's first position, out to the
/// other end and back, rad (the two ends, where it reverses, are not sampled: the velocities
/// there grow without bound at a lock; the course's marks show them); for a slider, its
/// coordinate, m. Every axis carries its SI unit. A position where the linkage fails leaves a
/// gap, and so does a value beyond ±10³⁰⁰ (an axis must have a finite width for its ticks to
/// be placed).
///
/// The time is bounded by the picture: [`Style::samples`] analyses for the curves, at most
/// [`MAX_PLAN_POSITIONS`] marked course positions (a longer course is thinned as
/// [`plan_view`](super::plan_view) thins it), one pass over the course to check it, and
/// ticks on axes whose ends and width are finite and whose width is at least 10⁻⁹ of their
/// magnitude (so a tick's step always advances).
///
/// # Errors
/// [`Error::OutOfRange`] or [`Error::NonFinite`] naming the field of a bad style
/// ([`Style::check`]); [`Error::Drawing`](crate::Error::Drawing) for a back-end failure;
/// [`Error::OutOfRange`] or [`Error::NonFinite`] for a bad course; [`Error::Description`] for
/// an output or joint that does not exist; the first position's error when no position of
/// the cycle can be solved.
///
/// # Examples
/// The shaper's balancing moment; its axis covers every value plotted:
/// ```
/// use tmm::draw::{diagram, Course, Diagram, Style};
/// use tmm::linkage::{bundled, Output, Plan};
/// let plan = Plan::new(&bundled::shaper())?;
/// let course = Course::new(&plan, Some(&Output::Slide("Q".into())), 12, 10.0)?;
/// let chart = diagram(&plan, &course, &Diagram::Balance, &Default::default())?;
/// let p = &chart.panels[0];
/// assert_eq!(p.y_label, "M_b, N·m");
/// assert!(p.series[0].1.iter().all(|[_, y]| p.y_range[0] <= *y && *y <= p.y_range[1]));
/// assert_eq!(p.marks.len(), 12);
/// let bad = Diagram::Kinematics(Output::Angle("no such link".into()));
/// assert!(diagram(&plan, &course, &bad, &Default::default()).is_err());
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn diagram(plan: &Plan, course: &Course, diagram: &Diagram, style: &Style) -> Result<Chart> {
    style.check()?;
    course.check()?;
    check(plan, diagram)?;
    let Abscissa {
        axis,
        samples,
        xs,
        range: x_range,
        label: x_label,
        unit: input_unit,
    } = Abscissa::new(plan, course, style.samples);

    // What each panel plots at one position.
    let specs = panel_specs(plan, diagram, input_unit)?;
    let mut a = plan.solver();
    let eval = |a: &mut Solver<'_>, m: Motion| -> Result<Values> {
        specs_values(plan, diagram, a, Inputs::one(m))
    };
    let data = sampled(samples.iter().map(|&m| eval(&mut a, m)))?;
    let marks_data: Vec<(usize, f64, Option<Values>)> =
        thin(course.inputs.len(), MAX_PLAN_POSITIONS)
            .map(|k| {
                let m = course.inputs[k];
                (k, axis.x(m), eval(&mut a, m).ok())
            })
            .collect();
    Curves::new(diagram, &xs, &data, &marks_data, x_range, &x_label).chart(&specs, style)
}

/// The values of every sample (`None` where its position failed), or the first error when
/// no position could be solved.
pub(super) fn sampled(values: impl Iterator<Item = Result<Values>>) -> Result<Vec<Option<Values>>> {
    let mut first_error = None;
    let data: Vec<Option<Values>> = values
        .map(|v| {
            v.map_err(|e| {
                first_error.get_or_insert(e);
            })
            .ok()
        })
        .collect();
    if data.iter().all(Option::is_none) {
        return Err(first_error.unwrap_or_else(|| drawing("a diagram", "no position")));
    }
    Ok(data)
}

/// The abscissa of a diagram: what the input has done since the course's first position.
#[derive(Debug, Clone, Copy)]
enum Axis {
    /// A crank turning: the angle turned from `start` in the sense `sense` (±1), in [0, 2π).
    Turn { start: f64, sense: f64 },
    /// A rocking input: the angle swept from `from` to `to` and back, in [0, 2|to − from|].
    Rocking { from: f64, to: f64 },
    /// A slider: its coordinate.
    Slide,
}

impl Axis {
    /// The abscissa of the input `m`.
    fn x(self, m: Motion) -> f64 {
        match self {
            Self::Turn { start, sense } => (sense * (m.value - start)).rem_euclid(TAU),
            Self::Rocking { from, to } => {
                let out = (m.value - from).abs();
                if m.rate * (to - from) < 0.0 {
                    2.0 * (to - from).abs() - out
                } else {
                    out
                }
            }
            Self::Slide => m.value,
        }
    }
}

/// The inputs sampled along a diagram's abscissa, and the axis's range and label.
struct Abscissa {
    axis: Axis,
    samples: Vec<Motion>,
    xs: Vec<f64>,
    range: [f64; 2],
    label: String,
    unit: &'static str,
}

impl Abscissa {
    /// `n` samples (one more to close a turn): over a turn of a crank from the course's
    /// first position in its sense; over a rocking input's sweep out and back (the two ends,
    /// where it reverses, left out: the samples sit in the middles of n equal steps); over
    /// the range of a slider's course.
    fn new(plan: &Plan, course: &Course, n: usize) -> Self {
        let first = course.inputs[0];
        if let Sweep::Rocking { from, to } = course.sweep {
            let w = course
                .inputs
                .iter()
                .map(|m| m.rate.abs())
                .fold(0.0, f64::max);
            let w = if w > 0.0 { w } else { 1.0 };
            let (span, sense) = ((to - from).abs(), (to - from).signum());
            #[allow(clippy::cast_precision_loss)]
            let samples: Vec<Motion> = (0..n)
                .map(|i| {
                    let s = (i as f64 + 0.5) * 2.0 * span / n as f64;
                    if s <= span {
                        Motion::new(from + sense * s, sense * w, 0.0)
                    } else {
                        Motion::new(to - sense * (s - span), -sense * w, 0.0)
                    }
                })
                .collect();
            let axis = Axis::Rocking { from, to };
            return Self {
                xs: samples.iter().map(|&m| axis.x(m)).collect(),
                samples,
                axis,
                range: pad(0.0, 2.0 * span, 0.0),
                label: format!(
                    "φ1 swept from {from:.3} rad to {to:.3} rad and back (rocking), rad"
                ),
                unit: "rad",
            };
        }
        let mut samples = path_inputs(plan, course, n);
        if plan.input_is_crank() {
            let sense = if first.rate < 0.0 { -1.0 } else { 1.0 };
            let axis = Axis::Turn {
                start: first.value,
                sense,
            };
            let mut xs: Vec<f64> = samples.iter().map(|&m| axis.x(m)).collect();
            // Close the turn: position 0 again at 2π.
            samples.push(samples[0]);
            xs.push(TAU);
            return Self {
                axis,
                samples,
                xs,
                range: [0.0, TAU],
                label: format!(
                    "φ1 turned {} from position 0 (φ1 = {:.3} rad), rad",
                    if sense < 0.0 {
                        "clockwise"
                    } else {
                        "counter-clockwise"
                    },
                    first.value
                ),
                unit: "rad",
            };
        }
        let xs: Vec<f64> = samples.iter().map(|&m| Axis::Slide.x(m)).collect();
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Self {
            axis: Axis::Slide,
            samples,
            xs,
            range: pad(lo, hi, 0.0),
            label: "s1, m".to_owned(),
            unit: "m",
        }
    }
}

/// The sampled values of a diagram, for drawing its panels.
pub(super) struct Curves<'a> {
    /// The abscissa of every sample.
    pub xs: &'a [f64],
    /// Every sample's values (per panel, per curve), `None` where the position failed.
    pub data: &'a [Option<Values>],
    /// The course positions: number, abscissa and values.
    pub marks: &'a [(usize, f64, Option<Values>)],
    pub x_range: [f64; 2],
    pub x_label: &'a str,
    pub hodograph: bool,
    pub reactions: bool,
}

impl<'a> Curves<'a> {
    /// The curves of `diagram`: the samples' abscissae `xs` and values `data`, the course
    /// positions `marks`, the abscissa's range and label.
    pub(super) fn new(
        diagram: &Diagram,
        xs: &'a [f64],
        data: &'a [Option<Values>],
        marks: &'a [(usize, f64, Option<Values>)],
        x_range: [f64; 2],
        x_label: &'a str,
    ) -> Self {
        Self {
            xs,
            data,
            marks,
            x_range,
            x_label,
            hodograph: matches!(diagram, Diagram::Hodograph(_)),
            reactions: matches!(diagram, Diagram::Reactions),
        }
    }

    /// The chart of the panels `specs`, drawn in `style`, its SVG checked for a non-finite
    /// number.
    pub(super) fn chart(&self, specs: &[Spec], style: &Style) -> Result<Chart> {
        let mut panels: Vec<Panel> = specs
            .iter()
            .enumerate()
            .map(|(p, spec)| self.panel(p, spec))
            .collect();
        let svg = render(&mut panels, style, self.hodograph)?;
        super::primitives::finite_numbers(&svg)?;
        Ok(Chart { svg, panels })
    }

    /// Panel `p` of `spec`: its curves, its marks and the ranges that cover them.
    pub(super) fn panel(&self, p: usize, spec: &Spec) -> Panel {
        let (xs, data, marks_data, x_range, hodograph) =
            (self.xs, self.data, self.marks, self.x_range, self.hodograph);
        let mut series = Vec::with_capacity(spec.series.len());
        for (s, name) in spec.series.iter().enumerate() {
            let mut pts = Vec::with_capacity(data.len());
            let mut prev: Option<f64> = None;
            for (x, d) in xs.iter().zip(data) {
                let Some(d) = d else {
                    prev = None;
                    continue;
                };
                let mut y = d[p][s];
                if spec.unwrap {
                    if let Some(py) = prev {
                        y = py + wrap(y - py);
                    }
                    prev = Some(y);
                }
                let q = if hodograph {
                    [d[p][0], d[p][1]]
                } else {
                    [*x, y]
                };
                if placeable(q) {
                    pts.push(q);
                } else {
                    prev = None;
                }
            }
            series.push((name.clone(), pts));
            if hodograph {
                break;
            }
        }
        let marks: Vec<(usize, [f64; 2])> = marks_data
            .iter()
            .filter_map(|(k, x, d)| {
                let d = d.as_ref()?;
                if hodograph {
                    return Some(vec![(*k, [d[p][0], d[p][1]])]);
                }
                let ys = if self.reactions {
                    d[p].clone()
                } else {
                    vec![d[p][0]]
                };
                Some(
                    ys.into_iter()
                        .enumerate()
                        .map(|(s, y)| {
                            // On an unwrapped angle, the mark follows the curve's turn.
                            let y = match (spec.unwrap, series.get(s)) {
                                (true, Some((_, c))) => nearest_turn(y, *x, c),
                                _ => y,
                            };
                            (*k, [*x, y])
                        })
                        .collect(),
                )
            })
            .flatten()
            // A position whose abscissa or value is not a finite number (an input too large
            // to place on the axis) or lies beyond the axes' limit has no place on the chart:
            // its mark is left out.
            .filter(|(_, m)| placeable(*m))
            .collect();
        let all = series
            .iter()
            .flat_map(|(_, s)| s.iter())
            .chain(marks.iter().map(|(_, m)| m));
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in all {
            for i in 0..2 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
        let (xr, yr) = if hodograph {
            (
                pad(lo[0].min(0.0), hi[0].max(0.0), 0.05),
                pad(lo[1].min(0.0), hi[1].max(0.0), 0.05),
            )
        } else {
            (x_range, pad(lo[1], hi[1], 0.05))
        };
        Panel {
            title: spec.title.clone(),
            x_label: if hodograph {
                spec.x_label.clone()
            } else {
                self.x_label.to_owned()
            },
            y_label: spec.y_label.clone(),
            x_range: xr,
            y_range: yr,
            x_pixels: [0.0; 2],
            y_pixels: [0.0; 2],
            series,
            marks,
        }
    }
}

/// The value `y` moved by whole turns to the curve `c` at `x`.
fn nearest_turn(y: f64, x: f64, c: &[[f64; 2]]) -> f64 {
    let near = c
        .iter()
        .min_by(|a, b| (a[0] - x).abs().total_cmp(&(b[0] - x).abs()))
        .map_or(y, |p| p[1]);
    y + TAU * ((near - y) / TAU).round()
}

/// An angle difference brought into (−π, π].
fn wrap(d: f64) -> f64 {
    d - TAU * (d / TAU).round()
}

/// The largest magnitude a diagram's axis reaches: a value beyond it is left out, as a
/// failed position is.
///
/// The chart's ticks are placed by stepping across the axis's width: an axis whose ends
/// differ by more than `f64::MAX` (values near ±10³⁰⁸ of both signs) has an infinite width,
/// and its ticks would never be placed. With every value within ±10³⁰⁰ the width, its
/// margins and every pixel stay finite.
const AXIS_LIMIT: f64 = 1e300;

/// Whether the point can be placed on an axis: both coordinates finite and within
/// ±[`AXIS_LIMIT`].
fn placeable(q: [f64; 2]) -> bool {
    q.iter().all(|v| v.abs() <= AXIS_LIMIT)
}

/// A range around [lo, hi] with a margin of `frac` (at most 1) of its width (a flat one
/// opened up); the unit range [−1, 1] when there is no value (lo > hi, or NaN).
///
/// The ends are finite, and so is the width, which is at least 10⁻⁹ of the magnitude.
pub(super) fn pad(lo: f64, hi: f64, frac: f64) -> [f64; 2] {
    // No value (an empty panel, lo = +inf and hi = -inf) or NaN.
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return [-1.0, 1.0];
    }
    let (lo, hi) = (lo.max(-AXIS_LIMIT), hi.min(AXIS_LIMIT));
    let w = hi - lo;
    // The chart steps its tick marks by a fraction of the width: a width of a few ulps of
    // the values would never advance, so a range narrower than 1e-9 of its magnitude is
    // opened up as a flat one.
    if w > 1e-9 * lo.abs().max(hi.abs()) {
        [lo - frac * w, hi + frac * w]
    } else {
        let m = (lo.abs() * 0.1).max(1e-9);
        [lo - m, hi + m]
    }
}

/// The values at one position: per panel, per curve.
pub(super) type Values = Vec<Vec<f64>>;

/// One panel's titles and the names of its curves.
pub(super) struct Spec {
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<String>,
    unwrap: bool,
}

pub(super) fn check(plan: &Plan, d: &Diagram) -> Result<()> {
    match d {
        Diagram::Kinematics(o) | Diagram::Transfer(o) => check_output(plan, o),
        Diagram::Hodograph(j) => plan.joint_id(j).map(|_| ()),
        Diagram::Balance | Diagram::Reactions | Diagram::Friction => Ok(()),
    }
}

/// Checks that an output names something of the plan.
fn check_output(plan: &Plan, o: &Output) -> Result<()> {
    match o {
        Output::Angle(n) => plan.link_id(n).map(|_| ()),
        Output::Slide(n) => {
            if plan.is_prismatic(n)? {
                Ok(())
            } else {
                Err(Error::Description {
                    item: format!("joint {n}"),
                    problem: "is not prismatic: it has no slide".to_owned(),
                })
            }
        }
        Output::X(n) | Output::Y(n) => plan
            .joint_id(n)
            .map(|_| ())
            .or_else(|_| plan.point_id(n).map(|_| ())),
    }
}

fn output_name(o: &Output) -> (String, &'static str) {
    match o {
        Output::Angle(n) => (format!("angle of {n}"), "rad"),
        Output::Slide(n) => (format!("slide of {n}"), "m"),
        Output::X(n) => (format!("x of {n}"), "m"),
        Output::Y(n) => (format!("y of {n}"), "m"),
    }
}

pub(super) fn panel_specs(plan: &Plan, d: &Diagram, input_unit: &str) -> Result<Vec<Spec>> {
    let name = plan.name();
    let one = |title: String, y: String, series: Vec<String>| Spec {
        title,
        x_label: String::new(),
        y_label: y,
        series,
        unwrap: false,
    };
    Ok(match d {
        Diagram::Kinematics(o) | Diagram::Transfer(o) => {
            let (what, u) = output_name(o);
            let unwrap = matches!(o, Output::Angle(_));
            let transfer = matches!(d, Diagram::Transfer(_));
            let labels: [(String, String); 3] = if transfer {
                [
                    (what.clone(), format!("value, {u}")),
                    (
                        format!("first transfer function of the {what}"),
                        format!("d/dq1, {u}/{input_unit}"),
                    ),
                    (
                        format!("second transfer function of the {what}"),
                        format!("d²/dq1², {u}/{input_unit}²"),
                    ),
                ]
            } else {
                [
                    (what.clone(), format!("position, {u}")),
                    (
                        format!("velocity of the {what}"),
                        format!("velocity, {u}/s"),
                    ),
                    (
                        format!("acceleration of the {what}"),
                        format!("acceleration, {u}/s²"),
                    ),
                ]
            };
            labels
                .into_iter()
                .enumerate()
                .map(|(i, (t, y))| Spec {
                    title: format!("{name}: {t}"),
                    x_label: String::new(),
                    y_label: y,
                    series: vec![t],
                    unwrap: unwrap && i == 0,
                })
                .collect()
        }
        Diagram::Balance if plan.input_count() == 2 => {
            // Each input's own: a crank's moment, N·m, a slider's force, N.
            let units: Vec<&str> = super::diagrams_two::input_is_crank(plan)
                .into_iter()
                .map(|crank| if crank { "N·m" } else { "N" })
                .collect();
            let y = if units[0] == units[1] {
                format!("M_b1, M_b2, {}", units[0])
            } else {
                format!("M_b1, {}; F_b2, {}", units[0], units[1])
            };
            let links = plan.input_links();
            let names = plan.link_names();
            vec![one(
                format!("{name}: balancing moments of the two inputs"),
                y,
                links
                    .iter()
                    .enumerate()
                    .map(|(i, l)| format!("input {} ({})", i + 1, names[l.index()]))
                    .collect(),
            )]
        }
        Diagram::Balance => {
            let (t, y) = if plan.input_is_crank() {
                ("balancing moment", "M_b, N·m")
            } else {
                ("driving force", "F_b, N")
            };
            vec![one(
                format!("{name}: {t}"),
                y.to_owned(),
                vec![t.to_owned()],
            )]
        }
        Diagram::Reactions => vec![one(
            format!("{name}: reactions in the joints"),
            "|R|, N".to_owned(),
            plan.joint_names()
                .iter()
                .map(|j| format!("R in {j}"))
                .collect(),
        )],
        Diagram::Friction => vec![
            one(
                format!("{name}: instantaneous efficiency"),
                "η = P_useful / P_drive, 1".to_owned(),
                vec!["efficiency".to_owned()],
            ),
            one(
                format!("{name}: power lost in the joints"),
                "P_lost, W".to_owned(),
                plan.joint_names()
                    .iter()
                    .map(|j| format!("lost in {j}"))
                    .collect(),
            ),
        ],
        Diagram::Hodograph(j) => {
            let r = format!("R in {j}");
            vec![Spec {
                title: format!("{name}: hodograph of the reaction in {j}"),
                x_label: format!("{r}, x component, N"),
                y_label: format!("{r}, y component, N"),
                series: vec![r],
                unwrap: false,
            }]
        }
    })
}

/// The values of every panel's curves at one position (one input's motion, or two).
pub(super) fn specs_values(
    plan: &Plan,
    d: &Diagram,
    solver: &mut Solver<'_>,
    inputs: Inputs,
) -> Result<Vec<Vec<f64>>> {
    let m = inputs.as_slice()[0];
    let finite = |v: Vec<Vec<f64>>| {
        if v.iter().flatten().all(|x| x.is_finite()) {
            Ok(v)
        } else {
            Err(Error::Overflow {
                what: "a diagram's value",
            })
        }
    };
    finite(match d {
        Diagram::Kinematics(o) => {
            let v = if inputs.len() == 1 {
                plan.output(o, m)?
            } else {
                read_output(solver.kinematics(inputs)?, o)?
            };
            vec![vec![v.value], vec![v.rate], vec![v.accel]]
        }
        Diagram::Transfer(o) => {
            let v = plan.transfer(o, m.value)?;
            vec![vec![v.value], vec![v.rate], vec![v.accel]]
        }
        Diagram::Balance if inputs.len() == 1 => vec![vec![solver.analyse(m)?.balance(0)?.value]],
        Diagram::Balance => {
            let a = solver.analyse(inputs)?;
            vec![(0..inputs.len())
                .map(|i| Ok(a.balance(i)?.value))
                .collect::<Result<_>>()?]
        }
        Diagram::Reactions => {
            let a = solver.analyse(inputs)?;
            vec![plan
                .joint_ids()
                .map(|j| Ok(a.reaction(j)?.force.norm()))
                .collect::<Result<_>>()?]
        }
        Diagram::Friction => {
            let a = solver.analyse(inputs)?;
            let e = a.efficiency()?;
            let lost = plan
                .joint_ids()
                .map(|j| Ok(a.friction(j)?.power_lost))
                .collect::<Result<_>>()?;
            let mut v = finite(vec![lost])?;
            // η has no value where the drive gives no power: the efficiency's curve leaves a
            // gap there (a NaN is no point of a curve, and no mark), the lost powers drawn.
            let eta = e.eta.filter(|x| x.is_finite()).unwrap_or(f64::NAN);
            v.insert(0, vec![eta]);
            return Ok(v);
        }
        Diagram::Hodograph(j) => {
            let r = solver.analyse(inputs)?.reaction(j)?;
            vec![vec![r.force.x, r.force.y]]
        }
    })
}

/// The value, rate and acceleration of `o` at a solved position.
fn read_output(k: &Kinematics<'_>, o: &Output) -> Result<Motion> {
    Ok(match o {
        Output::Angle(n) => k.link(n.as_str())?,
        Output::Slide(n) => k.slide(n.as_str())?,
        Output::X(n) | Output::Y(n) => {
            let p = k.joint(n.as_str()).or_else(|_| k.point(n.as_str()))?;
            if matches!(o, Output::Y(_)) {
                Motion::new(p.p.y, p.v.y, p.a.y)
            } else {
                Motion::new(p.p.x, p.v.x, p.a.x)
            }
        }
    })
}

const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 95, 168),
    RGBColor(192, 57, 43),
    RGBColor(46, 139, 87),
    RGBColor(125, 60, 152),
    RGBColor(211, 84, 0),
    RGBColor(19, 141, 144),
    RGBColor(127, 90, 58),
    RGBColor(176, 58, 122),
];

pub(super) fn render(panels: &mut [Panel], style: &Style, hodograph: bool) -> Result<String> {
    let fail = |e: &dyn std::fmt::Display| drawing("a diagram", e.to_string());
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (style.width, style.height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail(&e))?;
        let areas = root.split_evenly((panels.len(), 1));
        for (panel, area) in panels.iter_mut().zip(&areas) {
            draw_panel(panel, area, hodograph).map_err(|e| fail(&e))?;
        }
        root.present().map_err(|e| fail(&e))?;
    }
    Ok(svg)
}

type DrawResult<T> = std::result::Result<T, DrawingAreaErrorKind<std::io::Error>>;

fn draw_panel(
    panel: &mut Panel,
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    hodograph: bool,
) -> DrawResult<()> {
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 15))
        .margin(8)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(
            panel.x_range[0]..panel.x_range[1],
            panel.y_range[0]..panel.y_range[1],
        )?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .label_style(("sans-serif", 11))
        .axis_desc_style(("sans-serif", 12))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    let (xp, yp) = chart.plotting_area().get_pixel_range();
    panel.x_pixels = [f64::from(xp.start), f64::from(xp.end)];
    panel.y_pixels = [f64::from(yp.end), f64::from(yp.start)];
    let several = panel.series.len() > 1;
    for (s, (name, pts)) in panel.series.iter().enumerate() {
        let c = COLOURS[s % COLOURS.len()];
        // A gap in x (a failed position) breaks the line.
        let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        let step = if hodograph {
            f64::INFINITY
        } else {
            let n = pts.len().max(2);
            #[allow(clippy::cast_precision_loss)]
            let s = 1.5 * (panel.x_range[1] - panel.x_range[0]) / (n - 1) as f64;
            s
        };
        // A hodograph breaks where the reaction jumps (a load switching on): a step far
        // longer than the typical one.
        let jump = if hodograph {
            let mut steps: Vec<f64> = pts
                .windows(2)
                .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
                .collect();
            steps.sort_by(f64::total_cmp);
            20.0 * steps.get(steps.len() / 2).copied().unwrap_or(f64::INFINITY)
        } else {
            f64::INFINITY
        };
        let mut last: Option<[f64; 2]> = None;
        for p in pts {
            if let Some(l) = last
                && (p[0] - l[0] > step || (p[0] - l[0]).hypot(p[1] - l[1]) > jump)
            {
                runs.push(Vec::new());
            }
            last = Some(*p);
            if let Some(r) = runs.last_mut() {
                r.push((p[0], p[1]));
            }
        }
        for (i, run) in runs.into_iter().enumerate() {
            let series = chart.draw_series(LineSeries::new(run, c.stroke_width(2)))?;
            if several && i == 0 {
                series.label(name.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2))
                });
            }
        }
    }
    if hodograph {
        chart.draw_series(std::iter::once(Cross::new(
            (0.0, 0.0),
            5,
            BLACK.stroke_width(1),
        )))?;
    }
    chart.draw_series(
        panel
            .marks
            .iter()
            .map(|(_, m)| Circle::new((m[0], m[1]), 3, BLACK.filled())),
    )?;
    let mut numbered = Vec::new();
    for (k, m) in &panel.marks {
        if !numbered.contains(k) {
            numbered.push(*k);
            chart.draw_series(std::iter::once(Text::new(
                k.to_string(),
                (m[0], m[1]),
                ("sans-serif", 10).into_font().color(&BLACK),
            )))?;
        }
    }
    if several {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.6))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()?;
    }
    Ok(())
}
