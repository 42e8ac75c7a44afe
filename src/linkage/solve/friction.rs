//! The kinetostatics of one position with Coulomb friction in the joints: the same walk as
//! the frictionless statics (the groups from the last attached back to the input links),
//! each group solved by its friction block ([`kinetostatics::friction`]) with the relative
//! rates of the solved kinematics, and each crank by [`CrankFriction`] (coupling) or
//! [`GearFriction`] (gear pair), a slider input by its closed form with the guide's friction
//! ([`Analysis::slider_input_friction`]). Taken only when the plan has friction
//! ([`Plan::has_friction`](crate::linkage::Plan::has_friction)); the frictionless path is
//! untouched.
//!
//! Every reaction keeps the friction in its data: a hinge's [`Reaction::moment`] is its
//! friction couple (on `on` from `by`), a slide's force is the whole force (normal plus
//! friction) and its moment places the normal force, as in the frictionless solve.
//!
//! [`kinetostatics::friction`]: crate::kinetostatics::friction

use super::analysis::{Analysis, Balance, Reaction};
use super::state::within;
use super::statics::add;
use crate::error::{Error, Result};
use crate::kinetostatics::friction::{
    CrankFriction, Efficiency, GearFriction, JointFriction, PrpFriction, PrpJoints, PrpRates,
    RppFriction, RppJoints, RppRates, RprFriction, RprJoints, RprRates, RrpFriction, RrpJoints,
    RrpRates, RrrFriction, RrrJoints, RrrRates,
};
use crate::kinetostatics::{Conditioning, GearDrive, PrpDyad, RppDyad, RprDyad, RrpDyad, RrrDyad};
use crate::linkage::description::Drive;
use crate::linkage::handle::JointRef;
use crate::linkage::plan::{FrictionPlan, Group, GroupKind, InputPlan};
use crate::Load;
use nalgebra::Vector2;

/// The friction of the joints of one analysed position, with the iteration's totals.
#[derive(Debug, Clone, Default)]
pub(crate) struct FrictionState {
    /// Per joint: the friction load on the joint's reaction's `on` link from its `by` link
    /// (a couple for a hinge, a force along the slide for a slide), its pressure and the
    /// power lost.
    pub joints: Vec<JointFriction>,
    /// The Newton steps of every group's friction iteration (and the gear drive's
    /// fixed-point steps) at this position.
    pub iterations: usize,
}

impl FrictionState {
    pub(crate) fn new(joints: usize) -> Self {
        Self {
            joints: vec![NO_FRICTION; joints],
            iterations: 0,
        }
    }
}

/// The conditioning of a closed form that divides by nothing (a drive's balance).
const ONE: Conditioning = Conditioning {
    measure: 1.0,
    condition: 1.0,
};

/// A joint without friction.
const NO_FRICTION: JointFriction = JointFriction {
    load: 0.0,
    pressure: 0.0,
    power_lost: 0.0,
};

/// Names the linkage's joint in a block's self-locking error (the blocks name their joints
/// by their place in the dyad, in the order of `joints`).
fn name_joint<'a>(
    names: &'a [String],
    joints: [usize; 3],
    group: &'a str,
) -> impl Fn(Error) -> Error + 'a {
    move |e| match e {
        Error::In { part, source } if part.ends_with(" self-locks") => {
            let k = if part.starts_with("joint A") || part.starts_with("guide 2") {
                0
            } else if part.starts_with("joint B")
                || part.starts_with("the slide")
                || part.starts_with("the slot")
            {
                1
            } else {
                2
            };
            // The block's own labels ("joint B (links 2 and 3)") name the dyad's places, not
            // the user's joints: say the place in words, beside the user's joint name.
            let place = if part.starts_with("the slide") || part.starts_with("the slot") {
                "the dyad's slide"
            } else if part.starts_with("guide 2") {
                "the dyad's guide"
            } else {
                [
                    "the dyad's first outer joint",
                    "the dyad's middle joint",
                    "the dyad's second outer joint",
                ][k]
            };
            Error::In {
                part: format!("{group}: joint {} self-locks ({place})", names[joints[k]]),
                source,
            }
        }
        other => within(group)(other),
    }
}

