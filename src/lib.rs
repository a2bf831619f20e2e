//! thud — design single-unit impact dampers from the terminal.
//!
//! This crate is the application: the command line (`cli`), the terminal explorer (`tui`), files
//! (`export`, `config`, `store`) and the compiled-in presets. The physics lives in the pure
//! `thud-core` crate (no I/O, no terminal); its modules are re-exported here under their own
//! names so that `thud::contact`, `thud::design`, … read the same from either crate.

pub use thud_core::{
    acoustics, contact, continuation, damper, design, dynamics, ensemble, error, finite, fit, limits, orbit, paper,
    params, report, response, study, units, verdict, walk, ThudError,
};

pub mod ascii;
pub mod config;
pub mod export;
pub mod fsio;
pub mod presets;
pub mod shard;
pub mod signals;
pub mod store;
pub mod threads;

pub mod cli;
pub mod tui;
