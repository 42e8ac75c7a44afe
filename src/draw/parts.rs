//! The parts of a drawn linkage: the scene ([`super::scene`]) written with the primitives
//! ([`super::primitives`]) — a link's body, its hinges, the ground, the input's arrow, the
//! labels, and a whole position drawn with one [`Pen`].

use super::frame::Frame;
use super::primitives::{arc_arrow, arrow, block, colour, dot, hatch, hinge, r2, text, Labels};
use super::scene::{block_corners, crank_arc, hull, Extents, Pose, Topo};
use super::style::Style;
use nalgebra::Point2;
use svg::node::element::{Group, Line, Polygon};
use svg::Node;

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
