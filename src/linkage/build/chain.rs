#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The kinematic chain of a plan, piece by piece: the links with the frame first, the joints
//! as the edges of the structure, the input links, and the local coordinates of joints,
//! points and masses in the links' frames.

use super::reference::{
    finite_num, finite_pair, non_negative, place, reference_direction, Frame, Names,
};
use crate::angle::direction;
use crate::error::Result;
use crate::linkage::description::{Drive, Input, JointKind, Linkage};
use crate::linkage::plan::{bad, InputPlan, JointPlan, LinkPlan, PointPlan};
use crate::linkage::structure::{Edge, Pair};
use nalgebra::{Point2, Vector2};

/// The links reordered with the frame first.
pub(super) struct Links {
    /// The description's index of each planned link.
    pub order: Vec<usize>,
    /// The planned index of each of the description's links.
    pub index: Vec<usize>,
    /// The planned links' names.
    pub names: Vec<String>,
}

impl Links {
    /// Link 0 is the frame: the description's links reordered so that it comes first, the
    /// others in the order written (so that "the last link written" is the last planned).
    pub fn new(linkage: &Linkage, names: &Names<'_>) -> Result<Self> {
        let frame = names.link(&linkage.frame, "field frame")?;
        let order: Vec<usize> = std::iter::once(frame)
            .chain((0..linkage.links.len()).filter(|&k| k != frame))
            .collect();
        let mut index = vec![0; order.len()];
        for (new, &old) in order.iter().enumerate() {
            index[old] = new;
        }
        let names = order
            .iter()
            .map(|&k| linkage.links[k].name.clone())
            .collect();
        Ok(Self {
            order,
            index,
            names,
        })
    }
}

/// The reference position of joint `j`.
pub(super) fn joint_at(linkage: &Linkage, j: usize) -> Point2<f64> {
    let a = linkage.joints[j].at;
    Point2::new(a[0], a[1])
}

/// The guide direction of joint `j` in the reference pose (zero for a hinge).
pub(super) fn joint_direction(linkage: &Linkage, j: usize) -> Vector2<f64> {
    match &linkage.joints[j].kind {
        JointKind::Prismatic { direction, .. } => Vector2::new(direction[0], direction[1]),
        JointKind::Revolute => Vector2::zeros(),
    }
}

/// The links that list each joint; each link's joints at least two (one for the frame).
fn owners(linkage: &Linkage, names: &Names<'_>, links: &Links) -> Result<Vec<Vec<usize>>> {
    let frame = links.order[0];
    let mut owners: Vec<Vec<usize>> = vec![Vec::new(); linkage.joints.len()];
    for (k, link) in linkage.links.iter().enumerate() {
        let item = format!("link {}", link.name);
        if link.joints.len() < 2 && k != frame {
            return Err(bad(
                item,
                format!(
                    "has {} joint(s); a moving link needs at least two",
                    link.joints.len()
                ),
            ));
        }
        for j in &link.joints {
            let ji = names.joint(j, &item)?;
            if owners[ji].contains(&links.index[k]) {
                return Err(bad(item, format!("lists joint {j} twice")));
            }
            owners[ji].push(links.index[k]);
        }
    }
    Ok(owners)
}

