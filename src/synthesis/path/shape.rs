//! The global stage without prescribed timing: a search over the *shapes* of four-bars —
//! frame 1, crank, coupler and rocker (by their logarithms), the coupler point in units of the
//! coupler, the assembly mode — each candidate's coupler curve placed on the targets by the
//! similarity (scale, turn, shift) that fits it best, in closed form.
//!
//! Why: a similarity z ↦ αz + t (α, t complex) maps a four-bar onto a four-bar whose coupler
//! curve is the image of the first one's, so four of the nine dimensions need no search. For
//! given correspondences Q_i ↔ P_i the misses P_i − αQ_i − t are linear in α and t, and the
//! least-squares fit is α = Σ conj(Q_i − Q̄)(P_i − P̄) / Σ|Q_i − Q̄|², t = P̄ − αQ̄, leaving
//! Σ|P_i − P̄|² − |Σ conj(Q_i − Q̄)(P_i − P̄)|² / Σ|Q_i − Q̄|².
//!
//! The correspondences come from arc length, which a similarity scales uniformly: the targets,
//! in order, sit at fractions τ_i of their polyline's length; the candidate's curve (a closed
//! loop when its crank turns fully, its longest run of acceptable positions otherwise) is cut
//! at a start and a span (the whole loop for a closed target curve), each target put at its
//! fraction along the cut, and the start, span and sense that fit best are chosen on a grid,
//! then refined by halving steps. For the shape that traces the targets' curve the fit is
//! close (the chords between targets lag the arcs a little); each target is then projected
//! onto the curve between samples and the similarity refitted to the tangents there, which
//! takes that shape's cost to the interpolation's miss (~1e-8 of the path's size), far below
//! its neighbours'. Levenberg–Marquardt on the exact misses, with the crank angles found here
//! as its start, then finishes.

use super::{Problem, INFEASIBLE, V};
use crate::kinematics::batch::{four_bar_positions, CrankAngles, FourBarDims, Positions};
use crate::kinematics::Branch;
use nalgebra::{Matrix4, Point2, Vector4};
use std::f64::consts::TAU;

/// Shape genes: ln crank, ln coupler, ln rocker (frame 1), the coupler point (along, across)
/// in units of the coupler, the mode's sign.
pub(super) const SHAPE: usize = 6;

/// Start positions on the grid of a cut, and spans (open paths) tried per sense.
const STARTS: usize = 48;
/// The relative improvement of a run's best that counts as progress: a run that improves
/// less over [`STAGNATION`](super::STAGNATION) generations creeps along a wall or a flat
/// valley, and a fresh population is a better use of the budget.
const PROGRESS: f64 = 1e-3;
const SPANS: usize = 10;
/// Every how many members of a fresh population one is drawn with its coupler point near
/// the crank pin (its genes scaled by [`PIN_BOX`]), and every how many runs (the second of
/// each [`PIN_RUNS`]) search only there. Why: such a coupler point traces a near-circle,
/// which a wide family of other shapes fits to a few 1e-4 of the path's size; the shape that
/// traces the targets exactly has a narrow basin there, which draws over the whole box of
/// coupler points (±3 coupler lengths) seldom reach and a population drawn there leaves.
const NEAR_PIN: usize = 4;
const PIN_RUNS: usize = 3;
/// The coupler point's box near the pin, as a share of the whole box (±0.3 coupler lengths).
const PIN_BOX: f64 = 0.1;
/// The most rounds of projection and fit in [`Shapes::snap`].
const SNAPS: usize = 8;
/// The shortest span tried, as a fraction of the run.
const SPAN_RATIO: f64 = 0.08;

/// The best cut of a candidate: where the targets sit on its curve and the similarity.
#[derive(Debug, Clone, Copy)]
struct Cut {
    start: f64,
    span: f64,
    forward: bool,
    cost: f64,
    alpha: V,
    t: V,
}

