//! The observed orders and error bounds of the work-precision charts, asserted from the same
//! functions that draw them (`tests/work_precision/`; the charts themselves are drawn by
//! `benches/examples/work_precision.rs`) and from the CSV files committed beside the charts in
//! `docs/charts/`.

pub(crate) mod dd;
#[allow(dead_code)] // the CSV writers serve the example
mod dynamics_data;
mod fit;
use crate::kinetostatics::general_solve;
#[allow(dead_code)] // the CSV writers serve the example
mod kinematics_data;
#[allow(dead_code)] // the CSV writers serve the example
mod kinetostatics_data;
mod rng;

use dynamics_data::{asymptotic, Line, MACHINES, METHODS};
use fit::{slope, Csv};

fn committed(name: &str) -> Csv {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/charts")
        .join(name);
    Csv::parse(&std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}")))
}

/// The observed order of a fixed-step line: the slope of log error against log h over its
/// asymptotic points.
fn order(l: &Line) -> f64 {
    let a = asymptotic(l);
    assert!(
        a.len() >= 4,
        "{} {}: too few asymptotic points",
        l.machine,
        l.method
    );
    let h: Vec<f64> = a.iter().map(|p| p.parameter).collect();
    let e: Vec<f64> = a.iter().map(|p| p.error).collect();
    slope(&h, &e)
}

/// The orders each fixed-step line must show: finite increments ≈ 1 everywhere; RK4 ≈ 4
/// where the right-hand side is smooth and where its kinks are stepped onto: the landing
/// gear's piecewise-linear load table, whose nodes it reports as kinks (measured 4.31, its
/// first asymptotic point still pre-asymptotic), and the saturating five-bar, whose two
/// servos leave saturation 0.29 ms apart, inside one step of every h ≥ 0.375 ms, each
/// servo's clamp its own kink argument, located one after the other (measured 4.17; 2.37
/// when the one argument was the product of their margins, which does not change sign across
/// a step that holds both switches).
fn check_orders(lines: &[Line]) {
    for l in lines {
        if l.method == METHODS[2] {
            continue;
        }
        let p = order(l);
        let (lo, hi) = match (l.method, l.machine) {
            ("finite increments", _) => (0.9, 1.1),
            ("RK4", m) if m == MACHINES[0] || m == MACHINES[2] => (3.7, 4.3),
            _ => (3.7, 4.4),
        };
        assert!(
            (lo..=hi).contains(&p),
            "{} on {}: observed order {p}, expected {lo}–{hi}",
            l.method,
            l.machine
        );
    }
}

#[test]
fn steppers_show_their_orders() {
    let lines = dynamics_data::work_precision(false).unwrap();
    assert_eq!(lines.len(), MACHINES.len() * METHODS.len());
    check_orders(&lines);
    // On the exact solution the adaptive method meets its tolerance (within a factor of 10)
    // and its error falls with it.
    let dp = lines
        .iter()
        .find(|l| l.machine == MACHINES[0] && l.method == METHODS[2])
        .unwrap();
    for p in &dp.points {
        assert!(
            p.error < 10.0 * p.parameter,
            "tol {}: error {}",
            p.parameter,
            p.error
        );
    }
    assert!(dp.points.last().unwrap().error < 1e-3 * dp.points[0].error);
    // The committed data are these runs: the same evaluations and errors (to a margin for
    // another machine's last-bit rounding in the elementary functions).
    let csv = committed("dynamics_work_precision.csv");
    for l in &lines {
        let key = [("machine", l.machine), ("method", l.method)];
        let errors = csv.select(&key, "error");
        let evals = csv.select(&key, "evaluations");
        assert_eq!(errors.len(), l.points.len(), "{} {}", l.machine, l.method);
        for ((p, e), n) in l.points.iter().zip(&errors).zip(&evals) {
            assert_eq!(p.evaluations as f64, *n, "{} {}", l.machine, l.method);
            assert!(
                (p.error - e).abs() <= 1e-6 * e.abs() + 1e-13,
                "{} {}: committed error {e}, now {}",
                l.machine,
                l.method,
                p.error
            );
        }
    }
}

#[test]
fn committed_dynamics_data_show_the_orders() {
    let csv = committed("dynamics_work_precision.csv");
    let lines: Vec<Line> = MACHINES
        .iter()
        .flat_map(|m| METHODS.iter().map(move |k| (*m, *k)))
        .map(|(machine, method)| {
            let key = [("machine", machine), ("method", method)];
            let col = |c| csv.select(&key, c);
            let (h, e, n, s) = (
                col("parameter"),
                col("error"),
                col("evaluations"),
                col("steps"),
            );
            Line {
                machine,
                method,
                points: (0..h.len())
                    .map(|i| dynamics_data::Point {
                        parameter: h[i],
                        steps: s[i] as usize,
                        evaluations: n[i] as usize,
                        error: e[i],
                        seconds: 0.0,
                    })
                    .collect(),
                reference_error: col("reference_error")[0],
            }
        })
        .collect();
    check_orders(&lines);
}

