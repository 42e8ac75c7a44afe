//! Results over a cycle as named columns, written as CSV.

use super::solve::{Analysis, Kinematics};
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

/// Appends a vector's x, y and magnitude as three columns `"{name}_x [unit]"`, `"{name}_y
/// [unit]"`, `"|{name}| [unit]"`.
pub(crate) fn push_vector(row: &mut Vec<(String, f64)>, name: &str, unit: &str, v: Vector2<f64>) {
    row.push((format!("{name}_x [{unit}]"), v.x));
    row.push((format!("{name}_y [{unit}]"), v.y));
    row.push((format!("|{name}| [{unit}]"), v.norm()));
}

/// Appends one scalar column `"{name} [unit]"`.
pub(crate) fn push(row: &mut Vec<(String, f64)>, name: &str, unit: &str, value: f64) {
    row.push((format!("{name} [{unit}]"), value));
}

impl Tabulate for Kinematics<'_> {
    /// The course table's kinematic columns: the input, every moving link's angle, ω and ε,
    /// every joint's position, velocity and acceleration magnitudes, every prismatic joint's
    /// slide, and every group's transmission angle.
    fn row(&self) -> Vec<(String, f64)> {
        let plan = self.plan();
        let links = plan.link_names();
        let pose = self.pose();
        let mut r = Vec::with_capacity(8 * plan.joint_names().len() + 4 * links.len());
        let (q, unit, rate, accel) = if plan.input_is_crank() {
            ("phi_in", "rad", "rad/s", "rad/s^2")
        } else {
            ("s_in", "m", "m/s", "m/s^2")
        };
        let i = self.inputs().first();
        push(&mut r, q, unit, i.value);
        push(&mut r, &format!("{q}'"), rate, i.rate);
        push(&mut r, &format!("{q}''"), accel, i.accel);
        second_input_columns(&mut r, self);
        for (k, name) in links.iter().enumerate().skip(1) {
            let m = pose.link_angle_at(k);
            push(&mut r, &format!("phi({name})"), "rad", m.value);
            push(&mut r, &format!("omega({name})"), "rad/s", m.rate);
            push(&mut r, &format!("eps({name})"), "rad/s^2", m.accel);
        }
        for (j, name) in plan.joint_names().iter().enumerate() {
            let p = pose.joint_motion_at(j);
            push(&mut r, &format!("x({name})"), "m", p.p.x);
            push(&mut r, &format!("y({name})"), "m", p.p.y);
            push(&mut r, &format!("|v({name})|"), "m/s", p.v.norm());
            push(&mut r, &format!("|a({name})|"), "m/s^2", p.a.norm());
            if plan.is_prismatic_at(j) {
                let s = pose.slide_at(j);
                push(&mut r, &format!("s({name})"), "m", s.value);
                push(&mut r, &format!("v_rel({name})"), "m/s", s.rate);
                push(&mut r, &format!("a_rel({name})"), "m/s^2", s.accel);
            }
        }
        for (g, group) in plan.groups().iter().enumerate() {
            let mu = self.transmission_angle(g).unwrap_or(f64::NAN);
            push(&mut r, &format!("mu({})", group.name), "rad", mu);
        }
        r
    }
}

impl Tabulate for Analysis<'_> {
    /// The course table's row: the kinematic columns of [`Kinematics`], the reaction in every
    /// joint (R_by,on: x, y, magnitude), and the balancing moment `Mb [N·m, + counter-clockwise]`
    /// (or force `Fb [N, + along the guide]`) beside its value by virtual power (`NaN` when the
    /// input is at rest: the virtual power then has no rate). With two inputs: each input's
    /// balancing value (`Mb`, `Mb2`, or `Fb`, `Fb2` for sliders), then the drives' power
    /// `drive power [W]` beside `drive power by virtual power [W]`.
    fn row(&self) -> Vec<(String, f64)> {
        let mut r = self.kinematics().row();
        let plan = self.plan();
        let links = plan.link_names();
        for (j, name) in plan.joint_names().iter().enumerate() {
            let re = self.reactions[j];
            let label = format!("R({},{})@{name}", links[re.by], links[re.on]);
            push_vector(&mut r, &label, "N", re.force);
            if plan.is_prismatic_at(j) {
                push(
                    &mut r,
                    &format!("M({},{})@{name}", links[re.by], links[re.on]),
                    "N·m",
                    re.moment,
                );
            }
        }
        if plan.input_count() == 2 {
            two_input_balances(&mut r, self);
            return r;
        }
        let b = self.balances[0];
        // The sign convention rides in the header: a clockwise machine's driving moment is
        // negative, and its reader should not have to guess why.
        let (name, unit) = if plan.input_is_crank() {
            ("Mb", "N·m, + counter-clockwise")
        } else {
            ("Fb", "N, + along the guide")
        };
        push(&mut r, name, unit, b.value);
        // At rest the virtual power has no rate to divide by: the cell is NaN ("not
        // available"), as `Table` documents.
        let vp = self.power_check().map_or(f64::NAN, |c| c.virtual_power);
        push(&mut r, &format!("{name} by virtual power"), unit, vp);
        r
    }
}

