//! The buffers of one position's kinematics, allocated once per plan and refilled at every
//! position: each link's motion with its unit vector, the groups' constant turns and their
//! kinematic determinants.

use crate::error::Error;
use crate::kinematics::{Guide, LinkMotion, Motion, PointMotion};
use crate::linkage::inputs::Inputs;
use crate::linkage::plan::{Chain, Pose};
use nalgebra::{Point2, Vector2};

/// The kinematic state of one position of a [`Chain`].
#[derive(Debug, Clone, Default)]
pub(crate) struct KinState {
    pub input: Motion,
    pub second_input: Option<Motion>,
    pub links: Vec<LinkMotion>,
    /// Each link's unit vector e(φ), computed once per position: every point of a link is
    /// placed with it, so no trigonometry is repeated.
    pub units: Vec<Vector2<f64>>,
    /// Per group, the constant rotations (cos, sin) of its guides' offsets (first and second
    /// outer joint) and of an RPP's slide angle: a guide's unit vector is its link's rotated.
    pub turns: Vec<[Vector2<f64>; 3]>,
    pub dets: Vec<f64>,
    /// Per group, a triad's pose at the last solve (`None` for a dyad, or before the first
    /// solve): the rates-only pass works at it. No solve of positions reads it.
    pub triads: Vec<Option<crate::kinematics::TriadPose>>,
    /// Per group, a general group's Newton buffers (empty for the other kinds).
    pub general_work: Vec<crate::kinematics::GroupWork>,
    /// Per group, for an RRR dyad hung on twins ([`TwinPlan`](crate::linkage::plan::TwinPlan)),
    /// ±1: its base direction (from its first known joint to its second) is this times the
    /// axis's left normal; 0 where the twins' modes (as the plan now has them: a mode may be
    /// flipped after planning) are no mirror pair. Empty when no group has twins.
    pub twin_sides: Vec<f64>,
}

/// The frame's link motion (at rest at the origin).
pub(crate) fn frame_motion() -> LinkMotion {
    LinkMotion {
        origin: PointMotion::fixed(Point2::origin()),
        angle: 0.0,
        omega: 0.0,
        epsilon: 0.0,
    }
}

/// Wraps an error of one part so that it names the part.
pub(crate) fn within(part: &str) -> impl Fn(Error) -> Error + '_ {
    move |e| Error::In {
        part: part.to_owned(),
        source: Box::new(e),
    }
}

/// Each group's twin side (see [`KinState::twin_sides`]): the first twin's inner joint is
/// M + σ·h·n (σ its mode's sign, n the left normal of the axis from its first known point to
/// its second), its mirror image M − σ·h·n, so the direction from the first to the second is
/// −σ·n.
fn twin_sides(chain: &Chain) -> Vec<f64> {
    if chain.groups.iter().all(|g| g.twin.is_none()) {
        return Vec::new();
    }
    chain
        .groups
        .iter()
        .map(|g| match &g.twin {
            Some(t) => {
                let [f, s] = t.twins.map(|i| chain.groups[i].branch);
                // Mirror images: opposite modes on the same order of the known points, the
                // same mode on the other order.
                if (f == s) == t.swapped {
                    -f.sign()
                } else {
                    0.0
                }
            }
            None => 0.0,
        })
        .collect()
}

impl KinState {
    /// Buffers for the positions of `chain` (allocated once).
    pub fn new(chain: &Chain) -> Self {
        let n = chain.link_names.len();
        Self {
            input: Motion::default(),
            second_input: None,
            links: vec![frame_motion(); n],
            units: vec![Vector2::x(); n],
            turns: chain
                .groups
                .iter()
                .map(|g| {
                    let r = |angle: f64| Vector2::new(angle.cos(), angle.sin());
                    [
                        r(g.guide_offsets[0]),
                        r(g.guide_offsets[1]),
                        r(g.slide_angle),
                    ]
                })
                .collect(),
            dets: vec![0.0; chain.groups.len()],
            triads: vec![None; chain.groups.len()],
            general_work: vec![Default::default(); chain.groups.len()],
            twin_sides: twin_sides(chain),
        }
    }

    /// The read-only view of this position.
    #[inline]
    pub fn pose<'a>(&'a self, chain: &'a Chain) -> Pose<'a> {
        Pose {
            chain,
            links: &self.links,
            units: &self.units,
            inputs: self.inputs(),
        }
    }

    /// The inputs of the last solve.
    #[inline]
    pub fn inputs(&self) -> Inputs {
        match self.second_input {
            Some(m) => Inputs::two(self.input, m),
            None => Inputs::one(self.input),
        }
    }

    /// The motion of the point at `local` in link `k`'s frame.
    #[inline]
    pub fn at(&self, k: usize, local: Vector2<f64>) -> PointMotion {
        self.links[k].point_in_frame(self.units[k], local)
    }

    /// Stores link `k`'s motion with its unit vector.
    #[inline]
    pub fn set_link(&mut self, k: usize, m: LinkMotion) {
        self.put_link(k, m, m.unit());
    }

    /// Stores link `k`'s motion with its unit vector `u` = e(φ), already known.
    #[inline]
    pub fn put_link(&mut self, k: usize, m: LinkMotion, u: Vector2<f64>) {
        self.units[k] = u;
        self.links[k] = m;
    }

    /// The guide through the point at `local` of link `k`, at `offset` to the link's frame
    /// angle, moving with the link.
    pub fn guide_on(&self, k: usize, local: Vector2<f64>, offset: f64) -> Guide {
        let link = &self.links[k];
        Guide {
            point: self.at(k, local),
            angle: Motion::new(link.angle + offset, link.omega, link.epsilon),
        }
    }
}
