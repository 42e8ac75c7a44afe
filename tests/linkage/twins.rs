//! Twin dyads: a Peaucellier–Lipkin cell's two sides on O and A are mirror images about the
//! line O A, and the dyad that places the tracer P on them is solved in their frame, so P
//! stays on its line x = (l² − s²)/(2r) to 1e-12 of the size at the two lock angles (where
//! the rhombus folds, C = D), just inside them (10⁻¹⁶ … 10⁻⁶ rad) and at every row of the
//! course: for the bundled cell, for a copy of it scaled, turned and moved, and for cells of
//! other proportions (seeded). The reference is the line itself (P is A's inverse about O),
//! not the engine.

use super::gallery::meet;
use crate::common::fd::{cases, Rng};
use nalgebra::{Point2, Vector2};
use std::f64::consts::PI;
use tmm::kinematics::Motion;
use tmm::linkage::{bundled, Course, Linkage, Plan, Sweep};

type P = Point2<f64>;

/// The bound on P's distance from its line, as a fraction of the linkage's size.
const ON_LINE: f64 = 1e-12;

fn joint(l: &Linkage, name: &str) -> P {
    let j = l.joints.iter().find(|j| j.name == name).unwrap();
    Point2::from(j.at)
}

fn set(l: &mut Linkage, name: &str, p: P) {
    let j = l.joints.iter_mut().find(|j| j.name == name).unwrap();
    j.at = [p.x, p.y];
}

/// A Peaucellier cell's line and lock angles, from its description alone: O and O1 the
/// frame's pivots (|OO1| = r = |O1A|, so the crank carries A through O), l = |OC| = |OD|,
/// s = the rhombus's side. P lies on the line perpendicular to O O1 at (l² − s²)/(2r) from O;
/// the crank locks where |OA| = 2r·cos(φ/2) = l − s (φ from O O1's direction).
struct Cell {
    o: P,
    u: Vector2<f64>,
    at: f64,
    locks: [f64; 2],
}

impl Cell {
    fn of(l: &Linkage) -> Self {
        let (o, o1) = (joint(l, "O"), joint(l, "O1"));
        let r = (o1 - o).norm();
        let long = (joint(l, "C") - o).norm();
        let side = (joint(l, "C") - joint(l, "A")).norm();
        let u = (o1 - o) / r;
        let base = u.y.atan2(u.x);
        let lock = 2.0 * ((long - side) / (2.0 * r)).acos();
        Self {
            o,
            u,
            at: (long * long - side * side) / (2.0 * r),
            locks: [base - lock, base + lock],
        }
    }

    /// P's distance from the line.
    fn off(&self, p: P) -> f64 {
        ((p - self.o).dot(&self.u) - self.at).abs()
    }
}

/// The largest distances of P from its line (fractions of the size) at the locks
/// [`Plan::lock_positions`] finds, just inside them, and at the rows of the course; each
/// position solved at rest (`Plan::position`) and, inside, at the course's speed as well.
fn worst(l: &Linkage) -> [f64; 3] {
    let plan = Plan::new(l).unwrap();
    let cell = Cell::of(l);
    let size = plan.size();
    // At rest `Plan::position` is `Plan::kinematics` wherever that answers; within a few
    // ulps of a fold, where the twins' own closed form calls itself singular, it places them
    // by their position problem.
    let off = |phi: f64| {
        let at = plan
            .position(Motion::fixed(phi))
            .unwrap_or_else(|e| panic!("φ = {phi}: {e}"));
        cell.off(at.pose().joint("P").unwrap().p) / size
    };
    let (lo, hi) = plan
        .lock_positions(plan.reference_input())
        .unwrap()
        .unwrap();
    // The locks found are the closed form's to the search's 1e-12 rad (a turn apart at most).
    let turn = |a: f64, b: f64| ((a - b + PI).rem_euclid(2.0 * PI) - PI).abs();
    assert!(
        turn(lo, cell.locks[0]) < 1e-11 && turn(hi, cell.locks[1]) < 1e-11,
        "{lo} {hi} {:?}",
        cell.locks
    );
    let at_locks = off(lo).max(off(hi));
    let mut inside = 0.0f64;
    for k in 6..=16 {
        let delta = 10f64.powi(-k);
        inside = inside.max(off(lo + delta)).max(off(hi - delta));
    }
    let course = Course::new(&plan, None, 400, 1.0).unwrap();
    assert!(matches!(course.sweep, Sweep::Rocking { .. }));
    let mut rows = 0.0f64;
    for m in &course.inputs {
        rows = rows.max(off(m.value));
        if m.rate != 0.0 {
            let k = plan.kinematics(*m).unwrap();
            rows = rows.max(cell.off(k.joint("P").unwrap().p) / size);
        }
    }
    [at_locks, inside, rows]
}

/// A copy of `l` with every joint at t + k·R(α)·p.
fn moved(l: &Linkage, k: f64, alpha: f64, t: Vector2<f64>) -> Linkage {
    let mut out = l.clone();
    let (s, c) = alpha.sin_cos();
    for j in &mut out.joints {
        let [x, y] = j.at;
        j.at = [t.x + k * (c * x - s * y), t.y + k * (s * x + c * y)];
    }
    out
}

