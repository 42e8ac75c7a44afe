//! The motions of a linkage's inputs at one position: one, or two for a linkage of
//! mobility 2.

use crate::error::{Error, Result};
use crate::kinematics::Motion;

/// The motion of each input at one position: φ, ω, ε of a crank (s, ṡ, s̈ of a slider), one
/// per input in the order of [`Linkage::input`](super::Linkage::input) and
/// [`Linkage::second_input`](super::Linkage::second_input).
///
/// Every solve takes `impl Into<Inputs>`, so one input is just a [`Motion`].
///
/// # Examples
/// ```
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, Inputs, Plan};
/// let four_bar = Plan::new(&bundled::four_bar())?;
/// let a = four_bar.analyse(Motion::turning(1.0, 10.0))?;
/// assert_eq!(a.balances().len(), 1);
/// let robot = Plan::new(&bundled::five_bar_robot())?;
/// let r = robot.reference_inputs();
/// let b = robot.analyse(Inputs::two(Motion::turning(r[0], 2.0), Motion::fixed(r[1])))?;
/// assert_eq!(b.balances().len(), 2);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs {
    motions: [Motion; 2],
    count: usize,
}

impl Inputs {
    /// One input's motion.
    #[must_use]
    pub fn one(m: Motion) -> Self {
        Self {
            motions: [m, Motion::default()],
            count: 1,
        }
    }

    /// Two inputs' motions, the first input's first.
    #[must_use]
    pub fn two(first: Motion, second: Motion) -> Self {
        Self {
            motions: [first, second],
            count: 2,
        }
    }

    /// One motion per input, from a slice of one or two.
    ///
    /// # Errors
    /// [`Error::Description`] for an empty slice or one of more than two motions.
    pub fn from_slice(motions: &[Motion]) -> Result<Self> {
        match *motions {
            [m] => Ok(Self::one(m)),
            [m, n] => Ok(Self::two(m, n)),
            _ => Err(Error::Description {
                item: "inputs".to_owned(),
                problem: format!(
                    "a linkage has one or two inputs, {} motion(s) given",
                    motions.len()
                ),
            }),
        }
    }

    /// The motions, one per input.
    #[must_use]
    pub fn as_slice(&self) -> &[Motion] {
        &self.motions[..self.count]
    }

    /// The number of inputs: 1 or 2.
    #[must_use]
    pub fn len(&self) -> usize {
        self.count
    }

    /// Always `false`: there is at least one input.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The first input's motion.
    #[must_use]
    pub fn first(&self) -> Motion {
        self.motions[0]
    }

    /// Input `i`'s motion (0 the first), if there is one.
    #[must_use]
    pub fn get(&self, i: usize) -> Option<Motion> {
        self.as_slice().get(i).copied()
    }
}

/// The largest magnitude of an input coordinate a course takes: 10⁹ (rad for a crank, m for a
/// slider).
///
/// An `f64` near 10⁹ is spaced 2⁻²³ ≈ 1.2·10⁻⁷ apart, and the turns a crank angle holds there
/// are reduced by a 2π that is itself rounded (by up to 2.4·10⁻¹⁶ rad a turn, some 4·10⁻⁸ rad
/// over 1.6·10⁸ turns): within ±10⁹ rad an angle still names a position of the crank to about
/// 10⁻⁷ rad. Beyond, it names none — at 10¹⁶ rad neighbouring values are a whole turn apart,
/// and sin/cos of 10³⁰⁰ rad are rounding noise — so a course refuses it rather than drawing
/// some other position. A slider's coordinate is held to the same bound in metres: 10⁶ km,
/// beyond any machine, where its positions too are 1.2·10⁻⁷ m apart.
pub const MAX_INPUT_COORDINATE: f64 = 1e9;

/// `value`, an input coordinate named `name`, within ±[`MAX_INPUT_COORDINATE`].
pub(crate) fn check_input_coordinate(name: &'static str, value: f64) -> Result<()> {
    if value.abs() <= MAX_INPUT_COORDINATE {
        return Ok(());
    }
    crate::error::finite(name, value)?;
    Err(Error::OutOfRange {
        name,
        value,
        min: -MAX_INPUT_COORDINATE,
        max: MAX_INPUT_COORDINATE,
        ends: crate::Ends::Closed,
    })
}

impl From<Motion> for Inputs {
    fn from(m: Motion) -> Self {
        Self::one(m)
    }
}

impl From<&Motion> for Inputs {
    fn from(m: &Motion) -> Self {
        Self::one(*m)
    }
}

impl From<[Motion; 2]> for Inputs {
    fn from([m, n]: [Motion; 2]) -> Self {
        Self::two(m, n)
    }
}

impl From<(Motion, Motion)> for Inputs {
    fn from((m, n): (Motion, Motion)) -> Self {
        Self::two(m, n)
    }
}
