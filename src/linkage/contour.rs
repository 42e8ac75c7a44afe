//! Contour lines of a sampled field by marching squares: the curves where a field on a grid
//! of nodes changes sign, joined into polylines. Used for the singular curves and the
//! boundary of a workspace.

use std::collections::HashMap;

/// A grid of `n1` × `n2` nodes; an axis that wraps (a crank's full turn) joins its last
/// node to its first.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Grid {
    pub n1: usize,
    pub n2: usize,
    pub wrap1: bool,
    pub wrap2: bool,
}

/// A node's indices; along a wrapping axis the index may equal the count (the first node
/// one turn on), so that a crossing between them is found on the continuing side.
pub(crate) type Node = (usize, usize);

impl Grid {
    /// The cells' lower-left nodes.
    pub fn cells(&self) -> impl Iterator<Item = Node> + use<> {
        let c1 = if self.wrap1 { self.n1 } else { self.n1 - 1 };
        let c2 = if self.wrap2 { self.n2 } else { self.n2 - 1 };
        (0..c1).flat_map(move |i| (0..c2).map(move |j| (i, j)))
    }

    /// The node's place in a row-major array of the nodes.
    pub fn index(&self, (i, j): Node) -> usize {
        (i % self.n1) * self.n2 + j % self.n2
    }

    /// An edge's key: its lower node's index, doubled, plus 1 along the second axis.
    fn edge(&self, a: Node, along_second: bool) -> usize {
        2 * self.index(a) + usize::from(along_second)
    }
}

/// The curves where `value` changes sign (`> 0` inside, `≤ 0` outside; a NaN node is
/// missing, and no curve passes through a cell with a missing corner), as polylines; a closed
/// one ends at its first point. `crossing(a, b)` gives the point of the curve on the edge
/// from node `a` to node `b` (one inside, one outside), or `None` to break the curve there;
/// it is called once per edge, and may give anything that marks the point. A saddle cell is split as its centre's value (the mean of
/// its corners) decides.
pub(crate) fn contours<T: Copy>(
    grid: Grid,
    value: &[f64],
    mut crossing: impl FnMut(Node, Node) -> Option<T>,
) -> Vec<Vec<T>> {
    if grid.n1 < 2 || grid.n2 < 2 {
        return Vec::new();
    }
    let v = |n: Node| value[grid.index(n)];
    let mut segments: Vec<[(usize, Node, Node); 2]> = Vec::new();
    for (i, j) in grid.cells() {
        let c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
        let vals = c.map(v);
        if vals.iter().any(|x| x.is_nan()) {
            continue;
        }
        let inside = vals.map(|x| x > 0.0);
        // Edges bottom, right, top, left: (key, from, to).
        let edges = [
            (grid.edge(c[0], false), c[0], c[1]),
            (grid.edge(c[1], true), c[1], c[2]),
            (grid.edge(c[3], false), c[3], c[2]),
            (grid.edge(c[0], true), c[0], c[3]),
        ];
        let cut = [
            inside[0] != inside[1],
            inside[1] != inside[2],
            inside[3] != inside[2],
            inside[0] != inside[3],
        ];
        let cuts: Vec<usize> = (0..4).filter(|&e| cut[e]).collect();
        match cuts.len() {
            2 => segments.push([edges[cuts[0]], edges[cuts[1]]]),
            4 => {
                let centre = vals.iter().sum::<f64>() > 0.0;
                // Cut off the corners on the other side from the centre.
                let pairs = if inside[0] == centre {
                    [(0, 1), (2, 3)]
                } else {
                    [(0, 3), (1, 2)]
                };
                for (a, b) in pairs {
                    segments.push([edges[a], edges[b]]);
                }
            }
            _ => {}
        }
    }
    let mut points: HashMap<usize, Option<T>> = HashMap::new();
    for s in &segments {
        for &(key, a, b) in s {
            points.entry(key).or_insert_with(|| crossing(a, b));
        }
    }
    join(
        &segments
            .iter()
            .map(|s| [s[0].0, s[1].0])
            .collect::<Vec<_>>(),
    )
    .into_iter()
    .flat_map(|keys| {
        // A missing crossing breaks the chain into pieces.
        let mut pieces = vec![Vec::new()];
        for k in keys {
            match points[&k] {
                Some(p) => pieces.last_mut().expect("one piece").push(p),
                None => pieces.push(Vec::new()),
            }
        }
        pieces.into_iter().filter(|p| p.len() >= 2)
    })
    .collect()
}

/// Chains of segments (pairs of edge keys) that share edges: each chain the keys in order,
/// a closed chain ending with its first key.
fn join(segments: &[[usize; 2]]) -> Vec<Vec<usize>> {
    let mut at: HashMap<usize, Vec<usize>> = HashMap::new();
    for (s, e) in segments.iter().enumerate() {
        for &k in e {
            at.entry(k).or_default().push(s);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut chains = Vec::new();
    for start in 0..segments.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut chain = vec![segments[start][0], segments[start][1]];
        // Forward from the second key, then backward from the first.
        for backward in [false, true] {
            loop {
                let end = if backward {
                    chain[0]
                } else {
                    chain[chain.len() - 1]
                };
                let Some(&s) = at[&end].iter().find(|&&s| !used[s]) else {
                    break;
                };
                used[s] = true;
                let next = if segments[s][0] == end {
                    segments[s][1]
                } else {
                    segments[s][0]
                };
                if backward {
                    chain.insert(0, next);
                } else {
                    chain.push(next);
                }
            }
        }
        chains.push(chain);
    }
    chains
}
