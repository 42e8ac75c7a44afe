//! The same linkage at any scale (issues 27 and 28): every bundled description file with every
//! length multiplied by s (and a rotated, translated copy) is the same mechanism. Its positions
//! are s times the unscaled ones, its angles the same, and it succeeds or fails at the same
//! inputs; a scale whose numbers themselves overflow or underflow is refused by an error that
//! names the overflow, never as a singular position, and never with a NaN or an infinity inside
//! an `Ok`.
//!
//! The supported range: every s with the linkage's size² and size⁻² finite normal numbers, so
//! 10⁻¹⁵⁰ … 10¹⁵⁰ for the bundled linkages (their sizes lie between 0.1 and 10 m). The solve's
//! thresholds are relative to the group's own lengths or the plan's size, so inside that range
//! the answers are the unscaled ones to rounding.
//!
//! A translation far from the origin loses digits honestly: a coordinate of magnitude |t| is
//! rounded to ε·|t|, so the positions of a copy moved by t agree with the unmoved ones to
//! `1e-12·size + TRANSLATION_ULPS·ε·|t|`.

use std::f64::consts::TAU;
use std::path::Path;
use tmm::kinematics::{Motion, PointMotion};
use tmm::linkage::DEAD_POINT_RELATIVE_ERROR;
use tmm::linkage::{Analysis, At, Drive, Inputs, JointKind, Kinematics, Linkage, LoadSpec, Plan};
use tmm::Error;

/// The scales every file is tried at.
const SCALES: [f64; 8] = [1e-150, 1e-100, 1e-30, 1e-6, 1e3, 1e30, 1e100, 1e150];

/// The positions tried along each input.
pub(super) const POSITIONS: usize = 36;

/// Positions agree with the scaled unscaled ones to this fraction of the size.
const POSITION_RELATIVE: f64 = 1e-12;

/// Angles agree to this, rad.
const ANGLE_TOLERANCE: f64 = 1e-12;

/// Velocities agree to this fraction of s times the largest joint speed (or the size per
/// second, if larger).
const VELOCITY_RELATIVE: f64 = 1e-12;

/// Forces agree to this fraction of s times the largest reaction (balancing moments of s²
/// times it and the size): the kinetostatics divides by the same conditioning at any scale.
const FORCE_RELATIVE: f64 = 1e-10;

/// Forces carry the kinetostatics' conditioning on top of the positions' roundings: their
/// allowance for a translation is this many times `TRANSLATION_ULPS`' (about 100 ε·|t| seen,
/// relative to the largest reaction).
const FORCE_TRANSLATION_FACTOR: f64 = 10.0;

/// How many roundings of a translated coordinate (ε·|t| each) a position, a velocity or a
/// force may carry (relative to the size, the speeds, the reactions): the closure of a group
/// mixes a few coordinates, each rounded once to ε·|t|, and its solve amplifies them by its
/// conditioning (the bundled linkages keep away from their dead centres at the positions
/// tried, so a small multiple; 1 to 3 seen).
const TRANSLATION_ULPS: f64 = 100.0;

/// One affine change of a description: every point p ↦ s·R(θ)·p + t, every direction and
/// force turned by θ, every length times s.
#[derive(Clone, Copy, Debug)]
pub(super) struct Change {
    s: f64,
    theta: f64,
    t: [f64; 2],
}

impl Change {
    pub(super) fn scale(s: f64) -> Self {
        Self {
            s,
            theta: 0.0,
            t: [0.0, 0.0],
        }
    }

    fn turn(&self, v: [f64; 2]) -> [f64; 2] {
        if self.theta == 0.0 {
            return v;
        }
        let (sn, cs) = self.theta.sin_cos();
        [cs * v[0] - sn * v[1], sn * v[0] + cs * v[1]]
    }

    fn point(&self, p: [f64; 2]) -> [f64; 2] {
        let r = self.turn(p);
        [self.s * r[0] + self.t[0], self.s * r[1] + self.t[1]]
    }

    fn at(&self, a: &mut At) {
        if let At::Coords(p) = a {
            *p = self.point(*p);
        }
    }

    fn length(&self, x: &mut Option<f64>) {
        if let Some(v) = x {
            *v *= self.s;
        }
    }

