//! Speed against accuracy across the crate: work-precision charts as SVG and their data as
//! CSV, all from the crate's own runs.
//!
//! `cargo run --release -p tmm-bench --example work_precision [output folder]`
//! (default `target/tmm-charts/work-precision`; the README's charts come from
//! `cargo run --release -p tmm-bench --example work_precision docs/charts`, from the root).
//!
//! - `dynamics_work_precision.svg`: each stepper on three machines, error at the final time
//!   against evaluations of q̈ and against wall time;
//! - `dynamics_stability.svg`: the growth factor per step of finite increments on a damped
//!   oscillator against Ω = ωh with the limits min(4ζ, 1/ζ) marked, and RK4's on the negative
//!   real axis with its limit hλ ≈ −2.785;
//! - `kinetostatics.svg`: the error of the closed-form dyads and of the general LU solve
//!   against the conditioning as each group nears its singularity, and the time per call;
//! - `kinematics.svg`: the error of the 3-point derivatives and of the trapezoid rule against
//!   the number of positions per cycle, beside the exact transfer functions.
//!
//! The error axes are reproducible run to run (the same seeded cases, the same arithmetic);
//! the times vary with the machine. `tests/work_precision/mod.rs` asserts the observed orders
//! from the same functions and from the committed CSV files.

use std::error::Error;
use std::fs;
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

#[path = "../../tests/work_precision/dd.rs"]
mod dd;
#[path = "../../tests/work_precision/dynamics_data.rs"]
mod dynamics_data;
#[path = "../../tests/work_precision/fit.rs"]
#[allow(dead_code)] // its CSV reader serves the test
mod fit;
#[path = "../../tests/kinetostatics/general_solve.rs"]
#[allow(dead_code)]
mod general_solve;
#[path = "../../tests/work_precision/kinematics_data.rs"]
mod kinematics_data;
#[path = "../../tests/work_precision/kinetostatics_data.rs"]
mod kinetostatics_data;
#[path = "../../tests/work_precision/rng.rs"]
mod rng;

type Res<T> = std::result::Result<T, Box<dyn Error>>;
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

const COLOURS: [RGBColor; 5] = [
    RED,
    BLUE,
    RGBColor(0, 150, 0),
    MAGENTA,
    RGBColor(230, 140, 0),
];

/// One line of a log–log panel.
struct Curve {
    label: String,
    colour: RGBColor,
    points: Vec<(f64, f64)>,
    /// Draw markers at the points (data) or not (a guide line).
    markers: bool,
}

/// Decades enclosing the positive values.
fn log_range(v: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = v
        .filter(|x| *x > 0.0 && x.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    if lo > hi {
        return 1e-16..1.0;
    }
    10f64.powf(lo.log10().floor())..10f64.powf(hi.log10().ceil())
}

fn loglog(
    area: &Area,
    title: &str,
    axes: [&str; 2],
    legend: SeriesLabelPosition,
    curves: &[Curve],
) -> Res<()> {
    let [x_desc, y_desc] = axes;
    let xr = log_range(curves.iter().flat_map(|c| c.points.iter().map(|p| p.0)));
    let yr = log_range(curves.iter().flat_map(|c| c.points.iter().map(|p| p.1)));
    let mut ch = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 16))
        .margin(8)
        .x_label_area_size(35)
        .y_label_area_size(55)
        .build_cartesian_2d(xr.log_scale(), yr.log_scale())?;
    ch.configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 11))
        .light_line_style(TRANSPARENT)
        .draw()?;
    for c in curves {
        let colour = c.colour;
        let pts: Vec<(f64, f64)> = c
            .points
            .iter()
            .copied()
            .filter(|p| p.0 > 0.0 && p.1 > 0.0)
            .collect();
        let width = if c.markers { 2 } else { 1 };
        ch.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(width)))?
            .label(c.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
        if c.markers {
            ch.draw_series(pts.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
        }
    }
    ch.configure_series_labels()
        .label_font(("sans-serif", 11))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(legend)
        .draw()?;
    Ok(())
}

