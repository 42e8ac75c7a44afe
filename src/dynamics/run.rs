//! Running a machine until a stop condition: a final time, a watched quantity reaching a
//! value (located inside the step), or a steady state.

use nalgebra::{Matrix2, Vector2};

use super::stepper::{Advance, Handover, Stepper};
use super::system::{accelerations, LagrangeSystem, LagrangeTerms, State};
use super::trajectory::Trajectory;
use crate::error::{finite, positive, Error, Result};

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
    /// continuous extension ([`Dopri5`](super::Dopri5)) records them from it without changing
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

/// Why a run stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// The last state (the located crossing for [`Outcome::Reached`]).
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

fn watched<S: LagrangeSystem + ?Sized>(
    sys: &S,
    w: Watch,
    s: &State,
    buf: &mut Vec<f64>,
) -> Result<f64> {
    Ok(match w {
        Watch::Coordinate(i) => s.q[i],
        Watch::Speed(i) => s.qd[i],
        Watch::Output(i) => {
            buf.clear();
            sys.outputs(s.t, &s.q, &s.qd, buf)?;
            // A system whose outputs are fewer than its output names: an error, not a panic.
            *buf.get(i).ok_or(Error::OutOfRange {
                name: "watched output index (outputs given by the system)",
                value: i as f64,
                min: 0.0,
                max: buf.len() as f64 - 1.0,
                ends: crate::Ends::Closed,
            })?
        }
    })
}

fn crosses(d: Direction, g0: f64, g1: f64) -> bool {
    match d {
        Direction::Rising => g0 < 0.0 && g1 >= 0.0,
        Direction::Falling => g0 > 0.0 && g1 <= 0.0,
        Direction::Either => (g0 < 0.0 && g1 >= 0.0) || (g0 > 0.0 && g1 <= 0.0),
    }
}

/// The evaluations a run may still spend (`left` of its budget `limit`): locating a state
/// inside a step stops at the budget as stepping does, rather than overshooting it by up to a
/// hundred re-steps per located state.
#[derive(Clone, Copy)]
struct Allowance {
    left: usize,
    limit: usize,
}

impl Allowance {
    /// What is left of `opts`' evaluation budget after `spent`.
    fn after(opts: &RunOptions, spent: usize) -> Self {
        Self {
            left: opts.max_evaluations.saturating_sub(spent),
            limit: opts.max_evaluations,
        }
    }
}

/// Finds the state inside the step s0 → s1 at which g (f0 = g(s0), f1 = g(s1) of opposite
/// signs) vanishes, by re-stepping from s0 with θh (regula falsi, Illinois variant): the
/// located state is a true state of the method, not an interpolation. Also returns the
/// number of re-steps. A `guess` of θ in (0, 1) (from a continuous extension) is tried first.
fn locate<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    (s0, f0): (&State, f64),
    (s1, f1): (&State, f64),
    guess: Option<f64>,
    allowance: Allowance,
    mut g: impl FnMut(&State) -> Result<f64>,
) -> Result<(State, usize)> {
    let h = s1.t - s0.t;
    if f1 == 0.0 {
        return Ok((*s1, 0));
    }
    let mut resteps: usize = 0;
    let (mut a, mut fa, mut b, mut fb) = (0.0_f64, f0, 1.0_f64, f1);
    let mut best = *s1;
    let scale = f0.abs().max(f1.abs()).max(1e-300);
    let mut guess = guess.filter(|c| *c > 0.0 && *c < 1.0);
    for _ in 0..100 {
        let chord = ((a * fb - b * fa) / (fb - fa)).clamp(a.min(b), a.max(b));
        let c = guess.take().unwrap_or(chord);
        if c <= 0.0 {
            break;
        }
        if (resteps + 1).saturating_mul(method.evaluations_per_step()) > allowance.left {
            return Err(Error::Budget {
                what: "evaluation",
                limit: allowance.limit,
                time: s0.t,
            });
        }
        let sc = method.step(sys, s0, c * h)?;
        resteps += 1;
        let fc = g(&sc)?;
        best = sc;
        if fc.abs() <= 1e-14 * scale || (b - a).abs() * h <= 1e-15 * s0.t.abs().max(h) {
            break;
        }
        if fc * fb < 0.0 {
            (a, fa) = (b, fb);
        } else {
            fa *= 0.5;
        }
        (b, fb) = (c, fc);
    }
    Ok((best, resteps))
}

