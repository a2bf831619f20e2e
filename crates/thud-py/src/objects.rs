//! The results handed to Python: `Pulse`, `Run` and `Chart`, the very numbers of the command
//! line's `pulse --json`, `simulate --json` and `sweep --json` (computed by the same engine
//! calls), with sequences as NumPy arrays. Each number is checked finite before it is handed
//! out; a value that does not exist (no impact, so no SPL) is `None`, or NaN in a chart array
//! (zone 0).

use std::sync::atomic::AtomicBool;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;
use thud_core::acoustics::{Extremum, Levels};
use thud_core::contact::Contact;
use thud_core::damper::free_response;
use thud_core::design::{self, Design, Evaluation};
use thud_core::limits::{self, short};
use thud_core::params::PulseInput;
use thud_core::ThudError;

use crate::args::{engine_error, non_finite, parameter_error};

/// `v` if finite, else the internal error naming `what`.
fn finite(what: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(non_finite(what))
    }
}

/// An optional number: None stays None, a number must be finite.
fn finite_opt(what: &str, v: Option<f64>) -> PyResult<Option<f64>> {
    v.map(|x| finite(what, x)).transpose()
}

/// A NumPy array of `values`, each checked finite.
fn array(py: Python<'_>, what: &str, values: Vec<f64>) -> PyResult<Py<PyAny>> {
    if values.iter().any(|v| !v.is_finite()) {
        return Err(non_finite(what));
    }
    Ok(PyArray1::from_vec(py, values).into_any().unbind())
}

/// A dict of NumPy arrays, one per (key, values), each checked finite.
fn arrays(py: Python<'_>, what: &str, columns: Vec<(&str, Vec<f64>)>) -> PyResult<Py<PyDict>> {
    let d = PyDict::new(py);
    for (key, values) in columns {
        d.set_item(key, array(py, &format!("{what}.{key}"), values)?)?;
    }
    Ok(d.unbind())
}

