//! Landing on kinks: the nodes of the system's kink arguments (and the zeros of its switch
//! speeds) crossed inside a step, the earliest found and the step taken again to end exactly
//! there.

use super::locate::{locate, Allowance};
use super::options::RunOptions;
use super::progress::StepEnd;
use crate::dynamics::stepper::{ContinuousExtension, Handover, Stepper};
use crate::dynamics::system::{LagrangeSystem, State};
use crate::error::{Error, Result};

/// An argument and one of its nodes.
type Node = (usize, usize);

/// The first node of argument `k` crossed strictly by a step from σ0 to σ1 (in the direction
/// of motion), other than the (argument, node) pairs in `skip` (those the step starts on or
/// was cut short onto).
fn first_crossed(nodes: &[f64], s0: f64, s1: f64, k: usize, skip: &[Node]) -> Option<usize> {
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

/// Every kink argument at a state, into `out` (one entry per argument, each set to NaN first
/// so that one the system leaves unset is caught as not finite): the system's `n_args` kink
/// arguments, then its switch speeds.
#[inline]
fn kink_args<S: LagrangeSystem + ?Sized>(
    sys: &S,
    st: &State,
    out: &mut [f64],
    n_args: usize,
) -> Result<()> {
    out.fill(f64::NAN);
    let (args, speeds) = out.split_at_mut(n_args);
    if !args.is_empty() {
        sys.kink_arguments(st.t, &st.q, &st.qd, args)?;
    }
    if !speeds.is_empty() {
        sys.switch_speeds(st.t, &st.q, &st.qd, speeds)?;
    }
    if out.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFiniteState { time: st.t })
    }
}

/// The kinks of a run: each argument's nodes, and the arguments at the start of the step under
/// way.
pub(super) struct Kinks {
    /// The nodes of each argument, sorted: the system's kink arguments, then one argument
    /// per switch speed with the one node 0.
    nodes: Vec<Vec<f64>>,
    /// How many of the arguments are the system's kink arguments (the rest are switches).
    n_args: usize,
    /// Whether there is any node at all.
    any: bool,
    /// The arguments at the start of the step (σ), at its end (σ₁), and at a trial state.
    sigma: Vec<f64>,
    sigma1: Vec<f64>,
    probe: Vec<f64>,
    /// The crossings found in a step.
    crossed: Vec<Node>,
    /// The nodes the last step landed on (the next step starts there: no crossing).
    on_kink: Vec<Node>,
    /// Nodes crossed at the time of the earliest one located (within the time's rounding),
    /// other than the one chosen to land on.
    coincident: Vec<Node>,
}

impl Kinks {
    /// The kinks with these nodes for each of the system's kink arguments, and `switches`
    /// switch speeds.
    pub(super) fn new(mut nodes: Vec<Vec<f64>>, switches: usize) -> Self {
        let n_args = nodes.len();
        nodes.extend(std::iter::repeat_n(vec![0.0], switches));
        let n = nodes.len();
        Self {
            any: nodes.iter().any(|v| !v.is_empty()),
            nodes,
            n_args,
            sigma: vec![0.0; n],
            sigma1: vec![0.0; n],
            probe: vec![0.0; n],
            crossed: Vec::new(),
            on_kink: Vec::new(),
            coincident: Vec::new(),
        }
    }

    /// Whether there is any node to land on.
    #[inline]
    pub(super) fn any(&self) -> bool {
        self.any
    }

    /// Evaluates the arguments at the run's start.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] when an argument is not finite (or left unset).
    pub(super) fn start<S: LagrangeSystem + ?Sized>(&mut self, sys: &S, s: &State) -> Result<()> {
        kink_args(sys, s, &mut self.sigma, self.n_args)
    }

