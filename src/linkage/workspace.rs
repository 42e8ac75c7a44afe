//! The workspace of a point of a linkage with two inputs: the region the point reaches, its
//! boundary, and the singular curves.
//!
//! The inputs are sampled on a grid (a crank over a whole turn, a slider over a range given),
//! each node solved once for the point's position and once more for the second column of
//! the Jacobian J = ∂P/∂(q₁, q₂) (the point's velocity at unit rate of each input). Then:
//! - the **singular curves** where det J = 0 (the point cannot move in some direction, a leg
//!   stretched or folded: the serial singularities of a five-bar), found by marching squares
//!   on det J over the input grid, each crossing bisected to the last bits and mapped to the
//!   plane; and where the linkage stops assembling (a group's determinant vanishes: a
//!   five-bar's couplers in line), each crossing bisected to the last assemblable input;
//! - the **region**: the image of every cell of the input grid (its corners, and where it
//!   meets the assembly boundary, the bisected points there) filled on a raster of the plane;
//! - its **boundary**: round the raster's outline, a band of cells has its centres decided
//!   (whether a point of the plane is reached, by Newton's method on P(q) = X, and about a
//!   pole of the map in polar coordinates: module `workspace_reach`), and the decided
//!   raster's outline is traced by marching squares, each point bisected between a centre
//!   reached and a neighbour not (module `workspace_boundary`).
//!
//! The region's cells lie within about a raster cell of the truth, and next to the outline
//! they are the decided ones; the boundary's points lie on the edge of the reach to 10⁻¹¹ of
//! the span where the edge is a fold of the map (a leg stretched or folded), and to the
//! position's own rounding next to the image of a singular input (couplers in line: about
//! √ε of the size at a pole, where the point's position carries εL²/|AC|), holes included;
//! [`Workspace::area`] (inside the boundary) is the reach's to the chords between points a
//! cell apart. The tests check both against closed-form inverse kinematics on a dense grid
//! and a row-by-row area.

use super::contour::{contours, Grid};
use super::plan::{InputPlan, Plan};
use super::solve::Kinematics;
use super::workspace_boundary::{area_inside, refine, Raster};
use super::workspace_reach::{Axes, Jac, Pole, Reach};
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use nalgebra::{Point2, Vector2};
use std::f64::consts::PI;

/// How finely a [`Workspace`] is sampled, and over which inputs.
///
/// # Examples
/// ```
/// use tmm::linkage::WorkspaceOptions;
/// let o = WorkspaceOptions::default().with_samples(91).with_resolution(150);
/// assert_eq!((o.samples, o.resolution), (91, 150));
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct WorkspaceOptions {
    /// The range of each input, `[from, to]` (rad or m); `None`: a crank's whole turn (a
    /// slider needs a range).
    pub ranges: [Option<[f64; 2]>; 2],
    /// The nodes of the input grid along each input, 8 to 2000 (default 181).
    pub samples: usize,
    /// The raster cells of the region along its longer side, 8 to 4000 (default 240).
    pub resolution: usize,
}

impl Default for WorkspaceOptions {
    fn default() -> Self {
        Self {
            ranges: [None, None],
            samples: 181,
            resolution: 240,
        }
    }
}

impl WorkspaceOptions {
    /// With `samples` nodes of the input grid along each input.
    #[must_use]
    pub fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// With `resolution` raster cells along the region's longer side.
    #[must_use]
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }

    /// With input `i` (0 or 1; another index changes nothing) over `[from, to]`.
    #[must_use]
    pub fn with_range(mut self, i: usize, from: f64, to: f64) -> Self {
        if let Some(r) = self.ranges.get_mut(i) {
            *r = Some([from, to]);
        }
        self
    }
}

/// The workspace of a point of a linkage with two inputs: the region it reaches, its
/// outline and the singular curves; made by [`Plan::workspace`].
#[derive(Debug, Clone, PartialEq)]
pub struct Workspace {
    /// The joint or named point.
    pub point: String,
    /// The region the point reaches, on a raster: the images of the input grid's cells
    /// filled, and next to the outline each cell as its centre is decided reached or not
    /// (the outline goes round exactly these cells).
    pub region: Region,
    /// The region's outline: closed polylines (each ends at its first point), m.
    pub boundary: Vec<Vec<Point2<f64>>>,
    /// The singular curves, mapped to the plane.
    pub singular: Vec<SingularCurve>,
}

