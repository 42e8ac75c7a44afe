//! Scenario tests of `tmm::dynamics`: exact solutions, observed orders, energy balance,
//! independent formulations and the failure modes of the four machines.

use std::f64::consts::PI;

use nalgebra::{Matrix2, SMatrix, SVector, Vector2};
use tmm::dynamics::machines::{CoaxialPropellers, Failure, FiveBar, LandingGear, RpArm};
use tmm::dynamics::{
    accelerations, run, Beyond, Direction, Dopri5, FiniteIncrement, Handover, LagrangeSystem,
    Outcome, Reach, Rk4, RunOptions, State, Steady, Stepper, Table, Trajectory, Watch,
};
use tmm::Error;

/// Composite Simpson's rule over uniform samples (an even number of intervals).
pub(crate) fn simpson(t: &[f64], y: &[f64]) -> f64 {
    assert!(t.len() % 2 == 1 && t.len() >= 3);
    let h = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    let mut s = y[0] + y[y.len() - 1];
    for (i, v) in y.iter().enumerate().take(y.len() - 1).skip(1) {
        s += if i % 2 == 1 { 4.0 } else { 2.0 } * v;
    }
    s * h / 3.0
}

/// (ΔE, W): the change of T + Π and the net work of applied and viscous loads.
fn energy_balance(tr: &Trajectory) -> (f64, f64) {
    let n = tr.len() - 1;
    let de = tr.kinetic()[n] + tr.potential()[n] - tr.kinetic()[0] - tr.potential()[0];
    let p: Vec<f64> = tr
        .power_applied()
        .iter()
        .zip(tr.power_dissipated())
        .map(|(a, d)| a - d)
        .collect();
    (de, simpson(tr.t(), &p))
}

/// Runs a fixed-step method for `n` steps of `h` and returns the final state.
fn steps<S: LagrangeSystem, M: Stepper>(
    sys: &S,
    m: &M,
    mut s: State,
    h: f64,
    n: usize,
) -> tmm::Result<State> {
    for _ in 0..n {
        s = m.step(sys, &s, h)?;
    }
    Ok(s)
}

fn observed_orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

// ---------------------------------------------------------------------------------------
// Coaxial propellers: linear, constant inertia, exact solution.

/// The exact solution by nalgebra's matrix exponential of the augmented first-order system
/// d/dt (q, q̇, 1) = [[0, I, 0], [0, −K, c], [0, 0, 0]] (q, q̇, 1): independent of the crate's
/// rank-one closed form.
fn coaxial_by_expm(d: &CoaxialPropellers, start: &State, t: f64) -> State {
    let a = d.inertia_matrix().unwrap();
    let ainv = a.try_inverse().unwrap();
    let u = d.input_ratios();
    let k = d.motor.b * ainv * u * u.transpose();
    let c = ainv * (d.motor.a * u + Vector2::new(d.m_on4, d.m_onh));
    let mut m = SMatrix::<f64, 5, 5>::zeros();
    m[(0, 2)] = 1.0;
    m[(1, 3)] = 1.0;
    for i in 0..2 {
        for j in 0..2 {
            m[(2 + i, 2 + j)] = -k[(i, j)];
        }
        m[(2 + i, 4)] = c[i];
    }
    let e = (m * (t - start.t)).exp();
    let y0 = SVector::<f64, 5>::new(start.q[0], start.q[1], start.qd[0], start.qd[1], 1.0);
    let y = e * y0;
    State::new(t, Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]))
}

#[test]
fn coaxial_closed_form_matches_matrix_exponential() {
    let mut d = CoaxialPropellers::default();
    let starts = [
        State::at_rest(Vector2::zeros()),
        State::new(0.5, Vector2::new(1.0, -2.0), Vector2::new(-30.0, 40.0)),
    ];
    let mut worst: f64 = 0.0;
    for unbalanced in [false, true] {
        if unbalanced {
            d.m_on4 = 6000.0;
        }
        for s0 in &starts {
            for t in [
                s0.t + 1e-4,
                s0.t + 0.01,
                s0.t + 0.3,
                s0.t + 2.0,
                s0.t + 10.0,
            ] {
                let a = d.exact(s0, t).unwrap();
                let b = coaxial_by_expm(&d, s0, t);
                let scale = b.q.norm().max(b.qd.norm());
                worst = worst.max((a.q - b.q).norm().max((a.qd - b.qd).norm()) / scale);
            }
        }
    }
    eprintln!("coaxial closed form vs expm: largest relative difference {worst:e}");
    assert!(worst < 1e-10, "closed form vs expm: {worst:e}");
}

#[test]
fn coaxial_orders_finite_increments_one_rk4_four() {
    let d = CoaxialPropellers::default();
    let s0 = State::at_rest(Vector2::zeros());
    let t_end = 1.0;
    let exact = d.exact(&s0, t_end).unwrap();
    let err = |s: State| {
        ((s.q - exact.q).norm() / exact.q.norm()).max((s.qd - exact.qd).norm() / exact.qd.norm())
    };
    let fi: Vec<f64> = [250, 500, 1000, 2000]
        .iter()
        .map(|&n| err(steps(&d, &FiniteIncrement, s0, t_end / n as f64, n).unwrap()))
        .collect();
    let rk: Vec<f64> = [20, 40, 80, 160]
        .iter()
        .map(|&n| err(steps(&d, &Rk4, s0, t_end / n as f64, n).unwrap()))
        .collect();
    let (pf, pr) = (observed_orders(&fi), observed_orders(&rk));
    eprintln!("observed orders: finite increments {pf:?}, RK4 {pr:?}");
    for p in &pf {
        assert!(
            (p - 1.0).abs() < 0.1,
            "finite increments: orders {pf:?}, errors {fi:?}"
        );
    }
    for p in &pr {
        assert!((p - 4.0).abs() < 0.25, "RK4: orders {pr:?}, errors {rk:?}");
    }
}

#[test]
fn coaxial_dormand_prince_meets_its_tolerance() {
    let d = CoaxialPropellers::default();
    let s0 = State::at_rest(Vector2::zeros());
    let mut last_steps = 0;
    for tol in [1e-5, 1e-7, 1e-9] {
        let dp = Dopri5::new(tol).unwrap();
        let r = run(&d, &dp, s0, &RunOptions::until(3.0, 1e-3)).unwrap();
        assert_eq!(r.outcome, Outcome::FinalTime);
        // The global error of every recorded state, in the controller's own weighted norm.
        let mut worst: f64 = 0.0;
        for i in 0..r.trajectory.len() {
            let t = r.trajectory.t()[i];
            let ex = d.exact(&s0, t).unwrap();
            let got = [
                r.trajectory.q()[0][i],
                r.trajectory.q()[1][i],
                r.trajectory.qd()[0][i],
                r.trajectory.qd()[1][i],
            ];
            let want = [ex.q[0], ex.q[1], ex.qd[0], ex.qd[1]];
            for (g, w) in got.iter().zip(want) {
                worst = worst.max((g - w).abs() / (tol + tol * w.abs()));
            }
        }
        eprintln!(
            "Dormand-Prince tol {tol:e}: weighted global error {worst:.3}, {} steps",
            r.steps
        );
        assert!(worst <= 1.0, "tol {tol:e}: weighted global error {worst}");
        assert!(r.steps > last_steps, "a finer tolerance takes more steps");
        last_steps = r.steps;
    }
}

#[test]
fn coaxial_balanced_reaches_steady_state_unbalanced_drifts() {
    let mut d = CoaxialPropellers::default();
    assert!(d.steady_state_exists());
    assert!(d.drift_acceleration().unwrap().norm() < 1e-9);
    let mut opts = RunOptions::until(60.0, 2e-3);
    opts.record_every = 10;
    opts.steady = Some(Steady {
        tol: 1e-3,
        hold: 1.0,
    });
    let s0 = State::at_rest(Vector2::zeros());
    let r = run(&d, &FiniteIncrement, s0, &opts).unwrap();
    let Outcome::Steady { t } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert!(t > 1.0 && t < 20.0, "steady at {t}");
    // In the steady state the motor gives exactly the moment the loads ask: 1100 N·m.
    let u = d.input_ratios();
    let m1 = d.motor.torque(u.dot(&r.last.qd)).unwrap();
    assert!((m1 - 1100.0).abs() < 1.0, "motor moment {m1}");

    // Loads out of the gear ratio (D41): the run ends with a clear verdict, not at t_end.
    d.m_on4 = 6000.0;
    assert!(!d.steady_state_exists());
    let drift = d.drift_acceleration().unwrap();
    let r = run(&d, &Rk4, s0, &opts).unwrap();
    let Outcome::Drifting { t, acceleration } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert!(t < 20.0);
    assert!(
        (acceleration - drift).amax() <= 1e-3,
        "{acceleration} vs {drift}"
    );
    // The motor speed settles while the propellers drift apart with opposite accelerations.
    assert!(drift[0] * drift[1] < 0.0 || drift[0].abs() > 1e-3);
    assert!(u.dot(&drift).abs() < 1e-9 * drift.norm());
    // Without the drift window it would have run to the final time: NotSteady says so.
    let short = RunOptions { t_end: 0.5, ..opts };
    let r = run(&d, &Rk4, s0, &short).unwrap();
    assert!(matches!(r.outcome, Outcome::NotSteady { .. }));
}

