//! A whole rest reached mid-run under loads that change with time: a block on a ramp held by
//! Coulomb friction and pushed up the slope by a force growing with time, F = k·t. Every
//! phase has a closed form, so the stop, the breakaway and the motion after it are checked
//! exactly.
//!
//! With x up the slope, m·ẍ = k·t − m·g·sin α − μ·m·g·cos α·sgn(ẋ). Thrown up at v₀, the
//! block slides with m·v̇ = k·t − m·G, G = g·(sin α + μ·cos α), so
//! v(t) = v₀ + k·t²/(2m) − G·t and x(t) = v₀·t + k·t³/(6m) − G·t²/2: it stops at the smaller
//! root t₁ = (G − √(G² − 2·k·v₀/m))·m/k. There the drive along the slope is
//! k·t₁ − m·g·sin α and the friction holds it while −μ·m·g·cos α ≤ k·t − m·g·sin α ≤
//! μ·m·g·cos α: with tan α < μ the lower bound holds for every t ≥ 0, and the upper one
//! until t₂ = m·G/k (the vertex of the parabola v, so t₁ < t₂ whenever it stops). From t₂ on
//! m·v̇ = k·(t − t₂): v = k·(t − t₂)²/(2m), x = x₁ + k·(t − t₂)³/(6m).

use nalgebra::{Matrix2, Vector2};
use tmm::dynamics::{
    run, Dopri5, LagrangeSystem, Outcome, Rk4, RunOptions, RunResult, State, SwitchLoads,
};

const G_ACC: f64 = 9.81;

/// The block (mass `m`, ramp `alpha`, friction `mu`, push `k`·t); the second coordinate
/// is idle (a unit mass nothing drives).
struct Block {
    m: f64,
    alpha: f64,
    mu: f64,
    k: f64,
    /// Whether it says its forces change with time (they do when k ≠ 0).
    timed: bool,
}

