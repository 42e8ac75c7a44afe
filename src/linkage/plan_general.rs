//! The plan of a general group (a rigid group of hinges with no closed form): which links and
//! joints it holds, where the known links carry its outer hinges, the group as the
//! [`HingedGroup`] block reads it, and the reference pose every solve continues from.

use super::plan::Group;
use crate::kinematics::{GroupPose, HingedGroup};
use nalgebra::{Point2, Vector2};

/// The plan of a general group.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct GeneralPlan {
    /// Its links (indices into the plan's links), in the block's order.
    pub links: Vec<usize>,
    /// The hinges between two of its links, in the block's order.
    pub inner: Vec<usize>,
    /// The hinges to known links, in the block's order.
    pub outer: Vec<usize>,
    /// Per outer hinge, the known link that carries it and the hinge in that link's frame.
    pub known: Vec<(usize, Vector2<f64>)>,
    /// Per outer hinge, the known link's frame (origin, angle) in the reference pose: the
    /// start of the continuation.
    pub known_reference: Vec<(Point2<f64>, f64)>,
    /// The group, its links' points in their frames.
    pub block: HingedGroup,
    /// The links' frames in the reference pose.
    pub reference: GroupPose,
    /// The size of the linkage (the scale of the closure tolerances).
    pub size: f64,
}

impl Group {
    /// A general group as the [`HingedGroup`] block reads it, with its known points in the
    /// reference pose (the points its [`modes`](HingedGroup::modes) are searched on) and its
    /// links' frames there (the reference mode); `None` for a dyad or a triad.
    #[must_use]
    pub fn general_block(&self) -> Option<(&HingedGroup, Vec<Point2<f64>>, &GroupPose)> {
        self.general.as_ref().map(|g| {
            let outer = g
                .known
                .iter()
                .zip(&g.known_reference)
                .map(|(&(_, l), &(o, a))| {
                    let e = crate::angle::unit(a);
                    o + Vector2::new(e.x * l.x - e.y * l.y, e.y * l.x + e.x * l.y)
                })
                .collect();
            (&g.block, outer, &g.reference)
        })
    }
}
