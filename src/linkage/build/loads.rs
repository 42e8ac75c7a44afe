#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The loads of a plan: each of the description's loads checked and placed on its link, and
//! the dead centres of every piston under an indicator diagram found on the kinematic chain
//! (which is built and checked first), so a load is complete when it enters the plan.

use super::reference::{finite_num, finite_pair, non_negative, place, Frame, Names};
use crate::error::Result;
use crate::kinematics::{extreme_positions, transfer_functions, Motion};
use crate::linkage::description::{Anchor, At, LoadSpec};
use crate::linkage::indicator::IndicatorDiagram;
use crate::linkage::plan::{bad, Chain, LoadPlan};
use crate::linkage::solve::state::KinState;
use crate::linkage::springs::{DamperPlan, End, SpringPlan, TorsionPlan};
use nalgebra::Vector2;

/// A load checked against the description, waiting only for what the solved chain tells: an
/// indicator diagram's dead centres.
pub(super) enum Checked {
    /// Complete.
    Ready(LoadPlan),
    /// An indicator diagram on the piston of joint `joint`.
    Indicator {
        joint: usize,
        head: f64,
        diagram: IndicatorDiagram,
    },
}

impl Checked {
    /// The complete load, its piston's dead centres found on `chain`.
    pub(super) fn complete(self, chain: &Chain) -> Result<LoadPlan> {
        Ok(match self {
            Self::Ready(l) => l,
            Self::Indicator {
                joint,
                head,
                diagram,
            } => LoadPlan::Indicator {
                ends: dead_centres(chain, joint, head)?,
                joint,
                head,
                diagram,
            },
        })
    }
}

/// The dead centres of the piston of joint `joint` as the slide s·head: [head end, crank end].
fn dead_centres(chain: &Chain, joint: usize, head: f64) -> Result<[f64; 2]> {
    let name = format!("joint {}", chain.joint_names[joint]);
    let mut state = KinState::new(chain);
    let ext = extreme_positions(
        |phi| {
            transfer_functions(
                |m| {
                    state.solve(chain, &[m])?;
                    let s = state.pose(chain).slide_at(joint);
                    Ok(Motion::new(head * s.value, head * s.rate, head * s.accel))
                },
                phi,
            )
        },
        360,
    )
    .map_err(|e| {
        bad(
            &name,
            format!("its piston's dead centres cannot be found: {e}"),
        )
    })?;
    let hi = ext
        .iter()
        .map(|e| e.output.value)
        .fold(f64::NEG_INFINITY, f64::max);
    let lo = ext
        .iter()
        .map(|e| e.output.value)
        .fold(f64::INFINITY, f64::min);
    if !(hi > lo) {
        return Err(bad(
            name,
            "the piston has no stroke over a turn of the input",
        ));
    }
    Ok([hi, lo])
}

