//! The step loop of a run: each step planned by the schedule, taken, landed on the earliest
//! kink inside it, checked against the stop conditions, and recorded.

use super::band::BandWatch;
use super::dead_centre;
use super::lean::lean_steps;
use super::left_of::LeftOf;
use super::options::RunOptions;
use super::outcome::{Outcome, RunResult};
use super::progress::{accept, budgets, record_end, snap_to_end, Progress, StepEnd};
use super::schedule::Schedule;
use super::stop_conditions::{ReachWatch, ReversalWatch, SteadyWatch};
use std::cell::Cell;

use super::frozen::sign;
use super::held::Hold;
use crate::dynamics::stepper::{ContinuousExtension, Handover, Stepper};
use crate::dynamics::switch::SwitchLoads;
use crate::dynamics::system::{accelerations, LagrangeSystem, State};
use crate::dynamics::trajectory::Trajectory;
use crate::error::Result;

/// A jam: its time, the joint that self-locks and det(I − J) there.
type Jam = (f64, usize, f64);

/// What a landing on a switch's zero leads to.
enum Landing {
    /// The run ends there (stuck).
    Ends(RunResult),
    /// A coordinate is held from there: the state with its rate set to zero.
    Held(State),
    /// A held coordinate was released.
    Released,
    /// The motion goes on as it was (it breaks away, or nothing changed).
    Goes,
}

/// A run under way: what it was given, its schedule and stop conditions, what it carries
/// from step to step, and what it has recorded.
pub(super) struct Runner<'a, S: ?Sized, M> {
    sys: &'a S,
    method: &'a M,
    opts: &'a RunOptions,
    sched: Schedule,
    reach: Option<ReachWatch>,
    steady: Option<SteadyWatch>,
    progress: Progress,
    /// A recorded row's q̈ are those a method's first stage would evaluate at the same state:
    /// to a method that takes them, the row hands them on when the step before did not.
    takes_rows: bool,
    traj: Trajectory,
    /// The outputs of a watched state and of every recorded row, one buffer for the run.
    buf: Vec<f64>,
    /// The direction each switch's resistance is held in through the next step (see
    /// [`Frozen`](super::frozen::Frozen)), for a system with switches.
    modes: Option<&'a [Cell<f64>]>,
    /// The direction a motion broke away in from a switch it was weighed at (0: none), for
    /// the step that starts there.
    breakaway: Vec<f64>,
    /// The watch for the motion turning back, when the run ends there.
    reversal: Option<ReversalWatch>,
    /// Whether the run ended where the motion turned back.
    reversed: bool,
    /// The step last asked of the method, s: where a dead centre met in it is looked for.
    tried: f64,
    /// The coordinates held at rest by switches that can hold them (see
    /// [`held`](super::held)), for a system with such switches.
    hold: Option<&'a Hold>,
    /// The lock measures at the step ends, for a system that has them.
    band: Option<BandWatch>,
}

impl<'a, S: LagrangeSystem + ?Sized, M: Stepper> Runner<'a, S, M> {
    /// A run of `sys` with `method` from `start` (checked) on the schedule `sched`: the start
    /// recorded, the watched quantity and the kink arguments evaluated there.
    pub(super) fn start(
        sys: &'a S,
        method: &'a M,
        opts: &'a RunOptions,
        start: State,
        mut sched: Schedule,
        modes: Option<&'a [Cell<f64>]>,
    ) -> Result<Self> {
        let mut buf = Vec::new();
        let mut traj = Trajectory::for_system(sys);
        let a_start = traj.push_with(sys, &start, &mut buf)?;
        let reach = match opts.reach {
            Some(r) => Some(ReachWatch::start(sys, r, &start, &mut buf)?),
            None => None,
        };
        let takes_rows = method.uses_start_acceleration();
        let mut hand = Handover::default();
        if takes_rows {
            hand.acceleration = Some(a_start);
        }
        if sched.kinks.any() {
            sched.kinks.start(sys, &start)?;
        }
        let band = BandWatch::start(sys, &start);
        // A band is looked for after every step: the lean loop does not.
        sched.plain &= band.is_none();
        Ok(Self {
            sys,
            method,
            opts,
            sched,
            reach,
            steady: opts.steady.map(SteadyWatch::new),
            progress: Progress {
                s: start,
                prev: start,
                h: opts.h,
                hand,
                steps: 0,
                evaluations: 0,
                until_record: opts.record_every,
                row_handed: takes_rows,
            },
            takes_rows,
            traj,
            buf,
            modes,
            breakaway: vec![0.0; modes.map_or(0, <[_]>::len)],
            reversal: None,
            reversed: false,
            tried: opts.h,
            hold: None,
            band,
        })
    }

