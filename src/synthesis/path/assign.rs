//! Free timing's assignment: which sampled crank position of a turn meets each target, the
//! targets met in their order.
//!
//! Without prescribed timing the crank angle at each target is an unknown, but the targets
//! are still met in the order given: the crank turns one way, by less than a turn, from the
//! first to the last, over positions that all assemble with γ ≥ \[γ\]. Matching each target
//! to its nearest sampled position ignores that, and on a curve that passes near a target
//! twice (a crossing, or two close branches) it scores a candidate the order-checked polish
//! and the final check then refuse: the search's best candidates may all be refused and no
//! design returned (slider-crank free timing, seeded case 95, before session 10).
//!
//! The assignment here minimises the sum of the distances subject to the order, by dynamic
//! programming over the samples: with the samples unrolled from a cut c in the crank's
//! sense s (position j is sample c + s·j mod m), the targets' positions must not decrease
//! and no unusable sample may lie between two of them. Let D_k(j) be the least sum of
//! targets 0..=k with target k at position j; then
//! D_k(j) = d(k, j) + min { D_{k−1}(j′) : j′ ≤ j, every sample of j′..=j usable },
//! a running minimum that restarts after each unusable sample: O(n·m) per cut. Where the
//! nearest positions are already in order they are the answer (the unconstrained minimum
//! meets the constraint), so the common case costs the nearest search only.

use super::V;

/// Scratch space of [`Scratch::ordered`], reused between candidates; `idx` holds the last
/// assignment.
#[derive(Debug, Default)]
pub(super) struct Scratch {
    /// dist[k·m + i]: the distance of target k from sample i (its square until the
    /// programme needs the distances).
    dist: Vec<f64>,
    layer: Vec<f64>,
    next: Vec<f64>,
    /// from[k·m + j]: the position of target k − 1 under target k at position j.
    from: Vec<u32>,
    trial: Vec<usize>,
    /// The sample (index into the turn) of each target.
    pub(super) idx: Vec<usize>,
}

/// How many cuts the dynamic programme tries per sense on a turn whose every sample is
/// usable: at the two nearest local minima of the first target's distance (one sample
/// before) and at the nearest of the last target's (one sample after).
const FIRST_CUTS: usize = 2;

impl Scratch {
    /// Assigns each of `targets` a sample of the turn whose coupler points are (`px`, `py`)
    /// (m samples evenly round a turn, in increasing crank angle; `ok` the usable ones), in
    /// the targets' order as above; returns the least sum of distances, the samples in
    /// `self.idx`. `None` where no sample is usable.
    ///
    /// `above` is a mean distance beyond which the caller has no use for the answer (the
    /// evolution's trial worse than its member): as soon as the nearest distances of the
    /// first targets sum to more than `above` per target, that partial sum is returned (its
    /// mean above `above`, `self.idx` incomplete). It is a lower bound of the answer: every
    /// ordered assignment's distances are at least the nearest ones, and a sum of
    /// non-negative terms in floating point never falls as a term is added or grows, so the
    /// caller's comparison with `above` decides as it would on the whole answer.
    pub(super) fn ordered(
        &mut self,
        px: &[f64],
        py: &[f64],
        ok: &[bool],
        targets: &[V],
        above: f64,
    ) -> Option<f64> {
        let (n, m) = (targets.len(), ok.len());
        if n == 0 || m == 0 || !ok.iter().any(|&b| b) {
            return None;
        }
        self.dist.clear();
        self.idx.clear();
        let mut sum = 0.0;
        // The nearest by the squared distance (no square root or hypot per sample: the
        // assignment was half the search's time with them); a square that overflows (a
        // sample beyond 1e154 path sizes) counts as unusable for that target.
        for (k, t) in targets.iter().enumerate() {
            self.dist.extend((0..m).map(|i| {
                let (dx, dy) = (px[i] - t.x, py[i] - t.y);
                let d2 = dx * dx + dy * dy;
                if ok[i] && d2.is_finite() {
                    d2
                } else {
                    f64::INFINITY
                }
            }));
            let row = &self.dist[k * m..];
            let (mut best, mut at) = (f64::INFINITY, 0);
            for (i, &d2) in row.iter().enumerate() {
                if d2 < best {
                    (best, at) = (d2, i);
                }
            }
            sum += best.sqrt();
            self.idx.push(at);
            if sum / n as f64 > above {
                return Some(sum);
            }
        }
        if [1, -1].into_iter().any(|s| in_order(&self.idx, ok, s)) {
            return Some(sum);
        }
        // The programme sums distances.
        for d in &mut self.dist {
            *d = d.sqrt();
        }
        // The cuts: with an unusable sample, at it (no assignment crosses it, so the one cut
        // is exact in each sense); on a wholly usable turn, about the nearest local minima
        // of the first and the last target's distance.
        let mut best = f64::INFINITY;
        let mut best_idx = std::mem::take(&mut self.trial);
        for s in [1isize, -1] {
            let mut cuts = Vec::with_capacity(FIRST_CUTS + 1);
            if let Some(bad) = ok.iter().position(|&b| !b) {
                cuts.push(bad);
            } else {
                let minima = |k: usize, count: usize| -> Vec<usize> {
                    let d = &self.dist[k * m..(k + 1) * m];
                    let mut v: Vec<usize> = (0..m)
                        .filter(|&i| d[i] <= d[(i + 1) % m] && d[i] <= d[(i + m - 1) % m])
                        .collect();
                    v.sort_by(|&a, &b| d[a].total_cmp(&d[b]));
                    v.truncate(count);
                    v
                };
                let step = |i: usize, by: isize| (i as isize + by).rem_euclid(m as isize) as usize;
                cuts.extend(minima(0, FIRST_CUTS).into_iter().map(|i| step(i, -s)));
                cuts.extend(minima(n - 1, 1).into_iter().map(|i| step(i, s)));
            }
            for c in cuts {
                if let Some(v) = self.programme(ok, n, c, s)
                    && v < best
                {
                    best = v;
                    best_idx.clone_from(&self.idx);
                }
            }
        }
        self.trial = std::mem::take(&mut self.idx);
        self.idx = best_idx;
        best.is_finite().then_some(best)
    }

