//! Coulomb friction in the joints (`tmm::kinetostatics::friction`), checked against:
//! - an independent Newton solve of each dyad's full nonlinear Newton–Euler system (every
//!   reaction component an unknown, the friction loads functions of them, the Jacobian by
//!   central differences, each step by LU), on seeded random well-conditioned dyads of each
//!   kind for f in {0.05, 0.15, 0.3};
//! - every link's equilibrium with the friction loads the solvers report, taken as data;
//! - the power balance of a crank with each dyad: P_drive = P_useful + Σ P_lost;
//! - textbook closed forms derived here: the slider on an inclined guide (self-locking beyond
//!   a pressure angle of 90° − φ), the crank-slider's instantaneous efficiency, the drawer
//!   that jams (a cocked slider);
//! - the frictionless blocks, bit for bit, with every coefficient or every rate zero.
//!
//! Run with `--nocapture` to see the largest residuals and iteration counts.

use nalgebra::{DMatrix, DVector, Point2, Vector2};
use tmm::angle::{cross, perp, unit};
use tmm::kinetostatics::friction::*;
use tmm::kinetostatics::{PrpDyad, RppDyad, RprDyad, RrpDyad, RrrDyad};
use tmm::{Error, Load};

const FS: [f64; 3] = [0.05, 0.15, 0.3];
const CASES: usize = 400;

/// A small seeded generator (xorshift64*), so every run checks the same cases.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn sign(&mut self) -> f64 {
        if self.unit() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
    fn point(&mut self) -> Point2<f64> {
        Point2::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0))
    }
    fn load(&mut self) -> Load {
        Load::new(
            self.point(),
            Vector2::new(self.range(-500.0, 500.0), self.range(-500.0, 500.0)),
            self.range(-50.0, 50.0),
        )
    }
    /// A rate of either sign, away from zero.
    fn rate(&mut self) -> f64 {
        self.sign() * self.range(0.5, 10.0)
    }
    fn hinge(&mut self, f: f64) -> Hinge {
        Hinge::pin(self.range(0.01, 0.05), f).unwrap()
    }
    /// A slide, cocked (with a slider's length and middle) one time in two.
    fn slide(&mut self, f: f64) -> Slide {
        if self.unit() < 0.5 {
            Slide::new(f).unwrap()
        } else {
            Slide::cocked(f, self.range(0.1, 0.4))
                .unwrap()
                .centred_at(self.range(-0.05, 0.05))
        }
    }
}

// ----- The independent solve -----

/// Newton's method on `n` equations with the Jacobian by central differences and each step
/// by LU, from `x0`: `None` unless the step falls to 1e-13 of `scale` within 60 steps (it
/// stops at 1e-15, or where rounding stalls it).
fn newton(
    f: &dyn Fn(&DVector<f64>) -> DVector<f64>,
    x0: DVector<f64>,
    scale: f64,
) -> Option<DVector<f64>> {
    let n = x0.len();
    let mut x = x0;
    let mut last = f64::INFINITY;
    for _ in 0..60 {
        let r = f(&x);
        let mut jac = DMatrix::zeros(n, n);
        let h = 1e-6 * scale.max(1e-300);
        for j in 0..n {
            let mut xp = x.clone();
            let mut xm = x.clone();
            xp[j] += h;
            xm[j] -= h;
            let col = (f(&xp) - f(&xm)) / (2.0 * h);
            jac.set_column(j, &col);
        }
        let dx = jac.lu().solve(&(-r))?;
        x += &dx;
        let step = dx.amax();
        if !step.is_finite() || x.amax() > 1e8 * scale {
            return None;
        }
        if step <= 1e-15 * scale || (step <= 1e-13 * scale && step >= last) {
            return Some(x);
        }
        last = step;
    }
    None
}

/// Solves `residual(x, t)` for the friction factor t = 0 (linear: one Newton step from 0)
/// and then for t up to 1 in steps of 0.05, each from the last: `None` where the friction
/// cannot be switched on all the way (the reactions run away, Newton fails).
fn independent(
    residual: &dyn Fn(&DVector<f64>, f64) -> DVector<f64>,
    scale: f64,
) -> Option<DVector<f64>> {
    let mut x = newton(&|x| residual(x, 0.0), DVector::zeros(6), scale)?;
    for i in 1..=20 {
        let t = f64::from(i) / 20.0;
        x = newton(&|x| residual(x, t), x, scale)?;
    }
    Some(x)
}

