//! Records to Python: JSON values, NumPy arrays and dicts of columns.

use std::fmt;

use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::de::{DeserializeOwned, IgnoredAny, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::Value as Json;
use thud_core::design::Design;
use thud_core::limits::short;

use crate::args::non_finite;

/// `record` checked finite (the command line's check of its JSON), then as a JSON value.
pub(super) fn checked<T: Serialize>(what: &str, record: &T) -> PyResult<Json> {
    thud_core::finite::check(record).map_err(|e| non_finite(&format!("{what}: NonFinite({:?})", e.0)))?;
    serde_json::to_value(record).map_err(|e| non_finite(&format!("{what} ({e})")))
}

/// A JSON value as Python data (dicts, lists, numbers, strings, None).
pub(super) fn to_py(py: Python<'_>, v: &Json) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| non_finite(&format!("{e}")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// `record` as Python data through its JSON form (a design reads exactly as in `--json`).
pub(super) fn json_data<T: Serialize>(py: Python<'_>, what: &str, record: &T) -> PyResult<Py<PyAny>> {
    to_py(py, &checked(what, record)?)
}

/// A NumPy array of `values`, each checked finite.
pub(super) fn array(py: Python<'_>, what: &str, values: Vec<f64>) -> PyResult<Py<PyAny>> {
    if values.iter().any(|v| !v.is_finite()) {
        return Err(non_finite(what));
    }
    Ok(PyArray1::from_vec(py, values).into_any().unbind())
}

/// An internal error: a record without the field a result reads from it.
pub(super) fn missing(what: &str, key: &str) -> PyErr {
    PyRuntimeError::new_err(format!("internal error: the {what} record has no valid '{key}'"))
}

/// The number `key` of `record` (required).
pub(super) fn num(what: &str, record: &Json, key: &str) -> PyResult<f64> {
    record.get(key).and_then(Json::as_f64).ok_or_else(|| missing(what, key))
}

/// The number `key` of `record`, None for null.
pub(super) fn opt_num(what: &str, record: &Json, key: &str) -> PyResult<Option<f64>> {
    match record.get(key) {
        Some(Json::Null) => Ok(None),
        Some(v) => v.as_f64().map(Some).ok_or_else(|| missing(what, key)),
        None => Err(missing(what, key)),
    }
}

/// The whole number `key` of `record` (required).
pub(super) fn whole(what: &str, record: &Json, key: &str) -> PyResult<usize> {
    record.get(key).and_then(Json::as_u64).and_then(|v| usize::try_from(v).ok()).ok_or_else(|| missing(what, key))
}

/// The text `key` of `record`, None for null.
pub(super) fn opt_text(what: &str, record: &Json, key: &str) -> PyResult<Option<String>> {
    match record.get(key) {
        Some(Json::Null) => Ok(None),
        Some(Json::String(t)) => Ok(Some(t.clone())),
        _ => Err(missing(what, key)),
    }
}

/// The text `key` of `record` (required).
pub(super) fn text(what: &str, record: &Json, key: &str) -> PyResult<String> {
    opt_text(what, record, key)?.ok_or_else(|| missing(what, key))
}

/// The switch `key` of `record` (required).
pub(super) fn flag(what: &str, record: &Json, key: &str) -> PyResult<bool> {
    record.get(key).and_then(Json::as_bool).ok_or_else(|| missing(what, key))
}

/// The zone `key` of `record` (1–4), None for null.
pub(super) fn zone_of(what: &str, record: &Json, key: &str) -> PyResult<Option<u8>> {
    Ok(opt_num(what, record, key)?.map(|z| z as u8))
}

/// The top-level keys of a JSON object in the order of the text: a visitor, because
/// serde_json's own map (without its `preserve_order` feature, which would change the
/// command line's output too) sorts keys.
struct Keys(Vec<String>);

impl<'de> Deserialize<'de> for Keys {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Keys, D::Error> {
        struct KeysVisitor;
        impl<'de> Visitor<'de> for KeysVisitor {
            type Value = Keys;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a JSON object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Keys, A::Error> {
                let mut keys = Vec::new();
                while let Some((k, IgnoredAny)) = map.next_entry::<String, IgnoredAny>()? {
                    keys.push(k);
                }
                Ok(Keys(keys))
            }
        }
        d.deserialize_map(KeysVisitor)
    }
}

/// The keys of `value` in the order serde writes them: its fields' order (`t_s` first for an
/// impact), the natural order of a table's columns.
pub(super) fn field_order<T: Serialize>(value: &T) -> Vec<String> {
    serde_json::to_string(value).ok().and_then(|t| serde_json::from_str::<Keys>(&t).ok()).map_or_else(Vec::new, |k| k.0)
}

/// The field order of the record row `row` read as a `T` (empty when it is not one).
pub(super) fn order_of<T: Serialize + DeserializeOwned>(row: Option<&Json>) -> Vec<String> {
    row.and_then(|r| serde_json::from_value::<T>(r.clone()).ok()).map_or_else(Vec::new, |t| field_order(&t))
}

/// The key `key` of every object in `rows` (null where absent).
pub(super) fn column<'a>(rows: &'a [Json], key: &str) -> Vec<&'a Json> {
    rows.iter().map(|r| r.get(key).unwrap_or(&Json::Null)).collect()
}

