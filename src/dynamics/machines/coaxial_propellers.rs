//! The differential drive of coaxial propellers (seed 003, §5, eqs. 105–144).

use nalgebra::{Matrix2, Vector2};

use super::{gear_inertia, GearLink, LinearMotor};
use crate::dynamics::stepper::check_result;
use crate::dynamics::system::{checked_inertia, LagrangeSystem, LagrangeTerms, State};
use crate::error::{computed, computed_all, finite, positive, Result};

/// One motor drives two counter-rotating propellers through a differential: sun z1 (the
/// input, on the motor shaft), a block of k planets z2–z3 on the carrier H (the front
/// propeller), and the internal ring z4 (the rear propeller). The generalized coordinates are
/// q = (φ4, φH).
///
/// Kinematics (Willis; docs/errata.md#d32): φ̇1 = u14·φ̇4 + u1H·φ̇H with u14 = −z2z4/(z1z3) and
/// u1H = 1 + z2z4/(z1z3); the planets turn at φ̇2 = (z4/z3)·φ̇4 + (1 − z4/z3)·φ̇H and their
/// centres move at (r_w1 + r_w2)·φ̇H. The inertia matrix is constant (eqs. 112–114 with the k
/// of D34), and Q = M_p1·(u14, u1H) + ((M_on)4, (M_on)H) with M_p1 = a − b·φ̇1 (eqs. 122–126,
/// D37). The resisting moments are signed: they resist when their sign is opposite to the
/// speed of their propeller (the rear one turns backwards, so its resisting moment is
/// positive).
///
/// The equations are linear with constant coefficients, so [`exact`](Self::exact) gives the
/// motion in closed form. With constant resisting moments a steady state exists only when
/// (M_on)4/(M_on)H = u14/u1H (docs/errata.md#d41, [`steady_state_exists`](Self::steady_state_exists));
/// otherwise the motor speed settles but the propellers drift apart with the constant
/// accelerations of [`drift_acceleration`](Self::drift_acceleration).
#[derive(Debug, Clone, PartialEq)]
pub struct CoaxialPropellers {
    /// Teeth of the sun z1, the planet gears z2 (meshing the sun) and z3 (meshing the ring),
    /// and the internal ring z4.
    pub z: [u32; 4],
    /// Number of planet blocks k.
    pub k: u32,
    /// Mass of one planet block, kg.
    pub m2: f64,
    /// Carrier arm r_w1 + r_w2 (pitch radii of z1 and z2), m.
    pub carrier_arm: f64,
    /// Moment of inertia of z1 with the motor's moving parts, kg·m².
    pub i1: f64,
    /// Moment of inertia of one planet block about its own axis, kg·m².
    pub i2: f64,
    /// Moment of inertia of z4 with the rear propeller, kg·m².
    pub i4: f64,
    /// Moment of inertia of the carrier with the front propeller, kg·m².
    pub ih: f64,
    /// The motor on z1.
    pub motor: LinearMotor,
    /// Resisting moment on the rear propeller (ring z4), N·m, signed.
    pub m_on4: f64,
    /// Resisting moment on the front propeller (carrier H), N·m, signed.
    pub m_onh: f64,
}

impl Default for CoaxialPropellers {
    /// A turboprop of about 1.1 MW with contra-rotating propellers: z = (24, 48, 30, 96)
    /// (u14 = −6.4, u1H = 7.4), k = 3 planet blocks of 6 kg and 0.03 kg·m², carrier arm
    /// 0.18 m (module 5 mm); I1 = 0.5 kg·m² (free turbine and sun), I4 = IH = 150 kg·m²
    /// (4.5 m propellers); a motor with 1200 N·m nominal at 1000 rad/s and 1100 rad/s at no
    /// load (a = 13 200 N·m, b = 12 N·m·s); resisting moments in the gear ratio for a motor
    /// moment of 1100 N·m in the steady state: (M_on)4 = +7040 N·m, (M_on)H = −8140 N·m.
    fn default() -> Self {
        let motor = LinearMotor {
            a: 13_200.0,
            b: 12.0,
        };
        let (u14, u1h) = (-6.4, 7.4);
        Self {
            z: [24, 48, 30, 96],
            k: 3,
            m2: 6.0,
            carrier_arm: 0.18,
            i1: 0.5,
            i2: 0.03,
            i4: 150.0,
            ih: 150.0,
            motor,
            m_on4: -1100.0 * u14,
            m_onh: -1100.0 * u1h,
        }
    }
}

