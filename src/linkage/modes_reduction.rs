#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > y)` rejects NaN too, on purpose.
//! Every real assembly mode of a general group (a rigid group of hinges with no closed form)
//! by a reduction to one equation in one angle.
//!
//! # The reduction
//! Cut the group at one binary link c (the *closing* link) and it keeps one degree of
//! freedom (3(n − 1) − 2(m − 2) = 1 with 2m = 3n). Drive that freedom by the angle θ of a
//! link d hinged to a known point P (the *driver*: its frame is o = P − R(θ)·l). The rest is
//! placed dyad by dyad: two unknown links a and b hinged to each other at X, each hinged to
//! something already placed at A and B, close when X lies on the circle round A of radius
//! |l_X − l_A| (in a's frame) and on the circle round B of radius |l_X − l_B|; the two
//! intersections are the dyad's two branches. With every other link placed, the closing
//! link's two hinges sit at known points P₁ and P₂ and the group closes when
//!
//!   f_β(θ) = |P₂ − P₁| − |l₂ − l₁| = 0,
//!
//! one equation for each choice β of the dyads' branches. The links are counted so that a
//! rigid group of n links needs (n − 2)/2 dyads, so β ranges over 2^((n−2)/2) choices (four
//! for the double butterfly's six-link group).
//!
//! # Finding every root
//! Each f_β is sampled at `samples` equally spaced θ over the whole turn. A sign change
//! between two samples where f_β is defined brackets a root; where f_β stops being defined
//! (a dyad's circles part), the last defined θ is bisected to the last bits and f_β is read
//! there too, so a root between the last sample and the edge of the branch's domain is
//! bracketed (the two branches of that dyad meet at the edge with one value, so a pair of
//! roots straddling the fold is bracketed once on each branch). Each bracket is bisected to
//! the last bits, the pose there polished by Newton's method on the whole group's closure
//! ([`HingedGroup::newton`]), and kept once (two poses within 10⁻⁹ of the size are one mode).
//! A root of even multiplicity (f_β touching zero: two modes merged, the group at a branch
//! point) has no sign change and is not reported; nor are two roots closer together than a
//! sample spacing on one branch (raise `samples` to resolve them: the count is then stable).

use crate::error::{Error, Result};
use crate::kinematics::{GroupPose, HingedGroup};
use nalgebra::{Point2, Vector2};
use std::f64::consts::TAU;

/// Where a hinge of a link meets something known: a known point, or a hinge to another
/// link of the group (`inner` index, the side this link is on).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum End {
    Outer(usize),
    Inner(usize, usize),
}

/// One step of a reduction.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    /// Link `link` placed by the angle θ about outer hinge `outer`.
    Driver { link: usize, outer: usize },
    /// Links `a` and `b`, hinged to each other at inner hinge `h`, and at `ea` and `eb` to
    /// what is placed: `bit` is the branch's bit in β.
    Dyad {
        a: usize,
        ea: End,
        b: usize,
        eb: End,
        h: usize,
        bit: usize,
    },
    /// Link `link` between two placed hinges: the closure equation.
    Close { link: usize, e1: End, e2: End },
}

/// A reduction of a general group to one equation in one angle (module docs).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Reduction {
    steps: Vec<Step>,
    dyads: usize,
}

impl Reduction {
    /// The driver link and the closing link (indices in the group).
    pub(crate) fn driver_and_closing(&self) -> (usize, usize) {
        let mut d = 0;
        let mut c = 0;
        for s in &self.steps {
            match *s {
                Step::Driver { link, .. } => d = link,
                Step::Close { link, .. } => c = link,
                Step::Dyad { .. } => {}
            }
        }
        (d, c)
    }

    /// The number of branch choices β, 2^dyads.
    pub(crate) fn branch_choices(&self) -> usize {
        1 << self.dyads
    }
}

/// The local point of end `e` on its link.
fn local(g: &HingedGroup, e: End) -> Vector2<f64> {
    match e {
        End::Outer(o) => g.outer[o].1,
        End::Inner(h, s) => g.inner[h][s].1,
    }
}

/// The other link at end `e` (`None` for a known point).
fn other(g: &HingedGroup, e: End) -> Option<usize> {
    match e {
        End::Outer(_) => None,
        End::Inner(h, s) => Some(g.inner[h][1 - s].0),
    }
}

