#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The instant centres of velocity of every pair of links at one position, by the theorem of
//! Aronhold and Kennedy: the primary centres at the joints (a hinge is the centre of its two
//! links; a sliding pair's lies at infinity across its guide), then each missing centre C_ij
//! where two lines C_ik–C_kj meet (the three centres of any three links lie on one line).
//! A centre that no pair of such lines fixes (some six-bars have them) is read off the
//! velocities instead: the point where the two links' velocity fields agree.
//!
//! A centre at infinity (two links translating relative to each other: parallel lines of
//! Kennedy, or equal angular velocities) is reported as a direction, never as a point with
//! infinite coordinates.

use super::handle::LinkId;
use super::plan::{Plan, Pose};
use crate::angle::{cross, perp};
use crate::error::{Error, Result};
use nalgebra::{Point2, Vector2};

/// Where an instant centre lies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Centre {
    /// At a point of the plane, m.
    At(Point2<f64>),
    /// At infinity: every line through it has the unit direction given (the two links
    /// translate relative to each other, perpendicular to it).
    Infinite(Vector2<f64>),
}

/// How an instant centre was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Found {
    /// A primary centre: the joint between the two links.
    Joint,
    /// By the theorem of Aronhold and Kennedy, from two lines of three centres.
    Kennedy,
    /// From the velocities (a centre that Kennedy's theorem leaves open).
    Velocities,
}

/// The instant centre of two links.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InstantCentre {
    /// The two links, the lower index first.
    pub links: [LinkId; 2],
    /// Where it lies.
    pub centre: Centre,
    /// How it was found.
    pub found: Found,
}

/// A line through a point along a direction.
type Line = (Point2<f64>, Vector2<f64>);

impl Plan {
    /// The instant centres of every pair of links at the position `pose`, n(n − 1)/2 of them
    /// for n links (the frame among them), in the order (0, 1), (0, 2), …, (1, 2), …
    ///
    /// # Errors
    /// [`Error::Description`] for a pose of another plan; [`Error::Singular`] for a centre
    /// that Kennedy's theorem leaves open where the two links are at rest relative to each
    /// other (every point is then their centre), as at a pose whose rates are all zero: solve
    /// the position at a non-zero input rate.
    ///
    /// # Examples
    /// The four-bar's coupler turns about the meeting point of its crank's and rocker's
    /// lines (the centre C_02), where its velocity vanishes:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Centre, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let k = plan.kinematics(Motion::turning(0.7, 10.0))?;
    /// let ics = plan.instant_centres(&k.pose())?;
    /// assert_eq!(ics.len(), 6);
    /// let c02 = ics.iter().find(|c| c.links.map(|l| l.index()) == [0, 2]).unwrap();
    /// let Centre::At(p) = c02.centre else { panic!() };
    /// assert!(k.link_motion("coupler")?.motion_of(p).v.norm() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn instant_centres(&self, pose: &Pose<'_>) -> Result<Vec<InstantCentre>> {
        if !(std::ptr::eq(pose.chain, &self.chain) || *pose.chain == self.chain) {
            return Err(super::plan::bad("pose", "is a position of another plan"));
        }
        let n = self.chain.link_names.len();
        let mut known: Vec<Option<(Centre, Found)>> = vec![None; n * n];
        let slot = |i: usize, j: usize| i.min(j) * n + i.max(j);
        for (j, jp) in self.chain.joints.iter().enumerate() {
            let [a, b] = jp.links;
            let c = if jp.prismatic.is_some() {
                Centre::Infinite(perp(pose.guide_direction_at(j)))
            } else {
                Centre::At(pose.joint_position_on(j, a))
            };
            known[slot(a, b)].get_or_insert((c, Found::Joint));
        }
        // Each sweep fixes every centre two known lines meet at; a sweep that fixes none ends.
        let size = self.chain.size.max(f64::MIN_POSITIVE);
        loop {
            let mut fixed = false;
            for i in 0..n {
                for j in i + 1..n {
                    if known[slot(i, j)].is_some() {
                        continue;
                    }
                    let mut lines = Vec::new();
                    let mut shared = None;
                    for k in (0..n).filter(|&k| k != i && k != j) {
                        let (Some((ci, fi)), Some((cj, fj))) =
                            (known[slot(i, k)], known[slot(k, j)])
                        else {
                            continue;
                        };
                        // Both turn about one point relative to k: it is theirs too (the links
                        // of a hinge of three, or centres that meet).
                        if let (Centre::At(p), Centre::At(q)) = (ci, cj)
                            && (p - q).norm() <= 1e-12 * size
                        {
                            let how = if fi == Found::Joint && fj == Found::Joint {
                                Found::Joint
                            } else {
                                Found::Kennedy
                            };
                            shared = Some((ci, how));
                            break;
                        }
                        lines.extend(line_through(ci, cj));
                    }
                    let found = shared.or_else(|| meet(&lines, size).map(|c| (c, Found::Kennedy)));
                    if found.is_some() {
                        known[slot(i, j)] = found;
                        fixed = true;
                    }
                }
            }
            if !fixed {
                break;
            }
        }
        let mut out = Vec::with_capacity(n * (n - 1) / 2);
        for i in 0..n {
            for j in i + 1..n {
                let (centre, found) = match known[slot(i, j)] {
                    Some(c) => c,
                    None => (from_velocities(pose, i, j)?, Found::Velocities),
                };
                out.push(InstantCentre {
                    links: [LinkId(i), LinkId(j)],
                    centre,
                    found,
                });
            }
        }
        Ok(out)
    }
}