#[test]
fn stability_limits_on_the_chart_are_the_derived_ones() {
    let st = dynamics_data::stability().unwrap();
    for (zeta, c) in &st.fi_limits {
        let lim = dynamics_data::finite_increment_limit(*zeta);
        assert!(
            (c - lim).abs() < 1e-9 * lim,
            "ζ = {zeta}: crossing {c}, limit {lim}"
        );
    }
    for &(zeta, o, rho) in &st.finite_increments {
        let lim = dynamics_data::finite_increment_limit(zeta);
        if zeta == 0.0 {
            assert!(rho > 1.0, "ζ = 0, Ω = {o}: ρ = {rho}");
        } else if o < lim - 1e-9 {
            assert!(rho < 1.0, "ζ = {zeta}, Ω = {o}: ρ = {rho}");
        } else if o > lim + 1e-9 {
            assert!(rho > 1.0, "ζ = {zeta}, Ω = {o}: ρ = {rho}");
        }
    }
    // RK4's stability interval on the negative real axis ends at hλ ≈ −2.7853.
    assert!((st.rk4_limit + 2.785_29).abs() < 1e-4, "{}", st.rk4_limit);
    // The committed stability data cross 1 where the derived limits say.
    let fi = committed("stability_finite_increments.csv");
    let (z, o, r) = (
        fi.select(&[], "zeta"),
        fi.select(&[], "omega_h"),
        fi.select(&[], "spectral_radius"),
    );
    assert_eq!(z.len(), st.finite_increments.len());
    for i in 0..z.len() {
        let lim = dynamics_data::finite_increment_limit(z[i]);
        if z[i] > 0.0 && (o[i] - lim).abs() > 1e-9 {
            assert_eq!(r[i] < 1.0, o[i] < lim, "ζ = {}, Ω = {}", z[i], o[i]);
        }
    }
    let rk = committed("stability_rk4.csv");
    for (x, g) in rk
        .select(&[], "h_lambda")
        .iter()
        .zip(rk.select(&[], "growth"))
    {
        if *x < 0.0 {
            assert_eq!(g < 1.0, *x > -2.785, "hλ = {x}: |R| = {g}");
        }
    }
}

#[test]
fn double_double_is_far_more_accurate_than_f64() {
    use dd::Dd;
    let third = Dd::from(1.0) / Dd::from(3.0);
    let r = third * Dd::from(3.0) - Dd::from(1.0);
    assert!(r.to_f64().abs() < 1e-31, "{}", r.to_f64());
    // 0.1 is not exactly 1/10: its double-double residual shows the f64's own rounding.
    let tenth = Dd::from(1.0) / Dd::from(10.0);
    let d = (tenth - Dd::from(0.1)).to_f64();
    assert!(d != 0.0 && d.abs() < 1e-17, "{d}");
}

#[test]
fn dyad_errors_stay_within_condition_times_1e_14() {
    let check = |rows: &[kinetostatics_data::Row]| {
        for r in rows {
            assert!(
                r.error_per_condition <= 1e-14,
                "{} {} at δ = {}: error {} at condition {}",
                r.group,
                r.solver,
                r.delta,
                r.error,
                r.condition
            );
        }
        // The bound is not empty: near each singularity the error really grows.
        for g in kinetostatics_data::GROUPS {
            let near = rows
                .iter()
                .filter(|r| r.group == g && r.solver == "closed form")
                .map(|r| (r.condition, r.error))
                .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
            assert!(near.0 > 1e7 && near.1 > 1e-13, "{g}: {near:?}");
        }
    };
    check(&kinetostatics_data::sweep(4, false).unwrap());
    let csv = committed("kinetostatics.csv");
    let mut rows = Vec::new();
    for g in kinetostatics_data::GROUPS {
        for s in kinetostatics_data::SOLVERS {
            let key = [("group", g), ("solver", s)];
            let (d, c, e, q) = (
                csv.select(&key, "delta"),
                csv.select(&key, "condition"),
                csv.select(&key, "error"),
                csv.select(&key, "error_per_condition"),
            );
            assert_eq!(d.len(), kinetostatics_data::deltas().len());
            for i in 0..d.len() {
                rows.push(kinetostatics_data::Row {
                    group: g,
                    solver: s,
                    delta: d[i],
                    condition: c[i],
                    error: e[i],
                    error_per_condition: q[i],
                    ns_per_call: 0.0,
                });
            }
        }
    }
    check(&rows);
}

/// The orders the kinematics chart must show: 2 everywhere, except the one-sided formulas on
/// the slider-crank, whose end nodes sit at the dead centre φ1 = 0, where s‴ = 0 by symmetry
/// (s is even in φ1): the leading h² error term vanishes and the next one, h³, shows.
fn check_kinematics(rows: &[kinematics_data::Row]) {
    for mech in kinematics_data::MECHANISMS {
        for q in kinematics_data::QUANTITIES {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.0 == mech && r.1 == q && r.2 >= 96)
                .map(|r| (r.2 as f64, r.3))
                .collect();
            assert!(pts.len() >= 4);
            let n: Vec<f64> = pts.iter().map(|p| p.0).collect();
            let e: Vec<f64> = pts.iter().map(|p| p.1).collect();
            let p = -slope(&n, &e);
            let expected = if mech == kinematics_data::MECHANISMS[1] && q == "3-point ends" {
                3.0
            } else {
                2.0
            };
            assert!(
                (p - expected).abs() <= 0.1,
                "{mech}, {q}: observed order {p}, expected {expected}"
            );
        }
    }
}

#[test]
fn numerical_differentiation_and_integration_are_second_order() {
    let rows = kinematics_data::sweep().unwrap();
    check_kinematics(&rows);
    let csv = committed("kinematics.csv");
    let committed_rows: Vec<kinematics_data::Row> = rows
        .iter()
        .map(|r| {
            let n = r.2.to_string();
            let e = csv.select(
                &[("mechanism", r.0), ("quantity", r.1), ("positions", &n)],
                "error",
            );
            assert_eq!(e.len(), 1, "{r:?}");
            assert!(
                (e[0] - r.3).abs() <= 1e-6 * r.3 + 1e-13,
                "{r:?}: committed {}",
                e[0]
            );
            (r.0, r.1, r.2, e[0])
        })
        .collect();
    check_kinematics(&committed_rows);
}