// Two inputs (a separate section: the one-input columns above are unchanged).

/// The unit names of input `i`'s coordinate: (name, unit, rate unit, acceleration unit,
/// balance name, balance unit).
fn input_units(plan: &super::plan::Plan, i: usize) -> [&'static str; 6] {
    let crank = plan
        .chain
        .inputs()
        .nth(i)
        .is_none_or(|ip| matches!(ip, super::plan::InputPlan::Crank { .. }));
    match (crank, i) {
        (true, 0) => [
            "phi_in",
            "rad",
            "rad/s",
            "rad/s^2",
            "Mb",
            "N·m, + counter-clockwise",
        ],
        (true, _) => [
            "phi_in2",
            "rad",
            "rad/s",
            "rad/s^2",
            "Mb2",
            "N·m, + counter-clockwise",
        ],
        (false, 0) => ["s_in", "m", "m/s", "m/s^2", "Fb", "N, + along the guide"],
        (false, _) => ["s_in2", "m", "m/s", "m/s^2", "Fb2", "N, + along the guide"],
    }
}

/// The second input's columns, after the first's, for a linkage with two inputs.
fn second_input_columns(r: &mut Vec<(String, f64)>, k: &Kinematics<'_>) {
    if let Some(m) = k.inputs().get(1) {
        let [q, unit, rate, accel, ..] = input_units(k.plan(), 1);
        push(r, q, unit, m.value);
        push(r, &format!("{q}'"), rate, m.rate);
        push(r, &format!("{q}''"), accel, m.accel);
    }
}

/// Two inputs: each input's balancing value, then the drives' power Σ B_k·q̇_k beside the
/// power found by the principle of virtual power (−Σ P_i of every applied load), both in W —
/// with two inputs the virtual-power check is of powers, not of one balancing value.
fn two_input_balances(r: &mut Vec<(String, f64)>, a: &Analysis<'_>) {
    for (i, b) in a.balances().iter().enumerate() {
        let [.., name, unit] = input_units(a.plan(), i);
        push(r, name, unit, b.value);
    }
    let (chain, vp) = a
        .power_check()
        .map_or((f64::NAN, f64::NAN), |c| (c.chain, c.virtual_power));
    push(r, "drive power", "W", chain);
    push(r, "drive power by virtual power", "W", vp);
}

impl Table {
    /// The table of the positions that were analysed; failed positions (their `Err`) are left
    /// out, so a table's input-angle column tells which positions it holds.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{Table, Tabulate};
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

    /// The table as text for a terminal, transposed: one line per column (its name, padded to
    /// the longest, then its values across the positions) with `decimals` digits after the
    /// point (at most 12). A value that
    /// rounds to zero prints as zero, never as "-0.0000"; a non-finite one as `NaN` or `inf`.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{Table, Tabulate};
    /// struct P(f64);
    /// impl Tabulate for P {
    ///     fn row(&self) -> Vec<(String, f64)> { vec![("x [m]".into(), self.0)] }
    /// }
    /// let t = Table::of(&[Ok(P(-1e-9)), Ok(P(0.25))]);
    /// assert_eq!(t.to_text(3), format!("x [m] {:>11} {:>11}\n", "0.000", "0.250"));
    /// ```
    #[must_use]
    pub fn to_text(&self, decimals: usize) -> String {
        let decimals = decimals.min(12);
        let width = self
            .columns
            .iter()
            .map(|c| c.name.chars().count())
            .max()
            .unwrap_or(0);
        let mut out = String::new();
        for c in &self.columns {
            out.push_str(&format!("{:<width$}", c.name));
            for &v in &c.values {
                let text = format!("{v:.decimals$}");
                // "-0.000": the sign of something that rounds to zero says nothing.
                let text = if text.starts_with('-')
                    && text[1..].chars().all(|ch| ch == '0' || ch == '.')
                {
                    text[1..].to_owned()
                } else {
                    text
                };
                out.push_str(&format!(" {text:>11}"));
            }
            out.push('\n');
        }
        out
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
