//! One analysed position of a planned linkage: the kinematics of every link, the loads, the
//! reaction in every joint and the balancing moment or force, with the two independent checks
//! (virtual power and every link's equilibrium).
//!
//! An [`Analysis`] owns its buffers: [`Plan::analyse_into`] refills one without allocating,
//! so a sweep over millions of positions reuses a single one.

use super::description::Drive;
use super::plan::{Group, GroupKind, InputPlan, LoadPlan, Plan};
use crate::angle::{cross, perp, unit};
use crate::error::{Error, Result};
use crate::kinematics::{
    prp_dyad, rpp_dyad, rpr_dyad, rrp_dyad, rrr_dyad, Guide, LinkMotion, Motion, PointMotion,
};
use crate::kinetostatics::{
    Conditioning, CouplingDrive, GearDrive, PrpDyad, RppDyad, RprDyad, RrpDyad, RrrDyad,
};
use crate::Load;
use nalgebra::{Point2, Vector2};

/// The reaction in one joint: the force (and, in a sliding pair, the couple) that link `by`
/// exerts on link `on`, R_by,on. The other link feels the opposite.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Reaction {
    /// The link that exerts it (index into [`Plan::link_names`]).
    pub by: usize,
    /// The link it acts on.
    pub on: usize,
    /// The force, N.
    pub force: Vector2<f64>,
    /// The point the force is reduced to (the hinge, or a point on a sliding pair's axis), m.
    pub point: Point2<f64>,
    /// The couple about `point`, N·m (zero in a hinge; in a sliding pair it places the normal
    /// force's line of action, see [`Reaction::offset`]).
    pub moment: f64,
}

impl Reaction {
    /// The force (and couple) of link `by` on link `on`, reduced to `point`.
    #[must_use]
    pub fn new(by: usize, on: usize, force: Vector2<f64>, point: Point2<f64>, moment: f64) -> Self {
        Self {
            by,
            on,
            force,
            point,
            moment,
        }
    }

    /// A hinge's reaction: a force at the hinge, no couple.
    #[must_use]
    pub fn hinge(by: usize, on: usize, force: Vector2<f64>, point: Point2<f64>) -> Self {
        Self::new(by, on, force, point, 0.0)
    }

    /// The reaction as a load on link `on`.
    #[must_use]
    pub fn load(&self) -> Load {
        Load::new(self.point, self.force, self.moment)
    }

    /// The load on link `link`: the reaction itself if `link == on`, its opposite if
    /// `link == by`.
    ///
    /// # Errors
    /// [`Error::Description`] when `link` is neither of the two links the reaction joins
    /// (no load of this joint acts on it).
    pub fn load_on(&self, link: usize) -> Result<Load> {
        if link == self.on || link == self.by {
            Ok(self.load_on_side(link))
        } else {
            Err(Error::Description {
                item: format!("link index {link}"),
                problem: format!(
                    "is not joined by this reaction (it acts between links {} and {})",
                    self.by, self.on
                ),
            })
        }
    }

    /// [`load_on`](Self::load_on) for a link known to be `on` or `by`.
    fn load_on_side(&self, link: usize) -> Load {
        if link == self.on {
            self.load()
        } else {
            Load::new(self.point, -self.force, -self.moment)
        }
    }

    /// For a sliding pair with the axis direction `axis`: where the normal force's line of
    /// action crosses the axis through `point`, measured from `point` along `axis`, m. `None`
    /// when the force vanishes and the pair carries a pure couple.
    #[must_use]
    pub fn offset(&self, axis: Vector2<f64>) -> Option<f64> {
        let h = self.moment / cross(axis / axis.norm(), self.force);
        h.is_finite().then_some(h)
    }
}

/// What the drive supplies to the input link and what the frame holds.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Balance {
    /// The balancing generalized force: for a crank M_b about its pivot, N·m, counter-clockwise
    /// positive (for a gear drive the moment of the tooth force); for a slider the force along
    /// its guide direction, N.
    pub value: f64,
    /// The balancing force: the pinion's tooth force at the pitch point (gear drive), the
    /// drive's force along the guide (slider), zero for a coupling, N.
    pub force: Vector2<f64>,
    /// Where `force` acts: the pitch point, the slider's reference point, or the pivot, m.
    pub point: Point2<f64>,
    /// The conditioning of the balance (the gear drive's arm; 1 otherwise).
    pub conditioning: Conditioning,
}

/// The balancing value found two ways at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PowerCheck {
    /// From the group-by-group chain.
    pub chain: f64,
    /// From the principle of virtual power: −Σ P_i / q̇ over every applied load.
    pub virtual_power: f64,
    /// The scale of the comparison: the largest of |chain| and Σ|P_i|/|q̇|.
    pub scale: f64,
}

impl PowerCheck {
    /// |chain − virtual power| / scale.
    #[must_use]
    pub fn relative_error(&self) -> f64 {
        let d = (self.chain - self.virtual_power).abs();
        if self.scale > 0.0 {
            d / self.scale
        } else {
            d
        }
    }
}

/// One analysed position of a [`Plan`].
#[derive(Debug, Clone)]
pub struct Analysis<'p> {
    plan: &'p Plan,
    input: Motion,
    second_input: Option<Motion>,
    links: Vec<LinkMotion>,
    /// Each link's unit vector e(φ), computed once per position: every point of a link is
    /// placed with it, so no trigonometry is repeated.
    units: Vec<Vector2<f64>>,
    /// Per group, the constant rotations (cos, sin) of its guides' offsets (first and second
    /// outer joint) and of an RPP's slide angle: a guide's unit vector is its link's rotated.
    turns: Vec<[Vector2<f64>; 3]>,
    dets: Vec<f64>,
    applied: Vec<(usize, Load)>,
    acc: Vec<Load>,
    reactions: Vec<Reaction>,
    conditioning: Vec<Conditioning>,
    balance: Balance,
    second_balance: Option<Balance>,
    statics_done: bool,
}

/// Wraps an error of one part so that it names the part.
fn within(part: &str) -> impl Fn(Error) -> Error + '_ {
    move |e| Error::In {
        part: part.to_owned(),
        source: Box::new(e),
    }
}

/// The motion of an input link at its input coordinate.
fn input_motion(ip: &InputPlan, input: Motion) -> Result<LinkMotion> {
    Ok(match *ip {
        InputPlan::Crank { pivot, .. } => LinkMotion {
            origin: PointMotion::fixed(pivot),
            angle: crate::angle::normalize(input.value),
            omega: input.rate,
            epsilon: input.accel,
        },
        InputPlan::Slider { at, angle, .. } => {
            let d = unit(angle);
            let o = PointMotion::new(at + input.value * d, input.rate * d, input.accel * d);
            o.validate(["slider x", "slider y", "v.x", "v.y", "a.x", "a.y"])?;
            LinkMotion {
                origin: o,
                angle,
                omega: 0.0,
                epsilon: 0.0,
            }
        }
    })
}

