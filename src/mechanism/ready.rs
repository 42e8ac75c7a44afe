//! What every ready mechanism offers, written once: its description, and from it the plan and
//! the strokes of its output.

use crate::error::Result;
use crate::kinematics::{Rotation, Strokes};
use crate::linkage::{Linkage, Output, Plan};

/// A ready mechanism: a plain struct of SI parameters that writes its own
/// [`Linkage`] description. Each implementation gives its description and its output; the
/// plan and the strokes follow from them the same way for every mechanism.
///
/// The methods are the trait's: bring it into scope with `use tmm::mechanism::Mechanism`.
///
/// # Examples
/// A parallelogram four-bar (crank = rocker, coupler = frame) has a dead point where all
/// links are collinear, at φ1 = 0: the position fails naming the group.
/// ```
/// use nalgebra::Point2;
/// use tmm::{kinematics::Motion, mechanism::{FourBar, Mechanism}, Error};
/// let m = FourBar { o3: Point2::new(0.3, 0.0), l1: 0.1, l2: 0.3, l3: 0.1, ..FourBar::course_example() };
/// let plan = m.plan()?;
/// let e = plan.analyse(Motion::new(0.0, 10.0, 0.0)).unwrap_err();
/// assert!(matches!(e, Error::In { ref part, .. } if part == "group (coupler, rocker) RRR"));
/// assert!(plan.analyse(Motion::new(1.0, 10.0, 0.0)).is_ok());
/// # Ok::<(), tmm::Error>(())
/// ```
pub trait Mechanism {
    /// The description for the engine, in a reference pose computed from the parameters (a
    /// crank angle where the mechanism assembles in the assembly modes its `branch` fields
    /// give). A description the engine would refuse is an error, never an `Ok` holding a
    /// NaN or an infinity: if the mechanism assembles nowhere, the pose's joints are not
    /// finite and the error (that of [`Plan::new`]) names the joint.
    ///
    /// # Errors
    /// A parameter that no description can state (each implementation names its own); any
    /// error of [`Plan::new`] on the description.
    fn linkage(&self) -> Result<Linkage>;

    /// The output whose strokes [`Mechanism::strokes`] finds: the rocker's angle, a piston's
    /// slide, ….
    fn output(&self) -> Output;

    /// The plan of [`Mechanism::linkage`], ready to analyse any position with
    /// [`Plan::analyse`].
    ///
    /// # Errors
    /// As [`Mechanism::linkage`] and [`Plan::new`].
    fn plan(&self) -> Result<Plan> {
        Plan::new(&self.linkage()?)
    }

    /// The strokes of [`Mechanism::output`] for a crank turning in the sense `rotation` (its
    /// extreme positions found on the first transfer function, the working stroke the longer
    /// one).
    ///
    /// # Errors
    /// As [`Mechanism::plan`] and [`Plan::strokes`].
    fn strokes(&self, rotation: Rotation) -> Result<Strokes> {
        self.plan()?.strokes(&self.output(), rotation)
    }
}

/// `l` when the engine plans it, else the plan's error: what every ready mechanism's
/// [`Mechanism::linkage`] returns, so that a description with a non-finite number (a pose
/// that assembles nowhere, a parameter that overflows) is an error, not an `Ok`.
pub(crate) fn planned(l: Linkage) -> Result<Linkage> {
    Plan::new(&l)?;
    Ok(l)
}
