#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Any rigid group of links joined by hinges, by its closure equations: the general fallback
//! for an Assur group of a class that has no closed form (the six-link group of the "double
//! butterfly" eight-bar, a group of the 4th class, …).
//!
//! # The equations
//! Link k's frame has its origin o_k and angle θ_k; a point given in its frame at l lies at
//! p_k(l) = o_k + R(θ_k)·l. Each hinge between two links of the group closes when
//! p_a(l_a) − p_b(l_b) = 0, each hinge to a known point P when p_k(l) − P = 0: with n links and
//! m hinges, 2m equations in the 3n unknowns q = (o_k, θ_k), and a rigid group has 2m = 3n.
//! The derivative of p_k(l) is ȯ_k + θ̇_k·J·R(θ_k)l (J the quarter turn), so the closure
//! Jacobian K has the blocks [I, J·R(θ_k)l] per link and hinge.
//!
//! - **Positions**: Newton's method on the closure equations, each step one LU solve of K.
//!   A group has many assembly modes (the double butterfly's six-link group has dozens at a
//!   given input) and no sign tells them apart, so the engine fixes the mode by continuation
//!   ([`HingedGroup::track`]): the known points move from their reference places to their
//!   places now along a path the caller gives, in steps small enough that each Newton
//!   corrector contracts at once from the tangent predictor; the mode is the one the
//!   reference pose turns into. [`HingedGroup::modes`] searches for all of them.
//! - **Rates**: the velocity and acceleration closure are linear with the same matrix:
//!   K·q̇ = (0 | v_P) and K·q̈ = (θ̇_a²·R l_a − θ̇_b²·R l_b | a_P + θ̇_k²·R l), one factorisation
//!   for both.
//! - **Reactions**: by virtual work the equilibrium of the links is Kᵀλ + Q = 0, with Q_k the
//!   resultant force on link k and its moment about o_k; λ at a hinge between links a and b is
//!   the force that b exerts on a, at a hinge to a known point the force of the known link on
//!   the group's link. So the statics needs no second matrix.
//!
//! The conditioning of all three is that of K with its angle columns divided by the group's
//! size L, which vanishes at a dead point or a branch point of the group. A translation
//! column ∂f/∂o is a pure number and an angle column ∂f/∂θ = J·R·l a length: K·D, D =
//! diag(1, 1, 1/L, …), is the Jacobian in the unknowns (o, L·θ), every one a length, so its
//! entries are pure numbers and its conditioning is the same for the group drawn at any scale
//! (the angle columns multiplied by L instead would weigh them by L² against the
//! translations: 10⁻⁶⁰ at L = 10³⁰, a regular group refused as singular). [`HingedGroup::conditioning`] gives σ_min/σ_max (an SVD, for planning and
//! the mode search); the rates and reactions report the reciprocal 1-norm condition
//! 1/(‖K‖₁‖K⁻¹‖₁), ‖K⁻¹‖₁ estimated from the LU they solve with anyway (Hager's method: a
//! few triangular solves, no SVD per solve). The two agree within a factor of the number of
//! unknowns 3n (the norms' equivalence), and the estimate is never below the true 1-norm
//! reciprocal condition (Hager's estimate of ‖K⁻¹‖₁ is a lower bound).
//!
//! A [`GroupWork`] keeps the Newton solves' buffers from one solve to the next
//! ([`HingedGroup::track_in`]): tracking a group along a cycle allocates nothing but the pose
//! it returns.

use super::link::LinkMotion;
use super::lu_work::Linear;
use super::motion::PointMotion;
use crate::angle::{normalize, perp, unit};
use crate::error::{Error, Result};
use crate::load::Load;
use nalgebra::{DMatrix, DVector, Point2, Vector2};

/// Where a hinge sits on a group's link: the link's index in the group and the hinge's point
/// in the link's frame.
pub type HingeEnd = (usize, Vector2<f64>);

