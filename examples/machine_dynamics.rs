//! The second sheet of the course project: the dynamics of seed 001's two-cylinder compressor
//! (the crate's `Compressor::course_example`) under an induction motor. Prints the reduced
//! moment of inertia and moment over a turn, the run-up from rest to the steady state, the
//! steady turn's ω(φ) and the flywheel for δ = 1/20 and 1/50 (the energy–mass method of
//! Wittenbauer beside the textbook's simplified formula, each checked by integrating the
//! designed turn), and writes CSV and SVG charts.
//!
//! `cargo run --release --example machine_dynamics [output folder]`
//! (default `target/tmm-charts/machine_dynamics`).
//!
//! The compressor turns clockwise (seed 001): its crank speed is negative in the crate's
//! convention, and so is the motor's moment, M = −a − b·ω.

use std::error::Error;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use nalgebra::Vector2;
use plotters::prelude::*;
use tmm::dynamics::machines::LinearMotor;
use tmm::dynamics::{Rk4, State};
use tmm::linkage::dynamics::{LinkageSystem, Motor, RunUpOptions, Turn};
use tmm::mechanism::{Compressor, Mechanism};

type Res<T> = std::result::Result<T, Box<dyn Error>>;

const RPM: f64 = PI / 30.0;

/// One chart of a few lines against a common abscissa.
fn chart(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    lines: &[(&str, &[f64], &[f64])],
) -> Res<()> {
    let root = SVGBackend::new(path, (900, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let span = |v: &mut dyn Iterator<Item = f64>| {
        v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        })
    };
    let (x0, x1) = span(&mut lines.iter().flat_map(|l| l.1.iter().copied()));
    let (y0, y1) = span(&mut lines.iter().flat_map(|l| l.2.iter().copied()));
    let pad = 0.05 * (y1 - y0).max(1e-9);
    let mut c = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))?;
    c.configure_mesh().x_desc(x_desc).y_desc(y_desc).draw()?;
    for (i, (label, x, y)) in lines.iter().enumerate() {
        let colour = [RED, BLUE, GREEN, BLACK][i % 4];
        c.draw_series(LineSeries::new(
            x.iter().copied().zip(y.iter().copied()),
            colour.stroke_width(2),
        ))?
        .label(*label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
    }
    c.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

fn csv(path: &Path, header: &str, rows: impl Iterator<Item = Vec<f64>>) -> Res<()> {
    let mut s = format!("{header}\n");
    for r in rows {
        let line: Vec<String> = r.iter().map(|v| v.to_string()).collect();
        writeln!(s, "{}", line.join(","))?;
    }
    fs::write(path, s)?;
    Ok(())
}

fn turn_row(k: usize, t: &Turn) -> String {
    format!(
        "{k:>4} {:>9.4} {:>9.5} {:>10.2} {:>10.2} {:>10.2} {:>8.4}",
        t.t_start,
        t.period,
        t.omega_mean / RPM,
        t.omega_max / RPM,
        t.omega_min / RPM,
        t.delta
    )
}

fn run_example() -> Res<()> {
    let dir = std::env::args().nth(1).map_or_else(
        || PathBuf::from("target/tmm-charts/machine_dynamics"),
        PathBuf::from,
    );
    fs::create_dir_all(&dir)?;

    let compressor = Compressor::course_example();
    let omega_seed = Compressor::seed_speed(); // −960 rpm: clockwise
    let bare = LinkageSystem::from_linkage(&compressor.linkage()?)?;

    // 1. The machine reduced to its crank over a turn at the seed's speed.
    let reduced = bare.reduced_cycle(360, omega_seed)?;
    let m_mean = reduced.iter().map(|r| r.loads).sum::<f64>() / reduced.len() as f64;
    println!(
        "Two-cylinder compressor, {:.0} rpm clockwise",
        -omega_seed / RPM
    );
    println!("\nReduced to the crank (every 30°; the loads' mean {m_mean:.2} N·m):");
    println!("  φ, deg   J_red, kg·m²   dJ/dφ, kg·m²   M_red, N·m");
    for r in reduced.iter().step_by(30) {
        println!(
            "{:>8.1} {:>14.6} {:>14.6} {:>12.2}",
            (r.phi - reduced[0].phi).to_degrees().abs(),
            r.inertia,
            r.inertia_derivative,
            r.loads
        );
    }
    csv(
        &dir.join("reduced.csv"),
        "phi,J_red,dJ_dphi,M_red",
        reduced
            .iter()
            .map(|r| vec![r.phi, r.inertia, r.inertia_derivative, r.loads]),
    )?;

    // 2. The motor: an induction motor of 1000 rpm synchronous speed whose nominal moment at
    // 960 rpm is the loads' mean (10 % reserve), turning clockwise; its rotor 0.06 kg·m².
    let power = -m_mean * omega_seed;
    let m_nom = 1.1 * m_mean.abs();
    let motor = LinearMotor::from_nominal(m_nom, 1000.0 * RPM, 960.0 * RPM)?;
    let clockwise = LinearMotor {
        a: -motor.a,
        b: motor.b,
    };
    println!(
        "\nMotor: mean load power {:.2} kW; nominal {m_nom:.1} N·m at 960 rpm, M = −{:.1} − {:.3}·ω N·m",
        power / 1000.0,
        motor.a,
        motor.b
    );
    let machine = bare
        .clone()
        .with_motor(0, Motor::Linear(clockwise))?
        .with_inertia(0, 0.06)?;

    // 3. The run-up from rest.
    let mut opts = RunUpOptions::new(2e-5);
    opts.tol = 1e-7;
    opts.record_every = 5;
    let r = machine.run_up(&Rk4, &opts)?;
    println!(
        "\nRun-up from rest (RK4, h = 20 µs): steady after {} turns",
        r.turns.len()
    );
    println!("turn   t0, s     T, s      n_m, rpm  n_max, rpm n_min, rpm    δ");
    for (k, t) in r.turns.iter().enumerate() {
        if k < 6 || k + 3 >= r.turns.len() {
            println!("{}", turn_row(k + 1, t));
        } else if k == 6 {
            println!("   …");
        }
    }
    let omega_rpm: Vec<f64> = r.omega.iter().map(|w| -w / RPM).collect();
    csv(
        &dir.join("run_up.csv"),
        "t,phi,omega",
        (0..r.t.len()).map(|i| vec![r.t[i], r.phi[i], r.omega[i]]),
    )?;
    chart(
        &dir.join("run_up.svg"),
        "Compressor: run-up from rest",
        "t, s",
        "n, rpm (clockwise)",
        &[("crank speed", &r.t, &omega_rpm)],
    )?;

    // 4. The steady turn's ω(φ).
    let steady = *r.turns.last().expect("a steady turn");
    let tr = &r.steady.trajectory;
    let phi0 = tr.q()[0][0];
    let turned: Vec<f64> = tr.q()[0].iter().map(|p| (phi0 - p).to_degrees()).collect();
    let n_steady: Vec<f64> = tr.qd()[0].iter().map(|w| -w / RPM).collect();
    println!(
        "\nSteady turn: n_m = {:.2} rpm, δ = {:.4}",
        steady.omega_mean / RPM,
        steady.delta
    );
    println!("  turned, deg   n, rpm");
    let step = (turned.len() / 12).max(1);
    for i in (0..turned.len()).step_by(step) {
        println!("{:>12.1} {:>8.2}", turned[i], n_steady[i]);
    }
    csv(
        &dir.join("steady.csv"),
        "turned_deg,n_rpm",
        (0..turned.len()).map(|i| vec![turned[i], n_steady[i]]),
    )?;

    // 5. Flywheels for δ = 1/20 and 1/50 at the steady mean speed.
    let omega_m = steady.direction * steady.omega_mean;
    let mut lines = vec![("no flywheel".to_owned(), turned.clone(), n_steady.clone())];
    let mut rows = Vec::new();
    println!(
        "\nFlywheel at n_m = {:.1} rpm (constant driving moment, energy–mass method):",
        omega_m.abs() / RPM
    );
    println!("  δ      J_F, kg·m²  simplified  ΔE, J    M_d, N·m   δ integrated  δ with the motor");
    for delta in [1.0 / 20.0, 1.0 / 50.0] {
        // The machine with the motor's rotor, without the motor: the textbook's problem.
        let with_rotor = bare.clone().with_inertia(0, 0.06)?;
        let f = with_rotor.flywheel(delta, omega_m, 3600)?;
        // The designed turn: constant moment, flywheel, from the designed start speed.
        let designed = with_rotor
            .clone()
            .with_motor(0, Motor::Constant(f.driving_moment))?
            .with_inertia(0, f.moment_of_inertia)?;
        let start = State::new(
            0.0,
            Vector2::new(f.phi_start, 0.0),
            Vector2::new(f.omega_start.ok_or("no designed turn")?, 0.0),
        );
        let mut o = RunUpOptions::new(TAU / omega_m.abs() / 4000.0);
        o.max_turn_time = 1.0;
        let (check, _) = designed.turn(&Rk4, start, &o)?;
        // The same flywheel under the real motor: the motor's slope damps the fluctuation.
        let with_motor = machine.clone().with_inertia(0, f.moment_of_inertia)?;
        let run = with_motor.run_up(&Rk4, &opts)?;
        let real = *run.turns.last().expect("a steady turn");
        println!(
            "  1/{:<3.0} {:>10.4} {:>10.4} {:>8.2} {:>9.2} {:>12.5} {:>12.5}",
            1.0 / delta,
            f.moment_of_inertia,
            f.simplified,
            f.energy_range,
            f.driving_moment,
            check.delta,
            real.delta
        );
        rows.push(vec![
            delta,
            f.moment_of_inertia,
            f.simplified,
            f.energy_range,
            f.driving_moment,
            check.delta,
            real.delta,
        ]);
        let t = &run.steady.trajectory;
        let p0 = t.q()[0][0];
        lines.push((
            format!("flywheel for δ = 1/{:.0}", 1.0 / delta),
            t.q()[0].iter().map(|p| (p0 - p).to_degrees()).collect(),
            t.qd()[0].iter().map(|w| -w / RPM).collect(),
        ));
    }
    println!("(the rotor's 0.06 kg·m² counted in the machine; J_F is what to add)");
    csv(
        &dir.join("flywheel.csv"),
        "delta,J_F,J_F_simplified,energy_range,M_d,delta_integrated,delta_with_motor",
        rows.into_iter(),
    )?;
    let refs: Vec<(&str, &[f64], &[f64])> = lines
        .iter()
        .map(|(l, x, y)| (l.as_str(), x.as_slice(), y.as_slice()))
        .collect();
    chart(
        &dir.join("steady.svg"),
        "Compressor: steady turn under the motor",
        "crank turned, deg",
        "n, rpm",
        &refs,
    )?;
    println!("\nCSV and SVG written to {}", dir.display());
    Ok(())
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
