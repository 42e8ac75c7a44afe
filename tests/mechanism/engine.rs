//! The ready mechanisms through the linkage engine: the group-by-group chain against the
//! principle of virtual power, every link's equilibrium, the energy balance over a cycle,
//! dead points inside a cycle, the course-project positions, CSV, and the optional features
//! (rayon, serde).

use nalgebra::Point2;
use std::f64::consts::{PI, TAU};
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{
    course_inputs, run_cycle, uniform_inputs, Analysis, Drive, Output, Plan, Table, Tabulate,
};
use tmm::mechanism::{Compressor, FourBar, Mechanism, RockingCylinder, SixBar, SliderCrank};
use tmm::{Error, Result};

/// A gear drive for any mechanism: a wheel of 0.2 m on the crank, P at 200°, α_w = 20°.
const GEAR: Drive = Drive::Gear {
    pitch_radius: 0.2,
    pitch_angle: 200.0 * PI / 180.0,
    pressure_angle: 20.0 * PI / 180.0,
};

/// Checks the virtual-power agreement and the equilibrium of every link at every position;
/// returns the largest of each.
fn check_cycle(name: &str, positions: &[Result<Analysis<'_>>]) -> (f64, f64) {
    let (mut worst_power, mut worst_link) = (0.0f64, 0.0f64);
    for (k, p) in positions.iter().enumerate() {
        let p = p
            .as_ref()
            .unwrap_or_else(|e| panic!("{name}: position {k}: {e}"));
        let check = p.power_check().unwrap();
        assert!(
            check.relative_error() <= 1e-9,
            "{name}: position {k}: chain {} vs virtual power {}",
            check.chain,
            check.virtual_power
        );
        // The drive's power, F_b·v_P for a gear, is M_b·ω1.
        let plan = p.plan();
        let crank = p.link_motion(plan.input_links()[0]).unwrap();
        let b = p.balances()[0];
        let w1 = p.inputs().first().rate;
        let power = if b.force.norm() > 0.0 {
            b.force.dot(&crank.motion_of(b.point).v)
        } else {
            b.value * w1
        };
        assert!((power - check.chain * w1).abs() <= 1e-12 * check.scale * w1.abs());
        for k in 1..plan.link_names().len() {
            let r = p.residual(k).unwrap();
            assert!(
                r <= 1e-12,
                "{name}: position {k}: {} off equilibrium by {r:e}",
                plan.link_names()[k]
            );
        }
        worst_power = worst_power.max(check.relative_error());
        worst_link = worst_link.max(p.worst_residual());
    }
    (worst_power, worst_link)
}

/// 72 positions, with an input acceleration so that ε1 terms are exercised too.
fn inputs(omega1: f64) -> Vec<Motion> {
    uniform_inputs(72, 0.1, omega1, 0.3 * omega1.abs())
}

fn cycle<'p>(plan: &'p Plan, inputs: &[Motion]) -> Vec<Result<Analysis<'p>>> {
    run_cycle(inputs, |i| plan.analyse(i))
}

#[test]
fn every_ready_mechanism_balances_by_virtual_power_and_link_by_link() {
    let mut report = Vec::new();
    for drive in [Drive::Coupling, GEAR] {
        let plans = [
            (
                "six-bar",
                SixBar {
                    drive,
                    ..SixBar::course_example()
                }
                .plan(),
                10.0,
            ),
            (
                "four-bar",
                FourBar {
                    drive,
                    ..FourBar::course_example()
                }
                .plan(),
                -12.0,
            ),
            (
                "slider-crank",
                SliderCrank {
                    drive,
                    ..SliderCrank::course_example()
                }
                .plan(),
                150.0,
            ),
            (
                "compressor",
                Compressor {
                    drive,
                    ..Compressor::course_example()
                }
                .plan(),
                Compressor::seed_speed(),
            ),
            (
                "rocking cylinder",
                RockingCylinder {
                    drive,
                    ..RockingCylinder::course_example()
                }
                .plan(),
                20.0,
            ),
        ];
        for (name, plan, w) in plans {
            let plan = plan.unwrap();
            report.push(check_cycle(name, &cycle(&plan, &inputs(w))));
        }
    }
    let worst = report
        .iter()
        .fold((0.0f64, 0.0f64), |a, b| (a.0.max(b.0), a.1.max(b.1)));
    println!(
        "largest relative differences: virtual power {:.1e}, link equilibrium {:.1e}",
        worst.0, worst.1
    );
}

