//! The branch point itself: the pose of a group of the 3rd class where its velocity system K
//! is singular, found from a mode that lies within rounding of it.
//!
//! # Why a mode at a branch point is not good enough
//! Where two assembly modes merge, the data (the known joints) lie on the branch set, but
//! only to their rounding: η ≈ ε of the size off it ([`SINGULAR_BRANCH`](super::SINGULAR_BRANCH)).
//! On one side the two modes are then ≈ √η·s apart, on the other there is none, and the
//! scan's double root (F's extremum) or a polished root lands anywhere within ≈ √ε of the
//! size of the branch pose (1e-7 of the size seen over seeded groups). The branch pose
//! itself is well conditioned: it is a regular solution of the *fold's* equations (below),
//! and the data's rounding moves it by ≈ ε·s only.
//!
//! # The fold's equations, by Newton's method
//! In x = (O, L_T·θ) the closures G(x) have K′ = K·diag(1, 1, 1/L_T) as their Jacobian. With
//! its singular value decomposition K′ = Σ σ_i·m_i·n_iᵀ and σ_j the least, the branch pose
//! is where
//! - the closures vanish across the fold: m_i·G = 0 for i ≠ j (the two well-conditioned
//!   directions), and
//! - the fold's own direction is singular: σ_j = 0, while m_j·G is left at the data's
//!   distance from the branch set (η·s, which no pose can remove).
//!
//! Along n_j the closures follow the fold's normal form ([`fold`](super::fold)):
//! m_j·G(x + t·n_j) ≈ m_j·G + σ_j·t + q·t²/2 with q = m_j·G″(n_j, n_j), so σ_j (the slope
//! of m_j·G along n_j) vanishes at t = −σ_j/q: Newton's step for σ_j = 0. Across the fold,
//! Newton's step for m_i·G = 0 is −(m_i·G)/σ_i along n_i. Both together are one Newton
//! step of the fold's equations, which converge quadratically where q ≠ 0 (a simple fold).
//! A degenerate fold (q ≈ 0: more than two modes meeting, a cusp) sends the step away; then
//! the mode is kept as it was.

use super::fold::Legs;
use super::trig_roots::{unit as unit_c, CLOSES};
use nalgebra::{Complex, Matrix3, Vector2, Vector3};

type C = Complex<f64>;

/// The most Newton steps of the fold's equations. From a mode √ε·s off the branch pose
/// the quadratic convergence needs about four; the rest guard a slow start.
const MAX_STEPS: usize = 24;

/// The branch pose nearest the pose (O = `o`, direction `z`) of a group whose closures and
/// legs at any (O, z) `closures` gives, and whose largest dimension is `length`: the
/// origin, direction and velocity system there. `None` when the steps leave the group (a
/// step longer than a tenth of its size: a degenerate fold), do not settle at rounding, or
/// end at a pose that does not close to [`CLOSES`] of the size.
pub(super) fn fold_point(
    closures: impl Fn(Vector2<f64>, C) -> (Vector3<f64>, Legs),
    o: Vector2<f64>,
    z: C,
    length: f64,
) -> Option<(Vector2<f64>, C, Matrix3<f64>)> {
    let (mut o, mut z) = (o, z);
    // A step of a few roundings of the size is the rounding floor of the closures.
    let settled = 16.0 * f64::EPSILON * length;
    let mut last = f64::INFINITY;
    for _ in 0..MAX_STEPS {
        let (g, legs) = closures(o, z);
        let (d_o, d_theta) = newton_step(&legs, &g)?;
        let size = d_o.norm() + legs.lt * d_theta.abs();
        if size.is_nan() || size > 0.1 * length {
            return None;
        }
        o += d_o;
        z = unit_c(z * C::new(1.0, d_theta));
        last = size;
        if size <= settled {
            break;
        }
    }
    let (g, legs) = closures(o, z);
    // Quadratic convergence reaches the floor well within the steps; a last step above
    // 1e-12 of the size means the steps did not settle (a fold too flat to locate).
    let settled_and_closed = last <= 1e-12 * length && g.amax() <= CLOSES * length;
    if !settled_and_closed {
        return None;
    }
    Some((o, z, legs.matrix()))
}

/// One Newton step of the fold's equations (module docs) at a pose with closures `g` and
/// legs `legs`: (δO, δθ). `None` for a non-finite velocity system.
fn newton_step(legs: &Legs, g: &Vector3<f64>) -> Option<(Vector2<f64>, f64)> {
    let k = legs.matrix();
    let fold = legs.fold(&k)?;
    let lt = legs.lt;
    let scaled = Matrix3::from_fn(|i, j| if j == 2 { k[(i, j)] / lt } else { k[(i, j)] });
    let svd = scaled.svd(true, true);
    let (u, v_t) = (svd.u?, svd.v_t?);
    let s = svd.singular_values;
    let j = (0..3).min_by(|&a, &b| s[a].total_cmp(&s[b]))?;
    // Along the fold: σ_j's root (q = 0 gives an infinite step, refused by the caller).
    let t = -fold.sigma / fold.across();
    let mut d = Vector3::new(t * fold.d_o.x, t * fold.d_o.y, t * fold.d_theta);
    // Across it: the closures' Newton step in the two regular directions.
    for i in (0..3).filter(|&i| i != j) {
        let c = u.column(i).dot(g) / s[i];
        d -= c * Vector3::new(v_t[(i, 0)], v_t[(i, 1)], v_t[(i, 2)] / lt);
    }
    d.iter()
        .all(|x| x.is_finite())
        .then(|| (Vector2::new(d.x, d.y), d.z))
}
