//! Results over a cycle as named columns, written as CSV.

use super::inputs::Inputs;
use super::plan::Plan;
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

/// Where a [`Tabulate`] writes one position: a cell per column, its name made only when the
/// table is laid out (once, at its first position) and its value every time.
pub trait Cells {
    /// One cell: its column's name with the unit in brackets (a closure, called only when
    /// the name is needed) and its value.
    fn cell(&mut self, name: impl FnOnce() -> String, value: f64);
}

/// A result that becomes one row of a [`Table`]: always the same columns in the same order
/// for one type (and one plan).
///
/// A table lays its columns out from the first position's names and then takes only the
/// values of every position, so a row costs no allocation and no formatting.
pub trait Tabulate {
    /// Writes this position's cells, in column order.
    fn cells(&self, out: &mut impl Cells);

    /// The row as (column name, value) pairs: every name is made, so this is for reading
    /// one row, not for a loop (a [`Table`] takes the values alone).
    ///
    /// # Errors
    /// [`Error::In`](crate::Error::In) naming the first column whose value is not finite (a
    /// reaction or a power that overflows under a huge load), holding
    /// [`Error::Overflow`](crate::Error::Overflow): a row never holds an infinity or a NaN.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, Plan, Tabulate};
    /// use tmm::kinematics::Motion;
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let row = plan.kinematics(Motion::new(plan.reference_input(), 1.0, 0.0))?.row()?;
    /// assert_eq!(row[0].0, "phi_in [rad]");
    /// assert!(row.iter().all(|(_, v)| v.is_finite()));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    fn row(&self) -> Result<Vec<(String, f64)>> {
        struct Pairs(Vec<(String, f64)>);
        impl Cells for Pairs {
            fn cell(&mut self, name: impl FnOnce() -> String, value: f64) {
                self.0.push((name(), value));
            }
        }
        let mut pairs = Pairs(Vec::new());
        self.cells(&mut pairs);
        if let Some((name, _)) = pairs.0.iter().find(|(_, v)| !v.is_finite()) {
            return Err(crate::Error::In {
                part: format!("column {name}"),
                source: Box::new(crate::Error::Overflow {
                    what: "the value of a table's cell",
                }),
            });
        }
        Ok(pairs.0)
    }
}

/// A column's name from its pieces: one allocation of the exact length (a name is made once
/// per table, but a table of a short course is mostly its fixed cost).
fn cat(parts: &[&str]) -> String {
    parts.concat()
}

/// A column's name from three runs of pieces, in one allocation of the exact length.
fn cat3(a: &[&str], b: &[&str], c: &[&str]) -> String {
    let len = [a, b, c]
        .iter()
        .flat_map(|p| p.iter())
        .map(|s| s.len())
        .sum();
    let mut s = String::with_capacity(len);
    for piece in [a, b, c].iter().flat_map(|p| p.iter()) {
        s.push_str(piece);
    }
    s
}

/// Writes a vector's x, y and magnitude as three cells `"{name}_x [unit]"`, `"{name}_y
/// [unit]"`, `"|{name}| [unit]"`, `name` given as its pieces (each name made in one
/// allocation, and only when the table is laid out).
pub(crate) fn cell_vector(out: &mut impl Cells, name: &[&str], unit: &str, v: Vector2<f64>) {
    out.cell(|| cat3(name, &["_x [", unit, "]"], &[]), v.x);
    out.cell(|| cat3(name, &["_y [", unit, "]"], &[]), v.y);
    out.cell(|| cat3(&["|"], name, &["| [", unit, "]"]), v.norm());
}

impl Tabulate for Kinematics<'_> {
    /// The course table's kinematic columns: the input, every moving link's angle, ω and ε,
    /// every joint's position, velocity and acceleration magnitudes, every prismatic joint's
    /// slide, and every group's transmission angle (no column for a group above the 3rd
    /// class, where it is not defined).
    fn cells(&self, out: &mut impl Cells) {
        kinematic_cells(out, self, false);
    }
}

