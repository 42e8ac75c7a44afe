//! The five-bar robot linkage with two inputs (seed 003, §2, eqs. 8–38).

use nalgebra::{Matrix2, Point2, Vector2};

use crate::angle::{cross, perp, unit};
use crate::dynamics::system::{checked_inertia, kink_slots, LagrangeSystem, LagrangeTerms};
use crate::error::{computed_all, finite, finite2, positive, Error, Result};

/// A position servo on a crank: M = clamp(k_p·(target − φ) − k_d·φ̇, ±limit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Servo {
    /// Target angle, rad.
    pub target: f64,
    /// Proportional gain, N·m/rad.
    pub kp: f64,
    /// Derivative gain, N·m·s/rad.
    pub kd: f64,
    /// Largest moment the drive gives, N·m.
    pub limit: f64,
}

impl Servo {
    /// Checks the servo's data: finite target and gains, a finite non-negative limit.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite target, gain or limit; [`Error::OutOfRange`] for a
    /// negative limit.
    pub fn check(&self) -> Result<()> {
        if self.valid() {
            return Ok(());
        }
        self.check_named()
    }

    /// Whether [`check`](Self::check) passes, in one branch-free pass: the machine checks its
    /// servos at every evaluation, and only a failure needs the named error.
    #[inline]
    fn valid(&self) -> bool {
        let finite = [self.target, self.kp, self.kd, self.limit]
            .iter()
            .fold(true, |ok, v| ok & v.is_finite());
        finite & (self.limit >= 0.0)
    }

    /// [`check`](Self::check), naming the first bad field.
    #[cold]
    #[inline(never)]
    fn check_named(&self) -> Result<()> {
        finite("servo target", self.target)?;
        finite("servo k_p", self.kp)?;
        finite("servo k_d", self.kd)?;
        finite("servo limit", self.limit)?;
        if self.limit < 0.0 {
            return Err(Error::OutOfRange {
                name: "servo limit",
                value: self.limit,
                min: 0.0,
                max: f64::INFINITY,
                ends: crate::Ends::Closed,
            });
        }
        Ok(())
    }

    /// The driving moment at angle `phi` and speed `omega`, N·m.
    ///
    /// A demand k_p·e − k_d·ω that overflows saturates at the limit on the side of its
    /// dominant term, as the physical controller's would: the terms are compared scaled down
    /// by 2⁻¹¹⁰⁰ (every one that overflows is then at least 10⁻²³, and a product of two finite
    /// factors at most 10²⁸⁶), so k_p·e = 10⁴⁰⁰ against k_d·ω = 10³¹⁰ drives forwards at
    /// +limit. Never 0 by accident (∞ − ∞).
    ///
    /// # Errors
    /// As [`check`](Self::check); [`Error::NonFinite`] for a non-finite `phi` or `omega`;
    /// [`Error::Overflow`] when both terms overflow, push opposite ways and are equal even
    /// scaled (no direction to take).
    ///
    /// # Examples
    /// ```
    /// use tmm::dynamics::machines::Servo;
    /// let s = Servo { target: 0.0, kp: 1e300, kd: 1e300, limit: 5.0 };
    /// assert_eq!(s.torque(-1e300, 1.0).unwrap(), 5.0); // k_p·e overflows, k_d·ω = 10³⁰⁰
    /// assert_eq!(s.torque(-1.0, 1e300).unwrap(), -5.0); // k_d·ω overflows
    /// assert!(s.torque(-1e300, 1e300).is_err()); // both overflow, equal and opposite
    /// ```
    pub fn torque(&self, phi: f64, omega: f64) -> Result<f64> {
        self.check()?;
        finite("phi", phi)?;
        finite("omega", omega)?;
        Ok(self.demand(phi, omega)?.clamp(-self.limit, self.limit))
    }

