//! Results over a cycle as named columns, written as CSV.

use super::drive::Balance;
use crate::error::Result;
use nalgebra::Vector2;
use std::io;

/// One named column of numbers; the name carries the unit, for example `"R12_x [N]"`.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Column {
    /// The column's name with its unit in brackets.
    pub name: String,
    /// The values, one per tabulated position.
    pub values: Vec<f64>,
}

/// A table of results over a cycle: named columns of equal length, one row per position.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Table {
    /// The columns, in the order they are written.
    pub columns: Vec<Column>,
}

/// A result that becomes one row of a [`Table`]: (column name, value) pairs, always the same
/// names in the same order for one type.
pub trait Tabulate {
    /// The row of this position.
    fn row(&self) -> Vec<(String, f64)>;
}

/// Appends a vector's x, y and magnitude as three columns `"{name}_x [unit]"`, … .
pub(crate) fn push_vector(row: &mut Vec<(String, f64)>, name: &str, unit: &str, v: Vector2<f64>) {
    row.push((format!("{name}_x [{unit}]"), v.x));
    row.push((format!("{name}_y [{unit}]"), v.y));
    row.push((format!("|{name}| [{unit}]"), v.norm()));
}

/// Appends one scalar column `"{name} [unit]"`.
pub(crate) fn push(row: &mut Vec<(String, f64)>, name: &str, unit: &str, value: f64) {
    row.push((format!("{name} [{unit}]"), value));
}

/// Appends the joint reactions `reactions` (x, y and magnitude each, N), then the balance's
/// R01 and F_b (N) and M_b (N·m): the last columns of every ready mechanism's row.
pub(crate) fn push_reactions(
    row: &mut Vec<(String, f64)>,
    reactions: &[(&str, Vector2<f64>)],
    balance: &Balance,
) {
    for &(name, v) in reactions {
        push_vector(row, name, "N", v);
    }
    push_vector(row, "R01", "N", balance.r01);
    push_vector(row, "Fb", "N", balance.force);
    push(row, "Mb", "N*m", balance.moment);
}

impl Table {
    /// The table of the positions that were analysed; failed positions (their `Err`) are left
    /// out, so a table's input-angle column tells which positions it holds.
    ///
    /// # Examples
    /// ```
    /// use tmm::mechanism::{Table, Tabulate};
    /// struct P(f64);
    /// impl Tabulate for P {
    ///     fn row(&self) -> Vec<(String, f64)> { vec![("phi1 [rad]".into(), self.0)] }
    /// }
    /// let rows = [Ok(P(0.0)), Err(tmm::Error::NonFinite { name: "x", value: f64::NAN }), Ok(P(1.0))];
    /// let t = Table::of(&rows);
    /// assert_eq!(t.column("phi1 [rad]"), Some(&[0.0, 1.0][..]));
    /// let mut csv = Vec::new();
    /// t.write_csv(&mut csv)?;
    /// assert_eq!(String::from_utf8(csv).unwrap(), "phi1 [rad]\n0\n1\n");
    /// # Ok::<(), std::io::Error>(())
    /// ```
    #[must_use]
    pub fn of<P: Tabulate>(positions: &[Result<P>]) -> Self {
        let mut table = Self::default();
        for p in positions.iter().flatten() {
            let row = p.row();
            if table.columns.is_empty() {
                table.columns = row
                    .iter()
                    .map(|(name, _)| Column {
                        name: name.clone(),
                        values: Vec::with_capacity(positions.len()),
                    })
                    .collect();
            }
            for (col, (_, value)) in table.columns.iter_mut().zip(row) {
                col.values.push(value);
            }
        }
        table
    }

    /// The number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.columns.first().map_or(0, |c| c.values.len())
    }

    /// Whether the table has no rows.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The values of the column named `name`.
    #[must_use]
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.columns
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.values.as_slice())
    }

    /// Writes the table as CSV: a header of the column names, then one line per row, numbers
    /// in Rust's shortest round-trip form (reading them back gives the same f64). Names with a
    /// comma or a quote are quoted.
    ///
    /// # Errors
    /// The writer's I/O error; [`io::ErrorKind::InvalidInput`] when the columns are not all of
    /// the same length (a table built by hand), before anything is written.
    pub fn write_csv<W: io::Write>(&self, mut w: W) -> io::Result<()> {
        if let Some(c) = self.columns.iter().find(|c| c.values.len() != self.len()) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "column {:?} has {} values, the first column {}",
                    c.name,
                    c.values.len(),
                    self.len()
                ),
            ));
        }
        let quote = |s: &str| {
            if s.contains([',', '"', '\n']) {
                format!("\"{}\"", s.replace('"', "\"\""))
            } else {
                s.to_owned()
            }
        };
        let header: Vec<String> = self.columns.iter().map(|c| quote(&c.name)).collect();
        writeln!(w, "{}", header.join(","))?;
        for k in 0..self.len() {
            let line: Vec<String> = self
                .columns
                .iter()
                .map(|c| c.values[k].to_string())
                .collect();
            writeln!(w, "{}", line.join(","))?;
        }
        Ok(())
    }
}
