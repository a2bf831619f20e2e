//! Files that leave the terminal: CSV tables, SVG figures and WAV sound. Every function returns
//! the file's contents (`String` or `Vec<u8>`); the caller writes it (the CLI with
//! `store::write_atomic`).

pub mod csv;
pub mod figures;
pub mod report;
pub mod svg;
pub mod wav;