/// The unit vector along `v` (a link's side between two of its joints, never zero once its
/// group is solved).
#[inline]
fn direction_of(v: Vector2<f64>) -> Vector2<f64> {
    v / v.norm()
}

/// `u` turned by the angle whose cosine and sine are `r`.
#[inline]
fn turn(u: Vector2<f64>, r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(u.x * r.x - u.y * r.y, u.x * r.y + u.y * r.x)
}

/// The motion of the point at `local` (along, across) of `link`, whose unit vector is `e`.
#[inline]
fn point_with(link: &LinkMotion, e: Vector2<f64>, local: Vector2<f64>) -> PointMotion {
    let r = local.x * e + local.y * perp(e);
    PointMotion::new(
        link.origin.p + r,
        link.origin.v + link.omega * perp(r),
        link.origin.a + link.epsilon * perp(r) - link.omega * link.omega * r,
    )
}

impl<'p> Analysis<'p> {
    /// Buffers for analysing positions of `plan` (allocated once).
    #[must_use]
    pub fn new(plan: &'p Plan) -> Self {
        let n = plan.link_names.len();
        let zero = Reaction {
            by: 0,
            on: 0,
            force: Vector2::zeros(),
            point: Point2::origin(),
            moment: 0.0,
        };
        Self {
            plan,
            input: Motion::default(),
            second_input: None,
            links: vec![Plan::frame_motion(); n],
            units: vec![Vector2::x(); n],
            turns: plan
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
            dets: vec![0.0; plan.groups.len()],
            applied: Vec::with_capacity(n + plan.loads.len() * 2),
            acc: vec![Load::zero(Point2::origin()); n],
            reactions: vec![zero; plan.joints.len()],
            conditioning: vec![
                Conditioning {
                    measure: 1.0,
                    condition: 1.0
                };
                plan.groups.len()
            ],
            balance: Balance {
                value: 0.0,
                force: Vector2::zeros(),
                point: Point2::origin(),
                conditioning: Conditioning {
                    measure: 1.0,
                    condition: 1.0,
                },
            },
            second_balance: None,
            statics_done: false,
        }
    }

    /// The motion of the point at `local` in link `k`'s frame.
    #[inline]
    fn at(&self, k: usize, local: Vector2<f64>) -> PointMotion {
        point_with(&self.links[k], self.units[k], local)
    }

    /// The position alone of joint `j` as a point of link `link` (one of its two links): what
    /// [`joint_on_link`](Self::joint_on_link) gives as `p`, to the bit, without the
    /// velocity and acceleration the reactions do not need.
    #[inline]
    fn joint_position_on(&self, j: usize, link: usize) -> Point2<f64> {
        let jp = &self.plan.joints[j];
        let local = jp.local[usize::from(jp.links[1] == link)];
        let e = self.units[link];
        self.links[link].origin.p + (local.x * e + local.y * perp(e))
    }

    /// The unit vector along link `k`'s frame angle (kept with its motion).
    #[inline]
    pub(crate) fn link_unit(&self, k: usize) -> Vector2<f64> {
        self.units[k]
    }

    /// Stores link `k`'s motion with its unit vector.
    #[inline]
    fn set_link(&mut self, k: usize, m: LinkMotion) {
        self.put_link(k, m, m.unit());
    }

    /// Stores link `k`'s motion with its unit vector `u` = e(φ), already known.
    #[inline]
    fn put_link(&mut self, k: usize, m: LinkMotion, u: Vector2<f64>) {
        self.units[k] = u;
        self.links[k] = m;
    }

    /// The guide through the point at `local` of link `k`, at `offset` to the link's frame
    /// angle, moving with the link.
    fn guide_on(&self, k: usize, local: Vector2<f64>, offset: f64) -> Guide {
        let link = &self.links[k];
        Guide {
            point: self.at(k, local),
            angle: Motion::new(link.angle + offset, link.omega, link.epsilon),
        }
    }

