//! The synthesis module's only contact with the engine: a description's plan is made (so
//! every answer is one the engine accepts), and an output is read at given inputs (for the
//! structural error of a function generator).

use crate::error::Result;
use crate::kinematics::Motion;
use crate::linkage::{Linkage, Output, Plan};

/// Checks that the engine accepts `linkage` (its plan can be made).
pub(crate) fn accepted(linkage: &Linkage) -> Result<()> {
    Plan::new(linkage).map(|_| ())
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
