//! The fast path of tracking a group of the 3rd class along a cycle: Newton's method on the
//! group's three closures from the previous pose, and a certificate that the root it reaches
//! is the assembly mode that the full scan's [`nearest`](super::AssemblyModes::nearest)
//! would pick. The eliminated equation F(θ) is never formed.
//!
//! # Unknowns and the metric
//! The ternary link's pose is its joints' centroid c and its angle θ (kept as the unit vector
//! z = (cos θ, sin θ)); its joints are B_i = c + R(θ)·β̄_i with β̄_i the joints about their
//! centroid in the link's frame (Σβ̄_i = 0) and I = Σ|β̄_i|² their polar moment. The distance
//! of [`nearest`](super::AssemblyModes::nearest), D² = Σ|B_i − B_i′|², is then exactly
//! D² = 3|Δc|² + 4I·sin²(Δθ/2) (the cross terms hold Σβ̄_i = 0). For a change
//! Δ = (Δc, Δθ) with |Δθ| ≤ π write ‖Δ‖_W² = 3|Δc|² + I·Δθ²; since 2|sin(Δθ/2)| ≤ |Δθ|,
//! D ≤ ‖Δ‖_W, and since |Δθ| ≤ π|sin(Δθ/2)| on [−π, π], Δθ² ≤ π²·D²/(4I).
//!
//! # The closures are quadratic
//! Each closure g_i is exactly quadratic in the joints and in the rotation's unit vector: with
//! ΔB_i = Δc + (R(Δθ) − 1)·ρ_i (ρ_i = R(θ)·β̄_i) and R(Δθ)·ρ = ρ + Δθ·ρ⊥ + e,
//! |e| ≤ Δθ²·|ρ|/2 (|e^{iφ} − 1 − iφ| ≤ φ²/2), every other pose q = p + Δ satisfies
//!
//! g(q) = g(p) + J·Δ + r,  ‖r‖₂ ≤ C·D(p, q)²,
//!
//! with J the Jacobian at p (the velocity system, each row scaled by its leg) and C from each
//! kind of closure (the callers derive theirs: ½ + π²/(8I)·‖(|d_i|·|β̄_i|)‖₂ for hinged legs).
//!
//! # The certificate
//! Let σ be a lower bound of J's least singular value in the metric W (‖J·Δ‖₂ ≥ σ‖Δ‖_W):
//! σ = 1/‖W^{1/2}·J⁻¹‖_F, from the inverse the rates use anyway. For a root q at D from p,
//! 0 = g(p) + J·Δ + r gives σ·D ≤ σ‖Δ‖_W ≤ ‖g(p)‖ + C·D², so σD − CD² ≤ ‖g(p)‖: no root lies
//! at D strictly between D₋ and D₊ = (σ ± √(σ² − 4C‖g(p)‖))/(2C). A root within D₋ exists:
//! the map Δ ↦ −J⁻¹(g(p) + r(Δ)) takes the ball ‖Δ‖_W ≤ D₋ into itself (its image is at most
//! (‖g‖ + C·D₋²)/σ = D₋ long), so it has a fixed point (Brouwer), a root of g. Every other
//! mode q′ is at least D₊ from p, so D(q′, prev) ≥ D₊ − D(p, prev), while the mode q near p
//! is at most D(p, prev) + D₋ from the previous pose: q is the nearest when
//!
//! 2·D(p, prev) < D₊ − D₋ = √(σ² − 4C‖g(p)‖)/C,
//!
//! checked in squares (no square root) with ‖g‖₂ ≤ ‖g‖₁ plus its rounding, and σ² shrunk by
//! 2 % for the rounding of J⁻¹ (relative 1e-13 where the pose is accepted). Near a fold σ → 0
//! and the certificate refuses: the full scan decides there.
//!
//! # The stop rule
//! A Newton step Δ = −J⁻¹·g leaves the residual r(Δ), at most C‖Δ‖_W², so p + Δ is within
//! C‖Δ‖_W²/σ of the root (plus rounding). The iteration stops at a step ‖Δ‖_W ≤ 1e-10·σ and
//! returns p + Δ: its quadratic remainder C·1e-20·σ is below the rounding of the pose for
//! any σ up to the group's size, and the rates, read from J at p, are off those at p + Δ by
//! about ‖δJ‖/σ ≤ 1e-10 relative (J's rows change by |ΔB_i| ≤ ‖Δ‖_W over the step). At the
//! root the computed step is rounding, at most ‖g's rounding‖/σ (the *floor*); a step at
//! twice the floor that is still above 1e-10·σ means σ is too small for that (near a fold),
//! and the fast path refuses. The rates are solved with the Jacobian at p + Δ, inverted
//! again: read from J at p they would be off by up to a part in 10¹⁰, which differences of
//! the velocities over a cycle's steps amplify.

