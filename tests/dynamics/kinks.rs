//! Kinks of several arguments (issue: two switches in one step): a system reports one
//! argument per switching load, each with its own nodes, and `run` steps onto the earliest
//! crossing in a step, then onto the next. The five-bar's two servos leave saturation 0.29 ms
//! apart, inside one step of every h ≥ 0.375 ms, where the product of their margins (the one
//! argument they had before) does not change sign; a described linkage with a servo beside a
//! tabulated motor has both kinds of switch located; hostile arguments are errors.

use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::machines::FiveBar;
use tmm::dynamics::{
    run, Beyond, Dopri5, FiniteIncrement, LagrangeSystem, Rk4, RunOptions, RunResult, State, Table,
};
use tmm::linkage::bundled;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::Error;

/// The robot's start of the five-bar servo tests: (120°, 60°) at rest, both servos
/// saturated (demands ∓7 N·m against their 5 N·m limits).
fn start() -> State {
    State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians()))
}

/// The kink arguments of `sys` at row `i` of a trajectory.
fn arguments<S: LagrangeSystem>(sys: &S, r: &RunResult, i: usize) -> Vec<f64> {
    let tr = &r.trajectory;
    let q = Vector2::new(tr.q()[0][i], tr.q()[1][i]);
    let qd = Vector2::new(tr.qd()[0][i], tr.qd()[1][i]);
    let mut out = vec![0.0; sys.kinks().len()];
    sys.kink_arguments(tr.t()[i], &q, &qd, &mut out).unwrap();
    out
}

/// The rows of a run that lie on a node (to 10⁻¹²) of some argument, as (time, argument,
/// node).
fn landings<S: LagrangeSystem>(sys: &S, r: &RunResult) -> Vec<(f64, usize, f64)> {
    let kinks = sys.kinks();
    let mut out = Vec::new();
    for i in 0..r.trajectory.len() {
        let args = arguments(sys, r, i);
        for (k, nodes) in kinks.iter().enumerate() {
            for &x in nodes {
                if (args[k] - x).abs() <= 1e-12 {
                    out.push((r.trajectory.t()[i], k, x));
                }
            }
        }
    }
    out
}

/// Dormand–Prince at tolerance 1e-10 from the five-bar's start to `t_end`, every step
/// recorded.
fn dopri_1e10<S: LagrangeSystem>(sys: &S, t_end: f64) -> RunResult {
    let dp = Dopri5::new(1e-10).unwrap();
    run(sys, &dp, start(), &RunOptions::until(t_end, 1e-3)).unwrap()
}

/// RK4 with `n` equal steps to `t_end`, recording only the end.
fn rk4<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, n: u32, locate: bool) -> RunResult {
    let mut opts = RunOptions::until(t_end, t_end / f64::from(n));
    opts.record_every = usize::MAX;
    opts.locate_kinks = locate;
    run(sys, &Rk4, s0, &opts).unwrap()
}

/// The difference of two states in q and q̇, the larger of the two.
fn diff(a: &State, b: &State) -> f64 {
    (a.q - b.q).amax().max((a.qd - b.qd).amax())
}

