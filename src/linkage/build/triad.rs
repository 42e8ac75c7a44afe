#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! A triad of the plan: the frames of its four links in the reference pose, its dimensions
//! read off the pose, and its reference mode (the assembly mode nearest the drawn pose).

use super::reference::Frame;
use crate::angle::{cross, direction};
use crate::error::Result;
use crate::kinematics::{Branch, Guide, SliderTriadDims, SlidingPair};
use crate::kinematics::{TriadDims, TriadPose};
use crate::linkage::description::{JointKind, Linkage};
use crate::linkage::plan::{bad, Group, GroupKind, TriadPlan};
use crate::linkage::plan_triad::SliderLeg;
use crate::linkage::solve::unit_frame::{slider_triad_mode_nearest, triad_mode_nearest};
use crate::linkage::structure::{Edge, Pair};
use crate::linkage::structure_triad::TriadFound;
use nalgebra::{Point2, Vector2};

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
    let slides = |i: usize| {
        edges[t.outer[i]].pair == Pair::Prismatic || edges[t.inner[i]].pair == Pair::Prismatic
    };
    if let Some(i) = (0..3).find(|&i| slides(i)) {
        // The sliding leg first, the others in their order.
        let order = [i, (i + 1) % 3, (i + 2) % 3];
        let legs = TriadFound {
            ternary: t.ternary,
            binary: order.map(|k| t.binary[k]),
            outer: order.map(|k| t.outer[k]),
            inner: order.map(|k| t.inner[k]),
        };
        return plan_slider_triad(&legs, edges, link_names, linkage, frames);
    }
    let known = known_links(t, edges);
    let name = triad_name(t, link_names, "triad");
    let Drawn {
        a,
        b,
        l,
        side,
        ternary,
        b3,
    } = drawn(t, linkage, &name, 0)?;
    let theta = ternary.angle;
    let dims = TriadDims::new(l, side, b3.x, b3.y);
    let phi = [0, 1, 2].map(|i| direction(b[i] - a[i]));
    let drawn = TriadPose {
        b,
        theta,
        phi,
        det: 0.0,
    };
    let reference = triad_mode_nearest(a, &dims, &drawn).map_err(|e| {
        bad(
            name.clone(),
            format!("does not assemble in the reference pose: {e}"),
        )
    })?;
    frames[t.ternary] = ternary;
    for i in 0..3 {
        frames[t.binary[i]] = Frame {
            origin: a[i],
            angle: phi[i],
        };
    }
    let a_local = [0, 1, 2].map(|i| frames[known[i]].local(a[i]));
    let plan = TriadPlan {
        links: [t.ternary, t.binary[0], t.binary[1], t.binary[2]],
        outer: t.outer,
        inner: t.inner,
        known,
        a_local,
        dims,
        reference,
        slider: None,
    };
    Ok(triad_group(name, t, plan, [l[0], l[2]], 0.0))
}

/// Plans a triad whose first leg `t` slides (at its outer joint or at its inner one): the
/// frames as for the triad (the sliding link's at B1, outer, or at A1, inner, along the
/// guide), the guide read off the description, and the mode of [`slider_triad_modes`]
/// nearest the drawn pose.
fn plan_slider_triad(
    t: &TriadFound,
    edges: &[Edge],
    link_names: &[String],
    linkage: &Linkage,
    frames: &mut [Frame],
) -> Result<Group> {
    let known = known_links(t, edges);
    let name = triad_name(t, link_names, "triad with a sliding pair");
    let Drawn {
        a,
        b,
        l: [_, l1, l2],
        side,
        ternary,
        b3,
    } = drawn(t, linkage, &name, 1)?;
    let l = [l1, l2];
    let theta = ternary.angle;
    let outer_slides = edges[t.outer[0]].pair == Pair::Prismatic;
    let slide = if outer_slides { t.outer[0] } else { t.inner[0] };
    let d = match &linkage.joints[slide].kind {
        JointKind::Prismatic { direction, .. } => Vector2::new(direction[0], direction[1]),
        JointKind::Revolute => Vector2::zeros(),
    };
    let dn = d.norm();
    if !(dn > 0.0 && dn.is_finite()) {
        return Err(bad(
            linkage.joints[slide].name.clone(),
            "needs a finite, non-zero guide direction",
        ));
    }
    let d = d / dn;
    let slide_angle = direction(d);
    let pair = if outer_slides {
        SlidingPair::Outer {
            offset: cross(d, b[0] - a[0]),
        }
    } else {
        SlidingPair::Inner {
            angle: slide_angle - theta,
            offset: cross(d, a[0] - b[0]),
        }
    };
    let dims = SliderTriadDims {
        pair,
        l,
        l_b1b2: side,
        b3_along: b3.x,
        b3_across: b3.y,
    };
    let phi = [slide_angle, direction(b[1] - a[1]), direction(b[2] - a[2])];
    let drawn = TriadPose {
        b,
        theta,
        phi,
        det: 0.0,
    };
    let reference = slider_triad_mode_nearest(
        &Guide::fixed(a[0], slide_angle),
        [a[1], a[2]],
        &dims,
        &drawn,
    )
    .map_err(|e| {
        bad(
            name.clone(),
            format!("does not assemble in the reference pose: {e}"),
        )
    })?;
    frames[t.ternary] = ternary;
    frames[t.binary[0]] = Frame {
        origin: if outer_slides { b[0] } else { a[0] },
        angle: slide_angle,
    };
    for i in 1..3 {
        frames[t.binary[i]] = Frame {
            origin: a[i],
            angle: phi[i],
        };
    }
    let a_local = [0, 1, 2].map(|i| frames[known[i]].local(a[i]));
    let guide_offset = if outer_slides {
        slide_angle - frames[known[0]].angle
    } else {
        0.0
    };
    let plan = TriadPlan {
        links: [t.ternary, t.binary[0], t.binary[1], t.binary[2]],
        outer: t.outer,
        inner: t.inner,
        known,
        a_local,
        dims: TriadDims::new([1.0, l[0], l[1]], side, b3.x, b3.y),
        reference,
        slider: Some(SliderLeg { dims, guide_offset }),
    };
    Ok(triad_group(name, t, plan, l, guide_offset))
}

