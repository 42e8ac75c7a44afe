//! The known loads on the group: a point load on each link (F1, F2, F3), a second one on link 3
//! (the seed's couple M at E), and a uniformly distributed load on each link (a weight).

use super::geometry::{Frame, Geometry, Link};
use crate::angle::cross;
use crate::error::{finite, finite2, Error, Result};
use nalgebra::{Point2, Vector2};

/// A force and a couple applied at one section of a link.
///
/// `at` is the arc length from the link's start (A for link 1, C for link 2, B for link 3,
/// which runs B → D → E), m. Force in N (global x, y components), couple in N·m,
/// counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinkLoad {
    /// Arc length of the section from the link's start, m.
    pub at: f64,
    /// The force, N.
    pub force: Vector2<f64>,
    /// The couple, N·m, counter-clockwise positive.
    pub moment: f64,
}

impl LinkLoad {
    /// No load.
    pub const NONE: LinkLoad = LinkLoad {
        at: 0.0,
        force: Vector2::new(0.0, 0.0),
        moment: 0.0,
    };

    /// A force at the section `at`.
    #[must_use]
    pub fn force(at: f64, force: Vector2<f64>) -> Self {
        Self {
            at,
            force,
            moment: 0.0,
        }
    }

    /// A couple at the section `at`.
    #[must_use]
    pub fn couple(at: f64, moment: f64) -> Self {
        Self {
            at,
            force: Vector2::zeros(),
            moment,
        }
    }
}

/// All known loads on the group.
///
/// The seed's loads are F1 (on link 1), F2 (on link 2), F3 and the couple M (both on link 3).
/// Each of them may carry both a force and a couple, so an inertia load (−m·a_S at S plus
/// −J_S·ε) fits in one [`LinkLoad`]. `per_length` adds a uniformly distributed load along
/// each link (its weight, say), which makes the bending-moment diagrams piecewise quadratic.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Loads {
    /// F1: the load on link 1 (AB), `at` measured from A.
    pub f1: LinkLoad,
    /// F2: the load on link 2 (CD), `at` measured from C.
    pub f2: LinkLoad,
    /// F3: a load on link 3, `at` measured from B along B → D → E.
    pub f3: LinkLoad,
    /// M: a second load on link 3 (the seed's couple at E), `at` measured from B.
    pub m: LinkLoad,
    /// Uniformly distributed loads on links 1, 2, 3, force per unit length of the axis, N/m
    /// (global components; a weight is (0, −m·g/L)).
    pub per_length: [Vector2<f64>; 3],
}

impl Loads {
    /// No load at all (the loads of the unit state of the force method).
    pub const ZERO: Loads = Loads {
        f1: LinkLoad::NONE,
        f2: LinkLoad::NONE,
        f3: LinkLoad::NONE,
        m: LinkLoad::NONE,
        per_length: [Vector2::new(0.0, 0.0); 3],
    };

    /// The point loads on a link.
    pub(crate) fn on(&self, link: Link) -> [LinkLoad; 2] {
        match link {
            Link::Ab => [self.f1, LinkLoad::NONE],
            Link::Cd => [self.f2, LinkLoad::NONE],
            Link::Bde => [self.f3, self.m],
        }
    }

    /// Checks that every number is finite and every load lies on its link, and snaps the
    /// positions that round-off put a hair outside the link onto its ends.
    pub(crate) fn checked(&self, frame: &Frame) -> Result<Loads> {
        let mut out = *self;
        let names = [
            ("F1", ["F1.x", "F1.y"], "F1 couple", "F1 position"),
            ("F2", ["F2.x", "F2.y"], "F2 couple", "F2 position"),
            ("F3", ["F3.x", "F3.y"], "F3 couple", "F3 position"),
            ("M", ["M force x", "M force y"], "M", "M position"),
        ];
        let links = [Link::Ab, Link::Cd, Link::Bde, Link::Bde];
        let loads = [&mut out.f1, &mut out.f2, &mut out.f3, &mut out.m];
        for ((load, link), (_, force_names, couple_name, pos_name)) in
            loads.into_iter().zip(links).zip(names)
        {
            finite2(force_names, load.force)?;
            finite(couple_name, load.moment)?;
            finite(pos_name, load.at)?;
            let l = frame.l[link.index()];
            let slack = 1e-9 * l;
            if load.at < -slack || load.at > l + slack {
                return Err(Error::OutOfRange {
                    name: pos_name,
                    value: load.at,
                    min: 0.0,
                    max: l,
                    ends: crate::Ends::Closed,
                });
            }
            load.at = load.at.clamp(0.0, l);
        }
        for (w, names) in
            out.per_length
                .iter()
                .zip([["w1.x", "w1.y"], ["w2.x", "w2.y"], ["w3.x", "w3.y"]])
        {
            finite2(names, *w)?;
        }
        Ok(out)
    }

    /// The largest load of the group, N: the scale against which residuals are measured.
    /// Couples count as couple/size and distributed loads as w·length.
    #[must_use]
    pub fn scale(&self, geometry: &Geometry) -> f64 {
        let size = geometry.size();
        let mut s: f64 = 0.0;
        for l in [self.f1, self.f2, self.f3, self.m] {
            s = s.max(l.force.norm());
            if size > 0.0 {
                s = s.max(l.moment.abs() / size);
            }
        }
        for link in Link::ALL {
            s = s.max(self.per_length[link.index()].norm() * geometry.length(link));
        }
        s
    }
}

/// The resultant of the known loads on one link: the total force, and the total moment about
/// `pole`.
pub(crate) fn resultant(
    frame: &Frame,
    loads: &Loads,
    link: Link,
    pole: Point2<f64>,
) -> (Vector2<f64>, f64) {
    let g = &frame.g;
    let mut f = Vector2::zeros();
    let mut m = 0.0;
    for l in loads.on(link) {
        f += l.force;
        m += l.moment + cross(g.point_at(link, l.at) - pole, l.force);
    }
    let (wf, wm) = distributed_resultant(
        frame,
        loads.per_length[link.index()],
        link,
        0.0,
        frame.l[link.index()],
        pole,
    );
    (f + wf, m + wm)
}

/// The resultant of a uniform load `w` (N/m) over the arc [s0, s1] of a link: its force and
/// its moment about `pole`. Each straight piece contributes w·length at its middle.
pub(crate) fn distributed_resultant(
    frame: &Frame,
    w: Vector2<f64>,
    link: Link,
    s0: f64,
    s1: f64,
    pole: Point2<f64>,
) -> (Vector2<f64>, f64) {
    if w == Vector2::zeros() || s1 <= s0 {
        return (Vector2::zeros(), 0.0);
    }
    let g = &frame.g;
    let mut pieces = [(s0, s1), (0.0, 0.0)];
    if let Some(bend) = frame.bends(link)
        && s0 < bend
        && bend < s1
    {
        pieces = [(s0, bend), (bend, s1)];
    }
    let mut f = Vector2::zeros();
    let mut m = 0.0;
    for (a, b) in pieces {
        if b > a {
            let piece = w * (b - a);
            // The middle of a straight piece; the bend lies at a piece's end, never inside it.
            let mid = g.point_at(link, 0.5 * (a + b));
            f += piece;
            m += cross(mid - pole, piece);
        }
    }
    (f, m)
}
