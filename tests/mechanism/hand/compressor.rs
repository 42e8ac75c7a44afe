// Seed 001's two-cylinder air compressor: one crank with two throws O A and O C drives two
// pistons through two RRP groups, II(2,3) and II(4,5).

use super::drive::{Balance, Drive};
use super::link::{own_loads, LinkMass};
use super::Piston;
use super::{output_strokes, within, CRANK};
use nalgebra::{Point2, Vector2};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use tmm::error::Result;
use tmm::kinematics::{
    crank, rrp_dyad, Branch, CrankState, Guide, Motion, PointMotion, Rotation, RrpState, Strokes,
};
use tmm::kinetostatics::RrpDyad;
use tmm::linkage::IndicatorDiagram;
use tmm::Load;

/// The links' names, for errors and free bodies.
const LINKS: [&str; 5] = [
    CRANK,
    "link 2 (rod 1)",
    "link 3 (piston 1)",
    "link 4 (rod 2)",
    "link 5 (piston 2)",
];
const GROUP_23: &str = "group II(2,3) RRP";
const GROUP_45: &str = "group II(4,5) RRP";

/// A two-cylinder compressor: the crank 1 (throws O1A and O1C, the second turned by
/// `throw_angle` from the first), RRP group II(2,3) (rod 2 = AB, piston 3 at B) and RRP group
/// II(4,5) (rod 4 = CD, piston 5 at D), each piston on its own fixed guide through
/// `guide_point`.
///
/// Link frames: link 1 from O1 along O1A, rod 2 from A along AB, rod 4 from C along CD, the
/// pistons at B and D along their guides.
#[derive(Debug, Clone, PartialEq)]
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
    /// The direction angles of the guides of pistons 3 and 5, rad.
    pub guide_angles: [f64; 2],
    /// Assembly modes of the groups II(2,3) and II(4,5).
    pub branches: [Branch; 2],
    /// The mass properties of links 1 to 5.
    pub mass: [LinkMass; 5],
    /// g, m/s², along −y (0 to neglect weights).
    pub gravity: f64,
    /// The indicator diagrams of the cylinders of pistons 3 and 5.
    pub diagrams: [Option<IndicatorDiagram>; 2],
    /// How the crank is driven.
    pub drive: Drive,
}

