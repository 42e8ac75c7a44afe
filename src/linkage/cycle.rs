//! A planned linkage over its cycle: outputs, extreme positions and strokes, the inputs of a
//! course project's plans, lock positions, and runs over many positions.

use super::description::Output;
use super::inputs::Inputs;
use super::plan::{LoadPlan, Plan};
use super::solve::{Analysis, Kinematics};
use crate::error::{finite, Error, Result};
use crate::kinematics::{
    assembly_range, extreme_positions, transfer_functions, try_cycle_angles, Extreme, Motion,
    Rotation, Strokes,
};

/// An output resolved to indices.
#[derive(Debug, Clone, Copy)]
pub(super) enum Resolved {
    Angle(usize),
    Slide(usize),
    Joint(usize, bool),
    Point(usize, bool),
}

impl Plan {
    /// The indices `output` names; an unknown name is an error of the description's field
    /// `output` (checked once, by [`Plan::new`]).
    pub(super) fn resolve(&self, output: &Output) -> Result<Resolved> {
        Ok(match output {
            Output::Angle(n) => Resolved::Angle(self.chain.link(n)?),
            Output::Slide(n) => Resolved::Slide(self.chain.prismatic(n)?),
            Output::X(n) | Output::Y(n) => {
                let y = matches!(output, Output::Y(_));
                match self.chain.joint(n) {
                    Ok(j) => Resolved::Joint(j, y),
                    Err(_) => Resolved::Point(self.chain.point(n)?, y),
                }
            }
        })
    }

    /// The value, rate and acceleration of `output` at one position.
    ///
    /// # Errors
    /// An unknown name; the kinematics' errors.
    pub fn output(&self, output: &Output, input: Motion) -> Result<Motion> {
        let r = self.resolve(output)?;
        Ok(read(&self.kinematics(input)?, r))
    }

    /// The transfer functions of `output` at the input `q` (its value, first and second
    /// derivatives with respect to the input coordinate).
    ///
    /// # Errors
    /// As [`Plan::output`].
    pub fn transfer(&self, output: &Output, q: f64) -> Result<Motion> {
        let r = self.resolve(output)?;
        let mut a = Kinematics::new(self);
        transfer_functions(
            |m| {
                a.solve(&[m])?;
                Ok(read(&a, r))
            },
            q,
        )
    }

    /// The extreme positions of `output` over a full turn of the crank (360 samples, each
    /// refined to machine precision).
    ///
    /// # Errors
    /// A slider input (it has no turn); a position where the linkage fails.
    pub fn extremes(&self, output: &Output) -> Result<Vec<Extreme>> {
        self.need_crank("extreme positions over a turn")?;
        let r = self.resolve(output)?;
        let mut a = Kinematics::new(self);
        extreme_positions(
            |phi| {
                transfer_functions(
                    |m| {
                        a.solve(&[m])?;
                        Ok(read(&a, r))
                    },
                    phi,
                )
            },
            360,
        )
    }

    /// The working and idle strokes of `output` for a crank turning in the sense `rotation`:
    /// its two extreme positions, the crank angles of the strokes, the time ratio and the
    /// stroke (or swing).
    ///
    /// The working direction is derived from the loads where they tell it: a resistance on the
    /// output itself (on its link for an angle, on its joint for a slide) that is larger in
    /// one direction makes that direction the working stroke, even if it is the faster one.
    /// Otherwise the working stroke is the slower one (the larger crank angle).
    ///
    /// # Errors
    /// As [`Plan::extremes`]; an output without exactly two extreme positions (one that turns
    /// fully, or one with more extremes per turn).
    pub fn strokes(&self, output: &Output, rotation: Rotation) -> Result<Strokes> {
        let extremes = self.extremes(output)?;
        let resolved = self.resolve(output)?;
        let strokes = match resolved {
            Resolved::Angle(_) => Strokes::new(&extremes, rotation)?.of_angle(&extremes),
            _ => Strokes::new(&extremes, rotation)?,
        };
        let worked = self.loads.iter().find_map(|l| match (l, resolved) {
            (
                LoadPlan::Turning {
                    link,
                    forward,
                    backward,
                },
                Resolved::Angle(k),
            ) if *link == k && forward != backward => Some(forward > backward),
            (
                LoadPlan::Sliding {
                    joint,
                    forward,
                    backward,
                    ..
                },
                Resolved::Slide(j),
            ) if *joint == j && forward != backward => Some(forward > backward),
            _ => None,
        });
        worked.map_or(Ok(strokes), |rises| strokes.working_in(rises))
    }

