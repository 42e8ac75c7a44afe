//! `tmm synth`'s adapter to `tmm::synthesis`: a requirement ([`crate::design::Request`]) in,
//! the description's JSON and a report out. The report's "checked by the engine" part and the
//! misses come from the description written, planned and solved again ([`super::load`]),
//! not from the synthesis's own figures.

use std::f64::consts::{PI, TAU};
use std::time::Duration;

use tmm::kinematics::Motion;
use tmm::linkage::Output;
use tmm::synthesis::{
    crank_rocker, crank_rocker_through, function_generator, path_generator, shaper,
    six_bar_path_generator, slider_crank, CrankRockerRequirement, FrameChoice, FunctionRequirement,
    OffsetChoice, Options, PathOptions, PathRequirement, ShaperRequirement, SliderCrankRequirement,
    Spacing, Synthesis, Timing as PathTiming,
};

use super::{failure, grashof_text, load, Machine};
use crate::design::{
    DesignReport, Designed, Dimension, FunctionRequest, Kind, MissRow, Misses, PathMechanism,
    PathRequest, Request, Timing,
};
use crate::model::Failure;

/// Points of the structural error curve of a function generator, for its largest error.
const CURVE_POINTS: usize = 1001;
/// Rows of the structural error shown.
const CURVE_ROWS: usize = 11;

/// The library's error as a sentence, with the option that sets the parameter it names and,
/// for an angle, its values in degrees (the command line takes degrees, the library rad).
fn synth_failure(e: &tmm::Error, flags: &[(&str, &str)]) -> Failure {
    let f = failure(e);
    let (name, degrees) = match e {
        tmm::Error::OutOfRange {
            name,
            value,
            min,
            max,
            ..
        } => (
            *name,
            angle_name(name).then(|| {
                format!(
                    "{} lies outside {} to {}",
                    deg(*value),
                    deg_bound(*min),
                    deg_bound(*max)
                )
            }),
        ),
        tmm::Error::Infeasible {
            parameter,
            required,
            reachable,
        } => (
            *parameter,
            angle_name(parameter).then(|| {
                format!(
                    "{} asked for, {} reachable",
                    deg(*required),
                    deg(*reachable)
                )
            }),
        ),
        tmm::Error::NonFinite { name, .. } | tmm::Error::NonPositive { name, .. } => (*name, None),
        _ => ("", None),
    };
    let flag = flags
        .iter()
        .find(|(n, _)| !name.is_empty() && name.starts_with(n))
        .map(|(_, flag)| *flag);
    let hint = match (flag, degrees) {
        (Some(flag), Some(d)) => Some(format!("set by {flag}; in degrees: {d}")),
        (Some(flag), None) => Some(format!("set by {flag}")),
        (None, Some(d)) => Some(format!("in degrees: {d}")),
        (None, None) => None,
    };
    match hint {
        Some(h) => f.hint(h),
        None => f,
    }
}

/// Whether the library's parameter `name` is an angle (rad), whose values the hint repeats in
/// degrees ("timing (one crank angle per point)" is a count, not an angle).
fn angle_name(name: &str) -> bool {
    name.contains("(rad)")
        || name.contains("swing")
        || name.contains("transmission")
        || name.starts_with("crank angle")
        || name.starts_with("rocker angle")
}

/// An angle in degrees, four decimals; in scientific notation from 10⁶° (an option of
/// 1e308° read back in degrees was 309 digits).
fn deg(rad: f64) -> String {
    let d = rad.to_degrees();
    if d.abs() >= 1e6 {
        format!("{d:.4e}°")
    } else {
        format!("{d:.4}°")
    }
}

fn deg_bound(rad: f64) -> String {
    if rad.is_infinite() {
        if rad > 0.0 { "∞" } else { "−∞" }.to_owned()
    } else {
        deg(rad)
    }
}

/// The library's parameter names and the options of `tmm synth` that set them.
const COMMON_FLAGS: [(&str, &str); 2] = [
    ("min_transmission_angle", "--min-transmission"),
    ("minimum transmission angle", "--min-transmission"),
];

