//! Worked kinetostatics problems in the seeds' notation (programs SR1, SR2, SR3, SRWL1, SRWL2),
//! printed as the seeds tabulate them (magnitudes and direction angles in degrees), and one RRR
//! dyad driven towards its dead point to show the reported conditioning and the error at the
//! end.
//!
//! Run: `cargo run --example dyads`

use nalgebra::Vector2;
use tmm::angle::Polar;
use tmm::kinetostatics::{CouplingSeed, GearSeed, RprSeed, RrpSeed, RrrSeed};

fn show(name: &str, v: Vector2<f64>) {
    let p = Polar::of(v);
    println!(
        "  {name:<4} = {:>10.3} N  at {:>7.2}°",
        p.magnitude,
        p.angle.to_degrees()
    );
}

fn run_example() -> Result<(), tmm::Error> {
    let deg = f64::to_radians;

    println!("SR1: RRR dyad, l_BA = 0.30 m, l_BC = 0.40 m, phi2 = 30°, phi3 = 120°");
    let sr1 = RrrSeed {
        l_ba: 0.30,
        l_bs2: 0.15,
        l_bc: 0.40,
        l_bs3: 0.20,
        phi2: deg(30.0),
        phi3: deg(120.0),
        f2: 200.0,
        gamma2: deg(270.0),
        f3: 150.0,
        gamma3: deg(200.0),
        m2: 12.0,
        m3: -8.0,
    };
    let r = sr1.solve()?;
    println!(
        "  R12n = {:.3} N, R12t = {:.3} N, R43n = {:.3} N, R43t = {:.3} N",
        r.r12_n, r.r12_t, r.r43_n, r.r43_t
    );
    show("R12", r.r12);
    show("R43", r.r43);
    show("R23", r.r23);
    println!("  sin(phi3 - phi2) = {:.3}", r.conditioning.measure);

    println!("\nSR2: RRP dyad, l_BA = 0.25 m, phi2 = 160°, guide phi4 = 0°");
    let sr2 = RrpSeed {
        l_ba: 0.25,
        l_bs2: 0.10,
        phi2: deg(160.0),
        phi4: 0.0,
        f2: 40.0,
        gamma2: deg(250.0),
        f3: 1200.0,
        gamma3: deg(180.0),
        m2: 1.5,
        m3: 0.0,
    };
    let r = sr2.solve()?;
    show("R12", r.r12);
    show("R43", r.r43);
    show("R23", r.r23);
    println!(
        "  h43 = {:?} m (the slider's load passes through B)",
        r.offset
    );

    println!(
        "\nSR3: RPR dyad (rocking cylinder), l_AB = 0.5, l_EC = 0.45, l_BC = 0.2 m, phi2 = 75°"
    );
    let sr3 = RprSeed {
        l_ab: 0.50,
        l_ec: 0.45,
        l_bc: 0.20,
        l_as2: 0.20,
        l_es3: 0.15,
        phi2: deg(75.0),
        f2: 80.0,
        gamma2: deg(270.0),
        f3: 60.0,
        gamma3: deg(270.0),
        m2: 0.5,
        m3: -0.8,
    };
    let r = sr3.solve()?;
    show("R12", r.r12);
    show("R32", r.r32);
    show("R43", r.r43);
    match r.arm {
        Some(h) => println!("  h32 = {h:.4} m from A along the axis"),
        None => println!(
            "  R32 = 0: the sliding pair carries a couple of {:.3} N·m",
            r.couple
        ),
    }

    println!("\nSRWL2: input link through a coupling, l_O1A = 0.1 m, phi1 = 60°");
    let srwl2 = CouplingSeed {
        l_o1a: 0.10,
        l_o1s1: 0.05,
        phi1: deg(60.0),
        f1: 20.0,
        gamma1: deg(270.0),
        r21: 850.0,
        gamma21: deg(215.0),
        m1: 0.0,
    };
    let c = srwl2.solve()?;
    println!("  M_b  = {:>10.3} N·m", c.balancing_moment);
    show("R01", c.r01);

    println!("\nSRWL1: the same link through a gear, r_w = 0.15 m, alpha_w = 20°");
    let srwl1 = GearSeed {
        l_o1a: 0.10,
        l_o1s1: 0.05,
        l_o1p: 0.15,
        alpha_w: deg(20.0),
        phi1: deg(60.0),
        f1: 20.0,
        gamma1: deg(270.0),
        r21: 850.0,
        gamma21: deg(215.0),
        m1: 0.0,
    };
    let g = srwl1.solve()?;
    show("F_b", g.force);
    println!("  flank: {:?}", g.flank);
    show("R01", g.r01);

    println!("\nTowards a dead point: SR1 with phi3 -> phi2 + 180°");
    println!(
        "  {:>12}  {:>12}  {:>14}",
        "phi3 - phi2", "condition", "|R12| (N)"
    );
    for k in 1..=16 {
        let gap = 10f64.powi(-k);
        let dyad = RrrSeed {
            phi3: sr1.phi2 + std::f64::consts::PI - gap,
            ..sr1
        };
        match dyad.solve() {
            Ok(r) => println!(
                "  180° - 1e-{k:<2}  {:>12.3e}  {:>14.6e}",
                r.conditioning.condition,
                r.r12.norm()
            ),
            Err(e) => println!("  180° - 1e-{k:<2}  error: {e}"),
        }
    }
    Ok(())
}

/// Runs the example; an error is printed as its sentence (`Display`), never in `Debug` form.
fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
