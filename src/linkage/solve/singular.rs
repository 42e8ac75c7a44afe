//! Positions where the rates do not exist: a dead centre or a branch point of a group, where
//! its velocity system is singular but its position is still defined (two assembly modes
//! meet there, or the group is stretched straight). [`Plan::position`] returns the position
//! there, and the rates as the error that names the measure that vanished.
//!
//! The position pass is the ordinary one with the inputs at rest; a group whose closed form
//! refuses the position (its determinant vanished, or its closure fails by no more than
//! rounding: the tangent case) is placed by its position problem alone
//! ([`solve_contour_position`]), which has the tangent circles' one point (or the circle's
//! tangent point on a line). The RRR and RRP dyads are covered so. The other dyads have no
//! position where their rates fail: an RPR's slider hinge on the pivot of its guide leaves
//! the guide's direction free, and a PRP's or RPP's parallel guides meet nowhere or all
//! along a line; they report their error as before. A triad (revolute joints) at a branch
//! point, where two of its modes merge and the lines of its binary links meet at one point,
//! is placed by every mode of its certified bracket (which finds the double root of its
//! eliminated equation as one mode) and the one nearest its reference mode. A triad with a
//! sliding pair is placed so too, and then at the branch pose itself, where its velocity
//! system is singular ([`slider_triad_position`](crate::kinematics::slider_triad_position):
//! the scan's double root is only good to √ε of the size, the branch pose to ε). A general
//! group is placed only where its equations are regular.
//!
//! [`Plan::through`] gives the plan that moves on through a dead centre on the dyad's other
//! mode, as a mechanism carried by its inertia does.

use super::kinematics::Kinematics;
use super::state::{within, KinState};
use crate::angle::{normalize, unit};
use crate::error::{Error, Result};
use crate::kinematics::{solve_contour_position, LinkMotion, LoopVector, Motion, PointMotion};
use crate::linkage::inputs::Inputs;
use crate::linkage::plan::{Chain, Group, GroupKind, Plan};
use std::f64::consts::PI;

/// A position solved where its rates may not exist (see [`Plan::position`]).
#[derive(Debug, Clone)]
pub struct Position<'p> {
    k: Kinematics<'p>,
    rates: Option<Error>,
}

impl<'p> Position<'p> {
    /// The position: every position reading of [`Kinematics`] (joints, points, link
    /// angles, slides). Its rates are those of the inputs when [`rates`](Self::rates) is
    /// `Ok`, and zero (the linkage at rest) when it is not.
    #[must_use]
    pub fn pose(&self) -> &Kinematics<'p> {
        &self.k
    }

    /// The full kinematics (positions and rates) at the given input motions.
    ///
    /// # Errors
    /// The error of the group whose rates do not exist here: [`Error::In`] naming the group,
    /// around [`Error::Singular`] naming the measure that vanished (for an RRR dyad
    /// `sin(phi3 - phi2)`, with its value).
    pub fn rates(&self) -> Result<&Kinematics<'p>> {
        match &self.rates {
            None => Ok(&self.k),
            Some(e) => Err(e.clone()),
        }
    }
}

