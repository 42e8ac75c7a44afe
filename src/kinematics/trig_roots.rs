//! Every root of a real trigonometric polynomial on the circle, bracketed with a certificate:
//! the scan shared by the groups of the 3rd class, whose positions reduce to one such
//! equation F(θ) = 0 in the ternary link's angle (see [`triad`](mod@super::triad) for the rule of
//! the cells: excluded, monotone, halved, or a near-tangency below a width of 2⁻²⁴ rad).
//!
//! Inside a cell the angle is parametrised by the half-angle tangent t about the cell's
//! centre, z = z_c·(1 + i·t)²/(1 + t²), so that no trigonometric function is evaluated in the
//! scan or in Brent's iterations.

use crate::error::{Error, Result};
use nalgebra::Complex;

type C = Complex<f64>;

/// Every mode of a group of the 3rd class closes its three legs to this fraction of the
/// group's size. A root of F whose pose, polished by damped Newton steps on the closures,
/// does not close this well is not a mode and is dropped: F vanishes there only within its
/// rounding (a near-tangency of F whose closures have no common real point) or the pose's
/// linear equations are degenerate there and the other candidate of the root is the mode.
pub(super) const CLOSES: f64 = 1e-12;
/// Two polished poses of one group closer than this fraction of its size (by D, the distance
/// of the ternary link's joints) are one mode reached from two brackets. Each is known to
/// ≈ ε/σ of the size (σ the velocity system's least singular value), so below this only the
/// two modes of a fold within ≈ 1e-18 of the size of their branch point are merged — a double
/// root to rounding, which the scan of F cannot split either.
pub(super) const SAME_MODE: f64 = 1e-9;
/// Cells of the first scan of the circle.
const CELLS: usize = 32;
/// The width (rad) below which a cell that is neither excluded nor monotone is taken to hold a
/// near-tangency of F with zero.
const TANGENT_WIDTH: f64 = 1.0 / (1u64 << 24) as f64;

/// A smooth periodic function F(θ) at z = e^{iθ}, with the bound its scan needs.
pub(super) trait Periodic {
    /// F and F′ = dF/dθ at z.
    fn eval(&self, z: C) -> (f64, f64);
    /// F″ at z.
    fn second(&self, z: C) -> f64;
    /// M₂ ≥ |F″| everywhere.
    fn m2(&self) -> f64;
    /// The rounding level of an evaluation of F.
    fn tol(&self) -> f64;
}

/// Every root of a group's eliminated equation F, bracketed ([`bracket_all`]), once F is
/// known to be usable: its Fourier coefficients `f` and the size `scale` of the terms that
/// make it finite ([`Error::Overflow`] naming `overflow` otherwise), and its bound
/// `bound` = Σ|F_k| above the rounding of those terms ([`Error::Singular`] for `group` with
/// the measure `eliminated equation F(theta)` otherwise: F vanishes identically, the group
/// moves and its modes form a continuum).
pub(super) fn checked_roots(
    e: &impl Periodic,
    f: &[C],
    bound: f64,
    scale: f64,
    group: &'static str,
    overflow: &'static str,
) -> Result<Roots> {
    if !scale.is_finite() || !f.iter().all(|c| c.re.is_finite() && c.im.is_finite()) {
        return Err(Error::Overflow { what: overflow });
    }
    if bound <= 1024.0 * f64::EPSILON * scale {
        return Err(Error::Singular {
            what: group,
            measure: "eliminated equation F(theta)",
            value: bound / scale,
        });
    }
    let mut roots = Roots::default();
    bracket_all(e, &mut roots);
    merge_double(e, &mut roots);
    Ok(roots)
}

