//! `src/linkage/workspace.rs`: a region's cells.

use nalgebra::Point2;
use tmm::linkage::Region;

/// A hand-made region whose cells are fewer than `nx · ny` answers `false` where it holds no
/// cell, and reads the cells it holds.
#[test]
fn a_short_region_answers_without_indexing_past_its_cells() {
    let region = Region {
        origin: Point2::origin(),
        cell: 1.0,
        nx: 10,
        ny: 10,
        cells: vec![true; 5],
    };
    assert!(region.contains(Point2::new(4.5, 0.5)));
    assert!(!region.contains(Point2::new(5.5, 0.5)));
    assert!(!region.contains(Point2::new(5.5, 5.5)));
    assert!(!region.contains(Point2::new(-0.5, 0.5)));
}
