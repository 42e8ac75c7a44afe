//! The fast path of the triad with a sliding pair, as the revolute triad's
//! ([`triad_fast`](super::triad_fast)): its three closures solved by Newton's method in the
//! ternary link's centroid c and angle θ from the previous pose, the certificate of
//! [`triad_newton`](super::triad_newton), and the rates from the same Jacobian. The origin is
//! A2; ρ_i = R(θ)·β̄_i (β̄_i the joints about their centroid), B_i = c + ρ_i.
//!
//! # The closures and their Jacobian rows
//! - The hinged legs (A2 B2, A3 B3), as the triad's: g = ½(|d|² − l²), d = B − A, row
//!   d·[1, ρ⊥]; remainder d·e + ½|ΔB|² with |e| ≤ Δθ²|β̄|/2.
//! - The outer slide: B1 on the guide's line at the offset e, g_1 = λ·(n·B1 − h) with n the
//!   guide's normal (h = n·P + e, P a point of the guide); row λ·[n, ρ_1 × n]; remainder
//!   λ·n·e_1, at most λ·|β̄_1|·Δθ²/2. λ = (l_2 + l_3)/2 gives the row the hinged rows' unit
//!   (m²), so that σ weighs the three alike.
//! - The inner slide: A1 on the ternary link's guide through B1 at the offset e: with t = R(θ)·δ
//!   the guide's direction and n = t⊥, n·(A1 − B1) = e; since n·ρ_1 = δ⊥·β̄_1 = k does not
//!   turn, g_1 = λ·(n·(A1 − c) − k − e); ∂n/∂θ = −t, so the row is −λ·[n, t·(A1 − c)]. The
//!   remainder: n turned by Δθ is n + Δθ·t·(−1) + e_n with |e_n| ≤ Δθ²/2, and the step Δc
//!   meets the turned n: |r_1| ≤ λ·(Δθ²/2·|A1 − c| + 2|sin(Δθ/2)|·|Δc|)
//!   ≤ λ·(π²|A1 − c|/(8I) + 1/√(3I))·D² (Δθ² ≤ π²D²/(4I), 2|sin(Δθ/2)| ≤ D/√I,
//!   |Δc| ≤ D/√3).
//!
//! The certificate's C is ½ (the hinged legs' ½ΣΔB²) plus the 2-norm of the three rows'
//! other coefficients (π²/(8I)·|d_k|·|β̄_k| for a hinged leg, the slide's above).
//!
//! # Rates
//! A row of the velocity system with B1 as the reference point, (w, (p − B1) × w)·(v_B1, ω)
//! = R, reads (w, (p − c) × w)·(v_c, ω) = R with v_B1 = v_c + ω·ρ_1⊥, and for the
//! accelerations (a_B1 = a_c + ε·ρ_1⊥ − ω²ρ_1) the right side gains ω²·w·ρ_1. The right sides
//! are those of the module [`triad_slider`](super::triad_slider) (with its Coriolis terms),
//! each row scaled as J's (λ, −λ, or the hinged leg's l).

use super::fast_angle::direction_of;
use super::fold::{Leg, Legs};
use super::link::LinkMotion;
use super::motion::PointMotion;
use super::rrp::Guide;
use super::triad::{TriadPose, TriadState};
use super::triad_newton::{
    certifies, each2, each3, hinged_rounding, inverse3, line_rounding, rotate, solve, turn,
    Closures, Eval, Rows,
};
use super::triad_slider::{SliderTriadDims, SlidingPair};
use crate::angle::{cross, perp};
use nalgebra::{Matrix3, Point2, Vector2, Vector3};
use std::f64::consts::PI;

/// The sliding leg's closure: the outer pair's fixed line (its normal n and h, origin A2) or
/// the inner pair's guide (its direction δ in the ternary link's frame, A1 − A2 and the
/// constant k + e).
#[derive(Clone, Copy)]
enum Slide {
    Outer {
        n: Vector2<f64>,
        h: f64,
    },
    Inner {
        delta: Vector2<f64>,
        a1: Vector2<f64>,
        k: f64,
    },
}

