//! What the pictures share: the structure of a plan read once ([`Topo`]), one solved position
//! as plain points ([`Pose`]), the travel of every slider on its guide ([`Extents`]), and the
//! SVG elements of links, hinges, ground, labels and arrows.

use super::frame::Frame;
use super::style::Style;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::{Kinematics, Plan};
use nalgebra::{Point2, Vector2};
use svg::node::element::path::Data;
use svg::node::element::{Circle, Group, Line, Path, Polygon, Text};
use svg::Node;

/// The colours of the moving links, by index (the frame is black).
const PALETTE: [&str; 8] = [
    "#1f5fa8", "#c0392b", "#2e8b57", "#7d3c98", "#d35400", "#138d90", "#7f5a3a", "#b03a7a",
];

/// A pixel number with two decimals: enough for any screen, and short SVG text.
pub(crate) fn r2(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

/// The colour of link `k`.
pub(crate) fn colour(k: usize) -> &'static str {
    if k == 0 {
        "#000000"
    } else {
        PALETTE[(k - 1) % PALETTE.len()]
    }
}

/// How one drawing pass strokes the links.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pen {
    /// Override every link's colour (plans draw their positions in grey).
    pub colour: Option<&'static str>,
    /// Multiplies the style's line width.
    pub width: f64,
    /// The opacity of the fill of ternary links.
    pub fill_opacity: f64,
    /// The opacity of the whole pass.
    pub opacity: f64,
    /// Multiplies the style's hinge radius.
    pub hinge: f64,
    /// Whether slider blocks are filled white (hiding their guides), or outlines only.
    pub block_fill: bool,
}

impl Pen {
    pub(crate) const NORMAL: Self = Self {
        colour: None,
        width: 1.0,
        fill_opacity: 0.35,
        opacity: 1.0,
        hinge: 1.0,
        block_fill: true,
    };

    fn colour(&self, k: usize) -> &'static str {
        self.colour.unwrap_or_else(|| colour(k))
    }
}

/// The structure of a plan, read once through its public accessors.
#[derive(Debug, Clone)]
pub(crate) struct Topo {
    pub joint_links: Vec<[usize; 2]>,
    pub guide: Vec<Option<usize>>,
    pub link_joints: Vec<Vec<usize>>,
    pub joint_names: Vec<String>,
    pub point_names: Vec<String>,
    pub point_link: Vec<usize>,
    pub input: usize,
    pub crank: bool,
    pub size: f64,
}

impl Topo {
    pub(crate) fn new(plan: &Plan) -> Self {
        let nj = plan.joint_names().len();
        let nl = plan.link_names().len();
        let joint_links: Vec<[usize; 2]> = (0..nj).map(|j| plan.joint_links_at(j)).collect();
        let mut link_joints = vec![Vec::new(); nl];
        for (j, l) in joint_links.iter().enumerate() {
            for &k in l {
                link_joints[k].push(j);
            }
        }
        Self {
            guide: (0..nj).map(|j| plan.chain.guide_link_at(j)).collect(),
            joint_links,
            link_joints,
            joint_names: plan.joint_names().to_vec(),
            point_names: plan.point_names().to_vec(),
            point_link: (0..plan.point_names().len())
                .map(|i| plan.chain.points[i].link)
                .collect(),
            input: plan.chain.input.link(),
            crank: plan.input_is_crank(),
            size: plan.size(),
        }
    }

    pub(crate) fn links(&self) -> usize {
        self.link_joints.len()
    }

    /// The side (0 or 1) of joint `j` that link `k` is on.
    fn side(&self, j: usize, k: usize) -> usize {
        usize::from(self.joint_links[j][1] == k)
    }

    /// The link whose picture carries hinge `j` (its moving link, the later one if both move).
    pub(crate) fn hinge_owner(&self, j: usize) -> usize {
        self.joint_links[j][0].max(self.joint_links[j][1])
    }

