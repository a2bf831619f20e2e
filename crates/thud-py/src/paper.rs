//! `thud.paper(ID)`: a table or figure of the paper, beside the paper's numbers, as
//! `thud paper ID --json` writes it.

use pyo3::prelude::*;
use thud_core::{paper, ThudError};

use crate::args::engine_error;

/// paper(id) -> dict
///
/// A table or figure of the paper reproduced beside the paper's numbers (`thud paper ID`):
/// the dict of `thud paper ID --json`, key for key — id, title, notes, columns ([{key,
/// label}]), rows (each keyed by the columns' keys, in the paper's units: `mass_g`, `gap_cm`)
/// and, for some tables, summary. `id` is one of `thud paper --list`'s (table1 … fig17); an
/// unknown one raises ParameterError naming it.
#[pyfunction]
pub(crate) fn _paper(py: Python<'_>, id: &str) -> PyResult<String> {
    let key = id.to_ascii_lowercase();
    let Some(table) = py.detach(|| paper::get(&key)) else {
        let ids: Vec<&str> = paper::items().map(|i| i.id).collect();
        let e = ThudError::invalid("paper item", format!("unknown '{id}'; one of: {}", ids.join(", ")));
        return Err(engine_error(py, e));
    };
    let table = table.map_err(|e| engine_error(py, e))?;
    crate::json_of(py, &thud_render::json::table_json(&table))
}

/// The ids of the paper's tables and figures, in `thud paper --list`'s order.
#[pyfunction]
pub(crate) fn paper_ids() -> Vec<&'static str> {
    paper::items().map(|i| i.id).collect()
}
