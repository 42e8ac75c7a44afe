//! Stops of a machine with two inputs and joint friction (the bundled five-bar robot with
//! pins in every joint): where an input's rate reaches zero, the friction in its pivot holds
//! it (the run ends, stuck) or the drive breaks it away. Checked against the friction
//! kinetostatics solved independently: the balancing moments of the held motion and the
//! pivot's friction circle ρ·|R|.

use nalgebra::Vector2;
use tmm::dynamics::{run, Dopri5, LagrangeSystem, Outcome, Rk4, RunOptions, State};
use tmm::kinematics::Motion;
use tmm::linkage::dynamics::{LinkageSystem, Motor};
use tmm::linkage::{bundled, Friction, Inputs, Linkage, Plan};

const F: f64 = 0.15;

/// The five-bar robot (its couple of −0.3 N·m on coupler 3), with pins of radius 2 %
/// of its size and the coefficient `f` in every joint; and ρ = f·r.
fn five_bar(f: f64) -> (Linkage, f64) {
    let mut l = bundled::five_bar_robot();
    let r = 0.02 * Plan::new(&l).unwrap().size();
    if f > 0.0 {
        l.friction = Some(Friction::pin(f, r));
    }
    (l, f * r)
}

/// The joint between input `k`'s link and the frame.
fn pivot(plan: &Plan, k: usize) -> usize {
    let link = plan.input_links()[k].index();
    (0..plan.joint_names().len())
        .find(|&j| {
            let [a, b] = plan.joint_links(j).unwrap().map(|l| l.index());
            (a, b) == (0, link) || (a, b) == (link, 0)
        })
        .expect("the input's pivot")
}

fn inputs(q: &Vector2<f64>, qd: &Vector2<f64>, qdd: &Vector2<f64>) -> Inputs {
    let m = |i: usize| Motion::new(q[i], qd[i], qdd[i]);
    Inputs::two(m(0), m(1))
}

fn machine(l: &Linkage, tau: [f64; 2]) -> LinkageSystem {
    LinkageSystem::from_linkage(l)
        .unwrap()
        .with_motor(0, Motor::Constant(tau[0]))
        .unwrap()
        .with_motor(1, Motor::Constant(tau[1]))
        .unwrap()
}

/// At rest nothing slides, so the static balancing moments are the frictionless ones:
/// crank 2's motor balances its share (M_b2), crank 1's exceeds M_b1 by δ. Held, q̈ = 0
/// solves both equations (crank 2 balanced), so the couple that holds crank 1 is −δ. The
/// limit each way is the friction that sets in when crank 1 starts (crank 2 held): every
/// joint it moves (O1, A, B, C) slides, and the friction kinetostatics at q̇₁ = ±10⁻²⁰⁰,
/// q̈ = 0 needs the balancing moment M_b1± = M_b1 ± L±. For δ within [−L₋, L₊] the run ends
/// stuck at once, reporting δ and L±; beyond, crank 1 breaks away the way δ pushes. δ at
/// ±0.9, ±0.999, ±1.001 and ±1.1 of the limit that way, and 0. O1's friction circle alone,
/// ρ·|R_O1|, is a part of L.
#[test]
fn a_five_bar_at_rest_sticks_exactly_while_the_drive_is_within_the_pivots_friction_circle() {
    let (l, rho) = five_bar(F);
    let (bare, _) = five_bar(0.0);
    let plan = Plan::new(&bare).unwrap();
    let q = Vector2::from_vec(plan.reference_inputs());
    let z = Vector2::zeros();
    let a = plan.analyse(inputs(&q, &z, &z)).unwrap();
    let mb = [0, 1].map(|k| a.balance(k).unwrap().value);
    let r = a.reaction(pivot(&plan, 0)).unwrap().force.norm();
    let with = Plan::new(&l).unwrap();
    let starting = |s: f64| {
        let a = with
            .analyse(inputs(&q, &Vector2::new(s * 1e-200, 0.0), &z))
            .unwrap();
        s * (a.balance(0).unwrap().value - mb[0])
    };
    let (fwd, bwd) = (starting(1.0), starting(-1.0));
    assert!(
        fwd > rho * r && bwd > rho * r,
        "L± = {fwd}, {bwd}; ρ|R_O1| = {}",
        rho * r
    );
    let limit = fwd.max(bwd);
    let mut worst = 0.0f64;
    for x in [-1.1, -1.001, -0.999, -0.9, 0.0, 0.9, 0.999, 1.001, 1.1] {
        let delta = x * if x > 0.0 { fwd } else { bwd };
        let sys = machine(&l, [mb[0] + delta, mb[1]]);
        assert_eq!(sys.switches(), 2);
        let loads = sys.switch_loads(0, 0.0, &q, &z).unwrap();
        let scale = limit.max(mb[0].abs());
        worst = worst
            .max((loads.drive - delta).abs() / scale)
            .max((loads.forward - fwd).abs() / scale)
            .max((loads.backward - bwd).abs() / scale);
        // Two steps of RK4: enough to see the verdict and the way it breaks away.
        let r = run(
            &sys,
            &Rk4,
            State::at_rest(q),
            &RunOptions::until(2e-4, 1e-4),
        )
        .unwrap_or_else(|e| panic!("δ = {x} L: {e}"));
        if x.abs() < 1.0 {
            let Outcome::Stuck { t, switch, loads } = r.outcome else {
                panic!("δ = {x} L: {:?}", r.outcome)
            };
            assert_eq!((t, switch, loads.unit), (0.0, 0, "N·m"), "δ = {x} L");
            assert!(loads.holds());
        } else {
            assert!(
                matches!(r.outcome, Outcome::FinalTime),
                "δ = {x} L: {:?}",
                r.outcome
            );
            let w1 = r.last.qd[0];
            assert!(w1 * delta > 0.0, "δ = {x} L: q̇₁ = {w1}");
        }
    }
    println!(
        "five-bar at rest: L± = {fwd:.6e}, {bwd:.6e} N·m (ρ|R_O1| = {:.6e}), M_b = {mb:?}; \
         worst {worst:.1e}",
        rho * r
    );
    assert!(worst <= 1e-12, "{worst:e}");
}

