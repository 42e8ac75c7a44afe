//! The exact first- and second-order transfer functions of a linkage at one position, from
//! kinematic solves at unit input rates (see the [module docs](super)).

use nalgebra::{Point2, Vector2};

use crate::error::{Error, Result};
use crate::kinematics::{LinkMotion, Motion, PointMotion};
use crate::linkage::plan::{Chain, Group, GroupKind};
use crate::linkage::solve::state::KinState;
use crate::linkage::{Plan, DEAD_CENTRE_DETERMINANT};

/// The rates of one link in one solve: its origin's velocity and acceleration, ω and ε (the
/// positions are the same in every solve and stay in the buffers).
#[derive(Clone, Copy)]
pub(super) struct Rates {
    pub(super) v: Vector2<f64>,
    pub(super) a: Vector2<f64>,
    pub(super) omega: f64,
    pub(super) epsilon: f64,
}

/// The exact first- and second-order transfer functions of every link at one position:
/// kinematic solves at unit input rates and zero input accelerations, made with one set of
/// buffers; the positions are solved once, the rates at the other unit vectors again.
pub(super) struct Transfer<'p> {
    pub(super) n: usize,
    pub(super) nl: usize,
    /// The link rates of the solves, one block of `nl` per solve: q̇ = e₁ (and, for two
    /// inputs, e₂ and (1, 1)). The velocities of solve k are the first-order transfer
    /// functions ∂v/∂q̇_k, its accelerations the second-order ones ∂²r/∂q_k²; those of the
    /// solve at (1, 1) are Σ_jk ∂²r/∂q_j∂q_k, so the mixed derivative is
    /// (a_(1,1) − a_11 − a_22)/2.
    pub(super) rates: Vec<Rates>,
    /// The chain solved.
    pub(super) chain: &'p Chain,
    /// The buffers of the solves: their positions (the same in every solve, with every
    /// link's unit vector) serve the position-only look-ups.
    pub(super) kin: KinState,
}

