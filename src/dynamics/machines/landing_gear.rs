//! The landing-gear drive with two motors (seed 003, §4, eqs. 64–104).

use nalgebra::{Matrix2, Vector2};

use super::{gear_inertia, GearLink, LinearMotor};
use crate::dynamics::system::{kink_slots, LagrangeSystem};
use crate::dynamics::table::{Beyond, Table};
use crate::error::{computed, computed_all, finite, finite2, positive, Result};

/// A failed motor of the [`LandingGear`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Failure {
    /// Motor D1 (on the sun z1) gives no moment; `braked`: its shaft is held at rest.
    Motor1 {
        /// Whether a brake holds the failed input (it must start at rest).
        braked: bool,
    },
    /// Motor D6 (on the pinion z6) gives no moment; `braked`: its shaft is held at rest.
    Motor6 {
        /// Whether a brake holds the failed input (it must start at rest).
        braked: bool,
    },
}

/// The landing-gear drive: a differential (sun z1, k planets z2, internal ring z3, carrier H,
/// the output) and a row of gears z4–z5–z6 (z4 on the ring, z5 an idler, z6 on the second
/// motor's shaft). Two induction motors D1 (on z1) and D6 (on z6) drive it against the
/// gear's moment M_on(φ_H), given as a [`Table`]. The generalized coordinates are
/// q = (φ1, φ6).
///
/// Kinematics (Willis; docs/errata.md#d23): φ̇H = uH1·φ̇1 + uH3·u36·φ̇6 with uH1 = z1/(z1+z3),
/// uH3 = z3/(z1+z3), u36 = z6/z4; the planets turn at φ̇2 = u21·φ̇1 + u23·u36·φ̇6 with
/// u21 = z1(z2−z3)/(z2(z1+z3)), u23 = (z1+z2)z3/(z2(z1+z3)); the idler at u56 = −z6/z5. The
/// inertia matrix is constant (eqs. 71–73, D24, D25). Q = (M_p1, M_p6) + M_on·(uH1, uH3·u36)
/// (eqs. 81–84, D26): M_on is signed, negative when it resists the extension of φ_H.
///
/// With one motor failed ([`Failure`]) its moment is zero. If it is braked, the brake holds
/// its shaft: the brake moment is the reaction that keeps that coordinate's acceleration zero
/// (it is an output), and the differential works as a planetary gear, as the seed says. If it
/// is not braked, nothing holds the failed shaft: the working motor spins it backwards and
/// the gear falls back under its load (docs/errata.md#d31).
#[derive(Debug, Clone, PartialEq)]
pub struct LandingGear {
    /// Teeth z1 (sun), z2 (planet), z3 (ring), z4 (on the ring), z5 (idler), z6 (pinion).
    pub z: [u32; 6],
    /// Number of planets k.
    pub k: u32,
    /// Mass of one planet, kg.
    pub m2: f64,
    /// Carrier arm r_w1 + r_w2, m.
    pub carrier_arm: f64,
    /// Moment of inertia of z1 with the rotor of D1, kg·m².
    pub i1: f64,
    /// Moment of inertia of one planet about its axis, kg·m².
    pub i2: f64,
    /// Moment of inertia of the ring z3 with z4, kg·m².
    pub i3: f64,
    /// Moment of inertia of the idler z5, kg·m².
    pub i5: f64,
    /// Moment of inertia of z6 with the rotor of D6, kg·m².
    pub i6: f64,
    /// Moment of inertia of the carrier with the landing gear reduced to its axis, kg·m².
    pub ih: f64,
    /// Motor D1.
    pub motor1: LinearMotor,
    /// Motor D6.
    pub motor6: LinearMotor,
    /// The gear's moment on the carrier M_on(φ_H), N·m (signed).
    pub load: Table,
    /// The carrier angle at which the gear is retracted, rad.
    pub phi_h_max: f64,
    /// A failed motor, if any.
    pub failure: Option<Failure>,
}