fn sgn(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The pressure of a slide from its normal force N and the moment K of N about the
/// reference point, as the model has it: |N| for a slider that takes any couple, |N1| + |N2|
/// from the two end contacts of a cocked one.
fn slide_pressure(s: &Slide, n: f64, k: f64) -> f64 {
    match s.length {
        None => n.abs(),
        Some(l) => {
            let k = k - s.centre * n;
            let (n1, n2) = (n / 2.0 - k / l, n / 2.0 + k / l);
            n1.abs() + n2.abs()
        }
    }
}

fn v2(x: &DVector<f64>, i: usize) -> Vector2<f64> {
    Vector2::new(x[i], x[i + 1])
}

/// Moment rows are divided by this length, so every row has the size of a force.
const LEN: f64 = 1.0;

/// The pole the moments are taken about: not a joint of any dyad.
fn pole() -> Point2<f64> {
    Point2::new(0.37, -0.21)
}

fn mom(at: Point2<f64>, f: Vector2<f64>) -> f64 {
    cross(at - pole(), f) / LEN
}

/// RRR: x = [R12, R43, R23]; `given` = the friction couples [on 2 from 1, on 3 from 2, on 3
/// from 4] as data, else from x (times t).
fn rrr_residual(
    p: &RrrFriction,
    x: &DVector<f64>,
    t: f64,
    given: Option<[f64; 3]>,
) -> DVector<f64> {
    let d = &p.dyad;
    let (r12, r43, r23) = (v2(x, 0), v2(x, 2), v2(x, 4));
    let w = &p.rates;
    let [ma, mb, mc] = given.unwrap_or([
        -t * p.joints.a.rho * r12.norm() * sgn(w.omega2 - w.omega1),
        -t * p.joints.b.rho * r23.norm() * sgn(w.omega3 - w.omega2),
        -t * p.joints.c.rho * r43.norm() * sgn(w.omega3 - w.omega4),
    ]);
    let e2 = r12 - r23 + d.load2.force;
    let e3 = r43 + r23 + d.load3.force;
    DVector::from_vec(vec![
        e2.x,
        e2.y,
        mom(d.a, r12) - mom(d.b, r23) + (d.load2.moment_about(pole()) + ma - mb) / LEN,
        e3.x,
        e3.y,
        mom(d.c, r43) + mom(d.b, r23) + (d.load3.moment_about(pole()) + mb + mc) / LEN,
    ])
}

/// RRP: x = [R12, N, K, R23] (the guide's normal force and its moment about B); `given` =
/// [couple on 2 from 1, couple on 3 from 2, friction force on 3 from 4 along ĝ].
fn rrp_residual(
    p: &RrpFriction,
    x: &DVector<f64>,
    t: f64,
    given: Option<[f64; 3]>,
) -> DVector<f64> {
    let d = &p.dyad;
    let g = d.guide.normalize();
    let (r12, n, k, r23) = (v2(x, 0), x[2], x[3], v2(x, 4));
    let w = &p.rates;
    let [ma, mb, ff] = given.unwrap_or([
        -t * p.joints.a.rho * r12.norm() * sgn(w.omega2 - w.omega1),
        -t * p.joints.b.rho * r23.norm() * sgn(w.omega4 - w.omega2),
        -t * p.joints.guide.f * slide_pressure(&p.joints.guide, n, k) * sgn(w.slide),
    ]);
    let r43 = perp(g) * n + g * ff;
    let e2 = r12 - r23 + d.load2.force;
    let e3 = r43 + r23 + d.load3.force;
    DVector::from_vec(vec![
        e2.x,
        e2.y,
        mom(d.a, r12) - mom(d.b, r23) + (d.load2.moment_about(pole()) + ma - mb) / LEN,
        e3.x,
        e3.y,
        mom(d.b, r43) + mom(d.b, r23) + (k + d.load3.moment_about(pole()) + mb) / LEN,
    ])
}

/// RPR: x = [R12, N, K, R43] (the cylinder's normal force on the rod and its moment about
/// A); `given` = [couple on 2 from 1, friction force on 2 from 3 along û, couple on 3 from 4].
fn rpr_residual(
    p: &RprFriction,
    x: &DVector<f64>,
    t: f64,
    given: Option<[f64; 3]>,
) -> DVector<f64> {
    let d = &p.dyad;
    let u = d.axis.normalize();
    let (r12, n, k, r43) = (v2(x, 0), x[2], x[3], v2(x, 4));
    let w = &p.rates;
    let [ma, ff, me] = given.unwrap_or([
        -t * p.joints.a.rho * r12.norm() * sgn(w.omega - w.omega1),
        -t * p.joints.slide.f * slide_pressure(&p.joints.slide, n, k) * sgn(w.slide),
        -t * p.joints.e.rho * r43.norm() * sgn(w.omega - w.omega4),
    ]);
    let r32 = perp(u) * n + u * ff;
    let e2 = r12 + r32 + d.load2.force;
    let e3 = r43 - r32 + d.load3.force;
    DVector::from_vec(vec![
        e2.x,
        e2.y,
        mom(d.a, r12) + mom(d.a, r32) + (k + d.load2.moment_about(pole()) + ma) / LEN,
        e3.x,
        e3.y,
        mom(d.e, r43) - mom(d.a, r32) + (-k + d.load3.moment_about(pole()) + me) / LEN,
    ])
}

/// PRP: x = [N12, K12, R23, N43, K43]; `given` = [friction on 2 from 1 along ĝ2, couple on 3
/// from 2, friction on 3 from 4 along ĝ3].
fn prp_residual(
    p: &PrpFriction,
    x: &DVector<f64>,
    t: f64,
    given: Option<[f64; 3]>,
) -> DVector<f64> {
    let d = &p.dyad;
    let (g2, g3) = (d.guide2.normalize(), d.guide3.normalize());
    let (n12, k12, r23, n43, k43) = (x[0], x[1], v2(x, 2), x[4], x[5]);
    let w = &p.rates;
    let [f12, mb, f43] = given.unwrap_or([
        -t * p.joints.guide2.f * slide_pressure(&p.joints.guide2, n12, k12) * sgn(w.slide2),
        -t * p.joints.b.rho * r23.norm() * sgn(w.omega4 - w.omega1),
        -t * p.joints.guide3.f * slide_pressure(&p.joints.guide3, n43, k43) * sgn(w.slide3),
    ]);
    let r12 = perp(g2) * n12 + g2 * f12;
    let r43 = perp(g3) * n43 + g3 * f43;
    let e2 = r12 - r23 + d.load2.force;
    let e3 = r43 + r23 + d.load3.force;
    DVector::from_vec(vec![
        e2.x,
        e2.y,
        mom(d.b, r12) - mom(d.b, r23) + (k12 + d.load2.moment_about(pole()) - mb) / LEN,
        e3.x,
        e3.y,
        mom(d.b, r43) + mom(d.b, r23) + (k43 + d.load3.moment_about(pole()) + mb) / LEN,
    ])
}

/// RPP: x = [R12, N32, K32, N43, K43]; `given` = [couple on 2 from 1, friction on 2 from 3
/// along v̂, friction on 3 from 4 along û].
fn rpp_residual(
    p: &RppFriction,
    x: &DVector<f64>,
    t: f64,
    given: Option<[f64; 3]>,
) -> DVector<f64> {
    let d = &p.dyad;
    let (u, v) = (d.guide.normalize(), d.slot.normalize());
    let (r12, n32, k32, n43, k43) = (v2(x, 0), x[2], x[3], x[4], x[5]);
    let w = &p.rates;
    let [ma, f32_, f43] = given.unwrap_or([
        -t * p.joints.a.rho * r12.norm() * sgn(w.omega4 - w.omega1),
        -t * p.joints.slot.f * slide_pressure(&p.joints.slot, n32, k32) * sgn(w.slot),
        -t * p.joints.guide.f * slide_pressure(&p.joints.guide, n43, k43) * sgn(w.slide),
    ]);
    let r32 = perp(v) * n32 + v * f32_;
    let r43 = perp(u) * n43 + u * f43;
    let e2 = r12 + r32 + d.load2.force;
    let e3 = r43 - r32 + d.load3.force;
    DVector::from_vec(vec![
        e2.x,
        e2.y,
        mom(d.a, r12) + mom(d.a, r32) + (k32 + d.load2.moment_about(pole()) + ma) / LEN,
        e3.x,
        e3.y,
        mom(d.b, r43) - mom(d.a, r32) + (k43 - k32 + d.load3.moment_about(pole())) / LEN,
    ])
}

// ----- Random well-conditioned dyads with friction -----

fn random_rrr(rng: &mut Rng, f: f64) -> RrrFriction {
    RrrFriction {
        dyad: RrrDyad {
            a: Point2::new(rng.range(-1.0, -0.5), rng.range(-0.2, 0.2)),
            b: Point2::new(rng.range(-0.2, 0.2), rng.range(0.5, 1.0)),
            c: Point2::new(rng.range(0.5, 1.0), rng.range(-0.2, 0.2)),
            load2: rng.load(),
            load3: rng.load(),
        },
        joints: RrrJoints {
            a: rng.hinge(f),
            b: rng.hinge(f),
            c: rng.hinge(f),
        },
        rates: RrrRates {
            omega1: rng.rate(),
            omega2: rng.rate(),
            omega3: rng.rate(),
            omega4: rng.rate(),
        },
    }
}

/// A direction at an angle of `lo..hi` (either sign) from `from`.
fn turned(rng: &mut Rng, from: Vector2<f64>, lo: f64, hi: f64) -> Vector2<f64> {
    let phi = from.y.atan2(from.x) + rng.sign() * rng.range(lo, hi);
    unit(phi) * rng.range(0.5, 2.0)
}

fn random_rrp(rng: &mut Rng, f: f64) -> RrpFriction {
    let a = Point2::new(rng.range(-1.0, -0.5), rng.range(-0.2, 0.2));
    let b = Point2::new(rng.range(-0.2, 0.2), rng.range(0.5, 1.0));
    // Link 2 within 60° of the guide (either way along it): |cos(φ2 − φ4)| ≥ 0.5.
    let mut guide = turned(rng, b - a, 0.0, 1.0);
    if rng.unit() < 0.5 {
        guide = -guide;
    }
    RrpFriction {
        dyad: RrpDyad {
            a,
            b,
            guide,
            load2: rng.load(),
            load3: rng.load(),
        },
        joints: RrpJoints {
            a: rng.hinge(f),
            b: rng.hinge(f),
            guide: rng.slide(f),
        },
        rates: RrpRates {
            omega1: rng.rate(),
            omega2: rng.rate(),
            omega4: rng.rate(),
            slide: rng.rate(),
        },
    }
}

fn random_rpr(rng: &mut Rng, f: f64) -> RprFriction {
    let a = Point2::new(rng.range(-1.0, -0.5), rng.range(-0.2, 0.2));
    let e = Point2::new(rng.range(0.5, 1.0), rng.range(-0.2, 0.2));
    let axis = turned(rng, e - a, 0.0, 0.3);
    RprFriction {
        dyad: RprDyad {
            a,
            e,
            axis,
            load2: rng.load(),
            load3: rng.load(),
        },
        joints: RprJoints {
            a: rng.hinge(f),
            slide: rng.slide(f),
            e: rng.hinge(f),
        },
        rates: RprRates {
            omega1: rng.rate(),
            omega: rng.rate(),
            omega4: rng.rate(),
            slide: rng.rate(),
        },
    }
}

fn random_prp(rng: &mut Rng, f: f64) -> PrpFriction {
    let guide2 = unit(rng.range(0.0, std::f64::consts::TAU));
    let guide3 = turned(rng, guide2, 1.0, std::f64::consts::PI - 1.0);
    PrpFriction {
        dyad: PrpDyad {
            b: rng.point(),
            guide2,
            guide3,
            load2: rng.load(),
            load3: rng.load(),
        },
        joints: PrpJoints {
            guide2: rng.slide(f),
            b: rng.hinge(f),
            guide3: rng.slide(f),
        },
        rates: PrpRates {
            omega1: rng.rate(),
            omega4: rng.rate(),
            slide2: rng.rate(),
            slide3: rng.rate(),
        },
    }
}

fn random_rpp(rng: &mut Rng, f: f64) -> RppFriction {
    let guide = unit(rng.range(0.0, std::f64::consts::TAU));
    let slot = turned(rng, guide, 1.0, std::f64::consts::PI - 1.0);
    let a = rng.point();
    RppFriction {
        dyad: RppDyad {
            a,
            b: a + Vector2::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3)),
            guide,
            slot,
            load2: rng.load(),
            load3: rng.load(),
        },
        joints: RppJoints {
            a: rng.hinge(f),
            slot: rng.slide(f),
            guide: rng.slide(f),
        },
        rates: RppRates {
            omega1: rng.rate(),
            omega4: rng.rate(),
            slot: rng.rate(),
            slide: rng.rate(),
        },
    }
}

