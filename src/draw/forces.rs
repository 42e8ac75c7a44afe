//! The reactions in the joints as scaled arrows on the scheme at one position, with the
//! friction circles of the hinges.

use super::parts::{self, Pen};
use super::primitives;
use super::scene::{self, Extents, Pose, Topo};
use super::{Picture, Style};
use crate::error::Result;
use crate::linkage::{Inputs, Plan};
use svg::Node;

/// The force arrows at `input`: the scheme (faded), and in every joint the reaction R_i,j —
/// the force of link i on link j ([`Reaction`](crate::linkage::Reaction): `by` = i, `on` =
/// j, links numbered as in [`Plan::link_names`], 0 the frame) — as an arrow from the point it
/// acts at, all to one scale: the largest is 30 % of the linkage's size long. The balancing
/// moment of a crank is an arc arrow about its pivot in its own sense, a balancing force an
/// arrow to the same scale; each arrow is labelled with its magnitude (N, N·m), and a legend
/// gives the scale. A linkage with two inputs has both inputs' balancing moments or forces,
/// labelled M_b1 and M_b2 (F_b1, F_b2); every balance element (class `balance`) names its
/// input in `data-input` (0 the first) and holds its exact value in `data-value`. [`Picture::force_scale`] is the force per pixel of arrow, N/px.
///
/// A linkage with friction ([`Plan::has_friction`]) has, at each revolute joint with a
/// friction circle, that circle of radius ρ = f·r drawn to the scheme's scale (a `circle`
/// of class `friction-circle` with the joint's name in `data-joint`): the textbook's
/// construction, in which the reaction is tangent to the circle. Without friction the
/// picture is the frictionless one.
///
/// # Errors
/// As [`scheme`](super::scheme), and the kinetostatics' errors at this input.
///
/// # Examples
/// The tip of the crank pin's reaction lies `|R| / force_scale` pixels from the pin:
/// ```
/// use tmm::draw::{forces, Style};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Plan};
/// let plan = Plan::new(&bundled::watt_six_bar())?;
/// let input = Motion::new(1.0, 10.0, 0.0);
/// let pic = forces(&plan, input, &Style::default())?;
/// let r = plan.analyse(input)?.reaction("A")?;
/// let px = r.force.norm() / pic.force_scale.unwrap();
/// assert!(px > 1.0 && px < 800.0);
/// assert!(pic.svg.contains("N·m"));
/// # Ok::<(), tmm::Error>(())
/// ```
pub fn forces(plan: &Plan, input: impl Into<Inputs>, style: &Style) -> Result<Picture> {
    let input = input.into();
    style.check()?;
    let a = plan.analyse(input)?;
    let topo = Topo::new(plan);
    let pose = Pose::of(&a)?;
    let mut ext = Extents::new(&topo);
    ext.add(&topo, &pose);
    let reactions: Vec<_> = plan
        .joint_ids()
        .map(|j| a.reaction(j))
        .collect::<Result<_>>()?;
    let balances = a.balances().to_vec();
    let fmax = reactions
        .iter()
        .map(|r| r.force.norm())
        .chain(balances.iter().map(|b| b.force.norm()))
        .fold(0.0, f64::max);
    crate::error::computed("the largest reaction", fmax)?;
    // Metres of drawing per newton.
    let longest = 0.3 * topo.size;
    let m_per_n = if fmax > 0.0 { longest / fmax } else { 0.0 };
    // The arrow of a force, m: to scale, or, for forces too small for a finite scale
    // (subnormal newtons), as a fraction of the largest.
    let reach = |f: nalgebra::Vector2<f64>| {
        if m_per_n.is_finite() {
            f * m_per_n
        } else {
            f / fmax * longest
        }
    };
    let mut cover = Vec::new();
    pose.cover(&topo, &ext, &mut cover);
    for r in &reactions {
        cover.push(r.point + reach(r.force));
    }
    cover.extend(balances.iter().map(|b| b.point + reach(b.force)));
    let frame = scene::fit_with_input(&topo, &pose, &mut cover, style)?;
    let force_scale = (fmax > 0.0).then(|| fmax / (longest * frame.scale));

    let title = format!(
        "{} — reactions at input {}",
        plan.name(),
        super::scheme::values(input)
    );
    let mut doc = primitives::document(style, &title);
    doc.append(parts::ground(&topo, &pose, &ext, &frame, style));
    let faded = Pen {
        opacity: 0.45,
        ..Pen::NORMAL
    };
    doc.append(parts::position(&topo, &pose, &ext, &frame, style, faded));
    let red = "#b00020";
    let w = (0.8 * style.line_width).max(1.5);
    let mut labels = primitives::Labels::default();
    for r in &reactions {
        if r.force.norm() <= 0.0 || r.force.norm().is_nan() {
            continue;
        }
        let from = frame.to_pixel(r.point);
        let to = frame.to_pixel(r.point + reach(r.force));
        doc.append(primitives::arrow(from, to, w, red).set("class", "reaction"));
        if style.labels {
            let q = labels.place(to, style);
            doc.append(primitives::text(
                &format!(
                    "R{},{} = {} N",
                    r.by,
                    r.on,
                    primitives::short(r.force.norm())
                ),
                q,
                12.0,
                red,
            ));
        }
    }
    let circles = friction_circles(plan, &reactions, &frame);
    for (name, q, r) in &circles {
        doc.append(
            svg::node::element::Circle::new()
                .set("cx", primitives::r2(q[0]))
                .set("cy", primitives::r2(q[1]))
                .set("r", primitives::r2(*r))
                .set("fill", "none")
                .set("stroke", "#d35400")
                .set("stroke-width", w.min(0.5 * r.max(0.5)))
                .set("class", "friction-circle")
                .set("data-joint", name.as_str()),
        );
    }
    // The balancing moment or force of each input.
    let blue = "#0b3d91";
    let mut legend = vec![
        "R i,j: the force of link i on link j".to_owned(),
        format!(
            "links: {}",
            plan.link_names()
                .iter()
                .enumerate()
                .map(|(k, n)| format!("{k} {n}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    ];
    let two = balances.len() > 1;
    for (i, (link, balance)) in plan.input_links().iter().zip(&balances).enumerate() {
        // With two inputs each balance is named by its input: M_b1, M_b2.
        let tag = if two {
            format!("{}", i + 1)
        } else {
            String::new()
        };
        let pivot = pivot(&topo, link.index());
        // A crank turns about a hinge on the frame, a slider slides in a guide.
        let crank = pivot.is_some_and(|j| plan.chain.joints[j].prismatic.is_none());
        let exact = format!("{}", balance.value);
        if balance.force.norm() > 0.0 {
            let from = frame.to_pixel(balance.point);
            let to = frame.to_pixel(balance.point + reach(balance.force));
            doc.append(
                primitives::arrow(from, to, w, blue)
                    .set("class", "balance")
                    .set("data-input", i)
                    .set("data-value", exact.as_str()),
            );
            let text = format!("F_b{tag} = {} N", primitives::short(balance.force.norm()));
            if two && style.labels {
                let q = labels.place(to, style);
                doc.append(primitives::text(&text, q, 12.0, blue));
            }
            legend.push(format!(
                "balancing force {text}{}",
                if crank {
                    format!(
                        ", its moment M_b{tag} = {} N·m",
                        primitives::short(balance.value)
                    )
                } else {
                    String::new()
                }
            ));
        } else if let Some(j) = pivot {
            let q0 = frame.to_pixel(pose.joints[j][0]);
            let sense = if balance.value < 0.0 { -1.0 } else { 1.0 };
            let r = style.hinge_radius.max(2.0);
            let (arc, at) =
                primitives::arc_arrow(q0, 5.0 * r, 0.5 * std::f64::consts::PI, sense, r, blue);
            doc.append(
                arc.set("class", "balance")
                    .set("data-input", i)
                    .set("data-value", exact.as_str()),
            );
            let unit = if crank { "N·m" } else { "N" };
            let text = format!("M_b{tag} = {} {unit}", primitives::short(balance.value));
            if style.labels {
                doc.append(primitives::text(
                    &text,
                    [at[0] + 8.0, at[1] - 4.0],
                    12.0,
                    blue,
                ));
            }
            legend.push(format!(
                "balancing moment {text} (counter-clockwise positive)"
            ));
        }
    }
    if let Some(s) = force_scale {
        legend.push(format!("scale: 1 px = {} N", primitives::short(s)));
    }
    if !circles.is_empty() {
        legend.push(
            "friction circles (orange): radius ρ = f·r at each hinge, to the scheme's scale; \
             each reaction R is tangent to its circle"
                .to_owned(),
        );
    }
    if style.labels {
        for (i, line) in legend.iter().enumerate() {
            #[allow(clippy::cast_precision_loss)]
            let y = 16.0 + 15.0 * i as f64;
            doc.append(primitives::text(line, [8.0, y], 12.0, "#222222"));
        }
    }
    Ok(Picture {
        svg: primitives::finish(&doc)?,
        frame,
        force_scale,
    })
}

/// The joint between input link `link` and the frame, if it has one.
fn pivot(topo: &Topo, link: usize) -> Option<usize> {
    topo.link_joints[link]
        .iter()
        .copied()
        .find(|&j| topo.joint_links[j].contains(&0))
}

/// The friction circles of the hinges: (joint name, centre px, radius px) for every revolute
/// joint with ρ > 0, centred on the joint (where its reaction acts).
fn friction_circles(
    plan: &Plan,
    reactions: &[crate::linkage::Reaction],
    frame: &super::frame::Frame,
) -> Vec<(String, [f64; 2], f64)> {
    let Some(fp) = &plan.friction else {
        return Vec::new();
    };
    fp.iter()
        .zip(reactions)
        .enumerate()
        .filter(|(j, (f, _))| f.hinge.rho > 0.0 && plan.chain.joints[*j].prismatic.is_none())
        .map(|(j, (f, r))| {
            (
                plan.chain.joint_names[j].clone(),
                frame.to_pixel(r.point),
                f.hinge.rho * frame.scale,
            )
        })
        .collect()
}
