//! Whether a point of the plane is reached by the point of a linkage with two inputs: the
//! decision the workspace's outline is located by (module `workspace_boundary`).
//!
//! A point X of the plane is reached when some inputs q on the workspace's input grid's range
//! (a crank's whole turn, a slider's range) assemble the linkage in its plan's mode with its
//! point P(q) = X. Newton's method on P(q) = X (its Jacobian J = ∂P/∂q is the point's
//! velocities at unit input rates, which every solve gives) decides it: started from the
//! inputs of a reached neighbour when one is given, then from the input-grid nodes whose
//! images lie nearest X, each step limited to two grid steps per input, halved where the
//! linkage does not assemble, clamped to a slider's range; X is reached when |P(q) − X| falls
//! to 10⁻¹³ of the region's span. Near the edge of the reach the edge is a fold of the map
//! (det J = 0: a leg stretched or folded), the image of where the linkage stops assembling,
//! or the image of an isolated singular input (a pole of the map, below): on the reached side
//! within δ of a fold the map has two preimages about √δ apart, which Newton's method
//! reaches; on the other side its residual never falls below δ. So a decision "reached" is
//! certain (a preimage is found to the tolerance), and one "not reached" is exact down to
//! about 10⁻¹³ of the span wherever the preimages near the edge are regular.
//!
//! # Near a pole of the map
//! At an isolated input q* where a group's determinant vanishes and the linkage assembles all
//! round it (a five-bar's couplers folded onto each other) the point swings round a whole
//! curve as q goes round q*: P(q* + r·e(θ)) = C(θ) + r·W(θ) + O(r²), with e(θ) = (cos θ,
//! sin θ). In the inputs' own coordinates J grows as 1/r and Newton's method, started from
//! grid nodes a step away, wanders; but in the polar coordinates (r, θ) about q* the map is
//! smooth, with the Jacobian [J·e, r·J·e⊥] bounded and regular as r → 0 (its columns tend to
//! W(θ) and C′(θ)). So near the curve C the decision also runs Newton's method in (r, θ),
//! from the traced curve's point nearest X, keeping r > 0 (r = 0 is the singular input, not
//! a pose of the mode): X within the reach is found at r ≈ dist(X, C)/|W·n|; beyond the
//! curve Newton's method asks for r < 0 and the residual stays at the distance. The position
//! itself is computed to about εL²/|AC| there (a dyad's direction from two hinges |AC| apart,
//! |AC| ~ r), so X at δ from C is decided correctly down to δ ~ √ε·L (10⁻⁸ L): that is how
//! close to such a curve the outline is located.

use super::contour::Grid;
use nalgebra::{Point2, Vector2};
use std::collections::HashMap;

/// The input grid: each axis's first value, step and whether it wraps.
pub(crate) struct Axes {
    pub lo: [f64; 2],
    pub step: [f64; 2],
    pub grid: Grid,
}

impl Axes {
    /// The inputs at node `(i, j)`.
    pub(crate) fn q(&self, (i, j): super::contour::Node) -> [f64; 2] {
        #[allow(clippy::cast_precision_loss)]
        [
            self.lo[0] + self.step[0] * i as f64,
            self.lo[1] + self.step[1] * j as f64,
        ]
    }
}

/// The point's position and its velocities at unit rate of each input, at inputs q.
pub(crate) type Jac<'a> =
    dyn FnMut([f64; 2]) -> Option<(Point2<f64>, Vector2<f64>, Vector2<f64>)> + 'a;

/// An isolated singular input (a pole of the map, module docs) and the curve it maps to,
/// traced on a small circle about it: each sample's angle θ about `q` and the point there.
pub(crate) struct Pole {
    /// The singular input q*.
    pub q: [f64; 2],
    /// The radius of the traced circle about q*.
    pub radius: f64,
    /// (θ, P(q* + radius·e(θ))) round the circle.
    pub trace: Vec<(f64, Point2<f64>)>,
}