impl Analysis<'_> {
    /// The statics with friction: as [`solve_statics`](Self::solve_statics), each group
    /// and each drive by its friction block.
    pub(super) fn solve_friction_statics(&mut self, fp: &[FrictionPlan]) -> Result<()> {
        let plan = self.k.plan;
        for (k, acc) in self.acc.iter_mut().enumerate() {
            *acc = Load::zero(self.k.kin.links[k].origin.p);
        }
        for &(k, l) in &self.applied {
            add(&mut self.acc[k], &l);
        }
        self.friction.iterations = 0;
        for (g, group) in plan.chain.groups.iter().enumerate().rev() {
            self.friction_group(g, group, fp)?;
        }
        self.balances[0] = self.friction_drive(&plan.chain.input, fp)?;
        if let Some((ip, _)) = &plan.chain.second_input {
            self.balances[1] = self.friction_drive(ip, fp)?;
        }
        Ok(())
    }

    /// The velocity of link `x` relative to the other link of the prismatic joint `j`,
    /// along the unit direction `u` (parallel to the joint's guide).
    pub(super) fn relative_slide(&self, j: usize, x: usize, u: Vector2<f64>) -> f64 {
        let pose = self.pose();
        let (slider, _, d) = pose.slide_parts(j);
        let v = pose.slide_at(j).rate * d.dot(&u);
        if slider == x {
            v
        } else {
            -v
        }
    }

    #[allow(clippy::too_many_lines)]
    fn friction_group(&mut self, g: usize, group: &Group, fp: &[FrictionPlan]) -> Result<()> {
        if let Some(t) = &group.triad {
            return self.friction_triad(g, group, t, fp);
        }
        if let Some(gp) = &group.general {
            return self.friction_general(g, group, gp, fp);
        }
        let plan = self.k.plan;
        let [l2, l3] = group.links;
        let [ja, jb, jc] = group.joints;
        let [ka, kc] = group.known;
        let kin = &self.k.kin;
        let w = |k: usize| kin.links[k].omega;
        let a = kin.links[l2].origin.p;
        let (load2, load3) = (self.acc[l2], self.acc[l3]);
        let named = name_joint(&plan.chain.joint_names, group.joints, &group.name);
        let ((forces, couples, fr), at, cond, conv) = match group.kind {
            // A plan's triad and general group always carry their plans (solved above).
            GroupKind::Triad | GroupKind::General => {
                return Err(crate::Error::Description {
                    item: group.name.clone(),
                    problem: "a group above the 2nd class without its plan".to_owned(),
                });
            }
            GroupKind::Rrr => {
                let b = self.pose().joint_position_on(jb, l2);
                let c = kin.links[l3].origin.p;
                let dyad = RrrDyad {
                    a,
                    b,
                    c,
                    load2,
                    load3,
                };
                let r = RrrFriction {
                    dyad,
                    joints: RrrJoints {
                        a: fp[ja].hinge,
                        b: fp[jb].hinge,
                        c: fp[jc].hinge,
                    },
                    rates: RrrRates {
                        omega1: w(ka),
                        omega2: w(l2),
                        omega3: w(l3),
                        omega4: w(kc),
                    },
                }
                .solve()
                .map_err(named)?;
                (
                    r.by_joint(),
                    [(ka, l2, a), (l2, l3, b), (kc, l3, c)],
                    r.conditioning,
                    r.convergence,
                )
            }
            GroupKind::Rrp => {
                let b = kin.links[l3].origin.p;
                let guide = kin.units[l3];
                let slide = self.relative_slide(jc, l3, guide);
                let dyad = RrpDyad {
                    a,
                    b,
                    guide,
                    load2,
                    load3,
                };
                let r = RrpFriction {
                    dyad,
                    joints: RrpJoints {
                        a: fp[ja].hinge,
                        b: fp[jb].hinge,
                        guide: fp[jc].slide,
                    },
                    rates: RrpRates {
                        omega1: w(ka),
                        omega2: w(l2),
                        omega4: w(kc),
                        slide,
                    },
                }
                .solve()
                .map_err(named)?;
                (
                    r.by_joint(),
                    [(ka, l2, a), (l2, l3, b), (kc, l3, b)],
                    r.conditioning,
                    r.convergence,
                )
            }
            GroupKind::Rpr => {
                let c = kin.links[l3].origin.p;
                let axis = kin.units[l2];
                let slide = self.relative_slide(jb, l2, axis);
                let dyad = RprDyad {
                    a,
                    e: c,
                    axis,
                    load2,
                    load3,
                };
                let r = RprFriction {
                    dyad,
                    joints: RprJoints {
                        a: fp[ja].hinge,
                        slide: fp[jb].slide,
                        e: fp[jc].hinge,
                    },
                    rates: RprRates {
                        omega1: w(ka),
                        omega: w(l2),
                        omega4: w(kc),
                        slide,
                    },
                }
                .solve()
                .map_err(named)?;
                (
                    r.by_joint(),
                    [(ka, l2, a), (l3, l2, a), (kc, l3, c)],
                    r.conditioning,
                    r.convergence,
                )
            }
            GroupKind::Prp => {
                let b = kin.links[l2].origin.p;
                let (guide2, guide3) = (kin.units[l2], kin.units[l3]);
                let slide2 = self.relative_slide(ja, l2, guide2);
                let slide3 = self.relative_slide(jc, l3, guide3);
                let dyad = PrpDyad {
                    b,
                    guide2,
                    guide3,
                    load2,
                    load3,
                };
                let r = PrpFriction {
                    dyad,
                    joints: PrpJoints {
                        guide2: fp[ja].slide,
                        b: fp[jb].hinge,
                        guide3: fp[jc].slide,
                    },
                    rates: PrpRates {
                        omega1: w(ka),
                        omega4: w(kc),
                        slide2,
                        slide3,
                    },
                }
                .solve()
                .map_err(named)?;
                (
                    r.by_joint(),
                    [(ka, l2, b), (l2, l3, b), (kc, l3, b)],
                    r.conditioning,
                    r.convergence,
                )
            }
            GroupKind::Rpp => {
                let b = kin.links[l3].origin.p;
                let (guide, slot) = (kin.units[l3], kin.units[l2]);
                let slot_rate = self.relative_slide(jb, l2, slot);
                let slide = self.relative_slide(jc, l3, guide);
                let dyad = RppDyad {
                    a,
                    b,
                    guide,
                    slot,
                    load2,
                    load3,
                };
                let r = RppFriction {
                    dyad,
                    joints: RppJoints {
                        a: fp[ja].hinge,
                        slot: fp[jb].slide,
                        guide: fp[jc].slide,
                    },
                    rates: RppRates {
                        omega1: w(ka),
                        omega4: w(kc),
                        slot: slot_rate,
                        slide,
                    },
                }
                .solve()
                .map_err(named)?;
                (
                    r.by_joint(),
                    [(ka, l2, a), (l3, l2, a), (kc, l3, b)],
                    r.conditioning,
                    r.convergence,
                )
            }
        };
        // Each reaction of its first link on its second (as the block gives it) at its point.
        let [ra, rb, rc] = [0, 1, 2].map(|k| {
            let (by, on, point) = at[k];
            Reaction::new(by, on, forces[k], point, couples[k])
        });
        add(&mut self.acc[ka], &ra.load_on_side(ka));
        add(&mut self.acc[kc], &rc.load_on_side(kc));
        self.reactions[ja] = ra;
        self.reactions[jb] = rb;
        self.reactions[jc] = rc;
        self.friction.joints[ja] = fr[0];
        self.friction.joints[jb] = fr[1];
        self.friction.joints[jc] = fr[2];
        self.friction.iterations += conv.iterations;
        self.conditioning[g] = cond;
        Ok(())
    }

    /// The balancing moment or force of one input link with the friction of its frame pin
    /// or guide.
    fn friction_drive(&mut self, ip: &InputPlan, fp: &[FrictionPlan]) -> Result<Balance> {
        let plan = self.k.plan;
        let link = ip.link();
        let load = self.acc[link];
        let part = &plan.chain.link_names[link];
        let (joint, pivot, drive) = match *ip {
            InputPlan::Crank {
                joint,
                pivot,
                drive,
                ..
            } => (joint, pivot, drive),
            InputPlan::Slider { joint, angle, .. } if fp[joint].slide.f != 0.0 => {
                return self.slider_input_friction(joint, link, angle, fp[joint].slide);
            }
            // A slider input on a frictionless guide: the frictionless closed form.
            InputPlan::Slider { .. } => return self.solve_drive(ip),
        };
        let omega1 = self.k.kin.links[link].omega;
        let pin = fp[joint].hinge;
        let (balance, r01, friction) = match drive {
            Drive::Coupling => {
                let b = CrankFriction {
                    o1: pivot,
                    pin,
                    omega1,
                }
                .solve(&[load])
                .map_err(within(part))?;
                let balance = Balance {
                    value: b.balancing_moment,
                    force: Vector2::zeros(),
                    point: pivot,
                    conditioning: ONE,
                };
                (balance, b.r01, b.pin)
            }
            Drive::Gear {
                pitch_radius,
                pitch_angle,
                pressure_angle,
            } => {
                let d = GearDrive::at_angle(pivot, pitch_radius, pitch_angle, pressure_angle);
                let b = GearFriction {
                    drive: d,
                    pin,
                    omega1,
                }
                .solve(&[load])
                .map_err(|e| match e {
                    Error::In { part: p, source } if p.contains("self-locks") => Error::In {
                        part: format!("{part}: joint {} self-locks", plan.chain.joint_names[joint]),
                        source,
                    },
                    other => within(part)(other),
                })?;
                self.friction.iterations += b.iterations;
                let balance = Balance {
                    value: b.balancing_moment,
                    force: b.force,
                    point: d.pitch_point,
                    conditioning: ONE,
                };
                (balance, b.r01, b.pin)
            }
        };
        self.reactions[joint] = Reaction::new(0, link, r01, pivot, friction.load);
        self.friction.joints[joint] = friction;
        Ok(balance)
    }

    /// The balancing force of a slider input on a guide of the frame with friction.
    ///
    /// The balancing force acts along the guide d and the friction along the guide's line
    /// through the pair's reference point o (the joint on the slider), so neither has a
    /// moment about o, and the slider's equilibrium across the guide and about o gives the
    /// normal reaction without friction: N = −F·n and its moment about o, K = −(M + (P − o)×F)
    /// (F, M the slider's load reduced to P, n = d turned +90°). The friction force on the
    /// slider is then −f·ψ(N, K)·sgn(v)·d (ψ = |N|, or |N1| + |N2| for a cocked slider, v the
    /// slider's rate along d) and the balancing force along d is B = −F·d + f·ψ·sgn(v): a
    /// closed form, no iteration (a slider input cannot self-lock: its drive is along its
    /// guide).
    fn slider_input_friction(
        &mut self,
        joint: usize,
        link: usize,
        angle: f64,
        slide: crate::kinetostatics::friction::Slide,
    ) -> Result<Balance> {
        let plan = self.k.plan;
        let part = &plan.chain.link_names[link];
        let load = self.acc[link];
        let d = crate::angle::unit(angle);
        let n = Vector2::new(-d.y, d.x);
        let o = self.pose().joint_position_on(joint, link);
        let arm = load.point - o;
        let normal = -load.force.dot(&n);
        let moment = -(load.moment + arm.x * load.force.y - arm.y * load.force.x);
        let names = ["f", "length", "centre"];
        let (f, law) = slide.checked(names).map_err(within(part))?;
        let pressure = law.of(normal, moment);
        let v = self.relative_slide(joint, link, d);
        let signed = f * crate::kinetostatics::friction::sign(v);
        let friction = JointFriction::new(signed, pressure, v);
        let fb = -load.force.dot(&d) - friction.load;
        let all = [fb, normal, moment, friction.load];
        if !all.iter().all(|x| x.is_finite()) {
            return Err(within(part)(Error::NonFinite {
                name: "balancing force",
                value: fb,
            }));
        }
        self.reactions[joint] = Reaction::new(0, link, normal * n + friction.load * d, o, moment);
        self.friction.joints[joint] = friction;
        Ok(Balance {
            value: fb,
            force: fb * d,
            point: load.point,
            conditioning: ONE,
        })
    }

    /// The friction in a joint at this position: the friction load of the reaction's `by`
    /// link on its `on` link ([`Analysis::reaction`]) — a couple (N·m) in a hinge, a force
    /// along the slide (N) in a sliding pair — its pressure (|R|, or |N| or |N1| + |N2|) and
    /// the power it takes, W (≥ 0). All zero without friction; at rest (no relative motion)
    /// a joint has no friction.
    ///
    /// # Errors
    /// As [`Plan::joint_id`](crate::linkage::Plan::joint_id).
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Friction, Plan};
    /// let mut four_bar = bundled::four_bar();
    /// four_bar.friction = Some(Friction::pin(0.15, 0.01));
    /// let plan = Plan::new(&four_bar)?;
    /// let a = plan.analyse(Motion::turning(1.0, 10.0))?;
    /// let b = a.friction("B")?;
    /// assert!(b.power_lost > 0.0);
    /// assert!((b.load.abs() - 0.0015 * a.reaction("B")?.force.norm()).abs() < 1e-9);
    /// let e = a.efficiency()?;
    /// assert!((e.drive - e.useful - a.lost_power()).abs() < 1e-9 * e.drive.abs());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn friction(&self, joint: impl JointRef) -> Result<JointFriction> {
        let j = self.k.plan.chain.joint(joint)?;
        Ok(self.friction.joints.get(j).copied().unwrap_or(NO_FRICTION))
    }

    /// Σ P_lost, the power lost in every joint at this position, W (0 without friction).
    #[must_use]
    pub fn lost_power(&self) -> f64 {
        self.friction.joints.iter().map(|f| f.power_lost).sum()
    }

    /// The Newton steps the friction took at this position (every group's, and a gear
    /// drive's), 0 without friction.
    #[must_use]
    pub fn friction_iterations(&self) -> usize {
        self.friction.iterations
    }

    /// The drives' power at this position, W: Σ B_k·q̇_k (the balancing moment times the
    /// crank's ω, or the balancing force times the slider's rate).
    #[must_use]
    pub fn drive_power(&self) -> f64 {
        let kin = &self.k.kin;
        let mut p = self.balances[0].value * kin.input.rate;
        if let Some(m) = kin.second_input {
            p += self.balances[1].value * m.rate;
        }
        p
    }

    /// The instantaneous power balance: P_drive, Σ P_lost, P_useful = P_drive − Σ P_lost and
    /// η = P_useful / P_drive ([`Efficiency`]).
    ///
    /// What counts as useful: the power taken by every applied load — the described
    /// external loads (resistances, forces, moments, an indicator diagram, a user's loads)
    /// and the links' weights and inertia loads — so P_useful = −Σ P_loads. Over a steady
    /// cycle the weights' and the inertia loads' work is zero, and the cycle efficiency
    /// ([`Plan::cycle_efficiency`](crate::linkage::Plan::cycle_efficiency)) is the work of the
    /// external loads over the drive's.
    ///
    /// # Errors
    /// As [`Efficiency::new`] (a non-finite power).
    pub fn efficiency(&self) -> Result<Efficiency> {
        Efficiency::new(self.drive_power(), self.lost_power())
    }
}

