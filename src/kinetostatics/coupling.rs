//! The input link driven through a coupling (seed program SRWL2): the balancing moment.
//!
//! The motor's shaft turns link 1 about O1 through a coupling, which passes a pure moment M_b.
//! Link 1's moment about O1, M_b + Σ M_i(O1) = 0, gives the balancing moment
//! M_b = −Σ M_i(O1), and its force balance the frame's reaction R01 = −Σ F_i. The seed's 1.56
//! prints M_b without the minus sign, which is the moment of the known loads, not the one that
//! balances them (docs/errata.md#e7, #e8).

use super::conditioning::{ensure_finite, Conditioning};
use crate::angle::unit;
use crate::error::{all_finite, finite2, positive, Result};
use crate::Load;
use nalgebra::{Point2, Vector2};

/// An input link turning about O1 and driven through a coupling.
///
/// # Examples
/// A crank O1A = 0.1 m along +x; the connecting rod pulls down on the crank pin with
/// R21 = (0, −500) N. Its moment about O1 is 0.1·(−500) = −50 N·m, so the motor must supply
/// M_b = +50 N·m, and the frame holds the crank up with R01 = (0, 500) N.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::CouplingDrive, Load};
/// let drive = CouplingDrive { o1: Point2::origin() };
/// let r = drive.solve(&[Load::force_at(Point2::new(0.1, 0.0), Vector2::new(0.0, -500.0))])?;
/// assert_relative_eq!(r.balancing_moment, 50.0, epsilon = 1e-12);
/// assert_relative_eq!(r.r01, Vector2::new(0.0, 500.0));
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SRWL2")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CouplingDrive {
    /// The centre of the frame hinge O1.
    pub o1: Point2<f64>,
}

/// The balancing moment of an input link driven through a coupling, and the frame's reaction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CouplingBalance {
    /// M_b, the moment the motor applies to link 1, N·m, counter-clockwise positive.
    pub balancing_moment: f64,
    /// R01, the force of the frame on link 1 at O1, N.
    pub r01: Vector2<f64>,
    /// Always measure 1 and condition 1: the solution divides by nothing.
    pub conditioning: Conditioning,
}

impl CouplingDrive {
    /// The balancing moment and the frame's reaction for the loads on link 1: its own
    /// resultant load (external plus inertia) and the reactions R21 of the groups attached to
    /// it (each as a [`Load::force_at`] its joint).
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite number, or an overflow.
    #[inline]
    pub fn solve(&self, loads: &[Load]) -> Result<CouplingBalance> {
        finite2(["O1.x", "O1.y"], self.o1.coords)?;
        loads.iter().try_for_each(Load::validate)?;
        let total = Load::sum_about(loads, self.o1);
        let (balancing_moment, r01) = (-total.moment, -total.force);
        ensure_finite(
            "input link",
            "sum of loads",
            1.0,
            &[balancing_moment, r01.x, r01.y],
        )?;
        Ok(CouplingBalance {
            balancing_moment,
            r01,
            conditioning: Conditioning::perfect(),
        })
    }
}

/// An input link driven through a coupling, in the seeds' notation (program SRWL2).
///
/// φ1 is the direction of O1A; S1 lies on it at l_O1S1 from O1. F1 (at S1) and M1 are link 1's
/// own loads, R21 = |R12| with the direction γ21 = γ12 + π the reaction of the first group.
///
/// # Examples
/// The [`CouplingDrive`] example: l_O1A = 0.1 m, φ1 = 0, R21 = 500 N along 270°. The corrected
/// 1.56, M_b = −[R21·l_O1A·sin(γ21 − φ1) + F1·l_O1S1·sin(γ1 − φ1) + M1], gives
/// −[500·0.1·sin 270°] = +50 N·m.
/// ```
/// use approx::assert_relative_eq;
/// use tmm::kinetostatics::CouplingSeed;
/// let r = CouplingSeed {
///     l_o1a: 0.1, l_o1s1: 0.05, phi1: 0.0, f1: 0.0, gamma1: 0.0,
///     r21: 500.0, gamma21: 270f64.to_radians(), m1: 0.0,
/// }
/// .solve()?;
/// assert_relative_eq!(r.balancing_moment, 50.0, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[doc(alias = "SRWL2")]
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CouplingSeed {
    /// l_O1A, the length of the input link, m.
    pub l_o1a: f64,
    /// l_O1S1, the distance of S1 from O1, m.
    pub l_o1s1: f64,
    /// φ1, the direction angle of O1A, rad.
    pub phi1: f64,
    /// F1, the resultant force on link 1 (at S1), N.
    pub f1: f64,
    /// γ1, its direction angle, rad.
    pub gamma1: f64,
    /// R21, the magnitude of the first group's reaction on link 1 at A, N.
    pub r21: f64,
    /// γ21, its direction angle, rad.
    pub gamma21: f64,
    /// M1, the resultant moment on link 1 (without the balancing moment), N·m.
    pub m1: f64,
}

impl CouplingSeed {
    /// The loads on link 1 in Cartesian form, with O1 at the origin: [own load, R21 at A].
    ///
    /// # Errors
    /// Non-finite numbers, or a non-positive l_O1A.
    pub fn loads(&self) -> Result<[Load; 2]> {
        input_link_loads(
            self.l_o1a,
            [
                ("l_O1S1", self.l_o1s1),
                ("phi1", self.phi1),
                ("F1", self.f1),
                ("gamma1", self.gamma1),
                ("R21", self.r21),
                ("gamma21", self.gamma21),
                ("M1", self.m1),
            ],
        )
    }

    /// Solves the input link; see [`CouplingDrive::solve`].
    ///
    /// # Errors
    /// As [`CouplingSeed::loads`] and [`CouplingDrive::solve`].
    pub fn solve(&self) -> Result<CouplingBalance> {
        CouplingDrive {
            o1: Point2::origin(),
        }
        .solve(&self.loads()?)
    }
}

/// Link 1's loads from the seeds' numbers, in the order l_O1S1, φ1, F1, γ1, R21, γ21, M1.
pub(super) fn input_link_loads(l_o1a: f64, numbers: [(&'static str, f64); 7]) -> Result<[Load; 2]> {
    positive("l_O1A", l_o1a)?;
    all_finite(&numbers)?;
    let [l_o1s1, phi1, f1, gamma1, r21, gamma21, m1] = numbers.map(|(_, v)| v);
    let u1 = unit(phi1);
    Ok([
        Load::polar(Point2::from(u1 * l_o1s1), f1, gamma1, m1),
        Load::polar(Point2::from(u1 * l_o1a), r21, gamma21, 0.0),
    ])
}