/// The closures at one position, origin A2.
struct Sliding {
    slide: Slide,
    /// λ, the slide row's scale (m).
    lambda: f64,
    /// A2 − A2 = 0 and A3 − A2 for the hinged legs 2 and 3.
    a: [Vector2<f64>; 2],
    beta: [Vector2<f64>; 3],
    l2: [f64; 2],
    round0: f64,
    round_c: f64,
}

impl Sliding {
    /// ρ_i, the hinged legs' d_k, g and J at (c, z).
    #[inline(always)]
    fn rows(&self, c: Vector2<f64>, z: Vector2<f64>) -> Rows<2> {
        let rho = each3(|i| rotate(z, self.beta[i]));
        let d = [c + rho[1] - self.a[0], c + rho[2] - self.a[1]];
        let (g1, w, m) = match self.slide {
            Slide::Outer { n, h } => (
                self.lambda * (n.dot(&(c + rho[0])) - h),
                self.lambda * n,
                self.lambda * cross(rho[0], n),
            ),
            Slide::Inner { delta, a1, k } => {
                let t = rotate(z, delta);
                let (n, q) = (perp(t), a1 - c);
                (
                    self.lambda * (n.dot(&q) - k),
                    -self.lambda * n,
                    -self.lambda * t.dot(&q),
                )
            }
        };
        let g = Vector3::new(
            g1,
            0.5 * (d[0].norm_squared() - self.l2[0]),
            0.5 * (d[1].norm_squared() - self.l2[1]),
        );
        let j = Matrix3::new(
            w.x,
            w.y,
            m,
            d[0].x,
            d[0].y,
            cross(rho[1], d[0]),
            d[1].x,
            d[1].y,
            cross(rho[2], d[1]),
        );
        (rho, d, g, j)
    }
}

impl Closures for Sliding {
    #[inline(always)]
    fn eval(&self, c: Vector2<f64>, z: Vector2<f64>) -> Eval {
        let (_, _, g, j) = self.rows(c, z);
        Eval {
            g,
            j,
            g_round: self.round0 + self.round_c * (c.x.abs() + c.y.abs()),
        }
    }
}

/// A mode reached and certified by the fast path.
pub(super) struct Fast {
    /// J′⁻¹ and det J′, J′ the Jacobian at the returned pose.
    j_inv: Matrix3<f64>,
    det_j: f64,
    slide: Slide,
    lambda: f64,
    /// The returned pose's joints and direction, its ρ_i and hinged legs' d_k.
    b: [Point2<f64>; 3],
    z: Vector2<f64>,
    rho: [Vector2<f64>; 3],
    d: [Vector2<f64>; 2],
}

/// The slide's unit vector along its guide and its normal at the direction `z`.
#[inline(always)]
fn guide_at(slide: Slide, z: Vector2<f64>) -> (Vector2<f64>, Vector2<f64>) {
    match slide {
        Slide::Outer { n, .. } => (Vector2::new(n.y, -n.x), n),
        Slide::Inner { delta, .. } => {
            let t = rotate(z, delta);
            (t, perp(t))
        }
    }
}

