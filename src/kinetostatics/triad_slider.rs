//! The triad with one sliding pair (see
//! [`slider_triad_modes`](crate::kinematics::slider_triad_modes)): leg 1 slides, legs 2 and 3
//! are hinged at both ends.
//!
//! Derivation, as for the [`Triad`](super::Triad). A hinged leg k: its moment about B_k gives
//! the component of R_Ak across the leg, t_k = M_k(B_k)/l_k, and R_Bk = n_k·u_k + q_k with
//! q_k = t_k·u_k⊥ + F_k. The sliding pair carries a force N·n across its guide (n its unit
//! normal) and a couple; its line is taken through the leg's hinge, so that the sliding
//! link's moment about that hinge gives the couple at once:
//! - outer (link 1 slides on the known link's guide, hinged to the ternary link at B1): the
//!   couple of the guide on the slider is −M_1(B1), and R_B1 = N·n + F_1 acts at B1;
//! - inner (link 1 hinged to the known link at A1, sliding on the ternary link's guide): the
//!   couple of link 1 on the ternary link is M_1(A1), the force N·n acts through A1, and
//!   R_A1 = N·n − F_1.
//!
//! The ternary link's force balance and its moment about B1 are then three linear equations
//! in (N, n_2, n_3) whose matrix is the transpose of the velocity system K of
//! [`slider_triad_rates`](crate::kinematics::slider_triad_rates): the same determinant, zero
//! where the three lines of action meet at one point.

use super::conditioning::{ensure_finite, Conditioning};
use super::triad::{ternary_size, validate, LegLines};
use crate::angle::{cross, perp};
use crate::error::{finite2, length, Result};
use crate::kinematics::{Leg, Legs};
use crate::Load;
use nalgebra::{Point2, Vector2};

const WHAT: &str = "triad with a sliding pair";
const MEASURE: &str = "det(velocity system)/L_T";

/// Which of leg 1's pairs slides (the other is a hinge).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SlideAt {
    /// The pair with the known link (at A1) slides; B1 is a hinge.
    Outer,
    /// The pair with the ternary link (at B1) slides; A1 is a hinge.
    Inner,
}

/// A triad with a sliding pair in leg 1, in Cartesian form.
///
/// # Examples
/// The ternary link B1 = (0, 0), B2 = (1, 0), B3 = (0, 1) m rides on a slider at B1 that runs
/// along the x axis (outer pair, normal (0, 1)), hangs from a vertical leg at B2 (from
/// A2 = (1, 1)) and is held sideways by a horizontal leg at B3 (from A3 = (1, 1)). It carries
/// 300 N down at its centroid (1/3, 1/3): the horizontal leg carries nothing, and the moments
/// split the weight 2 : 1 between the slider (at x = 0) and the vertical leg (at x = 1).
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::{SlideAt, SliderTriad}, Load};
/// let b = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// let a = [Point2::new(-1.0, 0.0), Point2::new(1.0, 1.0), Point2::new(1.0, 1.0)];
/// let t = SliderTriad {
///     slide: SlideAt::Outer,
///     normal: Vector2::new(0.0, 1.0),
///     a,
///     b,
///     loads: [Load::zero(b[0]), Load::zero(a[1]), Load::zero(a[2])],
///     load_ternary: Load::force_at(Point2::new(1.0 / 3.0, 1.0 / 3.0), Vector2::new(0.0, -300.0)),
/// };
/// let r = t.solve()?;
/// assert_relative_eq!(r.r_b[0], Vector2::new(0.0, 200.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r_b[1], Vector2::new(0.0, 100.0), epsilon = 1e-12);
/// assert_relative_eq!(r.r_b[2], Vector2::zeros(), epsilon = 1e-12);
/// assert_relative_eq!(r.normal_force, 200.0, epsilon = 1e-12);
/// assert_relative_eq!(r.couple, 0.0, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SliderTriad {
    /// Which of leg 1's pairs slides.
    pub slide: SlideAt,
    /// n, the unit normal of the sliding pair's guide (either sense).
    pub normal: Vector2<f64>,
    /// A1 (inner: the hinge with the known link; outer: not read), A2, A3.
    pub a: [Point2<f64>; 3],
    /// B1 (the ternary link's origin: outer, the hinge; inner, a point of its guide), B2, B3.
    pub b: [Point2<f64>; 3],
    /// The resultant load on each binary link (link 1 the sliding one).
    pub loads: [Load; 3],
    /// The resultant load on the ternary link.
    pub load_ternary: Load,
}

