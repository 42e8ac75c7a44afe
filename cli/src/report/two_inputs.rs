//! The output of `tmm dynamics` for a linkage with two inputs: its mass matrix over a grid.

use std::fmt::Write as _;

use super::{array, json_number, json_string, number, object};
use crate::model::{HeldInput, MassRow, TwoInputDynamics, TwoInputRun};

/// The units of A₁₁, A₁₂, A₂₂ and of Q₁, Q₂ for inputs of the units `u` ("rad" or "m").
fn mass_units(u: [&str; 2]) -> ([&'static str; 3], [&'static str; 2]) {
    let a = |x: &str, y: &str| match (x, y) {
        ("rad", "rad") => "kg·m^2",
        ("m", "m") => "kg",
        _ => "kg·m",
    };
    let q = |x: &str| if x == "rad" { "N·m" } else { "N" };
    (
        [a(u[0], u[0]), a(u[0], u[1]), a(u[1], u[1])],
        [q(u[0]), q(u[1])],
    )
}

/// `tmm dynamics` of a linkage with two inputs: the mass matrix over the grid, as text.
pub fn mass_matrix(d: &TwoInputDynamics) -> String {
    let mut o = String::new();
    let (au, qu) = mass_units(d.units);
    let shown = |k: usize, v: f64| {
        if d.units[k] == "rad" {
            format!("{}°", number(v.to_degrees()))
        } else {
            format!("{} m", number(v))
        }
    };
    let _ = writeln!(
        o,
        "{} — two inputs (mobility 2): the kinetic energy is T = ½ q̇ᵀ A(q) q̇, with the mass \
         matrix A over a grid of {} × {} input pairs, q1 from {} to {} and q2 from {} to {}",
        d.name,
        d.n,
        d.n,
        shown(0, d.ranges[0][0]),
        shown(0, d.ranges[0][1]),
        shown(1, d.ranges[1][0]),
        shown(1, d.ranges[1][1]),
    );
    let _ = writeln!(
        o,
        "{} pairs assemble{}; Q are the loads' generalized forces at rest",
        d.rows.len(),
        if d.skipped > 0 {
            format!(" ({} do not and are left out)", d.skipped)
        } else {
            String::new()
        }
    );
    let det = |r: &MassRow| r.a[0] * r.a[2] - r.a[1] * r.a[1];
    let min_det = d.rows.iter().map(det).fold(f64::INFINITY, f64::min);
    let _ = writeln!(o, "smallest det A over the grid: {}", number(min_det));
    let _ = writeln!(
        o,
        "{:>10} {:>10} {:>12} {:>12} {:>12} {:>12} {:>12}",
        "q1", "q2", "A11", "A12", "A22", "Q1", "Q2"
    );
    let _ = writeln!(
        o,
        "{:>10} {:>10} {:>12} {:>12} {:>12} {:>12} {:>12}",
        if d.units[0] == "rad" { "deg" } else { "m" },
        if d.units[1] == "rad" { "deg" } else { "m" },
        au[0],
        au[1],
        au[2],
        qu[0],
        qu[1]
    );
    let step = (d.rows.len() / 12).max(1);
    let deg = |k: usize, v: f64| {
        if d.units[k] == "rad" {
            v.to_degrees()
        } else {
            v
        }
    };
    for r in d.rows.iter().step_by(step) {
        let _ = writeln!(
            o,
            "{:>10.3} {:>10.3} {:>12} {:>12} {:>12} {:>12} {:>12}",
            deg(0, r.q[0]),
            deg(1, r.q[1]),
            number(r.a[0]),
            number(r.a[1]),
            number(r.a[2]),
            number(r.loads[0]),
            number(r.loads[1])
        );
    }
    if let Some(run) = &d.run {
        run_text(&mut o, run, d.units);
    }
    o
}

/// The run from rest, as text: a few of its rows and the energy balance.
fn run_text(o: &mut String, run: &TwoInputRun, units: [&str; 2]) {
    let last = run.rows.last().copied().unwrap_or([0.0; 7]);
    let _ = writeln!(
        o,
        "\nrun from rest in the reference pose for {} s under M1 = {} − {}·q̇1 and M2 = {} − \
         {}·q̇2 and the loads: RK4, h = {} s ({} steps, {} evaluations)",
        number(last[0]),
        number(run.motors[0].0),
        number(run.motors[0].1),
        number(run.motors[1].0),
        number(run.motors[1].1),
        number(run.step),
        run.steps,
        run.evaluations
    );
    for h in &run.held {
        let _ = writeln!(o, "{}", held_text(h, units[h.input - 1]));
    }
    if let Some(why) = &run.stopped {
        let _ = writeln!(o, "the run stopped: {why}");
    }
    let _ = writeln!(
        o,
        "energy: kinetic energy gained {} J, work of the loads and motors {} J (trapezoids \
         over the steps), difference {:.3e} J",
        number(last[5]),
        number(run.work),
        last[5] - run.work
    );
    let u = |k: usize| {
        if units[k] == "rad" {
            ("deg", "rad/s")
        } else {
            ("m", "m/s")
        }
    };
    let _ = writeln!(
        o,
        "{:>10} {:>10} {:>10} {:>12} {:>12} {:>12}",
        "t", "q1", "q2", "q̇1", "q̇2", "T"
    );
    let _ = writeln!(
        o,
        "{:>10} {:>10} {:>10} {:>12} {:>12} {:>12}",
        "s",
        u(0).0,
        u(1).0,
        u(0).1,
        u(1).1,
        "J"
    );
    let step = (run.rows.len() / 10).max(1);
    let deg = |k: usize, v: f64| if units[k] == "rad" { v.to_degrees() } else { v };
    let shown = run
        .rows
        .iter()
        .step_by(step)
        .chain((!(run.rows.len() - 1).is_multiple_of(step)).then_some(&last));
    for r in shown {
        let _ = writeln!(
            o,
            "{:>10} {:>10.3} {:>10.3} {:>12} {:>12} {:>12}",
            number(r[0]),
            deg(0, r[1]),
            deg(1, r[2]),
            number(r[3]),
            number(r[4]),
            number(r[5])
        );
    }
}