impl Workspace {
    /// The area inside the outline ([`boundary`](Self::boundary)), m²: the outline's points
    /// lie on the edge of the reach (module docs), so this is the area of the reach to the
    /// chords between points a raster cell apart (of order (cell/ρ)² relative, ρ the edge's
    /// radius of curvature) and the tips of cusps thinner than a cell; the raster's own
    /// [`Region::area`] counts whole cells.
    #[must_use]
    pub fn area(&self) -> f64 {
        area_inside(&self.boundary)
    }
}

/// A region of the plane on a raster of square cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The lower-left corner of the raster, m.
    pub origin: Point2<f64>,
    /// The side of a cell, m.
    pub cell: f64,
    /// The cells along x.
    pub nx: usize,
    /// The cells along y.
    pub ny: usize,
    /// Whether each cell is reached, row by row from the bottom (`iy · nx + ix`).
    pub cells: Vec<bool>,
}

impl Region {
    /// The centre of cell `(ix, iy)`.
    #[must_use]
    pub fn centre(&self, ix: usize, iy: usize) -> Point2<f64> {
        #[allow(clippy::cast_precision_loss)]
        let c = Vector2::new(ix as f64 + 0.5, iy as f64 + 0.5) * self.cell;
        self.origin + c
    }

    /// Whether the cell holding `p` is reached (`false` off the raster, and for a cell the
    /// `cells` of a hand-made region do not hold).
    #[must_use]
    pub fn contains(&self, p: Point2<f64>) -> bool {
        self.cell_of(p).is_some_and(|(ix, iy)| {
            iy.checked_mul(self.nx)
                .and_then(|k| k.checked_add(ix))
                .and_then(|k| self.cells.get(k))
                .copied()
                .unwrap_or(false)
        })
    }

    /// The cell holding `p`, if on the raster.
    #[must_use]
    pub fn cell_of(&self, p: Point2<f64>) -> Option<(usize, usize)> {
        let u = (p - self.origin) / self.cell;
        #[allow(clippy::cast_precision_loss)]
        if !(u.x >= 0.0 && u.y >= 0.0 && u.x < self.nx as f64 && u.y < self.ny as f64) {
            return None;
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Some((u.x as usize, u.y as usize))
    }

    /// The area reached, m².
    #[must_use]
    pub fn area(&self) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let n = self.cells.iter().filter(|&&c| c).count() as f64;
        n * self.cell * self.cell
    }
}

/// A singular curve of a [`Workspace`].
#[derive(Debug, Clone, PartialEq)]
pub struct SingularCurve {
    /// Which singularity.
    pub kind: Singularity,
    /// The inputs along the curve, `[q₁, q₂]`.
    pub inputs: Vec<[f64; 2]>,
    /// The point's positions there, m.
    pub points: Vec<Point2<f64>>,
}

/// The kinds of singular curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Singularity {
    /// det ∂P/∂q = 0: the point cannot move in some direction whatever the inputs do (a leg
    /// stretched or folded).
    Serial,
    /// The linkage stops assembling: a group's determinant vanishes (its links in line), and
    /// beyond it the inputs have no position.
    Assembly,
    /// The image of an isolated input where a group's determinant vanishes but the linkage
    /// assembles all round it (a five-bar's couplers folded onto each other): as the inputs
    /// go round it the point sweeps a whole curve (a circle of the coupler's length about the
    /// folded hinges), traced about it at an eighth of a grid step, the singular input
    /// located to full precision (the loop's centre).
    Isolated,
}

