#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! The four-bar's geometry in closed form, shared by the synthesis methods: positions, the
//! rocker's extreme positions, the time ratio, the swing and the smallest transmission angle.
//!
//! Local frame (Freudenstein's): O1 at the origin, O3 at (d, 0); the crank angle φ of O1→A, the
//! rocker angle ψ of O3→B. The world frame places O1 at `o1` and turns the local x axis to the
//! direction `delta`. The assembly mode σ = +1 puts B to the left of the line A→O3 (the
//! engine's `Plus` for the group (coupler, rocker)).

use super::{acute, time_ratio_of, Report, MAX_LINK_RATIO};
use crate::angle::{cross, direction, normalize, perp, unit};
use crate::error::{Error, Result};
use crate::kinematics::{grashof, Grashof};
use crate::linkage::{Input, Joint, Link, Linkage, NamedPoint, Output};
use nalgebra::Vector2;
use std::f64::consts::PI;

type V = Vector2<f64>;

/// A four-bar: its placement, lengths and assembly mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FourBar {
    /// O1 in the world, m.
    pub o1: V,
    /// The direction of O1→O3 in the world, rad.
    pub delta: f64,
    /// Frame O1O3, crank O1A, coupler AB, rocker O3B, m.
    pub d: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    /// +1: B left of A→O3; −1: right.
    pub sigma: f64,
}

/// The rocker's two extreme positions of a crank-rocker, local angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Extremes {
    /// The crank angle where crank and coupler are stretched out (B farthest from O1).
    pub phi_ext: f64,
    /// The crank angle where they fold over each other.
    pub phi_fold: f64,
    /// The rocker angles there.
    pub psi_ext: f64,
    pub psi_fold: f64,
    /// θ, the angle at O1 between the two positions of B.
    pub theta: f64,
    /// The swing, rad.
    pub swing: f64,
}

/// The angle of a triangle between the sides `p` and `q`, opposite the side `o` (rad in
/// [0, π]), by Kahan's formula for needle-like triangles: with x ≥ y the two sides and
/// μ = o − (x − y) if y ≥ o, else y − (x − o),
/// angle = 2·atan √(((x − y) + o)·μ / ((x + (y + o))·((x − o) + y))).
///
/// Why not the cos law: acos(1 − δ) loses half the digits of a small angle (its derivative
/// is 1/sin), and near a change point or a dead point the angles that set K, the swing and
/// γ_min are small (the reported swing of a crank-rocker next to its K bound was off by
/// 5e-10 of itself). Each factor here is exact or one rounding of the data, so the angle is
/// good to a few ulps for every shape. The sides are divided by the largest first (free of
/// overflow and underflow); a set that is not a triangle by rounding gives the flat angle
/// nearest to it.
pub(crate) fn triangle_angle(p: f64, q: f64, o: f64) -> f64 {
    let s = p.max(q).max(o);
    if !(s > 0.0) {
        return 0.0;
    }
    let (p, q, o) = (p / s, q / s, o / s);
    let (x, y) = (p.max(q), p.min(q));
    let mu = if y >= o { o - (x - y) } else { y - (x - o) };
    let num = ((x - y) + o) * mu;
    let den = (x + (y + o)) * ((x - o) + y);
    if !(num >= 0.0) || !(den > 0.0) {
        return if o >= 0.5 * (x + y + o) { PI } else { 0.0 };
    }
    2.0 * (num / den).sqrt().atan()
}

impl FourBar {
    /// A four-bar in Freudenstein's frame.
    pub fn local(d: f64, a: f64, b: f64, c: f64, sigma: f64) -> Self {
        Self {
            o1: V::zeros(),
            delta: 0.0,
            d,
            a,
            b,
            c,
            sigma,
        }
    }

    /// The same four-bar (in Freudenstein's frame) with every length times `k`.
    pub fn scaled(&self, k: f64) -> Result<Self> {
        let mut out = *self;
        for (name, x) in [
            ("the frame", &mut out.d),
            ("the crank", &mut out.a),
            ("the coupler", &mut out.b),
            ("the rocker", &mut out.c),
        ] {
            *x = crate::error::positive(name, crate::error::computed(name, *x * k)?)?;
        }
        Ok(out)
    }

    fn world(&self, p: V) -> V {
        let (s, c) = self.delta.sin_cos();
        self.o1 + V::new(c * p.x - s * p.y, s * p.x + c * p.y)
    }

    /// Grashof's class.
    pub fn grashof(&self) -> Result<Grashof> {
        grashof(self.d, self.a, self.b, self.c)
    }

