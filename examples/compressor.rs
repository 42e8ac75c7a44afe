//! Seed 001's two-cylinder air compressor by closed vector contours (§ "analytical methods",
//! eqs. 2.6–2.14): one crank O A (and its second throw O C = −O A), two slider-crank contours
//! O A B O and O C D O, both cylinders along the y axis above O.
//!
//! The seed measures angles clockwise from +y, in the sense the crank turns. The crate
//! measures them counter-clockwise from +x. This example converts at its edge, visibly:
//! θ = π/2 − ψ for angles, ω_crate = −ω_seed and ε_crate = −ε_seed for rates; lengths and the
//! x, y axes are the same. It then checks the crate against the seed's closed forms (2.10)–
//! (2.14) with the errata K1 (the sign of l1·ω1²·cos φ1 in 2.14) and K2 (the ε1 terms), and
//! the centre of mass S2 with K4.
//!
//! Run with `cargo run --example compressor`.

use nalgebra::{Point2, Vector2};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use tmm::angle::normalize;
use tmm::kinematics::{
    crank, extreme_positions, rrp_dyad, transfer_functions, Branch, Guide, Motion, Rotation,
    RrpState, Strokes,
};

/// Crank, connecting rods (m), the rods' centres of mass from A and C (m).
const L1: f64 = 0.06;
const L2: f64 = 0.24;
const L4: f64 = 0.24;
const L_AS2: f64 = 0.08;

/// Seed angle (clockwise from +y) → crate angle (CCW from +x).
fn to_crate(psi: f64) -> f64 {
    FRAC_PI_2 - psi
}

/// Crate angle → seed angle in (−π, π].
fn to_seed(theta: f64) -> f64 {
    normalize(FRAC_PI_2 - theta + PI) - PI
}

/// The seed's closed forms for one contour with the crank throw at seed angle `psi`:
/// (φ2, l3, ω2, v3, ε2, a3), all in the seed's convention (K1, K2 applied).
fn seed_contour(psi: f64, l: f64, w1: f64, e1: f64) -> [f64; 6] {
    let phi2 = (-L1 * psi.sin() / l).asin(); // (2.10), branch cos φ2 > 0 (K3)
    let l3 = L1 * psi.cos() + l * phi2.cos();
    let w2 = -L1 * w1 * psi.cos() / (l * phi2.cos()); // (2.11)
    let v3 = -L1 * w1 * psi.sin() - l * w2 * phi2.sin(); // (2.12)
    let e2 = (L1 * w1 * w1 * psi.sin() - L1 * e1 * psi.cos() + l * w2 * w2 * phi2.sin())
        / (l * phi2.cos()); // (2.13) + K2
    let a3 = -L1 * w1 * w1 * psi.cos() // K1: the seed prints +
        - L1 * e1 * psi.sin() // K2
        - l * w2 * w2 * phi2.cos()
        - l * e2 * phi2.sin(); // (2.14)
    [phi2, l3, w2, v3, e2, a3]
}

/// The crate's contour, in the seed's convention.
fn crate_contour(d: &RrpState) -> [f64; 6] {
    [
        to_seed(d.link2.angle),
        d.slide.value,
        -d.link2.omega,
        d.slide.rate,
        -d.link2.epsilon,
        d.slide.accel,
    ]
}

/// Both contours at the seed's crank angle ψ1 turning clockwise at ω1 with ε1.
fn compressor(psi1: f64, w1: f64, e1: f64) -> tmm::Result<(RrpState, RrpState)> {
    let o = Point2::origin();
    let guide = Guide::fixed(o, FRAC_PI_2); // both cylinders along +y
    let a = crank(o, L1, Motion::new(to_crate(psi1), -w1, -e1))?.a;
    let c = crank(o, L1, Motion::new(to_crate(psi1 + PI), -w1, -e1))?.a;
    // Branch::Plus: each piston pin ahead of its crank pin along +y (the seed's arcsin).
    Ok((
        rrp_dyad(a, guide, L2, Branch::Plus)?,
        rrp_dyad(c, guide, L4, Branch::Plus)?,
    ))
}

