//! A six-bar of a crank, an RRR group and an RRP group (seed 001, figure 2.10's type): the
//! crank O1A drives the rocker O2B through the coupler AB; a point C of the rocker drives the
//! slider along a fixed guide through the rod CD.

use super::link::{reference_pose, xy, LinkMass};
use super::Mechanism;
use crate::angle::{direction, unit};
use crate::error::{Error, Result};
use crate::kinematics::{crank, rrp_dyad, rrr_dyad, Branch, Guide, Motion, PointMotion};
use crate::linkage::{Drive, Input, Joint, Link, Linkage, LoadSpec, Mode, Output};
use nalgebra::Point2;

/// A crank–rocker–slider six-bar: the crank O1A, the RRR group of the coupler AB and the
/// rocker O2B (carrying C), the RRP group of the rod CD and the slider at D on a fixed guide.
///
/// Its [`linkage`](SixBar::linkage) has the joints `O1`, `A`, `B`, `O2`, `C`, `D` and the
/// prismatic `Q` (the slider on its guide, at D), and the links `frame`, `crank`, `coupler`,
/// `rocker` (angle along O2→B), `rod` and `slider`. Link frames of [`LinkMass`]: the crank
/// from O1 along O1A, the coupler from A along AB, the rocker from O2 along O2B, the rod from
/// C along CD, the slider at D along the guide.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SixBar {
    /// O1, the crank's pivot, m.
    pub o1: Point2<f64>,
    /// O2, the rocker's pivot, m.
    pub o2: Point2<f64>,
    /// l_O1A, the crank, m.
    pub l1: f64,
    /// l_AB, the coupler, m.
    pub l2: f64,
    /// l_O2B, the rocker, m.
    pub l3: f64,
    /// C on the rocker: its distance from O2 along O2B, m.
    pub c_along: f64,
    /// C on the rocker: its distance to the left of O2B, m.
    pub c_across: f64,
    /// l_CD, the rod of the slider, m.
    pub l4: f64,
    /// A point of the slider's fixed guide, m.
    pub guide_point: Point2<f64>,
    /// The direction angle of the guide, rad.
    pub guide_angle: f64,
    /// Assembly mode of the RRR group (B to the left of A→O2 for `Plus`).
    #[cfg_attr(feature = "serde", serde(with = "super::serde_remote::BranchDef"))]
    pub branch23: Branch,
    /// Assembly mode of the RRP group (D ahead of the foot of C along the guide for `Plus`).
    #[cfg_attr(feature = "serde", serde(with = "super::serde_remote::BranchDef"))]
    pub branch45: Branch,
    /// The mass properties of the crank, coupler, rocker, rod and slider.
    pub mass: [LinkMass; 5],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The resistance on the slider during the working stroke, N (it opposes the slider's
    /// velocity while the slider moves in the working direction, and is zero on the return).
    pub resistance: f64,
    /// The working direction: +1 when the slider works moving along the guide direction
    /// (ṡ > 0), −1 against it (only its sign counts; it must be finite and non-zero).
    pub working_direction: f64,
    /// How the crank is driven.
    pub drive: Drive,
}

impl SixBar {
    /// A course-project six-bar (a crank-rocker driving a horizontal slider, the type of seed
    /// 001's figure 2.10), crank at 10 rad/s counter-clockwise in the examples:
    /// O1 = (0, 0), O2 = (0.30, 0) m; O1A = 0.08, AB = 0.28, O2B = 0.20 m; C on the rocker's
    /// line 0.30 m from O2; CD = 0.35 m; the guide y = 0.40 m along +x. Masses: crank 2 kg
    /// balanced about O1 (J = 0.005 kg·m²), uniform rods of 4 kg (coupler), 5 kg (rocker,
    /// 0.30 m), 3 kg (rod CD), slider 20 kg; g = 9.81 m/s²; 2 kN resistance on the working
    /// stroke, which is the slider's motion along −x; driven through a coupling.
    #[must_use]
    pub fn course_example() -> Self {
        Self {
            o1: Point2::origin(),
            o2: Point2::new(0.30, 0.0),
            l1: 0.08,
            l2: 0.28,
            l3: 0.20,
            c_along: 0.30,
            c_across: 0.0,
            l4: 0.35,
            guide_point: Point2::new(0.0, 0.40),
            guide_angle: 0.0,
            branch23: Branch::Plus,
            branch45: Branch::Plus,
            mass: [
                LinkMass::on_line(2.0, 0.005, 0.0),
                LinkMass::rod(4.0, 0.28),
                LinkMass::rod(5.0, 0.30),
                LinkMass::rod(3.0, 0.35),
                LinkMass::point(20.0),
            ],
            gravity: 9.81,
            resistance: 2000.0,
            working_direction: -1.0,
            drive: Drive::Coupling,
        }
    }
}

