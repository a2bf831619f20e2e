//! Calibration from measurements: the structure's f_n, ζ, K and C from a
//! measured free decay ([`structure`]), and the contact damping c1 of a damper from a measured
//! decay of the structure carrying it ([`damper`]). Pure: arrays in (time in s, one signal in
//! m, m/s or m/s²), numbers out; the front ends read the files (docs/model.md §13).
//!
//! This module holds what both fits share: the checked measurement ([`Series`]: finite, time
//! strictly increasing, not clipped), its slow trend, its noise level, its cycles (upward zero
//! crossings with hysteresis), and the amplitude of one window by a local least-squares sine
//! ([`window_amplitude`]).

pub mod damper;
pub mod path;
pub mod strike;
pub mod structure;

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

use crate::error::ThudError;

/// The parameter every data error names: the command line's `--data`, Python's data arrays.
pub const DATA_PARAM: &str = "data";

/// Fewest samples a measurement may have (3 cycles need far more; this refuses a stub early).
pub const MIN_SAMPLES: usize = 16;

/// Fewest whole cycles a fit accepts (the "too short").
pub const MIN_CYCLES: f64 = 3.0;

/// What a measured signal is: the main mass's displacement, velocity or acceleration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Displacement x (m); CSV column `x_m`.
    Displacement,
    /// Velocity x' (m/s); CSV column `v_m_s`.
    Velocity,
    /// Acceleration x'' (m/s²); CSV column `a_m_s2`.
    Acceleration,
}

impl Quantity {
    /// The SI unit of the signal ("m", "m/s", "m/s^2").
    #[must_use]
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Displacement => "m",
            Quantity::Velocity => "m/s",
            Quantity::Acceleration => "m/s^2",
        }
    }

    /// The column's name in SI (`x_m`, `v_m_s`, `a_m_s2`).
    #[must_use]
    pub fn column(self) -> &'static str {
        match self {
            Quantity::Displacement => "x_m",
            Quantity::Velocity => "v_m_s",
            Quantity::Acceleration => "a_m_s2",
        }
    }

    /// The derivative order of the signal: 0 for x, 1 for x', 2 for x''.
    #[must_use]
    pub fn order(self) -> i32 {
        match self {
            Quantity::Displacement => 0,
            Quantity::Velocity => 1,
            Quantity::Acceleration => 2,
        }
    }
}

/// One checked measurement: sample times (s, strictly increasing, any spacing) and the signal
/// at them (in the SI unit of `quantity`), every number finite, not clipped.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    t_s: Vec<f64>,
    values: Vec<f64>,
    quantity: Quantity,
}

fn bad(message: impl Into<String>) -> ThudError {
    ThudError::invalid(DATA_PARAM, message)
}

impl Series {
    /// Checks a measurement: as many times as values, at least [`MIN_SAMPLES`], every number
    /// finite, time strictly increasing (an unsorted or repeated time is refused, naming the
    /// sample), and no clipping ([`clipped`]). Errors name `data`.
    pub fn new(t_s: Vec<f64>, values: Vec<f64>, quantity: Quantity) -> Result<Self, ThudError> {
        if t_s.len() != values.len() {
            return Err(bad(format!("{} times but {} values; give one value per time", t_s.len(), values.len())));
        }
        if t_s.len() < MIN_SAMPLES {
            return Err(bad(format!(
                "too short: {} samples; a fit needs at least {MIN_SAMPLES} samples and {MIN_CYCLES} cycles",
                t_s.len()
            )));
        }
        for (i, (&t, &v)) in t_s.iter().zip(&values).enumerate() {
            if !t.is_finite() {
                return Err(bad(format!("sample {} has time {t}; every time must be a finite number", i + 1)));
            }
            if !v.is_finite() {
                return Err(bad(format!(
                    "sample {} (t = {t} s) has {} {v}; every value must be a finite number",
                    i + 1,
                    quantity.column()
                )));
            }
        }
        for (i, w) in t_s.windows(2).enumerate() {
            if w[1] == w[0] {
                return Err(bad(format!(
                    "repeated time {} s at samples {} and {}; times must increase",
                    w[0],
                    i + 1,
                    i + 2
                )));
            }
            if w[1] < w[0] {
                return Err(bad(format!(
                    "unsorted time: sample {} ({} s) comes before sample {} ({} s); sort the rows by time",
                    i + 2,
                    w[1],
                    i + 1,
                    w[0]
                )));
            }
        }
        if let Some(why) = clipped(&values) {
            return Err(bad(format!("the signal is clipped: {why}; record with more range")));
        }
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        if hi - lo <= 0.0 {
            return Err(bad("the signal is constant; there is no decay to fit"));
        }
        if hi - lo < MIN_SIGNAL_RANGE {
            return Err(bad(format!(
                "the signal spans only {} {}: numbers this small (below {MIN_SIGNAL_RANGE:e}) lose their digits; give it in a smaller unit",
                crate::units::short(hi - lo),
                quantity.unit()
            )));
        }
        if let Some(why) = lone_sample(&t_s) {
            return Err(bad(why));
        }
        Ok(Self { t_s, values, quantity })
    }

