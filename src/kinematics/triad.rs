//! The triad: the Assur group of the 3rd class with revolute joints (a ternary link T with the
//! joints B1, B2, B3, held by three binary links A1 B1, A2 B2, A3 B3 to known joints A1, A2, A3).
//!
//! # Positions: one equation in one angle, every root bracketed
//! With the ternary link's angle θ (the direction of B1 → B2) fixed, each binary link puts B1
//! on a circle: B1 ∈ circle(c_i(θ), l_i) with c_i = A_i − R(θ)·β_i (β_i the joint B_i in the
//! ternary link's frame, β_1 = 0). Subtracting the first circle's equation from the other two
//! leaves two linear equations in B1 (the radical axes), so B1 = A1 + i·W(θ)/D(θ) (complex
//! notation) with D = (c_2 − c_1) × (c_3 − c_1), and the first circle gives the eliminated
//! equation
//!
//! F(θ) = |W(θ)|² − l_1²·D(θ)² = 0,
//!
//! a real trigonometric polynomial of degree 3 (W is a Laurent polynomial in z = e^{iθ} of
//! degrees −1…2, D of degree 1): at most 6 real roots, the 6 assembly modes of the triad
//! (the sextic of the 3-RPR forward problem). F is one smooth single-valued function on the
//! circle — no branches, no folds — so its roots can be bracketed with certainty:
//!
//! - its Fourier coefficients F_0…F_3 are formed exactly from the dimensions (a few dozen
//!   complex products), which bounds |F″| ≤ M₂ = 2·Σ k²·|F_k| everywhere;
//! - the circle is cut into 32 cells and every cell is either *excluded* (F has one sign at
//!   both ends and min |F| > M₂·h²/8, so F cannot reach zero inside), or *monotone*
//!   (|F′(mid)| > M₂·h/2: at most one root, found by Brent's method if the ends' signs differ),
//!   or halved; a cell that keeps neither property down to a width of 2⁻²⁴ rad holds a
//!   near-tangency, where |F| is minimised (its extremum from F′ and F″) and the cell then
//!   holds two roots (bracketed on either side of the extremum), one double root (two modes
//!   merged: the extremum touches zero within rounding), or none;
//! - each root's pose is recovered from the linear equations and polished by one Newton step
//!   of the three closures on (B1, θ), whose matrix is the velocity system below.
//!
//! Inside a cell the angle is parametrised by the half-angle tangent t about the cell's
//! centre, z = z_c·(1 + i·t)²/(1 + t²), so that no trigonometric function is evaluated in the
//! scan or in Brent's iterations.
//!
//! # Rates: the velocity system
//! With B1 as the ternary link's reference point, r_i = B_i − B1 and u_i the unit vector along
//! A_i → B_i, projecting each closure's time derivative on u_i removes the binary link's own
//! ω_i and leaves three equations in (v_B1, ω_T):
//!
//! u_i · v_B1 + (r_i × u_i)·ω_T = u_i · v_Ai,
//!
//! a 3×3 system K whose rows are the Plücker coordinates of the binary links' lines. Its
//! determinant vanishes when the three lines meet at one point (or are parallel): the triad's
//! dead point. The accelerations solve the same K with the centripetal terms
//! u_i·a_Ai − l_i·ω_i² + ω_T²·(r_i · u_i); then ω_i and ε_i follow from the components across
//! each binary link. The reported `det` is det K divided by the ternary link's size L_T (the
//! root-mean-square distance of its joints from their centroid), a dimensionless measure that
//! is independent of the reference point. The rates are refused ([`Error::Singular`]) when the
//! data lie within rounding of a branch point: the measure is the data's distance from it,
//! estimated from the fold's normal form ([`SINGULAR_BRANCH`](super::SINGULAR_BRANCH) derives the rule).
//!
//! # Tracking a mode along a cycle
//! [`TriadModes::nearest`] picks the mode nearest a reference pose, by the distance
//! D² = Σ|B_i − B_i′|². [`triad_tracked`] is the fast path: Newton's method on the three
//! closures from the previous pose (F is not formed), accepted only when a certificate proves
//! that the root it reached is the mode the full bracket would pick (see its documentation
//! for the rule).

use super::fold::{split_steps, Leg, Legs};
use super::link::LinkMotion;
use super::motion::PointMotion;
use super::trig_cubic::{n1, Cubic};
use super::trig_roots::{checked_roots, times_pow2, unit, unit_exponent, CLOSES, SAME_MODE};
use crate::angle::{cross, direction, perp};
use crate::error::{finite, finite2, positive, Error, Result};
use nalgebra::{Complex, Matrix3, Point2, Vector2, Vector3};

type C = Complex<f64>;