    /// The joint between the input link and the frame.
    pub(crate) fn input_joint(&self) -> Option<usize> {
        self.link_joints[self.input]
            .iter()
            .copied()
            .find(|&j| self.joint_links[j].contains(&0))
    }

    /// Resolves a joint or point name to what a path follows.
    pub(crate) fn tracer(&self, name: &str) -> Result<Tracer> {
        if let Some(j) = self.joint_names.iter().position(|n| n == name) {
            return Ok(Tracer::Joint(j));
        }
        if let Some(i) = self.point_names.iter().position(|n| n == name) {
            return Ok(Tracer::Point(i));
        }
        Err(Error::Description {
            item: format!("point {name}"),
            problem: "is neither a joint nor a named point of this linkage".to_owned(),
        })
    }
}

/// A joint or named point whose path is drawn.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Tracer {
    Joint(usize),
    Point(usize),
}

/// One solved position as plain points.
#[derive(Debug, Clone)]
pub(crate) struct Pose {
    /// Every joint as a point of each of its two links.
    pub joints: Vec<[Point2<f64>; 2]>,
    /// Every joint's guide direction (zero for a hinge).
    pub guides: Vec<Vector2<f64>>,
    /// Every link's engine frame: origin and angle.
    pub links: Vec<(Point2<f64>, f64)>,
    /// Every named point.
    pub points: Vec<Point2<f64>>,
    /// The input.
    pub input: Motion,
}

impl Pose {
    pub(crate) fn of(a: &Kinematics<'_>) -> Result<Self> {
        let plan = a.plan();
        let nj = plan.joint_names().len();
        let solved = a.pose();
        let pose = Self {
            joints: (0..nj)
                .map(|j| [solved.joint_on_at(j, 0).p, solved.joint_on_at(j, 1).p])
                .collect(),
            guides: (0..nj).map(|j| solved.guide_direction_at(j)).collect(),
            links: (0..plan.link_names().len())
                .map(|k| {
                    let m = solved.links[k];
                    (m.origin.p, m.angle)
                })
                .collect(),
            points: (0..plan.point_names().len())
                .map(|i| solved.point_motion_at(i).p)
                .collect(),
            input: a.inputs().first(),
        };
        let finite = pose
            .joints
            .iter()
            .flatten()
            .chain(&pose.points)
            .all(|p| p.x.is_finite() && p.y.is_finite());
        if finite {
            Ok(pose)
        } else {
            Err(Error::Overflow {
                what: "a drawn position",
            })
        }
    }

    /// Joint `j` as a point of link `k`.
    pub(crate) fn on(&self, topo: &Topo, j: usize, k: usize) -> Point2<f64> {
        self.joints[j][topo.side(j, k)]
    }

    /// Joint `j` where it is drawn: a hinge's centre, or the slider's point of a sliding pair.
    pub(crate) fn at(&self, topo: &Topo, j: usize) -> Point2<f64> {
        match topo.guide[j] {
            Some(g) => self.joints[j][1 - topo.side(j, g)],
            None => self.joints[j][0],
        }
    }

    pub(crate) fn tracer(&self, topo: &Topo, t: Tracer) -> Point2<f64> {
        match t {
            Tracer::Joint(j) => self.at(topo, j),
            Tracer::Point(i) => self.points[i],
        }
    }

    /// Every point the picture of this position covers (guides from `ext`).
    pub(crate) fn cover(&self, topo: &Topo, ext: &Extents, out: &mut Vec<Point2<f64>>) {
        out.extend(self.joints.iter().flatten().copied());
        out.extend(self.points.iter().copied());
        for j in 0..self.joints.len() {
            if let Some((a, b)) = self.guide_ends(topo, ext, j) {
                out.push(a);
                out.push(b);
            }
        }
    }

    /// The ends of the guide line of joint `j` covering the slider's travel in `ext`.
    pub(crate) fn guide_ends(
        &self,
        topo: &Topo,
        ext: &Extents,
        j: usize,
    ) -> Option<(Point2<f64>, Point2<f64>)> {
        let g = topo.guide[j]?;
        let [lo, hi] = ext.travel[j];
        let d = self.guides[j];
        let base = self.on(topo, j, g);
        // A fixed guide reaches well past the block, so that it shows on both sides.
        let reach = if g == 0 { 2.5 * ext.block } else { ext.block };
        Some((base + d * (lo - reach), base + d * (hi + reach)))
    }
}

