//! The refusal of bad requirements and options, naming the parameter, before any search.

use super::angles::min_max;
use super::requirement::{PathOptions, PathRequirement, Timing};
use super::{Kind, MAX_POINTS, MAX_POPULATION, V};
use crate::error::{Error, Result};
use crate::synthesis::MAX_LINK_RATIO;
use std::f64::consts::TAU;

/// Refuses a bad requirement or option of the synthesis of `kind`, naming the parameter;
/// returns \[γ\].
pub(super) fn check_requirement(
    kind: Kind,
    req: &PathRequirement,
    opts: &PathOptions,
) -> Result<f64> {
    let gamma = opts.options.check()?;
    for p in &req.points {
        crate::error::finite("points", p[0])?;
        crate::error::finite("points", p[1])?;
    }
    let n = req.points.len();
    if n > MAX_POINTS {
        return Err(Error::OutOfRange {
            name: "points",
            value: n as f64,
            min: 0.0,
            max: MAX_POINTS as f64,
            ends: crate::Ends::Closed,
        });
    }
    // The unknowns without timing: a four-bar's nine dimensions, a slider-crank's eight
    // (O1, the guide's direction and offset, crank, rod, the coupler point), and an angle a
    // point, two equations a point.
    let free = match kind {
        Kind::FourBar => 9,
        Kind::SliderCrank => 8,
    };
    check_timing(req, free)?;
    let (pts, centre, size) = normalised(&req.points);
    // The engine squares lengths and coordinates: a path too large (or too small) for that
    // is no path of `f64` four-bars. A size of 0 is coinciding points, named below.
    let far = pts.iter().map(|p| p.norm()).fold(0.0, f64::max);
    if !(far * far).is_finite() {
        return Err(Error::Overflow {
            what: "points (their coordinates or the path's size)",
        });
    }
    if size > 0.0 && size * size < f64::MIN_POSITIVE {
        return Err(Error::NoMechanism {
            method: "path generation",
            problem: format!(
                "the path's size {size:e} m underflows: its square is below the smallest \
                 normal f64 ({:e}); give the points in a smaller unit",
                f64::MIN_POSITIVE
            ),
        });
    }
    for i in 0..n {
        for j in 0..i {
            if (pts[i] - pts[j]).norm() <= 1e-9 * size {
                return Err(Error::NoMechanism {
                    method: "path generation",
                    problem: format!("points {} and {} coincide", j + 1, i + 1),
                });
            }
        }
    }
    // Far from the origin, f64 cannot hold the points (nor the design's pivots) to the
    // tolerance: the misses reported would be rounding, not the design's.
    let resolution = centre.norm() * f64::EPSILON;
    if resolution > opts.tolerance.max(1e-12) * size {
        return Err(Error::NoMechanism {
            method: "path generation",
            problem: format!(
                "the points' centroid is {:e} m from the origin, {:.3e} path sizes: f64 \
                 resolves {resolution:.3e} m there, more than the tolerance ({:e} of the path's \
                 size {size:.3e} m); give the points in coordinates with the origin near them",
                centre.norm(),
                centre.norm() / size,
                opts.tolerance,
            ),
        });
    }
    check_options(opts)?;
    Ok(gamma)
}