/// Every end of link `k`.
fn ends(g: &HingedGroup, k: usize) -> Vec<End> {
    let mut v: Vec<End> = (0..g.outer.len())
        .filter(|&o| g.outer[o].0 == k)
        .map(End::Outer)
        .collect();
    for (h, pair) in g.inner.iter().enumerate() {
        for (s, end) in pair.iter().enumerate() {
            if end.0 == k {
                v.push(End::Inner(h, s));
            }
        }
    }
    v
}

/// The hinge an end belongs to (outer hinges first, then inner), to mark it used.
fn hinge(g: &HingedGroup, e: End) -> usize {
    match e {
        End::Outer(o) => o,
        End::Inner(h, _) => g.outer.len() + h,
    }
}

/// Two local points apart by more than rounding (a dyad's arm, the closing link's length).
fn apart(a: Vector2<f64>, b: Vector2<f64>, size: f64) -> bool {
    (a - b).norm() > 1e-9 * size
}

/// A reduction of `g` with the first driver (in the order of its outer hinges) for which the
/// group decomposes into dyads and one closing link; `None` when none does (a group that
/// needs two cut parameters).
pub(crate) fn reduce(g: &HingedGroup, size: f64) -> Option<Reduction> {
    (0..g.outer.len()).find_map(|o| reduce_from(g, o, size))
}

/// The reduction driven about outer hinge `o`, if the group decomposes from it.
fn reduce_from(g: &HingedGroup, o: usize, size: f64) -> Option<Reduction> {
    let n = g.links;
    let mut known = vec![false; n];
    let mut used = vec![false; g.outer.len() + g.inner.len()];
    let d = g.outer[o].0;
    known[d] = true;
    used[hinge(g, End::Outer(o))] = true;
    let mut steps = vec![Step::Driver { link: d, outer: o }];
    let mut dyads = 0;
    let mut closed = false;
    // An unused end of link k to something placed, away from local point `from`.
    let anchor = |k: usize, from: Vector2<f64>, known: &[bool], used: &[bool]| {
        ends(g, k).into_iter().find(|&e| {
            !used[hinge(g, e)]
                && other(g, e).is_none_or(|l| known[l])
                && apart(local(g, e), from, size)
        })
    };
    loop {
        let dyad = (0..g.inner.len()).find_map(|h| {
            let [(a, la), (b, lb)] = g.inner[h];
            if used[g.outer.len() + h] || known[a] || known[b] || a == b {
                return None;
            }
            let ea = anchor(a, la, &known, &used)?;
            let eb = anchor(b, lb, &known, &used)?;
            Some(Step::Dyad {
                a,
                ea,
                b,
                eb,
                h,
                bit: dyads,
            })
        });
        if let Some(
            step @ Step::Dyad {
                a, ea, b, eb, h, ..
            },
        ) = dyad
        {
            for e in [ea, eb, End::Inner(h, 0)] {
                used[hinge(g, e)] = true;
            }
            known[a] = true;
            known[b] = true;
            dyads += 1;
            steps.push(step);
            continue;
        }
        if closed {
            break;
        }
        let close = (0..n).filter(|&k| !known[k]).find_map(|k| {
            let all: Vec<End> = ends(g, k)
                .into_iter()
                .filter(|&e| !used[hinge(g, e)] && other(g, e).is_none_or(|l| known[l]))
                .collect();
            let (&e1, rest) = all.split_first()?;
            let &e2 = rest
                .iter()
                .find(|&&e| apart(local(g, e), local(g, e1), size))?;
            Some(Step::Close { link: k, e1, e2 })
        });
        let Some(step @ Step::Close { link, e1, e2 }) = close else {
            break;
        };
        used[hinge(g, e1)] = true;
        used[hinge(g, e2)] = true;
        known[link] = true;
        closed = true;
        steps.push(step);
    }
    (closed && known.iter().all(|&k| k) && used.iter().all(|&u| u) && dyads < 20)
        .then_some(Reduction { steps, dyads })
}

/// `l` turned by angle `a`.
fn turned(a: f64, l: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = a.sin_cos();
    Vector2::new(c * l.x - s * l.y, s * l.x + c * l.y)
}