/// The travel of every slider along its guide over the drawn positions, and the block size.
#[derive(Debug, Clone)]
pub(crate) struct Extents {
    /// Per joint: the least and greatest distance of the slider's point from the guide's
    /// reference point, along the guide (m).
    pub travel: Vec<[f64; 2]>,
    /// Half the length of a slider block, m.
    pub block: f64,
}

impl Extents {
    pub(crate) fn new(topo: &Topo) -> Self {
        Self {
            travel: vec![[f64::INFINITY, f64::NEG_INFINITY]; topo.joint_links.len()],
            block: 0.06 * topo.size,
        }
    }

    pub(crate) fn add(&mut self, topo: &Topo, pose: &Pose) {
        for (j, t) in self.travel.iter_mut().enumerate() {
            if let Some(g) = topo.guide[j] {
                let s = (pose.at(topo, j) - pose.on(topo, j, g)).dot(&pose.guides[j]);
                t[0] = t[0].min(s);
                t[1] = t[1].max(s);
            }
        }
    }
}

/// The box around `points`, fitted to the style's picture.
pub(crate) fn fit(points: &[Point2<f64>], style: &Style) -> Result<Frame> {
    let mut lo = Point2::new(f64::INFINITY, f64::INFINITY);
    let mut hi = Point2::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    Frame::fit(lo, hi, style.w(), style.h(), style.margin)
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
fn hull(points: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let mut p = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let cross = |o: &Point2<f64>, a: &Point2<f64>, b: &Point2<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let mut h: Vec<Point2<f64>> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = h.len();
        let it: Box<dyn Iterator<Item = &Point2<f64>>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for q in it {
            while h.len() >= start + 2 && cross(&h[h.len() - 2], &h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(*q);
        }
        h.pop();
    }
    h
}

/// The body of link `k` ≠ 0 at `pose`, mapped to pixels by `map`: a bar, a filled polygon, its
/// guides and its slider blocks.
#[allow(clippy::too_many_arguments)]
pub(crate) fn link_body(
    topo: &Topo,
    pose: &Pose,
    ext: &Extents,
    k: usize,
    scale: f64,
    style: &Style,
    pen: Pen,
    map: &dyn Fn(Point2<f64>) -> [f64; 2],
) -> Group {
    let c = pen.colour(k);
    let lw = style.line_width * pen.width;
    let mut g = Group::new();
    // The points of the body: hinges, and the link's own point of a sliding pair it slides in.
    let tol = 1e-9 * topo.size.max(f64::MIN_POSITIVE);
    let mut pts: Vec<Point2<f64>> = Vec::new();
    for &j in &topo.link_joints[k] {
        if topo.guide[j] == Some(k) {
            continue;
        }
        let p = pose.on(topo, j, k);
        if pts.iter().all(|q| (q - p).norm() > tol) {
            pts.push(p);
        }
    }
    // Named points are part of the body (a coupler point makes the coupler a triangle).
    for (i, &l) in topo.point_link.iter().enumerate() {
        let p = pose.points[i];
        if l == k && pts.iter().all(|q| (q - p).norm() > tol) {
            pts.push(p);
        }
    }
    let bar = |g: &mut Group, a: [f64; 2], b: [f64; 2], w: f64| {
        g.append(
            Line::new()
                .set("x1", r2(a[0]))
                .set("y1", r2(a[1]))
                .set("x2", r2(b[0]))
                .set("y2", r2(b[1]))
                .set("stroke", c)
                .set("stroke-width", r2(w))
                .set("stroke-linecap", "round"),
        );
    };
    let h = if pts.len() >= 3 {
        hull(&pts)
    } else {
        pts.clone()
    };
    if h.len() >= 3 {
        let points: Vec<String> = h
            .iter()
            .map(|&p| {
                let q = map(p);
                format!("{},{}", r2(q[0]), r2(q[1]))
            })
            .collect();
        g.append(
            Polygon::new()
                .set("points", points.join(" "))
                .set("fill", c)
                .set("fill-opacity", pen.fill_opacity)
                .set("stroke", c)
                .set("stroke-width", r2(lw))
                .set("stroke-linejoin", "round"),
        );
    } else if h.len() == 2 {
        bar(&mut g, map(h[0]), map(h[1]), lw);
    }
    // Guides carried by this link.
    for &j in &topo.link_joints[k] {
        if topo.guide[j] == Some(k)
            && let Some((a, b)) = pose.guide_ends(topo, ext, j)
        {
            bar(&mut g, map(a), map(b), lw);
        }
    }
    // Blocks of the sliding pairs this link slides in.
    for &j in &topo.link_joints[k] {
        match topo.guide[j] {
            Some(gl) if gl != k => {
                let corners =
                    block_corners(pose.on(topo, j, k), pose.guides[j], ext.block, scale, style);
                let mut b = block(&corners.map(map), c, lw * 0.6);
                if !pen.block_fill {
                    b = b.set("fill", "none");
                }
                g.append(b);
            }
            _ => {}
        }
    }
    g
}

/// The corners of a slider block at `p` along `d`: half-length `half` m, and a height of four
/// hinge radii (so that the hinge on it shows).
fn block_corners(
    p: Point2<f64>,
    d: Vector2<f64>,
    half: f64,
    scale: f64,
    style: &Style,
) -> [Point2<f64>; 4] {
    let n = Vector2::new(-d.y, d.x);
    let hw = (2.0 * style.hinge_radius.max(2.0)) / scale;
    let hl = half.max(1.5 * hw);
    [
        p - d * hl - n * hw,
        p + d * hl - n * hw,
        p + d * hl + n * hw,
        p - d * hl + n * hw,
    ]
}

fn block(corners: &[[f64; 2]; 4], c: &str, w: f64) -> Polygon {
    let pts: Vec<String> = corners
        .iter()
        .map(|q| format!("{},{}", r2(q[0]), r2(q[1])))
        .collect();
    Polygon::new()
        .set("points", pts.join(" "))
        .set("fill", "#ffffff")
        .set("stroke", c)
        .set("stroke-width", r2(w.max(1.0)))
}

/// A hinge at pixel `q`: a white circle with a dark outline and a centre mark.
pub(crate) fn hinge(q: [f64; 2], style: &Style, stroke: &str) -> Group {
    Group::new()
        .add(
            Circle::new()
                .set("cx", r2(q[0]))
                .set("cy", r2(q[1]))
                .set("r", r2(style.hinge_radius))
                .set("fill", "#ffffff")
                .set("stroke", stroke)
                .set("stroke-width", 1.5),
        )
        .add(dot(q, 1.3, stroke))
}

/// A named point's dot at pixel `q`.
pub(crate) fn dot(q: [f64; 2], r: f64, fill: &str) -> Circle {
    Circle::new()
        .set("cx", r2(q[0]))
        .set("cy", r2(q[1]))
        .set("r", r2(r))
        .set("fill", fill)
}

/// The hinges drawn with link `k`'s picture, and its named points.
pub(crate) fn link_hinges(
    topo: &Topo,
    pose: &Pose,
    k: usize,
    style: &Style,
    map: &dyn Fn(Point2<f64>) -> [f64; 2],
) -> Group {
    let mut g = Group::new();
    for &j in &topo.link_joints[k] {
        if topo.guide[j].is_none() && topo.hinge_owner(j) == k {
            g.append(hinge(map(pose.on(topo, j, k)), style, "#000000"));
        }
    }
    for (i, &l) in topo.point_link.iter().enumerate() {
        if l == k {
            g.append(dot(
                map(pose.points[i]),
                0.6 * style.hinge_radius + 1.0,
                colour(k),
            ));
        }
    }
    g
}

/// The frame: a hatched base under every ground pivot, a hatched line along every fixed guide.
pub(crate) fn ground(
    topo: &Topo,
    pose: &Pose,
    ext: &Extents,
    frame: &Frame,
    style: &Style,
) -> Group {
    let mut g = Group::new()
        .set("stroke", "#000000")
        .set("stroke-width", 1.5);
    let r = style.hinge_radius.max(2.0);
    for &j in &topo.link_joints[0] {
        match topo.guide[j] {
            None => {
                let q = frame.to_pixel(pose.joints[j][0]);
                let base = q[1] + 2.6 * r;
                g.append(
                    Polygon::new()
                        .set(
                            "points",
                            format!(
                                "{},{} {},{} {},{}",
                                r2(q[0]),
                                r2(q[1]),
                                r2(q[0] - 1.8 * r),
                                r2(base),
                                r2(q[0] + 1.8 * r),
                                r2(base)
                            ),
                        )
                        .set("fill", "#ffffff"),
                );
                hatch(&mut g, [q[0] - 3.2 * r, base], [q[0] + 3.2 * r, base], r);
            }
            Some(0) => {
                if let Some((a, b)) = pose.guide_ends(topo, ext, j) {
                    hatch(&mut g, frame.to_pixel(a), frame.to_pixel(b), r);
                }
            }
            Some(k) => {
                // The frame slides in a guide of a moving link: a fixed block.
                let corners = block_corners(
                    pose.on(topo, j, 0),
                    pose.guides[j],
                    ext.block,
                    frame.scale,
                    style,
                );
                g.append(block(&corners.map(|p| frame.to_pixel(p)), colour(k), 1.5));
            }
        }
    }
    g
}

/// A base line from `a` to `b` (px) with short hatches on its lower (right-hand) side.
fn hatch(g: &mut Group, a: [f64; 2], b: [f64; 2], r: f64) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len.is_nan() || len <= 0.0 {
        return;
    }
    let t = [dx / len, dy / len];
    // The normal pointing to the right of a→b on screen (below a line drawn left to right).
    let n = [-t[1], t[0]];
    let mut d = Data::new()
        .move_to((r2(a[0]), r2(a[1])))
        .line_to((r2(b[0]), r2(b[1])));
    let step = (1.4 * r).max(4.0);
    let h = 1.6 * r;
    let mut s = step * 0.5;
    while s < len {
        let p = [a[0] + t[0] * s, a[1] + t[1] * s];
        let q = [
            p[0] + h * (n[0] - t[0]) * 0.7,
            p[1] + h * (n[1] - t[1]) * 0.7,
        ];
        d = d
            .move_to((r2(p[0]), r2(p[1])))
            .line_to((r2(q[0]), r2(q[1])));
        s += step;
    }
    g.append(Path::new().set("d", d).set("fill", "none"));
}