// ---------------------------------------------------------------------------------------
// R–P arm.

#[test]
fn decoupled_rp_arm_agrees_with_closed_form() {
    let arm = RpArm::default().decoupled();
    let starts = [
        State::at_rest(Vector2::zeros()),
        State::new(0.0, Vector2::new(0.3, 0.2), Vector2::new(-1.0, 0.4)),
    ];
    let mut worst: f64 = 0.0;
    for s0 in starts {
        let r = run(&arm, &Rk4, s0, &RunOptions::until(5.0, 5e-3)).unwrap();
        for i in 0..r.trajectory.len() {
            let ex = arm.closed_form(&s0, r.trajectory.t()[i]).unwrap();
            for c in 0..2 {
                worst = worst
                    .max((r.trajectory.q()[c][i] - ex.q[c]).abs())
                    .max((r.trajectory.qd()[c][i] - ex.qd[c]).abs());
            }
        }
    }
    eprintln!("decoupled R-P arm, RK4 h = 5 ms vs closed form: {worst:e}");
    assert!(worst < 1e-9, "RK4 vs closed form: {worst:e}");
    // The seed's (62)–(63) from rest, as printed (with D21's F_p2/b2).
    let a = RpArm::default();
    let (c1, l2, l4) = (
        a.b1 * a.r0 * a.r0,
        -a.b1 * a.r0 * a.r0 / (a.iz1 + a.iz2),
        -a.b2 / a.m2,
    );
    let t = 1.7;
    let s = arm
        .closed_form(&State::at_rest(Vector2::zeros()), t)
        .unwrap();
    let phi = a.mp1 / (l2 * c1) * (1.0 - (l2 * t).exp()) + a.mp1 / c1 * t;
    let l = a.fp2 / (l4 * a.b2) * (1.0 - (l4 * t).exp()) + a.fp2 / a.b2 * t;
    assert!((s.q[0] - phi).abs() < 1e-12 && (s.q[1] - l).abs() < 1e-12);
}

#[test]
fn rp_arm_accelerations_are_eqs_52_and_corrected_53() {
    let a = RpArm::default();
    for (l, phid, ld) in [(0.3, 1.5, -0.2), (0.0, -2.0, 0.7), (0.8, 0.4, 0.1)] {
        let q = Vector2::new(0.7, l);
        let qd = Vector2::new(phid, ld);
        let acc = accelerations(&a, 0.0, &q, &qd).unwrap();
        let j = a.iz1 + a.iz2 + a.m2 * l * l;
        let phidd = (a.mp1 - 2.0 * a.m2 * l * phid * ld - a.b1 * a.r0 * a.r0 * phid) / j;
        let ldd = (a.fp2 + a.m2 * phid * phid * l - a.b2 * ld) / a.m2;
        assert!((acc[0] - phidd).abs() < 1e-12 && (acc[1] - ldd).abs() < 1e-12);
    }
}

#[test]
fn energy_balance_rp_arm_rk4_and_finite_increments() {
    let a = RpArm::default();
    let s0 = State::new(0.0, Vector2::new(0.0, 0.3), Vector2::new(1.0, 0.0));
    // RK4: fourth order, Simpson's rule too: the residual is tiny.
    let r = run(&a, &Rk4, s0, &RunOptions::until(2.0, 2e-3)).unwrap();
    let (de, w) = energy_balance(&r.trajectory);
    eprintln!("R-P arm energy, RK4 h = 2 ms: ΔE = {de} J, W = {w} J");
    assert!(
        (de - w).abs() < 1e-8 * w.abs().max(de.abs()),
        "RK4: ΔE {de} vs W {w}"
    );
    // Finite increments: first order, the residual halves with the step.
    let res: Vec<f64> = [4e-3, 2e-3, 1e-3]
        .iter()
        .map(|&h| {
            let r = run(&a, &FiniteIncrement, s0, &RunOptions::until(2.0, h)).unwrap();
            let (de, w) = energy_balance(&r.trajectory);
            (de - w).abs()
        })
        .collect();
    eprintln!("R-P arm energy residuals, finite increments h = 4, 2, 1 ms: {res:?}");
    for p in observed_orders(&res) {
        assert!(
            (p - 1.0).abs() < 0.2,
            "finite-increment energy residuals {res:?}"
        );
    }
}

#[test]
fn rp_arm_stops_when_the_slide_reaches_its_stroke() {
    let a = RpArm::default();
    let mut opts = RunOptions::until(10.0, 0.05);
    opts.reach = Some(Reach {
        watch: Watch::Coordinate(1),
        value: 0.6,
        direction: Direction::Rising,
    });
    let r = run(
        &a,
        &Rk4,
        State::new(0.0, Vector2::new(0.0, 0.3), Vector2::zeros()),
        &opts,
    )
    .unwrap();
    let Outcome::Reached { t } = r.outcome else {
        panic!()
    };
    assert!((r.last.q[1] - 0.6).abs() < 1e-12);
    // Located inside the step, not on the grid of 0.05 s.
    assert!(((t / 0.05).round() * 0.05 - t).abs() > 1e-6);
    // Against a fine adaptive run of the same motion.
    let fine = run(
        &a,
        &Dopri5::new(1e-11).unwrap(),
        State::new(0.0, Vector2::new(0.0, 0.3), Vector2::zeros()),
        &opts,
    )
    .unwrap();
    let Outcome::Reached { t: tf } = fine.outcome else {
        panic!()
    };
    assert!((t - tf).abs() < 1e-5, "{t} vs {tf}");
}

// ---------------------------------------------------------------------------------------
// Five-bar robot.

/// A hyper-dual number a + b·ε₁ + c·ε₂ + d·ε₁ε₂ (ε₁² = ε₂² = 0): carried through a function
/// it gives the value, two first directional derivatives and the mixed second derivative,
/// exact to rounding (forward-mode automatic differentiation).
#[derive(Debug, Clone, Copy)]
struct H {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
}

impl H {
    fn constant(a: f64) -> Self {
        H {
            a,
            b: 0.0,
            c: 0.0,
            d: 0.0,
        }
    }
    /// g(u) for a scalar function with derivatives g1 = g′(a), g2 = g″(a).
    fn chain(self, g: f64, g1: f64, g2: f64) -> Self {
        H {
            a: g,
            b: g1 * self.b,
            c: g1 * self.c,
            d: g1 * self.d + g2 * self.b * self.c,
        }
    }
    fn sqrt(self) -> Self {
        let r = self.a.sqrt();
        self.chain(r, 0.5 / r, -0.25 / (r * self.a))
    }
    fn sin(self) -> Self {
        self.chain(self.a.sin(), self.a.cos(), -self.a.sin())
    }
    fn cos(self) -> Self {
        self.chain(self.a.cos(), -self.a.sin(), -self.a.cos())
    }
    fn atan(self) -> Self {
        let q = 1.0 + self.a * self.a;
        self.chain(self.a.atan(), 1.0 / q, -2.0 * self.a / (q * q))
    }
    fn recip(self) -> Self {
        self.chain(1.0 / self.a, -1.0 / (self.a * self.a), 2.0 / self.a.powi(3))
    }
    /// atan2(y, x) with the derivatives of atan(y/x) (or of −atan(x/y)): only the value
    /// carries the branch constant.
    fn atan2(y: H, x: H) -> Self {
        let mut t = if x.a.abs() >= y.a.abs() {
            (y / x).atan()
        } else {
            -(x / y).atan()
        };
        t.a = y.a.atan2(x.a);
        t
    }
}

impl std::ops::Add for H {
    type Output = H;
    fn add(self, o: H) -> H {
        H {
            a: self.a + o.a,
            b: self.b + o.b,
            c: self.c + o.c,
            d: self.d + o.d,
        }
    }
}
impl std::ops::Sub for H {
    type Output = H;
    fn sub(self, o: H) -> H {
        H {
            a: self.a - o.a,
            b: self.b - o.b,
            c: self.c - o.c,
            d: self.d - o.d,
        }
    }
}
impl std::ops::Neg for H {
    type Output = H;
    fn neg(self) -> H {
        H {
            a: -self.a,
            b: -self.b,
            c: -self.c,
            d: -self.d,
        }
    }
}
impl std::ops::Mul for H {
    type Output = H;
    fn mul(self, o: H) -> H {
        H {
            a: self.a * o.a,
            b: self.a * o.b + self.b * o.a,
            c: self.a * o.c + self.c * o.a,
            d: self.a * o.d + self.b * o.c + self.c * o.b + self.d * o.a,
        }
    }
}
impl std::ops::Div for H {
    type Output = H;
    // u/v = u·(1/v): the chain rule of the reciprocal carries the derivatives.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: H) -> H {
        self * o.recip()
    }
}