/// At a whole rest both cranks' pivots are switches, and each is weighed with the other
/// crank free. Crank 1's motor balances it (its drive zero: it holds), crank 2's motor is
/// y times crank 2's own limit off its balance. Independently, from the kinetostatics at rest
/// (nothing slides, so the balances are the frictionless ones; each balance is affine in
/// the free crank's q̈, one secant step solves it): weighing crank k, the other crank's q̈
/// solves M_b,other(q̈) = τ_other with q̈ₖ = 0, the drive is τₖ − M_bk there, and the limits
/// L± are the friction that sets in when crank k starts (q̇ₖ = ±10⁻²⁰⁰) at that motion,
/// M_bk± − M_bk. Where crank 2's drive is within its limits too the machine stays at rest
/// (stuck at once, at switch 0); beyond them it runs with crank 2 moving the way its drive
/// pushes (it used to end stuck at switch 0, weighed alone).
#[test]
fn a_five_bar_at_rest_weighs_both_inputs_and_runs_when_one_breaks_away() {
    let (l, _) = five_bar(F);
    let plan = Plan::new(&l).unwrap();
    let q = Vector2::from_vec(plan.reference_inputs());
    let z = Vector2::zeros();
    let balance = |qd: &Vector2<f64>, qdd: &Vector2<f64>| {
        let a = plan.analyse(inputs(&q, qd, qdd)).unwrap();
        [a.balance(0).unwrap().value, a.balance(1).unwrap().value]
    };
    let e = |k: usize, x: f64| {
        let mut v = Vector2::zeros();
        v[k] = x;
        v
    };
    // Weighing crank k with the motors τ: (its drive, L+, L−).
    let weigh = |k: usize, tau: [f64; 2]| {
        let o = 1 - k;
        let m = |x: f64| balance(&z, &e(o, x))[o] - tau[o];
        let (g0, g1) = (m(0.0), m(1.0));
        let held = e(o, -g0 / (g1 - g0));
        let mb = balance(&z, &held)[k];
        let fwd = balance(&e(k, 1e-200), &held)[k] - mb;
        let bwd = mb - balance(&e(k, -1e-200), &held)[k];
        (tau[k] - mb, fwd, bwd)
    };
    let mb = balance(&z, &z);
    let limit2 = balance(&e(1, 1e-200), &z)[1] - mb[1];
    assert!(limit2 > 0.0);
    let (mut stuck, mut ran, mut worst) = (0, 0, 0.0f64);
    for y in [-3.0, -0.5, 0.0, 0.5, 3.0] {
        let tau2 = mb[1] + y * limit2;
        // Crank 1's motor: its balance with crank 2 free under τ₂ (drive zero).
        let tau1 = -weigh(0, [0.0, tau2]).0;
        let tau = [tau1, tau2];
        let sys = machine(&l, tau);
        let mut holds = [false; 2];
        for k in 0..2 {
            let (drive, fwd, bwd) = weigh(k, tau);
            let loads = sys.switch_loads(k, 0.0, &q, &z).unwrap();
            let scale = fwd.max(bwd).max(tau[k].abs());
            worst = worst
                .max((loads.drive - drive).abs() / scale)
                .max((loads.forward - fwd).abs() / scale)
                .max((loads.backward - bwd).abs() / scale);
            holds[k] = -bwd <= drive && drive <= fwd;
        }
        assert!(holds[0], "y = {y}");
        let r = run(
            &sys,
            &Rk4,
            State::at_rest(q),
            &RunOptions::until(2e-4, 1e-4),
        )
        .unwrap_or_else(|err| panic!("y = {y}: {err}"));
        if holds[1] {
            let Outcome::Stuck { t, switch, .. } = r.outcome else {
                panic!("y = {y}: {:?}", r.outcome)
            };
            assert_eq!((t, switch), (0.0, 0), "y = {y}");
            stuck += 1;
        } else {
            assert!(
                matches!(r.outcome, Outcome::FinalTime),
                "y = {y}: {:?}",
                r.outcome
            );
            let drive2 = weigh(1, tau).0;
            assert!(r.last.qd[1] * drive2 > 0.0, "y = {y}: {:?}", r.last.qd);
            ran += 1;
        }
    }
    println!(
        "five-bar at a whole rest, crank 1 balanced: {stuck} stuck, {ran} ran with crank 2 \
         broken away; worst {worst:.1e}"
    );
    assert!(stuck >= 1 && ran >= 2, "{stuck} stuck, {ran} ran");
    assert!(worst <= 1e-12, "{worst:e}");
}

