//! The course table by columns: `Plan::table` (one solver, cells written in place) against
//! `Table::of` over analyses kept one by one, bit for bit, on every bundled linkage with and
//! without friction; the friction columns against the power balance read from the table's
//! own kinematic and balance columns; the table staying rectangular and finite (a row that
//! is short or holds a non-finite value is left out); every cell of every bundled linkage's
//! table finite, moving and at rest, with and without friction and loads; and the balancing
//! value by virtual power at rest (by the velocity analogues) against the chain's.

use std::f64::consts::TAU;
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, run_cycle, Cells, Friction, Inputs, Linkage, Plan, Table, Tabulate};

fn turn(plan: &Plan, n: usize) -> Vec<Motion> {
    let q0 = plan.reference_input();
    let step = if plan.input_is_crank() {
        TAU
    } else {
        plan.size() * 0.05
    };
    (0..n)
        .map(|k| Motion::new(q0 + step * k as f64 / n as f64, 7.0, -3.0))
        .collect()
}

/// Every bundled linkage of one input, frictionless and (where the plan takes it) with
/// Coulomb friction in every joint.
fn plans() -> Vec<(String, Plan)> {
    let mut out = Vec::new();
    for l in bundled::all() {
        let Ok(plan) = Plan::new(&l) else { continue };
        if plan.input_count() != 1 {
            continue;
        }
        let mut rough = l.clone();
        rough.friction = Some(Friction::pin(0.15, 0.02 * plan.size()));
        out.push((l.name.clone(), plan));
        if let Ok(p) = Plan::new(&rough) {
            out.push((format!("{} with friction", l.name), p));
        }
    }
    out
}

fn same_bits(a: &Table, b: &Table) -> bool {
    a.columns.len() == b.columns.len()
        && a.columns.iter().zip(&b.columns).all(|(x, y)| {
            x.name == y.name
                && x.values.len() == y.values.len()
                && x.values
                    .iter()
                    .zip(&y.values)
                    .all(|(u, v)| u.to_bits() == v.to_bits())
        })
}

#[test]
fn plan_table_equals_the_table_of_kept_analyses_bit_for_bit() {
    let mut tables = 0;
    for (name, plan) in plans() {
        let inputs = turn(&plan, 48);
        let kept = run_cycle(&inputs, |i| plan.analyse(i));
        let fast = plan.table(&inputs);
        assert!(same_bits(&fast, &Table::of(&kept)), "{name}");
        // One row per position that solved, and each row is what `row()` names and gives.
        assert_eq!(
            fast.len(),
            kept.iter().filter(|r| r.is_ok()).count(),
            "{name}"
        );
        if let Some(k) = kept.iter().position(|r| r.is_ok()) {
            // The first solved position is the table's first row.
            let row = kept[k].as_ref().unwrap().row().unwrap();
            assert_eq!(row.len(), fast.columns.len(), "{name}");
            for ((n, v), c) in row.iter().zip(&fast.columns) {
                assert_eq!((n, v.to_bits()), (&c.name, c.values[0].to_bits()), "{name}");
            }
        }
        tables += 1;
    }
    assert!(tables >= 8, "only {tables} bundled plans tabulated");
}

