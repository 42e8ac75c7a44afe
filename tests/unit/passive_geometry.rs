//! `src/kinetostatics/passive/geometry.rs`: the seed's geometry, and degenerate geometries
//! refused by the solve naming the measure that vanished.

use approx::assert_relative_eq;
use tmm::angle::cross;
use tmm::kinetostatics::passive::{solve, Geometry, Link, Loads, Stiffness};
use tmm::Error;

#[test]
fn seed_geometry_is_a_parallelogram_with_a_straight_link_3() {
    let g = Geometry::seed(0.2, 0.2, 0.1, 0.25, 60f64.to_radians());
    assert_relative_eq!(g.b - g.a, g.d - g.c, epsilon = 1e-15);
    assert_relative_eq!(cross(g.d - g.b, g.e - g.d), 0.0, epsilon = 1e-15);
    assert_relative_eq!(g.length(Link::Bde), 0.35, epsilon = 1e-15);
    // E is (l3 + l4)·sin α4 away from the horizontal line AB.
    assert_relative_eq!(
        g.arm_e_ab().abs(),
        0.35 * 60f64.to_radians().sin(),
        epsilon = 1e-15
    );
    let mid = g.point_at(Link::Bde, 0.05);
    assert_relative_eq!(mid, g.b + 0.5 * (g.d - g.b), epsilon = 1e-15);
}

#[test]
fn degenerate_geometries_name_the_vanished_measure() {
    let stiffness = Stiffness {
        ei: [1.0; 3],
        ea: None,
    };
    let solved = |g: &Geometry| solve(g, &Loads::ZERO, &stiffness);
    let g = Geometry::seed(0.2, 0.2, 0.1, 0.25, 1.0);
    assert!(solved(&g).is_ok());
    let mut h = g;
    h.c = h.d;
    assert!(matches!(
        solved(&h),
        Err(Error::Singular {
            measure: "l_CD",
            ..
        })
    ));
    // α4 = 0: E lies on the line AB.
    let flat = Geometry::seed(0.2, 0.2, 0.1, 0.25, 0.0);
    assert!(matches!(
        solved(&flat),
        Err(Error::Singular {
            measure: "distance from E to line AB",
            ..
        })
    ));
    let mut nan = g;
    nan.e.x = f64::NAN;
    assert!(matches!(
        solved(&nan),
        Err(Error::NonFinite { name: "E.x", .. })
    ));
}
