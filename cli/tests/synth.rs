//! `tmm synth` by round trip: each kind's description, written by the program, is read back
//! by `tmm analyse` (and `tmm check`) and its motion measured from the CSV table — the time
//! ratio from the crank angles at the output's extreme positions (each located by a parabola
//! through the finest samples around it), the stroke or swing between them, the rocker's
//! angle at given crank angles, the coupler point at the design's crank angles — against the
//! requirement. And bad requirements: exit code 1, one line on stderr naming the parameter.

mod common;

use std::f64::consts::{PI, TAU};

use common::synth_function::SynthFunction;
use common::{assert_success, parse_csv, tmm, Broken, Run};

/// Runs `tmm synth ARGS -o FILE`: the report (stdout) and the temporary description file.
fn synth(name: &str, args: &[&str]) -> (Run, Broken) {
    let out = Broken::new(&format!("synth-{name}"), "");
    let path = out.path();
    let mut all = vec!["synth"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", &path]);
    let r = tmm(&all);
    assert_success(&r, &all.join(" "));
    let json = std::fs::read_to_string(&out.0).expect("the description is written");
    assert!(json.contains("\"joints\""), "{name}: {json}");
    (r, out)
}

/// A CSV table of `tmm analyse FILE ARGS --format csv`: the header and the rows.
fn analyse(file: &str, args: &[&str]) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut all = vec!["analyse", file];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--format", "csv"]);
    let r = tmm(&all);
    assert_success(&r, &all.join(" "));
    parse_csv(&r.stdout, &all.join(" "))
}

fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("a column {name}: {header:?}"))
}

/// a − b as an angle in [−π, π).
fn angle_difference(a: f64, b: f64) -> f64 {
    (a - b + PI).rem_euclid(TAU) - PI
}

/// The extreme (largest with `sign` = 1, smallest with −1) of `value` over the crank's turn
/// and the crank angle there: the best of 720 positions, then 201 positions 0.005° apart
/// around it, then the vertex of the parabola through the best three of those.
fn extreme(file: &str, value: &str, angle: bool, sign: f64) -> (f64, f64) {
    let samples = |header: &[String], rows: &[Vec<f64>]| -> Vec<(f64, f64)> {
        let (phi, v) = (column(header, "phi_in [rad]"), column(header, value));
        let first = rows[0][v];
        rows.iter()
            .map(|r| {
                // Angles unwrapped about the first: a rocker's swing is below a half turn.
                let y = if angle {
                    first + angle_difference(r[v], first)
                } else {
                    r[v]
                };
                (r[phi], sign * y)
            })
            .collect()
    };
    let best = |s: &[(f64, f64)]| {
        (0..s.len())
            .max_by(|&i, &j| s[i].1.total_cmp(&s[j].1))
            .unwrap()
    };
    let (header, rows) = analyse(file, &["--positions", "720"]);
    let coarse = samples(&header, &rows);
    let centre = coarse[best(&coarse)].0.to_degrees();
    let at: Vec<String> = (-100..=100)
        .map(|k| format!("{:.10}", centre + 0.005 * f64::from(k)))
        .collect();
    let mut args: Vec<&str> = vec!["--at"];
    args.extend(at.iter().map(String::as_str));
    let (header, rows) = analyse(file, &args);
    let fine = samples(&header, &rows);
    let k = best(&fine);
    assert!(
        k > 0 && k + 1 < fine.len(),
        "{file}: the fine samples bracket the extreme"
    );
    let (f0, f1, f2) = (fine[k - 1].1, fine[k].1, fine[k + 1].1);
    let h = fine[k + 1].0 - fine[k].0;
    let delta = 0.5 * (f0 - f2) / (f0 - 2.0 * f1 + f2);
    (
        fine[k].0 + delta * h,
        sign * (f1 - 0.25 * (f0 - f2) * delta),
    )
}

