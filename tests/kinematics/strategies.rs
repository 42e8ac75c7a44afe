//! Shared proptest strategies and finite-difference helpers for the kinematics tests.
//!
//! Ranges are bounded so every generated mechanism is of unit size (lengths 0.2–2 m, speeds
//! up to a few m/s and rad/s): the finite-difference steps below then resolve the motion.
#![allow(dead_code)]

use nalgebra::{Point2, Vector2};
use proptest::prelude::*;
use tmm::kinematics::PointMotion;

/// A point in the square [−1, 1]² m.
pub fn point() -> impl Strategy<Value = Point2<f64>> {
    (-1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y)| Point2::new(x, y))
}

/// A vector with components in [−m, m].
pub fn vector(m: f64) -> impl Strategy<Value = Vector2<f64>> {
    (-m..m, -m..m).prop_map(|(x, y)| Vector2::new(x, y))
}

/// A point moving with a bounded velocity and acceleration.
pub fn point_motion() -> impl Strategy<Value = PointMotion> {
    (point(), vector(2.0), vector(4.0)).prop_map(|(p, v, a)| PointMotion::new(p, v, a))
}

/// The point `m` at time `t` under constant acceleration: the path p + v·t + a·t²/2 whose
/// velocity and acceleration at t = 0 are `m.v` and `m.a` (so finite differences in t of a
/// solver fed with this path test the solver's velocities and accelerations).
pub fn along(m: PointMotion, t: f64) -> PointMotion {
    PointMotion::new(m.p + m.v * t + 0.5 * m.a * t * t, m.v + m.a * t, m.a)
}

/// The eighth-order central first derivative at 0 of a vector function, step `h`.
///
/// Tests differentiate positions to check velocities, and the solver's velocities to check
/// its accelerations: a first difference keeps rounding at ε/h, where a second difference of
/// positions would amplify it by 1/h² and force a step too long for the truncation error.
pub fn fd<const N: usize>(f: impl Fn(f64) -> [f64; N], h: f64) -> [f64; N] {
    const D1: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
    let mut d1 = [0.0; N];
    for (k, c1) in D1.iter().enumerate() {
        let s = (k + 1) as f64 * h;
        let (fp, fm) = (f(s), f(-s));
        for i in 0..N {
            d1[i] += c1 * (fp[i] - fm[i]);
        }
    }
    d1.map(|d| d / h)
}

/// Splits `[x0..xn, y0..yn]` into its halves.
pub fn halves<const N: usize, const M: usize>(v: [f64; M]) -> ([f64; N], [f64; N]) {
    assert_eq!(2 * N, M);
    (
        std::array::from_fn(|i| v[i]),
        std::array::from_fn(|i| v[N + i]),
    )
}

/// `a − b` for angles, in (−π, π]: lets finite differences of angles ignore the 2π wrap.
pub fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    if d > std::f64::consts::PI {
        d - std::f64::consts::TAU
    } else {
        d
    }
}

/// Asserts |got − want| ≤ tol·max(|want|, scale) component-wise, with a message.
pub fn close<const N: usize>(got: [f64; N], want: [f64; N], scale: f64, tol: f64, what: &str) {
    for i in 0..N {
        let bound = tol * want[i].abs().max(scale);
        assert!(
            (got[i] - want[i]).abs() <= bound,
            "{what}[{i}]: got {}, finite differences {}, |diff| {:e} > {bound:e}",
            got[i],
            want[i],
            (got[i] - want[i]).abs()
        );
    }
}
