//! Periodic orbits from Python: `thud.orbit` (`thud orbit`), `thud.continuation` (`thud
//! continue`) and `thud.impact_map` (`thud impact-map`). Each hands the command line's `--json`
//! record to the Python layer as JSON text, which builds the result object or the xarray
//! Dataset from it (`thud/_results.py`).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use thud_core::orbit::{self, Guess, Request};
use thud_core::params::Spelling;
use thud_core::units::{self, Kind};
use thud_core::{continuation, dynamics, limits, study, ThudError};

use crate::args::{self, engine_error, parameter_error, refuse, Kwargs};
use crate::{design_of, detach, json_of, options, vary_of};

/// The `period` option: the orbit's period in forcing periods (1 to 16), if given.
fn period(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<Option<u32>> {
    if kw.option("period").is_none() {
        return Ok(None);
    }
    let n = kw.count(py, "period", &limits::ORBIT_PERIODS, 1)?;
    Ok(Some(u32::try_from(n).unwrap_or(u32::MAX)))
}

/// The `guess` option: (x, v, z, zdot) at the force's phase 0, numbers in m and m/s or texts
/// with units.
fn guess(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<Option<Guess>> {
    let Some(v) = kw.option("guess") else { return Ok(None) };
    let bad = || {
        let msg = format!(
            "invalid guess: expected (x, v, z, zdot) in m, m/s, m, m/s, not {}",
            if v.is_instance_of::<PyString>() { "a str".to_string() } else { args::kind_of(v) }
        );
        parameter_error(py, "guess", msg)
    };
    if v.is_instance_of::<PyString>() {
        return Err(bad());
    }
    let items: Vec<Bound<'_, PyAny>> = match v.try_iter() {
        Ok(it) => it.collect::<PyResult<_>>()?,
        Err(_) => return Err(bad()),
    };
    let [x, vel, z, zd] = &items[..] else { return Err(bad()) };
    let value = |item: &Bound<'_, PyAny>, kind: Kind| -> PyResult<f64> {
        let x = match args::to_value(item)? {
            thud_core::params::Input::Num(x) => x,
            thud_core::params::Input::Text(t) => units::parse("guess", &t, kind).map_err(|e| engine_error(py, e))?,
            _ => return Err(bad()),
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(parameter_error(py, "guess", format!("invalid guess: {x} is not a finite number")))
        }
    };
    Ok(Some(Guess {
        x_m: value(x, Kind::Length)?,
        v_m_s: value(vel, Kind::Speed)?,
        z_m: value(z, Kind::Length)?,
        zdot_m_s: value(zd, Kind::Speed)?,
    }))
}

/// The engine's names of the orbit's options as this module's keywords.
pub(crate) fn keyword(e: ThudError) -> ThudError {
    match e.param() {
        "vary" => e.renamed("values"),
        _ => e,
    }
}

/// _orbit(**params) -> str
///
/// The periodic orbit of a forced design found by shooting, as `thud orbit --json`. Options:
/// period (1 to 16 forcing periods; default the one the motion repeats with), symmetric
/// (look for x(t + T/2) = −x(t)), guess ((x, v, z, zdot) to start Newton's method from).
#[pyfunction]
#[pyo3(signature = (**params))]
pub fn _orbit(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    let kw = Kwargs::new(params, options("orbit"))?;
    let d = design_of(py, &kw)?;
    let req = Request { periods: period(py, &kw)?, symmetric: kw.switch(py, "symmetric")?, guess: guess(py, &kw)? };
    let o = {
        let d = d.clone();
        detach::run(py, move |cancel| orbit::find(&d, &req, Some(cancel)))?
    };
    let o = o.map_err(|e| engine_error(py, keyword(e)))?;
    thud_core::finite::check(&o).map_err(|e| args::non_finite(&e.0))?;
    let mut v = serde_json::to_value(&o).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))?;
    if let Some(m) = v.as_object_mut() {
        m.insert("design".into(), serde_json::to_value(d.design()).unwrap_or_default());
    }
    json_of(py, &v)
}

/// _continuation(name, values, **params) -> str
///
/// The family of periodic orbits of a forced design continued in `name` from the first to the
/// last of `values`, as `thud continue --json`. Options: period, symmetric (as for `_orbit`).
#[pyfunction]
#[pyo3(signature = (name, values, **params))]
pub fn _continuation(
    py: Python<'_>,
    name: &str,
    values: Vec<Bound<'_, PyAny>>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let mut kw = Kwargs::new(params, options("continuation"))?;
    let all = vary_of(py, name, &values)?;
    let (Some(&a), Some(&b)) = (all.values.first(), all.values.last()) else {
        return Err(parameter_error(py, "values", format!("invalid {name}: give FROM and TO")));
    };
    let vary = study::Vary::of_values(name, &[a, b], Spelling::Keyword).map_err(|e| engine_error(py, e))?;
    crate::frequency_from_vary(&mut kw, &vary);
    let d = design_of(py, &kw)?;
    let req = Request { periods: period(py, &kw)?, symmetric: kw.switch(py, "symmetric")?, guess: None };
    let branch = {
        let d = d.clone();
        detach::run(py, move |cancel| continuation::continue_branch(&d, &vary, &req, Some(cancel), &|_| {}))?
    };
    let branch = branch.map_err(|e| engine_error(py, keyword(e)))?;
    thud_core::finite::check(&branch).map_err(|e| args::non_finite(&e.0))?;
    let mut v =
        serde_json::to_value(&branch).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))?;
    if let Some(m) = v.as_object_mut() {
        m.insert("design".into(), serde_json::to_value(d.design()).unwrap_or_default());
        // The parameter's column as `thud continue --csv` heads it (`freq_hz`).
        m.insert("column".into(), study::column(&branch.name, &branch.unit).into());
        // The range asked for, which the figure's title names (`thud continue --svg`'s).
        m.insert("range".into(), serde_json::json!([a, b]));
    }
    json_of(py, &v)
}