/// The time ratio and the stroke (or swing) of `value` measured on the analysed course.
fn measured_k_and_stroke(file: &str, value: &str, angle: bool) -> (f64, f64) {
    let (phi_max, max) = extreme(file, value, angle, 1.0);
    let (phi_min, min) = extreme(file, value, angle, -1.0);
    let one = (phi_max - phi_min).rem_euclid(TAU);
    let other = TAU - one;
    let stroke = if angle {
        angle_difference(max, min).abs()
    } else {
        max - min
    };
    (one.max(other) / one.min(other), stroke)
}

/// The engine's own strokes and γ_min of the description, from `tmm check --format json`.
fn checked(file: &str) -> (f64, f64, f64) {
    let r = tmm(&["check", file, "--format", "json"]);
    assert_success(&r, "check");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let gamma = v["transmission"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["min"].as_f64().expect("γ_min"))
        .fold(f64::INFINITY, f64::min);
    (
        v["strokes"]["time_ratio"].as_f64().expect("K"),
        v["strokes"]["stroke"].as_f64().expect("stroke"),
        gamma,
    )
}

/// The constant distance between two joints over the course.
fn distance(header: &[String], rows: &[Vec<f64>], p: &str, q: &str) -> f64 {
    let c = |n: String| column(header, &n);
    let (px, py, qx, qy) = (
        c(format!("x({p}) [m]")),
        c(format!("y({p}) [m]")),
        c(format!("x({q}) [m]")),
        c(format!("y({q}) [m]")),
    );
    let d: Vec<f64> = rows
        .iter()
        .map(|r| (r[px] - r[qx]).hypot(r[py] - r[qy]))
        .collect();
    let spread = d.iter().fold(0.0f64, |m, x| m.max((x - d[0]).abs()));
    assert!(spread < 1e-12, "{p}{q} keeps its length: {spread}");
    d[0]
}

#[test]
fn crank_rockers_meet_k_swing_rocker_and_frame() {
    // K, ψ (degrees), the rocker (m), the frame (m, or the best), [γ] (degrees).
    for (k, swing, rocker, frame, gamma_min) in [
        (1.25, 45.0f64, 0.3, None, 40.0f64),
        (1.25, 45.0, 0.3, Some(0.4), 30.0),
        (1.1, 30.0, 0.12, None, 40.0),
        (1.4, 60.0, 1.5, None, 25.0),
    ] {
        let (ks, sw, rk, gm) = (
            k.to_string(),
            swing.to_string(),
            rocker.to_string(),
            gamma_min.to_string(),
        );
        let fr = frame.map(|f: f64| f.to_string());
        let mut args = vec![
            "crank-rocker",
            "-K",
            &ks,
            "--swing",
            &sw,
            "--rocker",
            &rk,
            "--min-transmission",
            &gm,
        ];
        if let Some(f) = &fr {
            args.extend(["--frame", f.as_str()]);
        }
        let (report, file) = synth("crank-rocker", &args);
        let what = args.join(" ");
        assert!(report.stdout.contains("Grashof class"), "{what}");
        let (k_found, swing_found) = measured_k_and_stroke(&file.path(), "phi(rocker) [rad]", true);
        assert!((k_found - k).abs() < 1e-7, "{what}: K = {k_found}");
        assert!(
            (swing_found - swing.to_radians()).abs() < 1e-9,
            "{what}: ψ = {}°",
            swing_found.to_degrees()
        );
        let (k_check, swing_check, gamma) = checked(&file.path());
        assert!((k_check - k).abs() < 1e-9 && (swing_check - swing.to_radians()).abs() < 1e-9);
        assert!(
            gamma >= gamma_min.to_radians() - 1e-12,
            "{what}: γ_min {gamma}"
        );
        let (header, rows) = analyse(&file.path(), &["--positions", "36"]);
        assert!((distance(&header, &rows, "O3", "B") - rocker).abs() < 1e-12);
        if let Some(f) = frame {
            assert!((distance(&header, &rows, "O1", "O3") - f).abs() < 1e-12);
        }
    }
}