/// Positions of A, B, C and the coupler angles φ2, φ3 of the five-bar by a circle
/// intersection written here, independently of the crate's kinematics.
fn five_bar_points(f: &FiveBar, q: [H; 2]) -> [[H; 2]; 5] {
    let k = H::constant;
    let a = [
        k(f.o.x) + k(f.l_oa) * q[0].cos(),
        k(f.o.y) + k(f.l_oa) * q[0].sin(),
    ];
    let c = [
        k(f.d.x) + k(f.l_dc) * q[1].cos(),
        k(f.d.y) + k(f.l_dc) * q[1].sin(),
    ];
    let dv = [c[0] - a[0], c[1] - a[1]];
    let d = (dv[0] * dv[0] + dv[1] * dv[1]).sqrt();
    let x = (k(f.l_ab * f.l_ab - f.l_cb * f.l_cb) + d * d) / (k(2.0) * d);
    let y = (k(f.l_ab * f.l_ab) - x * x).sqrt() * k(f.mode);
    let b = [
        a[0] + (dv[0] * x - dv[1] * y) / d,
        a[1] + (dv[1] * x + dv[0] * y) / d,
    ];
    let phi2 = H::atan2(b[1] - a[1], b[0] - a[0]);
    let phi3 = H::atan2(b[1] - c[1], b[0] - c[0]);
    [a, b, c, [phi2, k(0.0)], [phi3, k(0.0)]]
}

/// The accelerations of the five-bar by d'Alembert–Lagrange from the positions alone:
/// Σ w·(J q̈ + ζ)·Jᵢ = Qᵢ − ∂Π/∂qᵢ over the point masses at A, B, C and the couplers' rotary
/// corrections, with the cranks' own inertia; J = ∂r/∂q and the convective acceleration
/// ζ = d²r(q + s·q̇)/ds² at s = 0 come from hyper-dual numbers (exact derivatives of the
/// independent circle intersection).
fn five_bar_independent(f: &FiveBar, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
    // ε₁ along q₁ and ε₂ along q₂: the b and c parts are the two Jacobian columns.
    let jac_run = five_bar_points(
        f,
        [
            H {
                a: q[0],
                b: 1.0,
                c: 0.0,
                d: 0.0,
            },
            H {
                a: q[1],
                b: 0.0,
                c: 1.0,
                d: 0.0,
            },
        ],
    );
    // ε₁ = ε₂ along q̇: the d part is the second directional derivative.
    let conv_run = five_bar_points(
        f,
        [
            H {
                a: q[0],
                b: qd[0],
                c: qd[0],
                d: 0.0,
            },
            H {
                a: q[1],
                b: qd[1],
                c: qd[1],
                d: 0.0,
            },
        ],
    );
    let col = |p: usize, i: usize| {
        let r = jac_run[p];
        if i == 0 {
            Vector2::new(r[0].b, r[1].b)
        } else {
            Vector2::new(r[0].c, r[1].c)
        }
    };
    let conv = |p: usize| Vector2::new(conv_run[p][0].d, conv_run[p][1].d);
    let [m_a2, m_b, m_c3] = f.point_masses().unwrap();
    let dj2 = f
        .j_s2
        .map_or(0.0, |j| j - f.m2 * f.l_as2 * (f.l_ab - f.l_as2));
    let dj3 = f
        .j_s3
        .map_or(0.0, |j| j - f.m3 * f.l_bs3 * (f.l_cb - f.l_bs3));
    let weights = [m_a2, m_b, m_c3, dj2, dj3];
    // The cranks' own moments of inertia about their fixed axes.
    let mut m = Matrix2::new(f.i1, 0.0, 0.0, f.i4);
    let mut rhs = Vector2::zeros();
    for i in 0..2 {
        // Applied loads by virtual work: the servos, the tool moment on link 3, gravity.
        let servo = if i == 0 { f.drive1 } else { f.drive4 };
        rhs[i] = servo.torque(q[i], qd[i]).unwrap()
            - f.m_on * col(4, i).x
            - f.gravity * (m_a2 * col(0, i).y + m_b * col(1, i).y + m_c3 * col(2, i).y);
        for (p, w) in weights.iter().enumerate() {
            for j in 0..2 {
                m[(i, j)] += w * col(p, i).dot(&col(p, j));
            }
            rhs[i] -= w * col(p, i).dot(&conv(p));
        }
    }
    m.lu().solve(&rhs).unwrap()
}

/// A deterministic generator (SplitMix64) for sampling states.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

#[test]
fn five_bar_accelerations_agree_with_an_independent_formulation() {
    let mut rng = Rng(2003);
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for variant in 0..3 {
        let mut f = FiveBar::default();
        if variant >= 1 {
            f.gravity = 9.81;
            f.m_on = -0.7;
        }
        if variant == 2 {
            // Slender rods: J_S = m l²/12, and an off-centre S2.
            f.l_as2 = 0.08;
            f.j_s2 = Some(f.m2 * f.l_ab * f.l_ab / 12.0 + f.m2 * (f.l_ab / 2.0 - f.l_as2).powi(2));
            f.j_s3 = Some(f.m3 * f.l_cb * f.l_cb / 12.0);
        }
        while checked < 200 * (variant + 1) {
            let q = Vector2::new(rng.range(0.0, PI), rng.range(0.0, PI));
            let Ok(k) = f.kinematics(&q) else { continue };
            if k.sin_phi3_minus_phi2.abs() < 0.1 {
                continue;
            }
            let qd = Vector2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let a = accelerations(&f, 0.0, &q, &qd).unwrap();
            let b = five_bar_independent(&f, &q, &qd);
            worst = worst.max((a - b).norm() / a.norm().max(b.norm()));
            checked += 1;
        }
    }
    eprintln!("five-bar vs independent formulation: {worst:e} over {checked} states");
    assert!(
        worst < 1e-10,
        "largest relative difference {worst:e} over {checked} states"
    );
}

/// The inertia of the five-bar, with the trait's numerical fallback for its derivatives.
struct NumericDerivatives(FiveBar);
impl LagrangeSystem for NumericDerivatives {
    fn inertia(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        self.0.inertia(q)
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        self.0.forces(t, q, qd)
    }
}

#[test]
fn five_bar_analytic_derivatives_match_the_numerical_fallback_and_the_seeds_coefficients() {
    let f = FiveBar::default();
    let nd = NumericDerivatives(f);
    let mut rng = Rng(7);
    let mut n = 0;
    let mut worst: f64 = 0.0;
    while n < 100 {
        let q = Vector2::new(rng.range(0.3, 2.8), rng.range(0.3, 2.8));
        let Ok(k) = f.kinematics(&q) else { continue };
        if k.sin_phi3_minus_phi2.abs() < 0.2 {
            continue;
        }
        let da = f.inertia_derivatives(&q).unwrap();
        let dn = nd.inertia_derivatives(&q).unwrap();
        for m in 0..2 {
            worst = worst.max((da[m] - dn[m]).amax() / da[m].amax());
        }
        // The corrected coefficient set of seed 003 (docs/errata.md#d11).
        let a = f.inertia(&q).unwrap();
        let (i11, i14, i44) = (a[(0, 0)], a[(0, 1)], a[(1, 1)]);
        let (i11_1, i11_4, i14_1, i14_4, i44_1, i44_4) = (
            da[0][(0, 0)],
            da[1][(0, 0)],
            da[0][(0, 1)],
            da[1][(0, 1)],
            da[0][(1, 1)],
            da[1][(1, 1)],
        );
        let del = i11 * i44 - i14 * i14;
        let qd = Vector2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
        let qf = f.forces(0.0, &q, &qd).unwrap();
        let (q1, q4) = (qf[0], qf[1]);
        let a0 = (q1 * i44 - q4 * i14) / del;
        let a11 = (i14 * i14_1 - 0.5 * i14 * i11_4 - 0.5 * i44 * i11_1) / del;
        let a14 = (i14 * i44_1 - i44 * i11_4) / del;
        let a44 = (0.5 * i14 * i44_4 + 0.5 * i44 * i44_1 - i44 * i14_4) / del;
        let b0 = (q4 * i11 - q1 * i14) / del;
        let b11 = (0.5 * i14 * i11_1 - i11 * i14_1 + 0.5 * i11 * i11_4) / del;
        let b14 = (i14 * i11_4 - i11 * i44_1) / del;
        let b44 = (i14 * i14_4 - 0.5 * i14 * i44_1 - 0.5 * i11 * i44_4) / del;
        let (w1, w4) = (qd[0], qd[1]);
        let seed = Vector2::new(
            a0 + a11 * w1 * w1 + a14 * w1 * w4 + a44 * w4 * w4,
            b0 + b11 * w1 * w1 + b14 * w1 * w4 + b44 * w4 * w4,
        );
        let ours = accelerations(&f, 0.0, &q, &qd).unwrap();
        assert!(
            (seed - ours).norm() <= 1e-12 * ours.norm().max(1.0),
            "{seed} vs {ours}"
        );
        n += 1;
    }
    eprintln!("five-bar analytic vs numerical dA/dq: {worst:e}");
    assert!(worst < 1e-8, "analytic vs numerical dA/dq: {worst:e}");
}

