//! Stops and reversals: the velocity-sign switches of a described machine (see
//! [`LagrangeSystem::switches`](crate::dynamics::LagrangeSystem::switches)), the rates at
//! which its resistances and its joints' friction jump, and the loads weighed where one of
//! them reaches zero.
//!
//! With one input every resistance's and every joint's rate is q̇₁ times a transfer
//! function: one switch, q̇₁, for all of them, weighed on the input.
//!
//! With two inputs each resistance (a resisting couple on a link, a resisting force in a
//! prismatic joint) is its own switch: its rate σ = c(q)·q̇, with c the rate's first-order
//! transfer functions. Where σ reaches zero, the load μ (N·m on the link, N along the slide)
//! that holds it there follows from the equation of motion with the resistance as the
//! generalized force μ·c: A·q̈ = Q̃ − Γ(q, q̇) − B·q̇ + μ·c, where Q̃ holds every other force.
//! With q̈_free the accelerations at μ = 0, σ̇ = c·q̈ + q̇ᵀ·H·q̇ = σ̇_free + μ·(c·A⁻¹·c), H
//! the rate's second-order transfer functions; σ̇ = 0 needs μ = −σ̇_free/(c·A⁻¹·c). The load
//! that drives σ, which the resistance must balance, is −μ: the switch's drive. When the
//! resistance holds it the run ends ([`Outcome::Stuck`](crate::dynamics::Outcome::Stuck)):
//! the resisted link stops turning (or the slide stops sliding) while the machine may still
//! move with its other freedom, a motion with that rate held that is not modelled. Otherwise
//! the motion goes on with σ of the drive's sign.
//!
//! # An input's joint friction with two inputs
//! The friction in an input's own joint (a crank's pivot on the frame, an input slider's
//! slide) is a switch too, after the resistances: its rate is the input's, σ = cₖ·q̇ₖ
//! (cₖ = ±1 for a direct crank). Where q̇ₖ reaches zero (that input stops while the other
//! may move on), the friction couple there is anything within ±L, L = ρ·|R| (f·|N| for a
//! slide), and the run weighs it as a resistance: held, q̈ₖ = 0 and the couple μ holding
//! it follows from A·q̈ = b + Q_f(q̈) + μ·eₖ with b = Q − Γ − B·q̇ at q̇ₖ = 0. The other
//! joints' friction Q_f depends on the reactions and so on q̈: the pair (q̈, μ) is the fixed
//! point q̈ = A⁻¹·(b + Q_f(q̈) + μ·eₖ), μ = −[A⁻¹·(b + Q_f)]ₖ / (A⁻¹)ₖₖ, iterated to
//! [`FRICTION_TOLERANCE`](super::FRICTION_TOLERANCE) like the free motion's. The limits L±
//! are the generalized friction along σ that sets in when σ = ±10⁻²⁰⁰ at the held motion
//! (Q_f of the friction statics there less Q_f at σ = 0): with the other input moving, only
//! the input's own joint starts to slide, L = ρ·|R| of its reaction; at a whole rest
//! (q̇ = 0) every joint the input moves starts with it, and L± is their friction reduced to
//! the input at the static reactions, as for one input. The machine sticks when
//! −L₋ ≤ drive ≤ L₊ (drive = −μ/cₖ, along σ); else it breaks away with q̇ₖ of the drive's
//! sign. Where it sticks while the other input moves, the run goes on with input k held
//! (q̇ₖ = 0, q̈ₖ = 0, this switch's coordinate: [`LagrangeSystem::switch_holds`]; the held
//! motion's terms, the other joints' friction solved with q̈ₖ = 0, are
//! [`LagrangeSystem::held_terms`]) and releases it where the drive reaches ±L, a located
//! event. The other joints' reversals are located as kinks. A machine at a whole rest is
//! weighed at every such switch, each with the other input left free: it stays at rest (the
//! run ends stuck: its loads do not change with time) when every one holds; else those that
//! break away go their drive's way and the motion goes on, an input whose friction holds it
//! held, weighed again as the others start to move (their rates a vanishing amount their
//! way, so that the joints they set sliding have their friction).

use nalgebra::Vector2;

use super::friction::{has_friction, FRICTION_BUDGET, FRICTION_TOLERANCE};
use super::system::LinkageSystem;
use super::transfer::Transfer;
use crate::dynamics::{
    accelerations, christoffel_terms, kink_slots, LagrangeSystem, LagrangeTerms, SwitchLoads,
};
use crate::error::{computed, Error, Result};
use crate::linkage::plan::{InputPlan, LoadPlan};

