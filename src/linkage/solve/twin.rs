#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! An RRR dyad hung on the inner joints of two twin dyads, solved in the twins' frame (see
//! [`TwinPlan`]).
//!
//! The twins hang on the known points K1, K2 with equal lengths in opposite modes, so their
//! inner joints are Q± = M ± h·n, mirror images about the axis K1K2 (e0 = (K2 − K1)/|K2 − K1|,
//! n = e0⊥, M the foot on the axis). The plain closed form takes this dyad's base direction
//! from Q₂ − Q₁, whose rounding (ε of the coordinates) is 1e-16/|Q₂ − Q₁| of a radian: at a
//! Peaucellier cell's lock (the rhombus folded, |Q₂ − Q₁| ≈ 10⁻⁸ of the size) the tracer
//! leaves its line by 10⁻¹⁰ of the size. Here the base direction is e = σ·n exactly (σ =
//! ±1 from the twins' modes, `KinState::twin_sides`), and its length d = (Q₂ − Q₁)·e. With
//! x = d/2 + (l₂² − l₃²)/(2d) along e from Q₁ (the circle–circle intersection, as the
//! plain form) and w² = l₂² − x² across, the inner joint is
//!
//!   B = M + (l₂² − l₃²)/(2d)·e + σ_B·w·e⊥,
//!
//! with M the foot of Q₁Q₂'s midpoint on the axis: a sum of terms each as exact as its
//! inputs, with no difference of nearly equal coordinates. For equal lengths the middle term
//! is zero, B lies on the axis and d enters only through w² = l² − d²/4 (its rounding moves
//! B by d·δd/(4w), nothing at the fold); at the fold itself (d = 0) this is B's limit along
//! the branch, the axis point at w = l from M on the mode's side. Unequal lengths need
//! d ≥ |l₂ − l₃| > 0 and take the same form.
//!
//! The rates are the plain form's (the velocity and acceleration systems on r₂ = B − A and
//! r₃ = B − C, [`rrr_rates`]), so inside the range they agree with it to the rounding of B.
//! Wherever this form has no clean answer (the twins no mirror pair any more, d ≤ 0 with
//! unequal lengths, this dyad near its own dead point, its determinant below the closed
//! forms' threshold while the linkage moves, anything not finite) the plain closed form
//! solves the dyad, with its errors: a twin dyad is refused where a plain one is.

use super::state::KinState;
use crate::angle::{cross, direction, perp};
use crate::kinematics::{rrr_rates, LinkMotion, PointMotion, SINGULAR_DETERMINANT};
use crate::linkage::plan::{Group, TwinPlan};
use nalgebra::{Point2, Vector2};

/// `true` when every value is finite.
#[inline]
fn finite<const N: usize>(values: [f64; N]) -> bool {
    values.iter().all(|v| v.is_finite())
}

impl KinState {
    /// Dyad `g` (an RRR dyad with twins `t`) solved in the twins' frame (the module's
    /// derivation) and stored: `true`; `false` when that form has no clean answer here and
    /// the plain closed form must decide (nothing stored).
    pub(super) fn solve_twin(&mut self, g: usize, group: &Group, t: &TwinPlan) -> bool {
        let side = self.twin_sides.get(g).copied().unwrap_or(0.0);
        if side == 0.0 {
            return false;
        }
        let [ka, kc] = group.known;
        let (a, c) = (self.at(ka, group.a_local), self.at(kc, group.c_local));
        let k1 = self.at(t.axis[0].0, t.axis[0].1).p;
        let k2 = self.at(t.axis[1].0, t.axis[1].1).p;
        let axis = k2 - k1;
        let e0 = axis / axis.norm();
        let e = side * perp(e0);
        let q = c.p - a.p;
        let d = q.dot(&e);
        let [l2, l3] = group.lengths;
        // B's offset from M along e: x − d/2.
        let along = if t.equal {
            0.0
        } else if d > 0.0 {
            (l2 - l3) * (l2 + l3) / (2.0 * d)
        } else {
            return false;
        };
        let x = 0.5 * d + along;
        let w2 = (l2 - x) * (l2 + x);
        // The plain form's test of its own tangent case (this dyad stretched or folded).
        let tol = 16.0 * f64::EPSILON * (l2 * l2 + l3 * l3 + d * d);
        if !(w2 > 2.0 * tol) || !finite([e0.x, e0.y, d, along, w2]) {
            return false;
        }
        let mid = Point2::from(0.5 * (a.p.coords + c.p.coords));
        let m = k1 + (mid - k1).dot(&e0) * e0;
        let b = m + along * e + (group.branch.sign() * w2.sqrt()) * perp(e);
        let (r2, r3) = (b - a.p, b - c.p);
        let big_d = cross(r2, r3);
        let det = big_d / (l2 * l3);
        let (dv, da) = (c.v - a.v, c.a - a.a);
        let rates = if det.abs() > 2.0 * SINGULAR_DETERMINANT {
            rrr_rates(r2, r3, 1.0 / big_d, dv, da)
        } else if t.equal && dv == Vector2::zeros() && da == Vector2::zeros() {
            // The twins folded (det = σ·w·d/l², w ≥ 10⁻⁷·l here, so d is what vanished)
            // with the linkage at rest: the position is the limit along the branch and
            // nothing moves.
            [0.0; 4]
        } else {
            return false;
        };
        let [omega2, omega3, epsilon2, epsilon3] = rates;
        let rod = LinkMotion {
            origin: a,
            angle: direction(r2),
            omega: omega2,
            epsilon: epsilon2,
        };
        let moving: PointMotion = rod.moving_at(b, r2);
        if !finite([
            b.x, b.y, det, omega2, omega3, epsilon2, epsilon3, moving.v.x, moving.v.y, moving.a.x,
            moving.a.y,
        ]) {
            return false;
        }
        let [n2, n3] = group.links;
        self.put_link(n2, rod, r2 / r2.norm());
        self.put_link(
            n3,
            LinkMotion {
                origin: c,
                angle: direction(r3),
                omega: omega3,
                epsilon: epsilon3,
            },
            r3 / r3.norm(),
        );
        self.dets[g] = det;
        true
    }
}

