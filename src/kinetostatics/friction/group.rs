//! Friction in the hinges of a group above the 2nd class: the triad ([`TriadFriction`]) and
//! any rigid group of hinges (the engine's general groups), by one solve.
//!
//! A group's reactions are linear in its links' loads, so, as for a dyad, they are affine in
//! the hinges' pressures m_k = |R_k|: V(m) = V0 + D·m, with V0 the frictionless solve and
//! column k of D the group's response to hinge k's friction couple per newton of pressure
//! (−c_k on the hinge's second link, +c_k on its first when that is one of the group's
//! links, c_k = ρ_k·sgn(ω_rel,k)). The frictionless block is solved once for V0 and once per
//! hinge with friction for D, then m = ψ(V(m)) by Newton ([`super::newton`]).

use super::newton::{Pressure, Pressures};
use super::solver::wider;
use super::{sign, Convergence, Hinge, Iteration, JointFriction};
use crate::error::{all_finite, Error, Result};
use crate::kinetostatics::{Conditioning, Triad};
use crate::Load;
use nalgebra::Vector2;

/// One hinge of a group: the links it joins, as indices into the group's loads (`by` is
/// `None` for a known link outside the group), its friction circle and its relative rate
/// ω_on − ω_by, rad/s.
#[derive(Debug, Clone, Copy)]
pub(crate) struct GroupHinge {
    pub by: Option<usize>,
    pub on: usize,
    pub rho: f64,
    pub rate: f64,
}

/// A group's reactions with friction: per hinge the force of `by` on `on`, N, and its
/// friction (the couple on `on` from `by`).
#[derive(Debug, Clone)]
pub(crate) struct GroupOutcome {
    pub forces: Vec<Vector2<f64>>,
    pub joints: Vec<JointFriction>,
    pub convergence: Convergence,
    pub conditioning: Conditioning,
}

/// The frictionless block of a group: per hinge the force of `by` on `on` under the loads
/// on the group's links (in the order of [`GroupHinge`]'s indices), and its conditioning.
pub(crate) type Frictionless<'a> =
    dyn Fn(&[Load]) -> Result<(Vec<Vector2<f64>>, Conditioning)> + 'a;

/// Solves a group of hinges with friction (module docs). `name(k)` names hinge k in a
/// self-locking error.
pub(crate) fn hinged_group(
    loads: &[Load],
    hinges: &[GroupHinge],
    solve: &Frictionless<'_>,
    options: &Iteration,
    what: &'static str,
    name: &dyn Fn(usize) -> String,
) -> Result<GroupOutcome> {
    let (v0, conditioning) = solve(loads)?;
    let c: Vec<f64> = hinges.iter().map(|h| h.rho * sign(h.rate)).collect();
    if c.iter().all(|&c| c == 0.0) {
        // No friction: the frictionless block's results as they are.
        return finite_outcome(
            GroupOutcome {
                joints: v0.iter().map(|r| JointFriction::none(r.norm())).collect(),
                forces: v0,
                convergence: Convergence::NONE,
                conditioning,
            },
            what,
        );
    }
    let pair = |v: &Vector2<f64>| [v.x, v.y];
    let mut d = Vec::with_capacity(hinges.len());
    for (h, &ck) in hinges.iter().zip(&c) {
        if ck == 0.0 {
            d.push(vec![[0.0; 2]; hinges.len()]);
            continue;
        }
        let mut unit: Vec<Load> = loads.iter().map(|l| Load::zero(l.point)).collect();
        unit[h.on].moment -= ck;
        if let Some(by) = h.by {
            unit[by].moment += ck;
        }
        d.push(solve(&unit)?.0.iter().map(pair).collect());
    }
    let scale = loads
        .iter()
        .map(|l| l.force)
        .chain(v0.iter().copied())
        .fold(0.0, |s, f| wider(wider(s, f.x.abs()), f.y.abs()));
    let s = Pressures {
        v0: v0.iter().map(pair).collect(),
        d,
        laws: vec![Pressure::Hinge; hinges.len()],
        active: c.iter().map(|&c| c != 0.0).collect(),
        scale,
    }
    .solve(options, what, name)?;
    let forces: Vec<Vector2<f64>> = s.v.iter().map(|p| Vector2::new(p[0], p[1])).collect();
    let joints: Vec<JointFriction> = (0..hinges.len())
        .map(|k| {
            if c[k] == 0.0 {
                JointFriction::none(forces[k].norm())
            } else {
                JointFriction::new(c[k], s.m[k], hinges[k].rate)
            }
        })
        .collect();
    finite_outcome(
        GroupOutcome {
            forces,
            joints,
            convergence: s.convergence,
            conditioning,
        },
        what,
    )
}

/// `out` if every number in it is finite: reactions near the top of f64 can still overflow
/// a pressure (|R| through R²) or a lost power (ρ·|R|·|ω|), and no such number leaves in an
/// `Ok`.
fn finite_outcome(out: GroupOutcome, what: &'static str) -> Result<GroupOutcome> {
    let finite = out
        .forces
        .iter()
        .all(|f| f.x.is_finite() && f.y.is_finite())
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
        let hinges: Vec<GroupHinge> = (0..3)
            .map(|i| GroupHinge {
                by: None,
                on: i,
                rho: rho[0][i],
                rate: w.binary[i] - w.outer[i],
            })
            .chain((0..3).map(|i| GroupHinge {
                by: Some(i),
                on: 3,
                rho: rho[1][i],
                rate: w.ternary - w.binary[i],
            }))
            .collect();
        let out = hinged_group(
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