/// K, λ, c and w = A⁻¹u of [`CoaxialPropellers::linear_parts`].
type LinearParts = (Matrix2<f64>, f64, Vector2<f64>, Vector2<f64>);

/// (1 − e^(−x))/x, (x − 1 + e^(−x))/x², (x²/2 − x + 1 − e^(−x))/x³, by series near 0.
fn phi_functions(x: f64) -> (f64, f64, f64) {
    if x.abs() < 0.1 {
        let (mut f1, mut f2, mut f3) = (0.0, 0.0, 0.0);
        let mut term = 1.0; // (−x)^n
        let mut fact = [1.0; 3]; // running (n+1)!, (n+2)!, (n+3)! divisors
        fact[1] = 2.0;
        fact[2] = 6.0;
        for n in 0..14 {
            f1 += term / fact[0];
            f2 += term / fact[1];
            f3 += term / fact[2];
            let nf = n as f64;
            term *= -x;
            fact[0] *= nf + 2.0;
            fact[1] *= nf + 3.0;
            fact[2] *= nf + 4.0;
        }
        (f1, f2, f3)
    } else {
        let e = (-x).exp_m1(); // e^(−x) − 1
        (
            (-e) / x,
            (x + e) / (x * x),
            (0.5 * x * x - x - e) / (x * x * x),
        )
    }
}

impl CoaxialPropellers {
    /// The gear ratios (u14, u1H) from the carrier and ring speeds to the sun's.
    #[must_use]
    pub fn input_ratios(&self) -> Vector2<f64> {
        let [z1, z2, z3, z4] = self.z.map(f64::from);
        let u14 = -z2 * z4 / (z1 * z3);
        Vector2::new(u14, 1.0 - u14)
    }

    /// The planets' ratios (u24, u2H): φ̇2 = u24·φ̇4 + u2H·φ̇H.
    #[must_use]
    pub fn planet_ratios(&self) -> Vector2<f64> {
        let r = f64::from(self.z[3]) / f64::from(self.z[2]);
        Vector2::new(r, 1.0 - r)
    }

    #[inline]
    fn check(&self) -> Result<()> {
        // One combined test on the hot path (every evaluation of the right-hand side); the
        // step-by-step checks below name what fails.
        let positive = [
            self.m2,
            self.carrier_arm,
            self.i1,
            self.i2,
            self.i4,
            self.ih,
        ]
        .iter()
        .fold(true, |ok, v| ok & (*v > 0.0) & v.is_finite());
        let finite = [self.motor.a, self.motor.b, self.m_on4, self.m_onh]
            .iter()
            .fold(true, |ok, v| ok & v.is_finite());
        let counts = self.z.iter().fold(true, |ok, z| ok & (*z > 0)) & (self.k > 0);
        if positive & finite & counts {
            return Ok(());
        }
        self.check_each()
    }

    #[cold]
    #[inline(never)]
    fn check_each(&self) -> Result<()> {
        for (i, &z) in self.z.iter().enumerate() {
            positive(["z1", "z2", "z3", "z4"][i], f64::from(z))?;
        }
        positive("k", f64::from(self.k))?;
        positive("m2", self.m2)?;
        positive("carrier_arm", self.carrier_arm)?;
        positive("I1", self.i1)?;
        positive("I2", self.i2)?;
        positive("I4", self.i4)?;
        positive("IH", self.ih)?;
        self.motor.check()?;
        finite("(M_on)4", self.m_on4)?;
        finite("(M_on)H", self.m_onh)?;
        Ok(())
    }

    /// The generalized forces at the speeds `qd`, the data already validated by
    /// [`check`](Self::check).
    #[inline]
    fn forces_checked(&self, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        let u = self.input_ratios();
        let mp1 = self.motor.torque(u.dot(qd))?;
        let q = mp1 * u + Vector2::new(self.m_on4, self.m_onh);
        computed_all("generalized forces", q.iter())?;
        Ok(q)
    }

    fn links(&self) -> [GearLink; 5] {
        let k = f64::from(self.k);
        [
            GearLink {
                inertia: self.i1,
                speed: self.input_ratios(),
            },
            GearLink {
                inertia: k * self.m2 * self.carrier_arm.powi(2),
                speed: Vector2::new(0.0, 1.0),
            },
            GearLink {
                inertia: k * self.i2,
                speed: self.planet_ratios(),
            },
            GearLink {
                inertia: self.ih,
                speed: Vector2::new(0.0, 1.0),
            },
            GearLink {
                inertia: self.i4,
                speed: Vector2::new(1.0, 0.0),
            },
        ]
    }

