//! `src/angle.rs`: normalisation, directions and the vector helpers.

use approx::assert_relative_eq;
use nalgebra::Vector2;
use std::f64::consts::{PI, TAU};
use tmm::angle::{
    cross, direction, line_of_action, normalize, perp, signed_direction, unit, Polar,
};

#[test]
fn normalize_lands_in_range() {
    for k in -50..50 {
        let a = f64::from(k) * 0.37;
        let n = normalize(a);
        assert!((0.0..TAU).contains(&n), "{a} -> {n}");
        assert_relative_eq!(n.sin(), a.sin(), epsilon = 1e-12);
        assert_relative_eq!(n.cos(), a.cos(), epsilon = 1e-12);
    }
    assert_eq!(normalize(-1e-300), 0.0);
}

#[test]
fn direction_inverts_unit() {
    for k in 0..720 {
        let a = f64::from(k) * TAU / 720.0;
        assert_relative_eq!(direction(unit(a) * 3.5), a, epsilon = 1e-12);
    }
    assert_eq!(direction(Vector2::new(-0.0, 0.0)), 0.0);
}

#[test]
fn signed_direction_matches_the_vector_it_describes() {
    for k in 0..100 {
        let phi = f64::from(k) * 0.1;
        for value in [-3.0, 2.0] {
            let v = unit(phi + 0.5 * PI) * value;
            assert_relative_eq!(
                unit(signed_direction(phi, 0.5 * PI, value)),
                v / f64::abs(value),
                epsilon = 1e-12
            );
        }
    }
}

#[test]
fn both_flank_directions_push_towards_the_centre() {
    // Pitch point on the -x side of the centre: the normal towards the centre is +x.
    let alpha: f64 = 0.35;
    for mirrored in [false, true] {
        let u = unit(line_of_action(0.5 * PI, alpha, mirrored));
        assert_relative_eq!(u.x, alpha.sin(), epsilon = 1e-15);
    }
}

#[test]
fn cross_and_perp_agree() {
    let a = Vector2::new(1.5, -0.5);
    let b = Vector2::new(0.25, 2.0);
    assert_relative_eq!(cross(a, b), perp(a).dot(&b));
    assert_relative_eq!(cross(a, perp(a)), a.norm_squared());
    let p = Polar::of(b);
    assert_relative_eq!(p.to_vector(), b, epsilon = 1e-15);
}