/// The frame (origin, angle) of a link with local points `l1`, `l2` at the places `p1` and
/// the direction of `p2 − p1` (the two coincide when |p2 − p1| = |l2 − l1|).
fn frame_through(
    p1: Point2<f64>,
    p2: Point2<f64>,
    l1: Vector2<f64>,
    l2: Vector2<f64>,
) -> (Point2<f64>, f64) {
    let w = p2 - p1;
    let v = l2 - l1;
    let angle = w.y.atan2(w.x) - v.y.atan2(v.x);
    (p1 - turned(angle, l1), angle)
}

/// Each link's frame: its origin and angle.
type Frames = Vec<(Point2<f64>, f64)>;

/// The group placed by reduction `r` at driver angle `theta` and branch choice `beta`: the
/// links' frames and the closure value f_β(θ); `None` where a dyad does not assemble.
fn place(
    g: &HingedGroup,
    r: &Reduction,
    outer: &[Point2<f64>],
    theta: f64,
    beta: usize,
) -> Option<(Frames, f64)> {
    let mut frames = vec![(Point2::origin(), 0.0); g.links];
    let at = |frames: &[(Point2<f64>, f64)], e: End| -> Point2<f64> {
        match e {
            End::Outer(o) => outer[o],
            End::Inner(h, s) => {
                let (k, l) = g.inner[h][1 - s];
                frames[k].0 + turned(frames[k].1, l)
            }
        }
    };
    let mut f = None;
    for s in &r.steps {
        match *s {
            Step::Driver { link, outer: o } => {
                frames[link] = (outer[o] - turned(theta, g.outer[o].1), theta);
            }
            Step::Dyad {
                a,
                ea,
                b,
                eb,
                h,
                bit,
            } => {
                let (pa, pb) = (at(&frames, ea), at(&frames, eb));
                let [(_, la), (_, lb)] = g.inner[h];
                let (ra, rb) = ((la - local(g, ea)).norm(), (lb - local(g, eb)).norm());
                let sign = if beta >> bit & 1 == 0 { 1.0 } else { -1.0 };
                let x = circles(pa, ra, pb, rb, sign)?;
                frames[a] = frame_through(pa, x, local(g, ea), la);
                frames[b] = frame_through(pb, x, local(g, eb), lb);
            }
            Step::Close { link, e1, e2 } => {
                let (p1, p2) = (at(&frames, e1), at(&frames, e2));
                let (l1, l2) = (local(g, e1), local(g, e2));
                frames[link] = frame_through(p1, p2, l1, l2);
                f = Some((p2 - p1).norm() - (l2 - l1).norm());
            }
        }
    }
    let f = f?;
    f.is_finite().then_some((frames, f))
}

/// The intersection of the circles round `a` of radius `ra` and round `b` of radius `rb` on
/// the side `sign` (+1: left of a → b); `None` where they do not meet.
fn circles(a: Point2<f64>, ra: f64, b: Point2<f64>, rb: f64, sign: f64) -> Option<Point2<f64>> {
    let w = b - a;
    let d = w.norm();
    if !(d > 0.0) {
        return None;
    }
    // Along a → b at x from a, across it at ±h: x² + h² = ra², (d − x)² + h² = rb².
    let x = (d * d + ra * ra - rb * rb) / (2.0 * d);
    let h2 = ra * ra - x * x;
    if !(h2 >= 0.0) {
        return None;
    }
    let u = w / d;
    Some(a + x * u + sign * h2.sqrt() * Vector2::new(-u.y, u.x))
}

/// The closure value of branch choice `beta` at θ, `None` where undefined.
fn value(
    g: &HingedGroup,
    r: &Reduction,
    outer: &[Point2<f64>],
    t: f64,
    beta: usize,
) -> Option<f64> {
    place(g, r, outer, t, beta).map(|p| p.1)
}

