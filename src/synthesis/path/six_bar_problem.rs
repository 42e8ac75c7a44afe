//! The Stephenson III six-bar of [`six_bar_path_generator`](super::six_bar_path_generator)
//! as the search sees it: its unknowns, its positions by the engine's blocks (a crank, two
//! RRR dyads), and the problem's misses, constraints and local solvers (Levenberg–Marquardt,
//! continuation) on them.

use super::{
    continuation, levenberg_marquardt, min_max, range_samples, Budget, CHECK_STEP, INFEASIBLE,
    SEARCH_STEP, V,
};
use crate::kinematics::batch::coupler_point;
use crate::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use nalgebra::Point2;
use std::cell::Cell;
use std::f64::consts::TAU;

/// The dimensions (15), then the two modes' genes and θ0.
pub(super) const DIMS: usize = 15;
/// The genes: the dimensions, the two modes' genes and θ0.
pub(super) const GENES: usize = DIMS + 3;
/// The unknowns the box `max_size` bounds: O1 (0, 1), the frame's length and the five
/// links (3–6, 11, 12), C's offsets (7, 8), O5 (9, 10) and P's offsets (13, 14).
const BOXED: [usize; 14] = [0, 1, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14];

/// One Stephenson III six-bar (any units).
#[derive(Debug, Clone, Copy)]
pub(super) struct SixBar {
    pub(super) o1: Point2<f64>,
    pub(super) o3: Point2<f64>,
    pub(super) o5: Point2<f64>,
    pub(super) a: f64,
    pub(super) b: f64,
    pub(super) c: f64,
    /// C on the coupler, (along, across)/AB.
    pub(super) uv_c: [f64; 2],
    pub(super) ce: f64,
    pub(super) e5: f64,
    /// P on CE, (along, across)/CE.
    pub(super) uv_p: [f64; 2],
    pub(super) mode1: Branch,
    pub(super) mode2: Branch,
}

/// The joints of one position: A, B, C, E, P.
pub(super) struct Pose {
    pub(super) a: Point2<f64>,
    pub(super) b: Point2<f64>,
    pub(super) c: Point2<f64>,
    pub(super) e: Point2<f64>,
    pub(super) p: Point2<f64>,
}

fn branch(s: f64) -> Branch {
    if s > 0.0 {
        Branch::Plus
    } else {
        Branch::Minus
    }
}

/// How far a dyad of the links `l1`, `l2` between points `d` apart is from assembling.
fn gap(d: f64, l1: f64, l2: f64) -> f64 {
    (d - (l1 + l2)).max((l1 - l2).abs() - d).max(0.0)
}

impl SixBar {
    /// From the dimensions `x[..15]` and the modes' signs.
    pub(super) fn of(x: &[f64], s1: f64, s2: f64) -> Self {
        let o1 = Point2::new(x[0], x[1]);
        Self {
            o1,
            o3: o1 + x[3] * V::new(x[2].cos(), x[2].sin()),
            o5: Point2::new(x[9], x[10]),
            a: x[4],
            b: x[5],
            c: x[6],
            uv_c: [x[7] / x[5], x[8] / x[5]],
            ce: x[11],
            e5: x[12],
            uv_p: [x[13] / x[11], x[14] / x[11]],
            mode1: branch(s1),
            mode2: branch(s2),
        }
    }

