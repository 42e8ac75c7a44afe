//! The input link driven through a coupling, with friction in its frame pin O1.

use super::{sign, Hinge, JointFriction};
use crate::angle::perp;
use crate::error::{finite, finite2, Result};
use crate::kinetostatics::conditioning::ensure_finite;
use crate::Load;
use nalgebra::{Point2, Vector2};

/// An input link turning about O1 with the angular velocity ω1, driven through a coupling,
/// with friction in its frame pin (seed program SRWL2 with friction).
///
/// A coupling passes a pure moment, so the frame's reaction R01 = −Σ F_i does not depend on
/// the balancing moment, and the pin's friction couple −ρ·|R01|·sgn(ω1) follows at once:
/// M_b = −Σ M_i(O1) + ρ·|R01|·sgn(ω1). No iteration.
///
/// # Examples
/// The crank of [`CouplingDrive`](crate::kinetostatics::CouplingDrive)'s example
/// (R21 = (0, −500) N at A = (0.1, 0) m, M_b = 50 N·m without friction) turning
/// counter-clockwise at 10 rad/s on a pin of ρ = 2 mm: the pin's friction adds
/// 0.002·500 = 1 N·m, and it costs 10 W of the 510 W the motor gives.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::Load;
/// use tmm::kinetostatics::friction::{CrankFriction, Hinge};
/// let crank = CrankFriction { o1: Point2::origin(), pin: Hinge::circle(0.002)?, omega1: 10.0 };
/// let r = crank.solve(&[Load::force_at(Point2::new(0.1, 0.0), Vector2::new(0.0, -500.0))])?;
/// assert_relative_eq!(r.balancing_moment, 51.0, epsilon = 1e-12);
/// assert_relative_eq!(r.pin.power_lost, 10.0, epsilon = 1e-12);
/// assert_relative_eq!(r.power_drive, 510.0, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SRWL2")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CrankFriction {
    /// The centre of the frame pin O1.
    pub o1: Point2<f64>,
    /// The frame pin's friction data.
    pub pin: Hinge,
    /// ω1, the input link's angular velocity, rad/s (relative to the frame).
    pub omega1: f64,
}

/// The balancing moment of an input link with friction in its frame pin.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CrankBalance {
    /// M_b, the moment the motor applies to link 1, N·m, counter-clockwise positive.
    pub balancing_moment: f64,
    /// R01, the force of the frame on link 1 at O1, N.
    pub r01: Vector2<f64>,
    /// O1's friction: the couple of the frame on link 1, rate ω1.
    pub pin: JointFriction,
    /// The motor's power M_b·ω1, W.
    pub power_drive: f64,
}

impl CrankFriction {
    /// The balancing moment for the loads on link 1: its own resultant load and the loads of
    /// the groups attached to it (the dyads' `on_link1(&dyad)`, friction couples included).
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) naming `O1.x`, `O1.y`, `omega1` or a
    /// load's number; [`Error::OutOfRange`](crate::Error::OutOfRange) for a negative
    /// `rho_O1`; [`Error::Overflow`](crate::Error::Overflow) when the sums overflow.
    pub fn solve(&self, loads: &[Load]) -> Result<CrankBalance> {
        finite2(["O1.x", "O1.y"], self.o1.coords)?;
        let rho = self.pin.checked("rho_O1")?;
        let omega = finite("omega1", self.omega1)?;
        loads.iter().try_for_each(Load::validate)?;
        let total = Load::sum_about(loads, self.o1);
        let r01 = -total.force;
        let pin = JointFriction::new(rho * sign(omega), r01.norm(), omega);
        let balancing_moment = -total.moment - pin.load;
        let power_drive = balancing_moment * omega;
        ensure_finite(
            "input link with friction",
            "sum of loads",
            1.0,
            &[balancing_moment, r01.x, r01.y, pin.power_lost, power_drive],
        )?;
        Ok(CrankBalance {
            balancing_moment,
            r01,
            pin,
            power_drive,
        })
    }
}

/// An input link turning about O1 with the angular velocity ω1, driven through a gear pair,
/// with friction in its frame pin (seed program SRWL1 with friction).
///
/// The tooth force F_b (along the flank's line of action, see
/// [`GearDrive`](crate::kinetostatics::GearDrive)) enters the frame's reaction
/// R01 = −(Σ F_i + F_b), so the pin's friction couple −ρ·|R01|·sgn(ω1) depends on the force
/// it helps to find: |F_b| = |M_req|/(r_w·cos α_w) with M_req = −Σ M_i(O1) + ρ·|R01|·sgn(ω1),
/// the flank chosen by the sign of M_req. It is solved by fixed-point iteration, which
/// contracts by ρ/(r_w·cos α_w) per step, to 10⁻¹⁴ of the load scale; where that factor is 1
/// or more, the pin self-locks (no tooth force turns the wheel).
///
/// # Examples
/// The [`GearDrive`](crate::kinetostatics::GearDrive) example (F = 266.04 N without
/// friction) with a pin of ρ = 2 mm turning counter-clockwise: the motor's power is the
/// loads' plus the pin's loss.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::angle::perp;
/// use tmm::kinetostatics::{friction::{GearFriction, Hinge}, GearDrive};
/// use tmm::Load;
/// let drive = GearDrive { o1: Point2::origin(), pitch_point: Point2::new(-0.2, 0.0), pressure_angle: 20f64.to_radians() };
/// let load = Load::force_at(Point2::new(0.1, 0.0), Vector2::new(0.0, -500.0));
/// let r = GearFriction { drive, pin: Hinge::circle(0.002)?, omega1: 10.0 }.solve(&[load])?;
/// assert!(r.magnitude > 266.04);
/// let p_load = load.force.dot(&(perp(load.point.coords) * 10.0));
/// assert_relative_eq!(r.power_drive + p_load, r.pin.power_lost, epsilon = 1e-9);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SRWL1")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GearFriction {
    /// The gear drive: O1, the pitch point, the pressure angle.
    pub drive: crate::kinetostatics::GearDrive,
    /// The frame pin's friction data.
    pub pin: Hinge,
    /// ω1, the input link's angular velocity, rad/s (relative to the frame).
    pub omega1: f64,
}

