//! `src/load.rs`: moving and summing loads, and the inertia load's cases.

use approx::assert_relative_eq;
use nalgebra::{Point2, Vector2};
use tmm::Load;

#[test]
fn moving_a_load_keeps_its_moment_about_every_point() {
    let l = Load::new(Point2::new(0.3, -0.1), Vector2::new(12.0, 5.0), -2.0);
    let m = l.moved_to(Point2::new(-1.0, 2.0));
    for p in [Point2::new(0.0, 0.0), Point2::new(4.0, -3.0)] {
        assert_relative_eq!(l.moment_about(p), m.moment_about(p), epsilon = 1e-12);
    }
}

#[test]
fn sum_about_is_the_static_resultant() {
    let loads = [
        Load::new(Point2::new(1.0, 0.0), Vector2::new(0.0, 10.0), 1.0),
        Load::new(Point2::new(0.0, 2.0), Vector2::new(-3.0, 0.0), -0.5),
    ];
    let pole = Point2::new(0.5, 0.5);
    let r = Load::sum_about(&loads, pole);
    assert_relative_eq!(r.force, Vector2::new(-3.0, 10.0));
    // Moments about any other point must agree too.
    let q = Point2::new(-2.0, 7.0);
    let direct: f64 = loads.iter().map(|l| l.moment_about(q)).sum();
    assert_relative_eq!(r.moment_about(q), direct, epsilon = 1e-12);
}

#[test]
fn inertia_cases_of_section_1_1() {
    let s = Point2::new(0.0, 0.0);
    // Rotation about the centre of mass: a couple only.
    let c = Load::inertia(s, 3.0, Vector2::zeros(), 0.2, -10.0).unwrap();
    assert_eq!(c.force, Vector2::zeros());
    assert_relative_eq!(c.moment, 2.0);
    // Translation: a force only.
    let t = Load::inertia(s, 3.0, Vector2::new(1.0, 2.0), 0.2, 0.0).unwrap();
    assert_eq!(t.moment, 0.0);
    assert_relative_eq!(t.force, Vector2::new(-3.0, -6.0));
    assert!(Load::inertia(s, -1.0, Vector2::zeros(), 0.0, 0.0).is_err());
    assert!(Load::inertia(s, 1.0, Vector2::new(f64::NAN, 0.0), 0.0, 0.0).is_err());
}
