//! `tmm::dynamics`: the machines' scenarios (exact solutions, orders, energy), stability limits,
//! breakpoints and kinks, and the five-bar's servos.

mod breakpoints;
mod five_bar_servo;
mod held_rest;
#[cfg(feature = "serde")] // it reads a bundled linkage
mod kinks;
#[cfg(feature = "serde")] // it reads a bundled linkage
mod lock_events;
#[cfg(feature = "serde")] // it reads a bundled linkage
mod reversals;
#[cfg(feature = "serde")] // it reads a bundled linkage
mod run_up_ends;
mod runaway;
pub(crate) mod scenarios;
mod stability;
#[cfg(feature = "serde")] // it reads a bundled linkage
mod two_input_stops;
