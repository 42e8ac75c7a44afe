#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Burmester's points of five poses by a root scan along the centre-point curve: the method
//! before the algebraic count of [`burmester_points`](super::burmester_points), kept as an
//! independent cross-check (it reaches the points along a different road: the standard
//! form's compatibility triangle, not the bisectors' pencil). A scan is not a count: two roots
//! closer than its step, or a root in a sliver of the parameter, can be stepped over.

use super::burmester::{check_poses, Dyad, Pose};
use super::burmester_five::kept;
use super::centre_curve::{rotation_minus_one, Compatibility, C};
use super::pose_newton::PoseEquations;
use super::pose_order;
use crate::error::{Error, Result};
use std::f64::consts::TAU;

/// A closed loop of the centre-point curve in the parameter u (see [`burmester_points_by_scan`]).
#[derive(Debug, Clone, Copy)]
enum Loop {
    /// One branch over the whole turn of β2, u = β2 in [0, 2π].
    Whole(f64),
    /// Both branches over the interval [l, r] of β2 between two folds (u in [0, 2]), and the
    /// number of grid samples in it.
    Interval(f64, f64, usize),
}

impl Loop {
    fn span(&self) -> f64 {
        match self {
            Self::Whole(_) => TAU,
            Self::Interval(..) => 2.0,
        }
    }

    /// The number of samples over the loop for a grid of `n` over the turn.
    fn samples(&self, n: usize) -> usize {
        match self {
            Self::Whole(_) => n,
            Self::Interval(_, _, len) => (4 * len).max(64),
        }
    }

    /// (β2, branch, at a fold) at u.
    fn point(&self, u: f64) -> (f64, f64, bool) {
        match *self {
            Self::Whole(sign) => (u, sign, false),
            Self::Interval(l, r, _) => {
                let (v, sign) = if u <= 1.0 { (u, 1.0) } else { (2.0 - u, -1.0) };
                let beta2 = l + 0.5 * (r - l) * (1.0 - (std::f64::consts::PI * v).cos());
                (beta2, sign, v == 0.0 || v == 1.0)
            }
        }
    }
}

