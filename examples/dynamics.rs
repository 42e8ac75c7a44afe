//! Runs the four machines of seed 003 on their built-in data, prints a summary of each,
//! writes every motion as CSV and draws φ(t) and φ̇(t) of each machine as SVG. The steppers'
//! work-precision charts and stability limits are drawn by the `work_precision` example.
//!
//! `cargo run --release --example dynamics [output folder]` (default `target/tmm-charts/dynamics`).

use std::error::Error;
use std::fs;
use std::path::{Path, PathBuf};

use nalgebra::Vector2;
use plotters::prelude::*;
use tmm::dynamics::machines::{CoaxialPropellers, Failure, FiveBar, LandingGear, RpArm};
use tmm::dynamics::{
    run, Direction, Dopri5, FiniteIncrement, LagrangeSystem, Outcome, Reach, Rk4, RunOptions,
    RunResult, State, Steady, Stepper, Trajectory, Watch,
};

type Res<T> = std::result::Result<T, Box<dyn Error>>;

/// One line of a chart: a label and a column.
struct Series<'a> {
    label: String,
    y: &'a [f64],
}

/// Two stacked panels sharing the time axis: positions above, speeds below.
fn chart(
    path: &Path,
    title: &str,
    t: &[f64],
    top: &[Series],
    bottom: &[Series],
    units: [&str; 2],
) -> Res<()> {
    let root = SVGBackend::new(path, (900, 700)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let panels = root.split_evenly((2, 1));
    let colours = [RED, BLUE, GREEN, MAGENTA, CYAN, BLACK];
    for (area, (series, unit)) in panels.iter().zip([(top, units[0]), (bottom, units[1])]) {
        let (lo, hi) = series
            .iter()
            .flat_map(|s| s.y.iter())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(*v), b.max(*v))
            });
        let pad = 0.05 * (hi - lo).max(1e-9);
        let t_end = *t.last().unwrap_or(&1.0);
        let mut c = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))?;
        c.configure_mesh().x_desc("t, s").y_desc(unit).draw()?;
        for (i, s) in series.iter().enumerate() {
            let colour = colours[i % colours.len()];
            c.draw_series(LineSeries::new(
                t.iter().copied().zip(s.y.iter().copied()),
                colour.stroke_width(2),
            ))?
            .label(s.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        }
        c.configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// The coordinates and their speeds, plus named outputs, as chart series.
fn series<'a>(
    tr: &'a Trajectory,
    extra_pos: &[&str],
    extra_speed: &[&str],
) -> (Vec<Series<'a>>, Vec<Series<'a>>) {
    let [a, b] = tr.coordinate_names();
    let mut top = vec![
        Series {
            label: a.into(),
            y: tr.q()[0],
        },
        Series {
            label: b.into(),
            y: tr.q()[1],
        },
    ];
    let mut bottom = vec![
        Series {
            label: format!("{a}_dot"),
            y: tr.qd()[0],
        },
        Series {
            label: format!("{b}_dot"),
            y: tr.qd()[1],
        },
    ];
    for n in extra_pos {
        top.push(Series {
            label: (*n).into(),
            y: tr.output(n).unwrap_or(&[]),
        });
    }
    for n in extra_speed {
        bottom.push(Series {
            label: (*n).into(),
            y: tr.output(n).unwrap_or(&[]),
        });
    }
    (top, bottom)
}

fn save(
    dir: &Path,
    name: &str,
    title: &str,
    r: &RunResult,
    extra_pos: &[&str],
    extra_speed: &[&str],
    units: [&str; 2],
) -> Res<()> {
    fs::write(dir.join(format!("{name}.csv")), r.trajectory.to_csv())?;
    let (top, bottom) = series(&r.trajectory, extra_pos, extra_speed);
    chart(
        &dir.join(format!("{name}.svg")),
        title,
        r.trajectory.t(),
        &top,
        &bottom,
        units,
    )
}

/// [`run`] of a machine given as a trait object: the integrator is then compiled once per
/// stepper rather than once per machine and stepper (the same motion, bit for bit).
fn simulate<M: Stepper>(
    sys: &dyn LagrangeSystem,
    method: &M,
    start: State,
    opts: &RunOptions,
) -> Res<RunResult> {
    Ok(run(sys, method, start, opts)?)
}

