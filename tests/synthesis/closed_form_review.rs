//! The hidden reviewer's checks of the closed-form syntheses, independent of the library's own
//! formulas: each answer's description is read back as joints (no `Report` number is trusted),
//! its requirement is measured twice — by a closed form written here (the crank-rocker's dead
//! centres by the cos law, the slider-crank's stroke from its two in-line positions, the
//! shaper's lever tangent to the crank circle, Freudenstein's equation evaluated directly) and
//! by the engine (`Plan::strokes`, `Plan::min_transmission_angle`, `Plan::output`) — over the
//! whole feasible range of each kind, edges included (K → 1⁺ and → its bound⁻, ψ → 0⁺ and π⁻,
//! offsets → 0, \[γ\] → the reachable maximum, scales 10⁻³ … 10³ m). Where no design exists
//! the answer must be an `Error` naming the parameter; hostile numbers are always an `Error`
//! (never a panic, never a non-finite number inside an `Ok`).
//!
//! Each sweep is a `pub fn` returning its failures, so that a scratch program can run it on
//! its own; the tests assert that the list is empty.

use std::f64::consts::{FRAC_PI_2, PI};
use std::panic::{catch_unwind, AssertUnwindSafe};
use tmm::kinematics::{grashof, Grashof, Motion, Rotation};
use tmm::linkage::{Linkage, Output, Plan};
use tmm::synthesis::{
    crank_rocker, crank_rocker_through, function_generator, shaper, slider_crank,
    CrankRockerRequirement, FrameChoice, FunctionRequirement, OffsetChoice, Options,
    ShaperRequirement, SliderCrankRequirement, Spacing, Synthesis,
};
use tmm::Error;

/// The relative allowance of every exact requirement.
const REL: f64 = 1e-10;
/// The allowance of the reported γ_min against the engine's, rad.
const GAMMA: f64 = 1e-9;

fn at(l: &Linkage, name: &str) -> [f64; 2] {
    l.joints
        .iter()
        .find(|j| j.name == name)
        .unwrap_or_else(|| panic!("no joint {name}"))
        .at
}

fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

fn rel(x: f64, want: f64) -> f64 {
    (x - want).abs() / want.abs().max(f64::MIN_POSITIVE)
}

/// The acos of a cosine that rounding may carry just past ±1.
fn acos(x: f64) -> f64 {
    x.clamp(-1.0, 1.0).acos()
}

/// Every number of an `Ok` answer is finite: joints, named points, report.
fn all_finite(s: &Synthesis) -> bool {
    let r = &s.report;
    s.linkage
        .joints
        .iter()
        .all(|j| j.at.iter().all(|x| x.is_finite()))
        && s.linkage
            .links
            .iter()
            .all(|l| l.points.iter().all(|p| p.at.iter().all(|x| x.is_finite())))
        && r.time_ratio.is_none_or(f64::is_finite)
        && r.stroke.is_none_or(f64::is_finite)
        && r.min_transmission_angle.is_finite()
        && r.min_transmission_at.is_finite()
        && r.dimensions.iter().all(|(_, v)| v.is_finite())
}

/// The engine's K, stroke and smallest transmission angle over every group, for a crank
/// turning counter-clockwise.
fn engine(s: &Synthesis, output: &Output) -> Result<(f64, f64, f64), String> {
    let plan = Plan::new(&s.linkage).map_err(|e| format!("plan: {e}"))?;
    let st = plan
        .strokes(output, Rotation::Ccw)
        .map_err(|e| format!("strokes: {e}"))?;
    let mut gamma = f64::INFINITY;
    for g in 0..plan.groups().len() {
        let (m, _) = plan
            .min_transmission_angle(g)
            .map_err(|e| format!("γ_min of group {g}: {e}"))?;
        gamma = gamma.min(m);
    }
    Ok((st.time_ratio, st.stroke, gamma))
}

/// K = (π + θ)/(π − θ).
fn k_of(theta: f64) -> f64 {
    (PI + theta) / (PI - theta)
}

/// The angle of a triangle with the sides `p`, `q` between them, opposite `o`, by Kahan's
/// formula for needle-like triangles ("Miscalculating area and angles of a needle-like
/// triangle", 2014): 2·atan√(((x − y) + o)·μ / ((x + (y + o))·((x − o) + y))), x ≥ y the two
/// sides, μ = o − (x − y) if y ≥ o, else y − (x − o). The cos law's acos loses half the digits
/// at an angle near 0 or π (a dead centre next to a change point); this keeps them all.
fn angle(p: f64, q: f64, o: f64) -> f64 {
    let (x, y) = (p.max(q), p.min(q));
    let mu = if y >= o { o - (x - y) } else { y - (x - o) };
    let num = ((x - y) + o) * mu;
    let den = (x + (y + o)) * ((x - o) + y);
    if num.is_nan() || num < 0.0 || den.is_nan() || den <= 0.0 {
        // Not a triangle (rounding at a flat one): the nearest flat angle.
        return if o >= x + y - o { PI } else { 0.0 };
    }
    2.0 * (num / den).sqrt().atan()
}

/// A crank-rocker (frame d, crank a, coupler b, rocker c) by the cos law at its two dead
/// centres, crank and coupler in line, |O1B| = r = b ± a: the triangle O1BO3 (sides r, d, c)
/// has the angle α(r) at O1 (opposite c) and β(r) at O3 (opposite r), in [`angle`]'s stable
/// form. Both dead centres lie on one side of the frame line (one assembly mode), so the crank
/// turns θ = |α(b + a) − α(b − a)| more than half a turn one way, and the rocker swings
/// |β(b + a) − β(b − a)|. Returns (K, ψ).
fn crank_rocker_by_cos_law(d: f64, a: f64, b: f64, c: f64) -> (f64, f64) {
    let alpha = |r: f64| angle(r, d, c);
    let beta = |r: f64| angle(c, d, r);
    let theta = (alpha(b + a) - alpha(b - a)).abs();
    (k_of(theta), (beta(b + a) - beta(b - a)).abs())
}

/// γ_min of a crank-rocker over a turn: the angle between coupler and rocker, cos μ = (b² +
/// c² − e²)/(2bc) with e = |AO3|, is monotonic in e, which runs between d − a and d + a, so
/// the acute angle is least at one of the two (its own derivation, not the library's).
fn crank_rocker_gamma(d: f64, a: f64, b: f64, c: f64) -> f64 {
    let mu = |e: f64| {
        let m = angle(b, c, e.abs());
        m.min(PI - m)
    };
    mu(d - a).min(mu(d + a))
}