fn dynamics(dir: &Path) -> Res<()> {
    use dynamics_data::{asymptotic, Line, MACHINES, METHODS};
    let lines = dynamics_data::work_precision(true)?;
    fs::write(
        dir.join("dynamics_work_precision.csv"),
        dynamics_data::to_csv(&lines),
    )?;
    println!("Dynamics: error at the final time (observed order = slope of log error vs log h):");
    let path = dir.join("dynamics_work_precision.svg");
    let root = SVGBackend::new(&path, (1000, 1500)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Work-precision of the steppers: error at the final time vs cost",
        ("sans-serif", 20),
    )?;
    let panels = root.split_evenly((4, 2));
    for (m, machine) in MACHINES.into_iter().enumerate() {
        let ls: Vec<&Line> = lines.iter().filter(|l| l.machine == machine).collect();
        for l in &ls {
            let a = asymptotic(l);
            let order = if l.method == METHODS[2] {
                String::from("(adaptive)")
            } else {
                let h: Vec<f64> = a.iter().map(|p| p.parameter).collect();
                let e: Vec<f64> = a.iter().map(|p| p.error).collect();
                format!("observed order {:.2}", fit::slope(&h, &e))
            };
            let row: Vec<String> = l
                .points
                .iter()
                .map(|p| format!("{:.1e}/{}", p.error, p.evaluations))
                .collect();
            println!(
                "  {machine:<19} {:<18} {order:<22} (reference error {:.0e}) error/evaluations: {}",
                l.method,
                l.reference_error,
                row.join(" ")
            );
        }
        let reference = if ls[0].reference_error == 0.0 {
            "exact solution".to_owned()
        } else {
            format!("reference error {:.0e}", ls[0].reference_error)
        };
        for (k, (ylabel, pick)) in [
            (
                "evaluations of q''",
                (|p: &dynamics_data::Point| p.evaluations as f64)
                    as fn(&dynamics_data::Point) -> f64,
            ),
            ("wall time, s", |p: &dynamics_data::Point| p.seconds),
        ]
        .into_iter()
        .enumerate()
        {
            let curves: Vec<Curve> = ls
                .iter()
                .enumerate()
                .map(|(i, l)| Curve {
                    label: l.method.to_owned(),
                    colour: COLOURS[i],
                    points: l
                        .points
                        .iter()
                        .map(|p| (p.error.max(1e-17), pick(p)))
                        .collect(),
                    markers: true,
                })
                .collect();
            loglog(
                &panels[2 * m + k],
                &format!("{machine} ({reference})"),
                ["error at the final time", ylabel],
                SeriesLabelPosition::LowerLeft,
                &curves,
            )?;
        }
    }
    root.present()?;
    Ok(())
}

