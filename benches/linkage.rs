//! The linkage engine against the same job written by hand, side by side in one run: the
//! bundled four-bar (crank + RRR) and Watt six-bar (crank + RRR + RRR), each per position:
//! kinematics, inertia loads and weights, external loads, the reverse pass and the balancing
//! moment. Two yardsticks each: the job chained from the crate's own blocks, and the job as a
//! straight Cartesian closed form (issue 13's yardstick) that returns everything the engine
//! returns (every link's angle, ω and ε, every joint's reaction, M_b). Both are checked
//! against the engine before timing, and the bench prints the ratio engine/Cartesian
//! (`yardstick | …` lines), measured in alternating rounds.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{Point2, Vector2};
use std::hint::black_box;
use std::time::Duration;
use tmm::kinematics::{crank, rrr_dyad, Branch, LinkMotion, Motion, PointMotion};
use tmm::kinetostatics::{CouplingDrive, RrrDyad};
use tmm::linkage::{bundled, run_cycle, Analysis, Cells, Column, Plan, Table, Tabulate};
use tmm::Load;

#[path = "common/yardstick.rs"]
mod yardstick;

#[path = "common/cpu_ratio.rs"]
mod cpu_ratio;

fn inputs(n: usize) -> Vec<Motion> {
    (0..n)
        .map(|k| Motion::new(k as f64 * 0.7371, 10.0, 2.0))
        .collect()
}

fn own(link: &LinkMotion, along: f64, across: f64, m: f64, j: f64) -> Load {
    let s = link.point_at(along, across);
    let i = Load::inertia(s.p, m, s.a, j, link.epsilon).unwrap();
    Load::new(s.p, i.force + Vector2::new(0.0, -9.81 * m), i.moment)
}

/// The local coordinates (along, across) of `p` in a link frame at `o` with angle `a`.
fn local(o: Point2<f64>, a: Point2<f64>, p: Point2<f64>) -> (f64, f64) {
    let e = (a - o).normalize();
    let r = p - o;
    (r.dot(&e), e.x * r.y - e.y * r.x)
}

/// The bundled four-bar chained by hand: the same geometry, masses and loads.
struct HandFourBar {
    o1: Point2<f64>,
    o3: Point2<f64>,
    l: [f64; 3],
    e: (f64, f64),
    s2: (f64, f64),
    s3: (f64, f64),
}

impl HandFourBar {
    fn new() -> Self {
        let (o1, a, b, o3) = (
            Point2::new(0.0, 0.0),
            Point2::new(0.1, 0.0),
            Point2::new(0.25612516773077276, 0.3132489936153635),
            Point2::new(0.4, 0.05),
        );
        Self {
            o1,
            o3,
            l: [0.1, (b - a).norm(), (b - o3).norm()],
            e: local(a, b, Point2::new(0.25, 0.25)),
            s2: local(a, b, nalgebra::center(&a, &b)),
            s3: local(o3, b, nalgebra::center(&o3, &b)),
        }
    }

    fn balance(&self, i: Motion) -> f64 {
        let c = crank(self.o1, self.l[0], i).unwrap();
        let g = rrr_dyad(
            c.a,
            PointMotion::fixed(self.o3),
            self.l[1],
            self.l[2],
            Branch::Plus,
        )
        .unwrap();
        let j2 = 1.5 * self.l[1] * self.l[1] / 12.0;
        let j3 = 2.0 * self.l[2] * self.l[2] / 12.0;
        let l1 = own(&c.link, 0.0, 0.0, 1.0, 0.002);
        let mut l2 = own(&g.link2, self.s2.0, self.s2.1, 1.5, j2);
        let e = g.link2.point_at(self.e.0, self.e.1).p;
        l2 = Load::sum_about(&[l2, Load::force_at(e, Vector2::new(0.0, -50.0))], c.a.p);
        let mut l3 = own(&g.link3, self.s3.0, self.s3.1, 2.0, j3);
        l3.moment -= 40.0 * g.link3.omega.signum();
        let r = RrrDyad {
            a: c.a.p,
            b: g.b.p,
            c: self.o3,
            load2: l2,
            load3: l3,
        }
        .solve()
        .unwrap();
        let l1 = Load::sum_about(&[l1, Load::force_at(c.a.p, -r.r12)], self.o1);
        CouplingDrive { o1: self.o1 }
            .solve(&[l1])
            .unwrap()
            .balancing_moment
    }
}

/// The same four-bar as a straight Cartesian closed form: no validation, nothing rebuilt
/// from an angle, inlined — the speed of the job itself (issue 13's yardstick). It does the
/// engine's whole job per position, not only the balancing moment: every moving link's angle
/// (one `atan2` per dyad link, in [0, 2π) as the engine returns them; the crank's is the
/// input reduced to one turn), angular velocity and acceleration; the reaction in every joint
/// (O1, A, B, O3); and the balancing moment.
struct CartesianFourBar {
    a: f64,
    l2: f64,
    l3: f64,
    o3: Vector2<f64>,
    e: (f64, f64),
}