/// The plan's group of triad `t` with its triad `plan`: the fields every group carries
/// filled from the first and last legs (known links, outer joints' local points), the legs'
/// `lengths` and the first leg's guide offset.
fn triad_group(
    name: String,
    t: &TriadFound,
    plan: TriadPlan,
    lengths: [f64; 2],
    guide_offset: f64,
) -> Group {
    Group {
        kind: GroupKind::Triad,
        name,
        links: [t.ternary, t.ternary],
        joints: t.inner,
        known: [plan.known[0], plan.known[2]],
        branch: Branch::Plus,
        a_local: plan.a_local[0],
        c_local: plan.a_local[2],
        lengths,
        guide_offsets: [guide_offset, 0.0],
        slide_angle: 0.0,
        triad: Some(Box::new(plan)),
        general: None,
        twin: None,
    }
}

/// A triad as drawn: the outer joints A_i, the ternary link's joints B_i, the legs'
/// lengths |B_i − A_i|, l_B1B2, and the ternary link's frame (at B1, along B1 → B2) with B3
/// in it.
struct Drawn {
    a: [Point2<f64>; 3],
    b: [Point2<f64>; 3],
    l: [f64; 3],
    side: f64,
    ternary: Frame,
    b3: Vector2<f64>,
}

/// Reads triad `t` off the description; the legs from `first_hinged` on are hinged at both
/// ends, and neither they nor B1 B2 may have zero length (a sliding leg's A1 may lie on
/// its guide through B1, or be B1 itself: its offset is then 0, not a length).
fn drawn(t: &TriadFound, linkage: &Linkage, name: &str, first_hinged: usize) -> Result<Drawn> {
    let at = |j: usize| Point2::new(linkage.joints[j].at[0], linkage.joints[j].at[1]);
    let a = t.outer.map(at);
    let b = t.inner.map(at);
    let l = [0, 1, 2].map(|i| (b[i] - a[i]).norm());
    let side = (b[1] - b[0]).norm();
    if !(l[first_hinged..].iter().all(|&x| x > 0.0) && side > 0.0) {
        return Err(bad(
            name,
            "has a link of zero length in the reference pose (A_i = B_i, or B1 = B2)",
        ));
    }
    let ternary = Frame {
        origin: b[0],
        angle: direction(b[1] - b[0]),
    };
    let b3 = ternary.local(b[2]);
    Ok(Drawn {
        a,
        b,
        l,
        side,
        ternary,
        b3,
    })
}

/// The known link of each leg: the one its outer joint joins, other than the leg itself.
fn known_links(t: &TriadFound, edges: &[Edge]) -> [usize; 3] {
    [0, 1, 2].map(|i| {
        let e = edges[t.outer[i]].links;
        if e[0] == t.binary[i] {
            e[1]
        } else {
            e[0]
        }
    })
}

/// The group's name in errors and reports: its ternary link, then its legs.
fn triad_name(t: &TriadFound, link_names: &[String], kind: &str) -> String {
    format!(
        "group ({}; {}, {}, {}) {kind}",
        link_names[t.ternary],
        link_names[t.binary[0]],
        link_names[t.binary[1]],
        link_names[t.binary[2]]
    )
}
