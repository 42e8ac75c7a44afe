//! The kinematics of one position, alone: the result of a solve that asks for no loads, so it
//! has no reactions to give.

use super::spare::Held;
use crate::angle::cross;
use crate::error::Result;
use crate::kinematics::{LinkMotion, Motion, PointMotion};
use crate::linkage::handle::{JointRef, LinkRef, PointRef};
use crate::linkage::inputs::Inputs;
use crate::linkage::plan::{GroupKind, Plan, Pose};
use nalgebra::Vector2;

/// The kinematics of one position of a [`Plan`]: every link's, joint's, point's and slide's
/// motion, the groups' transmission angles and determinants. Made by [`Plan::kinematics`]
/// or a [`Solver`](super::Solver); an [`Analysis`](super::Analysis) reads the same through
/// it, and adds the loads, reactions and balances.
///
/// Every reading takes a name or a handle ([`JointRef`], [`LinkRef`], [`PointRef`]); resolve
/// names once with [`Plan::joint_id`] and friends to read by handle in a loop.
///
/// # Examples
/// ```
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::four_bar())?;
/// let k = plan.kinematics(Motion::turning(1.0, 10.0))?;
/// assert!(k.joint("B")?.v.norm() > 0.0);
/// assert!(k.link("rocker")?.rate != 0.0);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Kinematics<'p> {
    pub(crate) plan: &'p Plan,
    /// The position's buffers, one box (read as a `KinState`).
    pub(crate) kin: Held,
}

/// The buffers go back to the plan for its next one-shot solve (see `spare`).
impl Drop for Kinematics<'_> {
    #[inline(always)]
    fn drop(&mut self) {
        if let Some(p) = self.kin.0.take() {
            self.plan.spare.give(p);
        }
    }
}

impl<'p> Kinematics<'p> {
    /// Buffers for the kinematics of `plan` (a dropped solve's, or allocated here).
    #[inline(always)]
    pub(crate) fn new(plan: &'p Plan) -> Self {
        Self {
            plan,
            kin: Held::of(&plan.chain, &plan.spare),
        }
    }

    /// Solves the position at `inputs` into these buffers.
    #[inline]
    pub(crate) fn solve(&mut self, inputs: &[Motion]) -> Result<()> {
        self.kin.solve(&self.plan.chain, inputs)
    }

    /// As [`solve`](Self::solve), for a user's call: where an input moves (a nonzero rate
    /// or acceleration), a dyad within its position's rounding of a dead point is refused,
    /// as the force analysis refuses it — its rates there would be rounding divided by a
    /// determinant of rounding (a rocking input at its lock moving). A position alone
    /// (every input at rest) is still given there.
    #[inline]
    pub(crate) fn solve_checked(&mut self, inputs: &[Motion]) -> Result<()> {
        self.kin.solve(&self.plan.chain, inputs)?;
        if inputs.iter().any(|m| m.rate != 0.0 || m.accel != 0.0) {
            self.kin.refuse_dead_points(&self.plan.chain)?;
        }
        Ok(())
    }

    /// Solves only `groups` at `inputs` (see `KinState::solve_groups`): what a search over
    /// one group's motion needs.
    #[inline]
    pub(crate) fn solve_groups(&mut self, inputs: &[Motion], groups: &[usize]) -> Result<()> {
        self.kin.solve_groups(&self.plan.chain, inputs, groups)
    }

