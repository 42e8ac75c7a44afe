//! The bundled description files: every `bundled` function reads the file of its name and
//! plans, the ready mechanisms' course examples read back as the linkages they build, and every
//! file plans and balances by virtual power over a turn.
#![cfg(feature = "serde")]

use std::collections::BTreeSet;
use std::f64::consts::TAU;
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, Linkage, Plan};
use tmm::mechanism::{Compressor, FourBar, Mechanism, RockingCylinder, SixBar, SliderCrank};

macro_rules! file {
    ($name:literal, $built:expr) => {
        (
            $name,
            include_str!(concat!("../../linkages/", $name)),
            $built,
        )
    };
}

fn files() -> Vec<(&'static str, &'static str, Linkage)> {
    vec![
        file!("four-bar.json", bundled::four_bar()),
        file!("geared-four-bar.json", bundled::geared_four_bar()),
        file!("watt-six-bar.json", bundled::watt_six_bar()),
        file!("stephenson-six-bar.json", bundled::stephenson_six_bar()),
        file!("shaper.json", bundled::shaper()),
        file!("scotch-yoke.json", bundled::scotch_yoke()),
        file!("slotted-rocker.json", bundled::slotted_rocker()),
        file!(
            "mechanism-four-bar.json",
            FourBar::course_example().linkage().unwrap()
        ),
        file!(
            "mechanism-slider-crank.json",
            SliderCrank::course_example().linkage().unwrap()
        ),
        file!(
            "mechanism-compressor.json",
            Compressor::course_example().linkage().unwrap()
        ),
        file!(
            "mechanism-six-bar.json",
            SixBar::course_example().linkage().unwrap()
        ),
        file!(
            "mechanism-rocking-cylinder.json",
            RockingCylinder::course_example().linkage().unwrap()
        ),
        file!("five-bar-robot.json", bundled::five_bar_robot()),
        file!("six-bar-triad.json", bundled::six_bar_triad()),
        file!("six-bar-slider-triad.json", bundled::six_bar_slider_triad()),
        file!("double-butterfly.json", bundled::double_butterfly()),
    ]
}

/// The gallery's files (`bundled::gallery`), tested in `gallery.rs` over their own ranges.
fn gallery_files() -> Vec<(&'static str, &'static str, Linkage)> {
    vec![
        file!("peaucellier-lipkin.json", bundled::peaucellier_lipkin()),
        file!(
            "chebyshev-straight-line.json",
            bundled::chebyshev_straight_line()
        ),
        file!(
            "hoekens-straight-line.json",
            bundled::hoekens_straight_line()
        ),
        file!("jansen-leg.json", bundled::jansen_leg()),
        file!("watt-ii-six-bar.json", bundled::watt_ii_six_bar()),
        file!(
            "stephenson-ii-six-bar.json",
            bundled::stephenson_ii_six_bar()
        ),
    ]
}

#[test]
fn every_file_reads_back_as_its_bundled_function_or_ready_mechanism() {
    let gallery = gallery_files();
    assert_eq!(gallery.len(), bundled::gallery().len());
    let mut files = files();
    files.extend(gallery);
    // Every file under linkages/ is in the list.
    let on_disk = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/linkages"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "json")
        })
        .count();
    assert_eq!(on_disk, files.len());
    for (name, text, built) in files {
        let read = Linkage::from_json(text).unwrap_or_else(|e| panic!("{name}: {e}"));
        if !name.starts_with("mechanism-") {
            // A `bundled` function is its file, exactly.
            assert!(
                read == built,
                "{name} is not the file its bundled function reads"
            );
            continue;
        }
        // The ready mechanisms compute their reference poses: their numbers may move in the
        // last bits when the blocks' arithmetic is reordered, so numbers agree to 1e-13.
        let as_value = |l: &Linkage| serde_json::from_str(&l.to_json().unwrap()).unwrap();
        if let Err(at) = same(&as_value(&read), &as_value(&built), name.to_owned()) {
            panic!("{name} differs from its linkage at {at}");
        }
    }
}

/// Equal JSON values, numbers to a relative 1e-13; `Err` names the first place they differ.
fn same(a: &serde_json::Value, b: &serde_json::Value, at: String) -> Result<(), String> {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if (x - y).abs() <= 1e-13 * x.abs().max(y.abs()).max(1.0) {
                Ok(())
            } else {
                Err(format!("{at}: {x} vs {y}"))
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .try_for_each(|(k, (x, y))| same(x, y, format!("{at}[{k}]"))),
        (Value::Object(x), Value::Object(y)) if x.len() == y.len() => {
            x.iter().try_for_each(|(k, v)| match y.get(k) {
                Some(w) => same(v, w, format!("{at}.{k}")),
                None => Err(format!("{at}.{k} missing")),
            })
        }
        _ if a == b => Ok(()),
        _ => Err(format!("{at}: {a} vs {b}")),
    }
}