/// The bundled cell with its joints placed for the proportions r, l, s and the crank at
/// `theta` (from O O1's direction): A = O1 + r·e(θ), C and D the circles' meets, P = C + D − A.
fn cell(r: f64, long: f64, side: f64, theta: f64) -> Linkage {
    let mut l = bundled::peaucellier_lipkin();
    let (o, o1) = (Point2::origin(), Point2::new(r, 0.0));
    let a = o1 + r * Vector2::new(theta.cos(), theta.sin());
    let c = meet(o, long, a, side, 1.0);
    let d = meet(o, long, a, side, -1.0);
    let p = c + (d - a);
    for (name, at) in [("O", o), ("O1", o1), ("A", a), ("C", c), ("D", d), ("P", p)] {
        set(&mut l, name, at);
    }
    l
}

#[test]
fn the_bundled_peaucellier_tracer_is_on_its_line_at_and_near_its_locks() {
    let [locks, inside, rows] = worst(&bundled::peaucellier_lipkin());
    println!("bundled: P off its line {locks:.1e} at the locks, {inside:.1e} near, {rows:.1e} on the course");
    assert!(locks < ON_LINE && inside < ON_LINE && rows < ON_LINE);
}

#[test]
fn a_scaled_turned_moved_peaucellier_is_straight_too() {
    let l = bundled::peaucellier_lipkin();
    for (k, alpha, t) in [
        (1.0, 0.0, Vector2::new(0.0, 0.0)),
        (37.5, 0.7, Vector2::new(-3.2, 11.9)),
        (1e-3, -2.3, Vector2::new(1e-3, -4e-4)),
        (2e3, 2.9, Vector2::new(5e3, 7e2)),
    ] {
        let [locks, inside, rows] = worst(&moved(&l, k, alpha, t));
        println!("×{k} turned {alpha} moved {t:?}: {locks:.1e} {inside:.1e} {rows:.1e}");
        assert!(
            locks < ON_LINE && inside < ON_LINE && rows < ON_LINE,
            "×{k} {alpha}: {locks:e} {inside:e} {rows:e}"
        );
    }
}

/// Cells of random proportions (seeded): r, l, s with l > s and l − s < 2r < √(l² − s²), so
/// that the crank rocks between two folds of the rhombus and A stays inside P's circle of
/// inversion (radius √(l² − s²) about O): on it the cell lies flat with P = A, a branch point
/// of P's dyad, which no fixed mode follows through. The crank is drawn anywhere inside its
/// range; each cell scaled, turned and moved at random.
#[test]
fn peaucellier_cells_of_other_proportions_are_straight() {
    let mut rng = Rng(0x007e_1e28);
    let n = cases("TMM_TWIN_CASES", 12);
    let mut worst_all = [0.0f64; 3];
    for case in 0..n {
        let side = rng.range(0.2, 1.0);
        let long = side * rng.range(1.2, 4.0);
        let inversion = ((long - side) * (long + side)).sqrt();
        let r = rng.range(0.5 * (long - side) * 1.05, 0.5 * inversion * 0.95);
        let lock = 2.0 * ((long - side) / (2.0 * r)).acos();
        let theta = lock * rng.range(-0.9, 0.9);
        let scale = 10f64.powf(rng.range(-2.0, 2.0));
        let l = moved(
            &cell(r, long, side, theta),
            scale,
            rng.range(-PI, PI),
            rng.vector(3.0 * scale),
        );
        let w = worst(&l);
        for (a, b) in worst_all.iter_mut().zip(w) {
            *a = a.max(b);
        }
        assert!(
            w.iter().all(|&x| x < ON_LINE),
            "case {case}: r {r}, l {long}, s {side}, θ {theta}: {w:?}"
        );
    }
    let [a, b, c] = worst_all;
    println!("{n} cells: P off its line at most {a:.1e} at the locks, {b:.1e} near, {c:.1e} on the course");
}

/// At the exact fold the position is the limit along the branch: [`Plan::position`] at the
/// closed-form lock angles (where the rhombus may be folded to the last bit) puts P on its
/// line, and the rates there are refused; a moving input at the locks is refused by the
/// analysis as before.
#[test]
fn at_the_fold_the_position_is_the_limit_and_the_rates_are_refused() {
    for l in [
        bundled::peaucellier_lipkin(),
        moved(
            &bundled::peaucellier_lipkin(),
            3.0,
            1.1,
            Vector2::new(0.4, -0.2),
        ),
    ] {
        let plan = Plan::new(&l).unwrap();
        let cell = Cell::of(&l);
        for phi in cell.locks {
            let at = plan.position(Motion::fixed(phi)).unwrap();
            let p = at.pose().joint("P").unwrap().p;
            let off = cell.off(p) / plan.size();
            println!("closed-form lock {phi}: P off its line {off:.1e}");
            assert!(off < ON_LINE, "{off:e}");
        }
        let (lo, hi) = plan
            .lock_positions(plan.reference_input())
            .unwrap()
            .unwrap();
        for phi in [lo, hi] {
            assert!(plan.analyse(Motion::new(phi, 1.0, 0.0)).is_err());
            assert!(plan.kinematics(Motion::new(phi, 1.0, 0.0)).is_err());
        }
    }
}
