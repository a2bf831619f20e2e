//! Figures and sound from Python: `_render(kind, design, …)` is the bytes `thud export
//! svg|pdf|wav KIND` writes for the same design and options (the renderers of `thud-render`,
//! shared with the command line); the Python package writes them to a file.

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use serde::Deserialize;
use thud_core::design::Design;
use thud_core::limits;
use thud_core::ThudError;
use thud_render::artifact::{self, Artifact, ExportOptions, RenderError};
use thud_render::dynamics::short_design;
use thud_render::svg::{self, Look};
use thud_render::wav::{SampleFormat, WavOptions};

use crate::args::{engine_error, parameter_error};
use crate::detach;

/// The artifact a figure or sound name names, as `thud export svg|wav NAME` spells it.
fn artifact(py: Python<'_>, kind: &str) -> PyResult<Artifact> {
    Ok(match kind {
        "waveform" => Artifact::SvgWaveform,
        "directivity" => Artifact::SvgDirectivity,
        "history" => Artifact::SvgHistory,
        "restitution" => Artifact::SvgRestitution,
        "chart" => Artifact::SvgChart,
        "fig17" => Artifact::SvgFig17,
        "response" => Artifact::SvgResponse,
        "wav" => Artifact::Wav,
        _ => {
            let msg = format!(
                "invalid kind: '{kind}'; expected waveform, directivity, history, restitution, chart, fig17, response or wav"
            );
            return Err(parameter_error(py, "kind", msg));
        }
    })
}

/// A number of a render option inside `range`, named as the keyword.
fn within(py: Python<'_>, name: &str, x: f64, range: &limits::Range) -> PyResult<f64> {
    range.check_as(name, x).map_err(|e| engine_error(py, e))
}

/// _render(kind, design, pdf=False, points=2001, u0=None, masses_kg=None, gaps_m=None,
/// freqs_hz=None, continuation=False, size=None, title=True, full_scale=20.0, format="pcm16")
/// -> bytes
///
/// The file `thud export svg KIND` (`pdf=True`: `thud export pdf KIND`; kind "wav": `thud export
/// wav`) writes for `design` (the JSON of a result's "design"), with the same options.
#[pyfunction]
#[pyo3(signature = (kind, design, pdf = false, points = 2001, u0 = None, masses_kg = None, gaps_m = None,
    freqs_hz = None, continuation = false, size = None, title = true, full_scale = 20.0, format = "pcm16"))]
// Over 80 lines: one keyword of `thud export` checked a few lines each, then one render.
#[allow(clippy::too_many_arguments)]
pub fn _render<'py>(
    py: Python<'py>,
    kind: &str,
    design: &str,
    pdf: bool,
    points: usize,
    u0: Option<f64>,
    masses_kg: Option<Vec<f64>>,
    gaps_m: Option<Vec<f64>>,
    freqs_hz: Option<Vec<f64>>,
    continuation: bool,
    size: Option<(f64, f64)>,
    title: bool,
    full_scale: f64,
    format: &str,
) -> PyResult<Bound<'py, PyBytes>> {
    let kind = artifact(py, kind)?;
    let d: Design = serde_json::from_str(design)
        .map_err(|e| parameter_error(py, "design", format!("invalid design: not a thud design ({e})")))?;
    let d = d.check().map_err(|e| engine_error(py, e))?;
    let points = within(py, "points", points as f64, &limits::POINTS)? as usize;
    if let Some(u) = u0 {
        within(py, "u0", u, &limits::U0)?;
    }
    for m in masses_kg.iter().flatten() {
        within(py, "masses_kg", *m, &limits::MASS)?;
    }
    for g in gaps_m.iter().flatten() {
        within(py, "gaps_m", *g, &limits::GAP)?;
    }
    for f in freqs_hz.iter().flatten() {
        within(py, "freqs_hz", *f, &limits::FREQ)?;
    }
    check_size(py, size)?;
    let format = sample_format(py, format)?;
    let full_scale_pa = within(py, "full_scale", full_scale, &limits::FULL_SCALE)?;
    if pdf && !kind.is_figure() {
        return Err(parameter_error(
            py,
            "kind",
            "invalid kind: a WAV is no figure; only figures are made as PDF".into(),
        ));
    }
    let freqs_hz = if kind.is_response() {
        Some(freqs_hz.unwrap_or_else(|| artifact::response_freqs(&ExportOptions::default(), &d)))
    } else {
        freqs_hz
    };
    let opts = ExportOptions {
        u0_m_s: u0,
        masses_kg,
        gaps_m,
        points,
        wav: WavOptions { format, full_scale_pa, ..WavOptions::default() },
        freqs_hz,
        continuation,
        ensemble_runs: 1,
        look: Look { size, title },
    };
    // The error boxed: it crosses the thread boundary of `detach::run` by value.
    let bytes = detach::run(py, move |_| {
        if pdf {
            artifact::render_pdf(kind, &d, &opts).map_err(Box::new)
        } else {
            artifact::render(kind, &d, &opts).map_err(Box::new)
        }
    })?;
    let bytes = bytes.map_err(|e| match *e {
        RenderError::Invalid(t) => engine_error(py, t),
        other => engine_error(py, ThudError::invalid("render", other.to_string())),
    })?;
    Ok(PyBytes::new(py, &bytes))
}

