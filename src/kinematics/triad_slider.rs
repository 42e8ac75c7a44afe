//! The triad with one sliding pair: the Assur group of the 3rd class whose first binary link
//! is joined by a prismatic pair instead of a hinge, either to its known link (the *outer*
//! pair: link 1 is a slider on a guide of the known link, hinged to the ternary link at B1) or
//! to the ternary link (the *inner* pair: link 1 is hinged to the known link at A1 and slides
//! along a guide of the ternary link through B1). The other two binary links are hinged at
//! both ends, as in the [`triad`](mod@super::triad).
//!
//! # Positions: one equation in one angle, every root bracketed
//! With the ternary link's angle θ fixed (z = e^{iθ}; the ternary link's frame has its origin
//! O at B1 and its x axis along B1 → B2), each leg is one equation in O:
//! - leg 1 a line, n·O = h: outer, B1 = O on the guide's line at the offset e,
//!   n = d⊥ (d the guide's unit vector) and h = n·P + e (P a point of the guide); inner, A1 on
//!   the ternary link's guide through O at the offset e, n = (R(θ)·δ)⊥ (δ the guide's direction
//!   in the ternary link's frame) and h = n·A1 − e;
//! - legs 2 and 3 circles, |O − c_k| = l_k with c_k = A_k − R(θ)·β_k.
//!
//! The circles' difference is the radical axis b·O = s, b = 2(c_3 − c_2),
//! s = |c_3|² − |c_2|² + l_2² − l_3²; with the line it gives Δ·O = X = s·n⊥ − h·b⊥,
//! Δ = n × b, and the second circle leaves the eliminated equation
//!
//! F(θ) = |X − Δ·c_2|² − l_2²·Δ² = 0,
//!
//! Placing the complex plane's origin at A1 (inner) or A2 (outer) makes h constant; then Δ
//! is a real trigonometric polynomial of degree 1 and W = X − Δ·c_2 a Laurent polynomial in
//! z of degrees −1…2 (n = ν·z for the inner pair, ν for the outer one): F is of degree 3
//! ([`trig_cubic`](super::trig_cubic), the RRR triad's form), its Fourier coefficients are
//! formed exactly from the dimensions (a few dozen complex products, no trigonometric
//! function), and it has at most six real roots. Every root is bracketed by the certified
//! scan of the RRR triad ([`trig_roots`](super::trig_roots)): no mode is missed or found
//! twice. Each root's pose follows from the linear equations (or, where Δ vanishes, from the
//! line and the second circle) and is polished by Newton's method on the three closures in
//! (O, θ), whose matrix is the velocity system below; where F's rounding merged the two
//! modes of a fold, the partner of the mode found is recovered from the fold's normal form
//! ([`fold`](super::fold)), as for the triad.
//!
//! # Rates: the velocity system
//! Each leg can push the ternary link only along one line (its Plücker row (w, (p − O) × w)):
//! a hinged leg along itself (w = u_k, p = B_k), the outer slider across its guide through
//! B1 (w = n, p = O), the inner slider across the ternary link's guide through A1 (w = n,
//! p = A1). The time derivative of each closure projected on w is
//!
//! w·v_O + ((p − O) × w)·ω_T = w·v_known(p),
//!
//! the point p's velocity as a point of the known link; a 3×3 system K whose determinant
//! vanishes when the three lines meet at one point (the group's dead point); the rates are
//! refused within rounding of a branch point by the triad's rule ([`SINGULAR_BRANCH`]: the
//! data's distance η from the fold). The accelerations solve the same K; besides the hinged legs' centripetal terms
//! (−l_k·ω_k² + ω_T²·(r_k·u_k)), a slider adds its Coriolis term: outer
//! n·a_O = n·a_K(O) + 2·ω_K·ṡ, inner n·a_O + ((A1 − O) × n)·ε_T = n·a_A1 − 2·ω_T·ṡ +
//! ω_T²·n·(A1 − O), with ṡ the slide's rate along the guide. The sliding link turns with the
//! link that carries its guide.

use super::fold::{split_steps, Leg, Legs, BRANCH_MEASURE, SINGULAR_BRANCH};
use super::link::LinkMotion;
use super::motion::PointMotion;
use super::rrp::Guide;
use super::triad::{AssemblyModes, TriadDims, TriadPose, TriadState};
use super::trig_cubic::{n1, Cubic};
use super::trig_roots::{
    checked_roots, times_pow2, unit as unit_c, unit_exponent, CLOSES, SAME_MODE,
};
use crate::angle::{cross, direction, perp, unit};
use crate::error::{finite, finite2, positive, Error, Result};
use nalgebra::{Complex, Matrix3, Point2, Vector2, Vector3};

type C = Complex<f64>;

// The position where the rates may not exist (a branch point): its own file.
mod branch;
pub use branch::{slider_triad_continued, slider_triad_position};

