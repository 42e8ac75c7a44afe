//! Every real assembly mode of a linkage at given inputs: [`Plan::assembly_modes`].
//!
//! The groups are taken in attachment order; each assembly of the groups before a group
//! gives that group its known points, and the group's modes there are found by the search
//! that fits its kind:
//! - an **RRR or RRP dyad**: its closed form on both branches (two modes, one where the
//!   two coincide at a dead point within 10⁻⁹ of the size, none where it cannot be
//!   assembled); an RPR, PRP or RPP dyad has one;
//! - a **triad** (revolute or with a sliding pair): the certified bracket of every root of
//!   its eliminated equation ([`triad_modes`](crate::kinematics::triad_modes),
//!   [`slider_triad_modes`](crate::kinematics::slider_triad_modes)), each placed by the
//!   engine's own triad solve;
//! - a **general group**: a reduction to one equation in one angle, every sign change of it
//!   over a dense scan of the driver's turn bracketed and bisected (module
//!   `modes_reduction`); a group that does not reduce so (it would need two cut
//!   parameters) falls back to a seeded multistart Newton search, whose count is a lower
//!   bound ([`ModeSearch::Multistart`]).
//!
//! Every assembly of the whole linkage is one choice of mode per group, each group's modes
//! found on the assembly of the groups before it: the tree of choices is walked to its
//! leaves, so the whole count is exact even where a group's count depends on the modes
//! before it. Where it does not (the usual case: each group's count is the same on every
//! assembly before it) the whole count is the product of the groups' counts
//! ([`AllModes::is_product`]).

use super::inputs::Inputs;
use super::modes_reduction::{check_samples, modes_by_reduction, reduce};
use super::plan::{Chain, GroupKind, Plan};
use super::solve::state::KinState;
use crate::angle::normalize;
use crate::error::{Error, Result};
use crate::kinematics::{
    slider_triad_modes, triad_modes, Branch, Guide, LinkMotion, Motion, PointMotion, SlidingPair,
    TriadPose,
};
use nalgebra::Point2;

/// The most link motions the enumeration holds at once (assemblies times links, about
/// 250 bytes each).
const MAX_LINK_STATES: usize = 4_000_000;

/// The most solves of a general group's closure equations one start of the multistart
/// search makes ([`ModeSearch::Multistart`]): a least-squares fit of the origins and up to
/// 100 Newton steps, each one LU of the group's Jacobian.
pub const MULTISTART_SOLVES_PER_START: usize = 101;

/// The budgets of [`Plan::assembly_modes_with`].
///
/// # Examples
/// ```
/// use tmm::linkage::ModeOptions;
/// let o = ModeOptions::default().with_samples(200_000);
/// assert_eq!(o.samples, 200_000);
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ModeOptions {
    /// Samples of the driver's turn in a general group's reduction, 64 to 10⁷ (default
    /// 20 000): two roots of one branch closer than 2π/samples rad are not told apart.
    pub samples: usize,
    /// The most assemblies of the whole linkage enumerated (default 100 000): more is
    /// [`Error::Budget`].
    pub max_modes: usize,
    /// Random starts of the multistart fallback for a general group with no reduction
    /// (default 2000).
    pub starts: usize,
}

impl Default for ModeOptions {
    fn default() -> Self {
        Self {
            samples: 20_000,
            max_modes: 100_000,
            starts: 2000,
        }
    }
}

impl ModeOptions {
    /// With `samples` samples of a general group's driver turn.
    #[must_use]
    pub fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// With at most `max_modes` assemblies of the whole linkage.
    #[must_use]
    pub fn with_max_modes(mut self, max_modes: usize) -> Self {
        self.max_modes = max_modes;
        self
    }
}

/// How a group's modes were found.
#[derive(Debug, Clone, PartialEq)]
pub enum ModeSearch {
    /// A dyad's closed form on both branches: every mode.
    ClosedForm,
    /// A triad's certified bracket of its eliminated equation: every mode.
    Triad,
    /// A general group reduced to one equation in the angle of `driver` (a link hinged to a
    /// known point), cut at `closing`, scanned at `samples` samples per branch choice
    /// (`branches` of them): every mode whose root is simple and apart from the others by
    /// more than a sample.
    Reduction {
        /// The driver link (an index into [`Plan::link_names`]).
        driver: usize,
        /// The closing link (an index into [`Plan::link_names`]).
        closing: usize,
        /// Samples of the driver's turn.
        samples: usize,
        /// Branch choices of the dyads (2^dyads).
        branches: usize,
    },
    /// A general group with no such reduction: a seeded multistart Newton search from
    /// `starts` random starts; its count is a lower bound.
    Multistart {
        /// The random starts.
        starts: usize,
    },
}

