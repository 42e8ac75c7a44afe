//! Hostile sweeps of the entry points no other sweep reached: the triad with friction
//! (`TriadFriction::solve`, `solve_with`), the friction solve of the triads and general
//! groups in a linkage (the triad six-bar and the double butterfly analysed with hostile
//! friction data and inputs), the triad with a sliding pair (`slider_triad_modes`,
//! `slider_triad`, `slider_triad_rates`), `synthesis::burmester_curves`,
//! `draw::structural_error` and the workspace (`Plan::workspace`, `draw::workspace`, every
//! SVG scanned). Each case starts from a valid worked problem and makes one or more fields
//! hostile, so that the sweeps reach past the input checks. Fixed seeds; `cases()` calls
//! per entry point, `cases()/20` for the linkage-wide solves (an analysis of the double
//! butterfly tracks its six-link group: some 10² times the cost of a block's call).

use super::{check, sweep};
use crate::common::hostile_gen::{cases, Gen};
use crate::common::svg_scan::assert_finite_svg;
use nalgebra::{Point2, Vector2};
use tmm::kinematics::{
    slider_triad, slider_triad_modes, slider_triad_rates, Guide, Motion, PointMotion,
    SliderTriadDims, SlidingPair, TriadPose,
};
use tmm::kinetostatics::friction::{Hinge, Iteration, TriadFriction, TriadJoints, TriadRates};
use tmm::kinetostatics::Triad;
use tmm::linkage::{bundled, Friction, GroupKind, Linkage, Plan, WorkspaceOptions};
use tmm::synthesis::{burmester_curves, function_generator, FunctionRequirement, Options, Pose};
use tmm::Load;

/// Half the time `ordinary`, else a hostile number.
fn or_hostile(g: &mut Gen, ordinary: f64) -> f64 {
    if g.next().is_multiple_of(2) {
        ordinary
    } else {
        g.f()
    }
}

/// [`Triad`]'s worked example: three binary links (outer joints `a`, inner joints `b`) on a
/// ternary link loaded by 300 N, every joint a friction circle of radius `rho`, the ternary
/// link turning at 1 rad/s and the rest at rest.
fn worked_triad_friction(rho: f64) -> TriadFriction {
    let b = [
        Point2::new(-1.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.0, 1.0),
    ];
    let a = [
        Point2::new(-1.0, 1.0),
        Point2::new(1.0, 1.0),
        Point2::new(1.0, 1.0),
    ];
    let pin = Hinge { rho };
    TriadFriction {
        triad: Triad {
            a,
            b,
            loads: [Load::zero(a[0]), Load::zero(a[1]), Load::zero(a[2])],
            load_ternary: Load::force_at(Point2::new(0.0, 1.0 / 3.0), Vector2::new(0.0, -300.0)),
        },
        joints: TriadJoints {
            a: [pin; 3],
            b: [pin; 3],
        },
        rates: TriadRates {
            outer: [0.0; 3],
            binary: [0.0; 3],
            ternary: 1.0,
        },
    }
}

/// [`worked_triad_friction`] with friction circles of 1 cm: a field or more made hostile.
fn hostile_triad_friction(g: &mut Gen) -> (TriadFriction, Iteration) {
    let worked = worked_triad_friction(0.01);
    let (mut a, mut b) = (worked.triad.a, worked.triad.b);
    for p in a.iter_mut().chain(b.iter_mut()) {
        if g.next().is_multiple_of(8) {
            *p = g.p();
        }
    }
    // Hostile loads whole: a reaction above 10¹⁵⁴ whose pressure overflows is an
    // `Overflow` error (`repro_triad_friction_overflowing_pressure`).
    let load = |g: &mut Gen, at: Point2<f64>| {
        if g.next().is_multiple_of(4) {
            let l = g.load();
            Load::new(l.point, l.force, l.moment)
        } else {
            Load::zero(at)
        }
    };
    let triad = Triad {
        a,
        b,
        loads: [load(g, a[0]), load(g, a[1]), load(g, a[2])],
        load_ternary: if g.next().is_multiple_of(4) {
            load(g, Point2::origin())
        } else {
            worked.triad.load_ternary
        },
    };
    let mut pin = || Hinge {
        rho: or_hostile(g, 0.01),
    };
    let joints = TriadJoints {
        a: [pin(), pin(), pin()],
        b: [pin(), pin(), pin()],
    };
    // Hostile rates too: a lost power that overflows is an `Overflow` error
    // (`repro_triad_friction_lost_power_overflows`).
    let mut rate = |ordinary: f64| or_hostile(g, ordinary);
    let rates = TriadRates {
        outer: [rate(0.0), rate(0.0), rate(0.0)],
        binary: [rate(0.0), rate(0.0), rate(0.0)],
        ternary: rate(1.0),
    };
    let it = Iteration::default()
        .with_tolerance(or_hostile(g, 1e-14))
        .with_budget((g.next() % 200) as usize);
    (
        TriadFriction {
            triad,
            joints,
            rates,
        },
        it,
    )
}