fn flags_of(kind: &Kind) -> Vec<(&'static str, &'static str)> {
    let own: &[(&str, &str)] = match kind {
        Kind::CrankRocker { .. } => &[
            ("rocker", "--rocker"),
            ("swing", "--swing"),
            ("K", "-K/--time-ratio"),
            ("frame", "--frame"),
        ],
        Kind::SliderCrank { .. } => &[
            ("stroke", "--stroke"),
            ("K", "-K/--time-ratio"),
            ("offset", "--offset"),
        ],
        Kind::Shaper { .. } => &[
            ("stroke", "--stroke"),
            ("K", "-K/--time-ratio"),
            ("centre_distance", "--centre-distance"),
            ("centre distance", "--centre-distance"),
        ],
        Kind::Through { .. } => &[
            ("frame", "--frame"),
            ("positions", "--at (two or three pairs φ,ψ)"),
            ("crank angle", "--at"),
            ("rocker angle", "--at"),
        ],
        Kind::Function(_) => &[
            ("x0", "--x"),
            ("x1", "--x"),
            ("crank angle", "--crank"),
            ("rocker angle", "--rocker"),
            ("frame", "--frame"),
            ("N", "--least-squares"),
            ("f(x", "--function and --x"),
        ],
        Kind::Path(PathRequest {
            mechanism: PathMechanism::SixBar,
            ..
        }) => &[
            (
                "points",
                "the points file (at least 8 points, with crank angles)",
            ),
            (
                "timing",
                "the points file's crank angles (its third CSV column, or \"crank\" in JSON)",
            ),
            ("population", "--budget"),
        ],
        Kind::Path(_) => &[
            (
                "points",
                "the points file (at least 9 points; 5 with crank angles)",
            ),
            (
                "timing",
                "the points file's crank angles (its third CSV column, or \"crank\" in JSON)",
            ),
            ("population", "--budget"),
        ],
    };
    own.iter().chain(&COMMON_FLAGS).copied().collect()
}

/// Synthesises the mechanism asked for, writes its description and checks it by the engine.
///
/// # Errors
/// The library's error for a requirement no mechanism of the kind meets (naming the
/// parameter and by how much), with the option that sets it.
pub fn synthesise(request: &Request, progress: &mut dyn FnMut(&str)) -> Result<Designed, Failure> {
    let flags = flags_of(&request.kind);
    let f = |e: tmm::Error| synth_failure(&e, &flags);
    let options = Options::default().with_min_transmission_angle(request.min_transmission);
    let mut notes = Vec::new();
    let (synthesis, misses): (Synthesis, Option<MissesOf>) = match &request.kind {
        Kind::CrankRocker {
            rocker,
            swing,
            time_ratio,
            frame,
        } => {
            let need = CrankRockerRequirement {
                rocker: *rocker,
                swing: *swing,
                time_ratio: *time_ratio,
                frame: frame.map_or(FrameChoice::BestTransmission, FrameChoice::Length),
            };
            if frame.is_none() {
                notes.push("the frame O1O3 chosen for the largest γ_min".to_owned());
            }
            (crank_rocker(&need, &options).map_err(f)?, None)
        }
        Kind::SliderCrank {
            stroke,
            time_ratio,
            offset,
        } => {
            let need = SliderCrankRequirement {
                stroke: *stroke,
                time_ratio: *time_ratio,
                offset: offset.map_or(OffsetChoice::BestTransmission, OffsetChoice::Given),
            };
            if offset.is_none() {
                notes.push("the offset chosen for the largest γ_min".to_owned());
            }
            (slider_crank(&need, &options).map_err(f)?, None)
        }
        Kind::Shaper {
            stroke,
            time_ratio,
            centre_distance,
        } => {
            let need = ShaperRequirement {
                stroke: *stroke,
                time_ratio: *time_ratio,
                centre_distance: *centre_distance,
            };
            (shaper(&need, &options).map_err(f)?, None)
        }
        Kind::Through { frame, positions } => {
            let s = crank_rocker_through(*frame, positions, &options).map_err(f)?;
            (s, Some(MissesOf::Rocker(positions.clone())))
        }
        Kind::Function(r) => function(r, &options, &flags, &mut notes)?,
        Kind::Path(p) => path(p, request.min_transmission, &flags, &mut notes, progress)?,
    };
    let json = synthesis.linkage.to_json().map_err(f)?;
    // The description as written, read back and planned: what every other command sees.
    let machine = load(&json)?;
    let misses = match misses {
        None => None,
        Some(MissesOf::Done(m)) => Some(m),
        Some(MissesOf::Rocker(pairs)) => Some(rocker_misses(&machine, &pairs)),
        Some(MissesOf::Coupler(targets, angles)) => {
            Some(coupler_misses(&machine, &targets, &angles))
        }
    };
    let r = &synthesis.report;
    Ok(Designed {
        json,
        report: DesignReport {
            kind: r.kind.to_owned(),
            dimensions: r
                .dimensions
                .iter()
                .map(|(name, value)| Dimension {
                    name: name.trim_end_matches(" (rad)").to_owned(),
                    value: *value,
                    angle: name.ends_with("(rad)"),
                })
                .collect(),
            time_ratio: r.time_ratio,
            stroke: r.stroke,
            angular_output: matches!(synthesis.linkage.output, Some(Output::Angle(_))),
            min_transmission: (r.min_transmission_angle, r.min_transmission_at),
            grashof: r.grashof.map(|g| grashof_text(g).to_owned()),
            checked: machine.structure(),
            misses,
            notes,
        },
    })
}

