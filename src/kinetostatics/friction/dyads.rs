//! The five dyads with Coulomb friction in their joints.
//!
//! Each solver checks the friction data of its three joints and the links' rates, describes
//! its joints as a group's (which links each joins, a hinge or a slide) and solves by the
//! dyads' one friction solve ([`super::dyad`]): the frictionless closed form, its response to
//! each joint's friction load (the closed forms are linear in the loads), and the friction
//! equations on the three joint pressures (see the [module](super)). The RRR dyad, the
//! engine's most frequent group, first tries its responses in closed form with Newton
//! written out.

use super::dyad::{dyad_friction, DyadBase, DyadSolved};
use super::group::GroupJoint;
use super::newton::DIRECT_STEPS;
use super::solver::{three_hinges, wider, Solved};
use super::{sign, Convergence, Hinge, Iteration, JointFriction, Slide, SlideContact};
use crate::angle::{cross, perp};
use crate::error::{unit_direction, Result};
use crate::kinetostatics::{
    Conditioning, PrpDyad, PrpReactions, RppDyad, RppReactions, RprDyad, RprReactions, RrpDyad,
    RrpReactions, RrrDyad, RrrReactions,
};
use crate::Load;
use nalgebra::{Point2, Vector2};

/// A dyad's reactions by joint, as the whole linkage's solve reads them: per joint the
/// whole force of its first link on its second, the couple that goes with it (a hinge's
/// friction couple, a slide's K, the normal force's moment about its reference point) and
/// its friction.
pub(crate) type ByJoint = ([Vector2<f64>; 3], [f64; 3], [JointFriction; 3]);

/// A friction block's `solve` with the default [`Iteration`], its reactions' power lost in
/// the joints `$joint` and its reactions by joint (forces `$force`, couples `$couple`).
macro_rules! block_api {
    ($block:ident, $reactions:ident, [$($joint:ident),+], [$($force:ident),+],
     [$($c1:ident . $c2:ident),+]) => {
        impl $block {
            /// Solves the dyad with friction, with the default [`Iteration`].
            ///
            /// # Errors
            /// As [`Self::solve_with`].
            pub fn solve(&self) -> Result<$reactions> {
                self.solve_with(&Iteration::default())
            }
        }

        impl $reactions {
            /// The power lost in the dyad's three joints, W.
            #[must_use]
            pub fn power_lost(&self) -> f64 {
                [$(self.$joint.power_lost),+].iter().sum()
            }

            /// The reactions by joint ([`ByJoint`]).
            pub(crate) fn by_joint(&self) -> ByJoint {
                (
                    [$(self.$force),+],
                    [$(self.$c1.$c2),+],
                    [$(self.$joint),+],
                )
            }
        }
    };
}

/// Checks that every named rate is finite; the error names the first that is not.
#[inline(always)]
fn all_finite(named: &[(&'static str, f64); 4]) -> Result<()> {
    if named.iter().fold(0.0, |s, (_, v)| s + v).is_finite() {
        Ok(())
    } else {
        crate::error::all_finite(named)
    }
}

/// A load, built in place.
#[inline(always)]
fn load(point: Point2<f64>, force: Vector2<f64>, moment: f64) -> Load {
    Load {
        point,
        force,
        moment,
    }
}

#[inline(always)]
fn vec(v: &[f64; 6], k: usize) -> Vector2<f64> {
    Vector2::new(v[2 * k], v[2 * k + 1])
}

/// The largest component of some vectors, in magnitude.
#[inline(always)]
fn max_abs(v: &[Vector2<f64>; 2]) -> f64 {
    wider(
        wider(v[0].x.abs(), v[0].y.abs()),
        wider(v[1].x.abs(), v[1].y.abs()),
    )
}

/// A frictionless dyad as its friction solve reads it: its loads, the same dyad under
/// other loads, and its reactions' pairs (see [`DyadBase`]) and whole forces.
trait Block: Sized {
    type Reactions;
    fn loads(&self) -> [&Load; 2];
    fn solve_under(&self, loads: &[Load; 2]) -> Result<Self::Reactions>;
    fn pairs(r: &Self::Reactions) -> [f64; 6];
    fn forces(r: &Self::Reactions) -> [Vector2<f64>; 3];
}

/// [`Block`] for a dyad whose reactions' pairs `$values` gives, its whole forces `$force`.
macro_rules! block {
    ($dyad:ident, $reactions:ident, $values:ident, [$($force:ident),+]) => {
        impl Block for $dyad {
            type Reactions = $reactions;
            fn loads(&self) -> [&Load; 2] {
                [&self.load2, &self.load3]
            }
            fn solve_under(&self, loads: &[Load; 2]) -> Result<$reactions> {
                let [load2, load3] = *loads;
                $dyad { load2, load3, ..*self }.solve()
            }
            fn pairs(r: &$reactions) -> [f64; 6] {
                $values(r)
            }
            fn forces(r: &$reactions) -> [Vector2<f64>; 3] {
                [$(r.$force),+]
            }
        }
    };
}

/// Solves the dyad `d`, whose frictionless reactions are `base`, with the friction of its
/// `joints` by [`dyad_friction`], `names` its own and its joints' in the errors.
fn solved<D: Block>(
    d: &D,
    base: &D::Reactions,
    joints: &[GroupJoint; 3],
    options: &Iteration,
    (what, names): (&'static str, [&'static str; 3]),
) -> Result<DyadSolved> {
    let start = DyadBase {
        pairs: D::pairs(base),
        forces: D::forces(base),
    };
    let block = |l: &[Load; 2]| d.solve_under(l).map(|r| D::pairs(&r));
    dyad_friction(&start, joints, d.loads(), block, options, what, names)
}

// ----- RRR -----

/// The friction data of an RRR dyad's hinges.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrJoints {
    /// A, the hinge of links 1 and 2.
    pub a: Hinge,
    /// B, the hinge of links 2 and 3.
    pub b: Hinge,
    /// C, the hinge of links 3 and 4.
    pub c: Hinge,
}

