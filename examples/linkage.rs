//! The course table of any linkage described in a JSON file: positions, velocities and
//! accelerations, the reaction in every joint, and the balancing moment beside its value by
//! the principle of virtual power, at the 12 course positions. Written as CSV too, and, with
//! the feature `draw` (on by default), the pictures: the kinematic scheme, the plan in the 12
//! positions with the paths of the joints, an animation of the cycle, the reactions as arrows
//! and the diagrams over the cycle, as SVG files beside the CSV. A linkage with two inputs
//! (the five-bar robot) runs round a loop about its reference pose: its table has both
//! balancing moments and the drives' power against the virtual power, and its pictures the
//! plan and animation along that loop and the workspace of its end effector.
//!
//! ```sh
//! cargo run --release --example linkage -- linkages/watt-six-bar.json
//! cargo run --release --example linkage            # the bundled shaper
//! ```

use std::fs;
use std::path::Path;
use tmm::linkage::{AnyCourse, Linkage, Plan, Sweep, Table};

const BUNDLED: &str = include_str!("../linkages/shaper.json");

fn run_example() -> Result<(), Box<dyn std::error::Error>> {
    let (text, source) = match std::env::args().nth(1) {
        Some(path) => (fs::read_to_string(&path)?, path),
        None => (
            BUNDLED.to_owned(),
            "linkages/shaper.json (bundled)".to_owned(),
        ),
    };
    run(&text, &source, Path::new("target/tmm-charts/linkage"))?;
    Ok(())
}