    /// The pose at the crank angle `phi` and the smaller |sin γ| of the two dyads; where it
    /// does not assemble (or is singular), the shortfall: 1 + the gap, or 2.
    pub(super) fn at(&self, phi: f64) -> std::result::Result<(Pose, f64), f64> {
        let a = crank(self.o1, self.a, Motion::fixed(phi))
            .map_err(|_| 2.0)?
            .a;
        let r1 = rrr_dyad(a, PointMotion::fixed(self.o3), self.b, self.c, self.mode1)
            .map_err(|_| 1.0 + gap((self.o3 - a.p).norm(), self.b, self.c).min(10.0))?;
        let c = coupler_point(a.p, r1.b.p, self.uv_c);
        let r2 = rrr_dyad(
            PointMotion::fixed(c),
            PointMotion::fixed(self.o5),
            self.ce,
            self.e5,
            self.mode2,
        )
        .map_err(|_| 1.0 + gap((self.o5 - c).norm(), self.ce, self.e5).min(10.0))?;
        let p = coupler_point(c, r2.b.p, self.uv_p);
        let m = r1.det.abs().min(r2.det.abs());
        if !(p.x + p.y + m).is_finite() {
            return Err(2.0);
        }
        Ok((
            Pose {
                a: a.p,
                b: r1.b.p,
                c,
                e: r2.b.p,
                p,
            },
            m,
        ))
    }
}

pub(super) struct Problem<'a> {
    pub(super) budget: Budget,
    /// The positions the engine's blocks solved for the search (each counted in `budget`).
    pub(super) solved: Cell<usize>,
    pub(super) targets: Vec<V>,
    pub(super) delta: &'a [f64],
    pub(super) sin_gamma: f64,
    pub(super) ratio: f64,
    pub(super) size: f64,
}

