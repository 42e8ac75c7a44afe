//! Whole mechanisms over a cycle, as in a course project on the theory of machines: the
//! six-bar of seed 001's figure 2.10 type and seed 001's two-cylinder compressor, then the
//! other ready mechanisms (four-bar, slider-crank driven through a gear pair, rocking
//! cylinder).
//!
//! For each: the 12 plans from the beginning of the working stroke (positions, velocities,
//! accelerations, the reactions in every pair, the balancing moment), the balancing moment
//! checked by the principle of virtual power, and over a 360-position cycle the CSV tables and
//! SVG charts (kinematic diagrams s(φ), v(φ), a(φ) of the output, the reactions, the balancing
//! moment) written to `target/tmm-charts/mechanisms/`.
//!
//! Each ready mechanism is a struct of parameters whose `plan()` is a linkage planned by the
//! engine (`tmm::linkage`); every position is `plan.analyse(motion)`.
//!
//! Run with `cargo run --release --example mechanisms`.

use plotters::prelude::*;
use std::error::Error as StdError;
use std::fs::{create_dir_all, File};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{course_inputs, run_cycle, uniform_inputs, Analysis, Plan, Table};
use tmm::mechanism::{Compressor, FourBar, Mechanism, RockingCylinder, SixBar, SliderCrank};

type Res<T> = std::result::Result<T, Box<dyn StdError>>;

/// The positions of `plan` at `inputs`, every one of which must be analysed.
fn analyse_all<'p>(plan: &'p Plan, inputs: &[Motion]) -> Res<Vec<tmm::Result<Analysis<'p>>>> {
    let positions = run_cycle(inputs, |i| plan.analyse(i));
    if let Some(Err(e)) = positions.iter().find(|p| p.is_err()) {
        return Err(e.to_string().into());
    }
    Ok(positions)
}