/// The largest force among the loads and the frictionless reactions.
fn load_scale(loads: [&Load; 2], values: &[f64]) -> f64 {
    values
        .iter()
        .map(|v| v.abs())
        .chain(loads.iter().map(|l| l.force.norm()))
        .fold(1e-300, f64::max)
}

/// What one kind's sweep found: the largest relative differences and the iterations.
#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    locked: usize,
    continued: usize,
    iterations_max: usize,
    iterations_sum: usize,
    vs_independent: f64,
    equilibrium: f64,
    friction_law: f64,
    det_min: f64,
}

impl Tally {
    fn new() -> Self {
        Self {
            det_min: f64::INFINITY,
            ..Self::default()
        }
    }
    fn add(&mut self, c: &Convergence, independent: f64, equilibrium: f64, law: f64) {
        self.cases += 1;
        self.continued += usize::from(c.continued);
        self.iterations_max = self.iterations_max.max(c.iterations);
        self.iterations_sum += c.iterations;
        self.vs_independent = self.vs_independent.max(independent);
        self.equilibrium = self.equilibrium.max(equilibrium);
        self.friction_law = self.friction_law.max(law);
        self.det_min = self.det_min.min(c.det);
    }
    fn report(&self, what: &str, f: f64) {
        println!(
            "{what} f = {f}: {} cases ({} self-locking, confirmed; {} by continuation), iterations max {} mean {:.2}, \
             min det(I-J) {:.3}; relative to the load scale: vs independent {:.2e}, \
             equilibrium {:.2e}, friction law {:.2e}",
            self.cases,
            self.locked,
            self.continued,
            self.iterations_max,
            self.iterations_sum as f64 / self.cases as f64,
            self.det_min,
            self.vs_independent,
            self.equilibrium,
            self.friction_law
        );
        assert!(self.vs_independent <= 1e-12, "{what} f = {f}: {self:?}");
        assert!(self.equilibrium <= 1e-12, "{what} f = {f}: {self:?}");
        assert!(self.friction_law <= 1e-12, "{what} f = {f}: {self:?}");
    }
}