    /// The switches whose speed is exactly zero at the start of the next step.
    pub(super) fn switches_at_zero(&self) -> impl Iterator<Item = usize> + '_ {
        (self.n_args..self.nodes.len())
            .filter(|&k| self.sigma[k] == 0.0)
            .map(|k| k - self.n_args)
    }

    /// The speed of switch `i` at the start of the next step.
    pub(super) fn switch_speed(&self, i: usize) -> f64 {
        self.sigma[self.n_args + i]
    }

    /// The switch the last step landed on (its speed located at zero), if any.
    pub(super) fn landed_switch(&self) -> Option<usize> {
        self.on_kink
            .iter()
            .find(|&&(k, _)| k >= self.n_args)
            .map(|&(k, _)| k - self.n_args)
    }

    /// Whether argument k has passed node i at a state whose arguments are `v`.
    #[inline]
    fn passed(&self, v: &[f64], (k, i): Node) -> bool {
        let node = self.nodes[k][i];
        (v[k] < node) != (self.sigma[k] < node)
    }

    /// Cuts the step `s` → `end` short onto the earliest node crossed inside it, if any: it is
    /// located (re-stepping from `s`) and the step taken again to end there (with error control
    /// for an adaptive method; `hand_s` is what the step before handed on). A fixed-step method
    /// cut short remembers the end of its grid step in `grid_end`. Each pass either ends or
    /// skips one more node, so this ends after at most as many passes as there are nodes.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for an argument that is not finite, [`Error::Budget`] when
    /// the evaluations run out, any error of the system or the method.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn land<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        opts: &RunOptions,
        (s, hand_s): (&State, Handover),
        end: &mut StepEnd<M::Dense>,
        (adaptive, t_tol): (bool, f64),
        grid_end: &mut Option<f64>,
        evaluations: &mut usize,
    ) -> Result<()> {
        // The (argument, node) pairs a crossing must not be taken for: those the step starts
        // on (found so, or located within rounding of its start) and those it has already
        // been cut short onto.
        let mut skip = std::mem::take(&mut self.on_kink);
        let mut landed = None;
        loop {
            kink_args(sys, &end.s1, &mut self.sigma1, self.n_args)?;
            self.crossed.clear();
            for (k, nodes) in self.nodes.iter().enumerate() {
                if let Some(i) = first_crossed(nodes, self.sigma[k], self.sigma1[k], k, &skip) {
                    self.crossed.push((k, i));
                }
            }
            if self.crossed.is_empty() {
                break;
            }
            let ((k, i), hit, resteps) = match &end.dense {
                Some(d) => {
                    let allowance = Allowance::after(opts, *evaluations);
                    self.earliest_by_extension(sys, method, (s, &end.s1), d, allowance)?
                }
                None => {
                    match self.earliest_by_locating(
                        sys,
                        method,
                        opts,
                        (s, &end.s1),
                        (*evaluations, t_tol),
                    )? {
                        Some(found) => found,
                        None => break, // not reached: `crossed` is not empty
                    }
                }
            };
            *evaluations =
                evaluations.saturating_add(resteps.saturating_mul(method.evaluations_per_step()));
            // Nodes crossed at the same time as the one chosen (a switch speed that is also a
            // kink argument's rate) are landed on with it: not located again, nor taken for a
            // crossing at the start of the next step.
            skip.append(&mut self.coincident);
            skip.push((k, i));
            let hk = hit.t - s.t;
            if hk <= t_tol {
                // Within rounding of the start: the step starts on this node; look again for
                // the crossings after it.
                continue;
            }
            if hit.t >= end.s1.t {
                landed = Some((k, i));
                break;
            }
            // Cut the step short onto the crossing, then check that no other crossing (missed
            // by the extension's first guess) lies before it.
            if Allowance::after(opts, *evaluations).left < method.evaluations_per_step() {
                return Err(Error::Budget {
                    what: "evaluation",
                    limit: opts.max_evaluations,
                    time: s.t,
                });
            }
            let (adv2, dense2) = method.advance_dense(sys, s, hk, Some(hand_s))?;
            *evaluations = evaluations.saturating_add(adv2.evaluations);
            if !adaptive && grid_end.is_none() {
                *grid_end = Some(end.s1.t);
            }
            end.s1 = adv2.state;
            end.dense = dense2;
            end.hand = adv2.handover;
            if end.s1.t == s.t + hk {
                landed = Some((k, i));
                end.h_next = None;
            } else {
                landed = None;
                end.h_next = Some(adv2.h_next);
            }
        }
        // σ at the step's end is where the next step starts.
        std::mem::swap(&mut self.sigma, &mut self.sigma1);
        skip.clear();
        skip.extend(landed);
        self.on_kink = skip;
        Ok(())
    }

    /// The earliest crossing of the step `s` → `s1` from its continuous extension (no
    /// evaluation), by bisection on "some argument has passed its node", then located from
    /// there as a first guess. Returns the node, the located state and the re-steps spent.
    fn earliest_by_extension<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        (s, s1): (&State, &State),
        d: &M::Dense,
        allowance: Allowance,
    ) -> Result<(Node, State, usize)> {
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        let mut first = self.crossed[0];
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            kink_args(
                sys,
                &d.at(s.t + mid * (s1.t - s.t))?,
                &mut self.probe,
                self.n_args,
            )?;
            match self.crossed.iter().find(|&&c| self.passed(&self.probe, c)) {
                Some(&c) => {
                    first = c;
                    hi = mid;
                }
                None => lo = mid,
            }
        }
        // Every crossing passed at `hi` but not at `lo` lies where `first` does (within 2⁻⁶⁰
        // of the step): a switch among them is the one to land on (its zero is where the run
        // weighs its loads), the others coincide with it.
        kink_args(
            sys,
            &d.at(s.t + hi * (s1.t - s.t))?,
            &mut self.probe,
            self.n_args,
        )?;
        let together: Vec<Node> = self
            .crossed
            .iter()
            .copied()
            .filter(|&c| self.passed(&self.probe, c))
            .collect();
        if first.0 < self.n_args
            && let Some(&switch) = together.iter().find(|c| c.0 >= self.n_args)
        {
            first = switch;
        }
        self.coincident = together.into_iter().filter(|&c| c != first).collect();
        let node = self.nodes[first.0][first.1];
        let (f0, f1) = (self.sigma[first.0] - node, self.sigma1[first.0] - node);
        let (probe, n_args) = (&mut self.probe, self.n_args);
        let (hit, resteps) = locate(
            sys,
            method,
            (s, f0),
            (s1, f1),
            Some(0.5 * (lo + hi)),
            allowance,
            |st| {
                kink_args(sys, st, probe, n_args)?;
                Ok(probe[first.0] - node)
            },
        )?;
        Ok((first, hit, resteps))
    }

    /// Without an extension: each crossing of the step `s` → `s1` located by re-stepping,
    /// the earliest kept (`evaluations` spent before); of crossings located within `t_tol`
    /// of each other a switch is kept (its zero is where the run weighs its loads: an input's
    /// own joint friction has its rate as a kink argument and as a switch speed), the others
    /// noted as coincident. Returns the node, the located state and the re-steps spent on all
    /// of them (`None` when nothing was crossed).
    fn earliest_by_locating<S: LagrangeSystem + ?Sized, M: Stepper>(
        &mut self,
        sys: &S,
        method: &M,
        opts: &RunOptions,
        (s, s1): (&State, &State),
        (evaluations, t_tol): (usize, f64),
    ) -> Result<Option<(Node, State, usize)>> {
        let mut earliest: Option<(Node, State)> = None;
        let mut hits: Vec<(Node, f64)> = Vec::with_capacity(self.crossed.len());
        let mut resteps: usize = 0;
        for &(k, i) in &self.crossed {
            let node = self.nodes[k][i];
            let (probe, n_args) = (&mut self.probe, self.n_args);
            let (hit, n) = locate(
                sys,
                method,
                (s, self.sigma[k] - node),
                (s1, self.sigma1[k] - node),
                None,
                Allowance::after(
                    opts,
                    evaluations
                        .saturating_add(resteps.saturating_mul(method.evaluations_per_step())),
                ),
                |st| {
                    kink_args(sys, st, probe, n_args)?;
                    Ok(probe[k] - node)
                },
            )?;
            resteps += n;
            hits.push(((k, i), hit.t));
            let n_args = self.n_args;
            if earliest.is_none_or(|(c, e)| {
                hit.t < e.t - t_tol || (hit.t <= e.t + t_tol && k >= n_args && c.0 < n_args)
            }) {
                earliest = Some(((k, i), hit));
            }
        }
        if let Some((c, e)) = &earliest {
            self.coincident = hits
                .into_iter()
                .filter(|&(h, t)| h != *c && (t - e.t).abs() <= t_tol)
                .map(|(h, _)| h)
                .collect();
        }
        Ok(earliest.map(|(c, hit)| (c, hit, resteps)))
    }
}
