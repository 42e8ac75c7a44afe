//! Any linkage of the 2nd class as data: one engine for its kinematics, loads, reactions and
//! balancing moment.
//!
//! The engine works in three steps:
//! 1. a **description** ([`Linkage`]): plain data a person writes, in Rust or as a JSON file
//!    (feature `serde`, `Linkage::from_json`; the format is in `docs/linkage-format.md`) — joints
//!    with their coordinates in a reference pose, links as sets of joints and named points,
//!    the input and its drive, masses and loads;
//! 2. a **plan** ([`Plan::new`]), made once: the structure (the mobility by Chebyshev's
//!    formula, the Assur dyads of the 2nd class in attachment order — all five kinds, RRR,
//!    RRP, RPR, PRP and RPP), every length and local
//!    coordinate read off the reference pose, the assembly mode of every group, the loads.
//!    Whatever is wrong with a description is found here, and the error names the joint,
//!    link, load or field;
//! 3. a **solve** per position: [`Plan::analyse`] (one position, the one-shot convenience),
//!    a [`Solver`] from [`Plan::solver`] (its buffers reused at every position: the fast path),
//!    [`Plan::cycle`] (a cycle through one solver), or [`Plan::kinematics`] (the kinematics
//!    alone, a [`Kinematics`] with no reactions to ask for). One input's motion is a
//!    [`Motion`](crate::kinematics::Motion), two are [`Inputs::two`]. The solve runs
//!    kinematics group by group in attachment order, the loads, the reactions from the last
//!    group back to the input link, and the balancing moment (crank through a coupling), the
//!    balancing force of a gear pair, or the driving force of a slider. Every result can be
//!    checked by the principle of virtual power ([`Analysis::power_check`]) and every link's
//!    equilibrium ([`Analysis::worst_residual`]).
//!
//! Conventions: angles of links are measured along each link's declared reference direction
//! (default: its first joint to its second); the reaction in a joint is the force of one of
//! its links on the other ([`Reaction`], R_by,on); a prismatic joint's slide is the sliding
//! link's displacement along the guide from the reference pose. A joint, link or point is
//! named by its name or by its handle ([`JointId`], [`LinkId`], [`PointId`]): resolve a name
//! once with [`Plan::joint_id`] and read by handle in a loop.
//!
//! # Example
//! The bundled Watt I six-bar, its balancing moment over a turn, each position checked:
//! ```
//! use tmm::linkage::{bundled, Plan};
//! use tmm::kinematics::Motion;
//! let plan = Plan::new(&bundled::watt_six_bar())?;
//! assert_eq!(plan.groups().len(), 2);
//! let mut solver = plan.solver();
//! for k in 0..12 {
//!     let phi = plan.reference_input() + k as f64 * std::f64::consts::PI / 6.0;
//!     let a = solver.analyse(Motion::turning(phi, 10.0))?;
//!     assert!(a.power_check()?.relative_error() < 1e-9);
//!     assert!(a.worst_residual() < 1e-12);
//! }
//! # Ok::<(), tmm::Error>(())
//! ```

mod build;
pub mod bundled;
mod contour;
mod course;
mod course_two;
mod cycle;
mod defaults;
mod description;
pub mod dynamics;
mod handle;
mod hinges;
mod indicator;
pub(crate) mod inputs;
mod instant_centres;
mod modes;
mod modes_reduction;
mod plan;
mod plan_general;
mod plan_triad;
pub(crate) mod solve;
mod springs;
mod structure;
mod structure_triad;
mod table;
mod torsion_range;
mod track;
mod workspace;
mod workspace_boundary;
mod workspace_reach;

pub use course::{Course, Sweep};
pub use course_two::{AnyCourse, Assembly, AssemblyFailure, TwoInputCourse, TwoInputShape};
#[cfg(feature = "rayon")]
pub use cycle::run_cycle_parallel;
pub use cycle::{course_inputs, run_cycle, try_course_inputs, try_uniform_inputs, uniform_inputs};
pub use defaults::DEFAULT_SPEED;
pub use description::{
    Anchor, At, Drive, Friction, Input, Joint, JointKind, Link, Linkage, LoadSpec, Mass, Mode,
    NamedPoint, Output,
};
pub use handle::{JointId, JointRef, LinkId, LinkRef, PointId, PointRef};
pub use indicator::IndicatorDiagram;
pub use inputs::{Inputs, MAX_INPUT_COORDINATE};
pub use instant_centres::{Centre, Found, InstantCentre};
pub use modes::{
    AllModes, GroupModes, LinkageMode, ModeOptions, ModeSearch, MULTISTART_SOLVES_PER_START,
};
pub use plan::{Group, GroupKind, Plan, Pose};
pub use solve::{
    Analysis, Balance, Kinematics, Position, PowerCheck, Reaction, Solver, DEAD_CENTRE_DETERMINANT,
    DEAD_POINT_RELATIVE_ERROR,
};
pub use structure::chebyshev;
pub use table::{Cells, Column, Table, Tabulate};
pub use track::{Crossing, Track};
pub use workspace::{Region, SingularCurve, Singularity, Workspace, WorkspaceOptions};
