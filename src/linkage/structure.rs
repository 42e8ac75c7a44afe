//! Structural analysis: the mobility by Chebyshev's formula, and the decomposition into the
//! input link and Assur dyads of the 2nd class in attachment order.
//!
//! A dyad is two links joined to each other by one joint (the inner joint) and each joined by
//! one more joint (an outer joint) to links whose motion is already known. Starting from the
//! frame and the input link, the decomposition repeatedly takes a pair of unknown links that
//! forms such a dyad; their other joints (those of a ternary link) are left for the groups
//! attached later. When no dyad attaches, a triad of the 3rd class is looked for, and when
//! none attaches either, a larger rigid group of hinges (`structure_triad.rs`). Whatever is
//! left then is links that are not connected as a mechanism with its inputs (or a higher
//! group with sliding pairs), and is named.

use super::structure_triad::{next_general, triad_on, Assur, Joint, TriadFound};
use crate::error::{Error, Result};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

/// The kind of a joint, as far as the structure is concerned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pair {
    Revolute,
    Prismatic,
}

/// A joint between two links (indices into the link list; 0 is the frame).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edge {
    pub pair: Pair,
    pub links: [usize; 2],
}

/// One dyad found by the decomposition: its links and joints, in the order
/// (outer joint of link 2, inner joint, outer joint of link 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Dyad {
    pub links: [usize; 2],
    pub joints: [usize; 3],
}

/// The mobility of a planar linkage by Chebyshev's formula W = 3n − 2p₅ − p₄, with n moving
/// links and p₅ lower pairs (every revolute and prismatic joint; no higher pairs here).
#[must_use]
pub fn chebyshev(moving_links: usize, lower_pairs: usize) -> i64 {
    3 * moving_links as i64 - 2 * lower_pairs as i64
}

/// The structure as adjacency lists, built once, and the state of a decomposition over it:
/// which links are known and how many joints join each link to known links. Every query a
/// dyad needs is then a look-up, and each link's list is walked a bounded number of times (when
/// it becomes known, when its count of known neighbours first reaches one, when it is taken
/// into a dyad), so the decomposition is linear in the joints and links, plus a logarithm for
/// the queue that keeps the joint order.
struct Graph<'a> {
    edges: &'a [Edge],
    /// Each link's joints, with the link at each joint's other end.
    adjacent: Vec<Vec<(usize, usize)>>,
    /// For each joint, how many joints join the same two links.
    between: Vec<u32>,
    known: Vec<bool>,
    /// For each link, how many of its joints go to known links.
    known_neighbours: Vec<u32>,
    /// Unknown links that may be a triad's ternary link (stale entries are skipped).
    ternary: BinaryHeap<Reverse<usize>>,
    /// Adjacency entries visited and queue operations: the decomposition's work.
    work: u64,
}

impl<'a> Graph<'a> {
    fn new(edges: &'a [Edge], n: usize) -> Self {
        let mut adjacent: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        let mut pairs: HashMap<[usize; 2], u32> = HashMap::with_capacity(edges.len());
        for (j, e) in edges.iter().enumerate() {
            let [a, b] = e.links;
            adjacent[a].push((j, b));
            adjacent[b].push((j, a));
            *pairs.entry([a.min(b), a.max(b)]).or_insert(0) += 1;
        }
        let between = edges
            .iter()
            .map(|e| pairs[&[e.links[0].min(e.links[1]), e.links[0].max(e.links[1])]])
            .collect();
        Self {
            edges,
            adjacent,
            between,
            known: vec![false; n],
            known_neighbours: vec![0; n],
            ternary: (0..n).map(Reverse).collect(),
            work: edges.len() as u64,
        }
    }

    /// Marks `link` known; `reached` is told every unknown link whose count of known
    /// neighbours has just become one.
    fn learn(&mut self, link: usize, reached: &mut Vec<usize>) {
        if self.known[link] {
            return;
        }
        self.known[link] = true;
        for &(_, other) in &self.adjacent[link] {
            self.work += 1;
            if !self.known[other] {
                self.known_neighbours[other] += 1;
                if self.known_neighbours[other] == 1 {
                    reached.push(other);
                }
            }
        }
    }

