//! Seed 002's example: the group with a parallel coupler, solved by the force method.
//!
//! Prints the paper's numbers beside ours, shows how the redundant force moves with the links'
//! axial stiffness, lists the extreme internal forces of every link, and writes two SVG charts:
//! the N, Q and M diagrams of every link (inextensible links as in the paper, and
//! EA·L²/EI = 10³), and X1 with the frame reactions against EA·L²/EI.
//!
//! Run: `cargo run --example passive_diagrams [-- <output folder>]`
//! (the default folder is `target/tmm-charts/passive`).

use plotters::prelude::*;
use std::error::Error;
use std::path::PathBuf;
use tmm::kinetostatics::passive::{
    Link, PaperGroup, PaperResult, Side, Solution, State, Stiffness,
};

/// The length scale of the axial-stiffness ratio EA·L²/EI: link 3, l3 + l4.
const L: f64 = 0.35;

fn run_example() -> Result<(), Box<dyn Error>> {
    let p = PaperGroup::example();
    // EI = 1 N·m²: then δ11 and Δ1F print as δ11·EI and Δ1F·EI, as in the paper.
    let r = p.solve(&Stiffness::bending_only(1.0))?;

    println!("Seed 002: Assur group with a parallel coupler (passive constraint), force method");
    println!("F1 = 250 N, F2 = 300 N, F3 = 200 N, M = 40 N·m, l1 = l2 = 200 mm, l3 = 100 mm,");
    println!("l4 = 250 mm, α1 = α2 = α4 = 60°, α3 = 75°; links inextensible, one EI\n");
    println!("{:<10} {:>12} {:>12}  note", "quantity", "paper", "tmm");
    let rows: [(&str, &str, String, &str); 12] = [
        (
            "δ11·EI",
            "4.4645e-4",
            format!("{:.5e}", r.delta11),
            "4.4643e-4 in eq. 8 (docs/errata.md#p2)",
        ),
        (
            "Δ1F·EI",
            "0.02796",
            format!("{:.6}", r.delta1f),
            "paper rounded Y_EF before Y_EF·l4 − M",
        ),
        ("X_AF", "282.5", format!("{:.3}", r.x_af), ""),
        ("Y_EF", "197.5", format!("{:.3}", r.y_ef), ""),
        (
            "X_EF",
            "74.27",
            format!("{:.3}", r.x_ef),
            "the paper rounded X_AF first",
        ),
        ("X1", "-62.6", format!("{:.3}", r.x1), "inherits Δ1F"),
        ("R01n", "327.2", format!("{:.3}", r.r01n), "inherits X1"),
        ("R01t", "108.3", format!("{:.3}", r.r01t), ""),
        ("R02n", "-62.6", format!("{:.3}", r.r02n), "= X1"),
        (
            "R02t",
            "129.9",
            format!("{:.3}", r.r02t),
            "upward; the paper prints the magnitude (P4)",
        ),
        ("R03n", "65.33", format!("{:.3}", r.r03n), ""),
        ("R03t", "213", format!("{:.3}", r.r03t), ""),
    ];
    for (name, paper, ours, note) in rows {
        println!("{name:<10} {paper:>12} {ours:>12}  {note}");
    }
    let s = &r.solution;
    println!(
        "hinge B: R13 = ({:.2}, {:.2}) N; hinge D: R23 = ({:.2}, {:.2}) N",
        s.reactions.r13.x, s.reactions.r13.y, s.reactions.r23.x, s.reactions.r23.y
    );

    let m3 = |x: f64| s.internal_in(State::Total, Link::Bde, x, Side::Before).m;
    println!(
        "bending moments of link 3 (the paper's deformation check): M(K) = {:.3}, M(D) = {:.3}, \
         M(mid DE) = {:.3}, M(E) = {:.3} N·m",
        m3(0.05),
        m3(0.1),
        m3(0.225),
        m3(0.35)
    );

    println!(
        "\nThe redundant depends on the links' axial stiffness (same EI and EA in every link):"
    );
    println!(
        "{:>12} {:>10} {:>12} {:>12}",
        "EA·L²/EI", "X1, N", "R01n, N", "|R03|, N"
    );
    let mut with_axial = None;
    for ratio in [1e1, 1e2, 1e3, 1e4, 1e5, 1e6] {
        let q = p.solve(&Stiffness::with_axial(1.0, ratio / (L * L)))?;
        println!(
            "{ratio:>12.0e} {:>10.2} {:>12.2} {:>12.2}",
            q.x1,
            q.r01n,
            q.solution.reactions.r03.norm()
        );
        if ratio == 1e3 {
            with_axial = Some(q.solution);
        }
    }
    println!(
        "{:>12} {:>10.2} {:>12.2} {:>12.2}   (the paper's model)",
        "∞",
        r.x1,
        r.r01n,
        s.reactions.r03.norm()
    );
    println!(
        "(L = l3 + l4 = 0.35 m; a solid round bar 20 mm thick and 0.35 m long has about 5·10³.)"
    );

    println!("\nExtreme internal forces (inextensible links; s from A, C and B, in mm):");
    for link in Link::ALL {
        let e = s.extremes(link);
        let (n, sn) = e.n.max_abs();
        let (q, sq) = e.q.max_abs();
        let (m, sm) = e.m.max_abs();
        println!(
            "  {:<4} N = {n:8.2} N at {:5.1}   Q = {q:8.2} N at {:5.1}   M = {m:7.3} N·m at {:5.1}",
            link.name(),
            1e3 * sn,
            1e3 * sq,
            1e3 * sm
        );
    }

    let dir = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/tmm-charts/passive"), PathBuf::from);
    std::fs::create_dir_all(&dir)?;
    let file = dir.join("passive_diagrams.svg");
    draw(&file, s, with_axial.as_ref().ok_or("no EA solution")?)?;
    let file2 = dir.join("passive_axial_stiffness.svg");
    draw_sensitivity(&file2, &p, &r)?;
    println!(
        "\nN, Q, M diagrams of every link written to {}",
        file.display()
    );
    println!(
        "X1 and the frame reactions against EA·L²/EI written to {}",
        file2.display()
    );
    println!("charts folder: {}", dir.display());
    Ok(())
}

