//! Linkages with two inputs (the bundled five-bar robot) and rocking inputs (the
//! Peaucellier–Lipkin inversor, Chebyshev's straight line, a four-bar whose crank cannot turn)
//! through `tmm`: checked against independent solves — the five-bar's end point against its
//! forward kinematics in closed form, in the table and in the scheme's pixels; the mass
//! matrix and a rocking crank's J_red against the links' kinetic energy from central
//! differences of the table's positions; a rocking crank's reduced quantities against the
//! balancing moment of the kinetostatics; the rocking range against `tmm check`'s lock angles.

mod common;

use common::{
    assert_one_line_failure, assert_success, assert_svg, parse_csv, rocking_four_bar, root, tmm,
};

type P = [f64; 2];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm(a: P) -> f64 {
    a[0].hypot(a[1])
}

/// A number as the program reads it back bit for bit.
fn arg(v: f64) -> String {
    format!("{v}")
}

fn json(args: &[&str]) -> serde_json::Value {
    let r = tmm(args);
    assert_success(&r, &args.join(" "));
    serde_json::from_str(&r.stdout).unwrap_or_else(|e| panic!("{args:?}: JSON reads back: {e}"))
}

/// The joints of a bundled file by name, m.
fn joints(file: &str) -> Vec<(String, P)> {
    let text = std::fs::read_to_string(root().join(file)).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| {
            let at = &j["at"];
            (
                j["name"].as_str().unwrap().to_owned(),
                [at[0].as_f64().unwrap(), at[1].as_f64().unwrap()],
            )
        })
        .collect()
}

fn joint(joints: &[(String, P)], name: &str) -> P {
    joints.iter().find(|(n, _)| n == name).expect(name).1
}

/// The five-bar's end point B by forward kinematics: A and C on their cranks, B on both
/// couplers' circles, on the side of A→C where it is in the reference pose.
fn five_bar_b(phi1: f64, phi2: f64) -> P {
    let j = joints("linkages/five-bar-robot.json");
    let (o, a0, b0, c0, d) = (
        joint(&j, "O"),
        joint(&j, "A"),
        joint(&j, "B"),
        joint(&j, "C"),
        joint(&j, "D"),
    );
    let (l1, l2, l3, l4) = (
        norm(sub(a0, o)),
        norm(sub(b0, a0)),
        norm(sub(b0, c0)),
        norm(sub(c0, d)),
    );
    let cross = |u: P, v: P| u[0] * v[1] - u[1] * v[0];
    let side = cross(sub(c0, a0), sub(b0, a0)).signum();
    let a = [o[0] + l1 * phi1.cos(), o[1] + l1 * phi1.sin()];
    let c = [d[0] + l4 * phi2.cos(), d[1] + l4 * phi2.sin()];
    let ac = sub(c, a);
    let e = norm(ac);
    let along = (l2 * l2 - l3 * l3 + e * e) / (2.0 * e);
    let h = (l2 * l2 - along * along).sqrt();
    let (ux, uy) = (ac[0] / e, ac[1] / e);
    [
        a[0] + along * ux - side * h * uy,
        a[1] + along * uy + side * h * ux,
    ]
}

/// The column of the CSV header whose name is `name` (unit aside).
fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h.split(" [").next() == Some(name))
        .unwrap_or_else(|| panic!("a column {name} in {header:?}"))
}

/// `tmm analyse FILE --at …` as CSV.
fn analyse_at(file: &str, at: &[f64], extra: &[&str]) -> (Vec<String>, Vec<Vec<f64>>) {
    let values: Vec<String> = at.iter().map(|&v| arg(v)).collect();
    let mut args = vec!["analyse", file, "--format", "csv", "--at"];
    args.extend(values.iter().map(String::as_str));
    args.extend_from_slice(extra);
    let r = tmm(&args);
    assert_success(&r, &args.join(" "));
    parse_csv(&r.stdout, file)
}