impl Plan {
    /// The workspace of the joint or named point `point` of a linkage with two inputs.
    ///
    /// The inputs are sampled on a grid (a crank over a whole turn, a slider over a range
    /// given), each node solved for the point's position and the Jacobian J = ∂P/∂(q₁, q₂)
    /// (its velocity at unit rate of each input). The serial singular curves are where
    /// det J = 0 (marching squares on the grid, each crossing bisected to the last bits and
    /// mapped to the plane); the assembly curves where the linkage stops assembling (each
    /// crossing bisected to the last assemblable input). The region is the image of every
    /// grid cell filled on a raster (a cell split where its map is far from linear), and its
    /// boundary the raster's outline with each point moved onto the edge of the reach (module
    /// docs).
    ///
    /// The cost is 2 · `samples`² solves, a few hundred more per curve crossing, and
    /// `resolution`² raster cells.
    ///
    /// # Errors
    /// [`Error::Description`] (`"field second_input"`) for a linkage with one input, naming
    /// the point when it is neither a joint nor a named point, or naming the input whose range
    /// is missing (a slider); [`Error::NonFinite`] or [`Error::NonPositive`] for a range that
    /// is not finite or empty, [`Error::Overflow`] for one too wide for `f64`;
    /// [`Error::OutOfRange`] for `samples` or `resolution` out of their bounds;
    /// [`Error::Description`] (`"ranges"`) when no node of the input grid assembles.
    ///
    /// # Examples
    /// The five-bar robot's end effector B reaches an area about its reference position:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Inputs, Plan, WorkspaceOptions};
    /// let plan = Plan::new(&bundled::five_bar_robot())?;
    /// let ws = plan.workspace("B", &WorkspaceOptions::default().with_samples(61).with_resolution(80))?;
    /// let r = plan.reference_inputs();
    /// let b = plan.kinematics(Inputs::two(Motion::fixed(r[0]), Motion::fixed(r[1])))?.joint("B")?.p;
    /// assert!(ws.region.contains(b));
    /// assert!(ws.region.area() > 0.05 && !ws.boundary.is_empty() && !ws.singular.is_empty());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn workspace(&self, point: &str, options: &WorkspaceOptions) -> Result<Workspace> {
        let read = self.point_reader(point)?;
        range_check("samples of a workspace", options.samples, 8, 2000)?;
        range_check("resolution of a workspace", options.resolution, 8, 4000)?;
        let axes = self.workspace_axes(options)?;
        let mut k = Kinematics::new(self);
        // The position and both Jacobian columns at q, if it assembles.
        let mut jac = |q: [f64; 2]| -> Option<(Point2<f64>, Vector2<f64>, Vector2<f64>)> {
            k.solve(&[Motion::new(q[0], 1.0, 0.0), Motion::new(q[1], 0.0, 0.0)])
                .ok()?;
            let (p, v1) = read(&k);
            k.solve(&[Motion::new(q[0], 0.0, 0.0), Motion::new(q[1], 1.0, 0.0)])
                .ok()?;
            let (_, v2) = read(&k);
            (p.iter().chain(&v1).chain(&v2).all(|x| x.is_finite())).then_some((p, v1, v2))
        };
        let mut at = |q: [f64; 2]| -> Option<(Point2<f64>, f64)> {
            let (p, v1, v2) = jac(q)?;
            let det = v1.x * v2.y - v1.y * v2.x;
            det.is_finite().then_some((p, det))
        };
        let g = axes.grid;
        let mut nodes = Vec::with_capacity(g.n1 * g.n2);
        for i in 0..g.n1 {
            for j in 0..g.n2 {
                nodes.push(at(axes.q((i, j))));
            }
        }
        if nodes.iter().all(Option::is_none) {
            return Err(Error::Description {
                item: "ranges".to_owned(),
                problem: "the linkage assembles at no input of the workspace's grid".to_owned(),
            });
        }
        let (region, poles) = fill(&axes, &nodes, &mut at, options.resolution);
        // Nodes that assemble but no cell of the grid between them (ranges whose angles carry
        // no digit, 1e133 rad wide): no region to hold, and its box would be infinite.
        if !(region.origin.x.is_finite() && region.origin.y.is_finite()) {
            return Err(Error::Description {
                item: "ranges".to_owned(),
                problem: "no cell of the workspace's input grid assembles at its corners"
                    .to_owned(),
            });
        }
        let mut singular = singular_curves(&axes, &nodes, &mut at);
        let poles = refine_poles(&axes, &poles, &mut jac);
        let mut at = |q: [f64; 2]| -> Option<(Point2<f64>, f64)> {
            let (p, v1, v2) = jac(q)?;
            let det = v1.x * v2.y - v1.y * v2.x;
            det.is_finite().then_some((p, det))
        };
        let (isolated, traces) = isolated_curves(&axes, &poles, &mut at);
        singular.extend(isolated);
        // The outline located by deciding points of the plane (module `workspace_boundary`).
        let images: Vec<Option<Point2<f64>>> = nodes.iter().map(|n| n.map(|n| n.0)).collect();
        #[allow(clippy::cast_precision_loss)]
        let span = region.cell * region.nx.max(region.ny) as f64;
        let mut reach = Reach::new(&mut jac, &axes, images, traces, 2.0 * region.cell, span);
        let (boundary, cells) = refine(
            &Raster {
                origin: region.origin,
                cell: region.cell,
                nx: region.nx,
                ny: region.ny,
                cells: &region.cells,
            },
            &mut reach,
        );
        let region = Region { cells, ..region };
        Ok(Workspace {
            point: point.to_owned(),
            region,
            boundary,
            singular,
        })
    }

    /// A function reading the position and velocity of a joint or named point.
    fn point_reader(
        &self,
        point: &str,
    ) -> Result<impl Fn(&Kinematics<'_>) -> (Point2<f64>, Vector2<f64>) + use<>> {
        if self.input_count() != 2 {
            return Err(Error::Description {
                item: "field second_input".to_owned(),
                problem: "a workspace needs a linkage with two inputs".to_owned(),
            });
        }
        let joint = self.chain.joint(point).ok();
        let named = match joint {
            Some(_) => None,
            None => Some(self.chain.point(point).map_err(|_| Error::Description {
                item: format!("point {point:?}"),
                problem: "the workspace's point is neither a joint nor a named point".to_owned(),
            })?),
        };
        Ok(move |k: &Kinematics<'_>| {
            let pose = k.pose();
            let m = match (joint, named) {
                (Some(j), _) => pose.joint_motion_at(j),
                (_, Some(p)) => pose.point_motion_at(p),
                _ => unreachable!("one of them is set"),
            };
            (m.p, m.v)
        })
    }

    /// The input grid of a workspace.
    fn workspace_axes(&self, options: &WorkspaceOptions) -> Result<Axes> {
        let n = options.samples.max(2);
        let reference = self.reference_inputs();
        let mut lo = [0.0; 2];
        let mut step = [0.0; 2];
        let mut wrap = [false; 2];
        for (i, ip) in self.chain.inputs().enumerate().take(2) {
            let which = if i == 0 { "first" } else { "second" };
            #[allow(clippy::cast_precision_loss)]
            match (options.ranges[i], ip) {
                (Some([a, b]), _) => {
                    crate::error::all_finite(&[
                        ("start of an input range", a),
                        ("end of an input range", b),
                    ])?;
                    if a == b {
                        return Err(Error::NonPositive {
                            name: "width of an input range",
                            value: 0.0,
                        });
                    }
                    crate::error::computed("width of an input range", b - a)?;
                    lo[i] = a;
                    step[i] = (b - a) / (n - 1) as f64;
                }
                (None, InputPlan::Crank { .. }) => {
                    lo[i] = reference[i] - PI;
                    step[i] = 2.0 * PI / n as f64;
                    wrap[i] = true;
                }
                (None, InputPlan::Slider { .. }) => {
                    return Err(Error::Description {
                        item: format!("ranges[{i}]"),
                        problem: format!(
                            "the {which} input is a slider: give its range for a workspace"
                        ),
                    });
                }
            }
        }
        Ok(Axes {
            lo,
            step,
            grid: Grid {
                n1: n,
                n2: n,
                wrap1: wrap[0],
                wrap2: wrap[1],
            },
        })
    }
}

