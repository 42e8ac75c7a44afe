//! The gallery of published linkages (`bundled::gallery`), each against the figure it is
//! known for and against an independent solve written here: every position rebuilt by
//! circle–circle intersections from the link lengths (the assembly modes taken from the file's
//! reference pose), the balancing moment by virtual power, the reactions by one LU solve of the
//! whole linkage.

use super::engine::lu_difference;
use nalgebra::{Point2, Vector2};
use std::f64::consts::{FRAC_PI_2, TAU};
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, Course, Linkage, Plan, Sweep};

type P = Point2<f64>;

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The point at distance `r1` from `c1` and `r2` from `c2` on the side `side` (+1: left of
/// c1 → c2).
pub(super) fn meet(c1: P, r1: f64, c2: P, r2: f64, side: f64) -> P {
    let d = c2 - c1;
    let l = d.norm();
    let a = (r1 * r1 - r2 * r2 + l * l) / (2.0 * l);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let u = d / l;
    c1 + a * u + side * h * Vector2::new(-u.y, u.x)
}

/// The side of `p` from the line c1 → c2.
fn side_of(c1: P, c2: P, p: P) -> f64 {
    cross(c2 - c1, p - c1).signum()
}

/// `p` turned with the rigid body that takes `from` (about `o`) to `to`.
fn carry(o: P, from: P, to: P, p: P) -> P {
    let ang = (to - o).y.atan2((to - o).x) - (from - o).y.atan2((from - o).x);
    let (s, c) = ang.sin_cos();
    let r = p - o;
    o + Vector2::new(c * r.x - s * r.y, s * r.x + c * r.y)
}

/// The reference position of joint or point `name` in a description.
fn at(l: &Linkage, name: &str) -> P {
    if let Some(j) = l.joints.iter().find(|j| j.name == name) {
        return Point2::from(j.at);
    }
    let p = l
        .links
        .iter()
        .flat_map(|k| &k.points)
        .find(|p| p.name == name)
        .unwrap();
    Point2::from(p.at)
}

fn dist(l: &Linkage, a: &str, b: &str) -> f64 {
    (at(l, a) - at(l, b)).norm()
}

/// A crank about `o` through the reference point `a0`, at the input angle `phi` when the
/// crank's reference angle is `phi0`.
fn crank(o: P, a0: P, phi0: f64, phi: f64) -> P {
    let (s, c) = (phi - phi0).sin_cos();
    let r = a0 - o;
    o + Vector2::new(c * r.x - s * r.y, s * r.x + c * r.y)
}

/// The engine's position of joint or point `name` at the input angle `phi`.
fn engine(plan: &Plan, phi: f64, name: &str) -> P {
    let k = plan.kinematics(Motion::fixed(phi)).unwrap();
    k.joint(name)
        .or_else(|_| k.point(name))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .p
}

/// Every gallery linkage plans, runs its course (a turn, or rocking between its locks) and
/// balances by virtual power and by the LU solve of the whole linkage at every position
/// inside its range.
#[test]
fn every_gallery_linkage_runs_its_course_and_balances() {
    let mut report = Vec::new();
    for l in bundled::gallery() {
        let plan = Plan::new(&l).unwrap_or_else(|e| panic!("{}: {e}", l.name));
        let course = Course::new(&plan, l.output.as_ref(), 72, 10.0)
            .unwrap_or_else(|e| panic!("{}: {e}", l.name));
        // The power check's gap against the largest balancing moment of the course (at an
        // output's extreme every load's power may vanish, and with it the check's own scale).
        let (mut gap, mut biggest, mut lu, mut eq) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for m in &course.inputs {
            if m.rate == 0.0 {
                continue; // a rocking input's turning points: the locks, singular rates
            }
            let a = plan
                .analyse(Motion::new(m.value, m.rate, 3.0))
                .unwrap_or_else(|e| panic!("{} at {}: {e}", l.name, m.value));
            let pc = a.power_check().unwrap();
            gap = gap.max((pc.chain - pc.virtual_power).abs());
            biggest = biggest.max(pc.chain.abs());
            lu = lu.max(lu_difference(&plan, &a));
            eq = eq.max(a.worst_residual());
        }
        let vp = gap / biggest;
        report.push(format!(
            "{}: {:?}, virtual power {vp:.1e}, LU {lu:.1e}, equilibrium {eq:.1e}",
            l.name, course.sweep
        ));
        assert!(
            vp < 1e-9 && lu < 1e-10 && eq < 1e-12,
            "{}",
            report.last().unwrap()
        );
    }
    println!("{}", report.join("\n"));
}

/// Peaucellier–Lipkin: the input rocks between the angles where the rhombus folds,
/// ±2·acos((l − s)/(2r)) about O1's direction, and P stays on x = (l² − s²)/(2r).
#[test]
fn peaucellier_draws_an_exact_straight_line_over_its_range() {
    let l = bundled::peaucellier_lipkin();
    let plan = Plan::new(&l).unwrap();
    let (r, long, side) = (dist(&l, "O", "O1"), dist(&l, "O", "C"), dist(&l, "A", "C"));
    let line = (long * long - side * side) / (2.0 * r);
    let lock = 2.0 * ((long - side) / (2.0 * r)).acos();
    // The crank's angle is measured from O1 to A: |OA| = 2r·cos(φ/2).
    let course = Course::new(&plan, None, 400, 1.0).unwrap();
    let Sweep::Rocking { from, to } = course.sweep else {
        panic!("{:?}", course.sweep)
    };
    let gap = |a: f64, b: f64| {
        ((a - b + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI).abs()
    };
    assert!(
        gap(from, -lock) < 1e-12 && gap(to, lock) < 1e-12,
        "locks {from} {to} vs ±{lock}"
    );
    let size = plan.size();
    let (mut inside, mut at_locks) = (0.0f64, 0.0f64);
    for m in &course.inputs {
        let p = engine(&plan, m.value, "P");
        let off = (p.x - line).abs() / size;
        if m.rate == 0.0 {
            at_locks = at_locks.max(off);
        } else {
            inside = inside.max(off);
        }
    }
    println!(
        "Peaucellier: P off its line by {inside:.1e} of the size inside the range, {at_locks:.1e} \
         at the locks (the rhombus folded: C = D)"
    );
    assert!(inside < 1e-12, "{inside:e}");
    // At the locks C and D are 10⁻⁸ m from the fold: their difference's direction carries
    // their coordinates' rounding over |CD| (1.6e-10 of the size off the line when P's dyad
    // took it from there); P's dyad is solved in the twin sides' frame, its base direction
    // the normal of O A (tests/linkage/twins.rs).
    assert!(at_locks < 1e-12, "{at_locks:e}");
}

/// The independent Chebyshev linkage: frame A0B0, crossed cranks, P the coupler's middle.
struct Chebyshev {
    a0: P,
    b0: P,
    a_ref: P,
    phi0: f64,
    coupler: f64,
    rocker: f64,
    side: f64,
}

impl Chebyshev {
    fn new(l: &Linkage) -> Self {
        let (a0, b0, a, b) = (at(l, "A0"), at(l, "B0"), at(l, "A"), at(l, "B"));
        Self {
            a0,
            b0,
            a_ref: a,
            phi0: (a - a0).y.atan2((a - a0).x),
            coupler: (b - a).norm(),
            rocker: (b - b0).norm(),
            side: side_of(a, b0, b),
        }
    }

    /// A, B and P at the input angle `phi`.
    fn at(&self, phi: f64) -> (P, P, P) {
        let a = crank(self.a0, self.a_ref, self.phi0, phi);
        let b = meet(a, self.coupler, self.b0, self.rocker, self.side);
        (a, b, Point2::from((a.coords + b.coords) / 2.0))
    }
}

/// Chebyshev's linkage: P at the height 4a in the middle and at both ends of its stroke of
/// 4a (where a crank stands vertical: the input at its lock atan2(3, 4), and at π/2), exactly;
/// in between its largest deviation, from a dense scan of the engine, equals the independent
/// solve's, and is of the published order: a few thousandths of the stroke (we find 0.24 %).
#[test]
fn chebyshev_is_straight_at_three_points_and_nearly_between() {
    let l = bundled::chebyshev_straight_line();
    let plan = Plan::new(&l).unwrap();
    let ch = Chebyshev::new(&l);
    let a = ch.coupler / 2.0;
    let size = plan.size();
    let height = 4.0 * a;
    for phi in [4.0f64.atan2(3.0), FRAC_PI_2] {
        let p = engine(&plan, phi, "P");
        assert!((p.y - height).abs() < 1e-12 * size, "φ = {phi}: {}", p.y);
    }
    // The third, (4a, 4a), is where the input locks (B0, A, B in a line): the lock the engine
    // finds is within rounding of atan2(3, 4), where P moves as the root of the distance.
    let (lo, _) = plan.lock_positions(1.0).unwrap().unwrap();
    assert!((lo - 3.0f64.atan2(4.0)).abs() < 1e-12, "{lo}");
    let p = engine(&plan, lo, "P");
    assert!(
        (p - Point2::new(4.0 * a, height)).norm() < 1e-7 * size,
        "{p}"
    );
    let hi = FRAC_PI_2;
    let n = 4000;
    let (mut dev_engine, mut dev_own, mut agree) = (0.0f64, 0.0f64, 0.0f64);
    let (mut xmin, mut xmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..=n {
        let phi = lo + (hi - lo) * f64::from(k) / f64::from(n);
        let p = engine(&plan, phi, "P");
        let (_, _, q) = ch.at(phi);
        // Within 0.01 rad of the lock both solves lose digits to the tangency (the
        // position moves as the root of the gap): compared there to 1e-8.
        let gap = (p - q).norm() / size;
        if phi - lo > 0.01 {
            agree = agree.max(gap);
        } else {
            assert!(gap < 1e-8, "φ = {phi}: {gap:e}");
        }
        dev_engine = dev_engine.max((p.y - height).abs());
        dev_own = dev_own.max((q.y - height).abs());
        xmin = xmin.min(p.x);
        xmax = xmax.max(p.x);
    }
    let stroke = xmax - xmin;
    println!(
        "Chebyshev: stroke {stroke:.6} m (4a = {:.6}), largest deviation {dev_engine:.4e} m = \
         {:.3} % of the stroke; engine vs own solve {agree:.1e} of the size",
        4.0 * a,
        100.0 * dev_engine / stroke
    );
    assert!(agree < 1e-12, "{agree:e}");
    assert!((stroke - 4.0 * a).abs() < 1e-7 * size, "{stroke}");
    assert!((dev_engine - dev_own).abs() < 1e-12 * size);
    assert!(dev_engine / stroke > 1e-3 && dev_engine / stroke < 1e-2);
}

/// Hoekens' linkage is the cognate of Chebyshev's: with its crank parallel to Chebyshev's
/// coupler (A → B), its point P is Chebyshev's P (Roberts–Chebyshev), over all of
/// Chebyshev's range; and its crank turns fully.
#[test]
fn hoekens_is_chebyshevs_cognate() {
    let cheb = Plan::new(&bundled::chebyshev_straight_line()).unwrap();
    let hoek = Plan::new(&bundled::hoekens_straight_line()).unwrap();
    assert_eq!(
        Course::new(&hoek, None, 12, 1.0).unwrap().sweep,
        Sweep::Turn
    );
    let course = Course::new(&cheb, None, 720, 1.0).unwrap();
    let size = cheb.size();
    let mut worst = 0.0f64;
    for m in course.inputs.iter().filter(|m| m.rate != 0.0) {
        let k = cheb.kinematics(Motion::fixed(m.value)).unwrap();
        let coupler = k.link("coupler").unwrap().value;
        let p = k.point("P").unwrap().p;
        let q = engine(&hoek, coupler, "P");
        worst = worst.max((p - q).norm() / size);
    }
    println!("Hoekens vs Chebyshev: P apart by {worst:.1e} of the size");
    assert!(worst < 1e-12, "{worst:e}");
}

/// Jansen's leg, rebuilt here from the holy numbers' link lengths, over a full turn; the
/// foot's path is flat-bottomed: within 1 % of the step of its lowest point for more than a
/// third of the turn, over more than 70 % of the step.
#[test]
fn jansens_leg_walks_on_a_flat_foot() {
    let l = bundled::jansen_leg();
    let plan = Plan::new(&l).unwrap();
    // The holy numbers, in the file's metres.
    let holy = [
        ("Z", "Y", 41.5),
        ("Z", "W", 39.3),
        ("Z", "U", 40.1),
        ("Y", "U", 55.8),
        ("U", "V", 39.4),
        ("W", "V", 36.7),
        ("V", "foot", 65.7),
        ("W", "foot", 49.0),
        ("X", "Y", 50.0),
        ("X", "W", 61.9),
        ("O", "X", 15.0),
    ];
    for (a, b, len) in holy {
        assert!((dist(&l, a, b) - len / 100.0).abs() < 1e-12, "{a}{b}");
    }
    let z = at(&l, "Z");
    assert!((z - Point2::new(-0.38, -0.078)).norm() < 1e-15);
    let name = |n: &str| at(&l, n);
    let sides = [
        side_of(name("X"), z, name("Y")),
        side_of(name("X"), z, name("W")),
        side_of(z, name("Y"), name("U")),
        side_of(name("U"), name("W"), name("V")),
        side_of(name("W"), name("V"), name("foot")),
    ];
    let phi0 = plan.reference_input();
    let size = plan.size();
    let (mut worst, mut feet) = (0.0f64, Vec::new());
    for k in 0..720 {
        let phi = phi0 + TAU * f64::from(k) / 720.0;
        let x = crank(name("O"), name("X"), phi0, phi);
        let y = meet(x, 0.5, z, 0.415, sides[0]);
        let w = meet(x, 0.619, z, 0.393, sides[1]);
        let u = meet(z, 0.401, y, 0.558, sides[2]);
        let v = meet(u, 0.394, w, 0.367, sides[3]);
        let foot = meet(w, 0.49, v, 0.657, sides[4]);
        let e = engine(&plan, phi, "foot");
        worst = worst.max((e - foot).norm() / size);
        feet.push(e);
    }
    let low = feet.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    let span = |ps: &[&P]| {
        let xs = ps.iter().map(|p| p.x);
        xs.clone().fold(f64::NEG_INFINITY, f64::max) - xs.fold(f64::INFINITY, f64::min)
    };
    let step = span(&feet.iter().collect::<Vec<_>>());
    let stance: Vec<&P> = feet.iter().filter(|p| p.y < low + 0.01 * step).collect();
    let share = stance.len() as f64 / feet.len() as f64;
    let lift = feet.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max) - low;
    println!(
        "Jansen: step {step:.4} m, lift {lift:.4} m, flat (1 % of the step) over {:.0} % of the \
         turn and {:.0} % of the step; engine vs own solve {worst:.1e} of the size",
        100.0 * share,
        100.0 * span(&stance) / step
    );
    assert!(worst < 1e-12, "{worst:e}");
    assert!(share > 1.0 / 3.0 && span(&stance) > 0.7 * step);
    assert!(lift > 0.2 * step, "the foot lifts to come back: {lift}");
}

/// The Watt II and Stephenson six-bars rebuilt here by circle intersections over a turn.
#[test]
fn the_six_bars_agree_with_their_own_solve() {
    // Watt II: O1–A–B–O3 then O3's rocker (B, C) – D – O5.
    let l = bundled::watt_ii_six_bar();
    let plan = Plan::new(&l).unwrap();
    let n = |s: &str| at(&l, s);
    let (sb, sd) = (
        side_of(n("A"), n("O3"), n("B")),
        side_of(n("C"), n("O5"), n("D")),
    );
    let phi0 = plan.reference_input();
    let mut worst = 0.0f64;
    for k in 0..360 {
        let phi = phi0 + TAU * f64::from(k) / 360.0;
        let a = crank(n("O1"), n("A"), phi0, phi);
        let b = meet(a, dist(&l, "A", "B"), n("O3"), dist(&l, "O3", "B"), sb);
        let c = carry(n("O3"), n("B"), b, n("C"));
        let d = meet(c, dist(&l, "C", "D"), n("O5"), dist(&l, "O5", "D"), sd);
        worst = worst.max((engine(&plan, phi, "D") - d).norm() / plan.size());
    }
    assert!(worst < 1e-12, "Watt II: {worst:e}");
    assert_eq!(plan.groups().len(), 2);

    // Stephenson: the ternary crank (A, E) and rocker (B, F), the dyad E–G–F.
    let l = bundled::stephenson_ii_six_bar();
    let plan = Plan::new(&l).unwrap();
    let n = |s: &str| at(&l, s);
    let (sb, sg) = (
        side_of(n("A"), n("O3"), n("B")),
        side_of(n("E"), n("F"), n("G")),
    );
    let phi0 = plan.reference_input();
    let mut worst2 = 0.0f64;
    for k in 0..360 {
        let phi = phi0 + TAU * f64::from(k) / 360.0;
        let a = crank(n("O1"), n("A"), phi0, phi);
        let e = crank(n("O1"), n("E"), phi0, phi);
        let b = meet(a, dist(&l, "A", "B"), n("O3"), dist(&l, "O3", "B"), sb);
        let f = carry(n("O3"), n("B"), b, n("F"));
        let g = meet(e, dist(&l, "E", "G"), f, dist(&l, "F", "G"), sg);
        worst2 = worst2.max((engine(&plan, phi, "G") - g).norm() / plan.size());
    }
    println!("own solve vs engine: Watt II {worst:.1e}, Stephenson {worst2:.1e} of the size");
    assert!(worst2 < 1e-12, "Stephenson: {worst2:e}");
    assert_eq!(plan.groups().len(), 2);
}

/// A rocking input's extremes and stroke: the Peaucellier tracer's stroke along its line is
/// 2·r·sin(lock)·(l + s)/(l − s) (P is A's inverse, |OA| = l − s at the locks), and
/// Chebyshev's P sweeps in x what an independent dense scan of its range finds.
#[test]
fn rocking_inputs_have_strokes_and_extremes() {
    use tmm::kinematics::ExtremeKind;
    use tmm::linkage::Output;
    let l = bundled::peaucellier_lipkin();
    let plan = Plan::new(&l).unwrap();
    let (r, long, side) = (dist(&l, "O", "O1"), dist(&l, "O", "C"), dist(&l, "A", "C"));
    let lock = 2.0 * ((long - side) / (2.0 * r)).acos();
    let expect = 2.0 * r * lock.sin() * (long + side) / (long - side);
    let y = Output::Y("P".into());
    let ext = plan.rocking_extremes(&y).unwrap();
    assert_eq!(ext.len(), 2, "{ext:?}");
    let stroke = plan.rocking_stroke(&y).unwrap();
    println!("Peaucellier: stroke {stroke:.12} m, closed form {expect:.12} m");
    assert!(
        (stroke - expect).abs() < 1e-7 * plan.size(),
        "{stroke} {expect}"
    );
    assert!(ext[0].kind != ext[1].kind);

    let l = bundled::chebyshev_straight_line();
    let plan = Plan::new(&l).unwrap();
    let ch = Chebyshev::new(&l);
    let x = Output::X("P".into());
    let ext = plan.rocking_extremes(&x).unwrap();
    let (lo, hi) = plan.lock_positions(1.0).unwrap().unwrap();
    let n = 20000;
    let xs: Vec<f64> = (0..=n)
        .map(|k| ch.at(lo + (hi - lo) * f64::from(k) / f64::from(n)).2.x)
        .collect();
    let own = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - xs.iter().cloned().fold(f64::INFINITY, f64::min);
    let stroke = plan.rocking_stroke(&x).unwrap();
    println!(
        "Chebyshev: x stroke {stroke:.9} m over {} extremes, own scan {own:.9} m",
        ext.len()
    );
    assert!((stroke - own).abs() < 1e-7 * plan.size(), "{stroke} {own}");
    // The two locks end the list, where the input reverses: each is an extreme of the output
    // on the one side the input reaches; between them the output stands still.
    assert!(ext.len() >= 2, "{ext:?}");
    let (first, last) = (ext[0], ext[ext.len() - 1]);
    // Angles compared a turn apart (an extreme's input lies in [0, 2π)).
    let near = |a: f64, b: f64| ((a - b) - TAU * ((a - b) / TAU).round()).abs() < 1e-12;
    for (e, lock) in [(first, lo), (last, hi)] {
        let ends = near(e.input, lo) || near(e.input, hi);
        assert!(ends, "{e:?} not at a lock ({lo}, {hi})");
        let inward = if near(e.input, lo) { 1e-4 } else { -1e-4 };
        let side = ch.at(e.input + inward).2.x - e.output.value;
        assert_eq!(
            e.kind == ExtremeKind::Max,
            side < 0.0,
            "{e:?} at the lock {lock}"
        );
    }
    for e in &ext[1..ext.len() - 1] {
        assert!(e.output.rate.abs() < 1e-9, "{e:?}");
        let side = (ch.at(e.input + 1e-4).2.x + ch.at(e.input - 1e-4).2.x) / 2.0 - e.output.value;
        assert_eq!(e.kind == ExtremeKind::Max, side < 0.0, "{e:?}");
    }
    // An input that turns fully is sent to Plan::extremes.
    let turns = Plan::new(&bundled::hoekens_straight_line()).unwrap();
    assert!(turns.rocking_extremes(&x).is_err());
}

/// A group above the 3rd class (the double butterfly's six links) has no transmission angle:
/// an error naming it, not π/2; the table leaves its column out and keeps every other
/// group's (the triad six-bar's, each between 0 and π/2).
#[test]
fn a_general_group_has_no_transmission_angle() {
    use tmm::linkage::GroupKind;
    let plan = Plan::new(&bundled::double_butterfly()).unwrap();
    let phi = plan.reference_input();
    let k = plan.kinematics(Motion::fixed(phi)).unwrap();
    let general: Vec<usize> = (0..plan.groups().len())
        .filter(|&g| plan.groups()[g].kind == GroupKind::General)
        .collect();
    assert!(!general.is_empty());
    for &g in &general {
        let e = k.transmission_angle(g).unwrap_err().to_string();
        assert!(
            e.contains("3rd class") && e.contains(&plan.groups()[g].name),
            "{e}"
        );
        assert!(plan.min_transmission_angle(g).is_err());
    }
    let inputs: Vec<Motion> = (0..3)
        .map(|i| Motion::turning(phi + 0.01 * f64::from(i), 1.0))
        .collect();
    let table = plan.table(inputs.iter().copied());
    assert_eq!(table.len(), 3);
    let mu = |t: &tmm::linkage::Table| {
        t.columns
            .iter()
            .filter(|c| c.name.starts_with("mu("))
            .map(|c| c.values.clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        mu(&table).len(),
        plan.groups().len() - general.len(),
        "{:?}",
        table.columns.iter().map(|c| &c.name).collect::<Vec<_>>()
    );
    let triad = Plan::new(&bundled::six_bar_triad()).unwrap();
    let t = triad
        .table((0..3).map(|i| Motion::turning(triad.reference_input() + 0.01 * f64::from(i), 1.0)));
    let columns = mu(&t);
    assert_eq!(columns.len(), triad.groups().len());
    assert!(columns
        .iter()
        .flatten()
        .all(|m| (0.0..=FRAC_PI_2).contains(m)));
}