const GROUP: &str = "triad";
/// The name of the triad's conditioning measure in [`Error::Singular`].
const MEASURE: &str = "det(velocity system)/L_T";
/// The most assembly modes a triad can have: the degree of the eliminated equation's sextic.
pub const MAX_TRIAD_MODES: usize = 6;
/// The former threshold on μ = |det K|/L_T of a group of the 3rd class with a sliding pair,
/// kept for callers that name it: no solver of the crate reads it any more. μ ≈ c·√ε at a
/// branch point computed in floating point (c the fold's curvature ratio, spread over
/// decades), so no absolute threshold on it separates a branch point from a regular pose
/// near one; both kinds of triad now refuse their rates and reactions by the data's
/// distance from the branch point, [`SINGULAR_BRANCH`](super::SINGULAR_BRANCH).
pub const SINGULAR_TRIAD: f64 = 1.5e-6;
/// The dimensions of a triad: the lengths of the three binary links and the ternary link's
/// triangle.
///
/// The ternary link's own frame has its origin at B1 and its x axis along B1 → B2, so B2 lies
/// at (`l_b1b2`, 0) and B3 at (`b3_along`, `b3_across`) (as in
/// [`LinkMotion::point_at`]). The three joints may lie on one line (a straight ternary link).
///
/// # Examples
/// An equilateral ternary link of side 0.2 m on legs of 0.3, 0.35 and 0.4 m:
/// ```
/// use tmm::kinematics::TriadDims;
/// let dims = TriadDims::new([0.3, 0.35, 0.4], 0.2, 0.1, 0.2 * 0.75f64.sqrt());
/// assert_eq!(dims.l[1], 0.35);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadDims {
    /// l_A1B1, l_A2B2, l_A3B3: the binary links' lengths, m.
    pub l: [f64; 3],
    /// l_B1B2, the side B1 B2 of the ternary link, m.
    pub l_b1b2: f64,
    /// B3's coordinate along B1 → B2, m.
    pub b3_along: f64,
    /// B3's coordinate across B1 → B2 (to the left of it), m.
    pub b3_across: f64,
}

impl TriadDims {
    /// The dimensions from the binary links' lengths and the ternary link's frame coordinates.
    #[must_use]
    pub fn new(l: [f64; 3], l_b1b2: f64, b3_along: f64, b3_across: f64) -> Self {
        Self {
            l,
            l_b1b2,
            b3_along,
            b3_across,
        }
    }

    /// The joints B1, B2, B3 in the ternary link's frame (B1 at the origin).
    #[must_use]
    pub fn local_joints(&self) -> [Vector2<f64>; 3] {
        [
            Vector2::zeros(),
            Vector2::new(self.l_b1b2, 0.0),
            Vector2::new(self.b3_along, self.b3_across),
        ]
    }

    /// L_T, the ternary link's size: the root-mean-square distance of its joints from their
    /// centroid, m (the scale of the triad's conditioning measure).
    #[must_use]
    pub fn ternary_size(&self) -> f64 {
        (self.ternary_moment() / 3.0).sqrt()
    }

    /// Σ|β_i − β̄|², the polar moment of the joints about their centroid, m².
    pub(super) fn ternary_moment(&self) -> f64 {
        // Σ|β_i|² − |Σβ_i|²/3, with β_1 = 0.
        let (x, y) = (self.l_b1b2 + self.b3_along, self.b3_across);
        self.l_b1b2 * self.l_b1b2 + self.b3_along * self.b3_along + y * y - (x * x + y * y) / 3.0
    }

    fn validate(&self) -> Result<()> {
        positive("l_A1B1", self.l[0])?;
        positive("l_A2B2", self.l[1])?;
        positive("l_A3B3", self.l[2])?;
        positive("l_B1B2", self.l_b1b2)?;
        finite("B3 along", self.b3_along)?;
        finite("B3 across", self.b3_across)?;
        Ok(())
    }
}

/// One assembly mode of a triad: where its joints are.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadPose {
    /// The ternary link's joints B1, B2, B3.
    pub b: [Point2<f64>; 3],
    /// θ, the ternary link's angle: the direction of B1 → B2, in [0, 2π).
    pub theta: f64,
    /// φ_i, the direction of A_i → B_i of each binary link, in [0, 2π).
    pub phi: [f64; 3],
    /// det K / L_T, the conditioning of the velocity system (see the module docs): zero when
    /// the lines of the three binary links meet at one point, and near zero where two modes
    /// merge.
    pub det: f64,
}

impl TriadPose {
    /// D² = Σ|B_i − B_i′|², the squared distance between two poses of a triad, m².
    #[must_use]
    pub fn distance_squared(&self, other: &TriadPose) -> f64 {
        (0..3)
            .map(|i| (self.b[i] - other.b[i]).norm_squared())
            .sum()
    }
}

/// All assembly modes of a triad at one position, in the order of θ (at most
/// [`MAX_TRIAD_MODES`]).
pub type TriadModes = AssemblyModes<MAX_TRIAD_MODES>;

/// All assembly modes of a group of the 3rd class at one position, in the order of the
/// ternary link's angle θ (at most `N`); no heap. [`TriadModes`] and
/// [`SliderTriadModes`](super::SliderTriadModes) are its two kinds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AssemblyModes<const N: usize> {
    count: usize,
    poses: [TriadPose; N],
}

impl<const N: usize> AssemblyModes<N> {
    /// No mode yet.
    pub(super) fn empty() -> Self {
        let blank = TriadPose {
            b: [Point2::origin(); 3],
            theta: 0.0,
            phi: [0.0; 3],
            det: 0.0,
        };
        Self {
            count: 0,
            poses: [blank; N],
        }
    }

    /// Adds `pose` unless a mode within `tol` (by D) is there already or all `N` are taken.
    pub(super) fn push_distinct(&mut self, pose: TriadPose, tol: f64) {
        let seen = self
            .as_slice()
            .iter()
            .any(|m| m.distance_squared(&pose) <= tol * tol);
        if !seen && self.count < N {
            self.poses[self.count] = pose;
            self.count += 1;
        }
    }