    /// The run holds coordinates at rest where `hold`'s switches stick (see
    /// [`held`](super::held)).
    pub(super) fn holding(mut self, hold: Option<&'a Hold>) -> Self {
        self.hold = hold;
        self
    }

    /// The run also ends where coordinate `i`'s speed, moving in the direction `d` (±1),
    /// turns back (see [`ReversalWatch`]).
    pub(super) fn ending_at_reversal(mut self, (i, d): (usize, f64)) -> Self {
        self.reversal = Some(ReversalWatch::start((i, d), &self.progress.s));
        self.sched.plain = false;
        self
    }

    /// Steps until a stop condition, and the result with whether the motion turned back
    /// there (the outcome then [`Outcome::Reached`] at the located time).
    pub(super) fn finish_or_reversal(mut self) -> Result<(RunResult, bool)> {
        let r = self.steps()?;
        Ok((r, self.reversed))
    }

    /// Steps until a stop condition, and the result.
    pub(super) fn finish(mut self) -> Result<RunResult> {
        self.steps()
    }

    /// Steps until a stop condition, and the result.
    fn steps(&mut self) -> Result<RunResult> {
        // The end of the step under way, one place for the run (the continuous extension it
        // holds is some hundreds of bytes: written there, not moved from step to step).
        let mut end = StepEnd {
            s1: self.progress.s,
            dense: None,
            hand: Handover::default(),
            h_next: None,
        };
        // A start exactly at switches (a whole rest stops every one): each weighed before
        // the first step. Those that break away are held the way they go; the run ends
        // stuck (at the first) only when every one holds, for then nothing moves.
        let n = self.modes.map_or(0, <[_]>::len);
        let at_zero: Vec<usize> = self
            .sched
            .kinks
            .switches_at_zero()
            .filter(|&i| i < n)
            .collect();
        let mut held = None;
        let mut holding = 0;
        let mut holds: Vec<(usize, usize)> = Vec::new();
        for &i in &at_zero {
            if let Some(loads) = self.weigh(i, self.progress.s)? {
                held.get_or_insert((i, loads));
                holding += 1;
                holds.extend(self.hold.and_then(|h| h.coordinate(i)).map(|k| (i, k)));
            }
        }
        let s = self.progress.s;
        // Every switch that holds holds a coordinate: they are held, unless that leaves the
        // machine at a whole rest whose loads do not change with time.
        let all = holding == at_zero.len() && holds.len() == holding;
        let moving = (0..2).any(|k| s.qd[k] != 0.0 && !holds.iter().any(|h| h.1 == k));
        let keep = !all || moving || self.sys.forces_depend_on_time();
        if let Some((switch, loads)) = held
            && holding == at_zero.len()
            && !(all && keep)
        {
            let outcome = Outcome::Stuck {
                t: s.t,
                switch,
                loads,
            };
            return self.result(s, true, outcome);
        }
        // Those that hold while others break away are weighed again as the others start to
        // move (their rates a vanishing amount the way they go): the joints those moves
        // set sliding no longer hold with them.
        let starting: Vec<(usize, usize, f64)> = at_zero
            .iter()
            .filter_map(|&i| {
                let away = *self.breakaway.get(i)?;
                let k = self.hold?.coordinate(i)?;
                (away != 0.0).then_some((i, k, away))
            })
            .collect();
        if !starting.is_empty() {
            holds = self.still_holding(&s, &starting, holds)?;
        }
        if !holds.is_empty()
            && let Some(hold) = self.hold
        {
            for &(i, k) in &holds {
                hold.set(k, Some(i));
            }
            // The start's row and its accelerations were the free motion's.
            self.held_changed(&s)?;
            self.traj.truncate(0);
            self.traj.push_with(self.sys, &s, &mut self.buf)?;
        }
        loop {
            match self.advance(&mut end) {
                Ok(Some(result)) => return Ok(result),
                Ok(None) => {}
                Err(e) => return self.stopped_by(e),
            }
        }
    }

