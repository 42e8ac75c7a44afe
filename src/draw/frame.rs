//! The mapping from the plane of a linkage to the pixels of a picture.

use crate::error::{Error, Result};
use nalgebra::Point2;

/// How a picture maps the plane of the linkage (metres, x right, y up) to its pixels (x
/// right, y down): one scale for both axes, so lengths and angles look as they are.
///
/// A point (x, y) m lands at pixel (`origin[0]` + `scale`·x, `origin[1]` − `scale`·y).
///
/// # Examples
/// ```
/// use tmm::draw::Frame;
/// use tmm::nalgebra::Point2;
/// let f = Frame::fit(Point2::new(0.0, 0.0), Point2::new(2.0, 1.0), 400.0, 300.0, 20.0)?;
/// assert_eq!(f.scale, 180.0); // 360 px for 2 m
/// let [x, y] = f.to_pixel(Point2::new(2.0, 1.0));
/// assert_eq!([x, y], [380.0, 60.0]);
/// assert_eq!(f.to_world([x, y]), Point2::new(2.0, 1.0));
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Pixels per metre, on both axes.
    pub scale: f64,
    /// The pixel where the plane's origin lands.
    pub origin: [f64; 2],
    /// The picture's width, px.
    pub width: f64,
    /// The picture's height, px.
    pub height: f64,
}

