#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Quick-return mechanisms by the time ratio K and the output's stroke: the crank-rocker, the
//! offset slider-crank and the shaper (crank, slotted lever, ram).

use super::four_bar::FourBar;
use super::held;
use super::search::maximise;
use super::{
    check, crank_excess, length, require_transmission, time_ratio_of, Options, Report, Synthesis,
    MAX_LINK_RATIO,
};
use crate::angle::{cross, normalize};
use crate::error::{finite, positive, Ends, Error, Result};
use crate::kinematics::Grashof;
use crate::linkage::{Input, Joint, Link, Linkage, Output};
use nalgebra::Vector2;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

type V = Vector2<f64>;

/// Where the crank's pivot of a [`crank_rocker`] goes on its locus circle.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum FrameChoice {
    /// At this distance from the rocker's pivot (the frame O1O3), m.
    Length(f64),
    /// Where the smallest transmission angle over a turn is largest.
    BestTransmission,
}

/// What a [`crank_rocker`] must do.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CrankRockerRequirement {
    /// l_O3B, the rocker, m (> 0).
    pub rocker: f64,
    /// ψ, the rocker's swing between its extreme positions, rad in (0, π).
    pub swing: f64,
    /// K, the time ratio of the rocker's strokes (> 1).
    pub time_ratio: f64,
    /// The choice of the crank's pivot.
    pub frame: FrameChoice,
}

/// The locus of the crank's pivot: with O3 at the origin and the rocker's extreme positions
/// B1 = c(sin ψ/2, cos ψ/2), B2 = c(−sin ψ/2, cos ψ/2), O1 sees the chord B1B2 under the angle
/// θ, so it lies on one of the two circles through B1 and B2 whose inscribed angle on the
/// arc on one side of the chord is θ: radius R = |B1B2|/(2 sin θ), centre on the chord's
/// perpendicular bisector at h = (|B1B2|/2)·cot θ towards that side (`side` = ±1 along +y).
struct Locus {
    b1: V,
    b2: V,
    c: f64,
    centre: [V; 2],
    radius: f64,
    mid_y: f64,
}

impl Locus {
    fn new(c: f64, swing: f64, theta: f64) -> Self {
        let (s, co) = (0.5 * swing).sin_cos();
        let half = c * s;
        let h = half / theta.tan();
        let mid_y = c * co;
        Self {
            b1: V::new(half, mid_y),
            b2: V::new(-half, mid_y),
            c,
            centre: [V::new(0.0, mid_y + h), V::new(0.0, mid_y - h)],
            radius: half / theta.sin(),
            mid_y,
        }
    }

    /// The point at the polar angle `t` on circle `k` (0: the arc above the chord, 1: below),
    /// if it lies on that circle's arc of inscribed angle θ.
    fn point(&self, k: usize, t: f64) -> Option<V> {
        let p = self.centre[k] + self.radius * V::new(t.cos(), t.sin());
        let side = if k == 0 { 1.0 } else { -1.0 };
        (side * (p.y - self.mid_y) > 0.0).then_some(p)
    }

    /// The crank-rocker with its crank's pivot at `p` (O3 at the origin), if there is one:
    /// B1 and B2 are its extreme positions when crank and coupler are collinear there, one
    /// stretched (|O1B| = a + b) and one folded (b − a), on the same side of the frame line
    /// (one assembly mode), and the crank turns fully.
    fn design(&self, p: V) -> Option<FourBar> {
        let (d, d1, d2) = (p.norm(), (p - self.b1).norm(), (p - self.b2).norm());
        let a = 0.5 * (d1 - d2).abs();
        let b = 0.5 * (d1 + d2);
        if !(a > 1e-9 * b && d > 1e-9 * self.c) {
            return None;
        }
        let (s1, s2) = (cross(-p, self.b1 - p), cross(-p, self.b2 - p));
        if !(s1 * s2 > 0.0) {
            return None;
        }
        let fb = FourBar::local(d, a, b, self.c, s1.signum());
        (fb.grashof().ok()? == Grashof::CrankRocker).then_some(fb)
    }

    fn candidate(&self, k: usize, t: f64) -> Option<FourBar> {
        self.design(self.point(k, t)?)
    }

    /// The arcs of circle `k` between the points where a design can begin or end: B1, B2
    /// and the circle's second crossings of the lines O3B1 and O3B2 (there B1 and B2 pass
    /// from one side of the frame line to the other). A feasible arc near the bound of K is
    /// a sliver next to B1 or B2 that a scan of the whole circle steps across; scanned arc
    /// by arc, each gets its own samples.
    fn arcs(&self, k: usize) -> Vec<(f64, f64)> {
        let centre = self.centre[k];
        let at = |p: V| (p - centre).y.atan2((p - centre).x);
        // A line s·u through O3 meets the circle where s² − 2s·u·C + |C|² − R² = 0; one root
        // is s = c (at B), the other (|C|² − R²)/c.
        let other = (centre.norm_squared() - self.radius * self.radius) / self.c;
        let mut ts: Vec<f64> = [self.b1, self.b2]
            .iter()
            .flat_map(|&b| [at(b), at(b / self.c * other)])
            .filter(|t| t.is_finite())
            .map(|t| t.rem_euclid(TAU))
            .collect();
        ts.sort_by(f64::total_cmp);
        ts.dedup();
        if ts.is_empty() {
            return vec![(0.0, TAU)];
        }
        let first = ts[0];
        ts.push(first + TAU);
        ts.windows(2).map(|w| (w[0], w[1])).collect()
    }

