//! Kinetostatics: the error of the closed-form dyad solvers and of the general LU solve of
//! the same group as the group approaches its singular configuration, and the time per call.
//!
//! Each group is built with its vanishing measure set to δ = 1, 10^-½, …, 10⁻⁸ (the sine for
//! RRR, the cosine for RRP, l_EA for RPR) in a random pose with random loads (seeded). The
//! reference is the group's Newton–Euler system for the same f64 inputs, assembled and solved
//! in double-double arithmetic ([`super::dd`]): its error, about condition × 10⁻³², is far below
//! what either f64 solver can reach. The error is the largest component error of the three
//! reactions, relative to the scale of the problem (the largest load or reaction).

use std::hint::black_box;
use std::time::Instant;

use nalgebra::{Point2, Vector2};
use tmm::kinetostatics::{RprDyad, RrpDyad, RrrDyad};
use tmm::Load;

use super::dd::{solve, Dd};
use super::general_solve;
use super::rng::Rng;

/// One solver on one group at one distance from the singularity.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// "RRR", "RRP" or "RPR".
    pub group: &'static str,
    /// "closed form" or "general LU".
    pub solver: &'static str,
    /// The vanishing measure the groups were built with.
    pub delta: f64,
    /// The largest `Conditioning::condition` the closed form reported over the samples.
    pub condition: f64,
    /// The largest error over the samples, relative to the scale.
    pub error: f64,
    /// The largest error / condition ratio over the samples.
    pub error_per_condition: f64,
    /// Mean wall time per call, ns (0 when timing is off).
    pub ns_per_call: f64,
}

/// The three groups, in the order the charts show them.
pub const GROUPS: [&str; 3] = ["RRR", "RRP", "RPR"];
/// The two solvers.
pub const SOLVERS: [&str; 2] = ["closed form", "general LU"];

type V = [Dd; 2];

fn dv(v: Vector2<f64>) -> V {
    [Dd::from(v.x), Dd::from(v.y)]
}

fn dsub(a: Point2<f64>, b: Point2<f64>) -> V {
    // The difference of two f64 is exact in double-double.
    [Dd::from(a.x) - Dd::from(b.x), Dd::from(a.y) - Dd::from(b.y)]
}

fn dcross(a: V, b: V) -> Dd {
    a[0] * b[1] - a[1] * b[0]
}

/// M + (P − pole) × F, in double-double.
fn moment(l: &Load, pole: Point2<f64>) -> Dd {
    Dd::from(l.moment) + dcross(dsub(l.point, pole), dv(l.force))
}

/// Reactions of one group: three vectors compared component by component.
type Reactions = [Vector2<f64>; 3];

fn to_vec(x: Dd, y: Dd) -> Vector2<f64> {
    Vector2::new(x.to_f64(), y.to_f64())
}

/// RRR reference: unknowns [R12, R43, R23]; link 2 and link 3 balances, moments about B.
fn rrr_reference(d: &RrrDyad) -> Option<Reactions> {
    let z = Dd::default();
    let one = Dd::from(1.0);
    let (ab, cb) = (dsub(d.a, d.b), dsub(d.c, d.b));
    let (f2, f3) = (dv(d.load2.force), dv(d.load3.force));
    let m = [
        [one, z, z, z, -one, z],
        [z, one, z, z, z, -one],
        [-ab[1], ab[0], z, z, z, z],
        [z, z, one, z, one, z],
        [z, z, z, one, z, one],
        [z, z, -cb[1], cb[0], z, z],
    ];
    let b = [
        -f2[0],
        -f2[1],
        -moment(&d.load2, d.b),
        -f3[0],
        -f3[1],
        -moment(&d.load3, d.b),
    ];
    let x = solve(m, b)?;
    Some([to_vec(x[0], x[1]), to_vec(x[2], x[3]), to_vec(x[4], x[5])])
}

/// RRP reference: unknowns [R12, N, K, R23] with R43 = N·ν (ν ⟂ guide, not normalised, so
/// exact) and K the guide's couple on the slider.
fn rrp_reference(d: &RrpDyad) -> Option<Reactions> {
    let z = Dd::default();
    let one = Dd::from(1.0);
    let ab = dsub(d.a, d.b);
    let nu = [-Dd::from(d.guide.y), Dd::from(d.guide.x)];
    let (f2, f3) = (dv(d.load2.force), dv(d.load3.force));
    let m = [
        [one, z, z, z, -one, z],
        [z, one, z, z, z, -one],
        [-ab[1], ab[0], z, z, z, z],
        [z, z, nu[0], z, one, z],
        [z, z, nu[1], z, z, one],
        [z, z, z, one, z, z],
    ];
    let b = [
        -f2[0],
        -f2[1],
        -moment(&d.load2, d.b),
        -f3[0],
        -f3[1],
        -moment(&d.load3, d.b),
    ];
    let x = solve(m, b)?;
    Some([
        to_vec(x[0], x[1]),
        to_vec(x[2] * nu[0], x[2] * nu[1]),
        to_vec(x[4], x[5]),
    ])
}

