//! The flywheel for a required coefficient of speed fluctuation, by the energy–mass method
//! of Wittenbauer and by the textbook's simplified formula (derivations in the
//! [module docs](super)).

use std::f64::consts::TAU;

use super::system::LinkageSystem;
use crate::error::{computed, finite, positive, Error, Result};

/// A flywheel designed for a coefficient of speed fluctuation δ at a mean speed ω_m, with
/// the constant driving moment that balances the loads over a turn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flywheel {
    /// The required δ = (ω_max − ω_min)/ω_m.
    pub delta: f64,
    /// The mean speed ω_m = (ω_max + ω_min)/2, rad/s (signed: negative turns clockwise).
    pub omega_mean: f64,
    /// The constant driving moment M_d = −(1/2π)∮ M_red dφ, N·m.
    pub driving_moment: f64,
    /// J_F by the energy–mass method (exact for the model), kg·m². Negative: the machine's own
    /// inertia keeps δ below the required value without a flywheel.
    pub moment_of_inertia: f64,
    /// J_F by the simplified formula ΔE/(δ·ω_m²) − J̄, kg·m².
    pub simplified: f64,
    /// ΔE, the range over the turn of W(φ) − ½·J_red(φ)·ω_m², J.
    pub energy_range: f64,
    /// The range over the turn of the work W(φ) alone, J.
    pub work_range: f64,
    /// J̄, the mean reduced moment of inertia of the machine without the flywheel, kg·m².
    pub inertia_mean: f64,
    /// The crank angle the turn starts from (the reference pose), rad.
    pub phi_start: f64,
    /// The speed there on the designed steady turn (signed), rad/s; `None` when J_F is so
    /// negative that no such turn exists.
    pub omega_start: Option<f64>,
}

impl LinkageSystem {
    /// The flywheel on the crank that keeps the coefficient of speed fluctuation at `delta`
    /// at the mean speed `omega_mean` under a constant driving moment, from the reduced
    /// moment of inertia and moment at `n` equally spaced positions (the loads that depend
    /// on the speed taken at `omega_mean`; the motor of the machine is not used). Add
    /// [`moment_of_inertia`](Flywheel::moment_of_inertia) with
    /// [`with_inertia`](Self::with_inertia) and drive with
    /// [`Motor::Constant`](super::Motor::Constant)`(driving_moment)` to get the designed turn.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for δ outside (0, 2) or n below 8 (or above 10⁷);
    /// [`Error::NonFinite`]/[`Error::NonPositive`] for a non-finite or zero `omega_mean`;
    /// [`Error::Description`] for a machine that is not one crank; as
    /// [`reduced`](Self::reduced).
    ///
    /// # Examples
    /// The Watt six-bar at 15 rad/s, δ = 1/20: the exact and the simplified flywheel agree
    /// within a few per cent.
    /// ```
    /// use tmm::linkage::{bundled, dynamics::LinkageSystem};
    /// let sys = LinkageSystem::from_linkage(&bundled::watt_six_bar())?;
    /// let f = sys.flywheel(1.0 / 20.0, 15.0, 720)?;
    /// assert!(f.moment_of_inertia > 0.0);
    /// assert!((f.simplified / f.moment_of_inertia - 1.0).abs() < 0.1);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn flywheel(&self, delta: f64, omega_mean: f64, n: usize) -> Result<Flywheel> {
        if !(delta > 0.0 && delta < 2.0) {
            return Err(Error::OutOfRange {
                name: "coefficient of speed fluctuation delta",
                value: delta,
                min: 0.0,
                max: 2.0,
                ends: crate::Ends::Open,
            });
        }
        if !(8..=10_000_000).contains(&n) {
            return Err(Error::OutOfRange {
                name: "number of positions",
                value: n as f64,
                min: 8.0,
                max: 1e7,
                ends: crate::Ends::Closed,
            });
        }
        let wm = positive("|omega_mean|", finite("omega_mean", omega_mean)?.abs())?;
        let dir = omega_mean.signum();
        let red = self.reduced_cycle(n, omega_mean)?;
        let m_d = -red.iter().map(|r| r.loads).sum::<f64>() / n as f64;
        // W at every position by the trapezoidal rule, closed over the turn (W_n = 0).
        let du = TAU / n as f64;
        let mut w = Vec::with_capacity(n);
        let mut acc = 0.0;
        for i in 0..n {
            w.push(acc);
            let next = red[(i + 1) % n].loads;
            acc += dir * 0.5 * du * ((m_d + red[i].loads) + (m_d + next));
        }
        let j: Vec<f64> = red.iter().map(|r| r.inertia).collect();
        let (w_max, w_min) = ((1.0 + 0.5 * delta) * wm, (1.0 - 0.5 * delta) * wm);
        let (psi_p, psi_m) = (0.5 * w_max * w_max, 0.5 * w_min * w_min);
        let fold = |f: &dyn Fn(usize) -> f64, max: bool| {
            (0..n).map(f).fold(
                if max {
                    f64::NEG_INFINITY
                } else {
                    f64::INFINITY
                },
                |a, b| if max { a.max(b) } else { a.min(b) },
            )
        };
        let c_max = fold(&|i| psi_p * j[i] - w[i], false);
        let c_min = fold(&|i| psi_m * j[i] - w[i], true);
        let j_f = computed(
            "flywheel moment of inertia",
            (c_min - c_max) / (psi_p - psi_m),
        )?;
        let e0 = c_max + psi_p * j_f;
        let omega_start = {
            let o2 = 2.0 * e0 / (j_f + j[0]);
            (o2 > 0.0
                && o2.is_finite()
                && j_f + j.iter().copied().fold(f64::INFINITY, f64::min) > 0.0)
                .then(|| dir * o2.sqrt())
        };
        let j_mean = j.iter().sum::<f64>() / n as f64;
        let e: Vec<f64> = (0..n).map(|i| w[i] - 0.5 * j[i] * wm * wm).collect();
        let range = |v: &[f64]| {
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - v.iter().copied().fold(f64::INFINITY, f64::min)
        };
        let energy_range = range(&e);
        let work_range = range(&w);
        Ok(Flywheel {
            delta,
            omega_mean,
            driving_moment: m_d,
            moment_of_inertia: j_f,
            simplified: computed(
                "simplified flywheel",
                energy_range / (delta * wm * wm) - j_mean,
            )?,
            energy_range,
            work_range,
            inertia_mean: j_mean,
            phi_start: self.plan().reference_input(),
            omega_start,
        })
    }
}
