//! What a newcomer's audit found, kept fixed: a description saved with a byte-order mark (as
//! some editors on Windows save) is read; a file that is JSON but not an object is told what
//! a description is, not that "a string" was expected; a function generator's report writes
//! its formula as the user typed it; the README's Rust code pastes into a new project as it
//! reads on the page (a whole program: no hidden doc-test lines, which the page would show).

mod common;

use common::synth_function::SynthFunction;
use common::{assert_one_line_failure, assert_success, number_after, root, tmm, Broken};

#[test]
fn a_file_saved_with_a_byte_order_mark_is_read() {
    let text = tmm(&["bundled", "four-bar"]).stdout;
    let plain = Broken::new("plain", &text);
    let marked = Broken::new("marked", &format!("\u{feff}{text}"));
    let (a, b) = (
        tmm(&["check", &plain.path()]),
        tmm(&["check", &marked.path()]),
    );
    assert_success(&b, "check of a file with a byte-order mark");
    assert_eq!(a.stdout, b.stdout);
}

#[test]
fn a_file_that_is_json_but_not_an_object_is_told_what_a_description_is() {
    for (name, text) in [
        ("array", "[1, 2]"),
        ("string", "\"four-bar\""),
        ("number", "42\n"),
        ("null", "null"),
    ] {
        let file = Broken::new(name, text);
        let r = tmm(&["check", &file.path()]);
        assert_one_line_failure(&r, &file.path());
        assert!(
            r.stderr.contains("a description is a JSON object") && r.stderr.contains("tmm bundled"),
            "{name}: {}",
            r.stderr
        );
        assert!(!r.stderr.contains("expected a string"), "{}", r.stderr);
    }
}

#[test]
fn a_function_generators_report_writes_its_formula() {
    let dir = std::env::temp_dir();
    // The help's two examples.
    for (function, formula, crank, rocker) in [
        ("x^2", "y = x^2, x from", "180,270", "240,330"),
        ("log10", "y = log10(x), x from", "-30,30", "0,90"),
    ] {
        let out = dir.join(format!("tmm-cli-test-{}-function.json", std::process::id()));
        let path = out.to_string_lossy();
        let r = tmm(&SynthFunction {
            function,
            crank,
            rocker,
            ..Default::default()
        }
        .command(&["-o", &path]));
        std::fs::remove_file(&out).ok();
        assert_success(&r, function);
        assert!(r.stdout.contains(formula), "{function}: {}", r.stdout);
    }
}

/// The README's Rust blocks are whole programs (`fn main` returning `Result`), with no line
/// starting with `# `: GitHub shows a doc test's hidden lines, and `# Ok::<(), tmm::Error>(())`
/// pasted into `main.rs` does not compile. Its `[dependencies]` line names the crate by a path
/// (the crate is built from this repository).
#[test]
fn the_readme_code_pastes_into_a_new_project() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let mut blocks = Vec::new();
    let mut lines = readme.lines();
    while let Some(line) = lines.next() {
        if let Some(lang) = line.strip_prefix("```")
            && !lang.is_empty()
        {
            let body: Vec<&str> = lines
                .by_ref()
                .take_while(|l| !l.starts_with("```"))
                .collect();
            blocks.push((lang.trim().to_owned(), body.join("\n")));
        }
    }
    let rust: Vec<&String> = blocks
        .iter()
        .filter(|(l, _)| l == "rust")
        .map(|(_, b)| b)
        .collect();
    assert!(!rust.is_empty(), "the README has Rust code");
    for code in rust {
        assert!(
            code.contains("fn main() -> Result<(), tmm::Error>"),
            "{code}"
        );
        assert!(
            !code.lines().any(|l| l.trim_start().starts_with("# ")),
            "a hidden doc-test line shows on the page: {code}"
        );
    }
    let toml = blocks
        .iter()
        .find(|(l, _)| l == "toml")
        .map(|(_, b)| b)
        .expect("the README shows the [dependencies] line");
    assert!(
        toml.contains("[dependencies]") && toml.contains("tmm = { path = "),
        "{toml}"
    );
}

