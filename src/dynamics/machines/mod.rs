//! The four machines of seed 003, each with realistic default data documented on its
//! `Default` implementation.

mod coaxial_propellers;
mod five_bar;
mod landing_gear;
mod motor;
mod rp_arm;

pub use coaxial_propellers::CoaxialPropellers;
pub use five_bar::{FiveBar, FiveBarKinematics, Servo};
pub use landing_gear::{Failure, LandingGear};
pub use motor::LinearMotor;
pub use rp_arm::{DecoupledRpArm, RpArm};

use nalgebra::{Matrix2, Vector2};

/// A rotating link of a gear drive: its moment of inertia about its axis (or a reduced
/// translational inertia such as k·m₂·(r_w1 + r_w2)² for the planets' centres) and its speed
/// as a row of ratios, ω = s·q̇.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GearLink {
    pub inertia: f64,
    pub speed: Vector2<f64>,
}

/// The constant inertia matrix A = Σ I·s sᵀ of a gear drive (T = ½ Σ I ω²).
pub(crate) fn gear_inertia(links: &[GearLink]) -> Matrix2<f64> {
    links.iter().fold(Matrix2::zeros(), |a, l| {
        a + l.inertia * l.speed * l.speed.transpose()
    })
}
