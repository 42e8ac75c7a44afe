//! One generation of differential evolution, the step every search of path generation
//! takes (the four-bar's with prescribed timing, the shapes', the six-bar's).

use std::f64::consts::TAU;

/// One generation of DE/current-to-pbest/1/bin with the scale factor F dithered in
/// [0.5, 1) (crossover 0.9): each member's trial moves towards one of the best tenth, plus a
/// random difference; a gene beyond its bounds is put back between the member's value and
/// the bound; the genes `wrap` are angles, taken modulo a turn instead. A trial that is no
/// worse by `f` replaces its member.
pub(super) fn generation(
    pop: &mut [Vec<f64>],
    fit: &mut [f64],
    lo: &[f64],
    hi: &[f64],
    wrap: &[usize],
    rng: &mut Rng,
    f: &mut dyn FnMut(&[f64]) -> f64,
) {
    generation_below(pop, fit, lo, hi, wrap, rng, &mut |x, _| f(x));
}

/// [`generation`] whose objective `f(trial, above)` is told its member's value `above`: a
/// trial is kept only at or below it, so `f` may stop as soon as it knows the trial's value
/// lies above and return any value above (the same generation, less work).
pub(super) fn generation_below(
    pop: &mut [Vec<f64>],
    fit: &mut [f64],
    lo: &[f64],
    hi: &[f64],
    wrap: &[usize],
    rng: &mut Rng,
    f: &mut dyn FnMut(&[f64], f64) -> f64,
) {
    let np = pop.len();
    let dim = lo.len();
    let f_scale = 0.5 + 0.5 * rng.unit();
    let mut ranked: Vec<usize> = (0..np).collect();
    ranked.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]));
    let top = (np / 10).max(2);
    for i in 0..np {
        let p = ranked[rng.below(top)];
        let (mut b, mut c) = (i, i);
        while b == i {
            b = rng.below(np);
        }
        while c == i || c == b {
            c = rng.below(np);
        }
        let jr = rng.below(dim);
        let trial: Vec<f64> = (0..dim)
            .map(|k| {
                let x = pop[i][k];
                if k != jr && rng.unit() >= 0.9 {
                    return x;
                }
                let v = x + f_scale * (pop[p][k] - x) + f_scale * (pop[b][k] - pop[c][k]);
                if wrap.contains(&k) {
                    v.rem_euclid(TAU)
                } else if v < lo[k] {
                    lo[k] + (x - lo[k]) * rng.unit()
                } else if v > hi[k] {
                    hi[k] - (hi[k] - x) * rng.unit()
                } else {
                    v
                }
            })
            .collect();
        let ft = f(&trial, fit[i]);
        if ft <= fit[i] {
            pop[i] = trial;
            fit[i] = ft;
        }
    }
}

/// Whether a run of the evolution still makes progress: its best must improve by the
/// relative share `share` within [`STAGNATION`](super::STAGNATION) generations.
pub(super) struct Stagnation {
    share: f64,
    last: f64,
    since: usize,
}

impl Stagnation {
    pub(super) fn new(share: f64) -> Self {
        Self {
            share,
            last: f64::INFINITY,
            since: 0,
        }
    }

    /// Takes the generation's best; `true` when the run has stagnated.
    pub(super) fn after(&mut self, best: f64) -> bool {
        if best < self.last * (1.0 - self.share) {
            (self.last, self.since) = (best, 0);
        } else {
            self.since += 1;
        }
        self.since >= super::STAGNATION
    }
}

/// `np` members drawn uniformly within the bounds.
pub(super) fn population(np: usize, lo: &[f64], hi: &[f64], rng: &mut Rng) -> Vec<Vec<f64>> {
    (0..np)
        .map(|_| {
            lo.iter()
                .zip(hi)
                .map(|(l, h)| l + (h - l) * rng.unit())
                .collect()
        })
        .collect()
}

/// splitmix64.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    pub(super) fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(super) fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}