impl crate::linkage::plan::Plan {
    /// The cycle efficiency over one steady turn of the crank: the works of the drive, of
    /// the friction and of the loads from `inputs`, the positions of one full turn in the
    /// order the crank reaches them (for example a [`Course`](crate::linkage::Course)'s
    /// inputs with [`Sweep::Turn`](crate::linkage::Sweep::Turn), their angles wrapped or
    /// not), the last joined back to the first a turn later. Each work W = ∫ P dt = ∫ (P/q̇) dq by the trapezoid in the
    /// crank's angle q: the drive's work is ∫ M_b dq. The result is an [`Efficiency`] of
    /// works, J: `drive`, `lost`, `useful` = drive − lost, and η = useful/drive. Over a
    /// steady cycle the weights' and the inertia loads' works vanish (up to the
    /// trapezoid's error), so the useful work is the external loads' (the resistances').
    ///
    /// # Errors
    /// [`Error::Description`] for a linkage of two inputs or a slider input;
    /// [`Error::OutOfRange`] for fewer than 2 positions; [`Error::Singular`] for a position
    /// where the crank stands still (q̇ = 0); the errors of [`Solver::analyse`](super::Solver::analyse).
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Course, Friction, Plan};
    /// let mut four_bar = bundled::four_bar();
    /// four_bar.friction = Some(Friction::pin(0.1, 0.01));
    /// let plan = Plan::new(&four_bar)?;
    /// let course = Course::new(&plan, None, 360, 10.0)?;
    /// let e = plan.cycle_efficiency(&course.inputs)?;
    /// assert!(e.lost > 0.0 && e.eta.unwrap() < 1.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn cycle_efficiency(&self, inputs: &[crate::kinematics::Motion]) -> Result<Efficiency> {
        if self.chain.second_input.is_some() || !self.input_is_crank() {
            return Err(crate::linkage::plan::bad(
                "cycle efficiency",
                "needs one crank input (a linkage of two inputs or a slider input has no turn)",
            ));
        }
        crate::linkage::handle::index_in("positions", "positions", 1, inputs.len())?;
        let mut solver = self.solver();
        // Per position: the crank angle and the drive's, the friction's and the loads'
        // powers over q̇.
        let mut rows = Vec::with_capacity(inputs.len() + 1);
        for &m in inputs {
            let a = solver.analyse(m)?;
            let q = a.k.kin.input.rate;
            if q == 0.0 || !q.is_finite() {
                return Err(Error::Singular {
                    what: "cycle efficiency",
                    measure: "input rate",
                    value: q,
                });
            }
            rows.push([m.value, a.balances[0].value, a.lost_power() / q]);
        }
        let first = rows[0];
        let turn = std::f64::consts::TAU * inputs[0].rate.signum();
        rows.push([first[0] + turn, first[1], first[2]]);
        let (mut drive, mut lost) = (0.0, 0.0);
        for w in rows.windows(2) {
            // The angles may be wrapped to [0, 2π): each step in the turn's direction.
            let s = turn.signum();
            let dq = ((w[1][0] - w[0][0]) * s).rem_euclid(std::f64::consts::TAU) * s;
            drive += 0.5 * (w[0][1] + w[1][1]) * dq;
            lost += 0.5 * (w[0][2] + w[1][2]) * dq;
        }
        Efficiency::new(drive, lost)
    }
}