    /// The dynamic programme from the cut `c` in the sense `s`: the least sum, the samples
    /// in `self.idx`.
    fn programme(&mut self, ok: &[bool], n: usize, c: usize, s: isize) -> Option<f64> {
        let m = ok.len();
        let sample = |j: usize| (c as isize + s * j as isize).rem_euclid(m as isize) as usize;
        self.layer.clear();
        self.layer.extend((0..m).map(|j| self.dist[sample(j)]));
        self.from.clear();
        self.from.resize(n * m, 0);
        for k in 1..n {
            self.next.clear();
            let (mut run, mut at) = (f64::INFINITY, 0u32);
            for j in 0..m {
                let i = sample(j);
                if !ok[i] {
                    run = f64::INFINITY;
                    self.next.push(f64::INFINITY);
                    continue;
                }
                if self.layer[j] < run {
                    (run, at) = (self.layer[j], j as u32);
                }
                self.from[k * m + j] = at;
                self.next.push(run + self.dist[k * m + i]);
            }
            std::mem::swap(&mut self.layer, &mut self.next);
        }
        let (mut j, mut v) = (0usize, f64::INFINITY);
        for (jj, &x) in self.layer.iter().enumerate() {
            if x < v {
                (j, v) = (jj, x);
            }
        }
        if !v.is_finite() {
            return None;
        }
        self.idx.clear();
        self.idx.resize(n, 0);
        for k in (0..n).rev() {
            self.idx[k] = sample(j);
            if k > 0 {
                j = self.from[k * m + j] as usize;
            }
        }
        Some(v)
    }
}

/// Whether the samples `idx` (of a turn of `ok.len()`) are met in order turning in the
/// sense `s`, by less than a turn, over usable samples only.
fn in_order(idx: &[usize], ok: &[bool], s: isize) -> bool {
    let m = ok.len() as isize;
    let mut total = 0;
    for w in idx.windows(2) {
        total += (s * (w[1] as isize - w[0] as isize)).rem_euclid(m);
    }
    total < m && (0..=total).all(|j| ok[(idx[0] as isize + s * j).rem_euclid(m) as usize])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force over every assignment of 3 targets to 12 samples: the programme's sum is
    /// the least among the ordered ones, on turns with and without unusable samples.
    #[test]
    fn the_programme_is_the_least_ordered_sum() {
        let m = 12;
        let mut seed = 7u64;
        let mut unit = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..200 {
            // A figure-eight-like curve, so that the nearest are often out of order.
            let px: Vec<f64> = (0..m)
                .map(|i| (i as f64 * 0.52).sin() + 0.3 * unit())
                .collect();
            let py: Vec<f64> = (0..m)
                .map(|i| (i as f64 * 1.05).sin() + 0.3 * unit())
                .collect();
            let ok: Vec<bool> = (0..m).map(|i| case % 3 != 0 || i % 5 != 2).collect();
            let targets: Vec<V> = (0..3)
                .map(|_| V::new(2.0 * unit() - 1.0, 2.0 * unit() - 1.0))
                .collect();
            let mut s = Scratch::default();
            let got = s.ordered(&px, &py, &ok, &targets, f64::INFINITY).unwrap();
            let d = |k: usize, i: usize| (px[i] - targets[k].x).hypot(py[i] - targets[k].y);
            let mut best = f64::INFINITY;
            for a in 0..m {
                for b in 0..m {
                    for c in 0..m {
                        let idx = [a, b, c];
                        if [1, -1].into_iter().any(|sg| in_order(&idx, &ok, sg)) {
                            best = best.min(d(0, a) + d(1, b) + d(2, c));
                        }
                    }
                }
            }
            // The cuts are exact with an unusable sample; on a whole turn a heuristic that
            // may miss the least by a little, never go below it.
            assert!(got >= best - 1e-12, "case {case}: {got} below {best}");
            if case % 3 == 0 {
                assert!((got - best).abs() <= 1e-12, "case {case}: {got} vs {best}");
            }
            let sum: f64 = s.idx.iter().enumerate().map(|(k, &i)| d(k, i)).sum();
            assert!((sum - got).abs() <= 1e-12);
            assert!([1, -1].into_iter().any(|sg| in_order(&s.idx, &ok, sg)));
            // Stopped early above a mean: the same answer where it is not above it, a
            // lower bound above it where it is (the caller decides the same either way).
            let above = got / 3.0 * (0.5 + unit());
            let part = s.ordered(&px, &py, &ok, &targets, above).unwrap();
            if got / 3.0 > above {
                assert!(
                    part / 3.0 > above && part <= got,
                    "case {case}: {part} vs {got}"
                );
            } else {
                assert_eq!(part, got, "case {case}");
            }
        }
    }
}
