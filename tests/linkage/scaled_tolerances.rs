//! The thresholds of the instant centres and of the branch tracking are relative: every
//! bundled file at 10⁻⁶ and 10⁶ of its size has its instant centres where the unscaled
//! file's are, times the scale (found the same way, the same pairs at infinity in the same
//! directions), and a parallelogram four-bar at those scales is tracked through the same
//! dead centres at the same crank angles with the same change of mode.

use super::scale::{changed_inputs, files, unscaled_inputs, Change, POSITIONS};
use tmm::linkage::{uniform_inputs, Centre, InstantCentre, Joint, Link, Linkage, Plan};

/// The scales tried besides 1.
const SCALES: [f64; 2] = [1e-6, 1e6];

/// A finite centre agrees with the unscaled one times s to this fraction of (the size + its
/// distance from the origin) — times (1 + d²/size²) for a centre d from the origin, where
/// the two lines that fix it cross at an angle ~size/d and the rounding of their directions
/// moves it by d/angle ~ d²/size (the positions themselves agree to 1e-14 of the size).
const CENTRE_RELATIVE: f64 = 1e-10;

/// The instant centres of `plan` at position `i` of the scale test's inputs on the copy
/// changed by `c`, or the error's text.
fn centres_at(
    plan: &Plan,
    unscaled: &Plan,
    c: Change,
    i: usize,
) -> Result<Vec<InstantCentre>, String> {
    let inputs = changed_inputs(unscaled, c, &unscaled_inputs(unscaled, i));
    let k = plan.kinematics(inputs).map_err(|e| e.to_string())?;
    plan.instant_centres(&k.pose()).map_err(|e| e.to_string())
}

#[test]
fn instant_centres_of_a_scaled_linkage_are_the_scaled_centres() {
    let (mut worst, mut finite, mut infinite, mut cases) = (0.0f64, 0, 0, 0);
    for (name, l) in files() {
        let plan = Plan::new(&l).unwrap();
        let size = plan.size();
        for s in SCALES {
            let c = Change::scale(s);
            let scaled = Plan::new(&c.apply(&l)).unwrap();
            for i in 0..POSITIONS {
                let a = centres_at(&plan, &plan, Change::scale(1.0), i);
                let b = centres_at(&scaled, &plan, c, i);
                let (a, b) = match (a, b) {
                    (Ok(a), Ok(b)) => (a, b),
                    (Err(_), Err(_)) => continue,
                    (a, b) => panic!(
                        "{name} at {s:e}, position {i}: {:?} against {:?}",
                        a.err(),
                        b.err()
                    ),
                };
                cases += 1;
                assert_eq!(a.len(), b.len(), "{name}");
                for (p, q) in a.iter().zip(&b) {
                    assert_eq!(
                        (p.links, p.found),
                        (q.links, q.found),
                        "{name} at {s:e}, {i}"
                    );
                    match (p.centre, q.centre) {
                        (Centre::At(x), Centre::At(y)) => {
                            let d = x.coords.norm() / size;
                            let gap = (y.coords / s - x.coords).norm()
                                / (size * (1.0 + d) * (1.0 + d * d));
                            assert!(
                                gap <= CENTRE_RELATIVE,
                                "{name} at {s:e}, position {i}, {:?}: {x} against {y}/s ({gap:e})",
                                p.links
                            );
                            worst = worst.max(gap);
                            finite += 1;
                        }
                        (Centre::Infinite(u), Centre::Infinite(v)) => {
                            // A direction is known up to its sign.
                            let gap = (u - v).norm().min((u + v).norm());
                            assert!(gap <= 1e-10, "{name} at {s:e}, {i}: {u} against {v}");
                            infinite += 1;
                        }
                        (x, y) => panic!(
                            "{name} at {s:e}, position {i}, {:?}: {x:?} against {y:?}",
                            p.links
                        ),
                    }
                }
            }
        }
    }
    println!(
        "instant centres at scales {SCALES:?}: {cases} positions, {finite} finite centres within \
         {worst:.1e} of the scaled unscaled ones (relative), {infinite} at infinity"
    );
    assert!(
        cases > 100 && finite > 1000 && infinite > 10,
        "{cases} {finite} {infinite}"
    );
}

/// A parallelogram four-bar (crank r, coupler and frame 3r, rocker r) drawn at 1 rad, with r
/// = 0.1·s.
fn parallelogram(s: f64) -> Linkage {
    let (sn, cs) = 1.0f64.sin_cos();
    let r = 0.1 * s;
    Linkage {
        name: "parallelogram".into(),
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", [r * cs, r * sn]),
            Joint::revolute("B", [3.0 * r + r * cs, r * sn]),
            Joint::revolute("O3", [3.0 * r, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("coupler", &["A", "B"]),
            Link::new("rocker", &["O3", "B"]),
        ],
        ..Linkage::default()
    }
}

#[test]
fn a_scaled_parallelogram_is_tracked_through_the_same_dead_centres() {
    let inputs = uniform_inputs(72, 1.0, 1.0, 0.0);
    let one = Plan::new(&parallelogram(1.0))
        .unwrap()
        .track(&inputs)
        .unwrap();
    // Its dead centres: the crank along the frame, at 0 and π; the plan's modes would fold
    // it into an antiparallelogram there, so the tracked run flips the rocker's dyad.
    assert_eq!(one.crossings.len(), 2, "{:?}", one.crossings);
    for (c, at) in one
        .crossings
        .iter()
        .zip([std::f64::consts::PI, std::f64::consts::TAU])
    {
        let gap =
            (c.at.rem_euclid(std::f64::consts::TAU) - at.rem_euclid(std::f64::consts::TAU)).abs();
        // Located to the width of the positions refused round a dead centre (a dyad within
        // rounding of its dead point has no rates: about 10⁻⁶ rad here), not to the bits.
        assert!(gap.min(std::f64::consts::TAU - gap) < 1e-5, "{c:?}");
    }
    for s in SCALES {
        let t = Plan::new(&parallelogram(s))
            .unwrap()
            .track(&inputs)
            .unwrap();
        assert_eq!(t.which, one.which, "scale {s:e}");
        assert_eq!(t.crossings.len(), one.crossings.len(), "scale {s:e}");
        for (a, b) in one.crossings.iter().zip(&t.crossings) {
            assert_eq!(
                (a.group, a.flipped, a.from_position),
                (b.group, b.flipped, b.from_position),
                "scale {s:e}"
            );
            assert!(
                (a.at - b.at).abs() <= 1e-5,
                "scale {s:e}: {} against {}",
                b.at,
                a.at
            );
            println!(
                "scale {s:e}: dead centre at {} (at scale 1: {})",
                b.at, a.at
            );
        }
        // The rocker turns with the crank (ω = 1 at unit rate) at every position, as at 1.
        let w = t.cycle(&inputs, |a| Ok(a.link_motion("rocker")?.omega));
        assert!(
            w.iter().all(|w| (w.as_ref().unwrap() - 1.0).abs() < 1e-9),
            "scale {s:e}: {w:?}"
        );
    }
}