fn orders(e: &[f64]) -> Vec<f64> {
    e.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// The five-bar's two servo switches (crank 1's at 13.145 ms, crank 4's at 13.435 ms) fall
/// into one step of RK4 for every h ≥ 0.375 ms; there both margins change sign, so their
/// product, the one kink argument before, has the same sign at both ends of the step and the
/// switches were stepped across. With one argument per servo each is located, the earlier
/// first: the observed order over h = 3, 1.5, 0.75, 0.375 ms is the method's 4 (measured
/// 3.99, 3.98, 3.98), and the finest run is about 10⁴ times more accurate than the same run
/// stepping across them (measured 2.4·10⁻¹⁰ against 2.4·10⁻⁶ rad/s: 9.8·10³).
///
/// The reference is RK4 with the kinks located at h/64 of the finest run (its own error
/// about (1/64)⁴ of that run's), within 3·10⁻¹³ of Dormand–Prince at 10⁻¹³.
#[test]
fn two_servo_switches_in_one_step_are_located_one_after_the_other() {
    let sys = FiveBar::default();
    let t_end = 0.12;
    // The switches, from the steps of a run that lands on them: each servo once.
    let on = landings(&sys, &dopri_1e10(&sys, t_end));
    assert_eq!(
        on.iter().map(|&(_, k, x)| (k, x)).collect::<Vec<_>>(),
        [(0, -1.0), (1, 1.0)],
        "{on:?}"
    );
    let (t1, t4) = (on[0].0, on[1].0);
    eprintln!("switches at {t1:.9} s (crank 1) and {t4:.9} s (crank 4)");
    assert!(t4 - t1 > 1e-4 && t4 - t1 < 1e-3, "{t1} {t4}");

    let ns = [40u32, 80, 160, 320];
    for &n in &ns {
        // Both switches inside one grid step...
        let h = t_end / f64::from(n);
        let j = (t1 / h).floor();
        assert_eq!(j, (t4 / h).floor(), "n = {n}");
        // ...at whose ends the product of the margins has one sign: the old argument saw no
        // switch (the run stepping across them records every grid point).
        let mut opts = RunOptions::until(t_end, h);
        opts.locate_kinks = false;
        let across = run(&sys, &Rk4, start(), &opts).unwrap();
        let i = j as usize;
        assert!(across.trajectory.t()[i] < t1 && t4 < across.trajectory.t()[i + 1]);
        let (a, b) = (arguments(&sys, &across, i), arguments(&sys, &across, i + 1));
        // Both saturated at the start of the step (|demand| > limit), both following at its end.
        assert!(
            a[0].abs() > 1.0 && a[1].abs() > 1.0 && b[0].abs() < 1.0 && b[1].abs() < 1.0,
            "{a:?} {b:?}"
        );
        let product = |v: &[f64]| (1.0 - v[0].abs()) * (1.0 - v[1].abs());
        assert!(product(&a) > 0.0 && product(&b) > 0.0);
    }

    let reference = rk4(&sys, start(), t_end, 64 * ns[ns.len() - 1], true).last;
    let exact = run(
        &sys,
        &Dopri5::new(1e-13).unwrap(),
        start(),
        &RunOptions::until(t_end, 1e-4),
    )
    .unwrap()
    .last;
    assert!(
        diff(&exact, &reference) < 1e-12,
        "{}",
        diff(&exact, &reference)
    );
    let mut with = Vec::new();
    let mut without = Vec::new();
    for &n in &ns {
        let w = rk4(&sys, start(), t_end, n, true);
        let wo = rk4(&sys, start(), t_end, n, false);
        // Two extra steps: each switch cuts its grid step once.
        assert_eq!(w.steps, n as usize + 2, "n = {n}");
        with.push(diff(&w.last, &reference));
        without.push(diff(&wo.last, &reference));
    }
    let (pw, pn) = (orders(&with), orders(&without));
    let ratio = without[3] / with[3];
    eprintln!("located: errors {with:?}, orders {pw:.2?}");
    eprintln!("stepped across: errors {without:?}, orders {pn:.2?}; finest {ratio:.3e} times");
    for p in &pw {
        assert!((3.5..4.5).contains(p), "order {p}: {with:?}");
    }
    assert!(ratio >= 1e3, "{with:?} vs {without:?}");
}

/// max over `times` and over (q, q̇) of |y − y_ref| / (tol·(1 + |y_ref|)): the global error
/// in the controller's own weighting, 1 = the tolerance.
fn weighted_error(r: &RunResult, reference: &RunResult, tol: f64, times: &[f64]) -> f64 {
    let (a, b) = (&r.trajectory, &reference.trajectory);
    let row = |tr: &tmm::dynamics::Trajectory, t: f64| {
        tr.t()
            .iter()
            .position(|&x| x == t)
            .expect("requested time recorded")
    };
    let mut worst: f64 = 0.0;
    for &t in times {
        let (i, j) = (row(a, t), row(b, t));
        for c in 0..2 {
            for (got, want) in [(a.q()[c][i], b.q()[c][j]), (a.qd()[c][i], b.qd()[c][j])] {
                worst = worst.max((got - want).abs() / (tol * (1.0 + want.abs())));
            }
        }
    }
    worst
}

/// Dormand–Prince across the two servo switches 0.29 ms apart meets its tolerance: at every
/// step end the weighted global error (1 = the tolerance) against a reference at 10⁻¹⁴ is
/// measured 0.71, 0.77, 0.70 at 10⁻⁸, 10⁻¹⁰, 10⁻¹²; stepping across the switches it is 34,
/// 34, 9.6 (the error estimate of a smooth method does not see a kink inside its step). The
/// bound asserted is the tolerance itself; stepping across must miss it at least fivefold.
/// (How far it misses depends on where the steps happen to fall around the switches: a
/// step-size controller that differs in the last bits of its factors gave 34, 30, 15.)
///
/// At step ends, not at requested times: the continuous extension (order 4) errs by up to 6
/// tolerances inside the long steps before the switches, with the kinks located or not (the
/// steps there are the same), which is the interpolant's error, not the kinks'.
#[test]
fn dormand_prince_meets_its_tolerance_across_two_close_servo_switches() {
    let sys = FiveBar::default();
    let t_end = 0.12;
    for tol in [1e-8, 1e-10, 1e-12] {
        let mut errors = [0.0; 2];
        for (e, locate) in errors.iter_mut().zip([true, false]) {
            let mut opts = RunOptions::until(t_end, 1e-4);
            opts.locate_kinks = locate;
            let r = run(&sys, &Dopri5::new(tol).unwrap(), start(), &opts).unwrap();
            // The reference at this run's step ends, from its continuous extension.
            let times = r.trajectory.t()[1..].to_vec();
            let mut o = RunOptions::at_times(t_end, 1e-4, times.clone());
            o.record_every = usize::MAX;
            let reference = run(&sys, &Dopri5::new(1e-14).unwrap(), start(), &o).unwrap();
            *e = weighted_error(&r, &reference, tol, &times);
            eprintln!(
                "tol {tol:e}, kinks located {locate}: {e:.3} of the tolerance ({} steps, {} \
                 evaluations)",
                r.steps, r.evaluations
            );
        }
        assert!(errors[0] <= 1.0, "tol {tol:e}: {errors:?}");
        assert!(errors[1] >= 5.0, "tol {tol:e}: {errors:?}");
    }
}

/// The five-bar described as a linkage, crank 1 driven by its servo and crank 4 by a
/// tabulated characteristic M(ω₄) with kinks at its nodes.
fn servo_and_table() -> LinkageSystem {
    let fb = FiveBar::default();
    let table = Table::new(
        vec![-6.0, -3.0, -1.5, -0.5, 0.5, 1.5, 3.0, 6.0],
        vec![15.0, 9.0, 5.5, 4.2, 1.8, 0.5, -3.0, -9.0],
        Beyond::HoldEnds,
    )
    .unwrap();
    LinkageSystem::from_linkage(&bundled::five_bar_robot())
        .unwrap()
        .with_motor(0, Motor::Servo(fb.drive1))
        .unwrap()
        .with_motor(1, Motor::Tabulated(table))
        .unwrap()
}

/// A servo beside a tabulated motor: two arguments (the servo's demand over its limit,
/// nodes ±1; the rate ω₄, the table's nodes), and every switch of either is stepped onto: crank 4 passes ω₄ = 0.5
/// and 1.5 rad/s, crank 1's servo leaves saturation in between. RK4 keeps its order 4
/// (measured 3.99, 3.99, 4.00) and its finest run (h = 0.94 ms) is some 500 times more
/// accurate than stepping across (measured 490; 2200 at half that step).
#[test]
fn a_servo_beside_a_tabulated_motor_has_both_kinds_of_switch_located() {
    let sys = servo_and_table();
    assert_eq!(
        sys.kinks(),
        [
            vec![-1.0, 1.0],
            vec![-6.0, -3.0, -1.5, -0.5, 0.5, 1.5, 3.0, 6.0]
        ]
    );
    let t_end = 0.3;
    let on = landings(&sys, &dopri_1e10(&sys, t_end));
    eprintln!("landed on {on:?}");
    assert_eq!(
        on.iter().map(|&(_, k, x)| (k, x)).collect::<Vec<_>>(),
        [(1, 0.5), (0, -1.0), (1, 1.5)],
        "{on:?}"
    );
    // Every crossing of the fine run's arguments is one of these: none stepped across.
    let fine = run(&sys, &Rk4, start(), &RunOptions::until(t_end, 1e-5)).unwrap();
    let kinks = sys.kinks();
    let mut crossings = 0;
    let mut before = arguments(&sys, &fine, 0);
    for i in 1..fine.trajectory.len() {
        let now = arguments(&sys, &fine, i);
        for (k, nodes) in kinks.iter().enumerate() {
            crossings += nodes
                .iter()
                .filter(|&&x| (before[k] - x).signum() != (now[k] - x).signum())
                .count();
        }
        before = now;
    }
    // (A fixed-step run records its grid only, not the landings.)
    assert_eq!(crossings, on.len(), "{crossings} sign changes");

    let ns = [40u32, 80, 160, 320];
    let reference = rk4(&sys, start(), t_end, 64 * ns[ns.len() - 1], true).last;
    let with: Vec<f64> = ns
        .iter()
        .map(|&n| diff(&rk4(&sys, start(), t_end, n, true).last, &reference))
        .collect();
    let without: Vec<f64> = ns
        .iter()
        .map(|&n| diff(&rk4(&sys, start(), t_end, n, false).last, &reference))
        .collect();
    let pw = orders(&with);
    let ratio = without[3] / with[3];
    eprintln!("located: errors {with:?}, orders {pw:.2?}");
    eprintln!(
        "stepped across: errors {without:?}, orders {:.2?}; finest {ratio:.3e} times",
        orders(&without)
    );
    for p in &pw {
        assert!((3.5..4.5).contains(p), "order {p}: {with:?}");
    }
    assert!(ratio >= 100.0, "{with:?} vs {without:?}");
}

/// A unit mass from rest pushed by 1 N plus a ramp max(0, t − nₖ) from the first node nₖ
/// of each of its two kink arguments (a finite one): t, and `scale`·t (left unset when
/// `unset`). Each piece
/// of x is a polynomial of degree ≤ 3 in t, which RK4 integrates exactly: a step that
/// straddles a node misses by about 10⁻⁴.
struct TwoArguments {
    nodes: [Vec<f64>; 2],
    scale: f64,
    unset: bool,
}

impl TwoArguments {
    fn new(first: Vec<f64>, second: Vec<f64>) -> Self {
        Self {
            nodes: [first, second],
            scale: 1.0,
            unset: false,
        }
    }

    /// x(t) exactly.
    fn x(&self, t: f64) -> f64 {
        let ramps: f64 = self
            .nodes
            .iter()
            .filter_map(|n| n.first().filter(|x| x.is_finite()))
            .map(|&n| (t - n).max(0.0).powi(3) / 6.0)
            .sum();
        0.5 * t * t + ramps
    }
}

impl LagrangeSystem for TwoArguments {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        let ramps: f64 = self
            .nodes
            .iter()
            .filter_map(|n| n.first().filter(|x| x.is_finite()))
            .map(|&n| (t - n).max(0.0))
            .sum();
        Ok(Vector2::new(1.0 + ramps, 0.0))
    }
    fn kinks(&self) -> Vec<Vec<f64>> {
        self.nodes.to_vec()
    }
    fn kink_arguments(
        &self,
        t: f64,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        out: &mut [f64],
    ) -> tmm::Result<()> {
        out[0] = t;
        if !self.unset {
            out[1] = self.scale * t;
        }
        Ok(())
    }
}

