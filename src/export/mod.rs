//! Files that leave the terminal: CSV tables, SVG and PDF figures and WAV sound.
//!
//! The building blocks ([`csv`], [`figures`], [`wav`], [`report`]; [`pdf`] converts a figure) return the file's contents
//! (`String` or `Vec<u8>`). [`render`] and [`export_to_path`] are the one-call front door used
//! by the CLI and the TUI: a [`Artifact`] of file, a design and [`ExportOptions`] in; the contents,
//! or a file written through [`crate::fsio`] (atomic, never over an existing file), out.

pub mod fit;
pub mod front;
pub mod report;
// The renderers live in their own crate (shared with the Python module), by their old paths.
pub use thud_render::{continuation, csv, dynamics, figures, pdf, studies, svg, wav};

use std::path::Path;

use thiserror::Error;

use crate::design::{Design, ValidDesign};
use crate::fsio::{self, FsError, Overwrite};
pub use thud_render::artifact::{directivity_points, response_freqs, Artifact, ExportOptions, RenderError};

/// Why an export to a file was not made.
#[derive(Debug, Error)]
pub enum ExportError {
    /// The bytes were not made (an invalid design or option, or a CSV, WAV or PDF failure).
    /// Boxed: the file's error beside it would make every result carry both.
    #[error(transparent)]
    Render(Box<RenderError>),
    /// The file could not be written (it exists, is not a regular file, or the system refused).
    #[error("cannot write {0}")]
    File(#[from] FsError),
}

impl From<RenderError> for ExportError {
    fn from(e: RenderError) -> Self {
        ExportError::Render(Box::new(e))
    }
}

/// The contents of an export of `kind` for `design` ([`thud_render::artifact::render`]).
pub fn render(kind: Artifact, design: &ValidDesign, opts: &ExportOptions) -> Result<Vec<u8>, ExportError> {
    Ok(thud_render::artifact::render(kind, design, opts)?)
}

/// The figure `kind` for `design` as a one-page PDF ([`thud_render::artifact::render_pdf`]).
pub fn render_pdf(kind: Artifact, design: &ValidDesign, opts: &ExportOptions) -> Result<Vec<u8>, ExportError> {
    Ok(thud_render::artifact::render_pdf(kind, design, opts)?)
}

/// Checks `design` ([`Design::check`]), renders an export of `kind` for it and writes it to
/// `path` through [`fsio::write`]: atomically, and never over an existing file (the explorer
/// picks a free name; a file that appears meanwhile is left alone and reported).
pub fn export_to_path(kind: Artifact, design: &Design, opts: &ExportOptions, path: &Path) -> Result<(), ExportError> {
    export_to_path_with(kind, design, opts, path, |bytes| bytes)
}

/// As [`export_to_path`], with the rendered bytes passed through `finish` before they are
/// written (the explorer's `--ascii` spelling of a figure).
pub fn export_to_path_with(
    kind: Artifact,
    design: &Design,
    opts: &ExportOptions,
    path: &Path,
    finish: impl FnOnce(Vec<u8>) -> Vec<u8>,
) -> Result<(), ExportError> {
    let design = design.clone().check().map_err(RenderError::from)?;
    fsio::write(path, &finish(render(kind, &design, opts)?), Overwrite::Refuse)?;
    Ok(())
}