#[test]
fn five_bar_inertia_is_symmetric_positive_definite_over_its_workspace() {
    for rods in [false, true] {
        let mut f = FiveBar::default();
        if rods {
            f.j_s2 = Some(f.m2 * f.l_ab * f.l_ab / 12.0);
            f.j_s3 = Some(f.m3 * f.l_cb * f.l_cb / 12.0);
        }
        let (mut inside, mut smallest) = (0, f64::INFINITY);
        let n = 120;
        for i in 0..=n {
            for j in 0..=n {
                let q = Vector2::new(
                    2.0 * PI * i as f64 / n as f64,
                    2.0 * PI * j as f64 / n as f64,
                );
                match f.kinematics(&q) {
                    Ok(_) => {}
                    Err(Error::NotAssemblable { .. }) | Err(Error::Singular { .. }) => continue,
                    Err(e) => panic!("{e}"),
                }
                let a = f.inertia(&q).unwrap();
                assert_eq!(a[(0, 1)], a[(1, 0)]);
                let eig = a.symmetric_eigenvalues();
                smallest = smallest.min(eig.min());
                assert!(a.cholesky().is_some());
                inside += 1;
            }
        }
        assert!(inside > 3000, "{inside} workspace positions");
        // At least the cranks' own inertia in every direction.
        assert!(
            smallest >= 0.02 * (1.0 - 1e-12),
            "smallest eigenvalue {smallest}"
        );
    }
}

#[test]
fn five_bar_energy_balance_with_gravity() {
    // Servos that never saturate: a clamp makes Q non-smooth, which lowers the order of any
    // method at the kinks (with the 5 N·m limit the residual falls only as h^1.4).
    let mut f = FiveBar {
        gravity: 9.81,
        j_s2: Some(0.003),
        ..FiveBar::default()
    };
    f.drive1.limit = 100.0;
    f.drive4.limit = 100.0;
    let s0 = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    let mut res = Vec::new();
    for h in [1e-3, 5e-4] {
        let r = run(&f, &Rk4, s0, &RunOptions::until(1.0, h)).unwrap();
        let (de, w) = energy_balance(&r.trajectory);
        let scale = r.trajectory.kinetic().iter().fold(0.0f64, |m, v| m.max(*v));
        res.push((de - w).abs() / scale);
        // The servos brought the cranks near their targets.
        assert!((r.last.q[0] - 100f64.to_radians()).abs() < 0.05);
    }
    eprintln!("five-bar energy residuals (h = 1 ms, 0.5 ms): {res:?}");
    assert!(res[0] < 1e-6, "relative residuals {res:?}");
    // Fourth order: halving h divides the residual by about 16.
    assert!(res[0] / res[1] > 10.0, "relative residuals {res:?}");
}

#[test]
fn five_bar_reports_singular_and_unassemblable_positions() {
    let f = FiveBar::default();
    // Cranks pointing away from each other: |AC| = 0.15 + 0.2 + 0.15 = l_AB + l_CB, the
    // couplers stretched into one line.
    let e = f.inertia(&Vector2::new(PI, 0.0)).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Singular {
                measure: "sin(phi3 - phi2)",
                ..
            }
        ),
        "{e}"
    );
    // With the frame hinges 0.1 m further apart the couplers no longer reach each other.
    let wide = FiveBar {
        d: nalgebra::Point2::new(0.3, 0.0),
        ..f
    };
    let e = wide.inertia(&Vector2::new(PI, 0.0)).unwrap_err();
    assert!(
        matches!(e, Error::NotAssemblable { gap, .. } if (gap - 0.1).abs() < 1e-12),
        "{e}"
    );
    // Near the singularity the conditioning measure is an output.
    let near = f.kinematics(&Vector2::new(PI - 0.01, 0.01)).unwrap();
    assert!(near.sin_phi3_minus_phi2.abs() < 0.1);
}

// ---------------------------------------------------------------------------------------
// Landing gear.

#[test]
fn landing_gear_inertia_is_the_seeds_corrected_71_to_73() {
    let g = LandingGear::default();
    let [z1, z2, z3, z4, z5, z6] = g.z.map(f64::from);
    let k = f64::from(g.k);
    let uh1 = z1 / (z1 + z3);
    let uh3 = z3 / (z1 + z3);
    let u36 = z6 / z4;
    let u56 = -z6 / z5;
    let u21 = (1.0 - z3 / z2) / (1.0 + z3 / z1);
    let u23 = (1.0 + z1 / z2) / (1.0 + z1 / z3);
    let r = g.carrier_arm;
    let i11 = g.i1 + k * g.m2 * r * r * uh1 * uh1 + k * g.i2 * u21 * u21 + g.ih * uh1 * uh1;
    let i66 = g.i6
        + k * g.m2 * r * r * uh3 * uh3 * u36 * u36
        + k * g.i2 * u23 * u23 * u36 * u36
        + g.ih * uh3 * uh3 * u36 * u36
        + g.i3 * u36 * u36
        + g.i5 * u56 * u56;
    let i16 =
        k * g.m2 * r * r * uh1 * uh3 * u36 + k * g.i2 * u21 * u23 * u36 + g.ih * uh1 * uh3 * u36;
    let a = g.inertia_matrix().unwrap();
    let want = Matrix2::new(i11, i16, i16, i66);
    assert!((a - want).amax() < 1e-15 * want.amax(), "{a} vs {want}");
    // D23, D26: the carrier's ratios (uH1, uH3·u36) as corrected, to the bit.
    assert_eq!(
        g.carrier_ratios(),
        Vector2::new(z1 / (z1 + z3), z3 / (z1 + z3) * z6 / z4)
    );
    // The printed (69), z1/(z2 + z3), is another number for this gear.
    assert!((z1 / (z2 + z3) - uh1).abs() > 1e-3, "{z2}");
    // Willis: with the sun at 1 and the ring (u36·q̇2) at −z1/z3, the carrier stands still.
    let q = Vector2::new(1.0, -(z1 / z3) / u36);
    assert!(g.carrier_ratios().dot(&q).abs() < 1e-15);
}

fn landing_run(g: &LandingGear, t_end: f64) -> tmm::dynamics::RunResult {
    let mut opts = RunOptions::until(t_end, 1e-3);
    opts.record_every = 10;
    opts.reach = Some(Reach {
        watch: Watch::Output(0),
        value: g.phi_h_max,
        direction: Direction::Rising,
    });
    run(g, &Rk4, State::at_rest(Vector2::zeros()), &opts).unwrap()
}

#[test]
fn landing_gear_retracts_with_two_motors_and_with_a_braked_failed_one() {
    let g = LandingGear::default();
    let both = landing_run(&g, 60.0);
    let Outcome::Reached { t: t_both } = both.outcome else {
        panic!("{:?}", both.outcome)
    };
    assert!((g.phi_h(&both.last.q).unwrap() - g.phi_h_max).abs() < 1e-9 * g.phi_h_max);
    assert!(t_both > 3.0 && t_both < 15.0, "retraction in {t_both} s");
    let (de, w) = energy_balance(&{
        let mut tr = both.trajectory.clone();
        // Simpson needs uniform samples: drop the located last row and keep an odd count.
        let keep = if (tr.len() - 1) % 2 == 1 {
            tr.len() - 1
        } else {
            tr.len() - 2
        };
        truncate(&mut tr, keep);
        tr
    });
    // The tabulated M_on(φ_H) is piecewise linear: its kinks cost RK4 and Simpson's rule
    // their full order there, so the balance holds to 1e-5 rather than to rounding.
    assert!((de - w).abs() < 1e-5 * w.abs(), "ΔE {de} vs W {w}");

    let mut braked = g.clone();
    braked.failure = Some(Failure::Motor6 { braked: true });
    let one = landing_run(&braked, 60.0);
    let Outcome::Reached { t: t_one } = one.outcome else {
        panic!("{:?}", one.outcome)
    };
    assert!(t_one > 1.5 * t_both, "{t_one} vs {t_both}");
    // The braked input never moved, and the brake carried a moment.
    assert!(one.trajectory.qd()[1].iter().all(|v| v.abs() < 1e-9));
    assert!(one
        .trajectory
        .output("M_brake")
        .unwrap()
        .iter()
        .any(|m| m.abs() > 0.1));
}

fn truncate(tr: &mut Trajectory, n: usize) {
    tr.truncate(n);
}

#[test]
fn landing_gear_with_an_unbraked_failed_motor_falls_back() {
    let g = LandingGear {
        failure: Some(Failure::Motor6 { braked: false }),
        ..LandingGear::default()
    };
    let mut opts = RunOptions::until(60.0, 1e-3);
    opts.record_every = 10;
    opts.reach = Some(Reach {
        watch: Watch::Output(0),
        value: 0.0,
        direction: Direction::Falling,
    });
    let r = run(&g, &Rk4, State::at_rest(Vector2::zeros()), &opts).unwrap();
    let Outcome::Reached { t } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    let phi_h = r.trajectory.output("phi_H").unwrap();
    let top = phi_h.iter().fold(0.0f64, |m, v| m.max(*v));
    assert!(top > 0.0 && top < g.phi_h_max, "rose to {top}");
    assert!(t > 0.0 && t < 60.0);
    // The working motor spins the free input backwards.
    assert!(r.last.qd[1] < 0.0);
}

// ---------------------------------------------------------------------------------------
// Tables, errors, CSV.