/// The modes of one group over the assemblies of the groups before it.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupModes {
    /// The group's index in [`Plan::groups`].
    pub group: usize,
    /// Its name.
    pub name: String,
    /// Its kind.
    pub kind: GroupKind,
    /// How its modes were found.
    pub search: ModeSearch,
    /// Its number of modes on each assembly of the groups before it, in the order of
    /// [`AllModes::modes`] (one entry for the first group).
    pub counts: Vec<usize>,
}

impl GroupModes {
    /// Its number of modes when it is the same on every assembly of the groups before it.
    #[must_use]
    pub fn count(&self) -> Option<usize> {
        let first = *self.counts.first()?;
        self.counts.iter().all(|&c| c == first).then_some(first)
    }
}

/// One assembly of the whole linkage: every link's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageMode {
    /// Each link's frame origin, m, and angle in [0, 2π), rad (indexed as
    /// [`Plan::link_names`]); the frame is the one every solve reports.
    pub frames: Vec<(Point2<f64>, f64)>,
    /// The largest gap between the two sides of a revolute joint, m: closure to rounding.
    pub gap: f64,
}

/// Every real assembly mode of a linkage at given inputs ([`Plan::assembly_modes`]).
#[derive(Debug, Clone, PartialEq)]
pub struct AllModes {
    /// Per group in attachment order, its modes' counts and how they were found.
    pub groups: Vec<GroupModes>,
    /// Every assembly of the whole linkage.
    pub modes: Vec<LinkageMode>,
    /// Which of [`modes`](Self::modes) the engine's solve gives at these inputs (`None`
    /// when the engine's mode does not assemble there).
    pub reference: Option<usize>,
}

impl AllModes {
    /// The number of assemblies of the whole linkage.
    #[must_use]
    pub fn total(&self) -> usize {
        self.modes.len()
    }

    /// Whether every group's count is the same on every assembly before it, so that the
    /// total is the product of the groups' counts.
    #[must_use]
    pub fn is_product(&self) -> bool {
        self.groups.iter().all(|g| g.count().is_some())
    }

    /// Whether every count is exact (no group fell back to the multistart search).
    #[must_use]
    pub fn is_exhaustive(&self) -> bool {
        !self
            .groups
            .iter()
            .any(|g| matches!(g.search, ModeSearch::Multistart { .. }))
    }
}

impl Plan {
    /// Every real assembly mode of the linkage at `inputs` (positions only, at rest), with
    /// the default budgets ([`ModeOptions`]); see [`assembly_modes_with`](Self::assembly_modes_with).
    ///
    /// # Examples
    /// A four-bar has two modes at a crank angle inside its range (its coupler crossed or
    /// open), and the engine's is one of them:
    /// ```
    /// use tmm::linkage::{bundled, Plan};
    /// use tmm::kinematics::Motion;
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let all = plan.assembly_modes(Motion::fixed(plan.reference_input()))?;
    /// assert_eq!(all.total(), 2);
    /// assert!(all.reference.is_some());
    /// assert!(all.modes.iter().all(|m| m.gap < 1e-12 * plan.size()));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`assembly_modes_with`](Self::assembly_modes_with).
    pub fn assembly_modes(&self, inputs: impl Into<Inputs>) -> Result<AllModes> {
        self.assembly_modes_with(inputs, &ModeOptions::default())
    }

