//! `thud.fit_structure(t, x, main_mass=…)` and `thud.fit_damper(t, x, **design)`: the engine's
//! calibration from measurements ([`thud_core::fit`]), the same numbers and keys as
//! `thud fit structure|damper --json`, returned as a dict.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use thud_core::fit::{self, Quantity, Series};
use thud_core::limits::{self, short, Estimate};
use thud_core::units::Kind;

use crate::args::{enforce, engine_error, parameter_error, refuse, Kwargs};
use crate::{cancelled, design_of, detach, options};

/// The `quantity` option: "x" (m), "v" (m/s) or "a" (m/s²).
fn quantity_of(py: Python<'_>, q: Option<&str>) -> PyResult<Quantity> {
    match q.unwrap_or("x") {
        "x" => Ok(Quantity::Displacement),
        "v" => Ok(Quantity::Velocity),
        "a" => Ok(Quantity::Acceleration),
        other => Err(parameter_error(
            py,
            "quantity",
            format!("invalid quantity: '{other}'; one of: x (m), v (m/s), a (m/s^2)"),
        )),
    }
}

/// One or several records: `t` and `x` each a sequence of numbers, or each a sequence of such
/// sequences (repeated strikes).
fn records(
    py: Python<'_>,
    t: &Bound<'_, PyAny>,
    x: &Bound<'_, PyAny>,
    q: Quantity,
    no_limit: bool,
) -> PyResult<Vec<Series>> {
    let pairs: Vec<(Vec<f64>, Vec<f64>)> = match (t.extract::<Vec<f64>>(), x.extract::<Vec<f64>>()) {
        (Ok(t), Ok(x)) => vec![(t, x)],
        _ => match (t.extract::<Vec<Vec<f64>>>(), x.extract::<Vec<Vec<f64>>>()) {
            (Ok(ts), Ok(xs)) if ts.len() == xs.len() => ts.into_iter().zip(xs).collect(),
            _ => {
                return Err(parameter_error(
                    py,
                    "data",
                    "invalid data: t and x must be sequences of numbers of one length (or lists of such sequences, one per strike)"
                        .to_string(),
                ))
            }
        },
    };
    pairs
        .into_iter()
        .map(|(t, x)| {
            let n = Estimate { cap: limits::HISTORY_SAMPLES, value: t.len() as f64 };
            enforce(py, n, "data", &format!("use at most {} samples", short(limits::HISTORY_SAMPLES.max)), no_limit)?;
            Series::new(t, x, q).map_err(|e| engine_error(py, e))
        })
        .collect()
}

/// The record's JSON as a Python dict (the command line's keys).
fn as_dict<'py, T: serde::Serialize>(py: Python<'py>, v: &T) -> PyResult<Bound<'py, PyDict>> {
    thud_core::finite::check(v).map_err(|e| crate::args::non_finite(&e.0))?;
    let text = serde_json::to_string(v).map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.cast_into::<PyDict>()?)
}

/// fit_structure(t_s, x, *, main_mass, quantity="x") -> dict
///
/// The structure alone, struck once: f_n, ζ, K and C with standard errors from a measured free
/// decay, as `thud fit structure --json` (keys f_n_hz, zeta, k_n_m, c_n_s_m, each with
/// `_stderr`, residual_rms, converged, …). `t_s`: times (s, increasing, any spacing); `x`: the
/// signal, a displacement (m, quantity="x"), velocity (m/s, "v") or acceleration (m/s², "a");
/// offset and drift are fitted. `main_mass`: M (kg, or e.g. "2kg").
///
/// Raises ParameterError for bad data (too short, NaN, unsorted or repeated time, clipping,
/// no decay) or a bad main mass. A fit that did not converge returns converged=False.
#[pyfunction]
#[pyo3(signature = (t_s, x, *, main_mass, quantity = "x"))]
pub fn fit_structure<'py>(
    py: Python<'py>,
    t_s: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    main_mass: &Bound<'py, PyAny>,
    quantity: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let q = quantity_of(py, Some(quantity))?;
    let m = match crate::args::to_value(main_mass)? {
        thud_core::params::Input::Num(v) => v,
        thud_core::params::Input::Text(t) => {
            thud_core::units::parse("main_mass", &t, Kind::Mass).map_err(|e| engine_error(py, e))?
        }
        _ => {
            return Err(parameter_error(
                py,
                "main_mass",
                "invalid main_mass: expected a number or a quantity such as \"2kg\"".into(),
            ))
        }
    };
    let m = limits::MAIN_MASS.check_as("main_mass", m).map_err(|e| engine_error(py, e))?;
    let mut recs = records(py, t_s, x, q, false)?;
    if recs.len() != 1 {
        return Err(parameter_error(py, "data", "invalid data: one record for a structure fit".into()));
    }
    let s = recs.remove(0);
    let f = detach::run(py, move |_| fit::structure::fit(&s, m))?.map_err(|e| engine_error(py, e))?;
    as_dict(py, &f)
}

/// fit_damper(t_s, x, **params) -> dict
///
/// The structure with the damper, struck once at the record's start, every other parameter of
/// the design known (the design's keywords, as for `simulate`): c1 and the restitution it
/// implies at the first impact's speed, each with a 95 % interval, as `thud fit damper --json`
/// (keys c1_n_s_m, c1_n_s_m_stderr, c1_n_s_m_ci, restitution, restitution_stderr,
/// restitution_ci, residual_rms, and note where c1 is poorly bounded). The ball's unknown start
/// is handled by an ensemble of starts.
/// `t_s`, `x` may be lists of records (repeated strikes), fitted together.
///
/// Options: preset: str (default "default"), quantity: "x" | "v" | "a" (default "x"),
/// no_limit: bool — lift the work caps.
#[pyfunction]
#[pyo3(signature = (t_s, x, **params))]
pub fn fit_damper<'py>(
    py: Python<'py>,
    t_s: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let kw = Kwargs::new(params, options("fit_damper"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let q = quantity_of(py, kw.text(py, "quantity")?.as_deref())?;
    let d = design_of(py, &kw)?;
    if crate::args::given(&kw.params, "ball-position") {
        return Err(parameter_error(
            py,
            "ball_position",
            "invalid ball_position: a damper fit spreads the ball's start itself (an ensemble)".into(),
        ));
    }
    let recs = records(py, t_s, x, q, no_limit)?;
    let span = fit::damper::common_span_s(&recs);
    let work = fit::damper::work_design(&d, span).map_err(|e| engine_error(py, e))?;
    let given = |n: &str| crate::args::given(&kw.params, n);
    refuse(py, limits::check_runs(&work, &given, fit::damper::GRID_POINTS, fit::damper::STARTS), "data", no_limit)?;
    let f = detach::run(py, move |cancel| fit::damper::fit(&d, &recs, Some(cancel)))?
        .map_err(|e| engine_error(py, e))?
        .ok_or_else(|| cancelled(py))?;
    as_dict(py, &f)
}