fn describe(o: &Outcome) -> String {
    match o {
        Outcome::FinalTime => "ran to the final time".into(),
        Outcome::Reached { t } => format!("reached the watched value at t = {t:.4} s"),
        Outcome::Steady { t } => format!("steady at t = {t:.3} s"),
        Outcome::Drifting { t, acceleration } => format!(
            "never steady: at t = {t:.3} s the accelerations settled to ({:.3}, {:.3}) rad/s² (speeds drift linearly)",
            acceleration[0], acceleration[1]
        ),
        Outcome::NotSteady { acceleration } => {
            format!("not steady by the final time (accelerations {:.3e}, {:.3e})", acceleration[0], acceleration[1])
        }
        Outcome::Stuck { t, loads, .. } => format!(
            "stuck at t = {t:.4} s: the drive {:.3} {} within the resistance's {:.3} / {:.3}",
            loads.drive, loads.unit, loads.forward, loads.backward
        ),
        other => format!("{other:?}"),
    }
}

fn five_bar(dir: &Path) -> Res<()> {
    let f = FiveBar::default();
    let s0 = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    let r = simulate(&f, &Dopri5::new(1e-8)?, s0, &RunOptions::until(1.5, 1e-3))?;
    let tr = &r.trajectory;
    let n = tr.len() - 1;
    let worst_sin = tr
        .output("sin_phi3_minus_phi2")
        .unwrap_or(&[])
        .iter()
        .fold(1.0f64, |m, v| m.min(v.abs()));
    println!(
        "Five-bar robot (servos to 100°, 80°; Dormand–Prince, tol 1e-8): {}",
        describe(&r.outcome)
    );
    println!(
        "  {} steps; φ1 = {:.3}°, φ4 = {:.3}°, B = ({:.4}, {:.4}) m; smallest |sin(φ3 − φ2)| on the way {:.3}",
        r.steps,
        tr.q()[0][n].to_degrees(),
        tr.q()[1][n].to_degrees(),
        tr.output("x_B").map_or(f64::NAN, |c| c[n]),
        tr.output("y_B").map_or(f64::NAN, |c| c[n]),
        worst_sin
    );
    save(
        dir,
        "five_bar",
        "Five-bar robot: φ1, φ4 (rad) and their speeds (rad/s)",
        &r,
        &[],
        &[],
        ["rad", "rad/s"],
    )
}

fn rp_arm(dir: &Path) -> Res<()> {
    let a = RpArm::default();
    let s0 = State::new(0.0, Vector2::new(0.0, 0.3), Vector2::zeros());
    let mut opts = RunOptions::until(10.0, 1e-3);
    opts.record_every = 10;
    opts.reach = Some(Reach {
        watch: Watch::Coordinate(1),
        value: 0.8,
        direction: Direction::Rising,
    });
    let r = simulate(&a, &Rk4, s0, &opts)?;
    let dec = a.decoupled();
    let rd = simulate(&dec, &Rk4, s0, &opts)?;
    let exact = dec.closed_form(&s0, rd.last.t)?;
    println!("R–P arm (M_p1 = 2 N·m, F_p2 = 10 N, slide from 0.3 m to 0.8 m; RK4, h = 1 ms):");
    println!(
        "  coupled: {}; φ10 = {:.4} rad",
        describe(&r.outcome),
        r.last.q[0]
    );
    println!(
        "  decoupled by counter-masses: {}; φ10 = {:.4} rad (closed form {:.4}, difference {:.1e})",
        describe(&rd.outcome),
        rd.last.q[0],
        exact.q[0],
        (rd.last.q[0] - exact.q[0]).abs()
    );
    save(
        dir,
        "rp_arm",
        "R–P arm: φ10 (rad), l_CS2 (m) and their speeds",
        &r,
        &[],
        &[],
        ["rad, m", "rad/s, m/s"],
    )?;
    save(
        dir,
        "rp_arm_decoupled",
        "Decoupled R–P arm: φ10 (rad), l_CS2 (m) and their speeds",
        &rd,
        &[],
        &[],
        ["rad, m", "rad/s, m/s"],
    )
}

