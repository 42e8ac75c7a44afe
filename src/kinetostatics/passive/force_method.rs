//! The force method for the once-indeterminate group: release the hinge C along CD, solve the
//! loaded and the unit state of the released structure, and restore compatibility,
//! δ11·X1 + Δ1F = 0 (seed 002, eqs. 3, 4, 8).

use super::diagrams::{DiagramExtremes, InternalForces, LinkCase};
use super::geometry::{Frame, Geometry, Link, Side, WHAT};
use super::loads::Loads;
use super::statics::{released, Reactions};
use crate::error::{positive, Error, Result};
use crate::kinetostatics::Conditioning;
use nalgebra::{Point2, Vector2};

/// The links' stiffnesses: bending EI (N·m²) and, optionally, axial EA (N), for links 1, 2, 3
/// (index with [`Link::index`]).
///
/// `ea: None` is the seed's model: bending only, the links inextensible. With `Some`, the
/// term ∫N1·N_F/EA enters δ11 and Δ1F. The redundant depends only on the ratios of the
/// stiffnesses, so in the seed's model a common EI drops out.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Stiffness {
    /// Bending stiffness EI of links 1, 2, 3, N·m².
    pub ei: [f64; 3],
    /// Axial stiffness EA of links 1, 2, 3, N; `None` for inextensible links.
    pub ea: Option<[f64; 3]>,
}

impl Stiffness {
    /// The seed's model: the same EI for every link, inextensible links.
    #[must_use]
    pub fn bending_only(ei: f64) -> Self {
        Self {
            ei: [ei; 3],
            ea: None,
        }
    }

    /// The same EI and EA for every link (bending and axial flexibility).
    #[must_use]
    pub fn with_axial(ei: f64, ea: f64) -> Self {
        Self {
            ei: [ei; 3],
            ea: Some([ea; 3]),
        }
    }

    fn check(&self) -> Result<()> {
        for (v, name) in self.ei.iter().zip(["EI_1", "EI_2", "EI_3"]) {
            positive(name, *v)?;
        }
        if let Some(ea) = self.ea {
            for (v, name) in ea.iter().zip(["EA_1", "EA_2", "EA_3"]) {
                positive(name, *v)?;
            }
        }
        Ok(())
    }
}

/// A displacement of the force method split into its bending and axial parts, m (per newton
/// for δ11, m/N).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Flexibility {
    /// ∫ M·M'/EI ds over every link.
    pub bending: f64,
    /// ∫ N·N'/EA ds over every link (zero for inextensible links).
    pub axial: f64,
}

impl Flexibility {
    /// Bending plus axial part.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.bending + self.axial
    }
}

/// Which state of the force method a diagram belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum State {
    /// The released structure under the known loads (the seed's "loaded state", M_zF).
    Loaded,
    /// The released structure under X1 = 1 N alone (the seed's "unit state", M_z1), per
    /// newton.
    Unit,
    /// The real group: loaded state plus X1 times the unit state.
    Total,
}

/// The solved group: the redundant, every hinge force, and the internal forces of every link.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Solution {
    /// The geometry solved.
    pub geometry: Geometry,
    /// The loads solved (positions snapped onto the links).
    pub loads: Loads,
    /// The stiffnesses used.
    pub stiffness: Stiffness,
    /// δ11: the displacement of C along C → D in the released structure under X1 = 1 N, m/N.
    pub delta11: Flexibility,
    /// Δ1F: the displacement of C along C → D in the released structure under the loads, m.
    pub delta1f: Flexibility,
    /// X1 = −Δ1F/δ11: the force of the frame on link 2 at C along C → D, N (the seed's
    /// X̄1 = R02ⁿ when C → D points along +x).
    pub x1: f64,
    /// The hinge forces of the released structure under the loads (X1 = 0).
    pub loaded: Reactions,
    /// The hinge forces of the released structure under X1 = 1 N, per newton.
    pub unit: Reactions,
    /// The hinge forces of the real group: `loaded + x1·unit`.
    pub reactions: Reactions,
    /// |distance from E to the line AB| / size: the divisor of the released structure's
    /// statics. The hinge forces amplify rounding errors (and any error of the geometry) by
    /// about 1/`arm_ratio`; a well-shaped group has a ratio of a few tenths. At 8ε the group
    /// is singular (an error).
    pub arm_ratio: f64,
    /// The same divisor in the form every kinetostatic solver of the crate reports:
    /// `measure` is the signed distance from E to the line AB, m ([`Geometry::arm_e_ab`]),
    /// and `condition` = max(1, 1/`arm_ratio`).
    pub conditioning: Conditioning,
    /// δ11·EI_max/size³: the divisor of the compatibility equation, made dimensionless. It
    /// vanishes when X1 no longer deforms the released structure (for example, bending only,
    /// with E on the line CD and DE along it); the seed's example has 0.0040. Below 10⁻¹²
    /// the group is singular (an error).
    pub delta11_ratio: f64,
    frame: Frame,
}

