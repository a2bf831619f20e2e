//! thud — the physics of single-unit impact dampers and the noise they make.
//!
//! A pure library: no I/O, no terminal. Equation numbers refer to the source paper
//! (see `README.md` and the project's model notes). SI units throughout.

pub mod contact;
pub mod damper;
pub mod error;

pub use error::ThudError;
