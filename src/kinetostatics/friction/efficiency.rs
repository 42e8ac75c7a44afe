//! The instantaneous and the cycle efficiency.

use super::non_negative;
use crate::error::{finite, Result};

/// The power balance of a machine at one position: what the drive gives, what friction
/// takes, and the instantaneous efficiency η = P_useful / P_drive.
///
/// With the loads' own power P_loads (the external and inertia loads of every link, each
/// F·v_S + M·ω, negative where they resist), the balance of a machine with friction is
/// P_drive + P_loads − Σ P_lost = 0, so the useful power, the power the loads take, is
/// P_useful = −P_loads = P_drive − Σ P_lost.
///
/// Self-locking is found by the solvers (the friction equations lose their solution and the
/// solve is an error naming the joint): on the solution they return, P_lost ≥ 0, so η ≤ 1,
/// and η ≤ 0 with P_drive > 0 only where the loads themselves give power (P_useful ≤ 0).
///
/// # A negative η: the load helps the motion
/// η < 0 (with P_drive > 0) where the loads *give* power instead of taking it — a weight on
/// its way down, a link's inertia load as it slows down, a resistance whose force happens to
/// push along the motion — and friction takes more than the drive gives: P_lost = P_drive +
/// (−P_useful), the drive's power and the loads' both lost in the joints. It is neither an
/// error nor self-locking (the drive still has to push, P_drive > 0), and its size is no
/// "efficiency" in the usual sense: −η = (power the loads give)/(power the drive gives). Where
/// the loads give enough that the drive brakes or idles (P_drive ≤ 0), η has no value. Over a
/// whole steady cycle the weights' and inertia loads' work is zero, so the cycle efficiency is
/// negative only when the external loads themselves do net work on the machine.
///
/// # Examples
/// ```
/// use tmm::kinetostatics::friction::Efficiency;
/// let e = Efficiency::new(510.0, 10.0)?;
/// assert_eq!(e.useful, 500.0);
/// assert!((e.eta.unwrap() - 500.0 / 510.0).abs() < 1e-15);
/// // Over a cycle sampled at equal time steps: the works' ratio.
/// let c = Efficiency::cycle(&[e, Efficiency::new(90.0, 10.0)?]).unwrap();
/// assert!((c - 580.0 / 600.0).abs() < 1e-15);
/// // A subnormal drive power: η = −1/5e-324 leaves f64, so it has no value (never −inf).
/// assert_eq!(Efficiency::new(5e-324, 1.0)?.eta, None);
/// assert!(Efficiency::new(-1.7e308, 1.7e308).is_err()); // P_useful overflows
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Efficiency {
    /// P_drive, the power of the balancing moment or force, W.
    pub drive: f64,
    /// Σ P_lost, the power lost in the joints, W (≥ 0).
    pub lost: f64,
    /// P_useful = P_drive − Σ P_lost, W.
    pub useful: f64,
    /// η = P_useful / P_drive, or `None` where the drive gives no power (P_drive ≤ 0: the
    /// loads drive the machine, and the motor brakes it or idles) or so little that the
    /// ratio leaves the range of `f64` (a subnormal P_drive). At most 1; negative where the
    /// loads help the motion and friction takes more than the drive gives (see
    /// [`Efficiency`]'s "A negative η").
    pub eta: Option<f64>,
}

impl Efficiency {
    /// The balance from the drive's power and the power lost in the joints (the sum of the
    /// solvers' `power_lost`).
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) naming `P_drive` or `P_lost`;
    /// [`Error::OutOfRange`](crate::Error::OutOfRange) for a negative `P_lost`;
    /// [`Error::Overflow`](crate::Error::Overflow) where P_drive − P_lost leaves the range of
    /// `f64`.
    pub fn new(drive: f64, lost: f64) -> Result<Self> {
        let drive = finite("P_drive", drive)?;
        let lost = non_negative("P_lost", lost)?;
        let useful = drive - lost;
        if !useful.is_finite() {
            return Err(crate::Error::Overflow {
                what: "P_useful = P_drive − P_lost",
            });
        }
        Ok(Self {
            drive,
            lost,
            useful,
            eta: (drive > 0.0)
                .then(|| useful / drive)
                .filter(|eta| eta.is_finite()),
        })
    }

    /// The cycle efficiency from positions at equal time steps over a whole cycle: the useful
    /// work over the drive's work, Σ P_useful / Σ P_drive (the works are the sums times the
    /// step). `None` when the drive does no net work; negative when the loads do net work on
    /// the machine over the cycle and friction takes it and the drive's (see "A negative η").
    #[must_use]
    pub fn cycle(positions: &[Efficiency]) -> Option<f64> {
        let (useful, drive) = positions
            .iter()
            .fold((0.0, 0.0), |(u, d), e| (u + e.useful, d + e.drive));
        (drive > 0.0).then(|| useful / drive)
    }
}