#[test]
fn friction_columns_close_the_power_balance_and_only_with_friction() {
    let mut checked = 0;
    for (name, plan) in plans() {
        let table = plan.table(turn(&plan, 36));
        if table.is_empty() {
            continue; // a plan whose friction the solve refuses (a triad's joints)
        }
        let lost: Vec<&str> = table
            .columns
            .iter()
            .map(|c| c.name.as_str())
            .filter(|n| n.starts_with("P_lost"))
            .collect();
        if !plan.has_friction() {
            assert!(
                lost.is_empty() && table.column("P_drive [W]").is_none(),
                "{name}"
            );
            continue;
        }
        // One column per joint, then the total.
        assert_eq!(lost.len(), plan.joint_names().len() + 1, "{name}");
        let total = table.column("P_lost [W]").unwrap();
        let p_drive = table.column("P_drive [W]").unwrap();
        // The drive's power from the table's own columns: M_b·ω1 (F_b·v for a slider).
        let (q_name, q_rate, q_accel, b) = if plan.input_is_crank() {
            (
                "phi_in [rad]",
                "phi_in' [rad/s]",
                "phi_in'' [rad/s^2]",
                "Mb [N·m, + counter-clockwise]",
            )
        } else {
            (
                "s_in [m]",
                "s_in' [m/s]",
                "s_in'' [m/s^2]",
                "Fb [N, + along the guide]",
            )
        };
        let (w, mb) = (table.column(q_rate).unwrap(), table.column(b).unwrap());
        let (q, acc) = (
            table.column(q_name).unwrap(),
            table.column(q_accel).unwrap(),
        );
        for r in 0..table.len() {
            let per_joint: f64 = plan
                .joint_names()
                .iter()
                .map(|j| table.column(&format!("P_lost({j}) [W]")).unwrap()[r])
                .sum();
            let drive = mb[r] * w[r];
            let scale = drive.abs().max(total[r]).max(1e-9);
            assert!(
                per_joint >= 0.0 && (per_joint - total[r]).abs() <= 1e-12 * scale,
                "{name} row {r}"
            );
            // The drive's column is M_b·ω1 (F_b·v), and η follows from the two columns as
            // `Analysis::efficiency` gives it, where it has a value.
            assert!(
                (p_drive[r] - drive).abs() <= 1e-12 * scale,
                "{name} row {r}"
            );
            let a = plan.analyse(Motion::new(q[r], w[r], acc[r])).unwrap();
            let e = a.efficiency().unwrap();
            match e.eta {
                Some(eta) => assert!(
                    p_drive[r] > 0.0
                        && (eta * p_drive[r] - (p_drive[r] - total[r])).abs() <= 1e-9 * scale,
                    "{name} row {r}"
                ),
                None => assert!(p_drive[r] <= 0.0, "{name} row {r}"),
            }
        }
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} plans with friction");
}

/// A position with `n` cells.
struct Cellular(usize);

impl Tabulate for Cellular {
    fn cells(&self, out: &mut impl Cells) {
        for k in 0..self.0 {
            out.cell(|| format!("c{k} [-]"), k as f64);
        }
    }
}

#[test]
fn a_table_stays_rectangular_and_finite() {
    let mut t = Table::default();
    assert!(t.push(&Cellular(3)));
    assert!(!t.push(&Cellular(2))); // short: left out
    assert!(t.push(&Cellular(5))); // long: the extra cells are dropped
    assert!(!t.push(&Filled(f64::NAN))); // no value: left out
    assert!(!t.push(&Filled(f64::INFINITY)));
    assert!(t.push(&Filled(7.0)));
    assert_eq!(t.columns.len(), 3);
    assert!(t.columns.iter().all(|c| c.values.len() == 3));
    assert_eq!(t.columns[2].values, [2.0, 2.0, 7.0]);
    let mut csv = Vec::new();
    t.write_csv(&mut csv).unwrap();
    assert_eq!(
        String::from_utf8(csv).unwrap(),
        "c0 [-],c1 [-],c2 [-]\n0,1,2\n0,1,2\n0,1,7\n"
    );
    // `Table::of` keeps the same rule: the rows held are those `push` holds.
    let rows = [
        Ok(Cellular(3)),
        Ok(Cellular(1)),
        Err(tmm::Error::Overflow { what: "x" }),
        Ok(Cellular(4)),
    ];
    let of = Table::of(&rows);
    assert_eq!(of.len(), 2);
    // A table with no row held has no columns, as a table of no positions.
    let mut none = Table::default();
    assert!(!none.push(&Filled(f64::NAN)));
    assert!(none.columns.is_empty() && none.to_text(3).is_empty());
    assert!(Table::of(&[Ok(Filled(f64::NAN))]).columns.is_empty());
    assert!(of.columns.iter().all(|c| c.values == [c.values[0]; 2]));
}

