//! The synthesis module's only contact with the engine: a description's plan is made (so
//! every answer is one the engine accepts), and an output is read at given inputs (for the
//! structural error of a function generator).

use super::coordinate;
use crate::error::Result;
use crate::kinematics::Motion;
use crate::linkage::{Linkage, Output, Plan};

/// Checks that the engine accepts `linkage`: its joints lie within [`MAX_LENGTH`](super::MAX_LENGTH) of the
/// origin, its plan can be made, and the engine solves it at its reference pose.
pub(crate) fn accepted(linkage: &Linkage) -> Result<()> {
    for j in &linkage.joints {
        for x in j.at {
            coordinate("a joint of the synthesised linkage (m)", x)?;
        }
    }
    let plan = Plan::new(linkage)?;
    plan.kinematics(Motion::fixed(plan.reference_input()))?;
    Ok(())
}

/// The values of `output` at each input angle (rad), by the engine.
pub(crate) fn output_values(
    linkage: &Linkage,
    output: &Output,
    inputs: &[f64],
) -> Result<Vec<f64>> {
    let plan = Plan::new(linkage)?;
    inputs
        .iter()
        .map(|&phi| plan.output(output, Motion::fixed(phi)).map(|m| m.value))
        .collect()
}