#[test]
fn the_five_bars_end_point_is_its_forward_kinematics() {
    let pairs = [[120.0, 60.0], [110.0, 70.0], [125.0, 55.0], [100.0, 50.0]];
    let flat: Vec<f64> = pairs.iter().flatten().copied().collect();
    let (header, rows) = analyse_at("five-bar-robot", &flat, &[]);
    assert_eq!(rows.len(), 4);
    let (x, y) = (col(&header, "x(B)"), col(&header, "y(B)"));
    let mut worst: f64 = 0.0;
    for (p, row) in pairs.iter().zip(&rows) {
        let b = five_bar_b(p[0].to_radians(), p[1].to_radians());
        worst = worst.max(norm(sub([row[x], row[y]], b)));
    }
    eprintln!("B in the table vs closed form: {worst:e} m");
    assert!(worst < 1e-12, "B in the table vs closed form: {worst} m");

    // In the scheme at (110°, 70°): the hinges are drawn at their points to one scale, y up;
    // the frame pivots O and D fix the map to pixels.
    let r = tmm(&["draw", "five-bar-robot", "--scheme", "110", "70"]);
    assert_success(&r, "scheme at a pair");
    assert_svg(&r.stdout, "five-bar scheme");
    let number = |tag: &str, key: &str| -> f64 {
        let k = tag.find(&format!(" {key}=\"")).expect(key) + key.len() + 3;
        tag[k..k + tag[k..].find('"').unwrap()].parse().unwrap()
    };
    let hinges: Vec<P> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("<circle") && l.contains(" r=\"5\""))
        .map(|l| [number(l, "cx"), number(l, "cy")])
        .collect();
    let lines: Vec<&str> = r.stdout.lines().collect();
    // A label is drawn beside its hinge: the hinge nearest the label's anchor.
    let pixel = |name: &str| -> P {
        let k = lines
            .iter()
            .position(|l| l.trim() == name)
            .unwrap_or_else(|| panic!("a label {name}"));
        let anchor = [number(lines[k - 1], "x"), number(lines[k - 1], "y")];
        *hinges
            .iter()
            .min_by(|a, b| norm(sub(**a, anchor)).total_cmp(&norm(sub(**b, anchor))))
            .unwrap()
    };
    let j = joints("linkages/five-bar-robot.json");
    let (po, pd) = (pixel("O"), pixel("D"));
    let scale = norm(sub(pd, po)) / norm(sub(joint(&j, "D"), joint(&j, "O")));
    assert!(
        (pd[1] - po[1]).abs() < 0.02,
        "the frame is level: {po:?} {pd:?}"
    );
    let b = five_bar_b(110f64.to_radians(), 70f64.to_radians());
    let expected = [po[0] + scale * b[0], po[1] - scale * b[1]];
    let off = norm(sub(pixel("B"), expected));
    // Pixels are written to 0.01: a 0.1° error of an input would move B by about 0.4 px.
    eprintln!("B in the scheme vs closed form: {off} px at {scale} px/m");
    assert!(off < 0.05, "B drawn {off} px from its forward kinematics");
}

#[test]
fn a_linkage_with_two_inputs_is_drawn_along_a_path_and_its_workspace() {
    for args in [
        &["--plan"][..],
        &["--animate"],
        &["--plan", "--along", "120", "60", "90", "60", "90", "90"],
        &["--animate", "--along", "120", "60", "90", "60", "90", "90"],
        &["--forces", "125", "55"],
        &["--diagram", "balance"],
        &[
            "--diagram",
            "kinematics",
            "--along",
            "120",
            "60",
            "90",
            "90",
        ],
        &["--diagram", "reactions", "--along", "120", "60", "90", "90"],
        &["--diagram", "hodograph"],
    ] {
        let mut all = vec!["draw", "five-bar-robot"];
        all.extend_from_slice(args);
        let r = tmm(&all);
        assert_success(&r, &all.join(" "));
        assert_svg(&r.stdout, &all.join(" "));
    }
    // There along the path and back again: 180 frames and 179 back.
    let r = tmm(&[
        "draw",
        "five-bar-robot",
        "--animate",
        "--along",
        "120",
        "60",
        "90",
        "90",
    ]);
    assert!(r.stdout.contains("359 frames"), "{}", &r.stdout[..300]);
    let r = tmm(&["draw", "five-bar-robot", "--workspace", "B"]);
    assert_success(&r, "workspace of B");
    assert!(
        r.stderr.is_empty(),
        "no progress when piped: {:?}",
        r.stderr
    );
    assert!(r.stdout.contains("workspace of B"));
    assert_svg(&r.stdout, "workspace of B");

    for (args, words) in [
        (&["--workspace", "nowhere"][..], "\"nowhere\""),
        (&["--scheme", "110"], "a pair φ1 φ2"),
        (&["--forces", "110", "70", "80"][..], ""),
        (
            &["--plan", "--along", "120", "60", "90", "60", "90"],
            "pairs",
        ),
        (&["--along", "120", "60", "90", "60"], "none was asked for"),
        (
            &["--plan", "--along", "120", "60", "120", "60"],
            "has length 0",
        ),
        (&["--diagram", "transfer"], "this linkage has two"),
    ] {
        let mut all = vec!["draw", "five-bar-robot"];
        all.extend_from_slice(args);
        let r = tmm(&all);
        if words.is_empty() {
            assert_eq!(r.code, 2, "{all:?}: a usage error: {}", r.stderr);
            continue;
        }
        assert_one_line_failure(&r, "five-bar-robot");
        assert!(r.stderr.contains(words), "{all:?}: {}", r.stderr);
    }
    for (args, words) in [
        (&["--workspace", "B"][..], "two inputs move independently"),
        (
            &["--plan", "--along", "10", "20", "30", "40"],
            "this linkage has one",
        ),
        (&["--scheme", "10", "20"], "one value φ"),
    ] {
        let mut all = vec!["draw", "four-bar"];
        all.extend_from_slice(args);
        let r = tmm(&all);
        assert_one_line_failure(&r, "four-bar");
        assert!(r.stderr.contains(words), "{all:?}: {}", r.stderr);
    }
}

