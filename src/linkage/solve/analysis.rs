//! One analysed position of a planned linkage: the buffers of its kinematics and
//! kinetostatics, and the readings of its results.
//!
//! An [`Analysis`] owns its buffers: [`Plan::analyse_into`] refills one without allocating,
//! so a sweep over millions of positions reuses a single one.

use super::state::KinState;
use crate::angle::cross;
use crate::error::{Error, Result};
use crate::kinematics::{LinkMotion, Motion, PointMotion};
use crate::kinetostatics::Conditioning;
use crate::linkage::plan::{GroupKind, Plan, Pose};
use crate::Load;
use nalgebra::{Point2, Vector2};

/// The reaction in one joint: the force (and, in a sliding pair, the couple) that link `by`
/// exerts on link `on`, R_by,on. The other link feels the opposite.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Reaction {
    /// The link that exerts it (index into [`Plan::link_names`]).
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
    pub fn load_on(&self, link: usize) -> Result<Load> {
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

/// One analysed position of a [`Plan`].
#[derive(Debug, Clone)]
pub struct Analysis<'p> {
    pub(crate) plan: &'p Plan,
    pub(crate) kin: KinState,
    pub(crate) applied: Vec<(usize, Load)>,
    pub(crate) acc: Vec<Load>,
    pub(crate) reactions: Vec<Reaction>,
    pub(crate) conditioning: Vec<Conditioning>,
    pub(crate) balance: Balance,
    pub(crate) second_balance: Option<Balance>,
    pub(crate) statics_done: bool,
}

impl<'p> Analysis<'p> {
    /// Buffers for analysing positions of `plan` (allocated once).
    #[must_use]
    pub fn new(plan: &'p Plan) -> Self {
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
        Self {
            plan,
            kin: KinState::new(c),
            applied: Vec::with_capacity(n + plan.loads.len() * 2),
            acc: vec![Load::zero(Point2::origin()); n],
            reactions: vec![zero; c.joints.len()],
            conditioning: vec![one; c.groups.len()],
            balance: Balance {
                value: 0.0,
                force: Vector2::zeros(),
                point: Point2::origin(),
                conditioning: one,
            },
            second_balance: None,
            statics_done: false,
        }
    }