/// The largest virtual-power disagreement and link-equilibrium residual over a cycle.
fn checks(positions: &[tmm::Result<Analysis<'_>>]) -> Res<(f64, f64)> {
    let mut worst = (0.0f64, 0.0f64);
    for p in positions {
        let p = p.as_ref().map_err(|e| e.to_string())?;
        worst.0 = worst.0.max(p.power_check()?.relative_error());
        worst.1 = worst.1.max(p.worst_residual());
    }
    Ok(worst)
}

/// One SVG line chart of several columns of a table against φ1 in degrees.
fn chart(path: &Path, title: &str, table: &Table, columns: &[&str], y_label: &str) -> Res<()> {
    let phi: Vec<f64> = table
        .column("phi_in [rad]")
        .ok_or("no phi_in column")?
        .iter()
        .map(|p| p.to_degrees())
        .collect();
    let series: Vec<(&str, &[f64])> = columns
        .iter()
        .map(|c| Ok((*c, table.column(c).ok_or(format!("no column {c}"))?)))
        .collect::<Res<_>>()?;
    let (lo, hi) = series
        .iter()
        .flat_map(|(_, v)| v.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let pad = 0.05 * (hi - lo).max(1e-12);
    let root = SVGBackend::new(path, (900, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut c = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..360.0, (lo - pad)..(hi + pad))?;
    c.configure_mesh()
        .x_desc("crank angle phi1, deg")
        .y_desc(y_label)
        .draw()?;
    let palette = [
        BLUE,
        RED,
        GREEN,
        MAGENTA,
        CYAN,
        BLACK,
        RGBColor(230, 130, 0),
    ];
    for (k, (name, values)) in series.iter().enumerate() {
        let colour = palette[k % palette.len()];
        let mut points: Vec<(f64, f64)> = phi.iter().copied().zip(values.iter().copied()).collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        c.draw_series(LineSeries::new(points, colour))?
            .label(*name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], colour));
    }
    c.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Writes a table as CSV and returns the path.
fn csv(dir: &Path, name: &str, table: &Table) -> Res<PathBuf> {
    let path = dir.join(format!("{name}.csv"));
    table.write_csv(BufWriter::new(File::create(&path)?))?;
    Ok(path)
}

/// The label of the reaction in joint `j`: R(by,on)@joint.
fn reaction_label(plan: &Plan, a: &Analysis<'_>, j: usize) -> tmm::Result<String> {
    let r = a.reaction(j)?;
    let links = plan.link_names();
    Ok(format!(
        "R({},{})@{}",
        links[r.by],
        links[r.on],
        plan.joint_names()[j]
    ))
}

/// Prints the magnitude of the reaction in every joint at each plan, with M_b by the chain
/// and by virtual power.
fn print_reactions(plan: &Plan, plans: &[tmm::Result<Analysis<'_>>]) -> Res<()> {
    let first = plans[0].as_ref().map_err(|e| e.to_string())?;
    let joints = plan.joint_names().len();
    println!("reactions |R(by,on)@joint|, N:");
    print!("{:>3}", "pos");
    for j in 0..joints {
        print!(" {:>22}", reaction_label(plan, first, j)?);
    }
    println!(" {:>9} {:>9} {:>8}", "Mb N·m", "Mb(VP)", "rel.err");
    for (k, p) in plans.iter().enumerate() {
        let p = p.as_ref().map_err(|e| e.to_string())?;
        let c = p.power_check()?;
        print!("{k:>3}");
        for j in 0..joints {
            print!(" {:>22.1}", p.reaction(j)?.force.norm());
        }
        println!(
            " {:>9.3} {:>9.3} {:>8.1e}",
            c.chain,
            c.virtual_power,
            c.relative_error()
        );
    }
    Ok(())
}

/// The |R| columns of every joint of a table.
fn reaction_columns(table: &Table) -> Vec<&str> {
    table
        .columns
        .iter()
        .map(|c| c.name.as_str())
        .filter(|n| n.starts_with("|R("))
        .collect()
}

/// Draws one chart per entry `(file suffix, title, columns, unit)` as `{name}_{suffix}.svg`.
fn charts(dir: &Path, name: &str, table: &Table, list: &[(&str, &str, &[&str], &str)]) -> Res<()> {
    for &(suffix, title, columns, unit) in list {
        chart(
            &dir.join(format!("{name}_{suffix}.svg")),
            title,
            table,
            columns,
            unit,
        )?;
    }
    Ok(())
}

fn six_bar(dir: &Path) -> Res<()> {
    let m = SixBar::course_example();
    let plan = m.plan()?;
    let w1 = 10.0;
    let strokes = m.strokes(Rotation::Ccw)?;
    println!("== Six-bar (crank + RRR + RRP, seed 001 fig. 2.10 type), omega1 = {w1} rad/s CCW ==");
    println!(
        "working stroke from phi1 = {:.2} deg over {:.2} deg, time ratio {:.4}",
        strokes.start.to_degrees(),
        strokes.working_angle.to_degrees(),
        strokes.time_ratio
    );
    let plans = analyse_all(&plan, &course_inputs(&strokes, 12, w1))?;
    println!(
        "{:>3} {:>7} {:>8} {:>8} {:>9} {:>8} {:>9} {:>7} {:>8}",
        "pos", "phi1°", "xD mm", "v5 m/s", "a5 m/s²", "ω3 1/s", "ε3 1/s²", "vC m/s", "aC m/s²"
    );
    for (k, p) in plans.iter().enumerate() {
        let p = p.as_ref().map_err(|e| e.to_string())?;
        let (s, rocker, c) = (p.slide("Q")?, p.link("rocker")?, p.joint("C")?);
        println!(
            "{:>3} {:>7.2} {:>8.2} {:>8.4} {:>9.3} {:>8.4} {:>9.3} {:>7.4} {:>8.3}",
            k,
            p.inputs().first().value.to_degrees(),
            p.joint("D")?.p.x * 1e3,
            s.rate,
            s.accel,
            rocker.rate,
            rocker.accel,
            c.v.norm(),
            c.a.norm()
        );
    }
    print_reactions(&plan, &plans)?;
    let cycle = analyse_all(&plan, &uniform_inputs(360, 0.0, w1, 0.0))?;
    let (vp, eq) = checks(&cycle)?;
    println!("360 positions: virtual power agrees to {vp:.1e}, links in equilibrium to {eq:.1e}\n");
    let table = Table::of(&cycle);
    csv(dir, "six_bar", &table)?;
    charts(
        dir,
        "six_bar",
        &table,
        &[
            ("s", "Six-bar: slider position s5", &["s(Q) [m]"], "m"),
            (
                "v",
                "Six-bar: slider velocity v5",
                &["v_rel(Q) [m/s]"],
                "m/s",
            ),
            (
                "a",
                "Six-bar: slider acceleration a5",
                &["a_rel(Q) [m/s^2]"],
                "m/s²",
            ),
            (
                "reactions",
                "Six-bar: joint reactions",
                &reaction_columns(&table),
                "N",
            ),
            (
                "mb",
                "Six-bar: balancing moment",
                &["Mb [N·m, + counter-clockwise]"],
                "N·m",
            ),
        ],
    )
}

fn compressor(dir: &Path) -> Res<()> {
    let m = Compressor::course_example();
    let plan = m.plan()?;
    let w1 = Compressor::seed_speed();
    let strokes = m.strokes(Rotation::Cw)?;
    println!("== Two-cylinder compressor (seed 001), 960 rpm clockwise, omega1 = {w1:.3} rad/s ==");
    println!(
        "piston 1's working stroke from phi1 = {:.2} deg (crate angle, CCW from +x)",
        strokes.start.to_degrees()
    );
    let plans = analyse_all(&plan, &course_inputs(&strokes, 12, w1))?;
    println!(
        "{:>3} {:>7} {:>8} {:>8} {:>9} {:>8} {:>8} {:>9} {:>9} {:>9}",
        "pos",
        "phi1°",
        "yB mm",
        "vB m/s",
        "aB m/s²",
        "yD mm",
        "vD m/s",
        "aD m/s²",
        "Fgas1 N",
        "Fgas2 N"
    );
    let (p1, p2) = (
        plan.link_id("piston 1")?.index(),
        plan.link_id("piston 2")?.index(),
    );
    for (k, p) in plans.iter().enumerate() {
        let p = p.as_ref().map_err(|e| e.to_string())?;
        let (b, d) = (p.joint("B")?, p.joint("D")?);
        // The gas forces: the applied loads on the pistons other than their own weight and
        // inertia (which act at the same point), i.e. the external ones, listed after them.
        let gas = |piston: usize| {
            p.applied_loads()
                .iter()
                .filter(|(l, _)| *l == piston)
                .skip(1)
                .map(|(_, f)| f.force.y)
                .sum::<f64>()
        };
        println!(
            "{:>3} {:>7.2} {:>8.2} {:>8.3} {:>9.1} {:>8.2} {:>8.3} {:>9.1} {:>9.1} {:>9.1}",
            k,
            p.inputs().first().value.to_degrees(),
            b.p.y * 1e3,
            b.v.y,
            b.a.y,
            d.p.y * 1e3,
            d.v.y,
            d.a.y,
            gas(p1),
            gas(p2)
        );
    }
    print_reactions(&plan, &plans)?;
    let cycle = analyse_all(&plan, &uniform_inputs(360, 0.0, w1, 0.0))?;
    let (vp, eq) = checks(&cycle)?;
    let table = Table::of(&cycle);
    let mb = table
        .column("Mb [N·m, + counter-clockwise]")
        .ok_or("no Mb")?;
    let mean = mb.iter().sum::<f64>() / mb.len() as f64;
    println!("360 positions: virtual power agrees to {vp:.1e}, links in equilibrium to {eq:.1e}");
    println!(
        "mean balancing moment {mean:.2} N·m: the drive's power {:.2} kW\n",
        (mean * w1).abs() / 1e3
    );
    csv(dir, "compressor", &table)?;
    charts(
        dir,
        "compressor",
        &table,
        &[
            (
                "s",
                "Compressor: pistons' positions",
                &["y(B) [m]", "y(D) [m]"],
                "m",
            ),
            (
                "v",
                "Compressor: pistons' velocities",
                &["v_rel(P1) [m/s]", "v_rel(P2) [m/s]"],
                "m/s",
            ),
            (
                "a",
                "Compressor: pistons' accelerations",
                &["a_rel(P1) [m/s^2]", "a_rel(P2) [m/s^2]"],
                "m/s²",
            ),
            (
                "reactions",
                "Compressor: joint reactions",
                &reaction_columns(&table),
                "N",
            ),
            (
                "mb",
                "Compressor: balancing moment",
                &["Mb [N·m, + counter-clockwise]"],
                "N·m",
            ),
        ],
    )
}

/// A one-line summary of a ready mechanism over 360 positions, its CSV and its M_b chart.
fn summary(dir: &Path, name: &str, title: &str, plan: &Plan, inputs: &[Motion]) -> Res<()> {
    let cycle = analyse_all(plan, inputs)?;
    let (vp, eq) = checks(&cycle)?;
    let table = Table::of(&cycle);
    let mb = table
        .column("Mb [N·m, + counter-clockwise]")
        .ok_or("no Mb")?;
    let peak = mb.iter().fold(0.0f64, |a, m| a.max(m.abs()));
    println!("{title}: max |Mb| = {peak:.2} N·m; virtual power agrees to {vp:.1e}, equilibrium to {eq:.1e}");
    csv(dir, name, &table)?;
    charts(
        dir,
        name,
        &table,
        &[(
            "mb",
            &format!("{title}: balancing moment"),
            &["Mb [N·m, + counter-clockwise]"],
            "N·m",
        )],
    )
}

fn run_example() -> Res<()> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/tmm-charts/mechanisms");
    create_dir_all(&dir)?;
    six_bar(&dir)?;
    compressor(&dir)?;
    println!("== The other ready mechanisms, 360 positions each ==");
    summary(
        &dir,
        "four_bar",
        "Four-bar (crank-rocker)",
        &FourBar::course_example().plan()?,
        &uniform_inputs(360, 0.0, 10.0, 0.0),
    )?;
    summary(
        &dir,
        "slider_crank_geared",
        "Slider-crank driven through a gear pair",
        &SliderCrank::geared_example().plan()?,
        &uniform_inputs(360, 0.0, 150.0, 0.0),
    )?;
    summary(
        &dir,
        "rocking_cylinder",
        "Rocking-cylinder pump (RPR)",
        &RockingCylinder::course_example().plan()?,
        &uniform_inputs(360, 0.0, 20.0, 0.0),
    )?;
    println!("\nCSV tables and SVG charts written to {}", dir.display());
    Ok(())
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