const GROUP: &str = "triad with a sliding pair";
const MEASURE: &str = "det(velocity system)/L_T";
/// The most assembly modes a triad with a sliding pair can have: the roots of its eliminated
/// equation, a trigonometric polynomial of degree 3 (module docs).
pub const MAX_SLIDER_TRIAD_MODES: usize = 6;
/// Where the first binary link's sliding pair is, with the dimension the pair fixes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SlidingPair {
    /// Link 1 slides on a guide of its known link and is hinged to the ternary link at B1
    /// (the leg's input is that [`Guide`]).
    Outer {
        /// e, B1's distance to the left of the guide line (along the guide's direction), m.
        offset: f64,
    },
    /// Link 1 is hinged to its known link at A1 and slides along a guide of the ternary link
    /// through B1 (the leg's input is A1's motion).
    Inner {
        /// The guide's direction in the ternary link's frame (from B1 → B2), rad.
        angle: f64,
        /// e, A1's distance to the left of the guide line (along its direction), m.
        offset: f64,
    },
}

/// The dimensions of a triad with a sliding pair in its first leg.
///
/// The ternary link's frame has its origin at B1 (for the inner pair: the point of the
/// ternary link's guide that was at the joint when drawn) and its x axis along B1 → B2, as in
/// [`TriadDims`].
///
/// # Examples
/// ```
/// use tmm::kinematics::{SliderTriadDims, SlidingPair};
/// let dims = SliderTriadDims {
///     pair: SlidingPair::Outer { offset: 0.1 },
///     l: [0.35, 0.4],
///     l_b1b2: 0.2,
///     b3_along: 0.1,
///     b3_across: 0.17,
/// };
/// assert_eq!(dims.l[0], 0.35);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SliderTriadDims {
    /// The sliding pair of leg 1.
    pub pair: SlidingPair,
    /// l_A2B2, l_A3B3: the hinged legs' lengths, m.
    pub l: [f64; 2],
    /// l_B1B2, m.
    pub l_b1b2: f64,
    /// B3's coordinate along B1 → B2, m.
    pub b3_along: f64,
    /// B3's coordinate across B1 → B2 (to the left of it), m.
    pub b3_across: f64,
}

impl SliderTriadDims {
    /// The ternary link's triangle as a [`TriadDims`] (its legs 1 long: unused), for
    /// [`TriadDims::ternary_size`].
    pub(super) fn triangle(&self) -> TriadDims {
        TriadDims::new(
            [1.0, self.l[0], self.l[1]],
            self.l_b1b2,
            self.b3_along,
            self.b3_across,
        )
    }

    fn validate(&self) -> Result<()> {
        positive("l_A2B2", self.l[0])?;
        positive("l_A3B3", self.l[1])?;
        positive("l_B1B2", self.l_b1b2)?;
        finite("B3 along", self.b3_along)?;
        finite("B3 across", self.b3_across)?;
        match self.pair {
            SlidingPair::Outer { offset } => finite("guide offset", offset)?,
            SlidingPair::Inner { angle, offset } => {
                finite("guide angle", angle)?;
                finite("guide offset", offset)?
            }
        };
        Ok(())
    }
}

/// All assembly modes of a triad with a sliding pair at one position, in the order of θ (at
/// most [`MAX_SLIDER_TRIAD_MODES`]).
pub type SliderTriadModes = AssemblyModes<MAX_SLIDER_TRIAD_MODES>;

/// The first leg's known part at one position: the guide's point and unit vector (outer), or
/// A1 (inner, `d` unused).
#[derive(Clone, Copy)]
struct First {
    p: Point2<f64>,
    d: Vector2<f64>,
}

