#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Burmester's curves: the centre-point curve of four finitely separated poses, sampled, and
//! Burmester's points of five (where two such curves meet). See [`centre_point_curve`] for the
//! dyad's standard form and the compatibility condition.

use super::burmester::{check_poses, v, Dyad, Pose};
use super::pose_newton::PoseEquations;
use super::pose_order;
use crate::error::{Error, Result};
use std::f64::consts::TAU;

type C = nalgebra::Complex<f64>;

/// The centre-point curve of four poses, sampled: the dyads (centre point, circle point in
/// the first pose) that carry the coupler through all four, for `n` crank rotations β2
/// between the first two poses, evenly spaced over a turn (up to two dyads each).
///
/// Derivation (the dyad's standard form): with W = A − O (the crank, from the centre point O
/// to the circle point A in pose 1), Z = P1 − A and the coupler's rotations α_j = θ_j − θ1,
/// pose j is reached when the crank has turned β_j:
/// W(e^{iβ_j} − 1) + Z(e^{iα_j} − 1) = δ_j = P_j − P1, j = 2, 3, 4.
/// Three complex equations in two complex unknowns are compatible only where the 3×3
/// determinant of [e^{iβ_j} − 1, e^{iα_j} − 1, δ_j] vanishes; expanded along its first column,
/// Δ1 + Δ2·e^{iβ2} + Δ3·e^{iβ3} + Δ4·e^{iβ4} = 0 (Δ2..Δ4 the cofactors, Δ1 = −ΣΔj). For a
/// chosen β2 the vectors Δ3·e^{iβ3} and Δ4·e^{iβ4} close a triangle with −(Δ1 + Δ2·e^{iβ2}):
/// two solutions, or none. Then W and Z solve equations 2 and 3 (Cramer), O = P1 − Z − W and
/// A = P1 − Z. The trivial solution β_j = α_j (the crank turning with the coupler) is left out.
///
/// # Examples
/// ```
/// use tmm::synthesis::{centre_point_curve, Pose};
/// let poses = [
///     Pose::new([0.0, 0.0], 0.0),
///     Pose::new([0.1, 0.05], 0.3),
///     Pose::new([0.2, 0.05], 0.7),
///     Pose::new([0.28, 0.0], 1.0),
/// ];
/// let dyads = centre_point_curve(&poses, 90)?;
/// assert!(!dyads.is_empty());
/// // Every dyad keeps its length through the four poses.
/// for d in &dyads {
///     assert!(d.misfit(&poses) < 1e-9 * (1.0 + d.length()));
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses;
/// [`Error::OutOfRange`] (`"n"`) for n = 0 or n above [`MAX_POINTS`](super::MAX_POINTS).
pub fn centre_point_curve(poses: &[Pose; 4], n: usize) -> Result<Vec<Dyad>> {
    // The runs check the poses and n.
    Ok(burmester_curves(poses, n)?.concat())
}

