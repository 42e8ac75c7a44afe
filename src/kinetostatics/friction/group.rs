//! Friction in the joints of a group above the 2nd class: the triad ([`TriadFriction`]), the
//! triad with a sliding pair and any rigid group of hinges (the engine's general groups), by
//! one solve.
//!
//! A group's reactions are linear in its links' loads, so, as for a dyad, they are affine in
//! the joints' pressures m_k (|R_k| of a hinge, ψ(N, K) of a slide): V(m) = V0 + D·m, with V0
//! the frictionless solve and column k of D the group's response to joint k's friction load
//! per newton of pressure (a hinge's couple, a slide's force along its guide through its
//! reference point: −c_k on the joint's second link, +c_k on its first when that is one of
//! the group's links, c_k = ρ_k·sgn(ω_rel,k) or f_k·sgn(v_rel,k)). The frictionless block is
//! solved once for V0 and once per joint with friction for D, then m = ψ(V(m)) by Newton
//! ([`super::newton`]).

use super::newton::{Pressure, Pressures};
use super::solver::wider;
use super::{sign, Convergence, Hinge, Iteration, JointFriction};
use crate::angle::perp;
use crate::error::{all_finite, Error, Result};
use crate::kinetostatics::{Conditioning, SlideAt, SliderTriad, Triad};
use crate::Load;
use nalgebra::{Point2, Vector2};

/// How a joint of a group carries its reaction and its friction.
#[derive(Debug, Clone, Copy)]
pub(crate) enum GroupPair {
    /// A hinge: its reaction is the pair (R_x, R_y), its friction a couple ρ·|R|.
    Hinge,
    /// A slide along the unit direction `dir` with the reference point `point`: its reaction
    /// is the pair (N, K), N along `dir` turned +90° and K the normal reaction's moment about
    /// `point`; its friction a force f·ψ(N, K) along `dir` through `point` (ψ the `law`).
    Slide {
        dir: Vector2<f64>,
        point: Point2<f64>,
        law: Pressure,
    },
}

/// One joint of a group: the links it joins, as indices into the group's loads (`by` is
/// `None` for a known link outside the group), its friction coefficient (ρ of a hinge, m;
/// f of a slide) and its relative rate (a hinge's ω_on − ω_by, rad/s; a slide's velocity
/// of `on` relative to `by` along `dir`, m/s).
#[derive(Debug, Clone, Copy)]
pub(crate) struct GroupJoint {
    pub by: Option<usize>,
    pub on: usize,
    pub coefficient: f64,
    pub rate: f64,
    pub pair: GroupPair,
}

impl GroupJoint {
    /// A hinge of friction circle `rho`.
    pub(crate) fn hinge(by: Option<usize>, on: usize, rho: f64, rate: f64) -> Self {
        Self {
            by,
            on,
            coefficient: rho,
            rate,
            pair: GroupPair::Hinge,
        }
    }

    /// A slide of coefficient `f` along the unit direction `dir` through `point`, whose
    /// pressure follows `law`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn slide(
        by: Option<usize>,
        on: usize,
        f: f64,
        rate: f64,
        dir: Vector2<f64>,
        point: Point2<f64>,
        law: Pressure,
    ) -> Self {
        Self {
            by,
            on,
            coefficient: f,
            rate,
            pair: GroupPair::Slide { dir, point, law },
        }
    }

    pub(super) fn law(&self) -> Pressure {
        match self.pair {
            GroupPair::Hinge => Pressure::Hinge,
            GroupPair::Slide { law, .. } => law,
        }
    }

    /// Puts the joint's friction load per newton of pressure into `unit` (the group's
    /// links' loads, zero before): −c on `on` from `by`, +c back on `by` when it is one of
    /// the group's links (c = ρ or f times the sign of the rate): a couple in a hinge, a
    /// force along the slide through its reference point in a slide.
    pub(super) fn put_unit_load(&self, c: f64, unit: &mut [Load]) {
        match self.pair {
            GroupPair::Hinge => {
                unit[self.on].moment -= c;
                if let Some(by) = self.by {
                    unit[by].moment += c;
                }
            }
            GroupPair::Slide { dir, point, .. } => {
                unit[self.on] = Load::force_at(point, -c * dir);
                if let Some(by) = self.by {
                    unit[by] = Load::force_at(point, c * dir);
                }
            }
        }
    }

    /// The joint's whole force of `by` on `on` and the couple that goes with it, from its
    /// pair `v` and its friction `fr`: a hinge's force and its friction couple; a slide's
    /// normal force with the friction along it, and its K.
    pub(super) fn reaction(&self, v: [f64; 2], fr: &JointFriction) -> (Vector2<f64>, f64) {
        match self.pair {
            GroupPair::Hinge => (Vector2::new(v[0], v[1]), fr.load),
            GroupPair::Slide { dir, .. } => (perp(dir) * v[0] + dir * fr.load, v[1]),
        }
    }

    /// The largest force number of the pair `v` (a hinge's two components, a slide's N; not
    /// its K, a moment): its share of the load scale.
    pub(super) fn force_of(&self, v: [f64; 2]) -> f64 {
        match self.pair {
            GroupPair::Hinge => wider(v[0].abs(), v[1].abs()),
            GroupPair::Slide { .. } => v[0].abs(),
        }
    }
}