/// A value of the wrong type is named by its field, not only by its line and column.
#[test]
fn a_value_of_the_wrong_type_names_its_field() {
    let four_bar = tmm(&["bundled", "four-bar"]).stdout;
    let first_at = four_bar.find("\"at\": [").expect("a joint's position") + "\"at\": [".len();
    let mut bad = four_bar.clone();
    bad.insert_str(first_at, "\"zero\", ");
    for (name, text, field) in [
        ("at-string", bad, "field joints[0].at[0]"),
        (
            "speed-string",
            four_bar.replacen('{', "{\"speed\": \"fast\",", 1),
            "field speed",
        ),
    ] {
        let file = Broken::new(name, &text);
        let r = tmm(&["check", &file.path()]);
        assert_one_line_failure(&r, &file.path());
        assert!(r.stderr.contains(field), "{name}: {}", r.stderr);
        assert!(r.stderr.contains("line "), "{}", r.stderr);
    }
}

/// `tmm draw FILE` without `-o` on a terminal is refused, naming `-o`, before any work (run
/// under `script`, which gives the program a pseudo-terminal); piped, the SVG still goes to
/// standard output. Where `script` is missing, only the piped half runs.
#[test]
fn a_picture_is_not_written_to_a_terminal() {
    let piped = tmm(&["draw", "four-bar"]);
    assert_success(&piped, "draw four-bar | …");
    assert!(
        piped.stdout.trim_start().starts_with("<svg"),
        "{}",
        &piped.stdout[..80.min(piped.stdout.len())]
    );
    let bin = env!("CARGO_BIN_EXE_tmm");
    let run = std::process::Command::new("script")
        .args(["-qec", &format!("'{bin}' draw four-bar"), "/dev/null"])
        .stdin(std::process::Stdio::null())
        .output();
    let Ok(out) = run else {
        eprintln!("no `script` here: the terminal half is not run");
        return;
    };
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(!text.contains("<svg"), "no SVG on the terminal: {text}");
    assert!(
        text.contains("tmm: four-bar: ") && text.contains("-o OUT.svg"),
        "{text}"
    );
    assert_eq!(text.trim().lines().count(), 1, "{text}");
    // With -o the same terminal gets no SVG and the file is written.
    let svg = std::env::temp_dir().join(format!("tmm-cli-terminal-{}.svg", std::process::id()));
    let out = std::process::Command::new("script")
        .args([
            "-qec",
            &format!("'{bin}' draw four-bar -o '{}'", svg.display()),
            "/dev/null",
        ])
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let _ = std::fs::remove_file(&svg);
}