    /// Every real assembly mode of the linkage at `inputs` (module docs): each group's
    /// modes on every assembly of the groups before it, and every assembly of the whole.
    ///
    /// # Errors
    /// - a non-finite input, or not one per input (as [`Plan::analyse`]);
    /// - [`Error::OutOfRange`] for `samples` outside 64 … 10⁷;
    /// - [`Error::In`] naming the first group with no mode on any assembly before it (the
    ///   inputs are outside the linkage's range), with that group's own error;
    /// - [`Error::Budget`] when more than `max_modes` assemblies are found, or a reduction
    ///   would take more than 10⁹ evaluations.
    pub fn assembly_modes_with(
        &self,
        inputs: impl Into<Inputs>,
        options: &ModeOptions,
    ) -> Result<AllModes> {
        check_samples(options.samples)?;
        let rest = at_rest(inputs.into());
        let mut chain = self.chain.clone();
        let mut first = KinState::new(&chain);
        first.solve_groups(&chain, &rest, &[])?;
        let mut states = vec![first];
        let mut groups = Vec::with_capacity(chain.groups.len());
        for g in 0..chain.groups.len() {
            let search = search_of(&chain, g, options);
            let mut next = Vec::new();
            let mut counts = Vec::with_capacity(states.len());
            let mut why = None;
            for s in &mut states {
                let mut keep = |placed: &KinState| next.push(placed.clone());
                match group_modes(&mut chain, g, s, &rest, options, &search, &mut keep) {
                    Ok(n) => counts.push(n),
                    Err(e) => {
                        counts.push(0);
                        why.get_or_insert(e);
                    }
                }
                // The assemblies are held whole (every link's motion): their number times
                // the links bounds the memory too.
                if next.len() > options.max_modes
                    || next.len().saturating_mul(chain.link_names.len()) > MAX_LINK_STATES
                {
                    return Err(Error::Budget {
                        what: "assembly mode",
                        limit: options.max_modes,
                        time: 0.0,
                    });
                }
            }
            let name = chain.groups[g].name.clone();
            if next.is_empty() {
                let source = why.unwrap_or_else(|| Error::Description {
                    item: name.clone(),
                    problem: "no assembly mode at these inputs".to_owned(),
                });
                return Err(Error::In {
                    part: name,
                    source: Box::new(source),
                });
            }
            groups.push(GroupModes {
                group: g,
                name,
                kind: chain.groups[g].kind,
                search,
                counts,
            });
            states = next;
        }
        let modes: Vec<LinkageMode> = states.iter().map(|s| linkage_mode(&chain, s)).collect();
        // The engine's own solve at these inputs (at rest), to name its mode.
        let mut engine = KinState::new(&self.chain);
        let reference = engine.solve(&self.chain, &rest).ok().and_then(|()| {
            let engine = linkage_mode(&self.chain, &engine);
            let size = self.size();
            modes
                .iter()
                .position(|m| distance(m, &engine, size) <= 1e-9 * size)
        });
        Ok(AllModes {
            groups,
            modes,
            reference,
        })
    }
}

impl Plan {
    /// The search each group's modes would be found by with `options` (no solve: a triad's
    /// bracket, a dyad's closed form, a general group's reduction when one exists, else the
    /// multistart), so that a caller can weigh a search's work before it runs it: a
    /// multistart makes up to [`MULTISTART_SOLVES_PER_START`] solves of its group's closure
    /// equations from each start.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, ModeOptions, ModeSearch, Plan};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let s = plan.mode_searches(&ModeOptions::default());
    /// assert_eq!(s, vec![ModeSearch::ClosedForm]);
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn mode_searches(&self, options: &ModeOptions) -> Vec<ModeSearch> {
        (0..self.chain.groups.len())
            .map(|g| search_of(&self.chain, g, options))
            .collect()
    }

    /// Each group's number of modes on the engine's own assembly of the groups before it
    /// (its known points where the engine's solve puts them), at `inputs`: one search per
    /// group, so linear in the number of groups where [`assembly_modes`](Self::assembly_modes)
    /// walks every combination. Their product is the whole linkage's count when each group's
    /// count is the same on every assembly before it.
    ///
    /// # Errors
    /// As [`assembly_modes_with`](Self::assembly_modes_with); and the engine's error where
    /// its own mode does not assemble at `inputs` (the groups after it have no known points).
    pub fn mode_counts(
        &self,
        inputs: impl Into<Inputs>,
        options: &ModeOptions,
    ) -> Result<Vec<GroupModes>> {
        check_samples(options.samples)?;
        let rest = at_rest(inputs.into());
        let mut chain = self.chain.clone();
        let mut engine = KinState::new(&chain);
        engine.solve(&self.chain, &rest)?;
        (0..chain.groups.len())
            .map(|g| {
                let search = search_of(&chain, g, options);
                let n = group_modes(
                    &mut chain,
                    g,
                    &mut engine,
                    &rest,
                    options,
                    &search,
                    &mut |_| {},
                )
                .map_err(|e| Error::In {
                    part: chain.groups[g].name.clone(),
                    source: Box::new(e),
                })?;
                Ok(GroupModes {
                    group: g,
                    name: chain.groups[g].name.clone(),
                    kind: chain.groups[g].kind,
                    search,
                    counts: vec![n],
                })
            })
            .collect()
    }
}

