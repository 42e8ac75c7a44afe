//! The description files bundled with `tmm` (the repository's `linkages/`), built into the
//! program so that `tmm analyse shaper` works wherever the program is installed.

/// Each bundled file: its name without `.json`, and its text.
pub const FILES: &[(&str, &str)] = &[
    (
        "chebyshev-straight-line",
        include_str!("../../linkages/chebyshev-straight-line.json"),
    ),
    (
        "double-butterfly",
        include_str!("../../linkages/double-butterfly.json"),
    ),
    (
        "five-bar-robot",
        include_str!("../../linkages/five-bar-robot.json"),
    ),
    ("four-bar", include_str!("../../linkages/four-bar.json")),
    (
        "geared-four-bar",
        include_str!("../../linkages/geared-four-bar.json"),
    ),
    (
        "hoekens-straight-line",
        include_str!("../../linkages/hoekens-straight-line.json"),
    ),
    ("jansen-leg", include_str!("../../linkages/jansen-leg.json")),
    (
        "mechanism-compressor",
        include_str!("../../linkages/mechanism-compressor.json"),
    ),
    (
        "mechanism-four-bar",
        include_str!("../../linkages/mechanism-four-bar.json"),
    ),
    (
        "mechanism-rocking-cylinder",
        include_str!("../../linkages/mechanism-rocking-cylinder.json"),
    ),
    (
        "mechanism-six-bar",
        include_str!("../../linkages/mechanism-six-bar.json"),
    ),
    (
        "mechanism-slider-crank",
        include_str!("../../linkages/mechanism-slider-crank.json"),
    ),
    (
        "peaucellier-lipkin",
        include_str!("../../linkages/peaucellier-lipkin.json"),
    ),
    (
        "scotch-yoke",
        include_str!("../../linkages/scotch-yoke.json"),
    ),
    ("shaper", include_str!("../../linkages/shaper.json")),
    (
        "six-bar-slider-triad",
        include_str!("../../linkages/six-bar-slider-triad.json"),
    ),
    (
        "six-bar-triad",
        include_str!("../../linkages/six-bar-triad.json"),
    ),
    (
        "slotted-rocker",
        include_str!("../../linkages/slotted-rocker.json"),
    ),
    (
        "stephenson-ii-six-bar",
        include_str!("../../linkages/stephenson-ii-six-bar.json"),
    ),
    (
        "stephenson-six-bar",
        include_str!("../../linkages/stephenson-six-bar.json"),
    ),
    (
        "watt-ii-six-bar",
        include_str!("../../linkages/watt-ii-six-bar.json"),
    ),
    (
        "watt-six-bar",
        include_str!("../../linkages/watt-six-bar.json"),
    ),
];

/// The text of the bundled file called `name` (with or without `.json`, with or without a
/// leading `linkages/`).
pub fn find(name: &str) -> Option<&'static str> {
    let stem = name.strip_prefix("linkages/").unwrap_or(name);
    let stem = stem.strip_suffix(".json").unwrap_or(stem);
    FILES
        .iter()
        .find(|(n, _)| *n == stem)
        .map(|(_, text)| *text)
}
