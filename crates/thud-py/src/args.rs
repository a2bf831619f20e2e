//! Keyword arguments in, errors out: Python keywords become the engine's named parameters
//! ([`thud_core::params`], the same mapping and range table as the command line's flags), and
//! every engine error becomes a [`ParameterError`] (a `ValueError`) with the same one line.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString};
use thud_core::limits::{self, short, Estimate, Range};
use thud_core::params::Input;
use thud_core::ThudError;

pyo3::create_exception!(
    thud,
    ParameterError,
    PyValueError,
    "A parameter thud cannot accept: unknown, of the wrong type, not finite, out of its range, \
     or a run whose work is over its cap. The message is one line naming the parameter; \
     `.param` is its name."
);

/// A `ParameterError` with `message`, its `.param` set to `param`.
pub fn parameter_error(py: Python<'_>, param: &str, message: String) -> PyErr {
    let err = ParameterError::new_err(message);
    // Setting an attribute on a fresh exception instance cannot fail in practice; if it did,
    // the message still names the parameter.
    let _ = err.value(py).setattr("param", param);
    err
}

/// An engine error as a `ParameterError`: "invalid main_mass: 1e308 kg is out of range; …".
pub fn engine_error(py: Python<'_>, e: ThudError) -> PyErr {
    let param = e.param().to_string();
    parameter_error(py, &param, e.to_string())
}

/// A non-finite number in a result: an internal error (never handed out as a value).
pub fn non_finite(what: &str) -> PyErr {
    PyRuntimeError::new_err(format!(
        "internal error: {what} came out as a number that is not finite; nothing was returned. \
         This is a bug in thud: please report it with the call"
    ))
}

/// The keyword arguments of one call, split into the run options the function knows itself
/// (`preset`, `points`, `no_limit`, …) and the named parameters for the engine.
pub struct Kwargs<'py> {
    options: Vec<(String, Bound<'py, PyAny>)>,
    /// Engine parameters as (keyword, value).
    pub params: Vec<(String, Input)>,
}

impl<'py> Kwargs<'py> {
    /// Splits `kwargs`: names in `options` are kept aside; every other name goes to the engine
    /// as typed (the engine knows the keyword spelling, `main_mass`). `None` means "not given".
    pub fn new(kwargs: Option<&Bound<'py, PyDict>>, options: &[&str]) -> PyResult<Self> {
        let mut out = Kwargs { options: Vec::new(), params: Vec::new() };
        let Some(kwargs) = kwargs else { return Ok(out) };
        for (key, value) in kwargs.iter() {
            let name: String = key.extract()?;
            if options.contains(&name.as_str()) {
                out.options.push((name, value));
                continue;
            }
            if value.is_none() {
                continue;
            }
            out.params.push((name, to_value(&value)?));
        }
        Ok(out)
    }

    /// The option `name`, unless absent or None.
    pub fn option(&self, name: &str) -> Option<&Bound<'py, PyAny>> {
        self.options.iter().find(|(n, v)| n == name && !v.is_none()).map(|(_, v)| v)
    }

    /// The text option `name` (`preset`).
    pub fn text(&self, py: Python<'py>, name: &str) -> PyResult<Option<String>> {
        match self.option(name) {
            None => Ok(None),
            Some(v) => match v.cast::<PyString>() {
                Ok(s) => Ok(Some(s.to_cow()?.into_owned())),
                Err(_) => {
                    Err(parameter_error(py, name, format!("invalid {name}: expected a name, not {}", kind_of(v))))
                }
            },
        }
    }

    /// The switch option `name` (`no_limit`), False when absent.
    pub fn switch(&self, py: Python<'py>, name: &str) -> PyResult<bool> {
        match self.option(name) {
            None => Ok(false),
            Some(v) => match v.cast::<PyBool>() {
                Ok(b) => Ok(b.is_true()),
                Err(_) => Err(parameter_error(
                    py,
                    name,
                    format!("invalid {name}: expected True or False, not {}", kind_of(v)),
                )),
            },
        }
    }

    /// The count option `name` (`points`, `samples`) against `range`, `default` when absent:
    /// a whole number, checked exactly as the command line checks its count flags.
    pub fn count(&self, py: Python<'py>, name: &str, range: &Range, default: usize) -> PyResult<usize> {
        let Some(v) = self.option(name) else { return Ok(default) };
        let text = if v.is_instance_of::<PyBool>() {
            None
        } else if let Ok(s) = v.cast::<PyString>() {
            Some(s.to_cow()?.into_owned())
        } else if let Ok(i) = v.extract::<i128>() {
            Some(i.to_string())
        } else {
            v.extract::<f64>().ok().map(|f| format!("{f}"))
        };
        let Some(text) = text else {
            return Err(parameter_error(
                py,
                name,
                format!("invalid {name}: expected a whole number, not {}", kind_of(v)),
            ));
        };
        range.parse_count(name, &text).map_err(|e| engine_error(py, e))
    }
}

