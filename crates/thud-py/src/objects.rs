//! The results handed to Python: `Pulse`, `Run`, `Ensemble`, `Chart` and `Response`. Each is
//! made from the engine's result record ([`thud_core::report`]) — the very record the command
//! line prints with `--json` — so the two cannot drift: scalars are copied, lists of records
//! become dicts of NumPy arrays by [`columns`] (one array per key of the record), nested
//! objects become dicts. Every number is checked finite before it is handed out; a value that
//! does not exist (no impact, so no SPL) is `None`, or NaN inside a float array (zone 0 in a
//! zone array).
//!
//! Every result pickles (and `copy.deepcopy`s): `__reduce__` hands out the record's JSON
//! (floats written and read back exactly), and `thud._restore` builds the object again from it
//! by the same constructor, so an unpickled result is the same object field for field. Tables
//! and labelled arrays (`impacts_frame`, `to_dataframe`, `to_xarray`), `as_dict(json=True)` and
//! `_repr_html_` are Python code (`thud/_frames.py`) that these methods call.

use std::fmt;
use std::sync::atomic::AtomicBool;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::de::{DeserializeOwned, IgnoredAny, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::Value as Json;
use thud_core::damper::{free_response, HistoryPoint, Maximum};
use thud_core::design::{self, Design, ValidDesign};
use thud_core::ensemble::{EnsembleChart, Member};
use thud_core::limits::{self, short};
use thud_core::params::PulseInput;
use thud_core::report::{EnsembleReport, ImpactReport, PulseReport, ResponseEnsembleReport, ResponseReport, RunReport};
use thud_core::response::{EnsemblePoint, ResponsePoint};
use thud_core::ThudError;

use crate::args::{engine_error, non_finite, parameter_error};

/// `record` checked finite (the command line's check of its JSON), then as a JSON value.
fn checked<T: Serialize>(what: &str, record: &T) -> PyResult<Json> {
    thud_core::finite::check(record).map_err(|e| non_finite(&format!("{what}: NonFinite({:?})", e.0)))?;
    serde_json::to_value(record).map_err(|e| non_finite(&format!("{what} ({e})")))
}

/// A JSON value as Python data (dicts, lists, numbers, strings, None).
fn to_py(py: Python<'_>, v: &Json) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| non_finite(&format!("{e}")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// `record` as Python data through its JSON form (a design reads exactly as in `--json`).
fn json_data<T: Serialize>(py: Python<'_>, what: &str, record: &T) -> PyResult<Py<PyAny>> {
    to_py(py, &checked(what, record)?)
}

/// A NumPy array of `values`, each checked finite.
fn array(py: Python<'_>, what: &str, values: Vec<f64>) -> PyResult<Py<PyAny>> {
    if values.iter().any(|v| !v.is_finite()) {
        return Err(non_finite(what));
    }
    Ok(PyArray1::from_vec(py, values).into_any().unbind())
}

/// An internal error: a record without the field a result reads from it.
fn missing(what: &str, key: &str) -> PyErr {
    PyRuntimeError::new_err(format!("internal error: the {what} record has no valid '{key}'"))
}

/// The number `key` of `record` (required).
fn num(what: &str, record: &Json, key: &str) -> PyResult<f64> {
    record.get(key).and_then(Json::as_f64).ok_or_else(|| missing(what, key))
}

/// The number `key` of `record`, None for null.
fn opt_num(what: &str, record: &Json, key: &str) -> PyResult<Option<f64>> {
    match record.get(key) {
        Some(Json::Null) => Ok(None),
        Some(v) => v.as_f64().map(Some).ok_or_else(|| missing(what, key)),
        None => Err(missing(what, key)),
    }
}

/// The whole number `key` of `record` (required).
fn whole(what: &str, record: &Json, key: &str) -> PyResult<usize> {
    record.get(key).and_then(Json::as_u64).and_then(|v| usize::try_from(v).ok()).ok_or_else(|| missing(what, key))
}

/// The text `key` of `record`, None for null.
fn opt_text(what: &str, record: &Json, key: &str) -> PyResult<Option<String>> {
    match record.get(key) {
        Some(Json::Null) => Ok(None),
        Some(Json::String(t)) => Ok(Some(t.clone())),
        _ => Err(missing(what, key)),
    }
}

/// The text `key` of `record` (required).
fn text(what: &str, record: &Json, key: &str) -> PyResult<String> {
    opt_text(what, record, key)?.ok_or_else(|| missing(what, key))
}

/// The switch `key` of `record` (required).
fn flag(what: &str, record: &Json, key: &str) -> PyResult<bool> {
    record.get(key).and_then(Json::as_bool).ok_or_else(|| missing(what, key))
}

/// The zone `key` of `record` (1–4), None for null.
fn zone_of(what: &str, record: &Json, key: &str) -> PyResult<Option<u8>> {
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
fn field_order<T: Serialize>(value: &T) -> Vec<String> {
    serde_json::to_string(value).ok().and_then(|t| serde_json::from_str::<Keys>(&t).ok()).map_or_else(Vec::new, |k| k.0)
}

/// The field order of the record row `row` read as a `T` (empty when it is not one).
fn order_of<T: Serialize + DeserializeOwned>(row: Option<&Json>) -> Vec<String> {
    row.and_then(|r| serde_json::from_value::<T>(r.clone()).ok()).map_or_else(Vec::new, |t| field_order(&t))
}

/// The key `key` of every object in `rows` (null where absent).
fn column<'a>(rows: &'a [Json], key: &str) -> Vec<&'a Json> {
    rows.iter().map(|r| r.get(key).unwrap_or(&Json::Null)).collect()
}

/// A list of records (JSON objects) as a dict of columns, one per key (the keys of
/// `template` when there are no rows, so an empty list still has every key): a `zone` as int8
/// (0 = none), the keys in `int8` as int8, other whole numbers as int64, numbers as float64
/// (NaN = none), booleans as bool, nested objects as dicts of columns, lists of records as
/// dicts of 2-D columns (row × item), anything else as a list. The keys in `order` come first,
/// in that order (a record's field order); any others follow in the record's (sorted) order.
fn columns(
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
fn stacked(py: Python<'_>, lists: &[&Json], int8: &[&str]) -> PyResult<Py<PyAny>> {
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
fn reshape(py: Python<'_>, value: &Bound<'_, PyAny>, front: &[usize]) -> PyResult<Py<PyAny>> {
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
fn rows_of(record: &Json, key: &str) -> Vec<Json> {
    record.get(key).and_then(Json::as_array).cloned().unwrap_or_default()
}

/// A scalar of the record (`None` for null).
fn field(py: Python<'_>, record: &Json, key: &str) -> PyResult<Py<PyAny>> {
    to_py(py, record.get(key).unwrap_or(&Json::Null))
}

/// Everything a `Pulse` holds, computed without the GIL.
pub struct PulseData(PulseReport);

impl PulseData {
    /// The pulse of `input` with a waveform of `points` points — the record of
    /// `thud pulse --json`.
    pub fn compute(input: &PulseInput, points: usize) -> Result<PulseData, ThudError> {
        let contact = input.contact();
        let field = input.field(&contact)?;
        Ok(PulseData(PulseReport::new(input, &contact, &field, points)))
    }
}

/// One Hertzian impact heard at one observer (`thud.pulse`): the inputs as used, the contact
/// (Eqs 5–7), the levels and the waveform. SI units; angles in degrees; levels in dB re 20 µPa.
#[pyclass(name = "Pulse", module = "thud", frozen)]
pub struct PyPulse {
    /// Sphere radius a (m).
    #[pyo3(get)]
    radius_m: f64,
    /// Sphere mass m (kg).
    #[pyo3(get)]
    mass_kg: f64,
    /// Impact speed U0 (m/s).
    #[pyo3(get)]
    u0_m_s: f64,
    /// Hertz stiffness K_HZ (N/m^1.5).
    #[pyo3(get)]
    k_hz_n_m1_5: f64,
    /// Observer distance r (m).
    #[pyo3(get)]
    r_m: f64,
    /// Observer angle θ (degrees).
    #[pyo3(get)]
    theta_deg: f64,
    /// "single", "dipole" or "quadrupole".
    #[pyo3(get)]
    source: String,
    /// "paper" or "rigid".
    #[pyo3(get)]
    quad_signs: String,
    /// "half-sine" or "hertz".
    #[pyo3(get)]
    pulse: String,
    /// Air impedance ρ0·c (Pa·s/m).
    #[pyo3(get)]
    rho_c_pa_s_m: f64,
    /// Speed of sound c (m/s).
    #[pyo3(get)]
    c_m_s: f64,
    /// Peak approach α_max (m).
    #[pyo3(get)]
    alpha_max_m: f64,
    /// Peak acceleration A_max (m/s²).
    #[pyo3(get)]
    accel_max_m_s2: f64,
    /// Contact duration τ (s).
    #[pyo3(get)]
    tau_s: f64,
    /// Peak contact force (N).
    #[pyo3(get)]
    force_max_n: f64,
    /// Arrival of the direct wave (s after the contact starts).
    #[pyo3(get)]
    arrival_s: f64,
    /// SPL (dB): rms over one contact duration from the direct arrival.
    #[pyo3(get)]
    spl_db: f64,
    /// How spl_db is defined.
    #[pyo3(get)]
    spl_definition: String,
    /// Peak level (dB).
    #[pyo3(get)]
    spl_peak_db: f64,
    /// Sound exposure level (dB).
    #[pyo3(get)]
    sel_db: f64,
    /// rms pressure over the SPL window (Pa).
    #[pyo3(get)]
    p_rms_pa: f64,
    /// Largest pressure (Pa).
    #[pyo3(get)]
    p_max_pa: f64,
    /// Smallest pressure (Pa).
    #[pyo3(get)]
    p_min_pa: f64,
    /// Local extrema of the waveform: {"t_s": array (s), "p_pa": array (Pa)}.
    #[pyo3(get)]
    extrema: Py<PyDict>,
    /// Waveform times (s), from the contact's start.
    #[pyo3(get)]
    t_s: Py<PyAny>,
    /// Waveform pressure (Pa).
    #[pyo3(get)]
    p_pa: Py<PyAny>,
    /// The record, for `as_dict`.
    record: Json,
}

impl PyPulse {
    pub fn new(py: Python<'_>, data: PulseData) -> PyResult<PyPulse> {
        Self::from_record(py, checked("pulse", &data.0)?)
    }

    /// The pulse of the record of `thud pulse --json` (finite already).
    fn from_record(py: Python<'_>, record: Json) -> PyResult<PyPulse> {
        const W: &str = "pulse";
        let number = |k: &str| num(W, &record, k);
        let wave = record.get("waveform").ok_or_else(|| missing(W, "waveform"))?;
        let series = |k: &str| -> PyResult<Vec<f64>> {
            let v = wave.get(k).and_then(Json::as_array).ok_or_else(|| missing(W, k))?;
            v.iter().map(|x| x.as_f64().ok_or_else(|| missing(W, k))).collect()
        };
        let template = serde_json::json!({"t_s": 0.0, "p_pa": 0.0});
        let extrema = rows_of(&record, "extrema");
        let order = order_of::<thud_core::acoustics::Extremum>(extrema.first());
        Ok(PyPulse {
            extrema: columns(py, &extrema, Some(&template), &[], &order)?,
            t_s: array(py, "t_s", series("t_s")?)?,
            p_pa: array(py, "p_pa", series("p_pa")?)?,
            radius_m: number("radius_m")?,
            mass_kg: number("mass_kg")?,
            u0_m_s: number("u0_m_s")?,
            k_hz_n_m1_5: number("k_hz_n_m1_5")?,
            r_m: number("r_m")?,
            theta_deg: number("theta_deg")?,
            source: text(W, &record, "source")?,
            quad_signs: text(W, &record, "quad_signs")?,
            pulse: text(W, &record, "pulse")?,
            rho_c_pa_s_m: number("rho_c_pa_s_m")?,
            c_m_s: number("c_m_s")?,
            alpha_max_m: number("alpha_max_m")?,
            accel_max_m_s2: number("accel_max_m_s2")?,
            tau_s: number("tau_s")?,
            force_max_n: number("force_max_n")?,
            arrival_s: number("arrival_s")?,
            spl_db: number("spl_db")?,
            spl_definition: text(W, &record, "spl_definition")?,
            spl_peak_db: number("spl_peak_db")?,
            sel_db: number("sel_db")?,
            p_rms_pa: number("p_rms_pa")?,
            p_max_pa: number("p_max_pa")?,
            p_min_pa: number("p_min_pa")?,
            record,
        })
    }
}

/// The scalars of `record` (every key but `skip`) into `d`, then `extra`.
fn fill(
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

#[pymethods]
impl PyPulse {
    /// as_dict(json=False) -> dict
    ///
    /// Every field in one dict (the command line's JSON keys; the waveform as "t_s"/"p_pa").
    /// json=True: plain lists, numbers and None only (NaN → None), ready for `json.dumps`.
    #[pyo3(signature = (json = false))]
    fn as_dict(&self, py: Python<'_>, json: bool) -> PyResult<Py<PyAny>> {
        let d = PyDict::new(py);
        let extrema = self.extrema.clone_ref(py).into_any();
        fill(
            py,
            &d,
            &self.record,
            &["waveform", "extrema"],
            &[("extrema", &extrema), ("t_s", &self.t_s), ("p_pa", &self.p_pa)],
        )?;
        plain(py, d, json)
    }

    /// to_dataframe() -> pandas.DataFrame
    ///
    /// The waveform as a table: t_s (s), p_pa (Pa); the scalars in `.attrs`. Needs pandas.
    fn to_dataframe(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "pulse_frame", slf.as_any())
    }

    /// to_xarray() -> xarray.Dataset
    ///
    /// The waveform on the dimension t_s (s): p_pa (Pa); the scalars in `.attrs`. Needs xarray.
    fn to_xarray(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "pulse_xarray", slf.as_any())
    }

    fn _repr_html_(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "repr_html", slf.as_any())
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        reduce(py, "Pulse", &self.record)
    }

    /// Equal when the records are (every field; an unpickled pulse equals its original).
    fn __eq__(&self, other: PyRef<'_, Self>) -> bool {
        self.record == other.record
    }

    fn __repr__(&self) -> String {
        format!(
            "Pulse(a={} m, m={} kg, U0={} m/s, {} at r={} m, θ={}°: τ={} s, SPL={:.2} dB, peak {:.2} dB)",
            short(self.radius_m),
            short(self.mass_kg),
            short(self.u0_m_s),
            self.source,
            short(self.r_m),
            short(self.theta_deg),
            short(self.tau_s),
            self.spl_db,
            self.spl_peak_db
        )
    }
}

/// How a result pickles: `thud._restore(kind, state)`, the state the record's JSON text.
type Reduced = (Py<PyAny>, (String, String));

/// `(thud._restore, (kind, JSON text of state))`: `__reduce__` of every result.
fn reduce(py: Python<'_>, kind: &str, state: &Json) -> PyResult<Reduced> {
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
const MAX_STATE_MAGNITUDE: f64 = 1e100;

/// The path (`record.sweeps.0.points`) of the first number in `v` beyond
/// [`MAX_STATE_MAGNITUDE`], if any.
fn implausible(v: &Json, at: &str) -> Option<String> {
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
fn restore_checked(py: Python<'_>, kind: &str, v: Json) -> PyResult<Py<PyAny>> {
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

/// `thud._frames.NAME(obj)`: the Python half of a result's table, HTML and JSON methods.
fn frames(py: Python<'_>, name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    Ok(py.import("thud._frames")?.getattr(name)?.call1((obj,))?.unbind())
}

/// `d`, or with `json` its JSON-ready copy (`thud._frames.jsonable`).
fn plain(py: Python<'_>, d: Bound<'_, PyDict>, json: bool) -> PyResult<Py<PyAny>> {
    if json {
        frames(py, "jsonable", d.as_any())
    } else {
        Ok(d.into_any().unbind())
    }
}

/// "mass=0.05 kg, gap=0.03 m": the design of a record, for a repr.
fn named(record: &Json) -> String {
    match record.get("design").and_then(|d| serde_json::from_value::<Design>(d.clone()).ok()) {
        Some(d) => format!("mass={} kg, gap={} m", short(d.damper.impact_mass_kg), short(d.damper.gap_m)),
        None => "design unknown".to_string(),
    }
}

/// Everything a `Run` holds, computed without the GIL.
pub struct RunData {
    report: RunReport,
    history: Vec<HistoryPoint>,
    x_free: Vec<f64>,
}

impl RunData {
    /// `design` simulated with `samples` history samples — the record of
    /// `thud simulate --json`, and the history of `--csv`.
    pub fn compute(d: &ValidDesign, samples: usize, cancel: &AtomicBool) -> Result<RunData, ThudError> {
        let eval = design::evaluate(d, samples, Some(cancel))?;
        let report = RunReport::new(d, &eval)?;
        let x_free = eval.run.history.iter().map(|h| free_response(&d.damper, h.t_s)).collect();
        Ok(RunData { report, history: eval.run.history, x_free })
    }
}

/// One damper design run through its impacts (`thud.simulate`): the metrics (Eq 27 e, e_fit,
/// U0max, SPLmax, zone), every impact, the cycle maxima, the energy ledger, the steady state
/// of a forced run and the time history. SI units; inclinations in cm/s; levels in dB re
/// 20 µPa. None = no such value (too few maxima for e, no impact for SPLmax).
#[pyclass(name = "Run", module = "thud", frozen)]
pub struct PyRun {
    /// The design as run (the command line's JSON "design" object).
    #[pyo3(get)]
    design: Py<PyAny>,
    /// Ball radius (m).
    #[pyo3(get)]
    ball_radius_m: f64,
    /// Number of impacts.
    #[pyo3(get)]
    n_impacts: usize,
    /// Damping inclination e of Eq 27 (cm/s).
    #[pyo3(get)]
    inclination_cm_s: Option<f64>,
    /// Robust least-squares inclination e_fit (cm/s).
    #[pyo3(get)]
    inclination_fit_cm_s: Option<f64>,
    /// Largest contact speed by the design's rule, U0max (m/s).
    #[pyo3(get)]
    u0_max_m_s: f64,
    /// Largest |z'| over the run including t = 0 (m/s).
    #[pyo3(get)]
    zdot_abs_max_m_s: f64,
    /// SPL of an impact at U0max, SPLmax (dB).
    #[pyo3(get)]
    spl_max_db: Option<f64>,
    /// Contact duration at U0max (s).
    #[pyo3(get)]
    contact_duration_s: Option<f64>,
    /// Mean restitution u_out/u_in.
    #[pyo3(get)]
    restitution_mean: Option<f64>,
    /// Zone 1–4 (3 = quiet and strong, the target).
    #[pyo3(get)]
    zone: Option<u8>,
    /// Every impact, as arrays: t_s (s), wall (±1, int8), u_in_m_s, u_out_m_s (m/s),
    /// restitution, t_end_s, duration_s (s), penetration_max_m (m), spl_db (dB).
    #[pyo3(get)]
    impacts: Py<PyDict>,
    /// Cycle maxima of the main mass: t_s (s), x_m (m).
    #[pyo3(get)]
    maxima: Py<PyDict>,
    /// Energy ledger (J): initial_j, final_mechanical_j, dissipated_viscous_j,
    /// dissipated_contact_j (and forcing_work_j of a forced run).
    #[pyo3(get)]
    energy: Py<PyAny>,
    /// Time reached (s).
    #[pyo3(get)]
    final_time_s: f64,
    /// Whether the solver's work cap stopped the run before its duration.
    #[pyo3(get)]
    truncated: bool,
    /// Why, when it did.
    #[pyo3(get)]
    truncation_reason: Option<String>,
    /// The steady state of a forced run over its last `periods` forcing periods (the JSON
    /// "steady" object: amplitude_m, amplitude_linear_m (m), reduction_db, leq_db (dB), …);
    /// None without a force.
    #[pyo3(get)]
    steady: Option<Py<PyAny>>,
    /// Uniform time history: t_s (s), x_m (main mass, m), y_m (ball, m), x_free_m (no damper, m).
    #[pyo3(get)]
    history: Py<PyDict>,
    /// The record (`thud simulate --json`), for pickling and the repr.
    record: Json,
}

impl PyRun {
    pub fn new(py: Python<'_>, data: RunData) -> PyResult<PyRun> {
        let RunData { report, history, x_free } = data;
        let series = vec![
            ("t_s", history.iter().map(|h| h.t_s).collect()),
            ("x_m", history.iter().map(|h| h.x_m).collect()),
            ("y_m", history.iter().map(|h| h.y_m).collect()),
            ("x_free_m", x_free),
        ];
        let history = series.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
        Self::from_parts(py, checked("run", &report)?, history)
    }

    /// The run of the record of `thud simulate --json` (finite already) and the time history
    /// (name, values) in order.
    fn from_parts(py: Python<'_>, record: Json, history: Vec<(String, Vec<f64>)>) -> PyResult<PyRun> {
        const W: &str = "run";
        let history_dict = PyDict::new(py);
        for (k, v) in history {
            history_dict.set_item(&k, array(py, &format!("history.{k}"), v)?)?;
        }
        let impacts = rows_of(&record, "impacts");
        let template = serde_json::to_value(ImpactReport::default()).ok();
        let impact_order = field_order(&ImpactReport::default());
        let maxima = rows_of(&record, "maxima");
        let maxima_template = serde_json::json!({"t_s": 0.0, "x_m": 0.0});
        let maxima_order = order_of::<Maximum>(maxima.first());
        Ok(PyRun {
            design: field(py, &record, "design")?,
            ball_radius_m: num(W, &record, "ball_radius_m")?,
            n_impacts: whole(W, &record, "n_impacts")?,
            inclination_cm_s: opt_num(W, &record, "inclination_cm_s")?,
            inclination_fit_cm_s: opt_num(W, &record, "inclination_fit_cm_s")?,
            u0_max_m_s: num(W, &record, "u0_max_m_s")?,
            zdot_abs_max_m_s: num(W, &record, "zdot_abs_max_m_s")?,
            spl_max_db: opt_num(W, &record, "spl_max_db")?,
            contact_duration_s: opt_num(W, &record, "contact_duration_s")?,
            restitution_mean: opt_num(W, &record, "restitution_mean")?,
            zone: zone_of(W, &record, "zone")?,
            impacts: columns(py, &impacts, template.as_ref(), &["wall"], &impact_order)?,
            maxima: columns(py, &maxima, Some(&maxima_template), &[], &maxima_order)?,
            energy: field(py, &record, "energy")?,
            final_time_s: num(W, &record, "final_time_s")?,
            truncated: flag(W, &record, "truncated")?,
            truncation_reason: opt_text(W, &record, "truncation_reason")?,
            steady: record.get("steady").map(|s| to_py(py, s)).transpose()?,
            history: history_dict.unbind(),
            record,
        })
    }

    /// Its pickled state: {"record": …, "history": [[name, [values…]], …]}.
    fn state(&self, py: Python<'_>) -> PyResult<Json> {
        let history = self.history.bind(py);
        let mut series = Vec::new();
        for (k, v) in history.iter() {
            let name: String = k.extract()?;
            let values: Vec<f64> = v.extract()?;
            series.push(serde_json::json!([name, values]));
        }
        Ok(serde_json::json!({"record": self.record, "history": series}))
    }

    /// The run of its pickled state: {"record": …, "history": [[name, [values…]], …]}.
    fn from_state(py: Python<'_>, state: Json) -> PyResult<PyRun> {
        let mut history = Vec::new();
        for item in state.get("history").and_then(Json::as_array).ok_or_else(|| missing("Run state", "history"))? {
            let name = item.get(0).and_then(Json::as_str).ok_or_else(|| missing("Run state", "history"))?;
            let values = item.get(1).and_then(Json::as_array).ok_or_else(|| missing("Run state", name))?;
            let values: Vec<f64> =
                values.iter().map(|v| v.as_f64().ok_or_else(|| missing("Run state", name))).collect::<PyResult<_>>()?;
            history.push((name.to_string(), values));
        }
        let record = state.get("record").cloned().ok_or_else(|| missing("Run state", "record"))?;
        Self::from_parts(py, record, history)
    }
}

#[pymethods]
impl PyRun {
    /// as_dict(json=False) -> dict
    ///
    /// Every field in one dict (the command line's JSON keys, plus "history"). json=True:
    /// plain lists, numbers and None only (NaN → None), ready for `json.dumps`.
    #[pyo3(signature = (json = false))]
    fn as_dict(&self, py: Python<'_>, json: bool) -> PyResult<Py<PyAny>> {
        let d = PyDict::new(py);
        d.set_item("design", self.design.clone_ref(py))?;
        d.set_item("ball_radius_m", self.ball_radius_m)?;
        d.set_item("n_impacts", self.n_impacts)?;
        d.set_item("inclination_cm_s", self.inclination_cm_s)?;
        d.set_item("inclination_fit_cm_s", self.inclination_fit_cm_s)?;
        d.set_item("u0_max_m_s", self.u0_max_m_s)?;
        d.set_item("zdot_abs_max_m_s", self.zdot_abs_max_m_s)?;
        d.set_item("spl_max_db", self.spl_max_db)?;
        d.set_item("contact_duration_s", self.contact_duration_s)?;
        d.set_item("restitution_mean", self.restitution_mean)?;
        d.set_item("zone", self.zone)?;
        d.set_item("impacts", self.impacts.clone_ref(py))?;
        d.set_item("maxima", self.maxima.clone_ref(py))?;
        d.set_item("energy", self.energy.clone_ref(py))?;
        d.set_item("final_time_s", self.final_time_s)?;
        d.set_item("truncated", self.truncated)?;
        d.set_item("truncation_reason", self.truncation_reason.clone())?;
        d.set_item("steady", self.steady.as_ref().map(|s| s.clone_ref(py)))?;
        d.set_item("history", self.history.clone_ref(py))?;
        plain(py, d, json)
    }

    /// impacts_frame() -> pandas.DataFrame
    ///
    /// Every impact as a row: t_s first, then the impact's fields in the record's order
    /// (units in the names); the design's scalars in `.attrs`. Needs pandas.
    fn impacts_frame(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "impacts_frame", slf.as_any())
    }

    /// history_frame() -> pandas.DataFrame
    ///
    /// The uniform time history as a table: t_s (s), x_m, y_m, x_free_m (m). Needs pandas.
    fn history_frame(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "history_frame", slf.as_any())
    }

    /// to_xarray() -> xarray.Dataset
    ///
    /// The time history on the dimension t_s (s): x_m, y_m, x_free_m (m); the metrics and the
    /// design in `.attrs`. Needs xarray.
    fn to_xarray(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "run_xarray", slf.as_any())
    }

    fn _repr_html_(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "repr_html", slf.as_any())
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        reduce(py, "Run", &self.state(py)?)
    }

    /// Equal when the records and the time histories are (an unpickled run equals its original).
    fn __eq__(&self, py: Python<'_>, other: PyRef<'_, Self>) -> PyResult<bool> {
        Ok(self.state(py)? == other.state(py)?)
    }

    fn __repr__(&self) -> String {
        let opt = |v: Option<f64>, digits: usize| v.map_or("None".into(), |x| format!("{x:.digits$}"));
        format!(
            "Run({}: {} impacts, e={} cm/s, e_fit={} cm/s, U0max={:.4} m/s, SPLmax={} dB, zone={}{})",
            named(&self.record),
            self.n_impacts,
            opt(self.inclination_cm_s, 4),
            opt(self.inclination_fit_cm_s, 4),
            self.u0_max_m_s,
            opt(self.spl_max_db, 2),
            self.zone.map_or("None".into(), |z| z.to_string()),
            if self.truncated { ", truncated" } else { "" }
        )
    }
}

/// One design run from N ball offsets (`thud.simulate(ensemble=N)`, N > 1): the zone of the
/// medians, how many runs are in zone 3 and agree with it, the p10/median/p90 of each metric
/// and every run — the fields of `thud simulate --ensemble N --json`.
#[pyclass(name = "Ensemble", module = "thud", frozen)]
pub struct PyEnsemble {
    /// The design (the JSON "design" object; its ball offset is each run's own).
    #[pyo3(get)]
    design: Py<PyAny>,
    /// Ball radius (m).
    #[pyo3(get)]
    ball_radius_m: f64,
    /// Runs N.
    #[pyo3(get)]
    runs: usize,
    /// The zone of the medians, 1–4.
    #[pyo3(get)]
    zone: Option<u8>,
    /// Fraction of the runs in zone 3.
    #[pyo3(get)]
    zone3_probability: f64,
    /// Fraction of the runs whose zone is the zone of the medians.
    #[pyo3(get)]
    agreement: f64,
    /// {"inclination_cm_s" | "inclination_fit_cm_s" (cm/s) | "u0_max_m_s" (m/s) |
    /// "spl_max_db" (dB): {"p10", "median", "p90"}} (None: the percentile falls among runs
    /// without the value).
    #[pyo3(get)]
    spread: Py<PyAny>,
    /// Every run, as arrays in order of k: ball_position_m (m), n_impacts, u0_max_m_s,
    /// zdot_abs_max_m_s (m/s), spl_max_db (dB), contact_duration_s (s), restitution_mean,
    /// inclination_cm_s, inclination_fit_cm_s (cm/s), zone (int8, 0 = none).
    #[pyo3(get)]
    ensemble: Py<PyDict>,
    /// Whether any run stopped at a solver work cap.
    #[pyo3(get)]
    truncated: bool,
    #[pyo3(get)]
    truncation_reason: Option<String>,
    record: Json,
}

impl PyEnsemble {
    pub fn new(py: Python<'_>, r: &EnsembleReport) -> PyResult<PyEnsemble> {
        Self::from_record(py, checked("ensemble", r)?)
    }

    /// The ensemble of the record of `thud simulate --ensemble N --json` (finite already).
    fn from_record(py: Python<'_>, record: Json) -> PyResult<PyEnsemble> {
        const W: &str = "ensemble";
        let members = rows_of(&record, "ensemble");
        let order = order_of::<Member>(members.first());
        Ok(PyEnsemble {
            design: field(py, &record, "design")?,
            ball_radius_m: num(W, &record, "ball_radius_m")?,
            runs: whole(W, &record, "runs")?,
            zone: zone_of(W, &record, "zone")?,
            zone3_probability: num(W, &record, "zone3_probability")?,
            agreement: num(W, &record, "agreement")?,
            spread: field(py, &record, "spread")?,
            ensemble: columns(py, &members, None, &[], &order)?,
            truncated: flag(W, &record, "truncated")?,
            truncation_reason: opt_text(W, &record, "truncation_reason")?,
            record,
        })
    }
}

#[pymethods]
impl PyEnsemble {
    /// as_dict(json=False) -> dict
    ///
    /// Every field in one dict (the command line's JSON keys; the runs as arrays). json=True:
    /// plain lists, numbers and None only (NaN → None), ready for `json.dumps`.
    #[pyo3(signature = (json = false))]
    fn as_dict(&self, py: Python<'_>, json: bool) -> PyResult<Py<PyAny>> {
        let d = PyDict::new(py);
        let runs = self.ensemble.clone_ref(py).into_any();
        fill(py, &d, &self.record, &["ensemble"], &[("ensemble", &runs)])?;
        plain(py, d, json)
    }

    /// to_dataframe() -> pandas.DataFrame
    ///
    /// One row per run (the index "run", in order of k), the columns of `thud simulate
    /// --ensemble N --csv` (`thud.schema()["ensemble"]`): ball_position_m, then each run's
    /// metrics; the zone 0 = none. Needs pandas.
    fn to_dataframe(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "ensemble_frame", slf.as_any())
    }

    /// to_xarray() -> xarray.Dataset
    ///
    /// Every run on the dimension run (k), with ball_position_m as a coordinate (m) and each
    /// run's metrics; the zone, its probability and the agreement in `.attrs`. Needs xarray.
    fn to_xarray(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "ensemble_xarray", slf.as_any())
    }

    fn _repr_html_(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "repr_html", slf.as_any())
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        reduce(py, "Ensemble", &self.record)
    }

    /// Equal when the records are (every run; an unpickled ensemble equals its original).
    fn __eq__(&self, other: PyRef<'_, Self>) -> bool {
        self.record == other.record
    }

    fn __repr__(&self) -> String {
        format!(
            "Ensemble({}: {} runs, zone of the medians {}, zone 3 in {:.0} % of the runs, {:.0} % agree{})",
            named(&self.record),
            self.runs,
            self.zone.map_or("None".into(), |z| z.to_string()),
            100.0 * self.zone3_probability,
            100.0 * self.agreement,
            if self.truncated { ", truncated" } else { "" }
        )
    }
}