/// The kinematic columns of [`Tabulate for Kinematics`](Tabulate), with every named point's
/// x, y, |v| and |a| after the joints' when `points` (the course table of
/// [`Plan::course_table`](super::Plan::course_table)).
fn kinematic_cells(out: &mut impl Cells, k: &Kinematics<'_>, points: bool) {
    let plan = k.plan();
    let links = plan.link_names();
    let pose = k.pose();
    let (q, unit, rate, accel) = if plan.input_is_crank() {
        ("phi_in", "rad", "rad/s", "rad/s^2")
    } else {
        ("s_in", "m", "m/s", "m/s^2")
    };
    let i = k.inputs().first();
    out.cell(|| cat(&[q, " [", unit, "]"]), i.value);
    out.cell(|| cat(&[q, "' [", rate, "]"]), i.rate);
    out.cell(|| cat(&[q, "'' [", accel, "]"]), i.accel);
    second_input_cells(out, k);
    for (l, name) in links.iter().enumerate().skip(1) {
        let m = pose.link_angle_at(l);
        out.cell(|| cat(&["phi(", name, ") [rad]"]), m.value);
        out.cell(|| cat(&["omega(", name, ") [rad/s]"]), m.rate);
        out.cell(|| cat(&["eps(", name, ") [rad/s^2]"]), m.accel);
    }
    for (j, name) in plan.joint_names().iter().enumerate() {
        point_cells(out, name, pose.joint_motion_at(j));
        if plan.is_prismatic_at(j) {
            let s = pose.slide_at(j);
            out.cell(|| cat(&["s(", name, ") [m]"]), s.value);
            out.cell(|| cat(&["v_rel(", name, ") [m/s]"]), s.rate);
            out.cell(|| cat(&["a_rel(", name, ") [m/s^2]"]), s.accel);
        }
    }
    if points {
        for (p, name) in plan.point_names().iter().enumerate() {
            point_cells(out, name, pose.point_motion_at(p));
        }
    }
    for (g, group) in plan.groups().iter().enumerate() {
        if group.kind == crate::linkage::GroupKind::General {
            // Not defined above the 3rd class: no column.
            continue;
        }
        // Defined for every group below the 4th class (`g` is in range): the fallback is
        // never taken, and a non-finite cell would leave the row out of a table.
        let mu = k.transmission_angle(g).unwrap_or(f64::NAN);
        out.cell(|| cat(&["mu(", &group.name, ") [rad]"]), mu);
    }
}

/// A point's x, y, |v| and |a|, named after it.
fn point_cells(out: &mut impl Cells, name: &str, p: crate::kinematics::PointMotion) {
    out.cell(|| cat(&["x(", name, ") [m]"]), p.p.x);
    out.cell(|| cat(&["y(", name, ") [m]"]), p.p.y);
    out.cell(|| cat(&["|v(", name, ")| [m/s]"]), p.v.norm());
    out.cell(|| cat(&["|a(", name, ")| [m/s^2]"]), p.a.norm());
}

impl Tabulate for Analysis<'_> {
    /// The course table's row: the kinematic columns of [`Kinematics`], the reaction in every
    /// joint (R_by,on: x, y, magnitude), and the balancing moment `Mb [N·m, + counter-clockwise]`
    /// (or force `Fb [N, + along the guide]`) beside its value by virtual power (by the
    /// velocity analogues, [`Analysis::power_check`]: defined at rest as well). A plan with
    /// friction adds, after the reactions, the power lost in every joint `P_lost(J) [W]`,
    /// their sum `P_lost [W]` and the drives' power `P_drive [W]` (the instantaneous
    /// efficiency is η = (P_drive − P_lost)/P_drive where P_drive > 0, and has no value where
    /// the drive gives no power, so it is not a column: [`Analysis::efficiency`]); a
    /// frictionless plan has none of these columns. With two inputs: each input's balancing
    /// value (`Mb`, `Mb2`, or `Fb`, `Fb2` for sliders), then the drives' power
    /// `drive power [W]` beside `drive power by virtual power [W]`.
    ///
    /// Every cell is a number defined at every position; one that overflows (a magnitude
    /// beyond `f64::MAX`, a power check whose sums overflow) is not finite, and a [`Table`]
    /// leaves that position's row out.
    fn cells(&self, out: &mut impl Cells) {
        analysis_cells(out, self, false);
    }
}

