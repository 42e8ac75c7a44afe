//! A crank-rocker four-bar: the crank O1A drives the rocker O3B through the coupler AB (one
//! RRR group).

use super::link::{reference_pose, xy, LinkMass};
use super::Mechanism;
use crate::error::Result;
use crate::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use crate::linkage::{Drive, Input, Joint, Link, Linkage, LoadSpec, Mode, Output};
use nalgebra::Point2;

/// A four-bar: the crank O1A, the RRR group of the coupler AB and the rocker O3B.
///
/// Its [`linkage`](FourBar::linkage) has the joints `O1`, `A`, `B`, `O3` and the links
/// `frame`, `crank` (O1A), `coupler` (AB) and `rocker` (O3B), whose angles are measured along
/// O1→A, A→B and O3→B. Link frames of [`LinkMass`]: the crank from O1 along O1A, the coupler
/// from A along AB, the rocker from O3 along O3B.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FourBar {
    /// O1, the crank's pivot, m.
    pub o1: Point2<f64>,
    /// O3, the rocker's pivot, m.
    pub o3: Point2<f64>,
    /// l_O1A, the crank, m.
    pub l1: f64,
    /// l_AB, the coupler, m.
    pub l2: f64,
    /// l_O3B, the rocker, m.
    pub l3: f64,
    /// Assembly mode (B to the left of A→O3 for `Plus`).
    #[cfg_attr(feature = "serde", serde(with = "super::serde_remote::BranchDef"))]
    pub branch: Branch,
    /// The mass properties of the crank, the coupler and the rocker.
    pub mass: [LinkMass; 3],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The magnitude of the resisting moment on the rocker, N·m: it opposes ω3 (zero when the
    /// rocker is at rest).
    pub resisting_moment: f64,
    /// How the crank is driven.
    pub drive: Drive,
}

impl FourBar {
    /// A crank-rocker of a course project: O1 = (0, 0), O3 = (0.40, 0.05) m, crank 0.10 m,
    /// coupler 0.35 m, rocker 0.30 m (Grashof, the crank the shortest link); uniform rods of
    /// 1.5 kg (coupler) and 2 kg (rocker), the crank 1 kg balanced about O1 (J = 0.002 kg·m²);
    /// g = 9.81 m/s²; 40 N·m resisting the rocker; driven through a coupling.
    #[must_use]
    pub fn course_example() -> Self {
        Self {
            o1: Point2::origin(),
            o3: Point2::new(0.40, 0.05),
            l1: 0.10,
            l2: 0.35,
            l3: 0.30,
            branch: Branch::Plus,
            mass: [
                LinkMass::on_line(1.0, 0.002, 0.0),
                LinkMass::rod(1.5, 0.35),
                LinkMass::rod(2.0, 0.30),
            ],
            gravity: 9.81,
            resisting_moment: 40.0,
            drive: Drive::Coupling,
        }
    }

    /// Grashof's classification of this four-bar (frame |O1O3|, crank, coupler, rocker).
    ///
    /// # Examples
    /// ```
    /// use tmm::{kinematics::Grashof, mechanism::FourBar};
    /// assert_eq!(FourBar::course_example().grashof()?, Grashof::CrankRocker);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`grashof`](crate::kinematics::grashof): a length that is not finite and positive.
    pub fn grashof(&self) -> Result<crate::kinematics::Grashof> {
        crate::kinematics::grashof((self.o3 - self.o1).norm(), self.l1, self.l2, self.l3)
    }
}

impl Mechanism for FourBar {
    /// The description for the engine, in a reference pose where the four-bar assembles
    /// (B as `branch` puts it). If it assembles nowhere, B is not finite and the error, that
    /// of [`Plan::new`](crate::linkage::Plan::new), names the joint.
    fn linkage(&self) -> Result<Linkage> {
        let pose = reference_pose(|phi| {
            let c = crank(self.o1, self.l1, Motion::new(phi, 0.0, 0.0))?;
            let g = rrr_dyad(
                c.a,
                PointMotion::fixed(self.o3),
                self.l2,
                self.l3,
                self.branch,
            )?;
            Ok(((c.a.p, g.b.p), g.det))
        });
        let (phi, (a, b)) = pose.unwrap_or_else(|| {
            let nan = Point2::new(f64::NAN, f64::NAN);
            (0.0, (self.o1 + self.l1 * crate::angle::unit(0.0), nan))
        });
        let (o1, o3) = (self.o1, self.o3);
        let dir = |p: Point2<f64>, q: Point2<f64>| crate::angle::direction(q - p);
        super::ready::planned(Linkage {
            name: "four-bar".to_owned(),
            joints: vec![
                Joint::revolute("O1", xy(o1)),
                Joint::revolute("A", xy(a)),
                Joint::revolute("B", xy(b)),
                Joint::revolute("O3", xy(o3)),
            ],
            links: vec![
                Link::new("frame", &["O1", "O3"]),
                Link::new("crank", &["O1", "A"]).with_mass(self.mass[0].at(xy(o1), phi)),
                Link::new("coupler", &["A", "B"]).with_mass(self.mass[1].at(xy(a), dir(a, b))),
                Link::new("rocker", &["O3", "B"]).with_mass(self.mass[2].at(xy(o3), dir(o3, b))),
            ],
            input: Input {
                link: "crank".to_owned(),
                drive: self.drive,
            },
            gravity: [0.0, -self.gravity],
            loads: vec![LoadSpec::Resistance {
                on: "rocker".to_owned(),
                forward: self.resisting_moment,
                backward: self.resisting_moment,
                at: None,
            }],
            groups: vec![["coupler".to_owned(), "rocker".to_owned()]],
            modes: vec![Mode {
                joint: "B".to_owned(),
                branch: self.branch,
            }],
            ..Linkage::default()
        })
    }

    /// The rocker's angle.
    fn output(&self) -> Output {
        Output::Angle("rocker".to_owned())
    }
}
