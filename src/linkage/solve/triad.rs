//! The triad in one position's solve: its positions and rates by the kinematics' triad
//! blocks (in the triad's own unit frame, [`unit_frame`](super::unit_frame): the same
//! mechanism at any scale), its reactions by [`Triad::solve`], applied back onto the known
//! links.
//!
//! # Which assembly mode
//! A triad has up to six assembly modes and no sign that tells them apart. Every solve takes
//! the mode nearest the plan's reference mode (the drawn pose's), by
//! [`triad`] started from it: Newton's method from the reference
//! angle, accepted when certified to reach the mode nearest the reference, else the full
//! bracket of every mode and the nearest. So a solve is a pure function of the inputs — the
//! same position gives the same bits whatever was solved before, on any thread, by a
//! [`Solver`](super::Solver) or by a one-shot [`Plan::analyse`](crate::linkage::Plan) —
//! and the mode is continuous along a cycle as long as the motion keeps the triad nearer
//! its reference mode than any other (the bundled six-bar's test checks it round a turn).
//! A triad whose motion carries it farther than that would switch modes; tracking from the
//! previous position is the way out (`triad` takes any previous pose), not taken here so that
//! no solve depends on the one before.

use super::analysis::{Analysis, Reaction};
use super::state::{within, KinState};
use super::unit_frame::{
    slider_triad_rates_scaled, slider_triad_scaled, triad_mode_nearest, triad_rates_scaled,
    triad_scaled,
};
use crate::angle::cross;
use crate::angle::perp;
use crate::error::Result;
use crate::kinematics::{Guide, LinkMotion, Motion, PointMotion, SlidingPair, TriadState};
use crate::kinetostatics::{SlideAt, SliderTriad, Triad};
use crate::linkage::plan::{Group, TriadPlan};
use crate::linkage::plan_triad::SliderLeg;
use nalgebra::{Point2, Vector2};

// A triad with a sliding pair placed at a branch point: its own file.
mod slider_branch;

impl KinState {
    /// Triad `g` solved in full, in the mode nearest the reference mode (module docs).
    pub(super) fn solve_triad_kinematics(
        &mut self,
        g: usize,
        group: &Group,
        t: &TriadPlan,
    ) -> Result<()> {
        let s = match &t.slider {
            Some(leg) => {
                let hinged = [1, 2].map(|i| self.at(t.known[i], t.a_local[i]));
                slider_triad_scaled(&self.first_leg(t, leg), hinged, &leg.dims, &t.reference)
            }
            None => {
                let a = [0, 1, 2].map(|i| self.at(t.known[i], t.a_local[i]));
                triad_scaled(a, &t.dims, &t.reference)
            }
        }
        .map_err(within(&group.name))?;
        for (k, m) in triad_links(t, &s) {
            self.set_link(k, m);
        }
        self.dets[g] = s.det;
        self.triads[g] = Some(s.pose());
        Ok(())
    }

    /// Triad `g`'s rates at the pose of the last solve, whose positions (and unit vectors)
    /// are kept to the bit; `Err` when there is none or a rate fails (the caller then solves
    /// the group in full, which names the failure).
    pub(super) fn triad_rates_at(&mut self, g: usize, group: &Group, t: &TriadPlan) -> Result<()> {
        let pose = self.triads[g].ok_or_else(|| {
            within(&group.name)(crate::Error::NonFinite {
                name: "triad pose",
                value: f64::NAN,
            })
        })?;
        let s = match &t.slider {
            Some(leg) => {
                let hinged = [1, 2].map(|i| self.at(t.known[i], t.a_local[i]));
                slider_triad_rates_scaled(&self.first_leg(t, leg), hinged, &leg.dims, &pose)
            }
            None => {
                let a = [0, 1, 2].map(|i| self.at(t.known[i], t.a_local[i]));
                triad_rates_scaled(a, &t.dims, &pose)
            }
        }
        .map_err(within(&group.name))?;
        for (k, m) in triad_links(t, &s) {
            let link = &mut self.links[k];
            link.origin.v = m.origin.v;
            link.origin.a = m.origin.a;
            link.omega = m.omega;
            link.epsilon = m.epsilon;
        }
        Ok(())
    }
}

