//! A triad solved in its own unit frame: the same mechanism at any scale and anywhere in the
//! plane.
//!
//! The triads' eliminated equation carries products of up to four lengths (squared distances
//! of squared distances), so a triad drawn in light-years (10¹⁶ m) overflows it at 10⁷⁷ and
//! one drawn at 10⁻⁷⁷ m underflows it to zero, though nothing else of the linkage comes near
//! the range of `f64`; and its coefficients built from coordinates far from the origin lose
//! the digits of the offset squared. A triad is the same mechanism under a translation and a
//! change of the unit of length, so the engine hands the kinematics the triad relative to one
//! of its known joints and in a unit u that is a power of two near the triad's own size:
//! p ↦ (p − o)/u, every velocity and acceleration over u, every length over u, every angle,
//! rate and the conditioning det K/L_T (a pure number: K has one column of lengths, L_T a
//! length) unchanged. Dividing by a power of two is exact, so the triad at scale 2ᵏ·s solves to
//! the same bits as at s; only the subtraction of o rounds, once, to ε of the coordinates.

use crate::error::Result;
use crate::kinematics::{
    slider_triad, slider_triad_modes, slider_triad_rates, triad, triad_modes, triad_rates, Guide,
    LinkMotion, PointMotion, SliderTriadDims, SlidingPair, TriadDims, TriadPose, TriadState,
};
use nalgebra::{Point2, Vector2};

/// The frame: its origin o and unit u (a power of two, or 1 for a size that has none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct UnitFrame {
    origin: Point2<f64>,
    unit: f64,
    inverse: f64,
}

impl UnitFrame {
    /// The frame at `origin` whose unit is the power of two at or below `size` (its exponent
    /// bits): 1 when `size` is not a positive normal number, so that bad input reaches the
    /// kinematics' own checks unchanged in magnitude.
    pub(crate) fn new(origin: Point2<f64>, size: f64) -> Self {
        let unit = if size.is_normal() && size > 0.0 {
            f64::from_bits(size.to_bits() & 0x7FF0_0000_0000_0000)
        } else {
            1.0
        };
        let inverse = unit.recip();
        // u in 2⁻¹⁰²² … 2¹⁰²³: 1/u is a power of two too, at worst subnormal but exact. A
        // non-finite origin is bad input: handed on unchanged, for the kinematics to name.
        let (unit, inverse, origin) = if origin.x.is_finite() && origin.y.is_finite() {
            (unit, inverse, origin)
        } else {
            (1.0, 1.0, Point2::origin())
        };
        Self {
            origin,
            unit,
            inverse,
        }
    }

    /// The frame of a triad: at `origin`, its unit the size of its longest dimension.
    pub(crate) fn of_triad(origin: Point2<f64>, dims: &TriadDims) -> Self {
        let size = dims.l[0]
            .max(dims.l[1])
            .max(dims.l[2])
            .max(dims.l_b1b2)
            .max(dims.b3_along.abs())
            .max(dims.b3_across.abs());
        Self::new(origin, size)
    }

    /// The frame of a triad with a sliding pair, as [`of_triad`](Self::of_triad).
    pub(crate) fn of_slider_triad(origin: Point2<f64>, dims: &SliderTriadDims) -> Self {
        let offset = match dims.pair {
            SlidingPair::Outer { offset } | SlidingPair::Inner { offset, .. } => offset.abs(),
        };
        let size = dims.l[0]
            .max(dims.l[1])
            .max(dims.l_b1b2)
            .max(dims.b3_along.abs())
            .max(dims.b3_across.abs())
            .max(offset);
        Self::new(origin, size)
    }

    fn length(&self, x: f64) -> f64 {
        x * self.inverse
    }

    fn vector(&self, v: Vector2<f64>) -> Vector2<f64> {
        v * self.inverse
    }

    fn point(&self, p: Point2<f64>) -> Point2<f64> {
        Point2::from(self.vector(p - self.origin))
    }

    fn motion(&self, m: PointMotion) -> PointMotion {
        PointMotion::new(self.point(m.p), self.vector(m.v), self.vector(m.a))
    }

    fn point_back(&self, p: Point2<f64>) -> Point2<f64> {
        self.origin + p.coords * self.unit
    }

    fn motion_back(&self, m: PointMotion) -> PointMotion {
        PointMotion::new(self.point_back(m.p), m.v * self.unit, m.a * self.unit)
    }

    fn link_back(&self, m: LinkMotion) -> LinkMotion {
        LinkMotion {
            origin: self.motion_back(m.origin),
            ..m
        }
    }

    fn pose(&self, p: &TriadPose) -> TriadPose {
        TriadPose {
            b: p.b.map(|b| self.point(b)),
            ..*p
        }
    }

    fn pose_back(&self, p: &TriadPose) -> TriadPose {
        TriadPose {
            b: p.b.map(|b| self.point_back(b)),
            ..*p
        }
    }

    fn state_back(&self, s: TriadState) -> TriadState {
        TriadState {
            b: s.b.map(|m| self.motion_back(m)),
            ternary: self.link_back(s.ternary),
            binary: s.binary.map(|m| self.link_back(m)),
            det: s.det,
        }
    }