/// How far K can move when each of the lengths is off by one rounding (ε of itself): the sum
/// of |∂K/∂l|·ε·l, the derivatives by central differences of [`crank_rocker_by_cos_law`].
/// Near K's bound the folded dead centre is a near change point and K is fixed by the lengths
/// only to this (no f64 description does better); elsewhere it is far below 10⁻¹⁰·K.
fn k_conditioning(l: [f64; 4]) -> f64 {
    let k = |l: [f64; 4]| crank_rocker_by_cos_law(l[0], l[1], l[2], l[3]).0;
    // Steps small against the folded dead centre's distance b − a from O1 for the crank and
    // the coupler: next to the bound K hangs on it, and a step of 10⁻⁷ of b spans it.
    let gap = l[2] - l[1];
    let steps = [1e-8 * l[0], 1e-8 * l[1].min(gap), 1e-8 * gap, 1e-8 * l[3]];
    (0..4)
        .map(|i| {
            let h = steps[i];
            let (mut up, mut down) = (l, l);
            up[i] += h;
            down[i] -= h;
            ((k(up) - k(down)) / (2.0 * h)).abs() * f64::EPSILON * l[i]
        })
        .sum()
}

/// Checks one crank-rocker answer against its requirement; pushes what fails.
fn review_crank_rocker(
    need: &CrankRockerRequirement,
    s: &Synthesis,
    fails: &mut Vec<String>,
    conditioned: &mut usize,
) {
    let tag = format!("{need:?}");
    if !all_finite(s) {
        fails.push(format!("{tag}: non-finite number in an Ok"));
        return;
    }
    let l = &s.linkage;
    let (d, a, b, c) = (
        dist(at(l, "O1"), at(l, "O3")),
        dist(at(l, "O1"), at(l, "A")),
        dist(at(l, "A"), at(l, "B")),
        dist(at(l, "O3"), at(l, "B")),
    );
    match grashof(d, a, b, c) {
        Ok(Grashof::CrankRocker) => {}
        other => fails.push(format!("{tag}: the description is {other:?}")),
    }
    if s.report.grashof != Some(Grashof::CrankRocker) {
        fails.push(format!("{tag}: reported class {:?}", s.report.grashof));
    }
    if rel(c, need.rocker) > 1e-12 {
        fails.push(format!("{tag}: rocker {c}"));
    }
    if let FrameChoice::Length(d0) = need.frame
        && rel(d, d0) > 1e-12
    {
        fails.push(format!("{tag}: frame {d}, asked {d0}"));
    }
    let (k, swing) = crank_rocker_by_cos_law(d, a, b, c);
    let allow_k = (REL * need.time_ratio).max(4.0 * k_conditioning([d, a, b, c]));
    if allow_k > REL * need.time_ratio {
        *conditioned += 1;
    }
    if (k - need.time_ratio).abs() > allow_k || rel(swing, need.swing) > REL {
        fails.push(format!(
            "{tag}: cos law K {k} ({:.2e} of the allowance), ψ {swing} (rel {:.2e})",
            (k - need.time_ratio).abs() / allow_k,
            rel(swing, need.swing)
        ));
    }
    let gamma = crank_rocker_gamma(d, a, b, c);
    if (gamma - s.report.min_transmission_angle).abs() > GAMMA {
        fails.push(format!(
            "{tag}: γ_min by hand {gamma}, reported {}",
            s.report.min_transmission_angle
        ));
    }
    match engine(s, &Output::Angle("rocker".into())) {
        Ok((mk, ms, mg)) => {
            if (mk - need.time_ratio).abs() > allow_k || rel(ms, need.swing) > REL {
                fails.push(format!(
                    "{tag}: engine K {mk} ({:.2e} of the allowance), ψ {ms} (rel {:.2e})",
                    (mk - need.time_ratio).abs() / allow_k,
                    rel(ms, need.swing)
                ));
            }
            if (mg - s.report.min_transmission_angle).abs() > GAMMA {
                fails.push(format!(
                    "{tag}: engine γ_min {mg}, reported {}",
                    s.report.min_transmission_angle
                ));
            }
        }
        Err(e) => fails.push(format!("{tag}: engine {e}")),
    }
    for (name, want) in [("time_ratio", need.time_ratio), ("swing", need.swing)] {
        let got = if name == "swing" {
            s.report.stroke
        } else {
            s.report.time_ratio
        };
        let allow = if name == "swing" { REL * want } else { allow_k };
        if got.is_none_or(|g| (g - want).abs() > allow) {
            fails.push(format!("{tag}: reported {name} {got:?}"));
        }
    }
}

/// An error that is allowed where no crank-rocker is designed: it names K, the swing, the
/// frame or the transmission angle.
fn names_a_parameter(e: &Error) -> bool {
    let text = e.to_string();
    !text.is_empty()
        && match e {
            Error::OutOfRange { name, .. } => !name.is_empty(),
            Error::NonFinite { .. } | Error::NonPositive { .. } => true,
            Error::Infeasible {
                parameter,
                required,
                reachable,
            } => !parameter.is_empty() && required.is_finite() && reachable.is_finite(),
            Error::NoMechanism { problem, .. } => !problem.is_empty(),
            _ => true,
        }
}