/// The largest force among the loads and the frictionless reactions.
fn frictionless_scale(l2: &Load, l3: &Load, r: tmm::Result<[Vector2<f64>; 3]>) -> f64 {
    r.unwrap()
        .iter()
        .map(|v| v.norm())
        .chain([l2.force.norm(), l3.force.norm()])
        .fold(1e-300, f64::max)
}

/// A self-locking reported by tmm: the independent continuation cannot switch the friction
/// on all the way either.
fn confirm_lock(e: &Error, residual: &dyn Fn(&DVector<f64>, f64) -> DVector<f64>, scale: f64) {
    assert!(
        matches!(e, Error::In { part, source } if part.ends_with("self-locks")
            && matches!(**source, Error::Singular { measure: "det(I - J)", .. })),
        "{e}"
    );
    assert!(
        independent(residual, scale).is_none(),
        "tmm: {e}; independent: solved"
    );
}

fn expect_solved(
    residual: &dyn Fn(&DVector<f64>, f64) -> DVector<f64>,
    scale: f64,
) -> DVector<f64> {
    independent(residual, scale).expect("tmm solved, the independent solve did not")
}

fn max_abs_diff(a: &DVector<f64>, b: &DVector<f64>) -> f64 {
    (a - b).amax()
}

#[test]
fn rrr_against_an_independent_nonlinear_solve() {
    let mut rng = Rng(0x5EED_0001);
    for f in FS {
        let mut t = Tally::new();
        for _ in 0..CASES {
            let p = random_rrr(&mut rng, f);
            let r = match p.solve() {
                Ok(r) => r,
                Err(e) => {
                    let s = frictionless_scale(
                        &p.dyad.load2,
                        &p.dyad.load3,
                        p.dyad.solve().map(|r| [r.r12, r.r23, r.r43]),
                    );
                    confirm_lock(&e, &|x, t| rrr_residual(&p, x, t, None), s);
                    t.locked += 1;
                    continue;
                }
            };
            let ours =
                DVector::from_vec(vec![r.r12.x, r.r12.y, r.r43.x, r.r43.y, r.r23.x, r.r23.y]);
            let s = load_scale([&p.dyad.load2, &p.dyad.load3], ours.as_slice());
            let theirs = expect_solved(&|x, t| rrr_residual(&p, x, t, None), s);
            let given = [r.a.load, r.b.load, r.c.load];
            let eq = rrr_residual(&p, &ours, 1.0, Some(given)).amax();
            let law = [
                (r.a.load.abs() - p.joints.a.rho * r.r12.norm()).abs(),
                (r.b.load.abs() - p.joints.b.rho * r.r23.norm()).abs(),
                (r.c.load.abs() - p.joints.c.rho * r.r43.norm()).abs(),
            ]
            .into_iter()
            .fold(0.0, f64::max);
            t.add(
                &r.convergence,
                max_abs_diff(&ours, &theirs) / s,
                eq / s,
                law / s,
            );
        }
        t.report("RRR", f);
    }
}

