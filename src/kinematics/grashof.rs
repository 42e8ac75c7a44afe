//! Grashof's classification of a four-bar by its four lengths: which links can turn fully.
//!
//! With s the shortest and l the longest of the four lengths and p, q the other two, a link
//! can turn fully relative to its neighbours only if s + l ≤ p + q (Grashof's condition), and
//! then the links that turn fully are the shortest one and, relative to it, its neighbours.
//! Which link is the shortest then names the mechanism:
//!
//! | s + l vs p + q | shortest link | mechanism |
//! |---|---|---|
//! | < | the input (next to the frame) | crank-rocker: the input turns fully, the output rocks |
//! | < | the output (next to the frame) | rocker-crank: the output turns fully, the input rocks |
//! | < | the frame | double crank (drag link): both turn fully |
//! | < | the coupler | Grashof double rocker: both rock, the coupler turns fully |
//! | = | any | change point: it passes through positions where all four links are collinear and can switch its assembly mode there |
//! | > | any | triple rocker (non-Grashof): no link turns fully |

#[cfg(doc)]
use crate::error::Error;
use crate::error::Result;

/// Grashof's classification of a four-bar (see the module's table).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Grashof {
    /// s + l < p + q, the input the shortest: the input turns fully, the output rocks.
    CrankRocker,
    /// s + l < p + q, the output the shortest: the output turns fully, the input rocks.
    RockerCrank,
    /// s + l < p + q, the frame the shortest: both the input and the output turn fully.
    DoubleCrank,
    /// s + l < p + q, the coupler the shortest: the input and the output both rock.
    DoubleRocker,
    /// s + l = p + q (to rounding): the linkage folds flat at some position, where its
    /// assembly mode can switch.
    ChangePoint,
    /// s + l > p + q: no link turns fully relative to another.
    TripleRocker,
}

/// The class in words, as the module's table names it: "crank-rocker", "rocker-crank",
/// "double crank", "double rocker", "change point" or "triple rocker".
impl std::fmt::Display for Grashof {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::CrankRocker => "crank-rocker",
            Self::RockerCrank => "rocker-crank",
            Self::DoubleCrank => "double crank",
            Self::DoubleRocker => "double rocker",
            Self::ChangePoint => "change point",
            Self::TripleRocker => "triple rocker",
        })
    }
}

impl Grashof {
    /// Whether the input link turns fully in one assembly mode (the crank of a course
    /// project's mechanism). `false` for a change point: its shortest link may turn fully, but
    /// only through the flat positions, where the assembly mode is not determined and the
    /// closed forms are singular.
    #[must_use]
    pub fn input_turns_fully(self) -> bool {
        matches!(self, Self::CrankRocker | Self::DoubleCrank)
    }
}

/// Grashof's classification of the four-bar with the frame O1O3 (`frame`), the input O1A
/// (`input`), the coupler AB (`coupler`) and the output O3B (`output`), all in m.
///
/// s + l and p + q are compared to a relative 1e-12 of the sum of all four lengths: closer
/// than that, the four-bar is a [`Grashof::ChangePoint`].
///
/// # Examples
/// A course project's crank-rocker (frame 0.403, crank 0.10, coupler 0.35, rocker 0.30 m):
/// s + l = 0.503 < p + q = 0.65, and the crank is the shortest.
/// ```
/// use tmm::kinematics::{grashof, Grashof};
/// let g = grashof(0.403, 0.10, 0.35, 0.30)?;
/// assert_eq!(g, Grashof::CrankRocker);
/// assert!(g.input_turns_fully());
/// // A parallelogram is a change point; a frame shortest of all, a drag link.
/// assert_eq!(grashof(0.3, 0.1, 0.3, 0.1)?, Grashof::ChangePoint);
/// assert_eq!(grashof(0.1, 0.3, 0.35, 0.32)?, Grashof::DoubleCrank);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] or [`Error::NonPositive`] for a length that is not a finite positive
/// number; [`Error::Overflow`] when the lengths' sum overflows.
pub fn grashof(frame: f64, input: f64, coupler: f64, output: f64) -> Result<Grashof> {
    let lengths = [frame, input, coupler, output];
    for (name, l) in ["frame", "input", "coupler", "output"]
        .into_iter()
        .zip(lengths)
    {
        crate::error::positive(name, l)?;
    }
    let total = crate::error::computed("the sum of the four lengths", lengths.iter().sum())?;
    let (mut s, mut l) = (0, 0);
    for k in 1..4 {
        if lengths[k] < lengths[s] {
            s = k;
        }
        if lengths[k] > lengths[l] {
            l = k;
        }
    }
    if s == l {
        // All four equal: a rhombus, which folds flat.
        return Ok(Grashof::ChangePoint);
    }
    let others: f64 = total - lengths[s] - lengths[l];
    let excess = lengths[s] + lengths[l] - others;
    if excess.abs() <= 1e-12 * total {
        return Ok(Grashof::ChangePoint);
    }
    if excess > 0.0 {
        return Ok(Grashof::TripleRocker);
    }
    Ok(match s {
        0 => Grashof::DoubleCrank,
        1 => Grashof::CrankRocker,
        2 => Grashof::DoubleRocker,
        _ => Grashof::RockerCrank,
    })
}