/// The earliest crossing comes first whichever argument it belongs to, by every method;
/// arguments crossing their nodes at the same state are landed on once; arguments without
/// nodes cost nothing; a NaN or unset argument, or a NaN node of either argument, is an
/// error, not a panic.
#[test]
fn several_arguments_earliest_first_and_hostile_ones_refused() {
    let s0 = State::at_rest(Vector2::zeros());
    let opts = RunOptions::until(1.0, 1.0); // one step holds every crossing
    let dp = Dopri5::new(1e-8).unwrap();
    // Argument 1 (node 0.05) before argument 0 (node 0.3), both inside the one step: the
    // earlier is landed on first, whichever argument it belongs to, with the dense output's
    // bisection (Dormand–Prince) or by locating each (RK4); RK4 is then exact.
    let sys = TwoArguments::new(vec![0.3], vec![0.05]);
    let r = run(&sys, &dp, s0, &opts).unwrap();
    let on: Vec<(usize, f64)> = landings(&sys, &r).iter().map(|&(_, k, x)| (k, x)).collect();
    assert_eq!(on, [(1, 0.05), (0, 0.3)], "{:?}", r.trajectory.t());
    assert!((r.last.q[0] - sys.x(1.0)).abs() < 1e-12);
    let r = run(&sys, &Rk4, s0, &opts).unwrap();
    assert_eq!(r.steps, 3);
    assert!(
        (r.last.q[0] - sys.x(1.0)).abs() < 1e-15,
        "{}",
        r.last.q[0] - sys.x(1.0)
    );
    for h in [0.1, 0.07, 0.3] {
        let r = run(&sys, &Rk4, s0, &RunOptions::until(1.0, h)).unwrap();
        assert!((r.last.q[0] - sys.x(1.0)).abs() < 1e-14, "h = {h}");
        let across = RunOptions {
            locate_kinks: false,
            ..RunOptions::until(1.0, h)
        };
        let r = run(&sys, &Rk4, s0, &across).unwrap();
        assert!((r.last.q[0] - sys.x(1.0)).abs() > 1e-7, "h = {h}");
    }
    // The same node of two equal arguments: one landing serves both.
    let twin = TwoArguments::new(vec![0.3], vec![0.3]);
    let r = run(&twin, &Rk4, s0, &opts).unwrap();
    assert_eq!(r.steps, 2);
    assert!((r.last.q[0] - twin.x(1.0)).abs() < 1e-15);
    let r = run(&twin, &dp, s0, &opts).unwrap();
    let at: Vec<f64> = landings(&twin, &r).iter().map(|&(t, _, _)| t).collect();
    assert!(at.len() == 2 && at[0] == at[1], "{at:?}");
    // Arguments without nodes: the run of a system without kinks, to the bit.
    let none = TwoArguments::new(Vec::new(), Vec::new());
    for h in [0.1, 0.37] {
        let o = RunOptions::until(1.0, h);
        let off = RunOptions {
            locate_kinks: false,
            ..o.clone()
        };
        assert_eq!(
            run(&none, &dp, s0, &o).unwrap(),
            run(&none, &dp, s0, &off).unwrap()
        );
        assert_eq!(
            run(&none, &Rk4, s0, &o).unwrap(),
            run(&none, &Rk4, s0, &off).unwrap()
        );
    }
    // Hostile arguments and nodes.
    let nan_argument = TwoArguments {
        scale: f64::NAN,
        ..TwoArguments::new(vec![0.3], vec![0.05])
    };
    let unset = TwoArguments {
        unset: true,
        ..TwoArguments::new(vec![0.3], vec![0.05])
    };
    let nan_node = TwoArguments::new(vec![0.3], vec![0.05, f64::NAN]);
    let infinite_node = TwoArguments::new(vec![f64::NEG_INFINITY], vec![0.05]);
    for (sys, state) in [
        (&nan_argument, true),
        (&unset, true),
        (&nan_node, false),
        (&infinite_node, false),
    ] {
        for r in [
            run(sys, &Rk4, s0, &opts),
            run(sys, &dp, s0, &opts),
            run(sys, &FiniteIncrement, s0, &opts),
        ] {
            let ok = if state {
                matches!(r, Err(Error::NonFiniteState { time }) if time == 0.0)
            } else {
                matches!(r, Err(Error::NonFinite { .. }))
            };
            assert!(ok, "{r:?}");
        }
        // Not asked for when the kinks are not located.
        let off = RunOptions {
            locate_kinks: false,
            ..opts.clone()
        };
        assert!(run(sys, &Rk4, s0, &off).is_ok());
    }
    // The crate's systems refuse room for another number of arguments.
    let linkage = servo_and_table();
    let (q, qd) = (start().q, Vector2::new(0.1, 0.2));
    for n in [0, 1, 3] {
        let r = linkage.kink_arguments(0.0, &q, &qd, &mut vec![0.0; n]);
        assert!(matches!(r, Err(Error::OutOfRange { .. })), "{n}: {r:?}");
    }
    let mut two = [0.0; 2];
    linkage.kink_arguments(0.0, &q, &qd, &mut two).unwrap();
    assert_eq!(two[1], 0.2);
}