/// `value` as Python data (dicts, lists, numbers, strings) through its JSON form, so a
/// design reads exactly as in the command line's `--json`.
fn json_data<T: Serialize>(py: Python<'_>, what: &str, value: &T) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| non_finite(&format!("{what} ({e})")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// Everything a `Pulse` holds, computed without the GIL.
pub struct PulseData {
    input: PulseInput,
    contact: Contact,
    arrival_s: f64,
    levels: Levels,
    extrema: Vec<Extremum>,
    t_s: Vec<f64>,
    p_pa: Vec<f64>,
}

impl PulseData {
    /// The pulse of `input` with a waveform of `points` points — the engine calls of
    /// `thud pulse --json`.
    pub fn compute(input: PulseInput, points: usize) -> Result<PulseData, ThudError> {
        let contact = input.contact();
        let field = input.field(&contact)?;
        let (t_s, p_pa) = field.waveform(points);
        Ok(PulseData {
            arrival_s: field.arrival_s(),
            levels: field.levels(),
            extrema: field.extrema(),
            contact,
            input,
            t_s,
            p_pa,
        })
    }
}

/// One Hertzian impact heard at one observer (`thud.pulse`): the inputs as used, the contact
/// (Eqs 5–7), the levels and the waveform. SI units; angles in degrees; levels in dB re 20 µPa.
#[pyclass(module = "thud", frozen, get_all)]
pub struct Pulse {
    /// Sphere radius a (m).
    radius_m: f64,
    /// Sphere mass m (kg).
    mass_kg: f64,
    /// Impact speed U0 (m/s).
    u0_m_s: f64,
    /// Hertz stiffness K_HZ (N/m^1.5).
    k_hz: f64,
    /// Observer distance r (m).
    r_m: f64,
    /// Observer angle θ (degrees).
    theta_deg: f64,
    /// "single", "dipole" or "quadrupole".
    source: String,
    /// "paper" or "rigid".
    quad_signs: String,
    /// "half-sine" or "hertz".
    pulse: String,
    /// Air impedance ρ0·c (Pa·s/m).
    rho_c_pa_s_m: f64,
    /// Speed of sound c (m/s).
    c_m_s: f64,
    /// Peak approach α_max (m).
    alpha_max_m: f64,
    /// Peak acceleration A_max (m/s²).
    accel_max_m_s2: f64,
    /// Contact duration τ (s).
    tau_s: f64,
    /// Peak contact force (N).
    force_max_n: f64,
    /// Arrival of the direct wave (s after the contact starts).
    arrival_s: f64,
    /// SPL (dB): rms over one contact duration from the direct arrival.
    spl_db: f64,
    /// How spl_db is defined.
    spl_definition: String,
    /// Peak level (dB).
    spl_peak_db: f64,
    /// Sound exposure level (dB).
    sel_db: f64,
    /// rms pressure over the SPL window (Pa).
    p_rms_pa: f64,
    /// Largest pressure (Pa).
    p_max_pa: f64,
    /// Smallest pressure (Pa).
    p_min_pa: f64,
    /// Local extrema of the waveform: {"t_s": array (s), "p_pa": array (Pa)}.
    extrema: Py<PyDict>,
    /// Waveform times (s), from the contact's start.
    t_s: Py<PyAny>,
    /// Waveform pressure (Pa).
    p_pa: Py<PyAny>,
}

impl Pulse {
    pub fn new(py: Python<'_>, d: PulseData) -> PyResult<Pulse> {
        let (c, lv, i) = (&d.contact, &d.levels, &d.input);
        let (ext_t, ext_p) = d.extrema.iter().map(|e| (e.t_s, e.p_pa)).unzip();
        Ok(Pulse {
            radius_m: finite("radius_m", i.radius_m)?,
            mass_kg: finite("mass_kg", i.impact.mass_kg)?,
            u0_m_s: finite("u0_m_s", i.impact.u0_m_s)?,
            k_hz: finite("k_hz", i.impact.k_hz)?,
            r_m: finite("r_m", i.observer.r_m)?,
            theta_deg: finite("theta_deg", i.observer.theta_rad.to_degrees())?,
            source: i.radiation.source.name().to_string(),
            quad_signs: i.radiation.quad_signs.name().to_string(),
            pulse: i.radiation.pulse.name().to_string(),
            rho_c_pa_s_m: finite("rho_c_pa_s_m", i.radiation.air.rho_c_pa_s_m)?,
            c_m_s: finite("c_m_s", i.radiation.air.c_m_s)?,
            alpha_max_m: finite("alpha_max_m", c.alpha_max_m)?,
            accel_max_m_s2: finite("accel_max_m_s2", c.accel_max_m_s2)?,
            tau_s: finite("tau_s", c.tau_s)?,
            force_max_n: finite("force_max_n", c.force_max_n)?,
            arrival_s: finite("arrival_s", d.arrival_s)?,
            spl_db: finite("spl_db", lv.spl_db)?,
            spl_definition: "rms over one contact duration from the direct arrival".to_string(),
            spl_peak_db: finite("spl_peak_db", lv.spl_peak_db)?,
            sel_db: finite("sel_db", lv.sel_db)?,
            p_rms_pa: finite("p_rms_pa", lv.p_rms_pa)?,
            p_max_pa: finite("p_max_pa", lv.p_max_pa)?,
            p_min_pa: finite("p_min_pa", lv.p_min_pa)?,
            extrema: arrays(py, "extrema", vec![("t_s", ext_t), ("p_pa", ext_p)])?,
            t_s: array(py, "t_s", d.t_s)?,
            p_pa: array(py, "p_pa", d.p_pa)?,
        })
    }
}

#[pymethods]
impl Pulse {
    /// Every field in one dict (the command line's JSON keys; the waveform as "t_s"/"p_pa").
    fn as_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let numbers = [
            ("radius_m", self.radius_m),
            ("mass_kg", self.mass_kg),
            ("u0_m_s", self.u0_m_s),
            ("k_hz", self.k_hz),
            ("r_m", self.r_m),
            ("theta_deg", self.theta_deg),
            ("rho_c_pa_s_m", self.rho_c_pa_s_m),
            ("c_m_s", self.c_m_s),
            ("alpha_max_m", self.alpha_max_m),
            ("accel_max_m_s2", self.accel_max_m_s2),
            ("tau_s", self.tau_s),
            ("force_max_n", self.force_max_n),
            ("arrival_s", self.arrival_s),
            ("spl_db", self.spl_db),
            ("spl_peak_db", self.spl_peak_db),
            ("sel_db", self.sel_db),
            ("p_rms_pa", self.p_rms_pa),
            ("p_max_pa", self.p_max_pa),
            ("p_min_pa", self.p_min_pa),
        ];
        for (k, v) in numbers {
            d.set_item(k, v)?;
        }
        for (k, v) in [
            ("source", &self.source),
            ("quad_signs", &self.quad_signs),
            ("pulse", &self.pulse),
            ("spl_definition", &self.spl_definition),
        ] {
            d.set_item(k, v)?;
        }
        d.set_item("extrema", self.extrema.clone_ref(py))?;
        d.set_item("t_s", self.t_s.clone_ref(py))?;
        d.set_item("p_pa", self.p_pa.clone_ref(py))?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Pulse(a={} m, m={} kg, U0={} m/s, {} at r={} m, θ={}°: τ={} s, SPL={:.2} dB, peak {:.2} dB)",
            short(self.radius_m),
            short(self.mass_kg),
            short(self.u0_m_s),
            self.source,
            short(self.r_m),
            short(self.theta_deg),
            short(self.tau_s),
            self.spl_db,
            self.spl_peak_db
        )
    }
}

