//! Two independent checks of a whole-mechanism force analysis: the principle of virtual
//! power, and the equilibrium of every link as a free body.
//!
//! The group-by-group chain (seed 000, §1.2) finds the balancing moment through every joint
//! reaction. The principle of virtual power finds it without any reaction: for a mechanism
//! with one degree of freedom and ideal (frictionless) joints the reactions do no work, so
//! Σ (F_i·v_i + M_i·ω_i) over all external, gravity and inertia loads, plus the drive's power
//! M_b·ω1 (or F_b·v_P), is zero at every position. Both must agree to rounding.

use super::drive::Balance;
use crate::error::{Error, Result};
use crate::kinematics::{CrankState, LinkMotion};
use crate::Load;
use nalgebra::Point2;

/// The power of a load on a link moving with `link`: F·v + M·ω, with v the velocity of the
/// link's point at the load's point of application, W.
///
/// # Examples
/// A 10 N force across a crank of 0.2 m turning at 3 rad/s, at the crank's end: v = 0.6 m/s
/// along the force, P = 6 W; a couple of 2 N·m adds 2·3 = 6 W.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use tmm::kinematics::{LinkMotion, PointMotion};
/// use tmm::{mechanism::power_of, Load};
/// let crank = LinkMotion { origin: PointMotion::fixed(Point2::origin()), angle: 0.0, omega: 3.0, epsilon: 0.0 };
/// let load = Load::new(Point2::new(0.2, 0.0), Vector2::new(0.0, 10.0), 2.0);
/// assert!((power_of(&load, &crank) - 12.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn power_of(load: &Load, link: &LinkMotion) -> f64 {
    load.force.dot(&link.motion_of(load.point).v) + load.moment * link.omega
}

/// One link cut free: its motion, the loads applied to it (external, weight, inertia, and the
/// drive's on the input link) and the reactions of the links it touches.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FreeBody {
    /// The link's name, for example `"link 3 (rocker)"`.
    pub name: &'static str,
    /// The link's motion.
    pub motion: LinkMotion,
    /// The applied loads: external, weight and inertia (not the drive, not reactions).
    pub loads: Vec<Load>,
    /// The drive's load on the input link (the balancing moment or force), `None` on the
    /// other links.
    pub drive: Option<Load>,
    /// The joint reactions on this link, each as a force at its joint (plus, for a sliding
    /// pair, the couple the pair transmits).
    pub reactions: Vec<Load>,
}

/// How far one link is from equilibrium.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Residual {
    /// |Σ F|, N.
    pub force: f64,
    /// |Σ M| about the link's origin, N·m.
    pub moment: f64,
    /// The scale of the loads and reactions: the largest |F|, N.
    pub force_scale: f64,
    /// The scale of the moments: the largest |M| about the origin, or force scale × the
    /// largest arm, N·m.
    pub moment_scale: f64,
}

impl Residual {
    /// The larger of the two relative residuals, force and moment.
    #[must_use]
    pub fn relative(&self) -> f64 {
        let rel = |r: f64, s: f64| if s > 0.0 { r / s } else { r };
        rel(self.force, self.force_scale).max(rel(self.moment, self.moment_scale))
    }
}

impl FreeBody {
    /// The input link `crank` cut free: its own load, the drive's load, the reactions of the
    /// groups attached to it (`groups`, each −R_1j at its pin) and the frame's R01 at O1.
    pub(crate) fn input_link(
        name: &'static str,
        crank: &CrankState,
        load: Load,
        balance: &Balance,
        mut groups: Vec<Load>,
    ) -> Self {
        groups.push(Load::force_at(crank.link.origin.p, balance.r01));
        Self {
            name,
            motion: crank.link,
            loads: vec![load],
            drive: Some(balance.load()),
            reactions: groups,
        }
    }

    /// The resultant of all loads and reactions on the link, and its scale.
    #[must_use]
    pub fn residual(&self) -> Residual {
        let pole: Point2<f64> = self.motion.origin.p;
        let all = || self.loads.iter().chain(&self.reactions).chain(&self.drive);
        let sum = Load::sum_about(&all().copied().collect::<Vec<_>>(), pole);
        let force_scale = all().map(|l| l.force.norm()).fold(0.0, f64::max);
        let arm = all().map(|l| (l.point - pole).norm()).fold(0.0, f64::max);
        let moment_scale = all()
            .map(|l| l.moment.abs())
            .fold(force_scale * arm, f64::max);
        Residual {
            force: sum.force.norm(),
            moment: sum.moment.abs(),
            force_scale,
            moment_scale,
        }
    }

    /// The power of the applied loads on this link (the drive's excluded), W.
    #[must_use]
    pub fn power(&self) -> f64 {
        self.loads.iter().map(|l| power_of(l, &self.motion)).sum()
    }
}

/// The balancing moment by the principle of virtual power: M_b = −Σ P_i / ω1, with P_i the
/// powers of the applied loads of all `bodies` (the drive's excluded).
///
/// Also returns Σ |P_i| / |ω1|, the scale against which the agreement with the
/// group-by-group chain is judged.
///
/// # Errors
/// [`Error::Singular`] with `omega1` when the input does not turn (ω1 = 0: the powers vanish
/// and say nothing about the moment).
pub fn virtual_power_moment(bodies: &[FreeBody], omega1: f64) -> Result<(f64, f64)> {
    if omega1 == 0.0 || !omega1.is_finite() {
        return Err(Error::Singular {
            what: "virtual power balance",
            measure: "omega1",
            value: omega1,
        });
    }
    let (sum, abs) = bodies
        .iter()
        .flat_map(|b| b.loads.iter().map(|l| power_of(l, &b.motion)))
        .fold((0.0, 0.0), |(s, a), p| (s + p, a + p.abs()));
    Ok((-sum / omega1, abs / omega1.abs()))
}
