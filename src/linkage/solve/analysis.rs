//! One analysed position of a planned linkage: its kinematics, the loads, the reaction in
//! every joint and each drive's balancing moment or force, and the readings of them.

use super::kinematics::Kinematics;
use crate::angle::cross;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::kinetostatics::Conditioning;
use crate::linkage::handle::JointRef;
use crate::linkage::plan::Plan;
use crate::Load;
use nalgebra::{Point2, Vector2};
use std::ops::Deref;

/// The reaction in one joint: the force (and, in a sliding pair, the couple) that link `by`
/// exerts on link `on`, R_by,on. The other link feels the opposite.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Reaction {
    /// The link that exerts it (its index in [`Plan::link_names`], [`LinkId::index`](crate::linkage::LinkId::index)).
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

/// One analysed position of a [`Plan`]: its [`Kinematics`] (every kinematic reading, through
/// `Deref`), the applied loads, the reactions and the balances.
///
/// Made by [`Plan::analyse`] (one position, its own buffers) or a
/// [`Solver`](super::Solver) (the same buffers refilled at every position: no allocation).
#[derive(Debug, Clone)]
pub struct Analysis<'p> {
    pub(crate) k: Kinematics<'p>,
    pub(crate) applied: Vec<(usize, Load)>,
    pub(crate) acc: Vec<Load>,
    pub(crate) reactions: Vec<Reaction>,
    pub(crate) conditioning: Vec<Conditioning>,
    /// One per input (the first `plan.input_count()` are meaningful).
    pub(crate) balances: [Balance; 2],
    /// The joints' friction (empty buffers for a frictionless plan).
    pub(crate) friction: super::friction::FrictionState,
}

impl<'p> Deref for Analysis<'p> {
    type Target = Kinematics<'p>;

    fn deref(&self) -> &Kinematics<'p> {
        &self.k
    }
}

impl<'p> Analysis<'p> {
    /// Buffers for analysing positions of `plan` (allocated once).
    pub(crate) fn new(plan: &'p Plan) -> Self {
        let c = &plan.chain;
        let n = c.link_names.len();
        let zero = Reaction {
            by: 0,
            on: 0,
            force: Vector2::zeros(),
            point: Point2::origin(),
            moment: 0.0,
        };
        let one = Conditioning {
            measure: 1.0,
            condition: 1.0,
        };
        let balance = Balance {
            value: 0.0,
            force: Vector2::zeros(),
            point: Point2::origin(),
            conditioning: one,
        };
        Self {
            k: Kinematics::new(plan),
            applied: Vec::with_capacity(n + plan.loads.len() * 2),
            acc: vec![Load::zero(Point2::origin()); n],
            reactions: vec![zero; c.joints.len()],
            conditioning: vec![one; c.groups.len()],
            balances: [balance; 2],
            friction: if plan.friction.is_some() {
                super::friction::FrictionState::new(c.joints.len())
            } else {
                super::friction::FrictionState::default()
            },
        }
    }

    /// Kinematics, loads, the reactions from the last group back to the input links, and the
    /// balancing moments or forces, at one motion per input.
    pub(crate) fn solve(&mut self, inputs: &[Motion]) -> Result<()> {
        self.k.solve(inputs)?;
        self.apply_loads()?;
        let plan = self.k.plan;
        match &plan.friction {
            None => self.solve_statics(),
            Some(fp) => self.solve_friction_statics(fp),
        }
    }

    /// The kinematics of this position (also every kinematic reading of `self` directly).
    #[must_use]
    pub fn kinematics(&self) -> &Kinematics<'p> {
        &self.k
    }

    /// The reaction in a joint, as the force of one of its links on the other.
    ///
    /// # Errors
    /// As [`Plan::joint_id`].
    pub fn reaction(&self, joint: impl JointRef) -> Result<Reaction> {
        Ok(self.reactions[self.plan.chain.joint(joint)?])
    }

    /// Every joint's reaction, indexed by the joint's handle: `a.reactions()[b.index()]` for
    /// `b = plan.joint_id("B")?`, resolved once before a loop. The hot path's reading: no
    /// `Result` per number, since the handle was checked when it was made.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let b = plan.joint_id("B")?; // checked once
    /// let mut solver = plan.solver();
    /// let mut peak = 0.0f64;
    /// for k in 0..36 {
    ///     let a = solver.analyse(Motion::turning(f64::from(k) * 0.1745, 10.0))?;
    ///     let r = a.reactions()[b.index()];
    ///     assert_eq!(r, a.reaction("B")?); // the same reading as by name
    ///     peak = peak.max(r.force.norm());
    /// }
    /// assert!(peak > 0.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    #[inline]
    pub fn reactions(&self) -> &[Reaction] {
        &self.reactions
    }

    /// The balancing moments (crank) or forces (slider), one per input.
    #[must_use]
    #[inline]
    pub fn balances(&self) -> &[Balance] {
        &self.balances[..self.plan.input_count()]
    }

    /// The balancing moment or force of input `i` (0 the first).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"input index"`) for an input the linkage does not have.
    pub fn balance(&self, i: usize) -> Result<Balance> {
        let n = self.plan.input_count();
        crate::linkage::handle::index_in("input index", "inputs", i, n)?;
        Ok(self.balances[i])
    }

    /// Each group's conditioning in the kinetostatics (the divisor of its closed form).
    #[must_use]
    pub fn conditioning(&self) -> &[Conditioning] {
        &self.conditioning
    }

    /// Every applied load (own inertia and weight, external) with the link it acts on
    /// (its index, [`LinkId::index`](crate::linkage::LinkId::index)).
    #[must_use]
    pub fn applied_loads(&self) -> &[(usize, Load)] {
        &self.applied
    }
}
