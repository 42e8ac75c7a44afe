// How the motor drives the input link: through a coupling or through a gear pair.

use nalgebra::{Point2, Vector2};
use tmm::error::Result;
use tmm::kinetostatics::{CouplingDrive, GearDrive};
use tmm::Load;

/// How the input link is driven, for its kinetostatics (the last step of the analysis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// Through a coupling on its shaft: a balancing moment (the seeds' SRWL2).
    Coupling,
    /// Through a gear pair: a balancing force of the driving pinion at the pitch point, along
    /// the line of action (the seeds' SRWL1).
    Gear {
        /// r_w, the pitch radius of the wheel on the input link, m.
        pitch_radius: f64,
        /// The polar angle of the pitch point P about O1 (fixed in the frame), rad. The seed's
        /// P lies at π (on the −x side of O1).
        pitch_angle: f64,
        /// α_w, the pressure angle of the mesh, rad, in [0, π/2).
        pressure_angle: f64,
    },
}

/// The balance of the input link: what the drive supplies and what the frame holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balance {
    /// M_b, the balancing moment about O1, N·m, counter-clockwise positive. For a gear drive
    /// it is the moment of the balancing force about O1.
    pub moment: f64,
    /// F_b, the balancing force of the pinion at the pitch point (zero for a coupling), N.
    pub force: Vector2<f64>,
    /// The pitch point P (O1 for a coupling), m.
    pub pitch_point: Point2<f64>,
    /// R01, the force of the frame on the input link at O1, N.
    pub r01: Vector2<f64>,
}

impl Balance {
    /// The drive's load on the input link, for an equilibrium check: F_b at P plus, for a
    /// coupling, the couple M_b.
    #[must_use]
    pub fn load(&self) -> Load {
        if self.force == Vector2::zeros() {
            Load::new(self.pitch_point, Vector2::zeros(), self.moment)
        } else {
            Load::force_at(self.pitch_point, self.force)
        }
    }

    /// The power the drive delivers to the input link turning at ω1 about O1: M_b·ω1 for a
    /// coupling, F_b·v_P = F_b·(ω1 × O1P) for a gear (the same number).
    #[must_use]
    pub fn power(&self, o1: Point2<f64>, omega1: f64) -> f64 {
        if self.force == Vector2::zeros() {
            self.moment * omega1
        } else {
            let r = self.pitch_point - o1;
            self.force.dot(&(omega1 * tmm::angle::perp(r)))
        }
    }
}

impl Drive {
    /// The balancing moment (or force) and the frame's reaction for the loads on the input
    /// link about O1: its own load and the reactions of the groups attached to it.
    ///
    /// # Errors
    /// As [`CouplingDrive::solve`] and [`GearDrive::solve`].
    pub fn balance(&self, o1: Point2<f64>, loads: &[Load]) -> Result<Balance> {
        match *self {
            Self::Coupling => {
                let b = CouplingDrive { o1 }.solve(loads)?;
                Ok(Balance {
                    moment: b.balancing_moment,
                    force: Vector2::zeros(),
                    pitch_point: o1,
                    r01: b.r01,
                })
            }
            Self::Gear {
                pitch_radius,
                pitch_angle,
                pressure_angle,
            } => {
                let drive = GearDrive::at_angle(o1, pitch_radius, pitch_angle, pressure_angle);
                let b = drive.solve(loads)?;
                Ok(Balance {
                    moment: b.balancing_moment,
                    force: b.force,
                    pitch_point: drive.pitch_point,
                    r01: b.r01,
                })
            }
        }
    }
}
