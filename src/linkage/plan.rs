#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The solve plan made once from a description: indices instead of names, lengths and local
//! coordinates read off the reference pose, assembly modes, the groups in attachment order and
//! the loads with the links they act on. Everything that can be wrong with a description is
//! found here and named.

use super::analysis::Analysis;
use super::description::{At, Drive, Input, JointKind, Linkage, LoadSpec};
use super::indicator::IndicatorDiagram;
use super::structure::{decompose, Edge, Pair};
use crate::angle::{cross, direction, perp};
use crate::error::{Error, Result};
use crate::kinematics::{Branch, LinkMotion, Motion};
use crate::Load;
use nalgebra::{Point2, Vector2};
use std::collections::HashMap;
use std::fmt;
use std::sync::Arc;

/// A user's load as a function of the kinematic state.
type LoadFnBox = Arc<dyn Fn(&Analysis<'_>) -> Result<Load> + Send + Sync>;

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

/// A linkage checked and planned for solving: made once, used at every position.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub(crate) name: String,
    pub(crate) link_names: Vec<String>,
    pub(crate) joint_names: Vec<String>,
    pub(crate) point_names: Vec<String>,
    pub(crate) links: Vec<LinkPlan>,
    pub(crate) joints: Vec<JointPlan>,
    pub(crate) points: Vec<PointPlan>,
    pub(crate) input: InputPlan,
    /// The second input of a linkage of mobility 2, with its reference coordinate.
    pub(crate) second_input: Option<(InputPlan, f64)>,
    pub(crate) groups: Vec<Group>,
    pub(crate) loads: Vec<LoadPlan>,
    pub(crate) gravity: Vector2<f64>,
    pub(crate) mobility: i64,
    pub(crate) reference_input: f64,
    pub(crate) size: f64,
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

fn bad(item: impl Into<String>, problem: impl Into<String>) -> Error {
    Error::Description {
        item: item.into(),
        problem: problem.into(),
    }
}

fn finite_pair(item: &str, field: &str, v: [f64; 2]) -> Result<Vector2<f64>> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(Vector2::new(v[0], v[1]))
    } else {
        Err(bad(
            item,
            format!("{field} must be finite, got [{}, {}]", v[0], v[1]),
        ))
    }
}

fn finite_num(item: &str, field: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(item, format!("{field} must be finite, got {v}")))
    }
}

fn non_negative(item: &str, field: &str, v: f64) -> Result<f64> {
    if finite_num(item, field, v)? >= 0.0 {
        Ok(v)
    } else {
        Err(bad(item, format!("{field} must be ≥ 0, got {v}")))
    }
}

/// The frame of a link in the reference pose: its origin and direction angle.
#[derive(Debug, Clone, Copy)]
struct Frame {
    origin: Point2<f64>,
    angle: f64,
}

impl Frame {
    fn local(&self, p: Point2<f64>) -> Vector2<f64> {
        let e = crate::angle::unit(self.angle);
        let r = p - self.origin;
        Vector2::new(r.dot(&e), r.dot(&perp(e)))
    }
}

/// Name look-up tables of a description.
struct Names<'a> {
    links: HashMap<&'a str, usize>,
    joints: HashMap<&'a str, usize>,
    points: HashMap<&'a str, (usize, Point2<f64>)>,
    joint_at: Vec<Point2<f64>>,
}

impl<'a> Names<'a> {
    fn link(&self, name: &str, item: &str) -> Result<usize> {
        self.links
            .get(name)
            .copied()
            .ok_or_else(|| bad(item, format!("names the unknown link \"{name}\"")))
    }

    fn joint(&self, name: &str, item: &str) -> Result<usize> {
        self.joints
            .get(name)
            .copied()
            .ok_or_else(|| bad(item, format!("names the unknown joint \"{name}\"")))
    }
}