impl KinState {
    /// Triad `g` placed where its rates fail (a branch point: two modes merge, and the lines
    /// of its three binary links meet at one point), at rest: every mode by the certified
    /// bracket, which finds a double root of the eliminated equation as one mode, and the
    /// one nearest the reference mode (the rule of every solve); `Ok` with the error its
    /// rates have there. `Err` when the rates do not fail there (the failure was another). A
    /// triad with a sliding pair is placed by `slider_triad_position_only`.
    pub(super) fn triad_position_only(
        &mut self,
        g: usize,
        group: &Group,
        t: &TriadPlan,
    ) -> Result<crate::Error> {
        if let Some(leg) = &t.slider {
            return self.slider_triad_position_only(g, group, t, leg);
        }
        let a = [0, 1, 2].map(|i| self.at(t.known[i], t.a_local[i]));
        let pose = triad_mode_nearest(a.map(|m| m.p), &t.dims, &t.reference)
            .map_err(within(&group.name))?;
        let at_rest = a.map(|m| PointMotion::fixed(m.p));
        let singular = match triad_rates_scaled(at_rest, &t.dims, &pose) {
            Err(e @ crate::Error::Singular { .. }) => e,
            _ => {
                return Err(crate::Error::Description {
                    item: group.name.clone(),
                    problem: "its rates do not vanish here".to_owned(),
                })
            }
        };
        let link = |origin: Point2<f64>, angle: f64| LinkMotion {
            origin: PointMotion::fixed(origin),
            angle,
            omega: 0.0,
            epsilon: 0.0,
        };
        let s = TriadState {
            b: pose.b.map(PointMotion::fixed),
            ternary: link(pose.b[0], pose.theta),
            binary: [0, 1, 2].map(|i| link(at_rest[i].p, pose.phi[i])),
            det: pose.det,
        };
        for (k, m) in triad_links(t, &s) {
            self.set_link(k, m);
        }
        self.dets[g] = pose.det;
        self.triads[g] = Some(pose);
        Ok(within(&group.name)(singular))
    }

    /// The sliding leg's known part: the known link's guide (outer pair), or A1 (inner pair,
    /// the guide's angle unused).
    fn first_leg(&self, t: &TriadPlan, leg: &SliderLeg) -> Guide {
        match leg.dims.pair {
            SlidingPair::Outer { .. } => self.guide_on(t.known[0], t.a_local[0], leg.guide_offset),
            SlidingPair::Inner { .. } => Guide {
                point: self.at(t.known[0], t.a_local[0]),
                angle: Motion::fixed(0.0),
            },
        }
    }
}

/// The motions of a triad's four links (the ternary link first), with their indices.
fn triad_links(t: &TriadPlan, s: &TriadState) -> [(usize, LinkMotion); 4] {
    [
        (t.links[0], s.ternary),
        (t.links[1], s.binary[0]),
        (t.links[2], s.binary[1]),
        (t.links[3], s.binary[2]),
    ]
}

/// A triad's transmission angle: the smallest over its binary links of μ_i, the acute angle
/// between binary link i's line and the line from B_i to P_jk, where the lines of the other
/// two binary links meet (the instant centre of the ternary link were link i taken away, so
/// B_i would move across B_i P_jk). It is π/2 − the pressure angle at B_i, and vanishes where
/// the three lines meet at one point: the triad's dead point (det K = 0).
///
/// A sliding leg's line is its pair's line of action: across the guide, through B1 (outer
/// pair) or A1 (inner pair), which then stands for B_1 as well.
pub(crate) fn transmission_angle(kin: &KinState, t: &TriadPlan, b: [Point2<f64>; 3]) -> f64 {
    let [_, l1, l2, l3] = t.links;
    let mut u = [l1, l2, l3].map(|k| kin.units[k]);
    let a = [l1, l2, l3].map(|k| kin.links[k].origin.p);
    let mut b = b;
    if t.slider.is_some() {
        // The sliding link's frame lies along the guide, its origin at B1 or A1.
        u[0] = perp(u[0]);
        b[0] = a[0];
    }
    let between = |p: Vector2<f64>, q: Vector2<f64>| cross(p, q).abs().atan2(p.dot(&q).abs());
    (0..3)
        .map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            // (B_i − P_jk)·(u_j × u_k), without dividing: P_jk = A_j + u_j·s with
            // s = ((A_k − A_j) × u_k)/(u_j × u_k).
            let d = (b[i] - a[j]) * cross(u[j], u[k]) - u[j] * cross(a[k] - a[j], u[k]);
            between(u[i], d)
        })
        .fold(std::f64::consts::FRAC_PI_2, f64::min)
}

