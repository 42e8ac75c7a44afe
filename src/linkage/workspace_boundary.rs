//! The boundary of a workspace located to the last digits: where a point of the plane stops
//! being reached, decided by solving for the inputs that put the linkage's point there
//! (module `workspace_reach`).
//!
//! # The boundary
//! The fill of the region (the images of the input grid's cells on a raster) lies within
//! about a cell of the truth: it marks a cell whose centre lies within a quarter cell of an
//! input cell's image, and an image is the polygon of its corners' images (within a quarter
//! cell of the true image where the map is split). So every cell within [`BAND`] cells of
//! the fill's outline has its centre decided (reached or not), each from its decided
//! neighbours' preimages first; a decided cell next to a reached one that the fill left out
//! is reached, and the band grows round it ([`GROW`] layers at most: a fill's shortfall or a
//! hole it leaves near a pole of the map). The outline is then the decided raster's by
//! marching squares, and each of its crossings lies between a centre decided reached (its
//! preimage known) and a neighbour decided not: it is bisected on the decision, each midpoint
//! tried from the last reached preimage, to 10⁻¹¹ of the span. So every outline point lies
//! on the edge of the reach to the decision's accuracy (10⁻¹³ of the span at a fold; √ε·L
//! next to the image of a pole, module `workspace_reach`), holes included, wherever the fill
//! is within [`BAND`] cells of the truth; a crossing whose reached side is not decided (the
//! fill's cell beyond the band) keeps the fill's own point, the pair's midpoint. Features
//! narrower than a cell between two centres (the tip of a cusp) are cut at the last centre
//! reached, on the edge still.
//!
//! The area inside the outline ([`area_inside`]: the sum of its closed polylines' areas, each
//! counted with the sign of its nesting depth, an outline inside another being a hole)
//! differs from the reach's by the chords between points a cell apart: for a boundary of
//! radius of curvature ρ, a chord of length c cuts off c³/(12ρ) of area, so the area's error
//! is about (perimeter)·c²/(12ρ), of order (cell/ρ)² of the area — 10⁻⁵ at 240 cells across —
//! plus the cut cusps' tips (a cusp of width k·y² below the height where it is a cell wide,
//! y₁ = √(cell/k), holds k·y₁³/3 = cell·y₁/3: a few cells).

use super::contour::{contours, Grid, Node};
use super::workspace_reach::Reach;
use nalgebra::{Point2, Vector2};

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

/// Each raster cell's decision: not yet decided, not reached, or reached with its preimage.
#[derive(Clone, Copy, PartialEq)]
enum Decided {
    Open,
    Out,
    In([f64; 2]),
}

/// The 8 neighbours of cell `(ix, iy)` on an `nx` × `ny` raster.
fn neighbours(ix: usize, iy: usize, nx: usize, ny: usize) -> impl Iterator<Item = (usize, usize)> {
    (-1i64..=1)
        .flat_map(|i| (-1i64..=1).map(move |j| (i, j)))
        .filter(|&d| d != (0, 0))
        .filter_map(move |(i, j)| {
            let x = usize::try_from(i64::try_from(ix).ok()? + i).ok()?;
            let y = usize::try_from(i64::try_from(iy).ok()? + j).ok()?;
            (x < nx && y < ny).then_some((x, y))
        })
}