#[test]
fn slider_cranks_meet_stroke_k_and_offset() {
    for (h, k, offset) in [
        (0.2, 1.2, None),
        (0.2, 1.15, Some(0.05)),
        (0.05, 1.05, None),
    ] {
        let (hs, ks) = (h.to_string(), k.to_string());
        let es = offset.map(|e: f64| e.to_string());
        let mut args = vec!["slider-crank", "--stroke", &hs, "-K", &ks];
        if let Some(e) = &es {
            args.extend(["--offset", e.as_str()]);
        }
        let (_, file) = synth("slider-crank", &args);
        let what = args.join(" ");
        let (k_found, stroke) = measured_k_and_stroke(&file.path(), "x(B) [m]", false);
        assert!((k_found - k).abs() < 1e-7, "{what}: K = {k_found}");
        assert!(
            (stroke - h).abs() < 1e-10 * h.max(1.0),
            "{what}: H = {stroke}"
        );
        let (k_check, h_check, _) = checked(&file.path());
        assert!((k_check - k).abs() < 1e-9 && (h_check - h).abs() < 1e-10);
        if let Some(e) = offset {
            let (header, rows) = analyse(&file.path(), &["--positions", "12"]);
            let y = column(&header, "y(B) [m]");
            assert!(rows.iter().all(|r| (r[y] - e).abs() < 1e-12), "{what}");
        }
    }
}

#[test]
fn shapers_meet_stroke_k_and_centre_distance() {
    for (h, k, d) in [(0.3, 1.6, 0.25), (0.5, 1.3, 0.4)] {
        let (hs, ks, ds) = (h.to_string(), k.to_string(), d.to_string());
        let args = [
            "shaper",
            "--stroke",
            &hs,
            "-K",
            &ks,
            "--centre-distance",
            &ds,
        ];
        let (report, file) = synth("shaper", &args);
        let what = args.join(" ");
        let (k_found, stroke) = measured_k_and_stroke(&file.path(), "x(F) [m]", false);
        assert!((k_found - k).abs() < 1e-7, "{what}: K = {k_found}");
        assert!((stroke - h).abs() < 1e-10, "{what}: H = {stroke}");
        let (header, rows) = analyse(&file.path(), &["--positions", "12"]);
        assert!((distance(&header, &rows, "O1", "O3") - d).abs() < 1e-12);
        // γ_min of the ram = 90° − θ/2, θ = 180°(K − 1)/(K + 1): as the report says.
        let gamma = 90.0 - 90.0 * (k - 1.0) / (k + 1.0);
        assert!(
            report.stdout.contains(&format!("{gamma:.4}°")),
            "{}",
            report.stdout
        );
    }
}

#[test]
fn a_crank_rocker_through_positions_puts_the_rocker_there() {
    let three = ["40,101.4", "100,112.8", "160,131.8"];
    for pairs in [&three[..], &three[1..], &["10,95", "200,135"][..]] {
        let mut args = vec![
            "through",
            "--frame",
            "0.4",
            "--min-transmission",
            "0",
            "--at",
        ];
        args.extend_from_slice(pairs);
        let (report, file) = synth("through", &args);
        let (phis, psis): (Vec<&str>, Vec<f64>) = pairs
            .iter()
            .map(|p| {
                let (a, b) = p.split_once(',').unwrap();
                (a, b.parse::<f64>().unwrap().to_radians())
            })
            .unzip();
        let mut at = vec!["--at"];
        at.extend(phis);
        let (header, rows) = analyse(&file.path(), &at);
        let psi = column(&header, "phi(rocker) [rad]");
        for (row, want) in rows.iter().zip(&psis) {
            let miss = angle_difference(row[psi], *want).abs();
            assert!(miss < 1e-10, "{pairs:?}: ψ misses by {miss} rad");
        }
        assert!(report.stdout.contains("crank-rocker"), "{}", report.stdout);
        assert!((distance(&header, &rows, "O1", "O3") - 0.4).abs() < 1e-12);
    }
}

