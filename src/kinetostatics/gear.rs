//! The input link driven through a gear pair (seed program SRWL1): the balancing force.
//!
//! Link 1 carries a gear wheel of pitch radius r_w = |O1P|; the motor's pinion drives it with a
//! tooth force at the pitch point P along a line of action inclined at the pressure angle α_w
//! to the tangent of the pitch circle. A tooth force can only push, so the sign of the moment
//! it must supply decides which tooth flank carries it (the seeds' flank rule, docs/errata.md#n2):
//! with e the unit vector O1→P and t = e turned −90° (the tangent),
//! - [`Flank::Preliminary`]: direction t·cos α_w − e·sin α_w, a clockwise moment
//!   −r_w·cos α_w·F about O1 (the seed's 0.5π − α_w for P on the −x side of O1);
//! - [`Flank::Mirrored`]: direction −t·cos α_w − e·sin α_w, a counter-clockwise moment
//!   +r_w·cos α_w·F (the seed's 1.5π + α_w).
//!
//! Both push towards O1. The magnitude is F = |M_b|/(r_w·cos α_w) with M_b = −Σ M_i(O1), and
//! the frame's reaction is R01 = −(Σ F_i + F_b). The seed writes P only on the −x side of O1
//! (docs/errata.md#n1); here P may lie anywhere on the pitch circle.

use super::conditioning::{ensure_finite, Conditioning};
use super::coupling::input_link_loads;
use crate::angle::unit;
use crate::error::{finite, finite2, positive, Error, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};
use std::f64::consts::{FRAC_PI_2, PI};

const WHAT: &str = "gear input link";
const MEASURE: &str = "r_w cos(alpha_w)";

/// Which tooth flank carries the balancing force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Flank {
    /// The seed's preliminary direction (0.5π − α_w for P on the −x side of O1): the tooth
    /// force turns link 1 clockwise.
    Preliminary,
    /// The other flank (1.5π + α_w for P on the −x side): the tooth force turns link 1
    /// counter-clockwise.
    Mirrored,
}

/// An input link turning about O1, driven by a gear whose pitch point is P.
///
/// # Examples
/// The crank of the [`CouplingDrive`](super::CouplingDrive) example (R21 = (0, −500) N at
/// A = (0.1, 0) m) driven through a wheel of r_w = 0.2 m with P on the −x side and α_w = 20°.
/// The loads turn link 1 by −50 N·m, so the tooth force must turn it counter-clockwise: the
/// mirrored flank, F = 50/(0.2·cos 20°) = 266.04 N along 270° + 20° = 290°.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{angle, kinetostatics::{Flank, GearDrive}, Load};
/// let drive = GearDrive {
///     o1: Point2::origin(),
///     pitch_point: Point2::new(-0.2, 0.0),
///     pressure_angle: 20f64.to_radians(),
/// };
/// let r = drive.solve(&[Load::force_at(Point2::new(0.1, 0.0), Vector2::new(0.0, -500.0))])?;
/// assert_eq!(r.flank, Flank::Mirrored);
/// assert_relative_eq!(r.magnitude, 266.044, epsilon = 1e-3);
/// assert_relative_eq!(angle::direction(r.force).to_degrees(), 290.0, epsilon = 1e-9);
/// assert_relative_eq!(r.r01, -(r.force + Vector2::new(0.0, -500.0)), epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SRWL1")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GearDrive {
    /// The centre of the frame hinge O1, which is also the wheel's centre.
    pub o1: Point2<f64>,
    /// The pitch point P, where the pinion's tooth force acts; r_w = |O1P|.
    pub pitch_point: Point2<f64>,
    /// α_w, the pressure angle (operating angle of the mesh), in [0, π/2), rad.
    pub pressure_angle: f64,
}

/// The balancing force of an input link driven through a gear pair, and the frame's reaction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GearBalance {
    /// F_b, the force of the driving pinion on the wheel at the pitch point, N.
    pub force: Vector2<f64>,
    /// |F_b|, N.
    pub magnitude: f64,
    /// The flank that carries it.
    pub flank: Flank,
    /// M_b, the moment of F_b about O1, N·m (what a coupling would have to supply).
    pub balancing_moment: f64,
    /// R01, the force of the frame on link 1 at O1, N.
    pub r01: Vector2<f64>,
    /// The measure r_w·cos α_w (m), the arm of the tooth force about O1, and the amplification
    /// ρ/(r_w·cos α_w), with ρ the largest distance of P and of the loads' points from O1.
    pub conditioning: Conditioning,
}

impl GearDrive {
    /// A gear drive with the pitch point at the polar angle `pitch_angle` (rad) of a pitch
    /// circle of radius `pitch_radius` (m) about O1. The seed's P is at `pitch_angle = π`.
    #[must_use]
    pub fn at_angle(
        o1: Point2<f64>,
        pitch_radius: f64,
        pitch_angle: f64,
        pressure_angle: f64,
    ) -> Self {
        Self {
            o1,
            pitch_point: o1 + unit(pitch_angle) * pitch_radius,
            pressure_angle,
        }
    }