/// Crank-rockers by K and ψ over the whole feasible range (K from 1 + 10⁻⁹ to within 10⁻⁴ of
/// (K* − 1) of the bound K* = (3π + ψ)/(π − ψ), ψ from 10⁻⁴ to π − 10⁻⁴, rockers of 10⁻³ …
/// 10³ m, the frame chosen or given), each met; above the bound, `OutOfRange` at K* exactly.
pub fn crank_rocker_sweep(fast: bool) -> (Vec<String>, usize, usize) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut fails = Vec::new();
    let (mut done, mut conditioned) = (0, 0);
    let swings: &[f64] = if fast {
        &[1e-3, 0.3, 1.5, 3.0]
    } else {
        &[
            1e-4,
            1e-3,
            0.05,
            0.3,
            0.8,
            1.5,
            2.2,
            2.8,
            3.0,
            3.1,
            PI - 1e-3,
            PI - 1e-4,
        ]
    };
    let fractions: &[f64] = if fast {
        &[1e-6, 0.3, 0.99]
    } else {
        &[1e-9, 1e-6, 1e-3, 0.05, 0.3, 0.6, 0.9, 0.99, 0.999, 0.9999]
    };
    let scales: &[f64] = if fast { &[1.0] } else { &[1e-3, 1.0, 1e3] };
    for &psi in swings {
        let top = (3.0 * PI + psi) / (PI - psi);
        for &f in fractions {
            let k = 1.0 + f * (top - 1.0);
            for &c in scales {
                let need = CrankRockerRequirement {
                    rocker: c,
                    swing: psi,
                    time_ratio: k,
                    frame: FrameChoice::BestTransmission,
                };
                let r = catch_unwind(AssertUnwindSafe(|| crank_rocker(&need, &loose)));
                let Ok(r) = r else {
                    fails.push(format!("{need:?}: panic"));
                    continue;
                };
                let s = match r {
                    Ok(s) => s,
                    Err(e) => {
                        if !names_a_parameter(&e) {
                            fails.push(format!("{need:?}: unclear error {e}"));
                        }
                        continue;
                    }
                };
                review_crank_rocker(&need, &s, &mut fails, &mut conditioned);
                done += 1;
                let d = s.report.dimension("frame").unwrap_or(f64::NAN);
                let best = s.report.min_transmission_angle;
                // Given frames near the best: each met, none better than the best.
                for g in [0.7, 0.98, 1.02, 1.5] {
                    let given = CrankRockerRequirement {
                        frame: FrameChoice::Length(g * d),
                        ..need
                    };
                    match catch_unwind(AssertUnwindSafe(|| crank_rocker(&given, &loose))) {
                        Err(_) => fails.push(format!("{given:?}: panic")),
                        Ok(Ok(s2)) => {
                            review_crank_rocker(&given, &s2, &mut fails, &mut conditioned);
                            done += 1;
                            if s2.report.min_transmission_angle > best + 1e-9 {
                                fails.push(format!(
                                    "{given:?}: γ_min {} beats the 'best' {best}",
                                    s2.report.min_transmission_angle
                                ));
                            }
                        }
                        Ok(Err(Error::Infeasible {
                            required,
                            reachable,
                            ..
                        })) => {
                            if !(reachable.is_finite() && reachable > 0.0)
                                || (required - g * d).abs() > 1e-12 * g * d
                            {
                                fails.push(format!(
                                    "{given:?}: infeasible frame {required}, nearest {reachable}"
                                ));
                            }
                        }
                        Ok(Err(e)) => {
                            if !names_a_parameter(&e) {
                                fails.push(format!("{given:?}: unclear error {e}"));
                            }
                        }
                    }
                }
                // [γ] at the best reachable is met; just above it is refused by how much.
                if best > 1e-6 && best < FRAC_PI_2 {
                    let at_best = Options::default().with_min_transmission_angle(best);
                    if let Err(e) = crank_rocker(&need, &at_best) {
                        fails.push(format!("{need:?}: [γ] = its own γ_min {best}: {e}"));
                    }
                    let above = Options::default().with_min_transmission_angle(best + 1e-7);
                    match crank_rocker(&need, &above) {
                        Err(Error::Infeasible {
                            required,
                            reachable,
                            ..
                        }) if (reachable - best).abs() <= 1e-9 && required == best + 1e-7 => {}
                        other => fails.push(format!(
                            "{need:?}: [γ] 1e-7 above γ_min {best}: {:?}",
                            other.map(|s| s.report.min_transmission_angle)
                        )),
                    }
                }
            }
        }
        // Above the bound: out of range with the bound itself.
        for above in [top * (1.0 + 1e-9), top + 1.0, 1e6] {
            let need = CrankRockerRequirement {
                rocker: 0.3,
                swing: psi,
                time_ratio: above,
                frame: FrameChoice::BestTransmission,
            };
            match crank_rocker(&need, &loose) {
                Err(Error::OutOfRange { name: "K", max, .. }) if rel(max, top) < 1e-12 => {}
                other => fails.push(format!(
                    "ψ {psi}: K {above} above the bound {top}: {:?}",
                    other.map(|s| s.report)
                )),
            }
        }
    }
    (fails, done, conditioned)
}

/// The slider-crank read from its description: crank a = |O1A|, rod b = |AB|, the guide's
/// offset e (B's height above O1: the guide runs along +x through B), its in-line positions
/// (crank and rod stretched, B at b + a from O1, and folded, b − a) at x = √(r² − e²): the
/// stroke is their difference, and the crank turns the angle between them, θ = atan2(e,
/// x_folded) − atan2(e, x_stretched), more than half a turn one way. γ_min: the rod leans
/// most from the guide when A is farthest from it on the other side, sin = (a + |e|)/b.
fn slider_crank_by_hand(l: &Linkage) -> (f64, f64, f64, f64) {
    let (o1, a_pt, b_pt) = (at(l, "O1"), at(l, "A"), at(l, "B"));
    let a = dist(o1, a_pt);
    let b = dist(a_pt, b_pt);
    let e = b_pt[1] - o1[1];
    // Factored: (b − a)² − e² cancels where the folded position nears the crank's pivot.
    let x_far = ((a + b - e.abs()) * (a + b + e.abs())).sqrt();
    let x_near = ((b - a - e.abs()) * (b - a + e.abs())).sqrt();
    let theta = (e.atan2(x_near) - e.atan2(x_far)).abs();
    (k_of(theta), x_far - x_near, acos((a + e.abs()) / b), e)
}

fn review_slider_crank(need: &SliderCrankRequirement, s: &Synthesis, fails: &mut Vec<String>) {
    let tag = format!("{need:?}");
    if !all_finite(s) {
        fails.push(format!("{tag}: non-finite number in an Ok"));
        return;
    }
    let (k, h, gamma, e) = slider_crank_by_hand(&s.linkage);
    if rel(k, need.time_ratio) > REL || rel(h, need.stroke) > REL {
        fails.push(format!(
            "{tag}: in-line positions give K {k} (rel {:.2e}), H {h} (rel {:.2e})",
            rel(k, need.time_ratio),
            rel(h, need.stroke)
        ));
    }
    if let OffsetChoice::Given(e0) = need.offset
        && rel(e, e0) > 1e-12
    {
        fails.push(format!("{tag}: offset {e}"));
    }
    if (gamma - s.report.min_transmission_angle).abs() > GAMMA {
        fails.push(format!(
            "{tag}: γ_min by hand {gamma}, reported {}",
            s.report.min_transmission_angle
        ));
    }
    match engine(s, &Output::Slide("P".into())) {
        Ok((mk, mh, mg)) => {
            if rel(mk, need.time_ratio) > REL || rel(mh, need.stroke) > REL {
                fails.push(format!(
                    "{tag}: engine K {mk} (rel {:.2e}), H {mh} (rel {:.2e})",
                    rel(mk, need.time_ratio),
                    rel(mh, need.stroke)
                ));
            }
            if (mg - s.report.min_transmission_angle).abs() > GAMMA {
                fails.push(format!(
                    "{tag}: engine γ_min {mg}, reported {}",
                    s.report.min_transmission_angle
                ));
            }
        }
        Err(err) => fails.push(format!("{tag}: engine {err}")),
    }
    let (rk, rh) = (s.report.time_ratio, s.report.stroke);
    if rk.is_none_or(|x| rel(x, need.time_ratio) > REL)
        || rh.is_none_or(|x| rel(x, need.stroke) > REL)
    {
        fails.push(format!("{tag}: reported K {rk:?}, H {rh:?}"));
    }
}