/// Crank 1 held at the state `s` (q̇₁ = 0, q̈₁ = 0) while crank 2 moves under τ₂ in the
/// friction kinetostatics of `plan`: q̈₂ solves M_b2(q̈₂) = τ₂ (secant), and the couple that
/// holds crank 1 is M_b1 there; its pivot's friction circle ρ·|R_O1| is the limit.
fn held_at(plan: &Plan, o1: usize, rho: f64, s: &State, tau2: f64) -> (f64, f64) {
    let (couple, limit, _) = held_motion_at(plan, o1, rho, s, tau2);
    (couple, limit)
}

/// [`held_at`] with the held motion's q̈₂.
fn held_motion_at(plan: &Plan, o1: usize, rho: f64, s: &State, tau2: f64) -> (f64, f64, f64) {
    let mut qd = s.qd;
    qd[0] = 0.0;
    let mb = |x: f64| {
        let a = plan
            .analyse(inputs(&s.q, &qd, &Vector2::new(0.0, x)))
            .unwrap();
        (a.balance(0).unwrap().value, a.balance(1).unwrap().value)
    };
    let (mut x0, mut x1) = (0.0, 1.0);
    let (mut g0, mut g1) = (mb(x0).1 - tau2, mb(x1).1 - tau2);
    for _ in 0..50 {
        if g1 == g0 || g1.abs() <= 1e-15 {
            break;
        }
        let x2 = x1 - g1 * (x1 - x0) / (g1 - g0);
        (x0, g0) = (x1, g1);
        x1 = x2;
        g1 = mb(x1).1 - tau2;
    }
    let mut tiny = qd;
    tiny[0] = 1e-200;
    let a = plan
        .analyse(inputs(&s.q, &tiny, &Vector2::new(0.0, x1)))
        .unwrap();
    (mb(x1).0, rho * a.reaction(o1).unwrap().force.norm(), x1)
}

/// The five-bar robot with f = 0.3 on pins of 10 % of its size (a friction circle the
/// motors can fall in), its plan, its ρ, and crank 1's pivot.
fn large_pins() -> (Linkage, Plan, f64, usize) {
    let mut l = bundled::five_bar_robot();
    let size = Plan::new(&l).unwrap().size();
    l.friction = Some(Friction::pin(0.3, 0.1 * size));
    let plan = Plan::new(&l).unwrap();
    let o1 = pivot(&plan, 0);
    (l, plan, 0.3 * 0.1 * size, o1)
}

