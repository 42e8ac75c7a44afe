//! A direction angle for the hot paths of the groups of the 3rd class: the angle of a vector
//! in [0, 2π), as [`angle::direction`](crate::angle::direction) to within two units in the
//! last place, without libm's `atan2` (whose call, and its saving and restoring of the
//! rounding mode, cost about 11 ns; a triad's state needs four angles a position).
//!
//! # The reduction
//! With n = min(|x|, |y|) and d = max(|x|, |y|) the angle folds into [0, π/4] as atan(n/d);
//! above tan(π/8) the pair turns back by π/4, (n, d) → (n − d, n + d) (a turn by −π/4 scaled
//! by √2, exact up to the two roundings of the sums, which move the angle by at most ε),
//! so that one division leaves t with |t| ≤ tan(π/8) = 0.4142 and α = base + atan(t). The
//! octant's and the quadrant's reflections (π/2 − α, π − β, 2π − γ) are one rounding each.
//!
//! # atan on |t| ≤ tan(π/8)
//! atan(t) = t + t·s·P(s) with s = t², P the degree-10 Chebyshev fit of
//! (atan(√s) − √s)/s^{3/2} on [0, tan²(π/8)] (derived with mpmath's `chebyfit` at 40
//! digits: the fit's error is 3.2e-17, so the term t·s·P(s) is off by at most
//! 3.2e-17·s·|t| ≤ 5.5e-18·|t|, below a twentieth of an ulp of atan(t); evaluated in doubles
//! the whole atan is within 0.53 ulp over 2·10⁴ samples). P is evaluated in Estrin's scheme
//! (four levels of products instead of a chain of ten), since a triad's four angles are
//! independent and the processor overlaps them.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// tan(π/8), rounded (the boundary of the turn by π/4; any value near it works).
const TAN_PI_8: f64 = 0.414_213_562_373_095_03;

/// The coefficients of P(s), of s⁰ … s¹⁰ (module docs).
const P: [f64; 11] = [
    -0.333_333_333_333_333_3,
    0.199_999_999_999_955_2,
    -0.142_857_142_846_665_42,
    0.111_111_110_152_563_61,
    -0.090_909_045_781_239_03,
    0.076_921_831_908_260_87,
    -0.066_645_114_473_819_48,
    0.058_581_489_128_022_1,
    -0.050_854_497_379_402_6,
    0.039_231_658_295_587_19,
    -0.019_176_887_119_062_26,
];

/// atan(t) for |t| ≤ tan(π/8) (module docs).
#[inline(always)]
fn atan_small(t: f64) -> f64 {
    let s = t * t;
    let s2 = s * s;
    let s4 = s2 * s2;
    let s8 = s4 * s4;
    let q0 = P[0] + P[1] * s;
    let q1 = P[2] + P[3] * s;
    let q2 = P[4] + P[5] * s;
    let q3 = P[6] + P[7] * s;
    let q4 = P[8] + P[9] * s;
    let r0 = q0 + q1 * s2;
    let r1 = q2 + q3 * s2;
    let r2 = q4 + P[10] * s2;
    let p = (r0 + r1 * s4) + r2 * s8;
    t + t * s * p
}

/// The direction angle of (x, y) in [0, 2π): [`angle::direction`](crate::angle::direction)
/// within two ulps (0 for the zero vector, NaN for NaN); infinite or huge components (whose
/// sum overflows) go to it.
#[inline(always)]
pub(super) fn direction_of(x: f64, y: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let swap = ay > ax;
    let (n, d) = if swap { (ax, ay) } else { (ay, ax) };
    let upper = n > TAN_PI_8 * d;
    let (num, den, base) = if upper {
        (n - d, n + d, FRAC_PI_4)
    } else {
        (n, d, 0.0)
    };
    if den.is_nan() || den > f64::MAX {
        // Infinite components or a sum that overflows (and NaN): the library's angle.
        return crate::angle::direction(nalgebra::Vector2::new(x, y));
    }
    if den == 0.0 {
        return 0.0;
    }
    let alpha = base + atan_small(num / den);
    let beta = if swap { FRAC_PI_2 - alpha } else { alpha };
    let gamma = if x < 0.0 { PI - beta } else { beta };
    if y < 0.0 {
        let r = TAU - gamma;
        // The angle 0 reached from below rounds to 2π: it is the angle 0.
        if r >= TAU {
            0.0
        } else {
            r
        }
    } else {
        gamma
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::direction;
    use nalgebra::Vector2;

    /// |a − b| in units of the last place of the larger, the two read on the circle (an angle
    /// just below 2π against one just above 0).
    fn ulps(a: f64, b: f64) -> f64 {
        let mut d = (a - b).abs();
        if d > PI {
            d = TAU - d;
        }
        let big = a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
        d / (big * f64::EPSILON)
    }

    /// Against libm's atan2 (through `angle::direction`): a million seeded directions over
    /// the whole circle and magnitudes from 1e-300 to 1e300, the octants' and axes'
    /// boundaries, the tan(π/8) boundary, tiny components beside large ones, signed zeros.
    #[test]
    fn direction_of_matches_the_library_within_two_ulps() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut worst: f64 = 0.0;
        let mut check = |x: f64, y: f64| {
            let (a, b) = (direction_of(x, y), direction(Vector2::new(x, y)));
            assert!((0.0..TAU).contains(&a), "{a} for ({x}, {y})");
            let e = ulps(a, b);
            assert!(e <= 2.0, "({x:e}, {y:e}): {a} against {b} ({e} ulps)");
            worst = worst.max(e);
        };
        for _ in 0..1_000_000 {
            let th = TAU * next();
            let mag = 10f64.powf(600.0 * next() - 300.0);
            check(mag * th.cos(), mag * th.sin());
        }
        for k in 0..16 {
            let th = FRAC_PI_4 * 0.5 * k as f64;
            for dt in [-1e-15, -1e-9, 0.0, 1e-9, 1e-15] {
                check((th + dt).cos(), (th + dt).sin());
            }
        }
        for (x, y) in [
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, 1.0),
            (0.0, -1.0),
            (1.0, -0.0),
            (-1.0, -0.0),
            (1.0, 1.0),
            (-1.0, -1.0),
            (1.0, TAN_PI_8),
            (1.0, -1e-300),
            (-1.0, 1e-300),
            (1e-310, 1.0),
            (1.0, 5e-324),
            (1.0, -5e-324),
        ] {
            check(x, y);
        }
        println!("direction_of: at most {worst:.2} ulps from the library's");
        assert_eq!(direction_of(0.0, 0.0), 0.0);
        assert_eq!(
            direction_of(1e308, 1e308),
            direction(Vector2::new(1e308, 1e308))
        );
        assert_eq!(
            direction_of(f64::INFINITY, 1.0),
            direction(Vector2::new(f64::INFINITY, 1.0))
        );
        assert!(direction_of(f64::NAN, 1.0).is_nan());
        assert!(direction_of(1.0, f64::NAN).is_nan());
    }
}
