//! The dynamics of a described linkage: its equation of motion from the engine's exact
//! transfer functions, the run-up under a motor to the steady state, the coefficient of speed
//! fluctuation, and the flywheel for a required one.
//!
//! # The equation of motion
//! With the inputs' coordinates q (one or two: crank angles or slides), every point of the
//! linkage moves with v_P = Σ_k u_P,k(q)·q̇_k and every link turns with ω = Σ_k w_k(q)·q̇_k,
//! where the first-order transfer functions u_P,k = ∂r_P/∂q_k and w_k = ∂φ/∂q_k are the
//! velocities of a kinematic solve at q̇ = e_k (unit rate of input k, the others still) and
//! q̈ = 0. The same solve's accelerations are the second-order transfer functions
//! ∂²r_P/∂q_k², ∂²φ/∂q_k², because a = Σ_jk ∂²r/∂q_j∂q_k·q̇_j·q̇_k + Σ_k u_k·q̈_k; a solve at
//! q̇ = (1, 1) gives the mixed one as (a₁₁ + 2a₁₂ + a₂₂ − a₁₁ − a₂₂)/2. No finite differences:
//! the transfer functions are the closed forms of the groups' velocity and acceleration
//! analysis. Then, with link masses m and central moments of inertia J_S,
//!
//! ```text
//! T = ½ q̇ᵀ A(q) q̇,   A_ik = Σ_links (m·u_S,i·u_S,k + J_S·w_i·w_k) + J_add,i·δ_ik
//! ∂A_ik/∂q_s = Σ_links m·(∂u_S,i/∂q_s·u_S,k + u_S,i·∂u_S,k/∂q_s) + J_S·(∂w_i/∂q_s·w_k + w_i·∂w_k/∂q_s)
//! Q_k = Σ_loads (F·u_P,k + M·w_k) + Σ_links m·g·u_S,k + M_motor,k(q_k, q̇_k)
//! B_ik = Σ_dampers c·r_i·r_k      (Φ = ½ c·ṙ², ṙ = Σ r_k q̇_k)
//! ```
//!
//! (the principle of virtual work for Q: the power of every load is Σ_k Q_k·q̇_k), and
//! Lagrange's equations A·q̈ + c(q, q̇) + B·q̇ = Q ([`crate::dynamics::accelerations`]) are
//! integrated by any of the crate's [`Stepper`](crate::dynamics::Stepper)s. With one input
//! this is the textbook's machine reduced to its crank: J_red(φ)·ε + ½·J_red′(φ)·ω² = M_red,
//! J_red = A₁₁, M_red = Q₁ ([`LinkageSystem::reduced`]). Gravity is one of the loads (not a
//! potential): the work of all loads W = ∫ Q·q̇ dt is the change of T.
//!
//! A load that depends on the motion (a resistance on the working stroke only, an indicator
//! diagram's compression and expansion branches, a function added by
//! [`Plan::add_load_fn`](crate::linkage::Plan::add_load_fn)) is evaluated at the state's
//! actual rates; it must not depend on the accelerations, which the equation is solved for.
//!
//! # Friction in the joints
//! A linkage described with Coulomb friction ([`Friction`](crate::linkage::Friction), see
//! [`kinetostatics::friction`](crate::kinetostatics::friction)) has the generalized friction
//! forces Q_f,k = −Σ_j |L_j|·sgn(ṙ_j)·∂ṙ_j/∂q̇_k ([`Terms::friction`]): L_j the friction
//! couple ρ·|R_j| of a hinge (or force f·|N_j| of a slide), ṙ_j the joint's relative rate,
//! so that Q_f·q̇ = −Σ P_lost. The reactions hold the inertia loads, affine in q̈
//! (R = R₀ + R₁·q̈ for one input without friction; with friction, the friction statics at
//! (q, q̇, q̈)), so the equation of motion A·q̈ = b + Q_f(q̈), b = Q − c − B·q̇, is solved for
//! q̈ at every evaluation: the fixed point q̈ = A⁻¹(b + Q_f(q̈)) from the frictionless q̈, by
//! the secant method for one input and Newton's method (Broyden's update) for two, until the fixed-point
//! residual is at most [`FRICTION_TOLERANCE`] of the acceleration scale, within
//! [`FRICTION_BUDGET`] friction solves (else an error: the friction's feedback on q̈ reaches
//! the inertia, the motion self-locks). The Q_f of the solution is the one returned, so
//! every integrator steps the motion with friction unchanged. The inverse dynamics takes Q_f
//! at the given q̈ directly.
//!
//! At rest there is no friction; a linkage of one input weighs its rest against the
//! friction's breakaway loads through the input's velocity-sign switch
//! ([`LagrangeSystem::switch_loads`](crate::dynamics::LagrangeSystem::switch_loads)), and
//! each joint's relative rate is a kink argument with the node 0
//! ([`LagrangeSystem::kinks`](crate::dynamics::LagrangeSystem::kinks)): where it reverses
//! the friction couple flips, and a run steps exactly onto it. The reactions see the
//! description's loads, the weights, the inertia loads and the drive on the input link; a
//! [`Damper`] between two other links acts through B only (its forces are not in the
//! joints' pressures). Without friction (every coefficient zero) nothing of this is
//! evaluated: the terms are the frictionless ones, bit for bit.
//!
//! ```
//! use nalgebra::Vector2;
//! use tmm::dynamics::accelerations;
//! use tmm::kinematics::Motion;
//! use tmm::linkage::{bundled, dynamics::LinkageSystem, Friction};
//! let mut l = bundled::four_bar();
//! l.friction = Some(Friction::pin(0.15, 0.01));
//! let sys = LinkageSystem::from_linkage(&l)?;
//! let (q, qd) = (Vector2::new(0.8, 0.0), Vector2::new(10.0, 0.0));
//! let t = sys.split_terms(&q, &qd)?;
//! let qdd = accelerations(&sys, 0.0, &q, &qd)?;
//! // The friction kinetostatics of that motion: no drive needed, and the same lost power.
//! let a = sys.plan().analyse(Motion::new(q[0], qd[0], qdd[0]))?;
//! assert!(a.balance(0)?.value.abs() < 1e-9);
//! assert!((t.friction.dot(&qd) + a.lost_power()).abs() < 1e-9 * a.lost_power());
//! # Ok::<(), tmm::Error>(())
//! ```
//!
//! # Cost
//! [`LinkageSystem::split_terms`] makes one set of buffers and one kinematic solve for a linkage
//! with one input. Two inputs need the rates at q̇ = e₁, e₂ and (1, 1) (the three
//! second-order transfer functions need three quadratic forms): the positions are solved
//! once, and for e₂ and (1, 1) only the groups' velocity and acceleration problems, which are
//! linear with the matrix of the position already solved (a few dot products per group, no
//! square root or `atan2`). Then it sums over the links and loads. The bench
//! `linkage_dynamics` (benches/) prints the ratio to one kinematic position of the same linkage
//! measured side by side: 1.44× for the four-bar, 1.35× for the Watt six-bar, 1.60× for the
//! compressor and 1.80× for the five-bar robot (3.2× when each rate vector re-solved the
//! positions). A [`LagrangeSystem`](crate::dynamics::LagrangeSystem) evaluation of the
//! accelerations asks for every part at once ([`LagrangeSystem::terms`](
//! crate::dynamics::LagrangeSystem::terms)): one such build per right-hand side.
//!
//! # Steady state, speed fluctuation
//! [`LinkageSystem::run_up`] starts the machine from rest and integrates it turn by turn;
//! the steady state is reached when the mean speed of a turn, ω_m = 2π/T_turn, differs from
//! the previous turn's by less than a relative tolerance. The coefficient of speed
//! fluctuation of a turn is δ = (ω_max − ω_min)/ω_m ([`Turn`]) with the textbook's
//! ω_m = (ω_max + ω_min)/2 (the time mean 2π/T_turn may differ from it by up to δ/2,
//! relative: by a first-order amount, which would blur a check of δ to a few per cent).
//!
//! # The flywheel (energy–mass method of Wittenbauer)
//! The textbook problem: a constant driving moment M_d balances the loads over a turn,
//! M_d = −(1/2π)∮ M_red dφ (the loads taken at the mean speed), and the work
//! W(φ) = ∫_φ₀^φ (M_d + M_red) dφ is periodic. With a flywheel J_F on the crank the energy
//! equation is exact:
//!
//! ```text
//! ½ (J_F + J_red(φ))·ω(φ)² = E₀ + W(φ).
//! ```
//!
//! Wanted: ω_max = ω_m(1 + δ/2), ω_min = ω_m(1 − δ/2), so that (ω_max − ω_min)/ω_m = δ with
//! ω_m = (ω_max + ω_min)/2. With ψ± = ½ω²_max,min the condition ω(φ)² ≤ ω²_max for every φ,
//! with equality somewhere, reads E₀ − ψ₊·J_F = min_φ (ψ₊·J_red − W), and ω(φ)² ≥ ω²_min
//! reads E₀ − ψ₋·J_F = max_φ (ψ₋·J_red − W). Subtracting (in Wittenbauer's diagram of W
//! against J_red: the two tangents of slopes ψ₊ and ψ₋ meet at (−J_F, −E₀)):
//!
//! ```text
//! J_F = [ max_φ(ψ₋·J_red(φ) − W(φ)) − min_φ(ψ₊·J_red(φ) − W(φ)) ] / (ψ₊ − ψ₋),
//! E₀  = min_φ(ψ₊·J_red − W) + ψ₊·J_F,   ω(φ₀) = √(2E₀/(J_F + J_red(φ₀))).
//! ```
//!
//! The textbook's simplified formula linearises the same equation about ω_m, taking the
//! links' own energy at the mean speed and J_F + J_red(φ) ≈ J_F + J̄ (J̄ the mean of J_red):
//! 2δ·ω_m² = ω²_max − ω²_min ≈ 2·ΔE/(J_F + J̄), with ΔE the range over the turn of
//! W(φ) − ½·J_red(φ)·ω_m², so
//!
//! ```text
//! J_F ≈ ΔE/(δ·ω_m²) − J̄.
//! ```
//!
//! Both are in [`Flywheel`] ([`LinkageSystem::flywheel`]); the simplified one errs by terms
//! of order δ and by the variation of J_red against J_F.
//!
//! # Example
//! The bundled four-bar under a motor of 50 N·m at rest falling to zero at 30 rad/s, with a
//! flywheel of 0.05 kg·m²: from rest to its steady state.
//! ```
//! use tmm::dynamics::{machines::LinearMotor, Rk4};
//! use tmm::linkage::{bundled, dynamics::{LinkageSystem, Motor, RunUpOptions}};
//! let mut l = bundled::four_bar();
//! l.loads.retain(|x| !matches!(x, tmm::linkage::LoadSpec::Resistance { .. }));
//! let sys = LinkageSystem::from_linkage(&l)?
//!     .with_motor(0, Motor::Linear(LinearMotor { a: 50.0, b: 50.0 / 30.0 }))?
//!     .with_inertia(0, 0.05)?;
//! let r = sys.run_up(&Rk4, &RunUpOptions::new(1e-3))?;
//! let steady = r.turns.last().unwrap();
//! assert!(steady.omega_mean > 25.0 && steady.omega_mean < 30.0);
//! assert!(steady.delta > 0.0 && steady.omega_min > 0.0);
//! # Ok::<(), tmm::Error>(())
//! ```

mod cycle;
mod drive;
mod flywheel;
mod friction;
mod stops;
mod system;
mod transfer;

pub use cycle::{Reduced, RunUp, RunUpOptions, Turn, MIN_STEPS_PER_TURN};
pub use drive::{Damper, Motor};
pub use flywheel::Flywheel;
pub use friction::{FRICTION_BUDGET, FRICTION_TOLERANCE};
pub use system::{LinkageSystem, Terms};
