//! Coordinates held at rest by their resistances: the equations with a held coordinate's row
//! replaced by q̈ₖ = 0, and the argument whose zero releases it.
//!
//! # The held motion
//! Where switch i's speed σᵢ = cₖ·q̇ₖ reaches zero and its resistance holds
//! ([`SwitchLoads::holds`]), the run sets q̇ₖ = 0 and goes on with q̈ₖ = 0: Lagrange's
//! equations with the reaction μₖ that holds the coordinate,
//!
//! ```text
//! A·q̈ = Q − c(q, q̇) − ∇Π − B·q̇ + μₖ·eₖ,      q̈ₖ = 0,
//! ```
//!
//! are, for the free coordinate j, A_jj·q̈_j = (Q − c − ∇Π − B·q̇)_j (A_jk·q̈ₖ vanishes), and
//! μₖ = A_kj·q̈_j − (Q − c − ∇Π − B·q̇)ₖ. With q̇ₖ = 0 the Christoffel terms reduce to
//! c_j = ½·∂A_jj/∂q_j·q̇_j² and cₖ = (∂A_kj/∂q_j − ½·∂A_jj/∂qₖ)·q̇_j². [`decoupled`] hands the
//! integrators terms whose accelerations are exactly these: A with its off-diagonal entries
//! zeroed (positive-definite, since A_jj > 0 and A_kk > 0), row k of Q, ∇Π, B and of the
//! Christoffel symbols zeroed (∂A/∂qₖ and ∂A_kj/∂q_j set to zero leave Γ_jjj =
//! ½·∂A_jj/∂q_j and make every Γ_kab zero). Then q̈ₖ is an exact zero (its numerator is
//! a sum of products with exact zeros), q̇ₖ stays exactly zero through every stage of any
//! explicit method, and the free row is unchanged. The energy and powers a row records are
//! the motion's: ½·q̇ᵀ·A·q̇ = ½·A_jj·q̇_j² and Q·q̇ = Q_j·q̇_j when q̇ₖ = 0, and the
//! reaction does no work.
//!
//! # The release
//! The resistance holds while the drive along σᵢ of the held motion lies within its
//! breakaway loads, −backward ≤ drive ≤ forward ([`SwitchLoads`], which the system
//! evaluates with the coordinate held). The release argument [`excess`] =
//! max(drive − forward, −drive − backward) is ≤ 0 exactly while it holds, and continuous in
//! the state: the run locates its zero crossing inside the step like a switch speed's, and
//! the coordinate breaks away there in the drive's direction, its q̈ₖ starting from zero
//! (the drive equals the breakaway load there).

use std::cell::Cell;

use nalgebra::Matrix2;

use crate::dynamics::switch::SwitchLoads;
use crate::dynamics::system::{LagrangeSystem, LagrangeTerms};

/// The release argument of a held switch: max(drive − forward, −drive − backward), ≤ 0
/// exactly while the resistance holds (see the [module docs](self)).
pub(super) fn excess(l: &SwitchLoads) -> f64 {
    (l.drive - l.forward).max(-l.drive - l.backward)
}

/// The value of a release argument while its coordinate is not held: below the node 0, so
/// that it crosses nothing.
pub(super) const NOT_HELD: f64 = -1.0;

/// The terms whose accelerations are those of the motion with the coordinates `held` at
/// rest (see the [module docs](self)): the held rows of Q, ∇Π, B and of the Christoffel
/// symbols zeroed, A's off-diagonal entries zeroed.
pub(super) fn decoupled(mut t: LagrangeTerms, held: [bool; 2]) -> LagrangeTerms {
    for (k, _) in held.iter().enumerate().filter(|&(_, &h)| h) {
        let j = 1 - k;
        t.inertia[(k, j)] = 0.0;
        t.inertia[(j, k)] = 0.0;
        t.inertia_derivatives[k] = Matrix2::zeros();
        t.inertia_derivatives[j][(k, j)] = 0.0;
        t.inertia_derivatives[j][(j, k)] = 0.0;
        t.forces[k] = 0.0;
        t.potential_gradient[k] = 0.0;
        t.damping[(k, 0)] = 0.0;
        t.damping[(k, 1)] = 0.0;
    }
    t
}

/// What the run and the system it steps share about held coordinates: which switches can
/// hold a coordinate, which are held now.
pub(super) struct Hold {
    /// The switches that can hold a coordinate, with it ([`LagrangeSystem::switch_holds`]),
    /// in switch order: their release arguments follow the system's switch speeds.
    pub(super) holdable: Vec<(usize, usize)>,
    /// Which switch holds each coordinate now (`None`: free).
    by: Cell<[Option<usize>; 2]>,
}

impl Hold {
    /// The holds of `sys`: `None` when no switch can hold a coordinate (then nothing of the
    /// run changes).
    pub(super) fn of<S: LagrangeSystem + ?Sized>(sys: &S) -> Option<Self> {
        let holdable: Vec<(usize, usize)> = (0..sys.switches())
            .filter_map(|i| sys.switch_holds(i).filter(|&k| k < 2).map(|k| (i, k)))
            .collect();
        (!holdable.is_empty()).then(|| Self {
            holdable,
            by: Cell::new([None; 2]),
        })
    }

    /// The coordinate switch `i` holds, if it can.
    pub(super) fn coordinate(&self, i: usize) -> Option<usize> {
        self.holdable.iter().find(|h| h.0 == i).map(|h| h.1)
    }

    /// Which coordinates are held.
    pub(super) fn held(&self) -> [bool; 2] {
        self.by.get().map(|b| b.is_some())
    }

    /// Whether switch `i` holds coordinate `k` now.
    pub(super) fn holds(&self, i: usize, k: usize) -> bool {
        self.by.get()[k] == Some(i)
    }

    /// Holds coordinate `k` by switch `i`, or frees it (`None`).
    pub(super) fn set(&self, k: usize, by: Option<usize>) {
        let mut b = self.by.get();
        b[k] = by;
        self.by.set(b);
    }
}