/// Solves the group with the parallel coupler by the force method.
///
/// The hinge C is released along CD (the seed's choice), X1 is the force of the frame on link 2
/// at C along C → D, and the compatibility equation δ11·X1 + Δ1F = 0 (seed eq. 3, with the
/// "= 0" the print lost) gives it. δ11 and Δ1F are products of the internal-force diagrams of
/// the unit and loaded states, computed exactly (Simpson's formula on every smooth piece), with
/// the axial term when [`Stiffness::ea`] is given.
///
/// # Examples
/// The seed's example in its own notation is [`PaperGroup`](super::PaperGroup). Here a
/// symmetric case checks by hand: a parallelogram with link 3 vertical, a horizontal force
/// P = 100 N on link 3 at the level of D and no other load.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use tmm::kinetostatics::passive::{solve, Geometry, LinkLoad, Loads, Stiffness};
/// use approx::assert_relative_eq;
/// // E on top at (0, 0.3), D at (0, 0.2), B at (0, 0); links 1 and 2 horizontal, 0.2 m long.
/// let g = Geometry::new(
///     Point2::new(-0.2, 0.0), Point2::new(0.0, 0.0),
///     Point2::new(-0.2, 0.2), Point2::new(0.0, 0.2),
///     Point2::new(0.0, 0.3),
/// );
/// let loads = Loads { f3: LinkLoad::force(0.2, Vector2::new(100.0, 0.0)), ..Loads::ZERO };
/// let s = solve(&g, &loads, &Stiffness::bending_only(1.0))?;
/// // Link 3 is a beam on three horizontal supports (the axial links at B and D, and E):
/// // continuous over D, loaded at D, so D takes all of P and B and E nothing.
/// // Link 2 pulls D back with 100 N: the frame pulls C against C → D (+x).
/// assert_relative_eq!(s.x1, -100.0, epsilon = 1e-9);
/// assert_relative_eq!(s.reactions.r01.norm(), 0.0, epsilon = 1e-9);
/// assert_relative_eq!(s.reactions.r03.norm(), 0.0, epsilon = 1e-9);
/// // The statics divide by the distance from E to the line AB, 0.3 m; the group's size is
/// // AE = √(0.2² + 0.3²) ≈ 0.3606 m, so rounding errors are amplified about 1.2 times.
/// assert_relative_eq!(s.conditioning.measure, 0.3, epsilon = 1e-12);
/// assert_relative_eq!(s.conditioning.condition, 0.13f64.sqrt() / 0.3, epsilon = 1e-12);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// Non-finite inputs ([`Error::NonFinite`]); non-positive EI or EA
/// ([`Error::NonPositive`]); a load placed off its link ([`Error::OutOfRange`]); coincident
/// hinges, E on the line AB, or a vanishing δ11 (the redundant does not deform the released
/// structure) ([`Error::Singular`], naming the measure); [`Error::Overflow`] when a
/// flexibility, the redundant or a reaction overflows.
pub fn solve(geometry: &Geometry, loads: &Loads, stiffness: &Stiffness) -> Result<Solution> {
    let frame = geometry.frame()?;
    let loads = loads.checked(&frame)?;
    stiffness.check()?;
    let unit = released(&frame, &Loads::ZERO, 1.0);
    let loaded = released(&frame, &loads, 0.0);
    let mut d11 = Flexibility {
        bending: 0.0,
        axial: 0.0,
    };
    let mut d1f = d11;
    for link in Link::ALL {
        let i = link.index();
        let u = LinkCase::new(&frame, &Loads::ZERO, &unit, link);
        let f = LinkCase::new(&frame, &loads, &loaded, link);
        let ea = stiffness.ea.map(|ea| ea[i]);
        let (b, a) = u.product(&frame, &u, stiffness.ei[i], ea);
        d11.bending += b;
        d11.axial += a;
        let (b, a) = u.product(&frame, &f, stiffness.ei[i], ea);
        d1f.bending += b;
        d1f.axial += a;
    }
    // δ11 is a sum of squares; it vanishes only when the unit state leaves every link
    // undeformed. Compare it with the flexibility scale size³/EI of the stiffest link.
    let size = geometry.size();
    let ei_max = stiffness.ei.iter().copied().fold(0.0, f64::max);
    let d11_scale = size.powi(3) / ei_max;
    let ratio = d11.total() / d11_scale;
    // Written so that a NaN ratio is caught too.
    if ratio.is_nan() || ratio <= 1e-12 {
        return Err(Error::Singular {
            what: WHAT,
            measure: "delta11 * EI / size^3",
            value: ratio,
        });
    }
    // A flexibility that over- or underflows (EI of 1e-300 or 5e-324) carries no digits.
    crate::error::computed_all(
        "flexibilities delta11, delta1F",
        [
            d11.bending,
            d11.axial,
            d1f.bending,
            d1f.axial,
            d11.total(),
            d1f.total(),
            ratio,
        ]
        .iter(),
    )?;
    let x1 = -d1f.total() / d11.total();
    crate::error::computed("X1", x1)?;
    let reactions = loaded.plus_scaled(x1, &unit);
    if !reactions.is_finite() {
        return Err(Error::Overflow { what: "reactions" });
    }
    Ok(Solution {
        geometry: *geometry,
        loads,
        stiffness: *stiffness,
        delta11: d11,
        delta1f: d1f,
        x1,
        loaded,
        unit,
        reactions,
        arm_ratio: frame.arm.abs() / size,
        conditioning: frame.conditioning,
        delta11_ratio: ratio,
        frame,
    })
}

