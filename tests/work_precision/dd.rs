//! Double-double arithmetic (about 32 significant digits) and a Gaussian elimination in it:
//! the reference for the kinetostatic errors, more accurate than both f64 solvers it judges.
//!
//! A value is an unevaluated sum hi + lo with |lo| ≤ ½ulp(hi). Sums use Knuth's two-sum and
//! products the exact fused multiply–add, so every operation has a relative error of a few
//! units of 2⁻¹⁰⁴ (Dekker 1971; Hida, Li & Bailey 2001).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// hi + lo, a double-double number.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dd {
    hi: f64,
    lo: f64,
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

impl Dd {
    /// An f64, exactly.
    pub const fn from(v: f64) -> Self {
        Self { hi: v, lo: 0.0 }
    }

    /// The nearest f64.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// |self|.
    pub fn abs(self) -> Self {
        if self.hi < 0.0 {
            -self
        } else {
            self
        }
    }
}

impl Add for Dd {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        Self { hi, lo }
    }
}

impl Neg for Dd {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl Mul for Dd {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p);
        let (hi, lo) = quick_two_sum(p, e + (self.hi * o.lo + self.lo * o.hi));
        Self { hi, lo }
    }
}

impl Div for Dd {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        // Two Newton corrections of the f64 quotient.
        let q1 = self.hi / o.hi;
        let r = self - o * Dd::from(q1);
        let q2 = r.hi / o.hi;
        let r = r - o * Dd::from(q2);
        let q3 = r.hi / o.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Self { hi, lo } + Dd::from(q3)
    }
}

/// Solves m·x = b (n×n, row-major) by Gaussian elimination with partial pivoting, in
/// double-double. `None` when a pivot is exactly zero.
pub fn solve<const N: usize>(mut m: [[Dd; N]; N], mut b: [Dd; N]) -> Option<[Dd; N]> {
    for k in 0..N {
        let p =
            (k..N).max_by(|&i, &j| m[i][k].abs().to_f64().total_cmp(&m[j][k].abs().to_f64()))?;
        if m[p][k].to_f64() == 0.0 {
            return None;
        }
        m.swap(k, p);
        b.swap(k, p);
        let pivot_row = m[k];
        let pivot_b = b[k];
        for (row, bi) in m.iter_mut().zip(b.iter_mut()).skip(k + 1) {
            let f = row[k] / pivot_row[k];
            for (mij, mkj) in row.iter_mut().zip(&pivot_row).skip(k) {
                *mij = *mij - f * *mkj;
            }
            *bi = *bi - f * pivot_b;
        }
    }
    let mut x = [Dd::default(); N];
    for k in (0..N).rev() {
        let mut s = b[k];
        for (mkj, xj) in m[k].iter().zip(&x).skip(k + 1) {
            s = s - *mkj * *xj;
        }
        x[k] = s / m[k][k];
    }
    Some(x)
}
