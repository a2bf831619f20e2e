//! Named starting designs: the compiled-in files of `crates/thud-presets/presets/` ([`thud_presets`], a
//! small crate the Python module shares), and each as a saved-design file
//! ([`crate::store::DesignFile`]) for the explorer and the tests.

use crate::error::ThudError;
use crate::store::DesignFile;

pub use thud_presets::{list, names, preset, PresetInfo, TABLE3_C1};

/// The preset called `name` (case-insensitive) with its description, as a design file.
pub fn preset_file(name: &str) -> Result<DesignFile, ThudError> {
    let p = thud_presets::preset_file(name)?;
    Ok(DesignFile {
        description: p.description,
        ensemble: None,
        uncertainty: std::collections::BTreeMap::default(),
        design: p.design,
    })
}