/// _figure(kind, record, pdf=False, size=None, title=True) -> bytes
///
/// The figure `thud basins --svg` (kind "basins"), `thud impact-map --svg` (kind
/// "impact_map"), `thud bifurcation --svg` (kind "bifurcation"; with the record's "branches",
/// `--branches N`'s), `thud continue --svg` (kind "continuation") or `thud sweep --vary … --svg`
/// (kind "study", over one or two parameters) draws, from the result's
/// record (its `--json` object; a bifurcation's under "bifurcation"); `pdf=True`: `--pdf`.
#[pyfunction]
#[pyo3(signature = (kind, record, pdf = false, size = None, title = true))]
pub fn _figure<'py>(
    py: Python<'py>,
    kind: &str,
    record: &str,
    pdf: bool,
    size: Option<(f64, f64)>,
    title: bool,
) -> PyResult<Bound<'py, PyBytes>> {
    check_size(py, size)?;
    let look = Look { size, title };
    let bad = |e: serde_json::Error| parameter_error(py, "record", format!("invalid record: not thud's ({e})"));
    let value: serde_json::Value = serde_json::from_str(record).map_err(bad)?;
    let design: Design = serde_json::from_value(value.get("design").cloned().unwrap_or_default()).map_err(bad)?;
    let svg = match kind {
        "basins" => {
            let b: thud_core::dynamics::Basins = serde_json::from_value(value).map_err(bad)?;
            let t = format!("Basins of attraction over the ball's start — {}", short_design(&design, ""));
            thud_render::dynamics::basins_svg(&b, &t, &look)
        }
        "impact_map" => {
            let run: thud_core::dynamics::OrbitRun = serde_json::from_value(value).map_err(bad)?;
            let t = format!("Impact map — {}", short_design(&design, ""));
            thud_render::dynamics::impact_map_svg(&run, &t, &look)
        }
        "bifurcation" => {
            let b: thud_core::dynamics::Bifurcation =
                serde_json::from_value(value.get("bifurcation").cloned().unwrap_or_default()).map_err(bad)?;
            let branches =
                crate::orbits::branches_of(value.get("branches").unwrap_or(&serde_json::Value::Null)).map_err(bad)?;
            let t = thud_render::dynamics::bifurcation_title(&design, &b);
            thud_render::dynamics::bifurcation_with_branches_svg(&b, &branches, &t, &look)
        }
        "continuation" => {
            let branch: thud_core::continuation::Branch = serde_json::from_value(value.clone()).map_err(bad)?;
            let range: Vec<f64> =
                serde_json::from_value(value.get("range").cloned().unwrap_or_default()).map_err(bad)?;
            let t = thud_render::dynamics::range_title("Orbits continued", &design, &branch.name, &branch.unit, &range);
            thud_render::continuation::continuation_svg(std::slice::from_ref(&branch), &t, &look)
        }
        "study" => {
            let study: thud_core::study::Study = serde_json::from_value(value).map_err(bad)?;
            let t = thud_render::studies::study_title(&study);
            thud_render::studies::study(&study, &t, &look).ok_or_else(|| {
                let n = study.axes.len();
                parameter_error(py, "vary", format!("a figure draws a study over one or two parameters, not {n}"))
            })?
        }
        _ => {
            let msg =
                format!("invalid kind: '{kind}'; expected basins, impact_map, bifurcation, continuation or study");
            return Err(parameter_error(py, "kind", msg));
        }
    };
    let bytes = if pdf {
        thud_render::pdf::from_svg(&svg).map_err(|e| engine_error(py, ThudError::invalid("render", e.to_string())))?
    } else {
        svg.into_bytes()
    };
    Ok(PyBytes::new(py, &bytes))
}

