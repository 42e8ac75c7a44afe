//! Coulomb friction in the joints (`tmm::kinetostatics::friction`), checked against:
//! - an independent Newton solve of each dyad's full nonlinear Newton–Euler system (every
//!   reaction component an unknown, the friction loads functions of them, the Jacobian by
//!   central differences, each step by LU), on seeded random well-conditioned dyads of each
//!   kind for f in {0.05, 0.15, 0.3}, and of the triad's twelve equations;
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
    independent_of(6, residual, scale)
}

/// As [`independent`], for `n` unknowns.
fn independent_of(
    n: usize,
    residual: &dyn Fn(&DVector<f64>, f64) -> DVector<f64>,
    scale: f64,
) -> Option<DVector<f64>> {
    let mut x = newton(&|x| residual(x, 0.0), DVector::zeros(n), scale)?;
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

/// Triad: x = [R_A1, R_A2, R_A3, R_B1, R_B2, R_B3] (R_Ai of the outer link on binary link
/// i, R_Bi of binary link i on the ternary link); `given` = the couples [on binary link i
/// from its outer link, i = 1..3; on the ternary link from binary link i, i = 1..3] as data,
/// else from x (times t).
fn triad_residual(
    p: &TriadFriction,
    x: &DVector<f64>,
    t: f64,
    given: Option<[f64; 6]>,
) -> DVector<f64> {
    let (tr, w) = (&p.triad, &p.rates);
    let ra = [0, 1, 2].map(|i| v2(x, 2 * i));
    let rb = [0, 1, 2].map(|i| v2(x, 6 + 2 * i));
    let c = given.unwrap_or_else(|| {
        let mut c = [0.0; 6];
        for i in 0..3 {
            c[i] = -t * p.joints.a[i].rho * ra[i].norm() * sgn(w.binary[i] - w.outer[i]);
            c[3 + i] = -t * p.joints.b[i].rho * rb[i].norm() * sgn(w.ternary - w.binary[i]);
        }
        c
    });
    let mut out = Vec::with_capacity(12);
    for i in 0..3 {
        let l = &tr.loads[i];
        let e = ra[i] - rb[i] + l.force;
        let m = mom(tr.a[i], ra[i]) - mom(tr.b[i], rb[i])
            + (l.moment_about(pole()) + c[i] - c[3 + i]) / LEN;
        out.extend([e.x, e.y, m]);
    }
    let lt = &tr.load_ternary;
    let e = rb[0] + rb[1] + rb[2] + lt.force;
    let m = (0..3)
        .map(|i| mom(tr.b[i], rb[i]) + c[3 + i] / LEN)
        .sum::<f64>()
        + lt.moment_about(pole()) / LEN;
    out.extend([e.x, e.y, m]);
    DVector::from_vec(out)
}

/// A seeded triad: the ternary link's joints about the origin 0.3 m out at roughly 120°
/// apart, each binary link 0.4–0.8 m long at a random angle, random loads, rates and pins;
/// `None` when the lines of the binary links come near one point (|det K/L_T| < 0.2).
fn random_triad(rng: &mut Rng, f: f64) -> Option<TriadFriction> {
    let b = [0, 1, 2].map(|i| {
        let th = std::f64::consts::TAU * f64::from(i) / 3.0 + rng.range(-0.3, 0.3);
        Point2::from(unit(th) * 0.3)
    });
    let a =
        [0, 1, 2].map(|i| b[i] + unit(rng.range(0.0, std::f64::consts::TAU)) * rng.range(0.4, 0.8));
    let triad = tmm::kinetostatics::Triad {
        a,
        b,
        loads: [rng.load(), rng.load(), rng.load()],
        load_ternary: rng.load(),
    };
    let p = TriadFriction {
        triad,
        joints: TriadJoints {
            a: [rng.hinge(f), rng.hinge(f), rng.hinge(f)],
            b: [rng.hinge(f), rng.hinge(f), rng.hinge(f)],
        },
        rates: TriadRates {
            outer: [rng.rate(), rng.rate(), rng.rate()],
            binary: [rng.rate(), rng.rate(), rng.rate()],
            ternary: rng.rate(),
        },
    };
    (triad.solve().ok()?.conditioning.measure.abs() >= 0.2).then_some(p)
}

/// The triad with friction in its six hinges against the independent nonlinear solve of its
/// twelve Newton–Euler equations, every link's equilibrium with the reported couples as
/// data, and each hinge's friction law, on 200 seeded triads for each f.
#[test]
fn triad_against_an_independent_nonlinear_solve() {
    let mut rng = Rng(0x5EED_0006);
    for f in FS {
        let (mut gap, mut eq, mut law, mut steps, mut n) = (0.0f64, 0.0f64, 0.0f64, 0, 0);
        while n < 200 {
            let Some(p) = random_triad(&mut rng, f) else {
                continue;
            };
            let r = p.solve().unwrap();
            let ours =
                DVector::from_iterator(12, r.r_a.iter().chain(&r.r_b).flat_map(|v| [v.x, v.y]));
            let tr = &p.triad;
            let s = tr
                .loads
                .iter()
                .chain([&tr.load_ternary])
                .map(|l| l.force.amax())
                .fold(ours.amax(), f64::max);
            let theirs = independent_of(12, &|x, t| triad_residual(&p, x, t, None), s)
                .expect("tmm solved, the independent solve did not");
            let given =
                [0, 1, 2, 3, 4, 5].map(|k| if k < 3 { r.a[k].load } else { r.b[k - 3].load });
            gap = gap.max(max_abs_diff(&ours, &theirs) / s);
            eq = eq.max(triad_residual(&p, &ours, 1.0, Some(given)).amax() / s);
            for i in 0..3 {
                let da = r.a[i].load.abs() - p.joints.a[i].rho * r.r_a[i].norm();
                let db = r.b[i].load.abs() - p.joints.b[i].rho * r.r_b[i].norm();
                law = law.max(da.abs().max(db.abs()) / s);
            }
            steps += r.convergence.iterations;
            n += 1;
        }
        println!(
            "triad f = {f}: {n} cases, relative to the load scale: vs independent {gap:.2e}, \
             equilibrium {eq:.2e}, friction law {law:.2e}; mean Newton steps {:.2}",
            steps as f64 / f64::from(n)
        );
        assert!(gap <= 1e-12 && eq <= 1e-12 && law <= 1e-12);
    }
}

/// Bad friction data or rates in a triad are errors naming the field.
#[test]
fn a_triad_with_bad_friction_data_names_the_field() {
    let mut rng = Rng(0x5EED_0007);
    let p = loop {
        if let Some(p) = random_triad(&mut rng, 0.15) {
            break p;
        }
    };
    let mut bad = p;
    bad.joints.b[1] = Hinge { rho: -0.01 };
    let e = bad.solve().unwrap_err().to_string();
    assert!(e.contains("rho_B2"), "{e}");
    let mut bad = p;
    bad.joints.a[2] = Hinge { rho: f64::INFINITY };
    let e = bad.solve().unwrap_err().to_string();
    assert!(e.contains("rho_A3"), "{e}");
    let mut bad = p;
    bad.rates.ternary = f64::NAN;
    let e = bad.solve().unwrap_err().to_string();
    assert!(e.contains("omega_ternary"), "{e}");
    // A budget of one Newton step is an error, never a silent result.
    let e = p
        .solve_with(&Iteration::default().with_budget(1))
        .unwrap_err();
    assert!(e.to_string().contains("Newton step"), "{e}");
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

// ----- The power balance of a crank with each dyad -----

/// The power of a load on a link whose point velocities are `v(point)` and whose angular
/// velocity is `omega`.
fn power(load: &Load, v: impl Fn(Point2<f64>) -> Vector2<f64>, omega: f64) -> f64 {
    load.force.dot(&v(load.point)) + load.moment * omega
}

/// x·p + y·q = w for (x, y), by Cramer.
fn solve2(p: Vector2<f64>, q: Vector2<f64>, w: Vector2<f64>) -> (f64, f64) {
    let det = cross(p, q);
    (cross(w, q) / det, cross(p, w) / det)
}

/// The crank: O1, the pin's friction, ω1, and its own load.
struct Crank {
    o1: Point2<f64>,
    pin: Hinge,
    omega1: f64,
    load1: Load,
}

impl Crank {
    /// A crank ending at A, of random length, direction, speed and load.
    fn random(rng: &mut Rng, a: Point2<f64>, f: f64) -> Self {
        let o1 = a - unit(rng.range(0.0, std::f64::consts::TAU)) * rng.range(0.1, 0.4);
        Self {
            o1,
            pin: rng.hinge(f),
            omega1: rng.rate(),
            load1: Load::new(
                o1 + Vector2::new(rng.range(-0.1, 0.1), rng.range(-0.1, 0.1)),
                Vector2::new(rng.range(-500.0, 500.0), rng.range(-500.0, 500.0)),
                rng.range(-50.0, 50.0),
            ),
        }
    }
    fn v(&self, p: Point2<f64>) -> Vector2<f64> {
        perp(p - self.o1) * self.omega1
    }
    /// The power balance P_drive + P_loads − Σ P_lost, relative to the powers' size.
    fn imbalance(&self, on_link1: Load, p_other_loads: f64, p_lost_dyad: f64) -> f64 {
        let crank = CrankFriction {
            o1: self.o1,
            pin: self.pin,
            omega1: self.omega1,
        }
        .solve(&[self.load1, on_link1])
        .unwrap();
        let p_loads = power(&self.load1, |p| self.v(p), self.omega1) + p_other_loads;
        let lost = crank.pin.power_lost + p_lost_dyad;
        let e = Efficiency::new(crank.power_drive, lost).unwrap();
        assert!((e.useful + p_loads).abs() <= 1e-12 * (e.drive.abs() + p_loads.abs() + lost));
        (crank.power_drive + p_loads - lost) / (crank.power_drive.abs() + p_loads.abs() + lost)
    }
}

#[derive(Default)]
struct Balance {
    cases: usize,
    locked: usize,
    worst: f64,
    lost_share: f64,
}

impl Balance {
    fn add(&mut self, imbalance: f64) {
        self.cases += 1;
        self.worst = self.worst.max(imbalance.abs());
    }
    fn report(&self, what: &str, f: f64) {
        println!(
            "power balance, crank + {what}, f = {f}: {} positions ({} self-locking), largest \
             |P_drive + P_loads - sum P_lost| / (|P_drive| + |P_loads| + sum P_lost) = {:.2e}",
            self.cases, self.locked, self.worst
        );
        assert!(self.worst <= 1e-12, "{what}");
        assert!(self.lost_share > 0.0);
    }
}

#[test]
fn crank_and_dyad_balance_power_with_the_losses() {
    let mut rng = Rng(0x5EED_0010);
    for f in FS {
        // RRR: the four-bar, C on the frame.
        let mut b = Balance::default();
        for _ in 0..CASES {
            let mut p = random_rrr(&mut rng, f);
            let d = p.dyad;
            let crank = Crank::random(&mut rng, d.a, f);
            let va = crank.v(d.a);
            let (w2, w3) = solve2(perp(d.b - d.a), -perp(d.b - d.c), -va);
            p.rates = RrrRates {
                omega1: crank.omega1,
                omega2: w2,
                omega3: w3,
                omega4: 0.0,
            };
            let Ok(r) = p.solve() else {
                b.locked += 1;
                continue;
            };
            let pl = power(&d.load2, |q| va + perp(q - d.a) * w2, w2)
                + power(&d.load3, |q| perp(q - d.c) * w3, w3);
            b.lost_share += r.power_lost();
            b.add(crank.imbalance(r.on_link1(&d), pl, r.power_lost()));
        }
        b.report("RRR", f);

        // RRP: the slider-crank, the guide on the frame.
        let mut b = Balance::default();
        for _ in 0..CASES {
            let mut p = random_rrp(&mut rng, f);
            let d = p.dyad;
            let g = d.guide.normalize();
            let crank = Crank::random(&mut rng, d.a, f);
            let va = crank.v(d.a);
            let (w2, s) = solve2(perp(d.b - d.a), -g, -va);
            p.rates = RrpRates {
                omega1: crank.omega1,
                omega2: w2,
                omega4: 0.0,
                slide: s,
            };
            let Ok(r) = p.solve() else {
                b.locked += 1;
                continue;
            };
            let pl =
                power(&d.load2, |q| va + perp(q - d.a) * w2, w2) + power(&d.load3, |_| g * s, 0.0);
            b.lost_share += r.power_lost();
            b.add(crank.imbalance(r.on_link1(&d), pl, r.power_lost()));
        }
        b.report("RRP", f);

        // RPR: the rocking cylinder, E on the frame.
        let mut b = Balance::default();
        for _ in 0..CASES {
            let mut p = random_rpr(&mut rng, f);
            let d = p.dyad;
            let u = d.axis.normalize();
            let crank = Crank::random(&mut rng, d.a, f);
            let va = crank.v(d.a);
            let (w, s) = solve2(perp(d.a - d.e), u, va);
            p.rates = RprRates {
                omega1: crank.omega1,
                omega: w,
                omega4: 0.0,
                slide: s,
            };
            let Ok(r) = p.solve() else {
                b.locked += 1;
                continue;
            };
            let pl = power(&d.load2, |q| va + perp(q - d.a) * w, w)
                + power(&d.load3, |q| perp(q - d.e) * w, w);
            b.lost_share += r.power_lost();
            b.add(crank.imbalance(r.on_link1(&d), pl, r.power_lost()));
        }
        b.report("RPR", f);

        // PRP: the crank carries guide 2; guide 3 on the frame.
        let mut b = Balance::default();
        for _ in 0..CASES {
            let mut p = random_prp(&mut rng, f);
            let d = p.dyad;
            let (g2, g3) = (d.guide2.normalize(), d.guide3.normalize());
            let crank = Crank::random(&mut rng, d.b, f);
            let (s2, s3) = solve2(g2, -g3, -crank.v(d.b));
            p.rates = PrpRates {
                omega1: crank.omega1,
                omega4: 0.0,
                slide2: s2,
                slide3: s3,
            };
            let Ok(r) = p.solve() else {
                b.locked += 1;
                continue;
            };
            let vb = g3 * s3;
            let pl = power(
                &d.load2,
                |q| vb + perp(q - d.b) * crank.omega1,
                crank.omega1,
            ) + power(&d.load3, |_| vb, 0.0);
            b.lost_share += r.power_lost();
            b.add(crank.imbalance(r.on_link1(&d), pl, r.power_lost()));
        }
        b.report("PRP", f);

        // RPP: the Scotch yoke, the guide on the frame.
        let mut b = Balance::default();
        for _ in 0..CASES {
            let mut p = random_rpp(&mut rng, f);
            let d = p.dyad;
            let (u, v) = (d.guide.normalize(), d.slot.normalize());
            let crank = Crank::random(&mut rng, d.a, f);
            let va = crank.v(d.a);
            let (s, q) = solve2(u, v, va);
            p.rates = RppRates {
                omega1: crank.omega1,
                omega4: 0.0,
                slot: q,
                slide: s,
            };
            let Ok(r) = p.solve() else {
                b.locked += 1;
                continue;
            };
            let pl = power(&d.load2, |_| va, 0.0) + power(&d.load3, |_| u * s, 0.0);
            b.lost_share += r.power_lost();
            b.add(crank.imbalance(r.on_link1(&d), pl, r.power_lost()));
        }
        b.report("RPP", f);
    }
}

// ----- Textbook cases -----

/// A slider of weight G on a guide inclined at θ, pushed up the guide by a rod (frictionless
/// hinges: a two-force member) whose force makes the pressure angle α with the slider's
/// velocity and presses it into the guide. With ĝ up the guide and ν̂ = ĝ⊥ out of it, the
/// rod's force is P·(cos α·ĝ − sin α·ν̂); the guide pushes N·ν̂ and rubs f·N down the guide:
///   along ĝ: P·cos α − G·sin θ − f·N = 0,  along ν̂: N − P·sin α − G·cos θ = 0,
/// so P = G·(sin θ + f·cos θ)/(cos α − f·sin α): finite only while tan α < 1/f, that is
/// α < 90° − φ with φ = atan f. Beyond it no push moves the slider: self-locking.
#[test]
fn inclined_guide_self_locks_beyond_ninety_degrees_less_the_friction_angle() {
    let (theta, g_weight) = (30f64.to_radians(), 100.0);
    let g = unit(theta);
    let nu = perp(g);
    let b = Point2::origin();
    let mut worst = 0.0_f64;
    let mut locked = 0;
    for f in FS {
        let phi = f.atan();
        for i in 0..180 {
            let alpha = (f64::from(i) * 0.5).to_radians();
            let e = g * alpha.cos() - nu * alpha.sin();
            let p = RrpFriction {
                dyad: RrpDyad {
                    a: b - e * 0.5,
                    b,
                    guide: g,
                    load2: Load::zero(b),
                    load3: Load::force_at(b, Vector2::new(0.0, -g_weight)),
                },
                joints: RrpJoints {
                    guide: Slide::new(f).unwrap(),
                    ..RrpJoints::default()
                },
                rates: RrpRates {
                    slide: 1.0,
                    ..RrpRates::default()
                },
            };
            let margin = alpha - (std::f64::consts::FRAC_PI_2 - phi);
            if margin < -1e-3 {
                let r = p.solve().unwrap();
                let push =
                    g_weight * (theta.sin() + f * theta.cos()) / (alpha.cos() - f * alpha.sin());
                let n = push * alpha.sin() + g_weight * theta.cos();
                worst = worst
                    .max((r.r23 - e * push).amax() / push)
                    .max((r.contact43.normal - n).abs() / push)
                    .max((r.guide.load + f * n).abs() / push);
            } else if margin > 1e-3 {
                let err = p.solve().unwrap_err();
                assert!(
                    matches!(&err, Error::In { part, .. } if part == "the guide (links 4 and 3) self-locks"),
                    "{err}"
                );
                locked += 1;
            }
        }
    }
    println!(
        "inclined guide: push and guide force against P = G(sin θ + f cos θ)/(cos α − f sin α) \
         to {worst:.2e} relative; {locked} angles beyond 90° − φ self-lock"
    );
    assert!(worst <= 1e-12);
}

/// The crank-slider (crank r, rod l, a centric guide) with friction on the guide (f) and in
/// the crank's frame pin (ρ0), the rod's hinges frictionless, so the rod is a two-force
/// member along ê = (B − A)/l. The slider, moving at v, meets a resistance Q against its
/// motion; the rod must drive it: |P|·|ê_x| = Q + f·|N| with |N| = |P|·|ê_y|, so
/// |P| = Q/(|ê_x| − f·|ê_y|). The frame's reaction on the crank is as large as the rod's
/// force, so the pin loses ρ0·|P|·|ω1|, and
///   η = Q·|v| / (Q·|v| + f·|N|·|v| + ρ0·|P|·|ω1|) = |v|·(|ê_x| − f·|ê_y|) / (|v|·|ê_x| + ρ0·|ω1|);
/// without pin friction, η = 1 − f·|tan β| with β the rod's angle to the guide.
#[test]
fn crank_slider_efficiency_against_its_closed_form() {
    let (r, l, omega, q) = (0.1, 0.35, 10.0, 1000.0);
    let mut worst = 0.0_f64;
    let mut etas = Vec::new();
    for f in FS {
        for rho0 in [0.0, 0.02 * f] {
            let mut cycle = Vec::new();
            for i in 0..72 {
                let phi = f64::from(i) * 5f64.to_radians();
                if phi.sin().abs() < 0.05 {
                    continue; // the dead points: the slider stands still
                }
                let a = Point2::new(r * phi.cos(), r * phi.sin());
                let sin_beta = -r * phi.sin() / l;
                let cos_beta = (1.0 - sin_beta * sin_beta).sqrt();
                let b = Point2::new(a.x + l * cos_beta, 0.0);
                let v = -r * omega * phi.sin() * (1.0 + r * phi.cos() / (l * cos_beta));
                let omega2 = -r * omega * phi.cos() / (l * cos_beta);
                let dyad = RrpDyad {
                    a,
                    b,
                    guide: Vector2::new(1.0, 0.0),
                    load2: Load::zero(b),
                    load3: Load::force_at(b, Vector2::new(-q * v.signum(), 0.0)),
                };
                let rr = RrpFriction {
                    dyad,
                    joints: RrpJoints {
                        guide: Slide::new(f).unwrap(),
                        ..RrpJoints::default()
                    },
                    rates: RrpRates {
                        omega1: omega,
                        omega2,
                        omega4: 0.0,
                        slide: v,
                    },
                }
                .solve()
                .unwrap();
                let crank = CrankFriction {
                    o1: Point2::origin(),
                    pin: Hinge::circle(rho0).unwrap(),
                    omega1: omega,
                }
                .solve(&[rr.on_link1(&dyad)])
                .unwrap();
                let e = Efficiency::new(crank.power_drive, crank.pin.power_lost + rr.power_lost())
                    .unwrap();
                let (ex, ey) = ((b.x - a.x) / l, (b.y - a.y) / l);
                let closed =
                    v.abs() * (ex.abs() - f * ey.abs()) / (v.abs() * ex.abs() + rho0 * omega.abs());
                worst = worst.max((e.eta.unwrap() - closed).abs());
                if rho0 == 0.0 {
                    worst = worst.max((e.eta.unwrap() - (1.0 - f * (ey / ex).abs())).abs());
                }
                cycle.push(e);
            }
            etas.push((f, rho0, Efficiency::cycle(&cycle).unwrap()));
        }
    }
    println!("crank-slider: instantaneous η against the closed form to {worst:.2e}; cycle η (f, ρ0, η): {etas:.4?}");
    assert!(worst <= 1e-12);
}

/// A drawer (a cocked slider of length L) pushed along its guide by a rod through its middle
/// B, against a resistance Q acting at the height e across the guide: the resistance's
/// moment about B, e·Q, must be taken by the two end contacts, ±e·Q/L, so that the friction
/// is f·2eQ/L, and the push P = Q·(1 + 2·f·e/L). With the resistance's line within the
/// slider (here: on B, e = 0) the contacts share no couple and P = Q.
#[test]
fn cocked_drawer_against_its_closed_form() {
    let (q, len, l_rod) = (200.0, 0.3, 0.5);
    let b = Point2::new(0.2, 0.1);
    for f in FS {
        for e in [0.0, 0.05, 0.2, 0.6] {
            let p = RrpFriction {
                dyad: RrpDyad {
                    a: b - Vector2::new(l_rod, 0.0),
                    b,
                    guide: Vector2::new(1.0, 0.0),
                    load2: Load::zero(b),
                    load3: Load::force_at(b + Vector2::new(0.0, e), Vector2::new(-q, 0.0)),
                },
                joints: RrpJoints {
                    guide: Slide::cocked(f, len).unwrap(),
                    ..RrpJoints::default()
                },
                rates: RrpRates {
                    slide: 0.5,
                    ..RrpRates::default()
                },
            };
            let r = p.solve().unwrap();
            let push = q * (1.0 + 2.0 * f * e / len);
            assert!(
                (r.r23.x - push).abs() <= 1e-12 * q,
                "f {f} e {e}: {} vs {push}",
                r.r23.x
            );
            let [n1, n2] = r.contact43.ends.unwrap();
            assert!((n1 - e * q / len).abs() <= 1e-12 * q && (n2 + e * q / len).abs() <= 1e-12 * q);
            // The same drawer with a slider that takes any couple: no extra friction.
            let free = RrpFriction {
                joints: RrpJoints {
                    guide: Slide::new(f).unwrap(),
                    ..RrpJoints::default()
                },
                ..p
            }
            .solve()
            .unwrap();
            assert!((free.r23.x - q).abs() <= 1e-12 * q);
        }
    }
}

// ----- Without friction: the frictionless blocks, bit for bit -----

#[test]
fn without_friction_the_results_are_the_frictionless_blocks_bit_for_bit() {
    let mut rng = Rng(0x5EED_0020);
    let same = |a: Vector2<f64>, b: Vector2<f64>| {
        a.x.to_bits() == b.x.to_bits() && a.y.to_bits() == b.y.to_bits()
    };
    for i in 0..200 {
        // Every coefficient zero (rates non-zero), or every coefficient 0.3 with rates zero.
        let (f, still) = if i % 2 == 0 {
            (0.0, false)
        } else {
            (0.3, true)
        };
        let mut p = random_rrr(&mut rng, f);
        if still {
            p.rates = RrrRates {
                omega1: 3.0,
                omega2: 3.0,
                omega3: 3.0,
                omega4: 3.0,
            };
        }
        let (r, o) = (p.solve().unwrap(), p.dyad.solve().unwrap());
        assert!(same(r.r12, o.r12) && same(r.r23, o.r23) && same(r.r43, o.r43));
        assert_eq!(r.power_lost(), 0.0);
        assert_eq!(r.convergence.iterations, 0);

        let mut p = random_rrp(&mut rng, f);
        if still {
            p.rates = RrpRates {
                omega1: -1.0,
                omega2: -1.0,
                omega4: -1.0,
                slide: 0.0,
            };
        }
        let (r, o) = (p.solve().unwrap(), p.dyad.solve().unwrap());
        assert!(same(r.r12, o.r12) && same(r.r23, o.r23) && same(r.r43, o.r43));
        assert_eq!(r.contact43.normal.to_bits(), o.r43_n.to_bits());
        assert_eq!(r.contact43.moment.to_bits(), o.guide_moment.to_bits());

        let mut p = random_rpr(&mut rng, f);
        if still {
            p.rates = RprRates {
                omega1: 2.0,
                omega: 2.0,
                omega4: 2.0,
                slide: 0.0,
            };
        }
        let (r, o) = (p.solve().unwrap(), p.dyad.solve().unwrap());
        assert!(same(r.r12, o.r12) && same(r.r32, o.r32) && same(r.r43, o.r43));

        let mut p = random_prp(&mut rng, f);
        if still {
            p.rates = PrpRates {
                omega1: 1.0,
                omega4: 1.0,
                slide2: 0.0,
                slide3: 0.0,
            };
        }
        let (r, o) = (p.solve().unwrap(), p.dyad.solve().unwrap());
        assert!(same(r.r12, o.r12) && same(r.r23, o.r23) && same(r.r43, o.r43));

        let mut p = random_rpp(&mut rng, f);
        if still {
            p.rates = RppRates {
                omega1: 0.0,
                omega4: 0.0,
                slot: 0.0,
                slide: 0.0,
            };
        }
        let (r, o) = (p.solve().unwrap(), p.dyad.solve().unwrap());
        assert!(same(r.r12, o.r12) && same(r.r32, o.r32) && same(r.r43, o.r43));
    }
    // The input link: no pin friction, the frictionless balancing moment.
    let loads = [Load::new(
        Point2::new(0.1, 0.2),
        Vector2::new(30.0, -40.0),
        1.5,
    )];
    let c = CrankFriction {
        o1: Point2::new(0.01, 0.02),
        pin: Hinge::FRICTIONLESS,
        omega1: 7.0,
    }
    .solve(&loads)
    .unwrap();
    let o = tmm::kinetostatics::CouplingDrive {
        o1: Point2::new(0.01, 0.02),
    }
    .solve(&loads)
    .unwrap();
    assert_eq!(c.balancing_moment.to_bits(), o.balancing_moment.to_bits());
    assert!(same(c.r01, o.r01));
}

// ----- At rest, and at a reversal -----

/// A joint whose relative rate is exactly zero carries no friction; any other rate enters
/// by its sign alone (the impending motion), and the power lost scales with its size.
#[test]
fn a_joint_at_rest_carries_no_friction_and_only_the_rates_sign_enters() {
    let mut rng = Rng(0x5EED_0030);
    let p = random_rrr(&mut rng, 0.3);
    let at_rest = RrrFriction {
        rates: RrrRates {
            omega2: p.rates.omega1,
            ..p.rates
        },
        ..p
    };
    let r = at_rest.solve().unwrap();
    assert_eq!(r.a.load, 0.0);
    assert_eq!(r.a.power_lost, 0.0);
    assert!(r.b.load != 0.0 && r.c.load != 0.0);
    // Reversing B's relative rotation turns its couple; scaling every rate changes no force.
    let scaled = RrrFriction {
        rates: RrrRates {
            omega1: p.rates.omega1 * 1e-6,
            omega2: p.rates.omega2 * 1e-6,
            omega3: p.rates.omega3 * 1e-6,
            omega4: p.rates.omega4 * 1e-6,
        },
        ..p
    };
    let (r, s) = (p.solve().unwrap(), scaled.solve().unwrap());
    assert_eq!(r.r12, s.r12);
    assert_eq!(r.b.load, s.b.load);
    assert!((s.power_lost() - r.power_lost() * 1e-6).abs() <= 1e-15 * r.power_lost());
}

// ----- Bad input: named -----

#[test]
fn bad_friction_data_is_an_error_naming_the_joint_and_field() {
    let mut rng = Rng(0x5EED_0040);
    let p = random_rrr(&mut rng, 0.1);
    let bad = RrrFriction {
        joints: RrrJoints {
            b: Hinge { rho: -0.01 },
            ..p.joints
        },
        ..p
    };
    assert!(matches!(
        bad.solve(),
        Err(Error::OutOfRange { name: "rho_B", .. })
    ));
    let bad = RrrFriction {
        rates: RrrRates {
            omega2: f64::NAN,
            ..p.rates
        },
        ..p
    };
    assert!(matches!(
        bad.solve(),
        Err(Error::NonFinite { name: "omega2", .. })
    ));
    let p = random_rrp(&mut rng, 0.1);
    let bad = RrpFriction {
        joints: RrpJoints {
            guide: Slide {
                f: f64::INFINITY,
                ..Slide::default()
            },
            ..p.joints
        },
        ..p
    };
    assert!(matches!(
        bad.solve(),
        Err(Error::NonFinite {
            name: "f_guide",
            ..
        })
    ));
    let bad = RrpFriction {
        joints: RrpJoints {
            guide: Slide {
                f: 0.1,
                length: Some(0.0),
                centre: 0.0,
            },
            ..p.joints
        },
        ..p
    };
    assert!(matches!(
        bad.solve(),
        Err(Error::NonPositive {
            name: "L_guide",
            ..
        })
    ));
    let p = random_rpp(&mut rng, 0.1);
    let bad = RppFriction {
        joints: RppJoints {
            slot: Slide {
                f: -0.2,
                ..Slide::default()
            },
            ..p.joints
        },
        ..p
    };
    assert!(matches!(
        bad.solve(),
        Err(Error::OutOfRange { name: "f_slot", .. })
    ));
    assert!(matches!(
        Hinge::pin(-0.01, 0.1),
        Err(Error::OutOfRange {
            name: "pin radius",
            ..
        })
    ));
    assert!(matches!(
        Hinge::pin(0.01, f64::NAN),
        Err(Error::NonFinite { name: "f", .. })
    ));
    assert!(matches!(
        Slide::cocked(0.1, -1.0),
        Err(Error::NonPositive { name: "length", .. })
    ));
    let c = CrankFriction {
        o1: Point2::origin(),
        pin: Hinge { rho: -1.0 },
        omega1: 1.0,
    };
    assert!(matches!(
        c.solve(&[]),
        Err(Error::OutOfRange { name: "rho_O1", .. })
    ));
    assert!(matches!(
        Efficiency::new(1.0, -1.0),
        Err(Error::OutOfRange { name: "P_lost", .. })
    ));
}

// ----- The iteration's budget -----

/// A budget too small for the tolerance is an error naming the iteration; a looser
/// tolerance converges in fewer steps.
#[test]
fn a_budget_used_up_is_an_error_and_the_tolerance_is_honoured() {
    let mut rng = Rng(0x5EED_0050);
    let p = random_rrr(&mut rng, 0.3);
    let e = p
        .solve_with(&Iteration::default().with_budget(1))
        .unwrap_err();
    assert!(
        matches!(&e, Error::In { source, .. } if matches!(**source, Error::Budget { limit: 1, .. })),
        "{e}"
    );
    let tight = p.solve().unwrap();
    let loose = p
        .solve_with(&Iteration::default().with_tolerance(1e-4))
        .unwrap();
    assert!(loose.convergence.iterations <= tight.convergence.iterations);
    let scale = tight.r12.norm().max(tight.r23.norm()).max(tight.r43.norm());
    assert!(tight.convergence.residual <= 1e-14 * scale / tight.convergence.det.min(1.0));
    assert!(loose.convergence.residual <= 1e-4 * scale);
}

/// Options no solve could honour are refused by name before any step: a tolerance that is
/// not a number, not positive or so loose that an unconverged answer would pass (the review
/// found 10¹⁰ returning a reaction 0.15 N off on a 100 N load), and a budget of zero.
#[test]
fn bad_iteration_options_are_refused_by_name() {
    let mut rng = Rng(0x5EED_0051);
    let p = random_rrr(&mut rng, 0.3);
    for tolerance in [f64::NAN, f64::INFINITY, -1.0, 0.0, 1e10, 2e-3] {
        let e = p
            .solve_with(&Iteration::default().with_tolerance(tolerance))
            .unwrap_err();
        assert!(
            matches!(
                e,
                Error::OutOfRange {
                    name: "tolerance",
                    ..
                }
            ),
            "tolerance {tolerance}: {e}"
        );
    }
    let e = p
        .solve_with(&Iteration::default().with_budget(0))
        .unwrap_err();
    assert!(matches!(e, Error::OutOfRange { name: "budget", .. }), "{e}");
    // The loosest tolerance accepted still converges.
    assert!(p
        .solve_with(&Iteration::default().with_tolerance(1e-3))
        .is_ok());
}

// ----- The input link through a gear pair -----

/// A crank driven through a gear pair with pin friction, carrying an RRR dyad: the power
/// balance holds with the pin's loss, and without friction the results are the gear drive's,
/// bit for bit.
#[test]
fn gear_drive_with_pin_friction_balances_power() {
    let mut rng = Rng(0x5EED_0060);
    let mut worst = 0.0_f64;
    let mut iterations = 0;
    for f in FS {
        for _ in 0..CASES {
            let mut p = random_rrr(&mut rng, f);
            let d = p.dyad;
            let crank = Crank::random(&mut rng, d.a, f);
            let va = crank.v(d.a);
            let (w2, w3) = solve2(perp(d.b - d.a), -perp(d.b - d.c), -va);
            p.rates = RrrRates {
                omega1: crank.omega1,
                omega2: w2,
                omega3: w3,
                omega4: 0.0,
            };
            let r = p.solve().unwrap();
            let drive = tmm::kinetostatics::GearDrive::at_angle(
                crank.o1,
                rng.range(0.1, 0.3),
                rng.range(0.0, std::f64::consts::TAU),
                rng.range(0.0, 0.45),
            );
            let loads = [crank.load1, r.on_link1(&d)];
            let g = GearFriction {
                drive,
                pin: crank.pin,
                omega1: crank.omega1,
            }
            .solve(&loads)
            .unwrap();
            iterations = iterations.max(g.iterations);
            let p_loads = power(&crank.load1, |q| crank.v(q), crank.omega1)
                + power(&d.load2, |q| va + perp(q - d.a) * w2, w2)
                + power(&d.load3, |q| perp(q - d.c) * w3, w3);
            let lost = g.pin.power_lost + r.power_lost();
            let size = g.power_drive.abs() + p_loads.abs() + lost;
            worst = worst.max((g.power_drive + p_loads - lost).abs() / size);
            // Without pin friction: the gear drive's own results.
            let plain = GearFriction {
                drive,
                pin: Hinge::FRICTIONLESS,
                omega1: crank.omega1,
            }
            .solve(&loads)
            .unwrap();
            let o = drive.solve(&loads).unwrap();
            assert_eq!(plain.force, o.force);
            assert_eq!(plain.r01, o.r01);
            assert_eq!(
                plain.balancing_moment.to_bits(),
                o.balancing_moment.to_bits()
            );
        }
    }
    println!("gear drive + RRR: power balance to {worst:.2e} relative; at most {iterations} fixed-point steps");
    assert!(worst <= 1e-12);
    // A friction circle as large as the tooth force's arm: no tooth force turns the wheel.
    let drive = tmm::kinetostatics::GearDrive::at_angle(Point2::origin(), 0.1, 0.0, 0.0);
    let e = GearFriction {
        drive,
        pin: Hinge::circle(0.1).unwrap(),
        omega1: 1.0,
    }
    .solve(&[Load::force_at(
        Point2::new(0.05, 0.0),
        Vector2::new(0.0, -100.0),
    )])
    .unwrap_err();
    assert!(
        matches!(&e, Error::In { part, .. } if part == "joint O1 (links 0 and 1) self-locks"),
        "{e}"
    );
}
