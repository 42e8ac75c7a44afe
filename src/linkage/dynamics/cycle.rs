//! A machine with one input over its turn: the reduced moment of inertia and moment, the
//! run-up from rest to the steady state, and each turn's speed fluctuation.

use std::f64::consts::TAU;

use nalgebra::Vector2;

use super::system::LinkageSystem;
use crate::dynamics::{
    accelerations, run_to_reversal, Direction, Outcome, Reach, RunOptions, RunResult, State,
    Stepper, Watch,
};
use crate::error::{finite, positive, Error, Result};

/// The fewest steps in which a fixed-step method may make a turn: a turn in fewer is not
/// resolved (its speeds are the method's error), so [`LinkageSystem::turn`] refuses it.
pub const MIN_STEPS_PER_TURN: usize = 32;

/// The machine reduced to its crank at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reduced {
    /// The crank angle φ, rad.
    pub phi: f64,
    /// The reduced moment of inertia J_red(φ) = A₁₁ (added inertia included), kg·m².
    pub inertia: f64,
    /// dJ_red/dφ, kg·m²/rad.
    pub inertia_derivative: f64,
    /// The reduced moment of gravity and the loads M_red, N·m (motor excluded).
    pub loads: f64,
    /// The motor's moment at this position and speed, N·m.
    pub drive: f64,
}

/// How [`LinkageSystem::run_up`] integrates and when it stops.
///
/// Made by [`RunUpOptions::new`] and changed with the `with_*` builders, so that options can
/// be added without breaking a caller.
///
/// # Examples
/// ```
/// use tmm::linkage::dynamics::RunUpOptions;
/// let o = RunUpOptions::new(1e-3).with_tol(1e-8).with_max_turns(500);
/// assert_eq!((o.h, o.tol, o.max_turns), (1e-3, 1e-8, 500));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RunUpOptions {
    /// The step (fixed-step methods) or the first proposed step (adaptive ones), s.
    pub h: f64,
    /// The steady state: the relative change of a turn's mean speed from the previous
    /// turn's at most this.
    pub tol: f64,
    /// The most turns the run-up may take ([`Error::Budget`] beyond).
    pub max_turns: usize,
    /// The longest one turn may take, s: a machine that stalls or turns back fails with an
    /// error, not a run without end.
    pub max_turn_time: f64,
    /// The most steps the whole run-up may take ([`Error::Budget`] beyond), checked after
    /// each turn: the turn under way is finished, so a run-up ends within this plus one
    /// turn's steps. No limit but each turn's own by default.
    pub max_steps: usize,
    /// Record every n-th step of each turn (the turn's ends always). A turn's ω_max and ω_min
    /// (and so δ) are read off the recorded steps, refined by a parabola through the peak and
    /// its neighbours: thinning the record coarsens them, so keep 1 where δ matters.
    pub record_every: usize,
}

impl RunUpOptions {
    /// Steps of `h`, a relative tolerance of 10⁻⁶ on the mean speed, at most 2 000 turns of
    /// at most 60 s each, every step recorded.
    #[must_use]
    pub fn new(h: f64) -> Self {
        Self {
            h,
            tol: 1e-6,
            max_turns: 2000,
            max_turn_time: 60.0,
            max_steps: usize::MAX,
            record_every: 1,
        }
    }

    /// The same options with the step (or first proposed step) `h`, s.
    #[must_use]
    pub fn with_h(mut self, h: f64) -> Self {
        self.h = h;
        self
    }

