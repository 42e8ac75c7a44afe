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
use super::handle::{index_in, JointId, JointRef, LinkId, LinkRef, PointId, PointRef};
use super::indicator::IndicatorDiagram;
use super::inputs::Inputs;
use super::springs::{DamperPlan, SpringPlan, TorsionPlan};
use crate::error::{Error, Result};
use crate::kinematics::frame_offset;
use crate::kinematics::{Branch, LinkMotion, Motion, PointMotion, TriadDims, TriadPose};
use crate::kinetostatics::friction::{Hinge, Slide};
use crate::Load;
use nalgebra::{Point2, Vector2};
use std::fmt;
use std::sync::Arc;

/// A user's load as a function of the kinematic state.
type LoadFnBox = Arc<dyn Fn(&Pose<'_>) -> Result<Load> + Send + Sync>;

/// The kind of an Assur group: a dyad of the 2nd class, by its joints from one outer joint
/// through the inner joint to the other (R revolute, P prismatic), or the triad of the 3rd
/// class.
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
    /// The triad, the Assur group of the 3rd class with revolute joints: a ternary link held
    /// by three binary links on three known joints (see [`Group::triad_links`]).
    Triad,
    /// A larger rigid group of hinges with no closed form (the double butterfly's six-link
    /// group, a group of the 4th class), solved by its closure equations (see
    /// [`Group::general_links`]).
    General,
}

impl GroupKind {
    /// "RRR", "RRP", "RPR", "PRP", "RPP", "triad" or "general".
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Rrr => "RRR",
            Self::Rrp => "RRP",
            Self::Rpr => "RPR",
            Self::Prp => "PRP",
            Self::Rpp => "RPP",
            Self::Triad => "triad",
            Self::General => "general",
        }
    }
}

/// A group of the plan (a dyad, or a triad), in attachment order.
///
/// The fields `links`, `joints` and `known` describe a dyad; a triad's four links and six
/// joints are read by [`triad_links`](Self::triad_links) and
/// [`triad_joints`](Self::triad_joints) (its `links` hold the ternary link twice, `joints`
/// the ternary link's three joints, `known` the known links of its first and third binary
/// links).
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
    /// A triad's plan (`None` for a dyad).
    pub(crate) triad: Option<Box<TriadPlan>>,
    /// A general group's plan (`None` for a dyad or a triad).
    pub(crate) general: Option<Box<super::plan_general::GeneralPlan>>,
    /// An RRR dyad hung on the inner joints of two twin dyads (a rhombus's or a kite's two
    /// sides, mirror images of each other): solved in the twins' own frame (`None` for every
    /// other group; see [`TwinPlan`]).
    pub(crate) twin: Option<Box<TwinPlan>>,
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

/// The plan of a triad: its links and joints, where the known links carry its outer joints,
/// its dimensions and its reference mode.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TriadPlan {
    /// The ternary link, then the binary links 1, 2, 3.
    pub links: [usize; 4],
    /// The outer joints A_i (binary link i with its known link).
    pub outer: [usize; 3],
    /// The joints B_i (binary link i with the ternary link).
    pub inner: [usize; 3],
    /// The known links that carry A_i.
    pub known: [usize; 3],
    /// A_i in the frames of the known links.
    pub a_local: [Vector2<f64>; 3],
    /// The lengths A_i B_i and the ternary link's triangle, from the reference pose.
    pub dims: TriadDims,
    /// The reference mode: the mode of [`triad_modes`](crate::kinematics::triad_modes) in the
    /// reference pose nearest the drawn one. Every solver starts from it.
    pub reference: TriadPose,
    /// The sliding leg (the first) of a triad with a sliding pair; `None` for revolute joints.
    pub slider: Option<super::plan_triad::SliderLeg>,
}

