//! Internal forces N, Q, M along a link, by the method of sections, and their extremes.
//!
//! Sign conventions (one set for every link and every state, so diagrams multiply
//! consistently): at a section with the unit tangent t (direction of increasing `s`) and
//! n = t turned +90°, the part of the link beyond the section acts on the part before it with
//! the force N·t − Q·n and the couple M (counter-clockwise). So N > 0 is tension, Q is the
//! sum of the transverse (along n) forces before the section, and dM/ds = Q. For a horizontal
//! beam run left to right this is the textbook convention: Q positive up on the left part,
//! M positive when the beam sags.

use super::geometry::{Frame, Link, Side};
use super::integrate::simpson_product;
use super::loads::{distributed_resultant, Loads};
use super::statics::Reactions;
use crate::angle::{cross, perp};
use nalgebra::Vector2;

/// The internal forces at a section: axial force N (N, tension positive), shear force Q (N)
/// and bending moment M (N·m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct InternalForces {
    /// Axial force, N, tension positive.
    pub n: f64,
    /// Shear force, N (dM/ds = Q).
    pub q: f64,
    /// Bending moment, N·m.
    pub m: f64,
}

/// The largest and smallest value of one diagram along a link, and where they occur (arc
/// length from the link's start, m).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Extreme {
    /// The largest value.
    pub max: f64,
    /// Where the largest value occurs, m.
    pub at_max: f64,
    /// The smallest value.
    pub min: f64,
    /// Where the smallest value occurs, m.
    pub at_min: f64,
}

impl Extreme {
    fn new() -> Self {
        Self {
            max: f64::NEG_INFINITY,
            at_max: 0.0,
            min: f64::INFINITY,
            at_min: 0.0,
        }
    }

    fn add(&mut self, s: f64, v: f64) {
        if v > self.max {
            self.max = v;
            self.at_max = s;
        }
        if v < self.min {
            self.min = v;
            self.at_min = s;
        }
    }

    /// The value of largest magnitude (with its sign) and where it occurs: the design value.
    #[must_use]
    pub fn max_abs(&self) -> (f64, f64) {
        if self.max.abs() >= self.min.abs() {
            (self.max, self.at_max)
        } else {
            (self.min, self.at_min)
        }
    }
}

/// The extremes of the three diagrams of one link.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DiagramExtremes {
    /// Axial force N.
    pub n: Extreme,
    /// Shear force Q.
    pub q: Extreme,
    /// Bending moment M.
    pub m: Extreme,
}

/// A force and a couple applied to a link at the arc length `s`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Action {
    pub s: f64,
    pub force: Vector2<f64>,
    pub couple: f64,
}

/// Everything that acts on one link in one state: point actions (hinge forces and loads) and
/// a uniform load per unit length.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct LinkCase {
    pub link: Link,
    actions: [Action; 5],
    count: usize,
    w: Vector2<f64>,
}

impl LinkCase {
    /// The forces on `link` when the hinges carry `r` and the known loads are `loads`.
    pub fn new(frame: &Frame, loads: &Loads, r: &Reactions, link: Link) -> Self {
        let l = frame.l[link.index()];
        let none = Action {
            s: 0.0,
            force: Vector2::zeros(),
            couple: 0.0,
        };
        let force = |s, force| Action {
            s,
            force,
            couple: 0.0,
        };
        let load = |x: super::LinkLoad| Action {
            s: x.at,
            force: x.force,
            couple: x.moment,
        };
        let (actions, count) = match link {
            Link::Ab => (
                [
                    force(0.0, r.r01),
                    load(loads.f1),
                    force(l, -r.r13),
                    none,
                    none,
                ],
                3,
            ),
            Link::Cd => (
                [
                    force(0.0, r.r02),
                    load(loads.f2),
                    force(l, -r.r23),
                    none,
                    none,
                ],
                3,
            ),
            Link::Bde => (
                [
                    force(0.0, r.r13),
                    force(frame.l_bd, r.r23),
                    load(loads.f3),
                    load(loads.m),
                    force(l, r.r03),
                ],
                5,
            ),
        };
        Self {
            link,
            actions,
            count,
            w: loads.per_length[link.index()],
        }
    }

    fn actions(&self) -> &[Action] {
        &self.actions[..self.count]
    }