/// An arrow from `a` to `b` (px): a line and a filled head.
pub(crate) fn arrow(a: [f64; 2], b: [f64; 2], width: f64, c: &str) -> Group {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    let mut g = Group::new();
    if len.is_nan() || len <= 0.0 {
        return g;
    }
    let t = [dx / len, dy / len];
    let n = [-t[1], t[0]];
    let head = (4.0 * width).max(8.0).min(0.6 * len.max(1.0));
    let base = [b[0] - t[0] * head, b[1] - t[1] * head];
    g.append(
        Line::new()
            .set("x1", r2(a[0]))
            .set("y1", r2(a[1]))
            .set("x2", r2(base[0]))
            .set("y2", r2(base[1]))
            .set("stroke", c)
            .set("stroke-width", r2(width)),
    );
    let w = 0.4 * head;
    g.append(
        Polygon::new()
            .set(
                "points",
                format!(
                    "{},{} {},{} {},{}",
                    r2(b[0]),
                    r2(b[1]),
                    r2(base[0] + n[0] * w),
                    r2(base[1] + n[1] * w),
                    r2(base[0] - n[0] * w),
                    r2(base[1] - n[1] * w)
                ),
            )
            .set("fill", c),
    );
    g
}

/// A text label.
pub(crate) fn text(s: &str, q: [f64; 2], size: f64, c: &str) -> Text {
    Text::new(s)
        .set("x", r2(q[0]))
        .set("y", r2(q[1]))
        .set("font-family", "sans-serif")
        .set("font-size", size)
        .set("fill", c)
}

