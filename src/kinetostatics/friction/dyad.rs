//! The one friction solve of the five dyads: a dyad is a group of three joints on two links
//! (link 2 and link 3, indices 0 and 1 of [`GroupJoint`]'s `by` and `on`), its reactions a
//! pair of numbers per joint ([`GroupPair`](super::group::GroupPair): a hinge's force, a slide's N and K). Each
//! joint's friction load per newton of pressure is the group's ([`GroupJoint`]); the
//! frictionless closed form's response to it is a column of D, and m = ψ(V0 + D·m) is
//! solved by the dyads' 3×3 Newton ([`Problem`]). The dyads' public solvers
//! ([`RrrFriction`](super::RrrFriction) … [`RppFriction`](super::RppFriction)) and the
//! whole linkage's solve go through here.

use super::group::{load_scale, GroupJoint};
use super::solver::{Problem, Solved};
use super::{sign, Convergence, Iteration, JointFriction};
use crate::error::Result;
use crate::Load;
use nalgebra::Vector2;

/// A dyad's frictionless solve as the friction solve reads it: per joint its pair (see
/// [`GroupPair`](super::group::GroupPair)), in `pairs` (joint k at 2k, 2k + 1), and its whole force.
pub(crate) struct DyadBase {
    pub pairs: [f64; 6],
    pub forces: [Vector2<f64>; 3],
}

/// A dyad solved with friction: per joint the whole force of `by` on `on` (see
/// [`GroupJoint::reaction`]), its friction, and its pair.
pub(crate) struct DyadSolved {
    pub forces: [Vector2<f64>; 3],
    pub joints: [JointFriction; 3],
    pub pairs: [f64; 6],
    pub convergence: Convergence,
}

/// Solves a dyad with the friction of its `joints` (module docs): `base` its frictionless
/// solve under `loads` (on links 2 and 3), `block` the frictionless pairs under any loads.
/// Without friction in any joint (every ρ or f zero, or every relative rate zero) the
/// frictionless results as they are, bit for bit.
///
/// # Errors
/// `block`'s errors; as [`Problem::solve`] (a joint that self-locks, named by `names`, a
/// budget used up).
pub(crate) fn dyad_friction(
    base: &DyadBase,
    joints: &[GroupJoint; 3],
    loads: [&Load; 2],
    block: impl Fn(&[Load; 2]) -> Result<[f64; 6]>,
    options: &Iteration,
    what: &'static str,
    names: [&'static str; 3],
) -> Result<DyadSolved> {
    let c = joints.map(|h| h.coefficient * sign(h.rate));
    let laws = joints.map(|h| h.law());
    let pair = |v: &[f64; 6], k: usize| [v[2 * k], v[2 * k + 1]];
    if c == [0.0; 3] {
        let fr = [0, 1, 2]
            .map(|k| JointFriction::none(laws[k].of(base.pairs[2 * k], base.pairs[2 * k + 1])));
        return Ok(DyadSolved {
            forces: base.forces,
            joints: fr,
            pairs: base.pairs,
            convergence: Convergence::NONE,
        });
    }
    let mut d = [[0.0; 6]; 3];
    for k in 0..3 {
        if c[k] != 0.0 {
            let mut unit = loads.map(|l| Load::zero(l.point));
            joints[k].put_unit_load(c[k], &mut unit);
            d[k] = block(&unit)?;
        }
    }
    let scale = load_scale(
        loads.iter().map(|l| l.force),
        (0..3).map(|k| joints[k].force_of(pair(&base.pairs, k))),
    );
    let problem = Problem {
        v0: base.pairs,
        d,
        laws,
        active: c.map(|c| c != 0.0),
        scale,
    };
    let Solved { m, v, convergence } = problem.solve(options, what, names)?;
    let fr = [0, 1, 2].map(|k| {
        if c[k] == 0.0 {
            JointFriction::none(laws[k].of(v[2 * k], v[2 * k + 1]))
        } else {
            JointFriction::new(c[k], m[k], joints[k].rate)
        }
    });
    Ok(DyadSolved {
        forces: [0, 1, 2].map(|k| joints[k].reaction(pair(&v, k), &fr[k]).0),
        joints: fr,
        pairs: v,
        convergence,
    })
}