/// The design chart of a sweep (`thud.sweep`): every metric as a 2-D array of shape
/// (len(gaps_m), len(masses_kg)) — row = gap, column = mass, as `pcolormesh(masses_kg, gaps_m,
/// chart.zone)` wants. NaN marks a value that does not exist (no impact: no SPLmax; too few
/// maxima: no e); zone 0 marks no zone. With `ensemble=N` the metrics are the medians of each
/// cell's runs and the ensemble fields are set.
#[pyclass(name = "Chart", module = "thud", frozen)]
pub struct PyChart {
    /// The design every cell varies (the command line's JSON "design" object).
    #[pyo3(get)]
    design: Py<PyAny>,
    /// Impact masses, the columns (kg).
    #[pyo3(get)]
    masses_kg: Py<PyAny>,
    /// Gaps, the rows (m).
    #[pyo3(get)]
    gaps_m: Py<PyAny>,
    /// Impacts per cell (int64).
    #[pyo3(get)]
    n_impacts: Py<PyAny>,
    /// e of Eq 27 (cm/s).
    #[pyo3(get)]
    inclination_cm_s: Py<PyAny>,
    /// e_fit (cm/s).
    #[pyo3(get)]
    inclination_fit_cm_s: Py<PyAny>,
    /// U0max (m/s).
    #[pyo3(get)]
    u0_max_m_s: Py<PyAny>,
    /// Largest |z'| (m/s).
    #[pyo3(get)]
    zdot_abs_max_m_s: Py<PyAny>,
    /// SPLmax (dB).
    #[pyo3(get)]
    spl_max_db: Py<PyAny>,
    /// Contact duration at U0max (s).
    #[pyo3(get)]
    contact_duration_s: Py<PyAny>,
    /// Mean restitution.
    #[pyo3(get)]
    restitution_mean: Py<PyAny>,
    /// Zone 1–4, 0 = none (int8).
    #[pyo3(get)]
    zone: Py<PyAny>,
    /// Zone thresholds: {"spl_db": L* (dB), "inclination_cm_s": e* (cm/s), "zone_by": "paper" | "fit"}.
    #[pyo3(get)]
    thresholds: Py<PyAny>,
    /// Runs per cell N (1: the single trajectory).
    #[pyo3(get)]
    runs: usize,
    /// Fraction of each cell's runs in zone 3 (2-D; None without an ensemble).
    #[pyo3(get)]
    zone3_probability: Option<Py<PyAny>>,
    /// Fraction of each cell's runs in the zone of its medians (2-D; None without an ensemble).
    #[pyo3(get)]
    agreement: Option<Py<PyAny>>,
    /// {metric: {"p10", "median", "p90"}} of e, e_fit, U0max and SPLmax, each 2-D (None
    /// without an ensemble).
    #[pyo3(get)]
    spread: Option<Py<PyAny>>,
    /// Every run of every cell: {"ball_position_m", metric…} as 3-D arrays (gap, mass, run)
    /// (None without an ensemble).
    #[pyo3(get)]
    ensemble: Option<Py<PyAny>>,
    /// The engine's chart (of the medians), kept for `Chart.table5`.
    chart: design::Chart,
    /// What the chart was made of, for pickling: {"design": …, "chart": the plain chart} or
    /// {"design": …, "ensembles": the chart of ensembles} (the engine's serde form).
    state: Json,
}