/// Places labels next to their points, moving one down while it would overlap another.
#[derive(Debug, Default)]
pub(crate) struct Labels {
    placed: Vec<[f64; 2]>,
}

impl Labels {
    pub(crate) fn place(&mut self, q: [f64; 2], style: &Style) -> [f64; 2] {
        let off = style.hinge_radius + 3.0;
        let mut p = [q[0] + off, q[1] - off];
        for _ in 0..6 {
            if self
                .placed
                .iter()
                .all(|o| (o[0] - p[0]).abs() > 12.0 || (o[1] - p[1]).abs() > 12.0)
            {
                break;
            }
            p[1] += 14.0;
        }
        self.placed.push(p);
        p
    }
}

/// The input's sense of motion: an arc arrow about a crank's pivot, or a straight arrow along
/// a slider's guide, with its symbol (ω1 or v1).
pub(crate) fn input_arrow(topo: &Topo, pose: &Pose, frame: &Frame, style: &Style) -> Option<Group> {
    let j = topo.input_joint()?;
    let sense = if pose.input.rate < 0.0 { -1.0 } else { 1.0 };
    let r = style.hinge_radius.max(2.0);
    let c = "#000000";
    let mut g = Group::new();
    if topo.crank {
        let (q0, radius, theta) = crank_arc(topo, pose, frame, style)?;
        let (arc, label) = arc_arrow(q0, radius, theta, sense, r, c);
        g.append(arc);
        if style.labels {
            g.append(text("ω1", label, 14.0, c));
        }
    } else {
        let d = pose.guides[j];
        let p = pose.at(topo, j);
        let q = frame.to_pixel(p);
        let dp = [d.x, -d.y];
        let n = [-dp[1], dp[0]];
        let a = [q[0] + n[0] * 5.0 * r, q[1] + n[1] * 5.0 * r];
        let b = [
            a[0] + sense * dp[0] * 8.0 * r,
            a[1] + sense * dp[1] * 8.0 * r,
        ];
        g.append(arrow(a, b, 1.5, c));
        if style.labels {
            g.append(text("v1", [b[0] + 4.0, b[1] - 4.0], 14.0, c));
        }
    }
    Some(g)
}