/// A unit mass under F = 1 + Σ max(0, t − n): x(t) = t²/2 + Σ max(0, t − n)³/6, a cubic on
/// each piece, which RK4 integrates exactly when every kink is a step end. The kink argument
/// is t itself, with the nodes listed per argument.
struct Ramps {
    real: Vec<f64>,
    nodes: Vec<Vec<f64>>,
    /// The kink argument is x instead of t (nodes then in metres).
    on_position: bool,
    /// Evaluations of the forces so far (one per evaluation of the accelerations).
    calls: std::cell::Cell<usize>,
}

impl Ramps {
    fn x(&self, t: f64) -> f64 {
        0.5 * t * t
            + self
                .real
                .iter()
                .map(|&n| (t - n).max(0.0).powi(3) / 6.0)
                .sum::<f64>()
    }
}

impl LagrangeSystem for Ramps {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::identity())
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        self.calls.set(self.calls.get() + 1);
        let f = 1.0 + self.real.iter().map(|&n| (t - n).max(0.0)).sum::<f64>();
        Ok(Vector2::new(f, 0.0))
    }
    fn kinks(&self) -> Vec<Vec<f64>> {
        self.nodes.clone()
    }
    fn kink_arguments(
        &self,
        t: f64,
        q: &Vector2<f64>,
        _: &Vector2<f64>,
        out: &mut [f64],
    ) -> tmm::Result<()> {
        out.fill(if self.on_position { q[0] } else { t });
        Ok(())
    }
}

