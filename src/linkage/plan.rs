#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The solve plan's data model, made once from a description by [`build`](super::build):
//! indices instead of names, lengths and local coordinates read off the reference pose,
//! assembly modes, the groups in attachment order and the loads with the links they act on;
//! every accessor of a [`Plan`]; and [`Pose`], the read-only view of one solved position that
//! a user's load function sees.
//!
//! The plan is two parts: the kinematic [`Chain`] (everything one position's kinematics
//! needs, made and checked first) and the loads on it. Nothing here solves anything.

use super::description::Drive;
use super::indicator::IndicatorDiagram;
use crate::error::{Error, Result};
use crate::kinematics::frame_offset;
use crate::kinematics::{Branch, LinkMotion, Motion, PointMotion};
use crate::Load;
use nalgebra::{Point2, Vector2};
use std::fmt;
use std::sync::Arc;

/// A user's load as a function of the kinematic state.
type LoadFnBox = Arc<dyn Fn(&Pose<'_>) -> Result<Load> + Send + Sync>;

/// The kind of an Assur dyad of the 2nd class, by its joints from one outer joint through the
/// inner joint to the other (R revolute, P prismatic).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum GroupKind {
    /// Three hinges (the seeds' SR1).
    Rrr,
    /// A hinge, a hinge, and a slider on a guide of a known link (SR2).
    Rrp,
    /// A rod hinged to a known link sliding in a cylinder hinged to another (SR3).
    Rpr,
    /// Two sliders, each on a guide of a known link, hinged to each other (the cross-slide,
    /// the slotted-crank drive of a slider).
    Prp,
    /// A link hinged to a known link and sliding in a second link, which slides on a guide of
    /// another known link (the Scotch yoke, the sine and tangent mechanisms).
    Rpp,
}

impl GroupKind {
    /// "RRR", "RRP", "RPR", "PRP" or "RPP".
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Rrr => "RRR",
            Self::Rrp => "RRP",
            Self::Rpr => "RPR",
            Self::Prp => "PRP",
            Self::Rpp => "RPP",
        }
    }
}

/// A dyad of the plan, in attachment order.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Its kind.
    pub kind: GroupKind,
    /// A name for tables and errors, for example `"group (coupler, rocker) RRR"`.
    pub name: String,
    /// Its two links (indices into [`Plan::link_names`]); the second is the slider of an RRP,
    /// the first is the hinged link of an RPP.
    pub links: [usize; 2],
    /// Its joints: the first link's outer joint, the inner joint, the second link's outer
    /// joint (indices into [`Plan::joint_names`]).
    pub joints: [usize; 3],
    /// The known links its outer joints attach to.
    pub known: [usize; 2],
    /// The assembly mode (read off the reference pose unless overridden).
    pub branch: Branch,
    pub(crate) a_local: Vector2<f64>,
    pub(crate) c_local: Vector2<f64>,
    pub(crate) lengths: [f64; 2],
    /// The directions of the outer sliding pairs' guides relative to the frames of the known
    /// links that carry them (first and second outer joint).
    pub(crate) guide_offsets: [f64; 2],
    /// RPP: the angle α from the guide to the slide between the group's links.
    pub(crate) slide_angle: f64,
}

/// How the plan drives an input link.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum InputPlan {
    Crank {
        link: usize,
        joint: usize,
        pivot: Point2<f64>,
        drive: Drive,
    },
    Slider {
        link: usize,
        joint: usize,
        at: Point2<f64>,
        angle: f64,
    },
}