/// The fast path on valid input: `None` unless the certificate holds.
#[inline(always)]
pub(super) fn track(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
    previous: &TriadPose,
) -> Option<Fast> {
    let local = dims.triangle().local_joints();
    let mean = (local[0] + local[1] + local[2]) / 3.0;
    let beta = each3(|i| local[i] - mean);
    let moment = beta[0].norm_squared() + beta[1].norm_squared() + beta[2].norm_squared();
    let origin = a[0];
    let rel = [Vector2::zeros(), a[1] - origin];
    let l = dims.l;
    let lambda = 0.5 * (l[0] + l[1]);
    let n1 = |v: Vector2<f64>| v.x.abs() + v.y.abs();
    let (mut round0, mut round_c) = (0.0, 0.0);
    for k in 0..2 {
        let (r0, rc) = hinged_rounding(l[k], n1(beta[k + 1]), n1(rel[k]));
        round0 += r0;
        round_c += rc;
    }
    let slide = match dims.pair {
        SlidingPair::Outer { offset } => {
            let (s, co) = first.angle.value.sin_cos();
            let n = Vector2::new(-s, co);
            let h = n.dot(&(first.point.p - origin)) + offset;
            round0 += line_rounding(lambda, n1(beta[0]) + h.abs()).0;
            Slide::Outer { n, h }
        }
        SlidingPair::Inner { angle, offset } => {
            let (s, co) = angle.sin_cos();
            let delta = Vector2::new(co, s);
            let a1 = first.point.p - origin;
            let k = perp(delta).dot(&beta[0]) + offset;
            round0 += line_rounding(lambda, n1(a1) + k.abs()).0;
            Slide::Inner { delta, a1, k }
        }
    };
    round_c += line_rounding(lambda, 0.0).1;
    let closures = Sliding {
        slide,
        lambda,
        a: rel,
        beta,
        l2: [l[0] * l[0], l[1] * l[1]],
        round0,
        round_c,
    };
    let p = previous.b;
    let side = p[1] - p[0];
    let z0 = side / side.norm();
    let c0 = (p[0].coords + p[1].coords + p[2].coords) / 3.0 - origin.coords;
    let s = solve(&closures, c0, z0, moment)?;
    let rho = each3(|i| rotate(s.z, beta[i]));
    let moved2 = (0..3)
        .map(|i| (origin + s.c + rho[i] - p[i]).norm_squared())
        .sum::<f64>();
    let k8 = PI * PI / (8.0 * moment);
    let hinged = |k: usize| {
        let d = Vector2::new(s.j[(k + 1, 0)], s.j[(k + 1, 1)]);
        k8 * d.norm() * beta[k + 1].norm()
    };
    let slide_coef = match slide {
        Slide::Outer { .. } => k8 * lambda * beta[0].norm(),
        Slide::Inner { a1, .. } => lambda * (k8 * (a1 - s.c).norm() + 1.0 / (3.0 * moment).sqrt()),
    };
    let (h2, h3) = (hinged(0), hinged(1));
    let curv = 0.5 + (slide_coef * slide_coef + h2 * h2 + h3 * h3).sqrt();
    if !certifies(&s, curv, moved2) {
        return None;
    }
    let (c, z) = (s.c + Vector2::new(s.step.x, s.step.y), turn(s.z, s.step.z));
    let (rho, d, _, j) = closures.rows(c, z);
    let (j_inv, det_j) = inverse3(&j);
    let b = each3(|i| origin + c + rho[i]);
    Some(Fast {
        j_inv,
        det_j,
        slide,
        lambda,
        b,
        z,
        rho,
        d,
    })
}

impl Fast {
    /// det K / L_T: det J′ = ±λ·l_2·l_3·det K (the inner slide's row is −λ times K's).
    #[inline(always)]
    fn det(&self, dims: &SliderTriadDims) -> f64 {
        let sign = match self.slide {
            Slide::Outer { .. } => 1.0,
            Slide::Inner { .. } => -1.0,
        };
        sign * self.det_j / (self.lambda * dims.l[0] * dims.l[1] * dims.triangle().ternary_size())
    }

    /// The pose reached (`a` = [A2, A3]).
    pub(super) fn pose(&self, a: &[Point2<f64>; 2], dims: &SliderTriadDims) -> TriadPose {
        let b = self.b;
        let (t, _) = guide_at(self.slide, self.z);
        let angle = |v: Vector2<f64>| direction_of(v.x, v.y);
        TriadPose {
            b,
            theta: angle(self.z),
            phi: [angle(t), angle(b[1] - a[0]), angle(b[2] - a[1])],
            det: self.det(dims),
        }
    }