/// Crank 1 thrown at `w1` rad/s against (or with) its motor τ₁ (each of `taus`) while crank
/// 2 turns on under 0.05 N·m: where q̇₁ reaches zero the run weighs its pivot's friction
/// with crank 2 still moving, so every other joint's friction acts and depends on the held
/// motion's reactions. Independently: q̈₂ of the held motion (q̈₁ = 0) solves M_b2(q̈₂) = τ₂
/// in the friction kinetostatics (secant), the couple that holds crank 1 is M_b1 − τ₁ there,
/// and the limit is ρ·|R_O1| of that solve. The run must hold crank 1 at the stop (its rate
/// an exact zero from there on, crank 2 moving on) exactly when the drive τ₁ − M_b1 is
/// within ±L, and reverse crank 1 there otherwise; the loads it weighs must equal the
/// independent ones. While crank 1 is held, every recorded row's q̈₂ is the independent
/// held motion's, its q̈₁ an exact zero, and its drive within ±L (up to the release, located
/// where it reaches ±L). Returns the stops held, reversed, and the largest difference of the
/// loads relative to the larger of L and |τ₁| (and of q̈₂ relative to its size).
fn stops_while_the_other_moves(w1: f64, taus: &[f64]) -> (usize, usize, f64) {
    let (l, plan, rho, o1) = large_pins();
    let r0 = plan.reference_inputs();
    let start = State::new(0.0, Vector2::new(r0[0], r0[1]), Vector2::new(w1, 1.0));
    let tau2 = 0.05;
    let (mut stuck, mut reversed) = (0, 0);
    let mut worst = 0.0f64;
    for &tau1 in taus {
        let sys = machine(&l, [tau1, tau2]);
        let r = run(
            &sys,
            &Dopri5::new(1e-10).unwrap(),
            start,
            &RunOptions::until(0.5, 1e-3),
        )
        .unwrap_or_else(|e| panic!("τ₁ = {tau1}: {e}"));
        assert!(
            matches!(r.outcome, Outcome::FinalTime),
            "τ₁ = {tau1}: {:?}",
            r.outcome
        );
        let tr = &r.trajectory;
        let w = tr.qd()[0];
        // The stop: the first row where q̇₁ lands on zero.
        let Some(i) = (1..tr.len() - 1).find(|&i| w[i].abs() <= 1e-9 * 3.0) else {
            println!("w₁ = {w1}, τ₁ = {tau1}: no stop within the run");
            continue;
        };
        let row = |i: usize| {
            State::new(
                tr.t()[i],
                Vector2::new(tr.q()[0][i], tr.q()[1][i]),
                Vector2::new(w[i], tr.qd()[1][i]),
            )
        };
        // Held: from the stop (or a few rows after it: the pivot's own rate, a kink argument
        // too, can be landed on first, and crank 1 cross zero a few times by 10⁻⁷ rad/s
        // before the switch is) q̇₁ is an exact zero.
        let hold = (i..(i + 8).min(tr.len() - 1)).find(|&h| w[h] == 0.0 && w[h + 1] == 0.0);
        let held = hold.is_some();
        assert!(w[i - 1] * w1 > 0.0, "τ₁ = {tau1}");
        if !held {
            assert!(w[i + 1] * w1 < 0.0, "τ₁ = {tau1}");
        }
        let s = row(i);
        assert!(s.qd[0].abs() <= 1e-9 * 3.0 && s.qd[1] != 0.0, "{s:?}");
        let (held_couple, limit) = held_at(&plan, o1, rho, &s, tau2);
        let drive = tau1 - held_couple;
        let loads = sys.switch_loads(0, s.t, &s.q, &s.qd).unwrap();
        let scale = limit.max(tau1.abs());
        worst = worst
            .max((loads.drive - drive).abs() / scale)
            .max((loads.forward - limit).abs() / scale)
            .max((loads.backward - limit).abs() / scale);
        let mut release = None;
        if let Some(h) = hold {
            // Every row of the hold: q̈₁ = 0 exactly, q̈₂ and the drive the independent ones.
            let mut j = h;
            while j < tr.len() && w[j] == 0.0 {
                let sj = row(j);
                let (couple, lim, x) = held_motion_at(&plan, o1, rho, &sj, tau2);
                let (a1, a2) = (tr.qdd()[0][j], tr.qdd()[1][j]);
                let d = tau1 - couple;
                let l = sys.switch_loads(0, sj.t, &sj.q, &sj.qd).unwrap();
                let releases = j + 1 < tr.len() && w[j + 1] != 0.0;
                worst = worst.max((l.drive - d).abs() / lim.max(tau1.abs()));
                if !releases {
                    // (The release's row has the free motion's q̈, which starts there.)
                    worst = worst.max((a2 - x).abs() / x.abs().max(1.0));
                }
                assert!(a1 == 0.0 || releases, "τ₁ = {tau1}: q̈₁ = {a1} at {}", sj.t);
                if releases {
                    // The release: the drive reaches the breakaway load.
                    assert!(
                        (d.abs() - lim).abs() <= 1e-9 * lim.max(tau1.abs()),
                        "τ₁ = {tau1}: released at drive {d}, L {lim}"
                    );
                    release = Some(sj.t);
                } else {
                    assert!(d.abs() <= lim * (1.0 + 1e-9), "τ₁ = {tau1}: {d} vs {lim}");
                }
                j += 1;
            }
        }
        println!(
            "w₁ = {w1}, τ₁ = {tau1}: stop at t = {:.6} s, drive {drive:.6e}, L {limit:.6e}: {}{}",
            s.t,
            if held { "held" } else { "reversed" },
            release.map_or(String::new(), |t| format!(", released at {t:.9} s"))
        );
        assert_eq!(
            held,
            drive.abs() <= limit,
            "τ₁ = {tau1}: {drive} vs {limit}"
        );
        if held {
            stuck += 1;
        } else {
            reversed += 1;
        }
    }
    (stuck, reversed, worst)
}

