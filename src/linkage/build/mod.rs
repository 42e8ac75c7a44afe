#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! From a description to a plan, one way: names, then the structure (the joints as edges, the
//! inputs, the Assur decomposition), the links' frames and the groups in attachment order,
//! the local coordinates of joints, points and masses — the kinematic chain, whose reference
//! pose is then solved and checked to close — and last the loads, complete with whatever the
//! solved chain tells them (an indicator diagram's dead centres). The plan is made once,
//! whole; nothing is patched afterwards.

mod chain;
mod friction;
mod general;
mod groups;
mod loads;
mod reference;
mod triad;
mod twins;

use chain::{
    edges, input_links, input_specs, joint_at, plan_inputs, plan_joints, plan_links, plan_points,
    reference_size, Links,
};
use reference::{finite_pair, index_names, Frame, Names};

use super::description::{Input, Linkage};
use super::plan::{bad, Chain, Plan};
use super::solve::state::KinState;
use super::structure::{chebyshev, decompose_counted, Dyad, Edge};
use super::structure_triad::Assur;
use crate::error::Result;
use nalgebra::Point2;

impl Plan {
    /// Checks a description and plans its solve: the structure (mobility, the dyads in
    /// attachment order), every length and local coordinate from the reference pose, the
    /// assembly mode of every group, and the loads.
    ///
    /// # Errors
    /// [`Error::Description`](crate::Error::Description) naming the joint, link, load or
    /// field at fault: unknown or repeated names, a joint listed by fewer than two links (a hinge
    /// listed by three or more is expanded to binary joints), a prismatic joint of more, a
    /// link with fewer than two joints, a guide without a direction, non-finite numbers,
    /// negative masses, an output naming no link, prismatic joint, joint or point, a linkage whose groups are neither dyads of the 2nd class nor triads
    /// of the 3rd (the links left over named), or of the wrong mobility, a pose that
    /// does not close, a group at a dead point in the reference pose without a given mode.
    pub fn new(linkage: &Linkage) -> Result<Self> {
        let binary = super::hinges::binary_joints(linkage)?;
        Self::from_binary(&binary).map_err(|e| super::hinges::explain(e, linkage))
    }

    /// [`Plan::new`] of a description whose joints each join two links.
    fn from_binary(linkage: &Linkage) -> Result<Self> {
        let Structure {
            names,
            links,
            edges,
            specs,
            inputs,
            dyads,
            ..
        } = Structure::new(linkage)?;

        // Frames in the reference pose: the inputs', then each group's in attachment order.
        let origin = Frame {
            origin: Point2::origin(),
            angle: 0.0,
        };
        let mut frames = vec![origin; links.names.len()];
        let mut planned = plan_inputs(
            linkage,
            &specs,
            &inputs,
            &edges,
            (&names, &links),
            &mut frames,
        )?;
        let second_input = planned.get(1).cloned();
        let (input, reference_input) = planned.swap_remove(0);
        check_modes(linkage, &dyads)?;
        // The first mode given for each joint (as a search of the list would find it).
        let mut modes = std::collections::HashMap::with_capacity(linkage.modes.len());
        for m in &linkage.modes {
            modes.entry(m.joint.as_str()).or_insert(m.branch);
        }
        let mut groups = dyads
            .iter()
            .map(|g| match g {
                Assur::Dyad(d) => {
                    groups::plan_group(d, &edges, &links.names, (linkage, &modes), &mut frames)
                }
                Assur::Triad(t) => triad::plan_triad(t, &edges, &links.names, linkage, &mut frames),
                Assur::General(g) => {
                    general::plan_general(g, &edges, &links.names, linkage, &mut frames)
                }
            })
            .collect::<Result<Vec<_>>>()?;

        let joints = plan_joints(linkage, &edges, (&names, &links), &frames);
        let (point_names, points) = plan_points(linkage, &links, &frames)?;
        let size = reference_size(linkage)?;
        twins::mark(&mut groups, linkage, size);
        let link_plans = plan_links(linkage, &edges, (&names, &links), &frames)?;
        let gravity = finite_pair("field gravity", "gravity", linkage.gravity)?;
        let chain = Chain {
            mobility: chebyshev(links.names.len() - 1, edges.len()),
            link_names: links.names.clone(),
            link_order: links.order.clone(),
            joint_names: linkage.joints.iter().map(|j| j.name.clone()).collect(),
            point_names,
            links: link_plans,
            joints,
            points,
            input,
            second_input,
            groups,
            reference_input,
            size,
        };
        let checked = linkage
            .loads
            .iter()
            .enumerate()
            .map(|(i, spec)| loads::plan_load(spec, i, &names, &links.index, &frames, &chain))
            .collect::<Result<Vec<_>>>()?;
        check_closure(&chain, linkage)?;
        let loads = checked
            .into_iter()
            .map(|c| c.complete(&chain))
            .collect::<Result<_>>()?;
        let friction = friction::plan_friction(linkage)?;
        let plan = Self {
            name: linkage.name.clone(),
            chain,
            loads,
            gravity,
            friction,
            spare: Default::default(),
        };
        super::torsion_range::check_torsion(&plan)?;
        // A typo in the output would otherwise surface only when strokes are asked for.
        if let Some(output) = &linkage.output {
            plan.resolve(output)
                .map_err(|e| bad("field output", e.to_string()))?;
        }
        Ok(plan)
    }
}