/// The angular velocities of the links an RRR dyad joins, rad/s, counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrRates {
    /// ω1, of link 1 (A's other link).
    pub omega1: f64,
    /// ω2, of link 2.
    pub omega2: f64,
    /// ω3, of link 3.
    pub omega3: f64,
    /// ω4, of link 4 (C's other link; 0 for the frame).
    pub omega4: f64,
}

/// An RRR dyad with friction in its hinges.
///
/// # Examples
/// The symmetric dyad of [`RrrDyad`]'s example (100 N down at B) opening up: link 2 turns
/// counter-clockwise, link 3 clockwise, about fixed pins. Each hinge with a friction circle
/// of 5 mm: the frictionless reactions, 70.7 N each, grow a little, and the powers lost are
/// ρ·|R|·|ω_rel|.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::RrrDyad, Load};
/// use tmm::kinetostatics::friction::{Hinge, RrrFriction, RrrJoints, RrrRates};
/// let b = Point2::new(1.0, 1.0);
/// let dyad = RrrDyad {
///     a: Point2::new(0.0, 0.0), b, c: Point2::new(2.0, 0.0),
///     load2: Load::zero(b),
///     load3: Load::force_at(b, Vector2::new(0.0, -100.0)),
/// };
/// let pin = Hinge::circle(0.005)?;
/// let r = RrrFriction {
///     dyad,
///     joints: RrrJoints { a: pin, b: pin, c: pin },
///     rates: RrrRates { omega1: 0.0, omega2: 1.0, omega3: -1.0, omega4: 0.0 },
/// }
/// .solve()?;
/// // Every friction couple opposes its relative rotation and costs ρ·|R|·|ω_rel|.
/// assert!(r.a.load < 0.0 && r.b.load > 0.0 && r.c.load > 0.0);
/// assert_relative_eq!(r.b.power_lost, 0.005 * r.r23.norm() * 2.0, epsilon = 1e-12);
/// assert!(r.convergence.iterations <= 4);
/// // Link 2's moments about B: R12 at A and the couples at A and B balance.
/// let ab = b - dyad.a;
/// assert_relative_eq!(ab.x * r.r12.y - ab.y * r.r12.x, r.a.load - r.b.load, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrFriction {
    /// The dyad: its hinges and its loads (external plus inertia).
    pub dyad: RrrDyad,
    /// The friction data of its hinges.
    pub joints: RrrJoints,
    /// The links' angular velocities.
    pub rates: RrrRates,
}

/// The reactions of an RRR dyad with friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrrFrictionReactions {
    /// R12, the force of link 1 on link 2 at A, N.
    pub r12: Vector2<f64>,
    /// R23, the force of link 2 on link 3 at B, N.
    pub r23: Vector2<f64>,
    /// R43, the force of link 4 on link 3 at C, N.
    pub r43: Vector2<f64>,
    /// A's friction: the couple of link 1 on link 2, rate ω2 − ω1.
    pub a: JointFriction,
    /// B's friction: the couple of link 2 on link 3, rate ω3 − ω2.
    pub b: JointFriction,
    /// C's friction: the couple of link 4 on link 3, rate ω3 − ω4.
    pub c: JointFriction,
    /// The frictionless closed form's conditioning.
    pub conditioning: Conditioning,
    /// The friction iteration.
    pub convergence: Convergence,
}

impl RrrFrictionReactions {
    /// The dyad's load on link 1 at A: −R12 and A's friction couple on link 1, reversed.
    #[must_use]
    pub fn on_link1(&self, dyad: &RrrDyad) -> Load {
        load(dyad.a, -self.r12, -self.a.load)
    }

    /// The dyad's load on link 4 at C: −R43 and C's friction couple on link 4, reversed.
    #[must_use]
    pub fn on_link4(&self, dyad: &RrrDyad) -> Load {
        load(dyad.c, -self.r43, -self.c.load)
    }
}

block_api!(
    RrrFriction,
    RrrFrictionReactions,
    [a, b, c],
    [r12, r23, r43],
    [a.load, b.load, c.load]
);

fn rrr_values(r: &RrrReactions) -> [f64; 6] {
    [r.r12.x, r.r12.y, r.r23.x, r.r23.y, r.r43.x, r.r43.y]
}

