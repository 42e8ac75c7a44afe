//! The position of a triad with a sliding pair where its rates may not exist: at a branch
//! point (two assembly modes merging, its velocity system singular) the branch pose itself
//! ([`fold_point`](super::super::fold_point)), with the rates' error.

use super::{slider_triad_modes, slider_triad_rates, vec, Equation, SliderTriadDims};
use crate::error::{Error, Result};
use crate::kinematics::fold_point::fold_point;
use crate::kinematics::{Guide, PointMotion, TriadPose};
use nalgebra::{Complex, Point2};

/// The position of a triad with a sliding pair (arguments as [`slider_triad_modes`]) in the
/// mode nearest `reference` (the rule of every solve), also where its rates do not exist,
/// with the error its rates have there (`None` where they exist: then the pose is the
/// mode's, bit for bit).
///
/// Where they do not (the data within rounding of a branch point, where two modes merge:
/// [`Error::Singular`] naming `distance from a branch point/size`), the pose returned is the
/// branch pose itself, where the velocity system is singular, found by Newton's method on
/// the fold's equations from the mode: the scan places a double root only to ≈ √ε of the
/// size, the branch pose follows the data to ≈ ε (module docs of `fold_point`). Where those
/// steps do not settle (a degenerate fold, where more than two modes meet), the mode is
/// returned as found.
///
/// # Examples
/// A slider on the x axis carries B1 = (0, 0) of a ternary link B1 B2 = (1, 0),
/// B3 = (0.4, 0.8); the legs from A2 and A3 lie along the lines from B2 and B3 through
/// P = (0, 2), the slide's line of action (across the guide, through B1) passes P too: the
/// three lines meet, two modes merge there, and that pose is returned with the rates
/// refused.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use tmm::kinematics::{slider_triad_position, Guide, SliderTriadDims, SlidingPair, TriadPose};
/// use tmm::Error;
/// let b = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.4, 0.8)];
/// let p = Point2::new(0.0, 2.0);
/// let l = [0.9, 0.7];
/// let a = [1, 2].map(|k| b[k] - l[k - 1] * (b[k] - p).normalize());
/// let dims = SliderTriadDims {
///     pair: SlidingPair::Outer { offset: 0.0 },
///     l,
///     l_b1b2: 1.0,
///     b3_along: 0.4,
///     b3_across: 0.8,
/// };
/// let guide = Guide::fixed(Point2::new(-1.0, 0.0), 0.0);
/// let branch = TriadPose { b, theta: 0.0, phi: [0.0; 3], det: 0.0 };
/// let (pose, rates) = slider_triad_position(&guide, a, &dims, &branch)?;
/// let off = (0..3).map(|i| (pose.b[i] - b[i]).norm()).fold(0.0, f64::max);
/// assert!(off < 1e-12, "{off:e}");
/// assert!(matches!(rates, Some(Error::Singular { .. })));
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// As [`slider_triad_modes`]; the rates' own errors other than [`Error::Singular`] (bad
/// input: [`Error::NonFinite`]).
pub fn slider_triad_position(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
    reference: &TriadPose,
) -> Result<(TriadPose, Option<Error>)> {
    let modes = slider_triad_modes(first, a, dims)?;
    let mode = *modes.nearest(reference);
    let still = Guide::fixed(first.point.p, first.angle.value);
    let at_rest = a.map(PointMotion::fixed);
    let singular = match slider_triad_rates(&still, at_rest, dims, &mode) {
        Ok(_) => return Ok((mode, None)),
        Err(e @ Error::Singular { .. }) => e,
        Err(e) => return Err(e),
    };
    let e = Equation::new(&still, a, dims);
    let side = mode.b[1] - mode.b[0];
    let z = Complex::new(side.x, side.y) / side.norm();
    let Some((o, z, k)) = fold_point(|o, z| e.legs(o, z), mode.b[0].coords, z, e.length) else {
        return Ok((mode, Some(singular)));
    };
    let branch = e.pose(o, vec(z), &k);
    // The branch pose is nearer the fold than the mode: its rates fail as well (the error
    // reported is the branch pose's own measure).
    match slider_triad_rates(&still, at_rest, dims, &branch) {
        Err(e @ Error::Singular { .. }) => Ok((branch, Some(e))),
        _ => Ok((mode, Some(singular))),
    }
}

/// The next position of a triad with a sliding pair along a course of its data (arguments
/// as [`slider_triad_modes`]), continued from the two positions before it, `before` then
/// `previous`: the mode nearest the pose extrapolated from them (2·previous − before, joint
/// by joint), as [`slider_triad_position`] gives it (so at a branch point the branch pose,
/// with the rates' error).
///
/// Why the extrapolation and not the previous pose: where the course passes a point where
/// two modes meet and part again (its data touching the branch set, as a Grashof
/// change-point four-bar's crank passes its dead centres), the two branches cross there,
/// x = x* + c₁·t and x = x* + c₂·t, and one step h past it they are |c₁ − c₂|·h apart while
/// the previous pose, h before it on the first, is as far from both when c₂ = −c₁: the
/// nearest mode is either. The extrapolated pose is within O(h²) of the branch whose
/// velocity continues (c₁), and the other is |c₁ − c₂|·h away. Where the course reverses at
/// a branch point (a rocking input at its lock: the data go up to the branch set and back),
/// the extrapolation from the branch pose x* and the pose before it, x* + c·√h·n on one
/// mode, is x* − c·√h·n, the partner mode's pose: the motion continues on the partner, as
/// it does through a dyad's dead centre.
///
/// # Errors
/// As [`slider_triad_position`].
pub fn slider_triad_continued(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
    before: &TriadPose,
    previous: &TriadPose,
) -> Result<(TriadPose, Option<Error>)> {
    let predicted = TriadPose {
        b: [0, 1, 2].map(|i| previous.b[i] + (previous.b[i] - before.b[i])),
        ..*previous
    };
    slider_triad_position(first, a, dims, &predicted)
}