/// The balancing force of an input link driven through a gear pair, with pin friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GearFrictionBalance {
    /// F_b, the force of the driving pinion on the wheel at the pitch point, N.
    pub force: Vector2<f64>,
    /// |F_b|, N.
    pub magnitude: f64,
    /// The flank that carries it.
    pub flank: crate::kinetostatics::Flank,
    /// The moment of F_b about O1, N·m.
    pub balancing_moment: f64,
    /// R01, the force of the frame on link 1 at O1, N.
    pub r01: Vector2<f64>,
    /// O1's friction: the couple of the frame on link 1, rate ω1.
    pub pin: JointFriction,
    /// The drive's power F_b·v_P, W.
    pub power_drive: f64,
    /// The fixed-point steps taken.
    pub iterations: usize,
}

impl GearFriction {
    /// The balancing force for the loads on link 1 (its own and the groups' `on_link1`).
    ///
    /// # Errors
    /// As [`GearDrive::solve`](crate::kinetostatics::GearDrive::solve); a bad `rho_O1` or
    /// `omega1`, named; [`Error::In`](crate::Error::In) around
    /// [`Error::Singular`](crate::Error::Singular) when the pin self-locks
    /// (ρ ≥ r_w·cos α_w), or around [`Error::Budget`](crate::Error::Budget) when 64 steps do
    /// not converge.
    pub fn solve(&self, loads: &[Load]) -> Result<GearFrictionBalance> {
        use crate::kinetostatics::Flank;
        let frictionless = self.drive.solve(loads)?;
        let rho = self.pin.checked("rho_O1")?;
        let omega = finite("omega1", self.omega1)?;
        let s = sign(omega);
        let o1 = self.drive.o1;
        let total = Load::sum_about(loads, o1);
        let op = self.drive.pitch_point - o1;
        let r_w = op.norm();
        let arm = r_w * self.drive.pressure_angle.cos();
        let e = op / r_w;
        let t = Vector2::new(e.y, -e.x);
        let (sa, ca) = self.drive.pressure_angle.sin_cos();
        let direction = |flank| match flank {
            Flank::Preliminary => t * ca - e * sa,
            Flank::Mirrored => -t * ca - e * sa,
        };
        let balance = |magnitude: f64, flank| {
            let force = direction(flank) * magnitude;
            let r01 = -(total.force + force);
            let pin = JointFriction::new(rho * s, r01.norm(), omega);
            (force, r01, pin, -total.moment - pin.load)
        };
        if rho * s == 0.0 {
            let (_, _, pin, _) = balance(frictionless.magnitude, frictionless.flank);
            return Ok(GearFrictionBalance {
                force: frictionless.force,
                magnitude: frictionless.magnitude,
                flank: frictionless.flank,
                balancing_moment: frictionless.balancing_moment,
                r01: frictionless.r01,
                pin: JointFriction::none(pin.pressure),
                power_drive: frictionless.force.dot(&(perp(op) * omega)),
                iterations: 0,
            });
        }
        if rho >= arm {
            return Err(locked(rho / arm));
        }
        let scale = total.force.norm().max(frictionless.magnitude);
        let (mut magnitude, mut flank) = (frictionless.magnitude, frictionless.flank);
        for iterations in 1..=64 {
            let (_, _, _, required) = balance(magnitude, flank);
            let next_flank = if required <= 0.0 {
                Flank::Preliminary
            } else {
                Flank::Mirrored
            };
            let next = required.abs() / arm;
            let step = (next - magnitude).abs();
            (magnitude, flank) = (next, next_flank);
            if step <= 1e-14 * scale {
                let (force, r01, pin, required) = balance(magnitude, flank);
                let power_drive = force.dot(&(perp(op) * omega));
                ensure_finite(
                    "gear input link with friction",
                    "r_w cos(alpha_w) - rho",
                    arm - rho,
                    &[magnitude, r01.x, r01.y, power_drive],
                )?;
                return Ok(GearFrictionBalance {
                    force,
                    magnitude,
                    flank,
                    balancing_moment: required,
                    r01,
                    pin,
                    power_drive,
                    iterations,
                });
            }
        }
        Err(crate::Error::In {
            part: "gear input link with friction: pin friction iteration".into(),
            source: Box::new(crate::Error::Budget {
                what: "fixed-point step",
                limit: 64,
                time: 1.0,
            }),
        })
    }
}

/// The pin O1 self-locks: its friction circle reaches the tooth force's arm.
fn locked(ratio: f64) -> crate::Error {
    crate::Error::In {
        part: "joint O1 (links 0 and 1) self-locks".into(),
        source: Box::new(crate::Error::Singular {
            what: "gear input link with friction",
            measure: "1 - rho/(r_w cos(alpha_w))",
            value: 1.0 - ratio,
        }),
    }
}
