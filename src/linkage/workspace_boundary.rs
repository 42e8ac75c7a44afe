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
//! Marching squares over the filled raster's cells gives the outline's topology (the fill is
//! within about a cell of the truth; its cells are kept as they are); each crossing between
//! a filled centre and an empty one is then moved onto the edge of the reach: the pair's ends
//! are moved along their line until one is decided reached and the other not (up to 1.5
//! cells either way), and the crossing is bisected on the decision to 10⁻¹¹ of the span. So
//! the outline's points lie on the edge of the reach to the decision's accuracy, and the area
//! inside it ([`area_inside`]: the sum of its closed polylines' areas, each counted with the
//! sign of its nesting depth, an outline inside another being a hole) differs from the
//! reach's by the chords between points a cell apart: for a boundary of radius of curvature
//! ρ, a chord of length c cuts off c³/(12ρ) of area, so the area's error is about
//! (perimeter)·c²/(12ρ), of order (cell/ρ)² of the area — 10⁻⁵ at 240 cells across.

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
    pub cells: &'a [bool],
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

    /// Up to eight nodes whose images lie nearest `x` (within two bins).
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
        near.into_iter().take(8).map(|(_, k)| k).collect()
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

/// The region's outline with every crossing located on the edge of the reach (module docs).
/// The raster's cells are left as the fill made them; only the outline's points move.
pub(crate) fn refine(region: &Raster<'_>, reach: &mut Reach<'_, '_>) -> Vec<Vec<Point2<f64>>> {
    let (nx, ny) = (region.nx, region.ny);
    let grid = Grid {
        n1: nx,
        n2: ny,
        wrap1: false,
        wrap2: false,
    };
    let mut value = vec![-1.0; nx * ny];
    for iy in 0..ny {
        for ix in 0..nx {
            if region.cells[iy * nx + ix] {
                value[grid.index((ix, iy))] = 1.0;
            }
        }
    }
    let centre = |n: Node| region.centre(n.0, n.1);
    // An empty cell next to a filled one whose centre is decided reached is reached (that
    // decision is certain): the outline goes round it, up to GROW cells out. This closes the
    // holes the fill leaves where it gives a cell up (near a pole of the map) and its
    // shortfalls; a filled cell is never emptied (a decision "not reached" may miss a
    // preimage).
    for _ in 0..GROW {
        let mut grown = Vec::new();
        for iy in 0..ny {
            for ix in 0..nx {
                let k = grid.index((ix, iy));
                let next = [
                    (ix > 0).then(|| (ix - 1, iy)),
                    (ix + 1 < nx).then_some((ix + 1, iy)),
                    (iy > 0).then(|| (ix, iy - 1)),
                    (iy + 1 < ny).then_some((ix, iy + 1)),
                ];
                if value[k] < 0.0
                    && next.iter().flatten().any(|&n| value[grid.index(n)] > 0.0)
                    && reach.reaches(centre((ix, iy)), &mut None)
                {
                    grown.push(k);
                }
            }
        }
        if grown.is_empty() {
            break;
        }
        for k in grown {
            value[k] = 1.0;
        }
    }
    #[allow(clippy::cast_precision_loss)]
    let span = region.cell * nx.max(ny) as f64;
    contours(grid, &value, |a, b| {
        let (a, b) = if value[grid.index(a)] > 0.0 {
            (a, b)
        } else {
            (b, a)
        };
        Some(crossing(centre(a), centre(b), reach, span))
    })
}

/// Where the reach ends on the line from `inside` (a filled cell's centre) to `outside` (an
/// empty one's, a cell away): the fill is within about a cell of the truth, so the end is
/// looked for up to [`WALK`] cells on either side of the pair. A reached point is certain
/// (its preimage is found to the tolerance); so the pair's ends are first moved, in half-cell
/// steps along the line, until `inside` is reached and `outside` is not, then the crossing is
/// bisected between them to 10⁻¹¹ of the span. Where no reached point is found, the midpoint
/// of the pair stays (the fill's own outline).
fn crossing(
    inside: Point2<f64>,
    outside: Point2<f64>,
    reach: &mut Reach<'_, '_>,
    span: f64,
) -> Point2<f64> {
    let step = (outside - inside) / 2.0;
    let mid = Point2::from((inside.coords + outside.coords) / 2.0);
    let mut warm = None;
    #[allow(clippy::cast_precision_loss)]
    let halves = (2.0 * WALK) as i32;
    // The reached end: the pair's inside, or a point up to WALK cells deeper.
    let Some(mut a) = (0..=halves)
        .map(|k| inside - step * f64::from(k))
        .find(|&p| reach.reaches(p, &mut warm))
    else {
        return mid;
    };
    // The end not reached: the pair's outside, or a point up to WALK cells farther out.
    let mut b = outside;
    for k in 1..=halves {
        let mut w = warm;
        if !reach.reaches(b, &mut w) {
            break;
        }
        (a, warm) = (b, w);
        b = outside + step * f64::from(k);
        if k == halves && reach.reaches(b, &mut None) {
            // Reached all the way out: no edge near this pair; the fill's outline stays.
            return mid;
        }
    }
    while (b - a).norm() > 1e-11 * span {
        let m = Point2::from((a.coords + b.coords) / 2.0);
        if m == a || m == b {
            break;
        }
        let mut w = warm;
        if reach.reaches(m, &mut w) {
            a = m;
            warm = w;
        } else {
            b = m;
        }
    }
    Point2::from((a.coords + b.coords) / 2.0)
}

/// How far past a pair of cells the end of the reach is looked for, in cells: the fill marks
/// a cell whose centre lies within a quarter cell of an input cell's image, and an image is
/// the polygon of its corners' images (within a quarter cell of the true image where the map
/// is split), so its outline lies within about a cell of the true one.
const WALK: f64 = 1.5;

/// How many layers of empty cells round the filled ones are decided (see [`refine`]).
const GROW: usize = 3;

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