fn run_example() -> tmm::Result<()> {
    let n1 = 960.0; // rpm
    let w1 = n1 * TAU / 60.0;
    let e1 = 0.0; // the seed's ω1 = const; the test suite also runs ε1 ≠ 0
    println!("Two-cylinder compressor: l1 = {L1} m, l2 = l4 = {L2} m, n1 = {n1} rpm (clockwise)");
    println!(
        "{:>6} {:>9} {:>9} {:>10} {:>9} {:>11} {:>11} {:>9} {:>11} {:>10}",
        "psi1°",
        "phi2°",
        "l3 mm",
        "omega2",
        "v3 m/s",
        "eps2",
        "a3 m/s²",
        "l5 mm",
        "a5 m/s²",
        "K1 error"
    );
    let mut worst = 0.0f64;
    for k in 0..12 {
        let psi1 = k as f64 * TAU / 12.0;
        let (d1, d2) = compressor(psi1, w1, e1)?;
        let got = [crate_contour(&d1), crate_contour(&d2)];
        let want = [
            seed_contour(psi1, L2, w1, e1),
            seed_contour(psi1 + PI, L4, w1, e1),
        ];
        let scales = [1.0, L1, w1, L1 * w1, w1 * w1, L1 * w1 * w1];
        for (g, w) in got.iter().zip(&want) {
            for i in 0..6 {
                worst = worst.max((g[i] - w[i]).abs() / scales[i]);
            }
        }
        // The printed (2.14) has +l1·ω1²·cos φ1: off by 2·l1·ω1²·cos φ1.
        let printed_a3 = want[0][5] + 2.0 * L1 * w1 * w1 * psi1.cos();
        let g = got[0];
        println!(
            "{:>6.0} {:>9.4} {:>9.3} {:>10.3} {:>9.4} {:>11.1} {:>11.2} {:>9.3} {:>11.2} {:>10.1}",
            psi1.to_degrees(),
            g[0].to_degrees(),
            g[1] * 1e3,
            g[2],
            g[3],
            g[4],
            g[5],
            got[1][1] * 1e3,
            got[1][5],
            printed_a3 - g[5]
        );
        // The centre of mass S2 (K4): coordinates, velocity and acceleration.
        let s2 = d1.link2.point_at(L_AS2, 0.0);
        let phi2 = want[0][0];
        let x = L1 * psi1.sin() + L_AS2 * phi2.sin();
        let y = L1 * psi1.cos() + L_AS2 * phi2.cos();
        assert!((s2.p - Point2::new(x, y)).norm() <= 1e-15);
        let vx = L1 * w1 * psi1.cos() + L_AS2 * want[0][2] * phi2.cos();
        let vy = -L1 * w1 * psi1.sin() - L_AS2 * want[0][2] * phi2.sin();
        assert!((s2.v - Vector2::new(vx, vy)).norm() <= 1e-12 * L1 * w1);
    }
    println!("largest relative difference from (2.10)-(2.14) with K1, K2: {worst:.1e}");
    assert!(worst <= 1e-12);

    // Extreme positions of piston 3 by root-finding on s3' (the seed's dead centres), and
    // the strokes for the clockwise crank (in the crate's angle, clockwise = decreasing).
    let s3 = |theta: f64| {
        transfer_functions(
            |input| {
                let a = crank(Point2::origin(), L1, input)?.a;
                Ok(rrp_dyad(
                    a,
                    Guide::fixed(Point2::origin(), FRAC_PI_2),
                    L2,
                    Branch::Plus,
                )?
                .slide)
            },
            theta,
        )
    };
    let ext = extreme_positions(s3, 360)?;
    for e in &ext {
        println!(
            "{:?} of piston 3 at psi1 = {:.12}°, l3 = {:.6} mm, s3' = {:.1e} m",
            e.kind,
            normalize(to_seed(e.input)).to_degrees(),
            e.output.value * 1e3,
            e.output.rate
        );
    }
    let strokes = Strokes::new(&ext, Rotation::Cw)?;
    println!(
        "working-stroke angle {:.6}°, time ratio {:.6} (a central slider-crank: 180°, 1)",
        strokes.working_angle.to_degrees(),
        strokes.time_ratio
    );
    Ok(())
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
