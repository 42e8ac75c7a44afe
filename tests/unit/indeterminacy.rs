//! `src/kinetostatics/passive/indeterminacy.rs`: the degree of static indeterminacy by
//! contours and by links.

use tmm::kinetostatics::passive::indeterminacy::{by_contours, by_links, contours, HingedChain};

#[test]
fn both_formulas_agree_for_every_connected_chain() {
    for links in 1..8 {
        for inner in 0..12 {
            for frame in 0..8 {
                let c = HingedChain {
                    links,
                    inner_hinges: inner,
                    frame_hinges: frame,
                };
                if let Some(n) = c.by_contours() {
                    assert_eq!(n, c.by_links(), "{c:?}");
                }
            }
        }
    }
}

#[test]
fn the_seeds_counts() {
    // σ = 14 − 10 + 1 = 5 for Fig. 1b.
    assert_eq!(contours(14, 10), Some(5));
    assert_eq!(by_contours(5, 14), 1);
    assert_eq!(by_links(5, 3), 1);
    assert_eq!(contours(3, 5), None);
}

#[test]
fn huge_counts_do_not_overflow() {
    assert_eq!(contours(u32::MAX, 1), Some(u32::MAX));
    assert_eq!(contours(u32::MAX, 0), None);
    let c = HingedChain {
        links: u32::MAX,
        inner_hinges: u32::MAX,
        frame_hinges: u32::MAX,
    };
    let max = i64::from(u32::MAX);
    assert_eq!(c.by_links(), 4 * max - 3 * max);
    assert_eq!(c.by_contours(), Some(c.by_links()));
    assert_eq!(c.simple_hinges(), u32::MAX);
    let s = c.support_bar_scheme();
    assert_eq!((s.disks, s.hinges), (u32::MAX, u32::MAX));
}
