//! The revolute triad's fast path: its three closures g_i = ½(|B_i − A_i|² − l_i²) solved by
//! Newton's method in the ternary link's centroid and angle from the previous pose, the
//! certificate that the mode reached is the full scan's nearest
//! ([`triad_newton`](super::triad_newton) derives both), and the rates from the same
//! Jacobian.
//!
//! # The Jacobian is the velocity system
//! With ρ_i = R(θ)·β̄_i and d_i = B_i − A_i, ∂g_i/∂c = d_i and ∂g_i/∂θ = d_i·ρ_i⊥ = ρ_i × d_i:
//! row i of J is d_i·[1, ρ_i⊥], the velocity system K of the module [`triad`](super::triad)
//! with its row scaled by l_i and its reference point moved from B1 to the centroid (a column
//! operation: det J = l_1·l_2·l_3·det K). Differentiating the closures in time (|d_i| = l_i
//! held):
//! - d_i·(v_c + ω·ρ_i⊥) = d_i·v_Ai, so J·(v_c, ω) = (d_i·v_Ai);
//! - d_i·(a_c + ε·ρ_i⊥ − ω²ρ_i − a_Ai) + |ḋ_i|² = 0, so
//!   J·(a_c, ε) = (d_i·(a_Ai + ω²ρ_i) − |ḋ_i|²) with ḋ_i = v_Bi − v_Ai;
//! - each binary link's ω_i = (d_i × ḋ_i)/l_i² and ε_i = (d_i × d̈_i)/l_i² (d = l·(cos φ, sin φ)
//!   gives d × ḋ = l²φ̇ and d × d̈ = l²φ̈).
//!
//! # The certificate's constant
//! g_i(p + Δ) − g_i(p) − J_i·Δ = d_i·e_i + ½|ΔB_i|² with |e_i| ≤ Δθ²|β̄_i|/2 (module
//! [`triad_newton`](super::triad_newton)); with Δθ² ≤ π²D²/(4I) and ‖(½|ΔB_i|²)‖₂ ≤ ½ΣΔB_i² =
//! ½D², ‖r‖₂ ≤ C·D² for C = ½ + π²/(8I)·‖(|d_i|·|β̄_i|)‖₂.

use super::fast_angle::direction_of;
use super::link::LinkMotion;
use super::motion::PointMotion;
use super::triad::{hinged_legs, TriadDims, TriadPose, TriadState};
use super::triad_newton::{
    certifies, each3, hinged_rounding, inverse3, rotate, solve, turn, Closures, Eval, Rows,
};
use crate::angle::{cross, perp};
use nalgebra::{Matrix3, Point2, Vector2, Vector3};
use std::f64::consts::PI;

/// The revolute triad's closures at one position, the origin at A1.
struct Hinged {
    /// A_i − A_1.
    a: [Vector2<f64>; 3],
    /// β̄_i, the joints about their centroid in the ternary link's frame.
    beta: [Vector2<f64>; 3],
    /// l_i².
    l2: [f64; 3],
    /// The part of g's rounding that does not depend on the pose, and the factor of |c|₁.
    round0: f64,
    round_c: f64,
}

impl Hinged {
    /// ρ_i, d_i, g and J at (c, z).
    #[inline(always)]
    fn rows(&self, c: Vector2<f64>, z: Vector2<f64>) -> Rows<3> {
        let rho = each3(|i| rotate(z, self.beta[i]));
        let d = each3(|i| c + rho[i] - self.a[i]);
        let g = Vector3::new(
            0.5 * (d[0].norm_squared() - self.l2[0]),
            0.5 * (d[1].norm_squared() - self.l2[1]),
            0.5 * (d[2].norm_squared() - self.l2[2]),
        );
        let j = Matrix3::new(
            d[0].x,
            d[0].y,
            cross(rho[0], d[0]),
            d[1].x,
            d[1].y,
            cross(rho[1], d[1]),
            d[2].x,
            d[2].y,
            cross(rho[2], d[2]),
        );
        (rho, d, g, j)
    }
}

impl Closures for Hinged {
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

/// A mode reached and certified by the fast path, origin at A1: the last point of
/// evaluation with its Jacobian (for the rates) and the pose to return.
pub(super) struct Fast {
    /// J′⁻¹ and det J′, J′ the Jacobian at the returned pose.
    j_inv: Matrix3<f64>,
    det_j: f64,
    /// The returned pose: joints and direction (the last point turned by its last step).
    b: [Point2<f64>; 3],
    z: Vector2<f64>,
    /// ρ_i and d_i at the returned pose.
    rho: [Vector2<f64>; 3],
    d: [Vector2<f64>; 3],
}

/// The fast path on valid input: `None` unless the certificate holds.
#[inline(always)]
pub(super) fn track(a: [Point2<f64>; 3], dims: &TriadDims, previous: &TriadPose) -> Option<Fast> {
    let local = dims.local_joints();
    let mean = (local[0] + local[1] + local[2]) / 3.0;
    let beta = each3(|i| local[i] - mean);
    let moment = beta[0].norm_squared() + beta[1].norm_squared() + beta[2].norm_squared();
    let origin = a[0];
    let rel = [Vector2::zeros(), a[1] - origin, a[2] - origin];
    let l = dims.l;
    let n1 = |v: Vector2<f64>| v.x.abs() + v.y.abs();
    let (mut round0, mut round_c) = (0.0, 0.0);
    for i in 0..3 {
        let (r0, rc) = hinged_rounding(l[i], n1(beta[i]), n1(rel[i]));
        round0 += r0;
        round_c += rc;
    }
    let closures = Hinged {
        a: rel,
        beta,
        l2: [l[0] * l[0], l[1] * l[1], l[2] * l[2]],
        round0,
        round_c,
    };
    let p = previous.b;
    let side = p[1] - p[0];
    let z0 = side / side.norm();
    let c0 = (p[0].coords + p[1].coords + p[2].coords) / 3.0 - origin.coords;
    let s = solve(&closures, c0, z0, moment)?;
    let rho_p = each3(|i| rotate(s.z, beta[i]));
    // The certificate at the last point of evaluation p.
    let moved2 = (0..3)
        .map(|i| (origin + s.c + rho_p[i] - p[i]).norm_squared())
        .sum::<f64>();
    let d_p = each3(|i| Vector2::new(s.j[(i, 0)], s.j[(i, 1)]));
    let spread = (0..3)
        .map(|i| d_p[i].norm_squared() * beta[i].norm_squared())
        .sum::<f64>();
    let curv = 0.5 + PI * PI / (8.0 * moment) * spread.sqrt();
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
        b,
        z,
        rho,
        d,
    })
}