use nalgebra::{Matrix3, Vector2, Vector3};

/// The unit roundoff, 2⁻⁵³.
const U: f64 = f64::EPSILON / 2.0;

/// The most Newton steps the fast path takes: from a step of 0.5 rad, quadratic convergence
/// reaches the floor in six; more means the iteration is not converging to a simple root.
const MAX_STEPS: usize = 8;

/// One evaluation of a group's closures at a pose: the closures g, their Jacobian J in
/// (c, θ), and a bound of the rounding of g (a 1-norm).
pub(super) struct Eval {
    pub g: Vector3<f64>,
    pub j: Matrix3<f64>,
    pub g_round: f64,
}

/// What a group's closures give at a pose: ρ_i = R(θ)·β̄_i, the hinged legs' d = B − A
/// (`K` of them), the closures g and their Jacobian J.
pub(super) type Rows<const K: usize> = (
    [Vector2<f64>; 3],
    [Vector2<f64>; K],
    Vector3<f64>,
    Matrix3<f64>,
);

/// The closures of a group of the 3rd class in (c, z), for [`solve`].
pub(super) trait Closures {
    /// g, J and g's rounding at the centroid `c` and direction `z`.
    fn eval(&self, c: Vector2<f64>, z: Vector2<f64>) -> Eval;
}

/// The pose reached: the last point of evaluation p = (c, z), its Jacobian, the last step (p + step is the pose to return) and what the certificate
/// needs.
pub(super) struct Solved {
    pub c: Vector2<f64>,
    pub z: Vector2<f64>,
    pub j: Matrix3<f64>,
    pub step: Vector3<f64>,
    /// σ², the lower bound of J's least singular value in the metric W, squared.
    pub sigma2: f64,
    /// ‖g(p)‖₁ plus its rounding.
    pub g_norm: f64,
}

/// z turned by δ: z·(1 − δ²/2 + i·(δ − δ³/6)), renormalised by one Newton step of 1/√
/// ((3 − |w|²)/2 squares a deviation of |w| from 1). The turn's angle is δ + O(δ⁵) — Newton's
/// step, to far better than its own quadratic error — with no trigonometric function.
#[inline(always)]
pub(super) fn turn(z: Vector2<f64>, delta: f64) -> Vector2<f64> {
    let d2 = delta * delta;
    let (rc, rs) = (1.0 - 0.5 * d2, delta * (1.0 - d2 / 6.0));
    let w = Vector2::new(z.x * rc - z.y * rs, z.y * rc + z.x * rs);
    w * (0.5 * (3.0 - w.norm_squared()))
}

