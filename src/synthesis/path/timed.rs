//! The search over all the dimensions (with prescribed timing, and the slider-crank's for
//! every timing): differential evolution with a Lamarckian polish, each run's best polished.

use super::design::Found;
use super::evolve::{self, Rng};
use super::nelder_mead::nelder_mead;
use super::polish::pb_residuals;
use super::problem::Problem;
use super::requirement::PathOptions;
use super::results::Progress;
use super::{INFEASIBLE, MEMETIC, POLISHED};
use crate::error::Result;

/// The search with prescribed timing: differential evolution over the ten genes (the nine
/// dimensions, the mode, θ0) with a Lamarckian Levenberg–Marquardt step every few
/// generations; the best candidates of each run polished by Nelder–Mead and
/// Levenberg–Marquardt. Returns the evaluations spent.
pub(super) fn search_timed(
    pb: &mut Problem,
    opts: &PathOptions,
    found: &mut Found,
    progress: &mut dyn FnMut(&Progress) -> bool,
) -> Result<usize> {
    let (lo, hi) = pb.bounds();
    let np = opts.population;
    let mut rng = Rng(opts.seed);
    let start = found.start;
    let want = opts.designs.max(1);
    let mut generation = 0;
    let mut stopped = false;
    // The best over every run: a restart's fresh population starts worse, and the best
    // reported must never rise.
    let mut best_ever = f64::INFINITY;
    // Runs of differential evolution from fresh random populations, each until it stagnates,
    // its best candidates polished; until enough designs meet the points to `tolerance` or
    // the budget is spent.
    while !stopped && pb.budget.room_search(2 * np) {
        let mut pop = evolve::population(np, &lo, &hi, &mut rng);
        let mut fit: Vec<f64> = pop.iter().map(|g| pb.objective(g)).collect();
        pb.budget.add(np);
        let mut stagnation = evolve::Stagnation::new(1e-6);
        while pb.budget.room_search(np) {
            generation += 1;
            evolve::generation_below(
                &mut pop,
                &mut fit,
                &lo,
                &hi,
                &[2, 10],
                &mut rng,
                &mut |g, above| {
                    pb.budget.add(1);
                    pb.objective_below(g, above)
                },
            );
            if generation % MEMETIC == 0 {
                // Lamarckian local search: the best member and a random one, polished by
                // Levenberg–Marquardt, replace themselves where that is better.
                let best_i = (0..np)
                    .min_by(|&a, &b| fit[a].total_cmp(&fit[b]))
                    .unwrap_or(0);
                for i in [best_i, rng.below(np)] {
                    if fit[i] >= INFEASIBLE || !pb.budget.room(2) {
                        continue;
                    }
                    let (x, sigma) = pb.start_of(&pop[i]);
                    let x = pb.lm(x, sigma, 30);
                    let g = pb.genes_of(&x, sigma);
                    let f = pb.objective(&g);
                    pb.budget.add(1);
                    // Only within the search's box: a member the polish took outside
                    // `max_size` would lead the population out of it, where no design is
                    // kept (with `max_size` 0.01 no design was found at all).
                    if f < fit[i] && pb.within_size(&g) {
                        pop[i] = g;
                        fit[i] = f;
                    }
                }
            }
            let best = fit.iter().copied().fold(f64::INFINITY, f64::min);
            best_ever = best_ever.min(best);
            let go_on = progress(&Progress {
                generation,
                evaluations: pb.budget.used(),
                best: best_ever,
                elapsed: start.elapsed(),
            });
            if !go_on {
                stopped = true;
                break;
            }
            if stagnation.after(best) {
                break;
            }
        }
        // Polish the best candidates, best first, until enough distinct designs are found.
        let mut order: Vec<usize> = (0..np).filter(|&i| fit[i] < INFEASIBLE).collect();
        order.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]));
        for (rank, &i) in order.iter().enumerate() {
            if rank >= POLISHED {
                break;
            }
            if !pb.budget.room(2) {
                break;
            }
            let (x, sigma) = pb.start_of(&pop[i]);
            let step: Vec<f64> = x.iter().map(|v| 0.02 * v.abs().max(0.5)).collect();
            let xn = {
                let (kind, targets, timing, budget) =
                    (pb.kind, &pb.targets, &pb.timing, &pb.budget);
                let mut f = |x: &[f64]| {
                    if !budget.take_polish() {
                        return None;
                    }
                    Some(
                        pb_residuals(kind, targets, timing, x, sigma)
                            .map_or(f64::INFINITY, |r| r.iter().map(|v| v * v).sum()),
                    )
                };
                nelder_mead(&mut f, &x, &step, 200 * x.len())
            };
            let x0 = x.clone();
            let x = if pb.feasible(&xn, sigma) { xn } else { x };
            let x = pb.polish_free(x, sigma, 200);
            // Where the free polish ends outside the constraints (in a box too small to
            // reach the points it grows the links past `max_size`) and no design is found
            // yet, the polish again from the member, every step kept within the box; and the
            // member itself (feasible in the search) when that is refused too: a search that
            // found a feasible candidate leaves a design (with `max_size` 0.01 the
            // slider-crank's left none).
            let x = if pb.feasible(&x, sigma) {
                x
            } else if !found.designs.is_empty() {
                continue;
            } else {
                let y = pb.lm_within(x0.clone(), sigma, 200);
                if pb.feasible(&y, sigma) {
                    y
                } else if pb.feasible(&x0, sigma) {
                    x0
                } else {
                    continue;
                }
            };
            let mut g = x[..9].to_vec();
            g.push(sigma);
            found.adopt(pb, &g, &x[9..], 0, opts.tolerance, false)?;
        }
        if found.good(opts.tolerance) >= want {
            break;
        }
    }

    Ok(pb.budget.used())
}