/// The columns of [`Tabulate for Analysis`](Tabulate), with the named points' after the
/// joints' when `points` (see [`kinematic_cells`]).
fn analysis_cells(out: &mut impl Cells, a: &Analysis<'_>, points: bool) {
    kinematic_cells(out, a.kinematics(), points);
    let plan = a.plan();
    let links = plan.link_names();
    for (j, name) in plan.joint_names().iter().enumerate() {
        let re = a.reactions[j];
        let (by, on) = (&links[re.by], &links[re.on]);
        cell_vector(out, &["R(", by, ",", on, ")@", name], "N", re.force);
        if plan.is_prismatic_at(j) {
            out.cell(
                || cat(&["M(", by, ",", on, ")@", name, " [N·m]"]),
                re.moment,
            );
        }
    }
    if plan.has_friction() {
        for (j, name) in plan.joint_names().iter().enumerate() {
            // A plan with friction holds every joint's (zero in a frictionless joint).
            let lost = a.friction.joints.get(j).map_or(0.0, |f| f.power_lost);
            out.cell(|| cat(&["P_lost(", name, ") [W]"]), lost);
        }
        out.cell(|| "P_lost [W]".to_owned(), a.lost_power());
        out.cell(|| "P_drive [W]".to_owned(), a.drive_power());
    }
    if plan.input_count() == 2 {
        two_input_balances(out, a);
        return;
    }
    let b = a.balances[0];
    // The sign convention rides in the header: a clockwise machine's driving moment is
    // negative, and its reader should not have to guess why.
    let (name, unit) = if plan.input_is_crank() {
        ("Mb", "N·m, + counter-clockwise")
    } else {
        ("Fb", "N, + along the guide")
    };
    out.cell(|| cat(&[name, " [", unit, "]"]), b.value);
    // Defined at rest too (the velocity analogues); it fails only where its sums overflow,
    // and the non-finite cell then leaves the row out of a table.
    let vp = a.power_check().map_or(f64::NAN, |c| c.virtual_power);
    out.cell(|| cat(&[name, " by virtual power [", unit, "]"]), vp);
}

/// One analysis as a row of the course table with the named points' columns
/// ([`Plan::course_table`](super::Plan::course_table)).
struct CourseRow<'a, 'p>(&'a Analysis<'p>);

impl Tabulate for CourseRow<'_, '_> {
    fn cells(&self, out: &mut impl Cells) {
        analysis_cells(out, self.0, true);
    }
}

/// The course table of `analyses`: as [`Table::of`], with every named point's x, y, |v| and
/// |a| after the joints' columns.
pub(crate) fn course_table(analyses: &[Result<Analysis<'_>>]) -> Table {
    let mut rows = Rows::new(analyses.iter().filter(|p| p.is_ok()).count());
    for a in analyses.iter().flatten() {
        rows.push(&CourseRow(a));
    }
    rows.finish()
}

/// The header sink: every column's name, no values.
struct Names<'a>(&'a mut Vec<Column>);

impl Cells for Names<'_> {
    fn cell(&mut self, name: impl FnOnce() -> String, _: f64) {
        self.0.push(Column {
            name: name(),
            values: Vec::new(),
        });
    }
}

