//! The R–P robot arm (seed 003, §3, eqs. 39–63).

use nalgebra::{Matrix2, Vector2};

use crate::dynamics::stepper::check_result;
use crate::dynamics::system::{LagrangeSystem, State};
use crate::error::{computed_all, finite, positive, Result};

/// A robot arm in a horizontal plane: link 1 turns about a vertical axis (coordinate φ10) and
/// link 2 slides along it (coordinate l = l_CS2, the distance of its centre of mass S2 from
/// the axis point C), driven by a moment M_p1 and a force F_p2, with viscous friction in both
/// joints. q = (φ10, l).
///
/// T = ½(I_z1 + I_z2 + m2 l²)·φ̇² + ½ m2 l̇² (eq. 41 with the dot of docs/errata.md#d15),
/// Φ = ½ b1 r0² φ̇² + ½ b2 l̇² (D14), Q = (M_p1, F_p2); gravity does no work. Lagrange's
/// equations give (52) and the corrected (53) (D17):
///
/// ```text
/// (I_z1 + I_z2 + m2 l²) φ̈ + 2 m2 l l̇ φ̇ + b1 r0² φ̇ = M_p1,
/// m2 l̈ − m2 φ̇² l + b2 l̇ = F_p2.
/// ```
///
/// The two motions are coupled through l; see [`DecoupledRpArm`] for the variant with
/// counter-masses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RpArm {
    /// Moment of inertia of link 1 about the joint axis, kg·m².
    pub iz1: f64,
    /// Moment of inertia of link 2 (with the object) about its centre of mass, kg·m².
    pub iz2: f64,
    /// Mass of link 2 with the object, kg.
    pub m2: f64,
    /// Radius of the journal of joint O, m.
    pub r0: f64,
    /// Viscous coefficient at the journal surface, N·s/m (b1·r0² in N·m·s).
    pub b1: f64,
    /// Viscous coefficient of the slide, N·s/m.
    pub b2: f64,
    /// Driving moment, N·m.
    pub mp1: f64,
    /// Driving force, N.
    pub fp2: f64,
}

impl Default for RpArm {
    /// A small assembly robot: I_z1 = 0.5 kg·m², I_z2 = 0.05 kg·m², m2 = 5 kg, a 20 mm
    /// journal with b1 = 500 N·s/m (b1·r0² = 0.2 N·m·s), b2 = 20 N·s/m, M_p1 = 2 N·m,
    /// F_p2 = 10 N.
    fn default() -> Self {
        Self {
            iz1: 0.5,
            iz2: 0.05,
            m2: 5.0,
            r0: 0.02,
            b1: 500.0,
            b2: 20.0,
            mp1: 2.0,
            fp2: 10.0,
        }
    }
}

/// `m` when every entry is finite: [`Error::Overflow`](crate::Error::Overflow) naming `what`
/// otherwise (finite data whose products overflow).
fn finite_matrix(what: &'static str, m: Matrix2<f64>) -> Result<Matrix2<f64>> {
    computed_all(what, m.iter())?;
    Ok(m)
}

impl RpArm {
    fn check(&self) -> Result<()> {
        positive("I_z1", self.iz1)?;
        positive("I_z2", self.iz2)?;
        positive("m2", self.m2)?;
        positive("r0", self.r0)?;
        finite("b1", self.b1)?;
        finite("b2", self.b2)?;
        finite("M_p1", self.mp1)?;
        finite("F_p2", self.fp2)?;
        Ok(())
    }

    /// The arm with ideal counter-masses (§3, eqs. 54–57, D19): the same data, constant
    /// inertia I_z1 + I_z2 and m2.
    #[must_use]
    pub fn decoupled(&self) -> DecoupledRpArm {
        DecoupledRpArm { arm: *self }
    }
}