/// A group of rigid links joined by hinges to each other and to known points.
#[derive(Debug, Clone, PartialEq)]
pub struct HingedGroup {
    /// The number of links.
    pub links: usize,
    /// The hinges between two of the group's links.
    pub inner: Vec<[HingeEnd; 2]>,
    /// The hinges to known points (given at each solve, in this order).
    pub outer: Vec<HingeEnd>,
}

/// A pose of a [`HingedGroup`]: each link's frame origin (m) and angle (rad).
#[derive(Debug, Clone, PartialEq)]
pub struct GroupPose {
    /// Each link's frame origin.
    pub origins: Vec<Point2<f64>>,
    /// Each link's frame angle.
    pub angles: Vec<f64>,
}

/// A group's motion: every link's motion and the conditioning of the scaled closure Jacobian
/// (its reciprocal 1-norm condition, module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct GroupMotion {
    /// Each link's motion (its frame origin's point motion, angle, ω, ε).
    pub links: Vec<LinkMotion>,
    /// The reciprocal 1-norm condition of the scaled closure Jacobian (module docs).
    pub conditioning: f64,
}

/// A group's reactions (module docs): at each inner hinge the force the hinge's second link
/// exerts on its first, at each outer hinge the force the known link exerts on the group.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupReactions {
    /// Per inner hinge, the force of its second link on its first, N.
    pub inner: Vec<Vector2<f64>>,
    /// Per outer hinge, the force of the known link on the group's link, N.
    pub outer: Vec<Vector2<f64>>,
    /// The reciprocal 1-norm condition of the scaled closure Jacobian (module docs).
    pub conditioning: f64,
}

/// The largest number of Newton steps of one solve.
const MAX_NEWTON: usize = 40;
/// Below this reciprocal condition the closure Jacobian carries no significant digit.
const SINGULAR_BELOW: f64 = 8.0 * f64::EPSILON;

impl GroupPose {
    fn to_q(&self) -> DVector<f64> {
        DVector::from_iterator(
            3 * self.angles.len(),
            self.origins
                .iter()
                .zip(&self.angles)
                .flat_map(|(o, &a)| [o.x, o.y, a]),
        )
    }

    /// Writes q = (o_k, θ_k) into `q` (resized when its length differs).
    fn write_q(&self, q: &mut DVector<f64>) {
        let n = 3 * self.angles.len();
        if q.len() != n {
            *q = DVector::zeros(n);
        }
        for (k, (o, &a)) in self.origins.iter().zip(&self.angles).enumerate() {
            q[3 * k] = o.x;
            q[3 * k + 1] = o.y;
            q[3 * k + 2] = a;
        }
    }

    fn from_q(q: &DVector<f64>) -> Self {
        let n = q.len() / 3;
        Self {
            origins: (0..n)
                .map(|k| Point2::new(q[3 * k], q[3 * k + 1]))
                .collect(),
            angles: (0..n).map(|k| q[3 * k + 2]).collect(),
        }
    }

    /// The largest distance between the two poses' hinge points, the angles' differences
    /// measured as arcs at `size`: how far apart two assembly modes are.
    #[must_use]
    pub fn distance(&self, other: &Self, size: f64) -> f64 {
        self.origins
            .iter()
            .zip(&other.origins)
            .map(|(a, b)| (a - b).norm())
            .chain(self.angles.iter().zip(&other.angles).map(|(a, b)| {
                size * (normalize(a - b + std::f64::consts::PI) - std::f64::consts::PI).abs()
            }))
            .fold(0.0, f64::max)
    }
}

impl HingedGroup {
    /// Checks that the group is rigid by count (2m = 3n), names links in range and holds
    /// finite points.
    ///
    /// # Errors
    /// [`Error::Description`] naming what is wrong.
    pub fn check(&self) -> Result<()> {
        let m = self.inner.len() + self.outer.len();
        let bad = |problem: String| Error::Description {
            item: "hinged group".to_owned(),
            problem,
        };
        if self.links == 0 || 2 * m != 3 * self.links {
            return Err(bad(format!(
                "{} links and {m} hinges: a rigid group needs 2·hinges = 3·links",
                self.links
            )));
        }
        let ends = self.inner.iter().flatten().chain(&self.outer);
        for &(k, l) in ends {
            if k >= self.links || !(l.x.is_finite() && l.y.is_finite()) {
                return Err(bad(format!(
                    "a hinge names link {k} (of {}) at [{}, {}]",
                    self.links, l.x, l.y
                )));
            }
        }
        if self.inner.iter().any(|[a, b]| a.0 == b.0) {
            return Err(bad("a hinge joins a link to itself".to_owned()));
        }
        Ok(())
    }