/// A position of three cells, the last one `self.0`.
struct Filled(f64);

impl Tabulate for Filled {
    fn cells(&self, out: &mut impl Cells) {
        out.cell(|| "c0 [-]".into(), 0.0);
        out.cell(|| "c1 [-]".into(), 1.0);
        out.cell(|| "c2 [-]".into(), self.0);
    }
}

/// Every bundled description file (`linkages/*.json`, the two-input five-bar robot and the
/// ready mechanisms' files among them), by its file name.
fn bundled_files() -> Vec<(String, Linkage)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("linkages");
    let mut out: Vec<(String, Linkage)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, Linkage::from_json(&text).unwrap())
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// The variants of one description: as written and with no loads at all (no external load,
/// no mass, no gravity), each frictionless and with Coulomb friction in every joint.
fn variants(name: &str, l: &Linkage) -> Vec<(String, Linkage)> {
    let mut bare = l.clone();
    bare.loads.clear();
    bare.gravity = [0.0, 0.0];
    for link in &mut bare.links {
        link.mass = None;
    }
    let mut out = Vec::new();
    for (what, base) in [("loaded", l.clone()), ("no loads", bare)] {
        let size = Plan::new(&base).map_or(1.0, |p| p.size());
        let mut smooth = base.clone();
        smooth.friction = None;
        let mut rough = base;
        rough.friction = Some(Friction::pin(0.15, 0.02 * size));
        out.push((format!("{name}, {what}"), smooth));
        out.push((format!("{name}, {what}, friction"), rough));
    }
    out
}

/// Positions of a plan about its reference pose: `n` steps over a turn (a crank) or a
/// twentieth of its size (a slider), each input at the given rate and acceleration.
fn positions(plan: &Plan, n: usize, rate: f64, accel: f64) -> Vec<Inputs> {
    let q0 = plan.reference_inputs();
    let span = |k: usize| {
        if k == 0 && plan.input_is_crank() {
            0.6
        } else {
            0.02 * plan.size()
        }
    };
    (0..n)
        .map(|k| {
            let t = (k as f64 / n as f64 * TAU).sin();
            let m: Vec<Motion> = q0
                .iter()
                .enumerate()
                .map(|(i, &q)| Motion::new(q + span(i) * t, rate, accel))
                .collect();
            Inputs::from_slice(&m).unwrap()
        })
        .collect()
}

fn all_finite(t: &Table) -> Result<(), String> {
    for c in &t.columns {
        if let Some(v) = c.values.iter().find(|v| !v.is_finite()) {
            return Err(format!("{} holds {v}", c.name));
        }
    }
    if format!("{t:?}").contains("NaN") || format!("{t:?}").contains("inf") {
        return Err("its Debug shows a non-finite number".into());
    }
    Ok(())
}

#[test]
fn every_cell_of_every_bundled_table_is_finite_moving_and_at_rest() {
    let mut tables = 0;
    for (file, l) in bundled_files() {
        for (name, linkage) in variants(&file, &l) {
            let Ok(plan) = Plan::new(&linkage) else {
                continue;
            };
            // Moving, at rest, and at rest accelerating.
            for (rate, accel) in [(7.0, -3.0), (-2.0, 0.0), (0.0, 0.0), (0.0, 5.0)] {
                let inputs = positions(&plan, 24, rate, accel);
                let kept: Vec<_> = inputs.iter().map(|&i| plan.analyse(i)).collect();
                let ok = kept.iter().filter(|r| r.is_ok()).count();
                let what = format!("{name} at rate {rate}, acceleration {accel}");
                for (how, t) in [
                    ("plan.table", plan.table(inputs.iter().copied())),
                    ("Table::of", Table::of(&kept)),
                    ("course_table", plan.course_table(&kept)),
                ] {
                    all_finite(&t).unwrap_or_else(|e| panic!("{what}, {how}: {e}"));
                    // Every cell has a value at every position: no position that analysed is
                    // left out of the table.
                    assert_eq!(t.len(), ok, "{what}, {how}");
                }
                if ok > 0 {
                    tables += 1;
                }
            }
        }
    }
    assert!(tables >= 200, "only {tables} tables");
}

