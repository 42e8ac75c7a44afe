//! The range check of torsion springs, made once when a plan is made: a twist read in
//! (−π, π] jumps a turn where it passes ±π (between links that turn fully relative to each
//! other, or a spring whose free angle lies half a turn from where its links go), where its
//! moment would jump and its energy would not be conserved. Such a spring is refused by name.

use super::inputs::Inputs;
use super::plan::{InputPlan, LoadPlan, Plan};
use super::springs::TorsionPlan;
use crate::error::Result;
use crate::kinematics::Motion;
use std::f64::consts::PI;

/// How close to ±π a torsion spring's twist may come at the sampled positions, rad: more
/// than the twist moves between two samples of a linkage away from its singular positions.
const TWIST_MARGIN: f64 = 0.1;

/// Positions sampled per input: a crank over a full turn (those that assemble), a slider over
/// ±4 sizes about its reference.
const SAMPLES: [usize; 2] = [720, 96];

/// Refuses a torsion spring whose twist comes within [`TWIST_MARGIN`] of ±π (half a turn from
/// its free angle) at some position the inputs reach: there its reading in (−π, π] would jump
/// a turn. The inputs are sampled ([`SAMPLES`]: a crank over its turn, a slider over ±4 sizes,
/// two inputs on a grid) and every position that assembles is read; nothing is solved for a
/// plan without a torsion spring.
///
/// # Errors
/// [`Error::Description`](crate::Error::Description) naming the spring, its two links, the
/// input where its twist came nearest ±π and the twist there.
pub(crate) fn check_torsion(plan: &Plan) -> Result<()> {
    let springs: Vec<&TorsionPlan> = plan
        .loads
        .iter()
        .filter_map(|l| match l {
            LoadPlan::Torsion(t) => Some(t),
            _ => None,
        })
        .collect();
    if springs.is_empty() {
        return Ok(());
    }
    let n = SAMPLES[plan.chain.input_count() - 1];
    let axes: Vec<Vec<f64>> = plan
        .chain
        .inputs()
        .zip(plan.chain.reference_inputs())
        .map(|(ip, q0)| {
            let span = match ip {
                InputPlan::Crank { .. } => 2.0 * PI,
                InputPlan::Slider { .. } => 8.0 * plan.chain.size,
            };
            #[allow(clippy::cast_precision_loss)]
            (0..n)
                .map(|i| q0 - 0.5 * span + span * i as f64 / n as f64)
                .collect()
        })
        .collect();
    // Per spring: the largest |τ| seen and the inputs there.
    let mut worst = vec![(0.0f64, Vec::new()); springs.len()];
    let mut solver = plan.solver();
    let second = axes.get(1).map_or(&[f64::NAN][..], |a| &a[..]);
    for &q1 in &axes[0] {
        for &q2 in second {
            let inputs = if q2.is_nan() {
                Inputs::one(Motion::fixed(q1))
            } else {
                Inputs::two(Motion::fixed(q1), Motion::fixed(q2))
            };
            // A position that does not assemble is out of the inputs' range.
            let Ok(k) = solver.kinematics(inputs) else {
                continue;
            };
            let pose = k.pose();
            for (t, w) in springs.iter().zip(worst.iter_mut()) {
                let tau = t.twist(t.links.map(|l| pose.links[l].angle));
                if tau.abs() > w.0 {
                    *w = (
                        tau.abs(),
                        inputs.as_slice().iter().map(|m| m.value).collect(),
                    );
                }
            }
        }
    }
    for (t, (tau, at)) in springs.iter().zip(worst) {
        if tau > PI - TWIST_MARGIN {
            let [a, b] = t.links.map(|l| &plan.chain.link_names[l]);
            return Err(super::plan::bad(
                &t.name,
                format!(
                    "links {a} and {b} turn {:.1}° from its free angle at input {at:?} (within \
                     {:.1}° of half a turn): its twist, read in (−180°, 180°], would jump a \
                     turn there; a torsion spring is for links that turn less than half a \
                     turn either way from its free angle",
                    tau.to_degrees(),
                    (PI - tau).to_degrees()
                ),
            ));
        }
    }
    Ok(())
}
