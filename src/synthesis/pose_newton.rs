#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x <= y)` rejects NaN too, on purpose.
//! Burmester's points polished on equations that stay well conditioned when poses nearly
//! coincide, and the accuracy that is then achievable (which decides when two points are one).
//!
//! Conditioning. A dyad (centre point O, circle point A in pose 1) fits pose j when
//! |D_j(A) − O|² = |A − O|². Written against pose 1, g_j = |D_j − O|² − |D_1 − O|² (j = 2..5),
//! two poses i, j a gap γ apart (γ: the distance of their points plus the arc of their turn
//! at the poses' size) give rows g_i, g_j whose difference is O(γ): the 4×4 Jacobian has a
//! singular value of order γ, while each g is evaluated with a rounding error of order εL²
//! (L the size). Newton on them then fixes the point only to εL/γ, and the scan's test of the
//! fifth pose (a miss of order γ·(distance along the curve)) accepts anything within
//! 10⁻⁹/γ of a root. The difference itself need not lose anything: with r_i = D_i − P_i,
//!   D_j − D_i = (P_j − P_i) + (R(θ_j − θ_i) − I)·r_i,
//! where P_j − P_i and θ_j − θ_i are differences of the given numbers (exact when the poses
//! are close, Sterbenz) and R(δ) − I = [[−2 sin²(δ/2), −sin δ], [sin δ, −2 sin²(δ/2)]] has no
//! cancellation. So each pair (i, j) of an edge of a tree spanning the five poses gives the
//! equation h_ij = (D_j − D_i)·(D_i + D_j − 2O)/s_ij = 0 (the difference of squares
//! factored), s_ij the pair's gap: a difference quotient, the pose's derivative when the gap
//! shrinks. Its rows are O(1) and independent at any gap, and evaluated to εL. Taking the
//! tree of least total gap (the minimum spanning tree) puts every near pair on its own edge.
//!
//! Achievable accuracy. The poses are data rounded to ε relative; a pair a gap γ apart has
//! its difference quotient (P_j − P_i)/γ known only to ε/γ relative, so a Burmester point of
//! the poses a four-bar generated is that four-bar's pivot only to about εL/γ (k = 1 in ε/γᵏ);
//! three poses within γ of each other make a second difference, εL/γ². For the given numbers
//! the difference-quotient equations fix each point to about ε·L/σ (σ the smallest singular
//! value of their Jacobian, O(1) unless two Burmester points nearly merge), and that is the
//! tolerance within which two polished points are one.

use super::burmester::{v, Dyad, Pose};
use nalgebra::{Matrix2, Matrix4, Matrix4x3, Vector2, Vector4};

type V = Vector2<f64>;

/// The rotation by `angle`.
fn rotation(angle: f64) -> Matrix2<f64> {
    let (s, c) = angle.sin_cos();
    Matrix2::new(c, -s, s, c)
}

/// R(δ) − I without cancellation: cos δ − 1 = −2 sin²(δ/2).
fn rotation_minus_identity(delta: f64) -> Matrix2<f64> {
    let h = (0.5 * delta).sin();
    let (s, c1) = (delta.sin(), -2.0 * h * h);
    Matrix2::new(c1, -s, s, c1)
}

/// The four difference-quotient equations of five poses: the edges of their minimum
/// spanning tree by gap, each with its scale.
#[derive(Debug, Clone)]
pub(super) struct PoseEquations {
    poses: [Pose; 5],
    /// (i, j, s_ij): the tree's edges and their gaps, m.
    edges: [(usize, usize, f64); 4],
    /// The poses' size (largest distance of a pose's point from the first), m.
    size: f64,
}

