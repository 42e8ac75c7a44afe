//! The workspace of a point of a linkage with two inputs, drawn over the linkage.

use super::parts::{self, Pen};
use super::primitives::{self, r2, Labels};
use super::scene::{self, Extents, Pose, Topo};
use super::{Picture, Style};
use crate::error::{Error, Result};
use crate::linkage::{Plan, Singularity, Workspace};
use nalgebra::Point2;
use svg::node::element::path::Data;
use svg::node::element::Path;
use svg::Node;

/// The fill of the region a point reaches.
pub const WORKSPACE_FILL: &str = "#bcd7f0";
/// The colour of the serial singular curves (det ∂P/∂q = 0).
pub const SERIAL_COLOUR: &str = "#d62728";
/// The colour of the curves where the linkage stops assembling.
pub const ASSEMBLY_COLOUR: &str = "#2ca02c";
/// The colour of the curves an isolated singular input maps to.
pub const ISOLATED_COLOUR: &str = "#9467bd";

/// The workspace `ws` of a point of `plan` ([`Plan::workspace`]): the region it reaches
/// filled ([`WORKSPACE_FILL`]) inside its outline, the serial singular curves
/// ([`SERIAL_COLOUR`]) and the curves where the linkage stops assembling
/// ([`ASSEMBLY_COLOUR`]) and those of isolated singular inputs ([`ISOLATED_COLOUR`]) over it, and the linkage in its reference pose on top. One scale on
/// both axes.
///
/// # Errors
/// [`Error::OutOfRange`] or [`Error::NonFinite`] naming the field of a bad style;
/// [`Error::Drawing`] for a workspace with no outline or a non-finite point in it; the
/// kinematics' errors at the reference pose.
///
/// # Examples
/// ```
/// use tmm::draw::{workspace, Style};
/// use tmm::linkage::{bundled, Plan, WorkspaceOptions};
/// let plan = Plan::new(&bundled::five_bar_robot())?;
/// let ws = plan.workspace("B", &WorkspaceOptions::default().with_samples(41).with_resolution(60))?;
/// let pic = workspace(&plan, &ws, &Style::default())?;
/// assert!(pic.svg.contains("workspace of B"));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn workspace(plan: &Plan, ws: &Workspace, style: &Style) -> Result<Picture> {
    style.check()?;
    let bad = |problem: &str| Error::Drawing {
        what: format!("the workspace of {}", ws.point),
        problem: problem.to_owned(),
    };
    if ws.boundary.iter().all(|l| l.len() < 2) {
        return Err(bad("it has no outline"));
    }
    let all = ws
        .boundary
        .iter()
        .flatten()
        .chain(ws.singular.iter().flat_map(|c| &c.points));
    if all.clone().any(|p| !(p.x.is_finite() && p.y.is_finite())) {
        return Err(bad("a point of it is not finite"));
    }
    let a = plan.kinematics(plan.chain.reference_motions())?;
    let topo = Topo::new(plan);
    let pose = Pose::of(&a)?;
    let mut ext = Extents::new(&topo);
    ext.add(&topo, &pose);
    let mut cover: Vec<Point2<f64>> = all.copied().collect();
    pose.cover(&topo, &ext, &mut cover);
    let frame = scene::fit_with_input(&topo, &pose, &mut cover, style)?;
    let title = format!("{} — workspace of {}", plan.name(), ws.point);
    let mut doc = primitives::document(style, &title);
    let line = |points: &[Point2<f64>], mut d: Data| {
        for (k, p) in points.iter().enumerate() {
            let q = frame.to_pixel(*p);
            let xy = (r2(q[0]), r2(q[1]));
            d = if k == 0 { d.move_to(xy) } else { d.line_to(xy) };
        }
        d
    };
    let mut region = Data::new();
    for l in ws.boundary.iter().filter(|l| l.len() >= 2) {
        region = line(l, region).close();
    }
    doc.append(
        Path::new()
            .set("d", region)
            .set("fill", WORKSPACE_FILL)
            .set("fill-rule", "evenodd")
            .set("stroke", "#1f4e79")
            .set("stroke-width", 1.2)
            .set("class", "workspace region"),
    );
    for c in ws.singular.iter().filter(|c| c.points.len() >= 2) {
        let (colour, class) = match c.kind {
            Singularity::Serial => (SERIAL_COLOUR, "singular serial"),
            Singularity::Assembly => (ASSEMBLY_COLOUR, "singular assembly"),
            Singularity::Isolated => (ISOLATED_COLOUR, "singular isolated"),
        };
        doc.append(
            Path::new()
                .set("d", line(&c.points, Data::new()))
                .set("fill", "none")
                .set("stroke", colour)
                .set("stroke-width", 2.0)
                .set("class", class),
        );
    }
    doc.append(parts::ground(&topo, &pose, &ext, &frame, style));
    doc.append(parts::position(
        &topo,
        &pose,
        &ext,
        &frame,
        style,
        Pen::NORMAL,
    ));
    if style.labels {
        doc.append(parts::labels(
            &topo,
            &pose,
            &frame,
            style,
            &mut Labels::default(),
        ));
    }
    Ok(Picture {
        svg: primitives::finish(&doc)?,
        frame,
        force_scale: None,
    })
}