#[inline]
fn perp2(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

#[inline]
fn cross2(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// A direction angle in [0, 2π), as the engine returns link angles.
#[inline]
fn angle_of(v: Vector2<f64>) -> f64 {
    let a = v.y.atan2(v.x);
    if a < 0.0 {
        a + std::f64::consts::TAU
    } else {
        a
    }
}

/// Everything the engine gives per position of a linkage with `L` moving links and `J`
/// joints: each moving link's angle, ω and ε (links 1..), each joint's reaction as the force
/// of its lower-numbered link on the higher-numbered one, and the balancing moment.
#[derive(Debug, Clone, Copy)]
struct Whole<const L: usize, const J: usize> {
    angle: [f64; L],
    omega: [f64; L],
    epsilon: [f64; L],
    reaction: [Vector2<f64>; J],
    balance: f64,
}

impl<const L: usize, const J: usize> Whole<L, J> {
    /// The same quantities read from the engine after a solve.
    /// Read as a hot loop reads: the slices indexed by handle (links 1.., joints 0..), no
    /// `Result` per number.
    #[inline]
    fn of(a: &Analysis<'_>) -> Self {
        let (links, reactions) = (&a.link_motions()[1..=L], &a.reactions()[..J]);
        Self {
            angle: std::array::from_fn(|k| links[k].angle),
            omega: std::array::from_fn(|k| links[k].omega),
            epsilon: std::array::from_fn(|k| links[k].epsilon),
            // The force of the lower-numbered link on the higher-numbered one, whichever way
            // the engine records it.
            reaction: std::array::from_fn(|j| {
                let r = reactions[j];
                if r.by < r.on {
                    r.force
                } else {
                    -r.force
                }
            }),
            balance: a.balances()[0].value,
        }
    }

    /// Every quantity folded into one number, so that the timed loops consume all of them.
    #[inline]
    fn fold(&self) -> f64 {
        let r = self.reaction.iter().fold(Vector2::zeros(), |s, v| s + v);
        let mut s = self.balance + r.x + r.y;
        for k in 0..L {
            s += self.angle[k] + self.omega[k] + self.epsilon[k];
        }
        s
    }

    /// Whether `self` (a yardstick) agrees with `engine` to `tol`, relative to each kind of
    /// quantity's scale (angles to 2π).
    fn agrees(&self, engine: &Self, tol: f64) -> bool {
        let near = |x: f64, y: f64, scale: f64| (x - y).abs() <= tol * scale.max(1.0);
        let w = self.omega.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let e = self.epsilon.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let f = self.reaction.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        (0..L).all(|k| {
            // An angle near 0 may come out near 2π on the other side: compare on the circle.
            let d = (self.angle[k] - engine.angle[k]).abs();
            let d = d.min(std::f64::consts::TAU - d);
            d <= tol * std::f64::consts::TAU
                && near(self.omega[k], engine.omega[k], w)
                && near(self.epsilon[k], engine.epsilon[k], e)
        }) && (0..J).all(|j| (self.reaction[j] - engine.reaction[j]).norm() <= tol * f.max(1.0))
            && near(self.balance, engine.balance, self.balance.abs())
    }
}

impl CartesianFourBar {
    fn new() -> Self {
        let hand = HandFourBar::new();
        Self {
            a: hand.l[0],
            l2: hand.l[1],
            l3: hand.l[2],
            o3: hand.o3.coords,
            e: hand.e,
        }
    }

    /// The reactions are recorded as the engine records them: at O1 the frame's force on the
    /// crank, at A the crank's on the coupler, at B the coupler's on the rocker, at O3 the
    /// frame's on the rocker.
    #[inline]
    fn position(&self, i: Motion) -> Whole<3, 4> {
        let (w, eps) = (i.rate, i.accel);
        let (sn, cs) = i.value.sin_cos();
        let ra = Vector2::new(self.a * cs, self.a * sn);
        let (va, aa) = (w * perp2(ra), eps * perp2(ra) - w * w * ra);
        // B on the left of A→O3, at l2 from A and l3 from O3.
        let d = self.o3 - ra;
        let dd = d.norm_squared();
        let along = (self.l2 * self.l2 - self.l3 * self.l3 + dd) / (2.0 * dd);
        let across = (self.l2 * self.l2 / dd - along * along).sqrt();
        let b = ra + along * d + across * perp2(d);
        let (r2, r3) = (b - ra, b - self.o3);
        let x = cross2(r2, r3);
        let (w2, w3) = (-va.dot(&r3) / x, -va.dot(&r2) / x);
        let q = -aa + w2 * w2 * r2 - w3 * w3 * r3;
        let (e2, e3) = (q.dot(&r3) / x, q.dot(&r2) / x);
        // Loads: inertia and weight at the rods' middles, the force at E, the resisting moment.
        let g = Vector2::new(0.0, -9.81);
        let (m1, m2, m3) = (1.0, 1.5, 2.0);
        let (j2, j3) = (m2 * self.l2 * self.l2 / 12.0, m3 * self.l3 * self.l3 / 12.0);
        let a_s2 = aa + 0.5 * (e2 * perp2(r2) - w2 * w2 * r2);
        let a_s3 = 0.5 * (e3 * perp2(r3) - w3 * w3 * r3);
        let (f2, f3) = (m2 * (g - a_s2), m3 * (g - a_s3));
        let fe = Vector2::new(0.0, -50.0);
        let re = (self.e.0 * r2 + self.e.1 * perp2(r2)) / self.l2;
        // Moments about B of each link's loads (S2 − B = −r2/2, E − B = re − r2, S3 − B = −r3/2).
        let m2b = -j2 * e2 + cross2(-0.5 * r2, f2) + cross2(re - r2, fe);
        let m3b = -j3 * e3 - 40.0 * w3.signum() + cross2(-0.5 * r3, f3);
        let f = f2 + f3 + fe;
        // R12 (frame of link 2's moments about B) and R43 = −F − R12 (link 3's).
        let (p, qq) = (-r2, -r3);
        let det = cross2(p, qq);
        let (b1, b2) = (-m2b, m3b - cross2(qq, f));
        let r12 = Vector2::new((b1 * qq.x - p.x * b2) / det, (-p.y * b2 + qq.y * b1) / det);
        // Link 2's force balance gives R23 = R12 + F2 + F_E, link 3's R43 = −(R23 + F3); the
        // crank (its weight at O1, no inertia force) R01 = R12 − m1·g, and M_b balances R21 at
        // A and −J1·ε.
        let r23 = r12 + f2 + fe;
        let r43 = -(r23 + f3);
        let r01 = r12 - m1 * g;
        Whole {
            angle: [
                i.value.rem_euclid(std::f64::consts::TAU),
                angle_of(r2),
                angle_of(r3),
            ],
            omega: [w, w2, w3],
            epsilon: [eps, e2, e3],
            reaction: [r01, r12, r23, r43],
            balance: cross2(ra, r12) + 0.002 * eps,
        }
    }
}

/// One linkage's whole position (group `group`): its hand chain (the balancing moment) and its
/// Cartesian closed form (every quantity of [`Whole`]) are checked against the engine over
/// 512 positions (the closed form to `tol`), then timed beside it, side by side (the
/// `yardstick | {label} whole position` line) and by criterion, with the engine's kinematics
/// alone beside them.
fn whole_position<const L: usize, const J: usize>(
    c: &mut Criterion,
    group: &str,
    label: &str,
    plan: &Plan,
    hand_balance: impl Fn(Motion) -> f64,
    cartesian: impl Fn(Motion) -> Whole<L, J>,
    tol: f64,
) {
    let ins = inputs(512);
    // The yardsticks must do the same job: check them against the engine first.
    let mut solver = plan.solver();
    for &i in &ins {
        let a = solver.analyse(i).unwrap();
        let (x, y) = (a.balances()[0].value, hand_balance(i));
        assert!(
            (x - y).abs() <= 1e-9 * x.abs().max(1.0),
            "{label}: hand chain {y} vs engine {x}"
        );
        let (y, x) = (cartesian(i), Whole::<L, J>::of(a));
        assert!(
            y.agrees(&x, tol),
            "{label}: Cartesian closed form {y:?} vs engine {x:?}"
        );
    }
    let by_hand = || {
        ins.iter()
            .map(|&i| cartesian(black_box(i)).fold())
            .sum::<f64>()
    };
    let mut engine = plan.solver();
    let mut tmm = || {
        ins.iter()
            .map(|&i| Whole::<L, J>::of(engine.analyse(black_box(i)).unwrap()).fold())
            .sum::<f64>()
    };
    yardstick::print_ratio(
        &format!("{label} whole position"),
        ins.len() as u32,
        &mut tmm,
        by_hand,
    );
    let mut g = c.benchmark_group(group);
    g.measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(30);
    g.throughput(Throughput::Elements(ins.len() as u64));
    g.bench_function("cartesian_closed_form", |b| b.iter(by_hand));
    g.bench_function("hand_chain", |b| {
        b.iter(|| ins.iter().map(|&i| hand_balance(black_box(i))).sum::<f64>())
    });
    g.bench_function("engine", |b| b.iter(&mut tmm));
    g.bench_function("engine_kinematics_only", |b| {
        b.iter(|| {
            ins.iter()
                .map(|&i| solver.kinematics(black_box(i)).unwrap().link_motions()[L].omega)
                .sum::<f64>()
        })
    });
    g.finish();
}

fn four_bar(c: &mut Criterion) {
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    let (hand, cart) = (HandFourBar::new(), CartesianFourBar::new());
    whole_position(
        c,
        "four_bar_whole_position",
        "four-bar",
        &plan,
        |i| hand.balance(i),
        |i| cart.position(i),
        1e-9,
    );
}

/// The bundled Watt six-bar chained by hand: crank, RRR (coupler ABE, rocker O3BF), RRR
/// (link 4 EG, link 5 FG), the same masses and the resisting moment on link 5.
struct HandWatt {
    o1: Point2<f64>,
    o3: Point2<f64>,
    l: [f64; 5],
    e: (f64, f64),
    f: (f64, f64),
    s2: (f64, f64),
    s3: (f64, f64),
}

impl HandWatt {
    fn new() -> Self {
        let p = Point2::new;
        let (o1, a, b, o3) = (p(0.0, 0.0), p(0.08, 0.0), p(0.3, 0.3), p(0.38, 0.0));
        let (e, f, g) = (p(0.25, 0.45), p(0.52, 0.28), p(0.45, 0.6));
        Self {
            o1,
            o3,
            l: [
                0.08,
                (b - a).norm(),
                (b - o3).norm(),
                (g - e).norm(),
                (g - f).norm(),
            ],
            e: local(a, b, e),
            f: local(o3, b, f),
            s2: local(a, b, p(0.21, 0.25)),
            s3: local(o3, b, p(0.4, 0.19)),
        }
    }

    fn balance(&self, i: Motion) -> f64 {
        let c = crank(self.o1, self.l[0], i).unwrap();
        let fixed = PointMotion::fixed(self.o3);
        let g1 = rrr_dyad(c.a, fixed, self.l[1], self.l[2], Branch::Plus).unwrap();
        let e = g1.link2.point_at(self.e.0, self.e.1);
        let f = g1.link3.point_at(self.f.0, self.f.1);
        let g2 = rrr_dyad(e, f, self.l[3], self.l[4], Branch::Plus).unwrap();
        let (j4, j5) = (self.l[3].powi(2) / 12.0, self.l[4].powi(2) / 12.0);
        let l4 = own(&g2.link2, self.l[3] / 2.0, 0.0, 1.0, j4);
        let mut l5 = own(&g2.link3, self.l[4] / 2.0, 0.0, 1.0, j5);
        l5.moment -= 30.0 * g2.link3.omega.signum();
        let r2 = RrrDyad {
            a: e.p,
            b: g2.b.p,
            c: f.p,
            load2: l4,
            load3: l5,
        }
        .solve()
        .unwrap();
        let l2 = own(&g1.link2, self.s2.0, self.s2.1, 3.0, 0.02);
        let l2 = Load::sum_about(&[l2, Load::force_at(e.p, -r2.r12)], c.a.p);
        let l3 = own(&g1.link3, self.s3.0, self.s3.1, 2.5, 0.015);
        let l3 = Load::sum_about(&[l3, Load::force_at(f.p, -r2.r43)], self.o3);
        let r1 = RrrDyad {
            a: c.a.p,
            b: g1.b.p,
            c: self.o3,
            load2: l2,
            load3: l3,
        }
        .solve()
        .unwrap();
        let l1 = own(&c.link, 0.0, 0.0, 1.0, 0.002);
        let l1 = Load::sum_about(&[l1, Load::force_at(c.a.p, -r1.r12)], self.o1);
        CouplingDrive { o1: self.o1 }
            .solve(&[l1])
            .unwrap()
            .balancing_moment
    }
}

/// A point fixed in a link, in the frame of the link's side `r` (the vector between two of
/// its joints, as it moves): p − origin = α·r + β·r⊥, with α, β found once from the pose.
#[derive(Debug, Clone, Copy)]
struct Fixed(f64, f64);

impl Fixed {
    fn new(origin: Point2<f64>, toward: Point2<f64>, p: Point2<f64>) -> Self {
        let (r, d) = (toward - origin, p - origin);
        let q = r.norm_squared();
        Self(d.dot(&r) / q, cross2(r, d) / q)
    }

    /// The point's position relative to the origin, for the side `r`.
    #[inline]
    fn at(self, r: Vector2<f64>) -> Vector2<f64> {
        self.0 * r + self.1 * perp2(r)
    }
}

/// An RRR dyad's position, velocities and accelerations by hand: B on the left of A→C at
/// `l2` from A and `l3` from C; `(p, v, a)` of A and of C given. Returns B − A, B − C, ω2,
/// ω3, ε2, ε3.
#[inline]
#[allow(clippy::type_complexity)]
fn rrr_by_hand(
    a: (Vector2<f64>, Vector2<f64>, Vector2<f64>),
    c: (Vector2<f64>, Vector2<f64>, Vector2<f64>),
    l2: f64,
    l3: f64,
) -> (Vector2<f64>, Vector2<f64>, f64, f64, f64, f64) {
    let d = c.0 - a.0;
    let dd = d.norm_squared();
    let along = (l2 * l2 - l3 * l3 + dd) / (2.0 * dd);
    let across = (l2 * l2 / dd - along * along).sqrt();
    let r2 = along * d + across * perp2(d);
    let r3 = r2 - d;
    // ω2·r2⊥ − ω3·r3⊥ = v_C − v_A, and likewise for ε with the centripetal terms.
    let x = cross2(r2, r3);
    let dv = c.1 - a.1;
    let (w2, w3) = (dv.dot(&r3) / x, dv.dot(&r2) / x);
    let q = c.2 - a.2 + w2 * w2 * r2 - w3 * w3 * r3;
    (r2, r3, w2, w3, q.dot(&r3) / x, q.dot(&r2) / x)
}

/// An RRR dyad's reactions by hand from each link's resultant force and its moment about B:
/// R12 from both links' moments about B (R43 = −F − R12), then R23 = R12 + F2. `p` = A − B,
/// `q` = C − B. Returns R12, R23, R43.
#[inline]
fn rrr_reactions(
    p: Vector2<f64>,
    q: Vector2<f64>,
    (f2, m2b): (Vector2<f64>, f64),
    (f3, m3b): (Vector2<f64>, f64),
) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>) {
    let det = cross2(p, q);
    let (b1, b2) = (-m2b, m3b - cross2(q, f2 + f3));
    let r12 = Vector2::new((b1 * q.x - p.x * b2) / det, (-p.y * b2 + q.y * b1) / det);
    let r23 = r12 + f2;
    (r12, r23, -(r23 + f3))
}

/// The Watt six-bar as a straight Cartesian closed form doing the engine's whole job per
/// position, as [`CartesianFourBar`]: the crank; the RRR dyad coupler ABE + rocker O3BF; the
/// points E and F carried by them (fixed coordinates in their links' side vectors, so no
/// angle and no unit vector is needed); the RRR dyad EG + FG; inertia loads and weights;
/// the reactions of the last dyad, then of the first with the last's reactions reversed on
/// it, then the crank's; every angle by one `atan2`.
struct CartesianWatt {
    l: [f64; 5],
    o3: Vector2<f64>,
    /// E, S2 in the coupler (side A→B); F, S3 in the rocker (side O3→B).
    e: Fixed,
    s2: Fixed,
    f: Fixed,
    s3: Fixed,
}

impl CartesianWatt {
    fn new() -> Self {
        let p = Point2::new;
        let (a, b, o3) = (p(0.08, 0.0), p(0.3, 0.3), p(0.38, 0.0));
        let (e, f, g) = (p(0.25, 0.45), p(0.52, 0.28), p(0.45, 0.6));
        Self {
            l: [
                0.08,
                (b - a).norm(),
                (b - o3).norm(),
                (g - e).norm(),
                (g - f).norm(),
            ],
            o3: o3.coords,
            e: Fixed::new(a, b, e),
            s2: Fixed::new(a, b, p(0.21, 0.25)),
            f: Fixed::new(o3, b, f),
            s3: Fixed::new(o3, b, p(0.4, 0.19)),
        }
    }

    /// Joints in the engine's order: O1, A, B, O3, E, F, G.
    #[inline]
    fn position(&self, i: Motion) -> Whole<5, 7> {
        let l = &self.l;
        let g = Vector2::new(0.0, -9.81);
        let (w1, e1) = (i.rate, i.accel);
        let (sn, cs) = i.value.sin_cos();
        let ra = Vector2::new(l[0] * cs, l[0] * sn);
        let (va, aa) = (w1 * perp2(ra), e1 * perp2(ra) - w1 * w1 * ra);
        let zero = Vector2::zeros();
        let (r2, r3, w2, w3, e2, e3) = rrr_by_hand((ra, va, aa), (self.o3, zero, zero), l[1], l[2]);
        let b = ra + r2;
        // A point at `r` from a link's origin moving with (v, a) turning at (ω, ε).
        let carried = |r: Vector2<f64>, v: Vector2<f64>, a: Vector2<f64>, w: f64, e: f64| {
            (v + w * perp2(r), a + e * perp2(r) - w * w * r)
        };
        let (re, rf) = (self.e.at(r2), self.f.at(r3));
        let (ve, ae) = carried(re, va, aa, w2, e2);
        let (vf, af) = carried(rf, zero, zero, w3, e3);
        let (pe, pf) = (ra + re, self.o3 + rf);
        let (r4, r5, w4, w5, e4, e5) = rrr_by_hand((pe, ve, ae), (pf, vf, af), l[3], l[4]);

        // Inertia loads and weights: m·(g − a_S) at S and −J·ε. Links 4 and 5 are rods of
        // 1 kg (S at their middles, J = m·l²/12); a 30 N·m moment resists link 5's turning.
        let (rs2, rs3) = (self.s2.at(r2), self.s3.at(r3));
        let f2 = 3.0 * (g - carried(rs2, va, aa, w2, e2).1);
        let f3 = 2.5 * (g - carried(rs3, zero, zero, w3, e3).1);
        let f4 = g - carried(0.5 * r4, ve, ae, w4, e4).1;
        let f5 = g - carried(0.5 * r5, vf, af, w5, e5).1;
        let (j4, j5) = (l[3] * l[3] / 12.0, l[4] * l[4] / 12.0);
        let resist = if w5 > 0.0 {
            -30.0
        } else if w5 < 0.0 {
            30.0
        } else {
            0.0
        };
        // The last dyad (A = E, B = G, C = F): moments about G, S4 − G = −r4/2.
        let (r24, r45, r35) = rrr_reactions(
            -r4,
            -r5,
            (f4, -j4 * e4 + cross2(-0.5 * r4, f4)),
            (f5, -j5 * e5 + resist + cross2(-0.5 * r5, f5)),
        );
        // The first dyad carries R42 = −R24 at E and R53 = −R35 at F: moments about B.
        let (de, df) = (pe - b, pf - b);
        let f2e = f2 - r24;
        let f3f = f3 - r35;
        let m2b = -0.02 * e2 + cross2(rs2 - r2, f2) - cross2(de, r24);
        let m3b = -0.015 * e3 + cross2(rs3 - r3, f3) - cross2(df, r35);
        let (r12, r23, r43) = rrr_reactions(-r2, -r3, (f2e, m2b), (f3f, m3b));
        // The crank: its weight at O1, no inertia force; M_b balances R21 at A and −J1·ε.
        let r01 = r12 - 1.0 * g;
        Whole {
            angle: [
                i.value.rem_euclid(std::f64::consts::TAU),
                angle_of(r2),
                angle_of(r3),
                angle_of(r4),
                angle_of(r5),
            ],
            omega: [w1, w2, w3, w4, w5],
            epsilon: [e1, e2, e3, e4, e5],
            reaction: [r01, r12, r23, r43, r24, r35, r45],
            balance: cross2(ra, r12) + 0.002 * e1,
        }
    }
}

fn six_bar(c: &mut Criterion) {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let (hand, cart) = (HandWatt::new(), CartesianWatt::new());
    whole_position(
        c,
        "watt_six_bar_whole_position",
        "Watt six-bar",
        &plan,
        |i| hand.balance(i),
        |i| cart.position(i),
        1e-12,
    );
}

/// The cost per position of a streamed sweep (inputs generated on the fly, each position's
/// balancing moment folded into a peak): flat from 10³ to 10⁶ positions, since nothing is
/// stored or allocated per position.
fn streamed_sweep(c: &mut Criterion) {
    let plan = Plan::new(&bundled::watt_six_bar()).unwrap();
    let mut g = c.benchmark_group("watt_six_bar_streamed_sweep");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in [1_000u32, 10_000, 100_000, 1_000_000] {
        g.throughput(Throughput::Elements(u64::from(n)));
        g.bench_function(format!("positions_{n}"), |b| {
            b.iter(|| {
                let step = std::f64::consts::TAU / f64::from(n);
                let inputs = (0..n).map(|k| Motion::turning(f64::from(k) * step, 10.0));
                let mut peak = 0.0f64;
                let mut solver = plan.solver();
                for i in inputs {
                    if let Ok(a) = solver.analyse(i) {
                        peak = peak.max(a.balances()[0].value.abs());
                    }
                }
                black_box(peak)
            })
        });
    }
    g.finish();
}

/// A cycle of the four-bar (512 positions, every quantity of each folded into one number) by
/// the calls a reader would write: the README's `plan.cycle`, a solver loop by hand (the
/// fastest engine path), the one-shot `plan.analyse` per position through `run_cycle` (the
/// old README call, one allocation of buffers per position), beside the Cartesian closed
/// form. `plan.cycle` should stay within 1.2× of the solver loop.
fn four_bar_cycle(c: &mut Criterion) {
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    let ins = inputs(512);
    let cart = CartesianFourBar::new();
    let mut g = c.benchmark_group("four_bar_cycle");
    g.measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(30);
    g.throughput(Throughput::Elements(ins.len() as u64));
    g.bench_function("cartesian_closed_form", |b| {
        b.iter(|| {
            ins.iter()
                .map(|&i| cart.position(black_box(i)).fold())
                .sum::<f64>()
        })
    });
    g.bench_function("solver_loop", |b| {
        let mut solver = plan.solver();
        b.iter(|| {
            ins.iter()
                .map(|&i| Whole::<3, 4>::of(solver.analyse(black_box(i)).unwrap()).fold())
                .sum::<f64>()
        })
    });
    g.bench_function("plan_cycle", |b| {
        b.iter(|| {
            plan.cycle(black_box(&ins), |a| Ok(Whole::<3, 4>::of(a).fold()))
                .into_iter()
                .map(|r| r.unwrap())
                .sum::<f64>()
        })
    });
    g.bench_function("run_cycle_plan_analyse", |b| {
        b.iter(|| {
            run_cycle(black_box(&ins), |i| plan.analyse(i))
                .iter()
                .map(|r| Whole::<3, 4>::of(r.as_ref().unwrap()).fold())
                .sum::<f64>()
        })
    });
    g.finish();
}

/// A sink of a table's cells that keeps only their sum: the cost of computing a course
/// table's cells with nothing stored, the fastest a table can be made.
struct SumCells(f64);

impl Cells for SumCells {
    #[inline]
    fn cell(&mut self, _: impl FnOnce() -> String, value: f64) {
        self.0 += value;
    }
}

/// A sink that writes each cell straight into its column (the hand-written table below).
struct IntoColumns<'a> {
    columns: &'a mut [Vec<f64>],
    next: usize,
}