block!(RrrDyad, RrrReactions, rrr_values, [r12, r23, r43]);

/// The columns of D for an RRR dyad: the reactions' response to each hinge's friction
/// couple per newton of pressure, −c_k times the response to a unit couple on the joint's
/// second link (minus the first's). The responses in closed form (the closed form of
/// [`RrrDyad`] with those loads, its terms that vanish dropped): with AB, CB, d = AB × CB and
/// AB·CB, a couple M2 = 1 on link 2 gives t2 = 1/|AB|², n2 = t2·(AB·CB)/d, n3 = −1/d; a
/// couple M3 = 1 on link 3 gives t3 = 1/|CB|², n2 = 1/d, n3 = −t3·(AB·CB)/d; then
/// R12 = n2·AB + t2·AB⊥, R43 = n3·CB + t3·CB⊥, R23 = −R43. A's couple acts on link 2, B's
/// on link 3 (and reversed on link 2), C's on link 3.
#[inline(always)]
fn rrr_friction_columns(d: &RrrDyad, c: [f64; 3]) -> [[f64; 6]; 3] {
    let (ab, cb) = (d.b - d.a, d.b - d.c);
    let (dot, i_d) = (ab.dot(&cb), 1.0 / cross(ab, cb));
    let inv =
        Vector2::repeat(1.0).component_div(&Vector2::new(ab.norm_squared(), cb.norm_squared()));
    let (t2, t3) = (inv.x, inv.y);
    // The couple on link 2: R12 = p2, R43 = q2.
    let p2 = ab * (t2 * dot * i_d) + perp(ab) * t2;
    let q2 = cb * -i_d;
    // The couple on link 3: R12 = p3, R43 = q3.
    let p3 = ab * i_d;
    let q3 = cb * (-t3 * dot * i_d) + perp(cb) * t3;
    let column = |k: f64, p: Vector2<f64>, q: Vector2<f64>| {
        let (p, q) = (p * -k, q * -k);
        [p.x, p.y, -q.x, -q.y, q.x, q.y]
    };
    [
        column(c[0], p2, q2),
        column(c[1], p3 - p2, q3 - q2),
        column(c[2], p3, q3),
    ]
}

impl RrrFriction {
    /// Solves the dyad with friction.
    ///
    /// # Errors
    /// - as [`RrrDyad::solve`] (bad numbers, dead points);
    /// - [`Error::NonFinite`](crate::Error::NonFinite) or
    ///   [`Error::OutOfRange`](crate::Error::OutOfRange) naming `rho_A`, `rho_B`, `rho_C`, or
    ///   a non-finite rate (`omega1` … `omega4`);
    /// - [`Error::In`](crate::Error::In) naming the joint that self-locks (see the
    ///   [module](super)), or the iteration whose budget was used up.
    pub fn solve_with(&self, options: &Iteration) -> Result<RrrFrictionReactions> {
        let options = &options.checked()?;
        let d = &self.dyad;
        let base = d.solve()?;
        let w = &self.rates;
        let rho = [self.joints.a.rho, self.joints.b.rho, self.joints.c.rho];
        // One test for the good case; the named checks only when it fails.
        let rates_finite = (w.omega1 + w.omega2 + w.omega3 + w.omega4).is_finite();
        let rho_ok = rho[0] >= 0.0 && rho[1] >= 0.0 && rho[2] >= 0.0;
        if !(rho_ok && (rho[0] + rho[1] + rho[2]).is_finite() && rates_finite) {
            self.joints.a.checked("rho_A")?;
            self.joints.b.checked("rho_B")?;
            self.joints.c.checked("rho_C")?;
            crate::error::all_finite(&[
                ("omega1", w.omega1),
                ("omega2", w.omega2),
                ("omega3", w.omega3),
                ("omega4", w.omega4),
            ])?;
        }
        let rate = [
            w.omega2 - w.omega1,
            w.omega3 - w.omega2,
            w.omega3 - w.omega4,
        ];
        let c = [
            rho[0] * sign(rate[0]),
            rho[1] * sign(rate[1]),
            rho[2] * sign(rate[2]),
        ];
        if c[0] != 0.0 && c[1] != 0.0 && c[2] != 0.0 {
            // The usual case, written out: friction in every hinge, Newton converging.
            let v0 = rrr_values(&base);
            let columns = rrr_friction_columns(d, c);
            let f = [d.load2.force, d.load3.force];
            let scale = v0.iter().fold(max_abs(&f), |s, x| wider(s, x.abs()));
            let tol = options.tolerance * scale;
            if let Some(Solved { m, v, convergence }) =
                three_hinges(&v0, &columns, tol, DIRECT_STEPS.min(options.budget))
            {
                return Ok(RrrFrictionReactions {
                    r12: vec(&v, 0),
                    r23: vec(&v, 1),
                    r43: vec(&v, 2),
                    a: JointFriction::new(c[0], m[0], rate[0]),
                    b: JointFriction::new(c[1], m[1], rate[1]),
                    c: JointFriction::new(c[2], m[2], rate[2]),
                    conditioning: base.conditioning,
                    convergence,
                });
            }
        }
        if c == [0.0; 3] {
            // No friction: the frictionless block's results as they are.
            return Ok(RrrFrictionReactions {
                r12: base.r12,
                r23: base.r23,
                r43: base.r43,
                a: JointFriction::none(base.r12.norm()),
                b: JointFriction::none(base.r23.norm()),
                c: JointFriction::none(base.r43.norm()),
                conditioning: base.conditioning,
                convergence: Convergence::NONE,
            });
        }
        self.general(&base, rho, rate, options)
    }