/// Offset slider-cranks over K in (1, 3), strokes 10⁻³ … 10³ m, the best offset and given
/// offsets from 10⁻⁶ of the best to just below the largest one (e < H·cot θ).
pub fn slider_crank_sweep(fast: bool) -> (Vec<String>, usize) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut fails = Vec::new();
    let mut done = 0;
    let ks: &[f64] = if fast {
        &[1.0 + 1e-6, 1.5, 2.9]
    } else {
        &[
            1.0 + 1e-9,
            1.0 + 1e-6,
            1.001,
            1.05,
            1.3,
            1.7,
            2.2,
            2.7,
            2.99,
            3.0 - 1e-6,
            3.0 - 1e-9,
        ]
    };
    let strokes: &[f64] = if fast { &[0.2] } else { &[1e-3, 0.2, 1e3] };
    for &k in ks {
        for &h in strokes {
            // H·cot θ, with π/2 − θ = π(3 − K)/(2(K + 1)) from K (θ rounded loses digits as
            // K nears 3).
            let e_max = h * (PI * (3.0 - k) / (2.0 * (k + 1.0))).tan();
            let mut offsets = vec![OffsetChoice::BestTransmission];
            for f in [1e-6, 1e-3, 0.1, 0.5, 0.9, 0.999, 1.0 - 1e-9] {
                offsets.push(OffsetChoice::Given(f * e_max));
            }
            for offset in offsets {
                let need = SliderCrankRequirement {
                    stroke: h,
                    time_ratio: k,
                    offset,
                };
                match catch_unwind(AssertUnwindSafe(|| slider_crank(&need, &loose))) {
                    Err(_) => fails.push(format!("{need:?}: panic")),
                    Ok(Ok(s)) => {
                        review_slider_crank(&need, &s, &mut fails);
                        done += 1;
                        let best = s.report.min_transmission_angle;
                        if offset == OffsetChoice::BestTransmission && best > 1e-6 {
                            let above = Options::default().with_min_transmission_angle(best + 1e-7);
                            match slider_crank(&need, &above) {
                                Err(Error::Infeasible { reachable, .. })
                                    if (reachable - best).abs() <= 1e-9 => {}
                                other => fails.push(format!(
                                    "{need:?}: [γ] above γ_min {best}: {:?}",
                                    other.map(|s| s.report.min_transmission_angle)
                                )),
                            }
                        }
                    }
                    Ok(Err(e)) => {
                        if !names_a_parameter(&e) {
                            fails.push(format!("{need:?}: unclear error {e}"));
                        }
                    }
                }
            }
            // Just above the largest offset: out of range, naming K or the offset.
            let need = SliderCrankRequirement {
                stroke: h,
                time_ratio: k,
                offset: OffsetChoice::Given(e_max * (1.0 + 1e-9)),
            };
            match slider_crank(&need, &loose) {
                Err(Error::OutOfRange { name, .. }) if name == "K" || name == "offset" => {}
                other => fails.push(format!(
                    "{need:?}: offset above H·cot θ: {:?}",
                    other.map(|s| s.report)
                )),
            }
        }
    }
    for k in [3.0, 3.0 + 1e-12, 10.0, 1e300] {
        let need = SliderCrankRequirement {
            stroke: 0.2,
            time_ratio: k,
            offset: OffsetChoice::BestTransmission,
        };
        match slider_crank(&need, &loose) {
            Err(Error::OutOfRange {
                name: "K",
                max: 3.0,
                ..
            }) => {}
            other => fails.push(format!("K {k}: {:?}", other.map(|s| s.report))),
        }
    }
    (fails, done)
}

/// The shaper read from its description: the crank r = |O1A|, the centres d = |O1O3|, the
/// guide's height h above O3 (the ram's pin F, on the guide, at the reference pose straight
/// above O3). At its extremes the lever is tangent to the crank's circle: sin(ψ/2) = r/d, the
/// crank perpendicular to it, so it turns π ± ψ between them and θ = ψ; the pin on the guide
/// is h·tan(ψ/2) either side of the vertical: H = 2h·tan(ψ/2); the ram block's slot leans
/// ψ/2 from the guide's normal at most, so γ_min = π/2 − ψ/2.
fn shaper_by_hand(l: &Linkage) -> (f64, f64, f64) {
    let r = dist(at(l, "O1"), at(l, "A"));
    let d = dist(at(l, "O1"), at(l, "O3"));
    let h = at(l, "F")[1] - at(l, "O3")[1];
    let half = (r / d).asin();
    (k_of(2.0 * half), 2.0 * h * half.tan(), FRAC_PI_2 - half)
}

/// Shapers over K from 1 + 10⁻⁹ to 10³, strokes 10⁻³ … 10³ m and centre distances from
/// 10⁻³ to the largest that keeps the crank's circle below the ram block.
pub fn shaper_sweep(fast: bool) -> (Vec<String>, usize) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut fails = Vec::new();
    let mut done = 0;
    let ks: &[f64] = if fast {
        &[1.0 + 1e-6, 1.6, 20.0]
    } else {
        &[1.0 + 1e-9, 1.0 + 1e-6, 1.001, 1.2, 1.6, 2.5, 4.0, 20.0, 1e3]
    };
    let strokes: &[f64] = if fast { &[0.3] } else { &[1e-3, 0.3, 1e3] };
    for &k in ks {
        for &h in strokes {
            let theta = PI * (k - 1.0) / (k + 1.0);
            let (s, co) = (0.5 * theta).sin_cos();
            // The guide h_g = H/(2 tan(θ/2)) must clear d + r = d(1 + sin(θ/2)).
            let d_max = 0.5 * h * co / s / (1.0 + s);
            for f in [1e-3, 0.1, 0.5, 0.9, 0.999_999] {
                let need = ShaperRequirement {
                    stroke: h,
                    time_ratio: k,
                    centre_distance: f * d_max,
                };
                match catch_unwind(AssertUnwindSafe(|| shaper(&need, &loose))) {
                    Err(_) => fails.push(format!("{need:?}: panic")),
                    Ok(Ok(sy)) => {
                        done += 1;
                        let tag = format!("{need:?}");
                        if !all_finite(&sy) {
                            fails.push(format!("{tag}: non-finite"));
                            continue;
                        }
                        let (mk, mh, mg) = shaper_by_hand(&sy.linkage);
                        if rel(mk, k) > REL || rel(mh, h) > REL {
                            fails.push(format!(
                                "{tag}: by hand K {mk} ({:.2e}) H {mh} ({:.2e})",
                                rel(mk, k),
                                rel(mh, h)
                            ));
                        }
                        if (mg - sy.report.min_transmission_angle).abs() > GAMMA {
                            fails.push(format!("{tag}: γ by hand {mg}"));
                        }
                        match engine(&sy, &Output::Slide("G".into())) {
                            Ok((ek, eh, eg)) => {
                                if rel(ek, k) > REL || rel(eh, h) > REL {
                                    fails.push(format!(
                                        "{tag}: engine K {ek} ({:.2e}) H {eh} ({:.2e})",
                                        rel(ek, k),
                                        rel(eh, h)
                                    ));
                                }
                                if (eg - sy.report.min_transmission_angle).abs() > GAMMA {
                                    fails.push(format!(
                                        "{tag}: engine γ {eg}, reported {}",
                                        sy.report.min_transmission_angle
                                    ));
                                }
                            }
                            Err(e) => fails.push(format!("{tag}: engine {e}")),
                        }
                    }
                    Ok(Err(e)) => {
                        if !names_a_parameter(&e) {
                            fails.push(format!("{need:?}: unclear error {e}"));
                        }
                    }
                }
            }
            let need = ShaperRequirement {
                stroke: h,
                time_ratio: k,
                centre_distance: d_max * (1.0 + 1e-9),
            };
            match shaper(&need, &loose) {
                Err(Error::Infeasible { .. } | Error::OutOfRange { .. }) => {}
                other => fails.push(format!(
                    "{need:?}: the crank circle reaches the ram block: {:?}",
                    other.map(|s| s.report)
                )),
            }
        }
    }
    (fails, done)
}