/// The most precision points listed one by one; a longer list shows its first and last
/// [`LISTED_POINTS`]` / 2` and its count.
const LISTED_POINTS: usize = 8;

/// The precision points as a line of the report: each with the fewest decimals (at least 6)
/// that tell the listed points apart — a least-squares fit over 10⁶ points at Chebyshev
/// spacing crowds its first points within 10⁻¹² of x0, where 6 decimals read them all
/// alike; a long list is its first and last few and its count.
fn precision_points(xs: &[f64]) -> String {
    let half = LISTED_POINTS / 2;
    let shown: Vec<f64> = if xs.len() > LISTED_POINTS {
        xs[..half]
            .iter()
            .chain(&xs[xs.len() - half..])
            .copied()
            .collect()
    } else {
        xs.to_vec()
    };
    let texts = distinct_texts(&shown);
    if xs.len() > LISTED_POINTS {
        format!(
            "precision points x = {}, …, {} ({} points)",
            texts[..half].join(", "),
            texts[half..].join(", "),
            xs.len()
        )
    } else {
        format!("precision points x = {}", texts.join(", "))
    }
}

/// `xs` with the fewest decimals, from 6 up, at which no two distinct values read the same;
/// values so close that no fixed number of decimals parts them (or values far from 1) are
/// written in full, the shortest text that reads back to each.
fn distinct_texts(xs: &[f64]) -> Vec<String> {
    let apart = |texts: &[String]| {
        xs.iter().zip(texts).all(|(x, t)| {
            xs.iter()
                .zip(texts)
                .all(|(y, u)| x.to_bits() == y.to_bits() || t != u)
        })
    };
    for decimals in 6..=17 {
        let texts: Vec<String> = xs.iter().map(|x| format!("{x:.decimals$}")).collect();
        if apart(&texts) {
            return texts;
        }
    }
    xs.iter().map(|x| format!("{x}")).collect()
}

