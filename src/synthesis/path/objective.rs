//! The global stage's objective of a candidate, and the polish's start from it.

use super::angles::min_max;
use super::budget::{range_samples, SEARCH_STEP};
use super::problem::{fill, Problem};
use super::requirement::Timing;
use super::V;
use crate::kinematics::batch::Lane;

impl Problem {
    /// The global stage's objective of the genes `g`.
    pub(super) fn objective(&mut self, g: &[f64]) -> f64 {
        self.objective_below(g, f64::INFINITY)
    }

    /// [`Problem::objective`] where only a value at or below `above` is of use (the
    /// evolution's trial against its member): without timing the ordered assignment stops
    /// as soon as it knows the value is above (returning a value above it, see
    /// [`assign::Scratch::ordered`](super::assign::Scratch::ordered)).
    pub(super) fn objective_below(&mut self, g: &[f64], above: f64) -> f64 {
        let p = self.lengths_ok(g);
        if p > 0.0 {
            return p;
        }
        let sigma = g[9];
        match &self.timing {
            Timing::Prescribed(delta) => {
                let theta0 = g[10];
                self.phi.clear();
                self.phi.extend(delta.iter().map(|&x| theta0 + x));
                let (mn, mx) = min_max(delta);
                let steps = range_samples(delta, SEARCH_STEP) - 1;
                for k in 0..=steps {
                    self.phi
                        .push(theta0 + mn + (mx - mn) * k as f64 / steps as f64);
                }
                self.angles.set(&self.phi);
                self.out.resize(self.phi.len());
                fill(self.kind, g, sigma, &self.angles, &mut self.out);
                let bad = (0..self.phi.len()).filter(|&i| !self.lane_ok(i)).count();
                if bad > 0 {
                    return self.penalty(0..self.phi.len());
                }
                let n = self.targets.len();
                (0..n)
                    .map(|i| (V::new(self.out.p_x[i], self.out.p_y[i]) - self.targets[i]).norm())
                    .sum::<f64>()
                    / n as f64
            }
            Timing::Free | Timing::ClosedCurve => {
                let m = self.turn.len();
                self.out.resize(m);
                fill(self.kind, g, sigma, &self.turn, &mut self.out);
                let ok: Vec<bool> = (0..m).map(|i| self.lane_ok(i)).collect();
                let closed = matches!(self.timing, Timing::ClosedCurve);
                let n_ok = ok.iter().filter(|&&b| b).count();
                if n_ok == 0 || (closed && n_ok < m) {
                    return self.penalty(0..m);
                }
                let Some(sum) = self.assign.ordered(
                    &self.out.p_x[..m],
                    &self.out.p_y[..m],
                    &ok,
                    &self.targets,
                    above,
                ) else {
                    return self.penalty(0..m);
                };
                sum / self.targets.len() as f64
            }
        }
    }

    /// The polish's unknowns from the genes `g`: the genes without the branch's, then θ0
    /// (prescribed timing) or each point's crank angle (the nearest good sample of a turn).
    pub(super) fn start_of(&mut self, g: &[f64]) -> (Vec<f64>, f64) {
        let sigma = if g[9] > 0.0 { 1.0 } else { -1.0 };
        let mut x: Vec<f64> = g[..9].to_vec();
        if let Timing::Prescribed(_) = self.timing {
            x.push(g[10]);
        } else {
            let m = self.turn.len();
            self.out.resize(m);
            self.budget.add(1);
            fill(self.kind, g, sigma, &self.turn, &mut self.out);
            // The targets' samples in order ([`assign`]) over the usable positions, else
            // over those that assemble (a start the polish may still mend).
            let usable: Vec<bool> = (0..m).map(|i| self.lane_ok(i)).collect();
            let assembles: Vec<bool> = (0..m).map(|i| self.out.status[i] == Lane::Ok).collect();
            let (px, py) = (&self.out.p_x[..m], &self.out.p_y[..m]);
            let found = self
                .assign
                .ordered(px, py, &usable, &self.targets, f64::INFINITY)
                .is_some()
                || self
                    .assign
                    .ordered(px, py, &assembles, &self.targets, f64::INFINITY)
                    .is_some();
            for k in 0..self.targets.len() {
                x.push(if found {
                    self.turn.phi()[self.assign.idx[k]]
                } else {
                    0.0
                });
            }
        }
        (x, sigma)
    }
}