/// Every assembly mode of a triad with a sliding pair, its first leg on `first` (for the
/// outer pair the guide of the known link; for the inner pair `first.point` is A1, and
/// `first.angle` only has to be finite) and its hinged legs on `a` = [A2, A3]. Only positions are
/// read. `TriadPose::phi[0]` is the sliding link's angle: the guide's for the outer pair,
/// θ plus the guide's angle for the inner one.
///
/// # Examples
/// A slider on the x axis carries B1; the ternary link B1 = (0, 0), B2 = (1, 0),
/// B3 = (0.5, 0.8) m was drawn on legs of 1 m from A2 = (1.6, 0.8) and A3 = (0.5, 1.8). The
/// drawn pose is one of the modes, and every mode closes.
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{slider_triad_modes, Guide, SliderTriadDims, SlidingPair};
/// let dims = SliderTriadDims {
///     pair: SlidingPair::Outer { offset: 0.0 },
///     l: [1.0, 1.0],
///     l_b1b2: 1.0,
///     b3_along: 0.5,
///     b3_across: 0.8,
/// };
/// let a = [Point2::new(1.6, 0.8), Point2::new(0.5, 1.8)];
/// let modes = slider_triad_modes(&Guide::fixed(Point2::new(-2.0, 0.0), 0.0), a, &dims)?;
/// assert!(modes.as_slice().iter().any(|m| m.b[0].coords.norm() < 1e-12));
/// for m in modes.as_slice() {
///     assert_relative_eq!(m.b[0].y, 0.0, epsilon = 1e-12);
///     assert_relative_eq!((m.b[1] - a[0]).norm(), 1.0, epsilon = 1e-12);
///     assert_relative_eq!((m.b[2] - a[1]).norm(), 1.0, epsilon = 1e-12);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - [`Error::NonFinite`] / [`Error::NonPositive`] for bad input;
/// - [`Error::NotAssemblable`] (`group = "triad with a sliding pair"`) when F has no root
///   (`gap`: the least closure miss of the second circle over 1024 orientations);
/// - [`Error::Singular`] with `measure = "eliminated equation F(theta)"` when F vanishes
///   identically (the group moves: a continuum of modes);
/// - [`Error::Overflow`] when the eliminated equation overflows.
pub fn slider_triad_modes(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
) -> Result<SliderTriadModes> {
    finite2(["A1.x", "A1.y"], first.point.p.coords)?;
    finite2(["A2.x", "A2.y"], a[0].coords)?;
    finite2(["A3.x", "A3.y"], a[1].coords)?;
    finite("guide angle", first.angle.value)?;
    dims.validate()?;
    // Solved in the unit frame (scale-free at any size: the data times a power of two).
    let offset = match dims.pair {
        SlidingPair::Outer { offset } | SlidingPair::Inner { offset, .. } => offset,
    };
    let k = unit_exponent(
        [first.point.p, a[0], a[1]]
            .iter()
            .flat_map(|p| [p.x, p.y])
            .chain(dims.l)
            .chain([dims.l_b1b2, dims.b3_along, dims.b3_across, offset]),
    );
    let s = |x: f64| times_pow2(x, k);
    let unit_dims = SliderTriadDims {
        pair: match dims.pair {
            SlidingPair::Outer { offset } => SlidingPair::Outer { offset: s(offset) },
            SlidingPair::Inner { angle, offset } => SlidingPair::Inner {
                angle,
                offset: s(offset),
            },
        },
        l: dims.l.map(s),
        l_b1b2: s(dims.l_b1b2),
        b3_along: s(dims.b3_along),
        b3_across: s(dims.b3_across),
    };
    unit_dims.validate().map_err(|_| Error::Overflow {
        what: "triad with a sliding pair: a length underflows to zero against the group's \
               other dimensions",
    })?;
    let point = |p: Point2<f64>| Point2::new(s(p.x), s(p.y));
    let unit_first = Guide::fixed(point(first.point.p), first.angle.value);
    match unit_modes(&unit_first, a.map(point), &unit_dims) {
        Ok(modes) => Ok(modes.scaled(-k)),
        Err(Error::NotAssemblable { group, gap }) => Err(Error::NotAssemblable {
            group,
            gap: times_pow2(gap, -k),
        }),
        Err(e) => Err(e),
    }
}

/// [`slider_triad_modes`] on valid data of the unit frame.
fn unit_modes(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
) -> Result<SliderTriadModes> {
    let e = Equation::new(first, a, dims);
    let overflow = "triad with a sliding pair: eliminated equation";
    let roots = checked_roots(&e.cubic, &e.cubic.f, e.cubic.s, e.scale, GROUP, overflow)?;
    let mut modes = SliderTriadModes::empty();
    let tol = SAME_MODE * e.length;
    for r in 0..roots.n {
        for pose in e
            .poses(roots.z[r], roots.multiple[r], roots.double[r])
            .into_iter()
            .flatten()
        {
            modes.push_distinct(pose, tol);
        }
        // A plateau of F within its rounding of zero (as the triad's): samples across it.
        for z in roots.plateau(r) {
            for pose in e.poses(z, true, false).into_iter().flatten() {
                modes.push_distinct(pose, tol);
            }
        }
        // Across a double root's stretch (F flat, its terms cancelling): only regular poses
        // are modes of their own, as the triad's ([`Roots::stretch`]); a pose within rounding
        // of the branch point is the double root's, already taken above or by the plateau's
        // unfiltered samples between F's extremum and the root.
        for z in roots.stretch(r) {
            for pose in e.poses(z, true, false).into_iter().flatten() {
                let still = Guide::fixed(first.point.p, first.angle.value);
                let rates = slider_triad_rates(&still, a.map(PointMotion::fixed), dims, &pose);
                if super::trig_roots::regular_mode(rates) {
                    modes.push_distinct(pose, tol);
                }
            }
        }
    }
    if modes.is_empty() {
        return Err(Error::NotAssemblable {
            group: GROUP,
            gap: e.gap(),
        });
    }
    // A degenerate ternary link (sides near the underflow) can give finite joints whose
    // conditioning overflows: that is no mode to hand on.
    if modes.as_slice().iter().any(|p| !p.det.is_finite()) {
        return Err(Error::Overflow {
            what: "triad with a sliding pair: conditioning of a mode",
        });
    }
    modes.sort();
    Ok(modes)
}

/// The fast path of tracking, as [`triad_tracked`](super::triad_tracked) for the triad:
/// the mode reached by Newton's method on F(θ) from `previous`'s angle, or `None` when it
/// cannot be certified to be the mode that
/// [`slider_triad_modes`]`(first, a, dims)?.`[`nearest`](SliderTriadModes::nearest)`(previous)`
/// returns (the same two conditions: no other root of F near, and no other mode can be as
/// near `previous`). `None` also for invalid input (the full path names the error).
#[must_use]
pub fn slider_triad_tracked(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
    previous: &TriadPose,
) -> Option<TriadPose> {
    let valid = [first.point.p, a[0], a[1]]
        .iter()
        .all(|p| p.x.is_finite() && p.y.is_finite())
        && first.angle.value.is_finite()
        && previous
            .b
            .iter()
            .all(|p| p.x.is_finite() && p.y.is_finite());
    if !valid || dims.validate().is_err() {
        return None;
    }
    Some(super::triad_slider_fast::track(first, a, dims, previous)?.pose(&a, dims))
}

