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
//!   global. The box given back last is taken and given back by one atomic exchange each
//!   (a loop of one-shot solves needs no more); the others wait in a pool behind a lock
//!   (see [`Spares`]) tried once and never waited on (a thread that finds it held
//!   allocates, or frees, as if there were no spares), and no other code runs under it (no
//!   user's load function can panic there), so threads sharing a plan never block each
//!   other;
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
use crossbeam_utils::atomic::AtomicCell;
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
    /// The static buffers while no analysis holds them (empty while one does, or before the
    /// box's first analysis). An analysis swaps them with its own fields one by one, a
    /// pointer and a length each: moved as one struct through the stack, they were read back
    /// in wider words than they were written, and each such read waited for the writes to
    /// reach the cache (a stalled store forwarding, perf: half of the one-shot's own time).
    pub statics: StaticBuffers,
    /// Whether `statics` holds an analysis's buffers.
    pub parked: bool,
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
    twin_sides: Vec::new(),
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
    #[inline(always)]
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
            statics: StaticBuffers::default(),
            parked: false,
        })))
    }
}

/// A plan's spare boxes (see the module docs). Not part of what a plan is: a clone starts
/// with none, two plans compare equal whatever they hold, and a plan's `Debug` does not list
/// them. Aligned to a cache line pair of its own: threads that make one-shot solves of one
/// plan write its cell and lock, which must not share a line with the plan data every solve
/// reads.
///
/// **No lock on the way of a loop.** The box given back last sits in an `AtomicCell`
/// (crossbeam-utils: safe code here, one `xchg` to take it and one to give it back), and a
/// loop of one-shot solves, one result alive at a time, never goes further. Only a box given
/// back while that cell is full (several results alive at once) goes to the pool, a `Mutex`
/// tried once (`try_lock`) and never waited on. With the `Mutex` alone a one-shot solve made
/// four locked read-modify-writes (two to take, two to give back) and two checks of the
/// thread's panic state: 0.07–0.13 of a four-bar position (docs/performance.md).
#[derive(Default)]
#[repr(align(128))]
pub(crate) struct Spares {
    /// The box given back last, taken and given back by one atomic exchange each (no lock):
    /// a loop of one-shot solves, one result alive at a time, never reaches the pool.
    last: AtomicCell<Option<Box<Parts>>>,
    pool: Mutex<Pool>,
}

// The cell holds a pointer (`None` is null), exchanged by one atomic instruction: never
// through crossbeam's fallback of global locks.
const _: () = assert!(AtomicCell::<Option<Box<Parts>>>::is_lock_free());

/// The boxes beyond `last`, a stack of at most [`KEEP`] − 1 (a fixed array: nothing is
/// allocated, nothing can fail, while the lock is held).
#[derive(Default)]
struct Pool {
    boxes: [Option<Box<Parts>>; KEEP - 1],
    len: usize,
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
    /// Runs `f` on the pool if no other thread holds it (tried once, never waited on);
    /// `None` if one does.
    #[inline(always)]
    fn with<R>(&self, f: impl FnOnce(&mut Pool) -> R) -> Option<R> {
        // A poisoned lock cannot happen (nothing that can panic runs under it), and would
        // only leave the spares unused.
        self.pool.try_lock().ok().map(|mut pool| f(&mut pool))
    }

    /// A spare box of the plan's: the one given back last (one atomic exchange), else one
    /// of the pool if one is free and no other thread holds it.
    #[inline(always)]
    pub fn take(&self) -> Option<Box<Parts>> {
        match self.last.take() {
            Some(b) => Some(b),
            None => self.take_pooled(),
        }
    }

    /// A box of the pool (kept out of line: a loop of one-shot solves never comes here).
    #[cold]
    #[inline(never)]
    fn take_pooled(&self) -> Option<Box<Parts>> {
        self.with(|p| {
            let last = p.len.checked_sub(1)?;
            p.len = last;
            p.boxes.get_mut(last)?.take()
        })
        .flatten()
    }

    /// Gives back a box to the plan's spares: it becomes the one given back last (one atomic
    /// exchange), and the box that was there, if any, goes to the pool; freed (after the
    /// lock is let go) if the pool is full or busy.
    #[inline(always)]
    pub fn give(&self, b: Box<Parts>) {
        if let Some(older) = self.last.swap(Some(b)) {
            self.pool_or_free(older);
        }
    }

    /// Puts `b` in the pool, or frees it if the pool is full or busy.
    #[cold]
    #[inline(never)]
    fn pool_or_free(&self, b: Box<Parts>) {
        let mut b = Some(b);
        self.with(|p| {
            if let Some(slot) = p.boxes.get_mut(p.len) {
                *slot = b.take();
                p.len += 1;
            }
        });
        drop(b);
    }
}

#[cfg(test)]
mod tests {
    use super::{Parts, Spares, KEEP};

    /// Threads taking and giving back boxes of one plan's spares never hold one box at
    /// once: each marks the box it took with its own number, yields, and finds its mark
    /// unchanged before giving the box back. A lock that let two threads in would let one
    /// overwrite the other's mark (or both pop the same slot, one box held twice).
    #[test]
    fn a_box_is_held_by_one_thread_at_a_time() {
        let spares = Spares::default();
        for _ in 0..KEEP {
            spares.give(Box::default());
        }
        let threads = 4;
        let (taken, missed) = std::thread::scope(|s| {
            let handles: Vec<_> = (0..threads)
                .map(|t| {
                    let spares = &spares;
                    s.spawn(move || {
                        let (mut taken, mut missed) = (0u32, 0u32);
                        for k in 0..20_000u32 {
                            let Some(mut b) = spares.take() else {
                                missed += 1;
                                std::hint::spin_loop();
                                continue;
                            };
                            let mark = f64::from(t * 1_000_000 + k % 1_000_000);
                            b.kin.input.value = mark;
                            if k % 64 == 0 {
                                std::thread::yield_now();
                            }
                            assert_eq!(b.kin.input.value, mark, "thread {t}: box shared");
                            spares.give(b);
                            taken += 1;
                        }
                        (taken, missed)
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap())
                .fold((0, 0), |(a, b), (c, d)| (a + c, b + d))
        });
        assert!(
            taken > 0,
            "no box was ever taken ({missed} tries found the spares held)"
        );
        // The boxes kept are distinct (a give that finds the lock held frees its box, so
        // fewer than KEEP may be left, never one twice).
        let mut back: Vec<Box<Parts>> = std::iter::from_fn(|| spares.take()).collect();
        let kept = back.len();
        assert!(kept <= KEEP, "{kept} boxes kept");
        back.sort_by_key(|b| std::ptr::from_ref::<Parts>(b) as usize);
        back.dedup_by_key(|b| std::ptr::from_ref::<Parts>(b) as usize);
        assert_eq!(back.len(), kept, "a box was held twice");
    }
}
