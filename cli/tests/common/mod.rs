//! What the tests of the `tmm` program share: running the built binary, reading its CSV back,
//! the shape of a failure, and temporary files.
#![allow(dead_code)] // each test binary uses a part

pub mod synth_function;

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
/// rows of numbers, every cell a finite number; checks each row has the header's count. The
/// one value the program leaves empty, the efficiency `eta [-]` where the drive gives no
/// power, reads as NaN and only in a row whose `P_drive [W]` is not positive.
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
                    if c.is_empty() && h == "eta [-]" {
                        let drive = header.iter().position(|h| h == "P_drive [W]");
                        assert!(
                            drive.is_some_and(|k| cells[k].parse::<f64>().is_ok_and(|p| p <= 0.0)),
                            "{what}: {h} is empty only where the drive gives no power: {line}"
                        );
                        return f64::NAN;
                    }
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

/// An SVG document: starts with `<svg`, ends with `</svg>`, every tag closed in order, no
/// `NaN` or `inf` anywhere.
pub fn assert_svg(svg: &str, what: &str) {
    assert!(svg.starts_with("<svg"), "{what} starts with <svg");
    assert!(
        svg.trim_end().ends_with("</svg>"),
        "{what} ends with </svg>"
    );
    for bad in ["NaN", "inf"] {
        assert!(!svg.contains(bad), "{what} contains {bad}");
    }
    let mut open: Vec<&str> = Vec::new();
    let mut rest = svg;
    while let Some(k) = rest.find('<') {
        let end = rest[k..]
            .find('>')
            .unwrap_or_else(|| panic!("{what}: a tag is closed"));
        let tag = &rest[k + 1..k + end];
        rest = &rest[k + end + 1..];
        if tag.starts_with('?') || tag.starts_with('!') || tag.ends_with('/') {
            continue;
        }
        let name = tag
            .trim_start_matches('/')
            .split(|c: char| c.is_whitespace())
            .next()
            .unwrap_or("");
        if tag.starts_with('/') {
            assert_eq!(open.pop(), Some(name), "{what}: </{name}> closes its tag");
        } else {
            open.push(name);
        }
    }
    assert!(open.is_empty(), "{what}: tags left open: {open:?}");
    assert_renders(svg, what);
}

/// The SVG rendered to pixels by resvg (as a browser would draw it; labels aside, resvg has no
/// fonts here): it parses, has a size, and is not blank (some pixel differs from the first).
pub fn assert_renders(svg: &str, what: &str) {
    use resvg::tiny_skia::{Pixmap, Transform};
    use resvg::usvg;
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .unwrap_or_else(|e| panic!("{what}: resvg reads the SVG: {e}"));
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height())
        .unwrap_or_else(|| panic!("{what}: the picture has a size"));
    resvg::render(&tree, Transform::default(), &mut pixmap.as_mut());
    let pixels = pixmap.pixels();
    let drawn = pixels.iter().filter(|p| **p != pixels[0]).count();
    assert!(
        drawn * 1000 > pixels.len(),
        "{what}: something is drawn ({drawn} of {} pixels differ from the corner's)",
        pixels.len()
    );
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

/// A slider-crank driven by its piston (a slider input), the crank loaded by a couple.
pub const PISTON_DRIVEN: &str = r#"{
  "name": "piston-driven slider-crank",
  "joints": [
    {"name": "O1", "at": [0.0, 0.0]},
    {"name": "A", "at": [0.03, 0.04]},
    {"name": "B", "at": [0.22, 0.0]},
    {"name": "P", "at": [0.22, 0.0], "kind": {"prismatic": {"guide": "frame", "direction": [1.0, 0.0]}}}
  ],
  "links": [
    {"name": "frame", "joints": ["O1", "P"]},
    {"name": "piston", "joints": ["B", "P"], "mass": {"m": 0.8, "j": 0.0, "centre": "B"}},
    {"name": "rod", "joints": ["A", "B"], "mass": {"m": 1.2, "j": 0.004, "centre": [0.125, 0.02]}},
    {"name": "crank", "joints": ["O1", "A"], "mass": {"m": 2.5, "j": 0.004, "centre": [0.0, 0.0]}}
  ],
  "input": {"link": "piston"},
  "loads": [{"moment": {"link": "crank", "moment": -5.0}}],
  "speed": 0.5
}"#;

/// The bundled four-bar with a crank too long to turn: it rocks between two lock angles
/// (s + l > p + q, a triple rocker).
pub fn rocking_four_bar() -> Broken {
    let four_bar = std::fs::read_to_string(root().join("linkages/four-bar.json")).unwrap();
    let text = four_bar
        .replace("\"at\": [0.1, 0.0]", "\"at\": [0.0, 0.3]")
        .replace(
            "\"at\": [0.25612516773077276, 0.3132489936153635]",
            "\"at\": [0.3, 0.35]",
        );
    assert_ne!(text, four_bar, "the test's edit applies");
    Broken::new("rocking", &text)
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

/// The eight timed points of the library's example six-bar
/// ([`tmm::synthesis::PathRequirement::six_bar_example`]), 0.3 rad of crank apart, as the
/// program reads them: x, y and the crank's turn in degrees.
pub fn six_bar_example_csv() -> String {
    let req = tmm::synthesis::PathRequirement::six_bar_example().unwrap();
    let tmm::synthesis::Timing::Prescribed(delta) = &req.timing else {
        panic!("the example is timed")
    };
    let mut csv = String::from("x,y,crank\n");
    for (p, d) in req.points.iter().zip(delta) {
        csv.push_str(&format!(
            "{:.15},{:.15},{:.15}\n",
            p[0],
            p[1],
            d.to_degrees()
        ));
    }
    csv
}

/// The number after `key` in `text`: its digits, sign, point and exponent, a sentence's
/// final full stop dropped.
pub fn number_after(text: &str, key: &str) -> f64 {
    let at = text
        .find(key)
        .unwrap_or_else(|| panic!("{key:?} in {text}"))
        + key.len();
    let num: String = text[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | '-' | '+'))
        .collect();
    num.trim_end_matches('.')
        .parse()
        .unwrap_or_else(|_| panic!("a number after {key:?} in {text}"))
}
