//! Loads on a link: a force at a point plus a moment, and the inertia loads of d'Alembert.
//!
//! Kinetostatics adds the inertia loads F = −m·a_S and M = −J_S·ε to the external loads and
//! then solves a static problem (seed 000, §1.1). Every solver of the crate takes the resultant
//! load of each link as one [`Load`]: several loads are combined with [`Load::sum_about`].

use crate::angle::{cross, unit};
use crate::error::{finite, finite2, positive, Result};
use nalgebra::{Point2, Vector2};

/// A force applied at a point of a link, plus a moment (a couple) on the same link.
///
/// Units: N, m, N·m. The moment is algebraic, counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Load {
    /// The point of application of the force (usually the link's centre of mass).
    pub point: Point2<f64>,
    /// The force, N.
    pub force: Vector2<f64>,
    /// The moment of the couple, N·m, counter-clockwise positive.
    pub moment: f64,
}

impl Load {
    /// A force and a moment at a point.
    #[must_use]
    pub fn new(point: Point2<f64>, force: Vector2<f64>, moment: f64) -> Self {
        Self {
            point,
            force,
            moment,
        }
    }

    /// A force at a point, without a couple. A reaction R_ij at a joint is such a load on
    /// link j.
    #[must_use]
    pub fn force_at(point: Point2<f64>, force: Vector2<f64>) -> Self {
        Self::new(point, force, 0.0)
    }

    /// No load; the point is only where a later sum will be taken.
    #[must_use]
    pub fn zero(point: Point2<f64>) -> Self {
        Self::new(point, Vector2::zeros(), 0.0)
    }

    /// A force given in the seeds' form: magnitude `f` along the direction angle `gamma`
    /// (radians from +x), at a point, plus a moment.
    #[must_use]
    pub fn polar(point: Point2<f64>, f: f64, gamma: f64, moment: f64) -> Self {
        Self::new(point, unit(gamma) * f, moment)
    }

    /// The weight of a link of mass `mass` (kg) under gravity `g` (m/s², pointing along −y),
    /// at its centre of mass.
    #[must_use]
    pub fn weight(centre: Point2<f64>, mass: f64, g: f64) -> Self {
        Self::force_at(centre, Vector2::new(0.0, -mass * g))
    }

    /// The moment of this load about a point: the couple plus (point − pole) × force.
    #[must_use]
    #[inline]
    pub fn moment_about(&self, pole: Point2<f64>) -> f64 {
        self.moment + cross(self.point - pole, self.force)
    }

    /// The same load moved to another point: the same force, and the couple that keeps the
    /// moment about every point unchanged.
    #[must_use]
    pub fn moved_to(&self, pole: Point2<f64>) -> Self {
        Self::new(pole, self.force, self.moment_about(pole))
    }

    /// The resultant of several loads on one link, reduced to a point: the sum of the forces
    /// acting at `pole`, plus the sum of their moments about `pole`.
    ///
    /// # Examples
    /// Two equal and opposite forces 0.2 m apart make a pure couple:
    /// ```
    /// use nalgebra::{Point2, Vector2};
    /// use tmm::Load;
    /// let loads = [
    ///     Load::force_at(Point2::new(0.0, 0.0), Vector2::new(0.0, -50.0)),
    ///     Load::force_at(Point2::new(0.2, 0.0), Vector2::new(0.0, 50.0)),
    /// ];
    /// let r = Load::sum_about(&loads, Point2::origin());
    /// assert_eq!(r.force, Vector2::zeros());
    /// assert!((r.moment - 10.0).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn sum_about(loads: &[Load], pole: Point2<f64>) -> Self {
        loads.iter().fold(Self::zero(pole), |acc, l| {
            Self::new(pole, acc.force + l.force, acc.moment + l.moment_about(pole))
        })
    }

    /// Checks that every number of the load is finite.
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) naming the first non-finite component.
    pub fn validate(&self) -> Result<()> {
        finite2(["load point x", "load point y"], self.point.coords)?;
        finite2(["load force x", "load force y"], self.force)?;
        finite("load moment", self.moment)?;
        Ok(())
    }

    /// The d'Alembert inertia load of a link: the force −m·a_S at the centre of mass S and the
    /// couple −J_S·ε (seed 000, eqs. 1.1 and 1.2).
    ///
    /// The three cases of §1.1 are this one function:
    /// - general plane motion, or rotation about an axis that misses S with ε ≠ 0: both parts;
    /// - translation, or uniform rotation about an axis that misses S (ε = 0): the force only;
    /// - rotation about an axis through S (a_S = 0): the couple only.
    ///
    /// Units: kg, m/s², kg·m², rad/s².
    ///
    /// # Examples
    /// A coupler of 2 kg and J_S = 0.01 kg·m² with a_S = (30, −40) m/s² and ε = 150 rad/s²:
    /// ```
    /// use nalgebra::{Point2, Vector2};
    /// use approx::assert_relative_eq;
    /// let f = tmm::Load::inertia(Point2::new(0.1, 0.2), 2.0, Vector2::new(30.0, -40.0), 0.01, 150.0)?;
    /// assert_relative_eq!(f.force, Vector2::new(-60.0, 80.0));
    /// assert_relative_eq!(f.moment, -1.5);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// A negative or non-finite mass or moment of inertia, or a non-finite acceleration;
    /// [`Error::Overflow`](crate::Error::Overflow) when the force or the couple overflows.
    pub fn inertia(
        centre: Point2<f64>,
        mass: f64,
        accel_centre: Vector2<f64>,
        inertia_centre: f64,
        angular_accel: f64,
    ) -> Result<Self> {
        non_negative("m", mass)?;
        non_negative("J_S", inertia_centre)?;
        finite2(["a_S.x", "a_S.y"], accel_centre)?;
        finite("epsilon", angular_accel)?;
        finite2(["S.x", "S.y"], centre.coords)?;
        let force = -mass * accel_centre;
        let moment = -inertia_centre * angular_accel;
        crate::error::computed_all("inertia force -m*a_S", force.iter())?;
        crate::error::computed("inertia couple -J_S*epsilon", moment)?;
        Ok(Self::new(centre, force, moment))
    }
}

/// A mass or a moment of inertia may be zero (a massless link), never negative.
fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value == 0.0 {
        Ok(0.0)
    } else {
        positive(name, value)
    }
}
