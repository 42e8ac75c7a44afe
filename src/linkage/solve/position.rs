//! The position pass: every link's position, velocity and acceleration at given inputs,
//! the input links first, then each group by its closed form in attachment order. It works on
//! the plan's kinematic [`Chain`] alone, so the plan's builder solves the reference pose with
//! it before any plan exists.

use super::state::{within, KinState};
use crate::angle::unit;
use crate::error::{Error, Result};
use crate::kinematics::{
    prp_dyad, rpp_dyad, rpr_dyad, rrp_dyad, rrr_dyad, LinkMotion, Motion, PointMotion,
};
use crate::linkage::inputs::check_input_coordinate;
use crate::linkage::plan::{Chain, Group, GroupKind, InputPlan};
use nalgebra::Vector2;

/// The motion of an input link at its input coordinate.
fn input_motion(ip: &InputPlan, input: Motion) -> Result<LinkMotion> {
    Ok(match *ip {
        InputPlan::Crank { pivot, .. } => LinkMotion {
            origin: PointMotion::fixed(pivot),
            angle: crate::angle::normalize(input.value),
            omega: input.rate,
            epsilon: input.accel,
        },
        InputPlan::Slider { at, angle, .. } => {
            let d = unit(angle);
            let o = PointMotion::new(at + input.value * d, input.rate * d, input.accel * d);
            o.validate(["slider x", "slider y", "v.x", "v.y", "a.x", "a.y"])?;
            LinkMotion {
                origin: o,
                angle,
                omega: 0.0,
                epsilon: 0.0,
            }
        }
    })
}

/// The unit vector along `v` (a link's side between two of its joints, never zero once its
/// group is solved).
#[inline]
fn direction_of(v: Vector2<f64>) -> Vector2<f64> {
    v / v.norm()
}

/// A dyad's solution read where its block wrote it, or the block's error named after the
/// group. A solution is some 200 bytes: moving it out of its `Result` (by `map_err` and `?`)
/// copied it twice per group and position.
#[inline]
fn in_place<'r, T>(r: &'r Result<T>, group: &Group) -> Result<&'r T> {
    r.as_ref().map_err(|e| within(&group.name)(e.clone()))
}

/// `u` turned by the angle whose cosine and sine are `r`.
#[inline]
fn turn(u: Vector2<f64>, r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(u.x * r.x - u.y * r.y, u.x * r.y + u.y * r.x)
}

impl KinState {
    /// Positions, velocities and accelerations of every link at one motion per input (φ, ω,
    /// ε for a crank; s, ṡ, s̈ for a slider), group by group in attachment order.
    ///
    /// # Errors
    /// Non-finite input; the number of motions not the number of inputs; [`Error::In`]
    /// naming the group that cannot be assembled or is at a dead point, or a named point whose
    /// motion overflows.
    pub fn solve(&mut self, plan: &Chain, inputs: &[Motion]) -> Result<()> {
        self.place_inputs(plan, inputs)?;
        for (g, group) in plan.groups.iter().enumerate() {
            self.solve_group_kinematics(g, group)?;
        }
        // A named point may lie farther out on its link than any joint (beyond the bound
        // checked on the inputs): its motion is computed on demand, so it is checked here,
        // once.
        for k in 0..plan.points.len() {
            let m = self.pose(plan).point_motion_at(k);
            if !(m.p.coords.iter().chain(m.v.iter()).chain(m.a.iter())).all(|x| x.is_finite()) {
                return Err(Error::In {
                    part: format!("point {}", plan.point_names[k]),
                    source: Box::new(Error::Overflow {
                        what: "its position, velocity or acceleration",
                    }),
                });
            }
        }
        Ok(())
    }

    /// Only the groups `groups` (indices in attachment order, each listed after every group
    /// whose links it reads, as `Plan::group_ancestry` gives them) at one motion per
    /// input: each listed group's motion to the bit of [`solve`](Self::solve)'s, because a
    /// group's closed form reads nothing but the input links and the links of the groups
    /// before it that it hangs on. The other groups keep whatever they held; named points
    /// are not checked.
    ///
    /// # Errors
    /// As [`solve`](Self::solve), for the inputs and the listed groups.
    pub(crate) fn solve_groups(
        &mut self,
        plan: &Chain,
        inputs: &[Motion],
        groups: &[usize],
    ) -> Result<()> {
        self.place_inputs(plan, inputs)?;
        for &g in groups {
            self.solve_group_kinematics(g, &plan.groups[g])?;
        }
        Ok(())
    }