impl InputPlan {
    /// The input link.
    pub(crate) fn link(&self) -> usize {
        match *self {
            Self::Crank { link, .. } | Self::Slider { link, .. } => link,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LinkPlan {
    pub angle_offset: f64,
    pub mass: f64,
    pub inertia: f64,
    pub centre: Vector2<f64>,
    pub size: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct JointPlan {
    pub links: [usize; 2],
    pub local: [Vector2<f64>; 2],
    /// For a prismatic joint: which of `links` carries the guide, and the guide's direction
    /// relative to each link's frame angle.
    pub prismatic: Option<(usize, [f64; 2])>,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PointPlan {
    pub link: usize,
    pub local: Vector2<f64>,
}

/// A user-supplied load: a function of the kinematic state at a position.
#[derive(Clone)]
pub(crate) struct LoadFn(pub LoadFnBox);

impl fmt::Debug for LoadFn {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("LoadFn")
    }
}

impl PartialEq for LoadFn {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LoadPlan {
    Force {
        link: usize,
        local: Vector2<f64>,
        force: Vector2<f64>,
    },
    Moment {
        link: usize,
        moment: f64,
    },
    Turning {
        link: usize,
        forward: f64,
        backward: f64,
    },
    Sliding {
        joint: usize,
        local: Vector2<f64>,
        forward: f64,
        backward: f64,
    },
    Indicator {
        joint: usize,
        head: f64,
        diagram: IndicatorDiagram,
        /// The dead centres as the slide s·head at the head end and at the crank end.
        ends: [f64; 2],
    },
    Custom {
        link: usize,
        f: LoadFn,
    },
}

/// The kinematic chain of a plan: the names, the links' and joints' local geometry, the
/// inputs and the groups in attachment order. It is all one position's kinematics needs, so
/// [`build`](super::build) makes it (and solves its reference pose) before the loads, and
/// the position pass works on it alone.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chain {
    pub link_names: Vec<String>,
    pub joint_names: Vec<String>,
    pub point_names: Vec<String>,
    pub links: Vec<LinkPlan>,
    pub joints: Vec<JointPlan>,
    pub points: Vec<PointPlan>,
    pub input: InputPlan,
    /// The second input of a linkage of mobility 2, with its reference coordinate.
    pub second_input: Option<(InputPlan, f64)>,
    pub groups: Vec<Group>,
    pub mobility: i64,
    pub reference_input: f64,
    pub size: f64,
}

/// A linkage checked and planned for solving: made once, used at every position.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub(crate) name: String,
    pub(crate) chain: Chain,
    pub(crate) loads: Vec<LoadPlan>,
    pub(crate) gravity: Vector2<f64>,
}

/// Checks index `i` (called `name`, for example `"joint index"`) against a collection of `len`
/// `things`: `Ok(i)` below `len`, else [`Error::OutOfRange`] over `[0, len − 1]`, or
/// [`Error::Description`] when there are no `things` at all (no interval to name).
fn index_in(name: &'static str, things: &str, i: usize, len: usize) -> Result<usize> {
    if i < len {
        Ok(i)
    } else if len == 0 {
        Err(bad(
            format!("{name} {i}"),
            format!("the linkage has no {things}"),
        ))
    } else {
        Err(Error::OutOfRange {
            name,
            value: i as f64,
            min: 0.0,
            max: (len - 1) as f64,
            ends: crate::Ends::Closed,
        })
    }
}

/// A description error: `item` names the joint, link, load or field, `problem` what is wrong.
pub(crate) fn bad(item: impl Into<String>, problem: impl Into<String>) -> Error {
    Error::Description {
        item: item.into(),
        problem: problem.into(),
    }
}
impl Chain {
    /// The index of the link called `name`.
    pub(crate) fn link_index(&self, name: &str) -> Result<usize> {
        self.link_names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| bad(format!("link {name}"), "is not a link of this linkage"))
    }

    /// The index of the joint called `name`.
    pub(crate) fn joint_index(&self, name: &str) -> Result<usize> {
        self.joint_names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| bad(format!("joint {name}"), "is not a joint of this linkage"))
    }

    /// The index of the named point called `name`.
    pub(crate) fn point_index(&self, name: &str) -> Result<usize> {
        self.point_names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| {
                bad(
                    format!("point {name}"),
                    "is not a named point of this linkage",
                )
            })
    }