    /// The unclamped demand k_p·(target − φ) − k_d·ω for checked data: finite, or ±∞ when it
    /// overflows (on the side of its dominant term), never NaN.
    fn demand(&self, phi: f64, omega: f64) -> Result<f64> {
        let demand = self.kp * (self.target - phi) - self.kd * omega;
        if demand.is_finite() {
            return Ok(demand);
        }
        // Scaled so that nothing overflows: e/2 (target − φ may overflow), then
        // k_p·2⁻⁵⁵⁰ · (e/2)·2⁻⁵⁴⁹ and k_d·2⁻⁵⁵⁰ · ω·2⁻⁵⁵⁰; a term small enough to underflow
        // here is negligible against one that overflowed unscaled.
        let s = 2f64.powi(-550);
        let half_e = 0.5 * self.target - 0.5 * phi;
        let p = (self.kp * s) * (half_e * (2.0 * s));
        let d = (self.kd * s) * (omega * s);
        if p > d {
            Ok(f64::INFINITY)
        } else if p < d {
            Ok(f64::NEG_INFINITY)
        } else {
            Err(Error::Overflow {
                what: "servo demand (k_p·e and k_d·ω overflow, equal and opposite)",
            })
        }
    }

    /// The nodes of [`switch_argument`](Self::switch_argument): its clamps ±1, none for a
    /// servo with limit 0.
    pub(crate) fn switch_nodes(&self) -> Vec<f64> {
        if self.limit == 0.0 {
            Vec::new()
        } else {
            vec![-1.0, 1.0]
        }
    }

    /// Where the servo switches between following its demand and saturating: the demand as
    /// a fraction of the limit, kept within [−2, 2] (a demand that overflows is ±2). The
    /// servo follows while it lies inside (−1, 1) and saturates outside, so its clamps are
    /// the nodes −1 and +1: a swing from one clamp through following to the other crosses
    /// both (a margin 1 − |demand|/limit would show no change of sign over it). `None` for a
    /// servo with limit 0, which never switches (it always gives 0).
    pub(crate) fn switch_argument(&self, phi: f64, omega: f64) -> Result<Option<f64>> {
        if self.limit == 0.0 {
            return Ok(None);
        }
        let d = self.demand(phi, omega)?;
        Ok(Some((d / self.limit).clamp(-2.0, 2.0)))
    }
}

/// Positions and the first- and second-order velocity analogs of the five-bar at (φ1, φ4).
/// Index k = 0 stands for φ1 and 1 for φ4 (so `b_q[1]` is V_Bφ4 of the seed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiveBarKinematics {
    /// Crank pin A (end of crank 1).
    pub a: Point2<f64>,
    /// The hinge B of the couplers (the end effector).
    pub b: Point2<f64>,
    /// Crank pin C (end of crank 4).
    pub c: Point2<f64>,
    /// Direction of A→B, rad.
    pub phi2: f64,
    /// Direction of C→B, rad.
    pub phi3: f64,
    /// sin(φ3 − φ2): zero when the couplers are collinear (a singular position).
    pub sin_phi3_minus_phi2: f64,
    /// ∂B/∂φₖ (velocity analogs of B, m/rad).
    pub b_q: [Vector2<f64>; 2],
    /// ∂φ2/∂φₖ.
    pub phi2_q: [f64; 2],
    /// ∂φ3/∂φₖ (U31^(4) and U34^(1) of docs/errata.md#d9).
    pub phi3_q: [f64; 2],
    /// ∂²B/∂φⱼ∂φₖ.
    pub b_qq: [[Vector2<f64>; 2]; 2],
    /// ∂²φ2/∂φⱼ∂φₖ.
    pub phi2_qq: [[f64; 2]; 2],
    /// ∂²φ3/∂φⱼ∂φₖ.
    pub phi3_qq: [[f64; 2]; 2],
}

