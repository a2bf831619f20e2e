//! The sound of a damper at its observer as a WAV file: every impact's pressure pulse (the
//! acoustic model at the impact's incoming speed) placed at its impact time, over the whole run.
//!
//! Scale (fixed, so two designs can be compared by ear): 32-bit float samples, mono, 48 kHz,
//! sample value = pressure / [`FULL_SCALE_PA`], i.e. 1.0 is 20 Pa (120 dB peak re 20 µPa).
//! Each sample is the mean pressure over its sampling interval (a box filter), so the short
//! Hertzian pulses are not aliased away. Every impact is heard as the model hears an impact on
//! the struck wall: same observer geometry and polarity for both walls (the model's convention).

use std::io::Cursor;

use crate::damper::Run;
use crate::design::Design;
use crate::error::{check_positive, ThudError};

/// Sample rate of exported sound (Hz).
pub const SAMPLE_RATE: u32 = 48_000;

/// Pressure (Pa) written as sample value 1.0.
pub const FULL_SCALE_PA: f64 = 20.0;

/// Sub-samples averaged per sample (the box filter).
const OVERSAMPLE: usize = 16;

/// How the sound is rendered and written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavOptions {
    /// Samples per second (Hz).
    pub sample_rate: u32,
    /// Pressure (Pa) that maps to sample value 1.0.
    pub full_scale_pa: f64,
}

impl Default for WavOptions {
    /// 48 kHz, 20 Pa full scale.
    fn default() -> Self {
        Self { sample_rate: SAMPLE_RATE, full_scale_pa: FULL_SCALE_PA }
    }
}

impl WavOptions {
    pub fn validate(&self) -> Result<(), ThudError> {
        if !(8_000..=384_000).contains(&self.sample_rate) {
            return Err(ThudError::invalid("rate", format!("{} Hz; must be 8000 to 384000 Hz", self.sample_rate)));
        }
        check_positive("full-scale", self.full_scale_pa, "Pa")
    }
}

/// Number of samples of a sound `duration_s` long.
pub fn sample_count(duration_s: f64, sample_rate: u32) -> usize {
    (duration_s * f64::from(sample_rate)).round().max(0.0) as usize
}

/// The pressure (Pa) at the observer over the run, one value per sample from t = 0 to the
/// design's duration: the sum of every impact's pulse, delayed by its impact time.
pub fn render(design: &Design, run: &Run, sample_rate: u32) -> Result<Vec<f64>, ThudError> {
    let d = design.resolved()?;
    let n = sample_count(d.damper.duration_s, sample_rate);
    let dt = 1.0 / f64::from(sample_rate);
    let mut p = vec![0.0; n];
    for impact in &run.impacts {
        let field = d.impact_field(impact.u_in_m_s)?;
        let (start, end) = (impact.t_s + field.arrival_s(), impact.t_s + field.end_s());
        let k0 = ((start / dt - 0.5).floor().max(0.0) as usize).min(n);
        let k1 = ((end / dt + 0.5).ceil().max(0.0) as usize).min(n);
        for (k, sample) in p.iter_mut().enumerate().take(k1).skip(k0) {
            let t0 = (k as f64 - 0.5) * dt - impact.t_s;
            let sum: f64 =
                (0..OVERSAMPLE).map(|j| field.pressure(t0 + (j as f64 + 0.5) * dt / OVERSAMPLE as f64)).sum();
            *sample += sum / OVERSAMPLE as f64;
        }
    }
    Ok(p)
}

/// Encodes pressures (Pa) as a mono 32-bit float WAV, sample = p / full scale. Values beyond
/// full scale are written as they are (float WAV does not clip), see [`clipped`].
pub fn encode(pressure_pa: &[f64], opts: &WavOptions) -> Result<Vec<u8>, ThudError> {
    opts.validate()?;
    let spec = hound::WavSpec {
        channels: 1,
        sample_rate: opts.sample_rate,
        bits_per_sample: 32,
        sample_format: hound::SampleFormat::Float,
    };
    let fail = |e: hound::Error| ThudError::invalid("wav", e.to_string());
    let mut cursor = Cursor::new(Vec::new());
    let mut w = hound::WavWriter::new(&mut cursor, spec).map_err(fail)?;
    for &p in pressure_pa {
        w.write_sample((p / opts.full_scale_pa) as f32).map_err(fail)?;
    }
    w.finalize().map_err(fail)?;
    Ok(cursor.into_inner())
}

/// Whether any pressure exceeds the full scale (players will clip it).
pub fn clipped(pressure_pa: &[f64], opts: &WavOptions) -> bool {
    pressure_pa.iter().any(|p| p.abs() > opts.full_scale_pa)
}

/// The WAV file of `design`'s run: [`render`] then [`encode`].
pub fn damper_sound(design: &Design, run: &Run, opts: &WavOptions) -> Result<Vec<u8>, ThudError> {
    opts.validate()?;
    encode(&render(design, run, opts.sample_rate)?, opts)
}
