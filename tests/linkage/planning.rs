//! Planning grows linearly whatever the order of the description: random linkages of dyads
//! and triads (each group hinged to links placed before it, at random points), every dyad's
//! mode given, their joints, links and modes listed in a random order or last-first, up to
//! 10⁴ joints. The decomposition's work (adjacency entries read, queue operations, the
//! triads' candidate checks) is counted by `Plan::decomposition_work` and fitted against the
//! number of joints; the plans themselves are made, with the groups the generator built.

use crate::common::hostile_gen::Gen;
use tmm::kinematics::Branch;
use tmm::linkage::{Joint, Link, Linkage, Mode, Plan};

/// A random linkage of `groups` groups, about a quarter of them triads (a ternary link held
/// by three binary links from three known links), the rest RRR dyads; the joints, links and
/// modes shuffled (or reversed). Returns it with its number of dyads and triads.
fn random_linkage(
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
fn fitted_exponent(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn planning_work_with_triads_grows_linearly_whatever_the_order() {
    let mut g = Gen::new(2027);
    for reversed in [false, true] {
        let mut points = Vec::new();
        for groups in [8, 25, 80, 250, 800, 2500] {
            let (l, _, triads) = random_linkage(groups, &mut g, reversed, true);
            assert!(triads > 0 || groups < 25, "{}", l.name);
            let work = Plan::decomposition_work(&l).unwrap();
            let size = (l.joints.len() + l.links.len()) as f64;
            assert!(work as f64 <= 30.0 * size, "{}: work {work}", l.name);
            points.push((l.joints.len() as f64, work as f64));
        }
        // Fitted from 250 joints up: below, the links' degrees (which grow like the log of
        // the number of groups placed before them) have not reached their spread, and the
        // work per joint still rises.
        let large: Vec<(f64, f64)> = points.iter().copied().filter(|p| p.0 >= 250.0).collect();
        let exponent = fitted_exponent(&large);
        println!("planning work (reversed {reversed}): exponent {exponent:.3}, {points:?}");
        assert!(
            points.last().unwrap().0 >= 9000.0,
            "up to 10⁴ joints: {points:?}"
        );
        assert!(
            exponent <= 1.1,
            "reversed {reversed}: exponent {exponent}, {points:?}"
        );
    }
    // The plans are made, whatever the order, with the groups built and every dyad's mode
    // read by name (random triads are left out here: a random pose may put one near a
    // branch point, where the triad's own tests take over). A random chain can hold a dyad
    // near its dead point, whose reference pose then closes only to its conditioning: the
    // only error allowed, and most plans must be made.
    let mut made = 0;
    for case in 0..8 {
        let (l, dyads, _) = random_linkage(60, &mut g, case % 2 == 1, false);
        match Plan::new(&l) {
            Ok(plan) => {
                assert_eq!(plan.groups().len(), dyads);
                made += 1;
            }
            Err(e) => assert!(
                e.to_string().contains("the reference pose does not close"),
                "{}: {e}",
                l.name
            ),
        }
    }
    assert!(made >= 6, "{made} of 8 plans made");
}
