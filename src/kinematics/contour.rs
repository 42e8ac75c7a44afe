//! The closed vector contour (Zinoviev's method): a loop of plane vectors whose sum is zero,
//! with exactly two unknown scalars among their lengths and angles.
//!
//! Every group of the 2nd class closes one such loop. With two unknowns, four cases occur, and
//! each has a closed form:
//!
//! | unknowns                          | geometry                    | occurs in            |
//! |-----------------------------------|-----------------------------|----------------------|
//! | two angles                        | circle ∩ circle             | RRR dyad             |
//! | an angle and a length (2 vectors) | line ∩ circle               | RRP dyad             |
//! | angle and length of one vector    | polar coordinates of a point| RPR dyad             |
//! | two lengths                       | line ∩ line                 | PRP / RPP groups     |
//!
//! The position problem gives the unknowns; differentiating the loop once and twice in time
//! gives two 2×2 linear systems with the same matrix, whose columns are L·e⊥(θ) for an unknown
//! angle and e(θ) for an unknown length (e(θ) = (cos θ, sin θ), e⊥ its +90° turn). Second
//! derivatives of a vector L·e(θ) carry the centripetal term −L·θ̇²·e and the Coriolis term
//! 2·L̇·θ̇·e⊥ of sliding along a rotating direction, so a slider on a rotating link needs no
//! special case.
//!
//! The matrix's determinant, normalised by the lengths of its columns, is the sine of the
//! angle between the two directions along which the unknowns can move: it is the contour's
//! conditioning (velocities grow like its inverse) and vanishes at a dead point.

use super::motion::Motion;
use crate::angle::{cross, direction, perp, unit};
use crate::error::{computed, computed_all, finite, finite2, Error, Result};
use nalgebra::Vector2;

/// Below this |normalised determinant| the velocity system is treated as singular.
///
/// A position solved from a double (tangent) root is itself only accurate to about √ε, so a
/// determinant this small carries no digits; [`Error::Singular`] is the honest answer.
pub const SINGULAR_DETERMINANT: f64 = 1e-12;

/// The assembly mode (branch) of a contour: which of the two closed-form solutions to take.
///
/// Its geometric meaning per case (the dyad blocks restate it in their own terms):
/// - two unknown angles (circle ∩ circle): `Plus` puts the first unknown-angle vector to the
///   left of (counter-clockwise from) the vector d that the two unknown vectors must add up to;
/// - an unknown angle and an unknown length (line ∩ circle): `Plus` makes the unknown-angle
///   vector point forward along the direction of the unknown-length vector;
/// - angle and length of one vector (polar): `Plus` gives a non-negative length, `Minus` a
///   non-positive one (the angle turned by π);
/// - two lengths: the solution is unique; the branch is ignored.
///
/// A mechanism keeps one branch for a whole cycle: the two branches meet only at a position
/// where the determinant vanishes (a dead point), which a continuous motion cannot cross.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Branch {
    /// The "+" sign in front of the square root.
    Plus,
    /// The "−" sign in front of the square root.
    Minus,
}

impl Branch {
    /// +1 for `Plus`, −1 for `Minus`.
    #[must_use]
    pub fn sign(self) -> f64 {
        match self {
            Self::Plus => 1.0,
            Self::Minus => -1.0,
        }
    }

    /// The other branch.
    #[must_use]
    pub fn flipped(self) -> Self {
        match self {
            Self::Plus => Self::Minus,
            Self::Minus => Self::Plus,
        }
    }
}

/// A length or an angle of a loop vector: known (with its time derivatives), or unknown.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Part {
    /// A known scalar with its rate and acceleration.
    Known(Motion),
    /// One of the contour's two unknowns.
    Unknown,
}