impl PoseEquations {
    /// The tree of least total gap over the poses (Prim's algorithm), the gap of two poses
    /// being the distance of their points plus the arc 2|sin(Δθ/2)| at the poses' size (one
    /// turned on the spot is apart too).
    pub(super) fn new(poses: &[Pose; 5]) -> Self {
        let size = poses
            .iter()
            .map(|p| (v(p.at) - v(poses[0].at)).norm())
            .fold(0.0, f64::max);
        // Poses turning on one spot: the arc at the unit radius gives the gaps a scale
        // (only their ratios matter to the tree, and they only scale the rows).
        let radius = if size > 0.0 { size } else { 1.0 };
        let gap = |i: usize, j: usize| {
            let (p, q) = (&poses[i], &poses[j]);
            (v(p.at) - v(q.at)).norm() + radius * (2.0 * (0.5 * (q.angle - p.angle)).sin()).abs()
        };
        let mut inside = [true, false, false, false, false];
        let mut edges = [(0, 0, 0.0); 4];
        for edge in &mut edges {
            let mut best = (0, 0, f64::INFINITY);
            for i in (0..5).filter(|&i| inside[i]) {
                for j in (0..5).filter(|&j| !inside[j]) {
                    let g = gap(i, j);
                    if g < best.2 {
                        best = (i, j, g);
                    }
                }
            }
            inside[best.1] = true;
            *edge = best;
        }
        Self {
            poses: *poses,
            edges,
            size,
        }
    }

    /// The equations as a pencil in the circle point: with u = (A − P1)/L and
    /// G = (O − P1)/L (P1 the first pose's point, L the poses' size, or 1 m for poses turning
    /// on one spot), h·L/s-scaled rows read B(u)·(G, 1)ᵀ = 0 where B(u) = B0 + u_x·Bx + u_y·By
    /// is a 4×3 matrix whose entries are affine in u. Returned: (P1, L, [B0, Bx, By]).
    ///
    /// Derivation: D_i = p_i + R_i·u (p_i = (P_i − P1)/L, R_i the turn from pose 1),
    /// d = D_j − D_i = Δ + E·R_i·u (Δ = (P_j − P_i)/L, E = R(θ_j − θ_i) − I, as in
    /// [`Self::polish`]) and m = D_i + D_j = σ + (R_i + R_j)·u (σ = p_i + p_j). The row is
    /// d·(m − 2G)/s' (s' = s/L); d·m = |D_j|² − |D_i|² has no term in |u|² (E·R_i·u·(R_i + R_j)·u
    /// = |R_j u|² − |R_i u|² = 0), so d·m = Δ·σ + u·((R_i + R_j)ᵀΔ + (E·R_i)ᵀσ): the row is
    /// [−2dᵀ/s', d·m/s'], affine in u, bilinear with G. A dyad is a u where B(u) has rank ≤ 2
    /// (its four perpendicular bisectors meet), G then spanning its null space.
    pub(super) fn pencil(&self) -> (V, f64, [Matrix4x3<f64>; 3]) {
        let first = &self.poses[0];
        let origin = v(first.at);
        let l = if self.size > 0.0 { self.size } else { 1.0 };
        let mut b = [Matrix4x3::zeros(); 3];
        for (row, &(i, j, s)) in self.edges.iter().enumerate() {
            let (pi, pj) = (&self.poses[i], &self.poses[j]);
            let ri_turn = rotation(pi.angle - first.angle);
            let rj_turn = rotation(pj.angle - first.angle);
            let e = rotation_minus_identity(pj.angle - pi.angle) * ri_turn;
            let delta = (v(pj.at) - v(pi.at)) / l;
            let sigma = (v(pi.at) - origin + v(pj.at) - origin) / l;
            let w = (ri_turn + rj_turn).transpose() * delta + e.transpose() * sigma;
            let s = s / l;
            b[0].row_mut(row).copy_from_slice(&[
                -2.0 * delta.x / s,
                -2.0 * delta.y / s,
                delta.dot(&sigma) / s,
            ]);
            for k in 0..2 {
                b[k + 1].row_mut(row).copy_from_slice(&[
                    -2.0 * e[(0, k)] / s,
                    -2.0 * e[(1, k)] / s,
                    w[k] / s,
                ]);
            }
        }
        (origin, l, b)
    }

