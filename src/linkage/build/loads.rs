#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The loads of a plan: each of the description's loads checked and placed on its link, and
//! the dead centres of every piston under an indicator diagram found on the kinematic chain
//! (which is built and checked first), so a load is complete when it enters the plan.

use super::reference::{finite_num, finite_pair, non_negative, place, Frame, Names};
use crate::error::Result;
use crate::kinematics::{extreme_positions, transfer_functions, Motion};
use crate::linkage::description::{At, LoadSpec};
use crate::linkage::indicator::IndicatorDiagram;
use crate::linkage::plan::{bad, Chain, LoadPlan};
use crate::linkage::solve::state::KinState;
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
                    format!("diagram.area must be > 0, got {}", diagram.area),
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
    }))
}
