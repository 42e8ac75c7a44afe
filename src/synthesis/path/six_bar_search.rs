//! The six-bar's global search: runs of differential evolution from fresh populations with
//! Lamarckian polishes, each run's distinct best members polished and followed to the
//! points, the distinct designs kept.

use super::six_bar_problem::{genes_of, split, Problem, GENES};
use super::{evolve, PathOptions, Progress, Rng, INFEASIBLE, POLISHED};
use std::f64::consts::TAU;

/// The genes that are angles: the frame's, θ0.
const WRAP: [usize; 2] = [2, GENES - 1];
/// Random members polished (Lamarckian) every generation, besides the best: a polish at the
/// n points costs n/`positions` of an evaluation a residual, so that where the search alone
/// stalls in sixteen dimensions, many short polishes are cheap.
const LUCKY: usize = 5;
/// The mean miss (path sizes) below which the run's best member is a near miss, followed
/// to the points by continuation within the run.
const NEAR: f64 = 1e-3;

/// Keeps the polished `x` among the distinct designs `found` (same six lengths to 1e-4: the
/// better of the two).
fn keep(found: &mut Vec<(Vec<f64>, [f64; 2], f64)>, x: Vec<f64>, s: [f64; 2], miss: f64) {
    let key = |x: &[f64]| {
        let mut l = [x[3], x[4], x[5], x[6], x[11], x[12]];
        l.sort_by(f64::total_cmp);
        l
    };
    let k = key(&x);
    let same = found.iter().position(|(y, _, _)| {
        key(y)
            .iter()
            .zip(&k)
            .all(|(a, b)| (a - b).abs() <= 1e-4 * b.abs())
    });
    match same {
        Some(i) if found[i].2 <= miss => {}
        Some(i) => found[i] = (x, s, miss),
        None => found.push((x, s, miss)),
    }
}

/// Runs of differential evolution from fresh populations, each until it stagnates, its best
/// candidates polished; until enough designs meet the points to the tolerance or the budget
/// is spent.
pub(super) fn search(
    pb: &Problem,
    opts: &PathOptions,
    found: &mut Vec<(Vec<f64>, [f64; 2], f64)>,
    progress: &mut dyn FnMut(&Progress) -> bool,
) {
    let s = pb.size;
    let l = super::shortest_link(s);
    let mut lo = vec![-s, -s, 0.0, l, l, l, l, -s, -s, -s, -s, l, l, -s, -s];
    let mut hi = vec![s, s, TAU, s, s, s, s, s, s, s, s, s, s, s, s];
    lo.extend([-1.0, -1.0, 0.0]);
    hi.extend([1.0, 1.0, TAU]);
    let np = opts.population;
    let mut rng = Rng(opts.seed);
    let want = opts.designs.max(1);
    let good = |found: &[(Vec<f64>, [f64; 2], f64)]| {
        found.iter().filter(|d| d.2 <= opts.tolerance).count()
    };
    let mut generation = 0;
    let mut stopped = false;
    // The best over every run: a restart's fresh population starts worse, and the best
    // reported must never rise.
    let mut best_ever = f64::INFINITY;
    while !stopped && pb.budget.room(2 * np) {
        let mut pop = evolve::population(np, &lo, &hi, &mut rng);
        let mut fit: Vec<f64> = pop.iter().map(|g| pb.objective(g)).collect();
        let mut stagnation = evolve::Stagnation::new(1e-6);
        let mut followed = f64::INFINITY;
        while pb.budget.room(np) {
            generation += 1;
            evolve::generation(&mut pop, &mut fit, &lo, &hi, &WRAP, &mut rng, &mut |g| {
                pb.objective(g)
            });
            {
                // Lamarckian: the best member and a random one polished, where that is better.
                let best_i = (0..np)
                    .min_by(|&a, &b| fit[a].total_cmp(&fit[b]))
                    .unwrap_or(0);
                let lucky: Vec<usize> = (0..LUCKY).map(|_| rng.below(np)).collect();
                for (k, i) in std::iter::once(best_i).chain(lucky).enumerate() {
                    if fit[i] >= INFEASIBLE || !pb.budget.room(2) {
                        continue;
                    }
                    let (x, sg) = split(&pop[i]);
                    // In the budget's second half (the end-of-run continuation alone has
                    // not closed a near miss): the best member, a near miss half the last
                    // one followed, followed to the points before its polish.
                    let follow = k == 0
                        && pb.budget.used.get() > 0.5 * pb.budget.max as f64
                        && fit[i] < NEAR
                        && fit[i] < 0.5 * followed;
                    // Free to leave the box on its way (held inside, it stalls at the box's
                    // walls); a member polished out of the box is refused by the objective.
                    let x = if follow {
                        followed = fit[i];
                        pb.follow(x, sg)
                    } else {
                        x
                    };
                    let g = genes_of(&pb.lm(x, sg, 30, false), sg);
                    let f = pb.objective(&g);
                    if f < fit[i] {
                        pop[i] = g;
                        fit[i] = f;
                    }
                }
            }
            let best = fit.iter().copied().fold(f64::INFINITY, f64::min);
            best_ever = best_ever.min(best);
            if !progress(&Progress {
                generation,
                evaluations: pb.budget.used(),
                best: best_ever,
                elapsed: pb.budget.start.elapsed(),
            }) {
                stopped = true;
                break;
            }
            if stagnation.after(best) {
                break;
            }
        }
        let mut order: Vec<usize> = (0..np).filter(|&i| fit[i] < INFEASIBLE).collect();
        order.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]));
        for &i in order.iter().take(POLISHED) {
            if !pb.budget.room(2) {
                break;
            }
            let (x0, sg) = split(&pop[i]);
            let x = pb.lm(x0.clone(), sg, 200, false);
            let (mut x, mut miss) = if let Some(m) = pb.check(&x, sg) {
                (x, m)
            } else if let Some(m0) = pb.check(&x0, sg) {
                // The free polish ended outside the box or past a dead point: done again
                // within them (the range sampled as the search does). The whole check may
                // still refuse it, and the start (in the box) is the design then.
                let y = pb.lm(x0.clone(), sg, 200, true);
                match pb.check(&y, sg) {
                    Some(m) => (y, m),
                    None => (x0, m0),
                }
            } else {
                continue;
            };
            if miss > opts.tolerance {
                // A near miss where Levenberg–Marquardt stalled in a curved valley of the
                // ill-conditioned misses: followed down to the points by continuation.
                // Where it ends outside the box, the check refuses it.
                let y = pb.lm(pb.follow(x.clone(), sg), sg, 200, false);
                if let Some(m) = pb.check(&y, sg)
                    && m < miss
                {
                    (x, miss) = (y, m);
                }
            }
            keep(found, x, sg, miss);
        }
        if good(found) >= want {
            break;
        }
    }
}