/// Whether the positions of the fast path's input are finite and the dimensions valid.
#[inline]
fn valid_input(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
    previous: &TriadPose,
) -> bool {
    let finite = |p: &Point2<f64>| p.x.is_finite() && p.y.is_finite();
    finite(&first.point.p)
        && finite(&a[0])
        && finite(&a[1])
        && first.angle.value.is_finite()
        && previous.b.iter().all(finite)
        && dims.validate().is_ok()
}

/// Positions, velocities and accelerations of a triad with a sliding pair, in the mode
/// nearest `previous`: the fast path [`slider_triad_tracked`] first, else
/// [`slider_triad_modes`] with [`nearest`](SliderTriadModes::nearest); then
/// [`slider_triad_rates`].
///
/// # Errors
/// As [`slider_triad_modes`] and [`slider_triad_rates`].
pub fn slider_triad(
    first: &Guide,
    a: [PointMotion; 2],
    dims: &SliderTriadDims,
    previous: &TriadPose,
) -> Result<TriadState> {
    let p = [a[0].p, a[1].p];
    if valid_input(first, p, dims, previous)
        && let Some(t) = super::triad_slider_fast::track(first, p, dims, previous)
        && let Some(state) = t.state(first, &a, dims)
    {
        return Ok(state);
    }
    slider_triad_checked(first, a, dims, previous)
}

/// [`slider_triad`] step by step, naming what fails.
#[cold]
#[inline(never)]
fn slider_triad_checked(
    first: &Guide,
    a: [PointMotion; 2],
    dims: &SliderTriadDims,
    previous: &TriadPose,
) -> Result<TriadState> {
    let p = [a[0].p, a[1].p];
    let pose = match slider_triad_tracked(first, p, dims, previous) {
        Some(pose) => pose,
        None => *slider_triad_modes(first, p, dims)?.nearest(previous),
    };
    slider_triad_rates(first, a, dims, &pose)
}

/// Velocities and accelerations of a triad with a sliding pair in a given mode (`pose`, one
/// of [`slider_triad_modes`]' at the positions of `first` and `a`), from the velocity system
/// K (module docs). The first binary link of the returned state is the sliding link: for the
/// outer pair its origin is B1 and it turns with the guide; for the inner pair its origin is
/// A1 and it turns with the ternary link.
///
/// # Errors
/// - [`Error::NonFinite`] for bad input;
/// - [`Error::Singular`] with `measure = "distance from a branch point/size"` when that
///   distance η ≤ [`SINGULAR_BRANCH`]: the three legs' lines of action meet at one point (a
///   dead point of the group, or two modes merging), to within what rounding can tell (the
///   rates would carry fewer than four digits); with `det(velocity system)/L_T` when K
///   cannot be inverted;
/// - [`Error::Overflow`] when a rate overflows.
pub fn slider_triad_rates(
    first: &Guide,
    a: [PointMotion; 2],
    dims: &SliderTriadDims,
    pose: &TriadPose,
) -> Result<TriadState> {
    first
        .point
        .validate(["A1.x", "A1.y", "v_A1.x", "v_A1.y", "a_A1.x", "a_A1.y"])?;
    first
        .angle
        .validate(["guide angle", "guide omega", "guide epsilon"])?;
    for m in &a {
        m.validate(["A.x", "A.y", "v_A.x", "v_A.y", "a_A.x", "a_A.y"])?;
    }
    for b in &pose.b {
        finite2(["B.x", "B.y"], b.coords)?;
    }
    finite("theta", pose.theta)?;
    dims.validate()?;
    rates(first, &a, dims, pose.b, unit(pose.theta), pose.theta)
}

/// The rates of a posed group (the joints `b`, the ternary link's direction `zt` at the angle
/// `theta`), on valid input: its legs' lines, then [`rates_of`].
fn rates(
    first: &Guide,
    a: &[PointMotion; 2],
    dims: &SliderTriadDims,
    b: [Point2<f64>; 3],
    zt: Vector2<f64>,
    theta: f64,
) -> Result<TriadState> {
    let o = b[0];
    let leg = [b[1] - a[0].p, b[2] - a[1].p];
    let len = [leg[0].norm(), leg[1].norm()];
    let (n, p, slide) = match dims.pair {
        SlidingPair::Outer { .. } => (perp(unit(first.angle.value)), o, Leg::FixedLine),
        SlidingPair::Inner { angle, .. } => (
            perp(rotate(zt, unit(angle))),
            first.point.p,
            Leg::TurningLine,
        ),
    };
    let legs = Legs {
        w: [n, leg[0] / len[0], leg[1] / len[1]],
        r: [p - o, b[1] - o, b[2] - o],
        kind: [slide, Leg::Hinged(len[0]), Leg::Hinged(len[1])],
        lt: dims.triangle().ternary_size(),
    };
    rates_of(first, a, dims, b, theta, &legs, &legs.matrix(), false)
}