impl Solution {
    fn case(&self, state: State, link: Link) -> LinkCase {
        match state {
            State::Loaded => LinkCase::new(&self.frame, &self.loads, &self.loaded, link),
            State::Unit => LinkCase::new(&self.frame, &Loads::ZERO, &self.unit, link),
            State::Total => LinkCase::new(&self.frame, &self.loads, &self.reactions, link),
        }
    }

    /// The length of a link, m.
    #[must_use]
    pub fn length(&self, link: Link) -> f64 {
        self.frame.l[link.index()]
    }

    /// The point of a link's axis at arc length `s` from its start.
    #[must_use]
    pub fn point_at(&self, link: Link, s: f64) -> Point2<f64> {
        self.frame.g.point_at(link, s)
    }

    /// The internal forces N, Q, M of the real group at the section `s` of `link` (arc length
    /// from the link's start, clamped to the link). Where a diagram jumps (a point load, a
    /// hinge, the bend of link 3) this is the value just after `s`; at the link's end, the
    /// value just before it. See [`Solution::internal_in`] for the other limit and the other
    /// states.
    #[must_use]
    pub fn internal(&self, link: Link, s: f64) -> InternalForces {
        let side = if s >= self.length(link) {
            Side::Before
        } else {
            Side::After
        };
        self.internal_in(State::Total, link, s, side)
    }

    /// The internal forces of one state at the section `s` of `link`, as the one-sided limit
    /// `side`. `Side::Before` at s = 0 and `Side::After` at the end are the zero outside the
    /// link.
    #[must_use]
    pub fn internal_in(&self, state: State, link: Link, s: f64, side: Side) -> InternalForces {
        self.case(state, link).at(&self.frame, s, side)
    }

    /// The largest and smallest N, Q and M of the real group along `link`, and where they
    /// occur.
    #[must_use]
    pub fn extremes(&self, link: Link) -> DiagramExtremes {
        self.extremes_in(State::Total, link)
    }

    /// The extremes of the diagrams of one state along `link`.
    #[must_use]
    pub fn extremes_in(&self, state: State, link: Link) -> DiagramExtremes {
        self.case(state, link).extremes(&self.frame)
    }

    /// The sorted sections of `link` where a diagram of the real group may jump or kink
    /// (both ends included); between two of them N and Q are linear and M is quadratic.
    #[must_use]
    pub fn breakpoints(&self, link: Link) -> Vec<f64> {
        let (b, n) = self.case(State::Total, link).breakpoints(&self.frame, None);
        b[..n].to_vec()
    }

    /// The unit vector along C → D: the direction of X1.
    #[must_use]
    pub fn redundant_direction(&self) -> Vector2<f64> {
        self.frame.t2
    }

    /// The equilibrium residual of each link of the real group: the sum of the forces, N, and
    /// the sum of the moments about the link's start divided by the group's size, N. Both are
    /// round-off small.
    #[must_use]
    pub fn residuals(&self) -> [(Vector2<f64>, f64); 3] {
        let size = self.geometry.size();
        Link::ALL.map(|link| {
            let (f, m) = self.case(State::Total, link).residual(&self.frame);
            (f, m / size)
        })
    }
}
