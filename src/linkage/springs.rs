//! Springs and dampers of a plan: a linear spring or a viscous damper between two places of
//! two links, a torsion spring between two links. Each is planned once (its ends as local
//! coordinates of their links) and read at every position by the one load interpreter, so a
//! spring's force enters the kinetostatics (reactions, balancing moment) and the dynamics'
//! generalized forces the same way.
//!
//! The laws, written once here:
//! - a linear spring's tension T(L) = F₀ + k·(L − L₀), its energy V(L) = F₀·x + ½·k·x²
//!   with x = L − L₀ (dV/dL = T: its forces' power is −dV/dt);
//! - a damper's force c·L̇ along the line of its ends, opposing L̇ (power −c·L̇²);
//! - a torsion spring's moment M(τ) = M₀ + k·τ on its first link and −M on its second, τ the
//!   twist (Δθ − Δθ₀ in (−π, π]), its energy M₀·τ + ½·k·τ².
//!
//! A twist read in (−π, π] jumps a turn where it passes ±π (between links that turn fully
//! relative to each other, or a spring whose free angle lies half a turn from where the links
//! go): its moment would jump and its energy would not be conserved. Such a spring is refused
//! when the plan is made (`torsion_range`), by name, with how close it came.

use nalgebra::Vector2;
use std::f64::consts::PI;

/// A place on a link of the plan: the link and the local coordinates in its frame.
pub(crate) type End = (usize, Vector2<f64>);

/// A linear spring between two places.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SpringPlan {
    /// "spring NAME" (or the load's number), for errors.
    pub name: String,
    pub ends: [End; 2],
    pub stiffness: f64,
    pub free_length: f64,
    pub preload: f64,
}

impl SpringPlan {
    /// The tension at the length `l` (positive pulls the ends together), N.
    pub fn tension(&self, l: f64) -> f64 {
        self.preload + self.stiffness * (l - self.free_length)
    }

    /// The potential energy at the length `l`, J (zero at the free length).
    pub fn energy(&self, l: f64) -> f64 {
        let x = l - self.free_length;
        x * (self.preload + 0.5 * self.stiffness * x)
    }
}

/// A viscous damper between two places.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DamperPlan {
    /// "damper NAME" (or the load's number), for errors.
    pub name: String,
    pub ends: [End; 2],
    pub c: f64,
}

/// A torsion spring between two links.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TorsionPlan {
    /// "torsion spring NAME" (or the load's number), for errors.
    pub name: String,
    pub links: [usize; 2],
    pub stiffness: f64,
    /// Δθ₀ as the angle between the links' frames (the engine's link angles), rad.
    pub free: f64,
    pub preload: f64,
}

impl TorsionPlan {
    /// The twist τ ∈ (−π, π] at the frames' angles `theta` of its two links.
    pub fn twist(&self, theta: [f64; 2]) -> f64 {
        wrap(theta[1] - theta[0] - self.free)
    }

    /// The moment on its first link at the twist `tau` (the second link takes −M), N·m.
    pub fn moment(&self, tau: f64) -> f64 {
        self.preload + self.stiffness * tau
    }

    /// The potential energy at the twist `tau`, J.
    pub fn energy(&self, tau: f64) -> f64 {
        tau * (self.preload + 0.5 * self.stiffness * tau)
    }
}

/// `a` brought into (−π, π].
pub(super) fn wrap(a: f64) -> f64 {
    let w = a - 2.0 * PI * (a / (2.0 * PI)).round();
    if w <= -PI {
        w + 2.0 * PI
    } else {
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_lands_in_the_half_open_turn() {
        for k in -5..=5 {
            for a in [-3.0, -1.0, 0.0, 0.5, 3.1, PI] {
                let w = wrap(a + 2.0 * PI * f64::from(k));
                assert!(w > -PI && w <= PI, "{a} {k} {w}");
                assert!((w - a).abs() < 1e-12 || (w - a + 2.0 * PI).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn energies_are_the_integrals_of_the_laws() {
        let s = SpringPlan {
            name: String::new(),
            ends: [(0, Vector2::zeros()); 2],
            stiffness: 300.0,
            free_length: 0.2,
            preload: 12.0,
        };
        let t = TorsionPlan {
            name: String::new(),
            links: [0, 1],
            stiffness: 4.0,
            free: 0.3,
            preload: -0.5,
        };
        // Central differences of a quadratic are exact up to rounding.
        let h = 1e-4;
        for x in [0.05, 0.2, 0.31] {
            let d = (s.energy(x + h) - s.energy(x - h)) / (2.0 * h);
            assert!((d - s.tension(x)).abs() < 1e-9, "{d} {}", s.tension(x));
            let d = (t.energy(x + h) - t.energy(x - h)) / (2.0 * h);
            assert!((d - t.moment(x)).abs() < 1e-9);
        }
    }
}
