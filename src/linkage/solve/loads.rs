//! The loads of one position: every link's weight and inertia load, and the description's
//! loads evaluated at the solved kinematics.

use super::analysis::Analysis;
use super::state::within;
use crate::error::{Error, Result};
use crate::linkage::plan::LoadPlan;
use crate::Load;
use nalgebra::Vector2;

impl Analysis<'_> {
    pub(super) fn apply_loads(&mut self) -> Result<()> {
        let plan = self.plan;
        self.applied.clear();
        for (k, lp) in plan.chain.links.iter().enumerate().skip(1) {
            if lp.mass == 0.0 && lp.inertia == 0.0 {
                continue;
            }
            let s = self.kin.at(k, lp.centre);
            let epsilon = self.kin.links[k].epsilon;
            // The mass and J_S were checked by the plan and the motion by the groups: only the
            // products can overflow, and then `Load::inertia` names what did.
            let force = lp.mass * (plan.gravity - s.a);
            let moment = -lp.inertia * epsilon;
            if !(force.x + force.y + moment).is_finite() {
                Load::inertia(s.p, lp.mass, s.a, lp.inertia, epsilon)
                    .map_err(within(&plan.chain.link_names[k]))?;
                return Err(within(&plan.chain.link_names[k])(Error::Overflow {
                    what: "the link's weight and inertia force m·(g − a_S)",
                }));
            }
            self.applied.push((k, Load::new(s.p, force, moment)));
        }
        for lp in &plan.loads {
            match lp {
                LoadPlan::Force { link, local, force } => {
                    let p = self.kin.at(*link, *local).p;
                    self.applied.push((*link, Load::force_at(p, *force)));
                }
                LoadPlan::Moment { link, moment } => {
                    let p = self.kin.links[*link].origin.p;
                    self.applied
                        .push((*link, Load::new(p, Vector2::zeros(), *moment)));
                }
                LoadPlan::Turning {
                    link,
                    forward,
                    backward,
                } => {
                    let l = &self.kin.links[*link];
                    let m = resist(l.omega, *forward, *backward);
                    self.applied
                        .push((*link, Load::new(l.origin.p, Vector2::zeros(), m)));
                }
                LoadPlan::Sliding {
                    joint,
                    local,
                    forward,
                    backward,
                } => {
                    let (slider, guide, d) = self.pose().slide_parts(*joint);
                    let s = self.slide_at(*joint);
                    let p = self.kin.at(slider, *local).p;
                    let f = resist(s.rate, *forward, *backward) * d;
                    self.applied.push((slider, Load::force_at(p, f)));
                    if guide != 0 {
                        self.applied.push((guide, Load::force_at(p, -f)));
                    }
                }
                LoadPlan::Indicator {
                    joint,
                    head,
                    diagram,
                    ends,
                } => {
                    let (slider, _, d) = self.pose().slide_parts(*joint);
                    let s = self.slide_at(*joint);
                    let p = self.pose().joint_on_link(*joint, slider).p;
                    let f = diagram
                        .force(head * s.value, head * s.rate, *head * d, ends[0], ends[1])
                        .map_err(within(&format!(
                            "piston of joint {}",
                            plan.chain.joint_names[*joint]
                        )))?;
                    self.applied.push((slider, Load::force_at(p, f)));
                }
                LoadPlan::Custom { link, f } => {
                    let l = (f.0)(&self.pose()).map_err(within(&plan.chain.link_names[*link]))?;
                    l.validate()
                        .map_err(within(&plan.chain.link_names[*link]))?;
                    self.applied.push((*link, l));
                }
            }
        }
        Ok(())
    }
}

/// A resistance of magnitude `forward` while `rate` > 0 and `backward` while it is < 0,
/// opposing the motion; zero at rest.
fn resist(rate: f64, forward: f64, backward: f64) -> f64 {
    if rate > 0.0 {
        -forward
    } else if rate < 0.0 {
        backward
    } else {
        0.0
    }
}
