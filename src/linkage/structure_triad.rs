//! The groups above the 2nd class in the structural decomposition: the triad (the Assur
//! group of the 3rd class with revolute joints), looked for when no dyad can be attached, and
//! the general fallback, a larger rigid group of hinges, when no triad can be either.
//!
//! A triad is four unknown links: a ternary link T joined to three binary links L1, L2, L3,
//! each of which is joined by its other joint to a known link (T itself has no joint to a
//! known link, and the binary links none to each other). Its three outer joints A_i are then
//! known points, and the group is rigid: 3·4 − 2·6 = 0. All six joints are hinges, or one of
//! them slides (the triad with a sliding pair; its leg is then planned first).
//!
//! A general group is a connected set of unknown links, all of whose joints are hinges,
//! with 2·joints = 3·links (rigid by count): the double butterfly's six-link group, a group of
//! the 4th class. It may hold smaller groups that the walk could not reach first (a dyad
//! hinged to a larger group); it is then solved whole, which is exact, only slower.

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

/// A rigid group of hinges of no smaller kind (the general fallback): its links, the hinges
/// between two of them (`inner`) and the hinges to known links (`outer`), each in joint
/// order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct GeneralFound {
    pub links: Vec<usize>,
    pub inner: Vec<usize>,
    pub outer: Vec<usize>,
}

/// A group found by the decomposition: a dyad (`D`, the structure's dyad), a triad or a
/// larger group.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Assur<D> {
    /// A dyad of the 2nd class.
    Dyad(D),
    /// A triad of the 3rd class.
    Triad(TriadFound),
    /// A larger rigid group of hinges, solved by its closure equations.
    General(GeneralFound),
}

/// A joint as the searches read it: the two links it joins, and whether it is a hinge.
pub(crate) type Joint = ([usize; 2], bool);

/// Each link's joints, with the link at each joint's other end.
pub(crate) type Adjacent = [Vec<(usize, usize)>];

/// The triad whose ternary link is `t`, if its joints make one over `known`; `work` counts
/// the adjacency entries read.
pub(crate) fn triad_on(
    edges: &[Joint],
    adjacent: &Adjacent,
    known: &[bool],
    t: usize,
    work: &mut u64,
) -> Option<TriadFound> {
    if known[t] {
        return None;
    }
    let joints = &adjacent[t];
    *work += joints.len() as u64;
    // T is joined to no known link.
    if joints.iter().any(|&(_, l)| known[l]) {
        return None;
    }
    // Candidates: joints of T to a binary link that has one joint to a known link and no
    // other joint to a known link or to T (at most one of a triad's six joints slides).
    let mut candidates: Vec<(usize, usize, usize)> = Vec::new();
    for &(j, l) in joints {
        let (mut to_t, mut outer, mut count) = (0, None, 0);
        for &(k, m) in &adjacent[l] {
            *work += 1;
            if k == j {
                continue;
            }
            if m == t {
                to_t += 1;
            }
            if known[m] {
                count += 1;
                outer = Some(k);
            }
        }
        if let (0, 1, Some(o)) = (to_t, count, outer)
            && (edges[o].1 || edges[j].1)
        {
            candidates.push((l, o, j));
        }
    }
    let n = candidates.len();
    let mut joined = |a: usize, b: usize| {
        *work += adjacent[a].len() as u64;
        adjacent[a].iter().any(|&(_, m)| m == b)
    };
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let c = [candidates[i], candidates[j], candidates[k]];
                let l = c.map(|x| x.0);
                if l[0] == l[1] || l[1] == l[2] || l[0] == l[2] {
                    continue;
                }
                let slides = c.iter().filter(|x| !(edges[x.1].1 && edges[x.2].1)).count();
                if slides > 1 {
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

/// The first connected set of unknown links (by its smallest link) that is a rigid group of
/// hinges over `known`: every joint of its links a hinge, 2·joints = 3·links. `work` counts
/// the adjacency entries read (each unknown link's list once).
pub(crate) fn next_general(
    edges: &[Joint],
    adjacent: &Adjacent,
    known: &[bool],
    work: &mut u64,
) -> Option<GeneralFound> {
    let mut seen = vec![false; known.len()];
    for start in 0..known.len() {
        if known[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        let mut links = vec![start];
        let (mut inner, mut outer) = (Vec::new(), Vec::new());
        let mut hinges = true;
        let mut next = 0;
        while next < links.len() {
            let l = links[next];
            next += 1;
            for &(j, m) in &adjacent[l] {
                *work += 1;
                hinges &= edges[j].1;
                if known[m] {
                    outer.push(j);
                } else {
                    // Each inner joint is met from both of its links: kept from the first.
                    if l < m {
                        inner.push(j);
                    }
                    if !seen[m] {
                        seen[m] = true;
                        links.push(m);
                    }
                }
            }
        }
        if hinges && 2 * (inner.len() + outer.len()) == 3 * links.len() {
            links.sort_unstable();
            inner.sort_unstable();
            outer.sort_unstable();
            return Some(GeneralFound {
                links,
                inner,
                outer,
            });
        }
    }
    None
}