/// The last θ from `t0` (defined) towards `t1` (undefined) where f_β is defined, to the last
/// bits.
fn edge(
    g: &HingedGroup,
    r: &Reduction,
    outer: &[Point2<f64>],
    t0: f64,
    t1: f64,
    beta: usize,
) -> f64 {
    let (mut inside, mut outside) = (t0, t1);
    for _ in 0..200 {
        let mid = 0.5 * (inside + outside);
        if mid == inside || mid == outside {
            break;
        }
        if value(g, r, outer, mid, beta).is_some() {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    inside
}

/// The root of f_β in [t0, t1] (its values there of opposite signs, or zero), bisected to
/// the last bits; `None` if f_β is undefined somewhere on the way.
fn root(
    g: &HingedGroup,
    r: &Reduction,
    outer: &[Point2<f64>],
    (mut t0, mut f0): (f64, f64),
    (mut t1, f1): (f64, f64),
    beta: usize,
) -> Option<f64> {
    if f0 == 0.0 {
        return Some(t0);
    }
    if f1 == 0.0 {
        return Some(t1);
    }
    for _ in 0..200 {
        let mid = 0.5 * (t0 + t1);
        if mid == t0 || mid == t1 {
            break;
        }
        let fm = value(g, r, outer, mid, beta)?;
        if fm == 0.0 {
            return Some(mid);
        }
        if (fm < 0.0) == (f0 < 0.0) {
            (t0, f0) = (mid, fm);
        } else {
            t1 = mid;
        }
    }
    Some(if f0.abs() <= f1.abs() { t0 } else { t1 })
}

/// Every real assembly mode of `g` on the known points `outer` found by reduction `r` with
/// `samples` samples of the driver's turn (module docs), each closed by Newton's method on
/// the whole group to rounding and kept once.
///
/// # Errors
/// As [`HingedGroup::check`].
pub(crate) fn modes_by_reduction(
    g: &HingedGroup,
    r: &Reduction,
    outer: &[Point2<f64>],
    size: f64,
    samples: usize,
) -> Result<Vec<GroupPose>> {
    g.check()?;
    let mut thetas: Vec<(f64, usize)> = Vec::new();
    #[allow(clippy::cast_precision_loss)]
    let t_at = |k: usize| TAU * k as f64 / samples as f64;
    for beta in 0..r.branch_choices() {
        let vals: Vec<Option<f64>> = (0..samples)
            .map(|k| value(g, r, outer, t_at(k), beta))
            .collect();
        for k in 0..samples {
            let (t0, t1) = (t_at(k), t_at(k + 1));
            let (v0, v1) = (vals[k], vals[(k + 1) % samples]);
            let found = match (v0, v1) {
                (Some(f0), Some(f1)) if (f0 <= 0.0) != (f1 <= 0.0) || f0 == 0.0 => {
                    root(g, r, outer, (t0, f0), (t1, f1), beta)
                }
                (Some(f0), None) => {
                    let te = edge(g, r, outer, t0, t1, beta);
                    value(g, r, outer, te, beta)
                        .filter(|&fe| (f0 <= 0.0) != (fe <= 0.0) || fe == 0.0)
                        .and_then(|fe| root(g, r, outer, (t0, f0), (te, fe), beta))
                }
                (None, Some(f1)) => {
                    let te = edge(g, r, outer, t1, t0, beta);
                    value(g, r, outer, te, beta)
                        .filter(|&fe| (f1 <= 0.0) != (fe <= 0.0) || fe == 0.0)
                        .and_then(|fe| root(g, r, outer, (te, fe), (t1, f1), beta))
                }
                _ => None,
            };
            if let Some(t) = found {
                thetas.push((t, beta));
            }
        }
    }
    let mut found: Vec<GroupPose> = Vec::new();
    for (t, beta) in thetas {
        let Some((frames, _)) = place(g, r, outer, t, beta) else {
            continue;
        };
        let start = GroupPose {
            origins: frames.iter().map(|f| f.0).collect(),
            angles: frames.iter().map(|f| f.1).collect(),
        };
        let Ok(pose) = g.newton(&start, outer, size) else {
            continue;
        };
        // Newton's method from a root of the reduced equation stays at that root (it starts
        // within rounding of it); a pose that closes but moved away is a different mode and is
        // dropped rather than counted for this one.
        if pose.distance(&start, size) > 1e-6 * size || g.residual(&pose, outer) > 1e-12 * size {
            continue;
        }
        if !found.iter().any(|p| p.distance(&pose, size) <= 1e-9 * size) {
            found.push(pose);
        }
    }
    Ok(found)
}

/// `samples` checked: 64 to 10⁷ samples of the driver's turn.
pub(crate) fn check_samples(samples: usize) -> Result<()> {
    if (64..=10_000_000).contains(&samples) {
        Ok(())
    } else {
        #[allow(clippy::cast_precision_loss)]
        Err(Error::OutOfRange {
            name: "samples of the mode search",
            value: samples as f64,
            min: 64.0,
            max: 1e7,
            ends: crate::error::Ends::Closed,
        })
    }
}