/// The rates of a posed group from its legs' lines `legs` (the slide's normal n, then the
/// hinged legs' unit vectors; the arms from O = B1) and their velocity system `k`. The
/// slide's direction is d with n = d⊥. On the `fast` path (where the caller falls back to
/// the checked one) a pose that cheap bounds cannot prove off a branch point is an error at
/// once.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rates_of(
    first: &Guide,
    a: &[PointMotion; 2],
    dims: &SliderTriadDims,
    b: [Point2<f64>; 3],
    theta: f64,
    legs: &Legs,
    k: &Matrix3<f64>,
    fast: bool,
) -> Result<TriadState> {
    let o = b[0];
    let r = [Vector2::zeros(), legs.r[1], legs.r[2]];
    let len = [hinged_length(legs.kind[1]), hinged_length(legs.kind[2])];
    let (n, u) = (legs.w[0], [legs.w[1], legs.w[2]]);
    let d = Vector2::new(n.y, -n.x);
    let slide_angle = match dims.pair {
        SlidingPair::Outer { .. } => first.angle.value,
        SlidingPair::Inner { .. } => direction(d),
    };
    let det = k.determinant() / legs.lt;
    if !legs.surely_regular(k, det) {
        let eta = if fast { f64::NAN } else { legs.eta(k) };
        if eta.is_nan() || eta <= SINGULAR_BRANCH {
            return Err(Error::Singular {
                what: GROUP,
                measure: BRANCH_MEASURE,
                value: eta,
            });
        }
    }
    let k_inv = k.try_inverse().ok_or(Error::Singular {
        what: GROUP,
        measure: MEASURE,
        value: det,
    })?;
    let (wk, ek) = (first.angle.rate, first.angle.accel);
    // The known point at p: the guide's point of the known link (outer) or A1 (inner).
    let (vk, ak) = match dims.pair {
        SlidingPair::Outer { .. } => {
            let q = o - first.point.p;
            (
                first.point.v + wk * perp(q),
                first.point.a + ek * perp(q) - wk * wk * q,
            )
        }
        SlidingPair::Inner { .. } => (first.point.v, first.point.a),
    };
    let vel = k_inv * Vector3::new(n.dot(&vk), u[0].dot(&a[0].v), u[1].dot(&a[1].v));
    let (v_o, omega_t) = (Vector2::new(vel.x, vel.y), vel.z);
    let vb = [v_o, v_o + omega_t * perp(r[1]), v_o + omega_t * perp(r[2])];
    let omega = [0, 1].map(|k| perp(u[k]).dot(&(vb[k + 1] - a[k].v)) / len[k]);
    let w2 = omega_t * omega_t;
    let first_acc = match dims.pair {
        SlidingPair::Outer { .. } => n.dot(&ak) + 2.0 * wk * d.dot(&(v_o - vk)),
        SlidingPair::Inner { .. } => {
            let q = legs.r[0];
            let s_dot = d.dot(&(vk - v_o - omega_t * perp(q)));
            n.dot(&ak) - 2.0 * omega_t * s_dot + w2 * n.dot(&q)
        }
    };
    let acc = k_inv
        * Vector3::new(
            first_acc,
            u[0].dot(&a[0].a) - len[0] * omega[0] * omega[0] + w2 * r[1].dot(&u[0]),
            u[1].dot(&a[1].a) - len[1] * omega[1] * omega[1] + w2 * r[2].dot(&u[1]),
        );
    let (a_o, eps_t) = (Vector2::new(acc.x, acc.y), acc.z);
    let ternary = LinkMotion {
        origin: PointMotion::new(o, v_o, a_o),
        angle: theta,
        omega: omega_t,
        epsilon: eps_t,
    };
    let bm = [0, 1, 2].map(|i| ternary.motion_of(b[i]));
    let eps = [0, 1].map(|k| perp(u[k]).dot(&(bm[k + 1].a - a[k].a)) / len[k]);
    let sliding = match dims.pair {
        SlidingPair::Outer { .. } => LinkMotion {
            origin: bm[0],
            angle: slide_angle,
            omega: wk,
            epsilon: ek,
        },
        SlidingPair::Inner { .. } => LinkMotion {
            origin: first.point,
            angle: slide_angle,
            omega: omega_t,
            epsilon: eps_t,
        },
    };
    let hinged = |k: usize| LinkMotion {
        origin: a[k],
        angle: direction(b[k + 1] - a[k].p),
        omega: omega[k],
        epsilon: eps[k],
    };
    let out = TriadState {
        b: bm,
        ternary,
        binary: [sliding, hinged(0), hinged(1)],
        det,
    };
    let finite = bm
        .iter()
        .all(|m| m.v.iter().chain(m.a.iter()).all(|x| x.is_finite()))
        && omega.iter().chain(eps.iter()).all(|x| x.is_finite())
        && omega_t.is_finite()
        && eps_t.is_finite()
        && det.is_finite();
    if finite {
        Ok(out)
    } else {
        Err(Error::Overflow {
            what: "triad with a sliding pair: rates",
        })
    }
}

/// The length of a hinged leg (NaN for a slide, which has none).
fn hinged_length(leg: Leg) -> f64 {
    match leg {
        Leg::Hinged(len) => len,
        Leg::FixedLine | Leg::TurningLine => f64::NAN,
    }
}

/// The joints of a ternary link whose joints are `beta` in its own frame, with its origin
/// at `o` and its direction `z`.
#[inline]
fn joints_at(o: Vector2<f64>, z: Vector2<f64>, beta: &[Vector2<f64>; 3]) -> [Point2<f64>; 3] {
    [0, 1, 2].map(|i| Point2::from(o + rotate(z, beta[i])))
}