/// The five-bar robot: cranks 1 (O–A, angle φ1) and 4 (D–C, angle φ4) driven by two motors,
/// couplers 2 (A–B) and 3 (C–B) meeting at the end effector B. q = (φ1, φ4).
///
/// As in the seed (eqs. 12–18), the couplers' masses are distributed statically to their
/// hinges: m_A2 = m2·l_S2B/l_AB, m_B = m2·l_AS2/l_AB + m3·l_S3C/l_CB, m_C3 = m3·l_BS3/l_CB, so
///
/// ```text
/// I11 = I1 + m_A2·l_OA² + m_B·|V_Bφ1|²,  I14 = m_B·V_Bφ1·V_Bφ4,  I44 = I4 + m_C3·l_DC² + m_B·|V_Bφ4|²,
/// ```
///
/// with the analogs from the closure A + l_AB·e(φ2) = C + l_CB·e(φ3) and the derivatives of A
/// from the second-order analogs. The two-point distribution drops the couplers' own
/// moment of inertia (docs/errata.md#d4: it gives m·l_AS·l_SB about S instead of J_S); set `j_s2`,
/// `j_s3` to add the difference (J_S − m·l_AS·l_SB)·φ̇² and get the rigid bodies' exact T.
///
/// The generalized forces are Q1 = M_p1 − M_on·∂φ3/∂φ1, Q4 = M_p4 − M_on·∂φ3/∂φ4 (eqs.
/// 29–32, docs/errata.md#d9; M_on > 0 opposes increasing φ3), and gravity g (along −y, zero for a
/// robot working in a horizontal plane) acts on the distributed masses through the potential
/// (exact for the couplers, which keep their centres of mass; the cranks are taken as
/// balanced about their axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiveBar {
    /// Frame hinge of crank 1.
    pub o: Point2<f64>,
    /// Frame hinge of crank 4.
    pub d: Point2<f64>,
    /// Crank 1, m.
    pub l_oa: f64,
    /// Coupler 2, m.
    pub l_ab: f64,
    /// Coupler 3, m.
    pub l_cb: f64,
    /// Crank 4, m.
    pub l_dc: f64,
    /// Distance from A to the centre of mass S2 of coupler 2, m.
    pub l_as2: f64,
    /// Distance from B to the centre of mass S3 of coupler 3, m.
    pub l_bs3: f64,
    /// Mass of coupler 2, kg.
    pub m2: f64,
    /// Mass of coupler 3, kg.
    pub m3: f64,
    /// Moment of inertia of crank 1 (with its motor's rotor, reduced) about O, kg·m².
    pub i1: f64,
    /// Moment of inertia of crank 4 about D, kg·m².
    pub i4: f64,
    /// Central moment of inertia of coupler 2, if it is to be kept, kg·m².
    pub j_s2: Option<f64>,
    /// Central moment of inertia of coupler 3, if it is to be kept, kg·m².
    pub j_s3: Option<f64>,
    /// Assembly mode: +1 puts B to the left of the direction A→C, −1 to the right.
    pub mode: f64,
    /// Gravitational acceleration along −y, m/s² (0 for a horizontal robot).
    pub gravity: f64,
    /// The drive of crank 1.
    pub drive1: Servo,
    /// The drive of crank 4.
    pub drive4: Servo,
    /// Resisting moment on coupler 3, N·m.
    pub m_on: f64,
}

impl Default for FiveBar {
    /// A small horizontal pick-and-place robot: frame hinges O = (0, 0) and D = (0.2, 0) m,
    /// cranks 0.15 m, couplers 0.25 m of 0.6 kg each with the centres of mass at their
    /// middles, I1 = I4 = 0.02 kg·m² (crank and geared motor), B above the line A–C, no
    /// gravity, the seed's two-point masses (no j_s2, j_s3). Servos with k_p = 20 N·m/rad,
    /// k_d = 1 N·m·s/rad and 5 N·m limit move the cranks to 100° and 80°; a tool moment
    /// M_on = 0.3 N·m resists on coupler 3. A good start is (φ1, φ4) = (120°, 60°) at rest.
    fn default() -> Self {
        let servo = |deg: f64| Servo {
            target: deg.to_radians(),
            kp: 20.0,
            kd: 1.0,
            limit: 5.0,
        };
        Self {
            o: Point2::origin(),
            d: Point2::new(0.2, 0.0),
            l_oa: 0.15,
            l_ab: 0.25,
            l_cb: 0.25,
            l_dc: 0.15,
            l_as2: 0.125,
            l_bs3: 0.125,
            m2: 0.6,
            m3: 0.6,
            i1: 0.02,
            i4: 0.02,
            j_s2: None,
            j_s3: None,
            mode: 1.0,
            gravity: 0.0,
            drive1: servo(100.0),
            drive4: servo(80.0),
            m_on: 0.3,
        }
    }
}

impl FiveBar {
    /// Checks the robot's data (the fields are public, so every evaluation checks them).
    #[inline]
    fn check(&self) -> Result<()> {
        if self.valid() {
            return Ok(());
        }
        self.check_named()
    }

