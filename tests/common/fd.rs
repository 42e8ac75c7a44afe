//! Shared by the tests of the groups (dyads, triads, general groups): a seeded generator,
//! eighth-order central differences, an angle unwrapped near another, the size of a seeded
//! sweep, and the rates of a whole plan against differences of its positions.
#![allow(dead_code)]

use nalgebra::Vector2;
use std::f64::consts::{PI, TAU};
use tmm::kinematics::Motion;
use tmm::linkage::Plan;

/// A seeded generator (SplitMix64), so that every run tests the same groups.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    pub fn vector(&mut self, r: f64) -> Vector2<f64> {
        Vector2::new(self.range(-r, r), self.range(-r, r))
    }
}

/// The number of seeded cases of a sweep: the environment variable `var` (for example
/// `TMM_TRIAD_CASES=10000` in CI, in release), else `default`.
pub fn cases(var: &str, default: usize) -> usize {
    std::env::var(var)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// The first and second derivatives of f at x by eighth-order central differences of step h.
pub fn fd8(f: &dyn Fn(f64) -> f64, x: f64, h: f64) -> (f64, f64) {
    const D1: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
    const D2: [f64; 4] = [8.0 / 5.0, -1.0 / 5.0, 8.0 / 315.0, -1.0 / 560.0];
    let f0 = f(x);
    let (mut d1, mut d2) = (0.0, -205.0 / 72.0 * f0);
    for k in 0..4 {
        let s = (k + 1) as f64 * h;
        let (fp, fm) = (f(x + s), f(x - s));
        d1 += D1[k] * (fp - fm);
        d2 += D2[k] * (fp + fm);
    }
    (d1 / h, d2 / (h * h))
}

/// The first derivative at the middle of nine samples at t = −4h…4h (eighth order).
pub fn fd(samples: &[f64; 9], h: f64) -> f64 {
    const D1: [f64; 9] = [
        1.0 / 280.0,
        -4.0 / 105.0,
        1.0 / 5.0,
        -4.0 / 5.0,
        0.0,
        4.0 / 5.0,
        -1.0 / 5.0,
        4.0 / 105.0,
        -1.0 / 280.0,
    ];
    samples.iter().zip(D1).map(|(s, c)| s * c).sum::<f64>() / h
}

/// [`fd`] of each component of a vector.
pub fn fd2(samples: &[Vector2<f64>; 9], h: f64) -> Vector2<f64> {
    Vector2::new(fd(&samples.map(|v| v.x), h), fd(&samples.map(|v| v.y), h))
}

/// An angle unwrapped to lie within π of `reference`.
pub fn near_angle(angle: f64, reference: f64) -> f64 {
    reference + (angle - reference + PI).rem_euclid(TAU) - PI
}

/// The largest difference, at the inputs `phis`, between a plan's rates (the input turning
/// at ω = `w`, ε = `e`) and eighth-order differences of step `h` of its positions (each a
/// one-shot solve): every joint's velocity and acceleration relative to size·(ω² + |ε|),
/// every link's ω and ε relative to ω² + |ε|.
pub fn plan_rates_vs_differences(plan: &Plan, phis: &[f64], w: f64, e: f64, h: f64) -> f64 {
    let mut worst: f64 = 0.0;
    let scale = w * w + e.abs();
    for &phi in phis {
        let a = plan.kinematics(Motion::new(phi, w, e)).unwrap();
        let pos = |x: f64| plan.kinematics(Motion::fixed(x)).unwrap();
        for j in 0..plan.joint_names().len() {
            for c in 0..2 {
                let f = |x: f64| pos(x).joint(j).unwrap().p[c];
                let (d1, d2) = fd8(&f, phi, h);
                let m = a.joint(j).unwrap();
                worst = worst.max((m.v[c] - d1 * w).abs() / (plan.size() * scale));
                worst = worst.max((m.a[c] - (d2 * w * w + d1 * e)).abs() / (plan.size() * scale));
            }
        }
        for li in 1..plan.link_names().len() {
            let base = a.link(li).unwrap().value;
            let f = |x: f64| {
                let v = pos(x).link(li).unwrap().value - base;
                v - TAU * (v / TAU).round()
            };
            let (d1, d2) = fd8(&f, phi, h);
            let m = a.link(li).unwrap();
            worst = worst.max((m.rate - d1 * w).abs() / scale);
            worst = worst.max((m.accel - (d2 * w * w + d1 * e)).abs() / scale);
        }
    }
    worst
}
