//! The main example (`examples/linkage.rs`) on every bundled description file: its own code,
//! included here, runs each file to its end (the course, the table, the CSV and the
//! pictures) and gives a full table whose balancing values agree with the principle of
//! virtual power — two-input linkages included.

#[path = "../../examples/linkage.rs"]
#[allow(dead_code)]
mod example;

use std::path::Path;

/// Every `linkages/*.json`, sorted by name.
fn bundled_files() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("linkages");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("linkages/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
}

#[test]
fn the_main_example_runs_every_bundled_file() {
    let files = bundled_files();
    assert!(files.len() >= 14, "{} bundled files", files.len());
    let out = std::env::temp_dir().join(format!("tmm-examples-run-{}", std::process::id()));
    let mut two_inputs = 0;
    for file in &files {
        let name = file.display().to_string();
        let text = std::fs::read_to_string(file).expect("the file reads");
        let table = example::run(&text, &name, &out)
            .unwrap_or_else(|e| panic!("{name}: the example fails: {e}"));
        // Every one of the 12 course positions solved and tabulated, but a rocking input's
        // locks (at rest), where the driven group is at its dead point and the forces are
        // refused: a table may leave them out.
        let linkage = tmm::linkage::Linkage::from_json(&text).expect("the file parses");
        let plan = tmm::linkage::Plan::new(&linkage).expect("the file plans");
        let course = plan
            .default_course(linkage.output.as_ref(), 12, linkage.input_speed())
            .expect("its course");
        let mut refused = 0;
        for i in course.inputs() {
            if let Err(e) = plan.analyse(i) {
                let at_lock = i.as_slice().iter().all(|m| m.rate == 0.0);
                assert!(
                    at_lock && e.to_string().contains("at its dead point"),
                    "{name}: {i:?}: {e}"
                );
                refused += 1;
            }
        }
        assert!(refused <= 2, "{name}: {refused} positions refused");
        assert!(
            (12 - refused..=12).contains(&table.len()),
            "{name}: rows of the table"
        );
        assert!(table.columns.len() > 10, "{name}: columns of the table");
        // The balancing values against the principle of virtual power, row by row: for two
        // inputs, the drives' power against the loads' power (W).
        let two = table.column("phi_in2 [rad]").is_some();
        let pairs: &[(&str, &str)] = if two {
            &[("drive power [W]", "drive power by virtual power [W]")]
        } else {
            &[
                (
                    "Mb [N·m, + counter-clockwise]",
                    "Mb by virtual power [N·m, + counter-clockwise]",
                ),
                (
                    "Fb [N, + along the guide]",
                    "Fb by virtual power [N, + along the guide]",
                ),
            ]
        };
        assert_eq!(table.column("drive power [W]").is_some(), two, "{name}");
        let (chain, vp) = pairs
            .iter()
            .find_map(|(c, v)| Some((table.column(c)?, table.column(v)?)))
            .unwrap_or_else(|| panic!("{name}: no balance beside its virtual power"));
        let scale = chain.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut compared = 0;
        let rate = table
            .column("phi_in' [rad/s]")
            .or_else(|| table.column("s_in' [m/s]"));
        for (k, (c, v)) in chain.iter().zip(vp).enumerate() {
            // A rocking input at rest where it reverses, at its lock: a dead centre of its
            // dyad, where both values grow as 1/det and their rounding with them (the
            // Chebyshev linkage's lock: Mb = −1.27e7 N·m, the two agree to 3.6e-9 of it), so
            // this test's 1e-9 of the largest value compares the moving rows, as it did when
            // the check had no value at rest. At rest away from dead centres the check is
            // `table::at_rest_the_balance_by_virtual_power_is_the_statics_virtual_work`.
            let at_rest = !two && rate.is_some_and(|r| r[k] == 0.0);
            if !at_rest {
                assert!((c - v).abs() <= 1e-9 * scale, "{name}: {c} against {v}");
                compared += 1;
            }
        }
        assert!(compared >= 10, "{name}: {compared} rows compared");
        if two {
            two_inputs += 1;
            assert!(table.column("Mb2 [N·m, + counter-clockwise]").is_some());
        }
        let csv = out.join(format!("{}.csv", name_of(&text)));
        let written = std::fs::read_to_string(&csv).expect("the CSV is written");
        assert_eq!(
            written.lines().count(),
            table.len() + 1,
            "{name}: header and the table's rows"
        );
    }
    assert!(two_inputs >= 1, "the five-bar robot has two inputs");
    let _ = std::fs::remove_dir_all(&out);
}

/// The CSV stem the example writes for a description.
fn name_of(text: &str) -> String {
    tmm::linkage::Linkage::from_json(text)
        .expect("it reads")
        .name
        .replace([' ', '/'], "_")
}

#[test]
fn the_main_example_names_what_is_wrong_in_a_bad_file() {
    let out = std::env::temp_dir().join(format!("tmm-examples-bad-{}", std::process::id()));
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("linkages/five-bar-robot.json"),
    )
    .unwrap();
    // The second input on a link that does not exist: an error naming it, never a panic.
    let bad = text.replace(
        r#""second_input": {"link": "crank 4""#,
        r#""second_input": {"link": "crank 9""#,
    );
    assert_ne!(bad, text);
    let e = example::run(&bad, "bad", &out).expect_err("an unknown link");
    assert!(e.to_string().contains("crank 9"), "{e}");
    let _ = std::fs::remove_dir_all(&out);
}
