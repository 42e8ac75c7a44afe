//! Planning grows linearly whatever the order of the description: random linkages of dyads
//! and triads (each group hinged to links placed before it, at random points), every dyad's
//! mode given, their joints, links and modes listed in a random order or last-first, up to
//! 10⁴ joints. The decomposition's work (adjacency entries read, queue operations, the
//! triads' candidate checks) is counted by `Plan::decomposition_work` and fitted against the
//! number of joints; the plans themselves are made, with the groups the generator built.

use crate::common::chains::{fitted_exponent, random_linkage};
use crate::common::hostile_gen::Gen;
use tmm::linkage::Plan;

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
