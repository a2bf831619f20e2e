//! `Pulse`: one Hertzian impact heard at one observer.

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use serde_json::Value as Json;
use thud_core::limits::short;
use thud_core::params::PulseInput;
use thud_core::report::PulseReport;
use thud_core::ThudError;

use super::convert::{array, checked, columns, fill, frames, missing, num, order_of, plain, rows_of, text};
use super::pickle::{reduce, Reduced};
use crate::render::{pulse_bytes, PulseFile};

/// Everything a `Pulse` holds, computed without the GIL.
pub struct PulseData(PulseReport);

impl PulseData {
    /// The pulse of `input` with a waveform of `points` points — the record of
    /// `thud pulse --json`.
    pub fn compute(input: &PulseInput, points: usize) -> Result<PulseData, ThudError> {
        let contact = input.contact();
        let field = input.field(&contact)?;
        Ok(PulseData(PulseReport::new(input, &contact, &field, points)))
    }
}

/// One Hertzian impact heard at one observer (`thud.pulse`): the inputs as used, the contact
/// (Eqs 5–7), the levels and the waveform. SI units; angles in degrees; levels in dB re 20 µPa.
#[pyclass(name = "Pulse", module = "thud", frozen)]
pub struct PyPulse {
    /// Sphere radius a (m).
    #[pyo3(get)]
    radius_m: f64,
    /// Sphere mass m (kg).
    #[pyo3(get)]
    mass_kg: f64,
    /// Impact speed U0 (m/s).
    #[pyo3(get)]
    u0_m_s: f64,
    /// Hertz stiffness K_HZ (N/m^1.5).
    #[pyo3(get)]
    k_hz_n_m1_5: f64,
    /// Observer distance r (m).
    #[pyo3(get)]
    r_m: f64,
    /// Observer angle θ (degrees).
    #[pyo3(get)]
    theta_deg: f64,
    /// "single", "dipole" or "quadrupole".
    #[pyo3(get)]
    source: String,
    /// "paper" or "rigid".
    #[pyo3(get)]
    quad_signs: String,
    /// "half-sine" or "hertz".
    #[pyo3(get)]
    pulse: String,
    /// Air impedance ρ0·c (Pa·s/m).
    #[pyo3(get)]
    rho_c_pa_s_m: f64,
    /// Speed of sound c (m/s).
    #[pyo3(get)]
    c_m_s: f64,
    /// Peak approach α_max (m).
    #[pyo3(get)]
    alpha_max_m: f64,
    /// Peak acceleration A_max (m/s²).
    #[pyo3(get)]
    accel_max_m_s2: f64,
    /// Contact duration τ (s).
    #[pyo3(get)]
    tau_s: f64,
    /// Peak contact force (N).
    #[pyo3(get)]
    force_max_n: f64,
    /// Arrival of the direct wave (s after the contact starts).
    #[pyo3(get)]
    arrival_s: f64,
    /// SPL (dB): rms over one contact duration from the direct arrival.
    #[pyo3(get)]
    spl_db: f64,
    /// How spl_db is defined.
    #[pyo3(get)]
    spl_definition: String,
    /// Peak level (dB).
    #[pyo3(get)]
    spl_peak_db: f64,
    /// Sound exposure level (dB).
    #[pyo3(get)]
    sel_db: f64,
    /// rms pressure over the SPL window (Pa).
    #[pyo3(get)]
    p_rms_pa: f64,
    /// Largest pressure (Pa).
    #[pyo3(get)]
    p_max_pa: f64,
    /// Smallest pressure (Pa).
    #[pyo3(get)]
    p_min_pa: f64,
    /// Local extrema of the waveform: {"t_s": array (s), "p_pa": array (Pa)}.
    #[pyo3(get)]
    extrema: Py<PyDict>,
    /// Waveform times (s), from the contact's start.
    #[pyo3(get)]
    t_s: Py<PyAny>,
    /// Waveform pressure (Pa).
    #[pyo3(get)]
    p_pa: Py<PyAny>,
    /// The record, for `as_dict`.
    record: Json,
}

impl PyPulse {
    pub fn new(py: Python<'_>, data: PulseData) -> PyResult<PyPulse> {
        Self::from_record(py, checked("pulse", &data.0)?)
    }