/// The timing of `req`: one finite angle a point spanning less than a turn, no two distinct
/// points at one angle, and at least the points the unknowns need (`free` without timing).
fn check_timing(req: &PathRequirement, free: usize) -> Result<()> {
    let n = req.points.len();
    let (min, name) = match &req.timing {
        Timing::Free | Timing::ClosedCurve => (free, "points"),
        Timing::Prescribed(d) => {
            for &x in d {
                // Beyond ±10⁹ rad an angle no longer names one crank position (the design
                // would be re-posed at another crank angle than the one searched).
                crate::linkage::inputs::check_input_coordinate("timing", x)?;
            }
            if d.len() != n {
                return Err(Error::OutOfRange {
                    name: "timing (one crank angle per point)",
                    value: d.len() as f64,
                    min: n as f64,
                    max: n as f64,
                    ends: crate::Ends::Closed,
                });
            }
            let (mn, mx) = min_max(d);
            if mx - mn >= TAU {
                return Err(Error::OutOfRange {
                    name: "timing (span of the crank angles, rad)",
                    value: mx - mn,
                    min: 0.0,
                    max: TAU,
                    ends: crate::Ends::OpenAbove,
                });
            }
            // Two distinct points at one crank angle: no linkage's tracer is at two places
            // at once, and the search would only split the difference.
            let ends = (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j)));
            if let Some((i, j)) = ends
                .into_iter()
                .find(|&(i, j)| d[i] == d[j] && req.points[i] != req.points[j])
            {
                return Err(Error::Description {
                    item: "timing".to_owned(),
                    problem: format!(
                        "points {} and {} are at one crank angle {} rad but at distinct places: \
                         give each point its own crank angle",
                        i + 1,
                        j + 1,
                        d[i]
                    ),
                });
            }
            (5, "points")
        }
    };
    if n < min {
        return Err(Error::OutOfRange {
            name,
            value: n as f64,
            min: min as f64,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    Ok(())
}

/// The search's options: bounds, counts and budgets.
fn check_options(opts: &PathOptions) -> Result<()> {
    // A ratio above the synthesis' bound could not be checked by the engine to 1e-10.
    for (name, v, lo, hi) in [
        ("max_link_ratio", opts.max_link_ratio, 1.0, MAX_LINK_RATIO),
        ("max_size", opts.max_size, 0.0, f64::INFINITY),
    ] {
        if v.is_nan() || v <= lo || v > hi || !v.is_finite() {
            return Err(Error::OutOfRange {
                name,
                value: v,
                min: lo,
                max: hi,
                ends: if hi.is_finite() {
                    crate::Ends::OpenBelow
                } else {
                    crate::Ends::Open
                },
            });
        }
    }
    if opts.designs == 0 {
        return Err(Error::OutOfRange {
            name: "designs",
            value: 0.0,
            min: 1.0,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    for (name, v) in [
        ("population", opts.population),
        ("positions", opts.positions),
    ] {
        if !(8..=MAX_POPULATION).contains(&v) {
            return Err(Error::OutOfRange {
                name,
                value: v as f64,
                min: 8.0,
                max: MAX_POPULATION as f64,
                ends: crate::Ends::Closed,
            });
        }
    }
    if !(opts.tolerance >= 0.0 && opts.tolerance.is_finite()) {
        return Err(Error::OutOfRange {
            name: "tolerance",
            value: opts.tolerance,
            min: 0.0,
            max: f64::INFINITY,
            ends: crate::Ends::OpenAbove,
        });
    }
    // The first population and one generation.
    let least = 2 * opts.population;
    if opts.max_evaluations < least {
        return Err(Error::OutOfRange {
            name: "max_evaluations (at least twice the population)",
            value: opts.max_evaluations as f64,
            min: least as f64,
            max: f64::INFINITY,
            ends: crate::Ends::Closed,
        });
    }
    if opts.max_time.is_zero() {
        return Err(Error::OutOfRange {
            name: "max_time",
            value: 0.0,
            min: 0.0,
            max: f64::INFINITY,
            ends: crate::Ends::OpenBelow,
        });
    }
    Ok(())
}

/// The points as vectors, their centroid and the path's size (the largest distance of a
/// point from the centroid), computed so that no sum overflows where the points do not.
pub(super) fn normalised(points: &[[f64; 2]]) -> (Vec<V>, V, f64) {
    let pts: Vec<V> = points.iter().map(|p| V::new(p[0], p[1])).collect();
    let n = pts.len().max(1) as f64;
    let c = pts.iter().map(|p| p / n).sum::<V>();
    let size = pts
        .iter()
        .map(|p| (p.x - c.x).hypot(p.y - c.y))
        .fold(0.0, f64::max);
    (pts, c, size)
}
