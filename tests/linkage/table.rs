//! The course table by columns: `Plan::table` (one solver, cells written in place) against
//! `Table::of` over analyses kept one by one, bit for bit, on every bundled linkage with and
//! without friction; the friction columns against the power balance read from the table's
//! own kinematic and balance columns; and the table staying rectangular.

use std::f64::consts::TAU;
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, run_cycle, Cells, Friction, Plan, Table, Tabulate};

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
            let row = kept[k].as_ref().unwrap().row();
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
                lost.is_empty() && table.column("eta [-]").is_none(),
                "{name}"
            );
            continue;
        }
        // One column per joint, then the total.
        assert_eq!(lost.len(), plan.joint_names().len() + 1, "{name}");
        let total = table.column("P_lost [W]").unwrap();
        let eta = table.column("eta [-]").unwrap();
        // The drive's power from the table's own columns: M_b·ω1 (F_b·v for a slider).
        let (q_rate, b) = if plan.input_is_crank() {
            ("phi_in' [rad/s]", "Mb [N·m, + counter-clockwise]")
        } else {
            ("s_in' [m/s]", "Fb [N, + along the guide]")
        };
        let (w, mb) = (table.column(q_rate).unwrap(), table.column(b).unwrap());
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
            if drive > 0.0 {
                // η·P_drive = P_drive − Σ P_lost.
                assert!(
                    (eta[r] * drive - (drive - total[r])).abs() <= 1e-9 * scale,
                    "{name} row {r}"
                );
            } else {
                assert!(
                    eta[r].is_nan(),
                    "{name} row {r}: η where the drive gives no power"
                );
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
fn a_table_stays_rectangular() {
    let mut t = Table::default();
    t.push(&Cellular(3));
    t.push(&Cellular(2)); // short: NaN in the last column
    t.push(&Cellular(5)); // long: the extra cells are dropped
    assert_eq!(t.columns.len(), 3);
    assert!(t.columns.iter().all(|c| c.values.len() == 3));
    assert!(t.columns[2].values[1].is_nan());
    assert_eq!(t.columns[2].values[2], 2.0);
    let mut csv = Vec::new();
    t.write_csv(&mut csv).unwrap();
    assert_eq!(
        String::from_utf8(csv).unwrap(),
        "c0 [-],c1 [-],c2 [-]\n0,1,2\n0,1,NaN\n0,1,2\n"
    );
}