    fn rows(&self) -> usize {
        2 * (self.inner.len() + self.outer.len())
    }

    /// The point `l` of link `k` at `q`, with R(θ_k)·l.
    fn point(q: &DVector<f64>, (k, l): HingeEnd) -> (Point2<f64>, Vector2<f64>) {
        Self::point_at(q, unit(q[3 * k + 2]), (k, l))
    }

    /// [`point`](Self::point) with the unit vector e = (cos θ_k, sin θ_k) given.
    fn point_at(
        q: &DVector<f64>,
        e: Vector2<f64>,
        (k, l): HingeEnd,
    ) -> (Point2<f64>, Vector2<f64>) {
        let r = Vector2::new(e.x * l.x - e.y * l.y, e.y * l.x + e.x * l.y);
        (Point2::new(q[3 * k], q[3 * k + 1]) + r, r)
    }

    /// Each link's unit vector (cos θ_k, sin θ_k) at `q` into `rot`: one `sin_cos` per link
    /// for a residual and a Jacobian (the same bits as [`point`](Self::point)'s own).
    fn rotations(&self, q: &DVector<f64>, rot: &mut Vec<Vector2<f64>>) {
        rot.clear();
        rot.extend((0..self.links).map(|k| unit(q[3 * k + 2])));
    }

    /// The closure residual at `q` (inner hinges first, then outer).
    fn residual_q(&self, q: &DVector<f64>, outer: &[Point2<f64>]) -> DVector<f64> {
        let mut f = DVector::zeros(self.rows());
        let mut rot = Vec::new();
        self.rotations(q, &mut rot);
        self.residual_into(q, &rot, outer, &mut f);
        f
    }

    /// [`residual_q`](Self::residual_q) into `f` (of the group's number of rows; every entry
    /// written), the links' unit vectors `rot` given.
    fn residual_into(
        &self,
        q: &DVector<f64>,
        rot: &[Vector2<f64>],
        outer: &[Point2<f64>],
        f: &mut DVector<f64>,
    ) {
        let point = |end: HingeEnd| Self::point_at(q, rot[end.0], end).0;
        for (i, &[a, b]) in self.inner.iter().enumerate() {
            let d = point(a) - point(b);
            f[2 * i] = d.x;
            f[2 * i + 1] = d.y;
        }
        let base = 2 * self.inner.len();
        for (o, (&end, p)) in self.outer.iter().zip(outer).enumerate() {
            let d = point(end) - p;
            f[base + 2 * o] = d.x;
            f[base + 2 * o + 1] = d.y;
        }
    }

    /// The closure Jacobian K at `q` (module docs), its angle columns multiplied by `scale`.
    fn jacobian(&self, q: &DVector<f64>, scale: f64) -> DMatrix<f64> {
        let mut k = DMatrix::zeros(self.rows(), 3 * self.links);
        let mut rot = Vec::new();
        self.rotations(q, &mut rot);
        self.jacobian_into(q, &rot, scale, &mut k);
        k
    }

    /// [`jacobian`](Self::jacobian) into `k` (of the group's shape; zeroed first), the
    /// links' unit vectors `rot` given.
    fn jacobian_into(
        &self,
        q: &DVector<f64>,
        rot: &[Vector2<f64>],
        scale: f64,
        k: &mut DMatrix<f64>,
    ) {
        k.fill(0.0);
        let mut put = |row: usize, end: HingeEnd, sign: f64| {
            let r = Self::point_at(q, rot[end.0], end).1;
            let c = 3 * end.0;
            let t = perp(r) * scale;
            k[(row, c)] += sign;
            k[(row + 1, c + 1)] += sign;
            k[(row, c + 2)] += sign * t.x;
            k[(row + 1, c + 2)] += sign * t.y;
        };
        for (i, &[a, b]) in self.inner.iter().enumerate() {
            put(2 * i, a, 1.0);
            put(2 * i, b, -1.0);
        }
        let base = 2 * self.inner.len();
        for (o, &end) in self.outer.iter().enumerate() {
            put(base + 2 * o, end, 1.0);
        }
    }