    /// Whether the links `a` and `b`, both unknown, joined by joint `inner` (and by no other
    /// joint), each have exactly one joint to known links: a dyad over the known links.
    fn is_dyad(&self, a: usize, b: usize, inner: usize) -> bool {
        !self.known[a]
            && !self.known[b]
            && self.between[inner] == 1
            && self.known_neighbours[a] == 1
            && self.known_neighbours[b] == 1
    }

    /// The one joint of `link` to a known link (`link` has exactly one).
    fn attachment(&mut self, link: usize) -> usize {
        let mut found = 0;
        for &(j, other) in &self.adjacent[link] {
            self.work += 1;
            if self.known[other] {
                found = j;
                break;
            }
        }
        found
    }

    /// The dyad of links `a` and `b` joined by `inner` (checked by [`Graph::is_dyad`]),
    /// its links marked known.
    fn take(&mut self, a: usize, b: usize, inner: usize, reached: &mut Vec<usize>) -> Dyad {
        let joints = [self.attachment(a), inner, self.attachment(b)];
        self.learn(a, reached);
        self.learn(b, reached);
        Dyad {
            links: [a, b],
            joints,
        }
    }

    /// Queues every joint of the `reached` links that now joins a dyad, and each of their
    /// unknown neighbours as a triad's possible ternary link (a triad over the known links
    /// appears only when one of its binary links is reached).
    fn queue(&mut self, reached: &mut Vec<usize>, queue: &mut BinaryHeap<Reverse<usize>>) {
        for link in reached.drain(..) {
            for &(j, other) in &self.adjacent[link] {
                self.work += 1;
                let [a, b] = self.edges[j].links;
                if self.is_dyad(a, b, j) {
                    self.work += 1;
                    queue.push(Reverse(j));
                }
                if !self.known[other] {
                    self.work += 1;
                    self.ternary.push(Reverse(other));
                }
            }
        }
    }

    /// The triad over the known links with the smallest ternary link, if any. A link leaves
    /// the set of ternary links for good only (a known neighbour, or a binary link with a
    /// second known neighbour, stays), and enters it only when a neighbour is reached, when
    /// it is queued again: so the smallest queued link that makes a triad is the smallest of
    /// all, as a scan of every link would find.
    fn next_triad(&mut self, joints: &[Joint]) -> Option<TriadFound> {
        while let Some(&Reverse(t)) = self.ternary.peek() {
            self.work += 1;
            if let Some(found) = triad_on(joints, &self.adjacent, &self.known, t, &mut self.work) {
                return Some(found);
            }
            self.ternary.pop();
        }
        None
    }
}

/// The dyads in attachment order, found automatically (`explicit` empty) or checked from the
/// given pairs of links. `names` are the links' names for errors; link 0 is the frame and
/// `inputs` the input links (one per degree of freedom).
#[cfg(test)]
pub(crate) fn decompose(
    edges: &[Edge],
    names: &[String],
    inputs: &[usize],
    explicit: &[[usize; 2]],
) -> Result<Vec<Assur<Dyad>>> {
    decompose_counted(edges, names, inputs, explicit).map(|(dyads, _)| dyads)
}