#[test]
fn sweep_triad_friction() {
    sweep(71, |g| {
        let (t, it) = hostile_triad_friction(g);
        check("TriadFriction::solve", &t, || t.solve());
        check("TriadFriction::solve_with", &(t, it), || t.solve_with(&it));
    });
}

/// The bundled linkages with a triad (hinged or with a sliding pair) or a general group.
fn larger_groups() -> Vec<Linkage> {
    bundled::all()
        .into_iter()
        .filter(|l| {
            Plan::new(l).is_ok_and(|p| {
                p.groups()
                    .iter()
                    .any(|g| matches!(g.kind, GroupKind::Triad | GroupKind::General))
            })
        })
        .collect()
}

#[test]
fn sweep_friction_in_triads_and_general_groups() {
    let all = larger_groups();
    assert_eq!(
        all.len(),
        3,
        "the triad six-bar, the double butterfly and the sliding triad six-bar"
    );
    let mut g = Gen::new(73);
    let mut solved = 0;
    for l in &all {
        let reference = Plan::new(l).unwrap().reference_input();
        for case in 0..cases().div_ceil(20) {
            let mut l = l.clone();
            let friction = Friction::pin(or_hostile(&mut g, 0.15), or_hostile(&mut g, 0.02));
            l.friction = Some(friction);
            if g.next().is_multiple_of(3) {
                let k = (g.next() % l.joints.len() as u64) as usize;
                l.joints[k].friction = Some(Friction::pin(g.f(), g.f()));
            }
            let turn = g.unit() * 6.0;
            let input = Motion::new(
                reference + or_hostile(&mut g, turn),
                or_hostile(&mut g, 10.0),
                or_hostile(&mut g, 0.0),
            );
            let what = format!("{} case {case}: {friction:?} {input:?}", l.name);
            check("Plan::new with friction", &what, || {
                let plan = Plan::new(&l)?;
                let a = plan.analyse(input)?;
                let frictions: Vec<_> = plan.joint_ids().map(|j| a.friction(j)).collect();
                solved += 1;
                Ok((a.reactions().to_vec(), a.balances().to_vec(), frictions))
            });
        }
    }
    println!("{solved} analyses with friction in the larger groups");
    assert!(solved > 0 || cases() < 20);
}

/// The slider triad of `slider_triad_modes`' example (a slider on the x axis carrying B1,
/// legs of 1 m), a field or more made hostile.
fn hostile_slider_triad(g: &mut Gen) -> (Guide, [PointMotion; 2], SliderTriadDims) {
    let pair = if g.next().is_multiple_of(2) {
        SlidingPair::Outer {
            offset: or_hostile(g, 0.0),
        }
    } else {
        SlidingPair::Inner {
            angle: or_hostile(g, 0.3),
            offset: or_hostile(g, 0.1),
        }
    };
    let dims = SliderTriadDims {
        pair,
        l: [or_hostile(g, 1.0), or_hostile(g, 1.0)],
        // Any ternary link: one of 10⁻²⁶¹ m whose modes' conditioning overflows is an
        // `Overflow` error (`repro_slider_triad_degenerate_ternary`).
        l_b1b2: or_hostile(g, 1.0),
        b3_along: or_hostile(g, 0.5),
        b3_across: or_hostile(g, 0.8),
    };
    let pm = |g: &mut Gen, x: f64, y: f64| {
        if g.next().is_multiple_of(3) {
            g.pm()
        } else {
            PointMotion::new(Point2::new(x, y), g.v(), g.v())
        }
    };
    let first = Guide {
        point: pm(g, -2.0, 0.0),
        angle: if g.next().is_multiple_of(3) {
            g.motion()
        } else {
            Motion::fixed(0.0)
        },
    };
    (first, [pm(g, 1.6, 0.8), pm(g, 0.5, 1.8)], dims)
}

