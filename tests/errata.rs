//! Misprints of the source texts that no other test pins down on its own: each test computes
//! the printed form and the corrected one independently of the crate and shows that the crate
//! follows the corrected one (and, where the printed one gives different numbers, that it
//! does). The misprints, their derivations and the tests for the others are listed in
//! `docs/errata.md`.

use nalgebra::Matrix2;
use tmm::dynamics::machines::{CoaxialPropellers, LinearMotor};
use tmm::kinetostatics::{CouplingSeed, RprSeed};

/// docs/errata.md#e4: the moment of F3 about E in (1.35) has sin(φ2 − γ3), not sin(φ2 − γ2).
#[test]
fn e4_rpr_moment_of_f3_uses_its_own_direction() {
    let s = RprSeed {
        l_ab: 0.3,
        l_bc: 0.1,
        l_ec: 0.3,
        l_as2: 0.1,
        l_es3: 0.12,
        phi2: 0.4,
        f2: 120.0,
        gamma2: 1.9,
        f3: 300.0,
        gamma3: 4.0,
        m2: 5.0,
        m3: -8.0,
    };
    let l_ea = s.l_ab - s.l_bc + s.l_ec;
    let l_es2 = l_ea - s.l_as2;
    let tangential = |gamma_of_f3: f64| {
        (s.f2 * l_es2 * (s.phi2 - s.gamma2).sin()
            + s.f3 * s.l_es3 * (s.phi2 - gamma_of_f3).sin()
            + s.m2
            + s.m3)
            / l_ea
    };
    let (corrected, printed) = (tangential(s.gamma3), tangential(s.gamma2));
    let r = s.solve().unwrap();
    assert!((r.r12_t - corrected).abs() < 1e-12 * corrected.abs().max(1.0));
    assert!((r.r12_t - printed).abs() > 1.0, "{} vs {printed}", r.r12_t);
}

/// docs/errata.md#e8: the balancing moment of an input link through a coupling is minus the
/// moment of the known loads about O1; the printed (1.56) drops the minus sign.
#[test]
fn e8_balancing_moment_has_the_sign_that_balances() {
    let s = CouplingSeed {
        l_o1a: 0.1,
        l_o1s1: 0.04,
        phi1: 0.7,
        f1: 20.0,
        gamma1: 4.2,
        r21: 350.0,
        gamma21: 2.5,
        m1: 1.5,
    };
    let printed = s.r21 * s.l_o1a * (s.gamma21 - s.phi1).sin()
        + s.f1 * s.l_o1s1 * (s.gamma1 - s.phi1).sin()
        + s.m1;
    let mb = s.solve().unwrap().balancing_moment;
    assert!((mb + printed).abs() < 1e-12 * printed.abs());
    assert!(
        printed.abs() > 1.0,
        "the case must tell the two signs apart"
    );
}

/// docs/errata.md#d32 to #d35: the coaxial-propeller differential's ratios (D32, D33), the
/// k planet blocks in I44 (D34) and the cross term I4H of the kinetic energy (D35), built here
/// from the teeth by Willis's formula and compared with the crate's inertia matrix.
#[test]
fn d32_to_d35_coaxial_ratios_and_inertia_matrix() {
    let d = CoaxialPropellers::default();
    let [z1, z2, z3, z4] = d.z.map(f64::from);
    let k = f64::from(d.k);
    // Carrier H held: the sun turns at u14 = −z2·z4/(z1·z3) times the ring (D32); ring held:
    // u1H = 1 − u14 = 1 + z2·z4/(z1·z3).
    let u14 = -z2 * z4 / (z1 * z3);
    let u1h = 1.0 + z2 * z4 / (z1 * z3);
    let u = d.input_ratios();
    assert!((u[0] - u14).abs() < 1e-15 * u14.abs() && (u[1] - u1h).abs() < 1e-15 * u1h);
    // The planets: u24 = z4/z3 (carrier held), u2H = 1 − z4/z3 (ring held).
    let (u24, u2h) = (z4 / z3, 1.0 - z4 / z3);
    let r2 = d.carrier_arm * d.carrier_arm;
    let i44 = d.i1 * u14 * u14 + k * d.i2 * u24 * u24 + d.i4; // with the k of D34
    let i4h = d.i1 * u14 * u1h + k * d.i2 * u24 * u2h; // u1H^(4) in the cross term (D33)
    let ihh = d.i1 * u1h * u1h + k * d.m2 * r2 + k * d.i2 * u2h * u2h + d.ih;
    let want = Matrix2::new(i44, i4h, i4h, ihh);
    let a = d.inertia_matrix().unwrap();
    assert!((a - want).amax() < 1e-13 * want.amax(), "{a} vs {want}");
    // The printed (112) without k gives a different I44 for the default data.
    let printed_i44 = d.i1 * u14 * u14 + d.i2 * u24 * u24 + d.i4;
    assert!((printed_i44 - i44).abs() > 1e-3 * i44);
}

/// docs/errata.md#d37: the motor's line M = a − b·ω through (ω_sync, 0) and (ω_nom, M_nom),
/// with the speeds (not the angles) in the denominators.
#[test]
fn d37_motor_line_through_the_synchronous_and_nominal_points() {
    let (m_nom, w_sync, w_nom) = (120.0, 157.08, 146.6);
    let m = LinearMotor::from_nominal(m_nom, w_sync, w_nom).unwrap();
    assert!(m.torque(w_sync).unwrap().abs() < 1e-12 * m_nom);
    assert!((m.torque(w_nom).unwrap() - m_nom).abs() < 1e-12 * m_nom);
    assert!((m.b - m_nom / (w_sync - w_nom)).abs() < 1e-15 * m.b);
}