    /// The same options with the steady state's relative tolerance `tol`.
    #[must_use]
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }

    /// The same options with at most `max_turns` turns.
    #[must_use]
    pub fn with_max_turns(mut self, max_turns: usize) -> Self {
        self.max_turns = max_turns;
        self
    }

    /// The same options with at most `max_turn_time` seconds a turn.
    #[must_use]
    pub fn with_max_turn_time(mut self, max_turn_time: f64) -> Self {
        self.max_turn_time = max_turn_time;
        self
    }

    /// The same options with at most `max_steps` steps in all (checked after each turn).
    ///
    /// ```
    /// use tmm::dynamics::Rk4;
    /// use tmm::linkage::dynamics::{LinkageSystem, Motor, RunUpOptions};
    /// use tmm::linkage::bundled;
    /// let sys = LinkageSystem::from_linkage(&bundled::four_bar())?
    ///     .with_motor(0, Motor::Linear(tmm::dynamics::machines::LinearMotor { a: 60.0, b: 2.0 }))?;
    /// // 100 steps of 1 ms do not reach a steady state: the budget ends the run-up.
    /// let e = sys.run_up(&Rk4, &RunUpOptions::new(1e-3).with_max_steps(100)).unwrap_err();
    /// assert!(matches!(e, tmm::Error::Budget { what: "run-up step", limit: 100, .. }), "{e}");
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn with_max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }

    /// The same options recording every `record_every`-th step of a turn.
    #[must_use]
    pub fn with_record_every(mut self, record_every: usize) -> Self {
        self.record_every = record_every;
        self
    }
}

/// One turn of the crank: its duration and speeds (as magnitudes, in the direction of the
/// motion).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turn {
    /// When the turn began, s.
    pub t_start: f64,
    /// How long it took, s.
    pub period: f64,
    /// The mean speed 2π/period, rad/s.
    pub omega_mean: f64,
    /// The largest speed over the turn, rad/s (between recorded steps by a parabola through
    /// the three steps around the largest).
    pub omega_max: f64,
    /// The smallest speed over the turn, rad/s (likewise).
    pub omega_min: f64,
    /// The coefficient of speed fluctuation δ = (ω_max − ω_min)/ω_m with the textbook's
    /// ω_m = (ω_max + ω_min)/2, as the flywheel's design uses it (the time mean
    /// [`omega_mean`](Self::omega_mean) differs from it by at most δ/2, relative, depending
    /// on the shape of ω(φ)).
    pub delta: f64,
    /// +1 counter-clockwise, −1 clockwise.
    pub direction: f64,
}

/// The run-up from rest to the steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct RunUp {
    /// Every turn, the last one steady.
    pub turns: Vec<Turn>,
    /// The recorded times of the whole run, s.
    pub t: Vec<f64>,
    /// The crank angle at those times, rad.
    pub phi: Vec<f64>,
    /// The crank speed at those times, rad/s.
    pub omega: Vec<f64>,
    /// The last (steady) turn as the integrator recorded it.
    pub steady: RunResult,
    /// Accepted steps over the whole run.
    pub steps: usize,
    /// Evaluations of the accelerations over the whole run.
    pub evaluations: usize,
}

/// How a turn ended: completed, or turned back (the run up to the turning state).
enum TurnEnd {
    Turned(Turn, RunResult),
    Back(RunResult),
}

/// The error of a turn from `start` whose crank turned back where the run `r` ended.
fn turned_back(start: &State, r: &RunResult) -> Error {
    Error::TurnedBack {
        time: r.last.t,
        angle: r.last.q[0],
        fraction: (r.last.q[0] - start.q[0]).abs() / TAU,
        from_speed: start.qd[0],
        from_time: start.t,
    }
}

/// The vertex of the parabola through three points (t, s), the middle one the extreme;
/// the middle value when the points are collinear.
fn vertex(t: [f64; 3], s: [f64; 3]) -> f64 {
    let f01 = (s[1] - s[0]) / (t[1] - t[0]);
    let f12 = (s[2] - s[1]) / (t[2] - t[1]);
    let f012 = (f12 - f01) / (t[2] - t[0]);
    if !(f012 != 0.0 && f012.is_finite()) {
        return s[1];
    }
    let ts = (0.5 * (t[0] + t[1]) - f01 / (2.0 * f012)).clamp(t[0], t[2]);
    let v = s[0] + f01 * (ts - t[0]) + f012 * (ts - t[0]) * (ts - t[1]);
    if v.is_finite() {
        v
    } else {
        s[1]
    }
}

