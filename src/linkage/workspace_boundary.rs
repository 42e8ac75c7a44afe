//! The boundary of a workspace located to the last digits: where a point of the plane stops
//! being reached, decided by solving for the inputs that put the linkage's point there.
//!
//! # Whether a point is reached
//! A point X of the plane is reached when some inputs q on the workspace's input grid's range
//! (a crank's whole turn, a slider's range) assemble the linkage in its plan's mode with its
//! point P(q) = X. Newton's method on P(q) = X (its Jacobian J = ∂P/∂q is the point's
//! velocities at unit input rates, which every solve gives) decides it: started from the
//! inputs of the input-grid nodes whose images lie nearest X (and from the inputs of the
//! last point decided, when one is given), each step limited to two grid steps per input,
//! halved where the linkage does not assemble, clamped to a slider's range; X is reached
//! when |P(q) − X| falls to 10⁻¹³ of the region's span. Near the boundary the boundary is a
//! fold of the map (det J = 0: a leg stretched or folded) or the image of where the linkage
//! stops assembling: on the reached side within δ of a fold the map has two preimages about
//! √δ apart, which Newton's method reaches; on the other side its residual never falls below
//! δ. So the decision is exact down to about 10⁻¹³ of the span.
//!
//! # The boundary
//! The raster's cells within three cells of the filled raster's edge are decided again this
//! way (the fill is within a cell or so of the truth, so farther cells keep its value); then
//! marching squares over the cells' centres gives the outline's topology, and each crossing
//! between a reached centre and one that is not is bisected on the decision to 10⁻¹¹ of the
//! span. The area inside the outline is the sum of its closed polylines' areas, each counted
//! with the sign of its nesting depth (an outline inside another is a hole).

use super::contour::{contours, Grid, Node};
use nalgebra::{Point2, Vector2};
use std::collections::HashMap;

/// The input grid: each axis's first value, step and whether it wraps.
pub(crate) struct Axes {
    pub lo: [f64; 2],
    pub step: [f64; 2],
    pub grid: Grid,
}

impl Axes {
    /// The inputs at node `(i, j)`.
    pub(crate) fn q(&self, (i, j): Node) -> [f64; 2] {
        #[allow(clippy::cast_precision_loss)]
        [
            self.lo[0] + self.step[0] * i as f64,
            self.lo[1] + self.step[1] * j as f64,
        ]
    }
}

/// A raster of square cells, lower-left corner `origin`, whether each is reached (row by
/// row from the bottom).
pub(crate) struct Raster<'a> {
    pub origin: Point2<f64>,
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
    pub cells: &'a mut [bool],
}

impl Raster<'_> {
    /// The centre of cell `(ix, iy)`.
    fn centre(&self, ix: usize, iy: usize) -> Point2<f64> {
        #[allow(clippy::cast_precision_loss)]
        let c = Vector2::new(ix as f64 + 0.5, iy as f64 + 0.5) * self.cell;
        self.origin + c
    }
}

/// The point's position and its velocities at unit rate of each input, at inputs q.
pub(crate) type Jac<'a> =
    dyn FnMut([f64; 2]) -> Option<(Point2<f64>, Vector2<f64>, Vector2<f64>)> + 'a;

/// Decides whether points of the plane are reached (module docs).
pub(crate) struct Reach<'r, 'j> {
    jac: &'r mut Jac<'j>,
    axes: &'r Axes,
    /// Node images binned on squares of side `bin`: the node indices in each.
    bins: HashMap<(i64, i64), Vec<usize>>,
    bin: f64,
    /// Each node's image (`None` where it does not assemble).
    images: Vec<Option<Point2<f64>>>,
    /// The residual at which a point counts as reached, m.
    tol: f64,
}

/// The bin holding `p`.
#[allow(clippy::cast_possible_truncation)]
fn bin_of(p: Point2<f64>, bin: f64) -> (i64, i64) {
    ((p.x / bin).floor() as i64, (p.y / bin).floor() as i64)
}