    /// Whether [`check_named`](Self::check_named) passes, in one branch-free pass (the
    /// check ran at every evaluation and cost some 7 % of one).
    #[inline]
    fn valid(&self) -> bool {
        // `&` rather than `&&`: no branch per field (and the comparisons are false for NaN).
        let finite = self.o.x.is_finite()
            & self.o.y.is_finite()
            & self.d.x.is_finite()
            & self.d.y.is_finite()
            & self.gravity.is_finite()
            & self.m_on.is_finite()
            & self.j_s2.is_none_or(f64::is_finite)
            & self.j_s3.is_none_or(f64::is_finite);
        let positive = |x: f64| (x > 0.0) & (x < f64::INFINITY);
        let positive = positive(self.l_oa)
            & positive(self.l_ab)
            & positive(self.l_cb)
            & positive(self.l_dc)
            & positive(self.m2)
            & positive(self.m3)
            & positive(self.i1)
            & positive(self.i4);
        let on_couplers =
            (0.0..=self.l_ab).contains(&self.l_as2) & (0.0..=self.l_cb).contains(&self.l_bs3);
        finite
            & positive
            & on_couplers
            & self.drive1.valid()
            & self.drive4.valid()
            & (self.mode.abs() == 1.0)
    }

    /// The checks of [`check`](Self::check), naming the first bad field.
    #[cold]
    #[inline(never)]
    fn check_named(&self) -> Result<()> {
        finite2(["O.x", "O.y"], self.o.coords)?;
        finite2(["D.x", "D.y"], self.d.coords)?;
        for (n, v) in [
            ("l_OA", self.l_oa),
            ("l_AB", self.l_ab),
            ("l_CB", self.l_cb),
            ("l_DC", self.l_dc),
            ("m2", self.m2),
            ("m3", self.m3),
            ("I1", self.i1),
            ("I4", self.i4),
        ] {
            positive(n, v)?;
        }
        for (n, v, l) in [
            ("l_AS2", self.l_as2, self.l_ab),
            ("l_BS3", self.l_bs3, self.l_cb),
        ] {
            if !(0.0..=l).contains(&v) {
                return Err(Error::OutOfRange {
                    name: n,
                    value: v,
                    min: 0.0,
                    max: l,
                    ends: crate::Ends::Closed,
                });
            }
        }
        finite("gravity", self.gravity)?;
        finite("M_on", self.m_on)?;
        if let Some(j) = self.j_s2 {
            finite("J_S2", j)?;
        }
        if let Some(j) = self.j_s3 {
            finite("J_S3", j)?;
        }
        self.drive1.check()?;
        self.drive4.check()?;
        if self.mode.abs() != 1.0 {
            return Err(Error::Description {
                item: "five-bar mode".into(),
                problem: format!("must be +1 or −1, got {}", self.mode),
            });
        }
        Ok(())
    }

    /// The point masses (m_A2, m_B, m_C3) of the static distribution (eqs. 12–16).
    ///
    /// # Errors
    /// Any error of the robot's data (non-finite or non-positive lengths and masses, a centre
    /// of mass off its coupler, a bad servo); [`Error::Overflow`] when a mass overflows.
    pub fn point_masses(&self) -> Result<[f64; 3]> {
        self.check()?;
        let m = self.masses();
        computed_all("five-bar point masses", m.iter())?;
        Ok(m)
    }

    /// [`point_masses`](Self::point_masses) for checked data.
    fn masses(&self) -> [f64; 3] {
        let m_a2 = self.m2 * (self.l_ab - self.l_as2) / self.l_ab;
        let m_b2 = self.m2 * self.l_as2 / self.l_ab;
        let m_b3 = self.m3 * (self.l_cb - self.l_bs3) / self.l_cb;
        let m_c3 = self.m3 * self.l_bs3 / self.l_cb;
        [m_a2, m_b2 + m_b3, m_c3]
    }

    /// The corrections ΔJ = J_S − m·l_AS·l_SB of the couplers' rotational inertia (zero when
    /// `j_s2`/`j_s3` are not set).
    fn delta_j(&self) -> [f64; 2] {
        [
            self.j_s2
                .map_or(0.0, |j| j - self.m2 * self.l_as2 * (self.l_ab - self.l_as2)),
            self.j_s3
                .map_or(0.0, |j| j - self.m3 * self.l_bs3 * (self.l_cb - self.l_bs3)),
        ]
    }