    /// Every other case: friction in some hinges only, or the direct Newton not converging
    /// (the dyads' one solve decides).
    #[cold]
    #[inline(never)]
    fn general(
        &self,
        base: &RrrReactions,
        rho: [f64; 3],
        rate: [f64; 3],
        options: &Iteration,
    ) -> Result<RrrFrictionReactions> {
        let d = &self.dyad;
        let joints = [
            GroupJoint::hinge(None, 0, rho[0], rate[0]),
            GroupJoint::hinge(Some(0), 1, rho[1], rate[1]),
            GroupJoint::hinge(None, 1, rho[2], rate[2]),
        ];
        let out = solved(
            d,
            base,
            &joints,
            options,
            (
                "RRR dyad with friction",
                [
                    "joint A (links 1 and 2)",
                    "joint B (links 2 and 3)",
                    "joint C (links 3 and 4)",
                ],
            ),
        )?;
        let [r12, r23, r43] = out.forces;
        let [a, b, c] = out.joints;
        Ok(RrrFrictionReactions {
            r12,
            r23,
            r43,
            a,
            b,
            c,
            conditioning: base.conditioning,
            convergence: out.convergence,
        })
    }
}

// ----- RRP -----

/// The friction data of an RRP dyad's joints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpJoints {
    /// A, the hinge of links 1 and 2.
    pub a: Hinge,
    /// B, the hinge of link 2 and the slider 3.
    pub b: Hinge,
    /// The slider 3 on link 4's guide; its reference point is B.
    pub guide: Slide,
}

/// The rates of an RRP dyad's links.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpRates {
    /// ω1, of link 1, rad/s.
    pub omega1: f64,
    /// ω2, of link 2, rad/s.
    pub omega2: f64,
    /// ω4, of link 4, whose guide the slider follows (so the slider's too), rad/s.
    pub omega4: f64,
    /// The slider's velocity relative to link 4, along the guide's direction, m/s.
    pub slide: f64,
}

/// An RRP dyad with friction in its hinges and on its guide.
///
/// # Examples
/// The slider-crank of [`RrpDyad`]'s example (the gas pushes the piston with 1000 N towards
/// −x through B) on its power stroke, the piston moving towards −x, and f = 0.1 on the guide
/// only. The friction opposes the piston's motion, so it pushes the piston towards +x and
/// relieves the rod: with the rod force P along A→B, (0.3, −0.1)/|AB|, the slider's balance
/// along x, 0.3·P/|AB| + f·N = 1000 N, and across, N = 0.1·P/|AB|, give N = 1000/(3 + f) =
/// 322.6 N (frictionless 333.3 N) and the friction f·N = 32.26 N along +x.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::RrpDyad, Load};
/// use tmm::kinetostatics::friction::{Hinge, RrpFriction, RrpJoints, RrpRates, Slide};
/// let b = Point2::new(0.4, 0.0);
/// let dyad = RrpDyad {
///     a: Point2::new(0.1, 0.1), b, guide: Vector2::new(1.0, 0.0),
///     load2: Load::zero(b),
///     load3: Load::force_at(b, Vector2::new(-1000.0, 0.0)),
/// };
/// let r = RrpFriction {
///     dyad,
///     joints: RrpJoints { a: Hinge::FRICTIONLESS, b: Hinge::FRICTIONLESS, guide: Slide::new(0.1)? },
///     rates: RrpRates { omega1: 0.0, omega2: 0.0, omega4: 0.0, slide: -2.0 },
/// }
/// .solve()?;
/// assert_relative_eq!(r.contact43.normal, 1000.0 / 3.1, epsilon = 1e-9);
/// assert_relative_eq!(r.guide.load, 100.0 / 3.1, epsilon = 1e-9); // along +x: against the motion
/// assert_relative_eq!(r.guide.power_lost, 2.0 * 100.0 / 3.1, epsilon = 1e-9);
/// assert_relative_eq!(r.r43, Vector2::new(100.0 / 3.1, 1000.0 / 3.1), epsilon = 1e-9);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpFriction {
    /// The dyad: its joints, guide and loads.
    pub dyad: RrpDyad,
    /// The friction data of its joints.
    pub joints: RrpJoints,
    /// The links' rates.
    pub rates: RrpRates,
}