fn landing_gear(dir: &Path) -> Res<()> {
    let g = LandingGear::default();
    let mut opts = RunOptions::until(60.0, 1e-3);
    opts.record_every = 20;
    opts.reach = Some(Reach {
        watch: Watch::Output(0),
        value: g.phi_h_max,
        direction: Direction::Rising,
    });
    println!("Landing gear (retraction to φ_H = {:.0} rad, the leg at 90°; finite increments, h = 1 ms):", g.phi_h_max);
    for (name, failure) in [
        ("landing_gear", None),
        (
            "landing_gear_braked_failure",
            Some(Failure::Motor6 { braked: true }),
        ),
        (
            "landing_gear_unbraked_failure",
            Some(Failure::Motor6 { braked: false }),
        ),
    ] {
        let gi = LandingGear {
            failure,
            ..g.clone()
        };
        let mut o = opts.clone();
        if matches!(failure, Some(Failure::Motor6 { braked: false })) {
            // It cannot retract: stop when it is back down.
            o.reach = Some(Reach {
                watch: Watch::Output(0),
                value: 0.0,
                direction: Direction::Falling,
            });
        }
        let r = simulate(&gi, &FiniteIncrement, State::at_rest(Vector2::zeros()), &o)?;
        let tr = &r.trajectory;
        let phi_h = tr.output("phi_H").unwrap_or(&[]);
        let top = phi_h.iter().fold(0.0f64, |m, v| m.max(*v));
        let label = match failure {
            None => "both motors",
            Some(Failure::Motor6 { braked: true }) => "D6 failed, braked (planetary gear)",
            _ => "D6 failed, not braked (docs/errata.md#d31)",
        };
        println!(
            "  {label}: {}; highest leg angle {:.1}°",
            describe(&r.outcome),
            (top / g.phi_h_max * 90.0)
        );
        let title = format!("Landing gear, {label}: φ1, φ6, φ_H (rad) and speeds (rad/s)");
        save(
            dir,
            name,
            &title,
            &r,
            &["phi_H"],
            &["omega_H"],
            ["rad", "rad/s"],
        )?;
    }
    Ok(())
}

fn coaxial(dir: &Path) -> Res<()> {
    let d = CoaxialPropellers::default();
    let mut opts = RunOptions::until(60.0, 1e-3);
    opts.record_every = 10;
    opts.steady = Some(Steady {
        tol: 1e-3,
        hold: 1.0,
    });
    let s0 = State::at_rest(Vector2::zeros());
    println!(
        "Coaxial propellers (finite increments, h = 1 ms, steady when |φ̈| < 1e-3 rad/s² for 1 s):"
    );
    let r = simulate(&d, &FiniteIncrement, s0, &opts)?;
    let n = r.trajectory.len() - 1;
    println!(
        "  loads in the gear ratio: {}; φ̇4 = {:.2}, φ̇H = {:.2}, φ̇1 = {:.2} rad/s",
        describe(&r.outcome),
        r.trajectory.qd()[0][n],
        r.trajectory.qd()[1][n],
        r.trajectory.output("omega_1").map_or(f64::NAN, |c| c[n])
    );
    save(
        dir,
        "coaxial_propellers",
        "Coaxial propellers: φ4, φH (rad) and speeds (rad/s)",
        &r,
        &[],
        &["omega_1"],
        ["rad", "rad/s"],
    )?;
    let un = CoaxialPropellers {
        m_on4: 6000.0,
        ..d.clone()
    };
    let r = simulate(&un, &FiniteIncrement, s0, &opts)?;
    println!(
        "  (M_on)4 = 6000 N·m, out of the ratio (docs/errata.md#d41): {}",
        describe(&r.outcome)
    );
    // Draw 20 s of it, so that the drift shows.
    let long = RunOptions {
        t_end: 20.0,
        steady: None,
        ..opts.clone()
    };
    let r = simulate(&un, &FiniteIncrement, s0, &long)?;
    save(
        dir,
        "coaxial_propellers_unbalanced",
        "Coaxial propellers, loads out of ratio (20 s): φ4, φH and speeds",
        &r,
        &[],
        &["omega_1"],
        ["rad", "rad/s"],
    )?;

    Ok(())
}

fn run_example() -> Res<()> {
    let dir: PathBuf = std::env::args().nth(1).map_or_else(
        || PathBuf::from("target/tmm-charts/dynamics"),
        PathBuf::from,
    );
    fs::create_dir_all(&dir)?;
    five_bar(&dir)?;
    rp_arm(&dir)?;
    landing_gear(&dir)?;
    coaxial(&dir)?;
    println!("CSV files and SVG charts written to {}", dir.display());
    println!("Work-precision of the steppers: cargo run --release --example work_precision");
    Ok(())
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
