//! Kinematic synthesis on built-in requirements: each kind of `tmm::synthesis` produces a
//! linkage description, whose report is printed and which the engine then analyses (its time
//! ratio, stroke and smallest transmission angle printed beside the report's). The
//! descriptions are written as JSON files to `target/tmm-charts/synthesis/`, ready for
//! `cargo run --example linkage -- FILE`, each beside its picture (SVG): the linkage with
//! what it was made for drawn on it (the path of a joint, the positions or precision
//! points, the poses, Burmester's curves, the target points), and the structural error of
//! the function generators.
//!
//! ```sh
//! cargo run --release --example synthesis
//! ```

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::fs;
use std::path::Path;
use tmm::draw::{structural_error, synthesis_scheme, Style, Targets};
use tmm::kinematics::{Motion, Rotation};
use tmm::linkage::{Output, Plan};
use tmm::synthesis::{
    burmester, burmester_curves, burmester_points, centre_point, centre_point_curve, crank_rocker,
    crank_rocker_through, four_bar_from_dyads, function_generator, path_generator, shaper,
    six_bar_path_generator, slider_crank, CrankRockerRequirement, FrameChoice, FunctionRequirement,
    OffsetChoice, Options, PathOptions, PathRequirement, Pose, ShaperRequirement,
    SliderCrankRequirement, Spacing, Synthesis, Timing,
};

fn deg(x: f64) -> f64 {
    x.to_radians()
}

/// Prints the report, the engine's figures for `output`, and writes the description to
/// `dir/stem.json`.
fn show(s: &Synthesis, output: &Output, dir: &Path, stem: &str) -> tmm::Result<()> {
    print!("{}", s.report);
    let plan = Plan::new(&s.linkage)?;
    if plan.input_is_crank() && s.report.time_ratio.is_some() {
        let st = plan.strokes(output, Rotation::Ccw)?;
        println!(
            "  engine: K = {:.10}, stroke/swing = {:.10} (m or rad)",
            st.time_ratio, st.stroke
        );
    }
    let file = dir.join(format!("{stem}.json"));
    if let Err(e) = s
        .linkage
        .to_json()
        .map(|json| fs::write(&file, json).map_err(|e| e.to_string()))
    {
        println!("  (not written: {e})");
    } else {
        println!("  description: {}", file.display());
    }
    println!();
    Ok(())
}