    /// The constant inertia matrix [[I44, I4H], [I4H, IHH]] (eqs. 112–114, docs/errata.md#d34).
    ///
    /// # Errors
    /// [`Error::NonPositive`](crate::Error::NonPositive) for a non-positive datum.
    pub fn inertia_matrix(&self) -> Result<Matrix2<f64>> {
        self.check()?;
        let a = gear_inertia(&self.links());
        computed_all("inertia matrix", a.iter())?;
        Ok(a)
    }

    /// `true` when the resisting moments stand in the gear ratio, so that a steady state
    /// exists (docs/errata.md#d41): (M_on)4·u1H = (M_on)H·u14, to 10⁻⁹ relative.
    #[must_use]
    pub fn steady_state_exists(&self) -> bool {
        let u = self.input_ratios();
        let lhs = self.m_on4 * u[1];
        let rhs = self.m_onh * u[0];
        (lhs - rhs).abs() <= 1e-9 * lhs.abs().max(rhs.abs()).max(f64::MIN_POSITIVE)
    }

    /// The accelerations (φ̈4, φ̈H) that the motion tends to for t → ∞: zero when a steady
    /// state exists, otherwise the constant drift of D41. A motor with no slope (b = 0, a
    /// constant moment) gives no damping: the accelerations are constant from the start.
    ///
    /// # Errors
    /// As [`inertia_matrix`](Self::inertia_matrix); [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite
    /// motor or resisting moment; [`Error::NonPositive`](crate::Error::NonPositive) for a motor slope b < 0 (its moment
    /// grows with speed and the motion runs away: nothing to tend to).
    pub fn drift_acceleration(&self) -> Result<Vector2<f64>> {
        let (_, _, c, w) = self.linear_parts()?;
        if self.motor.b == 0.0 {
            return Ok(c);
        }
        positive("motor slope b", self.motor.b)?;
        // c − K c/λ = c − w·(uᵀc)/(uᵀw) with w = A⁻¹u: b cancels, so a tiny slope cannot
        // overflow (uᵀw > 0 because A⁻¹ is positive-definite).
        let u = self.input_ratios();
        let drift = c - w * (u.dot(&c) / u.dot(&w));
        computed_all("drift acceleration", drift.iter())?;
        Ok(drift)
    }

    /// v̇ = −K v + c with K = b·A⁻¹u uᵀ (rank one, K² = λK, λ = b·uᵀA⁻¹u) and
    /// c = A⁻¹(a·u + M_on).
    /// Also returns w = A⁻¹u.
    fn linear_parts(&self) -> Result<LinearParts> {
        finite("motor a", self.motor.a)?;
        finite("motor b", self.motor.b)?;
        finite("(M_on)4", self.m_on4)?;
        finite("(M_on)H", self.m_onh)?;
        let a = self.inertia_matrix()?;
        let (a, det) = checked_inertia(&a, 0.0, &Vector2::zeros())?;
        let inv = Matrix2::new(a[(1, 1)], -a[(0, 1)], -a[(1, 0)], a[(0, 0)]) / det;
        let u = self.input_ratios();
        let w = inv * u;
        let k = self.motor.b * w * u.transpose();
        let lambda = self.motor.b * u.dot(&w);
        let c = inv * (self.motor.a * u + Vector2::new(self.m_on4, self.m_onh));
        computed_all("linear parts K, c", k.iter().chain(c.iter()))?;
        computed("lambda = b*u'A^-1 u", lambda)?;
        Ok((k, lambda, c, w))
    }

