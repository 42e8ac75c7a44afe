//! Every `tmm` command that README.md and cli/README.md show runs as written: the lines of
//! their `sh` blocks (`cargo run … -p tmm-cli -- ARGS` read as `tmm ARGS`, `A && B` as two
//! commands, `> FILE` writing standard output there) and the inline `tmm …` spans that name no
//! placeholder, in the order a reader meets them, in a directory of their own.

mod common;

use common::{root, tmm_in};

/// The commands of one Markdown text, in order: each a list of words after `tmm`, and the
/// file its standard output is redirected to.
fn commands(text: &str) -> Vec<(Vec<String>, Option<String>)> {
    let mut out = Vec::new();
    let mut in_sh = false;
    let mut prose = String::new();
    let flush = |prose: &mut String, out: &mut Vec<_>| {
        for (k, span) in prose.split('`').enumerate() {
            let span = span.split_whitespace().collect::<Vec<_>>().join(" ");
            let placeholder = span.split(' ').any(|w| {
                w.len() >= 3 && w.chars().all(|c| c.is_ascii_uppercase()) || w.starts_with('[')
            });
            let words = span.split(' ').count();
            if k % 2 == 1
                && span.starts_with("tmm ")
                && !placeholder
                && (words >= 3 || span.ends_with("--help"))
            {
                out.push(command(&span));
            }
        }
        prose.clear();
    };
    for line in text.lines() {
        if let Some(fence) = line.strip_prefix("```") {
            flush(&mut prose, &mut out);
            in_sh = !in_sh && fence.trim() == "sh";
            continue;
        }
        if !in_sh {
            prose.push_str(line);
            prose.push('\n');
            continue;
        }
        let line = line.split(" # ").next().unwrap().trim();
        for part in line.split("&&").map(str::trim) {
            if part.starts_with("tmm ") {
                out.push(command(part));
            } else if part.starts_with("cargo run") && part.contains("-p tmm-cli -- ") {
                let args = part.split("-p tmm-cli -- ").nth(1).unwrap();
                out.push(command(&format!("tmm {args}")));
            }
        }
    }
    flush(&mut prose, &mut out);
    out
}

/// `tmm ARGS [> FILE]` → (ARGS, FILE).
fn command(line: &str) -> (Vec<String>, Option<String>) {
    let (args, to) = match line.split_once(" > ") {
        Some((a, f)) => (a, Some(f.trim().to_owned())),
        None => (line, None),
    };
    let words = args.split_whitespace().skip(1).map(str::to_owned).collect();
    (words, to)
}

#[test]
fn every_command_in_the_readmes_runs_as_written() {
    let dir = std::env::temp_dir().join(format!("tmm-cli-test-{}-readme", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The points a reader brings to `tmm synth path points.csv`.
    std::fs::write(dir.join("points.csv"), common::coupler_curve_csv(12)).unwrap();
    let mut ran = Vec::new();
    for doc in ["README.md", "cli/README.md"] {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        for (args, to) in commands(&text) {
            let words: Vec<&str> = args.iter().map(String::as_str).collect();
            let r = tmm_in(&dir, &words);
            assert_eq!(r.code, 0, "{doc}: tmm {}: {}", args.join(" "), r.stderr);
            if let Some(file) = to {
                std::fs::write(dir.join(file), &r.stdout).unwrap();
            }
            ran.push(format!("{doc}: tmm {}", args.join(" ")));
        }
    }
    // Both READMEs' main command, the synthesis and its check by the engine, the help.
    let has = |s: &str| ran.iter().any(|r| r.contains(s));
    assert!(
        has("README.md: tmm analyse linkages/shaper.json"),
        "{ran:#?}"
    );
    assert!(has("tmm analyse my-shaper.json"), "{ran:#?}");
    assert!(has("tmm check cr.json") && has("tmm --help"), "{ran:#?}");
    assert!(ran.len() >= 7, "{ran:#?}");
    for written in ["my-shaper.json", "cr.json", "path.json"] {
        let text = std::fs::read_to_string(dir.join(written)).expect(written);
        assert!(text.contains("\"joints\""), "{written} is a description");
    }
    std::fs::remove_dir_all(&dir).ok();
}
