//! Branch tracking through a dead centre (`Plan::track`, `Course::track`): a parallelogram
//! four-bar stays a parallelogram over whole turns, a Grashof change-point four-bar runs on in
//! its other mode past its one change point with its velocities continuous (against finite
//! differences of its positions), and a crank-rocker's course is its plan's, bit for bit.

use std::f64::consts::{PI, TAU};
use tmm::linkage::{bundled, uniform_inputs, Course, Joint, Link, Linkage, Plan};

/// A four-bar: crank O1 A (`a`) about O1 = (0, 0), coupler A B (`b`), rocker O3 B (`c`) about
/// O3 = (`d`, 0), drawn at the crank angle `phi` with B on the side `s` (±1) of A → O3.
fn four_bar(a: f64, b: f64, c: f64, d: f64, phi: f64, s: f64) -> Linkage {
    let pa = [a * phi.cos(), a * phi.sin()];
    let (dx, dy) = (d - pa[0], -pa[1]);
    let l = dx.hypot(dy);
    let x = 0.5 * (l + (b - c) * (b + c) / l);
    let h = (b * b - x * x).max(0.0).sqrt();
    let pb = [
        pa[0] + (x * dx - s * h * dy) / l,
        pa[1] + (x * dy + s * h * dx) / l,
    ];
    Linkage {
        name: "four-bar".into(),
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", pa),
            Joint::revolute("B", pb),
            Joint::revolute("O3", [d, 0.0]),
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

/// `x` brought into (−π, π].
fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(TAU) - PI
}

#[test]
fn a_parallelogram_stays_a_parallelogram_over_whole_turns() {
    let plan = Plan::new(&four_bar(0.1, 0.3, 0.1, 0.3, PI / 3.0, 1.0)).unwrap();
    for (n, w) in [(360, 1.0), (360, -1.0), (12, 1.0), (1000, 1.0)] {
        let inputs = uniform_inputs(n, plan.reference_input(), w, 0.0);
        let track = plan.track(&inputs).unwrap();
        // Its two change points, at 0 and 180°, each crossed in the other mode.
        assert_eq!(track.crossings.len(), 2, "{:?}", track.crossings);
        assert!(track.crossings.iter().all(|c| c.flipped));
        assert!(track
            .crossings
            .iter()
            .all(|c| wrap(c.at).abs() < 1e-6 || (wrap(c.at).abs() - PI).abs() < 1e-6));
        let rows = track.cycle(&inputs, |a| {
            let (c, r) = (a.link_motion("crank")?, a.link_motion("rocker")?);
            Ok((wrap(r.angle - c.angle), r.omega - c.omega))
        });
        let (mut angle, mut rate) = (0.0f64, 0.0f64);
        for (m, r) in inputs.iter().zip(&rows) {
            match r {
                Ok((a, w)) => (angle, rate) = (angle.max(a.abs()), rate.max(w.abs())),
                // Only at a change point itself (0 or 180°), where the rates do not exist.
                Err(e) => assert!(
                    m.value.sin().abs() < 1e-12 && e.to_string().contains("singular"),
                    "{} {e}",
                    m.value
                ),
            }
        }
        println!(
            "parallelogram, {n} positions, ω {w}: rocker − crank ≤ {angle:.1e} rad, \
             ω(rocker) − ω(crank) ≤ {rate:.1e}"
        );
        assert!(angle < 1e-12, "{angle:e}");
        assert!(rate < 1e-9, "{rate:e}");
        assert_eq!(track.notes().len(), 2);
    }
    // Untracked, half the turn is on the antiparallelogram: the test can fail.
    let inputs = uniform_inputs(360, plan.reference_input(), 1.0, 0.0);
    let off = plan
        .cycle(&inputs, |a| {
            Ok(wrap(a.link_motion("rocker")?.angle - a.link_motion("crank")?.angle).abs())
        })
        .into_iter()
        .flatten()
        .filter(|d| *d > 1e-6)
        .count();
    assert!(off > 100, "{off}");
}

#[test]
fn a_change_point_four_bar_runs_on_in_its_other_mode_with_continuous_velocities() {
    // s + l = p + q (0.1 + 0.35 = 0.2 + 0.25), folded flat at φ = 0 only (|A O3| = 0.15 =
    // b − c): one change point a turn.
    let plan = Plan::new(&four_bar(0.1, 0.35, 0.2, 0.25, 1.0, 1.0)).unwrap();
    let n = 720;
    let inputs = uniform_inputs(n, plan.reference_input(), 1.0, 0.0);
    let track = plan.track(&inputs).unwrap();
    assert_eq!(track.crossings.len(), 1, "{:?}", track.crossings);
    assert!(track.crossings[0].flipped && wrap(track.crossings[0].at).abs() < 1e-6);
    // The rocker's angle between neighbouring positions against the trapezoid rule on its ω
    // (per unit crank rate): the error is h³/12·ψ''' ≈ 1e-7 for a smooth motion, a jump of
    // ω (the fold onto the other branch) makes it h·Δω/2 ≈ 1e-2.
    let worst_step = |rows: &[tmm::Result<(f64, f64)>]| {
        let h = TAU / f64::from(n as u32);
        rows.windows(2)
            .filter_map(|p| match (&p[0], &p[1]) {
                (Ok(a), Ok(b)) => Some((wrap(b.0 - a.0) - 0.5 * h * (a.1 + b.1)).abs()),
                _ => None,
            })
            .fold(0.0f64, f64::max)
    };
    let read = |a: &tmm::linkage::Analysis<'_>| {
        let r = a.link_motion("rocker")?;
        Ok((r.angle, r.omega))
    };
    let tracked = worst_step(&track.cycle(&inputs, read));
    let folded = worst_step(&plan.cycle(&inputs, read));
    println!(
        "change point: trapezoid residual tracked {tracked:.1e}, on the plan's mode {folded:.1e}"
    );
    assert!(tracked < 1e-5, "{tracked:e}");
    assert!(folded > 1e-3, "{folded:e}");
}