#[test]
fn rrp_against_an_independent_nonlinear_solve() {
    let mut rng = Rng(0x5EED_0002);
    for f in FS {
        let mut t = Tally::new();
        for _ in 0..CASES {
            let p = random_rrp(&mut rng, f);
            let r = match p.solve() {
                Ok(r) => r,
                Err(e) => {
                    let s = frictionless_scale(
                        &p.dyad.load2,
                        &p.dyad.load3,
                        p.dyad.solve().map(|r| [r.r12, r.r23, r.r43]),
                    );
                    confirm_lock(&e, &|x, t| rrp_residual(&p, x, t, None), s);
                    t.locked += 1;
                    continue;
                }
            };
            let c = r.contact43;
            let ours =
                DVector::from_vec(vec![r.r12.x, r.r12.y, c.normal, c.moment, r.r23.x, r.r23.y]);
            let s = load_scale(
                [&p.dyad.load2, &p.dyad.load3],
                &[r.r12.norm(), r.r23.norm(), c.normal],
            );
            let theirs = expect_solved(&|x, t| rrp_residual(&p, x, t, None), s);
            let eq = rrp_residual(&p, &ours, 1.0, Some([r.a.load, r.b.load, r.guide.load])).amax();
            let g = p.dyad.guide.normalize();
            let law = [
                (r.a.load.abs() - p.joints.a.rho * r.r12.norm()).abs(),
                (r.b.load.abs() - p.joints.b.rho * r.r23.norm()).abs(),
                (r.guide.load.abs()
                    - p.joints.guide.f * slide_pressure(&p.joints.guide, c.normal, c.moment))
                .abs(),
                // R43 is the normal force plus the friction force.
                (r.r43 - perp(g) * c.normal - g * r.guide.load).amax(),
            ]
            .into_iter()
            .fold(0.0, f64::max);
            t.add(
                &r.convergence,
                max_abs_diff(&ours, &theirs) / s,
                eq / s,
                law / s,
            );
        }
        t.report("RRP", f);
    }
}

