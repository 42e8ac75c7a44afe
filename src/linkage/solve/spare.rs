//! The buffers of one position of a plan, held in one box, and the plan's spare boxes.
//!
//! Every solve of a position writes into buffers sized for its plan: each link's motion, the
//! groups' determinants, the loads, the reactions (see `KinState` and [`StaticBuffers`]).
//! They live in one heap block, a [`Parts`], held by a [`Held`]: a
//! [`Kinematics`](super::Kinematics) or [`Analysis`](super::Analysis) moves an 8-byte pointer
//! to its buffers, never the buffers, so returning one through a `Result` copies a few words.
//!
//! **The spares.** The one-shot [`Plan::analyse`](crate::linkage::Plan::analyse) and
//! [`Plan::kinematics`](crate::linkage::Plan::kinematics) make a result per call. So that a
//! loop of them allocates nothing after its first call, a result that is dropped gives its
//! box back to its plan ([`Spares`]) and the next one-shot solve of that plan takes it. The
//! design, and what it does not do:
//! - the spares are the plan's own, and nothing else's: no thread keeps a box, nothing is
//!   global. Taking and giving back try the plan's lock once and never wait on it (a thread
//!   that finds it taken allocates, or frees, as if there were no spares), and no other code
//!   runs under it (no user's load function can panic there), so threads sharing a plan
//!   never block each other and the lock is never poisoned;
//! - it keeps little: at most [`KEEP`] boxes per plan, freed with the plan;
//! - it changes no result: every solve writes whatever it reads (a triad's last pose and the
//!   inputs, the only state a solve reads back, are reset when a box is taken), so a solve
//!   is a pure function of its inputs, as with a reused [`Solver`](super::Solver). A result
//!   dropped by a panic's unwinding gives back a box like any other, to be reset alike;
//! - it is no part of what a plan is: a clone of a plan starts with no spares, two plans
//!   compare equal whatever they hold, and a plan's `Debug` does not list them.
//!
//! A reused `plan.solver()` or `plan.cycle` does without the spares: one box for a sweep.

use super::reaction::{Balance, Reaction};
use super::state::KinState;
use crate::kinematics::Motion;
use crate::kinetostatics::Conditioning;
use crate::linkage::plan::Chain;
use crate::Load;
use std::ops::{Deref, DerefMut};
use std::sync::Mutex;

/// The most boxes a plan keeps (one per result alive at once, for a few threads).
pub(crate) const KEEP: usize = 8;

/// The buffers an analysis adds to the kinematics': loads, reactions, conditioning,
/// balances and the joints' friction (each a pointer and a length where its length is fixed,
/// so that an analysis that holds them is small to move). Parked in the box ([`Parts`])
/// while no [`Analysis`](super::Analysis) holds them, so that neither a one-shot analysis
/// nor one of a plan with friction allocates after its first.
#[derive(Debug, Clone, Default)]
pub(crate) struct StaticBuffers {
    pub applied: Vec<(usize, Load)>,
    pub acc: Box<[Load]>,
    pub reactions: Box<[Reaction]>,
    pub conditioning: Box<[Conditioning]>,
    /// One per input (two at most).
    pub balances: Box<[Balance]>,
    /// The joints' friction (empty for a frictionless plan).
    pub friction: super::friction::FrictionState,
}

/// All the buffers of one position: one heap block.
#[derive(Debug, Clone, Default)]
pub(crate) struct Parts {
    pub kin: KinState,
    /// `None` while an analysis holds them, or before the box's first analysis (taking
    /// them out, or putting them back, writes one word besides the buffers themselves).
    pub statics: Option<StaticBuffers>,
}

/// One position's buffers (a box of [`Parts`]), read as its `KinState`. The box is taken out
/// only when its holder is dropped (to go back to the plan's spares).
#[derive(Debug, Clone)]
pub(crate) struct Held(pub Option<Box<Parts>>);

/// What a [`Held`] whose box was taken reads as (never read: only a holder being dropped
/// has no box).
static NONE: KinState = KinState {
    input: Motion {
        value: 0.0,
        rate: 0.0,
        accel: 0.0,
    },
    second_input: None,
    links: Vec::new(),
    units: Vec::new(),
    turns: Vec::new(),
    dets: Vec::new(),
    triads: Vec::new(),
    general_work: Vec::new(),
};

impl Deref for Held {
    type Target = KinState;

    #[inline]
    fn deref(&self) -> &KinState {
        match &self.0 {
            Some(p) => &p.kin,
            None => &NONE,
        }
    }
}

impl DerefMut for Held {
    #[inline]
    fn deref_mut(&mut self) -> &mut KinState {
        &mut self.0.get_or_insert_with(Box::default).kin
    }
}

impl Held {
    /// The buffers of a position of `chain`: a spare box of `spares` (reset, see the module
    /// docs) or a new one.
    #[inline]
    pub fn of(chain: &Chain, spares: &Spares) -> Self {
        match spares.take() {
            Some(mut p) => {
                let k = &mut p.kin;
                k.input = Motion::default();
                k.second_input = None;
                k.triads.fill(None);
                Self(Some(p))
            }
            None => Self::fresh(chain),
        }
    }

    /// New buffers for `chain` (kept out of line: a loop of one-shot solves makes them once).
    #[cold]
    #[inline(never)]
    pub fn fresh(chain: &Chain) -> Self {
        Self(Some(Box::new(Parts {
            kin: KinState::new(chain),
            statics: None,
        })))
    }

    /// The parked static buffers, taken out (`None` if the box has none yet).
    #[inline]
    pub fn unpark(&mut self) -> Option<StaticBuffers> {
        self.0.as_mut()?.statics.take()
    }
}

/// A plan's spare boxes (see the module docs). Not part of what a plan is: a clone starts
/// with none, two plans compare equal whatever they hold, and a plan's `Debug` does not list
/// them. Aligned to a cache line pair of its own: threads that make one-shot solves of one
/// plan write its lock, which must not share a line with the plan data every solve reads.
#[derive(Default)]
#[repr(align(128))]
pub(crate) struct Spares {
    // Boxes, not the parts themselves: a box is handed on whole, its pointer moved.
    #[allow(clippy::vec_box)]
    pool: Mutex<Vec<Box<Parts>>>,
}

impl std::fmt::Debug for Spares {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Spares")
    }
}

impl Clone for Spares {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl PartialEq for Spares {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Spares {
    /// A spare box of the plan's, if one is free (the lock tried once).
    #[inline]
    pub fn take(&self) -> Option<Box<Parts>> {
        self.pool.try_lock().ok()?.pop()
    }

    /// Gives back a box to the plan's spares; freed (after the lock is let go) if they are
    /// full or busy.
    #[inline]
    pub fn give(&self, p: Box<Parts>) {
        if let Ok(mut v) = self.pool.try_lock()
            && v.len() < KEEP
        {
            v.push(p);
        }
    }
}
