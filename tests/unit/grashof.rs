//! `src/kinematics/grashof.rs`: Grashof's classes, and the class against the linkage itself.

use nalgebra::Point2;
use proptest::prelude::*;
use tmm::kinematics::{crank, grashof, rrr_dyad, Branch, Grashof, Motion, PointMotion};
use tmm::Error;

#[test]
fn each_class_and_bad_lengths() {
    assert_eq!(grashof(0.4, 0.1, 0.35, 0.3).unwrap(), Grashof::CrankRocker);
    assert_eq!(grashof(0.4, 0.3, 0.35, 0.1).unwrap(), Grashof::RockerCrank);
    assert_eq!(grashof(0.4, 0.45, 0.1, 0.3).unwrap(), Grashof::DoubleRocker);
    assert_eq!(grashof(0.5, 0.3, 0.35, 0.4).unwrap(), Grashof::TripleRocker);
    assert_eq!(grashof(0.2, 0.2, 0.2, 0.2).unwrap(), Grashof::ChangePoint);
    // s + l = p + q exactly, without a parallelogram (a kite).
    assert_eq!(grashof(0.3, 0.1, 0.1, 0.3).unwrap(), Grashof::ChangePoint);
    assert!(matches!(
        grashof(0.0, 1.0, 1.0, 1.0),
        Err(Error::NonPositive { .. })
    ));
    assert!(matches!(
        grashof(f64::NAN, 1.0, 1.0, 1.0),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        grashof(f64::MAX, f64::MAX, 1.0, 1.0),
        Err(Error::Overflow { .. })
    ));
}

proptest! {
    /// The class against the linkage itself: the input turns fully exactly when the four-bar
    /// assembles at every one of 3600 crank angles (away from change points, where the gaps
    /// in the motion are narrower than the sampling).
    #[test]
    fn the_input_turns_fully_exactly_when_it_assembles_everywhere(
        frame in 0.05..1.0f64, input in 0.05..1.0f64, coupler in 0.05..1.0f64,
        output in 0.05..1.0f64,
    ) {
        let total = frame + input + coupler + output;
        let mut sorted = [frame, input, coupler, output];
        sorted.sort_by(f64::total_cmp);
        prop_assume!((sorted[0] + sorted[3] - sorted[1] - sorted[2]).abs() > 1e-2 * total);
        let g = grashof(frame, input, coupler, output).unwrap();
        let o3 = PointMotion::fixed(Point2::new(frame, 0.0));
        let everywhere = (0..3600).all(|k| {
            let phi = f64::from(k) * std::f64::consts::TAU / 3600.0;
            let a = crank(Point2::origin(), input, Motion::fixed(phi)).unwrap().a;
            rrr_dyad(a, o3, coupler, output, Branch::Plus).is_ok()
        });
        prop_assert_eq!(g.input_turns_fully(), everywhere, "{:?}", g);
    }
}
