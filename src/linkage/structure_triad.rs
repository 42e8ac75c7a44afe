//! The triad in the structural decomposition: the Assur group of the 3rd class with revolute
//! joints, found when no dyad can be attached.
//!
//! A triad is four unknown links: a ternary link T hinged to three binary links L1, L2, L3,
//! each of which is hinged by its other joint to a known link (T itself has no joint to a
//! known link, and the binary links none to each other). Its three outer joints A_i are then
//! known points, and the group is rigid: 3·4 − 2·6 = 0.

/// One triad found by the decomposition: the ternary link and the binary links, the outer
/// joints A_i (binary link i with its known link) and the joints B_i (binary link i with the
/// ternary link), B_i in the order of the ternary link's joints in the description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TriadFound {
    pub ternary: usize,
    pub binary: [usize; 3],
    pub outer: [usize; 3],
    pub inner: [usize; 3],
}

impl TriadFound {
    /// The ternary link, then the binary links.
    pub(crate) fn links(&self) -> [usize; 4] {
        [self.ternary, self.binary[0], self.binary[1], self.binary[2]]
    }
}

/// A group found by the decomposition: a dyad (`D`, the structure's dyad) or a triad.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Assur<D> {
    /// A dyad of the 2nd class.
    Dyad(D),
    /// A triad of the 3rd class.
    Triad(TriadFound),
}

/// A joint as the triad's search reads it: the two links it joins, and whether it is a hinge.
pub(crate) type Joint = ([usize; 2], bool);

/// The link across joint `e` from `link`.
fn other(e: &Joint, link: usize) -> usize {
    if e.0[0] == link {
        e.0[1]
    } else {
        e.0[0]
    }
}

/// The first triad (by the ternary link's index) over `known`, if any.
pub(crate) fn next_triad(edges: &[Joint], known: &[bool]) -> Option<TriadFound> {
    (0..known.len())
        .filter(|&t| !known[t])
        .find_map(|t| triad_on(edges, known, t))
}

/// The triad whose ternary link is `t`, if its joints make one.
fn triad_on(edges: &[Joint], known: &[bool], t: usize) -> Option<TriadFound> {
    let joints: Vec<usize> = (0..edges.len())
        .filter(|&j| edges[j].0.contains(&t))
        .collect();
    // T is joined to no known link.
    if joints.iter().any(|&j| known[other(&edges[j], t)]) {
        return None;
    }
    // Candidates: revolute joints of T to a binary link that has one revolute joint to a
    // known link and no other joint to a known link or to T.
    let candidates: Vec<(usize, usize, usize)> = joints
        .iter()
        .filter(|&&j| edges[j].1)
        .filter_map(|&j| {
            let l = other(&edges[j], t);
            let mine: Vec<usize> = (0..edges.len())
                .filter(|&k| k != j && edges[k].0.contains(&l))
                .collect();
            let to_t = mine.iter().filter(|&&k| other(&edges[k], l) == t).count();
            let outer: Vec<usize> = mine
                .iter()
                .copied()
                .filter(|&k| known[other(&edges[k], l)])
                .collect();
            (to_t == 0 && outer.len() == 1 && edges[outer[0]].1).then(|| (l, outer[0], j))
        })
        .collect();
    let n = candidates.len();
    let joined = |a: usize, b: usize| edges.iter().any(|e| e.0.contains(&a) && e.0.contains(&b));
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let c = [candidates[i], candidates[j], candidates[k]];
                let l = c.map(|x| x.0);
                if l[0] == l[1] || l[1] == l[2] || l[0] == l[2] {
                    continue;
                }
                if joined(l[0], l[1]) || joined(l[1], l[2]) || joined(l[0], l[2]) {
                    continue;
                }
                return Some(TriadFound {
                    ternary: t,
                    binary: l,
                    outer: c.map(|x| x.1),
                    inner: c.map(|x| x.2),
                });
            }
        }
    }
    None
}