/// The parts of an ensemble chart beyond its medians, as arrays shaped (gap, mass, …).
struct EnsembleParts {
    zone3_probability: Py<PyAny>,
    agreement: Py<PyAny>,
    spread: Py<PyAny>,
    ensemble: Py<PyAny>,
}

impl EnsembleParts {
    fn new(py: Python<'_>, chart: &EnsembleChart) -> PyResult<EnsembleParts> {
        let record = checked("chart", chart)?;
        let cells = rows_of(&record, "cells");
        if cells.iter().any(Json::is_null) {
            return Err(pyo3::exceptions::PyRuntimeError::new_err("internal error: a cell of the chart is missing"));
        }
        let all = columns(py, &cells, None, &[], &[])?;
        let shaped = reshape(py, all.bind(py).as_any(), &[chart.gaps_m.len(), chart.masses_kg.len()])?;
        let shaped = shaped.bind(py);
        let get = |k: &str| -> PyResult<Py<PyAny>> { Ok(shaped.get_item(k)?.unbind()) };
        Ok(EnsembleParts {
            zone3_probability: get("zone3_probability")?,
            agreement: get("agreement")?,
            spread: get("spread")?,
            ensemble: get("ensemble")?,
        })
    }
}

impl PyChart {
    /// The chart `chart` of `d`; with the parts of an ensemble chart of `runs` runs a cell;
    /// `state` as the field says.
    fn with(
        py: Python<'_>,
        d: &Design,
        chart: design::Chart,
        runs: usize,
        parts: Option<EnsembleParts>,
        state: Json,
    ) -> PyResult<PyChart> {
        let (rows, cols) = (chart.gaps_m.len(), chart.masses_kg.len());
        let grid = |what: &str, f: &dyn Fn(&design::Metrics) -> Option<f64>| -> PyResult<Py<PyAny>> {
            let mut v = Vec::with_capacity(rows * cols);
            for c in &chart.cells {
                let x = c.as_ref().and_then(|c| f(&c.metrics));
                if x.is_some_and(|x| !x.is_finite()) {
                    return Err(non_finite(what));
                }
                v.push(x.unwrap_or(f64::NAN));
            }
            to_2d(py, rows, cols, v)
        };
        let n_impacts: Vec<i64> =
            chart.cells.iter().map(|c| c.as_ref().map_or(0, |c| c.metrics.n_impacts as i64)).collect();
        let zone: Vec<i8> = chart
            .cells
            .iter()
            .map(|c| c.as_ref().and_then(|c| c.metrics.zone).map_or(0, |z| z.number() as i8))
            .collect();
        let (zone3_probability, agreement, spread, ensemble) = match parts {
            Some(p) => (Some(p.zone3_probability), Some(p.agreement), Some(p.spread), Some(p.ensemble)),
            None => (None, None, None, None),
        };
        Ok(PyChart {
            design: json_data(py, "design", d)?,
            masses_kg: array(py, "masses_kg", chart.masses_kg.clone())?,
            gaps_m: array(py, "gaps_m", chart.gaps_m.clone())?,
            n_impacts: to_2d(py, rows, cols, n_impacts)?,
            inclination_cm_s: grid("inclination_cm_s", &|m| m.inclination_cm_s)?,
            inclination_fit_cm_s: grid("inclination_fit_cm_s", &|m| m.inclination_fit_cm_s)?,
            u0_max_m_s: grid("u0_max_m_s", &|m| Some(m.u0_max_m_s))?,
            zdot_abs_max_m_s: grid("zdot_abs_max_m_s", &|m| Some(m.zdot_abs_max_m_s))?,
            spl_max_db: grid("spl_max_db", &|m| m.spl_max_db)?,
            contact_duration_s: grid("contact_duration_s", &|m| m.contact_duration_s)?,
            restitution_mean: grid("restitution_mean", &|m| m.restitution_mean)?,
            zone: to_2d(py, rows, cols, zone)?,
            thresholds: json_data(py, "thresholds", &chart.thresholds)?,
            runs,
            zone3_probability,
            agreement,
            spread,
            ensemble,
            chart,
            state,
        })
    }

