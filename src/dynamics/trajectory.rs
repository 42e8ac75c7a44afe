//! A recorded motion as columns, exportable as CSV.

use std::fmt::Write as _;

use nalgebra::Vector2;

use super::system::{row_terms, LagrangeSystem, RowTerms, State};
use crate::error::{Error, Result};

/// A motion recorded as columns: time, q, q̇, q̈, the energies and powers, and the
/// machine's own outputs (for the gear drives the speed of every link).
///
/// The columns are private and grow only through [`push`](Self::push), which appends a whole
/// row of finite numbers or nothing: every column has [`len`](Self::len) entries, and no
/// recorded number is NaN or infinite. Read them through the accessors. Which rows a
/// [`run`](super::run) records (the start, step ends, requested times, the end) is said at
/// [`RunOptions`](super::RunOptions#what-is-recorded).
///
/// All columns live in one block (column after column, each with room for the same number of
/// rows), so that a run recording its start and end only allocates once, not once per column.
///
/// # Breaking change
/// [`q`](Self::q), [`qd`](Self::qd) and [`qdd`](Self::qdd) return `[&[f64]; 2]` (were
/// `&[Vec<f64>; 2]`) and [`outputs`](Self::outputs) returns `Vec<&[f64]>` (was
/// `&[Vec<f64>]`): indexing, `iter()` and `len()` read as before.
#[derive(Clone, Default)]
pub struct Trajectory {
    coordinate_names: [&'static str; 2],
    output_names: Vec<&'static str>,
    /// Rows recorded.
    len: usize,
    /// Rows each column has room for.
    cap: usize,
    /// The columns in the order of [`Column`], then the outputs; column c holds
    /// `data[c·cap .. c·cap + len]`.
    data: Vec<f64>,
}

/// The fixed columns, in their order in the block (and in the CSV).
#[derive(Clone, Copy)]
enum Column {
    T,
    Q1,
    Q2,
    Qd1,
    Qd2,
    Qdd1,
    Qdd2,
    Kinetic,
    Potential,
    PowerApplied,
    PowerDissipated,
}

/// The number of fixed columns (before the outputs).
const FIXED: usize = 11;

/// The rows a trajectory makes room for at its first row: a run that records its start and
/// end only then allocates once.
const FIRST_ROWS: usize = 4;

impl std::fmt::Debug for Trajectory {
    /// The names and every recorded column under its CSV header (not the block's room for
    /// rows not yet recorded, nor rows truncated away).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let header = self.header();
        let columns: Vec<(&str, &[f64])> = header
            .iter()
            .map(String::as_str)
            .zip((0..self.columns()).map(|c| self.column(c)))
            .collect();
        f.debug_struct("Trajectory")
            .field("len", &self.len)
            .field("columns", &columns)
            .finish()
    }
}

impl PartialEq for Trajectory {
    /// Equal names and equal recorded columns (whatever room each has left).
    fn eq(&self, other: &Self) -> bool {
        self.coordinate_names == other.coordinate_names
            && self.output_names == other.output_names
            && self.len == other.len
            && (0..self.columns()).all(|c| self.column(c) == other.column(c))
    }
}

impl Trajectory {
    /// An empty trajectory with the column names of `sys`.
    #[must_use]
    pub fn for_system<S: LagrangeSystem + ?Sized>(sys: &S) -> Self {
        Self {
            coordinate_names: sys.coordinate_names(),
            output_names: sys.output_names(),
            ..Self::default()
        }
    }

    /// The number of columns: the fixed ones and the outputs.
    fn columns(&self) -> usize {
        FIXED + self.output_names.len()
    }

    /// Column `c` (a [`Column`] or `FIXED + k` for output k) as recorded.
    fn column(&self, c: usize) -> &[f64] {
        let from = c * self.cap;
        &self.data[from..from + self.len]
    }

    fn fixed(&self, c: Column) -> &[f64] {
        self.column(c as usize)
    }