impl Default for LandingGear {
    /// A main-gear retraction drive: z = (20, 25, 70, 60, 30, 20) (uH1 = 2/9, uH3 = 7/9,
    /// u36 = 1/3), k = 3 planets of 0.05 kg and 1·10⁻⁵ kg·m², carrier arm 45 mm (module 2 mm);
    /// I1 = I6 = 4·10⁻⁴ kg·m² (rotor and pinion), I3 = 2·10⁻³, I5 = 5·10⁻⁵,
    /// IH = 3·10⁻⁴ kg·m² (carrier plus a 250 kg leg, about 480 kg·m² at its hinge, reduced
    /// by a screw-jack ratio of 2500). Two 400 Hz four-pole motors: 0.4 N·m nominal at
    /// 11 000 rpm, 12 000 rpm synchronous. The leg turns 90° (ψ = φ_H/2500, so
    /// φ_H_max = 1250π ≈ 3927 rad) against M_on = −(M_g cos ψ + M_a sin ψ)/2500 with the
    /// weight moment M_g = 250·9.81·1.2 = 2943 N·m and an aerodynamic moment M_a = 600 N·m,
    /// tabulated every 10° of ψ. Outside the table the end values hold ([`Beyond::HoldEnds`]):
    /// below φ_H = 0 the leg rests on its down-lock, and the integrator's inner stages may
    /// look slightly past the end of the stroke.
    fn default() -> Self {
        let rpm = std::f64::consts::PI / 30.0;
        let motor = LinearMotor {
            b: 0.4 / (1000.0 * rpm),
            a: 0.4 / (1000.0 * rpm) * 12_000.0 * rpm,
        };
        let ratio = 2500.0;
        let (mg, ma) = (250.0 * 9.81 * 1.2, 600.0);
        let psi: Vec<f64> = (0..=9).map(|i| f64::from(i) * 10f64.to_radians()).collect();
        let x = psi.iter().map(|p| p * ratio).collect();
        let y = psi
            .iter()
            .map(|p| -(mg * p.cos() + ma * p.sin()) / ratio)
            .collect();
        Self {
            z: [20, 25, 70, 60, 30, 20],
            k: 3,
            m2: 0.05,
            carrier_arm: 0.045,
            i1: 4e-4,
            i2: 1e-5,
            i3: 2e-3,
            i5: 5e-5,
            i6: 4e-4,
            ih: 3e-4,
            motor1: motor,
            motor6: motor,
            // Constant data, no input reaches it: ten finite points, x strictly increasing
            // (0°…90° every 10°, times the ratio). The unit tests build it, so a change that
            // broke it would fail there, not in a user's program.
            load: Table::new(x, y, Beyond::HoldEnds).expect("a valid built-in table"),
            phi_h_max: ratio * std::f64::consts::FRAC_PI_2,
            failure: None,
        }
    }
}

impl LandingGear {
    /// The ratios (uH1, uH3·u36) of the carrier: φ̇H = ratios · q̇.
    ///
    /// # Examples
    /// With z1 = 20, z3 = 70, z4 = 60, z6 = 20: uH1 = 20/90, uH3·u36 = (70/90)·(20/60) = 7/27,
    /// so both motors at 1200 rad/s turn the carrier at 1200·(2/9 + 7/27) = 577.8 rad/s.
    /// ```
    /// use nalgebra::Vector2;
    /// use tmm::dynamics::machines::LandingGear;
    /// let u = LandingGear::default().carrier_ratios();
    /// assert!((u.dot(&Vector2::new(1200.0, 1200.0)) - 1200.0 * (2.0 / 9.0 + 7.0 / 27.0)).abs() < 1e-9);
    /// ```
    #[must_use]
    pub fn carrier_ratios(&self) -> Vector2<f64> {
        let [z1, _, z3, z4, _, z6] = self.z.map(f64::from);
        Vector2::new(z1 / (z1 + z3), z3 / (z1 + z3) * z6 / z4)
    }

    /// The speed rows s (ω = s·q̇) of z1, z2, H, z3–z4, z5, z6.
    #[must_use]
    pub fn link_ratios(&self) -> [Vector2<f64>; 6] {
        let [z1, z2, z3, z4, z5, z6] = self.z.map(f64::from);
        let u36 = z6 / z4;
        let u21 = z1 * (z2 - z3) / (z2 * (z1 + z3));
        let u23 = (z1 + z2) * z3 / (z2 * (z1 + z3));
        [
            Vector2::new(1.0, 0.0),
            Vector2::new(u21, u23 * u36),
            self.carrier_ratios(),
            Vector2::new(0.0, u36),
            Vector2::new(0.0, -z6 / z5),
            Vector2::new(0.0, 1.0),
        ]
    }

    fn check(&self) -> Result<()> {
        for (i, &z) in self.z.iter().enumerate() {
            positive(["z1", "z2", "z3", "z4", "z5", "z6"][i], f64::from(z))?;
        }
        positive("k", f64::from(self.k))?;
        for (n, v) in [
            ("m2", self.m2),
            ("carrier_arm", self.carrier_arm),
            ("I1", self.i1),
            ("I2", self.i2),
            ("I3", self.i3),
            ("I5", self.i5),
            ("I6", self.i6),
            ("IH", self.ih),
        ] {
            positive(n, v)?;
        }
        self.motor1.check()?;
        self.motor6.check()?;
        finite("phi_H max", self.phi_h_max)?;
        Ok(())
    }