    /// The plain chart `chart` of `d`.
    pub fn new(py: Python<'_>, d: &Design, chart: design::Chart) -> PyResult<PyChart> {
        let state = serde_json::json!({"design": checked("design", d)?, "chart": checked("chart", &chart)?});
        Self::with(py, d, chart, 1, None, state)
    }

    /// The chart of ensembles `chart` of `d`: its medians, and the ensemble fields.
    pub fn of_ensembles(py: Python<'_>, d: &Design, chart: EnsembleChart) -> PyResult<PyChart> {
        let parts = EnsembleParts::new(py, &chart)?;
        let medians = chart.medians();
        let state = serde_json::json!({"design": checked("design", d)?, "ensembles": checked("chart", &chart)?});
        Self::with(py, d, medians, chart.runs, Some(parts), state)
    }

    /// The chart of its pickled state (see the `state` field).
    fn from_state(py: Python<'_>, state: Json) -> PyResult<PyChart> {
        let bad = |e: serde_json::Error| PyRuntimeError::new_err(format!("internal error: a Chart state: {e}"));
        let part = |k: &str| state.get(k).cloned().ok_or_else(|| missing("Chart state", k));
        let d: Design = serde_json::from_value(part("design")?).map_err(bad)?;
        // The design as every front end takes one: checked whole (a forged one is refused).
        d.clone()
            .check()
            .map_err(|e| PyRuntimeError::new_err(format!("internal error: a Chart state: design: {e}")))?;
        if state.get("ensembles").is_some() {
            return Self::of_ensembles(py, &d, serde_json::from_value(part("ensembles")?).map_err(bad)?);
        }
        Self::new(py, &d, serde_json::from_value(part("chart")?).map_err(bad)?)
    }
}

