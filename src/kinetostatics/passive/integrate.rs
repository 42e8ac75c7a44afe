//! Multiplication of diagrams: the integral ∫ f·g ds over a straight piece on which one
//! diagram is linear and the other at most quadratic.
//!
//! This is how the seed computes its displacements δ11 and Δ1F (eq. 4): Vereshchagin's rule
//! (the area of one diagram times the ordinate of the other, linear, diagram under the
//! first one's centroid) and Simpson's formula. Simpson's formula
//! ∫ f·g ds = L/6·(f_a·g_a + 4·f_m·g_m + f_b·g_b) is exact for a product of degree ≤ 3, so it
//! is exact for the linear × linear and linear × quadratic products of the force method, and
//! needs no centroid tables.

/// Simpson's formula for the product of two diagrams over a straight piece of length `len`:
/// `f` and `g` hold each diagram's values at the start, the middle and the end of the piece.
///
/// Exact when the product is a polynomial of degree ≤ 3 in the arc length (one diagram
/// linear, the other at most quadratic).
///
/// # Examples
/// A triangle (0 → 6 N·m over 3 m) times a linear diagram (2 → 5): Vereshchagin's rule gives
/// the triangle's area 9 times the ordinate of the second diagram under the triangle's
/// centroid (at 2/3 of the length, 2 + 3·2/3 = 4), that is 36.
/// ```
/// use tmm::kinetostatics::passive::simpson_product;
/// let v = simpson_product(3.0, [0.0, 3.0, 6.0], [2.0, 3.5, 5.0]);
/// assert!((v - 9.0 * 4.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn simpson_product(len: f64, f: [f64; 3], g: [f64; 3]) -> f64 {
    len / 6.0 * (f[0] * g[0] + 4.0 * f[1] * g[1] + f[2] * g[2])
}