impl Block {
    fn resistance(&self) -> f64 {
        self.mu * self.m * G_ACC * self.alpha.cos()
    }
    fn drive(&self, t: f64) -> f64 {
        self.k * t - self.m * G_ACC * self.alpha.sin()
    }
    fn big_g(&self) -> f64 {
        G_ACC * (self.alpha.sin() + self.mu * self.alpha.cos())
    }
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

impl LagrangeSystem for Block {
    fn inertia(&self, _: &Vector2<f64>) -> tmm::Result<Matrix2<f64>> {
        Ok(Matrix2::new(self.m, 0.0, 0.0, 1.0))
    }
    fn forces(&self, t: f64, _: &Vector2<f64>, qd: &Vector2<f64>) -> tmm::Result<Vector2<f64>> {
        Ok(Vector2::new(
            self.drive(t) - self.resistance() * sgn(qd[0]),
            0.0,
        ))
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
        Ok(Vector2::new(-self.resistance() * sgn(direction), 0.0))
    }
    fn switch_loads(
        &self,
        _: usize,
        t: f64,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
    ) -> tmm::Result<SwitchLoads> {
        Ok(SwitchLoads {
            what: "block",
            unit: "N",
            drive: self.drive(t),
            forward: self.resistance(),
            backward: self.resistance(),
        })
    }
    fn switch_holds(&self, i: usize) -> Option<usize> {
        (i == 0).then_some(0)
    }
    fn forces_depend_on_time(&self) -> bool {
        self.timed
    }
}

/// The first and last recorded times at which the block is held (its speed an exact zero).
fn rest(r: &RunResult) -> (f64, f64) {
    let (t, v) = (r.trajectory.t(), r.trajectory.qd()[0]);
    let held: Vec<f64> = (1..t.len())
        .filter(|&i| v[i] == 0.0)
        .map(|i| t[i])
        .collect();
    (held[0], *held.last().unwrap())
}

/// Thrown up the ramp, stopped by friction and gravity, held while the push grows, broken
/// away at t₂ = m·G/k: the stop, the breakaway and the final position and speed against the
/// closed forms, for RK4 at two steps and Dormand–Prince. (RK4 is exact for motions
/// polynomial in t of degree ≤ 4, so what is left is the location of the two events.)
#[test]
fn a_block_held_on_a_ramp_breaks_away_when_the_growing_push_reaches_its_friction() {
    let b = Block {
        m: 2.0,
        alpha: 20f64.to_radians(),
        mu: 0.5,
        k: 10.0,
        timed: true,
    };
    assert!(b.alpha.tan() < b.mu);
    let (m, k, g, v0) = (b.m, b.k, b.big_g(), 2.0);
    let t1 = (g - (g * g - 2.0 * k * v0 / m).sqrt()) * m / k;
    let x1 = v0 * t1 + k * t1.powi(3) / (6.0 * m) - g * t1 * t1 / 2.0;
    let t2 = m * g / k;
    let t_end = 3.0;
    let x_end = x1 + k * (t_end - t2).powi(3) / (6.0 * m);
    let v_end = k * (t_end - t2).powi(2) / (2.0 * m);
    let start = State::new(0.0, Vector2::zeros(), Vector2::new(v0, 0.0));
    let check = |name: &str, r: &RunResult| {
        assert!(
            matches!(r.outcome, Outcome::FinalTime),
            "{name}: {:?}",
            r.outcome
        );
        let (a, z) = rest(r);
        let e = [
            (a - t1).abs(),
            (z - t2).abs(),
            (r.last.q[0] - x_end).abs(),
            (r.last.qd[0] - v_end).abs() / v_end,
        ];
        println!(
            "{name}: stop {a:.12} s (exact {t1:.12}), breakaway {z:.12} s (exact {t2:.12}), \
             x {:.12} m (exact {x_end:.12}); errors {e:?}, {} steps",
            r.last.q[0], r.steps
        );
        for v in e {
            assert!(v <= 1e-9, "{name}: {e:?}");
        }
        // Held: the rows between the stop and the breakaway do not move at all.
        let (t, x) = (r.trajectory.t(), r.trajectory.q()[0]);
        let held: Vec<f64> = (0..t.len())
            .filter(|&i| t[i] >= a && t[i] <= z)
            .map(|i| x[i])
            .collect();
        assert!(
            held.len() >= 2 && held.iter().all(|&v| v == held[0]),
            "{name}"
        );
        assert!((held[0] - x1).abs() <= 1e-9, "{name}: {} vs {x1}", held[0]);
        (a, z)
    };
    let opts = |h: f64| RunOptions::until(t_end, h);
    let coarse = check("RK4 h = 0.01", &run(&b, &Rk4, start, &opts(0.01)).unwrap());
    let fine = check(
        "RK4 h = 0.0025",
        &run(&b, &Rk4, start, &opts(0.0025)).unwrap(),
    );
    let dp = run(&b, &Dopri5::new(1e-10).unwrap(), start, &opts(0.01)).unwrap();
    let dopri = check("Dopri5", &dp);
    for (x, y) in [(coarse, fine), (coarse, dopri)] {
        assert!((x.0 - y.0).abs() <= 1e-9 && (x.1 - y.1).abs() <= 1e-9);
    }
}

/// The same block at rest from the start, the push within its friction: it breaks away at
/// t₂ exactly, and without a push (loads constant in time) the run ends stuck at once; a
/// block that says its loads change but whose push stays within the friction (k < 0: the
/// drive falls towards the lower bound, which it does not reach before t_end) stays held to
/// the end in a bounded number of steps.
#[test]
fn a_block_at_rest_waits_for_its_breakaway_or_ends_stuck_when_nothing_changes() {
    let timed = Block {
        m: 2.0,
        alpha: 20f64.to_radians(),
        mu: 0.5,
        k: 10.0,
        timed: true,
    };
    let t2 = timed.m * timed.big_g() / timed.k;
    let start = State::at_rest(Vector2::zeros());
    let r = run(&timed, &Rk4, start, &RunOptions::until(2.0, 0.01)).unwrap();
    assert!(matches!(r.outcome, Outcome::FinalTime), "{:?}", r.outcome);
    let (a, z) = rest(&r);
    println!("at rest from t = 0: held until {z:.12} s (exact {t2:.12})");
    assert!(a <= 0.01 && (z - t2).abs() <= 1e-9, "{a} {z}");
    // Without a push and not timed: stuck at the start, no step taken.
    let still = Block {
        k: 0.0,
        timed: false,
        ..timed
    };
    let r = run(&still, &Rk4, start, &RunOptions::until(2.0, 0.01)).unwrap();
    let Outcome::Stuck { t, switch, loads } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert_eq!((t, switch, r.steps), (0.0, 0, 0));
    assert!(loads.holds());
    // Thrown up without a push: it stops at v₀/G and ends stuck there.
    let thrown = State::new(0.0, Vector2::zeros(), Vector2::new(2.0, 0.0));
    let r = run(&still, &Rk4, thrown, &RunOptions::until(2.0, 0.01)).unwrap();
    let Outcome::Stuck { t, .. } = r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert!((t - 2.0 / still.big_g()).abs() <= 1e-12, "{t}");
    // Timed, held for good: a bounded run, held to the end.
    let falling = Block { k: -0.1, ..timed };
    let dp = Dopri5::new(1e-10).unwrap();
    let r = run(&falling, &dp, start, &RunOptions::until(10.0, 0.01)).unwrap();
    assert!(matches!(r.outcome, Outcome::FinalTime), "{:?}", r.outcome);
    assert!(r.trajectory.q()[0].iter().all(|&x| x == 0.0));
    println!(
        "held to the end: {} steps, {} evaluations",
        r.steps, r.evaluations
    );
    assert!(r.steps <= 200, "{}", r.steps);
}
