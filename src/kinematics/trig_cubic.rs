//! The eliminated equation shared by the groups of the 3rd class, F(θ) = |W(θ)|² − l²·D(θ)²,
//! as a real trigonometric polynomial of degree 3 in the ternary link's angle θ (z = e^{iθ}).
//!
//! Both the [`triad`](mod@super::triad) and the triad with a sliding pair
//! ([`triad_slider`](mod@super::triad_slider)) reduce to it: two of the legs' equations are
//! linear in the ternary link's reference point O once θ is fixed (the radical axes of two
//! circles, or a radical axis and the sliding leg's line), so D·O = i·W (complex notation)
//! with D their determinant, a real trigonometric polynomial of degree 1
//! (D = e0 + 2·Re(e1·z)), and W a Laurent polynomial in z of degrees −1…2; the remaining
//! circle |O − c| = l then reads |W − D·c|² = l²·D², which is F once W absorbs D·c.
//! |W|² = Σ_{j,k} w_j·conj(w_k)·z^{j−k} has degree 3 and D² degree 2, so F has at most six
//! real roots: the group's assembly modes.

use super::trig_roots::Periodic;
use nalgebra::Complex;

type C = Complex<f64>;

/// F = F_0 + 2·Re(Σ_{k=1..3} F_k·z^k) with the bounds its scan and its certificates need.
#[derive(Debug, Clone, Copy)]
pub(super) struct Cubic {
    /// F's Fourier coefficients F_0 (real) … F_3.
    pub f: [C; 4],
    /// M₂ = 2·Σ k²|F_k|, a bound of |F″|.
    pub m2: f64,
    /// Σ|F_k| with F_0 once and the others twice: a bound of |F|.
    pub s: f64,
    /// The rounding level of an evaluation of F.
    pub tol: f64,
}

impl Cubic {
    /// F = |W|² − `l2`·D² from W's Laurent coefficients `w` (of z^−1, z^0, z^1, z^2) and
    /// D = `e0` + 2·Re(`e1`·z); `scale` is the size of the terms that make F (its rounding
    /// level is 64·ε·scale).
    pub fn new(w: &[C; 4], e0: f64, e1: C, l2: f64, scale: f64) -> Self {
        // |W|²_k = Σ_j w_j·conj(w_{j−k}); (D²)_k from e_{−1} = conj(e1), e_0, e_1.
        let wc = [w[0].conj(), w[1].conj(), w[2].conj(), w[3].conj()];
        let ww = [
            C::new(
                w[0].norm_sqr() + w[1].norm_sqr() + w[2].norm_sqr() + w[3].norm_sqr(),
                0.0,
            ),
            w[1] * wc[0] + w[2] * wc[1] + w[3] * wc[2],
            w[2] * wc[0] + w[3] * wc[1],
            w[3] * wc[0],
        ];
        let dd = [
            C::new(e0 * e0 + 2.0 * e1.norm_sqr(), 0.0),
            2.0 * e0 * e1,
            e1 * e1,
            C::new(0.0, 0.0),
        ];
        let f = [0, 1, 2, 3].map(|k| ww[k] - l2 * dd[k]);
        let f = [C::new(f[0].re, 0.0), f[1], f[2], f[3]];
        // Bounds need no square root: |c| ≤ |Re c| + |Im c|.
        let (g1, g2, g3) = (n1(f[1]), n1(f[2]), n1(f[3]));
        Self {
            f,
            m2: 2.0 * (g1 + 4.0 * g2 + 9.0 * g3),
            s: f[0].re.abs() + 2.0 * (g1 + g2 + g3),
            tol: 64.0 * f64::EPSILON * scale,
        }
    }

    /// F and F′ = dF/dθ at z = e^{iθ}.
    #[inline]
    pub fn eval(&self, z: C) -> (f64, f64) {
        let f = &self.f;
        let z2 = z * z;
        let z3 = z2 * z;
        let (p1, p2, p3) = (f[1] * z, f[2] * z2, f[3] * z3);
        let p = p1 + p2 + p3;
        let dp = p1 + 2.0 * p2 + 3.0 * p3;
        (f[0].re + 2.0 * p.re, -2.0 * dp.im)
    }

    /// F″ at z.
    pub fn second(&self, z: C) -> f64 {
        let f = &self.f;
        let z2 = z * z;
        let p = f[1] * z + 4.0 * f[2] * z2 + 9.0 * f[3] * z2 * z;
        -2.0 * p.re
    }
}

/// |Re c| + |Im c| ≥ |c|.
#[inline]
pub(super) fn n1(c: C) -> f64 {
    c.re.abs() + c.im.abs()
}

impl Periodic for Cubic {
    #[inline]
    fn eval(&self, z: C) -> (f64, f64) {
        Cubic::eval(self, z)
    }
    fn second(&self, z: C) -> f64 {
        Cubic::second(self, z)
    }
    fn m2(&self) -> f64 {
        self.m2
    }
    fn tol(&self) -> f64 {
        self.tol
    }
}