/// A resistance of a machine with two inputs: its rate σ = c·q̇ and what it opposes.
struct Resisted {
    /// The first-order transfer functions ∂σ/∂q̇ₖ.
    c: Vector2<f64>,
    /// σ̇ of the unit motions q̇ = e₁, e₂, (1, 1) at q̈ = 0: the quadratic form q̇ᵀ·H·q̇ at
    /// those three rates.
    second: [f64; 3],
    forward: f64,
    backward: f64,
    what: &'static str,
    unit: &'static str,
}

impl Resisted {
    /// The resistance `lp` (a [`LoadPlan::Turning`] or [`LoadPlan::Sliding`]) at the
    /// position of `tr`, solved for two inputs.
    fn new(tr: &Transfer<'_>, lp: &LoadPlan) -> Option<Self> {
        match *lp {
            LoadPlan::Turning {
                link,
                forward,
                backward,
            } => Some(Self::turning(
                tr,
                link,
                [forward, backward],
                "resisted link",
            )),
            LoadPlan::Sliding {
                joint,
                forward,
                backward,
                ..
            } => Some(Self::sliding(
                tr,
                joint,
                [forward, backward],
                "resisted slide",
            )),
            _ => None,
        }
    }

    /// The rate ω of `link` resisted by `[forward, backward]` N·m.
    fn turning(tr: &Transfer<'_>, link: usize, limits: [f64; 2], what: &'static str) -> Self {
        Self {
            c: Vector2::new(tr.omega(0, link), tr.omega(1, link)),
            second: [0, 1, 2].map(|s| tr.link(s, link).epsilon),
            forward: limits[0],
            backward: limits[1],
            what,
            unit: "N·m",
        }
    }

    /// The sliding rate of the prismatic `joint` resisted by `[forward, backward]` N.
    fn sliding(tr: &Transfer<'_>, joint: usize, limits: [f64; 2], what: &'static str) -> Self {
        let (_, guide, d) = tr.slide_parts(joint);
        // σ = (v_on − v_guide)·d with d turning with the guide at its ω:
        // σ̇ = (a_on − a_guide)·d + ω_guide·(v_on − v_guide)·d⊥.
        let across = Vector2::new(-d.y, d.x);
        let second = [0, 1, 2].map(|s| {
            let [on, g] = tr.slide_points(s, joint);
            (on.a - g.a).dot(&d) + tr.omega(s, guide) * (on.v - g.v).dot(&across)
        });
        Self {
            c: Vector2::new(tr.slide_rate(0, joint, d), tr.slide_rate(1, joint, d)),
            second,
            forward: limits[0],
            backward: limits[1],
            what,
            unit: "N",
        }
    }

    /// q̇ᵀ·H·q̇ from the form's values at e₁, e₂ and (1, 1).
    fn velocity_term(&self, qd: &Vector2<f64>) -> f64 {
        let [a, b, ab] = self.second;
        a * qd[0] * qd[0] + (ab - a - b) * qd[0] * qd[1] + b * qd[1] * qd[1]
    }

    /// The resistance's generalized force while σ has the sign of `direction` (zero for 0).
    fn force(&self, direction: f64) -> Vector2<f64> {
        let m = if direction > 0.0 {
            -self.forward
        } else if direction < 0.0 {
            self.backward
        } else {
            0.0
        };
        m * self.c
    }
}

impl LinkageSystem {
    /// The resistances among the loads, in the plan's order.
    fn resistances(&self) -> impl Iterator<Item = &LoadPlan> {
        self.plan()
            .loads
            .iter()
            .filter(|l| matches!(l, LoadPlan::Turning { .. } | LoadPlan::Sliding { .. }))
    }

    /// The machine's velocity-sign switches ([`LagrangeSystem::switches`](
    /// crate::dynamics::LagrangeSystem::switches)): with one input, one (the input's rate
    /// q̇₁) when a resistance is among its loads or a joint has friction, none otherwise;
    /// with two inputs, one per resistance and then one per input whose own joint has
    /// friction (see the [module docs](self)).
    pub(super) fn input_switches(&self) -> usize {
        if self.dof() == 1 {
            usize::from(self.resistances().next().is_some() || self.has_joint_friction())
        } else {
            self.resistances().count() + self.held_inputs().count()
        }
    }

    /// The inputs of a machine with two inputs whose own joint (a crank's pivot, an input
    /// slider's slide) has friction: (the input, its link, its joint).
    fn held_inputs(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        let plan = self.plan();
        plan.chain
            .inputs()
            .enumerate()
            .filter(move |_| plan.input_count() == 2)
            .map(|(k, ip)| match *ip {
                InputPlan::Crank { link, joint, .. } | InputPlan::Slider { link, joint, .. } => {
                    (k, link, joint)
                }
            })
            .filter(move |&(_, _, j)| has_friction(plan, j))
    }