/// A list of records (JSON objects) as a dict of columns, one per key (the keys of
/// `template` when there are no rows, so an empty list still has every key): a `zone` as int8
/// (0 = none), the keys in `int8` as int8, other whole numbers as int64, numbers as float64
/// (NaN = none), booleans as bool, nested objects as dicts of columns, lists of records as
/// dicts of 2-D columns (row × item), anything else as a list. The keys in `order` come first,
/// in that order (a record's field order); any others follow in the record's (sorted) order.
pub(super) fn columns(
    py: Python<'_>,
    rows: &[Json],
    template: Option<&Json>,
    int8: &[&str],
    order: &[String],
) -> PyResult<Py<PyDict>> {
    let d = PyDict::new(py);
    let mut found: Vec<&String> = Vec::new();
    for r in rows.iter().chain(template.filter(|_| rows.is_empty())) {
        for k in r.as_object().into_iter().flat_map(|o| o.keys()) {
            if !found.contains(&k) {
                found.push(k);
            }
        }
    }
    let mut keys: Vec<&String> = order.iter().filter(|k| found.contains(k)).collect();
    keys.extend(found.into_iter().filter(|k| !order.contains(k)));
    for key in keys {
        let col = column(rows, key);
        let value: Py<PyAny> = if key == "zone" || int8.contains(&key.as_str()) {
            let v: Vec<i8> = col.iter().map(|v| v.as_i64().map_or(0, |z| z as i8)).collect();
            v.into_pyarray(py).into_any().unbind()
        } else if !col.is_empty() && col.iter().all(|v| v.is_i64() || v.is_u64()) {
            let v: Vec<i64> = col.iter().map(|v| v.as_i64().unwrap_or(i64::MAX)).collect();
            v.into_pyarray(py).into_any().unbind()
        } else if !col.is_empty() && col.iter().all(|v| v.is_boolean()) {
            let v: Vec<bool> = col.iter().map(|v| v.as_bool() == Some(true)).collect();
            v.into_pyarray(py).into_any().unbind()
        } else if col.iter().all(|v| v.is_number() || v.is_null()) {
            PyArray1::from_vec(py, col.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect()).into_any().unbind()
        } else if col.iter().all(|v| v.is_object() || v.is_null()) {
            let inner: Vec<Json> = col.into_iter().cloned().collect();
            columns(py, &inner, None, int8, &[])?.into_any()
        } else if col.iter().all(|v| v.as_array().is_some_and(|a| a.iter().all(Json::is_object))) {
            stacked(py, &col, int8)?
        } else {
            let list = PyList::empty(py);
            for v in col {
                list.append(to_py(py, v)?)?;
            }
            list.into_any().unbind()
        };
        d.set_item(key, value)?;
    }
    Ok(d.unbind())
}