/// The reactions of an RRP dyad with friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RrpFrictionReactions {
    /// R12, the force of link 1 on link 2 at A, N.
    pub r12: Vector2<f64>,
    /// R23, the force of link 2 on the slider at B, N.
    pub r23: Vector2<f64>,
    /// R43, the whole force of the guide on the slider (normal plus friction), N.
    pub r43: Vector2<f64>,
    /// A's friction: the couple of link 1 on link 2, rate ω2 − ω1.
    pub a: JointFriction,
    /// B's friction: the couple of link 2 on the slider, rate ω4 − ω2.
    pub b: JointFriction,
    /// The guide's friction: the force of link 4 on the slider along the guide's direction,
    /// rate the slider's velocity relative to link 4.
    pub guide: JointFriction,
    /// The guide's normal reaction (moment about B).
    pub contact43: SlideContact,
    /// The frictionless closed form's conditioning.
    pub conditioning: Conditioning,
    /// The friction iteration.
    pub convergence: Convergence,
}

impl RrpFrictionReactions {
    /// The dyad's load on link 1 at A: −R12 and A's friction couple on link 1, reversed.
    #[must_use]
    pub fn on_link1(&self, dyad: &RrpDyad) -> Load {
        load(dyad.a, -self.r12, -self.a.load)
    }

    /// The dyad's load on link 4, reduced to B: −R43 and the normal force's moment about B, reversed.
    #[must_use]
    pub fn on_link4(&self, dyad: &RrpDyad) -> Load {
        load(dyad.b, -self.r43, -self.contact43.moment)
    }
}

block_api!(
    RrpFriction,
    RrpFrictionReactions,
    [a, b, guide],
    [r12, r23, r43],
    [a.load, b.load, contact43.moment]
);

fn rrp_values(r: &RrpReactions) -> [f64; 6] {
    [r.r12.x, r.r12.y, r.r23.x, r.r23.y, r.r43_n, r.guide_moment]
}

block!(RrpDyad, RrpReactions, rrp_values, [r12, r23, r43]);

impl RrpFriction {
    /// Solves the dyad with friction.
    ///
    /// # Errors
    /// - as [`RrpDyad::solve`];
    /// - [`Error::NonFinite`](crate::Error::NonFinite),
    ///   [`Error::OutOfRange`](crate::Error::OutOfRange) or
    ///   [`Error::NonPositive`](crate::Error::NonPositive) naming `rho_A`, `rho_B`,
    ///   `f_guide`, `L_guide`, `centre_guide` or a rate;
    /// - [`Error::In`](crate::Error::In) naming the joint that self-locks, or the iteration
    ///   whose budget was used up.
    pub fn solve_with(&self, options: &Iteration) -> Result<RrpFrictionReactions> {
        let options = &options.checked()?;
        let d = &self.dyad;
        let base = d.solve()?;
        let rho_a = self.joints.a.checked("rho_A")?;
        let rho_b = self.joints.b.checked("rho_B")?;
        let (f, law) = self
            .joints
            .guide
            .checked(["f_guide", "L_guide", "centre_guide"])?;
        let w = &self.rates;
        all_finite(&[
            ("omega1", w.omega1),
            ("omega2", w.omega2),
            ("omega4", w.omega4),
            ("slide", w.slide),
        ])?;
        let g = unit_direction("|guide|", d.guide)?;
        let joints = [
            GroupJoint::hinge(None, 0, rho_a, w.omega2 - w.omega1),
            GroupJoint::hinge(Some(0), 1, rho_b, w.omega4 - w.omega2),
            GroupJoint::slide(None, 1, f, w.slide, g, d.b, law),
        ];
        let out = solved(
            d,
            &base,
            &joints,
            options,
            (
                "RRP dyad with friction",
                [
                    "joint A (links 1 and 2)",
                    "joint B (links 2 and 3)",
                    "the guide (links 4 and 3)",
                ],
            ),
        )?;
        let [r12, r23, r43] = out.forces;
        let [a, b, guide] = out.joints;
        Ok(RrpFrictionReactions {
            r12,
            r23,
            r43,
            a,
            b,
            guide,
            contact43: SlideContact::new(out.pairs[4], out.pairs[5], law),
            conditioning: base.conditioning,
            convergence: out.convergence,
        })
    }
}

// ----- RPR -----

/// The friction data of an RPR dyad's joints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprJoints {
    /// A, the hinge of link 1 and the rod 2.
    pub a: Hinge,
    /// The rod sliding in the cylinder 3; its reference point is A (the bearing's middle at
    /// `centre` along the axis from A, for instance halfway between the piston and the
    /// cylinder's mouth).
    pub slide: Slide,
    /// E, the hinge of the cylinder and link 4.
    pub e: Hinge,
}

/// The rates of an RPR dyad's links.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprRates {
    /// ω1, of link 1, rad/s.
    pub omega1: f64,
    /// ω, of the rod and the cylinder (they turn together), rad/s.
    pub omega: f64,
    /// ω4, of link 4, rad/s.
    pub omega4: f64,
    /// The rod's velocity relative to the cylinder, along the axis direction, m/s.
    pub slide: f64,
}

/// An RPR dyad with friction in its hinges and its sliding pair.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprFriction {
    /// The dyad: its hinges, axis and loads.
    pub dyad: RprDyad,
    /// The friction data of its joints.
    pub joints: RprJoints,
    /// The links' rates.
    pub rates: RprRates,
}