/// The motor tmm chooses is echoed as a person writes one (5 significant digits, in the text
/// and the JSON alike), and it is the motor run: typing the echoed `a,b` back as `--motor`
/// repeats the run-up to the last digit of every turn.
#[test]
fn a_default_motor_is_echoed_as_written_and_repeats_its_run() {
    for file in ["four-bar", "mechanism-compressor"] {
        let chosen = tmm(&["dynamics", file, "--run-up", "--format", "json"]);
        assert_success(&chosen, file);
        let v: serde_json::Value = serde_json::from_str(&chosen.stdout).expect("JSON");
        let motor = &v["run_up"]["motor"];
        assert_eq!(motor["chosen_by_tmm"], serde_json::json!(true));
        let (a, b) = (motor["a"].as_f64().unwrap(), motor["b"].as_f64().unwrap());
        for x in [a, b] {
            let digits: String = format!("{x:e}")
                .split('e')
                .next()
                .unwrap()
                .chars()
                .filter(char::is_ascii_digit)
                .collect();
            assert!(digits.len() <= 5, "{file}: {x} has {} digits", digits.len());
        }
        let text = tmm(&["dynamics", file, "--run-up"]).stdout;
        let line = text
            .lines()
            .find(|l| l.contains("motor M = "))
            .unwrap_or_else(|| panic!("{file}: {text}"));
        assert_eq!(number_after(line, "motor M = "), a, "{file}: {line}");
        assert_eq!(number_after(line, " − "), b, "{file}: {line}");
        let given = tmm(&[
            "dynamics",
            file,
            "--run-up",
            "--format",
            "json",
            "--motor",
            &format!("{a},{b}"),
        ]);
        assert_success(&given, file);
        let w: serde_json::Value = serde_json::from_str(&given.stdout).expect("JSON");
        assert_eq!(
            w["run_up"]["motor"]["chosen_by_tmm"],
            serde_json::json!(false)
        );
        assert_eq!(v["run_up"]["turns"], w["run_up"]["turns"], "{file}");
    }
    // A refusal that echoes the chosen motor reads it the same way.
    let r = tmm(&["dynamics", "four-bar", "--run-up", "--speed", "1e-9"]);
    assert_one_line_failure(&r, "four-bar");
    let b = number_after(&r.stderr, "slope b = ");
    assert!(format!("{b:e}").len() <= "1.2345e11".len(), "{}", r.stderr);
}

/// A least-squares function generator over 10⁶ points lists precision points that read
/// apart (6 decimals read its first ones all `1.000000`), each the Chebyshev node it is:
/// x_j = (x0 + x1)/2 − (x1 − x0)/2·cos((2j − 1)π/2N), the first four and the last four with
/// the count; three points are listed in full.
#[test]
fn precision_points_read_apart() {
    let out = std::env::temp_dir().join(format!("tmm-cli-ls-{}.json", std::process::id()));
    let n = 1_000_000_usize;
    for (points, listed) in [(Some(n), 8), (None, 3)] {
        let mut args = SynthFunction::default().command(&["-o", out.to_str().unwrap()]);
        let count = points.map(|p| p.to_string());
        if let Some(c) = &count {
            args.extend_from_slice(&["--least-squares", c]);
        }
        let r = tmm(&args);
        assert_success(&r, "synth function");
        let line = r
            .stdout
            .lines()
            .find(|l| l.contains("precision points x = "))
            .unwrap_or_else(|| panic!("{}", r.stdout));
        let list = line.split("x = ").nth(1).unwrap();
        let list = list.split(" (").next().unwrap();
        let xs: Vec<f64> = list
            .split(", ")
            .filter(|t| *t != "…")
            .map(|t| t.parse().unwrap_or_else(|_| panic!("{t:?} in {line}")))
            .collect();
        assert_eq!(xs.len(), listed, "{line}");
        let total = points.unwrap_or(3);
        if points.is_some() {
            assert!(line.ends_with(&format!("({n} points)")), "{line}");
        }
        let nodes: Vec<usize> = if listed == 8 {
            (0..4).chain(total - 4..total).collect()
        } else {
            (0..3).collect()
        };
        for (x, j) in xs.iter().zip(nodes) {
            #[allow(clippy::cast_precision_loss)]
            let node =
                1.5 - 0.5 * ((2 * j + 1) as f64 * std::f64::consts::PI / (2 * total) as f64).cos();
            // Printed with the fewest decimals that part them: within half a unit of the
            // last decimal shown, and never all alike.
            let text = list
                .split(", ")
                .find(|t| t.parse::<f64>().ok() == Some(*x))
                .unwrap();
            let decimals = text.split('.').nth(1).map_or(0, str::len);
            assert!(
                (x - node).abs() <= 0.5 * 10f64.powi(-(decimals as i32)) + 1e-15,
                "{x} against the node {node}: {line}"
            );
        }
        for w in xs.windows(2) {
            assert!(w[0] < w[1], "{line}");
        }
    }
    let _ = std::fs::remove_file(&out);
}