/// `branches` as their JSON with each point's x(kT) at each of its orbit's periods
/// (`strobe_m`, which the files leave out), for drawing them over a bifurcation diagram.
pub(crate) fn branches_json(py: Python<'_>, branches: &[continuation::Branch]) -> PyResult<serde_json::Value> {
    let mut v =
        serde_json::to_value(branches).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))?;
    for (b, bv) in branches.iter().zip(v.as_array_mut().into_iter().flatten()) {
        for (p, pv) in b.points.iter().zip(bv["points"].as_array_mut().into_iter().flatten()) {
            pv["strobe_m"] = serde_json::json!(p.strobe_m);
        }
    }
    Ok(v)
}

/// The branches of a record's `branches` (as [`branches_json`] wrote them), each point's
/// `strobe_m` restored.
pub(crate) fn branches_of(v: &serde_json::Value) -> Result<Vec<continuation::Branch>, serde_json::Error> {
    let Some(list) = v.as_array() else { return Ok(Vec::new()) };
    list.iter()
        .map(|bv| {
            let mut b: continuation::Branch = serde_json::from_value(bv.clone())?;
            for (p, pv) in b.points.iter_mut().zip(bv["points"].as_array().into_iter().flatten()) {
                p.strobe_m =
                    serde_json::from_value(pv.get("strobe_m").cloned().unwrap_or_default()).unwrap_or_default();
            }
            Ok(b)
        })
        .collect()
}

/// _impact_map(**params) -> str
///
/// The impact map of a forced design, as `thud impact-map --json`: its stroboscopic samples
/// and its impacts over `periods` forcing periods after `transient` ones, and the orbit's type.
#[pyfunction]
#[pyo3(signature = (**params))]
pub fn _impact_map(py: Python<'_>, params: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    let kw = Kwargs::new(params, options("impact_map"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let transient = kw.count(py, "transient", &limits::TRANSIENT, dynamics::DEFAULT_TRANSIENT_PERIODS as usize)?;
    let periods = if args::given(&kw.params, "periods") { d.damper.steady_periods } else { dynamics::DEFAULT_PERIODS };
    let s = dynamics::Settings { transient_periods: u32::try_from(transient).unwrap_or(u32::MAX), periods };
    refuse(py, dynamics::check_work(1, s, false), "transient", no_limit)?;
    let run = {
        let d = d.clone();
        detach::run(py, move |cancel| dynamics::impact_map(&d, s, "force", Some(cancel)))?
    };
    let run = run.map_err(|e| engine_error(py, e))?;
    thud_core::finite::check(&run).map_err(|e| args::non_finite(&e.0))?;
    let mut v = serde_json::to_value(&run).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))?;
    if let Some(m) = v.as_object_mut() {
        m.insert("design".into(), serde_json::to_value(d.design()).unwrap_or_default());
        m.insert("settings".into(), serde_json::to_value(s).unwrap_or_default());
    }
    json_of(py, &v)
}