/// Crank 1 thrown forward (3 rad/s) against its motor: every motor reverses it at its stop.
#[test]
fn a_five_bar_input_stopping_while_the_other_moves_sticks_or_reverses_by_its_friction() {
    let (stuck, reversed, worst) =
        stops_while_the_other_moves(3.0, &[-0.02, -0.05, -0.1, -0.2, -0.6]);
    println!("five-bar stops: {stuck} stuck, {reversed} reversed, worst {worst:.1e}");
    assert!(reversed >= 3, "{stuck} stuck, {reversed} reversed");
    assert!(worst <= 1e-9, "{worst:e}");
}

/// Crank 1 nudged (±0.02 rad/s) while crank 2 turns on, with its motor y times its pivot's
/// friction circle off the couple that holds it at the start (the independent solve of
/// [`held_at`]): friction stops it at once, and at the stop it sticks (|y| < 1) or is driven
/// back (y = ∓3 against the nudge), each way: both sides of the breakaway threshold, both
/// directions of the stop (the stops above all reverse crank 1 from forward).
#[test]
fn a_five_bar_input_nudged_either_way_sticks_or_goes_back_by_its_friction() {
    let (_, plan, rho, o1) = large_pins();
    let r0 = plan.reference_inputs();
    let at_rest = State::new(0.0, Vector2::new(r0[0], r0[1]), Vector2::new(0.0, 1.0));
    let (couple, limit) = held_at(&plan, o1, rho, &at_rest, 0.05);
    let mut all = (0, 0);
    for w1 in [0.02_f64, -0.02] {
        let taus: Vec<f64> = [-0.5, 0.0, 0.5, -3.0 * w1.signum()]
            .iter()
            .map(|y| couple + y * limit)
            .collect();
        let (stuck, reversed, worst) = stops_while_the_other_moves(w1, &taus);
        println!("five-bar, w₁ = {w1}: {stuck} stuck, {reversed} reversed, worst {worst:.1e}");
        assert!(
            stuck >= 2 && reversed >= 1,
            "{stuck} stuck, {reversed} reversed"
        );
        assert!(worst <= 1e-9, "{worst:e}");
        all = (all.0 + stuck, all.1 + reversed);
    }
    println!(
        "five-bar nudged stops: {} stuck, {} reversed (held couple {couple:.6e}, L {limit:.6e})",
        all.0, all.1
    );
}