/// Decides whether points of the plane are reached (module docs).
pub(crate) struct Reach<'r, 'j> {
    jac: &'r mut Jac<'j>,
    axes: &'r Axes,
    /// Node images binned on squares of side `bin`: the node indices in each.
    bins: HashMap<(i64, i64), Vec<usize>>,
    bin: f64,
    /// Each node's image (`None` where it does not assemble).
    images: Vec<Option<Point2<f64>>>,
    /// The isolated singular inputs.
    poles: Vec<Pole>,
    /// The residual at which a point counts as reached, m.
    tol: f64,
}

/// The bin holding `p`.
#[allow(clippy::cast_possible_truncation)]
fn bin_of(p: Point2<f64>, bin: f64) -> (i64, i64) {
    ((p.x / bin).floor() as i64, (p.y / bin).floor() as i64)
}

/// Whether Newton's method has stalled: the residual falls by less than a quarter a step
/// (`slow` counts such steps in a row; four in a row give up). Converging at least linearly
/// by ½ (a double root's rate, the residual then falling by ¼) goes on; beyond the edge the
/// residual never falls below the distance to it.
fn stalled(slow: &mut u32, r: f64, rn: f64) -> bool {
    *slow = if rn > 0.75 * r { *slow + 1 } else { 0 };
    *slow >= 4
}

impl<'r, 'j> Reach<'r, 'j> {
    /// A decider over the nodes' images `images` (indexed as the input grid's nodes), with
    /// bins of side `bin`, the isolated singular inputs `poles` and the region's `span`.
    pub(crate) fn new(
        jac: &'r mut Jac<'j>,
        axes: &'r Axes,
        images: Vec<Option<Point2<f64>>>,
        poles: Vec<Pole>,
        bin: f64,
        span: f64,
    ) -> Self {
        let mut bins: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (k, p) in images.iter().enumerate() {
            if let Some(p) = p {
                bins.entry(bin_of(*p, bin)).or_default().push(k);
            }
        }
        Self {
            jac,
            axes,
            bins,
            bin,
            images,
            poles,
            tol: 1e-13 * span,
        }
    }

    /// The input-grid nodes' images with their inputs: points certainly reached.
    pub(crate) fn known(&self) -> Vec<(Point2<f64>, [f64; 2])> {
        self.images
            .iter()
            .enumerate()
            .filter_map(|(k, p)| p.map(|p| (p, self.node_q(k))))
            .collect()
    }

    /// The inputs of node `k`.
    fn node_q(&self, k: usize) -> [f64; 2] {
        let n2 = self.axes.grid.n2;
        self.axes.q((k / n2, k % n2))
    }

    /// Up to eight nodes whose images lie nearest `x` (within two bins).
    fn nearest(&self, x: Point2<f64>) -> Vec<usize> {
        let (bx, by) = bin_of(x, self.bin);
        let mut near: Vec<(f64, usize)> = Vec::new();
        for i in -2..=2 {
            for j in -2..=2 {
                if let Some(ks) = self.bins.get(&(bx + i, by + j)) {
                    for &k in ks {
                        if let Some(p) = self.images[k] {
                            near.push(((p - x).norm(), k));
                        }
                    }
                }
            }
        }
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        near.into_iter().take(8).map(|(_, k)| k).collect()
    }

