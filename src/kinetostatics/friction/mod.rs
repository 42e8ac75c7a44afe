//! Coulomb friction in the joints: the dyads and the input link with friction (issue 24).
//!
//! # The model
//! - A revolute pair (a *hinge*) of friction-circle radius ρ = f·r (pin radius r, friction
//!   coefficient f of the journal; [`Hinge`]) carries, besides the force R through its centre,
//!   a friction couple of magnitude ρ·|R| that opposes the relative rotation of the two links
//!   it joins: on link j from link i, M_ij = −ρ·|R_ij|·sgn(ω_j − ω_i). (The reaction is then
//!   tangent to the friction circle: the textbook's construction, written as a force and a
//!   couple.)
//! - A prismatic pair (a *slide*, [`Slide`]) with coefficient f (friction angle φ = atan f)
//!   carries, besides the normal force N, a friction force of magnitude f·|N| along the slide
//!   that opposes the relative sliding: on link j from link i, F_ij = −f·|N|·sgn(v_rel)·ĝ,
//!   with v_rel the velocity of j relative to i along the slide's unit direction ĝ. It acts
//!   along the slide's line through the pair's reference point (the height of the slider is
//!   neglected), so that it has no moment about that point.
//! - A slide given its slider's length L along the guide is *cocked* by a couple: the normal
//!   reaction is two contact forces N1 and N2 at the slider's ends (at `centre ∓ L/2` along
//!   the guide from the reference point), each with its own friction f·|N_i|. With N the normal
//!   force and K' its moment about the slider's middle, N1 = N/2 − K'/L and N2 = N/2 + K'/L,
//!   and the friction force is f·(|N1| + |N2|) = f·max(|N|, 2|K'|/L): as for a slider that
//!   takes any couple while the normal force's line of action crosses the slider
//!   (|K'/N| ≤ L/2), more when it does not (the drawer that jams).
//!
//! # At rest, and at a reversal of the relative motion
//! Only the *sign* of each relative rate enters the reactions (the rates' sizes enter the
//! powers lost). A relative rate that is exactly zero gives that joint **no friction**: static
//! friction is indeterminate (anything inside the friction cone), and the kinetostatics of the
//! textbooks (Artobolevsky, *Theory of Mechanisms and Machines*, ch. on friction in kinematic
//! pairs) takes the kinetic friction where there is relative motion only. To analyse the
//! impending motion at rest or at a reversal, pass a rate of the impending direction (any
//! non-zero value of that sign, say ±1): the friction then opposes the impending motion, and
//! the powers lost scale with the value given.
//!
//! # The solve
//! Each friction load is proportional to a pressure m_k (|R| for a hinge, |N| or |N1| + |N2|
//! for a slide) that depends on the reactions, which in turn depend on the friction loads.
//! The frictionless closed forms are linear in the loads, so the reactions are affine in the
//! three pressures m = (m_1, m_2, m_3) of a dyad's three joints: V(m) = V0 + D·m, with V0 the
//! frictionless solve and D the closed form's response to each joint's friction load per
//! newton of pressure. The equations m = ψ(V(m)) are solved by Newton's method from the
//! frictionless m0 = ψ(V0) (a 3×3 system per step, by Cramer's rule), until the step is at
//! most `tolerance` (default 10⁻¹⁴) of the load scale, divided by det(I − J) when that is
//! below 1 (rounding is amplified by 1/det near self-locking). When the direct iteration does
//! not converge with det(I − J) > 0, the friction is switched on gradually (continuation in a
//! factor t from 0 to 1 on every coefficient, Newton at each step) so that the solution found
//! is the one connected to the frictionless one. The steps taken are reported
//! ([`Convergence`]); a budget exhausted is an error.
//!
//! # Self-locking
//! J = ∂ψ/∂m is the friction's feedback on itself; det(I − J) is 1 without friction and falls
//! to 0 where the friction loads grow without bound: no finite load moves the group in the
//! given direction (the slider pushed at a pressure angle α with tan α ≥ 1/f). Where the
//! continuation cannot reach full friction with det(I − J) > 0, the solve is an
//! [`Error::In`] naming the joint whose own feedback J_kk is largest,
//! around an [`Error::Singular`] with the measure `det(I - J)`.
//!
//! With every coefficient zero (or every relative rate zero) the results are the frictionless
//! blocks' own, bit for bit.
//!
//! # Cost
//! One frictionless closed form, its responses to the three friction loads, and a few Newton
//! steps of a 3×3 system (two, plus the check, for the usual f ≤ 0.3). The RRR dyad, the
//! engine's most frequent group, has its responses in closed form and its Newton written out
//! (`benches/friction.rs`: about 6× its frictionless closed form, side by side, and a whole
//! four-bar position 1.6× the frictionless one); the other dyads call their closed form once
//! per joint for the responses (10–21× theirs), all five by one solve (`dyad.rs`).
//! A triad or a general group calls its block once per hinge with friction and takes Newton
//! steps of an n×n LU ([`TriadFriction`]; the continuation of every group is that solve's).
//!
//! | group | solver | joints (in the order of [`Convergence`]) |
//! |-------|--------|--------|
//! | RRR | [`RrrFriction`] | A (1–2), B (2–3), C (3–4) |
//! | RRP | [`RrpFriction`] | A (1–2), B (2–3), the guide (4–3) |
//! | RPR | [`RprFriction`] | A (1–2), the slide (3–2), E (4–3) |
//! | PRP | [`PrpFriction`] | guide 2 (1–2), B (2–3), guide 3 (4–3) |
//! | RPP | [`RppFriction`] | A (1–2), the slot (3–2), the guide (4–3) |
//! | triad | [`TriadFriction`] | A1, A2, A3 (outer), B1, B2, B3 (ternary) |
//! | triad with a sliding pair | the engine's (`group.rs`) | A1, A2, A3, B1, B2, B3 (one of A1, B1 the slide) |
//! | any group of hinges | the engine's general groups (`group.rs`) | its hinges |
//! | input link, coupling | [`CrankFriction`] | O1 (0–1) |
//! | input link, gear pair | [`GearFriction`] | O1 (0–1) |

