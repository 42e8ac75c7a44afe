//! The adapter's part for a machine reduced to its crank: the reduced moment of inertia and
//! moment over a turn (or a rocking crank's range), the run-up and the flywheels.

use std::f64::consts::TAU;

use tmm::dynamics::machines::LinearMotor;
use tmm::dynamics::Rk4;
use tmm::linkage::dynamics::{LinkageSystem, Motor, RunUpOptions};

use super::{failure, Machine};
use crate::budget;
use crate::model::{
    DynamicsReport, DynamicsRequest, Failure, FlywheelRow, Range, ReducedRow, RunUpReport, TurnRow,
};

/// The most RK4 steps a run-up may take (a turn under way is finished); one expected to need
/// more — a turn at the speed asked for, or the spin-up to that speed — is refused before it
/// starts. A linkage whose solve weighs more has fewer: see [`run_up_budget`].
const MAX_RUN_UP_STEPS: f64 = 1e6;

/// The positions at which a flywheel's energy–mass diagram is taken over a turn.
const FLYWHEEL_POSITIONS: usize = 3600;

/// Reduced quantities between two progress reports.
const PROGRESS_EVERY: usize = 5000;

/// The RK4 steps a run-up of a linkage whose one solve weighs `weight` dyad solves may take:
/// [`MAX_RUN_UP_STEPS`], or fewer where a step's 4 evaluations of the reduced quantities
/// would take the run-up above [`budget::MAX_WORK`] — ⌊min(10⁶, 4·10⁸ / (4·weight))⌋, a
/// count that depends on the description alone (the double butterfly's: 230 946).
pub fn run_up_budget(weight: f64) -> f64 {
    MAX_RUN_UP_STEPS
        .min(budget::most_solves(weight) / 4.0)
        .floor()
}

/// RK4's steps a turn at the top speed: 1° a step. The steady turns' speeds and δ agree to
/// the 5 digits printed with those at 2 000 steps a turn (the error of RK4 falls as h⁴; the
/// double butterfly, whose step this sets, was measured at 125, 250, 500 and 2 000).
const STEPS_PER_TURN: f64 = 360.0;

impl Machine {
    /// The machine's dynamics: reduced quantities, run-up and flywheels.
    ///
    /// # Errors
    /// Two inputs or a slider; the library's errors.
    pub fn dynamics(
        &self,
        request: &DynamicsRequest,
        progress: &mut dyn FnMut(&str),
    ) -> Result<DynamicsReport, Failure> {
        self.one_input("a machine reduced to its crank")?;
        if !self.plan.input_is_crank() {
            return Err(Failure::new(
                "the dynamics of a machine reduced to its crank need a crank input, and this \
                 linkage is driven by a slider",
            ));
        }
        let rocking = match self.range() {
            Range::Rocking(lo, hi) => Some((lo, hi)),
            _ => None,
        };
        if let Some((lo, hi)) = rocking
            && (request.run_up || !request.flywheel.is_empty())
        {
            return Err(Failure::new(format!(
                "a run-up and a flywheel need a crank that turns fully, and this crank rocks \
                 between the lock angles {:.4}° and {:.4}° ({lo} and {hi} rad), where the \
                 linkage stops it and it must reverse",
                lo.to_degrees(),
                hi.to_degrees()
            ))
            .hint("without --run-up and --flywheel, the reduced quantities over that range"));
        }
        let speed = request.speed;
        super::check_speed(speed)?;
        super::check_machine(request)?;
        if speed == 0.0 {
            return Err(Failure::new(format!(
                "the speed must be finite and not zero, got {}",
                crate::model::typed(speed)
            ))
            .hint("give --speed, rad/s, negative for clockwise"));
        }
        let f = |e: tmm::Error| failure(&e);
        let mut bare = LinkageSystem::new(self.plan.clone()).map_err(f)?;
        if request.rotor != 0.0 {
            bare = bare.with_inertia(0, request.rotor).map_err(f)?;
        }
        let weight = self.solve_weight();
        #[allow(clippy::cast_precision_loss)]
        let flywheel_solves = (request.flywheel.len() * FLYWHEEL_POSITIONS) as f64;
        budget::check(
            flywheel_solves,
            weight,
            &format!(
                "--flywheel with {} values of δ ({FLYWHEEL_POSITIONS} positions each)",
                request.flywheel.len()
            ),
            "give fewer values of δ to --flywheel",
        )?;
        let rows = Self::reduced_rows(&bare, rocking, request, weight, progress)?;
        let mut flywheels = Vec::new();
        let count = request.flywheel.len();
        for (k, &delta) in request.flywheel.iter().enumerate() {
            progress(&format!("flywheel {} of {count}, for δ = {delta}", k + 1));
            let fw = bare
                .flywheel(delta, speed, FLYWHEEL_POSITIONS)
                .map_err(|e| {
                    failure(&e).hint(format!(
                    "--flywheel {}: give each δ between 0 and 2, for example 0.05 (a machine's \
                     usual 0.01 to 0.1)",
                    crate::model::typed(delta)
                ))
                })?;
            flywheels.push(FlywheelRow {
                delta,
                inertia: fw.moment_of_inertia,
                simplified: fw.simplified,
                energy_range: fw.energy_range,
                driving_moment: fw.driving_moment,
            });
        }
        let run_up = if request.run_up {
            Some(Self::run_up(&bare, &rows, request, weight, progress)?)
        } else {
            None
        };
        Ok(DynamicsReport {
            name: self.name().to_owned(),
            speed,
            rotor: request.rotor,
            rocking,
            reduced: rows,
            run_up,
            flywheels,
        })
    }

