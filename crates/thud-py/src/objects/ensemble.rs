//! `Ensemble`: one design from N ball offsets.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value as Json;
use thud_core::ensemble::Member;
use thud_core::report::EnsembleReport;

use super::convert::{
    checked, columns, field, fill, flag, frames, named, num, opt_text, order_of, plain, rows_of, whole, zone_of,
};
use super::pickle::{reduce, Reduced};

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
    pub(super) fn from_record(py: Python<'_>, record: Json) -> PyResult<PyEnsemble> {
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