#[test]
fn rpr_against_an_independent_nonlinear_solve() {
    let mut rng = Rng(0x5EED_0003);
    for f in FS {
        let mut t = Tally::new();
        for _ in 0..CASES {
            let p = random_rpr(&mut rng, f);
            let r = match p.solve() {
                Ok(r) => r,
                Err(e) => {
                    let s = frictionless_scale(
                        &p.dyad.load2,
                        &p.dyad.load3,
                        p.dyad.solve().map(|r| [r.r12, r.r32, r.r43]),
                    );
                    confirm_lock(&e, &|x, t| rpr_residual(&p, x, t, None), s);
                    t.locked += 1;
                    continue;
                }
            };
            let c = r.contact32;
            let ours =
                DVector::from_vec(vec![r.r12.x, r.r12.y, c.normal, c.moment, r.r43.x, r.r43.y]);
            let s = load_scale(
                [&p.dyad.load2, &p.dyad.load3],
                &[r.r12.norm(), r.r43.norm(), c.normal],
            );
            let theirs = expect_solved(&|x, t| rpr_residual(&p, x, t, None), s);
            let eq = rpr_residual(&p, &ours, 1.0, Some([r.a.load, r.slide.load, r.e.load])).amax();
            let u = p.dyad.axis.normalize();
            let law = [
                (r.a.load.abs() - p.joints.a.rho * r.r12.norm()).abs(),
                (r.slide.load.abs()
                    - p.joints.slide.f * slide_pressure(&p.joints.slide, c.normal, c.moment))
                .abs(),
                (r.e.load.abs() - p.joints.e.rho * r.r43.norm()).abs(),
                (r.r32 - perp(u) * c.normal - u * r.slide.load).amax(),
            ]
            .into_iter()
            .fold(0.0, f64::max);
            t.add(
                &r.convergence,
                max_abs_diff(&ours, &theirs) / s,
                eq / s,
                law / s,
            );
        }
        t.report("RPR", f);
    }
}

