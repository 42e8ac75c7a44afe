//! `tmm synth`'s report as text: the design's dimensions and figures, the engine's check of
//! the description written, and the misses at the requirement's points.

use std::fmt::Write as _;

use super::{deg, direction, number};
use crate::design::{DesignReport, Misses};
use crate::model::Range;

/// A length in m as mm, four decimals; in scientific notation from 10⁹ mm and below
/// 10⁻⁴ mm (a design scaled from a stroke of 10²⁰ m printed 24 digits).
fn mm(m: f64) -> String {
    let v = m * 1e3;
    if v != 0.0 && !(1e-4..1e9).contains(&v.abs()) {
        format!("{v:.4e} mm")
    } else {
        format!("{v:.4} mm")
    }
}

/// The report of a synthesised mechanism.
pub fn design(r: &DesignReport) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "{}", r.kind);
    for d in &r.dimensions {
        let value = if d.angle {
            format!("{:.4}°", d.value.to_degrees())
        } else {
            mm(d.value)
        };
        let _ = writeln!(o, "  {:<32} {value:>14}", d.name);
    }
    if let Some(k) = r.time_ratio {
        let _ = writeln!(o, "  {:<32} {k:>14.6}", "time ratio K");
    }
    if let Some(s) = r.stroke {
        let (name, value) = if r.angular_output {
            ("swing ψ", format!("{:.4}°", s.to_degrees()))
        } else {
            ("stroke H", mm(s))
        };
        let _ = writeln!(o, "  {name:<32} {value:>14}");
    }
    let (gamma, at) = r.min_transmission;
    let _ = writeln!(
        o,
        "  {:<32} {:>14} at φ = {}",
        "smallest transmission angle",
        format!("{:.4}°", gamma.to_degrees()),
        direction(at)
    );
    if let Some(g) = &r.grashof {
        let _ = writeln!(o, "  {:<32} {g}", "Grashof class");
    }
    for n in &r.notes {
        let _ = writeln!(o, "  {n}");
    }
    checked(&mut o, r);
    if let Some(m) = &r.misses {
        misses(&mut o, m);
    }
    o
}

/// The engine's figures of the description as written.
fn checked(o: &mut String, r: &DesignReport) {
    let s = &r.checked;
    let _ = writeln!(o, "checked by the engine (the description as written):");
    let range = match &s.range {
        Range::FullTurn => "the crank turns fully".to_owned(),
        Range::Rocking(a, b) => format!(
            "the crank rocks between the lock angles {} and {}",
            deg(*a),
            deg(*b)
        ),
        Range::Travel(a, b) => format!("the slider travels {} m", number(b - a)),
        Range::Unknown(why) => format!("not determined: {why}"),
    };
    let _ = writeln!(o, "  range: {range}");
    if let Some(g) = &s.grashof {
        let _ = writeln!(o, "  Grashof: {g}");
    }
    match &s.strokes {
        Some(Ok(st)) => {
            let stroke = if st.stroke_unit == "rad" {
                format!("swing {:.6}°", st.stroke.to_degrees())
            } else {
                format!("stroke {}", mm(st.stroke))
            };
            let _ = writeln!(
                o,
                "  {}: time ratio K = {:.8}, {stroke}, the working stroke over {}",
                st.output,
                st.time_ratio,
                deg(st.working_angle)
            );
        }
        Some(Err(e)) => {
            let _ = writeln!(o, "  strokes: not available ({e})");
        }
        None => {}
    }
    for (name, t) in &s.transmission {
        match t {
            Ok((mu, at)) => {
                let _ = writeln!(
                    o,
                    "  {name}: γ_min = {:.4}° at φ = {}",
                    mu.to_degrees(),
                    direction(*at)
                );
            }
            Err(e) => {
                let _ = writeln!(o, "  {name}: γ_min not available ({e})");
            }
        }
    }
}

/// The misses as a table: one row per point of the requirement.
fn misses(o: &mut String, m: &Misses) {
    let _ = writeln!(o, "{}:", m.title);
    let show = |v: f64| match m.unit {
        _ if !v.is_finite() => "—".to_owned(),
        "deg" => format!("{:.6}", v.to_degrees()),
        _ => number(v),
    };
    let unit = if m.unit.is_empty() {
        String::new()
    } else {
        format!(" [{}]", m.unit)
    };
    let mut header = format!("  {:<16}", "at");
    for q in &m.quantities {
        header.push_str(&format!(" {:>14}", format!("{q} wanted")));
    }
    for q in &m.quantities {
        header.push_str(&format!(" {:>14}", format!("{q} reached")));
    }
    header.push_str(&format!(" {:>12}", format!("miss{unit}")));
    let _ = writeln!(o, "{header}");
    let mut unassembled = false;
    for row in &m.rows {
        let mut line = format!("  {:<16}", row.at);
        for v in row.wanted.iter().chain(&row.reached) {
            line.push_str(&format!(" {:>14}", show(*v)));
        }
        let miss = match m.unit {
            _ if !row.miss.is_finite() => "—".to_owned(),
            "deg" => format!("{:.3e}", row.miss.to_degrees()),
            _ => format!("{:.3e}", row.miss),
        };
        line.push_str(&format!(" {miss:>12}"));
        let _ = writeln!(o, "{line}");
        unassembled |= !row.miss.is_finite();
    }
    if unassembled {
        let _ = writeln!(o, "  (a dash: the linkage does not assemble there)");
    }
}