    /// The largest closure gap of `pose` with the known points `outer`, m.
    #[must_use]
    pub fn residual(&self, pose: &GroupPose, outer: &[Point2<f64>]) -> f64 {
        let f = self.residual_q(&pose.to_q(), outer);
        f.as_slice()
            .chunks(2)
            .map(|c| c[0].hypot(c[1]))
            .fold(0.0, f64::max)
    }

    /// A step's size: its translations and its rotations as arcs at `size`.
    fn step_norm(dq: &DVector<f64>, size: f64) -> f64 {
        dq.as_slice()
            .chunks(3)
            .map(|c| c[0].hypot(c[1]).max(size * c[2].abs()))
            .fold(0.0, f64::max)
    }

    /// The pose closing the group on `outer` nearest (by Newton's method) `start`.
    ///
    /// # Errors
    /// [`Error::NotAssemblable`] (the gap at `start`) when Newton's method does not converge
    /// from `start` (the group does not assemble near it).
    pub fn newton(&self, start: &GroupPose, outer: &[Point2<f64>], size: f64) -> Result<GroupPose> {
        self.check()?;
        let mut q = start.to_q();
        if self.newton_in(
            &mut q,
            &mut Linear::default(),
            outer,
            size,
            (MAX_NEWTON, size),
            false,
        ) {
            Ok(GroupPose::from_q(&q))
        } else {
            Err(no_assembly(self.residual(start, outer)))
        }
    }

    /// The pose the group reaches from `reference` (closed on `path(0)`) while its known
    /// points move along `path(t)`, t from 0 to 1 (`path` writes them into its slice): the
    /// assembly mode by continuity. Each step is predicted along the tangent (one solve with
    /// the factorised K) and corrected by Newton's method, which must contract from the first
    /// step and stay within a tenth of `size`; otherwise the step is halved (to 2⁻³⁰).
    ///
    /// # Errors
    /// [`Error::NotAssemblable`] with the closure gap of the last pose at the next step of
    /// the path where the path cannot be followed (the group does not assemble beyond it,
    /// or passes a branch point there); [`Error::Budget`] after 100 000 predictor–corrector
    /// steps (a path that keeps nearly failing).
    ///
    /// Its buffers are allocated for this call; [`track_in`](Self::track_in) reuses a
    /// [`GroupWork`] instead (the same bits).
    pub fn track(
        &self,
        reference: &GroupPose,
        path: impl FnMut(f64, &mut [Point2<f64>]),
        size: f64,
    ) -> Result<GroupPose> {
        self.track_in(reference, path, size, &mut GroupWork::default())
    }

    /// σ_min/σ_max of K at `q` with its angle columns divided by `size` (module docs).
    fn conditioning_q(&self, q: &DVector<f64>, size: f64) -> f64 {
        let inverse = size.recip();
        if !(size > 0.0 && inverse.is_finite()) {
            return 0.0;
        }
        let k = self.jacobian(q, inverse);
        // A non-finite K (an overflowing pose) has no conditioning; the SVD's iteration is
        // bounded all the same.
        if !k.iter().all(|x| x.is_finite()) {
            return 0.0;
        }
        let Some(svd) = k.try_svd(false, false, f64::EPSILON, 10_000) else {
            return 0.0;
        };
        let s = svd.singular_values;
        let (lo, hi) = s.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        if hi > 0.0 {
            lo / hi
        } else {
            0.0
        }
    }

    /// σ_min/σ_max of the scaled closure Jacobian at `pose` (module docs).
    #[must_use]
    pub fn conditioning(&self, pose: &GroupPose, size: f64) -> f64 {
        self.conditioning_q(&pose.to_q(), size)
    }