/// The line through two centres (two distinct points, or a point and a direction): `None`
/// when both are at infinity.
fn line_through(a: Centre, b: Centre) -> Option<Line> {
    match (a, b) {
        (Centre::At(p), Centre::At(q)) => Some((p, (q - p).normalize())),
        (Centre::At(p), Centre::Infinite(d)) | (Centre::Infinite(d), Centre::At(p)) => Some((p, d)),
        (Centre::Infinite(_), Centre::Infinite(_)) => None,
    }
}

/// Where the lines (unit directions) meet, from the pair that crosses most steeply: a
/// point, or a direction at infinity when they are all parallel and not all one line;
/// `None` when fewer than two distinct lines are given.
fn meet(lines: &[Line], size: f64) -> Option<Centre> {
    let mut best: Option<(f64, Line, Line)> = None;
    let mut parallel: Option<Vector2<f64>> = None;
    for (k, &(p1, d1)) in lines.iter().enumerate() {
        for &(p2, d2) in &lines[k + 1..] {
            let s = cross(d1, d2).abs();
            if s <= 1e-12 {
                // Parallel: distinct lines meet at infinity; one line twice fixes nothing.
                if cross(p2 - p1, d1).abs() > 1e-12 * size {
                    parallel = Some(d1);
                }
                continue;
            }
            if best.is_none_or(|(b, _, _)| s > b) {
                best = Some((s, (p1, d1), (p2, d2)));
            }
        }
    }
    match (best, parallel) {
        (Some((_, (p1, d1), (p2, d2))), _) => {
            let t = cross(p2 - p1, d2) / cross(d1, d2);
            Some(Centre::At(p1 + t * d1))
        }
        (None, Some(d)) => Some(Centre::Infinite(d)),
        (None, None) => None,
    }
}

/// The centre of links `i` and `j` from their velocity fields: where the relative velocity
/// v_rel(Q) + ω_rel × (P − Q) vanishes, P = Q + (−v_y, v_x)/ω_rel; at infinity across the
/// relative velocity when ω_rel vanishes.
fn from_velocities(pose: &Pose<'_>, i: usize, j: usize) -> Result<Centre> {
    let (mi, mj) = (pose.links[i], pose.links[j]);
    let q = mi.origin.p;
    let v = mi.origin.v - mj.motion_of(q).v;
    let w = mi.omega - mj.omega;
    let scale = pose.links.iter().map(|m| m.omega.abs()).fold(0.0, f64::max);
    let vs = pose
        .links
        .iter()
        .map(|m| m.origin.v.norm())
        .fold(0.0, f64::max);
    if w.abs() <= 1e-12 * scale && !(v.norm() > 1e-12 * vs) {
        // At rest relative to each other (or every rate zero): every point is their centre.
        return Err(Error::Singular {
            what: "an instant centre left open by Kennedy's theorem",
            measure: "the relative velocity of its two links",
            value: v.norm(),
        });
    }
    if w.abs() <= 1e-12 * scale {
        return Ok(Centre::Infinite(perp(v).normalize()));
    }
    Ok(Centre::At(q + Vector2::new(-v.y, v.x) / w))
}
