//! The polish of a candidate: Levenberg–Marquardt on the exact misses, and without timing
//! the re-assignment of the points' crank angles.

use super::least_squares::levenberg_marquardt;
use super::problem::{fill, gene_vec, point_of, Problem};
use super::requirement::Timing;
use super::slider::Slider;
use super::{Kind, REASSIGNMENTS, V};
use std::f64::consts::TAU;

impl Problem {
    /// Levenberg–Marquardt on the misses from `x` (the link ratio kept; the other
    /// constraints are checked on the result).
    pub(super) fn lm(&self, x: Vec<f64>, sigma: f64, iterations: usize) -> Vec<f64> {
        let res = |x: &[f64]| {
            if self.budget.take_polish() {
                pb_residuals(self.kind, &self.targets, &self.timing, x, sigma)
            } else {
                None
            }
        };
        let mut accept = |x: &[f64]| self.lengths_ok(&gene_vec(x, sigma)) == 0.0;
        levenberg_marquardt(&res, &mut accept, x, self.separable(), iterations)
    }

    /// [`Problem::lm`] with every step also kept within `max_size` (the search's box).
    pub(super) fn lm_within(&self, x: Vec<f64>, sigma: f64, iterations: usize) -> Vec<f64> {
        let res = |x: &[f64]| {
            if self.budget.take_polish() {
                pb_residuals(self.kind, &self.targets, &self.timing, x, sigma)
            } else {
                None
            }
        };
        let mut accept = |x: &[f64]| {
            let g = gene_vec(x, sigma);
            self.lengths_ok(&g) == 0.0 && self.within_size(&g)
        };
        levenberg_marquardt(&res, &mut accept, x, self.separable(), iterations)
    }

    /// The polish without prescribed timing: Levenberg–Marquardt, then, where a point's
    /// crank angle has settled by a local minimum of its distance while the ordered
    /// assignment ([`assign`]) of the polished design's turn puts it elsewhere (another
    /// pass of the curve near the point), again from those angles, kept where the misses
    /// are smaller; up to [`REASSIGNMENTS`] times.
    ///
    /// Why: the unknowns' angles are only as good as the start's assignment; a point met
    /// on the wrong pass of the curve holds the dimensions in a false minimum the damped
    /// steps cannot leave (each pass is its own basin of the point's angle).
    pub(super) fn polish_free(&mut self, x: Vec<f64>, sigma: f64, iterations: usize) -> Vec<f64> {
        let mut x = self.lm(x, sigma, iterations);
        if let Timing::Prescribed(_) = self.timing {
            return x;
        }
        for _ in 0..REASSIGNMENTS {
            let Some(y) = self.reassigned(&x, sigma) else {
                break;
            };
            let y = self.lm(y, sigma, iterations);
            let (before, after) = (self.misses(&x, sigma), self.misses(&y, sigma));
            if after.is_nan() || after >= before {
                break;
            }
            x = y;
        }
        x
    }

    /// The sum of the squared misses at the unknowns `x` (one polish evaluation; infinite
    /// where it does not assemble or the budget is spent).
    pub(super) fn misses(&self, x: &[f64], sigma: f64) -> f64 {
        if !self.budget.take_polish() {
            return f64::INFINITY;
        }
        pb_residuals(self.kind, &self.targets, &self.timing, x, sigma)
            .map_or(f64::INFINITY, |r| r.iter().map(|v| v * v).sum())
    }

    /// The unknowns `x` with each point's crank angle moved to its sample in the ordered
    /// assignment of the design's turn where that lies more than two samples away: `None`
    /// when none does (or nothing is usable, or the budget is spent).
    pub(super) fn reassigned(&mut self, x: &[f64], sigma: f64) -> Option<Vec<f64>> {
        let m = self.turn.len();
        if !self.budget.charge(1.0) {
            return None;
        }
        self.out.resize(m);
        fill(
            self.kind,
            &gene_vec(x, sigma),
            sigma,
            &self.turn,
            &mut self.out,
        );
        let ok: Vec<bool> = (0..m).map(|i| self.lane_ok(i)).collect();
        self.assign.ordered(
            &self.out.p_x[..m],
            &self.out.p_y[..m],
            &ok,
            &self.targets,
            f64::INFINITY,
        )?;
        let far = 2.5 * TAU / m as f64;
        let mut y = x.to_vec();
        let mut moved = false;
        for (k, &i) in self.assign.idx.iter().enumerate() {
            let phi = self.turn.phi()[i];
            let d = (phi - x[9 + k]).rem_euclid(TAU);
            if d.min(TAU - d) > far {
                y[9 + k] = phi;
                moved = true;
            }
        }
        moved.then_some(y)
    }
}

pub(super) fn pb_residuals(
    kind: Kind,
    targets: &[V],
    timing: &Timing,
    x: &[f64],
    sigma: f64,
) -> Option<Vec<f64>> {
    let g = gene_vec(x, sigma);
    let mut r = Vec::with_capacity(2 * targets.len());
    // The slider-crank's guide (a sine and cosine) once, not per point.
    let slider = (kind == Kind::SliderCrank).then(|| Slider::of(&g, sigma));
    for (i, t) in targets.iter().enumerate() {
        let phi = match timing {
            Timing::Prescribed(delta) => x[9] + delta[i],
            _ => x[9 + i],
        };
        let p = match &slider {
            Some(s) => s.at(phi.cos(), phi.sin()).ok()?.2,
            None => point_of(kind, &g, sigma, phi)?.0,
        };
        r.push(p.x - t.x);
        r.push(p.y - t.y);
    }
    Some(r)
}
