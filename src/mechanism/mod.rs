//! Whole mechanisms over a cycle: kinematics, inertia loads, joint reactions and the balancing
//! moment or force, group by group as the seeds teach (seed 000 §1.2, seed 001's group-wise
//! method).
//!
//! Each ready mechanism is a plain struct of public parameters (SI units) with a constructor
//! of realistic data, and one method `analyse(input)` whose body is a short chain of the
//! crate's blocks in the seeds' order:
//!
//! 1. the input link ([`crank`](crate::kinematics::crank)), then each group's kinematics in the
//!    order the groups are attached;
//! 2. the loads of every link: d'Alembert's inertia loads and weights ([`LinkMass::load`]), and
//!    the external loads, which may depend on the position (a gas-pressure diagram on a piston,
//!    [`IndicatorDiagram`]; a resistance on the working stroke);
//! 3. the kinetostatics of the group attached last, then of the one before it with the reactions
//!    reversed onto it (`R_ji = −R_ij`), and so on;
//! 4. the input link: the balancing moment (coupling) or force (gear), [`Drive`].
//!
//! | mechanism | groups | output |
//! |-----------|--------|--------|
//! | [`FourBar`] | crank + RRR | rocker 3 |
//! | [`SliderCrank`] | crank + RRP | piston 3 (with an indicator diagram) |
//! | [`Compressor`] | crank with two throws + RRP + RRP (seed 001) | pistons 3 and 5 |
//! | [`SixBar`] | crank + RRR + RRP (seed 001, fig. 2.10's type) | slider 5 |
//! | [`RockingCylinder`] | crank + RPR | the rocking cylinder (or slotted lever) 3 |
//!
//! Every position result implements [`Analysed`]: its links as [`FreeBody`]s, checked by the
//! principle of virtual power ([`Analysed::power_check`]) and by each link's equilibrium
//! ([`Analysed::worst_residual`]), and [`Tabulate`], so a cycle becomes a [`Table`] written as
//! CSV. A failed position (a group at a dead point, or one that cannot be assembled) is an
//! [`Error::In`] naming the group, for that position only: [`run_cycle`] goes on past it.
//!
//! A user who wants one dyad calls the dyad's solver directly; a mechanism of another layout
//! is a copy of the closest `analyse` with its chain changed.
//!
//! # Example
//! The course-project six-bar at 30° of its crank, and the two ways to its balancing moment:
//! ```
//! use tmm::kinematics::Motion;
//! use tmm::mechanism::{Analysed, SixBar};
//! let m = SixBar::course_example();
//! let p = m.analyse(Motion::new(30f64.to_radians(), 10.0, 0.0))?;
//! let check = p.power_check()?;
//! assert!(check.relative_error() < 1e-9);
//! assert!(p.worst_residual() < 1e-12);
//! # Ok::<(), tmm::Error>(())
//! ```

mod compressor;
mod drive;
mod four_bar;
mod link;
mod power;
mod pressure;
mod rocking_cylinder;
mod six_bar;
mod slider_crank;
mod table;

pub use compressor::{Compressor, CompressorPosition};
pub use drive::{Balance, Drive};
pub use four_bar::{FourBar, FourBarPosition};
pub use link::LinkMass;
pub use power::{power_of, virtual_power_moment, FreeBody, Residual};
pub use pressure::IndicatorDiagram;
pub use rocking_cylinder::{RockingCylinder, RockingCylinderPosition};
pub use six_bar::{SixBar, SixBarPosition};
pub use slider_crank::{SliderCrank, SliderCrankPosition};
pub use table::{Column, Table, Tabulate};

use crate::error::{Error, Result};
use crate::kinematics::{
    cycle_angles, extreme_positions, transfer_functions, Motion, Rotation, Strokes,
};

/// The balancing moment found two ways at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PowerCheck {
    /// M_b from the group-by-group chain, N·m.
    pub chain: f64,
    /// M_b from the principle of virtual power, N·m.
    pub virtual_power: f64,
    /// The scale of the comparison: the largest of |M_b| and Σ|P_i|/|ω1|, N·m.
    pub scale: f64,
}

impl PowerCheck {
    /// |chain − virtual power| / scale.
    #[must_use]
    pub fn relative_error(&self) -> f64 {
        let d = (self.chain - self.virtual_power).abs();
        if self.scale > 0.0 {
            d / self.scale
        } else {
            d
        }
    }
}

/// What every analysed position of a ready mechanism offers: its input, its balance, and its
/// links cut free with every load and reaction.
pub trait Analysed {
    /// The input link's φ1, ω1, ε1.
    fn input(&self) -> Motion;
    /// The balancing moment (or force) and the frame's reaction on the input link.
    fn balance(&self) -> Balance;
    /// Every moving link as a free body (the input link first, with the drive's load).
    fn free_bodies(&self) -> Vec<FreeBody>;

