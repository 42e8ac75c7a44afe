//! The group's geometry: frame hinges A, C, E; link 1 = AB, link 2 = CD, link 3 = B–D–E.
//!
//! Every link is a chain of straight members, and a section of a link is named by its arc
//! length `s` from the link's start: link 1 runs from A to B, link 2 from C to D, link 3 from B
//! through D to E. Link 3 may be bent at D (two straight members rigidly joined); the seed's
//! link 3 is straight (D on the line BE), which is the special case of collinear members.

use crate::angle::{cross, perp};
use crate::error::{finite2, Error, Result};
use crate::kinetostatics::Conditioning;
use nalgebra::{Point2, Vector2};

/// The name of the group in its errors.
pub(crate) const WHAT: &str = "parallel-coupler group";
/// The divisor of the released structure's statics, as named in its conditioning and errors.
pub(crate) const ARM: &str = "distance from E to line AB";

/// The positions of the five hinges, m.
///
/// A, C and E are the hinges to the frame; B joins links 1 and 3, D joins links 2 and 3.
/// In the seed (a parallel coupler) ABDC is a parallelogram: AB and CD are equal and parallel,
/// and the group is then a mechanism position with a passive constraint. The force method
/// itself does not need the parallelogram: any once-indeterminate frame of this topology is
/// solved the same way.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Geometry {
    /// Hinge of link 1 to the frame.
    pub a: Point2<f64>,
    /// Hinge between links 1 and 3.
    pub b: Point2<f64>,
    /// Hinge of link 2 to the frame (the hinge the force method releases).
    pub c: Point2<f64>,
    /// Hinge between links 2 and 3.
    pub d: Point2<f64>,
    /// Hinge of link 3 to the frame.
    pub e: Point2<f64>,
}

/// One link of the group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Link {
    /// Link 1, from A to B.
    Ab,
    /// Link 2 (the parallel coupler), from C to D.
    Cd,
    /// Link 3, from B through D to E.
    Bde,
}

impl Link {
    /// The three links in the seed's order 1, 2, 3.
    pub const ALL: [Link; 3] = [Link::Ab, Link::Cd, Link::Bde];

    /// 0, 1 or 2 for links 1, 2, 3 (the index into per-link arrays such as
    /// [`Stiffness::ei`](super::Stiffness::ei)).
    #[must_use]
    pub fn index(self) -> usize {
        match self {
            Link::Ab => 0,
            Link::Cd => 1,
            Link::Bde => 2,
        }
    }

    /// A short name: `"AB"`, `"CD"`, `"BDE"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Link::Ab => "AB",
            Link::Cd => "CD",
            Link::Bde => "BDE",
        }
    }
}

/// Which one-sided limit to take at a section where a diagram jumps (under a point load, at a
/// hinge, at the bend of link 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Side {
    /// The limit from smaller `s`: loads at the section itself are not yet included.
    Before,
    /// The limit from larger `s`: loads at the section are included.
    After,
}

impl Geometry {
    /// The geometry from the five hinge positions.
    #[must_use]
    pub fn new(
        a: Point2<f64>,
        b: Point2<f64>,
        c: Point2<f64>,
        d: Point2<f64>,
        e: Point2<f64>,
    ) -> Self {
        Self { a, b, c, d, e }
    }

    /// The seed's geometry (docs/errata.md#passive-geometry): link 3 straight with the frame hinge E at the
    /// origin, D = E − l4·u, B = E − (l3 + l4)·u with u = (cos α4, sin α4); links 1 and 2
    /// horizontal, with A = B − (l1, 0) and C = D − (l2, 0) on the left.
    ///
    /// With `l1 == l2` this is a parallelogram ABDC.
    #[must_use]
    pub fn seed(l1: f64, l2: f64, l3: f64, l4: f64, alpha4: f64) -> Self {
        let e = Point2::origin();
        let u = Vector2::new(alpha4.cos(), alpha4.sin());
        let d = e - l4 * u;
        let b = e - (l3 + l4) * u;
        let x = Vector2::x();
        Self::new(b - l1 * x, b, d - l2 * x, d, e)
    }

    /// The length of a link along its axis, m (for link 3, BD + DE).
    #[must_use]
    pub fn length(&self, link: Link) -> f64 {
        match link {
            Link::Ab => (self.b - self.a).norm(),
            Link::Cd => (self.d - self.c).norm(),
            Link::Bde => (self.d - self.b).norm() + (self.e - self.d).norm(),
        }
    }

    /// The point of the link's axis at arc length `s` from its start (clamped to the link).
    /// This accessor does not validate: a NaN `s` or coordinate gives a NaN point (the
    /// solvers reject such input with an error).
    #[must_use]
    pub fn point_at(&self, link: Link, s: f64) -> Point2<f64> {
        // Not `f64::clamp`, which panics on a NaN bound (a geometry with a NaN coordinate):
        // a NaN here gives a NaN point instead.
        let len = self.length(link);
        let s = if s > len {
            len
        } else if s < 0.0 {
            0.0
        } else {
            s
        };
        let (start, t, s0) = self.member(link, s, Side::After);
        start + (s - s0) * t
    }

