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
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite corner; [`Error::Drawing`] for a picture with no
    /// room inside its margins, or a box of no extent (a single point).
    ///
    /// # Examples
    /// A box twice as wide as high in a square picture: the width decides the scale.
    /// ```
    /// use tmm::draw::Frame;
    /// use tmm::nalgebra::Point2;
    /// let f = Frame::fit(Point2::new(-1.0, 0.0), Point2::new(1.0, 1.0), 100.0, 100.0, 0.0)?;
    /// assert_eq!(f.scale, 50.0);
    /// assert!(Frame::fit(Point2::origin(), Point2::origin(), 100.0, 100.0, 0.0).is_err());
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
        let room = [width - 2.0 * margin, height - 2.0 * margin];
        if !(room[0] > 0.0 && room[1] > 0.0 && margin >= 0.0) {
            return Err(drawing(
                "a frame",
                format!(
                    "a picture of {width} × {height} px has no room inside margins of {margin} px"
                ),
            ));
        }
        let span = hi - lo;
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
        Ok(Self {
            scale,
            origin: [0.5 * width - scale * c.x, 0.5 * height + scale * c.y],
            width,
            height,
        })
    }

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
