//! Every budget of the program is a count derived from the input, never from the clock: the
//! budgets printed are asserted against their closed forms (the weight of one solve of the
//! linkage in dyad solves: 1 an input, 1 a dyad, 16 a triad, (2n)³/4 a general group of n
//! inner joints; a stage at most 4·10⁸ of them), the same command gives the same output
//! twice, a size above its budget is refused naming the option and the bound, and progress
//! shows on a terminal (a pseudo-terminal made by `script`, where there is one).

mod common;

use common::{assert_one_line_failure, assert_success, number_after, tmm, Broken};

/// The work budget of one stage, in dyad solves.
const MAX_WORK: f64 = 4e8;

/// The run-up's step budget of a linkage whose solve weighs `weight`: at most 10⁶ steps,
/// each of 4 solves.
fn run_up_budget(weight: f64) -> f64 {
    1e6_f64.min(MAX_WORK / (4.0 * weight)).floor()
}

/// A general group of 4·`n` links and 2·`n` inner joints: a ring of `n` ternary links, each
/// held by a leg to the frame (the first leg to the crank). No dyad or triad can be split off
/// it, so the program solves it by its closure equations, of weight (4n)³/4.
fn ring(n: usize) -> String {
    use std::f64::consts::TAU;
    let mut joints = vec![r#"{"name": "O", "at": [0, 0]}"#.to_owned()];
    let mut links = Vec::new();
    let mut frame = vec!["\"O\"".to_owned()];
    for k in 0..n {
        let t = TAU * k as f64 / n as f64;
        let m = TAU * (k as f64 + 0.5) / n as f64;
        joints.push(format!(
            r#"{{"name": "R{k}", "at": [{}, {}]}}"#,
            t.cos(),
            t.sin()
        ));
        joints.push(format!(
            r#"{{"name": "M{k}", "at": [{}, {}]}}"#,
            0.95 * m.cos(),
            0.95 * m.sin()
        ));
        joints.push(format!(
            r#"{{"name": "G{k}", "at": [{}, {}]}}"#,
            2.0 * (m + 0.3).cos(),
            2.0 * (m + 0.3).sin()
        ));
        if k > 0 {
            frame.push(format!("\"G{k}\""));
        }
        links.push(format!(
            r#"{{"name": "ring{k}", "joints": ["R{k}", "R{}", "M{k}"], "mass": {{"m": 1, "j": 0.1, "centre": "M{k}"}}}}"#,
            (k + 1) % n
        ));
        links.push(format!(
            r#"{{"name": "leg{k}", "joints": ["M{k}", "G{k}"]}}"#
        ));
    }
    links.insert(0, r#"{"name": "crank", "joints": ["O", "G0"]}"#.to_owned());
    links.insert(
        0,
        format!(r#"{{"name": "frame", "joints": [{}]}}"#, frame.join(", ")),
    );
    format!(
        r#"{{"name": "ring of {n}", "joints": [{}], "links": [{}], "input": {{"link": "crank"}}}}"#,
        joints.join(", "),
        links.join(", ")
    )
}

/// The bundled linkages' run-up budgets: the four-bar (weight 2) and the triad (1 + 16) keep
/// 10⁶ steps; the double butterfly, one general group of 6 inner joints (weight
/// 1 + 12³/4 = 433), ⌊4·10⁸ / (4·433)⌋ = 230 946 — whatever the machine's load.
#[test]
fn the_run_up_budget_is_a_count_from_the_description() {
    for (file, weight) in [
        ("four-bar", 2.0),
        ("six-bar-triad", 17.0),
        ("double-butterfly", 1.0 + 12f64.powi(3) / 4.0),
    ] {
        let r = tmm(&[
            "dynamics",
            file,
            "--run-up",
            "--positions",
            "36",
            "--rotor",
            "1e300",
        ]);
        assert_one_line_failure(&r, file);
        let budget = number_after(&r.stderr, "above the ");
        assert_eq!(budget, run_up_budget(weight), "{file}: {}", r.stderr);
        assert!(r.stderr.contains("--rotor"), "{}", r.stderr);
    }
    assert_eq!(run_up_budget(433.0), 230_946.0);
    // A run-up that finishes says how many steps it could have taken, as text and as JSON.
    let r = tmm(&["dynamics", "four-bar", "--run-up", "--positions", "36"]);
    assert_success(&r, "four-bar --run-up");
    assert!(
        r.stdout.contains("steps of the 1000000 allowed"),
        "{}",
        r.stdout
    );
    let r = tmm(&[
        "dynamics",
        "four-bar",
        "--run-up",
        "--positions",
        "36",
        "--format",
        "json",
    ]);
    assert_success(&r, "four-bar --run-up --format json");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["run_up"]["step_budget"], 1_000_000, "{}", r.stdout);
    let steps = v["run_up"]["steps"].as_u64().unwrap();
    assert!(steps > 0 && steps <= 1_000_000, "{steps}");
}

/// The same command, the same output: a run-up, and a path search without --time (bounded
/// by its evaluations alone), whose failure names the budget of evaluations and no seconds.
#[test]
fn the_same_command_gives_the_same_output_twice() {
    let args = [
        "dynamics",
        "mechanism-compressor",
        "--run-up",
        "--flywheel",
        "0.05",
    ];
    let (a, b) = (tmm(&args), tmm(&args));
    assert_success(&a, "run-up");
    assert_eq!(a.stdout, b.stdout);
    let points = Broken::with_extension("budget-points", "csv", &common::coupler_curve_csv(12));
    let args = [
        "synth",
        "path",
        &points.path(),
        "--budget",
        "240",
        "--min-transmission",
        "60",
    ];
    let (a, b) = (tmm(&args), tmm(&args));
    assert_one_line_failure(&a, &points.path());
    assert_eq!(a.stderr, b.stderr);
    assert!(
        a.stderr.contains("240 candidate evaluations of --budget"),
        "{}",
        a.stderr
    );
    // No duration in it: "… 0.071 s" would differ from run to run.
    assert!(
        !a.stderr.contains(" s ") && !a.stderr.contains(" s)") && !a.stderr.contains("--time"),
        "{}",
        a.stderr
    );
    // With --time the bound is the user's, and said.
    let mut timed = args.to_vec();
    timed.extend(["--time", "1000"]);
    let r = tmm(&timed);
    assert_one_line_failure(&r, &points.path());
    assert!(r.stderr.contains("the 1000 s of --time"), "{}", r.stderr);
    // The budget of evaluations has a stated upper bound.
    let r = tmm(&["synth", "path", &points.path(), "--budget", "2000001"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("--budget") && r.stderr.contains("2000000"),
        "{}",
        r.stderr
    );
}

/// A stage whose work is above the budget is refused before it starts, naming the option and
/// the most it may ask: a ring of 30 (60 inner joints, weight 1 + 120³/4 = 432 001) may make
/// ⌊4·10⁸ / 432 001⌋ = 925 solves a stage — its range is not searched (about 2 000 solves),
/// nor its assembly modes (a multistart of 2 000 starts of up to 101 solves each), and 1 000
/// positions are refused; 257 flywheels of 3 600 positions on the double butterfly
/// are above its ⌊4·10⁸ / 433⌋ = 923 787 solves, 256 are not.
#[test]
fn a_size_above_its_budget_is_refused_naming_the_option_and_the_bound() {
    let ring = Broken::new("ring-30", &ring(30));
    let file = ring.path();
    let weight = 1.0 + 120f64.powi(3) / 4.0;
    let most = (MAX_WORK / weight).floor();
    assert_eq!(most, 925.0);
    let r = tmm(&["check", &file]);
    assert_success(&r, "check ring of 30");
    assert!(
        r.stdout
            .contains("range: not determined: the search of the input's range: 2000 solves"),
        "{}",
        r.stdout
    );
    assert_eq!(number_after(&r.stdout, "above the "), most, "{}", r.stdout);
    // Its assembly modes: a multistart search (the ring has no reduction to one angle) of
    // 2000 starts, each up to 101 solves of the group, is not run either.
    let modes = r
        .stdout
        .lines()
        .find(|l| l.starts_with("assembly modes at the reference input: not counted"))
        .unwrap_or_else(|| panic!("{}", r.stdout));
    assert!(modes.contains("multistart"), "{modes}");
    assert_eq!(number_after(modes, "above the "), most, "{modes}");
    assert_eq!(number_after(modes, "modes: "), 2000.0 * 101.0, "{modes}");
    for (args, option) in [
        (
            &["analyse", &file, "--positions", "1000"][..],
            "--positions",
        ),
        (
            &["dynamics", &file, "--positions", "1000"][..],
            "--positions",
        ),
        (&["draw", &file, "--plan"][..], "--scheme"),
    ] {
        let r = tmm(args);
        assert_one_line_failure(&r, &file);
        assert_eq!(number_after(&r.stderr, "above the "), most, "{}", r.stderr);
        assert!(r.stderr.contains(option), "{args:?}: {}", r.stderr);
    }
    let r = tmm(&["analyse", &file, "--positions", "1000"]);
    assert!(r.stderr.contains("at most 925"), "{}", r.stderr);
    // The flywheels: 256 values of δ are within the budget, 257 are not.
    let deltas = |n: usize| vec!["0.05"; n];
    let mut args = vec![
        "dynamics",
        "double-butterfly",
        "--positions",
        "12",
        "--flywheel",
    ];
    args.extend(deltas(257));
    let r = tmm(&args);
    assert_one_line_failure(&r, "double-butterfly");
    assert!(
        r.stderr.contains("--flywheel with 257 values") && r.stderr.contains("923787"),
        "{}",
        r.stderr
    );
    let most = (MAX_WORK / 433.0).floor();
    assert_eq!(most, 923_787.0);
    // The most flywheels of 3 600 positions each within it: 256, so 257 are refused.
    assert_eq!((most / 3600.0).floor(), 256.0);
}

/// On a terminal a long table reports its progress on stderr, one line overwritten; piped,
/// nothing. Run through `script`, which gives the program a pseudo-terminal (skipped where
/// there is no `script`).
#[test]
fn a_long_run_reports_progress_on_a_terminal() {
    let script = std::path::Path::new("/usr/bin/script");
    if !script.exists() {
        eprintln!("no /usr/bin/script: the terminal's progress is not checked here");
        return;
    }
    let bin = env!("CARGO_BIN_EXE_tmm");
    for (args, says) in [
        (
            "dynamics four-bar --positions 20000",
            "position 15001 of 20000",
        ),
        (
            "analyse four-bar --positions 20000 --format csv",
            "position 15001 of 20000",
        ),
        ("dynamics five-bar-robot --grid 30", "row 30 of 30"),
    ] {
        let out = std::process::Command::new(script)
            .args(["-qec", &format!("'{bin}' {args} > /dev/null"), "/dev/null"])
            .output()
            .expect("script runs");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{args}: {text}");
        assert!(text.contains(says), "{args}: {text:?}");
        // The line is cleared at the end, so that the terminal is left as it was.
        assert!(text.ends_with("\r\x1b[K"), "{args}: {text:?}");
    }
}

/// `n` crank-rockers hung on one crank: dyad k's coupler (0.4 m) is hinged to the crank
/// 0.1 m from its pivot and its rocker (0.3 m) to the frame 0.35 m away, at 2πk/n. Each
/// dyad hangs on the crank alone.
fn fan(n: usize) -> String {
    use std::f64::consts::TAU;
    let (r, c, rocker, d) = (0.1_f64, 0.4_f64, 0.3_f64, 0.35_f64);
    let mut joints = vec![r#"{"name": "O", "at": [0, 0]}"#.to_owned()];
    let (mut crank, mut frame) = (vec!["\"O\"".to_owned()], vec!["\"O\"".to_owned()]);
    let mut links = Vec::new();
    for k in 0..n {
        #[allow(clippy::cast_precision_loss)]
        let b = TAU * k as f64 / n as f64;
        let a = [r * (b + 0.3).cos(), r * (b + 0.3).sin()];
        let o = [d * b.cos(), d * b.sin()];
        // B on the circles about A (c) and O (rocker), to the left of A→O.
        let (dx, dy) = (o[0] - a[0], o[1] - a[1]);
        let l = dx.hypot(dy);
        let x = (c * c - rocker * rocker + l * l) / (2.0 * l);
        let h = (c * c - x * x).sqrt();
        let p = [a[0] + (x * dx - h * dy) / l, a[1] + (x * dy + h * dx) / l];
        for (name, at) in [("A", a), ("B", p), ("C", o)] {
            joints.push(format!(
                r#"{{"name": "{name}{k}", "at": [{}, {}]}}"#,
                at[0], at[1]
            ));
        }
        crank.push(format!("\"A{k}\""));
        frame.push(format!("\"C{k}\""));
        links.push(format!(
            r#"{{"name": "coupler{k}", "joints": ["A{k}", "B{k}"]}}, {{"name": "rocker{k}", "joints": ["C{k}", "B{k}"]}}"#
        ));
    }
    format!(
        r#"{{"name": "fan of {n}", "joints": [{}], "links": [{{"name": "frame", "joints": [{}]}}, {{"name": "crank", "joints": [{}]}}, {}], "input": {{"link": "crank", "drive": "coupling"}}}}"#,
        joints.join(", "),
        frame.join(", "),
        crank.join(", "),
        links.join(", ")
    )
}

/// `tmm check`'s scan of every group's transmission angle is budgeted by what it solves: the
/// sweep's 720 solves of the linkage, then each group's refinement on the groups it hangs on
/// alone. 2500 dyads hung on one crank are scanned (counted as whole-linkage refinements, 80
/// solves of 2501 dyads for each of 2500 groups, they were 5·10⁸ dyad solves, above the
/// budget of 4·10⁸, and refused), and each group's γ_min is the crank-rocker's closed form:
/// the coupler and rocker of the dyad k are at their most acute when the crank points at its
/// pivot, |AC| = d − r, cos γ = (c² + l² − (d − r)²)/(2cl) = (0.25 − 0.0625)/0.24.
#[test]
fn the_transmission_scan_is_budgeted_by_each_groups_ancestry() {
    let n = 2500;
    let file = Broken::new("fan", &fan(n));
    let r = tmm(&["check", &file.path(), "--format", "json"]);
    assert_success(&r, "check of the fan");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("JSON");
    let rows = v["transmission"].as_array().unwrap();
    assert_eq!(rows.len(), n);
    let exact = (0.1875_f64 / 0.24).acos();
    for row in rows {
        let min = row["min"]
            .as_f64()
            .unwrap_or_else(|| panic!("not computed: {row}"));
        assert!((min - exact).abs() < 1e-9, "{min} against {exact}: {row}");
    }
}
