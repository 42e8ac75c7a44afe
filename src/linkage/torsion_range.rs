//! The range check of torsion springs, made once when a plan is made: a twist read in
//! (−π, π] jumps a turn where it passes ±π (between links that turn fully relative to each
//! other, or a spring whose free angle lies half a turn from where its links go), where its
//! moment would jump and its energy would not be conserved. Such a spring is refused by name.
//!
//! # By continuity
//! With one input the twist is followed continuously over the input's whole range: a crank
//! that turns fully over a turn from its reference angle, a rocking crank from its reference
//! angle to each of its lock positions (exact, from [`Plan::lock_positions`]), a slider over
//! ±4 sizes or up to where it stops assembling (bisected to 1e-12 of the size). Each step
//! adds the change of the reading brought into (−π, π]; a step whose reading changes by more
//! than [`MAX_STEP_TWIST`] is halved, so the sum is the twist itself (a continuous function
//! of the input; it cannot change by a turn within a step without passing through a larger
//! change at half the step) and no wrap between samples is missed: a pair of links that turns
//! fully relative to each other over the course shows a twist of a whole turn. The positions
//! are read by [`Plan::position`], so a lock or dead position itself is read (where the rates
//! do not exist). Two inputs are sampled on a grid.
//!
//! # Why a grid for two inputs, and its error
//! The exact extreme of a twist over a two-input workspace lies at a stationary point of the
//! twist inside the workspace (both partial derivatives zero: two equations in the two inputs
//! through the linkage's whole position solve), on a boundary curve of the workspace (where
//! some group stops assembling) or at a corner; no closed form gives these for a general
//! linkage, and a solve of them would need every branch of the boundary. The grid bounds it
//! instead: every position of the workspace is within h·√2/2 of a grid point (h the grid's
//! step: 2π/96 ≈ 0.065 rad for a crank, 8 sizes/96 for a slider), so the twist read on the
//! grid misses its extreme by at most h·√2/2·G, G the largest norm of the twist's gradient
//! over the two inputs (|∇τ| = √((∂τ/∂q₁)² + (∂τ/∂q₂)²), rad per rad). The refusal's margin
//! [`TWIST_MARGIN`] = 0.1 rad covers that for G up to about 2.2 (crank inputs). The bound
//! assumes the nearest grid point assembles: near the boundary of the workspace the nearest
//! grid point that does can be farther than h·√2/2, and a spring closer than the grid can see
//! to ±π there, or near a singular position of the linkage (where G grows without bound), is
//! not caught by this check.

use super::inputs::Inputs;
use super::plan::{InputPlan, LoadPlan, Plan};
use super::springs::{wrap, TorsionPlan};
use crate::error::Result;
use crate::kinematics::Motion;
use std::f64::consts::PI;

/// How close to ±π a torsion spring's twist may come at the sampled positions, rad: more
/// than the twist moves between two samples of a linkage away from its singular positions.
const TWIST_MARGIN: f64 = 0.1;

/// Positions sampled per input: a crank over a full turn (those that assemble), a slider over
/// ±4 sizes about its reference (two inputs: a grid of 96 × 96).
const SAMPLES: [usize; 2] = [720, 96];

/// The largest change of a twist's reading over one step of the continuous following, rad;
/// larger changes halve the step.
const MAX_STEP_TWIST: f64 = 0.25;

/// Refuses a torsion spring whose twist comes within [`TWIST_MARGIN`] of ±π (half a turn from
/// its free angle) at some position the inputs reach: there its reading in (−π, π] would jump
/// a turn. One input: the twist followed by continuity over the input's range (module docs);
/// two inputs: sampled on a grid ([`SAMPLES`]). Nothing is solved for a plan without a
/// torsion spring.
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
    let worst = if plan.chain.input_count() == 1 {
        followed(plan, &springs)
    } else {
        sampled(plan, &springs)
    };
    for (t, (tau, at)) in springs.iter().zip(worst) {
        if tau > PI - TWIST_MARGIN {
            let [a, b] = t.links.map(|l| &plan.chain.link_names[l]);
            return Err(super::plan::bad(
                &t.name,
                format!(
                    "links {a} and {b} turn {:.1}° from its free angle at input {at:?} ({}): \
                     its twist, read in (−180°, 180°], would jump a turn there; a torsion \
                     spring is for links that turn less than half a turn either way from its \
                     free angle",
                    tau.to_degrees(),
                    if tau < PI {
                        format!("within {:.1}° of half a turn", (PI - tau).to_degrees())
                    } else {
                        "past half a turn".to_owned()
                    }
                ),
            ));
        }
    }
    Ok(())
}

