//! Friction in the hinges of a triad or a general group in one position's solve: the
//! group's frictionless block (the [`Triad`] closed form, or the general group's linear
//! equations) as the block of [`kinetostatics::friction`]'s solve for any group of hinges,
//! the relative rates from the solved kinematics. Each hinge's reaction keeps its friction
//! couple (on its `on` link from its `by` link), and the outer hinges' reactions are added
//! to the known links, as in the frictionless solve.
//!
//! [`kinetostatics::friction`]: crate::kinetostatics::friction

use super::analysis::{Analysis, Reaction};
use super::state::within;
use super::statics::add;
use crate::error::Result;
use crate::kinetostatics::friction::{
    hinged_group, triad_block, Frictionless, GroupHinge, Iteration,
};
use crate::kinetostatics::{Conditioning, Triad};
use crate::linkage::plan::{FrictionPlan, Group, TriadPlan};
use crate::linkage::plan_general::GeneralPlan;
use crate::Load;
use nalgebra::{Point2, Vector2};

/// A hinge of the group being solved: its joint, the plan's links it joins (`by` on `on`)
/// and where.
struct Hinged {
    joint: usize,
    by: usize,
    on: usize,
    point: Point2<f64>,
}

impl Analysis<'_> {
    /// Triad `g` with the friction of its hinges.
    pub(super) fn friction_triad(
        &mut self,
        g: usize,
        group: &Group,
        t: &TriadPlan,
        fp: &[FrictionPlan],
    ) -> Result<()> {
        let [lt, l1, l2, l3] = t.links;
        let binary = [l1, l2, l3];
        let a = binary.map(|l| self.k.kin.links[l].origin.p);
        let pose = self.pose();
        let b = [0, 1, 2].map(|i| pose.joint_position_on(t.inner[i], lt));
        // The hinges in the triad block's order: A1, A2, A3, then B1, B2, B3.
        let hinges: Vec<Hinged> = (0..3)
            .map(|i| Hinged {
                joint: t.outer[i],
                by: t.known[i],
                on: binary[i],
                point: a[i],
            })
            .chain((0..3).map(|i| Hinged {
                joint: t.inner[i],
                by: binary[i],
                on: lt,
                point: b[i],
            }))
            .collect();
        let zero = Load::zero(a[0]);
        let triad = Triad {
            a,
            b,
            loads: [zero; 3],
            load_ternary: zero,
        };
        self.friction_hinged(
            g,
            group,
            &[l1, l2, l3, lt],
            &hinges,
            &triad_block(&triad),
            fp,
        )
    }

    /// General group `g` with the friction of its hinges.
    pub(super) fn friction_general(
        &mut self,
        g: usize,
        group: &Group,
        gp: &GeneralPlan,
        fp: &[FrictionPlan],
    ) -> Result<()> {
        let pose = self.k.kin.general_stored(gp);
        let place = self.pose();
        // The block's reactions: at an inner hinge the force of its second link on its
        // first, at an outer hinge the known link's on the group's.
        let inner = gp.inner.iter().zip(&gp.block.inner).map(|(&j, &[a, b])| {
            let on = gp.links[a.0];
            Hinged {
                joint: j,
                by: gp.links[b.0],
                on,
                point: place.joint_position_on(j, on),
            }
        });
        let outer = gp.outer.iter().zip(&gp.block.outer).zip(&gp.known);
        let outer = outer.map(|((&j, end), &(known, _))| {
            let on = gp.links[end.0];
            Hinged {
                joint: j,
                by: known,
                on,
                point: place.joint_position_on(j, on),
            }
        });
        let hinges: Vec<Hinged> = inner.chain(outer).collect();
        let block = |loads: &[Load]| -> Result<(Vec<Vector2<f64>>, Conditioning)> {
            let r = gp.block.reactions(&pose, loads, gp.size)?;
            let c = Conditioning {
                measure: r.conditioning,
                condition: (1.0 / r.conditioning).max(1.0),
            };
            Ok((r.inner.into_iter().chain(r.outer).collect(), c))
        };
        self.friction_hinged(g, group, &gp.links, &hinges, &block, fp)
    }

    /// A group of hinges whose links are `links` (the order of `block`'s loads) with the
    /// friction of its hinges; `block` gives the frictionless reactions in the order of
    /// `hinges`.
    fn friction_hinged(
        &mut self,
        g: usize,
        group: &Group,
        links: &[usize],
        hinges: &[Hinged],
        block: &Frictionless<'_>,
        fp: &[FrictionPlan],
    ) -> Result<()> {
        let plan = self.k.plan;
        let kin = &self.k.kin;
        let local = |k: usize| links.iter().position(|&l| l == k);
        let spec: Vec<GroupHinge> = hinges
            .iter()
            .map(|h| GroupHinge {
                by: local(h.by),
                on: local(h.on).unwrap_or(0),
                rho: fp[h.joint].hinge.rho,
                rate: kin.links[h.on].omega - kin.links[h.by].omega,
            })
            .collect();
        let loads: Vec<Load> = links.iter().map(|&k| self.acc[k]).collect();
        let names = &plan.chain.joint_names;
        let out = hinged_group(
            &loads,
            &spec,
            block,
            &Iteration::default(),
            "friction in a group",
            &|k| format!("joint {}", names[hinges[k].joint]),
        )
        .map_err(within(&group.name))?;
        for (k, h) in hinges.iter().enumerate() {
            let fr = out.joints[k];
            let r = Reaction::new(h.by, h.on, out.forces[k], h.point, fr.load);
            if spec[k].by.is_none() {
                add(&mut self.acc[h.by], &r.load_on_side(h.by));
            }
            self.reactions[h.joint] = r;
            self.friction.joints[h.joint] = fr;
        }
        self.friction.iterations += out.convergence.iterations;
        self.conditioning[g] = out.conditioning;
        Ok(())
    }
}