/// RPR reference: unknowns [R12, N, K, R43] with R32 = N·n (n ⟂ axis, not normalised) acting
/// at A together with its couple K; rod moments about A, cylinder moments about E.
fn rpr_reference(d: &RprDyad) -> Option<Reactions> {
    let z = Dd::default();
    let one = Dd::from(1.0);
    let ae = dsub(d.a, d.e);
    let n = [-Dd::from(d.axis.y), Dd::from(d.axis.x)];
    let (f2, f3) = (dv(d.load2.force), dv(d.load3.force));
    let m = [
        [one, z, n[0], z, z, z],
        [z, one, n[1], z, z, z],
        [z, z, z, one, z, z],
        [z, z, -n[0], z, one, z],
        [z, z, -n[1], z, z, one],
        [z, z, -dcross(ae, n), -one, z, z],
    ];
    let b = [
        -f2[0],
        -f2[1],
        -moment(&d.load2, d.a),
        -f3[0],
        -f3[1],
        -moment(&d.load3, d.e),
    ];
    let x = solve(m, b)?;
    Some([
        to_vec(x[0], x[1]),
        to_vec(x[2] * n[0], x[2] * n[1]),
        to_vec(x[4], x[5]),
    ])
}

fn dir(phi: f64) -> Vector2<f64> {
    Vector2::new(phi.cos(), phi.sin())
}

fn random_load(rng: &mut Rng) -> Load {
    Load::new(
        Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
        Vector2::new(rng.range(-500.0, 500.0), rng.range(-500.0, 500.0)),
        rng.range(-50.0, 50.0),
    )
}

/// An RRR dyad with sin(φ3 − φ2) = δ in a random pose.
pub fn rrr_near(delta: f64, rng: &mut Rng) -> RrrDyad {
    let b = Point2::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5));
    let phi2 = rng.range(0.0, std::f64::consts::TAU);
    let phi3 = phi2 + std::f64::consts::PI - delta.asin();
    RrrDyad {
        a: b - rng.range(0.5, 1.5) * dir(phi2),
        b,
        c: b - rng.range(0.5, 1.5) * dir(phi3),
        load2: random_load(rng),
        load3: random_load(rng),
    }
}

/// An RRP dyad with cos(φ2 − φ4) = δ in a random pose.
pub fn rrp_near(delta: f64, rng: &mut Rng) -> RrpDyad {
    let b = Point2::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5));
    let phi4 = rng.range(0.0, std::f64::consts::TAU);
    let phi2 = phi4 + std::f64::consts::FRAC_PI_2 - delta.asin();
    RrpDyad {
        a: b - rng.range(0.5, 1.5) * dir(phi2),
        b,
        guide: dir(phi4),
        load2: random_load(rng),
        load3: random_load(rng),
    }
}

/// An RPR dyad with l_EA = δ (metres) in a random pose.
pub fn rpr_near(delta: f64, rng: &mut Rng) -> RprDyad {
    let e = Point2::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5));
    let phi = rng.range(0.0, std::f64::consts::TAU);
    let u = dir(phi);
    let n = Vector2::new(-u.y, u.x);
    RprDyad {
        a: e - delta * u + rng.range(0.3, 1.0) * n,
        e,
        axis: u,
        load2: random_load(rng),
        load3: random_load(rng),
    }
}

fn error(r: &Reactions, reference: &Reactions, loads: [&Load; 2]) -> f64 {
    let scale = reference
        .iter()
        .chain(loads.iter().map(|l| &l.force))
        .map(|v| v.amax())
        .fold(0.0, f64::max);
    r.iter()
        .zip(reference)
        .map(|(a, b)| (a - b).amax())
        .fold(0.0, f64::max)
        / scale
}

/// The distances from the singularity: δ = 10^(−k/2), k = 0…16.
pub fn deltas() -> Vec<f64> {
    (0..=16).map(|k| 10f64.powf(-f64::from(k) / 2.0)).collect()
}

/// Mean wall time per call of `f` over `cases`, repeated until about 2 ms have passed.
fn time_per_call<T, R>(cases: &[T], mut f: impl FnMut(&T) -> R) -> f64 {
    let mut calls = 0usize;
    let start = Instant::now();
    loop {
        for c in cases {
            black_box(f(black_box(c)));
        }
        calls += cases.len();
        let el = start.elapsed().as_secs_f64();
        if el > 2e-3 {
            return el / calls as f64 * 1e9;
        }
    }
}

/// One group at one δ: (reactions of the closed form, of the LU solve, the reference, the
/// condition, the two loads) for each sample.
struct Case {
    closed: Reactions,
    lu: Reactions,
    reference: Reactions,
    condition: f64,
    loads: [Load; 2],
}

