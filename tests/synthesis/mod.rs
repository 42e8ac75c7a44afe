//! Synthesis round trips: every synthesised description is analysed by the engine, which must
//! find the requirement met (K, the stroke or swing, precision points, poses) to 1e-10
//! relative, and the reported γ_min; bad and infeasible requirements are errors that name
//! the parameter.

use std::f64::consts::PI;
use tmm::kinematics::{grashof, Grashof, Rotation};
use tmm::linkage::{Linkage, Output, Plan};
use tmm::synthesis::{
    crank_rocker, shaper, slider_crank, CrankRockerRequirement, FrameChoice, OffsetChoice, Options,
    ShaperRequirement, SliderCrankRequirement, Synthesis,
};
use tmm::Error;

mod burmester_close;
mod burmester_count;
mod burmester_degenerate;
mod burmester_far;
mod closed_form;
mod closed_form_review;
mod hostile_requirements;
mod link_ratio;
mod path;
mod pictures;
mod six_bar;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// The engine's smallest transmission angle over the groups with the crank at φ; `None`
/// where the linkage does not assemble there.
fn gamma_at(plan: &Plan, phi: f64) -> Option<f64> {
    let k = plan.kinematics(tmm::kinematics::Motion::fixed(phi)).ok()?;
    (0..plan.groups().len()).try_fold(f64::INFINITY, |m, g| {
        k.transmission_angle(g).ok().map(|x| m.min(x))
    })
}