impl Fast {
    /// det K / L_T (det J′ = l_1·l_2·l_3·det K).
    #[inline(always)]
    fn det(&self, dims: &TriadDims) -> f64 {
        self.det_j / (dims.l[0] * dims.l[1] * dims.l[2] * dims.ternary_size())
    }

    /// The pose reached.
    pub(super) fn pose(&self, a: &[Point2<f64>; 3], dims: &TriadDims) -> TriadPose {
        let b = self.b;
        TriadPose {
            b,
            theta: direction_of(self.z.x, self.z.y),
            phi: each3(|i| {
                let v = b[i] - a[i];
                direction_of(v.x, v.y)
            }),
            det: self.det(dims),
        }
    }

    /// The velocities and accelerations (module docs), `None` wherever
    /// [`triad_rates`](super::triad_rates) could fail (or a rate is not finite) and near its
    /// branch-point threshold.
    #[inline(always)]
    pub(super) fn state(&self, a: &[PointMotion; 3], dims: &TriadDims) -> Option<TriadState> {
        let (rho, d, j_inv) = (&self.rho, &self.d, &self.j_inv);
        let il2 = [
            1.0 / (dims.l[0] * dims.l[0]),
            1.0 / (dims.l[1] * dims.l[1]),
            1.0 / (dims.l[2] * dims.l[2]),
        ];
        let vel = j_inv * Vector3::new(d[0].dot(&a[0].v), d[1].dot(&a[1].v), d[2].dot(&a[2].v));
        let (vc, omega_t) = (Vector2::new(vel.x, vel.y), vel.z);
        let vb = each3(|i| vc + omega_t * perp(rho[i]));
        let dv = each3(|i| vb[i] - a[i].v);
        let w2 = omega_t * omega_t;
        let rhs = |i: usize| d[i].dot(&(a[i].a + w2 * rho[i])) - dv[i].norm_squared();
        let acc = j_inv * Vector3::new(rhs(0), rhs(1), rhs(2));
        let (ac, eps_t) = (Vector2::new(acc.x, acc.y), acc.z);
        let ab = each3(|i| ac + eps_t * perp(rho[i]) - w2 * rho[i]);
        let omega = each3(|i| cross(d[i], dv[i]) * il2[i]);
        let eps = each3(|i| cross(d[i], ab[i] - a[i].a) * il2[i]);
        let det = self.det(dims);
        // The branch-point test of the rates on K (rows (u_i, r_i × u_i) with r_i = B_i − B1)
        // made from J: u_i = d_i/l_i and r_i × d_i = ρ_i × d_i − ρ_1 × d_i.
        let u = each3(|i| d[i] / dims.l[i]);
        let r = each3(|i| rho[i] - rho[0]);
        let k = Matrix3::new(
            u[0].x,
            u[0].y,
            cross(r[0], u[0]),
            u[1].x,
            u[1].y,
            cross(r[1], u[1]),
            u[2].x,
            u[2].y,
            cross(r[2], u[2]),
        );
        let arms = [
            0.0,
            dims.l_b1b2,
            (dims.b3_along * dims.b3_along + dims.b3_across * dims.b3_across).sqrt(),
        ];
        // The inputs' rates need no test of their own: J⁻¹ has no zero column, so a
        // non-finite component of a velocity or an acceleration of A_i makes the solved
        // vector non-finite (and ω_i, ε_i, which read it directly).
        let ok = super::rrr::all_finite([
            vel.x, vel.y, vel.z, acc.x, acc.y, acc.z, omega[0], omega[1], omega[2], eps[0], eps[1],
            eps[2], det,
        ]) && hinged_legs(u, r, dims.l, dims.ternary_size())
            .surely_regular_arms(&k, det, arms);
        if !ok {
            return None;
        }
        let b = self.b;
        let binary = |i: usize| {
            let v = b[i] - a[i].p;
            LinkMotion {
                origin: a[i],
                angle: direction_of(v.x, v.y),
                omega: omega[i],
                epsilon: eps[i],
            }
        };
        Some(TriadState {
            b: [
                PointMotion::new(b[0], vb[0], ab[0]),
                PointMotion::new(b[1], vb[1], ab[1]),
                PointMotion::new(b[2], vb[2], ab[2]),
            ],
            ternary: LinkMotion {
                origin: PointMotion::new(b[0], vb[0], ab[0]),
                angle: direction_of(self.z.x, self.z.y),
                omega: omega_t,
                epsilon: eps_t,
            },
            binary: [binary(0), binary(1), binary(2)],
            det,
        })
    }
}