    /// The residuals h (m) at (O, A), their Jacobian in (O, A) and each row's rounding
    /// scale ((|P_j − P_i| + |E·r_i|)/s·(|D_i| + |D_j| + 2|O|), the magnitudes the product
    /// and the sum d = (P_j − P_i) + E·r_i are formed of).
    fn equations(&self, o: V, a: V) -> (Vector4<f64>, Matrix4<f64>, Vector4<f64>) {
        let first = &self.poses[0];
        let (mut h, mut jac, mut round) = (Vector4::zeros(), Matrix4::zeros(), Vector4::zeros());
        let r1 = a - v(first.at);
        for (row, &(i, j, s)) in self.edges.iter().enumerate() {
            let (pi, pj) = (&self.poses[i], &self.poses[j]);
            let ri_turn = rotation(pi.angle - first.angle);
            let rj_turn = rotation(pj.angle - first.angle);
            let ri = ri_turn * r1;
            let (di, dj) = (v(pi.at) + ri, v(pj.at) + rj_turn * r1);
            let e = rotation_minus_identity(pj.angle - pi.angle);
            let (step, turn) = (v(pj.at) - v(pi.at), e * ri);
            let d = step + turn;
            let m = di + dj - 2.0 * o;
            h[row] = d.dot(&m) / s;
            // ∂d/∂A = E·R_i, ∂m/∂A = R_i + R_j, ∂m/∂O = −2I.
            let ga = ((e * ri_turn).transpose() * m + (ri_turn + rj_turn).transpose() * d) / s;
            let go = -2.0 * d / s;
            jac.row_mut(row).copy_from_slice(&[go.x, go.y, ga.x, ga.y]);
            // d is a sum: its rounding is ε of its terms' sizes, not of its own (the two cancel
            // where the circle point sits at the close pair's pole, moving by far less than
            // the poses).
            round[row] = (step.norm() + turn.norm()) / s * (di.norm() + dj.norm() + 2.0 * o.norm());
        }
        (h, jac, round)
    }

    /// Newton's method on the difference quotients from `dyad`: `Some` with the polished dyad
    /// and its [`Accuracy`], when every residual comes down to rounding (64ε of its row's
    /// magnitudes: a backward error of that size); `None` when it does not (the start was
    /// not near a Burmester point).
    pub(super) fn polish(&self, dyad: Dyad) -> Option<(Dyad, Accuracy)> {
        let (mut o, mut a) = (v(dyad.centre), v(dyad.circle));
        let eps = f64::EPSILON;
        for _ in 0..40 {
            let (h, jac, round) = self.equations(o, a);
            let converged = h
                .iter()
                .zip(round.iter())
                .all(|(r, b)| r.abs() <= 64.0 * eps * b);
            if converged {
                // One more step from where the residuals reached rounding, so that every
                // start ends at the rounding floor, not anywhere within the stopping rule;
                // kept only if it does not raise the residuals (where J is nearly singular
                // the step along its null direction is rounding, and can throw the point
                // off).
                let worst = |h: &Vector4<f64>, round: &Vector4<f64>| {
                    h.iter()
                        .zip(round.iter())
                        .map(|(r, b)| r.abs() / b)
                        .fold(0.0, f64::max)
                };
                if let Some(step) = jac
                    .lu()
                    .solve(&(-h))
                    .filter(|s| s.iter().all(|x| x.is_finite()))
                {
                    let (o2, a2) = (o + V::new(step[0], step[1]), a + V::new(step[2], step[3]));
                    let (h2, _, round2) = self.equations(o2, a2);
                    if worst(&h2, &round2) <= worst(&h, &round) {
                        (o, a) = (o2, a2);
                    }
                }
                let polished = Dyad {
                    centre: [o.x, o.y],
                    circle: [a.x, a.y],
                };
                let accuracy = self.accuracy(o, a)?;
                return Some((polished, accuracy));
            }
            let step = jac.lu().solve(&(-h))?;
            if !step.iter().all(|x| x.is_finite()) {
                return None;
            }
            o += V::new(step[0], step[1]);
            a += V::new(step[2], step[3]);
        }
        None
    }

