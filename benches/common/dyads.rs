//! The seeded dyads shared by `kinetostatics.rs` and `friction.rs`: a small generator
//! (xorshift64*, so every run benches the same inputs), random loads, and the RRR dyad's
//! joints in three separated boxes (A left, B above, C right: a well-conditioned dyad).

use nalgebra::{Point2, Vector2};
use tmm::kinetostatics::RrrDyad;
use tmm::Load;

/// A small seeded generator (xorshift64*).
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A point in the square [−1, 1]².
    pub fn point(&mut self) -> Point2<f64> {
        Point2::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0))
    }
    /// A load: a force up to 500 N a component at a random point, a couple up to 50 N·m.
    pub fn load(&mut self) -> Load {
        Load::new(
            self.point(),
            Vector2::new(self.range(-500.0, 500.0), self.range(-500.0, 500.0)),
            self.range(-50.0, 50.0),
        )
    }
    /// The dyad's first outer joint, left.
    pub fn a(&mut self) -> Point2<f64> {
        Point2::new(self.range(-1.0, -0.5), self.range(-0.2, 0.2))
    }
    /// The dyad's inner joint, above.
    pub fn b(&mut self) -> Point2<f64> {
        Point2::new(self.range(-0.2, 0.2), self.range(0.5, 1.0))
    }
    /// The dyad's second outer joint, right.
    pub fn c(&mut self) -> Point2<f64> {
        Point2::new(self.range(0.5, 1.0), self.range(-0.2, 0.2))
    }
    /// An RRR dyad with random loads.
    pub fn rrr_dyad(&mut self) -> RrrDyad {
        RrrDyad {
            a: self.a(),
            b: self.b(),
            c: self.c(),
            load2: self.load(),
            load3: self.load(),
        }
    }
}