#[test]
fn prp_against_an_independent_nonlinear_solve() {
    let mut rng = Rng(0x5EED_0004);
    for f in FS {
        let mut t = Tally::new();
        for _ in 0..CASES {
            let p = random_prp(&mut rng, f);
            let r = match p.solve() {
                Ok(r) => r,
                Err(e) => {
                    let s = frictionless_scale(
                        &p.dyad.load2,
                        &p.dyad.load3,
                        p.dyad.solve().map(|r| [r.r12, r.r23, r.r43]),
                    );
                    confirm_lock(&e, &|x, t| prp_residual(&p, x, t, None), s);
                    t.locked += 1;
                    continue;
                }
            };
            let (c2, c3) = (r.contact12, r.contact43);
            let ours = DVector::from_vec(vec![
                c2.normal, c2.moment, r.r23.x, r.r23.y, c3.normal, c3.moment,
            ]);
            let s = load_scale(
                [&p.dyad.load2, &p.dyad.load3],
                &[c2.normal, r.r23.norm(), c3.normal],
            );
            let theirs = expect_solved(&|x, t| prp_residual(&p, x, t, None), s);
            let eq = prp_residual(
                &p,
                &ours,
                1.0,
                Some([r.guide2.load, r.b.load, r.guide3.load]),
            )
            .amax();
            let law = [
                (r.guide2.load.abs()
                    - p.joints.guide2.f * slide_pressure(&p.joints.guide2, c2.normal, c2.moment))
                .abs(),
                (r.b.load.abs() - p.joints.b.rho * r.r23.norm()).abs(),
                (r.guide3.load.abs()
                    - p.joints.guide3.f * slide_pressure(&p.joints.guide3, c3.normal, c3.moment))
                .abs(),
            ]
            .into_iter()
            .fold(0.0, f64::max);
            t.add(
                &r.convergence,
                max_abs_diff(&ours, &theirs) / s,
                eq / s,
                law / s,
            );
        }
        t.report("PRP", f);
    }
}

#[test]
fn rpp_against_an_independent_nonlinear_solve() {
    let mut rng = Rng(0x5EED_0005);
    for f in FS {
        let mut t = Tally::new();
        for _ in 0..CASES {
            let p = random_rpp(&mut rng, f);
            let r = match p.solve() {
                Ok(r) => r,
                Err(e) => {
                    let s = frictionless_scale(
                        &p.dyad.load2,
                        &p.dyad.load3,
                        p.dyad.solve().map(|r| [r.r12, r.r32, r.r43]),
                    );
                    confirm_lock(&e, &|x, t| rpp_residual(&p, x, t, None), s);
                    t.locked += 1;
                    continue;
                }
            };
            let (c2, c3) = (r.contact32, r.contact43);
            let ours = DVector::from_vec(vec![
                r.r12.x, r.r12.y, c2.normal, c2.moment, c3.normal, c3.moment,
            ]);
            let s = load_scale(
                [&p.dyad.load2, &p.dyad.load3],
                &[r.r12.norm(), c2.normal, c3.normal],
            );
            let theirs = expect_solved(&|x, t| rpp_residual(&p, x, t, None), s);
            let eq =
                rpp_residual(&p, &ours, 1.0, Some([r.a.load, r.slot.load, r.guide.load])).amax();
            let law = [
                (r.a.load.abs() - p.joints.a.rho * r.r12.norm()).abs(),
                (r.slot.load.abs()
                    - p.joints.slot.f * slide_pressure(&p.joints.slot, c2.normal, c2.moment))
                .abs(),
                (r.guide.load.abs()
                    - p.joints.guide.f * slide_pressure(&p.joints.guide, c3.normal, c3.moment))
                .abs(),
            ]
            .into_iter()
            .fold(0.0, f64::max);
            t.add(
                &r.convergence,
                max_abs_diff(&ours, &theirs) / s,
                eq / s,
                law / s,
            );
        }
        t.report("RPP", f);
    }
}
