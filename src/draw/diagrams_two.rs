//! The diagrams of a linkage with two inputs, along a path of its inputs.

use super::diagrams::{check, pad, panel_specs, sampled, specs_values, Curves, Values};
use super::plan_view::{thin, MAX_PLAN_POSITIONS};
use super::{Chart, Diagram, Style};
use crate::error::{Error, Result};
use crate::linkage::{LinkId, Plan, TwoInputCourse, TwoInputShape};

/// Whether each input of `plan` is a crank (hinged to the frame) rather than a slider.
pub(super) fn input_is_crank(plan: &Plan) -> Vec<bool> {
    plan.input_links()
        .into_iter()
        .map(|link| {
            !plan.joint_ids().any(|j| {
                plan.joint_links(j)
                    .is_ok_and(|l| l.contains(&link) && l.contains(&LinkId::FRAME))
                    && plan.is_prismatic(j).unwrap_or(false)
            })
        })
        .collect()
}

/// Draws `diagram` for a linkage with two inputs along the path of `course`
/// ([`TwoInputShape::Path`]: the positions in the order the inputs run through them, as
/// [`TwoInputCourse::laws`] or [`TwoInputCourse::around_reference`] make them), the course
/// positions marked and numbered.
///
/// The abscissa is the path's parameter: the length travelled along the path in the plane of
/// the two inputs from position 0, s = Σ √(Δq₁² + Δq₂²) — rad when both inputs are cranks,
/// m when both are sliders; for one of each (whose coordinates have no common unit), the
/// position's number along the path. [`Diagram::Balance`] plots both inputs' balancing
/// moments (a slider's driving force), M_b1 and M_b2, one curve each;
/// [`Diagram::Kinematics`] an output's position, velocity and acceleration at the course's
/// input rates and accelerations (the x or y of a joint or named point: where it is and how
/// it moves); [`Diagram::Reactions`], [`Diagram::Hodograph`] and [`Diagram::Friction`] as for
/// one input. Every axis carries its SI unit; a position where the linkage fails leaves a gap.
///
/// Bounded by the picture: at most [`Style::samples`] positions of the course analysed for the
/// curves (a longer course is thinned evenly; the curves join the positions analysed), at
/// most [`MAX_PLAN_POSITIONS`] marked, and one pass over the course to check it.
///
/// # Errors
/// [`Error::Description`] (`"field second_input"`) for a linkage with one input (use
/// [`diagram`](super::diagram)); [`Error::Description`] (`"course"`) for a grid, whose
/// positions run along no path, and for [`Diagram::Transfer`] (with two inputs an output has
/// a derivative with respect to each: [`Diagram::Kinematics`] gives its motion along the
/// path); the errors of [`diagram`](super::diagram) for a bad style, course, output or
/// joint; the first position's error when no position of the path can be solved.
///
/// # Examples
/// Both balancing moments of the five-bar robot round a loop about its reference pose, each
/// plotted value the analysis's own:
/// ```
/// use tmm::draw::{diagram_two, Diagram, Style};
/// use tmm::linkage::{bundled, Plan, TwoInputCourse};
/// let plan = Plan::new(&bundled::five_bar_robot())?;
/// let course = TwoInputCourse::around_reference(&plan, 24, 2.0)?;
/// let chart = diagram_two(&plan, &course, &Diagram::Balance, &Style::default())?;
/// let p = &chart.panels[0];
/// assert_eq!(p.series.len(), 2);
/// let a = plan.analyse(course.inputs[5])?;
/// assert_eq!(p.series[1].1[5][1], a.balance(1)?.value);
/// assert!(p.x_label.contains("rad"));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn diagram_two(
    plan: &Plan,
    course: &TwoInputCourse,
    diagram: &Diagram,
    style: &Style,
) -> Result<Chart> {
    style.check()?;
    if plan.input_count() != 2 {
        return Err(Error::Description {
            item: "field second_input".to_owned(),
            problem: "a diagram along a path of two inputs needs a linkage with two inputs \
                      (`draw::diagram` draws one input's cycle)"
                .to_owned(),
        });
    }
    course.check()?;
    if let TwoInputShape::Grid { n1, n2 } = course.shape {
        return Err(Error::Description {
            item: "course".to_owned(),
            problem: format!(
                "is a grid of {n1} × {n2} positions, which runs along no path: a diagram needs \
                 a path of the inputs (TwoInputCourse::laws or around_reference)"
            ),
        });
    }
    if matches!(diagram, Diagram::Transfer(_)) {
        return Err(Error::Description {
            item: "course".to_owned(),
            problem: "has two inputs, and an output then has a transfer function with respect \
                      to each: Diagram::Kinematics gives its motion along the path"
                .to_owned(),
        });
    }
    check(plan, diagram)?;
    let (xs, unit) = abscissa(plan, course);
    let label = match unit {
        "1" => "position along the path of the inputs (q1, q2), its number, 1".to_owned(),
        u => format!("length along the path of the inputs (q1, q2) from position 0, {u}"),
    };
    let specs = panel_specs(plan, diagram, unit)?;
    let mut solver = plan.solver();
    let mut eval = |k: usize| specs_values(plan, diagram, &mut solver, course.inputs[k]);
    let n = course.inputs.len();
    let sampled_at: Vec<usize> = thin(n, style.samples).collect();
    let data = sampled(sampled_at.iter().map(|&k| eval(k)))?;
    // The marks reuse the analysed positions where they coincide.
    let marks: Vec<(usize, f64, Option<Values>)> = thin(n, MAX_PLAN_POSITIONS)
        .map(|k| {
            let v = match sampled_at.binary_search(&k) {
                Ok(i) => data[i].clone(),
                Err(_) => eval(k).ok(),
            };
            (k, xs[k], v)
        })
        .collect();
    let sample_xs: Vec<f64> = sampled_at.iter().map(|&k| xs[k]).collect();
    let x_range = pad(xs[0], xs[n - 1], 0.0);
    Curves::new(diagram, &sample_xs, &data, &marks, x_range, &label).chart(&specs, style)
}

/// The abscissa of every position of a path and its unit: the length along the path in the
/// plane of the inputs ("rad" for two cranks, "m" for two sliders), or the position's number
/// ("1") for a crank and a slider. A step too long for `f64` leaves the length where it was.
fn abscissa(plan: &Plan, course: &TwoInputCourse) -> (Vec<f64>, &'static str) {
    let kinds = input_is_crank(plan);
    #[allow(clippy::cast_precision_loss)]
    if kinds[0] != kinds[1] {
        return ((0..course.inputs.len()).map(|k| k as f64).collect(), "1");
    }
    let mut s = 0.0;
    let mut xs = Vec::with_capacity(course.inputs.len());
    let mut last: Option<[f64; 2]> = None;
    for i in &course.inputs {
        let q = [i.as_slice()[0].value, i.as_slice()[1].value];
        if let Some(l) = last {
            let step = (q[0] - l[0]).hypot(q[1] - l[1]);
            if (s + step).is_finite() {
                s += step;
            }
        }
        last = Some(q);
        xs.push(s);
    }
    (xs, if kinds[0] { "rad" } else { "m" })
}
