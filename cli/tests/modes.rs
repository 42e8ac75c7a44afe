//! `tmm check` reports the real assembly modes at the reference input: per group and in all,
//! as text and in its JSON output. The counts are the library's (`Plan::assembly_modes`),
//! checked there against independent searches; here the program must print them and agree
//! with itself (the whole count the product of the groups' where the groups are
//! independent).

mod common;

use common::{assert_success, tmm};

#[test]
fn check_reports_every_groups_modes_and_the_whole_count() {
    for (file, groups, total) in [
        ("linkages/double-butterfly.json", vec![8], 8),
        ("linkages/four-bar.json", vec![2], 2),
        ("linkages/watt-six-bar.json", vec![2, 2], 4),
        ("linkages/six-bar-triad.json", vec![], 0),
    ] {
        let r = tmm(&["check", file, "--format", "json"]);
        assert_success(&r, file);
        let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
        let m = &v["modes"];
        let counts: Vec<u64> = m["groups"]
            .as_array()
            .unwrap_or_else(|| panic!("{file}: {m}"))
            .iter()
            .map(|g| g["count"].as_u64().unwrap())
            .collect();
        let whole = m["total"].as_u64().unwrap();
        assert_eq!(whole, counts.iter().product::<u64>(), "{file}: {m}");
        assert_eq!(m["exhaustive"], true, "{file}");
        if total > 0 {
            assert_eq!(counts, groups, "{file}");
            assert_eq!(whole, total, "{file}");
        }
        let r = tmm(&["check", file]);
        assert_success(&r, file);
        let line = r
            .stdout
            .lines()
            .find(|l| l.trim_start().starts_with("in all:"))
            .unwrap_or_else(|| panic!("{file}: {}", r.stdout));
        assert!(
            line.contains(&format!("in all: {whole} ")),
            "{file}: {line}"
        );
    }
}
