// The mass properties of one link: mass, central moment of inertia, centre of mass.

use super::within;
use nalgebra::Point2;
use tmm::error::Result;
use tmm::kinematics::{LinkMotion, PointMotion};
use tmm::Load;

/// The mass properties of a rigid link, with its centre of mass S given on the link.
///
/// S lies `along` metres from the link's origin along its direction and `across` metres to the
/// left of it, in the frame of the [`LinkMotion`] the kinematic block returns for this link
/// (for example the crank's origin is O1 and its direction O1→A; an RRR dyad's link 3 starts at
/// its frame pivot C). Units: kg, kg·m², m. A massless link is `LinkMass::default()`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LinkMass {
    /// The mass m, kg (zero for a link whose inertia is neglected).
    pub mass: f64,
    /// The moment of inertia J_S about the centre of mass, kg·m².
    pub inertia: f64,
    /// The distance of S from the link's origin along the link, m.
    pub along: f64,
    /// The distance of S to the left of the link's line, m.
    pub across: f64,
}

impl LinkMass {
    /// A link with its centre of mass on its line, `along` metres from its origin.
    #[must_use]
    pub fn on_line(mass: f64, inertia: f64, along: f64) -> Self {
        Self {
            mass,
            inertia,
            along,
            across: 0.0,
        }
    }

    /// A uniform slender rod of `length` and `mass`: S at its middle, J_S = m·l²/12.
    #[must_use]
    pub fn rod(mass: f64, length: f64) -> Self {
        Self::on_line(mass, mass * length * length / 12.0, 0.5 * length)
    }

    /// A slider (or any link) whose centre of mass is its origin.
    #[must_use]
    pub fn point(mass: f64) -> Self {
        Self::on_line(mass, 0.0, 0.0)
    }

    /// The motion of the centre of mass S of a link moving with `link`.
    #[must_use]
    pub fn centre(&self, link: &LinkMotion) -> PointMotion {
        link.point_at(self.along, self.across)
    }

    /// The link's own load at S: the d'Alembert inertia load (−m·a_S, −J_S·ε) plus its
    /// weight under `gravity` (m/s², acting along −y; 0 to neglect weights).
    ///
    /// # Examples
    /// A 2 kg rod of 0.3 m turning about its end at ω = 10 rad/s without ε, at 0°: S is at
    /// 0.15 m, a_S = −ω²·0.15 = −15 m/s² along the rod, so the inertia force pulls outwards
    /// with 30 N; gravity adds 2·9.81 N downwards.
    /// ```
    /// use nalgebra::{Point2, Vector2};
    /// use approx::assert_relative_eq;
    /// use tmm::kinematics::{LinkMotion, PointMotion};
    /// use tmm::mechanism::LinkMass;
    /// let link = LinkMotion { origin: PointMotion::fixed(Point2::origin()), angle: 0.0, omega: 10.0, epsilon: 0.0 };
    /// let load = LinkMass::rod(2.0, 0.3).load(&link, 9.81)?;
    /// assert_relative_eq!(load.point, Point2::new(0.15, 0.0));
    /// assert_relative_eq!(load.force, Vector2::new(30.0, -19.62), epsilon = 1e-12);
    /// assert_eq!(load.moment, 0.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// A negative or non-finite mass or moment of inertia, or non-finite kinematics
    /// (see [`Load::inertia`]).
    pub fn load(&self, link: &LinkMotion, gravity: f64) -> Result<Load> {
        let s = self.centre(link);
        let inertia = Load::inertia(s.p, self.mass, s.a, self.inertia, link.epsilon)?;
        let weight = Load::weight(s.p, self.mass, gravity);
        Ok(Load::new(
            s.p,
            inertia.force + weight.force,
            inertia.moment + weight.moment,
        ))
    }
}

/// The own loads (inertia and weight, [`LinkMass::load`]) of the links `links` with the mass
/// properties `mass`, in the same order; an error names its link from `names`.
pub(crate) fn own_loads<const N: usize>(
    mass: &[LinkMass; N],
    links: &[LinkMotion; N],
    names: &[&'static str; N],
    gravity: f64,
) -> Result<[Load; N]> {
    let mut loads = [Load::zero(Point2::origin()); N];
    for (k, load) in loads.iter_mut().enumerate() {
        *load = mass[k].load(&links[k], gravity).map_err(within(names[k]))?;
    }
    Ok(loads)
}
