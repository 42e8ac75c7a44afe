//! The two independent checks of one analysed position: every link's equilibrium as a free
//! body, and the balancing value by the principle of virtual power.

use super::analysis::Analysis;
use crate::error::{Error, Result};
use crate::linkage::handle::LinkRef;
use crate::Load;

/// The balancing value found two ways at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PowerCheck {
    /// From the group-by-group chain.
    pub chain: f64,
    /// From the principle of virtual power: P'_lost − Σ P'_i over every applied load, each
    /// P'_i = F·v' + M·ω' the load's power per unit input rate (v', ω' the velocity
    /// analogues), P'_lost the power the joints' friction dissipates per unit rate (0
    /// without friction, and at rest). With two inputs, powers: P_lost − Σ P_i, W.
    pub virtual_power: f64,
    /// The scale of the comparison: the largest of |chain| and Σ|P'_i| + |P'_lost| (with two
    /// inputs Σ|P_i| + P_lost, W).
    pub scale: f64,
}

impl PowerCheck {
    /// |chain − virtual power| / scale.
    #[must_use]
    pub fn relative_error(&self) -> f64 {
        let d = (self.chain - self.virtual_power).abs();
        if self.scale > 0.0 {
            d / self.scale
        } else {
            d
        }
    }
}

impl Analysis<'_> {
    /// Every load on link `k` as a free body: applied loads, reactions of its joints, and
    /// the drive on the input link.
    ///
    /// # Errors
    /// As [`Plan::link_id`](crate::linkage::Plan::link_id).
    pub fn free_body(&self, link: impl LinkRef) -> Result<Vec<Load>> {
        Ok(self.free_body_at(self.k.plan.chain.link(link)?))
    }

    /// As [`free_body`](Self::free_body), for an index known to be a link's.
    fn free_body_at(&self, k: usize) -> Vec<Load> {
        let mut all: Vec<Load> = self
            .applied
            .iter()
            .filter(|(l, _)| *l == k)
            .map(|(_, l)| *l)
            .collect();
        for (j, jp) in self.k.plan.chain.joints.iter().enumerate() {
            if jp.links.contains(&k) {
                all.push(self.reactions[j].load_on_side(k));
            }
        }
        all.extend(
            self.drive_loads()
                .filter(|&(link, _)| link == k)
                .map(|(_, l)| l),
        );
        all
    }

    /// How far link `k` is from equilibrium: the larger of |ΣF|/F_scale and |ΣM|/M_scale,
    /// with the scales the largest force and the largest moment (or force × arm).
    ///
    /// # Errors
    /// As [`Plan::link_id`](crate::linkage::Plan::link_id).
    pub fn residual(&self, link: impl LinkRef) -> Result<f64> {
        Ok(self.residual_at(self.k.plan.chain.link(link)?))
    }

    /// As [`residual`](Self::residual), for an index known to be a link's.
    fn residual_at(&self, k: usize) -> f64 {
        let all = self.free_body_at(k);
        let pole = self.k.kin.links[k].origin.p;
        let direct = residual_of(&all, pole);
        if direct.is_finite() {
            direct
        } else {
            scaled_residual(&all, pole)
        }
    }

    /// The worst [`Analysis::residual`] over the moving links.
    #[must_use]
    pub fn worst_residual(&self) -> f64 {
        (1..self.k.kin.links.len())
            .map(|k| self.residual_at(k))
            .fold(0.0, f64::max)
    }

    /// The power of every applied load at the link motions `links`, W: (Σ F·v + M·ω, Σ |F·v +
    /// M·ω|). With the position's own motions these are the loads' powers; with the motions of
    /// a solve at unit input rate, their powers per unit rate (the velocity analogues).
    fn powers_with(&self, links: &[crate::kinematics::LinkMotion]) -> (f64, f64) {
        self.applied.iter().fold((0.0, 0.0), |(s, a), (k, l)| {
            let link = &links[*k];
            let p = l.force.dot(&link.motion_of(l.point).v) + l.moment * link.omega;
            (s + p, a + p.abs())
        })
    }

    /// The power of every applied load, W: Σ F·v + M·ω.
    fn powers(&self) -> (f64, f64) {
        self.powers_with(&self.k.kin.links)
    }

    /// The balancing value by virtual power of a linkage of one input, P'_lost − Σ P'_i (the
    /// loads' powers and the joints' lost power per unit input rate), with its scale
    /// Σ |P'_i| + |P'_lost|: the statics virtual-work check, defined whether the input moves
    /// or not.
    ///
    /// The principle of virtual power holds for any virtual velocities the joints admit; the
    /// velocity analogues (every velocity per unit input rate, v' = ∂v/∂q̇, the first-order
    /// transfer functions) are such velocities at every position, moving or at rest. The
    /// kinematics' rate problems are linear in q̇ (the input's acceleration enters only the
    /// accelerations), so where the input moves v' = v/q̇ and Σ P'_i = (Σ P_i)/q̇: the sums
    /// are the position's own powers over q̇, with no second solve. At rest
    /// (q̇ = 0) the analogues come from a kinematic solve of the same position at q̇ = 1 (its
    /// accelerations are not read).
    ///
    /// Friction: each joint's friction load L_j (a couple or a force along the slide, on one
    /// link from the other) does the virtual power −L_j·r'_j on the joint's relative rate per
    /// unit input rate r'_j = ṙ_j/q̇, so P'_lost = Σ −L_j·r'_j. Moving, that is Σ P_lost/q̇
    /// (each P_lost = −L_j·ṙ_j). At rest every relative rate is r'_j·0 = 0, and the friction
    /// solve's rest convention gives a joint whose relative rate is exactly zero no friction
    /// (L_j = −c·sgn(0)·pressure = 0, see [`kinetostatics::friction`]), so P'_lost = 0: the
    /// balancing value at rest is the frictionless statics', and so is its check.
    ///
    /// # Errors
    /// The kinematic solve at unit rate's error (at rest only: a rate the plan's size
    /// overflows).
    ///
    /// [`kinetostatics::friction`]: crate::kinetostatics::friction
    fn by_unit_rate(&self) -> Result<(f64, f64)> {
        let q = self.k.kin.input.rate;
        if q != 0.0 {
            // q̇ is finite (the solve checked it); P_lost ≥ 0, so |P'_lost| = P_lost/|q̇|.
            let (sum, abs) = self.powers();
            let lost = self.lost_power();
            return Ok(((lost - sum) / q, (abs + lost) / q.abs()));
        }
        let plan = self.k.plan;
        let mut unit = super::kinematics::Kinematics::new(plan);
        let m = self.k.kin.input;
        unit.solve(&[crate::kinematics::Motion::new(m.value, 1.0, 0.0)])?;
        let (sum, abs) = self.powers_with(&unit.kin.links);
        Ok((-sum, abs))
    }

    /// The balancing value by the chain and by the principle of virtual power. For a linkage
    /// with one input, B = P'_lost − Σ P'_i over every applied load with the velocity
    /// analogues (each load's power per unit input rate, [`PowerCheck::virtual_power`]): the
    /// statics virtual-work check, defined at rest as well as moving. For a linkage
    /// with two inputs the comparison is of powers, W: the drives' Σ B_k·q̇_k against
    /// P_lost − Σ P_i of every applied load. With friction the drives also supply the power
    /// the joints dissipate, P_lost = Σ [`JointFriction::power_lost`](crate::kinetostatics::friction::JointFriction)
    /// (the friction loads are internal to the linkage, so they enter here by their lost
    /// power and not as applied loads); at rest a joint has no friction (no relative motion).
    ///
    /// # Errors
    /// [`Error::NonFinite`] (`"virtual power"`) where a sum overflows; at rest, the error of
    /// the kinematic solve at unit rate that gives the velocity analogues.
    ///
    /// # Examples
    /// At rest the check is the statics' virtual work, by the velocity analogues:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let c = plan.analyse(Motion::turning(1.0, 0.0))?.power_check()?;
    /// assert!(c.relative_error() < 1e-12);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn power_check(&self) -> Result<PowerCheck> {
        if let (Some(m), [_, b]) = (self.k.kin.second_input, self.balances()) {
            // Two inputs: the drives' power against the loads' power, W.
            let (sum, abs) = self.powers();
            let lost = self.lost_power();
            let chain = self.balances[0].value * self.k.kin.input.rate + b.value * m.rate;
            let vp = lost - sum;
            if !(chain.is_finite() && vp.is_finite()) {
                return Err(Error::NonFinite {
                    name: "virtual power",
                    value: vp,
                });
            }
            return Ok(PowerCheck {
                chain,
                virtual_power: vp,
                scale: (abs + lost).max(chain.abs()),
            });
        }
        let (vp, scale) = self.by_unit_rate()?;
        if !(vp.is_finite() && scale.is_finite()) {
            return Err(Error::NonFinite {
                name: "virtual power",
                value: vp,
            });
        }
        Ok(PowerCheck {
            chain: self.balances[0].value,
            virtual_power: vp,
            scale: scale.max(self.balances[0].value.abs()),
        })
    }
}

