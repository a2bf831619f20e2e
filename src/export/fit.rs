//! The figures of `thud export svg|pdf fit`: a measurement over the model `thud fit` fitted to
//! it — the structure's record over its fitted free decay, or a damper record's energy
//! envelope over the envelope of the fitted c1's median run.

use crate::fit::damper::DamperFit;
use crate::fit::structure::StructureFit;
use crate::fit::Series as Record;

use super::svg::{line_plot, Axis, Look, Series, Style};

/// Most points drawn of a record (every k-th sample beyond).
const MAX_POINTS: usize = 20_000;

/// The record `s` (its own unit) and the fitted model at its times, against time (s).
pub fn structure(s: &Record, f: &StructureFit, title: &str, look: &Look) -> String {
    let step = s.len().div_ceil(MAX_POINTS).max(1);
    let data: Vec<(f64, f64)> = s.t_s().iter().zip(s.values()).step_by(step).map(|(&t, &y)| (t, y)).collect();
    let model: Vec<(f64, f64)> = data.iter().map(|&(t, _)| (t, f.model.at(t))).collect();
    let x = Axis::fit("time t (s)", data.iter().map(|p| p.0));
    let y =
        Axis::fit(&format!("measured {} ({})", s.quantity().column(), f.unit), data.iter().chain(&model).map(|p| p.1));
    line_plot(
        title,
        look,
        x,
        y,
        &[Series::new("measurement", data, Style::Line), Series::new("fitted free decay", model, Style::Dashed)],
    )
}

/// The measured envelope (amplitude per period, mm) and the fitted c1's median run's.
pub fn damper(f: &DamperFit, title: &str, look: &Look) -> String {
    let at = |j: usize| (j as f64 + 0.5) * f.envelope_period_s;
    let data: Vec<(f64, f64)> = f.measured_envelope_m.iter().enumerate().map(|(j, a)| (at(j), a * 1e3)).collect();
    let model: Vec<(f64, f64)> = f.model_envelope_m.iter().enumerate().map(|(j, a)| (at(j), a * 1e3)).collect();
    let x = Axis::fit("time t (s)", data.iter().chain(&model).map(|p| p.0));
    let y = Axis::fit("amplitude per period (mm)", data.iter().chain(&model).map(|p| p.1).chain([0.0]));
    line_plot(
        title,
        look,
        x,
        y,
        &[
            Series::new("measured envelope", data, Style::LineMarkers),
            Series::new("median run at the fitted c1", model, Style::Dashed),
        ],
    )
}
