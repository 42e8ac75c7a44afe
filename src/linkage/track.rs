//! Branch tracking through dead centres: the assembly modes a mechanism keeps as its input
//! runs on through a position where one of its dyads is at a dead centre.
//!
//! A plan keeps each dyad's assembly mode (the side σ of its inner joint) fixed. At a dead
//! centre a dyad's two modes meet, and where the input runs on through it (a Grashof
//! change point: a parallelogram four-bar at 0 and 180°), the motion that continues smoothly
//! is the one whose velocities carry on: along it the dyad's determinant σ·h crosses zero and
//! changes sign, so it lies on the *other* mode past the dead centre. On the plan's own mode
//! the motion folds onto a different branch (the parallelogram turns antiparallelogram, its
//! rocker's ω jumping from +1 to −0.5). [`Plan::track`] walks the inputs in steps of at most
//! 0.5°, finds where a dyad's |determinant| has a minimum that is a dead centre, and keeps the
//! mode whose velocity analogues (ω per unit input rate) continue across it.

use super::plan::{GroupKind, Plan};
use crate::error::{Error, Result};
use crate::kinematics::Motion;

/// The largest step of the walk, rad: 0.5°, fine enough to see each dead centre as a
/// minimum of its dyad's |determinant| between neighbouring steps.
const STEP: f64 = std::f64::consts::TAU / 720.0;

/// The most positions a walk solves besides the inputs (about 0.1 s of kinematics): a run
/// whose inputs turn the crank through more than this many steps walks in longer ones.
const MAX_SAMPLES: usize = 200_000;

/// Below this |determinant| a minimum is a dead centre. At a change point the determinant
/// falls linearly to zero and the refinement gets it to about 10⁻¹²; a crank-rocker's
/// smallest transmission angle (a minimum that is no dead centre) is degrees, not 10⁻⁶ rad.
const DEAD: f64 = 1e-6;

/// The distance from a dead centre at which the velocities on its two sides are compared,
/// rad: far enough that the analogues (∝ 1/determinant near a fold) are well conditioned,
/// near enough that they have not changed by more than 10⁻⁴ of themselves.
const SIDE: f64 = 1e-4;

/// One dead centre a tracked run crosses.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// The input coordinate of the dead centre.
    pub at: f64,
    /// The index of the dyad (in [`Plan::groups`]).
    pub group: usize,
    /// The dyad's name.
    pub name: String,
    /// Whether the dyad changed its assembly mode there (the continuing motion is on the
    /// other mode), or kept it (it continues on its own).
    pub flipped: bool,
    /// The first of the inputs that lies past it.
    pub from_position: usize,
}

/// The plans a run of inputs is solved on when it tracks its branch through dead centres
/// ([`Plan::track`]).
#[derive(Debug, Clone)]
pub struct Track {
    /// The plans, the first the one tracked from; each following one has the modes past
    /// one more dead centre.
    pub plans: Vec<Plan>,
    /// Per input, the index of its plan in `plans`.
    pub which: Vec<usize>,
    /// The dead centres crossed, in the order the inputs reach them.
    pub crossings: Vec<Crossing>,
}

impl Track {
    /// The plan input `k` is solved on.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for `k` beyond the inputs.
    pub fn plan(&self, k: usize) -> Result<&Plan> {
        crate::linkage::handle::index_in("position index", "positions", k, self.which.len())?;
        Ok(&self.plans[self.which[k]])
    }

    /// What `f` takes of each input's analysis, each on its tracked plan (as
    /// [`Plan::cycle`]); a failed position's `Err` in its place.
    pub fn cycle<T, F>(&self, inputs: &[Motion], mut f: F) -> Vec<Result<T>>
    where
        F: FnMut(&super::Analysis<'_>) -> Result<T>,
    {
        let mut solvers: Vec<_> = self.plans.iter().map(Plan::solver).collect();
        inputs
            .iter()
            .zip(&self.which)
            .map(|(&m, &p)| solvers[p].analyse(m).and_then(&mut f))
            .collect()
    }

    /// Each input's analysis on its tracked plan, calling `progress` with each input's index
    /// first (as [`Plan::analyse_each`]).
    pub fn analyse_each(
        &self,
        inputs: &[Motion],
        progress: &mut dyn FnMut(usize),
    ) -> Vec<Result<super::Analysis<'_>>> {
        inputs
            .iter()
            .zip(&self.which)
            .enumerate()
            .map(|(k, (&m, &p))| {
                progress(k);
                self.plans[p].analyse(m)
            })
            .collect()
    }

    /// A note for tables: where the run crossed a dead centre and what it did there.
    #[must_use]
    pub fn notes(&self) -> Vec<String> {
        self.crossings
            .iter()
            .map(|c| {
                format!(
                    "{} at its dead centre at input {:.6}: {} (the motion continuing smoothly)",
                    c.name,
                    c.at,
                    if c.flipped {
                        "runs on in its other assembly mode"
                    } else {
                        "keeps its assembly mode"
                    }
                )
            })
            .collect()
    }
}

