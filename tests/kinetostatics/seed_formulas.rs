//! The seed's own scalar formulas (seed 000), with the corrections of docs/errata.md (E2, E4, E5, E8),
//! written out independently of the crate: a second derivation to compare against.

use std::f64::consts::{FRAC_PI_2, PI};
use tmm::kinetostatics::{RprSeed, RrpSeed, RrrSeed};

pub struct Sr1 {
    pub r12_t: f64,
    pub r43_t: f64,
    pub r12_n: f64,
    pub r43_n: f64,
}

/// (1.5), (1.8), (1.10) and the solution after it.
pub fn sr1(s: &RrrSeed) -> Sr1 {
    let r12_t = (s.f2 * s.l_bs2 * (s.phi2 - s.gamma2).sin() + s.m2) / s.l_ba;
    let r43_t = (s.f3 * s.l_bs3 * (s.phi3 - s.gamma3).sin() + s.m3) / s.l_bc;
    let a = r12_t * (s.phi2 + FRAC_PI_2).cos()
        + s.f2 * s.gamma2.cos()
        + s.f3 * s.gamma3.cos()
        + r43_t * (s.phi3 + FRAC_PI_2).cos();
    let b = r12_t * (s.phi2 + FRAC_PI_2).sin()
        + s.f2 * s.gamma2.sin()
        + s.f3 * s.gamma3.sin()
        + r43_t * (s.phi3 + FRAC_PI_2).sin();
    Sr1 {
        r12_t,
        r43_t,
        r12_n: -(a * s.phi3.sin() - b * s.phi3.cos()) / (s.phi3 - s.phi2).sin(),
        r43_n: -(a * s.phi2.sin() - b * s.phi2.cos()) / (s.phi2 - s.phi3).sin(),
    }
}

/// (1.24), (1.26) in its full (correct) form, and its solution. Returns (R12τ, R12ⁿ, R43).
pub fn sr2(s: &RrpSeed) -> (f64, f64, f64) {
    let r12_t = (s.f2 * s.l_bs2 * (s.phi2 - s.gamma2).sin() + s.m2) / s.l_ba;
    let a = r12_t * (s.phi2 + FRAC_PI_2).cos() + s.f2 * s.gamma2.cos() + s.f3 * s.gamma3.cos();
    let b = r12_t * (s.phi2 + FRAC_PI_2).sin() + s.f2 * s.gamma2.sin() + s.f3 * s.gamma3.sin();
    let det = (s.phi2 - s.phi4).cos();
    (
        r12_t,
        -(a * s.phi4.cos() + b * s.phi4.sin()) / det,
        (a * s.phi2.sin() - b * s.phi2.cos()) / det,
    )
}

/// (1.35) corrected (γ3 in the F3 term, docs/errata.md#e4), (1.37) and its solution, (1.46).
/// Returns (R12τ, R12ⁿ, R32, h32).
pub fn sr3(s: &RprSeed) -> (f64, f64, f64, Option<f64>) {
    let l_ea = s.l_ab - s.l_bc + s.l_ec;
    let l_es2 = l_ea - s.l_as2;
    let r12_t = (s.f2 * l_es2 * (s.phi2 - s.gamma2).sin()
        + s.f3 * s.l_es3 * (s.phi2 - s.gamma3).sin()
        + s.m2
        + s.m3)
        / l_ea;
    let a = r12_t * (s.phi2 + FRAC_PI_2).cos() + s.f2 * s.gamma2.cos();
    let b = r12_t * (s.phi2 + FRAC_PI_2).sin() + s.f2 * s.gamma2.sin();
    let r32 = a * s.phi2.sin() - b * s.phi2.cos();
    let h32 = -(s.f2 * s.l_as2 * (s.gamma2 - s.phi2).sin() + s.m2) / r32;
    (
        r12_t,
        -(a * s.phi2.cos() + b * s.phi2.sin()),
        r32,
        Some(h32).filter(|h| h.is_finite() && r32.abs() > 1e-6),
    )
}

/// SRWL2's corrected 1.56 and SRWL1's 1.49 with the flank rule. Returns
/// (M_b, (F3p, γ3p)).
#[allow(clippy::too_many_arguments)]
pub fn srwl(
    l_o1a: f64,
    l_o1s1: f64,
    l_o1p: f64,
    alpha_w: f64,
    phi1: f64,
    f1: f64,
    gamma1: f64,
    r21: f64,
    gamma21: f64,
    m1: f64,
) -> (f64, (f64, f64)) {
    let known = r21 * l_o1a * (gamma21 - phi1).sin() + f1 * l_o1s1 * (gamma1 - phi1).sin() + m1;
    let gamma = FRAC_PI_2 - alpha_w;
    let f = known / (l_o1p * gamma.sin());
    let gear = if f < 0.0 {
        (f.abs(), 1.5 * PI + alpha_w)
    } else {
        (f, gamma)
    };
    (-known, gear)
}
