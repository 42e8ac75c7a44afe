//! One search's problem: the normalised targets, the constraints, the mechanism of a gene
//! vector and its positions, and the whole check of a polished candidate.

use super::angles::{min_max, once_round, ordered_arc};
use super::budget::{Budget, CHECK_STEP};
use super::requirement::Timing;
use super::{assign, slider, Kind, BASE, INFEASIBLE, V};
use crate::kinematics::batch::{
    coupler_point, four_bar_positions, CrankAngles, FourBarDims, Lane, Positions,
};
use crate::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use nalgebra::Point2;
use std::f64::consts::TAU;

pub(super) struct Problem {
    pub(super) kind: Kind,
    pub(super) budget: Budget,
    pub(super) targets: Vec<V>,
    pub(super) timing: Timing,
    pub(super) sin_gamma: f64,
    pub(super) ratio: f64,
    pub(super) size: f64,
    pub(super) turn: CrankAngles,
    pub(super) angles: CrankAngles,
    pub(super) out: Positions,
    pub(super) phi: Vec<f64>,
    /// Free timing's ordered assignment ([`assign`]).
    pub(super) assign: assign::Scratch,
}

pub(super) fn dims_of(g: &[f64], sigma: f64) -> FourBarDims {
    let o = Point2::new(g[0], g[1]);
    FourBarDims {
        o,
        c: o + g[3] * V::new(g[2].cos(), g[2].sin()),
        l_oa: g[4],
        l_ab: g[5],
        l_cb: g[6],
        branch: if sigma > 0.0 {
            Branch::Plus
        } else {
            Branch::Minus
        },
        coupler: V::new(g[7], g[8]),
    }
}

/// The positions of the mechanism of the genes `g` (mode `sigma`) at `angles`, into `out`
/// (sized for them): a batch lane each.
pub(super) fn fill(kind: Kind, g: &[f64], sigma: f64, angles: &CrankAngles, out: &mut Positions) {
    match kind {
        Kind::FourBar => {
            let _ = four_bar_positions(&dims_of(g, sigma), angles, out.columns_mut());
        }
        Kind::SliderCrank => slider::Slider::of(g, sigma).positions(angles, out),
    }
}

/// The coupler point of the genes `g` at the crank angle `phi`, exactly as [`fill`] gives
/// it, with the lane's measure.
pub(super) fn point_of(kind: Kind, g: &[f64], sigma: f64, phi: f64) -> Option<(V, f64)> {
    match kind {
        Kind::FourBar => point_at(&dims_of(g, sigma), phi),
        Kind::SliderCrank => slider::Slider::of(g, sigma)
            .at(phi.cos(), phi.sin())
            .ok()
            .map(|(_, _, p, m)| (p, m)),
    }
}

/// The coupler point of `d` at the crank angle `phi` by the scalar blocks (exactly a batch
/// lane), with sin(φ3 − φ2).
pub(super) fn point_at(d: &FourBarDims, phi: f64) -> Option<(V, f64)> {
    let a = crank(d.o, d.l_oa, Motion::fixed(phi)).ok()?.a;
    let r = rrr_dyad(a, PointMotion::fixed(d.c), d.l_ab, d.l_cb, d.branch).ok()?;
    Some((coupler_point(a.p, r.b.p, d.coupler_uv()).coords, r.det))
}

/// The shortest link a search tries, in path sizes: 2 % of the path, or a tenth of the
/// largest (`max_size`, `s`) when that is smaller, so that every link stays within `s`.
pub(super) fn shortest_link(s: f64) -> f64 {
    0.02_f64.min(0.1 * s)
}

impl Problem {
    pub(super) fn genes(&self) -> usize {
        BASE + usize::from(matches!(self.timing, Timing::Prescribed(_)))
    }

