//! Locating a state inside a step where a function of the state vanishes (a kink's argument
//! on its node, a watched quantity on its value), by re-stepping from the step's start.

use super::options::RunOptions;
use crate::dynamics::stepper::Stepper;
use crate::dynamics::system::{LagrangeSystem, State};
use crate::error::{Error, Result};

/// The evaluations a run may still spend (`left` of its budget `limit`): locating a state
/// inside a step stops at the budget as stepping does, rather than overshooting it by up to a
/// hundred re-steps per located state.
#[derive(Clone, Copy)]
pub(super) struct Allowance {
    pub(super) left: usize,
    limit: usize,
}

impl Allowance {
    /// What is left of `opts`' evaluation budget after `spent`.
    pub(super) fn after(opts: &RunOptions, spent: usize) -> Self {
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
pub(super) fn locate<S: LagrangeSystem + ?Sized, M: Stepper>(
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
