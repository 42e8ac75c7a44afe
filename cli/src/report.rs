//! The program's output as text, CSV and JSON, from its own plain data ([`crate::model`]).

mod synth;
mod two_inputs;

use std::fmt::Write as _;

use crate::model::{DynamicsReport, InputKind, ModesInfo, Range, StrokeInfo, Structure, TableData};

pub use synth::design;
pub use two_inputs::{mass_matrix, mass_matrix_csv, mass_matrix_json};

/// An angle in rad as degrees, one decimal.
fn deg(rad: f64) -> String {
    format!("{:.1}°", rad.to_degrees())
}

/// A direction in rad as degrees in [0, 360), one decimal.
fn direction(rad: f64) -> String {
    let d = rad.to_degrees().rem_euclid(360.0);
    let text = format!("{d:.1}");
    if text == "360.0" {
        "0.0°".to_owned()
    } else {
        format!("{text}°")
    }
}

/// A number for a person: four decimals in the usual range, scientific notation outside it,
/// a dash where the value is not available, never "-0.0000".
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return "—".to_owned();
    }
    let a = v.abs();
    // Below 1e-10 is rounding (an ω of -2e-16 rad/s): four decimals show it as zero.
    let text = if a >= 1e6 || (1e-10..1e-3).contains(&a) {
        format!("{v:.4e}")
    } else {
        format!("{v:.4}")
    };
    if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_owned()
    } else {
        text
    }
}

/// `tmm check`: the structure as text.
pub fn structure(s: &Structure) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "{}", s.name);
    let _ = writeln!(o, "mobility W = {} (Chebyshev)", s.mobility);
    for (k, i) in s.inputs.iter().enumerate() {
        let which = if s.inputs.len() > 1 {
            format!("input {}", k + 1)
        } else {
            "input".to_owned()
        };
        let (kind, reference) = match i.kind {
            InputKind::Crank => (
                "crank",
                format!("φ = {} in the reference pose", direction(i.reference)),
            ),
            InputKind::Slider => ("slider", "s = 0 m in the reference pose".to_owned()),
        };
        let _ = writeln!(
            o,
            "{which}: {kind} \"{}\", driven {}; {reference}",
            i.link, i.drive
        );
    }
    let _ = writeln!(o, "groups in attachment order:");
    if s.groups.is_empty() {
        let _ = writeln!(o, "  (none)");
    }
    for (k, g) in s.groups.iter().enumerate() {
        let line = match g.inner {
            // A general group: every link, its inner hinges, its hinges to known links.
            Some(n) => format!(
                "links {}; joints {} inside, {} to known links",
                g.links.join(", "),
                g.joints[..n].join(", "),
                g.joints[n..].join(", ")
            ),
            None => format!(
                "links {}, joints {}",
                g.links.join(" and "),
                g.joints.join("–")
            ),
        };
        let _ = writeln!(o, "  {}. {}  {line}", k + 1, g.kind);
    }
    if let [first, second] = s.inputs.as_slice()
        && let [r1, r2] = s.input_ranges.as_slice()
    {
        let _ = writeln!(
            o,
            "range: two inputs move the linkage over a 2-D region of input pairs (draw what a \
             point reaches with `tmm draw FILE --workspace POINT`); each input alone, the \
             other fixed at its reference value:"
        );
        for (this, other, r) in [(first, second, r1), (second, first, r2)] {
            let held = match other.kind {
                InputKind::Crank => format!("{} at {}", other.link, direction(other.reference)),
                InputKind::Slider => format!("{} at s = 0 m", other.link),
            };
            let _ = writeln!(o, "  {} ({held}): {}", this.link, range_text(r));
        }
    } else {
        let _ = writeln!(o, "range: {}", range_text(&s.range));
    }
    if let Some(g) = &s.grashof {
        let _ = writeln!(o, "Grashof: {g}");
    }
    modes_text(&mut o, &s.modes);
    if !s.transmission.is_empty() {
        let _ = writeln!(o, "smallest transmission angle over a turn:");
        for (name, t) in &s.transmission {
            match t {
                Ok((mu, at)) => {
                    let _ = writeln!(
                        o,
                        "  {name}: γ_min = {} at φ = {}",
                        deg(*mu),
                        direction(*at)
                    );
                }
                Err(e) => {
                    let _ = writeln!(o, "  {name}: not available ({e})");
                }
            }
        }
    }
    match &s.strokes {
        Some(Ok(StrokeInfo {
            output,
            start,
            working_angle,
            time_ratio,
            stroke,
            stroke_unit,
        })) => {
            let stroke = if *stroke_unit == "rad" {
                format!("swing {}", deg(*stroke))
            } else {
                format!("stroke {} m", number(*stroke))
            };
            let _ = writeln!(
                o,
                "output {output}: {stroke}; working stroke from φ = {} over {}, time ratio {:.4}",
                direction(*start),
                deg(*working_angle),
                time_ratio
            );
        }
        Some(Err(e)) => {
            let _ = writeln!(o, "output: no strokes ({e})");
        }
        None => {}
    }
    o
}

