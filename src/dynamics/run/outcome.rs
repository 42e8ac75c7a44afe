//! What a run ends with: why it stopped, the recorded motion, the last state, its counts.

use nalgebra::Vector2;

#[cfg(doc)]
use super::{run, Reach};
use crate::dynamics::switch::SwitchLoads;
use crate::dynamics::system::{LagrangeSystem, State};
use crate::dynamics::trajectory::Trajectory;
#[cfg(doc)]
use crate::dynamics::Stepper;
use crate::error::Result;

/// Why a run stopped.
///
/// # Breaking change
/// [`Stuck`](Self::Stuck) is new, and the enum is `#[non_exhaustive]`: a `match` needs a
/// wildcard arm, so that further reasons do not break it again.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Outcome {
    /// The final time was reached (no other stop condition was asked for, or the watched
    /// value was never reached).
    FinalTime,
    /// The watched quantity reached its value at time `t` (located inside the step).
    Reached {
        /// The time of the crossing, s.
        t: f64,
    },
    /// The steady state held from `t − hold` to `t`.
    Steady {
        /// The time at which the steady state was confirmed, s.
        t: f64,
    },
    /// A steady state was asked for but can never be met: the accelerations settled to a
    /// non-zero constant, so the speeds change linearly for ever (for example the coaxial
    /// propellers with resisting moments not in the gear ratio, docs/errata.md#d41).
    Drifting {
        /// The time of the verdict, s.
        t: f64,
        /// The settled accelerations.
        acceleration: Vector2<f64>,
    },
    /// A resistance that opposes the motion holds it: at time `t` the speed of switch
    /// `switch` ([`LagrangeSystem::switches`]) reached zero (located inside the step) and
    /// the drive along it was within the resistance's breakaway loads, so the motion along
    /// that switch stops there for good (for loads that do not change with time). With one
    /// freedom the machine is at rest; with more, the others may still be moving in the
    /// run's last state (`qd` of the result): the run ends there, since it does not model a
    /// motion with one freedom held. [`SwitchLoads::stalled`] turns it into the error of a
    /// motion that had to go on.
    Stuck {
        /// The time the motion stopped, s.
        t: f64,
        /// The switch that holds it.
        switch: usize,
        /// The loads along it there.
        loads: SwitchLoads,
    },
    /// The motion jams ([`Error::Jammed`](crate::Error::Jammed)): at time `t` a joint with
    /// friction self-locks under the motion's loads and no finite reactions carry it on. The
    /// rows up to the last state (located just before `t`) are kept.
    Jammed {
        /// Its time, s: the end of the shortest step of the method from the last accepted
        /// state that jams, located by bisection to the run's time tolerance (10⁻¹² of the
        /// final time); the run's last state is the end of the longest that carries.
        t: f64,
        /// The joint that self-locks, by its index in the system's description (a
        /// linkage's [`Plan::joint_names`](crate::linkage::Plan::joint_names)).
        joint: usize,
        /// The friction's feedback det(I − J) there (at or below the threshold of
        /// self-locking).
        value: f64,
    },
    /// The machine reaches a dead centre of one of its dyads
    /// ([`Error::DeadCentre`](crate::Error::DeadCentre)), where its coordinates no longer
    /// describe the motion (a rocking input at its lock): `t` is the last state the system
    /// accepts, located inside the step that met the dead centre by halving steps of the
    /// method towards it until the accepted and the refused times are within 10⁻¹² of each
    /// other (relative to max(1, |t|)). The rows up to there are kept.
    DeadCentre {
        /// The time of the located last state, s.
        t: f64,
        /// The dyad, by its index among the plan's groups
        /// ([`Plan::groups`](crate::linkage::Plan::groups)).
        dyad: usize,
        /// Its determinant at the refused state next to it (at most
        /// [`DEAD_CENTRE_DETERMINANT`](crate::linkage::DEAD_CENTRE_DETERMINANT) in size).
        value: f64,
    },
    /// A steady state was asked for and the final time came first.
    NotSteady {
        /// The accelerations at the final time.
        acceleration: Vector2<f64>,
    },
}

/// The result of [`run`].
#[derive(Debug, Clone, PartialEq)]
pub struct RunResult {
    /// The recorded motion.
    pub trajectory: Trajectory,
    /// Why it stopped.
    pub outcome: Outcome,
    /// The last state (the located crossing for [`Outcome::Reached`], the located zero of
    /// the switch speed for [`Outcome::Stuck`]).
    pub last: State,
    /// Accepted steps taken.
    pub steps: usize,
    /// Evaluations of the accelerations spent by the stepper, the location of kinks
    /// included (the location of a [`Reach`] crossing and the recording not counted). A
    /// recorded row's q̈ that a step takes over as its first stage (see
    /// [`Stepper::uses_start_acceleration`]) counts once, as the step's: recording changes
    /// the work a run does, not this count.
    pub evaluations: usize,
}

impl RunResult {
    /// The result of a run that ends at `last` for `outcome`: `last` becomes the trajectory's
    /// last row unless it is `recorded` already (it may take the row kept free for it).
    pub(super) fn finish<S: LagrangeSystem + ?Sized>(
        sys: &S,
        traj: &mut Trajectory,
        buf: &mut Vec<f64>,
        (last, recorded): (State, bool),
        outcome: Outcome,
        (steps, evaluations): (usize, usize),
    ) -> Result<Self> {
        if !recorded {
            traj.push_with(sys, &last, buf)?;
        }
        Ok(Self {
            trajectory: std::mem::take(traj),
            outcome,
            last,
            steps,
            evaluations,
        })
    }
}