    /// The best design over both circles by γ_min (each arc scanned with its share of `n`
    /// points, at least 64, then golden section).
    fn best(&self, n: usize) -> Option<FourBar> {
        (0..2)
            .flat_map(|k| self.arcs(k).into_iter().map(move |arc| (k, arc)))
            .filter_map(|(k, (lo, hi))| {
                let m = ((n as f64 * (hi - lo) / TAU) as usize).max(64);
                maximise(
                    |t| self.candidate(k, t).map(|f| f.gamma_full().0),
                    lo,
                    hi,
                    m,
                )
                .and_then(|(t, _)| self.candidate(k, t))
            })
            .max_by(|x, y| x.gamma_full().0.total_cmp(&y.gamma_full().0))
    }

    /// The designs whose frame is `d0`: where the circle of radius d0 about O3 crosses the
    /// two locus circles.
    fn with_frame(&self, d0: f64) -> Vec<FourBar> {
        let mut out = Vec::new();
        for (k, centre) in self.centre.iter().enumerate() {
            let dist = centre.norm();
            if dist == 0.0 {
                continue;
            }
            let along = (d0 * d0 - self.radius * self.radius + dist * dist) / (2.0 * dist);
            let h2 = d0 * d0 - along * along;
            if h2 < 0.0 {
                continue;
            }
            let u = centre / dist;
            for s in [1.0, -1.0] {
                let p = along * u + s * h2.sqrt() * V::new(-u.y, u.x);
                let t = (p - centre).y.atan2((p - centre).x);
                if self.point(k, t).is_some()
                    && let Some(f) = self.design(p)
                {
                    out.push(f);
                }
            }
        }
        out
    }
}

const SCAN: usize = 2048;

