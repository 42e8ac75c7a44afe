// A crank-driven RPR drive: the crank O1A drives a rod (piston rod, or slider block) 2 that
// slides in a cylinder (or slotted lever) 3 rocking about the frame pivot C: an oscillating-
// cylinder pump, or a crank and slotted lever.

use super::drive::{Balance, Drive};
use super::link::{own_loads, LinkMass};
use super::{output_strokes, sign, within, CRANK};
use nalgebra::{Point2, Vector2};
use tmm::error::Result;
use tmm::kinematics::{
    crank, rpr_dyad, CrankState, Motion, PointMotion, Rotation, RprState, Strokes,
};
use tmm::kinetostatics::RprDyad;
use tmm::Load;

/// The links' names, for errors and free bodies.
const LINKS: [&str; 3] = [CRANK, "link 2 (rod)", "link 3 (cylinder)"];
const GROUP_23: &str = "group II(2,3) RPR";

/// A crank and an RPR group: input link 1 (O1A), rod 2 hinged at A sliding along the axis of
/// cylinder 3, which rocks about the frame pivot C (the axis passes through C).
///
/// The fluid in the cylinder resists the sliding: while the rod moves in (l_AC decreasing)
/// it pushes the rod out with `force_in`, while it moves out it pulls the rod in with
/// `force_out`; the cylinder takes the opposite force along the same axis, at the piston P,
/// `l_piston` from A along A→C. Link frames: link 1 from O1 along O1A, the rod from A along
/// A→C, the cylinder from C along C→A.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RockingCylinder {
    /// O1, the crank's pivot, m.
    pub o1: Point2<f64>,
    /// C, the cylinder's pivot, m.
    pub c: Point2<f64>,
    /// l_O1A, the crank, m.
    pub l1: f64,
    /// The distance of the piston from A along the rod, m.
    pub l_piston: f64,
    /// The mass properties of links 1 to 3.
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

/// One analysed position of a [`RockingCylinder`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RockingCylinderPosition {
    /// φ1, ω1, ε1.
    pub input: Motion,
    /// The crank and its pin A.
    pub crank: CrankState,
    /// The RPR group: rod 2, cylinder 3, the length l_AC with its rates.
    pub group23: RprState,
    /// The own loads of links 1–3 (inertia and weight) at their centres of mass.
    pub loads: [Load; 3],
    /// The piston P and the fluid's force on the rod there, N (the cylinder takes −F).
    pub fluid: Load,
    /// R12, the crank on the rod at A, N.
    pub r12: Vector2<f64>,
    /// R32, the cylinder on the rod (normal to the axis), N.
    pub r32: Vector2<f64>,
    /// The moment of R32 about A, N·m.
    pub r32_moment: f64,
    /// R03, the frame on the cylinder at C, N.
    pub r03: Vector2<f64>,
    /// The balancing moment (or force) and R01.
    pub balance: Balance,
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

    /// The kinematics alone: crank and RPR group.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn kinematics(&self, input: Motion) -> Result<(CrankState, RprState)> {
        let crank = crank(self.o1, self.l1, input).map_err(within(CRANK))?;
        let g23 = rpr_dyad(crank.a, PointMotion::fixed(self.c)).map_err(within(GROUP_23))?;
        Ok((crank, g23))
    }

    /// The strokes of the cylinder's swing (its angle) for a crank turning in the sense
    /// `rotation`.
    ///
    /// # Errors
    /// A position of the cycle that fails, or not exactly two extremes.
    pub fn strokes(&self, rotation: Rotation) -> Result<Strokes> {
        output_strokes(|m| Ok(self.kinematics(m)?.1.link3.angle_motion()), rotation)
    }

    /// The whole analysis at one input position.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn analyse(&self, input: Motion) -> Result<RockingCylinderPosition> {
        let (crank, g23) = self.kinematics(input)?;
        let links = [crank.link, g23.link2, g23.link3];
        let loads = own_loads(&self.mass, &links, &LINKS, self.gravity)?;
        // u points from A into the cylinder; moving in (ṡ < 0) the fluid pushes the rod out.
        let u = g23.link2.unit();
        let rate = g23.slide.rate;
        let push_out = if rate < 0.0 {
            self.force_in
        } else {
            -self.force_out
        };
        let piston = crank.a.p + self.l_piston * u;
        let fluid = Load::force_at(piston, -push_out * sign(rate).abs() * u);
        let rod = Load::sum_about(&[loads[1], fluid], crank.a.p);
        let cylinder = Load::sum_about(&[loads[2], Load::force_at(piston, -fluid.force)], self.c);
        let r = RprDyad {
            a: crank.a.p,
            e: self.c,
            axis: u,
            load2: rod,
            load3: cylinder,
        }
        .solve()
        .map_err(within(GROUP_23))?;
        let balance = self
            .drive
            .balance(self.o1, &[loads[0], Load::force_at(crank.a.p, -r.r12)])
            .map_err(within(CRANK))?;
        Ok(RockingCylinderPosition {
            input,
            crank,
            group23: g23,
            loads,
            fluid,
            r12: r.r12,
            r32: r.r32,
            r32_moment: r.couple,
            r03: r.r43,
            balance,
        })
    }
}
