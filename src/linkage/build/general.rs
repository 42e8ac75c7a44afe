#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! A general group of the plan (a rigid group of hinges with no closed form): its links'
//! frames in the reference pose, its hinges in those frames, and the reference pose, which
//! fixes its assembly mode (every solve continues from it).

use super::chain::{joint_at, reference_size};
use super::reference::Frame;
use crate::angle::direction;
use crate::error::Result;
use crate::kinematics::{Branch, GroupPose, HingedGroup};
use crate::linkage::description::Linkage;
use crate::linkage::plan::{bad, Group, GroupKind};
use crate::linkage::plan_general::GeneralPlan;
use crate::linkage::structure::Edge;
use crate::linkage::structure_triad::GeneralFound;

/// Plans the general group `g`: each link's frame at its first hinge in joint order, along
/// the first hinge at another place; the hinges in those frames; the conditioning of the
/// reference pose checked (a group at a dead or branch point there has no mode to follow).
pub(super) fn plan_general(
    g: &GeneralFound,
    edges: &[Edge],
    link_names: &[String],
    linkage: &Linkage,
    frames: &mut [Frame],
) -> Result<Group> {
    let names: Vec<&str> = g.links.iter().map(|&k| link_names[k].as_str()).collect();
    let name = format!("group ({}) general", names.join(", "));
    let mut slot = std::collections::HashMap::with_capacity(g.links.len());
    for (i, &k) in g.links.iter().enumerate() {
        slot.insert(k, i);
    }
    for &k in &g.links {
        let mut at = g
            .inner
            .iter()
            .chain(&g.outer)
            .filter(|&&j| edges[j].links.contains(&k))
            .map(|&j| joint_at(linkage, j));
        let origin = at
            .next()
            .ok_or_else(|| bad(&name, "has a link without hinges"))?;
        let far = at.find(|p| *p != origin).ok_or_else(|| {
            bad(
                &name,
                format!("link {} has all its hinges at one place", link_names[k]),
            )
        })?;
        frames[k] = Frame {
            origin,
            angle: direction(far - origin),
        };
    }
    let end = |j: usize, k: usize| (slot[&k], frames[k].local(joint_at(linkage, j)));
    let inner = g
        .inner
        .iter()
        .map(|&j| edges[j].links.map(|k| end(j, k)))
        .collect();
    let (mut outer, mut known, mut known_reference) = (Vec::new(), Vec::new(), Vec::new());
    for &j in &g.outer {
        let [a, b] = edges[j].links;
        let (mine, theirs) = if slot.contains_key(&a) {
            (a, b)
        } else {
            (b, a)
        };
        outer.push(end(j, mine));
        known.push((theirs, frames[theirs].local(joint_at(linkage, j))));
        known_reference.push((frames[theirs].origin, frames[theirs].angle));
    }
    let block = HingedGroup {
        links: g.links.len(),
        inner,
        outer,
    };
    block.check().map_err(|e| bad(&name, e.to_string()))?;
    let reference = GroupPose {
        origins: g.links.iter().map(|&k| frames[k].origin).collect(),
        angles: g.links.iter().map(|&k| frames[k].angle).collect(),
    };
    let size = reference_size(linkage)?;
    let conditioning = block.conditioning(&reference, size);
    if !(conditioning > 1e-12) {
        return Err(bad(
            &name,
            format!(
                "is at a dead point or a branch point in the reference pose (sigma_min/sigma_max \
                 of its closure Jacobian = {conditioning:.3e}): its assembly mode cannot be \
                 followed from there; draw it in a regular pose"
            ),
        ));
    }
    let all: Vec<usize> = g.inner.iter().chain(&g.outer).copied().collect();
    let (Some(&first), Some(&last)) = (known.first(), known.last()) else {
        return Err(bad(&name, "is joined to no known link"));
    };
    let (first_known, last_known) = (first.0, last.0);
    Ok(Group {
        kind: GroupKind::General,
        name,
        links: [g.links[0], g.links[0]],
        joints: [all[0], all[1], all[2]],
        known: [first_known, last_known],
        branch: Branch::Plus,
        a_local: first.1,
        c_local: last.1,
        lengths: [0.0; 2],
        guide_offsets: [0.0; 2],
        slide_angle: 0.0,
        twin: None,
        triad: None,
        general: Some(Box::new(GeneralPlan {
            links: g.links.clone(),
            inner: g.inner.clone(),
            outer: g.outer.clone(),
            known,
            known_reference,
            block,
            reference,
            size,
        })),
    })
}
