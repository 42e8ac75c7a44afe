//! `src/kinetostatics/passive/integrate.rs`: Simpson's rule for a product of parabolas.

use approx::assert_relative_eq;
use tmm::kinetostatics::passive::simpson_product;

/// Gauss–Legendre with 3 points: exact to degree 5, an independent rule.
fn gauss3(len: f64, h: impl Fn(f64) -> f64) -> f64 {
    let x = (0.6f64).sqrt();
    let w = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let p = [-x, 0.0, x];
    0.5 * len
        * p.iter()
            .zip(w)
            .map(|(p, w)| w * h(0.5 * len * (1.0 + p)))
            .sum::<f64>()
}

#[test]
fn exact_for_linear_times_quadratic() {
    let len = 1.7;
    let f = |s: f64| 2.0 - 3.0 * s;
    let g = |s: f64| -1.0 + 0.5 * s + 4.0 * s * s;
    let v = simpson_product(
        len,
        [f(0.0), f(0.5 * len), f(len)],
        [g(0.0), g(0.5 * len), g(len)],
    );
    assert_relative_eq!(v, gauss3(len, |s| f(s) * g(s)), max_relative = 1e-14);
}

#[test]
fn not_exact_for_quadratic_times_quadratic() {
    // Degree 4: the rule's error is −L⁵/2880·(fg)'''' ≠ 0, which shows the test can fail.
    let len = 1.0;
    let f = |s: f64| s * s;
    let v = simpson_product(len, [0.0, 0.25, 1.0], [0.0, 0.25, 1.0]);
    let exact = gauss3(len, |s| f(s) * f(s));
    assert_relative_eq!(exact, 0.2, max_relative = 1e-14);
    assert_relative_eq!(v - exact, 1.0 / 120.0, max_relative = 1e-12);
}