    /// Lower and upper bounds of the genes.
    pub(super) fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let s = self.size;
        let l = shortest_link(s);
        let (mut lo, mut hi) = match self.kind {
            Kind::FourBar => (
                vec![-s, -s, 0.0, l, l, l, l, -s, -s, -1.0],
                vec![s, s, TAU, s, s, s, s, s, s, 1.0],
            ),
            // The offset is signed, and gene 6 unused.
            Kind::SliderCrank => (
                vec![-s, -s, 0.0, -s, l, l, 0.0, -s, -s, -1.0],
                vec![s, s, TAU, s, s, s, 0.0, s, s, 1.0],
            ),
        };
        if self.genes() > BASE {
            lo.push(0.0);
            hi.push(TAU);
        }
        (lo, hi)
    }

    pub(super) fn lengths_ok(&self, g: &[f64]) -> f64 {
        let l = match self.kind {
            Kind::FourBar => &g[3..7],
            Kind::SliderCrank => &g[4..6],
        };
        if self.kind == Kind::SliderCrank && !g[3].is_finite() {
            return INFEASIBLE * 10.0;
        }
        let (mn, mx) = l
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if mn.is_nan() || mn <= 0.0 || !l.iter().all(|x| x.is_finite()) {
            return INFEASIBLE * 10.0;
        }
        let excess = mx / mn / self.ratio - 1.0;
        if excess > 0.0 {
            INFEASIBLE + excess
        } else {
            0.0
        }
    }

    /// Whether the genes `g` are within `max_size` (the search's box): the pivot, the frame or
    /// the slider's offset, the links and the coupler point's offsets. A polish may pass
    /// outside on its way (its path is not constrained, so that it converges as fast as it
    /// can); the design it ends on must be inside.
    pub(super) fn within_size(&self, g: &[f64]) -> bool {
        let l = match self.kind {
            Kind::FourBar => &g[3..7],
            Kind::SliderCrank => &g[4..6],
        };
        [g[0], g[1], g[3], g[7], g[8]]
            .iter()
            .chain(l)
            .all(|x| x.abs() <= self.size)
    }

    pub(super) fn lane_ok(&self, i: usize) -> bool {
        self.lane_ok_in(&self.out, i)
    }

    pub(super) fn lane_ok_in(&self, out: &Positions, i: usize) -> bool {
        out.status[i] == Lane::Ok && out.measure[i].abs() >= self.sin_gamma
    }

    /// How far lane `i` is from acceptable: the shortfall of |sin γ| below sin \[γ\], the gap
    /// (in path sizes) plus 1 where it does not assemble, 2 where it is singular or invalid.
    pub(super) fn shortfall(out: &Positions, sin_gamma: f64, i: usize) -> f64 {
        let m = out.measure[i];
        match out.status[i] {
            Lane::Ok => (sin_gamma - m.abs()).max(0.0),
            Lane::NotAssemblable => 1.0 + m.abs().min(10.0),
            _ => 2.0,
        }
    }

    /// The penalty of an infeasible candidate: the mean shortfall over the lanes `lanes`.
    pub(super) fn penalty(&self, lanes: impl Iterator<Item = usize>) -> f64 {
        self.penalty_in(&self.out, lanes)
    }

    pub(super) fn penalty_in(&self, out: &Positions, lanes: impl Iterator<Item = usize>) -> f64 {
        let (mut sum, mut n) = (0.0, 0usize);
        for i in lanes {
            sum += Self::shortfall(out, self.sin_gamma, i);
            n += 1;
        }
        INFEASIBLE + sum / n.max(1) as f64
    }

    /// The genes of the polish's unknowns `x`.
    pub(super) fn genes_of(&self, x: &[f64], sigma: f64) -> Vec<f64> {
        let mut g = x[..9].to_vec();
        g[2] = g[2].rem_euclid(TAU);
        g.push(sigma);
        if let Timing::Prescribed(_) = self.timing {
            g.push(x[9].rem_euclid(TAU));
        }
        g
    }

    pub(super) fn angle_of(&self, x: &[f64], i: usize) -> f64 {
        match &self.timing {
            Timing::Prescribed(delta) => x[9] + delta[i],
            _ => x[9 + i],
        }
    }

    /// The whole check of a polished point: link ratio, and assembly with γ ≥ \[γ\] over the
    /// input range it needs (sampled every 1°, and at each target's angle).
    pub(super) fn feasible(&mut self, x: &[f64], sigma: f64) -> bool {
        let mut scratch = (
            std::mem::take(&mut self.phi),
            std::mem::take(&mut self.angles),
            std::mem::take(&mut self.out),
        );
        let ok = self.feasible_in(x, sigma, &mut scratch);
        (self.phi, self.angles, self.out) = scratch;
        ok
    }

    /// [`Problem::feasible`] in the scratch space `phi`, `angles`, `out`.
    pub(super) fn feasible_in(
        &self,
        x: &[f64],
        sigma: f64,
        (phi, angles, out): &mut (Vec<f64>, CrankAngles, Positions),
    ) -> bool {
        let g = gene_vec(x, sigma);
        if self.lengths_ok(&g) > 0.0 || !self.within_size(&g) {
            return false;
        }
        let phis: Vec<f64> = (0..self.targets.len())
            .map(|i| self.angle_of(x, i))
            .collect();
        let (start, span) = match self.timing {
            Timing::ClosedCurve => {
                if !once_round(&phis) {
                    return false;
                }
                (0.0, TAU)
            }
            Timing::Prescribed(_) => {
                let (mn, mx) = min_max(&phis);
                (mn, mx - mn)
            }
            Timing::Free => match ordered_arc(&phis) {
                Some(a) => a,
                None => return false,
            },
        };
        let steps = (span / CHECK_STEP).ceil().max(1.0) as usize;
        phi.clear();
        phi.extend_from_slice(&phis);
        phi.extend((0..=steps).map(|k| start + span * k as f64 / steps as f64));
        // A four-bar crank that turns fully is reported (and analysed by the engine) with
        // γ_min over the whole turn, so [γ] must hold there too, not only over the targets'
        // arc: its γ extremes are at the crank in line with the frame (FourBar::gamma_full),
        // two positions more.
        if self.kind == Kind::FourBar && turns_fully(&g) {
            phi.extend([g[2], g[2] + std::f64::consts::PI]);
        }
        angles.set(phi);
        out.resize(phi.len());
        self.budget.add_positions(phi.len());
        fill(self.kind, &g, sigma, angles, out);
        (0..phi.len()).all(|i| self.lane_ok_in(out, i))
    }

    /// The unknowns of the polish whose residuals each move every residual: the nine
    /// dimensions and θ0; the crank angle at each point (free timing) moves its own two.
    pub(super) fn separable(&self) -> usize {
        if let Timing::Prescribed(_) = self.timing {
            10
        } else {
            9
        }
    }
}

/// Whether the crank of the four-bar of the genes `g` (frame g[3], crank g[4], coupler g[5],
/// rocker g[6]) turns fully, by Grashof's class as the report reads it.
fn turns_fully(g: &[f64]) -> bool {
    crate::kinematics::grashof(g[3], g[4], g[5], g[6]).is_ok_and(|c| c.input_turns_fully())
}

pub(super) fn gene_vec(x: &[f64], sigma: f64) -> Vec<f64> {
    let mut g = x[..9].to_vec();
    g.push(sigma);
    g.push(*x.get(9).unwrap_or(&0.0));
    g
}