impl<'p> Transfer<'p> {
    #[inline]
    pub(super) fn new(plan: &'p Plan, n: usize, q: &Vector2<f64>) -> Result<Self> {
        let chain = &plan.chain;
        let mut kin = KinState::new(chain);
        let nl = chain.link_names.len();
        let unit_rates: &[[f64; 2]] = if n == 1 {
            &[[1.0, 0.0]]
        } else {
            &[[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]
        };
        let mut rates = Vec::with_capacity(nl * unit_rates.len());
        for (i, r) in unit_rates.iter().enumerate() {
            let m = [Motion::new(q[0], r[0], 0.0), Motion::new(q[1], r[1], 0.0)];
            if i == 0 {
                kin.solve(chain, &m[..n])?;
                at_no_dead_centre(chain, &kin.dets)?;
            } else {
                // The same positions: only the (linear) rate problems again.
                kin.solve_rates(chain, &m[..n])?;
            }
            rates.extend((0..nl).map(|l| {
                let m = &kin.links[l];
                Rates {
                    v: m.origin.v,
                    a: m.origin.a,
                    omega: m.omega,
                    epsilon: m.epsilon,
                }
            }));
        }
        Ok(Self {
            n,
            nl,
            rates,
            chain,
            kin,
        })
    }

    /// The motion of the point at `local` (along, across) of link `l` in solve `s`.
    #[inline]
    pub(super) fn point(&self, s: usize, l: usize, local: Vector2<f64>) -> PointMotion {
        self.link(s, l).point_in_frame(self.kin.units[l], local)
    }

    /// Link `l` in solve `s` (0, 1: unit rate of input s; 2: both).
    #[inline]
    pub(super) fn link(&self, s: usize, l: usize) -> LinkMotion {
        let r = &self.rates[s * self.nl + l];
        let m = &self.kin.links[l];
        LinkMotion {
            origin: PointMotion::new(m.origin.p, r.v, r.a),
            angle: m.angle,
            omega: r.omega,
            epsilon: r.epsilon,
        }
    }

    /// ∂ω_l/∂q̇_k.
    #[inline]
    pub(super) fn omega(&self, k: usize, l: usize) -> f64 {
        self.link(k, l).omega
    }

    /// ∂v_P/∂q̇_k of the point of link `l` at the local coordinates `local`.
    pub(super) fn vel(&self, k: usize, l: usize, local: Vector2<f64>) -> Vector2<f64> {
        self.point(k, l, local).v
    }

    /// ∂v_P/∂q̇_k of the point of link `l` at `p`.
    pub(super) fn vel_of(&self, k: usize, l: usize, p: Point2<f64>) -> Vector2<f64> {
        self.link(k, l).motion_of(p).v
    }

    /// The sliding link and the guide's link of prismatic joint `j`, and the guide's unit
    /// direction now.
    pub(super) fn slide_parts(&self, j: usize) -> (usize, usize, Vector2<f64>) {
        self.kin.pose(self.chain).slide_parts(j)
    }

    /// The motions of prismatic joint `j`'s point on its sliding link and on its guide's
    /// link in solve `k`.
    pub(super) fn slide_points(&self, k: usize, j: usize) -> [PointMotion; 2] {
        let jp = &self.chain.joints[j];
        let g = jp.prismatic.map_or(0, |(g, _)| g);
        [1 - g, g].map(|side| {
            let local = jp.local[side];
            self.point(k, jp.links[side], local)
        })
    }

    /// ∂ṡ/∂q̇_k of the slide of prismatic joint `j` along the guide direction `d`: the
    /// relative velocity of its points on the sliding link and on the guide's link.
    pub(super) fn slide_rate(&self, k: usize, j: usize, d: Vector2<f64>) -> f64 {
        let [on, guide] = self.slide_points(k, j);
        (on.v - guide.v).dot(&d)
    }

    /// The actual rate Σ_k (∂r/∂q_k)·q̇_k of a quantity with transfer functions `f(k)`.
    pub(super) fn rate(&self, qd: &Vector2<f64>, f: impl Fn(usize) -> f64) -> f64 {
        (0..self.n).map(|k| f(k) * qd[k]).sum()
    }
}

/// Refuses a state at (or within [`DEAD_CENTRE_DETERMINANT`] of) a dead centre of an RRR or
/// RRP dyad. There the dyad's links move at rates of order q̇/det, so the reduced inertia
/// grows as 1/det²: the inputs no longer describe the motion (a one-input linkage is at a
/// lock of its input; a two-input one can leave the dyad's assembly mode, which the plan
/// holds fixed). A fixed-step run that stepped into this region would otherwise go on with
/// an energy error of any size (the five-bar robot with one motor gained 10⁸ J in one step).
///
/// The error is [`Error::DeadCentre`], which a run turns into its stop
/// [`Outcome::DeadCentre`](crate::dynamics::Outcome::DeadCentre).
fn at_no_dead_centre(chain: &Chain, dets: &[f64]) -> Result<()> {
    for (index, (group, det)) in chain.groups.iter().zip(dets).enumerate() {
        if is_dyad(group) && det.abs() <= DEAD_CENTRE_DETERMINANT {
            return Err(Error::DeadCentre {
                index,
                group: group.name.clone(),
                value: *det,
            });
        }
    }
    Ok(())
}

/// Whether `group` is an RRR or RRP dyad, whose dead centre a state is refused at (see
/// [`at_no_dead_centre`]).
fn is_dyad(group: &Group) -> bool {
    matches!(group.kind, GroupKind::Rrr | GroupKind::Rrp)
        && group.triad.is_none()
        && group.general.is_none()
}

/// The number of RRR and RRP dyads of `plan`: its lock measures (see [`lock_measures`]).
pub(super) fn dyad_count(plan: &Plan) -> usize {
    plan.chain.groups.iter().filter(|g| is_dyad(g)).count()
}

/// The lock measures of `plan` at the positions `q` of its `n` inputs: |det| −
/// [`DEAD_CENTRE_DETERMINANT`] of each RRR and RRP dyad in attachment order, positive away
/// from its dead centre and at most zero in the band [`at_no_dead_centre`] refuses (one
/// solve of the positions).
///
/// # Errors
/// `out` not one entry per dyad ([`Error::OutOfRange`]); a position that does not assemble.
pub(super) fn lock_measures(
    plan: &Plan,
    n: usize,
    q: &Vector2<f64>,
    out: &mut [f64],
) -> Result<()> {
    let count = dyad_count(plan);
    if out.len() != count {
        return Err(Error::OutOfRange {
            name: "number of lock measures",
            value: out.len() as f64,
            min: count as f64,
            max: count as f64,
            ends: crate::Ends::Closed,
        });
    }
    let chain = &plan.chain;
    let mut kin = KinState::new(chain);
    let m = [Motion::fixed(q[0]), Motion::fixed(q[1])];
    kin.solve(chain, &m[..n])?;
    let dets = chain
        .groups
        .iter()
        .zip(&kin.dets)
        .filter(|(g, _)| is_dyad(g));
    for (o, (_, det)) in out.iter_mut().zip(dets) {
        *o = det.abs() - DEAD_CENTRE_DETERMINANT;
    }
    Ok(())
}