/// Sorted finite values, each once; an error names the first non-finite one.
fn sorted_finite(name: &'static str, v: impl IntoIterator<Item = f64>) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for x in v {
        finite(name, x)?;
        out.push(x);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    Ok(out)
}

/// The first node of argument `k` crossed strictly by a step from σ0 to σ1 (in the direction
/// of motion), other than the (argument, node) pairs in `skip` (those the step starts on or
/// was cut short onto).
fn first_crossed(
    nodes: &[f64],
    s0: f64,
    s1: f64,
    k: usize,
    skip: &[(usize, usize)],
) -> Option<usize> {
    let crossed = |i: &usize| {
        let l = nodes[*i];
        !skip.contains(&(k, *i)) && ((s0 < l && l < s1) || (s1 < l && l < s0))
    };
    if s1 >= s0 {
        (0..nodes.len()).find(crossed)
    } else {
        (0..nodes.len()).rev().find(crossed)
    }
}

/// An error when one more row (other than the end's) would leave no row for the end.
fn row_budget(len: usize, opts: &RunOptions, t: f64, t_tol: f64) -> Result<()> {
    if len + 1 >= opts.max_rows && (opts.t_end - t) > t_tol {
        return Err(Error::Budget {
            what: "recorded row",
            limit: opts.max_rows,
            time: t,
        });
    }
    Ok(())
}