/// One vector of a closed contour.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum LoopVector {
    /// A fully known vector with its first and second time derivatives (for example the
    /// vector between two joints whose motion is known).
    Cartesian {
        /// The vector, m.
        r: Vector2<f64>,
        /// Its time derivative, m/s.
        v: Vector2<f64>,
        /// Its second time derivative, m/s².
        a: Vector2<f64>,
    },
    /// A vector L·e(θ) given by its length and direction angle, either of which (or both) may
    /// be unknown. A length paired with an unknown angle must be positive (it is a circle's
    /// radius); other lengths are algebraic.
    Polar {
        /// The length L.
        length: Part,
        /// The direction angle θ, radians CCW from +x.
        angle: Part,
    },
}

impl LoopVector {
    /// A constant vector.
    #[must_use]
    pub fn fixed(r: Vector2<f64>) -> Self {
        Self::Cartesian {
            r,
            v: Vector2::zeros(),
            a: Vector2::zeros(),
        }
    }

    /// A vector of known constant length and unknown direction (a link between two revolute
    /// joints).
    #[must_use]
    pub fn unknown_angle(length: f64) -> Self {
        Self::Polar {
            length: Part::Known(Motion::fixed(length)),
            angle: Part::Unknown,
        }
    }

    /// A vector of unknown length along a known (possibly rotating) direction (a slide).
    #[must_use]
    pub fn unknown_length(angle: Motion) -> Self {
        Self::Polar {
            length: Part::Unknown,
            angle: Part::Known(angle),
        }
    }

    /// A vector whose length and direction are both unknown.
    #[must_use]
    pub fn unknown() -> Self {
        Self::Polar {
            length: Part::Unknown,
            angle: Part::Unknown,
        }
    }
}

/// Which of the four closed forms a contour needed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ContourCase {
    /// Two unknown angles: the intersection of two circles.
    CircleCircle,
    /// An unknown angle and an unknown length in two vectors: a line meets a circle.
    LineCircle,
    /// The angle and length of one vector: polar coordinates.
    Polar,
    /// Two unknown lengths: two lines meet.
    Linear,
}

/// The solved contour: its two unknowns with their rates and accelerations.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContourSolution {
    /// The unknowns in loop order (vector by vector; within one vector the length first).
    /// Unknown angles are in [0, 2π).
    pub unknowns: [Motion; 2],
    /// The velocity system's determinant normalised by its column lengths: the sine of the
    /// angle between the two directions along which the unknowns move. |det| ≤ 1; its
    /// inverse is the amplification of velocities and accelerations.
    pub determinant: f64,
    /// The closed form used.
    pub case: ContourCase,
}

const GROUP: &str = "closed vector contour";
const MEASURE: &str = "sine between the unknowns' directions";

#[derive(Clone, Copy, PartialEq, Eq)]
enum Slot {
    Length(usize),
    Angle(usize),
}

