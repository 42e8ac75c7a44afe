//! What the tests of the `tmm` program share: running the built binary, reading its CSV back,
//! the shape of a failure, and temporary files.
#![allow(dead_code)] // each test binary uses a part

use std::path::{Path, PathBuf};
use std::process::Command;

/// The exit code, standard output and standard error of one run.
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

pub fn tmm(args: &[&str]) -> Run {
    tmm_in(&root(), args)
}

/// Runs `tmm` in the directory `dir`.
pub fn tmm_in(dir: &Path, args: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_tmm"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the tmm binary runs");
    Run {
        code: out.status.code().expect("tmm exits (no signal)"),
        stdout: String::from_utf8(out.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(out.stderr).expect("stderr is UTF-8"),
    }
}

/// The repository's root (the CLI's parent).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("cli/ has a parent")
        .to_owned()
}

/// A failure as the program must report it: exit code 1, exactly one line on stderr naming
/// the file, nothing that looks like a panic or a `Debug` dump.
pub fn assert_one_line_failure(r: &Run, file: &str) {
    assert_eq!(r.code, 1, "exit code for {file}; stderr: {}", r.stderr);
    assert_eq!(
        r.stderr.lines().count(),
        1,
        "one line on stderr for {file}: {:?}",
        r.stderr
    );
    assert!(r.stderr.starts_with("tmm: "), "{}", r.stderr);
    assert!(r.stderr.contains(file), "names {file}: {}", r.stderr);
    for debug in ["panicked", "Description {", "Error {", "Some(", "\\n"] {
        assert!(!r.stderr.contains(debug), "no {debug:?} in {}", r.stderr);
    }
}

pub fn assert_success(r: &Run, what: &str) {
    assert_eq!(r.code, 0, "{what} exits 0; stderr: {}", r.stderr);
}

/// Parses CSV text (no quoted cells with commas in the numbers): the header's cells and the
/// rows of numbers, every cell a finite number; checks each row has the header's count.
pub fn parse_csv(text: &str, what: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = split_csv_line(lines.next().expect("a header"));
    let rows: Vec<Vec<f64>> = lines
        .map(|line| {
            let cells = split_csv_line(line);
            assert_eq!(
                cells.len(),
                header.len(),
                "{what}: a row has as many cells as the header"
            );
            cells
                .iter()
                .zip(&header)
                .map(|(c, h)| {
                    let v: f64 = c
                        .parse()
                        .unwrap_or_else(|_| panic!("{what}: cell {c:?} of {h} is a number"));
                    assert!(v.is_finite(), "{what}: {h} = {v} is finite");
                    v
                })
                .collect()
        })
        .collect();
    (header, rows)
}

/// One CSV line's cells, honouring quotes.
pub fn split_csv_line(line: &str) -> Vec<String> {
    let mut cells = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                cells.last_mut().unwrap().push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => cells.push(String::new()),
            c => cells.last_mut().unwrap().push(c),
        }
    }
    cells
}

/// A broken description in a temporary file.
pub struct Broken(pub PathBuf);

impl Broken {
    pub fn new(name: &str, text: &str) -> Self {
        let path =
            std::env::temp_dir().join(format!("tmm-cli-test-{}-{name}.json", std::process::id()));
        std::fs::write(&path, text).expect("a temporary file");
        Self(path)
    }

    /// A temporary file whose name ends in `.ext`.
    pub fn with_extension(name: &str, ext: &str, text: &str) -> Self {
        let path =
            std::env::temp_dir().join(format!("tmm-cli-test-{}-{name}.{ext}", std::process::id()));
        std::fs::write(&path, text).expect("a temporary file");
        Self(path)
    }

    pub fn path(&self) -> String {
        self.0.to_string_lossy().into_owned()
    }
}

impl Drop for Broken {
    fn drop(&mut self) {
        std::fs::remove_file(&self.0).ok();
    }
}

/// The four-bar whose coupler curve the path-generation tests aim at: O1 = (0, 0),
/// O3 = (0.4, 0), crank 0.1, coupler 0.35, rocker 0.3 m (B left of O3→A's line), the coupler
/// point 0.175 m along AB and 0.1 m to its left. Its point at the crank angle φ, m.
pub fn coupler_point(phi: f64) -> [f64; 2] {
    let (a, b, c, d) = (0.1, 0.35, 0.3, 0.4);
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    // B on the circles about A (radius b) and O3 (radius c): along A→O3, then across it.
    let (vx, vy) = (d - ax, -ay);
    let e = vx.hypot(vy);
    let along = (b * b - c * c + e * e) / (2.0 * e);
    let h = (b * b - along * along).sqrt();
    let (bx, by) = (
        ax + along * vx / e - h * vy / e,
        ay + along * vy / e + h * vx / e,
    );
    let (ux, uy) = ((bx - ax) / b, (by - ay) / b);
    [ax + 0.5 * b * ux - 0.1 * uy, ay + 0.5 * b * uy + 0.1 * ux]
}

/// `n` points of that coupler curve, the crank every 360°/n from 0, as CSV with a header.
pub fn coupler_curve_csv(n: usize) -> String {
    let mut text = String::from("x,y\n");
    for k in 0..n {
        let p = coupler_point(std::f64::consts::TAU * k as f64 / n as f64);
        text.push_str(&format!("{:.12},{:.12}\n", p[0], p[1]));
    }
    text
}
