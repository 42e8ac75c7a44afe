//! Dynamics: error at the final time against the cost of each stepper on three machines, and
//! the stability limits of the two fixed-step methods, all from the crate's own runs.
//!
//! - Coaxial propellers (linear, constant inertia): the error is against the exact solution
//!   (`CoaxialPropellers::exact`, a matrix exponential).
//! - Five-bar robot (its default servos, which saturate at 5 N·m, and the same machine with
//!   servos that never saturate) and landing gear: the error is against a tight reference, Dormand–Prince
//!   at a tolerance of 10⁻¹³; its own error is estimated by the distance to the run at 10⁻¹²
//!   and reported, and only errors well above it are used for the slopes.
//!
//! The error of a run is max(|Δq|∞ / |q_ref|∞, |Δq̇|∞ / |q̇_ref|∞) at the final time.

use std::time::Instant;

use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar, LandingGear, Servo};
use tmm::dynamics::{
    run, Dopri5, FiniteIncrement, LagrangeSystem, Rk4, RunOptions, RunResult, State, Stepper,
};

/// The three steppers, in chart order.
pub const METHODS: [&str; 3] = ["finite increments", "RK4", "Dormand-Prince"];
/// The three machines, in chart order.
pub const MACHINES: [&str; 4] = [
    "coaxial propellers",
    "five-bar (servos saturating)",
    "five-bar (servos unsaturated)",
    "landing gear",
];

/// One run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// The step size h, s (fixed-step methods) or the tolerance (Dormand–Prince).
    pub parameter: f64,
    /// Steps taken.
    pub steps: usize,
    /// Evaluations of the accelerations q̈.
    pub evaluations: usize,
    /// Error at the final time (see the module docs).
    pub error: f64,
    /// Wall time of one run, s (the fastest of several; 0 when timing is off).
    pub seconds: f64,
}

/// One stepper on one machine over its range of steps or tolerances.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// One of [`MACHINES`].
    pub machine: &'static str,
    /// One of [`METHODS`].
    pub method: &'static str,
    /// The runs, coarsest first.
    pub points: Vec<Point>,
    /// The error of the reference itself (0 for an exact solution).
    pub reference_error: f64,
}

/// What is run on one machine.
struct Setup {
    t_end: f64,
    start: State,
    fi_steps: Vec<usize>,
    rk4_steps: Vec<usize>,
    tolerances: Vec<f64>,
}

fn doubling(from: usize, count: u32) -> Vec<usize> {
    (0..count).map(|k| from << k).collect()
}

fn setup(machine: &str) -> Setup {
    let tolerances = (3..=12).map(|k| 10f64.powi(-k)).collect();
    match machine {
        "coaxial propellers" => Setup {
            t_end: 1.0,
            start: State::at_rest(Vector2::zeros()),
            fi_steps: doubling(100, 8),
            rk4_steps: doubling(10, 7),
            tolerances,
        },
        "five-bar (servos saturating)" | "five-bar (servos unsaturated)" => Setup {
            t_end: 0.5,
            start: State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians())),
            fi_steps: doubling(100, 8),
            rk4_steps: doubling(10, 8),
            tolerances,
        },
        _ => Setup {
            t_end: 2.0,
            start: State::at_rest(Vector2::zeros()),
            fi_steps: doubling(200, 8),
            rk4_steps: doubling(20, 8),
            tolerances,
        },
    }
}

/// Runs only to the final time, recording nothing on the way (as a benchmark would).
fn options(t_end: f64, h: f64) -> RunOptions {
    RunOptions {
        record_every: usize::MAX,
        ..RunOptions::until(t_end, h)
    }
}

fn run_method<S: LagrangeSystem>(
    sys: &S,
    method: &str,
    parameter: f64,
    su: &Setup,
) -> tmm::Result<RunResult> {
    match method {
        "finite increments" => run(
            sys,
            &FiniteIncrement,
            su.start,
            &options(su.t_end, parameter),
        ),
        "RK4" => run(sys, &Rk4, su.start, &options(su.t_end, parameter)),
        _ => run(
            sys,
            &Dopri5::new(parameter)?,
            su.start,
            &options(su.t_end, 1e-3 * su.t_end),
        ),
    }
}

/// The error measure of the module docs.
pub fn error(s: &State, reference: &State) -> f64 {
    ((s.q - reference.q).amax() / reference.q.amax())
        .max((s.qd - reference.qd).amax() / reference.qd.amax())
}

/// The fastest of enough repetitions of `f` to fill about 20 ms.
fn fastest<R>(mut f: impl FnMut() -> R) -> f64 {
    let (mut best, mut total, mut reps) = (f64::INFINITY, 0.0, 0);
    while total < 0.02 && reps < 1000 {
        let t0 = Instant::now();
        std::hint::black_box(f());
        let el = t0.elapsed().as_secs_f64();
        best = best.min(el);
        total += el;
        reps += 1;
    }
    best
}

