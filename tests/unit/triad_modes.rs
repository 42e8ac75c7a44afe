//! `src/kinematics/triad.rs`: the generating pose is a mode, and a triad whose ends are too
//! far apart is refused with its gap.

use nalgebra::Point2;
use tmm::kinematics::{triad_modes, triad_tracked, TriadDims};
use tmm::Error;

fn example() -> (TriadDims, [Point2<f64>; 3]) {
    (
        TriadDims::new([1.0, 1.0, 1.0], 1.0, 0.5, 0.8),
        [
            Point2::new(0.0, -1.0),
            Point2::new(1.6, 0.8),
            Point2::new(0.5, 1.8),
        ],
    )
}

#[test]
fn triad_generating_pose_is_a_mode() {
    let (dims, a) = example();
    let modes = triad_modes(a, &dims).unwrap();
    assert!(modes
        .as_slice()
        .iter()
        .any(|m| m.b[0].coords.norm() < 1e-12));
    let reference = modes.as_slice()[0];
    assert_eq!(*modes.nearest(&reference), reference);
    let tracked = triad_tracked(a, &dims, &reference).unwrap();
    assert!(tracked.distance_squared(&reference) < 1e-24);
}

#[test]
fn triad_far_apart_is_not_assemblable() {
    let (dims, mut a) = example();
    a[2] = Point2::new(10.0, 10.0);
    match triad_modes(a, &dims) {
        Err(Error::NotAssemblable { group, gap }) => {
            assert_eq!(group, "triad");
            assert!(gap > 1.0, "{gap}");
        }
        other => panic!("{other:?}"),
    }
}
