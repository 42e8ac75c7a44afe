//! Both kinds of triad called directly (not through the linkage engine, which scales to a
//! unit frame) at any size: seeded random groups with every length and coordinate multiplied
//! by 1e-100, 1e-6, 1e6 and 1e100 (and by the powers of two nearest them) have as many
//! modes as at scale 1, their joints scaled to 1e-12 of the size (at the decimal sizes, within
//! what one rounding of the data moves each mode), and their rates (the known
//! points' velocities and accelerations scaled too, by a power of two) scaled alike to
//! 1e-12, the angular rates unchanged.

use crate::common::fd::{cases, Rng};
use crate::triad_slider::{random_case, size, Case};
use nalgebra::{Matrix3, Point2, Vector2, Vector3};
use std::f64::consts::TAU;
use tmm::kinematics::{
    slider_triad_modes, slider_triad_rates, triad_modes, triad_rates, Guide, Motion, PointMotion,
    SliderTriadDims, SlidingPair, TriadDims, TriadPose, TriadState,
};
use tmm::Error;

/// Powers of two near 1e∓100 and 1e∓6 (the data scaled exactly: poses and rates are compared
/// there, to 1e-12), and the decimal sizes themselves (their data carry one rounding, which
/// each mode bears through its conditioning: [`rounding_allowance`]).
const SCALES: [f64; 8] = [
    1.0 / (1u128 << 110) as f64 / (1u128 << 111) as f64 / (1u128 << 111) as f64,
    1.0 / (1u64 << 20) as f64,
    (1u64 << 20) as f64,
    (1u128 << 110) as f64 * (1u128 << 111) as f64 * (1u128 << 111) as f64,
    1e-100,
    1e-6,
    1e6,
    1e100,
];

/// Whether the data are scaled exactly (f a power of two).
fn exact(f: f64) -> bool {
    f.log2().fract() == 0.0
}

fn scaled_point(p: PointMotion, f: f64) -> PointMotion {
    PointMotion::new(Point2::from(p.p.coords * f), p.v * f, p.a * f)
}

/// The largest difference of two mode lists (the second scaled back by 1/f), relative to
/// `size`; `None` when the counts differ.
fn modes_off(one: &[TriadPose], other: &[TriadPose], f: f64, size: f64) -> Option<f64> {
    (one.len() == other.len()).then(|| {
        one.iter()
            .map(|m| nearest_off(m, other, f))
            .fold(0.0, f64::max)
            / size
    })
}