    /// Positions and velocity analogs at q = (φ1, φ4).
    ///
    /// # Errors
    /// [`Error::NotAssemblable`] when the couplers cannot reach each other;
    /// [`Error::Singular`] (measure `sin(phi3 - phi2)`) when they are collinear.
    ///
    /// # Examples
    /// The default robot at (120°, 60°) is symmetric about x = 0.1 m: A = (−0.075, 0.1299),
    /// C = (0.275, 0.1299), so B = (0.1, 0.1299 + √(0.25² − 0.175²)) = (0.1, 0.3085), and
    /// turning crank 1 alone moves B as much (mirrored) as turning crank 4 alone.
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::dynamics::machines::FiveBar;
    /// let k = FiveBar::default()
    ///     .kinematics(&Vector2::new(120f64.to_radians(), 60f64.to_radians()))
    ///     .unwrap();
    /// let yb = 0.15 * 60f64.to_radians().sin() + (0.25f64.powi(2) - 0.175f64.powi(2)).sqrt();
    /// assert!((k.b.x - 0.1).abs() < 1e-12 && (k.b.y - yb).abs() < 1e-12);
    /// assert!((k.b_q[0].x - k.b_q[1].x).abs() < 1e-12 && (k.b_q[0].y + k.b_q[1].y).abs() < 1e-12);
    /// ```
    pub fn kinematics(&self, q: &Vector2<f64>) -> Result<FiveBarKinematics> {
        self.kinematics_inline(q)
    }

    /// [`kinematics`](Self::kinematics), inlined into the Lagrange terms: the 300-byte result
    /// is then built where it is used instead of copied out of a call (twice, some 4 % of an
    /// evaluation).
    #[inline(always)]
    fn kinematics_inline(&self, q: &Vector2<f64>) -> Result<FiveBarKinematics> {
        self.check()?;
        finite("phi1", q[0])?;
        finite("phi4", q[1])?;
        let (e1, e4) = (unit(q[0]), unit(q[1]));
        let a = self.o + self.l_oa * e1;
        let c = self.d + self.l_dc * e4;
        let ac = c - a;
        let dist = ac.norm();
        let (r2, r3) = (self.l_ab, self.l_cb);
        if dist > r2 + r3 || dist < (r2 - r3).abs() || dist == 0.0 {
            let gap = if dist > r2 + r3 {
                dist - r2 - r3
            } else {
                (r2 - r3).abs() - dist
            };
            return Err(Error::NotAssemblable {
                group: "five-bar (couplers 2 and 3)",
                gap,
            });
        }
        let along = (r2 * r2 - r3 * r3 + dist * dist) / (2.0 * dist);
        let height = (r2 * r2 - along * along).max(0.0).sqrt();
        let ehat = ac / dist;
        let b = a + along * ehat + self.mode * height * perp(ehat);
        let phi2 = crate::angle::direction(b - a);
        let phi3 = crate::angle::direction(b - c);
        let (e2, e3) = (unit(phi2), unit(phi3));
        let (p2, p3) = (perp(e2) * r2, perp(e3) * r3);
        let sin32 = (phi3 - phi2).sin();
        // The closure l_AB·e⊥2·φ2,k − l_CB·e⊥3·φ3,k = C,k − A,k has det −l_AB·l_CB·sin(φ3 − φ2).
        let det = cross(p2, -p3);
        if sin32.abs() < 1e-10 {
            return Err(Error::Singular {
                what: "five-bar (couplers collinear)",
                measure: "sin(phi3 - phi2)",
                value: sin32,
            });
        }
        let solve = |r: Vector2<f64>| (cross(r, -p3) / det, cross(p2, r) / det);
        let a_q = [self.l_oa * perp(e1), Vector2::zeros()];
        let c_q = [Vector2::zeros(), self.l_dc * perp(e4)];
        let mut phi2_q = [0.0; 2];
        let mut phi3_q = [0.0; 2];
        let mut b_q = [Vector2::zeros(); 2];
        for k in 0..2 {
            (phi2_q[k], phi3_q[k]) = solve(c_q[k] - a_q[k]);
            b_q[k] = a_q[k] + p2 * phi2_q[k];
        }
        // Second order: differentiating the closure again (d e⊥/dφ = −e) gives the same
        // matrix with the right side C,kj − A,kj + l_AB·e2·φ2,k·φ2,j − l_CB·e3·φ3,k·φ3,j.
        let a_qq = [
            [-self.l_oa * e1, Vector2::zeros()],
            [Vector2::zeros(), Vector2::zeros()],
        ];
        let c_qq = [
            [Vector2::zeros(), Vector2::zeros()],
            [Vector2::zeros(), -self.l_dc * e4],
        ];
        let mut phi2_qq = [[0.0; 2]; 2];
        let mut phi3_qq = [[0.0; 2]; 2];
        let mut b_qq = [[Vector2::zeros(); 2]; 2];
        for k in 0..2 {
            for j in 0..2 {
                let r = c_qq[k][j] - a_qq[k][j] + r2 * e2 * phi2_q[k] * phi2_q[j]
                    - r3 * e3 * phi3_q[k] * phi3_q[j];
                (phi2_qq[k][j], phi3_qq[k][j]) = solve(r);
                b_qq[k][j] = a_qq[k][j] + p2 * phi2_qq[k][j] - r2 * e2 * phi2_q[k] * phi2_q[j];
            }
        }
        Ok(FiveBarKinematics {
            a,
            b,
            c,
            phi2,
            phi3,
            sin_phi3_minus_phi2: sin32,
            b_q,
            phi2_q,
            phi3_q,
            b_qq,
            phi2_qq,
            phi3_qq,
        })
    }

