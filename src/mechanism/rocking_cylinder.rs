//! A crank-driven RPR drive: the crank O1A drives a rod (piston rod, or slider block) that
//! slides in a cylinder (or slotted lever) rocking about the frame pivot C: an
//! oscillating-cylinder pump, or a crank and slotted lever.

use super::link::{reference_pose, xy, LinkMass};
use super::Mechanism;
use crate::angle::direction;
use crate::error::Result;
use crate::kinematics::{crank, rpr_dyad, Motion, PointMotion};
use crate::linkage::{At, Drive, Input, Joint, Link, Linkage, LoadSpec, Output};
use nalgebra::Point2;

/// A crank and an RPR group: the crank O1A, the rod hinged at A sliding along the axis of the
/// cylinder, which rocks about the frame pivot C (the axis passes through C).
///
/// The fluid in the cylinder resists the sliding: while the rod moves in (l_AC decreasing)
/// it pushes the rod out with `force_in`, while it moves out it pulls the rod in with
/// `force_out`; the cylinder takes the opposite force along the same axis, at the piston P,
/// `l_piston` from A along A→C.
///
/// Its [`linkage`](RockingCylinder::linkage) has the joints `O1`, `A`, `C` and the prismatic
/// `Q` (the rod in the cylinder, at A, its slide growing as the rod comes out along C→A), the
/// links `frame`, `crank`, `rod` (with the point `P`, the piston; angle along A→C) and
/// `cylinder` (angle along C→A). The fluid is a [`LoadSpec::Resistance`] on `Q` at `P`:
/// `forward = force_out`, `backward = force_in`. Link frames of [`LinkMass`]: the crank from
/// O1 along O1A, the rod from A along A→C, the cylinder from C along C→A.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RockingCylinder {
    /// O1, the crank's pivot, m.
    pub o1: Point2<f64>,
    /// C, the cylinder's pivot, m.
    pub c: Point2<f64>,
    /// l_O1A, the crank, m.
    pub l1: f64,
    /// The distance of the piston from A along the rod, m.
    pub l_piston: f64,
    /// The mass properties of the crank, the rod and the cylinder.
    pub mass: [LinkMass; 3],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The fluid force while the rod moves into the cylinder, N (≥ 0: it resists).
    pub force_in: f64,
    /// The fluid force while the rod moves out of the cylinder, N (≥ 0: it resists).
    pub force_out: f64,
    /// How the crank is driven.
    pub drive: Drive,
}

impl RockingCylinder {
    /// An oscillating-cylinder pump: O1 = (0, 0), C = (0.35, 0) m, crank 0.10 m, piston
    /// 0.20 m from A; crank 1.5 kg balanced (J = 0.003 kg·m²), rod 1 kg with S 0.10 m from A
    /// (J_S = 0.004 kg·m²), cylinder 3 kg with S 0.12 m from C (J_S = 0.02 kg·m²);
    /// g = 9.81 m/s²; 1.5 kN on the pressure stroke (in), 0.3 kN on suction (out); driven
    /// through a coupling (20 rad/s in the examples).
    #[must_use]
    pub fn course_example() -> Self {
        Self {
            o1: Point2::origin(),
            c: Point2::new(0.35, 0.0),
            l1: 0.10,
            l_piston: 0.20,
            mass: [
                LinkMass::on_line(1.5, 0.003, 0.0),
                LinkMass::on_line(1.0, 0.004, 0.10),
                LinkMass::on_line(3.0, 0.02, 0.12),
            ],
            gravity: 9.81,
            force_in: 1500.0,
            force_out: 300.0,
            drive: Drive::Coupling,
        }
    }
}

impl Mechanism for RockingCylinder {
    /// The description for the engine, in a reference pose where A is off C (not finite if
    /// there is none, which [`Plan::new`](crate::linkage::Plan::new) rejects naming the joint).
    fn linkage(&self) -> Result<Linkage> {
        let size = self.l1 + (self.c - self.o1).norm();
        let pose = reference_pose(|phi| {
            let k = crank(self.o1, self.l1, Motion::new(phi, 0.0, 0.0))?;
            let g = rpr_dyad(k.a, PointMotion::fixed(self.c))?;
            Ok((k.a.p, g.slide.value / size))
        });
        let (phi, a) = pose.unwrap_or((0.0, Point2::new(f64::NAN, f64::NAN)));
        let c = self.c;
        let (to_c, out) = (c - a, a - c);
        let p = a + self.l_piston * to_c / to_c.norm();
        super::ready::planned(Linkage {
            name: "rocking cylinder".to_owned(),
            joints: vec![
                Joint::revolute("O1", xy(self.o1)),
                Joint::revolute("A", xy(a)),
                Joint::revolute("C", xy(c)),
                Joint::prismatic("Q", xy(a), "cylinder", [out.x, out.y]),
            ],
            links: vec![
                Link::new("frame", &["O1", "C"]),
                Link::new("crank", &["O1", "A"]).with_mass(self.mass[0].at(xy(self.o1), phi)),
                Link::new("rod", &["A", "Q"])
                    .with_point("P", xy(p))
                    .with_mass(self.mass[1].at(xy(a), direction(to_c))),
                Link::new("cylinder", &["C", "Q"])
                    .with_mass(self.mass[2].at(xy(c), direction(out))),
            ],
            input: Input {
                link: "crank".to_owned(),
                drive: self.drive,
            },
            gravity: [0.0, -self.gravity],
            loads: vec![LoadSpec::Resistance {
                on: "Q".to_owned(),
                forward: self.force_out,
                backward: self.force_in,
                at: Some(At::name("P")),
            }],
            groups: vec![["rod".to_owned(), "cylinder".to_owned()]],
            ..Linkage::default()
        })
    }

    /// The cylinder's swing (its angle).
    fn output(&self) -> Output {
        Output::Angle("cylinder".to_owned())
    }
}