#[test]
fn table_interpolates_and_refuses_or_holds_outside() {
    let t = Table::new(vec![0.0, 2.0, 3.0], vec![1.0, 5.0, -1.0], Beyond::Error).unwrap();
    assert_eq!(t.at(1.0).unwrap(), 3.0);
    assert_eq!(t.at(2.5).unwrap(), 2.0);
    assert_eq!(t.at(3.0).unwrap(), -1.0);
    assert!(
        matches!(t.at(-0.1), Err(Error::OutOfRange { min, max, .. }) if min == 0.0 && max == 3.0)
    );
    assert!(matches!(t.at(f64::NAN), Err(Error::NonFinite { .. })));
    let h = Table::new(vec![0.0, 2.0, 3.0], vec![1.0, 5.0, -1.0], Beyond::HoldEnds).unwrap();
    assert_eq!(h.at(-5.0).unwrap(), 1.0);
    assert_eq!(h.at(7.0).unwrap(), -1.0);
    assert!(Table::new(vec![0.0, 0.0], vec![1.0, 2.0], Beyond::Error).is_err());
    assert!(Table::new(vec![0.0], vec![1.0], Beyond::Error).is_err());
    assert!(Table::new(vec![0.0, 1.0], vec![1.0], Beyond::Error).is_err());
}

struct Degenerate;
impl LagrangeSystem for Degenerate {
    fn inertia(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        // Loses rank where q₁ = q₂.
        Ok(Matrix2::new(1.0, 1.0, 1.0, 1.0 + (q[0] - q[1]).powi(2)))
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(1.0, 0.0))
    }
}

#[test]
fn errors_name_what_and_where() {
    let s = State::at_rest(Vector2::new(0.3, 0.3));
    let e = accelerations(&Degenerate, 2.5, &s.q, &s.qd).unwrap_err();
    let Error::NotPositiveDefinite { at, det } = &e else {
        panic!("{e}")
    };
    assert!(at.contains("t = 2.5") && at.contains("0.3"), "{at}");
    assert!(*det <= 0.0 || det.abs() < 1e-12);
    for h in [0.0, -1e-3] {
        assert!(matches!(
            Rk4.step(&RpArm::default(), &s, h),
            Err(Error::NonPositive { .. })
        ));
        assert!(matches!(
            FiniteIncrement.step(&RpArm::default(), &s, h),
            Err(Error::NonPositive { .. })
        ));
        assert!(matches!(
            run(&RpArm::default(), &Rk4, s, &RunOptions::until(1.0, h)),
            Err(Error::NonPositive { .. })
        ));
    }
    assert!(Dopri5::new(0.0).is_err());
    let bad = State::new(0.0, Vector2::new(f64::NAN, 0.0), Vector2::zeros());
    assert!(
        matches!(Rk4.step(&RpArm::default(), &bad, 0.1), Err(Error::NonFiniteState { time }) if time == 0.0)
    );
    // A strict table in the landing gear: falling below φ_H = 0 is an out-of-range lookup.
    let mut g = LandingGear::default();
    g.load = Table::new(g.load.xs().to_vec(), g.load.ys().to_vec(), Beyond::Error).unwrap();
    g.failure = Some(Failure::Motor6 { braked: false });
    let e = run(
        &g,
        &Rk4,
        State::at_rest(Vector2::zeros()),
        &RunOptions::until(30.0, 1e-3),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::OutOfRange {
                name: "table argument",
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn trajectory_csv_round_trips() {
    let d = CoaxialPropellers::default();
    let r = run(
        &d,
        &Rk4,
        State::at_rest(Vector2::zeros()),
        &RunOptions::until(0.1, 0.01),
    )
    .unwrap();
    let csv = r.trajectory.to_csv();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[..3], ["t", "phi_4", "phi_H"]);
    assert!(header.contains(&"omega_1"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 11);
    assert_eq!(rows[7][0], r.trajectory.t()[7]);
    assert_eq!(rows[7][4], r.trajectory.qd()[1][7]);
    let w1 = header.iter().position(|h| *h == "omega_1").unwrap();
    assert_eq!(rows[7][w1], r.trajectory.output("omega_1").unwrap()[7]);
}

// ---------------------------------------------------------------------------------------
// Property tests over random five-bar geometries.

mod props {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, max_global_rejects: 100_000, ..ProptestConfig::default() })]

        /// Random geometry, masses and state: A(q) is symmetric positive-definite and the
        /// accelerations agree with the independent d'Alembert–Lagrange formulation.
        #[test]
        fn five_bar_random_geometry(
            base in 0.05f64..0.4, l_oa in 0.08f64..0.3, l_dc in 0.08f64..0.3,
            l_ab in 0.2f64..0.5, l_cb in 0.2f64..0.5, s2 in 0.1f64..0.9, s3 in 0.1f64..0.9,
            m2 in 0.1f64..3.0, m3 in 0.1f64..3.0, phi1 in 0.0f64..PI, phi4 in 0.0f64..PI,
            w1 in -4.0f64..4.0, w4 in -4.0f64..4.0, mode in prop::bool::ANY,
        ) {
            let f = FiveBar {
                d: nalgebra::Point2::new(base, 0.0),
                l_oa, l_dc, l_ab, l_cb,
                l_as2: s2 * l_ab,
                l_bs3: s3 * l_cb,
                m2, m3,
                mode: if mode { 1.0 } else { -1.0 },
                gravity: 9.81,
                j_s2: Some(m2 * l_ab * l_ab / 12.0),
                ..FiveBar::default()
            };
            let q = Vector2::new(phi1, phi4);
            let k = f.kinematics(&q);
            prop_assume!(matches!(&k, Ok(k) if k.sin_phi3_minus_phi2.abs() > 0.1));
            let a = f.inertia(&q).unwrap();
            prop_assert!(a.cholesky().is_some());
            let qd = Vector2::new(w1, w4);
            let ours = accelerations(&f, 0.0, &q, &qd).unwrap();
            let indep = five_bar_independent(&f, &q, &qd);
            prop_assert!((ours - indep).norm() <= 1e-10 * ours.norm().max(indep.norm()), "{ours} vs {indep}");
        }
    }
}

#[test]
fn gear_drives_accelerations_are_the_seeds_corrected_87_88_and_127_128() {
    // Coaxial propellers, (127)–(128) (with D39's numerator).
    let d = CoaxialPropellers::default();
    let a = d.inertia_matrix().unwrap();
    let (i44, i4h, ihh) = (a[(0, 0)], a[(0, 1)], a[(1, 1)]);
    let u = d.input_ratios();
    let qd = Vector2::new(-40.0, 55.0);
    let mp1 = d.motor.torque(u.dot(&qd)).unwrap();
    let (m4, mh) = (d.m_on4, d.m_onh);
    let phh = ((m4 * i4h - mh * i44) + mp1 * (u[0] * i4h - u[1] * i44)) / (i4h * i4h - i44 * ihh);
    let p44 = ((m4 * ihh - mh * i4h) + mp1 * (u[0] * ihh - u[1] * i4h)) / (i44 * ihh - i4h * i4h);
    let ours = accelerations(&d, 0.0, &Vector2::zeros(), &qd).unwrap();
    assert!((ours - Vector2::new(p44, phh)).norm() < 1e-12 * ours.norm());

    // Landing gear, (87)–(88) with D28's inertia on the Q6 term.
    let g = LandingGear::default();
    let a = g.inertia_matrix().unwrap();
    let (i11, i16, i66) = (a[(0, 0)], a[(0, 1)], a[(1, 1)]);
    let q = Vector2::new(3000.0, 2500.0);
    let qd = Vector2::new(900.0, 1100.0);
    let m_on = g.load.at(g.phi_h(&q).unwrap()).unwrap();
    let uh = g.carrier_ratios();
    let q1 = g.motor1.torque(qd[0]).unwrap() + m_on * uh[0];
    let q6 = g.motor6.torque(qd[1]).unwrap() + m_on * uh[1];
    let p1 = (q1 * i66 - q6 * i16) / (i11 * i66 - i16 * i16);
    let p6 = (q1 * i16 - q6 * i11) / (i16 * i16 - i11 * i66);
    let ours = accelerations(&g, 0.0, &q, &qd).unwrap();
    assert!((ours - Vector2::new(p1, p6)).norm() < 1e-12 * ours.norm());
}

/// A rotor of 0.5 kg·m² under a viscous moment −0.25·ω (ω(t) = ω0·e^(−t/2)) beside a
/// second coordinate that never moves; `short` outputs fewer values than it names.
struct SpinDown {
    short: bool,
}
impl LagrangeSystem for SpinDown {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(0.5, 0.0, 0.0, 1.0))
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::zeros())
    }
    fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(0.25, 0.0, 0.0, 0.0))
    }
    fn output_names(&self) -> Vec<&'static str> {
        vec!["omega", "twice omega"]
    }
    fn outputs(
        &self,
        _: f64,
        _: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> tmm::Result<()> {
        out.push(qd[0]);
        if !self.short {
            out.push(2.0 * qd[0]);
        }
        Ok(())
    }
}