#[test]
fn sweep_slider_triads() {
    sweep(79, |g| {
        let (first, a, dims) = hostile_slider_triad(g);
        let case = (first, a, dims);
        check("slider_triad_modes", &case, || {
            slider_triad_modes(&first, [a[0].p, a[1].p], &dims)
        });
        let previous = TriadPose {
            b: [g.p(), g.p(), g.p()],
            theta: g.f(),
            phi: [g.f(), g.f(), g.f()],
            det: g.f(),
        };
        check("slider_triad", &(case, previous), || {
            slider_triad(&first, a, &dims, &previous)
        });
        if let Ok(modes) = slider_triad_modes(&first, [a[0].p, a[1].p], &dims) {
            for pose in modes.as_slice() {
                check("slider_triad_rates", &(case, pose), || {
                    slider_triad_rates(&first, a, &dims, pose)
                });
            }
        }
    });
}

/// Was a defect (fixed): `slider_triad_rates` at a
/// pose that is not one of the modes, with B1 at x = f64::MAX, returns `Ok` with `det: inf`.
#[test]
fn repro_slider_triad_rates_at_an_overflowing_pose() {
    let dims = SliderTriadDims {
        pair: SlidingPair::Outer { offset: 0.0 },
        l: [1.0, 1.0],
        l_b1b2: 1.0,
        b3_along: 0.5,
        b3_across: 0.8,
    };
    let first = Guide::fixed(Point2::new(-2.0, 0.0), 0.0);
    let a = [
        PointMotion::fixed(Point2::new(1.6, 0.8)),
        PointMotion::fixed(Point2::new(0.5, 1.8)),
    ];
    let pose = TriadPose {
        b: [
            Point2::new(f64::MAX, 0.66),
            Point2::new(0.1, 0.06),
            Point2::new(0.5, 0.0),
        ],
        theta: 0.0,
        phi: [0.0, 0.05, 0.06],
        det: -0.27,
    };
    check("slider_triad_rates", &pose, || {
        slider_triad_rates(&first, a, &dims, &pose)
    });
}

/// Was a defect (fixed): a finite outer
/// rate of −f64::MAX rad/s gives `power_lost: inf` in an `Ok`.
#[test]
fn repro_triad_friction_lost_power_overflows() {
    let mut t = worked_triad_friction(0.5);
    t.rates.outer[2] = -f64::MAX;
    t.rates.binary[0] = 0.5;
    check("TriadFriction::solve", &t, || t.solve());
}

#[test]
fn sweep_burmester_curves() {
    let ordinary = [
        ([0.0, 0.0], 0.0),
        ([0.1, 0.05], 0.3),
        ([0.2, 0.05], 0.7),
        ([0.28, 0.0], 1.0),
    ];
    sweep(83, |g| {
        let poses = ordinary.map(|(at, angle)| {
            Pose::new(
                [or_hostile(g, at[0]), or_hostile(g, at[1])],
                or_hostile(g, angle),
            )
        });
        // n up to 96 (the curves cost n); sometimes a hostile count.
        let n = match g.next() % 8 {
            0 => [0, 1, 2, usize::MAX, 1 << 40][(g.next() % 5) as usize],
            _ => (g.next() % 96) as usize,
        };
        check("burmester_curves", &(poses, n), || {
            burmester_curves(&poses, n)
        });
    });
}

#[test]
fn sweep_structural_error_charts() {
    use tmm::draw::{structural_error, Style};
    use tmm::synthesis::Spacing;
    let deg = f64::to_radians;
    let need = FunctionRequirement {
        x_range: [1.0, 2.0],
        crank_range: [deg(-30.0), deg(30.0)],
        rocker_range: [deg(0.0), deg(90.0)],
        frame: 0.1,
        spacing: Spacing::Chebyshev,
    };
    let made = function_generator(f64::log10, &need, &Options::default()).unwrap();
    let mut g = Gen::new(89);
    let mut charts = 0;
    for case in 0..cases().div_ceil(10) {
        let mut generator = made.clone();
        match g.next() % 5 {
            0 => generator.coefficients[(g.next() % 3) as usize] = g.f(),
            1 => generator.requirement.x_range[(g.next() % 2) as usize] = g.f(),
            2 => generator.y_range[(g.next() % 2) as usize] = g.f(),
            3 => generator.precision_x.push(g.f()),
            _ => {}
        }
        let mut style = Style {
            samples: 2 + (g.next() % 200) as usize,
            ..Style::default()
        };
        match g.next() % 6 {
            0 => style.margin = g.f(),
            1 => style.line_width = g.f(),
            2 => style.width = (g.next() % 12_000) as u32,
            3 => style.samples = (g.next() % 5) as usize,
            _ => {}
        }
        // The wanted function: log10, or one that gives hostile values.
        let kind = g.next() % 3;
        let hostile = g.f();
        let f = move |x: f64| match kind {
            0 => x.log10(),
            1 => hostile,
            _ => x.log10() * hostile,
        };
        let what = format!("case {case}: {generator:?} {style:?} f kind {kind} ({hostile})");
        check("draw::structural_error", &what, || {
            let chart = structural_error(&generator, f, &style)?;
            assert_finite_svg(&chart.svg, &what);
            charts += 1;
            Ok(chart.panels)
        });
        check("FunctionGenerator::structural_error", &what, || {
            generator.structural_error(f, style.samples)
        });
    }
    println!("{charts} structural error charts drawn and scanned");
    assert!(charts > 0 || cases() < 10);
}