/// The joints as the structure's edges: each joins exactly two links, a prismatic one with
/// its guide on one of them and a non-zero direction.
pub(super) fn edges(linkage: &Linkage, names: &Names<'_>, links: &Links) -> Result<Vec<Edge>> {
    let owners = owners(linkage, names, links)?;
    let mut edges = Vec::with_capacity(linkage.joints.len());
    for (j, joint) in linkage.joints.iter().enumerate() {
        let item = format!("joint {}", joint.name);
        finite_pair(&item, "at", joint.at)?;
        if owners[j].len() != 2 {
            let listed: Vec<&str> = owners[j].iter().map(|&k| links.names[k].as_str()).collect();
            return Err(bad(
                item,
                format!(
                    "is listed by {} link(s) [{}]; list it in each link it joins (a revolute \
                     joint may join three or more, a hinge of all of them; a prismatic one joins \
                     exactly two)",
                    owners[j].len(),
                    listed.join(", ")
                ),
            ));
        }
        let pair = match &joint.kind {
            JointKind::Revolute => Pair::Revolute,
            JointKind::Prismatic { guide, direction } => {
                let g = names.link(guide, &item)?;
                if !owners[j].contains(&links.index[g]) {
                    return Err(bad(
                        item,
                        format!("has its guide on link {guide}, which does not list it"),
                    ));
                }
                let d = finite_pair(&item, "direction", *direction)?;
                if !(d.norm() > 0.0) || !d.norm().is_finite() {
                    return Err(bad(item, "guide direction must be a non-zero vector"));
                }
                Pair::Prismatic
            }
        };
        edges.push(Edge {
            pair,
            links: [owners[j][0], owners[j][1]],
        });
    }
    Ok(edges)
}

/// The description's inputs (one, or two for a linkage of mobility 2) with their fields'
/// names.
pub(super) fn input_specs(linkage: &Linkage) -> Vec<(&Input, &'static str)> {
    std::iter::once((&linkage.input, "field input"))
        .chain(
            linkage
                .second_input
                .as_ref()
                .map(|i| (i, "field second_input")),
        )
        .collect()
}