/// An RRR dyad whose two known joints are the inner joints of two *twin* RRR dyads: the
/// twins hang on the same two known joints K1, K2 with the same lengths in opposite modes, so
/// their inner joints are mirror images about the line K1K2 (the axis), M ± h·n with n the
/// axis's unit normal. Near the twins' fold (h → 0: a Peaucellier cell at its lock) the
/// difference of their absolute coordinates no longer gives this dyad's base direction, which
/// is ±n exactly; the solve (`solve/twin.rs`) takes it from the axis. Found by
/// `build/twins.rs`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TwinPlan {
    /// The twin groups (indices in attachment order) whose inner joints are this dyad's
    /// first and second known joints.
    pub twins: [usize; 2],
    /// The axis: the first twin's known points (known link, point in its frame), in that
    /// twin's order.
    pub axis: [(usize, Vector2<f64>); 2],
    /// Whether the second twin lists the two known points in the other order (then the
    /// twins are mirror images in the same mode, otherwise in opposite modes).
    pub swapped: bool,
    /// Whether this dyad's two lengths are equal (then its inner joint lies on the axis).
    pub equal: bool,
}

impl Group {
    /// A general group's links and its joints (the hinges between two of its links, then
    /// the hinges to known links), indices into [`Plan::link_names`] and
    /// [`Plan::joint_names`]; `None` for a dyad or a triad.
    #[must_use]
    pub fn general_links(&self) -> Option<(&[usize], &[usize], &[usize])> {
        self.general
            .as_ref()
            .map(|g| (g.links.as_slice(), g.inner.as_slice(), g.outer.as_slice()))
    }

    /// A triad's links: the ternary link, then the binary links 1, 2, 3 (indices into
    /// [`Plan::link_names`]); `None` for a dyad.
    #[must_use]
    pub fn triad_links(&self) -> Option<[usize; 4]> {
        self.triad.as_ref().map(|t| t.links)
    }

    /// A triad's joints: the outer joints A_1, A_2, A_3 (each binary link with its known
    /// link) and the joints B_1, B_2, B_3 (each binary link with the ternary link); `None`
    /// for a dyad.
    #[must_use]
    pub fn triad_joints(&self) -> Option<[[usize; 3]; 2]> {
        self.triad.as_ref().map(|t| [t.outer, t.inner])
    }
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
    Spring(SpringPlan),
    Damper(DamperPlan),
    Torsion(TorsionPlan),
}

/// The kinematic chain of a plan: the names, the links' and joints' local geometry, the
/// inputs and the groups in attachment order. It is all one position's kinematics needs, so
/// [`build`](super::build) makes it (and solves its reference pose) before the loads, and
/// the position pass works on it alone.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chain {
    pub link_names: Vec<String>,
    /// The description's index of each planned link (the file's order; the frame is 0 here).
    pub link_order: Vec<usize>,
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
    /// Each joint's friction (by joint index), or `None` for a frictionless linkage (every
    /// coefficient zero): then the solve takes the frictionless path.
    pub(crate) friction: Option<Vec<FrictionPlan>>,
    /// The buffers of finished one-shot solves, for the next (not part of what the plan is).
    pub(crate) spare: super::solve::spare::Spares,
}

/// One joint's friction: the hinge's for a revolute joint, the slide's for a prismatic one
/// (the other frictionless).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct FrictionPlan {
    pub hinge: Hinge,
    pub slide: Slide,
}

/// A description error: `item` names the joint, link, load or field, `problem` what is wrong.
pub(crate) fn bad(item: impl Into<String>, problem: impl Into<String>) -> Error {
    Error::Description {
        item: item.into(),
        problem: problem.into(),
    }
}

impl Chain {
    /// The index of the link `r` names.
    #[inline]
    pub(crate) fn link(&self, r: impl LinkRef) -> Result<usize> {
        Ok(r.link_in(&self.link_names)?.0)
    }

    /// The index of the joint `r` names.
    #[inline]
    pub(crate) fn joint(&self, r: impl JointRef) -> Result<usize> {
        Ok(r.joint_in(&self.joint_names)?.0)
    }

    /// The index of the named point `r` names.
    #[inline]
    pub(crate) fn point(&self, r: impl PointRef) -> Result<usize> {
        Ok(r.point_in(&self.point_names)?.0)
    }

    /// The index of the prismatic joint `r` names.
    ///
    /// # Errors
    /// As [`joint`](Self::joint); [`Error::Description`] for a revolute joint.
    pub(crate) fn prismatic(&self, r: impl JointRef) -> Result<usize> {
        let j = self.joint(r)?;
        if self.is_prismatic_at(j) {
            Ok(j)
        } else {
            Err(bad(
                format!("joint {}", self.joint_names[j]),
                "is not prismatic: it has no slide",
            ))
        }
    }

