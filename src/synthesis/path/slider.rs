//! The offset slider-crank of path generation: its positions from the search's genes, and
//! the design (description and report) of a polished candidate.
//!
//! Genes (normalised units, as [`Problem`]'s): the crank's pivot O1 = (g0, g1), the guide's
//! direction α = g2, its signed offset e = g3 (the guide is the line of the points X with
//! (X − O1)·n = e, n = (−sin α, cos α) the direction's left normal), the crank r = g4, the
//! rod l = g5 (g6 unused), the coupler point (along, across) = (g7, g8) on the rod A→B, the
//! mode σ = the sign of g9 (the slider ahead of the crank pin along the guide for σ > 0).

use super::angles::normalize_angle;
use super::results::PathDesign;
use super::V;
use crate::error::Result;
use crate::kinematics::batch::{coupler_point, CrankAngles, Lane, Positions};
use crate::linkage::{Input, Joint, Link, Linkage, NamedPoint, Output};
use crate::synthesis::{check, time_ratio_of, Report, Synthesis};
use nalgebra::Point2;
use std::f64::consts::{FRAC_PI_2, TAU};

/// One offset slider-crank.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slider {
    o: V,
    /// The guide's direction and its left normal.
    u: V,
    n: V,
    alpha: f64,
    e: f64,
    r: f64,
    l: f64,
    uv: [f64; 2],
    sigma: f64,
}

impl Slider {
    pub(super) fn of(g: &[f64], sigma: f64) -> Self {
        let (s, c) = g[2].sin_cos();
        Self {
            o: V::new(g[0], g[1]),
            u: V::new(c, s),
            n: V::new(-s, c),
            alpha: g[2],
            e: g[3],
            r: g[4],
            l: g[5],
            uv: [g[7] / g[5], g[8] / g[5]],
            sigma: if sigma > 0.0 { 1.0 } else { -1.0 },
        }
    }

    /// A, B, P and sin γ with the crank at the angle whose cosine and sine are `c`, `s`; the
    /// gap |h| − l (`Err`) where the rod cannot reach the guide.
    ///
    /// Why: the crank pin A = O1 + r(cos φ, sin φ) lies h = (A − O1)·n − e from the guide;
    /// the point of the guide at the distance l from A is B = A − h·n + σ√(l² − h²)·u. The
    /// rod leans by β from the guide, sin β = |h|/l, and the transmission angle (between the
    /// rod and the slider's normal) is γ = π/2 − β: sin γ = √(l² − h²)/l, zero at a dead
    /// point.
    pub(super) fn at(&self, c: f64, s: f64) -> std::result::Result<(V, V, V, f64), f64> {
        let a = self.o + self.r * V::new(c, s);
        let h = (a - self.o).dot(&self.n) - self.e;
        let root2 = (self.l - h) * (self.l + h);
        if root2.is_nan() || root2 < 0.0 {
            return Err((h.abs() - self.l).max(0.0));
        }
        let root = root2.sqrt();
        let b = a - h * self.n + self.sigma * root * self.u;
        let p = coupler_point(Point2::from(a), Point2::from(b), self.uv).coords;
        Ok((a, b, p, root / self.l))
    }

    /// The batch: a lane a crank angle, `Ok` with sin γ as its measure, `NotAssemblable`
    /// with the gap, `Invalid` for non-finite results.
    pub(super) fn positions(&self, angles: &CrankAngles, out: &mut Positions) {
        let (cos, sin) = (angles.cos(), angles.sin());
        for i in 0..angles.len() {
            let (status, measure, b, p) = match self.at(cos[i], sin[i]) {
                Ok((_, b, p, m)) if (p.x + p.y + b.x + b.y + m).is_finite() => (Lane::Ok, m, b, p),
                Ok(_) => (Lane::Invalid, f64::NAN, V::zeros(), V::zeros()),
                Err(gap) => (Lane::NotAssemblable, gap, V::zeros(), V::zeros()),
            };
            out.status[i] = status;
            out.measure[i] = measure;
            out.b_x[i] = b.x;
            out.b_y[i] = b.y;
            out.p_x[i] = p.x;
            out.p_y[i] = p.y;
        }
    }