/// The function generator, its notes (precision points, coefficients, the largest structural
/// error) and the structural error across the range as the misses.
fn function(
    r: &FunctionRequest,
    options: &Options,
    flags: &[(&str, &str)],
    notes: &mut Vec<String>,
) -> Result<(Synthesis, Option<MissesOf>), Failure> {
    let FunctionRequest {
        function,
        x,
        crank,
        rocker,
        frame,
        least_squares,
    } = r;
    let f = |e: tmm::Error| synth_failure(&e, flags);
    let need = FunctionRequirement {
        x_range: *x,
        crank_range: *crank,
        rocker_range: *rocker,
        frame: *frame,
        spacing: least_squares.map_or(Spacing::Chebyshev, Spacing::LeastSquares),
    };
    let func = |v: f64| function.eval(v);
    let g = function_generator(func, &need, options).map_err(&f)?;
    notes.push(format!(
        "y = {}, x from {} to {}: {}",
        function.formula(),
        x[0],
        x[1],
        match least_squares {
            None => "three precision points at Chebyshev spacing".to_owned(),
            Some(n) => format!("least squares over {n} points at Chebyshev spacing"),
        }
    ));
    notes.push(precision_points(&g.precision_x));
    notes.push(format!(
        "Freudenstein's coefficients K1 = {:.6}, K2 = {:.6}, K3 = {:.6}",
        g.coefficients[0], g.coefficients[1], g.coefficients[2]
    ));
    // The structural error by the engine: the largest over a fine grid, and a few
    // rows to read.
    let curve = g.structural_error(func, CURVE_POINTS).map_err(&f)?;
    let worst = curve
        .iter()
        .max_by(|a, b| a.error.abs().total_cmp(&b.error.abs()))
        .copied();
    if let Some(w) = worst {
        notes.push(format!(
            "largest structural error {:.3e} at x = {:.4} ({:.3} % of the range of y), over {CURVE_POINTS} points by the engine",
            w.error,
            w.x,
            100.0 * w.error.abs() / (g.y_range[1] - g.y_range[0]).abs()
        ));
    }
    let rows = g
        .structural_error(func, CURVE_ROWS)
        .map_err(&f)?
        .into_iter()
        .map(|p| MissRow {
            at: format!("x = {:.4}", p.x),
            wanted: vec![p.wanted],
            reached: vec![p.generated],
            miss: p.error.abs(),
        })
        .collect();
    let misses = Misses {
        title: "the structural error: y wanted and generated (the rocker's angle by \
                the engine, mapped back to y)"
            .to_owned(),
        quantities: vec!["y".to_owned()],
        unit: "",
        rows,
    };
    Ok((g.synthesis, Some(MissesOf::Done(misses))))
}

/// What the misses are measured against, before the description is read back.
enum MissesOf {
    /// Already by the engine (the function generator's structural error).
    Done(Misses),
    /// (φ, ψ) pairs: the rocker's angle at each crank angle.
    Rocker(Vec<(f64, f64)>),
    /// Target points and the crank angles the design reaches them at.
    Coupler(Vec<[f64; 2]>, Vec<f64>),
}

/// "φ = 30.000000°": a crank angle in degrees in [0, 360), to the digits that pin a point
/// of a 1 m linkage to 2e-8 m.
fn angle_label(phi: f64) -> String {
    let d = format!("{:.6}", phi.to_degrees().rem_euclid(360.0));
    if d == "360.000000" {
        "φ = 0.000000°".to_owned()
    } else {
        format!("φ = {d}°")
    }
}

/// The difference of two angles, rad in [−π, π).
fn angle_difference(a: f64, b: f64) -> f64 {
    (a - b + PI).rem_euclid(TAU) - PI
}

fn rocker_misses(m: &Machine, pairs: &[(f64, f64)]) -> Misses {
    let rocker = Output::Angle("rocker".to_owned());
    let rows = pairs
        .iter()
        .map(|&(phi, psi)| {
            let got = m
                .plan
                .output(&rocker, Motion::fixed(phi))
                .map_or(f64::NAN, |o| o.value);
            let d = angle_difference(got, psi);
            MissRow {
                at: angle_label(phi),
                wanted: vec![psi],
                reached: vec![psi + d],
                miss: d.abs(),
            }
        })
        .collect();
    Misses {
        title: "the rocker's angle ψ wanted and reached (by the engine) at each crank angle"
            .to_owned(),
        quantities: vec!["ψ".to_owned()],
        unit: "deg",
        rows,
    }
}

fn coupler_misses(m: &Machine, targets: &[[f64; 2]], angles: &[f64]) -> Misses {
    let rows = targets
        .iter()
        .zip(angles)
        .map(|(t, &phi)| {
            let got = m
                .plan
                .kinematics(Motion::fixed(phi))
                .and_then(|k| k.point("P"))
                .map_or([f64::NAN; 2], |p| [p.p.x, p.p.y]);
            MissRow {
                at: angle_label(phi),
                wanted: t.to_vec(),
                reached: got.to_vec(),
                miss: (got[0] - t[0]).hypot(got[1] - t[1]),
            }
        })
        .collect();
    Misses {
        title: "the target points and the coupler point P reached (by the engine) at the \
                design's crank angles"
            .to_owned(),
        quantities: vec!["x".to_owned(), "y".to_owned()],
        unit: "m",
        rows,
    }
}

