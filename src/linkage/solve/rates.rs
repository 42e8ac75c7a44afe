//! The rates-only pass: new input rates at the positions of the last kinematic solve.
//!
//! The velocity and acceleration problems of a group are linear in its unknown rates, with
//! the matrix of its position (the same 2×2 whose determinant is the group's conditioning).
//! Given the positions, each group's rates are a few dot products: no square root, no
//! `atan2`, no assembly test. The dynamics of a linkage with two inputs needs three rate
//! vectors at one position (its transfer functions); this pass makes the second and third
//! cost a fraction of a full solve.

use super::state::KinState;
use crate::angle::cross;
use crate::error::Result;
use crate::kinematics::{rpr_rates, rrp_rates, rrr_rates, LinkMotion, Motion, PointMotion};
use crate::linkage::plan::{Chain, Group, GroupKind, InputPlan};

impl KinState {
    /// Velocities and accelerations of every link at the input motions `inputs`, whose
    /// values (φ or s) must be those of the last successful
    /// [`solve`](Self::solve) on these buffers: the
    /// positions are taken from it, only the rates are solved again.
    ///
    /// RRR, RRP and RPR groups are solved from their positions; PRP and RPP groups (solved by
    /// the general contour solver) and any group whose rates come out non-finite go through
    /// their full closed form, which reports the failure as a full solve would. When the
    /// values are not those of the last solve (a caller's mistake), the whole position is
    /// solved again.
    ///
    /// # Errors
    /// As [`solve`](Self::solve).
    pub fn solve_rates(&mut self, plan: &Chain, inputs: &[Motion]) -> Result<()> {
        let same = |m: &Motion, last: &Motion| m.value.to_bits() == last.value.to_bits();
        let (input, second) = match (inputs, self.second_input, &plan.second_input) {
            ([i], None, None) if same(i, &self.input) => (*i, None),
            ([i, j], Some(last), Some((ip, _))) if same(i, &self.input) && same(j, &last) => {
                (*i, Some((*j, ip)))
            }
            _ => return self.solve(plan, inputs),
        };
        let rates_ok = |m: &Motion| {
            m.rate.is_finite()
                && m.accel.is_finite()
                && (plan.size * (m.rate * m.rate + m.accel.abs())).is_finite()
        };
        if !rates_ok(&input) || !second.as_ref().is_none_or(|(m, _)| rates_ok(m)) {
            // The full solve names the bad rate (or the overflow).
            return self.solve(plan, inputs);
        }
        self.input = input;
        self.set_input_rates(&plan.input, input);
        if let Some((m, ip)) = second {
            self.set_input_rates(ip, m);
            self.second_input = Some(m);
        }
        for (g, group) in plan.groups.iter().enumerate() {
            if !self.group_rates(g, group) {
                self.solve_group_kinematics(g, group)?;
            }
        }
        Ok(())
    }

    /// The input link's motion at the rates of `m`, its position kept.
    fn set_input_rates(&mut self, ip: &InputPlan, m: Motion) {
        let k = ip.link();
        let link = &mut self.links[k];
        match *ip {
            InputPlan::Crank { .. } => {
                link.omega = m.rate;
                link.epsilon = m.accel;
            }
            InputPlan::Slider { .. } => {
                // The slider's direction, as `input_motion` made it (unit(angle)).
                let d = self.units[k];
                link.origin.v = m.rate * d;
                link.origin.a = m.accel * d;
            }
        }
    }

    /// Group `g`'s rates from its stored positions; `false` (nothing stored) for a PRP or RPP
    /// group or when a rate is not finite.
    fn group_rates(&mut self, g: usize, group: &Group) -> bool {
        if let Some(t) = &group.triad {
            // A failure is reported by the full solve that follows.
            return self.triad_rates_at(g, group, t).is_ok();
        }
        if let Some(gp) = &group.general {
            return self.general_rates_at(g, gp).is_ok();
        }
        let [l2, l3] = group.links;
        let [ka, kc] = group.known;
        let (u2, u3) = (self.units[l2], self.units[l3]);
        let a = self.at(ka, group.a_local);
        let link = |origin: PointMotion, angle: f64, omega: f64, epsilon: f64| LinkMotion {
            origin,
            angle,
            omega,
            epsilon,
        };
        let (angle2, angle3) = (self.links[l2].angle, self.links[l3].angle);
        // Each kind's rates by its block's own kernel, on the stored position.
        let (m2, m3) = match group.kind {
            GroupKind::Rrr => {
                // r2 = B − A and r3 = B − C of the stored position.
                let c = self.at(kc, group.c_local);
                let (r2, r3) = (group.lengths[0] * u2, group.lengths[1] * u3);
                let i_d = 1.0 / cross(r2, r3);
                let [omega2, omega3, epsilon2, epsilon3] =
                    rrr_rates(r2, r3, i_d, c.v - a.v, c.a - a.a);
                (
                    link(a, angle2, omega2, epsilon2),
                    link(c, angle3, omega3, epsilon3),
                )
            }
            GroupKind::Rrp => {
                // The guide (of link `kc`, along the slider's direction u3) through G,
                // B = A + r2 on it at s = (B − G)·u3.
                let gp = self.at(kc, group.c_local);
                let guide = &self.links[kc];
                let (w4, e4) = (guide.omega, guide.epsilon);
                let r2 = group.lengths[0] * u2;
                let (d, dv, da) = (gp.p - a.p, gp.v - a.v, gp.a - a.a);
                let s = (r2 - d).dot(&u3);
                let i_d = 1.0 / r2.dot(&u3);
                let [omega2, _, epsilon2, _] = rrp_rates(u3, r2, s, i_d, (dv, da), (w4, e4));
                let rod = link(a, angle2, omega2, epsilon2);
                // B as the rod's point, at the slider's stored position.
                let b = rod.moving_at(self.links[l3].origin.p, r2);
                (rod, link(b, angle3, w4, e4))
            }
            GroupKind::Rpr => {
                // The axis A→E of length l = the stored measure.
                let e = self.at(kc, group.c_local);
                let l = self.dets[g];
                let [_, omega, _, epsilon] = rpr_rates(u2, l, 1.0 / l, e.v - a.v, e.a - a.a);
                (
                    link(a, angle2, omega, epsilon),
                    link(e, angle3, omega, epsilon),
                )
            }
            GroupKind::Prp | GroupKind::Rpp | GroupKind::Triad | GroupKind::General => {
                return false
            }
        };
        let finite = [m2, m3].iter().fold(true, |ok, m| {
            ok & [
                m.origin.v.x,
                m.origin.v.y,
                m.origin.a.x,
                m.origin.a.y,
                m.omega,
                m.epsilon,
            ]
            .iter()
            .fold(true, |ok, v| ok & v.is_finite())
        });
        if finite {
            self.links[l2] = m2;
            self.links[l3] = m3;
        }
        finite
    }
}