    /// The reduced quantities at `request.positions` crank angles: over a turn from the
    /// reference pose, or between the lock angles of a rocking crank; refused before the
    /// work when it is above the budget for a linkage whose solve weighs `weight`.
    fn reduced_rows(
        bare: &LinkageSystem,
        rocking: Option<(f64, f64)>,
        request: &DynamicsRequest,
        weight: f64,
        progress: &mut dyn FnMut(&str),
    ) -> Result<Vec<ReducedRow>, Failure> {
        let speed = request.speed;
        let n = request.positions;
        #[allow(clippy::cast_precision_loss)]
        budget::check(
            n as f64,
            weight,
            &format!("--positions {n}"),
            &format!(
                "give --positions N with N at most {:.0}",
                budget::most_solves(weight)
            ),
        )?;
        let phis: Vec<f64> = match rocking {
            None => {
                // The angles of the library's `reduced_cycle`: n equal steps over a turn from
                // the reference pose in the sense of `speed`, taken here one by one so that
                // a long table reports its progress.
                let phi0 = bare.plan().reference_input();
                #[allow(clippy::cast_precision_loss)]
                let step = speed.signum() * TAU / n as f64;
                #[allow(clippy::cast_precision_loss)]
                (0..n).map(|i| phi0 + step * i as f64).collect()
            }
            Some((lo, hi)) => {
                // At a lock the linkage is at a dead point: the crank's rate moves no
                // dead-pointed group, whose links' transfer functions and so J_red grow
                // without bound. The positions are the middles of equal steps between the
                // locks, in the order the crank meets them at `speed`.
                #[allow(clippy::cast_precision_loss)]
                let h = (hi - lo) / n as f64;
                let mut phis: Vec<f64> = (0..n)
                    .map(|k| {
                        #[allow(clippy::cast_precision_loss)]
                        let k = k as f64;
                        lo + h * (k + 0.5)
                    })
                    .collect();
                if speed < 0.0 {
                    phis.reverse();
                }
                phis
            }
        };
        let over = if rocking.is_some() {
            "the rocking range"
        } else {
            "a turn"
        };
        progress(&format!("reduced moment of inertia and moment over {over}"));
        let reduced = phis
            .iter()
            .enumerate()
            .map(|(k, &phi)| {
                if k % PROGRESS_EVERY == 0 && n > PROGRESS_EVERY {
                    progress(&format!(
                        "reduced moment of inertia and moment, position {} of {n}",
                        k + 1
                    ));
                }
                bare.reduced(phi, speed).map_err(|e| match rocking {
                    Some(_) => Failure::new(format!("at φ = {:.6}°: {e}", phi.to_degrees())),
                    None => failure(&e),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let phi0 = match rocking {
            Some((_, hi)) if speed < 0.0 => hi,
            Some((lo, _)) => lo,
            None => reduced.first().map_or(0.0, |r| r.phi),
        };
        Ok(reduced
            .iter()
            .map(|r| ReducedRow {
                phi: r.phi,
                turned: (r.phi - phi0).abs(),
                inertia: r.inertia,
                inertia_derivative: r.inertia_derivative,
                loads: r.loads,
            })
            .collect())
    }

    /// The run-up from rest under the motor of `request` (or one sized from the loads of
    /// `rows`) to the steady state, by RK4, within the budget of steps of [`run_up_budget`]
    /// for a linkage whose solve weighs `weight`.
    fn run_up(
        bare: &LinkageSystem,
        rows: &[ReducedRow],
        request: &DynamicsRequest,
        weight: f64,
        progress: &mut dyn FnMut(&str),
    ) -> Result<RunUpReport, Failure> {
        let f = |e: tmm::Error| failure(&e);
        let speed = request.speed;
        let (a, b, default_motor) = match request.motor {
            Some((a, b)) => (a, b, false),
            None => {
                let mean = rows.iter().map(|r| r.loads).sum::<f64>() / rows.len() as f64;
                let peak = rows.iter().map(|r| r.loads.abs()).fold(0.0, f64::max);
                // An induction motor of 4 % slip at the speed asked for, whose nominal
                // moment covers the loads' mean with 10 % to spare (or a tenth of their
                // peak, for a machine whose loads average out).
                let nominal = (1.1 * mean.abs()).max(0.1 * peak);
                if nominal.is_nan() || nominal <= 0.0 {
                    return Err(
                        Failure::new("the machine has no loads to size a motor from")
                            .hint("give the motor with --motor a,b (M = a − b·|ω|, N·m)"),
                    );
                }
                // A speed so small (5e-324 rad/s) that 4 % above it rounds to itself has
                // no slip to size the motor by: the speed is at fault, named as typed.
                let m = LinearMotor::from_nominal(nominal, speed.abs() / 0.96, speed.abs())
                    .map_err(|e| {
                        if speed.abs() / 0.96 > speed.abs() {
                            return f(e);
                        }
                        Failure::new(format!(
                            "--speed {} rad/s is too slow to size a motor for: its idle speed \
                             4 % above it rounds to the speed itself",
                            crate::model::typed(speed)
                        ))
                        .hint("give a larger --speed, or the motor with --motor a,b")
                    })?;
                // Rounded as a person writes a motor's data: the values echoed are the
                // values run, and `--motor a,b` with them repeats the run.
                (
                    crate::model::as_written(m.a),
                    crate::model::as_written(m.b),
                    true,
                )
            }
        };
        if !(a > 0.0 && b >= 0.0) {
            return Err(Failure::new(format!(
                "the motor M = a − b·|ω| needs a starting moment a > 0 (in the sense of \
                 --speed) and a slope b ≥ 0 (a moment that grows with speed runs away), and \
                 it is a = {} N·m, b = {} N·m·s/rad",
                crate::model::typed(a),
                crate::model::typed(b)
            ))
            .hint("give --motor a,b with a > 0 and b ≥ 0; a negative --speed turns it clockwise"));
        }
        let sense = speed.signum();
        let machine = bare
            .clone()
            .with_motor(0, Motor::Linear(LinearMotor { a: sense * a, b }))
            .map_err(f)?;
        // STEPS_PER_TURN a turn at the speed the machine may reach: the speed asked, or a
        // damped motor's idle speed a/b if that is higher (up to 100 times the speed asked,
        // so that a run stays within its step budget), and RK4 well inside its stability
        // limit (hλ ≈ −2.785) for the motor's damping b/J_red.
        let idle = if b > 0.0 { a.abs() / b } else { 0.0 };
        let top = speed.abs().max(idle.min(100.0 * speed.abs()));
        let (j_min, phi_min) = rows
            .iter()
            .map(|r| (r.inertia, r.phi))
            .fold((f64::INFINITY, 0.0), |m, r| if r.0 < m.0 { r } else { m });
        if j_min.is_nan() || j_min <= 0.0 {
            // Without inertia the motion has no acceleration to integrate: ω jumps to where
            // the motor balances the loads.
            return Err(Failure::new(format!(
                "a run-up needs the machine's inertia, and its reduced moment of inertia \
                 J_red is {} kg·m² at φ = {:.4}° (its links carry no mass there)",
                crate::model::typed(j_min),
                phi_min.to_degrees()
            ))
            .hint("give the links masses in the file, or a flywheel on the crank with --rotor J"));
        }
        let h = (TAU / top / STEPS_PER_TURN).min(0.5 * j_min / b.abs().max(f64::MIN_POSITIVE));
        let budget = run_up_budget(weight);
        Self::within_budget(rows, speed, (a, b), h, budget)?;
        // No one turn may spend more than the whole budget of steps; no turn begins after it.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let opts = RunUpOptions::new(h)
            .with_record_every(1)
            .with_max_turn_time(60.0_f64.min(budget * h))
            .with_max_steps(budget as usize);
        progress(&format!(
            "run-up from rest (RK4, h = {h:.3e} s, at most {budget:.0} steps)"
        ));
        let r = machine.run_up(&Rk4, &opts).map_err(|e| match e {
            tmm::Error::Budget {
                what: "run-up step",
                ..
            } => failure(&e).hint(format!(
                "a run-up may take {budget:.0} steps{}; give a --motor a,b whose moment falls \
                 faster with speed (a larger b), or a smaller --rotor",
                Self::budget_note(budget)
            )),
            // A turn the step cannot resolve: the machine runs far faster than it was sized for.
            tmm::Error::OutOfRange { name, .. } if name.starts_with("step h") => failure(&e).hint(
                "the machine ran far faster than --speed: give --speed near the speed it runs \
                 at, or a motor whose moment falls with speed (--motor a,b with b > 0)",
            ),
            e => f(e),
        })?;
        Ok(RunUpReport {
            motor: (a, b),
            default_motor,
            step: h,
            turns: r
                .turns
                .iter()
                .map(|t| TurnRow {
                    t_start: t.t_start,
                    period: t.period,
                    omega_mean: t.omega_mean,
                    omega_max: t.omega_max,
                    omega_min: t.omega_min,
                    delta: t.delta,
                })
                .collect(),
            steps: r.steps,
            evaluations: r.evaluations,
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            budget: budget as usize,
        })
    }

    /// Refuses a run-up that the step `h` cannot finish within `budget` steps: a turn at
    /// `speed` that needs more (the motor's damping b forces a step far below the turn's),
    /// or a spin-up from rest and two turns at speed that do. The spin-up takes at least
    /// J·|ω|/a — the motor's full starting moment a on the mean reduced moment of inertia J,
    /// with no load and no fall of the moment with speed — so a larger estimate is certainly
    /// too long.
    fn within_budget(
        rows: &[ReducedRow],
        speed: f64,
        (a, b): (f64, f64),
        h: f64,
        budget: f64,
    ) -> Result<(), Failure> {
        let turn = TAU / speed.abs() / h;
        if turn.is_nan() || turn > budget {
            return Err(Failure::new(format!(
                "a turn at {} rad/s takes {} steps of h = {h:.3e} s (the step RK4 needs \
                 for the motor's slope b = {} N·m·s/rad), above the {budget:e} a \
                 run-up may take{}",
                crate::model::typed(speed),
                crate::model::many(turn),
                crate::model::typed(b),
                Self::budget_note(budget)
            ))
            .hint("give --motor a,b with a smaller b, a larger --speed, or a --rotor"));
        }
        // The mean of J_red, each term divided first: 360 rows of a rotor of 10³⁰⁸ kg·m²
        // summed overflow.
        #[allow(clippy::cast_precision_loss)]
        let n = rows.len() as f64;
        let j = rows.iter().map(|r| r.inertia / n).sum::<f64>();
        let spin_up = j * speed.abs() / a;
        // Two turns at speed besides: a steady state is one turn's mean speed against the
        // previous turn's.
        let steps = spin_up / h + 2.0 * turn;
        if steps.is_nan() || steps > budget {
            // Six significant digits: a computed time, not one to type back; past f64's
            // range (a rotor of 10³⁰⁰ kg·m²), its bound.
            let needs = if spin_up.is_finite() {
                let t: f64 = format!("{spin_up:.5e}").parse().unwrap_or(spin_up);
                format!("at least {} s", crate::model::typed(t))
            } else {
                format!("more than {:.1e} s", f64::MAX)
            };
            return Err(Failure::new(format!(
                "the motor's starting moment a = {} N·m needs {needs} to bring the crank \
                 (J_red ≈ {j:.4e} kg·m²) to {} rad/s, and two turns more to see it steady: \
                 {} steps of h = {h:.3e} s, above the {budget:e} a run-up may take{}",
                crate::model::typed(a),
                crate::model::typed(speed),
                crate::model::many(steps),
                Self::budget_note(budget)
            ))
            .hint("give --motor a,b with a larger a, a smaller --rotor, or a lower --speed"));
        }
        Ok(())
    }

    /// Why a budget below [`MAX_RUN_UP_STEPS`] is what it is.
    fn budget_note(budget: f64) -> String {
        if budget < MAX_RUN_UP_STEPS {
            format!(
                " (fewer than {MAX_RUN_UP_STEPS:e} because this linkage's solve is slow: \
                 4 solves a step within a budget of {:e} dyad solves)",
                budget::MAX_WORK
            )
        } else {
            String::new()
        }
    }
}
