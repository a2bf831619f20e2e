//! `thud.design(...)` and `thud.Designer(...)`: the design search of `thud design` from
//! Python. The problem is given in the command line's words (`vary="mass=20g:120g"`,
//! `minimize="spl_max_db"`, `require="mass<=60g"`, `over="freqs=4.5Hz:5.5Hz:21"`,
//! `evaluations`, `seed`, `reference`), parsed by the engine's own parsers
//! ([`thud_core::design::search`]); the result is the command line's `--json` record, handed
//! over as JSON text, which the Python layer (`thud/_design.py`) turns into a `Front`.
//!
//! `_design` runs the whole search without the GIL, reporting its evaluations to a
//! `progress(done, total)` callback. Ctrl-C (or a callback that raises) stops it after the
//! batch under way and its exception propagates, carrying the front found so far (marked
//! partial) as JSON text in `_thud_front`, which the Python layer makes the exception's `front`.
//! `_Designer` is the ask/tell form ([`thud_core::design::asktell`]): the points go out, the
//! caller evaluates them anywhere and tells the result columns back.

use std::sync::atomic::Ordering;
use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use thud_core::design::asktell::{AskTell, Failure};
use thud_core::design::search::{
    self, Bound as Limit, Candidate, Constraint, Objective, Outcome, Problem, Sense, Settings, Value, Variable,
};
use thud_core::limits;
use thud_core::params::{Accepts, Spelling};
use thud_core::units::Kind;
use thud_core::ThudError;

use crate::args::{self, engine_error, parameter_error, refuse, Kwargs};
use crate::progress::Progress;
use crate::{design_of, detach, json_of};

/// The keywords of `Designer` beside the design's own (its caller evaluates, so it has no
/// progress of its own).
pub const DESIGNER_OPTIONS: [&str; 12] = [
    "preset",
    "design",
    "vary",
    "choose",
    "minimize",
    "maximize",
    "require",
    "over",
    "evaluations",
    "seed",
    "reference",
    "no_limit",
];

/// The keywords of `design` beside the design's own: `Designer`'s, and `progress`.
pub const OPTIONS: [&str; DESIGNER_OPTIONS.len() + 1] = with_progress(DESIGNER_OPTIONS);

/// `options` and `progress` after them.
const fn with_progress<const N: usize, const M: usize>(options: [&'static str; N]) -> [&'static str; M] {
    let mut out = ["progress"; M];
    let mut i = 0;
    while i < N {
        out[i] = options[i];
        i += 1;
    }
    out
}

/// The budget unless `evaluations` is given (the command line's default).
const EVALUATIONS_DEFAULT: usize = 400;

/// The engine's error naming the command line's flag (`--vary mass`, `--minimize`) renamed to
/// this module's keyword (`vary`, `minimize`; the force amplitude's is `force`).
fn keyword(e: ThudError) -> ThudError {
    let Some(flag) = e.param().strip_prefix("--") else { return e };
    let name = flag.split_whitespace().next().unwrap_or(flag);
    let name = if name == "force-amplitude" { "force".to_string() } else { Spelling::Keyword.spell(name) };
    e.renamed(name)
}

fn error(py: Python<'_>, e: ThudError) -> PyErr {
    engine_error(py, keyword(e))
}

/// The text option `name`: one text, or a sequence of texts (none when absent).
fn texts(py: Python<'_>, kw: &Kwargs<'_>, name: &str) -> PyResult<Vec<String>> {
    let Some(v) = kw.option(name) else { return Ok(Vec::new()) };
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(vec![s.to_cow()?.into_owned()]);
    }
    let bad = || {
        let msg = format!(
            "invalid {name}: expected a text such as the command line's or a list of them, not {}",
            args::kind_of(v)
        );
        parameter_error(py, name, msg)
    };
    let items: Vec<Bound<'_, PyAny>> = v.try_iter().map_err(|_| bad())?.collect::<PyResult<_>>()?;
    items.iter().map(|i| i.cast::<PyString>().map_err(|_| bad()).and_then(|s| Ok(s.to_cow()?.into_owned()))).collect()
}