/// A group's reactions with friction: per joint the whole force of `by` on `on`, N (a
/// slide's normal force and its friction), with the couple that goes with it (a hinge's
/// friction couple, a slide's K), N·m, and its friction.
#[derive(Debug, Clone)]
pub(crate) struct GroupOutcome {
    pub forces: Vec<Vector2<f64>>,
    pub couples: Vec<f64>,
    pub joints: Vec<JointFriction>,
    pub convergence: Convergence,
    pub conditioning: Conditioning,
}

/// The frictionless block of a group: per joint its reaction's pair (see [`GroupPair`])
/// under the loads on the group's links (in the order of [`GroupJoint`]'s indices), and its
/// conditioning.
pub(crate) type Frictionless<'a> =
    dyn Fn(&[Load]) -> Result<(Vec<Vector2<f64>>, Conditioning)> + 'a;

/// Solves a group of hinges and slides with friction (module docs). `name(k)` names joint k
/// in a self-locking error.
pub(crate) fn group_friction(
    loads: &[Load],
    joints: &[GroupJoint],
    solve: &Frictionless<'_>,
    options: &Iteration,
    what: &'static str,
    name: &dyn Fn(usize) -> String,
) -> Result<GroupOutcome> {
    let (v0, conditioning) = solve(loads)?;
    let c: Vec<f64> = joints
        .iter()
        .map(|h| h.coefficient * sign(h.rate))
        .collect();
    let pair = |v: &Vector2<f64>| [v.x, v.y];
    if c.iter().all(|&c| c == 0.0) {
        // No friction: the frictionless block's results as they are.
        let m: Vec<f64> = joints
            .iter()
            .zip(&v0)
            .map(|(h, v)| h.law().of(v.x, v.y))
            .collect();
        let v: Vec<[f64; 2]> = v0.iter().map(pair).collect();
        return outcome(joints, &c, &m, &v, Convergence::NONE, conditioning, what);
    }
    let mut d = Vec::with_capacity(joints.len());
    for (h, &ck) in joints.iter().zip(&c) {
        if ck == 0.0 {
            d.push(vec![[0.0; 2]; joints.len()]);
            continue;
        }
        let mut unit: Vec<Load> = loads.iter().map(|l| Load::zero(l.point)).collect();
        h.put_unit_load(ck, &mut unit);
        d.push(solve(&unit)?.0.iter().map(pair).collect());
    }
    let scale = load_scale(
        loads.iter().map(|l| l.force),
        joints.iter().zip(&v0).map(|(h, v)| h.force_of([v.x, v.y])),
    );
    let s = Pressures {
        v0: v0.iter().map(pair).collect(),
        d,
        laws: joints.iter().map(GroupJoint::law).collect(),
        active: c.iter().map(|&c| c != 0.0).collect(),
        scale,
    }
    .solve(options, what, name)?;
    outcome(joints, &c, &s.m, &s.v, s.convergence, conditioning, what)
}

/// The load scale of a friction solve: the largest force component among the loads' forces
/// and the frictionless reactions' force numbers (`reactions`, see
/// [`GroupJoint::force_of`]).
pub(super) fn load_scale(
    loads: impl Iterator<Item = Vector2<f64>>,
    reactions: impl Iterator<Item = f64>,
) -> f64 {
    let s = loads.fold(0.0, |s, f| wider(wider(s, f.x.abs()), f.y.abs()));
    reactions.fold(s, wider)
}

/// The outcome from the pressures `m` and the reactions' pairs `v`, if every number in it
/// is finite: reactions near the top of f64 can still overflow a pressure (|R| through R²)
/// or a lost power (ρ·|R|·|ω|), and no such number leaves in an `Ok`.
fn outcome(
    joints: &[GroupJoint],
    c: &[f64],
    m: &[f64],
    v: &[[f64; 2]],
    convergence: Convergence,
    conditioning: Conditioning,
    what: &'static str,
) -> Result<GroupOutcome> {
    let n = joints.len();
    let (mut forces, mut couples, mut friction) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for (k, h) in joints.iter().enumerate() {
        let fr = if c[k] == 0.0 {
            JointFriction::none(m[k])
        } else {
            JointFriction::new(c[k], m[k], h.rate)
        };
        let (force, couple) = h.reaction(v[k], &fr);
        forces.push(force);
        couples.push(couple);
        friction.push(fr);
    }
    finite_outcome(
        GroupOutcome {
            forces,
            couples,
            joints: friction,
            convergence,
            conditioning,
        },
        what,
    )
}