#[test]
fn sweep_workspaces() {
    use tmm::draw::{workspace, Style};
    let plan = Plan::new(&bundled::five_bar_robot()).unwrap();
    let points = ["B", "C", "D", "nowhere"];
    let mut g = Gen::new(97);
    let mut pictures = 0;
    for case in 0..cases().div_ceil(200) {
        // Coarse grids (the refinement's cost is samples² · resolution): hostile ranges.
        let mut options = WorkspaceOptions::default()
            .with_samples(8 + (g.next() % 24) as usize)
            .with_resolution(8 + (g.next() % 40) as usize);
        for i in 0..2 {
            if g.next().is_multiple_of(3) {
                options = options.with_range(i, g.f(), g.f());
            }
        }
        // Counts out of range (8 to 2000 nodes, 8 to 4000 cells) are refused before any work.
        if g.next().is_multiple_of(8) {
            options.samples = [0, 7, 2001, usize::MAX][(g.next() % 4) as usize];
        }
        if g.next().is_multiple_of(8) {
            options.resolution = [0, 7, 4001, usize::MAX][(g.next() % 4) as usize];
        }
        let point = points[(g.next() % points.len() as u64) as usize];
        let mut style = Style::default();
        match g.next() % 4 {
            0 => style.margin = g.f(),
            1 => style.hinge_radius = g.f(),
            2 => style.width = (g.next() % 12_000) as u32,
            _ => {}
        }
        let what = format!("case {case}: {point} {options:?} {style:?}");
        check("Plan::workspace", &what, || {
            let ws = plan.workspace(point, &options)?;
            assert!(ws.region.area().is_finite(), "{what}");
            check("draw::workspace", &what, || {
                let pic = workspace(&plan, &ws, &style)?;
                assert_finite_svg(&pic.svg, &what);
                pictures += 1;
                Ok(pic.frame)
            });
            Ok((ws.boundary, ws.singular, ws.region.origin, ws.region.cell))
        });
    }
    println!("{pictures} workspace pictures drawn and scanned");
    assert!(pictures > 0 || cases() < 2000);
}

/// Was a defect (fixed): a ternary link of 2.9e-261 m (B3 at 1e-300 m)
/// gives two modes with `det: inf` and `-inf` in an `Ok`.
#[test]
fn repro_slider_triad_degenerate_ternary() {
    let dims = SliderTriadDims {
        pair: SlidingPair::Inner {
            angle: 0.6131172605895407,
            offset: 0.48590558384976057,
        },
        l: [1.0, 1.0],
        l_b1b2: 2.8836329346400556e-261,
        b3_along: 1e-300,
        b3_across: 0.0,
    };
    let first = Guide::fixed(Point2::new(-2.0, 0.0), 3.5637498953343983e-273);
    let a = [Point2::new(1.6, 0.8), Point2::new(0.5, 1.8)];
    check("slider_triad_modes", &dims, || {
        slider_triad_modes(&first, a, &dims)
    });
}

/// Was a defect (fixed): a load of 10¹⁵⁵ N on binary link 1 gives
/// R_A1 ≈ 9.7e154 N (finite) but `pressure: inf` in an `Ok` (|R| through R², 10³⁰⁹).
#[test]
fn repro_triad_friction_overflowing_pressure() {
    let mut t = worked_triad_friction(0.01);
    t.triad.loads[0] = Load::new(
        Point2::new(0.2483104554069141, 0.9505200837930332),
        Vector2::new(-1e155, -4.703608630422799e-221),
        1e-300,
    );
    t.joints.a[0] = Hinge { rho: 1000.0 };
    t.joints.b[0] = Hinge {
        rho: 0.3978690523496686,
    };
    t.rates = TriadRates {
        outer: [0.0; 3],
        binary: [-0.0, 0.40483659570963054, 0.0],
        ternary: 0.4592036254460079,
    };
    check("TriadFriction::solve", &t, || t.solve());
}