    /// ∂A/∂q from the analogs of `k` (see [`LagrangeSystem::inertia_derivatives`]).
    fn derivatives_from(&self, k: &FiveBarKinematics) -> [Matrix2<f64>; 2] {
        let [_, m_b, _] = self.masses();
        let [dj2, dj3] = self.delta_j();
        let mut d = [Matrix2::zeros(); 2];
        for (n, dn) in d.iter_mut().enumerate() {
            for i in 0..2 {
                for j in 0..2 {
                    dn[(i, j)] = m_b * (k.b_qq[i][n].dot(&k.b_q[j]) + k.b_q[i].dot(&k.b_qq[j][n]))
                        + dj2 * (k.phi2_qq[i][n] * k.phi2_q[j] + k.phi2_q[i] * k.phi2_qq[j][n])
                        + dj3 * (k.phi3_qq[i][n] * k.phi3_q[j] + k.phi3_q[i] * k.phi3_qq[j][n]);
                }
            }
        }
        d
    }

    /// Q at (q, q̇) with the analogs of `k`: the servos and the tool moment.
    fn forces_from(
        &self,
        k: &FiveBarKinematics,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<Vector2<f64>> {
        let f = Vector2::new(
            self.drive1.torque(q[0], qd[0])? - self.m_on * k.phi3_q[0],
            self.drive4.torque(q[1], qd[1])? - self.m_on * k.phi3_q[1],
        );
        computed_all("five-bar generalized forces", f.iter())?;
        Ok(f)
    }

    /// ∇Π at q with the analogs of `k`.
    fn gradient_from(&self, k: &FiveBarKinematics, q: &Vector2<f64>) -> Vector2<f64> {
        let [m_a2, m_b, m_c3] = self.masses();
        let (e1, e4) = (unit(q[0]), unit(q[1]));
        self.gravity
            * Vector2::new(
                m_a2 * self.l_oa * e1.x + m_b * k.b_q[0].y,
                m_c3 * self.l_dc * e4.x + m_b * k.b_q[1].y,
            )
    }

    fn inertia_from(&self, k: &FiveBarKinematics) -> Matrix2<f64> {
        let [m_a2, m_b, m_c3] = self.masses();
        let [dj2, dj3] = self.delta_j();
        let mut a = Matrix2::new(
            self.i1 + m_a2 * self.l_oa * self.l_oa,
            0.0,
            0.0,
            self.i4 + m_c3 * self.l_dc * self.l_dc,
        );
        for i in 0..2 {
            for j in i..2 {
                a[(i, j)] += m_b * k.b_q[i].dot(&k.b_q[j])
                    + dj2 * k.phi2_q[i] * k.phi2_q[j]
                    + dj3 * k.phi3_q[i] * k.phi3_q[j];
            }
        }
        // Symmetric by construction, to the last bit.
        a[(1, 0)] = a[(0, 1)];
        a
    }
}

impl LagrangeSystem for FiveBar {
    fn coordinate_names(&self) -> [&'static str; 2] {
        ["phi_1", "phi_4"]
    }

    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        let a = self.inertia_from(&self.kinematics(q)?);
        computed_all("five-bar inertia matrix", a.iter())?;
        Ok(a)
    }