impl<'r, 'j> Reach<'r, 'j> {
    /// A decider over the nodes' images `images` (indexed as the input grid's nodes), with
    /// bins of side `bin` and the region's `span`.
    pub(crate) fn new(
        jac: &'r mut Jac<'j>,
        axes: &'r Axes,
        images: Vec<Option<Point2<f64>>>,
        bin: f64,
        span: f64,
    ) -> Self {
        let mut bins: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (k, p) in images.iter().enumerate() {
            if let Some(p) = p {
                bins.entry(bin_of(*p, bin)).or_default().push(k);
            }
        }
        Self {
            jac,
            axes,
            bins,
            bin,
            images,
            tol: 1e-13 * span,
        }
    }

    /// The inputs of node `k`.
    fn node_q(&self, k: usize) -> [f64; 2] {
        let n2 = self.axes.grid.n2;
        self.axes.q((k / n2, k % n2))
    }

    /// Up to four nodes whose images lie nearest `x` (within two bins).
    fn nearest(&self, x: Point2<f64>) -> Vec<usize> {
        let (bx, by) = bin_of(x, self.bin);
        let mut near: Vec<(f64, usize)> = Vec::new();
        for i in -2..=2 {
            for j in -2..=2 {
                if let Some(ks) = self.bins.get(&(bx + i, by + j)) {
                    for &k in ks {
                        if let Some(p) = self.images[k] {
                            near.push(((p - x).norm(), k));
                        }
                    }
                }
            }
        }
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        near.into_iter().take(4).map(|(_, k)| k).collect()
    }

    /// Inputs q in the range with P(q) − x inside the tolerance, by Newton's method from `q0`.
    fn newton(&mut self, x: Point2<f64>, q0: [f64; 2]) -> Option<[f64; 2]> {
        let (mut p, mut v1, mut v2) = (self.jac)(q0)?;
        let mut q = q0;
        let mut r = (x - p).norm();
        let mut slow = 0;
        let h = self.axes.step.map(f64::abs);
        for _ in 0..40 {
            if r <= self.tol {
                return Some(q);
            }
            let det = v1.x * v2.y - v1.y * v2.x;
            if !(det.is_finite() && det != 0.0) {
                return None;
            }
            let d = x - p;
            // J·dq = d by Cramer's rule, J = [v1 v2].
            let mut dq = [
                (d.x * v2.y - d.y * v2.x) / det,
                (v1.x * d.y - v1.y * d.x) / det,
            ];
            let over = (dq[0].abs() / (2.0 * h[0])).max(dq[1].abs() / (2.0 * h[1]));
            if !over.is_finite() {
                return None;
            }
            if over > 1.0 {
                dq = dq.map(|c| c / over);
            }
            let mut t = 1.0;
            let mut next = None;
            for _ in 0..12 {
                let qn = self.clamp([q[0] + t * dq[0], q[1] + t * dq[1]]);
                if let Some(s) = (self.jac)(qn) {
                    next = Some((qn, s));
                    break;
                }
                t *= 0.5;
            }
            let (qn, (pn, a, b)) = next?;
            let rn = (x - pn).norm();
            // Converging at least linearly by ½ (a double root's rate) or giving up: beyond
            // the boundary the residual never falls below the distance to it.
            slow = if rn > 0.75 * r { slow + 1 } else { 0 };
            if slow >= 4 {
                return None;
            }
            (q, p, v1, v2, r) = (qn, pn, a, b, rn);
        }
        (r <= self.tol).then_some(q)
    }

    /// `q` clamped to a slider's (or a given) range; a crank's whole turn is not clamped.
    fn clamp(&self, q: [f64; 2]) -> [f64; 2] {
        let g = self.axes.grid;
        let mut out = q;
        for (i, wrap) in [g.wrap1, g.wrap2].into_iter().enumerate() {
            if !wrap {
                let n = if i == 0 { g.n1 } else { g.n2 };
                #[allow(clippy::cast_precision_loss)]
                let end = self.axes.lo[i] + self.axes.step[i] * (n - 1) as f64;
                let (lo, hi) = (self.axes.lo[i].min(end), self.axes.lo[i].max(end));
                out[i] = q[i].clamp(lo, hi);
            }
        }
        out
    }

    /// Whether `x` is reached; `warm` (inputs near x's preimage, if any) is tried first and
    /// updated to the preimage found.
    pub(crate) fn reaches(&mut self, x: Point2<f64>, warm: &mut Option<[f64; 2]>) -> bool {
        if let Some(q0) = *warm
            && let Some(q) = self.newton(x, q0)
        {
            *warm = Some(q);
            return true;
        }
        for k in self.nearest(x) {
            let q0 = self.node_q(k);
            if let Some(q) = self.newton(x, q0) {
                *warm = Some(q);
                return true;
            }
        }
        false
    }
}

