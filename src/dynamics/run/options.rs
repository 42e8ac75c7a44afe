//! What a run is asked: its final time and step, what it records, the quantities it watches
//! and the conditions it stops at, its budgets.

#[cfg(doc)]
use super::{run, Outcome};
#[cfg(doc)]
use crate::dynamics::{Dopri5, LagrangeSystem};
#[cfg(doc)]
use crate::error::Error;

/// A quantity a run can watch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Watch {
    /// The generalized coordinate qᵢ (i = 0 or 1).
    Coordinate(usize),
    /// The generalized speed q̇ᵢ.
    Speed(usize),
    /// The machine's i-th extra output (see [`LagrangeSystem::output_names`]), for example
    /// the carrier angle φ_H of the landing gear.
    Output(usize),
}

/// Which crossings of the value count.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Direction {
    /// From below to the value or above.
    #[default]
    Rising,
    /// From above to the value or below.
    Falling,
    /// Either way.
    Either,
}

/// Stop when a watched quantity reaches a value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// What to watch.
    pub watch: Watch,
    /// The value to reach.
    pub value: f64,
    /// Which crossings count (the start state itself never counts).
    pub direction: Direction,
}

/// Stop at a steady state: every generalized acceleration (the seed's speed increments per
/// unit time, which does not depend on the step) stays within `tol` for `hold` seconds.
///
/// The same window also detects motions that can never become steady: when the accelerations
/// stay above `tol` but change by less than `tol` over `hold` seconds, the speeds grow (or
/// fall) linearly for ever and the run ends with [`Outcome::Drifting`]. A transient whose time
/// constant is longer than about hold·|q̈|/tol is indistinguishable from such a drift over the
/// window: choose `hold` longer than the slowest time constant of the machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Steady {
    /// Tolerance on |q̈ᵢ| (rad/s² or m/s²).
    pub tol: f64,
    /// How long the condition must hold, s (positive).
    pub hold: f64,
}

/// How a run is done and when it stops. The final time always bounds the run, and so do
/// three budgets (steps, evaluations, recorded rows) whose exhaustion is an
/// [`Error::Budget`] naming the time reached: no run is endless or takes unbounded memory.
///
/// # What is recorded
/// The trajectory holds, in increasing time and each time once: the start; every
/// `record_every`-th step end (a fixed-step method's step cut short at a breakpoint or a kink
/// counts once, with its rest, so its rows stay on the grid t₀ + n·h); every requested time
/// of [`times`](Self::times) up to the stop, carrying the requested value bitwise; and the
/// last state. Breakpoints and kinks are stepped onto but recorded only as step ends.
///
/// # Examples
/// Record only the start, three requested times and the end of a run with steps of 0.3 s:
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{run, LagrangeSystem, Rk4, RunOptions, State};
/// struct Slider;
/// impl LagrangeSystem for Slider {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::identity())
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::new(2.0, 0.0))
///     }
/// }
/// let opts = RunOptions {
///     record_every: usize::MAX,
///     ..RunOptions::at_times(1.0, 0.3, vec![0.5, 0.1, 0.7])
/// };
/// let r = run(&Slider, &Rk4, State::at_rest(Vector2::zeros()), &opts).unwrap();
/// assert_eq!(r.trajectory.t(), [0.0, 0.1, 0.5, 0.7, 1.0]);
/// assert!((r.trajectory.q()[0][2] - 0.25).abs() < 1e-15); // x = t² at t = 0.5
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// The latest time, s; the run stops there if nothing else stopped it.
    pub t_end: f64,
    /// The step size (fixed-step methods) or the first proposed step (adaptive ones), s.
    pub h: f64,
    /// Record every n-th step (1 = every step); the start and the end are always recorded.
    pub record_every: usize,
    /// Stop when a quantity reaches a value.
    pub reach: Option<Reach>,
    /// Stop at a steady state.
    pub steady: Option<Steady>,
    /// The most accepted steps the run may take (default
    /// [`DEFAULT_MAX_STEPS`](Self::DEFAULT_MAX_STEPS)).
    pub max_steps: usize,
    /// The most evaluations of the accelerations the stepper may spend, rejected trial steps
    /// included (default [`DEFAULT_MAX_EVALUATIONS`](Self::DEFAULT_MAX_EVALUATIONS)). It is
    /// checked before every step and before every re-step that locates a kink or a watched
    /// value inside a step, so a run ends past it by at most the step under way (for RK4
    /// fewer than four evaluations; for Dormand–Prince that step's rejected trials too).
    pub max_evaluations: usize,
    /// The most rows the trajectory may hold, start and end included (default
    /// [`DEFAULT_MAX_ROWS`](Self::DEFAULT_MAX_ROWS)); record fewer with `record_every`.
    pub max_rows: usize,
    /// Times at which the state is recorded (default none), s: finite and within
    /// [t_start, t_end] (else an error), in any order, repeats recorded once. A method with a
    /// continuous extension ([`Dopri5`]) records them from it without changing
    /// its steps; a fixed-step method steps exactly onto each (shortening the one step that
    /// would cross it, then finishing that step). Each recorded row carries the requested
    /// time bitwise. Times after a stop condition ended the run are not recorded.
    pub times: Vec<f64>,
    /// Times at which the right-hand side is not smooth (default none), s, besides the
    /// system's own [`LagrangeSystem::breakpoints`]: every method steps exactly onto each, so
    /// that no step straddles a kink or a jump. Finite (else an error), in any order; those
    /// outside (t_start, t_end) are ignored.
    pub breakpoints: Vec<f64>,
    /// Whether to locate the nodes of the system's [`LagrangeSystem::kinks`] (default
    /// `true`): every argument's, the earliest crossing in a step first. Turned off, the run
    /// neither asks for the kinks nor evaluates their arguments, and steps across them as a
    /// solver that knows nothing of them would: for side-by-side comparisons with such a
    /// solver, or when the kinks are too mild to matter. Breakpoints are stepped onto either
    /// way.
    pub locate_kinks: bool,
}

impl RunOptions {
    /// The default step budget: ten million steps.
    pub const DEFAULT_MAX_STEPS: usize = 10_000_000;
    /// The default evaluation budget: a hundred million evaluations.
    pub const DEFAULT_MAX_EVALUATIONS: usize = 100_000_000;
    /// The default row budget: a million rows (some 100–200 MB of columns).
    pub const DEFAULT_MAX_ROWS: usize = 1_000_000;

    /// Run to `t_end` with steps `h`, recording every step, with the default budgets.
    #[must_use]
    pub fn until(t_end: f64, h: f64) -> Self {
        Self {
            t_end,
            h,
            record_every: 1,
            reach: None,
            steady: None,
            max_steps: Self::DEFAULT_MAX_STEPS,
            max_evaluations: Self::DEFAULT_MAX_EVALUATIONS,
            max_rows: Self::DEFAULT_MAX_ROWS,
            times: Vec::new(),
            breakpoints: Vec::new(),
            locate_kinks: true,
        }
    }

    /// As [`until`](Self::until), recording also the state at the requested `times` (see
    /// [`times`](Self::times)).
    ///
    /// # Examples
    /// ```
    /// use tmm::dynamics::RunOptions;
    /// let o = RunOptions::at_times(2.0, 0.01, vec![0.5, 1.5]);
    /// assert_eq!((o.t_end, o.times.len(), o.record_every), (2.0, 2, 1));
    /// ```
    #[must_use]
    pub fn at_times(t_end: f64, h: f64, times: Vec<f64>) -> Self {
        Self {
            times,
            ..Self::until(t_end, h)
        }
    }
}