    /// The run's result when `e` is a stop: a jam ([`Outcome::Jammed`]), the motion ending at
    /// the located jam ([`locate_jam`](Self::locate_jam)), or at the last accepted state when
    /// it is not found inside the step; a dead centre ([`Outcome::DeadCentre`]), located
    /// inside the step that met it. Any other error as it is.
    fn stopped_by(&mut self, e: crate::Error) -> Result<RunResult> {
        if let Some(d) = dead_centre::locate(
            self.sys,
            self.method,
            self.opts,
            &mut self.progress,
            self.tried,
            &e,
        )? {
            let outcome = Outcome::DeadCentre {
                t: d.last.t,
                dyad: d.dyad,
                value: d.value,
            };
            let recorded = self.traj.t().last() == Some(&d.last.t);
            return self.result(d.last, recorded, outcome);
        }
        let Some(jam) = e.jam() else {
            return Err(e);
        };
        let s = self.progress.s;
        let ((t, joint, value), last) = match self.locate_jam(&s, jam) {
            Some((jam, last)) => (jam, Some(last)),
            None => (jam, None),
        };
        let outcome = Outcome::Jammed { t, joint, value };
        match last {
            Some(last) if last.t > s.t => self.result(last, false, outcome),
            _ => {
                let recorded = self.traj.t().last() == Some(&s.t);
                self.result(s, recorded, outcome)
            }
        }
    }

    /// The jam `jam` (its time, joint, measure) found in the step from `s`, located: the
    /// shortest step of the method from `s` that fails (in a stage, or in the accelerations
    /// of its end) found by bisection on the step's length, between a length that carries
    /// (0) and one that jams (the evaluation's time less `s.t`, else the step tried, doubled
    /// up to four times), to the run's time tolerance. A step that fails otherwise on the
    /// way counts as failing: next to a jam the motion's own equation loses its solution
    /// too (the friction's feedback reaching the inertia spends the q̈ iteration's budget).
    /// Returns the jam at the end time of the shortest length that fails (the joint and
    /// measure of the nearest length that jams), and the state at the end of the longest
    /// that carries; `None` when no length that jams is found (the first jam stands).
    fn locate_jam(&mut self, s: &State, jam: Jam) -> Option<(Jam, State)> {
        let (sys, method) = (self.sys, self.method);
        let per_step = method.evaluations_per_step() + 1;
        let spent = &mut self.progress.evaluations;
        // A step of length h from s: its end state when it carries, else the jam it meets
        // (none for another failure).
        let mut try_step = |h: f64| -> std::result::Result<State, Option<(usize, f64)>> {
            *spent += per_step;
            let e = match method.step(sys, s, h) {
                Ok(s1) => match accelerations(sys, s1.t, &s1.q, &s1.qd) {
                    Ok(_) => return Ok(s1),
                    Err(e) => e,
                },
                Err(e) => e,
            };
            Err(e.jam().map(|(_, joint, value)| (joint, value)))
        };
        let mut hi = if jam.0 > s.t {
            jam.0 - s.t
        } else {
            self.progress.h
        };
        let mut hi_jam = None;
        for _ in 0..5 {
            if !(hi > 0.0 && hi.is_finite()) {
                return None;
            }
            if let Err(Some(j)) = try_step(hi) {
                hi_jam = Some(j);
                break;
            }
            hi *= 2.0;
        }
        let mut hi_jam = hi_jam?;
        let (mut lo, mut lo_state) = (0.0, *s);
        // Each halving costs one step: some forty from a step of 10⁻⁴ s to 10⁻¹² of the run.
        while hi - lo > self.sched.t_tol && lo < 0.5 * (lo + hi) && 0.5 * (lo + hi) < hi {
            let mid = 0.5 * (lo + hi);
            match try_step(mid) {
                Ok(s1) => (lo, lo_state) = (mid, s1),
                Err(j) => {
                    hi = mid;
                    hi_jam = j.unwrap_or(hi_jam);
                }
            }
        }
        Some(((s.t + hi, hi_jam.0, hi_jam.1), lo_state))
    }