impl Plan {
    /// Checks a description and plans its solve: the structure (mobility, the dyads in
    /// attachment order), every length and local coordinate from the reference pose, the
    /// assembly mode of every group, and the loads.
    ///
    /// # Errors
    /// [`Error::Description`] naming the joint, link, load or field at fault: unknown or
    /// repeated names, a joint not joining exactly two links, a link with fewer than two
    /// joints, a guide without a direction, non-finite numbers, negative masses, a linkage
    /// outside the 2nd class or of the wrong mobility, a pose that does not close, a group at a
    /// dead point in the reference pose without a given mode.
    pub fn new(linkage: &Linkage) -> Result<Self> {
        let names = index_names(linkage)?;
        let frame = names.link(&linkage.frame, "field frame")?;
        // Link 0 is the frame: reorder so that it comes first.
        let mut order: Vec<usize> = (0..linkage.links.len()).collect();
        order.swap(0, frame);
        let mut link_index = vec![0; order.len()];
        for (new, &old) in order.iter().enumerate() {
            link_index[old] = new;
        }
        let link_names: Vec<String> = order
            .iter()
            .map(|&k| linkage.links[k].name.clone())
            .collect();

        // Joints: each joins exactly two links.
        let mut owners: Vec<Vec<usize>> = vec![Vec::new(); linkage.joints.len()];
        for (k, link) in linkage.links.iter().enumerate() {
            let item = format!("link {}", link.name);
            if link.joints.len() < 2 && k != frame {
                return Err(bad(
                    item,
                    format!(
                        "has {} joint(s); a moving link needs at least two",
                        link.joints.len()
                    ),
                ));
            }
            for j in &link.joints {
                let ji = names.joint(j, &item)?;
                if owners[ji].contains(&link_index[k]) {
                    return Err(bad(item, format!("lists joint {j} twice")));
                }
                owners[ji].push(link_index[k]);
            }
        }
        let mut edges = Vec::with_capacity(linkage.joints.len());
        for (j, joint) in linkage.joints.iter().enumerate() {
            let item = format!("joint {}", joint.name);
            finite_pair(&item, "at", joint.at)?;
            if owners[j].len() != 2 {
                let listed: Vec<&str> = owners[j].iter().map(|&k| link_names[k].as_str()).collect();
                return Err(bad(
                    item,
                    format!(
                        "is listed by {} link(s) [{}]; a joint joins exactly two links (use two \
                         joints at one place for a hinge of three links)",
                        owners[j].len(),
                        listed.join(", ")
                    ),
                ));
            }
            let pair = match &joint.kind {
                JointKind::Revolute => Pair::Revolute,
                JointKind::Prismatic { guide, direction } => {
                    let g = names.link(guide, &item)?;
                    if !owners[j].contains(&link_index[g]) {
                        return Err(bad(
                            item,
                            format!("has its guide on link {guide}, which does not list it"),
                        ));
                    }
                    let d = finite_pair(&item, "direction", *direction)?;
                    if !(d.norm() > 0.0) || !d.norm().is_finite() {
                        return Err(bad(item, "guide direction must be a non-zero vector"));
                    }
                    Pair::Prismatic
                }
            };
            edges.push(Edge {
                pair,
                links: [owners[j][0], owners[j][1]],
            });
        }

        // The input links (one, or two for a linkage of mobility 2) and their joints with the
        // frame.
        let specs: Vec<(&Input, &str)> = std::iter::once((&linkage.input, "field input"))
            .chain(
                linkage
                    .second_input
                    .as_ref()
                    .map(|i| (i, "field second_input")),
            )
            .collect();
        let mut inputs = Vec::with_capacity(specs.len());
        for &(spec, field) in &specs {
            let item = format!("{field}.link");
            let input = link_index[names.link(&spec.link, &item)?];
            if input == 0 {
                return Err(bad(item, "the input cannot be the frame"));
            }
            if inputs.iter().any(|&(l, _)| l == input) {
                return Err(bad(item, "names the same link as the first input"));
            }
            let to_frame: Vec<usize> = (0..edges.len())
                .filter(|&j| edges[j].links.contains(&0) && edges[j].links.contains(&input))
                .collect();
            let [input_joint] = to_frame[..] else {
                return Err(bad(
                    format!("link {}", link_names[input]),
                    format!(
                        "is the input but has {} joints with the frame; it needs exactly one (a \
                         crank's pivot or a slider's guide)",
                        to_frame.len()
                    ),
                ));
            };
            inputs.push((input, input_joint));
        }
        let explicit: Vec<[usize; 2]> = linkage
            .groups
            .iter()
            .map(|[a, b]| {
                Ok([
                    link_index[names.link(a, "field groups")?],
                    link_index[names.link(b, "field groups")?],
                ])
            })
            .collect::<Result<_>>()?;
        let input_links: Vec<usize> = inputs.iter().map(|&(l, _)| l).collect();
        let dyads = decompose(&edges, &link_names, &input_links, &explicit)?;
        let mobility = super::structure::chebyshev(link_names.len() - 1, edges.len());

        let at = |j: usize| {
            let a = linkage.joints[j].at;
            Point2::new(a[0], a[1])
        };
        let dir = |j: usize| match &linkage.joints[j].kind {
            JointKind::Prismatic { direction, .. } => Vector2::new(direction[0], direction[1]),
            JointKind::Revolute => Vector2::zeros(),
        };

        // Frames in the reference pose.
        let mut frames = vec![
            Frame {
                origin: Point2::origin(),
                angle: 0.0
            };
            link_names.len()
        ];
        let mut planned = Vec::with_capacity(inputs.len());
        for (k, (&(input, input_joint), &(spec, _))) in inputs.iter().zip(&specs).enumerate() {
            planned.push(match edges[input_joint].pair {
                Pair::Revolute => {
                    let pivot = at(input_joint);
                    let item = format!("link {}", link_names[input]);
                    let reference = reference_direction(linkage, &order, input, &names, &item)?
                        .ok_or_else(|| {
                            bad(&item, "the crank's joints coincide: it has no direction")
                        })?;
                    frames[input] = Frame {
                        origin: pivot,
                        angle: reference,
                    };
                    check_drive(
                        &spec.drive,
                        ["field input.drive", "field second_input.drive"][k],
                    )?;
                    (
                        InputPlan::Crank {
                            link: input,
                            joint: input_joint,
                            pivot,
                            drive: spec.drive,
                        },
                        crate::angle::normalize(reference),
                    )
                }
                Pair::Prismatic => {
                    let angle = direction(dir(input_joint));
                    frames[input] = Frame {
                        origin: at(input_joint),
                        angle,
                    };
                    (
                        InputPlan::Slider {
                            link: input,
                            joint: input_joint,
                            at: at(input_joint),
                            angle,
                        },
                        0.0,
                    )
                }
            });
        }
        let second_input = planned.get(1).cloned();
        let (input_plan, reference_input) = planned.swap_remove(0);
        // A mode must name some group's inner joint; a mode that matches none is a typo.
        for m in &linkage.modes {
            let inner = |d: &super::structure::Dyad| linkage.joints[d.joints[1]].name == m.joint;
            if !dyads.iter().any(inner) {
                return Err(bad(
                    format!("mode for joint {}", m.joint),
                    "names no group's inner joint (the joint between a group's two links)",
                ));
            }
        }
        let mut groups = Vec::with_capacity(dyads.len());
        for d in &dyads {
            groups.push(plan_group(
                d,
                &edges,
                &link_names,
                linkage,
                &mut frames,
                &at,
                &dir,
            )?);
        }

        // Local coordinates of joints and points.
        let joints: Vec<JointPlan> = edges
            .iter()
            .enumerate()
            .map(|(j, e)| JointPlan {
                links: e.links,
                local: e.links.map(|k| frames[k].local(at(j))),
                prismatic: match &linkage.joints[j].kind {
                    JointKind::Revolute => None,
                    JointKind::Prismatic { guide, .. } => {
                        let g = link_index[names.links[guide.as_str()]];
                        let side = usize::from(e.links[1] == g);
                        let d = direction(dir(j));
                        Some((side, e.links.map(|k| d - frames[k].angle)))
                    }
                },
            })
            .collect();
        let mut point_names = Vec::new();
        let mut points = Vec::new();
        for (k, link) in linkage.links.iter().enumerate() {
            for p in &link.points {
                let item = format!("point {}", p.name);
                let xy = finite_pair(&item, "at", p.at)?;
                let li = link_index[k];
                point_names.push(p.name.clone());
                points.push(PointPlan {
                    link: li,
                    local: frames[li].local(Point2::from(xy)),
                });
            }
        }

        // Links: reference directions, masses, sizes.
        let size = linkage
            .joints
            .iter()
            .flat_map(|j| {
                linkage.joints.iter().map(move |k| {
                    ((j.at[0] - k.at[0]).powi(2) + (j.at[1] - k.at[1]).powi(2)).sqrt()
                })
            })
            .fold(0.0, f64::max);
        if !size.is_finite() {
            return Err(bad("linkage", format!("its size overflows ({size} m)")));
        }
        let mut links = Vec::with_capacity(link_names.len());
        for (li, &k) in order.iter().enumerate() {
            let link = &linkage.links[k];
            let item = format!("link {}", link.name);
            let reference = if li == 0 {
                frames[0].angle
            } else {
                reference_direction(linkage, &order, li, &names, &item)?.unwrap_or(frames[li].angle)
            };
            let (mass, inertia, centre) = match &link.mass {
                None => (0.0, 0.0, Vector2::zeros()),
                Some(m) => {
                    let c = place(&m.centre, &names, li, &link_index, &item, "mass.centre")?;
                    (
                        non_negative(&item, "mass.m", m.m)?,
                        non_negative(&item, "mass.j", m.j)?,
                        frames[li].local(c),
                    )
                }
            };
            links.push(LinkPlan {
                angle_offset: reference - frames[li].angle,
                mass,
                inertia,
                centre,
                size: 0.0,
            });
        }
        for (j, e) in edges.iter().enumerate() {
            for k in e.links {
                links[k].size = links[k].size.max(frames[k].local(at(j)).norm());
            }
        }
        let gravity = finite_pair("field gravity", "gravity", linkage.gravity)?;

        let mut plan = Self {
            name: linkage.name.clone(),
            link_names,
            joint_names: linkage.joints.iter().map(|j| j.name.clone()).collect(),
            point_names,
            links,
            joints,
            points,
            input: input_plan,
            second_input,
            groups,
            loads: Vec::new(),
            gravity,
            mobility,
            reference_input,
            size,
        };
        for (i, spec) in linkage.loads.iter().enumerate() {
            let lp = plan_load(spec, i, &names, &link_index, &frames, &plan)?;
            plan.loads.push(lp);
        }
        plan.check_closure(linkage)?;
        plan.find_dead_centres()?;
        Ok(plan)
    }

