//! `src/dynamics/trajectory.rs`: the recorded rows, their Debug form, and rows of another
//! system refused.

use nalgebra::Vector2;
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar};
use tmm::dynamics::{accelerations, kinetic_energy, powers, LagrangeSystem, State, Trajectory};
use tmm::Error;

/// Debug shows the recorded rows under their names, never the block's spare room or
/// rows truncated away.
#[test]
fn debug_shows_the_recorded_columns_only() {
    let sys = FiveBar::default();
    let mut tr = Trajectory::for_system(&sys);
    for i in 0..3 {
        let x = 0.1 * f64::from(i) + 0.123_456_789;
        let s = State::new(x, Vector2::new(2.0, 1.0), Vector2::new(x, 0.0));
        tr.push(&sys, &s).unwrap();
    }
    tr.truncate(2);
    let text = format!("{tr:?}");
    assert!(text.contains("len: 2") && text.contains("\"t\", [0.123456789, 0.223456789"));
    assert!(!text.contains("0.323456789"), "{text}");
    for name in tr.header() {
        assert!(text.contains(&format!("\"{name}\"")), "{name}: {text}");
    }
    assert_eq!(
        format!("{:?}", Trajectory::default()).matches("[]").count(),
        Trajectory::default().header().len()
    );
}

/// Rows pushed one by one (through three doublings of the block) hold what the separate
/// public functions give at each state, bit for bit: q̈, T, the powers, Π, the outputs.
fn rows_match_the_separate_functions<S: LagrangeSystem>(sys: &S, base: Vector2<f64>) {
    let states: Vec<State> = (0..19)
        .map(|i| {
            let x = f64::from(i);
            State::new(
                0.01 * x,
                base + Vector2::new(0.03 * x, -0.02 * x),
                Vector2::new(0.5 - 0.1 * x, 0.2 * x),
            )
        })
        .collect();
    let mut tr = Trajectory::for_system(sys);
    for (n, s) in states.iter().enumerate() {
        tr.push(sys, s).unwrap();
        assert_eq!(tr.len(), n + 1);
        // Every earlier row survives the block's moves.
        for (r, s) in states[..=n].iter().enumerate() {
            let a = accelerations(sys, s.t, &s.q, &s.qd).unwrap();
            let (pa, pd) = powers(sys, s.t, &s.q, &s.qd).unwrap();
            let mut out = Vec::new();
            sys.outputs(s.t, &s.q, &s.qd, &mut out).unwrap();
            assert_eq!(tr.t()[r], s.t);
            assert_eq!([tr.q()[0][r], tr.q()[1][r]], [s.q[0], s.q[1]]);
            assert_eq!([tr.qd()[0][r], tr.qd()[1][r]], [s.qd[0], s.qd[1]]);
            assert_eq!([tr.qdd()[0][r], tr.qdd()[1][r]], [a[0], a[1]]);
            let t = kinetic_energy(sys, &s.q, &s.qd).unwrap();
            assert!((tr.kinetic()[r] - t).abs() <= 1e-15 * t.abs());
            assert_eq!(tr.potential()[r], sys.potential(&s.q).unwrap());
            assert_eq!([tr.power_applied()[r], tr.power_dissipated()[r]], [pa, pd]);
            let cols = tr.outputs();
            assert_eq!(cols.len(), out.len());
            for (c, v) in cols.iter().zip(&out) {
                assert_eq!(c[r], *v);
            }
        }
    }
    assert_eq!(tr.last_state(), states.last().copied());
    // Truncated and grown again: equal to one recorded straight, whatever the room left.
    let mut cut = tr.clone();
    cut.truncate(5);
    assert_eq!(cut.len(), 5);
    assert_ne!(cut, tr);
    for s in &states[5..] {
        cut.push(sys, s).unwrap();
    }
    assert_eq!(cut, tr);
    let mut short = Trajectory::for_system(sys);
    for s in &states[..5] {
        short.push(sys, s).unwrap();
    }
    tr.truncate(5);
    assert_eq!(short, tr);
    assert_eq!(short.to_csv(), tr.to_csv());
}

/// A trajectory takes rows of the system it was made for only; a default one takes the
/// first system's names. `output_at` reads the same columns as `outputs`.
#[test]
fn rows_of_another_system_are_refused() {
    let (coax, five) = (CoaxialPropellers::default(), FiveBar::default());
    let q0 = Vector2::new(120f64.to_radians(), 60f64.to_radians());
    let (s_coax, s_five) = (State::at_rest(Vector2::zeros()), State::at_rest(q0));
    let mut tr = Trajectory::default();
    tr.push(&coax, &s_coax).unwrap();
    assert_eq!(tr.coordinate_names(), coax.coordinate_names());
    let before = tr.clone();
    let e = tr.push(&five, &s_five);
    assert!(matches!(e, Err(Error::Description { .. })), "{e:?}");
    assert_eq!(tr, before);
    tr.truncate(0);
    assert!(tr.push(&five, &s_five).is_err());
    tr.push(&coax, &s_coax).unwrap();
    let cols = tr.outputs();
    assert!(!cols.is_empty());
    for (k, c) in cols.iter().enumerate() {
        assert_eq!(tr.output_at(k), Some(*c));
    }
    assert_eq!(tr.output_at(cols.len()), None);
    let mut fresh = Trajectory::for_system(&five);
    assert!(fresh.push(&coax, &s_coax).is_err());
    fresh.push(&five, &s_five).unwrap();
}

#[test]
fn rows_of_the_coaxial_drive() {
    rows_match_the_separate_functions(&CoaxialPropellers::default(), Vector2::zeros());
}

#[test]
fn rows_of_the_five_bar() {
    let q0 = Vector2::new(120f64.to_radians(), 60f64.to_radians());
    rows_match_the_separate_functions(&FiveBar::default(), q0);
}