/// A Python value as an engine value: str → text (units allowed, `"40.5g"`), bool → switch,
/// anything with `__float__` (int, float, NumPy scalars) → number, else "a <type>".
pub fn to_value(v: &Bound<'_, PyAny>) -> PyResult<Input> {
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(Input::Switch(b.is_true()));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(Input::Text(s.to_cow()?.into_owned()));
    }
    match v.extract::<f64>() {
        Ok(x) => Ok(Input::Num(x)),
        Err(_) => Ok(Input::Other(kind_of(v))),
    }
}

/// "a list", "a dict": what a value is, for messages.
pub fn kind_of(v: &Bound<'_, PyAny>) -> String {
    let name = v.get_type().name().map_or_else(|_| "object".into(), |n| n.to_string());
    let article = if name.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
    format!("{article} {name}")
}

/// Refuses an estimate over its cap unless `no_limit`: "invalid dt: 2e12 Newmark steps exceed
/// the limit of 1e9; use dt ≥ 2e-9 s or a shorter duration, or pass no_limit=True".
pub fn enforce(py: Python<'_>, e: Estimate, param: &str, hint: &str, no_limit: bool) -> PyResult<()> {
    if no_limit || !e.exceeded() {
        return Ok(());
    }
    Err(parameter_error(py, param, format!("invalid {param}: {}; {hint}, or pass no_limit=True", e.describe())))
}

/// Refuses one simulation of `d` keeping `samples` history samples whose work is over a cap,
/// blaming `duration` when it was given without `dt`, else `dt`.
pub fn check_run(
    py: Python<'_>,
    d: &thud_core::design::Design,
    given: &[(String, Input)],
    samples: usize,
    no_limit: bool,
) -> PyResult<()> {
    let [steps, cycles, history] = limits::design_run(d, samples);
    check_solver(py, d, given, steps, cycles, "", no_limit)?;
    enforce(py, history, "samples", &format!("use samples ≤ {}", short(history.cap.max)), no_limit)
}

/// Refuses Newmark steps or main-mass cycles over their caps (`per` says "with N cells").
pub fn check_solver(
    py: Python<'_>,
    d: &thud_core::design::Design,
    given: &[(String, Input)],
    steps: Estimate,
    cycles: Estimate,
    per: &str,
    no_limit: bool,
) -> PyResult<()> {
    let has = |n: &str| given.iter().any(|(g, _)| g == n);
    let dur = d.damper.duration_s;
    if let thud_core::damper::Solver::Newmark { dt_s } = d.solver {
        let scale = steps.value / limits::newmark_steps(dur, dt_s);
        let (min_dt, max_dur) = (dur * scale / steps.cap.max, steps.cap.max * dt_s / scale);
        if has("duration") && !has("dt") {
            let hint = format!("use duration ≤ {} s{per} or a larger dt", short(max_dur));
            enforce(py, steps, "duration", &hint, no_limit)?;
        } else {
            let hint = format!("use dt ≥ {} s{per} or a shorter duration", short(min_dt));
            enforce(py, steps, "dt", &hint, no_limit)?;
        }
    }
    let max_dur = dur * cycles.cap.max / cycles.value;
    enforce(py, cycles, "duration", &format!("use duration ≤ {} s{per}", short(max_dur)), no_limit)
}

/// Refuses `cells` cells of `d` with `runs` ensemble runs each whose work is over a cap, as the
/// command line's `--ensemble` does: the runs, the simulated run-seconds, and the Newmark steps
/// and main-mass cycles summed over the runs.
pub fn check_runs(
    py: Python<'_>,
    d: &thud_core::design::Design,
    given: &[(String, Input)],
    cells: usize,
    runs: usize,
    no_limit: bool,
) -> PyResult<()> {
    let [n, seconds, steps, cycles] = limits::ensemble_work(d, cells, runs);
    let hint = if cells > 1 {
        format!("use fewer runs ({cells} cells × {runs}; at most {} runs)", short(n.cap.max))
    } else {
        format!("use at most {} runs", short(n.cap.max))
    };
    enforce(py, n, "ensemble", &hint, no_limit)?;
    let per = format!(" with {} runs", short(n.value));
    let hint = format!("use duration ≤ {} s{per} or fewer runs", short(seconds.cap.max / n.value));
    enforce(py, seconds, "duration", &hint, no_limit)?;
    check_solver(py, d, given, steps, cycles, &per, no_limit)
}