    /// The reciprocal 1-norm condition of K at `q` with its angle columns divided by `size`
    /// (module docs), from K factorised in `lin` (unscaled: the scaling moves no pivot):
    /// `lin` keeps the factors for the solves that follow, `lin.rot` the links' unit vectors.
    fn factorise_conditioned(&self, q: &DVector<f64>, size: f64, lin: &mut Linear) -> Result<f64> {
        lin.size(q.len());
        self.rotations(q, &mut lin.rot);
        self.jacobian_into(q, &lin.rot, 1.0, &mut lin.k);
        // A non-finite K (an overflowing pose) has no conditioning.
        let finite = lin.k.iter().all(|x| x.is_finite());
        let scale = |i: usize| if i % 3 == 2 { size.recip() } else { 1.0 };
        // ‖K·D‖₁: the largest column sum.
        let norm = lin
            .k
            .column_iter()
            .enumerate()
            .map(|(c, col)| scale(c) * col.iter().map(|x| x.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let c = if finite && norm.is_finite() && size > 0.0 && size.recip().is_finite() {
            lin.factorise();
            lin.rcond(&scale, norm)
        } else {
            0.0
        };
        if !(c > SINGULAR_BELOW) {
            return Err(Error::Singular {
                what: "hinged group",
                measure: "reciprocal 1-norm condition of its closure Jacobian",
                value: c,
            });
        }
        Ok(c)
    }

    /// `pose` has one origin and angle per link, and `known` (of `what`, unless empty) one
    /// entry per outer hinge.
    fn check_counts(&self, pose: &GroupPose, known: usize, what: &str) -> Result<()> {
        if pose.origins.len() != self.links || pose.angles.len() != self.links {
            return Err(self.count_error(pose.origins.len().min(pose.angles.len()), "pose entries"));
        }
        if !what.is_empty() && known != self.outer.len() {
            return Err(Error::Description {
                item: "hinged group".to_owned(),
                problem: format!("{known} {what} for {} outer hinges", self.outer.len()),
            });
        }
        Ok(())
    }

    fn count_error(&self, n: usize, what: &str) -> Error {
        Error::Description {
            item: "hinged group".to_owned(),
            problem: format!("{n} {what} for {} links", self.links),
        }
    }

    /// The links' velocities and accelerations at `pose` (closed on the positions of
    /// `outer`), from the known points' motions `outer`. One factorisation of K serves the
    /// conditioning and both solves.
    ///
    /// # Errors
    /// [`Error::Singular`] when K is singular (its reciprocal condition ≤ 8ε: a dead point or
    /// branch point of the group); [`Error::NonFinite`] when a rate overflows;
    /// [`Error::Description`] when `pose` does not have one entry per link or `outer` one
    /// per outer hinge.
    pub fn rates(&self, pose: &GroupPose, outer: &[PointMotion], size: f64) -> Result<GroupMotion> {
        self.check_counts(pose, outer.len(), "known point motions")?;
        let q = pose.to_q();
        let mut lin = Linear::default();
        let conditioning = self.factorise_conditioned(&q, size, &mut lin)?;
        let base = 2 * self.inner.len();
        let rhs = &mut lin.f;
        rhs.fill(0.0);
        for (o, m) in outer.iter().enumerate() {
            rhs[base + 2 * o] = m.v.x;
            rhs[base + 2 * o + 1] = m.v.y;
        }
        if !lin.solve() {
            return Err(singular());
        }
        let qd = lin.f.clone();
        // The centripetal terms: p̈ = ö + θ̈·J·R l − θ̇²·R l.
        let spin = |end: HingeEnd| Self::point(&q, end).1 * qd[3 * end.0 + 2].powi(2);
        let rhs = &mut lin.f;
        for (i, &[a, b]) in self.inner.iter().enumerate() {
            let c = spin(a) - spin(b);
            rhs[2 * i] = c.x;
            rhs[2 * i + 1] = c.y;
        }
        for (o, (&end, m)) in self.outer.iter().zip(outer).enumerate() {
            let c = m.a + spin(end);
            rhs[base + 2 * o] = c.x;
            rhs[base + 2 * o + 1] = c.y;
        }
        if !lin.solve() {
            return Err(singular());
        }
        let qdd = &lin.f;
        if !(qd.iter().chain(qdd.iter()).all(|x| x.is_finite())) {
            return Err(Error::NonFinite {
                name: "a group's velocity or acceleration",
                value: f64::NAN,
            });
        }
        let links = (0..self.links)
            .map(|k| LinkMotion {
                origin: PointMotion::new(
                    pose.origins[k],
                    Vector2::new(qd[3 * k], qd[3 * k + 1]),
                    Vector2::new(qdd[3 * k], qdd[3 * k + 1]),
                ),
                angle: normalize(pose.angles[k]),
                omega: qd[3 * k + 2],
                epsilon: qdd[3 * k + 2],
            })
            .collect();
        Ok(GroupMotion {
            links,
            conditioning,
        })
    }

    /// The reactions of the group at `pose` under `loads` (one resultant per link, at any
    /// point), by Kᵀλ + Q = 0 (module docs).
    ///
    /// # Errors
    /// [`Error::Singular`] at a singular K; [`Error::NonFinite`] when a reaction overflows;
    /// [`Error::Description`] when `pose` or `loads` do not have one entry per link.
    pub fn reactions(&self, pose: &GroupPose, loads: &[Load], size: f64) -> Result<GroupReactions> {
        self.check_counts(pose, self.links, "")?;
        if loads.len() != self.links {
            return Err(self.count_error(loads.len(), "loads"));
        }
        let q = pose.to_q();
        let mut lin = Linear::default();
        let conditioning = self.factorise_conditioned(&q, size, &mut lin)?;
        // Kᵀ factorised on its own (the same bits as `Kᵀ.lu().solve`).
        self.jacobian_into(&q, &lin.rot, 1.0, &mut lin.k);
        lin.k.transpose_mut();
        lin.factorise();
        let rhs = &mut lin.f;
        rhs.fill(0.0);
        for (k, l) in loads.iter().enumerate() {
            let r = l.point - pose.origins[k];
            rhs[3 * k] = -l.force.x;
            rhs[3 * k + 1] = -l.force.y;
            rhs[3 * k + 2] = -(l.moment + crate::angle::cross(r, l.force));
        }
        if !lin.solve() {
            return Err(singular());
        }
        let lambda = &lin.f;
        if !lambda.iter().all(|x| x.is_finite()) {
            return Err(Error::NonFinite {
                name: "a group's reaction",
                value: f64::NAN,
            });
        }
        let at = |h: usize| Vector2::new(lambda[2 * h], lambda[2 * h + 1]);
        let ni = self.inner.len();
        Ok(GroupReactions {
            inner: (0..ni).map(at).collect(),
            outer: (0..self.outer.len()).map(|o| at(ni + o)).collect(),
            conditioning,
        })
    }

    /// Every assembly mode of the group on the known points `outer` that a search from
    /// `starts` random link angles finds (seeded by `seed`): for each start the origins are
    /// fitted to the angles by least squares (the closure is linear in them), then Newton's
    /// method, each step limited to `size`, runs to convergence; the converged poses are
    /// kept once each (two poses are one mode when they are within 1e-7 of `size`), the
    /// regular ones only (σ_min/σ_max > 1e-10). The count is a lower bound that grows with
    /// `starts` until every mode is found; compare two counts to see it has stopped growing.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn modes(
        &self,
        outer: &[Point2<f64>],
        size: f64,
        starts: usize,
        seed: u64,
    ) -> Result<Vec<GroupPose>> {
        self.check()?;
        let mut rng = seed | 1;
        let mut next = move || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut found: Vec<GroupPose> = Vec::new();
        let n = self.links;
        for _ in 0..starts {
            let mut q = DVector::zeros(3 * n);
            for k in 0..n {
                q[3 * k + 2] = std::f64::consts::TAU * next();
            }
            // Origins by least squares at these angles: the closure is K_o·o = −f(0).
            let f = self.residual_q(&q, outer);
            let k = self.jacobian(&q, 1.0);
            let cols: Vec<usize> = (0..n).flat_map(|k| [3 * k, 3 * k + 1]).collect();
            let ko = k.select_columns(&cols);
            let Some(o) = (ko.transpose() * &ko).lu().solve(&(-(ko.transpose() * f))) else {
                continue;
            };
            for (i, &c) in cols.iter().enumerate() {
                q[c] = o[i];
            }
            let Some(q) = self.damped_newton(q, outer, size) else {
                continue;
            };
            if self.conditioning_q(&q, size) <= 1e-10 {
                continue;
            }
            let pose = GroupPose::from_q(&q);
            if !found.iter().any(|p| p.distance(&pose, size) <= 1e-7 * size) {
                found.push(pose);
            }
        }
        Ok(found)
    }

    /// Newton's method with each step cut to `size`, up to 100 steps, to rounding.
    fn damped_newton(
        &self,
        mut q: DVector<f64>,
        outer: &[Point2<f64>],
        size: f64,
    ) -> Option<DVector<f64>> {
        for _ in 0..100 {
            let f = self.residual_q(&q, outer);
            let mut dq = self.jacobian(&q, 1.0).lu().solve(&(-f))?;
            let step = Self::step_norm(&dq, size);
            if !step.is_finite() {
                return None;
            }
            if step > size {
                dq *= size / step;
            }
            q += dq;
            if step <= 1e-13 * size {
                let mut q = q;
                return self
                    .newton_in(
                        &mut q,
                        &mut Linear::default(),
                        outer,
                        size,
                        (4, size),
                        false,
                    )
                    .then_some(q);
            }
        }
        None
    }
}

/// Reusable buffers for the Newton solves of one [`HingedGroup`] (any size; resized when the
/// group's size changes). `Default` allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct GroupWork {
    lin: Linear,
    q: DVector<f64>,
    guess: DVector<f64>,
    pts: Vec<Point2<f64>>,
    before: Vec<Point2<f64>>,
}