#[test]
fn every_bundled_function_reads_and_plans() {
    let mut names = BTreeSet::new();
    for (linkage, inputs) in bundled::all()
        .into_iter()
        .map(|l| (l, 1))
        .chain([(bundled::five_bar_robot(), 2)])
    {
        let plan = Plan::new(&linkage).unwrap_or_else(|e| panic!("{}: {e}", linkage.name));
        assert_eq!(plan.input_count(), inputs, "{}", linkage.name);
        assert_eq!(
            usize::try_from(plan.mobility()).ok(),
            Some(inputs),
            "{}",
            linkage.name
        );
        assert!(!plan.groups().is_empty(), "{}", linkage.name);
        assert!(names.insert(linkage.name.clone()), "{} twice", linkage.name);
    }
    // Every bundled file of one input is in `all`, and `all` holds nothing else.
    let single = files()
        .iter()
        .filter(|(name, _, _)| !name.starts_with("mechanism-") && name != &"five-bar-robot.json")
        .count();
    assert_eq!(bundled::all().len(), single);
}

#[test]
fn every_file_balances_by_virtual_power_over_a_turn() {
    for (name, text, _) in files() {
        let plan = Plan::new(&Linkage::from_json(text).unwrap()).unwrap();
        let (mut vp, mut eq) = (0.0f64, 0.0f64);
        let r = plan.reference_inputs();
        for k in 0..72 {
            let theta = TAU * (f64::from(k) + 0.5) / 72.0;
            let a = if r.len() == 1 {
                plan.analyse(Motion::new(r[0] + theta, 10.0, 3.0)).unwrap()
            } else {
                // Two inputs (the five-bar robot): a loop of ±0.3 rad around the reference
                // pose, both cranks moving.
                let m = [
                    Motion::new(r[0] + 0.3 * theta.sin(), 10.0, 3.0),
                    Motion::new(r[1] + 0.3 * theta.cos(), -7.0, 2.0),
                ];
                plan.analyse(m).unwrap()
            };
            vp = vp.max(a.power_check().unwrap().relative_error());
            eq = eq.max(a.worst_residual());
        }
        assert!(vp < 1e-9, "{name}: virtual power {vp:e}");
        assert!(eq < 1e-12, "{name}: equilibrium {eq:e}");
    }
}

#[test]
fn the_watt_file_is_at_most_40_lines() {
    let text = include_str!("../../linkages/watt-six-bar.json");
    assert!(text.lines().count() <= 40, "{} lines", text.lines().count());
}

/// The diagrams' default output is the angle of the last link written that is neither the
/// frame nor the input, in whatever order the links are written (the frame last moved the
/// crank to the end once, and the diagram showed the input itself).
#[test]
fn the_default_output_is_the_last_link_written_that_is_not_frame_or_input() {
    let base = bundled::four_bar();
    let n = base.links.len();
    let base_plan = Plan::new(&base).unwrap();
    let base_kin = base_plan.kinematics(Motion::fixed(0.7)).unwrap();
    let mut orders = 0;
    // Every rotation and its reverse of the links' order.
    for shift in 0..n {
        for reverse in [false, true] {
            let mut l = base.clone();
            l.links.rotate_left(shift);
            if reverse {
                l.links.reverse();
            }
            l.output = None;
            let expected = l
                .links
                .iter()
                .rev()
                .find(|k| k.name != l.frame && k.name != l.input.link)
                .map(|k| k.name.clone())
                .unwrap();
            let plan = Plan::new(&l).unwrap();
            match plan.output_or_last(None) {
                tmm::linkage::Output::Angle(name) => {
                    assert_eq!(name, expected, "{shift} {reverse}")
                }
                other => panic!("{other:?}"),
            }
            // The engine's motion of every link does not depend on the order written.
            let (a, b) = (plan.kinematics(Motion::fixed(0.7)).unwrap(), &base_kin);
            for link in &base.links {
                let (x, y) = (
                    a.link(link.name.as_str()).unwrap(),
                    b.link(link.name.as_str()).unwrap(),
                );
                assert_eq!(
                    (x.value, x.rate, x.accel),
                    (y.value, y.rate, y.accel),
                    "{}",
                    link.name
                );
            }
            orders += 1;
        }
    }
    assert_eq!(orders, 2 * n);
}