/// Per spring, the largest |twist| over the input's range and the input there, following the
/// twist by continuity (module docs).
fn followed(plan: &Plan, springs: &[&TorsionPlan]) -> Vec<(f64, Vec<f64>)> {
    let q0 = plan.chain.reference_inputs()[0];
    let read = |q: f64| -> Option<Vec<f64>> {
        let at = plan.position(Motion::fixed(q)).ok()?;
        let pose = at.pose().pose();
        let tau: Vec<f64> = springs
            .iter()
            .map(|t| t.twist(t.links.map(|l| pose.links[l].angle)))
            .collect();
        tau.iter().all(|x| x.is_finite()).then_some(tau)
    };
    let mut worst = vec![(0.0f64, vec![q0]); springs.len()];
    let Some(start) = read(q0) else {
        return worst;
    };
    for (w, &t) in worst.iter_mut().zip(&start) {
        w.0 = t.abs();
    }
    let crank = matches!(plan.chain.input, InputPlan::Crank { .. });
    let ends = if crank {
        match plan.lock_positions(q0) {
            Ok(Some((lo, hi))) => vec![hi, lo],
            _ => vec![q0 + 2.0 * PI],
        }
    } else {
        let span = 4.0 * plan.chain.size;
        vec![q0 + span, q0 - span]
    };
    let tiny = 1e-12
        * if crank {
            q0.abs().max(1.0)
        } else {
            plan.chain.size
        };
    let base = 2.0 * PI / SAMPLES[0] as f64 * if crank { 1.0 } else { plan.chain.size };
    for to in ends {
        follow(&read, q0, to, &start, base, tiny, &mut worst);
    }
    worst
}

/// Follows the twists from `from` (where they read `start`) towards `to`, in steps of at most
/// `base`, halved where a reading changes by more than [`MAX_STEP_TWIST`] or the linkage does
/// not assemble (down to `tiny`: there the range ends), updating `worst`.
fn follow(
    read: &dyn Fn(f64) -> Option<Vec<f64>>,
    from: f64,
    to: f64,
    start: &[f64],
    base: f64,
    tiny: f64,
    worst: &mut [(f64, Vec<f64>)],
) {
    let dir = (to - from).signum();
    let (mut q, mut h) = (from, base);
    let (mut last, mut tau) = (start.to_vec(), start.to_vec());
    while dir * (to - q) > 0.0 {
        let next = if dir * (to - q) <= h { to } else { q + dir * h };
        let Some(r) = read(next) else {
            if h <= tiny {
                return;
            }
            h *= 0.5;
            continue;
        };
        let d: Vec<f64> = r.iter().zip(&last).map(|(x, y)| wrap(x - y)).collect();
        if h > tiny && d.iter().any(|x| x.abs() > MAX_STEP_TWIST) {
            h *= 0.5;
            continue;
        }
        for ((t, w), dt) in tau.iter_mut().zip(worst.iter_mut()).zip(&d) {
            *t += dt;
            if t.abs() > w.0 {
                *w = (t.abs(), vec![next]);
            }
        }
        (q, last) = (next, r);
        h = (2.0 * h).min(base);
    }
}

/// Per spring, the largest |twist| read on a grid of the inputs ([`SAMPLES`]) and the inputs
/// there.
fn sampled(plan: &Plan, springs: &[&TorsionPlan]) -> Vec<(f64, Vec<f64>)> {
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
    worst
}