/// `out` if every number in it is finite.
fn finite_outcome(out: GroupOutcome, what: &'static str) -> Result<GroupOutcome> {
    let finite = out
        .forces
        .iter()
        .all(|f| f.x.is_finite() && f.y.is_finite())
        && out.couples.iter().all(|c| c.is_finite())
        && out.joints.iter().all(|j| {
            [j.load, j.pressure, j.power_lost]
                .iter()
                .all(|x| x.is_finite())
        });
    if finite {
        Ok(out)
    } else {
        Err(Error::Overflow { what })
    }
}

/// The friction data of a triad's hinges.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadJoints {
    /// A_i, the hinges of the binary links with their outer links.
    pub a: [Hinge; 3],
    /// B_i, the hinges of the binary links with the ternary link.
    pub b: [Hinge; 3],
}

/// The angular velocities of the links a triad joins, rad/s, counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadRates {
    /// Of the outer link that carries A_i (0 for the frame).
    pub outer: [f64; 3],
    /// Of binary link i.
    pub binary: [f64; 3],
    /// Of the ternary link.
    pub ternary: f64,
}

/// A triad ([`Triad`]) with friction in its six hinges.
///
/// # Examples
/// [`Triad`]'s example, the ternary link turning at 1 rad/s on binary links at rest and a
/// friction circle of 1 cm in every hinge: the couples oppose each hinge's relative rotation
/// and every link stays in equilibrium with them.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use approx::assert_relative_eq;
/// use tmm::{kinetostatics::Triad, Load};
/// use tmm::kinetostatics::friction::{Hinge, TriadFriction, TriadJoints, TriadRates};
/// let b = [Point2::new(-1.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// let a = [Point2::new(-1.0, 1.0), Point2::new(1.0, 1.0), Point2::new(1.0, 1.0)];
/// let triad = Triad {
///     a,
///     b,
///     loads: [Load::zero(a[0]), Load::zero(a[1]), Load::zero(a[2])],
///     load_ternary: Load::force_at(Point2::new(0.0, 1.0 / 3.0), Vector2::new(0.0, -300.0)),
/// };
/// let pin = Hinge::circle(0.01)?;
/// let r = TriadFriction {
///     triad,
///     joints: TriadJoints { a: [pin; 3], b: [pin; 3] },
///     rates: TriadRates { outer: [0.0; 3], binary: [0.0; 3], ternary: 1.0 },
/// }
/// .solve()?;
/// // The B hinges turn (ω_T − ω_i = 1): their couples on the ternary link are −ρ·|R_Bi|.
/// for i in 0..3 {
///     assert_relative_eq!(r.b[i].load, -0.01 * r.r_b[i].norm(), epsilon = 1e-12);
///     assert_eq!(r.a[i].load, 0.0);
/// }
/// // Binary link 1 about A1: R_B1 at B1 (reversed) and B1's couple (reversed) balance.
/// let arm = b[0] - a[0];
/// let m = -(arm.x * r.r_b[0].y - arm.y * r.r_b[0].x) - r.b[0].load;
/// assert!(m.abs() < 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadFriction {
    /// The triad: its joints and loads.
    pub triad: Triad,
    /// The friction data of its hinges.
    pub joints: TriadJoints,
    /// The links' angular velocities.
    pub rates: TriadRates,
}

/// The reactions of a triad with friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriadFrictionReactions {
    /// R_Ai, the force of the outer link on binary link i at A_i, N.
    pub r_a: [Vector2<f64>; 3],
    /// R_Bi, the force of binary link i on the ternary link at B_i, N.
    pub r_b: [Vector2<f64>; 3],
    /// A_i's friction: the couple of the outer link on binary link i, rate ω_i − ω_outer,i.
    pub a: [JointFriction; 3],
    /// B_i's friction: the couple of binary link i on the ternary link, rate ω_T − ω_i.
    pub b: [JointFriction; 3],
    /// The frictionless triad's conditioning.
    pub conditioning: Conditioning,
    /// The friction iteration.
    pub convergence: Convergence,
}