    /// Inputs q in the range with P(q) − x inside the tolerance, by Newton's method from `q0`.
    fn newton(&mut self, x: Point2<f64>, q0: [f64; 2]) -> Option<[f64; 2]> {
        let (mut p, mut v1, mut v2) = (self.jac)(q0)?;
        let mut q = q0;
        let mut r = (x - p).norm();
        let mut slow = 0;
        let h = self.axes.step.map(f64::abs);
        for _ in 0..40 {
            if r <= self.tol(q, v1, v2) {
                return Some(q);
            }
            let det = v1.x * v2.y - v1.y * v2.x;
            if !(det.is_finite() && det != 0.0) {
                return None;
            }
            let d = x - p;
            // J·dq = d by Cramer's rule, J = [v1 v2].
            let mut dq = [
                (d.x * v2.y - d.y * v2.x) / det,
                (v1.x * d.y - v1.y * d.x) / det,
            ];
            let over = (dq[0].abs() / (2.0 * h[0])).max(dq[1].abs() / (2.0 * h[1]));
            if !over.is_finite() {
                return None;
            }
            if over > 1.0 {
                dq = dq.map(|c| c / over);
            }
            let mut t = 1.0;
            let mut next = None;
            for _ in 0..12 {
                let qn = self.clamp([q[0] + t * dq[0], q[1] + t * dq[1]]);
                if let Some(s) = (self.jac)(qn) {
                    next = Some((qn, s));
                    break;
                }
                t *= 0.5;
            }
            let (qn, (pn, a, b)) = next?;
            let rn = (x - pn).norm();
            if stalled(&mut slow, r, rn) {
                return None;
            }
            (q, p, v1, v2, r) = (qn, pn, a, b, rn);
        }
        (r <= self.tol(q, v1, v2)).then_some(q)
    }

    /// The residual at which x counts as reached from inputs `q` where the point moves at
    /// `v1`, `v2` per unit of each input: 10⁻¹³ of the span, or the position's own rounding
    /// there if larger. A rounding of q by its last bit (ε|qᵢ|) moves P(q) by ε|qᵢ|·|vᵢ|, so
    /// P is not defined closer than that, and it grows without bound near a pole (|vᵢ| ~ 1/r);
    /// four times the sum allows for the solve's own rounding of as much. It is capped at
    /// √ε of the span: near a pole that rounding grows as c₁/r while a point δ off the pole's
    /// curve has its preimage at r ~ δ/c₂, so a cap t accepts points up to t beyond the curve
    /// and decides those within c₁c₂/t inside it not reached; the error is least, √(c₁c₂)
    /// ~ √ε·L, at t of that size (module docs).
    fn tol(&self, q: [f64; 2], v1: Vector2<f64>, v2: Vector2<f64>) -> f64 {
        let moved = q[0].abs() * v1.norm() + q[1].abs() * v2.norm();
        let cap = f64::EPSILON.sqrt() * 1e13 * self.tol;
        self.tol.max((4.0 * f64::EPSILON * moved).min(cap))
    }

    /// Inputs q = q* + r·e(θ), r > 0, about pole `k` with P(q) − x inside the tolerance, by
    /// Newton's method in (r, θ) from (`r0`, `t0`) (module docs).
    fn polar(&mut self, x: Point2<f64>, k: usize, r0: f64, t0: f64) -> Option<[f64; 2]> {
        let qs = self.poles[k].q;
        let at = |r: f64, t: f64| [qs[0] + r * t.cos(), qs[1] + r * t.sin()];
        let rmax = 2.0 * self.axes.step[0].abs().max(self.axes.step[1].abs());
        let (mut r, mut t) = (r0, t0);
        let mut q = at(r, t);
        let (mut p, mut v1, mut v2) = (self.jac)(q)?;
        let mut res = (x - p).norm();
        let mut slow = 0;
        for _ in 0..40 {
            if res <= self.tol(q, v1, v2) {
                return Some(q);
            }
            let (e, n) = (
                Vector2::new(t.cos(), t.sin()),
                Vector2::new(-t.sin(), t.cos()),
            );
            // The columns ∂P/∂r = J·e and ∂P/∂θ = r·J·e⊥.
            let a = v1 * e.x + v2 * e.y;
            let b = (v1 * n.x + v2 * n.y) * r;
            let det = a.x * b.y - a.y * b.x;
            if !(det.is_finite() && det != 0.0) {
                return None;
            }
            let d = x - p;
            let mut dr = (d.x * b.y - d.y * b.x) / det;
            let mut dt = (a.x * d.y - a.y * d.x) / det;
            // At most half a radian round and a grid step out.
            let over = (dt.abs() / 0.5).max(dr.abs() / (0.5 * rmax));
            if !over.is_finite() {
                return None;
            }
            if over > 1.0 {
                (dr, dt) = (dr / over, dt / over);
            }
            let mut next = None;
            let mut s = 1.0;
            for _ in 0..12 {
                // r stays positive: a step to r ≤ 0 goes a quarter of the way to 0 instead
                // (the edge is the curve r = 0; beyond it the residual stalls).
                let rn = (r + s * dr).max(0.25 * r).min(rmax);
                let tn = t + s * dt;
                let qn = at(rn, tn);
                if let Some(v) = (self.jac)(qn) {
                    next = Some((rn, tn, qn, v));
                    break;
                }
                s *= 0.5;
            }
            let (rn, tn, qn, (pn, a, b)) = next?;
            let resn = (x - pn).norm();
            if stalled(&mut slow, res, resn) {
                return None;
            }
            (r, t, q, p, v1, v2, res) = (rn, tn, qn, pn, a, b, resn);
        }
        (res <= self.tol(q, v1, v2)).then_some(q)
    }

