//! Friction in the joints of a triad (hinged, or with a sliding pair) or a general group in
//! one position's solve: the group's frictionless block (the [`Triad`] or [`SliderTriad`]
//! closed form, or the general group's linear equations) as the block of
//! [`kinetostatics::friction`]'s solve for any group of hinges and slides, the relative
//! rates from the solved kinematics. Each hinge's reaction keeps its friction couple (on its
//! `on` link from its `by` link), each slide's its couple K with the friction force in its
//! force, and the outer joints' reactions are added to the known links, as in the
//! frictionless solve.
//!
//! [`kinetostatics::friction`]: crate::kinetostatics::friction

use super::analysis::{Analysis, Reaction};
use super::state::within;
use super::statics::add;
use crate::angle::perp;
use crate::error::Result;
use crate::kinematics::SlidingPair;
use crate::kinetostatics::friction::{
    group_friction, slider_triad_block, triad_block, Frictionless, GroupJoint, GroupPair, Iteration,
};
use crate::kinetostatics::{Conditioning, SlideAt, SliderTriad, Triad};
use crate::linkage::plan::{FrictionPlan, Group, TriadPlan};
use crate::linkage::plan_general::GeneralPlan;
use crate::linkage::plan_triad::SliderLeg;
use crate::Load;
use nalgebra::{Point2, Vector2};

/// A joint of the group being solved: its joint, the plan's links it joins (`by` on `on`),
/// where, and, for a slide, its unit direction.
struct Hinged {
    joint: usize,
    by: usize,
    on: usize,
    point: Point2<f64>,
    slide: Option<Vector2<f64>>,
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
                slide: None,
            })
            .chain((0..3).map(|i| Hinged {
                joint: t.inner[i],
                by: binary[i],
                on: lt,
                point: b[i],
                slide: None,
            }))
            .collect();
        let zero = Load::zero(a[0]);
        if let Some(leg) = &t.slider {
            return self.friction_slider_triad(g, group, t, leg, hinges, fp);
        }
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

    /// Triad `g` with a sliding pair in its first leg, with the friction of its hinges and
    /// its slide: the slide (at A1, outer; at B1, inner) acts through its reference point,
    /// the sliding link's origin (B1 or A1), along the sliding link's direction.
    fn friction_slider_triad(
        &mut self,
        g: usize,
        group: &Group,
        t: &TriadPlan,
        leg: &SliderLeg,
        mut hinges: Vec<Hinged>,
        fp: &[FrictionPlan],
    ) -> Result<()> {
        let [lt, l1, l2, l3] = t.links;
        let kin = &self.k.kin;
        let dir = kin.units[l1];
        let (slide, k) = match leg.dims.pair {
            SlidingPair::Outer { .. } => (SlideAt::Outer, 0),
            SlidingPair::Inner { .. } => (SlideAt::Inner, 3),
        };
        let a = [0, 1, 2].map(|i| hinges[i].point);
        let b = [3, 4, 5].map(|i| hinges[i].point);
        // The sliding link's origin: B1 (outer) or A1 (inner), the pair's reference point.
        hinges[k].point = kin.links[l1].origin.p;
        hinges[k].slide = Some(dir);
        let zero = Load::zero(a[0]);
        let triad = SliderTriad {
            slide,
            normal: perp(dir),
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
            &slider_triad_block(&triad),
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
                slide: None,
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
                slide: None,
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

    /// A group of hinges and slides whose links are `links` (the order of `block`'s loads)
    /// with the friction of its joints; `block` gives the frictionless reactions' pairs in
    /// the order of `hinges`.
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
        let local = |k: usize| links.iter().position(|&l| l == k);
        let mut spec = Vec::with_capacity(hinges.len());
        for h in hinges {
            let (by, on) = (local(h.by), local(h.on).unwrap_or(0));
            spec.push(match h.slide {
                None => {
                    let w = |k: usize| self.k.kin.links[k].omega;
                    GroupJoint::hinge(by, on, fp[h.joint].hinge.rho, w(h.on) - w(h.by))
                }
                Some(dir) => {
                    // Checked when the plan was made.
                    let (f, law) = fp[h.joint].slide.checked(["f", "length", "centre"])?;
                    GroupJoint {
                        by,
                        on,
                        coefficient: f,
                        rate: self.relative_slide(h.joint, h.on, dir),
                        pair: GroupPair::Slide {
                            dir,
                            point: h.point,
                            law,
                        },
                    }
                }
            });
        }
        let loads: Vec<Load> = links.iter().map(|&k| self.acc[k]).collect();
        let names = &plan.chain.joint_names;
        let out = group_friction(
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
            let r = Reaction::new(h.by, h.on, out.forces[k], h.point, out.couples[k]);
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