mod drive;
mod dyad;
mod dyads;
mod efficiency;
mod group;
mod newton;
mod solver;

pub use drive::{CrankBalance, CrankFriction, GearFriction, GearFrictionBalance};
pub use dyads::{
    PrpFriction, PrpFrictionReactions, PrpJoints, PrpRates, RppFriction, RppFrictionReactions,
    RppJoints, RppRates, RprFriction, RprFrictionReactions, RprJoints, RprRates, RrpFriction,
    RrpFrictionReactions, RrpJoints, RrpRates, RrrFriction, RrrFrictionReactions, RrrJoints,
    RrrRates,
};
pub use efficiency::Efficiency;
pub(crate) use group::{
    group_friction, slider_triad_block, triad_block, Frictionless, GroupJoint, GroupPair,
};
pub use group::{TriadFriction, TriadFrictionReactions, TriadJoints, TriadRates};

use crate::error::{finite, Ends, Error, Result};

/// The friction data of a revolute pair: the radius ρ of its friction circle.
///
/// A hinge that carries the force R has the friction couple ρ·|R| (see the
/// [module](self)). For a journal of radius r and (reduced) friction coefficient f, ρ = f·r
/// ([`Hinge::pin`]); give ρ directly ([`Hinge::circle`]) for any other law.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Hinge {
    /// ρ, the radius of the friction circle, m (≥ 0).
    pub rho: f64,
}

impl Hinge {
    /// A frictionless hinge.
    pub const FRICTIONLESS: Self = Self { rho: 0.0 };

    /// A pin of radius `radius` (m) with the friction coefficient `f`: ρ = f·r.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] (below 0) naming `pin radius` or `f`.
    pub fn pin(radius: f64, f: f64) -> Result<Self> {
        let r = non_negative("pin radius", radius)?;
        let f = non_negative("f", f)?;
        Self::circle(f * r)
    }

    /// A friction circle of radius `rho` (m).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] (below 0) naming `rho`.
    pub fn circle(rho: f64) -> Result<Self> {
        Ok(Self {
            rho: non_negative("rho", rho)?,
        })
    }

    /// ρ, checked as the named field of a joint (`"rho_A"`).
    #[inline]
    pub(crate) fn checked(&self, name: &'static str) -> Result<f64> {
        non_negative(name, self.rho)
    }
}