/// The column's title: `name [unit]`.
fn title(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        name.to_owned()
    } else {
        format!("{name} [{unit}]")
    }
}

/// `tmm analyse --format table`: one line per quantity, one column per position.
pub fn table_text(t: &TableData) -> String {
    let titles: Vec<String> = t.columns.iter().map(|c| title(&c.name, &c.unit)).collect();
    let width = titles.iter().map(|s| s.chars().count()).max().unwrap_or(0);
    let rows = t.columns.first().map_or(0, |c| c.values.len());
    let mut o = String::new();
    let (unit, rate) = match t.input {
        InputKind::Crank => ("rad/s", "ω"),
        InputKind::Slider => ("m/s", "v"),
    };
    let _ = writeln!(
        o,
        "{}: {} positions at {rate} = {} {unit}",
        t.name,
        rows,
        number(t.speed)
    );
    for note in &t.notes {
        let _ = writeln!(o, "{note}");
    }
    let _ = write!(o, "{:<width$}", "position");
    for k in 1..=rows {
        let _ = write!(o, " {k:>11}");
    }
    o.push('\n');
    for (c, title) in t.columns.iter().zip(&titles) {
        let pad = width - title.chars().count();
        let _ = write!(o, "{title}{}", " ".repeat(pad));
        for &v in &c.values {
            let _ = write!(o, " {:>11}", number(v));
        }
        o.push('\n');
    }
    o
}

/// A CSV cell: quoted when it holds a comma, a quote or a line break.
fn cell(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_owned()
    }
}

/// `tmm analyse --format csv`: a header of `name [unit]`, then one line per position, numbers
/// in their shortest round-trip form; an empty cell where a value is not available.
pub fn table_csv(t: &TableData) -> String {
    let mut o = String::new();
    let header: Vec<String> = t
        .columns
        .iter()
        .map(|c| cell(&title(&c.name, &c.unit)))
        .collect();
    let _ = writeln!(o, "{}", header.join(","));
    let rows = t.columns.first().map_or(0, |c| c.values.len());
    for k in 0..rows {
        let line: Vec<String> = t
            .columns
            .iter()
            .map(|c| {
                let v = c.values[k];
                if v.is_finite() {
                    v.to_string()
                } else {
                    String::new()
                }
            })
            .collect();
        let _ = writeln!(o, "{}", line.join(","));
    }
    o
}

/// A JSON string literal.
pub fn json_string(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 2);
    o.push('"');
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            '\n' => o.push_str("\\n"),
            '\r' => o.push_str("\\r"),
            '\t' => o.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

/// A JSON number (`null` where not available).
fn json_number(v: f64) -> String {
    if v.is_finite() {
        // The shortest text that reads back as the same f64, as JSON writes numbers; with an
        // exponent outside [10⁻⁵, 10¹⁶), where the plain form would run to hundreds of digits.
        let a = v.abs();
        if a != 0.0 && !(1e-5..1e16).contains(&a) {
            format!("{v:e}")
        } else {
            format!("{v}")
        }
    } else {
        "null".to_owned()
    }
}