/// The reactions of an RPR dyad with friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RprFrictionReactions {
    /// R12, the force of link 1 on the rod at A, N.
    pub r12: Vector2<f64>,
    /// R32, the whole force of the cylinder on the rod (normal plus friction), N.
    pub r32: Vector2<f64>,
    /// R43, the force of link 4 on the cylinder at E, N.
    pub r43: Vector2<f64>,
    /// A's friction: the couple of link 1 on the rod, rate ω − ω1.
    pub a: JointFriction,
    /// The sliding pair's friction: the force of the cylinder on the rod along the axis,
    /// rate the rod's velocity relative to the cylinder.
    pub slide: JointFriction,
    /// E's friction: the couple of link 4 on the cylinder, rate ω − ω4.
    pub e: JointFriction,
    /// The sliding pair's normal reaction on the rod (moment about A).
    pub contact32: SlideContact,
    /// The frictionless closed form's conditioning.
    pub conditioning: Conditioning,
    /// The friction iteration.
    pub convergence: Convergence,
}

impl RprFrictionReactions {
    /// The dyad's load on link 1 at A: −R12 and A's friction couple on link 1, reversed.
    #[must_use]
    pub fn on_link1(&self, dyad: &RprDyad) -> Load {
        load(dyad.a, -self.r12, -self.a.load)
    }

    /// The dyad's load on link 4 at E: −R43 and E's friction couple on link 4, reversed.
    #[must_use]
    pub fn on_link4(&self, dyad: &RprDyad) -> Load {
        load(dyad.e, -self.r43, -self.e.load)
    }
}

block_api!(
    RprFriction,
    RprFrictionReactions,
    [a, slide, e],
    [r12, r32, r43],
    [a.load, contact32.moment, e.load]
);

fn rpr_values(r: &RprReactions) -> [f64; 6] {
    [r.r12.x, r.r12.y, r.r32_n, r.couple, r.r43.x, r.r43.y]
}

block!(RprDyad, RprReactions, rpr_values, [r12, r32, r43]);

impl RprFriction {
    /// Solves the dyad with friction.
    ///
    /// # Errors
    /// - as [`RprDyad::solve`];
    /// - [`Error::NonFinite`](crate::Error::NonFinite),
    ///   [`Error::OutOfRange`](crate::Error::OutOfRange) or
    ///   [`Error::NonPositive`](crate::Error::NonPositive) naming `rho_A`, `f_slide`,
    ///   `L_slide`, `centre_slide`, `rho_E` or a rate;
    /// - [`Error::In`](crate::Error::In) naming the joint that self-locks, or the iteration
    ///   whose budget was used up.
    pub fn solve_with(&self, options: &Iteration) -> Result<RprFrictionReactions> {
        let options = &options.checked()?;
        let d = &self.dyad;
        let base = d.solve()?;
        let rho_a = self.joints.a.checked("rho_A")?;
        let (f, law) = self
            .joints
            .slide
            .checked(["f_slide", "L_slide", "centre_slide"])?;
        let rho_e = self.joints.e.checked("rho_E")?;
        let w = &self.rates;
        all_finite(&[
            ("omega1", w.omega1),
            ("omega", w.omega),
            ("omega4", w.omega4),
            ("slide", w.slide),
        ])?;
        let u = unit_direction("|axis|", d.axis)?;
        let joints = [
            GroupJoint::hinge(None, 0, rho_a, w.omega - w.omega1),
            GroupJoint::slide(Some(1), 0, f, w.slide, u, d.a, law),
            GroupJoint::hinge(None, 1, rho_e, w.omega - w.omega4),
        ];
        let out = solved(
            d,
            &base,
            &joints,
            options,
            (
                "RPR dyad with friction",
                [
                    "joint A (links 1 and 2)",
                    "the slide (links 3 and 2)",
                    "joint E (links 4 and 3)",
                ],
            ),
        )?;
        let [r12, r32, r43] = out.forces;
        let [a, slide, e] = out.joints;
        Ok(RprFrictionReactions {
            r12,
            r32,
            r43,
            a,
            slide,
            e,
            contact32: SlideContact::new(out.pairs[2], out.pairs[3], law),
            conditioning: base.conditioning,
            convergence: out.convergence,
        })
    }
}

// ----- PRP -----

/// The friction data of a PRP dyad's joints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpJoints {
    /// The slider 2 on link 1's guide; its reference point is B.
    pub guide2: Slide,
    /// B, the hinge of the two sliders.
    pub b: Hinge,
    /// The slider 3 on link 4's guide; its reference point is B.
    pub guide3: Slide,
}

/// The rates of a PRP dyad's links.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpRates {
    /// ω1, of link 1 (so of the slider 2), rad/s.
    pub omega1: f64,
    /// ω4, of link 4 (so of the slider 3), rad/s.
    pub omega4: f64,
    /// The slider 2's velocity relative to link 1, along guide 2's direction, m/s.
    pub slide2: f64,
    /// The slider 3's velocity relative to link 4, along guide 3's direction, m/s.
    pub slide3: f64,
}

