//! What a picture shows, in the plane of the linkage: the structure of a plan read once
//! ([`Topo`]), one solved position as plain points ([`Pose`]), the travel of every slider on
//! its guide ([`Extents`]), the outline of a link's body and of a slider's block, where the
//! input's arrow goes, and the frame that fits them all.

use super::frame::Frame;
use super::style::Style;
use crate::error::{Error, Result};
use crate::kinematics::Motion;
use crate::linkage::{Kinematics, Plan};
use nalgebra::{Point2, Vector2};

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
pub(crate) fn hull(points: &[Point2<f64>]) -> Vec<Point2<f64>> {
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

/// The corners of a slider block at `p` along `d`: half-length `half` m, and a height of four
/// hinge radii (so that the hinge on it shows).
pub(crate) fn block_corners(
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

/// Where a crank's arc arrow goes: the pivot's pixel, the radius (px) and the direction of
/// the arc's middle (opposite the crank, rad on the picture).
pub(crate) fn crank_arc(
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

#[cfg(all(test, feature = "serde"))]
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