/// `tmm analyse --format json`: `{"name", "rows", "columns": [{"name", "unit", "values"}],
/// "failed": [{"input", "error"}], "notes"}`, `null` where a value is not available.
pub fn table_json(t: &TableData) -> String {
    let rows = t.columns.first().map_or(0, |c| c.values.len());
    let mut o = String::new();
    let _ = writeln!(o, "{{");
    let _ = writeln!(o, "  \"name\": {},", json_string(&t.name));
    let _ = writeln!(o, "  \"rows\": {rows},");
    let _ = writeln!(o, "  \"columns\": [");
    for (k, c) in t.columns.iter().enumerate() {
        let values: Vec<String> = c.values.iter().map(|&v| json_number(v)).collect();
        let _ = writeln!(
            o,
            "    {{\"name\": {}, \"unit\": {}, \"values\": [{}]}}{}",
            json_string(&c.name),
            json_string(&c.unit),
            values.join(", "),
            if k + 1 < t.columns.len() { "," } else { "" }
        );
    }
    let _ = writeln!(o, "  ],");
    let failed: Vec<String> = t
        .failures
        .iter()
        .map(|(input, e)| {
            format!(
                "{{\"input\": {}, \"error\": {}}}",
                json_number(*input),
                json_string(e)
            )
        })
        .collect();
    let _ = writeln!(o, "  \"failed\": [{}],", failed.join(", "));
    let notes: Vec<String> = t.notes.iter().map(|n| json_string(n)).collect();
    let _ = writeln!(o, "  \"notes\": [{}]", notes.join(", "));
    let _ = writeln!(o, "}}");
    o
}

/// A failed position's input for a person.
pub fn input_text(kind: InputKind, value: f64) -> String {
    match kind {
        InputKind::Crank => format!("φ = {}", direction(value)),
        InputKind::Slider => format!("s = {} m", number(value)),
    }
}