fn cases(group: &str, delta: f64, samples: usize, rng: &mut Rng) -> tmm::Result<Vec<Case>> {
    let mut out = Vec::with_capacity(samples);
    for _ in 0..samples {
        let case = match group {
            "RRR" => {
                let d = rrr_near(delta, rng);
                let r = d.solve()?;
                Case {
                    closed: [r.r12, r.r43, r.r23],
                    lu: general_solve::rrr(d.a, d.b, d.c, &d.load2, &d.load3),
                    reference: rrr_reference(&d).expect("not exactly singular"),
                    condition: r.conditioning.condition,
                    loads: [d.load2, d.load3],
                }
            }
            "RRP" => {
                let d = rrp_near(delta, rng);
                let r = d.solve()?;
                Case {
                    closed: [r.r12, r.r43, r.r23],
                    lu: general_solve::rrp(d.a, d.b, d.guide, &d.load2, &d.load3).0,
                    reference: rrp_reference(&d).expect("not exactly singular"),
                    condition: r.conditioning.condition,
                    loads: [d.load2, d.load3],
                }
            }
            _ => {
                let d = rpr_near(delta, rng);
                let r = d.solve()?;
                Case {
                    closed: [r.r12, r.r32, r.r43],
                    lu: general_solve::rpr(d.a, d.e, d.axis, &d.load2, &d.load3).0,
                    reference: rpr_reference(&d).expect("not exactly singular"),
                    condition: r.conditioning.condition,
                    loads: [d.load2, d.load3],
                }
            }
        };
        out.push(case);
    }
    Ok(out)
}

fn timing(group: &str, delta: f64, samples: usize, seed: u64) -> [f64; 2] {
    let mut rng = Rng::new(seed);
    match group {
        "RRR" => {
            let ds: Vec<_> = (0..samples).map(|_| rrr_near(delta, &mut rng)).collect();
            [
                time_per_call(&ds, RrrDyad::solve),
                time_per_call(&ds, |d| {
                    general_solve::rrr(d.a, d.b, d.c, &d.load2, &d.load3)
                }),
            ]
        }
        "RRP" => {
            let ds: Vec<_> = (0..samples).map(|_| rrp_near(delta, &mut rng)).collect();
            [
                time_per_call(&ds, RrpDyad::solve),
                time_per_call(&ds, |d| {
                    general_solve::rrp(d.a, d.b, d.guide, &d.load2, &d.load3)
                }),
            ]
        }
        _ => {
            let ds: Vec<_> = (0..samples).map(|_| rpr_near(delta, &mut rng)).collect();
            [
                time_per_call(&ds, RprDyad::solve),
                time_per_call(&ds, |d| {
                    general_solve::rpr(d.a, d.e, d.axis, &d.load2, &d.load3)
                }),
            ]
        }
    }
}

/// The whole sweep: every group, every δ of [`deltas`], `samples` random groups each;
/// timed when `timed`.
///
/// # Errors
/// A closed-form solver's error (none is expected: the smallest δ is far from 8ε).
pub fn sweep(samples: usize, timed: bool) -> tmm::Result<Vec<Row>> {
    let mut rows = Vec::new();
    for (g, group) in GROUPS.into_iter().enumerate() {
        for (k, delta) in deltas().into_iter().enumerate() {
            let seed = 1000 * g as u64 + k as u64 + 1;
            let cs = cases(group, delta, samples, &mut Rng::new(seed))?;
            let times = if timed {
                timing(group, delta, samples, seed)
            } else {
                [0.0; 2]
            };
            let condition = cs.iter().map(|c| c.condition).fold(1.0, f64::max);
            for (s, solver) in SOLVERS.into_iter().enumerate() {
                let errs: Vec<(f64, f64)> = cs
                    .iter()
                    .map(|c| {
                        let r = if s == 0 { &c.closed } else { &c.lu };
                        let e = error(r, &c.reference, [&c.loads[0], &c.loads[1]]);
                        (e, e / c.condition)
                    })
                    .collect();
                rows.push(Row {
                    group,
                    solver,
                    delta,
                    condition,
                    error: errs.iter().map(|e| e.0).fold(0.0, f64::max),
                    error_per_condition: errs.iter().map(|e| e.1).fold(0.0, f64::max),
                    ns_per_call: times[s],
                });
            }
        }
    }
    Ok(rows)
}

/// The rows as CSV.
pub fn to_csv(rows: &[Row]) -> String {
    let mut s =
        String::from("group,solver,delta,condition,error,error_per_condition,ns_per_call\n");
    for r in rows {
        s += &format!(
            "{},{},{:e},{:e},{:e},{:e},{:.1}\n",
            r.group, r.solver, r.delta, r.condition, r.error, r.error_per_condition, r.ns_per_call
        );
    }
    s
}