/// The rocker angle of the four-bar (d, a, b, c) with O1 at the origin and O3 at (d, 0) at
/// the crank angle φ, mode σ (+1: B left of A→O3), by intersecting the circles about A and
/// O3 (in units of the longest link); `None` where it does not assemble.
fn rocker_angle(d: f64, a: f64, b: f64, c: f64, sigma: f64, phi: f64) -> Option<f64> {
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    let (vx, vy) = (d - ax, -ay);
    let e = vx.hypot(vy);
    let along = 0.5 * (e + (b - c) * (b + c) / e);
    let h2 = (b - along) * (b + along);
    if h2 < -1e-12 * b * b {
        return None;
    }
    let (ux, uy) = (vx / e, vy / e);
    let h = sigma * h2.max(0.0).sqrt();
    let (bx, by) = (ax + along * ux - h * uy, ay + along * uy + h * ux);
    Some(by.atan2(bx - d))
}

/// The angle difference wrapped into (−π, π].
fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(std::f64::consts::TAU);
    if y > PI {
        y - std::f64::consts::TAU
    } else {
        y
    }
}

/// A seeded xorshift generator of uniform numbers in [0, 1).
fn rng(mut x: u64) -> impl FnMut() -> f64 {
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Crank-rockers through three (and two) positions of a known random crank-rocker (scales
/// 10⁻³ … 10³): the engine's rocker stands at each ψ_i when the crank stands at φ_i (to
/// 10⁻¹⁰ rad), the three-position answer is that four-bar (its lengths to 10⁻⁸), and the
/// reported γ_min is the engine's.
pub fn through_sweep(cases: usize) -> (Vec<String>, usize) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut next = rng(0x0DDB_A11C_0FFE_E123);
    let mut fails = Vec::new();
    let mut done = 0;
    for case in 0..cases {
        let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
        let scale = 10f64.powf(r(-3.0, 3.0));
        let (d, a) = (1.0, r(0.05, 0.4));
        let (b, c) = (r(0.5, 1.6), r(0.4, 1.4));
        let sigma = if r(0.0, 1.0) < 0.5 { 1.0 } else { -1.0 };
        if grashof(d, a, b, c).ok() != Some(Grashof::CrankRocker) {
            continue;
        }
        let phi0 = r(0.0, 6.0);
        let phis = [phi0, phi0 + r(0.3, 1.5), phi0 + r(1.8, 3.5)];
        let pairs: Vec<(f64, f64)> = phis
            .iter()
            .map(|&p| (p, rocker_angle(d, a, b, c, sigma, p).unwrap()))
            .collect();
        for n in [3, 2] {
            let tag = format!("case {case}, {n} positions, scale {scale:e}");
            let made = catch_unwind(AssertUnwindSafe(|| {
                crank_rocker_through(d * scale, &pairs[..n], &loose)
            }));
            let s = match made {
                Err(_) => {
                    fails.push(format!("{tag}: panic"));
                    continue;
                }
                Ok(Err(e)) => {
                    // Three positions of a crank-rocker always have one: it must be found.
                    if n == 3 {
                        let g = crank_rocker_gamma(d, a, b, c);
                        if g > 1e-3 && (b / a) < 1e2 && (c / a) < 1e2 {
                            fails.push(format!("{tag}: {e} (the known four-bar exists)"));
                        }
                    }
                    continue;
                }
                Ok(Ok(s)) => s,
            };
            done += 1;
            if !all_finite(&s) {
                fails.push(format!("{tag}: non-finite"));
                continue;
            }
            let plan = match Plan::new(&s.linkage) {
                Ok(p) => p,
                Err(e) => {
                    fails.push(format!("{tag}: plan {e}"));
                    continue;
                }
            };
            for &(phi, psi) in &pairs[..n] {
                match plan.output(&Output::Angle("rocker".into()), Motion::fixed(phi)) {
                    Ok(m) if wrap(m.value - psi).abs() <= REL * PI => {}
                    other => fails.push(format!(
                        "{tag}: at φ {phi} the engine's rocker {:?}, wanted {psi}",
                        other.map(|m| m.value)
                    )),
                }
            }
            let l = &s.linkage;
            let got = [
                dist(at(l, "O1"), at(l, "O3")),
                dist(at(l, "O1"), at(l, "A")),
                dist(at(l, "A"), at(l, "B")),
                dist(at(l, "O3"), at(l, "B")),
            ];
            if n == 3 {
                let want = [d, a, b, c].map(|x| x * scale);
                if got.iter().zip(want).any(|(g, w)| rel(*g, w) > 1e-8) {
                    fails.push(format!("{tag}: lengths {got:?}, the four-bar {want:?}"));
                }
            }
            let [gd, ga, gb, gc] = got;
            let gamma = crank_rocker_gamma(gd, ga, gb, gc);
            if (gamma - s.report.min_transmission_angle).abs() > GAMMA {
                fails.push(format!(
                    "{tag}: γ_min by hand {gamma}, reported {}",
                    s.report.min_transmission_angle
                ));
            }
            match engine(&s, &Output::Angle("rocker".into())) {
                Ok((_, _, mg)) if (mg - s.report.min_transmission_angle).abs() <= GAMMA => {}
                other => fails.push(format!(
                    "{tag}: engine γ {other:?}, reported {}",
                    s.report.min_transmission_angle
                )),
            }
        }
    }
    (fails, done)
}

/// A function and its range for [`function_sweep`].
struct Wanted {
    f: fn(f64) -> f64,
    x: [f64; 2],
}

/// Function generators of several f over several crank and rocker ranges and frames (10⁻³ …
/// 10³ m): at Chebyshev's three points the engine's rocker is exactly the wanted angle
/// (10⁻¹⁰ rad), Freudenstein's equation holds there with the coefficients read back from the
/// description, the least-squares coefficients solve the normal equations (solved here), and
/// the structural error is the one evaluated here by circle intersection.
pub fn function_sweep(fast: bool) -> (Vec<String>, usize) {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let deg = f64::to_radians;
    let mut fails = Vec::new();
    let mut done = 0;
    let wanted = [
        Wanted {
            f: f64::log10,
            x: [1.0, 2.0],
        },
        Wanted {
            f: |x| x * x,
            x: [0.0, 1.0],
        },
        Wanted {
            f: f64::exp,
            x: [0.0, 1.0],
        },
        Wanted {
            f: f64::sin,
            x: [0.0, FRAC_PI_2],
        },
        Wanted {
            f: |x| 1.0 / x,
            x: [1.0, 3.0],
        },
        Wanted {
            f: f64::sqrt,
            x: [4.0, 1.0],
        },
    ];
    let ranges: &[([f64; 2], [f64; 2])] = &[
        ([-30.0, 30.0], [0.0, 90.0]),
        ([40.0, 120.0], [100.0, 140.0]),
        ([200.0, 290.0], [250.0, 330.0]),
        ([10.0, 70.0], [95.0, 60.0]),
    ];
    let frames: &[f64] = if fast { &[0.1] } else { &[1e-3, 0.1, 1e3] };
    let spacings: &[Spacing] = if fast {
        &[Spacing::Chebyshev, Spacing::LeastSquares(9)]
    } else {
        &[
            Spacing::Chebyshev,
            Spacing::LeastSquares(4),
            Spacing::LeastSquares(31),
        ]
    };
    for w in &wanted {
        for &(cr, rr) in ranges {
            for &frame in frames {
                for &spacing in spacings {
                    let need = FunctionRequirement {
                        x_range: w.x,
                        crank_range: cr.map(deg),
                        rocker_range: rr.map(deg),
                        frame,
                        spacing,
                    };
                    let tag = format!("{need:?}");
                    let g = match catch_unwind(AssertUnwindSafe(|| {
                        function_generator(w.f, &need, &loose)
                    })) {
                        Err(_) => {
                            fails.push(format!("{tag}: panic"));
                            continue;
                        }
                        Ok(Err(e)) => {
                            if !names_a_parameter(&e) {
                                fails.push(format!("{tag}: unclear error {e}"));
                            }
                            continue;
                        }
                        Ok(Ok(g)) => g,
                    };
                    done += 1;
                    review_function(w, &need, &g, &mut fails);
                }
            }
        }
    }
    (fails, done)
}

fn review_function(
    w: &Wanted,
    need: &FunctionRequirement,
    g: &tmm::synthesis::FunctionGenerator,
    fails: &mut Vec<String>,
) {
    let tag = format!("{need:?}");
    let s = &g.synthesis;
    if !all_finite(s) {
        fails.push(format!("{tag}: non-finite"));
        return;
    }
    let l = &s.linkage;
    let (o1, o3) = (at(l, "O1"), at(l, "O3"));
    if o1 != [0.0, 0.0] || o3[1] != 0.0 {
        fails.push(format!(
            "{tag}: not in Freudenstein's frame: O1 {o1:?} O3 {o3:?}"
        ));
        return;
    }
    let (d, a, b, c) = (
        dist(o1, o3),
        dist(o1, at(l, "A")),
        dist(at(l, "A"), at(l, "B")),
        dist(o3, at(l, "B")),
    );
    if rel(d, need.frame) > 1e-12 {
        fails.push(format!("{tag}: frame {d}"));
    }
    // The mode from the reference pose: B's side of A→O3.
    let (pa, pb) = (at(l, "A"), at(l, "B"));
    let cross = (o3[0] - pa[0]) * (pb[1] - pa[1]) - (o3[1] - pa[1]) * (pb[0] - pa[0]);
    let sigma = cross.signum();
    // Freudenstein's coefficients of the description, and the maps.
    let k = [
        d / a,
        d / c,
        (a * a - b * b + c * c + d * d) / (2.0 * a * c),
    ];
    if k.iter()
        .zip(g.coefficients)
        .any(|(x, y)| (x - y).abs() > 1e-9 * (1.0 + y.abs()))
    {
        fails.push(format!(
            "{tag}: coefficients {:?}, the description's {k:?}",
            g.coefficients
        ));
    }
    let [x0, x1] = w.x;
    let (y0, y1) = ((w.f)(x0), (w.f)(x1));
    let phi = |x: f64| {
        need.crank_range[0] + (need.crank_range[1] - need.crank_range[0]) * (x - x0) / (x1 - x0)
    };
    let psi = |y: f64| {
        need.rocker_range[0] + (need.rocker_range[1] - need.rocker_range[0]) * (y - y0) / (y1 - y0)
    };
    let n = match need.spacing {
        Spacing::Chebyshev => 3,
        Spacing::LeastSquares(n) => n,
    };
    let xs: Vec<f64> = (1..=n)
        .map(|j| {
            0.5 * (x0 + x1) - 0.5 * (x1 - x0) * ((2 * j - 1) as f64 * PI / (2 * n) as f64).cos()
        })
        .collect();
    if xs
        .iter()
        .zip(&g.precision_x)
        .any(|(p, q)| (p - q).abs() > 1e-14 * (1.0 + p.abs()))
    {
        fails.push(format!(
            "{tag}: precision x {:?}, Chebyshev's {xs:?}",
            g.precision_x
        ));
    }
    let plan = match Plan::new(l) {
        Ok(p) => p,
        Err(e) => {
            fails.push(format!("{tag}: plan {e}"));
            return;
        }
    };
    if n == 3 {
        for &x in &xs {
            let (p, q) = (phi(x), psi((w.f)(x)));
            let resid = k[0] * q.cos() - k[1] * p.cos() + k[2] - (p - q).cos();
            if resid.abs() > 1e-9 * (1.0 + k[0].abs() + k[1].abs() + k[2].abs()) {
                fails.push(format!("{tag}: Freudenstein's residual {resid:e} at x {x}"));
            }
            match plan.output(&Output::Angle("rocker".into()), Motion::fixed(p)) {
                Ok(m) if wrap(m.value - q).abs() <= REL * PI => {}
                other => fails.push(format!(
                    "{tag}: at x {x} the engine's rocker {:?}, wanted {q}",
                    other.map(|m| m.value)
                )),
            }
        }
    } else {
        // The normal equations MᵀM k = Mᵀr of the rows (cos ψ, −cos φ, 1 | cos(φ − ψ)).
        let mut ata = [[0.0f64; 3]; 3];
        let mut atr = [0.0f64; 3];
        for &x in &xs {
            let (p, q) = (phi(x), psi((w.f)(x)));
            let row = [q.cos(), -p.cos(), 1.0];
            for i in 0..3 {
                for j in 0..3 {
                    ata[i][j] += row[i] * row[j];
                }
                atr[i] += row[i] * (p - q).cos();
            }
        }
        let kk = g.coefficients;
        let resid: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| ata[i][j] * kk[j]).sum::<f64>() - atr[i])
            .collect();
        let size = ata.iter().flatten().map(|v| v.abs()).fold(0.0, f64::max)
            * (1.0 + kk.iter().map(|v| v.abs()).fold(0.0, f64::max));
        if resid.iter().any(|r| r.abs() > 1e-10 * size) {
            fails.push(format!(
                "{tag}: normal equations' residual {resid:?} (size {size:e})"
            ));
        }
    }
    // The structural error at 25 points against circle intersection, followed by continuity.
    let sample: Vec<f64> = (0..25)
        .map(|i| x0 + (x1 - x0) * f64::from(i) / 24.0)
        .collect();
    match g.structural_error_at(w.f, &sample) {
        Ok(curve) => {
            let scale = (y1 - y0) / (need.rocker_range[1] - need.rocker_range[0]);
            let mut last = need.rocker_range[0];
            for (p, &x) in curve.iter().zip(&sample) {
                let Some(mine) = rocker_angle(d, a, b, c, sigma, phi(x)) else {
                    fails.push(format!("{tag}: no assembly by hand at x {x}"));
                    return;
                };
                last += wrap(mine - last);
                let error = (last - psi((w.f)(x))) * scale;
                if (p.error - error).abs() > 1e-9 * (y1 - y0).abs() {
                    fails.push(format!(
                        "{tag}: structural error at x {x}: {} against {error} by hand",
                        p.error
                    ));
                    return;
                }
            }
        }
        Err(e) => fails.push(format!("{tag}: structural error {e}")),
    }
    // γ_min over the crank's range against the engine's at many positions.
    let (lo, span) = (
        need.crank_range[0].min(need.crank_range[1]),
        (need.crank_range[1] - need.crank_range[0]).abs(),
    );
    let mut least = f64::INFINITY;
    for i in 0..=4000 {
        let p = lo + span * f64::from(i) / 4000.0;
        if let Ok(kin) = plan.kinematics(Motion::fixed(p))
            && let Ok(m) = kin.transmission_angle(0)
        {
            least = least.min(m);
        }
    }
    let reported = s.report.min_transmission_angle;
    if least < reported - GAMMA || least > reported + 1e-4 {
        fails.push(format!(
            "{tag}: engine's γ over the range {least}, reported {reported}"
        ));
    }
}