/// The largest distance between two assemblies' link frames, their angles' differences
/// measured as arcs at the linkage's `size`.
fn distance(a: &LinkageMode, b: &LinkageMode, size: f64) -> f64 {
    a.frames
        .iter()
        .zip(&b.frames)
        .map(|(p, q)| {
            let turn = (normalize(p.1 - q.1 + std::f64::consts::PI) - std::f64::consts::PI).abs();
            (p.0 - q.0).norm().max(turn * size)
        })
        .fold(0.0, f64::max)
}

/// The assembly held in `s`, with its closure gap over the revolute joints.
fn linkage_mode(chain: &Chain, s: &KinState) -> LinkageMode {
    let frames = s
        .links
        .iter()
        .map(|l| (l.origin.p, normalize(l.angle)))
        .collect();
    let gap = chain
        .joints
        .iter()
        .filter(|j| j.prismatic.is_none())
        .map(|j| (s.at(j.links[0], j.local[0]).p - s.at(j.links[1], j.local[1]).p).norm())
        .fold(0.0, f64::max);
    LinkageMode { frames, gap }
}

/// The search group `g` takes.
fn search_of(chain: &Chain, g: usize, options: &ModeOptions) -> ModeSearch {
    let group = &chain.groups[g];
    if group.triad.is_some() {
        return ModeSearch::Triad;
    }
    let Some(gp) = &group.general else {
        return ModeSearch::ClosedForm;
    };
    match reduce(&gp.block, gp.size) {
        Some(r) => {
            let (d, c) = r.driver_and_closing();
            ModeSearch::Reduction {
                driver: gp.links[d],
                closing: gp.links[c],
                samples: options.samples,
                branches: r.branch_choices(),
            }
        }
        None => ModeSearch::Multistart {
            starts: options.starts,
        },
    }
}

/// The links group `g` places.
fn group_links(chain: &Chain, g: usize) -> Vec<usize> {
    let group = &chain.groups[g];
    match (&group.triad, &group.general) {
        (Some(t), _) => t.links.to_vec(),
        (_, Some(gp)) => gp.links.clone(),
        _ => group.links.to_vec(),
    }
}

/// The modes of group `g` on the assembly in `s` of the groups before it: `keep` sees `s`
/// with the group placed in each mode, in turn; then `s` is as it was. `chain` is the
/// plan's chain, whose group `g` is changed for a solve and restored. Returns the number of
/// modes; `Err` with the group's own error where it has none.
fn group_modes(
    chain: &mut Chain,
    g: usize,
    s: &mut KinState,
    rest: &[Motion],
    options: &ModeOptions,
    search: &ModeSearch,
    keep: &mut dyn FnMut(&KinState),
) -> Result<usize> {
    let links = group_links(chain, g);
    let saved: Vec<_> = links.iter().map(|&k| (s.links[k], s.units[k])).collect();
    let (det, triad) = (s.dets[g], s.triads[g]);
    let found = place_modes(chain, g, s, rest, options, search, &links, keep);
    for (&k, &(m, u)) in links.iter().zip(&saved) {
        s.put_link(k, m, u);
    }
    s.dets[g] = det;
    s.triads[g] = triad;
    found
}

