#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The groups of a plan: each Assur dyad classified by its pairs, its links ordered, their
//! frames set in the reference pose, and its assembly mode read off the pose (or taken from
//! the description's `modes`).

use super::reference::Frame;
use crate::angle::{cross, direction};
use crate::error::{Error, Result};
use crate::kinematics::{Branch, SINGULAR_DETERMINANT};
use crate::linkage::description::{JointKind, Linkage};
use crate::linkage::plan::{bad, Group, GroupKind};
use crate::linkage::structure::{Dyad, Edge, Pair};
use nalgebra::{Point2, Vector2};
use std::collections::HashMap;

/// A dyad's kind, its links (an RRP's slider second, an RPP's hinged link first) and its
/// joints in the order outer, inner, outer.
fn classify(
    d: &Dyad,
    edges: &[Edge],
    link_names: &[String],
) -> Result<(GroupKind, [usize; 2], [usize; 3])> {
    let pairs = d.joints.map(|j| edges[j].pair);
    let flipped = (
        [d.links[1], d.links[0]],
        [d.joints[2], d.joints[1], d.joints[0]],
    );
    let (kind, (links, joints)) = match pairs {
        [Pair::Revolute, Pair::Revolute, Pair::Revolute] => (GroupKind::Rrr, (d.links, d.joints)),
        [Pair::Revolute, Pair::Revolute, Pair::Prismatic] => (GroupKind::Rrp, (d.links, d.joints)),
        [Pair::Prismatic, Pair::Revolute, Pair::Revolute] => (GroupKind::Rrp, flipped),
        [Pair::Revolute, Pair::Prismatic, Pair::Revolute] => (GroupKind::Rpr, (d.links, d.joints)),
        [Pair::Prismatic, Pair::Revolute, Pair::Prismatic] => (GroupKind::Prp, (d.links, d.joints)),
        [Pair::Revolute, Pair::Prismatic, Pair::Prismatic] => (GroupKind::Rpp, (d.links, d.joints)),
        [Pair::Prismatic, Pair::Prismatic, Pair::Revolute] => (GroupKind::Rpp, flipped),
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
    Ok((kind, links, joints))
}

/// A group in the reference pose, as its kind's placement reads it.
struct Site<'a> {
    name: &'a str,
    /// The reference positions of its joints (outer, inner, outer).
    a: Point2<f64>,
    b: Point2<f64>,
    c: Point2<f64>,
    /// The guide directions of its joints (zero for a hinge).
    dirs: [Vector2<f64>; 3],
    /// The frame angles of the known links its outer joints attach to.
    known_angles: [f64; 2],
    /// The names of its joints.
    joint_names: [&'a str; 3],
    /// The assembly mode the description gives, if any.
    mode: Option<Branch>,
}

/// What a kind's placement reads off the reference pose.
struct Placement {
    /// The frames of the group's two links.
    frames: [Frame; 2],
    lengths: [f64; 2],
    guide_offsets: [f64; 2],
    slide_angle: f64,
    /// Where the known links carry the group: A and C (B for an RRP, the guides' points for
    /// a PRP and an RPP).
    anchors: [Point2<f64>; 2],
    branch: Branch,
}

impl Site<'_> {
    fn frame(origin: Point2<f64>, angle: f64) -> Frame {
        Frame { origin, angle }
    }

    /// The error of a group whose mode the pose cannot tell.
    fn need_mode(&self, what: &str) -> Error {
        bad(
            self.name,
            format!(
                "{what} in the reference pose; give its assembly mode in `modes` (joint {})",
                self.joint_names[1]
            ),
        )
    }

    /// The given mode, or the one the sign of `side` tells (`what` when it is zero).
    fn mode_by(&self, side: f64, what: &str) -> Result<Branch> {
        match self.mode {
            Some(m) => Ok(m),
            None if side > 0.0 => Ok(Branch::Plus),
            None if side < 0.0 => Ok(Branch::Minus),
            None => Err(self.need_mode(what)),
        }
    }

    fn rrr(&self) -> Result<Placement> {
        let (a, b, c) = (self.a, self.b, self.c);
        let lengths = [(b - a).norm(), (b - c).norm()];
        if !(lengths[0] > 0.0 && lengths[1] > 0.0) {
            return Err(bad(
                self.name,
                "has a link of zero length in the reference pose",
            ));
        }
        Ok(Placement {
            frames: [
                Self::frame(a, direction(b - a)),
                Self::frame(c, direction(b - c)),
            ],
            lengths,
            guide_offsets: [0.0; 2],
            slide_angle: 0.0,
            anchors: [a, c],
            branch: self.mode_by(
                cross(c - a, b - a),
                "is at a dead point (its three hinges collinear)",
            )?,
        })
    }

    fn rrp(&self) -> Result<Placement> {
        let (a, b) = (self.a, self.b);
        let length = (b - a).norm();
        if !(length > 0.0) {
            return Err(bad(
                self.name,
                "has a link of zero length in the reference pose",
            ));
        }
        let g = self.dirs[2];
        let ga = direction(g);
        Ok(Placement {
            frames: [Self::frame(a, direction(b - a)), Self::frame(b, ga)],
            lengths: [length, 0.0],
            guide_offsets: [0.0, ga - self.known_angles[1]],
            slide_angle: 0.0,
            anchors: [a, b],
            branch: self.mode_by((b - a).dot(&g), "has its rod perpendicular to the guide")?,
        })
    }

    fn rpr(&self) -> Result<Placement> {
        let (a, c) = (self.a, self.c);
        let ac = c - a;
        if !(ac.norm() > 0.0) {
            return Err(bad(
                self.name,
                "has its two hinges at one place in the reference pose",
            ));
        }
        let u = self.dirs[1];
        if cross(u / u.norm(), ac).abs() > 1e-9 * ac.norm() {
            return Err(bad(
                format!("joint {}", self.joint_names[1]),
                "the sliding axis of an RPR group must pass through both of its hinges \
                 (an offset axis is not supported)",
            ));
        }
        Ok(Placement {
            frames: [
                Self::frame(a, direction(ac)),
                Self::frame(c, direction(-ac)),
            ],
            lengths: [0.0; 2],
            guide_offsets: [0.0; 2],
            slide_angle: 0.0,
            anchors: [a, c],
            branch: Branch::Plus,
        })
    }

    fn prp(&self) -> Result<Placement> {
        // Each slider's hinge B traces, on the known link carrying its guide, the line
        // through B along the pair's direction (a sliding pair only translates, so which
        // of its links carries the guide does not matter).
        let b = self.b;
        let (u2, u3) = (self.dirs[0], self.dirs[2]);
        let (u2, u3) = (u2 / u2.norm(), u3 / u3.norm());
        if !(cross(u2, u3).abs() > SINGULAR_DETERMINANT) {
            return Err(bad(
                self.name,
                format!(
                    "has parallel guides (joints {} and {}): sin(phi_g3 - phi_g2) = {:.4e}, \
                     its sliders could slide together along them",
                    self.joint_names[0],
                    self.joint_names[2],
                    cross(u2, u3)
                ),
            ));
        }
        Ok(Placement {
            frames: [Self::frame(b, direction(u2)), Self::frame(b, direction(u3))],
            lengths: [0.0; 2],
            guide_offsets: [
                direction(u2) - self.known_angles[0],
                direction(u3) - self.known_angles[1],
            ],
            slide_angle: 0.0,
            anchors: [b, b],
            branch: Branch::Plus,
        })
    }

    fn rpp(&self) -> Result<Placement> {
        // Link 2 is hinged at A and slides in link 3 along v; link 3 slides along u on
        // the known link. B, where the slide's line through A crosses the guide's line,
        // is the point of link 3 that runs along the guide.
        let (a, c) = (self.a, self.c);
        let (v, u) = (self.dirs[1], self.dirs[2]);
        let (v, u) = (v / v.norm(), u / u.norm());
        let sin_alpha = cross(u, v);
        if !(sin_alpha.abs() > SINGULAR_DETERMINANT) {
            return Err(bad(
                self.name,
                format!(
                    "has its slide (joint {}) parallel to its guide (joint {}): sin(alpha) = \
                     {sin_alpha:.4e}, its two links could slide together along the guide",
                    self.joint_names[1], self.joint_names[2],
                ),
            ));
        }
        let bb = a + v * (cross(u, c - a) / sin_alpha);
        Ok(Placement {
            frames: [Self::frame(a, direction(v)), Self::frame(bb, direction(u))],
            lengths: [0.0; 2],
            guide_offsets: [0.0, direction(u) - self.known_angles[1]],
            slide_angle: direction(v) - direction(u),
            anchors: [a, bb],
            branch: Branch::Plus,
        })
    }
}

