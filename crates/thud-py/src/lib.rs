//! `thud` in Python: the engine of the `thud` app (`thud-core`) as a Python module, NumPy
//! arrays out.
//!
//! - `thud.pulse(**params) -> Pulse`: one Hertzian impact heard at one observer (`thud pulse`).
//! - `thud.simulate(**params) -> Run`: one damper design through its impacts (`thud simulate`).
//! - `thud.sweep(masses_kg, gaps_m, **params) -> Chart`: the design chart (`thud sweep`).
//! - `thud.response(freqs_hz=None, **params) -> Response`: the frequency response under the
//!   harmonic force (`thud response`; by default over the engine's band of the design).
//! - `thud.fit_structure(t_s, x, main_mass=…)`, `thud.fit_damper(t_s, x, **params)`:
//!   calibration from a measured free decay (`thud fit structure|damper`), dicts out.
//! - `ensemble=N` on `simulate` (then an `Ensemble`), `sweep` and `response`: N runs from
//!   ball offsets spread over the clearance, as `--ensemble N`.
//!
//! Parameters are the command line's long flags as keywords (`--main-mass` → `main_mass=`), in
//! the same SI units; the mapping and the range table are the engine's
//! ([`thud_core::params`], [`thud_core::limits`]), so a value the command line refuses raises
//! `thud.ParameterError` (a `ValueError`) with the same one line, the parameter spelled as
//! typed. The engine runs without the GIL (see the `detach` module). Every number handed out is checked
//! finite; a missing value (no impact, so no SPL) is `None`, or NaN inside an array.
//!
//! This is the native part, `thud._thud`, of the mixed package `thud` (`python/thud`): the
//! pure-Python `thud/__init__.py` wraps these functions with explicit keyword signatures built
//! at import from `_parameters()` (the engine's parameter table), turns `progress=True` into a
//! progress bar and holds the DataFrame / xarray converters (`thud/_frames.py`). The
//! Python-facing documentation is in the `#[pyo3]` items and the stub `python/thud/__init__.pyi`.

mod args;
mod caps;
#[path = "design.rs"]
mod design_search;
mod designfile;
mod detach;
mod fit;
mod objects;
mod orbits;
mod paper;
mod progress;
mod render;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use thud_core::design::{self, Design, ValidDesign};
use thud_core::limits::{self, short};
use thud_core::params::{self, Spelling};
use thud_core::report::{EnsembleReport, ResponseEnsembleReport, ResponseReport};
use thud_core::response::{self, ResponseOptions};
use thud_core::units::Kind;
use thud_core::{continuation, dynamics, ensemble, study, ThudError};

use args::{enforce, engine_error, parameter_error, refuse, Kwargs};
use objects::{PyChart, PyEnsemble, PyPulse, PyResponse, PyRun};
use progress::Progress;

/// The keywords each function takes beside the engine's named parameters (its run options),
/// as `_parameters()` hands them to the Python wrapper for the signatures.
const OPTIONS: [(&str, &[&str]); 13] = [
    ("pulse", &["preset", "design", "points", "no_limit"]),
    ("simulate", &["preset", "design", "samples", "ensemble", "no_limit"]),
    ("simulate_ensemble", &["preset", "design", "no_limit"]),
    ("sweep", &["preset", "design", "ensemble", "progress", "no_limit"]),
    ("response", &["preset", "design", "continuation", "ensemble", "progress", "no_limit"]),
    ("fit_damper", &["preset", "design", "quantity", "no_limit"]),
    ("study", &["preset", "design", "progress", "no_limit"]),
    ("bifurcation", &["preset", "design", "transient", "continuation", "branches", "progress", "no_limit"]),
    ("orbit", &["preset", "design", "period", "symmetric", "guess"]),
    ("continuation", &["preset", "design", "period", "symmetric"]),
    ("impact_map", &["preset", "design", "transient", "no_limit"]),
    ("basins", &["preset", "design", "transient", "no_limit"]),
    ("restitution", &["preset", "design", "no_limit"]),
];

/// Waveform points of a pulse unless `points` is given.
const POINTS_DEFAULT: usize = 2000;
/// Time-history samples of a run unless `samples` is given.
const SAMPLES_DEFAULT: usize = 2001;

/// The run options of the function `name` (see [`OPTIONS`]).
pub(crate) fn options(name: &str) -> &'static [&'static str] {
    OPTIONS.iter().find(|(n, _)| *n == name).map_or(&[], |(_, o)| o)
}

