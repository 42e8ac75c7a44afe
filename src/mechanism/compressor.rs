//! Seed 001's two-cylinder air compressor: one crank with two throws O1A and O1C drives two
//! pistons through two RRP groups.

use super::link::{reference_pose, xy, LinkMass};
use super::Mechanism;
use crate::angle::{direction, unit};
use crate::error::Result;
use crate::kinematics::{crank, rrp_dyad, Branch, Guide, Motion};
use crate::linkage::{
    Drive, IndicatorDiagram, Input, Joint, Link, Linkage, LoadSpec, Mode, Output,
};
use nalgebra::Point2;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A two-cylinder compressor: the crank with the throws O1A and O1C (the second turned by
/// `throw_angle` from the first), the RRP group of rod 1 (AB) and piston 1 at B, and the RRP
/// group of rod 2 (CD) and piston 2 at D, each piston on its own fixed guide through
/// `guide_point`.
///
/// Its [`linkage`](Compressor::linkage) has the joints `O1`, `A`, `C`, `B`, `D` and the
/// prismatic `P1` (at B) and `P2` (at D), and the links `frame`, `crank` (angle along O1→A),
/// `rod 1`, `piston 1`, `rod 2`, `piston 2`. Link frames of [`LinkMass`]: the crank from O1
/// along O1A, rod 1 from A along AB, rod 2 from C along CD, the pistons at B and D along
/// their guides.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Compressor {
    /// O1, the crank's pivot, m.
    pub o1: Point2<f64>,
    /// l_O1A = l_O1C, the crank throws, m.
    pub l1: f64,
    /// The angle from the throw O1A to the throw O1C, rad (π in seed 001).
    pub throw_angle: f64,
    /// l_AB, the first connecting rod, m.
    pub l2: f64,
    /// l_CD, the second connecting rod, m.
    pub l4: f64,
    /// A point of both guides (the cylinders' axes cross it), m.
    pub guide_point: Point2<f64>,
    /// The direction angles of the guides of pistons 1 and 2, rad.
    pub guide_angles: [f64; 2],
    /// Assembly modes of the two RRP groups (as [`SliderCrank::branch`](super::SliderCrank)).
    #[cfg_attr(feature = "serde", serde(with = "branches"))]
    pub branches: [Branch; 2],
    /// The mass properties of the crank, rod 1, piston 1, rod 2, piston 2.
    pub mass: [LinkMass; 5],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The indicator diagrams of the cylinders of pistons 1 and 2.
    pub diagrams: [Option<IndicatorDiagram>; 2],
    /// How the crank is driven.
    pub drive: Drive,
}

