//! thud — the physics of single-unit impact dampers and the noise they make.
//!
//! The engine (`contact`, `acoustics`, `paper`, `units`) is pure: no I/O, no terminal.
//! Equation numbers refer to the source paper. SI units throughout; the front ends
//! (`cli`) convert at the edges. `config`, `store` and `export` are front-end support: settings,
//! saved designs and files (CSV, SVG, WAV), kept out of the physics modules.

pub mod acoustics;
pub mod config;
pub mod contact;
pub mod damper;
pub mod design;
pub mod error;
pub mod export;
pub mod paper;
pub mod presets;
pub mod store;
pub mod units;

pub mod cli;
pub mod tui;

pub use error::ThudError;
