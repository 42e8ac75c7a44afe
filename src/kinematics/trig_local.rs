//! The second certificate of tracking a mode of a group of the 3rd class, for where the
//! first one ([`Cubic::certifies`]: no other root of F within a radius from Taylor's bounds)
//! cannot tell: every root of the eliminated equation F on the short arc of angles where a
//! mode could be as near the previous pose as the tracked one, bracketed with local bounds,
//! and the poses of the roots other than the tracked one compared.
//!
//! Why it is needed. Where the linear equations that give the ternary link's reference point
//! at a fixed angle are nearly parallel (Δ ≈ 0 for the sliding triad, D ≈ 0 for the triad),
//! F = Δ²·g carries the factor Δ², and two modes lie a few 1e-3 rad apart in θ with their
//! reference points far apart (where a line cuts a circle twice). F is flat there
//! (|F′| ≈ 1e-4 against M₂ ≈ 8 on the bench's sliding triad), so no radius from global
//! bounds isolates the tracked root, though the other mode is far in the pose.
//!
//! The rule. A mode turned by Δθ from the previous pose is at least 4·I·sin²(Δθ/2) from it
//! (D² = 3|c − c′|² + 4·I·sin²(Δθ/2), c the centroid of the ternary link's joints, I their
//! polar moment about it), so a mode nearer than the tracked one (D*) has
//! |θ − θ_prev| < δ with 4·I·sin²(δ/2) = D*². Every root of F on that arc is bracketed
//! ([`roots_near`]): cells in the half-angle tangent t about the previous angle
//! (|dθ/dt| ≤ 2, so a cell of width Δt spans at most 2Δt of angle and every point of it is
//! within r = Δt of the angle at its middle), each *excluded* (|F| − |F′|·r − B₂·r²/2 >
//! tol, B₂ = |F″(mid)| + M₃·r ≥ |F″| on the cell by Taylor's theorem with M₃ ≥ |F‴|) or
//! *monotone* (|F′| − B₂·r > tol: at most one root, present when the ends' signs differ,
//! each end farther than tol from zero) or halved. The cell holding the tracked angle is its
//! root; every other root's poses are found as the full scan finds them and must be farther
//! from the previous pose than D* (or be the tracked mode itself). Anything the rule cannot
//! settle (a cell that keeps neither property, too many roots, an arc too wide) sends the
//! position to the full scan.

use super::trig_cubic::Cubic;
use super::trig_roots::{along, brent};
use nalgebra::{Complex, Point2};

type C = Complex<f64>;

/// The most cells examined on one arc before the full scan is left to decide.
const BUDGET: usize = 48;
/// The most roots of F bracketed on one arc (the degree's six).
const MOST: usize = 6;

/// The roots of F on an arc, each bracketed in a cell of the half-angle tangent t about the
/// arc's centre (z = z_c·(1 + i·t)²/(1 + t²)).
pub(super) struct NearRoots {
    pub n: usize,
    /// Each root's cell [t_a, t_b] with F at its ends.
    pub cells: [(f64, f64, f64, f64); MOST],
}

impl NearRoots {
    /// The root in cell `k`, by Brent's method on t.
    pub fn root(&self, f: &Cubic, zc: C, k: usize) -> C {
        let (ta, fa, tb, fb) = self.cells[k];
        let g = |t: f64| f.eval(along(zc, t)).0;
        along(
            zc,
            brent(
                &g,
                ta,
                tb,
                fa,
                fb,
                0.5 * (tb - ta).abs().max(ta.abs()).max(tb.abs()),
            ),
        )
    }
}

/// Every root of F with |θ − θ_c| ≤ `half` (z_c = e^{iθ_c}, 0 < `half` ≤ 1 rad), bracketed
/// with local bounds (module docs); `None` when the rule cannot settle the arc.
pub(super) fn roots_near(f: &Cubic, zc: C, half: f64) -> Option<NearRoots> {
    if !(half > 0.0 && half <= 1.0) {
        return None;
    }
    let tau = (0.5 * half).tan();
    let value = |t: f64| f.eval(along(zc, t)).0;
    let mut out = NearRoots {
        n: 0,
        cells: [(0.0, 0.0, 0.0, 0.0); MOST],
    };
    // Depth-first over cells (t_a, F_a, t_b, F_b); each halving adds one waiting cell.
    let mut stack = [(0.0, 0.0, 0.0, 0.0); BUDGET + 2];
    let (fl, fr) = (value(-tau), value(tau));
    stack[0] = (-tau, fl, tau, fr);
    let mut top = 1;
    let mut examined = 0;
    let tol = f.tol;
    while top > 0 {
        top -= 1;
        examined += 1;
        if examined > BUDGET {
            return None;
        }
        let (ta, fa, tb, fb) = stack[top];
        let tm = 0.5 * (ta + tb);
        let zm = along(zc, tm);
        let (fm, gm) = f.eval(zm);
        let r = tb - ta;
        let b2 = f.second(zm).abs() + f.m3 * r;
        if fm.abs() - gm.abs() * r - 0.5 * b2 * r * r > tol {
            continue;
        }
        if gm.abs() - b2 * r > tol {
            if fa.abs() <= tol || fb.abs() <= tol {
                return None;
            }
            if (fa < 0.0) != (fb < 0.0) {
                if out.n == MOST {
                    return None;
                }
                out.cells[out.n] = (ta, fa, tb, fb);
                out.n += 1;
            }
            continue;
        }
        if top + 2 > stack.len() {
            return None;
        }
        stack[top] = (tm, fm, tb, fb);
        stack[top + 1] = (ta, fa, tm, fm);
        top += 2;
    }
    Some(out)
}

