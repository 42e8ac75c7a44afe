//! A tabulated function y(x) with linear interpolation, such as the landing gear's resisting
//! moment M_on(φ_H), which the seed gives only as a graph.

use crate::error::{finite, Error, Result};

/// What a [`Table`] does for an argument outside [x_first, x_last].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Beyond {
    /// Return [`Error::OutOfRange`] (the default: a table says nothing outside its range).
    #[default]
    Error,
    /// Hold the end values (y(x) = y_first below the range, y_last above it). Use it when
    /// the physics does: for example a landing gear resting on its stop.
    HoldEnds,
}

/// A function given by points (xᵢ, yᵢ) with strictly increasing xᵢ, interpolated linearly.
///
/// # Examples
/// ```
/// use tmm::dynamics::{Beyond, Table};
/// let t = Table::new(vec![0.0, 1.0, 3.0], vec![10.0, 20.0, 0.0], Beyond::Error).unwrap();
/// assert_eq!(t.at(0.5).unwrap(), 15.0);
/// assert_eq!(t.at(2.0).unwrap(), 10.0);
/// assert!(t.at(3.5).is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    x: Vec<f64>,
    y: Vec<f64>,
    beyond: Beyond,
}

impl Table {
    /// A table from its abscissae and values.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite entry; [`Error::OutOfRange`] when there are fewer
    /// than two points, the lengths differ, or the abscissae do not strictly increase.
    pub fn new(x: Vec<f64>, y: Vec<f64>, beyond: Beyond) -> Result<Self> {
        for &v in x.iter() {
            finite("table x", v)?;
        }
        for &v in y.iter() {
            finite("table y", v)?;
        }
        if x.len() < 2 || x.len() != y.len() {
            return Err(Error::OutOfRange {
                name: "number of table points (x and y of equal length)",
                value: x.len().min(y.len()) as f64,
                min: 2.0,
                max: f64::INFINITY,
                ends: crate::Ends::Closed,
            });
        }
        if let Some(w) = x.windows(2).find(|w| w[1] <= w[0]) {
            return Err(Error::OutOfRange {
                name: "table x (must strictly increase)",
                value: w[1],
                min: w[0],
                max: f64::INFINITY,
                ends: crate::Ends::OpenBelow,
            });
        }
        Ok(Self { x, y, beyond })
    }

    /// The abscissae.
    #[must_use]
    pub fn xs(&self) -> &[f64] {
        &self.x
    }

    /// The values.
    #[must_use]
    pub fn ys(&self) -> &[f64] {
        &self.y
    }

    /// The rule outside the range.
    #[must_use]
    pub fn beyond(&self) -> Beyond {
        self.beyond
    }

    /// The value at `x`, interpolated linearly between the neighbouring points.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `x`; [`Error::OutOfRange`] outside the table when
    /// the rule is [`Beyond::Error`].
    pub fn at(&self, x: f64) -> Result<f64> {
        finite("table argument", x)?;
        let (first, last) = (self.x[0], self.x[self.x.len() - 1]);
        if x < first || x > last {
            return match self.beyond {
                Beyond::Error => Err(Error::OutOfRange {
                    name: "table argument",
                    value: x,
                    min: first,
                    max: last,
                    ends: crate::Ends::Closed,
                }),
                Beyond::HoldEnds if x < first => Ok(self.y[0]),
                Beyond::HoldEnds => Ok(self.y[self.y.len() - 1]),
            };
        }
        // Index of the interval [x_i, x_{i+1}] that holds x (binary search).
        let i = self
            .x
            .partition_point(|&xi| xi <= x)
            .clamp(1, self.x.len() - 1)
            - 1;
        let (x0, x1, y0, y1) = (self.x[i], self.x[i + 1], self.y[i], self.y[i + 1]);
        // (x − x0)/(x1 − x0), without overflowing the differences of abscissae near ±f64::MAX.
        let s = if (x1 - x0).is_finite() {
            (x - x0) / (x1 - x0)
        } else {
            (x / 2.0 - x0 / 2.0) / (x1 / 2.0 - x0 / 2.0)
        };
        let y = y0 + s * (y1 - y0);
        // Values of opposite signs near ±f64::MAX: the weighted form cannot overflow.
        let y = if y.is_finite() {
            y
        } else {
            (1.0 - s) * y0 + s * y1
        };
        crate::error::computed("table value", y)
    }
}
