//! Hostile options, one test per class of failure found by sweeping every subcommand over the
//! bundled files: a run that would take hours is refused at once with the budget it breaks
//! and the option to change; a machine option out of its domain names that option; an empty
//! file or file name is said to be one. Every failure is one line on stderr, exit code 1.

mod common;

use common::{assert_one_line_failure, tmm};

/// The number after `key` in `text` (up to the next space, comma or unit).
fn number_after(text: &str, key: &str) -> f64 {
    let at = text
        .find(key)
        .unwrap_or_else(|| panic!("{key:?} in {text}"))
        + key.len();
    let num: String = text[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | '-' | '+'))
        .collect();
    num.parse()
        .unwrap_or_else(|_| panic!("a number after {key:?} in {text}"))
}

/// A run-up whose step cannot finish it within the step budget is refused before it starts:
/// a spin-up from rest to 10⁹ rad/s, a rotor of 10³⁰⁰ kg·m², a motor of 10⁻³⁰⁰ N·m (each
/// needing far more steps than allowed), or a speed of 10⁻⁹ rad/s, whose default motor is so
/// steep that RK4's stable step makes a turn take 10²³ steps. The spin-up's stated least time
/// is J·|ω|/a of the stated J, ω and a: the motor's full starting moment on the crank alone.
#[test]
fn a_run_up_beyond_its_step_budget_is_refused_at_once() {
    let cases: [(&[&str], &str); 4] = [
        (&["--speed", "1e9"], "--speed"),
        (&["--rotor", "1e300"], "--rotor"),
        (&["--motor", "1e-300,0"], "--motor"),
        (&["--speed", "1e-9"], "larger --speed"),
    ];
    for (file, omega) in [("four-bar", 10.0), ("mechanism-compressor", 10.0)] {
        for (extra, option) in cases {
            let mut args = vec!["dynamics", file, "--run-up"];
            args.extend_from_slice(extra);
            let r = tmm(&args);
            assert_one_line_failure(&r, file);
            assert!(r.stderr.contains("above the 1e6"), "{}", r.stderr);
            assert!(r.stderr.contains(option), "names {option}: {}", r.stderr);
            if r.stderr.contains("needs at least") {
                let a = number_after(&r.stderr, "a = ");
                let j = number_after(&r.stderr, "J_red ≈ ");
                let w = if extra[0] == "--speed" {
                    extra[1].parse().unwrap()
                } else {
                    omega
                };
                let t = number_after(&r.stderr, "at least ");
                // J is printed to 5 significant digits.
                assert!(
                    (t - j * w / a).abs() <= 1e-4 * t,
                    "{t} s against J·ω/a = {}: {}",
                    j * w / a,
                    r.stderr
                );
            }
        }
    }
    // The budget refuses nothing a machine really does: the default run-up still runs.
    let r = tmm(&["dynamics", "four-bar", "--run-up"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("steady after"), "{}", r.stdout);
}

/// A motor that cannot drive the crank in the sense asked (a ≤ 0) or whose moment grows with
/// speed (b < 0, a run-away) is refused naming --motor, not run until the budget is spent.
#[test]
fn a_motor_that_cannot_drive_or_runs_away_is_refused() {
    for motor in ["-1,-1", "0,5", "10,-1", "nan,0"] {
        let r = tmm(&["dynamics", "four-bar", "--run-up", "--motor", motor]);
        assert_one_line_failure(&r, "four-bar");
        assert!(r.stderr.contains("--motor"), "{motor}: {}", r.stderr);
    }
}

/// Each machine option out of its domain is named in the one line: a negative or NaN rotor,
/// a coefficient of speed fluctuation outside (0, 2) or so small that the flywheel overflows,
/// a motor of a linkage with two inputs that is not finite, and a run of two inputs that
/// leaves the linkage's reach (the robot, undriven, falls and spins for 10⁴ s).
#[test]
fn a_machine_option_out_of_its_domain_is_named() {
    for (args, option) in [
        (&["dynamics", "four-bar", "--rotor", "-1"][..], "--rotor"),
        (&["dynamics", "four-bar", "--rotor", "nan"][..], "--rotor"),
        (
            &["dynamics", "four-bar", "--flywheel", "0"][..],
            "--flywheel 0",
        ),
        (
            &["dynamics", "four-bar", "--flywheel", "nan"][..],
            "--flywheel NaN",
        ),
        (
            &["dynamics", "shaper", "--flywheel", "1e-300"][..],
            "--flywheel 1e-300",
        ),
        (
            &["dynamics", "five-bar-robot", "--rotor", "-1"][..],
            "--rotor",
        ),
        (
            &[
                "dynamics",
                "five-bar-robot",
                "--run",
                "1",
                "--motor2",
                "nan,0",
            ][..],
            "--motor2",
        ),
        (
            &[
                "dynamics",
                "five-bar-robot",
                "--run",
                "1",
                "--motor",
                "1e300,0",
            ][..],
            "--run",
        ),
    ] {
        let r = tmm(args);
        assert_one_line_failure(&r, args[1]);
        assert!(
            r.stderr.contains(option),
            "{args:?} names {option}: {}",
            r.stderr
        );
    }
}

/// An empty description file, or an empty name for one, is said to be that, with what to do.
#[test]
fn an_empty_file_or_file_name_is_said_so() {
    let empty = std::env::temp_dir().join(format!("tmm-cli-empty-{}.json", std::process::id()));
    std::fs::write(&empty, "  \n").unwrap();
    let path = empty.to_string_lossy().into_owned();
    for command in ["check", "analyse", "draw", "dynamics"] {
        let r = tmm(&[command, &path]);
        assert_one_line_failure(&r, &path);
        assert!(r.stderr.contains("the file is empty"), "{}", r.stderr);
        let r = tmm(&[command, ""]);
        assert_one_line_failure(&r, "");
        assert!(r.stderr.contains("name is empty"), "{}", r.stderr);
    }
    let _ = std::fs::remove_file(&empty);
}

/// A picture at a position that does not assemble (the Peaucellier cell's crank rocks between
/// ±96.4°, so 120° is beyond its lock) names the option and the value asked for, the gap by
/// which the group fails to close (positive), and where to see the range; a single value
/// where a linkage with two inputs needs a pair names the option given in its hint.
#[test]
fn a_position_that_does_not_assemble_names_the_option() {
    for option in ["--scheme", "--forces"] {
        let r = tmm(&["draw", "peaucellier-lipkin", option, "120"]);
        assert_one_line_failure(&r, "peaucellier-lipkin");
        assert!(
            r.stderr.contains(&format!("{option} 120: ")),
            "{}",
            r.stderr
        );
        assert!(
            number_after(&r.stderr, "closure fails by ") > 0.0,
            "{}",
            r.stderr
        );
        assert!(r.stderr.contains("tmm check"), "{}", r.stderr);
        let r = tmm(&["draw", "five-bar-robot", "--workspace", "X"]);
        assert_one_line_failure(&r, "five-bar-robot");
        assert!(
            r.stderr.contains("--workspace takes a joint"),
            "{}",
            r.stderr
        );
        let r = tmm(&["draw", "five-bar-robot", option, "100"]);
        assert_one_line_failure(&r, "five-bar-robot");
        assert!(
            r.stderr.contains(&format!("{option} 120 60")),
            "{}",
            r.stderr
        );
    }
}

/// A two-input picture at a speed beyond ±10⁹ rad/s names `--speed`, not an acceleration
/// deep in the library (the five-bar's balance diagram at 10²⁰⁰ rad/s reported "input
/// acceleration must be finite, got -inf").
#[test]
fn a_two_input_picture_at_a_hostile_speed_names_the_speed() {
    for (extra, speed) in [
        (&["--diagram", "balance"][..], "1e200"),
        (&["--scheme", "100", "60"][..], "-1e300"),
        (&["--plan"][..], "1e10"),
    ] {
        let out = std::env::temp_dir().join("tmm-hostile-speed.svg");
        let mut args = vec!["draw", "five-bar-robot"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--speed", speed, "-o", out.to_str().unwrap()]);
        let r = tmm(&args);
        assert_one_line_failure(&r, "five-bar-robot");
        assert!(
            r.stderr.contains("the speed must be finite"),
            "{}",
            r.stderr
        );
    }
}
