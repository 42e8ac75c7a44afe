//! Statics of the released structure: the group with the hinge C turned into a roller that
//! lets C slide along CD, loaded by the known loads and by the redundant X1 along C → D.
//!
//! The released structure is statically determinate (9 equations, 9 unknowns), and it is
//! solved link by link in closed form:
//! - link 2: moments about D give the roller's reaction across CD;
//! - link 1: moments about B give A's reaction across AB (its axial part is still unknown);
//! - link 3: moments about E give link 1's axial force, with the arm from E to the line AB;
//! - the force balances give the rest.

use super::geometry::{Frame, Link};
use super::loads::{resultant, Loads};
use crate::angle::cross;
use nalgebra::Vector2;

/// The forces in the five hinges, N, as vectors in the global frame.
///
/// `R_ij` is the force that link i exerts on link j (0 is the frame), so the force of link 3
/// on link 1 at B is `-r13`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Reactions {
    /// R01: the frame on link 1 at A.
    pub r01: Vector2<f64>,
    /// R02: the frame on link 2 at C.
    pub r02: Vector2<f64>,
    /// R03: the frame on link 3 at E.
    pub r03: Vector2<f64>,
    /// R13: link 1 on link 3 at B.
    pub r13: Vector2<f64>,
    /// R23: link 2 on link 3 at D.
    pub r23: Vector2<f64>,
}

impl Reactions {
    /// `self + k·other`, component by component (superposition of two states).
    #[must_use]
    pub fn plus_scaled(&self, k: f64, other: &Reactions) -> Reactions {
        Reactions {
            r01: self.r01 + k * other.r01,
            r02: self.r02 + k * other.r02,
            r03: self.r03 + k * other.r03,
            r13: self.r13 + k * other.r13,
            r23: self.r23 + k * other.r23,
        }
    }

    /// Whether every component is finite.
    pub(crate) fn is_finite(&self) -> bool {
        [self.r01, self.r02, self.r03, self.r13, self.r23]
            .iter()
            .all(|v| v.x.is_finite() && v.y.is_finite())
    }
}

/// The reactions of the released structure under `loads` and the redundant force `x` applied
/// by the frame on link 2 at C along C → D.
pub(crate) fn released(frame: &Frame, loads: &Loads, x: f64) -> Reactions {
    let g = &frame.g;
    // Link 2: moments about D. The frame force at C is x·t2 + y·n2 and its moment about D is
    // (C − D) × (x·t2 + y·n2) = −l2·y.
    let (f2, m2_d) = resultant(frame, loads, Link::Cd, g.d);
    let y = m2_d / frame.l[1];
    let r02 = x * frame.t2 + y * frame.n2;
    let r23 = r02 + f2;
    // Link 1: moments about B give the part of R01 across AB; its part p along AB is found
    // from link 3.
    let (f1, m1_b) = resultant(frame, loads, Link::Ab, g.b);
    let q = m1_b / frame.l[0];
    let known13 = q * frame.n1 + f1;
    // Link 3: moments about E; (B − E) × t1 is the signed arm from E to the line AB.
    let (f3, m3_e) = resultant(frame, loads, Link::Bde, g.e);
    let p = -(cross(g.b - g.e, known13) + cross(g.d - g.e, r23) + m3_e) / frame.arm;
    let r01 = p * frame.t1 + q * frame.n1;
    let r13 = r01 + f1;
    let r03 = -(r13 + r23 + f3);
    Reactions {
        r01,
        r02,
        r03,
        r13,
        r23,
    }
}