fn stability(dir: &Path) -> Res<()> {
    use dynamics_data::{finite_increment_limit, ZETAS};
    let st = dynamics_data::stability()?;
    let (fi, rk) = dynamics_data::stability_csv(&st);
    fs::write(dir.join("stability_finite_increments.csv"), fi)?;
    fs::write(dir.join("stability_rk4.csv"), rk)?;
    println!("Stability (where the growth per step crosses 1):");
    for (z, c) in &st.fi_limits {
        println!(
            "  finite increments, ζ = {z}: Ω = {c:.6} (min(4ζ, 1/ζ) = {:.6})",
            finite_increment_limit(*z)
        );
    }
    println!("  RK4 on the negative real axis: hλ = {:.6}", st.rk4_limit);

    let path = dir.join("dynamics_stability.svg");
    let root = SVGBackend::new(&path, (1000, 450)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(560);
    let mut ch = ChartBuilder::on(&left)
        .caption(
            "Finite increments on x'' + 2ζωx' + ω²x = 0: growth per step",
            ("sans-serif", 15),
        )
        .margin(8)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(0.0..4.0, 0.0..2.0)?;
    ch.configure_mesh()
        .x_desc("Ω = ωh")
        .y_desc("spectral radius")
        .light_line_style(TRANSPARENT)
        .draw()?;
    ch.draw_series(LineSeries::new(
        [(0.0, 1.0), (4.0, 1.0)],
        BLACK.stroke_width(1),
    ))?;
    for (i, z) in ZETAS.into_iter().enumerate() {
        let colour = COLOURS[i];
        let pts: Vec<(f64, f64)> = st
            .finite_increments
            .iter()
            .filter(|r| r.0 == z)
            .map(|r| (r.1, r.2.min(2.0)))
            .collect();
        let lim = finite_increment_limit(z);
        let label = if z == 0.0 {
            "ζ = 0 (never stable)".to_owned()
        } else {
            format!("ζ = {z}, limit Ω = {lim:.2}")
        };
        ch.draw_series(LineSeries::new(pts, colour.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
        if z > 0.0 {
            ch.draw_series(LineSeries::new(
                [(lim, 0.0), (lim, 2.0)],
                colour.mix(0.6).stroke_width(1),
            ))?;
        }
    }
    ch.configure_series_labels()
        .label_font(("sans-serif", 11))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()?;

    let mut ch = ChartBuilder::on(&right)
        .caption("RK4 on x'' = λx' (λ < 0): |R(hλ)|", ("sans-serif", 15))
        .margin(8)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(-3.5..0.0, 0.0..2.0)?;
    ch.configure_mesh()
        .x_desc("hλ")
        .y_desc("|R(hλ)|")
        .light_line_style(TRANSPARENT)
        .draw()?;
    ch.draw_series(LineSeries::new(
        [(-3.5, 1.0), (0.0, 1.0)],
        BLACK.stroke_width(1),
    ))?;
    ch.draw_series(LineSeries::new(
        st.rk4.iter().map(|&(x, g)| (x, g.min(2.0))),
        BLUE.stroke_width(2),
    ))?
    .label(format!("RK4, limit hλ = {:.3}", st.rk4_limit))
    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLUE.stroke_width(2)));
    ch.draw_series(LineSeries::new(
        [(st.rk4_limit, 0.0), (st.rk4_limit, 2.0)],
        RED.stroke_width(1),
    ))?;
    ch.configure_series_labels()
        .label_font(("sans-serif", 11))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}

fn kinetostatics(dir: &Path) -> Res<()> {
    use kinetostatics_data::{GROUPS, SOLVERS};
    let rows = kinetostatics_data::sweep(16, true)?;
    fs::write(
        dir.join("kinetostatics.csv"),
        kinetostatics_data::to_csv(&rows),
    )?;
    println!("Kinetostatics (16 random groups per δ, δ = 1 … 1e-8; error / condition, worst):");
    let path = dir.join("kinetostatics.svg");
    let root = SVGBackend::new(&path, (1000, 1050)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Dyads near their singularities: error (vs a double-double solve) and time per call",
        ("sans-serif", 18),
    )?;
    let panels = root.split_evenly((3, 2));
    for (g, group) in GROUPS.into_iter().enumerate() {
        let mut err_curves = Vec::new();
        let mut time_curves = Vec::new();
        for (s, solver) in SOLVERS.into_iter().enumerate() {
            let rs: Vec<_> = rows
                .iter()
                .filter(|r| r.group == group && r.solver == solver)
                .collect();
            let worst = rs.iter().map(|r| r.error_per_condition).fold(0.0, f64::max);
            let ns: Vec<f64> = rs.iter().map(|r| r.ns_per_call).collect();
            println!(
                "  {group} {solver:<11}: largest error {:.1e} at condition {:.1e}; error/condition ≤ {worst:.1e}; {:.0}–{:.0} ns per call",
                rs.iter().map(|r| r.error).fold(0.0, f64::max),
                rs.iter().map(|r| r.condition).fold(0.0, f64::max),
                ns.iter().copied().fold(f64::INFINITY, f64::min),
                ns.iter().copied().fold(0.0, f64::max),
            );
            err_curves.push(Curve {
                label: solver.to_owned(),
                colour: COLOURS[s],
                points: rs
                    .iter()
                    .map(|r| (r.condition, r.error.max(1e-18)))
                    .collect(),
                markers: true,
            });
            time_curves.push(Curve {
                label: solver.to_owned(),
                colour: COLOURS[s],
                points: rs.iter().map(|r| (r.condition, r.ns_per_call)).collect(),
                markers: true,
            });
        }
        let conds: Vec<f64> = rows
            .iter()
            .filter(|r| r.group == group)
            .map(|r| r.condition)
            .collect();
        let (lo, hi) = (
            conds.iter().copied().fold(f64::INFINITY, f64::min),
            conds.iter().copied().fold(0.0, f64::max),
        );
        err_curves.push(Curve {
            label: "condition × 1e-16".to_owned(),
            colour: BLACK,
            points: vec![(lo, lo * 1e-16), (hi, hi * 1e-16)],
            markers: false,
        });
        err_curves.push(Curve {
            label: "condition × 1e-14 (the test's bound)".to_owned(),
            colour: RGBColor(150, 150, 150),
            points: vec![(lo, lo * 1e-14), (hi, hi * 1e-14)],
            markers: false,
        });
        let measure = ["sin(φ3 − φ2)", "cos(φ2 − φ4)", "l_EA"][g];
        loglog(
            &panels[2 * g],
            &format!("{group}: worst relative error, {measure} → 0"),
            ["condition (closed form's Conditioning)", "error / scale"],
            SeriesLabelPosition::UpperLeft,
            &err_curves,
        )?;
        loglog(
            &panels[2 * g + 1],
            &format!("{group}: time per call (varies with the machine)"),
            ["condition", "ns per call"],
            SeriesLabelPosition::UpperRight,
            &time_curves,
        )?;
    }
    root.present()?;
    Ok(())
}

fn kinematics(dir: &Path) -> Res<()> {
    use kinematics_data::{MECHANISMS, QUANTITIES};
    let rows = kinematics_data::sweep()?;
    fs::write(dir.join("kinematics.csv"), kinematics_data::to_csv(&rows))?;
    println!("Kinematics (observed order = −slope of log error vs log N over N ≥ 96):");
    let path = dir.join("kinematics.svg");
    let root = SVGBackend::new(&path, (1000, 450)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(480);

    // Left: the exact first transfer function of the rocker beside the 3-point values from the
    // seed's 12 positions.
    let fine: Vec<(f64, f64)> = (0..=360)
        .map(|i| {
            let phi = f64::from(i).to_radians();
            kinematics_data::exact(MECHANISMS[0], phi).map(|m| (f64::from(i), m.rate))
        })
        .collect::<tmm::Result<_>>()?;
    let (h, t) = kinematics_data::table(MECHANISMS[0], 12)?;
    let d = tmm::kinematics::differentiate(&t.iter().map(|m| m.value).collect::<Vec<_>>(), h)?;
    let mut curve_csv = String::from("phi1_deg,exact_rate\n");
    for (x, y) in &fine {
        curve_csv += &format!("{x},{y:.12e}\n");
    }
    fs::write(dir.join("kinematics_transfer_function.csv"), curve_csv)?;
    let (lo, hi) = fine
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    let mut ch = ChartBuilder::on(&left)
        .caption(
            "Four-bar rocker: φ3′(φ1), exact and 3-point from 12 positions",
            ("sans-serif", 14),
        )
        .margin(8)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(0.0..360.0, (lo - 0.1)..(hi + 0.1))?;
    ch.configure_mesh()
        .x_desc("φ1, °")
        .y_desc("φ3′")
        .light_line_style(TRANSPARENT)
        .draw()?;
    ch.draw_series(LineSeries::new(fine.clone(), BLUE.stroke_width(2)))?
        .label("exact transfer function")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLUE.stroke_width(2)));
    ch.draw_series(
        d.iter()
            .enumerate()
            .map(|(i, v)| Circle::new((30.0 * i as f64, *v), 4, RED.filled())),
    )?
    .label("3-point formulas, N = 12")
    .legend(|(x, y)| Circle::new((x + 9, y), 4, RED.filled()));
    ch.configure_series_labels()
        .label_font(("sans-serif", 11))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;

    let mut curves = Vec::new();
    for (m, mech) in MECHANISMS.into_iter().enumerate() {
        for (q, quantity) in QUANTITIES.into_iter().enumerate() {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.0 == mech && r.1 == quantity)
                .map(|r| (r.2 as f64, r.3))
                .collect();
            let tail: Vec<&(f64, f64)> = pts.iter().filter(|p| p.0 >= 96.0).collect();
            let order = -fit::slope(
                &tail.iter().map(|p| p.0).collect::<Vec<_>>(),
                &tail.iter().map(|p| p.1).collect::<Vec<_>>(),
            );
            println!("  {mech:<19} {quantity:<23} order {order:.3}");
            let colour = COLOURS[q];
            curves.push(Curve {
                label: format!("{quantity} ({})", ["four-bar", "slider-crank"][m]),
                colour: if m == 0 {
                    colour
                } else {
                    RGBColor(colour.0 / 2 + 100, colour.1 / 2 + 100, colour.2 / 2 + 100)
                },
                points: pts,
                markers: m == 0,
            });
        }
    }
    loglog(
        &right,
        "Error vs positions per cycle (slope −2 = order 2)",
        ["positions per cycle N", "relative error"],
        SeriesLabelPosition::UpperRight,
        &curves,
    )?;
    root.present()?;
    Ok(())
}

fn main() -> Res<()> {
    let dir: PathBuf = std::env::args().nth(1).map_or_else(
        || PathBuf::from("target/tmm-charts/work-precision"),
        PathBuf::from,
    );
    fs::create_dir_all(&dir)?;
    let t0 = std::time::Instant::now();
    dynamics(&dir)?;
    stability(&dir)?;
    kinetostatics(&dir)?;
    kinematics(&dir)?;
    println!(
        "SVG charts and CSV data written to {} in {:.1} s",
        dir.display(),
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}
