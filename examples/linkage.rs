//! The course table of any linkage described in a JSON file: positions, velocities and
//! accelerations, the reaction in every joint, and the balancing moment beside its value by
//! the principle of virtual power, at the 12 course positions. Written as CSV too, and, with
//! the feature `draw` (on by default), the pictures: the kinematic scheme, the plan in the 12
//! positions with the paths of the joints, an animation of the cycle, the reactions as arrows
//! and the diagrams over the cycle, as SVG files beside the CSV.
//!
//! ```sh
//! cargo run --release --example linkage -- linkages/watt-six-bar.json
//! cargo run --release --example linkage            # the bundled shaper
//! ```

use std::f64::consts::TAU;
use std::fs;
use std::path::Path;
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{course_inputs, Course, Linkage, Plan, Sweep, Table};

const BUNDLED: &str = include_str!("../linkages/shaper.json");

fn run_example() -> Result<(), Box<dyn std::error::Error>> {
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
    // A crank that cannot turn fully rocks between the angles where the linkage locks.
    let rocks = plan.input_is_crank()
        && plan
            .lock_positions(plan.reference_input())
            .is_ok_and(|l| l.is_some());
    let inputs = match (&linkage.output, plan.input_is_crank()) {
        _ if rocks => {
            let course = Course::new(&plan, linkage.output.as_ref(), 12, speed)?;
            if let Sweep::Rocking { from, to } = course.sweep {
                println!(
                    "the input cannot turn fully: it rocks from φ1 = {:.2}° to {:.2}° and back",
                    from.to_degrees(),
                    to.to_degrees()
                );
            }
            course.inputs
        }
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
            // A rocking input at rest where it reverses has no virtual power to compare.
            Ok(a) if a.inputs().first().rate == 0.0 => println!(
                "position {k:2}: input {:8.4}  balance {:12.4} (input at rest: no virtual power)  worst link residual {:.1e}",
                a.inputs().first().value,
                a.balance(0)?.value,
                a.worst_residual()
            ),
            Ok(a) => {
                let c = a.power_check()?;
                println!(
                    "position {k:2}: input {:8.4}  balance {:12.4} (virtual power {:12.4}, rel. diff {:.1e})  worst link residual {:.1e}",
                    a.inputs().first().value,
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
    #[cfg(feature = "draw")]
    pictures::write(&linkage, &plan, &inputs, dir)?;
    Ok(())
}

/// The pictures of the linkage (feature `draw`), each an SVG file in `dir`.
#[cfg(feature = "draw")]
mod pictures {
    use std::fs;
    use std::path::Path;
    use tmm::draw::{self, Diagram, Style};
    use tmm::kinematics::Motion;
    use tmm::linkage::LinkId;
    use tmm::linkage::{uniform_inputs, Course, Linkage, Output, Plan, Sweep};

    pub fn write(
        linkage: &Linkage,
        plan: &Plan,
        inputs: &[Motion],
        dir: &Path,
    ) -> Result<(), Box<dyn std::error::Error>> {
        let stem = linkage.name.replace([' ', '/'], "_");
        let style = Style::default();
        let save = |what: &str, svg: &str| -> std::io::Result<()> {
            let file = dir.join(format!("{stem}_{what}.svg"));
            fs::write(&file, svg)?;
            println!("{what} drawn in {}", file.display());
            Ok(())
        };
        let first = inputs[0];
        save("scheme", &draw::scheme(plan, first, &style)?.svg)?;
        save("forces", &draw::forces(plan, first, &style)?.svg)?;
        if !plan.input_is_crank() {
            // A slider has no turn: the course is the table's positions.
            let course = Course::given(inputs.to_vec());
            save("plan", &draw::plan_view(plan, &course, &[], &style)?.svg)?;
            save(
                "animation",
                &draw::animation(plan, inputs, 2.0, &style)?.svg,
            )?;
            save(
                "balance",
                &draw::diagram(plan, &course, &Diagram::Balance, &style)?.svg,
            )?;
            return Ok(());
        }
        let speed = linkage.speed.unwrap_or(10.0);
        let course = Course::new(plan, linkage.output.as_ref(), 12, speed)?;
        // The paths of every joint off the frame and of every named point.
        let paths: Vec<&str> = plan
            .joint_names()
            .iter()
            .enumerate()
            .filter(|&(j, _)| {
                plan.joint_links(j)
                    .is_ok_and(|l| !l.contains(&LinkId::FRAME))
            })
            .map(|(_, n)| n.as_str())
            .chain(plan.point_names().iter().map(String::as_str))
            .collect();
        save("plan", &draw::plan_view(plan, &course, &paths, &style)?.svg)?;
        let turn = match course.sweep {
            Sweep::Rocking { .. } => Course::new(plan, None, 360, speed)?.inputs,
            _ => uniform_inputs(360, course.inputs[0].value, speed, 0.0),
        };
        save("animation", &draw::animation(plan, &turn, 4.0, &style)?.svg)?;
        let tall = Style {
            height: 900,
            ..Style::default()
        };
        let output = linkage.output.clone().unwrap_or_else(|| {
            Output::Angle(plan.link_names()[plan.link_names().len() - 1].clone())
        });
        save(
            "kinematics",
            &draw::diagram(plan, &course, &Diagram::Kinematics(output.clone()), &tall)?.svg,
        )?;
        save(
            "transfer",
            &draw::diagram(plan, &course, &Diagram::Transfer(output), &tall)?.svg,
        )?;
        save(
            "balance",
            &draw::diagram(plan, &course, &Diagram::Balance, &style)?.svg,
        )?;
        save(
            "reactions",
            &draw::diagram(plan, &course, &Diagram::Reactions, &style)?.svg,
        )?;
        // The hodograph of the crank pin's reaction: the input link's joint off the frame.
        let input = plan.input_links()[0];
        if let Some(j) = (0..plan.joint_names().len()).find(|&j| {
            plan.joint_links(j)
                .is_ok_and(|l| l.contains(&input) && !l.contains(&LinkId::FRAME))
        }) {
            let joint = plan.joint_names()[j].clone();
            save(
                "hodograph",
                &draw::diagram(plan, &course, &Diagram::Hodograph(joint), &style)?.svg,
            )?;
        }
        Ok(())
    }
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
