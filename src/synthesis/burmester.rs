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
use super::{check, require_transmission, Options, Synthesis};
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

fn v(p: [f64; 2]) -> V {
    V::new(p[0], p[1])
}

fn xy(p: V) -> [f64; 2] {
    [p.x, p.y]
}

/// D_j(z): the coupler point at z in `first` carried to `pose`.
fn displace(first: &Pose, pose: &Pose, z: V) -> V {
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

fn check_poses(poses: &[Pose]) -> Result<()> {
    for p in poses {
        finite("pose x", p.at[0])?;
        finite("pose y", p.at[1])?;
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
    finite("circle point x", circle[0])?;
    finite("circle point y", circle[1])?;
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
    finite("centre point x", centre[0])?;
    finite("centre point y", centre[1])?;
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
    finite("circle point x", circle[0])?;
    finite("circle point y", circle[1])?;
    finite("along", along)?;
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
        finite(name, p[0])?;
        finite(name, p[1])?;
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

type C = nalgebra::Complex<f64>;

/// The centre-point curve of four poses, sampled: the dyads (centre point, circle point in
/// the first pose) that carry the coupler through all four, for `n` crank rotations β2
/// between the first two poses, evenly spaced over a turn (up to two dyads each).
///
/// Derivation (the dyad's standard form): with W = A − O (the crank, from the centre point O
/// to the circle point A in pose 1), Z = P1 − A and the coupler's rotations α_j = θ_j − θ1,
/// pose j is reached when the crank has turned β_j:
/// W(e^{iβ_j} − 1) + Z(e^{iα_j} − 1) = δ_j = P_j − P1, j = 2, 3, 4.
/// Three complex equations in two complex unknowns are compatible only where the 3×3
/// determinant of [e^{iβ_j} − 1, e^{iα_j} − 1, δ_j] vanishes; expanded along its first column,
/// Δ1 + Δ2·e^{iβ2} + Δ3·e^{iβ3} + Δ4·e^{iβ4} = 0 (Δ2..Δ4 the cofactors, Δ1 = −ΣΔj). For a
/// chosen β2 the vectors Δ3·e^{iβ3} and Δ4·e^{iβ4} close a triangle with −(Δ1 + Δ2·e^{iβ2}):
/// two solutions, or none. Then W and Z solve equations 2 and 3 (Cramer), O = P1 − Z − W and
/// A = P1 − Z. The trivial solution β_j = α_j (the crank turning with the coupler) is left out.
///
/// # Examples
/// ```
/// use tmm::synthesis::{centre_point_curve, Pose};
/// let poses = [
///     Pose::new([0.0, 0.0], 0.0),
///     Pose::new([0.1, 0.05], 0.3),
///     Pose::new([0.2, 0.05], 0.7),
///     Pose::new([0.28, 0.0], 1.0),
/// ];
/// let dyads = centre_point_curve(&poses, 90)?;
/// assert!(!dyads.is_empty());
/// // Every dyad keeps its length through the four poses.
/// for d in &dyads {
///     assert!(d.misfit(&poses) < 1e-9 * (1.0 + d.length()));
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses;
/// [`Error::OutOfRange`] (`"n"`) for n = 0 or n above [`MAX_POINTS`](super::MAX_POINTS).
pub fn centre_point_curve(poses: &[Pose; 4], n: usize) -> Result<Vec<Dyad>> {
    check_poses(poses)?;
    if !(1..=super::MAX_POINTS).contains(&n) {
        return Err(Error::OutOfRange {
            name: "n",
            value: n as f64,
            min: 1.0,
            max: super::MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    let compat = Compatibility::new(poses);
    let mut out = Vec::new();
    for k in 0..n {
        let beta2 = TAU * (k as f64 + 0.5) / n as f64;
        for sign in [1.0, -1.0] {
            if let Some(dyad) = compat.dyad(beta2, sign)
                && dyad.misfit(poses) <= 1e-9 * (compat.size + dyad.length())
            {
                out.push(dyad);
            }
        }
    }
    Ok(out)
}

/// Burmester's compatibility of four poses (see [`centre_point_curve`]): the coefficients
/// of the standard form and the determinant's cofactors.
struct Compatibility {
    p1: C,
    /// The coupler's rotations from pose 1 as e^{iα_j} − 1, j = 2, 3, 4.
    alpha: [C; 3],
    /// The first pose's turns α_j, rad.
    turns: [f64; 3],
    /// δ_j = P_j − P1.
    delta: [C; 3],
    /// Δ1..Δ4.
    d: [C; 4],
    /// The largest |δ_j|, m.
    size: f64,
}

fn rotation_minus_one(angle: f64) -> C {
    C::from_polar(1.0, angle) - 1.0
}

impl Compatibility {
    fn new(poses: &[Pose]) -> Self {
        let p1 = C::new(poses[0].at[0], poses[0].at[1]);
        let turns = [1, 2, 3].map(|j| poses[j].angle - poses[0].angle);
        let alpha = turns.map(rotation_minus_one);
        let delta = [1, 2, 3].map(|j| C::new(poses[j].at[0], poses[j].at[1]) - p1);
        // Cofactors of the first column of [e^{iβ} − 1, e^{iα} − 1, δ] (rows j = 2, 3, 4).
        let minor = |r: usize, s: usize| alpha[r] * delta[s] - alpha[s] * delta[r];
        let (d2, d3, d4) = (minor(1, 2), -minor(0, 2), minor(0, 1));
        Self {
            p1,
            alpha,
            turns,
            delta,
            d: [-(d2 + d3 + d4), d2, d3, d4],
            size: delta.iter().map(|d| d.norm()).fold(0.0, f64::max),
        }
    }

    /// Whether the compatibility triangle closes for the turn β2 (two real branches).
    fn closes(&self, beta2: f64) -> bool {
        let [d1, d2, d3, d4] = self.d;
        let l = (d1 + d2 * C::from_polar(1.0, beta2)).norm();
        let (r3, r4) = (d3.norm(), d4.norm());
        l > 0.0 && l <= r3 + r4 && l >= (r3 - r4).abs()
    }

    /// (W, Z) for the crank's turn β2 to pose 2 on the branch `sign` of the compatibility
    /// triangle; `None` where the triangle does not close, on the trivial solution, or where
    /// equations 2 and 3 do not fix W and Z. `fold` puts the triangle's apex on its base (the
    /// two branches' meeting point, where the apex's height is zero to rounding).
    fn standard_form_with(&self, beta2: f64, sign: f64, fold: bool) -> Option<(C, C)> {
        let [d1, d2, d3, d4] = self.d;
        let s = -(d1 + d2 * C::from_polar(1.0, beta2));
        let (r3, r4, l) = (d3.norm(), d4.norm(), s.norm());
        if !(r3 > 0.0 && r4 > 0.0 && l > 0.0) {
            return None;
        }
        // a = Δ3·e^{iβ3}: |a| = r3, |s − a| = r4.
        if !self.closes(beta2) {
            return None;
        }
        let along = (r3 * r3 - r4 * r4 + l * l) / (2.0 * l);
        let h2 = if fold {
            0.0
        } else {
            (r3 * r3 - along * along).max(0.0)
        };
        let a = s / l * C::new(along, sign * h2.sqrt());
        let betas = [beta2, (a / d3).arg(), ((s - a) / d4).arg()];
        let trivial = betas
            .iter()
            .zip(self.turns)
            .all(|(&b, t)| (0.5 * (b - t)).sin().abs() < 1e-9);
        if trivial {
            return None;
        }
        let (b2, b3) = (rotation_minus_one(betas[0]), rotation_minus_one(betas[1]));
        let [a2, a3, _] = self.alpha;
        let det = b2 * a3 - b3 * a2;
        if !(det.norm() > 1e-12) {
            return None;
        }
        let w = (self.delta[0] * a3 - self.delta[1] * a2) / det;
        let z = (b2 * self.delta[1] - b3 * self.delta[0]) / det;
        Some((w, z))
    }

    /// The dyad for β2 on the branch `sign`: O = P1 − Z − W, A = P1 − Z.
    fn dyad(&self, beta2: f64, sign: f64) -> Option<Dyad> {
        self.dyad_with(beta2, sign, false)
    }

    fn dyad_with(&self, beta2: f64, sign: f64, fold: bool) -> Option<Dyad> {
        let (w, z) = self.standard_form_with(beta2, sign, fold)?;
        let (circle, centre) = (self.p1 - z, self.p1 - z - w);
        let dyad = Dyad {
            centre: [centre.re, centre.im],
            circle: [circle.re, circle.im],
        };
        dyad.centre
            .iter()
            .chain(&dyad.circle)
            .all(|x| x.is_finite())
            .then_some(dyad)
    }
}

/// A closed loop of the centre-point curve in the parameter u (see [`burmester_points`]).
#[derive(Debug, Clone, Copy)]
enum Loop {
    /// One branch over the whole turn of β2, u = β2 in [0, 2π].
    Whole(f64),
    /// Both branches over the interval [l, r] of β2 between two folds (u in [0, 2]), and the
    /// number of grid samples in it.
    Interval(f64, f64, usize),
}

impl Loop {
    fn span(&self) -> f64 {
        match self {
            Self::Whole(_) => TAU,
            Self::Interval(..) => 2.0,
        }
    }

    /// The number of samples over the loop for a grid of `n` over the turn.
    fn samples(&self, n: usize) -> usize {
        match self {
            Self::Whole(_) => n,
            Self::Interval(_, _, len) => (4 * len).max(64),
        }
    }

    /// (β2, branch, at a fold) at u.
    fn point(&self, u: f64) -> (f64, f64, bool) {
        match *self {
            Self::Whole(sign) => (u, sign, false),
            Self::Interval(l, r, _) => {
                let (v, sign) = if u <= 1.0 { (u, 1.0) } else { (2.0 - u, -1.0) };
                let beta2 = l + 0.5 * (r - l) * (1.0 - (std::f64::consts::PI * v).cos());
                (beta2, sign, v == 0.0 || v == 1.0)
            }
        }
    }
}

/// Burmester's points of five poses: the dyads that carry the coupler through all five (at
/// most four; none for some poses), where the centre-point curves of poses 1–4 and 1, 2, 3, 5
/// meet.
///
/// Derivation: along the centre-point curve of poses 1–4 (parameter β2, two branches; see
/// [`centre_point_curve`]) the dyad (W, Z) reaches pose 5 when some crank turn β5 solves
/// W(e^{iβ5} − 1) + Z(e^{iα5} − 1) = δ5, that is when |δ5 − Z(e^{iα5} − 1) + W| = |W|. The
/// difference of the two sides is scanned along the curve's loops (`n` samples of β2 over a
/// turn; near a fold, where the two branches meet and β2 turns back, in a parameter in which
/// the branches join smoothly) and every sign change is refined by bisection to machine
/// precision; a root is kept if the dyad fits all five poses to 1e-9 of its size.
///
/// # Examples
/// Five poses of the coupler of a four-bar: its two dyads are among Burmester's points.
/// ```
/// use tmm::synthesis::{burmester_points, Pose};
/// // The coupler of the crank-rocker O1 = (0, 0), A, B, O3 = (0.4, 0): five poses read off
/// // its motion (A on the crank of 0.1 m; B on the rocker of 0.3 m; coupler 0.35 m).
/// let (a, b, c, d) = (0.1, 0.35, 0.3, 0.4);
/// // The pose: the coupler point P, 0.1 m left of the middle of AB, and the angle of AB.
/// let pose = |phi: f64| {
///     let (ax, ay) = (a * phi.cos(), a * phi.sin());
///     let (vx, vy) = (d - ax, -ay);
///     let e = vx.hypot(vy);
///     let along = (b * b - c * c + e * e) / (2.0 * e);
///     let h = (b * b - along * along).sqrt();
///     let (bx, by) = (ax + along * vx / e - h * vy / e, ay + along * vy / e + h * vx / e);
///     let (ux, uy) = ((bx - ax) / b, (by - ay) / b);
///     Pose::new([ax + 0.5 * b * ux - 0.1 * uy, ay + 0.5 * b * uy + 0.1 * ux], uy.atan2(ux))
/// };
/// let poses = [0.3, 0.9, 1.6, 2.4, 3.0].map(pose);
/// let points = burmester_points(&poses, 2000)?;
/// // The crank O1A (centre (0, 0)) and the rocker O3B (centre (0.4, 0)) are among them.
/// let near = |x: f64, y: f64| points.iter().any(|p| (p.centre[0] - x).hypot(p.centre[1] - y) < 1e-8);
/// assert!(near(0.0, 0.0) && near(0.4, 0.0));
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number; [`Error::NoMechanism`] for coinciding poses;
/// [`Error::OutOfRange`] (`"n"`) for n below 8 or above [`MAX_POINTS`](super::MAX_POINTS).
pub fn burmester_points(poses: &[Pose; 5], n: usize) -> Result<Vec<Dyad>> {
    check_poses(poses)?;
    if !(8..=super::MAX_POINTS).contains(&n) {
        return Err(Error::OutOfRange {
            name: "n",
            value: n as f64,
            min: 8.0,
            max: super::MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    let compat = Compatibility::new(&poses[..4]);
    let a5 = rotation_minus_one(poses[4].angle - poses[0].angle);
    let d5 = C::new(poses[4].at[0], poses[4].at[1]) - compat.p1;
    // The signed miss of pose 5, scaled to the dyad's size.
    let miss_with = |beta2: f64, sign: f64, fold: bool| -> Option<f64> {
        let (w, z) = compat.standard_form_with(beta2, sign, fold)?;
        let m = (d5 - z * a5 + w).norm() - w.norm();
        let f = m / (w.norm() + z.norm() + compat.size);
        f.is_finite().then_some(f)
    };
    // The branches as closed loops in a parameter u: where the triangle closes over the
    // whole turn, each branch is a loop over β2; otherwise each interval [l, r] of closing
    // (its ends, the folds where the branches meet, found by bisection) is one loop, the
    // branch + for u in [0, 1] and − back for u in [1, 2], with β2 = l + (r − l)(1 − cos πu)/2
    // so that the square root at the folds becomes smooth in u (a root next to a fold is
    // then not lost between samples).
    let h = TAU / n as f64;
    let closes: Vec<bool> = (0..n).map(|k| compat.closes(h * k as f64)).collect();
    let mut loops: Vec<Loop> = Vec::new();
    if closes.iter().all(|&c| c) {
        loops.push(Loop::Whole(1.0));
        loops.push(Loop::Whole(-1.0));
    } else if closes.iter().any(|&c| c) {
        let fold = |inside: f64, outside: f64| {
            let (mut a, mut b) = (inside, outside);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if mid == a || mid == b {
                    break;
                }
                if compat.closes(mid) {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            a
        };
        // Runs of closing samples, cyclically, starting after a sample that does not close.
        let first_out = closes.iter().position(|&c| !c).unwrap_or(0);
        let mut k = 0;
        while k < n {
            let i = (first_out + k) % n;
            if closes[i] && !closes[(i + n - 1) % n] {
                let mut len = 0;
                while closes[(i + len) % n] {
                    len += 1;
                }
                let start = h * i as f64;
                let end = start + h * (len - 1) as f64;
                loops.push(Loop::Interval(
                    fold(start, start - h),
                    fold(end, end + h),
                    len,
                ));
                k += len;
            } else {
                k += 1;
            }
        }
    }
    let mut candidates: Vec<(f64, f64, bool)> = Vec::new();
    for lp in &loops {
        let m = lp.samples(n);
        let at = |u: f64| lp.point(u);
        let value = |u: f64| {
            let (beta2, sign, fold) = at(u);
            miss_with(beta2, sign, fold)
        };
        let us: Vec<f64> = (0..=m).map(|i| lp.span() * i as f64 / m as f64).collect();
        let vals: Vec<Option<f64>> = us.iter().map(|&u| value(u)).collect();
        if let Loop::Interval(..) = lp {
            candidates.push(at(0.0));
            candidates.push(at(1.0));
        }
        for i in 0..m {
            let (Some(flo), Some(fhi)) = (vals[i], vals[i + 1]) else {
                continue;
            };
            if flo == 0.0 {
                candidates.push(at(us[i]));
            }
            if flo * fhi < 0.0 {
                let (mut a, mut b, mut fa) = (us[i], us[i + 1], flo);
                for _ in 0..200 {
                    let mid = 0.5 * (a + b);
                    if mid == a || mid == b {
                        break;
                    }
                    let Some(fm) = value(mid) else { break };
                    if (fm < 0.0) == (fa < 0.0) && fm != 0.0 {
                        (a, fa) = (mid, fm);
                    } else {
                        b = mid;
                    }
                }
                candidates.push(at(0.5 * (a + b)));
            }
        }
    }
    let mut out: Vec<Dyad> = Vec::new();
    for (beta2, sign, fold) in candidates {
        let Some(dyad) = compat.dyad_with(beta2, sign, fold) else {
            continue;
        };
        let scale = compat.size + dyad.length();
        let duplicate = out.iter().any(|o| {
            (v(o.centre) - v(dyad.centre)).norm() < 1e-8 * scale
                && (v(o.circle) - v(dyad.circle)).norm() < 1e-8 * scale
        });
        if dyad.misfit(poses) <= 1e-9 * scale && !duplicate {
            out.push(dyad);
        }
    }
    Ok(out)
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