/// The five-bar robot with f = 0.3 on pins of 5 cm in every joint (the CLI's
/// `--run 0.5 --motor 5,0 --motor2 0,0` on the bundled file with a `friction` object), 5 N·m
/// on crank 1. The plain fixed-point iteration for q̈ spent its 60 friction solves at
/// t ≈ 0.278 s (its factor ‖A⁻¹·∂Q_f/∂q̈‖ reached 0.64, and more further on); Newton's method
/// runs to 0.285 s. Energy, independently of the run's Q_f: the kinetic energy gained equals
/// the motor's work τ·q̇ and the couple's −0.3·ω₃ less the joints' lost power Σ P_lost of the
/// friction kinetostatics at the run's (q, q̇, q̈), integrated by trapezoids over the steps
/// (error O(h²)). The friction's work is a sizeable part of the balance, so that the check
/// could fail. Shortly after (t < 0.3 s) the couplers fold (the dyad's angle at B about 7°)
/// and the dyad self-locks under the friction: the run ends there, jammed
/// ([`Outcome::Jammed`]), with its rows, the time and the joint.
#[test]
fn a_five_bar_with_large_pins_runs_with_the_energy_balance_of_its_friction_and_then_jams() {
    let mut l = bundled::five_bar_robot();
    l.friction = Some(Friction::pin(0.3, 0.05));
    let tau = [5.0, 0.0];
    let sys = machine(&l, tau);
    let plan = sys.plan();
    let r0 = plan.reference_inputs();
    let q0 = Vector2::new(r0[0], r0[1]);
    let mut opts = RunOptions::until(0.285, 1e-4);
    opts.record_every = 1;
    let r = run(&sys, &Rk4, State::at_rest(q0), &opts).unwrap();
    assert!(matches!(r.outcome, Outcome::FinalTime), "{:?}", r.outcome);
    let tr = &r.trajectory;
    let (t, q, qd, kin) = (tr.t(), tr.q(), tr.qd(), tr.kinetic());
    let mut power = Vec::with_capacity(tr.len());
    let mut lost = 0.0;
    for i in 0..tr.len() {
        let (qi, qdi) = (
            Vector2::new(q[0][i], q[1][i]),
            Vector2::new(qd[0][i], qd[1][i]),
        );
        let qdd = tmm::dynamics::accelerations(&sys, t[i], &qi, &qdi).unwrap();
        let a = plan.analyse(inputs(&qi, &qdi, &qdd)).unwrap();
        let w3 = a.link("coupler 3").unwrap().rate;
        power.push((tau[0] * qdi[0] + tau[1] * qdi[1] - 0.3 * w3, a.lost_power()));
    }
    let mut work = 0.0;
    for i in 1..tr.len() {
        let h = t[i] - t[i - 1];
        work += 0.5 * h * (power[i - 1].0 + power[i].0 - power[i - 1].1 - power[i].1);
        lost += 0.5 * h * (power[i - 1].1 + power[i].1);
    }
    let gained = kin[tr.len() - 1] - kin[0];
    let err = (gained - work).abs() / (gained + lost);
    println!(
        "five-bar, 5 N·m, large pins: T gained {gained:.9} J, drive and load work less \
         friction {work:.9} J, friction work {lost:.6} J; relative error {err:.1e} over {} \
         steps",
        r.steps
    );
    assert!(lost > 0.05 * gained, "{lost} vs {gained}");
    assert!(err <= 1e-6, "{err:e}");
    // The jam is the run's stop: the rows up to it kept (the same steps as the run above),
    // the joint named, the friction's feedback det(I − J) at or below the threshold of
    // self-locking (1.5·10⁻⁸), the time inside the step after the last row.
    let h = 1e-4;
    let mut opts = RunOptions::until(0.3, h);
    opts.record_every = 1;
    let j = run(&sys, &Rk4, State::at_rest(q0), &opts).expect("a jam is a stop");
    let Outcome::Jammed {
        t: tj,
        joint,
        value,
    } = j.outcome
    else {
        panic!("the couplers jam before 0.3 s: {:?}", j.outcome)
    };
    let last = j.last.t;
    let name = &plan.joint_names()[joint];
    println!(
        "five-bar jams at t = {tj:.6} s (last row {last:.6} s, {} rows): joint {name}, \
         det(I - J) = {value:.3e}",
        j.trajectory.len()
    );
    // Located: the last state is the end of the longest step that carries, within the
    // run's time tolerance (10⁻¹² of 0.3 s) of the shortest that jams.
    assert!(tj > 0.285 && tj < 0.3 && tj > last, "{tj} vs {last}");
    assert!(tj - last <= 1e-12 * 0.3 + 1e-16, "{tj} vs {last}");
    assert!(value <= 1.5e-8, "{value:e}");
    assert_eq!(j.trajectory.t().last(), Some(&last));
    // Independently: plain RK4 steps of 10⁻⁶ s (no location) from the run's row 5 ms
    // before the jam, until a step (a stage or its end's q̈) fails: the jam lies inside
    // that step. The located time must fall into it (the two trajectories differ by
    // RK4's error at 10⁻⁴ s over 5 ms, far below 10⁻⁶ s in time).
    let rows = j.trajectory.len();
    let k = (0..rows)
        .rev()
        .find(|&i| j.trajectory.t()[i] <= tj - 5e-3)
        .unwrap();
    let (jq, jqd) = (j.trajectory.q(), j.trajectory.qd());
    let mut s = State::new(
        j.trajectory.t()[k],
        Vector2::new(jq[0][k], jq[1][k]),
        Vector2::new(jqd[0][k], jqd[1][k]),
    );
    let fine = 1e-6;
    let bracket = loop {
        use tmm::dynamics::Stepper;
        let carried = Rk4
            .step(&sys, &s, fine)
            .and_then(|s1| tmm::dynamics::accelerations(&sys, s1.t, &s1.q, &s1.qd).map(|_| s1));
        match carried {
            Ok(s1) => s = s1,
            Err(e) => {
                // The jam, or the q̈ iteration failing just before it where the friction's
                // feedback reaches the inertia: the run locates the first failure.
                assert!(e.to_string().contains("self-lock"), "{e}");
                break (s.t, s.t + fine);
            }
        }
        assert!(s.t < 0.3, "the fine steps do not jam");
    };
    println!(
        "located jam {tj:.9} s; fine RK4 steps jam inside [{:.9}, {:.9}] s",
        bracket.0, bracket.1
    );
    assert!(
        tj >= bracket.0 - 1e-9 && tj <= bracket.1 + 1e-9,
        "{tj} vs {bracket:?}"
    );
    // Dopri5 at 10⁻¹⁰ locates the same jam, on its own trajectory. Its location is the end of
    // one trial step from its last accepted state, a step as long as the error control let
    // the accepted ones be, whose own error is not controlled where the couplers fold fast:
    // 9·10⁻⁷ s past the fine steps' bracket when written (1.4·10⁻⁷ s before Dormand–Prince
    // capped an angle's relative tolerance at 2π), so it is held to 2·10⁻⁶ s of the bracket.
    let d = run(
        &sys,
        &Dopri5::new(1e-10).unwrap(),
        State::at_rest(q0),
        &opts,
    )
    .unwrap();
    let Outcome::Jammed {
        t: td, joint: jd, ..
    } = d.outcome
    else {
        panic!("Dopri5: {:?}", d.outcome)
    };
    println!("Dopri5 locates the jam at {td:.9} s (RK4 {tj:.9} s)");
    assert_eq!(jd, joint);
    assert!(
        td >= bracket.0 - 2e-6 && td <= bracket.1 + 2e-6,
        "{td} vs {bracket:?}"
    );
    // (The run above ends on 0.285 s exactly: its last step is cut to reach it.)
    let n = tr.len() - 1;
    let same = |a: &[f64], b: &[f64]| a[..n] == b[..n];
    assert!(same(j.trajectory.t(), tr.t()) && same(j.trajectory.kinetic(), tr.kinetic()));
    // The last row's motion is one the friction statics carries; the joint is a coupler's.
    let (ql, qdl) = (j.last.q, j.last.qd);
    let qdd = tmm::dynamics::accelerations(&sys, last, &ql, &qdl).unwrap();
    assert!(plan.analyse(inputs(&ql, &qdl, &qdd)).is_ok());
    let [a, b] = plan.joint_links(joint).unwrap().map(|l| l.index());
    assert!(a != 0 && b != 0, "joint {name} holds the frame");
}