/// The structure of a description: its names, links, joints as edges, inputs and the Assur
/// dyads in attachment order, with the work the decomposition did.
struct Structure<'a> {
    names: Names<'a>,
    links: Links,
    edges: Vec<Edge>,
    specs: Vec<(&'a Input, &'static str)>,
    inputs: Vec<(usize, usize)>,
    dyads: Vec<Assur<Dyad>>,
    work: u64,
}

impl<'a> Structure<'a> {
    fn new(linkage: &'a Linkage) -> Result<Self> {
        let names = index_names(linkage)?;
        let links = Links::new(linkage, &names)?;
        let edges = edges(linkage, &names, &links)?;
        let specs = input_specs(linkage);
        let inputs = input_links(&specs, &names, &links, &edges)?;
        let explicit: Vec<[usize; 2]> = linkage
            .groups
            .iter()
            .map(|[a, b]| {
                Ok([
                    links.index[names.link(a, "field groups")?],
                    links.index[names.link(b, "field groups")?],
                ])
            })
            .collect::<Result<_>>()?;
        let input_links: Vec<usize> = inputs.iter().map(|&(l, _)| l).collect();
        let (dyads, work) = decompose_counted(&edges, &links.names, &input_links, &explicit)?;
        Ok(Self {
            names,
            links,
            edges,
            specs,
            inputs,
            dyads,
            work,
        })
    }
}

impl Plan {
    /// The work of the structural decomposition of `linkage` (adjacency entries visited and
    /// queue operations), for the tests that show it grows linearly with the size of a
    /// description whatever its order. Not part of the API.
    ///
    /// # Errors
    /// As [`Plan::new`], for the structure.
    #[doc(hidden)]
    pub fn decomposition_work(linkage: &Linkage) -> Result<u64> {
        let linkage = super::hinges::binary_joints(linkage)?;
        Structure::new(&linkage).map(|s| s.work)
    }
}

/// A mode must name some group's inner joint; a mode that matches none is a typo.
fn check_modes(linkage: &Linkage, dyads: &[Assur<Dyad>]) -> Result<()> {
    let inner: std::collections::HashSet<&str> = dyads
        .iter()
        .filter_map(|g| match g {
            Assur::Dyad(d) => Some(linkage.joints[d.joints[1]].name.as_str()),
            Assur::Triad(_) | Assur::General(_) => None,
        })
        .collect();
    for m in &linkage.modes {
        if !inner.contains(m.joint.as_str()) {
            return Err(bad(
                format!("mode for joint {}", m.joint),
                "names no group's inner joint (the joint between a group's two links)",
            ));
        }
    }
    Ok(())
}

/// Solves the reference pose of `chain` and compares every joint with its given position.
fn check_closure(chain: &Chain, linkage: &Linkage) -> Result<()> {
    let mut state = KinState::new(chain);
    state
        .solve(chain, chain.reference_motions().as_slice())
        .map_err(|e| bad("reference pose", format!("does not assemble: {e}")))?;
    let pose = state.pose(chain);
    let tol = 1e-9 * chain.size.max(f64::MIN_POSITIVE);
    for (j, joint) in linkage.joints.iter().enumerate() {
        let given = joint_at(linkage, j);
        for side in 0..2 {
            let gap = (pose.joint_on_at(j, side).p - given).norm();
            if !(gap <= tol) {
                return Err(bad(
                    format!("joint {}", joint.name),
                    format!(
                        "the reference pose does not close: the joint as carried by link {} \
                         lies {gap:.3e} m from its given position",
                        chain.link_names[chain.joints[j].links[side]]
                    ),
                ));
            }
        }
    }
    Ok(())
}