    /// The member of `link` that holds the section `s`: its start point, unit tangent and the
    /// arc length at its start. At the bend D of link 3, `side` picks BD or DE.
    fn member(&self, link: Link, s: f64, side: Side) -> (Point2<f64>, Vector2<f64>, f64) {
        let dir = |p: Point2<f64>, q: Point2<f64>| {
            let v = q - p;
            let n = v.norm();
            // A NaN stays a NaN (an unvalidated geometry must not look valid).
            if n > 0.0 || n.is_nan() {
                v / n
            } else {
                Vector2::x()
            }
        };
        match link {
            Link::Ab => (self.a, dir(self.a, self.b), 0.0),
            Link::Cd => (self.c, dir(self.c, self.d), 0.0),
            Link::Bde => {
                let l_bd = (self.d - self.b).norm();
                let on_bd = match side {
                    Side::Before => s <= l_bd,
                    Side::After => s < l_bd,
                };
                if on_bd {
                    (self.b, dir(self.b, self.d), 0.0)
                } else {
                    (self.d, dir(self.d, self.e), l_bd)
                }
            }
        }
    }

    /// The unit tangent of the link's axis at `s` (the direction of increasing `s`); at the
    /// bend D of link 3, `side` picks the member.
    #[must_use]
    pub fn tangent(&self, link: Link, s: f64, side: Side) -> Vector2<f64> {
        self.member(link, s, side).1
    }

    /// The largest distance between two hinges, m: the length scale of the group.
    #[must_use]
    pub fn size(&self) -> f64 {
        let p = [self.a, self.b, self.c, self.d, self.e];
        let mut m: f64 = 0.0;
        for (i, pi) in p.iter().enumerate() {
            for pj in &p[i + 1..] {
                m = m.max((pj - pi).norm());
            }
        }
        m
    }

    /// The signed distance from E to the line AB, m (positive when E lies to the left of
    /// A→B). The axial force of link 1 is found from the moments of link 3 about E with this
    /// arm: where it vanishes, link 1's axial force is undetermined (the group is singular),
    /// and where it is small the reactions grow like size/arm.
    #[must_use]
    pub fn arm_e_ab(&self) -> f64 {
        let l = (self.b - self.a).norm();
        if l > 0.0 {
            cross(self.b - self.a, self.e - self.a) / l
        } else {
            0.0
        }
    }

    /// Validates the geometry and precomputes what the solvers use.
    pub(crate) fn frame(&self) -> Result<Frame> {
        finite2(["A.x", "A.y"], self.a.coords)?;
        finite2(["B.x", "B.y"], self.b.coords)?;
        finite2(["C.x", "C.y"], self.c.coords)?;
        finite2(["D.x", "D.y"], self.d.coords)?;
        finite2(["E.x", "E.y"], self.e.coords)?;
        let size = self.size();
        if !size.is_finite() {
            return Err(Error::NonFinite {
                name: "group size",
                value: size,
            });
        }
        // Relative tolerance: a length below this is a coincidence of two hinges, not a member.
        let tol = 1e-12 * size;
        let member = |name: &'static str, p: Point2<f64>, q: Point2<f64>| -> Result<f64> {
            let l = (q - p).norm();
            if l > tol {
                Ok(l)
            } else {
                Err(Error::Singular {
                    what: WHAT,
                    measure: name,
                    value: l,
                })
            }
        };
        let l1 = member("l_AB", self.a, self.b)?;
        let l2 = member("l_CD", self.c, self.d)?;
        let l_bd = member("l_BD", self.b, self.d)?;
        let l_de = member("l_DE", self.d, self.e)?;
        let arm = self.arm_e_ab();
        // Below 8ε·size the arm, computed from coordinates of size `size`, has no significant
        // digit left (an error); above it, the condition size/|arm| tells how much the
        // reactions amplify rounding errors.
        let conditioning = Conditioning::of(WHAT, ARM, arm, size)?;
        let t1 = (self.b - self.a) / l1;
        let t2 = (self.d - self.c) / l2;
        Ok(Frame {
            g: *self,
            l: [l1, l2, l_bd + l_de],
            l_bd,
            t1,
            n1: perp(t1),
            t2,
            n2: perp(t2),
            arm,
            conditioning,
        })
    }
}

/// A validated geometry with the derived lengths and directions.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Frame {
    pub g: Geometry,
    /// Lengths of links 1, 2, 3.
    pub l: [f64; 3],
    /// Length of the member BD of link 3.
    pub l_bd: f64,
    pub t1: Vector2<f64>,
    pub n1: Vector2<f64>,
    pub t2: Vector2<f64>,
    pub n2: Vector2<f64>,
    /// Signed distance from E to the line AB.
    pub arm: f64,
    /// The conditioning of the division by `arm`.
    pub conditioning: Conditioning,
}

impl Frame {
    /// The arc lengths where a link changes direction (link 3's bend at D), besides its ends.
    pub fn bends(&self, link: Link) -> Option<f64> {
        match link {
            Link::Bde => Some(self.l_bd),
            _ => None,
        }
    }
}