/// `tmm dynamics`: the reduced quantities, the run-up and the flywheels as text.
pub fn dynamics(d: &DynamicsReport) -> String {
    let mut o = String::new();
    let sense = if d.speed < 0.0 {
        "clockwise"
    } else {
        "counter-clockwise"
    };
    let _ = writeln!(
        o,
        "{} — the machine reduced to its crank at ω = {} rad/s ({sense}, {:.1} rpm)",
        d.name,
        number(d.speed.abs()),
        d.speed.abs() * 30.0 / std::f64::consts::PI
    );
    if d.rotor != 0.0 {
        let _ = writeln!(o, "rotor on the crank: {} kg·m²", number(d.rotor));
    }
    if let Some((lo, hi)) = d.rocking {
        let _ = writeln!(
            o,
            "the crank rocks: the reduced quantities over its range between the lock angles \
             {}° and {}° ({} and {} rad); at the locks the linkage is at a dead point, where \
             its transfer functions and so J_red are unbounded, so the {} positions are the middles of equal steps \
             between them (φ the crank angle, turned from the lock it starts at)",
            number(lo.to_degrees()),
            number(hi.to_degrees()),
            lo,
            hi,
            d.reduced.len()
        );
    }
    let n = d.reduced.len().max(1);
    // Each term divided first: 360 rows of a rotor of 10³⁰⁸ kg·m² summed overflow.
    let n = n as f64;
    let mean = d.reduced.iter().map(|r| r.loads / n).sum::<f64>();
    let j_mean = d.reduced.iter().map(|r| r.inertia / n).sum::<f64>();
    let _ = writeln!(
        o,
        "mean reduced moment of the loads {} N·m, mean J_red {} kg·m² ({} positions)",
        number(mean),
        number(j_mean),
        d.reduced.len()
    );
    let _ = writeln!(
        o,
        "{:>10} {:>10} {:>14} {:>14} {:>14}",
        "φ", "turned", "J_red", "dJ_red/dφ", "M_red"
    );
    let _ = writeln!(
        o,
        "{:>10} {:>10} {:>14} {:>14} {:>14}",
        "deg", "deg", "kg·m²", "kg·m²", "N·m"
    );
    let step = (d.reduced.len() / 12).max(1);
    for r in d.reduced.iter().step_by(step) {
        let _ = writeln!(
            o,
            "{:>10.1} {:>10.1} {:>14} {:>14} {:>14}",
            r.phi.to_degrees(),
            r.turned.to_degrees(),
            number(r.inertia),
            number(r.inertia_derivative),
            number(r.loads)
        );
    }
    if let Some(r) = &d.run_up {
        let chosen = if r.default_motor {
            " (chosen by tmm: 4 % slip at the speed asked for, 10 % above the loads' mean, to 5 \
             significant digits; --motor a,b to give your own)"
        } else {
            ""
        };
        let _ = writeln!(
            o,
            "\nrun-up from rest under the motor M = {} − {}·|ω| N·m{chosen}",
            number(r.motor.0),
            number(r.motor.1)
        );
        let _ = writeln!(
            o,
            "RK4, h = {} s: steady after {} turns ({} steps of the {} allowed, {} evaluations)",
            number(r.step),
            r.turns.len(),
            r.steps,
            r.budget,
            r.evaluations
        );
        let _ = writeln!(
            o,
            "{:>5} {:>11} {:>11} {:>11} {:>11} {:>11} {:>9}",
            "turn", "t0, s", "T, s", "ω_m, rad/s", "ω_max", "ω_min", "δ"
        );
        for (k, t) in r.turns.iter().enumerate() {
            if k < 5 || k + 3 >= r.turns.len() {
                let _ = writeln!(
                    o,
                    "{:>5} {:>11} {:>11} {:>11} {:>11} {:>11} {:>9.5}",
                    k + 1,
                    number(t.t_start),
                    number(t.period),
                    number(t.omega_mean),
                    number(t.omega_max),
                    number(t.omega_min),
                    t.delta
                );
            } else if k == 5 {
                let _ = writeln!(o, "{:>5}", "…");
            }
        }
    }
    if !d.flywheels.is_empty() {
        let _ = writeln!(
            o,
            "\nflywheel on the crank at ω_m = {} rad/s under a constant driving moment \
             (energy–mass method of Wittenbauer, and the simplified formula):",
            number(d.speed.abs())
        );
        let _ = writeln!(
            o,
            "{:>10} {:>14} {:>14} {:>12} {:>12}",
            "δ", "J_F, kg·m²", "simplified", "ΔE, J", "M_d, N·m"
        );
        for f in &d.flywheels {
            let _ = writeln!(
                o,
                "{:>10} {:>14} {:>14} {:>12} {:>12}",
                number(f.delta),
                number(f.inertia),
                number(f.simplified),
                number(f.energy_range),
                number(f.driving_moment)
            );
        }
    }
    o
}

/// `tmm dynamics --csv`: the reduced quantities over the turn, one line per position.
pub fn reduced_csv(d: &DynamicsReport) -> String {
    let mut o =
        String::from("phi [rad],turned [rad],J_red [kg·m^2],dJ_red/dphi [kg·m^2],M_red [N·m]\n");
    for r in &d.reduced {
        let _ = writeln!(
            o,
            "{},{},{},{},{}",
            r.phi, r.turned, r.inertia, r.inertia_derivative, r.loads
        );
    }
    o
}

/// A JSON object from (key, JSON text) pairs.
fn object(fields: &[(&str, String)]) -> String {
    let inner: Vec<String> = fields
        .iter()
        .map(|(k, v)| format!("{}: {v}", json_string(k)))
        .collect();
    format!("{{{}}}", inner.join(", "))
}

/// A JSON array of JSON texts.
fn array(items: impl IntoIterator<Item = String>) -> String {
    format!("[{}]", items.into_iter().collect::<Vec<_>>().join(", "))
}