    /// How far a polished point (O, A) can be from the exact root of the equations as
    /// evaluated in floating point (derivation): each row h = d·m/s is formed from
    /// d = (P_j − P_i) + E·r_i (a sum of rotated vectors: a few roundings, each at most ε of
    /// the terms' sizes) and m = D_i + D_j − 2O (three additions after the rotations), then a
    /// dot product and a division: its evaluation error is at most about
    /// 8ε·(|P_j − P_i| + |E·r_i|)/s·(|D_i| + |D_j| + 2|O|) = 8ε·ρ_r (ρ_r the row's rounding
    /// scale, as in the stopping rule). At the polished point x the computed residual is h,
    /// so the exact residual is within |h_r| + 8ερ_r of zero in each row, and to first order
    /// the root x* is x − J⁻¹(h + δh): each of O's and A's two coordinates within
    /// Σ_r ‖(J⁻¹)_{·,r}‖·(|h_r| + 8ερ_r) (the column r of J⁻¹ restricted to O's or A's rows),
    /// plus the rounding of the coordinates themselves (ε|O|, ε|A|). The sum over rows (not
    /// the largest ρ over the smallest singular value of J) keeps each row's own scale: a far
    /// circle point's rows are large only where its long vectors enter. `None` when J is
    /// singular (the start reached a double point: not a point to keep).
    fn accuracy(&self, o: V, a: V) -> Option<Accuracy> {
        let (h, jac, round) = self.equations(o, a);
        let inverse = jac.try_inverse()?;
        let eps = f64::EPSILON;
        let (mut centre, mut circle) = (0.0, 0.0);
        for r in 0..4 {
            let column = inverse.column(r);
            let row = h[r].abs() + 8.0 * eps * round[r];
            centre += column.rows(0, 2).norm() * row;
            circle += column.rows(2, 2).norm() * row;
        }
        // The first-order bound needs J⁻¹ to mean something: J's entries are formed with a
        // few roundings each, so its computed smallest singular value is uncertain by about
        // ε‖J‖ times a few; where σ_min/σ_max is within 2¹⁰ε of zero, J is singular to working
        // precision (a dyad nearly a slider's, two points merging), the residual's valley can
        // run far along the null direction, and no local bound holds: such a point is fixed
        // only to the wide 2¹⁰εM/σ_min (M the rows' largest magnitude; session 12's tolerance:
        // the polishes of one such point were seen 16 m apart at 2·10⁵ m, within it).
        let singular = jac.singular_values();
        let (low, high) = (singular.min(), singular.max());
        let grow = if low > 1024.0 * eps * high {
            1.0
        } else {
            let scale = self.size + (a - o).norm();
            let magnitude = (scale + o.norm() + a.norm()).max(round.amax());
            let wide = 1024.0 * eps * magnitude / low;
            (wide / centre.hypot(circle)).max(1.0)
        };
        let accuracy = Accuracy {
            centre: grow * centre + eps * o.norm(),
            circle: grow * circle + eps * a.norm(),
        };
        (accuracy.centre.is_finite() && accuracy.circle.is_finite()).then_some(accuracy)
    }
}

/// How far a polished Burmester point can be from the exact root of the equations as
/// evaluated (see [`PoseEquations::accuracy`] for the derivation), m: two polishes of one root
/// are within the sum of theirs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Accuracy {
    /// The bound on the centre point's error, m.
    pub(super) centre: f64,
    /// The bound on the circle point's error, m.
    pub(super) circle: f64,
}
