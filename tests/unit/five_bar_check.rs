//! `src/dynamics/machines/five_bar.rs`: the robot's data check (a one-pass test with a named
//! error only on failure) against the rule it documents, for every field set to each kind of
//! value.

use tmm::dynamics::machines::{FiveBar, Servo};
use tmm::Error;

/// The servo's rule: finite target, gains and limit, the limit not negative.
fn servo_ok(s: &Servo) -> bool {
    [s.target, s.kp, s.kd, s.limit]
        .iter()
        .all(|v| v.is_finite())
        && s.limit >= 0.0
}

/// The robot's rule: finite pivots, gravity, motor moment and given inertias; positive
/// finite lengths, masses and crank inertias; each centre of mass on its coupler; good
/// servos; the mode ±1.
fn robot_ok(f: &FiveBar) -> bool {
    let finite = [f.o.x, f.o.y, f.d.x, f.d.y, f.gravity, f.m_on]
        .iter()
        .all(|v| v.is_finite())
        && f.j_s2.is_none_or(f64::is_finite)
        && f.j_s3.is_none_or(f64::is_finite);
    let positive = [f.l_oa, f.l_ab, f.l_cb, f.l_dc, f.m2, f.m3, f.i1, f.i4]
        .iter()
        .all(|&v| v > 0.0 && v < f64::INFINITY);
    let on = |v: f64, l: f64| 0.0 <= v && v <= l;
    finite
        && positive
        && on(f.l_as2, f.l_ab)
        && on(f.l_bs3, f.l_cb)
        && servo_ok(&f.drive1)
        && servo_ok(&f.drive4)
        && f.mode.abs() == 1.0
}

/// Every public evaluation checks the data first (`point_masses` here): bad data gives the
/// check's error, never an overflow of the masses computed from it; good data passes (its
/// masses may overflow only for huge values). Each servo's `check` follows its rule.
#[test]
fn the_fast_check_agrees_with_the_named_one() {
    let values = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        -1.0,
        -0.0,
        0.0,
        1e-300,
        0.05,
        0.3,
        1.0,
        2.0,
        1e300,
    ];
    type Field = fn(&mut FiveBar) -> &mut f64;
    let fields: [Field; 27] = [
        |f| &mut f.o.x,
        |f| &mut f.o.y,
        |f| &mut f.d.x,
        |f| &mut f.d.y,
        |f| &mut f.l_oa,
        |f| &mut f.l_ab,
        |f| &mut f.l_cb,
        |f| &mut f.l_dc,
        |f| &mut f.l_as2,
        |f| &mut f.l_bs3,
        |f| &mut f.m2,
        |f| &mut f.m3,
        |f| &mut f.i1,
        |f| &mut f.i4,
        |f| f.j_s2.get_or_insert(0.0),
        |f| f.j_s3.get_or_insert(0.0),
        |f| &mut f.mode,
        |f| &mut f.gravity,
        |f| &mut f.m_on,
        |f| &mut f.drive1.target,
        |f| &mut f.drive1.kp,
        |f| &mut f.drive1.kd,
        |f| &mut f.drive1.limit,
        |f| &mut f.drive4.target,
        |f| &mut f.drive4.kp,
        |f| &mut f.drive4.kd,
        |f| &mut f.drive4.limit,
    ];
    let (mut passed, mut failed) = (0, 0);
    for field in fields {
        for v in values {
            let mut robot = FiveBar::default();
            *field(&mut robot) = v;
            let ok = robot_ok(&robot);
            match robot.point_masses() {
                Ok(_) | Err(Error::Overflow { .. }) => assert!(ok, "{v} passed in {robot:?}"),
                Err(e) => assert!(!ok, "{v} refused in {robot:?}: {e}"),
            }
            for s in [robot.drive1, robot.drive4] {
                assert_eq!(s.check().is_ok(), servo_ok(&s), "{s:?}");
            }
            if ok {
                passed += 1
            } else {
                failed += 1
            }
        }
    }
    // Both outcomes are exercised.
    assert!(
        passed > 50 && failed > 100,
        "{passed} passed, {failed} failed"
    );
}