/// |determinant| of every dyad of `plan` at `q` and the velocity analogues of every link
/// (ω at unit input rate), or `None` where the position cannot be solved with its rates (a
/// dead centre hit exactly, or closure failing by rounding).
fn sample(plan: &Plan, q: f64) -> Option<(Vec<f64>, Vec<f64>)> {
    // Unchecked: the walk reads the analogues up to the dead centre itself, where a user's
    // `Plan::kinematics` with a rate refuses them; it compares their signs and sizes only.
    let mut k = super::solve::Kinematics::new(plan);
    k.solve(&[Motion::new(q, 1.0, 0.0)]).ok()?;
    let dets = k.group_determinants().iter().map(|d| d.abs()).collect();
    let omegas = k.link_motions().iter().map(|m| m.omega).collect();
    Some((dets, omegas))
}

/// |determinant| of dyad `g` at `q` (0 where the position fails: at the dead centre itself).
fn det_at(plan: &Plan, g: usize, q: f64) -> f64 {
    plan.kinematics(Motion::fixed(q))
        .ok()
        .map_or(0.0, |k| k.group_determinants()[g].abs())
}

/// How far the crank turns from `m0` to `m1`: their angles' difference taken modulo a turn
/// (inputs over a turn are brought into [0, 2π)), in the sense of the rate where one is given
/// (a clockwise crank's angles fall), else the shorter way.
fn advance(m0: Motion, m1: Motion) -> f64 {
    use std::f64::consts::{PI, TAU};
    let d = m1.value - m0.value;
    let rate = if m0.rate == 0.0 { m1.rate } else { m0.rate };
    if rate > 0.0 {
        d.rem_euclid(TAU)
    } else if rate < 0.0 {
        -(-d).rem_euclid(TAU)
    } else {
        (d + PI).rem_euclid(TAU) - PI
    }
}

/// The dyads whose mode could change at a dead centre: RRR and RRP dyads.
fn is_dyad(plan: &Plan, g: usize) -> bool {
    let group = &plan.groups()[g];
    matches!(group.kind, GroupKind::Rrr | GroupKind::Rrp)
}