/// The friction data of a prismatic pair: the coefficient f and, for a cocked slider, the
/// slider's length along the guide.
///
/// Without a length the friction force is f·|N| for the normal force N whatever couple the
/// pair carries; with one, the normal reaction is two contact forces at the slider's ends,
/// each with its own friction (see the [module](self)). `centre` is where the slider's middle
/// lies along the guide from the pair's reference point (each solver names it: B for a slider
/// on B, A for the block on a crank pin), m.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Slide {
    /// f, the coefficient of sliding friction (≥ 0); the friction angle is atan f.
    pub f: f64,
    /// L, the slider's length along the guide, m (> 0), or `None` for a slider that takes
    /// any couple.
    pub length: Option<f64>,
    /// The slider's middle, along the guide from the pair's reference point, m.
    pub centre: f64,
}

impl Slide {
    /// A frictionless slide.
    pub const FRICTIONLESS: Self = Self {
        f: 0.0,
        length: None,
        centre: 0.0,
    };

    /// A slide with the coefficient `f` that takes any couple.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] (below 0) naming `f`.
    pub fn new(f: f64) -> Result<Self> {
        Ok(Self {
            f: non_negative("f", f)?,
            ..Self::FRICTIONLESS
        })
    }

    /// A slide with the coefficient `f` whose slider, of length `length` (m) along the guide
    /// and centred on the reference point, is cocked by a couple.
    ///
    /// # Errors
    /// As [`Slide::new`], and [`Error::NonFinite`] or [`Error::NonPositive`] naming `length`.
    pub fn cocked(f: f64, length: f64) -> Result<Self> {
        Ok(Self {
            f: non_negative("f", f)?,
            length: Some(crate::error::positive("length", length)?),
            centre: 0.0,
        })
    }

    /// The same slide with the slider's middle at `centre` (m) along the guide from the
    /// reference point.
    #[must_use]
    pub fn centred_at(self, centre: f64) -> Self {
        Self { centre, ..self }
    }

    /// The friction angle φ = atan f, rad.
    #[must_use]
    pub fn friction_angle(&self) -> f64 {
        self.f.atan()
    }

    /// f, and the pressure law, checked with the joint's field names (`f`, `L`, `centre`).
    #[inline]
    pub(crate) fn checked(&self, names: [&'static str; 3]) -> Result<(f64, solver::Pressure)> {
        let f = non_negative(names[0], self.f)?;
        let centre = finite(names[2], self.centre)?;
        let law = match self.length {
            None => solver::Pressure::Normal,
            Some(l) => {
                let half = crate::error::positive(names[1], l)? / 2.0;
                // The end pressures divide by the half length: a subnormal one overflows
                // them (a length of 5e-324 m gave an infinite end force inside an `Ok`).
                if half < f64::MIN_POSITIVE {
                    return Err(Error::OutOfRange {
                        name: names[1],
                        value: l,
                        min: 2.0 * f64::MIN_POSITIVE,
                        max: f64::INFINITY,
                        ends: crate::error::Ends::Closed,
                    });
                }
                solver::Pressure::Ends { centre, half }
            }
        };
        Ok((f, law))
    }
}

/// The loosest tolerance [`Iteration::checked`] accepts, relative to the load scale.
pub const MAX_TOLERANCE: f64 = 1e-3;

/// The options of the friction iteration: its tolerance and its budget of Newton steps.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Iteration {
    /// The largest Newton step accepted as converged, relative to the load scale (the largest
    /// force among the loads and the frictionless reactions). Default 10⁻¹⁴.
    pub tolerance: f64,
    /// The largest number of Newton steps, continuation included. Default 64.
    pub budget: usize,
}

impl Default for Iteration {
    fn default() -> Self {
        Self {
            tolerance: 1e-14,
            budget: 64,
        }
    }
}

impl Iteration {
    /// The same options with another tolerance.
    #[must_use]
    pub fn with_tolerance(self, tolerance: f64) -> Self {
        Self { tolerance, ..self }
    }

    /// The same options with another budget.
    #[must_use]
    pub fn with_budget(self, budget: usize) -> Self {
        Self { budget, ..self }
    }

