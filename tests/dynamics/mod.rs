//! `tmm::dynamics`: the machines' scenarios (exact solutions, orders, energy), stability limits,
//! breakpoints and kinks, and the five-bar's servos.

mod breakpoints;
mod five_bar_servo;
mod kinks;
mod scenarios;
mod stability;