#[test]
fn a_gear_supplies_the_same_moment_as_a_coupling() {
    let coupled = SixBar::course_example().plan().unwrap();
    let geared = SixBar {
        drive: GEAR,
        ..SixBar::course_example()
    }
    .plan()
    .unwrap();
    for input in inputs(10.0) {
        let (c, g) = (
            coupled.analyse(input).unwrap(),
            geared.analyse(input).unwrap(),
        );
        let mb = c.balances()[0].value;
        assert!((g.balances()[0].value - mb).abs() <= 1e-12 * mb.abs().max(1.0));
        // |F_b| = |M_b| / (r_w cos α_w), along one of the two lines of action.
        let arm = 0.2 * 20f64.to_radians().cos();
        let fb = g.balances()[0].force;
        assert!((fb.norm() - mb.abs() / arm).abs() <= 1e-9 * mb.abs().max(1.0));
        // The frame takes the difference: R01 changes by −F_b.
        let (rc, rg) = (c.reaction("O1").unwrap(), g.reaction("O1").unwrap());
        assert_eq!(
            (rc.by, rc.on),
            (0, coupled.link_id("crank").unwrap().index())
        );
        assert!((rg.force - (rc.force - fb)).norm() <= 1e-9 * mb.abs().max(1.0));
    }
}