    /// Switch `i`'s resistance for a machine with two inputs, at the position of `tr`.
    /// For an input's joint friction (limits zero: see
    /// [`joint_stop_loads`](Self::joint_stop_loads)), also the input and the joint.
    fn resisted(&self, tr: &Transfer<'_>, i: usize) -> Result<(Resisted, Option<[usize; 2]>)> {
        let n = self.resistances().count();
        if i < n {
            return self
                .resistances()
                .nth(i)
                .and_then(|lp| Resisted::new(tr, lp))
                .map(|r| (r, None))
                .ok_or_else(|| self.no_switch(i));
        }
        let (k, link, joint) = self
            .held_inputs()
            .nth(i - n)
            .ok_or_else(|| self.no_switch(i))?;
        let what = "input joint with friction";
        let r = if self.plan().is_prismatic_at(joint) {
            Resisted::sliding(tr, joint, [0.0; 2], what)
        } else {
            Resisted::turning(tr, link, [0.0; 2], what)
        };
        Ok((r, Some([k, joint])))
    }

    fn no_switch(&self, i: usize) -> Error {
        Error::OutOfRange {
            name: "switch index",
            value: i as f64,
            min: 0.0,
            max: self.input_switches() as f64 - 1.0,
            ends: crate::Ends::Closed,
        }
    }

