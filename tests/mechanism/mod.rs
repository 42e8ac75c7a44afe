//! `tmm::mechanism`: the ready mechanisms through the linkage engine (engine), and against the
//! hand-written chains they replaced (reference, with those chains in hand/).

mod engine;
mod hand;
mod reference;