/// Over one turn at constant ω1 the kinetic energy comes back and gravity does no net work:
/// ∮ M_b dφ1 = −(the work of the external loads per cycle).
fn cycle_work(positions: &[Result<Analysis<'_>>]) -> (f64, f64) {
    let n = positions.len() as f64;
    let (mut w, mut abs) = (0.0, 0.0);
    for p in positions {
        let m = p.as_ref().unwrap().balances()[0].value;
        w += m * TAU / n;
        abs += m.abs() * TAU / n;
    }
    (w, abs)
}

#[test]
fn inertia_and_weights_do_no_net_work_over_a_cycle() {
    let n = 720;
    let plans = [
        (
            "six-bar",
            SixBar {
                resistance: 0.0,
                ..SixBar::course_example()
            }
            .plan(),
            10.0,
        ),
        (
            "four-bar",
            FourBar {
                resisting_moment: 0.0,
                ..FourBar::course_example()
            }
            .plan(),
            10.0,
        ),
        (
            "rocking cylinder",
            RockingCylinder {
                force_in: 0.0,
                force_out: 0.0,
                ..RockingCylinder::course_example()
            }
            .plan(),
            20.0,
        ),
    ];
    for (name, plan, omega) in plans {
        let plan = plan.unwrap();
        let (w, abs) = cycle_work(&cycle(&plan, &uniform_inputs(n, 0.0, omega, 0.0)));
        assert!(abs > 1.0, "{name}: the inertia loads do work along the way");
        assert!(w.abs() <= 1e-9 * abs, "{name}: {w} of {abs}");
    }
}

#[test]
fn the_crank_supplies_the_indicator_work_per_cycle() {
    // W = A·H·∫(p_in − p_out) dx, exact on the piecewise-linear tables (trapezoids).
    let sc = SliderCrank::course_example();
    let d = sc.diagram.clone().unwrap();
    let trapezoid = |t: &[[f64; 2]]| {
        t.windows(2)
            .map(|w| 0.5 * (w[1][1] + w[0][1]) * (w[1][0] - w[0][0]))
            .sum::<f64>()
    };
    let stroke = 2.0 * sc.l1; // a central slider-crank
    let work = d.area * stroke * (trapezoid(&d.inward) - trapezoid(&d.outward));
    let plan = sc.plan().unwrap();
    let (w, _) = cycle_work(&cycle(&plan, &uniform_inputs(20_000, 0.0, 150.0, 0.0)));
    let rel = (w - work).abs() / work;
    println!("indicator work {work:.4} J, ∮M_b dφ = {w:.4} J, relative {rel:.1e}");
    assert!(rel <= 1e-6, "{w} vs {work}");
}

/// Each resistance opposes its link's motion, so over one turn at constant ω1 it takes its
/// magnitude times the path it acts over, and ∮ M_b dφ1 equals that work: the four-bar's
/// moment 2·M_r·Δφ3 over both swings of the rocker, the six-bar's force R·H on the working
/// stroke only, the rocking cylinder's fluid (F_in + F_out)·2·l1 (l_AC runs between
/// |O1C| − l1 and |O1C| + l1). A resistance with the wrong sign would do the opposite work.
#[test]
fn each_resistance_takes_its_closed_form_work_per_cycle() {
    let n = 4000;
    let wrap = |d: f64| (d + PI).rem_euclid(TAU) - PI;
    let check = |name: &str, w: f64, work: f64| {
        let rel = (w - work).abs() / work;
        println!("{name}: ∮M_b dφ = {w:.6} J, closed form {work:.6} J, relative {rel:.1e}");
        assert!(rel <= 1e-5, "{name}: {w} vs {work}");
    };
    let at = |plan: &Plan, output: &Output, phi1: f64| {
        plan.output(output, Motion::new(phi1, 1.0, 0.0))
            .unwrap()
            .value
    };

    let four = FourBar::course_example();
    let plan = four.plan().unwrap();
    let s = four.strokes(Rotation::Ccw).unwrap();
    let rocker = Output::Angle("rocker".to_owned());
    let swing = wrap(at(&plan, &rocker, s.end) - at(&plan, &rocker, s.start)).abs();
    let (w, _) = cycle_work(&cycle(&plan, &uniform_inputs(n, 0.0, 10.0, 0.0)));
    check("four-bar", w, 2.0 * four.resisting_moment * swing);

    let six = SixBar::course_example();
    let plan = six.plan().unwrap();
    let s = six.strokes(Rotation::Ccw).unwrap();
    let slide = Output::Slide("Q".to_owned());
    let stroke = (at(&plan, &slide, s.end) - at(&plan, &slide, s.start)).abs();
    let (w, _) = cycle_work(&cycle(&plan, &uniform_inputs(n, 0.0, 10.0, 0.0)));
    check("six-bar", w, six.resistance * stroke);

    let rc = RockingCylinder::course_example();
    let plan = rc.plan().unwrap();
    let (w, _) = cycle_work(&cycle(&plan, &uniform_inputs(n, 0.0, 20.0, 0.0)));
    check(
        "rocking cylinder",
        w,
        (rc.force_in + rc.force_out) * 2.0 * rc.l1,
    );
}

#[test]
fn a_six_bar_without_a_working_direction_is_an_error() {
    for wd in [0.0, f64::NAN, f64::INFINITY] {
        let m = SixBar {
            working_direction: wd,
            ..SixBar::course_example()
        };
        let e = m.plan().unwrap_err();
        assert!(
            matches!(e, Error::In { ref part, .. } if part == "slider"),
            "{e}"
        );
    }
    // Either finite sign plans, and the resistance changes side with it.
    let back = SixBar {
        working_direction: 1.0,
        ..SixBar::course_example()
    };
    let (wf, _) = cycle_work(&cycle(
        &back.plan().unwrap(),
        &uniform_inputs(720, 0.0, 10.0, 0.0),
    ));
    let (wb, _) = cycle_work(&cycle(
        &SixBar::course_example().plan().unwrap(),
        &uniform_inputs(720, 0.0, 10.0, 0.0),
    ));
    // Both strokes have the same length H, so the work per cycle is R·H either way.
    assert!((wf - wb).abs() <= 1e-6 * wb.abs() && wb > 0.0);
}

#[test]
fn a_dead_point_fails_its_position_naming_the_group_and_the_cycle_goes_on() {
    // A parallelogram four-bar: crank = rocker, coupler = frame. All four links are collinear
    // at φ1 = 0 and φ1 = π.
    let m = FourBar {
        o3: Point2::new(0.3, 0.0),
        l1: 0.1,
        l2: 0.3,
        l3: 0.1,
        ..FourBar::course_example()
    };
    let plan = m.plan().unwrap();
    let positions = cycle(&plan, &uniform_inputs(36, 0.0, 10.0, 0.0));
    assert_eq!(positions.len(), 36);
    for (k, p) in positions.iter().enumerate() {
        match p {
            Err(Error::In { part, source }) => {
                assert!(k == 0 || k == 18, "position {k} failed: {source}");
                assert_eq!(part, "group (coupler, rocker) RRR");
                assert!(matches!(
                    **source,
                    Error::Singular { .. } | Error::NotAssemblable { .. }
                ));
            }
            Err(e) => panic!("position {k}: unexpected {e}"),
            Ok(p) => {
                assert!(k != 0 && k != 18, "position {k} passed a dead point");
                assert!(p.power_check().unwrap().relative_error() <= 1e-9);
            }
        }
    }
    // The table keeps the 34 good positions.
    assert_eq!(Table::of(&positions).len(), 34);
}

#[test]
fn a_six_bar_whose_slider_group_locks_names_that_group() {
    // Lower the guide until the rod CD cannot reach it at part of the cycle.
    let m = SixBar {
        guide_point: Point2::new(0.0, 0.62),
        ..SixBar::course_example()
    };
    let plan = m.plan().unwrap();
    let positions = cycle(&plan, &uniform_inputs(36, 0.0, 10.0, 0.0));
    let failed: Vec<_> = positions.iter().filter_map(|p| p.as_ref().err()).collect();
    assert!(!failed.is_empty() && failed.len() < 36);
    for e in failed {
        assert!(
            matches!(e, Error::In { part, .. } if part == "group (rod, slider) RRP"),
            "{e}"
        );
    }
}

#[test]
fn a_mechanism_that_assembles_nowhere_fails_its_plan() {
    // A coupler and rocker of 0.05 and 0.1 m reach at most 0.15 m from O3; A never comes
    // closer than 0.30 m.
    let m = FourBar {
        l2: 0.05,
        l3: 0.1,
        ..FourBar::course_example()
    };
    let e = m.plan().unwrap_err();
    assert!(matches!(e, Error::Description { .. }), "{e}");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let plan = SixBar::course_example().plan().unwrap();
    let e = plan.analyse(Motion::new(f64::NAN, 1.0, 0.0)).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    // At rest the balance by virtual power is the statics virtual-work check, by the
    // velocity analogues (issue 27: it was an error, ω1 = 0 having no rate to divide by).
    let p = plan.analyse(Motion::new(1.0, 0.0, 0.0)).unwrap();
    let c = p.power_check().unwrap();
    assert!(c.relative_error() < 1e-9, "ω1 = 0: {c:?}");
}

#[test]
fn course_positions_start_at_the_working_stroke() {
    let six = SixBar::course_example();
    let plan = six.plan().unwrap();
    let strokes = six.strokes(Rotation::Ccw).unwrap();
    let inputs = course_inputs(&strokes, 12, 10.0);
    assert_eq!(inputs.len(), 12);
    let first = plan.analyse(inputs[0]).unwrap();
    // An extreme position: the slider is at rest there (the stroke works along −x, as the
    // example's resistance assumes).
    let scale = 10.0 * six.l1;
    assert!(first.slide("Q").unwrap().rate.abs() <= 1e-9 * scale);
    let mid = plan
        .analyse(Motion::new(
            strokes.start + 0.5 * strokes.working_angle,
            10.0,
            0.0,
        ))
        .unwrap();
    assert!(mid.slide("Q").unwrap().rate * six.working_direction > 0.0);
    assert!(strokes.time_ratio > 1.0);

    // The compressor turns clockwise: its plans go clockwise from piston 1's dead centre.
    let comp = Compressor::course_example();
    let plan = comp.plan().unwrap();
    let strokes = comp.strokes(Rotation::Cw).unwrap();
    let inputs = course_inputs(&strokes, 12, Compressor::seed_speed());
    assert!(inputs.iter().all(|m| m.rate < 0.0));
    let p0 = plan.analyse(inputs[0]).unwrap();
    assert!(p0.slide("P1").unwrap().rate.abs() <= 1e-9 * comp.l1 * 100.0);
    for pair in inputs.windows(2) {
        let step = tmm::angle::normalize(pair[0].value - pair[1].value);
        assert!((step - TAU / 12.0).abs() < 1e-12);
    }
}

#[test]
fn csv_holds_every_column_and_reads_back_bit_for_bit() {
    let plan = SixBar::course_example().plan().unwrap();
    let positions = cycle(&plan, &uniform_inputs(36, 0.0, 10.0, 0.0));
    let table = Table::of(&positions);
    assert_eq!(table.len(), 36);
    let row = positions[0].as_ref().unwrap().row().unwrap();
    assert_eq!(table.columns.len(), row.len());
    for name in [
        "R(frame,crank)@O1",
        "R(crank,coupler)@A",
        "R(coupler,rocker)@B",
        "R(frame,rocker)@O2",
        "R(rocker,rod)@C",
        "R(rod,slider)@D",
        "R(frame,slider)@Q",
    ] {
        assert!(table.column(&format!("|{name}| [N]")).is_some(), "{name}");
    }
    let mut csv = Vec::new();
    table.write_csv(&mut csv).unwrap();
    let text = String::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    // The names hold commas, R(by,on): they are quoted.
    let header = split_quoted(lines.next().unwrap());
    let names: Vec<&str> = table.columns.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(header, names);
    for (k, line) in lines.enumerate() {
        for (j, cell) in line.split(',').enumerate() {
            let v: f64 = cell.parse().unwrap();
            assert_eq!(v.to_bits(), table.columns[j].values[k].to_bits());
        }
    }
    // |R| columns are the norms of the x, y columns; M_b beside its virtual-power value.
    let (x, y, m) = (
        table.column("R(crank,coupler)@A_x [N]").unwrap(),
        table.column("R(crank,coupler)@A_y [N]").unwrap(),
        table.column("|R(crank,coupler)@A| [N]").unwrap(),
    );
    let (mb, vp) = (
        table.column("Mb [N·m, + counter-clockwise]").unwrap(),
        table
            .column("Mb by virtual power [N·m, + counter-clockwise]")
            .unwrap(),
    );
    for k in 0..36 {
        assert!((x[k].hypot(y[k]) - m[k]).abs() <= 1e-12 * m[k]);
        assert!((mb[k] - vp[k]).abs() <= 1e-9 * mb.iter().fold(0.0f64, |a, b| a.max(b.abs())));
    }
}

/// The cells of one CSV line whose cells may be quoted (no quotes inside quotes here).
fn split_quoted(line: &str) -> Vec<String> {
    let (mut cells, mut cell, mut quoted) = (Vec::new(), String::new(), false);
    for ch in line.chars() {
        match ch {
            '"' => quoted = !quoted,
            ',' if !quoted => cells.push(std::mem::take(&mut cell)),
            _ => cell.push(ch),
        }
    }
    cells.push(cell);
    cells
}

#[cfg(feature = "rayon")]
#[test]
fn the_parallel_cycle_equals_the_serial_one_bit_for_bit() {
    use tmm::linkage::run_cycle_parallel;
    let inputs = uniform_inputs(360, 0.2, 10.0, 1.0);
    for plan in [
        SixBar::course_example().plan().unwrap(),
        Compressor::course_example().plan().unwrap(),
    ] {
        let a = Table::of(&run_cycle(&inputs, |i| plan.analyse(i)));
        let b = Table::of(&run_cycle_parallel(&inputs, |i| plan.analyse(i)));
        assert_eq!(a.len(), 360);
        assert_eq!(a.columns.len(), b.columns.len());
        for (x, y) in a.columns.iter().zip(&b.columns) {
            assert_eq!(x.name, y.name);
            assert!(x
                .values
                .iter()
                .zip(&y.values)
                .all(|(p, q)| p.to_bits() == q.to_bits()));
        }
    }
}

#[cfg(feature = "serde")]
#[test]
fn mechanisms_and_results_survive_a_serde_round_trip() {
    fn round<T: serde::Serialize + serde::de::DeserializeOwned>(t: &T) -> T {
        serde_json::from_str(&serde_json::to_string(t).unwrap()).unwrap()
    }
    let six = SixBar {
        drive: GEAR,
        ..SixBar::course_example()
    };
    assert_eq!(round(&six), six);
    let four = FourBar::course_example();
    assert_eq!(round(&four), four);
    let sc = SliderCrank::geared_example();
    assert_eq!(round(&sc), sc);
    let rc = RockingCylinder::course_example();
    assert_eq!(round(&rc), rc);
    let comp = Compressor::course_example();
    let back = round(&comp);
    assert_eq!(back, comp);
    // Its description too, and the loaded mechanism gives the same results bit for bit.
    assert_eq!(round(&comp.linkage().unwrap()), comp.linkage().unwrap());
    let inputs = uniform_inputs(36, 0.0, -100.0, 0.0);
    let plan = comp.plan().unwrap();
    let table = Table::of(&cycle(&plan, &inputs));
    assert_eq!(round(&table), table);
    let plan_back = back.plan().unwrap();
    assert_eq!(Table::of(&cycle(&plan_back, &inputs)), table);
    // A reaction and a balance.
    let a = plan.analyse(inputs[3]).unwrap();
    assert_eq!(round(&a.reaction("P1").unwrap()), a.reaction("P1").unwrap());
    assert_eq!(round(&a.balances()[0]), a.balances()[0]);
}

/// Seed 001's closed forms (2.10)–(2.14) for one contour, with the errata K1 and K2, in the
/// seed's convention (angles clockwise from +y): (φ2, l3, ω2, v3, ε2, a3).
fn seed_contour(l1: f64, l: f64, psi: f64, w1: f64, e1: f64) -> [f64; 6] {
    let phi2 = (-l1 * psi.sin() / l).asin();
    let l3 = l1 * psi.cos() + l * phi2.cos();
    let w2 = -l1 * w1 * psi.cos() / (l * phi2.cos());
    let v3 = -l1 * w1 * psi.sin() - l * w2 * phi2.sin();
    let e2 = (l1 * w1 * w1 * psi.sin() - l1 * e1 * psi.cos() + l * w2 * w2 * phi2.sin())
        / (l * phi2.cos());
    let a3 = -l1 * w1 * w1 * psi.cos()
        - l1 * e1 * psi.sin()
        - l * w2 * w2 * phi2.cos()
        - l * e2 * phi2.sin();
    [phi2, l3, w2, v3, e2, a3]
}

#[test]
fn the_compressor_reproduces_seed_001s_closed_forms_for_both_pistons() {
    let m = Compressor::course_example();
    let plan = m.plan().unwrap();
    let (w1, e1) = (-Compressor::seed_speed(), 250.0); // the seed's clockwise ω1 > 0
    let mut worst = 0.0f64;
    for k in 0..36 {
        let psi = k as f64 * TAU / 36.0;
        // Seed angle ψ clockwise from +y → crate angle π/2 − ψ; rates change sign.
        let p = plan.analyse(Motion::new(0.5 * PI - psi, -w1, -e1)).unwrap();
        for (rod, pin, slide, throw) in [("rod 1", "B", "P1", 0.0), ("rod 2", "D", "P2", PI)] {
            let s = seed_contour(m.l1, m.l2, psi + throw, w1, e1);
            let r = p.link(rod).unwrap();
            let phi2 = tmm::angle::normalize(0.5 * PI - r.value + PI) - PI;
            // Both guides run along +y through O1: l3 is the pin's y.
            let y = p.joint(pin).unwrap().p.y;
            let sl = p.slide(slide).unwrap();
            let got = [phi2, y, -r.rate, sl.rate, -r.accel, sl.accel];
            let scales = [1.0, m.l1, w1, m.l1 * w1, w1 * w1, m.l1 * w1 * w1];
            for i in 0..6 {
                worst = worst.max((got[i] - s[i]).abs() / scales[i]);
            }
        }
    }
    assert!(worst <= 1e-12, "{worst}");
}

#[test]
fn uniform_inputs_follow_the_sense_of_rotation() {
    let ccw = uniform_inputs(4, 0.0, 2.0, 0.5);
    let cw = uniform_inputs(4, 0.0, -2.0, 0.5);
    let deg = |v: &[Motion]| {
        v.iter()
            .map(|m| m.value.to_degrees().round())
            .collect::<Vec<_>>()
    };
    assert_eq!(deg(&ccw), [0.0, 90.0, 180.0, 270.0]);
    assert_eq!(deg(&cw), [0.0, 270.0, 180.0, 90.0]);
    assert!(cw.iter().all(|m| m.rate == -2.0 && m.accel == 0.5));
}