/// `tmm check --format json`: the structure, angles in rad, lengths in m.
/// The assembly modes at the reference input(s), as text.
fn modes_text(o: &mut String, m: &Result<ModesInfo, String>) {
    let m = match m {
        Ok(m) => m,
        Err(e) => {
            let _ = writeln!(o, "assembly modes at the reference input: not counted: {e}");
            return;
        }
    };
    let _ = writeln!(o, "real assembly modes at the reference input:");
    for (name, n, how) in &m.groups {
        let _ = writeln!(o, "  {name}: {n} ({how})");
    }
    let product: Option<usize> = m.groups.iter().try_fold(1usize, |p, g| p.checked_mul(g.1));
    let at_least = if m.exhaustive { "" } else { "at least " };
    match (&m.total, product) {
        (Ok(t), Some(p)) if *t == p => {
            let _ = writeln!(
                o,
                "  in all: {at_least}{t} (every combination enumerated; the product of the groups' counts)"
            );
        }
        (Ok(t), _) => {
            let _ = writeln!(
                o,
                "  in all: {at_least}{t} (every combination enumerated; a group's count depends \
                 on the modes before it)"
            );
        }
        (Err(e), Some(p)) => {
            let _ = writeln!(
                o,
                "  in all: {at_least}{p} as the product of the groups' counts (not enumerated: {e})"
            );
        }
        (Err(e), None) => {
            let _ = writeln!(o, "  in all: more than 2^64 (not enumerated: {e})");
        }
    }
}

/// The assembly modes as JSON.
fn modes_json(m: &Result<ModesInfo, String>) -> String {
    match m {
        Err(e) => object(&[("error", json_string(e))]),
        Ok(m) => object(&[
            (
                "groups",
                array(m.groups.iter().map(|(name, n, how)| {
                    object(&[
                        ("group", json_string(name)),
                        ("count", n.to_string()),
                        ("search", json_string(how)),
                    ])
                })),
            ),
            (
                "total",
                match &m.total {
                    Ok(t) => t.to_string(),
                    Err(_) => "null".to_owned(),
                },
            ),
            (
                "total_error",
                match &m.total {
                    Ok(_) => "null".to_owned(),
                    Err(e) => json_string(e),
                },
            ),
            ("exhaustive", m.exhaustive.to_string()),
        ]),
    }
}

pub fn structure_json(s: &Structure) -> String {
    let inputs = array(s.inputs.iter().map(|i| {
        object(&[
            ("link", json_string(&i.link)),
            (
                "kind",
                json_string(match i.kind {
                    InputKind::Crank => "crank",
                    InputKind::Slider => "slider",
                }),
            ),
            ("drive", json_string(&i.drive)),
            ("reference", json_number(i.reference)),
        ])
    }));
    let groups = array(s.groups.iter().map(|g| {
        object(&[
            ("kind", json_string(&g.kind)),
            ("name", json_string(&g.name)),
            ("links", array(g.links.iter().map(|l| json_string(l)))),
            ("joints", array(g.joints.iter().map(|j| json_string(j)))),
        ])
    }));
    let range = range_json(&s.range);
    let input_ranges = array(s.input_ranges.iter().map(range_json));
    let transmission = array(s.transmission.iter().map(|(name, t)| match t {
        Ok((mu, at)) => object(&[
            ("group", json_string(name)),
            ("min", json_number(*mu)),
            ("at", json_number(*at)),
        ]),
        Err(e) => object(&[("group", json_string(name)), ("error", json_string(e))]),
    }));
    let strokes = match &s.strokes {
        None => "null".to_owned(),
        Some(Ok(st)) => object(&[
            ("output", json_string(&st.output)),
            ("start", json_number(st.start)),
            ("working_angle", json_number(st.working_angle)),
            ("time_ratio", json_number(st.time_ratio)),
            ("stroke", json_number(st.stroke)),
            ("stroke_unit", json_string(st.stroke_unit)),
        ]),
        Some(Err(e)) => object(&[("error", json_string(e))]),
    };
    let mut o = object(&[
        ("name", json_string(&s.name)),
        ("mobility", s.mobility.to_string()),
        ("inputs", inputs),
        ("groups", groups),
        ("range", range),
        ("input_ranges", input_ranges),
        (
            "grashof",
            s.grashof.as_deref().map_or("null".to_owned(), json_string),
        ),
        ("transmission", transmission),
        ("strokes", strokes),
        ("modes", modes_json(&s.modes)),
    ]);
    o.push('\n');
    o
}