/// Lists of records of equal length (one list per row) as a dict of 2-D columns (row × item).
pub(super) fn stacked(py: Python<'_>, lists: &[&Json], int8: &[&str]) -> PyResult<Py<PyAny>> {
    let n = lists.first().and_then(|l| l.as_array()).map_or(0, Vec::len);
    let flat: Vec<Json> = lists.iter().flat_map(|l| l.as_array().into_iter().flatten().cloned()).collect();
    if flat.len() != n * lists.len() {
        return Err(pyo3::exceptions::PyRuntimeError::new_err("internal error: ragged lists of records"));
    }
    let d = columns(py, &flat, None, int8, &[])?;
    reshape(py, d.bind(py).as_any(), &[lists.len(), n])
}

/// Every array in `value` (a dict of arrays, nested) with its first axis split into `front`; a
/// list split into `front[0]` lists of `front[1]` (two axes).
pub(super) fn reshape(py: Python<'_>, value: &Bound<'_, PyAny>, front: &[usize]) -> PyResult<Py<PyAny>> {
    if let Ok(d) = value.cast::<PyDict>() {
        let out = PyDict::new(py);
        for (k, v) in d.iter() {
            out.set_item(k, reshape(py, &v, front)?)?;
        }
        return Ok(out.into_any().unbind());
    }
    if let (Ok(list), [rows, n]) = (value.cast::<PyList>(), front) {
        // A list column (text, or values with gaps): one list per row, as the arrays are split.
        let out = PyList::empty(py);
        for r in 0..*rows {
            out.append(list.get_slice(r * n, (r + 1) * n))?;
        }
        return Ok(out.into_any().unbind());
    }
    if value.hasattr("reshape")? {
        let rest: Vec<usize> = value.getattr("shape")?.extract::<Vec<usize>>()?.into_iter().skip(1).collect();
        let shape: Vec<usize> = front.iter().chain(&rest).copied().collect();
        return Ok(value.call_method1("reshape", (pyo3::types::PyTuple::new(py, shape)?,))?.unbind());
    }
    Ok(value.clone().unbind())
}

/// The JSON objects of the list `key` of `record`.
pub(super) fn rows_of(record: &Json, key: &str) -> Vec<Json> {
    record.get(key).and_then(Json::as_array).cloned().unwrap_or_default()
}

/// A scalar of the record (`None` for null).
pub(super) fn field(py: Python<'_>, record: &Json, key: &str) -> PyResult<Py<PyAny>> {
    to_py(py, record.get(key).unwrap_or(&Json::Null))
}

/// The scalars of `record` (every key but `skip`) into `d`, then `extra`.
pub(super) fn fill(
    py: Python<'_>,
    d: &Bound<'_, PyDict>,
    record: &Json,
    skip: &[&str],
    extra: &[(&str, &Py<PyAny>)],
) -> PyResult<()> {
    for (k, v) in record.as_object().into_iter().flatten() {
        if !skip.contains(&k.as_str()) {
            d.set_item(k, to_py(py, v)?)?;
        }
    }
    for (k, v) in extra {
        d.set_item(k, v.clone_ref(py))?;
    }
    Ok(())
}

/// `thud._frames.NAME(obj)`: the Python half of a result's table, HTML and JSON methods.
pub(super) fn frames(py: Python<'_>, name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    Ok(py.import("thud._frames")?.getattr(name)?.call1((obj,))?.unbind())
}

/// `d`, or with `json` its JSON-ready copy (`thud._frames.jsonable`).
pub(super) fn plain(py: Python<'_>, d: Bound<'_, PyDict>, json: bool) -> PyResult<Py<PyAny>> {
    if json {
        frames(py, "jsonable", d.as_any())
    } else {
        Ok(d.into_any().unbind())
    }
}

/// "mass=0.05 kg, gap=0.03 m": the design of a record, for a repr.
pub(super) fn named(record: &Json) -> String {
    match record.get("design").and_then(|d| serde_json::from_value::<Design>(d.clone()).ok()) {
        Some(d) => format!("mass={} kg, gap={} m", short(d.damper.impact_mass_kg), short(d.damper.gap_m)),
        None => "design unknown".to_string(),
    }
}