/// [`group_modes`] without the restoring.
#[allow(clippy::too_many_arguments)]
fn place_modes(
    chain: &mut Chain,
    g: usize,
    s: &mut KinState,
    rest: &[Motion],
    options: &ModeOptions,
    search: &ModeSearch,
    links: &[usize],
    keep: &mut dyn FnMut(&KinState),
) -> Result<usize> {
    let size = chain.size;
    if chain.groups[g].general.is_some() {
        return general_modes(chain, g, s, options, search, keep);
    }
    if let Some(t) = chain.groups[g].triad.clone() {
        let poses: Vec<TriadPose> = match &t.slider {
            Some(leg) => {
                // The sliding leg's known part, as the engine's triad solve reads it: the
                // known link's guide through A1 (outer pair), or A1 alone (inner pair).
                let first = match leg.dims.pair {
                    SlidingPair::Outer { .. } => {
                        s.guide_on(t.known[0], t.a_local[0], leg.guide_offset)
                    }
                    SlidingPair::Inner { .. } => Guide {
                        point: s.at(t.known[0], t.a_local[0]),
                        angle: Motion::fixed(0.0),
                    },
                };
                let a = [1, 2].map(|i| s.at(t.known[i], t.a_local[i]).p);
                slider_triad_modes(&first, a, &leg.dims)?
                    .as_slice()
                    .to_vec()
            }
            None => {
                let a = [0, 1, 2].map(|i| s.at(t.known[i], t.a_local[i]).p);
                triad_modes(a, &t.dims)?.as_slice().to_vec()
            }
        };
        let mut n = 0;
        let mut why = None;
        for pose in poses {
            // The engine's triad solve takes the mode nearest its plan's reference: with the
            // reference set to this mode, it places this mode.
            if let Some(tp) = chain.groups[g].triad.as_mut() {
                tp.reference = pose;
            }
            match s.solve_groups(chain, rest, &[g]) {
                Ok(()) => {
                    n += 1;
                    keep(s);
                }
                Err(e) => {
                    why.get_or_insert(e);
                }
            }
        }
        chain.groups[g].triad = Some(t);
        return match (n, why) {
            (0, Some(e)) => Err(e),
            _ => Ok(n),
        };
    }
    let two = matches!(chain.groups[g].kind, GroupKind::Rrr | GroupKind::Rrp);
    let branches: &[Branch] = if two {
        &[Branch::Plus, Branch::Minus]
    } else {
        &[Branch::Plus]
    };
    let held = chain.groups[g].branch;
    let mut placed: Vec<Vec<(Point2<f64>, nalgebra::Vector2<f64>)>> = Vec::new();
    let mut why = None;
    for &b in branches {
        chain.groups[g].branch = b;
        match s.solve_groups(chain, rest, &[g]) {
            Ok(()) => {
                let now: Vec<_> = links
                    .iter()
                    .map(|&k| (s.links[k].origin.p, s.units[k]))
                    .collect();
                // The two branches coincide at a dead point: one mode.
                let same = placed.iter().any(|o| {
                    o.iter().zip(&now).all(|(p, q)| {
                        (p.0 - q.0).norm() <= 1e-9 * size && (p.1 - q.1).norm() <= 1e-9
                    })
                });
                if !same {
                    placed.push(now);
                    keep(s);
                }
            }
            Err(e) => {
                why.get_or_insert(e);
            }
        }
    }
    chain.groups[g].branch = held;
    match (placed.len(), why) {
        (0, Some(e)) => Err(e),
        (n, _) => Ok(n),
    }
}

/// The modes of general group `g` on the assembly in `s` before it (module docs), as
/// [`group_modes`] gives them.
fn general_modes(
    chain: &Chain,
    g: usize,
    s: &mut KinState,
    options: &ModeOptions,
    search: &ModeSearch,
    keep: &mut dyn FnMut(&KinState),
) -> Result<usize> {
    let Some(gp) = &chain.groups[g].general else {
        return Ok(0);
    };
    let outer: Vec<Point2<f64>> = gp.known.iter().map(|&(k, l)| s.at(k, l).p).collect();
    let poses = match search {
        ModeSearch::Reduction { branches, .. } => {
            if options.samples.saturating_mul(*branches) > 1_000_000_000 {
                return Err(Error::Budget {
                    what: "mode search evaluation",
                    limit: 1_000_000_000,
                    time: 0.0,
                });
            }
            let Some(r) = reduce(&gp.block, gp.size) else {
                return Ok(0);
            };
            modes_by_reduction(&gp.block, &r, &outer, gp.size, options.samples)?
        }
        _ => gp.block.modes(&outer, gp.size, options.starts, 0x5eed)?,
    };
    for pose in &poses {
        for (i, &k) in gp.links.iter().enumerate() {
            s.set_link(
                k,
                LinkMotion {
                    origin: PointMotion::fixed(pose.origins[i]),
                    angle: normalize(pose.angles[i]),
                    omega: 0.0,
                    epsilon: 0.0,
                },
            );
        }
        keep(s);
    }
    Ok(poses.len())
}

/// The inputs held at their values (no rate): the modes are a property of the pose alone.
fn at_rest(inputs: Inputs) -> Vec<Motion> {
    inputs
        .as_slice()
        .iter()
        .map(|m| Motion::fixed(m.value))
        .collect()
}