#[test]
fn at_rest_the_balance_by_virtual_power_is_the_statics_virtual_work() {
    let mut checked = 0;
    let mut worst = 0.0f64;
    for (file, l) in bundled_files() {
        for (name, linkage) in variants(&file, &l) {
            let Ok(plan) = Plan::new(&linkage) else {
                continue;
            };
            if plan.input_count() != 1 {
                continue;
            }
            let mut smooth = linkage.clone();
            smooth.friction = None;
            let frictionless = Plan::new(&smooth).unwrap();
            for inputs in positions(&plan, 24, 0.0, 4.0) {
                let Ok(a) = plan.analyse(inputs) else {
                    continue;
                };
                let c = a.power_check().unwrap();
                // The chain's balance against the virtual work by the velocity analogues.
                let err = (c.chain - c.virtual_power).abs() / c.scale.max(f64::MIN_POSITIVE);
                assert!(err <= 1e-9, "{name} at {inputs:?}: {c:?}");
                worst = worst.max(err);
                // At rest no joint slides or turns on another: friction takes no part, and
                // the balance is the frictionless one.
                let b = frictionless.analyse(inputs).unwrap().balances()[0].value;
                assert!(
                    (b - c.chain).abs() <= 1e-12 * c.scale,
                    "{name}: {b} against {}",
                    c.chain
                );
                assert_eq!(a.lost_power(), 0.0, "{name}");
                checked += 1;
            }
        }
    }
    assert!(checked >= 1000, "only {checked} positions");
    eprintln!("at rest: {checked} positions, worst relative error {worst:.1e}");
}

mod hostile {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(160))]

        /// Hostile input values, rates and accelerations on every bundled linkage (with and
        /// without friction and loads): whatever analyses, the tables hold finite numbers only.
        #[test]
        fn tables_hold_finite_numbers_whatever_the_inputs(
            pick in 0usize..1000,
            values in proptest::collection::vec(
                prop_oneof![
                    Just(0.0), Just(-0.0), Just(1e-300), Just(5e-324), Just(1e150), Just(-1e300),
                    Just(f64::MAX), Just(f64::MIN_POSITIVE), -10.0..10.0f64, -1e6..1e6f64,
                ],
                6,
            ),
        ) {
            let files = bundled_files();
            let (file, l) = &files[pick % files.len()];
            let vs = variants(file, l);
            let (name, linkage) = &vs[(pick / files.len()) % vs.len()];
            let Ok(plan) = Plan::new(linkage) else { return Ok(()) };
            let q0 = plan.reference_inputs();
            let one = |i: usize, k: usize| {
                Motion::new(q0[i] + values[k % 6] * 1e-3, values[(k + 1) % 6], values[(k + 2) % 6])
            };
            let inputs: Vec<Inputs> = (0..4)
                .map(|k| {
                    let m: Vec<Motion> = (0..q0.len()).map(|i| one(i, k + 3 * i)).collect();
                    Inputs::from_slice(&m).unwrap()
                })
                .collect();
            let kept: Vec<_> = inputs.iter().map(|&i| plan.analyse(i)).collect();
            let ok = kept.iter().filter(|r| r.is_ok()).count();
            for (how, t) in [
                ("plan.table", plan.table(inputs.iter().copied())),
                ("Table::of", Table::of(&kept)),
                ("course_table", plan.course_table(&kept)),
            ] {
                prop_assert!(all_finite(&t).is_ok(), "{name}, {how}: {:?}", all_finite(&t));
                prop_assert!(t.len() <= ok);
            }
        }
    }
}
