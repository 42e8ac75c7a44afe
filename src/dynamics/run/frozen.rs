//! A system whose velocity-sign switches are held in one direction through a step: the
//! resistances keep the direction they had at the step's start, so that a switch speed passes
//! zero smoothly inside the step and its crossing can be located.

use std::cell::{Cell, RefCell};

use nalgebra::{Matrix2, Vector2};

use super::held::{decoupled, excess, Hold, NOT_HELD};
use crate::dynamics::switch::SwitchLoads;
use crate::dynamics::system::{kink_slots, LagrangeSystem, LagrangeTerms};
use crate::error::{Error, Result};

/// The sign of `x` as −1, 0 or +1.
pub(super) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// `sys` with each switch's resistance held in the direction `modes[i]` (±1; 0 leaves the
/// system's own): where a state's switch speed has another sign, the system's force for that
/// sign is replaced by the one for the mode ([`LagrangeSystem::switch_force`]). The run sets
/// the modes before each step.
///
/// With `hold` (a system some of whose switches can hold a coordinate, see
/// [`held`](super::held)), the coordinates it holds have their rows replaced by q̈ₖ = 0, and
/// each holdable switch has a release argument after the system's switch speeds (its
/// [`excess`] while it holds, [`NOT_HELD`] otherwise).
pub(super) struct Frozen<'a, S: ?Sized> {
    sys: &'a S,
    modes: &'a [Cell<f64>],
    speeds: RefCell<Vec<f64>>,
    hold: Option<&'a Hold>,
}

impl<'a, S: LagrangeSystem + ?Sized> Frozen<'a, S> {
    /// `sys` with one mode for each of its switches, and the coordinates `hold` holds.
    pub(super) fn new(sys: &'a S, modes: &'a [Cell<f64>], hold: Option<&'a Hold>) -> Self {
        Self {
            sys,
            modes,
            speeds: RefCell::new(vec![0.0; modes.len()]),
            hold,
        }
    }

    /// The coordinates held now (none without holds).
    fn held_now(&self) -> Option<[bool; 2]> {
        self.hold.map(Hold::held).filter(|h| h.iter().any(|&x| x))
    }

    /// One part of the terms as the held motion sees it: `part` of the terms made of the
    /// system's `set` alone (the others zero), decoupled.
    fn held_part<T>(
        held: [bool; 2],
        set: impl FnOnce(&mut LagrangeTerms),
        part: impl FnOnce(LagrangeTerms) -> T,
    ) -> T {
        let mut t = LagrangeTerms {
            inertia: Matrix2::identity(),
            inertia_derivatives: [Matrix2::zeros(); 2],
            forces: Vector2::zeros(),
            potential_gradient: Vector2::zeros(),
            damping: Matrix2::zeros(),
        };
        set(&mut t);
        part(decoupled(t, held))
    }