/// The starting design: the `design` option (a design file or a saved design's name, as the
/// command line's `--design`), else the preset named by the `preset` option (default:
/// "default"), as the command line loads it (the app's compiled-in preset files). The user's
/// config file is not read: a script gives the same numbers on every machine.
fn preset(py: Python<'_>, kw: &Kwargs<'_>, default: Option<&str>) -> PyResult<Option<Design>> {
    if let Some(file) = kw.option("design") {
        if kw.option("preset").is_some() {
            let msg = "invalid design: give design or preset, not both".to_string();
            return Err(args::parameter_error(py, "design", msg));
        }
        return designfile::load(py, file).map(Some);
    }
    match kw.text(py, "preset")?.as_deref().or(default) {
        None => Ok(None),
        Some(name) => thud_presets::preset(name).map(Some).map_err(|e| engine_error(py, e)),
    }
}

/// The design of a call: the preset, then the keyword parameters (the engine's mapping).
pub(crate) fn design_of(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<ValidDesign> {
    let base = preset(py, kw, Some("default"))?.unwrap_or_default();
    params::design(base, &kw.params, Spelling::Keyword).map_err(|e| engine_error(py, e))
}

/// pulse(**params) -> Pulse
///
/// The pressure pulse of one Hertzian impact at an observer (Eqs 1–24), as `thud pulse --json`.
///
/// Defaults are the paper's Fig 2 impact: an acrylic sphere a = 19.05 mm, m = 40.5 g,
/// U0 = 1.4 m/s, K_HZ = 5.6e8 N/m^1.5 on a fixed plate, heard as a dipole at r = 0.7 m, θ = 45°.
///
/// Options (numbers in SI units unless noted, or strings with a unit such as "19.05mm"):
///     preset: str — take the defaults from a preset (`thud.presets()`): its ball, K_HZ,
///         observer, source and air, and U0 = its v0; the target stays a fixed plate.
///     points: int — waveform points (default 2000),
///     no_limit: bool — lift the work cap on points.
/// The impact's keywords (sphere and plate: K_HZ from the materials, Eq 2; main_mass: a
/// movable target, K* = (m+M)/(mM), Eq 8) are listed under "Keywords" from the engine's table.
///
/// Raises ParameterError (a ValueError) naming the parameter for an unknown name, a wrong
/// type, NaN/inf or an out-of-range value — the command line's message and range table.
#[pyfunction]
#[pyo3(signature = (**params))]
fn pulse(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<PyPulse> {
    let kw = Kwargs::new(params, options("pulse"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let points = kw.count(py, "points", &limits::POINTS, POINTS_DEFAULT)?;
    let cap = limits::WAVEFORM_POINTS.max;
    enforce(py, limits::waveform_points(points), "points", &format!("use points ≤ {}", short(cap)), no_limit)?;
    let base = preset(py, &kw, None)?;
    let input = params::pulse(base.as_ref(), &kw.params, Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    let computed = detach::run(py, move |_| objects::PulseData::compute(&input, points))?;
    PyPulse::new(py, computed.map_err(|e| engine_error(py, e))?)
}

/// simulate(**params) -> Run
///
/// One impact-damper design through its impacts (Eqs 25–27), as `thud simulate --json`, plus
/// the time history.
///
/// Options (the design's keywords, numbers in SI units unless noted or strings with a unit
/// such as "40.5g", are listed under "Keywords" from the engine's parameter table):
///     preset: str — the starting design (default "default"; `thud.presets()` lists them),
///     samples: int — time-history samples (default 2001),
///     ensemble: int — N runs from ball offsets y0 = −d/2 + (k + ½)·d/N at rest (default 1);
///         N > 1 returns an Ensemble (not with ball_position),
///     no_limit: bool — lift the work caps.
///
/// Raises ParameterError (a ValueError) naming the parameter for an unknown name, a wrong
/// type, NaN/inf, an out-of-range value or a run over its work cap. Ctrl-C stops the run
/// (KeyboardInterrupt).
#[pyfunction]
#[pyo3(signature = (**params))]
fn simulate(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<Py<PyAny>> {
    let kw = Kwargs::new(params, options("simulate"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let samples = kw.count(py, "samples", &limits::SAMPLES, SAMPLES_DEFAULT)?;
    let runs = ensemble_runs(py, &kw)?;
    let given = |n: &str| args::given(&kw.params, n);
    if runs > 1 {
        return Ok(ensemble_of(py, &d, &kw, runs, no_limit)?.into_pyobject(py)?.into_any().unbind());
    }
    refuse(py, limits::check_run(&d, &given, samples), "samples", no_limit)?;
    let data = detach::run(py, |cancel| objects::RunData::compute(&d, samples, cancel))?;
    Ok(PyRun::new(py, data.map_err(|e| engine_error(py, e))?)?.into_pyobject(py)?.into_any().unbind())
}

/// simulate_ensemble(runs, **params) -> Ensemble
///
/// One design from `runs` ball offsets y0 = −d/2 + (k + ½)·d/N at rest, always an Ensemble
/// (even of one run): `simulate(ensemble=N)` with a return type a type checker knows.
/// Keywords: as for `simulate` (no samples, ensemble or ball_position).
#[pyfunction]
#[pyo3(signature = (runs, **params))]
fn simulate_ensemble(
    py: Python<'_>,
    runs: &Bound<'_, PyAny>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyEnsemble> {
    let kw = Kwargs::new(params, options("simulate_ensemble"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let given = PyDict::new(py);
    given.set_item("runs", runs)?;
    let n = Kwargs::new(Some(&given), &["runs"])?.count(py, "runs", &limits::ENSEMBLE, 1)?;
    // An ensemble of one run is still an ensemble here: refuse a ball offset the runs set.
    params::check_ensemble(n.max(2), ball_position_typed(&kw), Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    ensemble_of(py, &d, &kw, n, no_limit)
}

/// The ensemble of `runs` runs of `d`, its work checked first.
fn ensemble_of(py: Python<'_>, d: &ValidDesign, kw: &Kwargs<'_>, runs: usize, no_limit: bool) -> PyResult<PyEnsemble> {
    let given = |n: &str| args::given(&kw.params, n);
    refuse(py, limits::check_run(d, &given, 0), "samples", no_limit)?;
    refuse(py, limits::check_runs(d, &given, 1, runs), "ensemble", no_limit)?;
    let e = {
        let d = d.clone();
        detach::run(py, move |cancel| ensemble::evaluate(&d, runs, Some(cancel)))?
    };
    let e = e.map_err(|e| engine_error(py, e))?.ok_or_else(|| cancelled(py))?;
    PyEnsemble::new(py, &EnsembleReport::new(d, &e))
}

/// The `ensemble` option (a count, default 1), refused with `ball_position` when over 1.
fn ensemble_runs(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<usize> {
    let runs = kw.count(py, "ensemble", &limits::ENSEMBLE, 1)?;
    params::check_ensemble(runs, ball_position_typed(kw), Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    Ok(runs)
}

/// Whether the call gave the ball's start (`ball_position`).
fn ball_position_typed(kw: &Kwargs<'_>) -> bool {
    kw.params.iter().any(|(n, _)| *n == Spelling::Keyword.key("ball-position"))
}

/// The error of runs stopped without an interrupt (not expected: a stop comes from Ctrl-C).
pub(crate) fn cancelled(py: Python<'_>) -> PyErr {
    engine_error(py, ThudError::Cancelled)
}

/// An axis of a sweep: a sequence of numbers in SI units, or "FROM:TO:N" text as on the
/// command line ("30g:100g:20"), each value inside `range`.
pub(crate) fn axis(
    py: Python<'_>,
    name: &str,
    value: &Bound<'_, PyAny>,
    kind: Kind,
    range: &limits::Range,
) -> PyResult<Vec<f64>> {
    let values: Vec<f64> = if let Ok(s) = value.cast::<PyString>() {
        params::parse_range(name, &s.to_cow()?, kind, range).map_err(|e| engine_error(py, e))?
    } else {
        let seq: Vec<Bound<'_, PyAny>> = if let Ok(it) = value.try_iter() {
            it.collect::<PyResult<_>>()?
        } else {
            let what = args::kind_of(value);
            let msg =
                format!("invalid {name}: expected a sequence of numbers in {} or 'FROM:TO:N', not {what}", range.unit);
            return Err(parameter_error(py, name, msg));
        };
        let mut out = Vec::with_capacity(seq.len());
        for v in &seq {
            if v.is_instance_of::<pyo3::types::PyInt>()
                && !v.is_instance_of::<pyo3::types::PyBool>()
                && v.extract::<f64>().is_err()
            {
                // An int beyond any float (`10**400`): out of range, named as such.
                return Err(args::huge_int(py, name, v));
            }
            let x = match args::to_value(v)? {
                params::Input::Num(x) => x,
                params::Input::Text(t) => thud_core::units::parse(name, &t, kind).map_err(|e| engine_error(py, e))?,
                _ => {
                    let msg = format!("invalid {name}: expected numbers in {}, not {}", range.unit, args::kind_of(v));
                    return Err(parameter_error(py, name, msg));
                }
            };
            out.push(range.check_as(name, x).map_err(|e| engine_error(py, e))?);
        }
        out
    };
    if values.is_empty() || values.len() as f64 > limits::GRID_N.max {
        let msg = format!("invalid {name}: {} values; give 1 to {}", values.len(), short(limits::GRID_N.max));
        return Err(parameter_error(py, name, msg));
    }
    Ok(values)
}

/// sweep(masses_kg, gaps_m, **params) -> Chart
///
/// The design chart: the design (preset and keyword parameters, as for `simulate`) run for every
/// impact mass × gap on all cores, as `thud sweep --json`.
///
/// masses_kg, gaps_m: sequences of numbers (kg, m), or "FROM:TO:N" text as on the command line
/// ("30g:100g:20", "2cm:5cm:20": N evenly spaced values, the command line's very numbers).
/// Keywords: as for `simulate` (no `samples`); ensemble: int — N runs a cell (the metrics are
/// then the medians, with zone3_probability, agreement, spread and every run); no_limit: bool
/// — lift the work caps.
///
/// The chart's 2-D arrays have shape (len(gaps_m), len(masses_kg)): row = gap, column = mass.
/// progress: a callable progress(done, total) called with the engine's count of finished
/// cells (at most every 0.1 s, and at the end), or True for a bar on stderr (tqdm if
/// installed); an exception it raises stops the sweep and propagates.
///
/// Raises ParameterError (a ValueError) as `simulate` does. Ctrl-C stops the sweep.
#[pyfunction]
#[pyo3(signature = (masses_kg, gaps_m, **params))]
fn sweep(
    py: Python<'_>,
    masses_kg: &Bound<'_, PyAny>,
    gaps_m: &Bound<'_, PyAny>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyChart> {
    let kw = Kwargs::new(params, options("sweep"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let masses = axis(py, "masses_kg", masses_kg, Kind::Mass, &limits::MASS)?;
    let gaps = axis(py, "gaps_m", gaps_m, Kind::Length, &limits::GAP)?;
    let runs = ensemble_runs(py, &kw)?;
    let given = |n: &str| args::given(&kw.params, n);
    refuse(py, limits::check_sweep(&d, &given, masses.len(), gaps.len()), "masses_kg", no_limit)?;
    let n = masses.len() * gaps.len();
    let progress = Progress::new(py, &kw, n)?;
    let done = &progress.done;
    if runs > 1 {
        refuse(py, limits::check_runs(&d, &given, n, runs), "ensemble", no_limit)?;
        let chart = detach::run_watched(
            py,
            |cancel| ensemble::sweep(&d, &masses, &gaps, runs, Some(cancel), &|_, _| Progress::tick(done)),
            || progress.report(),
        )?;
        return PyChart::of_ensembles(py, &d, chart.map_err(|e| engine_error(py, e))?);
    }
    let chart = detach::run_watched(
        py,
        |cancel| design::sweep(&d, &masses, &gaps, Some(cancel), &|_, _| Progress::tick(done)),
        || progress.report(),
    )?;
    PyChart::new(py, &d, chart.map_err(|e| engine_error(py, e))?)
}

/// response(freqs_hz=None, **params) -> Response
///
/// The frequency response of a design under the harmonic force F0·cos(2π·f·t) on the main
/// mass, as `thud response --json`: per frequency the steady amplitude with the damper beside
/// the closed form without it (m), the cut (dB), the impacts per period and the level Leq of
/// the rattle (dB re 20 µPa), over the last `periods` forcing periods of a settled run.
///
/// freqs_hz: a sequence of frequencies (Hz), or "FROM:TO:N" text as on the command line
/// ("3Hz:8Hz:101"); None (the default): 0.6–1.6 × the natural frequency, 101 points, as the
/// command line without --freqs. Keywords: as for `simulate` (force is needed; no freq, no samples; each
/// frequency starts from rest unless v0, ball_position or ball_velocity is given), and
/// continuation: bool — each frequency from the previous one's final state, rising then
/// falling; ensemble: int — N runs a frequency from ball offsets y0 = −d/2 + (k + ½)·d/N
/// (p10/median/p90 of each figure, and every run); no_limit: bool — lift the work caps.
///
/// progress: as for `sweep`, counting the points of every run (each sweep of a continuation).
///
/// Raises ParameterError (a ValueError) as `simulate` does. Ctrl-C stops the response.
#[pyfunction]
#[pyo3(name = "response", signature = (freqs_hz=None, **params))]
fn response_curve(
    py: Python<'_>,
    freqs_hz: Option<&Bound<'_, PyAny>>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyResponse> {
    let kw = Kwargs::new(params, options("response"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let continuation = kw.switch(py, "continuation")?;
    let typed = freqs_hz.filter(|f| !f.is_none()).map(|f| axis(py, "freqs_hz", f, Kind::Frequency, &limits::FREQ));
    let base = preset(py, &kw, Some("default"))?.unwrap_or_default();
    // The design first, then its frequencies: freqs_hz, or the engine's default band.
    let (d, freqs) = params::response_setup(base, &kw.params, Spelling::Keyword, typed.transpose()?, "force")
        .map_err(|e| engine_error(py, e))?;
    let runs = ensemble_runs(py, &kw)?;
    check_response(py, &d, &freqs, continuation, runs, no_limit)?;
    let opts = ResponseOptions { continuation, settle: true };
    // The engine's count: every point of every run, each sweep of a continuation.
    let points = freqs.len() * runs * if continuation { 2 } else { 1 };
    let progress = Progress::new(py, &kw, points)?;
    let done = &progress.done;
    if runs > 1 {
        let r = detach::run_watched(
            py,
            |cancel| response::response_ensemble(&d, &freqs, runs, &opts, Some(cancel), &|| Progress::tick(done)),
            || progress.report(),
        )?;
        let r = r.map_err(|e| engine_error(py, e))?;
        return PyResponse::of_ensembles(py, &ResponseEnsembleReport::new(&d, &r, continuation));
    }
    let r = detach::run_watched(
        py,
        |cancel| response::response(&d, &freqs, &opts, Some(cancel), &|| Progress::tick(done)),
        || progress.report(),
    )?;
    let r = r.map_err(|e| engine_error(py, e))?;
    PyResponse::new(py, &ResponseReport::new(&d, &r, continuation))
}

/// Refuses a response of `runs` runs a frequency whose work is over a cap, as the command
/// line does: the forcing periods and Newmark steps over all runs, the cycles of one run.
fn check_response(
    py: Python<'_>,
    d: &ValidDesign,
    freqs: &[f64],
    continuation: bool,
    runs: usize,
    no_limit: bool,
) -> PyResult<()> {
    let r = response::check_response(d, freqs, continuation, runs);
    let counted = match &r {
        Err(e) if e.param == limits::RUNS_PARAM => "ensemble",
        _ => "freqs_hz",
    };
    refuse(py, r, counted, no_limit)
}

/// The varied parameters of a study: `(keyword, values)` pairs, each a numeric row of the
/// engine's table at values in its plain unit, checked by the engine's one parser
/// ([`study::Vary::of_values`]).
fn varies(py: Python<'_>, axes: &Bound<'_, PyList>) -> PyResult<Vec<study::Vary>> {
    let mut out = Vec::with_capacity(axes.len());
    for item in axes.iter() {
        let (name, values): (String, Vec<Bound<'_, PyAny>>) = item.extract()?;
        out.push(vary_of(py, &name, &values)?);
    }
    Ok(out)
}

/// A varied frequency supplies the design's frequency where none is given (its first value),
/// so `freq=[…]` with a force alone is a forced design.
pub(crate) fn frequency_from_vary(kw: &mut Kwargs<'_>, vary: &study::Vary) {
    let freq = Spelling::Keyword.key("freq");
    if vary.name() == "freq" && !args::given(&kw.params, "freq") {
        if let Some(&f) = vary.values.first() {
            kw.params.push((freq, params::Input::Num(f)));
        }
    }
}

/// The keyword `name` at `values` (numbers in the row's plain unit, or text with a unit).
pub(crate) fn vary_of(py: Python<'_>, name: &str, values: &[Bound<'_, PyAny>]) -> PyResult<study::Vary> {
    let row = study::numeric_row(name, Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    let kind = match row.accepts {
        params::Accepts::Quantity { kind, .. } => Some(kind),
        _ => None,
    };
    let mut xs = Vec::with_capacity(values.len());
    for v in values {
        let x = match (args::to_value(v)?, kind) {
            (params::Input::Num(x), _) => x,
            (params::Input::Text(t), Some(kind)) => {
                thud_core::units::parse(name, &t, kind).map_err(|e| engine_error(py, e))?
            }
            _ => {
                let msg = format!("invalid {name}: expected numbers to vary, not {}", args::kind_of(v));
                return Err(parameter_error(py, name, msg));
            }
        };
        xs.push(x);
    }
    study::Vary::of_values(name, &xs, Spelling::Keyword).map_err(|e| engine_error(py, e))
}

/// _study(axes, **params) -> str
///
/// A study over any numeric parameters (`thud sweep --vary … --json`): `axes` is a list of
/// (keyword, values); the grid is their product in C order. Returns the JSON `thud sweep --vary
/// --json` prints ({"design", "axes", "cells"}); `thud.sweep(v0=[…], c1=[…])` turns it into an
/// xarray Dataset (`thud._frames.study_xarray`).
#[pyfunction]
#[pyo3(signature = (axes, **params))]
fn _study(py: Python<'_>, axes: &Bound<'_, PyList>, params: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    let kw = Kwargs::new(params, options("study"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let grid = study::Grid::new(d.clone(), varies(py, axes)?, Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    let given = |n: &str| args::given(&kw.params, n);
    refuse(py, study::check_grid(&grid, &given), "axes", no_limit)?;
    let progress = Progress::new(py, &kw, grid.cells())?;
    let done = &progress.done;
    let s = detach::run_watched(
        py,
        |cancel| study::sweep(&grid, Some(cancel), &|_, _| Progress::tick(done)),
        || progress.report(),
    )?;
    let s = s.map_err(|e| engine_error(py, e))?;
    if s.cells.len() < grid.cells() {
        return Err(cancelled(py));
    }
    thud_core::finite::check(&s).map_err(|e| args::non_finite(&e.0))?;
    // Each axis with its column as `sweep --vary --csv` heads it (`v0_m_s`): Python's dimension.
    let mut axes =
        serde_json::to_value(&s.axes).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))?;
    if let Some(list) = axes.as_array_mut() {
        for (a, axis) in list.iter_mut().zip(&s.axes) {
            if let Some(m) = a.as_object_mut() {
                m.insert("column".into(), axis.column().into());
            }
        }
    }
    json_of(py, &serde_json::json!({ "design": d.design(), "axes": axes, "cells": s.cells }))
}

/// _bifurcation(name, values, **params) -> str
///
/// The bifurcation diagram of a forced design over one parameter (`thud bifurcation --vary
/// NAME=… --json`): per value the stroboscopic samples, the impacts and the orbit's type.
/// Options: transient (periods before sampling, default 200), periods (sampled, default
/// here 100), continuation, branches (N seed values: the continued branches to draw over the
/// figure, as `--branches N`). Returns the JSON; `thud.bifurcation` turns it into xarray.
#[pyfunction]
#[pyo3(signature = (name, values, **params))]
fn _bifurcation(
    py: Python<'_>,
    name: &str,
    values: Vec<Bound<'_, PyAny>>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let mut kw = Kwargs::new(params, options("bifurcation"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let continuation = kw.switch(py, "continuation")?;
    let vary = vary_of(py, name, &values)?;
    frequency_from_vary(&mut kw, &vary);
    let d = design_of(py, &kw)?;
    let transient = kw.count(py, "transient", &limits::TRANSIENT, dynamics::DEFAULT_TRANSIENT_PERIODS as usize)?;
    let periods = if args::given(&kw.params, "periods") { d.damper.steady_periods } else { dynamics::DEFAULT_PERIODS };
    let s = dynamics::Settings { transient_periods: u32::try_from(transient).unwrap_or(u32::MAX), periods };
    refuse(py, dynamics::check_work(vary.values.len(), s, continuation), "values", no_limit)?;
    let seeds = branch_seeds(py, &kw, &d, no_limit)?;
    let n = vary.values.len() * if continuation { 2 } else { 1 };
    let progress = Progress::new(py, &kw, n)?;
    let done = &progress.done;
    let b = detach::run_watched(
        py,
        |cancel| dynamics::bifurcation(&d, &vary, s, continuation, "force", Some(cancel), &|_| Progress::tick(done)),
        || progress.report(),
    )?;
    let b = b.map_err(|e| engine_error(py, e))?;
    thud_core::finite::check(&b).map_err(|e| args::non_finite(&e.0))?;
    // The parameter's column as `bifurcation --csv` heads it (`freq_hz`): Python's coordinate.
    let column = study::column(vary.name(), vary.unit());
    let mut record = serde_json::json!({ "design": d.design(), "bifurcation": b, "column": column });
    if let Some(n) = seeds {
        let branches = {
            let d = d.clone();
            detach::run(py, move |cancel| continuation::continue_family(&d, &vary, n, Some(cancel), &|_| {}))?
        };
        let branches = branches.map_err(|e| engine_error(py, orbits::keyword(e)))?;
        thud_core::finite::check(&branches).map_err(|e| args::non_finite(&e.0))?;
        record["branches"] = orbits::branches_json(py, &branches)?;
    }
    json_of(py, &record)
}

/// `branches=N` of `bifurcation`: a whole number of seed values from 2 to
/// [`continuation::MAX_SEEDS`] with the event solver, checked as `thud bifurcation --branches`.
fn branch_seeds(
    py: Python<'_>,
    kw: &Kwargs<'_>,
    d: &thud_core::design::ValidDesign,
    no_limit: bool,
) -> PyResult<Option<usize>> {
    let Some(v) = kw.option("branches") else { return Ok(None) };
    let max = continuation::MAX_SEEDS;
    // As the command line reads `--branches N`: a number (or its text) that is whole.
    let n = if v.is_instance_of::<pyo3::types::PyBool>() {
        None
    } else if let Ok(s) = v.cast::<PyString>() {
        s.to_cow()?.trim().parse::<f64>().ok()
    } else {
        v.extract::<f64>().ok()
    };
    let n = n.filter(|x| x.fract() == 0.0 && (2.0..=max as f64).contains(x)).ok_or_else(|| {
        let shown = v.repr().map_or_else(|_| "?".to_string(), |r| r.to_string());
        parameter_error(
            py,
            "branches",
            format!("invalid branches: {shown}; give a whole number of seed values from 2 to {max}"),
        )
    })?;
    if d.solver != thud_core::damper::Solver::Event {
        return Err(parameter_error(
            py,
            "solver",
            "invalid solver: newmark: orbits are continued with the event solver; use solver=\"event\" with branches"
                .into(),
        ));
    }
    let n = n as usize;
    enforce(py, limits::family_seed_periods(n), "branches", "give fewer seed values", no_limit)?;
    Ok(Some(n))
}

/// `v` (its numbers checked finite before) as JSON text.
pub(crate) fn json_of(py: Python<'_>, v: &serde_json::Value) -> PyResult<String> {
    serde_json::to_string(v).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))
}

/// axis(name, spec) -> numpy.ndarray
///
/// The values of a sweep axis given as "FROM:TO:N" text, exactly as the command line computes
/// them: name is "masses" (kg) or "gaps" (m); e.g. axis("masses", "30g:100g:20").
#[pyfunction]
#[pyo3(name = "axis")]
fn axis_values<'py>(py: Python<'py>, name: &str, spec: &str) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let (kind, range) = match name {
        "masses" => (Kind::Mass, &limits::MASS),
        "gaps" => (Kind::Length, &limits::GAP),
        _ => {
            return Err(parameter_error(py, "name", format!("invalid name: '{name}'; one of: masses, gaps")));
        }
    };
    let v = params::parse_range(name, spec, kind, range).map_err(|e| engine_error(py, e))?;
    Ok(numpy::PyArray1::from_vec(py, v))
}

/// presets() -> dict[str, str]
///
/// The named starting designs (`preset=`), each with its one-line description.
#[pyfunction]
fn presets(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for p in thud_presets::list().map_err(|e| engine_error(py, e))? {
        d.set_item(p.name, p.description)?;
    }
    Ok(d)
}

/// ranges() -> list[dict]
///
/// The valid range of every numeric parameter (the command line's `thud limits`), in the
/// units of a plain number: [{"param": "mass", "what": "ball mass m", "min": 0.0001,
/// "max": 100.0, "unit": "kg", "reason": …}, …]. `param` is the keyword.
#[pyfunction]
fn ranges(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let rows = PyList::empty(py);
    for r in params::listed_ranges() {
        let row = PyDict::new(py);
        row.set_item("param", Spelling::Keyword.spell(r.param))?;
        row.set_item("what", r.what)?;
        row.set_item("min", r.min)?;
        row.set_item("max", r.max)?;
        row.set_item("unit", r.unit)?;
        row.set_item("reason", r.reason)?;
        rows.append(row)?;
    }
    Ok(rows)
}

/// thud — design single-unit impact dampers: Hertz contact, impact noise, the damper and its
/// design chart, on the engine of the `thud` terminal app (identical numbers).
///
/// pulse(**params) -> Pulse, simulate(**params) -> Run (or Ensemble with ensemble=N),
/// sweep(masses_kg, gaps_m, **params) -> Chart, response(freqs_hz, **params) -> Response.
/// Parameters are the command line's long flags as keywords (--main-mass →
/// main_mass=), SI units (angles in degrees), or strings with units ("40.5g"). Bad input
/// raises ParameterError (a ValueError) naming the parameter. The GIL is released while the
/// engine runs.
/// _parameters() -> dict
///
/// The keywords of every function, for the Python wrapper's signatures: {"design": rows,
/// "pulse": rows, "options": {function: [option, …]}, "refused": {function: [keyword, …]}},
/// a row {"name": keyword, "accepts": "quantity" | "choice" | "name" | "switch" | "count",
/// "help": its line of help, "range": its range as text (or None), "doc": the line the
/// docstrings show ([`params::Param::doc_line`]), "unit": the plain number's unit (quantities
/// and counts), "choices": [names] (choices)},
/// and "defaults": {option: its default} — the engine's tables ([`params::DESIGN`], [`params::PULSE`]) in their order.
#[pyfunction]
fn _parameters(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("design", table_rows(py, params::DESIGN)?)?;
    d.set_item("pulse", table_rows(py, params::PULSE)?)?;
    let opts = PyDict::new(py);
    for (name, o) in OPTIONS {
        opts.set_item(name, o.to_vec())?;
    }
    d.set_item("options", opts)?;
    let defaults = PyDict::new(py);
    defaults.set_item("points", POINTS_DEFAULT)?;
    defaults.set_item("samples", SAMPLES_DEFAULT)?;
    defaults.set_item("ensemble", 1)?;
    defaults.set_item("continuation", false)?;
    defaults.set_item("no_limit", false)?;
    defaults.set_item("progress", py.None())?;
    defaults.set_item("quantity", "x")?;
    defaults.set_item("transient", dynamics::DEFAULT_TRANSIENT_PERIODS)?;
    defaults.set_item("design", py.None())?;
    defaults.set_item("period", py.None())?;
    defaults.set_item("symmetric", false)?;
    defaults.set_item("guess", py.None())?;
    defaults.set_item("branches", py.None())?;
    d.set_item("defaults", defaults)?;
    let refused = PyDict::new(py);
    // A response sweeps the frequency itself (`params::response_design` refuses `freq`).
    refused.set_item("response", vec![Spelling::Keyword.spell("freq")])?;
    // An ensemble sets each run's ball offset (`params::check_ensemble`).
    refused.set_item("simulate_ensemble", vec![Spelling::Keyword.spell("ball-position")])?;
    // A damper fit spreads the ball's start itself (an ensemble over starts).
    refused.set_item("fit_damper", vec![Spelling::Keyword.spell("ball-position")])?;
    // The basins set the ball's start themselves.
    refused
        .set_item("basins", vec![Spelling::Keyword.spell("ball-position"), Spelling::Keyword.spell("ball-velocity")])?;
    d.set_item("refused", refused)?;
    Ok(d)
}

/// The rows of one parameter table as dicts (see `_parameters()`).
fn table_rows<'py, T>(py: Python<'py>, table: &[params::Param<T>]) -> PyResult<Bound<'py, PyList>> {
    let rows = PyList::empty(py);
    for p in table {
        let row = PyDict::new(py);
        row.set_item("name", Spelling::Keyword.spell(p.name))?;
        row.set_item("help", p.help)?;
        row.set_item("range", p.range().map(limits::Range::describe))?;
        row.set_item("doc", p.doc_line(Spelling::Keyword))?;
        let accepts = match &p.accepts {
            params::Accepts::Quantity { range, .. } => {
                row.set_item("unit", range.unit)?;
                "quantity"
            }
            params::Accepts::Choice { names, .. } => {
                row.set_item("choices", names.to_vec())?;
                "choice"
            }
            params::Accepts::Name { .. } => "name",
            params::Accepts::Switch { .. } => "switch",
            params::Accepts::Count { range, .. } => {
                row.set_item("unit", range.unit)?;
                "count"
            }
        };
        row.set_item("accepts", accepts)?;
        rows.append(row)?;
    }
    Ok(rows)
}

/// schema() -> dict
///
/// The one data schema: {table: [(name, unit, meaning), …]} for every table thud writes, the
/// columns in order — the command line's CSV headers (`pulse`, `history`, `impacts`,
/// `ensemble`, `sweep`, `sweep_ensemble`, `shard_part`, `response`, `response_ensemble`,
/// `study`, `bifurcation`, `impact_map`, `basins`, `restitution`, `orbit`, `continuation`) and
/// the columns of the DataFrames (`Pulse.to_dataframe()`, `Run.history_frame()`, …). The name
/// "{varied}" stands for one column per varied parameter, named by its keyword and unit
/// (`v0_m_s`, `freq_hz`).
#[pyfunction]
fn schema(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for t in &thud_core::schema::TABLES {
        let cols: Vec<(&str, &str, &str)> = t.columns.iter().map(|c| (c.name, c.unit, c.doc)).collect();
        out.set_item(t.id, cols)?;
    }
    Ok(out)
}

#[pymodule]
#[pyo3(name = "_thud")]
fn thud_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    // NumPy's C API is imported on the first array made, running Python code: a Ctrl-C
    // pending then made the numpy crate panic (PanicException). Imported here instead, where
    // an error is an ImportError, and no array conversion runs Python code later.
    drop(numpy::PyArray1::<f64>::from_vec(py, vec![0.0]));
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ParameterError", py.get_type::<args::ParameterError>())?;
    m.add_class::<PyPulse>()?;
    m.add_class::<PyRun>()?;
    m.add_class::<PyEnsemble>()?;
    m.add_class::<PyChart>()?;
    m.add_class::<PyResponse>()?;
    m.add_function(wrap_pyfunction!(pulse, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_ensemble, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(response_curve, m)?)?;
    m.add_function(wrap_pyfunction!(_study, m)?)?;
    m.add_function(wrap_pyfunction!(_bifurcation, m)?)?;
    m.add_function(wrap_pyfunction!(orbits::_orbit, m)?)?;
    m.add_function(wrap_pyfunction!(orbits::_continuation, m)?)?;
    m.add_function(wrap_pyfunction!(orbits::_impact_map, m)?)?;
    m.add_function(wrap_pyfunction!(orbits::_basins, m)?)?;
    m.add_function(wrap_pyfunction!(orbits::_restitution, m)?)?;
    m.add_function(wrap_pyfunction!(render::_render, m)?)?;
    m.add_function(wrap_pyfunction!(render::_figure, m)?)?;
    m.add_function(wrap_pyfunction!(axis_values, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(ranges, m)?)?;
    m.add_function(wrap_pyfunction!(caps::limits, m)?)?;
    m.add_function(wrap_pyfunction!(paper::_paper, m)?)?;
    m.add_function(wrap_pyfunction!(paper::paper_ids, m)?)?;
    m.add_function(wrap_pyfunction!(schema, m)?)?;
    m.add_function(wrap_pyfunction!(_parameters, m)?)?;
    m.add_function(wrap_pyfunction!(objects::_restore, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_structure, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_damper, m)?)?;
    m.add_function(wrap_pyfunction!(design_search::_design, m)?)?;
    m.add_class::<design_search::PyDesigner>()?;
    Ok(())
}