/// The whole example on the description `text` (read from `source`): the course, its table
/// printed and written as CSV in `dir`, and the pictures. Returns the table. The test
/// `tests/linkage/examples_run.rs` runs it on every bundled file.
pub fn run(text: &str, source: &str, dir: &Path) -> Result<Table, Box<dyn std::error::Error>> {
    let linkage = Linkage::from_json(text)?;
    let plan = Plan::new(&linkage)?;
    println!("{} — from {source}", linkage.name);
    println!(
        "mobility W = {} (Chebyshev), {} input(s); groups in attachment order: {}",
        plan.mobility(),
        plan.input_count(),
        plan.groups()
            .iter()
            .map(|g| g.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let speed = linkage.input_speed();
    let course = plan.default_course(linkage.output.as_ref(), 12, speed)?;
    match &course {
        AnyCourse::One(c) => match (c.sweep, &linkage.output) {
            (Sweep::Rocking { from, to }, _) => println!(
                "the input cannot turn fully: it rocks from φ1 = {:.2}° to {:.2}° and back",
                from.to_degrees(),
                to.to_degrees()
            ),
            (Sweep::Turn, Some(out)) => println!(
                "output {out:?}: the course starts at its working stroke, φ1 = {:.2}°",
                c.inputs[0].value.to_degrees()
            ),
            _ => {}
        },
        AnyCourse::Two(_) => println!(
            "two inputs: the course runs round a closed path about the reference pose \
             (each input swings harmonically, the second a quarter period behind)"
        ),
    }
    let inputs = course.inputs();
    let positions = plan.analyse_each(&inputs, &mut |_| {});
    for (k, p) in positions.iter().enumerate() {
        let a = match p {
            Ok(a) => a,
            Err(e) => {
                println!("position {k:2}: {e}");
                continue;
            }
        };
        let q: Vec<String> = a
            .inputs()
            .as_slice()
            .iter()
            .map(|m| format!("{:8.4}", m.value))
            .collect();
        let b: Vec<String> = a
            .balances()
            .iter()
            .map(|b| format!("{:12.4}", b.value))
            .collect();
        let check = match a.power_check() {
            // Two inputs compare the drives' power with the loads' (W).
            Ok(c) if plan.input_count() == 2 => format!(
                "drive power {:10.4} W, by virtual power {:10.4} W, rel. diff {:.1e}",
                c.chain,
                c.virtual_power,
                c.relative_error()
            ),
            Ok(c) => format!(
                "virtual power {:12.4}, rel. diff {:.1e}",
                c.virtual_power,
                c.relative_error()
            ),
            // A rocking input at rest where it reverses has no virtual power to compare.
            Err(_) => "input at rest: no virtual power".to_owned(),
        };
        println!(
            "position {k:2}: input {}  balance {} ({check})  worst link residual {:.1e}",
            q.join(" "),
            b.join(" "),
            a.worst_residual()
        );
    }
    let table = plan.course_table(&positions);
    println!("\n{}", table.to_text(4));
    fs::create_dir_all(dir)?;
    let file = dir.join(format!("{}.csv", stem(&linkage)));
    table.write_csv(fs::File::create(&file)?)?;
    println!("course table written to {}", file.display());
    #[cfg(feature = "draw")]
    match &course {
        AnyCourse::One(c) => pictures::write(&linkage, &plan, &c.inputs, dir)?,
        AnyCourse::Two(c) => pictures::write_two(&linkage, &plan, c, dir)?,
    }
    Ok(table)
}

/// The stem of the files written for `linkage`: its name with spaces and slashes as `_`.
fn stem(linkage: &Linkage) -> String {
    linkage.name.replace([' ', '/'], "_")
}

/// The pictures of the linkage (feature `draw`), each an SVG file in `dir`.
#[cfg(feature = "draw")]
mod pictures {
    use std::fs;
    use std::path::Path;
    use tmm::draw::{self, Diagram, Style};
    use tmm::kinematics::Motion;
    use tmm::linkage::{
        uniform_inputs, Course, Linkage, Plan, Sweep, TwoInputCourse, WorkspaceOptions,
    };

    /// Writes the picture `what` of `linkage` as `dir/STEM_what.svg` and says so.
    fn saver<'a>(
        linkage: &Linkage,
        dir: &'a Path,
    ) -> impl Fn(&str, &str) -> std::io::Result<()> + 'a {
        let stem = super::stem(linkage);
        move |what, svg| {
            let file = dir.join(format!("{stem}_{what}.svg"));
            fs::write(&file, svg)?;
            println!("{what} drawn in {}", file.display());
            Ok(())
        }
    }

    /// The pictures of a linkage with two inputs: the scheme and the reactions at the first
    /// position, the plan along the course, an animation round it, and the workspace of the
    /// first named point (or the first joint between two links that are neither the frame
    /// nor an input link).
    pub fn write_two(
        linkage: &Linkage,
        plan: &Plan,
        course: &TwoInputCourse,
        dir: &Path,
    ) -> Result<(), Box<dyn std::error::Error>> {
        let style = Style::default();
        let save = saver(linkage, dir);
        let first = course.inputs[0];
        save("scheme", &draw::scheme(plan, first, &style)?.svg)?;
        save("forces", &draw::forces(plan, first, &style)?.svg)?;
        let point = plan
            .point_names()
            .first()
            .map(String::as_str)
            .or_else(|| plan.end_joint());
        let paths: Vec<&str> = point.into_iter().collect();
        save(
            "plan",
            &draw::plan_view_two(plan, course, &paths, &style)?.svg,
        )?;
        let speed = linkage.input_speed();
        let round = TwoInputCourse::around_reference(plan, 360, speed)?;
        save(
            "animation",
            &draw::animation_path(plan, &round.inputs, 4.0, &style)?.svg,
        )?;
        if let Some(point) = point {
            let ws = plan.workspace(point, &WorkspaceOptions::default())?;
            println!(
                "workspace of {point}: {:.4} m², {} outline(s), {} singular curve(s)",
                ws.region.area(),
                ws.boundary.len(),
                ws.singular.len()
            );
            save("workspace", &draw::workspace(plan, &ws, &style)?.svg)?;
        }
        Ok(())
    }

    pub fn write(
        linkage: &Linkage,
        plan: &Plan,
        inputs: &[Motion],
        dir: &Path,
    ) -> Result<(), Box<dyn std::error::Error>> {
        let style = Style::default();
        let save = saver(linkage, dir);
        let first = inputs[0];
        save("scheme", &draw::scheme(plan, first, &style)?.svg)?;
        // The forces at the first position that has them (a rocking input's course starts at
        // its lock, where the driven group is at its dead point).
        let loaded = inputs
            .iter()
            .copied()
            .find(|&m| plan.analyse(m).is_ok())
            .unwrap_or(first);
        save("forces", &draw::forces(plan, loaded, &style)?.svg)?;
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
        let speed = linkage.input_speed();
        let course = Course::new(plan, linkage.output.as_ref(), 12, speed)?;
        let paths = plan.traced_points();
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
        let output = plan.output_or_last(linkage.output.as_ref());
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
        // The hodograph of the crank pin's reaction.
        if let Some(pin) = plan.crank_pin() {
            save(
                "hodograph",
                &draw::diagram(plan, &course, &Diagram::Hodograph(pin.to_owned()), &style)?.svg,
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