    fn friction(&self, f: &mut Option<tmm::linkage::Friction>) {
        if let Some(f) = f {
            self.length(&mut f.pin_radius);
            self.length(&mut f.rho);
            self.length(&mut f.length);
            self.length(&mut f.centre);
        }
    }

    /// The description in the new unit of length (mass and time kept): every quantity of
    /// dimension Lᵏ times sᵏ, so that the changed linkage is the same mechanism and every
    /// result follows by its dimension. Lengths (coordinates, pin radii, friction circles,
    /// slider lengths and centres, free lengths, pitch radii) ×s; moments of inertia ×s²;
    /// forces (loads, gravity's m·g through g, a spring's preload, a slide's resistance) ×s;
    /// moments (couples, a link's resistance, a torsion spring's stiffness and preload) ×s²;
    /// stiffness N/m and damping N·s/m unchanged; pressure ×1/s on an area ×s²; a slider's
    /// input speed ×s. Then every point turned by θ and moved by t, every direction, force
    /// and gravity turned.
    pub(super) fn apply(&self, l: &Linkage) -> Linkage {
        let s = self.s;
        let mut l = l.clone();
        let joint_names: Vec<String> = l.joints.iter().map(|j| j.name.clone()).collect();
        for j in &mut l.joints {
            j.at = self.point(j.at);
            if let JointKind::Prismatic { direction, .. } = &mut j.kind {
                *direction = self.turn(*direction);
            }
            self.friction(&mut j.friction);
        }
        self.friction(&mut l.friction);
        for link in &mut l.links {
            for p in &mut link.points {
                p.at = self.point(p.at);
            }
            if let Some(m) = &mut link.mass {
                m.j *= s * s;
                self.at(&mut m.centre);
            }
        }
        for input in std::iter::once(&mut l.input).chain(l.second_input.as_mut()) {
            if let Drive::Gear {
                pitch_radius,
                pitch_angle,
                ..
            } = &mut input.drive
            {
                *pitch_radius *= s;
                *pitch_angle += self.theta;
            }
        }
        let g = self.turn(l.gravity);
        l.gravity = [g[0] * s, g[1] * s];
        for load in &mut l.loads {
            match load {
                LoadSpec::Force { at, force, .. } => {
                    self.at(at);
                    let f = self.turn(*force);
                    *force = [f[0] * s, f[1] * s];
                }
                LoadSpec::Moment { moment, .. } => *moment *= s * s,
                LoadSpec::Resistance {
                    on,
                    forward,
                    backward,
                    at,
                } => {
                    // On a prismatic joint a force, on a link a couple.
                    let k = if joint_names.contains(on) { s } else { s * s };
                    *forward *= k;
                    *backward *= k;
                    if let Some(at) = at {
                        self.at(at);
                    }
                }
                LoadSpec::Indicator { diagram, .. } => {
                    diagram.area *= s * s;
                    for xp in diagram.outward.iter_mut().chain(diagram.inward.iter_mut()) {
                        xp[1] /= s;
                    }
                }
                LoadSpec::Spring {
                    ends,
                    free_length,
                    preload,
                    ..
                } => {
                    ends.iter_mut().for_each(|e| self.at(&mut e.at));
                    *free_length *= s;
                    *preload *= s;
                }
                LoadSpec::Damper { ends, .. } => {
                    ends.iter_mut().for_each(|e| self.at(&mut e.at));
                }
                LoadSpec::TorsionSpring {
                    stiffness, preload, ..
                } => {
                    *stiffness *= s * s;
                    *preload *= s * s;
                }
            }
        }
        l
    }
}

/// Every description file under `linkages/`, by name.
pub(super) fn files() -> Vec<(String, Linkage)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("linkages");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    names.sort();
    names
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            let l = Linkage::from_json(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, l)
        })
        .collect()
}

/// Whether input `k` of `plan` is a slider (a length) rather than a crank (an angle).
fn is_slider(plan: &Plan, k: usize) -> bool {
    if k == 0 {
        return !plan.input_is_crank();
    }
    let link = plan.input_links()[k];
    plan.joint_ids().any(|j| {
        plan.joint_links(j).is_ok_and(|ls| ls.contains(&link)) && plan.is_prismatic(j).unwrap()
    })
}

