//! `thud.limits()`: every parameter's range and every work cap, the table of `thud limits --json`.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use thud_core::limits::{Cap, CAPS, COUNTS, GRID_N};

/// A cap as `thud limits --json` writes it: {basis, max, what}.
fn cap<'py>(py: Python<'py>, what: &str, max: f64, basis: &str) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("basis", basis)?;
    d.set_item("max", max)?;
    d.set_item("what", what)?;
    Ok(d)
}

/// limits() -> dict
///
/// The valid range of every parameter and the work cap of every run: the table of the command
/// line's `thud limits --json`, key for key ({"caps": [{basis, max, what}, …],
/// "orbit_seed_impacts_max": …, "orbit_transient_periods_max": …, "ranges": [{max, min, param,
/// reason, unit, what}, …], "settle_periods_max": …, "solver_caps": […]}); a range's `param`
/// is the command line's flag without its dashes (`ranges()` gives Python's keywords).
/// `no_limit=True` on a call lifts the caps.
#[pyfunction]
pub(crate) fn limits(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let ranges = PyList::empty(py);
    // The sweep axis's N is a part of FROM:TO:N, not a flag: the command line's JSON leaves it out.
    for r in
        thud_core::params::listed_ranges().into_iter().chain(COUNTS.into_iter().filter(|r| r.param != GRID_N.param))
    {
        let row = PyDict::new(py);
        row.set_item("max", r.max)?;
        row.set_item("min", r.min)?;
        row.set_item("param", r.param)?;
        row.set_item("reason", r.reason)?;
        row.set_item("unit", r.unit)?;
        row.set_item("what", r.what)?;
        ranges.append(row)?;
    }
    let caps = PyList::empty(py);
    for c in CAPS.iter().map(|c: &Cap| cap(py, c.what, c.max, c.basis)) {
        caps.append(c?)?;
    }
    let solver = PyList::empty(py);
    for c in thud_core::damper::SOLVER_CAPS.iter().map(|c| cap(py, c.what, c.max, c.basis)) {
        solver.append(c?)?;
    }
    let out = PyDict::new(py);
    out.set_item("caps", caps)?;
    out.set_item("orbit_seed_impacts_max", thud_core::orbit::SETTLE_IMPACTS_MAX)?;
    out.set_item("orbit_transient_periods_max", thud_core::orbit::MAX_TRANSIENT_PERIODS)?;
    out.set_item("ranges", ranges)?;
    out.set_item("settle_periods_max", thud_core::damper::SETTLE_PERIODS_MAX)?;
    out.set_item("solver_caps", solver)?;
    Ok(out)
}