    /// Sample times (s).
    #[must_use]
    pub fn t_s(&self) -> &[f64] {
        &self.t_s
    }

    /// The signal at the sample times (SI unit of [`Series::quantity`]).
    #[must_use]
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// What the signal is.
    #[must_use]
    pub fn quantity(&self) -> Quantity {
        self.quantity
    }

    /// The record's span (s): last time − first time.
    #[must_use]
    pub fn span_s(&self) -> f64 {
        self.t_s[self.t_s.len() - 1] - self.t_s[0]
    }

    /// The number of samples.
    #[must_use]
    pub fn len(&self) -> usize {
        self.t_s.len()
    }

    /// Always false: a series has at least [`MIN_SAMPLES`] samples.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }
}

/// Smallest range (largest − smallest value) a signal may have: far below it the numbers are
/// subnormal and carry fewer digits than a fit's residual needs (its standard errors would
/// come out 0).
pub const MIN_SIGNAL_RANGE: f64 = 1e-280;

/// Why the times are degenerate, if they are: a span that is not a finite number, or one gap
/// between samples longer than all the rest of the record (a stray row far from the others,
/// like a time of 1e305 s after a record of seconds, which would leave every other sample at
/// one instant of the fit).
#[must_use]
pub fn lone_sample(t_s: &[f64]) -> Option<String> {
    let span = t_s[t_s.len() - 1] - t_s[0];
    if !span.is_finite() {
        return Some(format!("the times span {span} s, beyond the largest number thud holds"));
    }
    let (i, gap) = t_s.windows(2).map(|w| w[1] - w[0]).enumerate().max_by(|a, b| a.1.total_cmp(&b.1))?;
    (gap > 0.5 * span).then(|| {
        format!(
            "samples {} (t = {} s) and {} (t = {} s) are {} s apart, more than all the rest of the record; cut the record at the gap",
            i + 1,
            crate::units::short(t_s[i]),
            i + 2,
            crate::units::short(t_s[i + 1]),
            crate::units::short(gap)
        )
    })
}

/// Why the signal looks clipped, if it does: its largest (or smallest) value held flat for at
/// least 5 samples in a row, or reached in two separate runs of 2 or more (a rail a decaying
/// signal meets again). A measured signal with noise meets its extreme once; a quantised one
/// may hold it for a sample or two at the first peak, which passes.
#[must_use]
pub fn clipped(values: &[f64]) -> Option<String> {
    let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    for (extreme, name) in [(hi, "largest"), (lo, "smallest")] {
        let mut runs = Vec::new();
        let mut run = 0usize;
        for &v in values {
            if v == extreme {
                run += 1;
            } else if run > 0 {
                runs.push(run);
                run = 0;
            }
        }
        if run > 0 {
            runs.push(run);
        }
        let longest = runs.iter().copied().max().unwrap_or(0);
        let repeated = runs.iter().filter(|&&r| r >= 2).count();
        if longest >= 5 || repeated >= 2 {
            return Some(format!(
                "its {name} value {extreme} is held for {longest} samples in a row ({} times in all)",
                runs.iter().sum::<usize>()
            ));
        }
    }
    None
}