/// The inputs at position `i` of `POSITIONS` of the unscaled `plan`: each crank at its
/// reference angle plus i/36 of a turn (the second input of a two-input linkage a quarter turn
/// behind), each slider ±half the size about its reference, at unit speeds.
pub(super) fn unscaled_inputs(plan: &Plan, i: usize) -> Vec<Motion> {
    #[allow(clippy::cast_precision_loss)]
    let u = i as f64 / POSITIONS as f64;
    plan.reference_inputs()
        .iter()
        .enumerate()
        .map(|(k, &r)| {
            #[allow(clippy::cast_precision_loss)]
            let phase = TAU * u + k as f64 * 0.25 * TAU;
            if is_slider(plan, k) {
                Motion::new(r + 0.5 * plan.size() * phase.sin(), 1.0, 0.0)
            } else {
                Motion::new(r + TAU * u * if k == 0 { 1.0 } else { -1.0 }, 1.0, 0.0)
            }
        })
        .collect()
}

/// The same inputs on the changed copy: sliders' coordinates and speeds times s, cranks'
/// angles turned by θ.
pub(super) fn changed_inputs(plan: &Plan, c: Change, unscaled: &[Motion]) -> Inputs {
    let m: Vec<Motion> = unscaled
        .iter()
        .enumerate()
        .map(|(k, m)| {
            if is_slider(plan, k) {
                Motion::new(c.s * m.value, c.s * m.rate, c.s * m.accel)
            } else {
                Motion::new(m.value + c.theta, m.rate, m.accel)
            }
        })
        .collect();
    Inputs::from_slice(&m).unwrap()
}

/// The difference of two angles wrapped into (−π, π].
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    if d > std::f64::consts::PI {
        d - TAU
    } else {
        d
    }
}

/// `true` for the errors a genuine overflow or underflow of the numbers may give.
fn names_overflow(e: &Error) -> bool {
    match e {
        Error::Overflow { .. } => true,
        Error::In { source, .. } => names_overflow(source),
        _ => false,
    }
}

/// `true` if an error is (or wraps) a singular position.
fn is_singular(e: &Error) -> bool {
    match e {
        Error::Singular { .. } => true,
        Error::In { source, .. } => is_singular(source),
        _ => false,
    }
}

/// The largest gaps of a changed solve from the unscaled one, each over its allowance:
/// positions (every joint and point), link angles, velocities (relative to s times the
/// largest joint speed), forces (every reaction and balance, relative to s times the largest
/// reaction, the balances' moments to s² times it and the size).
#[derive(Default, Debug, Clone, Copy)]
struct Gaps {
    position: f64,
    angle: f64,
    velocity: f64,
    force: f64,
}

impl Gaps {
    fn max(&mut self, o: Gaps) {
        self.position = self.position.max(o.position);
        self.angle = self.angle.max(o.angle);
        self.velocity = self.velocity.max(o.velocity);
        self.force = self.force.max(o.force);
    }
}

/// The allowances of a change: positions to 1e-12 of the size, angles to 1e-12 rad, each
/// plus the translation's roundings (`TRANSLATION_ULPS`·ε·|t|, over the size for an angle);
/// and that last relative term alone, which velocities and forces add to theirs.
fn allowances(c: Change, size: f64) -> (f64, f64, f64) {
    let shift = TRANSLATION_ULPS * f64::EPSILON * c.t[0].hypot(c.t[1]);
    (
        POSITION_RELATIVE * size + shift,
        ANGLE_TOLERANCE + shift / size,
        shift / size,
    )
}

fn compare(
    plan: &Plan,
    frame_name: &str,
    c: Change,
    a: &Kinematics,
    b: &Kinematics,
    size: f64,
) -> Gaps {
    let (tol, angle_tol, relative) = allowances(c, size);
    let mut g = Gaps::default();
    let vmax = plan
        .joint_ids()
        .map(|j| a.joint(j).unwrap().v.norm())
        .fold(plan.size(), f64::max);
    let mut put = |pa: PointMotion, pb: PointMotion, velocity: bool| {
        let want = c.point([pa.p.x, pa.p.y]);
        g.position = g
            .position
            .max((pb.p.x - want[0]).hypot(pb.p.y - want[1]) / tol);
        if velocity {
            let wv = c.turn([pa.v.x, pa.v.y]);
            let vgap = (pb.v.x - c.s * wv[0]).hypot(pb.v.y - c.s * wv[1]);
            g.velocity = g
                .velocity
                .max(vgap / (c.s * vmax) / (VELOCITY_RELATIVE + relative));
        }
    };
    for j in plan.joint_ids() {
        put(a.joint(j).unwrap(), b.joint(j).unwrap(), true);
    }
    for p in plan.point_ids() {
        put(a.point(p).unwrap(), b.point(p).unwrap(), false);
    }
    let frame = plan.link_id(frame_name).unwrap();
    for l in plan.link_ids().filter(|&l| l != frame) {
        let (ma, mb) = (a.link_motion(l).unwrap(), b.link_motion(l).unwrap());
        g.angle = g
            .angle
            .max(angle_gap(mb.angle, ma.angle + c.theta).abs() / angle_tol);
    }
    g
}