fn run_example() -> tmm::Result<()> {
    let dir = Path::new("target/tmm-charts/synthesis");
    if let Err(e) = fs::create_dir_all(dir) {
        println!("cannot create {}: {e}", dir.display());
    }
    let options = Options::default();
    let rocker = Output::Angle("rocker".to_owned());

    println!("== crank-rocker by K and the swing: rocker 300 mm, swing 45°, K = 1.25 ==");
    let need = CrankRockerRequirement {
        rocker: 0.3,
        swing: deg(45.0),
        time_ratio: 1.25,
        frame: FrameChoice::BestTransmission,
    };
    let best = crank_rocker(&need, &options)?;
    show(&best, &rocker, dir, "crank-rocker")?;
    let plan = Plan::new(&best.linkage)?;
    picture(
        &best,
        plan.reference_input(),
        &Targets::points(&[], "B"),
        dir,
        "crank-rocker",
    )?;
    let longer = CrankRockerRequirement {
        frame: FrameChoice::Length(1.2 * best.report.dimension("frame").unwrap_or(0.5)),
        ..need
    };
    println!("== the same with a frame 20 % longer than the best one's ==");
    match crank_rocker(&longer, &options) {
        Ok(s) => show(&s, &rocker, dir, "crank-rocker-longer-frame")?,
        Err(e) => println!("  {e}\n"),
    }

    println!("== offset slider-crank: stroke 200 mm, K = 1.2, offset for the best transmission ==");
    let sc = slider_crank(
        &SliderCrankRequirement {
            stroke: 0.2,
            time_ratio: 1.2,
            offset: OffsetChoice::BestTransmission,
        },
        &options,
    )?;
    show(&sc, &Output::Slide("P".to_owned()), dir, "slider-crank")?;
    picture(&sc, 0.0, &Targets::points(&[], "A"), dir, "slider-crank")?;

    println!("== shaper: ram stroke 300 mm, K = 1.6, O1O3 = 250 mm ==");
    let sh = shaper(
        &ShaperRequirement {
            stroke: 0.3,
            time_ratio: 1.6,
            centre_distance: 0.25,
        },
        &options,
    )?;
    show(&sh, &Output::Slide("G".to_owned()), dir, "shaper")?;
    picture(&sh, FRAC_PI_2, &Targets::points(&[], "D"), dir, "shaper")?;

    println!("== crank-rocker through three positions (frame 400 mm) ==");
    let pairs = [
        (deg(40.0), deg(101.4)),
        (deg(100.0), deg(112.8)),
        (deg(160.0), deg(131.8)),
    ];
    let loose = options.with_min_transmission_angle(0.0);
    let through = crank_rocker_through(0.4, &pairs, &loose)?;
    show(&through, &rocker, dir, "crank-rocker-through-positions")?;
    // The rocker's pin at the three given positions, on the path it traces.
    let at_pairs = joint_at(&through, "B", &pairs.map(|p| p.0))?;
    picture(
        &through,
        pairs[0].0,
        &Targets::points(&at_pairs, "B"),
        dir,
        "crank-rocker-through-positions",
    )?;

    println!("== function generator: y = log10 x on [1, 2], crank −30°..30°, rocker 0°..90° ==");
    let need = FunctionRequirement {
        x_range: [1.0, 2.0],
        crank_range: [deg(-30.0), deg(30.0)],
        rocker_range: [deg(0.0), deg(90.0)],
        frame: 0.1,
        spacing: Spacing::Chebyshev,
    };
    for spacing in [Spacing::Chebyshev, Spacing::LeastSquares(21)] {
        let g = function_generator(
            f64::log10,
            &FunctionRequirement { spacing, ..need },
            &options,
        )?;
        println!("-- {spacing:?}: precision x = {:.4?}", g.precision_x);
        let curve = g.structural_error(f64::log10, 401)?;
        let worst = curve
            .iter()
            .max_by(|a, b| a.error.abs().total_cmp(&b.error.abs()))
            .map_or((0.0, 0.0), |p| (p.x, p.error));
        println!(
            "  structural error (by the engine): largest {:.3e} at x = {:.3} ({:.2} % of the range of y)",
            worst.1,
            worst.0,
            100.0 * worst.1.abs() / 2f64.log10()
        );
        let stem = format!("function-generator-{}", g.precision_x.len());
        show(&g.synthesis, &rocker, dir, &stem)?;
        // The rocker's pin at the precision points; the structural error over the range.
        let phis: Vec<f64> = g.precision_x.iter().map(|&x| g.crank_angle(x)).collect();
        let at_precision = joint_at(&g.synthesis, "B", &phis)?;
        picture(
            &g.synthesis,
            g.crank_angle(need.x_range[0]),
            &Targets::points(&at_precision, "B"),
            dir,
            &stem,
        )?;
        let chart = structural_error(&g, f64::log10, &Style::default())?;
        write(dir, &format!("{stem}-structural-error"), &chart.svg);
    }

    println!("== Burmester: three poses of the coupler point P and its line ==");
    let poses = [
        Pose::new([0.0, 0.0], 0.0),
        Pose::new([0.1, 0.05], 0.3),
        Pose::new([0.2, 0.05], 0.7),
    ];
    let (za, zb) = ([-0.05, -0.1], [0.1, -0.08]);
    let s = burmester(&poses, za, zb, &loose)?;
    let crank = centre_point(&poses, za)?;
    let plan = Plan::new(&s.linkage)?;
    for (pose, phi) in poses.iter().zip(crank.angles(&poses)) {
        let k = plan.kinematics(Motion::fixed(phi))?;
        let p = k.point("P")?.p;
        println!(
            "  φ = {:8.3}°: P = ({:.6}, {:.6}) m (wanted ({:.6}, {:.6})), angle {:.6}° (wanted {:.6}°)",
            phi.to_degrees(),
            p.x,
            p.y,
            pose.at[0],
            pose.at[1],
            k.link("coupler")?.value.to_degrees(),
            pose.angle.to_degrees()
        );
    }
    show(
        &s,
        &Output::Angle("coupler".to_owned()),
        dir,
        "burmester-three-poses",
    )?;
    picture(
        &s,
        crank.angles(&poses)[0],
        &Targets::poses(&poses),
        dir,
        "burmester-three-poses",
    )?;

    println!("== Burmester: four poses, dyads from the centre-point curve ==");
    let four = [poses[0], poses[1], poses[2], Pose::new([0.28, 0.0], 1.0)];
    let curve = centre_point_curve(&four, 360)?;
    println!("  {} dyads sampled on the centre-point curve", curve.len());
    // The first pair of small dyads that makes a four-bar without a defect and with γ_min ≥ 30°.
    let small: Vec<_> = curve.iter().filter(|d| d.length() < 0.5).collect();
    let strict = options.with_min_transmission_angle(deg(30.0));
    let found = small.iter().enumerate().find_map(|(i, crank)| {
        small[i + 1..]
            .iter()
            .find_map(|rocker| four_bar_from_dyads(&four, crank, rocker, &strict).ok())
            .map(|s| (s, **crank))
    });
    match found {
        Some((s, crank)) => {
            let plan = Plan::new(&s.linkage)?;
            let mut worst = 0.0f64;
            for (pose, phi) in four.iter().zip(crank.angles(&four)) {
                let p = plan.kinematics(Motion::fixed(phi))?.point("P")?.p;
                worst = worst.max((p.x - pose.at[0]).hypot(p.y - pose.at[1]));
            }
            println!("  the engine misses the four poses' points by at most {worst:.2e} m");
            show(
                &s,
                &Output::Angle("coupler".to_owned()),
                dir,
                "burmester-four-poses",
            )?;
            picture(
                &s,
                crank.angles(&four)[0],
                &Targets::poses(&four).with_burmester_curves(&burmester_curves(&four, 720)?),
                dir,
                "burmester-four-poses",
            )?;
        }
        None => println!("  no pair of small dyads without a defect and with γ_min ≥ 30°\n"),
    }

    println!("== Burmester: five poses read off a crank-rocker's coupler, its points ==");
    // The crank-rocker O1 = (0, 0), O3 = (0.4, 0), crank 0.1, coupler 0.35, rocker 0.3 m; the
    // coupler point 0.1 m left of the middle of AB.
    let (a, b, c, d) = (0.1, 0.35, 0.3, 0.4);
    let pose = |phi: f64| {
        let (ax, ay) = (a * phi.cos(), a * phi.sin());
        let (vx, vy) = (d - ax, -ay);
        let e = vx.hypot(vy);
        let along = (b * b - c * c + e * e) / (2.0 * e);
        let h = (b * b - along * along).sqrt();
        let (bx, by) = (
            ax + along * vx / e - h * vy / e,
            ay + along * vy / e + h * vx / e,
        );
        let (ux, uy) = ((bx - ax) / b, (by - ay) / b);
        Pose::new(
            [ax + 0.5 * b * ux - 0.1 * uy, ay + 0.5 * b * uy + 0.1 * ux],
            uy.atan2(ux),
        )
    };
    let five = [0.3, 0.9, 1.6, 2.4, 3.0].map(pose);
    let points = burmester_points(&five)?;
    for p in &points {
        println!(
            "  centre point ({:9.6}, {:9.6}) m, circle point ({:9.6}, {:9.6}) m",
            p.centre[0], p.centre[1], p.circle[0], p.circle[1]
        );
    }
    println!("  (the crank's pivot (0, 0) and the rocker's (0.4, 0) among them)\n");
    // The four-bar of the first two of Burmester's points that make one without a defect.
    let pair = points.iter().enumerate().find_map(|(i, c)| {
        points[i + 1..].iter().find_map(|r| {
            four_bar_from_dyads(&five, c, r, &loose)
                .ok()
                .map(|s| (s, *c))
        })
    });
    if let Some((s5, crank5)) = pair {
        show(
            &s5,
            &Output::Angle("coupler".to_owned()),
            dir,
            "burmester-five-poses",
        )?;
        let first_four = [five[0], five[1], five[2], five[3]];
        picture(
            &s5,
            crank5.angles(&five)[0],
            &Targets::poses(&five).with_burmester_curves(&burmester_curves(&first_four, 720)?),
            dir,
            "burmester-five-poses",
        )?;
    }

    println!("== path generation: a four-bar through 24 points of a closed curve ==");
    // The points: the coupler curve of the crank-rocker above, in 24 steps of the crank.
    let closed: Vec<[f64; 2]> = (0..24).map(|k| pose(TAU * k as f64 / 24.0).at).collect();
    let req = PathRequirement {
        points: closed.clone(),
        timing: Timing::ClosedCurve,
    };
    let opts = PathOptions::default().with_population(40).with_designs(3);
    let designs = path_generator(&req, &opts, |_| true)?;
    for (i, d) in designs.iter().enumerate() {
        println!(
            "  design {}: mean miss {:.2e} m, largest {:.2e} m",
            i + 1,
            d.mean_error,
            d.max_error
        );
    }
    let first = &designs[0];
    show(&first.synthesis, &rocker, dir, "path-generator")?;
    picture(
        &first.synthesis,
        first.crank_angles[0],
        &Targets::points(&closed, "P"),
        dir,
        "path-generator",
    )?;
    picture(
        &s,
        crank.angles(&poses)[0],
        &Targets::poses(&four).with_burmester_curves(&burmester_curves(&four, 720)?),
        dir,
        "burmester-curves",
    )?;

    println!("== path generation: a Stephenson III six-bar through 8 points, timed ==");
    // The points: the tracer of a known six-bar (a crank, an RRR dyad, C on its coupler,
    // a second RRR dyad from C, P on its link CE) at crank angles 0.3 rad apart.
    let req = PathRequirement::six_bar_example()?;
    let traced = req.points.clone();
    let opts = PathOptions::default()
        .with_designs(1)
        .with_min_transmission_angle(0.3);
    let six = &six_bar_path_generator(&req, &opts, |_| true)?[0];
    println!(
        "  mean miss {:.2e} m, largest {:.2e} m",
        six.mean_error, six.max_error
    );
    show(
        &six.synthesis,
        &Output::Angle("output".to_owned()),
        dir,
        "six-bar-path-generator",
    )?;
    picture(
        &six.synthesis,
        six.crank_angles[0],
        &Targets::points(&traced, "P"),
        dir,
        "six-bar-path-generator",
    )?;

    println!("== requirements no mechanism meets ==");
    let hard = CrankRockerRequirement {
        time_ratio: 2.5,
        swing: deg(100.0),
        ..need_of(&best)
    };
    for r in [
        crank_rocker(&hard, &options),
        crank_rocker(
            &CrankRockerRequirement {
                time_ratio: 30.0,
                ..hard
            },
            &loose,
        ),
        crank_rocker(&CrankRockerRequirement { swing: PI, ..hard }, &options),
    ] {
        match r {
            Ok(s) => print!("{}", s.report),
            Err(e) => println!("  {e}"),
        }
    }
    Ok(())
}

