//! Hostile requirements for every public synthesis function but path generation (which has
//! its own): non-finite numbers, 0, negative, 1e±300, K ≤ 1 or beyond the feasible bound, a
//! swing outside (0, π), coinciding poses and points, too few points, and ordinary
//! requirements scaled by an extreme factor. Each call gives an `Error` (whose message names
//! something) or an `Ok` whose every number is finite and whose description the engine plans,
//! solves at its reference pose and around a turn with finite numbers, and reads back from
//! JSON to the same answer; where the report states K and the stroke, the engine finds them.
//! A seeded generator (`crate::common::hostile_gen`), `TMM_HOSTILE_CASES` cases per sweep.

use std::f64::consts::{PI, TAU};
use std::panic::{catch_unwind, AssertUnwindSafe};
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{Output, Plan};
use tmm::synthesis::{
    burmester, burmester_points, burmester_points_by_scan, centre_point, centre_point_curve,
    centre_point_two, circle_point, crank_rocker, crank_rocker_through, four_bar_from_dyads,
    freudenstein_coefficients, function_generator, shaper, slider_crank, CrankRockerRequirement,
    Dyad, FrameChoice, FunctionRequirement, OffsetChoice, Options, Pose, ShaperRequirement,
    SliderCrankRequirement, Spacing, Synthesis, MAX_POINTS,
};

use crate::common::hostile_gen::{cases, has_non_finite, Gen, SPECIAL};

thread_local! {
    /// The cases that failed so far in this test (a sweep runs to its end and then reports
    /// them all, so that one run shows every defect).
    static FAILED: std::cell::RefCell<Vec<String>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Runs `f`, panicking with `what` on a panic, to replay it.
fn no_panic<T>(what: &str, f: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| panic!("panicked: {what}"))
}

/// Runs one case; a failure is recorded (its message is on stderr), and the sweep goes on.
fn record(sweep: &str, case: usize, f: impl FnOnce()) {
    if catch_unwind(AssertUnwindSafe(f)).is_err() {
        FAILED.with(|f| f.borrow_mut().push(format!("{sweep} case {case}")));
    }
}

/// Fails the test if any case failed, naming the first few.
fn no_failures(sweep: &str) {
    let failed = FAILED.with(|f| std::mem::take(&mut *f.borrow_mut()));
    assert!(
        failed.is_empty(),
        "{sweep}: {} cases failed, the first: {:#?}",
        failed.len(),
        &failed[..failed.len().min(5)]
    );
}

/// An ordinary number in [lo, hi) most of the time, a hostile one otherwise.
fn mostly(g: &mut Gen, lo: f64, hi: f64) -> f64 {
    if g.next().is_multiple_of(5) {
        g.f()
    } else {
        lo + (hi - lo) * g.unit()
    }
}

/// A scale for a whole requirement: 1 half the time, else a hostile magnitude (including
/// 1e±300, 0, a negative one, NaN).
fn scale(g: &mut Gen) -> f64 {
    match g.next() % 6 {
        0 => SPECIAL[(g.next() % SPECIAL.len() as u64) as usize],
        1 => 10f64.powi((g.next() % 601) as i32 - 300),
        _ => 1.0,
    }
}

fn options(g: &mut Gen) -> Options {
    let gamma = match g.next() % 4 {
        0 => g.f(),
        1 => 0.0,
        _ => 0.7 * g.unit(),
    };
    Options::default().with_min_transmission_angle(gamma)
}