    fn dims(&self, d: &TriadDims) -> TriadDims {
        TriadDims::new(
            d.l.map(|l| self.length(l)),
            self.length(d.l_b1b2),
            self.length(d.b3_along),
            self.length(d.b3_across),
        )
    }

    fn slider_dims(&self, d: &SliderTriadDims) -> SliderTriadDims {
        SliderTriadDims {
            pair: match d.pair {
                SlidingPair::Outer { offset } => SlidingPair::Outer {
                    offset: self.length(offset),
                },
                SlidingPair::Inner { angle, offset } => SlidingPair::Inner {
                    angle,
                    offset: self.length(offset),
                },
            },
            l: d.l.map(|l| self.length(l)),
            l_b1b2: self.length(d.l_b1b2),
            b3_along: self.length(d.b3_along),
            b3_across: self.length(d.b3_across),
        }
    }

    fn guide(&self, g: &Guide) -> Guide {
        Guide {
            point: self.motion(g.point),
            angle: g.angle,
        }
    }
}

/// [`triad`] in the triad's unit frame at its first known joint (module docs).
pub(crate) fn triad_scaled(
    a: [PointMotion; 3],
    dims: &TriadDims,
    previous: &TriadPose,
) -> Result<TriadState> {
    let f = UnitFrame::of_triad(a[0].p, dims);
    triad(a.map(|m| f.motion(m)), &f.dims(dims), &f.pose(previous)).map(|s| f.state_back(s))
}

/// [`triad_rates`] in the triad's unit frame at its first known joint.
pub(crate) fn triad_rates_scaled(
    a: [PointMotion; 3],
    dims: &TriadDims,
    pose: &TriadPose,
) -> Result<TriadState> {
    let f = UnitFrame::of_triad(a[0].p, dims);
    triad_rates(a.map(|m| f.motion(m)), &f.dims(dims), &f.pose(pose)).map(|s| f.state_back(s))
}

/// The mode of [`triad_modes`] nearest `to`, in the triad's unit frame at its first known
/// joint.
pub(crate) fn triad_mode_nearest(
    a: [Point2<f64>; 3],
    dims: &TriadDims,
    to: &TriadPose,
) -> Result<TriadPose> {
    let f = UnitFrame::of_triad(a[0], dims);
    let modes = triad_modes(a.map(|p| f.point(p)), &f.dims(dims))?;
    Ok(f.pose_back(modes.nearest(&f.pose(to))))
}

/// [`slider_triad`] in the triad's unit frame at the sliding leg's known point.
pub(crate) fn slider_triad_scaled(
    first: &Guide,
    a: [PointMotion; 2],
    dims: &SliderTriadDims,
    previous: &TriadPose,
) -> Result<TriadState> {
    let f = UnitFrame::of_slider_triad(first.point.p, dims);
    slider_triad(
        &f.guide(first),
        a.map(|m| f.motion(m)),
        &f.slider_dims(dims),
        &f.pose(previous),
    )
    .map(|s| f.state_back(s))
}

/// [`slider_triad_rates`] in the triad's unit frame at the sliding leg's known point.
pub(crate) fn slider_triad_rates_scaled(
    first: &Guide,
    a: [PointMotion; 2],
    dims: &SliderTriadDims,
    pose: &TriadPose,
) -> Result<TriadState> {
    let f = UnitFrame::of_slider_triad(first.point.p, dims);
    slider_triad_rates(
        &f.guide(first),
        a.map(|m| f.motion(m)),
        &f.slider_dims(dims),
        &f.pose(pose),
    )
    .map(|s| f.state_back(s))
}

/// The mode of [`slider_triad_modes`] nearest `to`, in the triad's unit frame at the sliding
/// leg's known point.
pub(crate) fn slider_triad_mode_nearest(
    first: &Guide,
    a: [Point2<f64>; 2],
    dims: &SliderTriadDims,
    to: &TriadPose,
) -> Result<TriadPose> {
    let f = UnitFrame::of_slider_triad(first.point.p, dims);
    let modes = slider_triad_modes(&f.guide(first), a.map(|p| f.point(p)), &f.slider_dims(dims))?;
    Ok(f.pose_back(modes.nearest(&f.pose(to))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_is_the_power_of_two_at_or_below_the_size() {
        let o = Point2::new(1.0, 2.0);
        assert_eq!(UnitFrame::new(o, 3.0).unit, 2.0);
        assert_eq!(UnitFrame::new(o, 1e300).unit, 2f64.powi(996));
        assert_eq!(UnitFrame::new(o, 1e-300).unit, 2f64.powi(-997));
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-310] {
            assert_eq!(UnitFrame::new(o, bad).unit, 1.0, "{bad}");
        }
        // An inverse that would be subnormal is still exact: the round trip is bit for bit.
        let f = UnitFrame::new(Point2::origin(), f64::MAX);
        let p = Point2::new(3.0e307, -1.5e308);
        assert_eq!(f.point_back(f.point(p)), p);
    }
}
