#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The description read in its reference pose: names checked and looked up, numbers checked
//! finite, each link's frame, and the places that joints, points and reference directions
//! name.

use crate::angle::{direction, perp};
use crate::error::Result;
use crate::linkage::description::{At, Linkage};
use crate::linkage::plan::bad;
use nalgebra::{Point2, Vector2};
use std::collections::HashMap;

pub(super) fn finite_pair(item: &str, field: &str, v: [f64; 2]) -> Result<Vector2<f64>> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(Vector2::new(v[0], v[1]))
    } else {
        Err(bad(
            item,
            format!("{field} must be finite, got [{}, {}]", v[0], v[1]),
        ))
    }
}

pub(super) fn finite_num(item: &str, field: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(item, format!("{field} must be finite, got {v}")))
    }
}

pub(super) fn non_negative(item: &str, field: &str, v: f64) -> Result<f64> {
    if finite_num(item, field, v)? >= 0.0 {
        Ok(v)
    } else {
        Err(bad(item, format!("{field} must be ≥ 0, got {}", shown(v))))
    }
}

/// A description's number echoed in a message as its file may write it: the shortest text
/// that reads back to it, in scientific notation outside [10⁻⁴, 10⁹) (`-1e308`, not its 309
/// digits).
pub(super) fn shown(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The frame of a link in the reference pose: its origin and direction angle.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub origin: Point2<f64>,
    pub angle: f64,
}

impl Frame {
    pub fn local(&self, p: Point2<f64>) -> Vector2<f64> {
        let e = crate::angle::unit(self.angle);
        let r = p - self.origin;
        Vector2::new(r.dot(&e), r.dot(&perp(e)))
    }
}

/// Name look-up tables of a description.
pub(super) struct Names<'a> {
    pub links: HashMap<&'a str, usize>,
    pub joints: HashMap<&'a str, usize>,
    pub points: HashMap<&'a str, (usize, Point2<f64>)>,
    pub joint_at: Vec<Point2<f64>>,
}

impl<'a> Names<'a> {
    pub fn link(&self, name: &str, item: &str) -> Result<usize> {
        self.links
            .get(name)
            .copied()
            .ok_or_else(|| bad(item, format!("names the unknown link \"{name}\"")))
    }

    pub fn joint(&self, name: &str, item: &str) -> Result<usize> {
        self.joints
            .get(name)
            .copied()
            .ok_or_else(|| bad(item, format!("names the unknown joint \"{name}\"")))
    }
}

/// Checks names: unique, non-empty; builds the look-up tables.
pub(super) fn index_names(linkage: &Linkage) -> Result<Names<'_>> {
    let mut links = HashMap::new();
    for (k, l) in linkage.links.iter().enumerate() {
        if l.name.is_empty() || links.insert(l.name.as_str(), k).is_some() {
            return Err(bad(
                format!("link \"{}\"", l.name),
                "link names must be non-empty and unique",
            ));
        }
    }
    let mut joints = HashMap::new();
    for (j, jt) in linkage.joints.iter().enumerate() {
        if jt.name.is_empty() || joints.insert(jt.name.as_str(), j).is_some() {
            return Err(bad(
                format!("joint \"{}\"", jt.name),
                "joint names must be non-empty and unique",
            ));
        }
    }
    let mut points = HashMap::new();
    for (k, l) in linkage.links.iter().enumerate() {
        for p in &l.points {
            if p.name.is_empty()
                || joints.contains_key(p.name.as_str())
                || points
                    .insert(p.name.as_str(), (k, Point2::new(p.at[0], p.at[1])))
                    .is_some()
            {
                return Err(bad(
                    format!("point \"{}\"", p.name),
                    "point names must be non-empty and unique among joints and points",
                ));
            }
        }
    }
    if linkage.links.is_empty() {
        return Err(bad("field links", "a linkage needs links"));
    }
    let joint_at = linkage
        .joints
        .iter()
        .map(|j| Point2::new(j.at[0], j.at[1]))
        .collect();
    Ok(Names {
        links,
        joints,
        points,
        joint_at,
    })
}

/// The position of a named joint or point of the link with the new index `li`, or given
/// coordinates.
pub(super) fn place(
    at: &At,
    names: &Names<'_>,
    li: usize,
    link_index: &[usize],
    item: &str,
    field: &str,
) -> Result<Point2<f64>> {
    match at {
        At::Coords(c) => Ok(Point2::from(finite_pair(item, field, *c)?)),
        At::Name(n) => {
            if let Some(&(k, p)) = names.points.get(n.as_str()) {
                return if link_index[k] == li {
                    Ok(p)
                } else {
                    Err(bad(
                        item,
                        format!("{field} names point {n}, which is on another link"),
                    ))
                };
            }
            match names.joints.get(n.as_str()) {
                Some(&j) => Ok(names.joint_at[j]),
                None => Err(bad(
                    item,
                    format!("{field} names \"{n}\", which is neither a joint nor a point"),
                )),
            }
        }
    }
}

/// The angle of a link's declared reference direction in the reference pose.
pub(super) fn reference_direction(
    linkage: &Linkage,
    order: &[usize],
    li: usize,
    names: &Names<'_>,
    item: &str,
) -> Result<Option<f64>> {
    let link = &linkage.links[order[li]];
    let pos = |n: &str| -> Result<Point2<f64>> {
        if let Some(&j) = names.joints.get(n)
            && link.joints.iter().any(|x| x == n)
        {
            let a = linkage.joints[j].at;
            return Ok(Point2::new(a[0], a[1]));
        }
        if let Some(&(k, p)) = names.points.get(n)
            && k == order[li]
        {
            return Ok(p);
        }
        Err(bad(
            item,
            format!("reference names \"{n}\", which is not on this link"),
        ))
    };
    let (a, b) = match &link.reference {
        Some([a, b]) => (pos(a)?, pos(b)?),
        None => {
            // The first two distinct joints; a link whose joints all coincide (a slider
            // block) keeps the engine's frame: `None`. Each is a joint of this link by
            // construction, so it is looked up without the membership test of `pos`
            // (which would read the whole list for each: quadratic in a frame of many
            // joints).
            let at = |n: &str| -> Result<Point2<f64>> {
                names
                    .joints
                    .get(n)
                    .map(|&j| names.joint_at[j])
                    .ok_or_else(|| bad(item, format!("names the unknown joint \"{n}\"")))
            };
            let mut ps = link.joints.iter().map(|j| at(j));
            let Some(first) = ps.next().transpose()? else {
                return Ok(None);
            };
            let mut second = None;
            for p in ps {
                let p = p?;
                if p != first {
                    second = Some(p);
                    break;
                }
            }
            match second {
                Some(b) => (first, b),
                None => return Ok(None),
            }
        }
    };
    let d = b - a;
    // Not `d.norm() > 0`: on a linkage of 10⁻¹⁶² m the norm underflows between distinct points.
    if d.x == 0.0 && d.y == 0.0 {
        return Err(bad(
            item,
            "its reference direction joins two coincident points; name two distinct ones in \
             `reference`",
        ));
    }
    Ok(Some(direction(d)))
}
