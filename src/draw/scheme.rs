//! The kinematic scheme of a linkage at one position.

use super::parts::{self, Pen};
use super::primitives::{self, Labels};
use super::scene::{self, Extents, Pose, Topo};
use super::{Picture, Style};
use crate::error::Result;
use crate::linkage::{Centre, Inputs, Plan};
use svg::Node;

/// The kinematic scheme of `plan` at the input `input` (a [`Motion`](crate::kinematics::Motion),
/// or both inputs' motions, [`Inputs::two`], for a linkage with two inputs): bars for binary links, filled
/// polygons for ternary and larger ones (each link in its own colour), hinges as circles,
/// sliders as blocks on their guides, the ground hatched under every fixed pivot and along
/// every fixed guide, the names of joints and points, and the input's sense of motion (the
/// sign of `input.rate`; counter-clockwise when it is zero). One scale on both axes.
///
/// # Errors
/// [`Error::OutOfRange`](crate::Error::OutOfRange) or [`Error::NonFinite`](crate::Error::NonFinite)
/// naming the field of a bad style ([`Style::check`]); the errors of [`Plan::position`] at
/// this input (non-finite, cannot be assembled). At a dead centre or a lock, where the rates
/// do not exist, the position is drawn all the same ([`Plan::position`]), at rest.
///
/// # Examples
/// The hinge B of the four-bar lands on the picture where its frame says:
/// ```
/// use tmm::draw::{scheme, Style};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::four_bar())?;
/// let input = Motion::new(0.5, 10.0, 0.0);
/// let pic = scheme(&plan, input, &Style::default())?;
/// let b = plan.kinematics(input)?.joint("B")?.p;
/// let [x, y] = pic.frame.to_pixel(b);
/// assert!(pic.svg.contains(&format!(r#"cx="{}""#, (x * 100.0).round() / 100.0)));
/// assert!(pic.svg.contains(&format!(r#"cy="{}""#, (y * 100.0).round() / 100.0)));
/// assert!(scheme(&plan, Motion::new(f64::NAN, 1.0, 0.0), &Style::default()).is_err());
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn scheme(plan: &Plan, input: impl Into<Inputs>, style: &Style) -> Result<Picture> {
    draw(plan, input.into(), style, false)
}

/// The kinematic scheme of [`scheme`] with the instant centres of every pair of links
/// ([`Plan::instant_centres`]) drawn over it: each centre that lies on the picture as a small
/// ring labelled `Iij` in the user's numbering of the links ([`InstantCentre::label`]: i, j
/// their places in the description's `links`, 0 the first written), its two links' names in
/// the label's `data-links` (`"crank|rocker"`), and a key of the numbers with the links' names
/// in the lower left corner. Centres off the picture or at infinity are not drawn.
///
/// [`InstantCentre::label`]: crate::linkage::InstantCentre::label
///
/// # Errors
/// As [`scheme`]; as [`Plan::instant_centres`].
///
/// # Examples
/// The four-bar (written frame, crank, coupler, rocker) has its centres I13 (crank and
/// rocker, by Kennedy) and I23 (the hinge B) on its picture:
/// ```
/// use tmm::draw::{scheme_with_centres, Style};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::four_bar())?;
/// let pic = scheme_with_centres(&plan, Motion::turning(1.2, 10.0), &Style::default())?;
/// assert!(pic.svg.contains("\nI13\n") && pic.svg.contains("\nI23\n"));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn scheme_with_centres(
    plan: &Plan,
    input: impl Into<Inputs>,
    style: &Style,
) -> Result<Picture> {
    draw(plan, input.into(), style, true)
}

fn draw(plan: &Plan, input: Inputs, style: &Style, with_centres: bool) -> Result<Picture> {
    style.check()?;
    // A scheme needs positions only: at a dead centre or a lock, where the rates do not
    // exist, the position-only solve still places every link (drawn at rest).
    let position = plan.position(input)?;
    let a = position.pose();
    let topo = Topo::new(plan);
    let pose = Pose::of(a)?;
    let mut ext = Extents::new(&topo);
    ext.add(&topo, &pose);
    let mut cover = Vec::new();
    pose.cover(&topo, &ext, &mut cover);
    let frame = scene::fit_with_input(&topo, &pose, &mut cover, style)?;
    let title = format!(
        "{} — kinematic scheme at input {}",
        plan.name(),
        values(input)
    );
    let mut doc = primitives::document(style, &title);
    doc.append(parts::ground(&topo, &pose, &ext, &frame, style));
    doc.append(parts::position(
        &topo,
        &pose,
        &ext,
        &frame,
        style,
        Pen::NORMAL,
    ));
    if let Some(arrow) = parts::input_arrow(&topo, &pose, &frame, style) {
        doc.append(arrow);
    }
    if with_centres {
        doc.append(centres(plan, a, &frame, style)?);
    }
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

/// The inputs' values for a title: `0.5000`, or `(0.5000, 1.2000)` for two inputs.
pub(crate) fn values(inputs: Inputs) -> String {
    match inputs.as_slice() {
        [m] => format!("{:.4}", m.value),
        ms => {
            let v: Vec<String> = ms.iter().map(|m| format!("{:.4}", m.value)).collect();
            format!("({})", v.join(", "))
        }
    }
}

/// The instant centres that lie on the picture: rings labelled `Iij` in the user's numbering,
/// and the key of that numbering.
fn centres(
    plan: &Plan,
    a: &crate::linkage::Kinematics<'_>,
    frame: &super::Frame,
    style: &Style,
) -> Result<svg::node::element::Group> {
    let mut g = svg::node::element::Group::new().set("class", "instant-centres");
    let names = plan.link_names();
    let mut key: Vec<(usize, &str)> = plan
        .link_ids()
        .map(|l| Ok((plan.link_number(l)?, names[l.index()].as_str())))
        .collect::<Result<_>>()?;
    key.sort_unstable();
    let key: Vec<String> = key.iter().map(|(k, n)| format!("{k} {n}")).collect();
    g.append(
        primitives::text(
            &format!("links: {}", key.join(", ")),
            [8.0, frame.height - 8.0],
            11.0,
            "#b03030",
        )
        .set("class", "link-key"),
    );
    for ic in plan.instant_centres(&a.pose())? {
        let Centre::At(p) = ic.centre else { continue };
        let q = frame.to_pixel(p);
        if !(q[0] >= 0.0 && q[0] <= frame.width && q[1] >= 0.0 && q[1] <= frame.height) {
            continue;
        }
        let r = 0.6 * style.hinge_radius;
        g.append(
            primitives::dot(q, r, "none")
                .set("stroke", "#b03030")
                .set("stroke-width", primitives::r2(0.5 * style.line_width)),
        );
        let [i, j] = ic.links.map(|l| names[l.index()].as_str());
        g.append(
            primitives::text(&ic.label(plan)?, [q[0] + r, q[1] - r], 11.0, "#b03030")
                .set("data-links", format!("{i}|{j}")),
        );
    }
    Ok(g)
}