impl Mechanism for SixBar {
    /// The description for the engine, in a reference pose where both groups assemble (B
    /// and D as the branches put them; not finite if it assembles nowhere, which
    /// [`Plan::new`](crate::linkage::Plan::new) rejects naming the joint). The working-stroke
    /// resistance is a [`LoadSpec::Resistance`] on `Q`, zero in the direction opposite
    /// `working_direction`.
    ///
    /// # Errors
    /// [`Error::In`] naming `"slider"` for a `working_direction` that is zero or not finite.
    fn linkage(&self) -> Result<Linkage> {
        if !(self.working_direction.is_finite() && self.working_direction != 0.0) {
            return Err(Error::In {
                part: "slider".to_owned(),
                source: Box::new(Error::OutOfRange {
                    name: "working direction",
                    value: self.working_direction,
                    min: -1.0,
                    max: 1.0,
                    ends: crate::Ends::Closed,
                }),
            });
        }
        let guide = Guide::fixed(self.guide_point, self.guide_angle);
        let pose = reference_pose(|phi| {
            let c = crank(self.o1, self.l1, Motion::new(phi, 0.0, 0.0))?;
            let o2 = PointMotion::fixed(self.o2);
            let g23 = rrr_dyad(c.a, o2, self.l2, self.l3, self.branch23)?;
            let pc = g23.link3.point_at(self.c_along, self.c_across);
            let g45 = rrp_dyad(pc, guide, self.l4, self.branch45)?;
            let q = g23.det.abs().min(g45.det.abs());
            Ok(((c.a.p, g23.b.p, pc.p, g45.b.p), q))
        });
        let nan = Point2::new(f64::NAN, f64::NAN);
        let (phi, (a, b, c, d)) = pose.unwrap_or((0.0, (nan, nan, nan, nan)));
        let g = unit(self.guide_angle);
        let (forward, backward) = if self.working_direction > 0.0 {
            (self.resistance, 0.0)
        } else {
            (0.0, self.resistance)
        };
        let m = &self.mass;
        super::ready::planned(Linkage {
            name: "six-bar".to_owned(),
            joints: vec![
                Joint::revolute("O1", xy(self.o1)),
                Joint::revolute("A", xy(a)),
                Joint::revolute("B", xy(b)),
                Joint::revolute("O2", xy(self.o2)),
                Joint::revolute("C", xy(c)),
                Joint::revolute("D", xy(d)),
                Joint::prismatic("Q", xy(d), "frame", [g.x, g.y]),
            ],
            links: vec![
                Link::new("frame", &["O1", "O2", "Q"]),
                Link::new("crank", &["O1", "A"]).with_mass(m[0].at(xy(self.o1), phi)),
                Link::new("coupler", &["A", "B"]).with_mass(m[1].at(xy(a), direction(b - a))),
                Link::new("rocker", &["O2", "B", "C"])
                    .with_mass(m[2].at(xy(self.o2), direction(b - self.o2))),
                Link::new("rod", &["C", "D"]).with_mass(m[3].at(xy(c), direction(d - c))),
                Link::new("slider", &["D", "Q"]).with_mass(m[4].at(xy(d), self.guide_angle)),
            ],
            input: Input {
                link: "crank".to_owned(),
                drive: self.drive,
            },
            gravity: [0.0, -self.gravity],
            loads: vec![LoadSpec::Resistance {
                on: "Q".to_owned(),
                forward,
                backward,
                at: None,
            }],
            groups: vec![
                ["coupler".to_owned(), "rocker".to_owned()],
                ["rod".to_owned(), "slider".to_owned()],
            ],
            modes: vec![
                Mode {
                    joint: "B".to_owned(),
                    branch: self.branch23,
                },
                Mode {
                    joint: "D".to_owned(),
                    branch: self.branch45,
                },
            ],
            ..Linkage::default()
        })
    }

    /// The slider's slide.
    fn output(&self) -> Output {
        Output::Slide("Q".to_owned())
    }
}