/// Least-squares straight line through `(t, y)`: `(offset at t[0], slope)`.
#[must_use]
pub fn line(t: &[f64], y: &[f64]) -> (f64, f64) {
    let n = t.len() as f64;
    let t0 = t[0];
    let (st, sy) = t.iter().zip(y).fold((0.0, 0.0), |(a, b), (&ti, &yi)| (a + ti - t0, b + yi));
    let (mt, my) = (st / n, sy / n);
    let (num, den) = t
        .iter()
        .zip(y)
        .fold((0.0, 0.0), |(a, b), (&ti, &yi)| (a + (ti - t0 - mt) * (yi - my), b + (ti - t0 - mt).powi(2)));
    let slope = if den > 0.0 { num / den } else { 0.0 };
    (my - slope * mt, slope)
}

/// `y` less its least-squares straight line (the offset and the drift).
#[must_use]
pub fn detrended(t: &[f64], y: &[f64]) -> Vec<f64> {
    let (o, s) = line(t, y);
    t.iter().zip(y).map(|(&ti, &yi)| yi - o - s * (ti - t[0])).collect()
}

/// The white noise's standard deviation in `y`, from the second differences: for samples
/// far denser than the signal's cycles, `y_i − (y_{i−1} + y_{i+1})/2` is the noise with
/// variance 1.5σ²; the median absolute value (÷ 0.6745 for a normal) keeps the impacts' spikes
/// and steps out.
#[must_use]
pub fn noise_sd(y: &[f64]) -> f64 {
    let mut d: Vec<f64> = y.windows(3).map(|w| (w[1] - 0.5 * (w[0] + w[2])).abs()).collect();
    if d.is_empty() {
        return 0.0;
    }
    d.sort_by(f64::total_cmp);
    d[d.len() / 2] / 0.6745 / 1.5f64.sqrt()
}

/// Times (s) of the upward zero crossings of `y` (detrended) with hysteresis `h`: each is
/// counted when the signal climbs from below −h to above +h, at the last sign change between
/// (linear interpolation).
#[must_use]
pub fn up_crossings(t: &[f64], y: &[f64], h: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut armed = false;
    let mut last_change = None;
    for i in 0..y.len() {
        if y[i] < -h {
            armed = true;
            last_change = None;
        }
        if i > 0 && y[i - 1] <= 0.0 && y[i] > 0.0 {
            last_change = Some(i);
        }
        if armed && y[i] > h {
            if let Some(j) = last_change {
                let (t0, t1, y0, y1) = (t[j - 1], t[j], y[j - 1], y[j]);
                out.push(t0 + (t1 - t0) * (-y0) / (y1 - y0));
            }
            armed = false;
        }
    }
    out
}

/// The samples of sorted times `t` with `a ≤ t < b` (`from..to`) and the window's middle;
/// `None` with fewer than `min` of them.
fn window_span(t: &[f64], a: f64, b: f64, min: usize) -> Option<(usize, usize, f64)> {
    let from = t.partition_point(|&ti| ti < a);
    let to = t.partition_point(|&ti| ti < b);
    (to >= from + min).then_some((from, to, 0.5 * (a + b)))
}

/// The amplitude of `y` over the samples with `a ≤ t < b` at angular frequency `omega`
/// (rad/s): the least-squares `c + p·cos ωt + q·sin ωt` through them, `√(p² + q²)`. `None`
/// with fewer than 6 samples in the window or a singular fit.
#[must_use]
pub fn window_amplitude(t: &[f64], y: &[f64], a: f64, b: f64, omega: f64) -> Option<f64> {
    let (from, to, mid) = window_span(t, a, b, 6)?;
    let mut ata = Matrix3::zeros();
    let mut aty = Vector3::zeros();
    for i in from..to {
        let ph = omega * (t[i] - mid);
        let row = Vector3::new(1.0, ph.cos(), ph.sin());
        ata += row * row.transpose();
        aty += row * y[i];
    }
    let sol = ata.lu().solve(&aty)?;
    let amp = sol[1].hypot(sol[2]);
    amp.is_finite().then_some(amp)
}