/// `min ≤ n ≤ max`.
fn range_check(name: &'static str, n: usize, min: usize, max: usize) -> Result<()> {
    if (min..=max).contains(&n) {
        return Ok(());
    }
    #[allow(clippy::cast_precision_loss)]
    Err(Error::OutOfRange {
        name,
        value: n as f64,
        min: min as f64,
        max: max as f64,
        ends: crate::Ends::Closed,
    })
}

type At<'a> = dyn FnMut([f64; 2]) -> Option<(Point2<f64>, f64)> + 'a;

/// The point between `qa` (where `good` holds) and `qb` (where it does not) where it stops
/// holding, bisected to the last bits; with the value there.
fn bisect<T>(
    qa: [f64; 2],
    qb: [f64; 2],
    mut good: impl FnMut([f64; 2]) -> Option<T>,
) -> Option<([f64; 2], T)> {
    let (mut a, mut b) = (qa, qb);
    let mut best = (a, good(a)?);
    for _ in 0..60 {
        let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        if m == a || m == b {
            break;
        }
        match good(m) {
            Some(v) => {
                a = m;
                best = (m, v);
            }
            None => b = m,
        }
    }
    Some(best)
}

/// The serial and assembly singular curves over the input grid.
fn singular_curves(
    axes: &Axes,
    nodes: &[Option<(Point2<f64>, f64)>],
    at: &mut At<'_>,
) -> Vec<SingularCurve> {
    let g = axes.grid;
    // det J = 0 between nodes that both assemble; a pole of det J (where it changes sign
    // through infinity) is not a zero: the bisection lands on a large |det| and is dropped.
    let det: Vec<f64> = nodes
        .iter()
        .map(|n| n.map_or(f64::NAN, |(_, d)| d))
        .collect();
    let serial = contours(g, &det, |a, b| {
        let (da, db) = (det[g.index(a)], det[g.index(b)]);
        let sign = da > 0.0;
        let (q, (p, d)) = bisect(axes.q(a), axes.q(b), |q| {
            at(q).filter(|&(_, d)| (d > 0.0) == sign)
        })?;
        (d.abs() <= da.abs().min(db.abs())).then_some((q, p))
    });
    // Where the nodes stop assembling: from the node that assembles towards the other.
    let ok: Vec<f64> = nodes
        .iter()
        .map(|n| if n.is_some() { 1.0 } else { -1.0 })
        .collect();
    let assembly = contours(g, &ok, |a, b| {
        let (a, b) = if ok[g.index(a)] > 0.0 { (a, b) } else { (b, a) };
        let (q, (p, _)) = bisect(axes.q(a), axes.q(b), &mut *at)?;
        Some((q, p))
    });
    let curve = |kind, c: &[([f64; 2], Point2<f64>)]| SingularCurve {
        kind,
        inputs: c.iter().map(|x| x.0).collect(),
        points: c.iter().map(|x| x.1).collect(),
    };
    let serial = serial.iter().flat_map(|c| split_at_jumps(c));
    let assembly = assembly.iter().flat_map(|c| split_at_jumps(c));
    serial
        .map(|c| curve(Singularity::Serial, c))
        .chain(assembly.map(|c| curve(Singularity::Assembly, c)))
        .collect()
}