/// Solves positions, velocities and accelerations of a closed contour.
///
/// # Examples
/// A four-bar's RRR loop C → A → B → C: the crank pin A = (0.1, 0), the rocker pivot
/// C = (0.3, 0), coupler AB = 0.2 and rocker CB = 0.2 make an isosceles triangle, so B lies
/// at (0.2, √0.03) on the `Plus` branch (left of A → C) and the two link directions are 60°
/// and 120° + 180°:
/// ```
/// use nalgebra::Vector2;
/// use approx::assert_relative_eq;
/// use tmm::kinematics::{solve_contour, Branch, LoopVector};
/// let loop_ = [
///     LoopVector::fixed(Vector2::new(-0.2, 0.0)), // C → A
///     LoopVector::unknown_angle(0.2),              // A → B, angle φ2
///     LoopVector::unknown_angle(0.2),              // B → C, angle φ3 + π
/// ];
/// let s = solve_contour(&loop_, Branch::Plus)?;
/// assert_relative_eq!(s.unknowns[0].value.to_degrees(), 60.0, epsilon = 1e-12);
/// assert_relative_eq!(s.unknowns[1].value.to_degrees(), 300.0, epsilon = 1e-12);
/// assert_relative_eq!(s.determinant, -(120f64.to_radians()).sin(), epsilon = 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// - [`Error::OutOfRange`] unless exactly two scalars are unknown;
/// - [`Error::NonFinite`] for a non-finite input, [`Error::NonPositive`] for a non-positive
///   length paired with an unknown angle;
/// - [`Error::NotAssemblable`] when the loop cannot close (`gap` is the shortfall, m);
/// - [`Error::Singular`] when the velocity system's normalised determinant is below
///   [`SINGULAR_DETERMINANT`] (a dead point; the tangent case of two merging branches), or
///   when the position itself is undetermined (parallel lines, concentric circles, a polar
///   vector of zero length).
#[doc(alias = "Zinoviev")]
pub fn solve_contour(vectors: &[LoopVector], branch: Branch) -> Result<ContourSolution> {
    let (slots, case) = classify(vectors)?;
    let holders = [slot_index(slots[0]), slot_index(slots[1])];
    // The known vectors' sums and their derivatives, in one pass (one sin_cos per vector).
    let (kr, kv, ka) = known_sums(vectors, holders);
    computed_all("sum of the known loop vectors", kr.iter())?;
    let (x, y) = checked_position(vectors, slots, case, branch, -kr)?;
    computed_all(
        "rates of the known loop vectors",
        kv.iter().chain(ka.iter()),
    )?;
    let mut m = [Motion::fixed(x), Motion::fixed(y)];
    // The vectors holding the unknowns (one vector in the polar case), with their unit
    // vectors computed once.
    let mut h = [
        Holder::new(vectors, holders[0]),
        Holder::new(vectors, holders[1]),
    ];
    let count = if holders[0] == holders[1] { 1 } else { 2 };
    for hk in &mut h[..count] {
        hk.fill(slots, &m);
    }
    // Columns of the velocity system: ∂(loop sum)/∂(unknown).
    let c = [0, 1].map(|k| {
        let hk = &h[usize::from(count == 2 && k == 1)];
        match slots[k] {
            Slot::Length(_) => hk.e,
            Slot::Angle(_) => hk.l.value * perp(hk.e),
        }
    });
    let det = cross(c[0], c[1]);
    let norm = c[0].norm() * c[1].norm();
    let determinant = if norm > 0.0 { det / norm } else { 0.0 };
    if determinant.abs() <= SINGULAR_DETERMINANT || !determinant.is_finite() {
        return Err(Error::Singular {
            what: GROUP,
            measure: MEASURE,
            value: determinant,
        });
    }
    // Velocities: the loop's derivative with the unknown rates at zero, then J·ẋ = −that.
    let v0 = h[..count].iter().fold(kv, |acc, hk| acc + hk.velocity());
    let rates = solve2(c, -v0, det);
    m[0].rate = rates[0];
    m[1].rate = rates[1];
    // Accelerations: the second derivative with the unknown accelerations at zero (it holds
    // the centripetal and Coriolis terms), then J·ẍ = −that.
    for hk in &mut h[..count] {
        hk.fill(slots, &m);
    }
    let a0 = h[..count]
        .iter()
        .fold(ka, |acc, hk| acc + hk.acceleration());
    let accels = solve2(c, -a0, det);
    m[0].accel = accels[0];
    m[1].accel = accels[1];
    computed_all(
        "contour velocities and accelerations",
        [m[0].rate, m[1].rate, m[0].accel, m[1].accel].iter(),
    )?;
    Ok(ContourSolution {
        unknowns: m,
        determinant,
        case,
    })
}

/// A vector that holds an unknown: its length and angle motions and its unit vector.
struct Holder {
    i: usize,
    l: Motion,
    t: Motion,
    e: Vector2<f64>,
}

impl Holder {
    fn new(vectors: &[LoopVector], i: usize) -> Self {
        let (length, angle) = polar(&vectors[i]).unwrap_or((Part::Unknown, Part::Unknown));
        Self {
            i,
            l: known(length),
            t: known(angle),
            e: Vector2::zeros(),
        }
    }

    /// Puts the unknowns' current motions into this vector and refreshes its unit vector.
    fn fill(&mut self, slots: [Slot; 2], m: &[Motion; 2]) {
        for (k, s) in slots.iter().enumerate() {
            match *s {
                Slot::Length(j) if j == self.i => self.l = m[k],
                Slot::Angle(j) if j == self.i => self.t = m[k],
                _ => {}
            }
        }
        self.e = unit(self.t.value);
    }