impl Analysis<'_> {
    /// Triad `g`'s reactions from the loads collected on its links; its outer reactions are
    /// added to the known links' loads.
    pub(super) fn solve_triad(&mut self, g: usize, group: &Group, t: &TriadPlan) -> Result<()> {
        if let Some(leg) = &t.slider {
            return self.solve_slider_triad(g, group, t, leg);
        }
        let kin = &self.k.kin;
        let [lt, l1, l2, l3] = t.links;
        let binary = [l1, l2, l3];
        let a = binary.map(|l| kin.links[l].origin.p);
        let pose = self.pose();
        let b = [0, 1, 2].map(|i| pose.joint_position_on(t.inner[i], lt));
        let r = Triad {
            a,
            b,
            loads: binary.map(|l| self.acc[l]),
            load_ternary: self.acc[lt],
        }
        .solve()
        .map_err(within(&group.name))?;
        for i in 0..3 {
            let ra = Reaction::hinge(t.known[i], binary[i], r.r_a[i], a[i]);
            super::statics::add(&mut self.acc[t.known[i]], &ra.load_on_side(t.known[i]));
            self.reactions[t.outer[i]] = ra;
            self.reactions[t.inner[i]] = Reaction::hinge(binary[i], lt, r.r_b[i], b[i]);
        }
        self.conditioning[g] = r.conditioning;
        Ok(())
    }

    /// A triad with a sliding pair: its reactions by [`SliderTriad::solve`], the sliding
    /// pair's as a force on its line with the couple (see [`Reaction::offset`]).
    fn solve_slider_triad(
        &mut self,
        g: usize,
        group: &Group,
        t: &TriadPlan,
        leg: &SliderLeg,
    ) -> Result<()> {
        let kin = &self.k.kin;
        let [lt, l1, l2, l3] = t.links;
        let binary = [l1, l2, l3];
        let a = binary.map(|l| kin.links[l].origin.p);
        let normal = perp(kin.units[l1]);
        let pose = self.pose();
        let b = [0, 1, 2].map(|i| pose.joint_position_on(t.inner[i], lt));
        let slide = match leg.dims.pair {
            SlidingPair::Outer { .. } => SlideAt::Outer,
            SlidingPair::Inner { .. } => SlideAt::Inner,
        };
        let r = SliderTriad {
            slide,
            normal,
            a,
            b,
            loads: binary.map(|l| self.acc[l]),
            load_ternary: self.acc[lt],
        }
        .solve()
        .map_err(within(&group.name))?;
        let (outer, inner) = match slide {
            SlideAt::Outer => (
                Reaction::new(t.known[0], l1, r.r_a[0], b[0], r.couple),
                Reaction::hinge(l1, lt, r.r_b[0], b[0]),
            ),
            SlideAt::Inner => (
                Reaction::hinge(t.known[0], l1, r.r_a[0], a[0]),
                Reaction::new(l1, lt, r.r_b[0], a[0], r.couple),
            ),
        };
        let mut reactions = [(outer, inner); 3];
        for i in 1..3 {
            reactions[i] = (
                Reaction::hinge(t.known[i], binary[i], r.r_a[i], a[i]),
                Reaction::hinge(binary[i], lt, r.r_b[i], b[i]),
            );
        }
        for (i, (ra, rb)) in reactions.into_iter().enumerate() {
            super::statics::add(&mut self.acc[t.known[i]], &ra.load_on_side(t.known[i]));
            self.reactions[t.outer[i]] = ra;
            self.reactions[t.inner[i]] = rb;
        }
        self.conditioning[g] = r.conditioning;
        Ok(())
    }
}