/// A seeded xorshift generator of uniform numbers in [0, 1).
fn xorshift(mut x: u64) -> impl FnMut() -> f64 {
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn joint(l: &Linkage, name: &str) -> [f64; 2] {
    l.joints.iter().find(|j| j.name == name).unwrap().at
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

/// The hinges A and B of the four-bar (frame d, crank a, coupler b, rocker c) with O1 =
/// (0, 0), O3 = (d, 0) at the crank angle φ, by direct circle intersection (independent of
/// the engine), in the mode σ (B left of A→O3 for +1); `None` where it does not assemble.
fn hinges(d: f64, a: f64, b: f64, c: f64, sigma: f64, phi: f64) -> Option<([f64; 2], [f64; 2])> {
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    let (vx, vy) = (d - ax, -ay);
    let e = vx.hypot(vy);
    let along = (b * b - c * c + e * e) / (2.0 * e);
    let h2 = b * b - along * along;
    if h2 <= 0.0 {
        return None;
    }
    let (ux, uy) = (vx / e, vy / e);
    let h = sigma * h2.sqrt();
    Some((
        [ax, ay],
        [ax + along * ux - h * uy, ay + along * uy + h * ux],
    ))
}

/// The engine's K, stroke and γ_min (over every group) for `output` with a crank turning
/// counter-clockwise.
fn measured(s: &Synthesis, output: &Output) -> (f64, f64, f64) {
    let plan = Plan::new(&s.linkage).unwrap();
    let strokes = plan.strokes(output, Rotation::Ccw).unwrap();
    let gamma = (0..plan.groups().len())
        .map(|g| plan.min_transmission_angle(g).unwrap().0)
        .fold(f64::INFINITY, f64::min);
    (strokes.time_ratio, strokes.stroke, gamma)
}

/// The largest relative error of K, the stroke and γ_min against the requirement and the
/// report.
fn round_trip(s: &Synthesis, output: &Output, k: f64, stroke: f64) -> f64 {
    let (mk, ms, mg) = measured(s, output);
    let r = &s.report;
    // The engine's transmission angle where the report says γ_min occurs is γ_min.
    let plan = Plan::new(&s.linkage).unwrap();
    let at = gamma_at(&plan, r.min_transmission_at).unwrap();
    let errors = [
        rel(mk, k),
        rel(ms, stroke),
        rel(r.time_ratio.unwrap(), k),
        rel(r.stroke.unwrap(), stroke),
        rel(mg, r.min_transmission_angle),
        rel(at, r.min_transmission_angle),
    ];
    errors.into_iter().fold(0.0, f64::max)
}

#[test]
fn crank_rockers_meet_k_and_swing_through_the_engine() {
    let mut worst: f64 = 0.0;
    let mut cases = 0;
    let loose = Options::default().with_min_transmission_angle(0.0);
    for &k in &[1.05, 1.2, 1.4, 1.7] {
        for &swing_deg in &[20.0, 40.0, 60.0, 80.0] {
            let need = CrankRockerRequirement {
                rocker: 0.25,
                swing: f64::to_radians(swing_deg),
                time_ratio: k,
                frame: FrameChoice::BestTransmission,
            };
            let Ok(s) = crank_rocker(&need, &loose) else {
                continue;
            };
            let l = &s.linkage;
            let (d, a, b, c) = (
                dist(joint(l, "O1"), joint(l, "O3")),
                dist(joint(l, "O1"), joint(l, "A")),
                dist(joint(l, "A"), joint(l, "B")),
                dist(joint(l, "O3"), joint(l, "B")),
            );
            assert_eq!(grashof(d, a, b, c).unwrap(), Grashof::CrankRocker);
            assert_eq!(s.report.grashof, Some(Grashof::CrankRocker));
            assert!(rel(c, 0.25) < 1e-12);
            let e = round_trip(&s, &Output::Angle("rocker".into()), k, need.swing);
            assert!(e < 1e-10, "K {k} swing {swing_deg}: {e:e}");
            worst = worst.max(e);
            cases += 1;
            // A frame 10 % longer than the best one's, if it is feasible, is met exactly.
            let longer = CrankRockerRequirement {
                frame: FrameChoice::Length(1.1 * d),
                ..need
            };
            if let Ok(s2) = crank_rocker(&longer, &loose) {
                let l2 = &s2.linkage;
                assert!(rel(dist(joint(l2, "O1"), joint(l2, "O3")), 1.1 * d) < 1e-12);
                assert!(
                    s2.report.min_transmission_angle <= s.report.min_transmission_angle + 1e-12
                );
                let e = round_trip(&s2, &Output::Angle("rocker".into()), k, need.swing);
                assert!(e < 1e-10, "K {k} swing {swing_deg} longer frame: {e:e}");
                worst = worst.max(e);
                cases += 1;
            }
        }
    }
    assert!(cases >= 24, "{cases}");
    eprintln!("crank-rocker round trips: {cases} cases, worst relative error {worst:.2e}");
}

#[test]
fn the_best_frame_is_a_maximum_of_gamma_min() {
    // Frames near the best one's transmit worse (or no crank-rocker exists there).
    let need = CrankRockerRequirement {
        rocker: 0.3,
        swing: 0.8,
        time_ratio: 1.3,
        frame: FrameChoice::BestTransmission,
    };
    let loose = Options::default().with_min_transmission_angle(0.0);
    let best = crank_rocker(&need, &loose).unwrap();
    let d = best.report.dimension("frame").unwrap();
    for f in [0.9, 0.97, 0.995, 1.005, 1.03, 1.1] {
        let other = CrankRockerRequirement {
            frame: FrameChoice::Length(f * d),
            ..need
        };
        if let Ok(s) = crank_rocker(&other, &loose) {
            assert!(
                s.report.min_transmission_angle <= best.report.min_transmission_angle + 1e-9,
                "{f}"
            );
        }
    }
}

#[test]
fn slider_cranks_meet_k_and_stroke_through_the_engine() {
    let mut worst: f64 = 0.0;
    let mut cases = 0;
    let loose = Options::default().with_min_transmission_angle(0.0);
    for &k in &[1.05, 1.2, 1.5, 2.0, 2.6] {
        for &h in &[0.05, 0.2, 1.0] {
            let need = SliderCrankRequirement {
                stroke: h,
                time_ratio: k,
                offset: OffsetChoice::BestTransmission,
            };
            let s = slider_crank(&need, &loose).unwrap();
            let e = round_trip(&s, &Output::Slide("P".into()), k, h);
            assert!(e < 1e-10, "K {k} H {h}: {e:e}");
            worst = worst.max(e);
            cases += 1;
            let offset = s.report.dimension("offset").unwrap();
            for f in [0.5, 1.5] {
                let given = SliderCrankRequirement {
                    offset: OffsetChoice::Given(f * offset),
                    ..need
                };
                if let Ok(s2) = slider_crank(&given, &loose) {
                    assert!(rel(joint(&s2.linkage, "B")[1], f * offset) < 1e-12);
                    assert!(
                        s2.report.min_transmission_angle <= s.report.min_transmission_angle + 1e-12
                    );
                    let e = round_trip(&s2, &Output::Slide("P".into()), k, h);
                    assert!(e < 1e-10, "K {k} H {h} offset x{f}: {e:e}");
                    worst = worst.max(e);
                    cases += 1;
                }
            }
        }
    }
    assert!(cases >= 30, "{cases}");
    eprintln!("slider-crank round trips: {cases} cases, worst relative error {worst:.2e}");
}

#[test]
fn the_best_offset_is_a_maximum_of_gamma_min() {
    let loose = Options::default().with_min_transmission_angle(0.0);
    for k in [1.1, 1.4, 2.0] {
        let need = SliderCrankRequirement {
            stroke: 0.2,
            time_ratio: k,
            offset: OffsetChoice::BestTransmission,
        };
        let best = slider_crank(&need, &loose).unwrap();
        let e = best.report.dimension("offset").unwrap();
        for f in [0.8, 0.95, 0.999, 1.001, 1.05, 1.2] {
            let other = SliderCrankRequirement {
                offset: OffsetChoice::Given(f * e),
                ..need
            };
            if let Ok(s) = slider_crank(&other, &loose) {
                assert!(
                    s.report.min_transmission_angle <= best.report.min_transmission_angle + 1e-12,
                    "K {k} offset x{f}"
                );
            }
        }
    }
}

#[test]
fn shapers_meet_k_and_stroke_through_the_engine() {
    let mut worst: f64 = 0.0;
    let mut cases = 0;
    for &k in &[1.2, 1.5, 2.0, 3.0] {
        for &h in &[0.1, 0.4] {
            for &d in &[0.05, 0.15] {
                let need = ShaperRequirement {
                    stroke: h,
                    time_ratio: k,
                    centre_distance: d,
                };
                let Ok(s) = shaper(&need, &Options::default()) else {
                    continue;
                };
                let e = round_trip(&s, &Output::Slide("G".into()), k, h);
                assert!(e < 1e-10, "K {k} H {h} d {d}: {e:e}");
                worst = worst.max(e);
                cases += 1;
            }
        }
    }
    assert!(cases >= 10, "{cases}");
    eprintln!("shaper round trips: {cases} cases, worst relative error {worst:.2e}");
}

#[test]
fn bad_requirements_name_the_parameter() {
    let base = CrankRockerRequirement {
        rocker: 0.3,
        swing: 0.7,
        time_ratio: 1.3,
        frame: FrameChoice::BestTransmission,
    };
    let o = Options::default();
    let name = |r: tmm::Result<Synthesis>| match r {
        Err(
            Error::OutOfRange { name, .. }
            | Error::NonFinite { name, .. }
            | Error::NonPositive { name, .. },
        ) => name.to_owned(),
        Err(Error::Infeasible { parameter, .. }) => parameter.to_owned(),
        Err(e) => format!("other: {e}"),
        Ok(_) => "ok".to_owned(),
    };
    for (need, expected) in [
        (
            CrankRockerRequirement {
                time_ratio: 1.0,
                ..base
            },
            "K",
        ),
        (
            CrankRockerRequirement {
                time_ratio: 0.5,
                ..base
            },
            "K",
        ),
        (
            CrankRockerRequirement {
                time_ratio: f64::NAN,
                ..base
            },
            "K",
        ),
        (
            CrankRockerRequirement {
                time_ratio: 50.0,
                ..base
            },
            "K",
        ),
        (CrankRockerRequirement { swing: PI, ..base }, "swing"),
        (CrankRockerRequirement { swing: 0.0, ..base }, "swing"),
        (
            CrankRockerRequirement {
                swing: f64::INFINITY,
                ..base
            },
            "swing",
        ),
        (
            CrankRockerRequirement {
                rocker: -1.0,
                ..base
            },
            "rocker",
        ),
        (
            CrankRockerRequirement {
                frame: FrameChoice::Length(0.001),
                ..base
            },
            "frame length O1O3 (m)",
        ),
    ] {
        assert_eq!(name(crank_rocker(&need, &o)), expected, "{need:?}");
    }
    // γ_min unreachable: the error says the best reachable and by how much it misses.
    let strict = Options::default().with_min_transmission_angle(80f64.to_radians());
    match crank_rocker(&base, &strict) {
        Err(
            e @ Error::Infeasible {
                required,
                reachable,
                ..
            },
        ) => {
            let text = e.to_string();
            let head = "minimum transmission angle (rad) = 1.396 cannot be met";
            assert!(text.starts_with(head), "{text}");
            assert!(text.contains("misses by 0."), "{text}");
            let best = crank_rocker(&base, &o)
                .unwrap()
                .report
                .min_transmission_angle;
            assert!(rel(reachable, best) < 1e-12 && reachable < required);
        }
        other => panic!("{other:?}"),
    }
    // The K bound in the error is one the synthesis meets just below.
    if let Err(Error::OutOfRange { max, .. }) = crank_rocker(
        &CrankRockerRequirement {
            time_ratio: 50.0,
            ..base
        },
        &o.with_min_transmission_angle(0.0),
    ) {
        let below = CrankRockerRequirement {
            time_ratio: 1.0 + 0.999 * (max - 1.0),
            ..base
        };
        assert!(
            crank_rocker(&below, &o.with_min_transmission_angle(0.0)).is_ok(),
            "{max}"
        );
        // ... and not just above (for every swing tried, the bound is where feasibility ends).
        let above = CrankRockerRequirement {
            time_ratio: 1.0 + 1.001 * (max - 1.0),
            ..base
        };
        assert!(matches!(
            crank_rocker(&above, &o.with_min_transmission_angle(0.0)),
            Err(Error::OutOfRange { name: "K", .. })
        ));
    } else {
        panic!("K = 50 accepted");
    }
    let slider = SliderCrankRequirement {
        stroke: 0.2,
        time_ratio: 1.3,
        offset: OffsetChoice::Given(0.05),
    };
    let loose = o.with_min_transmission_angle(0.0);
    for (need, expected) in [
        (
            SliderCrankRequirement {
                time_ratio: 3.0,
                ..slider
            },
            "K",
        ),
        (
            SliderCrankRequirement {
                time_ratio: 1.0,
                ..slider
            },
            "K",
        ),
        (
            SliderCrankRequirement {
                offset: OffsetChoice::Given(0.0),
                ..slider
            },
            "offset",
        ),
        (
            SliderCrankRequirement {
                offset: OffsetChoice::Given(1.0),
                ..slider
            },
            "K",
        ),
        (
            SliderCrankRequirement {
                stroke: f64::NAN,
                ..slider
            },
            "stroke",
        ),
    ] {
        assert_eq!(name(slider_crank(&need, &loose)), expected, "{need:?}");
    }
    let sh = ShaperRequirement {
        stroke: 0.3,
        time_ratio: 1.5,
        centre_distance: 0.1,
    };
    for (need, expected) in [
        (
            ShaperRequirement {
                time_ratio: 4.0,
                ..sh
            },
            "minimum transmission angle (rad)",
        ),
        (
            ShaperRequirement {
                centre_distance: 2.0,
                ..sh
            },
            "centre distance O1O3 (m)",
        ),
        (
            ShaperRequirement {
                time_ratio: -1.0,
                ..sh
            },
            "K",
        ),
        (ShaperRequirement { stroke: 0.0, ..sh }, "stroke"),
    ] {
        assert_eq!(name(shaper(&need, &o)), expected, "{need:?}");
    }
    assert_eq!(
        name(crank_rocker(&base, &o.with_min_transmission_angle(2.0))),
        "min_transmission_angle"
    );
}

mod freudenstein {
    use super::*;
    use proptest::prelude::*;
    use tmm::kinematics::Motion;
    use tmm::synthesis::{
        crank_rocker_through, freudenstein_coefficients, function_generator, FunctionRequirement,
        Spacing,
    };

    /// The rocker angle ψ of the four-bar (d, a, b, c) at the crank angle φ in the mode σ.
    fn rocker_angle(d: f64, a: f64, b: f64, c: f64, sigma: f64, phi: f64) -> Option<f64> {
        hinges(d, a, b, c, sigma, phi).map(|(_, b)| b[1].atan2(b[0] - d))
    }

    proptest! {
        /// Freudenstein's equation holds at every position of random four-bars: a position
        /// (φ, ψ) of the pivots O1 = (0, 0), O3 = (d, 0) fixes the coupler b = |AB|, and the
        /// circle intersection of that four-bar in the position's mode gives ψ back.
        #[test]
        fn the_equation_holds_at_every_position(
            d in 0.05..1.0f64, a in 0.05..1.0f64, c in 0.05..1.0f64,
            phi in 0.0..std::f64::consts::TAU, psi in 0.0..std::f64::consts::TAU,
        ) {
            let (ax, ay) = (a * phi.cos(), a * phi.sin());
            let (bx, by) = (d + c * psi.cos(), c * psi.sin());
            let b = (bx - ax).hypot(by - ay);
            let cross = (d - ax) * (by - ay) - (-ay) * (bx - ax);
            if b < 1e-3 || cross.abs() < 1e-6 * b * (d - ax).hypot(ay) {
                return Ok(()); // (nearly) coincident hinges or a flat pose: no mode to speak of
            }
            let sigma = cross.signum();
            let back = rocker_angle(d, a, b, c, sigma, phi).unwrap();
            prop_assert!((back - psi).sin().abs() < 1e-9 && (back - psi).cos() > 0.0);
            let k = freudenstein_coefficients(d, a, b, c).unwrap();
            let lhs = k[0] * psi.cos() - k[1] * phi.cos() + k[2];
            let scale = 1.0 + k.iter().map(|x| x.abs()).sum::<f64>();
            prop_assert!((lhs - (phi - psi).cos()).abs() < 1e-12 * scale, "{} vs {}", lhs, (phi - psi).cos());
        }

        /// Three positions of a random crank-rocker give that crank-rocker back, and the engine
        /// passes through them.
        #[test]
        fn three_positions_of_a_crank_rocker_give_it_back(
            d in 0.3..1.0f64, a in 0.05..0.12f64, b in 0.3..1.0f64, c in 0.3..1.0f64,
            plus in any::<bool>(), phi0 in 0.0..std::f64::consts::TAU, step in 0.3..1.5f64,
        ) {
            prop_assume!(grashof(d, a, b, c).unwrap() == Grashof::CrankRocker);
            let sigma = if plus { 1.0 } else { -1.0 };
            let pairs: Vec<(f64, f64)> = (0..3)
                .map(|i| {
                    let phi = phi0 + step * f64::from(i);
                    (phi, rocker_angle(d, a, b, c, sigma, phi).unwrap())
                })
                .collect();
            let loose = Options::default().with_min_transmission_angle(0.0);
            let s = crank_rocker_through(d, &pairs, &loose);
            prop_assume!(!matches!(s, Err(Error::Singular { .. })));
            let s = s.unwrap();
            for (name, want) in [("crank", a), ("coupler", b), ("rocker", c)] {
                prop_assert!(rel(s.report.dimension(name).unwrap(), want) < 1e-9, "{}", name);
            }
            let plan = Plan::new(&s.linkage).unwrap();
            for &(phi, psi) in &pairs {
                let got = plan.output(&Output::Angle("rocker".into()), Motion::fixed(phi)).unwrap().value;
                let diff = (got - psi).sin().abs();
                prop_assert!(diff < 1e-10, "{}", diff);
            }
        }
    }

    #[test]
    fn a_position_in_the_other_assembly_mode_is_a_branch_defect() {
        // Freudenstein's equation does not see the mode: three positions of one crank-rocker,
        // the third in its mirror mode, give the same lengths, and the answer is refused.
        let (d, a, b, c) = (0.4, 0.1, 0.35, 0.3);
        let pairs = [
            (0.5, rocker_angle(d, a, b, c, 1.0, 0.5).unwrap()),
            (1.5, rocker_angle(d, a, b, c, 1.0, 1.5).unwrap()),
            (2.5, rocker_angle(d, a, b, c, -1.0, 2.5).unwrap()),
        ];
        let o = Options::default().with_min_transmission_angle(0.0);
        let e = crank_rocker_through(d, &pairs, &o).unwrap_err();
        assert!(e.to_string().contains("branch defect"), "{e}");
        // All three in one mode: accepted, the lengths back.
        let pairs = [
            pairs[0],
            pairs[1],
            (2.5, rocker_angle(d, a, b, c, 1.0, 2.5).unwrap()),
        ];
        let s = crank_rocker_through(d, &pairs, &o).unwrap();
        assert!(rel(s.report.dimension("coupler").unwrap(), b) < 1e-12);
    }

    /// Two positions of a known crank-rocker always give a crank-rocker through them, even
    /// where the crank ratios a/d that do so form a stretch narrower than the search's scan
    /// step (this one: about 5e-5 wide, the step 2.4e-4; it was refused).
    #[test]
    fn two_positions_on_a_narrow_stretch_of_the_crank_ratio_are_found() {
        let (d, a, b, c) = (
            1.0,
            0.207_130_318_904_277_74,
            1.415_638_452_260_869_4,
            0.815_487_492_197_035_6,
        );
        let pairs = [93.183_703_779_192_f64, 266.825_609_644_362_15].map(|deg| {
            let phi = deg.to_radians();
            (phi, rocker_angle(d, a, b, c, 1.0, phi).unwrap())
        });
        // The rocker angles the report that found it gave (69.11074167595777°, 92.21931443964895°).
        assert!((pairs[0].1.to_degrees() - 69.110_741_675_957_77).abs() < 1e-9);
        assert!((pairs[1].1.to_degrees() - 92.219_314_439_648_95).abs() < 1e-9);
        let loose = Options::default().with_min_transmission_angle(0.0);
        let s = crank_rocker_through(d, &pairs, &loose).unwrap();
        let plan = Plan::new(&s.linkage).unwrap();
        for &(phi, psi) in &pairs {
            let got = plan
                .output(&Output::Angle("rocker".into()), Motion::fixed(phi))
                .unwrap()
                .value;
            assert!((got - psi).sin().abs() < 1e-10, "{got} vs {psi}");
        }
        assert!(s.report.min_transmission_angle > 0.0);
    }

    #[test]
    fn two_positions_leave_the_crank_ratio_for_the_best_transmission() {
        let deg = f64::to_radians;
        let pairs = [(deg(40.0), deg(101.4)), (deg(160.0), deg(131.8))];
        let loose = Options::default().with_min_transmission_angle(0.0);
        let s = crank_rocker_through(0.5, &pairs, &loose).unwrap();
        let plan = Plan::new(&s.linkage).unwrap();
        let mut worst: f64 = 0.0;
        for &(phi, psi) in &pairs {
            let got = plan
                .output(&Output::Angle("rocker".into()), Motion::fixed(phi))
                .unwrap()
                .value;
            worst = worst.max((got - tmm::angle::normalize(psi)).abs() / psi.abs());
        }
        assert!(worst < 1e-10, "{worst:e}");
        let (gamma, _) = plan.min_transmission_angle(0).unwrap();
        assert!(rel(gamma, s.report.min_transmission_angle) < 1e-10);
        // The engine's K and swing are the report's.
        let st = plan
            .strokes(&Output::Angle("rocker".into()), Rotation::Ccw)
            .unwrap();
        assert!(rel(st.time_ratio, s.report.time_ratio.unwrap()) < 1e-10);
        assert!(rel(st.stroke, s.report.stroke.unwrap()) < 1e-10);
    }

    /// x in [1, 2], the crank from −30° to 30°, the rocker through 90° from `rocker` degrees.
    fn need(rocker: f64, spacing: Spacing) -> FunctionRequirement {
        let deg = f64::to_radians;
        FunctionRequirement {
            x_range: [1.0, 2.0],
            crank_range: [deg(-30.0), deg(30.0)],
            rocker_range: [deg(rocker), deg(rocker + 90.0)],
            frame: 0.1,
            spacing,
        }
    }

    /// A function's name, the function and the rocker's first angle in degrees.
    type Case = (&'static str, fn(f64) -> f64, f64);

    fn log_need(spacing: Spacing) -> FunctionRequirement {
        need(0.0, spacing)
    }

    #[test]
    fn function_generators_are_exact_at_the_precision_points() {
        let loose = Options::default().with_min_transmission_angle(0.0);
        let fns: [Case; 5] = [
            ("log10", f64::log10, 0.0),
            ("x^2", |x| x * x, 270.0),
            ("sqrt", f64::sqrt, 345.0),
            ("exp", f64::exp, 255.0),
            ("1/x", |x| 1.0 / x, 15.0),
        ];
        let mut worst: f64 = 0.0;
        let mut cases = 0;
        for (name, f, rocker) in fns {
            let g = function_generator(f, &need(rocker, Spacing::Chebyshev), &loose).unwrap();
            let plan = Plan::new(&g.synthesis.linkage).unwrap();
            for &x in &g.precision_x {
                let got = plan
                    .output(
                        &Output::Angle("rocker".into()),
                        Motion::fixed(g.crank_angle(x)),
                    )
                    .unwrap()
                    .value;
                let want = tmm::angle::normalize(g.rocker_angle(f(x)));
                let e = (got - want).abs() / want;
                assert!(e < 1e-10, "{name} at {x}: {e:e}");
                worst = worst.max(e);
                cases += 1;
            }
            // The structural error vanishes at the precision points (sign changes around them)
            // and is the engine's at the ends.
            let curve = g.structural_error(f, 1001).unwrap();
            let signs: Vec<bool> = curve
                .iter()
                .filter(|p| p.error.abs() > 1e-12)
                .map(|p| p.error > 0.0)
                .collect();
            let changes = signs.windows(2).filter(|w| w[0] != w[1]).count();
            assert!(changes >= 3, "{name}: {changes}");
            // Least squares over three points is the exact solution.
            let ls =
                function_generator(f, &need(rocker, Spacing::LeastSquares(3)), &loose).unwrap();
            for (p, q) in ls.coefficients.iter().zip(g.coefficients) {
                assert!(rel(*p, q) < 1e-9);
            }
        }
        assert_eq!(cases, 15);
        eprintln!(
            "function generators: {cases} precision points, worst relative error {worst:.2e}"
        );
    }

    #[test]
    fn least_squares_beats_no_fit_and_spreads_the_error() {
        let loose = Options::default().with_min_transmission_angle(0.0);
        let exact = function_generator(f64::log10, &log_need(Spacing::Chebyshev), &loose).unwrap();
        let ls =
            function_generator(f64::log10, &log_need(Spacing::LeastSquares(25)), &loose).unwrap();
        let worst = |g: &tmm::synthesis::FunctionGenerator| {
            g.structural_error(f64::log10, 501)
                .unwrap()
                .iter()
                .map(|p| p.error.abs())
                .fold(0.0, f64::max)
        };
        let (we, wl) = (worst(&exact), worst(&ls));
        // Both small against the range of y (log10 2 ≈ 0.3).
        assert!(we < 0.01 && wl < 0.01, "{we} {wl}");
        // Fitting 25 points instead of passing through three lowers the worst structural
        // error over the range (3.56e-3 against 3.64e-3 when written).
        assert!(wl < we, "least squares {wl:e}, three exact points {we:e}");
        // It spreads the error: the fitted curve crosses the wanted one (the error changes
        // sign) at least as often as the three-point one, which crosses at its three points
        // (on a grid of 500, which misses them: at a grid point the error is rounding).
        let crossings = |g: &tmm::synthesis::FunctionGenerator| {
            let e = g.structural_error(f64::log10, 500).unwrap();
            e.windows(2)
                .filter(|w| w[0].error * w[1].error < 0.0)
                .count()
        };
        let (ce, cl) = (crossings(&exact), crossings(&ls));
        assert!(ce == 3 && cl >= 3, "{ce} {cl}");
    }

    /// The generated y at x is the engine's rocker angle followed by continuity from x0,
    /// mapped to y, whatever f is: so the structural error of f + c/(x − π/2) (a pole in the
    /// range) is that of f minus c/(x − π/2), exactly, at every sample, however large. Compared
    /// mod 2π it was capped at half a rocker turn (−π·dy/dψ). A design asked of tan on [1, 2]
    /// itself is refused: Freudenstein's equation meets its middle point a whole rocker turn
    /// away (tan 1.5 = 14.1, far outside [tan 1, tan 2]).
    #[test]
    fn a_pole_in_the_range_shows_its_whole_structural_error() {
        use tmm::synthesis::{function_generator, FunctionRequirement, Options, Spacing};
        let need = FunctionRequirement {
            x_range: [1.0, 2.0],
            crank_range: [(-30f64).to_radians(), 30f64.to_radians()],
            rocker_range: [0.0, 90f64.to_radians()],
            frame: 0.1,
            spacing: Spacing::Chebyshev,
        };
        let loose = Options::default().with_min_transmission_angle(0.0);
        let g = function_generator(f64::log10, &need, &loose).unwrap();
        let c = 1e-3;
        let pole = |x: f64| c / (x - PI / 2.0);
        let plain = g.structural_error(f64::log10, 1000).unwrap();
        let with_pole = g.structural_error(|x| x.log10() + pole(x), 1000).unwrap();
        let half_turn = PI * 2f64.log10() / (PI / 2.0);
        let mut largest = 0.0f64;
        for (p, q) in plain.iter().zip(&with_pole) {
            let expected = p.error - pole(p.x);
            assert!(
                (q.error - expected).abs() <= 1e-9 * expected.abs().max(1.0),
                "at x = {}: {} against {expected}",
                p.x,
                q.error
            );
            largest = largest.max(q.error.abs());
        }
        assert!(largest > 4.0 * half_turn, "{largest} against {half_turn}");
        let e = function_generator(f64::tan, &need, &loose)
            .unwrap_err()
            .to_string();
        assert!(e.contains("rocker turn") && e.contains("x = 1.5"), "{e}");
        // Refused outside the range, where the continuity is not followed.
        let outside = g.structural_error_at(f64::log10, &[2.5]).unwrap_err();
        assert!(outside.to_string().contains("x = 2.5"), "{outside}");
    }

    #[test]
    fn bad_function_requirements_name_the_parameter() {
        let o = Options::default().with_min_transmission_angle(0.0);
        let n2 = function_generator(f64::log10, &log_need(Spacing::LeastSquares(2)), &o);
        assert!(
            matches!(n2, Err(Error::OutOfRange { name: "N", .. })),
            "{n2:?}"
        );
        let nan = FunctionRequirement {
            x_range: [f64::NAN, 2.0],
            ..log_need(Spacing::Chebyshev)
        };
        assert!(matches!(
            function_generator(f64::log10, &nan, &o),
            Err(Error::NonFinite { name: "x0", .. })
        ));
        let same = FunctionRequirement {
            x_range: [1.0, 1.0],
            ..log_need(Spacing::Chebyshev)
        };
        assert!(matches!(
            function_generator(f64::log10, &same, &o),
            Err(Error::NoMechanism { .. })
        ));
        let flat = function_generator(|_| 1.0, &log_need(Spacing::Chebyshev), &o);
        assert!(matches!(flat, Err(Error::NoMechanism { .. })), "{flat:?}");
        let bad_f = function_generator(
            |x| if x > 1.5 { f64::NAN } else { x },
            &log_need(Spacing::Chebyshev),
            &o,
        );
        assert!(matches!(bad_f, Err(Error::NonFinite { .. })), "{bad_f:?}");
        // Positions: too few, too many, coinciding.
        let p = [(0.1, 1.0), (0.5, 1.2), (0.9, 1.1), (1.3, 1.0)];
        assert!(matches!(
            crank_rocker_through(0.4, &p[..1], &o),
            Err(Error::OutOfRange {
                name: "positions",
                ..
            })
        ));
        assert!(matches!(
            crank_rocker_through(0.4, &p, &o),
            Err(Error::OutOfRange {
                name: "positions",
                ..
            })
        ));
        let twice = [(0.1, 1.0), (0.1 + std::f64::consts::TAU, 1.2), (0.9, 1.1)];
        let e = crank_rocker_through(0.4, &twice, &o).unwrap_err();
        assert!(e.to_string().contains("coincide"), "{e}");
        assert!(matches!(
            crank_rocker_through(f64::INFINITY, &p[..3], &o),
            Err(Error::NonFinite { name: "frame", .. })
        ));
    }
}

mod burmester {
    use super::*;
    use proptest::prelude::*;
    use tmm::kinematics::Motion;
    use tmm::synthesis::{
        burmester, centre_point, centre_point_curve, centre_point_two, circle_point,
        four_bar_from_dyads, Dyad, Pose,
    };

    /// The largest miss of the engine's coupler against the poses: |P − P_j| relative to the
    /// linkage's size, and the angle's.
    fn miss(s: &Synthesis, poses: &[Pose], crank: &Dyad) -> f64 {
        let plan = Plan::new(&s.linkage).unwrap();
        let size = s
            .linkage
            .joints
            .iter()
            .map(|j| j.at[0].hypot(j.at[1]))
            .fold(0.0, f64::max);
        poses
            .iter()
            .zip(crank.angles(poses))
            .map(|(pose, phi)| {
                let k = plan.kinematics(Motion::fixed(phi)).unwrap();
                let p = k.point("P").unwrap().p;
                let dp = (p.x - pose.at[0]).hypot(p.y - pose.at[1]) / size;
                let turn = k.link("coupler").unwrap().value - pose.angle;
                dp.max(turn.sin().abs())
            })
            .fold(0.0, f64::max)
    }

    fn pose() -> impl Strategy<Value = Pose> {
        (-0.3..0.3f64, -0.3..0.3f64, -1.0..1.0f64).prop_map(|(x, y, a)| Pose::new([x, y], a))
    }

    fn point() -> impl Strategy<Value = [f64; 2]> {
        (-0.5..0.5f64, -0.5..0.5f64).prop_map(|(x, y)| [x, y])
    }

    proptest! {
        /// The circle point of a dyad's centre point is the dyad's circle point.
        #[test]
        fn circle_point_inverts_centre_point(p in [pose(), pose(), pose()], z in point()) {
            let Ok(dyad) = centre_point(&p, z) else { return Ok(()) };
            let back = circle_point(&p, dyad.centre);
            prop_assume!(back.is_ok());
            let back = back.unwrap();
            let scale = 1.0 + dyad.length() + dyad.centre[0].hypot(dyad.centre[1]);
            prop_assume!(scale < 1e3);
            prop_assert!((back.circle[0] - z[0]).hypot(back.circle[1] - z[1]) < 1e-9 * scale);
        }
    }

    /// The four-bar of two dyads as drawn in the first pose, without any check.
    fn drawn(first: &Pose, crank: &Dyad, rocker: &Dyad) -> Linkage {
        use tmm::linkage::{Input, Joint, Link};
        let q = [
            first.at[0] + 0.1 * first.angle.cos(),
            first.at[1] + 0.1 * first.angle.sin(),
        ];
        let coupler = Link {
            reference: Some(["P".to_owned(), "Q".to_owned()]),
            ..Link::new("coupler", &["A", "B"])
                .with_point("P", first.at)
                .with_point("Q", q)
        };
        Linkage {
            joints: vec![
                Joint::revolute("O1", crank.centre),
                Joint::revolute("A", crank.circle),
                Joint::revolute("B", rocker.circle),
                Joint::revolute("O3", rocker.centre),
            ],
            links: vec![
                Link::new("frame", &["O1", "O3"]),
                Link::new("crank", &["O1", "A"]),
                coupler,
                Link::new("rocker", &["O3", "B"]),
            ],
            input: Input::crank("crank"),
            ..Linkage::default()
        }
    }

    #[test]
    fn three_pose_four_bars_meet_their_poses_through_the_engine() {
        // A seeded generator of three poses and two circle points; the cases without a branch
        // or an order defect are analysed by the engine.
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let loose = Options::default().with_min_transmission_angle(0.0);
        let (mut worst, mut cases, mut defects): (f64, usize, usize) = (0.0, 0, 0);
        let (mut branch, mut order) = (0, 0);
        for _ in 0..400 {
            let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
            let poses = [
                Pose::new([0.0, 0.0], 0.0),
                Pose::new([r(0.02, 0.15), r(-0.05, 0.1)], r(-0.6, 0.6)),
                Pose::new([r(0.1, 0.3), r(-0.05, 0.15)], r(-1.0, 1.0)),
            ];
            let za = [r(-0.2, 0.0), r(-0.2, 0.0)];
            let zb = [r(0.05, 0.3), r(-0.2, 0.0)];
            match burmester(&poses, za, zb, &loose) {
                Ok(s) => {
                    let crank = centre_point(&poses, za).unwrap();
                    let e = miss(&s, &poses, &crank);
                    assert!(e < 1e-10, "{poses:?} {za:?} {zb:?}: {e:e}");
                    worst = worst.max(e);
                    cases += 1;
                }
                Err(Error::NoMechanism { problem, .. }) => {
                    defects += 1;
                    // A defect is real: the four-bar as drawn in pose 1 (the engine keeps its
                    // assembly mode) misses a pose (branch), or cannot move between them
                    // (order).
                    let crank = centre_point(&poses, za).unwrap();
                    let rocker = centre_point(&poses, zb).unwrap();
                    let l = drawn(&poses[0], &crank, &rocker);
                    let Ok(plan) = Plan::new(&l) else { continue };
                    let phis = crank.angles(&poses);
                    let reaches = |phi: f64, pose: &Pose| {
                        plan.kinematics(Motion::fixed(phi)).is_ok_and(|k| {
                            let p = k.point("P").unwrap().p;
                            let turn = k.link("coupler").unwrap().value - pose.angle;
                            dist([p.x, p.y], pose.at) < 1e-8 && turn.sin().abs() < 1e-8
                        })
                    };
                    if problem.starts_with("branch defect") {
                        assert!(
                            !poses
                                .iter()
                                .zip(&phis)
                                .all(|(pose, &phi)| reaches(phi, pose)),
                            "{problem}: the engine reaches every pose"
                        );
                        branch += 1;
                    } else if problem.starts_with("order defect") {
                        // Along both arcs from the first pose's crank angle to the last's,
                        // through the middle one or not: one of them fails to assemble or
                        // skips the middle pose.
                        let through = |start: f64, span: f64| {
                            (0..=400).all(|i| {
                                let phi = start + span * f64::from(i) / 400.0;
                                plan.kinematics(Motion::fixed(phi)).is_ok()
                            })
                        };
                        let ccw = (phis[2] - phis[0]).rem_euclid(std::f64::consts::TAU);
                        let mid = (phis[1] - phis[0]).rem_euclid(std::f64::consts::TAU);
                        let arc = if mid < ccw {
                            (phis[0], ccw)
                        } else {
                            (phis[2], std::f64::consts::TAU - ccw)
                        };
                        assert!(
                            !through(arc.0, arc.1),
                            "{problem}: the engine moves through the poses"
                        );
                        order += 1;
                    }
                }
                Err(Error::Singular { .. }) => defects += 1,
                Err(e) => panic!("{e}"),
            }
        }
        assert!(
            branch >= 10 && order >= 10,
            "{branch} branch, {order} order defects"
        );
        assert!(cases >= 100, "{cases} ({defects} defects)");
        eprintln!(
            "Burmester three poses: {cases} four-bars, worst miss {worst:.2e} ({defects} with a defect: {branch} branch, {order} order confirmed by the engine)"
        );
    }

    #[test]
    fn the_inverted_construction_gives_the_same_four_bar() {
        let poses = [
            Pose::new([0.0, 0.0], 0.0),
            Pose::new([0.1, 0.05], 0.3),
            Pose::new([0.2, 0.05], 0.7),
        ];
        let loose = Options::default().with_min_transmission_angle(0.0);
        // Centre points chosen, circle points found.
        let crank = circle_point(&poses, [-0.1, -0.2]).unwrap();
        let rocker = circle_point(&poses, [0.3, -0.2]).unwrap();
        let s = four_bar_from_dyads(&poses, &crank, &rocker, &loose).unwrap();
        assert!(miss(&s, &poses, &crank) < 1e-10);
        let (gamma, _) = Plan::new(&s.linkage)
            .unwrap()
            .min_transmission_angle(0)
            .map_or((s.report.min_transmission_angle, 0.0), |g| g);
        if s.report.grashof.unwrap().input_turns_fully() {
            assert!(rel(gamma, s.report.min_transmission_angle) < 1e-10);
        }
    }

    #[test]
    fn two_poses_put_the_centre_points_on_the_bisectors() {
        let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.15, 0.05], 0.5)];
        let loose = Options::default().with_min_transmission_angle(0.0);
        let mut cases = 0;
        for along in [-0.3, -0.1, 0.1, 0.3] {
            let crank = centre_point_two(&poses, [-0.05, -0.1], along).unwrap();
            let rocker = centre_point_two(&poses, [0.12, -0.08], -along).unwrap();
            if let Ok(s) = four_bar_from_dyads(&poses, &crank, &rocker, &loose) {
                assert!(miss(&s, &poses, &crank) < 1e-10);
                cases += 1;
            }
        }
        assert!(cases >= 1);
    }

    #[test]
    fn bad_poses_are_named() {
        let p = Pose::new([0.1, 0.2], 0.3);
        let coincide = centre_point(&[p, p, Pose::new([0.3, 0.0], 0.0)], [0.0, 0.0]);
        assert!(
            matches!(&coincide, Err(Error::NoMechanism { problem, .. }) if problem.contains("poses 1 and 2")),
            "{coincide:?}"
        );
        let nan = centre_point(
            &[
                p,
                Pose::new([f64::NAN, 0.0], 0.0),
                Pose::new([0.3, 0.0], 0.0),
            ],
            [0.0, 0.0],
        );
        assert!(matches!(nan, Err(Error::NonFinite { name: "pose x", .. })));
        // Pure translations along x: every point moves along a line, the centre at infinity.
        let line = [
            Pose::new([0.0, 0.0], 0.0),
            Pose::new([0.1, 0.0], 0.0),
            Pose::new([0.3, 0.0], 0.0),
        ];
        assert!(matches!(
            centre_point(&line, [0.0, 0.1]),
            Err(Error::Singular { .. })
        ));
        let loose = Options::default();
        let one = four_bar_from_dyads(
            &[p],
            &Dyad {
                centre: [0.0, 0.0],
                circle: [0.1, 0.0],
            },
            &Dyad {
                centre: [0.4, 0.0],
                circle: [0.3, 0.3],
            },
            &loose,
        );
        assert!(matches!(one, Err(Error::OutOfRange { name: "poses", .. })));
        // A dyad that does not fit the poses.
        let poses = [Pose::new([0.0, 0.0], 0.0), Pose::new([0.1, 0.05], 0.3)];
        let wrong = four_bar_from_dyads(
            &poses,
            &Dyad {
                centre: [0.0, -0.3],
                circle: [0.0, -0.1],
            },
            &Dyad {
                centre: [0.4, -0.3],
                circle: [0.3, -0.1],
            },
            &loose,
        );
        assert!(
            matches!(&wrong, Err(Error::NoMechanism { problem, .. }) if problem.contains("does not fit")),
            "{wrong:?}"
        );
    }

    #[test]
    fn four_poses_from_the_centre_point_curve() {
        let poses = [
            Pose::new([0.0, 0.0], 0.0),
            Pose::new([0.1, 0.05], 0.3),
            Pose::new([0.2, 0.05], 0.7),
            Pose::new([0.28, 0.0], 1.0),
        ];
        let dyads = centre_point_curve(&poses, 120).unwrap();
        assert!(dyads.len() >= 40, "{}", dyads.len());
        // Every sampled dyad fits the four poses; the curve's centre points are also the
        // three-pose construction's for their circle points.
        for d in &dyads {
            assert!(d.misfit(&poses) < 1e-9 * (1.0 + d.length()), "{d:?}");
            let three = [poses[0], poses[1], poses[2]];
            if let Ok(c) = centre_point(&three, d.circle) {
                let scale = 1.0 + d.length();
                assert!(
                    (c.centre[0] - d.centre[0]).hypot(c.centre[1] - d.centre[1]) < 1e-7 * scale
                );
            }
        }
        // Pairs of dyads of moderate size make four-bars through the four poses.
        let small: Vec<&Dyad> = dyads
            .iter()
            .filter(|d| d.length() < 1.0 && d.centre[0].hypot(d.centre[1]) < 1.5)
            .collect();
        let loose = Options::default().with_min_transmission_angle(0.0);
        let (mut worst, mut cases): (f64, usize) = (0.0, 0);
        for (i, crank) in small.iter().enumerate() {
            for rocker in small.iter().skip(i + 1).step_by(3) {
                if let Ok(s) = four_bar_from_dyads(&poses, crank, rocker, &loose) {
                    let e = miss(&s, &poses, crank);
                    assert!(e < 1e-10, "{crank:?} {rocker:?}: {e:e}");
                    worst = worst.max(e);
                    cases += 1;
                }
            }
        }
        assert!(cases >= 5, "{cases} of {} small dyads", small.len());
        eprintln!("Burmester four poses: {} dyads on the curve, {cases} four-bars, worst miss {worst:.2e}", dyads.len());
    }
}

