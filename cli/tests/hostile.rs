//! Hostile options, one test per class of failure found by sweeping every subcommand over the
//! bundled files: a run that would take hours is refused at once with the budget it breaks
//! and the option to change; a machine option out of its domain names that option; an empty
//! file or file name is said to be one. Every failure is one line on stderr, exit code 1.

mod common;

use common::synth_function::SynthFunction;
use common::{assert_one_line_failure, assert_success, number_after, tmm, Broken, PISTON_DRIVEN};

/// The number that ends just before `key` in `text`.
fn number_before(text: &str, key: &str) -> f64 {
    let end = text
        .find(key)
        .unwrap_or_else(|| panic!("{key:?} in {text}"));
    let start = text[..end].rfind(' ').map_or(0, |k| k + 1);
    text[start..end]
        .parse()
        .unwrap_or_else(|_| panic!("a number before {key:?} in {text}"))
}

/// A run-up whose step cannot finish it within the step budget is refused before it starts:
/// a spin-up from rest to 10⁹ rad/s, a rotor of 10³⁰⁰ kg·m², a motor of 10⁻³⁰⁰ N·m (each
/// needing far more steps than allowed), or a speed of 10⁻⁹ rad/s, whose default motor is so
/// steep that RK4's stable step makes a turn take 10²³ steps. The budget is at most 10⁶
/// steps (fewer where the linkage's solve is slow: the double butterfly's general group), and
/// the steps stated exceed it. The spin-up's stated least time is J·|ω|/a of the stated J, ω
/// and a: the motor's full starting moment on the crank alone.
#[test]
fn a_run_up_beyond_its_step_budget_is_refused_at_once() {
    let cases: [(&[&str], &str); 4] = [
        (&["--speed", "1e9"], "--speed"),
        (&["--rotor", "1e300"], "--rotor"),
        (&["--motor", "1e-300,0"], "--motor"),
        (&["--speed", "1e-9"], "larger --speed"),
    ];
    for (file, omega) in [
        ("four-bar", 10.0),
        ("mechanism-compressor", 10.0),
        ("double-butterfly", 10.0),
    ] {
        for (extra, option) in cases {
            let mut args = vec!["dynamics", file, "--run-up", "--positions", "36"];
            args.extend_from_slice(extra);
            let r = tmm(&args);
            assert_one_line_failure(&r, file);
            let budget = number_after(&r.stderr, "above the ");
            let steps = number_before(&r.stderr, " steps of h");
            assert!(
                (1.0..=1e6).contains(&budget) && steps > budget,
                "{steps} steps against a budget of {budget}: {}",
                r.stderr
            );
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

/// An option given where it would change nothing is refused, naming the option and why,
/// whatever its value (NaN included), rather than silently ignored: the grid, span, run and
/// second motor of two inputs on a linkage with one; the positions over a turn and the speed
/// on one with two; a motor without the run it drives; a speed with a workspace. Without the
/// option the same command runs.
#[test]
fn an_option_that_changes_nothing_is_refused_naming_it() {
    let cases: [(&[&str], &str, &str); 12] = [
        (
            &["dynamics", "four-bar", "--span", "nan"],
            "--span",
            "has one input",
        ),
        (
            &["dynamics", "four-bar", "--span", "10"],
            "--span",
            "has one input",
        ),
        (
            &["dynamics", "four-bar", "--grid", "5"],
            "--grid",
            "has one input",
        ),
        (
            &["dynamics", "four-bar", "--run", "1"],
            "--run",
            "has one input",
        ),
        (
            &["dynamics", "four-bar", "--motor2", "1,0"],
            "--motor2",
            "one input",
        ),
        (
            &["dynamics", "four-bar", "--motor", "60,2"],
            "--motor",
            "no run-up",
        ),
        (
            &["dynamics", "five-bar-robot", "--positions", "36"],
            "--positions",
            "two inputs",
        ),
        (
            &["dynamics", "five-bar-robot", "--speed", "nan"],
            "--speed",
            "two inputs",
        ),
        (
            &["dynamics", "five-bar-robot", "--speed", "5"],
            "--speed",
            "two inputs",
        ),
        (
            &["dynamics", "five-bar-robot", "--motor", "1,0"],
            "--motor",
            "no run",
        ),
        (
            &["dynamics", "five-bar-robot", "--motor2", "nan,0"],
            "--motor2",
            "no run",
        ),
        (
            &[
                "draw",
                "five-bar-robot",
                "--workspace",
                "B",
                "--speed",
                "nan",
            ],
            "--speed",
            "workspace",
        ),
    ];
    for (args, option, why) in cases {
        let r = tmm(args);
        assert_one_line_failure(&r, args[1]);
        assert!(
            r.stderr.contains(&format!("{option} ")) && r.stderr.contains(why),
            "{args:?} names {option} and says {why:?}: {}",
            r.stderr
        );
    }
    // The refusal is the option's: without it (and its value) the command runs.
    for args in [
        &["dynamics", "four-bar"][..],
        &["dynamics", "five-bar-robot", "--grid", "3"],
    ] {
        assert_success(&tmm(args), &args.join(" "));
    }
}

/// A slider input's coordinate that is not a finite number of metres within ±10⁹ m names the
/// option it came from (it read "no position could be analysed: input must be finite").
#[test]
fn a_slider_coordinate_out_of_its_domain_names_the_option() {
    let file = Broken::new("hostile-slider", PISTON_DRIVEN);
    for value in ["nan", "inf", "-1e300"] {
        for (args, option) in [
            (&["analyse", &file.path(), "--at", value][..], "--at"),
            (&["draw", &file.path(), "--scheme", value], "--scheme"),
            (&["draw", &file.path(), "--forces", value], "--forces"),
        ] {
            let r = tmm(args);
            assert_one_line_failure(&r, &file.path());
            assert!(
                r.stderr.contains(&format!("{option} ")) && r.stderr.contains("metres"),
                "{args:?}: {}",
                r.stderr
            );
        }
    }
}

/// A file that is not a description is refused before it is read, naming it and why: a
/// directory, a device, a file of 50 MB (its size and the 16 MB limit, in its words), a file
/// that is not UTF-8 text.
#[test]
fn a_file_that_is_not_a_description_is_refused_before_it_is_read() {
    let big = Broken::new("hostile-big", "");
    std::fs::File::options()
        .write(true)
        .open(&big.0)
        .and_then(|f| f.set_len(50 * 1024 * 1024))
        .expect("a sparse file of 50 MB");
    let binary = Broken::new("hostile-binary", "");
    std::fs::write(&binary.0, [b'{', 0xff, 0xfe, b'}']).unwrap();
    let dir = common::root().join("linkages");
    let dir = dir.to_str().unwrap();
    let mut cases = vec![
        (
            big.path(),
            "the file is 50.0 MB (52428800 bytes), above the 16.0 MB",
        ),
        (binary.path(), "not UTF-8"),
        (dir.to_owned(), "it is a directory"),
    ];
    if cfg!(unix) {
        cases.push(("/dev/zero".to_owned(), "not a file but a device"));
    }
    for (path, why) in cases {
        for command in ["check", "analyse", "draw", "dynamics"] {
            let r = tmm(&[command, &path]);
            assert_one_line_failure(&r, &path);
            assert!(r.stderr.contains(why), "{command} {path}: {}", r.stderr);
        }
    }
}

/// A file to write that cannot be written — in a directory that does not exist, or a
/// directory itself — is refused before the work, naming the path and why.
#[test]
fn an_output_that_cannot_be_written_is_refused_before_the_work() {
    let missing = std::env::temp_dir().join(format!("tmm-no-such-dir-{}", std::process::id()));
    let into_missing = missing.join("out.svg");
    let into_missing = into_missing.to_str().unwrap();
    let dir = std::env::temp_dir();
    let dir = dir.to_str().unwrap();
    for (args, path, why) in [
        (
            &["draw", "shaper", "--plan", "-o", into_missing][..],
            into_missing,
            "does not exist",
        ),
        (
            &["analyse", "shaper", "--csv", into_missing],
            into_missing,
            "does not exist",
        ),
        (
            &["dynamics", "shaper", "--csv", into_missing],
            into_missing,
            "does not exist",
        ),
        (&["draw", "shaper", "-o", dir], dir, "it is a directory"),
    ] {
        let r = tmm(args);
        assert_eq!(r.code, 1, "{args:?}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
        assert!(
            r.stderr.contains(path) && r.stderr.contains(why),
            "{args:?}: {}",
            r.stderr
        );
        assert!(r.stdout.is_empty(), "{args:?}");
    }
    assert!(!missing.exists());
}

/// A machine whose links carry no mass (Jansen's leg as bundled) has no run-up to integrate:
/// refused naming J_red and the fix; with a flywheel on the crank (--rotor) it runs up to a
/// steady turn that balances energy. Over a steady turn the kinetic energy returns, so
/// ∮(a − b·ω) dφ + ∮ M_red dφ = 0: a − b·ω_φ + M̄_red = 0 with ω_φ the mean of ω over the
/// angle, which exceeds the turn's mean over time ω̄ = 2π/T by var(ω)/ω̄ ≤ (δ/2)²·ω̄. So
/// 0 ≤ a − b·ω̄ + M̄_red ≤ b·ω̄·δ²/4.
#[test]
fn a_run_up_without_inertia_is_refused_and_runs_with_a_rotor() {
    let r = tmm(&["dynamics", "jansen-leg", "--run-up"]);
    assert_one_line_failure(&r, "jansen-leg");
    assert!(
        r.stderr.contains("J_red is 0 kg·m²") && r.stderr.contains("--rotor"),
        "{}",
        r.stderr
    );
    let r = tmm(&[
        "dynamics",
        "jansen-leg",
        "--run-up",
        "--rotor",
        "0.5",
        "--format",
        "json",
    ]);
    assert_success(&r, "jansen-leg --run-up --rotor 0.5");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("JSON");
    let loads: Vec<f64> = v["reduced"]["M_red"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    #[allow(clippy::cast_precision_loss)]
    let mean_load = loads.iter().sum::<f64>() / loads.len() as f64;
    let (a, b) = (
        v["run_up"]["motor"]["a"].as_f64().unwrap(),
        v["run_up"]["motor"]["b"].as_f64().unwrap(),
    );
    let last = v["run_up"]["turns"].as_array().unwrap().last().unwrap();
    let (w, delta) = (
        last["omega_mean"].as_f64().unwrap(),
        last["delta"].as_f64().unwrap(),
    );
    let gap = a - b * w + mean_load;
    // The mean load over 360 positions is the integral's to ~10⁻⁵ of the loads' scale.
    let slack = 1e-4 * loads.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(
        gap >= -slack && gap <= b * w * delta * delta / 4.0 + slack,
        "a − b·ω̄ + M̄ = {gap} outside [0, {}]",
        b * w * delta * delta / 4.0
    );
}

/// Whether `text` holds a non-finite number as Rust, JSON readers or a person would read one:
/// a word `NaN`, `nan`, `inf`, `Infinity` (`infinite` in a sentence is not one).
fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .find(|w| matches!(*w, "NaN" | "nan" | "inf" | "Inf" | "Infinity" | "infinity"))
}

/// One hostile run judged: it ends (no signal) with exit code 0, 1 or 2; a failure is one
/// line on stderr beginning `tmm: `, never a panic; a success holds no non-finite number on
/// standard output or in the file it wrote.
fn judge(args: &[&str], out: &std::path::Path) -> i32 {
    let _ = std::fs::remove_file(out);
    let r = tmm(args);
    assert!(
        matches!(r.code, 0..=2),
        "{args:?}: exit code {}: {}",
        r.code,
        r.stderr
    );
    assert!(!r.stderr.contains("panicked"), "{args:?}: {}", r.stderr);
    if r.code == 0 {
        let written = std::fs::read_to_string(out).unwrap_or_default();
        for text in [&r.stdout, &written] {
            if let Some(w) = non_finite_word(text) {
                panic!(
                    "{args:?}: {w} in the result: {}",
                    &text[..text.len().min(2000)]
                );
            }
        }
    } else {
        assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
        assert!(r.stderr.starts_with("tmm: "), "{args:?}: {}", r.stderr);
        // The message writes numbers as a person reads them: no `inf` or `NaN` the user did
        // not type, no run of 20 digits (10³⁰⁸ in full) the user did not type.
        // (A value the library names as not finite, "got NaN", is what it says.)
        let typed = args.join(" ");
        let told = ["got NaN", "got -inf", "got inf"]
            .iter()
            .fold(r.stderr.clone(), |t, said| t.replace(said, ""));
        if non_finite_word(&typed).is_none() {
            assert!(non_finite_word(&told).is_none(), "{args:?}: {}", r.stderr);
        }
        if longest_digit_run(&typed) < 20 {
            assert!(longest_digit_run(&r.stderr) < 20, "{args:?}: {}", r.stderr);
        }
    }
    r.code
}

/// The most digits in a row in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

/// The hostile numbers every numeric option is given: NaN, the infinities, the largest and
/// the least (subnormal) doubles, zero of both signs, negatives, huge counts (beyond `u32`
/// and beyond `u64`), an empty and a garbage word. `TMM_HOSTILE_CASES` at 1000 or more
/// (the CI's release sweeps) adds more.
fn hostile_values() -> Vec<&'static str> {
    let mut v = vec![
        "nan",
        "inf",
        "-inf",
        "1e308",
        "-1e308",
        "5e-324",
        "0",
        "-0",
        "-1",
        "",
        "x",
        "99999999999999999999",
    ];
    if std::env::var("TMM_HOSTILE_CASES")
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .is_some_and(|n| n >= 1000)
    {
        v.extend([
            "-5e-324",
            "1e-300",
            "1e20",
            "4294967296",
            "1e154",
            "-1e154",
            "2.5",
        ]);
    }
    v
}

/// Every option of every subcommand taking a number, with each hostile value, on a linkage
/// with one input and on one with two, and each pair option with hostile pairs: every run
/// ends with a one-line error (exit 1, or 2 for a value clap refuses) or a finite result, in
/// the budgets of the counts (no run here may spend its budget: each is refused up front, or
/// small). The classes this sweep found are fixed: a degree echoed in 309 digits (`--swing
/// 1e308`), a synthesised length of 10²³ mm in 24 digits, a run-up at 5e-324 rad/s refused
/// by a library parameter the user never typed (`omega_nom`), a spin-up time in 17 digits.
#[test]
fn every_option_of_every_subcommand_survives_hostile_values() {
    let dir = std::env::temp_dir().join(format!("tmm-cli-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("o.svg");
    let svg = svg.to_str().unwrap();
    let json = dir.join("o.json");
    let json = json.to_str().unwrap();
    let points = dir.join("points.csv");
    std::fs::write(&points, common::coupler_curve_csv(12)).unwrap();
    let points = points.to_str().unwrap();
    let (one, two) = ("four-bar", "five-bar-robot");
    let mut runs = 0;
    let mut codes = [0; 3];
    for v in hostile_values() {
        let x = format!("1,{v}");
        let crank = format!("-30,{v}");
        let at = format!("{v},101.4");
        let power = format!("x^{v}");
        let cases: Vec<(Vec<&str>, &str)> = vec![
            (vec!["analyse", one, "--positions", v], ""),
            (vec!["analyse", one, "--at", v], ""),
            (vec!["analyse", one, "--speed", v], ""),
            (vec!["analyse", two, "--at", v, v], ""),
            (vec!["analyse", "shaper", "--at", v, "--speed", "2"], ""),
            (vec!["draw", one, "--scheme", v, "-o", svg], svg),
            (vec!["draw", one, "--forces", v, "-o", svg], svg),
            (vec!["draw", one, "--plan", "--speed", v, "-o", svg], svg),
            (vec!["draw", one, "--animate", "--speed", v, "-o", svg], svg),
            (
                vec!["draw", one, "--diagram", "balance", "--speed", v, "-o", svg],
                svg,
            ),
            (vec!["draw", two, "--scheme", v, "60", "-o", svg], svg),
            (
                vec![
                    "draw",
                    two,
                    "--animate",
                    "--along",
                    "120",
                    "60",
                    v,
                    "90",
                    "-o",
                    svg,
                ],
                svg,
            ),
            (vec!["dynamics", one, "--speed", v], ""),
            (vec!["dynamics", one, "--run-up", "--speed", v], ""),
            (vec!["dynamics", one, "--flywheel", v], ""),
            (vec!["dynamics", one, "--run-up", "--rotor", v], ""),
            (vec!["dynamics", one, "--positions", v], ""),
            (vec!["dynamics", two, "--grid", v], ""),
            (vec!["dynamics", two, "--span", v], ""),
            (vec!["dynamics", two, "--run", v], ""),
            (
                vec![
                    "synth",
                    "crank-rocker",
                    "-K",
                    v,
                    "--swing",
                    "45",
                    "--rocker",
                    "0.3",
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "crank-rocker",
                    "-K",
                    "1.2",
                    "--swing",
                    v,
                    "--rocker",
                    "0.3",
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "crank-rocker",
                    "-K",
                    "1.2",
                    "--swing",
                    "45",
                    "--rocker",
                    v,
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "crank-rocker",
                    "-K",
                    "1.2",
                    "--swing",
                    "45",
                    "--rocker",
                    "0.3",
                    "--frame",
                    v,
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "crank-rocker",
                    "-K",
                    "1.2",
                    "--swing",
                    "45",
                    "--rocker",
                    "0.3",
                    "--min-transmission",
                    v,
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "slider-crank",
                    "--stroke",
                    v,
                    "-K",
                    "1.2",
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "slider-crank",
                    "--stroke",
                    "0.2",
                    "-K",
                    "1.2",
                    "--offset",
                    v,
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "shaper",
                    "--stroke",
                    "0.3",
                    "-K",
                    v,
                    "--centre-distance",
                    "0.25",
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "shaper",
                    "--stroke",
                    "0.3",
                    "-K",
                    "1.6",
                    "--centre-distance",
                    v,
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "through",
                    "--frame",
                    v,
                    "--at",
                    "40,101.4",
                    "100,112.8",
                    "160,131.8",
                    "--min-transmission",
                    "0",
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "through",
                    "--frame",
                    "0.4",
                    "--at",
                    &at,
                    "100,112.8",
                    "160,131.8",
                    "--min-transmission",
                    "0",
                    "-o",
                    json,
                ],
                json,
            ),
            (
                SynthFunction {
                    x: &x,
                    ..Default::default()
                }
                .command(&["-o", json]),
                json,
            ),
            (
                SynthFunction {
                    crank: &crank,
                    ..Default::default()
                }
                .command(&["-o", json]),
                json,
            ),
            (
                SynthFunction {
                    function: &power,
                    frame: v,
                    ..Default::default()
                }
                .command(&["-o", json]),
                json,
            ),
            (
                SynthFunction::default().command(&["--least-squares", v, "-o", json]),
                json,
            ),
            (
                vec!["synth", "path", points, "--budget", v, "-o", json],
                json,
            ),
            (
                vec![
                    "synth", "path", points, "--budget", "500", "--seed", v, "-o", json,
                ],
                json,
            ),
            (
                vec![
                    "synth",
                    "path",
                    points,
                    "--budget",
                    "500",
                    "--designs",
                    v,
                    "-o",
                    json,
                ],
                json,
            ),
            (
                vec![
                    "synth", "path", points, "--budget", "500", "--time", v, "-o", json,
                ],
                json,
            ),
        ];
        for (args, out) in cases {
            let code = judge(&args, std::path::Path::new(out));
            codes[usize::try_from(code).unwrap()] += 1;
            runs += 1;
        }
    }
    for pair in [
        "nan,0",
        "1e308,1e308",
        "5e-324,0",
        "1,",
        ",",
        "1,2,3",
        "0,0",
        "-1,-1",
        "inf,1",
    ] {
        for args in [
            vec!["dynamics", one, "--run-up", "--motor", pair],
            vec!["dynamics", two, "--run", "0.2", "--motor", pair],
            vec!["dynamics", two, "--run", "0.2", "--motor2", pair],
            SynthFunction {
                function: "sqrt",
                x: pair,
                ..Default::default()
            }
            .command(&["-o", json]),
            vec![
                "synth",
                "through",
                "--frame",
                "0.4",
                "--at",
                pair,
                "100,112.8",
                "160,131.8",
                "-o",
                json,
            ],
        ] {
            let code = judge(&args, std::path::Path::new(json));
            codes[usize::try_from(code).unwrap()] += 1;
            runs += 1;
        }
    }
    // Options given twice, or together where they exclude each other: clap's usage error.
    for args in [
        &["analyse", one, "--speed", "1", "--speed", "2"][..],
        &["draw", one, "-o", svg, "-o", svg],
        &["check", one, "--format", "json", "--format", "text"],
        &["analyse", one, "--positions", "3", "--at", "1"],
        &["draw", one, "--plan", "--animate", "-o", svg],
        &[
            "synth",
            "shaper",
            "--stroke",
            "0.3",
            "--stroke",
            "0.2",
            "-K",
            "1.6",
            "--centre-distance",
            "0.25",
        ],
    ] {
        assert_eq!(judge(args, std::path::Path::new("")), 2, "{args:?}");
        runs += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    println!("{runs} hostile runs: exit codes 0/1/2 {codes:?}");
    // Each class answered: results, one-line errors, and clap's refusals.
    assert!(codes.iter().all(|&c| c > 20), "{codes:?}");
}

/// A small seeded generator (xorshift64*): the same mutations on every run.
struct Seeded(u64);

impl Seeded {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let r = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        usize::try_from(r % n.max(1) as u64).unwrap()
    }
}

/// `text` mutated once by `rng`: a number replaced by a hostile one (the largest, the least
/// subnormal, zero, negative, 10¹⁵⁴ whose square overflows, a count of 10⁶), the text cut
/// short, a span of it deleted, or a name duplicated.
fn mutate(text: &str, rng: &mut Seeded) -> String {
    let numbers: Vec<(usize, usize)> = {
        let b = text.as_bytes();
        let mut v = Vec::new();
        let mut k = 0;
        while k < b.len() {
            if b[k].is_ascii_digit() && (k == 0 || !b[k - 1].is_ascii_alphabetic()) {
                let start = if k > 0 && b[k - 1] == b'-' { k - 1 } else { k };
                let mut end = k;
                while end < b.len() && (b[end].is_ascii_digit() || b".eE-+".contains(&b[end])) {
                    end += 1;
                }
                v.push((start, end));
                k = end;
            } else {
                k += 1;
            }
        }
        v
    };
    let at = |n: usize, rng: &mut Seeded| {
        let mut k = rng.below(n);
        while !text.is_char_boundary(k) {
            k -= 1;
        }
        k
    };
    match rng.below(5) {
        0 | 1 if !numbers.is_empty() => {
            let (s, e) = numbers[rng.below(numbers.len())];
            let hostile = [
                "1e308", "-1e308", "5e-324", "0", "-1", "1e154", "1e-154", "1000000", "-0.0",
            ];
            format!(
                "{}{}{}",
                &text[..s],
                hostile[rng.below(hostile.len())],
                &text[e..]
            )
        }
        2 => text[..at(text.len(), rng)].to_owned(),
        3 => {
            let a = at(text.len(), rng);
            let mut b = (a + 1 + rng.below(40)).min(text.len());
            while !text.is_char_boundary(b) {
                b += 1;
            }
            format!("{}{}", &text[..a], &text[b..])
        }
        _ => text.replacen("\"name\": \"A\"", "\"name\": \"B\"", 1),
    }
}

/// Every bundled description mutated (hostile numbers in every field, cut short, bytes
/// deleted, names duplicated): `check`, `analyse`, `draw` and `dynamics` on each end with a
/// one-line error or a finite result. Two mutations per file by default;
/// `TMM_HOSTILE_CASES` / 100 per file when it is set above 200 (the CI's release sweep).
#[test]
fn mutated_descriptions_fail_in_one_line_or_give_finite_results() {
    let per_file = std::env::var("TMM_HOSTILE_CASES")
        .ok()
        .and_then(|s| s.parse::<usize>().ok())
        .map_or(2, |n| (n / 100).max(2));
    let dir = std::env::temp_dir().join(format!("tmm-cli-mutated-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("o.svg");
    let mut rng = Seeded(0x9e37_79b9_7f4a_7c15);
    let mut files: Vec<_> = std::fs::read_dir(common::root().join("linkages"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let (mut runs, mut ok) = (0, 0);
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for k in 0..per_file {
            let path = dir.join(format!(
                "{}-{k}.json",
                file.file_stem().unwrap().to_string_lossy()
            ));
            std::fs::write(&path, mutate(&text, &mut rng)).unwrap();
            let p = path.to_str().unwrap();
            for args in [
                &["check", p][..],
                &["analyse", p],
                &["draw", p, "--animate", "-o", svg.to_str().unwrap()],
                &["dynamics", p],
            ] {
                let code = judge(args, &svg);
                assert_ne!(code, 2, "{args:?}: a file's fault is not a usage error");
                ok += usize::from(code == 0);
                runs += 1;
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    println!("{runs} runs on mutated descriptions, {ok} results");
    assert!(runs >= 4 * 2 * 20 && ok > 0 && ok < runs, "{ok} of {runs}");
}
