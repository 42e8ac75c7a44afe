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
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (at(k.saturating_sub(1)), at((k + 1).min(n - 1)));
    let (mut x1, mut x2) = (b - r * (b - a), a + r * (b - a));
    let (mut f1, mut f2) = (value(x1), value(x2));
    let tol = 1e-13 * (hi - lo).abs().max(f64::MIN_POSITIVE);
    while (b - a).abs() > tol {
        if f1 >= f2 {
            (b, x2, f2) = (x2, x1, f1);
            x1 = b - r * (b - a);
            f1 = value(x1);
        } else {
            (a, x1, f1) = (x1, x2, f2);
            x2 = a + r * (b - a);
            f2 = value(x2);
        }
    }
    let (x, fx) = if f1 >= f2 { (x1, f1) } else { (x2, f2) };
    Some(if fx > v { (x, fx) } else { (at(k), v) })
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
