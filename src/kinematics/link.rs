//! The plane motion of one rigid link: a reference point and the direction of the link.

use super::motion::{Motion, PointMotion};
use crate::angle::{perp, unit};
use nalgebra::{Point2, Vector2};

/// The plane motion of a rigid link: the motion of one of its points (the origin, usually a
/// joint) and the direction angle of the link with its angular velocity and acceleration.
///
/// Any other point of the link follows from rigid-body kinematics (Euler's formulas):
/// v_P = v_O + ω × OP and a_P = a_O + ε × OP − ω²·OP. This is how the centre of mass of a
/// link is found for the inertia loads ([`Load::inertia`](crate::Load::inertia)).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinkMotion {
    /// The link's reference point (a joint) with its velocity and acceleration.
    pub origin: PointMotion,
    /// The direction angle of the link, radians CCW from +x, in [0, 2π).
    pub angle: f64,
    /// The angular velocity ω, rad/s, CCW positive.
    pub omega: f64,
    /// The angular acceleration ε, rad/s², CCW positive.
    pub epsilon: f64,
}

impl LinkMotion {
    /// The unit vector along the link, (cos φ, sin φ).
    #[must_use]
    pub fn unit(&self) -> Vector2<f64> {
        unit(self.angle)
    }

    /// The link's angle with its ω and ε as one [`Motion`] (its transfer functions φ, φ′, φ″
    /// when the input moves at unit speed).
    #[must_use]
    pub fn angle_motion(&self) -> Motion {
        Motion::new(self.angle, self.omega, self.epsilon)
    }

    /// The motion of the point of the link that is at `p` now.
    ///
    /// # Examples
    /// A crank O A of 0.1 m at φ = 90° turning at ω = 10 rad/s, ε = 0: its midpoint moves at
    /// 0.5 m/s along −x and accelerates at ω²·0.05 = 5 m/s² towards O.
    /// ```
    /// use nalgebra::{Point2, Vector2};
    /// use approx::assert_relative_eq;
    /// use tmm::kinematics::{LinkMotion, PointMotion};
    /// let crank = LinkMotion {
    ///     origin: PointMotion::fixed(Point2::origin()),
    ///     angle: std::f64::consts::FRAC_PI_2,
    ///     omega: 10.0,
    ///     epsilon: 0.0,
    /// };
    /// let m = crank.motion_of(Point2::new(0.0, 0.05));
    /// assert_relative_eq!(m.v, Vector2::new(-0.5, 0.0), epsilon = 1e-15);
    /// assert_relative_eq!(m.a, Vector2::new(0.0, -5.0), epsilon = 1e-15);
    /// ```
    #[must_use]
    pub fn motion_of(&self, p: Point2<f64>) -> PointMotion {
        self.moving_at(p, p - self.origin.p)
    }

    /// The motion of the point at `local` = (along, across) in the link's frame whose unit
    /// vector is `e` (the link's direction, or any direction fixed to the link): the point at
    /// r = along·e + across·e⊥ from the origin. The engine keeps `e` with the link's motion, so
    /// a point is placed without trigonometry.
    ///
    /// # Examples
    /// The crank of [`motion_of`](Self::motion_of)'s example, its midpoint given in the
    /// crank's frame: the same motion.
    /// ```
    /// use nalgebra::{Point2, Vector2};
    /// use tmm::kinematics::{LinkMotion, PointMotion};
    /// let crank = LinkMotion {
    ///     origin: PointMotion::fixed(Point2::origin()),
    ///     angle: std::f64::consts::FRAC_PI_2,
    ///     omega: 10.0,
    ///     epsilon: 0.0,
    /// };
    /// let m = crank.point_in_frame(Vector2::y(), Vector2::new(0.05, 0.0));
    /// assert_eq!(m, crank.motion_of(Point2::new(0.0, 0.05)));
    /// ```
    #[must_use]
    #[inline]
    pub fn point_in_frame(&self, e: Vector2<f64>, local: Vector2<f64>) -> PointMotion {
        let r = frame_offset(e, local);
        self.moving_at(self.origin.p + r, r)
    }

    /// The motion of the link's point at the offset `r` from its origin, which lies at `p`
    /// (= origin + r, as the caller computed it): Euler's formulas v = v_O + ω × r and
    /// a = a_O + ε × r − ω²·r, written once for every point of a moving link.
    #[must_use]
    #[inline]
    pub(crate) fn moving_at(&self, p: Point2<f64>, r: Vector2<f64>) -> PointMotion {
        PointMotion::new(
            p,
            self.origin.v + self.omega * perp(r),
            self.origin.a + self.epsilon * perp(r) - self.omega * self.omega * r,
        )
    }

    /// The motion of the link point at `along` metres along the link from its origin and
    /// `across` metres to the left of it (along the link direction turned +90°).
    ///
    /// A centre of mass on the line of a link at l_AS from A is `point_at(l_AS, 0.0)`.
    #[must_use]
    pub fn point_at(&self, along: f64, across: f64) -> PointMotion {
        let e = self.unit();
        self.motion_of(self.origin.p + along * e + across * perp(e))
    }
}

/// The offset r = along·e + across·e⊥ of the point at `local` = (along, across) in a frame
/// whose unit vector is `e`: where [`LinkMotion::point_in_frame`] puts a point, for a caller
/// that needs only its position.
#[must_use]
#[inline]
pub(crate) fn frame_offset(e: Vector2<f64>, local: Vector2<f64>) -> Vector2<f64> {
    local.x * e + local.y * perp(e)
}