    /// The next step (or the lean steps and the step that reaches the end), and the result
    /// when the run ends there.
    fn advance(&mut self, end: &mut StepEnd<M::Dense>) -> Result<Option<RunResult>> {
        let (sys, method, opts) = (self.sys, self.method, self.opts);
        let t_tol = self.sched.t_tol;
        // A run with nothing to stop at or watch on the way takes its interior steps in
        // `lean_steps`; the step that reaches the end, and every step of any other run,
        // is this loop's.
        if self.sched.plain && self.sched.grid_end.is_none() {
            let p = &mut self.progress;
            let lean = lean_steps(
                sys,
                method,
                opts,
                t_tol,
                self.takes_rows,
                p,
                &mut self.traj,
                &mut self.buf,
            );
            if lean.is_err() {
                self.tried = self.progress.h;
            }
            lean?;
        }
        if opts.t_end - self.progress.s.t <= t_tol {
            return self.at_final_time().map(Some);
        }
        let p = &self.progress;
        budgets(opts, p.steps, p.evaluations, p.s.t)?;
        self.hold_switches();
        self.take_step(end)?;
        if self.sched.kinks.any() {
            let p = &mut self.progress;
            self.sched.kinks.land(
                sys,
                method,
                opts,
                (&p.s, p.hand),
                end,
                (self.sched.adaptive, t_tol),
                &mut self.sched.grid_end,
                &mut p.evaluations,
            )?;
        }
        if let Some(result) = self.band_in_step(end)? {
            return Ok(Some(result));
        }
        if let Some(hn) = end.h_next {
            self.progress.h = hn;
        }
        self.look_at(end)
    }

    /// A lock's band the step to `end.s1` carried the motion across unseen (see
    /// [`BandWatch`]): located as a dead centre met inside a step
    /// ([`dead_centre::locate`]), from the last state the finer walk accepted, and the run's
    /// result there. `None` when the step met no band: the run goes on from `end.s1` as
    /// before, only the evaluations of the finer walk counted.
    fn band_in_step(&mut self, end: &StepEnd<M::Dense>) -> Result<Option<RunResult>> {
        let Some(watch) = self.band.as_mut() else {
            return Ok(None);
        };
        let s = self.progress.s;
        let (sys, method, opts) = (self.sys, self.method, self.opts);
        let Some(r) = watch.check(sys, method, opts, &mut self.progress, (&s, &end.s1))? else {
            return Ok(None);
        };
        let kept = self.progress;
        let p = &mut self.progress;
        (p.s, p.prev, p.hand) = (r.from, r.from, Handover::default());
        match dead_centre::locate(sys, method, opts, p, r.h, &r.error)? {
            Some(d) => {
                let outcome = Outcome::DeadCentre {
                    t: d.last.t,
                    dyad: d.dyad,
                    value: d.value,
                };
                let recorded = self.traj.t().last() == Some(&d.last.t);
                self.result(d.last, recorded, outcome).map(Some)
            }
            None => {
                let spent = self.progress.evaluations;
                self.progress = kept;
                self.progress.evaluations = spent;
                Ok(None)
            }
        }
    }

    /// The result at the final time: [`Outcome::NotSteady`] when a steady state was asked
    /// for, else [`Outcome::FinalTime`].
    fn at_final_time(&mut self) -> Result<RunResult> {
        let s = self.progress.s;
        let outcome = match &self.opts.steady {
            Some(_) => Outcome::NotSteady {
                acceleration: match self.progress.hand.acceleration {
                    Some(a) => a,
                    None => accelerations(self.sys, s.t, &s.q, &s.qd)?,
                },
            },
            None => Outcome::FinalTime,
        };
        let recorded = self.traj.t().last() == Some(&s.t);
        self.result(s, recorded, outcome)
    }