/// A free body's residual, [`Analysis::residual`]: the larger of |ΣF|/F_scale and
/// |ΣM|/M_scale about `pole`.
fn residual_of(all: &[Load], pole: nalgebra::Point2<f64>) -> f64 {
    let sum = Load::sum_about(all, pole);
    let fs = all.iter().map(|l| l.force.norm()).fold(0.0, f64::max);
    let arm = all
        .iter()
        .map(|l| (l.point - pole).norm())
        .fold(0.0, f64::max);
    let ms = all.iter().map(|l| l.moment.abs()).fold(fs * arm, f64::max);
    let rel = |r: f64, s: f64| if s > 0.0 { r / s } else { r };
    rel(sum.force.norm(), fs).max(rel(sum.moment.abs(), ms))
}

/// [`residual_of`] where its sums overflow (finite loads far from the pole, or huge forces
/// times arms): the same ratios with every force divided by a power of two near the largest
/// force, every arm by a power of two near the largest coordinate, and the moments compared
/// in the logarithm, so that an analysis that is finite gives a finite residual.
fn scaled_residual(all: &[Load], pole: nalgebra::Point2<f64>) -> f64 {
    // 2^-e with 2^e ≥ x > 0, and its exponent e.
    let power = |x: f64| {
        let e = x.log2().ceil().clamp(-1000.0, 1023.0);
        (2f64.powf(-e), e)
    };
    let largest = |it: &mut dyn Iterator<Item = f64>| it.map(f64::abs).fold(0.0, f64::max);
    let fbig = largest(&mut all.iter().flat_map(|l| [l.force.x, l.force.y]));
    let cbig = largest(
        &mut all
            .iter()
            .flat_map(|l| [l.point.x, l.point.y])
            .chain([pole.x, pole.y]),
    );
    let (fsc, fe) = if fbig > 0.0 { power(fbig) } else { (1.0, 0.0) };
    let (csc, ce) = if cbig > 0.0 { power(cbig) } else { (1.0, 0.0) };
    let f: Vec<nalgebra::Vector2<f64>> = all.iter().map(|l| l.force * fsc).collect();
    let r: Vec<nalgebra::Vector2<f64>> = all
        .iter()
        .map(|l| l.point.coords * csc - pole.coords * csc)
        .collect();
    let fs = f.iter().map(|v| v.norm()).fold(0.0, f64::max);
    let arm = r.iter().map(|v| v.norm()).fold(0.0, f64::max);
    let force_sum: nalgebra::Vector2<f64> = f.iter().sum();
    let force = if fs > 0.0 {
        force_sum.norm() / fs
    } else {
        force_sum.norm()
    };
    // Σ r×F = T·2^(ce + fe), F_scale·arm = fs·arm·2^(ce + fe); log2 of the moment scale.
    let t: f64 = r.iter().zip(&f).map(|(r, f)| r.x * f.y - r.y * f.x).sum();
    let l_couples = (fs * arm).log2() + ce + fe;
    let mbig = all.iter().map(|l| l.moment.abs()).fold(0.0, f64::max);
    let l_scale = l_couples.max(mbig.log2());
    if l_scale == f64::NEG_INFINITY {
        return force;
    }
    // Each term divided by the scale 2^l_scale, in the logarithm: every quotient at most a
    // few units, whatever the magnitudes.
    let over = |x: f64, l: f64| x.signum() * (x.abs().log2() + l - l_scale).exp2();
    let moment = over(t, ce + fe)
        + all
            .iter()
            .map(|l| {
                if l.moment == 0.0 {
                    0.0
                } else {
                    over(l.moment, 0.0)
                }
            })
            .sum::<f64>();
    force.max(moment.abs())
}