/// Hostile numbers in every field of every closed-form kind: always an `Error`, never a panic
/// or a non-finite number inside an `Ok`.
pub fn hostile_sweep() -> (Vec<String>, usize) {
    let hostile = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        -1.0,
        1e300,
        -1e300,
        1e-300,
        5e-324,
        f64::MIN_POSITIVE / 3.0,
        f64::MAX,
        1.0,
        PI,
        1e6,
        -1e6,
    ];
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut fails = Vec::new();
    let mut done = 0;
    let mut look =
        |what: String, r: std::thread::Result<tmm::Result<Synthesis>>, must_err: bool| {
            done += 1;
            match r {
                Err(_) => fails.push(format!("{what}: panic")),
                Ok(Ok(s)) => {
                    if !all_finite(&s) {
                        fails.push(format!("{what}: non-finite number in an Ok"));
                    } else if must_err {
                        fails.push(format!("{what}: Ok, wanted an Error"));
                    }
                }
                Ok(Err(e)) => {
                    if e.to_string().is_empty() {
                        fails.push(format!("{what}: empty message"));
                    }
                }
            }
        };
    // A value is certainly bad for a length if it is not finite and positive, or out of
    // 1e-100..1e100; for K if not finite or ≤ 1; for the swing if outside (0, π).
    let bad_len = |v: f64| !(v.is_finite() && (1e-100..=1e100).contains(&v));
    for &v in &hostile {
        for field in 0..4 {
            let mut need = CrankRockerRequirement {
                rocker: 0.3,
                swing: 0.8,
                time_ratio: 1.3,
                frame: FrameChoice::BestTransmission,
            };
            let must = match field {
                0 => {
                    need.rocker = v;
                    bad_len(v)
                }
                1 => {
                    need.swing = v;
                    !(v > 0.0 && v < PI)
                }
                2 => {
                    need.time_ratio = v;
                    !(v.is_finite() && v > 1.0)
                }
                _ => {
                    need.frame = FrameChoice::Length(v);
                    bad_len(v)
                }
            };
            let r = catch_unwind(AssertUnwindSafe(|| crank_rocker(&need, &loose)));
            look(format!("crank_rocker {need:?}"), r, must);
        }
        for field in 0..3 {
            let mut need = SliderCrankRequirement {
                stroke: 0.2,
                time_ratio: 1.3,
                offset: OffsetChoice::BestTransmission,
            };
            let must = match field {
                0 => {
                    need.stroke = v;
                    bad_len(v)
                }
                1 => {
                    need.time_ratio = v;
                    !(v.is_finite() && v > 1.0 && v < 3.0)
                }
                _ => {
                    need.offset = OffsetChoice::Given(v);
                    bad_len(v)
                }
            };
            let r = catch_unwind(AssertUnwindSafe(|| slider_crank(&need, &loose)));
            look(format!("slider_crank {need:?}"), r, must);
        }
        for field in 0..3 {
            let mut need = ShaperRequirement {
                stroke: 0.3,
                time_ratio: 1.6,
                centre_distance: 0.25,
            };
            let must = match field {
                0 => {
                    need.stroke = v;
                    bad_len(v)
                }
                1 => {
                    need.time_ratio = v;
                    !(v.is_finite() && v > 1.0)
                }
                _ => {
                    need.centre_distance = v;
                    bad_len(v)
                }
            };
            let r = catch_unwind(AssertUnwindSafe(|| shaper(&need, &loose)));
            look(format!("shaper {need:?}"), r, must);
        }
        // [γ] itself.
        let opts = Options::default().with_min_transmission_angle(v);
        let must = !(v.is_finite() && (0.0..=FRAC_PI_2).contains(&v));
        let need = CrankRockerRequirement {
            rocker: 0.3,
            swing: 0.8,
            time_ratio: 1.3,
            frame: FrameChoice::BestTransmission,
        };
        let r = catch_unwind(AssertUnwindSafe(|| crank_rocker(&need, &opts)));
        look(format!("crank_rocker [γ] = {v}"), r, must);
        // Positions: each number of the three pairs, and the frame.
        let base = [(0.7, 1.77), (1.75, 1.97), (2.8, 2.3)];
        for i in 0..7 {
            let mut pairs = base;
            let mut frame = 0.4;
            match i {
                6 => frame = v,
                _ if i % 2 == 0 => pairs[i / 2].0 = v,
                _ => pairs[i / 2].1 = v,
            }
            let must = if i == 6 { bad_len(v) } else { !v.is_finite() };
            let r = catch_unwind(AssertUnwindSafe(|| {
                crank_rocker_through(frame, &pairs, &loose)
            }));
            look(format!("crank_rocker_through {frame} {pairs:?}"), r, must);
        }
        // The function generator's numbers.
        for i in 0..7 {
            let mut need = FunctionRequirement {
                x_range: [1.0, 2.0],
                crank_range: [-0.5, 0.5],
                rocker_range: [0.0, 1.5],
                frame: 0.1,
                spacing: Spacing::Chebyshev,
            };
            match i {
                0 => need.x_range[0] = v,
                1 => need.x_range[1] = v,
                2 => need.crank_range[0] = v,
                3 => need.crank_range[1] = v,
                4 => need.rocker_range[0] = v,
                5 => need.rocker_range[1] = v,
                _ => need.frame = v,
            }
            let must = if i == 6 { bad_len(v) } else { !v.is_finite() };
            let r = catch_unwind(AssertUnwindSafe(|| {
                function_generator(f64::log10, &need, &loose).map(|g| g.synthesis)
            }));
            look(format!("function_generator {need:?}"), r, must);
        }
    }
    // A function that returns hostile values.
    for v in hostile {
        let need = FunctionRequirement {
            x_range: [1.0, 2.0],
            crank_range: [-0.5, 0.5],
            rocker_range: [0.0, 1.5],
            frame: 0.1,
            spacing: Spacing::LeastSquares(7),
        };
        let r = catch_unwind(AssertUnwindSafe(|| {
            function_generator(
                |x| if x > 1.4 && x < 1.6 { v } else { x.ln() },
                &need,
                &loose,
            )
            .map(|g| g.synthesis)
        }));
        look(
            format!("function_generator f = {v} inside"),
            r,
            !v.is_finite(),
        );
    }
    // Coinciding and too few positions, K exactly 1, ψ exactly π and 0.
    for pairs in [
        vec![(0.7, 1.77), (0.7, 1.97), (2.8, 2.3)],
        vec![(0.7, 1.77), (0.7 + std::f64::consts::TAU, 1.97)],
        vec![(0.7, 1.77)],
        vec![],
    ] {
        let r = catch_unwind(AssertUnwindSafe(|| {
            crank_rocker_through(0.4, &pairs, &loose)
        }));
        look(format!("crank_rocker_through {pairs:?}"), r, true);
    }
    (fails, done)
}