    /// Checks a group's index: `Ok(g)` for an index below `groups.len()`.
    pub(crate) fn check_group(&self, g: usize) -> Result<usize> {
        index_in("group index", "groups", g, self.groups.len())
    }

    /// The number of inputs: 1, or 2.
    pub(crate) fn input_count(&self) -> usize {
        1 + usize::from(self.second_input.is_some())
    }

    /// The input plans, one or two.
    pub(crate) fn inputs(&self) -> impl Iterator<Item = &InputPlan> {
        std::iter::once(&self.input).chain(self.second_input.as_ref().map(|(ip, _)| ip))
    }

    /// The input coordinates in the reference pose, one per input.
    pub(crate) fn reference_inputs(&self) -> Vec<f64> {
        std::iter::once(self.reference_input)
            .chain(self.second_input.as_ref().map(|(_, r)| *r))
            .collect()
    }

    /// The reference pose at rest.
    pub(crate) fn reference_motions(&self) -> Inputs {
        let r = self.reference_inputs();
        match r[..] {
            [q1, q2] => Inputs::two(Motion::fixed(q1), Motion::fixed(q2)),
            _ => Inputs::one(Motion::fixed(r[0])),
        }
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
    /// use tmm::kinematics::Motion;
    /// use tmm::Load;
    /// let mut plan = Plan::new(&bundled::four_bar())?;
    /// plan.add_load_fn("coupler", |pose| {
    ///     let b = pose.joint("B")?.p;
    ///     let stretch = b - nalgebra::Point2::new(0.5, 0.5);
    ///     Ok(Load::force_at(b, -2000.0 * stretch))
    /// })?;
    /// let r = plan.analyse(Motion::turning(1.0, 10.0))?;
    /// assert!(r.power_check()?.relative_error() < 1e-9);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn add_load_fn<F>(&mut self, link: impl LinkRef, f: F) -> Result<()>
    where
        F: Fn(&Pose<'_>) -> Result<Load> + Send + Sync + 'static,
    {
        let link = self.chain.link(link)?;
        self.loads.push(LoadPlan::Custom {
            link,
            f: LoadFn(Arc::new(f)),
        });
        Ok(())
    }

    /// Whether any joint has friction (a coefficient above zero): then every solve takes the
    /// friction statics ([`Analysis::friction`](super::Analysis::friction)).
    #[must_use]
    pub fn has_friction(&self) -> bool {
        self.friction.is_some()
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

    /// The groups (dyads, and triads) in attachment order.
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

    /// The handle of the link `link` names (a name, or a handle checked against this plan):
    /// resolve a name once, then read by handle.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name; [`Error::OutOfRange`] for a handle of
    /// another, larger plan.
    pub fn link_id(&self, link: impl LinkRef) -> Result<LinkId> {
        link.link_in(&self.chain.link_names)
    }

    /// The handle of the joint `joint` names.
    ///
    /// # Errors
    /// As [`link_id`](Self::link_id).
    ///
    /// # Examples
    /// Resolve once, read by handle at every position:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let b = plan.joint_id("B")?;
    /// let mut solver = plan.solver();
    /// for k in 0..12 {
    ///     let a = solver.analyse(Motion::turning(0.5 * f64::from(k), 10.0))?;
    ///     assert!(a.reaction(b)?.force.norm() > 0.0);
    /// }
    /// assert!(plan.joint_id("Z").is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn joint_id(&self, joint: impl JointRef) -> Result<JointId> {
        joint.joint_in(&self.chain.joint_names)
    }

    /// The handle of the named point `point` names.
    ///
    /// # Errors
    /// As [`link_id`](Self::link_id).
    pub fn point_id(&self, point: impl PointRef) -> Result<PointId> {
        point.point_in(&self.chain.point_names)
    }

    /// Every link's handle, the frame first.
    pub fn link_ids(&self) -> impl ExactSizeIterator<Item = LinkId> + use<> {
        (0..self.chain.link_names.len()).map(LinkId)
    }

    /// Every joint's handle, in the description's order.
    pub fn joint_ids(&self) -> impl ExactSizeIterator<Item = JointId> + use<> {
        (0..self.chain.joint_names.len()).map(JointId)
    }

    /// Every named point's handle.
    pub fn point_ids(&self) -> impl ExactSizeIterator<Item = PointId> + use<> {
        (0..self.chain.point_names.len()).map(PointId)
    }

    /// The input coordinate in the reference pose: the crank's angle (rad), or 0 for a
    /// slider (its coordinate is measured from the reference pose).
    #[must_use]
    pub fn reference_input(&self) -> f64 {
        self.chain.reference_input
    }

    /// Whether the (first) input is a crank (an angle) rather than a slider (a length).
    #[must_use]
    pub fn input_is_crank(&self) -> bool {
        matches!(self.chain.input, InputPlan::Crank { .. })
    }

    /// The input links, one per input.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// assert_eq!(plan.input_links(), [plan.link_id("crank 1")?, plan.link_id("crank 4")?]);
    /// assert_eq!(Plan::new(&bundled::four_bar())?.input_links().len(), 1);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn input_links(&self) -> Vec<LinkId> {
        self.chain.inputs().map(|ip| LinkId(ip.link())).collect()
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

    /// Checks a group's index: `Ok(g)` for an index below `groups().len()`.
    pub(crate) fn check_group(&self, g: usize) -> Result<usize> {
        self.chain.check_group(g)
    }

    /// The link a named point belongs to and its local coordinates (along, across the link's
    /// frame), for [`LinkMotion::point_in_frame`].
    ///
    /// # Errors
    /// As [`point_id`](Self::point_id).
    pub fn point_local(&self, point: impl PointRef) -> Result<(LinkId, Vector2<f64>)> {
        let p = &self.chain.points[self.chain.point(point)?];
        Ok((LinkId(p.link), p.local))
    }

    /// Whether a joint is prismatic.
    ///
    /// # Errors
    /// As [`joint_id`](Self::joint_id).
    pub fn is_prismatic(&self, joint: impl JointRef) -> Result<bool> {
        Ok(self.chain.is_prismatic_at(self.chain.joint(joint)?))
    }

    /// Whether joint `joint` (a valid index) is prismatic.
    #[inline]
    pub(crate) fn is_prismatic_at(&self, joint: usize) -> bool {
        self.chain.is_prismatic_at(joint)
    }

    /// The two links a joint joins.
    ///
    /// # Errors
    /// As [`joint_id`](Self::joint_id).
    pub fn joint_links(&self, joint: impl JointRef) -> Result<[LinkId; 2]> {
        Ok(self.joint_links_at(self.chain.joint(joint)?).map(LinkId))
    }

    /// The two links joint `joint` (a valid index) joins.
    #[inline]
    pub(crate) fn joint_links_at(&self, joint: usize) -> [usize; 2] {
        self.chain.joints[joint].links
    }

    /// For a prismatic joint, the link that carries its guide (one of
    /// [`joint_links`](Self::joint_links)); `None` for a revolute joint.
    ///
    /// # Errors
    /// As [`joint_id`](Self::joint_id).
    ///
    /// # Examples
    /// The shaper's ram slides on a guide of the frame:
    /// ```
    /// use tmm::linkage::{bundled, LinkId, Plan};
    /// let plan = Plan::new(&bundled::shaper())?;
    /// assert_eq!(plan.guide_link("Q")?, Some(LinkId::FRAME));
    /// assert_eq!(plan.guide_link("O1")?, None);
    /// assert!(plan.guide_link("no such joint").is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn guide_link(&self, joint: impl JointRef) -> Result<Option<LinkId>> {
        Ok(self
            .chain
            .guide_link_at(self.chain.joint(joint)?)
            .map(LinkId))
    }
}

/// One solved position, read-only: the motions of the links, joints, named points and
/// slides. It is what a load added by [`Plan::add_load_fn`] sees, and what every result of a
/// solve reads its kinematics from.
///
/// Every reading takes a name or a handle ([`JointRef`], [`LinkRef`], [`PointRef`]); a
/// handle is read without a string look-up.
#[derive(Debug, Clone, Copy)]
pub struct Pose<'a> {
    pub(crate) chain: &'a Chain,
    pub(crate) links: &'a [LinkMotion],
    /// Each link's unit vector e(φ), kept with its motion.
    pub(crate) units: &'a [Vector2<f64>],
    pub(crate) inputs: Inputs,
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