/// The sample format `format` names ("pcm16", "pcm24" or "float").
fn sample_format(py: Python<'_>, format: &str) -> PyResult<SampleFormat> {
    Ok(match format {
        "pcm16" => SampleFormat::Pcm16,
        "pcm24" => SampleFormat::Pcm24,
        "float" => SampleFormat::Float,
        _ => {
            let msg = format!("invalid format: '{format}'; expected pcm16, pcm24 or float");
            return Err(parameter_error(py, "format", msg));
        }
    })
}

/// What a pulse is made into: its figure (as SVG or PDF) or its sound.
pub enum PulseFile {
    /// `thud export svg pulse` (`pdf`: `thud export pdf pulse`) at this size and with or without the title.
    Figure { pdf: bool, size: Option<(f64, f64)>, title: bool },
    /// `thud export wav pulse --full-scale … --format …`.
    Sound { full_scale: f64, format: String },
}

/// The bytes `thud export svg|pdf|wav pulse` writes for the pulse whose record (`thud pulse
/// --json`) is `record`: the same impact, so the same bytes.
pub fn pulse_bytes<'py>(py: Python<'py>, record: &serde_json::Value, what: PulseFile) -> PyResult<Bound<'py, PyBytes>> {
    let spec = thud_core::report::PulseReport::deserialize(record)
        .map(thud_render::pulse::PulseSpec::from)
        .map_err(|e| parameter_error(py, "record", format!("invalid record: not a thud pulse ({e})")))?;
    let failed = |e: String| engine_error(py, ThudError::invalid("render", e));
    let bytes = match what {
        PulseFile::Figure { pdf, size, title } => {
            check_size(py, size)?;
            let svg = thud_render::pulse::svg(&spec, &Look { size, title }).map_err(|e| engine_error(py, e))?;
            if pdf {
                thud_render::pdf::from_svg(&svg).map_err(|e| failed(e.to_string()))?
            } else {
                svg.into_bytes()
            }
        }
        PulseFile::Sound { full_scale, format } => {
            let format = sample_format(py, &format)?;
            let full_scale_pa = within(py, "full_scale", full_scale, &limits::FULL_SCALE)?;
            let opts = WavOptions { format, full_scale_pa, ..WavOptions::default() };
            thud_render::pulse::sound(&spec, &opts).map_err(|e| match e {
                thud_render::wav::WavError::Invalid(t) => engine_error(py, t),
                other @ thud_render::wav::WavError::NonFinite(_) => failed(other.to_string()),
            })?
        }
    };
    Ok(PyBytes::new(py, &bytes))
}

/// Refuses a figure size outside what `--size` takes.
pub fn check_size(py: Python<'_>, size: Option<(f64, f64)>) -> PyResult<()> {
    if let Some((w, h)) = size {
        let (min, max) = (svg::MIN_SIZE, svg::MAX_SIZE);
        if !(min.0..=max.0).contains(&w) || !(min.1..=max.1).contains(&h) {
            let msg = format!(
                "invalid size: ({w}, {h}); must be (WIDTH, HEIGHT) in px, width {} to {}, height {} to {}",
                min.0, max.0, min.1, max.1
            );
            return Err(parameter_error(py, "size", msg));
        }
    }
    Ok(())
}
