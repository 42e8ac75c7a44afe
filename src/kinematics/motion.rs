//! Scalars and points with their first and second time derivatives.
//!
//! Every kinematic block of the crate passes motion around as plain data: a coordinate with its
//! rate and its acceleration ([`Motion`]), or a point with its velocity and acceleration
//! ([`PointMotion`]). The same types carry transfer functions: with the input moving at unit
//! speed and no acceleration (ω1 = 1, ε1 = 0) the "rate" of an output is its first transfer
//! function and its "acceleration" the second (see [`Motion::unit_speed`]).

use crate::error::{finite, finite2, Result};
use nalgebra::{Point2, Vector2};

/// A scalar coordinate with its first and second time derivatives.
///
/// For an angle: φ (rad), ω (rad/s), ε (rad/s²). For a sliding coordinate: s (m), v (m/s),
/// a (m/s²). For a transfer function (input at unit speed): φ, φ′, φ″ or s, s′, s″.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Motion {
    /// The coordinate.
    pub value: f64,
    /// Its first time derivative.
    pub rate: f64,
    /// Its second time derivative.
    pub accel: f64,
}

impl Motion {
    /// A coordinate with its rate and acceleration.
    #[must_use]
    pub fn new(value: f64, rate: f64, accel: f64) -> Self {
        Self { value, rate, accel }
    }

    /// A coordinate at rest (a constant): a crank held at the angle `value`.
    #[must_use]
    pub fn fixed(value: f64) -> Self {
        Self::new(value, 0.0, 0.0)
    }

    /// A coordinate moving at the constant speed `rate` (no acceleration): a crank at the
    /// angle φ = `value` turning steadily at ω = `rate` (rad/s), or a slider at s moving at ṡ.
    /// The same as `Motion::new(value, rate, 0.0)`, with the numbers labelled.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// let m = Motion::turning(30f64.to_radians(), 10.0);
    /// assert_eq!((m.rate, m.accel), (10.0, 0.0));
    /// ```
    #[must_use]
    pub fn turning(value: f64, rate: f64) -> Self {
        Self::new(value, rate, 0.0)
    }

    /// An input coordinate moving at unit speed without acceleration (ω1 = 1, ε1 = 0).
    ///
    /// Feeding this to a chain of blocks makes every output's `rate` its first transfer
    /// function (φ′ = dφ/dφ1 or s′ = ds/dφ1) and every `accel` its second (φ″, s″): the seed's
    /// "analogues of velocity and acceleration".
    #[must_use]
    pub fn unit_speed(value: f64) -> Self {
        Self::new(value, 1.0, 0.0)
    }

    /// The motion of an output from its transfer functions (`self` = value, first, second
    /// transfer function) and the input's actual speed ω1 and acceleration ε1:
    /// ω = φ′·ω1 and ε = φ″·ω1² + φ′·ε1 (seed 001; the same for sliders).
    ///
    /// # Examples
    /// A rocker with φ′ = 0.5 and φ″ = −0.2 driven at ω1 = 10 rad/s, ε1 = 4 rad/s²:
    /// ```
    /// use tmm::kinematics::Motion;
    /// let m = Motion::new(1.0, 0.5, -0.2).at_input_speed(10.0, 4.0);
    /// assert_eq!(m.rate, 5.0); // 0.5·10
    /// assert_eq!(m.accel, -18.0); // −0.2·100 + 0.5·4
    /// ```
    #[must_use]
    pub fn at_input_speed(self, omega1: f64, epsilon1: f64) -> Self {
        Self::new(
            self.value,
            self.rate * omega1,
            self.accel * omega1 * omega1 + self.rate * epsilon1,
        )
    }

    /// Checks that the three numbers are finite.
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) naming `names[i]` for the first bad one.
    pub fn validate(&self, names: [&'static str; 3]) -> Result<()> {
        finite(names[0], self.value)?;
        finite(names[1], self.rate)?;
        finite(names[2], self.accel)?;
        Ok(())
    }
}

/// A point with its velocity and acceleration (m, m/s, m/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointMotion {
    /// The position.
    pub p: Point2<f64>,
    /// The velocity.
    pub v: Vector2<f64>,
    /// The acceleration.
    pub a: Vector2<f64>,
}

impl PointMotion {
    /// A point with its velocity and acceleration.
    #[must_use]
    pub fn new(p: Point2<f64>, v: Vector2<f64>, a: Vector2<f64>) -> Self {
        Self { p, v, a }
    }

    /// A fixed point (a joint of the frame).
    #[must_use]
    pub fn fixed(p: Point2<f64>) -> Self {
        Self::new(p, Vector2::zeros(), Vector2::zeros())
    }

    /// Checks that all six numbers are finite.
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) naming the point (`name`) and the part.
    pub fn validate(&self, name: [&'static str; 6]) -> Result<()> {
        finite2([name[0], name[1]], self.p.coords)?;
        finite2([name[2], name[3]], self.v)?;
        finite2([name[4], name[5]], self.a)?;
        Ok(())
    }
}