impl Plan {
    /// The plans `inputs` (a crank's, in the order the input reaches them) are solved on
    /// when the mechanism tracks its branch through dead centres, as one carried on by its
    /// inertia does: the inputs are walked in steps of at most 0.5° (longer where they turn
    /// the crank through more than 2·10⁵ such steps in all), each dyad's
    /// |determinant| watched; at a minimum that reaches zero (below 10⁻⁶ once refined: a
    /// dead centre the input runs through), the mode whose velocity analogues 10⁻⁴ rad past it
    /// continue those 10⁻⁴ rad before it is kept, the plan's or the other one. A run with no
    /// dead centre has one plan, this one, so its results are this plan's, bit for bit.
    ///
    /// # Errors
    /// [`Error::Description`] for a slider input; the kinematics' error at the first input.
    ///
    /// # Examples
    /// A parallelogram four-bar (crank 0.1, coupler 0.3, rocker 0.1, frame 0.3) stays a
    /// parallelogram through its dead centres at 0 and 180°:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{uniform_inputs, Joint, Link, Linkage, Plan};
    /// let (s, c) = 1.0f64.sin_cos();
    /// let l = Linkage {
    ///     name: "parallelogram".into(),
    ///     joints: vec![
    ///         Joint::revolute("O1", [0.0, 0.0]),
    ///         Joint::revolute("A", [0.1 * c, 0.1 * s]),
    ///         Joint::revolute("B", [0.3 + 0.1 * c, 0.1 * s]),
    ///         Joint::revolute("O3", [0.3, 0.0]),
    ///     ],
    ///     links: vec![
    ///         Link::new("frame", &["O1", "O3"]),
    ///         Link::new("crank", &["O1", "A"]),
    ///         Link::new("coupler", &["A", "B"]),
    ///         Link::new("rocker", &["O3", "B"]),
    ///     ],
    ///     ..Linkage::default()
    /// };
    /// let plan = Plan::new(&l)?;
    /// let inputs = uniform_inputs(36, 1.0, 1.0, 0.0);
    /// let track = plan.track(&inputs)?;
    /// assert_eq!(track.crossings.len(), 2);
    /// let w = track.cycle(&inputs, |a| Ok(a.link_motion("rocker")?.omega));
    /// assert!(w.iter().all(|w| (w.as_ref().unwrap() - 1.0).abs() < 1e-9));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn track(&self, inputs: &[Motion]) -> Result<Track> {
        if !self.input_is_crank() {
            return Err(Error::Description {
                item: "field input".to_owned(),
                problem: "branch tracking walks a crank's angle; a slider input has none"
                    .to_owned(),
            });
        }
        let mut track = Track {
            plans: vec![self.clone()],
            which: Vec::with_capacity(inputs.len()),
            crossings: Vec::new(),
        };
        let Some(first) = inputs.first() else {
            return Ok(track);
        };
        self.kinematics(Motion::fixed(first.value))?;
        // The walk's budget: its step widens past 0.5° where the inputs turn the crank
        // through more than MAX_SAMPLES half-degrees in all (inputs far apart, given by hand).
        let total: f64 = inputs.windows(2).map(|p| advance(p[0], p[1]).abs()).sum();
        #[allow(clippy::cast_precision_loss)]
        let step = STEP.max(total / MAX_SAMPLES as f64);
        // The last two samples' |determinants| (per group) on the current plan.
        let mut prev: Option<(f64, Vec<f64>)> = None;
        let mut before: Option<(f64, Vec<f64>)> = None;
        track.which.push(0);
        for (k, pair) in inputs.windows(2).enumerate() {
            let (q0, q1) = (pair[0].value, pair[0].value + advance(pair[0], pair[1]));
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let steps = ((q1 - q0).abs() / step).ceil().clamp(1.0, 1e6) as usize;
            // The first sample of a pair is the last of the one before.
            for j in usize::from(k > 0)..=steps {
                #[allow(clippy::cast_precision_loss)]
                let q = q0 + (q1 - q0) * j as f64 / steps as f64;
                let cur = track.plans.len() - 1;
                let dets = sample(&track.plans[cur], q)
                    .map_or_else(|| vec![0.0; self.groups().len()], |s| s.0);
                if let (Some((qa, da)), Some((_, db))) = (&before, &prev) {
                    for g in (0..dets.len()).filter(|&g| is_dyad(self, g)) {
                        // A minimum of |det| at the middle sample qb, between qa and q.
                        if db[g] <= da[g] && db[g] <= dets[g] && db[g] < 0.1 {
                            self.cross(&mut track, g, *qa, q, k + 1);
                        }
                    }
                }
                if track.plans.len() - 1 != cur {
                    // An input already given its plan that lies past the dead centre (the
                    // minimum is seen one sample late) takes the new one.
                    let last = track.which.len() - 1;
                    if let Some(c) = track.crossings.last_mut()
                        && last == k
                        && (q0 - c.at) * (q1 - q0).signum() > 0.0
                    {
                        track.which[last] = track.plans.len() - 1;
                        c.from_position = last;
                    }
                    // A new plan: the watch starts again on its modes.
                    before = None;
                    prev = sample(track.plans.last().unwrap_or(self), q).map(|s| (q, s.0));
                    continue;
                }
                before = prev.take();
                prev = Some((q, dets));
            }
            track.which.push(track.plans.len() - 1);
        }
        Ok(track)
    }

    /// Dyad `g`'s |determinant| has a minimum between `qa` and `qb` on the track's last
    /// plan: refined (ternary search, a failed position counting as 0), and where it is a
    /// dead centre, the continuing mode chosen by the velocity analogues on both sides and a
    /// plan with it pushed when it is the other one.
    fn cross(&self, track: &mut Track, g: usize, qa: f64, qb: f64, from_position: usize) {
        let plan = track.plans.last().unwrap_or(self);
        let (mut lo, mut hi) = (qa.min(qb), qa.max(qb));
        for _ in 0..200 {
            if hi - lo <= 1e-13 * (1.0 + lo.abs()) {
                break;
            }
            let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if det_at(plan, g, m1) <= det_at(plan, g, m2) {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        let qc = 0.5 * (lo + hi);
        if det_at(plan, g, qc) > DEAD {
            return;
        }
        // Only a dead centre inside (qa, qb] belongs to this step: one at qa was crossed
        // before.
        let s = (qb - qa).signum();
        let omega = |p: &Plan, q: f64| sample(p, q).map(|x| x.1);
        let mut other = plan.clone();
        other.chain.groups[g].branch = other.chain.groups[g].branch.flipped();
        let (Some(w0), Some(keep), Some(flip)) = (
            omega(plan, qc - s * SIDE),
            omega(plan, qc + s * SIDE),
            omega(&other, qc + s * SIDE),
        ) else {
            return;
        };
        let gap = |w: &[f64]| {
            w.iter()
                .zip(&w0)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f64, f64::max)
        };
        let flipped = gap(&flip) < gap(&keep);
        track.crossings.push(Crossing {
            at: qc,
            group: g,
            name: self.groups()[g].name.clone(),
            flipped,
            from_position,
        });
        if flipped {
            track.plans.push(other);
        }
    }
}
