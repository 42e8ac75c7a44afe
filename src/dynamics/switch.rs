//! Velocity-sign switches: resistances that oppose a motion (dry friction, a constant
//! resisting moment) and so jump where the speed they oppose changes sign.

use crate::error::{finite, Error, Result};

/// The loads along a velocity-sign switch where its speed σ vanishes, as a system gives them
/// ([`LagrangeSystem::switch_loads`](super::LagrangeSystem::switch_loads)) and
/// [`run`](super::run) weighs them.
///
/// A resistance that opposes σ is a set-valued force at σ = 0: anything from −`forward` to
/// `backward` (along σ) when the motion is at rest there, `−forward` once σ > 0 and
/// `+backward` once σ < 0. Where σ reaches zero the motion either *sticks* (the drive, every
/// other force along σ, lies within what the resistance can hold: −backward ≤ drive ≤
/// forward) or goes on with σ of the drive's sign (the resistance cannot hold it: a reversal,
/// or a motion that never stopped). All three numbers are in the units of the generalized
/// force along σ (N·m for a crank, N for a slide), named by [`unit`](Self::unit).
///
/// # Examples
/// A block on a ramp pushed down the slope by 3 N, held by friction of up to 5 N either way:
/// it sticks; pushed by 6 N it slides.
/// ```
/// use tmm::dynamics::SwitchLoads;
/// let held = SwitchLoads { what: "block", unit: "N", drive: -3.0, forward: 5.0, backward: 5.0 };
/// assert!(held.holds() && held.breakaway() == 5.0);
/// assert!(!SwitchLoads { drive: -6.0, ..held }.holds());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwitchLoads {
    /// What moves along σ, for messages (for example `"crank"`).
    pub what: &'static str,
    /// The unit of the loads, for messages (`"N·m"` or `"N"`).
    pub unit: &'static str,
    /// The generalized force along σ of everything but the switch's resistance at the state
    /// (motors, gravity, the other loads): positive drives σ positive.
    pub drive: f64,
    /// The resistance's magnitude against σ > 0 (its breakaway load that way), ≥ 0.
    pub forward: f64,
    /// The resistance's magnitude against σ < 0, ≥ 0.
    pub backward: f64,
}

impl SwitchLoads {
    /// Whether the resistance holds the motion at σ = 0 against the drive
    /// (−backward ≤ drive ≤ forward; a drive exactly at the breakaway load does not break
    /// away).
    #[must_use]
    pub fn holds(&self) -> bool {
        -self.backward <= self.drive && self.drive <= self.forward
    }

    /// The breakaway load in the direction the drive pushes: `forward` for a drive ≥ 0, else
    /// `backward`.
    #[must_use]
    pub fn breakaway(&self) -> f64 {
        if self.drive >= 0.0 {
            self.forward
        } else {
            self.backward
        }
    }

    /// Checks the loads a system handed over: every one finite, the breakaway loads ≥ 0 (a
    /// run weighs them, and a stuck run returns them).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming the load.
    pub(crate) fn checked(self) -> Result<Self> {
        finite("drive along a switch (switch_loads)", self.drive)?;
        for (name, v) in [
            (
                "forward breakaway load of a switch (switch_loads)",
                self.forward,
            ),
            (
                "backward breakaway load of a switch (switch_loads)",
                self.backward,
            ),
        ] {
            finite(name, v)?;
            if v < 0.0 {
                return Err(Error::OutOfRange {
                    name,
                    value: v,
                    min: 0.0,
                    max: f64::INFINITY,
                    ends: crate::Ends::Closed,
                });
            }
        }
        Ok(self)
    }

    /// The error of a motion that must go on (a turn of a crank) and stuck at time `time`
    /// instead: [`Error::Stalled`] naming both loads.
    #[must_use]
    pub fn stalled(&self, time: f64) -> Error {
        Error::Stalled {
            time,
            drive: self.drive.abs(),
            resistance: self.breakaway(),
            unit: self.unit,
        }
    }
}