    /// What to add to the system's forces at a state for the held directions.
    fn held(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Option<Vector2<f64>>> {
        let mut speeds = self.speeds.borrow_mut();
        speeds.fill(f64::NAN);
        self.sys.switch_speeds(t, q, qd, &mut speeds)?;
        let mut add: Option<Vector2<f64>> = None;
        for (i, (&v, mode)) in speeds.iter().zip(self.modes).enumerate() {
            if !v.is_finite() {
                return Err(Error::NonFiniteState { time: t });
            }
            let (mode, actual) = (mode.get(), sign(v));
            if mode == 0.0 || actual == mode {
                continue;
            }
            let mut d = self.sys.switch_force(i, t, q, qd, mode)?;
            if actual != 0.0 {
                d -= self.sys.switch_force(i, t, q, qd, actual)?;
            }
            *add.get_or_insert_with(Vector2::zeros) += d;
        }
        Ok(add)
    }
}

impl<S: LagrangeSystem + ?Sized> LagrangeSystem for Frozen<'_, S> {
    fn coordinate_names(&self) -> [&'static str; 2] {
        self.sys.coordinate_names()
    }
    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        let a = self.sys.inertia(q)?;
        Ok(match self.held_now() {
            Some(h) => Self::held_part(h, |t| t.inertia = a, |t| t.inertia),
            None => a,
        })
    }
    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        let d = self.sys.inertia_derivatives(q)?;
        Ok(match self.held_now() {
            Some(h) => Self::held_part(h, |t| t.inertia_derivatives = d, |t| t.inertia_derivatives),
            None => d,
        })
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        if self.held_now().is_some() {
            return Ok(self.terms(t, q, qd)?.forces);
        }
        let f = self.sys.forces(t, q, qd)?;
        Ok(match self.held(t, q, qd)? {
            Some(d) => f + d,
            None => f,
        })
    }
    fn potential(&self, q: &Vector2<f64>) -> Result<f64> {
        self.sys.potential(q)
    }
    fn potential_gradient(&self, q: &Vector2<f64>) -> Result<Vector2<f64>> {
        let g = self.sys.potential_gradient(q)?;
        Ok(match self.held_now() {
            Some(h) => Self::held_part(h, |t| t.potential_gradient = g, |t| t.potential_gradient),
            None => g,
        })
    }
    fn damping(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        let b = self.sys.damping(q)?;
        Ok(match self.held_now() {
            Some(h) => Self::held_part(h, |t| t.damping = b, |t| t.damping),
            None => b,
        })
    }
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        if let Some(h) = self.held_now() {
            let mut terms = self.sys.held_terms(t, q, qd, h)?;
            if let Some(d) = self.held(t, q, qd)? {
                terms.forces += d;
            }
            return Ok(decoupled(terms, h));
        }
        let mut terms = self.sys.terms(t, q, qd)?;
        if let Some(d) = self.held(t, q, qd)? {
            terms.forces += d;
        }
        Ok(terms)
    }
    fn output_names(&self) -> Vec<&'static str> {
        self.sys.output_names()
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.sys.breakpoints()
    }
    fn kinks(&self) -> Vec<Vec<f64>> {
        self.sys.kinks()
    }
    fn kink_arguments(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        self.sys.kink_arguments(t, q, qd, out)
    }
    /// The system's switches, then one release argument per switch that can hold a
    /// coordinate.
    fn switches(&self) -> usize {
        self.modes.len() + self.hold.map_or(0, |h| h.holdable.len())
    }
    fn switch_speeds(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        let Some(hold) = self.hold else {
            return self.sys.switch_speeds(t, q, qd, out);
        };
        kink_slots(out, self.switches())?;
        let (speeds, releases) = out.split_at_mut(self.modes.len());
        self.sys.switch_speeds(t, q, qd, speeds)?;
        for (o, &(i, k)) in releases.iter_mut().zip(&hold.holdable) {
            *o = if hold.holds(i, k) {
                excess(&self.sys.switch_loads(i, t, q, qd)?.checked()?)
            } else {
                NOT_HELD
            };
        }
        Ok(())
    }
    fn switch_holds(&self, i: usize) -> Option<usize> {
        if i < self.modes.len() {
            self.sys.switch_holds(i)
        } else {
            None
        }
    }
    fn forces_depend_on_time(&self) -> bool {
        self.sys.forces_depend_on_time()
    }
    fn switch_force(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        direction: f64,
    ) -> Result<Vector2<f64>> {
        self.sys.switch_force(i, t, q, qd, direction)
    }
    fn switch_loads(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Result<SwitchLoads> {
        self.sys.switch_loads(i, t, q, qd)
    }
    fn outputs(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut Vec<f64>,
    ) -> Result<()> {
        self.sys.outputs(t, q, qd, out)
    }
    fn locks(&self) -> usize {
        self.sys.locks()
    }
    fn lock_measures(&self, q: &Vector2<f64>, out: &mut [f64]) -> Result<()> {
        self.sys.lock_measures(q, out)
    }
}
