//! Keyword arguments in, errors out: Python keywords become the engine's named parameters
//! ([`thud_core::params`], the same mapping and range table as the command line's flags), and
//! every engine error becomes a [`ParameterError`] (a `ValueError`) with the same one line.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt, PyString};
use thud_core::limits::{self, short, Estimate, Range, Refusal, Remedy};
use thud_core::params::{Input, Spelling};
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
    if e == ThudError::Cancelled {
        return pyo3::exceptions::PyKeyboardInterrupt::new_err(e.to_string());
    }
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
            if value.is_instance_of::<PyInt>() && !value.is_instance_of::<PyBool>() && value.extract::<f64>().is_err() {
                // An int beyond any float (`10**400`): out of range, named as such.
                return Err(huge_int(value.py(), &name, &value));
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
        } else if v.is_instance_of::<PyInt>() {
            // An int too large for any count (`10**400`): out of range, named as such.
            let digits = v.str().map_or(0, |s| s.to_string().trim_start_matches('-').len());
            let sign = if v.lt(0).unwrap_or(false) { "a negative " } else { "an " };
            return Err(engine_error(
                py,
                ThudError::invalid(
                    name,
                    format!(
                        "{sign}integer of {digits} digits is out of range; the {} must be {}",
                        range.what,
                        range.describe()
                    ),
                ),
            ));
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

/// The error of an int too large for a float given for the parameter `name`: out of range,
/// with the parameter's range when it has one.
pub(crate) fn huge_int(py: Python<'_>, name: &str, v: &Bound<'_, PyAny>) -> PyErr {
    let digits = v.str().map_or(0, |s| s.to_string().trim_start_matches('-').len());
    let sign = if v.lt(0).unwrap_or(false) { "a negative " } else { "an " };
    let range = thud_core::params::listed_ranges().into_iter().find(|r| Spelling::Keyword.spell(r.param) == name);
    let tail = match range {
        Some(r) => format!("; the {} must be {}", r.what, r.describe()),
        None => String::new(),
    };
    parameter_error(py, name, format!("invalid {name}: {sign}integer of {digits} digits is out of range{tail}"))
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

/// The engine's refusal ([`limits::check_run`] and the like) in Python's words, as a
/// `ParameterError` naming the keyword to change: "invalid duration: 2e12 Newmark steps exceed
/// the limit of 1e9; use duration ≤ 2 s or a larger dt, or pass no_limit=True". `counted`
/// is the keyword of what the caller counts (`samples`, `masses_kg`, `ensemble`).
pub fn refuse(py: Python<'_>, r: Result<(), Refusal>, counted: &str, no_limit: bool) -> PyResult<()> {
    let Err(r) = r else { return Ok(()) };
    let param = match r.param {
        limits::SAMPLES_PARAM | limits::CELLS_PARAM | limits::RUNS_PARAM | limits::FREQS_PARAM => counted.to_string(),
        row => Spelling::Keyword.spell(row),
    };
    let per = &r.per;
    let hint = match r.remedy {
        Remedy::ShorterDuration { max_s } => format!("use duration ≤ {} s{per}", short(max_s)),
        Remedy::ShorterDurationOrLargerDt { max_s } => format!("use duration ≤ {} s{per} or a larger dt", short(max_s)),
        Remedy::LargerDtOrShorterDuration { min_s } => {
            format!("use dt ≥ {} s{per} or a shorter duration", short(min_s))
        }
        Remedy::FewerSamples { max } => format!("use {counted} ≤ {}", short(max)),
        Remedy::FewerCells { max } => format!("use fewer values on either axis (product ≤ {})", short(max)),
        Remedy::ShorterDurationOrFewerCells { max_s } => {
            format!("use duration ≤ {} s{per} or fewer cells", short(max_s))
        }
        Remedy::FewerRuns { max, cells, runs } if cells > 1 => {
            format!("use fewer runs ({cells} cells × {runs}; at most {} runs)", short(max))
        }
        Remedy::FewerRuns { max, .. } => format!("use at most {} runs", short(max)),
        Remedy::ShorterDurationOrFewerRuns { max_s } => format!("use duration ≤ {} s{per} or fewer runs", short(max_s)),
        Remedy::FewerRunsPerFrequency { max } => {
            format!("use fewer runs (at most {} for these frequencies)", short(max))
        }
        Remedy::FewerFrequencies => "use fewer frequencies or a shorter duration".to_string(),
        Remedy::LowerFrequencies => "use lower frequencies or a shorter duration".to_string(),
        Remedy::EventSolverOrLargerDt => "use the event solver or a larger dt".to_string(),
    };
    enforce(py, r.estimate, &param, &hint, no_limit)
}

/// Whether the keyword of the table row `name` was given.
pub fn given(params: &[(String, Input)], name: &str) -> bool {
    let key = Spelling::Keyword.key(name);
    params.iter().any(|(n, _)| *n == key)
}
