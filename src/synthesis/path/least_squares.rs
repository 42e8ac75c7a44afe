//! Local least squares on residuals: a central-difference Jacobian, Levenberg–Marquardt and
//! a continuation from a near miss.

use nalgebra::{DMatrix, DVector};

/// The Jacobian of the residuals `r` at `x` by central differences.
///
/// The unknowns from `separable` on are the crank angles of the points, one each: angle k
/// moves only residuals 2(k − separable) and the next, so one pair of evaluations gives all
/// their columns. `None` where a residual cannot be evaluated (the budget is spent, or a
/// neighbour does not assemble).
pub(super) fn jacobian(
    res: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    x: &[f64],
    m: usize,
    separable: usize,
) -> Option<DMatrix<f64>> {
    let n = x.len();
    let mut j = DMatrix::zeros(m, n);
    let step = |k: usize| 1e-7 * x[k].abs().max(1.0);
    for k in 0..separable.min(n) {
        let h = step(k);
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[k] += h;
        xm[k] -= h;
        let (rp, rm) = (res(&xp)?, res(&xm)?);
        for i in 0..m {
            j[(i, k)] = (rp[i] - rm[i]) / (2.0 * h);
        }
    }
    if separable < n {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        for k in separable..n {
            xp[k] += step(k);
            xm[k] -= step(k);
        }
        let (rp, rm) = (res(&xp)?, res(&xm)?);
        for k in separable..n {
            let h = step(k);
            for i in [2 * (k - separable), 2 * (k - separable) + 1] {
                j[(i, k)] = (rp[i] - rm[i]) / (2.0 * h);
            }
        }
    }
    Some(j)
}

/// Levenberg–Marquardt on the residuals, with a central-difference Jacobian ([`jacobian`]);
/// a step is taken only where `accept` agrees (the design stays feasible).
pub(super) fn levenberg_marquardt(
    res: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    accept: &mut dyn FnMut(&[f64]) -> bool,
    x0: Vec<f64>,
    separable: usize,
    iterations: usize,
) -> Vec<f64> {
    let mut x = x0;
    let Some(mut r) = res(&x) else { return x };
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    let mut lambda = 1e-3;
    let n = x.len();
    for _ in 0..iterations {
        if cost < 1e-30 {
            break;
        }
        let Some(j) = jacobian(res, &x, r.len(), separable) else {
            return x;
        };
        let jt = j.transpose();
        let jtj = &jt * &j;
        let g = &jt * DVector::from_vec(r.clone());
        let mut improved = false;
        for _ in 0..12 {
            let mut a = jtj.clone();
            for k in 0..n {
                a[(k, k)] += lambda * (jtj[(k, k)] + 1e-12);
            }
            let Some(step) = a.lu().solve(&(-&g)) else {
                lambda *= 10.0;
                continue;
            };
            let xn: Vec<f64> = x.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            if let Some(rn) = res(&xn) {
                let cn: f64 = rn.iter().map(|v| v * v).sum();
                if cn < cost && accept(&xn) {
                    let small =
                        step.norm() <= 1e-15 * (1.0 + x.iter().map(|v| v * v).sum::<f64>().sqrt());
                    x = xn;
                    r = rn;
                    cost = cn;
                    lambda = (lambda / 10.0).max(1e-15);
                    improved = !small;
                    break;
                }
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    x
}

/// Continuation from a near miss to the points: the misses `r0` at `x0` are shrunk to zero
/// along the way, the targets of step s being the points plus (1 − s)·r0, and the root at
/// each s tracked by a tangent predictor and a chord-Newton corrector (the Jacobian of the
/// predictor's point).
///
/// Why: where the misses are a square system whose Jacobian is ill-conditioned (eight
/// precision points of a six-bar: the smallest singular value 1e-6 of the largest), the
/// root may lie far along a curved valley of the misses, where Levenberg–Marquardt creeps
/// by tiny damped steps and stalls; the continuation follows the valley instead. It stops
/// where a step of 1e-6 in s does not converge (a fold: no root of this branch), when
/// `accept` refuses a point, or after `steps` steps; the last point reached is returned.
pub(super) fn continuation(
    res: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    accept: &mut dyn FnMut(&[f64]) -> bool,
    x0: Vec<f64>,
    separable: usize,
    steps: usize,
) -> Vec<f64> {
    let Some(r0) = res(&x0) else { return x0 };
    let r0 = DVector::from_vec(r0);
    let size = r0.norm();
    if !(size > 0.0 && size.is_finite()) {
        return x0;
    }
    let (mut x, mut s, mut ds) = (DVector::from_vec(x0), 0.0f64, 0.125f64);
    for _ in 0..steps {
        if s >= 1.0 || ds < 1e-6 {
            break;
        }
        let Some(j) = jacobian(res, x.as_slice(), r0.len(), separable) else {
            break;
        };
        let svd = j.clone().svd(true, true);
        let solve = |b: &DVector<f64>| svd.solve(b, 1e-14 * svd.singular_values.max());
        let Ok(tangent) = solve(&(-&r0)) else { break };
        let t = (s + ds).min(1.0);
        // The residuals of step t: Q(x) − T − (1 − t)·r0.
        let f =
            |y: &DVector<f64>| res(y.as_slice()).map(|q| DVector::from_vec(q) - (1.0 - t) * &r0);
        let mut y = &x + (t - s) * &tangent;
        let mut ok = false;
        for _ in 0..6 {
            let Some(fy) = f(&y) else { break };
            if fy.norm() <= 1e-3 * size * (1.0 - t) + 1e-14 * (1.0 + y.norm()) {
                ok = true;
                break;
            }
            let Ok(dy) = solve(&(-fy)) else { break };
            y += dy;
        }
        if ok && accept(y.as_slice()) {
            (x, s) = (y, t);
            ds *= 2.0;
        } else {
            ds /= 4.0;
        }
    }
    x.as_slice().to_vec()
}