impl TriadFriction {
    /// Solves the triad with friction, with the default [`Iteration`].
    ///
    /// # Errors
    /// As [`TriadFriction::solve_with`].
    pub fn solve(&self) -> Result<TriadFrictionReactions> {
        self.solve_with(&Iteration::default())
    }

    /// Solves the triad with friction.
    ///
    /// # Errors
    /// - as [`Triad::solve`] (bad numbers, dead points);
    /// - [`Error::NonFinite`](crate::Error::NonFinite) or
    ///   [`Error::OutOfRange`](crate::Error::OutOfRange) naming `rho_A1` … `rho_B3`, or a
    ///   non-finite rate;
    /// - [`Error::In`](crate::Error::In) naming the hinge that self-locks, or the iteration
    ///   whose budget was used up.
    pub fn solve_with(&self, options: &Iteration) -> Result<TriadFrictionReactions> {
        let options = &options.checked()?;
        let names = [
            ["rho_A1", "rho_A2", "rho_A3"],
            ["rho_B1", "rho_B2", "rho_B3"],
        ];
        let mut rho = [[0.0; 3]; 2];
        for i in 0..3 {
            rho[0][i] = self.joints.a[i].checked(names[0][i])?;
            rho[1][i] = self.joints.b[i].checked(names[1][i])?;
        }
        let w = &self.rates;
        all_finite(&[
            ("omega_outer1", w.outer[0]),
            ("omega_outer2", w.outer[1]),
            ("omega_outer3", w.outer[2]),
            ("omega_binary1", w.binary[0]),
            ("omega_binary2", w.binary[1]),
            ("omega_binary3", w.binary[2]),
            ("omega_ternary", w.ternary),
        ])?;
        let t = &self.triad;
        // The loads in the order binary 1, 2, 3, ternary; the hinges A1, A2, A3, B1, B2, B3.
        let loads = [t.loads[0], t.loads[1], t.loads[2], t.load_ternary];
        let hinges: Vec<GroupJoint> = (0..3)
            .map(|i| GroupJoint::hinge(None, i, rho[0][i], w.binary[i] - w.outer[i]))
            .chain(
                (0..3).map(|i| GroupJoint::hinge(Some(i), 3, rho[1][i], w.ternary - w.binary[i])),
            )
            .collect();
        let out = group_friction(
            &loads,
            &hinges,
            &triad_block(t),
            options,
            "triad with friction",
            &|k| {
                let (joint, i) = if k < 3 { ("A", k) } else { ("B", k - 3) };
                format!("joint {joint}{}", i + 1)
            },
        )?;
        let f = &out.forces;
        let j = &out.joints;
        Ok(TriadFrictionReactions {
            r_a: [f[0], f[1], f[2]],
            r_b: [f[3], f[4], f[5]],
            a: [j[0], j[1], j[2]],
            b: [j[3], j[4], j[5]],
            conditioning: out.conditioning,
            convergence: out.convergence,
        })
    }
}

/// The frictionless triad as a group's block: loads binary 1, 2, 3, ternary; forces R_A1,
/// R_A2, R_A3, R_B1, R_B2, R_B3.
pub(crate) fn triad_block(
    t: &Triad,
) -> impl Fn(&[Load]) -> Result<(Vec<Vector2<f64>>, Conditioning)> + '_ {
    move |loads: &[Load]| {
        let r = Triad {
            loads: [loads[0], loads[1], loads[2]],
            load_ternary: loads[3],
            ..*t
        }
        .solve()?;
        Ok((
            r.r_a.iter().chain(&r.r_b).copied().collect(),
            r.conditioning,
        ))
    }
}

/// The frictionless triad with a sliding pair as a group's block: loads binary 1, 2, 3,
/// ternary; per joint A1, A2, A3, B1, B2, B3 its pair (see [`GroupPair`]): the sliding
/// pair's (N, K) — N along `t.normal`, K its couple (outer: of the known link on the slider,
/// about B1; inner: of the slider on the ternary link, about A1) — the hinges' forces.
pub(crate) fn slider_triad_block(
    t: &SliderTriad,
) -> impl Fn(&[Load]) -> Result<(Vec<Vector2<f64>>, Conditioning)> + '_ {
    move |loads: &[Load]| {
        let r = SliderTriad {
            loads: [loads[0], loads[1], loads[2]],
            load_ternary: loads[3],
            ..*t
        }
        .solve()?;
        let slide = Vector2::new(r.normal_force, r.couple);
        let mut pairs: Vec<Vector2<f64>> = r.r_a.iter().chain(&r.r_b).copied().collect();
        match t.slide {
            SlideAt::Outer => pairs[0] = slide,
            SlideAt::Inner => pairs[3] = slide,
        }
        Ok((pairs, r.conditioning))
    }
}