/// Points of one diagram along a link, with both one-sided limits at every jump.
fn series(
    s: &Solution,
    link: Link,
    pick: fn(&tmm::kinetostatics::passive::InternalForces) -> f64,
) -> Vec<(f64, f64)> {
    let bp = s.breakpoints(link);
    let mut out = Vec::new();
    for w in bp.windows(2) {
        let (a, b) = (w[0], w[1]);
        for k in 0..=40 {
            let x = a + (b - a) * f64::from(k) / 40.0;
            let side = if k == 40 { Side::Before } else { Side::After };
            out.push((x, pick(&s.internal_in(State::Total, link, x, side))));
        }
    }
    out
}

fn draw(file: &std::path::Path, rigid: &Solution, axial: &Solution) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(file, (1350, 950)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Seed 002: internal forces of the group with a parallel coupler (blue: inextensible links, as in the paper; red: EA·L²/EI = 1000)",
        ("sans-serif", 17),
    )?;
    let panels = root.split_evenly((3, 3));
    type Pick = fn(&tmm::kinetostatics::passive::InternalForces) -> f64;
    let kinds: [(&str, Pick); 3] = [("N, N", |f| f.n), ("Q, N", |f| f.q), ("M, N·m", |f| f.m)];
    for (row, (label, pick)) in kinds.iter().enumerate() {
        for (col, link) in Link::ALL.iter().enumerate() {
            let a = series(rigid, *link, *pick);
            let b = series(axial, *link, *pick);
            let (mut lo, mut hi) = a
                .iter()
                .chain(&b)
                .fold((0.0f64, 0.0f64), |(lo, hi), &(_, v)| (lo.min(v), hi.max(v)));
            let pad = 0.08 * (hi - lo).max(1e-9);
            lo -= pad;
            hi += pad;
            let len = rigid.length(*link);
            let mut chart = ChartBuilder::on(&panels[3 * row + col])
                .caption(
                    format!(
                        "{} along {}",
                        label.split(',').next().unwrap_or(label),
                        link.name()
                    ),
                    ("sans-serif", 15),
                )
                .margin(8)
                .x_label_area_size(32)
                .y_label_area_size(52)
                .build_cartesian_2d(0.0..len, lo..hi)?;
            chart
                .configure_mesh()
                .x_desc("s from the link's start, m")
                .y_desc(*label)
                .label_style(("sans-serif", 11))
                .draw()?;
            chart.draw_series(LineSeries::new([(0.0, 0.0), (len, 0.0)], BLACK.mix(0.4)))?;
            chart.draw_series(LineSeries::new(a, BLUE.stroke_width(2)))?;
            chart.draw_series(LineSeries::new(b, RED.stroke_width(1)))?;
        }
    }
    root.present()?;
    Ok(())
}

/// X1 and the frame reactions as the links' axial stiffness grows, against the paper's
/// inextensible model (dashed).
fn draw_sensitivity(
    file: &std::path::Path,
    p: &PaperGroup,
    rigid: &PaperResult,
) -> Result<(), Box<dyn Error>> {
    let ratios: Vec<f64> = (0..=120)
        .map(|k| 10f64.powf(1.0 + 6.0 * f64::from(k) / 120.0))
        .collect();
    let mut curves: [Vec<(f64, f64)>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    for &ratio in &ratios {
        let q = p.solve(&Stiffness::with_axial(1.0, ratio / (L * L)))?;
        curves[0].push((ratio, q.x1));
        curves[1].push((ratio, q.r01n));
        curves[2].push((ratio, q.solution.reactions.r03.norm()));
    }
    let limits = [rigid.x1, rigid.r01n, rigid.solution.reactions.r03.norm()];
    let (lo, hi) = curves
        .iter()
        .flatten()
        .fold((0.0f64, 0.0f64), |(lo, hi), &(_, v)| (lo.min(v), hi.max(v)));
    let root = SVGBackend::new(file, (900, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Seed 002: the redundant X1 and the frame reactions against the links' axial stiffness",
            ("sans-serif", 17),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d((10.0..1e7).log_scale(), (lo - 20.0)..(hi + 20.0))?;
    chart
        .configure_mesh()
        .x_desc("EA·L²/EI (L = l3 + l4 = 0.35 m; dashed: inextensible links, as in the paper)")
        .y_desc("force, N")
        .draw()?;
    let colors = [BLUE, RED, GREEN];
    let names = ["X1 = R02n", "R01n", "|R03|"];
    for ((curve, limit), (color, name)) in
        curves.into_iter().zip(limits).zip(colors.iter().zip(names))
    {
        let c = *color;
        chart
            .draw_series(LineSeries::new(curve, c.stroke_width(2)))?
            .label(name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], c.stroke_width(2)));
        chart.draw_series(DashedLineSeries::new(
            [(10.0, limit), (1e7, limit)],
            6,
            4,
            c.into(),
        ))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
