//! Crank angles: ranges, normalisation, and the order in which a crank meets them.

use std::f64::consts::TAU;

pub(super) fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        })
}

pub(super) fn normalize_angle(a: f64) -> f64 {
    crate::angle::normalize(a)
}

/// The arc (start, span) the crank sweeps to reach the angles `phis` in their order, turning
/// one way by less than a turn: `None` when no sense does (an order defect).
pub(super) fn ordered_arc(phis: &[f64]) -> Option<(f64, f64)> {
    let sweep = |sense: f64| -> f64 {
        phis.windows(2)
            .map(|w| (sense * (w[1] - w[0])).rem_euclid(TAU))
            .sum()
    };
    let n = phis.len();
    let (fwd, bwd) = (sweep(1.0), sweep(-1.0));
    if n == 0 {
        None
    } else if fwd < TAU {
        Some((phis[0], fwd))
    } else if bwd < TAU {
        Some((phis[n - 1], bwd))
    } else {
        None
    }
}

/// Whether the angles `phis`, taken cyclically in order, go round once in one sense: the
/// points of a closed curve met in order, once per turn.
pub(super) fn once_round(phis: &[f64]) -> bool {
    let n = phis.len();
    [1.0, -1.0].into_iter().any(|sense: f64| {
        let sum: f64 = (0..n)
            .map(|i| (sense * (phis[(i + 1) % n] - phis[i])).rem_euclid(TAU))
            .sum();
        (sum - TAU).abs() < 1e-6
    })
}