/// The extreme of `s` over the samples (largest when `max`), refined by a parabola when it
/// lies inside.
fn extreme(t: &[f64], s: &[f64], max: bool) -> f64 {
    let better = |a: f64, b: f64| if max { a > b } else { a < b };
    let mut k = 0;
    for i in 1..s.len() {
        if better(s[i], s[k]) {
            k = i;
        }
    }
    if k == 0 || k + 1 >= s.len() {
        return s[k];
    }
    vertex([t[k - 1], t[k], t[k + 1]], [s[k - 1], s[k], s[k + 1]])
}

impl LinkageSystem {
    /// Checks that the machine has one input, a crank.
    fn one_crank(&self, what: &str) -> Result<()> {
        if self.dof() == 1 && self.plan().input_is_crank() {
            Ok(())
        } else {
            Err(Error::Description {
                item: "field input".to_owned(),
                problem: format!("{what} need one input, a crank"),
            })
        }
    }

    /// The machine reduced to its crank at the angle `phi` turning at `omega` (the speed
    /// matters for the loads that depend on the motion and for the motor).
    ///
    /// # Errors
    /// [`Error::Description`] for a machine with two inputs or a slider input; as
    /// [`split_terms`](Self::split_terms).
    ///
    /// # Examples
    /// The four-bar's crank alone has 0.002 kg·m²; the coupler and rocker add more:
    /// ```
    /// use tmm::linkage::{bundled, dynamics::LinkageSystem};
    /// let sys = LinkageSystem::from_linkage(&bundled::four_bar())?;
    /// let r = sys.reduced(0.5, 10.0)?;
    /// assert!(r.inertia > 0.002 && r.drive == 0.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn reduced(&self, phi: f64, omega: f64) -> Result<Reduced> {
        self.one_crank("the reduced moment of inertia and moment")?;
        let t = self.split_terms(&Vector2::new(phi, 0.0), &Vector2::new(omega, 0.0))?;
        Ok(Reduced {
            phi,
            inertia: t.inertia[(0, 0)],
            inertia_derivative: t.inertia_derivatives[0][(0, 0)],
            loads: t.loads[0],
            drive: t.drives[0],
        })
    }

    /// [`reduced`](Self::reduced) at `n` equally spaced angles over one turn from the
    /// reference pose, in the direction of `omega`.
    ///
    /// # Errors
    /// [`Error::NonPositive`] for n = 0; [`Error::NonFinite`] or [`Error::NonPositive`] for
    /// a non-finite or zero `omega`; as [`reduced`](Self::reduced).
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, dynamics::LinkageSystem};
    /// let sys = LinkageSystem::from_linkage(&bundled::watt_six_bar())?;
    /// let turn = sys.reduced_cycle(72, 10.0)?;
    /// assert_eq!(turn.len(), 72);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn reduced_cycle(&self, n: usize, omega: f64) -> Result<Vec<Reduced>> {
        if !(1..=crate::kinematics::MAX_POSITIONS).contains(&n) {
            return Err(Error::OutOfRange {
                name: "number of positions",
                value: n as f64,
                min: 1.0,
                max: crate::kinematics::MAX_POSITIONS as f64,
                ends: crate::Ends::Closed,
            });
        }
        positive("|omega|", finite("omega", omega)?.abs())?;
        let phi0 = self.plan().reference_input();
        let step = omega.signum() * TAU / n as f64;
        (0..n)
            .map(|i| self.reduced(phi0 + step * i as f64, omega))
            .collect()
    }

    /// Integrates one turn of the crank from `start` with `method`: the crank's angle
    /// advances by 2π in the direction it moves (or, from rest, in the direction it starts).
    ///
    /// # Examples
    /// The Watt six-bar coasting at 20 rad/s with no loads, gravity off: T is constant, so
    /// the speed comes back to 20 rad/s after the turn.
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::dynamics::{Rk4, State};
    /// use tmm::linkage::{bundled, dynamics::{LinkageSystem, RunUpOptions}};
    /// let mut l = bundled::watt_six_bar();
    /// l.loads.clear();
    /// l.gravity = [0.0, 0.0];
    /// let sys = LinkageSystem::from_linkage(&l)?;
    /// let start = State::new(0.0, Vector2::new(sys.plan().reference_input(), 0.0), Vector2::new(20.0, 0.0));
    /// let (turn, r) = sys.turn(&Rk4, start, &RunUpOptions::new(1e-4))?;
    /// assert!((r.last.qd[0] - 20.0).abs() < 1e-6 && turn.delta > 0.0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Stalled`] naming the driving load and the resistance when the resistances
    /// hold the machine at rest (it stops, or never starts); [`Error::TurnedBack`] with the
    /// time, the angle and the fraction of the turn made when the crank turns back (its
    /// speed passes zero against the turn's direction, or leaves zero the other way: located
    /// to the method's own state); [`Error::Singular`] when
    /// nothing starts the machine from rest, when it does not complete the turn within
    /// `opts.max_turn_time`, or when the turn takes no time;
    /// [`Error::OutOfRange`] naming the step `h` when a fixed-step method made the turn in
    /// fewer than [`MIN_STEPS_PER_TURN`] steps; as [`run`](crate::dynamics::run).
    pub fn turn<M: Stepper>(
        &self,
        method: &M,
        start: State,
        opts: &RunUpOptions,
    ) -> Result<(Turn, RunResult)> {
        match self.turn_or_back(method, start, opts)? {
            TurnEnd::Turned(turn, r) => Ok((turn, r)),
            TurnEnd::Back(r) => Err(turned_back(&start, &r)),
        }
    }

    /// [`turn`](Self::turn), or the run up to where the crank turned back (its speed passed
    /// zero against the turn's direction and the drive moves it the other way).
    fn turn_or_back<M: Stepper>(
        &self,
        method: &M,
        start: State,
        opts: &RunUpOptions,
    ) -> Result<TurnEnd> {
        self.one_crank("turns and run-ups")?;
        positive("max_turn_time", opts.max_turn_time)?;
        let direction = if start.qd[0] != 0.0 {
            start.qd[0].signum()
        } else {
            let a = accelerations(self, start.t, &start.q, &start.qd)?[0];
            if a == 0.0 {
                return Err(Error::Singular {
                    what: "run-up",
                    measure: "crank acceleration from rest (nothing starts the machine)",
                    value: a,
                });
            }
            a.signum()
        };
        let mut ro = RunOptions::until(start.t + opts.max_turn_time, opts.h);
        ro.record_every = opts.record_every;
        ro.reach = Some(Reach {
            watch: Watch::Coordinate(0),
            value: start.q[0] + direction * TAU,
            direction: if direction > 0.0 {
                Direction::Rising
            } else {
                Direction::Falling
            },
        });
        let r = match run_to_reversal(self, method, start, &ro, (0, direction)) {
            // A machine driven backwards spins the other way ever faster and fills its
            // budget before max_turn_time: that is a turn that never comes, said as one.
            Err(Error::Budget { time, .. }) => {
                return Err(Error::Singular {
                    what: "run-up",
                    measure: "time reached without completing a turn before the run's step or \
                              row budget ran out (the machine turns back or stalls)",
                    value: time - start.t,
                });
            }
            r => match r? {
                (r, true) => return Ok(TurnEnd::Back(r)),
                (r, false) => r,
            },
        };
        if let Outcome::Stuck { t, loads, .. } = r.outcome {
            // The resistances hold the machine at rest: no turn will ever end.
            return Err(loads.stalled(t));
        }
        if let Outcome::Jammed { t, joint, value } = r.outcome {
            return Err(super::friction::jam_error(self.plan(), t, joint, value));
        }
        if let Outcome::DeadCentre { dyad, value, .. } = r.outcome {
            // A turn cannot pass a dead centre of a dyad: name it, as a state there is named.
            let group = self
                .plan()
                .groups()
                .get(dyad)
                .map_or_else(String::new, |g| g.name.clone());
            return Err(Error::DeadCentre {
                index: dyad,
                group,
                value,
            });
        }
        if !matches!(r.outcome, Outcome::Reached { .. }) {
            return Err(Error::Singular {
                what: "run-up",
                measure: "fraction of a turn completed within max_turn_time (the machine \
                          stalls or turns back)",
                value: direction * (r.last.q[0] - start.q[0]) / TAU,
            });
        }
        let tr = &r.trajectory;
        let speed: Vec<f64> = tr.qd()[0].iter().map(|w| direction * w).collect();
        let period = r.last.t - start.t;
        if period.is_nan() || period <= 0.0 {
            // A turn that ends where it began has no mean speed (it would be 2π/0).
            return Err(Error::Singular {
                what: "turn",
                measure: "its duration (the turn ended when it began)",
                value: period,
            });
        }
        if !method.is_adaptive() && r.steps < MIN_STEPS_PER_TURN {
            // A fixed step that spans a large part of a turn (a machine run up far faster
            // than its step was chosen for) samples the method's error, not the motion: its
            // speeds could turn back, or repeat a regime, where the machine does neither.
            return Err(Error::OutOfRange {
                name: "step h of a fixed-step turn (it must take at least 32 steps a turn; \
                       choose a smaller h, or an adaptive method)",
                value: opts.h,
                min: 0.0,
                max: period / MIN_STEPS_PER_TURN as f64,
                ends: crate::Ends::OpenBelow,
            });
        }
        let omega_mean = crate::error::computed("mean speed of a turn", TAU / period)?;
        let omega_max = extreme(tr.t(), &speed, true);
        let omega_min = extreme(tr.t(), &speed, false);
        if omega_min.is_nan() || omega_min < 0.0 {
            // The crank turned back within a turn it completed: δ, a fluctuation about a mean
            // speed, has no meaning there (a turn from rest starts at ω = 0, and has δ = 2).
            return Err(Error::Singular {
                what: "run-up",
                measure: "the least crank speed within a turn (it turns back)",
                value: omega_min,
            });
        }
        let delta = crate::error::computed(
            "coefficient of speed fluctuation",
            2.0 * (omega_max - omega_min) / (omega_max + omega_min),
        )?;
        let turn = Turn {
            t_start: start.t,
            period,
            omega_mean,
            omega_max,
            omega_min,
            delta,
            direction,
        };
        Ok(TurnEnd::Turned(turn, r))
    }

    /// The run-up from rest in the reference pose to the steady state (see
    /// [`run_up_from`](Self::run_up_from)).
    ///
    /// # Errors
    /// As [`run_up_from`](Self::run_up_from).
    pub fn run_up<M: Stepper>(&self, method: &M, opts: &RunUpOptions) -> Result<RunUp> {
        let q0 = Vector2::new(self.plan().reference_input(), 0.0);
        self.run_up_from(method, State::at_rest(q0), opts)
    }

    /// Integrates turn after turn from `start` until a turn's mean speed changes from the
    /// previous turn's by at most `opts.tol` (relative): the steady state.
    ///
    /// Where the crank turns back (a machine thrown against its drive stops and the drive,
    /// above the resistances' breakaway load, turns it the other way), the run-up goes on
    /// from that state at rest, with turns in the new direction; the part of a turn before
    /// it is in the recorded motion but not in [`RunUp::turns`].
    ///
    /// The cost is bounded: at most `opts.max_turns` turns (a turning back counts as one),
    /// each at most
    /// `opts.max_turn_time` of motion and the run's step budget
    /// ([`RunOptions`](crate::dynamics::RunOptions)), and no turn begun after
    /// `opts.max_steps` steps in all.
    ///
    /// # Errors
    /// [`Error::Budget`] when `opts.max_turns` turns or `opts.max_steps` steps pass without
    /// a steady state, wrapped
    /// in [`Error::In`] saying why when at least 8 turns were run: the mean speed grew in
    /// each of the last turns (the machine runs away), fell in each, or went up and down
    /// without settling;
    /// [`Error::NonFinite`]/[`Error::NonPositive`] for a bad tolerance; as
    /// [`turn`](Self::turn).
    pub fn run_up_from<M: Stepper>(
        &self,
        method: &M,
        start: State,
        opts: &RunUpOptions,
    ) -> Result<RunUp> {
        positive("run-up tolerance", opts.tol)?;
        positive("max_turns", opts.max_turns as f64)?;
        let mut out = RunUp {
            turns: Vec::new(),
            t: Vec::new(),
            phi: Vec::new(),
            omega: Vec::new(),
            steady: RunResult {
                trajectory: crate::dynamics::Trajectory::default(),
                outcome: Outcome::FinalTime,
                last: start,
                steps: 0,
                evaluations: 0,
            },
            steps: 0,
            evaluations: 0,
        };
        let mut s = start;
        let mut back: Option<(usize, f64, usize)> = None;
        for k in 0..opts.max_turns {
            let end = self.turn_or_back(method, s, opts)?;
            let r = match &end {
                TurnEnd::Turned(_, r) | TurnEnd::Back(r) => r,
            };
            let skip = usize::from(k > 0);
            let tr = &r.trajectory;
            out.t.extend(&tr.t()[skip..]);
            out.phi.extend(&tr.q()[0][skip..]);
            out.omega.extend(&tr.qd()[0][skip..]);
            out.steps += r.steps;
            out.evaluations += r.evaluations;
            s = r.last;
            let (turn, r) = match end {
                TurnEnd::Turned(turn, r) => (turn, r),
                TurnEnd::Back(_) => {
                    // The speed located at zero (to rounding): the next turn starts from rest
                    // in the direction the drive moves it.
                    s.qd[0] = 0.0;
                    back = Some((back.map_or(0, |b| b.0) + 1, s.t, out.turns.len()));
                    if out.steps >= opts.max_steps {
                        break;
                    }
                    continue;
                }
            };
            // A turn before a turning back went the other way: not compared.
            let fresh = back.map_or(0, |b| b.2);
            let steady = out.turns[fresh..].last().is_some_and(|p| {
                (turn.omega_mean - p.omega_mean).abs() <= opts.tol * turn.omega_mean
            });
            out.turns.push(turn);
            out.steady = r;
            if steady {
                return Ok(out);
            }
            if out.steps >= opts.max_steps {
                break;
            }
        }
        let budget = if out.steps >= opts.max_steps {
            Error::Budget {
                what: "run-up step",
                limit: opts.max_steps,
                time: s.t,
            }
        } else {
            Error::Budget {
                what: "turn",
                limit: opts.max_turns,
                time: s.t,
            }
        };
        let why = match back.filter(|_| out.turns.is_empty()) {
            Some((n, t, _)) => Some(format!(
                "run-up without a turn: the crank turned back {n} times, the last at t = {t} s"
            )),
            None => no_steady_state(&out.turns, opts.tol),
        };
        Err(match why {
            Some(why) => Error::In {
                part: why,
                source: Box::new(budget),
            },
            None => budget,
        })
    }
}