/// The region's outline with every crossing located on the edge of the reach, and the
/// raster's cells it goes round (the fill's, with the decided cells' decisions; module docs).
pub(crate) fn refine(
    region: &Raster<'_>,
    reach: &mut Reach<'_, '_>,
) -> (Vec<Vec<Point2<f64>>>, Vec<bool>) {
    let (nx, ny) = (region.nx, region.ny);
    let grid = Grid {
        n1: nx,
        n2: ny,
        wrap1: false,
        wrap2: false,
    };
    let at = |(ix, iy): Node| grid.index((ix, iy));
    let filled = |n: Node| region.cells[n.1 * nx + n.0];
    let centre = |n: Node| region.centre(n.0, n.1);
    // The fill's outline cells (a 4-neighbour differs), then the band round them.
    let mut distance = vec![usize::MAX; nx * ny];
    let mut layer: Vec<Node> = Vec::new();
    for iy in 0..ny {
        for ix in 0..nx {
            let four = [
                (ix > 0).then(|| (ix - 1, iy)),
                (ix + 1 < nx).then_some((ix + 1, iy)),
                (iy > 0).then(|| (ix, iy - 1)),
                (iy + 1 < ny).then_some((ix, iy + 1)),
            ];
            if four
                .iter()
                .flatten()
                .any(|&n| filled(n) != filled((ix, iy)))
            {
                distance[at((ix, iy))] = 0;
                layer.push((ix, iy));
            }
        }
    }
    let mut band = layer.clone();
    for d in 1..=BAND {
        let mut next = Vec::new();
        for &(ix, iy) in &layer {
            for n in neighbours(ix, iy, nx, ny) {
                if distance[at(n)] == usize::MAX {
                    distance[at(n)] = d;
                    next.push(n);
                }
            }
        }
        band.extend_from_slice(&next);
        layer = next;
    }
    // Decide the band, row by row, each cell from its reached neighbours' preimages first.
    band.sort_by_key(|&(ix, iy)| (iy, ix));
    let mut decided = vec![Decided::Open; nx * ny];
    let decide = |n: Node, decided: &mut [Decided], reach: &mut Reach<'_, '_>| {
        let warm: Vec<[f64; 2]> = neighbours(n.0, n.1, nx, ny)
            .filter_map(|m| match decided[at(m)] {
                Decided::In(q) => Some(q),
                _ => None,
            })
            .collect();
        decided[at(n)] = match reach.reaches(centre(n), &warm) {
            Some(q) => Decided::In(q),
            None => Decided::Out,
        };
    };
    for &n in &band {
        decide(n, &mut decided, reach);
    }
    // Each cell newly reached is a start for its neighbours: one decided not reached is
    // tried again from its preimage (a missed preimage would put a notch in the outline),
    // and one not decided yet past the band (the fill's shortfall, up to GROW cells past the
    // band) is decided; until no cell changes. A cell is tried again at most once per
    // neighbour reached.
    // A cell whose centre is not reached but which holds a node's image (a reached point:
    // a feature thinner than a cell, the tip of a cusp) is reached, that image standing for
    // its centre in the crossings.
    let mut stand_in: Vec<Option<Point2<f64>>> = vec![None; nx * ny];
    for (p, q) in reach.known() {
        let u = (p - region.origin) / region.cell;
        #[allow(clippy::cast_precision_loss)]
        if !(u.x >= 0.0 && u.y >= 0.0 && u.x < nx as f64 && u.y < ny as f64) {
            continue;
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = (u.x as usize, u.y as usize);
        if decided[at(n)] == Decided::Out {
            decided[at(n)] = Decided::In(q);
            stand_in[at(n)] = Some(p);
            band.push(n);
        }
    }
    let mut depth = vec![usize::MAX; nx * ny];
    for &n in &band {
        depth[at(n)] = 0;
    }
    let mut fresh: Vec<Node> = band
        .iter()
        .copied()
        .filter(|&n| matches!(decided[at(n)], Decided::In(_)))
        .collect();
    while !fresh.is_empty() {
        let mut next: Vec<Node> = Vec::new();
        for &n in &fresh {
            for m in neighbours(n.0, n.1, nx, ny) {
                match decided[at(m)] {
                    Decided::Out => next.push(m),
                    Decided::Open if depth[at(n)] < GROW => {
                        depth[at(m)] = depth[at(m)].min(depth[at(n)] + 1);
                        next.push(m);
                    }
                    _ => {}
                }
            }
        }
        next.sort_unstable();
        next.dedup();
        fresh.clear();
        for m in next {
            decide(m, &mut decided, reach);
            if matches!(decided[at(m)], Decided::In(_)) {
                fresh.push(m);
            }
        }
    }
    let value: Vec<f64> = (0..nx * ny)
        .map(|k| {
            let (ix, iy) = (k / ny, k % ny);
            let inside = match decided[k] {
                Decided::In(_) => true,
                Decided::Out => false,
                Decided::Open => filled((ix, iy)),
            };
            if inside {
                1.0
            } else {
                -1.0
            }
        })
        .collect();
    #[allow(clippy::cast_precision_loss)]
    let span = region.cell * nx.max(ny) as f64;
    let lines = contours(grid, &value, |a, b| {
        let (a, b) = if value[at(a)] > 0.0 { (a, b) } else { (b, a) };
        if decided[at(a)] == Decided::Open {
            decide(a, &mut decided, reach);
        }
        Some(match decided[at(a)] {
            Decided::In(q) => {
                let from = stand_in[at(a)].unwrap_or_else(|| centre(a));
                crossing(from, q, centre(b), reach, span)
            }
            // The fill's cell past the band, not reached after all: its own outline point.
            _ => Point2::from((centre(a).coords + centre(b).coords) / 2.0),
        })
    });
    // The cells the outline goes round, row by row from the bottom.
    let mut cells = vec![false; nx * ny];
    for iy in 0..ny {
        for ix in 0..nx {
            cells[iy * nx + ix] = value[at((ix, iy))] > 0.0;
        }
    }
    (lines, cells)
}

/// Where the reach ends between `inside` (reached, with preimage `q`) and `outside` (decided
/// not reached), bisected on the decision to 10⁻¹¹ of the span, each midpoint tried from the
/// last reached preimage.
fn crossing(
    inside: Point2<f64>,
    q: [f64; 2],
    outside: Point2<f64>,
    reach: &mut Reach<'_, '_>,
    span: f64,
) -> Point2<f64> {
    let (mut a, mut b, mut warm) = (inside, outside, q);
    while (b - a).norm() > 1e-11 * span {
        let m = Point2::from((a.coords + b.coords) / 2.0);
        if m == a || m == b {
            break;
        }
        match reach.reaches(m, &[warm]) {
            Some(q) => (a, warm) = (m, q),
            None => b = m,
        }
    }
    Point2::from((a.coords + b.coords) / 2.0)
}

/// How many cells either side of the fill's outline are decided: the fill lies within about
/// a cell of the truth (module docs), and one more for its rounding.
const BAND: usize = 2;

/// How many layers of cells past the band next to reached ones are decided (module docs).
const GROW: usize = 6;

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
