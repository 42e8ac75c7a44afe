//! Whole mechanisms: the group-by-group chain against the principle of virtual power, every
//! link's equilibrium, the energy balance over a cycle, dead points inside a cycle, the
//! course-project positions, CSV, and the optional features (rayon, serde).

use nalgebra::Point2;
use std::f64::consts::{PI, TAU};
use tmm::kinematics::{Motion, Rotation};
use tmm::mechanism::{
    course_inputs, run_cycle, uniform_inputs, Analysed, Column, Compressor, Drive, FourBar,
    RockingCylinder, SixBar, SliderCrank, Table, Tabulate,
};
use tmm::{Error, Result};

/// A gear drive for any mechanism: a wheel of 0.2 m on the crank, P at 200°, α_w = 20°.
const GEAR: Drive = Drive::Gear {
    pitch_radius: 0.2,
    pitch_angle: 200.0 * PI / 180.0,
    pressure_angle: 20.0 * PI / 180.0,
};

/// Checks the virtual-power agreement and the equilibrium of every link at every position;
/// returns the largest of each.
fn check_cycle<P: Analysed>(name: &str, positions: &[Result<P>]) -> (f64, f64) {
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
        let o1 = p.free_bodies()[0].motion.origin.p;
        let power = p.balance().power(o1, p.input().rate);
        assert!(
            (power - check.chain * p.input().rate).abs()
                <= 1e-12 * check.scale * p.input().rate.abs()
        );
        for body in p.free_bodies() {
            let r = body.residual();
            assert!(
                r.relative() <= 1e-12,
                "{name}: position {k}: {} off equilibrium by {r:?}",
                body.name
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

#[test]
fn every_ready_mechanism_balances_by_virtual_power_and_link_by_link() {
    let mut report = Vec::new();
    for drive in [Drive::Coupling, GEAR] {
        let six = SixBar {
            drive,
            ..SixBar::course_example()
        };
        report.push(check_cycle(
            "six-bar",
            &run_cycle(&inputs(10.0), |i| six.analyse(i)),
        ));
        let four = FourBar {
            drive,
            ..FourBar::course_example()
        };
        report.push(check_cycle(
            "four-bar",
            &run_cycle(&inputs(-12.0), |i| four.analyse(i)),
        ));
        let sc = SliderCrank {
            drive,
            ..SliderCrank::course_example()
        };
        report.push(check_cycle(
            "slider-crank",
            &run_cycle(&inputs(150.0), |i| sc.analyse(i)),
        ));
        let comp = Compressor {
            drive,
            ..Compressor::course_example()
        };
        let w = Compressor::seed_speed();
        report.push(check_cycle(
            "compressor",
            &run_cycle(&inputs(w), |i| comp.analyse(i)),
        ));
        let rc = RockingCylinder {
            drive,
            ..RockingCylinder::course_example()
        };
        report.push(check_cycle(
            "rocking cylinder",
            &run_cycle(&inputs(20.0), |i| rc.analyse(i)),
        ));
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
    let coupled = SixBar::course_example();
    let geared = SixBar {
        drive: GEAR,
        ..coupled
    };
    for input in inputs(10.0) {
        let (c, g) = (
            coupled.analyse(input).unwrap(),
            geared.analyse(input).unwrap(),
        );
        let mb = c.balance.moment;
        assert!((g.balance.moment - mb).abs() <= 1e-12 * mb.abs().max(1.0));
        // |F_b| = |M_b| / (r_w cos α_w), along one of the two lines of action.
        let arm = 0.2 * 20f64.to_radians().cos();
        assert!((g.balance.force.norm() - mb.abs() / arm).abs() <= 1e-9 * mb.abs().max(1.0));
        // The frame takes the difference: R01 changes by −F_b.
        assert!(
            (g.balance.r01 - (c.balance.r01 - g.balance.force)).norm() <= 1e-9 * mb.abs().max(1.0)
        );
    }
}

/// Over one turn at constant ω1 the kinetic energy comes back and gravity does no net work:
/// ∮ M_b dφ1 = −(the work of the external loads per cycle).
fn cycle_work<P: Analysed>(positions: &[Result<P>]) -> (f64, f64) {
    let n = positions.len() as f64;
    let (mut w, mut abs) = (0.0, 0.0);
    for p in positions {
        let m = p.as_ref().unwrap().balance().moment;
        w += m * TAU / n;
        abs += m.abs() * TAU / n;
    }
    (w, abs)
}

#[test]
fn inertia_and_weights_do_no_net_work_over_a_cycle() {
    let n = 720;
    let six = SixBar {
        resistance: 0.0,
        ..SixBar::course_example()
    };
    let (w, abs) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 10.0, 0.0), |i| {
        six.analyse(i)
    }));
    assert!(w.abs() <= 1e-9 * abs, "six-bar: {w} of {abs}");
    let four = FourBar {
        resisting_moment: 0.0,
        ..FourBar::course_example()
    };
    let (w, abs) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 10.0, 0.0), |i| {
        four.analyse(i)
    }));
    assert!(w.abs() <= 1e-9 * abs, "four-bar: {w} of {abs}");
    let rc = RockingCylinder {
        force_in: 0.0,
        force_out: 0.0,
        ..RockingCylinder::course_example()
    };
    let (w, abs) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 20.0, 0.0), |i| {
        rc.analyse(i)
    }));
    assert!(w.abs() <= 1e-9 * abs, "rocking cylinder: {w} of {abs}");
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
    let n = 20_000;
    let (w, _) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 150.0, 0.0), |i| {
        sc.analyse(i)
    }));
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

    let four = FourBar::course_example();
    let s = four.strokes(Rotation::Ccw).unwrap();
    let phi3 = |phi1| {
        four.kinematics(Motion::new(phi1, 1.0, 0.0))
            .unwrap()
            .1
            .link3
            .angle
    };
    let swing = wrap(phi3(s.end) - phi3(s.start)).abs();
    let (w, _) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 10.0, 0.0), |i| {
        four.analyse(i)
    }));
    check("four-bar", w, 2.0 * four.resisting_moment * swing);

    let six = SixBar::course_example();
    let s = six.strokes(Rotation::Ccw).unwrap();
    let s5 = |phi1| {
        six.kinematics(Motion::new(phi1, 1.0, 0.0))
            .unwrap()
            .3
            .slide
            .value
    };
    let stroke = (s5(s.end) - s5(s.start)).abs();
    let (w, _) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 10.0, 0.0), |i| {
        six.analyse(i)
    }));
    check("six-bar", w, six.resistance * stroke);

    let rc = RockingCylinder::course_example();
    let (w, _) = cycle_work(&run_cycle(&uniform_inputs(n, 0.0, 20.0, 0.0), |i| {
        rc.analyse(i)
    }));
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
        let e = m.analyse(Motion::new(1.0, 10.0, 0.0)).unwrap_err();
        assert!(
            matches!(e, Error::In { ref part, .. } if part == "link 5 (slider)"),
            "{e}"
        );
    }
}

