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
//! the motion goes on with σ of the drive's sign. The joints' friction of a machine with two
//! inputs is not a switch: its reversals are located as kinks.

use nalgebra::Vector2;

use super::system::LinkageSystem;
use super::transfer::Transfer;
use crate::dynamics::{accelerations, kink_slots, LagrangeSystem, SwitchLoads};
use crate::error::{computed, Error, Result};
use crate::linkage::plan::LoadPlan;

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
            } => Some(Self {
                c: Vector2::new(tr.omega(0, link), tr.omega(1, link)),
                second: [0, 1, 2].map(|s| tr.link(s, link).epsilon),
                forward,
                backward,
                what: "resisted link",
                unit: "N·m",
            }),
            LoadPlan::Sliding {
                joint,
                forward,
                backward,
                ..
            } => {
                let (_, guide, d) = tr.slide_parts(joint);
                // σ = (v_on − v_guide)·d with d turning with the guide at its ω:
                // σ̇ = (a_on − a_guide)·d + ω_guide·(v_on − v_guide)·d⊥.
                let across = Vector2::new(-d.y, d.x);
                let second = [0, 1, 2].map(|s| {
                    let [on, g] = tr.slide_points(s, joint);
                    (on.a - g.a).dot(&d) + tr.omega(s, guide) * (on.v - g.v).dot(&across)
                });
                Some(Self {
                    c: Vector2::new(tr.slide_rate(0, joint, d), tr.slide_rate(1, joint, d)),
                    second,
                    forward,
                    backward,
                    what: "resisted slide",
                    unit: "N",
                })
            }
            _ => None,
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
    /// with two inputs, one per resistance (see the [module docs](self)).
    pub(super) fn input_switches(&self) -> usize {
        if self.dof() == 1 {
            usize::from(self.resistances().next().is_some() || self.has_joint_friction())
        } else {
            self.resistances().count()
        }
    }

    /// Switch `i`'s resistance for a machine with two inputs, at the position of `tr`.
    fn resisted(&self, tr: &Transfer<'_>, i: usize) -> Result<Resisted> {
        self.resistances()
            .nth(i)
            .and_then(|lp| Resisted::new(tr, lp))
            .ok_or_else(|| self.no_switch(i))
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
        for (o, lp) in out.iter_mut().zip(self.resistances()) {
            if let Some(r) = Resisted::new(&tr, lp) {
                *o = r.c.dot(qd);
            }
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
        let r = self.resisted(&Transfer::new(self.plan(), 2, q)?, i)?;
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
            let r = self.resisted(&Transfer::new(self.plan(), 2, q)?, i)?;
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
}