    /// Solves the reference pose and compares every joint with its given position.
    fn check_closure(&self, linkage: &Linkage) -> Result<()> {
        let mut a = Analysis::new(self);
        a.solve_kinematics_inputs(&self.reference_motions())
            .map_err(|e| bad("reference pose", format!("does not assemble: {e}")))?;
        let tol = 1e-9 * self.size.max(f64::MIN_POSITIVE);
        for (j, joint) in linkage.joints.iter().enumerate() {
            let given = Point2::new(joint.at[0], joint.at[1]);
            for side in 0..2 {
                let p = a.joint_on_at(j, side).p;
                let gap = (p - given).norm();
                if !(gap <= tol) {
                    return Err(bad(
                        format!("joint {}", joint.name),
                        format!(
                            "the reference pose does not close: the joint as carried by link \
                             {} lies {gap:.3e} m from its given position",
                            self.link_names[self.joints[j].links[side]]
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The dead centres of every piston loaded by an indicator diagram.
    fn find_dead_centres(&mut self) -> Result<()> {
        for k in 0..self.loads.len() {
            let LoadPlan::Indicator { joint, head, .. } = self.loads[k] else {
                continue;
            };
            let name = format!("joint {}", self.joint_names[joint]);
            let mut a = Analysis::new(self);
            let ext = crate::kinematics::extreme_positions(
                |phi| {
                    crate::kinematics::transfer_functions(
                        |m| {
                            a.solve_kinematics(m)?;
                            let s = a.slide_at(joint);
                            Ok(Motion::new(head * s.value, head * s.rate, head * s.accel))
                        },
                        phi,
                    )
                },
                360,
            )
            .map_err(|e| {
                bad(
                    &name,
                    format!("its piston's dead centres cannot be found: {e}"),
                )
            })?;
            let hi = ext
                .iter()
                .map(|e| e.output.value)
                .fold(f64::NEG_INFINITY, f64::max);
            let lo = ext
                .iter()
                .map(|e| e.output.value)
                .fold(f64::INFINITY, f64::min);
            if !(hi > lo) {
                return Err(bad(
                    name,
                    "the piston has no stroke over a turn of the input",
                ));
            }
            if let LoadPlan::Indicator { ends, .. } = &mut self.loads[k] {
                *ends = [hi, lo];
            }
        }
        Ok(())
    }

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
        F: Fn(&Analysis<'_>) -> Result<Load> + Send + Sync + 'static,
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
        self.mobility
    }

    /// The dyads in attachment order.
    #[must_use]
    pub fn groups(&self) -> &[Group] {
        &self.groups
    }

    /// The links' names; index 0 is the frame.
    #[must_use]
    pub fn link_names(&self) -> &[String] {
        &self.link_names
    }

    /// The joints' names, in the description's order.
    #[must_use]
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// The named points' names.
    #[must_use]
    pub fn point_names(&self) -> &[String] {
        &self.point_names
    }

    /// The input coordinate in the reference pose: the crank's angle (rad), or 0 for a
    /// slider (its coordinate is measured from the reference pose).
    #[must_use]
    pub fn reference_input(&self) -> f64 {
        self.reference_input
    }

    /// Whether the input is a crank (an angle) rather than a slider (a length).
    #[must_use]
    pub fn input_is_crank(&self) -> bool {
        matches!(self.input, InputPlan::Crank { .. })
    }

    /// The input link's index.
    #[must_use]
    pub fn input_link(&self) -> usize {
        match self.input {
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
        1 + usize::from(self.second_input.is_some())
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
        self.second_input.as_ref().map(|(ip, _)| ip.link())
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

    /// The largest distance between two joints in the reference pose, m.
    #[must_use]
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The index of the link called `name`.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name.
    pub fn link_index(&self, name: &str) -> Result<usize> {
        self.link_names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| bad(format!("link {name}"), "is not a link of this linkage"))
    }

    /// The index of the joint called `name`.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name.
    pub fn joint_index(&self, name: &str) -> Result<usize> {
        self.joint_names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| bad(format!("joint {name}"), "is not a joint of this linkage"))
    }

    /// The index of the named point called `name`.
    ///
    /// # Errors
    /// [`Error::Description`] for an unknown name.
    pub fn point_index(&self, name: &str) -> Result<usize> {
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

    /// Checks a link's index: `Ok(k)` for an index below `link_names().len()`.
    pub(crate) fn check_link(&self, k: usize) -> Result<usize> {
        index_in("link index", "links", k, self.link_names.len())
    }

    /// Checks a joint's index: `Ok(j)` for an index below `joint_names().len()`.
    pub(crate) fn check_joint(&self, j: usize) -> Result<usize> {
        index_in("joint index", "joints", j, self.joint_names.len())
    }

    /// Checks a named point's index: `Ok(k)` for an index below `point_names().len()`.
    pub(crate) fn check_point(&self, k: usize) -> Result<usize> {
        index_in("point index", "named points", k, self.point_names.len())
    }

    /// Checks a group's index: `Ok(g)` for an index below `groups().len()`.
    pub(crate) fn check_group(&self, g: usize) -> Result<usize> {
        index_in("group index", "groups", g, self.groups.len())
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
        (self.points[point].link, self.points[point].local)
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
        self.joints[joint].prismatic.is_some()
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
        self.joints[joint].links
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
        let j = &self.joints[joint];
        j.prismatic.map(|(side, _)| j.links[side])
    }

    /// The frame's link motion (at rest at the origin).
    pub(crate) fn frame_motion() -> LinkMotion {
        LinkMotion {
            origin: crate::kinematics::PointMotion::fixed(Point2::origin()),
            angle: 0.0,
            omega: 0.0,
            epsilon: 0.0,
        }
    }
}

/// Checks a gear drive's data; `item` names the input's field.
fn check_drive(drive: &Drive, item: &str) -> Result<()> {
    if let Drive::Gear {
        pitch_radius,
        pitch_angle,
        pressure_angle,
    } = *drive
    {
        if !(finite_num(item, "pitch_radius", pitch_radius)? > 0.0) {
            return Err(bad(
                item,
                format!("pitch_radius must be > 0, got {pitch_radius}"),
            ));
        }
        finite_num(item, "pitch_angle", pitch_angle)?;
        let a = finite_num(item, "pressure_angle", pressure_angle)?;
        if !(0.0..std::f64::consts::FRAC_PI_2).contains(&a) {
            return Err(bad(
                item,
                format!("pressure_angle must lie in [0, π/2), got {a} rad"),
            ));
        }
    }
    Ok(())
}

/// Checks names: unique, non-empty; builds the look-up tables.
fn index_names(linkage: &Linkage) -> Result<Names<'_>> {
    let mut links = HashMap::new();
    for (k, l) in linkage.links.iter().enumerate() {
        if l.name.is_empty() || links.insert(l.name.as_str(), k).is_some() {
            return Err(bad(
                format!("link \"{}\"", l.name),
                "link names must be non-empty and unique",
            ));
        }
    }
    let mut joints = HashMap::new();
    for (j, jt) in linkage.joints.iter().enumerate() {
        if jt.name.is_empty() || joints.insert(jt.name.as_str(), j).is_some() {
            return Err(bad(
                format!("joint \"{}\"", jt.name),
                "joint names must be non-empty and unique",
            ));
        }
    }
    let mut points = HashMap::new();
    for (k, l) in linkage.links.iter().enumerate() {
        for p in &l.points {
            if p.name.is_empty()
                || joints.contains_key(p.name.as_str())
                || points
                    .insert(p.name.as_str(), (k, Point2::new(p.at[0], p.at[1])))
                    .is_some()
            {
                return Err(bad(
                    format!("point \"{}\"", p.name),
                    "point names must be non-empty and unique among joints and points",
                ));
            }
        }
    }
    if linkage.links.is_empty() {
        return Err(bad("field links", "a linkage needs links"));
    }
    let joint_at = linkage
        .joints
        .iter()
        .map(|j| Point2::new(j.at[0], j.at[1]))
        .collect();
    Ok(Names {
        links,
        joints,
        points,
        joint_at,
    })
}

/// The position of a named joint or point of the link with the new index `li`, or given
/// coordinates.
fn place(
    at: &At,
    names: &Names<'_>,
    li: usize,
    link_index: &[usize],
    item: &str,
    field: &str,
) -> Result<Point2<f64>> {
    match at {
        At::Coords(c) => Ok(Point2::from(finite_pair(item, field, *c)?)),
        At::Name(n) => {
            if let Some(&(k, p)) = names.points.get(n.as_str()) {
                return if link_index[k] == li {
                    Ok(p)
                } else {
                    Err(bad(
                        item,
                        format!("{field} names point {n}, which is on another link"),
                    ))
                };
            }
            match names.joints.get(n.as_str()) {
                Some(&j) => Ok(names.joint_at[j]),
                None => Err(bad(
                    item,
                    format!("{field} names \"{n}\", which is neither a joint nor a point"),
                )),
            }
        }
    }
}

/// The angle of a link's declared reference direction in the reference pose.
fn reference_direction(
    linkage: &Linkage,
    order: &[usize],
    li: usize,
    names: &Names<'_>,
    item: &str,
) -> Result<Option<f64>> {
    let link = &linkage.links[order[li]];
    let pos = |n: &str| -> Result<Point2<f64>> {
        if let Some(&j) = names.joints.get(n)
            && link.joints.iter().any(|x| x == n)
        {
            let a = linkage.joints[j].at;
            return Ok(Point2::new(a[0], a[1]));
        }
        if let Some(&(k, p)) = names.points.get(n)
            && k == order[li]
        {
            return Ok(p);
        }
        Err(bad(
            item,
            format!("reference names \"{n}\", which is not on this link"),
        ))
    };
    let (a, b) = match &link.reference {
        Some([a, b]) => (pos(a)?, pos(b)?),
        None => {
            // The first two distinct joints; a link whose joints all coincide (a slider
            // block) keeps the engine's frame: `None`.
            let ps: Vec<Point2<f64>> = link.joints.iter().map(|j| pos(j)).collect::<Result<_>>()?;
            match ps.iter().skip(1).find(|p| **p != ps[0]) {
                Some(&b) => (ps[0], b),
                None => return Ok(None),
            }
        }
    };
    let d = b - a;
    if !(d.norm() > 0.0) {
        return Err(bad(
            item,
            "its reference direction joins two coincident points; name two distinct ones in \
             `reference`",
        ));
    }
    Ok(Some(direction(d)))
}

/// Classifies a dyad, orders its links so that an RRP's slider comes second, sets the frames
/// of its links in the reference pose and reads its assembly mode off the pose.
#[allow(clippy::too_many_arguments)]
fn plan_group(
    d: &super::structure::Dyad,
    edges: &[Edge],
    link_names: &[String],
    linkage: &Linkage,
    frames: &mut [Frame],
    at: &dyn Fn(usize) -> Point2<f64>,
    dir: &dyn Fn(usize) -> Vector2<f64>,
) -> Result<Group> {
    let pairs = d.joints.map(|j| edges[j].pair);
    let (links, joints, kind) = match pairs {
        [Pair::Revolute, Pair::Revolute, Pair::Revolute] => (d.links, d.joints, GroupKind::Rrr),
        [Pair::Revolute, Pair::Revolute, Pair::Prismatic] => (d.links, d.joints, GroupKind::Rrp),
        [Pair::Prismatic, Pair::Revolute, Pair::Revolute] => (
            [d.links[1], d.links[0]],
            [d.joints[2], d.joints[1], d.joints[0]],
            GroupKind::Rrp,
        ),
        [Pair::Revolute, Pair::Prismatic, Pair::Revolute] => (d.links, d.joints, GroupKind::Rpr),
        [Pair::Prismatic, Pair::Revolute, Pair::Prismatic] => (d.links, d.joints, GroupKind::Prp),
        [Pair::Revolute, Pair::Prismatic, Pair::Prismatic] => (d.links, d.joints, GroupKind::Rpp),
        [Pair::Prismatic, Pair::Prismatic, Pair::Revolute] => (
            [d.links[1], d.links[0]],
            [d.joints[2], d.joints[1], d.joints[0]],
            GroupKind::Rpp,
        ),
        _ => {
            let label: String = pairs
                .iter()
                .map(|p| if *p == Pair::Revolute { 'R' } else { 'P' })
                .collect();
            return Err(bad(
                format!(
                    "group ({}, {})",
                    link_names[d.links[0]], link_names[d.links[1]]
                ),
                format!(
                    "is a {label} group: three sliding pairs leave its links free to slide \
                     together, so it is not a dyad of the 2nd class"
                ),
            ));
        }
    };
    let other = |j: usize, l: usize| {
        let e = edges[j].links;
        if e[0] == l {
            e[1]
        } else {
            e[0]
        }
    };
    let known = [other(joints[0], links[0]), other(joints[2], links[1])];
    let name = format!(
        "group ({}, {}) {}",
        link_names[links[0]],
        link_names[links[1]],
        kind.label()
    );
    let (a, b, c) = (at(joints[0]), at(joints[1]), at(joints[2]));
    let mode = linkage
        .modes
        .iter()
        .find(|m| m.joint == linkage.joints[joints[1]].name)
        .map(|m| m.branch);
    let need_mode = |what: &str| {
        bad(
            name.clone(),
            format!(
                "{what} in the reference pose; give its assembly mode in `modes` (joint {})",
                linkage.joints[joints[1]].name
            ),
        )
    };
    let mut lengths = [0.0; 2];
    let mut guide_offsets = [0.0; 2];
    let mut slide_angle = 0.0;
    // Where the known links carry the group: A and C (B for an RRP, the guides' points for
    // a PRP and an RPP).
    let mut anchors = [a, c];
    let branch;
    match kind {
        GroupKind::Rrr => {
            lengths = [(b - a).norm(), (b - c).norm()];
            if !(lengths[0] > 0.0 && lengths[1] > 0.0) {
                return Err(bad(name, "has a link of zero length in the reference pose"));
            }
            frames[links[0]] = Frame {
                origin: a,
                angle: direction(b - a),
            };
            frames[links[1]] = Frame {
                origin: c,
                angle: direction(b - c),
            };
            let side = cross(c - a, b - a);
            branch = match mode {
                Some(m) => m,
                None if side > 0.0 => Branch::Plus,
                None if side < 0.0 => Branch::Minus,
                None => return Err(need_mode("is at a dead point (its three hinges collinear)")),
            };
        }
        GroupKind::Rrp => {
            lengths[0] = (b - a).norm();
            if !(lengths[0] > 0.0) {
                return Err(bad(name, "has a link of zero length in the reference pose"));
            }
            let g = dir(joints[2]);
            let ga = direction(g);
            frames[links[0]] = Frame {
                origin: a,
                angle: direction(b - a),
            };
            frames[links[1]] = Frame {
                origin: b,
                angle: ga,
            };
            guide_offsets[1] = ga - frames[known[1]].angle;
            anchors[1] = b;
            let ahead = (b - a).dot(&g);
            branch = match mode {
                Some(m) => m,
                None if ahead > 0.0 => Branch::Plus,
                None if ahead < 0.0 => Branch::Minus,
                None => return Err(need_mode("has its rod perpendicular to the guide")),
            };
        }
        GroupKind::Rpr => {
            let ac = c - a;
            if !(ac.norm() > 0.0) {
                return Err(bad(
                    name,
                    "has its two hinges at one place in the reference pose",
                ));
            }
            let u = dir(joints[1]);
            if cross(u / u.norm(), ac).abs() > 1e-9 * ac.norm() {
                return Err(bad(
                    format!("joint {}", linkage.joints[joints[1]].name),
                    "the sliding axis of an RPR group must pass through both of its hinges \
                     (an offset axis is not supported)",
                ));
            }
            frames[links[0]] = Frame {
                origin: a,
                angle: direction(ac),
            };
            frames[links[1]] = Frame {
                origin: c,
                angle: direction(-ac),
            };
            branch = Branch::Plus;
        }
        GroupKind::Prp => {
            // Each slider's hinge B traces, on the known link carrying its guide, the line
            // through B along the pair's direction (a sliding pair only translates, so which
            // of its links carries the guide does not matter).
            let (u2, u3) = (dir(joints[0]), dir(joints[2]));
            let (u2, u3) = (u2 / u2.norm(), u3 / u3.norm());
            if !(cross(u2, u3).abs() > crate::kinematics::SINGULAR_DETERMINANT) {
                return Err(bad(
                    name,
                    format!(
                        "has parallel guides (joints {} and {}): sin(phi_g3 - phi_g2) = {:.4e}, \
                         its sliders could slide together along them",
                        linkage.joints[joints[0]].name,
                        linkage.joints[joints[2]].name,
                        cross(u2, u3)
                    ),
                ));
            }
            for (side, u) in [(0, u2), (1, u3)] {
                frames[links[side]] = Frame {
                    origin: b,
                    angle: direction(u),
                };
                guide_offsets[side] = direction(u) - frames[known[side]].angle;
            }
            anchors = [b, b];
            branch = Branch::Plus;
        }
        GroupKind::Rpp => {
            // Link 2 is hinged at A and slides in link 3 along v; link 3 slides along u on
            // the known link. B, where the slide's line through A crosses the guide's line,
            // is the point of link 3 that runs along the guide.
            let (v, u) = (dir(joints[1]), dir(joints[2]));
            let (v, u) = (v / v.norm(), u / u.norm());
            let sin_alpha = cross(u, v);
            if !(sin_alpha.abs() > crate::kinematics::SINGULAR_DETERMINANT) {
                return Err(bad(
                    name,
                    format!(
                        "has its slide (joint {}) parallel to its guide (joint {}): sin(alpha) = \
                         {sin_alpha:.4e}, its two links could slide together along the guide",
                        linkage.joints[joints[1]].name, linkage.joints[joints[2]].name,
                    ),
                ));
            }
            let bb = a + v * (cross(u, c - a) / sin_alpha);
            frames[links[0]] = Frame {
                origin: a,
                angle: direction(v),
            };
            frames[links[1]] = Frame {
                origin: bb,
                angle: direction(u),
            };
            guide_offsets[1] = direction(u) - frames[known[1]].angle;
            slide_angle = direction(v) - direction(u);
            anchors[1] = bb;
            branch = Branch::Plus;
        }
    }
    Ok(Group {
        kind,
        name,
        links,
        joints,
        known,
        branch,
        a_local: frames[known[0]].local(anchors[0]),
        c_local: frames[known[1]].local(anchors[1]),
        lengths,
        guide_offsets,
        slide_angle,
    })
}

fn plan_load(
    spec: &LoadSpec,
    i: usize,
    names: &Names<'_>,
    link_index: &[usize],
    frames: &[Frame],
    plan: &Plan,
) -> Result<LoadPlan> {
    let item = format!("load {}", i + 1);
    let link_of = |n: &str| names.link(n, &item).map(|k| link_index[k]);
    let at_on = |a: &At, li: usize, field: &str| -> Result<Vector2<f64>> {
        Ok(frames[li].local(place(a, names, li, link_index, &item, field)?))
    };
    Ok(match spec {
        LoadSpec::Force { link, at, force } => {
            let link = link_of(link)?;
            LoadPlan::Force {
                link,
                local: at_on(at, link, "at")?,
                force: finite_pair(&item, "force", *force)?,
            }
        }
        LoadSpec::Moment { link, moment } => LoadPlan::Moment {
            link: link_of(link)?,
            moment: finite_num(&item, "moment", *moment)?,
        },
        LoadSpec::Resistance {
            on,
            forward,
            backward,
            at,
        } => {
            let forward = non_negative(&item, "forward", *forward)?;
            let backward = non_negative(&item, "backward", *backward)?;
            if let Some(&j) = names.joints.get(on.as_str()) {
                let Some((side, _)) = plan.joints[j].prismatic else {
                    return Err(bad(
                        &item,
                        format!("resists joint {on}, which is not prismatic"),
                    ));
                };
                let slider = plan.joints[j].links[1 - side];
                let local = match at {
                    None => plan.joints[j].local[1 - side],
                    Some(a) => at_on(a, slider, "at")?,
                };
                LoadPlan::Sliding {
                    joint: j,
                    local,
                    forward,
                    backward,
                }
            } else {
                LoadPlan::Turning {
                    link: link_of(on)?,
                    forward,
                    backward,
                }
            }
        }
        LoadSpec::Indicator {
            joint,
            diagram,
            head,
        } => {
            let j = names.joint(joint, &item)?;
            match plan.joints[j].prismatic {
                Some((side, _)) if plan.joints[j].links[side] == 0 => {}
                _ => {
                    return Err(bad(
                        &item,
                        format!("joint {joint} must be prismatic with its guide on the frame"),
                    ))
                }
            }
            if !(*head == 1.0 || *head == -1.0) {
                return Err(bad(&item, format!("head must be +1 or −1, got {head}")));
            }
            if !(diagram.area.is_finite() && diagram.area > 0.0) {
                return Err(bad(
                    &item,
                    format!("diagram.area must be > 0, got {}", diagram.area),
                ));
            }
            LoadPlan::Indicator {
                joint: j,
                head: *head,
                diagram: diagram.clone(),
                ends: [0.0, 0.0],
            }
        }
    })
}
