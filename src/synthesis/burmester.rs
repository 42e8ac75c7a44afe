#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Motion generation (Burmester): dyads that carry a coupler through finitely separated
//! poses, and the four-bar of two dyads.
//!
//! A pose is the position of a coupler point P and the angle θ of a line fixed in the
//! coupler. The displacement from pose 1 to pose j moves a coupler point z to
//! D_j(z) = P_j + R(θ_j − θ_1)(z − P_1). A dyad is a moving pivot (the circle point, given in
//! pose 1) and a fixed pivot (the centre point) at the same distance from every position
//! D_j(z) of the circle point: the centre point is the centre of the circle through them (the
//! perpendicular bisectors' intersection). Inverted — the frame seen from the coupler — the
//! centre point C occupies the coupler positions D_j⁻¹(C), and the circle point is the centre
//! of the circle through those.

use super::four_bar::FourBar;
use super::{check, coordinate, require_transmission, Options, Synthesis};
use crate::angle::{cross, direction, normalize, perp, unit};
use crate::error::{finite, Error, Result};
use crate::linkage::{Input, Joint, Link, Linkage, NamedPoint, Output};
use nalgebra::Vector2;
use std::f64::consts::TAU;

type V = Vector2<f64>;

/// A pose of the coupler: where its point P is and the angle of a line fixed in it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pose {
    /// P, m.
    pub at: [f64; 2],
    /// The angle of the coupler's line, rad (counter-clockwise from +x).
    pub angle: f64,
}

impl Pose {
    /// P at `at`, the coupler's line at `angle`.
    #[must_use]
    pub fn new(at: [f64; 2], angle: f64) -> Self {
        Self { at, angle }
    }

    fn p(&self) -> V {
        V::new(self.at[0], self.at[1])
    }
}

/// A dyad of a four-bar in motion generation: the fixed pivot and the moving pivot (where it
/// is in the first pose), m.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Dyad {
    /// The centre point: the pivot on the frame.
    pub centre: [f64; 2],
    /// The circle point: the pivot on the coupler, in the first pose.
    pub circle: [f64; 2],
}

impl Dyad {
    /// The dyad's angle (from the centre point to the circle point) in each pose, rad in
    /// [0, 2π): the crank angles at which a four-bar driven by this dyad reaches the poses.
    #[must_use]
    pub fn angles(&self, poses: &[Pose]) -> Vec<f64> {
        let (c, z) = (v(self.centre), v(self.circle));
        poses
            .iter()
            .map(|pose| direction(displace(&poses[0], pose, z) - c))
            .collect()
    }

    /// The link length |centre − circle|, m.
    #[must_use]
    pub fn length(&self) -> f64 {
        (v(self.circle) - v(self.centre)).norm()
    }
}

pub(super) fn v(p: [f64; 2]) -> V {
    V::new(p[0], p[1])
}

fn xy(p: V) -> [f64; 2] {
    [p.x, p.y]
}

/// D_j(z): the coupler point at z in `first` carried to `pose`.
pub(super) fn displace(first: &Pose, pose: &Pose, z: V) -> V {
    let (s, c) = (pose.angle - first.angle).sin_cos();
    let r = z - first.p();
    pose.p() + V::new(c * r.x - s * r.y, s * r.x + c * r.y)
}

/// D_j⁻¹(w): the point of the first pose's coupler that `pose` puts at w.
fn undisplace(first: &Pose, pose: &Pose, w: V) -> V {
    let (s, c) = (first.angle - pose.angle).sin_cos();
    let r = w - pose.p();
    first.p() + V::new(c * r.x - s * r.y, s * r.x + c * r.y)
}

