//! The sound of a damper at its observer as a WAV file: every impact's pressure pulse (the
//! acoustic model at the impact's incoming speed) placed at its impact time, over the whole run.
//!
//! **Level.** The scale is fixed, never normalised to the loudest sample, so two designs can be
//! compared by ear: sample value = (the mean pressure over the sample's interval) / full scale,
//! where the full scale (`--full-scale`, default [`FULL_SCALE_PA`] = 20 Pa, i.e. 120 dB peak re
//! 20 µPa) is the pressure written as sample value 1.0.
//!
//! **Samples.** Mono, 48 kHz by default. [`SampleFormat::Pcm16`] (the default) and
//! [`SampleFormat::Pcm24`] write signed integers: the value is clipped to [−1, 1] and multiplied
//! by 2^(b−1) − 1 (32767 or 8388607), rounded to the nearest integer, so the scale is symmetric
//! and −1.0 is −32767; [`clipped_samples`] counts what the clip changed (the command line warns).
//! [`SampleFormat::Float`] writes 32-bit IEEE floats unclipped (a value beyond ±1.0 is kept as it
//! is). Each sample is the mean pressure over its sampling interval (a box filter), so the short
//! Hertzian pulses are not aliased away. Every impact is heard as the model hears an impact on
//! the struck wall: same observer geometry and polarity for both walls (the model's convention).
//!
//! **Why the header is written here and not by `hound`.** hound writes `WAVE_FORMAT_EXTENSIBLE`
//! for anything above 16 bits, which Python's `wave` module (before 3.12) and some older readers
//! refuse. The canonical RIFF/WAVE layout is 44 bytes for PCM (`fmt ` chunk of 16 bytes, format
//! tag 1); float uses format tag 3 with an 18-byte `fmt ` chunk (cbSize 0) and the `fact` chunk
//! the specification asks of non-PCM data, as libsndfile and sox write it. Both are a few fixed
//! fields, written by [`encode`] and checked byte by byte in the tests.

use thiserror::Error;

use crate::acoustics::Field;
use crate::damper::Run;
use crate::design::ValidDesign;
use crate::error::{check_positive, ThudError};

/// Why a WAV was not made.
#[derive(Debug, Error)]
pub enum WavError {
    /// The design or an option is not valid.
    #[error(transparent)]
    Invalid(#[from] ThudError),
    /// A pressure to write is not a finite number (a bug: it is the engine's own).
    #[error("{0} Pa in a WAV sample")]
    NonFinite(f64),
}

/// Sample rate of exported sound (Hz).
pub const SAMPLE_RATE: u32 = 48_000;

/// Pressure (Pa) written as sample value 1.0.
pub const FULL_SCALE_PA: f64 = 20.0;

/// Sub-samples averaged per sample (the box filter).
const OVERSAMPLE: usize = 16;

/// How each sample is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SampleFormat {
    /// 16-bit signed PCM (format tag 1): what every reader opens.
    #[default]
    Pcm16,
    /// 24-bit signed PCM (format tag 1, little-endian, 3 bytes a sample).
    Pcm24,
    /// 32-bit IEEE float (format tag 3), not clipped.
    Float,
}

impl SampleFormat {
    /// Bits per sample.
    pub fn bits(self) -> u16 {
        match self {
            SampleFormat::Pcm16 => 16,
            SampleFormat::Pcm24 => 24,
            SampleFormat::Float => 32,
        }
    }

    /// The WAVE format tag: 1 (PCM) or 3 (IEEE float).
    pub fn format_tag(self) -> u16 {
        match self {
            SampleFormat::Pcm16 | SampleFormat::Pcm24 => 1,
            SampleFormat::Float => 3,
        }
    }

    /// The largest integer code of a PCM format (2^(b−1) − 1); None for float.
    pub fn pcm_max(self) -> Option<i32> {
        match self {
            SampleFormat::Pcm16 => Some(i32::from(i16::MAX)),
            SampleFormat::Pcm24 => Some((1 << 23) - 1),
            SampleFormat::Float => None,
        }
    }
}

/// How the sound is rendered and written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavOptions {
    /// Samples per second (Hz).
    pub sample_rate: u32,
    /// Pressure (Pa) that maps to sample value 1.0.
    pub full_scale_pa: f64,
    /// How each sample is stored.
    pub format: SampleFormat,
}

