// A slider-crank: the crank O1A drives the piston 3 along a fixed guide through the
// connecting rod AB (one RRP group), with the gas force of an indicator diagram.

use super::drive::{Balance, Drive};
use super::link::{own_loads, LinkMass};
use super::Piston;
use super::{output_strokes, within, CRANK};
use nalgebra::{Point2, Vector2};
use std::f64::consts::PI;
use tmm::error::Result;
use tmm::kinematics::{
    crank, rrp_dyad, Branch, CrankState, Guide, Motion, Rotation, RrpState, Strokes,
};
use tmm::kinetostatics::RrpDyad;
use tmm::linkage::IndicatorDiagram;
use tmm::Load;

/// The links' names, for errors and free bodies.
const LINKS: [&str; 3] = [CRANK, "link 2 (connecting rod)", "link 3 (piston)"];
const GROUP_23: &str = "group II(2,3) RRP";

/// A slider-crank: input link 1 (O1A), RRP group II(2,3) (connecting rod 2 = AB, piston 3 at
/// B on a fixed guide), optionally loaded by the gas pressure of an [`IndicatorDiagram`].
///
/// Link frames: link 1 from O1 along O1A, link 2 from A along AB, the piston at B along the
/// guide. The cylinder head lies on the piston's side of the crank (ahead along the guide for
/// `branch = Plus`).
#[derive(Debug, Clone, PartialEq)]
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
    pub branch: Branch,
    /// The mass properties of links 1 to 3.
    pub mass: [LinkMass; 3],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The gas pressure on the piston, if any.
    pub diagram: Option<IndicatorDiagram>,
    /// How the crank is driven.
    pub drive: Drive,
}

/// One analysed position of a [`SliderCrank`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankPosition {
    /// φ1, ω1, ε1.
    pub input: Motion,
    /// The crank and its pin A.
    pub crank: CrankState,
    /// The RRP group: rod 2, piston 3 at B, its coordinate `slide`.
    pub group23: RrpState,
    /// The own loads of links 1–3 (inertia and weight) at their centres of mass.
    pub loads: [Load; 3],
    /// The gas force on the piston, at B, N.
    pub gas_force: Vector2<f64>,
    /// R12, the crank on the rod at A, N.
    pub r12: Vector2<f64>,
    /// R23, the rod on the piston at B, N.
    pub r23: Vector2<f64>,
    /// R03, the cylinder wall on the piston (normal to the guide), N.
    pub r03: Vector2<f64>,
    /// The moment of R03 about B, N·m.
    pub r03_moment: f64,
    /// The balancing moment (or force) and R01.
    pub balance: Balance,
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

    /// The piston's fixed guide.
    #[must_use]
    pub fn guide(&self) -> Guide {
        Guide::fixed(self.guide_point, self.guide_angle)
    }

    /// The kinematics alone: crank and RRP group.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn kinematics(&self, input: Motion) -> Result<(CrankState, RrpState)> {
        let crank = crank(self.o1, self.l1, input).map_err(within(CRANK))?;
        let g23 =
            rrp_dyad(crank.a, self.guide(), self.l2, self.branch).map_err(within(GROUP_23))?;
        Ok((crank, g23))
    }

    /// The strokes of the piston for a crank turning in the sense `rotation`.
    ///
    /// # Errors
    /// A position of the cycle that fails, or not exactly two extremes.
    pub fn strokes(&self, rotation: Rotation) -> Result<Strokes> {
        output_strokes(|m| Ok(self.kinematics(m)?.1.slide), rotation)
    }

    /// The whole analysis at one input position.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed; an error of the indicator
    /// diagram (`"gas pressure"`).
    pub fn analyse(&self, input: Motion) -> Result<SliderCrankPosition> {
        let (crank, g23) = self.kinematics(input)?;
        let links = [crank.link, g23.link2, g23.link3];
        let loads = own_loads(&self.mass, &links, &LINKS, self.gravity)?;
        let gas_force = match &self.diagram {
            Some(d) => Piston::new(
                self.o1,
                self.l1,
                self.l2,
                self.guide_point,
                self.guide_angle,
                self.branch,
            )
            .and_then(|p| p.gas_force(d, &g23.b))
            .map_err(within("gas pressure"))?,
            None => Vector2::zeros(),
        };
        let b = g23.b.p;
        let piston = Load::sum_about(&[loads[2], Load::force_at(b, gas_force)], b);
        let r = RrpDyad {
            a: crank.a.p,
            b,
            guide: self.guide().unit(),
            load2: loads[1],
            load3: piston,
        }
        .solve()
        .map_err(within(GROUP_23))?;
        let balance = self
            .drive
            .balance(self.o1, &[loads[0], Load::force_at(crank.a.p, -r.r12)])
            .map_err(within(CRANK))?;
        Ok(SliderCrankPosition {
            input,
            crank,
            group23: g23,
            loads,
            gas_force,
            r12: r.r12,
            r23: r.r23,
            r03: r.r43,
            r03_moment: r.guide_moment,
            balance,
        })
    }
}