/// Checks an answer: an error with a message, or a finite answer that the engine analyses.
fn check(what: &str, r: &tmm::Result<Synthesis>) -> bool {
    let s = match r {
        Err(e) => {
            assert!(!e.to_string().is_empty(), "{what}: an empty message");
            // What an error computes (the nearest reachable value, a bound) is finite; only
            // the value asked for may echo a hostile input.
            match e {
                tmm::Error::Infeasible { reachable, .. } => {
                    assert!(reachable.is_finite(), "{what}: {e:?}");
                }
                tmm::Error::OutOfRange { min, max, .. } => {
                    assert!(min < max, "{what}: an empty range in {e:?}");
                }
                _ => {}
            }
            return false;
        }
        Ok(s) => s,
    };
    let shown = format!("{s:?}");
    assert!(!has_non_finite(&shown), "{what}: {shown}");
    let rep = &s.report;
    assert!(
        (0.0..=PI / 2.0).contains(&rep.min_transmission_angle),
        "{what}: γ_min {}",
        rep.min_transmission_angle
    );
    assert!(
        rep.dimensions.iter().all(|(_, x)| *x > 0.0),
        "{what}: {:?}",
        rep.dimensions
    );
    let plan =
        Plan::new(&s.linkage).unwrap_or_else(|e| panic!("{what}: the engine refuses it: {e}"));
    let phi0 = plan.reference_input();
    let k = plan
        .kinematics(Motion::new(phi0, 1.0, 0.0))
        .unwrap_or_else(|e| panic!("{what}: not solved at its reference pose: {e}"));
    let shown = format!("{k:?}");
    assert!(!has_non_finite(&shown), "{what}: {shown}");
    for i in 1..8 {
        if let Ok(k) = plan.kinematics(Motion::new(phi0 + TAU * f64::from(i) / 8.0, 1.0, 0.0)) {
            let shown = format!("{k:?}");
            assert!(!has_non_finite(&shown), "{what} at {i}/8 turn: {shown}");
        }
    }
    #[cfg(feature = "serde")]
    {
        let json = s
            .linkage
            .to_json()
            .unwrap_or_else(|e| panic!("{what}: not written: {e}"));
        let back = tmm::linkage::Linkage::from_json(&json)
            .unwrap_or_else(|e| panic!("{what}: not read back: {e}"));
        assert_eq!(back, s.linkage, "{what}");
        let again = Plan::new(&back).unwrap();
        let out = s.linkage.output.clone().unwrap();
        let at = Motion::fixed(phi0 + 0.3);
        assert_eq!(
            plan.output(&out, at).ok(),
            again.output(&out, at).ok(),
            "{what}"
        );
    }
    // The report's K and stroke are the engine's.
    // (A four-bar's report speaks of its rocker, whatever output the description names.)
    let out = if rep.grashof.is_some() {
        Some(Output::Angle("rocker".to_owned()))
    } else {
        s.linkage.output.clone()
    };
    if let (Some(k), Some(stroke), Some(out)) = (rep.time_ratio, rep.stroke, out) {
        let st = plan
            .strokes(&out, Rotation::Ccw)
            .unwrap_or_else(|e| panic!("{what}: no strokes: {e}"));
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        // The engine measures an angle's stroke in [0, 2π) values: a swing across the
        // direction +x comes out as 2π minus the swing (noted in the report).
        let stroke_of = if matches!(out, Output::Angle(_)) {
            st.stroke.min(TAU - st.stroke)
        } else {
            st.stroke
        };
        assert!(
            rel(st.time_ratio, k) < 1e-8 && rel(stroke_of, stroke) < 1e-8,
            "{what}: engine K {} stroke {:e}, report {k} {stroke:e}; {:?}",
            st.time_ratio,
            st.stroke,
            rep.dimensions
        );
    }
    true
}

fn check_dyad(what: &str, d: &Dyad) {
    assert!(
        d.centre.iter().chain(&d.circle).all(|x| x.is_finite()),
        "{what}: {d:?}"
    );
}

#[test]
fn quick_return_requirements() {
    let mut g = Gen::new(0x51_0001);
    let mut ok = 0;
    for case in 0..cases() {
        record("quick-return", case, || {
            let s = scale(&mut g);
            let o = options(&mut g);
            let frame = if g.next().is_multiple_of(2) {
                FrameChoice::Length(s * mostly(&mut g, 0.2, 1.5))
            } else {
                FrameChoice::BestTransmission
            };
            let need = CrankRockerRequirement {
                rocker: s * mostly(&mut g, 0.1, 1.0),
                swing: mostly(&mut g, 0.0, PI),
                time_ratio: mostly(&mut g, 0.9, 3.0),
                frame,
            };
            let what = format!("case {case}: crank_rocker({need:?}, {o:?})");
            let r = no_panic(&what, || crank_rocker(&need, &o));
            ok += usize::from(check(&what, &r));
            let offset = if g.next().is_multiple_of(2) {
                OffsetChoice::Given(s * mostly(&mut g, 0.0, 0.5))
            } else {
                OffsetChoice::BestTransmission
            };
            let need = SliderCrankRequirement {
                stroke: s * mostly(&mut g, 0.05, 1.0),
                time_ratio: mostly(&mut g, 0.9, 3.2),
                offset,
            };
            let what = format!("case {case}: slider_crank({need:?}, {o:?})");
            let r = no_panic(&what, || slider_crank(&need, &o));
            ok += usize::from(check(&what, &r));
            let need = ShaperRequirement {
                stroke: s * mostly(&mut g, 0.05, 1.0),
                time_ratio: mostly(&mut g, 0.9, 3.2),
                centre_distance: s * mostly(&mut g, 0.01, 0.5),
            };
            let what = format!("case {case}: shaper({need:?}, {o:?})");
            let r = no_panic(&what, || shaper(&need, &o));
            ok += usize::from(check(&what, &r));
        });
    }
    no_failures("quick-return");
    // The sweep is not all errors: the ordinary majority gives answers to check.
    assert!(ok >= cases() / 4, "{ok} answers");
    eprintln!(
        "hostile quick-return: {} calls, {ok} answers checked",
        3 * cases()
    );
}