/// A crossing located within rounding of a step's start (a second argument switching
/// 5e-13 s after the first, or a node 5e-13 s after the start) does not hide the kinks later
/// in the same step: RK4 in one step of the whole run lands on every one of them and is
/// exact to rounding (it was 2.5e-3 and 1.1e-2 off when such a crossing ended the search).
#[test]
fn a_crossing_at_the_start_of_a_step_does_not_hide_later_ones() {
    let s0 = State::at_rest(Vector2::zeros());
    let opts = RunOptions::until(1.0, 1.0);
    for (real, nodes, steps) in [
        (vec![0.3, 0.6], vec![vec![0.3], vec![0.6]], 3),
        (vec![0.3, 0.6], vec![vec![0.3], vec![0.3 + 5e-13, 0.6]], 3),
        (vec![0.6], vec![vec![5e-13, 0.6]], 2),
        (vec![0.3, 0.6], vec![vec![0.6], vec![0.3]], 3),
        (
            vec![0.2, 0.5, 0.7],
            vec![vec![0.7], vec![0.5], vec![0.2]],
            4,
        ),
    ] {
        let sys = Ramps {
            real,
            nodes: nodes.clone(),
            on_position: false,
            calls: Default::default(),
        };
        for method in ["RK4", "DP"] {
            let r = match method {
                "RK4" => run(&sys, &Rk4, s0, &opts).unwrap(),
                _ => run(&sys, &Dopri5::new(1e-10).unwrap(), s0, &opts).unwrap(),
            };
            let err = (r.last.q[0] - sys.x(1.0)).abs();
            assert!(err < 1e-13, "{method} {nodes:?}: error {err:e}");
            if method == "RK4" {
                assert_eq!(r.steps, steps, "{nodes:?}");
            }
        }
    }
}