/// Runs `sys` from `start` with `method` until a stop condition of `opts`.
///
/// No step straddles a breakpoint: the run shortens the step that would cross one of the
/// times in [`RunOptions::breakpoints`] or [`LagrangeSystem::breakpoints`] so that it ends
/// exactly there. When a step carries one or more of the
/// [`LagrangeSystem::kink_arguments`] across a node of its own (argument k's nodes are
/// [`LagrangeSystem::kinks`]`()[k]`), the run finds the earliest of these crossings (from the
/// continuous extension by bisection when the method has one, else by locating each),
/// locates it inside the step (re-stepping from its start, regula falsi, to about 10⁻¹⁴ of
/// the argument's change over the step) and takes the step again to end there (with error
/// control for an adaptive method); the next step, starting on that node, finds the next
/// crossing. A fixed-step method then finishes the grid step it was taking, so its grid
/// t₀ + n·h stays. The states at [`RunOptions::times`] are recorded as that field says.
///
/// # Errors
/// [`Error::NonPositive`]/[`Error::NonFinite`] for a bad step, final time, steady tolerance
/// or hold, or record interval; [`Error::NonFinite`] for a requested time, a breakpoint or a
/// kink node that is not finite; [`Error::OutOfRange`] for a requested time outside
/// [t_start, t_end] or a watched index that does not exist; [`Error::NonFiniteState`] when
/// a kink argument is not finite (or is left unset by the system);
/// [`Error::Singular`] when a step is too short to advance the time
/// (h below the rounding of t); [`Error::NonFiniteState`] naming the time when the motion
/// diverges (or a recorded quantity overflows); [`Error::Budget`] naming the time reached
/// when the steps, evaluations or rows of `opts` run out (or [`Error::OutOfRange`] for a row
/// budget below 2); any error of the system or the method.
///
/// # Examples
/// A 1 kg slider pushed by 2 N from rest reaches x = 1 m at t = 1 s; with steps of 0.3 s the
/// crossing is still found at t = 1 s (inside the fourth step), not at t = 1.2 s:
/// ```
/// use nalgebra::{Matrix2, Vector2};
/// use tmm::dynamics::{run, Direction, LagrangeSystem, Outcome, Reach, Rk4, RunOptions, State, Watch};
/// struct Slider;
/// impl LagrangeSystem for Slider {
///     fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
///         Ok(Matrix2::identity())
///     }
///     fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
///         Ok(Vector2::new(2.0, 0.0))
///     }
/// }
/// let mut opts = RunOptions::until(5.0, 0.3);
/// opts.reach = Some(Reach { watch: Watch::Coordinate(0), value: 1.0, direction: Direction::Rising });
/// let r = run(&Slider, &Rk4, State::at_rest(Vector2::zeros()), &opts).unwrap();
/// let Outcome::Reached { t } = r.outcome else { panic!() };
/// assert!((t - 1.0).abs() < 1e-12 && (r.last.q[0] - 1.0).abs() < 1e-12);
/// ```
pub fn run<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    start: State,
    opts: &RunOptions,
) -> Result<RunResult> {
    positive("step size h", opts.h)?;
    finite("t_end", opts.t_end)?;
    positive("t_end - t_start", opts.t_end - start.t)?;
    positive("record_every", opts.record_every as f64)?;
    positive("max_steps", opts.max_steps as f64)?;
    positive("max_evaluations", opts.max_evaluations as f64)?;
    // The start and the end are always recorded.
    if opts.max_rows < 2 {
        return Err(Error::OutOfRange {
            name: "max_rows",
            value: opts.max_rows as f64,
            min: 2.0,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    if !start.is_finite() {
        return Err(Error::NonFiniteState { time: start.t });
    }
    if let Some(r) = &opts.reach {
        finite("reach value", r.value)?;
        let (i, n) = match r.watch {
            Watch::Coordinate(i) | Watch::Speed(i) => (i, 2),
            Watch::Output(i) => (i, sys.output_names().len()),
        };
        if i >= n {
            return Err(Error::OutOfRange {
                name: "watched index",
                value: i as f64,
                min: 0.0,
                max: n as f64 - 1.0,
                ends: crate::Ends::Closed,
            });
        }
    }
    if let Some(st) = &opts.steady {
        positive("steady tolerance", st.tol)?;
        // Zero would also turn any two steps with equal accelerations into a drift verdict.
        positive("steady hold", st.hold)?;
    }

    // Requested times: the start is recorded anyway.
    let times = sorted_finite("requested time", opts.times.iter().copied())?;
    if let Some(&t) = times.iter().find(|&&t| !(t >= start.t && t <= opts.t_end)) {
        return Err(Error::OutOfRange {
            name: "requested time",
            value: t,
            min: start.t,
            max: opts.t_end,
            ends: crate::Ends::Closed,
        });
    }
    let times: Vec<f64> = times.into_iter().filter(|&t| t > start.t).collect();
    let breaks: Vec<f64> = sorted_finite(
        "breakpoint",
        opts.breakpoints.iter().copied().chain(sys.breakpoints()),
    )?
    .into_iter()
    .filter(|&t| t > start.t && t < opts.t_end)
    .collect();
    // The nodes of each kink argument (none at all when they are not located).
    let kinks: Vec<Vec<f64>> = if opts.locate_kinks {
        sys.kinks()
            .into_iter()
            .map(|nodes| sorted_finite("kink", nodes))
            .collect::<Result<_>>()?
    } else {
        Vec::new()
    };
    let any_kinks = kinks.iter().any(|nodes| !nodes.is_empty());
    // The times a step must end on: the breakpoints, and the requested times for a method
    // that cannot interpolate.
    let dense_times = method.has_dense_output();
    let stops = if dense_times {
        breaks
    } else {
        sorted_finite(
            "requested time",
            breaks.into_iter().chain(times.iter().copied()),
        )?
    };
    let adaptive = method.is_adaptive();

    // The outputs of a watched state and of every recorded row, one buffer for the run.
    let mut buf = Vec::new();
    let mut traj = Trajectory::for_system(sys);
    let a_start = traj.push_with(sys, &start, &mut buf)?;
    let mut s = start;
    let mut h = opts.h;
    let (mut steps, mut evaluations) = (0usize, 0usize);
    let mut g_prev = match &opts.reach {
        Some(r) => watched(sys, r.watch, &s, &mut buf)? - r.value,
        None => 0.0,
    };
    let mut steady_since: Option<f64> = None;
    let mut drift_ref: Option<(f64, Vector2<f64>)> = None;
    // The end counts as reached within rounding of the times (not of h: a step longer than
    // the whole run must still take the run to its end).
    let t_tol = 1e-12 * opts.t_end.abs().max(start.t.abs());
    // What the last step handed on for the next one: q̈ at `s` when it gave them
    // (Dormand–Prince's last stage) and its error norm (the step-size controller's memory).
    let mut hand_s = Handover::default();
    // A recorded row's q̈ are those a method's first stage would evaluate at the same state:
    // to a method that takes them, the row hands them on when the step before did not.
    // `row_handed` says that the next step's q̈ at its start came from a row, an evaluation
    // the run counts when that step is taken (so that counts do not depend on recording).
    let takes_rows = method.uses_start_acceleration();
    let mut row_handed = takes_rows;
    if takes_rows {
        hand_s.acceleration = Some(a_start);
    }
    // Every kink argument at a state, into `out` (one entry per argument, each set to NaN
    // first so that one the system leaves unset is caught as not finite).
    let kink_args = |st: &State, out: &mut [f64]| -> Result<()> {
        out.fill(f64::NAN);
        sys.kink_arguments(st.t, &st.q, &st.qd, out)?;
        if out.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Error::NonFiniteState { time: st.t })
        }
    };
    // The arguments at the start of the step (σ), at its end (σ₁), and at a trial state.
    let (mut sigma, mut sigma1, mut probe) = (
        vec![0.0; kinks.len()],
        vec![0.0; kinks.len()],
        vec![0.0; kinks.len()],
    );
    if any_kinks {
        kink_args(&s, &mut sigma)?;
    }
    // The crossings (argument, node) found in a step.
    let mut crossed: Vec<(usize, usize)> = Vec::new();
    // The (argument, node) the last step landed on (the next step starts there: no crossing).
    let mut on_kink: Vec<(usize, usize)> = Vec::new();
    // The end of the grid step a fixed-step method was taking when a stop or a kink cut it.
    let mut grid_end: Option<f64> = None;
    // Grid steps left until the next recorded one (a countdown rather than a division per
    // step: every `record_every`-th grid step is recorded).
    let (mut i_stop, mut i_time, mut until_record) = (0usize, 0usize, opts.record_every);

    let finish = |traj: &mut Trajectory,
                  buf: &mut Vec<f64>,
                  last: State,
                  recorded: bool,
                  outcome: Outcome,
                  steps: usize,
                  evaluations: usize|
     -> Result<RunResult> {
        if !recorded {
            // The end may take the row kept free for it.
            traj.push_with(sys, &last, buf)?;
        }
        Ok(RunResult {
            trajectory: std::mem::take(traj),
            outcome,
            last,
            steps,
            evaluations,
        })
    };

    // A run with nothing to stop at or watch on the way takes its interior steps in
    // `lean_steps`; the step that reaches the end, and every step of any other run, is the
    // full loop's.
    let plain = stops.is_empty()
        && times.is_empty()
        && !any_kinks
        && opts.reach.is_none()
        && opts.steady.is_none();

    loop {
        if plain && grid_end.is_none() {
            let mut lean = Lean {
                s,
                h,
                hand: hand_s,
                steps,
                evaluations,
                until_record,
                row_handed,
            };
            lean_steps(
                sys, method, opts, t_tol, takes_rows, &mut lean, &mut traj, &mut buf,
            )?;
            Lean {
                s,
                h,
                hand: hand_s,
                steps,
                evaluations,
                until_record,
                row_handed,
            } = lean;
        }

        let remaining = opts.t_end - s.t;
        if remaining <= t_tol {
            let outcome = match &opts.steady {
                Some(_) => Outcome::NotSteady {
                    acceleration: match hand_s.acceleration {
                        Some(a) => a,
                        None => accelerations(sys, s.t, &s.q, &s.qd)?,
                    },
                },
                None => Outcome::FinalTime,
            };
            let recorded = traj.t().last() == Some(&s.t);
            return finish(
                &mut traj,
                &mut buf,
                s,
                recorded,
                outcome,
                steps,
                evaluations,
            );
        }
        budgets(opts, steps, evaluations, s.t)?;
        while i_stop < stops.len() && stops[i_stop] <= s.t + t_tol {
            i_stop += 1;
        }
        let stop = stops.get(i_stop).map_or(opts.t_end, |&t| t.min(opts.t_end));
        let remaining = stop - s.t;
        let goal = grid_end.take();
        let h_want = goal.map_or(h, |g| g - s.t);
        let clamped = h_want >= remaining;
        let h_try = if clamped { remaining } else { h_want };
        // A fixed-step method cut short by a stop goes on to the end of its grid step.
        if clamped && !adaptive && h_want - remaining > t_tol {
            grid_end = Some(goal.unwrap_or(s.t + h));
        }
        // A step that ends on a stop integrates up to it from the left: a force that jumps
        // there (written `if t < t_b`) is evaluated at its value before the jump in the
        // step's last stages, and at its new value from the next step on.
        // The continuous extension is built only when something will read it: a requested
        // time still ahead, or a kink to locate (its first guess).
        let want_dense = i_time < times.len() || any_kinks;
        let (adv, mut dense) = match (clamped, want_dense) {
            (true, true) => {
                method.advance_dense(&LeftOf { sys, at: stop }, &s, h_try, Some(hand_s))?
            }
            (true, false) => (
                method.advance_from(&LeftOf { sys, at: stop }, &s, h_try, Some(hand_s))?,
                None,
            ),
            (false, true) => method.advance_dense(sys, &s, h_try, Some(hand_s))?,
            (false, false) => (method.advance_from(sys, &s, h_try, Some(hand_s))?, None),
        };
        let (mut s1, mut hand1) = accept(&s, &adv, &mut steps, &mut evaluations, &mut row_handed)?;
        // The whole step asked for was taken: it ends on the stop or the grid point.
        let full = s1.t == s.t + h_try;
        let target = if clamped { Some(stop) } else { goal };
        if let Some(t) = target.filter(|_| full) {
            if s1.t != t {
                s1.t = t;
                hand1.acceleration = None; // they belong to the unsnapped time
            }
            if clamped && stop < opts.t_end {
                // A breakpoint: the forces after it may differ, so neither the accelerations
                // nor the error of the step before it carry over.
                hand1 = Handover::default();
            }
        }
        snap_to_end(opts, t_tol, &mut s1, &mut hand1);
        if let Some(d) = dense.as_mut() {
            d.set_end(s1.t);
        }
        // The method's proposal, unless the run shortened the step.
        let mut h_next = (!(target.is_some() && full)).then_some(adv.h_next);

        // Nodes of the kink arguments crossed inside the step: step again, exactly onto the
        // earliest crossing (the next step finds the next one).
        if any_kinks {
            // The (argument, node) pairs a crossing must not be taken for: those the step
            // starts on (found so, or located within rounding of its start) and those it has
            // already been cut short onto. Each pass of the loop either ends it or adds one
            // pair, so it ends after at most as many passes as there are nodes.
            let mut skip = std::mem::take(&mut on_kink);
            let mut landed = None;
            loop {
                kink_args(&s1, &mut sigma1)?;
                crossed.clear();
                for (k, nodes) in kinks.iter().enumerate() {
                    if let Some(i) = first_crossed(nodes, sigma[k], sigma1[k], k, &skip) {
                        crossed.push((k, i));
                    }
                }
                if crossed.is_empty() {
                    break;
                }
                // Whether argument k has passed node i at a state whose arguments are `v`.
                let passed = |v: &[f64], (k, i): (usize, usize)| {
                    let node = kinks[k][i];
                    (v[k] < node) != (sigma[k] < node)
                };
                let ((k, i), hit, resteps) = match &dense {
                    // The earliest crossing from the continuous extension (no evaluation), by
                    // bisection on "some argument has passed its node", then located from
                    // there as a first guess.
                    Some(d) => {
                        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
                        let mut first = crossed[0];
                        for _ in 0..60 {
                            let mid = 0.5 * (lo + hi);
                            kink_args(&d.at(s.t + mid * (s1.t - s.t))?, &mut probe)?;
                            match crossed.iter().find(|&&c| passed(&probe, c)) {
                                Some(&c) => {
                                    first = c;
                                    hi = mid;
                                }
                                None => lo = mid,
                            }
                        }
                        let node = kinks[first.0][first.1];
                        let (hit, resteps) = locate(
                            sys,
                            method,
                            (&s, sigma[first.0] - node),
                            (&s1, sigma1[first.0] - node),
                            Some(0.5 * (lo + hi)),
                            Allowance::after(opts, evaluations),
                            |st| {
                                kink_args(st, &mut probe)?;
                                Ok(probe[first.0] - node)
                            },
                        )?;
                        (first, hit, resteps)
                    }
                    // No extension: each crossing located by re-stepping, the earliest kept.
                    None => {
                        let mut earliest: Option<((usize, usize), State)> = None;
                        let mut resteps: usize = 0;
                        for &(k, i) in &crossed {
                            let node = kinks[k][i];
                            let (hit, n) = locate(
                                sys,
                                method,
                                (&s, sigma[k] - node),
                                (&s1, sigma1[k] - node),
                                None,
                                Allowance::after(
                                    opts,
                                    evaluations.saturating_add(
                                        resteps.saturating_mul(method.evaluations_per_step()),
                                    ),
                                ),
                                |st| {
                                    kink_args(st, &mut probe)?;
                                    Ok(probe[k] - node)
                                },
                            )?;
                            resteps += n;
                            if earliest.is_none_or(|(_, e)| hit.t < e.t) {
                                earliest = Some(((k, i), hit));
                            }
                        }
                        match earliest {
                            Some((c, hit)) => (c, hit, resteps),
                            None => break, // not reached: `crossed` is not empty
                        }
                    }
                };
                evaluations = evaluations
                    .saturating_add(resteps.saturating_mul(method.evaluations_per_step()));
                skip.push((k, i));
                let hk = hit.t - s.t;
                if hk <= t_tol {
                    // Within rounding of the start: the step starts on this node; look again
                    // for the crossings after it.
                    continue;
                }
                if hit.t >= s1.t {
                    landed = Some((k, i));
                    break;
                }
                // Cut the step short onto the crossing, then check that no other crossing
                // (missed by the extension's first guess) lies before it.
                if Allowance::after(opts, evaluations).left < method.evaluations_per_step() {
                    return Err(Error::Budget {
                        what: "evaluation",
                        limit: opts.max_evaluations,
                        time: s.t,
                    });
                }
                let (adv2, dense2) = method.advance_dense(sys, &s, hk, Some(hand_s))?;
                evaluations = evaluations.saturating_add(adv2.evaluations);
                if !adaptive && grid_end.is_none() {
                    grid_end = Some(s1.t);
                }
                s1 = adv2.state;
                dense = dense2;
                hand1 = adv2.handover;
                if s1.t == s.t + hk {
                    landed = Some((k, i));
                    h_next = None;
                } else {
                    landed = None;
                    h_next = Some(adv2.h_next);
                }
            }
            // σ at the step's end is where the next step starts.
            std::mem::swap(&mut sigma, &mut sigma1);
            on_kink = landed.into_iter().collect();
        }
        if let Some(hn) = h_next {
            h = hn;
        }

        let mut hit = None;
        if let Some(r) = &opts.reach {
            let g1 = watched(sys, r.watch, &s1, &mut buf)? - r.value;
            if crosses(r.direction, g_prev, g1) {
                let (located, resteps) = locate(
                    sys,
                    method,
                    (&s, g_prev),
                    (&s1, g1),
                    None,
                    Allowance::after(opts, evaluations),
                    |st| Ok(watched(sys, r.watch, st, &mut buf)? - r.value),
                )?;
                evaluations = evaluations
                    .saturating_add(resteps.saturating_mul(method.evaluations_per_step()));
                hit = Some(located);
            }
            g_prev = g1;
        }

        // The requested times inside the step (up to a located stop).
        let t_lim = hit.map_or(s1.t, |x| x.t);
        let mut at_end = false;
        while i_time < times.len() && times[i_time] <= t_lim {
            let tau = times[i_time];
            i_time += 1;
            if tau == s1.t {
                at_end = true;
                continue;
            }
            if hit.is_some_and(|x| x.t == tau) {
                continue; // the located stop is the last row anyway
            }
            let st = match &dense {
                Some(d) => d.at(tau)?,
                // A method without an extension steps onto each requested time; should one
                // fall inside a step all the same, one step from its start gives it.
                None => State {
                    t: tau,
                    ..method.step(sys, &s, tau - s.t)?
                },
            };
            row_budget(traj.len(), opts, tau, t_tol)?;
            traj.push_with(sys, &st, &mut buf)?;
        }
        if let Some(located) = hit {
            let outcome = Outcome::Reached { t: located.t };
            return finish(
                &mut traj,
                &mut buf,
                located,
                false,
                outcome,
                steps,
                evaluations,
            );
        }

        // Steps cut short on the grid of a fixed-step method count once, with their rest.
        let mut on_grid_record = false;
        if grid_end.is_none() {
            until_record -= 1;
            if until_record == 0 {
                until_record = opts.record_every;
                on_grid_record = true;
            }
        }
        let mut recorded = false;
        if at_end || on_grid_record {
            // One row stays free for the end.
            row_handed = record_end(
                sys, opts, t_tol, takes_rows, &s1, &mut hand1, &mut traj, &mut buf,
            )?;
            recorded = true;
        }
        hand_s = hand1;

        if let Some(st) = &opts.steady {
            let acc = match hand_s.acceleration {
                Some(a) => a,
                None => accelerations(sys, s1.t, &s1.q, &s1.qd)?,
            };
            if acc.amax() <= st.tol {
                drift_ref = None;
                let since = *steady_since.get_or_insert(s1.t);
                if s1.t - since >= st.hold {
                    return finish(
                        &mut traj,
                        &mut buf,
                        s1,
                        recorded,
                        Outcome::Steady { t: s1.t },
                        steps,
                        evaluations,
                    );
                }
            } else {
                steady_since = None;
                match drift_ref {
                    Some((t0, a0)) if (acc - a0).amax() <= st.tol => {
                        if s1.t - t0 >= st.hold {
                            let outcome = Outcome::Drifting {
                                t: s1.t,
                                acceleration: acc,
                            };
                            return finish(
                                &mut traj,
                                &mut buf,
                                s1,
                                recorded,
                                outcome,
                                steps,
                                evaluations,
                            );
                        }
                    }
                    _ => drift_ref = Some((s1.t, acc)),
                }
            }
        }
        s = s1;
    }
}

/// What the lean loop of [`run`] carries from step to step.
#[derive(Clone, Copy)]
struct Lean {
    s: State,
    h: f64,
    hand: Handover,
    steps: usize,
    evaluations: usize,
    until_record: usize,
    row_handed: bool,
}

/// The interior steps of a run with nothing to stop at or watch on the way (no
/// breakpoints, requested times, kinks, reach or steady state): what the full loop of
/// [`run`] does for such a step, without carrying every feature's state through each step
/// (that cost some 50 ns a step, a tenth of a run on a cheap right-hand side). It returns
/// before the step that reaches the end, which is the full loop's.
///
/// A function of its own, kept out of line: inside the large body of `run` the compiler
/// does not inline the system's terms into the steps (on a linear system that tripled the
/// cost of a step); in this small one it does.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn lean_steps<S: LagrangeSystem + ?Sized, M: Stepper>(
    sys: &S,
    method: &M,
    opts: &RunOptions,
    t_tol: f64,
    takes_rows: bool,
    lean: &mut Lean,
    traj: &mut Trajectory,
    buf: &mut Vec<f64>,
) -> Result<()> {
    let Lean {
        mut s,
        mut h,
        mut hand,
        mut steps,
        mut evaluations,
        mut until_record,
        mut row_handed,
    } = *lean;
    loop {
        let remaining = opts.t_end - s.t;
        // The end, or the step clamped onto it: the full loop's.
        if remaining <= t_tol || h >= remaining {
            break;
        }
        budgets(opts, steps, evaluations, s.t)?;
        let adv = method.advance_from(sys, &s, h, Some(hand))?;
        let (mut s1, mut hand1) = accept(&s, &adv, &mut steps, &mut evaluations, &mut row_handed)?;
        snap_to_end(opts, t_tol, &mut s1, &mut hand1);
        h = adv.h_next;
        until_record -= 1;
        if until_record == 0 {
            until_record = opts.record_every;
            row_handed = record_end(sys, opts, t_tol, takes_rows, &s1, &mut hand1, traj, buf)?;
        }
        hand = hand1;
        s = s1;
    }
    *lean = Lean {
        s,
        h,
        hand,
        steps,
        evaluations,
        until_record,
        row_handed,
    };
    Ok(())
}