/// Where a crank's arc arrow goes: the pivot's pixel, the radius (px) and the direction of
/// the arc's middle (opposite the crank, rad on the picture).
fn crank_arc(
    topo: &Topo,
    pose: &Pose,
    frame: &Frame,
    style: &Style,
) -> Option<([f64; 2], f64, f64)> {
    let j = topo.input_joint()?;
    let r = style.hinge_radius.max(2.0);
    let pivot = pose.joints[j][0];
    let q0 = frame.to_pixel(pivot);
    // The crank's direction: to its farthest joint.
    let tip = topo.link_joints[topo.input]
        .iter()
        .map(|&i| pose.on(topo, i, topo.input))
        .max_by(|a, b| (a - pivot).norm().total_cmp(&(b - pivot).norm()))?;
    let len = (tip - pivot).norm() * frame.scale;
    let radius = (0.5 * len).clamp(3.5 * r, 32.0_f64.max(3.5 * r));
    let theta = (tip - pivot).y.atan2((tip - pivot).x) + std::f64::consts::PI;
    Some((q0, radius, theta))
}

/// The frame that shows `cover` and the input's arrow with its label: fitted once to the
/// linkage, then again with the arrow's reach (a fixed size in pixels) added.
pub(crate) fn fit_with_input(
    topo: &Topo,
    pose: &Pose,
    cover: &mut Vec<Point2<f64>>,
    style: &Style,
) -> Result<Frame> {
    let f = fit(cover, style)?;
    let reach = if topo.crank {
        crank_arc(topo, pose, &f, style).map(|(q0, radius, theta)| (q0, radius + 24.0, theta))
    } else {
        topo.input_joint().map(|j| {
            let q = f.to_pixel(pose.at(topo, j));
            // The arrow lies off the guide along the picture's normal (d_y, d_x) px.
            let d = pose.guides[j];
            (q, 14.0 * style.hinge_radius.max(2.0), (-d.x).atan2(d.y))
        })
    };
    let Some((q0, radius, theta)) = reach else {
        return Ok(f);
    };
    for i in 0..=8 {
        let a = theta + (-1.3 + 2.6 * f64::from(i) / 8.0);
        cover.push(f.to_world([q0[0] + radius * a.cos(), q0[1] - radius * a.sin()]));
    }
    fit(cover, style)
}