    /// Sets the direction each switch's resistance is held in through the next step: the
    /// one its speed has at the step's start, or the one the motion breaks away in from a
    /// switch it was weighed at. Where a resistance's direction changes, the accelerations
    /// handed on from the step before (or from the start's row) belong to the other
    /// direction: they are dropped, and the step evaluates its own.
    fn hold_switches(&mut self) {
        let Some(modes) = self.modes else {
            return;
        };
        let mut changed = false;
        for (i, (mode, away)) in modes.iter().zip(&mut self.breakaway).enumerate() {
            let at_start = sign(self.sched.kinks.switch_speed(i));
            let new = if *away != 0.0 { *away } else { at_start };
            // The direction the forces were evaluated in, and will be (0 holds none: the
            // speed's own sign).
            let held = |m: f64| if m != 0.0 { m } else { at_start };
            changed |= held(mode.get()) != held(new);
            mode.set(new);
            *away = 0.0;
        }
        if changed {
            self.progress.hand.acceleration = None;
            self.progress.row_handed = false;
        }
    }

    /// What happens where the step landed on switch `i`'s zero at `s`: a release argument
    /// (after the system's switches) frees its coordinate, which breaks away in the drive's
    /// direction. A switch of the system is weighed: where its resistance does not hold, the
    /// motion breaks away in the drive's direction (the next step holds the resistance so);
    /// where it holds and it can hold its coordinate, the coordinate is held at rest (its
    /// rate set to an exact zero) unless that leaves a whole rest whose loads do not change
    /// with time; otherwise the run ends [`Outcome::Stuck`] at `s`.
    fn at_switch(&mut self, i: usize, s: State) -> Result<Landing> {
        let n = self.modes.map_or(0, <[_]>::len);
        if i >= n {
            return match self.hold.and_then(|h| h.holdable.get(i - n).copied()) {
                Some((switch, k)) => {
                    self.release(switch, k, &s)?;
                    Ok(Landing::Released)
                }
                None => Ok(Landing::Goes),
            };
        }
        let Some(loads) = self.weigh(i, s)? else {
            return Ok(Landing::Goes);
        };
        if let Some(hold) = self.hold
            && let Some(k) = hold.coordinate(i)
        {
            let mut held = s;
            held.qd[k] = 0.0;
            let whole = held.qd == nalgebra::Vector2::zeros();
            if !whole || self.sys.forces_depend_on_time() {
                hold.set(k, Some(i));
                self.held_changed(&held)?;
                return Ok(Landing::Held(held));
            }
        }
        let outcome = Outcome::Stuck {
            t: s.t,
            switch: i,
            loads,
        };
        self.result(s, false, outcome).map(Landing::Ends)
    }

    /// Frees coordinate `k`, held by `switch`, at `s`: it breaks away in the direction of
    /// the drive along the switch (held so through the next step).
    fn release(&mut self, switch: usize, k: usize, s: &State) -> Result<()> {
        let Some(hold) = self.hold else {
            return Ok(());
        };
        let loads = self.sys.switch_loads(switch, s.t, &s.q, &s.qd)?.checked()?;
        hold.set(k, None);
        let away = sign(loads.drive);
        if let Some(a) = self.breakaway.get_mut(switch) {
            *a = away;
        }
        // The other coordinates held, weighed again as this one starts to move.
        let others: Vec<(usize, usize)> = hold
            .holdable
            .iter()
            .copied()
            .filter(|&(i, k)| hold.holds(i, k))
            .collect();
        if !others.is_empty() {
            let keep = self.still_holding(s, &[(switch, k, away)], others.clone())?;
            for (i, k) in others {
                if !keep.contains(&(i, k)) {
                    hold.set(k, None);
                }
            }
        }
        self.held_changed(s)
    }

