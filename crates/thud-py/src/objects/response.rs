//! `Response`: the frequency response of a forced design.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value as Json;
use thud_core::limits::short;
use thud_core::report::{ResponseEnsembleReport, ResponseReport};
use thud_core::response::{EnsemblePoint, ResponsePoint};

use super::convert::{checked, columns, field, fill, frames, missing, named, order_of, plain, rows_of, whole};
use super::pickle::{reduce, Reduced};

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
    pub(super) fn from_record(py: Python<'_>, record: Json, runs: usize) -> PyResult<PyResponse> {
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
    pub(super) fn from_state(py: Python<'_>, state: Json) -> PyResult<PyResponse> {
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