/// The interval of θ in (0, `top`) around `theta` where the longest-to-shortest link ratio
/// `ratio(θ)` (None where no design exists) stays within [`MAX_LINK_RATIO`]: the feasible run
/// of a scan nearest to `theta`, its ends refined by bisection, and whether it reaches `top`.
/// None if no θ of the scan is feasible. As K → 1 the quick-return designs stretch without bound (a slider-crank's rod
/// grows as 1/θ, a shaper's lever as 1/θ²), so a K near 1 has a lower bound here; a large
/// offset makes the slider-crank's rod long at both ends of the range, so it can have an
/// upper bound too.
fn ratio_interval(
    theta: f64,
    top: f64,
    ratio: impl Fn(f64) -> Option<f64>,
) -> Option<(f64, f64, bool)> {
    let ok = |t: f64| ratio(t).is_some_and(|r| r <= MAX_LINK_RATIO);
    let grid: Vec<f64> = (1..RATIO_SCAN)
        .map(|i| top * i as f64 / RATIO_SCAN as f64)
        .collect();
    let nearest = grid
        .iter()
        .copied()
        .filter(|&t| ok(t))
        .min_by(|x, y| (x - theta).abs().total_cmp(&(y - theta).abs()))?;
    let edge = |inside: f64, outside: f64| {
        let (mut inside, mut outside) = (inside, outside);
        for _ in 0..60 {
            let mid = 0.5 * (inside + outside);
            if ok(mid) {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        inside
    };
    let step = top / RATIO_SCAN as f64;
    let mut lo = nearest;
    while lo - step > 0.0 && ok(lo - step) {
        lo -= step;
    }
    let mut hi = nearest;
    while hi + step < top && ok(hi + step) {
        hi += step;
    }
    let reaches_top = hi + step >= top;
    let hi = if reaches_top {
        top
    } else {
        edge(hi, hi + step)
    };
    Some((edge(lo, (lo - step).max(0.0)), hi, reaches_top))
}

const RATIO_SCAN: usize = 512;

/// [`Error::OutOfRange`] for K when the design at `theta` breaks [`MAX_LINK_RATIO`]
/// (`ratio_now`), with the interval of K that keeps it; [`Error::NoMechanism`] naming
/// `culprit` when no K does.
fn link_ratio_error(
    method: &'static str,
    k: f64,
    ratio_now: f64,
    interval: Option<(f64, f64, bool)>,
    culprit: &str,
) -> Error {
    match interval {
        Some((lo, hi, top)) => Error::OutOfRange {
            name: "K (the longest link within 10³ of the shortest)",
            value: k,
            min: time_ratio_of(lo),
            max: time_ratio_of(hi),
            // The top of the range is where no design exists any more (K = 3 for a
            // slider-crank); an edge the ratio sets is a design.
            ends: if top { Ends::OpenAbove } else { Ends::Closed },
        },
        None => Error::NoMechanism {
            method,
            problem: format!(
                "its longest link is {ratio_now:.4e} times its shortest (at most \
                 {MAX_LINK_RATIO:e}), and no K keeps it within that for this {culprit}"
            ),
        },
    }
}

/// The largest crank excess θ of a crank-rocker with the swing ψ: (π + ψ)/2, so K below
/// (3π + ψ)/(π − ψ) (not reached).
///
/// Derivation: B1 and B2 must lie on one side of the frame line O1O3, so O1 lies outside
/// the double wedge of the lines O3B1 and O3B2. The angle θ = ∠B1O1B2 under which O1 sees
/// the chord B1B2 is largest where O1 nears B1 (or B2) along the wedge's edge from O3:
/// there the ray to B1 points along O3→B1 and the ray to B2 along B1→B2, whose angle is π
/// minus the isosceles triangle O3B1B2's base angle (π − ψ)/2, that is (π + ψ)/2. Towards
/// that limit a = (|O1B2| − |O1B1|)/2 → b and d → c (Grashof holds there: a + c ≤ b + d is
/// |O1O3| + |O1B1| ≥ |O3B1|), and γ_min → 0: a change-point four-bar.
fn largest_crank_excess(swing: f64) -> f64 {
    0.5 * (PI + swing)
}

/// The error when no crank-rocker of the swing has the time ratio `k` (crank excess
/// `theta`): K at or above the bound of [`largest_crank_excess`] is out of range (the
/// interval names the exact bound); below it, no design found names the swing and the
/// bound (the designs next to the bound near a change point; a swing near 0 or π).
fn no_crank_rocker(k: f64, swing: f64, theta: f64) -> Error {
    let top = largest_crank_excess(swing);
    // K* = (π + θ*)/(π − θ*) with θ* = (π + ψ)/2 is (3π + ψ)/(π − ψ): from ψ directly, since
    // π − θ* rounded loses digits as ψ nears π (4e-12 of K* at ψ = π − 10⁻⁴).
    let bound = (3.0 * PI + swing) / (PI - swing);
    if theta >= top {
        return Error::OutOfRange {
            name: "K",
            value: k,
            min: 1.0,
            max: bound,
            ends: Ends::Open,
        };
    }
    Error::NoMechanism {
        method: "crank-rocker",
        problem: format!(
            "no crank-rocker of the swing ψ = {swing:e} rad ({:.6}°) with K = {k} was \
             found on the locus circle, though K is below this swing's bound (3π + ψ)/(π − ψ) \
             = {:.10e}: next to the bound the designs end in a change point (γ_min → 0), and \
             at a swing this near 0 or π (or a K this near 1) their crank is below 1e-9 of the \
             coupler; change the swing or K",
            swing.to_degrees(),
            bound
        ),
    }
}

/// A crank-rocker four-bar whose rocker swings through `swing` with the time ratio K, the
/// crank's pivot on its locus circle at a given frame length or where the smallest
/// transmission angle is largest.
///
/// Derivation: at the rocker's extreme positions B1 and B2 the crank and the coupler are
/// collinear, stretched (|O1B1| = b + a) and folded (|O1B2| = b − a); the crank turns
/// π + θ from one to the other and π − θ back, so K = (π + θ)/(π − θ), θ = π(K − 1)/(K + 1),
/// and θ is the angle B1O1B2. O1 is therefore on a circle through B1 and B2 (inscribed angle
/// θ), and then a = (|O1B1| − |O1B2|)/2, b = (|O1B1| + |O1B2|)/2, d = |O1O3|. Not every point
/// of the arc gives a crank-rocker: B1 and B2 must lie on one side of the frame line (one
/// assembly mode) and the crank must be the shortest link (Grashof). γ_min over a turn is at
/// φ = 0 or π (the crank along the frame line), in closed form.
///
/// The description is in Freudenstein's frame (O1 at the origin, O3 at (d, 0)), posed at the
/// stretched extreme position; output: the rocker's angle.
///
/// # Examples
/// A worked problem: a rocker of 0.3 m swinging 45° with K = 1.25, the frame chosen for the
/// best transmission. By hand, θ = 180°·(1.25 − 1)/(1.25 + 1) = 20°: the crank turns
/// 180° + 20° = 200° on the working stroke and 160° on the return.
/// ```
/// use tmm::synthesis::{crank_rocker, CrankRockerRequirement, FrameChoice, Options};
/// use tmm::kinematics::Rotation;
/// use tmm::linkage::{Output, Plan};
/// let need = CrankRockerRequirement {
///     rocker: 0.3,
///     swing: 45f64.to_radians(),
///     time_ratio: 1.25,
///     frame: FrameChoice::BestTransmission,
/// };
/// let s = crank_rocker(&need, &Options::default())?;
/// assert!(s.report.min_transmission_angle > 40f64.to_radians());
/// // The engine finds the same K and swing.
/// let strokes = Plan::new(&s.linkage)?.strokes(&Output::Angle("rocker".into()), Rotation::Ccw)?;
/// assert!((strokes.time_ratio - 1.25).abs() < 1e-9);
/// assert!((strokes.stroke - 45f64.to_radians()).abs() < 1e-9);
/// assert!((strokes.working_angle.to_degrees() - 200.0).abs() < 1e-8);
/// assert!((strokes.idle_angle.to_degrees() - 160.0).abs() < 1e-8);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] / [`Error::NonPositive`] for a bad rocker length or frame length;
/// [`Error::OutOfRange`] for a swing outside (0, π), for K ≤ 1, and for K above the largest
/// time ratio any crank-rocker of this swing reaches (the interval names it);
/// [`Error::Infeasible`] for a frame length on which no crank-rocker's pivot lies (with the
/// nearest that works) and for γ_min below \[γ\] (with the best reachable);
/// [`Error::OutOfRange`] (`"K (…)"`, the interval's top the largest K that is held) for a K so
/// near its bound that no description in f64 holds it to 10⁻¹⁰ as the engine measures it.
///
/// The report is computed from the lengths of the description (as the engine reads them off
/// its joints), and the engine's own K and swing of the description are checked to 10⁻¹⁰
/// before it is returned.
pub fn crank_rocker(need: &CrankRockerRequirement, options: &Options) -> Result<Synthesis> {
    let made = crank_rocker_made(need, options);
    if let Err(Error::NoMechanism {
        method: LINK_RATIO,
        problem,
    }) = &made
    {
        let made_at = |k: f64, o: &Options| {
            let other = CrankRockerRequirement {
                time_ratio: k,
                ..*need
            };
            crank_rocker_made(&other, o).is_ok()
        };
        return Err(least_k_above(
            need,
            made_at,
            "K (the longest link within 10³ of the shortest)",
        )
        .unwrap_or_else(|| Error::NoMechanism {
            method: "crank-rocker",
            problem: format!(
                "{problem}, and no K up to the bound keeps it within that for the swing ψ = \
                     {} rad",
                need.swing
            ),
        }));
    }
    let (s, kept) = made?;
    if kept {
        return Ok(s);
    }
    // Designed, but K is too near its bound for any f64 description to hold it: say up to
    // which K one does (the transmission angle aside: that has its own error).
    let loose = options.with_min_transmission_angle(0.0);
    let kept_at = |k: f64| {
        let other = CrankRockerRequirement {
            time_ratio: k,
            ..*need
        };
        matches!(crank_rocker_made(&other, &loose), Ok((_, true)))
    };
    let kept_above = |k: f64, o: &Options| {
        let other = CrankRockerRequirement {
            time_ratio: k,
            ..*need
        };
        matches!(crank_rocker_made(&other, o), Ok((_, true)))
    };
    Err(held::k_not_held(need.time_ratio, kept_at)
        .or_else(|| {
            // K next to 1 (θ of a few ulps): held from some K above.
            least_k_above(
                need,
                kept_above,
                "K (held to 1e-10 by a description in f64 only from the interval's bottom)",
            )
        })
        .unwrap_or_else(|| Error::NoMechanism {
            method: "crank-rocker",
            problem: format!(
                "its description holds K = {} only to {:.2e} of it (its report: K {:?}, swing \
                 {:?} rad), not to 1e-10, and neither does the design at a K between 1 and \
                 this one tried",
                need.time_ratio,
                s.report
                    .time_ratio
                    .map_or(f64::NAN, |k| (k - need.time_ratio).abs() / need.time_ratio),
                s.report.time_ratio,
                s.report.stroke
            ),
        }))
}

/// The method named by a crank-rocker whose links break [`MAX_LINK_RATIO`].
const LINK_RATIO: &str = "crank-rocker (link ratio)";

/// The error for a crank-rocker that `made_at(K, options)` refuses at its K, next to 1 (the
/// links break [`MAX_LINK_RATIO`] as the crank shrinks against the rocker, or θ is a few
/// ulps): [`Error::OutOfRange`] (`name`) for K with the least K above it that `made_at`
/// accepts (a design is tried at K − 1 times 10, 100, … and at 1 %,
/// 10 %, 50 % of the way to the bound, the first that keeps it bisected against K), up to
/// the bound (3π + ψ)/(π − ψ). `None` if none of those is accepted.
fn least_k_above(
    need: &CrankRockerRequirement,
    made_at: impl Fn(f64, &Options) -> bool,
    name: &'static str,
) -> Option<Error> {
    let loose = Options::default().with_min_transmission_angle(0.0);
    let k = need.time_ratio;
    let top = (3.0 * PI + need.swing) / (PI - need.swing);
    let ok = |t: f64| made_at(t, &loose);
    let mut tries: Vec<f64> = (1..=15)
        .map(|j| 1.0 + (k - 1.0) * 10f64.powi(j))
        .chain([0.01, 0.1, 0.5].map(|s| 1.0 + (top - 1.0) * s))
        .filter(|&t| t > k && t < top)
        .collect();
    tries.sort_by(f64::total_cmp);
    let mut good = tries.into_iter().find(|&t| ok(t))?;
    let mut bad = k;
    for _ in 0..60 {
        let mid = 0.5 * (bad + good);
        if mid <= bad || mid >= good {
            break;
        }
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    Some(Error::OutOfRange {
        name,
        value: k,
        min: good,
        max: top,
        ends: Ends::OpenAbove,
    })
}

/// [`crank_rocker`]'s design, and whether its description holds K and the swing to
/// [`held::HELD`] (its report is computed from the description's own lengths).
fn crank_rocker_made(
    need: &CrankRockerRequirement,
    options: &Options,
) -> Result<(Synthesis, bool)> {
    let c = length("rocker", need.rocker)?;
    let swing = finite("swing", need.swing)?;
    if !(swing > 0.0 && swing < PI) {
        return Err(Error::OutOfRange {
            name: "swing",
            value: swing,
            min: 0.0,
            max: PI,
            ends: Ends::Open,
        });
    }
    let theta = crank_excess(need.time_ratio)?;
    let required = options.check()?;
    if let FrameChoice::Length(d) = need.frame {
        length("frame length", d)?;
    }
    // Beyond the bound no design exists (a search there would meet only rounding).
    if theta >= largest_crank_excess(swing) {
        return Err(no_crank_rocker(need.time_ratio, swing, theta));
    }
    // The problem is similar in scale: solved for a rocker of 1, scaled by c at the end.
    let locus = Locus::new(1.0, swing, theta);
    // A given frame: where its circle about O3 crosses the locus, the best of those.
    let given = match need.frame {
        FrameChoice::Length(d0) => locus
            .with_frame(d0 / c)
            .into_iter()
            .max_by(|x, y| x.gamma_full().0.total_cmp(&y.gamma_full().0)),
        FrameChoice::BestTransmission => None,
    };
    let design = if let Some(f) = given {
        f
    } else {
        let Some(best) = locus.best(SCAN) else {
            return Err(no_crank_rocker(need.time_ratio, swing, theta));
        };
        if let FrameChoice::Length(d0) = need.frame {
            let nearest = (0..2)
                .flat_map(|k| (0..4 * SCAN).map(move |i| (k, TAU * i as f64 / (4 * SCAN) as f64)))
                .filter_map(|(k, t)| locus.candidate(k, t))
                .map(|f| f.d)
                .min_by(|x, y| (x - d0 / c).abs().total_cmp(&(y - d0 / c).abs()))
                .unwrap_or(best.d);
            return Err(Error::Infeasible {
                parameter: "frame length O1O3 (m)",
                required: d0,
                reachable: nearest * c,
            });
        }
        best
    };
    let design = held::polish_crank_rocker(design, theta, swing).scaled(c)?;
    design.proportions(LINK_RATIO)?;
    let linkage = design.linkage(
        "synthesised crank-rocker",
        design.extremes().phi_ext,
        Vec::new(),
        None,
    )?;
    // The report from the lengths the engine reads off the joints, not the design's.
    let described = held::described_four_bar(&linkage).unwrap_or(design);
    let report = described.report("crank-rocker", None)?;
    require_transmission(report.min_transmission_angle, required)?;
    check::accepted(&linkage)?;
    // K to 1e-10, or, next to its bound, to three times what one rounding of each length
    // moves it by (no f64 description does better there); the swing to 1e-10.
    let k_tol = held::HELD.max(3.0 * held::crank_rocker_k_rounding(&described) / need.time_ratio);
    let kept = held::held_to(report.time_ratio, need.time_ratio, k_tol)
        && held::held(report.stroke, swing)
        && held::engine_holds(&linkage, (need.time_ratio, k_tol), swing);
    Ok((Synthesis { linkage, report }, kept))
}

/// Where the guide of a [`slider_crank`] goes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum OffsetChoice {
    /// At this distance e above the crank's pivot, m (> 0: a central slider-crank has K = 1).
    Given(f64),
    /// At the offset where the smallest transmission angle over a turn is largest.
    BestTransmission,
}

/// What a [`slider_crank`] must do.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SliderCrankRequirement {
    /// H, the slider's stroke, m (> 0).
    pub stroke: f64,
    /// K, the time ratio of the strokes, in (1, 3) (above, θ ≥ π/2, which no slider-crank
    /// reaches).
    pub time_ratio: f64,
    /// The guide's offset.
    pub offset: OffsetChoice,
}

/// The offset slider-crank for (H, θ, e): the dead centres B1 = (x2 + H, e) (stretched) and
/// B2 = (x2, e) (folded), with the angle B1O1B2 = θ. From tan θ = e·H/(x1·x2 + e²):
/// x2² + H·x2 − (e·H·cot θ − e²) = 0, so x2 = 2q/(H + √(H² + 4q)) with q = e·H·cot θ − e²,
/// and q > 0 (x2 > 0: both dead centres ahead of the crank, one assembly mode) needs
/// e < H·cot θ. Then a = (|O1B1| − |O1B2|)/2, b = (|O1B1| + |O1B2|)/2. Returns (a, b, x1).
fn slider_design(h: f64, theta: f64, e: f64) -> Option<(f64, f64, f64)> {
    let q = e * h / theta.tan() - e * e;
    if !(q > 0.0) {
        return None;
    }
    let x2 = 2.0 * q / (h + (h * h + 4.0 * q).sqrt());
    let x1 = x2 + h;
    let (r1, r2) = (x1.hypot(e), x2.hypot(e));
    Some((0.5 * (r1 - r2), 0.5 * (r1 + r2), x1))
}

/// The offset (for H = 1) at which γ_min of the slider-crank with the crank excess `theta`
/// is largest: a scan of (0, cot θ), then golden section about its best point (γ_min is
/// unimodal in e, so the best lies next to the scan's best even where it is far below the
/// scan's step: e → H/2 as θ → 0 while cot θ grows as 1/θ).
fn best_offset(theta: f64) -> Option<f64> {
    let top = 1.0 / theta.tan();
    let f = |e: f64| slider_design(1.0, theta, e).map(|(a, b, _)| slider_gamma(a, b, e));
    maximise(f, 1e-9 * top, top * (1.0 - 1e-9), SCAN).map(|(e, _)| e)
}

/// The least crank excess θ (the least K) whose design keeps `ratio(θ)` (longest over
/// shortest link) within [`MAX_LINK_RATIO`], by one bisection between `theta`, whose ratio
/// breaks it, and π/4; `None` if π/4 breaks it too.
///
/// Why a bisection suffices: at the best offset the rod's ratio to the crank falls as θ
/// grows (tends to √(2/θ) as θ → 0, 1 as θ → π/2; checked at 400 θ from 10⁻¹³ to π/2, and
/// the design just inside the bound is checked by the tests), so it crosses the bound once.
/// It replaces a scan of 512 θ, each a search of the best offset: 250 ms, now about 70 (θ to one ulp).
fn least_theta(theta: f64, ratio: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let ok = |t: f64| ratio(t).is_some_and(|r| r <= MAX_LINK_RATIO);
    let (mut lo, mut hi) = (theta, PI / 4.0);
    if !(lo < hi) || !ok(hi) {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// γ_min of an offset slider-crank (guide at y = e > 0): the rod leans most, sin β =
/// (a + e)/b, with A lowest (φ = 3π/2); γ = π/2 − β.
fn slider_gamma(a: f64, b: f64, e: f64) -> f64 {
    ((a + e) / b).clamp(-1.0, 1.0).acos()
}

/// An offset slider-crank with the stroke H and the time ratio K, at a given offset or at
/// the offset where the smallest transmission angle is largest.
///
/// The crank's pivot O1 is at the origin, the guide the line y = e along +x, the slider to the
/// right of the crank. Derivation: at the dead centres B1 = (x2 + H, e) (crank and rod
/// stretched, |O1B1| = b + a) and B2 = (x2, e) (folded, b − a) the crank angles differ by
/// π − θ, so ∠B1O1B2 = θ = π(K − 1)/(K + 1); tan θ = e·H/(x1·x2 + e²) gives the quadratic
/// x2² + H·x2 − (e·H·cot θ − e²) = 0, whose root must be positive (both dead centres ahead of
/// the crank, one assembly mode): e < H·cot θ, so K < 3 (θ < π/2) and, for a given offset,
/// θ < arctan(H/e). Then a = (|O1B1| − |O1B2|)/2 and b = (|O1B1| + |O1B2|)/2.
/// γ_min = arccos((a + e)/b), with the crank pointing down (φ = 3π/2). The description is
/// posed at the outer dead centre; joints `O1`, `A`, `B`, `P` (prismatic, the slider on the
/// frame's guide); links `frame`, `crank`, `rod`, `slider`; output the slide of `P`.
///
/// # Examples
/// A stroke of 0.2 m with K = 1.2, the offset chosen for the best transmission (γ_min ≈ 47°;
/// with K = 1.4 the best is about 33°, below the default 40°, and the answer is an error):
/// ```
/// use tmm::synthesis::{slider_crank, OffsetChoice, Options, SliderCrankRequirement};
/// use tmm::kinematics::Rotation;
/// use tmm::linkage::{Output, Plan};
/// let need = SliderCrankRequirement { stroke: 0.2, time_ratio: 1.2, offset: OffsetChoice::BestTransmission };
/// let s = slider_crank(&need, &Options::default())?;
/// let strokes = Plan::new(&s.linkage)?.strokes(&Output::Slide("P".into()), Rotation::Ccw)?;
/// assert!((strokes.stroke - 0.2).abs() < 1e-10);
/// assert!((strokes.time_ratio - 1.2).abs() < 1e-9);
/// assert!((s.report.min_transmission_angle.to_degrees() - 47.2).abs() < 0.1);
/// let harder = SliderCrankRequirement { time_ratio: 1.4, ..need };
/// assert!(slider_crank(&harder, &Options::default()).is_err());
/// # Ok::<(), tmm::Error>(())
/// ```
/// A worked problem with the offset given: H = 200 mm, K = 1.2, e = 50 mm. By hand:
/// θ = 180°·0.2/2.2 = 16.364°; q = e·H·cot θ − e² = 31 716 mm², x2 = 2q/(H + √(H² + 4q)) =
/// 103.86 mm, x1 = x2 + H = 303.86 mm; |O1B1| = √(x1² + e²) = 307.94 mm = b + a and
/// |O1B2| = √(x2² + e²) = 115.26 mm = b − a, so the crank a = 96.34 mm, the rod
/// b = 211.60 mm, and γ_min = arccos((a + e)/b) = 46.25°:
/// ```
/// use tmm::synthesis::{slider_crank, OffsetChoice, Options, SliderCrankRequirement};
/// let need = SliderCrankRequirement { stroke: 0.2, time_ratio: 1.2, offset: OffsetChoice::Given(0.05) };
/// let s = slider_crank(&need, &Options::default())?;
/// assert!((s.report.dimension("crank").unwrap() - 0.096_34).abs() < 5e-6);
/// assert!((s.report.dimension("rod").unwrap() - 0.211_60).abs() < 5e-6);
/// assert!((s.report.min_transmission_angle.to_degrees() - 46.25).abs() < 5e-3);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] / [`Error::NonPositive`] for the stroke or the offset;
/// [`Error::OutOfRange`] for K outside (1, 3), or above the largest K of the given offset
/// (θ < arctan(H/e)); [`Error::Infeasible`] for γ_min below \[γ\]; [`Error::OutOfRange`]
/// (`"K (…)"`, the interval's top the largest K that is held) where no description in f64
/// holds K to 10⁻¹⁰ as the engine measures it (a small given offset with K near 3: the folded
/// dead centre next to the crank's pivot).
///
/// The report is computed from the lengths of the description, and the engine's own K and
/// stroke of the description are checked to 10⁻¹⁰ before it is returned.
pub fn slider_crank(need: &SliderCrankRequirement, options: &Options) -> Result<Synthesis> {
    let (s, kept) = slider_crank_made(need, options)?;
    if kept {
        return Ok(s);
    }
    // Designed, but no f64 description holds K (the folded dead centre next to the crank's
    // pivot, or K next to 3): say up to which K one does.
    let loose = options.with_min_transmission_angle(0.0);
    let kept_at = |k: f64| {
        let other = SliderCrankRequirement {
            time_ratio: k,
            ..*need
        };
        matches!(slider_crank_made(&other, &loose), Ok((_, true)))
    };
    Err(
        held::k_not_held(need.time_ratio, kept_at).unwrap_or_else(|| Error::NoMechanism {
            method: "offset slider-crank",
            problem: format!(
                "its description holds K = {} and the stroke {} m only to the report's K \
                 {:?} and stroke {:?}, not to 1e-10, and neither does the design at a K \
                 between 1 and this one tried",
                need.time_ratio, need.stroke, s.report.time_ratio, s.report.stroke
            ),
        }),
    )
}

/// [`slider_crank`]'s design, and whether its description holds K and the stroke to
/// [`held::HELD`] (its report is computed from the description's own lengths).
fn slider_crank_made(
    need: &SliderCrankRequirement,
    options: &Options,
) -> Result<(Synthesis, bool)> {
    let h = length("stroke", need.stroke)?;
    let theta = crank_excess(need.time_ratio)?;
    let required = options.check()?;
    let out_of_range = |max: f64| Error::OutOfRange {
        name: "K",
        value: need.time_ratio,
        min: 1.0,
        max,
        ends: Ends::Open,
    };
    if theta >= FRAC_PI_2 {
        return Err(out_of_range(3.0));
    }
    // Similar in scale: solved for H = 1 (the offset e/H), scaled by H at the end.
    let given = match need.offset {
        OffsetChoice::Given(e) => Some(length("offset", e)? / h),
        OffsetChoice::BestTransmission => None,
    };
    // The largest offset (per unit stroke) is cot θ = tan(π/2 − θ), and π/2 − θ =
    // π(3 − K)/(2(K + 1)) from K itself: from θ rounded it loses digits as K nears 3 (4e-7
    // of it at K = 3 − 10⁻⁹), and an offset just above the bound was designed by rounding.
    let k = need.time_ratio;
    let cot = (PI * ((3.0 - k) / (2.0 * (k + 1.0)))).tan();
    if let Some(e) = given
        && (e >= cot || slider_design(1.0, theta, e).is_none())
    {
        let k_max = time_ratio_of(e.recip().atan());
        // An offset so large that even K → 1 needs a smaller one: it is the offset to change.
        return Err(if k_max - 1.0 > 1e-9 {
            out_of_range(k_max)
        } else {
            Error::OutOfRange {
                name: "offset",
                value: e * h,
                min: 0.0,
                max: h * cot,
                ends: Ends::Open,
            }
        });
    }
    let offset_at = |t: f64| match given {
        Some(e) => Some(e),
        None => best_offset(t),
    };
    let e = offset_at(theta).ok_or(Error::Overflow {
        what: "the offset's search",
    })?;
    let (a, b, x1) = slider_design(1.0, theta, e).ok_or(Error::Overflow {
        what: "the slider-crank's dimensions",
    })?;
    if !(b / a <= MAX_LINK_RATIO) {
        let top = given.map_or(FRAC_PI_2, |e| e.recip().atan());
        let ratio = |t: f64| {
            let e = offset_at(t)?;
            slider_design(1.0, t, e).map(|(a, b, _)| b / a)
        };
        let interval = match given {
            // The best offset's ratio falls as θ grows: one bisection for the least θ.
            None => least_theta(theta, ratio).map(|lo| (lo, FRAC_PI_2, true)),
            Some(_) => None,
        }
        .or_else(|| ratio_interval(theta, top, ratio));
        let culprit = if given.is_some() { "offset" } else { "stroke" };
        return Err(link_ratio_error(
            "offset slider-crank",
            need.time_ratio,
            b / a,
            interval,
            culprit,
        ));
    }
    let (a, b, x1, e) = (a * h, b * h, x1 * h, e * h);
    for x in [a, b, x1, e] {
        positive(
            "a dimension of the slider-crank",
            crate::error::computed("a dimension of the slider-crank", x)?,
        )?;
    }
    let r1 = x1.hypot(e);
    let pin = [a * x1 / r1, a * e / r1];
    let linkage = Linkage {
        name: "synthesised offset slider-crank".to_owned(),
        joints: vec![
            Joint::revolute("O1", [0.0, 0.0]),
            Joint::revolute("A", pin),
            Joint::revolute("B", [x1, e]),
            Joint::prismatic("P", [x1, e], "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "P"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("rod", &["A", "B"]),
            Link::new("slider", &["B", "P"]),
        ],
        input: Input::crank("crank"),
        groups: vec![["rod".to_owned(), "slider".to_owned()]],
        output: Some(Output::Slide("P".to_owned())),
        ..Linkage::default()
    };
    // The report from the lengths the engine reads off the joints (crank |O1A|, rod |AB|,
    // the guide's offset B_y): the dead centres at |O1B| = b ± a on y = e, x = √(r² − e²)
    // factored as √((r − e)(r + e)) (the folded one's r − e cancels when it nears O1).
    let (o1, pa, pb) = (V::zeros(), V::new(pin[0], pin[1]), V::new(x1, e));
    let (a, b) = ((pa - o1).norm(), (pb - pa).norm());
    let inline = |r: f64| ((r - e) * (r + e)).sqrt();
    let (far, near) = (inline(a + b), inline(b - a));
    if !(near >= 0.0) {
        return Err(Error::OutOfRange {
            name: "offset",
            value: e,
            min: 0.0,
            max: h / theta.tan(),
            ends: Ends::Open,
        });
    }
    let achieved_theta = e.atan2(near) - e.atan2(far);
    let gamma = slider_gamma(a, b, e);
    let report = Report {
        kind: "offset slider-crank",
        time_ratio: Some(time_ratio_of(achieved_theta)),
        stroke: Some(far - near),
        min_transmission_angle: gamma,
        min_transmission_at: 1.5 * PI,
        grashof: None,
        dimensions: vec![
            ("crank O1A".to_owned(), a),
            ("rod AB".to_owned(), b),
            ("offset e".to_owned(), e),
        ],
    };
    crate::error::computed("the slider-crank's dimensions", a + b + far + near)?;
    require_transmission(gamma, required)?;
    check::accepted(&linkage)?;
    let kept = held::held(report.time_ratio, need.time_ratio)
        && held::held(report.stroke, need.stroke)
        && held::engine_holds(&linkage, (need.time_ratio, held::HELD), need.stroke);
    Ok((Synthesis { linkage, report }, kept))
}

/// What a [`shaper`] must do.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ShaperRequirement {
    /// H, the ram's stroke, m (> 0).
    pub stroke: f64,
    /// K, the time ratio of the ram's strokes (> 1).
    pub time_ratio: f64,
    /// The distance O1O3 between the crank's pivot and the lever's pivot below it, m (> 0).
    pub centre_distance: f64,
}

/// A shaper (quick-return mechanism with a slotted lever): the crank O1A's block slides in
/// the slotted lever pivoted at O3 below O1 (an RPR group), and a block hinged to the ram
/// slides in the same slot higher up, the ram on a horizontal guide (a PRP group).
///
/// Derivation: the lever's extreme positions are tangent to the crank circle, so the lever's
/// swing ψ satisfies sin(ψ/2) = r/d (d = O1O3, r the crank), and there the crank is
/// perpendicular to the lever: it turns π + ψ one way and π − ψ the other, so ψ = θ =
/// π(K − 1)/(K + 1) and r = d·sin(θ/2). The ram's pin on the lever's line at the height h
/// above O3 moves as x = −h·tan β (β the lever's tilt from the vertical), monotonic in β, so
/// the ram's extremes are the lever's and H = 2h·tan(θ/2): h = H/(2 tan(θ/2)). The RPR group
/// transmits at π/2; the PRP group at π/2 − |β|, least at the extremes: γ_min = π/2 − θ/2
/// (at φ = 2π − θ/2, where the working stroke begins for a crank turning counter-clockwise,
/// the ram moving to −x).
///
/// Description: O1 at the origin, O3 at (0, −d), the guide the line y = h − d; joints `O1`,
/// `A`, `P` (the crank's block in the slot), `O3`, `S` (the ram's block in the slot), `F`
/// (the ram's pin), `G` (the ram on its guide); links `frame`, `crank`, `block`, `lever` (with
/// its tip `D`), `ram block`, `ram`; output the slide of `G`. Posed with the crank straight up.
///
/// # Examples
/// A worked problem: a ram stroke of 0.3 m with K = 1.6, the lever's pivot 0.25 m below the
/// crank's. By hand, θ = ψ = 180°·0.6/2.6 = 41.538°; the crank r = 250 mm·sin 20.769° =
/// 88.65 mm; the guide h = 300 mm/(2 tan 20.769°) = 395.52 mm above O3; the lever
/// h/cos 20.769° = 423.01 mm; γ_min = 90° − 20.769° = 69.23°:
/// ```
/// use tmm::synthesis::{shaper, Options, ShaperRequirement};
/// use tmm::kinematics::Rotation;
/// use tmm::linkage::{Output, Plan};
/// let s = shaper(&ShaperRequirement { stroke: 0.3, time_ratio: 1.6, centre_distance: 0.25 }, &Options::default())?;
/// let strokes = Plan::new(&s.linkage)?.strokes(&Output::Slide("G".into()), Rotation::Ccw)?;
/// assert!((strokes.stroke - 0.3).abs() < 1e-10);
/// assert!((strokes.time_ratio - 1.6).abs() < 1e-9);
/// let r = &s.report;
/// assert!((r.dimension("crank").unwrap() - 0.088_65).abs() < 5e-6);
/// assert!((r.dimension("guide height").unwrap() - 0.395_52).abs() < 5e-6);
/// assert!((r.dimension("lever O3D").unwrap() - 0.423_01).abs() < 5e-6);
/// assert!((r.min_transmission_angle.to_degrees() - 69.23).abs() < 5e-3);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] / [`Error::NonPositive`] for the stroke or the centre distance;
/// [`Error::OutOfRange`] for K ≤ 1; [`Error::Infeasible`] for γ_min = π/2 − θ/2 below \[γ\], and
/// for a centre distance so large that the crank's circle reaches the ram's block (h ≤ d + r).
pub fn shaper(need: &ShaperRequirement, options: &Options) -> Result<Synthesis> {
    let stroke = length("stroke", need.stroke)?;
    let d = length("centre_distance", need.centre_distance)?;
    let theta = crank_excess(need.time_ratio)?;
    let required = options.check()?;
    let (s, co) = (0.5 * theta).sin_cos();
    let r = d * s;
    let h = 0.5 * stroke * co / s;
    require_transmission(FRAC_PI_2 - 0.5 * theta, required)?;
    if !(h > d + r) {
        return Err(Error::Infeasible {
            parameter: "centre distance O1O3 (m)",
            required: d,
            reachable: h / (1.0 + s),
        });
    }
    let lever = h / co;
    // The lever over the crank, H/(2·d·sin²(θ/2)): the crank is the shortest link (r < d) and
    // the lever the longest (lever > h > d + r).
    let ratio = |t: f64| Some(0.5 * stroke / (d * (0.5 * t).sin().powi(2)));
    if !(lever / r <= MAX_LINK_RATIO) {
        let interval = ratio_interval(theta, PI, ratio);
        let k = need.time_ratio;
        return Err(link_ratio_error(
            "shaper",
            k,
            lever / r,
            interval,
            "centre distance",
        ));
    }
    crate::error::computed("the shaper's dimensions", lever + h + r)?;
    // The report from the dimensions alone.
    let psi = 2.0 * (r / d).asin();
    let report = Report {
        kind: "shaper",
        time_ratio: Some(time_ratio_of(psi)),
        stroke: Some(2.0 * h * (0.5 * psi).tan()),
        min_transmission_angle: FRAC_PI_2 - 0.5 * psi,
        min_transmission_at: normalize(-0.5 * psi),
        grashof: None,
        dimensions: vec![
            ("crank O1A".to_owned(), r),
            ("centre distance O1O3".to_owned(), d),
            ("guide height above O3".to_owned(), h),
            ("lever O3D".to_owned(), lever),
            ("lever swing (rad)".to_owned(), psi),
        ],
    };
    let (o1, a, o3) = ([0.0, 0.0], [0.0, r], [0.0, -d]);
    let f = [0.0, h - d];
    let up = [0.0, 1.0];
    let linkage = Linkage {
        name: "synthesised shaper".to_owned(),
        joints: vec![
            Joint::revolute("O1", o1),
            Joint::revolute("A", a),
            Joint::prismatic("P", a, "lever", up),
            Joint::revolute("O3", o3),
            Joint::prismatic("S", f, "lever", up),
            Joint::revolute("F", f),
            Joint::prismatic("G", f, "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3", "G"]),
            Link::new("crank", &["O1", "A"]),
            Link::new("block", &["A", "P"]),
            Link::new("lever", &["O3", "P", "S"]).with_point("D", [0.0, lever - d]),
            Link::new("ram block", &["S", "F"]),
            Link::new("ram", &["F", "G"]),
        ],
        input: Input::crank("crank"),
        output: Some(Output::Slide("G".to_owned())),
        ..Linkage::default()
    };
    check::accepted(&linkage)?;
    Ok(Synthesis { linkage, report })
}