    /// Of the switches `holds` that hold their coordinates at `s`, those that still hold
    /// when the coordinates of `starting` (switch, coordinate, direction of its switch
    /// speed) start to move: each weighed at `s` with those rates a vanishing amount
    /// (10⁻²⁰⁰) the way they go, where the joints they set sliding have their friction. A
    /// switch that no longer holds breaks away in its drive's direction there.
    fn still_holding(
        &mut self,
        s: &State,
        starting: &[(usize, usize, f64)],
        holds: Vec<(usize, usize)>,
    ) -> Result<Vec<(usize, usize)>> {
        const TINY: f64 = 1e-200;
        let mut nudged = *s;
        let mut speeds = vec![0.0; self.sys.switches()];
        for &(i, k, dir) in starting {
            nudged.qd[k] = TINY;
            speeds.fill(f64::NAN);
            self.sys
                .switch_speeds(s.t, &nudged.q, &nudged.qd, &mut speeds)?;
            if sign(speeds.get(i).copied().unwrap_or(0.0)) != dir {
                nudged.qd[k] = -TINY;
            }
        }
        let mut keep = Vec::with_capacity(holds.len());
        for (i, k) in holds {
            let loads = self
                .sys
                .switch_loads(i, s.t, &nudged.q, &nudged.qd)?
                .checked()?;
            if loads.holds() {
                keep.push((i, k));
            } else if let Some(away) = self.breakaway.get_mut(i) {
                *away = sign(loads.drive);
            }
        }
        Ok(keep)
    }

    /// A held coordinate whose release argument is above zero at the step's end `s1`
    /// without a crossing located (it started the step exactly on zero: a drive exactly at
    /// the breakaway load when the hold began) is released there. Returns whether one was.
    fn released_late(&mut self, s1: &State) -> Result<bool> {
        let (Some(hold), Some(modes)) = (self.hold, self.modes) else {
            return Ok(false);
        };
        let n = modes.len();
        let late: Vec<(usize, usize)> = hold
            .holdable
            .iter()
            .enumerate()
            .filter(|&(r, &(i, k))| hold.holds(i, k) && self.sched.kinks.switch_speed(n + r) > 0.0)
            .map(|(_, &h)| h)
            .collect();
        for &(i, k) in &late {
            self.release(i, k, s1)?;
        }
        Ok(!late.is_empty())
    }

    /// After the held coordinates changed at `s`: the release arguments evaluated afresh
    /// there, and the accelerations handed on (those of the other motion) dropped.
    fn held_changed(&mut self, s: &State) -> Result<()> {
        self.sched.kinks.start(self.sys, s)?;
        self.progress.hand = Handover::default();
        self.progress.row_handed = false;
        Ok(())
    }

    /// Switch `i`'s loads at `s` (its speed zero there) when its resistance holds the
    /// motion; else `None`, the motion breaking away in the drive's direction (held so
    /// through the next step).
    fn weigh(&mut self, i: usize, s: State) -> Result<Option<SwitchLoads>> {
        let loads = self.sys.switch_loads(i, s.t, &s.q, &s.qd)?.checked()?;
        if loads.holds() {
            return Ok(Some(loads));
        }
        if let Some(away) = self.breakaway.get_mut(i) {
            *away = sign(loads.drive);
        }
        Ok(None)
    }

    /// The run's result, ending at `last`.
    fn result(&mut self, last: State, recorded: bool, outcome: Outcome) -> Result<RunResult> {
        let p = &self.progress;
        RunResult::finish(
            self.sys,
            &mut self.traj,
            &mut self.buf,
            (last, recorded),
            outcome,
            (p.steps, p.evaluations),
        )
    }

