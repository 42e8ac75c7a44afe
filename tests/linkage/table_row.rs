//! `Tabulate::row` never hands back a value that is not finite: a load so large that a
//! reaction's magnitude overflows (|R| = √(R_x² + R_y²) with R_x, R_y ≈ 10¹⁶⁰, whose squares
//! leave `f64`) is an error naming that column, while a load 10¹⁰ times smaller gives the
//! whole row, every cell finite and the magnitudes equal to the components' hypot.

use std::path::Path;
use tmm::kinematics::Motion;
use tmm::linkage::{Linkage, Plan, Tabulate};
use tmm::Error;

fn four_bar_with_load(force: &str) -> Linkage {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("linkages/four-bar.json");
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("[0.0, -50.0]"));
    Linkage::from_json(&text.replace("[0.0, -50.0]", force)).unwrap()
}

#[test]
fn a_row_whose_magnitude_overflows_is_an_error_naming_the_column() {
    let plan = Plan::new(&four_bar_with_load("[1e160, 1e160]")).unwrap();
    let a = plan
        .analyse(Motion::new(plan.reference_input(), 10.0, 0.0))
        .unwrap();
    let e = a.row().unwrap_err();
    let Error::In { part, source } = &e else {
        panic!("{e}");
    };
    assert!(part.starts_with("column |R("), "{e}");
    assert!(matches!(**source, Error::Overflow { .. }), "{e}");
    // The column named is one whose cell is not finite, and it is the first such.
    let mut cells = Vec::new();
    struct All<'a>(&'a mut Vec<(String, f64)>);
    impl tmm::linkage::Cells for All<'_> {
        fn cell(&mut self, name: impl FnOnce() -> String, value: f64) {
            self.0.push((name(), value));
        }
    }
    a.cells(&mut All(&mut cells));
    let first = cells.iter().find(|(_, v)| !v.is_finite()).unwrap();
    assert_eq!(part, &format!("column {}", first.0));

    // 10¹⁰ times smaller: every cell finite, each magnitude the hypot of its components.
    let plan = Plan::new(&four_bar_with_load("[1e150, 1e150]")).unwrap();
    let a = plan
        .analyse(Motion::new(plan.reference_input(), 10.0, 0.0))
        .unwrap();
    let row = a.row().unwrap();
    assert!(row.iter().all(|(_, v)| v.is_finite()));
    let value = |n: &str| row.iter().find(|(c, _)| c == n).unwrap().1;
    let mut magnitudes = 0;
    for (name, v) in &row {
        if let Some(inner) = name.strip_prefix('|').and_then(|n| n.strip_suffix("| [N]")) {
            let (x, y) = (
                value(&format!("{inner}_x [N]")),
                value(&format!("{inner}_y [N]")),
            );
            assert!(
                (v - x.hypot(y)).abs() <= 1e-15 * v,
                "{name}: {v} vs {x}, {y}"
            );
            magnitudes += 1;
        }
    }
    assert!(magnitudes >= 4, "{magnitudes}");
}