    /// The smallest transmission angle over the crank's arc (`start`, `span`) and the crank
    /// angle where it occurs: where |h| = |r sin(φ − α) − e| is largest, at an end of the arc
    /// or where sin(φ − α) = ±1 inside it.
    fn gamma_over(&self, start: f64, span: f64) -> (f64, f64) {
        let h = |phi: f64| (self.r * (phi - self.alpha).sin() - self.e).abs();
        let mut worst = (h(start), start);
        let inside = [self.alpha + FRAC_PI_2, self.alpha - FRAC_PI_2]
            .map(|phi| start + (phi - start).rem_euclid(TAU))
            .into_iter()
            .filter(|&phi| phi - start <= span);
        for phi in inside.chain([start + span]) {
            if h(phi) > worst.0 {
                worst = (h(phi), phi);
            }
        }
        (
            (worst.0 / self.l).clamp(-1.0, 1.0).acos().min(FRAC_PI_2),
            normalize_angle(worst.1).rem_euclid(TAU),
        )
    }

    /// The slider's stroke and K when the crank turns fully (r + |e| < l): at the dead
    /// centres the pin is at √((l ± r)² − e²) along the guide from O1's foot, and the crank
    /// angles there differ by π ± θ with θ = |atan(e/near) − atan(e/far)|.
    fn strokes(&self) -> Option<(f64, f64)> {
        let (r, l, e) = (self.r, self.l, self.e);
        if r + e.abs() >= l {
            return None;
        }
        let far = ((l + r) * (l + r) - e * e).sqrt();
        let near = ((l - r) * (l - r) - e * e).sqrt();
        let theta = ((e / near).atan() - (e / far).atan()).abs();
        Some((far - near, time_ratio_of(theta)))
    }
}

/// The design in the world of the genes `g` (world units, mode `sigma`) with the crank at
/// `phis` at the `targets` over the arc (`start`, `span`): the description posed at the first
/// point's crank angle, its report and its misses; `None` where it does not assemble at a
/// target.
pub(super) fn design(
    g: &[f64],
    sigma: f64,
    phis: &[f64],
    targets: &[V],
    (start, span): (f64, f64),
) -> Result<Option<PathDesign>> {
    let s = Slider::of(g, sigma);
    let n = phis.len();
    let mut poses = Vec::with_capacity(n);
    let (mut sum, mut max) = (0.0, 0.0f64);
    for (&phi, t) in phis.iter().zip(targets) {
        let Ok(pose) = s.at(phi.cos(), phi.sin()) else {
            return Ok(None);
        };
        let miss = (pose.2 - t).norm();
        sum += miss;
        max = max.max(miss);
        poses.push(pose);
    }
    let (gamma, at) = s.gamma_over(start, span);
    let strokes = s.strokes();
    let report = Report {
        kind: "offset slider-crank path generator",
        time_ratio: strokes.map(|(_, k)| k),
        stroke: strokes.map(|(h, _)| h),
        min_transmission_angle: gamma,
        min_transmission_at: at,
        grashof: None,
        dimensions: vec![
            ("crank O1A".to_owned(), s.r),
            ("rod AB".to_owned(), s.l),
            ("offset e of the guide from O1".to_owned(), s.e),
            (
                "guide direction (rad)".to_owned(),
                normalize_angle(s.alpha).rem_euclid(TAU),
            ),
            ("coupler point along AB".to_owned(), g[7]),
            ("coupler point across AB".to_owned(), g[8]),
        ],
    };
    let xy = |v: V| [v.x, v.y];
    let (a, b, p, _) = poses[0];
    let mut rod = Link::new("rod", &["A", "B"]);
    rod.points = vec![NamedPoint {
        name: "P".to_owned(),
        at: xy(p),
    }];
    let linkage = Linkage {
        name: "synthesised slider-crank path generator".to_owned(),
        joints: vec![
            Joint::revolute("O1", xy(s.o)),
            Joint::revolute("A", xy(a)),
            Joint::revolute("B", xy(b)),
            Joint::prismatic("S", xy(b), "frame", xy(s.u)),
        ],
        links: vec![
            Link::new("frame", &["O1", "S"]),
            Link::new("crank", &["O1", "A"]),
            rod,
            Link::new("slider", &["B", "S"]),
        ],
        input: Input::crank("crank"),
        groups: vec![["rod".to_owned(), "slider".to_owned()]],
        output: Some(Output::Slide("S".to_owned())),
        ..Linkage::default()
    };
    // The engine refuses what it cannot check (a joint beyond its range): no design then.
    if check::accepted(&linkage).is_err() {
        return Ok(None);
    }
    Ok(Some(PathDesign {
        synthesis: Synthesis { linkage, report },
        mean_error: sum / n as f64,
        max_error: max,
        crank_angles: phis.to_vec(),
        coupler_points: poses.iter().map(|q| xy(q.2)).collect(),
    }))
}
