//! A triad with a sliding pair placed where its rates fail: at a branch point, by
//! [`slider_triad_position`], at rest.

use super::{triad_links, within, KinState};
use crate::error::{Error, Result};
use crate::kinematics::{slider_triad_position, Guide, LinkMotion, PointMotion, SlidingPair};
use crate::kinematics::{TriadPose, TriadState};
use crate::linkage::plan::{Group, TriadPlan};
use crate::linkage::plan_triad::SliderLeg;
use nalgebra::Point2;

impl KinState {
    /// Triad `g`, with its sliding pair `leg`, placed where its rates fail (a branch point:
    /// two modes merge, and the three legs' lines of action meet at one point), at rest: in
    /// the mode nearest the reference mode (the rule of every solve), refined to the branch
    /// pose itself ([`slider_triad_position`]); `Ok` with the error its rates have there.
    /// `Err` when the rates do not fail there (the failure was another).
    pub(in crate::linkage::solve) fn slider_triad_position_only(
        &mut self,
        g: usize,
        group: &Group,
        t: &TriadPlan,
        leg: &SliderLeg,
    ) -> Result<Error> {
        let first = self.first_leg(t, leg);
        let first = Guide::fixed(first.point.p, first.angle.value);
        let hinged = [1, 2].map(|i| self.at(t.known[i], t.a_local[i]).p);
        let (pose, rates) = slider_triad_position(&first, hinged, &leg.dims, &t.reference)
            .map_err(within(&group.name))?;
        let Some(singular) = rates else {
            return Err(Error::Description {
                item: group.name.clone(),
                problem: "its rates do not vanish here".to_owned(),
            });
        };
        let s = at_rest(&pose, first.point.p, hinged, leg);
        for (k, m) in triad_links(t, &s) {
            self.set_link(k, m);
        }
        self.dets[g] = pose.det;
        self.triads[g] = Some(pose);
        Ok(within(&group.name)(singular))
    }
}

/// The group's links at rest in `pose`: the ternary link at B1; the sliding link at B1
/// (outer pair, along its guide) or at A1 (inner pair, along the ternary link's guide), as
/// the rates' solve places it; the hinged legs at A2, A3.
fn at_rest(
    pose: &TriadPose,
    a1: Point2<f64>,
    hinged: [Point2<f64>; 2],
    leg: &SliderLeg,
) -> TriadState {
    let link = |origin: Point2<f64>, angle: f64| LinkMotion {
        origin: PointMotion::fixed(origin),
        angle,
        omega: 0.0,
        epsilon: 0.0,
    };
    let sliding = match leg.dims.pair {
        SlidingPair::Outer { .. } => pose.b[0],
        SlidingPair::Inner { .. } => a1,
    };
    TriadState {
        b: pose.b.map(PointMotion::fixed),
        ternary: link(pose.b[0], pose.theta),
        binary: [
            link(sliding, pose.phi[0]),
            link(hinged[0], pose.phi[1]),
            link(hinged[1], pose.phi[2]),
        ],
        det: pose.det,
    }
}