fn lines_for<S: LagrangeSystem>(
    sys: &S,
    machine: &'static str,
    exact: Option<State>,
    timed: bool,
) -> tmm::Result<Vec<Line>> {
    let su = setup(machine);
    let (reference, reference_error) = match exact {
        Some(e) => (e, 0.0),
        None => {
            let tight = run_method(sys, "Dormand-Prince", 1e-13, &su)?.last;
            let looser = run_method(sys, "Dormand-Prince", 1e-12, &su)?.last;
            (tight, error(&looser, &tight))
        }
    };
    let mut out = Vec::new();
    for method in METHODS {
        let params: Vec<f64> = match method {
            "finite increments" => su.fi_steps.iter().map(|&n| su.t_end / n as f64).collect(),
            "RK4" => su.rk4_steps.iter().map(|&n| su.t_end / n as f64).collect(),
            _ => su.tolerances.clone(),
        };
        let mut points = Vec::with_capacity(params.len());
        for parameter in params {
            let r = run_method(sys, method, parameter, &su)?;
            let seconds = if timed {
                fastest(|| run_method(sys, method, parameter, &su))
            } else {
                0.0
            };
            points.push(Point {
                parameter,
                steps: r.steps,
                evaluations: r.evaluations,
                error: error(&r.last, &reference),
                seconds,
            });
        }
        out.push(Line {
            machine,
            method,
            points,
            reference_error,
        });
    }
    Ok(out)
}

/// The default five-bar with servos that never saturate (limit 10⁶ N·m): the same machine
/// with a smooth right-hand side, to show what the clamp of the default servos costs.
pub fn smooth_five_bar() -> FiveBar {
    let f = FiveBar::default();
    FiveBar {
        drive1: Servo {
            limit: 1e6,
            ..f.drive1
        },
        drive4: Servo {
            limit: 1e6,
            ..f.drive4
        },
        ..f
    }
}

/// Every stepper on every machine; timed when `timed`.
///
/// # Errors
/// A run's error (none is expected on these ranges).
pub fn work_precision(timed: bool) -> tmm::Result<Vec<Line>> {
    let coax = CoaxialPropellers::default();
    let su = setup(MACHINES[0]);
    let exact = coax.exact(&su.start, su.t_end)?;
    let mut lines = lines_for(&coax, MACHINES[0], Some(exact), timed)?;
    lines.extend(lines_for(&FiveBar::default(), MACHINES[1], None, timed)?);
    lines.extend(lines_for(&smooth_five_bar(), MACHINES[2], None, timed)?);
    lines.extend(lines_for(
        &LandingGear::default(),
        MACHINES[3],
        None,
        timed,
    )?);
    Ok(lines)
}

/// The points of a line far enough from both the pre-asymptotic range and the rounding (or
/// reference) floor to show the order: errors in [max(1e-12, 100 × reference error), 0.1].
pub fn asymptotic(line: &Line) -> Vec<Point> {
    let floor = 1e-12f64.max(100.0 * line.reference_error);
    line.points
        .iter()
        .copied()
        .filter(|p| p.error >= floor && p.error <= 0.1)
        .collect()
}

/// x″ + 2ζx′ + x = 0 (ω = 1, unit inertia) in both coordinates: spring as a potential,
/// damper as Rayleigh's function. With ζ = c/2 and no spring (`spring = false`) it is the
/// first-order decay x″ = −c·x′ that probes a method on the negative real axis.
pub struct Oscillator {
    /// The damping ratio ζ.
    pub zeta: f64,
    /// Whether the spring is there.
    pub spring: bool,
}

impl LagrangeSystem for Oscillator {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, _: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::zeros())
    }
    fn potential_gradient(&self, q: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(if self.spring { *q } else { Vector2::zeros() })
    }
    fn damping(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity() * 2.0 * self.zeta)
    }
}

/// The spectral radius of one finite-increment step on the oscillator with Ω = ωh = `big_omega`:
/// the amplification matrix is read off two steps of the crate's stepper from unit states.
///
/// # Errors
/// A step's error.
pub fn finite_increment_growth(zeta: f64, big_omega: f64) -> tmm::Result<f64> {
    let sys = Oscillator { zeta, spring: true };
    let h = big_omega;
    let mut m = Matrix2::zeros();
    // Columns act on (x, h·x′).
    for (col, (x, v)) in [(1.0, 0.0), (0.0, 1.0 / h)].into_iter().enumerate() {
        let s = FiniteIncrement.step(
            &sys,
            &State::new(0.0, Vector2::new(x, 0.0), Vector2::new(v, 0.0)),
            h,
        )?;
        m[(0, col)] = s.q[0];
        m[(1, col)] = s.qd[0] * h;
    }
    let (tr, det) = (m.trace(), m.determinant());
    let disc = tr * tr - 4.0 * det;
    Ok(if disc >= 0.0 {
        let r = disc.sqrt();
        ((tr + r) / 2.0).abs().max(((tr - r) / 2.0).abs())
    } else {
        det.abs().sqrt()
    })
}