/// Writes the scheme of `s` at the crank angle `phi` with `targets` drawn on it to
/// `dir/stem.svg`.
fn picture(s: &Synthesis, phi: f64, targets: &Targets, dir: &Path, stem: &str) -> tmm::Result<()> {
    let plan = Plan::new(&s.linkage)?;
    let pic = synthesis_scheme(&plan, Motion::fixed(phi), targets, &Style::default())?;
    write(dir, stem, &pic.svg);
    Ok(())
}

/// Writes `svg` to `dir/stem.svg`.
fn write(dir: &Path, stem: &str, svg: &str) {
    let file = dir.join(format!("{stem}.svg"));
    match fs::write(&file, svg) {
        Ok(()) => println!("  picture: {}\n", file.display()),
        Err(e) => println!("  (picture not written: {e})\n"),
    }
}

/// Where the engine puts the joint `name` of `s` at each crank angle.
fn joint_at(s: &Synthesis, name: &str, phis: &[f64]) -> tmm::Result<Vec<[f64; 2]>> {
    let plan = Plan::new(&s.linkage)?;
    phis.iter()
        .map(|&phi| {
            let p = plan.kinematics(Motion::fixed(phi))?.joint(name)?.p;
            Ok([p.x, p.y])
        })
        .collect()
}

/// The requirement of the first crank-rocker, for variations.
fn need_of(s: &Synthesis) -> CrankRockerRequirement {
    CrankRockerRequirement {
        rocker: s.report.dimension("rocker").unwrap_or(0.3),
        swing: s.report.stroke.unwrap_or(1.0),
        time_ratio: s.report.time_ratio.unwrap_or(1.2),
        frame: FrameChoice::BestTransmission,
    }
}

fn main() {
    if let Err(e) = run_example() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