    /// The read-only view of this position's kinematics.
    #[inline]
    pub fn pose(&self) -> Pose<'_> {
        self.kin.pose(&self.plan.chain)
    }

    /// The plan this position belongs to.
    #[must_use]
    pub fn plan(&self) -> &'p Plan {
        self.plan
    }

    /// Positions, velocities and accelerations of every link at the input `input` (φ1, ω1,
    /// ε1 for a crank; s, ṡ, s̈ for a slider), group by group in attachment order.
    ///
    /// # Errors
    /// Non-finite input; [`Error::In`] naming the group that cannot be assembled or is at a
    /// dead point; [`Error::Description`] for a linkage with two inputs (use
    /// [`Analysis::solve_kinematics_inputs`]).
    pub fn solve_kinematics(&mut self, input: Motion) -> Result<()> {
        self.solve_kinematics_inputs(&[input])
    }

    /// As [`Analysis::solve_kinematics`], with one motion per input: one for a linkage with
    /// one input, two for a linkage with a [`second_input`](crate::linkage::Linkage::second_input).
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics`]; [`Error::Description`] when the number of motions is
    /// not the number of inputs.
    ///
    /// # Examples
    /// The five-bar robot: both cranks at their reference angles, crank 1 turning at 1 rad/s;
    /// the end effector B moves.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Analysis, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let [q1, q2] = plan.reference_inputs()[..] else { unreachable!() };
    /// let mut a = Analysis::new(&plan);
    /// a.solve_kinematics_inputs(&[Motion::new(q1, 1.0, 0.0), Motion::new(q2, 0.0, 0.0)])?;
    /// assert!(a.joint("B")?.v.norm() > 0.0);
    /// assert!(a.solve_kinematics(Motion::new(q1, 1.0, 0.0)).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn solve_kinematics_inputs(&mut self, inputs: &[Motion]) -> Result<()> {
        self.statics_done = false;
        self.kin.solve(&self.plan.chain, inputs)
    }

    /// Kinematics, loads, the reactions from the last group back to the input link, and the
    /// balancing moment or force.
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics`]; a load that cannot be evaluated (a non-finite
    /// inertia load, an indicator diagram read outside its stroke); [`Error::In`] naming the
    /// group or the input link whose closed form is singular.
    pub fn solve(&mut self, input: Motion) -> Result<()> {
        self.solve_inputs(&[input])
    }

    /// As [`Analysis::solve`], with one motion per input (see
    /// [`Analysis::solve_kinematics_inputs`]): a linkage with two inputs gets two balancing
    /// moments or forces, [`Analysis::balance`] and [`Analysis::second_balance`].
    ///
    /// # Errors
    /// As [`Analysis::solve`] and [`Analysis::solve_kinematics_inputs`].
    ///
    /// # Examples
    /// The five-bar robot turning both cranks: the two balancing moments supply the power of
    /// every load, and every link is in equilibrium.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Analysis, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let r = plan.reference_inputs();
    /// let mut a = Analysis::new(&plan);
    /// a.solve_inputs(&[Motion::new(r[0], 2.0, 1.0), Motion::new(r[1], -1.0, 3.0)])?;
    /// assert!(a.second_balance().is_some());
    /// assert!(a.power_check()?.relative_error() < 1e-12);
    /// assert!(a.worst_residual() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn solve_inputs(&mut self, inputs: &[Motion]) -> Result<()> {
        self.solve_kinematics_inputs(inputs)?;
        self.apply_loads()?;
        self.solve_statics()
    }

    // ---- kinematic results (read through the position's Pose) ---------------------------

    /// The input φ1, ω1, ε1 (or s, ṡ, s̈).
    #[must_use]
    pub fn input(&self) -> Motion {
        self.kin.input
    }

    /// The second input's motion, for a linkage with two inputs.
    #[must_use]
    pub fn second_input(&self) -> Option<Motion> {
        self.kin.second_input
    }

    /// The motion of link `k` in the frame the engine uses for it (its origin a joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn link_motion(&self, k: usize) -> Result<&LinkMotion> {
        Ok(&self.kin.links[self.plan.check_link(k)?])
    }

    /// The angle of link `k` along its declared reference direction, with ω and ε.
    ///
    /// # Errors
    /// As [`Pose::link_angle_index`].
    pub fn link_angle_index(&self, k: usize) -> Result<Motion> {
        self.pose().link_angle_index(k)
    }

    /// As [`link_angle_index`](Self::link_angle_index), for an index known to be a link's.
    #[inline]
    pub(crate) fn link_angle_at(&self, k: usize) -> Motion {
        self.pose().link_angle_at(k)
    }

    /// The angle of the link called `name` (rad, along its reference direction), ω and ε.
    ///
    /// # Errors
    /// An unknown name.
    pub fn link(&self, name: &str) -> Result<Motion> {
        self.pose().link(name)
    }

    /// The motion of joint `j` as a point of the `side`-th of its two links
    /// ([`Plan::joint_links`]).
    ///
    /// # Errors
    /// As [`Pose::joint_on`].
    pub fn joint_on(&self, j: usize, side: usize) -> Result<PointMotion> {
        self.pose().joint_on(j, side)
    }

    /// The motion of joint `j` as a point of link `link` (one of its two links).
    ///
    /// # Errors
    /// As [`Pose::joint_index_on`].
    pub fn joint_index_on(&self, j: usize, link: usize) -> Result<PointMotion> {
        self.pose().joint_index_on(j, link)
    }

    /// The motion of the joint called `name` (for a prismatic joint, its point on the sliding
    /// link).
    ///
    /// # Errors
    /// An unknown name.
    pub fn joint(&self, name: &str) -> Result<PointMotion> {
        self.pose().joint(name)
    }

    /// The motion of joint `j` (for a prismatic joint, its point on the sliding link).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn joint_motion(&self, j: usize) -> Result<PointMotion> {
        self.pose().joint_motion(j)
    }

    /// As [`joint_motion`](Self::joint_motion), for an index known to be a joint's.
    #[inline]
    pub(crate) fn joint_motion_at(&self, j: usize) -> PointMotion {
        self.pose().joint_motion_at(j)
    }

    /// The motion of the named point `name`.
    ///
    /// # Errors
    /// An unknown name.
    pub fn point(&self, name: &str) -> Result<PointMotion> {
        self.pose().point(name)
    }

    /// The motion of named point `k`.
    ///
    /// # Errors
    /// As [`Pose::point_motion`].
    pub fn point_motion(&self, k: usize) -> Result<PointMotion> {
        self.pose().point_motion(k)
    }

    /// As [`point_motion`](Self::point_motion), for an index known to be a named point's.
    #[inline]
    pub(crate) fn point_motion_at(&self, k: usize) -> PointMotion {
        self.pose().point_motion_at(k)
    }

    /// The current unit direction of the guide of prismatic joint `j` (zero for a revolute
    /// joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn guide_direction(&self, j: usize) -> Result<Vector2<f64>> {
        self.pose().guide_direction(j)
    }

    /// The slide of prismatic joint `j` (see [`Pose::slide_index`]).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn slide_index(&self, j: usize) -> Result<Motion> {
        self.pose().slide_index(j)
    }

    /// As [`slide_index`](Self::slide_index), for an index known to be a joint's.
    pub(crate) fn slide_at(&self, j: usize) -> Motion {
        self.pose().slide_at(j)
    }

    /// The slide of the prismatic joint called `name`.
    ///
    /// # Errors
    /// An unknown name, or a revolute joint.
    pub fn slide(&self, name: &str) -> Result<Motion> {
        self.pose().slide(name)
    }

    /// The transmission angle μ of group `g` (in attachment order) at this position, rad in
    /// [0, π/2]: the acute angle between the force a group's driving link can pass on and the
    /// motion of the point it drives, complemented (μ = π/2 − the pressure angle). Engineers
    /// keep it above about 40° over the cycle; it vanishes at a dead point.
    ///
    /// - RRR: the angle between the lines of its two links at the inner joint (the coupler and
    ///   the rocker);
    /// - RRP: π/2 minus the angle between the rod and the guide (μ = 0 with the rod across the
    ///   guide);
    /// - PRP: the angle between the two guides; RPP: between the slide and the guide (the
    ///   force crosses each sliding pair along its normal);
    /// - RPR: π/2 always: the sliding pair pushes the cylinder across its axis, which is the
    ///   direction its point there moves in.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"group index"`) for `g` not below `plan.groups().len()`;
    /// [`Error::Description`] for a linkage without groups.
    pub fn transmission_angle(&self, g: usize) -> Result<f64> {
        let group = &self.plan.chain.groups[self.plan.check_group(g)?];
        let (u2, u3) = (
            self.kin.units[group.links[0]],
            self.kin.units[group.links[1]],
        );
        let between = |a: Vector2<f64>, b: Vector2<f64>| cross(a, b).abs().atan2(a.dot(&b).abs());
        Ok(match group.kind {
            GroupKind::Rrr | GroupKind::Prp | GroupKind::Rpp => between(u2, u3),
            GroupKind::Rrp => std::f64::consts::FRAC_PI_2 - between(u2, u3),
            GroupKind::Rpr => std::f64::consts::FRAC_PI_2,
        })
    }

    /// The kinematic conditioning of every group in attachment order: sin(φ3 − φ2) for RRR,
    /// cos(φ2 − φ4) for RRP, l_EA (m) for RPR, sin(φg3 − φg2) for PRP and sin α for RPP.
    #[must_use]
    pub fn group_determinants(&self) -> &[f64] {
        &self.kin.dets
    }

    // ---- kinetostatic results ----------------------------------------------------------

    /// The reaction in joint `j` (valid after [`Analysis::solve`]).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn reaction_index(&self, j: usize) -> Result<Reaction> {
        Ok(self.reaction_at(self.plan.check_joint(j)?))
    }

    /// As [`reaction_index`](Self::reaction_index), for an index known to be a joint's.
    #[inline]
    pub(crate) fn reaction_at(&self, j: usize) -> Reaction {
        self.reactions[j]
    }

    /// The reaction in the joint called `name`, as the force of one of its links on the other.
    ///
    /// # Errors
    /// An unknown name.
    pub fn reaction(&self, name: &str) -> Result<Reaction> {
        Ok(self.reactions[self.plan.joint_index(name)?])
    }

    /// The balancing moment (crank) or force (slider) of the (first) input.
    #[must_use]
    pub fn balance(&self) -> Balance {
        self.balance
    }

    /// The balancing moment or force of the second input, for a linkage with two inputs
    /// (valid after [`Analysis::solve_inputs`]).
    #[must_use]
    pub fn second_balance(&self) -> Option<Balance> {
        self.second_balance
    }

    /// Each group's conditioning in the kinetostatics (the divisor of its closed form).
    #[must_use]
    pub fn conditioning(&self) -> &[Conditioning] {
        &self.conditioning
    }

    /// Every applied load (own inertia and weight, external) with the link it acts on.
    #[must_use]
    pub fn applied_loads(&self) -> &[(usize, Load)] {
        &self.applied
    }

    /// Whether the kinetostatics of this position has been solved.
    #[must_use]
    pub fn has_statics(&self) -> bool {
        self.statics_done
    }
}