    /// Takes the next step as the schedule shapes it, counted, its end (into `end`) put
    /// exactly on the stop or the grid point it was asked to reach.
    fn take_step(&mut self, end: &mut StepEnd<M::Dense>) -> Result<()> {
        let (sys, method, opts) = (self.sys, self.method, self.opts);
        let t_tol = self.sched.t_tol;
        let p = &mut self.progress;
        let plan = self.sched.next_step(p.s.t, p.h, opts.t_end);
        let (s, hand_s, h_try, stop) = (p.s, p.hand, plan.h_try, plan.stop);
        self.tried = h_try;
        // A step that ends on a stop integrates up to it from the left: a force that jumps
        // there (written `if t < t_b`) is evaluated at its value before the jump in the
        // step's last stages, and at its new value from the next step on.
        // The continuous extension is built only when something will read it.
        let adv;
        (adv, end.dense) = match (plan.clamped, self.sched.wants_extension()) {
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
        let (mut s1, mut hand1) = accept(
            &s,
            &adv,
            &mut p.steps,
            &mut p.evaluations,
            &mut p.row_handed,
        )?;
        // The whole step asked for was taken: it ends on the stop or the grid point.
        let full = s1.t == s.t + h_try;
        let target = if plan.clamped { Some(stop) } else { plan.goal };
        if let Some(t) = target.filter(|_| full) {
            if s1.t != t {
                s1.t = t;
                hand1.acceleration = None; // they belong to the unsnapped time
            }
            if plan.clamped && stop < opts.t_end {
                // A breakpoint: the forces after it may differ, so neither the accelerations
                // nor the error of the step before it carry over.
                hand1 = Handover::default();
            }
        }
        snap_to_end(opts, t_tol, &mut s1, &mut hand1);
        if let Some(d) = end.dense.as_mut() {
            d.set_end(s1.t);
        }
        end.s1 = s1;
        end.hand = hand1;
        // The method's proposal, unless the run shortened the step.
        end.h_next = (!(target.is_some() && full)).then_some(adv.h_next);
        Ok(())
    }

    /// Looks at the end of a step: a watched value reached inside it, the requested times it
    /// passed, its row, a steady state. Returns the result when the run ends there; else the
    /// next step starts from the step's end.
    fn look_at(&mut self, end: &StepEnd<M::Dense>) -> Result<Option<RunResult>> {
        let (sys, method, opts) = (self.sys, self.method, self.opts);
        let (s1, dense, mut hand1) = (end.s1, end.dense.as_ref(), end.hand);
        let s = self.progress.s;
        let hit = match self.reach.as_mut() {
            Some(r) => r.check(
                sys,
                method,
                opts,
                (&s, &s1),
                &mut self.buf,
                &mut self.progress.evaluations,
            )?,
            None => None,
        };
        let turned = match self.reversal.as_mut() {
            Some(w) => w.check(sys, method, opts, (&s, &s1), &mut self.progress.evaluations)?,
            None => None,
        };
        // The earlier of the two ends the run (the value reached, on a tie).
        let reach_first = hit.is_some_and(|h| turned.is_none_or(|r| h.t <= r.t));
        let at_end = self.sched.record_times(
            sys,
            method,
            opts,
            (&s, &s1),
            if reach_first { hit } else { turned.or(hit) },
            dense,
            &mut self.traj,
            &mut self.buf,
        )?;
        if let Some(located) = hit.filter(|_| reach_first) {
            return self
                .result(located, false, Outcome::Reached { t: located.t })
                .map(Some);
        }
        let mut s1 = s1;
        // A hold or a release is recorded where it happens, on any method's grid.
        let mut event = false;
        if let Some(i) = self.sched.kinks.landed_switch() {
            match self.at_switch(i, s1)? {
                Landing::Ends(result) => return Ok(Some(result)),
                Landing::Held(s_held) => {
                    s1 = s_held;
                    hand1 = Handover::default();
                    event = true;
                }
                Landing::Released => {
                    hand1 = Handover::default();
                    event = true;
                }
                Landing::Goes => {}
            }
        }
        if self.released_late(&s1)? {
            hand1 = Handover::default();
            event = true;
        }
        if let Some(back) = turned {
            // A motion that stuck at a switch landed on has not turned back (weighed above).
            self.reversed = true;
            let recorded = self.traj.t().last() == Some(&back.t);
            return self
                .result(back, recorded, Outcome::Reached { t: back.t })
                .map(Some);
        }
        // Steps cut short on the grid of a fixed-step method count once, with their rest.
        let p = &mut self.progress;
        let mut on_grid_record = false;
        if self.sched.grid_end.is_none() {
            p.until_record -= 1;
            if p.until_record == 0 {
                p.until_record = opts.record_every;
                on_grid_record = true;
            }
        }
        let mut recorded = false;
        if at_end || on_grid_record || (event && self.traj.t().last() != Some(&s1.t)) {
            // One row stays free for the end.
            p.row_handed = record_end(
                sys,
                opts,
                self.sched.t_tol,
                self.takes_rows,
                &s1,
                &mut hand1,
                &mut self.traj,
                &mut self.buf,
            )?;
            recorded = true;
        }
        p.hand = hand1;
        if let Some(st) = self.steady.as_mut()
            && let Some(outcome) = st.check(sys, &s1, hand1)?
        {
            return self.result(s1, recorded, outcome).map(Some);
        }
        self.progress.prev = s;
        self.progress.s = s1;
        Ok(None)
    }
}
