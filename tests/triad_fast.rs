//! The triads' fast paths (Newton's method on the closures with the certificate of
//! `kinematics::triad_newton`) against the full scan: along random cycles the fast path,
//! where it answers, is the scan's nearest mode to 1e-12 of the size, for the triad and for
//! both kinds of the triad with a sliding pair; and where a second mode lies 1e-6 of the size
//! away, the certificate refuses whenever the previous pose cannot tell the two apart.

use nalgebra::{Point2, Vector2};
use std::f64::consts::TAU;
use tmm::kinematics::{
    slider_triad_modes, slider_triad_tracked, triad_modes, triad_tracked, Guide, SliderTriadDims,
    SlidingPair, TriadDims, TriadPose,
};

/// A seeded xorshift generator (the tests' own, as in the other triad tests).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

fn unit(a: f64) -> Vector2<f64> {
    Vector2::new(a.cos(), a.sin())
}

fn rotate(th: f64, v: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = th.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

fn n_cases() -> usize {
    std::env::var("TMM_TRIAD_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200)
}

/// A random ternary link placed at a random pose: its joints.
fn ternary(rng: &mut Rng) -> ([f64; 3], [Point2<f64>; 3], f64) {
    let (l12, along, across) = (
        rng.range(0.3, 1.0),
        rng.range(-0.3, 1.2),
        rng.range(0.2, 0.9) * if rng.next() < 0.5 { -1.0 } else { 1.0 },
    );
    let th = rng.range(0.0, TAU);
    let o = Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
    let b = [
        o,
        o + rotate(th, Vector2::new(l12, 0.0)),
        o + rotate(th, Vector2::new(along, across)),
    ];
    ([l12, along, across], b, th)
}

fn pose_of(b: [Point2<f64>; 3]) -> TriadPose {
    TriadPose {
        b,
        theta: 0.0,
        phi: [0.0; 3],
        det: 0.0,
    }
}

/// Along a cycle of 360 steps (A1 on a circle of 2 % of the size), every answer of the
/// fast path is the full scan's nearest mode within 1e-12 of the size.
#[test]
fn the_fast_path_is_the_scans_nearest_mode_along_random_cycles() {
    let mut rng = Rng(0xFA57_0028);
    let (mut tried, mut fast, mut worst) = (0usize, 0usize, 0.0f64);
    for case in 0..n_cases() / 10 {
        let (t, b, _) = ternary(&mut rng);
        let l = [0, 1, 2].map(|_| rng.range(0.4, 1.2));
        let dims = TriadDims::new(l, t[0], t[1], t[2]);
        let a = [0, 1, 2].map(|i| b[i] - l[i] * unit(rng.range(0.0, TAU)));
        let s = l.iter().fold(t[0], |m, &x| m.max(x));
        let Ok(modes) = triad_modes(a, &dims) else {
            continue;
        };
        let mut prev = *modes.nearest(&pose_of(b));
        let r = 0.02 * s;
        let centre = a[0] - Vector2::new(r, 0.0);
        for k in 1..=360 {
            let mut ak = a;
            ak[0] = centre + r * unit(TAU * k as f64 / 360.0);
            let Ok(all) = triad_modes(ak, &dims) else {
                break;
            };
            let full = *all.nearest(&prev);
            tried += 1;
            if let Some(t) = triad_tracked(ak, &dims, &prev) {
                fast += 1;
                let off = t.distance_squared(&full).sqrt() / s;
                assert!(
                    off <= 1e-12,
                    "case {case}, step {k}: the fast path is {off:e} of the size off the scan's \
                     nearest mode (modes {:?})",
                    all.as_slice()
                );
                worst = worst.max(off);
            }
            prev = full;
        }
    }
    println!(
        "triad fast path: {fast} of {tried} positions answered, at most {worst:.1e} of the size \
         from the scan's nearest mode"
    );
    assert!(fast * 2 > tried, "{fast} of {tried}");
}

/// The same for the triad with a sliding pair, both kinds (outer: a slider on a fixed guide
/// carries B1; inner: A1 slides on a guide of the ternary link), A2 on a circle.
#[test]
fn the_sliding_fast_path_is_the_scans_nearest_mode_along_random_cycles() {
    let mut rng = Rng(0x51DE_0028);
    let (mut tried, mut fast, mut worst) = (0usize, 0usize, 0.0f64);
    for case in 0..n_cases() / 10 {
        let (t, b, th) = ternary(&mut rng);
        let l = [rng.range(0.4, 1.2), rng.range(0.4, 1.2)];
        let offset = rng.range(-0.3, 0.3);
        let (pair, guide) = if case % 2 == 0 {
            let phi = rng.range(0.0, TAU);
            let n = Vector2::new(-phi.sin(), phi.cos());
            let p = b[0] - offset * n + rng.range(-1.0, 1.0) * unit(phi);
            (SlidingPair::Outer { offset }, Guide::fixed(p, phi))
        } else {
            let angle = rng.range(0.0, TAU);
            let d = rotate(th, unit(angle));
            let a1 = b[0] + rng.range(-0.5, 0.5) * d + offset * Vector2::new(-d.y, d.x);
            (SlidingPair::Inner { angle, offset }, Guide::fixed(a1, 0.0))
        };
        let dims = SliderTriadDims {
            pair,
            l,
            l_b1b2: t[0],
            b3_along: t[1],
            b3_across: t[2],
        };
        let a = [
            b[1] - l[0] * unit(rng.range(0.0, TAU)),
            b[2] - l[1] * unit(rng.range(0.0, TAU)),
        ];
        let s = l.iter().fold(t[0], |m, &x| m.max(x));
        let Ok(modes) = slider_triad_modes(&guide, a, &dims) else {
            continue;
        };
        let mut prev = *modes.nearest(&pose_of(b));
        let r = 0.02 * s;
        let centre = a[0] - Vector2::new(r, 0.0);
        for k in 1..=360 {
            let ak = [centre + r * unit(TAU * k as f64 / 360.0), a[1]];
            let Ok(all) = slider_triad_modes(&guide, ak, &dims) else {
                break;
            };
            let full = *all.nearest(&prev);
            tried += 1;
            if let Some(t) = slider_triad_tracked(&guide, ak, &dims, &prev) {
                fast += 1;
                let off = t.distance_squared(&full).sqrt() / s;
                assert!(
                    off <= 1e-12,
                    "case {case}, step {k}: the fast path is {off:e} of the size off the scan's \
                     nearest mode ({pair:?})"
                );
                worst = worst.max(off);
            }
            prev = full;
        }
    }
    println!(
        "sliding triad fast path: {fast} of {tried} positions answered, at most {worst:.1e} of \
         the size from the scan's nearest mode"
    );
    assert!(fast * 2 > tried, "{fast} of {tried}");
}

/// Two modes 1e-6 of the size apart: a triad built at a branch point (the three legs' lines
/// through one point P, where two modes merge), then A1 moved along its leg by 1e-12 of the
/// size to the side where the pair exists (the pair's distance grows as the square root of
/// the move). From previous poses on the segment between the two modes, the fast path either
/// refuses or returns the scan's nearest mode; from the midpoint, where no rule can tell the
/// two apart, it refuses; from each mode itself it may answer (that mode).
#[test]
fn the_certificate_refuses_between_two_modes_a_millionth_apart() {
    let mut rng = Rng(0x0DD5_0028);
    let mut built = 0;
    for case in 0..400 {
        let (t, b, _) = ternary(&mut rng);
        let centroid = (b[0].coords + b[1].coords + b[2].coords) / 3.0;
        let p = Point2::from(centroid + rng.range(0.8, 2.0) * unit(rng.range(0.0, TAU)));
        let l = [0, 1, 2].map(|_| rng.range(0.4, 1.2));
        // A_i on the line B_i P, on P's side or beyond B_i.
        let a = [0, 1, 2].map(|i| {
            let e = (p - b[i]).normalize();
            b[i] + if rng.next() < 0.5 { l[i] } else { -l[i] } * e
        });
        let dims = TriadDims::new(l, t[0], t[1], t[2]);
        let s = l.iter().fold(t[0], |m, &x| m.max(x));
        let along = (b[0] - a[0]).normalize();
        let mut best: Option<(TriadPose, TriadPose, [Point2<f64>; 3])> = None;
        for sign in [-1.0, 1.0] {
            let mut moved = a;
            moved[0] += sign * 1e-12 * s * along;
            let Ok(modes) = triad_modes(moved, &dims) else {
                continue;
            };
            let mut near: Vec<TriadPose> = modes.as_slice().to_vec();
            near.sort_by(|x, y| {
                x.distance_squared(&pose_of(b))
                    .total_cmp(&y.distance_squared(&pose_of(b)))
            });
            if near.len() >= 2 {
                let apart = near[0].distance_squared(&near[1]).sqrt() / s;
                let close = near[1].distance_squared(&pose_of(b)).sqrt() / s;
                if (1e-7..1e-5).contains(&apart) && close < 1e-4 {
                    best = Some((near[0], near[1], moved));
                }
            }
        }
        let Some((m0, m1, moved)) = best else {
            continue;
        };
        built += 1;
        let full_modes = triad_modes(moved, &dims).unwrap();
        for f in [0.0, 0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9, 1.0] {
            let prev = pose_of([0, 1, 2].map(|i| m0.b[i] + f * (m1.b[i] - m0.b[i])));
            let full = full_modes.nearest(&prev);
            // Refusing is always allowed: the full scan then decides.
            if let Some(fast) = triad_tracked(moved, &dims, &prev) {
                assert!(
                    f != 0.5,
                    "case {case}: the fast path answered halfway between two modes \
                         {:e} of the size apart",
                    m0.distance_squared(&m1).sqrt() / s
                );
                assert!(
                    fast.distance_squared(full).sqrt() <= 1e-12 * s,
                    "case {case}, f {f}: the fast path answered another mode than the \
                         scan's nearest"
                );
            }
        }
        if built >= 20 {
            break;
        }
    }
    println!(
        "certificate near a branch point: {built} pairs of modes 1e-7..1e-5 of the size apart"
    );
    assert!(built >= 5, "only {built} pairs built");
}
