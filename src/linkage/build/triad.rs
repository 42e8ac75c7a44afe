#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! A triad of the plan: the frames of its four links in the reference pose, its dimensions
//! read off the pose, and its reference mode (the assembly mode nearest the drawn pose).

use super::reference::Frame;
use crate::angle::direction;
use crate::error::Result;
use crate::kinematics::Branch;
use crate::kinematics::{triad_modes, TriadDims, TriadPose};
use crate::linkage::description::Linkage;
use crate::linkage::plan::{bad, Group, GroupKind, TriadPlan};
use crate::linkage::structure::Edge;
use crate::linkage::structure_triad::TriadFound;
use nalgebra::Point2;

/// Plans the triad `t`: sets the frames of its links (the ternary link's at B1 along
/// B1 → B2, each binary link's at A_i along A_i → B_i), reads its dimensions and picks the
/// mode of [`triad_modes`] nearest the drawn pose.
pub(super) fn plan_triad(
    t: &TriadFound,
    edges: &[Edge],
    link_names: &[String],
    linkage: &Linkage,
    frames: &mut [Frame],
) -> Result<Group> {
    let other = |j: usize, l: usize| {
        let e = edges[j].links;
        if e[0] == l {
            e[1]
        } else {
            e[0]
        }
    };
    let known = [0, 1, 2].map(|i| other(t.outer[i], t.binary[i]));
    let name = format!(
        "group ({}; {}, {}, {}) triad",
        link_names[t.ternary],
        link_names[t.binary[0]],
        link_names[t.binary[1]],
        link_names[t.binary[2]]
    );
    let at = |j: usize| Point2::new(linkage.joints[j].at[0], linkage.joints[j].at[1]);
    let a = t.outer.map(at);
    let b = t.inner.map(at);
    let l = [0, 1, 2].map(|i| (b[i] - a[i]).norm());
    let side = (b[1] - b[0]).norm();
    if !(l.iter().all(|&x| x > 0.0) && side > 0.0) {
        return Err(bad(
            name,
            "has a link of zero length in the reference pose (A_i = B_i, or B1 = B2)",
        ));
    }
    let theta = direction(b[1] - b[0]);
    let ternary = Frame {
        origin: b[0],
        angle: theta,
    };
    let b3 = ternary.local(b[2]);
    let dims = TriadDims::new(l, side, b3.x, b3.y);
    let phi = [0, 1, 2].map(|i| direction(b[i] - a[i]));
    let drawn = TriadPose {
        b,
        theta,
        phi,
        det: 0.0,
    };
    let reference = *triad_modes(a, &dims)
        .map_err(|e| {
            bad(
                name.clone(),
                format!("does not assemble in the reference pose: {e}"),
            )
        })?
        .nearest(&drawn);
    frames[t.ternary] = ternary;
    for i in 0..3 {
        frames[t.binary[i]] = Frame {
            origin: a[i],
            angle: phi[i],
        };
    }
    let a_local = [0, 1, 2].map(|i| frames[known[i]].local(a[i]));
    Ok(Group {
        kind: GroupKind::Triad,
        name,
        links: [t.ternary, t.ternary],
        joints: t.inner,
        known: [known[0], known[2]],
        branch: Branch::Plus,
        a_local: a_local[0],
        c_local: a_local[2],
        lengths: [l[0], l[2]],
        guide_offsets: [0.0; 2],
        slide_angle: 0.0,
        triad: Some(Box::new(TriadPlan {
            links: [t.ternary, t.binary[0], t.binary[1], t.binary[2]],
            outer: t.outer,
            inner: t.inner,
            known,
            a_local,
            dims,
            reference,
        })),
        general: None,
    })
}
