//! Twin dyads, found once at plan time: two RRR dyads on the same two known joints with the
//! same lengths in opposite modes (a rhombus's or a kite's two sides: the Peaucellier cell's
//! C and D about the line O A), and the RRR dyads hung on their two inner joints, which are
//! then solved in the twins' frame (see [`TwinPlan`] and `solve/twin.rs`).
//!
//! Two lengths read off a description's coordinates are equal only to their rounding (the
//! bundled Peaucellier's |AC| and |AD| differ by 7e-18 m), so lengths and places are compared
//! to [`TWIN_TOLERANCE`] of the linkage's size, and a pair found so is made exact: each pair
//! of lengths is replaced by its mean, so that the plan describes the mirror-symmetric
//! linkage its file draws to within that tolerance (and which the closure check still
//! accepts, to 10⁻⁹ of the size). A linkage without twins is planned exactly as before.

use crate::linkage::description::Linkage;
use crate::linkage::plan::{Group, GroupKind, TwinPlan};
use nalgebra::Point2;

/// Two lengths or two places of a linkage closer than this fraction of its size are taken
/// as equal when twins are sought: far above the rounding of coordinates (10⁻¹⁶ of their
/// magnitude, so a copy moved 10³ sizes away still qualifies), far below what a drawing
/// means (the reference pose is checked to 10⁻⁹ of the size).
pub(crate) const TWIN_TOLERANCE: f64 = 1e-12;

/// Marks every RRR dyad of `groups` hung on the inner joints of a pair of twins (with the
/// twins' and its own lengths made exactly equal where they agree to the tolerance).
/// `linkage` is the description with binary joints whose joints the groups index; `size`
/// the linkage's size.
pub(super) fn mark(groups: &mut [Group], linkage: &Linkage, size: f64) {
    let tol = TWIN_TOLERANCE * size;
    let at = |j: usize| Point2::new(linkage.joints[j].at[0], linkage.joints[j].at[1]);
    let close = |p: Point2<f64>, q: Point2<f64>| (p - q).norm() <= tol;
    let same = |a: f64, b: f64| (a - b).abs() <= tol;
    for g in 0..groups.len() {
        if !plain_rrr(&groups[g]) {
            continue;
        }
        let known = groups[g].known;
        // The dyad, before `g`, that holds each known link (a link is in one group only).
        let holder =
            |k: usize| (0..g).find(|&i| plain_rrr(&groups[i]) && groups[i].links.contains(&k));
        let (Some(f), Some(s)) = (holder(known[0]), holder(known[1])) else {
            continue;
        };
        let joints = groups[g].joints;
        if f == s
            || !close(at(joints[0]), at(groups[f].joints[1]))
            || !close(at(joints[2]), at(groups[s].joints[1]))
        {
            continue;
        }
        let (first, second) = (&groups[f], &groups[s]);
        // The known points as (link, reference place), in each twin's order.
        let ends = |t: &Group| [(t.known[0], at(t.joints[0])), (t.known[1], at(t.joints[2]))];
        let (p, q) = (ends(first), ends(second));
        let meet = |x: (usize, Point2<f64>), y: (usize, Point2<f64>)| x.0 == y.0 && close(x.1, y.1);
        let [la, lb] = first.lengths;
        let [ma, mb] = second.lengths;
        let swapped = if meet(p[0], q[0])
            && meet(p[1], q[1])
            && same(la, ma)
            && same(lb, mb)
            && first.branch != second.branch
        {
            false
        } else if meet(p[0], q[1])
            && meet(p[1], q[0])
            && same(la, mb)
            && same(lb, ma)
            && first.branch == second.branch
        {
            true
        } else {
            continue;
        };
        // Two known points at one place leave the twins no axis.
        if close(p[0].1, p[1].1) {
            continue;
        }
        let axis = [
            (first.known[0], first.a_local),
            (first.known[1], first.c_local),
        ];
        // The twins' lengths made equal pairwise (each pair's mean, the same bits in both).
        let (a, b) = (
            0.5 * (la + if swapped { mb } else { ma }),
            0.5 * (lb + if swapped { ma } else { mb }),
        );
        groups[f].lengths = [a, b];
        groups[s].lengths = if swapped { [b, a] } else { [a, b] };
        let [l2, l3] = groups[g].lengths;
        let equal = same(l2, l3);
        if equal {
            let l = 0.5 * (l2 + l3);
            groups[g].lengths = [l, l];
        }
        groups[g].twin = Some(Box::new(TwinPlan {
            twins: [f, s],
            axis,
            swapped,
            equal,
        }));
    }
}

/// An RRR dyad (not a triad's or a general group's stand-in).
fn plain_rrr(g: &Group) -> bool {
    g.kind == GroupKind::Rrr && g.triad.is_none() && g.general.is_none()
}