/// A link's mass, moment of inertia about its centre, centre (m, reference pose) and the
/// joint it is carried by.
struct Body {
    link: &'static str,
    joint: &'static str,
    m: f64,
    j: f64,
    centre: P,
}

/// The transfer functions of each body at the inputs `q` (rad): u = ∂S/∂q_k of its centre
/// and w = ∂φ/∂q_k of its link, for each input k, by central differences (step h) of the
/// positions in the table, each centre carried rigidly with its joint and its link's angle
/// from the row of the reference inputs.
fn transfer(file: &str, bodies: &[Body], reference: &[f64], q: &[f64]) -> Vec<Vec<(P, f64)>> {
    let n = q.len();
    let h = 1e-5;
    let mut at = reference.to_vec();
    for k in 0..n {
        for s in [1.0, -1.0] {
            let mut p = q.to_vec();
            p[k] += s * h;
            at.extend(p);
        }
    }
    let degrees: Vec<f64> = at.iter().map(|v| v.to_degrees()).collect();
    let (header, rows) = analyse_at(file, &degrees, &["--speed", "1"]);
    assert_eq!(rows.len(), 1 + 2 * n, "{file}: every position solves");
    let centre = |row: &[f64], b: &Body| -> (P, f64) {
        let (x, y) = (
            col(&header, &format!("x({})", b.joint)),
            col(&header, &format!("y({})", b.joint)),
        );
        let phi = col(&header, &format!("phi({})", b.link));
        let r0 = &rows[0];
        let turn = row[phi] - r0[phi];
        let arm = sub(b.centre, [r0[x], r0[y]]);
        let (c, s) = (turn.cos(), turn.sin());
        (
            [
                row[x] + c * arm[0] - s * arm[1],
                row[y] + s * arm[0] + c * arm[1],
            ],
            row[phi],
        )
    };
    bodies
        .iter()
        .map(|b| {
            (0..n)
                .map(|k| {
                    let (sp, pp) = centre(&rows[1 + 2 * k], b);
                    let (sm, pm) = centre(&rows[2 + 2 * k], b);
                    let d = sub(sp, sm);
                    ([d[0] / (2.0 * h), d[1] / (2.0 * h)], (pp - pm) / (2.0 * h))
                })
                .collect()
        })
        .collect()
}

/// The links' kinetic energy matrix Σ m·u_i·u_k + J·w_i·w_k from their transfer functions.
fn kinetic_matrix(bodies: &[Body], t: &[Vec<(P, f64)>]) -> Vec<Vec<f64>> {
    let n = t[0].len();
    let mut a = vec![vec![0.0; n]; n];
    for (b, tb) in bodies.iter().zip(t) {
        for i in 0..n {
            for k in 0..n {
                let ((ui, wi), (uk, wk)) = (tb[i], tb[k]);
                a[i][k] += b.m * (ui[0] * uk[0] + ui[1] * uk[1]) + b.j * wi * wk;
            }
        }
    }
    a
}