    /// The exact motion at time `t` from the state `start` (a closed form of the linear
    /// equations, the matrix exponential of the rank-one K: e^(−Kτ) = I + (e^(−λτ) − 1)/λ·K):
    ///
    /// ```text
    /// τ = t − t0, x = λτ,
    /// q̇(t) = q̇0 + cτ − τ f1(x) K q̇0 − τ² f2(x) K c,
    /// q(t) = q0 + q̇0 τ + cτ²/2 − τ² f2(x) K q̇0 − τ³ f3(x) K c,
    /// f1 = (1 − e⁻ˣ)/x, f2 = (x − 1 + e⁻ˣ)/x², f3 = (x²/2 − x + 1 − e⁻ˣ)/x³.
    /// ```
    ///
    /// # Errors
    /// As [`inertia_matrix`](Self::inertia_matrix); [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite
    /// `t`, motor or resisting moment; [`Error::NonFiniteState`](crate::Error::NonFiniteState) for a non-finite `start` or
    /// a result that overflows.
    ///
    /// # Examples
    /// Started at the steady motor speed with balanced loads, the propellers keep their speeds:
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::dynamics::{machines::CoaxialPropellers, State};
    /// let d = CoaxialPropellers::default();
    /// let u = d.input_ratios();
    /// // Motor moment 1100 N·m at ω1 = (13 200 − 1100)/12 rad/s, split as the loads ask.
    /// let w1 = (13_200.0 - 1100.0) / 12.0;
    /// let qd = Vector2::new(-0.5 * w1 / u[0].abs(), 0.5 * w1 / u[1]);
    /// let s = d.exact(&State::new(0.0, Vector2::zeros(), qd), 3.0).unwrap();
    /// assert!((s.qd - qd).norm() < 1e-9 * qd.norm());
    /// ```
    pub fn exact(&self, start: &State, t: f64) -> Result<State> {
        let (k, lambda, c, w) = self.linear_parts()?;
        finite("t", t)?;
        check_result(*start)?;
        let tau = t - start.t;
        let x = lambda * tau;
        let (f1, f2, f3) = phi_functions(x);
        let (q0, v0) = (start.q, start.qd);
        if self.motor.b == 0.0 || !x.is_finite() {
            let qd = v0 + c * tau - tau * f1 * (k * v0) - tau * tau * f2 * (k * c);
            let q = q0 + v0 * tau + 0.5 * c * tau * tau
                - tau * tau * f2 * (k * v0)
                - tau.powi(3) * f3 * (k * c);
            return check_result(State::new(t, q, qd));
        }
        // With the projector P = K/λ = w uᵀ/(uᵀw) and x f2 = 1 − f1, x f3 = ½ − f2, the same
        // closed form splits into the undamped part (I − P) and the damped part P, with no
        // terms that grow like τ² and cancel (1e-12 relative at large λτ):
        // q̇ = (I−P)(v0 + cτ) + P(e⁻ˣ v0 + τ f1 c),
        // q  = q0 + (I−P)(v0 τ + cτ²/2) + P(τ f1 v0 + τ² f2 c).
        let u = self.input_ratios();
        let p = |v: Vector2<f64>| w * (u.dot(&v) / u.dot(&w));
        let (pv, pc) = (p(v0), p(c));
        let decay = (-x).exp();
        let qd = (v0 - pv) + (c - pc) * tau + pv * decay + pc * (tau * f1);
        let q = q0
            + (v0 - pv) * tau
            + (c - pc) * (0.5 * tau * tau)
            + pv * (tau * f1)
            + pc * (tau * tau * f2);
        check_result(State::new(t, q, qd))
    }
}

impl LagrangeSystem for CoaxialPropellers {
    fn coordinate_names(&self) -> [&'static str; 2] {
        ["phi_4", "phi_H"]
    }

    fn inertia(&self, _q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.inertia_matrix()
    }

    fn inertia_derivatives(&self, _q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        Ok([Matrix2::zeros(); 2])
    }

    fn forces(&self, _t: f64, _q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.check()?;
        self.forces_checked(qd)
    }

    /// No potential energy: its gradient is zero (the default would difference Π = 0 eight
    /// times per evaluation to find so).
    fn potential_gradient(&self, _q: &Vector2<f64>) -> Result<Vector2<f64>> {
        Ok(Vector2::zeros())
    }

    /// Every term of one evaluation with the data validated once (the default would validate
    /// them for the inertia and again for the forces), in the default's order: the inertia
    /// matrix and its determinant, then the forces.
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        let inertia = self.inertia_matrix()?;
        checked_inertia(&inertia, t, q)?;
        Ok(LagrangeTerms {
            inertia,
            inertia_derivatives: [Matrix2::zeros(); 2],
            forces: self.forces_checked(qd)?,
            potential_gradient: Vector2::zeros(),
            damping: Matrix2::zeros(),
        })
    }

    fn output_names(&self) -> Vec<&'static str> {
        vec!["phi_1", "omega_1", "omega_2", "omega_4", "omega_H", "M_p1"]
    }

    fn outputs(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        self.check()?;
        let u = self.input_ratios();
        let w1 = u.dot(qd);
        let values = [
            u.dot(q),
            w1,
            self.planet_ratios().dot(qd),
            qd[0],
            qd[1],
            self.motor.torque(w1)?,
        ];
        computed_all("coaxial propellers' outputs", values.iter())?;
        out.extend(values);
        Ok(())
    }
}
