//! A slider-crank: the crank O1A drives the piston along a fixed guide through the connecting
//! rod AB (one RRP group), with the gas force of an indicator diagram.

use super::link::{reference_pose, xy, LinkMass};
use super::Mechanism;
use crate::angle::{direction, unit};
use crate::error::Result;
use crate::kinematics::{crank, rrp_dyad, Branch, Guide, Motion};
use crate::linkage::{
    Drive, IndicatorDiagram, Input, Joint, Link, Linkage, LoadSpec, Mode, Output,
};
use nalgebra::Point2;
use std::f64::consts::PI;

/// A slider-crank: the crank O1A, the RRP group of the connecting rod AB and the piston at B
/// on a fixed guide, optionally loaded by the gas pressure of an [`IndicatorDiagram`].
///
/// Its [`linkage`](SliderCrank::linkage) has the joints `O1`, `A`, `B` and the prismatic `P`
/// (the piston in its cylinder, at B, along the guide) and the links `frame`, `crank`, `rod`
/// and `piston`. The piston's slide is `P`'s. Link frames of [`LinkMass`]: the crank from O1
/// along O1A, the rod from A along AB, the piston at B along the guide. The cylinder head lies
/// on the piston's side of the crank (ahead along the guide for `branch = Plus`).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SliderCrank {
    /// O1, the crank's pivot, m.
    pub o1: Point2<f64>,
    /// l_O1A, the crank, m.
    pub l1: f64,
    /// l_AB, the connecting rod, m.
    pub l2: f64,
    /// A point of the piston's guide (the cylinder axis), m.
    pub guide_point: Point2<f64>,
    /// The direction angle of the guide, rad.
    pub guide_angle: f64,
    /// Assembly mode (B ahead of the foot of A along the guide for `Plus`).
    #[cfg_attr(feature = "serde", serde(with = "super::serde_remote::BranchDef"))]
    pub branch: Branch,
    /// The mass properties of the crank, the rod and the piston.
    pub mass: [LinkMass; 3],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The gas pressure on the piston, if any.
    pub diagram: Option<IndicatorDiagram>,
    /// How the crank is driven.
    pub drive: Drive,
}

impl SliderCrank {
    /// A single-stage horizontal air compressor: central slider-crank, crank 0.05 m, rod
    /// 0.20 m, piston 80 mm in diameter, air from 0.1 to 0.4 MPa (absolute, n = 1.3, 5 %
    /// clearance); crank 2.5 kg balanced about O1 (J = 0.004 kg·m²), rod 1.2 kg uniform,
    /// piston 0.8 kg; weights neglected in a horizontal machine's plane (g = 0); driven
    /// through a coupling (the examples turn it at 150 rad/s).
    #[must_use]
    pub fn course_example() -> Self {
        let area = PI * 0.08 * 0.08 / 4.0;
        Self {
            o1: Point2::origin(),
            l1: 0.05,
            l2: 0.20,
            guide_point: Point2::origin(),
            guide_angle: 0.0,
            branch: Branch::Plus,
            mass: [
                LinkMass::on_line(2.5, 0.004, 0.0),
                LinkMass::rod(1.2, 0.20),
                LinkMass::point(0.8),
            ],
            gravity: 0.0,
            diagram: Some(IndicatorDiagram::compressor(
                area, 1.0e5, 4.0e5, 1.0e5, 1.3, 0.05, 61,
            )),
            drive: Drive::Coupling,
        }
    }

    /// The course example driven through a gear pair instead of a coupling: a wheel of
    /// r_w = 0.15 m on the crank, the pitch point on the −x side of O1, α_w = 20°.
    #[must_use]
    pub fn geared_example() -> Self {
        Self {
            drive: Drive::Gear {
                pitch_radius: 0.15,
                pitch_angle: PI,
                pressure_angle: 20f64.to_radians(),
            },
            ..Self::course_example()
        }
    }
}

impl Mechanism for SliderCrank {
    /// The description for the engine, in a reference pose where the slider-crank assembles
    /// (B as `branch` puts it; not finite if it assembles nowhere, which
    /// [`Plan::new`](crate::linkage::Plan::new) rejects naming the joint).
    fn linkage(&self) -> Result<Linkage> {
        let guide = Guide::fixed(self.guide_point, self.guide_angle);
        let pose = reference_pose(|phi| {
            let c = crank(self.o1, self.l1, Motion::new(phi, 0.0, 0.0))?;
            let g = rrp_dyad(c.a, guide, self.l2, self.branch)?;
            Ok(((c.a.p, g.b.p), g.det))
        });
        let nan = Point2::new(f64::NAN, f64::NAN);
        let (phi, (a, b)) = pose.unwrap_or((0.0, (self.o1 + self.l1 * unit(0.0), nan)));
        let g = unit(self.guide_angle);
        let mut loads = Vec::new();
        if let Some(d) = &self.diagram {
            loads.push(LoadSpec::Indicator {
                joint: "P".to_owned(),
                diagram: d.clone(),
                head: self.branch.sign(),
            });
        }
        super::ready::planned(Linkage {
            name: "slider-crank".to_owned(),
            joints: vec![
                Joint::revolute("O1", xy(self.o1)),
                Joint::revolute("A", xy(a)),
                Joint::revolute("B", xy(b)),
                Joint::prismatic("P", xy(b), "frame", [g.x, g.y]),
            ],
            links: vec![
                Link::new("frame", &["O1", "P"]),
                Link::new("crank", &["O1", "A"]).with_mass(self.mass[0].at(xy(self.o1), phi)),
                Link::new("rod", &["A", "B"]).with_mass(self.mass[1].at(xy(a), direction(b - a))),
                Link::new("piston", &["B", "P"])
                    .with_mass(self.mass[2].at(xy(b), self.guide_angle)),
            ],
            input: Input {
                link: "crank".to_owned(),
                drive: self.drive,
            },
            gravity: [0.0, -self.gravity],
            loads,
            groups: vec![["rod".to_owned(), "piston".to_owned()]],
            modes: vec![Mode {
                joint: "B".to_owned(),
                branch: self.branch,
            }],
            ..Linkage::default()
        })
    }

    /// The piston's slide.
    fn output(&self) -> Output {
        Output::Slide("P".to_owned())
    }
}
