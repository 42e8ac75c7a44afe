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
//! - each thread keeps the box it gave back last, with the plan's number (every plan, and
//!   every clone of one, gets its own number when it is made): a loop of one-shot solves on
//!   one thread hands one box from each call to the next with no lock and no atomic
//!   operation. A box given back while the thread holds one of the same plan goes to the
//!   plan's own spares, under a lock that is tried once and never waited on (a thread that
//!   finds it taken allocates, or frees, as if there were no spares), so threads sharing a
//!   plan never block each other;
//! - it keeps little: at most [`KEEP`] boxes per plan, freed with the plan, and one box per
//!   thread (freed when the thread gives back a box of another plan, or ends);
//! - it changes no result: every solve writes whatever it reads (a triad's last pose and the
//!   inputs, the only state a solve reads back, are reset when a box is taken), so a solve
//!   is a pure function of its inputs, as with a reused [`Solver`](super::Solver);
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
use std::cell::Cell;
use std::ops::{Deref, DerefMut};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// The most boxes a plan keeps (a few per thread that makes one-shot solves).
pub(crate) const KEEP: usize = 8;

/// The buffers an analysis adds to the kinematics': loads, reactions, conditioning and
/// balances (each a pointer and a length where its length is fixed, so that an
/// analysis that holds them is small to move). Parked here, in the box, while no [`Analysis`](super::Analysis) holds
/// them (empty until the first analysis of the box).
#[derive(Debug, Clone, Default)]
pub(crate) struct StaticBuffers {
    pub applied: Vec<(usize, Load)>,
    pub acc: Box<[Load]>,
    pub reactions: Box<[Reaction]>,
    pub conditioning: Box<[Conditioning]>,
    /// One per input (two at most).
    pub balances: Box<[Balance]>,
}

/// All the buffers of one position: one heap block.
#[derive(Debug, Clone, Default)]
pub(crate) struct Parts {
    pub kin: KinState,
    pub statics: StaticBuffers,
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
            None => Self(Some(Box::new(Parts {
                kin: KinState::new(chain),
                statics: StaticBuffers::default(),
            }))),
        }
    }

    /// The parked static buffers (empty if there are none), taken out.
    #[inline]
    pub fn unpark(&mut self) -> StaticBuffers {
        match &mut self.0 {
            Some(p) => std::mem::take(&mut p.statics),
            None => StaticBuffers::default(),
        }
    }

    /// Parks static buffers in the box.
    #[inline]
    pub fn park(&mut self, s: StaticBuffers) {
        if let Some(p) = &mut self.0 {
            p.statics = s;
        }
    }
}

/// The number of the next plan made (see [`Spares`]).
static NEXT_PLAN: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// The box this thread gave back last, with its plan's number.
    static LAST: Cell<Option<(u64, Box<Parts>)>> = const { Cell::new(None) };
}

/// A plan's spare boxes (see the module docs), under the plan's number. Not part of what a
/// plan is: a clone starts with none (and a number of its own), two plans compare equal
/// whatever they hold, and a plan's `Debug` does not list them.
pub(crate) struct Spares {
    plan: u64,
    // Boxes, not the parts themselves: a box is handed on whole, its pointer moved.
    #[allow(clippy::vec_box)]
    pool: Mutex<Vec<Box<Parts>>>,
}

impl Default for Spares {
    fn default() -> Self {
        Self {
            plan: NEXT_PLAN.fetch_add(1, Ordering::Relaxed),
            pool: Mutex::default(),
        }
    }
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
    /// A spare box: this thread's last if it is of this plan, else one of the plan's if one
    /// is free.
    #[inline]
    pub fn take(&self) -> Option<Box<Parts>> {
        let mine = LAST
            .try_with(|c| match c.take() {
                Some((plan, p)) if plan == self.plan => Some(p),
                other => {
                    c.set(other);
                    None
                }
            })
            .ok()
            .flatten();
        mine.or_else(|| self.pool.try_lock().ok()?.pop())
    }

    /// Gives back a box: it becomes this thread's last, and the one that was (if of this
    /// plan) goes to the plan's spares, dropped if they are full or busy.
    #[inline]
    pub fn give(&self, p: Box<Parts>) {
        let before = match LAST.try_with(|c| c.replace(Some((self.plan, p)))) {
            Ok(Some((plan, old))) if plan == self.plan => old,
            // Another plan's box (freed here), none, or the thread is ending.
            Ok(_) => return,
            Err(_) => return,
        };
        if let Ok(mut v) = self.pool.try_lock()
            && v.len() < KEEP
        {
            v.push(before);
        }
    }
}