pub(super) fn check_poses(poses: &[Pose]) -> Result<()> {
    for p in poses {
        coordinate("pose x", p.at[0])?;
        coordinate("pose y", p.at[1])?;
        finite("pose angle", p.angle)?;
    }
    let scale = poses
        .iter()
        .map(|p| p.p().norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for (i, p) in poses.iter().enumerate() {
        for (j, q) in poses.iter().enumerate().skip(i + 1) {
            if (p.p() - q.p()).norm() <= 1e-12 * scale
                && (0.5 * (p.angle - q.angle)).sin().abs() <= 1e-12
            {
                return Err(Error::NoMechanism {
                    method: "motion generation",
                    problem: format!("poses {} and {} coincide", i + 1, j + 1),
                });
            }
        }
    }
    Ok(())
}

/// The centre of the circle through three points: from z1, w solves 2(z_k − z1)·w =
/// |z_k − z1|² (k = 2, 3), a 2×2 system of determinant 2·cross(z2 − z1, z3 − z1).
fn circumcentre(what: &'static str, z: [V; 3]) -> Result<V> {
    let (u, w) = (z[1] - z[0], z[2] - z[0]);
    let det = cross(u, w);
    let sine = det / (u.norm() * w.norm());
    if !(sine.abs() > 1e-12) {
        return Err(Error::Singular {
            what,
            measure: "sin of the angle between z2 − z1 and z3 − z1",
            value: if sine.is_finite() { sine } else { 0.0 },
        });
    }
    let (uu, ww) = (0.5 * u.norm_squared(), 0.5 * w.norm_squared());
    Ok(z[0] + V::new(uu * w.y - ww * u.y, u.x * ww - w.x * uu) / det)
}

/// The centre point of the circle point `circle` (where it is in the first pose) for three
/// poses: the centre of the circle through its three positions.
///
/// # Examples
/// A worked problem: the coupler point P at (0, 0), (100, 0) and (0, 100) mm, the coupler
/// turned 0°, 90° and 180°; the circle point chosen at P itself. Its three positions are the
/// poses' points, a right angle at (0, 0), so by hand the centre point is the midpoint of the
/// hypotenuse, (50, 50) mm, and the crank |OA| = 50√2 = 70.71 mm stands at 225°, 315° and
/// 135° in the three poses (the directions from the centre point to the three positions):
/// ```
/// use tmm::synthesis::{centre_point, Pose};
/// let deg = f64::to_radians;
/// let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.1, 0.0], deg(90.0)), Pose::new([0.0, 0.1], deg(180.0))];
/// let dyad = centre_point(&poses, [0.0, 0.0])?;
/// assert!((dyad.centre[0] - 0.05).abs() < 1e-15 && (dyad.centre[1] - 0.05).abs() < 1e-15);
/// assert!((dyad.length() - 0.05 * 2f64.sqrt()).abs() < 1e-15);
/// let turns: Vec<f64> = dyad.angles(&poses).iter().map(|a| a.to_degrees()).collect();
/// assert!((turns[0] - 225.0).abs() < 1e-12 && (turns[1] - 315.0).abs() < 1e-12);
/// assert!((turns[2] - 135.0).abs() < 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
/// Any poses and circle point:
/// ```
/// use tmm::synthesis::{centre_point, Pose};
/// let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.1, 0.05], 0.3), Pose::new([0.2, 0.05], 0.7)];
/// let dyad = centre_point(&poses, [-0.05, -0.1])?;
/// // The circle point stays at one distance from the centre point in every pose.
/// let [a1, a2, a3] = dyad.angles(&poses)[..] else { unreachable!() };
/// assert!(a1 != a2 && a2 != a3);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses;
/// [`Error::Singular`] when the three positions are collinear (the centre point is at
/// infinity: a slider would do) or two of them coincide (the circle point is a pole).
pub fn centre_point(poses: &[Pose; 3], circle: [f64; 2]) -> Result<Dyad> {
    check_poses(poses)?;
    coordinate("circle point x", circle[0])?;
    coordinate("circle point y", circle[1])?;
    let z = v(circle);
    let c = circumcentre(
        "the three positions of the circle point",
        [
            z,
            displace(&poses[0], &poses[1], z),
            displace(&poses[0], &poses[2], z),
        ],
    )?;
    crate::error::computed_all("the centre point", c.iter())?;
    Ok(Dyad {
        centre: xy(c),
        circle,
    })
}

/// The circle point (in the first pose) of the centre point `centre` for three poses: the
/// centre of the circle through the centre point's positions relative to the coupler (the
/// poses inverted).
///
/// # Examples
/// ```
/// use tmm::synthesis::{centre_point, circle_point, Pose};
/// let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.1, 0.05], 0.3), Pose::new([0.2, 0.05], 0.7)];
/// let there = centre_point(&poses, [-0.05, -0.1])?;
/// let back = circle_point(&poses, there.centre)?;
/// assert!((back.circle[0] + 0.05).abs() < 1e-12 && (back.circle[1] + 0.1).abs() < 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`centre_point`].
pub fn circle_point(poses: &[Pose; 3], centre: [f64; 2]) -> Result<Dyad> {
    check_poses(poses)?;
    coordinate("centre point x", centre[0])?;
    coordinate("centre point y", centre[1])?;
    let c = v(centre);
    let z = circumcentre(
        "the three inverted positions of the centre point",
        [
            c,
            undisplace(&poses[0], &poses[1], c),
            undisplace(&poses[0], &poses[2], c),
        ],
    )?;
    crate::error::computed_all("the circle point", z.iter())?;
    Ok(Dyad {
        centre,
        circle: xy(z),
    })
}

/// A dyad for two poses: the circle point `circle` (in the first pose) and a centre point on
/// the perpendicular bisector of its two positions, `along` (m) from their midpoint, positive
/// to the left of the direction from the first position to the second.
///
/// # Examples
/// Two poses; the crank's and the rocker's centre points 0.2 m off the bisectors' midpoints:
/// ```
/// use tmm::synthesis::{centre_point_two, four_bar_from_dyads, Options, Pose};
/// let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.15, 0.05], 0.5)];
/// let crank = centre_point_two(&poses, [-0.05, -0.1], -0.2)?;
/// let rocker = centre_point_two(&poses, [0.12, -0.08], 0.2)?;
/// assert!(crank.misfit(&poses) < 1e-15 && rocker.misfit(&poses) < 1e-15);
/// let s = four_bar_from_dyads(&poses, &crank, &rocker, &Options::default().with_min_transmission_angle(0.0))?;
/// assert_eq!(s.linkage.joints.len(), 4);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses;
/// [`Error::Singular`] when the circle point does not move (it is the pole of the two poses).
pub fn centre_point_two(poses: &[Pose; 2], circle: [f64; 2], along: f64) -> Result<Dyad> {
    check_poses(poses)?;
    coordinate("circle point x", circle[0])?;
    coordinate("circle point y", circle[1])?;
    coordinate("along", along)?;
    let z1 = v(circle);
    let z2 = displace(&poses[0], &poses[1], z1);
    let chord = z2 - z1;
    let n = chord.norm();
    let scale = z1.norm().max(n).max(f64::MIN_POSITIVE);
    if !(n > 1e-12 * scale) {
        return Err(Error::Singular {
            what: "the two positions of the circle point",
            measure: "their distance",
            value: n,
        });
    }
    let c = 0.5 * (z1 + z2) + along * perp(chord / n);
    crate::error::computed_all("the centre point", c.iter())?;
    Ok(Dyad {
        centre: xy(c),
        circle,
    })
}

/// The four-bar of two dyads for the poses: the crank from `crank.centre` (O1) to
/// `crank.circle` (A), the rocker from `rocker.centre` (O3) to `rocker.circle` (B), the coupler
/// AB carrying the poses' point `P` and a point `Q` along the poses' line, its angle measured
/// from P to Q (so the engine's coupler angle is the pose angle). Posed in the first pose.
///
/// Both dyads must fit every pose (each circle point at one distance from its centre point);
/// the four-bar must reach every pose in one assembly mode (no branch defect) and move from
/// the first pose to the last through the others without leaving it (no order defect: it
/// assembles all along the crank's arc); γ_min over a full turn if the crank turns fully,
/// over that arc otherwise, must meet \[γ\]. The crank angles of the poses are
/// [`Dyad::angles`] of `crank`.
///
/// # Examples
/// Three poses, the circle points chosen, the centre points found:
/// ```
/// use tmm::synthesis::{centre_point, four_bar_from_dyads, Options, Pose};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::Plan;
/// let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.1, 0.05], 0.3), Pose::new([0.2, 0.05], 0.7)];
/// let crank = centre_point(&poses, [-0.05, -0.1])?;
/// let rocker = centre_point(&poses, [0.1, -0.08])?;
/// let s = four_bar_from_dyads(&poses, &crank, &rocker, &Options::default().with_min_transmission_angle(0.0))?;
/// let plan = Plan::new(&s.linkage)?;
/// for (pose, phi) in poses.iter().zip(crank.angles(&poses)) {
///     let k = plan.kinematics(Motion::fixed(phi))?;
///     let p = k.point("P")?.p;
///     assert!((p.x - pose.at[0]).abs() < 1e-12 && (p.y - pose.at[1]).abs() < 1e-12);
///     let turn = k.link("coupler")?.value - pose.angle;
///     assert!(turn.sin().abs() < 1e-12);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses,
/// coinciding pivots, a dyad that does not fit a pose, a branch or an order defect;
/// [`Error::OutOfRange`] (`"poses"`) for fewer than two poses; [`Error::Infeasible`] for γ_min
/// below \[γ\].
pub fn four_bar_from_dyads(
    poses: &[Pose],
    crank: &Dyad,
    rocker: &Dyad,
    options: &Options,
) -> Result<Synthesis> {
    const METHOD: &str = "four-bar of two dyads";
    let required = options.check()?;
    if poses.len() < 2 {
        return Err(Error::OutOfRange {
            name: "poses",
            value: poses.len() as f64,
            min: 2.0,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    check_poses(poses)?;
    for (name, p) in [
        ("crank centre point", crank.centre),
        ("crank circle point", crank.circle),
        ("rocker centre point", rocker.centre),
        ("rocker circle point", rocker.circle),
    ] {
        coordinate(name, p[0])?;
        coordinate(name, p[1])?;
    }
    let (o1, a, b, o3) = (
        v(crank.centre),
        v(crank.circle),
        v(rocker.circle),
        v(rocker.centre),
    );
    let scale = [o1, a, b, o3]
        .iter()
        .map(|p| p.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for (what, p, q) in [
        ("the crank's pivots O1 and A", o1, a),
        ("the rocker's pivots O3 and B", o3, b),
        ("the coupler's pivots A and B", a, b),
        ("the frame's pivots O1 and O3", o1, o3),
    ] {
        if !((p - q).norm() > 1e-12 * scale) {
            return Err(Error::NoMechanism {
                method: METHOD,
                problem: format!("{what} coincide"),
            });
        }
    }
    let first = &poses[0];
    let mut modes = Vec::with_capacity(poses.len());
    for (j, pose) in poses.iter().enumerate() {
        let (aj, bj) = (displace(first, pose, a), displace(first, pose, b));
        for (what, centre, z, zj) in [("crank", o1, a, aj), ("rocker", o3, b, bj)] {
            let miss = ((zj - centre).norm() - (z - centre).norm()).abs();
            if miss > 1e-9 * (z - centre).norm() {
                return Err(Error::NoMechanism {
                    method: METHOD,
                    problem: format!(
                        "the {what} dyad does not fit pose {}: its length changes by {miss:.4e} m",
                        j + 1
                    ),
                });
            }
        }
        modes.push(FourBar::from_points(o1, aj, bj, o3).sigma);
    }
    if modes.contains(&0.0) || modes.iter().any(|&m| m != modes[0]) {
        return Err(Error::NoMechanism {
            method: METHOD,
            problem: format!(
                "branch defect: the poses need the assembly modes {modes:?} (+1: B left of A→O3)"
            ),
        });
    }
    let fb = FourBar::from_points(o1, a, b, o3);
    fb.proportions(METHOD)?;
    // The crank's arc from the first pose to the last through the others, in local angles.
    let phis: Vec<f64> = crank
        .angles(poses)
        .iter()
        .map(|&p| normalize(p - fb.delta))
        .collect();
    let offsets: Vec<f64> = phis.iter().map(|&p| normalize(p - phis[0])).collect();
    let last = offsets[offsets.len() - 1];
    let ccw = offsets.windows(2).all(|w| w[0] <= w[1]);
    let cw = offsets[1..].windows(2).all(|w| w[0] >= w[1]);
    let (start, span) = if poses.len() == 2 {
        // Two poses: the shorter way round.
        if last <= TAU - last {
            (phis[0], last)
        } else {
            (phis[1], TAU - last)
        }
    } else if ccw {
        (phis[0], last)
    } else if cw {
        (phis[phis.len() - 1], TAU - last)
    } else {
        return Err(Error::NoMechanism {
            method: METHOD,
            problem: format!(
                "order defect: the crank reaches the poses at {:?} rad, not in one sense of turning",
                crank.angles(poses)
            ),
        });
    };
    for i in 0..=1024 {
        let phi = start + span * f64::from(i) / 1024.0;
        if fb.local_pose(phi).is_none() {
            return Err(Error::NoMechanism {
                method: METHOD,
                problem: format!(
                    "order defect: it does not assemble at the crank angle {:.6} rad between the poses",
                    fb.world_angle(phi)
                ),
            });
        }
    }
    // γ_min over a full turn if the crank turns fully, over the arc of the poses otherwise.
    let report = fb.report("four-bar for motion generation", Some((start, span)))?;
    require_transmission(report.min_transmission_angle, required)?;
    let p = first.p();
    let q = p + (b - a).norm() * unit(first.angle);
    let mut coupler = Link::new("coupler", &["A", "B"]);
    coupler.points = vec![
        NamedPoint {
            name: "P".to_owned(),
            at: xy(p),
        },
        NamedPoint {
            name: "Q".to_owned(),
            at: xy(q),
        },
    ];
    coupler.reference = Some(["P".to_owned(), "Q".to_owned()]);
    let linkage = Linkage {
        name: "four-bar for motion generation".to_owned(),
        joints: vec![
            Joint::revolute("O1", xy(o1)),
            Joint::revolute("A", xy(a)),
            Joint::revolute("B", xy(b)),
            Joint::revolute("O3", xy(o3)),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]),
            coupler,
            Link::new("rocker", &["O3", "B"]),
        ],
        input: Input::crank("crank"),
        output: Some(Output::Angle("coupler".to_owned())),
        ..Linkage::default()
    };
    check::accepted(&linkage)?;
    Ok(Synthesis { linkage, report })
}

/// The four-bar through three poses with the circle points `crank_circle` and
/// `rocker_circle` chosen (in the first pose): [`centre_point`] for each, then
/// [`four_bar_from_dyads`].
///
/// # Examples
/// ```
/// use tmm::synthesis::{burmester, Options, Pose};
/// let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.1, 0.05], 0.3), Pose::new([0.2, 0.05], 0.7)];
/// let s = burmester(&poses, [-0.05, -0.1], [0.1, -0.08], &Options::default())?;
/// assert!(s.report.min_transmission_angle > 40f64.to_radians());
/// println!("{}", s.report);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`centre_point`] and [`four_bar_from_dyads`].
pub fn burmester(
    poses: &[Pose; 3],
    crank_circle: [f64; 2],
    rocker_circle: [f64; 2],
    options: &Options,
) -> Result<Synthesis> {
    let crank = centre_point(poses, crank_circle)?;
    let rocker = centre_point(poses, rocker_circle)?;
    four_bar_from_dyads(poses, &crank, &rocker, options)
}

impl Dyad {
    /// How far the dyad is from fitting the poses: the largest change of the distance from
    /// the centre point to the circle point's position in each pose, m.
    #[must_use]
    pub fn misfit(&self, poses: &[Pose]) -> f64 {
        let (c, z) = (v(self.centre), v(self.circle));
        let l = (z - c).norm();
        poses
            .iter()
            .map(|p| ((displace(&poses[0], p, z) - c).norm() - l).abs())
            .fold(0.0, f64::max)
    }
}
