//! The mass properties of one link given in its own frame, and the search for a reference
//! pose.

use crate::angle::unit;
use crate::error::Result;
use crate::linkage::{At, Mass};
use nalgebra::Point2;

/// The mass properties of a rigid link, with its centre of mass S given on the link.
///
/// S lies `along` metres from the link's origin along its direction and `across` metres to the
/// left of it, in the link's frame as each ready mechanism documents it (for example the
/// crank's origin is O1 and its direction O1→A; a rocker starts at its frame pivot). Units:
/// kg, kg·m², m. A massless link is `LinkMass::default()`. [`LinkMass::at`] turns it into the
/// engine's [`Mass`] at a pose.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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

    /// The engine's [`Mass`] of a link whose frame, in the reference pose, starts at `origin`
    /// with the direction angle `angle`: S at origin + along·e + across·e⊥.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::At;
    /// use tmm::mechanism::LinkMass;
    /// let m = LinkMass::rod(2.0, 0.3).at([1.0, 0.0], std::f64::consts::FRAC_PI_2);
    /// let At::Coords(s) = m.centre else { unreachable!() };
    /// assert!((s[0] - 1.0).abs() < 1e-15 && (s[1] - 0.15).abs() < 1e-15);
    /// assert_eq!((m.m, m.j), (2.0, 2.0 * 0.09 / 12.0));
    /// ```
    #[must_use]
    pub fn at(&self, origin: [f64; 2], angle: f64) -> Mass {
        let e = unit(angle);
        let s = [
            origin[0] + self.along * e.x - self.across * e.y,
            origin[1] + self.along * e.y + self.across * e.x,
        ];
        Mass::new(self.mass, self.inertia, At::Coords(s))
    }
}

/// A point as the engine's coordinates.
pub(crate) fn xy(p: Point2<f64>) -> [f64; 2] {
    [p.x, p.y]
}

/// The reference crank angle of a ready mechanism and its pose there: the first of a fixed
/// list of angles where `pose` assembles with a conditioning (its second value, 0 at a dead
/// point, 1 at best) of at least 0.2, else the best-conditioned one that assembles; `None`
/// when the mechanism assembles at none of them.
pub(crate) fn reference_pose<T>(pose: impl Fn(f64) -> Result<(T, f64)>) -> Option<(f64, T)> {
    let mut best: Option<(f64, f64, T)> = None;
    for k in 0..24 {
        let phi = 1.0 + f64::from(k) * std::f64::consts::TAU / 24.0;
        let Ok((t, q)) = pose(phi) else { continue };
        let q = q.abs();
        if q >= 0.2 {
            return Some((phi, t));
        }
        if best.as_ref().is_none_or(|b| q > b.1) {
            best = Some((phi, q, t));
        }
    }
    best.map(|(phi, _, t)| (phi, t))
}