/// K at the top of f64: θ = π(K − 1)/(K + 1) tends to π, so the quick-return methods name a
/// finite largest feasible K (crank-rocker) or a finite reachable value (shaper), never
/// `inf` and never an empty range.
#[test]
fn the_largest_time_ratios_give_finite_bounds() {
    let o = Options::default();
    for k in [1e308, f64::MAX] {
        let need = CrankRockerRequirement {
            rocker: 0.3,
            swing: 45f64.to_radians(),
            time_ratio: k,
            frame: FrameChoice::BestTransmission,
        };
        match crank_rocker(&need, &o) {
            Err(tmm::Error::OutOfRange { name, max, .. }) => {
                assert_eq!(name, "K");
                assert!(max.is_finite() && max > 1.0, "K = {k}: largest {max}");
            }
            other => panic!("K = {k}: {other:?}"),
        }
        let need = ShaperRequirement {
            stroke: 0.3,
            time_ratio: k,
            centre_distance: 0.25,
        };
        match shaper(&need, &o) {
            Err(tmm::Error::Infeasible { reachable, .. }) => {
                assert!(reachable.is_finite(), "K = {k}: reachable {reachable}");
            }
            Err(tmm::Error::OutOfRange { max, .. }) => {
                assert!(max.is_finite() && max > 1.0, "K = {k}: largest {max}");
            }
            other => panic!("K = {k}: {other:?}"),
        }
    }
}

/// A crank-rocker's rocker angle at φ (σ = +1, O1 at the origin, O3 at (d, 0)).
fn rocker_angle(d: f64, a: f64, b: f64, c: f64, phi: f64) -> Option<f64> {
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    let (vx, vy) = (d - ax, -ay);
    let e = vx.hypot(vy);
    let along = (b * b - c * c + e * e) / (2.0 * e);
    let h2 = b * b - along * along;
    (h2 > 0.0).then(|| {
        let h = h2.sqrt();
        let (bx, by) = (
            ax + (along * vx - h * vy) / e,
            ay + (along * vy + h * vx) / e,
        );
        by.atan2(bx - d)
    })
}