/// Whether the tracked mode (its joints `ours`, its direction `z_ours`) is certified, by the
/// rule of the module docs, to be the mode nearest `previous` of all the group's modes:
/// `previous` are the previous pose's joints, `poses` gives the joints of the modes at a
/// root of F as the full scan finds them (each polished),
/// `moment` is I = Σ|β_i − β̄|² and `same` the distance within which two poses are one mode.
#[cold]
#[inline(never)]
pub(super) fn nearest_on_arc(
    f: &Cubic,
    previous: &[Point2<f64>; 3],
    ours: &[Point2<f64>; 3],
    z_ours: C,
    moment: f64,
    same: f64,
    poses: impl Fn(C) -> [Option<[Point2<f64>; 3]>; 4],
) -> bool {
    let d2 = |p: &[Point2<f64>; 3], q: &[Point2<f64>; 3]| {
        (p[0] - q[0]).norm_squared() + (p[1] - q[1]).norm_squared() + (p[2] - q[2]).norm_squared()
    };
    let moved = d2(ours, previous);
    // The arc |θ − θ_prev| < δ outside which a mode is farther than D*: 4·I·sin²(δ/2) = D*²,
    // widened by 0.1 % (and the sine's argument by a relative 1e-6) for rounding.
    let x = (moved / (4.0 * moment)).sqrt() * (1.0 + 1e-6);
    if !(x.is_finite() && x < 0.4) {
        return false;
    }
    let half = 2.0 * x.asin() * 1.001;
    let side = previous[1] - previous[0];
    let zp = C::new(side.x, side.y) / side.norm();
    let Some(near) = roots_near(f, zp, half) else {
        return false;
    };
    let r = zp.conj() * z_ours;
    let t_ours = r.im / (1.0 + r.re);
    let mut found = false;
    for k in 0..near.n {
        let (ta, _, tb, _) = near.cells[k];
        if ta <= t_ours && t_ours <= tb {
            found = true;
            continue;
        }
        for pose in poses(near.root(f, zp, k)).into_iter().flatten() {
            if d2(&pose, ours) <= same * same {
                continue;
            }
            let d = d2(&pose, previous);
            if d.is_nan() || d <= moved * (1.0 + 1e-9) {
                return false;
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::super::{
        slider_triad, slider_triad_modes, slider_triad_tracked, Guide, PointMotion,
        SliderTriadDims, SlidingPair, TriadPose,
    };
    use nalgebra::{Point2, Vector2};

    /// The bench's sliding triad on its crank of 0.05 m (1024 positions a turn): 13 of its
    /// positions, near where the radical axis turns parallel to the guide, were left to the
    /// full scan by the first certificate. Every position is now answered by the fast path,
    /// and every answer is the full scan's nearest mode (to 1e-12 of the size), the mode
    /// that the cycle continues.
    #[test]
    fn the_second_certificate_keeps_the_bench_cycle_on_the_fast_path() {
        let dims = SliderTriadDims {
            pair: SlidingPair::Outer { offset: 0.0 },
            l: [0.55, 0.5],
            l_b1b2: 0.5,
            b3_along: 0.2,
            b3_across: 0.35,
        };
        let guide = Guide::fixed(Point2::new(-1.0, 0.0), 0.0);
        let b = [
            Point2::new(0.0, 0.0),
            Point2::new(0.5, 0.0),
            Point2::new(0.2, 0.35),
        ];
        let leg = |l: f64, angle: f64| l * Vector2::new(angle.cos(), angle.sin());
        let a0 = [b[1] - leg(0.55, 2.2), b[2] - leg(0.5, -2.0)];
        let (radius, n) = (0.05, 1024);
        let centre = a0[0] - Vector2::new(radius, 0.0);
        let mut prev = TriadPose {
            b,
            theta: 0.0,
            phi: [0.0; 3],
            det: 0.0,
        };
        let mut fast = 0;
        for k in 0..=n {
            let phi = std::f64::consts::TAU * (k % n) as f64 / n as f64;
            let p = [centre + radius * Vector2::new(phi.cos(), phi.sin()), a0[1]];
            let full = *slider_triad_modes(&guide, p, &dims)
                .expect("assembles")
                .nearest(&prev);
            if k > 0 {
                let t = slider_triad_tracked(&guide, p, &dims, &prev).expect("the fast path");
                assert!(t.distance_squared(&full).sqrt() <= 1e-12, "position {k}");
                fast += 1;
            }
            let m = [PointMotion::fixed(p[0]), PointMotion::fixed(p[1])];
            prev = slider_triad(&guide, m, &dims, &prev)
                .expect("solves")
                .pose();
            assert!(prev.distance_squared(&full).sqrt() <= 1e-12, "position {k}");
        }
        assert_eq!(fast, n);
    }
}
