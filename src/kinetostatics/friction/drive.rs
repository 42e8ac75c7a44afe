//! The input link driven through a coupling, with friction in its frame pin O1.

use super::{sign, Hinge, JointFriction};
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