/// `poles` without those within an eighth of a grid step of one kept before.
fn distinct(axes: &Axes, poles: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let h = axes.step[0].abs().max(axes.step[1].abs());
    let mut kept: Vec<[f64; 2]> = Vec::new();
    for &q in poles {
        if kept
            .iter()
            .all(|k| (k[0] - q[0]).abs().max((k[1] - q[1]).abs()) > h / 8.0)
        {
            kept.push(q);
        }
    }
    kept
}

/// The isolated singular inputs located to full precision: each of `poles` (distinct ones,
/// located to a split of a grid cell) refined by [`refine_pole`], or kept as it is where the
/// refinement does not settle near it.
fn refine_poles(axes: &Axes, poles: &[[f64; 2]], jac: &mut Jac<'_>) -> Vec<[f64; 2]> {
    let h = axes.step[0].abs().max(axes.step[1].abs());
    let refined: Vec<[f64; 2]> = distinct(axes, poles)
        .into_iter()
        .map(|q| refine_pole(q, h, jac).unwrap_or(q))
        .collect();
    distinct(axes, &refined)
}

/// An isolated singular input q* near `q0` (within a quarter of the grid step `h`).
///
/// Near q* the point's position depends, to first order, only on the direction of q − q*
/// (it swings round a whole curve as the inputs go round q*): along a ray from q* it moves
/// at a bounded rate, across it at a rate ~ 1/|q − q*|. So the Jacobian's right singular
/// vector of the smaller singular value points along the ray, to within O(|q − q*|) of
/// angle: the line through a probe q along it passes within O(|q − q*|²) of q*. The lines
/// of eight probes round the estimate meet (least squares) at the next estimate; the
/// probes' circle shrinks with the step, down to 1e-6 of a grid step (below that the
/// position loses its digits as 1/|q − q*|).
fn refine_pole(q0: [f64; 2], h: f64, jac: &mut Jac<'_>) -> Option<[f64; 2]> {
    let mut q = Vector2::new(q0[0], q0[1]);
    let mut rho = h / 8.0;
    for _ in 0..24 {
        let mut m = nalgebra::Matrix2::zeros();
        let mut rhs = Vector2::zeros();
        for k in 0..8 {
            let t = std::f64::consts::TAU * (f64::from(k) + 0.5) / 8.0;
            let qk = q + rho * Vector2::new(t.cos(), t.sin());
            let (_, v1, v2) = jac([qk.x, qk.y])?;
            let n = null_direction(v1, v2)?;
            // Projection across the line: its distance from x is |(I − n nᵀ)(x − qk)|.
            let across = nalgebra::Matrix2::identity() - n * n.transpose();
            m += across;
            rhs += across * qk;
        }
        let next = m.lu().solve(&rhs)?;
        let moved = (next - q).norm();
        if !(moved.is_finite() && (next - Vector2::new(q0[0], q0[1])).norm() <= h / 4.0) {
            return None;
        }
        q = next;
        if moved <= 1e-14 * (1.0 + q.norm()) {
            break;
        }
        rho = (4.0 * moved).min(rho / 4.0).max(1e-6 * h);
    }
    Some([q.x, q.y])
}

