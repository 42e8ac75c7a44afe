//! A hinge of three or more links, as a person draws it, turned into the equivalent binary
//! joints the engine solves: a revolute joint listed by k links is k − 1 joints at one place,
//! a star from one of them (the centre) to each of the others.
//!
//! The centre is the link nearest the frame (or an input) in the graph of links that share
//! joints: in attachment order it is known first, so each other link gets a known joint at
//! the hinge, as the Assur decomposition needs (a star from a link known late would give a
//! group two joints at one place). The first binary joint keeps the hinge's name, so every
//! reading by that name works; the others are named `"B:link"`, the hinge `B` as link `link`
//! holds it. A description without such a hinge is used as it is, unchanged and uncopied.

use super::description::{At, JointKind, Linkage, LoadSpec};
use super::plan::bad;
use crate::error::{Error, Result};
use std::borrow::Cow;
use std::collections::{HashMap, HashSet, VecDeque};

/// `linkage` with every hinge of three or more links expanded to binary joints.
///
/// # Errors
/// [`Error::Description`](crate::Error::Description) naming the joint: a prismatic joint
/// listed by more than two links, or an expanded joint's name (`"B:link"`) already taken.
pub(crate) fn binary_joints(linkage: &Linkage) -> Result<Cow<'_, Linkage>> {
    let owners = owners(linkage);
    let multi: Vec<usize> = (0..linkage.joints.len())
        .filter(|&j| {
            owners
                .get(linkage.joints[j].name.as_str())
                .map_or(0, Vec::len)
                > 2
        })
        .collect();
    if multi.is_empty() {
        return Ok(Cow::Borrowed(linkage));
    }
    let depth = depths(linkage, &owners);
    let mut taken: HashSet<String> = linkage.joints.iter().map(|j| j.name.clone()).collect();
    taken.extend(
        linkage
            .links
            .iter()
            .flat_map(|l| l.points.iter().map(|p| p.name.clone())),
    );
    let mut out = linkage.clone();
    for j in multi {
        let joint = &linkage.joints[j];
        let item = format!("joint {}", joint.name);
        if matches!(joint.kind, JointKind::Prismatic { .. }) {
            return Err(bad(
                item,
                "is prismatic and listed by more than two links; a sliding pair joins two",
            ));
        }
        let mut held = owners[joint.name.as_str()].clone();
        // The nearest first (a stable sort keeps the listed order among equals).
        held.sort_by_key(|&k| depth[k]);
        let centre = held[0];
        for &k in &held[2..] {
            let name = format!("{}:{}", joint.name, linkage.links[k].name);
            if !taken.insert(name.clone()) {
                return Err(bad(
                    item,
                    format!(
                        "joins {} links, and the name {name} of its part is taken",
                        held.len()
                    ),
                ));
            }
            let mut part = joint.clone();
            part.name.clone_from(&name);
            out.joints.push(part);
            out.links[centre].joints.push(name.clone());
            rename_on(&mut out, k, &joint.name, &name);
        }
    }
    Ok(Cow::Owned(out))
}

/// A description error of the expanded `linkage` with each hinge of three or more links
/// named, and how it was taken: a fault in the structure may come from there.
pub(crate) fn explain(e: Error, linkage: &Linkage) -> Error {
    let Error::Description { item, mut problem } = e else {
        return e;
    };
    let owners = owners(linkage);
    for j in &linkage.joints {
        if let Some(o) = owners.get(j.name.as_str())
            && o.len() > 2
        {
            let names: Vec<&str> = o.iter().map(|&k| linkage.links[k].name.as_str()).collect();
            problem.push_str(&format!(
                "; (hinge {} joins {} links [{}], taken as {} joints at one place)",
                j.name,
                o.len(),
                names.join(", "),
                o.len() - 1
            ));
        }
    }
    Error::Description { item, problem }
}

/// The links (description indices) that list each joint name, each once.
fn owners(linkage: &Linkage) -> HashMap<&str, Vec<usize>> {
    let mut owners: HashMap<&str, Vec<usize>> = HashMap::new();
    for (k, link) in linkage.links.iter().enumerate() {
        for j in &link.joints {
            let o = owners.entry(j.as_str()).or_default();
            if !o.contains(&k) {
                o.push(k);
            }
        }
    }
    owners
}

/// Every link's distance from the frame and the inputs in the graph of links sharing joints
/// (`usize::MAX` for a link not reached).
fn depths(linkage: &Linkage, owners: &HashMap<&str, Vec<usize>>) -> Vec<usize> {
    let n = linkage.links.len();
    let mut depth = vec![usize::MAX; n];
    let mut queue = VecDeque::new();
    let starts = std::iter::once(&linkage.frame)
        .chain(std::iter::once(&linkage.input.link))
        .chain(linkage.second_input.iter().map(|i| &i.link));
    for s in starts {
        if let Some(k) = linkage.links.iter().position(|l| &l.name == s)
            && depth[k] == usize::MAX
        {
            depth[k] = 0;
            queue.push_back(k);
        }
    }
    while let Some(k) = queue.pop_front() {
        for j in &linkage.links[k].joints {
            for &o in owners.get(j.as_str()).into_iter().flatten() {
                if depth[o] == usize::MAX {
                    depth[o] = depth[k] + 1;
                    queue.push_back(o);
                }
            }
        }
    }
    depth
}

/// Link `k` holds the hinge `old` as the joint `new`: its joint list, its reference
/// direction and the ends of springs and dampers fastened to it there say so.
fn rename_on(out: &mut Linkage, k: usize, old: &str, new: &str) {
    let swap = |s: &mut String| {
        if s == old {
            new.clone_into(s);
        }
    };
    let link = &mut out.links[k];
    link.joints.iter_mut().for_each(swap);
    if let Some(r) = &mut link.reference {
        r.iter_mut().for_each(swap);
    }
    let link_name = link.name.clone();
    for load in &mut out.loads {
        if let LoadSpec::Spring { ends, .. } | LoadSpec::Damper { ends, .. } = load {
            for e in ends.iter_mut() {
                if e.link.as_deref() == Some(link_name.as_str())
                    && let At::Name(n) = &mut e.at
                {
                    swap(n);
                }
            }
        }
    }
}