impl Cells for IntoColumns<'_> {
    #[inline]
    fn cell(&mut self, _: impl FnOnce() -> String, value: f64) {
        self.columns[self.next].push(value);
        self.next += 1;
    }
}

/// The fastest path to a course table written by hand: the column names known beforehand
/// (cloned into the table, as a caller writing them as literals would), every column
/// allocated once at its full length, and a solver loop pushing each position's cells
/// straight into their columns (no block, no names made, no check of the row's width):
/// the same `Table`, the same layout, freshly allocated per call, as `plan.table` makes.
fn table_by_hand(plan: &Plan, ins: &[Motion], names: &[String]) -> Table {
    let mut solver = plan.solver();
    let mut values: Vec<Vec<f64>> = names
        .iter()
        .map(|_| Vec::with_capacity(ins.len()))
        .collect();
    for &i in ins {
        if let Ok(a) = solver.analyse(i) {
            a.cells(&mut IntoColumns {
                columns: &mut values,
                next: 0,
            });
        }
    }
    Table {
        columns: names
            .iter()
            .zip(values)
            .map(|(name, values)| Column {
                name: name.clone(),
                values,
            })
            .collect(),
    }
}

/// Which of `four_bar_over_n`'s ratios to print (`TMM_OVER_N_JOBS`, all when unset).
struct Jobs(Option<String>);