    /// A and B (local) at the local crank angle `phi`, `None` where it does not assemble.
    /// The largest of the four lengths: the positions are found in units of it, so that
    /// neither squares of huge lengths overflow nor those of tiny ones underflow.
    fn size(&self) -> f64 {
        self.d.max(self.a).max(self.b).max(self.c)
    }

    pub fn local_pose(&self, phi: f64) -> Option<(V, V)> {
        let s = self.size();
        let (d, a_len, b, c) = (self.d / s, self.a / s, self.b / s, self.c / s);
        let a = a_len * unit(phi);
        let v = V::new(d, 0.0) - a;
        let e = v.norm();
        if e == 0.0 {
            return None;
        }
        let along = 0.5 * (e + (b - c) * (b + c) / e);
        // h² = b² − along² = c² − (e − along)², from the shorter link (see below).
        let (xs, ls) = if c < b { (e - along, c) } else { (along, b) };
        let h2 = (ls - xs) * (ls + xs);
        if h2 < -1e-12 * b * b {
            return None;
        }
        let u = v / e;
        let across = self.sigma * h2.max(0.0).sqrt() * perp(u);
        // B from the shorter of coupler and rocker: the same point, but the rounding of
        // `along` (≈ ε·e) moves B by ε·e·e/h from A's side and by ε·e·(e − along)/h from
        // O3's, which matters when the rocker is much shorter than the coupler (B near O3).
        let b_point = if c < b {
            V::new(d, 0.0) + across - (e - along) * u
        } else {
            a + along * u + across
        };
        Some((s * a, s * b_point))
    }

    /// The transmission angle (acute, between coupler and rocker) where |AO3| = e: the
    /// triangle A B O3's angle at B, opposite e.
    fn mu(&self, e: f64) -> f64 {
        acute(triangle_angle(self.b, self.c, e))
    }

    /// The transmission angle at the local crank angle `phi`.
    pub fn transmission(&self, phi: f64) -> f64 {
        let (sin, cos) = phi.sin_cos();
        self.mu((self.d - self.a * cos).hypot(self.a * sin))
    }

    /// γ_min over a full turn and the local crank angle where it occurs: |AO3| runs from
    /// |d − a| (φ = 0) to d + a (φ = π) and back, the angle at B is monotonic in |AO3|, and the
    /// acute angle of it is concave, so its minimum is at φ = 0 or φ = π.
    pub fn gamma_full(&self) -> (f64, f64) {
        let (g0, gpi) = (self.mu((self.d - self.a).abs()), self.mu(self.d + self.a));
        if g0 <= gpi {
            (g0, 0.0)
        } else {
            (gpi, PI)
        }
    }

    /// γ_min over the local crank angles from `start` through `span` (> 0, < 2π): at the
    /// ends, or at φ = 0 or π inside (the same argument as [`FourBar::gamma_full`]).
    pub fn gamma_over(&self, start: f64, span: f64) -> (f64, f64) {
        let mut best = (self.transmission(start), start);
        let mut consider = |phi: f64| {
            let g = self.transmission(phi);
            if g < best.0 {
                best = (g, phi);
            }
        };
        consider(start + span);
        for special in [0.0, PI] {
            let off = normalize(special - start);
            if off <= span {
                consider(start + off);
            }
        }
        (best.0, normalize(best.1))
    }

    /// The rocker's extreme positions of a crank that turns fully (where crank and coupler
    /// are collinear): B at a + b and at b − a from O1, on the mode's side of the frame line
    /// (σ = +1: above it, since then cross(O3 − A, B − A) = d·B_y with A on the line O1B).
    pub fn extremes(&self) -> Extremes {
        let (d, c, s) = (self.d, self.c, self.sigma);
        // The triangle O1 B O3 (|O1B| = r): α at O1 (opposite c), β at O3 (opposite r).
        let at = |r: f64| (triangle_angle(r, d, c), triangle_angle(c, d, r));
        let (ae, be) = at(self.a + self.b);
        let (af, bf) = at(self.b - self.a);
        Extremes {
            phi_ext: normalize(s * ae),
            phi_fold: normalize(s * af + PI),
            psi_ext: normalize(PI - s * be),
            psi_fold: normalize(PI - s * bf),
            theta: (af - ae).abs(),
            swing: (be - bf).abs(),
        }
    }