/// One input held by its joint's friction, as a sentence: which, where, from when until when
/// (or to the end), and why: the load that would move it against the friction its joint can
/// hold, where the hold begins and where it ends.
fn held_text(h: &HeldInput, unit: &str) -> String {
    let at = if unit == "rad" {
        format!("{:.3}°", h.at.to_degrees())
    } else {
        format!("{} m", number(h.at))
    };
    let until = if h.released {
        format!("until t = {} s, where it breaks away", number(h.until))
    } else {
        "to the end of the run".to_owned()
    };
    let why = h.loads.as_ref().map_or_else(
        || " (its loads could not be weighed)".to_owned(),
        |l| {
            format!(
                ": the load that would move it, {} {u} at t = {} s and {} {u} at t = {} s, is \
                 within the friction its joint can hold, {} and {} {u}{}",
                number(l.drive[0]),
                number(l.weighed[0]),
                number(l.drive[1]),
                number(l.weighed[1]),
                number(l.breakaway[0]),
                number(l.breakaway[1]),
                if h.released {
                    " (it reaches it at the release)"
                } else {
                    ""
                },
                u = l.unit,
            )
        },
    );
    format!(
        "input {} held at {at} by the friction in its own joint from t = {} s {until}{why}",
        h.input,
        number(h.from),
    )
}

/// `tmm dynamics --csv` of a linkage with two inputs: one line per pair of the grid.
pub fn mass_matrix_csv(d: &TwoInputDynamics) -> String {
    let (au, qu) = mass_units(d.units);
    let mut o = format!(
        "q1 [{}],q2 [{}],A11 [{}],A12 [{}],A22 [{}],Q1 [{}],Q2 [{}]\n",
        d.units[0], d.units[1], au[0], au[1], au[2], qu[0], qu[1]
    );
    for r in &d.rows {
        let _ = writeln!(
            o,
            "{},{},{},{},{},{},{}",
            r.q[0], r.q[1], r.a[0], r.a[1], r.a[2], r.loads[0], r.loads[1]
        );
    }
    o
}

/// `tmm dynamics --format json` of a linkage with two inputs: columns in SI units.
pub fn mass_matrix_json(d: &TwoInputDynamics) -> String {
    let column = |f: &dyn Fn(&MassRow) -> f64| array(d.rows.iter().map(|r| json_number(f(r))));
    let mut o = object(&[
        ("name", json_string(&d.name)),
        ("units", array(d.units.iter().map(|u| json_string(u)))),
        (
            "ranges",
            array(
                d.ranges
                    .iter()
                    .map(|r| array(r.iter().map(|&v| json_number(v)))),
            ),
        ),
        ("grid", d.n.to_string()),
        ("skipped", d.skipped.to_string()),
        ("run", d.run.as_ref().map_or("null".to_owned(), run_json)),
        (
            "mass_matrix",
            object(&[
                ("q1", column(&|r| r.q[0])),
                ("q2", column(&|r| r.q[1])),
                ("A11", column(&|r| r.a[0])),
                ("A12", column(&|r| r.a[1])),
                ("A22", column(&|r| r.a[2])),
                ("Q1", column(&|r| r.loads[0])),
                ("Q2", column(&|r| r.loads[1])),
            ]),
        ),
    ]);
    o.push('\n');
    o
}

/// The run from rest as JSON: the motors, the step, the energy balance and every row's
/// columns in SI units.
fn run_json(run: &TwoInputRun) -> String {
    let column = |k: usize| array(run.rows.iter().map(|r| json_number(r[k])));
    object(&[
        (
            "motors",
            array(
                run.motors
                    .iter()
                    .map(|&(a, b)| object(&[("a", json_number(a)), ("b", json_number(b))])),
            ),
        ),
        ("step", json_number(run.step)),
        ("steps", run.steps.to_string()),
        ("evaluations", run.evaluations.to_string()),
        ("work", json_number(run.work)),
        (
            "stopped",
            run.stopped
                .as_deref()
                .map_or_else(|| "null".to_owned(), json_string),
        ),
        (
            "held",
            array(run.held.iter().map(|h| {
                object(&[
                    ("input", h.input.to_string()),
                    ("at", json_number(h.at)),
                    ("from", json_number(h.from)),
                    ("until", json_number(h.until)),
                    ("released", h.released.to_string()),
                    (
                        "loads",
                        h.loads.as_ref().map_or_else(
                            || "null".to_owned(),
                            |l| {
                                let pair = |v: [f64; 2]| array(v.map(json_number));
                                object(&[
                                    ("weighed", pair(l.weighed)),
                                    ("drive", pair(l.drive)),
                                    ("breakaway", pair(l.breakaway)),
                                    ("unit", json_string(l.unit)),
                                ])
                            },
                        ),
                    ),
                ])
            })),
        ),
        ("t", column(0)),
        ("q1", column(1)),
        ("q2", column(2)),
        ("qd1", column(3)),
        ("qd2", column(4)),
        ("kinetic", column(5)),
        ("power", column(6)),
    ])
}
