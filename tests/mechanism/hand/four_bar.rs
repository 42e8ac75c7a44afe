// A crank-rocker four-bar: the crank O1A drives the rocker O3B through the coupler AB (one
// RRR group).

use super::drive::{Balance, Drive};
use super::link::{own_loads, LinkMass};
use super::{output_strokes, sign, within, CRANK};
use nalgebra::{Point2, Vector2};
use tmm::error::Result;
use tmm::kinematics::{
    crank, rrr_dyad, Branch, CrankState, Motion, PointMotion, Rotation, RrrState, Strokes,
};
use tmm::kinetostatics::RrrDyad;
use tmm::Load;

/// The links' names, for errors and free bodies.
const LINKS: [&str; 3] = [CRANK, "link 2 (coupler)", "link 3 (rocker)"];
const GROUP_23: &str = "group II(2,3) RRR";

/// A four-bar: input link 1 (O1A), RRR group II(2,3) (coupler 2 = AB, rocker 3 = O3B).
///
/// Link frames: link 1 from O1 along O1A, link 2 from A along AB, link 3 from O3 along O3B.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    pub branch: Branch,
    /// The mass properties of links 1 to 3.
    pub mass: [LinkMass; 3],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The magnitude of the resisting moment on the rocker, N·m: it opposes ω3 (zero when the
    /// rocker is at rest).
    pub resisting_moment: f64,
    /// How the crank is driven.
    pub drive: Drive,
}

/// One analysed position of a [`FourBar`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FourBarPosition {
    /// φ1, ω1, ε1.
    pub input: Motion,
    /// The crank and its pin A.
    pub crank: CrankState,
    /// The RRR group: B, coupler 2, rocker 3.
    pub group23: RrrState,
    /// The own loads of links 1–3 (inertia and weight) at their centres of mass.
    pub loads: [Load; 3],
    /// The resisting moment on the rocker, N·m.
    pub rocker_moment: f64,
    /// R12, the crank on the coupler at A, N.
    pub r12: Vector2<f64>,
    /// R23, the coupler on the rocker at B, N.
    pub r23: Vector2<f64>,
    /// R03, the frame on the rocker at O3, N.
    pub r03: Vector2<f64>,
    /// The balancing moment (or force) and R01.
    pub balance: Balance,
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

    /// The kinematics alone: crank and RRR group.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn kinematics(&self, input: Motion) -> Result<(CrankState, RrrState)> {
        let crank = crank(self.o1, self.l1, input).map_err(within(CRANK))?;
        let o3 = PointMotion::fixed(self.o3);
        let g23 = rrr_dyad(crank.a, o3, self.l2, self.l3, self.branch).map_err(within(GROUP_23))?;
        Ok((crank, g23))
    }

    /// The strokes of the rocker (its angle) for a crank turning in the sense `rotation`.
    ///
    /// # Errors
    /// A position of the cycle that fails, or not exactly two extremes.
    pub fn strokes(&self, rotation: Rotation) -> Result<Strokes> {
        output_strokes(|m| Ok(self.kinematics(m)?.1.link3.angle_motion()), rotation)
    }

    /// The whole analysis at one input position.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed (`"group II(2,3) RRR"` at a
    /// dead point of the group).
    ///
    /// # Examples
    /// A parallelogram four-bar (crank = rocker, coupler = frame) has a dead point where all
    /// links are collinear, at φ1 = 0: the position fails naming the group.
    /// ```
    /// use nalgebra::Point2;
    /// use tmm::{kinematics::Motion, mechanism::FourBar, Error};
    /// let m = FourBar { o3: Point2::new(0.3, 0.0), l1: 0.1, l2: 0.3, l3: 0.1, ..FourBar::course_example() };
    /// let e = m.analyse(Motion::new(0.0, 10.0, 0.0)).unwrap_err();
    /// assert!(matches!(e, Error::In { ref part, .. } if part == "group II(2,3) RRR"));
    /// assert!(m.analyse(Motion::new(1.0, 10.0, 0.0)).is_ok());
    /// ```
    pub fn analyse(&self, input: Motion) -> Result<FourBarPosition> {
        let (crank, g23) = self.kinematics(input)?;
        let links = [crank.link, g23.link2, g23.link3];
        let loads = own_loads(&self.mass, &links, &LINKS, self.gravity)?;
        let rocker_moment = -self.resisting_moment * sign(g23.link3.omega);
        let rocker = Load::new(
            loads[2].point,
            loads[2].force,
            loads[2].moment + rocker_moment,
        );
        let r = RrrDyad {
            a: crank.a.p,
            b: g23.b.p,
            c: self.o3,
            load2: loads[1],
            load3: rocker,
        }
        .solve()
        .map_err(within(GROUP_23))?;
        let balance = self
            .drive
            .balance(self.o1, &[loads[0], Load::force_at(crank.a.p, -r.r12)])
            .map_err(within(CRANK))?;
        Ok(FourBarPosition {
            input,
            crank,
            group23: g23,
            loads,
            rocker_moment,
            r12: r.r12,
            r23: r.r23,
            r03: r.r43,
            balance,
        })
    }
}