#[test]
fn freudenstein_requirements() {
    let mut g = Gen::new(0x51_0002);
    let mut ok = 0;
    for case in 0..cases() {
        record("Freudenstein", case, || {
            let s = scale(&mut g);
            let o = options(&mut g);
            // Positions of a crank-rocker (unit frame), some numbers made hostile, some repeated.
            let (a, b, c) = (
                0.05 + 0.1 * g.unit(),
                0.6 + 0.4 * g.unit(),
                0.4 + 0.5 * g.unit(),
            );
            let n = (g.next() % 5) as usize;
            let start = TAU * g.unit();
            let mut pairs: Vec<(f64, f64)> = (0..n)
                .map(|i| {
                    let phi = start + 1.2 * i as f64;
                    (phi, rocker_angle(1.0, a, b, c, phi).unwrap_or(1.0))
                })
                .collect();
            for p in &mut pairs {
                match g.next() % 8 {
                    0 => p.0 = g.f(),
                    1 => p.1 = g.f(),
                    _ => {}
                }
            }
            if n >= 2 && g.next().is_multiple_of(8) {
                pairs[1].0 = pairs[0].0 + TAU;
            }
            let frame = s * mostly(&mut g, 0.5, 1.5);
            let what = format!("case {case}: crank_rocker_through({frame:e}, {pairs:?}, {o:?})");
            let r = no_panic(&what, || crank_rocker_through(frame, &pairs, &o));
            ok += usize::from(check(&what, &r));
            let lengths = [g.f(), s * mostly(&mut g, 0.1, 1.0), g.len(), g.len()];
            let what = format!("case {case}: freudenstein_coefficients({lengths:?})");
            if let Ok(k) = no_panic(&what, || {
                freudenstein_coefficients(lengths[0], lengths[1], lengths[2], lengths[3])
            }) {
                assert!(k.iter().all(|x| x.is_finite()), "{what}: {k:?}");
            }
            // A function generator for one of a few functions, over a hostile or ordinary range.
            let which = g.next() % 4;
            let wild = g.f();
            let f = move |x: f64| match which {
                0 => x.ln(),
                1 => x * x,
                2 => (x * wild).sin(),
                _ => wild,
            };
            let x0 = mostly(&mut g, 1.0, 2.0);
            let spacing = match g.next() % 6 {
                0 => Spacing::LeastSquares((g.next() % 40) as usize),
                1 => Spacing::LeastSquares(MAX_POINTS + 1),
                _ => Spacing::Chebyshev,
            };
            let need = FunctionRequirement {
                x_range: [x0, x0 + mostly(&mut g, 0.5, 1.5)],
                crank_range: [mostly(&mut g, -0.6, 0.0), mostly(&mut g, 0.3, 1.0)],
                rocker_range: [mostly(&mut g, 0.0, TAU), mostly(&mut g, 0.5, 1.5)],
                frame: s * mostly(&mut g, 0.05, 1.0),
                spacing,
            };
            let need = FunctionRequirement {
                rocker_range: [
                    need.rocker_range[0],
                    need.rocker_range[0] + need.rocker_range[1],
                ],
                ..need
            };
            let what =
                format!("case {case}: function_generator(f{which} wild {wild:e}, {need:?}, {o:?})");
            let r = no_panic(&what, || function_generator(f, &need, &o));
            if let Ok(fg) = &r {
                for x in [need.x_range[0], need.x_range[1], fg.precision_x[0]] {
                    assert!(fg.crank_angle(x).is_finite(), "{what}");
                    assert!(fg.rocker_angle(f(x)).is_finite(), "{what}");
                }
                let m = [0, 1, 2, 17, MAX_POINTS + 1][(g.next() % 5) as usize];
                if let Ok(curve) = no_panic(&what, || fg.structural_error(f, m)) {
                    assert_eq!(curve.len(), m);
                    let shown = format!("{curve:?}");
                    assert!(!has_non_finite(&shown), "{what}: {shown}");
                }
            }
            ok += usize::from(check(&what, &r.map(|fg| fg.synthesis)));
        });
    }
    no_failures("Freudenstein");
    assert!(ok >= cases() / 10, "{ok} answers");
    eprintln!(
        "hostile Freudenstein: {} calls, {ok} answers checked",
        3 * cases()
    );
}

/// Poses of a coupler moving along an ordinary path (scaled by `s`), some numbers hostile,
/// some poses repeated.
fn poses<const N: usize>(g: &mut Gen, s: f64) -> [Pose; N] {
    let mut p: [Pose; N] = std::array::from_fn(|j| {
        let t = j as f64;
        Pose::new(
            [
                s * (0.1 * t + 0.03 * g.unit()),
                s * (0.05 * (t * 1.3).sin() + 0.03 * g.unit()),
            ],
            0.3 * t + 0.2 * g.unit(),
        )
    });
    for q in &mut p {
        match g.next() % 12 {
            0 => q.at[0] = g.f(),
            1 => q.at[1] = g.f(),
            2 => q.angle = g.f(),
            _ => {}
        }
    }
    if N >= 2 && g.next().is_multiple_of(8) {
        p[1] = p[0];
    }
    p
}

fn point(g: &mut Gen, s: f64) -> [f64; 2] {
    [s * mostly(g, -0.3, 0.3), s * mostly(g, -0.3, 0.0)]
}