/// The unit vector x minimising |J x| for J = [v1 v2]: the eigenvector of JᵀJ of its
/// smaller eigenvalue; `None` when J vanishes or is not finite.
fn null_direction(v1: Vector2<f64>, v2: Vector2<f64>) -> Option<Vector2<f64>> {
    let (a, b, c) = (v1.dot(&v1), v1.dot(&v2), v2.dot(&v2));
    let lambda = 0.5 * (a + c) - (0.5 * (a - c)).hypot(b);
    // Two forms of the same eigenvector: the longer is the better conditioned.
    let x = Vector2::new(b, lambda - a);
    let y = Vector2::new(lambda - c, b);
    let v = if x.norm() >= y.norm() { x } else { y };
    let n = v.norm();
    (n > 0.0 && n.is_finite()).then(|| v / n)
}

/// The curves an isolated singular input maps to: round each of `poles` (refined by
/// [`refine_poles`]), the images of a small circle of inputs about it, an eighth of a grid
/// step across, in 720 positions, cut where a position fails or the curve jumps; with each
/// pole's trace for the decisions near it (module `workspace_reach`).
fn isolated_curves(
    axes: &Axes,
    poles: &[[f64; 2]],
    at: &mut At<'_>,
) -> (Vec<SingularCurve>, Vec<Pole>) {
    let h = axes.step[0].abs().max(axes.step[1].abs());
    let mut out = Vec::new();
    let mut traces = Vec::new();
    for &q in poles {
        let mut pieces: Vec<Vec<([f64; 2], Point2<f64>)>> = vec![Vec::new()];
        let mut trace = Vec::new();
        for k in 0..=720 {
            let t = std::f64::consts::TAU * f64::from(k) / 720.0;
            let qk = [q[0] + h / 8.0 * t.cos(), q[1] + h / 8.0 * t.sin()];
            match at(qk) {
                Some((p, _)) => {
                    pieces.last_mut().expect("one piece").push((qk, p));
                    trace.push((t, p));
                }
                None => pieces.push(Vec::new()),
            }
        }
        for piece in &pieces {
            for c in split_at_jumps(piece) {
                out.push(SingularCurve {
                    kind: Singularity::Isolated,
                    inputs: c.iter().map(|x| x.0).collect(),
                    points: c.iter().map(|x| x.1).collect(),
                });
            }
        }
        traces.push(Pole {
            q,
            radius: h / 8.0,
            trace,
        });
    }
    (out, traces)
}