/// As [`decompose`], with the work it did: the adjacency entries it visited and its queue
/// operations (at most a constant times the joints and links, plus the queue's logarithm,
/// while only dyads attach; a triad's search is the exception, `structure_triad.rs`).
pub(crate) fn decompose_counted(
    edges: &[Edge],
    names: &[String],
    inputs: &[usize],
    explicit: &[[usize; 2]],
) -> Result<(Vec<Assur<Dyad>>, u64)> {
    let n = names.len();
    let mobility = chebyshev(n - 1, edges.len());
    let mut graph = Graph::new(edges, n);
    let mut reached = Vec::new();
    graph.learn(0, &mut reached);
    for &input in inputs {
        graph.learn(input, &mut reached);
    }
    let mut dyads = Vec::new();
    if explicit.is_empty() {
        // The first joint (in joint order) whose two links form a dyad over the known links,
        // again and again. A joint leaves the set of such joints only for good (links only
        // become known, counts only grow), so a queue with stale entries skipped at the top
        // gives the same joint as a scan of all joints would. When no dyad attaches, a triad
        // is looked for (structure_triad.rs), and the dyads it makes possible are queued.
        let mut queue = BinaryHeap::new();
        reached.clear();
        for (j, e) in edges.iter().enumerate() {
            if graph.is_dyad(e.links[0], e.links[1], j) {
                queue.push(Reverse(j));
            }
        }
        let mut joints: Vec<([usize; 2], bool)> = Vec::new();
        loop {
            while let Some(Reverse(j)) = queue.pop() {
                graph.work += 1;
                let [a, b] = edges[j].links;
                if graph.is_dyad(a, b, j) {
                    dyads.push(Assur::Dyad(graph.take(a, b, j, &mut reached)));
                    graph.queue(&mut reached, &mut queue);
                }
            }
            if joints.is_empty() {
                joints = edges
                    .iter()
                    .map(|e| (e.links, e.pair == Pair::Revolute))
                    .collect();
            }
            if let Some(t) = graph.next_triad(&joints) {
                for l in t.links() {
                    graph.learn(l, &mut reached);
                }
                dyads.push(Assur::Triad(t));
            } else if let Some(g) =
                next_general(&joints, &graph.adjacent, &graph.known, &mut graph.work)
            {
                for &l in &g.links {
                    graph.learn(l, &mut reached);
                }
                dyads.push(Assur::General(g));
            } else {
                break;
            }
            graph.queue(&mut reached, &mut queue);
        }
    } else {
        let mut first: HashMap<[usize; 2], usize> = HashMap::with_capacity(edges.len());
        for (j, e) in edges.iter().enumerate() {
            let [a, b] = e.links;
            first.entry([a.min(b), a.max(b)]).or_insert(j);
        }
        for &[a, b] in explicit {
            graph.work += 1;
            let d = first
                .get(&[a.min(b), a.max(b)])
                .copied()
                .filter(|&j| graph.is_dyad(a, b, j))
                .map(|j| graph.take(a, b, j, &mut reached))
                .ok_or_else(|| Error::Description {
                    item: format!("group ({}, {})", names[a], names[b]),
                    problem: "is not a dyad of the 2nd class over the links before it: two \
                              links joined to each other and each by one joint to known links"
                        .to_owned(),
                })?;
            reached.clear();
            dyads.push(Assur::Dyad(d));
        }
    }
    let left: Vec<&str> = (0..n)
        .filter(|&k| !graph.known[k])
        .map(|k| names[k].as_str())
        .collect();
    let wanted = inputs.len() as i64;
    if !left.is_empty() || mobility != wanted {
        let problem = if left.is_empty() {
            format!("has mobility W = {mobility} by Chebyshev's formula (3·{} moving links − 2·{} lower pairs); the engine needs W = {wanted}, one per declared input", n - 1, edges.len())
        } else {
            format!(
                "links {} do not decompose into dyads of the 2nd class, triads of the 3rd or rigid \
                 groups of hinges (mobility W = {mobility} by Chebyshev's formula, {} moving \
                 links, {} lower pairs): a wrong mobility, a link hanging free, or a group of \
                 a higher class with a sliding pair",
                left.join(", "),
                n - 1,
                edges.len()
            )
        };
        return Err(Error::Description {
            item: "linkage".to_owned(),
            problem,
        });
    }
    Ok((dyads, graph.work))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(a: usize, b: usize) -> Edge {
        Edge {
            pair: Pair::Revolute,
            links: [a, b],
        }
    }

    fn names(n: usize) -> Vec<String> {
        (0..n).map(|k| k.to_string()).collect()
    }

    /// The decomposition as it was first written (a scan of every joint for each dyad,
    /// cubic in the worst order): the reference the linear one must agree with exactly.
    fn reference(
        edges: &[Edge],
        n: usize,
        inputs: &[usize],
        explicit: &[[usize; 2]],
    ) -> Option<Vec<Dyad>> {
        let attachments = |link: usize, except: usize, known: &[bool]| -> Vec<usize> {
            edges
                .iter()
                .enumerate()
                .filter(|&(j, e)| j != except && e.links.contains(&link))
                .filter(|(_, e)| {
                    known[if e.links[0] == link {
                        e.links[1]
                    } else {
                        e.links[0]
                    }]
                })
                .map(|(j, _)| j)
                .collect()
        };
        let as_dyad = |a: usize, b: usize, inner: usize, known: &[bool]| {
            let (ja, jb) = (attachments(a, inner, known), attachments(b, inner, known));
            let between = edges
                .iter()
                .filter(|e| e.links.contains(&a) && e.links.contains(&b))
                .count();
            (ja.len() == 1 && jb.len() == 1 && between == 1).then(|| Dyad {
                links: [a, b],
                joints: [ja[0], inner, jb[0]],
            })
        };
        let mut known = vec![false; n];
        known[0] = true;
        for &i in inputs {
            known[i] = true;
        }
        let mut dyads = Vec::new();
        if explicit.is_empty() {
            while let Some(d) = edges.iter().enumerate().find_map(|(j, e)| {
                let [a, b] = e.links;
                (!known[a] && !known[b])
                    .then(|| as_dyad(a, b, j, &known))
                    .flatten()
            }) {
                known[d.links[0]] = true;
                known[d.links[1]] = true;
                dyads.push(d);
            }
        } else {
            for &[a, b] in explicit {
                let d = edges
                    .iter()
                    .enumerate()
                    .find(|(_, e)| e.links == [a, b] || e.links == [b, a])
                    .and_then(|(j, _)| (!known[a] && !known[b]).then_some(j))
                    .and_then(|j| as_dyad(a, b, j, &known))?;
                known[a] = true;
                known[b] = true;
                dyads.push(d);
            }
        }
        let mobility = chebyshev(n - 1, edges.len());
        (known.iter().all(|&k| k) && mobility == inputs.len() as i64).then_some(dyads)
    }

    #[test]
    fn the_linear_decomposition_agrees_with_the_scan() {
        // Random structures: dyads hinged (or slid) to random known links, sometimes a stray
        // joint, a missing one or a doubled one, in a random joint order; automatic and
        // explicit (in the order found, and shuffled) decompositions.
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut agreed = 0;
        for case in 0..4000 {
            let dyads = 1 + (next() % 12) as usize;
            let mut edges = vec![r(0, 1)];
            let mut n = 2;
            for k in 0..dyads {
                let first = if k == 0 {
                    1
                } else {
                    (next() % n as u64) as usize
                };
                let second = (next() % n as u64) as usize;
                let pair = |x: u64| {
                    if x.is_multiple_of(5) {
                        Pair::Prismatic
                    } else {
                        Pair::Revolute
                    }
                };
                edges.push(Edge {
                    pair: pair(next()),
                    links: [first, n],
                });
                edges.push(Edge {
                    pair: pair(next()),
                    links: [n, n + 1],
                });
                edges.push(Edge {
                    pair: pair(next()),
                    links: [n + 1, second],
                });
                n += 2;
            }
            match next() % 6 {
                0 => {
                    let a = (next() % n as u64) as usize;
                    let b = (next() % n as u64) as usize;
                    if a != b {
                        edges.push(r(a, b));
                    }
                }
                1 => {
                    let j = 1 + (next() % (edges.len() as u64 - 1)) as usize;
                    edges.remove(j);
                }
                2 => {
                    let j = (next() % edges.len() as u64) as usize;
                    edges.push(edges[j]);
                }
                _ => {}
            }
            for v in 1..edges.len() {
                edges.swap(v, (next() % (v as u64 + 1)) as usize);
            }
            for e in &mut edges {
                if next().is_multiple_of(2) {
                    e.links.swap(0, 1);
                }
            }
            let names = names(n);
            // Only dyads: a structure the old algorithm could not finish may now hold a triad.
            let dyads_only = |r: Result<Vec<Assur<Dyad>>>| -> Option<Vec<Dyad>> {
                r.ok()?
                    .into_iter()
                    .map(|g| match g {
                        Assur::Dyad(d) => Some(d),
                        Assur::Triad(_) | Assur::General(_) => None,
                    })
                    .collect()
            };
            let found = dyads_only(decompose(&edges, &names, &[1], &[]));
            assert_eq!(
                found,
                reference(&edges, n, &[1], &[]),
                "case {case}: {edges:?}"
            );
            if let Some(d) = found {
                agreed += 1;
                let mut explicit: Vec<[usize; 2]> = d.iter().map(|d| d.links).collect();
                if next().is_multiple_of(2) {
                    for v in 1..explicit.len() {
                        explicit.swap(v, (next() % (v as u64 + 1)) as usize);
                    }
                    if let Some(p) = explicit.first_mut() {
                        p.swap(0, 1);
                    }
                }
                assert_eq!(
                    dyads_only(decompose(&edges, &names, &[1], &explicit)),
                    reference(&edges, n, &[1], &explicit),
                    "case {case}: {edges:?} {explicit:?}"
                );
            }
        }
        assert!(agreed > 1000, "{agreed}");
    }

    #[test]
    fn a_four_bar_is_one_dyad() {
        let e = [r(0, 1), r(1, 2), r(2, 3), r(3, 0)];
        let d = decompose(&e, &names(4), &[1], &[]).unwrap();
        assert_eq!(
            d,
            vec![Assur::Dyad(Dyad {
                links: [2, 3],
                joints: [1, 2, 3]
            })]
        );
        assert_eq!(chebyshev(3, 4), 1);
    }

    #[test]
    fn a_triad_is_found_when_no_dyad_attaches() {
        // Crank 1 drives link 3; a ternary link 2 is hinged to 3, 4 and 5; 4 and 5 are hinged
        // to the frame: a group of the 3rd class (four links, six joints), W = 3·5 − 2·7 = 1.
        let e = [
            r(0, 1),
            r(1, 3),
            r(3, 2),
            r(2, 4),
            r(2, 5),
            r(4, 0),
            r(5, 0),
        ];
        let d = decompose(&e, &names(6), &[1], &[]).unwrap();
        assert_eq!(
            d,
            vec![Assur::Triad(crate::linkage::structure_triad::TriadFound {
                ternary: 2,
                binary: [3, 4, 5],
                outer: [1, 5, 6],
                inner: [2, 3, 4],
            })]
        );
    }

    #[test]
    fn a_group_of_a_higher_class_is_a_general_group_and_with_a_slider_is_named() {
        // A group of the 4th class: the closed contour 2-3-4-5, link 3 hinged to the frame,
        // 2 held by link 6 from the crank and 4 by link 7 from the frame (six links, nine
        // joints), W = 3·7 − 2·10 = 1. No dyad and no triad attaches: one general group.
        let mut e = vec![
            r(0, 1),
            r(2, 3),
            r(3, 4),
            r(4, 5),
            r(5, 2),
            r(6, 2),
            r(6, 1),
            r(7, 4),
            r(7, 0),
            r(3, 0),
        ];
        let d = decompose(&e, &names(8), &[1], &[]).unwrap();
        assert_eq!(
            d,
            vec![Assur::General(
                crate::linkage::structure_triad::GeneralFound {
                    links: vec![2, 3, 4, 5, 6, 7],
                    inner: vec![1, 2, 3, 4, 5, 7],
                    outer: vec![6, 8, 9],
                }
            )]
        );
        // With a sliding pair it is no group the engine solves: the links are named.
        e[3].pair = Pair::Prismatic;
        let err = decompose(&e, &names(8), &[1], &[]).unwrap_err().to_string();
        assert!(err.contains("links 2, 3, 4, 5, 6, 7"), "{err}");
        assert!(err.contains("W = 1"), "{err}");
    }

    #[test]
    fn a_third_class_group_with_a_wrong_mobility_is_named() {
        let e = [
            r(0, 1),
            r(1, 3),
            r(3, 2),
            r(2, 4),
            r(2, 5),
            r(4, 0),
            r(5, 0),
        ];
        // One more hinge from the frame to 3 makes W = −1.
        let mut e2 = e.to_vec();
        e2.push(r(3, 0));
        let err = decompose(&e2, &names(6), &[1], &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("W = -1"), "{err}");
    }
}