/// The pose with its origin at `o` and its direction `z` (the ternary link's joints `beta`
/// in its frame), the hinged legs' outer joints `a`, the slide's direction `slide` and the
/// conditioning `det`.
fn pose_at(
    o: Vector2<f64>,
    z: Vector2<f64>,
    beta: &[Vector2<f64>; 3],
    a: &[Point2<f64>; 2],
    slide: Vector2<f64>,
    det: f64,
) -> TriadPose {
    let b = joints_at(o, z, beta);
    TriadPose {
        b,
        theta: direction(z),
        phi: [
            direction(slide),
            direction(b[1] - a[0]),
            direction(b[2] - a[1]),
        ],
        det,
    }
}

/// W's Laurent coefficients (of z^−1 … z^2) and Δ = e0 + 2·Re(e1·z), in the complex plane
/// with its origin at `origin`, for the sliding leg's line n·O = h with n = ν·z^m (m = 1 for
/// the `inner` pair, whose guide turns with the ternary link; m = 0 for the outer one) and
/// h constant.
///
/// With c_k = a_k − β_k·z (k = 2, 3; a_k = A_k − origin): the radical axis b·O = s has
/// b = 2(c_3 − c_2) = b0 + b1·z and s = |c_3|² − |c_2|² + l_2² − l_3² = s0 + 2·Re(s1·z), since
/// |c_k|² = |a_k|² + |β_k|² − 2·Re(conj(a_k)·β_k·z); Δ = n × b = Im(conj(n)·b) and
/// X = i·(s·n − h·b) (Δ·O = X), so that W = X − Δ·c_2 and F = |W|² − l_2²·Δ².
#[allow(clippy::too_many_arguments)]
fn laurent(
    origin: Point2<f64>,
    nu: C,
    inner: bool,
    h: f64,
    a: [Point2<f64>; 2],
    beta: &[Vector2<f64>; 3],
    l: [f64; 2],
) -> ([C; 4], f64, C) {
    let rel = |p: Point2<f64>| C::new(p.x - origin.x, p.y - origin.y);
    let (a2, a3) = (rel(a[0]), rel(a[1]));
    let (be2, be3) = (C::new(beta[1].x, beta[1].y), C::new(beta[2].x, beta[2].y));
    let (b0, b1) = (2.0 * (a3 - a2), -2.0 * (be3 - be2));
    let s0 =
        a3.norm_sqr() + be3.norm_sqr() - a2.norm_sqr() - be2.norm_sqr() + l[0] * l[0] - l[1] * l[1];
    let s1 = -(a3.conj() * be3 - a2.conj() * be2);
    // Im(c·z) = (c·z − conj(c)/z)/(2i): e1 is the coefficient of z.
    let half_i = C::new(0.0, -0.5); // 1/(2i)
    let (e0, e1) = if inner {
        ((nu.conj() * b1).im, -nu * b0.conj() * half_i)
    } else {
        ((nu.conj() * b0).im, nu.conj() * b1 * half_i)
    };
    let zero = C::new(0.0, 0.0);
    let sn = if inner {
        [zero, s1.conj() * nu, s0 * nu, s1 * nu]
    } else {
        [s1.conj() * nu, s0 * nu, s1 * nu, zero]
    };
    let hb = [zero, h * b0, h * b1, zero];
    let dc = [
        e1.conj() * a2,
        e0 * a2 - e1.conj() * be2,
        e1 * a2 - e0 * be2,
        -e1 * be2,
    ];
    let i = C::new(0.0, 1.0);
    let w = [0, 1, 2, 3].map(|k| i * (sn[k] - hb[k]) - dc[k]);
    (w, e0, e1)
}

/// v turned by the unit complex number z.
#[inline]
fn rotate(z: Vector2<f64>, v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(z.x * v.x - z.y * v.y, z.y * v.x + z.x * v.y)
}

fn vec(z: C) -> Vector2<f64> {
    Vector2::new(z.re, z.im)
}

/// The eliminated equation of one triad with a sliding pair at one position.
struct Equation {
    first: First,
    inner: bool,
    offset: f64,
    /// The inner guide's direction in the ternary link's frame.
    delta: Vector2<f64>,
    a: [Point2<f64>; 2],
    beta: [Vector2<f64>; 3],
    l: [f64; 2],
    /// F = |W|² − l_2²·Δ².
    cubic: Cubic,
    /// The size of the terms that make F.
    scale: f64,
    /// |e0| + 2|e1| ≥ |Δ|.
    dscale: f64,
    /// L_T, the ternary link's size.
    lt: f64,
    /// The group's largest dimension, m.
    length: f64,
}