/// [f(0), f(1), f(2)], inlined (`[0, 1, 2].map(f)` was left as a call in the hot paths).
#[inline(always)]
pub(super) fn each3<T>(f: impl Fn(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

/// [f(0), f(1)], inlined.
#[inline(always)]
pub(super) fn each2<T>(f: impl Fn(usize) -> T) -> [T; 2] {
    [f(0), f(1)]
}

/// The vector `v` turned by the unit vector `z` (complex product).
#[inline(always)]
pub(super) fn rotate(z: Vector2<f64>, v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(z.x * v.x - z.y * v.y, z.y * v.x + z.x * v.y)
}

/// The inverse of a 3×3 matrix by its adjugate, and the determinant.
#[inline(always)]
pub(super) fn inverse3(k: &Matrix3<f64>) -> (Matrix3<f64>, f64) {
    let c00 = k[(1, 1)] * k[(2, 2)] - k[(1, 2)] * k[(2, 1)];
    let c01 = k[(1, 2)] * k[(2, 0)] - k[(1, 0)] * k[(2, 2)];
    let c02 = k[(1, 0)] * k[(2, 1)] - k[(1, 1)] * k[(2, 0)];
    let det = k[(0, 0)] * c00 + k[(0, 1)] * c01 + k[(0, 2)] * c02;
    let adj = Matrix3::new(
        c00,
        k[(0, 2)] * k[(2, 1)] - k[(0, 1)] * k[(2, 2)],
        k[(0, 1)] * k[(1, 2)] - k[(0, 2)] * k[(1, 1)],
        c01,
        k[(0, 0)] * k[(2, 2)] - k[(0, 2)] * k[(2, 0)],
        k[(0, 2)] * k[(1, 0)] - k[(0, 0)] * k[(1, 2)],
        c02,
        k[(0, 1)] * k[(2, 0)] - k[(0, 0)] * k[(2, 1)],
        k[(0, 0)] * k[(1, 1)] - k[(0, 1)] * k[(1, 0)],
    );
    (adj * (1.0 / det), det)
}

/// ‖Δ‖_W² = 3|Δc|² + I·Δθ² (module docs).
#[inline(always)]
fn w_norm2(step: &Vector3<f64>, moment: f64) -> f64 {
    3.0 * (step.x * step.x + step.y * step.y) + moment * step.z * step.z
}

/// ‖W^{1/2}·J⁻¹‖_F² = 1/σ² (module docs): W^{1/2} = diag(√3, √3, √I) scales J⁻¹'s rows.
#[inline(always)]
fn frobenius2(j_inv: &Matrix3<f64>, moment: f64) -> f64 {
    let row = |i: usize| {
        j_inv[(i, 0)] * j_inv[(i, 0)]
            + j_inv[(i, 1)] * j_inv[(i, 1)]
            + j_inv[(i, 2)] * j_inv[(i, 2)]
    };
    3.0 * (row(0) + row(1)) + moment * row(2)
}

/// Newton's method on the closures from (`c`, `z`) to the stop rule (module docs); `None`
/// when it does not converge within [`MAX_STEPS`], a step turns by more than 0.5 rad (no
/// tracking then) or anything is not finite. `moment` is I.
#[inline(always)]
pub(super) fn solve(
    closures: &impl Closures,
    mut c: Vector2<f64>,
    mut z: Vector2<f64>,
    moment: f64,
) -> Option<Solved> {
    for _ in 0..MAX_STEPS {
        let e = closures.eval(c, z);
        let (j_inv, _) = inverse3(&e.j);
        let step = -(j_inv * e.g);
        // f = ‖W^{1/2}·J⁻¹‖_F² = 1/σ²: the stop rule's comparisons multiplied out by it.
        let f = frobenius2(&j_inv, moment);
        let w2 = w_norm2(&step, moment);
        // (NaN fails every comparison and ends in `None`.)
        if w2 * f <= 1e-20 {
            return Some(Solved {
                c,
                z,
                j: e.j,
                step,
                sigma2: 1.0 / f,
                g_norm: e.g.x.abs() + e.g.y.abs() + e.g.z.abs() + e.g_round,
            });
        }
        // At twice the floor (‖Δ‖ ≤ 2·rounding/σ) but above 1e-10·σ: σ is too small for
        // the rates to be read from J at p; the full path decides.
        if !(w2 > 4.0 * e.g_round * e.g_round * f && step.z.abs() <= 0.5) {
            return None;
        }
        c += Vector2::new(step.x, step.y);
        z = turn(z, step.z);
    }
    None
}

/// The certificate (module docs): whether the root near the last point of evaluation is
/// certainly the mode nearest a previous pose `moved2` = D(p, prev)² from it, with the
/// closures' curvature constant `curv` = C.
#[inline(always)]
pub(super) fn certifies(s: &Solved, curv: f64, moved2: f64) -> bool {
    let disc = 0.98 * s.sigma2 - 4.0 * curv * s.g_norm;
    // (NaN fails.)
    disc > 0.0 && 4.0 * moved2 * curv * curv < disc
}

/// The rounding of a hinged leg's closure ½(|B − A|² − l²) evaluated as in the callers:
/// the joint B = origin + c + z·β̄ is off by about 4u·(|c| + |β̄| + |a|), the leg d = B − A by
/// as much again plus u·|d|, and the sum of squares by 2u·(|d|² + l²): a bound of 4u times
/// ((|d|² + l²) + 2l·(|c|₁ + |β̄|₁ + |a|₁ + l)) (1-norms bound the lengths), returned as the
/// part without |c|₁ and the factor of |c|₁ (the pose's part).
#[inline(always)]
pub(super) fn hinged_rounding(l: f64, beta1: f64, a1: f64) -> (f64, f64) {
    (
        4.0 * U * (2.0 * l * l + 2.0 * l * (beta1 + a1 + l)),
        8.0 * U * l,
    )
}

/// The rounding of a sliding leg's closure λ·(n·B − h), linear in the joint: each term of
/// the product off by about 4u of its size, returned as the part for the terms other than
/// the centroid, of 1-norm `terms`, and the factor of |c|₁.
#[inline(always)]
pub(super) fn line_rounding(lambda: f64, terms: f64) -> (f64, f64) {
    (4.0 * U * lambda * terms, 4.0 * U * lambda)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The turn is a rotation by δ to O(δ⁵) and stays on the unit circle.
    #[test]
    fn turn_is_a_rotation_to_fifth_order_and_unit() {
        let z = Vector2::new(0.6, 0.8);
        for delta in [1e-12, 1e-6, 1e-3, 1e-2, 0.1] {
            let w = turn(z, delta);
            let exact = rotate(z, Vector2::new(delta.cos(), delta.sin()));
            assert!(
                (w - exact).norm() <= 0.05 * delta.powi(5) + 2e-16,
                "{delta}"
            );
            let w2 = turn(w, 0.0);
            assert!((w2.norm() - 1.0).abs() <= 4e-16, "{delta}: {}", w2.norm());
        }
    }
}