impl Plan {
    /// The position at one motion per input, also at a dead centre or a branch point, where
    /// [`kinematics`](Self::kinematics) fails because the rates do not exist there: the
    /// position is returned and the rates as the error naming the vanished measure
    /// ([`Position::rates`]).
    ///
    /// # Errors
    /// As [`kinematics`](Self::kinematics), for a position that does not exist (a group that
    /// cannot be assembled by more than rounding) or whose group is neither an RRR nor an RRP
    /// dyad nor a triad (with revolute joints or one sliding pair).
    ///
    /// # Examples
    /// A four-bar stretched straight: at φ = 0 its coupler (2 m) and rocker (1 m) lie along
    /// one line from the crank pin (1, 0) to the pivot (−2, 0).
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{Joint, Link, Linkage, Plan};
    /// use tmm::Error;
    /// let (s, c) = 0.5f64.sin_cos();
    /// let p = [c, s];
    /// // B at 2 m from the pin and 1 m from (−2, 0), left of the pin → pivot line.
    /// let (dx, dy) = (-2.0 - c, -s);
    /// let l = dx.hypot(dy);
    /// let x = 0.5 * (l + 3.0 / l);
    /// let h = (4.0 - x * x).sqrt();
    /// let b = [c + (x * dx - h * dy) / l, s + (x * dy + h * dx) / l];
    /// let linkage = Linkage {
    ///     name: "stretched".into(),
    ///     joints: vec![
    ///         Joint::revolute("O", [0.0, 0.0]),
    ///         Joint::revolute("P", p),
    ///         Joint::revolute("B", b),
    ///         Joint::revolute("Q", [-2.0, 0.0]),
    ///     ],
    ///     links: vec![
    ///         Link::new("frame", &["O", "Q"]),
    ///         Link::new("crank", &["O", "P"]),
    ///         Link::new("coupler", &["P", "B"]),
    ///         Link::new("rocker", &["B", "Q"]),
    ///     ],
    ///     ..Linkage::default()
    /// };
    /// let plan = Plan::new(&linkage)?;
    /// assert!(plan.kinematics(Motion::turning(0.0, 1.0)).is_err());
    /// let at = plan.position(Motion::turning(0.0, 1.0))?;
    /// assert!((at.pose().joint("B")?.p.x + 1.0).abs() < 1e-7);
    /// let Err(Error::In { source, .. }) = at.rates() else { panic!() };
    /// assert!(matches!(*source, Error::Singular { measure: "sin(phi3 - phi2)", .. }));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn position(&self, inputs: impl Into<Inputs>) -> Result<Position<'_>> {
        let inputs = inputs.into();
        let mut k = Kinematics::new(self);
        let first = match k.kin.solve(&self.chain, inputs.as_slice()) {
            Ok(()) => return Ok(Position { k, rates: None }),
            Err(e) => e,
        };
        let rest: Vec<Motion> = inputs
            .as_slice()
            .iter()
            .map(|m| Motion::fixed(m.value))
            .collect();
        let rates = k.kin.solve_positions(&self.chain, &rest).map_err(|e| {
            if matches!(e, Error::In { .. }) {
                e
            } else {
                first.clone()
            }
        })?;
        Ok(Position {
            k,
            rates: Some(rates.unwrap_or(first)),
        })
    }
}

impl KinState {
    /// Positions at the inputs `rest` (at rest), each group by its closed form or, where that
    /// refuses a defined position, by its position problem alone; the first such group's
    /// error (the rates' error) is returned with the positions.
    fn solve_positions(&mut self, chain: &Chain, rest: &[Motion]) -> Result<Option<Error>> {
        // The inputs and the groups before the first failing one are placed by this solve.
        let failed = match self.solve(chain, rest) {
            Ok(()) => return Ok(None),
            Err(e) => e,
        };
        if !matches!(failed, Error::In { .. }) {
            return Err(failed);
        }
        let mut rates = None;
        for (g, group) in chain.groups.iter().enumerate() {
            if let Err(e) = self.solve_group_kinematics(g, group) {
                let singular = self.position_only(g, group).map_err(|_| e)?;
                rates.get_or_insert(singular);
            }
        }
        Ok(rates)
    }

