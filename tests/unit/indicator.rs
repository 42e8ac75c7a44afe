//! `src/linkage/indicator.rs`: the diagram's pressure between its stations, and the gas
//! force on the piston.

use nalgebra::Vector2;
use tmm::linkage::IndicatorDiagram;

/// The pressure is the table's linear interpolation: exact on a straight branch, and a
/// branch whose stations do not cover the stroke (or that has none) is refused.
#[test]
fn interpolation_is_exact_on_a_line_and_rejects_gaps() {
    let line = vec![[0.0, 1.0], [0.5, 2.0], [1.0, 3.0]];
    let d = IndicatorDiagram {
        area: 0.01,
        outward: line.clone(),
        inward: line.clone(),
    };
    for k in 0..=20 {
        let x = f64::from(k) / 20.0;
        for inward in [false, true] {
            assert!((d.pressure(x, inward).unwrap() - (1.0 + 2.0 * x)).abs() < 1e-15);
        }
    }
    let short = IndicatorDiagram {
        area: 0.01,
        outward: line[..2].to_vec(),
        inward: Vec::new(),
    };
    assert!(short.pressure(0.75, false).is_err());
    assert!(short.pressure(0.25, false).is_ok());
    assert!(short.pressure(0.5, true).is_err());
}

#[test]
fn the_force_pushes_away_from_the_head() {
    let d = IndicatorDiagram {
        area: 0.01,
        outward: vec![[0.0, 1e5], [1.0, 0.0]],
        inward: vec![[0.0, 1e5], [1.0, 1e5]],
    };
    let g = Vector2::new(0.0, 1.0);
    // Halfway out: 0.5e5 Pa on 0.01 m² = 500 N along −y.
    let f = d.force(0.25, -1.0, g, 0.3, 0.2).unwrap();
    assert!((f - Vector2::new(0.0, -500.0)).norm() < 1e-9);
    let f = d.force(0.25, 1.0, g, 0.3, 0.2).unwrap();
    assert!((f - Vector2::new(0.0, -1000.0)).norm() < 1e-9);
    assert!(d.force(0.35, 1.0, g, 0.3, 0.2).is_err());
}