/// A (rows, cols) NumPy array of `v` (row-major: `v[row * cols + col]`).
fn to_2d<T: numpy::Element>(py: Python<'_>, rows: usize, cols: usize, v: Vec<T>) -> PyResult<Py<PyAny>> {
    let a = Array2::from_shape_vec((rows, cols), v)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("internal error: chart shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

#[pymethods]
impl PyChart {
    /// table5(band_cm_s=0.2) -> dict of arrays
    ///
    /// Table 5 of the paper: the spread of SPLmax among the designs in each band of the
    /// inclination (by the thresholds' zone_by) of width band_cm_s (cm/s), as `thud sweep
    /// --band`: {"e_lo_cm_s", "e_hi_cm_s" (cm/s), "count" (int64), "spl_min_db", "spl_max_db" (dB)}.
    #[pyo3(signature = (band_cm_s = 0.2, no_limit = false))]
    fn table5<'py>(&self, py: Python<'py>, band_cm_s: f64, no_limit: bool) -> PyResult<Bound<'py, PyDict>> {
        let chart = &self.chart;
        let band = limits::BAND.check_as("band_cm_s", band_cm_s).map_err(|e| engine_error(py, e))?;
        let zone_by = chart.thresholds.zone_by;
        if let Some((lo, hi)) = design::inclination_span(chart, zone_by) {
            let bands = limits::band_count(lo, hi, band);
            if bands.exceeded() && !no_limit {
                let msg = format!(
                    "invalid band_cm_s: {}; use band_cm_s ≥ {} cm/s, or pass no_limit=True",
                    bands.describe(),
                    short((hi - lo) / bands.cap.max)
                );
                return Err(parameter_error(py, "band_cm_s", msg));
            }
        }
        let rows = design::spl_range_by_inclination(chart, band, zone_by);
        let records: Vec<Json> = rows.iter().map(|b| checked("table5", b)).collect::<PyResult<_>>()?;
        let template =
            serde_json::json!({"e_lo_cm_s": 0.0, "e_hi_cm_s": 0.0, "count": 0, "spl_min_db": 0.0, "spl_max_db": 0.0});
        let order = rows.first().map(field_order).unwrap_or_default();
        Ok(columns(py, &records, Some(&template), &[], &order)?.into_bound(py))
    }

    /// as_dict(json=False) -> dict
    ///
    /// Every field in one dict (the 2-D arrays by metric name). json=True: nested lists,
    /// numbers and None only (NaN → None), ready for `json.dumps`.
    #[pyo3(signature = (json = false))]
    fn as_dict(&self, py: Python<'_>, json: bool) -> PyResult<Py<PyAny>> {
        let d = PyDict::new(py);
        for (k, v) in [
            ("design", &self.design),
            ("masses_kg", &self.masses_kg),
            ("gaps_m", &self.gaps_m),
            ("n_impacts", &self.n_impacts),
            ("inclination_cm_s", &self.inclination_cm_s),
            ("inclination_fit_cm_s", &self.inclination_fit_cm_s),
            ("u0_max_m_s", &self.u0_max_m_s),
            ("zdot_abs_max_m_s", &self.zdot_abs_max_m_s),
            ("spl_max_db", &self.spl_max_db),
            ("contact_duration_s", &self.contact_duration_s),
            ("restitution_mean", &self.restitution_mean),
            ("zone", &self.zone),
            ("thresholds", &self.thresholds),
        ] {
            d.set_item(k, v.clone_ref(py))?;
        }
        d.set_item("runs", self.runs)?;
        for (k, v) in [
            ("zone3_probability", &self.zone3_probability),
            ("agreement", &self.agreement),
            ("spread", &self.spread),
            ("ensemble", &self.ensemble),
        ] {
            d.set_item(k, v.as_ref().map(|v| v.clone_ref(py)))?;
        }
        plain(py, d, json)
    }

    /// to_dataframe() -> pandas.DataFrame
    ///
    /// The chart as a tidy table, one row per cell, the columns of `thud sweep --csv`
    /// (`thud.schema()["sweep"]`: mass_kg, gap_m, then every metric, zone 0 = none); with
    /// ensemble=N those of `thud sweep --ensemble N --csv` (`"sweep_ensemble"`: mass_kg, gap_m,
    /// runs, the medians as metrics, X_p10 / X_median / X_p90, zone3_probability, agreement;
    /// every run: `runs_frame()`). The thresholds and the design in `.attrs`. Needs pandas.
    fn to_dataframe(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "chart_frame", slf.as_any())
    }

    /// runs_frame() -> pandas.DataFrame
    ///
    /// A chart of ensembles, one row per run of each cell: run, mass_kg, gap_m,
    /// ball_position_m and the run's metrics (the columns of a CSV part of `thud sweep
    /// --shard` but its index and truncated). Needs pandas.
    fn runs_frame(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "chart_runs_frame", slf.as_any())
    }

    /// to_xarray() -> xarray.Dataset
    ///
    /// The chart as labelled arrays on the dimensions gap_m × mass_kg (coordinates in m and
    /// kg): every metric, and with ensemble=N zone3_probability, agreement, the spread as
    /// {metric}_p10 / _median / _p90 and every run on gap_m × mass_kg × run. Units in each
    /// variable's attrs. Needs xarray.
    fn to_xarray(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "chart_xarray", slf.as_any())
    }

    fn _repr_html_(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "repr_html", slf.as_any())
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        reduce(py, "Chart", &self.state)
    }

    /// Equal when what the charts were made of is (an unpickled chart equals its original).
    fn __eq__(&self, other: PyRef<'_, Self>) -> bool {
        self.state == other.state
    }

    fn __repr__(&self) -> String {
        let c = &self.chart;
        let zone3 = c.cells.iter().flatten().filter(|c| c.metrics.zone.is_some_and(|z| z.number() == 3)).count();
        let runs =
            if self.runs > 1 { format!(", {} runs a cell (zones of the medians)", self.runs) } else { String::new() };
        let span = |v: &[f64]| match (v.first(), v.last()) {
            (Some(a), Some(b)) if v.len() > 1 => format!("{}–{}", short(*a), short(*b)),
            (Some(a), _) => short(*a),
            _ => String::new(),
        };
        format!(
            "Chart({} masses {} kg × {} gaps {} m, {} cells in zone 3{runs})",
            c.masses_kg.len(),
            span(&c.masses_kg),
            c.gaps_m.len(),
            span(&c.gaps_m),
            zone3
        )
    }
}