/// Roots that rounding alone set apart, merged into the double root they are. A group built
/// at a branch point (two modes merged: a double root of F, where the group's velocity
/// system is singular) has its data rounded, which shifts F by about its rounding level and
/// splits the double root into two roots about √(tol/|F″|) apart (or leaves none): as two
/// modes they would be regular, with rates of the order of 1/√ε and meaningless. So two
/// neighbouring roots between which F dips by no more than its rounding (|F″|·Δ²/8 ≤ tol,
/// Δ their distance), and a cluster (`multiple`) whose extremum of F is within the rounding
/// of zero, become one root at that extremum of F, where the group's determinant vanishes.
fn merge_double(f: &impl Periodic, roots: &mut Roots) {
    let n = roots.n;
    let mut gone = [false; 12];
    for j in 0..n {
        if roots.multiple[j] {
            let (ze, fe) = extremum(f, roots.z[j], 1e-3);
            if fe.abs() <= f.tol() {
                roots.z[j] = ze;
                roots.multiple[j] = false;
                roots.double[j] = true;
            }
        }
    }
    for j in 0..n {
        let k = (j + 1) % n;
        if n < 2 || (n == 2 && j == 1) || gone[j] || gone[k] {
            continue;
        }
        let r = roots.z[j].conj() * roots.z[k];
        let delta = r.im.atan2(r.re).abs();
        let zm = unit(roots.z[j] + roots.z[k]);
        if f.second(zm).abs() * delta * delta / 8.0 > f.tol() {
            continue;
        }
        // The estimate by F″ at the midpoint alone would also merge two genuine roots around
        // an inflection of F (F″ ≈ 0 there, at any distance): F itself at the extremum
        // between them must be within its rounding of zero, as for a cluster.
        let (ze, fe) = extremum(f, zm, 0.5 * delta);
        if fe.abs() <= f.tol() {
            // The double root keeps the stretch its two roots spanned (from the first root
            // of j to the last of k): where F stays within its rounding of zero across a
            // stretch (its terms cancelling, the circles nearly coaxal) it may hide more
            // modes there than the two it shows, which the closures tell apart
            // ([`Roots::plateau`]).
            roots.z[j] = ze;
            roots.stretch_end[j] = roots.end[k];
            roots.multiple[j] = false;
            roots.double[j] = true;
            gone[k] = true;
        }
    }
    let mut kept = 0;
    for (j, &gone) in gone.iter().enumerate().take(n) {
        if !gone {
            roots.z[kept] = roots.z[j];
            roots.start[kept] = roots.start[j];
            roots.stretch_end[kept] = roots.stretch_end[j];
            roots.end[kept] = roots.end[j];
            roots.multiple[kept] = roots.multiple[j];
            roots.double[kept] = roots.double[j];
            kept += 1;
        }
    }
    roots.n = kept;
}

/// The extremum of F near `zm` (one Newton step on F′, at most `reach` rad) and F there.
fn extremum(f: &impl Periodic, zm: C, reach: f64) -> (C, f64) {
    let (_, g) = f.eval(zm);
    let h = f.second(zm);
    let u = if h != 0.0 {
        (-g / h).clamp(-reach, reach)
    } else {
        0.0
    };
    let ze = along(zm, (0.5 * u).tan());
    (ze, f.eval(ze).0)
}

/// Brackets every root of F on the circle (module docs) into `roots`.
pub(super) fn bracket_all(f: &impl Periodic, roots: &mut Roots) {
    let h0 = std::f64::consts::TAU / CELLS as f64;
    let step = C::new(h0.cos(), h0.sin());
    let mut grid = [C::new(1.0, 0.0); CELLS + 1];
    for j in 1..CELLS {
        grid[j] = grid[j - 1] * step;
    }
    let mut values = [0.0; CELLS + 1];
    for j in 0..CELLS {
        values[j] = f.eval(grid[j]).0;
    }
    values[CELLS] = values[0];
    // Cells to examine: (z_a, F_a, z_b, F_b, width).
    // Depth-first: at most CELLS + 24 cells wait (each halving adds one).
    let mut stack = [(C::new(0.0, 0.0), 0.0, C::new(0.0, 0.0), 0.0, 0.0); CELLS + 32];
    let mut top = 0;
    for j in (0..CELLS).rev() {
        stack[top] = (grid[j], values[j], grid[j + 1], values[j + 1], h0);
        top += 1;
    }
    while top > 0 {
        top -= 1;
        let (za, fa, zb, fb, h) = stack[top];
        let same = (fa < 0.0) == (fb < 0.0);
        if same && fa.abs().min(fb.abs()) > f.m2() * h * h / 8.0 + f.tol() {
            continue;
        }
        let zm = unit(za + zb);
        let (fm, gm) = f.eval(zm);
        if gm.abs() > f.m2() * h / 2.0 + f.tol() {
            if !same {
                roots.push(brent_cell(f, za, fa, zb, fb));
            }
            continue;
        }
        if h <= TANGENT_WIDTH {
            tangent(f, za, fa, zb, fb, zm, gm, h, roots);
            continue;
        }
        stack[top] = (zm, fm, zb, fb, 0.5 * h);
        stack[top + 1] = (za, fa, zm, fm, 0.5 * h);
        top += 2;
    }
}