#[test]
fn motion_requirements() {
    let mut g = Gen::new(0x51_0003);
    let mut ok = 0;
    for case in 0..cases() {
        record("motion", case, || {
            let s = scale(&mut g);
            let o = options(&mut g);
            let three: [Pose; 3] = poses(&mut g, s);
            let (za, zb) = (point(&mut g, s), point(&mut g, s));
            let what = format!("case {case}: burmester({three:?}, {za:?}, {zb:?}, {o:?})");
            let r = no_panic(&what, || burmester(&three, za, zb, &o));
            ok += usize::from(check(&what, &r));
            let what = format!("case {case}: centre_point/circle_point({three:?}, {za:?})");
            if let Ok(d) = no_panic(&what, || centre_point(&three, za)) {
                check_dyad(&what, &d);
                assert!(d.angles(&three).iter().all(|x| x.is_finite()), "{what}");
                if let Ok(back) = no_panic(&what, || circle_point(&three, d.centre)) {
                    check_dyad(&what, &back);
                }
            }
            if let Ok(d) = no_panic(&what, || circle_point(&three, zb)) {
                check_dyad(&what, &d);
            }
            let two = [three[0], three[1]];
            let along = s * mostly(&mut g, -0.3, 0.3);
            let what = format!("case {case}: centre_point_two({two:?}, {za:?}, {along:e})");
            let crank = no_panic(&what, || centre_point_two(&two, za, along));
            let rocker = no_panic(&what, || centre_point_two(&two, zb, -along));
            if let (Ok(c), Ok(r)) = (&crank, &rocker) {
                check_dyad(&what, c);
                check_dyad(&what, r);
                let what = format!("{what}: four_bar_from_dyads({c:?}, {r:?}, {o:?})");
                let four = no_panic(&what, || four_bar_from_dyads(&two, c, r, &o));
                ok += usize::from(check(&what, &four));
            }
            // Hostile dyads and too few poses.
            let wild = Dyad {
                centre: [g.f(), g.f()],
                circle: [g.f(), g.f()],
            };
            let tame = Dyad {
                centre: point(&mut g, s),
                circle: point(&mut g, s),
            };
            let k = (g.next() % 4) as usize;
            let what = format!(
                "case {case}: four_bar_from_dyads({:?}, {wild:?}, {tame:?})",
                &three[..k]
            );
            let r = no_panic(&what, || four_bar_from_dyads(&three[..k], &wild, &tame, &o));
            ok += usize::from(check(&what, &r));
            let four: [Pose; 4] = poses(&mut g, s);
            let n = [0, 1, 16, 90, MAX_POINTS + 1][(g.next() % 5) as usize];
            let what = format!("case {case}: centre_point_curve({four:?}, {n})");
            if let Ok(dyads) = no_panic(&what, || centre_point_curve(&four, n)) {
                assert!(dyads.len() <= 2 * n, "{what}");
                for d in &dyads {
                    check_dyad(&what, d);
                }
            }
        });
    }
    no_failures("motion");
    assert!(ok >= cases() / 10, "{ok} answers");
    eprintln!(
        "hostile motion generation: {} calls, {ok} answers checked",
        4 * cases()
    );
}

#[test]
fn five_pose_requirements() {
    let mut g = Gen::new(0x51_0004);
    // Burmester's points are costly (a scan of the curve's loops): a quarter of the cases.
    for case in 0..cases().div_ceil(4) {
        record("five poses", case, || {
            let s = scale(&mut g);
            let five: [Pose; 5] = poses(&mut g, s);
            let n = [0, 7, 8, 64, 400][(g.next() % 5) as usize];
            // The scan's sample count is hostile too (the count itself takes none).
            let scan = format!("case {case}: burmester_points_by_scan({five:?}, {n})");
            if let Ok(points) = no_panic(&scan, || burmester_points_by_scan(&five, n)) {
                assert!(points.len() <= 4, "{scan}: {points:?}");
                points.iter().for_each(|d| check_dyad(&scan, d));
            }
            let what = format!("case {case}: burmester_points({five:?})");
            if let Ok(points) = no_panic(&what, || burmester_points(&five)) {
                assert!(points.len() <= 4, "{what}: {points:?}");
                for d in &points {
                    check_dyad(&what, d);
                    let size = five
                        .iter()
                        .map(|p| p.at[0].hypot(p.at[1]))
                        .fold(d.length(), f64::max);
                    assert!(d.misfit(&five) <= 1e-8 * size, "{what}: {d:?}");
                }
            }
        });
    }
    no_failures("five poses");
}