    /// The sum of the forces on the link and of their moments about its start, with the
    /// moments divided by `size` (a residual in newtons).
    pub fn residual(&self, frame: &Frame) -> (Vector2<f64>, f64) {
        let g = &frame.g;
        let pole = g.point_at(self.link, 0.0);
        let mut f = Vector2::zeros();
        let mut m = 0.0;
        for a in self.actions() {
            f += a.force;
            m += a.couple + cross(g.point_at(self.link, a.s) - pole, a.force);
        }
        let (wf, wm) = distributed_resultant(
            frame,
            self.w,
            self.link,
            0.0,
            frame.l[self.link.index()],
            pole,
        );
        (f + wf, m + wm)
    }

    /// The internal forces at the section `s` (one-sided limit `side`).
    pub fn at(&self, frame: &Frame, s: f64, side: Side) -> InternalForces {
        let g = &frame.g;
        let s = s.clamp(0.0, frame.l[self.link.index()]);
        let p = g.point_at(self.link, s);
        let t = g.tangent(self.link, s, side);
        let n = perp(t);
        let mut f = Vector2::zeros();
        let mut m = 0.0;
        for a in self.actions() {
            let before = match side {
                Side::Before => a.s < s,
                Side::After => a.s <= s,
            };
            if before {
                f += a.force;
                m += a.couple + cross(g.point_at(self.link, a.s) - p, a.force);
            }
        }
        let (wf, wm) = distributed_resultant(frame, self.w, self.link, 0.0, s, p);
        f += wf;
        m += wm;
        InternalForces {
            n: -f.dot(&t),
            q: f.dot(&n),
            m: -m,
        }
    }

    /// The sorted arc lengths where a diagram may jump or kink, including both ends.
    pub fn breakpoints(&self, frame: &Frame, other: Option<&LinkCase>) -> ([f64; 16], usize) {
        let mut b = [0.0; 16];
        let mut k = 0;
        let mut push = |s: f64| {
            b[k] = s;
            k += 1;
        };
        push(0.0);
        push(frame.l[self.link.index()]);
        if let Some(bend) = frame.bends(self.link) {
            push(bend);
        }
        for a in self.actions() {
            push(a.s);
        }
        if let Some(o) = other {
            for a in o.actions() {
                push(a.s);
            }
        }
        b[..k].sort_by(f64::total_cmp);
        let mut n = 0;
        for i in 0..k {
            if n == 0 || b[i] > b[n - 1] {
                b[n] = b[i];
                n += 1;
            }
        }
        (b, n)
    }

    /// The integrals ∫ M·M'/EI ds and ∫ N·N'/EA ds of this state against `other` over the
    /// link (Simpson's formula on each smooth piece: exact, since one of the two states
    /// always has a piecewise-linear diagram in the force method).
    pub fn product(&self, frame: &Frame, other: &LinkCase, ei: f64, ea: Option<f64>) -> (f64, f64) {
        let (b, n) = self.breakpoints(frame, Some(other));
        let mut bending = 0.0;
        let mut axial = 0.0;
        for w in b[..n].windows(2) {
            let (s0, s1) = (w[0], w[1]);
            let sm = 0.5 * (s0 + s1);
            let f = [
                self.at(frame, s0, Side::After),
                self.at(frame, sm, Side::After),
                self.at(frame, s1, Side::Before),
            ];
            let g = [
                other.at(frame, s0, Side::After),
                other.at(frame, sm, Side::After),
                other.at(frame, s1, Side::Before),
            ];
            bending += simpson_product(s1 - s0, f.map(|x| x.m), g.map(|x| x.m));
            if ea.is_some() {
                axial += simpson_product(s1 - s0, f.map(|x| x.n), g.map(|x| x.n));
            }
        }
        (bending / ei, ea.map_or(0.0, |ea| axial / ea))
    }

    /// The extremes of N, Q and M along the link: at every piece's ends (both one-sided
    /// limits) and, for M, where Q changes sign inside a piece (M is quadratic there).
    pub fn extremes(&self, frame: &Frame) -> DiagramExtremes {
        let (b, n) = self.breakpoints(frame, None);
        let mut ex = DiagramExtremes {
            n: Extreme::new(),
            q: Extreme::new(),
            m: Extreme::new(),
        };
        for w in b[..n].windows(2) {
            let (s0, s1) = (w[0], w[1]);
            let fa = self.at(frame, s0, Side::After);
            let fb = self.at(frame, s1, Side::Before);
            for (s, f) in [(s0, fa), (s1, fb)] {
                ex.n.add(s, f.n);
                ex.q.add(s, f.q);
                ex.m.add(s, f.m);
            }
            if fa.q * fb.q < 0.0 {
                let s = s0 + (s1 - s0) * fa.q / (fa.q - fb.q);
                ex.m.add(s, self.at(frame, s, Side::After).m);
            }
        }
        ex
    }
}