impl Default for WavOptions {
    /// 48 kHz, 20 Pa full scale, 16-bit PCM.
    fn default() -> Self {
        Self { sample_rate: SAMPLE_RATE, full_scale_pa: FULL_SCALE_PA, format: SampleFormat::Pcm16 }
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
pub fn render(design: &ValidDesign, run: &Run, sample_rate: u32) -> Result<Vec<f64>, ThudError> {
    let d = design.clone();
    let n = sample_count(d.damper.duration_s, sample_rate);
    let dt = 1.0 / f64::from(sample_rate);
    let mut p = vec![0.0; n];
    for impact in &run.impacts {
        add_pulse(&mut p, &d.impact_field(impact.u_in_m_s)?, impact.t_s, dt);
    }
    Ok(p)
}

/// Adds to the samples `p` (interval `dt`, the first centred on t = 0) the pressure of `field`
/// whose contact starts at `t_impact` (s), each sample the mean over its interval.
fn add_pulse(p: &mut [f64], field: &Field, t_impact: f64, dt: f64) {
    let n = p.len();
    let (start, end) = (t_impact + field.arrival_s(), t_impact + field.end_s());
    let k0 = ((start / dt - 0.5).floor().max(0.0) as usize).min(n);
    let k1 = ((end / dt + 0.5).ceil().max(0.0) as usize).min(n);
    for (k, sample) in p.iter_mut().enumerate().take(k1).skip(k0) {
        let t0 = (k as f64 - 0.5) * dt - t_impact;
        let sum: f64 = (0..OVERSAMPLE).map(|j| field.pressure(t0 + (j as f64 + 0.5) * dt / OVERSAMPLE as f64)).sum();
        *sample += sum / OVERSAMPLE as f64;
    }
}

/// Silence after a single pulse's sound (s), so a player has a click to play.
pub const PULSE_TAIL_S: f64 = 0.1;

/// The pressure (Pa) of one impact's `field` at its observer, one value per sample from the
/// contact's start to [`PULSE_TAIL_S`] after the last wave has decayed.
pub fn render_pulse(field: &Field, sample_rate: u32) -> Vec<f64> {
    let n = sample_count(field.end_s() + PULSE_TAIL_S, sample_rate);
    let mut p = vec![0.0; n];
    add_pulse(&mut p, field, 0.0, 1.0 / f64::from(sample_rate));
    p
}

/// The integer code of sample value `v` in a PCM format whose largest code is `max`: clipped to
/// [−1, 1], scaled by `max` and rounded to the nearest integer.
fn pcm_code(v: f64, max: i32) -> i32 {
    (v.clamp(-1.0, 1.0) * f64::from(max)).round() as i32
}

/// Appends the RIFF/WAVE header of `samples` samples of `format` at `rate` Hz, mono.
fn header(out: &mut Vec<u8>, format: SampleFormat, rate: u32, samples: u32) {
    let block = format.bits() / 8;
    let data_len = samples * u32::from(block);
    let float = format == SampleFormat::Float;
    // fmt chunk: 16 bytes for PCM; 18 (with cbSize = 0) and a 12-byte fact chunk for float.
    let (fmt_len, fact_len) = if float { (18u32, 12u32) } else { (16, 0) };
    let riff_len = 4 + (8 + fmt_len) + fact_len + 8 + data_len + (data_len & 1);
    out.extend_from_slice(b"RIFF");
    out.extend_from_slice(&riff_len.to_le_bytes());
    out.extend_from_slice(b"WAVE");
    out.extend_from_slice(b"fmt ");
    out.extend_from_slice(&fmt_len.to_le_bytes());
    out.extend_from_slice(&format.format_tag().to_le_bytes());
    out.extend_from_slice(&1u16.to_le_bytes()); // channels
    out.extend_from_slice(&rate.to_le_bytes());
    out.extend_from_slice(&(rate * u32::from(block)).to_le_bytes()); // bytes per second
    out.extend_from_slice(&block.to_le_bytes()); // block align
    out.extend_from_slice(&format.bits().to_le_bytes());
    if float {
        out.extend_from_slice(&0u16.to_le_bytes()); // cbSize
        out.extend_from_slice(b"fact");
        out.extend_from_slice(&4u32.to_le_bytes());
        out.extend_from_slice(&samples.to_le_bytes());
    }
    out.extend_from_slice(b"data");
    out.extend_from_slice(&data_len.to_le_bytes());
}

/// Encodes pressures (Pa) as a mono WAV in `opts.format`, sample value = p / full scale (see the
/// module doc for the scaling and the clip). Refuses a non-finite pressure (the caller's bug:
/// the pressure is the engine's own) and a sound longer than a WAV can hold (4 GiB).
pub fn encode(pressure_pa: &[f64], opts: &WavOptions) -> Result<Vec<u8>, WavError> {
    opts.validate()?;
    if let Some(&p) = pressure_pa.iter().find(|p| !p.is_finite()) {
        return Err(WavError::NonFinite(p));
    }
    let block = usize::from(opts.format.bits() / 8);
    let samples = u32::try_from(pressure_pa.len())
        .ok()
        .filter(|&n| u64::from(n) * block as u64 + 64 < u64::from(u32::MAX))
        .ok_or_else(|| ThudError::invalid("wav", format!("{} samples do not fit in a WAV file", pressure_pa.len())))?;
    let mut out = Vec::with_capacity(64 + pressure_pa.len() * block + 1);
    header(&mut out, opts.format, opts.sample_rate, samples);
    for &p in pressure_pa {
        let v = p / opts.full_scale_pa;
        match opts.format {
            SampleFormat::Pcm16 => out.extend_from_slice(&(pcm_code(v, i32::from(i16::MAX)) as i16).to_le_bytes()),
            SampleFormat::Pcm24 => out.extend_from_slice(&pcm_code(v, (1 << 23) - 1).to_le_bytes()[..3]),
            SampleFormat::Float => out.extend_from_slice(&(v as f32).to_le_bytes()),
        }
    }
    if out.len() % 2 == 1 {
        out.push(0); // RIFF chunks are padded to an even length
    }
    Ok(out)
}

/// How many samples lie beyond the full scale: clipped in a PCM file, kept in a float one
/// (players will clip them).
pub fn clipped_samples(pressure_pa: &[f64], opts: &WavOptions) -> usize {
    pressure_pa.iter().filter(|p| p.abs() > opts.full_scale_pa).count()
}

/// The WAV file of `design`'s run: [`render`] then [`encode`].
pub fn damper_sound(design: &ValidDesign, run: &Run, opts: &WavOptions) -> Result<Vec<u8>, WavError> {
    opts.validate()?;
    encode(&render(design, run, opts.sample_rate)?, opts)
}

/// The WAV file of one impact's `field` at its observer (`thud export wav pulse`):
/// [`render_pulse`] then [`encode`].
pub fn pulse_sound(field: &Field, opts: &WavOptions) -> Result<Vec<u8>, WavError> {
    opts.validate()?;
    encode(&render_pulse(field, opts.sample_rate), opts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u16_at(b: &[u8], i: usize) -> u16 {
        u16::from_le_bytes([b[i], b[i + 1]])
    }
    fn u32_at(b: &[u8], i: usize) -> u32 {
        u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
    }

    #[test]
    fn pcm16_is_the_canonical_44_byte_header_then_clipped_symmetric_codes() {
        let opts = WavOptions::default();
        // 0, half scale, full scale, twice full scale (clipped), minus twice (clipped), a quarter below.
        let p = [0.0, 10.0, 20.0, 40.0, -40.0, -5.0];
        let b = encode(&p, &opts).unwrap();
        assert_eq!(&b[0..4], b"RIFF");
        assert_eq!(u32_at(&b, 4) as usize, b.len() - 8, "RIFF size");
        assert_eq!(&b[8..16], b"WAVEfmt ");
        assert_eq!(u32_at(&b, 16), 16, "fmt chunk size of PCM");
        assert_eq!(u16_at(&b, 20), 1, "format tag PCM");
        assert_eq!(u16_at(&b, 22), 1, "mono");
        assert_eq!(u32_at(&b, 24), 48_000);
        assert_eq!(u32_at(&b, 28), 96_000, "bytes per second");
        assert_eq!(u16_at(&b, 32), 2, "block align");
        assert_eq!(u16_at(&b, 34), 16, "bits");
        assert_eq!(&b[36..40], b"data");
        assert_eq!(u32_at(&b, 40), 12);
        assert_eq!(b.len(), 44 + 12);
        let codes: Vec<i16> = b[44..].chunks_exact(2).map(|c| i16::from_le_bytes([c[0], c[1]])).collect();
        assert_eq!(codes, [0, 16384, 32767, 32767, -32767, -8192]);
        assert_eq!(clipped_samples(&p, &opts), 2);
    }

    #[test]
    fn pcm24_writes_three_bytes_a_sample_and_pads_the_data_chunk() {
        let opts = WavOptions { format: SampleFormat::Pcm24, ..WavOptions::default() };
        let b = encode(&[20.0, -10.0, 0.0], &opts).unwrap();
        assert_eq!((u16_at(&b, 20), u16_at(&b, 32), u16_at(&b, 34)), (1, 3, 24));
        assert_eq!(u32_at(&b, 28), 144_000);
        assert_eq!(u32_at(&b, 40), 9, "data size counts no pad byte");
        assert_eq!(b.len(), 44 + 9 + 1, "the odd data chunk is padded");
        assert_eq!(u32_at(&b, 4) as usize, b.len() - 8);
        let code = |i: usize| i32::from_le_bytes([0, b[44 + 3 * i], b[45 + 3 * i], b[46 + 3 * i]]) >> 8;
        assert_eq!([code(0), code(1), code(2)], [8_388_607, -4_194_304, 0]);
    }

    #[test]
    fn float_has_format_tag_3_a_fact_chunk_and_unclipped_samples() {
        let opts = WavOptions { format: SampleFormat::Float, ..WavOptions::default() };
        let b = encode(&[30.0, -5.0], &opts).unwrap();
        assert_eq!((u32_at(&b, 16), u16_at(&b, 20), u16_at(&b, 34), u16_at(&b, 36)), (18, 3, 32, 0));
        assert_eq!(&b[38..42], b"fact");
        assert_eq!((u32_at(&b, 42), u32_at(&b, 46)), (4, 2), "fact: the sample count");
        assert_eq!(&b[50..54], b"data");
        assert_eq!(u32_at(&b, 54), 8);
        let s: Vec<f32> = b[58..].chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        assert_eq!(s, [1.5, -0.25]);
        assert_eq!(u32_at(&b, 4) as usize, b.len() - 8);
    }

    #[test]
    fn a_non_finite_pressure_is_refused() {
        assert!(matches!(encode(&[0.0, f64::NAN], &WavOptions::default()), Err(WavError::NonFinite(_))));
    }
}
