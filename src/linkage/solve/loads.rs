//! The loads of one position: every link's weight and inertia load, and the description's
//! loads read by one interpreter, [`apply`], for both the kinetostatics (which collects them
//! as loads on links) and the dynamics (which projects them on the transfer functions).

use super::analysis::Analysis;
use super::state::{within, KinState};
use crate::error::{Error, Result};
use crate::linkage::plan::{Chain, LoadPlan, Plan, Pose};
use crate::Load;
use nalgebra::{Point2, Vector2};

/// What the load interpreter reads of a position, and where it puts each load.
///
/// The kinetostatics reads one solved position and collects the loads on the links; the
/// dynamics reads the transfer functions at a state and adds each load's generalized force.
/// Each reading is the one a load kind needs, so both see a description's load the same way.
pub(crate) trait LoadSite {
    /// The position of the point at `local` of link `link`.
    fn position(&self, link: usize, local: Vector2<f64>) -> Point2<f64>;
    /// The angular velocity of link `link`.
    fn omega(&self, link: usize) -> f64;
    /// The sliding link, the guide's link and the guide's unit direction now of the prismatic
    /// joint `joint`.
    fn slide_parts(&self, joint: usize) -> (usize, usize, Vector2<f64>);
    /// The slide of prismatic joint `joint` along the guide direction `d`, and its rate.
    fn slide(&self, joint: usize, d: Vector2<f64>) -> (f64, f64);
    /// The position as a user's load function sees it.
    fn pose(&mut self) -> Result<Pose<'_>>;
    /// A force at the point `local` of link `link`.
    fn force_at_local(&mut self, link: usize, local: Vector2<f64>, force: Vector2<f64>);
    /// A couple on link `link`.
    fn couple(&mut self, link: usize, moment: f64);
    /// A force on link `on` at `p` and its opposite on link `against` at the same place (a
    /// sliding pair's force between the slider and its guide).
    fn force_between(&mut self, on: usize, against: usize, p: Point2<f64>, force: Vector2<f64>);
    /// A load on link `link` (a user's, checked finite).
    fn load(&mut self, link: usize, load: Load);
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

/// Reads every load of `plan` (the description's, then the users' functions, in the plan's
/// order) at `site` and puts it there.
///
/// # Errors
/// An indicator diagram read outside its stroke ([`Error::In`] naming the piston's joint); a
/// user's load function's error or a non-finite load ([`Error::In`] naming its link).
pub(crate) fn apply(plan: &Plan, site: &mut impl LoadSite) -> Result<()> {
    let names = &plan.chain;
    for lp in &plan.loads {
        match lp {
            LoadPlan::Force { link, local, force } => site.force_at_local(*link, *local, *force),
            LoadPlan::Moment { link, moment } => site.couple(*link, *moment),
            LoadPlan::Turning {
                link,
                forward,
                backward,
            } => {
                let m = resist(site.omega(*link), *forward, *backward);
                site.couple(*link, m);
            }
            LoadPlan::Sliding {
                joint,
                local,
                forward,
                backward,
            } => {
                let (slider, guide, d) = site.slide_parts(*joint);
                let (_, rate) = site.slide(*joint, d);
                let f = resist(rate, *forward, *backward) * d;
                let p = site.position(slider, *local);
                site.force_between(slider, guide, p, f);
            }
            LoadPlan::Indicator {
                joint,
                head,
                diagram,
                ends,
            } => {
                // The piston's guide is the frame: the force acts on the piston alone.
                let (slider, _, d) = site.slide_parts(*joint);
                let (s, rate) = site.slide(*joint, d);
                let f = diagram
                    .force(head * s, head * rate, *head * d, ends[0], ends[1])
                    .map_err(within(&format!(
                        "piston of joint {}",
                        names.joint_names[*joint]
                    )))?;
                let jp = &names.joints[*joint];
                let local = jp.local[usize::from(jp.links[1] == slider)];
                site.force_at_local(slider, local, f);
            }
            LoadPlan::Custom { link, f } => {
                let part = within(&names.link_names[*link]);
                let l = (f.0)(&site.pose()?).map_err(&part)?;
                l.validate().map_err(&part)?;
                site.load(*link, l);
            }
        }
    }
    Ok(())
}

/// The kinetostatics' site: one solved position, the loads collected on the links.
struct Collect<'a> {
    chain: &'a Chain,
    kin: &'a KinState,
    applied: &'a mut Vec<(usize, Load)>,
}

impl LoadSite for Collect<'_> {
    #[inline]
    fn position(&self, link: usize, local: Vector2<f64>) -> Point2<f64> {
        self.kin.at(link, local).p
    }

    #[inline]
    fn omega(&self, link: usize) -> f64 {
        self.kin.links[link].omega
    }

    fn slide_parts(&self, joint: usize) -> (usize, usize, Vector2<f64>) {
        self.kin.pose(self.chain).slide_parts(joint)
    }

    fn slide(&self, joint: usize, _d: Vector2<f64>) -> (f64, f64) {
        let s = self.kin.pose(self.chain).slide_at(joint);
        (s.value, s.rate)
    }

    fn pose(&mut self) -> Result<Pose<'_>> {
        Ok(self.kin.pose(self.chain))
    }

    #[inline]
    fn force_at_local(&mut self, link: usize, local: Vector2<f64>, force: Vector2<f64>) {
        let p = self.position(link, local);
        self.applied.push((link, Load::force_at(p, force)));
    }

    #[inline]
    fn couple(&mut self, link: usize, moment: f64) {
        let p = self.kin.links[link].origin.p;
        self.applied
            .push((link, Load::new(p, Vector2::zeros(), moment)));
    }

    fn force_between(&mut self, on: usize, against: usize, p: Point2<f64>, force: Vector2<f64>) {
        self.applied.push((on, Load::force_at(p, force)));
        // The frame's share holds nothing up: it is left out of the free bodies.
        if against != 0 {
            self.applied.push((against, Load::force_at(p, -force)));
        }
    }

    #[inline]
    fn load(&mut self, link: usize, load: Load) {
        self.applied.push((link, load));
    }
}

impl Analysis<'_> {
    pub(super) fn apply_loads(&mut self) -> Result<()> {
        let plan = self.k.plan;
        self.applied.clear();
        for (k, lp) in plan.chain.links.iter().enumerate().skip(1) {
            if lp.mass == 0.0 && lp.inertia == 0.0 {
                continue;
            }
            let s = self.k.kin.at(k, lp.centre);
            let epsilon = self.k.kin.links[k].epsilon;
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
        apply(
            plan,
            &mut Collect {
                chain: &plan.chain,
                kin: &self.k.kin,
                applied: &mut self.applied,
            },
        )
    }
}