/// The frequency response of a forced design (`thud.response`): per frequency the steady state
/// with the damper beside the closed form without it — the fields of `thud response --json`,
/// each sweep's points as arrays.
#[pyclass(name = "Response", module = "thud", frozen)]
pub struct PyResponse {
    /// The design at the first frequency (the JSON "design" object).
    #[pyo3(get)]
    design: Py<PyAny>,
    /// Force amplitude F0 (N).
    #[pyo3(get)]
    force_n: f64,
    /// Forcing periods N of each steady-state window.
    #[pyo3(get)]
    periods: u32,
    /// Whether each frequency started from the previous one's final state.
    #[pyo3(get)]
    continuation: bool,
    /// Runs per frequency N (1: the single trajectory).
    #[pyo3(get)]
    runs: usize,
    /// The sweeps: one from rest, or "up" then "down" with continuation. Each a dict:
    /// "direction" and, per frequency, arrays: freq_hz (Hz), amplitude_m and
    /// amplitude_linear_m (m; NaN: unbounded), reduction_db, leq_db (dB; NaN: no impact),
    /// impacts_per_period, periodic, settled, truncated (bool), window_start_s, window_end_s,
    /// final_time_s (s), periods, and "verdict" (the verdict on each point's motion, as
    /// columns: kind, impacts, periods, symmetric, …; `to_dataframe()` gives its labels). With ensemble=N: freq_hz, amplitude_linear_m,
    /// periodic_fraction, settled_fraction, truncated, "spread" {amplitude_m | reduction_db |
    /// impacts_per_period | leq_db: {"p10", "median", "p90"}} and "ensemble" (every run: 2-D
    /// arrays, frequency × run).
    #[pyo3(get)]
    sweeps: Py<PyList>,
    record: Json,
}