/// One analysed position of a [`Compressor`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompressorPosition {
    /// φ1, ω1, ε1.
    pub input: Motion,
    /// The crank and its first pin A.
    pub crank: CrankState,
    /// The second crank pin C.
    pub c: PointMotion,
    /// The group II(2,3): rod 2, piston 3 at B.
    pub group23: RrpState,
    /// The group II(4,5): rod 4, piston 5 at D.
    pub group45: RrpState,
    /// The own loads of links 1–5 (inertia and weight) at their centres of mass.
    pub loads: [Load; 5],
    /// The gas forces on pistons 3 (at B) and 5 (at D), N.
    pub gas_forces: [Vector2<f64>; 2],
    /// R12, the crank on rod 2 at A, N.
    pub r12: Vector2<f64>,
    /// R23, rod 2 on piston 3 at B, N.
    pub r23: Vector2<f64>,
    /// R03, the first cylinder on piston 3, N.
    pub r03: Vector2<f64>,
    /// R14, the crank on rod 4 at C, N.
    pub r14: Vector2<f64>,
    /// R45, rod 4 on piston 5 at D, N.
    pub r45: Vector2<f64>,
    /// R05, the second cylinder on piston 5, N.
    pub r05: Vector2<f64>,
    /// The moments of R03 about B and of R05 about D, N·m.
    pub wall_moments: [f64; 2],
    /// The balancing moment (or force) and R01.
    pub balance: Balance,
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

    /// The fixed guide of piston 3 (`k = 0`) or 5 (`k = 1`).
    ///
    /// # Panics
    /// For `k` > 1 (there are two guides).
    #[must_use]
    pub fn guide(&self, k: usize) -> Guide {
        Guide::fixed(self.guide_point, self.guide_angles[k])
    }

    /// The kinematics alone: crank, the second pin C, both RRP groups.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn kinematics(
        &self,
        input: Motion,
    ) -> Result<(CrankState, PointMotion, RrpState, RrpState)> {
        let crank = crank(self.o1, self.l1, input).map_err(within(CRANK))?;
        let (s, c) = self.throw_angle.sin_cos();
        let pin_c = crank.link.point_at(self.l1 * c, self.l1 * s);
        let g23 = rrp_dyad(crank.a, self.guide(0), self.l2, self.branches[0])
            .map_err(within(GROUP_23))?;
        let g45 =
            rrp_dyad(pin_c, self.guide(1), self.l4, self.branches[1]).map_err(within(GROUP_45))?;
        Ok((crank, pin_c, g23, g45))
    }

    /// The strokes of piston 3 for a crank turning in the sense `rotation`.
    ///
    /// # Errors
    /// A position of the cycle that fails, or not exactly two extremes.
    pub fn strokes(&self, rotation: Rotation) -> Result<Strokes> {
        output_strokes(|m| Ok(self.kinematics(m)?.2.slide), rotation)
    }

    /// The whole analysis at one input position: kinematics, loads (with both gas forces),
    /// the groups II(4,5) and II(2,3), then the crank with both reactions.
    ///
    /// # Errors
    /// [`Error::In`](tmm::Error::In) naming the part that failed.
    pub fn analyse(&self, input: Motion) -> Result<CompressorPosition> {
        let (crank, c, g23, g45) = self.kinematics(input)?;
        let links = [crank.link, g23.link2, g23.link3, g45.link2, g45.link3];
        let loads = own_loads(&self.mass, &links, &LINKS, self.gravity)?;
        let rods = [self.l2, self.l4];
        let pins = [g23.b, g45.b];
        let mut gas_forces = [Vector2::zeros(); 2];
        for k in 0..2 {
            if let Some(d) = &self.diagrams[k] {
                let piston = Piston::new(
                    self.o1,
                    self.l1,
                    rods[k],
                    self.guide_point,
                    self.guide_angles[k],
                    self.branches[k],
                );
                gas_forces[k] = piston
                    .and_then(|p| p.gas_force(d, &pins[k]))
                    .map_err(within(
                        ["gas pressure, cylinder 1", "gas pressure, cylinder 2"][k],
                    ))?;
            }
        }
        let piston = |load: Load, b: Point2<f64>, f: Vector2<f64>| {
            Load::sum_about(&[load, Load::force_at(b, f)], b)
        };
        // Both groups hang on the crank; II(4,5) was attached last.
        let r45 = RrpDyad {
            a: c.p,
            b: g45.b.p,
            guide: self.guide(1).unit(),
            load2: loads[3],
            load3: piston(loads[4], g45.b.p, gas_forces[1]),
        }
        .solve()
        .map_err(within(GROUP_45))?;
        let r23 = RrpDyad {
            a: crank.a.p,
            b: g23.b.p,
            guide: self.guide(0).unit(),
            load2: loads[1],
            load3: piston(loads[2], g23.b.p, gas_forces[0]),
        }
        .solve()
        .map_err(within(GROUP_23))?;
        let balance = self
            .drive
            .balance(
                self.o1,
                &[
                    loads[0],
                    Load::force_at(crank.a.p, -r23.r12),
                    Load::force_at(c.p, -r45.r12),
                ],
            )
            .map_err(within(CRANK))?;
        Ok(CompressorPosition {
            input,
            crank,
            c,
            group23: g23,
            group45: g45,
            loads,
            gas_forces,
            r12: r23.r12,
            r23: r23.r23,
            r03: r23.r43,
            r14: r45.r12,
            r45: r45.r23,
            r05: r45.r43,
            wall_moments: [r23.guide_moment, r45.guide_moment],
            balance,
        })
    }
}