/// A tiny cell that is neither excluded nor certified monotone: a near-tangency of F with
/// zero. The extremum of F (one Newton step on F′ from the middle) decides.
#[allow(clippy::too_many_arguments)]
fn tangent(
    f: &impl Periodic,
    za: C,
    fa: f64,
    zb: C,
    fb: f64,
    zm: C,
    gm: f64,
    h: f64,
    roots: &mut Roots,
) {
    if (fa < 0.0) != (fb < 0.0) {
        roots.push(brent_cell(f, za, fa, zb, fb));
        return;
    }
    let hm = f.second(zm);
    let u = if hm != 0.0 {
        (-gm / hm).clamp(-0.5 * h, 0.5 * h)
    } else {
        0.0
    };
    let te = 0.5 * u;
    let ze = along(zm, te);
    let fe = f.eval(ze).0;
    let tau = half_tangent(zm, zb);
    if (fe < 0.0) != (fa < 0.0) {
        let g = |t: f64| f.eval(along(zm, t)).0;
        roots.push(along(zm, brent(&g, -tau, te, fa, fe, tau)));
        roots.push(along(zm, brent(&g, te, tau, fe, fb, tau)));
    } else if fe.abs() <= f.tol() {
        let n = roots.n;
        roots.push(ze);
        if roots.n > n {
            roots.double[n] = true;
        }
    }
}

/// The root of F in a cell whose ends have opposite signs, by Brent's method on the
/// half-angle tangent about the cell's centre.
fn brent_cell(f: &impl Periodic, za: C, fa: f64, zb: C, fb: f64) -> C {
    let zc = unit(za + zb);
    let tau = half_tangent(zc, zb);
    let g = |t: f64| f.eval(along(zc, t)).0;
    along(zc, brent(&g, -tau, tau, fa, fb, tau))
}

/// The roots of F found by the scan, as unit complex numbers z = e^{iθ}, in the order of θ.
/// Roots closer than [`CLUSTER`] merge into one marked `multiple`: a near-tangency of F, where
/// rounding can make F cross zero several times.
#[derive(Default)]
pub(super) struct Roots {
    pub n: usize,
    pub z: [C; 12],
    pub multiple: [bool; 12],
    /// A double root within rounding (two roots merged at F's extremum, [`merge_double`]):
    /// its pose is taken there unpolished if it closes (Newton's method on the closures
    /// would walk to one of the two roots that rounding set apart).
    pub double: [bool; 12],
    /// The first root pushed to each cluster (the root itself when it is alone; for a
    /// double root, the first of the two merged).
    pub start: [C; 12],
    /// The last root pushed to each cluster (the root itself when it is alone).
    pub end: [C; 12],
    /// The last root of the stretch a double root's two merged roots spanned (else as `end`).
    pub stretch_end: [C; 12],
}

/// Roots of F closer than this (rad) are one cluster.
const CLUSTER: f64 = 1e-6;

impl Roots {
    /// Adds a root, or extends the cluster it continues: a root within [`CLUSTER`] of the
    /// last one pushed to the latest cluster (so that a stretch where F stays within its
    /// rounding of zero, pushed a root a tangent cell at a time, is one cluster however long)
    /// or of the first root (the circle closing).
    pub fn push(&mut self, z: C) {
        let near = |w: C| (z - w).norm() < CLUSTER;
        if self.n > 0 && near(self.end[self.n - 1]) {
            self.multiple[self.n - 1] = true;
            self.end[self.n - 1] = z;
        } else if self.n > 0 && near(self.z[0]) {
            self.multiple[0] = true;
        } else if self.n < self.z.len() {
            self.z[self.n] = z;
            self.start[self.n] = z;
            self.end[self.n] = z;
            self.stretch_end[self.n] = z;
            self.n += 1;
        }
    }

    /// The angles at which a cluster's poses are sought besides its first root: none for a
    /// cluster narrower than 2·[`CLUSTER`]; across a longer one (a plateau of F within its
    /// rounding of zero, where the three legs' circles are nearly coaxal and F cannot tell
    /// its roots apart, though the closures can), every 1e-5 rad up to its end (at most
    /// 256 samples).
    pub fn plateau(&self, r: usize) -> impl Iterator<Item = C> {
        samples(self.z[r], self.end[r], 1)
    }