    /// The velocities and accelerations (module docs), `None` wherever
    /// [`slider_triad_rates`](super::slider_triad_rates) could fail (or a rate is not
    /// finite) and near its branch-point threshold.
    #[inline(always)]
    pub(super) fn state(
        &self,
        first: &Guide,
        a: &[PointMotion; 2],
        dims: &SliderTriadDims,
    ) -> Option<TriadState> {
        let (j_inv, lambda) = (&self.j_inv, self.lambda);
        let (rho, d) = (&self.rho, &self.d);
        let (t, n) = guide_at(self.slide, self.z);
        let o = self.b[0];
        let (wk, ek) = (first.angle.rate, first.angle.accel);
        // The slide row's right sides, before the terms in the ternary link's own motion.
        let (v1, sign) = match self.slide {
            Slide::Outer { .. } => {
                let q = o - first.point.p;
                let vk = first.point.v + wk * perp(q);
                (lambda * n.dot(&vk), lambda)
            }
            Slide::Inner { .. } => (-lambda * n.dot(&first.point.v), -lambda),
        };
        let vel = j_inv * Vector3::new(v1, d[0].dot(&a[0].v), d[1].dot(&a[1].v));
        let (vc, omega_t) = (Vector2::new(vel.x, vel.y), vel.z);
        let vb = each3(|i| vc + omega_t * perp(rho[i]));
        let dv = each2(|k| vb[k + 1] - a[k].v);
        let w2 = omega_t * omega_t;
        let a1 = match self.slide {
            Slide::Outer { .. } => {
                let q = o - first.point.p;
                let vk = first.point.v + wk * perp(q);
                let ak = first.point.a + ek * perp(q) - wk * wk * q;
                n.dot(&ak) + 2.0 * wk * t.dot(&(vb[0] - vk)) + w2 * n.dot(&rho[0])
            }
            Slide::Inner { .. } => {
                let q = first.point.p - o;
                let s_dot = t.dot(&(first.point.v - vb[0] - omega_t * perp(q)));
                n.dot(&first.point.a) - 2.0 * omega_t * s_dot + w2 * n.dot(&(q + rho[0]))
            }
        };
        let rhs = |k: usize| d[k].dot(&(a[k].a + w2 * rho[k + 1])) - dv[k].norm_squared();
        let acc = j_inv * Vector3::new(sign * a1, rhs(0), rhs(1));
        let (ac, eps_t) = (Vector2::new(acc.x, acc.y), acc.z);
        let ab = each3(|i| ac + eps_t * perp(rho[i]) - w2 * rho[i]);
        let il2 = [1.0 / (dims.l[0] * dims.l[0]), 1.0 / (dims.l[1] * dims.l[1])];
        let omega = each2(|k| cross(d[k], dv[k]) * il2[k]);
        let eps = each2(|k| cross(d[k], ab[k + 1] - a[k].a) * il2[k]);
        let det = self.det(dims);
        // The branch-point test on K with B1 as the reference point (module
        // `triad_slider`): rows (w, (p − B1) × w).
        let b1 = o;
        let (p, kind) = match self.slide {
            Slide::Outer { .. } => (b1, Leg::FixedLine),
            Slide::Inner { .. } => (first.point.p, Leg::TurningLine),
        };
        let legs = Legs {
            w: [n, d[0] / dims.l[0], d[1] / dims.l[1]],
            r: [p - b1, rho[1] - rho[0], rho[2] - rho[0]],
            kind: [kind, Leg::Hinged(dims.l[0]), Leg::Hinged(dims.l[1])],
            lt: dims.triangle().ternary_size(),
        };
        let ok = super::rrr::all_finite([
            vel.x, vel.y, vel.z, acc.x, acc.y, acc.z, omega[0], omega[1], eps[0], eps[1], det,
        ]) && legs.surely_regular(&legs.matrix(), det);
        if !ok {
            return None;
        }
        let b = self.b;
        let bm = each3(|i| PointMotion::new(b[i], vb[i], ab[i]));
        let sliding = match self.slide {
            Slide::Outer { .. } => LinkMotion {
                origin: bm[0],
                angle: first.angle.value,
                omega: wk,
                epsilon: ek,
            },
            Slide::Inner { .. } => LinkMotion {
                origin: first.point,
                angle: direction_of(t.x, t.y),
                omega: omega_t,
                epsilon: eps_t,
            },
        };
        let hinged = |k: usize| {
            let v = b[k + 1] - a[k].p;
            LinkMotion {
                origin: a[k],
                angle: direction_of(v.x, v.y),
                omega: omega[k],
                epsilon: eps[k],
            }
        };
        Some(TriadState {
            b: bm,
            ternary: LinkMotion {
                origin: bm[0],
                angle: direction_of(self.z.x, self.z.y),
                omega: omega_t,
                epsilon: eps_t,
            },
            binary: [sliding, hinged(0), hinged(1)],
            det,
        })
    }
}