    /// The plan this position belongs to.
    #[must_use]
    pub fn plan(&self) -> &'p Plan {
        self.plan
    }

    /// Positions, velocities and accelerations of every link at the input `input` (φ1, ω1,
    /// ε1 for a crank; s, ṡ, s̈ for a slider), group by group in attachment order.
    ///
    /// # Errors
    /// Non-finite input; [`Error::In`] naming the group that cannot be assembled or is at a
    /// dead point; [`Error::Description`] for a linkage with two inputs (use
    /// [`Analysis::solve_kinematics_inputs`]).
    pub fn solve_kinematics(&mut self, input: Motion) -> Result<()> {
        self.solve_kinematics_inputs(&[input])
    }

    /// As [`Analysis::solve_kinematics`], with one motion per input: one for a linkage with
    /// one input, two for a linkage with a [`second_input`](super::Linkage::second_input).
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics`]; [`Error::Description`] when the number of motions is
    /// not the number of inputs.
    ///
    /// # Examples
    /// The five-bar robot: both cranks at their reference angles, crank 1 turning at 1 rad/s;
    /// the end effector B moves.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Analysis, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let [q1, q2] = plan.reference_inputs()[..] else { unreachable!() };
    /// let mut a = Analysis::new(&plan);
    /// a.solve_kinematics_inputs(&[Motion::new(q1, 1.0, 0.0), Motion::new(q2, 0.0, 0.0)])?;
    /// assert!(a.joint("B")?.v.norm() > 0.0);
    /// assert!(a.solve_kinematics(Motion::new(q1, 1.0, 0.0)).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn solve_kinematics_inputs(&mut self, inputs: &[Motion]) -> Result<()> {
        self.statics_done = false;
        let plan = self.plan;
        let (input, second) = match (inputs, &plan.second_input) {
            ([i], None) => (*i, None),
            ([i, j], Some((ip, _))) => (*i, Some((*j, ip))),
            _ => {
                return Err(Error::Description {
                    item: "inputs".to_owned(),
                    problem: format!(
                        "the linkage has {} input(s), {} motion(s) given",
                        plan.input_count(),
                        inputs.len()
                    ),
                })
            }
        };
        input.validate(["input", "input rate", "input acceleration"])?;
        // The input's ω² and ε times the linkage's size bound its points' accelerations: past
        // f64's range the motion overflows whatever the groups do.
        let bound = |m: &Motion| {
            crate::error::computed(
                "the input's accelerations (size·(ω² + |ε|))",
                plan.size * (m.rate * m.rate + m.accel.abs()),
            )
        };
        bound(&input)?;
        self.input = input;
        let link = plan.input.link();
        let motion = input_motion(&plan.input, input)?;
        self.set_link(link, motion);
        self.second_input = None;
        if let Some((m, ip)) = second {
            m.validate([
                "second input",
                "second input rate",
                "second input acceleration",
            ])?;
            bound(&m)?;
            let motion = input_motion(ip, m)?;
            self.set_link(ip.link(), motion);
            self.second_input = Some(m);
        }
        for (g, group) in plan.groups.iter().enumerate() {
            self.solve_group_kinematics(g, group)?;
        }
        // A named point may lie farther out on its link than any joint (beyond the bound
        // above): its motion is computed on demand, so it is checked here, once.
        for k in 0..plan.points.len() {
            let m = self.point_motion_at(k);
            if !(m.p.coords.iter().chain(m.v.iter()).chain(m.a.iter())).all(|x| x.is_finite()) {
                return Err(Error::In {
                    part: format!("point {}", plan.point_names[k]),
                    source: Box::new(Error::Overflow {
                        what: "its position, velocity or acceleration",
                    }),
                });
            }
        }
        Ok(())
    }

    /// Kinematics, loads, the reactions from the last group back to the input link, and the
    /// balancing moment or force.
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics`]; a load that cannot be evaluated (a non-finite
    /// inertia load, an indicator diagram read outside its stroke); [`Error::In`] naming the
    /// group or the input link whose closed form is singular.
    pub fn solve(&mut self, input: Motion) -> Result<()> {
        self.solve_inputs(&[input])
    }

    /// As [`Analysis::solve`], with one motion per input (see
    /// [`Analysis::solve_kinematics_inputs`]): a linkage with two inputs gets two balancing
    /// moments or forces, [`Analysis::balance`] and [`Analysis::second_balance`].
    ///
    /// # Errors
    /// As [`Analysis::solve`] and [`Analysis::solve_kinematics_inputs`].
    ///
    /// # Examples
    /// The five-bar robot turning both cranks: the two balancing moments supply the power of
    /// every load, and every link is in equilibrium.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Analysis, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let r = plan.reference_inputs();
    /// let mut a = Analysis::new(&plan);
    /// a.solve_inputs(&[Motion::new(r[0], 2.0, 1.0), Motion::new(r[1], -1.0, 3.0)])?;
    /// assert!(a.second_balance().is_some());
    /// assert!(a.power_check()?.relative_error() < 1e-12);
    /// assert!(a.worst_residual() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn solve_inputs(&mut self, inputs: &[Motion]) -> Result<()> {
        self.solve_kinematics_inputs(inputs)?;
        self.apply_loads()?;
        self.solve_statics()
    }

    fn apply_loads(&mut self) -> Result<()> {
        let plan = self.plan;
        self.applied.clear();
        for (k, lp) in plan.links.iter().enumerate().skip(1) {
            if lp.mass == 0.0 && lp.inertia == 0.0 {
                continue;
            }
            let s = self.at(k, lp.centre);
            let epsilon = self.links[k].epsilon;
            // The mass and J_S were checked by the plan and the motion by the groups: only the
            // products can overflow, and then `Load::inertia` names what did.
            let force = lp.mass * (plan.gravity - s.a);
            let moment = -lp.inertia * epsilon;
            if !(force.x + force.y + moment).is_finite() {
                Load::inertia(s.p, lp.mass, s.a, lp.inertia, epsilon)
                    .map_err(within(&plan.link_names[k]))?;
                return Err(within(&plan.link_names[k])(Error::Overflow {
                    what: "the link's weight and inertia force m·(g − a_S)",
                }));
            }
            self.applied.push((k, Load::new(s.p, force, moment)));
        }
        for lp in &plan.loads {
            match lp {
                LoadPlan::Force { link, local, force } => {
                    let p = self.at(*link, *local).p;
                    self.applied.push((*link, Load::force_at(p, *force)));
                }
                LoadPlan::Moment { link, moment } => {
                    let p = self.links[*link].origin.p;
                    self.applied
                        .push((*link, Load::new(p, Vector2::zeros(), *moment)));
                }
                LoadPlan::Turning {
                    link,
                    forward,
                    backward,
                } => {
                    let l = &self.links[*link];
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
                    let (slider, guide, d) = self.slide_parts(*joint);
                    let s = self.slide_at(*joint);
                    let p = self.at(slider, *local).p;
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
                    let (slider, _, d) = self.slide_parts(*joint);
                    let s = self.slide_at(*joint);
                    let p = self.joint_on_link(*joint, slider).p;
                    let f = diagram
                        .force(head * s.value, head * s.rate, *head * d, ends[0], ends[1])
                        .map_err(within(&format!(
                            "piston of joint {}",
                            plan.joint_names[*joint]
                        )))?;
                    self.applied.push((slider, Load::force_at(p, f)));
                }
                LoadPlan::Custom { link, f } => {
                    let l = (f.0)(self).map_err(within(&plan.link_names[*link]))?;
                    l.validate().map_err(within(&plan.link_names[*link]))?;
                    self.applied.push((*link, l));
                }
            }
        }
        Ok(())
    }

    fn solve_statics(&mut self) -> Result<()> {
        let plan = self.plan;
        for (k, acc) in self.acc.iter_mut().enumerate() {
            *acc = Load::zero(self.links[k].origin.p);
        }
        for &(k, l) in &self.applied {
            add(&mut self.acc[k], &l);
        }
        for (g, group) in plan.groups.iter().enumerate().rev() {
            self.solve_group(g, group)?;
        }
        self.solve_input()?;
        self.statics_done = true;
        Ok(())
    }

    fn solve_group(&mut self, g: usize, group: &Group) -> Result<()> {
        let [l2, l3] = group.links;
        let [ja, jb, jc] = group.joints;
        let [ka, kc] = group.known;
        let a = self.links[l2].origin.p;
        let (load2, load3) = (self.acc[l2], self.acc[l3]);
        let name = &group.name;
        let (ra, rb, rc, cond) = match group.kind {
            GroupKind::Rrr => {
                let b = self.joint_position_on(jb, l2);
                let c = self.links[l3].origin.p;
                let r = RrrDyad {
                    a,
                    b,
                    c,
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::hinge(l2, l3, r.r23, b),
                    Reaction::hinge(kc, l3, r.r43, c),
                    r.conditioning,
                )
            }
            GroupKind::Rrp => {
                let b = self.links[l3].origin.p;
                let r = RrpDyad {
                    a,
                    b,
                    guide: self.units[l3],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::hinge(l2, l3, r.r23, b),
                    Reaction::new(kc, l3, r.r43, b, r.guide_moment),
                    r.conditioning,
                )
            }
            GroupKind::Rpr => {
                let c = self.links[l3].origin.p;
                let r = RprDyad {
                    a,
                    e: c,
                    axis: self.units[l2],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::new(l3, l2, r.r32, a, r.couple),
                    Reaction::hinge(kc, l3, r.r43, c),
                    r.conditioning,
                )
            }
            GroupKind::Prp => {
                let b = self.links[l2].origin.p;
                let r = PrpDyad {
                    b,
                    guide2: self.units[l2],
                    guide3: self.units[l3],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::new(ka, l2, r.r12, b, r.moment12),
                    Reaction::hinge(l2, l3, r.r23, b),
                    Reaction::new(kc, l3, r.r43, b, r.moment43),
                    r.conditioning,
                )
            }
            GroupKind::Rpp => {
                let b = self.links[l3].origin.p;
                let r = RppDyad {
                    a,
                    b,
                    guide: self.units[l3],
                    slot: self.units[l2],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::new(l3, l2, r.r32, a, r.moment32),
                    Reaction::new(kc, l3, r.r43, b, r.moment43),
                    r.conditioning,
                )
            }
        };
        add(&mut self.acc[ka], &ra.load_on_side(ka));
        add(&mut self.acc[kc], &rc.load_on_side(kc));
        self.reactions[ja] = ra;
        self.reactions[jb] = rb;
        self.reactions[jc] = rc;
        self.conditioning[g] = cond;
        Ok(())
    }

    fn solve_input(&mut self) -> Result<()> {
        let plan = self.plan;
        self.balance = self.solve_drive(&plan.input)?;
        self.second_balance = match &plan.second_input {
            Some((ip, _)) => Some(self.solve_drive(ip)?),
            None => None,
        };
        Ok(())
    }

    /// The balancing moment or force of one input link, and its reaction with the frame.
    fn solve_drive(&mut self, ip: &InputPlan) -> Result<Balance> {
        let plan = self.plan;
        let link = ip.link();
        let load = self.acc[link];
        let part = &plan.link_names[link];
        let balance;
        match *ip {
            InputPlan::Crank {
                joint,
                pivot,
                drive,
                ..
            } => {
                let (value, force, at, r01, conditioning) = match drive {
                    Drive::Coupling => {
                        let b = CouplingDrive { o1: pivot }
                            .solve(&[load])
                            .map_err(within(part))?;
                        (
                            b.balancing_moment,
                            Vector2::zeros(),
                            pivot,
                            b.r01,
                            b.conditioning,
                        )
                    }
                    Drive::Gear {
                        pitch_radius,
                        pitch_angle,
                        pressure_angle,
                    } => {
                        let d =
                            GearDrive::at_angle(pivot, pitch_radius, pitch_angle, pressure_angle);
                        let b = d.solve(&[load]).map_err(within(part))?;
                        (
                            b.balancing_moment,
                            b.force,
                            d.pitch_point,
                            b.r01,
                            b.conditioning,
                        )
                    }
                };
                self.reactions[joint] = Reaction::hinge(0, link, r01, pivot);
                balance = Balance {
                    value,
                    force,
                    point: at,
                    conditioning,
                };
            }
            InputPlan::Slider { joint, angle, .. } => {
                let d = unit(angle);
                let f = load.force;
                let fb = -f.dot(&d);
                let normal = -(f + fb * d);
                self.reactions[joint] = Reaction::new(0, link, normal, load.point, -load.moment);
                balance = Balance {
                    value: fb,
                    force: fb * d,
                    point: load.point,
                    conditioning: Conditioning {
                        measure: 1.0,
                        condition: 1.0,
                    },
                };
                let all = [fb, normal.x, normal.y, load.moment];
                if !all.iter().all(|v| v.is_finite()) {
                    return Err(within(part)(Error::NonFinite {
                        name: "balancing force",
                        value: fb,
                    }));
                }
            }
        }
        Ok(balance)
    }

    // ---- kinematic results -------------------------------------------------------------

    /// The input φ1, ω1, ε1 (or s, ṡ, s̈).
    #[must_use]
    pub fn input(&self) -> Motion {
        self.input
    }

    /// The second input's motion, for a linkage with two inputs.
    #[must_use]
    pub fn second_input(&self) -> Option<Motion> {
        self.second_input
    }

    /// The motion of link `k` in the frame the engine uses for it (its origin a joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn link_motion(&self, k: usize) -> Result<&LinkMotion> {
        Ok(self.link_motion_at(self.plan.check_link(k)?))
    }

    /// As [`link_motion`](Self::link_motion), for an index known to be a link's.
    #[inline]
    pub(crate) fn link_motion_at(&self, k: usize) -> &LinkMotion {
        &self.links[k]
    }

    /// The angle of link `k` along its declared reference direction, with ω and ε.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn link_angle_index(&self, k: usize) -> Result<Motion> {
        Ok(self.link_angle_at(self.plan.check_link(k)?))
    }

    /// As [`link_angle_index`](Self::link_angle_index), for an index known to be a link's.
    #[inline]
    pub(crate) fn link_angle_at(&self, k: usize) -> Motion {
        let l = &self.links[k];
        Motion::new(
            crate::angle::normalize(l.angle + self.plan.links[k].angle_offset),
            l.omega,
            l.epsilon,
        )
    }

    /// The angle of the link called `name` (rad, along its reference direction), ω and ε.
    ///
    /// # Errors
    /// An unknown name.
    pub fn link(&self, name: &str) -> Result<Motion> {
        Ok(self.link_angle_at(self.plan.link_index(name)?))
    }

    /// The motion of joint `j` as a point of the `side`-th of its two links
    /// ([`Plan::joint_links`]).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`;
    /// [`Error::OutOfRange`] (`"side"`) for `side` not 0 or 1.
    pub fn joint_on(&self, j: usize, side: usize) -> Result<PointMotion> {
        let j = self.plan.check_joint(j)?;
        if side > 1 {
            return Err(Error::OutOfRange {
                name: "side",
                value: side as f64,
                min: 0.0,
                max: 1.0,
                ends: crate::Ends::Closed,
            });
        }
        Ok(self.joint_on_at(j, side))
    }

    /// As [`joint_on`](Self::joint_on), for a joint's index and a side 0 or 1.
    #[inline]
    pub(crate) fn joint_on_at(&self, j: usize, side: usize) -> PointMotion {
        let jp = &self.plan.joints[j];
        self.at(jp.links[side], jp.local[side])
    }

    /// The motion of joint `j` as a point of link `link` (one of its two links).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`, `"link index"`) for `j` not below
    /// `plan.joint_names().len()` or `link` not below `plan.link_names().len()`;
    /// [`Error::Description`] naming both when the joint does not join link `link`.
    pub fn joint_index_on(&self, j: usize, link: usize) -> Result<PointMotion> {
        let j = self.plan.check_joint(j)?;
        let link = self.plan.check_link(link)?;
        let links = self.plan.joints[j].links;
        if !links.contains(&link) {
            return Err(Error::Description {
                item: format!("joint {}", self.plan.joint_names[j]),
                problem: format!(
                    "does not join link {} (it joins {} and {})",
                    self.plan.link_names[link],
                    self.plan.link_names[links[0]],
                    self.plan.link_names[links[1]]
                ),
            });
        }
        Ok(self.joint_on_link(j, link))
    }

    /// As [`joint_index_on`](Self::joint_index_on), for a joint's index and one of its links.
    #[inline]
    pub(crate) fn joint_on_link(&self, j: usize, link: usize) -> PointMotion {
        let side = usize::from(self.plan.joints[j].links[1] == link);
        self.joint_on_at(j, side)
    }

    /// The motion of the joint called `name` (for a prismatic joint, its point on the sliding
    /// link).
    ///
    /// # Errors
    /// An unknown name.
    pub fn joint(&self, name: &str) -> Result<PointMotion> {
        let j = self.plan.joint_index(name)?;
        Ok(self.joint_motion_at(j))
    }

    /// The motion of joint `j` (for a prismatic joint, its point on the sliding link).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn joint_motion(&self, j: usize) -> Result<PointMotion> {
        Ok(self.joint_motion_at(self.plan.check_joint(j)?))
    }

    /// As [`joint_motion`](Self::joint_motion), for an index known to be a joint's.
    #[inline]
    pub(crate) fn joint_motion_at(&self, j: usize) -> PointMotion {
        let side = match self.plan.joints[j].prismatic {
            Some((guide, _)) => 1 - guide,
            None => 0,
        };
        self.joint_on_at(j, side)
    }

    /// The motion of the named point `name`.
    ///
    /// # Errors
    /// An unknown name.
    pub fn point(&self, name: &str) -> Result<PointMotion> {
        Ok(self.point_motion_at(self.plan.point_index(name)?))
    }

    /// The motion of named point `k`.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"point index"`) for `k` not below `plan.point_names().len()`;
    /// [`Error::Description`] for a linkage without named points.
    pub fn point_motion(&self, k: usize) -> Result<PointMotion> {
        Ok(self.point_motion_at(self.plan.check_point(k)?))
    }

    /// As [`point_motion`](Self::point_motion), for an index known to be a named point's.
    #[inline]
    pub(crate) fn point_motion_at(&self, k: usize) -> PointMotion {
        let (link, local) = self.plan.point_local_at(k);
        self.at(link, local)
    }

    /// The sliding link, the guide's link and the guide's current unit direction of the
    /// prismatic joint `j` (zero direction for a revolute joint).
    fn slide_parts(&self, j: usize) -> (usize, usize, Vector2<f64>) {
        let jp = &self.plan.joints[j];
        let Some((g, offsets)) = jp.prismatic else {
            return (jp.links[0], jp.links[1], Vector2::zeros());
        };
        let guide = jp.links[g];
        (
            jp.links[1 - g],
            guide,
            unit(self.links[guide].angle + offsets[g]),
        )
    }

    /// The current unit direction of the guide of prismatic joint `j` (zero for a revolute
    /// joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn guide_direction(&self, j: usize) -> Result<Vector2<f64>> {
        Ok(self.guide_direction_at(self.plan.check_joint(j)?))
    }

    /// As [`guide_direction`](Self::guide_direction), for an index known to be a joint's.
    #[inline]
    pub(crate) fn guide_direction_at(&self, j: usize) -> Vector2<f64> {
        self.slide_parts(j).2
    }

    /// The slide of prismatic joint `j`: the sliding link's displacement along the guide from
    /// the reference pose, with its velocity and acceleration relative to the guide (zero for
    /// a revolute joint).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn slide_index(&self, j: usize) -> Result<Motion> {
        Ok(self.slide_at(self.plan.check_joint(j)?))
    }

    /// As [`slide_index`](Self::slide_index), for an index known to be a joint's.
    pub(crate) fn slide_at(&self, j: usize) -> Motion {
        let jp = &self.plan.joints[j];
        let Some((g, _)) = jp.prismatic else {
            return Motion::default();
        };
        let (_, guide, d) = self.slide_parts(j);
        let on_slider = self.joint_on_at(j, 1 - g);
        let on_guide = self.joint_on_at(j, g);
        let w = self.links[guide].omega;
        // r = s·d with d turning at ω: v_r = ṡ·d + s·ω·d⊥, a_r = (s̈ − s·ω²)·d + (…)·d⊥.
        let s = (on_slider.p - on_guide.p).dot(&d);
        let v = (on_slider.v - on_guide.v).dot(&d);
        let a = (on_slider.a - on_guide.a).dot(&d) + s * w * w;
        Motion::new(s, v, a)
    }

    /// The slide of the prismatic joint called `name`.
    ///
    /// # Errors
    /// An unknown name, or a revolute joint.
    pub fn slide(&self, name: &str) -> Result<Motion> {
        let j = self.plan.joint_index(name)?;
        if !self.plan.is_prismatic_at(j) {
            return Err(Error::Description {
                item: format!("joint {name}"),
                problem: "is not prismatic: it has no slide".to_owned(),
            });
        }
        Ok(self.slide_at(j))
    }

    /// The transmission angle μ of group `g` (in attachment order) at this position, rad in
    /// [0, π/2]: the acute angle between the force a group's driving link can pass on and the
    /// motion of the point it drives, complemented (μ = π/2 − the pressure angle). Engineers
    /// keep it above about 40° over the cycle; it vanishes at a dead point.
    ///
    /// - RRR: the angle between the lines of its two links at the inner joint (the coupler and
    ///   the rocker);
    /// - RRP: π/2 minus the angle between the rod and the guide (μ = 0 with the rod across the
    ///   guide);
    /// - PRP: the angle between the two guides; RPP: between the slide and the guide (the
    ///   force crosses each sliding pair along its normal);
    /// - RPR: π/2 always: the sliding pair pushes the cylinder across its axis, which is the
    ///   direction its point there moves in.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"group index"`) for `g` not below `plan.groups().len()`;
    /// [`Error::Description`] for a linkage without groups.
    pub fn transmission_angle(&self, g: usize) -> Result<f64> {
        let group = &self.plan.groups[self.plan.check_group(g)?];
        let (u2, u3) = (self.units[group.links[0]], self.units[group.links[1]]);
        let between = |a: Vector2<f64>, b: Vector2<f64>| cross(a, b).abs().atan2(a.dot(&b).abs());
        Ok(match group.kind {
            GroupKind::Rrr | GroupKind::Prp | GroupKind::Rpp => between(u2, u3),
            GroupKind::Rrp => std::f64::consts::FRAC_PI_2 - between(u2, u3),
            GroupKind::Rpr => std::f64::consts::FRAC_PI_2,
        })
    }

    /// The kinematic conditioning of every group in attachment order: sin(φ3 − φ2) for RRR,
    /// cos(φ2 − φ4) for RRP, l_EA (m) for RPR, sin(φg3 − φg2) for PRP and sin α for RPP.
    #[must_use]
    pub fn group_determinants(&self) -> &[f64] {
        &self.dets
    }

    // ---- kinetostatic results ----------------------------------------------------------

    /// The reaction in joint `j` (valid after [`Analysis::solve`]).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"joint index"`) for `j` not below `plan.joint_names().len()`.
    pub fn reaction_index(&self, j: usize) -> Result<Reaction> {
        Ok(self.reaction_at(self.plan.check_joint(j)?))
    }

    /// As [`reaction_index`](Self::reaction_index), for an index known to be a joint's.
    #[inline]
    pub(crate) fn reaction_at(&self, j: usize) -> Reaction {
        self.reactions[j]
    }

    /// The reaction in the joint called `name`, as the force of one of its links on the other.
    ///
    /// # Errors
    /// An unknown name.
    pub fn reaction(&self, name: &str) -> Result<Reaction> {
        Ok(self.reactions[self.plan.joint_index(name)?])
    }

    /// The balancing moment (crank) or force (slider) of the (first) input.
    #[must_use]
    pub fn balance(&self) -> Balance {
        self.balance
    }

    /// The balancing moment or force of the second input, for a linkage with two inputs
    /// (valid after [`Analysis::solve_inputs`]).
    #[must_use]
    pub fn second_balance(&self) -> Option<Balance> {
        self.second_balance
    }

    /// Each group's conditioning in the kinetostatics (the divisor of its closed form).
    #[must_use]
    pub fn conditioning(&self) -> &[Conditioning] {
        &self.conditioning
    }

    /// Every applied load (own inertia and weight, external) with the link it acts on.
    #[must_use]
    pub fn applied_loads(&self) -> &[(usize, Load)] {
        &self.applied
    }

    /// The drive's load on the input link: the balancing couple, or the balancing force.
    #[must_use]
    pub fn drive_load(&self) -> Load {
        drive_load(&self.plan.input, &self.balance)
    }

    /// The second drive's load on the second input link, for a linkage with two inputs.
    #[must_use]
    pub fn second_drive_load(&self) -> Option<Load> {
        match (&self.plan.second_input, &self.second_balance) {
            (Some((ip, _)), Some(b)) => Some(drive_load(ip, b)),
            _ => None,
        }
    }

    /// Every load on link `k` as a free body: applied loads, reactions of its joints, and
    /// the drive on the input link.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn free_body(&self, k: usize) -> Result<Vec<Load>> {
        Ok(self.free_body_at(self.plan.check_link(k)?))
    }

    /// As [`free_body`](Self::free_body), for an index known to be a link's.
    fn free_body_at(&self, k: usize) -> Vec<Load> {
        let mut all: Vec<Load> = self
            .applied
            .iter()
            .filter(|(l, _)| *l == k)
            .map(|(_, l)| *l)
            .collect();
        for (j, jp) in self.plan.joints.iter().enumerate() {
            if jp.links.contains(&k) {
                all.push(self.reactions[j].load_on_side(k));
            }
        }
        if k == self.plan.input_link() {
            all.push(self.drive_load());
        }
        if Some(k) == self.plan.second_input_link() {
            all.extend(self.second_drive_load());
        }
        all
    }

    /// How far link `k` is from equilibrium: the larger of |ΣF|/F_scale and |ΣM|/M_scale,
    /// with the scales the largest force and the largest moment (or force × arm).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"link index"`) for `k` not below `plan.link_names().len()`.
    pub fn residual(&self, k: usize) -> Result<f64> {
        Ok(self.residual_at(self.plan.check_link(k)?))
    }

    /// As [`residual`](Self::residual), for an index known to be a link's.
    fn residual_at(&self, k: usize) -> f64 {
        let all = self.free_body_at(k);
        let pole = self.links[k].origin.p;
        let sum = Load::sum_about(&all, pole);
        let fs = all.iter().map(|l| l.force.norm()).fold(0.0, f64::max);
        let arm = all
            .iter()
            .map(|l| (l.point - pole).norm())
            .fold(0.0, f64::max);
        let ms = all.iter().map(|l| l.moment.abs()).fold(fs * arm, f64::max);
        let rel = |r: f64, s: f64| if s > 0.0 { r / s } else { r };
        rel(sum.force.norm(), fs).max(rel(sum.moment.abs(), ms))
    }

    /// The worst [`Analysis::residual`] over the moving links.
    #[must_use]
    pub fn worst_residual(&self) -> f64 {
        (1..self.links.len())
            .map(|k| self.residual_at(k))
            .fold(0.0, f64::max)
    }

    /// The power of every applied load, W: Σ F·v + M·ω.
    fn powers(&self) -> (f64, f64) {
        self.applied.iter().fold((0.0, 0.0), |(s, a), (k, l)| {
            let link = &self.links[*k];
            let p = l.force.dot(&link.motion_of(l.point).v) + l.moment * link.omega;
            (s + p, a + p.abs())
        })
    }

    /// The balancing value by the chain and by the principle of virtual power. For a linkage
    /// with two inputs the comparison is of powers, W: the drives' Σ B_k·q̇_k against
    /// −Σ P_i of every applied load.
    ///
    /// # Errors
    /// [`Error::Singular`] when the input does not move (q̇ = 0).
    pub fn power_check(&self) -> Result<PowerCheck> {
        if let (Some(m), Some(b)) = (self.second_input, self.second_balance) {
            // Two inputs: the drives' power against the loads' power, W.
            let (sum, abs) = self.powers();
            let chain = self.balance.value * self.input.rate + b.value * m.rate;
            if !(chain.is_finite() && sum.is_finite()) {
                return Err(Error::NonFinite {
                    name: "virtual power",
                    value: sum,
                });
            }
            return Ok(PowerCheck {
                chain,
                virtual_power: -sum,
                scale: abs.max(chain.abs()),
            });
        }
        let q = self.input.rate;
        if q == 0.0 || !q.is_finite() {
            return Err(Error::Singular {
                what: "virtual power balance",
                measure: "input rate",
                value: q,
            });
        }
        let (sum, abs) = self.powers();
        let (vp, scale) = (-sum / q, abs / q.abs());
        if !(vp.is_finite() && scale.is_finite()) {
            return Err(Error::NonFinite {
                name: "virtual power",
                value: vp,
            });
        }
        Ok(PowerCheck {
            chain: self.balance.value,
            virtual_power: vp,
            scale: scale.max(self.balance.value.abs()),
        })
    }

    /// Whether the kinetostatics of this position has been solved.
    #[must_use]
    pub fn has_statics(&self) -> bool {
        self.statics_done
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

/// The load a drive exerts on its input link: the balancing couple, or the balancing force.
fn drive_load(ip: &InputPlan, b: &Balance) -> Load {
    match ip {
        InputPlan::Crank {
            drive: Drive::Coupling,
            ..
        } => Load::new(b.point, Vector2::zeros(), b.value),
        _ => Load::force_at(b.point, b.force),
    }
}

/// Adds `l` to the resultant `acc` (kept at its point).
fn add(acc: &mut Load, l: &Load) {
    acc.moment += l.moment + cross(l.point - acc.point, l.force);
    acc.force += l.force;
}

impl Plan {
    /// Analyses one position (allocating its buffers; see [`Plan::analyse_into`] for sweeps).
    ///
    /// # Errors
    /// As [`Analysis::solve`].
    pub fn analyse(&self, input: Motion) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve(input)?;
        Ok(a)
    }

    /// Analyses one position into existing buffers: no allocation. The buffers must have
    /// been made for this plan ([`Analysis::new`] with it, or a previous analysis of it).
    ///
    /// # Errors
    /// [`Error::Description`] for buffers made for another plan (they would be solved for
    /// theirs, not this one); as [`Analysis::solve`].
    pub fn analyse_into(&self, input: Motion, into: &mut Analysis<'_>) -> Result<()> {
        if !std::ptr::eq(into.plan, self) {
            return Err(Error::Description {
                item: "analysis buffers".to_owned(),
                problem: "were made for another plan: make them with Analysis::new(plan)"
                    .to_owned(),
            });
        }
        into.solve(input)
    }

    /// Analyses one position of a linkage with one or two inputs (one motion per input).
    ///
    /// # Errors
    /// As [`Analysis::solve_inputs`].
    ///
    /// # Examples
    /// The five-bar robot held still against its tool moment: both drives hold it.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let r = plan.reference_inputs();
    /// let a = plan.analyse_inputs(&[Motion::fixed(r[0]), Motion::fixed(r[1])])?;
    /// let (m1, m4) = (a.balance().value, a.second_balance().unwrap().value);
    /// assert!(m1.abs() > 0.0 && m4.abs() > 0.0);
    /// assert!(a.worst_residual() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn analyse_inputs(&self, inputs: &[Motion]) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve_inputs(inputs)?;
        Ok(a)
    }

    /// The kinematics alone at one position of a linkage with one or two inputs.
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics_inputs`].
    pub fn kinematics_inputs(&self, inputs: &[Motion]) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve_kinematics_inputs(inputs)?;
        Ok(a)
    }

    /// The kinematics alone at one position.
    ///
    /// # Errors
    /// As [`Analysis::solve_kinematics`].
    pub fn kinematics(&self, input: Motion) -> Result<Analysis<'_>> {
        let mut a = Analysis::new(self);
        a.solve_kinematics(input)?;
        Ok(a)
    }
}

/// The rates-only pass: new input rates at the positions of the last kinematic solve.
///
/// The velocity and acceleration problems of a group are linear in its unknown rates, with
/// the matrix of its position (the same 2×2 whose determinant is the group's conditioning).
/// Given the positions, each group's rates are a few dot products: no square root, no
/// `atan2`, no assembly test. The dynamics of a linkage with two inputs needs three rate
/// vectors at one position (its transfer functions); this pass makes the second and third
/// cost a fraction of a full solve.
impl Analysis<'_> {
    /// Velocities and accelerations of every link at the input motions `inputs`, whose
    /// values (φ or s) must be those of the last successful
    /// [`solve_kinematics_inputs`](Self::solve_kinematics_inputs) on these buffers: the
    /// positions are taken from it, only the rates are solved again.
    ///
    /// RRR, RRP and RPR groups are solved from their positions; PRP and RPP groups (solved by
    /// the general contour solver) and any group whose rates come out non-finite go through
    /// their full closed form, which reports the failure as a full solve would. When the
    /// values are not those of the last solve (a caller's mistake), the whole position is
    /// solved again.
    ///
    /// # Errors
    /// As [`solve_kinematics_inputs`](Self::solve_kinematics_inputs).
    pub(crate) fn solve_rates_inputs(&mut self, inputs: &[Motion]) -> Result<()> {
        let plan = self.plan;
        let same = |m: &Motion, last: &Motion| m.value.to_bits() == last.value.to_bits();
        let (input, second) = match (inputs, self.second_input, &plan.second_input) {
            ([i], None, None) if same(i, &self.input) => (*i, None),
            ([i, j], Some(last), Some((ip, _))) if same(i, &self.input) && same(j, &last) => {
                (*i, Some((*j, ip)))
            }
            _ => return self.solve_kinematics_inputs(inputs),
        };
        let rates_ok = |m: &Motion| {
            m.rate.is_finite()
                && m.accel.is_finite()
                && (plan.size * (m.rate * m.rate + m.accel.abs())).is_finite()
        };
        if !rates_ok(&input) || !second.as_ref().is_none_or(|(m, _)| rates_ok(m)) {
            // The full solve names the bad rate (or the overflow).
            return self.solve_kinematics_inputs(inputs);
        }
        self.statics_done = false;
        self.input = input;
        self.set_input_rates(&plan.input, input);
        if let Some((m, ip)) = second {
            self.set_input_rates(ip, m);
            self.second_input = Some(m);
        }
        for (g, group) in plan.groups.iter().enumerate() {
            if !self.group_rates(g, group) {
                self.solve_group_kinematics(g, group)?;
            }
        }
        Ok(())
    }

    /// The input link's motion at the rates of `m`, its position kept.
    fn set_input_rates(&mut self, ip: &InputPlan, m: Motion) {
        let k = ip.link();
        let link = &mut self.links[k];
        match *ip {
            InputPlan::Crank { .. } => {
                link.omega = m.rate;
                link.epsilon = m.accel;
            }
            InputPlan::Slider { .. } => {
                // The slider's direction, as `input_motion` made it (unit(angle)).
                let d = self.units[k];
                link.origin.v = m.rate * d;
                link.origin.a = m.accel * d;
            }
        }
    }

    /// Group `g`'s rates from its stored positions; `false` (nothing stored) for a PRP or RPP
    /// group or when a rate is not finite.
    fn group_rates(&mut self, g: usize, group: &Group) -> bool {
        let [l2, l3] = group.links;
        let [ka, kc] = group.known;
        let (u2, u3) = (self.units[l2], self.units[l3]);
        let a = self.at(ka, group.a_local);
        let (m2, m3) = match group.kind {
            GroupKind::Rrr => {
                // As `rrr_fast`, on r2 = B − A and r3 = B − C of the stored position.
                let c = self.at(kc, group.c_local);
                let (r2, r3) = (group.lengths[0] * u2, group.lengths[1] * u3);
                let (dv, da) = (c.v - a.v, c.a - a.a);
                let i_d = 1.0 / cross(r2, r3);
                let omega2 = dv.dot(&r3) * i_d;
                let omega3 = dv.dot(&r2) * i_d;
                let rhs = da + omega2 * omega2 * r2 - omega3 * omega3 * r3;
                let epsilon2 = rhs.dot(&r3) * i_d;
                let epsilon3 = rhs.dot(&r2) * i_d;
                (
                    LinkMotion {
                        origin: a,
                        angle: self.links[l2].angle,
                        omega: omega2,
                        epsilon: epsilon2,
                    },
                    LinkMotion {
                        origin: c,
                        angle: self.links[l3].angle,
                        omega: omega3,
                        epsilon: epsilon3,
                    },
                )
            }
            GroupKind::Rrp => {
                // As `rrp_fast`: the guide (of link `kc`, along the slider's direction u3)
                // through G, B = A + r2 on it at s = (B − G)·u3.
                let gp = self.at(kc, group.c_local);
                let guide = &self.links[kc];
                let (w4, e4) = (guide.omega, guide.epsilon);
                let (g, n) = (u3, perp(u3));
                let r2 = group.lengths[0] * u2;
                let (d, dv, da) = (gp.p - a.p, gp.v - a.v, gp.a - a.a);
                let s = (r2 - d).dot(&g);
                let i_d = 1.0 / r2.dot(&g);
                let rv = dv + (s * w4) * n;
                let omega2 = cross(g, rv) * i_d;
                let s_rate = -r2.dot(&rv) * i_d;
                let ra = da + (omega2 * omega2) * r2 + (2.0 * s_rate * w4 + s * e4) * n
                    - (s * w4 * w4) * g;
                let epsilon2 = cross(g, ra) * i_d;
                let b = PointMotion::new(
                    self.links[l3].origin.p,
                    a.v + omega2 * perp(r2),
                    a.a + epsilon2 * perp(r2) - omega2 * omega2 * r2,
                );
                (
                    LinkMotion {
                        origin: a,
                        angle: self.links[l2].angle,
                        omega: omega2,
                        epsilon: epsilon2,
                    },
                    LinkMotion {
                        origin: b,
                        angle: self.links[l3].angle,
                        omega: w4,
                        epsilon: e4,
                    },
                )
            }
            GroupKind::Rpr => {
                // As `rpr_fast`: the axis A→E of length l = the stored measure.
                let e = self.at(kc, group.c_local);
                let (u, l) = (u2, self.dets[g]);
                let n = perp(u);
                let (dv, da) = (e.v - a.v, e.a - a.a);
                let i_l = 1.0 / l;
                let l_rate = dv.dot(&u);
                let omega = dv.dot(&n) * i_l;
                let epsilon = (da.dot(&n) - 2.0 * l_rate * omega) * i_l;
                let link = |origin: PointMotion, angle: f64| LinkMotion {
                    origin,
                    angle,
                    omega,
                    epsilon,
                };
                (link(a, self.links[l2].angle), link(e, self.links[l3].angle))
            }
            GroupKind::Prp | GroupKind::Rpp => return false,
        };
        let finite = [m2, m3].iter().fold(true, |ok, m| {
            ok & [
                m.origin.v.x,
                m.origin.v.y,
                m.origin.a.x,
                m.origin.a.y,
                m.omega,
                m.epsilon,
            ]
            .iter()
            .fold(true, |ok, v| ok & v.is_finite())
        });
        if finite {
            self.links[l2] = m2;
            self.links[l3] = m3;
        }
        finite
    }

    /// Group `g` solved in full by its closed form (as in
    /// [`solve_kinematics_inputs`](Self::solve_kinematics_inputs)), the known links' motions
    /// already stored.
    #[inline]
    fn solve_group_kinematics(&mut self, g: usize, group: &Group) -> Result<()> {
        let [l2, l3] = group.links;
        let [ka, kc] = group.known;
        let a = self.at(ka, group.a_local);
        // Each arm also gives the links' unit vectors from the group's geometry (or a known
        // link's turned by a constant), never from the returned angles again.
        let t = self.turns[g];
        let (s2, s3, det, u2, u3) = match group.kind {
            GroupKind::Rrr => {
                let c = self.at(kc, group.c_local);
                let s = rrr_dyad(a, c, group.lengths[0], group.lengths[1], group.branch)
                    .map_err(within(&group.name))?;
                let (u2, u3) = (direction_of(s.b.p - a.p), direction_of(s.b.p - c.p));
                (s.link2, s.link3, s.det, u2, u3)
            }
            GroupKind::Rrp => {
                let guide = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
                let s = rrp_dyad(a, guide, group.lengths[0], group.branch)
                    .map_err(within(&group.name))?;
                let u3 = turn(self.units[kc], t[1]);
                (s.link2, s.link3, s.det, direction_of(s.b.p - a.p), u3)
            }
            GroupKind::Rpr => {
                let c = self.at(kc, group.c_local);
                let s = rpr_dyad(a, c).map_err(within(&group.name))?;
                let u = direction_of(c.p - a.p);
                (s.link2, s.link3, s.slide.value, u, -u)
            }
            GroupKind::Prp => {
                let g2 = self.guide_on(ka, group.a_local, group.guide_offsets[0]);
                let g3 = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
                let s = prp_dyad(g2, g3).map_err(within(&group.name))?;
                let (u2, u3) = (turn(self.units[ka], t[0]), turn(self.units[kc], t[1]));
                (s.link2, s.link3, s.det, u2, u3)
            }
            GroupKind::Rpp => {
                let g = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
                let s = rpp_dyad(a, g, group.slide_angle).map_err(within(&group.name))?;
                let u3 = turn(self.units[kc], t[1]);
                (s.link2, s.link3, s.det, turn(u3, t[2]), u3)
            }
        };
        self.put_link(l2, s2, u2);
        self.put_link(l3, s3, u3);
        self.dets[g] = det;
        Ok(())
    }
}
