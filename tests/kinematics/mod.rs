//! `tmm::kinematics`: whole cycles and errors (scenarios), property tests of the dyad blocks
//! against finite differences (props), the prismatic blocks (prismatic), and their strategies.

mod prismatic;
mod props;
mod scenarios;
mod strategies;