impl HingedGroup {
    /// Newton's method from `q` (in place): true when it converges (the step falls to
    /// rounding, 4ε of `size`, or stalls within 10⁻¹² of `size` plus 16ε of the known
    /// points' coordinates) within `max` steps, each step no more than `size`, the first
    /// no more than `first_max` and, once `contract` is set, each at most half the one
    /// before. A step beyond a bound ends the solve at once (a caller that would refuse the
    /// result pays for no further factorisation).
    fn newton_in(
        &self,
        q: &mut DVector<f64>,
        lin: &mut Linear,
        outer: &[Point2<f64>],
        size: f64,
        (max, first_max): (usize, f64),
        contract: bool,
    ) -> bool {
        lin.size(q.len());
        let mut rot = std::mem::take(&mut lin.rot);
        let done = self.newton_steps(q, lin, &mut rot, outer, size, (max, first_max), contract);
        lin.rot = rot;
        done
    }

    /// The steps of [`newton_in`](Self::newton_in), the links' unit vectors in `rot`.
    #[allow(clippy::too_many_arguments)]
    fn newton_steps(
        &self,
        q: &mut DVector<f64>,
        lin: &mut Linear,
        rot: &mut Vec<Vector2<f64>>,
        outer: &[Point2<f64>],
        size: f64,
        (max, first_max): (usize, f64),
        contract: bool,
    ) -> bool {
        let mut last = f64::INFINITY;
        // The rounding of a position is ε of its coordinates, not of the group's size: a
        // group drawn far from the origin (10⁶ sizes away) closes only to ε·|p|, and its
        // steps stall there. The floor below which a stalled step counts as converged.
        let reach = outer
            .iter()
            .map(|p| p.x.abs().max(p.y.abs()))
            .fold(0.0, f64::max);
        let floor = 16.0 * f64::EPSILON * reach;
        for i in 0..max {
            self.rotations(q, rot);
            self.residual_into(q, rot, outer, &mut lin.f);
            self.jacobian_into(q, rot, 1.0, &mut lin.k);
            lin.factorise();
            lin.f.neg_mut();
            if !lin.solve() {
                return false;
            }
            let step = Self::step_norm(&lin.f, size);
            if !step.is_finite() || step > size || (i == 0 && step > first_max) {
                return false;
            }
            *q += &lin.f;
            if step <= 4.0 * f64::EPSILON * size || (step >= last && step <= 1e-12 * size + floor) {
                return true;
            }
            if contract && step > 1e-11 * size + floor && step > 0.5 * last {
                return false;
            }
            last = step;
        }
        false
    }

