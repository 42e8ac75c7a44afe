//! The built `tmm` program run on every bundled description for each subcommand, and on
//! broken files. Outputs are parsed back: CSV cells counted and read as finite numbers, JSON
//! read back, SVG checked for a well-formed tree of tags without `NaN` or `inf` and rendered
//! to pixels by resvg (not blank). `tests/synth.rs` holds `tmm synth`'s round trips.
//!
//! Linkages with two inputs and rocking inputs have their own file, `tests/inputs.rs`; here
//! they run through every subcommand like the others, with these differences (each refusal a
//! clear one-line error with exit code 1, never a panic):
//! - `five-bar-robot.json` has two inputs (mobility 2): its pictures are taken at pairs
//!   φ1 φ2, its plan, animation and diagrams follow a loop about the reference pose, and
//!   its `dynamics` is the mass matrix over a grid of the inputs. A transfer function (a
//!   derivative with respect to one input) and a run-up or flywheel refuse it (asserted).
//! - `peaucellier-lipkin.json` and `chebyshev-straight-line.json` have rocking inputs: their
//!   pictures, tables and reduced quantities are taken inside their lock angles; a run-up or
//!   flywheel refuses them, naming the lock angles.

mod common;

use common::{
    assert_one_line_failure, assert_success, assert_svg, number_after, parse_csv, rocking_four_bar,
    root, tmm, tmm_in, Broken, PISTON_DRIVEN,
};

