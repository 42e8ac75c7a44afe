//! Structural analysis: the mobility by Chebyshev's formula, and the decomposition into the
//! input link and Assur dyads of the 2nd class in attachment order.
//!
//! A dyad is two links joined to each other by one joint (the inner joint) and each joined by
//! one more joint (an outer joint) to links whose motion is already known. Starting from the
//! frame and the input link, the decomposition repeatedly takes a pair of unknown links that
//! forms such a dyad; their other joints (those of a ternary link) are left for the groups
//! attached later. When no dyad attaches, a triad of the 3rd class is looked for
//! (`structure_triad.rs`). A linkage of the 2nd class, with triads, is used up exactly;
//! whatever is left is a group of a higher class, or links that are not connected as a
//! mechanism with one input.

use super::structure_triad::{next_triad, Assur};
use crate::error::{Error, Result};

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

/// Joints of `link` other than `except` whose other link is in `known`.
fn attachments(edges: &[Edge], link: usize, except: usize, known: &[bool]) -> Vec<usize> {
    edges
        .iter()
        .enumerate()
        .filter(|&(j, e)| j != except && e.links.contains(&link))
        .filter(|(_, e)| {
            let other = if e.links[0] == link {
                e.links[1]
            } else {
                e.links[0]
            };
            known[other]
        })
        .map(|(j, _)| j)
        .collect()
}

/// Whether links `a` and `b`, both unknown, joined by `inner`, form a dyad over `known`.
fn as_dyad(edges: &[Edge], a: usize, b: usize, inner: usize, known: &[bool]) -> Option<Dyad> {
    let ja = attachments(edges, a, inner, known);
    let jb = attachments(edges, b, inner, known);
    let between = edges
        .iter()
        .filter(|e| e.links.contains(&a) && e.links.contains(&b))
        .count();
    (ja.len() == 1 && jb.len() == 1 && between == 1).then(|| Dyad {
        links: [a, b],
        joints: [ja[0], inner, jb[0]],
    })
}

/// The dyads in attachment order, found automatically (`explicit` empty) or checked from the
/// given pairs of links. `names` are the links' names for errors; link 0 is the frame and
/// `inputs` the input links (one per degree of freedom).
pub(crate) fn decompose(
    edges: &[Edge],
    names: &[String],
    inputs: &[usize],
    explicit: &[[usize; 2]],
) -> Result<Vec<Assur<Dyad>>> {
    let n = names.len();
    let mobility = chebyshev(n - 1, edges.len());
    let mut known = vec![false; n];
    known[0] = true;
    for &input in inputs {
        known[input] = true;
    }
    let mut dyads = Vec::new();
    if explicit.is_empty() {
        // A dyad when one attaches, else a triad (structure_triad.rs).
        let joints: Vec<_> = edges
            .iter()
            .map(|e| (e.links, e.pair == Pair::Revolute))
            .collect();
        loop {
            if let Some(d) = next_dyad(edges, &known) {
                known[d.links[0]] = true;
                known[d.links[1]] = true;
                dyads.push(Assur::Dyad(d));
            } else if let Some(t) = next_triad(&joints, &known) {
                for l in t.links() {
                    known[l] = true;
                }
                dyads.push(Assur::Triad(t));
            } else {
                break;
            }
        }
    } else {
        for &[a, b] in explicit {
            let d = edges
                .iter()
                .enumerate()
                .find(|(_, e)| e.links == [a, b] || e.links == [b, a])
                .and_then(|(j, _)| (!known[a] && !known[b]).then_some(j))
                .and_then(|j| as_dyad(edges, a, b, j, &known))
                .ok_or_else(|| Error::Description {
                    item: format!("group ({}, {})", names[a], names[b]),
                    problem: "is not a dyad of the 2nd class over the links before it: two \
                              links joined to each other and each by one joint to known links"
                        .to_owned(),
                })?;
            known[a] = true;
            known[b] = true;
            dyads.push(Assur::Dyad(d));
        }
    }
    let left: Vec<&str> = (0..n)
        .filter(|&k| !known[k])
        .map(|k| names[k].as_str())
        .collect();
    let wanted = inputs.len() as i64;
    if !left.is_empty() || mobility != wanted {
        let problem = if left.is_empty() {
            format!("has mobility W = {mobility} by Chebyshev's formula (3·{} moving links − 2·{} lower pairs); the engine needs W = {wanted}, one per declared input", n - 1, edges.len())
        } else {
            format!(
                "links {} do not decompose into dyads of the 2nd class or triads of the 3rd (mobility W = {mobility} \
                 by Chebyshev's formula, {} moving links, {} lower pairs): a group of a higher \
                 class, a wrong mobility or a link hanging free",
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
    Ok(dyads)
}

/// The first pair of unknown links (in joint order) that forms a dyad over `known`.
fn next_dyad(edges: &[Edge], known: &[bool]) -> Option<Dyad> {
    edges.iter().enumerate().find_map(|(j, e)| {
        let [a, b] = e.links;
        (!known[a] && !known[b])
            .then(|| as_dyad(edges, a, b, j, known))
            .flatten()
    })
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
    fn a_group_of_a_higher_class_is_named() {
        // A group of the 4th class: the closed contour 2-3-4-5, link 3 hinged to the frame,
        // 2 held by link 6 from the crank and 4 by link 7 from the frame (six links, nine
        // joints), W = 3·7 − 2·10 = 1. No dyad and no triad attaches.
        let e = [
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
