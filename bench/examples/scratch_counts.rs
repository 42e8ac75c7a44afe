//! Scratch: evaluation counts and errors, tmm vs ode_solvers (temporary).
use nalgebra::Vector2;
use ode_solvers::dop_shared::OutputType;
use tmm::dynamics::machines::{CoaxialPropellers, FiveBar};
use tmm::dynamics::{accelerations, run, Dopri5, LagrangeSystem, RunOptions, State};
type Y = ode_solvers::Vector4<f64>;
struct Peer<'a, S>(&'a S);
impl<S: LagrangeSystem> ode_solvers::System<f64, Y> for Peer<'_, S> {
    fn system(&self, t: f64, y: &Y, dy: &mut Y) {
        let (q, qd) = (Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]));
        let a = accelerations(self.0, t, &q, &qd).unwrap_or(Vector2::repeat(f64::NAN));
        *dy = Y::new(qd[0], qd[1], a[0], a[1]);
    }
}
fn tmm_dp<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, tol: f64) -> (State, usize, usize) {
    let dp = Dopri5::new(tol).unwrap();
    let o = RunOptions { record_every: usize::MAX, ..RunOptions::until(t_end, 1e-3 * t_end) };
    let r = run(sys, &dp, s0, &o).unwrap();
    (r.last, r.evaluations, r.steps)
}
fn peer<S: LagrangeSystem>(sys: &S, s0: State, t_end: f64, tol: f64) -> (Y, u32, u32, u32) {
    let y0 = Y::new(s0.q[0], s0.q[1], s0.qd[0], s0.qd[1]);
    let mut p = ode_solvers::Dopri5::from_param(Peer(sys), s0.t, t_end, t_end, y0, tol, tol, 0.9, 0.04, 0.2, 10.0, t_end, 1e-3 * t_end, 100_000, 1000, OutputType::Sparse);
    let st = p.integrate().unwrap();
    (*p.y_out().last().unwrap(), st.num_eval, st.accepted_steps, st.rejected_steps)
}
fn err(a: &State, r: &State) -> f64 {
    (a.q - r.q).amax().max((a.qd - r.qd).amax())
}
fn perr(a: &Y, r: &State) -> f64 {
    [a[0] - r.q[0], a[1] - r.q[1], a[2] - r.qd[0], a[3] - r.qd[1]].iter().fold(0.0, |m: f64, d| m.max(d.abs()))
}
fn go<S: LagrangeSystem>(name: &str, sys: &S, s0: State, t_end: f64) {
    let (reference, _, _) = tmm_dp(sys, s0, t_end, 1e-14);
    let (mut tt, mut tp) = (0, 0);
    for k in 3..=12 {
        let tol = 10f64.powi(-k);
        let (a, n, st) = tmm_dp(sys, s0, t_end, tol);
        let (b, m, acc, rej) = peer(sys, s0, t_end, tol);
        tt += n; tp += m as usize;
        println!("{name} tol 1e-{k}: tmm {n} ({st} steps) err {:.2e} | peer {m} ({acc}+{rej}) err {:.2e}", err(&a, &reference), perr(&b, &reference));
    }
    println!("{name} total tmm {tt} peer {tp}");
}
fn main() {
    go("coax", &CoaxialPropellers::default(), State::at_rest(Vector2::zeros()), 1.0);
    go("fivebar", &FiveBar::default(), State::at_rest(Vector2::new(120f64.to_radians(), 60f64.to_radians())), 0.5);
}