    /// The modes with their joints multiplied by 2^k (angles and the dimensionless `det`
    /// unchanged): back from the unit frame a search ran in.
    pub(super) fn scaled(mut self, k: i32) -> Self {
        for pose in &mut self.poses[..self.count] {
            pose.b = pose
                .b
                .map(|p| Point2::new(times_pow2(p.x, k), times_pow2(p.y, k)));
        }
        self
    }

    /// Orders the modes by θ.
    pub(super) fn sort(&mut self) {
        self.poses[..self.count].sort_by(|p, q| p.theta.total_cmp(&q.theta));
    }

    /// The modes, ordered by the ternary link's angle θ.
    #[must_use]
    pub fn as_slice(&self) -> &[TriadPose] {
        &self.poses[..self.count]
    }

    /// The number of modes.
    #[must_use]
    pub fn len(&self) -> usize {
        self.count
    }

    /// Never true for a value returned by [`triad_modes`] or
    /// [`slider_triad_modes`](super::slider_triad_modes) (a group without modes is an error).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The mode nearest `reference` by D² = Σ|B_i − B_i′|² (the continuity rule along a
    /// cycle: pass the previous position's pose).
    ///
    /// # Panics
    /// Never for a value returned by [`triad_modes`] or
    /// [`slider_triad_modes`](super::slider_triad_modes), which hold at least one mode.
    #[must_use]
    pub fn nearest(&self, reference: &TriadPose) -> &TriadPose {
        self.as_slice()
            .iter()
            .min_by(|p, q| {
                p.distance_squared(reference)
                    .total_cmp(&q.distance_squared(reference))
            })
            .expect("a triad's modes are never empty")
    }
}

/// The solved triad with velocities and accelerations.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadState {
    /// The joints B1, B2, B3 with their velocities and accelerations.
    pub b: [PointMotion; 3],
    /// The ternary link: origin B1, angle θ (direction of B1 → B2), ω_T, ε_T.
    pub ternary: LinkMotion,
    /// The binary links: origin A_i, angle φ_i (direction of A_i → B_i), ω_i, ε_i.
    pub binary: [LinkMotion; 3],
    /// det K / L_T, as in [`TriadPose::det`].
    pub det: f64,
}

impl TriadState {
    /// The pose of this state (to track the mode at the next position).
    #[must_use]
    pub fn pose(&self) -> TriadPose {
        TriadPose {
            b: [self.b[0].p, self.b[1].p, self.b[2].p],
            theta: self.ternary.angle,
            phi: [
                self.binary[0].angle,
                self.binary[1].angle,
                self.binary[2].angle,
            ],
            det: self.det,
        }
    }
}

/// Every assembly mode of a triad with its outer joints at `a`.
///
/// The eliminated equation F(θ) = 0 in the ternary link's angle is scanned over the whole
/// circle with a certificate per cell (module docs), so no mode is missed and none is found
/// twice; each mode closes its three binary links to rounding.
///
/// # Examples
/// A triad built from a pose: the ternary link B1 = (0, 0), B2 = (1, 0), B3 = (0.5, 0.8) m on
/// legs of 1 m pointing straight down from B1, up and right from B2 and straight up from B3.
/// The generating pose is one of the modes, and every mode closes all three legs.
/// ```
/// use nalgebra::Point2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{triad_modes, TriadDims};
/// let dims = TriadDims::new([1.0, 1.0, 1.0], 1.0, 0.5, 0.8);
/// let a = [Point2::new(0.0, -1.0), Point2::new(1.6, 0.8), Point2::new(0.5, 1.8)];
/// let modes = triad_modes(a, &dims)?;
/// assert!(modes.len() >= 1 && modes.len() <= 6);
/// assert!(modes.as_slice().iter().any(|m| (m.b[0] - Point2::origin()).norm() < 1e-12));
/// for m in modes.as_slice() {
///     for i in 0..3 {
///         assert_relative_eq!((m.b[i] - a[i]).norm(), 1.0, epsilon = 1e-12);
///     }
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - [`Error::NonFinite`] / [`Error::NonPositive`] for bad input;
/// - [`Error::NotAssemblable`] with `group = "triad"` when F has no root (`gap`: by how much
///   the radical centre of the three circles misses them, at the best orientation scanned);
/// - [`Error::Singular`] with `measure = "eliminated equation F(theta)"` when F vanishes
///   identically: the group moves (a triad with a mobility, such as equal legs between similar
///   triangles), and its modes form a continuum.
pub fn triad_modes(a: [Point2<f64>; 3], dims: &TriadDims) -> Result<TriadModes> {
    validate_points(a)?;
    dims.validate()?;
    // Solved in the unit frame (scale-free at any size: the data times a power of two).
    let k = unit_exponent(a.iter().flat_map(|p| [p.x, p.y]).chain(dims.l).chain([
        dims.l_b1b2,
        dims.b3_along,
        dims.b3_across,
    ]));
    let s = |x: f64| times_pow2(x, k);
    let unit_dims = TriadDims::new(
        dims.l.map(s),
        s(dims.l_b1b2),
        s(dims.b3_along),
        s(dims.b3_across),
    );
    unit_dims.validate().map_err(|_| Error::Overflow {
        what: "triad: a length underflows to zero against the group's other dimensions",
    })?;
    let unit_a = a.map(|p| Point2::new(s(p.x), s(p.y)));
    match unit_modes(unit_a, &unit_dims) {
        Ok(modes) => Ok(modes.scaled(-k)),
        Err(Error::NotAssemblable { group, gap }) => Err(Error::NotAssemblable {
            group,
            gap: times_pow2(gap, -k),
        }),
        Err(e) => Err(e),
    }
}