fn report(name: &str, fails: &[String], done: usize) {
    eprintln!("{name}: {done} answers reviewed, {} failures", fails.len());
    for f in fails.iter().take(20) {
        eprintln!("  {f}");
    }
    assert!(fails.is_empty(), "{name}: {} failures", fails.len());
}

#[test]
fn reviewer_crank_rockers_by_k_and_swing() {
    let full = std::env::var("TMM_SYNTH_CASES").is_ok();
    let (fails, done, conditioned) = crank_rocker_sweep(!full);
    eprintln!("  ({conditioned} checked against the lengths' rounding of K)");
    report("crank-rocker", &fails, done);
}

#[test]
fn reviewer_slider_cranks_by_stroke_and_k() {
    let full = std::env::var("TMM_SYNTH_CASES").is_ok();
    let (fails, done) = slider_crank_sweep(!full);
    report("slider-crank", &fails, done);
}

#[test]
fn reviewer_shapers_by_stroke_and_k() {
    let full = std::env::var("TMM_SYNTH_CASES").is_ok();
    let (fails, done) = shaper_sweep(!full);
    report("shaper", &fails, done);
}

#[test]
fn reviewer_crank_rockers_through_positions() {
    let n = std::env::var("TMM_SYNTH_CASES")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .map_or(40, |n| 10 * n);
    let (fails, done) = through_sweep(n);
    report("crank-rocker through positions", &fails, done);
}