/// The reactions in the joints of a triad with a sliding pair.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SliderTriadReactions {
    /// The force of the known link on binary link i (outer: the slide's N·n, acting through
    /// B1 with [`couple`](Self::couple); otherwise at A_i), N.
    pub r_a: [Vector2<f64>; 3],
    /// The force of binary link i on the ternary link (inner: the slide's N·n, acting through
    /// A1 with [`couple`](Self::couple); otherwise at B_i), N.
    pub r_b: [Vector2<f64>; 3],
    /// N, the sliding pair's normal force along `normal`, N.
    pub normal_force: f64,
    /// The sliding pair's couple (outer: of the known link on the slider; inner: of the slider
    /// on the ternary link), N·m.
    pub couple: f64,
    /// det K / L_T and its amplification.
    pub conditioning: Conditioning,
}

impl SliderTriad {
    /// Solves the group for its joint reactions.
    ///
    /// # Errors
    /// - [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite coordinate or load;
    /// - [`Error::NonPositive`](crate::Error::NonPositive) when a hinged leg or the normal has
    ///   zero length, or the ternary link's joints coincide (`L_T`);
    /// - [`Error::Singular`](crate::Error::Singular) with `distance from a branch point/size`
    ///   when the pose lies within rounding of a branch point of the group (that distance η
    ///   ≤ [`SINGULAR_BRANCH`](crate::kinematics::SINGULAR_BRANCH): the three lines of action
    ///   meet at one point, and the forces would carry fewer than four digits), the rule of
    ///   the rates ([`slider_triad_rates`](crate::kinematics::slider_triad_rates)); with
    ///   `det(velocity system)/L_T` when that determinant vanishes to working precision.
    pub fn solve(&self) -> Result<SliderTriadReactions> {
        validate(&self.a, &self.b, &self.loads, &self.load_ternary)?;
        finite2(["normal.x", "normal.y"], self.normal)?;
        let n = self.normal / length("normal", self.normal)?;
        let names = ["l_A2B2", "l_A3B3"];
        let mut u = [Vector2::zeros(); 3];
        let mut l = [0.0; 3];
        u[0] = n;
        for i in 1..3 {
            let leg = self.b[i] - self.a[i];
            l[i] = length(names[i - 1], leg)?;
            u[i] = leg / l[i];
        }
        let o = self.b[0];
        // The point each leg's line passes through.
        let p0 = match self.slide {
            SlideAt::Outer => o,
            SlideAt::Inner => self.a[0],
        };
        let r = [p0 - o, self.b[1] - o, self.b[2] - o];
        let size = ternary_size(&self.b);
        if size > 0.0 {
            // (A zero L_T is named by LegLines.) The rule of the rates: refused within
            // rounding of a branch point.
            let slide = match self.slide {
                SlideAt::Outer => Leg::FixedLine,
                SlideAt::Inner => Leg::TurningLine,
            };
            Legs {
                w: u,
                r,
                kind: [slide, Leg::Hinged(l[1]), Leg::Hinged(l[2])],
                lt: size,
            }
            .ensure_off_branch(WHAT)?;
        }
        let lines = LegLines::new(WHAT, &self.b, u, r)?;
        let t = [
            0.0,
            self.loads[1].moment_about(self.b[1]) / l[1],
            self.loads[2].moment_about(self.b[2]) / l[2],
        ];
        let (q0, couple, couple_on_t) = match self.slide {
            SlideAt::Outer => (self.loads[0].force, -self.loads[0].moment_about(o), 0.0),
            SlideAt::Inner => {
                let c = self.loads[0].moment_about(self.a[0]);
                (Vector2::zeros(), c, c)
            }
        };
        let q = [
            q0,
            perp(u[1]) * t[1] + self.loads[1].force,
            perp(u[2]) * t[2] + self.loads[2].force,
        ];
        let f = -(self.load_ternary.force + q[0] + q[1] + q[2]);
        let m = -(self.load_ternary.moment_about(o)
            + couple_on_t
            + (0..3).map(|i| cross(r[i], q[i])).sum::<f64>());
        let s = lines.solve(f, m);
        let r_b = [0, 1, 2].map(|i| u[i] * s[i] + q[i]);
        let r_a = [
            match self.slide {
                SlideAt::Outer => n * s[0],
                SlideAt::Inner => n * s[0] - self.loads[0].force,
            },
            r_b[1] - self.loads[1].force,
            r_b[2] - self.loads[2].force,
        ];
        let values: Vec<f64> = r_a
            .iter()
            .chain(r_b.iter())
            .flat_map(|v| [v.x, v.y])
            .chain(s)
            .chain([couple])
            .collect();
        ensure_finite(WHAT, MEASURE, lines.conditioning.measure, &values)?;
        Ok(SliderTriadReactions {
            r_a,
            r_b,
            normal_force: s[0],
            couple,
            conditioning: lines.conditioning,
        })
    }
}