/// The pictures of a synthesis with hostile targets and styles: an error, or an SVG without
/// a non-finite number.
#[cfg(feature = "draw")]
#[test]
fn pictures_of_hostile_targets() {
    use crate::common::svg_scan::assert_finite_svg;
    use tmm::draw::{structural_error, synthesis_scheme, Style, Targets};
    let deg = f64::to_radians;
    let s = crank_rocker(
        &CrankRockerRequirement {
            rocker: 0.3,
            swing: deg(45.0),
            time_ratio: 1.25,
            frame: FrameChoice::BestTransmission,
        },
        &Options::default(),
    )
    .unwrap();
    let plan = Plan::new(&s.linkage).unwrap();
    let fg = function_generator(
        f64::log10,
        &FunctionRequirement {
            x_range: [1.0, 2.0],
            crank_range: [deg(-30.0), deg(30.0)],
            rocker_range: [deg(0.0), deg(90.0)],
            frame: 0.1,
            spacing: Spacing::Chebyshev,
        },
        &Options::default(),
    )
    .unwrap();
    let mut g = Gen::new(0x51_0005);
    let (mut drawn, n) = (0, cases().div_ceil(4));
    for case in 0..n {
        record("pictures", case, || {
            let style = Style {
                samples: [0, 1, 2, 90, 100_000_000][(g.next() % 5) as usize],
                line_width: if g.next().is_multiple_of(4) {
                    g.f()
                } else {
                    2.0
                },
                ..Style::default()
            };
            let k = (g.next() % 6) as usize;
            let points: Vec<[f64; 2]> = (0..k)
                .map(|_| [mostly(&mut g, -0.3, 0.5), mostly(&mut g, -0.3, 0.5)])
                .collect();
            let poses: Vec<Pose> = (0..k)
                .map(|_| {
                    Pose::new(
                        [mostly(&mut g, -0.3, 0.5), mostly(&mut g, -0.3, 0.5)],
                        g.f(),
                    )
                })
                .collect();
            let curve: Vec<[f64; 2]> = (0..(g.next() % 50) as usize)
                .map(|i| {
                    let t = i as f64 * 0.1;
                    if g.next().is_multiple_of(7) {
                        [g.f(), g.f()]
                    } else {
                        [0.2 * t.cos(), 0.2 * t.sin()]
                    }
                })
                .collect();
            let path = ["B", "A", "Z", ""][(g.next() % 4) as usize];
            let mut targets = Targets::points(&points, path).with_curves(vec![curve]);
            targets.poses = poses;
            let phi = mostly(&mut g, 0.0, TAU);
            let what = format!("case {case}: synthesis_scheme(φ {phi:e}, {targets:?}, {style:?})");
            if let Ok(pic) = no_panic(&what, || {
                synthesis_scheme(&plan, Motion::fixed(phi), &targets, &style)
            }) {
                assert_finite_svg(&pic.svg, &what);
                drawn += 1;
            }
            let wild = g.f();
            let what = format!("case {case}: structural_error(wild {wild:e}, {style:?})");
            let f = |x: f64| if x > 1.9 { wild } else { x.log10() };
            if let Ok(chart) = no_panic(&what, || structural_error(&fg, f, &style)) {
                assert_finite_svg(&chart.svg, &what);
                drawn += 1;
            }
        });
    }
    no_failures("pictures");
    assert!(drawn >= n / 4, "{drawn} pictures");
}

/// The reviewer's finding: points scaled by 1e-300 were refused as an overflow. Their size's
/// square underflows (below 2.2e-308): the message says that, and points scaled by 1e160 (whose
/// squares overflow) still say they overflow; at 1e-150 (squares 1e-300, normal) neither.
#[test]
fn points_too_small_underflow_and_too_large_overflow() {
    use tmm::synthesis::{path_generator, PathOptions, PathRequirement, Timing};
    let points = |s: f64| -> Vec<[f64; 2]> {
        (0..9)
            .map(|i| {
                let t = f64::from(i) * 0.6;
                [s * (0.3 + 0.1 * t.cos()), s * (0.2 + 0.05 * t.sin())]
            })
            .collect()
    };
    let ask = |s: f64| {
        let req = PathRequirement {
            points: points(s),
            timing: Timing::Free,
        };
        let mut opts = PathOptions::default();
        opts.max_evaluations = 200;
        path_generator(&req, &opts, |_| true)
    };
    let small = ask(1e-300).unwrap_err().to_string();
    assert!(
        small.contains("underflows") && !small.contains("overflows"),
        "{small}"
    );
    let large = ask(1e160).unwrap_err().to_string();
    assert!(large.contains("overflows"), "{large}");
    if let Err(e) = ask(1e-150) {
        let e = e.to_string();
        assert!(!e.contains("flows"), "{e}");
    }
}