/// Hostile requirements: any numbers (huge, tiny, zero, negative, NaN, infinite) give an
/// answer whose every number is finite, or an error — never a panic.
mod hostile {
    use super::*;
    use proptest::prelude::*;
    use tmm::synthesis::{
        burmester, centre_point_curve, crank_rocker_through, function_generator,
        FunctionRequirement, Pose, Spacing,
    };

    fn wild() -> impl Strategy<Value = f64> {
        prop_oneof![
            -1e300..1e300f64,
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(0.0),
            1e-300..1e-290f64,
            -10.0..10.0f64,
            0.0..4.0f64,
            1.0..3.0f64,
        ]
    }

    fn finite_answer(r: &tmm::Result<Synthesis>) -> bool {
        match r {
            Err(e) => !e.to_string().is_empty(),
            Ok(s) => {
                let rep = &s.report;
                s.linkage
                    .joints
                    .iter()
                    .all(|j| j.at.iter().all(|x| x.is_finite()))
                    && rep.time_ratio.is_none_or(f64::is_finite)
                    && rep.stroke.is_none_or(f64::is_finite)
                    && (0.0..=std::f64::consts::FRAC_PI_2).contains(&rep.min_transmission_angle)
                    && rep.min_transmission_at.is_finite()
                    && rep
                        .dimensions
                        .iter()
                        .all(|(_, x)| x.is_finite() && *x > 0.0)
                    && Plan::new(&s.linkage).is_ok()
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]

        #[test]
        fn quick_return(x in [wild(), wild(), wild(), wild()], given in any::<bool>(), g in wild()) {
            let o = Options::default().with_min_transmission_angle(g.clamp(0.0, 1.0));
            let frame = if given { FrameChoice::Length(x[3]) } else { FrameChoice::BestTransmission };
            let r = crank_rocker(&CrankRockerRequirement { rocker: x[0], swing: x[1], time_ratio: x[2], frame }, &o);
            prop_assert!(finite_answer(&r), "{:?}", r);
            let offset = if given { OffsetChoice::Given(x[3]) } else { OffsetChoice::BestTransmission };
            let r = slider_crank(&SliderCrankRequirement { stroke: x[0], time_ratio: x[2], offset }, &o);
            prop_assert!(finite_answer(&r), "{:?}", r);
            let r = shaper(&ShaperRequirement { stroke: x[0], time_ratio: x[2], centre_distance: x[3] }, &o);
            prop_assert!(finite_answer(&r), "{:?}", r);
        }

        #[test]
        fn freudenstein(x in proptest::collection::vec(wild(), 11), n in 0usize..8) {
            let o = Options::default().with_min_transmission_angle(0.0);
            let pairs = [(x[0], x[1]), (x[2], x[3]), (x[4], x[5])];
            let r = crank_rocker_through(x[6], &pairs[..n.clamp(0, 3)], &o);
            prop_assert!(finite_answer(&r), "{:?}", r);
            let need = FunctionRequirement {
                x_range: [x[0], x[1]],
                crank_range: [x[2], x[3]],
                rocker_range: [x[4], x[5]],
                frame: x[6],
                spacing: if n < 4 { Spacing::Chebyshev } else { Spacing::LeastSquares(n) },
            };
            let r = function_generator(|t| t.sin() + x[7] * t, &need, &o);
            if let Ok(g) = &r {
                let curve = g.structural_error(|t| t.sin() + x[7] * t, 17);
                if let Ok(c) = curve {
                    prop_assert!(c.iter().all(|p| p.error.is_finite() && p.generated.is_finite()));
                }
            }
            prop_assert!(finite_answer(&r.map(|g| g.synthesis)));
        }

        #[test]
        fn motion(x in proptest::collection::vec(wild(), 16)) {
            let o = Options::default().with_min_transmission_angle(0.0);
            let poses = [
                Pose::new([x[0], x[1]], x[2]),
                Pose::new([x[3], x[4]], x[5]),
                Pose::new([x[6], x[7]], x[8]),
            ];
            let r = burmester(&poses, [x[9], x[10]], [x[11], x[12]], &o);
            prop_assert!(finite_answer(&r), "{:?}", r);
            let four = [poses[0], poses[1], poses[2], Pose::new([x[13], x[14]], x[15])];
            if let Ok(dyads) = centre_point_curve(&four, 16) {
                prop_assert!(dyads.iter().all(|d| d.centre.iter().chain(&d.circle).all(|v| v.is_finite())));
            }
        }
    }
}

mod five_poses {
    use super::*;
    use tmm::kinematics::Motion;
    use tmm::synthesis::{burmester_points, four_bar_from_dyads, Dyad, Pose};