    /// The inputs' motions (φ, ω, ε of a crank; s, ṡ, s̈ of a slider), one per input.
    #[must_use]
    pub fn inputs(&self) -> Inputs {
        self.inputs
    }

    /// A link's motion in the frame the engine uses for it (its origin a joint, its angle
    /// that of the engine's frame).
    ///
    /// # Errors
    /// As [`Plan::link_id`].
    pub fn link_motion(&self, link: impl LinkRef) -> Result<LinkMotion> {
        Ok(self.links[self.chain.link(link)?])
    }

    /// A link's angle along its declared reference direction (rad, in [0, 2π)), with ω and ε.
    ///
    /// # Errors
    /// As [`Plan::link_id`].
    pub fn link(&self, link: impl LinkRef) -> Result<Motion> {
        Ok(self.link_angle_at(self.chain.link(link)?))
    }

    /// As [`link`](Self::link), for an index known to be a link's.
    #[inline]
    pub(crate) fn link_angle_at(&self, k: usize) -> Motion {
        let l = &self.links[k];
        Motion::new(
            crate::angle::normalize(l.angle + self.chain.links[k].angle_offset),
            l.omega,
            l.epsilon,
        )
    }

    /// The motion of a joint (for a prismatic joint, its point on the sliding link).
    ///
    /// # Errors
    /// As [`Plan::joint_id`].
    pub fn joint(&self, joint: impl JointRef) -> Result<PointMotion> {
        Ok(self.joint_motion_at(self.chain.joint(joint)?))
    }