    /// Whether `x` is reached from the inputs near a pole, by [`Reach::polar`] from the two
    /// traced points nearest `x` (a quarter turn apart at least) of each pole whose curve
    /// passes within four bins of `x`.
    fn near_poles(&mut self, x: Point2<f64>) -> Option<[f64; 2]> {
        for k in 0..self.poles.len() {
            let pole = &self.poles[k];
            let mut near: Vec<(f64, f64)> = pole
                .trace
                .iter()
                .map(|&(t, p)| ((p - x).norm(), t))
                .collect();
            near.sort_by(|a, b| a.0.total_cmp(&b.0));
            let Some(&(d0, t0)) = near.first() else {
                continue;
            };
            if d0 > 4.0 * self.bin {
                continue;
            }
            let second = near.iter().find(|(_, t)| {
                let dt = (t - t0).rem_euclid(std::f64::consts::TAU);
                dt.min(std::f64::consts::TAU - dt) > std::f64::consts::FRAC_PI_2
            });
            let r0 = pole.radius;
            for t in std::iter::once(t0).chain(second.map(|s| s.1)) {
                if let Some(q) = self.polar(x, k, r0, t) {
                    return Some(q);
                }
            }
        }
        None
    }

    /// `q` clamped to a slider's (or a given) range; a crank's whole turn is not clamped.
    fn clamp(&self, q: [f64; 2]) -> [f64; 2] {
        let g = self.axes.grid;
        let mut out = q;
        for (i, wrap) in [g.wrap1, g.wrap2].into_iter().enumerate() {
            if !wrap {
                let n = if i == 0 { g.n1 } else { g.n2 };
                #[allow(clippy::cast_precision_loss)]
                let end = self.axes.lo[i] + self.axes.step[i] * (n - 1) as f64;
                let (lo, hi) = (self.axes.lo[i].min(end), self.axes.lo[i].max(end));
                out[i] = q[i].clamp(lo, hi);
            }
        }
        out
    }

    /// Whether `x` is reached, trying the inputs `warm` first (inputs whose image is near x:
    /// a reached neighbour's preimage); the preimage found, if any.
    pub(crate) fn reaches(&mut self, x: Point2<f64>, warm: &[[f64; 2]]) -> Option<[f64; 2]> {
        for &q0 in warm {
            if let Some(q) = self.newton(x, q0) {
                return Some(q);
            }
        }
        for k in self.nearest(x) {
            let q0 = self.node_q(k);
            if let Some(q) = self.newton(x, q0) {
                return Some(q);
            }
        }
        self.near_poles(x)
    }
}