/// Everything a `Run` holds, computed without the GIL.
pub struct RunData {
    eval: Evaluation,
    spls: Vec<f64>,
    x_free: Vec<f64>,
}

impl RunData {
    /// `design` simulated with `samples` history samples — the engine calls of
    /// `thud simulate --json` (and of `--csv` for the history).
    pub fn compute(d: Design, samples: usize, cancel: &AtomicBool) -> Result<RunData, ThudError> {
        let eval = design::evaluate(&d, samples, Some(cancel))?;
        let spls = design::impact_spls(&eval.run, &d)?;
        let x_free = eval.run.history.iter().map(|h| free_response(&d.damper, h.t_s)).collect();
        Ok(RunData { eval, spls, x_free })
    }
}

/// One damper design run through its impacts (`thud.simulate`): the metrics (Eq 27 e, e_fit,
/// U0max, SPLmax, zone), every impact, the cycle maxima, the energy ledger and the time history.
/// SI units; inclinations in cm/s; levels in dB re 20 µPa. None = no such value (too few
/// maxima for e, no impact for SPLmax).
#[pyclass(module = "thud", frozen, get_all)]
pub struct Run {
    /// The design as run (the command line's JSON "design" object).
    design: Py<PyAny>,
    /// Ball radius (m).
    ball_radius_m: f64,
    /// Number of impacts.
    n_impacts: usize,
    /// Damping inclination e of Eq 27 (cm/s).
    inclination_cm_s: Option<f64>,
    /// Robust least-squares inclination e_fit (cm/s).
    inclination_fit_cm_s: Option<f64>,
    /// Largest contact speed by the design's rule, U0max (m/s).
    u0_max_m_s: f64,
    /// Largest |z'| over the run including t = 0 (m/s).
    zdot_abs_max_m_s: f64,
    /// SPL of an impact at U0max, SPLmax (dB).
    spl_max_db: Option<f64>,
    /// Contact duration at U0max (s).
    contact_duration_s: Option<f64>,
    /// Mean restitution u_out/u_in.
    restitution_mean: Option<f64>,
    /// Zone 1–4 (3 = quiet and strong, the target).
    zone: Option<u8>,
    /// Every impact, as arrays: t_s (s), wall (±1, int8), u_in_m_s, u_out_m_s (m/s),
    /// restitution, t_end_s, duration_s (s), penetration_max_m (m), spl_db (dB).
    impacts: Py<PyDict>,
    /// Cycle maxima of the main mass: t_s (s), x_m (m).
    maxima: Py<PyDict>,
    /// Energy ledger (J): initial_j, final_mechanical_j, dissipated_viscous_j, dissipated_contact_j.
    energy: Py<PyDict>,
    /// Time reached (s).
    final_time_s: f64,
    /// Whether the solver's work cap stopped the run before its duration.
    truncated: bool,
    /// Why, when it did.
    truncation_reason: Option<String>,
    /// Uniform time history: t_s (s), x_m (main mass, m), y_m (ball, m), x_free_m (no damper, m).
    history: Py<PyDict>,
}

