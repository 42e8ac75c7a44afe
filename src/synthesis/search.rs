#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > y)` rejects NaN too, on purpose.
//! A bounded 1-D maximisation: a dense scan, then golden section between the best sample's
//! neighbours. The objective may be undefined (`None`) on parts of the interval (designs that
//! do not exist there); those count as −∞.

/// The argument in [`lo`, `hi`] where `f` is largest, and the value there: `n` samples, the
/// best one refined by golden section to 1e-13 of the interval. `None` when `f` is undefined
/// at every sample.
pub(crate) fn maximise<F>(f: F, lo: f64, hi: f64, n: usize) -> Option<(f64, f64)>
where
    F: Fn(f64) -> Option<f64>,
{
    let n = n.max(2);
    let h = (hi - lo) / (n - 1) as f64;
    let at = |k: usize| if k + 1 == n { hi } else { lo + h * k as f64 };
    let mut best: Option<(usize, f64)> = None;
    for k in 0..n {
        if let Some(v) = f(at(k)).filter(|v| v.is_finite())
            && best.is_none_or(|(_, b)| v > b)
        {
            best = Some((k, v));
        }
    }
    let (k, v) = best?;
    let value = |x: f64| f(x).filter(|v| v.is_finite()).unwrap_or(f64::NEG_INFINITY);
    let mut g = Golden::new(at(k.saturating_sub(1)), at((k + 1).min(n - 1)), &value);
    // Relative to the interval, but never below the arguments' own spacing: a narrow
    // interval far from zero would otherwise be split for ever.
    let spacing = 4.0 * f64::EPSILON * lo.abs().max(hi.abs());
    let tol = (1e-13 * (hi - lo).abs())
        .max(spacing)
        .max(f64::MIN_POSITIVE);
    for _ in 0..400 {
        if !((g.b - g.a).abs() > tol) {
            break;
        }
        g.step(&value);
    }
    let (x, fx) = if g.f1 >= g.f2 {
        (g.x1, g.f1)
    } else {
        (g.x2, g.f2)
    };
    Some(if fx > v { (x, fx) } else { (at(k), v) })
}

/// A golden-section search for a maximum on [a, b]: its two inner points and their values.
struct Golden {
    a: f64,
    b: f64,
    x1: f64,
    x2: f64,
    f1: f64,
    f2: f64,
}

/// The golden ratio's conjugate, (√5 − 1)/2: each step keeps this share of the bracket.
const GOLDEN: f64 = 0.618_033_988_749_894_8;

impl Golden {
    fn new(a: f64, b: f64, value: &impl Fn(f64) -> f64) -> Self {
        let (x1, x2) = (b - GOLDEN * (b - a), a + GOLDEN * (b - a));
        Self {
            a,
            b,
            x1,
            x2,
            f1: value(x1),
            f2: value(x2),
        }
    }

    /// Drops the part of the bracket beyond the lower inner point (one new value).
    fn step(&mut self, value: &impl Fn(f64) -> f64) {
        if self.f1 >= self.f2 {
            (self.b, self.x2, self.f2) = (self.x2, self.x1, self.f1);
            self.x1 = self.b - GOLDEN * (self.b - self.a);
            self.f1 = value(self.x1);
        } else {
            (self.a, self.x1, self.f1) = (self.x1, self.x2, self.f2);
            self.x2 = self.a + GOLDEN * (self.b - self.a);
            self.f2 = value(self.x2);
        }
    }
}

/// Feasible stretches of [`lo`, `hi`] narrower than a scan's step: `margin` is a continuous
/// measure that is positive where a design exists (`ok`). Where its `n` samples peak below
/// zero, the peak is sought by golden section between the peak's neighbours; a peak where
/// `ok` holds is widened by bisection (on `ok`) to the stretch's two ends. Each stretch is
/// returned as (start, end). Stretches the scan itself sees are not looked for.
pub(crate) fn narrow_stretches<M, K>(
    margin: M,
    ok: K,
    lo: f64,
    hi: f64,
    n: usize,
) -> Vec<(f64, f64)>
where
    M: Fn(f64) -> f64,
    K: Fn(f64) -> bool,
{
    let n = n.max(3);
    let h = (hi - lo) / (n - 1) as f64;
    let at = |k: usize| if k + 1 == n { hi } else { lo + h * k as f64 };
    let value = |x: f64| {
        let m = margin(x);
        if m.is_nan() {
            f64::NEG_INFINITY
        } else {
            m
        }
    };
    let m: Vec<f64> = (0..n).map(|k| value(at(k))).collect();
    let mut out = Vec::new();
    for k in 1..n - 1 {
        // A peak (a plateau counts at its first sample) below zero.
        if !(m[k] <= 0.0 && m[k] > m[k - 1] && m[k] >= m[k + 1]) {
            continue;
        }
        let mut g = Golden::new(at(k - 1), at(k + 1), &value);
        let mut found = None;
        for _ in 0..200 {
            // The margin is cheap and `ok` is not: `ok` is asked only where the margin says yes.
            if g.f1 > 0.0 && ok(g.x1) {
                found = Some(g.x1);
                break;
            }
            if g.f2 > 0.0 && ok(g.x2) {
                found = Some(g.x2);
                break;
            }
            if !(g.b - g.a > 1e-15 * (hi - lo).abs()) {
                break;
            }
            g.step(&value);
        }
        let Some(inside) = found else { continue };
        // The stretch's ends, each between a feasible and an infeasible argument.
        let edge = |mut yes: f64, mut no: f64| {
            for _ in 0..200 {
                let mid = 0.5 * (yes + no);
                if mid == yes || mid == no {
                    break;
                }
                if ok(mid) {
                    yes = mid;
                } else {
                    no = mid;
                }
            }
            yes
        };
        out.push((edge(inside, at(k - 1)), edge(inside, at(k + 1))));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::maximise;

    #[test]
    fn finds_a_kink_and_skips_undefined_parts() {
        // max of min(x, 2 − x) on [0, 3], undefined above 2.5: the kink at 1.
        let f = |x: f64| (x <= 2.5).then(|| x.min(2.0 - x));
        let (x, v) = maximise(f, 0.0, 3.0, 50).unwrap();
        assert!(
            (x - 1.0).abs() < 1e-11 && (v - 1.0).abs() < 1e-11,
            "{x} {v}"
        );
        assert!(maximise(|_| None, 0.0, 1.0, 10).is_none());
    }
}