    /// The pulse of the record of `thud pulse --json` (finite already).
    pub(super) fn from_record(py: Python<'_>, record: Json) -> PyResult<PyPulse> {
        const W: &str = "pulse";
        let number = |k: &str| num(W, &record, k);
        let wave = record.get("waveform").ok_or_else(|| missing(W, "waveform"))?;
        let series = |k: &str| -> PyResult<Vec<f64>> {
            let v = wave.get(k).and_then(Json::as_array).ok_or_else(|| missing(W, k))?;
            v.iter().map(|x| x.as_f64().ok_or_else(|| missing(W, k))).collect()
        };
        let template = serde_json::json!({"t_s": 0.0, "p_pa": 0.0});
        let extrema = rows_of(&record, "extrema");
        let order = order_of::<thud_core::acoustics::Extremum>(extrema.first());
        Ok(PyPulse {
            extrema: columns(py, &extrema, Some(&template), &[], &order)?,
            t_s: array(py, "t_s", series("t_s")?)?,
            p_pa: array(py, "p_pa", series("p_pa")?)?,
            radius_m: number("radius_m")?,
            mass_kg: number("mass_kg")?,
            u0_m_s: number("u0_m_s")?,
            k_hz_n_m1_5: number("k_hz_n_m1_5")?,
            r_m: number("r_m")?,
            theta_deg: number("theta_deg")?,
            source: text(W, &record, "source")?,
            quad_signs: text(W, &record, "quad_signs")?,
            pulse: text(W, &record, "pulse")?,
            rho_c_pa_s_m: number("rho_c_pa_s_m")?,
            c_m_s: number("c_m_s")?,
            alpha_max_m: number("alpha_max_m")?,
            accel_max_m_s2: number("accel_max_m_s2")?,
            tau_s: number("tau_s")?,
            force_max_n: number("force_max_n")?,
            arrival_s: number("arrival_s")?,
            spl_db: number("spl_db")?,
            spl_definition: text(W, &record, "spl_definition")?,
            spl_peak_db: number("spl_peak_db")?,
            sel_db: number("sel_db")?,
            p_rms_pa: number("p_rms_pa")?,
            p_max_pa: number("p_max_pa")?,
            p_min_pa: number("p_min_pa")?,
            record,
        })
    }
}

#[pymethods]
impl PyPulse {
    /// as_dict(json=False) -> dict
    ///
    /// Every field in one dict (the command line's JSON keys; the waveform as "t_s"/"p_pa").
    /// json=True: plain lists, numbers and None only (NaN → None), ready for `json.dumps`.
    #[pyo3(signature = (json = false))]
    fn as_dict(&self, py: Python<'_>, json: bool) -> PyResult<Py<PyAny>> {
        let d = PyDict::new(py);
        let extrema = self.extrema.clone_ref(py).into_any();
        fill(
            py,
            &d,
            &self.record,
            &["waveform", "extrema"],
            &[("extrema", &extrema), ("t_s", &self.t_s), ("p_pa", &self.p_pa)],
        )?;
        plain(py, d, json)
    }

    /// to_dataframe() -> pandas.DataFrame
    ///
    /// The waveform as a table: t_s (s), p_pa (Pa); the scalars in `.attrs`. Needs pandas.
    fn to_dataframe(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "pulse_frame", slf.as_any())
    }

    /// to_xarray() -> xarray.Dataset
    ///
    /// The waveform on the dimension t_s (s): p_pa (Pa); the scalars in `.attrs`. Needs xarray.
    fn to_xarray(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "pulse_xarray", slf.as_any())
    }

    fn _repr_html_(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        frames(slf.py(), "repr_html", slf.as_any())
    }

    /// _file(kind, size=None, title=True, full_scale=20.0, format="pcm16") -> bytes
    ///
    /// The bytes `thud export svg|pdf|wav pulse` (kind "svg", "pdf" or "wav") writes for this
    /// impact; the Python package writes them to a file (`to_svg`, `to_pdf`, `to_wav`).
    #[pyo3(signature = (kind, size = None, title = true, full_scale = 20.0, format = "pcm16".to_string()))]
    fn _file<'py>(
        &self,
        py: Python<'py>,
        kind: &str,
        size: Option<(f64, f64)>,
        title: bool,
        full_scale: f64,
        format: String,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let what = match kind {
            "svg" | "pdf" => PulseFile::Figure { pdf: kind == "pdf", size, title },
            "wav" => PulseFile::Sound { full_scale, format },
            _ => {
                let msg = format!("invalid kind: '{kind}'; expected svg, pdf or wav");
                return Err(crate::args::parameter_error(py, "kind", msg));
            }
        };
        pulse_bytes(py, &self.record, what)
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        reduce(py, "Pulse", &self.record)
    }

    /// Equal when the records are (every field; an unpickled pulse equals its original).
    fn __eq__(&self, other: PyRef<'_, Self>) -> bool {
        self.record == other.record
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