impl PyResponse {
    fn from_record(py: Python<'_>, record: Json, runs: usize) -> PyResult<PyResponse> {
        let sweeps = PyList::empty(py);
        for sweep in rows_of(&record, "sweeps") {
            let points = rows_of(&sweep, "points");
            let order = if runs > 1 {
                order_of::<EnsemblePoint>(points.first())
            } else {
                order_of::<ResponsePoint>(points.first())
            };
            let d = columns(py, &points, None, &[], &order)?.into_bound(py);
            d.set_item("direction", field(py, &sweep, "direction")?)?;
            sweeps.append(d)?;
        }
        let number = |k: &str| record.get(k).and_then(Json::as_f64).unwrap_or(f64::NAN);
        Ok(PyResponse {
            design: field(py, &record, "design")?,
            force_n: number("force_n"),
            periods: record.get("periods").and_then(Json::as_u64).map_or(0, |p| u32::try_from(p).unwrap_or(u32::MAX)),
            continuation: record.get("continuation").and_then(Json::as_bool).unwrap_or(false),
            runs,
            sweeps: sweeps.unbind(),
            record,
        })
    }

    pub fn new(py: Python<'_>, r: &ResponseReport) -> PyResult<PyResponse> {
        Self::from_record(py, checked("response", r)?, 1)
    }

