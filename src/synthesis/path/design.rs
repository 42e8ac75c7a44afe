//! The designs a search finds: a polished candidate checked whole, placed in the world and
//! described, and the distinct best kept.

use super::angles::{min_max, normalize_angle, ordered_arc};
use super::problem::{dims_of, gene_vec, point_at, Problem};
use super::requirement::Timing;
use super::results::PathDesign;
use super::{slider, Kind, V};
use crate::error::Result;
use crate::linkage::NamedPoint;
use crate::synthesis::four_bar::FourBar;
use crate::synthesis::Synthesis;
use nalgebra::Point2;
use std::f64::consts::TAU;
use std::time::Instant;

/// The designs found so far, with what places them in the world.
pub(super) struct Found {
    pub(super) designs: Vec<PathDesign>,
    /// Each design's sorted link lengths (normalised), to tell designs apart.
    pub(super) keys: Vec<[f64; 4]>,
    pub(super) start: Instant,
    pub(super) centre: V,
    pub(super) scale: f64,
}

impl Found {
    /// How many designs meet the points to `tolerance` path sizes.
    pub(super) fn good(&self, tolerance: f64) -> usize {
        self.designs
            .iter()
            .filter(|d| d.mean_error <= tolerance * self.scale)
            .count()
    }

    /// Polishes the genes `g` with the crank angles `phis` at the targets (Levenberg–Marquardt,
    /// `iterations`), and keeps the design when it passes the whole check (and, if
    /// `only_good`, meets the points to `tolerance`); of two designs with the same links
    /// (to 1e-4), the better one.
    pub(super) fn adopt(
        &mut self,
        pb: &mut Problem,
        g: &[f64],
        phis: &[f64],
        iterations: usize,
        tolerance: f64,
        only_good: bool,
    ) -> Result<()> {
        let sigma = if g[9] > 0.0 { 1.0 } else { -1.0 };
        let mut x0 = g[..9].to_vec();
        x0.extend_from_slice(phis);
        let x = pb.polish_free(x0.clone(), sigma, iterations);
        // Levenberg–Marquardt keeps the link ratio only: where it steps out of the
        // constraints (γ, assembly, order), the unpolished start, which met them in the
        // search, is the design (no search that found a feasible candidate ends empty).
        let x = if pb.feasible(&x, sigma) {
            x
        } else if !only_good && pb.feasible(&x0, sigma) {
            x0
        } else {
            return Ok(());
        };
        let Some(design) = design_of(pb, &x, sigma, self.centre, self.scale)? else {
            return Ok(());
        };
        if only_good && design.mean_error > tolerance * self.scale {
            return Ok(());
        }
        let key = {
            let mut l = [x[3], x[4], x[5], x[6]];
            l.sort_by(f64::total_cmp);
            l
        };
        let same = self.keys.iter().position(|k| {
            k.iter()
                .zip(&key)
                .all(|(a, b)| (a - b).abs() <= 1e-4 * b.abs())
        });
        match same {
            Some(i) if self.designs[i].mean_error <= design.mean_error => {}
            Some(i) => {
                self.designs[i] = design;
                self.keys[i] = key;
            }
            None => {
                self.designs.push(design);
                self.keys.push(key);
            }
        }
        Ok(())
    }
}

/// The design in the world: the description posed at the first point's crank angle.
pub(super) fn design_of(
    pb: &Problem,
    x: &[f64],
    sigma: f64,
    centre: V,
    scale: f64,
) -> Result<Option<PathDesign>> {
    let n = pb.targets.len();
    let phis: Vec<f64> = (0..n).map(|i| normalize_angle(pb.angle_of(x, i))).collect();
    let targets: Vec<V> = pb.targets.iter().map(|t| t * scale + centre).collect();
    // The crank's arc over the points: a turn, the prescribed range, or the arc swept in
    // their order.
    let (start, span) = match &pb.timing {
        Timing::ClosedCurve => (0.0, TAU),
        Timing::Prescribed(_) => {
            let (mn, mx) = min_max(&(0..n).map(|i| pb.angle_of(x, i)).collect::<Vec<_>>());
            (mn, mx - mn)
        }
        Timing::Free => ordered_arc(&phis).unwrap_or((0.0, 0.0)),
    };
    let mut g = gene_vec(x, sigma);
    if pb.kind == Kind::SliderCrank {
        g[0] = centre.x + g[0] * scale;
        g[1] = centre.y + g[1] * scale;
        for k in [3, 4, 5, 7, 8] {
            g[k] *= scale;
        }
        return slider::design(&g, sigma, &phis, &targets, (start, span));
    }
    let mut d = dims_of(&g, sigma);
    d.o = Point2::from(centre + d.o.coords * scale);
    d.c = Point2::from(centre + d.c.coords * scale);
    d.l_oa *= scale;
    d.l_ab *= scale;
    d.l_cb *= scale;
    d.coupler *= scale;
    let mut points = Vec::with_capacity(n);
    let (mut sum, mut max) = (0.0, 0.0f64);
    for (&phi, t) in phis.iter().zip(&targets) {
        let Some((p, _)) = point_at(&d, phi) else {
            return Ok(None);
        };
        let miss = (p - t).norm();
        sum += miss;
        max = max.max(miss);
        points.push([p.x, p.y]);
    }
    let delta = normalize_angle(x[2]);
    let fb = FourBar {
        o1: d.o.coords,
        delta,
        d: g[3] * scale,
        a: d.l_oa,
        b: d.l_ab,
        c: d.l_cb,
        sigma,
    };
    let mut report = fb.report(
        "path generator",
        // A turn is given as just under one (the report's arc is half-open).
        Some((normalize_angle(start - delta), span.clamp(1e-9, TAU - 1e-9))),
    )?;
    report
        .dimensions
        .push(("coupler point along AB".to_owned(), d.coupler.x));
    report
        .dimensions
        .push(("coupler point across AB".to_owned(), d.coupler.y));
    let reference = phis[0];
    let linkage = fb.linkage(
        "path generator",
        normalize_angle(reference - delta),
        vec![NamedPoint {
            name: "P".to_owned(),
            at: points[0],
        }],
        None,
    )?;
    Ok(Some(PathDesign {
        synthesis: Synthesis { linkage, report },
        mean_error: sum / n as f64,
        max_error: max,
        crank_angles: phis,
        coupler_points: points,
    }))
}
