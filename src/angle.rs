//! Direction angles: the jobs of the seeds' UGL2, UGL3 and UGL4 helpers.
//!
//! The seeds carry every force as a magnitude and a direction angle, and flip a preliminary
//! direction by π (or by ±π/2) when a signed magnitude comes out negative. The crate carries
//! forces as vectors instead, so the sign logic disappears from the solvers; these helpers give
//! a vector's direction in the seeds' form when a table or a textbook check needs it.
//!
//! Angles are in radians, counter-clockwise from +x. Every angle returned lies in [0, 2π).

use nalgebra::Vector2;
use std::f64::consts::{PI, TAU};

/// Brings an angle into [0, 2π).
///
/// # Examples
/// ```
/// use std::f64::consts::PI;
/// assert_eq!(tmm::angle::normalize(-PI / 2.0), 1.5 * PI);
/// assert_eq!(tmm::angle::normalize(2.0 * PI), 0.0);
/// ```
#[must_use]
#[inline]
pub fn normalize(angle: f64) -> f64 {
    // The same as rem_euclid, without its fmod for the angles a hot path meets: within one
    // turn either side of 0 (the remainder of such an angle is the angle itself).
    let r = if (0.0..TAU).contains(&angle) {
        angle
    } else if angle > -TAU && angle < 0.0 {
        angle + TAU
    } else {
        angle.rem_euclid(TAU)
    };
    // rem_euclid of a tiny negative angle rounds up to exactly 2π; that is the angle 0.
    if r >= TAU {
        0.0
    } else {
        r
    }
}

/// The direction angle of a vector from its projections, in [0, 2π) (the seeds' UGL3).
///
/// Uses `atan2`, so it never divides by a projection (the seeds' piecewise arctangents divide
/// by Fx, see docs/errata.md#n4). The zero vector has no direction; it gets 0 by convention.
///
/// # Examples
/// ```
/// use nalgebra::Vector2;
/// use std::f64::consts::PI;
/// use approx::assert_relative_eq;
/// assert_relative_eq!(tmm::angle::direction(Vector2::new(-1.0, -1.0)), 1.25 * PI);
/// assert_eq!(tmm::angle::direction(Vector2::new(3.0, 0.0)), 0.0);
/// ```
#[doc(alias = "UGL3")]
#[must_use]
#[inline]
pub fn direction(v: Vector2<f64>) -> f64 {
    if v.x == 0.0 && v.y == 0.0 {
        return 0.0;
    }
    normalize(v.y.atan2(v.x))
}

/// The direction angle of a vector given as a signed magnitude along a preliminary direction
/// φ + α (the seeds' UGL2).
///
/// A non-negative `value` points along φ + α; a negative one points the other way, φ + α + π.
/// The vector's magnitude is `value.abs()`.
///
/// # Examples
/// A tangential reaction R12τ = −40 N with the preliminary direction φ2 + π/2 (φ2 = 30°) points
/// along φ2 − π/2 = −60°, that is 300°:
/// ```
/// use approx::assert_relative_eq;
/// let psi = tmm::angle::signed_direction(30f64.to_radians(), 90f64.to_radians(), -40.0);
/// assert_relative_eq!(psi.to_degrees(), 300.0, epsilon = 1e-12);
/// ```
#[doc(alias = "UGL2")]
#[must_use]
pub fn signed_direction(phi: f64, alpha: f64, value: f64) -> f64 {
    if value < 0.0 {
        normalize(phi + alpha + PI)
    } else {
        normalize(phi + alpha)
    }
}

/// The direction of a force along one of the two lines that make the angle α with the
/// direction φ (the seeds' UGL4).
///
/// `mirrored = false` gives φ − α; `mirrored = true` gives φ + π + α, the other line turned so
/// that both directions have the same component along the normal φ − π/2. This is the rule of
/// a gear's two tooth flanks: with φ the tangent to the pitch circle at the pitch point and α
/// the pressure angle, the two directions are the lines of action of the two flanks, and both
/// push towards the gear's centre.
///
/// # Examples
/// Seed 000, §1.4.1: the preliminary direction of the balancing force is π/2 − α_w, the other
/// flank's is 3π/2 + α_w.
/// ```
/// use std::f64::consts::PI;
/// use approx::assert_relative_eq;
/// use tmm::angle::line_of_action;
/// let alpha_w = 20f64.to_radians();
/// assert_relative_eq!(line_of_action(PI / 2.0, alpha_w, false), PI / 2.0 - alpha_w);
/// assert_relative_eq!(line_of_action(PI / 2.0, alpha_w, true), 1.5 * PI + alpha_w);
/// ```
#[doc(alias = "UGL4")]
#[must_use]
pub fn line_of_action(phi: f64, alpha: f64, mirrored: bool) -> f64 {
    if mirrored {
        normalize(phi + PI + alpha)
    } else {
        normalize(phi - alpha)
    }
}

/// A vector as a magnitude and a direction angle, the way the seeds tabulate forces.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Polar {
    /// The magnitude, never negative.
    pub magnitude: f64,
    /// The direction angle in [0, 2π), radians (0 for the zero vector).
    pub angle: f64,
}

impl Polar {
    /// The magnitude and direction angle of a vector.
    ///
    /// # Examples
    /// ```
    /// use nalgebra::Vector2;
    /// use approx::assert_relative_eq;
    /// let p = tmm::angle::Polar::of(Vector2::new(0.0, -2.0));
    /// assert_relative_eq!(p.magnitude, 2.0);
    /// assert_relative_eq!(p.angle.to_degrees(), 270.0);
    /// ```
    #[must_use]
    pub fn of(v: Vector2<f64>) -> Self {
        Self {
            magnitude: v.norm(),
            angle: direction(v),
        }
    }

    /// The vector of this magnitude and direction. A negative magnitude points the other way.
    #[must_use]
    pub fn to_vector(self) -> Vector2<f64> {
        unit(self.angle) * self.magnitude
    }
}

/// The unit vector of a direction angle, (cos θ, sin θ).
#[must_use]
#[inline]
pub fn unit(angle: f64) -> Vector2<f64> {
    let (s, c) = angle.sin_cos();
    Vector2::new(c, s)
}

/// The z component of the cross product a × b: the moment of the force `b` applied at the
/// arm `a`, counter-clockwise positive.
#[must_use]
#[inline]
pub fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The vector turned by +90° (counter-clockwise): (−y, x).
#[must_use]
#[inline]
pub fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}
