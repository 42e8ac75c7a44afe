//! A deterministic generator of hostile numbers and inputs, shared by the adversarial tests,
//! and the check for a NaN or an infinity in a result's `Debug` rendering.
#![allow(dead_code)]

use nalgebra::{Point2, Vector2};
use tmm::kinematics::{Branch, Motion, PointMotion};
use tmm::Load;

/// The number of generated cases per sweep: `TMM_HOSTILE_CASES` (default 200).
pub fn cases() -> usize {
    std::env::var("TMM_HOSTILE_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200)
}

/// A small deterministic generator (xorshift64*), so that a failure can be replayed.
pub struct Gen(pub u64);

pub const SPECIAL: [f64; 24] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    f64::MIN_POSITIVE,
    1e-300,
    -1e-300,
    1e-16,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    1e155,
    -1e155,
    1e160,
    1.0,
    -1.0,
    0.5,
    2.0,
    0.1,
    std::f64::consts::PI,
];

impl Gen {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A hostile number: a special value, an ordinary one, or a random magnitude.
    pub fn f(&mut self) -> f64 {
        match self.next() % 4 {
            0 => SPECIAL[(self.next() % SPECIAL.len() as u64) as usize],
            1 => 2.0 * self.unit() - 1.0,
            2 => (self.unit() - 0.5) * 10f64.powi((self.next() % 600) as i32 - 300),
            _ => self.unit() * 0.5 + 0.05,
        }
    }
    /// A mostly ordinary positive length, sometimes hostile.
    pub fn len(&mut self) -> f64 {
        if self.next().is_multiple_of(3) {
            self.f()
        } else {
            0.05 + self.unit()
        }
    }
    pub fn v(&mut self) -> Vector2<f64> {
        Vector2::new(self.f(), self.f())
    }
    pub fn p(&mut self) -> Point2<f64> {
        Point2::from(self.v())
    }
    pub fn pm(&mut self) -> PointMotion {
        PointMotion::new(self.p(), self.v(), self.v())
    }
    pub fn motion(&mut self) -> Motion {
        Motion::new(self.f(), self.f(), self.f())
    }
    pub fn load(&mut self) -> Load {
        Load::new(self.p(), self.v(), self.f())
    }
    pub fn branch(&mut self) -> Branch {
        if self.next().is_multiple_of(2) {
            Branch::Plus
        } else {
            Branch::Minus
        }
    }
}

/// `true` when a `Debug` rendering holds a NaN or an infinity.
pub fn has_non_finite(s: &str) -> bool {
    s.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .any(|t| t == "NaN" || t == "inf")
}

/// A result that is `Ok` holds only finite numbers (its `Debug` rendering scanned for `NaN`
/// and `inf`); an error renders its message. The success check of every hostile call whose
/// value is not otherwise looked at.
pub fn ok_finite<T: std::fmt::Debug>(r: &tmm::Result<T>, what: &str) {
    match r {
        Ok(v) => {
            let s = format!("{v:?}");
            assert!(!has_non_finite(&s), "{what}: an Ok holds {s}");
        }
        Err(e) => assert!(!e.to_string().is_empty(), "{what}: an empty message"),
    }
}
