//! A system seen from the left of a breakpoint, for the step that ends on it.

use nalgebra::{Matrix2, Vector2};

use crate::dynamics::switch::SwitchLoads;
use crate::dynamics::system::{LagrangeSystem, LagrangeTerms};
use crate::error::Result;

/// A system seen from the left of the time `at`: its forces at `at` or later are those at the
/// last time before it (`at.next_down()`), so that a step ending on a breakpoint integrates
/// the force it had before a jump there. Everything else is the system's own.
pub(super) struct LeftOf<'a, S: ?Sized> {
    pub(super) sys: &'a S,
    pub(super) at: f64,
}

impl<S: LagrangeSystem + ?Sized> LeftOf<'_, S> {
    fn time(&self, t: f64) -> f64 {
        if t >= self.at {
            self.at.next_down()
        } else {
            t
        }
    }
}

impl<S: LagrangeSystem + ?Sized> LagrangeSystem for LeftOf<'_, S> {
    fn coordinate_names(&self) -> [&'static str; 2] {
        self.sys.coordinate_names()
    }
    fn inertia(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.sys.inertia(q)
    }
    fn inertia_derivatives(&self, q: &Vector2<f64>) -> Result<[Matrix2<f64>; 2]> {
        self.sys.inertia_derivatives(q)
    }
    fn forces(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.sys.forces(self.time(t), q, qd)
    }
    fn potential(&self, q: &Vector2<f64>) -> Result<f64> {
        self.sys.potential(q)
    }
    fn potential_gradient(&self, q: &Vector2<f64>) -> Result<Vector2<f64>> {
        self.sys.potential_gradient(q)
    }
    fn damping(&self, q: &Vector2<f64>) -> Result<Matrix2<f64>> {
        self.sys.damping(q)
    }
    fn terms(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Result<LagrangeTerms> {
        self.sys.terms(self.time(t), q, qd)
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
    fn switches(&self) -> usize {
        self.sys.switches()
    }
    fn switch_speeds(
        &self,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        out: &mut [f64],
    ) -> Result<()> {
        self.sys.switch_speeds(t, q, qd, out)
    }
    fn switch_force(
        &self,
        i: usize,
        t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        direction: f64,
    ) -> Result<Vector2<f64>> {
        self.sys.switch_force(i, self.time(t), q, qd, direction)
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