    /// The range of the crank angle, through `phi`, over which the linkage assembles: `None`
    /// when the crank turns fully, otherwise the two angles where it locks.
    ///
    /// # Errors
    /// A slider input; [`Error::OutOfRange`] for |φ| beyond
    /// [`MAX_INPUT_COORDINATE`](crate::linkage::MAX_INPUT_COORDINATE) (where the search's
    /// steps would be lost in φ's rounding); the linkage's error at `phi` itself.
    pub fn lock_positions(&self, phi: f64) -> Result<Option<(f64, f64)>> {
        self.need_crank("lock positions")?;
        crate::linkage::inputs::check_input_coordinate("phi", phi)?;
        let mut a = Kinematics::new(self);
        // Searched about φ brought into [0, 2π): far out (φ ~ 10⁹ rad, where neighbouring
        // angles are 10⁻⁷ apart) the bisections to 10⁻¹² rad could not be made about φ itself.
        let base = crate::angle::normalize(phi);
        let turns = phi - base;
        let range = assembly_range(base, |x| a.solve(&[Motion::fixed(x)]))?;
        Ok(range.map(|(lo, hi)| (lo + turns, hi + turns)))
    }

    /// The smallest transmission angle of group `g` over a turn of the crank, and the crank
    /// angle where it occurs: `(μ_min, φ1)`, rad. Found on 720 positions, then refined by
    /// golden-section search to 1e-12 rad of φ1. See [`Kinematics::transmission_angle`].
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"group index"`) for `g` not below `groups().len()`
    /// ([`Error::Description`] for a linkage without groups); a slider input; any position's
    /// error (a crank that cannot turn fully
    /// has no cycle to search).
    pub fn min_transmission_angle(&self, g: usize) -> Result<(f64, f64)> {
        self.check_group(g)?;
        self.need_crank("transmission angles over a turn")?;
        let mut a = Kinematics::new(self);
        let (mut best, mut at) = (f64::INFINITY, 0.0);
        for k in 0..TRANSMISSION_SWEEP {
            let phi = transmission_sweep_angle(k);
            a.solve(&[Motion::fixed(phi)])?;
            let m = a.transmission_angle(g)?;
            if m < best {
                (best, at) = (m, phi);
            }
        }
        let chain = Ancestry::new(self).of(g).to_vec();
        refine_transmission(&mut a, g, &chain, (best, at))
    }

    /// [`min_transmission_angle`](Self::min_transmission_angle) of every group at once, in
    /// the plan's group order: one sweep of the turn for all groups (720 solves of the
    /// linkage), then each group's refinement (52 positions a group), where a loop
    /// over the groups would solve the whole turn once per group. A group without a
    /// transmission angle (a general group) has its error in its place.
    ///
    /// A refinement solves only the group and the groups it hangs on
    /// ([`group_ancestry`](Self::group_ancestry)), never the groups after it or beside it:
    /// the whole search costs 720 solves of the linkage and 52 solves of each group's
    /// ancestry, so a linkage whose groups each hang on a few before them costs a small
    /// multiple of the sweep, and only a chain in which every group hangs on all the others
    /// costs the square of its length (half the whole-linkage refinement's).
    ///
    /// # Errors
    /// A slider input; any position's error (a crank that cannot turn fully has no cycle to
    /// search).
    pub fn min_transmission_angles(&self) -> Result<Vec<Result<(f64, f64)>>> {
        self.need_crank("transmission angles over a turn")?;
        let groups = self.groups().len();
        let mut a = Kinematics::new(self);
        let mut best: Vec<Result<(f64, f64)>> = vec![Ok((f64::INFINITY, 0.0)); groups];
        for k in 0..TRANSMISSION_SWEEP {
            let phi = transmission_sweep_angle(k);
            a.solve(&[Motion::fixed(phi)])?;
            for (g, b) in best.iter_mut().enumerate() {
                if let Ok((m0, at)) = b {
                    match a.transmission_angle(g) {
                        Ok(m) if m < *m0 => (*m0, *at) = (m, phi),
                        Ok(_) => {}
                        Err(e) => *b = Err(e),
                    }
                }
            }
        }
        let mut ancestry = Ancestry::new(self);
        Ok(best
            .into_iter()
            .enumerate()
            .map(|(g, b)| b.and_then(|found| refine_transmission(&mut a, g, ancestry.of(g), found)))
            .collect())
    }

    /// The groups whose solve group `g`'s solve reads, itself included, in attachment order
    /// (the order a solve takes them in): the groups that place the known links `g` hangs
    /// on, theirs in turn, down to the input links and the frame. Its motion at any input is
    /// a function of these groups alone, so solving them alone gives it to the bit.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"group index"`) for `g` not below `groups().len()`
    /// ([`Error::Description`] for a linkage without groups).
    ///
    /// # Examples
    /// The Watt six-bar's second dyad hangs on the first one's rocker:
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// let plan = Plan::new(&bundled::watt_six_bar())?;
    /// assert_eq!(plan.group_ancestry(0)?, [0]);
    /// assert_eq!(plan.group_ancestry(1)?, [0, 1]);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn group_ancestry(&self, g: usize) -> Result<Vec<usize>> {
        self.check_group(g)?;
        Ok(Ancestry::new(self).of(g).to_vec())
    }

    fn need_crank(&self, what: &str) -> Result<()> {
        if self.input_is_crank() {
            Ok(())
        } else {
            Err(Error::Description {
                item: "field input".to_owned(),
                problem: format!("{what} need a crank input, this linkage is driven by a slider"),
            })
        }
    }

    /// Analyses every position of `inputs` in turn with one [`Solver`](super::Solver) and
    /// maps each to what `f` takes of it: the cycle's values in order, a failed position's
    /// `Err` in its place (the cycle goes on past a group at a dead point). Nothing is
    /// allocated per position but what `f` returns, so this runs as fast as a solver loop by
    /// hand. `inputs` may be a slice or any iterator of inputs (generated on the fly).
    ///
    /// # Examples
    /// The balancing moment of the Watt six-bar over a turn, in 12 positions:
    /// ```
    /// use tmm::linkage::{bundled, uniform_inputs, Plan};
    /// let plan = Plan::new(&bundled::watt_six_bar())?;
    /// let inputs = uniform_inputs(12, plan.reference_input(), 10.0, 0.0);
    /// let mb = plan.cycle(&inputs, |a| Ok(a.balance(0)?.value));
    /// assert_eq!(mb.len(), 12);
    /// assert!(mb.iter().all(|m| m.is_ok()));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn cycle<I, T, F>(&self, inputs: I, mut f: F) -> Vec<Result<T>>
    where
        I: IntoIterator,
        I::Item: Into<Inputs>,
        F: FnMut(&Analysis<'_>) -> Result<T>,
    {
        let inputs = inputs.into_iter();
        let mut out = Vec::with_capacity(inputs.size_hint().0);
        let mut solver = self.solver();
        for i in inputs {
            out.push(solver.analyse(i).and_then(&mut f));
        }
        out
    }

    /// [`cycle`](Self::cycle) on all cores (feature `rayon`), one solver per worker: the same
    /// results, bit for bit, in the same order, because every position is a pure function of
    /// its inputs.
    #[cfg(feature = "rayon")]
    pub fn cycle_parallel<T, F>(
        &self,
        inputs: &[impl Into<Inputs> + Copy + Sync],
        f: F,
    ) -> Vec<Result<T>>
    where
        T: Send,
        F: Fn(&Analysis<'_>) -> Result<T> + Sync,
    {
        use rayon::prelude::*;
        inputs
            .par_iter()
            .map_init(|| self.solver(), |s, &i| s.analyse(i).and_then(&f))
            .collect()
    }
}

fn read(k: &Kinematics<'_>, r: Resolved) -> Motion {
    let a = k.pose();
    match r {
        Resolved::Angle(k) => a.link_angle_at(k),
        Resolved::Slide(j) => a.slide_at(j),
        Resolved::Joint(j, y) => coord(a.joint_motion_at(j), y),
        Resolved::Point(p, y) => coord(a.point_motion_at(p), y),
    }
}

fn coord(p: crate::kinematics::PointMotion, y: bool) -> Motion {
    if y {
        Motion::new(p.p.y, p.v.y, p.a.y)
    } else {
        Motion::new(p.p.x, p.v.x, p.a.x)
    }
}

/// The inputs of `n` equally spaced positions over one turn from `start`, at the constant
/// speed ω1 = `omega1` and acceleration ε1 = `epsilon1`. A negative ω1 turns clockwise: the
/// angles then decrease from `start`, in the order the crank reaches them.
///
/// Input that has no positions gives none: an empty vector for `n = 0`, `n` above
/// [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS) or a non-finite number;
/// [`try_uniform_inputs`] says why.
#[must_use]
pub fn uniform_inputs(n: usize, start: f64, omega1: f64, epsilon1: f64) -> Vec<Motion> {
    try_uniform_inputs(n, start, omega1, epsilon1).unwrap_or_default()
}

/// As [`uniform_inputs`], with an error for input that has no positions.
///
/// # Errors
/// [`Error::NonFinite`] naming a non-finite `start`, `omega1` or `epsilon1`;
/// [`Error::OutOfRange`] for `n = 0` or `n` above
/// [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS).
///
/// # Examples
/// ```
/// use tmm::linkage::try_uniform_inputs;
/// let inputs = try_uniform_inputs(4, 0.0, -2.0, 0.0).unwrap();
/// let angles: Vec<f64> = inputs.iter().map(|m| m.value.to_degrees().round()).collect();
/// assert_eq!(angles, [0.0, 270.0, 180.0, 90.0]); // clockwise, in the crank's order
/// assert!(try_uniform_inputs(0, 0.0, 1.0, 0.0).is_err());
/// assert!(try_uniform_inputs(12, 0.0, f64::NAN, 0.0).is_err());
/// ```
pub fn try_uniform_inputs(n: usize, start: f64, omega1: f64, epsilon1: f64) -> Result<Vec<Motion>> {
    finite("input speed omega1", omega1)?;
    finite("input acceleration epsilon1", epsilon1)?;
    let angles = try_cycle_angles(n, start)?;
    let mut a = Vec::with_capacity(angles.len());
    if omega1 < 0.0 {
        a.extend(angles.first().copied());
        a.extend(angles.iter().skip(1).rev().copied());
    } else {
        a.extend(angles);
    }
    Ok(a.into_iter()
        .map(|phi| Motion::new(phi, omega1, epsilon1))
        .collect())
}

/// The inputs of the `n` plans of a course project (12 in the seeds): equally spaced from the
/// beginning of the working stroke in the crank's sense of rotation, at the speed |ω1| =
/// `omega1` (its sign follows the rotation).
///
/// Input that has no plans gives none (an empty vector); [`try_course_inputs`] says why.
#[must_use]
pub fn course_inputs(strokes: &Strokes, n: usize, omega1: f64) -> Vec<Motion> {
    try_course_inputs(strokes, n, omega1).unwrap_or_default()
}

/// As [`course_inputs`], with an error for input that has no plans.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `omega1` or start of the working stroke;
/// [`Error::OutOfRange`] for `n = 0` or `n` above
/// [`MAX_POSITIONS`](crate::kinematics::MAX_POSITIONS).
pub fn try_course_inputs(strokes: &Strokes, n: usize, omega1: f64) -> Result<Vec<Motion>> {
    finite("input speed omega1", omega1)?;
    let w = match strokes.rotation {
        Rotation::Ccw => omega1.abs(),
        Rotation::Cw => -omega1.abs(),
    };
    Ok(strokes
        .try_plan_positions(n)?
        .into_iter()
        .map(|phi| Motion::new(phi, w, 0.0))
        .collect())
}

/// Runs any per-position function at every input, position by position. A position that
/// fails (for example a group at a dead point) gives its `Err` in its place and the cycle goes
/// on. For a plan's analyses, [`Plan::cycle`] is the fast path: it reuses one solver, where
/// `run_cycle(inputs, |i| plan.analyse(i))` allocates a whole analysis per position.
pub fn run_cycle<P, F>(inputs: &[Motion], analyse: F) -> Vec<Result<P>>
where
    F: Fn(Motion) -> Result<P>,
{
    inputs.iter().map(|&i| analyse(i)).collect()
}

/// [`run_cycle`] on all cores (feature `rayon`): the same results, bit for bit, in the same
/// order, because every position is a pure function of its input.
#[cfg(feature = "rayon")]
pub fn run_cycle_parallel<P, F>(inputs: &[Motion], analyse: F) -> Vec<Result<P>>
where
    P: Send,
    F: Fn(Motion) -> Result<P> + Sync,
{
    use rayon::prelude::*;
    inputs.par_iter().map(|&i| analyse(i)).collect()
}

/// The positions of a turn on which transmission angles are first searched.
const TRANSMISSION_SWEEP: u32 = 720;

/// The crank angle of the sweep's k-th position.
fn transmission_sweep_angle(k: u32) -> f64 {
    std::f64::consts::TAU / f64::from(TRANSMISSION_SWEEP) * f64::from(k)
}

/// Group `g`'s smallest transmission angle refined from the sweep's best `(μ, φ)` by
/// golden-section search on [φ − h, φ + h] (h the sweep's step), where μ has its one
/// minimum, to 1e-12 rad of φ.
///
/// Each position solves only `chain`, the group's ancestry (ending in `g`): the group's
/// motion is the whole solve's to the bit, without the groups it does not hang on.
fn refine_transmission(
    a: &mut Kinematics<'_>,
    g: usize,
    chain: &[usize],
    (best, at): (f64, f64),
) -> Result<(f64, f64)> {
    let mut mu = |phi: f64| -> Result<f64> {
        a.solve_groups(&[Motion::fixed(phi)], chain)?;
        a.transmission_angle(g)
    };
    let h = std::f64::consts::TAU / f64::from(TRANSMISSION_SWEEP);
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (at - h, at + h);
    let (mut x1, mut x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut f1, mut f2) = (mu(x1)?, mu(x2)?);
    while hi - lo > 1e-12 {
        if f1 <= f2 {
            (hi, x2, f2) = (x2, x1, f1);
            x1 = hi - r * (hi - lo);
            f1 = mu(x1)?;
        } else {
            (lo, x1, f1) = (x1, x2, f2);
            x2 = lo + r * (hi - lo);
            f2 = mu(x2)?;
        }
    }
    let (m, x) = if f1 <= f2 { (f1, x1) } else { (f2, x2) };
    Ok(if m < best {
        (m, crate::angle::normalize(x))
    } else {
        (best, at)
    })
}

/// The ancestries of a plan's groups, found one after another with the same buffers: which
/// group places each link, a mark per group (the number of the walk that last reached it)
/// and the walk's stack, so a walk costs the size of the ancestry it finds.
struct Ancestry<'p> {
    plan: &'p Plan,
    /// Per link, the group that places it; `None` for the frame and the input links.
    placed_by: Vec<Option<usize>>,
    /// Per group, the walk that last reached it.
    mark: Vec<usize>,
    walk: usize,
    stack: Vec<usize>,
    found: Vec<usize>,
}