/// Whether a prismatic joint's slide or a turning link's rate is within 10⁻⁹ of the fastest
/// (in its kind) of rest: a resistance there acts in rounding's direction.
fn near_rest(plan: &Plan, k: &Kinematics) -> bool {
    let omega: Vec<f64> = plan
        .link_ids()
        .map(|l| k.link_motion(l).unwrap().omega.abs())
        .filter(|&w| w != 0.0)
        .collect();
    let slides: Vec<f64> = plan
        .joint_ids()
        .filter(|&j| plan.is_prismatic(j).unwrap())
        .map(|j| k.slide(j).unwrap().rate.abs())
        .collect();
    [omega, slides].iter().any(|v| {
        let top = v.iter().copied().fold(0.0, f64::max);
        v.iter().any(|&x| x <= 1e-9 * top)
    })
}

/// The reactions and balances of the changed analysis against the unscaled one's: forces
/// ×s turned by θ, a crank's balancing moment ×s², a slider's balancing force ×s.
fn compare_forces(plan: &Plan, c: Change, a: &Analysis, b: &Analysis, relative: f64) -> f64 {
    let fmax = a
        .reactions()
        .iter()
        .map(|r| r.force.norm())
        .fold(0.0, f64::max);
    if fmax == 0.0 {
        return 0.0;
    }
    let mut worst: f64 = 0.0;
    for (ra, rb) in a.reactions().iter().zip(b.reactions()) {
        let want = c.turn([ra.force.x, ra.force.y]);
        let gap = (rb.force.x - c.s * want[0]).hypot(rb.force.y - c.s * want[1]);
        worst = worst.max(gap / (c.s * fmax));
    }
    for (k, (ba, bb)) in a.balances().iter().zip(b.balances()).enumerate() {
        let (want, scale) = if is_slider(plan, k) {
            (c.s * ba.value, c.s * fmax)
        } else {
            (c.s * c.s * ba.value, c.s * c.s * fmax * plan.size())
        };
        worst = worst.max((bb.value - want).abs() / scale);
    }
    worst / (FORCE_RELATIVE + FORCE_TRANSLATION_FACTOR * relative)
}

/// `Ok` where the unscaled solve is `Ok` and the changed one agrees with it, or both fail
/// the same way (a singular position refused at both, or any failure where the unscaled one
/// fails otherwise), or the changed one overflows: the mismatch otherwise.
fn same_outcome<A, B>(a: &tmm::Result<A>, b: &tmm::Result<B>) -> Result<(), String> {
    match (a, b) {
        (Ok(_), Ok(_)) => Ok(()),
        (Err(ea), Err(eb)) if !is_singular(eb) || is_singular(ea) => Ok(()),
        (Ok(_), Err(e)) if names_overflow(e) => Ok(()),
        (a, b) => Err(format!(
            "unscaled {:?}, changed {:?}",
            a.as_ref().err(),
            b.as_ref().err()
        )),
    }
}

