#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Burmester's curves: the centre-point curve of four finitely separated poses, sampled. See
//! [`centre_point_curve`] for the dyad's standard form and the compatibility condition
//! (Burmester's points of five poses are in `burmester_five`).

use super::burmester::{check_poses, Dyad, Pose};
use crate::error::{Error, Result};
use std::f64::consts::TAU;

pub(super) type C = nalgebra::Complex<f64>;

/// The centre-point curve of four poses, sampled: the dyads (centre point, circle point in
/// the first pose) that carry the coupler through all four, for `n` crank rotations β2
/// between the first two poses, evenly spaced over a turn (up to two dyads each).
///
/// Derivation (the dyad's standard form): with W = A − O (the crank, from the centre point O
/// to the circle point A in pose 1), Z = P1 − A and the coupler's rotations α_j = θ_j − θ1,
/// pose j is reached when the crank has turned β_j:
/// W(e^{iβ_j} − 1) + Z(e^{iα_j} − 1) = δ_j = P_j − P1, j = 2, 3, 4.
/// Three complex equations in two complex unknowns are compatible only where the 3×3
/// determinant of [e^{iβ_j} − 1, e^{iα_j} − 1, δ_j] vanishes; expanded along its first column,
/// Δ1 + Δ2·e^{iβ2} + Δ3·e^{iβ3} + Δ4·e^{iβ4} = 0 (Δ2..Δ4 the cofactors, Δ1 = −ΣΔj). For a
/// chosen β2 the vectors Δ3·e^{iβ3} and Δ4·e^{iβ4} close a triangle with −(Δ1 + Δ2·e^{iβ2}):
/// two solutions, or none. Then W and Z solve equations 2 and 3 (Cramer), O = P1 − Z − W and
/// A = P1 − Z. The trivial solution β_j = α_j (the crank turning with the coupler) is left out.
///
/// # Examples
/// ```
/// use tmm::synthesis::{centre_point_curve, Pose};
/// let poses = [
///     Pose::new([0.0, 0.0], 0.0),
///     Pose::new([0.1, 0.05], 0.3),
///     Pose::new([0.2, 0.05], 0.7),
///     Pose::new([0.28, 0.0], 1.0),
/// ];
/// let dyads = centre_point_curve(&poses, 90)?;
/// assert!(!dyads.is_empty());
/// // Every dyad keeps its length through the four poses.
/// for d in &dyads {
///     assert!(d.misfit(&poses) < 1e-9 * (1.0 + d.length()));
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses;
/// [`Error::OutOfRange`] (`"n"`) for n = 0 or n above [`MAX_POINTS`](super::MAX_POINTS).
pub fn centre_point_curve(poses: &[Pose; 4], n: usize) -> Result<Vec<Dyad>> {
    // The runs check the poses and n.
    Ok(burmester_curves(poses, n)?.concat())
}