/// A PRP dyad with friction on its guides and in its hinge.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpFriction {
    /// The dyad: its hinge, guides and loads.
    pub dyad: PrpDyad,
    /// The friction data of its joints.
    pub joints: PrpJoints,
    /// The links' rates.
    pub rates: PrpRates,
}

/// The reactions of a PRP dyad with friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PrpFrictionReactions {
    /// R12, the whole force of link 1's guide on the slider 2 (normal plus friction), N.
    pub r12: Vector2<f64>,
    /// R23, the force of the slider 2 on the slider 3 at B, N.
    pub r23: Vector2<f64>,
    /// R43, the whole force of link 4's guide on the slider 3, N.
    pub r43: Vector2<f64>,
    /// Guide 2's friction: the force of link 1 on the slider 2 along guide 2's direction.
    pub guide2: JointFriction,
    /// B's friction: the couple of the slider 2 on the slider 3, rate ω4 − ω1.
    pub b: JointFriction,
    /// Guide 3's friction: the force of link 4 on the slider 3 along guide 3's direction.
    pub guide3: JointFriction,
    /// Guide 2's normal reaction (moment about B).
    pub contact12: SlideContact,
    /// Guide 3's normal reaction (moment about B).
    pub contact43: SlideContact,
    /// The frictionless closed form's conditioning.
    pub conditioning: Conditioning,
    /// The friction iteration.
    pub convergence: Convergence,
}

impl PrpFrictionReactions {
    /// The dyad's load on link 1, reduced to B: −R12 and guide 2's normal moment about B, reversed.
    #[must_use]
    pub fn on_link1(&self, dyad: &PrpDyad) -> Load {
        load(dyad.b, -self.r12, -self.contact12.moment)
    }

    /// The dyad's load on link 4, reduced to B: −R43 and guide 3's normal moment about B, reversed.
    #[must_use]
    pub fn on_link4(&self, dyad: &PrpDyad) -> Load {
        load(dyad.b, -self.r43, -self.contact43.moment)
    }
}

block_api!(
    PrpFriction,
    PrpFrictionReactions,
    [guide2, b, guide3],
    [r12, r23, r43],
    [contact12.moment, b.load, contact43.moment]
);

fn prp_values(r: &PrpReactions) -> [f64; 6] {
    [r.r12_n, r.moment12, r.r23.x, r.r23.y, r.r43_n, r.moment43]
}

block!(PrpDyad, PrpReactions, prp_values, [r12, r23, r43]);

impl PrpFriction {
    /// Solves the dyad with friction.
    ///
    /// # Errors
    /// - as [`PrpDyad::solve`];
    /// - a bad friction number or rate, named (`f_guide2`, `L_guide2`, `centre_guide2`,
    ///   `rho_B`, `f_guide3`, …);
    /// - [`Error::In`](crate::Error::In) naming the joint that self-locks, or the iteration
    ///   whose budget was used up.
    pub fn solve_with(&self, options: &Iteration) -> Result<PrpFrictionReactions> {
        let options = &options.checked()?;
        let d = &self.dyad;
        let base = d.solve()?;
        let (f2, law2) = self
            .joints
            .guide2
            .checked(["f_guide2", "L_guide2", "centre_guide2"])?;
        let rho_b = self.joints.b.checked("rho_B")?;
        let (f3, law3) = self
            .joints
            .guide3
            .checked(["f_guide3", "L_guide3", "centre_guide3"])?;
        let w = &self.rates;
        all_finite(&[
            ("omega1", w.omega1),
            ("omega4", w.omega4),
            ("slide2", w.slide2),
            ("slide3", w.slide3),
        ])?;
        let g2 = unit_direction("|guide2|", d.guide2)?;
        let g3 = unit_direction("|guide3|", d.guide3)?;
        let joints = [
            GroupJoint::slide(None, 0, f2, w.slide2, g2, d.b, law2),
            GroupJoint::hinge(Some(0), 1, rho_b, w.omega4 - w.omega1),
            GroupJoint::slide(None, 1, f3, w.slide3, g3, d.b, law3),
        ];
        let out = solved(
            d,
            &base,
            &joints,
            options,
            (
                "PRP dyad with friction",
                [
                    "guide 2 (links 1 and 2)",
                    "joint B (links 2 and 3)",
                    "guide 3 (links 4 and 3)",
                ],
            ),
        )?;
        let [r12, r23, r43] = out.forces;
        let [guide2, b, guide3] = out.joints;
        Ok(PrpFrictionReactions {
            r12,
            r23,
            r43,
            guide2,
            b,
            guide3,
            contact12: SlideContact::new(out.pairs[0], out.pairs[1], law2),
            contact43: SlideContact::new(out.pairs[4], out.pairs[5], law3),
            conditioning: base.conditioning,
            convergence: out.convergence,
        })
    }
}

// ----- RPP -----

/// The friction data of an RPP dyad's joints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppJoints {
    /// A, the hinge of links 1 and 2.
    pub a: Hinge,
    /// Link 2 sliding in link 3's slot; its reference point is A.
    pub slot: Slide,
    /// Link 3 on link 4's guide; its reference point is B.
    pub guide: Slide,
}

