//! What a newcomer's audit found, kept fixed: a description saved with a byte-order mark (as
//! some editors on Windows save) is read; a file that is JSON but not an object is told what
//! a description is, not that "a string" was expected; a function generator's report writes
//! its formula as the user typed it; the README's Rust code pastes into a new project as it
//! reads on the page (a whole program: no hidden doc-test lines, which the page would show).

mod common;

use common::{assert_one_line_failure, assert_success, root, tmm, Broken};

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
        let r = tmm(&[
            "synth",
            "function",
            "--function",
            function,
            "--x",
            "1,2",
            "--crank",
            crank,
            "--rocker",
            rocker,
            "--frame",
            "0.1",
            "-o",
            &out.to_string_lossy(),
        ]);
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
