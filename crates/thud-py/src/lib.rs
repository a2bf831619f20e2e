//! `thud` in Python: the engine of the `thud` app (`thud-core`) as a Python module, NumPy
//! arrays out.
//!
//! - `thud.pulse(**params) -> Pulse`: one Hertzian impact heard at one observer (`thud pulse`).
//! - `thud.simulate(**params) -> Run`: one damper design through its impacts (`thud simulate`).
//! - `thud.sweep(masses_kg, gaps_m, **params) -> Chart`: the design chart (`thud sweep`).
//! - `thud.response(freqs_hz, **params) -> Response`: the frequency response under the
//!   harmonic force (`thud response`).
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
//! The Python-facing documentation (docstrings, `thud.pyi`) is in the `#[pyo3]` items and the
//! stub file next to `Cargo.toml`.

mod args;
mod detach;
mod objects;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use thud_core::design::{self, Design};
use thud_core::limits::{self, short};
use thud_core::params::{self, Spelling};
use thud_core::report::{EnsembleReport, ResponseEnsembleReport, ResponseReport};
use thud_core::response::{self, ResponseOptions};
use thud_core::units::Kind;
use thud_core::{ensemble, ThudError};

use args::{enforce, engine_error, parameter_error, refuse, Kwargs};
use objects::{PyChart, PyEnsemble, PyPulse, PyResponse, PyRun};

/// The preset named by the `preset` option (default: "default"), as the command line loads it
/// (the app's compiled-in preset files). The user's config file is not read: a script gives
/// the same numbers on every machine.
fn preset(py: Python<'_>, kw: &Kwargs<'_>, default: Option<&str>) -> PyResult<Option<Design>> {
    match kw.text(py, "preset")?.as_deref().or(default) {
        None => Ok(None),
        Some(name) => thud_presets::preset(name).map(Some).map_err(|e| engine_error(py, e)),
    }
}