    /// [`track`](Self::track) in the buffers of `work` (the same steps, the same bits).
    ///
    /// # Errors
    /// As [`track`](Self::track).
    pub fn track_in(
        &self,
        reference: &GroupPose,
        mut path: impl FnMut(f64, &mut [Point2<f64>]),
        size: f64,
        work: &mut GroupWork,
    ) -> Result<GroupPose> {
        let GroupWork {
            lin,
            q,
            guess,
            pts,
            before,
        } = work;
        reference.write_q(q);
        lin.size(q.len());
        pts.clear();
        pts.resize(self.outer.len(), Point2::origin());
        before.clear();
        before.resize(self.outer.len(), Point2::origin());
        let (mut t, mut dt) = (0.0f64, 1.0f64);
        path(0.0, before);
        let base = 2 * self.inner.len();
        let mut steps = 0;
        while t < 1.0 {
            // Each step at least doubles back to its size after a failure, but a path that
            // keeps nearly failing at dt ≈ 10⁻⁹ would take 10⁹ steps: a budget ends it.
            steps += 1;
            if steps > MAX_TRACK_STEPS {
                return Err(Error::Budget {
                    what: "continuation step (path parameter reached in `time`)",
                    limit: MAX_TRACK_STEPS,
                    time: t,
                });
            }
            let t1 = (t + dt).min(1.0);
            path(t1, pts);
            // Tangent predictor: K·Δq = (0 | ΔP).
            self.rotations(q, &mut lin.rot);
            self.jacobian_into(q, &lin.rot, 1.0, &mut lin.k);
            lin.f.fill(0.0);
            for (o, (p1, p0)) in pts.iter().zip(before.iter()).enumerate() {
                lin.f[base + 2 * o] = p1.x - p0.x;
                lin.f[base + 2 * o + 1] = p1.y - p0.y;
            }
            lin.factorise();
            let corrected = lin.solve() && {
                guess.clone_from(q);
                *guess += &lin.f;
                self.newton_in(guess, lin, pts, size, (12, 0.1 * size), true)
            };
            if corrected {
                std::mem::swap(q, guess);
                t = t1;
                before.copy_from_slice(pts);
                dt = (2.0 * dt).min(1.0);
            } else if dt > 1e-9 {
                dt *= 0.5;
            } else {
                let gap = self.residual(&GroupPose::from_q(q), pts);
                return Err(no_assembly(gap));
            }
        }
        // Polish at the end: the corrector stopped at rounding already; one more solve
        // brings every hinge to the last bit the closure allows.
        guess.clone_from(q);
        if !self.newton_in(guess, lin, pts, size, (MAX_NEWTON, size), false) {
            return Err(no_assembly(self.residual(&GroupPose::from_q(q), pts)));
        }
        Ok(GroupPose::from_q(guess))
    }
}

/// The most predictor–corrector steps of one [`HingedGroup::track_in`] along its path.
const MAX_TRACK_STEPS: usize = 100_000;

fn singular() -> Error {
    Error::Singular {
        what: "hinged group",
        measure: "reciprocal 1-norm condition of its closure Jacobian",
        value: 0.0,
    }
}

/// The group does not close: `gap` is its largest closure gap where the solve gave up.
fn no_assembly(gap: f64) -> Error {
    Error::NotAssemblable {
        group: "hinged group",
        gap,
    }
}