/// Classifies a dyad, orders its links so that an RRP's slider comes second, sets the frames
/// of its links in the reference pose and reads its assembly mode off the pose (or `modes`,
/// the description's modes by joint name, looked up once per group).
pub(super) fn plan_group(
    d: &Dyad,
    edges: &[Edge],
    link_names: &[String],
    (linkage, modes): (&Linkage, &HashMap<&str, Branch>),
    frames: &mut [Frame],
) -> Result<Group> {
    let (kind, links, joints) = classify(d, edges, link_names)?;
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
    let joint = |j: usize| &linkage.joints[j];
    let at = |j: usize| Point2::new(joint(j).at[0], joint(j).at[1]);
    let dir = |j: usize| match &joint(j).kind {
        JointKind::Prismatic { direction, .. } => Vector2::new(direction[0], direction[1]),
        JointKind::Revolute => Vector2::zeros(),
    };
    let site = Site {
        name: &name,
        a: at(joints[0]),
        b: at(joints[1]),
        c: at(joints[2]),
        dirs: joints.map(dir),
        known_angles: known.map(|k| frames[k].angle),
        joint_names: joints.map(|j| joint(j).name.as_str()),
        mode: modes.get(joint(joints[1]).name.as_str()).copied(),
    };
    let p = match kind {
        GroupKind::Rrr => site.rrr(),
        GroupKind::Rrp => site.rrp(),
        GroupKind::Rpr => site.rpr(),
        GroupKind::Prp => site.prp(),
        GroupKind::Rpp => site.rpp(),
        GroupKind::Triad | GroupKind::General => Err(bad(
            &name,
            "is not a dyad (planned by build/triad.rs or general.rs)",
        )),
    }?;
    frames[links[0]] = p.frames[0];
    frames[links[1]] = p.frames[1];
    Ok(Group {
        kind,
        links,
        joints,
        known,
        branch: p.branch,
        a_local: frames[known[0]].local(p.anchors[0]),
        c_local: frames[known[1]].local(p.anchors[1]),
        lengths: p.lengths,
        guide_offsets: p.guide_offsets,
        slide_angle: p.slide_angle,
        name,
        triad: None,
        general: None,
        twin: None,
    })
}
