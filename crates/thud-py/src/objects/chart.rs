//! `Chart`: the design chart of a sweep.

use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value as Json;
use thud_core::design::{self, Design};
use thud_core::ensemble::EnsembleChart;
use thud_core::limits::{self, short};

use crate::args::{engine_error, non_finite, parameter_error};

use super::convert::{array, checked, columns, field_order, frames, json_data, missing, plain, reshape, rows_of};
use super::pickle::{reduce, Reduced};

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
    pub(super) fn from_state(py: Python<'_>, state: Json) -> PyResult<PyChart> {
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
pub(super) fn to_2d<T: numpy::Element>(py: Python<'_>, rows: usize, cols: usize, v: Vec<T>) -> PyResult<Py<PyAny>> {
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

    /// _ensemble_figure(pdf=False, size=None, title=True) -> bytes
    ///
    /// The figure `thud sweep --ensemble N --svg` (`pdf=True`: `--pdf`) draws for this chart of
    /// ensembles: each cell's median damping and SPLmax and the width of their p10–p90 band.
    #[pyo3(signature = (pdf = false, size = None, title = true))]
    fn _ensemble_figure<'py>(
        &self,
        py: Python<'py>,
        pdf: bool,
        size: Option<(f64, f64)>,
        title: bool,
    ) -> PyResult<Bound<'py, pyo3::types::PyBytes>> {
        let bad = |e: serde_json::Error| PyRuntimeError::new_err(format!("internal error: a Chart state: {e}"));
        let Some(ensembles) = self.state.get("ensembles") else {
            let msg = "invalid ensemble: a chart of one run a cell draws the zone chart (to_svg with figure=\"chart\")";
            return Err(parameter_error(py, "ensemble", msg.into()));
        };
        let e: EnsembleChart = serde_json::from_value(ensembles.clone()).map_err(bad)?;
        let d: Design = serde_json::from_value(self.state.get("design").cloned().unwrap_or_default()).map_err(bad)?;
        crate::render::check_size(py, size)?;
        let look = thud_render::svg::Look { size, title };
        let svg = thud_render::studies::ensemble_chart(&e, &thud_render::studies::ensemble_title(&e, &d), &look);
        let bytes = if pdf {
            thud_render::pdf::from_svg(&svg)
                .map_err(|e| engine_error(py, thud_core::ThudError::invalid("render", e.to_string())))?
        } else {
            svg.into_bytes()
        };
        Ok(pyo3::types::PyBytes::new(py, &bytes))
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
