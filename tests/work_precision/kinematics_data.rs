//! Kinematics: the error of the seed's numerical differentiation (3-point formulas) and
//! integration (trapezoid rule) of tabulated positions against the number of positions per
//! cycle, measured against the exact transfer functions of the same mechanism.
//!
//! Two mechanisms: the rocker φ3(φ1) of a crank-rocker four-bar (crank 0.1 m, coupler
//! 0.35 m, rocker 0.3 m, frame hinges (0, 0) and (0.4, 0.05) m) and the slide s(φ1) of a
//! central slider-crank (crank 0.1 m, rod 0.3 m). N positions per cycle, N + 1 nodes from
//! φ1 = 0 to 2π (h = 2π/N), the table open at both ends as in the seed.
//!
//! Errors, each relative to the size of the exact function it approximates:
//! - "3-point inside": the central formula at the inner nodes, against φ′;
//! - "3-point ends": the one-sided formulas at the two end nodes, against φ′;
//! - "trapezoid": the running integral of the exact φ′ against φ(φ1) − φ(0);
//! - "central twice periodic": the periodic central formula applied twice, against φ″.

use nalgebra::Point2;
use tmm::kinematics::{
    crank, differentiate, differentiate_periodic, integrate_trapezoid, rrp_dyad, rrr_dyad,
    transfer_functions, Branch, Guide, Motion, PointMotion,
};

/// The two mechanisms.
pub const MECHANISMS: [&str; 2] = ["four-bar rocker", "slider-crank slide"];
/// The four measured quantities.
pub const QUANTITIES: [&str; 4] = [
    "3-point inside",
    "3-point ends",
    "trapezoid",
    "central twice periodic",
];

/// The position function and transfer functions (value, φ′, φ″) of a mechanism at φ1.
///
/// # Errors
/// A block's error (none: both mechanisms assemble everywhere).
pub fn exact(mechanism: &str, phi1: f64) -> tmm::Result<Motion> {
    if mechanism == MECHANISMS[0] {
        transfer_functions(
            |m| {
                let a = crank(Point2::origin(), 0.1, m)?.a;
                Ok(rrr_dyad(
                    a,
                    PointMotion::fixed(Point2::new(0.4, 0.05)),
                    0.35,
                    0.3,
                    Branch::Plus,
                )?
                .link3
                .angle_motion())
            },
            phi1,
        )
    } else {
        transfer_functions(
            |m| {
                let a = crank(Point2::origin(), 0.1, m)?.a;
                Ok(rrp_dyad(a, Guide::fixed(Point2::origin(), 0.0), 0.3, Branch::Plus)?.slide)
            },
            phi1,
        )
    }
}

/// The exact values at N + 1 nodes, the angle unwrapped so that it is continuous.
///
/// # Errors
/// As [`exact`].
pub fn table(mechanism: &str, n: usize) -> tmm::Result<(f64, Vec<Motion>)> {
    let h = std::f64::consts::TAU / n as f64;
    let mut out: Vec<Motion> = Vec::with_capacity(n + 1);
    for i in 0..=n {
        let mut m = exact(mechanism, h * i as f64)?;
        if let (Some(prev), true) = (out.last(), mechanism == MECHANISMS[0]) {
            let d = (m.value - prev.value + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            m.value = prev.value + d;
        }
        out.push(m);
    }
    Ok((h, out))
}

fn amax(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0, |m, x| m.max(x.abs()))
}

/// The four errors of [`QUANTITIES`] for one mechanism at N positions per cycle.
///
/// # Errors
/// As [`exact`], or a numerics error.
pub fn errors(mechanism: &str, n: usize) -> tmm::Result<[f64; 4]> {
    let (h, t) = table(mechanism, n)?;
    let value: Vec<f64> = t.iter().map(|m| m.value).collect();
    let rate: Vec<f64> = t.iter().map(|m| m.rate).collect();
    let accel: Vec<f64> = t.iter().map(|m| m.accel).collect();
    let d = differentiate(&value, h)?;
    let rate_scale = amax(rate.iter().copied());
    let inside = amax((1..n).map(|i| d[i] - rate[i])) / rate_scale;
    let ends = amax([0, n].into_iter().map(|i| d[i] - rate[i])) / rate_scale;
    let integral = integrate_trapezoid(&rate, h)?;
    let (lo, hi) = value
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let trapezoid = amax((0..=n).map(|i| integral[i] - (value[i] - value[0]))) / (hi - lo);
    // One period: the last node is the first again.
    let d2 = differentiate_periodic(&differentiate_periodic(&value[..n], h)?, h)?;
    let twice = amax((0..n).map(|i| d2[i] - accel[i])) / amax(accel.iter().copied());
    Ok([inside, ends, trapezoid, twice])
}

/// The numbers of positions per cycle: 12 (the seed's plans) doubling to 1536.
pub fn positions() -> Vec<usize> {
    (0..8).map(|k| 12usize << k).collect()
}

/// One row: mechanism, quantity, positions per cycle, error.
pub type Row = (&'static str, &'static str, usize, f64);

/// Every mechanism, quantity and number of positions.
///
/// # Errors
/// As [`errors`].
pub fn sweep() -> tmm::Result<Vec<Row>> {
    let mut rows = Vec::new();
    for mech in MECHANISMS {
        for n in positions() {
            let e = errors(mech, n)?;
            for (q, err) in QUANTITIES.into_iter().zip(e) {
                rows.push((mech, q, n, err));
            }
        }
    }
    Ok(rows)
}

/// The rows as CSV.
pub fn to_csv(rows: &[Row]) -> String {
    let mut s = String::from("mechanism,quantity,positions,error\n");
    for (m, q, n, e) in rows {
        s += &format!("{m},{q},{n},{e:e}\n");
    }
    s
}