    fn velocity(&self) -> Vector2<f64> {
        self.l.rate * self.e + self.l.value * self.t.rate * perp(self.e)
    }

    /// The second derivative: centripetal −L·θ̇²·e, Coriolis 2·L̇·θ̇·e⊥, and the rest.
    fn acceleration(&self) -> Vector2<f64> {
        let (l, t) = (self.l, self.t);
        (l.accel - l.value * t.rate * t.rate) * self.e
            + (2.0 * l.rate * t.rate + l.value * t.accel) * perp(self.e)
    }
}

/// The sums of the vectors that hold no unknown, and of their first and second derivatives.
fn known_sums(
    vectors: &[LoopVector],
    holders: [usize; 2],
) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>) {
    let mut r = Vector2::zeros();
    let mut v = Vector2::zeros();
    let mut a = Vector2::zeros();
    for (i, vec) in vectors.iter().enumerate() {
        if holders.contains(&i) {
            continue;
        }
        match *vec {
            LoopVector::Cartesian {
                r: ri,
                v: vi,
                a: ai,
            } => {
                r += ri;
                v += vi;
                a += ai;
            }
            LoopVector::Polar { length, angle } => {
                let h = Holder {
                    i,
                    l: known(length),
                    t: known(angle),
                    e: unit(known(angle).value),
                };
                r += h.l.value * h.e;
                v += h.velocity();
                a += h.acceleration();
            }
        }
    }
    (r, v, a)
}

/// Solves only the position problem of a closed contour: the two unknowns in loop order.
///
/// This skips the velocity system, so it also works at a dead point.
///
/// # Errors
/// As [`solve_contour`], except that a vanishing velocity determinant is not an error.
pub fn solve_contour_position(vectors: &[LoopVector], branch: Branch) -> Result<[f64; 2]> {
    let (slots, case) = classify(vectors)?;
    let holders = [slot_index(slots[0]), slot_index(slots[1])];
    let (kr, _, _) = known_sums(vectors, holders);
    computed_all("sum of the known loop vectors", kr.iter())?;
    let (x, y) = checked_position(vectors, slots, case, branch, -kr)?;
    Ok([x, y])
}

/// [`position`], with [`Error::Overflow`] for a result (or a closure vector) that is not
/// finite although the inputs are: |d| above about 1.3·10¹⁵⁴ m overflows its square.
fn checked_position(
    vectors: &[LoopVector],
    slots: [Slot; 2],
    case: ContourCase,
    branch: Branch,
    d: Vector2<f64>,
) -> Result<(f64, f64)> {
    computed("length of the closing vector", d.norm())?;
    let (x, y) = position(vectors, slots, case, branch, d)?;
    computed("contour position", x)?;
    computed("contour position", y)?;
    Ok((x, y))
}

/// Finds the two unknowns, checks the inputs, and names the case.
fn classify(vectors: &[LoopVector]) -> Result<([Slot; 2], ContourCase)> {
    let mut slots = [Slot::Length(0); 2];
    let mut n = 0usize;
    for (i, v) in vectors.iter().enumerate() {
        match *v {
            LoopVector::Cartesian { r, v, a } => {
                finite2(["loop vector x", "loop vector y"], r)?;
                finite2(["loop vector rate x", "loop vector rate y"], v)?;
                finite2(["loop vector accel x", "loop vector accel y"], a)?;
            }
            LoopVector::Polar { length, angle } => {
                for (part, slot, names) in [
                    (
                        length,
                        Slot::Length(i),
                        ["loop length", "loop length rate", "loop length accel"],
                    ),
                    (
                        angle,
                        Slot::Angle(i),
                        ["loop angle", "loop angle rate", "loop angle accel"],
                    ),
                ] {
                    match part {
                        Part::Known(m) => m.validate(names)?,
                        Part::Unknown => {
                            if n < 2 {
                                slots[n] = slot;
                            }
                            n += 1;
                        }
                    }
                }
                if let (Part::Known(l), Part::Unknown) = (length, angle) {
                    crate::error::positive("loop length with an unknown angle", l.value)?;
                }
            }
        }
    }
    if n != 2 {
        return Err(Error::OutOfRange {
            name: "number of unknowns in the contour",
            value: n as f64,
            min: 2.0,
            max: 2.0,
            ends: crate::Ends::Closed,
        });
    }
    let case = match slots {
        [Slot::Length(i), Slot::Angle(j)] if i == j => ContourCase::Polar,
        [Slot::Angle(_), Slot::Angle(_)] => ContourCase::CircleCircle,
        [Slot::Length(_), Slot::Length(_)] => ContourCase::Linear,
        _ => ContourCase::LineCircle,
    };
    Ok((slots, case))
}