    /// The switch speeds into `out` (one entry per switch): q̇₁ with one input; each
    /// resistance's rate c·q̇ with two.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] when `out` has not one entry per switch; the kinematics' errors.
    pub(super) fn input_switch_speeds(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        kink_slots(out, self.input_switches())?;
        if self.dof() == 1 {
            out.fill(qd[0]);
            return Ok(());
        }
        if out.is_empty() {
            return Ok(());
        }
        let tr = Transfer::new(self.plan(), 2, q)?;
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.resisted(&tr, i)?.0.c.dot(qd);
        }
        Ok(())
    }

    /// The loads along switch `i` where its speed vanishes ([`SwitchLoads`]).
    ///
    /// With one input, at rest at `q`: the drive is Q₁ at q̇ = 0, where every resistance is
    /// zero (motor, gravity, the other loads); the breakaway loads are the resistances
    /// reduced to the input, Q₁ at rest minus Q₁ at a vanishing rate each way (10⁻²⁰⁰: the
    /// resistances' magnitudes do not depend on the speed, and every smooth load changes by
    /// nothing there). With two inputs, at the state (t, q, q̇): the load that drives the
    /// resisted rate (see the [module docs](self)) and the resistance's magnitudes.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a switch that does not exist; [`Error::Singular`] when the
    /// resisted rate does not move with the inputs at this position (c·A⁻¹·c = 0); as
    /// [`split_terms`](Self::split_terms) and [`accelerations`].
    pub(super) fn input_switch_loads(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<SwitchLoads> {
        if i >= self.input_switches() {
            return Err(self.no_switch(i));
        }
        if self.dof() == 2 {
            return self.resistance_loads(i, t, q, qd);
        }
        const TINY: f64 = 1e-200;
        // The loads and the joints' friction (zero at rest).
        let resisting = |t: &super::Terms| t.loads[0] + t.friction[0];
        let at = |rate: f64| self.split_terms(q, &Vector2::new(rate, 0.0));
        let (rest, forward, backward) = (at(0.0)?, at(TINY)?, at(-TINY)?);
        let (what, unit) = if self.plan().input_is_crank() {
            ("crank", "N·m")
        } else {
            ("input slider", "N")
        };
        Ok(SwitchLoads {
            what,
            unit,
            drive: rest.forces()[0],
            forward: (resisting(&rest) - resisting(&forward)).max(0.0),
            backward: (resisting(&backward) - resisting(&rest)).max(0.0),
        })
    }

    /// A resistance's loads for a machine with two inputs (see the [module docs](self)).
    fn resistance_loads(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<SwitchLoads> {
        let (r, held) = self.resisted(&Transfer::new(self.plan(), 2, q)?, i)?;
        if let Some([k, joint]) = held {
            return self.joint_stop_loads(&r, k, joint, t, q, qd);
        }
        let singular = |value: f64| Error::Singular {
            what: "a resistance's stop",
            measure: "c·A⁻¹·c, the mobility of the resisted rate (it does not move with the \
                      inputs at this position)",
            value,
        };
        let a = self.inertia(q)?.cholesky().ok_or_else(|| singular(0.0))?;
        let a_inv_c = a.solve(&r.c);
        let mobility = r.c.dot(&a_inv_c);
        if !(mobility > 0.0 && mobility.is_finite()) {
            return Err(singular(mobility));
        }
        // The accelerations without this resistance: those of the state less its part.
        let now = r.force(r.c.dot(qd));
        let free = accelerations(self, t, q, qd)? - a.solve(&now);
        let drive = computed(
            "drive along a resisted rate",
            (r.c.dot(&free) + r.velocity_term(qd)) / mobility,
        )?;
        Ok(SwitchLoads {
            what: r.what,
            unit: r.unit,
            drive,
            forward: r.forward,
            backward: r.backward,
        })
    }

    /// The generalized force of switch `i`'s resistances while its speed has the sign of
    /// `direction` (+1 or −1; 0 gives zero): with one input, Q₁ at a vanishing rate that way
    /// minus Q₁ at rest (see [`input_switch_loads`](Self::input_switch_loads)); with two,
    /// the resistance's magnitude against σ times its transfer functions c.
    ///
    /// # Errors
    /// As [`input_switch_loads`](Self::input_switch_loads).
    pub(super) fn input_switch_force(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        direction: f64,
    ) -> Result<Vector2<f64>> {
        if self.dof() == 2 {
            if i >= self.input_switches() {
                return Err(self.no_switch(i));
            }
            let (r, held) = self.resisted(&Transfer::new(self.plan(), 2, q)?, i)?;
            if let Some([k, joint]) = held {
                let l = self.joint_stop_loads(&r, k, joint, t, q, qd)?;
                return Ok(Resisted {
                    forward: l.forward,
                    backward: l.backward,
                    ..r
                }
                .force(direction));
            }
            return Ok(r.force(direction));
        }
        let l = self.input_switch_loads(i, t, q, qd)?;
        let f = if direction > 0.0 {
            -l.forward
        } else if direction < 0.0 {
            l.backward
        } else {
            0.0
        };
        Ok(Vector2::new(f, 0.0))
    }

    /// The loads along the friction switch of input `k`'s own joint `joint` (rate σ = c·q̇,
    /// c along input k alone) at the state (t, q, q̇) with σ taken as zero: see the
    /// [module docs](self). The held motion solves A·q̈ = b + Q_f(q̈) + μ·c with c·q̈ = 0 (σ̇
    /// = c·q̈: the input link's rate is q̇ₖ times a constant); the drive is −μ, the limits
    /// the generalized friction along σ that sets in at that motion with σ = ±10⁻²⁰⁰.
    ///
    /// # Errors
    /// [`Error::Singular`] when A is not positive-definite; [`Error::Budget`] (within
    /// [`Error::In`]) when the held motion is not found within
    /// [`FRICTION_BUDGET`](super::FRICTION_BUDGET) evaluations; the friction statics' and
    /// the terms' errors.
    fn joint_stop_loads(
        &self,
        r: &Resisted,
        k: usize,
        _joint: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<SwitchLoads> {
        const TINY: f64 = 1e-200;
        let ck = r.c[k];
        if ck == 0.0 {
            return Err(Error::Singular {
                what: "an input joint's friction at its stop",
                measure: "the input joint's rate per unit input rate",
                value: ck,
            });
        }
        let mut rest = *qd;
        rest[k] = 0.0;
        let (qdd, mu) = self.held_motion(k, t, q, qd)?;
        // The friction that sets in with σ = ±10⁻²⁰⁰ at the held motion: the joints that
        // were moving keep their friction, those whose rate vanishes with σ (the input's own
        // joint; at a whole rest, every joint the input moves) add theirs, along σ.
        let held = self.evaluate(q, &rest, true, None, Some(&qdd))?.friction;
        let limit = |s: f64| -> Result<f64> {
            let mut v = rest;
            v[k] = s * TINY / ck;
            let f = self.evaluate(q, &v, true, None, Some(&qdd))?.friction;
            Ok((-s * (f[k] - held[k]) / ck).max(0.0))
        };
        let (forward, backward) = (limit(1.0)?, limit(-1.0)?);
        Ok(SwitchLoads {
            what: r.what,
            unit: r.unit,
            // μ·eₖ = (μ/cₖ)·c: the held load along σ is μ/cₖ.
            drive: computed("drive along an input joint with friction", -mu / ck)?,
            forward,
            backward,
        })
    }
}

impl LinkageSystem {
    /// The motion with input `k` held at rest (q̇ₖ taken as 0, q̈ₖ = 0) at the state
    /// (t, q, q̇), the other input free: its accelerations and the generalized force μ along
    /// eₖ that holds input k. A·q̈ = b + Q_f(q̈) + μ·eₖ with b = Q − Γ − B·q̇ at q̇ₖ = 0, and
    /// the other joints' friction Q_f depends on the reactions and so on q̈: the pair is the
    /// fixed point q̈ = A⁻¹·(b + Q_f(q̈)) + μ·A⁻¹·eₖ, μ = −[A⁻¹·(b + Q_f)]ₖ / (A⁻¹)ₖₖ (the
    /// multiple of A⁻¹·eₖ that cancels q̈ₖ), iterated to
    /// [`FRICTION_TOLERANCE`](super::FRICTION_TOLERANCE) of the accelerations.
    ///
    /// # Errors
    /// [`Error::Singular`] when A is not positive-definite; [`Error::Budget`] (within
    /// [`Error::In`]) when the held motion is not found within
    /// [`FRICTION_BUDGET`](super::FRICTION_BUDGET) evaluations; the friction statics' and
    /// the terms' errors.
    pub(super) fn held_motion(
        &self,
        k: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<(Vector2<f64>, f64)> {
        let singular = |value: f64| Error::Singular {
            what: "an input joint's friction at its stop",
            measure: "the input's diagonal of A⁻¹ (its mobility)",
            value,
        };
        let mut rest = *qd;
        rest[k] = 0.0;
        let a = self.inertia(q)?.cholesky().ok_or_else(|| singular(0.0))?;
        let e = if k == 0 { Vector2::x() } else { Vector2::y() };
        let a_inv_e = a.solve(&e);
        let mobility = a_inv_e[k];
        if !(mobility > 0.0 && mobility.is_finite()) {
            return Err(singular(mobility));
        }
        let (mut qdd, mut scale) = (Vector2::zeros(), None);
        for _ in 0..FRICTION_BUDGET {
            let terms = self.evaluate(q, &rest, true, None, Some(&qdd))?;
            let b = terms.forces()
                - christoffel_terms(&terms.inertia_derivatives, &rest)?
                - terms.damping * rest;
            let p = a.solve(&b);
            let mu = -p[k] / mobility;
            let mut next = p + a_inv_e * mu;
            next[k] = 0.0;
            let step = (next - qdd).norm();
            let s = *scale.get_or_insert(next.norm() + step);
            qdd = next;
            if step <= FRICTION_TOLERANCE * s {
                return Ok((qdd, mu));
            }
        }
        Err(Error::In {
            part: format!(
                "an input joint's friction at its stop at q = ({}, {}): the held motion \
                 not found",
                q[0], q[1]
            ),
            source: Box::new(Error::Budget {
                what: "friction evaluation",
                limit: FRICTION_BUDGET,
                time: t,
            }),
        })
    }

    /// The coordinate switch `i` holds ([`LagrangeSystem::switch_holds`]): with one input
    /// its one switch, the input's rate; with two, the switch of an input's own joint
    /// friction (its rate is cₖ·q̇ₖ). A resistance on a link or a slide moves with both
    /// inputs: none.
    pub(super) fn input_switch_holds(&self, i: usize) -> Option<usize> {
        if i >= self.input_switches() {
            return None;
        }
        if self.dof() == 1 {
            return Some(0);
        }
        let n = self.resistances().count();
        i.checked_sub(n)
            .and_then(|h| self.held_inputs().nth(h))
            .map(|(k, _, _)| k)
    }

    /// The terms of the motion with the inputs `held` at rest
    /// ([`LagrangeSystem::held_terms`]): with one input of two held and joint friction, the
    /// friction of the held motion ([`held_motion`](Self::held_motion)); otherwise the terms
    /// at the state (a whole rest has no friction).
    pub(super) fn input_held_terms(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        held: [bool; 2],
    ) -> Result<LagrangeTerms> {
        let one = match held {
            [true, false] => Some(0),
            [false, true] => Some(1),
            _ => None,
        };
        let all = match one {
            Some(k) if self.dof() == 2 && self.has_joint_friction() => {
                let (qdd, _) = self.held_motion(k, t, q, qd)?;
                let mut rest = *qd;
                rest[k] = 0.0;
                self.evaluate(q, &rest, true, Some(t), Some(&qdd))?
            }
            _ => return self.terms(t, q, qd),
        };
        Ok(LagrangeTerms {
            inertia: all.inertia,
            inertia_derivatives: all.inertia_derivatives,
            forces: all.forces(),
            potential_gradient: Vector2::zeros(),
            damping: all.damping,
        })
    }
}