/// The value sink: one value into each column in turn; cells past the last column are
/// dropped (a position of another type or plan cannot make the table ragged), and whether
/// every value taken was finite is noted.
struct Values<'a> {
    columns: &'a mut [Column],
    next: usize,
    finite: bool,
}

impl Cells for Values<'_> {
    #[inline]
    fn cell(&mut self, _: impl FnOnce() -> String, value: f64) {
        if let Some(c) = self.columns.get_mut(self.next) {
            c.values.push(value);
            self.finite &= value.is_finite();
        }
        self.next += 1;
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

/// The second input's cells, after the first's, for a linkage with two inputs.
fn second_input_cells(out: &mut impl Cells, k: &Kinematics<'_>) {
    if let Some(m) = k.inputs().get(1) {
        let [q, unit, rate, accel, ..] = input_units(k.plan(), 1);
        out.cell(|| cat(&[q, " [", unit, "]"]), m.value);
        out.cell(|| cat(&[q, "' [", rate, "]"]), m.rate);
        out.cell(|| cat(&[q, "'' [", accel, "]"]), m.accel);
    }
}

/// Two inputs: each input's balancing value, then the drives' power Σ B_k·q̇_k beside the
/// power found by the principle of virtual power (−Σ P_i of every applied load), both in W —
/// with two inputs the virtual-power check is of powers, not of one balancing value.
fn two_input_balances(out: &mut impl Cells, a: &Analysis<'_>) {
    for (i, b) in a.balances().iter().enumerate() {
        let [.., name, unit] = input_units(a.plan(), i);
        out.cell(|| cat(&[name, " [", unit, "]"]), b.value);
    }
    // The check fails only where its sums overflow: the non-finite cell then leaves the row
    // out of a table.
    let vp = a.power_check().map_or(f64::NAN, |c| c.virtual_power);
    out.cell(|| "drive power [W]".to_owned(), a.drive_power());
    out.cell(|| "drive power by virtual power [W]".to_owned(), vp);
}

/// Whether the row written at `start..` of `block` is held: it gives at least `width` cells
/// (the extra ones are cut) and every one is finite. A row not held is taken off `block`.
#[inline]
fn held(block: &mut Vec<f64>, start: usize, width: usize) -> bool {
    // A fold with no early exit: one vectorised pass (a row is almost always held).
    let ok = block.len() >= start + width
        && block[start..start + width]
            .iter()
            .fold(true, |ok, v| ok & v.is_finite());
    block.truncate(if ok { start + width } else { start });
    ok
}

/// The value sink of a block of rows: every cell one push onto one buffer.
struct Flat<'a>(&'a mut Vec<f64>);

impl Cells for Flat<'_> {
    #[inline]
    fn cell(&mut self, _: impl FnOnce() -> String, value: f64) {
        self.0.push(value);
    }
}

/// A table filled many rows at a time: the rows gather in a block, row after row in one
/// buffer, and each column takes the block's values in one pass, so a cell is one push onto
/// one buffer (each row of a four-bar's analysis has 43), and each column is written in one
/// stream (pushing each cell straight into its column writes 43 streams at once, and took
/// 1.1–1.5× the CPU time at 3600 and 36 000 rows; docs/performance.md).
struct Rows {
    table: Table,
    block: Vec<f64>,
    reserve: usize,
}

impl Rows {
    /// Rows per block.
    const BLOCK: usize = 64;

    /// An empty table whose columns will have room for `reserve` rows.
    fn new(reserve: usize) -> Self {
        Self {
            table: Table::default(),
            block: Vec::new(),
            reserve,
        }
    }

    /// Appends one position's row, as [`Table::push`] does: held only when it gives a finite
    /// value for every column.
    fn push<P: Tabulate + ?Sized>(&mut self, position: &P) {
        if self.table.columns.is_empty() {
            self.table.lay_out(position, self.reserve);
            // Room for a whole block: one allocation per table, never grown.
            self.block
                .reserve_exact(Self::BLOCK * self.table.columns.len());
        }
        let width = self.table.columns.len();
        let start = self.block.len();
        position.cells(&mut Flat(&mut self.block));
        // Rectangular and finite: a long row is cut; a short one, or one with a value that
        // is not finite, is left out ([`Table::push`]).
        if !held(&mut self.block, start, width) {
            return;
        }
        if self.block.len() >= Self::BLOCK * width {
            self.flush();
        }
    }

