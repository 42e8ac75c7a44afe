#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x <= y)` rejects NaN too, on purpose.
//! Whether a description in f64 holds the K and the stroke it was designed for, and what to
//! say when it cannot.
//!
//! The engine reads a description's lengths off its joints' coordinates, each rounded once.
//! Near the bound of K (a crank-rocker whose folded dead centre nears a change point, a
//! slider-crank whose folded dead centre nears the crank's pivot) K moves by far more than
//! 10⁻¹⁰ of itself for one rounding of the lengths, so no description of that design meets the
//! requirement to 10⁻¹⁰ — a design there is refused, naming K and the largest K that is held.
//! Every answer's report is computed from the description's own lengths (as the engine will
//! read them), so it is what the engine measures.

use super::four_bar::FourBar;
use crate::error::{Ends, Error};
use crate::linkage::Linkage;
use nalgebra::Vector2;

/// The relative precision to which a synthesised description must hold K and the stroke.
pub(crate) const HELD: f64 = 1e-10;

/// A joint's coordinates as a vector (the synthesis names them itself).
pub(crate) fn joint(linkage: &Linkage, name: &str) -> Option<Vector2<f64>> {
    linkage
        .joints
        .iter()
        .find(|j| j.name == name)
        .map(|j| Vector2::new(j.at[0], j.at[1]))
}

/// The four-bar a description `O1`, `A`, `B`, `O3` holds, its lengths as the engine reads
/// them.
pub(crate) fn described_four_bar(linkage: &Linkage) -> Option<FourBar> {
    Some(FourBar::from_points(
        joint(linkage, "O1")?,
        joint(linkage, "A")?,
        joint(linkage, "B")?,
        joint(linkage, "O3")?,
    ))
}

/// Whether `got` meets `want` to [`HELD`] of it (`None` never does).
pub(crate) fn held(got: Option<f64>, want: f64) -> bool {
    held_to(got, want, HELD)
}

/// Whether `got` meets `want` to `tol` of it (`None` never does).
pub(crate) fn held_to(got: Option<f64>, want: f64, tol: f64) -> bool {
    got.is_some_and(|g| (g - want).abs() <= tol * want.abs())
}

/// How far K of the crank-rocker `fb` moves when each of its four lengths is off by one
/// rounding (ε of itself), relative to nothing (absolute): Σ |∂K/∂l|·ε·l, with K = (π + θ)/
/// (π − θ), ∂K/∂θ = 2π/(π − θ)², and ∂θ/∂l by central differences of the closed form (steps
/// 10⁻⁸ of each length, and of b − a for the crank and the coupler: next to the bound the
/// folded dead centre b − a is what θ hangs on). Far from the bound this is far below
/// 10⁻¹⁰·K; next to it, above (1.1e-9 of K at ψ = 170°, K a hundredth of (K* − 1) below its
/// bound K*), and there no description in f64 fixes K better.
pub(crate) fn crank_rocker_k_rounding(fb: &FourBar) -> f64 {
    let theta = fb.extremes().theta;
    let gap = fb.b - fb.a;
    let slope = |set: &dyn Fn(&mut FourBar, f64), l: f64, h: f64| {
        let (mut up, mut down) = (*fb, *fb);
        set(&mut up, h);
        set(&mut down, -h);
        (up.extremes().theta - down.extremes().theta).abs() / (2.0 * h) * f64::EPSILON * l
    };
    let d_theta = slope(&|f, h| f.d += h, fb.d, 1e-8 * fb.d)
        + slope(&|f, h| f.a += h, fb.a, 1e-8 * fb.a.min(gap))
        + slope(&|f, h| f.b += h, fb.b, 1e-8 * gap)
        + slope(&|f, h| f.c += h, fb.c, 1e-8 * fb.c);
    let pi = std::f64::consts::PI;
    2.0 * pi / ((pi - theta) * (pi - theta)) * d_theta
}

