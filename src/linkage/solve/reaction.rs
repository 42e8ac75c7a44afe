//! What one position's kinetostatics gives per joint and per drive: a joint's reaction and a
//! drive's balance (plain data, read by handle or by name through an
//! [`Analysis`](super::Analysis)).

use crate::angle::cross;
use crate::error::{Error, Result};
use crate::kinetostatics::Conditioning;
use crate::Load;
use nalgebra::{Point2, Vector2};

/// The reaction in one joint: the force (and, in a sliding pair, the couple) that link `by`
/// exerts on link `on`, R_by,on. The other link feels the opposite.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Reaction {
    /// The link that exerts it (its index in [`Plan::link_names`](crate::linkage::Plan::link_names), [`LinkId::index`](crate::linkage::LinkId::index)).
    pub by: usize,
    /// The link it acts on.
    pub on: usize,
    /// The force, N.
    pub force: Vector2<f64>,
    /// The point the force is reduced to (the hinge, or a point on a sliding pair's axis), m.
    pub point: Point2<f64>,
    /// The couple about `point`, N·m (zero in a hinge; in a sliding pair it places the normal
    /// force's line of action, see [`Reaction::offset`]).
    pub moment: f64,
}

impl Reaction {
    /// The force (and couple) of link `by` on link `on`, reduced to `point`.
    #[must_use]
    pub fn new(by: usize, on: usize, force: Vector2<f64>, point: Point2<f64>, moment: f64) -> Self {
        Self {
            by,
            on,
            force,
            point,
            moment,
        }
    }

    /// A hinge's reaction: a force at the hinge, no couple.
    #[must_use]
    pub fn hinge(by: usize, on: usize, force: Vector2<f64>, point: Point2<f64>) -> Self {
        Self::new(by, on, force, point, 0.0)
    }

    /// The reaction as a load on link `on`.
    #[must_use]
    pub fn load(&self) -> Load {
        Load::new(self.point, self.force, self.moment)
    }

    /// The load on link `link`: the reaction itself if `link == on`, its opposite if
    /// `link == by`.
    ///
    /// # Errors
    /// [`Error::Description`] when `link` is neither of the two links the reaction joins
    /// (no load of this joint acts on it).
    pub fn load_on(&self, link: impl Into<usize>) -> Result<Load> {
        let link = link.into();
        if link == self.on || link == self.by {
            Ok(self.load_on_side(link))
        } else {
            Err(Error::Description {
                item: format!("link index {link}"),
                problem: format!(
                    "is not joined by this reaction (it acts between links {} and {})",
                    self.by, self.on
                ),
            })
        }
    }

    /// [`load_on`](Self::load_on) for a link known to be `on` or `by`.
    pub(crate) fn load_on_side(&self, link: usize) -> Load {
        if link == self.on {
            self.load()
        } else {
            Load::new(self.point, -self.force, -self.moment)
        }
    }

    /// For a sliding pair with the axis direction `axis`: where the normal force's line of
    /// action crosses the axis through `point`, measured from `point` along `axis`, m. `None`
    /// when the force vanishes and the pair carries a pure couple.
    #[must_use]
    pub fn offset(&self, axis: Vector2<f64>) -> Option<f64> {
        let h = self.moment / cross(axis / axis.norm(), self.force);
        h.is_finite().then_some(h)
    }
}

/// What the drive supplies to the input link and what the frame holds.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Balance {
    /// The balancing generalized force: for a crank M_b about its pivot, N·m, counter-clockwise
    /// positive (for a gear drive the moment of the tooth force); for a slider the force along
    /// its guide direction, N.
    pub value: f64,
    /// The balancing force: the pinion's tooth force at the pitch point (gear drive), the
    /// drive's force along the guide (slider), zero for a coupling, N.
    pub force: Vector2<f64>,
    /// Where `force` acts: the pitch point, the slider's reference point, or the pivot, m.
    pub point: Point2<f64>,
    /// The conditioning of the balance (the gear drive's arm; 1 otherwise).
    pub conditioning: Conditioning,
}