/// A curve cut where it jumps: a step more than 8 times its median step. Near a pole of the
/// map (a five-bar's couplers folded onto each other) neighbouring inputs land far apart, and
/// a line between them would cross the plane where no singular point lies.
fn split_at_jumps(c: &[([f64; 2], Point2<f64>)]) -> Vec<&[([f64; 2], Point2<f64>)]> {
    let step = |w: &[([f64; 2], Point2<f64>)]| (w[1].1 - w[0].1).norm();
    let mut steps: Vec<f64> = c.windows(2).map(step).collect();
    steps.sort_by(f64::total_cmp);
    let Some(&median) = steps.get(steps.len() / 2) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut start = 0;
    for k in 1..c.len() {
        if step(&c[k - 1..=k]) > 8.0 * median {
            out.push(&c[start..k]);
            start = k;
        }
    }
    out.push(&c[start..]);
    out.retain(|piece| piece.len() >= 2);
    out
}

/// The image of every cell of the input grid, filled on a raster of `resolution` cells
/// along the longer side (two empty cells of margin round it): each cell's corners that
/// assemble and, on an edge from one that does to one that does not, the last assemblable
/// point, as a polygon, filled as a fan of triangles from its first corner.
fn fill(
    axes: &Axes,
    nodes: &[Option<(Point2<f64>, f64)>],
    at: &mut At<'_>,
    resolution: usize,
) -> (Region, Vec<[f64; 2]>) {
    let g = axes.grid;
    // The raster's cell from the nodes' images: a cell whose map departs from linear by
    // more than a quarter of it is split.
    let (lo, hi) = bounds(nodes.iter().flatten().map(|n| n.0));
    let span = (hi - lo).max();
    #[allow(clippy::cast_precision_loss)]
    let cell = if span > 0.0 {
        span / resolution as f64
    } else {
        1e-3
    };
    let mut polygons: Vec<Vec<Point2<f64>>> = Vec::new();
    let mut poles = Vec::new();
    for (i, j) in g.cells() {
        let c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
        if let [Some(a), Some(b), Some(d), Some(e)] = c.map(|n| nodes[g.index(n)]) {
            let p = [a.0, b.0, d.0, e.0];
            let q = c.map(|n| axes.q(n));
            fill_cell(&mut polygons, &mut poles, at, q, p, 0.25 * cell, 6);
            continue;
        }
        let mut poly = Vec::with_capacity(6);
        for k in 0..4 {
            let (a, b) = (c[k], c[(k + 1) % 4]);
            let (na, nb) = (nodes[g.index(a)], nodes[g.index(b)]);
            if let Some((p, _)) = na {
                poly.push(p);
            }
            let edge = match (na, nb) {
                (Some(_), None) => bisect(axes.q(a), axes.q(b), &mut *at),
                (None, Some(_)) => bisect(axes.q(b), axes.q(a), &mut *at),
                _ => None,
            };
            poly.extend(edge.map(|(_, (p, _))| p));
        }
        if !poly.is_empty() {
            polygons.push(poly);
        }
    }
    let (lo, hi) = bounds(polygons.iter().flatten().copied());
    let origin = lo - Vector2::new(2.0, 2.0) * cell;
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let count = |w: f64| (w / cell).ceil() as usize + 4;
    let (nx, ny) = (count(hi.x - lo.x), count(hi.y - lo.y));
    let mut region = Region {
        origin,
        cell,
        nx,
        ny,
        cells: vec![false; nx * ny],
    };
    for poly in &polygons {
        for &p in poly {
            if let Some((ix, iy)) = region.cell_of(p) {
                region.cells[iy * nx + ix] = true;
            }
        }
        for k in 1..poly.len().saturating_sub(1) {
            triangle(&mut region, [poly[0], poly[k], poly[k + 1]], 0.25 * cell);
        }
    }
    (region, poles)
}