/// The rates of an RPP dyad's links.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppRates {
    /// ω1, of link 1, rad/s.
    pub omega1: f64,
    /// ω4, of link 4 (so of links 2 and 3, which only slide on it), rad/s.
    pub omega4: f64,
    /// Link 2's velocity relative to link 3, along the slot's direction, m/s.
    pub slot: f64,
    /// Link 3's velocity relative to link 4, along the guide's direction, m/s.
    pub slide: f64,
}

/// An RPP dyad with friction in its hinge, its slot and on its guide.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppFriction {
    /// The dyad: its hinge, directions and loads.
    pub dyad: RppDyad,
    /// The friction data of its joints.
    pub joints: RppJoints,
    /// The links' rates.
    pub rates: RppRates,
}

/// The reactions of an RPP dyad with friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RppFrictionReactions {
    /// R12, the force of link 1 on link 2 at A, N.
    pub r12: Vector2<f64>,
    /// R32, the whole force of link 3 on link 2 in the slot (normal plus friction), N.
    pub r32: Vector2<f64>,
    /// R43, the whole force of link 4's guide on link 3, N.
    pub r43: Vector2<f64>,
    /// A's friction: the couple of link 1 on link 2, rate ω4 − ω1.
    pub a: JointFriction,
    /// The slot's friction: the force of link 3 on link 2 along the slot's direction.
    pub slot: JointFriction,
    /// The guide's friction: the force of link 4 on link 3 along the guide's direction.
    pub guide: JointFriction,
    /// The slot's normal reaction on link 2 (moment about A).
    pub contact32: SlideContact,
    /// The guide's normal reaction on link 3 (moment about B).
    pub contact43: SlideContact,
    /// The frictionless closed form's conditioning.
    pub conditioning: Conditioning,
    /// The friction iteration.
    pub convergence: Convergence,
}

impl RppFrictionReactions {
    /// The dyad's load on link 1 at A: −R12 and A's friction couple on link 1, reversed.
    #[must_use]
    pub fn on_link1(&self, dyad: &RppDyad) -> Load {
        load(dyad.a, -self.r12, -self.a.load)
    }

    /// The dyad's load on link 4, reduced to B: −R43 and the guide's normal moment about B, reversed.
    #[must_use]
    pub fn on_link4(&self, dyad: &RppDyad) -> Load {
        load(dyad.b, -self.r43, -self.contact43.moment)
    }
}

block_api!(
    RppFriction,
    RppFrictionReactions,
    [a, slot, guide],
    [r12, r32, r43],
    [a.load, contact32.moment, contact43.moment]
);

fn rpp_values(r: &RppReactions) -> [f64; 6] {
    [r.r12.x, r.r12.y, r.r32_n, r.moment32, r.r43_n, r.moment43]
}

block!(RppDyad, RppReactions, rpp_values, [r12, r32, r43]);

impl RppFriction {
    /// Solves the dyad with friction.
    ///
    /// # Errors
    /// - as [`RppDyad::solve`];
    /// - a bad friction number or rate, named (`rho_A`, `f_slot`, `L_slot`, `centre_slot`,
    ///   `f_guide`, …);
    /// - [`Error::In`](crate::Error::In) naming the joint that self-locks, or the iteration
    ///   whose budget was used up.
    pub fn solve_with(&self, options: &Iteration) -> Result<RppFrictionReactions> {
        let options = &options.checked()?;
        let d = &self.dyad;
        let base = d.solve()?;
        let rho_a = self.joints.a.checked("rho_A")?;
        let (fs, law_s) = self
            .joints
            .slot
            .checked(["f_slot", "L_slot", "centre_slot"])?;
        let (fg, law_g) = self
            .joints
            .guide
            .checked(["f_guide", "L_guide", "centre_guide"])?;
        let w = &self.rates;
        all_finite(&[
            ("omega1", w.omega1),
            ("omega4", w.omega4),
            ("slot", w.slot),
            ("slide", w.slide),
        ])?;
        let u = unit_direction("|guide|", d.guide)?;
        let v_dir = unit_direction("|slot|", d.slot)?;
        let joints = [
            GroupJoint::hinge(None, 0, rho_a, w.omega4 - w.omega1),
            GroupJoint::slide(Some(1), 0, fs, w.slot, v_dir, d.a, law_s),
            GroupJoint::slide(None, 1, fg, w.slide, u, d.b, law_g),
        ];
        let out = solved(
            d,
            &base,
            &joints,
            options,
            (
                "RPP dyad with friction",
                [
                    "joint A (links 1 and 2)",
                    "the slot (links 3 and 2)",
                    "the guide (links 4 and 3)",
                ],
            ),
        )?;
        let [r12, r32, r43] = out.forces;
        let [a, slot, guide] = out.joints;
        Ok(RppFrictionReactions {
            r12,
            r32,
            r43,
            a,
            slot,
            guide,
            contact32: SlideContact::new(out.pairs[2], out.pairs[3], law_s),
            contact43: SlideContact::new(out.pairs[4], out.pairs[5], law_g),
            conditioning: base.conditioning,
            convergence: out.convergence,
        })
    }
}
