//! How close a closed form is to dividing by zero.

use crate::error::{Error, Result};

/// The quantity a closed-form solver divides by, and the amplification that division causes.
///
/// `measure` is the quantity itself, in the units the solver documents (a sine or cosine of
/// two link directions, or a length in metres). `condition` is a dimensionless factor, at least
/// 1, by which rounding errors of the inputs are amplified in the reactions, relative to the
/// largest load or reaction: expect relative errors of about `condition × 1e-16`. A well-shaped
/// group has a condition of a few units; near a dead point it grows like 1/|measure|.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Conditioning {
    /// The quantity that vanishes at the singular configuration.
    pub measure: f64,
    /// The amplification of rounding errors, ≥ 1.
    pub condition: f64,
}

/// Below this relative size a divisor carries no significant digit: the configuration is
/// treated as exactly singular.
const SINGULAR_BELOW: f64 = 8.0 * f64::EPSILON;

impl Conditioning {
    /// The conditioning of a division by `measure`, where `scale` is the size `measure` has in a
    /// well-shaped configuration (1 for a sine, a characteristic length for a length).
    ///
    /// # Errors
    /// [`Error::Singular`] naming `what` and `name` when |measure| ≤ 8ε·scale.
    pub(crate) fn of(
        what: &'static str,
        name: &'static str,
        measure: f64,
        scale: f64,
    ) -> Result<Self> {
        let relative = measure.abs() / scale;
        if relative.is_nan() || relative <= SINGULAR_BELOW {
            return Err(Error::Singular {
                what,
                measure: name,
                value: measure,
            });
        }
        Ok(Self {
            measure,
            condition: (1.0 / relative).max(1.0),
        })
    }

    /// For a solver's fast path, which multiplies by `inverse` = 1/`measure` instead of
    /// dividing: the conditioning (the same as [`of`](Self::of) up to the rounding of the
    /// inverse) and whether the configuration is clearly regular, that is, at least twice as
    /// far from singular as [`of`](Self::of) requires. Near the threshold the fast path gives
    /// way to the checked one, so that a rounding difference between the two cannot move a
    /// configuration across it: [`Error::Singular`] is reported exactly where it was.
    #[inline]
    pub(crate) fn fast(measure: f64, inverse: f64, scale: f64) -> (Self, bool) {
        (
            Self {
                measure,
                condition: (inverse.abs() * scale).max(1.0),
            },
            measure.abs() > 2.0 * SINGULAR_BELOW * scale,
        )
    }

    /// The conditioning of a solver that never divides by a configuration-dependent quantity.
    pub(crate) fn perfect() -> Self {
        Self {
            measure: 1.0,
            condition: 1.0,
        }
    }
}

/// `true` when every component of eight pairs is finite, by one test of their sum: a sum with
/// an infinity or a NaN among its terms is not finite. A sum of finite values can still
/// overflow; then this says `false` too, and the solver's checked path, which names the value
/// at fault, runs instead: the test may send a good case there, never let a bad one through.
/// The sum is a tree of vector additions (three deep), not a chain.
#[inline(always)]
pub(crate) fn finite_sum(v: [nalgebra::Vector2<f64>; 8]) -> bool {
    let s = ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7]));
    (s.x + s.y).is_finite()
}

/// Turns an overflow in a result into an error, so that no solver returns an infinity:
/// [`Error::Singular`] naming the measure when the (relative) measure is below √ε, so that
/// the division by it did the damage near a dead point, else [`Error::Overflow`] naming the
/// group (the inputs are too large for `f64`).
pub(crate) fn ensure_finite(
    what: &'static str,
    name: &'static str,
    measure: f64,
    values: &[f64],
) -> Result<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else if measure.abs() < f64::EPSILON.sqrt() {
        Err(Error::Singular {
            what,
            measure: name,
            value: measure,
        })
    } else {
        Err(Error::Overflow { what })
    }
}