/// [`triad_modes`] on valid data of the unit frame.
fn unit_modes(a: [Point2<f64>; 3], dims: &TriadDims) -> Result<TriadModes> {
    let e = Eliminated::new(a, dims);
    let overflow = "triad: eliminated equation";
    let roots = checked_roots(&e.cubic, &e.cubic.f, e.cubic.s, e.scale, GROUP, overflow)?;
    let mut modes = TriadModes::empty();
    let tol = SAME_MODE * e.length();
    for r in 0..roots.n {
        for pose in e
            .poses(roots.z[r], roots.multiple[r], roots.double[r], dims)
            .into_iter()
            .flatten()
        {
            modes.push_distinct(pose, tol);
        }
        // A plateau of F within its rounding of zero (the three circles nearly coaxal: D and
        // W vanish together): the closures sort its modes out from samples across it.
        for z in roots.plateau(r) {
            for pose in e.poses(z, true, false, dims).into_iter().flatten() {
                modes.push_distinct(pose, tol);
            }
        }
        // Across a double root's stretch: only regular poses are modes of their own.
        for z in roots.stretch(r) {
            for pose in e.poses(z, true, false, dims).into_iter().flatten() {
                if super::trig_roots::regular_mode(triad_rates_at(a, dims, &pose)) {
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
    modes.sort();
    Ok(modes)
}

/// The fast path of tracking: the mode reached by Newton's method on the three closures from
/// `previous`, or `None` when it cannot be certified to be the mode that
/// [`triad_modes`]`(a, dims)?.`[`nearest`](TriadModes::nearest)`(previous)` returns.
///
/// The unknowns are the ternary link's centroid c and angle θ; the closures
/// ½(|B_i − A_i|² − l_i²) are exactly quadratic in them (up to the rotation's remainder), so
/// any other root lies at least D₊ ≈ σ/C from the one reached, by the distance
/// D² = Σ|B_i − B_i′|² of [`nearest`](TriadModes::nearest) (σ a lower bound of the
/// Jacobian's least singular value, C the closures' curvature bound). The root is accepted
/// when twice its distance from `previous` is below D₊ − D₋ (the full rule and its derivation
/// are in the module `triad_newton`). Near a merger of modes σ vanishes and the bracket
/// decides. `None` also for invalid input (the full path names the error).
#[must_use]
pub fn triad_tracked(
    a: [Point2<f64>; 3],
    dims: &TriadDims,
    previous: &TriadPose,
) -> Option<TriadPose> {
    if !(valid_points(a) && valid_points(previous.b) && dims.validate().is_ok()) {
        return None;
    }
    Some(super::triad_fast::track(a, dims, previous)?.pose(&a, dims))
}

/// Positions, velocities and accelerations of a triad, in the mode nearest `previous`.
///
/// Tries the fast path [`triad_tracked`] first and falls back to [`triad_modes`] with
/// [`TriadModes::nearest`]; then solves the velocity and acceleration systems
/// ([`triad_rates`]).
///
/// # Examples
/// The triad of [`triad_modes`]' example, its outer joints at rest but A1 moving up at
/// 0.1 m/s: B1 follows (the leg A1 B1 is along the motion, so at this instant the group moves
/// as it would if A1 B1 were rigid with the frame moving).
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{triad, triad_modes, PointMotion, TriadDims};
/// let dims = TriadDims::new([1.0, 1.0, 1.0], 1.0, 0.5, 0.8);
/// let p = [Point2::new(0.0, -1.0), Point2::new(1.6, 0.8), Point2::new(0.5, 1.8)];
/// let modes = triad_modes(p, &dims)?;
/// let start = modes.as_slice().iter().find(|m| m.b[0].coords.norm() < 1e-9).unwrap();
/// let a = [
///     PointMotion::new(p[0], Vector2::new(0.0, 0.1), Vector2::zeros()),
///     PointMotion::fixed(p[1]),
///     PointMotion::fixed(p[2]),
/// ];
/// let s = triad(a, &dims, start)?;
/// // Closure of every leg, and the velocity of B_i along its leg equals A_i's.
/// for i in 0..3 {
///     let u = (s.b[i].p - a[i].p) / 1.0;
///     assert_relative_eq!(u.norm(), 1.0, epsilon = 1e-12);
///     assert_relative_eq!(s.b[i].v.dot(&u), a[i].v.dot(&u), epsilon = 1e-12);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`triad_modes`] and [`triad_rates`].
pub fn triad(a: [PointMotion; 3], dims: &TriadDims, previous: &TriadPose) -> Result<TriadState> {
    let p = [a[0].p, a[1].p, a[2].p];
    let valid = super::rrr::all_finite([
        p[0].x,
        p[0].y,
        p[1].x,
        p[1].y,
        p[2].x,
        p[2].y,
        dims.b3_along,
        dims.b3_across,
    ]) & (dims.l[0] > 0.0)
        & (dims.l[1] > 0.0)
        & (dims.l[2] > 0.0)
        & (dims.l_b1b2 > 0.0)
        & super::rrr::all_finite([dims.l[0], dims.l[1], dims.l[2], dims.l_b1b2]);
    if valid
        && valid_points(previous.b)
        && let Some(t) = super::triad_fast::track(p, dims, previous)
        && let Some(state) = t.state(&a, dims)
    {
        return Ok(state);
    }
    triad_checked(a, dims, previous)
}

/// [`triad`] step by step, naming what fails.
#[cold]
#[inline(never)]
fn triad_checked(
    a: [PointMotion; 3],
    dims: &TriadDims,
    previous: &TriadPose,
) -> Result<TriadState> {
    let p = [a[0].p, a[1].p, a[2].p];
    let pose = match triad_tracked(p, dims, previous) {
        Some(pose) => pose,
        None => *triad_modes(p, dims)?.nearest(previous),
    };
    triad_rates(a, dims, &pose)
}

/// Velocities and accelerations of a triad in a given mode (`pose`, one of
/// [`triad_modes`]' at the positions of `a`), from the velocity system K (module docs).
///
/// # Errors
/// - [`Error::NonFinite`] for bad input;
/// - [`Error::Singular`] with `measure = "distance from a branch point/size"` when that
///   distance η ≤ [`SINGULAR_BRANCH`](super::SINGULAR_BRANCH): the lines of the three binary links meet at one point
///   (a dead point of the group, or two modes merging), to within what rounding can tell
///   (the rates would carry fewer than four digits);
/// - [`Error::Overflow`] when a rate overflows.
pub fn triad_rates(a: [PointMotion; 3], dims: &TriadDims, pose: &TriadPose) -> Result<TriadState> {
    for m in &a {
        m.validate(["A.x", "A.y", "v_A.x", "v_A.y", "a_A.x", "a_A.y"])?;
    }
    for b in &pose.b {
        finite2(["B.x", "B.y"], b.coords)?;
    }
    dims.validate()?;
    let b = pose.b;
    let r = [Vector2::zeros(), b[1] - b[0], b[2] - b[0]];
    let leg = [b[0] - a[0].p, b[1] - a[1].p, b[2] - a[2].p];
    let len = [leg[0].norm(), leg[1].norm(), leg[2].norm()];
    let u = [leg[0] / len[0], leg[1] / len[1], leg[2] / len[2]];
    let k = velocity_matrix(u, r);
    let lt = dims.ternary_size();
    let det = k.determinant() / lt;
    ensure_off_branch(u, r, len, lt)?;
    let k_inv = k.try_inverse().ok_or(Error::Singular {
        what: GROUP,
        measure: MEASURE,
        value: det,
    })?;
    let vel = k_inv * Vector3::from_fn(|i, _| u[i].dot(&a[i].v));
    let (v1, omega_t) = (Vector2::new(vel.x, vel.y), vel.z);
    let vb = [v1, v1 + omega_t * perp(r[1]), v1 + omega_t * perp(r[2])];
    let omega = [0, 1, 2].map(|i| perp(u[i]).dot(&(vb[i] - a[i].v)) / len[i]);
    let acc = k_inv
        * Vector3::from_fn(|i, _| {
            u[i].dot(&a[i].a) - len[i] * omega[i] * omega[i] + omega_t * omega_t * r[i].dot(&u[i])
        });
    let (a1, eps_t) = (Vector2::new(acc.x, acc.y), acc.z);
    let ternary = LinkMotion {
        origin: PointMotion::new(b[0], v1, a1),
        angle: direction(r[1]),
        omega: omega_t,
        epsilon: eps_t,
    };
    let bm = [0, 1, 2].map(|i| ternary.motion_of(b[i]));
    let eps = [0, 1, 2].map(|i| perp(u[i]).dot(&(bm[i].a - a[i].a)) / len[i]);
    let binary = [0, 1, 2].map(|i| LinkMotion {
        origin: a[i],
        angle: direction(leg[i]),
        omega: omega[i],
        epsilon: eps[i],
    });
    let out = TriadState {
        b: bm,
        ternary,
        binary,
        det,
    };
    let finite = bm
        .iter()
        .all(|m| m.v.iter().chain(m.a.iter()).all(|x| x.is_finite()))
        && omega.iter().chain(eps.iter()).all(|x| x.is_finite())
        && omega_t.is_finite()
        && eps_t.is_finite();
    if finite {
        Ok(out)
    } else {
        Err(Error::Overflow {
            what: "triad: rates",
        })
    }
}

/// [`triad_rates`] of `pose` at rest (only whether it fails matters to the caller).
#[cold]
fn triad_rates_at(a: [Point2<f64>; 3], dims: &TriadDims, pose: &TriadPose) -> Result<TriadState> {
    triad_rates(a.map(PointMotion::fixed), dims, pose)
}

/// The branch-point test of a posed revolute triad, one rule for its rates
/// ([`triad_rates`]) and its reactions
/// ([`kinetostatics::Triad::solve`](crate::kinetostatics::Triad::solve)):
/// [`Error::Singular`] naming `distance from a branch point/size` when η ≤
/// [`SINGULAR_BRANCH`](super::SINGULAR_BRANCH) (or is NaN). `u` are the legs' unit vectors A_i → B_i, `r` the arms
/// B_i − B1, `len` the legs' lengths and `lt` the ternary link's size L_T.
pub(crate) fn ensure_off_branch(
    u: [Vector2<f64>; 3],
    r: [Vector2<f64>; 3],
    len: [f64; 3],
    lt: f64,
) -> Result<()> {
    hinged_legs(u, r, len, lt).ensure_off_branch(GROUP)
}

/// The legs of a posed revolute triad for the fold's normal form.
#[inline]
pub(super) fn hinged_legs(
    u: [Vector2<f64>; 3],
    r: [Vector2<f64>; 3],
    len: [f64; 3],
    lt: f64,
) -> Legs {
    Legs {
        w: u,
        r,
        kind: len.map(Leg::Hinged),
        lt,
    }
}

/// The velocity system K of a triad: row i is (u_i, r_i × u_i).
fn velocity_matrix(u: [Vector2<f64>; 3], r: [Vector2<f64>; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| match j {
        0 => u[i].x,
        1 => u[i].y,
        _ => cross(r[i], u[i]),
    })
}

fn validate_points(a: [Point2<f64>; 3]) -> Result<()> {
    finite2(["A1.x", "A1.y"], a[0].coords)?;
    finite2(["A2.x", "A2.y"], a[1].coords)?;
    finite2(["A3.x", "A3.y"], a[2].coords)?;
    Ok(())
}

fn valid_points(a: [Point2<f64>; 3]) -> bool {
    a.iter().all(|p| p.x.is_finite() && p.y.is_finite())
}

/// The eliminated equation of one triad at one position, origin at A1.
struct Eliminated {
    /// A_1 (the origin of the complex plane below).
    a1: Point2<f64>,
    /// A_i − A_1 and β_i as complex numbers.
    a: [C; 3],
    beta: [C; 3],
    l: [f64; 3],
    /// W's Laurent coefficients of z^-1, z^0, z^1, z^2.
    w: [C; 4],
    /// D = e0 + 2·Re(e1·z).
    e0: f64,
    e1: C,
    /// F = |W|² − l1²·D².
    cubic: Cubic,
    /// |e0| + 2|e1|, the size of D.
    dscale: f64,
    /// The size of the terms that make F (for the rounding tolerance).
    scale: f64,
}

impl Eliminated {
    fn new(a: [Point2<f64>; 3], dims: &TriadDims) -> Self {
        let rel = |p: Point2<f64>| C::new(p.x - a[0].x, p.y - a[0].y);
        let av = [C::new(0.0, 0.0), rel(a[1]), rel(a[2])];
        let beta = [
            C::new(0.0, 0.0),
            C::new(dims.l_b1b2, 0.0),
            C::new(dims.b3_along, dims.b3_across),
        ];
        let l = dims.l;
        let l1s = l[0] * l[0];
        // s_k = σ_k − Re(γ_k·z), c_k = a_k − β_k·z (k = 1, 2: the joints 2 and 3).
        let sigma = |k: usize| 0.5 * (l1s + av[k].norm_sqr() + beta[k].norm_sqr() - l[k] * l[k]);
        let gamma = |k: usize| av[k].conj() * beta[k];
        // Laurent coefficients (z^-1, z^0, z^1, z^2) of s_k·c_m.
        let sc = |k: usize, m: usize| {
            let (s, g) = (sigma(k), gamma(k));
            [
                -0.5 * g.conj() * av[m],
                s * av[m] + 0.5 * g.conj() * beta[m],
                -s * beta[m] - 0.5 * g * av[m],
                0.5 * g * beta[m],
            ]
        };
        let (p, q) = (sc(2, 1), sc(1, 2));
        let w = [p[0] - q[0], p[1] - q[1], p[2] - q[2], p[3] - q[3]];
        let e0 = (av[1].conj() * av[2] + beta[1].conj() * beta[2]).im;
        let mu = beta[1] * av[2].conj() - av[1].conj() * beta[2];
        let e1 = C::new(0.0, -0.5) * mu;
        let wsum = n1(w[0]) + n1(w[1]) + n1(w[2]) + n1(w[3]);
        let dscale = e0.abs() + 2.0 * n1(e1);
        let scale = wsum * wsum + l1s * dscale * dscale;
        Self {
            a1: a[0],
            a: av,
            beta,
            l,
            w,
            e0,
            e1,
            cubic: Cubic::new(&w, e0, e1, l1s, scale),
            dscale,
            scale,
        }
    }

    /// The triad's largest dimension (for closure tolerances), m.
    fn length(&self) -> f64 {
        self.a
            .iter()
            .chain(self.beta.iter())
            .map(|c| c.norm())
            .chain(self.l)
            .fold(0.0, f64::max)
    }

    /// W(z) and D(z).
    fn w_d(&self, z: C) -> (C, f64) {
        let w = &self.w;
        let wz = w[0] * z.conj() + w[1] + z * (w[2] + z * w[3]);
        (wz, self.e0 + 2.0 * (self.e1 * z).re)
    }

    /// The poses at a root z of F: B1 from the radical axes, then Newton's method on the
    /// three closures in (B1, θ), whose matrix is the velocity system K. Where the radical
    /// axes are nearly parallel (D ≈ 0, the three circles nearly coaxal) or the root is
    /// `multiple`, two modes can share (nearly) one θ with different B1: then both
    /// intersections of two of the circles are polished, and every candidate that closes is
    /// returned.
    /// A `double` root (two merged within rounding) keeps its pose from the radical axes
    /// unpolished where that closes to [`CLOSES`] of the size; otherwise, and at a cluster,
    /// the mode found's partner across the fold ([`split_fold`](Self::split_fold)) is added.
    fn poses(
        &self,
        z: C,
        multiple: bool,
        double: bool,
        dims: &TriadDims,
    ) -> [Option<TriadPose>; 4] {
        let (wz, d) = self.w_d(z);
        if double && d.abs() > 1e-3 * self.dscale {
            let p = C::new(0.0, 1.0) * wz / d;
            let p = Vector2::new(p.re, p.im);
            if let Some(pose) = self.polish_steps(p, z, dims, 0, CLOSES) {
                return [Some(pose), None, None, None];
            }
        }
        let found = if d.abs() > 1e-3 * self.dscale && !multiple {
            let p = C::new(0.0, 1.0) * wz / d;
            [self.polish(Vector2::new(p.re, p.im), z, dims), None]
        } else {
            match self.two_circles(z) {
                Some([p, q]) => [self.polish(p, z, dims), self.polish(q, z, dims)],
                None => [None, None],
            }
        };
        // Two modes of one fold that F's rounding could not split (a cluster of roots, or a
        // double root whose pose at F's extremum does not close): the partner of the mode
        // found, from the fold's normal form.
        let partners = match found.iter().flatten().next() {
            Some(pose) if multiple || double => {
                let side = pose.b[1] - pose.b[0];
                let zp = C::new(side.x, side.y) / side.norm();
                self.split_fold(pose.b[0] - self.a1, zp, dims)
                    .unwrap_or([None, None])
            }
            _ => [None, None],
        };
        [found[0], found[1], partners[0], partners[1]]
    }

    /// The two modes of a fold whose roots of F were merged within F's rounding (a cluster,
    /// or a double root) although the closures tell them apart: F's rounding scales with its
    /// terms, the closures' with the size, and near a fold with F's terms cancelling, F's
    /// dip between the two roots can be below the one while the two poses are far apart by
    /// the other (seen: two modes 1e-4 of the size apart whose angles differ by less than
    /// 1e-6 rad). From a pose B1 − A1 = `p` at z near the fold, the steps across it of the
    /// fold's normal form ([`split_steps`]) along the least singular direction of K′, each
    /// polished. `None` when the model has no two real roots (the fold's other side: no pair).
    fn split_fold(
        &self,
        p: Vector2<f64>,
        z: C,
        dims: &TriadDims,
    ) -> Option<[Option<TriadPose>; 2]> {
        let b1 = self.a1 + p;
        let (u, r, h) = self.legs(b1, z);
        let legs = hinged_legs(u, r, self.l, dims.ternary_size());
        let fold = legs.fold(&velocity_matrix(u, r))?;
        let t = split_steps(&fold, &h)?;
        let at = |t: f64| {
            let zt = unit(z * C::new(1.0, t * fold.d_theta));
            self.polish(p + t * fold.d_o, zt, dims)
        };
        Some([at(t[0]), at(t[1])])
    }

    /// The pose from B1 − A1 = `p` at z, polished by Newton's method on the closures (each
    /// step halved until it reduces the closure error, kept while one does); `None` (no
    /// mode: [`CLOSES`] gives the reasons) when it does not close to [`CLOSES`] of the size.
    fn polish(&self, p: Vector2<f64>, z: C, dims: &TriadDims) -> Option<TriadPose> {
        self.polish_steps(p, z, dims, 48, CLOSES)
    }

    /// [`polish`](Self::polish) with at most `steps` Newton steps, `None` unless the pose
    /// closes to `within` of the size.
    fn polish_steps(
        &self,
        p: Vector2<f64>,
        z: C,
        dims: &TriadDims,
        steps: usize,
        within: f64,
    ) -> Option<TriadPose> {
        let mut b1 = self.a1 + p;
        let mut z = z;
        let length = self.length();
        let mut err = self.closure(b1, z);
        // To the rounding floor: until a step (halved up to six times) no longer reduces the
        // closure error. (Stopping at 1e-15 of the size left poses 5× the floor off along a
        // near fold's null direction, which differences of poses over small steps amplify.)
        for _ in 0..steps {
            if err == 0.0 {
                break;
            }
            let (u, r, h) = self.legs(b1, z);
            let Some(k_inv) = velocity_matrix(u, r).try_inverse() else {
                break;
            };
            // Near a branch point K is nearly singular: Newton's step along its null direction
            // overshoots (and at a double root it only halves the error), so the step is halved
            // until the closure error falls, as a damped Newton method.
            let mut step = k_inv * (-h);
            let mut better = None;
            for _ in 0..6 {
                let b1n = b1 + Vector2::new(step.x, step.y);
                let zn = unit(z * C::new(1.0, step.z));
                let errn = self.closure(b1n, zn);
                if errn < err {
                    better = Some((b1n, zn, errn));
                    break;
                }
                step *= 0.5;
            }
            match better {
                Some(next) => (b1, z, err) = next,
                None => break,
            }
        }
        if err.is_nan() || err > within * length {
            return None;
        }
        let (u, r, _) = self.legs(b1, z);
        let det = velocity_matrix(u, r).determinant() / dims.ternary_size();
        let b = self.joints(b1, z);
        let a = self.outer();
        Some(TriadPose {
            b,
            theta: direction(Vector2::new(z.re, z.im)),
            phi: [0, 1, 2].map(|i| direction(b[i] - a[i])),
            det,
        })
    }

    /// The two intersections (B1 − A1) of the first circle with the other one whose centre
    /// is farther from A1 (the tangent point twice when they touch).
    fn two_circles(&self, z: C) -> Option<[Vector2<f64>; 2]> {
        let c = [1, 2].map(|k| self.a[k] - self.beta[k] * z);
        let k = if c[0].norm() >= c[1].norm() { 0 } else { 1 };
        let (ck, lk) = (c[k], self.l[k + 1]);
        let dist = ck.norm();
        if dist == 0.0 {
            return None;
        }
        let e = ck / dist;
        let l0 = self.l[0];
        let x = 0.5 * (dist + (l0 - lk) * (l0 + lk) / dist);
        let h = (l0 * l0 - x * x).max(0.0).sqrt();
        Some([C::new(x, h), C::new(x, -h)].map(|w| {
            let p = e * w;
            Vector2::new(p.re, p.im)
        }))
    }

    fn outer(&self) -> [Point2<f64>; 3] {
        [0, 1, 2].map(|i| self.a1 + Vector2::new(self.a[i].re, self.a[i].im))
    }

    fn joints(&self, b1: Point2<f64>, z: C) -> [Point2<f64>; 3] {
        let r = |i: usize| {
            let r = self.beta[i] * z;
            b1 + Vector2::new(r.re, r.im)
        };
        [b1, r(1), r(2)]
    }

    /// The unit vectors of the legs, the arms r_i = B_i − B1, and the closure errors
    /// |B_i − A_i| − l_i.
    fn legs(&self, b1: Point2<f64>, z: C) -> ([Vector2<f64>; 3], [Vector2<f64>; 3], Vector3<f64>) {
        let b = self.joints(b1, z);
        let a = self.outer();
        let leg = [0, 1, 2].map(|i| b[i] - a[i]);
        let n = leg.map(|v| v.norm());
        (
            [0, 1, 2].map(|i| leg[i] / n[i]),
            [0, 1, 2].map(|i| b[i] - b1),
            Vector3::new(n[0] - self.l[0], n[1] - self.l[1], n[2] - self.l[2]),
        )
    }

    /// The largest closure error of a pose, m.
    fn closure(&self, b1: Point2<f64>, z: C) -> f64 {
        let b = self.joints(b1, z);
        let a = self.outer();
        (0..3)
            .map(|i| ((b[i] - a[i]).norm() - self.l[i]).abs())
            .fold(0.0, f64::max)
    }

    /// By how much the radical centre of the three circles misses them (the largest of the
    /// three misses), at the best of 1024 orientations: the `gap` of
    /// [`Error::NotAssemblable`].
    #[cold]
    fn gap(&self) -> f64 {
        let n = 1024;
        let dscale = self.dscale;
        let mut best = f64::INFINITY;
        for j in 0..n {
            let th = std::f64::consts::TAU * j as f64 / n as f64;
            let z = C::new(th.cos(), th.sin());
            let (wz, d) = self.w_d(z);
            if d.abs() <= 1e-9 * dscale {
                continue;
            }
            let p = C::new(0.0, 1.0) * wz / d;
            let miss = (0..3)
                .map(|i| ((p - (self.a[i] - self.beta[i] * z)).norm() - self.l[i]).abs())
                .fold(0.0, f64::max);
            best = best.min(miss);
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn example() -> (TriadDims, [Point2<f64>; 3]) {
        (
            TriadDims::new([1.0, 1.0, 1.0], 1.0, 0.5, 0.8),
            [
                Point2::new(0.0, -1.0),
                Point2::new(1.6, 0.8),
                Point2::new(0.5, 1.8),
            ],
        )
    }

    /// F from its coefficients equals |W|² − l1²·D² evaluated geometrically.
    #[test]
    fn triad_coefficients_match_the_geometry() {
        let (dims, a) = example();
        let e = Eliminated::new(a, &dims);
        for j in 0..37 {
            let th = 0.17 * j as f64;
            let z = C::new(th.cos(), th.sin());
            // Geometric: c_k = a_k − β_k z, s_k = (l1² + |c_k|² − l_k²)/2, W = s_3 c_2 − s_2 c_3.
            let c = [0, 1, 2].map(|k| e.a[k] - e.beta[k] * z);
            let s = [0, 1, 2].map(|k| 0.5 * (e.l[0].powi(2) + c[k].norm_sqr() - e.l[k].powi(2)));
            let w = s[2] * c[1] - s[1] * c[2];
            let d = (c[1].conj() * c[2]).im;
            let f = w.norm_sqr() - e.l[0].powi(2) * d * d;
            let (wz, dz) = e.w_d(z);
            assert!((wz - w).norm() < 1e-12);
            assert_relative_eq!(dz, d, epsilon = 1e-12);
            assert_relative_eq!(e.cubic.eval(z).0, f, epsilon = 1e-11);
            // F′ against a central difference.
            let hh = 1e-6;
            let fp = e.cubic.eval(C::new((th + hh).cos(), (th + hh).sin())).0;
            let fm = e.cubic.eval(C::new((th - hh).cos(), (th - hh).sin())).0;
            assert_relative_eq!(e.cubic.eval(z).1, (fp - fm) / (2.0 * hh), epsilon = 1e-6);
        }
    }
}