/// An arc arrow about the pixel `q0`, of radius `radius` px, spanning two radians about the
/// direction `theta` (rad, counter-clockwise on the picture), turning counter-clockwise for
/// `sense` > 0; and a place for its label, outside the arc's middle.
pub(crate) fn arc_arrow(
    q0: [f64; 2],
    radius: f64,
    theta: f64,
    sense: f64,
    r: f64,
    c: &str,
) -> (Group, [f64; 2]) {
    let at = |a: f64| [q0[0] + radius * a.cos(), q0[1] - radius * a.sin()];
    let n = 24;
    let mut d = Data::new();
    let mut last = [0.0; 2];
    let mut prev = [0.0; 2];
    for i in 0..=n {
        let a = theta + sense * (-1.0 + 2.0 * f64::from(i) / f64::from(n));
        let p = at(a);
        d = if i == 0 {
            d.move_to((r2(p[0]), r2(p[1])))
        } else {
            d.line_to((r2(p[0]), r2(p[1])))
        };
        prev = last;
        last = p;
    }
    let mut g = Group::new();
    g.append(
        Path::new()
            .set("d", d)
            .set("fill", "none")
            .set("stroke", c)
            .set("stroke-width", 1.5),
    );
    // The head along the arc's last chord, a little past its end.
    let t = [last[0] - prev[0], last[1] - prev[1]];
    let tl = t[0].hypot(t[1]).max(1e-9);
    let end = [last[0] + t[0] / tl * 2.4 * r, last[1] + t[1] / tl * 2.4 * r];
    g.append(arrow(last, end, 1.5, c));
    let l = at(theta);
    let out = [l[0] - q0[0], l[1] - q0[1]];
    let ol = out[0].hypot(out[1]).max(1e-9);
    let label = [
        l[0] + out[0] / ol * 12.0 - 6.0,
        l[1] + out[1] / ol * 12.0 + 5.0,
    ];
    (g, label)
}

/// `x` with about four significant digits, for a label.
pub(crate) fn short(x: f64) -> String {
    let a = x.abs();
    if a >= 1000.0 || a == 0.0 {
        format!("{x:.0}")
    } else if a >= 100.0 {
        format!("{x:.1}")
    } else if a >= 10.0 {
        format!("{x:.2}")
    } else if a >= 0.01 {
        format!("{x:.3}")
    } else {
        format!("{x:.3e}")
    }
}

/// The SVG document of a picture: size, view box and a white background.
pub(crate) fn document(style: &Style, title: &str) -> svg::Document {
    svg::Document::new()
        .set("width", style.width)
        .set("height", style.height)
        .set("viewBox", (0, 0, style.width, style.height))
        .add(svg::node::element::Title::new(title))
        .add(
            svg::node::element::Rectangle::new()
                .set("width", style.width)
                .set("height", style.height)
                .set("fill", "#ffffff"),
        )
}