/// Burmester's curves of four poses as lines to draw: the dyads of [`centre_point_curve`]
/// in runs along one branch of the compatibility triangle, each run without a gap (a run
/// ends where the triangle stops closing, at a fold where the two branches meet, or at a
/// dyad that does not fit). The centre points of a run trace the centre-point curve, their
/// circle points (in the first pose) the circle-point curve.
///
/// # Examples
/// ```
/// use tmm::synthesis::{burmester_curves, centre_point_curve, Pose};
/// let poses = [
///     Pose::new([0.0, 0.0], 0.0),
///     Pose::new([0.1, 0.05], 0.3),
///     Pose::new([0.2, 0.05], 0.7),
///     Pose::new([0.28, 0.0], 1.0),
/// ];
/// let runs = burmester_curves(&poses, 360)?;
/// let all: usize = runs.iter().map(Vec::len).sum();
/// assert_eq!(all, centre_point_curve(&poses, 360)?.len());
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`centre_point_curve`].
pub fn burmester_curves(poses: &[Pose; 4], n: usize) -> Result<Vec<Vec<Dyad>>> {
    check_poses(poses)?;
    if !(1..=super::MAX_POINTS).contains(&n) {
        return Err(Error::OutOfRange {
            name: "n",
            value: n as f64,
            min: 1.0,
            max: super::MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    let compat = Compatibility::new(poses);
    let mut runs: Vec<Vec<Dyad>> = Vec::new();
    for sign in [1.0, -1.0] {
        let first = runs.len();
        let mut run: Vec<Dyad> = Vec::new();
        let (mut at_start, mut at_end) = (false, false);
        for k in 0..n {
            let beta2 = TAU * (k as f64 + 0.5) / n as f64;
            match compat
                .dyad(beta2, sign)
                .filter(|d| d.misfit(poses) <= 1e-9 * (compat.size + d.length()))
            {
                Some(d) => {
                    at_start |= k == 0;
                    at_end = k == n - 1;
                    run.push(d);
                }
                None if !run.is_empty() => runs.push(std::mem::take(&mut run)),
                None => {}
            }
        }
        if !run.is_empty() {
            runs.push(run);
        }
        // A run through β2 = 0 is one line: its end joins its beginning.
        if at_start && at_end && runs.len() > first + 1 {
            let last = runs.pop().unwrap_or_default();
            runs[first].splice(0..0, last);
        }
    }
    Ok(runs)
}

/// Burmester's compatibility of four poses (see [`centre_point_curve`]): the coefficients
/// of the standard form and the determinant's cofactors.
struct Compatibility {
    p1: C,
    /// The coupler's rotations from pose 1 as e^{iα_j} − 1, j = 2, 3, 4.
    alpha: [C; 3],
    /// The first pose's turns α_j, rad.
    turns: [f64; 3],
    /// δ_j = P_j − P1.
    delta: [C; 3],
    /// Δ1..Δ4.
    d: [C; 4],
    /// The largest |δ_j|, m.
    size: f64,
}

fn rotation_minus_one(angle: f64) -> C {
    C::from_polar(1.0, angle) - 1.0
}

impl Compatibility {
    fn new(poses: &[Pose]) -> Self {
        let p1 = C::new(poses[0].at[0], poses[0].at[1]);
        let turns = [1, 2, 3].map(|j| poses[j].angle - poses[0].angle);
        let alpha = turns.map(rotation_minus_one);
        let delta = [1, 2, 3].map(|j| C::new(poses[j].at[0], poses[j].at[1]) - p1);
        // Cofactors of the first column of [e^{iβ} − 1, e^{iα} − 1, δ] (rows j = 2, 3, 4).
        let minor = |r: usize, s: usize| alpha[r] * delta[s] - alpha[s] * delta[r];
        let (d2, d3, d4) = (minor(1, 2), -minor(0, 2), minor(0, 1));
        Self {
            p1,
            alpha,
            turns,
            delta,
            d: [-(d2 + d3 + d4), d2, d3, d4],
            size: delta.iter().map(|d| d.norm()).fold(0.0, f64::max),
        }
    }

    /// Whether the compatibility triangle closes for the turn β2 (two real branches).
    fn closes(&self, beta2: f64) -> bool {
        let [d1, d2, d3, d4] = self.d;
        let l = (d1 + d2 * C::from_polar(1.0, beta2)).norm();
        let (r3, r4) = (d3.norm(), d4.norm());
        l > 0.0 && l <= r3 + r4 && l >= (r3 - r4).abs()
    }

    /// (W, Z) for the crank's turn β2 to pose 2 on the branch `sign` of the compatibility
    /// triangle; `None` where the triangle does not close, on the trivial solution, or where
    /// equations 2 and 3 do not fix W and Z. `fold` puts the triangle's apex on its base (the
    /// two branches' meeting point, where the apex's height is zero to rounding).
    fn standard_form_with(&self, beta2: f64, sign: f64, fold: bool) -> Option<(C, C)> {
        let [d1, d2, d3, d4] = self.d;
        let s = -(d1 + d2 * C::from_polar(1.0, beta2));
        let (r3, r4, l) = (d3.norm(), d4.norm(), s.norm());
        if !(r3 > 0.0 && r4 > 0.0 && l > 0.0) {
            return None;
        }
        // a = Δ3·e^{iβ3}: |a| = r3, |s − a| = r4.
        if !self.closes(beta2) {
            return None;
        }
        let along = (r3 * r3 - r4 * r4 + l * l) / (2.0 * l);
        let h2 = if fold {
            0.0
        } else {
            (r3 * r3 - along * along).max(0.0)
        };
        let a = s / l * C::new(along, sign * h2.sqrt());
        let betas = [beta2, (a / d3).arg(), ((s - a) / d4).arg()];
        let trivial = betas
            .iter()
            .zip(self.turns)
            .all(|(&b, t)| (0.5 * (b - t)).sin().abs() < 1e-9);
        if trivial {
            return None;
        }
        let (b2, b3) = (rotation_minus_one(betas[0]), rotation_minus_one(betas[1]));
        let [a2, a3, _] = self.alpha;
        let det = b2 * a3 - b3 * a2;
        if !(det.norm() > 1e-12) {
            return None;
        }
        let w = (self.delta[0] * a3 - self.delta[1] * a2) / det;
        let z = (b2 * self.delta[1] - b3 * self.delta[0]) / det;
        Some((w, z))
    }

    /// The dyad for β2 on the branch `sign`: O = P1 − Z − W, A = P1 − Z.
    fn dyad(&self, beta2: f64, sign: f64) -> Option<Dyad> {
        self.dyad_with(beta2, sign, false)
    }

    fn dyad_with(&self, beta2: f64, sign: f64, fold: bool) -> Option<Dyad> {
        let (w, z) = self.standard_form_with(beta2, sign, fold)?;
        let (circle, centre) = (self.p1 - z, self.p1 - z - w);
        let dyad = Dyad {
            centre: [centre.re, centre.im],
            circle: [circle.re, circle.im],
        };
        dyad.centre
            .iter()
            .chain(&dyad.circle)
            .all(|x| x.is_finite())
            .then_some(dyad)
    }
}

/// A closed loop of the centre-point curve in the parameter u (see [`burmester_points`]).
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

/// Burmester's points of five poses: the dyads that carry the coupler through all five (at
/// most four; none for some poses), where the centre-point curves of poses 1–4 and 1, 2, 3, 5
/// meet.
///
/// Derivation: along the centre-point curve of poses 1–4 (parameter β2, two branches; see
/// [`centre_point_curve`]) the dyad (W, Z) reaches pose 5 when some crank turn β5 solves
/// W(e^{iβ5} − 1) + Z(e^{iα5} − 1) = δ5, that is when |δ5 − Z(e^{iα5} − 1) + W| = |W|. The
/// difference of the two sides is scanned along the curve's loops (`n` samples of β2 over a
/// turn; near a fold, where the two branches meet and β2 turns back, in a parameter in which
/// the branches join smoothly) and every sign change is refined by bisection to machine
/// precision; a root is kept if the dyad fits all five poses to 1e-9 of its size.
///
/// # Examples
/// Five poses of the coupler of a four-bar: its two dyads are among Burmester's points.
/// ```
/// use tmm::synthesis::{burmester_points, Pose};
/// // The coupler of the crank-rocker O1 = (0, 0), A, B, O3 = (0.4, 0): five poses read off
/// // its motion (A on the crank of 0.1 m; B on the rocker of 0.3 m; coupler 0.35 m).
/// let (a, b, c, d) = (0.1, 0.35, 0.3, 0.4);
/// // The pose: the coupler point P, 0.1 m left of the middle of AB, and the angle of AB.
/// let pose = |phi: f64| {
///     let (ax, ay) = (a * phi.cos(), a * phi.sin());
///     let (vx, vy) = (d - ax, -ay);
///     let e = vx.hypot(vy);
///     let along = (b * b - c * c + e * e) / (2.0 * e);
///     let h = (b * b - along * along).sqrt();
///     let (bx, by) = (ax + along * vx / e - h * vy / e, ay + along * vy / e + h * vx / e);
///     let (ux, uy) = ((bx - ax) / b, (by - ay) / b);
///     Pose::new([ax + 0.5 * b * ux - 0.1 * uy, ay + 0.5 * b * uy + 0.1 * ux], uy.atan2(ux))
/// };
/// let poses = [0.3, 0.9, 1.6, 2.4, 3.0].map(pose);
/// let points = burmester_points(&poses, 2000)?;
/// // The crank O1A (centre (0, 0)) and the rocker O3B (centre (0.4, 0)) are among them.
/// let near = |x: f64, y: f64| points.iter().any(|p| (p.centre[0] - x).hypot(p.centre[1] - y) < 1e-8);
/// assert!(near(0.0, 0.0) && near(0.4, 0.0));
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses,
/// for poses that all turn about one point (every coupler point then keeps its distance
/// from it: a continuum of dyads) and for other degenerate poses that more than four dyads
/// fit. A dyad more than 10⁶ times longer than the poses' extent (from the first pose) is
/// not returned: the curves approach their points at infinity (a slider's) and meet there
/// only to rounding.
/// [`Error::OutOfRange`] (`"n"`) for n below 8 or above [`MAX_POINTS`](super::MAX_POINTS).
pub fn burmester_points(poses: &[Pose; 5], n: usize) -> Result<Vec<Dyad>> {
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
    // The poses' extent from the first given one (the scale of the fit and of duplicates).
    let extent = given
        .iter()
        .map(|p| (v(p.at) - v(given[0].at)).norm())
        .fold(0.0, f64::max);
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
    // Each root polished on the five poses' difference-quotient equations (well conditioned
    // with poses close together, see `pose_newton`); a start that does not converge to
    // rounding was not near a Burmester point.
    let equations = PoseEquations::new(given);
    let mut out: Vec<(Dyad, f64)> = Vec::new();
    for (beta2, sign, fold) in candidates {
        let Some(dyad) = compat.dyad_with(beta2, sign, fold) else {
            continue;
        };
        let Some((dyad, tol)) = equations.polish(pose_order::renamed(dyad, &poses[0], given))
        else {
            continue;
        };
        let scale = extent + dyad.length();
        // The same point reached from two roots of the scan: each is fixed to its
        // tolerance (εL over the smallest singular value of the equations), and two
        // polishes of one root have one Jacobian, so one tolerance: two points within twice
        // the smaller of theirs are one. (The larger would merge a nearly double root, whose
        // tolerance is wide, with a distinct point far off.)
        let duplicate = out.iter().any(|(o, t)| {
            let within = 2.0 * tol.min(*t);
            (v(o.centre) - v(dyad.centre)).norm() <= within
                && (v(o.circle) - v(dyad.circle)).norm() <= within
        });
        // A dyad a million times longer than the poses' extent is the curve running out to
        // its points at infinity (a slider's), found there only to rounding: not kept.
        let finite_dyad = dyad.length() <= 1e6 * extent;
        if dyad.misfit(given) <= 1e-9 * scale && !duplicate && finite_dyad {
            out.push((dyad, tol));
        }
    }
    let out: Vec<Dyad> = out.into_iter().map(|(d, _)| d).collect();
    // Two centre-point curves in general position meet in at most four real Burmester
    // points; more means they share a piece (for example poses that all turn about one
    // point): a continuum of dyads, not a finite answer.
    if out.len() > 4 {
        return Err(Error::NoMechanism {
            method: "Burmester's points",
            problem: format!(
                "the five poses are degenerate: {} distinct dyads fit them (at most four in \
                 general position), so the centre-point curves share a piece",
                out.len()
            ),
        });
    }
    Ok(out)
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