    /// The balancing moment by the chain and by the principle of virtual power.
    ///
    /// # Errors
    /// [`Error::Singular`] when ω1 = 0 (see [`virtual_power_moment`]).
    fn power_check(&self) -> Result<PowerCheck> {
        let (vp, scale) = virtual_power_moment(&self.free_bodies(), self.input().rate)?;
        let chain = self.balance().moment;
        Ok(PowerCheck {
            chain,
            virtual_power: vp,
            scale: scale.max(chain.abs()),
        })
    }

    /// The largest relative equilibrium residual of any link ([`Residual::relative`]).
    fn worst_residual(&self) -> f64 {
        self.free_bodies()
            .iter()
            .map(|b| b.residual().relative())
            .fold(0.0, f64::max)
    }
}

/// The input link's name in every ready mechanism, for errors and free bodies.
pub(crate) const CRANK: &str = "link 1 (crank)";

/// +1, −1, or 0 for a zero: the sense a resistance opposes. Unlike [`f64::signum`] it gives 0
/// at rest, where a resistance vanishes.
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Wraps an error of one part of a mechanism (a group, the input link) so that it names it.
pub(crate) fn within(part: &'static str) -> impl Fn(Error) -> Error {
    move |e| Error::In {
        part: part.to_owned(),
        source: Box::new(e),
    }
}

/// The inputs of `n` equally spaced positions over one turn from `start`, at the constant
/// speed ω1 = `omega1` and acceleration ε1 = `epsilon1`. A negative ω1 turns clockwise: the
/// angles then decrease from `start`, in the order the crank reaches them.
#[must_use]
pub fn uniform_inputs(n: usize, start: f64, omega1: f64, epsilon1: f64) -> Vec<Motion> {
    let angles = cycle_angles(n, start);
    if omega1 < 0.0 {
        // The same angles visited clockwise: start, start − step, …
        let mut a = Vec::with_capacity(n);
        a.extend(angles.first().copied());
        a.extend(angles.iter().skip(1).rev().copied());
        a.into_iter()
            .map(|phi| Motion::new(phi, omega1, epsilon1))
            .collect()
    } else {
        angles
            .into_iter()
            .map(|phi| Motion::new(phi, omega1, epsilon1))
            .collect()
    }
}

/// The inputs of the `n` plans of a course project (12 in the seeds): equally spaced from the
/// beginning of the working stroke in the crank's sense of rotation, at the speed |ω1| =
/// `omega1` (its sign follows the rotation).
#[must_use]
pub fn course_inputs(strokes: &Strokes, n: usize, omega1: f64) -> Vec<Motion> {
    let w = match strokes.rotation {
        Rotation::Ccw => omega1.abs(),
        Rotation::Cw => -omega1.abs(),
    };
    strokes
        .plan_positions(n)
        .into_iter()
        .map(|phi| Motion::new(phi, w, 0.0))
        .collect()
}

/// Runs an analysis at every input, position by position. A position that fails (for example
/// a group at a dead point) gives its `Err` in its place and the cycle goes on. The cost is
/// linear in the number of positions.
///
/// # Examples
/// ```
/// use tmm::mechanism::{run_cycle, uniform_inputs, SixBar};
/// let m = SixBar::course_example();
/// let positions = run_cycle(&uniform_inputs(36, 0.0, 10.0, 0.0), |i| m.analyse(i));
/// assert!(positions.iter().all(Result::is_ok));
/// ```
pub fn run_cycle<P, F>(inputs: &[Motion], analyse: F) -> Vec<Result<P>>
where
    F: Fn(Motion) -> Result<P>,
{
    inputs.iter().map(|&i| analyse(i)).collect()
}

/// [`run_cycle`] on all cores (feature `rayon`): the same results, bit for bit, in the same
/// order, because every position is a pure function of its input.
#[cfg(feature = "rayon")]
pub fn run_cycle_parallel<P, F>(inputs: &[Motion], analyse: F) -> Vec<Result<P>>
where
    P: Send,
    F: Fn(Motion) -> Result<P> + Sync,
{
    use rayon::prelude::*;
    inputs.par_iter().map(|&i| analyse(i)).collect()
}

/// serde for the crate's types that this module stores (feature `serde`).
#[cfg(feature = "serde")]
pub(crate) mod serde_remote {
    /// [`Branch`](crate::kinematics::Branch) as "Plus" or "Minus".
    #[derive(serde::Serialize, serde::Deserialize)]
    #[serde(remote = "crate::kinematics::Branch")]
    pub(crate) enum BranchDef {
        Plus,
        Minus,
    }
}

/// The strokes of an output coordinate (its transfer functions from `output` at unit input
/// speed): the extremes over 360 samples, refined to machine precision.
pub(crate) fn output_strokes<F>(output: F, rotation: Rotation) -> Result<Strokes>
where
    F: Fn(Motion) -> Result<Motion>,
{
    let ext = extreme_positions(|phi| transfer_functions(&output, phi), 360)?;
    Strokes::new(&ext, rotation)
}
