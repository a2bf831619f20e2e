//! How a result pickles and is restored from its record's JSON text.

use std::fmt;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use serde_json::Value as Json;

use crate::args::non_finite;

use super::{PyChart, PyEnsemble, PyPulse, PyResponse, PyRun};

/// How a result pickles: `thud._restore(kind, state)`, the state the record's JSON text.
pub(super) type Reduced = (Py<PyAny>, (String, String));

/// `(thud._restore, (kind, JSON text of state))`: `__reduce__` of every result.
pub(super) fn reduce(py: Python<'_>, kind: &str, state: &Json) -> PyResult<Reduced> {
    let text = serde_json::to_string(state).map_err(|e| non_finite(&format!("{kind} ({e})")))?;
    let restore = py.import("thud")?.getattr("_restore")?.unbind();
    Ok((restore, (kind.to_string(), text)))
}

/// _restore(kind, state) -> Pulse | Run | Ensemble | Chart | Response
///
/// A result again from its pickled state (what `__reduce__` gave): the same constructor as a
/// fresh result, from the record's JSON text.
#[pyfunction]
pub fn _restore(py: Python<'_>, kind: &str, state: &str) -> PyResult<Py<PyAny>> {
    let bad = |e: &dyn fmt::Display| pyo3::exceptions::PyValueError::new_err(format!("not a thud {kind} state: {e}"));
    let v: Json = serde_json::from_str(state).map_err(|e| bad(&e))?;
    // A state the results' own constructors cannot read is a forged or damaged one: a
    // ValueError naming the field, never an "internal error".
    let forged = |e: PyErr| {
        if e.is_instance_of::<PyRuntimeError>(py) {
            let text = e.value(py).to_string();
            bad(&text.trim_start_matches("internal error: "))
        } else {
            e
        }
    };
    if let Some(at) = implausible(&v, "") {
        return Err(bad(&format!("'{at}' is out of range (a finite number, -1e100 to 1e100)")));
    }
    restore_checked(py, kind, v).map_err(forged)
}

/// The largest magnitude of a number in a result's state: far beyond anything thud computes,
/// far below where sums of such numbers overflow to ∞ and their differences to NaN (a forged
/// chart's Table 5 bands). The same bound as `thud merge` holds a part's cells to.
pub(super) const MAX_STATE_MAGNITUDE: f64 = 1e100;

/// The path (`record.sweeps.0.points`) of the first number in `v` beyond
/// [`MAX_STATE_MAGNITUDE`], if any.
pub(super) fn implausible(v: &Json, at: &str) -> Option<String> {
    let join = |k: &dyn fmt::Display| if at.is_empty() { k.to_string() } else { format!("{at}.{k}") };
    match v {
        Json::Number(n) => {
            n.as_f64().is_none_or(|x| !x.is_finite() || x.abs() > MAX_STATE_MAGNITUDE).then(|| at.into())
        }
        Json::Array(items) => items.iter().enumerate().find_map(|(i, x)| implausible(x, &join(&i))),
        Json::Object(map) => map.iter().find_map(|(k, x)| implausible(x, &join(k))),
        _ => None,
    }
}

/// [`_restore`] once the state is JSON.
pub(super) fn restore_checked(py: Python<'_>, kind: &str, v: Json) -> PyResult<Py<PyAny>> {
    let bad = |e: &dyn fmt::Display| pyo3::exceptions::PyValueError::new_err(format!("not a thud {kind} state: {e}"));
    let obj = match kind {
        "Pulse" => PyPulse::from_record(py, v)?.into_pyobject(py)?.into_any(),
        "Run" => PyRun::from_state(py, v)?.into_pyobject(py)?.into_any(),
        "Ensemble" => PyEnsemble::from_record(py, v)?.into_pyobject(py)?.into_any(),
        "Chart" => PyChart::from_state(py, v)?.into_pyobject(py)?.into_any(),
        "Response" => PyResponse::from_state(py, v)?.into_pyobject(py)?.into_any(),
        _ => return Err(bad(&"unknown kind")),
    };
    Ok(obj.unbind())
}