    fn flush(&mut self) {
        let width = self.table.columns.len();
        if width == 0 {
            return;
        }
        for (k, c) in self.table.columns.iter_mut().enumerate() {
            // A strided copy of known length: the column grows once (if at all: it was
            // reserved for the whole table when its length was known), and each value is
            // written once, with no capacity test and no zero fill before it.
            c.values
                .extend(self.block.chunks_exact(width).map(|row| row[k]));
        }
        self.block.clear();
    }

    fn finish(mut self) -> Table {
        self.flush();
        if self.table.is_empty() {
            // No row held: no columns either, as for a table of no positions.
            return Table::default();
        }
        self.table
    }
}

impl Table {
    /// The table of the positions that were analysed; failed positions (their `Err`) are left
    /// out, and so are rows not held by the rule of [`push`](Self::push) (a value that is not
    /// finite, or too few cells), so every number the table holds is finite and its
    /// input-angle column tells which positions it holds. For a plan's cycle,
    /// [`Plan::table`](super::Plan::table) solves and tabulates in one pass, with no analysis
    /// kept per position.
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{Cells, Table, Tabulate};
    /// struct P(f64);
    /// impl Tabulate for P {
    ///     fn cells(&self, out: &mut impl Cells) { out.cell(|| "phi1 [rad]".into(), self.0) }
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
        let mut rows = Rows::new(positions.iter().filter(|p| p.is_ok()).count());
        for p in positions.iter().flatten() {
            rows.push(p);
        }
        rows.finish()
    }

    /// Appends one position as a row, and says whether it was held. The first position
    /// pushed onto a table without columns lays them out (its names); every later one gives
    /// its values alone, into the same columns in the same order: no allocation per row
    /// beyond the columns' growth.
    ///
    /// A table holds only finite numbers: a row is held when it gives a finite value for
    /// every column laid out (cells past the last column are cut). A table with no row held
    /// has no columns. A row that gives fewer
    /// cells than the table has columns (a position of another type or plan), or a value
    /// that is not finite (an overflow, or a `NaN` a user's [`Tabulate`] wrote for "no
    /// value"), is left out whole and `false` returned: the table stays rectangular, and its
    /// input column tells which positions it holds. A quantity that has no value at some
    /// positions belongs in a column of what it is made from (the table of an [`Analysis`]
    /// has `P_drive [W]` and `P_lost [W]`, not the efficiency, which has no value where the
    /// drive gives no power).
    ///
    /// # Examples
    /// A table of the four-bar's turn, solved and tabulated position by position:
    /// ```
    /// use tmm::kinematics::Motion;
    /// use tmm::linkage::{bundled, Plan, Table};
    /// let plan = Plan::new(&bundled::four_bar())?;
    /// let mut solver = plan.solver();
    /// let mut table = Table::default();
    /// for k in 0..36 {
    ///     assert!(table.push(solver.analyse(Motion::turning(f64::from(k) * 0.1745, 10.0))?));
    /// }
    /// assert_eq!(table.len(), 36);
    /// // The chain's balancing moment equals its value by virtual power at every position.
    /// let (mb, vp) = (table.column("Mb [N·m, + counter-clockwise]").unwrap(),
    ///                 table.column("Mb by virtual power [N·m, + counter-clockwise]").unwrap());
    /// assert!(mb.iter().zip(vp).all(|(a, b)| (a - b).abs() <= 1e-9 * a.abs().max(1.0)));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    ///
    /// A row with no value in a column is not held:
    /// ```
    /// use tmm::linkage::{Cells, Table, Tabulate};
    /// struct Ratio(f64, f64);
    /// impl Tabulate for Ratio {
    ///     fn cells(&self, out: &mut impl Cells) {
    ///         out.cell(|| "a [-]".into(), self.0);
    ///         out.cell(|| "a/b [-]".into(), self.0 / self.1);
    ///     }
    /// }
    /// let mut t = Table::default();
    /// assert!(t.push(&Ratio(1.0, 2.0)));
    /// assert!(!t.push(&Ratio(0.0, 0.0))); // 0/0
    /// assert_eq!(t.column("a/b [-]"), Some(&[0.5][..]));
    /// ```
    pub fn push<P: Tabulate + ?Sized>(&mut self, position: &P) -> bool {
        let fresh = self.columns.is_empty();
        self.lay_out(position, 0);
        let held = self.push_values(position);
        if fresh && !held {
            // A row not held leaves the table as it was: no columns of no rows.
            self.columns.clear();
        }
        held
    }

    /// Appends `position`'s values to the columns laid out if it gives a finite value for
    /// every one ([`push`](Self::push)); otherwise takes back what it wrote.
    fn push_values<P: Tabulate + ?Sized>(&mut self, position: &P) -> bool {
        let mut values = Values {
            columns: &mut self.columns,
            next: 0,
            finite: true,
        };
        position.cells(&mut values);
        let (given, finite) = (values.next, values.finite);
        if given >= self.columns.len() && finite {
            return true;
        }
        // Each column before `given` took exactly one value.
        for c in self.columns.iter_mut().take(given) {
            c.values.pop();
        }
        false
    }

    /// Lays the columns out from `position`'s names (with room for `rows` values each) if
    /// the table has none yet.
    fn lay_out<P: Tabulate + ?Sized>(&mut self, position: &P, rows: usize) {
        if self.columns.is_empty() {
            position.cells(&mut Names(&mut self.columns));
            for c in &mut self.columns {
                c.values.reserve(rows);
            }
        }
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
    /// use tmm::linkage::{Cells, Table, Tabulate};
    /// struct P(f64);
    /// impl Tabulate for P {
    ///     fn cells(&self, out: &mut impl Cells) { out.cell(|| "x [m]".into(), self.0) }
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

impl Plan {
    /// The course table of `inputs` (a slice or any iterator of inputs): every position
    /// analysed by one [`Solver`](super::Solver) and written straight into the table's
    /// columns (the columns of [`Tabulate for Analysis`](Tabulate)), with nothing kept or
    /// allocated per position. Positions that fail are left out, as in [`Table::of`]; a
    /// [`cycle`](Self::cycle) gives their errors. Every cell of an analysis is defined at every
    /// position (at rest as well as moving, with no loads at all); a row is left out only
    /// where a value overflows (see [`Table::push`]).
    ///
    /// # Examples
    /// ```
    /// use tmm::linkage::{bundled, uniform_inputs, Plan, Table};
    /// let plan = Plan::new(&bundled::watt_six_bar())?;
    /// let inputs = uniform_inputs(36, plan.reference_input(), 10.0, 0.0);
    /// let table = plan.table(&inputs);
    /// assert_eq!(table.len(), 36);
    /// // The same table as from the analyses kept one by one.
    /// let kept: Vec<_> = inputs.iter().map(|&i| plan.analyse(i)).collect();
    /// assert_eq!(table, Table::of(&kept));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    #[must_use]
    pub fn table<I>(&self, inputs: I) -> Table
    where
        I: IntoIterator,
        I::Item: Into<Inputs>,
    {
        let inputs = inputs.into_iter();
        let mut rows = Rows::new(inputs.size_hint().0);
        let mut solver = self.solver();
        for i in inputs {
            if let Ok(a) = solver.analyse(i) {
                rows.push(a);
            }
        }
        rows.finish()
    }
}