    /// Room for one more row in every column: the block doubles, each column moved to its
    /// new place (amortised O(1) a row, as a `Vec`'s push).
    fn reserve_row(&mut self) {
        if self.len < self.cap {
            return;
        }
        let cap = (2 * self.cap).max(FIRST_ROWS);
        let mut data = vec![0.0; cap * self.columns()];
        for c in 0..self.columns() {
            data[c * cap..c * cap + self.len].copy_from_slice(self.column(c));
        }
        self.data = data;
        self.cap = cap;
    }

    /// A [`Default`] trajectory, made for no system yet.
    fn is_blank(&self) -> bool {
        self.cap == 0 && self.coordinate_names == [""; 2] && self.output_names.is_empty()
    }

    /// Names of the two generalized coordinates.
    #[must_use]
    pub fn coordinate_names(&self) -> [&'static str; 2] {
        self.coordinate_names
    }

    /// Time, s.
    #[must_use]
    pub fn t(&self) -> &[f64] {
        self.fixed(Column::T)
    }

    /// Generalized coordinates, one column each.
    #[must_use]
    pub fn q(&self) -> [&[f64]; 2] {
        [self.fixed(Column::Q1), self.fixed(Column::Q2)]
    }

    /// Generalized speeds, one column each.
    #[must_use]
    pub fn qd(&self) -> [&[f64]; 2] {
        [self.fixed(Column::Qd1), self.fixed(Column::Qd2)]
    }

    /// Generalized accelerations, one column each.
    #[must_use]
    pub fn qdd(&self) -> [&[f64]; 2] {
        [self.fixed(Column::Qdd1), self.fixed(Column::Qdd2)]
    }

    /// Kinetic energy T, J.
    #[must_use]
    pub fn kinetic(&self) -> &[f64] {
        self.fixed(Column::Kinetic)
    }

    /// Potential energy Π, J.
    #[must_use]
    pub fn potential(&self) -> &[f64] {
        self.fixed(Column::Potential)
    }

    /// Power of the applied loads Q·q̇, W.
    #[must_use]
    pub fn power_applied(&self) -> &[f64] {
        self.fixed(Column::PowerApplied)
    }

    /// Power lost to viscous friction q̇ᵀBq̇ = 2Φ, W.
    #[must_use]
    pub fn power_dissipated(&self) -> &[f64] {
        self.fixed(Column::PowerDissipated)
    }

    /// Names of the machine's extra outputs.
    #[must_use]
    pub fn output_names(&self) -> &[&'static str] {
        &self.output_names
    }

    /// The extra outputs, one column per name (see [`output_at`](Self::output_at) for one
    /// column without collecting them all).
    #[must_use]
    pub fn outputs(&self) -> Vec<&[f64]> {
        (FIXED..self.columns()).map(|c| self.column(c)).collect()
    }

    /// The column of output `k` (in the order of [`output_names`](Self::output_names)),
    /// `None` when the machine has fewer outputs.
    #[must_use]
    pub fn output_at(&self, k: usize) -> Option<&[f64]> {
        (k < self.output_names.len()).then(|| self.column(FIXED + k))
    }

    /// Appends a state with everything derived from it.
    ///
    /// # Errors
    /// Any error of the system at this state; [`Error::NonFiniteState`] naming the time when
    /// a derived quantity (an energy, a power, an output) is not finite;
    /// [`Error::OutOfRange`] when the system gives a number of outputs other than its
    /// output names; [`Error::Description`] when its coordinate or output names are not those
    /// the trajectory was made for (a [`Default`] trajectory takes them on its first row).
    /// Nothing is appended then (the columns stay of equal length).
    pub fn push<S: LagrangeSystem + ?Sized>(&mut self, sys: &S, s: &State) -> Result<()> {
        if !self.is_blank()
            && (sys.coordinate_names() != self.coordinate_names
                || sys.output_names() != self.output_names)
        {
            return Err(Error::Description {
                item: "trajectory".to_owned(),
                problem: format!(
                    "was made for coordinates {:?} and outputs {:?}, not for a system with {:?} \
                     and {:?}",
                    self.coordinate_names,
                    self.output_names,
                    sys.coordinate_names(),
                    sys.output_names()
                ),
            });
        }
        self.push_with(sys, s, &mut Vec::new()).map(|_| ())
    }