impl<'p> Ancestry<'p> {
    fn new(plan: &'p Plan) -> Self {
        let mut placed_by = vec![None; plan.link_names().len()];
        for (g, group) in plan.groups().iter().enumerate() {
            for &l in placed_links(group) {
                placed_by[l] = Some(g);
            }
        }
        Self {
            plan,
            placed_by,
            mark: vec![0; plan.groups().len()],
            walk: 0,
            stack: Vec::new(),
            found: Vec::new(),
        }
    }

    /// Group `g`'s ancestry, in attachment order (`g` a group of the plan).
    fn of(&mut self, g: usize) -> &[usize] {
        self.walk += 1;
        self.found.clear();
        self.stack.clear();
        self.stack.push(g);
        self.mark[g] = self.walk;
        while let Some(h) = self.stack.pop() {
            self.found.push(h);
            let group = &self.plan.groups()[h];
            for_each_known_link(group, |l| {
                if let Some(p) = self.placed_by[l]
                    && self.mark[p] != self.walk
                {
                    self.mark[p] = self.walk;
                    self.stack.push(p);
                }
            });
        }
        // Attachment order is the groups' order: each is solved after those it reads.
        self.found.sort_unstable();
        &self.found
    }
}

/// The links a group places: a dyad's two, a triad's four, a general group's all.
fn placed_links(group: &super::plan::Group) -> &[usize] {
    if let Some(t) = &group.triad {
        &t.links
    } else if let Some(gp) = &group.general {
        &gp.links
    } else {
        &group.links
    }
}