#[test]
fn a_function_generator_is_exact_at_its_chebyshev_points() {
    let (x0, x1, phi0, phi1, psi0, psi1) = (1.0f64, 2.0f64, -30.0, 30.0, 0.0, 90.0);
    let (_, file) = synth("function", &SynthFunction::default().args(&[]));
    // The precision points x_j = (x0 + x1)/2 − (x1 − x0)/2·cos((2j − 1)π/6), the crank at
    // the linear image of x_j, the rocker at that of log10 x_j; and x0, x1 between.
    let xs: Vec<f64> = (1..=3)
        .map(|j| 0.5 * (x0 + x1) - 0.5 * (x1 - x0) * (f64::from(2 * j - 1) * PI / 6.0).cos())
        .chain([x0, 1.3, x1])
        .collect();
    let crank = |x: f64| phi0 + (phi1 - phi0) * (x - x0) / (x1 - x0);
    let rocker = |x: f64| {
        (psi0 + (psi1 - psi0) * (x.log10() - x0.log10()) / (x1.log10() - x0.log10())).to_radians()
    };
    let at: Vec<String> = xs.iter().map(|&x| format!("{:.12}", crank(x))).collect();
    let mut args = vec!["--at"];
    args.extend(at.iter().map(String::as_str));
    let (header, rows) = analyse(&file.path(), &args);
    let psi = column(&header, "phi(rocker) [rad]");
    let scale = (psi1 - psi0).to_radians();
    for (k, (row, &x)) in rows.iter().zip(&xs).enumerate() {
        let miss = angle_difference(row[psi], rocker(x)).abs();
        if k < 3 {
            assert!(miss < 1e-9, "at the precision point x = {x}: {miss} rad");
        } else {
            // Between them the structural error: small, and not zero.
            assert!(miss > 1e-6 && miss < 0.02 * scale, "x = {x}: {miss} rad");
        }
    }
}

#[test]
fn a_path_generator_passes_its_coupler_point_through_the_targets() {
    let points = Broken::with_extension("points", "csv", &common::coupler_curve_csv(12));
    let (report, file) = synth(
        "path",
        &[
            "path",
            &points.path(),
            "--seed",
            "7",
            "--budget",
            "20000",
            "--time",
            "100000",
        ],
    );
    // No progress line when stderr is not a terminal.
    assert!(
        report.stderr.is_empty(),
        "quiet when piped: {:?}",
        report.stderr
    );
    // The report's rows: "φ = …°", the targets, the reached points and the miss.
    let angles = report_angles(&report.stdout);
    assert_eq!(angles.len(), 12, "{}", report.stdout);
    let mut args = vec!["--at"];
    args.extend(angles.iter().map(String::as_str));
    let (header, rows) = analyse(&file.path(), &args);
    let (x, y) = (column(&header, "x(P) [m]"), column(&header, "y(P) [m]"));
    for (k, row) in rows.iter().enumerate() {
        let want = common::coupler_point(TAU * k as f64 / 12.0);
        let miss = (row[x] - want[0]).hypot(row[y] - want[1]);
        // The angles are printed to 1e-6°: 2e-9 m on a 0.2 m crank-and-coupler.
        assert!(miss < 1e-7, "target {k}: the engine's P misses by {miss} m");
    }
}