#[test]
fn reviewer_function_generators() {
    let full = std::env::var("TMM_SYNTH_CASES").is_ok();
    let (fails, done) = function_sweep(!full);
    report("function generator", &fails, done);
}

#[test]
fn reviewer_hostile_numbers() {
    let (fails, done) = hostile_sweep();
    report("hostile numbers", &fails, done);
}

/// K → 1⁺: a crank-rocker whose crank shrinks past 10⁻³ of its rocker, or whose θ is a few
/// ulps, is refused naming K and the least K that is designed — and that K is designed and
/// met; a swing that no K serves says so.
#[test]
fn reviewer_k_next_to_one_names_the_least_k() {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let mut conditioned = 0;
    let mut fails = Vec::new();
    for swing_deg in [45.0f64, 90.0] {
        for k in [1.0 + 1e-15, 1.0 + 1e-12, 1.0 + 1e-9] {
            let need = CrankRockerRequirement {
                rocker: 0.3,
                swing: swing_deg.to_radians(),
                time_ratio: k,
                frame: FrameChoice::BestTransmission,
            };
            match crank_rocker(&need, &loose) {
                Ok(s) => review_crank_rocker(&need, &s, &mut fails, &mut conditioned),
                Err(Error::OutOfRange { name, min, .. }) if name.starts_with('K') && min > k => {
                    let at_min = CrankRockerRequirement {
                        time_ratio: min,
                        ..need
                    };
                    match crank_rocker(&at_min, &loose) {
                        Ok(s) => review_crank_rocker(&at_min, &s, &mut fails, &mut conditioned),
                        Err(e) => fails.push(format!("{at_min:?}: the least K named fails: {e}")),
                    }
                }
                Err(e) => fails.push(format!("{need:?}: {e}")),
            }
        }
    }
    let tiny = CrankRockerRequirement {
        rocker: 0.3,
        swing: 1e-4,
        time_ratio: 1.3,
        frame: FrameChoice::BestTransmission,
    };
    match crank_rocker(&tiny, &loose) {
        Ok(s) => review_crank_rocker(&tiny, &s, &mut fails, &mut conditioned),
        Err(e) => {
            let text = e.to_string();
            if !(text.contains("swing") || text.starts_with('K')) {
                fails.push(format!("{tiny:?}: {text}"));
            }
        }
    }
    report("K next to 1", &fails, 7);
}