#[test]
fn a_ragged_table_is_an_io_error_not_a_panic() {
    let t = Table {
        columns: vec![
            Column {
                name: "a".into(),
                values: vec![1.0, 2.0],
            },
            Column {
                name: "b".into(),
                values: vec![1.0],
            },
        ],
    };
    let mut out = Vec::new();
    let e = t.write_csv(&mut out).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
    assert!(out.is_empty());
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
    let positions = run_cycle(&uniform_inputs(36, 0.0, 10.0, 0.0), |i| m.analyse(i));
    assert_eq!(positions.len(), 36);
    for (k, p) in positions.iter().enumerate() {
        match p {
            Err(Error::In { part, source }) => {
                assert!(k == 0 || k == 18, "position {k} failed: {source}");
                assert_eq!(part, "group II(2,3) RRR");
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
    let positions = run_cycle(&uniform_inputs(36, 0.0, 10.0, 0.0), |i| m.analyse(i));
    let failed: Vec<_> = positions.iter().filter_map(|p| p.as_ref().err()).collect();
    assert!(!failed.is_empty() && failed.len() < 36);
    for e in failed {
        assert!(
            matches!(e, Error::In { part, .. } if part == "group II(4,5) RRP"),
            "{e}"
        );
    }
}

#[test]
fn bad_input_is_an_error_naming_the_input_link() {
    let e = SixBar::course_example()
        .analyse(Motion::new(f64::NAN, 1.0, 0.0))
        .unwrap_err();
    assert!(
        matches!(e, Error::In { ref part, .. } if part == "link 1 (crank)"),
        "{e}"
    );
    let p = SixBar::course_example()
        .analyse(Motion::new(1.0, 0.0, 0.0))
        .unwrap();
    assert!(
        p.power_check().is_err(),
        "ω1 = 0 has no virtual-power balance"
    );
}

#[test]
fn course_positions_start_at_the_working_stroke() {
    let six = SixBar::course_example();
    let strokes = six.strokes(Rotation::Ccw).unwrap();
    let plan = course_inputs(&strokes, 12, 10.0);
    assert_eq!(plan.len(), 12);
    let first = six.analyse(plan[0]).unwrap();
    // An extreme position: the slider is at rest there, at its largest s (the stroke works
    // along −x, as the example's resistance assumes).
    let scale = 10.0 * six.l1;
    assert!(first.group45.slide.rate.abs() <= 1e-9 * scale);
    let mid = six
        .analyse(Motion::new(
            strokes.start + 0.5 * strokes.working_angle,
            10.0,
            0.0,
        ))
        .unwrap();
    assert!(mid.group45.slide.rate * six.working_direction > 0.0);
    assert!(strokes.time_ratio > 1.0);

    // The compressor turns clockwise: its plans go clockwise from piston 3's dead centre.
    let comp = Compressor::course_example();
    let strokes = comp.strokes(Rotation::Cw).unwrap();
    let plan = course_inputs(&strokes, 12, Compressor::seed_speed());
    assert!(plan.iter().all(|m| m.rate < 0.0));
    let p0 = comp.analyse(plan[0]).unwrap();
    assert!(p0.group23.slide.rate.abs() <= 1e-9 * comp.l1 * 100.0);
    for pair in plan.windows(2) {
        let step = tmm::angle::normalize(pair[0].value - pair[1].value);
        assert!((step - TAU / 12.0).abs() < 1e-12);
    }
}

#[test]
fn csv_holds_every_column_and_reads_back_bit_for_bit() {
    let six = SixBar::course_example();
    let positions = run_cycle(&uniform_inputs(36, 0.0, 10.0, 0.0), |i| six.analyse(i));
    let table = Table::of(&positions);
    assert_eq!(table.len(), 36);
    let row = positions[0].as_ref().unwrap().row();
    assert_eq!(table.columns.len(), row.len());
    for name in ["R12", "R23", "R03", "R34", "R45", "R05"] {
        assert!(table.column(&format!("|{name}| [N]")).is_some(), "{name}");
    }
    let mut csv = Vec::new();
    table.write_csv(&mut csv).unwrap();
    let text = String::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), table.columns.len());
    for (k, line) in lines.enumerate() {
        for (j, cell) in line.split(',').enumerate() {
            let v: f64 = cell.parse().unwrap();
            assert_eq!(v.to_bits(), table.columns[j].values[k].to_bits());
        }
    }
    // |R| columns are the norms of the x, y columns.
    let (x, y, m) = (
        table.column("R12_x [N]").unwrap(),
        table.column("R12_y [N]").unwrap(),
        table.column("|R12| [N]").unwrap(),
    );
    for k in 0..36 {
        assert!((x[k].hypot(y[k]) - m[k]).abs() <= 1e-12 * m[k]);
    }
}

#[cfg(feature = "rayon")]
#[test]
fn the_parallel_cycle_equals_the_serial_one_bit_for_bit() {
    use tmm::mechanism::run_cycle_parallel;
    let inputs = uniform_inputs(360, 0.2, 10.0, 1.0);
    let six = SixBar::course_example();
    assert_eq!(
        run_cycle(&inputs, |i| six.analyse(i)),
        run_cycle_parallel(&inputs, |i| six.analyse(i))
    );
    let comp = Compressor::course_example();
    let a = Table::of(&run_cycle(&inputs, |i| comp.analyse(i)));
    let b = Table::of(&run_cycle_parallel(&inputs, |i| comp.analyse(i)));
    for (x, y) in a.columns.iter().zip(&b.columns) {
        assert!(x
            .values
            .iter()
            .zip(&y.values)
            .all(|(p, q)| p.to_bits() == q.to_bits()));
    }
}

#[cfg(feature = "serde")]
#[test]
fn mechanisms_and_results_survive_a_serde_round_trip() {
    let six = SixBar {
        drive: GEAR,
        ..SixBar::course_example()
    };
    let back: SixBar = serde_json::from_str(&serde_json::to_string(&six).unwrap()).unwrap();
    assert_eq!(back, six);
    let comp = Compressor::course_example();
    let back: Compressor = serde_json::from_str(&serde_json::to_string(&comp).unwrap()).unwrap();
    assert_eq!(back, comp);
    let inputs = uniform_inputs(36, 0.0, -100.0, 0.0);
    let table = Table::of(&run_cycle(&inputs, |i| comp.analyse(i)));
    let back: Table = serde_json::from_str(&serde_json::to_string(&table).unwrap()).unwrap();
    assert_eq!(back, table);
    // The loaded mechanism gives the same results.
    let again = Table::of(&run_cycle(&inputs, |i| back_analyse(&comp, i)));
    assert_eq!(again, table);
    // A whole analysed position (kinematic states, loads, reactions, balance) too.
    let position = six.analyse(inputs[5]).unwrap();
    let back: tmm::mechanism::SixBarPosition =
        serde_json::from_str(&serde_json::to_string(&position).unwrap()).unwrap();
    assert_eq!(back, position);
    let balance = comp.analyse(inputs[3]).unwrap().balance;
    let back: tmm::mechanism::Balance =
        serde_json::from_str(&serde_json::to_string(&balance).unwrap()).unwrap();
    assert_eq!(back, balance);
}

#[cfg(feature = "serde")]
fn back_analyse(m: &Compressor, i: Motion) -> Result<tmm::mechanism::CompressorPosition> {
    let copy: Compressor = serde_json::from_str(&serde_json::to_string(m).unwrap()).unwrap();
    copy.analyse(i)
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
    let (w1, e1) = (-Compressor::seed_speed(), 250.0); // the seed's clockwise ω1 > 0
    let mut worst = 0.0f64;
    for k in 0..36 {
        let psi = k as f64 * TAU / 36.0;
        // Seed angle ψ clockwise from +y → crate angle π/2 − ψ; rates change sign.
        let p = m.analyse(Motion::new(0.5 * PI - psi, -w1, -e1)).unwrap();
        for (g, throw) in [(&p.group23, 0.0), (&p.group45, PI)] {
            let s = seed_contour(m.l1, m.l2, psi + throw, w1, e1);
            let phi2 = tmm::angle::normalize(0.5 * PI - g.link2.angle + PI) - PI;
            let got = [
                phi2,
                g.slide.value,
                -g.link2.omega,
                g.slide.rate,
                -g.link2.epsilon,
                g.slide.accel,
            ];
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
