//! The kinetostatics of one position: the reactions group by group from the last attached
//! back to the input links, and each drive's balancing moment or force.

use super::analysis::{Analysis, Balance, Reaction};
use super::state::within;
use crate::angle::{cross, unit};
use crate::error::{Error, Result};
use crate::kinetostatics::{
    Conditioning, CouplingDrive, GearDrive, PrpDyad, RppDyad, RprDyad, RrpDyad, RrrDyad,
};
use crate::linkage::description::Drive;
use crate::linkage::plan::{Group, GroupKind, InputPlan};
use crate::Load;
use nalgebra::Vector2;

impl Analysis<'_> {
    pub(super) fn solve_statics(&mut self) -> Result<()> {
        let plan = self.k.plan;
        for (k, acc) in self.acc.iter_mut().enumerate() {
            *acc = Load::zero(self.k.kin.links[k].origin.p);
        }
        for &(k, l) in &self.applied {
            add(&mut self.acc[k], &l);
        }
        for (g, group) in plan.chain.groups.iter().enumerate().rev() {
            self.solve_group(g, group)?;
        }
        self.solve_input()?;
        Ok(())
    }

    fn solve_group(&mut self, g: usize, group: &Group) -> Result<()> {
        if let Some(t) = &group.triad {
            return self.solve_triad(g, group, t);
        }
        if let Some(gp) = &group.general {
            return self.solve_general(g, group, gp);
        }
        let [l2, l3] = group.links;
        let [ja, jb, jc] = group.joints;
        let [ka, kc] = group.known;
        let a = self.k.kin.links[l2].origin.p;
        let (load2, load3) = (self.acc[l2], self.acc[l3]);
        let name = &group.name;
        let (ra, rb, rc, cond) = match group.kind {
            GroupKind::Rrr => {
                let b = self.pose().joint_position_on(jb, l2);
                let c = self.k.kin.links[l3].origin.p;
                let r = RrrDyad {
                    a,
                    b,
                    c,
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::hinge(l2, l3, r.r23, b),
                    Reaction::hinge(kc, l3, r.r43, c),
                    r.conditioning,
                )
            }
            GroupKind::Rrp => {
                let b = self.k.kin.links[l3].origin.p;
                let r = RrpDyad {
                    a,
                    b,
                    guide: self.k.kin.units[l3],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::hinge(l2, l3, r.r23, b),
                    Reaction::new(kc, l3, r.r43, b, r.guide_moment),
                    r.conditioning,
                )
            }
            GroupKind::Rpr => {
                let c = self.k.kin.links[l3].origin.p;
                let r = RprDyad {
                    a,
                    e: c,
                    axis: self.k.kin.units[l2],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::new(l3, l2, r.r32, a, r.couple),
                    Reaction::hinge(kc, l3, r.r43, c),
                    r.conditioning,
                )
            }
            GroupKind::Prp => {
                let b = self.k.kin.links[l2].origin.p;
                let r = PrpDyad {
                    b,
                    guide2: self.k.kin.units[l2],
                    guide3: self.k.kin.units[l3],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::new(ka, l2, r.r12, b, r.moment12),
                    Reaction::hinge(l2, l3, r.r23, b),
                    Reaction::new(kc, l3, r.r43, b, r.moment43),
                    r.conditioning,
                )
            }
            // A plan's triad always carries its plan (solved above).
            GroupKind::Triad | GroupKind::General => {
                return Err(Error::Description {
                    item: group.name.clone(),
                    problem: "a triad without its plan".to_owned(),
                })
            }
            GroupKind::Rpp => {
                let b = self.k.kin.links[l3].origin.p;
                let r = RppDyad {
                    a,
                    b,
                    guide: self.k.kin.units[l3],
                    slot: self.k.kin.units[l2],
                    load2,
                    load3,
                }
                .solve()
                .map_err(within(name))?;
                (
                    Reaction::hinge(ka, l2, r.r12, a),
                    Reaction::new(l3, l2, r.r32, a, r.moment32),
                    Reaction::new(kc, l3, r.r43, b, r.moment43),
                    r.conditioning,
                )
            }
        };
        add(&mut self.acc[ka], &ra.load_on_side(ka));
        add(&mut self.acc[kc], &rc.load_on_side(kc));
        self.reactions[ja] = ra;
        self.reactions[jb] = rb;
        self.reactions[jc] = rc;
        self.conditioning[g] = cond;
        Ok(())
    }

    fn solve_input(&mut self) -> Result<()> {
        let plan = self.k.plan;
        self.balances[0] = self.solve_drive(&plan.chain.input)?;
        if let Some((ip, _)) = &plan.chain.second_input {
            self.balances[1] = self.solve_drive(ip)?;
        }
        Ok(())
    }

    /// The balancing moment or force of one input link, and its reaction with the frame.
    // Inlined: returned through memory, a `Result<Balance>` was copied byte-shifted (the
    // error's tag first), and reading the balance back stalled on those stores.
    #[inline(always)]
    pub(super) fn solve_drive(&mut self, ip: &InputPlan) -> Result<Balance> {
        let plan = self.k.plan;
        let link = ip.link();
        let load = self.acc[link];
        let part = &plan.chain.link_names[link];
        let balance;
        match *ip {
            InputPlan::Crank {
                joint,
                pivot,
                drive,
                ..
            } => {
                let (value, force, at, r01, conditioning) = match drive {
                    Drive::Coupling => {
                        let b = CouplingDrive { o1: pivot }
                            .solve(&[load])
                            .map_err(within(part))?;
                        (
                            b.balancing_moment,
                            Vector2::zeros(),
                            pivot,
                            b.r01,
                            b.conditioning,
                        )
                    }
                    Drive::Gear {
                        pitch_radius,
                        pitch_angle,
                        pressure_angle,
                    } => {
                        let d =
                            GearDrive::at_angle(pivot, pitch_radius, pitch_angle, pressure_angle);
                        let b = d.solve(&[load]).map_err(within(part))?;
                        (
                            b.balancing_moment,
                            b.force,
                            d.pitch_point,
                            b.r01,
                            b.conditioning,
                        )
                    }
                };
                self.reactions[joint] = Reaction::hinge(0, link, r01, pivot);
                balance = Balance {
                    value,
                    force,
                    point: at,
                    conditioning,
                };
            }
            InputPlan::Slider { joint, angle, .. } => {
                let d = unit(angle);
                let f = load.force;
                let fb = -f.dot(&d);
                let normal = -(f + fb * d);
                self.reactions[joint] = Reaction::new(0, link, normal, load.point, -load.moment);
                balance = Balance {
                    value: fb,
                    force: fb * d,
                    point: load.point,
                    conditioning: Conditioning {
                        measure: 1.0,
                        condition: 1.0,
                    },
                };
                let all = [fb, normal.x, normal.y, load.moment];
                if !all.iter().all(|v| v.is_finite()) {
                    return Err(within(part)(Error::NonFinite {
                        name: "balancing force",
                        value: fb,
                    }));
                }
            }
        }
        Ok(balance)
    }

    /// The drive's load on input `i`'s link (0 the first): the balancing couple, or the
    /// balancing force.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"input index"`) for an input the linkage does not have.
    pub fn drive_load(&self, i: usize) -> Result<Load> {
        let b = self.balance(i)?;
        let ip = self
            .k
            .plan
            .chain
            .inputs()
            .nth(i)
            .unwrap_or(&self.k.plan.chain.input);
        Ok(drive_load(ip, &b))
    }

    /// Each drive's load on its input link, with the link's index.
    pub(crate) fn drive_loads(&self) -> impl Iterator<Item = (usize, Load)> + '_ {
        self.k
            .plan
            .chain
            .inputs()
            .zip(&self.balances)
            .map(|(ip, b)| (ip.link(), drive_load(ip, b)))
    }
}

/// The load a drive exerts on its input link: the balancing couple, or the balancing force.
fn drive_load(ip: &InputPlan, b: &Balance) -> Load {
    match ip {
        InputPlan::Crank {
            drive: Drive::Coupling,
            ..
        } => Load::new(b.point, Vector2::zeros(), b.value),
        _ => Load::force_at(b.point, b.force),
    }
}

/// Adds `l` to the resultant `acc` (kept at its point).
pub(super) fn add(acc: &mut Load, l: &Load) {
    acc.moment += l.moment + cross(l.point - acc.point, l.force);
    acc.force += l.force;
}