impl Jobs {
    fn wants(&self, job: &str) -> bool {
        self.0
            .as_ref()
            .is_none_or(|v| v.split(',').any(|j| j.trim() == job))
    }
}

/// Prints the ratio `tmm / yardstick` side by side: in thread CPU time (`cpu | …`) and, if
/// `wall`, in wall time (`yardstick | …`).
fn both_ratios<A, B>(
    label: &str,
    n: usize,
    rounds: usize,
    wall: bool,
    mut tmm: impl FnMut() -> A,
    mut yardstick: impl FnMut() -> B,
) {
    if wall {
        yardstick::print_ratio(label, n as u32, &mut tmm, &mut yardstick);
    }
    cpu_ratio::print_cpu_ratio(label, n as u32, rounds, tmm, yardstick);
}

/// The obvious calls against the fastest path, per position, over N = 36 … 10⁶ positions of
/// the four-bar (group `four_bar_over_n`, throughput per position, so a flat rate is linear
/// cost): the README's `plan.cycle` against a solver loop by hand (the same job: every
/// quantity of each position folded into one number); the one-shot `plan.analyse` per
/// position (its buffers the plan's spares, nothing kept); the course table by
/// `plan.table` against the fastest path to the same table by hand ([`table_by_hand`]: a
/// solver loop writing the cells into new columns of the same layout), and against the same
/// cells summed by a solver loop with nothing stored (not a table: what the cells cost
/// without the memory a table fills); in criterion also the old way,
/// `Table::of(&run_cycle(&inputs, |i| plan.analyse(i)))`, which keeps an analysis per
/// position (up to 36 000 positions).
fn four_bar_over_n(c: &mut Criterion) {
    let plan = Plan::new(&bundled::four_bar()).unwrap();
    let mut g = c.benchmark_group("four_bar_over_n");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    // `TMM_OVER_N=36,360` runs only those N (all five by default).
    let only: Option<Vec<usize>> = std::env::var("TMM_OVER_N")
        .ok()
        .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect());
    // `TMM_ROUNDS=40`: more alternating rounds of CPU time per ratio (20 by default).
    let rounds = std::env::var("TMM_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20);
    // `TMM_OVER_N_JOBS=analyse,table`: only those ratios (of cycle, analyse, table, summed).
    let jobs = Jobs(std::env::var("TMM_OVER_N_JOBS").ok());
    // `TMM_WALL=0`: the CPU-time lines only (no wall-time `yardstick | …` lines).
    let wall = std::env::var("TMM_WALL").map_or(true, |v| v != "0");
    if let Ok(load) = std::fs::read_to_string("/proc/loadavg") {
        println!(
            "four_bar_over_n | load average (1, 5, 15 min): {}",
            load.trim()
        );
    }
    for n in [36usize, 360, 3_600, 36_000, 1_000_000] {
        if only.as_ref().is_some_and(|o| !o.contains(&n)) {
            continue;
        }
        let ins = inputs(n);
        // The table holds what the analyses give, and `Table::of` agrees with it.
        if n == 36 {
            let kept = run_cycle(&ins, |i| plan.analyse(i));
            assert_eq!(plan.table(&ins), Table::of(&kept));
        }
        {
            // The ratios, side by side in alternating rounds (criterion's means below drift with
            // the load of a shared machine; the fastest rounds do not).
            let mut solver = plan.solver();
            let mut loop_ = || {
                ins.iter()
                    .map(|&i| Whole::<3, 4>::of(solver.analyse(black_box(i)).unwrap()).fold())
                    .sum::<f64>()
            };
            let cycle = || {
                plan.cycle(black_box(&ins), |a| Ok(Whole::<3, 4>::of(a).fold()))
                    .into_iter()
                    .map(|r| r.unwrap())
                    .sum::<f64>()
            };
            let name = |what: &str| format!("four-bar N = {n}: {what}");
            if jobs.wants("cycle") {
                both_ratios(
                    &name("plan.cycle / solver loop"),
                    n,
                    rounds,
                    wall,
                    cycle,
                    &mut loop_,
                );
            }
            let one_shot = || {
                ins.iter()
                    .map(|&i| Whole::<3, 4>::of(&plan.analyse(black_box(i)).unwrap()).fold())
                    .sum::<f64>()
            };
            if jobs.wants("analyse") {
                both_ratios(
                    &name("plan.analyse per position / solver loop"),
                    n,
                    rounds,
                    wall,
                    one_shot,
                    &mut loop_,
                );
            }
            // The fastest path to the same table, by hand (checked equal first).
            let names: Vec<String> = plan
                .table(&ins[..1])
                .columns
                .into_iter()
                .map(|c| c.name)
                .collect();
            if n <= 3_600 {
                assert_eq!(table_by_hand(&plan, &ins, &names), plan.table(&ins));
            }
            let table = || plan.table(black_box(&ins)).len();
            if jobs.wants("table") {
                let by_hand = || table_by_hand(&plan, black_box(&ins), &names).len();
                both_ratios(
                    &name("plan.table / the same table by hand (solver loop into new columns)"),
                    n,
                    rounds,
                    wall,
                    table,
                    by_hand,
                );
            }
            if jobs.wants("summed") {
                // Not a table: the cells computed and summed, nothing stored (what a table
                // costs beyond the memory it fills).
                let mut cells_solver = plan.solver();
                let summed = || {
                    let mut sum = SumCells(0.0);
                    for &i in &ins {
                        cells_solver.analyse(black_box(i)).unwrap().cells(&mut sum);
                    }
                    sum.0
                };
                both_ratios(
                    &name("plan.table / its cells summed by a solver loop, nothing stored"),
                    n,
                    rounds,
                    wall,
                    table,
                    summed,
                );
            }
        }
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(BenchmarkId::new("solver_loop", n), |b| {
            let mut solver = plan.solver();
            b.iter(|| {
                ins.iter()
                    .map(|&i| Whole::<3, 4>::of(solver.analyse(black_box(i)).unwrap()).fold())
                    .sum::<f64>()
            })
        });
        g.bench_function(BenchmarkId::new("plan_cycle", n), |b| {
            b.iter(|| {
                plan.cycle(black_box(&ins), |a| Ok(Whole::<3, 4>::of(a).fold()))
                    .into_iter()
                    .map(|r| r.unwrap())
                    .sum::<f64>()
            })
        });
        g.bench_function(BenchmarkId::new("plan_analyse_per_position", n), |b| {
            b.iter(|| {
                ins.iter()
                    .map(|&i| Whole::<3, 4>::of(&plan.analyse(black_box(i)).unwrap()).fold())
                    .sum::<f64>()
            })
        });
        g.bench_function(BenchmarkId::new("table_cells_summed", n), |b| {
            let mut solver = plan.solver();
            b.iter(|| {
                let mut sum = SumCells(0.0);
                for &i in &ins {
                    solver.analyse(black_box(i)).unwrap().cells(&mut sum);
                }
                sum.0
            })
        });
        g.bench_function(BenchmarkId::new("plan_table", n), |b| {
            b.iter(|| plan.table(black_box(&ins)).len())
        });
        if n <= 36_000 {
            g.bench_function(BenchmarkId::new("table_of_run_cycle", n), |b| {
                b.iter(|| Table::of(&run_cycle(black_box(&ins), |i| plan.analyse(i))).len())
            });
        }
    }
    g.finish();
}