/// The region's cells within three cells of its edge decided again by `reach`, and its
/// outline with every crossing bisected on the decision (module docs).
pub(crate) fn refine(region: &mut Raster<'_>, reach: &mut Reach<'_, '_>) -> Vec<Vec<Point2<f64>>> {
    let (nx, ny) = (region.nx, region.ny);
    let at = |ix: usize, iy: usize| iy * nx + ix;
    let filled = region.cells.to_vec();
    let edge = |ix: usize, iy: usize| {
        let c = filled[at(ix, iy)];
        (ix > 0 && filled[at(ix - 1, iy)] != c)
            || (ix + 1 < nx && filled[at(ix + 1, iy)] != c)
            || (iy > 0 && filled[at(ix, iy - 1)] != c)
            || (iy + 1 < ny && filled[at(ix, iy + 1)] != c)
    };
    let mut band = vec![false; nx * ny];
    for iy in 0..ny {
        for ix in 0..nx {
            if edge(ix, iy) {
                for jy in iy.saturating_sub(3)..(iy + 4).min(ny) {
                    for jx in ix.saturating_sub(3)..(ix + 4).min(nx) {
                        band[at(jx, jy)] = true;
                    }
                }
            }
        }
    }
    for iy in 0..ny {
        let mut warm = None;
        for ix in 0..nx {
            if band[at(ix, iy)] {
                region.cells[at(ix, iy)] = reach.reaches(region.centre(ix, iy), &mut warm);
            }
        }
    }
    let grid = Grid {
        n1: nx,
        n2: ny,
        wrap1: false,
        wrap2: false,
    };
    let mut value = vec![-1.0; nx * ny];
    for iy in 0..ny {
        for ix in 0..nx {
            if region.cells[at(ix, iy)] {
                value[grid.index((ix, iy))] = 1.0;
            }
        }
    }
    #[allow(clippy::cast_precision_loss)]
    let span = region.cell * nx.max(ny) as f64;
    let centre = |n: Node| region.centre(n.0, n.1);
    contours(grid, &value, |a, b| {
        let (a, b) = if value[grid.index(a)] > 0.0 {
            (a, b)
        } else {
            (b, a)
        };
        let (mut inside, mut outside) = (centre(a), centre(b));
        let mut warm = None;
        if !reach.reaches(inside, &mut warm) {
            // Decided once already: only a pole of the map can make the second decision
            // differ; the midpoint marks the edge then.
            return Some(Point2::from((inside.coords + outside.coords) / 2.0));
        }
        while (outside - inside).norm() > 1e-11 * span {
            let mid = Point2::from((inside.coords + outside.coords) / 2.0);
            if mid == inside || mid == outside {
                break;
            }
            let mut w = warm;
            if reach.reaches(mid, &mut w) {
                inside = mid;
                warm = w;
            } else {
                outside = mid;
            }
        }
        Some(Point2::from((inside.coords + outside.coords) / 2.0))
    })
}

/// The area of a closed polyline (the shoelace formula), signed (counter-clockwise
/// positive).
fn signed_area(l: &[Point2<f64>]) -> f64 {
    l.windows(2)
        .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
        .sum::<f64>()
        / 2.0
}

/// Whether `p` lies inside the closed polyline `l` (the even–odd rule).
fn inside(p: Point2<f64>, l: &[Point2<f64>]) -> bool {
    let mut c = false;
    for w in l.windows(2) {
        let (a, b) = (w[0], w[1]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                c = !c;
            }
        }
    }
    c
}

/// The area inside closed outlines: each one's area, added at an even nesting depth and
/// taken away at an odd one (a hole).
pub(crate) fn area_inside(lines: &[Vec<Point2<f64>>]) -> f64 {
    lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.len() >= 4 && l.first() == l.last())
        .map(|(i, l)| {
            let depth = lines
                .iter()
                .enumerate()
                .filter(|&(j, m)| j != i && m.len() >= 4 && inside(l[0], m))
                .count();
            let a = signed_area(l).abs();
            if depth % 2 == 0 {
                a
            } else {
                -a
            }
        })
        .sum()
}
