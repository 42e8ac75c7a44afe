#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The instant centres of velocity of every pair of links at one position, by the theorem of
//! Aronhold and Kennedy: the primary centres at the joints (a hinge is the centre of its two
//! links; a sliding pair's lies at infinity across its guide), then each missing centre C_ij
//! where two lines C_ik–C_kj meet (the three centres of any three links lie on one line).
//! A centre that no pair of such lines fixes (some six-bars have them) is read off the
//! velocities instead: the point where the two links' velocity fields agree, the fields from
//! the chain's velocity equations at the position (a unit-rate solve, up to scale). For a
//! linkage of one input every centre is thus geometry alone: the same at any input rate, at
//! rest too (`Motion::fixed`, a rocking input at its lock). A linkage of two inputs has its
//! centres where its inputs' rates put them (their ratio), from the pose's rates.
//!
//! The centres name their links by the plan's [`LinkId`]s (the frame is link 0 of the plan),
//! and are labelled by the user's numbering: each link's place in the description's `links`
//! list ([`Plan::link_number`], 0 the first written), so that the centre of the links written
//! 1st and 3rd reads I13 wherever the frame was written ([`InstantCentre::label`]; the
//! scheme writes these labels and a key of the numbers with the links' names).
//!
//! A centre at infinity (two links translating relative to each other: parallel lines of
//! Kennedy, or equal angular velocities) is reported as a direction, never as a point with
//! infinite coordinates.

use super::handle::LinkId;
use super::plan::{Chain, InputPlan, Plan, Pose};
use crate::angle::{cross, perp};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector, Point2, Vector2};

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
    /// From the velocities of the chain's motion at the position, a unit-rate solve up to
    /// scale (a centre that Kennedy's theorem leaves open).
    Velocities,
}

/// The instant centre of two links.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InstantCentre {
    /// The two links, the lower index first (the plan's link indices, 0 the frame; the
    /// user's numbers are [`Plan::link_number`], the label [`InstantCentre::label`]).
    pub links: [LinkId; 2],
    /// Where it lies.
    pub centre: Centre,
    /// How it was found.
    pub found: Found,
}

impl InstantCentre {
    /// The centre's label in the user's numbering of the links ([`Plan::link_number`]):
    /// `I13` for the links written 1st and 3rd in the description's `links` (counting from
    /// 0), the smaller number first; with a number of two digits or more the two are
    /// separated, `I3,12`.
    ///
    /// # Errors
    /// [`Error::Description`] for a centre whose links are not `plan`'s.
    ///
    /// # Examples
    /// The four-bar written with its frame last: its crank (written first, number 0) and
    /// rocker (number 2) have the centre I02, whatever the plan's own order:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let mut four_bar = bundled::four_bar();
    /// four_bar.links.rotate_left(1); // crank, coupler, rocker, frame
    /// let plan = Plan::new(&four_bar)?;
    /// let k = plan.kinematics(Motion::fixed(0.7))?;
    /// let crank = plan.link_id("crank")?;
    /// let rocker = plan.link_id("rocker")?;
    /// let ics = plan.instant_centres(&k.pose())?;
    /// let ic = ics.iter().find(|c| c.links.contains(&crank) && c.links.contains(&rocker));
    /// assert_eq!(ic.unwrap().label(&plan)?, "I02");
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn label(&self, plan: &Plan) -> Result<String> {
        let [a, b] = self.links.map(|l| plan.link_number(l));
        let (a, b) = (a?, b?);
        let (a, b) = (a.min(b), a.max(b));
        Ok(if a.max(b) >= 10 {
            format!("I{a},{b}")
        } else {
            format!("I{a}{b}")
        })
    }
}

impl Plan {
    /// The user's number of a link: its place in the description's `links` list, 0 the first
    /// written (the plan itself puts the frame first: [`Plan::link_names`]).
    ///
    /// # Errors
    /// As [`Plan::link_id`].
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let mut four_bar = bundled::four_bar();
    /// four_bar.links.rotate_left(1); // crank, coupler, rocker, frame
    /// let plan = Plan::new(&four_bar)?;
    /// assert_eq!(plan.link_names()[0], "frame");
    /// assert_eq!(plan.link_number("frame")?, 3);
    /// assert_eq!(plan.link_number("crank")?, 0);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn link_number(&self, link: impl super::LinkRef) -> Result<usize> {
        Ok(self.chain.link_order[self.chain.link(link)?])
    }
}

