//! `Run`: one design through its impacts.

use std::sync::atomic::AtomicBool;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value as Json;
use thud_core::damper::{free_response, HistoryPoint, Maximum};
use thud_core::design::{self, ValidDesign};
use thud_core::report::{ImpactReport, RunReport};
use thud_core::ThudError;

use super::convert::{
    array, checked, columns, field, field_order, flag, frames, missing, named, num, opt_num, opt_text, order_of, plain,
    rows_of, to_py, whole, zone_of,
};
use super::pickle::{reduce, Reduced};

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
    pub(super) fn from_state(py: Python<'_>, state: Json) -> PyResult<PyRun> {
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