/// The labels of every joint and named point at `pose`.
pub(crate) fn labels(
    topo: &Topo,
    pose: &Pose,
    frame: &Frame,
    style: &Style,
    placed: &mut Labels,
) -> Group {
    let mut g = Group::new();
    for (j, name) in topo.joint_names.iter().enumerate() {
        let p = placed.place(frame.to_pixel(pose.at(topo, j)), style);
        g.append(text(name, p, 13.0, "#111111"));
    }
    for (i, name) in topo.point_names.iter().enumerate() {
        let p = placed.place(frame.to_pixel(pose.points[i]), style);
        g.append(text(name, p, 13.0, colour(topo.point_link[i])));
    }
    g
}

/// One whole position drawn with `pen`: the moving links, then their hinges.
pub(crate) fn position(
    topo: &Topo,
    pose: &Pose,
    ext: &Extents,
    frame: &Frame,
    style: &Style,
    pen: Pen,
) -> Group {
    let map = |p: Point2<f64>| frame.to_pixel(p);
    let mut g = Group::new();
    if pen.opacity < 1.0 {
        g = g.set("opacity", pen.opacity);
    }
    for k in 1..topo.links() {
        g.append(link_body(topo, pose, ext, k, frame.scale, style, pen, &map));
    }
    let small = Style {
        hinge_radius: style.hinge_radius * pen.hinge,
        ..style.clone()
    };
    for k in 1..topo.links() {
        g.append(link_hinges(topo, pose, k, &small, &map));
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linkage::bundled;

    #[test]
    fn the_hull_keeps_the_corners_counter_clockwise() {
        let p = |x, y| Point2::new(x, y);
        let h = hull(&[
            p(0.0, 0.0),
            p(1.0, 1.0),
            p(0.5, 0.5),
            p(1.0, 0.0),
            p(0.0, 1.0),
        ]);
        assert_eq!(h, [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]);
        // Collinear points: the two ends.
        assert_eq!(hull(&[p(0.0, 0.0), p(1.0, 0.0), p(2.0, 0.0)]).len(), 2);
    }

    #[test]
    fn labels_move_off_each_other() {
        let style = Style::default();
        let mut l = Labels::default();
        let a = l.place([100.0, 100.0], &style);
        let b = l.place([100.0, 100.0], &style);
        let c = l.place([300.0, 100.0], &style);
        assert_eq!(a, [108.0, 92.0]);
        assert_eq!(b, [108.0, 106.0]);
        assert_eq!(c, [308.0, 92.0]);
    }

    #[test]
    fn short_numbers_keep_four_digits() {
        assert_eq!(short(1469.4), "1469");
        assert_eq!(short(726.94), "726.9");
        assert_eq!(short(-0.4624), "-0.462");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(1.5e-5), "1.500e-5");
    }

    #[test]
    fn a_slider_travels_along_its_guide() {
        let plan = Plan::new(&bundled::shaper()).unwrap();
        let topo = Topo::new(&plan);
        let q = plan.joint_id("Q").unwrap().index();
        assert_eq!(topo.guide[q], Some(0));
        let mut ext = Extents::new(&topo);
        for k in 0..36 {
            let a = plan
                .kinematics(Motion::new(f64::from(k) * 0.1745, 1.0, 0.0))
                .unwrap();
            ext.add(&topo, &Pose::of(&a).unwrap());
        }
        let [lo, hi] = ext.travel[q];
        // The ram's stroke, about 0.3 m for this shaper, on either side of its reference.
        assert!(hi - lo > 0.2 && hi - lo < 0.5, "{lo} {hi}");
        // A hinge has no travel.
        assert_eq!(ext.travel[0], [f64::INFINITY, f64::NEG_INFINITY]);
    }

    #[test]
    fn a_picture_of_one_point_has_no_frame() {
        let style = Style::default();
        assert!(fit(&[Point2::new(1.0, 1.0)], &style).is_err());
        let f = fit(&[Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)], &style).unwrap();
        assert_eq!(f.scale, 720.0);
        assert_eq!(f.to_pixel(Point2::new(0.5, 0.0)), [400.0, 300.0]);
    }
}