/// The corners of the box round `points`.
fn bounds(points: impl Iterator<Item = Point2<f64>>) -> (Point2<f64>, Point2<f64>) {
    let inf = f64::INFINITY;
    points.fold(
        (Point2::new(inf, inf), Point2::new(-inf, -inf)),
        |(lo, hi), p| (lo.inf(&p), hi.sup(&p)),
    )
}

/// A cell of the input grid whose four corners assemble (inputs `q`, images `p`, in order
/// round it), as polygons to fill: itself when the map is near linear over it (the image of
/// its centre within `tol` of its corners' mean), otherwise its four quarters, `depth` times
/// at most. A cell that stays far from linear holds a pole of
/// the map (a five-bar's couplers folded onto each other, where the end effector swings
/// round a whole circle): it is left to its neighbours and its corners.
fn fill_cell(
    polygons: &mut Vec<Vec<Point2<f64>>>,
    poles: &mut Vec<[f64; 2]>,
    at: &mut At<'_>,
    q: [[f64; 2]; 4],
    p: [Point2<f64>; 4],
    tol: f64,
    depth: u32,
) {
    let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let qc = mid(mid(q[0], q[1]), mid(q[2], q[3]));
    let mean = Point2::from((p[0].coords + p[1].coords + p[2].coords + p[3].coords) / 4.0);
    let Some((pc, _)) = at(qc) else {
        polygons.push(p.to_vec());
        return;
    };
    if (pc - mean).norm() <= tol {
        polygons.push(p.to_vec());
        return;
    }
    if depth == 0 {
        poles.push(qc);
        return;
    }
    let qm = [
        mid(q[0], q[1]),
        mid(q[1], q[2]),
        mid(q[2], q[3]),
        mid(q[3], q[0]),
    ];
    let pm = qm.map(|q| at(q).map(|x| x.0));
    let [Some(m0), Some(m1), Some(m2), Some(m3)] = pm else {
        polygons.push(p.to_vec());
        return;
    };
    let quarters = [
        ([q[0], qm[0], qc, qm[3]], [p[0], m0, pc, m3]),
        ([qm[0], q[1], qm[1], qc], [m0, p[1], m1, pc]),
        ([qc, qm[1], q[2], qm[2]], [pc, m1, p[2], m2]),
        ([qm[3], qc, qm[2], q[3]], [m3, pc, m2, p[3]]),
    ];
    for (q, p) in quarters {
        fill_cell(polygons, poles, at, q, p, tol, depth - 1);
    }
}

/// Marks every cell of `region` whose centre lies in the triangle `t` or within `margin` of
/// it: the margin closes the slivers between a split cell's images and its neighbour's
/// (they differ from linear by `margin` at most).
fn triangle(region: &mut Region, t: [Point2<f64>; 3], margin: f64) {
    let cross = |o: Point2<f64>, a: Point2<f64>, b: Point2<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let area = cross(t[0], t[1], t[2]);
    if area == 0.0 {
        return;
    }
    let m = Vector2::new(margin, margin);
    let lo = t[0].inf(&t[1]).inf(&t[2]) - m;
    let hi = t[0].sup(&t[1]).sup(&t[2]) + m;
    let (Some(a), Some(b)) = (region.cell_of(lo), region.cell_of(hi)) else {
        return;
    };
    let sides = [
        (t[2] - t[1]).norm(),
        (t[0] - t[2]).norm(),
        (t[1] - t[0]).norm(),
    ];
    for iy in a.1..=b.1 {
        for ix in a.0..=b.0 {
            let c = region.centre(ix, iy);
            let w = [
                cross(t[1], t[2], c),
                cross(t[2], t[0], c),
                cross(t[0], t[1], c),
            ];
            // Inside, or within `margin` of every side's line.
            if (0..3).all(|i| w[i] * area.signum() >= -margin * sides[i]) {
                region.cells[iy * region.nx + ix] = true;
            }
        }
    }
}
