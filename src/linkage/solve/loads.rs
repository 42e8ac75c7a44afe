//! The loads of one position: every link's weight and inertia load, and the description's
//! loads read by one interpreter, [`apply`], for both the kinetostatics (which collects them
//! as loads on links) and the dynamics (which projects them on the transfer functions).

use super::analysis::Analysis;
use super::state::{within, KinState};
use crate::error::{computed, Error, Result};
use crate::linkage::plan::{Chain, LoadPlan, Plan, Pose};
use crate::linkage::springs::End;
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
    /// The velocity of the point at `local` of link `link`.
    fn velocity(&self, link: usize, local: Vector2<f64>) -> Vector2<f64>;
    /// The angle of link `link`'s frame.
    fn angle(&self, link: usize) -> f64;
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
            LoadPlan::Spring(sp) => {
                let (u, l) = line_of(site, &sp.ends, &sp.name, names.size)?;
                pull(site, &sp.ends, sp.tension(l) * u);
            }
            LoadPlan::Damper(dp) => {
                let (u, _) = line_of(site, &dp.ends, &dp.name, names.size)?;
                let [(a, pa), (b, pb)] = dp.ends;
                let rate = u.dot(&(site.velocity(b, pb) - site.velocity(a, pa)));
                pull(site, &dp.ends, dp.c * rate * u);
            }
            LoadPlan::Torsion(tp) => {
                let [a, b] = tp.links;
                let m = tp.moment(tp.twist([site.angle(a), site.angle(b)]));
                // The frame holds its share without a free body of its own.
                if a != 0 {
                    site.couple(a, m);
                }
                if b != 0 {
                    site.couple(b, -m);
                }
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

/// The unit vector from the first end of a spring or damper `name` to its second, and their
/// distance.
///
/// # Errors
/// [`Error::Singular`] (within `name`) when the ends meet (to 10⁻¹² of the linkage's
/// `size`, where rounding alone turns the direction): the line of the force is lost.
fn line_of(
    site: &impl LoadSite,
    ends: &[End; 2],
    name: &str,
    size: f64,
) -> Result<(Vector2<f64>, f64)> {
    let [(a, pa), (b, pb)] = *ends;
    let d = site.position(b, pb) - site.position(a, pa);
    let l = d.norm();
    if l > 1e-12 * size && l.is_finite() {
        Ok((d / l, l))
    } else {
        Err(within(name)(Error::Singular {
            what: "the line between the ends",
            measure: "the distance between the ends",
            value: l,
        }))
    }
}

/// The force `f` on the first end (toward the second when it pulls) and −`f` on the
/// second; the frame's share is left out of the free bodies.
fn pull(site: &mut impl LoadSite, ends: &[End; 2], f: Vector2<f64>) {
    for ((link, local), f) in ends.iter().zip([f, -f]) {
        if *link != 0 {
            site.force_at_local(*link, *local, f);
        }
    }
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
    fn velocity(&self, link: usize, local: Vector2<f64>) -> Vector2<f64> {
        self.kin.at(link, local).v
    }

    #[inline]
    fn angle(&self, link: usize) -> f64 {
        self.kin.links[link].angle
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

impl Plan {
    /// The potential energy stored in the description's springs (linear and torsion) at a
    /// solved position, J: zero at each spring's free length (or angle).
    ///
    /// # Errors
    /// [`Error::Overflow`](crate::Error::Overflow) when the sum overflows;
    /// [`Error::Description`](crate::Error::Description) for a pose of another plan.
    ///
    /// # Examples
    /// A spring of 200 N/m and free length 0.1 m from a frame point to the four-bar's
    /// coupler: its energy at the reference pose is ½·k·(L − L₀)².
    /// ```
    /// use tmm::linkage::{bundled, Anchor, At, LoadSpec, Plan};
    /// let mut l = bundled::four_bar();
    /// l.loads = vec![LoadSpec::Spring {
    ///     name: "s".into(),
    ///     ends: [Anchor::on("frame", At::Coords([0.2, 0.5])), Anchor::on("coupler", At::name("B"))],
    ///     stiffness: 200.0,
    ///     free_length: 0.1,
    ///     preload: 0.0,
    /// }];
    /// let plan = Plan::new(&l)?;
    /// let b = l.joints.iter().find(|j| j.name == "B").unwrap().at;
    /// let len = ((b[0] - 0.2f64).powi(2) + (b[1] - 0.5f64).powi(2)).sqrt();
    /// let k = plan.kinematics(tmm::kinematics::Motion::fixed(plan.reference_input()))?;
    /// let v = plan.spring_energy(&k.pose())?;
    /// assert!((v - 0.5 * 200.0 * (len - 0.1f64).powi(2)).abs() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn spring_energy(&self, pose: &Pose<'_>) -> Result<f64> {
        if !(std::ptr::eq(pose.chain, &self.chain) || *pose.chain == self.chain) {
            return Err(crate::linkage::plan::bad(
                "pose",
                "is a position of another plan",
            ));
        }
        let mut v = 0.0;
        for l in &self.loads {
            v += match l {
                LoadPlan::Spring(s) => {
                    let [(a, pa), (b, pb)] = s.ends;
                    s.energy((pose.at(b, pb).p - pose.at(a, pa).p).norm())
                }
                LoadPlan::Torsion(t) => {
                    let [a, b] = t.links;
                    t.energy(t.twist([pose.links[a].angle, pose.links[b].angle]))
                }
                _ => 0.0,
            };
        }
        computed("the springs' potential energy", v)
    }
}