    /// Checks the proportions: the longest link at most [`MAX_LINK_RATIO`] times the
    /// shortest, [`Error::NoMechanism`] otherwise.
    pub fn proportions(&self, method: &'static str) -> Result<()> {
        let shortest = self.d.min(self.a).min(self.b).min(self.c);
        let ratio = self.size() / shortest;
        if ratio <= MAX_LINK_RATIO {
            Ok(())
        } else {
            Err(Error::NoMechanism {
                method,
                problem: format!(
                    "its longest link is {ratio:.4e} times its shortest (at most {MAX_LINK_RATIO:e})"
                ),
            })
        }
    }

    /// The closed-form report: K and the swing for a crank-rocker, γ_min over a full turn for
    /// a crank that turns fully, over `range` (local start, span) otherwise.
    pub fn report(&self, kind: &'static str, range: Option<(f64, f64)>) -> Result<Report> {
        let class = self.grashof()?;
        let (k, swing) = if class == Grashof::CrankRocker {
            let e = self.extremes();
            (Some(time_ratio_of(e.theta)), Some(e.swing))
        } else {
            (None, None)
        };
        let (gamma, at) = match range {
            _ if class.input_turns_fully() => self.gamma_full(),
            Some((start, span)) => self.gamma_over(start, span),
            None => {
                return Err(Error::NoMechanism {
                    method: kind,
                    problem: format!("the crank does not turn fully (Grashof class: {class})"),
                })
            }
        };
        Ok(Report {
            kind,
            time_ratio: k,
            stroke: swing,
            min_transmission_angle: gamma,
            min_transmission_at: normalize(at + self.delta),
            grashof: Some(class),
            dimensions: vec![
                ("frame O1O3".to_owned(), self.d),
                ("crank O1A".to_owned(), self.a),
                ("coupler AB".to_owned(), self.b),
                ("rocker O3B".to_owned(), self.c),
            ],
        })
    }

    /// The description, posed at the local crank angle `phi`: joints `O1`, `A`, `B`, `O3`,
    /// links `frame`, `crank`, `coupler` (with `points`, and its angle measured along
    /// `reference` if given), `rocker`; the output the rocker's angle.
    pub fn linkage(
        &self,
        name: &str,
        phi: f64,
        points: Vec<NamedPoint>,
        reference: Option<[String; 2]>,
    ) -> Result<Linkage> {
        let (a, b) = self.local_pose(phi).ok_or_else(|| Error::NoMechanism {
            method: "four-bar",
            problem: format!("it does not assemble at the reference crank angle {phi} rad"),
        })?;
        let xy = |p: V| {
            let w = self.world(p);
            [w.x, w.y]
        };
        let mut coupler = Link::new("coupler", &["A", "B"]);
        coupler.points = points;
        coupler.reference = reference;
        Ok(Linkage {
            name: name.to_owned(),
            joints: vec![
                Joint::revolute("O1", xy(V::zeros())),
                Joint::revolute("A", xy(a)),
                Joint::revolute("B", xy(b)),
                Joint::revolute("O3", xy(V::new(self.d, 0.0))),
            ],
            links: vec![
                Link::new("frame", &["O1", "O3"]),
                Link::new("crank", &["O1", "A"]),
                coupler,
                Link::new("rocker", &["O3", "B"]),
            ],
            input: Input::crank("crank"),
            output: Some(Output::Angle("rocker".to_owned())),
            ..Linkage::default()
        })
    }

    /// The assembly mode of the configuration with the hinges A and B (local): the sign of
    /// cross(O3 − A, B − A), zero for a flat configuration.
    pub fn mode_of(d: f64, a: V, b: V) -> f64 {
        let s = cross(V::new(d, 0.0) - a, b - a);
        if s > 0.0 {
            1.0
        } else if s < 0.0 {
            -1.0
        } else {
            0.0
        }
    }

    /// The world direction of a local angle.
    pub fn world_angle(&self, local: f64) -> f64 {
        normalize(local + self.delta)
    }

    /// The local position of a world point.
    pub fn local_of(&self, p: V) -> V {
        let q = p - self.o1;
        let (s, c) = self.delta.sin_cos();
        V::new(c * q.x + s * q.y, -s * q.x + c * q.y)
    }

    /// The four-bar with the pivots `o1`, `o3` (world), the hinges `a`, `b` in one pose.
    pub fn from_points(o1: V, a: V, b: V, o3: V) -> Self {
        let f = o3 - o1;
        let mut fb = Self {
            o1,
            delta: direction(f),
            d: f.norm(),
            a: (a - o1).norm(),
            b: (b - a).norm(),
            c: (b - o3).norm(),
            sigma: 1.0,
        };
        fb.sigma = Self::mode_of(fb.d, fb.local_of(a), fb.local_of(b));
        fb
    }
}