    /// The angles across the stretch a double root's two merged roots spanned, from the
    /// first to the last, every 1e-5 rad (at most 257 samples); none for a root that is not
    /// double or a stretch narrower than 2·[`CLUSTER`]. F stays within its rounding of zero
    /// across it and may hide more modes there than the two it shows (its terms cancelling,
    /// the circles nearly coaxal); the closures tell them apart ([`regular_mode`]).
    pub fn stretch(&self, r: usize) -> impl Iterator<Item = C> {
        let first = if self.double[r] { 0 } else { usize::MAX };
        samples(self.start[r], self.stretch_end[r], first)
    }
}

/// Angles from z0 to z1 every 1e-5 rad at most (at most 256 steps), from step `first`; none
/// when they are closer than 2·[`CLUSTER`].
fn samples(z0: C, z1: C, first: usize) -> impl Iterator<Item = C> {
    let turn = z0.conj() * z1;
    let span = turn.im.atan2(turn.re).abs();
    let steps = if span > 2.0 * CLUSTER {
        ((span / 1e-5).ceil() as usize).clamp(1, 256)
    } else {
        0
    };
    let first = if steps == 0 { 1 } else { first };
    let sign = if turn.im < 0.0 { -1.0 } else { 1.0 };
    (first..=steps).map(move |k| {
        let phi = sign * span * k as f64 / steps as f64;
        z0 * C::new(phi.cos(), phi.sin())
    })
}

/// Whether a pose sampled across a double root's stretch ([`Roots::plateau`]) is a mode of
/// its own, from its rates at rest: a pose within rounding of a branch point (its rates
/// refused as [`Error::Singular`], the data's distance from the fold at most
/// [`SINGULAR_BRANCH`](super::SINGULAR_BRANCH)) is one of the two modes that rounding split
/// apart at the double root, which stands for both; a regular pose there (F flat across the
/// stretch, its terms cancelling) is a mode F could not show.
pub(super) fn regular_mode<T>(rates: Result<T>) -> bool {
    !matches!(rates, Err(Error::Singular { .. }))
}

/// The exponent k that brings the largest magnitude among `values` into [1/2, 1) when they
/// are multiplied by 2^k (0 when they are all zero): a group's data scaled by it solve in the
/// unit frame, where none of F's products (sixth powers of the lengths) over- or underflows,
/// and scaling by a power of two adds no rounding (a value leaves the normal range only if
/// it is below 2⁻¹⁰²² of the largest, far under anything the group can resolve).
pub(super) fn unit_exponent(values: impl IntoIterator<Item = f64>) -> i32 {
    let m = values.into_iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if m > 0.0 && m.is_finite() {
        -(m.log2().floor() as i32 + 1)
    } else {
        0
    }
}

/// x·2^k, exact unless the result leaves the normal range; in steps of at most 2^±1000 so
/// that every factor is representable (k spans up to ±2100 between subnormal and huge data).
pub(super) fn times_pow2(x: f64, k: i32) -> f64 {
    let (mut x, mut k) = (x, k);
    while k > 1000 {
        x *= 2f64.powi(1000);
        k -= 1000;
    }
    while k < -1000 {
        x *= 2f64.powi(-1000);
        k += 1000;
    }
    x * 2f64.powi(k)
}

/// z turned by the angle 2·atan(t): z·(1 + i·t)²/(1 + t²), without a trigonometric function.
#[inline]
pub(super) fn along(z: C, t: f64) -> C {
    let w = C::new(1.0 - t * t, 2.0 * t) / (1.0 + t * t);
    z * w
}

/// The unit complex number along z.
#[inline]
pub(super) fn unit(z: C) -> C {
    z / z.norm()
}

/// tan(α/2) for the angle α from zc to zb (less than π).
#[inline]
fn half_tangent(zc: C, zb: C) -> f64 {
    let r = zc.conj() * zb;
    r.im / (1.0 + r.re)
}

/// Brent's method (zeroin) for a root of g in [a, b] with g(a) = fa, g(b) = fb of opposite
/// signs (or one of them zero), to the resolution of f64 on an interval of half-width `half`.
pub(super) fn brent(g: &impl Fn(f64) -> f64, a: f64, b: f64, fa: f64, fb: f64, half: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (a, b, fa, fb);
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 {
        return b;
    }
    let xtol = 2.0 * f64::EPSILON * half;
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if (fb > 0.0) == (fc > 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            return b;
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = g(b);
    }
    b
}
