//! A damper design and what it is worth: damping inclination (Eq 27), peak contact speed, peak
//! SPL, zones (Figs 15–17), the design sweep over mass × gap and Table 5. Pure functions.

pub mod asktell;
mod chart;
mod metrics;
mod restitution;
pub mod search;
mod search_operators;
mod table5;
mod types;
mod valid;

pub use chart::*;
pub use metrics::*;
pub use restitution::*;
pub use table5::*;
pub use types::*;
pub use valid::*;

#[cfg(test)]
mod tests;