    #[test]
    fn a_four_bars_own_dyads_are_among_burmesters_points() {
        // Five poses of the coupler of random crank-rockers (a coupler point off AB): both of
        // its dyads come back, and the four-bar made of them passes through the five poses.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let loose = Options::default().with_min_transmission_angle(0.0);
        let (mut cases, mut worst): (usize, f64) = (0, 0.0);
        for _ in 0..40 {
            let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
            let (d, a, b, c) = (r(0.3, 0.6), r(0.05, 0.12), r(0.3, 0.6), r(0.25, 0.6));
            if grashof(d, a, b, c).unwrap() != Grashof::CrankRocker {
                continue;
            }
            let (along, off) = (r(0.2, 0.8), r(-0.2, 0.2));
            let start = r(0.0, 6.0);
            let phis: Vec<f64> = (0..5)
                .map(|k| start + 0.45 * f64::from(k) + r(0.0, 0.3))
                .collect();
            let pose_of = |phi: f64| {
                let (pa, pb) = hinges(d, a, b, c, 1.0, phi).unwrap();
                let (ux, uy) = ((pb[0] - pa[0]) / b, (pb[1] - pa[1]) / b);
                Pose::new(
                    [
                        pa[0] + along * b * ux - off * uy,
                        pa[1] + along * b * uy + off * ux,
                    ],
                    uy.atan2(ux),
                )
            };
            let poses: [Pose; 5] = std::array::from_fn(|k| pose_of(phis[k]));
            let points = burmester_points(&poses).unwrap();
            let (a1, b1) = hinges(d, a, b, c, 1.0, phis[0]).unwrap();
            let crank = Dyad {
                centre: [0.0, 0.0],
                circle: a1,
            };
            let rocker = Dyad {
                centre: [d, 0.0],
                circle: b1,
            };
            for own in [crank, rocker] {
                let found = points.iter().any(|p| {
                    dist(p.centre, own.centre) < 1e-7 && dist(p.circle, own.circle) < 1e-7
                });
                assert!(found, "{own:?} not among {points:?}; poses {poses:?}");
            }
            let s = four_bar_from_dyads(&poses, &crank, &rocker, &loose).unwrap();
            let plan = Plan::new(&s.linkage).unwrap();
            for (pose, phi) in poses.iter().zip(crank.angles(&poses)) {
                let k = plan.kinematics(Motion::fixed(phi)).unwrap();
                let p = k.point("P").unwrap().p;
                let e = dist([p.x, p.y], pose.at)
                    .max((k.link("coupler").unwrap().value - pose.angle).sin().abs());
                worst = worst.max(e);
            }
            cases += 1;
        }
        assert!(cases >= 10, "{cases}");
        assert!(worst < 1e-10, "{worst:e}");
        eprintln!("Burmester five poses: {cases} four-bars recovered, worst miss {worst:.2e}");
    }
}

/// Every kind's description survives JSON (the format of `docs/linkage-format.md`) and plans
/// to the same answer.
#[cfg(feature = "serde")]
#[test]
fn descriptions_survive_json() {
    use tmm::kinematics::Motion;
    use tmm::synthesis::{burmester, crank_rocker_through, Pose};
    let o = Options::default().with_min_transmission_angle(0.0);
    let deg = f64::to_radians;
    let all = [
        crank_rocker(
            &CrankRockerRequirement {
                rocker: 0.3,
                swing: 0.8,
                time_ratio: 1.3,
                frame: FrameChoice::BestTransmission,
            },
            &o,
        ),
        slider_crank(
            &SliderCrankRequirement {
                stroke: 0.2,
                time_ratio: 1.2,
                offset: OffsetChoice::BestTransmission,
            },
            &o,
        ),
        shaper(
            &ShaperRequirement {
                stroke: 0.3,
                time_ratio: 1.6,
                centre_distance: 0.25,
            },
            &o,
        ),
        crank_rocker_through(
            0.4,
            &[
                (deg(40.0), deg(101.4)),
                (deg(100.0), deg(112.8)),
                (deg(160.0), deg(131.8)),
            ],
            &o,
        ),
        burmester(
            &[
                Pose::new([0.0, 0.0], 0.0),
                Pose::new([0.1, 0.05], 0.3),
                Pose::new([0.2, 0.05], 0.7),
            ],
            [-0.05, -0.1],
            [0.1, -0.08],
            &o,
        ),
    ];
    for s in all {
        let s = s.unwrap();
        let back = Linkage::from_json(&s.linkage.to_json().unwrap()).unwrap();
        assert_eq!(back, s.linkage);
        let (p, q) = (Plan::new(&s.linkage).unwrap(), Plan::new(&back).unwrap());
        let out = s.linkage.output.clone().unwrap();
        let at = Motion::fixed(p.reference_input() + 0.3);
        assert_eq!(p.output(&out, at).unwrap(), q.output(&out, at).unwrap());
    }
}

/// A requirement whose linear maps overflow (found by the hostile test: the SVD of a
/// non-finite system never ended) is an error at once.
#[test]
fn overflowing_maps_are_an_error() {
    use tmm::synthesis::{function_generator, FunctionRequirement, Spacing};
    let need = FunctionRequirement {
        x_range: [1.768432583298752e299, -6.78640403404003e299],
        crank_range: [0.0, 2.6806225978709803],
        rocker_range: [-3.777638690240938e299, 1.3307248007636203],
        frame: 0.1,
        spacing: Spacing::LeastSquares(4),
    };
    let o = Options::default().with_min_transmission_angle(0.0);
    let r = function_generator(|t| t.sin() + 1.537968918599314 * t, &need, &o);
    assert!(matches!(r, Err(Error::Overflow { .. })), "{r:?}");
}
