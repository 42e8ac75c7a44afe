//! What drives an input and what damps the motion: motor characteristics and viscous
//! dampers (Rayleigh's dissipation function).

use crate::dynamics::machines::{LinearMotor, Servo};
use crate::dynamics::Table;
use crate::error::{finite, Error, Result};

/// The mechanical characteristic of the motor on one input: the generalized driving force
/// it applies (a moment on a crank, N·m; a force along the guide of a slider, N) as a function
/// of the input coordinate q and its rate q̇.
///
/// A motor turning the crank clockwise has a negative characteristic: for example
/// `Linear(LinearMotor { a: -a0, b })` gives M = −a0 − b·ω, which vanishes at ω = −a0/b.
///
/// # Examples
/// ```
/// use tmm::dynamics::machines::LinearMotor;
/// use tmm::dynamics::{Beyond, Table};
/// use tmm::linkage::dynamics::Motor;
/// let linear = Motor::Linear(LinearMotor { a: 60.0, b: 0.5 });
/// assert_eq!(linear.moment(0.0, 100.0)?, 10.0);
/// let table = Table::new(vec![0.0, 100.0, 120.0], vec![50.0, 20.0, 0.0], Beyond::Error)?;
/// assert_eq!(Motor::Tabulated(table).moment(0.0, 110.0)?, 10.0);
/// assert_eq!(Motor::Constant(7.0).moment(3.0, -1.0)?, 7.0);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Motor {
    /// No motor: the input is free (a machine coasting, or one driven by its loads).
    #[default]
    None,
    /// A constant driving moment (or force), the textbook's model of the flywheel problem.
    Constant(f64),
    /// The linear characteristic M = a − b·q̇ of an induction motor's working branch.
    Linear(LinearMotor),
    /// A tabulated characteristic M(q̇), interpolated linearly (outside the table as the
    /// table's [`Beyond`](crate::dynamics::Beyond) rule says).
    Tabulated(Table),
    /// A position servo M = clamp(k_p·(target − q) − k_d·q̇, ±limit).
    Servo(Servo),
}

impl Motor {
    /// The driving moment (or force) at the input coordinate `q` and rate `qd`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite argument or coefficient; the table's
    /// [`Error::OutOfRange`] outside a [`Beyond::Error`](crate::dynamics::Beyond::Error)
    /// table; [`Error::Overflow`] when the moment overflows.
    pub fn moment(&self, q: f64, qd: f64) -> Result<f64> {
        finite("input coordinate", q)?;
        finite("input rate", qd)?;
        match self {
            Self::None => Ok(0.0),
            Self::Constant(m) => finite("constant driving moment", *m),
            Self::Linear(m) => m.torque(qd),
            Self::Tabulated(t) => t.at(qd),
            Self::Servo(s) => s.torque(q, qd),
        }
    }

    /// Checks the motor's data (finite coefficients).
    ///
    /// # Errors
    /// [`Error::NonFinite`] naming the coefficient.
    pub fn check(&self) -> Result<()> {
        match self {
            Self::None | Self::Tabulated(_) => Ok(()),
            Self::Constant(m) => finite("constant driving moment", *m).map(|_| ()),
            Self::Linear(m) => m.check(),
            Self::Servo(s) => s.check(),
        }
    }
}

/// A viscous damper: a term of Rayleigh's dissipation function Φ = ½·c·r², where r is the
/// rate it resists; its generalized forces are −∂Φ/∂q̇ = −B·q̇ with B = Σ c·(∂r/∂q̇)(∂r/∂q̇)ᵀ.
///
/// # Examples
/// A damper of 2 N·m·s/rad on the four-bar's crank bearing: B₁₁ = c·(∂ω/∂q̇)² = 2.
/// ```
/// use nalgebra::Vector2;
/// use tmm::linkage::{bundled, dynamics::{Damper, LinkageSystem}};
/// let sys = LinkageSystem::from_linkage(&bundled::four_bar())?
///     .with_damper(&Damper::Link { link: "crank".into(), c: 2.0 })?;
/// let b = sys.split_terms(&Vector2::new(0.3, 0.0), &Vector2::zeros())?.damping;
/// assert!((b[(0, 0)] - 2.0).abs() < 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Damper {
    /// On a link's absolute angular velocity ω (bearing friction against the frame, air
    /// drag), c in N·m·s/rad.
    Link {
        /// The link's name.
        link: String,
        /// The coefficient c ≥ 0.
        c: f64,
    },
    /// On a joint's relative rate: the relative angular velocity of its two links (revolute,
    /// c in N·m·s/rad) or the slide rate (prismatic, c in N·s/m).
    Joint {
        /// The joint's name.
        joint: String,
        /// The coefficient c ≥ 0.
        c: f64,
    },
}

/// A damper resolved against a plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum DamperPlan {
    Link { link: usize, c: f64 },
    Hinge { links: [usize; 2], c: f64 },
    Slide { joint: usize, c: f64 },
}

impl Damper {
    pub(crate) fn resolve(&self, plan: &crate::linkage::Plan) -> Result<DamperPlan> {
        let c = match self {
            Self::Link { c, .. } | Self::Joint { c, .. } => *c,
        };
        if !(c.is_finite() && c >= 0.0) {
            return Err(Error::Description {
                item: "damper".to_owned(),
                problem: format!("its coefficient c must be finite and ≥ 0, got {c}"),
            });
        }
        Ok(match self {
            Self::Link { link, .. } => DamperPlan::Link {
                link: plan.chain.link(link)?,
                c,
            },
            Self::Joint { joint, .. } => {
                let j = plan.chain.joint(joint)?;
                if plan.is_prismatic_at(j) {
                    DamperPlan::Slide { joint: j, c }
                } else {
                    DamperPlan::Hinge {
                        links: plan.joint_links_at(j),
                        c,
                    }
                }
            }
        })
    }
}