    /// Group `g` placed by its position problem alone, at rest; `Ok` with the error its rates
    /// have there (a vanished determinant).
    fn position_only(&mut self, g: usize, group: &Group) -> Result<Error> {
        if let (Some(t), None) = (&group.triad, &group.general) {
            return self.triad_position_only(g, group, t);
        }
        if group.kind == GroupKind::Rrp && group.triad.is_none() && group.general.is_none() {
            return self.rrp_position_only(g, group);
        }
        if group.kind != GroupKind::Rrr || group.triad.is_some() || group.general.is_some() {
            return Err(Error::Description {
                item: group.name.clone(),
                problem:
                    "its rates fail here, and only an RRR or RRP dyad or a triad is placed where \
                          they do (another dyad has no position there)"
                        .to_owned(),
            });
        }
        let [l2, l3] = group.links;
        let [ka, kc] = group.known;
        let (a, c) = (self.at(ka, group.a_local).p, self.at(kc, group.c_local).p);
        // The loop C → A → B → C, as the dyad's closed form writes it.
        let loop_ = [
            LoopVector::Cartesian {
                r: a - c,
                v: nalgebra::Vector2::zeros(),
                a: nalgebra::Vector2::zeros(),
            },
            LoopVector::unknown_angle(group.lengths[0]),
            LoopVector::unknown_angle(group.lengths[1]),
        ];
        let [phi2, phi3] = solve_contour_position(&loop_, group.branch)?;
        let phi3 = normalize(phi3 - PI);
        let at_rest = |p, angle| LinkMotion {
            origin: PointMotion::fixed(p),
            angle,
            omega: 0.0,
            epsilon: 0.0,
        };
        let (u2, u3) = (unit(phi2), unit(phi3));
        self.put_link(l2, at_rest(a, phi2), u2);
        self.put_link(l3, at_rest(c, phi3), u3);
        let det = crate::angle::cross(u2, u3);
        self.dets[g] = det;
        Ok(within(&group.name)(Error::Singular {
            what: "RRR dyad",
            measure: "sin(phi3 - phi2)",
            value: det,
        }))
    }

    /// An RRP dyad placed by its position problem alone (the rod's circle against the
    /// guide's line, which has the tangent point where they touch), at rest; `Ok` with the
    /// error its rates have there: the rod across the guide, cos(φ2 − φ4) = 0.
    fn rrp_position_only(&mut self, g: usize, group: &Group) -> Result<Error> {
        let [l2, l3] = group.links;
        let [ka, kc] = group.known;
        let a = self.at(ka, group.a_local).p;
        let guide = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
        let beta = guide.angle.value;
        // The loop G → A → B → G, as the dyad's closed form writes it (its Plus puts B ahead
        // along the guide: the contour's opposite).
        let loop_ = [
            LoopVector::Cartesian {
                r: a - guide.point.p,
                v: nalgebra::Vector2::zeros(),
                a: nalgebra::Vector2::zeros(),
            },
            LoopVector::unknown_angle(group.lengths[0]),
            LoopVector::unknown_length(Motion::fixed(beta + PI)),
        ];
        let [phi2, _] = solve_contour_position(&loop_, group.branch.flipped())?;
        let (u2, g4) = (unit(phi2), unit(beta));
        let b = a + group.lengths[0] * u2;
        let at_rest = |p, angle| LinkMotion {
            origin: PointMotion::fixed(p),
            angle,
            omega: 0.0,
            epsilon: 0.0,
        };
        self.put_link(l2, at_rest(a, phi2), u2);
        self.put_link(l3, at_rest(b, normalize(beta)), g4);
        let det = u2.dot(&g4);
        self.dets[g] = det;
        Ok(within(&group.name)(Error::Singular {
            what: "RRP dyad",
            measure: "cos(phi2 - phi4)",
            value: det,
        }))
    }
}

/// The largest |determinant| of a dyad that [`Plan::through`] takes for a dead centre. Near
/// a dead centre a dyad's determinant grows as the square root of the input's distance
/// from it, so this admits an input within about 10⁻⁶ (relative) of the dead centre: a
/// lock angle printed to six digits, or [`Plan::lock_positions`]'s exact one.
pub const DEAD_CENTRE_DETERMINANT: f64 = 1e-3;