    /// Checks a link's index: `Ok(k)` for an index below `link_names.len()`.
    pub(crate) fn check_link(&self, k: usize) -> Result<usize> {
        index_in("link index", "links", k, self.link_names.len())
    }

    /// Checks a joint's index: `Ok(j)` for an index below `joint_names.len()`.
    pub(crate) fn check_joint(&self, j: usize) -> Result<usize> {
        index_in("joint index", "joints", j, self.joint_names.len())
    }

    /// Checks a named point's index: `Ok(k)` for an index below `point_names.len()`.
    pub(crate) fn check_point(&self, k: usize) -> Result<usize> {
        index_in("point index", "named points", k, self.point_names.len())
    }

    /// Checks a group's index: `Ok(g)` for an index below `groups.len()`.
    pub(crate) fn check_group(&self, g: usize) -> Result<usize> {
        index_in("group index", "groups", g, self.groups.len())
    }

    /// The number of inputs: 1, or 2.
    pub(crate) fn input_count(&self) -> usize {
        1 + usize::from(self.second_input.is_some())
    }

    /// The input coordinates in the reference pose, one per input.
    pub(crate) fn reference_inputs(&self) -> Vec<f64> {
        std::iter::once(self.reference_input)
            .chain(self.second_input.as_ref().map(|(_, r)| *r))
            .collect()
    }

    /// The reference pose at rest, one motion per input.
    pub(crate) fn reference_motions(&self) -> Vec<Motion> {
        self.reference_inputs()
            .into_iter()
            .map(|r| Motion::new(r, 0.0, 0.0))
            .collect()
    }

    /// Whether joint `joint` (a valid index) is prismatic.
    #[inline]
    pub(crate) fn is_prismatic_at(&self, joint: usize) -> bool {
        self.joints[joint].prismatic.is_some()
    }

    /// The link that carries the guide of joint `joint` (a valid index), if it is prismatic.
    #[inline]
    pub(crate) fn guide_link_at(&self, joint: usize) -> Option<usize> {
        let j = &self.joints[joint];
        j.prismatic.map(|(side, _)| j.links[side])
    }
}

impl Plan {
    /// Adds a load computed by `f` from the kinematic state at each position (a force at a
    /// point plus a couple, on `link`): anything the description's load kinds do not cover.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown link.
    ///
    /// # Examples
    /// A spring of 2 kN/m from a fixed point (0.5, 0.5) m to the coupler's point B:
    /// ```
    /// # use tmm::linkage::{Plan, bundled};
    /// use tmm::Load;
    /// let mut plan = Plan::new(&bundled::four_bar())?;
    /// plan.add_load_fn("coupler", |a| {
    ///     let b = a.joint("B")?.p;
    ///     let stretch = b - nalgebra::Point2::new(0.5, 0.5);
    ///     Ok(Load::force_at(b, -2000.0 * stretch))
    /// })?;
    /// let r = plan.analyse(tmm::kinematics::Motion::new(1.0, 10.0, 0.0))?;
    /// assert!(r.power_check()?.relative_error() < 1e-9);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn add_load_fn<F>(&mut self, link: &str, f: F) -> Result<()>
    where
        F: Fn(&Pose<'_>) -> Result<Load> + Send + Sync + 'static,
    {
        let link = self.link_index(link)?;
        self.loads.push(LoadPlan::Custom {
            link,
            f: LoadFn(Arc::new(f)),
        });
        Ok(())
    }

    /// The linkage's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The mobility by Chebyshev's formula: the number of inputs (1, or 2 with a
    /// [`second_input`](super::Linkage::second_input)).
    #[must_use]
    pub fn mobility(&self) -> i64 {
        self.chain.mobility
    }

    /// The dyads in attachment order.
    #[must_use]
    pub fn groups(&self) -> &[Group] {
        &self.chain.groups
    }

    /// The links' names; index 0 is the frame.
    #[must_use]
    pub fn link_names(&self) -> &[String] {
        &self.chain.link_names
    }

    /// The joints' names, in the description's order.
    #[must_use]
    pub fn joint_names(&self) -> &[String] {
        &self.chain.joint_names
    }

    /// The named points' names.
    #[must_use]
    pub fn point_names(&self) -> &[String] {
        &self.chain.point_names
    }

    /// The input coordinate in the reference pose: the crank's angle (rad), or 0 for a
    /// slider (its coordinate is measured from the reference pose).
    #[must_use]
    pub fn reference_input(&self) -> f64 {
        self.chain.reference_input
    }

    /// Whether the input is a crank (an angle) rather than a slider (a length).
    #[must_use]
    pub fn input_is_crank(&self) -> bool {
        matches!(self.chain.input, InputPlan::Crank { .. })
    }

    /// The input link's index.
    #[must_use]
    pub fn input_link(&self) -> usize {
        match self.chain.input {
            InputPlan::Crank { link, .. } | InputPlan::Slider { link, .. } => link,
        }
    }

    /// The number of inputs (degrees of freedom): 1, or 2 for a linkage with a
    /// [`second_input`](super::Linkage::second_input).
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// assert_eq!(Plan::new(&bundled::four_bar())?.input_count(), 1);
    /// assert_eq!(Plan::new(&bundled::five_bar_robot())?.input_count(), 2);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn input_count(&self) -> usize {
        self.chain.input_count()
    }