/// The input links and their joints with the frame.
pub(super) fn input_links(
    specs: &[(&Input, &'static str)],
    names: &Names<'_>,
    links: &Links,
    edges: &[Edge],
) -> Result<Vec<(usize, usize)>> {
    let mut inputs: Vec<(usize, usize)> = Vec::with_capacity(specs.len());
    for &(spec, field) in specs {
        let item = format!("{field}.link");
        let input = links.index[names.link(&spec.link, &item)?];
        if input == 0 {
            return Err(bad(item, "the input cannot be the frame"));
        }
        if inputs.iter().any(|&(l, _)| l == input) {
            return Err(bad(item, "names the same link as the first input"));
        }
        let to_frame: Vec<usize> = (0..edges.len())
            .filter(|&j| edges[j].links.contains(&0) && edges[j].links.contains(&input))
            .collect();
        let [input_joint] = to_frame[..] else {
            return Err(bad(
                format!("link {}", links.names[input]),
                format!(
                    "is the input but has {} joints with the frame; it needs exactly one (a \
                     crank's pivot or a slider's guide)",
                    to_frame.len()
                ),
            ));
        };
        inputs.push((input, input_joint));
    }
    Ok(inputs)
}

/// Each input's plan and reference coordinate, its link's frame set.
pub(super) fn plan_inputs(
    linkage: &Linkage,
    specs: &[(&Input, &'static str)],
    inputs: &[(usize, usize)],
    edges: &[Edge],
    (names, links): (&Names<'_>, &Links),
    frames: &mut [Frame],
) -> Result<Vec<(InputPlan, f64)>> {
    let mut planned = Vec::with_capacity(inputs.len());
    for (&(input, joint), &(spec, field)) in inputs.iter().zip(specs) {
        let at = joint_at(linkage, joint);
        planned.push(match edges[joint].pair {
            Pair::Revolute => {
                let item = format!("link {}", links.names[input]);
                let reference = reference_direction(linkage, &links.order, input, names, &item)?
                    .ok_or_else(|| {
                        bad(&item, "the crank's joints coincide: it has no direction")
                    })?;
                frames[input] = Frame {
                    origin: at,
                    angle: reference,
                };
                check_drive(&spec.drive, &format!("{field}.drive"))?;
                (
                    InputPlan::Crank {
                        link: input,
                        joint,
                        pivot: at,
                        drive: spec.drive,
                    },
                    crate::angle::normalize(reference),
                )
            }
            Pair::Prismatic => {
                let angle = direction(joint_direction(linkage, joint));
                frames[input] = Frame { origin: at, angle };
                (
                    InputPlan::Slider {
                        link: input,
                        joint,
                        at,
                        angle,
                    },
                    0.0,
                )
            }
        });
    }
    Ok(planned)
}

/// Checks a gear drive's data; `item` names the input's field.
fn check_drive(drive: &Drive, item: &str) -> Result<()> {
    if let Drive::Gear {
        pitch_radius,
        pitch_angle,
        pressure_angle,
    } = *drive
    {
        if !(finite_num(item, "pitch_radius", pitch_radius)? > 0.0) {
            return Err(bad(
                item,
                format!("pitch_radius must be > 0, got {pitch_radius}"),
            ));
        }
        finite_num(item, "pitch_angle", pitch_angle)?;
        let a = finite_num(item, "pressure_angle", pressure_angle)?;
        if !(0.0..std::f64::consts::FRAC_PI_2).contains(&a) {
            return Err(bad(
                item,
                format!("pressure_angle must lie in [0, π/2), got {a} rad"),
            ));
        }
    }
    Ok(())
}

/// Every joint's local coordinates on its two links, and a prismatic joint's guide.
pub(super) fn plan_joints(
    linkage: &Linkage,
    edges: &[Edge],
    (names, links): (&Names<'_>, &Links),
    frames: &[Frame],
) -> Vec<JointPlan> {
    edges
        .iter()
        .enumerate()
        .map(|(j, e)| JointPlan {
            links: e.links,
            local: e.links.map(|k| frames[k].local(joint_at(linkage, j))),
            prismatic: match &linkage.joints[j].kind {
                JointKind::Revolute => None,
                JointKind::Prismatic { guide, .. } => {
                    let g = links.index[names.links[guide.as_str()]];
                    let side = usize::from(e.links[1] == g);
                    let d = direction(joint_direction(linkage, j));
                    Some((side, e.links.map(|k| d - frames[k].angle)))
                }
            },
        })
        .collect()
}

/// The named points' names and local coordinates.
pub(super) fn plan_points(
    linkage: &Linkage,
    links: &Links,
    frames: &[Frame],
) -> Result<(Vec<String>, Vec<PointPlan>)> {
    let mut point_names = Vec::new();
    let mut points = Vec::new();
    for (k, link) in linkage.links.iter().enumerate() {
        for p in &link.points {
            let item = format!("point {}", p.name);
            let xy = finite_pair(&item, "at", p.at)?;
            let li = links.index[k];
            let local = frames[li].local(Point2::from(xy));
            if !(local.x.is_finite() && local.y.is_finite()) {
                return Err(bad(
                    item,
                    format!(
                        "its coordinates on link {} overflow: it lies too far from the link's \
                         joints",
                        links.names[li]
                    ),
                ));
            }
            point_names.push(p.name.clone());
            points.push(PointPlan { link: li, local });
        }
    }
    Ok((point_names, points))
}

/// The distance of two joints' reference positions.
fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

/// The largest distance between two joints in the reference pose (its joints' positions
/// checked finite): every pair for a small linkage; beyond 64 joints, the antipodal pairs of
/// the joints' convex hull (rotating calipers), so that a description of many joints is
/// planned in n log n.
pub(super) fn reference_size(linkage: &Linkage) -> Result<f64> {
    let at: Vec<[f64; 2]> = linkage.joints.iter().map(|j| j.at).collect();
    let size = if at.len() <= 64 {
        at.iter()
            .flat_map(|&j| at.iter().map(move |&k| distance(j, k)))
            .fold(0.0, f64::max)
    } else {
        hull_diameter(&at)
    };
    if !size.is_finite() {
        // The largest distance between two joints is past f64's range (not "inf m").
        return Err(bad(
            "linkage",
            format!(
                "its size overflows (two joints are more than {:.1e} m apart)",
                f64::MAX
            ),
        ));
    }
    Ok(size)
}

/// The largest distance between two of the points `at` (finite), from the antipodal pairs of
/// their convex hull. The hull is found on the points scaled by a power of two (exactly), so
/// that its cross products cannot overflow; the distances are those of the given points.
fn hull_diameter(at: &[[f64; 2]]) -> f64 {
    let big = at
        .iter()
        .flat_map(|p| [p[0].abs(), p[1].abs()])
        .fold(0.0, f64::max);
    if big == 0.0 {
        return 0.0;
    }
    // 2^-e with 2^e ≥ big: every scaled coordinate within [−1, 1].
    let e = big.log2().ceil().clamp(-1000.0, 1023.0);
    let scale = 2f64.powf(-e);
    let scaled: Vec<[f64; 2]> = at.iter().map(|p| [p[0] * scale, p[1] * scale]).collect();
    let mut order: Vec<usize> = (0..at.len()).collect();
    order.sort_by(|&a, &b| {
        scaled[a][0]
            .total_cmp(&scaled[b][0])
            .then(scaled[a][1].total_cmp(&scaled[b][1]))
    });
    let cross = |o: usize, a: usize, b: usize| {
        let (o, a, b) = (scaled[o], scaled[a], scaled[b]);
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    // Andrew's monotone chain, counter-clockwise, collinear points left out.
    let mut hull: Vec<usize> = Vec::with_capacity(2 * order.len());
    for pass in 0..2 {
        let start = hull.len();
        let points: Box<dyn Iterator<Item = &usize>> = if pass == 0 {
            Box::new(order.iter())
        } else {
            Box::new(order.iter().rev())
        };
        for &p in points {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    let h = hull.len();
    let d = |a: usize, b: usize| distance(at[hull[a % h]], at[hull[b % h]]);
    match h {
        0 => 0.0,
        1 => 0.0,
        2 => d(0, 1),
        _ => {
            let area = |i: usize, k: usize, j: usize| cross(hull[i % h], hull[k % h], hull[j % h]);
            let mut best: f64 = 0.0;
            let mut j = 1;
            for i in 0..h {
                let k = i + 1;
                let mut steps = 0;
                while steps < h && area(i, k, j + 1) > area(i, k, j) {
                    j += 1;
                    steps += 1;
                }
                // The pair found, and its neighbours against rounding in the areas.
                for m in [j + h - 1, j, j + 1] {
                    best = best.max(d(i, m)).max(d(k, m));
                }
            }
            best
        }
    }
}

/// Every link's reference direction, mass properties and size.
pub(super) fn plan_links(
    linkage: &Linkage,
    edges: &[Edge],
    (names, links): (&Names<'_>, &Links),
    frames: &[Frame],
) -> Result<Vec<LinkPlan>> {
    let mut planned = Vec::with_capacity(links.names.len());
    for (li, &k) in links.order.iter().enumerate() {
        let link = &linkage.links[k];
        let item = format!("link {}", link.name);
        let reference = if li == 0 {
            frames[0].angle
        } else {
            reference_direction(linkage, &links.order, li, names, &item)?
                .unwrap_or(frames[li].angle)
        };
        let (mass, inertia, centre) = match &link.mass {
            None => (0.0, 0.0, Vector2::zeros()),
            Some(m) => {
                let c = place(&m.centre, names, li, &links.index, &item, "mass.centre")?;
                let centre = frames[li].local(c);
                if !(centre.x.is_finite() && centre.y.is_finite()) {
                    return Err(bad(
                        &item,
                        format!(
                            "mass.centre [{}, {}] overflows on the link: it lies too far from \
                             the link's joints",
                            c.x, c.y
                        ),
                    ));
                }
                (
                    non_negative(&item, "mass.m", m.m)?,
                    non_negative(&item, "mass.j", m.j)?,
                    centre,
                )
            }
        };
        planned.push(LinkPlan {
            angle_offset: reference - frames[li].angle,
            mass,
            inertia,
            centre,
            size: 0.0,
        });
    }
    for (j, e) in edges.iter().enumerate() {
        for k in e.links {
            let local = frames[k].local(joint_at(linkage, j)).norm();
            if !local.is_finite() {
                return Err(bad(
                    format!("joint {}", linkage.joints[j].name),
                    format!(
                        "its distance from the origin of link {} overflows",
                        links.names[k]
                    ),
                ));
            }
            planned[k].size = planned[k].size.max(local);
        }
    }
    Ok(planned)
}