/// The known value of a part (0 for an unknown one; only called on known parts).
fn known(p: Part) -> Motion {
    match p {
        Part::Known(m) => m,
        Part::Unknown => Motion::default(),
    }
}

/// The (length, angle) of a polar vector, or None for a Cartesian one.
fn polar(v: &LoopVector) -> Option<(Part, Part)> {
    match *v {
        LoopVector::Polar { length, angle } => Some((length, angle)),
        LoopVector::Cartesian { .. } => None,
    }
}

/// The closed-form position solution: the two unknowns in slot order.
fn position(
    vectors: &[LoopVector],
    slots: [Slot; 2],
    case: ContourCase,
    branch: Branch,
    d: Vector2<f64>,
) -> Result<(f64, f64)> {
    // d: what the two vectors holding unknowns must add up to (minus the sum of the rest).
    let holders = [slot_index(slots[0]), slot_index(slots[1])];
    let sigma = branch.sign();
    let eps16 = 16.0 * f64::EPSILON;
    match case {
        ContourCase::Polar => {
            let r = d.norm();
            if r == 0.0 {
                return Err(Error::Singular {
                    what: GROUP,
                    measure: "length of the polar vector",
                    value: r,
                });
            }
            Ok(match branch {
                Branch::Plus => (r, direction(d)),
                Branch::Minus => (-r, direction(-d)),
            })
        }
        ContourCase::Linear => {
            let e1 = unit(known(polar(&vectors[holders[0]]).map_or(Part::Unknown, |p| p.1)).value);
            let e2 = unit(known(polar(&vectors[holders[1]]).map_or(Part::Unknown, |p| p.1)).value);
            let det = cross(e1, e2);
            if det.abs() <= SINGULAR_DETERMINANT {
                return Err(Error::Singular {
                    what: GROUP,
                    measure: "sine between the two slide directions",
                    value: det,
                });
            }
            Ok((cross(d, e2) / det, cross(e1, d) / det))
        }
        ContourCase::CircleCircle => {
            let a = known(polar(&vectors[holders[0]]).map_or(Part::Unknown, |p| p.0)).value;
            let b = known(polar(&vectors[holders[1]]).map_or(Part::Unknown, |p| p.0)).value;
            let l = d.norm();
            if l == 0.0 {
                return Err(Error::Singular {
                    what: GROUP,
                    measure: "distance between the circles' centres",
                    value: l,
                });
            }
            let e = d / l;
            // x = (l² + a² − b²)/(2l), written to lose fewer digits when l ≪ a, b.
            let x = 0.5 * (l + (a - b) * (a + b) / l);
            let h2 = (a - x) * (a + x);
            let tol = eps16 * (a * a + b * b + l * l);
            let h = if h2 < -tol {
                let gap = (l - a - b).max((a - b).abs() - l);
                return Err(Error::NotAssemblable {
                    group: GROUP,
                    gap: gap.max(0.0),
                });
            } else if h2 <= tol {
                0.0 // tangent circles: both branches merge here
            } else {
                h2.sqrt()
            };
            let p = x * e + sigma * h * perp(e);
            Ok((direction(p), direction(d - p)))
        }
        ContourCase::LineCircle => {
            // Which holder has the unknown angle, which the unknown length.
            let (ia, il, angle_first) = match slots {
                [Slot::Angle(i), Slot::Length(j)] => (i, j, true),
                [Slot::Length(j), Slot::Angle(i)] => (i, j, false),
                _ => unreachable!("classify gives LineCircle only for an angle and a length"),
            };
            let a = known(polar(&vectors[ia]).map_or(Part::Unknown, |p| p.0)).value;
            let beta = known(polar(&vectors[il]).map_or(Part::Unknown, |p| p.1)).value;
            let u = unit(beta);
            let n = perp(u);
            let q = n.dot(&d);
            let c2 = (a - q) * (a + q);
            let tol = eps16 * (a * a + d.norm_squared());
            let c = if c2 < -tol {
                return Err(Error::NotAssemblable {
                    group: GROUP,
                    gap: (q.abs() - a).max(0.0),
                });
            } else if c2 <= tol {
                0.0
            } else {
                c2.sqrt()
            };
            let p = sigma * c * u + q * n;
            let theta = direction(p);
            let s = (d - p).dot(&u);
            Ok(if angle_first { (theta, s) } else { (s, theta) })
        }
    }
}