impl Frame {
    /// The largest scale that shows the box from `lo` to `hi` (m) in a picture of `width` ×
    /// `height` px with `margin` px on every side, the box centred.
    ///
    /// The frame it returns is finite, and so is the pixel of every point of the box: a box
    /// that would need a scale or an origin beyond f64's range, or an origin so far off (more
    /// than [`Frame::MAX_ORIGIN`] px) that pixel numbers would lose their hundredths, is an
    /// error rather than a frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite corner, size or margin; [`Error::OutOfRange`]
    /// for a width or height outside (0, [`Frame::MAX_SIZE`]] px or a negative margin;
    /// [`Error::Drawing`] for a corner `lo` above or right of `hi`, a picture with no room
    /// inside its margins, a box of no extent (a single point) or of an extent beyond f64's
    /// range, or a frame whose scale or origin would not be finite or would lie farther off
    /// than [`Frame::MAX_ORIGIN`].
    ///
    /// # Examples
    /// A box twice as wide as high in a square picture: the width decides the scale.
    /// ```
    /// use tmm::draw::Frame;
    /// use tmm::nalgebra::Point2;
    /// let f = Frame::fit(Point2::new(-1.0, 0.0), Point2::new(1.0, 1.0), 100.0, 100.0, 0.0)?;
    /// assert_eq!(f.scale, 50.0);
    /// assert!(Frame::fit(Point2::origin(), Point2::origin(), 100.0, 100.0, 0.0).is_err());
    /// // A box upside down, an infinite picture, a box a subnormal wide at 10¹⁶ m: errors.
    /// let (lo, hi) = (Point2::new(5e-324, 1e16), Point2::new(1e-310, 1e12));
    /// assert!(Frame::fit(lo, hi, 1e-16, 1e308, 1e-154).is_err());
    /// assert!(Frame::fit(Point2::origin(), Point2::new(1.0, 1.0), f64::INFINITY, 1.0, 0.0).is_err());
    /// let (lo, hi) = (Point2::new(1e16, 1e16), Point2::new(1e16 + 2.0, 1e16 + 2.0));
    /// assert!(Frame::fit(lo, hi, 800.0, 600.0, 40.0).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn fit(
        lo: Point2<f64>,
        hi: Point2<f64>,
        width: f64,
        height: f64,
        margin: f64,
    ) -> Result<Self> {
        crate::error::finite2(["lo.x", "lo.y"], lo.coords)?;
        crate::error::finite2(["hi.x", "hi.y"], hi.coords)?;
        for (name, v) in [("width", width), ("height", height)] {
            crate::error::finite(name, v)?;
            if !(v > 0.0 && v <= Self::MAX_SIZE) {
                return Err(Error::OutOfRange {
                    name,
                    value: v,
                    min: 0.0,
                    max: Self::MAX_SIZE,
                    ends: crate::Ends::OpenBelow,
                });
            }
        }
        crate::error::finite("margin", margin)?;
        if margin < 0.0 {
            return Err(Error::OutOfRange {
                name: "margin",
                value: margin,
                min: 0.0,
                max: f64::INFINITY,
                ends: crate::Ends::Closed,
            });
        }
        if lo.x > hi.x || lo.y > hi.y {
            return Err(drawing(
                "a frame",
                format!("the box's corner lo {lo:?} lies above or right of hi {hi:?}"),
            ));
        }
        let room = [width - 2.0 * margin, height - 2.0 * margin];
        if !(room[0] > 0.0 && room[1] > 0.0) {
            return Err(drawing(
                "a frame",
                format!(
                    "a picture of {width} × {height} px has no room inside margins of {margin} px"
                ),
            ));
        }
        let span = hi - lo;
        if !(span.x.is_finite() && span.y.is_finite()) {
            return Err(drawing(
                "a frame",
                format!("the box from {lo:?} to {hi:?} is wider than f64's range"),
            ));
        }
        let sx = if span.x > 0.0 {
            room[0] / span.x
        } else {
            f64::INFINITY
        };
        let sy = if span.y > 0.0 {
            room[1] / span.y
        } else {
            f64::INFINITY
        };
        let scale = sx.min(sy);
        if !scale.is_finite() || scale <= 0.0 {
            return Err(drawing(
                "a frame",
                format!("the box from {lo:?} to {hi:?} has no extent to draw"),
            ));
        }
        let c = nalgebra::center(&lo, &hi);
        let origin = [0.5 * width - scale * c.x, 0.5 * height + scale * c.y];
        if !origin.iter().all(|o| o.abs() <= Self::MAX_ORIGIN) {
            return Err(drawing(
                "a frame",
                format!(
                    "the box from {lo:?} to {hi:?} at {scale:e} px/m puts the plane's origin at \
                     {origin:?} px, beyond ±{:e} px",
                    Self::MAX_ORIGIN
                ),
            ));
        }
        Ok(Self {
            scale,
            origin,
            width,
            height,
        })
    }

    /// The largest width or height of a picture [`Frame::fit`] accepts, px: 10⁶.
    pub const MAX_SIZE: f64 = 1e6;

    /// The farthest the plane's origin may land from the picture's corner, px: 10¹². Beyond
    /// it a pixel number (origin + scale·x) would keep less than a hundredth of a pixel of its
    /// point's place.
    pub const MAX_ORIGIN: f64 = 1e12;

    /// The pixel of the point `p` of the plane.
    ///
    /// # Examples
    /// ```
    /// use tmm::draw::Frame;
    /// use tmm::nalgebra::Point2;
    /// let f = Frame { scale: 100.0, origin: [10.0, 90.0], width: 100.0, height: 100.0 };
    /// assert_eq!(f.to_pixel(Point2::new(0.5, 0.5)), [60.0, 40.0]); // y up in the plane, down in px
    /// ```
    #[must_use]
    pub fn to_pixel(&self, p: Point2<f64>) -> [f64; 2] {
        [
            self.origin[0] + self.scale * p.x,
            self.origin[1] - self.scale * p.y,
        ]
    }

    /// The point of the plane at pixel `q` (the inverse of [`Frame::to_pixel`]).
    ///
    /// # Examples
    /// ```
    /// use tmm::draw::Frame;
    /// use tmm::nalgebra::Point2;
    /// let f = Frame { scale: 100.0, origin: [10.0, 90.0], width: 100.0, height: 100.0 };
    /// assert_eq!(f.to_world([60.0, 40.0]), Point2::new(0.5, 0.5));
    /// ```
    #[must_use]
    pub fn to_world(&self, q: [f64; 2]) -> Point2<f64> {
        Point2::new(
            (q[0] - self.origin[0]) / self.scale,
            (self.origin[1] - q[1]) / self.scale,
        )
    }
}

/// An [`Error::Drawing`].
pub(crate) fn drawing(what: &str, problem: impl Into<String>) -> Error {
    Error::Drawing {
        what: what.to_owned(),
        problem: problem.into(),
    }
}