    /// The second input link's index, for a linkage with two inputs.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// assert_eq!(plan.second_input_link(), Some(plan.link_index("crank 4")?));
    /// assert_eq!(Plan::new(&bundled::four_bar())?.second_input_link(), None);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn second_input_link(&self) -> Option<usize> {
        self.chain.second_input.as_ref().map(|(ip, _)| ip.link())
    }

    /// The input coordinates in the reference pose, one per input (see
    /// [`reference_input`](Self::reference_input)).
    ///
    /// # Examples
    /// The five-bar robot is drawn with its cranks at 120° and 60°:
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let r = Plan::new(&bundled::five_bar_robot())?.reference_inputs();
    /// assert!((r[0].to_degrees() - 120.0).abs() < 1e-12 && (r[1].to_degrees() - 60.0).abs() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn reference_inputs(&self) -> Vec<f64> {
        self.chain.reference_inputs()
    }

    /// The largest distance between two joints in the reference pose, m.
    #[must_use]
    pub fn size(&self) -> f64 {
        self.chain.size
    }

    /// The index of the link called `name`.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name.
    pub fn link_index(&self, name: &str) -> Result<usize> {
        self.chain.link_index(name)
    }

    /// The index of the joint called `name`.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name.
    pub fn joint_index(&self, name: &str) -> Result<usize> {
        self.chain.joint_index(name)
    }

    /// The index of the named point called `name`.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name.
    pub fn point_index(&self, name: &str) -> Result<usize> {
        self.chain.point_index(name)
    }

    /// Checks a link's index: `Ok(k)` for an index below `link_names().len()`.
    pub(crate) fn check_link(&self, k: usize) -> Result<usize> {
        self.chain.check_link(k)
    }

    /// Checks a joint's index: `Ok(j)` for an index below `joint_names().len()`.
    pub(crate) fn check_joint(&self, j: usize) -> Result<usize> {
        self.chain.check_joint(j)
    }

    /// Checks a named point's index: `Ok(k)` for an index below `point_names().len()`.
    pub(crate) fn check_point(&self, k: usize) -> Result<usize> {
        self.chain.check_point(k)
    }

    /// Checks a group's index: `Ok(g)` for an index below `groups().len()`.
    pub(crate) fn check_group(&self, g: usize) -> Result<usize> {
        self.chain.check_group(g)
    }

    /// The link named point `point` belongs to and its local coordinates, for
    /// [`LinkMotion::point_at`].
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"point index"`) for `point` not below `point_names().len()`;
    /// [`Error::Description`] for a linkage without named points.
    pub fn point_local(&self, point: usize) -> Result<(usize, Vector2<f64>)> {
        Ok(self.point_local_at(self.check_point(point)?))
    }

    /// As [`point_local`](Self::point_local), for an index known to be a named point's.
    #[inline]
    pub(crate) fn point_local_at(&self, point: usize) -> (usize, Vector2<f64>) {
        (
            self.chain.points[point].link,
            self.chain.points[point].local,
        )
    }

    /// Whether joint `joint` is prismatic.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `joint` not below `joint_names().len()`.
    pub fn is_prismatic(&self, joint: usize) -> Result<bool> {
        Ok(self.is_prismatic_at(self.check_joint(joint)?))
    }

    /// As [`is_prismatic`](Self::is_prismatic), for an index known to be a joint's.
    #[inline]
    pub(crate) fn is_prismatic_at(&self, joint: usize) -> bool {
        self.chain.is_prismatic_at(joint)
    }

    /// The two links a joint joins.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `joint` not below `joint_names().len()`.
    pub fn joint_links(&self, joint: usize) -> Result<[usize; 2]> {
        Ok(self.joint_links_at(self.check_joint(joint)?))
    }

    /// As [`joint_links`](Self::joint_links), for an index known to be a joint's.
    #[inline]
    pub(crate) fn joint_links_at(&self, joint: usize) -> [usize; 2] {
        self.chain.joints[joint].links
    }

    /// For a prismatic joint, the link that carries its guide (one of
    /// [`joint_links`](Self::joint_links)); `None` for a revolute joint.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `joint` not below `joint_names().len()`.
    ///
    /// # Examples
    /// The shaper's ram slides on a guide of the frame (link 0):
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::shaper())?;
    /// assert_eq!(plan.guide_link(plan.joint_index("Q")?)?, Some(0));
    /// assert_eq!(plan.guide_link(plan.joint_index("O1")?)?, None);
    /// assert!(plan.guide_link(plan.joint_names().len()).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn guide_link(&self, joint: usize) -> Result<Option<usize>> {
        Ok(self.guide_link_at(self.check_joint(joint)?))
    }

    /// As [`guide_link`](Self::guide_link), for an index known to be a joint's.
    #[inline]
    pub(crate) fn guide_link_at(&self, joint: usize) -> Option<usize> {
        self.chain.guide_link_at(joint)
    }
}

/// One solved position, read-only: the motions of the links, joints, named points and
/// slides. It is what a load added by [`Plan::add_load_fn`] sees, and what every result of a
/// solve reads its kinematics from.
#[derive(Debug, Clone, Copy)]
pub struct Pose<'a> {
    pub(crate) chain: &'a Chain,
    pub(crate) links: &'a [LinkMotion],
    /// Each link's unit vector e(φ), kept with its motion.
    pub(crate) units: &'a [Vector2<f64>],
    pub(crate) input: Motion,
    pub(crate) second_input: Option<Motion>,
}

impl Pose<'_> {
    /// The motion of the point at `local` in link `k`'s frame.
    #[inline]
    pub(crate) fn at(&self, k: usize, local: Vector2<f64>) -> PointMotion {
        self.links[k].point_in_frame(self.units[k], local)
    }

    /// The position alone of joint `j` as a point of link `link` (one of its two links): what
    /// [`joint_on_link`](Self::joint_on_link) gives as `p`, to the bit, without the
    /// velocity and acceleration the reactions do not need.
    #[inline]
    pub(crate) fn joint_position_on(&self, j: usize, link: usize) -> Point2<f64> {
        let jp = &self.chain.joints[j];
        let local = jp.local[usize::from(jp.links[1] == link)];
        self.links[link].origin.p + frame_offset(self.units[link], local)
    }

    /// The input φ1, ω1, ε1 (or s, ṡ, s̈).
    #[must_use]
    pub fn input(&self) -> Motion {
        self.input
    }

    /// The second input's motion, for a linkage with two inputs.
    #[must_use]
    pub fn second_input(&self) -> Option<Motion> {
        self.second_input
    }

    /// The motion of link `k` in the frame the engine uses for it (its origin a joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn link_motion(&self, k: usize) -> Result<&LinkMotion> {
        Ok(&self.links[self.chain.check_link(k)?])
    }

    /// The angle of link `k` along its declared reference direction, with ω and ε.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn link_angle_index(&self, k: usize) -> Result<Motion> {
        Ok(self.link_angle_at(self.chain.check_link(k)?))
    }

    /// As [`link_angle_index`](Self::link_angle_index), for an index known to be a link's.
    #[inline]
    pub(crate) fn link_angle_at(&self, k: usize) -> Motion {
        let l = &self.links[k];
        Motion::new(
            crate::angle::normalize(l.angle + self.chain.links[k].angle_offset),
            l.omega,
            l.epsilon,
        )
    }

    /// The angle of the link called `name` (rad, along its reference direction), ω and ε.
    ///
    /// # Errors
    /// An unknown name.
    pub fn link(&self, name: &str) -> Result<Motion> {
        Ok(self.link_angle_at(self.chain.link_index(name)?))
    }

    /// The motion of joint `j` as a point of the `side`-th of its two links
    /// ([`Plan::joint_links`]).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`;
    /// [`Error::OutOfRange`] (`"side"`) for `side` not 0 or 1.
    pub fn joint_on(&self, j: usize, side: usize) -> Result<PointMotion> {
        let j = self.chain.check_joint(j)?;
        if side > 1 {
            return Err(Error::OutOfRange {
                name: "side",
                value: side as f64,
                min: 0.0,
                max: 1.0,
                ends: crate::Ends::Closed,
            });
        }
        Ok(self.joint_on_at(j, side))
    }

    /// As [`joint_on`](Self::joint_on), for a joint's index and a side 0 or 1.
    #[inline]
    pub(crate) fn joint_on_at(&self, j: usize, side: usize) -> PointMotion {
        let jp = &self.chain.joints[j];
        self.at(jp.links[side], jp.local[side])
    }

    /// The motion of joint `j` as a point of link `link` (one of its two links).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`, `"link index"`) for `j` not below
    /// `plan.joint_names().len()` or `link` not below `plan.link_names().len()`;
    /// [`Error::Description`] naming both when the joint does not join link `link`.
    pub fn joint_index_on(&self, j: usize, link: usize) -> Result<PointMotion> {
        let c = self.chain;
        let j = c.check_joint(j)?;
        let link = c.check_link(link)?;
        let links = c.joints[j].links;
        if !links.contains(&link) {
            return Err(Error::Description {
                item: format!("joint {}", c.joint_names[j]),
                problem: format!(
                    "does not join link {} (it joins {} and {})",
                    c.link_names[link], c.link_names[links[0]], c.link_names[links[1]]
                ),
            });
        }
        Ok(self.joint_on_link(j, link))
    }

    /// As [`joint_index_on`](Self::joint_index_on), for a joint's index and one of its links.
    #[inline]
    pub(crate) fn joint_on_link(&self, j: usize, link: usize) -> PointMotion {
        let side = usize::from(self.chain.joints[j].links[1] == link);
        self.joint_on_at(j, side)
    }

    /// The motion of the joint called `name` (for a prismatic joint, its point on the sliding
    /// link).
    ///
    /// # Errors
    /// An unknown name.
    pub fn joint(&self, name: &str) -> Result<PointMotion> {
        Ok(self.joint_motion_at(self.chain.joint_index(name)?))
    }

    /// The motion of joint `j` (for a prismatic joint, its point on the sliding link).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn joint_motion(&self, j: usize) -> Result<PointMotion> {
        Ok(self.joint_motion_at(self.chain.check_joint(j)?))
    }

    /// As [`joint_motion`](Self::joint_motion), for an index known to be a joint's.
    #[inline]
    pub(crate) fn joint_motion_at(&self, j: usize) -> PointMotion {
        let side = match self.chain.joints[j].prismatic {
            Some((guide, _)) => 1 - guide,
            None => 0,
        };
        self.joint_on_at(j, side)
    }

    /// The motion of the named point `name`.
    ///
    /// # Errors
    /// An unknown name.
    pub fn point(&self, name: &str) -> Result<PointMotion> {
        Ok(self.point_motion_at(self.chain.point_index(name)?))
    }

    /// The motion of named point `k`.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"point index"`) for `k` not below `plan.point_names().len()`;
    /// [`Error::Description`] for a linkage without named points.
    pub fn point_motion(&self, k: usize) -> Result<PointMotion> {
        Ok(self.point_motion_at(self.chain.check_point(k)?))
    }

    /// As [`point_motion`](Self::point_motion), for an index known to be a named point's.
    #[inline]
    pub(crate) fn point_motion_at(&self, k: usize) -> PointMotion {
        let p = &self.chain.points[k];
        self.at(p.link, p.local)
    }

    /// The sliding link, the guide's link and the guide's current unit direction of the
    /// prismatic joint `j` (zero direction for a revolute joint).
    pub(crate) fn slide_parts(&self, j: usize) -> (usize, usize, Vector2<f64>) {
        let jp = &self.chain.joints[j];
        let Some((g, offsets)) = jp.prismatic else {
            return (jp.links[0], jp.links[1], Vector2::zeros());
        };
        let guide = jp.links[g];
        (
            jp.links[1 - g],
            guide,
            crate::angle::unit(self.links[guide].angle + offsets[g]),
        )
    }

    /// The current unit direction of the guide of prismatic joint `j` (zero for a revolute
    /// joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn guide_direction(&self, j: usize) -> Result<Vector2<f64>> {
        Ok(self.guide_direction_at(self.chain.check_joint(j)?))
    }

    /// As [`guide_direction`](Self::guide_direction), for an index known to be a joint's.
    #[inline]
    pub(crate) fn guide_direction_at(&self, j: usize) -> Vector2<f64> {
        self.slide_parts(j).2
    }

    /// The slide of prismatic joint `j`: the sliding link's displacement along the guide from
    /// the reference pose, with its velocity and acceleration relative to the guide (zero for
    /// a revolute joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn slide_index(&self, j: usize) -> Result<Motion> {
        Ok(self.slide_at(self.chain.check_joint(j)?))
    }

    /// As [`slide_index`](Self::slide_index), for an index known to be a joint's.
    pub(crate) fn slide_at(&self, j: usize) -> Motion {
        let jp = &self.chain.joints[j];
        let Some((g, _)) = jp.prismatic else {
            return Motion::default();
        };
        let (_, guide, d) = self.slide_parts(j);
        let on_slider = self.joint_on_at(j, 1 - g);
        let on_guide = self.joint_on_at(j, g);
        let w = self.links[guide].omega;
        // r = s·d with d turning at ω: v_r = ṡ·d + s·ω·d⊥, a_r = (s̈ − s·ω²)·d + (…)·d⊥.
        let s = (on_slider.p - on_guide.p).dot(&d);
        let v = (on_slider.v - on_guide.v).dot(&d);
        let a = (on_slider.a - on_guide.a).dot(&d) + s * w * w;
        Motion::new(s, v, a)
    }

    /// The slide of the prismatic joint called `name`.
    ///
    /// # Errors
    /// An unknown name, or a revolute joint.
    pub fn slide(&self, name: &str) -> Result<Motion> {
        let j = self.chain.joint_index(name)?;
        if !self.chain.is_prismatic_at(j) {
            return Err(Error::Description {
                item: format!("joint {name}"),
                problem: "is not prismatic: it has no slide".to_owned(),
            });
        }
        Ok(self.slide_at(j))
    }
}