#[test]
fn a_crank_rockers_course_is_its_plans_bit_for_bit() {
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    for w in [10.0, -10.0] {
        let course = Course::new(&plan, None, 360, w).unwrap();
        let track = course.track(&plan).unwrap();
        assert!(track.crossings.is_empty() && track.plans.len() == 1);
        let row = |a: &tmm::linkage::Analysis<'_>| {
            Ok((
                a.balance(0)?.value,
                a.joint("B")?.p,
                a.link_motion("rocker")?.epsilon,
            ))
        };
        let ok = |v: Vec<tmm::Result<_>>| v.into_iter().map(Result::ok).collect::<Vec<_>>();
        let (tracked, own) = (
            ok(track.cycle(&course.inputs, row)),
            ok(plan.cycle(&course.inputs, row)),
        );
        assert!(tracked.iter().all(Option::is_some));
        assert_eq!(tracked, own);
    }
    // A rocking course reverses at its locks and crosses nothing.
    let plan = Plan::new(&bundled::chebyshev_straight_line()).unwrap();
    let course = Course::new(&plan, None, 24, 10.0).unwrap();
    assert!(course.track(&plan).unwrap().crossings.is_empty());
}

#[cfg(feature = "draw")]
#[test]
fn the_scheme_is_drawn_at_a_dead_centre_and_at_a_lock() {
    use tmm::draw::{scheme, Style};
    use tmm::kinematics::Motion;
    let plan = Plan::new(&four_bar(0.1, 0.3, 0.1, 0.3, PI / 3.0, 1.0)).unwrap();
    let at = Motion::new(PI, 1.0, 0.0);
    assert!(
        plan.kinematics(at).is_err(),
        "the rates do not exist at 180°"
    );
    let pic = scheme(&plan, at, &Style::default()).unwrap();
    // B drawn where the position-only solve puts it: (0.2, 0), on the line of the frame.
    let b = plan.position(at).unwrap().pose().joint("B").unwrap().p;
    assert!(
        (b - nalgebra::Point2::new(0.2, 0.0)).norm() < 1e-7 * plan.size(),
        "{b:?}"
    );
    let [x, y] = pic.frame.to_pixel(b);
    assert!(pic
        .svg
        .contains(&format!(r#"cx="{}""#, (x * 100.0).round() / 100.0)));
    assert!(pic
        .svg
        .contains(&format!(r#"cy="{}""#, (y * 100.0).round() / 100.0)));
    let plan = Plan::new(&bundled::chebyshev_straight_line()).unwrap();
    let (lo, hi) = plan.lock_positions(1.0).unwrap().unwrap();
    for q in [lo, hi] {
        assert!(scheme(&plan, Motion::fixed(q), &Style::default()).is_ok());
    }
}