    /// The constant inertia matrix [[I11, I16], [I16, I66]] (eqs. 71–73).
    ///
    /// # Errors
    /// [`Error::NonPositive`](crate::Error::NonPositive) for a non-positive datum.
    pub fn inertia_matrix(&self) -> Result<Matrix2<f64>> {
        self.check()?;
        let [s1, s2, sh, s3, s5, s6] = self.link_ratios();
        let k = f64::from(self.k);
        let a = gear_inertia(&[
            GearLink {
                inertia: self.i1,
                speed: s1,
            },
            GearLink {
                inertia: k * self.m2 * self.carrier_arm.powi(2),
                speed: sh,
            },
            GearLink {
                inertia: k * self.i2,
                speed: s2,
            },
            GearLink {
                inertia: self.ih,
                speed: sh,
            },
            GearLink {
                inertia: self.i3,
                speed: s3,
            },
            GearLink {
                inertia: self.i5,
                speed: s5,
            },
            GearLink {
                inertia: self.i6,
                speed: s6,
            },
        ]);
        computed_all("inertia matrix", a.iter())?;
        Ok(a)
    }

    /// The carrier angle φ_H = uH1·φ1 + uH3·u36·φ6 (zero when q = 0).
    ///
    /// # Errors
    /// [`Error::NonFinite`](crate::Error::NonFinite) for a non-finite q;
    /// [`Error::Overflow`](crate::Error::Overflow) when φ_H overflows.
    pub fn phi_h(&self, q: &Vector2<f64>) -> Result<f64> {
        finite2(["phi_1", "phi_6"], *q)?;
        computed("phi_H", self.carrier_ratios().dot(q))
    }

    /// The motor moments, the gear's moment, the brake moment and Q, in that order.
    fn loads(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<(f64, f64, f64, f64, Vector2<f64>)> {
        self.check()?;
        let mut mp1 = self.motor1.torque(qd[0])?;
        let mut mp6 = self.motor6.torque(qd[1])?;
        let mut braked = None;
        match self.failure {
            Some(Failure::Motor1 { braked: b }) => {
                mp1 = 0.0;
                braked = b.then_some(0);
            }
            Some(Failure::Motor6 { braked: b }) => {
                mp6 = 0.0;
                braked = b.then_some(1);
            }
            None => {}
        }
        let m_on = self.load.at(self.phi_h(q)?)?;
        let mut qf = Vector2::new(mp1, mp6) + m_on * self.carrier_ratios();
        let mut brake = 0.0;
        if let Some(j) = braked {
            // The brake reaction that makes q̈_j = 0: the other row gives q̈_o = Q_o/A_oo, and
            // row j then needs Q_j + M_br = A_jo·q̈_o.
            let a = self.inertia_matrix()?;
            let o = 1 - j;
            brake = a[(j, o)] * qf[o] / a[(o, o)] - qf[j];
            qf[j] += brake;
        }
        computed_all("generalized forces", qf.iter())?;
        computed("brake moment", brake)?;
        Ok((mp1, mp6, m_on, brake, qf))
    }
}

impl LagrangeSystem for LandingGear {
    fn coordinate_names(&self) -> [&'static str; 2] {
        ["phi_1", "phi_6"]
    }

    fn inertia(&self, _q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.inertia_matrix()
    }

    fn inertia_derivatives(&self, _q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        Ok([Matrix2::zeros(); 2])
    }

    fn forces(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        Ok(self.loads(q, qd)?.4)
    }

    /// One kink argument, φ_H (see [`kink_arguments`](Self::kink_arguments)), with the
    /// nodes of the moment table [`load`](Self::load): M_on(φ_H) has a kink at each.
    fn kinks(&self) -> Vec<Vec<f64>> {
        vec![self.load.xs().to_vec()]
    }

    /// The carrier angle φ_H, the argument of the moment table: `out` has one entry.
    fn kink_arguments(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        _qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        kink_slots(out, 1)?;
        out[0] = self.phi_h(q)?;
        Ok(())
    }

    fn output_names(&self) -> Vec<&'static str> {
        vec![
            "phi_H", "omega_1", "omega_2", "omega_H", "omega_3", "omega_5", "omega_6", "M_p1",
            "M_p6", "M_on", "M_brake",
        ]
    }

    fn outputs(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        let phi_h = self.phi_h(q)?;
        let (mp1, mp6, m_on, brake, _) = self.loads(q, qd)?;
        let speeds = self.link_ratios().map(|s| s.dot(qd));
        computed_all("link speeds", speeds.iter())?;
        out.push(phi_h);
        out.extend(speeds);
        out.extend([mp1, mp6, m_on, brake]);
        Ok(())
    }
}