#[test]
fn dormand_prince_first_same_as_last_saves_an_evaluation_and_changes_nothing() {
    let sys = SpinDown { short: false };
    let dp = Dopri5::new(1e-9).unwrap();
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
    // One step: the last stage is q̈ at the end state, to the last bit.
    let a = dp.advance(&sys, &s0, 0.1).unwrap();
    let end = a.handover.acceleration.unwrap();
    assert_eq!(
        end,
        accelerations(&sys, a.state.t, &a.state.q, &a.state.qd).unwrap()
    );
    // Given it, the next step is the same step for one evaluation less (both given the
    // step-size controller's memory, the error norm of the step before).
    let forget = |h: Handover| Handover {
        acceleration: None,
        ..h
    };
    let fresh = dp
        .advance_from(&sys, &a.state, a.h_next, Some(forget(a.handover)))
        .unwrap();
    let reused = dp
        .advance_from(&sys, &a.state, a.h_next, Some(a.handover))
        .unwrap();
    assert_eq!((fresh.state, fresh.h_next), (reused.state, reused.h_next));
    assert_eq!(fresh.evaluations, reused.evaluations + 1);
    // A run passes it on: the same motion as stepping without reuse (with the same
    // controller memory), and exactly one evaluation saved per step after the first.
    let t_end = 3.0;
    let r = run(&sys, &dp, s0, &RunOptions::until(t_end, 0.1)).unwrap();
    let (mut s, mut h, mut evals, mut steps) = (s0, 0.1_f64, 0, 0);
    let mut from = None;
    while s.t < t_end - 1e-12 {
        let a = dp.advance_from(&sys, &s, h.min(t_end - s.t), from).unwrap();
        if h < t_end - s.t {
            h = a.h_next;
        }
        from = Some(forget(a.handover));
        (s, evals, steps) = (a.state, evals + a.evaluations, steps + 1);
    }
    assert_eq!(r.steps, steps);
    assert_eq!((r.last.q, r.last.qd), (s.q, s.qd));
    assert_eq!(r.evaluations, evals - (steps - 1));
    assert!((r.last.qd[0] - 2.0 * (-0.5 * t_end).exp()).abs() < 1e-8);
}

/// A pendulum-like pair with a configuration-dependent inertia and a time-dependent drive
/// that counts how often its forces are evaluated (once per evaluation of the terms).
struct Counted {
    calls: std::cell::Cell<usize>,
}
impl LagrangeSystem for Counted {
    fn inertia(&self, q: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        let c = 0.3 * (q[0] - q[1]).cos();
        Ok(Matrix2::new(1.0, c, c, 0.8))
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        self.calls.set(self.calls.get() + 1);
        Ok(Vector2::new(
            (3.0 * t).sin() - 2.0 * q[0].sin() - 0.1 * qd[0],
            -q[1].sin(),
        ))
    }
}

/// A recorded row's q̈ are the first stage of the step that starts there: RK4 and finite
/// increments take them over, so that a run recording every step costs the method's own
/// evaluations and no more. The motion is the bare steps' to the last bit, the reported
/// counts are the method's evaluations per step, and the terms are evaluated once per
/// reported evaluation plus once for the end row (recording every step used to add one
/// evaluation per step).
#[test]
fn recorded_rows_hand_their_accelerations_to_the_next_step() {
    let s0 = State::new(0.0, Vector2::new(0.4, -0.2), Vector2::new(0.0, 1.0));
    // Binary fractions: the run's last step, clamped onto the end, is a whole step too.
    let (t_end, h) = (2.5, 0.0625);
    let n = 40;
    fn check<M: Stepper>(m: &M, s0: State, t_end: f64, h: f64, n: usize) {
        let sys = Counted {
            calls: std::cell::Cell::new(0),
        };
        let mut bare = s0;
        for _ in 0..n {
            bare = m.step(&sys, &bare, h).unwrap();
        }
        let lean = RunOptions::until(t_end, h);
        let sparse = RunOptions {
            record_every: 7,
            ..RunOptions::until(t_end, h)
        };
        // A steady state that is never reached takes the run's full loop.
        let full = RunOptions {
            steady: Some(Steady {
                tol: 1e-300,
                hold: 1e9,
            }),
            ..RunOptions::until(t_end, h)
        };
        for (what, opts) in [("lean", lean), ("sparse", sparse), ("full", full)] {
            sys.calls.set(0);
            let r = run(&sys, m, s0, &opts).unwrap();
            let name = format!("{} {what}", m.name());
            assert_eq!(r.steps, n, "{name}");
            assert_eq!((r.last.q, r.last.qd), (bare.q, bare.qd), "{name}");
            assert_eq!(r.evaluations, n * m.evaluations_per_step(), "{name}");
            // Rows not handed on (between recorded steps and at the end) cost their own.
            let rows = r.trajectory.len();
            let handed = if what == "sparse" { rows - 1 } else { n };
            assert_eq!(
                sys.calls.get(),
                r.evaluations + rows - handed,
                "{name}: {rows} rows"
            );
            // The trajectory's q̈ are the system's at every row.
            let tr = &r.trajectory;
            let ([q0, q1], [v0, v1], [a0, a1]) = (tr.q(), tr.qd(), tr.qdd());
            for k in 0..rows {
                let (q, v) = (Vector2::new(q0[k], q1[k]), Vector2::new(v0[k], v1[k]));
                let a = accelerations(&sys, tr.t()[k], &q, &v).unwrap();
                assert_eq!((a0[k], a1[k]), (a[0], a[1]), "{name} row {k}");
            }
        }
    }
    check(&Rk4, s0, t_end, h, n);
    check(&FiniteIncrement, s0, t_end, h, n);
}

/// A stepper of the user's that reports absurd evaluation counts and takes the rows' q̈:
/// the run's count saturates and its budget ends the run (it must not overflow, in the lean
/// loop or the full one).
#[test]
fn a_stepper_reporting_huge_counts_meets_the_budget() {
    struct Boastful;
    impl Stepper for Boastful {
        type Dense = tmm::dynamics::NoExtension;
        fn name(&self) -> &'static str {
            "boastful"
        }
        fn order(&self) -> u32 {
            4
        }
        fn evaluations_per_step(&self) -> usize {
            usize::MAX
        }
        fn step<S: LagrangeSystem + ?Sized>(
            &self,
            sys: &S,
            s: &State,
            h: f64,
        ) -> tmm::Result<State> {
            Rk4.step(sys, s, h)
        }
        fn advance_from<S: LagrangeSystem + ?Sized>(
            &self,
            sys: &S,
            s: &State,
            h: f64,
            _: Option<Handover>,
        ) -> tmm::Result<tmm::dynamics::Advance> {
            Ok(tmm::dynamics::Advance {
                state: Rk4.step(sys, s, h)?,
                h_next: h,
                evaluations: usize::MAX,
                handover: Handover::default(),
            })
        }
        fn uses_start_acceleration(&self) -> bool {
            true
        }
    }
    let sys = SpinDown { short: false };
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
    let lean = RunOptions::until(1.0, 0.1);
    let full = RunOptions {
        steady: Some(Steady {
            tol: 1e-300,
            hold: 1e9,
        }),
        ..RunOptions::until(1.0, 0.1)
    };
    for opts in [lean, full] {
        match run(&sys, &Boastful, s0, &opts) {
            Err(Error::Budget { what, time, .. }) => {
                assert_eq!(what, "evaluation");
                assert!((time - 0.1).abs() < 1e-15, "{time}");
            }
            other => panic!("{other:?}"),
        }
    }
}

/// The step-size controller is the PI controller its docs derive: after an accepted step with
/// error norm err, the next step is h·0.9·err^(−α)·errₙ₋₁^β (α = 0.17, β = 0.04) given the
/// error norm errₙ₋₁ of the step before, and h·0.9·err^(−1/5) without it.
#[test]
fn dormand_prince_step_sizes_follow_the_pi_controller() {
    let sys = SpinDown { short: false };
    let dp = Dopri5::new(1e-9).unwrap();
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
    let (alpha, beta) = (0.2 - 0.75 * 0.04, 0.04);
    let with = |memory: Option<f64>| {
        let from = Handover {
            acceleration: None,
            error_norm: memory,
        };
        dp.advance_from(&sys, &s0, 0.1, Some(from)).unwrap()
    };
    let first = with(None);
    let err = first.handover.error_norm.unwrap();
    assert!(err > 0.0 && err <= 1.0, "{err}");
    let h = first.state.t; // accepted as asked (no rejection)
    assert_eq!(h, 0.1);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b;
    assert!(close(first.h_next, h * 0.9 * err.powf(-0.2)));
    for m in [1e-3, 0.1, 0.5, 1.0] {
        let a = with(Some(m));
        // The same step (the memory changes only the proposal).
        assert_eq!((a.state, a.handover.error_norm), (first.state, Some(err)));
        let want = h * 0.9 * err.powf(-alpha) * m.powf(beta);
        assert!(close(a.h_next, want), "memory {m}: {} vs {want}", a.h_next);
    }
    // A smaller error before means errors are growing: a more cautious proposal.
    assert!(with(Some(1e-3)).h_next < with(Some(0.5)).h_next);
    // An exact step before (err = 0) is remembered as 10⁻⁴, not as 0 (which would propose
    // h = 0); a remembered error that is not a number is ignored.
    assert_eq!(with(Some(0.0)).h_next, with(Some(1e-4)).h_next);
    assert!(with(Some(0.0)).h_next > 0.0);
    assert_eq!(with(Some(f64::NAN)).h_next, first.h_next);
    assert_eq!(with(Some(-1.0)).h_next, first.h_next);
}

/// A 1 kg slider pushed by 2 N until t = 0.5 s and pulled back by 1 N after, the jump not
/// declared as a breakpoint: x is piecewise quadratic, so every step not straddling the jump
/// is exact (err = 0) and the step size grows tenfold a step until one straddles it.
struct Pulse;
impl LagrangeSystem for Pulse {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(if t < 0.5 { 2.0 } else { -1.0 }, 0.0))
    }
}