#[test]
fn the_mass_matrix_of_two_inputs_is_the_links_kinetic_energy() {
    let v = json(&[
        "dynamics",
        "five-bar-robot",
        "--grid",
        "3",
        "--span",
        "10",
        "--format",
        "json",
    ]);
    assert_eq!(
        (v["grid"].as_u64(), v["skipped"].as_u64()),
        (Some(3), Some(0))
    );
    let m = &v["mass_matrix"];
    let column = |name: &str| -> Vec<f64> {
        m[name]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (q1, q2) = (column("q1"), column("q2"));
    let (a11, a12, a22) = (column("A11"), column("A12"), column("A22"));
    let (f1, f2) = (column("Q1"), column("Q2"));
    assert_eq!(q1.len(), 9);
    let j = joints("linkages/five-bar-robot.json");
    let mid = |p: &str, q: &str| {
        let (a, b) = (joint(&j, p), joint(&j, q));
        [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
    };
    let bodies = [
        Body {
            link: "crank 1",
            joint: "O",
            m: 0.0,
            j: 0.02,
            centre: joint(&j, "O"),
        },
        Body {
            link: "coupler 2",
            joint: "A",
            m: 0.6,
            j: 0.009375,
            centre: mid("A", "B"),
        },
        Body {
            link: "coupler 3",
            joint: "C",
            m: 0.6,
            j: 0.009375,
            centre: mid("C", "B"),
        },
        Body {
            link: "crank 4",
            joint: "D",
            m: 0.0,
            j: 0.02,
            centre: joint(&j, "D"),
        },
    ];
    let reference = [120f64.to_radians(), 60f64.to_radians()];
    let (mut worst, mut worst_q): (f64, f64) = (0.0, 0.0);
    for node in [0, 4, 8, 2] {
        let q = [q1[node], q2[node]];
        let t = transfer("five-bar-robot", &bodies, &reference, &q);
        let a = kinetic_matrix(&bodies, &t);
        let scale = a[0][0].max(a[1][1]);
        for (got, want) in [
            (a11[node], a[0][0]),
            (a12[node], a[0][1]),
            (a22[node], a[1][1]),
        ] {
            worst = worst.max((got - want).abs() / scale);
        }
        assert!(
            a11[node] * a22[node] - a12[node] * a12[node] > 0.0,
            "A positive definite"
        );
        // The one load is a couple of −0.3 N·m on coupler 3: Q_k = −0.3·∂φ3/∂q_k.
        let w3 = [t[2][0].1, t[2][1].1];
        for (got, k) in [(f1[node], 0), (f2[node], 1)] {
            worst_q = worst_q.max((got + 0.3 * w3[k]).abs() / 0.3);
        }
    }
    eprintln!("A vs kinetic energy {worst:e} of |A|, Q vs virtual work {worst_q:e} N·m/N·m");
    assert!(worst_q < 1e-6, "Q vs the couple's virtual work: {worst_q}");
    assert!(
        worst < 1e-6,
        "A vs the links' kinetic energy: {worst} of A's size"
    );

    // The CSV: every column with its unit, the same numbers.
    let out = std::env::temp_dir().join(format!("tmm-cli-test-{}-mass.csv", std::process::id()));
    let out_s = out.to_string_lossy().into_owned();
    let r = tmm(&[
        "dynamics",
        "five-bar-robot",
        "--grid",
        "3",
        "--span",
        "10",
        "--csv",
        &out_s,
    ]);
    assert_success(&r, "dynamics --csv of two inputs");
    let text = std::fs::read_to_string(&out).unwrap();
    std::fs::remove_file(&out).ok();
    let (header, rows) = parse_csv(&text, "mass matrix");
    assert_eq!(
        header,
        [
            "q1 [rad]",
            "q2 [rad]",
            "A11 [kg·m^2]",
            "A12 [kg·m^2]",
            "A22 [kg·m^2]",
            "Q1 [N·m]",
            "Q2 [N·m]"
        ]
    );
    assert_eq!(rows.len(), 9);
    assert_eq!(rows[4][2], a11[4]);

    for (args, words) in [
        (&["--run-up"][..], "no cycle of its own"),
        (&["--flywheel", "0.05"], "no cycle of its own"),
        (&["--span", "-5"], "span"),
        (&["--span", "200"], "at most 180°"),
        (&["--span", "nan"], "span"),
        (
            &["--speed", "inf"],
            "--speed is the speed of a linkage with one input",
        ),
        // RK4's stable step under this damping would need 10⁸ steps: refused before it runs.
        (&["--run", "1", "--motor", "1,1e6"], "make the run stiff"),
        (&["--run", "1", "--motor2", "1,1e308"], "make the run stiff"),
    ] {
        let mut all = vec!["dynamics", "five-bar-robot"];
        all.extend_from_slice(args);
        let r = tmm(&all);
        assert_one_line_failure(&r, "five-bar-robot");
        assert!(r.stderr.contains(words), "{all:?}: {}", r.stderr);
    }
    // A speed that is not a number is named as such, for one input and for two.
    for file in ["four-bar", "five-bar-robot"] {
        for speed in ["NaN", "inf", "1e308"] {
            let r = tmm(&["analyse", file, "--speed", speed, "--positions", "4"]);
            assert_one_line_failure(&r, file);
            assert!(
                r.stderr.contains("speed must be finite"),
                "{file} {speed}: {}",
                r.stderr
            );
        }
    }
}

/// A JSON array of numbers.
fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn a_linkage_with_two_inputs_runs_from_rest_under_two_motors() {
    let v = json(&[
        "dynamics",
        "five-bar-robot",
        "--grid",
        "3",
        "--run",
        "0.5",
        "--motor",
        "0.2,0.05",
        "--motor2",
        "-0.1,0.05",
        "--format",
        "json",
    ]);
    let run = &v["run"];
    let (t, kinetic) = (numbers(&run["t"]), numbers(&run["kinetic"]));
    let (qd1, qd2) = (numbers(&run["qd1"]), numbers(&run["qd2"]));
    assert_eq!(*t.last().unwrap(), 0.5);
    // The energy balance: the kinetic energy gained from rest is the work of the loads and
    // motors (trapezoids over the steps: an error of order h²).
    let gained = *kinetic.last().unwrap();
    let work = run["work"].as_f64().unwrap();
    eprintln!(
        "five-bar run: T = {gained} J, W = {work} J, {:e} relative",
        (gained - work) / gained
    );
    assert!(gained > 1e-3 && (gained - work).abs() < 1e-6 * gained);
    // The first step from rest: q̈(0) = A⁻¹·Q with A and Q of the grid's middle node (the
    // reference pose) and the motors' moments at rest, Q + (0.2, −0.1).
    let m = &v["mass_matrix"];
    let at = |name: &str| numbers(&m[name])[4];
    let (a11, a12, a22) = (at("A11"), at("A12"), at("A22"));
    let (f1, f2) = (at("Q1") + 0.2, at("Q2") - 0.1);
    let det = a11 * a22 - a12 * a12;
    let qdd = [(a22 * f1 - a12 * f2) / det, (a11 * f2 - a12 * f1) / det];
    let started = [qd1[1] / t[1], qd2[1] / t[1]];
    eprintln!("five-bar run: q̈(0) from the first step {started:?}, A⁻¹Q {qdd:?}");
    for k in 0..2 {
        assert!(
            (started[k] - qdd[k]).abs() < 1e-3 * qdd[0].abs().max(qdd[1].abs()),
            "q̈(0): {started:?} vs A⁻¹Q = {qdd:?}"
        );
    }
    for (args, words) in [
        (&["--run", "0"][..], "duration"),
        (&["--run", "nan"], "duration"),
        (&["--run", "1e-300"], "10⁻⁶ s"),
        (&["--run", "1", "--motor2", "1,nan"], "finite"),
    ] {
        let mut all = vec!["dynamics", "five-bar-robot"];
        all.extend_from_slice(args);
        let r = tmm(&all);
        assert_one_line_failure(&r, "five-bar-robot");
        assert!(r.stderr.contains(words), "{all:?}: {}", r.stderr);
    }
    let r = tmm(&["dynamics", "four-bar", "--run", "1"]);
    assert_one_line_failure(&r, "four-bar");
    assert!(r.stderr.contains("--run-up"), "{}", r.stderr);
    // The means of the reduced quantities over a turn need more than a sample or two.
    let r = tmm(&["dynamics", "four-bar", "--positions", "1"]);
    assert_ne!(r.code, 0, "{}", r.stdout);
    assert!(r.stderr.contains("--positions"), "{}", r.stderr);
}

/// `tmm dynamics … --format json`'s reduced column `name`.
fn reduced(v: &serde_json::Value, name: &str) -> Vec<f64> {
    v["reduced"][name]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn a_rocking_crank_has_its_reduced_quantities_between_its_lock_angles() {
    let four_bar = rocking_four_bar();
    let path = four_bar.path();
    for file in [
        "peaucellier-lipkin",
        "chebyshev-straight-line",
        path.as_str(),
    ] {
        let check = json(&["check", file, "--format", "json"]);
        assert_eq!(check["range"]["kind"], "rocking", "{file}");
        let lock = [
            check["range"]["from"].as_f64().unwrap(),
            check["range"]["to"].as_f64().unwrap(),
        ];
        for speed in ["7", "-7"] {
            let v = json(&[
                "dynamics",
                file,
                "--positions",
                "40",
                "--speed",
                speed,
                "--format",
                "json",
            ]);
            let range = [
                v["range"]["from"].as_f64().unwrap(),
                v["range"]["to"].as_f64().unwrap(),
            ];
            assert!(
                (range[0] - lock[0]).abs() <= 1e-12 && (range[1] - lock[1]).abs() <= 1e-12,
                "{file}: the range {range:?} ends at the lock angles {lock:?}"
            );
            let phi = reduced(&v, "phi");
            assert_eq!(phi.len(), 40);
            let h = (lock[1] - lock[0]) / 40.0;
            let (first, last) = if speed == "7" {
                (lock[0] + h / 2.0, lock[1] - h / 2.0)
            } else {
                (lock[1] - h / 2.0, lock[0] + h / 2.0)
            };
            assert!(
                (phi[0] - first).abs() < 1e-12 && (phi[39] - last).abs() < 1e-12,
                "{file} at {speed} rad/s: from {} to {}",
                phi[0],
                phi[39]
            );
            let turned = reduced(&v, "turned");
            assert!(
                turned.windows(2).all(|w| w[1] > w[0]),
                "{file}: turned grows"
            );
        }
        // The course table: from one lock to the other and back, as the mechanism runs.
        for (speed, ends) in [("7", lock), ("-7", [lock[1], lock[0]])] {
            let r = tmm(&["analyse", file, "--speed", speed, "--format", "csv"]);
            assert_success(&r, &format!("analyse {file}"));
            let (header, rows) = parse_csv(&r.stdout, file);
            let q: Vec<f64> = rows.iter().map(|r| r[col(&header, "phi_in")]).collect();
            // At the two locks the driven group is at its dead point: those positions are left
            // out, each with a warning that says why; the other ten are tabulated.
            assert_eq!(q.len(), 10);
            for end in ends {
                let warning = format!(
                    "position at φ = {:.1}° left out",
                    end.to_degrees().rem_euclid(360.0)
                );
                assert!(
                    r.stderr
                        .lines()
                        .any(|l| l.contains(&warning) && l.contains("dead point")),
                    "{file} at {speed} rad/s: the course turns at the locks {ends:?}: {}",
                    r.stderr
                );
            }
            // Out from the first lock and back: the input moves away from it, then returns.
            let s = (ends[1] - ends[0]).signum();
            assert!(q[..5].windows(2).all(|w| (w[1] - w[0]) * s > 0.0), "{q:?}");
            assert!(q[5..].windows(2).all(|w| (w[1] - w[0]) * s < 0.0), "{q:?}");
            assert!(q.iter().all(|&x| x >= lock[0] && x <= lock[1]), "{q:?}");
        }
        let r = tmm(&["dynamics", file, "--run-up"]);
        assert_one_line_failure(&r, file);
        let degrees = format!("{:.4}°", lock[0].to_degrees());
        assert!(
            r.stderr.contains(&degrees),
            "names the lock {degrees}: {}",
            r.stderr
        );
    }

    // The four-bar has masses: J_red against the links' kinetic energy, and the balancing
    // moment of the kinetostatics at ε = 0 against the reduced equation of motion,
    // Mb = ½·J_red′·ω² − M_red.
    let v = json(&[
        "dynamics",
        &path,
        "--positions",
        "12",
        "--speed",
        "3",
        "--format",
        "json",
    ]);
    let (phi, jr, dj, mr) = (
        reduced(&v, "phi"),
        reduced(&v, "J_red"),
        reduced(&v, "dJ_red_dphi"),
        reduced(&v, "M_red"),
    );
    let text = std::fs::read_to_string(&four_bar.0).unwrap();
    let desc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mass = |link: &str| -> (f64, f64, P) {
        let l = desc["links"]
            .as_array()
            .unwrap()
            .iter()
            .find(|l| l["name"] == link)
            .unwrap();
        let m = &l["mass"];
        let c = &m["centre"];
        (
            m["m"].as_f64().unwrap(),
            m["j"].as_f64().unwrap(),
            [c[0].as_f64().unwrap(), c[1].as_f64().unwrap()],
        )
    };
    let body = |link: &'static str, joint: &'static str| {
        let (m, j, centre) = mass(link);
        Body {
            link,
            joint,
            m,
            j,
            centre,
        }
    };
    let bodies = [
        body("crank", "O1"),
        body("coupler", "A"),
        body("rocker", "O3"),
    ];
    let reference = check_reference(&path);
    let (header, rows) = analyse_at(
        &path,
        &phi.iter().map(|p| p.to_degrees()).collect::<Vec<_>>(),
        &["--speed", "3"],
    );
    let mb = col(&header, "Mb");
    let (mut worst_j, mut worst_mb): (f64, f64) = (0.0, 0.0);
    for k in 0..phi.len() {
        let a = kinetic_matrix(&bodies, &transfer(&path, &bodies, &[reference], &[phi[k]]));
        worst_j = worst_j.max((a[0][0] - jr[k]).abs() / jr[k]);
        let chain = rows[k][mb];
        let lagrange = 0.5 * dj[k] * 9.0 - mr[k];
        worst_mb = worst_mb.max((chain - lagrange).abs() / chain.abs().max(1.0));
    }
    eprintln!("rocking four-bar: J_red vs kinetic energy {worst_j:e}, Mb vs Lagrange {worst_mb:e}");
    assert!(
        worst_j < 1e-6,
        "J_red vs the kinetic energy: {worst_j} relative"
    );
    assert!(worst_mb < 1e-9, "Mb vs ½J′ω² − M_red: {worst_mb}");
    // Towards a lock the rocker's transfer function, and with it J_red, grows: each end
    // position's J_red is above its neighbour's.
    let n = jr.len();
    assert!(jr[0] > jr[1] && jr[n - 1] > jr[n - 2], "J_red {jr:?}");
}

#[test]
fn the_peaucellier_tracer_stays_on_its_line_between_the_locks() {
    let r = tmm(&[
        "analyse",
        "peaucellier-lipkin",
        "--positions",
        "200",
        "--format",
        "csv",
    ]);
    assert_success(&r, "analyse the inversor");
    let (header, rows) = parse_csv(&r.stdout, "inversor");
    let (x, y) = (col(&header, "x(P)"), col(&header, "y(P)"));
    // The line x = x_P of the reference pose; the linkage's size about 0.1 m.
    let j = joints("linkages/peaucellier-lipkin.json");
    let line = joint(&j, "P")[0];
    let worst = rows.iter().map(|r| (r[x] - line).abs()).fold(0.0, f64::max);
    let span = rows
        .iter()
        .map(|r| r[y])
        .fold(0.0, |m: f64, v| m.max(v.abs()));
    eprintln!("inversor: P off its line by {worst:e} m over |y| ≤ {span} m");
    assert!(worst < 1e-13, "P off its line by {worst} m");
    assert!(
        span > 0.09,
        "the tracer runs along the line: |y| up to {span} m"
    );
}

/// The first input's angle in the reference pose, from `tmm check`.
fn check_reference(file: &str) -> f64 {
    json(&["check", file, "--format", "json"])["inputs"][0]["reference"]
        .as_f64()
        .unwrap()
}

/// The five-bar's crank 1 lengthened to 0.4 m (A at 120°): with crank 4 held at its
/// reference 60° the couplers reach only |A − C| ≤ l2 + l3, so crank 1 rocks.
fn long_crank_five_bar() -> common::Broken {
    let text = std::fs::read_to_string(root().join("linkages/five-bar-robot.json")).unwrap();
    let a = [
        0.4 * 120f64.to_radians().cos(),
        0.4 * 120f64.to_radians().sin(),
    ];
    let edited = text.replace(
        "[-0.07499999999999997, 0.1299038105676658]",
        &format!("[{}, {}]", arg(a[0]), arg(a[1])),
    );
    assert_ne!(edited, text, "the test's edit applies");
    common::Broken::new("long-crank-five-bar", &edited)
}

/// `tmm check` on two inputs reports what is determined: each input's range with the other
/// held at its reference value, against the closed form of the five-bar (the couplers close
/// while |l2 − l3| ≤ |A − C| ≤ l2 + l3; the locks where |A − C| = l2 + l3, φ1 = θ_C ± arccos
/// of the cosine rule), and that the region of input pairs is 2-D (the workspace).
#[test]
fn check_reports_each_inputs_range_with_the_other_held() {
    let long = long_crank_five_bar();
    let bundled = root().join("linkages/five-bar-robot.json");
    for (file, rocks) in [
        (bundled.to_str().unwrap().to_owned(), false),
        (long.path(), true),
    ] {
        let v = json(&["check", &file, "--format", "json"]);
        let ranges = v["input_ranges"].as_array().expect("input_ranges");
        assert_eq!(ranges.len(), 2, "{file}");
        // Crank 4 holds C where it is; crank 1 sweeps A round O.
        let text = std::fs::read_to_string(&file).unwrap();
        let j: serde_json::Value = serde_json::from_str(&text).unwrap();
        let at = |name: &str| -> P {
            let p = j["joints"]
                .as_array()
                .unwrap()
                .iter()
                .find(|x| x["name"] == name)
                .unwrap();
            [p["at"][0].as_f64().unwrap(), p["at"][1].as_f64().unwrap()]
        };
        let (o, a, b, c) = (at("O"), at("A"), at("B"), at("C"));
        let (l1, l2, l3, oc) = (
            norm(sub(a, o)),
            norm(sub(b, a)),
            norm(sub(b, c)),
            norm(sub(c, o)),
        );
        assert!(
            (oc - l1).abs() > (l2 - l3).abs(),
            "{file}: the inner limit is never met here"
        );
        let reach = l2 + l3;
        assert_eq!(
            l1 + oc > reach,
            rocks,
            "{file}: the edit makes crank 1 rock"
        );
        let first = &ranges[0];
        if rocks {
            assert_eq!(first["kind"], "rocking", "{file}: {first}");
            let theta = (c[1] - o[1]).atan2(c[0] - o[0]);
            let half = ((l1 * l1 + oc * oc - reach * reach) / (2.0 * l1 * oc)).acos();
            let (from, to) = (
                first["from"].as_f64().unwrap(),
                first["to"].as_f64().unwrap(),
            );
            // A reaches C's side: the range is the arc of A within l2 + l3 of C.
            let want = [theta - half, theta + half];
            for (got, w) in [from, to].into_iter().zip(want) {
                let d = (got - w).rem_euclid(std::f64::consts::TAU);
                let d = d.min(std::f64::consts::TAU - d);
                assert!(d < 1e-9, "{file}: lock {got} rad, closed form {w} rad");
            }
        } else {
            assert_eq!(first["kind"], "full turn", "{file}: {first}");
        }
        let r = tmm(&["check", &file]);
        assert_success(&r, &file);
        assert!(!r.stdout.contains("not determined"), "{}", r.stdout);
        assert!(r.stdout.contains("--workspace POINT"), "{}", r.stdout);
        assert!(
            r.stdout.contains("crank 1 (crank 4 at 60"),
            "the held input and its angle: {}",
            r.stdout
        );
    }
}

/// An angle so large that an f64 no longer places the crank (beyond ±10⁹ rad) is refused by
/// every option that takes one, in one sentence naming the option; 10⁹ rad itself is taken.
#[test]
fn huge_angles_are_refused_naming_the_option() {
    for (args, option) in [
        (&["analyse", "four-bar", "--at", "1e300"][..], "--at"),
        (&["analyse", "four-bar", "--at", "-6e10"], "--at"),
        (
            &["analyse", "five-bar-robot", "--at", "120", "1e300"],
            "--at",
        ),
        (&["draw", "four-bar", "--scheme", "1e300"], "--scheme"),
        (&["draw", "four-bar", "--forces", "-1e20"], "--forces"),
        (
            &["draw", "five-bar-robot", "--scheme", "1e300", "60"],
            "--scheme",
        ),
        (
            &[
                "draw",
                "five-bar-robot",
                "--plan",
                "--along",
                "120",
                "60",
                "1e300",
                "60",
            ],
            "--along",
        ),
    ] {
        let file = args[1];
        let r = tmm(args);
        assert_one_line_failure(&r, file);
        assert!(
            r.stderr.contains(option) && r.stderr.contains("10⁹ rad"),
            "{args:?}: {}",
            r.stderr
        );
    }
    // 10⁹ rad in degrees, just inside the bound: a position like any other.
    let inside = arg(1e9f64.to_degrees() * (1.0 - 1e-12));
    let r = tmm(&["analyse", "four-bar", "--format", "csv", "--at", &inside]);
    assert_success(&r, "an angle just inside the bound");
}

/// `tmm check` lists a triad as it lists a general group: its four links (the ternary one
/// first) and six joints (its legs' hinges on the ternary link, then their joints to known
/// links), each as the file has them.
#[test]
fn check_lists_a_triads_four_links_and_six_joints() {
    let v = json(&["check", "six-bar-triad", "--format", "json"]);
    let text = std::fs::read_to_string(root().join("linkages/six-bar-triad.json")).unwrap();
    let file: serde_json::Value = serde_json::from_str(&text).unwrap();
    let joints_of = |link: &str| -> Vec<String> {
        file["links"]
            .as_array()
            .unwrap()
            .iter()
            .find(|l| l["name"] == link)
            .unwrap()["joints"]
            .as_array()
            .unwrap()
            .iter()
            .map(|j| j.as_str().unwrap().to_owned())
            .collect()
    };
    let groups = v["groups"].as_array().unwrap();
    let triad = groups
        .iter()
        .find(|g| g["links"].as_array().unwrap().len() == 4)
        .unwrap_or_else(|| panic!("a group of four links: {groups:?}"));
    let links: Vec<String> = triad["links"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap().to_owned())
        .collect();
    let joints: Vec<String> = triad["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap().to_owned())
        .collect();
    assert_eq!(links[0], "ternary");
    assert_eq!(joints.len(), 6, "{joints:?}");
    let mut sorted = joints.clone();
    sorted.sort();
    sorted.dedup();
    assert_eq!(sorted.len(), 6, "six distinct joints: {joints:?}");
    for (k, j) in joints.iter().enumerate() {
        let on: Vec<&String> = links.iter().filter(|l| joints_of(l).contains(j)).collect();
        if k < 3 {
            // A leg's hinge on the ternary link: on the ternary link and on one leg.
            assert!(on.len() == 2 && *on[0] == links[0], "{j}: {on:?}");
        } else {
            // A leg's joint to a known link: on one leg only within the group.
            assert!(on.len() == 1 && *on[0] != links[0], "{j}: {on:?}");
        }
    }
    let r = tmm(&["check", "six-bar-triad"]);
    assert_success(&r, "check six-bar-triad");
    let line = r
        .stdout
        .lines()
        .find(|l| l.contains("ternary"))
        .expect("the triad's line");
    assert!(
        line.contains("joints") && line.contains("inside") && line.contains("to known links"),
        "{line}"
    );
}

/// `tmm draw --centres` draws the instant centres on the scheme in the file's numbering of
/// the links, with the key; the four-bar's crank–rocker centre I13 lies on the picture at
/// 30°, and its frame–crank pivot I01 too.
#[test]
fn the_scheme_draws_the_instant_centres_in_the_files_numbering() {
    let r = tmm(&["draw", "four-bar", "--scheme", "30", "--centres"]);
    assert_success(&r, "draw --centres");
    assert_svg(&r.stdout, "draw --centres");
    assert!(r
        .stdout
        .contains("links: 0 frame, 1 crank, 2 coupler, 3 rocker"));
    for label in ["\nI13\n", "\nI01\n", "\nI12\n"] {
        assert!(r.stdout.contains(label), "{label:?}");
    }
    let plain = tmm(&["draw", "four-bar", "--scheme", "30"]);
    assert!(!plain.stdout.contains("instant-centres"));
    let r = tmm(&["draw", "four-bar", "--plan", "--centres"]);
    assert_eq!(r.code, 2, "a usage error: {}", r.stderr);
}