    /// The input links' motions checked and stored (the first step of every solve).
    #[inline]
    fn place_inputs(&mut self, plan: &Chain, inputs: &[Motion]) -> Result<()> {
        let (input, second) = match (inputs, &plan.second_input) {
            ([i], None) => (*i, None),
            ([i, j], Some((ip, _))) => (*i, Some((*j, ip))),
            _ => {
                return Err(Error::Description {
                    item: "inputs".to_owned(),
                    problem: format!(
                        "the linkage has {} input(s), {} motion(s) given",
                        plan.input_count(),
                        inputs.len()
                    ),
                })
            }
        };
        input.validate(["input", "input rate", "input acceleration"])?;
        // Beyond ±10⁹ an input coordinate names no position (module `inputs`).
        check_input_coordinate("input", input.value)?;
        // The input's ω² and ε times the linkage's size bound its points' accelerations: past
        // f64's range the motion overflows whatever the groups do.
        let bound = |m: &Motion| {
            crate::error::computed(
                "the input's accelerations (size·(ω² + |ε|))",
                plan.size * (m.rate * m.rate + m.accel.abs()),
            )
        };
        bound(&input)?;
        self.input = input;
        let link = plan.input.link();
        let motion = input_motion(&plan.input, input)?;
        self.set_link(link, motion);
        self.second_input = None;
        if let Some((m, ip)) = second {
            m.validate([
                "second input",
                "second input rate",
                "second input acceleration",
            ])?;
            check_input_coordinate("second input", m.value)?;
            bound(&m)?;
            let motion = input_motion(ip, m)?;
            self.set_link(ip.link(), motion);
            self.second_input = Some(m);
        }
        Ok(())
    }

    /// Group `g` solved in full by its closed form (as in
    /// [`solve`](Self::solve)), the known links' motions
    /// already stored.
    #[inline]
    pub(super) fn solve_group_kinematics(&mut self, g: usize, group: &Group) -> Result<()> {
        if let Some(t) = &group.triad {
            return self.solve_triad_kinematics(g, group, t);
        }
        if let Some(gp) = &group.general {
            return self.solve_general_kinematics(g, group, gp);
        }
        // An RRR dyad on twins' inner joints, in their frame where it has a clean answer
        // (`twin.rs`); the plain closed form below otherwise.
        if let Some(t) = &group.twin
            && self.solve_twin(g, group, t)
        {
            return Ok(());
        }
        let [l2, l3] = group.links;
        let [ka, kc] = group.known;
        let a = self.at(ka, group.a_local);
        // Each arm also gives the links' unit vectors from the group's geometry (or a known
        // link's turned by a constant), never from the returned angles again.
        let t = self.turns[g];
        let (s2, s3, det, u2, u3) = match group.kind {
            GroupKind::Rrr => {
                let c = self.at(kc, group.c_local);
                let r = rrr_dyad(a, c, group.lengths[0], group.lengths[1], group.branch);
                let s = in_place(&r, group)?;
                let (u2, u3) = (direction_of(s.b.p - a.p), direction_of(s.b.p - c.p));
                (s.link2, s.link3, s.det, u2, u3)
            }
            GroupKind::Rrp => {
                let guide = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
                let r = rrp_dyad(a, guide, group.lengths[0], group.branch);
                let s = in_place(&r, group)?;
                let u3 = turn(self.units[kc], t[1]);
                (s.link2, s.link3, s.det, direction_of(s.b.p - a.p), u3)
            }
            GroupKind::Rpr => {
                let c = self.at(kc, group.c_local);
                let r = rpr_dyad(a, c);
                let s = in_place(&r, group)?;
                let u = direction_of(c.p - a.p);
                (s.link2, s.link3, s.slide.value, u, -u)
            }
            GroupKind::Prp => {
                let g2 = self.guide_on(ka, group.a_local, group.guide_offsets[0]);
                let g3 = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
                let r = prp_dyad(g2, g3);
                let s = in_place(&r, group)?;
                let (u2, u3) = (turn(self.units[ka], t[0]), turn(self.units[kc], t[1]));
                (s.link2, s.link3, s.det, u2, u3)
            }
            // A plan's triad always carries its plan (solved above).
            GroupKind::Triad | GroupKind::General => {
                return Err(Error::Description {
                    item: group.name.clone(),
                    problem: "a triad without its plan".to_owned(),
                })
            }
            GroupKind::Rpp => {
                let g = self.guide_on(kc, group.c_local, group.guide_offsets[1]);
                let r = rpp_dyad(a, g, group.slide_angle);
                let s = in_place(&r, group)?;
                let u3 = turn(self.units[kc], t[1]);
                (s.link2, s.link3, s.det, turn(u3, t[2]), u3)
            }
        };
        self.put_link(l2, s2, u2);
        self.put_link(l3, s3, u3);
        self.dets[g] = det;
        Ok(())
    }
}