/// After a rejection the next step does not grow. A jump of the forces that no breakpoint
/// declares costs rejections (the controller homes in on it step by step), and accuracy too:
/// across a jump the embedded estimate understates the error (both solutions are of order 1
/// there), which is why `run` steps onto declared breakpoints and kinks.
#[test]
fn dormand_prince_across_an_undeclared_jump() {
    let tol = 1e-8;
    let dp = Dopri5::new(tol).unwrap();
    let r = run(
        &Pulse,
        &dp,
        State::at_rest(Vector2::zeros()),
        &RunOptions::until(1.0, 1e-3),
    )
    .unwrap();
    // Every trial after the first costs six evaluations (first same as last).
    assert_eq!((r.evaluations - 1) % 6, 0);
    assert!((r.evaluations - 1) / 6 > r.steps, "rejections expected");
    // v(1) = 1 − 0.5 = 0.5: off by far more than the tolerance.
    assert!((r.last.qd[0] - 0.5).abs() > 10.0 * tol, "{}", r.last.qd[0]);
    // A step asked far too long is accepted shorter and proposes no longer a step than the
    // one it took (its estimate just failed near there).
    let s = State::new(0.45, Vector2::new(0.2025, 0.0), Vector2::new(0.9, 0.0));
    let a = dp.advance(&Pulse, &s, 0.1).unwrap();
    let taken = a.state.t - s.t;
    assert!(
        taken < 0.1 && a.evaluations > 7,
        "{taken} {}",
        a.evaluations
    );
    assert!(a.h_next <= taken, "{} after {taken}", a.h_next);
}

/// A slider pushed by F = √t from rest: q̈ has an infinite derivative at t = 0, so the error
/// estimate of a first step grows like h^2.5, not h⁵.
struct Root;
impl LagrangeSystem for Root {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(t.max(0.0).sqrt(), 0.0))
    }
}

/// From the second rejection of a step on, the controller shortens it by the exponent the
/// failed trials showed instead of the asymptotic 1/5. For the first step of 0.1 s under
/// F = √t (err ≈ C·h^2.5, err ≈ 3·10⁴ at 0.1 s and ≈ 0.85 at 1.5 ms), the fixed exponent
/// would take six trials (0.1 → 0.02 → 5.0e-3 → 2.5e-3 → 1.8e-3 → 1.5e-3 s, each
/// h·max(0.2, 0.9·err^(−1/5))); the observed one takes four, to a step as long.
#[test]
fn dormand_prince_shortens_a_failing_step_by_the_exponent_it_shows() {
    let dp = Dopri5::new(1e-8).unwrap();
    let a = dp
        .advance(&Root, &State::at_rest(Vector2::zeros()), 0.1)
        .unwrap();
    let err = a.handover.error_norm.unwrap();
    let trials = (a.evaluations - 1) / 6;
    assert!(trials <= 4, "{trials} trials");
    assert!((0.5..=1.0).contains(&err), "accepted at err = {err}");
    assert!((1e-3..2e-3).contains(&a.state.t), "{}", a.state.t);
}

/// ode_solvers 0.6.2's Dopri5 (Hairer and Wanner's PI controller) spends 637 evaluations on
/// the five-bar robot's first 0.5 s at rtol = atol = 10⁻⁸ with the same first step, reaching
/// an error of 5.2e-9 (`benches/peers.rs` prints both): tmm, stepping across the
/// servos' switches as the peer does, spends no more for no worse an error.
#[test]
fn dormand_prince_five_bar_costs_no_more_than_the_peer() {
    let fb = FiveBar::default();
    let s0 = State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()));
    // The peer knows nothing of the servos' switches: tmm steps across them as it does.
    let blind = RunOptions {
        record_every: usize::MAX,
        locate_kinks: false,
        ..RunOptions::until(0.5, 5e-4)
    };
    let located = RunOptions {
        locate_kinks: true,
        ..blind.clone()
    };
    let at = |tol: f64, opts: &RunOptions| run(&fb, &Dopri5::new(tol).unwrap(), s0, opts).unwrap();
    let (r, reference) = (at(1e-8, &blind), at(1e-14, &located).last);
    let error = (r.last.q - reference.q)
        .amax()
        .max((r.last.qd - reference.qd).amax());
    assert!(r.evaluations <= 637, "{} evaluations", r.evaluations);
    assert!(error <= 5.2e-9, "error {error:e}");
}

#[test]
fn dormand_prince_pure_relative_tolerance_and_tiny_requested_steps() {
    // atol = 0 with a coordinate at rest: its error and its scale are both zero (0/0 used
    // to reject every step).
    let sys = SpinDown { short: false };
    let dp = Dopri5 {
        rtol: 1e-9,
        atol: 0.0,
    };
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
    let r = run(&sys, &dp, s0, &RunOptions::until(1.0, 0.1)).unwrap();
    assert!((r.last.qd[0] - 2.0 * (-0.5f64).exp()).abs() < 1e-8);
    assert_eq!(r.last.q[1], 0.0);
    // A step the caller asks for below the controller's floor is taken, not refused.
    let a = Dopri5::new(1e-9)
        .unwrap()
        .advance(&sys, &s0, 1e-13)
        .unwrap();
    assert_eq!(a.state.t, 1e-13);
    assert!((a.state.qd[0] - 2.0 * (-0.5e-13f64).exp()).abs() < 1e-15);
}

#[test]
fn run_options_cannot_loop_for_ever_panic_or_stop_early() {
    let sys = SpinDown { short: false };
    let s0 = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
    // A step longer than the whole run takes the run to its end in one step.
    for h in [1.0, 10.0, 1e13] {
        let r = run(&sys, &Rk4, s0, &RunOptions::until(1.0, h)).unwrap();
        assert_eq!((r.steps, r.last.t), (1, 1.0), "h = {h}");
        let one = Rk4.step(&sys, &s0, 1.0).unwrap();
        assert_eq!(r.last.qd, one.qd);
    }
    // A step below the rounding of t cannot advance the run: an error, not an endless loop.
    let late = State::new(1e10, Vector2::zeros(), Vector2::new(2.0, 0.0));
    let e = run(&sys, &Rk4, late, &RunOptions::until(1e10 + 1.0, 1e-7)).unwrap_err();
    assert!(matches!(e, Error::Singular { what: "run", .. }), "{e}");
    let e = run(
        &sys,
        &FiniteIncrement,
        late,
        &RunOptions::until(1e10 + 1.0, 1e-7),
    )
    .unwrap_err();
    assert!(matches!(e, Error::Singular { what: "run", .. }), "{e}");
    // Bad numbers in the options are errors.
    let mut bad = Vec::new();
    for (t_end, h) in [
        (f64::NAN, 0.1),
        (1.0, f64::NAN),
        (1.0, f64::INFINITY),
        (0.0, 0.1),
        (-1.0, 0.1),
    ] {
        bad.push(RunOptions::until(t_end, h));
    }
    let mut o = RunOptions::until(1.0, 0.1);
    o.record_every = 0;
    bad.push(o);
    // (Hold zero would make any two steps with equal accelerations a drift verdict.)
    for (tol, hold) in [
        (0.0, 1.0),
        (f64::NAN, 1.0),
        (1e-3, 0.0),
        (1e-3, -1.0),
        (1e-3, f64::NAN),
    ] {
        let mut o = RunOptions::until(1.0, 0.1);
        o.steady = Some(Steady { tol, hold });
        bad.push(o);
    }
    for value in [f64::NAN, f64::INFINITY] {
        let mut o = RunOptions::until(1.0, 0.1);
        o.reach = Some(Reach {
            watch: Watch::Speed(0),
            value,
            direction: Direction::Falling,
        });
        bad.push(o);
    }
    for watch in [Watch::Coordinate(2), Watch::Speed(7), Watch::Output(2)] {
        let mut o = RunOptions::until(1.0, 0.1);
        o.reach = Some(Reach {
            watch,
            value: 1.0,
            direction: Direction::Either,
        });
        bad.push(o);
    }
    for o in &bad {
        for r in [
            run(&sys, &Rk4, s0, o),
            run(&sys, &FiniteIncrement, s0, o),
            run(&sys, &Dopri5::new(1e-8).unwrap(), s0, o),
        ] {
            assert!(r.is_err(), "{o:?}");
        }
    }
    // Steady once |q̈| = 0.5 ω ≤ 0.1, i.e. ω ≤ 0.2 from t = 2 ln 10 = 4.605 s, held 3 s (longer
    // than the time constant 2 s, so that the decay is not taken for a drift).
    let mut o = RunOptions::until(10.0, 0.01);
    o.steady = Some(Steady {
        tol: 0.1,
        hold: 3.0,
    });
    for r in [
        run(&sys, &Rk4, s0, &o).unwrap(),
        run(&sys, &Dopri5::new(1e-10).unwrap(), s0, &o).unwrap(),
    ] {
        let Outcome::Steady { t } = r.outcome else {
            panic!("{:?}", r.outcome)
        };
        let t_s = 2.0 * 10f64.ln() + 3.0;
        assert!(t >= t_s && t < t_s + 0.5, "{t}");
    }
    // A system that gives fewer outputs than it names: an error, not an index panic.
    let mut o = RunOptions::until(1.0, 0.1);
    o.reach = Some(Reach {
        watch: Watch::Output(1),
        value: 1.0,
        direction: Direction::Falling,
    });
    let e = run(&SpinDown { short: true }, &Rk4, s0, &o).unwrap_err();
    assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
}

