// A six-bar of a crank, an RRR group and an RRP group (seed 001, figure 2.10's type): the
// crank O1A drives the rocker O2B through the coupler AB; a point C of the rocker drives the
// slider 5 along a fixed guide through the connecting rod CD.

use super::drive::{Balance, Drive};
use super::link::{own_loads, LinkMass};
use super::{output_strokes, within, CRANK};
use nalgebra::{Point2, Vector2};
use tmm::error::{Error, Result};
use tmm::kinematics::{
    crank, rrp_dyad, rrr_dyad, Branch, CrankState, Guide, Motion, PointMotion, Rotation, RrpState,
    RrrState, Strokes,
};
use tmm::kinetostatics::{RrpDyad, RrrDyad};
use tmm::Load;

/// The links' names, for errors and free bodies.
const LINKS: [&str; 5] = [
    CRANK,
    "link 2 (coupler)",
    "link 3 (rocker)",
    "link 4 (rod)",
    "link 5 (slider)",
];
const GROUP_23: &str = "group II(2,3) RRR";
const GROUP_45: &str = "group II(4,5) RRP";

/// A crank–rocker–slider six-bar: input link 1 (O1A), RRR group II(2,3) (coupler 2 = AB,
/// rocker 3 = O2B carrying C), RRP group II(4,5) (rod 4 = CD, slider 5 at D on a fixed guide).
///
/// Link frames (for the centres of mass, [`LinkMass`]): link 1 from O1 along O1A, link 2 from
/// A along AB, link 3 from O2 along O2B, link 4 from C along CD, slider 5 at D along the guide.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// l_CD, the connecting rod of the slider, m.
    pub l4: f64,
    /// A point of the slider's fixed guide, m.
    pub guide_point: Point2<f64>,
    /// The direction angle of the guide, rad.
    pub guide_angle: f64,
    /// Assembly mode of the RRR group (B to the left of A→O2 for `Plus`).
    pub branch23: Branch,
    /// Assembly mode of the RRP group (D ahead of the foot of C along the guide for `Plus`).
    pub branch45: Branch,
    /// The mass properties of links 1 to 5.
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

/// One analysed position of a [`SixBar`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SixBarPosition {
    /// φ1, ω1, ε1.
    pub input: Motion,
    /// The crank and its pin A.
    pub crank: CrankState,
    /// The RRR group: B, coupler 2, rocker 3.
    pub group23: RrrState,
    /// The rocker's point C.
    pub c: PointMotion,
    /// The RRP group: rod 4, slider 5 at D (`group45.b`), its coordinate `group45.slide`.
    pub group45: RrpState,
    /// The own loads of links 1–5 (inertia and weight) at their centres of mass.
    pub loads: [Load; 5],
    /// The resistance on the slider, at D, N.
    pub resistance: Vector2<f64>,
    /// R12, the crank on the coupler at A, N.
    pub r12: Vector2<f64>,
    /// R23, the coupler on the rocker at B, N.
    pub r23: Vector2<f64>,
    /// R03, the frame on the rocker at O2, N.
    pub r03: Vector2<f64>,
    /// R34, the rocker on the rod at C, N.
    pub r34: Vector2<f64>,
    /// R45, the rod on the slider at D, N.
    pub r45: Vector2<f64>,
    /// R05, the guide on the slider (normal to the guide), N.
    pub r05: Vector2<f64>,
    /// The moment of R05 about D, N·m (non-zero when the slider's loads miss D).
    pub r05_moment: f64,
    /// The balancing moment (or force) and R01.
    pub balance: Balance,
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

    /// The slider's fixed guide.
    #[must_use]
    pub fn guide(&self) -> Guide {
        Guide::fixed(self.guide_point, self.guide_angle)
    }

    /// The kinematics alone: crank, RRR group, C, RRP group.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn kinematics(
        &self,
        input: Motion,
    ) -> Result<(CrankState, RrrState, PointMotion, RrpState)> {
        let crank = crank(self.o1, self.l1, input).map_err(within(CRANK))?;
        let o2 = PointMotion::fixed(self.o2);
        let g23 =
            rrr_dyad(crank.a, o2, self.l2, self.l3, self.branch23).map_err(within(GROUP_23))?;
        let c = g23.link3.point_at(self.c_along, self.c_across);
        let g45 = rrp_dyad(c, self.guide(), self.l4, self.branch45).map_err(within(GROUP_45))?;
        Ok((crank, g23, c, g45))
    }

    /// The strokes of the slider for a crank turning in the sense `rotation` (its extreme
    /// positions found on the first transfer function, the working stroke the longer one).
    ///
    /// # Errors
    /// A position of the cycle that fails, or not exactly two extremes.
    pub fn strokes(&self, rotation: Rotation) -> Result<Strokes> {
        output_strokes(|m| Ok(self.kinematics(m)?.3.slide), rotation)
    }

    /// The whole analysis at one input position: kinematics, loads, kinetostatics of group
    /// II(4,5), then II(2,3), then the crank.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed (for example
    /// `"group II(2,3) RRR"` at a dead point of the RRR group); a `working_direction` that is
    /// zero or not finite (`"link 5 (slider)"`).
    pub fn analyse(&self, input: Motion) -> Result<SixBarPosition> {
        if !(self.working_direction.is_finite() && self.working_direction != 0.0) {
            return Err(within(LINKS[4])(Error::OutOfRange {
                name: "working direction",
                value: self.working_direction,
                min: -1.0,
                max: 1.0,
                ends: tmm::Ends::Closed,
            }));
        }
        // 1. Kinematics, in the order the groups are attached.
        let (crank, g23, c, g45) = self.kinematics(input)?;
        // 2. Loads: inertia and weight of every link, the resistance on the slider.
        let links = [crank.link, g23.link2, g23.link3, g45.link2, g45.link3];
        let loads = own_loads(&self.mass, &links, &LINKS, self.gravity)?;
        let v5 = g45.slide.rate;
        let resistance = if v5 * self.working_direction > 0.0 {
            -v5.signum() * self.resistance * self.guide().unit()
        } else {
            Vector2::zeros()
        };
        let d = g45.b.p;
        let slider = Load::sum_about(&[loads[4], Load::force_at(d, resistance)], d);
        // 3. Kinetostatics: the group attached last first.
        let r45 = RrpDyad {
            a: c.p,
            b: d,
            guide: self.guide().unit(),
            load2: loads[3],
            load3: slider,
        }
        .solve()
        .map_err(within(GROUP_45))?;
        let rocker = Load::sum_about(&[loads[2], Load::force_at(c.p, -r45.r12)], self.o2);
        let r23 = RrrDyad {
            a: crank.a.p,
            b: g23.b.p,
            c: self.o2,
            load2: loads[1],
            load3: rocker,
        }
        .solve()
        .map_err(within(GROUP_23))?;
        // 4. The crank: its own load and the coupler's reaction R21 = −R12.
        let balance = self
            .drive
            .balance(self.o1, &[loads[0], Load::force_at(crank.a.p, -r23.r12)])
            .map_err(within(CRANK))?;
        Ok(SixBarPosition {
            input,
            crank,
            group23: g23,
            c,
            group45: g45,
            loads,
            resistance,
            r12: r23.r12,
            r23: r23.r23,
            r03: r23.r43,
            r34: r45.r12,
            r45: r45.r23,
            r05: r45.r43,
            r05_moment: r45.guide_moment,
            balance,
        })
    }
}