/// A path search that found no design within its budget, said by its budget as asked: the
/// library's sentence up to what it spent, without the seconds it took, which differ from
/// one run to the next (the same command gives the same sentence).
fn no_design(method: &str, problem: &str, p: &PathRequest) -> Failure {
    let what = problem.find(") in ").map_or(problem, |k| &problem[..=k]);
    // A huge --time (1e308) in exponent form, not as a run of 309 digits.
    let time = p.time.map_or_else(String::new, |t| {
        if t < 1e15 {
            format!(" or the {t} s of --time")
        } else {
            format!(" or the {t:e} s of --time")
        }
    });
    Failure::new(format!(
        "{method}: {what}, within the {} candidate evaluations of --budget{time}",
        p.budget
    ))
    .hint(if p.time.is_some() {
        "raise --budget or --time, try another --seed, or lower --min-transmission"
    } else {
        "raise --budget, try another --seed, or lower --min-transmission"
    })
}

/// The path search: the best design, and the targets with its crank angles at them.
fn path(
    p: &PathRequest,
    gamma: f64,
    flags: &[(&str, &str)],
    notes: &mut Vec<String>,
    progress: &mut dyn FnMut(&str),
) -> Result<(Synthesis, Option<MissesOf>), Failure> {
    let f = |e: tmm::Error| synth_failure(&e, flags);
    let req = PathRequirement {
        points: p.points.clone(),
        timing: match &p.timing {
            Timing::Free => PathTiming::Free,
            Timing::Prescribed(d) => PathTiming::Prescribed(d.clone()),
            Timing::Closed => PathTiming::ClosedCurve,
        },
    };
    if let Some(t) = p.time
        && !(t.is_finite() && t > 0.0)
    {
        return Err(Failure::new(format!(
            "the search's time bound must be a positive number of seconds, got {}",
            crate::model::typed(t)
        ))
        .hint("set by --time"));
    }
    // Without --time the evaluations alone bound the search (the library's default bound
    // of 60 s of wall clock lifted), so that its design does not depend on the machine.
    let max_time = p
        .time
        .map_or(Duration::MAX, |t| Duration::from_secs_f64(t.min(1e6)));
    let mut opts = PathOptions::default()
        .with_min_transmission_angle(gamma)
        .with_max_evaluations(p.budget)
        .with_max_time(max_time)
        .with_designs(p.designs);
    if let Some(seed) = p.seed {
        opts = opts.with_seed(seed);
    }
    let report = |pr: &tmm::synthesis::Progress| {
        progress(&format!(
            "path search: generation {}, {} of {} evaluations, best mean miss {:.3e} path sizes",
            pr.generation, pr.evaluations, p.budget, pr.best
        ));
        true
    };
    let designs = match p.mechanism {
        PathMechanism::FourBar => path_generator(&req, &opts, report),
        PathMechanism::SixBar => six_bar_path_generator(&req, &opts, report),
    }
    .map_err(|e| match e {
        // The search ran out of its budget without a design that meets the constraints.
        tmm::Error::NoMechanism { method, problem } => no_design(method, &problem, p),
        e => {
            let failure = f(e);
            // A budget below what the search needs to start (its first generation).
            if failure.message.contains("evaluations") && failure.hint.is_none() {
                failure.hint("raise --budget")
            } else {
                failure
            }
        }
    })?;
    let Some(best) = designs.first() else {
        return Err(Failure::new("the path search returned no design")
            .hint("raise --budget, or try another --seed"));
    };
    notes.push(format!(
        "seed {}, budget {} evaluations: {} design{} found, the best written",
        opts.seed,
        p.budget,
        designs.len(),
        if designs.len() == 1 { "" } else { "s" }
    ));
    for (k, d) in designs.iter().enumerate() {
        notes.push(format!(
            "design {}: mean miss {:.4e} m, largest {:.4e} m, γ_min {:.2}°",
            k + 1,
            d.mean_error,
            d.max_error,
            d.synthesis.report.min_transmission_angle.to_degrees()
        ));
    }
    Ok((
        best.synthesis.clone(),
        Some(MissesOf::Coupler(
            p.points.clone(),
            best.crank_angles.clone(),
        )),
    ))
}
