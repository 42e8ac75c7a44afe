//! The five hand-written chains of `tmm::mechanism` as they were before the linkage engine
//! (commit e98753d), kept as the reference the engine's results are checked against.
#![allow(dead_code, clippy::all)]

pub mod compressor;
pub mod drive;
pub mod four_bar;
pub mod link;
pub mod rocking_cylinder;
pub mod six_bar;
pub mod slider_crank;

use nalgebra::{Point2, Vector2};
use tmm::angle::{cross, unit};
use tmm::error::{Error, Result};
use tmm::kinematics::{
    extreme_positions, transfer_functions, Branch, Motion, PointMotion, Rotation, Strokes,
};
use tmm::linkage::IndicatorDiagram;

/// The input link's name in every ready mechanism, for errors and free bodies.
pub(crate) const CRANK: &str = "link 1 (crank)";

/// +1, −1, or 0 for a zero.
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Wraps an error of one part of a mechanism so that it names it.
pub(crate) fn within(part: &'static str) -> impl Fn(Error) -> Error {
    move |e| Error::In {
        part: part.to_owned(),
        source: Box::new(e),
    }
}

/// The strokes of an output coordinate.
pub(crate) fn output_strokes<F>(output: F, rotation: Rotation) -> Result<Strokes>
where
    F: Fn(Motion) -> Result<Motion>,
{
    let ext = extreme_positions(|phi| transfer_functions(&output, phi), 360)?;
    Strokes::new(&ext, rotation)
}

/// The piston of a slider-crank, for its gas force (the old `pressure::Piston`).
pub(crate) struct Piston {
    head: Vector2<f64>,
    foot: Point2<f64>,
    d_head: f64,
    d_crank: f64,
}

impl Piston {
    pub(crate) fn new(
        o1: Point2<f64>,
        l1: f64,
        l2: f64,
        guide_point: Point2<f64>,
        guide_angle: f64,
        branch: Branch,
    ) -> Result<Self> {
        let g = unit(guide_angle);
        let offset = cross(g, o1 - guide_point).abs();
        let gap = offset - (l2 - l1);
        if gap >= 0.0 || !gap.is_finite() {
            return Err(Error::NotAssemblable {
                group: "piston (crank cannot turn fully)",
                gap,
            });
        }
        Ok(Self {
            head: branch.sign() * g,
            foot: guide_point + (o1 - guide_point).dot(&g) * g,
            d_head: ((l1 + l2).powi(2) - offset * offset).sqrt(),
            d_crank: ((l2 - l1).powi(2) - offset * offset).sqrt(),
        })
    }

    pub(crate) fn gas_force(
        &self,
        diagram: &IndicatorDiagram,
        b: &PointMotion,
    ) -> Result<Vector2<f64>> {
        diagram.force(
            (b.p - self.foot).dot(&self.head),
            b.v.dot(&self.head),
            self.head,
            self.d_head,
            self.d_crank,
        )
    }
}
