//! The linear mechanical characteristic M = a − b·ω of an induction motor (seed 003, eqs.
//! 85–86 and 126).

use crate::error::{computed, finite, positive, Error, Result};

/// A motor whose driving moment falls linearly with its speed: M = a − b·ω.
///
/// Built from the nominal moment and the synchronous (no-load) and nominal speeds, the line
/// passes through (ω_sync, 0) and (ω_nom, M_nom): b = M_nom/(ω_sync − ω_nom), a = b·ω_sync
/// (eqs. 85–86; docs/errata.md#d37). This is the working branch of an induction motor's
/// characteristic, extended down to standstill: the starting moment a is then the nominal
/// moment times ω_sync/(ω_sync − ω_nom), larger than a real motor gives.
///
/// # Examples
/// A 400 Hz four-pole aircraft motor: 12 000 rpm synchronous, 11 000 rpm nominal, 0.4 N·m:
/// ```
/// use tmm::dynamics::machines::LinearMotor;
/// let rpm = std::f64::consts::PI / 30.0;
/// let m = LinearMotor::from_nominal(0.4, 12_000.0 * rpm, 11_000.0 * rpm).unwrap();
/// assert!((m.torque(11_000.0 * rpm).unwrap() - 0.4).abs() < 1e-12);
/// assert!(m.torque(12_000.0 * rpm).unwrap().abs() < 1e-12);
/// assert!((m.a - 4.8).abs() < 1e-12); // 12 × nominal at standstill
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearMotor {
    /// The moment at standstill, N·m.
    pub a: f64,
    /// The slope, N·m·s/rad.
    pub b: f64,
}

impl LinearMotor {
    /// The characteristic through (ω_sync, 0) and (ω_nom, M_nom).
    ///
    /// # Errors
    /// [`Error::NonPositive`] for a non-positive moment or speed; [`Error::OutOfRange`] when
    /// the nominal speed is not below the synchronous one; [`Error::Overflow`] when the slope
    /// or the starting moment overflows (or the slope underflows to zero).
    pub fn from_nominal(m_nom: f64, omega_sync: f64, omega_nom: f64) -> Result<Self> {
        positive("M_nom", m_nom)?;
        positive("omega_sync", omega_sync)?;
        positive("omega_nom", omega_nom)?;
        if omega_nom >= omega_sync {
            return Err(Error::OutOfRange {
                name: "omega_nom",
                value: omega_nom,
                min: 0.0,
                max: omega_sync,
                ends: crate::Ends::Open,
            });
        }
        let b = computed("motor slope b", m_nom / (omega_sync - omega_nom))?;
        if b == 0.0 {
            return Err(Error::Overflow {
                what: "motor slope b (underflows to zero)",
            });
        }
        Ok(Self {
            a: computed("motor starting moment a", b * omega_sync)?,
            b,
        })
    }

    /// Checks the characteristic: finite a and b.
    ///
    /// # Errors
    /// [`Error::NonFinite`] naming the coefficient that is not finite.
    pub fn check(&self) -> Result<()> {
        finite("motor a", self.a)?;
        finite("motor b", self.b)?;
        Ok(())
    }

    /// The driving moment at the shaft speed ω, N·m.
    ///
    /// # Errors
    /// As [`check`](Self::check); [`Error::NonFinite`] for a non-finite ω;
    /// [`Error::Overflow`] when the moment overflows.
    pub fn torque(&self, omega: f64) -> Result<f64> {
        self.check()?;
        finite("omega", omega)?;
        computed("motor moment a - b*omega", self.a - self.b * omega)
    }
}