impl Equation {
    fn new(first: &Guide, a: [Point2<f64>; 2], dims: &SliderTriadDims) -> Self {
        let (inner, offset, delta) = match dims.pair {
            SlidingPair::Outer { offset } => (false, offset, Vector2::zeros()),
            SlidingPair::Inner { angle, offset } => (true, offset, unit(angle)),
        };
        let beta = [
            Vector2::zeros(),
            Vector2::new(dims.l_b1b2, 0.0),
            Vector2::new(dims.b3_along, dims.b3_across),
        ];
        let first = First {
            p: first.point.p,
            d: unit(first.angle.value),
        };
        // The origin: A1 (inner) or A2 (outer), so that the line's h is constant and the
        // coefficients are of the group's size.
        let (origin, nu, h) = if inner {
            (first.p, C::new(-delta.y, delta.x), -offset)
        } else {
            let n = perp(first.d);
            (a[0], C::new(n.x, n.y), n.dot(&(first.p - a[0])) + offset)
        };
        let (w, e0, e1) = laurent(origin, nu, inner, h, a, &beta, dims.l);
        let wsum = n1(w[0]) + n1(w[1]) + n1(w[2]) + n1(w[3]);
        let dscale = e0.abs() + 2.0 * n1(e1);
        let l2 = dims.l[0] * dims.l[0];
        let scale = wsum * wsum + l2 * dscale * dscale;
        let mut e = Self {
            first,
            inner,
            offset,
            delta,
            a,
            beta,
            l: dims.l,
            cubic: Cubic::new(&w, e0, e1, l2, scale),
            scale,
            dscale,
            lt: dims.triangle().ternary_size(),
            length: 0.0,
        };
        // The largest of the lengths (the distances compared squared: one square root).
        let square = beta[2]
            .norm_squared()
            .max((a[0] - e.first.p).norm_squared())
            .max((a[1] - e.first.p).norm_squared())
            .max((a[1] - a[0]).norm_squared());
        e.length = (dims.l[0].max(dims.l[1]).max(dims.l_b1b2))
            .max(offset.abs())
            .max(square.sqrt());
        e
    }

    /// The line of leg 1 at z: n·O = h, n a unit vector.
    fn line(&self, z: Vector2<f64>) -> (Vector2<f64>, f64) {
        if self.inner {
            let n = perp(rotate(z, self.delta));
            (n, n.dot(&self.first.p.coords) - self.offset)
        } else {
            let n = perp(self.first.d);
            (n, n.dot(&self.first.p.coords) + self.offset)
        }
    }

    /// The circles' centres c_2, c_3 for O at z.
    fn centres(&self, z: Vector2<f64>) -> [Vector2<f64>; 2] {
        [0, 1].map(|k| self.a[k].coords - rotate(z, self.beta[k + 1]))
    }

    /// F at z, the size of its terms, and Δ.
    fn value(&self, z: C) -> (f64, f64, f64) {
        let zv = vec(z);
        let (n, h) = self.line(zv);
        let c = self.centres(zv);
        let b = 2.0 * (c[1] - c[0]);
        let s = c[1].norm_squared() - c[0].norm_squared() + self.l[0] * self.l[0]
            - self.l[1] * self.l[1];
        let delta = cross(n, b);
        let x = s * perp(n) - h * perp(b);
        let w = x - delta * c[0];
        let ld = self.l[0] * delta;
        let size = (s.abs() + h.abs() * b.norm() + delta.abs() * c[0].norm()).powi(2) + ld * ld;
        (w.norm_squared() - ld * ld, size, delta)
    }

    /// The poses at a root z: O from the linear equations, or, where Δ nearly vanishes or
    /// the root is `multiple`, both intersections of the line with the second circle; each
    /// polished (module docs).
    fn poses(&self, z: C, multiple: bool, double: bool) -> [Option<TriadPose>; 4] {
        let zv = vec(z);
        let (n, h) = self.line(zv);
        let c = self.centres(zv);
        let b = 2.0 * (c[1] - c[0]);
        let s = c[1].norm_squared() - c[0].norm_squared() + self.l[0] * self.l[0]
            - self.l[1] * self.l[1];
        let delta = cross(n, b);
        let regular = delta.abs() > 1e-3 * self.dscale;
        if double && regular {
            let o = (s * perp(n) - h * perp(b)) / delta;
            if let Some(pose) = self.polish_steps(o, z, 0) {
                return [Some(pose), None, None, None];
            }
        }
        let found = if regular && !multiple {
            let o = (s * perp(n) - h * perp(b)) / delta;
            [self.polish(o, z), None]
        } else {
            // The line n·O = h against the circle |O − c_2| = l_2.
            let dist = h - n.dot(&c[0]);
            let foot = c[0] + dist * n;
            let half = (self.l[0] * self.l[0] - dist * dist).max(0.0).sqrt();
            let t = perp(n);
            [
                self.polish(foot + half * t, z),
                self.polish(foot - half * t, z),
            ]
        };
        // Two modes of one fold that F's rounding could not split (a cluster of roots, or a
        // double root whose pose at F's extremum does not close): the partner of the mode
        // found, from the fold's normal form.
        let partners = match found.iter().flatten().next() {
            Some(pose) if multiple || double => {
                let side = pose.b[1] - pose.b[0];
                let zp = C::new(side.x, side.y) / side.norm();
                self.split_fold(pose.b[0].coords, zp)
                    .unwrap_or([None, None])
            }
            _ => [None, None],
        };
        [found[0], found[1], partners[0], partners[1]]
    }

    /// The two modes of a fold whose roots of F were merged within F's rounding, although
    /// the closures tell them apart (as the triad's: F's rounding scales with its terms, the
    /// closures' with the size): from a pose O = `o` at z near the fold, the steps across it
    /// of the fold's normal form ([`split_steps`]) along the least singular direction of
    /// K′, each polished. `None` when the model has no two real roots.
    fn split_fold(&self, o: Vector2<f64>, z: C) -> Option<[Option<TriadPose>; 2]> {
        let (g, legs) = self.legs(o, z);
        let fold = legs.fold(&legs.matrix())?;
        let t = split_steps(&fold, &g)?;
        let at = |t: f64| {
            let zt = unit_c(z * C::new(1.0, t * fold.d_theta));
            self.polish(o + t * fold.d_o, zt)
        };
        Some([at(t[0]), at(t[1])])
    }