#[cfg(feature = "serde")]
mod branches {
    use super::super::serde_remote::BranchDef;
    use crate::kinematics::Branch;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    struct B(#[serde(with = "BranchDef")] Branch);

    pub(super) fn serialize<S: Serializer>(b: &[Branch; 2], s: S) -> Result<S::Ok, S::Error> {
        [B(b[0]), B(b[1])].serialize(s)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[Branch; 2], D::Error> {
        let [B(x), B(y)] = <[B; 2]>::deserialize(d)?;
        Ok([x, y])
    }
}

impl Compressor {
    /// Seed 001's compressor (its geometry l1 = 0.06 m, l2 = l4 = 0.24 m, l_AS2 = 0.08 m,
    /// both cylinders along +y above O, throws at 180°; it turns clockwise at 960 rpm in the
    /// examples) with realistic two-stage loads: cylinder 1 of 120 mm bore from 0.1 to 0.3 MPa,
    /// cylinder 2 of 70 mm bore from 0.3 to 0.8 MPa (absolute, n = 1.3, 5 % clearance); crank
    /// 6 kg balanced about O (J = 0.02 kg·m²); rods 2 kg with S 0.08 m from the crank pin and
    /// J_S = 0.012 kg·m²; pistons 1.5 kg and 0.9 kg; g = 9.81 m/s²; driven through a coupling.
    #[must_use]
    pub fn course_example() -> Self {
        let area = |d: f64| PI * d * d / 4.0;
        let rod = LinkMass::on_line(2.0, 0.012, 0.08);
        Self {
            o1: Point2::origin(),
            l1: 0.06,
            throw_angle: PI,
            l2: 0.24,
            l4: 0.24,
            guide_point: Point2::origin(),
            guide_angles: [FRAC_PI_2, FRAC_PI_2],
            branches: [Branch::Plus, Branch::Plus],
            mass: [
                LinkMass::on_line(6.0, 0.02, 0.0),
                rod,
                LinkMass::point(1.5),
                rod,
                LinkMass::point(0.9),
            ],
            gravity: 9.81,
            diagrams: [
                Some(IndicatorDiagram::compressor(
                    area(0.12),
                    1.0e5,
                    3.0e5,
                    1.0e5,
                    1.3,
                    0.05,
                    61,
                )),
                Some(IndicatorDiagram::compressor(
                    area(0.07),
                    3.0e5,
                    8.0e5,
                    1.0e5,
                    1.3,
                    0.05,
                    61,
                )),
            ],
            drive: Drive::Coupling,
        }
    }

    /// The seed's crank speed, 960 rpm clockwise, as ω1 in the crate's convention (rad/s,
    /// negative: clockwise).
    #[must_use]
    pub fn seed_speed() -> f64 {
        -960.0 * TAU / 60.0
    }
}

impl Mechanism for Compressor {
    /// The description for the engine, in a reference pose where both groups assemble (B
    /// and D as `branches` put them; not finite if it assembles nowhere, which
    /// [`Plan::new`](crate::linkage::Plan::new) rejects naming the joint).
    fn linkage(&self) -> Result<Linkage> {
        let guides = self.guide_angles.map(|a| Guide::fixed(self.guide_point, a));
        let (st, ct) = self.throw_angle.sin_cos();
        let pose = reference_pose(|phi| {
            let c = crank(self.o1, self.l1, Motion::new(phi, 0.0, 0.0))?;
            let pin_c = c.link.point_at(self.l1 * ct, self.l1 * st);
            let g23 = rrp_dyad(c.a, guides[0], self.l2, self.branches[0])?;
            let g45 = rrp_dyad(pin_c, guides[1], self.l4, self.branches[1])?;
            let q = g23.det.abs().min(g45.det.abs());
            Ok(((c.a.p, pin_c.p, g23.b.p, g45.b.p), q))
        });
        let nan = Point2::new(f64::NAN, f64::NAN);
        let (phi, (a, c, b, d)) = pose.unwrap_or((0.0, (nan, nan, nan, nan)));
        let (ga, gb) = (unit(self.guide_angles[0]), unit(self.guide_angles[1]));
        let mut loads = Vec::new();
        for (k, joint) in ["P1", "P2"].iter().enumerate() {
            if let Some(diagram) = &self.diagrams[k] {
                loads.push(LoadSpec::Indicator {
                    joint: (*joint).to_owned(),
                    diagram: diagram.clone(),
                    head: self.branches[k].sign(),
                });
            }
        }
        let m = &self.mass;
        super::ready::planned(Linkage {
            name: "two-cylinder compressor".to_owned(),
            joints: vec![
                Joint::revolute("O1", xy(self.o1)),
                Joint::revolute("A", xy(a)),
                Joint::revolute("C", xy(c)),
                Joint::revolute("B", xy(b)),
                Joint::revolute("D", xy(d)),
                Joint::prismatic("P1", xy(b), "frame", [ga.x, ga.y]),
                Joint::prismatic("P2", xy(d), "frame", [gb.x, gb.y]),
            ],
            links: vec![
                Link::new("frame", &["O1", "P1", "P2"]),
                Link::new("crank", &["O1", "A", "C"]).with_mass(m[0].at(xy(self.o1), phi)),
                Link::new("rod 1", &["A", "B"]).with_mass(m[1].at(xy(a), direction(b - a))),
                Link::new("piston 1", &["B", "P1"]).with_mass(m[2].at(xy(b), self.guide_angles[0])),
                Link::new("rod 2", &["C", "D"]).with_mass(m[3].at(xy(c), direction(d - c))),
                Link::new("piston 2", &["D", "P2"]).with_mass(m[4].at(xy(d), self.guide_angles[1])),
            ],
            input: Input {
                link: "crank".to_owned(),
                drive: self.drive,
            },
            gravity: [0.0, -self.gravity],
            loads,
            groups: vec![
                ["rod 1".to_owned(), "piston 1".to_owned()],
                ["rod 2".to_owned(), "piston 2".to_owned()],
            ],
            modes: vec![
                Mode {
                    joint: "B".to_owned(),
                    branch: self.branches[0],
                },
                Mode {
                    joint: "D".to_owned(),
                    branch: self.branches[1],
                },
            ],
            ..Linkage::default()
        })
    }

    /// The slide of piston 1.
    fn output(&self) -> Output {
        Output::Slide("P1".to_owned())
    }
}