#[test]
fn prescribed_timing_is_kept_and_json_points_read() {
    // Six points of the coupler curve 20° of crank apart: the design's crank angles at them
    // differ by the same 20°, whatever the search found.
    let pts: Vec<String> = (0..6)
        .map(|k| {
            let p = common::coupler_point(f64::from(k) * 20f64.to_radians());
            format!("[{:.12}, {:.12}]", p[0], p[1])
        })
        .collect();
    let json = format!(
        "{{\"points\": [{}], \"crank\": [0, 20, 40, 60, 80, 100]}}",
        pts.join(", ")
    );
    // (A temporary file's name ends in .json: read as JSON.)
    let points = Broken::new("points-timed", &json);
    let (report, _file) = synth(
        "timed",
        &[
            "path",
            &points.path(),
            "--seed",
            "3",
            "--budget",
            "20000",
            "--time",
            "100000",
        ],
    );
    let angles: Vec<f64> = report
        .stdout
        .lines()
        .filter_map(|l| l.trim().strip_prefix("φ = "))
        .map(|l| l.split('°').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(angles.len(), 6, "{}", report.stdout);
    for (k, a) in angles.iter().enumerate() {
        let turned = (a - angles[0]).rem_euclid(360.0);
        assert!(
            (turned - 20.0 * k as f64).abs() < 2e-6,
            "point {k}: the crank turned {turned}°"
        );
    }
}

#[test]
fn a_six_bar_passes_its_point_p_through_the_targets_at_their_crank_angles() {
    // The eight points of the library's example six-bar, 0.3 rad of crank apart.
    let req = tmm::synthesis::PathRequirement::six_bar_example().unwrap();
    let tmm::synthesis::Timing::Prescribed(delta) = &req.timing else {
        panic!("the example is timed")
    };
    let csv = common::six_bar_example_csv();
    let points = Broken::with_extension("six-bar-points", "csv", &csv);
    let (report, file) = synth(
        "six-bar",
        &[
            "six-bar",
            &points.path(),
            "--min-transmission",
            "17",
            "--designs",
            "1",
            "--time",
            "100000",
        ],
    );
    assert!(
        report.stdout.contains("Stephenson III"),
        "{}",
        report.stdout
    );
    let angles = report_angles(&report.stdout);
    assert_eq!(angles.len(), 8, "{}", report.stdout);
    // The timing kept: the crank turns 0.3 rad from each point to the next.
    let first: f64 = angles[0].parse().unwrap();
    for (k, a) in angles.iter().enumerate() {
        let turned = (a.parse::<f64>().unwrap() - first).rem_euclid(360.0);
        assert!(
            (turned - delta[k].to_degrees()).abs() < 2e-6,
            "point {k}: the crank turned {turned}°"
        );
    }
    // The description written, analysed by the engine at those angles: P on the targets.
    let mut args = vec!["--at"];
    args.extend(angles.iter().map(String::as_str));
    let (header, rows) = analyse(&file.path(), &args);
    let (x, y) = (column(&header, "x(P) [m]"), column(&header, "y(P) [m]"));
    assert_eq!(rows.len(), 8);
    for (k, (row, want)) in rows.iter().zip(&req.points).enumerate() {
        let miss = (row[x] - want[0]).hypot(row[y] - want[1]);
        // The angles are printed to 1e-6°: P moves less than 1 m/rad, so 2e-8 m.
        assert!(miss < 1e-7, "target {k}: the engine's P misses by {miss} m");
    }
    // Without crank angles there is no six-bar synthesis: one line naming the timing.
    let untimed: String = req
        .points
        .iter()
        .map(|p| format!("{},{}\n", p[0], p[1]))
        .collect();
    let untimed = Broken::with_extension("six-bar-untimed", "csv", &untimed);
    assert_refused(&["six-bar", &untimed.path()], &["timing", "crank angles"]);
    // Seven timed points are fewer than the unknowns: named, with the count needed.
    let seven: String = csv.lines().take(8).map(|l| format!("{l}\n")).collect();
    let seven = Broken::with_extension("six-bar-seven", "csv", &seven);
    assert_refused(&["six-bar", &seven.path()], &["points", "at least 8"]);
}

/// A failure of `tmm synth`: exit code 1, one line on stderr that names `words`, and no
/// description on stdout or in the file.
fn assert_refused(args: &[&str], words: &[&str]) {
    let out = Broken::new("refused", "");
    std::fs::remove_file(&out.0).ok();
    let path = out.path();
    let mut all = vec!["synth"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", &path]);
    let r = tmm(&all);
    let what = all.join(" ");
    assert_eq!(r.code, 1, "{what}: exit code; stderr {}", r.stderr);
    assert_eq!(
        r.stderr.lines().count(),
        1,
        "{what}: one line: {:?}",
        r.stderr
    );
    assert!(r.stderr.starts_with("tmm: "), "{what}: {}", r.stderr);
    for w in words {
        assert!(r.stderr.contains(w), "{what}: names {w:?}: {}", r.stderr);
    }
    for debug in ["panicked", "{", "Some(", "NaN)"] {
        assert!(
            !r.stderr.contains(debug),
            "{what}: no {debug:?}: {}",
            r.stderr
        );
    }
    assert!(r.stdout.is_empty(), "{what}: nothing on stdout");
    assert!(!out.0.exists(), "{what}: no file written");
}

#[test]
fn bad_requirements_are_one_line_naming_the_parameter() {
    let cr = |k: &'static str, swing: &'static str, rocker: &'static str| {
        vec![
            "crank-rocker",
            "-K",
            k,
            "--swing",
            swing,
            "--rocker",
            rocker,
        ]
    };
    assert_refused(
        &cr("0.9", "45", "0.3"),
        &["K = 0.9", "(1, ∞)", "-K/--time-ratio"],
    );
    assert_refused(&cr("1", "45", "0.3"), &["K = 1 ", "-K/--time-ratio"]);
    assert_refused(&cr("nan", "45", "0.3"), &["K must be finite"]);
    assert_refused(&cr("1.2", "200", "0.3"), &["swing", "--swing", "200.0000°"]);
    assert_refused(&cr("1.2", "0", "0.3"), &["swing", "--swing"]);
    assert_refused(
        &cr("1.2", "45", "-0.3"),
        &["rocker must be positive", "--rocker"],
    );
    // K and ψ no crank-rocker reaches with γ_min ≥ 40°: by how much, in degrees too.
    assert_refused(
        &cr("2.5", "100", "0.3"),
        &[
            "minimum transmission angle",
            "cannot be met",
            "misses by",
            "--min-transmission",
            "40.0000° asked for",
        ],
    );
    let mut far = cr("1.25", "45", "0.3");
    far.extend(["--frame", "5"]);
    assert_refused(
        &far,
        &["frame length O1O3 (m) = 5", "nearest reachable", "--frame"],
    );
    let mut steep = cr("1.25", "45", "0.3");
    steep.extend(["--min-transmission", "100"]);
    assert_refused(&steep, &["min_transmission_angle", "--min-transmission"]);
    assert_refused(
        &["slider-crank", "--stroke", "0.2", "-K", "1.4"],
        &["minimum transmission angle", "--min-transmission"],
    );
    assert_refused(
        &["slider-crank", "--stroke", "0", "-K", "1.2"],
        &["stroke must be positive", "--stroke"],
    );
    assert_refused(
        &[
            "shaper",
            "--stroke",
            "0.3",
            "-K",
            "1.6",
            "--centre-distance",
            "-0.25",
        ],
        &["centre_distance must be positive", "--centre-distance"],
    );
    assert_refused(
        &[
            "shaper",
            "--stroke",
            "0.3",
            "-K",
            "inf",
            "--centre-distance",
            "0.25",
        ],
        &["K must be finite"],
    );
    // A centre distance so large that the crank's circle reaches the ram's block.
    assert_refused(
        &[
            "shaper",
            "--stroke",
            "0.3",
            "-K",
            "100",
            "--centre-distance",
            "0.25",
            "--min-transmission",
            "0",
        ],
        &[
            "centre distance O1O3 (m) = 0.25",
            "nearest reachable",
            "--centre-distance",
        ],
    );
    assert_refused(
        &["through", "--frame", "0.4", "--at", "40,101.4"],
        &["positions = 1", "[2, 3]", "--at"],
    );
    assert_refused(
        &[
            "through", "--frame", "0.4", "--at", "40,101", "100,112", "160,131", "200,140",
        ],
        &["positions = 4", "--at"],
    );
    assert_refused(
        &["through", "--frame", "0", "--at", "40,101.4", "100,112.8"],
        &["frame must be positive", "--frame"],
    );
    let function = |extra: &[&'static str]| SynthFunction::default().args(extra);
    assert_refused(
        &function(&["--least-squares", "2"]),
        &["N = 2", "--least-squares"],
    );
    let with_x = |x| {
        SynthFunction {
            x,
            ..Default::default()
        }
        .args(&[])
    };
    assert_refused(&with_x("2,2"), &["x0 = x1"]);
    assert_refused(
        &with_x("-2,-1"),
        &["f(x0) must be finite", "--function and --x"],
    );
}

#[test]
fn a_bad_points_file_is_one_line_naming_the_file_and_the_line() {
    let few = Broken::with_extension("few", "csv", &common::coupler_curve_csv(5));
    assert_refused(
        &["path", &few.path()],
        &[&few.path(), "points = 5", "at least 9"],
    );
    let text = common::coupler_curve_csv(12).replace("\n0.1", "\n0.1x");
    let typo = Broken::with_extension("typo", "csv", &text);
    assert_refused(
        &["path", &typo.path()],
        &[&typo.path(), "line ", "is not a number"],
    );
    let ragged = Broken::with_extension("ragged", "csv", "1,2\n3,4,5\n");
    assert_refused(
        &["path", &ragged.path()],
        &[&ragged.path(), "line 2", "3 values"],
    );
    assert_refused(
        &["path", "no/such/points.csv"],
        &["no/such/points.csv", "cannot read"],
    );
    // Crank angles that do not match the points: a count, named, not an angle in degrees.
    let mismatched = Broken::new(
        "mismatched",
        r#"{"points": [[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.2]], "crank": [0, 10]}"#,
    );
    assert_refused(
        &["path", &mismatched.path()],
        &[
            "one crank angle per point",
            "must be 5, got 2",
            "\"crank\" in JSON",
        ],
    );
    let r = tmm(&["synth", "path", &mismatched.path()]);
    assert!(!r.stderr.contains('°'), "{}", r.stderr);
    // More points than the search takes (its polish is dense in their number): the limit.
    let many = Broken::with_extension("many", "csv", &common::coupler_curve_csv(501));
    assert_refused(
        &["path", &many.path()],
        &[&many.path(), "501 target points", "500", "one point in 2"],
    );
    // A budget below one generation of the search: no design, and the fix.
    let points = Broken::with_extension("points-budget", "csv", &common::coupler_curve_csv(12));
    assert_refused(
        &["path", &points.path(), "--budget", "100"],
        &[&points.path(), "evaluations", "raise --budget"],
    );
    assert_refused(
        &["path", &points.path(), "--time", "-1"],
        &["time bound", "--time"],
    );
    let timed = Broken::with_extension(
        "closed-timed",
        "csv",
        "0,0,0\n1,0,10\n1,1,20\n0,1,30\n0.5,0.5,40\n",
    );
    assert_refused(
        &["path", &timed.path(), "--closed"],
        &[&timed.path(), "--closed"],
    );
}

#[test]
fn without_o_the_description_goes_to_stdout_and_the_report_to_stderr() {
    let r = tmm(&[
        "synth",
        "shaper",
        "--stroke",
        "0.3",
        "-K",
        "1.6",
        "--centre-distance",
        "0.25",
    ]);
    assert_success(&r, "synth shaper > file");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("stdout is the JSON");
    assert_eq!(v["output"]["slide"], "G", "{}", r.stdout);
    assert!(r.stderr.contains("time ratio K"), "{}", r.stderr);
    assert!(r.stderr.contains("checked by the engine"), "{}", r.stderr);
    // What a shell's `>` saved is a description every command reads.
    let saved = Broken::new("saved-shaper", &r.stdout);
    let (k, stroke, _) = checked(&saved.path());
    assert!((k - 1.6).abs() < 1e-9 && (stroke - 0.3).abs() < 1e-10);
}

/// The crank angles of a path report's rows ("φ = …°"), as printed.
fn report_angles(stdout: &str) -> Vec<String> {
    stdout
        .lines()
        .filter_map(|l| l.trim().strip_prefix("φ = "))
        .map(|l| l.split('°').next().unwrap().to_owned())
        .collect()
}
