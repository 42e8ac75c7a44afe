//! The joints' friction, checked and resolved: each joint's own [`Friction`] or the
//! linkage's default, turned into the blocks' [`Hinge`] (revolute) or [`Slide`] (prismatic).
//! A plan whose every coefficient is zero has no friction at all, so its solve is the
//! frictionless one, bit for bit.

use super::super::description::{Friction, JointKind, Linkage};
use super::super::plan::{bad, FrictionPlan};
use crate::error::Result;
use crate::kinetostatics::friction::{Hinge, Slide};

/// The friction of every joint (by the description's order), or `None` when no joint has any.
///
/// # Errors
/// [`Error::Description`](crate::Error::Description) naming the joint (`joint B, friction`)
/// and the field: a negative or non-finite number, a revolute joint's `f` without
/// `pin_radius`, a prismatic joint's own `rho` or `pin_radius`, a `length` that is not > 0.
pub(super) fn plan_friction(linkage: &Linkage) -> Result<Option<Vec<FrictionPlan>>> {
    if let Some(d) = &linkage.friction {
        check_numbers(d, "field friction")?;
    }
    let mut any = false;
    let mut plans = Vec::with_capacity(linkage.joints.len());
    for joint in &linkage.joints {
        let own = joint.friction.as_ref();
        let Some(fr) = own.or(linkage.friction.as_ref()) else {
            plans.push(FrictionPlan::default());
            continue;
        };
        let item = if own.is_some() {
            format!("joint {}, friction", joint.name)
        } else {
            format!("joint {}, friction (the linkage's default)", joint.name)
        };
        check_numbers(fr, &item)?;
        let plan = match joint.kind {
            JointKind::Revolute => {
                let rho = match (fr.rho, fr.f, fr.pin_radius) {
                    (Some(rho), _, _) => rho,
                    (None, Some(f), Some(r)) => f * r,
                    (None, None, None) => 0.0,
                    (None, Some(_), None) => {
                        return Err(bad(
                            item,
                            "a revolute joint needs pin_radius with f (or rho)",
                        ))
                    }
                    (None, None, Some(_)) => {
                        return Err(bad(item, "a revolute joint needs f with pin_radius"))
                    }
                };
                FrictionPlan {
                    hinge: Hinge { rho },
                    slide: Slide::FRICTIONLESS,
                }
            }
            JointKind::Prismatic { .. } => {
                if own.is_some() && (fr.rho.is_some() || fr.pin_radius.is_some()) {
                    return Err(bad(
                        item,
                        "rho and pin_radius are for a revolute joint; a slide takes f and length",
                    ));
                }
                FrictionPlan {
                    hinge: Hinge::FRICTIONLESS,
                    slide: Slide {
                        f: fr.f.unwrap_or(0.0),
                        length: fr.length,
                        centre: fr.centre.unwrap_or(0.0),
                    },
                }
            }
        };
        any |= plan.hinge.rho != 0.0 || plan.slide.f != 0.0;
        plans.push(plan);
    }
    Ok(any.then_some(plans))
}

/// Every number finite, the coefficients and radii ≥ 0, a length > 0.
fn check_numbers(fr: &Friction, item: &str) -> Result<()> {
    let fields = [
        ("f", fr.f),
        ("pin_radius", fr.pin_radius),
        ("rho", fr.rho),
        ("length", fr.length),
    ];
    for (name, value) in fields {
        if let Some(v) = value {
            // A length's half must be a normal number: the end pressures divide by it.
            let ok = v.is_finite()
                && if name == "length" {
                    v >= 2.0 * f64::MIN_POSITIVE
                } else {
                    v >= 0.0
                };
            if !ok {
                let want = if name == "length" {
                    "≥ 4.5e-308 (a normal number's double)"
                } else {
                    "≥ 0"
                };
                return Err(bad(
                    item,
                    format!(
                        "{name} must be finite and {want}, got {}",
                        super::reference::shown(v)
                    ),
                ));
            }
        }
    }
    if let Some(c) = fr.centre.filter(|c| !c.is_finite()) {
        return Err(bad(item, format!("centre must be finite, got {c}")));
    }
    Ok(())
}
