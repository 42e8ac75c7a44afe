//! Bounded proptest strategies for the kinetostatics tests.

use nalgebra::{Point2, Vector2};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use tmm::Load;

/// A load whose point is given relative to a base point and a size, so one strategy serves
/// every link.
#[derive(Debug, Clone, Copy)]
pub struct RawLoad {
    offset: (f64, f64),
    f: f64,
    gamma: f64,
    m: f64,
}

impl RawLoad {
    /// The load with its point at `base + size·offset`.
    pub fn at(&self, base: Point2<f64>, size: f64) -> Load {
        Load::polar(
            base + Vector2::new(self.offset.0, self.offset.1) * size,
            self.f,
            self.gamma,
            self.m,
        )
    }
}

/// Forces up to 1 kN in any direction, moments up to ±200 N·m, points within a box.
pub fn raw_load() -> impl Strategy<Value = RawLoad> {
    (
        (-1.0..1.0f64, -1.0..1.0f64),
        0.0..1000.0f64,
        0.0..TAU,
        -200.0..200.0f64,
    )
        .prop_map(|(offset, f, gamma, m)| RawLoad {
            offset,
            f,
            gamma,
            m,
        })
}

/// A point in a 4 m square.
pub fn point() -> impl Strategy<Value = Point2<f64>> {
    (-2.0..2.0f64, -2.0..2.0f64).prop_map(|(x, y)| Point2::new(x, y))
}

/// A link length from 5 cm to 2 m.
pub fn length() -> impl Strategy<Value = f64> {
    0.05..2.0f64
}

/// An angle away from 0 and π by at least 0.25 rad, either sign: a well-shaped dyad angle.
pub fn well_shaped_angle() -> impl Strategy<Value = f64> {
    (0.25..(PI - 0.25), any::<bool>()).prop_map(|(d, neg)| if neg { -d } else { d })
}

/// A small angle 10^−x, x in [1, 17], with a sign: the distance from a singular angle.
pub fn tiny_angle() -> impl Strategy<Value = f64> {
    (1.0..17.0f64, any::<bool>()).prop_map(|(x, neg)| {
        let d = 10f64.powf(-x);
        if neg {
            -d
        } else {
            d
        }
    })
}

/// An angle at least 0.25 rad away from ±π/2 relative to a reference: a well-shaped RRP.
pub fn away_from_right_angle() -> impl Strategy<Value = f64> {
    (-(FRAC_PI_2 - 0.25)..(FRAC_PI_2 - 0.25), any::<bool>())
        .prop_map(|(d, flip)| if flip { d + PI } else { d })
}

/// Any direction.
pub fn direction() -> impl Strategy<Value = f64> {
    0.0..TAU
}