impl Problem<'_> {
    /// 0 where the six links keep the ratio bound, else a penalty above [`INFEASIBLE`].
    pub(super) fn lengths_ok(&self, x: &[f64]) -> f64 {
        let l = [x[3], x[4], x[5], x[6], x[11], x[12]];
        if !x[..DIMS].iter().all(|v| v.is_finite()) || l.iter().any(|&v| v.is_nan() || v <= 0.0) {
            return INFEASIBLE * 10.0;
        }
        let (mn, mx) = min_max(&l);
        let excess = mx / mn / self.ratio - 1.0;
        if excess > 0.0 {
            INFEASIBLE + excess
        } else {
            0.0
        }
    }

    /// Whether the unknowns `x` are within the box `max_size` (path sizes): the pivots O1 and
    /// O5 (each coordinate from the points' centroid), the six lengths and the offsets of C
    /// and P (the search's bounds; the frame's angle and θ0 are free).
    pub(super) fn within(&self, x: &[f64]) -> bool {
        BOXED.iter().all(|&k| x[k].abs() <= self.size)
    }

    /// The crank angles of the points and `step`-spaced samples of the range between them.
    pub(super) fn angles(&self, theta0: f64, step: f64) -> Vec<f64> {
        let (mn, mx) = min_max(self.delta);
        let steps = range_samples(self.delta, step) - 1;
        self.delta
            .iter()
            .map(|d| theta0 + d)
            .chain((0..=steps).map(|k| theta0 + mn + (mx - mn) * k as f64 / steps as f64))
            .collect()
    }

    /// The mean miss of the unknowns `x` (dimensions, θ0) with the modes `s`, if every
    /// sample at `step` assembles with γ ≥ \[γ\]; else a penalty ≥ [`INFEASIBLE`].
    pub(super) fn cost(&self, x: &[f64], s: [f64; 2], step: f64) -> f64 {
        let p = self.lengths_ok(x);
        if p > 0.0 {
            return p;
        }
        let m = SixBar::of(x, s[0], s[1]);
        let phis = self.angles(x[DIMS], step);
        self.solved.set(self.solved.get() + phis.len());
        let (mut miss, mut short, mut bad) = (0.0, 0.0, false);
        for (i, &phi) in phis.iter().enumerate() {
            match m.at(phi) {
                Ok((pose, g)) => {
                    short += (self.sin_gamma - g).max(0.0);
                    bad |= g < self.sin_gamma;
                    if let Some(t) = self.targets.get(i).filter(|_| i < self.delta.len()) {
                        miss += (pose.p.coords - t).norm();
                    }
                }
                Err(s) => {
                    short += s;
                    bad = true;
                }
            }
        }
        if bad {
            INFEASIBLE + short / phis.len() as f64
        } else {
            miss / self.delta.len() as f64
        }
    }

    pub(super) fn objective(&self, g: &[f64]) -> f64 {
        self.budget.add(1);
        let (x, s) = split(g);
        // Outside the box (a Lamarckian polish that left it; the evolution's own trials stay
        // within its bounds, which are the box): refused, so that the population stays in
        // the box where the designs must end.
        if !self.within(&x) {
            return INFEASIBLE * 10.0;
        }
        self.cost(&x, s, SEARCH_STEP)
    }

    pub(super) fn residuals(&self, x: &[f64], s: [f64; 2]) -> Option<Vec<f64>> {
        if !self.budget.take_polish() {
            return None;
        }
        let m = SixBar::of(x, s[0], s[1]);
        let mut r = Vec::with_capacity(2 * self.targets.len());
        for (t, d) in self.targets.iter().zip(self.delta) {
            self.solved.set(self.solved.get() + 1);
            let (pose, _) = m.at(x[DIMS] + d).ok()?;
            r.push(pose.p.x - t.x);
            r.push(pose.p.y - t.y);
        }
        Some(r)
    }

    /// Levenberg–Marquardt on the misses, the link ratio kept; if `within`, each step also
    /// kept within the other constraints (the box `max_size`, and assembly with γ ≥ \[γ\]
    /// over the range as the search samples it): a free polish that converges to a design
    /// the whole check refuses (outside the box, or the points met only past a dead point)
    /// is done again within them.
    pub(super) fn lm(&self, x: Vec<f64>, s: [f64; 2], iterations: usize, within: bool) -> Vec<f64> {
        let res = |x: &[f64]| self.residuals(x, s);
        let mut accept = |x: &[f64]| {
            self.lengths_ok(x) == 0.0
                && (!within || self.within(x))
                && (!within
                    || self.budget.room(1) && {
                        self.budget.add(1);
                        self.cost(x, s, SEARCH_STEP) < INFEASIBLE
                    })
        };
        let n = x.len();
        levenberg_marquardt(&res, &mut accept, x, n, iterations)
    }

    /// [`continuation`] from the near miss `x` to the points, the link ratio kept.
    pub(super) fn follow(&self, x: Vec<f64>, s: [f64; 2]) -> Vec<f64> {
        let res = |x: &[f64]| self.residuals(x, s);
        let mut accept = |x: &[f64]| self.lengths_ok(x) == 0.0;
        let n = x.len();
        continuation(&res, &mut accept, x, n, 400)
    }

    /// The whole check: the box `max_size`, the ratio, assembly with γ ≥ \[γ\] every 1° of
    /// the range; the mean miss where it passes, `None` where it does not (or the budget has
    /// no room for it).
    pub(super) fn check(&self, x: &[f64], s: [f64; 2]) -> Option<f64> {
        if !self.within(x) || !self.budget.charge(self.budget.check) {
            return None;
        }
        Some(self.cost(x, s, CHECK_STEP)).filter(|&c| c < INFEASIBLE)
    }
}

/// The unknowns (dimensions, θ0) and the modes' signs of the genes `g`.
pub(super) fn split(g: &[f64]) -> (Vec<f64>, [f64; 2]) {
    let mut x = g[..DIMS].to_vec();
    x.push(g[DIMS + 2]);
    (x, [g[DIMS].signum(), g[DIMS + 1].signum()])
}

/// The genes of the unknowns `x` (dimensions, θ0) and the modes' signs `s`, the angles
/// taken modulo a turn.
pub(super) fn genes_of(x: &[f64], s: [f64; 2]) -> Vec<f64> {
    let mut g = x[..DIMS].to_vec();
    g[2] = g[2].rem_euclid(TAU);
    g.extend([s[0], s[1], x[DIMS].rem_euclid(TAU)]);
    g
}