/// A line through a point along a direction.
type Line = (Point2<f64>, Vector2<f64>);

impl Plan {
    /// The instant centres of every pair of links at the position `pose`, n(n − 1)/2 of them
    /// for n links (the frame among them), in the order (0, 1), (0, 2), …, (1, 2), …
    ///
    /// # Errors
    /// [`Error::Description`] for a pose of another plan; [`Error::Singular`] for a centre
    /// that Kennedy's theorem leaves open where the velocity equations of the position have
    /// more motions than inputs (a branch point: the singular value that vanished, relative
    /// to the largest), where
    /// the two links are at rest relative to each other (every point is then their centre),
    /// or, with two inputs, where both input rates of the pose are zero.
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
        // The pairs left open are read off one unit-rate solve of this position.
        let fields = if known
            .iter()
            .enumerate()
            .any(|(s, c)| c.is_none() && s / n < s % n)
        {
            chain_motion(&self.chain, pose)?
        } else {
            Vec::new()
        };
        let mut out = Vec::with_capacity(n * (n - 1) / 2);
        for i in 0..n {
            for j in i + 1..n {
                let (centre, found) = match known[slot(i, j)] {
                    Some(c) => c,
                    None => (from_velocities(&fields, size, i, j)?, Found::Velocities),
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

/// Each link's velocity field in the chain's motion at the position of `pose`, as (u, ω)
/// with the velocity of the link's point P equal to u + ω·perp(P) (u: the velocity of the
/// link's point passing the origin; the frame's is (0, 0)). With one input the fields are
/// those of a unit-rate solve up to a common factor, which no centre depends on; with two,
/// those of the pose's input rates, whose ratio the centres depend on.
///
/// One linear system of the whole chain at the pose's positions, whatever its groups: each
/// hinge makes its two links' velocities agree at the hinge; each sliding pair makes their
/// angular velocities equal and their relative velocity run along its guide. With one input
/// its motions form a line, the null space of these equations (found by the SVD, so that a
/// rocking input at its lock, whose own rate vanishes there, is not singular); two inputs add
/// their rates as equations. Only positions are read: the centres do not depend on the rates.
/// The unknown ω is scaled by the plan's size so that the columns are alike.
fn chain_motion(chain: &Chain, pose: &Pose<'_>) -> Result<Vec<(Vector2<f64>, f64)>> {
    let n = chain.link_names.len();
    let size = chain.size.max(f64::MIN_POSITIVE);
    let two = chain.input_count() == 2;
    let rates: Vec<f64> = pose.inputs().as_slice().iter().map(|m| m.rate).collect();
    if two && rates.iter().all(|&r| r == 0.0) {
        return Err(Error::Singular {
            what: "an instant centre left open by Kennedy's theorem (two inputs at rest)",
            measure: "the input rates",
            value: 0.0,
        });
    }
    let cols = 3 * (n - 1);
    let equations = 2 * chain.joints.len() + if two { 2 } else { 0 };
    // Rows of zeros pad the system to a square at least, so that the SVD gives every
    // singular vector.
    let mut a = DMatrix::<f64>::zeros(equations.max(cols), cols);
    let mut b = DVector::<f64>::zeros(equations.max(cols));
    // Adds `sign` × (the velocity of link k's point P, projected on `on`) to row r.
    let put =
        |a: &mut DMatrix<f64>, r: usize, k: usize, p: Point2<f64>, on: Vector2<f64>, sign: f64| {
            if k == 0 {
                return;
            }
            let c = 3 * (k - 1);
            a[(r, c)] += sign * on.x;
            a[(r, c + 1)] += sign * on.y;
            a[(r, c + 2)] += sign * on.dot(&perp(p.coords)) / size;
        };
    for (j, jp) in chain.joints.iter().enumerate() {
        let [ka, kb] = jp.links;
        let p = pose.joint_position_on(j, ka);
        let r = 2 * j;
        if jp.prismatic.is_some() {
            let across = perp(pose.guide_direction_at(j));
            put(&mut a, r, ka, p, across, 1.0);
            put(&mut a, r, kb, p, across, -1.0);
            for (k, sign) in [(ka, 1.0), (kb, -1.0)] {
                if k != 0 {
                    a[(r + 1, 3 * (k - 1) + 2)] += sign;
                }
            }
        } else {
            for (row, on) in [(r, Vector2::x()), (r + 1, Vector2::y())] {
                put(&mut a, row, ka, p, on, 1.0);
                put(&mut a, row, kb, p, on, -1.0);
            }
        }
    }
    if two {
        for (i, (ip, &rate)) in chain.inputs().zip(&rates).enumerate() {
            let (r, k) = (2 * chain.joints.len() + i, ip.link());
            match ip {
                InputPlan::Crank { .. } => {
                    a[(r, 3 * (k - 1) + 2)] = 1.0;
                    b[r] = rate * size;
                }
                InputPlan::Slider { .. } => {
                    put(&mut a, r, k, pose.links[k].origin.p, pose.units[k], 1.0);
                    b[r] = rate;
                }
            }
        }
    }
    let svd = a.svd(true, true);
    let mut sigma: Vec<(f64, usize)> = svd.singular_values.iter().copied().zip(0..).collect();
    sigma.sort_by(|x, y| x.0.total_cmp(&y.0));
    let hi = sigma.last().map_or(0.0, |s| s.0);
    // One input: one motion (the smallest singular value ~0, the next not); two: none free.
    let free = usize::from(!two);
    let conditioning = sigma[free].0 / hi;
    if !(conditioning > 1e-12) {
        return Err(Error::Singular {
            what: "the chain's motion for an instant centre left open by Kennedy's theorem",
            measure: "a singular value of the chain's velocity equations beyond its mobility \
                      (relative to the largest)",
            value: conditioning,
        });
    }
    let x = if two {
        svd.solve(&b, 0.0)
            .map_err(|_| super::plan::bad("pose", "has no velocity solution"))?
    } else {
        let Some(v_t) = svd.v_t.as_ref() else {
            return Err(super::plan::bad("pose", "has no velocity solution"));
        };
        v_t.row(sigma[0].1).transpose()
    };
    let mut fields = vec![(Vector2::zeros(), 0.0); n];
    for (k, f) in fields.iter_mut().enumerate().skip(1) {
        let c = 3 * (k - 1);
        *f = (Vector2::new(x[c], x[c + 1]), x[c + 2] / size);
    }
    Ok(fields)
}

/// The centre of links `i` and `j` from their velocity fields (u, ω) of
/// [`chain_motion`]: where the relative velocity u_rel + ω_rel·perp(P) vanishes,
/// P = (−u_rel,y, u_rel,x)/ω_rel; at infinity across the relative velocity when ω_rel
/// vanishes.
fn from_velocities(
    fields: &[(Vector2<f64>, f64)],
    size: f64,
    i: usize,
    j: usize,
) -> Result<Centre> {
    let u = fields[i].0 - fields[j].0;
    let w = fields[i].1 - fields[j].1;
    // The largest speed of the links' points within the plan's size of the origin.
    let scale = fields
        .iter()
        .map(|(u, w)| u.norm() + w.abs() * size)
        .fold(0.0, f64::max);
    if w.abs() * size <= 1e-12 * scale {
        if !(u.norm() > 1e-12 * scale) {
            // At rest relative to each other: every point is their centre.
            return Err(Error::Singular {
                what: "an instant centre left open by Kennedy's theorem",
                measure: "the relative velocity of its two links",
                value: u.norm(),
            });
        }
        return Ok(Centre::Infinite(perp(u).normalize()));
    }
    Ok(Centre::At(Point2::new(-u.y / w, u.x / w)))
}