    /// The options checked before any solve uses them: a tolerance in (0, 10⁻³] (a looser
    /// one would accept an unconverged answer as the result, a NaN none at all) and a budget
    /// of at least one step.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] naming `tolerance` or `budget`.
    pub fn checked(self) -> Result<Self> {
        if !(self.tolerance > 0.0 && self.tolerance <= MAX_TOLERANCE) {
            return Err(Error::OutOfRange {
                name: "tolerance",
                value: self.tolerance,
                min: 0.0,
                max: MAX_TOLERANCE,
                ends: Ends::OpenBelow,
            });
        }
        if self.budget == 0 {
            return Err(Error::OutOfRange {
                name: "budget",
                value: 0.0,
                min: 1.0,
                max: f64::INFINITY,
                ends: Ends::Closed,
            });
        }
        Ok(self)
    }
}

/// How the friction iteration went.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Convergence {
    /// The Newton steps taken (0 without friction), continuation included.
    pub iterations: usize,
    /// Whether the friction had to be switched on gradually (continuation).
    pub continued: bool,
    /// det(I − J) of the last Newton step (within a step of the solution): 1 without
    /// friction, towards 0 near self-locking. The rounding errors of the reactions are
    /// amplified by about 1/det.
    pub det: f64,
    /// The largest |m_k − ψ_k(V(m))| at the solution, N: how far the pressures the friction
    /// loads were computed from are from the pressures of the reactions returned.
    pub residual: f64,
}

impl Convergence {
    /// Without friction: nothing to iterate.
    pub(crate) const NONE: Self = Self {
        iterations: 0,
        continued: false,
        det: 1.0,
        residual: 0.0,
    };
}

/// The friction in one joint, as solved.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointFriction {
    /// The friction load on the joint's second link from its first (the solver names them):
    /// a couple, N·m, for a hinge; a force along the slide's direction, N, for a slide.
    pub load: f64,
    /// The pressure the friction is proportional to, N: |R| for a hinge, |N| or |N1| + |N2|
    /// for a slide.
    pub pressure: f64,
    /// The power lost in the joint, W (≥ 0): ρ·|R|·|ω_rel| or f·|N|·|v_rel|, with the
    /// relative rate ω_j − ω_i (rad/s) of a hinge, or the second link's sliding velocity
    /// relative to the first (m/s) of a slide.
    pub power_lost: f64,
}

impl JointFriction {
    /// `coefficient` (ρ or f, with the sign of the rate folded in: c = coefficient·sgn(rate))
    /// times the pressure, opposed to the motion.
    #[inline]
    pub(crate) fn new(signed_coefficient: f64, pressure: f64, rate: f64) -> Self {
        let load = -signed_coefficient * pressure;
        Self {
            load,
            pressure,
            power_lost: -load * rate,
        }
    }

    /// A joint without friction (pressure as given).
    #[inline]
    pub(crate) fn none(pressure: f64) -> Self {
        Self {
            load: 0.0,
            pressure,
            power_lost: 0.0,
        }
    }
}

/// The normal reaction of a slide, as solved.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SlideContact {
    /// N, the normal force along the slide's unit direction turned +90°, N.
    pub normal: f64,
    /// The moment of the normal force about the pair's reference point, N·m.
    pub moment: f64,
    /// For a cocked slider, the contact forces [N1, N2] at its rear and front ends (the
    /// `centre ∓ L/2` along the guide), along the same normal, N.
    pub ends: Option<[f64; 2]>,
}

impl SlideContact {
    #[inline]
    pub(crate) fn new(normal: f64, moment: f64, law: solver::Pressure) -> Self {
        let ends = match law {
            solver::Pressure::Ends { centre, half } => {
                let k = (moment - centre * normal) / (2.0 * half);
                Some([normal / 2.0 - k, normal / 2.0 + k])
            }
            _ => None,
        };
        Self {
            normal,
            moment,
            ends,
        }
    }
}

/// `value` ≥ 0 and finite, or an error naming it.
#[inline]
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value >= 0.0 && value.is_finite() {
        return Ok(value);
    }
    finite(name, value)?;
    {
        Err(Error::OutOfRange {
            name,
            value,
            min: 0.0,
            max: f64::INFINITY,
            ends: Ends::Closed,
        })
    }
}

/// −1, 0 or +1: the sign of a relative rate, 0 for a zero rate (of either sign) — the
/// convention at rest (see the [module](self)).
#[inline]
pub(crate) fn sign(rate: f64) -> f64 {
    f64::from(u8::from(rate > 0.0)) - f64::from(u8::from(rate < 0.0))
}