/// Burmester's points of five poses by a scan (the cross-check of
/// [`burmester_points`](super::burmester_points), which should be used instead: this scan can
/// miss a point that the count cannot).
///
/// Derivation: along the centre-point curve of poses 1–4 (parameter β2, two branches; see
/// [`centre_point_curve`](super::centre_point_curve)) the dyad (W, Z) reaches pose 5 when some
/// crank turn β5 solves W(e^{iβ5} − 1) + Z(e^{iα5} − 1) = δ5, that is when
/// |δ5 − Z(e^{iα5} − 1) + W| = |W|. The difference of the two sides is scanned along the
/// curve's loops (`n` samples of β2 over a turn; near a fold, where the two branches meet and
/// β2 turns back, in a parameter in which the branches join smoothly) and every sign change is
/// refined by bisection; each root is polished and kept as by
/// [`burmester_points`](super::burmester_points).
///
/// # Examples
/// ```
/// use tmm::synthesis::{burmester_points, burmester_points_by_scan, Pose};
/// let poses = [
///     Pose::new([0.0, 0.0], 0.0),
///     Pose::new([0.1, 0.05], 0.3),
///     Pose::new([0.2, 0.05], 0.7),
///     Pose::new([0.28, 0.0], 1.0),
///     Pose::new([0.33, -0.08], 1.4),
/// ];
/// let scanned = burmester_points_by_scan(&poses, 4000)?;
/// let counted = burmester_points(&poses)?;
/// assert!(scanned.len() <= counted.len());
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`burmester_points`](super::burmester_points);
/// [`Error::OutOfRange`] (`"n"`) for n below 8 or above [`MAX_POINTS`](super::MAX_POINTS).
pub fn burmester_points_by_scan(poses: &[Pose; 5], n: usize) -> Result<Vec<Dyad>> {
    check_poses(poses)?;
    pose_order::not_about_one_point(poses)?;
    if !(8..=super::MAX_POINTS).contains(&n) {
        return Err(Error::OutOfRange {
            name: "n",
            value: n as f64,
            min: 8.0,
            max: super::MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    // Searched in the order that spreads the poses best (see `pose_order`), each point
    // named and checked in the given order.
    let order = pose_order::spread_order(poses);
    let given = poses;
    let poses = &order.map(|i| given[i]);
    let compat = Compatibility::new(&poses[..4]);
    let a5 = rotation_minus_one(poses[4].angle - poses[0].angle);
    let d5 = C::new(poses[4].at[0], poses[4].at[1]) - compat.p1;
    // The signed miss of pose 5, scaled to the dyad's size.
    let miss_with = |beta2: f64, sign: f64, fold: bool| -> Option<f64> {
        let (w, z) = compat.standard_form_with(beta2, sign, fold)?;
        let m = (d5 - z * a5 + w).norm() - w.norm();
        let f = m / (w.norm() + z.norm() + compat.size);
        f.is_finite().then_some(f)
    };
    // The branches as closed loops in a parameter u: where the triangle closes over the
    // whole turn, each branch is a loop over β2; otherwise each interval [l, r] of closing
    // (its ends, the folds where the branches meet, found by bisection) is one loop, the
    // branch + for u in [0, 1] and − back for u in [1, 2], with β2 = l + (r − l)(1 − cos πu)/2
    // so that the square root at the folds becomes smooth in u (a root next to a fold is
    // then not lost between samples).
    let h = TAU / n as f64;
    let closes: Vec<bool> = (0..n).map(|k| compat.closes(h * k as f64)).collect();
    let mut loops: Vec<Loop> = Vec::new();
    if closes.iter().all(|&c| c) {
        loops.push(Loop::Whole(1.0));
        loops.push(Loop::Whole(-1.0));
    } else if closes.iter().any(|&c| c) {
        let fold = |inside: f64, outside: f64| {
            let (mut a, mut b) = (inside, outside);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if mid == a || mid == b {
                    break;
                }
                if compat.closes(mid) {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            a
        };
        // Runs of closing samples, cyclically, starting after a sample that does not close.
        let first_out = closes.iter().position(|&c| !c).unwrap_or(0);
        let mut k = 0;
        while k < n {
            let i = (first_out + k) % n;
            if closes[i] && !closes[(i + n - 1) % n] {
                let mut len = 0;
                while closes[(i + len) % n] {
                    len += 1;
                }
                let start = h * i as f64;
                let end = start + h * (len - 1) as f64;
                loops.push(Loop::Interval(
                    fold(start, start - h),
                    fold(end, end + h),
                    len,
                ));
                k += len;
            } else {
                k += 1;
            }
        }
    }
    let mut candidates: Vec<(f64, f64, bool)> = Vec::new();
    for lp in &loops {
        let m = lp.samples(n);
        let at = |u: f64| lp.point(u);
        let value = |u: f64| {
            let (beta2, sign, fold) = at(u);
            miss_with(beta2, sign, fold)
        };
        let us: Vec<f64> = (0..=m).map(|i| lp.span() * i as f64 / m as f64).collect();
        let vals: Vec<Option<f64>> = us.iter().map(|&u| value(u)).collect();
        if let Loop::Interval(..) = lp {
            candidates.push(at(0.0));
            candidates.push(at(1.0));
        }
        for i in 0..m {
            let (Some(flo), Some(fhi)) = (vals[i], vals[i + 1]) else {
                continue;
            };
            if flo == 0.0 {
                candidates.push(at(us[i]));
            }
            if flo * fhi < 0.0 {
                candidates.push(at(bisect(&value, us[i], us[i + 1], flo)));
            }
        }
        // Two roots closer than a sample step change no sign between samples: a local
        // minimum of |f| between neighbours of its sign is searched for a dip across zero,
        // and each side of the dip bisected.
        for i in 1..m {
            let (Some(f0), Some(f1), Some(f2)) = (vals[i - 1], vals[i], vals[i + 1]) else {
                continue;
            };
            if f0 * f1 <= 0.0 || f1 * f2 <= 0.0 || f1.abs() > f0.abs() || f1.abs() > f2.abs() {
                continue;
            }
            let s = f1.signum();
            let (lo, hi) = (us[i - 1], us[i + 1]);
            if let Some((u, fu)) = dip(&|u| value(u).map(|f| s * f), lo, hi) {
                candidates.push(at(bisect(&value, lo, u, f0)));
                candidates.push(at(bisect(&value, u, hi, s * fu)));
            }
        }
    }
    let starts = candidates.into_iter().filter_map(|(beta2, sign, fold)| {
        let dyad = compat.dyad_with(beta2, sign, fold)?;
        Some(pose_order::renamed(dyad, &poses[0], given))
    });
    kept(&PoseEquations::new(given), given, starts)
}

/// A root of `value` in [a, b] by bisection, `fa` the value at `a` (of the sign opposite to
/// the value at `b`).
fn bisect(value: &dyn Fn(f64) -> Option<f64>, a: f64, b: f64, fa: f64) -> f64 {
    let (mut a, mut b, mut fa) = (a, b, fa);
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if mid == a || mid == b {
            break;
        }
        let Some(fm) = value(mid) else { break };
        if (fm < 0.0) == (fa < 0.0) && fm != 0.0 {
            (a, fa) = (mid, fm);
        } else {
            b = mid;
        }
    }
    0.5 * (a + b)
}

/// The minimum of `f` on [a, b] by golden-section search, if it is below zero: `(u, f(u))`.
fn dip(f: &dyn Fn(f64) -> Option<f64>, a: f64, b: f64) -> Option<(f64, f64)> {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c)?, f(d)?);
    for _ in 0..120 {
        if fc <= 0.0 || fd <= 0.0 {
            break;
        }
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = f(c)?;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = f(d)?;
        }
    }
    let (u, fu) = if fc < fd { (c, fc) } else { (d, fd) };
    (fu <= 0.0).then_some((u, fu))
}