impl LagrangeSystem for RpArm {
    fn coordinate_names(&self) -> [&'static str; 2] {
        ["phi_10", "l_CS2"]
    }

    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.check()?;
        finite("l_CS2", q[1])?;
        finite_matrix(
            "R-P arm inertia matrix",
            Matrix2::new(
                self.iz1 + self.iz2 + self.m2 * q[1] * q[1],
                0.0,
                0.0,
                self.m2,
            ),
        )
    }

    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        self.check()?;
        finite("l_CS2", q[1])?;
        Ok([
            Matrix2::zeros(),
            finite_matrix(
                "R-P arm inertia derivatives",
                Matrix2::new(2.0 * self.m2 * q[1], 0.0, 0.0, 0.0),
            )?,
        ])
    }

    fn forces(&self, _t: f64, _q: &Vector2<f64>, _qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.check()?;
        Ok(Vector2::new(self.mp1, self.fp2))
    }

    fn damping(&self, _q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.check()?;
        finite_matrix(
            "R-P arm damping matrix",
            Matrix2::new(self.b1 * self.r0 * self.r0, 0.0, 0.0, self.b2),
        )
    }
}

/// The R–P arm decoupled by counter-masses (§3): the centre of mass of the sliding parts
/// stays at C, and in the seed's idealization (docs/errata.md#d19) the inertia about the axis stays
/// J = I_z1 + I_z2 and the translating mass m2, so the equations separate (56 and the
/// corrected 57, D20):
///
/// ```text
/// J φ̈ + b1 r0² φ̇ = M_p1,   m2 l̈ + b2 l̇ = F_p2.
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecoupledRpArm {
    /// The arm's data.
    pub arm: RpArm,
}

impl DecoupledRpArm {
    /// The closed-form motion from `start` (eqs. 58–63, corrected in D21 and generalized to
    /// any initial state): for each coordinate with inertia m, viscous coefficient c and load
    /// F, v(t) = F/c + (v0 − F/c)·e^(−cτ/m) and x(t) = x0 + (F/c)τ + (v0 − F/c)(m/c)(1 − e^(−cτ/m)),
    /// τ = t − t0.
    ///
    /// # Errors
    /// [`Error::NonPositive`](crate::Error::NonPositive) when a viscous coefficient is not
    /// positive (the closed form divides by it) or a datum is invalid;
    /// [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite `t`;
    /// [`Error::NonFiniteState`](crate::Error::NonFiniteState) for a non-finite `start` or a
    /// result that overflows.
    ///
    /// # Examples
    /// From rest, the default arm's slide (m2 = 5 kg, b2 = 20 N·s/m, F = 10 N) reaches
    /// l̇ = 0.5·(1 − e⁻⁴) m/s after 1 s:
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::dynamics::{machines::RpArm, State};
    /// let s = RpArm::default().decoupled().closed_form(&State::at_rest(Vector2::zeros()), 1.0).unwrap();
    /// assert!((s.qd[1] - 0.5 * (1.0 - (-4.0f64).exp())).abs() < 1e-15);
    /// ```
    pub fn closed_form(&self, start: &State, t: f64) -> Result<State> {
        let a = &self.arm;
        a.check()?;
        let c = [positive("b1", a.b1)? * a.r0 * a.r0, positive("b2", a.b2)?];
        computed_all("R-P arm damping and inertia", [c[0], a.iz1 + a.iz2].iter())?;
        finite("t", t)?;
        check_result(*start)?;
        let m = [a.iz1 + a.iz2, a.m2];
        let f = [a.mp1, a.fp2];
        let tau = t - start.t;
        let mut s = State::new(t, start.q, start.qd);
        for i in 0..2 {
            let vinf = f[i] / c[i];
            let r = c[i] / m[i];
            // 1 − e^(−rτ) without cancellation for small rτ.
            let one_minus = -(-r * tau).exp_m1();
            s.qd[i] = vinf + (start.qd[i] - vinf) * (1.0 - one_minus);
            s.q[i] = start.q[i] + vinf * tau + (start.qd[i] - vinf) / r * one_minus;
        }
        // Far back in time (τ ≪ −m/c) e^(−rτ) overflows.
        check_result(s)
    }
}

impl LagrangeSystem for DecoupledRpArm {
    fn coordinate_names(&self) -> [&'static str; 2] {
        ["phi_10", "l_CS2"]
    }

    fn inertia(&self, _q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.arm.check()?;
        finite_matrix(
            "R-P arm inertia matrix",
            Matrix2::new(self.arm.iz1 + self.arm.iz2, 0.0, 0.0, self.arm.m2),
        )
    }

    fn inertia_derivatives(&self, _q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        Ok([Matrix2::zeros(); 2])
    }

    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.arm.forces(t, q, qd)
    }

    fn damping(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.arm.damping(q)
    }
}