    /// As [`push`](Self::push), gathering the outputs in the caller's buffer `out` (cleared
    /// first): a run records all its rows through one buffer instead of allocating one per
    /// row. Returns the row's q̈ (a run hands them on to the step that starts there).
    pub(crate) fn push_with<S: LagrangeSystem + ?Sized>(
        &mut self,
        sys: &S,
        s: &State,
        out: &mut Vec<f64>,
    ) -> Result<Vector2<f64>> {
        if self.is_blank() {
            // A default (empty) trajectory takes the system's columns on its first row.
            *self = Self::for_system(sys);
        }
        // q̈, T and the powers from one evaluation of the Lagrange terms.
        let RowTerms {
            acceleration: a,
            kinetic,
            applied: pa,
            dissipated: pd,
        } = row_terms(sys, s)?;
        let potential = sys.potential(&s.q)?;
        out.clear();
        let outputs = self.output_names.len();
        out.reserve(outputs);
        sys.outputs(s.t, &s.q, &s.qd, out)?;
        if out.len() != outputs {
            return Err(Error::OutOfRange {
                name: "number of outputs given by the system (must match its output names)",
                value: out.len() as f64,
                min: outputs as f64,
                max: outputs as f64,
                ends: crate::Ends::Closed,
            });
        }
        if !(potential.is_finite() && out.iter().all(|v| v.is_finite())) {
            return Err(Error::NonFiniteState { time: s.t });
        }
        self.reserve_row();
        let row = [
            s.t, s.q[0], s.q[1], s.qd[0], s.qd[1], a[0], a[1], kinetic, potential, pa, pd,
        ];
        let (cap, n) = (self.cap, self.len);
        for (c, &v) in row.iter().chain(out.iter()).enumerate() {
            self.data[c * cap + n] = v;
        }
        self.len += 1;
        Ok(a)
    }

    /// Keeps the first `n` rows (all of them when there are fewer), in every column.
    pub fn truncate(&mut self, n: usize) {
        self.len = self.len.min(n);
    }

    /// Number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` when nothing is recorded.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The column of the output `name`, if the machine has it.
    #[must_use]
    pub fn output(&self, name: &str) -> Option<&[f64]> {
        let i = self.output_names.iter().position(|n| *n == name)?;
        Some(self.column(FIXED + i))
    }

    /// The last recorded state.
    #[must_use]
    pub fn last_state(&self) -> Option<State> {
        let n = self.len.checked_sub(1)?;
        let at = |c: Column| self.fixed(c)[n];
        Some(State::new(
            at(Column::T),
            nalgebra::Vector2::new(at(Column::Q1), at(Column::Q2)),
            nalgebra::Vector2::new(at(Column::Qd1), at(Column::Qd2)),
        ))
    }

    /// The column names of [`to_csv`](Self::to_csv), in order.
    #[must_use]
    pub fn header(&self) -> Vec<String> {
        let [a, b] = self.coordinate_names;
        let mut h = vec!["t".to_string(), a.into(), b.into()];
        h.extend([
            format!("{a}_dot"),
            format!("{b}_dot"),
            format!("{a}_ddot"),
            format!("{b}_ddot"),
        ]);
        h.extend(["T", "Pi", "P_applied", "P_dissipated"].map(String::from));
        h.extend(self.output_names.iter().map(|s| s.to_string()));
        h
    }

    /// The trajectory as CSV: one header line (see [`header`](Self::header)), then one line
    /// per row, values in full precision (Rust's shortest round-trip form).
    #[must_use]
    pub fn to_csv(&self) -> String {
        let mut s = self.header().join(",");
        s.push('\n');
        let columns: Vec<&[f64]> = (0..self.columns()).map(|c| self.column(c)).collect();
        for r in 0..self.len {
            let row = columns.iter().map(|c| c[r]);
            for (i, v) in row.enumerate() {
                if i > 0 {
                    s.push(',');
                }
                let _ = write!(s, "{v}");
            }
            s.push('\n');
        }
        s
    }
}