/// Every bundled description, as a path relative to the root.
fn bundled() -> Vec<String> {
    let mut files: Vec<String> = std::fs::read_dir(root().join("linkages"))
        .expect("linkages/ exists")
        .map(|e| e.expect("a directory entry").file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .map(|n| format!("linkages/{n}"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "the bundled descriptions: {files:?}");
    files
}

/// Files that cannot run a single course (see the module docs).
fn two_inputs(file: &str) -> bool {
    file.ends_with("five-bar-robot.json")
}

/// Files whose input rocks (see the module docs).
fn rocking(file: &str) -> bool {
    file.ends_with("peaucellier-lipkin.json") || file.ends_with("chebyshev-straight-line.json")
}

#[test]
fn check_every_bundled_file() {
    for file in bundled() {
        let r = tmm(&["check", &file]);
        assert_success(&r, &format!("check {file}"));
        assert!(r.stdout.contains("mobility W = "), "{file}: {}", r.stdout);
        assert!(r.stdout.contains("groups in attachment order"), "{file}");
        assert!(r.stdout.contains("range: "), "{file}");
        assert!(!r.stdout.contains("NaN"), "{file}: {}", r.stdout);
    }
    // The double butterfly's general group: all six links and its nine hinges (six inside,
    // three to the crank and the frame), each named once.
    let r = tmm(&["check", "linkages/double-butterfly.json"]);
    let line = r
        .stdout
        .lines()
        .find(|l| l.contains("general"))
        .unwrap_or_else(|| panic!("no general group: {}", r.stdout));
    let words: Vec<&str> = line
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect();
    for name in ["CE", "EFG", "BFJ", "DHI", "GH", "IJ"] {
        assert_eq!(
            words.iter().filter(|w| **w == name).count(),
            1,
            "{name}: {line}"
        );
    }
    for name in ["C", "D", "E", "F", "G", "H", "I", "J", "B"] {
        assert_eq!(
            words.iter().filter(|w| **w == name).count(),
            1,
            "{name}: {line}"
        );
    }
}

#[test]
fn check_and_dynamics_as_json_read_back() {
    for file in bundled() {
        let r = tmm(&["check", &file, "--format", "json"]);
        assert_success(&r, &format!("check --format json {file}"));
        let v: serde_json::Value = serde_json::from_str(&r.stdout)
            .unwrap_or_else(|e| panic!("{file}: JSON reads back: {e}"));
        assert!(v["mobility"].as_i64().is_some_and(|m| m >= 1), "{file}");
        assert!(!v["groups"].as_array().unwrap().is_empty(), "{file}");
    }
    let r = tmm(&["check", "four-bar", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["range"]["kind"], "full turn");
    let mu = v["transmission"][0]["min"].as_f64().unwrap();
    // The cosine law at the crank's two positions in line with the frame, from the file's
    // joints: cos μ = (b² + c² − (d ∓ a)²)/(2bc), the transmission angle taken acute.
    let [o1, a, b, o3] = [
        [0.0, 0.0],
        [0.1, 0.0],
        [0.25612516773077276, 0.3132489936153635],
        [0.4, 0.05],
    ];
    let len = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let (la, lb, lc, ld) = (len(o1, a), len(a, b), len(o3, b), len(o1, o3));
    let acute = |x: f64| x.min(std::f64::consts::PI - x);
    let at = |l: f64| acute(((lb * lb + lc * lc - l * l) / (2.0 * lb * lc)).acos());
    let exact = at(ld - la).min(at(ld + la));
    assert!(
        (mu - exact).abs() < 1e-9,
        "γ_min of the four-bar, {mu} against {exact} rad"
    );
    let r = tmm(&[
        "dynamics",
        "four-bar",
        "--run-up",
        "--flywheel",
        "0.05",
        "--format",
        "json",
    ]);
    assert_success(&r, "dynamics --format json");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["reduced"]["J_red"].as_array().unwrap().len(), 360);
    assert!(v["run_up"]["turns"].as_array().unwrap().len() >= 2);
    assert!(v["flywheels"][0]["moment_of_inertia"].as_f64().unwrap() > 0.0);
}

#[test]
fn check_names_the_range_grashof_and_transmission_angle() {
    let r = tmm(&["check", "linkages/four-bar.json"]);
    assert_success(&r, "check four-bar");
    assert!(r.stdout.contains("the crank turns fully"), "{}", r.stdout);
    assert!(r.stdout.contains("Grashof: crank-rocker"), "{}", r.stdout);
    assert!(r.stdout.contains("γ_min = "), "{}", r.stdout);
    assert!(r.stdout.contains("time ratio"), "{}", r.stdout);
}

#[test]
fn analyse_every_bundled_file_as_csv() {
    for file in bundled() {
        let r = tmm(&["analyse", &file, "--format", "csv"]);
        assert_success(&r, &format!("analyse {file}"));
        let (header, rows) = parse_csv(&r.stdout, &file);
        // A rocking crank's two locks, where the driven group is at its dead point, are left
        // out saying why.
        let locks = if rocking(&file) { 2 } else { 0 };
        assert_eq!(
            r.stderr.matches("at its dead point").count(),
            locks,
            "{file}"
        );
        assert_eq!(rows.len(), 12 - locks, "{file}: the 12 course positions");
        assert!(
            header.iter().all(|h| h.ends_with(']') && h.contains(" [")),
            "{file}: every column has its unit: {header:?}"
        );
        assert!(
            header.iter().any(|h| h.starts_with("Mb ")),
            "{file}: {header:?}"
        );
    }
}

#[test]
fn analyse_every_bundled_file_as_json_and_table() {
    for file in bundled() {
        let r = tmm(&["analyse", &file, "--positions", "8", "--format", "json"]);
        assert_success(&r, &format!("analyse --format json {file}"));
        let v: serde_json::Value = serde_json::from_str(&r.stdout)
            .unwrap_or_else(|e| panic!("{file}: JSON reads back: {e}"));
        // A rocking crank's positions run from lock to lock and back: at its two locks the
        // driven group is at its dead point and the forces are refused, saying so.
        let failed = v["failed"].as_array().expect("failed");
        let locks = if rocking(&file) { 2 } else { 0 };
        assert_eq!(failed.len(), locks, "{file}: {failed:?}");
        assert!(
            failed.iter().all(|f| f["error"]
                .as_str()
                .is_some_and(|e| e.contains("at its dead point"))),
            "{file}: {failed:?}"
        );
        assert_eq!(v["rows"], 8 - locks, "{file}");
        let columns = v["columns"].as_array().expect("columns");
        assert!(columns.len() > 10, "{file}");
        for c in columns {
            assert!(
                !c["unit"].as_str().expect("a unit").is_empty(),
                "{file}: {c}"
            );
            let values = c["values"].as_array().expect("values");
            assert_eq!(values.len(), 8 - locks, "{file}: {}", c["name"]);
            assert!(
                values
                    .iter()
                    .all(|v| v.as_f64().is_some_and(f64::is_finite)),
                "{file}: {c}"
            );
        }
        let at: &[&str] = if two_inputs(&file) {
            &["120", "60", "110", "70", "125", "55"]
        } else if rocking(&file) {
            &["60", "80", "70"]
        } else {
            &["10", "-20", "370"]
        };
        let mut args = vec!["analyse", file.as_str(), "--at"];
        args.extend_from_slice(at);
        let t = tmm(&args);
        assert_success(&t, &format!("analyse --at {file}"));
        // A title line, the positions' line, then one line per column.
        assert_eq!(t.stdout.lines().count(), columns.len() + 2, "{file}");
        assert!(!t.stdout.contains("NaN"), "{file}");
        assert!(
            !t.stdout.lines().skip(2).any(|l| l.contains(" —")),
            "{file}: every value available: {}",
            t.stdout
        );
    }
}

#[test]
fn analyse_writes_the_csv_file_it_prints() {
    let out = std::env::temp_dir().join(format!("tmm-cli-test-{}.csv", std::process::id()));
    let out_s = out.to_string_lossy().into_owned();
    let r = tmm(&[
        "analyse", "shaper", "--speed", "-6", "--format", "csv", "--csv", &out_s,
    ]);
    assert_success(&r, "analyse --csv");
    let written = std::fs::read_to_string(&out).expect("the CSV file is written");
    std::fs::remove_file(&out).ok();
    assert_eq!(written, r.stdout);
    let (header, rows) = parse_csv(&written, "shaper at -6 rad/s");
    let speed = header
        .iter()
        .position(|h| h == "phi_in' [rad/s]")
        .expect("ω column");
    assert!(rows.iter().all(|row| row[speed] == -6.0));
}

#[test]
fn analyse_gives_angles_in_degrees_when_asked() {
    let r = tmm(&[
        "analyse",
        "four-bar",
        "--at",
        "30",
        "-45",
        "--degrees",
        "--format",
        "csv",
    ]);
    assert_success(&r, "analyse --degrees");
    let (header, rows) = parse_csv(&r.stdout, "four-bar in degrees");
    let phi = header
        .iter()
        .position(|h| h == "phi_in [deg]")
        .expect("φ in deg");
    assert!((rows[0][phi] - 30.0).abs() < 1e-12 && (rows[1][phi] + 45.0).abs() < 1e-12);
    assert!(header.iter().all(|h| !h.ends_with("[rad]")), "{header:?}");
    assert!(
        header.iter().any(|h| h.ends_with("[rad/s]")),
        "rates stay in rad/s"
    );
}

#[test]
fn a_linkage_with_two_inputs_is_analysed_at_pairs_of_inputs() {
    let r = tmm(&[
        "analyse",
        "five-bar-robot",
        "--at",
        "120",
        "60",
        "110",
        "70",
        "--format",
        "csv",
    ]);
    assert_success(&r, "analyse five-bar --at pairs");
    let (header, rows) = parse_csv(&r.stdout, "five-bar at pairs");
    assert_eq!(rows.len(), 2);
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let (q1, q2) = (col("phi_in [rad]"), col("phi_in2 [rad]"));
    assert!((rows[1][q1].to_degrees() - 110.0).abs() < 1e-9);
    assert!((rows[1][q2].to_degrees() - 70.0).abs() < 1e-9);
    // Both inputs turn at the file's 10 rad/s: the drives' power is (Mb + Mb2)·ω.
    let (mb, mb2) = (
        col("Mb [N·m, + counter-clockwise]"),
        col("Mb2 [N·m, + counter-clockwise]"),
    );
    let power = col("drive power by virtual power [W]");
    for row in &rows {
        let chain = (row[mb] + row[mb2]) * 10.0;
        assert!(
            (chain - row[power]).abs() < 1e-9 * row[power].abs().max(1.0),
            "{row:?}"
        );
    }
    let odd = tmm(&["analyse", "five-bar-robot", "--at", "120", "60", "110"]);
    assert_one_line_failure(&odd, "five-bar-robot");
}

#[test]
fn analyse_keeps_only_the_columns_asked_for() {
    let r = tmm(&[
        "analyse", "shaper", "--only", "Mb", "R(crank", "--format", "csv",
    ]);
    assert_success(&r, "analyse --only");
    let (header, rows) = parse_csv(&r.stdout, "shaper, some columns");
    assert_eq!(header[0], "phi_in [rad]");
    assert!(header.len() > 3, "{header:?}");
    assert!(
        header[1..]
            .iter()
            .all(|h| h.contains("Mb") || h.contains("R(crank")),
        "{header:?}"
    );
    assert_eq!(rows.len(), 12);
}

#[test]
fn an_unknown_column_is_an_error_naming_it_and_the_columns() {
    let all = tmm(&["analyse", "shaper", "--format", "csv"]);
    assert_success(&all, "analyse shaper");
    let (header, _) = parse_csv(&all.stdout, "shaper, every column");
    // One text that matches and one that matches nothing: the whole request is refused.
    let r = tmm(&["analyse", "shaper", "--only", "Mb", "zzz"]);
    assert_one_line_failure(&r, "shaper");
    assert!(r.stderr.contains("--only \"zzz\""), "{}", r.stderr);
    for h in &header {
        let name = h.split(" [").next().unwrap();
        assert!(r.stderr.contains(name), "lists {name}: {}", r.stderr);
    }
    assert!(r.stdout.is_empty(), "no table: {}", r.stdout);
}

/// The digits of a number echoed in a message, longest run.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn huge_and_tiny_numbers_are_echoed_readably() {
    for (args, file, field, shown) in [
        (
            &["dynamics", "five-bar-robot", "--span", "1e308"][..],
            "five-bar-robot",
            "span",
            "1e308°",
        ),
        (
            &["dynamics", "five-bar-robot", "--run", "1e308"],
            "five-bar-robot",
            "duration",
            "1e308 s",
        ),
        (
            &["dynamics", "five-bar-robot", "--run=-1e-300"],
            "five-bar-robot",
            "duration",
            "-1e-300 s",
        ),
        (
            &["analyse", "four-bar", "--speed", "1e300"],
            "four-bar",
            "speed",
            "1e300",
        ),
        (
            &["analyse", "four-bar", "--at", "1e300"],
            "four-bar",
            "--at",
            "1e300",
        ),
        (
            &["draw", "four-bar", "--scheme", "-1e200"],
            "four-bar",
            "--scheme",
            "-1e200",
        ),
        (
            &["dynamics", "shaper", "--rotor", "-1e300"],
            "shaper",
            "moment of inertia",
            "-1e300",
        ),
    ] {
        let r = tmm(args);
        assert_one_line_failure(&r, file);
        assert!(
            r.stderr.contains(field),
            "{args:?} names {field}: {}",
            r.stderr
        );
        assert!(
            r.stderr.contains(shown),
            "{args:?} shows {shown}: {}",
            r.stderr
        );
        // The longest number a message holds otherwise is a limit such as 10000.
        assert!(longest_digit_run(&r.stderr) < 12, "{args:?}: {}", r.stderr);
    }
}

#[test]
fn options_with_numbers_come_after_the_file() {
    let dir = std::env::temp_dir().join(format!("tmm-cli-test-{}-order", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("forces.svg");
    let out = out.to_str().unwrap();
    // The order of the usage line and the examples works, with an angle and without one.
    for args in [
        &["draw", "four-bar", "--forces", "30", "-o", out][..],
        &["draw", "four-bar", "--forces", "-o", out],
    ] {
        let r = tmm(args);
        assert_success(&r, &args.join(" "));
        assert_svg(&std::fs::read_to_string(out).unwrap(), &args.join(" "));
    }
    let help = tmm(&["draw", "--help"]);
    assert!(
        help.stdout.contains("Usage: tmm draw <FILE> ["),
        "{}",
        help.stdout
    );
    // The file after an option that takes numbers would be read as one of them: a usage error
    // (exit 2) on one line that names the file and says where it goes.
    for args in [
        &["draw", "--forces", "four-bar", "-o", out][..],
        &["draw", "--forces", "30", "four-bar", "-o", out],
        &["analyse", "--at", "30", "four-bar"],
        &["dynamics", "--flywheel", "0.05", "shaper"],
    ] {
        let r = tmm(args);
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {:?}", r.stderr);
        assert!(r.stderr.starts_with("tmm: "), "{}", r.stderr);
        let file = args
            .iter()
            .find(|a| a.ends_with("bar") || **a == "shaper")
            .unwrap();
        assert!(
            r.stderr.contains(&format!("\"{file}\" is not a number")),
            "{}",
            r.stderr
        );
        assert!(
            r.stderr.contains("the description file comes first"),
            "{}",
            r.stderr
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn draw_every_picture_of_every_bundled_file() {
    let pictures: &[&[&str]] = &[
        &[],
        &["--scheme", "30"],
        &["--plan"],
        &["--animate"],
        &["--forces", "45"],
        &["--diagrams"],
        &["--diagram", "kinematics"],
        &["--diagram", "transfer"],
        &["--diagram", "reactions"],
        &["--diagram", "hodograph"],
        &["--workspace", "B"],
        &["--animate", "--along", "120", "60", "100", "80"],
    ];
    for file in bundled() {
        for picture in pictures {
            let mut args = vec!["draw", file.as_str()];
            for &a in *picture {
                match a {
                    "30" | "45" if two_inputs(&file) => args.extend(["110", "70"]),
                    "30" | "45" if rocking(&file) => args.push("60"),
                    a => args.push(a),
                }
            }
            let what = args.join(" ");
            let r = tmm(&args);
            // What a picture cannot show, one sentence says why.
            let refused = if two_inputs(&file) {
                args.contains(&"transfer")
                    .then_some("a derivative with respect to one input")
            } else if args.contains(&"--workspace") {
                Some("as two inputs move independently")
            } else if args.contains(&"--along") {
                Some("this linkage has one")
            } else {
                None
            };
            if let Some(why) = refused {
                assert_one_line_failure(&r, &file);
                assert!(
                    r.stderr.contains(why),
                    "{what}: the sentence says why: {}",
                    r.stderr
                );
                continue;
            }
            assert_success(&r, &what);
            assert_svg(&r.stdout, &what);
        }
    }
}

#[test]
fn draw_writes_the_file_named_by_o() {
    let out = std::env::temp_dir().join(format!("tmm-cli-test-{}.svg", std::process::id()));
    let out_s = out.to_string_lossy().into_owned();
    let r = tmm(&["draw", "linkages/watt-six-bar.json", "--plan", "-o", &out_s]);
    assert_success(&r, "draw -o");
    assert!(r.stdout.is_empty());
    let svg = std::fs::read_to_string(&out).expect("the SVG file is written");
    std::fs::remove_file(&out).ok();
    assert_svg(&svg, "watt plan");
}

#[test]
fn dynamics_of_every_bundled_file() {
    for file in bundled() {
        // A linkage with two inputs has a grid where one with one has positions over a turn.
        let size = if two_inputs(&file) {
            ["--grid", "5"]
        } else {
            ["--positions", "72"]
        };
        let r = tmm(&["dynamics", &file, "--flywheel", "0.05", size[0], size[1]]);
        if two_inputs(&file) || rocking(&file) {
            assert_one_line_failure(&r, &file);
            let why = if two_inputs(&file) {
                "a linkage with two inputs (mobility 2) has no cycle of its own"
            } else {
                "need a crank that turns fully, and this crank rocks between the lock angles"
            };
            assert!(
                r.stderr.contains(why),
                "{file}: the sentence says why: {}",
                r.stderr
            );
            // Without a flywheel: what is meaningful for them.
            let r = tmm(&["dynamics", &file, size[0], size[1]]);
            assert_success(&r, &format!("dynamics {file}"));
            let what = if two_inputs(&file) { "A11" } else { "J_red" };
            assert!(r.stdout.contains(what), "{file}: {}", r.stdout);
            assert!(
                !r.stdout.contains("NaN") && !r.stdout.contains("inf"),
                "{file}"
            );
            continue;
        }
        assert_success(&r, &format!("dynamics {file}"));
        assert!(r.stdout.contains("J_red"), "{file}");
        assert!(r.stdout.contains("J_F, kg·m²"), "{file}");
        for bad in ["NaN", "inf", " — \n", "  —"] {
            assert!(!r.stdout.contains(bad), "{file}: {bad} in {}", r.stdout);
        }
    }
}

#[test]
fn dynamics_of_every_bundled_file_as_csv_with_units() {
    let out = std::env::temp_dir().join(format!("tmm-cli-test-{}-dyn.csv", std::process::id()));
    let out_s = out.to_string_lossy().into_owned();
    for file in bundled() {
        let size = if two_inputs(&file) {
            ["--grid", "4"]
        } else {
            ["--positions", "24"]
        };
        let r = tmm(&["dynamics", &file, size[0], size[1], "--csv", &out_s]);
        assert_success(&r, &format!("dynamics --csv {file}"));
        let text = std::fs::read_to_string(&out).expect("the CSV file is written");
        let (header, rows) = parse_csv(&text, &file);
        assert!(
            header.iter().all(|h| h.ends_with(']') && h.contains(" [")),
            "{file}: every column has its unit: {header:?}"
        );
        let (n, first) = if two_inputs(&file) {
            (16, "q1 [rad]")
        } else {
            (24, "phi [rad]")
        };
        assert_eq!((rows.len(), header[0].as_str()), (n, first), "{file}");
    }
    std::fs::remove_file(&out).ok();
}

#[test]
fn dynamics_runs_a_machine_up_to_its_steady_state() {
    for file in ["linkages/four-bar.json", "linkages/watt-six-bar.json"] {
        let r = tmm(&["dynamics", file, "--run-up", "--positions", "72"]);
        assert_success(&r, &format!("dynamics --run-up {file}"));
        assert!(r.stdout.contains("steady after"), "{file}: {}", r.stdout);
        assert!(!r.stdout.contains("NaN"), "{file}");
    }
    let r = tmm(&[
        "dynamics", "four-bar", "--run-up", "--motor", "300,25", "--rotor", "0.05",
    ]);
    assert_success(&r, "dynamics --motor");
    assert!(
        r.stdout.contains("M = 300.0000 − 25.0000·|ω|"),
        "{}",
        r.stdout
    );
}

/// A motor of 10⁴ N·m against loads of tens of N·m runs the four-bar away from the 10 rad/s its
/// step was sized for: the run-up is refused naming the step, with what to change, never
/// judged from turns the step cannot resolve ("turns back", "a regime that repeats").
/// A damped motor's idle speed a/b sizes the step: 300 − 0.3·|ω| (idle 1000 rad/s) runs up.
#[test]
fn a_run_up_far_faster_than_its_step_says_what_to_change() {
    let r = tmm(&["dynamics", "four-bar", "--run-up", "--motor", "1e4,0"]);
    assert_one_line_failure(&r, "four-bar");
    assert!(
        r.stderr.contains("step h") && r.stderr.contains("--speed"),
        "{}",
        r.stderr
    );
    assert!(!r.stderr.contains("turns back") && !r.stderr.contains("repeats"));
    let r = tmm(&["dynamics", "four-bar", "--run-up", "--motor", "300,0.3"]);
    assert_success(&r, "dynamics --motor 300,0.3");
    assert!(r.stdout.contains("steady after"), "{}", r.stdout);
}

#[test]
fn dynamics_writes_the_reduced_quantities_as_csv() {
    let out = std::env::temp_dir().join(format!("tmm-cli-test-{}-reduced.csv", std::process::id()));
    let out_s = out.to_string_lossy().into_owned();
    let r = tmm(&[
        "dynamics",
        "watt-six-bar",
        "--positions",
        "36",
        "--csv",
        &out_s,
    ]);
    assert_success(&r, "dynamics --csv");
    let text = std::fs::read_to_string(&out).expect("the CSV file is written");
    std::fs::remove_file(&out).ok();
    let (header, rows) = parse_csv(&text, "reduced");
    assert_eq!(header.len(), 5);
    assert_eq!(rows.len(), 36);
    assert!(rows.iter().all(|r| r[2] > 0.0), "J_red > 0");
}

#[test]
fn bundled_lists_every_file_in_linkages() {
    let r = tmm(&["bundled"]);
    assert_success(&r, "bundled");
    for file in bundled() {
        let stem = file
            .trim_start_matches("linkages/")
            .trim_end_matches(".json");
        assert!(
            r.stdout.lines().any(|l| l.starts_with(&format!("{stem} "))),
            "{stem} is built into the program (cli/src/bundled.rs): {}",
            r.stdout
        );
        let text = tmm(&["bundled", stem]);
        assert_success(&text, stem);
        let on_disk = std::fs::read_to_string(root().join(&file)).expect("readable");
        assert_eq!(text.stdout, on_disk, "{stem} is the file in linkages/");
    }
    assert!(!r.stdout.contains("does not load"), "{}", r.stdout);
}

const SUBCOMMANDS: [&str; 4] = ["check", "analyse", "draw", "dynamics"];

#[test]
fn a_rocking_crank_is_tabulated_and_drawn_inside_its_lock_angles() {
    let file = rocking_four_bar();
    let r = tmm(&["check", &file.path()]);
    assert_success(&r, "check rocking");
    assert!(
        r.stdout.contains("the crank rocks between the lock angles"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("Grashof: triple rocker"), "{}", r.stdout);
    let r = tmm(&["analyse", &file.path(), "--format", "csv"]);
    assert_success(&r, "analyse rocking");
    let (_, rows) = parse_csv(&r.stdout, "rocking four-bar");
    // Its two locks, where the driven group is at its dead point, are left out saying why.
    assert_eq!(rows.len(), 10);
    assert_eq!(
        r.stderr.matches("at its dead point").count(),
        2,
        "{}",
        r.stderr
    );
    for picture in [
        &[][..],
        &["--plan"],
        &["--animate"],
        &["--diagram", "kinematics"],
    ] {
        let mut args = vec!["draw", file.0.to_str().unwrap()];
        args.extend_from_slice(picture);
        let r = tmm(&args);
        assert_success(&r, &args.join(" "));
        assert_svg(&r.stdout, &args.join(" "));
    }
    // A run-up needs a turn: one sentence says so, naming the lock angles.
    let r = tmm(&["dynamics", &file.path(), "--run-up"]);
    assert_one_line_failure(&r, &file.path());
    assert!(r.stderr.contains("turns fully"), "{}", r.stderr);
    assert!(r.stderr.contains("lock angles"), "{}", r.stderr);
}

#[test]
fn a_slider_input_travels_between_its_dead_points() {
    let file = Broken::new("slider", PISTON_DRIVEN);
    let r = tmm(&["check", &file.path()]);
    assert_success(&r, "check slider");
    // The crank's radius is 0.05 m: the piston's stroke is 0.1 m.
    assert!(r.stdout.contains("(a stroke of 0.1000 m)"), "{}", r.stdout);
    let r = tmm(&[
        "analyse",
        &file.path(),
        "--speed",
        "-0.5",
        "--format",
        "csv",
    ]);
    assert_success(&r, "analyse slider");
    assert!(r.stderr.is_empty(), "no position left out: {}", r.stderr);
    let (header, rows) = parse_csv(&r.stdout, "piston-driven");
    assert_eq!(rows.len(), 12);
    assert_eq!(header[0], "s_in [m]");
    assert!(
        rows.windows(2).all(|w| w[1][0] < w[0][0]),
        "a negative speed slides back"
    );
    assert!(header.iter().any(|h| h.starts_with("Fb ")), "{header:?}");
    for picture in [
        &[][..],
        &["--plan"],
        &["--animate"],
        &["--forces"],
        &["--diagram", "transfer"],
    ] {
        let mut args = vec!["draw", file.0.to_str().unwrap()];
        args.extend_from_slice(picture);
        let r = tmm(&args);
        assert_success(&r, &args.join(" "));
        assert_svg(&r.stdout, &args.join(" "));
    }
    let r = tmm(&["dynamics", &file.path()]);
    assert_one_line_failure(&r, &file.path());
    assert!(r.stderr.contains("slider"), "{}", r.stderr);
}

#[test]
fn a_missing_file_is_one_line_and_exit_1() {
    for sub in SUBCOMMANDS {
        let r = tmm(&[sub, "no/such/linkage.json"]);
        assert_one_line_failure(&r, "no/such/linkage.json");
        assert!(r.stderr.contains("cannot read"), "{}", r.stderr);
        assert!(r.stderr.contains("tmm bundled"), "the fix: {}", r.stderr);
    }
}

#[test]
fn malformed_json_is_one_line_naming_line_and_column() {
    let four_bar = std::fs::read_to_string(root().join("linkages/four-bar.json")).unwrap();
    let cut = Broken::new("cut", &four_bar[..four_bar.len() / 2]);
    for sub in SUBCOMMANDS {
        let r = tmm(&[sub, &cut.path()]);
        assert_one_line_failure(&r, &cut.path());
        assert!(r.stderr.contains("line"), "{}", r.stderr);
        assert!(r.stderr.contains("column"), "{}", r.stderr);
        assert!(
            r.stderr.contains("docs/linkage-format.md"),
            "the fix: {}",
            r.stderr
        );
    }
}

#[test]
fn a_misspelt_field_is_named() {
    let four_bar = std::fs::read_to_string(root().join("linkages/four-bar.json")).unwrap();
    let file = Broken::new(
        "field",
        &four_bar.replace("\"input\": {\"link\"", "\"input\": {\"lnk\""),
    );
    for sub in SUBCOMMANDS {
        let r = tmm(&[sub, &file.path()]);
        assert_one_line_failure(&r, &file.path());
        assert!(
            r.stderr.contains("lnk"),
            "{sub} names the field: {}",
            r.stderr
        );
    }
}

#[test]
fn a_joint_that_does_not_exist_is_named() {
    let four_bar = std::fs::read_to_string(root().join("linkages/four-bar.json")).unwrap();
    let text = four_bar.replace(
        "{\"name\": \"coupler\", \"joints\": [\"A\", \"B\"]",
        "{\"name\": \"coupler\", \"joints\": [\"A\", \"Bx\"]",
    );
    assert_ne!(text, four_bar, "the test's edit applies");
    let file = Broken::new("joint", &text);
    for sub in SUBCOMMANDS {
        let r = tmm(&[sub, &file.path()]);
        assert_one_line_failure(&r, &file.path());
        assert!(r.stderr.contains("Bx"), "names the joint: {}", r.stderr);
    }
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["analyse"][..],
        &["analyse", "shaper", "--format", "xml"],
        &["analyse", "shaper", "--positions", "3", "--at", "10"],
        &["analyse", "shaper", "--positions", "0"],
        &["dynamics", "shaper", "--motor", "60"],
        &["draw", "shaper", "--plan", "--animate"],
        &["frobnicate"],
    ] {
        let r = tmm(args);
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert!(!r.stderr.is_empty());
    }
}

#[test]
fn help_has_examples() {
    let r = tmm(&["--help"]);
    assert_success(&r, "--help");
    assert!(r.stdout.contains("Examples:"), "{}", r.stdout);
    for sub in SUBCOMMANDS.iter().chain(&["bundled", "synth"]) {
        let r = tmm(&[sub, "--help"]);
        assert_success(&r, sub);
        assert!(r.stdout.contains("Examples:"), "{sub}: {}", r.stdout);
        assert!(
            r.stdout.contains(&format!("tmm {sub}")),
            "{sub}: {}",
            r.stdout
        );
    }
    for kind in SYNTH_KINDS {
        let r = tmm(&["synth", kind, "--help"]);
        assert_success(&r, kind);
        assert!(r.stdout.contains("Examples:"), "{kind}: {}", r.stdout);
        assert!(
            r.stdout.contains(&format!("tmm synth {kind} ")),
            "{kind}: {}",
            r.stdout
        );
    }
}

const SYNTH_KINDS: [&str; 7] = [
    "crank-rocker",
    "slider-crank",
    "shaper",
    "through",
    "function",
    "path",
    "six-bar",
];

#[test]
fn every_example_in_the_help_runs() {
    // In a directory of its own, where `linkages/…` does not exist: the bundled descriptions
    // stand in, and the pictures and tables written land there.
    let dir = std::env::temp_dir().join(format!("tmm-cli-test-{}-examples", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The points file of the path-generation examples.
    std::fs::write(dir.join("points.csv"), common::coupler_curve_csv(12)).unwrap();
    // The timed points of the six-bar's examples.
    std::fs::write(dir.join("timed.csv"), common::six_bar_example_csv()).unwrap();
    let mut examples = Vec::new();
    let synth: Vec<String> = SYNTH_KINDS.iter().map(|k| format!("synth {k}")).collect();
    let helps = [
        "", "check", "analyse", "draw", "dynamics", "bundled", "synth",
    ]
    .into_iter()
    .chain(synth.iter().map(String::as_str));
    for sub in helps {
        let args: Vec<&str> = sub.split_whitespace().chain(["--help"]).collect();
        let help = tmm(&args).stdout;
        for line in help.lines().filter_map(|l| l.strip_prefix("  tmm ")) {
            // The command ends at a run of spaces (its comment) or a redirection.
            let command = line.split("  ").next().unwrap();
            let command = command.split(" > ").next().unwrap();
            examples.push(command.to_owned());
        }
    }
    assert!(examples.len() >= 35, "{examples:?}");
    for example in &examples {
        let args: Vec<&str> = example.split_whitespace().collect();
        let r = tmm_in(&dir, &args);
        assert_eq!(r.code, 0, "tmm {example}: {}", r.stderr);
    }
    assert!(dir.join("watt.svg").exists() && dir.join("shaper.csv").exists());
    for written in [
        "crank-rocker.json",
        "through.json",
        "square.json",
        "path.json",
    ] {
        let text = std::fs::read_to_string(dir.join(written)).expect(written);
        assert!(text.contains("\"joints\""), "{written} is a description");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Mutations of a description that a person could make by mistake: a joint moved onto
/// another (a zero length), a negative mass, a link or a joint removed, the input renamed,
/// a coordinate far away, the frame's name changed.
fn mutations(text: &str) -> Vec<(String, String)> {
    let base: serde_json::Value = serde_json::from_str(text).unwrap();
    let mut out = Vec::new();
    let mut push = |what: String, v: serde_json::Value| out.push((what, v.to_string()));
    let joints = base["joints"].as_array().unwrap().len();
    let links = base["links"].as_array().unwrap().len();
    for j in 1..joints {
        let mut v = base.clone();
        v["joints"][j]["at"] = v["joints"][j - 1]["at"].clone();
        push(format!("joint {j} onto joint {}", j - 1), v);
        let mut v = base.clone();
        v["joints"][j]["at"][0] = serde_json::json!(1e9);
        push(format!("joint {j} far away"), v);
    }
    for k in 0..links {
        let mut v = base.clone();
        v["links"].as_array_mut().unwrap().remove(k);
        push(format!("link {k} removed"), v);
        if base["links"][k].get("mass").is_some() {
            let mut v = base.clone();
            v["links"][k]["mass"]["m"] = serde_json::json!(-1.0);
            push(format!("link {k} of negative mass"), v);
        }
    }
    let mut v = base.clone();
    v["joints"].as_array_mut().unwrap().remove(joints - 1);
    push("last joint removed".to_owned(), v);
    let mut v = base.clone();
    v["input"]["link"] = serde_json::json!("nothing");
    push("input renamed".to_owned(), v);
    let mut v = base.clone();
    v["frame"] = serde_json::json!("ground");
    push("frame renamed".to_owned(), v);
    let mut v = base;
    v["speed"] = serde_json::json!(0.0);
    push("speed zero".to_owned(), v);
    out
}

#[test]
fn mistakes_in_a_description_never_panic() {
    let mut runs = 0;
    for file in [
        "four-bar",
        "shaper",
        "scotch-yoke",
        "slotted-rocker",
        "watt-six-bar",
        "five-bar-robot",
        "peaucellier-lipkin",
    ] {
        let text = std::fs::read_to_string(root().join(format!("linkages/{file}.json"))).unwrap();
        for (k, (what, mutated)) in mutations(&text).into_iter().enumerate() {
            let broken = Broken::new(&format!("{file}-{k}"), &mutated);
            for args in [
                &["check"][..],
                &["analyse", "--format", "csv"],
                &["draw", "--plan"],
                &["draw", "--animate"],
                &["draw", "--workspace", "B"],
                &["dynamics", "--positions", "36"],
            ] {
                let mut all = vec![args[0], broken.0.to_str().unwrap()];
                // A linkage with two inputs has a grid where one with one has positions.
                if args[0] == "dynamics" && file == "five-bar-robot" {
                    all.extend_from_slice(&["--grid", "5"]);
                } else {
                    all.extend_from_slice(&args[1..]);
                }
                let r = tmm(&all);
                let context = format!("{file} with {what}: tmm {}", all.join(" "));
                runs += 1;
                match r.code {
                    0 => {
                        for bad in ["NaN", "inf"] {
                            assert!(!r.stdout.contains(bad), "{context}: {bad} in the output");
                        }
                    }
                    1 => assert_one_line_failure(&r, &broken.path()),
                    code => panic!("{context}: exit code {code}: {}", r.stderr),
                }
            }
        }
    }
    assert!(runs > 200, "{runs} runs");
}

#[test]
fn long_runs_are_quiet_when_piped() {
    // Progress goes to a terminal only (stderr here is a pipe): nothing on stderr.
    for args in [
        &[
            "analyse",
            "four-bar",
            "--positions",
            "12000",
            "--format",
            "csv",
        ][..],
        &["dynamics", "four-bar", "--run-up", "--flywheel", "0.05"],
        &["draw", "five-bar-robot", "--workspace", "B"],
    ] {
        let r = tmm(args);
        assert_success(&r, &args.join(" "));
        assert!(r.stderr.is_empty(), "{args:?}: {:?}", r.stderr);
        assert!(
            !r.stdout.contains('\r') && !r.stdout.contains('\x1b'),
            "{args:?}"
        );
    }
}

/// The five-bar robot (`linkages/five-bar-robot.json`) started from rest in its reference
/// pose with friction circles of ρ in every hinge, crank 4 held and crank 1 moving the way
/// `dir` says (±1): the Newton–Euler equations of crank 1 (pivot O, I = 0.02 kg·m²) and the
/// couplers 2 (A–B) and 3 (C–B, the tool's −0.3 N·m on it), 0.6 kg and 0.009375 kg·m² each,
/// with C fixed, written out here. Unknowns: the hinge forces R_O (frame on 1), R_A (1 on 2),
/// R_B (2 on 3), R_C (4 on 3) and q̈₁; at rest every rate is q̇₁ times its ratio to it
/// (ω₂/ω₁, ω₃/ω₁ of the four-bar O–A–B–C) and every acceleration q̈₁ times the same ratios
/// (no velocity terms), so the nine equations are linear once each hinge's friction couple
/// −ρ·|R|·sgn(ω_on − ω_by) is data: iterated from no friction to its fixed point. Crank 4
/// (massless, I·0) is held: the couple on it of R_C's reaction at C and of C's friction,
/// plus the motor `tau2`, must be carried by D's static friction, at most ρ·|R_D| = ρ·|R_C|.
/// Returns (q̈₁, the couple that would turn crank 4 (along q̇₂), |R_D|).
fn five_bar_crank_4_held(rho: f64, tau1: f64, tau2: f64, dir: f64) -> (f64, f64, f64) {
    use tmm::nalgebra::{SMatrix, SVector, Vector2};
    type V = Vector2<f64>;
    let cross = |a: V, b: V| a.x * b.y - a.y * b.x;
    let wx = |w: f64, r: V| V::new(-w * r.y, w * r.x);
    let (o, a, b) = (
        V::new(0.0, 0.0),
        V::new(-0.075, 0.129_903_810_567_665_8),
        V::new(0.1, 0.308_439_521_281_237_1),
    );
    let (c, d) = (V::new(0.275, 0.129_903_810_567_665_8), V::new(0.2, 0.0));
    let (g2, g3) = (
        V::new(0.0125, 0.219_171_665_924_451_45),
        V::new(0.1875, 0.219_171_665_924_451_4),
    );
    let (m, j, j1, tool) = (0.6, 0.009_375, 0.02, -0.3);
    // ω₂, ω₃ per unit ω₁: v_A + ω₂ × (B − A) = ω₃ × (B − C).
    let (ba, bc, va) = (b - a, b - c, wx(1.0, a - o));
    let k = SMatrix::<f64, 2, 2>::new(-ba.y, bc.y, ba.x, -bc.x)
        .lu()
        .solve(&(-va))
        .expect("the four-bar O-A-B-C moves");
    let (k2, k3) = (k.x, k.y);
    let a2 = wx(1.0, a - o) + wx(k2, g2 - a);
    let a3 = wx(k3, g3 - c);
    let mut mat = SMatrix::<f64, 9, 9>::zeros();
    let rows: [[f64; 9]; 9] = [
        [1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, a.y, -a.x, 0.0, 0.0, 0.0, 0.0, -j1],
        [0.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, -m * a2.x],
        [0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, -m * a2.y],
        [
            0.0,
            0.0,
            -(a - g2).y,
            (a - g2).x,
            (b - g2).y,
            -(b - g2).x,
            0.0,
            0.0,
            -j * k2,
        ],
        [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -m * a3.x],
        [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, -m * a3.y],
        [
            0.0,
            0.0,
            0.0,
            0.0,
            -(b - g3).y,
            (b - g3).x,
            -(c - g3).y,
            (c - g3).x,
            -j * k3,
        ],
    ];
    for (i, r) in rows.iter().enumerate() {
        for (l, &v) in r.iter().enumerate() {
            mat[(i, l)] = v;
        }
    }
    let lu = mat.lu();
    let sgn = |x: f64| {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    let mut x = SVector::<f64, 9>::zeros();
    for _ in 0..200 {
        let norm = |i: usize| V::new(x[2 * i], x[2 * i + 1]).norm();
        // Each hinge's friction couple on its `on` link (O: 1 on the frame's; A: 2 on 1's;
        // B: 3 on 2's; C: 3 on 4's, ω₄ = 0).
        let (fo, fa) = (
            -rho * norm(0) * sgn(dir),
            -rho * norm(1) * sgn(dir * (k2 - 1.0)),
        );
        let (fb, fc) = (
            -rho * norm(2) * sgn(dir * (k3 - k2)),
            -rho * norm(3) * sgn(dir * k3),
        );
        let rhs = SVector::<f64, 9>::from_column_slice(&[
            0.0,
            0.0,
            -(tau1 + fo - fa),
            0.0,
            0.0,
            -(fa - fb),
            0.0,
            0.0,
            -(tool + fb + fc),
        ]);
        let next = lu.solve(&rhs).expect("the equations of motion solve");
        let done = (next - x).amax() <= 1e-15;
        x = next;
        if done {
            break;
        }
    }
    let r_c = V::new(x[6], x[7]);
    let fc = -rho * r_c.norm() * sgn(dir * k3);
    // On crank 4: −R_C at C, C's couple reversed, the motor.
    let couple = cross(c - d, -r_c) - fc + tau2;
    (x[8], couple, r_c.norm())
}

/// The five-bar robot with friction in every joint (f = 0.3 on pins of 5 cm, ρ = 15 mm),
/// from rest in its reference pose. Crank 1 driven by 1 mN·m (the tool's −0.3 N·m on coupler
/// 3 drives it the other way with 0.17 N·m): crank 1 turns back, and the friction in crank
/// 4's pivot holds crank 4 for the whole run. By hand ([`five_bar_crank_4_held`]): with crank
/// 4 held and crank 1 starting backwards, q̈₁ = −3.35 rad/s² (its sign the one assumed; the
/// other assumption is inconsistent), and the couple that would turn crank 4 is 0.0110 N·m,
/// within its pivot's 0.0163 N·m (without the joints' friction it would be 0.046 N·m against
/// 0.018: the friction of the moving joints is what lets the pivot hold). The program must say
/// which input is held, from when, to the end, with those two loads where the hold begins,
/// and run to the end. A drive the friction holds at rest for good (motors 0.17 and −0.045
/// N·m against the loads' 0.1734 and −0.0449 at rest) stops the run at t = 0, and says so.
/// Without friction the first run goes to the end with nothing held. With pins of 2 cm and
/// motors on both cranks, crank 1 stops while crank 2 still turns and is held from there on,
/// its load within its pivot's friction at both ends of the hold.
#[test]
fn a_two_input_run_that_friction_stops_says_so() {
    let text = std::fs::read_to_string("../linkages/five-bar-robot.json")
        .or_else(|_| std::fs::read_to_string("linkages/five-bar-robot.json"))
        .expect("the bundled five-bar");
    let text = text.replacen('{', "{\"friction\": {\"f\": 0.3, \"pin_radius\": 0.05},", 1);
    let path =
        std::env::temp_dir().join(format!("tmm-cli-test-{}-fb-fric.json", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let p = path.to_string_lossy().into_owned();
    let rho = 0.3 * 0.05;
    let (qdd1, couple, pressure) = five_bar_crank_4_held(rho, 0.001, 0.0, -1.0);
    let limit = rho * pressure;
    let (qdd1_up, _, _) = five_bar_crank_4_held(rho, 0.001, 0.0, 1.0);
    println!(
        "by hand: q̈₁ = {qdd1:.6} rad/s², crank 4's couple {couple:.6} N·m, limit {limit:.6} N·m"
    );
    assert!(
        qdd1 < 0.0 && qdd1_up < 0.0,
        "crank 1 goes backwards: {qdd1} {qdd1_up}"
    );
    assert!(couple.abs() < limit, "held by hand: {couple} vs {limit}");
    let (_, free_couple, free_pressure) = five_bar_crank_4_held(0.0, 0.001, 0.0, -1.0);
    assert!(
        free_couple.abs() > rho * free_pressure,
        "{free_couple} {free_pressure}"
    );
    let r = tmm(&[
        "dynamics", &p, "--run", "0.5", "--motor", "0.001,0", "--motor2", "0,0",
    ]);
    assert_success(&r, "a run with crank 4 held");
    let line = r
        .stdout
        .lines()
        .find(|l| l.starts_with("input 2 held at 60.000° by the friction in its own joint"))
        .unwrap_or_else(|| panic!("{}", r.stdout));
    assert!(
        line.contains("from t = 0.0000 s to the end of the run"),
        "{line}"
    );
    // Printed to 3 significant digits, at the first step (q̇₁ = 4·10⁻⁴ rad/s: its squares
    // move the loads by far less).
    let (drive, held) = (
        number_after(line, "would move it, "),
        number_after(line, "joint can hold, "),
    );
    assert!(
        (drive - couple).abs() <= 6e-5,
        "{drive} vs {couple}: {line}"
    );
    assert!((held - limit).abs() <= 6e-5, "{held} vs {limit}: {line}");
    assert!(!r.stdout.contains("the run stopped"), "{}", r.stdout);
    assert!(r.stdout.contains("for 0.5000 s"), "{}", r.stdout);
    let rows = run_rows(&r.stdout);
    assert!(rows.len() >= 10, "{}", r.stdout);
    for row in &rows[1..] {
        assert!(row[2] == 60.0 && row[4] == 0.0 && row[3] < 0.0, "{row:?}");
    }
    // The same in JSON: one hold, of input 2, from 0 to the end, with the loads by hand.
    let r = tmm(&[
        "dynamics", &p, "--run", "0.5", "--motor", "0.001,0", "--motor2", "0,0", "--format", "json",
    ]);
    assert_success(&r, "a run with crank 4 held, in JSON");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let held = v["run"]["held"].as_array().expect("run.held");
    assert_eq!(held.len(), 1, "{held:?}");
    let h = &held[0];
    assert_eq!(
        (
            h["input"].as_u64(),
            h["released"].as_bool(),
            h["from"].as_f64()
        ),
        (Some(2), Some(false), Some(0.0)),
        "{h}"
    );
    assert!((h["until"].as_f64().unwrap() - 0.5).abs() <= 1e-12, "{h}");
    let (d0, b0) = (
        h["loads"]["drive"][0].as_f64().unwrap(),
        h["loads"]["breakaway"][0].as_f64().unwrap(),
    );
    assert!(
        (d0 - couple).abs() <= 1e-5 * limit && (b0 - limit).abs() <= 1e-5 * limit,
        "{h}"
    );
    // The first printed row after the start (0.05 s): q̇₁/t is q̈₁ within 10⁻³ (the rates'
    // squares, the change of the pose and the printed digits).
    let (t1, w1) = (rows[1][0], rows[1][3]);
    assert!(
        (w1 / t1 - qdd1).abs() <= 1e-3 * qdd1.abs(),
        "{w1} at {t1}: {qdd1}"
    );
    // Held for good: both inputs' drives within their friction at rest.
    let r = tmm(&[
        "dynamics", &p, "--run", "0.5", "--motor", "0.17,0", "--motor2", "-0.045,0",
    ]);
    assert_success(&r, "a run stopped by friction");
    assert!(
        r.stdout.contains("the run stopped: stopped at t = 0 s")
            && r.stdout.contains("is below the resistance")
            && r.stdout.contains("(0 steps"),
        "{}",
        r.stdout
    );
    let drive = number_after(&r.stdout, "the driving load ");
    let resistance = number_after(&r.stdout, "is below the resistance ");
    assert!(drive < resistance, "{drive} vs {resistance}");
    let r = tmm(&[
        "dynamics",
        "five-bar-robot",
        "--run",
        "0.5",
        "--motor",
        "0.001,0",
        "--motor2",
        "0,0",
    ]);
    assert_success(&r, "a run without friction");
    assert!(!r.stdout.contains("the run stopped"), "{}", r.stdout);
    assert!(!r.stdout.contains(" held at "), "{}", r.stdout);
    assert!(r.stdout.contains("for 0.5000 s"), "{}", r.stdout);
    // One input held by its friction while the other still turns: the run goes on with it
    // held, and says from when and with which loads.
    let small =
        std::env::temp_dir().join(format!("tmm-cli-test-{}-fb-fric2.json", std::process::id()));
    let text = std::fs::read_to_string(&path).unwrap().replacen(
        "\"pin_radius\": 0.05",
        "\"pin_radius\": 0.02",
        1,
    );
    std::fs::write(&small, text).unwrap();
    let s = small.to_string_lossy().into_owned();
    let r = tmm(&[
        "dynamics",
        &s,
        "--run",
        "0.5",
        "--motor",
        "0.2,0.05",
        "--motor2",
        "-0.1,0.05",
    ]);
    assert_success(&r, "a run with one input held");
    let rows = run_rows(&r.stdout);
    let last = rows.last().expect("rows");
    assert!(
        last[4].abs() > 1e-3 && last[3] == 0.0,
        "{last:?}: {}",
        r.stdout
    );
    let line = r
        .stdout
        .lines()
        .find(|l| l.starts_with("input 1 held at "))
        .unwrap_or_else(|| panic!("{}", r.stdout));
    assert!(line.contains("to the end of the run"), "{line}");
    let from = number_after(line, "from t = ");
    assert!(from > 0.1 && from < 0.45, "{line}");
    let drive = number_after(line, "would move it, ");
    let held = number_after(line, "joint can hold, ");
    assert!(drive.abs() < held, "{line}");
    // Rows from the hold on: crank 1 where it stopped.
    let q1 = rows
        .iter()
        .filter(|r| r[0] >= from)
        .map(|r| r[1])
        .collect::<Vec<_>>();
    assert!(q1.len() >= 2 && q1.iter().all(|&v| v == q1[0]), "{q1:?}");
    assert!(!r.stdout.contains("the run stopped"), "{}", r.stdout);
    std::fs::remove_file(&small).ok();
    std::fs::remove_file(&path).ok();
}

/// The rows of a two-input run's text: t, q₁, q₂, q̇₁, q̇₂, T.
fn run_rows(out: &str) -> Vec<Vec<f64>> {
    let run = &out[out.find("run from rest").expect("a run")..];
    run.lines()
        .filter_map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .ok()?;
            (v.len() == 6).then_some(v)
        })
        .collect()
}

/// `tmm analyse` of a machine with friction and no external loads at 30 rad/s, whose inertia
/// drives it back over part of its turn: the table has the drive's power beside the power
/// lost and the efficiency η = (P_drive − P_lost)/P_drive where the drive gives power, an
/// empty cell (and only there) where it does not; every other cell is a number.
#[test]
fn analyse_prints_the_efficiency_where_it_has_a_value_and_a_blank_where_not() {
    let mut l = tmm::linkage::bundled::four_bar();
    l.loads.clear();
    l.friction = Some(tmm::linkage::Friction::pin(0.15, 0.01));
    l.speed = Some(30.0);
    let path = std::env::temp_dir().join(format!("tmm-cli-test-{}-eta.json", std::process::id()));
    std::fs::write(&path, l.to_json().unwrap()).unwrap();
    let p = path.to_string_lossy().into_owned();
    let r = tmm(&["analyse", &p, "--positions", "72", "--format", "csv"]);
    let text = tmm(&["analyse", &p, "--positions", "72"]);
    let _ = std::fs::remove_file(&path);
    assert_success(&r, "analyse with friction");
    assert_success(&text, "analyse with friction, as text");
    // The text table's eta line shows a dash where η has no value.
    let line = text
        .stdout
        .lines()
        .find(|l| l.starts_with("eta "))
        .expect("an eta line");
    assert!(line.contains('—'), "{line}");
    // `parse_csv` admits an empty cell only in eta and only where P_drive ≤ 0.
    let (header, rows) = parse_csv(&r.stdout, "four-bar with friction, no loads");
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let (drive, lost, eta) = (col("P_drive [W]"), col("P_lost [W]"), col("eta [-]"));
    assert_eq!(eta, drive + 1);
    let mut blanks = 0;
    for row in &rows {
        if row[drive] > 0.0 {
            let expected = (row[drive] - row[lost]) / row[drive];
            assert!(
                (row[eta] - expected).abs() <= 1e-12 * expected.abs().max(1.0),
                "{row:?}"
            );
        } else {
            assert!(row[eta].is_nan(), "{row:?}");
            blanks += 1;
        }
    }
    assert!(
        blanks > 0 && blanks < rows.len(),
        "{blanks} of {} rows idle",
        rows.len()
    );
}

/// A load so large that every reaction overflows leaves no row of the table finite: the
/// program fails naming the overflow (it printed an empty table and exited 0), while a load
/// 10¹⁰ times smaller still gives every row, every cell finite.
#[test]
fn a_load_whose_reactions_overflow_is_a_named_failure_not_an_empty_table() {
    let text = std::fs::read_to_string(root().join("linkages/four-bar.json")).unwrap();
    assert!(text.contains("[0.0, -50.0]"));
    let huge = Broken::new("huge-load", &text.replace("[0.0, -50.0]", "[1e160, 1e160]"));
    let r = tmm(&[
        "analyse",
        &huge.path(),
        "--positions",
        "12",
        "--format",
        "csv",
    ]);
    assert_one_line_failure(&r, &huge.path());
    assert!(
        r.stderr.contains("not finite (it overflows)"),
        "{}",
        r.stderr
    );
    let large = Broken::new(
        "large-load",
        &text.replace("[0.0, -50.0]", "[1e150, 1e150]"),
    );
    let r = tmm(&[
        "analyse",
        &large.path(),
        "--positions",
        "12",
        "--format",
        "csv",
    ]);
    assert_success(&r, "a load of 1e150 N");
    let (_, rows) = parse_csv(&r.stdout, "a load of 1e150 N");
    assert_eq!(rows.len(), 12);
}
