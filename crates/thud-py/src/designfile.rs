//! `design=`: the starting design from a design file or a saved design's name, as the command
//! line's `--design FILE|NAME` (what `--save`, `fit --save` and the explorer write).

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use thud_core::design::Design;
use thud_core::ThudError;

use crate::args::{engine_error, kind_of, parameter_error};

/// The largest design file read (1 MiB), as the command line's; a real one is a few hundred
/// bytes.
const MAX_READ_BYTES: u64 = 1 << 20;

/// Whether `text` names a file (a path with a `/`, a name ending in `.toml`, or an existing
/// file) rather than a design saved in the user's data directory — the command line's rule.
fn names_a_file(text: &str) -> bool {
    text.contains('/') || text.to_ascii_lowercase().ends_with(".toml") || Path::new(text).is_file()
}

/// The file of the saved design `name` (1–64 letters, digits, '-' or '_').
fn saved(name: &str) -> Result<PathBuf, ThudError> {
    let ok = (1..=64).contains(&name.len()) && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if !ok {
        return Err(ThudError::invalid(
            "design",
            format!("no file '{name}' and no saved design of that name (a file is named with its path or .toml)"),
        ));
    }
    let dirs = directories::ProjectDirs::from("", "", "thud")
        .ok_or_else(|| ThudError::invalid("design", "no home directory to find saved designs in"))?;
    Ok(dirs.data_dir().join("designs").join(format!("{name}.toml")))
}

/// The design `value` (a path or a saved design's name) names.
pub fn load(py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<Design> {
    let Ok(path) = value.extract::<PathBuf>() else {
        let msg =
            format!("invalid design: expected a design file's path or a saved design's name, not {}", kind_of(value));
        return Err(parameter_error(py, "design", msg));
    };
    let text = path.to_string_lossy().into_owned();
    let file = if names_a_file(&text) { Ok(path) } else { saved(&text) };
    read(&file.map_err(|e| engine_error(py, e))?, &text).map_err(|e| engine_error(py, e))
}

/// The design file at `path` (typed as `typed`): a regular file of at most 1 MiB, parsed and
/// validated.
fn read(path: &Path, typed: &str) -> Result<Design, ThudError> {
    let bad = |what: String| ThudError::invalid("design", format!("{}: {what}", path.display()));
    let meta = std::fs::metadata(path).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound && !names_a_file(typed) {
            ThudError::invalid(
                "design",
                format!("no file '{typed}' and no saved design of that name (a file is named with its path or .toml)"),
            )
        } else {
            bad(e.to_string())
        }
    })?;
    if !meta.is_file() {
        return Err(bad("not a regular file".into()));
    }
    if meta.len() > MAX_READ_BYTES {
        return Err(bad(format!("{} bytes; a design file is at most 1 MiB", meta.len())));
    }
    let text = std::fs::read_to_string(path).map_err(|e| bad(e.to_string()))?;
    thud_presets::design_file(&text).map_err(|e| bad(e.to_string()))
}