impl Plan {
    /// Analyses one position (allocating its buffers; see [`Plan::analyse_into`] for sweeps).
    ///
    /// # Errors
    /// As [`Analysis::solve`].
    pub fn analyse(&self, input: Motion) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve(input)?;
        Ok(a)
    }

    /// Analyses one position into existing buffers: no allocation. The buffers must have
    /// been made for this plan ([`Analysis::new`] with it, or a previous analysis of it).
    ///
    /// # Errors
    /// [`Error::Description`] for buffers made for another plan (they would be solved for
    /// theirs, not this one); as [`Analysis::solve`].
    pub fn analyse_into(&self, input: Motion, into: &mut Analysis<'_>) -> Result<()> {
        if !std::ptr::eq(into.plan, self) {
            return Err(Error::Description {
                item: "analysis buffers".to_owned(),
                problem: "were made for another plan: make them with Analysis::new(plan)"
                    .to_owned(),
            });
        }
        into.solve(input)
    }

    /// Analyses one position of a linkage with one or two inputs (one motion per input).
    ///
    /// # Errors
    /// As [`Analysis::solve_inputs`].
    ///
    /// # Examples
    /// The five-bar robot held still against its tool moment: both drives hold it.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let r = plan.reference_inputs();
    /// let a = plan.analyse_inputs(&[Motion::fixed(r[0]), Motion::fixed(r[1])])?;
    /// let (m1, m4) = (a.balance().value, a.second_balance().unwrap().value);
    /// assert!(m1.abs() > 0.0 && m4.abs() > 0.0);
    /// assert!(a.worst_residual() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn analyse_inputs(&self, inputs: &[Motion]) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve_inputs(inputs)?;
        Ok(a)
    }

    /// The kinematics alone at one position of a linkage with one or two inputs.
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics_inputs`].
    pub fn kinematics_inputs(&self, inputs: &[Motion]) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve_kinematics_inputs(inputs)?;
        Ok(a)
    }

    /// The kinematics alone at one position.
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics`].
    pub fn kinematics(&self, input: Motion) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve_kinematics(input)?;
        Ok(a)
    }
}