    /// The residuals of the three closures at (O, z) (the slide's n·O − h, then
    /// |B_k − A_k| − l_k), with the legs' lines there.
    fn legs(&self, o: Vector2<f64>, z: C) -> (Vector3<f64>, Legs) {
        let zv = vec(z);
        let r = [rotate(zv, self.beta[1]), rotate(zv, self.beta[2])];
        let leg = [0, 1].map(|k| o + r[k] - self.a[k].coords);
        let len = leg.map(|v| v.norm());
        let u = [leg[0] / len[0], leg[1] / len[1]];
        let (n, h) = self.line(zv);
        let (r0, slide) = if self.inner {
            (self.first.p.coords - o, Leg::TurningLine)
        } else {
            (Vector2::zeros(), Leg::FixedLine)
        };
        (
            Vector3::new(n.dot(&o) - h, len[0] - self.l[0], len[1] - self.l[1]),
            Legs {
                w: [n, u[0], u[1]],
                r: [r0, r[0], r[1]],
                kind: [slide, Leg::Hinged(len[0]), Leg::Hinged(len[1])],
                lt: self.lt,
            },
        )
    }

    /// The residuals of the three closures at (O, z), with the velocity system there.
    #[inline]
    fn residual(&self, o: Vector2<f64>, z: C) -> (Vector3<f64>, Matrix3<f64>) {
        let (g, legs) = self.legs(o, z);
        (g, legs.matrix())
    }

    /// The pose from O = `o` at z, polished by Newton's method on the closures (kept while
    /// it reduces the closure error); `None` (no mode: [`CLOSES`] gives the reasons) when it
    /// does not close to [`CLOSES`] of the size.
    ///
    /// The steps go on to the rounding floor of the residuals, not to a set tolerance: a
    /// pose left at 1e-15 of the size scatters its angles by several ulps from position to
    /// position (8.6e-15 rad on the bundled six-bar), which the rates do not have and which
    /// an 8th-order second difference of positions amplifies by 6.5/h².
    /// While the pose does not yet close to [`CLOSES`], a step that does not reduce the
    /// error is halved (up to 6 times) before giving up: near a branch point K is nearly
    /// singular, the full step overshoots along its null direction, and at a double root
    /// Newton's method only halves the error per step (hence up to 48 steps).
    fn polish(&self, o: Vector2<f64>, z: C) -> Option<TriadPose> {
        self.polish_steps(o, z, 48)
    }

    /// [`polish`](Self::polish) with at most `steps` Newton steps.
    fn polish_steps(&self, o: Vector2<f64>, z: C, steps: usize) -> Option<TriadPose> {
        let (mut o, mut z) = (o, z);
        let (mut g, mut k) = self.residual(o, z);
        let mut err = g.amax();
        let closes = CLOSES * self.length;
        for _ in 0..steps {
            if err == 0.0 {
                break;
            }
            let Some(k_inv) = k.try_inverse() else {
                break;
            };
            let mut step = k_inv * (-g);
            let halvings = if err > closes { 6 } else { 0 };
            let mut better = None;
            for _ in 0..=halvings {
                let on = o + Vector2::new(step.x, step.y);
                let zn = unit_c(z * C::new(1.0, step.z));
                let (gn, kn) = self.residual(on, zn);
                if gn.amax() < err {
                    better = Some((on, zn, gn, kn));
                    break;
                }
                step *= 0.5;
            }
            match better {
                Some((on, zn, gn, kn)) => (o, z, g, k, err) = (on, zn, gn, kn, gn.amax()),
                None => break,
            }
        }
        if err.is_nan() || err > closes {
            return None;
        }
        Some(self.pose(o, vec(z), &k))
    }

    /// The pose with its origin at `o` and its direction `z`, K being its velocity system.
    fn pose(&self, o: Vector2<f64>, z: Vector2<f64>, k: &Matrix3<f64>) -> TriadPose {
        let slide = if self.inner {
            rotate(z, self.delta)
        } else {
            self.first.d
        };
        pose_at(o, z, &self.beta, &self.a, slide, k.determinant() / self.lt)
    }

    /// The least miss of the second circle by the linear equations' O, at the best of 1024
    /// orientations: the `gap` of [`Error::NotAssemblable`].
    #[cold]
    fn gap(&self) -> f64 {
        let mut best = f64::INFINITY;
        for j in 0..1024 {
            let th = std::f64::consts::TAU * j as f64 / 1024.0;
            let z = C::new(th.cos(), th.sin());
            let (f, _, delta) = self.value(z);
            if delta.abs() <= 1e-9 * self.dscale {
                continue;
            }
            // |X − Δ·c_2|² − l_2²·Δ² = Δ²·(|O − c_2|² − l_2²): the miss in length.
            let q = f / (delta * delta) + self.l[0] * self.l[0];
            best = best.min((q.max(0.0).sqrt() - self.l[0]).abs());
        }
        best
    }
}