/// Whether the engine, analysing `linkage` (its output's extreme positions over a turn of
/// the crank), measures the time ratio `k.0` to `k.1` of it and the stroke or swing `stroke`
/// to [`HELD`]: the round trip itself. Next to the bound of K the closed form of the description's lengths
/// can hold K while the engine, which locates each extreme where the output's velocity
/// vanishes, cannot (a rocker's extreme next to a change point is flat to high order: the
/// engine's K was 1.9e-9 of itself off at ψ = 0.3 rad, K 0.1 % of (K* − 1) below its bound).
pub(crate) fn engine_holds(linkage: &Linkage, k: (f64, f64), stroke: f64) -> bool {
    let Ok(plan) = crate::linkage::Plan::new(linkage) else {
        return false;
    };
    let Some(output) = linkage.output.as_ref() else {
        return false;
    };
    plan.strokes(output, crate::kinematics::Rotation::Ccw)
        .is_ok_and(|s| held_to(Some(s.time_ratio), k.0, k.1) && held(Some(s.stroke), stroke))
}

/// The error for a K that a description cannot hold: `held_at(k)` says whether the design
/// at K = k is made and holds its requirement. The largest held K below `k` is found by a
/// bisection from a held one (tried at (k − 1)·s above 1 for s = 0.99, 0.9, 0.5, 0.1, 0.01),
/// and named as the interval's upper end; `None` when none of those holds (the caller then
/// says what else is wrong).
pub(crate) fn k_not_held(k: f64, held_at: impl Fn(f64) -> bool) -> Option<Error> {
    let mut lo = [0.99, 0.9, 0.5, 0.1, 0.01]
        .into_iter()
        .map(|s| 1.0 + (k - 1.0) * s)
        .find(|&t| held_at(t))?;
    let mut hi = k;
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if held_at(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(Error::OutOfRange {
        name: "K (held to 1e-10 by a description in f64 only up to the interval's top)",
        value: k,
        min: 1.0,
        max: lo,
        ends: Ends::OpenBelow,
    })
}

/// Newton's method on the crank `a` and the coupler `b` of a crank-rocker (frame and rocker
/// fixed) so that its crank excess θ and swing, in closed form, are `theta` and `swing` to
/// the rounding of the lengths: the locus construction leaves them a few roundings of the
/// pivot's coordinates off, which near the bound of K is many times 10⁻¹⁰ of K. The
/// Jacobian by central differences (steps 10⁻⁶ of the smaller of a and b − a, the folded
/// dead centre's distance from O1); a step is taken only if it keeps a crank-rocker and
/// lowers the residual.
pub(crate) fn polish_crank_rocker(fb: FourBar, theta: f64, swing: f64) -> FourBar {
    let residual = |f: &FourBar| {
        let e = f.extremes();
        [e.theta - theta, e.swing - swing]
    };
    let size = |r: [f64; 2]| r[0].abs().max(r[1].abs());
    let mut best = fb;
    let mut r = residual(&best);
    for _ in 0..8 {
        if size(r) == 0.0 {
            break;
        }
        let h = 1e-6 * best.a.min(best.b - best.a);
        if !(h > 0.0) {
            break;
        }
        let at = |da: f64, db: f64| {
            residual(&FourBar {
                a: best.a + da,
                b: best.b + db,
                ..best
            })
        };
        let (pa, ma, pb, mb) = (at(h, 0.0), at(-h, 0.0), at(0.0, h), at(0.0, -h));
        let j = [
            [(pa[0] - ma[0]) / (2.0 * h), (pb[0] - mb[0]) / (2.0 * h)],
            [(pa[1] - ma[1]) / (2.0 * h), (pb[1] - mb[1]) / (2.0 * h)],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if !(det.abs() > 0.0) || !det.is_finite() {
            break;
        }
        let da = (j[1][1] * r[0] - j[0][1] * r[1]) / det;
        let db = (j[0][0] * r[1] - j[1][0] * r[0]) / det;
        let next = FourBar {
            a: best.a - da,
            b: best.b - db,
            ..best
        };
        let ok = next.a > 0.0
            && next.b > next.a
            && next.grashof().ok() == Some(crate::kinematics::Grashof::CrankRocker);
        let rn = residual(&next);
        if !(ok && size(rn) < size(r)) {
            break;
        }
        (best, r) = (next, rn);
    }
    best
}