    pub fn of_ensembles(py: Python<'_>, r: &ResponseEnsembleReport) -> PyResult<PyResponse> {
        Self::from_record(py, checked("response", r)?, r.runs)
    }

    /// The response of its pickled state: {"record": …, "runs": N}.
    fn from_state(py: Python<'_>, state: Json) -> PyResult<PyResponse> {
        let runs = whole("Response state", &state, "runs")?;
        let record = state.get("record").cloned().ok_or_else(|| missing("Response state", "record"))?;
        Self::from_record(py, record, runs)
    }
}

#[pymethods]
impl PyResponse {
    /// as_dict(json=False) -> dict
    ///
    /// Every field in one dict (the command line's JSON keys; each sweep's points as arrays).
    /// json=True: plain lists, numbers and None only (NaN → None), ready for `json.dumps`.
    #[pyo3(signature = (json = false))]
    fn as_dict(&self, py: Python<'_>, json: bool) -> PyResult<Py<PyAny>> {
        let d = PyDict::new(py);
        let sweeps = self.sweeps.clone_ref(py).into_any();
        fill(py, &d, &self.record, &["sweeps"], &[("sweeps", &sweeps)])?;
        d.set_item("runs", self.runs)?;
        plain(py, d, json)
    }

    /// to_dataframe() -> pandas.DataFrame
    ///
    /// One row per frequency of each sweep, the columns of `thud response --csv`
    /// (`thud.schema()["response"]`: direction, freq_hz, then the point's fields in the
    /// record's order; with ensemble=N `"response_ensemble"`: the spread as {figure}_p10 /
    /// _median / _p90). Needs pandas.
    fn to_dataframe(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "response_frame", slf.as_any())
    }

    /// to_xarray() -> xarray.Dataset
    ///
    /// The response on the dimensions direction × freq_hz (Hz; each sweep's points in rising
    /// frequency; NaN where a sweep has no point): every figure of a point, units in attrs.
    /// Needs xarray.
    fn to_xarray(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "response_xarray", slf.as_any())
    }

    fn _repr_html_(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "repr_html", slf.as_any())
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        reduce(py, "Response", &serde_json::json!({"record": self.record, "runs": self.runs}))
    }

    /// Equal when the records and the runs are (an unpickled response equals its original).
    fn __eq__(&self, other: PyRef<'_, Self>) -> bool {
        self.record == other.record && self.runs == other.runs
    }

    fn __repr__(&self) -> String {
        let points = self
            .record
            .get("sweeps")
            .and_then(Json::as_array)
            .and_then(|s| s.first())
            .map_or(0, |s| s.get("points").and_then(Json::as_array).map_or(0, Vec::len));
        let runs = if self.runs > 1 { format!(", {} runs a frequency", self.runs) } else { String::new() };
        format!(
            "Response({}, F0={} N: {} frequencies{}{runs})",
            named(&self.record),
            short(self.force_n),
            points,
            if self.continuation { ", up and down" } else { "" }
        )
    }
}