/// Takes an accepted step from `s`: checks that it advanced, counts it and its evaluations
/// (with the one a recorded row handed to it, if any), and returns its end and handover.
#[inline(always)]
fn accept(
    s: &State,
    adv: &Advance,
    steps: &mut usize,
    evaluations: &mut usize,
    row_handed: &mut bool,
) -> Result<(State, Handover)> {
    advanced(s.t, adv.state.t)?;
    *steps += 1;
    *evaluations = evaluations
        .saturating_add(adv.evaluations)
        .saturating_add(usize::from(std::mem::take(row_handed)));
    Ok((adv.state, adv.handover))
}

/// A step end within rounding of the final time is put on it exactly; q̈ handed on belong to
/// the unsnapped time and are dropped.
#[inline(always)]
fn snap_to_end(opts: &RunOptions, t_tol: f64, s1: &mut State, hand1: &mut Handover) {
    if (opts.t_end - s1.t).abs() <= t_tol && s1.t != opts.t_end {
        s1.t = opts.t_end;
        hand1.acceleration = None;
    }
}

/// Records the step end `s1` as a row (one row stays free for the run's end) and, to a
/// method that takes them, hands the row's q̈ on to the step that starts there when the step
/// before handed none. Returns whether it did (the run then counts that evaluation with the
/// next step).
#[allow(clippy::too_many_arguments)]
fn record_end<S: LagrangeSystem + ?Sized>(
    sys: &S,
    opts: &RunOptions,
    t_tol: f64,
    takes_rows: bool,
    s1: &State,
    hand1: &mut Handover,
    traj: &mut Trajectory,
    buf: &mut Vec<f64>,
) -> Result<bool> {
    row_budget(traj.len(), opts, s1.t, t_tol)?;
    let a = traj.push_with(sys, s1, buf)?;
    if takes_rows && hand1.acceleration.is_none() {
        hand1.acceleration = Some(a);
        return Ok(true);
    }
    Ok(false)
}