/// A whole four-bar position with friction in every hinge (f = 0.15 on pins of 10 mm,
/// `Plan::has_friction`: each group by its friction block, the crank by `CrankFriction`)
/// beside the same position frictionless, by the same reused solver: the goal is at most 6×.
/// Measured on a loaded 2-core machine (`uptime` load 5–7): 27.0 µs against 19.5 µs per 64
/// positions, 1.4–1.6×.
fn four_bar_friction(c: &mut Criterion) {
    let free = Plan::new(&bundled::four_bar()).unwrap();
    let mut l = bundled::four_bar();
    l.friction = Some(tmm::linkage::Friction::pin(0.15, 0.01));
    let with = Plan::new(&l).unwrap();
    let ins = inputs(64);
    let mut g = c.benchmark_group("four_bar_friction");
    g.measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500))
        .sample_size(30);
    g.throughput(Throughput::Elements(ins.len() as u64));
    for (name, plan) in [("frictionless", &free), ("friction", &with)] {
        g.bench_function(name, |b| {
            let mut solver = plan.solver();
            b.iter(|| {
                ins.iter()
                    .map(|&i| {
                        let a = solver.analyse(black_box(i)).unwrap();
                        a.balance(0).unwrap().value + a.reaction(2).unwrap().force.x
                    })
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    four_bar,
    six_bar,
    streamed_sweep,
    four_bar_cycle,
    four_bar_over_n,
    four_bar_friction
);
criterion_main!(benches);