/// Calls `f` on each known link a group's outer joints (or guides) hang on.
fn for_each_known_link(group: &super::plan::Group, mut f: impl FnMut(usize)) {
    if let Some(t) = &group.triad {
        t.known.iter().for_each(|&l| f(l));
    } else if let Some(gp) = &group.general {
        gp.known.iter().for_each(|&(l, _)| f(l));
    } else {
        group.known.iter().for_each(|&l| f(l));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linkage::bundled;

    /// Solving a group's ancestry alone gives the group's links the whole solve's motion to
    /// the bit, and its transmission angle, at 48 positions of every bundled crank linkage
    /// (a missed dependency would leave a stale or unsolved known link); the buffers are
    /// first filled at another position so that nothing is read from a previous solve.
    #[test]
    fn a_groups_ancestry_alone_gives_its_motion_to_the_bit() {
        let mut compared = 0;
        for l in bundled::all() {
            let plan = Plan::new(&l).unwrap();
            if !plan.input_is_crank() || plan.input_count() != 1 {
                continue;
            }
            let mut walk = Ancestry::new(&plan);
            let (mut whole, mut alone) = (Kinematics::new(&plan), Kinematics::new(&plan));
            for k in 0..48 {
                let phi = 0.1 + f64::from(k) * std::f64::consts::TAU / 48.0;
                if whole.solve(&[Motion::fixed(phi)]).is_err() {
                    continue;
                }
                for g in 0..plan.groups().len() {
                    let chain = walk.of(g).to_vec();
                    assert_eq!(chain.last(), Some(&g));
                    assert!(chain.windows(2).all(|w| w[0] < w[1]));
                    alone.solve(&[Motion::fixed(phi + 1.0)]).ok();
                    alone.solve_groups(&[Motion::fixed(phi)], &chain).unwrap();
                    for &link in placed_links(&plan.groups()[g]) {
                        let (a, b) = (whole.kin.links[link], alone.kin.links[link]);
                        assert_eq!(format!("{a:?}"), format!("{b:?}"), "{} group {g}", l.name);
                    }
                    match (whole.transmission_angle(g), alone.transmission_angle(g)) {
                        (Ok(a), Ok(b)) => assert_eq!(a.to_bits(), b.to_bits(), "{}", l.name),
                        (Err(_), Err(_)) => {}
                        (a, b) => panic!("{} group {g}: {a:?} against {b:?}", l.name),
                    }
                    compared += 1;
                }
            }
        }
        assert!(compared > 500, "{compared} group positions compared");
    }
}