/// What a first look at a measurement finds: its trend removed, its noise, its cycles and
/// their rough frequency.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Look {
    /// The signal less its straight line.
    pub detrended: Vec<f64>,
    /// The noise's standard deviation (signal unit).
    pub noise: f64,
    /// Upward zero crossings (s).
    pub crossings: Vec<f64>,
    /// Whole cycles between the first and last crossing.
    pub cycles: f64,
    /// Their mean frequency (Hz).
    pub freq_hz: f64,
}

/// A first look at `s`: refuses a record with fewer than [`MIN_CYCLES`] cycles ("too short").
pub(crate) fn look(s: &Series) -> Result<Look, ThudError> {
    let detrended = detrended(s.t_s(), s.values());
    let noise = noise_sd(&detrended);
    let peak = detrended.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // Hysteresis: well above the noise, well below the first swings.
    let h = (4.0 * noise).max(1e-3 * peak).min(0.3 * peak);
    let crossings = up_crossings(s.t_s(), &detrended, h);
    let cycles = crossings.len().saturating_sub(1) as f64;
    if cycles < MIN_CYCLES {
        return Err(bad(format!(
            "too short: {} whole cycles found in {} s; a fit needs at least {MIN_CYCLES}",
            cycles,
            crate::units::sig(s.span_s(), 4)
        )));
    }
    let freq_hz = cycles / (crossings[crossings.len() - 1] - crossings[0]);
    Ok(Look { detrended, noise, crossings, cycles, freq_hz })
}

/// c1 values of the grid.
pub const GRID_POINTS: usize = 41;

/// The c1 grid (N·s/m): `GRID_POINTS` log-spaced from the c1 of restitution 0.995 to that of
/// 0.02 (0.05 where 0.02 is out of reach), for one contact of the design's ball at the strike speed |v0|.
pub fn grid(d: &crate::design::ValidDesign) -> Result<Vec<f64>, ThudError> {
    let u0 = d.damper.v0_m_s.abs();
    if u0 <= 0.0 {
        return Err(ThudError::invalid("v0", "0 m/s; a damper fit needs the strike's speed (give --v0)"));
    }
    let lo = crate::design::c1_for_restitution(d, u0, 0.995)?.max(1e-6);
    // The most damped end: restitution 0.02, or 0.05 where 0.02 is out of reach.
    let hi = crate::design::c1_for_restitution(d, u0, 0.02)
        .or_else(|_| crate::design::c1_for_restitution(d, u0, 0.05))?
        .min(crate::limits::C1.max);
    // A strike so slow (or so fast) that restitution 0.995 needs more c1 than the most damped
    // end allows, or than a number holds, leaves no grid: the strike's speed is the cause.
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(ThudError::invalid(
            "v0",
            format!("{u0:e} m/s is too slow a strike to fit c1 from (no contact damping up to the largest c1 gives restitution 0.995 to 0.02 at that speed); strike faster"),
        ));
    }
    Ok(crate::design::linspace(lo.ln(), hi.ln(), GRID_POINTS).into_iter().map(f64::exp).collect())
}

