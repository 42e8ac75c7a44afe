//! A recorded motion as columns, exportable as CSV.

use std::fmt::Write as _;

use super::system::{accelerations, kinetic_energy, powers, LagrangeSystem, State};
use crate::error::{Error, Result};

/// A motion recorded as columns: time, q, q̇, q̈, the energies and powers, and the
/// machine's own outputs (for the gear drives the speed of every link).
///
/// The columns are private and grow only through [`push`](Self::push), which appends a whole
/// row of finite numbers or nothing: every column has [`len`](Self::len) entries, and no
/// recorded number is NaN or infinite. Read them through the accessors. Which rows a
/// [`run`](super::run) records (the start, step ends, requested times, the end) is said at
/// [`RunOptions`](super::RunOptions#what-is-recorded).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trajectory {
    coordinate_names: [&'static str; 2],
    t: Vec<f64>,
    q: [Vec<f64>; 2],
    qd: [Vec<f64>; 2],
    qdd: [Vec<f64>; 2],
    kinetic: Vec<f64>,
    potential: Vec<f64>,
    power_applied: Vec<f64>,
    power_dissipated: Vec<f64>,
    output_names: Vec<&'static str>,
    outputs: Vec<Vec<f64>>,
}

impl Trajectory {
    /// An empty trajectory with the column names of `sys`.
    #[must_use]
    pub fn for_system<S: LagrangeSystem + ?Sized>(sys: &S) -> Self {
        let output_names = sys.output_names();
        Self {
            coordinate_names: sys.coordinate_names(),
            outputs: vec![Vec::new(); output_names.len()],
            output_names,
            ..Self::default()
        }
    }

    /// Names of the two generalized coordinates.
    #[must_use]
    pub fn coordinate_names(&self) -> [&'static str; 2] {
        self.coordinate_names
    }

    /// Time, s.
    #[must_use]
    pub fn t(&self) -> &[f64] {
        &self.t
    }

    /// Generalized coordinates, one column each.
    #[must_use]
    pub fn q(&self) -> &[Vec<f64>; 2] {
        &self.q
    }

    /// Generalized speeds, one column each.
    #[must_use]
    pub fn qd(&self) -> &[Vec<f64>; 2] {
        &self.qd
    }

    /// Generalized accelerations, one column each.
    #[must_use]
    pub fn qdd(&self) -> &[Vec<f64>; 2] {
        &self.qdd
    }

    /// Kinetic energy T, J.
    #[must_use]
    pub fn kinetic(&self) -> &[f64] {
        &self.kinetic
    }

    /// Potential energy Π, J.
    #[must_use]
    pub fn potential(&self) -> &[f64] {
        &self.potential
    }

    /// Power of the applied loads Q·q̇, W.
    #[must_use]
    pub fn power_applied(&self) -> &[f64] {
        &self.power_applied
    }

    /// Power lost to viscous friction q̇ᵀBq̇ = 2Φ, W.
    #[must_use]
    pub fn power_dissipated(&self) -> &[f64] {
        &self.power_dissipated
    }

    /// Names of the machine's extra outputs.
    #[must_use]
    pub fn output_names(&self) -> &[&'static str] {
        &self.output_names
    }

    /// The extra outputs, one column per name.
    #[must_use]
    pub fn outputs(&self) -> &[Vec<f64>] {
        &self.outputs
    }

    /// Appends a state with everything derived from it.
    ///
    /// # Errors
    /// Any error of the system at this state; [`Error::NonFiniteState`] naming the time when
    /// a derived quantity (an energy, a power, an output) is not finite;
    /// [`Error::OutOfRange`] when the system gives a number of outputs other than its
    /// output names (or other names than the trajectory was made for). Nothing is appended
    /// then (the columns stay of equal length).
    pub fn push<S: LagrangeSystem + ?Sized>(&mut self, sys: &S, s: &State) -> Result<()> {
        self.push_with(sys, s, &mut Vec::new())
    }

    /// As [`push`](Self::push), gathering the outputs in the caller's buffer `out` (cleared
    /// first): a run records all its rows through one buffer instead of allocating one per
    /// row.
    pub(crate) fn push_with<S: LagrangeSystem + ?Sized>(
        &mut self,
        sys: &S,
        s: &State,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        if self.t.is_empty() && self.output_names.is_empty() && self.outputs.is_empty() {
            // A default (empty) trajectory takes the system's columns on its first row.
            *self = Self::for_system(sys);
        }
        let a = accelerations(sys, s.t, &s.q, &s.qd)?;
        let (pa, pd) = powers(sys, s.t, &s.q, &s.qd)?;
        let kinetic = kinetic_energy(sys, &s.q, &s.qd).map_err(|e| match e {
            Error::NonFinite { .. } => Error::NonFiniteState { time: s.t },
            e => e,
        })?;
        let potential = sys.potential(&s.q)?;
        out.clear();
        out.reserve(self.outputs.len());
        sys.outputs(s.t, &s.q, &s.qd, out)?;
        if out.len() != self.outputs.len() {
            return Err(Error::OutOfRange {
                name: "number of outputs given by the system (must match its output names)",
                value: out.len() as f64,
                min: self.outputs.len() as f64,
                max: self.outputs.len() as f64,
                ends: crate::Ends::Closed,
            });
        }
        if !(potential.is_finite() && out.iter().all(|v| v.is_finite())) {
            return Err(Error::NonFiniteState { time: s.t });
        }
        self.t.push(s.t);
        for i in 0..2 {
            self.q[i].push(s.q[i]);
            self.qd[i].push(s.qd[i]);
            self.qdd[i].push(a[i]);
        }
        self.kinetic.push(kinetic);
        self.potential.push(potential);
        self.power_applied.push(pa);
        self.power_dissipated.push(pd);
        for (col, &v) in self.outputs.iter_mut().zip(out.iter()) {
            col.push(v);
        }
        Ok(())
    }

    /// Keeps the first `n` rows (all of them when there are fewer), in every column.
    pub fn truncate(&mut self, n: usize) {
        self.t.truncate(n);
        for c in self
            .q
            .iter_mut()
            .chain(self.qd.iter_mut())
            .chain(self.qdd.iter_mut())
            .chain(self.outputs.iter_mut())
        {
            c.truncate(n);
        }
        for c in [
            &mut self.kinetic,
            &mut self.potential,
            &mut self.power_applied,
            &mut self.power_dissipated,
        ] {
            c.truncate(n);
        }
    }

    /// Number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// `true` when nothing is recorded.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The column of the output `name`, if the machine has it.
    #[must_use]
    pub fn output(&self, name: &str) -> Option<&[f64]> {
        let i = self.output_names.iter().position(|n| *n == name)?;
        Some(&self.outputs[i])
    }

    /// The last recorded state.
    #[must_use]
    pub fn last_state(&self) -> Option<State> {
        let n = self.len().checked_sub(1)?;
        Some(State::new(
            self.t[n],
            nalgebra::Vector2::new(self.q[0][n], self.q[1][n]),
            nalgebra::Vector2::new(self.qd[0][n], self.qd[1][n]),
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
        for r in 0..self.len() {
            let mut row = vec![
                self.t[r],
                self.q[0][r],
                self.q[1][r],
                self.qd[0][r],
                self.qd[1][r],
                self.qdd[0][r],
                self.qdd[1][r],
                self.kinetic[r],
                self.potential[r],
                self.power_applied[r],
                self.power_dissipated[r],
            ];
            row.extend(self.outputs.iter().map(|c| c[r]));
            for (i, v) in row.iter().enumerate() {
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
