//! The bench four-bar and its hand kernel, shared by `kinematics.rs` and `batch.rs`: crank
//! O = (0, 0), l_OA = 0.1 m; frame pivot C = (0.4, 0.05) m; coupler l_AB = 0.35 m, rocker
//! l_CB = 0.3 m (`benches/pylinkage_numba/` times pylinkage on the same one).

use nalgebra::{Point2, Vector2};

/// l_OA, m.
pub const L1: f64 = 0.1;
/// l_AB, m.
pub const L2: f64 = 0.35;
/// l_CB, m.
pub const L3: f64 = 0.3;
/// The rocker's frame pivot C, m.
pub const C: Point2<f64> = Point2::new(0.4, 0.05);

/// Input angles from a fixed-seed linear congruential generator (reproducible, no deps).
pub fn seeded_angles(n: usize) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU
        })
        .collect()
}

/// The four-bar by hand, a straight Cartesian closed form with no validation: B, v_B, a_B
/// and (φ2, ω2, ε2), (φ3, ω3, ε3) at the crank angle `phi` turning at ω = `omega`, ε =
/// `epsilon`.
#[inline]
pub fn four_bar_by_hand(phi: f64, omega: f64, epsilon: f64) -> [f64; 12] {
    let perp = |v: Vector2<f64>| Vector2::new(-v.y, v.x);
    let (s, c) = phi.sin_cos();
    let r1 = L1 * Vector2::new(c, s);
    let (va, aa) = (omega * perp(r1), epsilon * perp(r1) - omega * omega * r1);
    let d = C.coords - r1;
    let l_sq = d.norm_squared();
    let l = l_sq.sqrt();
    let x = (l_sq + L2 * L2 - L3 * L3) / (2.0 * l);
    let h = (L2 * L2 - x * x).sqrt();
    let r2 = (x * d + h * perp(d)) / l;
    let r3 = r2 - d;
    let dd = r2.x * r3.y - r2.y * r3.x;
    let (w2, w3) = (-va.dot(&r3) / dd, -va.dot(&r2) / dd);
    let rhs = -aa + w2 * w2 * r2 - w3 * w3 * r3;
    let (e2, e3) = (rhs.dot(&r3) / dd, rhs.dot(&r2) / dd);
    let angle = |v: Vector2<f64>| {
        let t = v.y.atan2(v.x);
        if t < 0.0 {
            t + std::f64::consts::TAU
        } else {
            t
        }
    };
    let b = r1 + r2;
    let vb = va + w2 * perp(r2);
    let ab = aa + e2 * perp(r2) - w2 * w2 * r2;
    [
        b.x,
        b.y,
        vb.x,
        vb.y,
        ab.x,
        ab.y,
        angle(r2),
        w2,
        e2,
        angle(r3),
        w3,
        e3,
    ]
}

/// Every one of the hand kernel's twelve numbers, folded into one, so that a timed loop
/// consumes all of them (the compiler cannot drop an `atan2` nobody reads).
#[inline]
pub fn fold(r: [f64; 12]) -> f64 {
    r.iter().sum()
}