/// The shape stage's data and scratch space.
pub(super) struct Shapes {
    targets: Vec<V>,
    /// Arc-length fraction of each target along the targets' polyline (closed: loop).
    tau: Vec<f64>,
    closed: bool,
    turn: CrankAngles,
    out: Positions,
    /// Lanes along the run of acceptable positions, in crank order.
    run: Vec<usize>,
    /// Whether the run is the whole turn (a loop).
    looped: bool,
    /// Cumulative arc length at each run position (a loop has one more: back to the first).
    arc: Vec<f64>,
    q: Vec<V>,
    pos: Vec<f64>,
    /// Scratch of [`Shapes::snap`].
    q2: Vec<V>,
    pos2: Vec<f64>,
    tangent: Vec<V>,
}

/// Complex product a·b of vectors read as complex numbers.
fn mul(a: V, b: V) -> V {
    V::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// The least-squares similarity taking `q` onto `p`: (remaining sum of squares, α, t).
fn similarity(p: &[V], q: &[V]) -> Option<(f64, V, V)> {
    let n = p.len() as f64;
    let pm = p.iter().sum::<V>() / n;
    let qm = q.iter().sum::<V>() / n;
    let (mut num, mut den, mut pp) = (V::zeros(), 0.0, 0.0);
    for (a, b) in q.iter().zip(p) {
        let (dq, dp) = (a - qm, b - pm);
        num += V::new(dq.x * dp.x + dq.y * dp.y, dq.x * dp.y - dq.y * dp.x);
        den += dq.norm_squared();
        pp += dp.norm_squared();
    }
    if den.is_nan() || den <= 1e-30 {
        return None;
    }
    let alpha = num / den;
    Some((
        (pp - num.norm_squared() / den).max(0.0),
        alpha,
        pm - mul(alpha, qm),
    ))
}

/// The similarity (α, t) that puts the points `q` of the unplaced curve on the tangent lines
/// through the targets `p`, in the least-squares sense: the misses along the placed curve's
/// normals n_i (the tangents `d` turned by `alpha` and a right angle),
/// n_i·(αq_i + t − p_i), are linear in (Re α, Im α, t), four unknowns of a 4×4 system.
fn tangent_fit(p: &[V], q: &[V], d: &[V], alpha: V) -> Option<(V, V)> {
    let mut a = Matrix4::zeros();
    let mut b = Vector4::zeros();
    for ((pi, qi), di) in p.iter().zip(q).zip(d) {
        let dir = mul(alpha, *di);
        let len = dir.norm();
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let n = V::new(-dir.y, dir.x) / len;
        let row = Vector4::new(n.dot(qi), n.dot(&V::new(-qi.y, qi.x)), n.x, n.y);
        a += row * row.transpose();
        b += row * n.dot(pi);
    }
    let x = a.lu().solve(&b)?;
    x.iter()
        .all(|v| v.is_finite())
        .then(|| (V::new(x[0], x[1]), V::new(x[2], x[3])))
}

impl Shapes {
    pub(super) fn new(pb: &Problem, positions: usize) -> Self {
        let closed = matches!(pb.timing, super::Timing::ClosedCurve);
        let n = pb.targets.len();
        let mut tau = vec![0.0; n];
        for i in 1..n {
            tau[i] = tau[i - 1] + (pb.targets[i] - pb.targets[i - 1]).norm();
        }
        let total = tau[n - 1]
            + if closed {
                (pb.targets[0] - pb.targets[n - 1]).norm()
            } else {
                0.0
            };
        for x in &mut tau {
            *x /= total;
        }
        Self {
            targets: pb.targets.clone(),
            tau,
            closed,
            turn: CrankAngles::turn(positions),
            out: Positions::new(positions),
            run: Vec::with_capacity(positions),
            looped: false,
            arc: Vec::with_capacity(positions + 1),
            q: vec![V::zeros(); n],
            pos: vec![0.0; n],
            q2: vec![V::zeros(); n],
            pos2: vec![0.0; n],
            tangent: vec![V::zeros(); n],
        }
    }

    /// Gene bounds for the link ratio `ratio`.
    pub(super) fn bounds(ratio: f64) -> (Vec<f64>, Vec<f64>) {
        let l = ratio.ln();
        (
            vec![-l, -l, -l, -3.0, -3.0, -1.0],
            vec![l, l, l, 3.0, 3.0, 1.0],
        )
    }

    fn dims(h: &[f64]) -> FourBarDims {
        let b = h[1].exp();
        FourBarDims {
            o: Point2::origin(),
            c: Point2::new(1.0, 0.0),
            l_oa: h[0].exp(),
            l_ab: b,
            l_cb: h[2].exp(),
            branch: if h[5] > 0.0 {
                Branch::Plus
            } else {
                Branch::Minus
            },
            coupler: V::new(h[3] * b, h[4] * b),
        }
    }

    /// The objective of the shape `h`: the RMS miss of the best cut, in path sizes, or a
    /// penalty ≥ [`INFEASIBLE`].
    pub(super) fn cost(&mut self, pb: &Problem, h: &[f64]) -> f64 {
        match self.cut(pb, h) {
            Ok(c) => c.cost,
            Err(p) => p,
        }
    }

    /// The genes of [`Problem`] (normalised world) and the crank angles at the targets of
    /// the shape `h` placed by its best cut.
    pub(super) fn place(&mut self, pb: &Problem, h: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        pb.budget.add(1);
        let c = self.cut(pb, h).ok()?;
        let (k, turn) = (c.alpha.norm(), c.alpha.y.atan2(c.alpha.x));
        let d = Self::dims(h);
        let genes = vec![
            c.t.x,
            c.t.y,
            turn.rem_euclid(TAU),
            k,
            d.l_oa * k,
            d.l_ab * k,
            d.l_cb * k,
            d.coupler.x * k,
            d.coupler.y * k,
            h[5].signum(),
        ];
        let m = self.turn.len() as f64;
        let first = self.turn.phi()[self.run[0]];
        let phis = self
            .pos
            .iter()
            .map(|&j| first + j * TAU / m + turn)
            .collect();
        Some((genes, phis))
    }

    fn cut(&mut self, pb: &Problem, h: &[f64]) -> Result<Cut, f64> {
        let l = [1.0, h[0].exp(), h[1].exp(), h[2].exp()];
        let (mn, mx) = super::min_max(&l);
        if mx / mn > pb.ratio || (mx / mn).is_nan() {
            return Err(INFEASIBLE + (mx / mn / pb.ratio).min(1e3));
        }
        let d = Self::dims(h);
        let _ = four_bar_positions(&d, &self.turn, self.out.columns_mut());
        self.runs(pb)?;
        let total = *self.arc.last().unwrap_or(&0.0);
        if total.is_nan() || total <= 0.0 {
            return Err(INFEASIBLE + 2.0);
        }
        let mut best: Option<Cut> = None;
        let spans = if self.closed { 1 } else { SPANS };
        for forward in [true, false] {
            for k in 0..spans {
                // Spans from the whole run down to a tenth of it, geometrically.
                let span = total * SPAN_RATIO.powf(k as f64 / SPANS as f64);
                let room = if self.looped { total } else { total - span };
                let starts = if self.looped || room > 0.0 { STARTS } else { 1 };
                for k in 0..starts {
                    let start = room * k as f64 / starts as f64;
                    if let Some(c) = self.try_cut(start, span, forward)
                        && best.is_none_or(|b| c.cost < b.cost)
                    {
                        best = Some(c);
                    }
                }
            }
        }
        let mut best = best.ok_or(INFEASIBLE + 2.0)?;
        // Refine the start (and an open path's span) by halving steps about the best; the
        // span's first step is half the spans' grid ratio (a span between two of the grid's
        // is reached whatever it is).
        let mut step = total / STARTS as f64;
        let mut span_step = best.span * (1.0 - SPAN_RATIO.powf(1.0 / SPANS as f64));
        for _ in 0..10 {
            step /= 2.0;
            span_step /= 2.0;
            for (ds, dw) in [
                (step, 0.0),
                (-step, 0.0),
                (0.0, span_step),
                (0.0, -span_step),
            ] {
                if self.closed && dw != 0.0 {
                    continue;
                }
                let (start, span) = (best.start + ds, best.span + dw);
                let fits = span > 0.0
                    && span <= total
                    && (self.looped || (start >= 0.0 && start + span <= total));
                if fits
                    && let Some(c) = self.try_cut(start, span, best.forward)
                    && c.cost < best.cost
                {
                    best = c;
                }
            }
        }
        self.fill(best.start, best.span, best.forward);
        self.snap(&mut best);
        // The placed design within the size bound.
        let k = best.alpha.norm();
        let far = [
            k * l[0],
            k * l[1],
            k * l[2],
            k * l[3],
            best.t.norm(),
            (best.alpha + best.t).norm(),
            k * d.coupler.x.abs(),
            k * d.coupler.y.abs(),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        if far.is_nan() || far > pb.size {
            return Err(INFEASIBLE + (far / pb.size).min(1e3));
        }
        Ok(best)
    }

    /// The run of acceptable lanes: the whole turn, or (open paths) the longest stretch of
    /// consecutive ones; its cumulative arc length. A penalty when there is none.
    fn runs(&mut self, pb: &Problem) -> Result<(), f64> {
        let m = self.turn.len();
        let ok = |i: usize| pb.lane_ok_in(&self.out, i);
        self.run.clear();
        self.arc.clear();
        let bad = (0..m).filter(|&i| !ok(i)).count();
        if bad == 0 {
            self.looped = true;
            self.run.extend(0..m);
        } else if self.closed || bad == m {
            return Err(pb.penalty_in(&self.out, 0..m));
        } else {
            self.looped = false;
            // The longest stretch of good lanes, cyclically: start after a bad lane.
            let first_bad = (0..m).find(|&i| !ok(i)).unwrap_or(0);
            let (mut best, mut cur) = ((0, 0), (0, 0));
            for s in 1..=m {
                let i = (first_bad + s) % m;
                if ok(i) {
                    if cur.1 == 0 {
                        cur.0 = i;
                    }
                    cur.1 += 1;
                    if cur.1 > best.1 {
                        best = cur;
                    }
                } else {
                    cur.1 = 0;
                }
            }
            if best.1 < 8 {
                return Err(pb.penalty_in(&self.out, 0..m));
            }
            self.run.extend((0..best.1).map(|j| (best.0 + j) % m));
        }
        let mut s = 0.0;
        self.arc.push(0.0);
        let len = self.run.len() + usize::from(self.looped);
        for j in 1..len {
            s += (self.point(j) - self.point(j - 1)).norm();
            self.arc.push(s);
        }
        Ok(())
    }

    /// The coupler point at run position `j` (a loop wraps).
    fn point(&self, j: usize) -> V {
        let i = self.run[j % self.run.len()];
        V::new(self.out.p_x[i], self.out.p_y[i])
    }

    /// The point at arc length `s` along the run, and its fractional run position.
    fn at(&self, s: f64) -> (V, f64) {
        let total = self.arc[self.arc.len() - 1];
        let s = if self.looped {
            s.rem_euclid(total)
        } else {
            s.clamp(0.0, total)
        };
        let j = self
            .arc
            .partition_point(|&x| x <= s)
            .saturating_sub(1)
            .min(self.arc.len() - 2);
        let seg = self.arc[j + 1] - self.arc[j];
        let f = if seg > 0.0 {
            ((s - self.arc[j]) / seg).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (p0, p1) = (self.point(j), self.point(j + 1));
        (p0 + f * (p1 - p0), j as f64 + f)
    }

    /// Puts the targets on the cut (start, span, sense): their points in `q`, their run
    /// positions in `pos`.
    fn fill(&mut self, start: f64, span: f64, forward: bool) {
        for i in 0..self.targets.len() {
            let f = if forward {
                self.tau[i]
            } else {
                1.0 - self.tau[i]
            };
            let (p, j) = self.at(start + f * span);
            self.q[i] = p;
            self.pos[i] = j;
        }
    }

    /// Moves each target's point on the curve to the curve's point nearest to the target as
    /// placed (within a target's share of the run about where the cut put it) and fits the
    /// similarity again, while that lowers the cost. The chords between the targets lag the
    /// arcs most where the curve turns sharply: this takes the correspondences from the
    /// geometry instead. Leaves the run positions of the best correspondences in `pos`.
    ///
    /// Why between samples, and why the fit to the curve's tangents: a correspondence at the
    /// nearest sample leaves a miss of up to half a sample's spacing even for the shape that
    /// traces the targets, a floor under the cost below which the search cannot tell shapes
    /// apart (many shapes fit ten points to that floor). On the parabola through three samples
    /// the miss of the traced curve is of the order of the spacing cubed; and the similarity
    /// fitted to the tangent lines at the correspondences (misses measured along the curve's
    /// normals, linear in α and t) lets each target slide along the curve, which the
    /// point-to-point fit of fixed correspondences does not: alternated with the projection
    /// it converges to a miss of zero for that shape in a few steps, where the point-to-point
    /// fit creeps.
    fn snap(&mut self, best: &mut Cut) {
        let n = self.targets.len();
        let (mut pos, mut q) = (std::mem::take(&mut self.pos2), std::mem::take(&mut self.q2));
        let mut tangent = std::mem::take(&mut self.tangent);
        pos.copy_from_slice(&self.pos);
        let (mut alpha, mut t) = (best.alpha, best.t);
        for round in 0..SNAPS {
            let mut sum = 0.0;
            for i in 0..n {
                let w = self.unplaced(alpha, t, self.targets[i]);
                let reach = if round == 0 { None } else { Some(3) };
                let (j, p, d) = self.nearest(pos[i], w, reach);
                (pos[i], q[i], tangent[i]) = (j, p, d);
                sum += (mul(alpha, p) + t - self.targets[i]).norm_squared();
            }
            let cost = (sum / n as f64).sqrt();
            if cost < best.cost {
                (best.alpha, best.t, best.cost) = (alpha, t, cost);
                self.pos.copy_from_slice(&pos);
                self.q.copy_from_slice(&q);
            } else if round > 0 {
                break;
            }
            let fit = if round == 0 {
                similarity(&self.targets, &q).map(|(_, a, b)| (a, b))
            } else {
                tangent_fit(&self.targets, &q, &tangent, alpha)
            };
            let Some(next) = fit else { break };
            (alpha, t) = next;
        }
        (self.pos2, self.q2, self.tangent) = (pos, q, tangent);
    }

    /// The point `p` of the world taken back to the unplaced curve by the similarity
    /// (`alpha`, `t`): (p − t)/α.
    fn unplaced(&self, alpha: V, t: V, p: V) -> V {
        let n = alpha.norm_squared();
        if n.is_nan() || n <= 0.0 {
            return p;
        }
        mul(p - t, V::new(alpha.x, -alpha.y)) / n
    }

    /// The point of the run nearest to `w` (on the unplaced curve) within `reach` samples
    /// (by default a target's share of the run) about the run position `about`: its fractional run position, the point and the
    /// curve's tangent there (per sample). The nearest sample first, then Newton's method on
    /// (Q(s) − w)·Q′(s) = 0 along the parabola Q through it and its neighbours.
    fn nearest(&self, about: f64, w: V, reach: Option<isize>) -> (f64, V, V) {
        let len = self.run.len() as isize;
        let span = reach.unwrap_or((len / self.targets.len() as isize).max(2));
        let centre = about.round() as isize;
        let mut near = (f64::INFINITY, centre.clamp(0, len - 1));
        for j in centre - span..=centre + span {
            let j = if self.looped {
                j.rem_euclid(len)
            } else if (0..len).contains(&j) {
                j
            } else {
                continue;
            };
            let dd = (self.point(j as usize) - w).norm_squared();
            if dd < near.0 {
                near = (dd, j);
            }
        }
        let j = near.1;
        // The parabola's middle sample: an open run's ends have a neighbour on one side only.
        let c = if self.looped { j } else { j.clamp(1, len - 2) };
        let at = |k: isize| self.point(k.rem_euclid(len) as usize);
        let (p0, pm, pp) = (at(c), at(c - 1), at(c + 1));
        let (d1, d2) = ((pp - pm) / 2.0, pp - 2.0 * p0 + pm);
        let mut s = (j - c) as f64;
        for _ in 0..4 {
            let (qs, dq) = (p0 + s * d1 + 0.5 * s * s * d2, d1 + s * d2);
            let slope = dq.norm_squared() + (qs - w).dot(&d2);
            if slope.is_nan() || slope <= 0.0 {
                break;
            }
            s = (s - (qs - w).dot(&dq) / slope).clamp(-1.0, 1.0);
        }
        let qs = p0 + s * d1 + 0.5 * s * s * d2;
        if (qs - w).norm_squared() < near.0 {
            let place = c as f64 + s;
            (place.rem_euclid(len as f64), qs, d1 + s * d2)
        } else {
            (j as f64, self.point(j as usize), d1 + (j - c) as f64 * d2)
        }
    }

    fn try_cut(&mut self, start: f64, span: f64, forward: bool) -> Option<Cut> {
        self.fill(start, span, forward);
        let (res, alpha, t) = similarity(&self.targets, &self.q)?;
        Some(Cut {
            start,
            span,
            forward,
            cost: (res / self.targets.len() as f64).sqrt(),
            alpha,
            t,
        })
    }
}

/// The shape of the cognate of `h` whose crank turns with its crank (Roberts–Chebyshev), in
/// both assembly modes: it traces the same coupler curve, turned and scaled, at the same
/// crank angles (shifted by one constant), so the placement puts it on the same targets.
///
/// Why: with complex numbers, the crank a = A − O1, the rocker c = B − O3 and the coupler
/// point P = A + z(B − A), B − A = (O3 − O1) + c − a gives P = O_C + (1 − z)a + zc with the
/// third pivot O_C = O1 + z(O3 − O1). So the four-bar with the crank O_C C' = (1 − z)a, the
/// rocker O3 D = (z − 1)(B − A) and the coupler C'D = (z − 1)c carries P at
/// C' + zc = C' + z/(z − 1)·(D − C'): its links are |1 − z| times (a, c, b) on the frame
/// |1 − z|·|O3 − O1| — the same shape with coupler and rocker swapped — and its coupler point
/// is z/(z − 1). A cognate whose coupler point lies beyond the search's bounds, or in a
/// broad basin the search prefers, is turned into one (maybe within them) by this map.
fn cognate(h: &[f64]) -> Option<[[f64; SHAPE]; 2]> {
    let z = V::new(h[3], h[4]);
    let w = V::new(z.x - 1.0, z.y);
    let n = w.norm_squared();
    if n.is_nan() || n < 1e-12 {
        return None;
    }
    // z/w = z·conj(w)/|w|².
    let q = mul(z, V::new(w.x, -w.y)) / n;
    let mode = |s: f64| [h[0], h[2], h[1], q.x, q.y, s];
    Some([mode(1.0), mode(-1.0)])
}

/// Places the shape `h` and polishes it into a design (kept if `only_good` it meets the
/// tolerance); where the result is not yet a design that meets it, the same for its cognate
/// (the mode that fits better).
fn adopt_with_cognate(
    pb: &mut Problem,
    shapes: &mut Shapes,
    found: &mut super::Found,
    h: &[f64],
    iterations: usize,
    tolerance: f64,
    only_good: bool,
) -> crate::error::Result<()> {
    let before = found.good(tolerance);
    if let Some((g, phis)) = shapes.place(pb, h) {
        found.adopt(pb, &g, &phis, iterations, tolerance, only_good)?;
    }
    if found.good(tolerance) > before || !pb.budget.room(5) {
        return Ok(());
    }
    let Some(twins) = cognate(h) else {
        return Ok(());
    };
    pb.budget.add(2);
    let cost = twins.map(|t| shapes.cost(pb, &t));
    let t = &twins[usize::from(cost[1] < cost[0])];
    if cost[0].min(cost[1]) < INFEASIBLE
        && let Some((g, phis)) = shapes.place(pb, t)
    {
        found.adopt(pb, &g, &phis, iterations, tolerance, only_good)?;
    }
    Ok(())
}

/// The search over shapes: runs of differential evolution from fresh random populations,
/// each until it stagnates (its best improved by less than [`PROGRESS`] in
/// [`STAGNATION`](super::STAGNATION) generations), the best member polished every few
/// generations (kept when it meets the points to the tolerance) and the best few at the end
/// of each run, each with its cognate where it falls short; until `opts.designs` designs meet
/// the points or the budget is spent (the last run's polish has its reserved share).
pub(super) fn search(
    pb: &mut Problem,
    opts: &super::PathOptions,
    found: &mut super::Found,
    progress: &mut dyn FnMut(&super::Progress) -> bool,
) -> crate::error::Result<usize> {
    let mut shapes = Shapes::new(pb, opts.positions);
    let (whole_lo, whole_hi) = Shapes::bounds(pb.ratio);
    let np = opts.population;
    let want = opts.designs.max(1);
    let mut rng = super::Rng(opts.seed);
    let mut generations = 0usize;
    let start = found.start;
    let mut runs = 0usize;
    // The best over every run: a restart's fresh population starts worse, and the best
    // reported must never rise.
    let mut best_ever = f64::INFINITY;
    while pb.budget.room_search(2 * np) {
        let (mut lo, mut hi) = (whole_lo.clone(), whole_hi.clone());
        if runs % PIN_RUNS == 1 {
            for k in [3, 4] {
                lo[k] *= PIN_BOX;
                hi[k] *= PIN_BOX;
            }
        }
        runs += 1;
        let mut pop: Vec<Vec<f64>> = (0..np)
            .map(|m| {
                let mut h: Vec<f64> = (0..SHAPE)
                    .map(|k| lo[k] + (hi[k] - lo[k]) * rng.unit())
                    .collect();
                if m % NEAR_PIN == 0 {
                    h[3] *= PIN_BOX;
                    h[4] *= PIN_BOX;
                }
                h
            })
            .collect();
        let mut fit: Vec<f64> = pop.iter().map(|h| shapes.cost(pb, h)).collect();
        pb.budget.add(np);
        let mut stagnation = super::evolve::Stagnation::new(PROGRESS);
        while pb.budget.room_search(np) {
            generations += 1;
            super::evolve::generation(&mut pop, &mut fit, &lo, &hi, &[], &mut rng, &mut |h| {
                shapes.cost(pb, h)
            });
            pb.budget.add(np);
            let best_i = (0..np)
                .min_by(|&a, &b| fit[a].total_cmp(&fit[b]))
                .unwrap_or(0);
            let best = fit[best_i];
            if generations.is_multiple_of(super::MEMETIC)
                && best < INFEASIBLE
                && pb.budget.room_search(3)
            {
                let h = pop[best_i].clone();
                adopt_with_cognate(pb, &mut shapes, found, &h, 60, opts.tolerance, true)?;
                if found.good(opts.tolerance) >= want {
                    return Ok(pb.budget.used());
                }
            }
            best_ever = best_ever.min(best);
            let go_on = progress(&super::Progress {
                generation: generations,
                evaluations: pb.budget.used(),
                best: best_ever,
                elapsed: start.elapsed(),
            });
            if !go_on {
                return Ok(pb.budget.used());
            }
            if stagnation.after(best) {
                break;
            }
        }
        let mut order: Vec<usize> = (0..np).filter(|&i| fit[i] < INFEASIBLE).collect();
        order.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]));
        for &i in order.iter().take(super::POLISHED) {
            if !pb.budget.room(3) {
                break;
            }
            let h = pop[i].clone();
            adopt_with_cognate(pb, &mut shapes, found, &h, 200, opts.tolerance, false)?;
            if found.good(opts.tolerance) >= want {
                break;
            }
        }
        if found.good(opts.tolerance) >= want {
            break;
        }
    }
    Ok(pb.budget.used())
}
