//! The program's budgets. Every bound on a command's work is a count derived from the input —
//! positions, RK4 steps, candidate evaluations — weighed by the linkage's structure, never a
//! measurement of the clock: the same command gives the same output, or is refused with the
//! same sentence, on a quiet machine and on a loaded one.
//!
//! The unit of work is one solve of a closed-form group (a dyad) at one position. One solve
//! of a whole linkage weighs [`INPUT_WEIGHT`] for each input, 1 for each dyad,
//! [`TRIAD_WEIGHT`] for each triad and [`general_weight`] for each larger group. The weights
//! are the ratios of the reduced quantities' cost per position measured once on the bundled
//! files (release build, one core of the 2-core test machine): a dyad about 0.15 µs, the
//! triads of `six-bar-triad` and `six-bar-slider-triad` about 2 µs, the six-joint general
//! group of `double-butterfly` about 60 µs. They are a bound's yardstick, not a prediction.

use crate::model::Failure;

/// The most work one stage of a command may do (a table, the reduced quantities, a run-up, a
/// grid, a picture), in solves of a dyad: 4·10⁸, about a minute of one core where a dyad
/// takes 0.15 µs. A stage asked to do more is refused before it starts.
pub const MAX_WORK: f64 = 4e8;

/// The weight of an input link's own solve (a crank's or a slider's position).
pub const INPUT_WEIGHT: f64 = 1.0;

/// The weight of a triad (an Assur group of the 3rd class): its mode found by a certified
/// scan of a trigonometric polynomial, then its rates — measured at about 13 dyads, taken as
/// 16.
pub const TRIAD_WEIGHT: f64 = 16.0;

/// The weight of a general group of `inner` inner joints, solved by Newton's method on its
/// 2·`inner` closure equations: a dense LU of that size costs about (2n)³/3 operations, so
/// the weight grows as the cube, (2n)³/4 — 432 for the double butterfly's six joints,
/// against the 400 measured.
#[must_use]
pub fn general_weight(inner: usize) -> f64 {
    #[allow(clippy::cast_precision_loss)]
    let unknowns = 2.0 * inner as f64;
    (unknowns.powi(3) / 4.0).max(1.0)
}

/// The most solves of a linkage whose one solve weighs `weight` that a stage may make:
/// ⌊[`MAX_WORK`] / `weight`⌋.
#[must_use]
pub fn most_solves(weight: f64) -> f64 {
    (MAX_WORK / weight.max(1.0)).floor()
}

/// Refuses, before any work, a stage of `solves` solves of a linkage whose one solve weighs
/// `weight` when their work is above [`MAX_WORK`]: one sentence naming `what` is asked, the
/// count, the most this linkage allows, and `fix` (the option to change).
///
/// # Errors
/// The work is above the budget.
pub fn check(solves: f64, weight: f64, what: &str, fix: &str) -> Result<(), Failure> {
    let most = most_solves(weight);
    if solves <= most {
        return Ok(());
    }
    Err(Failure::new(format!(
        "{what}: {solves:.0} solves of the linkage's positions, above the {most:.0} one stage \
         of a command may make for this linkage (a budget of {MAX_WORK:e} dyad solves, and \
         one solve of this linkage weighs {weight} of them)"
    ))
    .hint(fix.to_owned()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_double_butterflys_group_weighs_432_dyads() {
        assert_eq!(general_weight(6), 432.0);
        assert_eq!(most_solves(433.0), (4e8_f64 / 433.0).floor());
        assert!(check(most_solves(433.0), 433.0, "x", "y").is_ok());
        assert!(check(most_solves(433.0) + 1.0, 433.0, "x", "y").is_err());
    }
}