impl Plan {
    /// The plan that carries the motion on through a dead centre at `at`: every RRR or RRP
    /// dyad at its dead centre there (|determinant| ≤ [`DEAD_CENTRE_DETERMINANT`]) takes
    /// its other assembly mode, all else unchanged.
    ///
    /// At a dead centre a dyad's two modes meet, and a mechanism that moves on through it
    /// (the inner joint crossing the line of the outer ones, as a flywheel carries a crank
    /// past the dead centre of a piston's stroke) leaves on the other mode. So a rocking
    /// input that reverses at its lock (a slider driving a crank, a rocker driving a
    /// triple-rocker) runs its return sweep on `plan.through(lock)`, and the motion of the
    /// links it drives keeps its sense instead of folding back. At the dead centre both plans
    /// give the same position.
    ///
    /// # Errors
    /// The errors of [`position`](Self::position); [`Error::Description`] (field `inputs`)
    /// when no RRR or RRP dyad is at a dead centre at `at`, naming the dyad nearest one and
    /// its determinant.
    ///
    /// # Examples
    /// The four-bar of [`position`](Self::position), stretched straight at φ = 0: on the
    /// other mode, B is on the other side of the line from the crank pin to the pivot.
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{Joint, Link, Linkage, Plan};
    /// let (s, c) = 0.5f64.sin_cos();
    /// let (dx, dy) = (-2.0 - c, -s);
    /// let l = dx.hypot(dy);
    /// let x = 0.5 * (l + 3.0 / l);
    /// let h = (4.0 - x * x).sqrt();
    /// let b = [c + (x * dx - h * dy) / l, s + (x * dy + h * dx) / l];
    /// let linkage = Linkage {
    ///     name: "stretched".into(),
    ///     joints: vec![
    ///         Joint::revolute("O", [0.0, 0.0]),
    ///         Joint::revolute("P", [c, s]),
    ///         Joint::revolute("B", b),
    ///         Joint::revolute("Q", [-2.0, 0.0]),
    ///     ],
    ///     links: vec![
    ///         Link::new("frame", &["O", "Q"]),
    ///         Link::new("crank", &["O", "P"]),
    ///         Link::new("coupler", &["P", "B"]),
    ///         Link::new("rocker", &["B", "Q"]),
    ///     ],
    ///     ..Linkage::default()
    /// };
    /// let plan = Plan::new(&linkage)?;
    /// let on = plan.through(Motion::fixed(0.0))?;
    /// // Which side of the line from the pin P to the pivot Q the joint B is on.
    /// let side = |p: &Plan, phi: f64| -> Result<f64, tmm::Error> {
    ///     let k = p.kinematics(Motion::fixed(phi))?;
    ///     let (p, b) = (k.joint("P")?.p, k.joint("B")?.p);
    ///     Ok((-2.0 - p.x) * (b.y - p.y) + p.y * (b.x - p.x))
    /// };
    /// assert!(side(&plan, -0.1)? * side(&on, -0.1)? < 0.0);
    /// assert!(side(&plan, 0.1)? * side(&on, 0.1)? < 0.0);
    /// assert!(plan.through(Motion::fixed(0.5)).is_err()); // no dead centre there
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn through(&self, at: impl Into<Inputs>) -> Result<Plan> {
        let position = self.position(at)?;
        let dets = position.pose().group_determinants();
        let dyads = || {
            self.chain.groups.iter().enumerate().filter(|(_, g)| {
                matches!(g.kind, GroupKind::Rrr | GroupKind::Rrp)
                    && g.triad.is_none()
                    && g.general.is_none()
            })
        };
        let mut next = self.clone();
        let mut flipped = false;
        for (g, _) in dyads().filter(|(g, _)| dets[*g].abs() <= DEAD_CENTRE_DETERMINANT) {
            let group = &mut next.chain.groups[g];
            group.branch = group.branch.flipped();
            flipped = true;
        }
        if flipped {
            return Ok(next);
        }
        let nearest = dyads().min_by(|(a, _), (b, _)| dets[*a].abs().total_cmp(&dets[*b].abs()));
        Err(Error::Description {
            item: "inputs".to_owned(),
            problem: match nearest {
                Some((g, group)) => format!(
                    "no dyad is at a dead centre here: the nearest, {}, has |determinant| {:.3e} \
                     (at most {DEAD_CENTRE_DETERMINANT:e} at a dead centre)",
                    group.name,
                    dets[g].abs()
                ),
                None => "the linkage has no RRR or RRP dyad, whose mode could change at a \
                         dead centre"
                    .to_owned(),
            },
        })
    }
}
