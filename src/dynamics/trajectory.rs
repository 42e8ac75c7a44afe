//! A recorded motion as columns, exportable as CSV.

use std::fmt::Write as _;

use super::system::{accelerations, kinetic_energy, powers, LagrangeSystem, State};
use crate::error::{Error, Result};

/// A motion recorded as columns: time, q, q̇, q̈, the energies and powers, and the
/// machine's own outputs (for the gear drives the speed of every link).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trajectory {
    /// Names of the two generalized coordinates.
    pub coordinate_names: [&'static str; 2],
    /// Time, s.
    pub t: Vec<f64>,
    /// Generalized coordinates, one column each.
    pub q: [Vec<f64>; 2],
    /// Generalized speeds.
    pub qd: [Vec<f64>; 2],
    /// Generalized accelerations.
    pub qdd: [Vec<f64>; 2],
    /// Kinetic energy T, J.
    pub kinetic: Vec<f64>,
    /// Potential energy Π, J.
    pub potential: Vec<f64>,
    /// Power of the applied loads Q·q̇, W.
    pub power_applied: Vec<f64>,
    /// Power lost to viscous friction q̇ᵀBq̇ = 2Φ, W.
    pub power_dissipated: Vec<f64>,
    /// Names of the machine's extra outputs.
    pub output_names: Vec<&'static str>,
    /// The extra outputs, one column per name.
    pub outputs: Vec<Vec<f64>>,
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

    /// Appends a state with everything derived from it.
    ///
    /// # Errors
    /// Any error of the system at this state; [`Error::NonFiniteState`] naming the time when
    /// a derived quantity overflows. Nothing is appended then (the columns stay of equal
    /// length).
    pub fn push<S: LagrangeSystem + ?Sized>(&mut self, sys: &S, s: &State) -> Result<()> {
        let a = accelerations(sys, s.t, &s.q, &s.qd)?;
        let (pa, pd) = powers(sys, s.t, &s.q, &s.qd)?;
        let kinetic = kinetic_energy(sys, &s.q, &s.qd).map_err(|e| match e {
            Error::NonFinite { .. } => Error::NonFiniteState { time: s.t },
            e => e,
        })?;
        let potential = sys.potential(&s.q)?;
        let mut out = Vec::with_capacity(self.outputs.len());
        sys.outputs(s.t, &s.q, &s.qd, &mut out)?;
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
        for (col, v) in self.outputs.iter_mut().zip(out) {
            col.push(v);
        }
        Ok(())
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