/// The distance of a mode's joints from the nearest mode of `other` scaled back by 1/f, m.
fn nearest_off(m: &TriadPose, other: &[TriadPose], f: f64) -> f64 {
    other
        .iter()
        .map(|q| {
            (0..3)
                .map(|i| (m.b[i] - Point2::from(q.b[i].coords / f)).norm())
                .fold(0.0, f64::max)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The largest difference of two states' rates (the second's linear rates scaled back by
/// 1/f), relative to the first's largest linear rate (and 1 for the angular ones).
fn rates_off(one: &TriadState, other: &TriadState, f: f64) -> f64 {
    let big_v = one.b.iter().map(|m| m.v.norm()).fold(1e-300, f64::max);
    let big_a = one.b.iter().map(|m| m.a.norm()).fold(1e-300, f64::max);
    let mut off = 0.0f64;
    for i in 0..3 {
        off = off.max((one.b[i].v - other.b[i].v / f).norm() / big_v);
        off = off.max((one.b[i].a - other.b[i].a / f).norm() / big_a);
    }
    let links = [one.ternary, one.binary[0], one.binary[1], one.binary[2]];
    let others = [
        other.ternary,
        other.binary[0],
        other.binary[1],
        other.binary[2],
    ];
    let big_w = links.iter().map(|l| l.omega.abs()).fold(1e-300, f64::max);
    let big_e = links.iter().map(|l| l.epsilon.abs()).fold(1e-300, f64::max);
    for (l, o) in links.iter().zip(&others) {
        off = off.max((l.omega - o.omega).abs() / big_w);
        off = off.max((l.epsilon - o.epsilon).abs() / big_e);
    }
    off
}

/// How far a mode's joints move when every datum of the group is rounded once (a decimal
/// scale): each closure |B_i − A_i| = l_i is disturbed by at most
/// δ_i = ε·(l_i + |A_i| + |β_i|) (the length, the known joint's coordinates and the joint's
/// coordinates in the ternary link each off by ε/2 of themselves, √2 for two coordinates),
/// which moves (v_B1, ω_T) by K⁻¹·δ to first order (K the velocity system: rows u_i and
/// r_i × u_i, the closures' derivatives along the legs) and each joint B_i by |Δv| + |Δω|·|r_i|.
/// Twice that (the second-order term and the two solves' own rounding are far smaller away
/// from a fold; near one K⁻¹ grows and so does the allowance, as the data's meaning does).
fn rounding_allowance(m: &TriadPose, a: [Point2<f64>; 3], dims: &TriadDims) -> f64 {
    let beta = dims.local_joints();
    let r = [0, 1, 2].map(|i| m.b[i] - m.b[0]);
    let u = [0, 1, 2].map(|i| (m.b[i] - a[i]) / (m.b[i] - a[i]).norm());
    let k = Matrix3::from_fn(|i, j| match j {
        0 => u[i].x,
        1 => u[i].y,
        _ => r[i].x * u[i].y - r[i].y * u[i].x,
    });
    let Some(k_inv) = k.try_inverse() else {
        return f64::INFINITY;
    };
    let delta =
        Vector3::from_fn(|i, _| f64::EPSILON * (dims.l[i] + a[i].coords.norm() + beta[i].norm()));
    let step = k_inv.abs() * delta;
    let reach = r.iter().map(|v| v.norm()).fold(0.0, f64::max);
    2.0 * (step.x.hypot(step.y) + step.z * reach)
}

fn rotate(v: Vector2<f64>, t: f64) -> Vector2<f64> {
    let (s, c) = t.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

#[test]
fn triads_called_directly_are_scale_free() {
    let n = (cases("TMM_TRIAD_CASES", 500) / 5).max(50);
    let mut rng = Rng(0x5CA1_E028);
    let (mut worst_pose, mut worst_rate, mut checked) = (0.0f64, 0.0f64, 0);
    for case in 0..n {
        let dims = TriadDims::new(
            [
                rng.range(0.3, 2.0),
                rng.range(0.3, 2.0),
                rng.range(0.3, 2.0),
            ],
            rng.range(0.3, 1.5),
            rng.range(-0.5, 1.5),
            rng.range(-1.2, 1.2),
        );
        let o = Point2::from(rng.vector(1.0));
        let theta = rng.range(0.0, TAU);
        let beta = dims.local_joints();
        let b = beta.map(|q| o + rotate(q, theta));
        let a = [0, 1, 2].map(|k| b[k] - dims.l[k] * rotate(Vector2::x(), rng.range(0.0, TAU)));
        let motion = a.map(|p| PointMotion::new(p, rng.vector(1.0), rng.vector(1.0)));
        let size = dims.l.iter().fold(2.0f64, |m, &l| m.max(l));
        let modes = triad_modes(a, &dims).unwrap_or_else(|e| panic!("case {case}: {e}"));
        for f in SCALES {
            let sd = TriadDims::new(
                dims.l.map(|l| l * f),
                dims.l_b1b2 * f,
                dims.b3_along * f,
                dims.b3_across * f,
            );
            let sa = a.map(|p| Point2::from(p.coords * f));
            let other =
                triad_modes(sa, &sd).unwrap_or_else(|e| panic!("case {case} at {f:e}: {e}"));
            let off = modes_off(modes.as_slice(), other.as_slice(), f, size).unwrap_or_else(|| {
                panic!(
                    "case {case} at {f:e}: {} modes, {} at scale 1",
                    other.len(),
                    modes.len()
                )
            });
            if exact(f) {
                assert!(
                    off <= 1e-12,
                    "case {case} at {f:e}: joints off by {off:e} of the size"
                );
            } else {
                // Each mode against its own data-rounding allowance (the scaled data carry
                // one rounding, which the mode bears through its conditioning).
                for m in modes.as_slice() {
                    let off_m = nearest_off(m, other.as_slice(), f);
                    let allowed = 1e-12 * size + rounding_allowance(m, a, &dims);
                    assert!(
                        off_m <= allowed,
                        "case {case} at {f:e}: a mode's joints off by {off_m:e} m, allowed \
                         {allowed:e} (det {:e})",
                        m.det
                    );
                }
            }
            worst_pose = worst_pose.max(off);
            for (m, q) in modes.as_slice().iter().zip(other.as_slice()) {
                if m.det.abs() < 1e-2 || !exact(f) {
                    continue;
                }
                let r1 = triad_rates(motion, &dims, m).unwrap();
                let rf = triad_rates(motion.map(|p| scaled_point(p, f)), &sd, q)
                    .unwrap_or_else(|e| panic!("case {case} at {f:e}: rates {e}"));
                let off = rates_off(&r1, &rf, f);
                assert!(off <= 1e-12, "case {case} at {f:e}: rates off by {off:e}");
                worst_rate = worst_rate.max(off);
                checked += 1;
            }
        }
    }
    println!(
        "triads at 1e±100, 1e±6: {n} groups, joints within {worst_pose:.1e} of the size, \
         {checked} rates within {worst_rate:.1e}"
    );
}

fn scaled_case(c: &Case, f: f64) -> (Guide, [Point2<f64>; 2], SliderTriadDims) {
    let pair = match c.dims.pair {
        SlidingPair::Outer { offset } => SlidingPair::Outer { offset: offset * f },
        SlidingPair::Inner { angle, offset } => SlidingPair::Inner {
            angle,
            offset: offset * f,
        },
    };
    (
        Guide::fixed(
            Point2::from(c.first.point.p.coords * f),
            c.first.angle.value,
        ),
        c.a.map(|p| Point2::from(p.coords * f)),
        SliderTriadDims {
            pair,
            l: c.dims.l.map(|l| l * f),
            l_b1b2: c.dims.l_b1b2 * f,
            b3_along: c.dims.b3_along * f,
            b3_across: c.dims.b3_across * f,
        },
    )
}

#[test]
fn sliding_triads_called_directly_are_scale_free() {
    let n = (cases("TMM_TRIAD_CASES", 500) / 5).max(50);
    let mut rng = Rng(0x5CA1_E029);
    let (mut worst_pose, mut worst_rate, mut checked) = (0.0f64, 0.0f64, 0);
    for inner in [false, true] {
        for case in 0..n {
            let c = random_case(&mut rng, inner, true);
            let s = size(&c);
            let modes = slider_triad_modes(&c.first, c.a, &c.dims).unwrap();
            let first_v = (rng.vector(1.0), rng.vector(1.0));
            let guide_rates = (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
            let va = [
                (rng.vector(1.0), rng.vector(1.0)),
                (rng.vector(1.0), rng.vector(1.0)),
            ];
            let moving = |f: f64, g: &Guide, a: [Point2<f64>; 2]| {
                (
                    Guide {
                        point: PointMotion::new(g.point.p, first_v.0 * f, first_v.1 * f),
                        angle: Motion::new(g.angle.value, guide_rates.0, guide_rates.1),
                    },
                    [0, 1].map(|k| PointMotion::new(a[k], va[k].0 * f, va[k].1 * f)),
                )
            };
            for f in SCALES {
                let (g, a, d) = scaled_case(&c, f);
                let other = slider_triad_modes(&g, a, &d)
                    .unwrap_or_else(|e| panic!("case {case} at {f:e}: {e}"));
                let off =
                    modes_off(modes.as_slice(), other.as_slice(), f, s).unwrap_or_else(|| {
                        panic!(
                            "case {case} at {f:e}: {} modes, {} at scale 1",
                            other.len(),
                            modes.len()
                        )
                    });
                assert!(
                    off <= 1e-12,
                    "case {case} at {f:e}: joints off by {off:e} of the size"
                );
                worst_pose = worst_pose.max(off);
                for (m, q) in modes.as_slice().iter().zip(other.as_slice()) {
                    if m.det.abs() < 1e-2 || !exact(f) {
                        continue;
                    }
                    let (g1, a1) = moving(1.0, &c.first, c.a);
                    let r1 = slider_triad_rates(&g1, a1, &c.dims, m).unwrap();
                    let (gf, af) = moving(f, &g, a);
                    let rf = slider_triad_rates(&gf, af, &d, q)
                        .unwrap_or_else(|e| panic!("case {case} at {f:e}: rates {e}"));
                    let off = rates_off(&r1, &rf, f);
                    assert!(off <= 1e-12, "case {case} at {f:e}: rates off by {off:e}");
                    worst_rate = worst_rate.max(off);
                    checked += 1;
                }
            }
        }
    }
    println!(
        "sliding triads at 1e±100, 1e±6: {n} groups a kind, joints within {worst_pose:.1e} of \
         the size, {checked} rates within {worst_rate:.1e}"
    );
}

/// A length that underflows to zero against the other dimensions is named, not a mode.
#[test]
fn triads_whose_lengths_underflow_against_their_coordinates_are_refused() {
    let dims = TriadDims::new([5e-324, 1.0, 1.0], 1e300, 0.5, 0.8);
    let a = [
        Point2::new(0.0, -1.0),
        Point2::new(1.6, 0.8),
        Point2::new(0.5, 1.8),
    ];
    match triad_modes(a, &dims) {
        Err(Error::Overflow { what }) => assert!(what.contains("underflows"), "{what}"),
        other => panic!("{other:?}"),
    }
}
