//! A run from rest that jams: the bundled five-bar robot with f = 0.3 on pins of 5 cm in every
//! joint, 5 N·m on crank 1. The couplers fold and a dyad self-locks under its friction before
//! 0.3 s: the program prints the rows up to the jam, then the jam's line (its time, the joint,
//! det(I − J)), and exits 0 (a stop of the motion is a result, not a failure: exit code 1 is
//! kept for failures, 2 for usage errors). Checked against the library's own run.

mod common;

use common::{assert_success, tmm, Broken};
use tmm::dynamics::machines::LinearMotor;
use tmm::dynamics::{run, Outcome, Rk4, RunOptions, State};
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{Linkage, Plan};
use tmm::nalgebra::Vector2;

/// The bundled five-bar with every hinge's ρ = 0.3 · 5 cm, in a temporary file.
fn jamming_five_bar() -> (Broken, String) {
    let text = std::fs::read_to_string(common::root().join("linkages/five-bar-robot.json"))
        .expect("the bundled five-bar");
    let open = text.find('{').expect("an object");
    let with = format!(
        "{{\"friction\": {{\"f\": 0.3, \"pin_radius\": 0.05}},{}",
        &text[open + 1..]
    );
    (Broken::new("jam-five-bar", &with), with)
}

const ARGS: [&str; 6] = ["--run", "0.5", "--motor", "5,0", "--motor2", "0,0"];

/// The number after `key` in `line`, up to the next space.
fn number_after(line: &str, key: &str) -> f64 {
    let at = line
        .find(key)
        .unwrap_or_else(|| panic!("{key:?} in {line:?}"))
        + key.len();
    let rest = &line[at..];
    let end = rest.find(' ').unwrap_or(rest.len());
    rest[..end]
        .trim_end_matches([',', ':'])
        .parse()
        .unwrap_or_else(|e| panic!("{:?} after {key:?}: {e}", &rest[..end]))
}

#[test]
fn a_run_that_jams_prints_its_rows_and_then_the_jam() {
    let (file, text) = jamming_five_bar();
    let mut args = vec!["dynamics", "FILE"];
    args.extend(ARGS);
    let path = file.path();
    args[1] = &path;
    let r = tmm(&args);
    assert_success(&r, "a run that jams");
    let line = r
        .stdout
        .lines()
        .find(|l| l.contains("jams"))
        .unwrap_or_else(|| panic!("the jam's line in {}", r.stdout));
    assert!(
        line.starts_with("the run stopped: the linkage jams at t = "),
        "{line}"
    );
    let t = number_after(line, "jams at t = ");
    let value = number_after(line, "det(I - J) = ");
    let joint = line
        .split("joint ")
        .nth(1)
        .and_then(|s| s.split(" self-locks").next())
        .unwrap_or_else(|| panic!("the joint in {line}"));
    // The energy line follows the jam's: the rows up to it are accounted for.
    assert!(
        r.stdout.contains("energy: kinetic energy gained"),
        "{}",
        r.stdout
    );

    // The rows: every one before the jam, the last within the time tolerance of it.
    args.extend(["--format", "json"]);
    let j = tmm(&args);
    assert_success(&j, "a run that jams, as JSON");
    let v: serde_json::Value = serde_json::from_str(&j.stdout).expect("JSON");
    let run_v = &v["run"];
    let column = |k: &str| -> Vec<f64> {
        run_v[k]
            .as_array()
            .unwrap_or_else(|| panic!("column {k}"))
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let times = column("t");
    let stopped = run_v["stopped"].as_str().expect("the stop");
    assert!(
        stopped.contains(joint) && stopped.contains("jams"),
        "{stopped}"
    );
    let last = *times.last().unwrap();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "the rows in time");
    assert!(
        times.len() > 100 && last < 0.5,
        "{} rows to {last}",
        times.len()
    );
    assert!(
        (last - t).abs() <= 1e-6,
        "last row {last} vs the jam at {t}"
    );
    for k in ["q1", "q2", "qd1", "qd2", "kinetic"] {
        assert!(column(k).iter().all(|x| x.is_finite()), "{k}");
    }

    // The library's run, independently: the same machine and steps jam at the same time in
    // the same joint (the line prints six decimals and three significant digits).
    let linkage = Linkage::from_json(&text).unwrap();
    let plan = Plan::new(&linkage).unwrap();
    let mut sys = LinkageSystem::new(plan.clone()).unwrap();
    for (k, a) in [(0, 5.0), (1, 0.0)] {
        sys = sys
            .with_motor(k, Motor::Linear(LinearMotor { a, b: 0.0 }))
            .unwrap();
    }
    let reference = plan.reference_inputs();
    let step = run_v["step"].as_f64().unwrap();
    let mut opts = RunOptions::until(0.5, step);
    opts.record_every = 1;
    let q0 = Vector2::new(reference[0], reference[1]);
    let lib = run(&sys, &Rk4, State::at_rest(q0), &opts).unwrap();
    let Outcome::Jammed {
        t: tl,
        joint: jl,
        value: vl,
    } = lib.outcome
    else {
        panic!("the library's run jams: {:?}", lib.outcome)
    };
    println!("CLI: {line}\nlibrary: jams at {tl:.9} s, joint {jl}, det {vl:e}");
    assert!((tl - t).abs() <= 5e-7, "{tl} vs {t}");
    assert_eq!(plan.joint_names()[jl], joint);
    assert!(
        (vl - value).abs() <= 5e-3 * vl.abs().max(1e-300) + 1e-20,
        "{vl} vs {value}"
    );
    assert!(value <= 1.5e-8, "{value}");
    assert_eq!(lib.trajectory.len(), times.len());
}