#[cfg(test)]
mod tests {
    use crate::kinematics::Motion;
    use crate::linkage::{bundled, Plan};

    /// `plan` with every twin mark removed: the plain closed form for every dyad, on the same
    /// (equalised) lengths.
    fn plain(plan: &Plan) -> Plan {
        let mut p = plan.clone();
        for g in &mut p.chain.groups {
            g.twin = None;
        }
        p
    }

    /// Inside the range the twin solve's rates, accelerations and forces are the plain
    /// solve's to 1e-13 (relative, each quantity against its own kind's largest value at
    /// that position) at 1000 positions between the locks, a moving and accelerating
    /// input; the positions the analysis refuses (within its rounding of a lock) are refused
    /// by both.
    #[test]
    fn twin_rates_and_forces_are_the_plain_ones_inside_the_range() {
        let twin = Plan::new(&bundled::peaucellier_lipkin()).unwrap();
        assert_eq!(
            twin.chain
                .groups
                .iter()
                .filter(|g| g.twin.is_some())
                .count(),
            1
        );
        let plain = plain(&twin);
        let (lo, hi) = twin
            .lock_positions(twin.reference_input())
            .unwrap()
            .unwrap();
        let n = 1000;
        let (mut worst, mut compared) = ([0.0f64; 4], 0);
        for k in 1..=n {
            let phi = lo + (hi - lo) * f64::from(k) / f64::from(n + 1);
            let m = Motion::new(phi, 3.0, -20.0);
            let (a, b) = match (twin.analyse(m), plain.analyse(m)) {
                (Ok(a), Ok(b)) => (a, b),
                (Err(_), Err(_)) => continue,
                (a, b) => panic!("φ = {phi}: {:?} vs {:?}", a.err(), b.err()),
            };
            compared += 1;
            let (ka, kb) = (a.kinematics(), b.kinematics());
            let rel = |x: &[f64], y: &[f64]| {
                let scale = y.iter().fold(f64::MIN_POSITIVE, |s, v| s.max(v.abs()));
                x.iter()
                    .zip(y)
                    .map(|(p, q)| (p - q).abs() / scale)
                    .fold(0.0, f64::max)
            };
            let mut kinds: [(Vec<f64>, Vec<f64>); 4] = Default::default();
            for j in twin.joint_names() {
                let (p, q) = (ka.joint(j.as_str()).unwrap(), kb.joint(j.as_str()).unwrap());
                kinds[0].0.extend([p.p.x, p.p.y]);
                kinds[0].1.extend([q.p.x, q.p.y]);
                kinds[1].0.extend([p.v.x, p.v.y]);
                kinds[1].1.extend([q.v.x, q.v.y]);
                kinds[2].0.extend([p.a.x, p.a.y]);
                kinds[2].1.extend([q.a.x, q.a.y]);
            }
            for (r, s) in a.reactions().iter().zip(b.reactions()) {
                kinds[3].0.extend([r.force.x, r.force.y]);
                kinds[3].1.extend([s.force.x, s.force.y]);
            }
            kinds[3].0.push(a.balances()[0].value);
            kinds[3].1.push(b.balances()[0].value);
            for (w, (x, y)) in worst.iter_mut().zip(&kinds) {
                *w = w.max(rel(x, y));
            }
        }
        println!(
            "twin vs plain over {compared} of {n} positions: positions {:.1e}, velocities \
             {:.1e}, accelerations {:.1e}, forces {:.1e}",
            worst[0], worst[1], worst[2], worst[3]
        );
        assert!(compared > 990, "{compared}");
        assert!(worst.iter().all(|&w| w < 1e-13), "{worst:?}");
    }

    /// A linkage without twins has no twin mark and no twin buffer: its solve is the plain
    /// one, bit for bit, whatever this module does.
    #[test]
    fn no_twins_no_mark() {
        let files = bundled::all()
            .into_iter()
            .chain(bundled::gallery())
            .chain([bundled::five_bar_robot()]);
        for l in files {
            let name = l.name.clone();
            let plan = Plan::new(&l).unwrap();
            let marks = plan
                .chain
                .groups
                .iter()
                .filter(|g| g.twin.is_some())
                .count();
            let expected = usize::from(name.starts_with("Peaucellier"));
            assert_eq!(marks, expected, "{name}");
            let state = crate::linkage::solve::state::KinState::new(&plan.chain);
            assert_eq!(state.twin_sides.is_empty(), expected == 0, "{name}");
        }
    }
}