/// |R(hλ)| of one RK4 step on x″ = λ·x′ (λ = `h_lambda` < 0 with h = 1): the factor by which
/// the crate's RK4 multiplies the speed.
///
/// # Errors
/// A step's error.
pub fn rk4_growth(h_lambda: f64) -> tmm::Result<f64> {
    let sys = Oscillator {
        zeta: -0.5 * h_lambda,
        spring: false,
    };
    let s = Rk4.step(
        &sys,
        &State::new(0.0, Vector2::zeros(), Vector2::new(1.0, 0.0)),
        1.0,
    )?;
    Ok(s.qd[0].abs())
}

/// Where `growth` crosses 1 between `lo` (below 1) and `hi` (above 1), by bisection.
///
/// # Errors
/// A step's error.
pub fn crossing(
    mut lo: f64,
    mut hi: f64,
    growth: impl Fn(f64) -> tmm::Result<f64>,
) -> tmm::Result<f64> {
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if growth(mid)? < 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The damping ratios of the finite-increment stability chart.
pub const ZETAS: [f64; 5] = [0.0, 0.1, 0.25, 0.5, 1.0];

/// The derived limit Ω < min(4ζ, 1/ζ) of finite increments (0 for ζ = 0: never stable).
pub fn finite_increment_limit(zeta: f64) -> f64 {
    if zeta == 0.0 {
        0.0
    } else {
        (4.0 * zeta).min(1.0 / zeta)
    }
}

/// The stability data: rows (ζ, Ω, spectral radius) of finite increments, rows (hλ, |R|) of
/// RK4, the observed crossing of each ζ > 0 and RK4's crossing on the negative real axis.
pub struct Stability {
    /// (ζ, Ω, ρ).
    pub finite_increments: Vec<(f64, f64, f64)>,
    /// (hλ, |R(hλ)|).
    pub rk4: Vec<(f64, f64)>,
    /// (ζ, the observed Ω where ρ crosses 1).
    pub fi_limits: Vec<(f64, f64)>,
    /// The observed hλ where |R| crosses 1.
    pub rk4_limit: f64,
}

/// The stability sweep.
///
/// # Errors
/// A step's error.
pub fn stability() -> tmm::Result<Stability> {
    let mut finite_increments = Vec::new();
    let mut fi_limits = Vec::new();
    for zeta in ZETAS {
        for i in 1..=200 {
            let o = 0.02 * f64::from(i);
            finite_increments.push((zeta, o, finite_increment_growth(zeta, o)?));
        }
        if zeta > 0.0 {
            let lim = finite_increment_limit(zeta);
            let c = crossing(0.5 * lim, 1.5 * lim, |o| finite_increment_growth(zeta, o))?;
            fi_limits.push((zeta, c));
        }
    }
    let mut rk4 = Vec::new();
    for i in 0..=175 {
        let x = -0.02 * f64::from(i);
        rk4.push((x, rk4_growth(x)?));
    }
    let rk4_limit = -crossing(2.0, 3.5, |x| rk4_growth(-x))?;
    Ok(Stability {
        finite_increments,
        rk4,
        fi_limits,
        rk4_limit,
    })
}

/// The work-precision lines as CSV.
pub fn to_csv(lines: &[Line]) -> String {
    let mut s =
        String::from("machine,method,parameter,steps,evaluations,error,seconds,reference_error\n");
    for l in lines {
        for p in &l.points {
            s += &format!(
                "{},{},{:e},{},{},{:e},{:e},{:e}\n",
                l.machine,
                l.method,
                p.parameter,
                p.steps,
                p.evaluations,
                p.error,
                p.seconds,
                l.reference_error
            );
        }
    }
    s
}

/// The stability data as two CSV texts (finite increments, RK4).
pub fn stability_csv(st: &Stability) -> (String, String) {
    let mut fi = String::from("zeta,omega_h,spectral_radius\n");
    for (z, o, r) in &st.finite_increments {
        fi += &format!("{z},{o:.2},{r:.12e}\n");
    }
    let mut rk = String::from("h_lambda,growth\n");
    for (x, g) in &st.rk4 {
        rk += &format!("{x:.2},{g:.12e}\n");
    }
    (fi, rk)
}