    /// The read-only view of this position (what a user's load function sees).
    #[must_use]
    #[inline]
    pub fn pose(&self) -> Pose<'_> {
        self.kin.pose(&self.plan.chain)
    }

    /// The plan this position belongs to.
    #[must_use]
    pub fn plan(&self) -> &'p Plan {
        self.plan
    }

    /// The inputs' motions, one per input.
    #[must_use]
    pub fn inputs(&self) -> Inputs {
        self.kin.inputs()
    }

    /// A link's motion in the engine's frame for it (see [`Pose::link_motion`]).
    ///
    /// # Errors
    /// As [`Plan::link_id`].
    #[inline]
    pub fn link_motion(&self, link: impl LinkRef) -> Result<LinkMotion> {
        Ok(self.kin.links[self.plan.chain.link(link)?])
    }

    /// Every link's motion in the engine's frame for it (as [`link_motion`](Self::link_motion)),
    /// indexed by the link's handle: `k.link_motions()[l.index()]` for
    /// `l = plan.link_id("rocker")?`, resolved once before a loop. The hot path's reading:
    /// no `Result` per number. Index 0 is the frame.
    #[must_use]
    #[inline]
    pub fn link_motions(&self) -> &[LinkMotion] {
        &self.kin.links
    }

    /// A link's angle along its reference direction, with ω and ε (see [`Pose::link`]).
    ///
    /// # Errors
    /// As [`Plan::link_id`].
    pub fn link(&self, link: impl LinkRef) -> Result<Motion> {
        self.pose().link(link)
    }

    /// A joint's motion (see [`Pose::joint`]).
    ///
    /// # Errors
    /// As [`Plan::joint_id`].
    pub fn joint(&self, joint: impl JointRef) -> Result<PointMotion> {
        self.pose().joint(joint)
    }

    /// A joint's motion as a point of one of its two links (see [`Pose::joint_on`]).
    ///
    /// # Errors
    /// As [`Pose::joint_on`].
    pub fn joint_on(&self, joint: impl JointRef, link: impl LinkRef) -> Result<PointMotion> {
        self.pose().joint_on(joint, link)
    }

    /// A named point's motion (see [`Pose::point`]).
    ///
    /// # Errors
    /// As [`Plan::point_id`].
    pub fn point(&self, point: impl PointRef) -> Result<PointMotion> {
        self.pose().point(point)
    }

    /// A prismatic joint's slide (see [`Pose::slide`]).
    ///
    /// # Errors
    /// As [`Pose::slide`].
    pub fn slide(&self, joint: impl JointRef) -> Result<Motion> {
        self.pose().slide(joint)
    }

    /// The current unit direction of a joint's guide (see [`Pose::guide_direction`]).
    ///
    /// # Errors
    /// As [`Plan::joint_id`].
    pub fn guide_direction(&self, joint: impl JointRef) -> Result<Vector2<f64>> {
        self.pose().guide_direction(joint)
    }

    /// The transmission angle μ of group `g` (in attachment order) at this position, rad in
    /// [0, π/2]: the acute angle between the force a group's driving link can pass on and the
    /// motion of the point it drives, complemented (μ = π/2 − the pressure angle). Engineers
    /// keep it above about 40° over the cycle; it vanishes at a dead point.
    ///
    /// - RRR: the angle between the lines of its two links at the inner joint (the coupler and
    ///   the rocker);
    /// - triad: the smallest over its binary links of the angle between the link's line and
    ///   the line from its joint B_i on the ternary link to the point where the other two
    ///   binary links' lines meet (zero at the triad's dead point, the three lines meeting);
    /// - RRP: π/2 minus the angle between the rod and the guide (μ = 0 with the rod across the
    ///   guide);
    /// - PRP: the angle between the two guides; RPP: between the slide and the guide (the
    ///   force crosses each sliding pair along its normal);
    /// - RPR: π/2 always: the sliding pair pushes the cylinder across its axis, which is the
    ///   direction its point there moves in;
    /// - a general group (above the 3rd class): not defined, an error.
    ///
    /// # Errors
    /// [`Error::OutOfRange`](crate::Error::OutOfRange) (`"group index"`) for `g` not below `plan.groups().len()`;
    /// [`Error::Description`](crate::Error::Description) for a linkage without groups, or
    /// naming a [`GroupKind::General`] group ("not defined for a group above the 3rd class").
    pub fn transmission_angle(&self, g: usize) -> Result<f64> {
        let group = &self.plan.chain.groups[self.plan.check_group(g)?];
        if let Some(t) = &group.triad {
            let pose = self.pose();
            let b = t.inner.map(|j| pose.joint_position_on(j, t.links[0]));
            return Ok(super::triad::transmission_angle(&self.kin, t, b));
        }
        let (u2, u3) = (
            self.kin.units[group.links[0]],
            self.kin.units[group.links[1]],
        );
        let between = |a: Vector2<f64>, b: Vector2<f64>| cross(a, b).abs().atan2(a.dot(&b).abs());
        Ok(match group.kind {
            GroupKind::Rrr | GroupKind::Prp | GroupKind::Rpp => between(u2, u3),
            GroupKind::Rrp => std::f64::consts::FRAC_PI_2 - between(u2, u3),
            GroupKind::Rpr | GroupKind::Triad => std::f64::consts::FRAC_PI_2,
            // No driving link meets a single driven one: no angle says how well it transmits.
            GroupKind::General => {
                return Err(crate::linkage::plan::bad(
                    &group.name,
                    "the transmission angle is not defined for a group above the 3rd class",
                ))
            }
        })
    }

    /// The kinematic conditioning of every group in attachment order: sin(φ3 − φ2) for RRR,
    /// cos(φ2 − φ4) for RRP, l_EA (m) for RPR, sin(φg3 − φg2) for PRP and sin α for RPP.
    #[must_use]
    pub fn group_determinants(&self) -> &[f64] {
        &self.kin.dets
    }
}