/// The design of a call: the preset, then the keyword parameters (the engine's mapping).
fn design_of(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<Design> {
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
/// Parameters (keywords; numbers in SI units unless noted, or strings with a unit such as
/// "19.05mm"; None = not given):
///     preset: str — take the defaults from a preset (`thud.presets()`): its ball, K_HZ,
///         observer, source and air, and U0 = its v0; the target stays a fixed plate.
///     radius (m), mass (kg), u0 (m/s), k_hz (N/m^1.5),
///     sphere, plate: material names (K_HZ then follows from them, Eq 2),
///     main_mass (kg): a movable target, K* = (m+M)/(mM) (Eq 8),
///     r (m), theta (degrees), source: "single" | "dipole" | "quadrupole",
///     quad_signs: "paper" | "rigid", pulse: "half-sine" | "hertz",
///     rho_c (Pa·s/m), c (speed of sound, m/s),
///     points: int — waveform points (default 2000),
///     no_limit: bool — lift the work cap on points.
///
/// Raises ParameterError (a ValueError) naming the parameter for an unknown name, a wrong
/// type, NaN/inf or an out-of-range value — the command line's message and range table.
#[pyfunction]
#[pyo3(signature = (**params))]
fn pulse(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<PyPulse> {
    let kw = Kwargs::new(params, &["preset", "points", "no_limit"])?;
    let no_limit = kw.switch(py, "no_limit")?;
    let points = kw.count(py, "points", &limits::POINTS, 2000)?;
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
/// Parameters (keywords; numbers in SI units unless noted, or strings with a unit such as
/// "40.5g"; None = not given):
///     preset: str — the starting design (default "default"; `thud.presets()` lists them),
///     mass (kg), gap (m), v0 (m/s), main_mass (kg), k (N/m), c (N·s/m), c1 (N·s/m),
///     k_hz (N/m^1.5), sphere / plate (materials: K_HZ from Eq 2), no_tension (bool),
///     duration (s), solver: "event" | "newmark", dt (s, Newmark only),
///     density (kg/m³) or radius (m) of the ball, r (m), theta (degrees),
///     source: "single" | "dipole" | "quadrupole", quad_signs: "paper" | "rigid",
///     pulse: "half-sine" | "hertz", l_star (dB), e_star (cm/s),
///     force (N; alias force_amplitude) and freq (Hz): the harmonic force F0·cos(2π·f·t)
///     on the main mass (default 0, the paper's free decay),
///     ball_position (m, |y0| < gap/2) and ball_velocity (m/s): the ball's start,
///     periods: int — forcing periods of the steady-state window (default 10),
///     settle: bool — run a forced design on until its steady amplitude settles,
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
    let kw = Kwargs::new(params, &["preset", "samples", "no_limit", "ensemble"])?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let samples = kw.count(py, "samples", &limits::SAMPLES, 2001)?;
    let runs = ensemble_runs(py, &kw)?;
    let given = |n: &str| args::given(&kw.params, n);
    if runs > 1 {
        refuse(py, limits::check_run(&d, &given, 0), "samples", no_limit)?;
        refuse(py, limits::check_runs(&d, &given, 1, runs), "ensemble", no_limit)?;
        let e = {
            let d = d.clone();
            detach::run(py, move |cancel| ensemble::evaluate(&d, runs, Some(cancel)))?
        };
        let e = e.map_err(|e| engine_error(py, e))?.ok_or_else(|| cancelled(py))?;
        return Ok(PyEnsemble::new(py, &EnsembleReport::new(&d, &e))?.into_pyobject(py)?.into_any().unbind());
    }
    refuse(py, limits::check_run(&d, &given, samples), "samples", no_limit)?;
    let data = detach::run(py, |cancel| objects::RunData::compute(&d, samples, cancel))?;
    Ok(PyRun::new(py, data.map_err(|e| engine_error(py, e))?)?.into_pyobject(py)?.into_any().unbind())
}

/// The `ensemble` option (a count, default 1), refused with `ball_position` when over 1.
fn ensemble_runs(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<usize> {
    let runs = kw.count(py, "ensemble", &limits::ENSEMBLE, 1)?;
    let typed = kw.params.iter().any(|(n, _)| *n == Spelling::Keyword.key("ball-position"));
    params::check_ensemble(runs, typed, Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    Ok(runs)
}

/// The error of runs stopped without an interrupt (not expected: a stop comes from Ctrl-C).
fn cancelled(py: Python<'_>) -> PyErr {
    engine_error(py, ThudError::Cancelled)
}

/// An axis of a sweep: a sequence of numbers in SI units, or "FROM:TO:N" text as on the
/// command line ("30g:100g:20"), each value inside `range`.
fn axis(py: Python<'_>, name: &str, value: &Bound<'_, PyAny>, kind: Kind, range: &limits::Range) -> PyResult<Vec<f64>> {
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
/// Raises ParameterError (a ValueError) as `simulate` does. Ctrl-C stops the sweep.
#[pyfunction]
#[pyo3(signature = (masses_kg, gaps_m, **params))]
fn sweep(
    py: Python<'_>,
    masses_kg: &Bound<'_, PyAny>,
    gaps_m: &Bound<'_, PyAny>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyChart> {
    let kw = Kwargs::new(params, &["preset", "no_limit", "ensemble"])?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let masses = axis(py, "masses_kg", masses_kg, Kind::Mass, &limits::MASS)?;
    let gaps = axis(py, "gaps_m", gaps_m, Kind::Length, &limits::GAP)?;
    let runs = ensemble_runs(py, &kw)?;
    let given = |n: &str| args::given(&kw.params, n);
    refuse(py, limits::check_sweep(&d, &given, masses.len(), gaps.len()), "masses_kg", no_limit)?;
    let n = masses.len() * gaps.len();
    if runs > 1 {
        refuse(py, limits::check_runs(&d, &given, n, runs), "ensemble", no_limit)?;
        let chart = detach::run(py, |cancel| ensemble::sweep(&d, &masses, &gaps, runs, Some(cancel), &|_, _| {}))?;
        return PyChart::of_ensembles(py, &d, &chart.map_err(|e| engine_error(py, e))?);
    }
    let chart = detach::run(py, |cancel| design::sweep(&d, &masses, &gaps, Some(cancel), &|_, _| {}))?;
    PyChart::new(py, &d, chart.map_err(|e| engine_error(py, e))?)
}

/// response(freqs_hz, **params) -> Response
///
/// The frequency response of a design under the harmonic force F0·cos(2π·f·t) on the main
/// mass, as `thud response --json`: per frequency the steady amplitude with the damper beside
/// the closed form without it (m), the cut (dB), the impacts per period and the level Leq of
/// the rattle (dB re 20 µPa), over the last `periods` forcing periods of a settled run.
///
/// freqs_hz: a sequence of frequencies (Hz), or "FROM:TO:N" text as on the command line
/// ("3Hz:8Hz:101"). Keywords: as for `simulate` (force is needed; no freq, no samples; each
/// frequency starts from rest unless v0, ball_position or ball_velocity is given), and
/// continuation: bool — each frequency from the previous one's final state, rising then
/// falling; ensemble: int — N runs a frequency from ball offsets y0 = −d/2 + (k + ½)·d/N
/// (p10/median/p90 of each figure, and every run); no_limit: bool — lift the work caps.
///
/// Raises ParameterError (a ValueError) as `simulate` does. Ctrl-C stops the response.
#[pyfunction]
#[pyo3(name = "response", signature = (freqs_hz, **params))]
fn response_curve(
    py: Python<'_>,
    freqs_hz: &Bound<'_, PyAny>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyResponse> {
    let kw = Kwargs::new(params, &["preset", "no_limit", "ensemble", "continuation"])?;
    let no_limit = kw.switch(py, "no_limit")?;
    let continuation = kw.switch(py, "continuation")?;
    let freqs = axis(py, "freqs_hz", freqs_hz, Kind::Frequency, &limits::FREQ)?;
    let base = preset(py, &kw, Some("default"))?.unwrap_or_default();
    let d = params::response_design(base, &kw.params, Spelling::Keyword, freqs[0], "force")
        .map_err(|e| engine_error(py, e))?;
    let runs = ensemble_runs(py, &kw)?;
    check_response(py, &d, &freqs, continuation, runs, no_limit)?;
    let opts = ResponseOptions { continuation, settle: true };
    if runs > 1 {
        let r = detach::run(py, |cancel| response::response_ensemble(&d, &freqs, runs, &opts, Some(cancel), &|| {}))?;
        let r = r.map_err(|e| engine_error(py, e))?;
        return PyResponse::of_ensembles(py, &ResponseEnsembleReport::new(&d, &r, continuation));
    }
    let r = detach::run(py, |cancel| response::response(&d, &freqs, &opts, Some(cancel), &|| {}))?;
    let r = r.map_err(|e| engine_error(py, e))?;
    PyResponse::new(py, &ResponseReport::new(&d, &r, continuation))
}

/// Refuses a response of `runs` runs a frequency whose work is over a cap, as the command
/// line does: the forcing periods and Newmark steps over all runs, the cycles of one run.
fn check_response(
    py: Python<'_>,
    d: &Design,
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
    for r in &limits::RANGES {
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
#[pymodule]
#[pyo3(name = "thud")]
fn thud_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ParameterError", py.get_type::<args::ParameterError>())?;
    m.add_class::<PyPulse>()?;
    m.add_class::<PyRun>()?;
    m.add_class::<PyEnsemble>()?;
    m.add_class::<PyChart>()?;
    m.add_class::<PyResponse>()?;
    m.add_function(wrap_pyfunction!(pulse, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(response_curve, m)?)?;
    m.add_function(wrap_pyfunction!(axis_values, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(ranges, m)?)?;
    Ok(())
}
