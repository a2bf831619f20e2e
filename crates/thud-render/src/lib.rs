//! thud's files from engine results, as bytes: SVG figures ([`figures`], [`dynamics`], [`pulse`]
//! on the writer [`svg`]), PDF figures ([`pdf`]), WAV sound ([`wav`]) and CSV tables ([`csv`], the
//! studies' in [`dynamics`]). No file I/O and no terminal: the app writes what these return
//! (atomically, never over a file), and so does the Python module.

// The engine's modules by the names the renderers use (`crate::design`, `crate::damper`, …).
use thud_core::{acoustics, contact, damper, design, ensemble, error, paper, response, study, units};

pub mod artifact;
pub mod continuation;
pub mod csv;
pub mod dynamics;
pub mod figures;
pub mod json;
pub mod pdf;
pub mod pulse;
pub mod studies;
pub mod svg;
pub mod wav;