/// Checks load `i` of the description and places it on its link.
pub(super) fn plan_load(
    spec: &LoadSpec,
    i: usize,
    names: &Names<'_>,
    link_index: &[usize],
    frames: &[Frame],
    plan: &Chain,
) -> Result<Checked> {
    let item = format!("load {}", i + 1);
    let link_of = |n: &str| names.link(n, &item).map(|k| link_index[k]);
    let at_on = |a: &At, li: usize, field: &str| -> Result<Vector2<f64>> {
        Ok(frames[li].local(place(a, names, li, link_index, &item, field)?))
    };
    Ok(Checked::Ready(match spec {
        LoadSpec::Force { link, at, force } => {
            let link = link_of(link)?;
            LoadPlan::Force {
                link,
                local: at_on(at, link, "at")?,
                force: finite_pair(&item, "force", *force)?,
            }
        }
        LoadSpec::Moment { link, moment } => LoadPlan::Moment {
            link: link_of(link)?,
            moment: finite_num(&item, "moment", *moment)?,
        },
        LoadSpec::Resistance {
            on,
            forward,
            backward,
            at,
        } => {
            let forward = non_negative(&item, "forward", *forward)?;
            let backward = non_negative(&item, "backward", *backward)?;
            if let Some(&j) = names.joints.get(on.as_str()) {
                let Some((side, _)) = plan.joints[j].prismatic else {
                    return Err(bad(
                        &item,
                        format!("resists joint {on}, which is not prismatic"),
                    ));
                };
                let slider = plan.joints[j].links[1 - side];
                let local = match at {
                    None => plan.joints[j].local[1 - side],
                    Some(a) => at_on(a, slider, "at")?,
                };
                LoadPlan::Sliding {
                    joint: j,
                    local,
                    forward,
                    backward,
                }
            } else {
                LoadPlan::Turning {
                    link: link_of(on)?,
                    forward,
                    backward,
                }
            }
        }
        LoadSpec::Indicator {
            joint,
            diagram,
            head,
        } => {
            let j = names.joint(joint, &item)?;
            match plan.joints[j].prismatic {
                Some((side, _)) if plan.joints[j].links[side] == 0 => {}
                _ => {
                    return Err(bad(
                        &item,
                        format!("joint {joint} must be prismatic with its guide on the frame"),
                    ))
                }
            }
            if !(*head == 1.0 || *head == -1.0) {
                return Err(bad(&item, format!("head must be +1 or −1, got {head}")));
            }
            if !(diagram.area.is_finite() && diagram.area > 0.0) {
                return Err(bad(
                    &item,
                    format!(
                        "diagram.area must be > 0, got {}",
                        super::reference::shown(diagram.area)
                    ),
                ));
            }
            if let Some(problem) = diagram.non_finite_point() {
                return Err(bad(&item, problem));
            }
            return Ok(Checked::Indicator {
                joint: j,
                head: *head,
                diagram: diagram.clone(),
            });
        }
        LoadSpec::Spring {
            name,
            ends,
            stiffness,
            free_length,
            preload,
        } => {
            let item = named(&item, "spring", name);
            LoadPlan::Spring(SpringPlan {
                ends: plan_ends(ends, &item, names, link_index, frames, plan)?,
                stiffness: non_negative(&item, "stiffness", *stiffness)?,
                free_length: non_negative(&item, "free_length", *free_length)?,
                preload: finite_num(&item, "preload", *preload)?,
                name: item,
            })
        }
        LoadSpec::Damper { name, ends, c } => {
            let item = named(&item, "damper", name);
            LoadPlan::Damper(DamperPlan {
                ends: plan_ends(ends, &item, names, link_index, frames, plan)?,
                c: non_negative(&item, "c", *c)?,
                name: item,
            })
        }
        LoadSpec::TorsionSpring {
            name,
            links,
            stiffness,
            free_angle,
            preload,
        } => {
            let item = named(&item, "torsion spring", name);
            let [a, b] =
                [&links[0], &links[1]].map(|l| names.link(l, &item).map(|k| link_index[k]));
            let (a, b) = (a?, b?);
            if a == b {
                return Err(bad(
                    &item,
                    format!("joins link {} to itself: name two links", links[0]),
                ));
            }
            // The engine's link angles are its frames'; a given Δθ₀ is along the links'
            // reference directions, which lie at the plans' offsets from the frames.
            let free = match free_angle {
                None => frames[b].angle - frames[a].angle,
                Some(f) => {
                    finite_num(&item, "free_angle", *f)?
                        - (plan.links[b].angle_offset - plan.links[a].angle_offset)
                }
            };
            LoadPlan::Torsion(TorsionPlan {
                links: [a, b],
                stiffness: non_negative(&item, "stiffness", *stiffness)?,
                free,
                preload: finite_num(&item, "preload", *preload)?,
                name: item,
            })
        }
    }))
}

/// "spring NAME", or "load N (spring)" for an unnamed one.
fn named(item: &str, kind: &str, name: &str) -> String {
    if name.is_empty() {
        format!("{item} ({kind})")
    } else {
        format!("{kind} {name}")
    }
}

/// The two ends of a spring or damper `item`, each on its link, on two different links.
fn plan_ends(
    ends: &[Anchor; 2],
    item: &str,
    names: &Names<'_>,
    link_index: &[usize],
    frames: &[Frame],
    plan: &Chain,
) -> Result<[End; 2]> {
    let mut out = [(0, Vector2::zeros()); 2];
    for (e, (anchor, field)) in out.iter_mut().zip(ends.iter().zip(["ends[0]", "ends[1]"])) {
        *e = plan_end(anchor, item, field, names, link_index, frames, plan)?;
    }
    if out[0].0 == out[1].0 {
        return Err(bad(
            item,
            format!(
                "has both ends on link {}: it would pull on nothing",
                plan.link_names[out[0].0]
            ),
        ));
    }
    Ok(out)
}

/// One end: its link (given, or read off a point or a joint with the frame) and its local
/// coordinates there.
fn plan_end(
    anchor: &Anchor,
    item: &str,
    field: &str,
    names: &Names<'_>,
    link_index: &[usize],
    frames: &[Frame],
    plan: &Chain,
) -> Result<End> {
    let joint_links = |n: &str| names.joints.get(n).map(|&j| plan.joints[j].links);
    let link = match (&anchor.link, &anchor.at) {
        (Some(l), at) => {
            let li = link_index[names.link(l, item)?];
            if let At::Name(n) = at
                && let Some(ls) = joint_links(n)
                && !ls.contains(&li)
            {
                return Err(bad(
                    item,
                    format!("{field} names joint {n}, which link {l} does not hold"),
                ));
            }
            li
        }
        (None, At::Name(n)) => match (names.points.get(n.as_str()), joint_links(n)) {
            (Some(&(k, _)), _) => link_index[k],
            (None, Some([0, other]) | Some([other, 0])) => other,
            (None, Some([a, b])) => {
                return Err(bad(
                    item,
                    format!(
                        "{field} names joint {n} of links {} and {}: say which holds the end \
                         with `link`",
                        plan.link_names[a], plan.link_names[b]
                    ),
                ))
            }
            (None, None) => {
                return Err(bad(
                    item,
                    format!("{field} names \"{n}\", which is neither a joint nor a point"),
                ))
            }
        },
        (None, At::Coords(_)) => {
            return Err(bad(
                item,
                format!("{field} gives coordinates without the `link` they are on"),
            ))
        }
    };
    let p = place(&anchor.at, names, link, link_index, item, field)?;
    Ok((link, frames[link].local(p)))
}