/// Burmester's curves of four poses as lines to draw: the dyads of [`centre_point_curve`]
/// in runs along one branch of the compatibility triangle, each run without a gap (a run
/// ends where the triangle stops closing, at a fold where the two branches meet, or at a
/// dyad that does not fit). The centre points of a run trace the centre-point curve, their
/// circle points (in the first pose) the circle-point curve.
///
/// # Examples
/// ```
/// use tmm::synthesis::{burmester_curves, centre_point_curve, Pose};
/// let poses = [
///     Pose::new([0.0, 0.0], 0.0),
///     Pose::new([0.1, 0.05], 0.3),
///     Pose::new([0.2, 0.05], 0.7),
///     Pose::new([0.28, 0.0], 1.0),
/// ];
/// let runs = burmester_curves(&poses, 360)?;
/// let all: usize = runs.iter().map(Vec::len).sum();
/// assert_eq!(all, centre_point_curve(&poses, 360)?.len());
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`centre_point_curve`].
pub fn burmester_curves(poses: &[Pose; 4], n: usize) -> Result<Vec<Vec<Dyad>>> {
    check_poses(poses)?;
    if !(1..=super::MAX_POINTS).contains(&n) {
        return Err(Error::OutOfRange {
            name: "n",
            value: n as f64,
            min: 1.0,
            max: super::MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    let compat = Compatibility::new(poses);
    let mut runs: Vec<Vec<Dyad>> = Vec::new();
    for sign in [1.0, -1.0] {
        let first = runs.len();
        let mut run: Vec<Dyad> = Vec::new();
        let (mut at_start, mut at_end) = (false, false);
        for k in 0..n {
            let beta2 = TAU * (k as f64 + 0.5) / n as f64;
            match compat
                .dyad(beta2, sign)
                .filter(|d| d.misfit(poses) <= 1e-9 * (compat.size + d.length()))
            {
                Some(d) => {
                    at_start |= k == 0;
                    at_end = k == n - 1;
                    run.push(d);
                }
                None if !run.is_empty() => runs.push(std::mem::take(&mut run)),
                None => {}
            }
        }
        if !run.is_empty() {
            runs.push(run);
        }
        // A run through β2 = 0 is one line: its end joins its beginning.
        if at_start && at_end && runs.len() > first + 1 {
            let last = runs.pop().unwrap_or_default();
            runs[first].splice(0..0, last);
        }
    }
    Ok(runs)
}

/// Burmester's compatibility of four poses (see [`centre_point_curve`]): the coefficients
/// of the standard form and the determinant's cofactors.
pub(super) struct Compatibility {
    pub(super) p1: C,
    /// The coupler's rotations from pose 1 as e^{iα_j} − 1, j = 2, 3, 4.
    alpha: [C; 3],
    /// The first pose's turns α_j, rad.
    turns: [f64; 3],
    /// δ_j = P_j − P1.
    delta: [C; 3],
    /// Δ1..Δ4.
    d: [C; 4],
    /// The largest |δ_j|, m.
    pub(super) size: f64,
}

pub(super) fn rotation_minus_one(angle: f64) -> C {
    C::from_polar(1.0, angle) - 1.0
}

impl Compatibility {
    pub(super) fn new(poses: &[Pose]) -> Self {
        let p1 = C::new(poses[0].at[0], poses[0].at[1]);
        let turns = [1, 2, 3].map(|j| poses[j].angle - poses[0].angle);
        let alpha = turns.map(rotation_minus_one);
        let delta = [1, 2, 3].map(|j| C::new(poses[j].at[0], poses[j].at[1]) - p1);
        // Cofactors of the first column of [e^{iβ} − 1, e^{iα} − 1, δ] (rows j = 2, 3, 4).
        let minor = |r: usize, s: usize| alpha[r] * delta[s] - alpha[s] * delta[r];
        let (d2, d3, d4) = (minor(1, 2), -minor(0, 2), minor(0, 1));
        Self {
            p1,
            alpha,
            turns,
            delta,
            d: [-(d2 + d3 + d4), d2, d3, d4],
            size: delta.iter().map(|d| d.norm()).fold(0.0, f64::max),
        }
    }

    /// Whether the compatibility triangle closes for the turn β2 (two real branches).
    pub(super) fn closes(&self, beta2: f64) -> bool {
        let [d1, d2, d3, d4] = self.d;
        let l = (d1 + d2 * C::from_polar(1.0, beta2)).norm();
        let (r3, r4) = (d3.norm(), d4.norm());
        l > 0.0 && l <= r3 + r4 && l >= (r3 - r4).abs()
    }

    /// (W, Z) for the crank's turn β2 to pose 2 on the branch `sign` of the compatibility
    /// triangle; `None` where the triangle does not close, on the trivial solution, or where
    /// equations 2 and 3 do not fix W and Z. `fold` puts the triangle's apex on its base (the
    /// two branches' meeting point, where the apex's height is zero to rounding).
    pub(super) fn standard_form_with(&self, beta2: f64, sign: f64, fold: bool) -> Option<(C, C)> {
        let [d1, d2, d3, d4] = self.d;
        let s = -(d1 + d2 * C::from_polar(1.0, beta2));
        let (r3, r4, l) = (d3.norm(), d4.norm(), s.norm());
        if !(r3 > 0.0 && r4 > 0.0 && l > 0.0) {
            return None;
        }
        // a = Δ3·e^{iβ3}: |a| = r3, |s − a| = r4.
        if !self.closes(beta2) {
            return None;
        }
        let along = (r3 * r3 - r4 * r4 + l * l) / (2.0 * l);
        let h2 = if fold {
            0.0
        } else {
            (r3 * r3 - along * along).max(0.0)
        };
        let a = s / l * C::new(along, sign * h2.sqrt());
        let betas = [beta2, (a / d3).arg(), ((s - a) / d4).arg()];
        let trivial = betas
            .iter()
            .zip(self.turns)
            .all(|(&b, t)| (0.5 * (b - t)).sin().abs() < 1e-9);
        if trivial {
            return None;
        }
        let (b2, b3) = (rotation_minus_one(betas[0]), rotation_minus_one(betas[1]));
        let [a2, a3, _] = self.alpha;
        let det = b2 * a3 - b3 * a2;
        if !(det.norm() > 1e-12) {
            return None;
        }
        let w = (self.delta[0] * a3 - self.delta[1] * a2) / det;
        let z = (b2 * self.delta[1] - b3 * self.delta[0]) / det;
        Some((w, z))
    }

    /// The dyad for β2 on the branch `sign`: O = P1 − Z − W, A = P1 − Z.
    fn dyad(&self, beta2: f64, sign: f64) -> Option<Dyad> {
        self.dyad_with(beta2, sign, false)
    }

    pub(super) fn dyad_with(&self, beta2: f64, sign: f64, fold: bool) -> Option<Dyad> {
        let (w, z) = self.standard_form_with(beta2, sign, fold)?;
        let (circle, centre) = (self.p1 - z, self.p1 - z - w);
        let dyad = Dyad {
            centre: [centre.re, centre.im],
            circle: [circle.re, circle.im],
        };
        dyad.centre
            .iter()
            .chain(&dyad.circle)
            .all(|x| x.is_finite())
            .then_some(dyad)
    }
}