/// _basins(grid, w0, **params) -> str
///
/// The basins of attraction of a forced design over the ball's start, as `thud basins
/// --json`: `grid` offsets y0 across the clearance × `grid` velocities w0 from `w0[0]` to
/// `w0[1]` (m/s); each start's attractor and amplitude. Options: transient, no_limit.
#[pyfunction]
#[pyo3(signature = (grid, w0, **params))]
pub fn _basins(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    w0: (Bound<'_, PyAny>, Bound<'_, PyAny>),
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let kw = Kwargs::new(params, options("basins"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let given = PyDict::new(py);
    given.set_item("grid", grid)?;
    let n = Kwargs::new(Some(&given), &["grid"])?.count(py, "grid", &limits::GRID_N, 20)?;
    let speed = |v: &Bound<'_, PyAny>| -> PyResult<f64> {
        let x = match args::to_value(v)? {
            thud_core::params::Input::Num(x) => x,
            thud_core::params::Input::Text(t) => {
                units::parse("w0", &t, Kind::Speed).map_err(|e| engine_error(py, e))?
            }
            _ => {
                let msg = format!("invalid w0: expected (FROM, TO) in m/s, not {}", args::kind_of(v));
                return Err(parameter_error(py, "w0", msg));
            }
        };
        limits::BALL_VELOCITY.check_as("w0", x).map_err(|e| engine_error(py, e))
    };
    let (lo, hi) = (speed(&w0.0)?, speed(&w0.1)?);
    if args::given(&kw.params, "ball-position") || args::given(&kw.params, "ball-velocity") {
        let msg = "invalid grid: the basins set the ball's start; leave out ball_position and ball_velocity";
        return Err(parameter_error(py, "grid", msg.to_string()));
    }
    let transient = kw.count(py, "transient", &limits::TRANSIENT, dynamics::DEFAULT_TRANSIENT_PERIODS as usize)?;
    let periods = if args::given(&kw.params, "periods") { d.damper.steady_periods } else { dynamics::DEFAULT_PERIODS };
    let s = dynamics::Settings { transient_periods: u32::try_from(transient).unwrap_or(u32::MAX), periods };
    refuse(py, dynamics::check_work(n * n, s, false), "grid", no_limit)?;
    let w = thud_core::design::linspace(lo, hi, n);
    let b = {
        let d = d.clone();
        detach::run(py, move |cancel| dynamics::basins(&d, n, &w, s, "force", Some(cancel), &|_| {}))?
    };
    let b = b.map_err(|e| engine_error(py, e))?;
    thud_core::finite::check(&b).map_err(|e| args::non_finite(&e.0))?;
    let mut v = serde_json::to_value(&b).map_err(|e| engine_error(py, ThudError::invalid("json", e.to_string())))?;
    if let Some(m) = v.as_object_mut() {
        m.insert("design".into(), serde_json::to_value(d.design()).unwrap_or_default());
    }
    json_of(py, &v)
}

/// The restitution curve (mass, R) and, with a target R, the c1 that gives it at each mass.
type Restitutions = (Vec<(f64, f64)>, Option<Vec<f64>>);

/// _restitution(masses_kg, u0, target, **params) -> str
///
/// The restitution of one isolated contact at approach speed `u0` (m/s) against the impact
/// mass, as `thud restitution --json`'s rows: {"design", "u0_m_s", "masses_kg", "restitution",
/// "c1_for_target_n_s_m" (with a target R)}.
#[pyfunction]
#[pyo3(signature = (masses_kg, u0, target, **params))]
pub fn _restitution(
    py: Python<'_>,
    masses_kg: &Bound<'_, PyAny>,
    u0: &Bound<'_, PyAny>,
    target: Option<&Bound<'_, PyAny>>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let kw = Kwargs::new(params, options("restitution"))?;
    let no_limit = kw.switch(py, "no_limit")?;
    let d = design_of(py, &kw)?;
    let masses = crate::axis(py, "masses_kg", masses_kg, Kind::Mass, &limits::MASS)?;
    let number = |name: &str, v: &Bound<'_, PyAny>, kind: Kind, range: &limits::Range| -> PyResult<f64> {
        let x = match args::to_value(v)? {
            thud_core::params::Input::Num(x) => x,
            thud_core::params::Input::Text(t) => units::parse(name, &t, kind).map_err(|e| engine_error(py, e))?,
            _ => {
                let msg = format!("invalid {name}: expected a number, not {}", args::kind_of(v));
                return Err(parameter_error(py, name, msg));
            }
        };
        range.check_as(name, x).map_err(|e| engine_error(py, e))
    };
    let u0 = number("u0", u0, Kind::Speed, &limits::U0)?;
    let target =
        target.filter(|t| !t.is_none()).map(|t| number("target", t, Kind::Number, &limits::TARGET)).transpose()?;
    let contacts = limits::restitution_contacts(masses.len(), target.is_some());
    let per_mass = contacts.value / masses.len() as f64;
    let hint = format!("use at most {} masses", limits::short((contacts.cap.max / per_mass).floor()));
    args::enforce(py, contacts, "masses_kg", &hint, no_limit)?;
    let out = {
        let d = d.clone();
        detach::run(py, move |_| -> Result<Restitutions, ThudError> {
            let curve = thud_core::design::restitution_curve(&d, &masses, u0)?;
            let c1 = match target {
                None => None,
                Some(t) => Some(
                    curve
                        .iter()
                        .map(|&(m, _)| {
                            let v = thud_core::design::variant(&d, m, d.damper.gap_m).check()?;
                            thud_core::design::c1_for_restitution(&v, u0, t)
                        })
                        .collect::<Result<Vec<f64>, ThudError>>()?,
                ),
            };
            Ok((curve, c1))
        })?
    };
    let (curve, c1) = out.map_err(|e| engine_error(py, e))?;
    let v = serde_json::json!({
        "design": d.design(),
        "u0_m_s": u0,
        "target": target,
        "masses_kg": curve.iter().map(|c| c.0).collect::<Vec<f64>>(),
        "restitution": curve.iter().map(|c| c.1).collect::<Vec<f64>>(),
        "c1_for_target_n_s_m": c1,
    });
    thud_core::finite::check(&v).map_err(|e| args::non_finite(&e.0))?;
    json_of(py, &v)
}