    /// The balancing force and the frame's reaction for the loads on link 1: its own resultant
    /// load and the reactions R21 of the groups attached to it.
    ///
    /// # Errors
    /// - [`Error::NonFinite`] for a non-finite number;
    /// - [`Error::NonPositive`] when P = O1 (`r_w`);
    /// - [`Error::OutOfRange`] for a pressure angle outside [0, π/2);
    /// - [`Error::Singular`] with `r_w cos(alpha_w)` when the tooth force has no arm about O1.
    pub fn solve(&self, loads: &[Load]) -> Result<GearBalance> {
        finite2(["O1.x", "O1.y"], self.o1.coords)?;
        finite2(["P.x", "P.y"], self.pitch_point.coords)?;
        let alpha = finite("alpha_w", self.pressure_angle)?;
        if !(0.0..FRAC_PI_2).contains(&alpha) {
            return Err(Error::OutOfRange {
                name: "alpha_w",
                value: alpha,
                min: 0.0,
                max: FRAC_PI_2,
                ends: crate::Ends::OpenAbove,
            });
        }
        loads.iter().try_for_each(Load::validate)?;
        let op = self.pitch_point - self.o1;
        let r_w = crate::error::length("r_w", op)?;
        let arm = r_w * alpha.cos();
        let rho = loads
            .iter()
            .map(|l| (l.point - self.o1).norm())
            .fold(r_w, f64::max);
        crate::error::computed("distance of a load from O1", rho)?;
        let conditioning = Conditioning::of(WHAT, MEASURE, arm, rho)?;

        let total = Load::sum_about(loads, self.o1);
        let balancing_moment = -total.moment;
        let e = op / r_w;
        let t = Vector2::new(e.y, -e.x);
        let (s, c) = alpha.sin_cos();
        // The preliminary flank turns link 1 clockwise; it is the seed's choice for M_b = 0.
        let (flank, direction) = if balancing_moment <= 0.0 {
            (Flank::Preliminary, t * c - e * s)
        } else {
            (Flank::Mirrored, -t * c - e * s)
        };
        let magnitude = balancing_moment.abs() / arm;
        let force = direction * magnitude;
        let r01 = -(total.force + force);
        ensure_finite(WHAT, MEASURE, arm / rho, &[magnitude, r01.x, r01.y])?;
        Ok(GearBalance {
            force,
            magnitude,
            flank,
            balancing_moment,
            r01,
            conditioning,
        })
    }
}

/// An input link driven through a gear pair, in the seeds' notation (program SRWL1): the pitch
/// point lies at l_O1P on the −x side of O1, as in the seed's figure.
///
/// # Examples
/// The [`GearDrive`] example. The seed's 1.49 gives
/// F3p = R21·l_O1A·sin(γ21 − φ1)/(l_O1P·sin γ3p) = 500·0.1·sin 270°/(0.2·cos 20°) = −266.04 N:
/// negative, so the flank rule turns the force to γ3p = 1.5π + α_w with magnitude 266.04 N.
/// ```
/// use approx::assert_relative_eq;
/// use tmm::kinetostatics::{Flank, GearSeed};
/// let r = GearSeed {
///     l_o1a: 0.1, l_o1s1: 0.05, l_o1p: 0.2, alpha_w: 20f64.to_radians(), phi1: 0.0,
///     f1: 0.0, gamma1: 0.0, r21: 500.0, gamma21: 270f64.to_radians(), m1: 0.0,
/// }
/// .solve()?;
/// assert_eq!(r.flank, Flank::Mirrored);
/// assert_relative_eq!(r.magnitude, 266.044, epsilon = 1e-3);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SRWL1")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GearSeed {
    /// l_O1A, the length of the input link, m.
    pub l_o1a: f64,
    /// l_O1S1, the distance of S1 from O1, m.
    pub l_o1s1: f64,
    /// l_O1P, the pitch radius r_w of the wheel, m.
    pub l_o1p: f64,
    /// α_w, the pressure angle, rad.
    pub alpha_w: f64,
    /// φ1, the direction angle of O1A, rad.
    pub phi1: f64,
    /// F1, the resultant force on link 1 (at S1), N.
    pub f1: f64,
    /// γ1, its direction angle, rad.
    pub gamma1: f64,
    /// R21, the magnitude of the first group's reaction on link 1 at A, N.
    pub r21: f64,
    /// γ21, its direction angle, rad.
    pub gamma21: f64,
    /// M1, the resultant moment on link 1, N·m.
    pub m1: f64,
}

impl GearSeed {
    /// Solves the input link; see [`GearDrive::solve`].
    ///
    /// # Errors
    /// Non-finite numbers, non-positive lengths, and as [`GearDrive::solve`].
    pub fn solve(&self) -> Result<GearBalance> {
        let loads = input_link_loads(
            self.l_o1a,
            [
                ("l_O1S1", self.l_o1s1),
                ("phi1", self.phi1),
                ("F1", self.f1),
                ("gamma1", self.gamma1),
                ("R21", self.r21),
                ("gamma21", self.gamma21),
                ("M1", self.m1),
            ],
        )?;
        positive("l_O1P", self.l_o1p)?;
        GearDrive::at_angle(Point2::origin(), self.l_o1p, PI, self.alpha_w).solve(&loads)
    }
}