impl Run {
    pub fn new(py: Python<'_>, d: &Design, data: RunData) -> PyResult<Run> {
        let RunData { eval, spls, x_free } = data;
        let (run, m) = (&eval.run, &eval.metrics);
        let col = |f: fn(&thud_core::damper::ImpactEvent) -> f64| run.impacts.iter().map(f).collect::<Vec<f64>>();
        let impacts = arrays(
            py,
            "impacts",
            vec![
                ("t_s", col(|i| i.t_s)),
                ("u_in_m_s", col(|i| i.u_in_m_s)),
                ("u_out_m_s", col(|i| i.u_out_m_s)),
                ("restitution", col(|i| i.u_out_m_s / i.u_in_m_s)),
                ("t_end_s", col(|i| i.t_end_s)),
                ("duration_s", col(|i| i.t_end_s - i.t_s)),
                ("penetration_max_m", col(|i| i.penetration_max_m)),
                ("spl_db", spls),
            ],
        )?;
        let walls: Vec<i8> = run.impacts.iter().map(|i| i8::from(i.wall)).collect();
        impacts.bind(py).set_item("wall", walls.into_pyarray(py))?;
        let energy = PyDict::new(py);
        let en = &run.energy;
        for (k, v) in [
            ("initial_j", en.initial_j),
            ("final_mechanical_j", en.final_mechanical_j),
            ("dissipated_viscous_j", en.dissipated_viscous_j),
            ("dissipated_contact_j", en.dissipated_contact_j),
        ] {
            energy.set_item(k, finite(&format!("energy.{k}"), v)?)?;
        }
        let truncation_reason = design::truncation(run, d.damper.duration_s);
        Ok(Run {
            design: json_data(py, "design", d)?,
            ball_radius_m: finite("ball_radius_m", d.ball_radius_m())?,
            n_impacts: m.n_impacts,
            inclination_cm_s: finite_opt("inclination_cm_s", m.inclination_cm_s)?,
            inclination_fit_cm_s: finite_opt("inclination_fit_cm_s", m.inclination_fit_cm_s)?,
            u0_max_m_s: finite("u0_max_m_s", m.u0_max_m_s)?,
            zdot_abs_max_m_s: finite("zdot_abs_max_m_s", m.zdot_abs_max_m_s)?,
            spl_max_db: finite_opt("spl_max_db", m.spl_max_db)?,
            contact_duration_s: finite_opt("contact_duration_s", m.contact_duration_s)?,
            restitution_mean: finite_opt("restitution_mean", m.restitution_mean)?,
            zone: m.zone.map(thud_core::design::Zone::number),
            impacts,
            maxima: arrays(
                py,
                "maxima",
                vec![
                    ("t_s", run.maxima.iter().map(|x| x.t_s).collect()),
                    ("x_m", run.maxima.iter().map(|x| x.x_m).collect()),
                ],
            )?,
            energy: energy.unbind(),
            final_time_s: finite("final_time_s", run.final_time_s)?,
            truncated: truncation_reason.is_some(),
            truncation_reason,
            history: arrays(
                py,
                "history",
                vec![
                    ("t_s", run.history.iter().map(|h| h.t_s).collect()),
                    ("x_m", run.history.iter().map(|h| h.x_m).collect()),
                    ("y_m", run.history.iter().map(|h| h.y_m).collect()),
                    ("x_free_m", x_free),
                ],
            )?,
        })
    }
}

#[pymethods]
impl Run {
    /// Every field in one dict (the command line's JSON keys, plus "history").
    fn as_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
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
        d.set_item("history", self.history.clone_ref(py))?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let opt = |v: Option<f64>, digits: usize| v.map_or("None".into(), |x| format!("{x:.digits$}"));
        format!(
            "Run({} impacts, e={} cm/s, e_fit={} cm/s, U0max={:.4} m/s, SPLmax={} dB, zone={}{})",
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

/// The design chart of a sweep (`thud.sweep`): every metric as a 2-D array of shape
/// (len(gaps_m), len(masses_kg)) — row = gap, column = mass, as `pcolormesh(masses_kg, gaps_m,
/// chart.zone)` wants. NaN marks a value that does not exist (no impact: no SPLmax; too few
/// maxima: no e); zone 0 marks no zone.
#[pyclass(module = "thud", frozen)]
pub struct Chart {
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
    /// The engine's chart, kept for `Chart.table5`.
    chart: design::Chart,
}

impl Chart {
    pub fn new(py: Python<'_>, d: &Design, chart: design::Chart) -> PyResult<Chart> {
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
        Ok(Chart {
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
            chart,
        })
    }
}

/// A (rows, cols) NumPy array of `v` (row-major: `v[row * cols + col]`).
fn to_2d<T: numpy::Element>(py: Python<'_>, rows: usize, cols: usize, v: Vec<T>) -> PyResult<Py<PyAny>> {
    let a = Array2::from_shape_vec((rows, cols), v)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("internal error: chart shape: {e}")))?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

#[pymethods]
impl Chart {
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
        let d = PyDict::new(py);
        let col = |f: fn(&design::Band) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
        for (k, v) in [
            ("e_lo_cm_s", col(|b| b.e_lo_cm_s)),
            ("e_hi_cm_s", col(|b| b.e_hi_cm_s)),
            ("spl_min_db", col(|b| b.spl_min_db)),
            ("spl_max_db", col(|b| b.spl_max_db)),
        ] {
            d.set_item(k, array(py, &format!("table5.{k}"), v)?)?;
        }
        let counts: Vec<i64> = rows.iter().map(|b| b.count as i64).collect();
        d.set_item("count", counts.into_pyarray(py))?;
        Ok(d)
    }

    /// Every field in one dict (the 2-D arrays by metric name).
    fn as_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
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
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let c = &self.chart;
        let zone3 = c.cells.iter().flatten().filter(|c| c.metrics.zone.is_some_and(|z| z.number() == 3)).count();
        format!("Chart({} masses × {} gaps, {} cells in zone 3)", c.masses_kg.len(), c.gaps_m.len(), zone3)
    }
}