    /// As [`joint`](Self::joint), for an index known to be a joint's.
    #[inline]
    pub(crate) fn joint_motion_at(&self, j: usize) -> PointMotion {
        let side = match self.chain.joints[j].prismatic {
            Some((guide, _)) => 1 - guide,
            None => 0,
        };
        self.joint_on_at(j, side)
    }

    /// The motion of a joint as a point of `link`, one of the two links it joins (at a
    /// prismatic joint the two differ).
    ///
    /// # Errors
    /// As [`Plan::joint_id`] and [`Plan::link_id`]; [`Error::Description`] naming both when
    /// the joint does not join the link.
    pub fn joint_on(&self, joint: impl JointRef, link: impl LinkRef) -> Result<PointMotion> {
        let c = self.chain;
        let j = c.joint(joint)?;
        let link = c.link(link)?;
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

    /// Joint `j` as a point of the `side`-th of its two links (valid indices).
    #[inline]
    pub(crate) fn joint_on_at(&self, j: usize, side: usize) -> PointMotion {
        let jp = &self.chain.joints[j];
        self.at(jp.links[side], jp.local[side])
    }

    /// Joint `j` as a point of `link`, one of its links (valid indices).
    #[inline]
    pub(crate) fn joint_on_link(&self, j: usize, link: usize) -> PointMotion {
        let side = usize::from(self.chain.joints[j].links[1] == link);
        self.joint_on_at(j, side)
    }

    /// The motion of a named point.
    ///
    /// # Errors
    /// As [`Plan::point_id`].
    pub fn point(&self, point: impl PointRef) -> Result<PointMotion> {
        Ok(self.point_motion_at(self.chain.point(point)?))
    }

    /// As [`point`](Self::point), for an index known to be a named point's.
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

    /// The current unit direction of a joint's guide (zero for a revolute joint).
    ///
    /// # Errors
    /// As [`Plan::joint_id`].
    pub fn guide_direction(&self, joint: impl JointRef) -> Result<Vector2<f64>> {
        Ok(self.guide_direction_at(self.chain.joint(joint)?))
    }

    /// As [`guide_direction`](Self::guide_direction), for an index known to be a joint's.
    #[inline]
    pub(crate) fn guide_direction_at(&self, j: usize) -> Vector2<f64> {
        self.slide_parts(j).2
    }

    /// The slide of a prismatic joint: the sliding link's displacement along the guide from
    /// the reference pose, with its velocity and acceleration relative to the guide.
    ///
    /// # Errors
    /// As [`Plan::joint_id`]; [`Error::Description`] naming a revolute joint (it has no
    /// slide).
    pub fn slide(&self, joint: impl JointRef) -> Result<Motion> {
        Ok(self.slide_at(self.chain.prismatic(joint)?))
    }

    /// As [`slide`](Self::slide), for an index known to be a joint's (zero for a revolute
    /// joint).
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
}