/// One file at one change: the success or failure at each position against the unscaled
/// plan's, and the gaps where both succeed. Returns the worst gaps and the mismatches found.
fn check(name: &str, l: &Linkage, c: Change) -> (Gaps, Vec<String>) {
    let mut bad = Vec::new();
    let mut worst = Gaps::default();
    let plan = Plan::new(l).unwrap();
    let changed = c.apply(l);
    let scaled = match Plan::new(&changed) {
        Ok(p) => p,
        Err(e) => {
            if !names_overflow(&e) {
                bad.push(format!("{name} at {c:?}: not planned: {e}"));
            }
            return (worst, bad);
        }
    };
    for i in 0..POSITIONS {
        let unscaled = unscaled_inputs(&plan, i);
        let inputs = changed_inputs(&plan, c, &unscaled);
        let a = plan.kinematics(Inputs::from_slice(&unscaled).unwrap());
        let b = scaled.kinematics(inputs);
        // The dead-point rule refuses a dyad whose determinant the position's rounding leaves
        // without six digits; moved by t the rounding is ε·|t|, and the determinant's error
        // grows as its square root: refused (honestly) where |det| is below about
        // √(ε·|t|/size / 10⁻⁶) times the dyad's shape factor (√1000 admits every shape of the
        // bundled dyads; 0.14 of the 0.47 it gives at 10⁶ sizes is the largest seen).
        let near = allowances(c, scaled.size()).2 / TRANSLATION_ULPS;
        let dead_point_of_rounding = |e: &Error| {
            is_singular(e)
                && e.to_string().contains("within its position's rounding")
                && a.as_ref().is_ok_and(|a| {
                    a.group_determinants()
                        .iter()
                        .any(|d| d.abs() <= (1000.0 * near / DEAD_POINT_RELATIVE_ERROR).sqrt())
                })
        };
        let admitted = |b: &tmm::Result<_>| b.as_ref().is_err_and(dead_point_of_rounding);
        if let Err(m) = same_outcome(&a, &b)
            && !admitted(&b)
        {
            bad.push(format!("{name} at {c:?}, position {i}, kinematics: {m}"));
        }
        let mut g = match (&a, &b) {
            (Ok(a), Ok(b)) => compare(&plan, &l.frame, c, a, b, scaled.size()),
            _ => Gaps::default(),
        };
        let a = plan.analyse(Inputs::from_slice(&unscaled).unwrap());
        let b = scaled.analyse(inputs);
        if let Err(m) = same_outcome(&a, &b)
            && !b.as_ref().is_err_and(dead_point_of_rounding)
        {
            bad.push(format!("{name} at {c:?}, position {i}, analysis: {m}"));
        }
        // A resistance opposes the motion and is zero at rest: where a slide or a turning
        // link is within rounding of rest its direction is rounding's choice, at any scale
        // (the Scotch yoke's dead centres), so the forces are compared elsewhere only.
        if let (Ok(a), Ok(b)) = (&a, &b)
            && !near_rest(&plan, a.kinematics())
        {
            g.force = compare_forces(&plan, c, a, b, allowances(c, scaled.size()).2);
        }
        if g.position > 1.0 || g.angle > 1.0 || g.velocity > 1.0 || g.force > 1.0 {
            bad.push(format!("{name} at {c:?}, position {i}: {g:?}"));
        }
        worst.max(g);
    }
    (worst, bad)
}

/// Every file at every scale of [`SCALES`].
#[test]
fn every_file_at_every_scale_is_the_same_mechanism() {
    let mut bad = Vec::new();
    let mut worst = Gaps::default();
    for (name, l) in files() {
        for s in SCALES {
            let (g, b) = check(&name, &l, Change::scale(s));
            eprintln!("{name} s = {s:e}: {g:?}");
            worst.max(g);
            bad.extend(b);
        }
    }
    eprintln!("worst over every file and scale (1 = the allowance): {worst:?}");
    assert!(
        bad.is_empty(),
        "{} mismatches:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// Every file turned and moved (near, and a million sizes away), at three scales: the
/// positions to 1e-12 of the size plus the translation's roundings (module docs).
#[test]
fn every_file_turned_and_moved_far_away_is_the_same_mechanism() {
    let mut bad = Vec::new();
    let mut worst = Gaps::default();
    for (name, l) in files() {
        let size = Plan::new(&l).unwrap().size();
        for (s, theta, away) in [(1.0, 2.0, 10.0), (1e-100, 0.7, 1e6), (1e100, -1.0, 1e6)] {
            let d = away * s * size;
            let c = Change {
                s,
                theta,
                t: [0.6 * d, -0.8 * d],
            };
            let (g, b) = check(&name, &l, c);
            eprintln!("{name} {c:?}: {g:?}");
            worst.max(g);
            bad.extend(b);
        }
    }
    eprintln!("worst over every file and change (1 = the allowance): {worst:?}");
    assert!(
        bad.is_empty(),
        "{} mismatches:\n{}",
        bad.len(),
        bad.join("\n")
    );
}