/// `tmm dynamics --format json`: the reduced quantities as columns, the run-up's turns and
/// the flywheels, SI units.
pub fn dynamics_json(d: &DynamicsReport) -> String {
    let column = |f: &dyn Fn(&crate::model::ReducedRow) -> f64| {
        array(d.reduced.iter().map(|r| json_number(f(r))))
    };
    let reduced = object(&[
        ("phi", column(&|r| r.phi)),
        ("turned", column(&|r| r.turned)),
        ("J_red", column(&|r| r.inertia)),
        ("dJ_red_dphi", column(&|r| r.inertia_derivative)),
        ("M_red", column(&|r| r.loads)),
    ]);
    let run_up = d.run_up.as_ref().map_or("null".to_owned(), |r| {
        object(&[
            (
                "motor",
                object(&[
                    ("a", json_number(r.motor.0)),
                    ("b", json_number(r.motor.1)),
                    ("chosen_by_tmm", r.default_motor.to_string()),
                ]),
            ),
            ("step", json_number(r.step)),
            ("steps", r.steps.to_string()),
            ("evaluations", r.evaluations.to_string()),
            ("step_budget", r.budget.to_string()),
            (
                "turns",
                array(r.turns.iter().map(|t| {
                    object(&[
                        ("t_start", json_number(t.t_start)),
                        ("period", json_number(t.period)),
                        ("omega_mean", json_number(t.omega_mean)),
                        ("omega_max", json_number(t.omega_max)),
                        ("omega_min", json_number(t.omega_min)),
                        ("delta", json_number(t.delta)),
                    ])
                })),
            ),
        ])
    });
    let flywheels = array(d.flywheels.iter().map(|f| {
        object(&[
            ("delta", json_number(f.delta)),
            ("moment_of_inertia", json_number(f.inertia)),
            ("simplified", json_number(f.simplified)),
            ("energy_range", json_number(f.energy_range)),
            ("driving_moment", json_number(f.driving_moment)),
        ])
    }));
    let mut o = object(&[
        ("name", json_string(&d.name)),
        ("speed", json_number(d.speed)),
        ("rotor", json_number(d.rotor)),
        (
            "range",
            match d.rocking {
                None => object(&[("kind", json_string("full turn"))]),
                Some((lo, hi)) => object(&[
                    ("kind", json_string("rocking")),
                    ("from", json_number(lo)),
                    ("to", json_number(hi)),
                ]),
            },
        ),
        ("reduced", reduced),
        ("run_up", run_up),
        ("flywheels", flywheels),
    ]);
    o.push('\n');
    o
}

/// A range in words: a full turn, the lock angles, a slider's travel, or why not known.
fn range_text(range: &Range) -> String {
    match range {
        Range::FullTurn => "the crank turns fully".to_owned(),
        Range::Rocking(a, b) => format!(
            "the crank rocks between the lock angles {} and {} (a swing of {})",
            deg(*a),
            deg(*b),
            deg(b - a)
        ),
        Range::Travel(a, b) => format!(
            "the slider travels from s = {} m to {} m (a stroke of {} m)",
            number(*a),
            number(*b),
            number(b - a)
        ),
        Range::Unknown(why) => format!("not determined: {why}"),
    }
}

/// A range as JSON: its kind, and its ends (rad or m) or why it is not known.
fn range_json(range: &Range) -> String {
    match range {
        Range::FullTurn => object(&[("kind", json_string("full turn"))]),
        Range::Rocking(a, b) => object(&[
            ("kind", json_string("rocking")),
            ("from", json_number(*a)),
            ("to", json_number(*b)),
        ]),
        Range::Travel(a, b) => object(&[
            ("kind", json_string("travel")),
            ("from", json_number(*a)),
            ("to", json_number(*b)),
        ]),
        Range::Unknown(why) => {
            object(&[("kind", json_string("unknown")), ("why", json_string(why))])
        }
    }
}