/// The times crank 1 is held in a run (its rate an exact zero on two rows running): the
/// first such row and the last (the release, located), or `None` without a hold.
fn hold_times(r: &tmm::dynamics::RunResult) -> Option<(f64, f64)> {
    let (t, w) = (r.trajectory.t(), r.trajectory.qd()[0]);
    let first = (0..t.len() - 1).find(|&i| w[i] == 0.0 && w[i + 1] == 0.0)?;
    let last = (first..t.len()).take_while(|&i| w[i] == 0.0).last()?;
    Some((t[first], t[last]))
}

/// Crank 1 nudged at 0.02 rad/s with its motor half its pivot's friction circle below the
/// couple that holds it (the large pins), crank 2 turning on under 0.05 N·m: friction stops
/// crank 1, holds it while crank 2 speeds up, and releases it where the couple the held
/// motion needs reaches the breakaway load. The hold and the release are located events, so
/// RK4 at h and h/4 and Dormand–Prince at 10⁻¹⁰ find the same times (RK4's error of order
/// h⁴ in the state moves them by about as much): each within 10⁻⁶ s of Dormand–Prince, RK4
/// at h/4 closer than at h. Energy through the hold and the release, independently of the
/// run's generalized forces: the kinetic energy gained equals the motors' work τ·q̇ and the
/// couple's −0.3·ω₃ less the joints' lost power Σ P_lost of the friction kinetostatics at the
/// run's (q, q̇, q̈) (while held q̇₁ = q̈₁ = 0: the pivot's static friction does no work),
/// integrated by trapezoids over the rows of RK4 at h/4 (error O(h²): 1.2·10⁻⁶ of the
/// energies when written, held to 5·10⁻⁶).
#[test]
fn a_five_bar_input_held_by_its_friction_is_released_at_the_same_time_by_every_method() {
    let (l, plan, rho, o1) = large_pins();
    let r0 = plan.reference_inputs();
    let q0 = Vector2::new(r0[0], r0[1]);
    let start = State::new(0.0, q0, Vector2::new(0.02, 1.0));
    let tau2 = 0.05;
    let (couple, limit) = held_at(
        &plan,
        o1,
        rho,
        &State::new(0.0, q0, Vector2::new(0.0, 1.0)),
        tau2,
    );
    let tau = [couple - 0.5 * limit, tau2];
    let sys = machine(&l, tau);
    let t_end = 0.5;
    let h = 1e-3;
    let opts = |h: f64| RunOptions::until(t_end, h);
    let rk = run(&sys, &Rk4, start, &opts(h)).unwrap();
    let rk4 = run(&sys, &Rk4, start, &opts(h / 4.0)).unwrap();
    let dp = run(&sys, &Dopri5::new(1e-10).unwrap(), start, &opts(h)).unwrap();
    for r in [&rk, &rk4, &dp] {
        assert!(matches!(r.outcome, Outcome::FinalTime), "{:?}", r.outcome);
    }
    let (a, b, c) = (
        hold_times(&rk).expect("RK4 h: a hold"),
        hold_times(&rk4).expect("RK4 h/4: a hold"),
        hold_times(&dp).expect("Dopri5: a hold"),
    );
    println!(
        "crank 1 held from / released at: RK4 h {:.9} / {:.9} s, RK4 h/4 {:.9} / {:.9} s, \
         Dopri5 {:.9} / {:.9} s",
        a.0, a.1, b.0, b.1, c.0, c.1
    );
    assert!(c.1 > c.0 + 0.1 && c.1 < t_end - 0.01, "{c:?}");
    // The holds and the releases of all three. (The pivot's rate is both a kink argument and
    // the switch speed: a run that landed on the kink first, without weighing the switch,
    // held crank 1 0.9 ms late at h/4.)
    for (x, y) in [(a.0, c.0), (a.1, c.1), (b.0, c.0), (b.1, c.1)] {
        assert!((x - y).abs() <= 1e-6, "{x} vs {y}");
    }
    // Energy over RK4 at h/4.
    let tr = &rk4.trajectory;
    let (t, q, qd, qdd, kin) = (tr.t(), tr.q(), tr.qd(), tr.qdd(), tr.kinetic());
    let power: Vec<(f64, f64)> = (0..tr.len())
        .map(|i| {
            let qi = Vector2::new(q[0][i], q[1][i]);
            let qdi = Vector2::new(qd[0][i], qd[1][i]);
            let qddi = Vector2::new(qdd[0][i], qdd[1][i]);
            let an = plan.analyse(inputs(&qi, &qdi, &qddi)).unwrap();
            let w3 = an.link("coupler 3").unwrap().rate;
            (
                tau[0] * qdi[0] + tau[1] * qdi[1] - 0.3 * w3,
                an.lost_power(),
            )
        })
        .collect();
    let (mut work, mut lost) = (0.0, 0.0);
    for i in 1..tr.len() {
        let dt = t[i] - t[i - 1];
        work += 0.5 * dt * (power[i - 1].0 + power[i].0 - power[i - 1].1 - power[i].1);
        lost += 0.5 * dt * (power[i - 1].1 + power[i].1);
    }
    let gained = kin[tr.len() - 1] - kin[0];
    let err = (gained - work).abs() / (gained.abs() + lost);
    println!(
        "energy through the hold: T gained {gained:.9e} J, work less friction {work:.9e} J, \
         friction {lost:.6e} J; relative error {err:.1e} over {} rows",
        tr.len()
    );
    assert!(lost > 0.01 * gained.abs(), "friction {lost} vs {gained}");
    assert!(err <= 5e-6, "{err:e}");
}
