//! The spare buffers of a plan's finished solves, handed to its next one: what makes the
//! one-shot [`Plan::analyse`](crate::linkage::Plan::analyse) and
//! [`Plan::kinematics`](crate::linkage::Plan::kinematics) allocate nothing in a loop.
//!
//! An [`Analysis`](super::Analysis) or [`Kinematics`](super::Kinematics) that is dropped
//! gives its buffers back to its plan; the next one made takes them instead of allocating.
//! Every solve writes whatever it reads, so the buffers' history does not reach any result
//! (a solve is a pure function of its inputs, as with a reused [`Solver`](super::Solver)).
//! The pool never waits: a thread that finds it busy allocates (or frees) as before, and it
//! keeps at most [`KEEP`] sets, so that dropping a million kept analyses holds no memory.
//!
//! This file names only plain data, so that the plan can hold the pool.

use super::reaction::Reaction;
use crate::kinematics::{GroupWork, LinkMotion, TriadPose};
use crate::kinetostatics::Conditioning;
use crate::Load;
use nalgebra::Vector2;
use std::sync::Mutex;

/// The most sets of buffers a plan keeps (a few per thread that makes one-shot solves).
pub(crate) const KEEP: usize = 8;

/// The buffers of one position's kinematics (see `KinState`).
#[derive(Debug)]
pub(crate) struct KinBuffers {
    pub links: Vec<LinkMotion>,
    pub units: Vec<Vector2<f64>>,
    pub turns: Vec<[Vector2<f64>; 3]>,
    pub dets: Vec<f64>,
    pub triads: Vec<Option<TriadPose>>,
    pub general_work: Vec<GroupWork>,
}

/// The buffers an analysis adds to the kinematics': loads, reactions, conditioning.
#[derive(Debug)]
pub(crate) struct StaticBuffers {
    pub applied: Vec<(usize, Load)>,
    pub acc: Vec<Load>,
    pub reactions: Vec<Reaction>,
    pub conditioning: Vec<Conditioning>,
}

#[derive(Default)]
struct Pool {
    kin: Vec<KinBuffers>,
    statics: Vec<StaticBuffers>,
}

/// A plan's spare buffers. Not part of what a plan is: a clone starts with none, two plans
/// compare equal whatever they hold, and a plan's `Debug` does not list them.
#[derive(Default)]
pub(crate) struct Spares(Mutex<Pool>);

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
    /// A spare set of kinematic buffers, if one is free.
    #[inline]
    pub fn kin(&self) -> Option<KinBuffers> {
        self.0.try_lock().ok()?.kin.pop()
    }

    /// Spare kinematic and static buffers (each if one is free), under one lock.
    #[inline]
    pub fn analysis(&self) -> (Option<KinBuffers>, Option<StaticBuffers>) {
        match self.0.try_lock() {
            Ok(mut p) => (p.kin.pop(), p.statics.pop()),
            Err(_) => (None, None),
        }
    }

    /// Gives back a set of buffers (dropped if the pool is full or busy).
    #[inline]
    pub fn give(&self, kin: Option<KinBuffers>, statics: Option<StaticBuffers>) {
        if let Ok(mut p) = self.0.try_lock() {
            if let Some(k) = kin
                && p.kin.len() < KEEP
            {
                p.kin.push(k);
            }
            if let Some(s) = statics
                && p.statics.len() < KEEP
            {
                p.statics.push(s);
            }
        }
    }
}