/// The step and evaluation budgets, checked before a step from time `t`.
#[inline]
fn budgets(opts: &RunOptions, steps: usize, evaluations: usize, t: f64) -> Result<()> {
    if steps >= opts.max_steps {
        return Err(Error::Budget {
            what: "step",
            limit: opts.max_steps,
            time: t,
        });
    }
    if evaluations >= opts.max_evaluations {
        return Err(Error::Budget {
            what: "evaluation",
            limit: opts.max_evaluations,
            time: t,
        });
    }
    Ok(())
}

/// A step too short to change t (h below the rounding of t) would repeat for ever.
#[inline]
fn advanced(t0: f64, t1: f64) -> Result<()> {
    if t1 <= t0 || t1.is_nan() {
        return Err(Error::Singular {
            what: "run",
            measure: "time advanced by a step (h below the rounding of t)",
            value: t1 - t0,
        });
    }
    Ok(())
}

/// A system seen from the left of the time `at`: its forces at `at` or later are those at the
/// last time before it (`at.next_down()`), so that a step ending on a breakpoint integrates
/// the force it had before a jump there. Everything else is the system's own.
struct LeftOf<'a, S: ?Sized> {
    sys: &'a S,
    at: f64,
}

impl<S: LagrangeSystem + ?Sized> LeftOf<'_, S> {
    fn time(&self, t: f64) -> f64 {
        if t >= self.at {
            self.at.next_down()
        } else {
            t
        }
    }
}

impl<S: LagrangeSystem + ?Sized> LagrangeSystem for LeftOf<'_, S> {
    fn coordinate_names(&self) -> [&'static str; 2] {
        self.sys.coordinate_names()
    }
    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.sys.inertia(q)
    }
    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        self.sys.inertia_derivatives(q)
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.sys.forces(self.time(t), q, qd)
    }
    fn potential(&self, q: &Vector2<f64>) -> Result<f64> {
        self.sys.potential(q)
    }
    fn potential_gradient(&self, q: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.sys.potential_gradient(q)
    }
    fn damping(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.sys.damping(q)
    }
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        self.sys.terms(self.time(t), q, qd)
    }
    fn output_names(&self) -> Vec<&'static str> {
        self.sys.output_names()
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.sys.breakpoints()
    }
    fn kinks(&self) -> Vec<Vec<f64>> {
        self.sys.kinks()
    }
    fn kink_arguments(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        self.sys.kink_arguments(t, q, qd, out)
    }
    fn outputs(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        self.sys.outputs(t, q, qd, out)
    }
}