#[test]
fn energies_and_closed_forms_refuse_non_finite_input() {
    let sys = SpinDown { short: false };
    let (q, nan) = (Vector2::zeros(), Vector2::new(f64::NAN, 0.0));
    assert!(tmm::dynamics::kinetic_energy(&sys, &q, &nan).is_err());
    assert!(tmm::dynamics::kinetic_energy(&sys, &nan, &q).is_err());
    assert!(tmm::dynamics::powers(&sys, 0.0, &q, &nan).is_err());
    assert!(tmm::dynamics::powers(&sys, f64::NAN, &q, &q).is_err());
    let huge = Vector2::new(1e200, 0.0);
    assert!(tmm::dynamics::kinetic_energy(&sys, &q, &huge).is_err());
    // T = ½·0.5·2² = 1 J; no applied load; dissipated q̇ᵀBq̇ = 0.25·2² = 1 W.
    assert_eq!(
        tmm::dynamics::kinetic_energy(&sys, &q, &Vector2::new(2.0, 0.0)),
        Ok(1.0)
    );
    assert_eq!(
        tmm::dynamics::powers(&sys, 0.0, &q, &Vector2::new(2.0, 0.0)),
        Ok((0.0, 1.0))
    );

    let d = CoaxialPropellers::default();
    let s0 = State::at_rest(Vector2::zeros());
    assert!(d.exact(&s0, f64::NAN).is_err());
    assert!(d.exact(&State::new(0.0, nan, q), 1.0).is_err());
    let arm = RpArm::default().decoupled();
    assert!(arm.closed_form(&s0, f64::INFINITY).is_err());
    assert!(
        arm.closed_form(&s0, -1e6).is_err(),
        "e^(+c·1e6/m) overflows"
    );
    assert!(arm.closed_form(&State::new(f64::NAN, q, q), 1.0).is_err());

    // A constant-moment motor (b = 0): no damping, so the accelerations are those of the
    // start for ever (they used to be 0/0).
    let mut c = CoaxialPropellers::default();
    c.motor.b = 0.0;
    let drift = c.drift_acceleration().unwrap();
    let a0 = accelerations(&c, 0.0, &q, &Vector2::new(50.0, -30.0)).unwrap();
    assert!((drift - a0).norm() <= 1e-12 * a0.norm(), "{drift} vs {a0}");
    c.motor.b = -1.0;
    assert!(c.drift_acceleration().is_err());
    c.motor.b = f64::NAN;
    assert!(c.drift_acceleration().is_err() && c.exact(&s0, 1.0).is_err());
}

/// A block of mass m on a ramp of angle α, x up the slope, with dry friction of a constant
/// magnitude `friction` against its sliding (a velocity-sign switch, x′ = 0): under gravity
/// alone its drive at rest is −m·g·sin α. The second coordinate is a decoupled unit mass.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ramp {
    pub(crate) m: f64,
    pub(crate) alpha: f64,
    pub(crate) friction: f64,
}

impl Ramp {
    pub(crate) const G: f64 = 9.81;
    pub(crate) fn slope_pull(&self) -> f64 {
        -self.m * Self::G * self.alpha.sin()
    }
}

impl LagrangeSystem for Ramp {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(self.m, 0.0, 0.0, 1.0))
    }
    fn inertia_derivatives(&self, _: &Vector2<f64>) -> tmm::Result<[Matrix2<f64>; 2]> {
        Ok([Matrix2::zeros(); 2])
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        let resist = if qd[0] > 0.0 {
            -self.friction
        } else if qd[0] < 0.0 {
            self.friction
        } else {
            0.0
        };
        Ok(Vector2::new(self.slope_pull() + resist, 0.0))
    }
    fn switches(&self) -> usize {
        1
    }
    fn switch_speeds(
        &self,
        _: f64,
        _: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> tmm::Result<()> {
        out[0] = qd[0];
        Ok(())
    }
    fn switch_force(
        &self,
        _: usize,
        _: f64,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        direction: f64,
    ) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(-direction * self.friction, 0.0))
    }
    fn switch_loads(
        &self,
        _: usize,
        _: f64,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
    ) -> tmm::Result<tmm::dynamics::SwitchLoads> {
        Ok(tmm::dynamics::SwitchLoads {
            what: "block",
            unit: "N",
            drive: self.slope_pull(),
            forward: self.friction,
            backward: self.friction,
        })
    }
}

/// Thrown up the ramp at v₀, the block decelerates at (m·g·sin α + F)/m to rest at
/// t₁ = v₀/a₁, x₁ = v₀²/(2a₁). With friction above the slope's pull it stays there: the run
/// ends at t₁, stuck, naming both loads. Below it, the block slides back down at
/// (m·g·sin α − F)/m. Piecewise constant accelerations: every method that lands on the switch
/// integrates both pieces exactly (RK4 and Dormand–Prince to rounding), where stepping across
/// it chattered about v = 0 until the step budget ran out.
#[test]
fn a_block_on_a_ramp_sticks_or_slides_back_exactly() {
    let (m, alpha, v0) = (2.0, 0.3_f64, 3.0);
    let pull = m * Ramp::G * alpha.sin(); // 5.80 N
    let start = State::new(0.0, Vector2::zeros(), Vector2::new(v0, 0.0));
    let dp = Dopri5::new(1e-10).unwrap();
    // Sticks: friction 8 N above the pull.
    let held = Ramp {
        m,
        alpha,
        friction: 8.0,
    };
    let a1 = (pull + held.friction) / m;
    let (t1, x1) = (v0 / a1, v0 * v0 / (2.0 * a1));
    for (name, r) in [
        (
            "RK4",
            run(&held, &Rk4, start, &RunOptions::until(2.0, 0.01)),
        ),
        (
            "Dormand-Prince",
            run(&held, &dp, start, &RunOptions::until(2.0, 0.01)),
        ),
    ] {
        let r = r.unwrap();
        let Outcome::Stuck { t, switch, loads } = r.outcome else {
            panic!("{name}: {:?}", r.outcome);
        };
        assert!((t - t1).abs() < 1e-12, "{name}: stuck at {t}, exact {t1}");
        assert!(
            (r.last.q[0] - x1).abs() < 1e-12,
            "{name}: x = {}",
            r.last.q[0]
        );
        assert!(r.last.qd[0].abs() < 1e-10, "{name}: v = {}", r.last.qd[0]);
        assert_eq!(switch, 0);
        assert!(loads.holds() && (loads.drive + pull).abs() < 1e-15);
        assert!(r.steps < 100, "{name}: {} steps", r.steps);
        let e = loads.stalled(t);
        assert!(e.to_string().contains("below the resistance 8 N"), "{e}");
    }
    // Slides back: friction 2 N below the pull; the exact motion at t = 2 s.
    let slides = Ramp {
        m,
        alpha,
        friction: 2.0,
    };
    let a1 = (pull + slides.friction) / m;
    let a2 = (pull - slides.friction) / m;
    let (t1, x1) = (v0 / a1, v0 * v0 / (2.0 * a1));
    let t_end = 2.0;
    let x_end = x1 - 0.5 * a2 * (t_end - t1).powi(2);
    let v_end = -a2 * (t_end - t1);
    for (name, r) in [
        (
            "RK4",
            run(&slides, &Rk4, start, &RunOptions::until(t_end, 0.01)),
        ),
        (
            "Dormand-Prince",
            run(&slides, &dp, start, &RunOptions::until(t_end, 0.01)),
        ),
    ] {
        let r = r.unwrap();
        assert_eq!(r.outcome, Outcome::FinalTime, "{name}");
        assert!(
            (r.last.q[0] - x_end).abs() < 1e-11,
            "{name}: {} vs {x_end}",
            r.last.q[0]
        );
        assert!(
            (r.last.qd[0] - v_end).abs() < 1e-11,
            "{name}: {} vs {v_end}",
            r.last.qd[0]
        );
        // The turning point is a step end (landed on, not stepped across), recorded by the
        // adaptive method (a fixed-step method records its grid only).
        let lands = r.trajectory.t().iter().any(|&t| (t - t1).abs() < 1e-12);
        assert!(lands || name == "RK4", "{name}: no step ends at t₁ = {t1}");
        assert!(r.steps < 300, "{name}: {} steps", r.steps);
    }
    // At rest on the ramp from the start: held at once, or sliding off at once.
    let rest = State::at_rest(Vector2::zeros());
    let r = run(&held, &dp, rest, &RunOptions::until(1.0, 0.01)).unwrap();
    assert!(matches!(r.outcome, Outcome::Stuck { t: 0.0, .. }) && r.steps == 0);
    // (Its first step sees no friction in its first stage, where v = 0 exactly: not exact.)
    let r = run(&slides, &Rk4, rest, &RunOptions::until(1.0, 0.01)).unwrap();
    assert!(
        (r.last.q[0] + 0.5 * a2).abs() < 1e-3 * 0.5 * a2,
        "{}",
        r.last.q[0]
    );
}
