//! The entry points of a solve: a reusable [`Solver`] (the fast path: one set of buffers for
//! every position), and the one-shot [`Plan::analyse`] and [`Plan::kinematics`].

use super::analysis::Analysis;
use super::kinematics::Kinematics;
use crate::error::Result;
use crate::linkage::inputs::Inputs;
use crate::linkage::plan::Plan;

/// The buffers of one position of a plan, refilled at every position: a sweep of any length
/// allocates nothing after [`Plan::solver`]. Each solve returns a view of the buffers, valid
/// until the next.
///
/// A solver is `Send`: give each thread its own.
///
/// # Examples
/// The largest balancing moment of the Watt six-bar over 10⁴ positions:
/// ```
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::watt_six_bar())?;
/// let mut solver = plan.solver();
/// let n = 10_000;
/// let mut peak = 0.0f64;
/// for k in 0..n {
///     let a = solver.analyse(Motion::turning(k as f64 * std::f64::consts::TAU / n as f64, 10.0))?;
///     peak = peak.max(a.balance(0)?.value.abs());
/// }
/// assert!(peak > 0.0);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Solver<'p> {
    a: Analysis<'p>,
}

impl<'p> Solver<'p> {
    /// The plan it solves.
    #[must_use]
    pub fn plan(&self) -> &'p Plan {
        self.a.plan
    }

    /// Kinematics, loads, reactions and balances at one motion per input (a [`Motion`] for
    /// a linkage with one input, [`Inputs::two`] for two).
    ///
    /// # Errors
    /// Non-finite inputs, or not one motion per input; [`Error::In`](crate::Error::In)
    /// naming the group that cannot be assembled or is at a dead point, the link whose load
    /// cannot be evaluated (a non-finite inertia load, a user's load's error), the piston
    /// whose indicator diagram is read outside its stroke, or the group or input link whose
    /// closed form is singular.
    ///
    /// [`Motion`]: crate::kinematics::Motion
    #[inline]
    pub fn analyse(&mut self, inputs: impl Into<Inputs>) -> Result<&Analysis<'p>> {
        self.a.solve(inputs.into().as_slice())?;
        Ok(&self.a)
    }

    /// The kinematics alone at one motion per input: no loads, no reactions.
    ///
    /// # Errors
    /// As [`analyse`](Self::analyse), the kinematics' errors only: where an input moves, a
    /// dyad within its position's rounding of a dead point is [`Error::Singular`](crate::Error::Singular)
    /// (its rates would be rounding); a position alone (every input at rest) is given there.
    #[inline]
    pub fn kinematics(&mut self, inputs: impl Into<Inputs>) -> Result<&Kinematics<'p>> {
        self.a.k.solve_checked(inputs.into().as_slice())?;
        Ok(&self.a.k)
    }
}

impl Plan {
    /// A solver for this plan's positions: its buffers are allocated here, once, and every
    /// [`Solver::analyse`] refills them. The fast path for any number of positions.
    #[must_use]
    pub fn solver(&self) -> Solver<'_> {
        Solver {
            a: Analysis::new(self),
        }
    }

    /// Analyses one position, the one-shot convenience. Its buffers are one box, taken from
    /// the plan's spares: the plan keeps up to eight boxes that dropped results of it gave
    /// back (a box is allocated when none is free), held by the plan alone (no thread, nothing
    /// global, keeps one; a clone of the plan starts with none) and reset when taken, so the
    /// result is bit for bit that of fresh buffers. A loop of `plan.analyse` thus allocates
    /// nothing after its first call, and the result moves a pointer to its buffers, not the
    /// buffers. A reused [`solver`](Self::solver) or [`cycle`](Self::cycle) does the same
    /// work with one box and no exchange at every position: the fast path.
    ///
    /// # Errors
    /// As [`Solver::analyse`].
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let a = plan.analyse(Motion::turning(1.0, 10.0))?;
    /// assert!(a.power_check()?.relative_error() < 1e-9);
    /// assert!(a.reaction("B")?.force.norm() > 0.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    // Always inlined: in the caller's loop the 136-byte result is built where the caller
    // keeps it; called, it was built, copied into the `Result` and copied out again (two
    // `memcpy` calls that waited on the stores just made).
    #[inline(always)]
    pub fn analyse(&self, inputs: impl Into<Inputs>) -> Result<Analysis<'_>> {
        // Built where it is returned (one value returned on every path), not moved there.
        let mut r = Ok(Analysis::new(self));
        if let Ok(a) = &mut r
            && let Err(e) = a.solve(inputs.into().as_slice())
        {
            r = Err(e);
        }
        r
    }

    /// The kinematics alone at one position, the one-shot convenience (see
    /// [`analyse`](Self::analyse)). The result has no reactions to ask for.
    ///
    /// # Errors
    /// As [`Solver::kinematics`].
    #[inline(always)]
    pub fn kinematics(&self, inputs: impl Into<Inputs>) -> Result<Kinematics<'_>> {
        let mut r = Ok(Kinematics::new(self));
        if let Ok(k) = &mut r
            && let Err(e) = k.solve_checked(inputs.into().as_slice())
        {
            r = Err(e);
        }
        r
    }
}