fn slot_index(s: Slot) -> usize {
    match s {
        Slot::Length(i) | Slot::Angle(i) => i,
    }
}

/// The (length, angle) motions of a polar vector with the unknowns filled in from `m`.
fn filled(vectors: &[LoopVector], slots: [Slot; 2], m: &[Motion; 2], i: usize) -> (Motion, Motion) {
    let (length, angle) = polar(&vectors[i]).unwrap_or((Part::Unknown, Part::Unknown));
    let mut l = known(length);
    let mut t = known(angle);
    for (k, s) in slots.iter().enumerate() {
        match *s {
            Slot::Length(j) if j == i => l = m[k],
            Slot::Angle(j) if j == i => t = m[k],
            _ => {}
        }
    }
    (l, t)
}

/// Cramer's rule for [c0 c1]·x = rhs with det = c0 × c1.
fn solve2(c: [Vector2<f64>; 2], rhs: Vector2<f64>, det: f64) -> [f64; 2] {
    [cross(rhs, c[1]) / det, cross(c[0], rhs) / det]
}

/// The sum of a contour's vectors once its unknowns are filled in: the loop-closure residual
/// (zero for an exact solution), m.
///
/// # Errors
/// [`Error::OutOfRange`] unless exactly two scalars are unknown.
pub fn contour_residual(vectors: &[LoopVector], unknowns: [f64; 2]) -> Result<Vector2<f64>> {
    let (slots, _) = classify(vectors)?;
    let m = [Motion::fixed(unknowns[0]), Motion::fixed(unknowns[1])];
    let mut sum = Vector2::zeros();
    for (i, v) in vectors.iter().enumerate() {
        sum += match *v {
            LoopVector::Cartesian { r, .. } => r,
            LoopVector::Polar { .. } => {
                let (l, t) = filled(vectors, slots, &m, i);
                l.value * unit(t.value)
            }
        };
    }
    finite("contour residual", sum.norm())?;
    Ok(sum)
}

/// Renames a contour error after the group that closed the contour, so the user reads
/// "RRR dyad cannot be assembled" or "RRP dyad is singular: cos(phi2 - phi4) = …".
/// `det_sign` converts the contour's normalised determinant into the group's own measure.
pub(crate) fn in_group(
    e: Error,
    group: &'static str,
    measure: &'static str,
    det_sign: f64,
) -> Error {
    match e {
        Error::NotAssemblable { gap, .. } => Error::NotAssemblable { group, gap },
        Error::Singular {
            what: GROUP,
            measure: MEASURE,
            value,
        } => Error::Singular {
            what: group,
            measure,
            value: det_sign * value,
        },
        Error::Singular { measure, value, .. } => Error::Singular {
            what: group,
            measure,
            value,
        },
        other => other,
    }
}