/// Why the mean speeds of a run-up's turns did not settle, read from the last (at most 16)
/// turns: they grew in every one (the drive still exceeds the resistances at every speed
/// reached: a machine without a steady state runs away, its mean speed rising like the
/// square root of the work done), fell in every one, or went up and down without settling
/// to `tol` (a regime that repeats over several turns). `None` for fewer than 8 turns: too
/// few to tell a slow approach from none.
fn no_steady_state(turns: &[Turn], tol: f64) -> Option<String> {
    const LAST: usize = 16;
    if turns.len() < 8 {
        return None;
    }
    let w: Vec<f64> = turns[turns.len().saturating_sub(LAST)..]
        .iter()
        .map(|t| t.omega_mean)
        .collect();
    let n = w.len();
    let (first, last) = (w[0], w[n - 1]);
    let rising = w.windows(2).all(|p| p[1] > p[0]);
    let falling = w.windows(2).all(|p| p[1] < p[0]);
    let (lo, hi) = w
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x), h.max(x))
        });
    Some(if rising {
        format!(
            "run-up without a steady state: the mean speed grew in each of the last {n} turns, \
             from {first:.6e} to {last:.6e} rad/s (the drive exceeds the resistances at every \
             speed reached)"
        )
    } else if falling {
        format!(
            "run-up without a steady state: the mean speed fell in each of the last {n} turns, \
             from {first:.6e} to {last:.6e} rad/s"
        )
    } else {
        format!(
            "run-up without a steady state: the mean speed went up and down between \
             {lo:.6e} and {hi:.6e} rad/s over the last {n} turns without settling to a \
             relative {tol:e} (a regime that repeats over several turns)"
        )
    })
}