/// The problem of a call, every part checked (the error names the keyword).
fn problem(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<Problem> {
    let base = design_of(py, kw)?;
    let mut variables = Vec::new();
    for t in texts(py, kw, "vary")? {
        variables.push(Variable::parse_range(&t).map_err(|e| error(py, e))?);
    }
    for t in texts(py, kw, "choose")? {
        variables.push(Variable::parse_choice(&t).map_err(|e| error(py, e))?);
    }
    let mut objectives = Vec::new();
    for t in texts(py, kw, "minimize")? {
        objectives.push(Objective::parse(&t, Sense::Minimize).map_err(|e| error(py, e))?);
    }
    for t in texts(py, kw, "maximize")? {
        objectives.push(Objective::parse(&t, Sense::Maximize).map_err(|e| error(py, e))?);
    }
    let mut constraints = Vec::new();
    for t in texts(py, kw, "require")? {
        constraints.push(Constraint::parse(&t).map_err(|e| error(py, e))?);
    }
    let band_hz = match kw.text(py, "over")? {
        None => Vec::new(),
        Some(t) => {
            let spec = t.strip_prefix("freqs=").ok_or_else(|| {
                parameter_error(
                    py,
                    "over",
                    format!("invalid over: '{t}'; expected freqs=FROM:TO:N, e.g. freqs=4.5Hz:5.5Hz:21"),
                )
            })?;
            thud_core::params::parse_range("over", spec, Kind::Frequency, &limits::FREQ).map_err(|e| error(py, e))?
        }
    };
    let p = Problem { base, variables, objectives, constraints, band_hz, robust: None };
    p.check().map_err(|e| error(py, e))?;
    Ok(p)
}

/// The `seed` option: a whole number from 0 to 2⁶⁴ − 1 (default 0).
fn seed(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<u64> {
    let Some(v) = kw.option("seed") else { return Ok(0) };
    let bad = || {
        parameter_error(
            py,
            "seed",
            format!("invalid seed: expected a whole number from 0 to {}, not {}", u64::MAX, shown(v)),
        )
    };
    if v.is_instance_of::<pyo3::types::PyBool>() {
        return Err(bad());
    }
    if let Ok(s) = v.cast::<PyString>() {
        return s.to_cow()?.trim().parse().map_err(|_| bad());
    }
    v.extract::<u64>().map_err(|_| bad())
}

fn shown(v: &Bound<'_, PyAny>) -> String {
    v.repr().map_or_else(|_| args::kind_of(v), |r| r.to_string())
}

/// The `reference` option: two finite numbers in the objectives' units (two objectives only).
fn reference(py: Python<'_>, kw: &Kwargs<'_>, objectives: usize) -> PyResult<Option<Vec<f64>>> {
    let Some(v) = kw.option("reference") else { return Ok(None) };
    let bad = |why: &str| parameter_error(py, "reference", format!("invalid reference: {}: {why}", shown(v)));
    let r: Vec<f64> = v.extract().map_err(|_| bad("expected two numbers (V1, V2), e.g. (106, 0)"))?;
    if r.len() != 2 || r.iter().any(|x| !x.is_finite()) {
        return Err(bad("expected two finite numbers (V1, V2), e.g. (106, 0)"));
    }
    if r.iter().any(|x| x.abs() > search::REFERENCE_MAX) {
        return Err(bad(&format!("each value must be within ±{:e}", search::REFERENCE_MAX)));
    }
    if objectives != 2 {
        return Err(bad("a hypervolume is computed with two objectives only"));
    }
    Ok(Some(r))
}

/// The problem, budget, seed and reference of a call, its work checked.
fn setup(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<(Problem, Settings, Option<Vec<f64>>)> {
    let no_limit = kw.switch(py, "no_limit")?;
    let p = problem(py, kw)?;
    let evaluations = kw.count(py, "evaluations", &limits::EVALUATIONS, EVALUATIONS_DEFAULT)?;
    let settings = Settings { evaluations, seed: seed(py, kw)? };
    let reference = reference(py, kw, p.objectives.len())?;
    let given = |n: &str| args::given(&kw.params, n);
    refuse(py, search::check_work(&p, evaluations, &given), "evaluations", no_limit)?;
    Ok((p, settings, reference))
}

fn value_json(v: &Value) -> serde_json::Value {
    match v {
        Value::Number(x) => serde_json::json!(x),
        Value::Choice(s) => serde_json::json!(s),
    }
}

/// The sentence of an infeasible problem, as the command line's: which constraint binds.
fn binding(p: &Problem, o: &Outcome) -> Option<String> {
    if !o.front.is_empty() {
        return None;
    }
    let ran = o.all.iter().filter(|c| c.error.is_none()).count();
    if ran == 0 {
        let why = o.all.first().and_then(|c| c.error.clone()).unwrap_or_default();
        return Some(format!("no design of the search could be run ({why})"));
    }
    Some(match p.binding(&o.all) {
        Some((k, best)) => format!(
            "no design meets every constraint: {} binds (the best of {ran} designs misses it by {})",
            p.constraints[k].text,
            limits::short(-best)
        ),
        None => format!("no design of {ran} has every objective defined (no impact?)"),
    })
}

/// The margin's column, as the command line's CSV heads it (`margin_mass_le`).
fn margin_column(c: &Constraint) -> String {
    let name = match &c.bound {
        Limit::Result(col) => col.name().to_string(),
        Limit::Param(row) => row.name.replace('-', "_"),
    };
    format!("margin_{name}_{}", if c.at_most { "le" } else { "ge" })
}

/// The command line's `thud design --json` record of `o`, with what the Python layer needs
/// beside it under "python": each variable's keyword and each margin's column.
fn record(p: &Problem, o: &Outcome, s: Settings) -> serde_json::Value {
    let front: Vec<serde_json::Value> = o
        .front
        .iter()
        .map(|&i| {
            let c: &Candidate = &o.all[i];
            let variables: serde_json::Map<String, serde_json::Value> =
                p.variables.iter().zip(&c.values).map(|(v, x)| (v.column(), value_json(x))).collect();
            let objectives: serde_json::Map<String, serde_json::Value> = p
                .objectives
                .iter()
                .zip(&c.objectives)
                .map(|(ob, v)| (ob.column.name().to_string(), serde_json::json!(v)))
                .collect();
            let margins: serde_json::Map<String, serde_json::Value> =
                p.constraints.iter().zip(&c.margins).map(|(k, m)| (k.text.clone(), serde_json::json!(m))).collect();
            serde_json::json!({"index": c.index, "variables": variables, "objectives": objectives, "margins": margins})
        })
        .collect();
    let variables: Vec<serde_json::Value> = p
        .variables
        .iter()
        .map(|v| match v {
            Variable::Range { row, lo, hi } => {
                serde_json::json!({"name": row.name, "column": v.column(), "unit": row.unit(), "from": lo, "to": hi})
            }
            Variable::Choice { row, options } => {
                serde_json::json!({"name": row.name, "column": v.column(), "options": options})
            }
        })
        .collect();
    let mut r = serde_json::json!({
        "design": p.base.design(),
        "variables": variables,
        "objectives": p.objectives.iter().map(|o| serde_json::json!({"column": o.column.name(), "sense": o.sense})).collect::<Vec<_>>(),
        "constraints": p.constraints.iter().map(|c| c.text.as_str()).collect::<Vec<_>>(),
        "evaluations": o.all.len(),
        "budget": s.evaluations,
        "seed": s.seed,
        "partial": o.partial,
        "reference": o.reference,
        "hypervolume": o.hypervolume,
        "front": front,
    });
    if let Some(m) = r.as_object_mut() {
        if !p.band_hz.is_empty() {
            m.insert("band_hz".into(), serde_json::json!(p.band_hz));
        }
        if let Some(b) = binding(p, o) {
            m.insert("binding".into(), serde_json::json!(b));
        }
        m.insert("python".into(), python_keys(p));
    }
    r
}

/// What the Python layer reads beside the record: each variable's keyword (`mass`) and whether
/// it is a count, each constraint's margin column.
fn python_keys(p: &Problem) -> serde_json::Value {
    serde_json::json!({
        "keywords": p.variables.iter().map(|v| Spelling::Keyword.spell(v.name())).collect::<Vec<_>>(),
        "counts": p.variables.iter().map(is_count).collect::<Vec<_>>(),
        "margin_columns": p.constraints.iter().map(margin_column).collect::<Vec<_>>(),
    })
}

fn is_count(v: &Variable) -> bool {
    matches!(v, Variable::Range { row, .. } if matches!(row.accepts, Accepts::Count { .. }))
}

/// `o`'s record as JSON text, its numbers checked finite.
fn record_text(py: Python<'_>, p: &Problem, o: &Outcome, s: Settings) -> PyResult<String> {
    let r = record(p, o, s);
    thud_core::finite::check(&r).map_err(|e| args::non_finite(&e.0))?;
    json_of(py, &r)
}

/// _design(**params) -> str
///
/// The design search of `thud design`, as `thud design --json` prints it (JSON text; the
/// Python layer makes a `Front` of it). `progress(done, total)` hears the designs evaluated
/// out of the budget. An interrupt (Ctrl-C, or the callback's exception) propagates with the
/// partial front's record in its `_thud_front`.
#[pyfunction]
#[pyo3(signature = (**params))]
pub fn _design(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    let kw = Kwargs::new(params, &OPTIONS)?;
    let (p, settings, reference) = setup(py, &kw)?;
    let progress = Progress::new(py, &kw, settings.evaluations)?;
    let done = &progress.done;
    // The outcome is kept here too: an interrupt's error carries the front found so far.
    let kept: Mutex<Option<Outcome>> = Mutex::new(None);
    let on_batch = |at: search::Progress, _: &[Candidate], _: &[usize]| done.store(at.evaluations, Ordering::Relaxed);
    let ran = detach::run_watched(
        py,
        |cancel| {
            let o = search::search(&p, settings, reference.as_deref(), Some(cancel), &on_batch);
            if let Ok(o) = &o {
                *kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(o.clone());
            }
            o
        },
        || progress.report(),
    );
    let o = match ran {
        Ok(o) => o.map_err(|e| error(py, e))?,
        Err(stop) => {
            let partial = kept.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner);
            if let Some(o) = partial {
                let text = record_text(py, &p, &o, settings)?;
                stop.value(py).setattr("_thud_front", text)?;
            }
            return Err(stop);
        }
    };
    if o.partial {
        return Err(crate::cancelled(py));
    }
    record_text(py, &p, &o, settings)
}

/// The ask/tell form of the design search (`thud.Designer` wraps it).
#[pyclass(name = "_Designer", module = "thud._thud")]
pub struct PyDesigner {
    inner: Mutex<AskTell>,
}

impl PyDesigner {
    fn lock(&self) -> std::sync::MutexGuard<'_, AskTell> {
        self.inner.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// A point's values from Python: numbers (a count as an int) and names, one per variable.
fn values_of(py: Python<'_>, at: &AskTell, x: &Bound<'_, PyAny>) -> PyResult<Vec<Value>> {
    let items: Vec<Bound<'_, PyAny>> = x.try_iter()?.collect::<PyResult<_>>()?;
    if items.len() != at.problem().variables.len() {
        let msg =
            format!("invalid xs: a point has {} values for {} variables", items.len(), at.problem().variables.len());
        return Err(parameter_error(py, "xs", msg));
    }
    items
        .iter()
        .map(|i| {
            if let Ok(s) = i.cast::<PyString>() {
                Ok(Value::Choice(s.to_cow()?.into_owned()))
            } else {
                Ok(Value::Number(i.extract::<f64>()?))
            }
        })
        .collect()
}

#[pymethods]
impl PyDesigner {
    #[new]
    #[pyo3(signature = (**params))]
    fn new(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let kw = Kwargs::new(params, &DESIGNER_OPTIONS)?;
        let (p, settings, reference) = setup(py, &kw)?;
        let at = AskTell::new(p, settings, reference).map_err(|e| error(py, e))?;
        Ok(PyDesigner { inner: Mutex::new(at) })
    }

    /// The result columns each told result must carry, in order.
    fn columns(&self) -> Vec<&'static str> {
        self.lock().columns().iter().map(|c| c.name()).collect()
    }

    /// Whether the search is over.
    fn done(&self) -> bool {
        self.lock().done()
    }

    /// Points asked and not told yet.
    fn outstanding(&self) -> usize {
        self.lock().outstanding()
    }

    /// Up to n points, each a list of values (a count as an int, a choice as its name).
    fn ask<'py>(&self, py: Python<'py>, n: usize) -> PyResult<Bound<'py, PyList>> {
        let (points, counts) = py.detach(|| {
            let mut at = self.lock();
            let counts: Vec<bool> = at.problem().variables.iter().map(is_count).collect();
            (at.ask(n), counts)
        });
        let points = points.map_err(|e| error(py, e))?;
        let out = PyList::empty(py);
        for p in points {
            let row = PyList::empty(py);
            for (v, count) in p.iter().zip(&counts) {
                match v {
                    Value::Number(x) if *count => row.append(*x as i64)?,
                    Value::Number(x) => row.append(*x)?,
                    Value::Choice(s) => row.append(s)?,
                }
            }
            out.append(row)?;
        }
        Ok(out)
    }

    /// The forcing frequencies of the band (Hz), one run of a point each; empty without one.
    fn band_hz(&self) -> Vec<f64> {
        self.lock().problem().band_hz.clone()
    }

    /// Tells one point's result: `values` as asked; `result` one list per run of the point
    /// (one run, or one per frequency of the band), each one number or None per column, or a
    /// text saying why the point could not be run.
    fn tell(&self, py: Python<'_>, values: &Bound<'_, PyAny>, result: &Bound<'_, PyAny>) -> PyResult<()> {
        let mut at = self.lock();
        let x = values_of(py, &at, values)?;
        let told: Result<Vec<Vec<Option<f64>>>, Failure> = if let Ok(s) = result.cast::<PyString>() {
            Err(Failure(s.to_cow()?.into_owned()))
        } else {
            let runs: Vec<Vec<Option<f64>>> = result.extract()?;
            if let Some(bad) = runs.iter().flatten().flatten().find(|x| !x.is_finite()) {
                return Err(parameter_error(py, "results", format!("invalid results: {bad} is not a finite number")));
            }
            Ok(runs)
        };
        at.tell_runs(&x, told).map_err(|e| engine_error(py, e.renamed("xs")))
    }

    /// The record of what was found so far (partial until done), as `_design` returns it.
    fn result(&self, py: Python<'_>) -> PyResult<String> {
        let at = self.lock();
        let o = at.outcome();
        record_text(py, at.problem(), &o, at.settings())
    }
}
