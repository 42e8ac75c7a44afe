//! The look of a picture.

use super::MAX_FRAMES;
use crate::error::{finite, Error, Result};
use crate::Ends;

/// The size and look of a picture: a plain struct, [`Style::default`] for the usual one.
///
/// # Examples
/// A small picture without labels:
/// ```
/// use tmm::draw::Style;
/// let style = Style { width: 400, height: 300, labels: false, ..Style::default() };
/// assert_eq!(style.margin, 40.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// The picture's width, px (16 to 10 000).
    pub width: u32,
    /// The picture's height, px (16 to 10 000).
    pub height: u32,
    /// The free border around the linkage, px (room for ground symbols and labels): ≥ 0 and
    /// below half the picture's smaller side.
    pub margin: f64,
    /// The width of a bar (a binary link), px (> 0, at most [`Style::max_stroke`]).
    pub line_width: f64,
    /// The radius of a hinge's circle, px (> 0, at most [`Style::max_stroke`]).
    pub hinge_radius: f64,
    /// Whether to write the names of joints and points, the input's symbol and the numbers of
    /// positions.
    pub labels: bool,
    /// The number of positions over a cycle for the paths of points ([`plan_view`](super::plan_view))
    /// and the curves of [`diagram`](super::diagram) (2 to [`MAX_FRAMES`]).
    pub samples: usize,
}

impl Default for Style {
    /// 800 × 600 px, a 40 px margin, 3 px bars, 5 px hinges, labels, 360 samples.
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            margin: 40.0,
            line_width: 3.0,
            hinge_radius: 5.0,
            labels: true,
            samples: 360,
        }
    }
}

impl Style {
    /// Checks every field: the size in [16, 10 000] px; the margin finite, ≥ 0 and below half
    /// the smaller side; the line width and the hinge radius finite, > 0 and at most a tenth
    /// of the smaller side ([`Style::max_stroke`]); the samples in [2, [`MAX_FRAMES`]].
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming the field (`"style.hinge_radius"`).
    ///
    /// # Examples
    /// ```
    /// use tmm::draw::Style;
    /// assert!(Style::default().check().is_ok());
    /// let huge = Style { hinge_radius: 1e300, ..Style::default() };
    /// assert!(matches!(
    ///     huge.check(),
    ///     Err(tmm::Error::OutOfRange { name: "style.hinge_radius", .. })
    /// ));
    /// assert!(Style { line_width: f64::MAX, ..Style::default() }.check().is_err());
    /// ```
    pub fn check(&self) -> Result<()> {
        for (name, v) in [("style.width", self.width), ("style.height", self.height)] {
            if !(16..=10_000).contains(&v) {
                return Err(out_of_range(
                    name,
                    f64::from(v),
                    16.0,
                    10_000.0,
                    Ends::Closed,
                ));
            }
        }
        let side = self.w().min(self.h());
        finite("style.margin", self.margin)?;
        if !(self.margin >= 0.0 && 2.0 * self.margin < side) {
            return Err(out_of_range(
                "style.margin",
                self.margin,
                0.0,
                0.5 * side,
                Ends::OpenAbove,
            ));
        }
        let max = self.max_stroke();
        for (name, v) in [
            ("style.line_width", self.line_width),
            ("style.hinge_radius", self.hinge_radius),
        ] {
            finite(name, v)?;
            if !(v > 0.0 && v <= max) {
                return Err(out_of_range(name, v, 0.0, max, Ends::OpenBelow));
            }
        }
        if !(2..=MAX_FRAMES).contains(&self.samples) {
            #[allow(clippy::cast_precision_loss)]
            return Err(out_of_range(
                "style.samples",
                self.samples as f64,
                2.0,
                MAX_FRAMES as f64,
                Ends::Closed,
            ));
        }
        Ok(())
    }

    /// The largest line width and hinge radius of this picture, px: a tenth of its smaller
    /// side (60 px in 800 × 600).
    ///
    /// # Examples
    /// ```
    /// use tmm::draw::Style;
    /// assert_eq!(Style::default().max_stroke(), 60.0);
    /// ```
    #[must_use]
    pub fn max_stroke(&self) -> f64 {
        0.1 * self.w().min(self.h())
    }

    pub(crate) fn w(&self) -> f64 {
        f64::from(self.width)
    }

    pub(crate) fn h(&self) -> f64 {
        f64::from(self.height)
    }
}

/// An [`Error::OutOfRange`].
fn out_of_range(name: &'static str, value: f64, min: f64, max: f64, ends: Ends) -> Error {
    Error::OutOfRange {
        name,
        value,
        min,
        max,
        ends,
    }
}
