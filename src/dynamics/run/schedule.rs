//! A run's schedule: the times its steps must end on (breakpoints, and requested times for a
//! method without a continuous extension), the requested times it records, the kinks it
//! lands on, the grid of a fixed-step method, and whether anything stops or is watched on
//! the way at all.

use super::kinks::Kinks;
use super::options::RunOptions;
use super::progress::row_budget;
use crate::dynamics::stepper::{ContinuousExtension, Stepper};
use crate::dynamics::system::{LagrangeSystem, State};
use crate::dynamics::trajectory::Trajectory;
use crate::error::{finite, Error, Result};

/// What a run steps onto and records on the way, made once from the options and the system,
/// with the cursors that walk it.
pub(super) struct Schedule {
    /// The requested times after the start, sorted, each once.
    times: Vec<f64>,
    /// The next requested time not yet recorded.
    i_time: usize,
    /// The times a step must end on: the breakpoints, and the requested times for a method
    /// that cannot interpolate.
    stops: Vec<f64>,
    /// The next stop not yet passed.
    i_stop: usize,
    /// The end of the grid step a fixed-step method was taking when a stop or a kink cut it.
    pub(super) grid_end: Option<f64>,
    /// The nodes of the kink arguments and the switch speeds, and where the arguments are.
    pub(super) kinks: Kinks,
    /// Whether the method chooses its own steps.
    pub(super) adaptive: bool,
    /// The end counts as reached within rounding of the times (not of h: a step longer than
    /// the whole run must still take the run to its end).
    pub(super) t_tol: f64,
    /// Nothing to stop at or watch on the way (no breakpoints, requested times, kinks, reach
    /// or steady state): the interior steps can be the lean loop's.
    pub(super) plain: bool,
}

/// The step a run takes next, as the schedule shapes it.
#[derive(Clone, Copy)]
pub(super) struct Planned {
    /// The next stop (or the final time).
    pub(super) stop: f64,
    /// The end of the grid step under way, when a fixed-step method was cut short.
    pub(super) goal: Option<f64>,
    /// The step asked of the method.
    pub(super) h_try: f64,
    /// Whether the step was clamped onto the stop.
    pub(super) clamped: bool,
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

impl Schedule {
    /// The schedule of a run of `sys` with `method` from the time `t_start` (the options
    /// already checked).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a requested time, a breakpoint or a kink node that is not
    /// finite; [`Error::OutOfRange`] for a requested time outside [t_start, t_end].
    pub(super) fn new<S: LagrangeSystem + ?Sized, M: Stepper>(
        sys: &S,
        method: &M,
        t_start: f64,
        opts: &RunOptions,
    ) -> Result<Self> {
        // Requested times: the start is recorded anyway.
        let times = sorted_finite("requested time", opts.times.iter().copied())?;
        if let Some(&t) = times.iter().find(|&&t| !(t >= t_start && t <= opts.t_end)) {
            return Err(Error::OutOfRange {
                name: "requested time",
                value: t,
                min: t_start,
                max: opts.t_end,
                ends: crate::Ends::Closed,
            });
        }
        let times: Vec<f64> = times.into_iter().filter(|&t| t > t_start).collect();
        let breaks: Vec<f64> = sorted_finite(
            "breakpoint",
            opts.breakpoints.iter().copied().chain(sys.breakpoints()),
        )?
        .into_iter()
        .filter(|&t| t > t_start && t < opts.t_end)
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
        // The switch speeds, always located (stepping across one is what chatters): one more
        // argument each, with the node 0.
        let kinks = Kinks::new(kinks, sys.switches());
        let stops = if method.has_dense_output() {
            breaks
        } else {
            sorted_finite(
                "requested time",
                breaks.into_iter().chain(times.iter().copied()),
            )?
        };
        let plain = stops.is_empty()
            && times.is_empty()
            && !kinks.any()
            && opts.reach.is_none()
            && opts.steady.is_none();
        Ok(Self {
            times,
            i_time: 0,
            stops,
            i_stop: 0,
            grid_end: None,
            kinks,
            adaptive: method.is_adaptive(),
            t_tol: 1e-12 * opts.t_end.abs().max(t_start.abs()),
            plain,
        })
    }

    /// The step from time `t` where the method would take `h`: clamped onto the next stop
    /// (a fixed-step method then goes on to the end of its grid step), or the rest of a grid
    /// step cut short.
    #[inline]
    pub(super) fn next_step(&mut self, t: f64, h: f64, t_end: f64) -> Planned {
        while self.i_stop < self.stops.len() && self.stops[self.i_stop] <= t + self.t_tol {
            self.i_stop += 1;
        }
        let stop = self.stops.get(self.i_stop).map_or(t_end, |&s| s.min(t_end));
        let remaining = stop - t;
        let goal = self.grid_end.take();
        let h_want = goal.map_or(h, |g| g - t);
        let clamped = h_want >= remaining;
        let h_try = if clamped { remaining } else { h_want };
        // A fixed-step method cut short by a stop goes on to the end of its grid step.
        if clamped && !self.adaptive && h_want - remaining > self.t_tol {
            self.grid_end = Some(goal.unwrap_or(t + h));
        }
        Planned {
            stop,
            goal,
            h_try,
            clamped,
        }
    }

    /// Whether the next step's continuous extension will be read: a requested time still
    /// ahead, or a kink to locate (its first guess).
    #[inline]
    pub(super) fn wants_extension(&self) -> bool {
        self.i_time < self.times.len() || self.kinks.any()
    }

    /// Records the requested times inside the step `s` → `s1` up to `t_lim` (the step's end,
    /// or a located stop `hit` before it), from the continuous extension `dense` when there
    /// is one. Returns whether a requested time is the step's end (which the caller records).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn record_times<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        opts: &RunOptions,
        (s, s1): (&State, &State),
        hit: Option<State>,
        dense: Option<&M::Dense>,
        traj: &mut Trajectory,
        buf: &mut Vec<f64>,
    ) -> Result<bool> {
        let t_lim = hit.map_or(s1.t, |x| x.t);
        let mut at_end = false;
        while self.i_time < self.times.len() && self.times[self.i_time] <= t_lim {
            let tau = self.times[self.i_time];
            self.i_time += 1;
            if tau == s1.t {
                at_end = true;
                continue;
            }
            if hit.is_some_and(|x| x.t == tau) {
                continue; // the located stop is the last row anyway
            }
            let st = match dense {
                Some(d) => d.at(tau)?,
                // A method without an extension steps onto each requested time; should one
                // fall inside a step all the same, one step from its start gives it.
                None => State {
                    t: tau,
                    ..method.step(sys, s, tau - s.t)?
                },
            };
            row_budget(traj.len(), opts, tau, self.t_tol)?;
            traj.push_with(sys, &st, buf)?;
        }
        Ok(at_end)
    }
}
