//! The kinetostatics' refusal of a dyad at its dead point to within the position's own
//! rounding (a rocking input at its lock, a crank at a dead centre).
//!
//! An RRR dyad's inner joint is B = A + x·e + σ·h·e⊥ with h² = l_AB² − x² (e the unit vector
//! from A to C, x = (l² + l_AB² − l_CB²)/(2l), l = |AC|); its determinant is
//! sin(φ3 − φ2) = σ·h·l/(l_AB·l_CB), so it is proportional to h. Near a dead point h² is a
//! difference of nearly equal numbers: an error δ in h² (rounding of x, and of A and C
//! themselves) moves h by δ/(2h), a relative error of δ/(2h²) in the determinant and, since
//! the group's reactions are proportional to its inverse, in every reaction and balance
//! downstream. At a lock found by bisection h² is of the order of δ: the determinant
//! (≈ 1e-7) is rounding alone, the true reactions are unbounded or the limit of a cancelling
//! difference of unbounded ones, and the closed forms' own conditioning (1/det ≈ 1e7) does
//! not see it. The RRP dyad is the same with h the rod's reach across the guide:
//! B = F + σ·h·g on the foot F of A on the guide, h² = l² − d⊥², cos(φ2 − φ4) = h/l.
//!
//! Bound of δ: x carries a few ε of l + |l_AB² − l_CB²|/l, and l the rounding of A's and C's
//! coordinates (ε of their magnitudes, summed over the groups before); h² = (l_AB − x)·
//! (l_AB + x) turns an error Δx into 2·l_AB·Δx. So for the RRR dyad
//! δ = 4ε·(l_AB + l_CB)·(l + |l_AB² − l_CB²|/l + |A|₁ + |C|₁). An assembled dyad has
//! |l_AB − l_CB| ≤ l ≤ l_AB + l_CB = s, so δ ≤ 4ε·s·(2s + |A|₁ + |C|₁) and
//! h² ≥ det²·l_AB²·l_CB²/s²: the test below uses these bounds, which need neither a square
//! root nor a division by the position's numbers (it runs at every analysed position), and
//! refuses a little more than the exact δ/(2h²) would (by at most (s/l)², where l is nearest
//! |l_AB − l_CB|: the dyad folded). The RRP dyad's reach: δ = 4ε·l·(l + |A|₁ + |B|₁) (d⊥ from
//! A and a point of the guide), h = |det|·l. The analysis refuses the position when δ/(2h²)
//! exceeds [`DEAD_POINT_RELATIVE_ERROR`]: its forces would carry fewer than six significant
//! digits, and within about 10⁻⁸ rad of a lock none at all.

use super::state::{within, KinState};
use crate::error::{Error, Result};
use crate::linkage::plan::{Chain, GroupKind};
use nalgebra::Point2;

/// The largest relative error of a dyad's determinant, from the rounding of its position,
/// at which the kinetostatics still answers: the reactions, proportional to the
/// determinant's inverse, keep six significant digits. Beyond it (within about 10⁻⁸ rad of
/// a rocking input's lock, for the bundled linkages) the analysis returns
/// [`Error::Singular`] naming the group.
pub const DEAD_POINT_RELATIVE_ERROR: f64 = 1e-6;

/// |p|₁: the scale of the rounding of p's coordinates.
#[inline(always)]
fn l1(p: Point2<f64>) -> f64 {
    p.x.abs() + p.y.abs()
}

impl KinState {
    /// `Err` naming the first RRR or RRP dyad (in attachment order) whose determinant is
    /// within its rounding bound's reach of zero (see the module's derivation): the
    /// kinetostatics has no digits to give there. The other groups' determinants come from
    /// linear equations, with no square root of a difference, and their closed forms'
    /// conditioning covers them.
    #[inline]
    pub(super) fn refuse_dead_points(&self, chain: &Chain) -> Result<()> {
        const EPS4: f64 = 4.0 * f64::EPSILON;
        for (g, group) in chain.groups.iter().enumerate() {
            if group.triad.is_some() || group.general.is_some() {
                continue;
            }
            let det = self.dets[g];
            let [l2, l3] = group.links;
            // A is link 2's origin in both dyads; C (RRR) and B (RRP) link 3's.
            let (a, c) = (self.links[l2].origin.p, self.links[l3].origin.p);
            // δ and h² as in the module's derivation (their bounds for the RRR dyad).
            let (what, measure, delta, h2) = match group.kind {
                GroupKind::Rrr => {
                    let [lab, lcb] = group.lengths;
                    let s = lab + lcb;
                    let r = lab * lcb / s;
                    (
                        "RRR dyad at its dead point (within its position's rounding)",
                        "sin(phi3 - phi2)",
                        EPS4 * s * (2.0 * s + l1(a) + l1(c)),
                        det * det * r * r,
                    )
                }
                GroupKind::Rrp => {
                    let l = group.lengths[0];
                    (
                        "RRP dyad at its dead point (within its position's rounding)",
                        "cos(phi2 - phi4)",
                        EPS4 * l * (l + l1(a) + l1(c)),
                        det * det * l * l,
                    )
                }
                _ => continue,
            };
            if delta > 2.0 * DEAD_POINT_RELATIVE_ERROR * h2 {
                return Err(within(&group.name)(Error::Singular {
                    what,
                    measure,
                    value: det,
                }));
            }
        }
        Ok(())
    }
}