/// The samples of an acceleration without its impacts' spikes: every sample further than 4
/// robust standard deviations (1.4826 × the median absolute deviation) from the median of its
/// 9 neighbours is left out with the two samples each side; the first sample is kept.
fn without_spikes(t: &[f64], y: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = y.len();
    let h = 4usize;
    let dev: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(h), (i + h + 1).min(n));
            let mut w = y[a..b].to_vec();
            w.sort_by(f64::total_cmp);
            (y[i] - w[w.len() / 2]).abs()
        })
        .collect();
    let mut sorted = dev.clone();
    sorted.sort_by(f64::total_cmp);
    let cut = 4.0 * 1.4826 * sorted[n / 2];
    let mut keep = vec![true; n];
    for i in (0..n).filter(|&i| dev[i] > cut) {
        keep[i.saturating_sub(2)..(i + 3).min(n)].iter_mut().for_each(|k| *k = false);
    }
    keep[0] = true;
    (0..n).filter(|&i| keep[i]).map(|i| (t[i], y[i])).unzip()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sine(n: usize, f: f64, rate: f64) -> (Vec<f64>, Vec<f64>) {
        let t: Vec<f64> = (0..n).map(|i| i as f64 / rate).collect();
        let y = t.iter().map(|&t| (2.0 * std::f64::consts::PI * f * t).sin()).collect();
        (t, y)
    }

    #[test]
    fn bad_series_are_refused_naming_the_problem() {
        let (t, y) = sine(200, 5.0, 100.0);
        let mut nan = y.clone();
        nan[7] = f64::NAN;
        assert!(Series::new(t.clone(), nan, Quantity::Displacement).unwrap_err().to_string().contains("sample 8"));
        let mut back = t.clone();
        back.swap(10, 11);
        assert!(Series::new(back, y.clone(), Quantity::Displacement).unwrap_err().to_string().contains("unsorted"));
        let mut rep = t.clone();
        rep[11] = rep[10];
        assert!(Series::new(rep, y.clone(), Quantity::Displacement).unwrap_err().to_string().contains("repeated"));
        let clip: Vec<f64> = y.iter().map(|v| v.clamp(-0.8, 0.8)).collect();
        assert!(Series::new(t.clone(), clip, Quantity::Displacement).unwrap_err().to_string().contains("clipped"));
        assert!(Series::new(t[..10].to_vec(), y[..10].to_vec(), Quantity::Displacement).is_err());
        assert!(Series::new(t, y, Quantity::Displacement).is_ok());
    }

    /// Degenerate records are refused naming what is wrong: a stray row far after the rest
    /// (t = 1e305 s), a signal too small for its digits (subnormal numbers), a span beyond f64.
    #[test]
    fn degenerate_records_are_refused() {
        let (t, y) = sine(200, 5.0, 100.0);
        let mut far = t.clone();
        far[199] = 1e305;
        let e = Series::new(far, y.clone(), Quantity::Displacement).unwrap_err().to_string();
        assert!(e.contains("samples 199") && e.contains("1e305") && e.contains("gap"), "{e}");
        let tiny: Vec<f64> = y.iter().map(|v| v * 1e-306).collect();
        let e = Series::new(t.clone(), tiny, Quantity::Displacement).unwrap_err().to_string();
        assert!(e.contains("spans only") && e.contains("smaller unit"), "{e}");
        let mut huge = t.clone();
        huge[0] = -1.7e308;
        huge[199] = 1.7e308;
        let e = Series::new(huge, y.clone(), Quantity::Displacement).unwrap_err().to_string();
        assert!(e.contains("beyond the largest number"), "{e}");
        // A gap shorter than the rest of the record is a measurement with a gap: kept.
        let mut gappy = t.clone();
        for v in &mut gappy[100..] {
            *v += 0.9;
        }
        assert!(Series::new(gappy, y.clone(), Quantity::Displacement).is_ok());
        let small: Vec<f64> = y.iter().map(|v| v * 1e-270).collect();
        assert!(Series::new(t, small, Quantity::Displacement).is_ok());
    }

    #[test]
    fn crossings_count_cycles_through_noise() {
        let (t, y) = sine(1000, 5.0, 1000.0);
        let noisy: Vec<f64> =
            y.iter().enumerate().map(|(i, v)| v + 0.02 * ((i as f64 * 12.9898).sin() * 43758.5453).fract()).collect();
        let c = up_crossings(&t, &noisy, 0.1);
        // The first rise from t = 0 is not armed (never below −h before it).
        assert_eq!(c.len(), 4, "{c:?}");
        assert!((c[1] - c[0] - 0.2).abs() < 2e-3);
    }

    #[test]
    fn window_amplitude_of_a_sine_with_offset() {
        let t: Vec<f64> = (0..400).map(|i| f64::from(i) * 0.001 + 0.0003 * f64::from(i % 3)).collect();
        let y: Vec<f64> = t.iter().map(|&t| 0.7 + 2.5 * (31.4 * t + 0.3).cos()).collect();
        let a = window_amplitude(&t, &y, 0.0, 0.2, 31.4).unwrap();
        assert!((a - 2.5).abs() < 1e-9, "{a}");
    }
}
