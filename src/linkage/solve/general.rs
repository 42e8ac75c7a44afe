//! A general group (a rigid group of hinges with no closed form) in one position's solve:
//! its positions by continuation from the reference pose, its rates and reactions by its
//! linear equations ([`HingedGroup`](crate::kinematics::HingedGroup)).
//!
//! # Which assembly mode
//! Every solve starts from the plan's reference pose and moves each known link that carries
//! an outer hinge from its reference frame to its frame now (its origin along the straight
//! line, its angle along the shorter arc, and if the group cannot follow that path, the
//! longer one), tracking the group by continuation. So the mode is the one the drawn pose
//! turns into, a solve is a pure function of the inputs (the same bits whatever was solved
//! before), and a crank input's path is the crank's own motion. Its Newton buffers
//! ([`GroupWork`]) are kept with the solver's state and reused from one position to the next.

use super::analysis::{Analysis, Reaction};
use super::state::{within, KinState};
use crate::angle::{normalize, unit};
use crate::error::Result;
use crate::kinematics::{GroupPose, GroupWork, PointMotion};
use crate::linkage::plan::Group;
use crate::linkage::plan_general::GeneralPlan;
use nalgebra::{Point2, Vector2};
use std::f64::consts::{PI, TAU};

/// `l` turned by the angle of the unit vector `e`.
fn turned(e: Vector2<f64>, l: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(e.x * l.x - e.y * l.y, e.y * l.x + e.x * l.y)
}

impl KinState {
    /// The known points of general group `gp` now.
    fn general_outer(&self, gp: &GeneralPlan) -> Vec<PointMotion> {
        gp.known.iter().map(|&(k, l)| self.at(k, l)).collect()
    }

    /// The pose of general group `gp` now, by continuation from its reference pose (module
    /// docs).
    fn general_pose(
        &self,
        gp: &GeneralPlan,
        outer: &[PointMotion],
        work: &mut GroupWork,
    ) -> Result<GroupPose> {
        let turns: Vec<f64> = gp
            .known
            .iter()
            .zip(&gp.known_reference)
            .map(|(&(k, _), &(_, a0))| normalize(self.links[k].angle - a0 + PI) - PI)
            .collect();
        let mut follow = |longer: bool| {
            let path = |t: f64, pts: &mut [Point2<f64>]| {
                for (o, p) in pts.iter_mut().enumerate() {
                    if t == 1.0 {
                        *p = outer[o].p;
                        continue;
                    }
                    let (k, l) = gp.known[o];
                    let (o0, a0) = gp.known_reference[o];
                    let turn = if longer && turns[o] != 0.0 {
                        turns[o] - TAU * turns[o].signum()
                    } else {
                        turns[o]
                    };
                    let origin = o0 + t * (self.links[k].origin.p - o0);
                    *p = origin + turned(unit(a0 + t * turn), l);
                }
            };
            gp.block.track_in(&gp.reference, path, gp.size, work)
        };
        follow(false).or_else(|e| {
            if turns.iter().any(|&t| t != 0.0) {
                follow(true).map_err(|_| e)
            } else {
                Err(e)
            }
        })
    }

    /// General group `g` solved in full: positions by continuation, then rates.
    pub(super) fn solve_general_kinematics(
        &mut self,
        g: usize,
        group: &Group,
        gp: &GeneralPlan,
    ) -> Result<()> {
        let outer = self.general_outer(gp);
        // The buffers are lent out for the solve (taking them allocates nothing).
        let mut work = std::mem::take(&mut self.general_work[g]);
        let pose = self.general_pose(gp, &outer, &mut work);
        self.general_work[g] = work;
        let pose = pose.map_err(within(&group.name))?;
        self.put_general(g, gp, &pose, &outer)
            .map_err(within(&group.name))
    }

    /// The rates of general group `g` at `pose`, stored with the positions.
    fn put_general(
        &mut self,
        g: usize,
        gp: &GeneralPlan,
        pose: &GroupPose,
        outer: &[PointMotion],
    ) -> Result<()> {
        let m = gp.block.rates(pose, outer, gp.size)?;
        for (i, &k) in gp.links.iter().enumerate() {
            self.put_link(k, m.links[i], unit(pose.angles[i]));
        }
        self.dets[g] = m.conditioning;
        Ok(())
    }

    /// The stored pose of general group `gp`.
    pub(super) fn general_stored(&self, gp: &GeneralPlan) -> GroupPose {
        GroupPose {
            origins: gp.links.iter().map(|&k| self.links[k].origin.p).collect(),
            angles: gp.links.iter().map(|&k| self.links[k].angle).collect(),
        }
    }

    /// General group `g`'s rates at the positions of the last solve; `Err` when a rate
    /// fails (the caller then solves the group in full, which names the failure).
    pub(super) fn general_rates_at(&mut self, g: usize, gp: &GeneralPlan) -> Result<()> {
        let outer = self.general_outer(gp);
        let pose = self.general_stored(gp);
        self.put_general(g, gp, &pose, &outer)
    }
}

impl Analysis<'_> {
    /// General group `g`'s reactions from the loads collected on its links; its outer
    /// reactions are added to the known links' loads.
    pub(super) fn solve_general(
        &mut self,
        g: usize,
        group: &Group,
        gp: &GeneralPlan,
    ) -> Result<()> {
        let pose = self.k.kin.general_stored(gp);
        let loads: Vec<_> = gp.links.iter().map(|&k| self.acc[k]).collect();
        let r = gp
            .block
            .reactions(&pose, &loads, gp.size)
            .map_err(within(&group.name))?;
        let at = |(i, l): (usize, Vector2<f64>)| pose.origins[i] + turned(unit(pose.angles[i]), l);
        for (h, &j) in gp.inner.iter().enumerate() {
            let [a, b] = gp.block.inner[h];
            // λ is the force of the hinge's second link on its first.
            self.reactions[j] = Reaction::hinge(gp.links[b.0], gp.links[a.0], r.inner[h], at(a));
        }
        for (o, &j) in gp.outer.iter().enumerate() {
            let end = gp.block.outer[o];
            let known = gp.known[o].0;
            let ra = Reaction::hinge(known, gp.links[end.0], r.outer[o], at(end));
            super::statics::add(&mut self.acc[known], &ra.load_on_side(known));
            self.reactions[j] = ra;
        }
        self.conditioning[g] = crate::kinetostatics::Conditioning {
            measure: r.conditioning,
            condition: (1.0 / r.conditioning).max(1.0),
        };
        Ok(())
    }
}
