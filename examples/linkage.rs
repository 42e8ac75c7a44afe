//! The course table of any linkage described in a JSON file: positions, velocities and
//! accelerations, the reaction in every joint, and the balancing moment beside its value by
//! the principle of virtual power, at the 12 course positions. Written as CSV too.
//!
//! ```sh
//! cargo run --release --example linkage -- linkages/watt-six-bar.json
//! cargo run --release --example linkage            # the bundled shaper
//! ```

use std::f64::consts::TAU;
use std::fs;
use std::path::Path;
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{course_inputs, Linkage, Plan, Table};

const BUNDLED: &str = include_str!("../linkages/shaper.json");

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (text, source) = match std::env::args().nth(1) {
        Some(path) => (fs::read_to_string(&path)?, path),
        None => (
            BUNDLED.to_owned(),
            "linkages/shaper.json (bundled)".to_owned(),
        ),
    };
    let linkage = Linkage::from_json(&text)?;
    let plan = Plan::new(&linkage)?;
    println!("{} — from {source}", linkage.name);
    println!(
        "mobility W = {} (Chebyshev); groups in attachment order: {}",
        plan.mobility(),
        plan.groups()
            .iter()
            .map(|g| g.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let speed = linkage.speed.unwrap_or(10.0);
    let rotation = if speed < 0.0 {
        Rotation::Cw
    } else {
        Rotation::Ccw
    };
    let inputs = match (&linkage.output, plan.input_is_crank()) {
        (Some(out), true) => {
            let s = plan.strokes(out, rotation)?;
            println!(
                "output {out:?}: working stroke from φ1 = {:.2}° over {:.2}°, time ratio {:.4}",
                s.start.to_degrees(),
                s.working_angle.to_degrees(),
                s.time_ratio
            );
            course_inputs(&s, 12, speed)
        }
        _ => (0..12)
            .map(|k| {
                let step = if plan.input_is_crank() {
                    TAU / 12.0
                } else {
                    0.01
                };
                Motion::new(
                    plan.reference_input() + speed.signum() * step * f64::from(k),
                    speed,
                    0.0,
                )
            })
            .collect(),
    };
    let positions: Vec<_> = inputs.iter().map(|&i| plan.analyse(i)).collect();
    for (k, p) in positions.iter().enumerate() {
        match p {
            Ok(a) => {
                let c = a.power_check()?;
                println!(
                    "position {k:2}: input {:8.4}  balance {:12.4} (virtual power {:12.4}, rel. diff {:.1e})  worst link residual {:.1e}",
                    a.input().value,
                    c.chain,
                    c.virtual_power,
                    c.relative_error(),
                    a.worst_residual()
                );
            }
            Err(e) => println!("position {k:2}: {e}"),
        }
    }
    let table = Table::of(&positions);
    println!("\n{}", table.to_text(4));
    let dir = Path::new("target/tmm-charts/linkage");
    fs::create_dir_all(dir)?;
    let file = dir.join(format!("{}.csv", linkage.name.replace([' ', '/'], "_")));
    table.write_csv(fs::File::create(&file)?)?;
    println!("course table written to {}", file.display());
    Ok(())
}