    /// ∂A_ij/∂q_k = m_B (B,ik·B,j + B,i·B,jk) + ΔJ (φ,ik φ,j + φ,i φ,jk) from the
    /// second-order analogs.
    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        let d = self.derivatives_from(&self.kinematics(q)?);
        computed_all(
            "five-bar inertia derivatives",
            d.iter().flat_map(|m| m.iter()),
        )?;
        Ok(d)
    }

    /// Every term from one [`kinematics`](FiveBar::kinematics) (the separate methods solve
    /// it once each), the failures in the order of the separate methods: the kinematics, A
    /// not positive-definite, a servo's error.
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        let k = self.kinematics_inline(q)?;
        let inertia = self.inertia_from(&k);
        checked_inertia(&inertia, t, q)?;
        let inertia_derivatives = self.derivatives_from(&k);
        computed_all(
            "five-bar inertia derivatives",
            inertia_derivatives.iter().flat_map(|m| m.iter()),
        )?;
        let potential_gradient = self.gradient_from(&k, q);
        computed_all("five-bar potential gradient", potential_gradient.iter())?;
        Ok(LagrangeTerms {
            inertia,
            inertia_derivatives,
            forces: self.forces_from(&k, q, qd)?,
            potential_gradient,
            damping: Matrix2::zeros(),
        })
    }

    fn forces(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.forces_from(&self.kinematics(q)?, q, qd)
    }

    fn potential(&self, q: &Vector2<f64>) -> Result<f64> {
        let k = self.kinematics(q)?;
        let [m_a2, m_b, m_c3] = self.masses();
        crate::error::computed(
            "five-bar potential",
            self.gravity * (m_a2 * k.a.y + m_b * k.b.y + m_c3 * k.c.y),
        )
    }

    fn potential_gradient(&self, q: &Vector2<f64>) -> Result<Vector2<f64>> {
        let g = self.gradient_from(&self.kinematics(q)?, q);
        computed_all("five-bar potential gradient", g.iter())?;
        Ok(g)
    }

    /// The servos' saturation switches: two arguments, crank 1's servo's demand over its
    /// limit and crank 4's (see [`kink_arguments`](Self::kink_arguments)), each with the
    /// nodes ±1 (its clamps); a servo with limit 0 never switches and its argument has no
    /// node.
    fn kinks(&self) -> Vec<Vec<f64>> {
        [self.drive1, self.drive4]
            .iter()
            .map(Servo::switch_nodes)
            .collect()
    }

    /// Each servo's demand as a fraction of its limit, (k_p·e − k_d·ω)/limit kept within
    /// [−2, 2] (`out[0]` crank 1's, `out[1]` crank 4's): the servo follows its demand inside
    /// (−1, 1) and saturates outside, so its clamps are the nodes ±1. The clamp is a kink of
    /// Q, and [`run`](crate::dynamics::run) steps onto it, so that a fixed-step method keeps
    /// its order; two switches in one step (the default robot's servos switch about a
    /// millisecond apart, and one servo may swing from one clamp to the other) are located
    /// one after the other. A servo with limit 0 (never switching) gives 0 and has no node.
    ///
    /// # Errors
    /// As [`Servo::torque`]; [`Error::OutOfRange`] when `out` has not two entries.
    fn kink_arguments(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        kink_slots(out, 2)?;
        self.drive1.check()?;
        self.drive4.check()?;
        finite2(["phi1", "phi4"], *q)?;
        finite2(["phi1_dot", "phi4_dot"], *qd)?;
        out[0] = self.drive1.switch_argument(q[0], qd[0])?.unwrap_or(0.0);
        out[1] = self.drive4.switch_argument(q[1], qd[1])?.unwrap_or(0.0);
        Ok(())
    }

    fn output_names(&self) -> Vec<&'static str> {
        vec![
            "x_B",
            "y_B",
            "phi_2",
            "phi_3",
            "M_p1",
            "M_p4",
            "sin_phi3_minus_phi2",
        ]
    }

    fn outputs(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        let k = self.kinematics(q)?;
        out.extend([
            k.b.x,
            k.b.y,
            k.phi2,
            k.phi3,
            self.drive1.torque(q[0], qd[0])?,
            self.drive4.torque(q[1], qd[1])?,
            k.sin_phi3_minus_phi2,
        ]);
        Ok(())
    }
}