/// The evaluation budget holds while kinks (and a watched value) are located inside a step:
/// for every budget from 1 to 300 evaluations (the run needs 236), a run either ends within it (past it by at
/// most the one RK4 step under way when it was checked) or stops with a budget error; none
/// overshoots it by the re-steps of a location (which used to go unchecked).
#[test]
fn locating_stays_within_the_evaluation_budget() {
    // The kinks located on x (a cubic in t: regula falsi needs several re-steps each), three
    // in the first step of RK4.
    let mut sys = Ramps {
        real: vec![0.2, 0.5, 0.7],
        nodes: Vec::new(),
        on_position: true,
        calls: Default::default(),
    };
    sys.nodes = sys.real.iter().rev().map(|&t| vec![sys.x(t)]).collect();
    let s0 = State::at_rest(Vector2::zeros());
    let (mut ok, mut refused) = (0, 0);
    for max in 1..=300 {
        for reach in [false, true] {
            let mut opts = RunOptions::until(1.0, 1.0);
            opts.max_evaluations = max;
            if reach {
                opts.reach = Some(tmm::dynamics::Reach {
                    watch: tmm::dynamics::Watch::Coordinate(0),
                    value: 0.3,
                    direction: tmm::dynamics::Direction::Rising,
                });
                opts.t_end = 2.0;
            }
            sys.calls.set(0);
            let result = run(&sys, &Rk4, s0, &opts);
            // What was spent, counted by the system itself (the recorded rows' two
            // evaluations aside).
            let spent = sys.calls.get().saturating_sub(2);
            assert!(spent < max + 4, "{max}: {spent} evaluations spent");
            match result {
                Ok(r) => {
                    assert!(
                        r.evaluations < max + 4,
                        "{max}: {} evaluations",
                        r.evaluations
                    );
                    ok += 1;
                }
                Err(Error::Budget { what, limit, .. }) => {
                    assert_eq!((what, limit), ("evaluation", max));
                    refused += 1;
                }
                Err(e) => panic!("{max}: {e}"),
            }
        }
    }
    assert!(ok > 50 && refused > 50, "{ok} ended, {refused} refused");
}
