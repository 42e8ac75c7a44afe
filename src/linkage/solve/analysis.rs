//! One analysed position of a planned linkage: its kinematics, the loads, the reaction in
//! every joint and each drive's balancing moment or force, and the readings of them.

use super::kinematics::Kinematics;
pub use super::reaction::{Balance, Reaction};
use super::spare::StaticBuffers;
use crate::error::Result;
use crate::kinematics::Motion;
use crate::kinetostatics::Conditioning;
use crate::linkage::handle::JointRef;
use crate::linkage::plan::Plan;
use crate::Load;
use nalgebra::{Point2, Vector2};
use std::ops::Deref;

/// A closed form that divides by nothing.
const ONE: Conditioning = Conditioning {
    measure: 1.0,
    condition: 1.0,
};

/// The static buffers of `plan`'s positions (every solve writes each load, reaction and
/// conditioning it reads).
#[cold]
fn new_statics(plan: &Plan) -> StaticBuffers {
    let c = &plan.chain;
    let n = c.link_names.len();
    let balance = Balance {
        value: 0.0,
        force: Vector2::zeros(),
        point: Point2::origin(),
        conditioning: ONE,
    };
    StaticBuffers {
        applied: Vec::with_capacity(n + plan.loads.len() * 2),
        acc: vec![Load::zero(Point2::origin()); n].into(),
        reactions: vec![Reaction::hinge(0, 0, Vector2::zeros(), Point2::origin()); c.joints.len()]
            .into(),
        conditioning: vec![ONE; c.groups.len()].into(),
        balances: vec![balance; 2].into(),
        friction: if plan.friction.is_some() {
            super::friction::FrictionState::new(c.joints.len())
        } else {
            super::friction::FrictionState::default()
        },
    }
}

/// One analysed position of a [`Plan`]: its [`Kinematics`] (every kinematic reading, through
/// `Deref`), the applied loads, the reactions and the balances.
///
/// Made by [`Plan::analyse`] (one position; dropped, it gives its buffers back to the plan
/// for the next) or a [`Solver`](super::Solver) (the same buffers refilled at every
/// position).
#[derive(Debug, Clone)]
pub struct Analysis<'p> {
    pub(crate) k: Kinematics<'p>,
    pub(crate) applied: Vec<(usize, Load)>,
    pub(crate) acc: Box<[Load]>,
    pub(crate) reactions: Box<[Reaction]>,
    pub(crate) conditioning: Box<[Conditioning]>,
    /// One per input (two; the first `plan.input_count()` are meaningful).
    pub(crate) balances: Box<[Balance]>,
    /// The joints' friction (empty buffers for a frictionless plan).
    pub(crate) friction: super::friction::FrictionState,
}

impl<'p> Deref for Analysis<'p> {
    type Target = Kinematics<'p>;

    #[inline]
    fn deref(&self) -> &Kinematics<'p> {
        &self.k
    }
}

/// The static buffers go back into the position's box, and the box to the plan for its next
/// one-shot solve (see `spare`).
impl Drop for Analysis<'_> {
    #[inline(always)]
    fn drop(&mut self) {
        if let Some(mut p) = self.k.kin.0.take() {
            self.swap_statics(&mut p.statics);
            p.parked = true;
            self.k.plan.spare.give(p);
        }
    }
}

impl<'p> Analysis<'p> {
    /// Buffers for analysing positions of `plan`: a dropped solve's box, or allocated here
    /// (the static buffers when the box has none yet).
    #[inline(always)]
    pub(crate) fn new(plan: &'p Plan) -> Self {
        let mut a = Self {
            k: Kinematics::new(plan),
            applied: Vec::new(),
            acc: Box::default(),
            reactions: Box::default(),
            conditioning: Box::default(),
            balances: Box::default(),
            friction: super::friction::FrictionState::default(),
        };
        // The box is taken out for the exchange (one pointer), put back after it.
        if let Some(mut p) = a.k.kin.0.take() {
            if p.parked {
                p.parked = false;
                a.swap_statics(&mut p.statics);
            } else {
                a.swap_statics(&mut new_statics(plan));
            }
            a.k.kin.0 = Some(p);
        }
        a
    }

    /// Exchanges this analysis's static buffers with `s`'s, field by field: a pointer and a
    /// length each, nothing copied and no struct built on the way (see `Parts::statics`).
    #[inline]
    fn swap_statics(&mut self, s: &mut StaticBuffers) {
        use std::mem::swap;
        swap(&mut self.applied, &mut s.applied);
        swap(&mut self.acc, &mut s.acc);
        swap(&mut self.reactions, &mut s.reactions);
        swap(&mut self.conditioning, &mut s.conditioning);
        swap(&mut self.balances, &mut s.balances);
        swap(&mut self.friction, &mut s.friction);
    }

    /// Kinematics, loads, the reactions from the last group back to the input links, and the
    /// balancing moments or forces, at one motion per input.
    pub(crate) fn solve(&mut self, inputs: &[Motion]) -> Result<()> {
        self.k.solve(inputs)?;
        // A dyad within its position's rounding of its dead point has no forces to give.
        self.k.kin.refuse_dead_points(&self.k.plan.chain)?;
        self.apply_loads()?;
        let plan = self.k.plan;
        match &plan.friction {
            None => self.solve_statics(),
            Some(fp) => self.solve_friction_statics(fp),
        }
    }

    /// The kinematics of this position (also every kinematic reading of `self` directly).
    #[must_use]
    #[inline]
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
    /// [`Error::OutOfRange`](crate::Error::OutOfRange) (`"input index"`) for an input the
    /// linkage does not have.
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
