//! Random linkages of dyads and triads in a random order, for the planning tests (the
//! adversarial suite's and the linear-time property's), and the fit of a growth exponent.
#![allow(dead_code)]

use crate::common::hostile_gen::Gen;
use tmm::kinematics::Branch;
use tmm::linkage::{Joint, Link, Linkage, Mode};

/// A random linkage of `groups` groups, about a quarter of them triads (a ternary link held
/// by three binary links from three known links), the rest RRR dyads; the joints, links and
/// modes shuffled (or reversed). Returns it with its number of dyads and triads.
pub fn random_linkage(
    groups: usize,
    g: &mut Gen,
    reversed: bool,
    triads_too: bool,
) -> (Linkage, usize, usize) {
    let mut joints = vec![Joint::revolute("O", [0.0, 0.0])];
    let mut members: Vec<Vec<String>> = vec![vec!["O".into()], vec!["O".into()]];
    let mut modes = Vec::new();
    let p = |g: &mut Gen| [4.0 * g.unit() - 2.0, 4.0 * g.unit() - 2.0];
    let (mut dyads, mut triads) = (0, 0);
    for k in 0..groups {
        let known = members.len() as u64;
        let pick = |g: &mut Gen| {
            if k == 0 {
                1
            } else {
                (g.next() % known) as usize
            }
        };
        let mut hinge =
            |name: String, a: usize, b: usize, g: &mut Gen, members: &mut Vec<Vec<String>>| {
                let at = p(g);
                joints.push(Joint::revolute(&name, at));
                members[a].push(name.clone());
                members[b].push(name);
                at
            };
        if triads_too && k > 0 && g.next().is_multiple_of(4) {
            // A triad: ternary t, binaries b1..b3, each from a known link.
            let t = members.len();
            for _ in 0..4 {
                members.push(Vec::new());
            }
            for i in 0..3 {
                let from = pick(g);
                hinge(format!("A{k}_{i}"), from, t + 1 + i, g, &mut members);
                hinge(format!("B{k}_{i}"), t + 1 + i, t, g, &mut members);
            }
            triads += 1;
        } else {
            let (first, second) = (pick(g), pick(g));
            let (l2, l3) = (members.len(), members.len() + 1);
            members.push(Vec::new());
            members.push(Vec::new());
            let a = hinge(format!("A{k}"), first, l2, g, &mut members);
            let b = hinge(format!("B{k}"), l2, l3, g, &mut members);
            let c = hinge(format!("C{k}"), l3, second, g, &mut members);
            // The mode of the drawn pose: B to the left of A→C is `Plus`.
            let side = (c[0] - a[0]) * (b[1] - a[1]) - (c[1] - a[1]) * (b[0] - a[0]);
            modes.push((format!("B{k}"), l2, l3, side > 0.0));
            dyads += 1;
        }
    }
    let mut links: Vec<Link> = members
        .iter()
        .enumerate()
        .map(|(k, js)| {
            let name = match k {
                0 => "frame".to_owned(),
                1 => "crank".to_owned(),
                k => format!("L{k}"),
            };
            let js: Vec<&str> = js.iter().map(String::as_str).collect();
            Link::new(&name, &js)
        })
        .collect();
    let shuffle = |n: usize, g: &mut Gen| -> Vec<usize> {
        let mut order: Vec<usize> = (0..n).collect();
        if reversed {
            order[1..].reverse();
        } else {
            for v in 2..n {
                order.swap(v, 1 + (g.next() % v as u64) as usize);
            }
        }
        order
    };
    let order = shuffle(joints.len(), g);
    joints = order.iter().map(|&i| joints[i].clone()).collect();
    let order = shuffle(links.len(), g);
    links = order.iter().map(|&i| links[i].clone()).collect();
    // The engine takes a dyad's links in the order of the list: when l3 comes first, the
    // drawn side is measured from C to A, and the mode flips.
    let mut place = vec![0; order.len()];
    for (at, &k) in order.iter().enumerate() {
        place[k] = at;
    }
    let mut modes: Vec<Mode> = modes
        .into_iter()
        .map(|(joint, l2, l3, left)| Mode {
            joint,
            branch: if left == (place[l2] < place[l3]) {
                Branch::Plus
            } else {
                Branch::Minus
            },
        })
        .collect();
    if reversed {
        modes.reverse();
    }
    let l = Linkage {
        name: format!("{groups} random groups"),
        joints,
        links,
        modes,
        ..Linkage::default()
    };
    (l, dyads, triads)
}

/// The slope of the least-squares line through (ln x, ln y).
pub fn fitted_exponent(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}
