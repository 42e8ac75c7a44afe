//! The look of a picture.

use super::frame::drawing;
use super::MAX_FRAMES;
use crate::error::Result;

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
    /// The free border around the linkage, px (room for ground symbols and labels).
    pub margin: f64,
    /// The width of a bar (a binary link), px.
    pub line_width: f64,
    /// The radius of a hinge's circle, px.
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
    /// Checks every field.
    pub(crate) fn check(&self) -> Result<()> {
        let bad = |p: String| Err(drawing("with this style", p));
        for (name, v) in [("width", self.width), ("height", self.height)] {
            if !(16..=10_000).contains(&v) {
                return bad(format!("{name} must lie in [16, 10000] px, got {v}"));
            }
        }
        for (name, v) in [
            ("margin", self.margin),
            ("line_width", self.line_width),
            ("hinge_radius", self.hinge_radius),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(format!("{name} must be finite and ≥ 0 px, got {v}"));
            }
        }
        if 2.0 * self.margin >= f64::from(self.width.min(self.height)) {
            return bad(format!(
                "margin {} px leaves no room in {} × {} px",
                self.margin, self.width, self.height
            ));
        }
        if !(2..=MAX_FRAMES).contains(&self.samples) {
            return bad(format!(
                "samples must lie in [2, {MAX_FRAMES}], got {}",
                self.samples
            ));
        }
        Ok(())
    }

    pub(crate) fn w(&self) -> f64 {
        f64::from(self.width)
    }

    pub(crate) fn h(&self) -> f64 {
        f64::from(self.height)
    }
}
