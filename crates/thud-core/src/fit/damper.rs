// Over 800 lines: one fit of c1 from records (envelopes, the table of runs, comparison, inputs), in order.
//! The damper's contact damping c1 from measured decays of the structure carrying it, struck
//! once, every other parameter of the design known (docs/model.md §13.2).
//!
//! The ball's motion is chaotic and where it sat when the structure was struck is unknown, so
//! no single trajectory is fitted point by point. The fit compares what is robust — the
//! **energy envelope**: the main mass's amplitude over each period of the structure, by a local
//! least-squares sine with a constant and a slope ([`envelope`]) — with an ensemble of runs
//! over the unknown start, as `--ensemble` does ([`crate::ensemble::ball_positions`]: the ball
//! at rest at N evenly spread offsets in the clearance).
//!
//! The statistic of one record is the mean over its periods j = 1 … J−1 of ln(A_j/A_0), the
//! decay of the envelope against its first period (independent of the sensor's gain). For each
//! c1 of a grid (log-spaced between the c1 of restitution 0.995 and 0.02 at the strike speed
//! v0, [`grid`]) the N = 39 members give the statistic's spread over the start. The 95 %
//! interval is the Neyman construction: the c1 whose acceptance band holds the observed
//! statistic (Neyman 1937). The evenly spread starts stand for a start spread uniformly over
//! the clearance: member i sits at the quantile (i + ½)/N of the start, so the sorted members
//! joined by straight lines are the statistic's quantile function at that c1.
//! The band is the 2.5 % and 97.5 % points of that distribution plus the measurement's noise
//! (the statistic's standard deviation from the amplitudes' noise), found by drawing: for n
//! records (repeated strikes fitted together) the mean of n draws, so the band narrows as √n.
//! The draws use a fixed generator, so an answer is repeatable. (The members' own [min, max]
//! would be a near-100 % band: evenly spread starts reach the ends of the start's range.)
//!
//! Two refinements (docs/model.md §13.2): records that differ from the structure's own decay
//! beyond their noise are compared only with the members the ball was hit in (the starts it
//! misses give the structure's decay at every c1 and would leave c1 unbounded); and the
//! interval is the intersection of two such sets at 97.5 % each (Bonferroni), for the whole
//! decay's statistic and for its first third's, because the whole decay is not monotone in
//! c1 where the most damped contacts stop the rattle. Where c1 stays poorly bounded the fit
//! carries a one-line [`DamperFit::note`]. An acceleration's windows are fitted robustly
//! ([`window_fit`]): its impact spikes last more samples than the median removes.
//!
//! The signal in any kind is first turned into the main mass's displacement: a velocity is
//! integrated (trapezoids; its offset becomes a slope, which each period's fit removes), an
//! acceleration is divided by −K/M after a 5-sample running median takes out the impacts'
//! spikes (in flight M·x'' = −K·x − C·x', and C·x'/K is below 2ζ of x). The record must start at
//! the strike (its first sample is t = 0 of the runs).

use std::f64::consts::PI;
use std::sync::atomic::AtomicBool;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::{bad, noise_sd, Quantity, Series};
pub use super::{grid, GRID_POINTS};
use crate::damper::{self, RunOptions};
use crate::design::{self, Design, ValidDesign};
use crate::draws::SplitMix64;
use crate::error::ThudError;

/// Ensemble members (ball starts) per c1.
pub const STARTS: usize = 39;
/// History samples per period of each run (the envelope's least-squares sines).
const SAMPLES_PER_PERIOD: f64 = 100.0;
/// Means drawn per c1 for several records.
const DRAWS: usize = 4000;

/// The fitted contact damping with its 95 % interval; what `--json` prints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DamperFit {
    /// Contact damping c1 (N·s/m): where the members' median statistic meets the data's.
    pub c1_n_s_m: f64,
    /// Half the 95 % interval's width over 1.96 (N·s/m): a normal-equivalent standard error.
    pub c1_n_s_m_stderr: f64,
    /// The 95 % interval [low, high] (N·s/m).
    pub c1_n_s_m_ci: [f64; 2],
    /// Whether the interval reaches an end of the grid (then that end is the grid's: the data
    /// do not bound c1 there).
    pub ci_open: bool,
    /// Restitution R of one contact at the first impact's speed with the fitted c1.
    pub restitution: f64,
    /// Half the restitution's 95 % interval (from the c1 interval) over 1.96.
    pub restitution_stderr: f64,
    /// The restitution's 95 % interval [low, high].
    pub restitution_ci: [f64; 2],
    /// The first impact's speed (m/s): the members' median at the fitted c1.
    pub first_impact_speed_m_s: f64,
    /// RMS of data − the median member's envelope at the fitted c1 (m), over the records.
    pub residual_rms: f64,
    /// The data's statistic (mean ln(A_j/A_0)) and the periods it used.
    pub statistic: f64,
    pub periods: usize,
    pub records: usize,
    /// Ensemble members per c1 and c1 grid points.
    pub starts: usize,
    pub grid_points: usize,
    /// The measured envelope of the first record (m, one a period from its start) and the
    /// fitted median member's, for plotting.
    pub envelope_period_s: f64,
    pub measured_envelope_m: Vec<f64>,
    pub model_envelope_m: Vec<f64>,
    /// The given inputs' uncertainties carried into the interval: each input's relative
    /// standard uncertainty and the shift of ln c1 it makes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inputs: Vec<InputShift>,
    /// The strike's speed read from the records themselves (m/s; [`super::strike`]), to check
    /// the design's v0 against, and its standard uncertainty (with the given structure values'
    /// uncertainties, which move it, carried in).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v0_m_s_record: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub v0_m_s_record_stderr: Option<f64>,
    /// A one-line note where the data cannot bound c1 well (the record is the structure's own
    /// decay, or the interval is open or wider than a factor 3), with what to do.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// A record turned into the main mass's displacement and its envelope.
#[derive(Debug, Clone, PartialEq)]
pub struct Observed {
    /// The displacement-equivalent signal (m) at the record's times from its start (s).
    pub t_s: Vec<f64>,
    pub x_m: Vec<f64>,
    /// The amplitude over each whole period from the start (m).
    pub envelope_m: Vec<f64>,
    /// Each period's amplitude's noise standard deviation (m), from that window's own residual
    /// ([`window_fit`]).
    pub envelope_sd_m: Vec<f64>,
    /// The amplitude's white-noise standard deviation (m), from the samples' second differences.
    pub amplitude_noise_m: f64,
    /// Leading periods well above the noise (amplitude ≥ 10 noise sd).
    pub usable: usize,
}

/// The structure's damped period (s) of the design.
fn period_s(d: &Design) -> Result<f64, ThudError> {
    let f = d.damper.natural_frequency_hz();
    if f > 0.0 {
        Ok(1.0 / f)
    } else {
        Err(ThudError::invalid(
            "k",
            "the structure has no free vibration (K = 0 or overdamped); a damper fit needs one",
        ))
    }
}

/// The samples of `y` at `t` in [a, b) and the regressor row of the sloped sine
/// `c + s·τ + p cos ωτ + q sin ωτ` at each (τ from the window's middle).
struct SlopedWindow<'a> {
    t: &'a [f64],
    y: &'a [f64],
    from: usize,
    to: usize,
    mid: f64,
    omega: f64,
}

impl<'a> SlopedWindow<'a> {
    /// The window, `None` with fewer than 8 samples in it.
    fn new(t: &'a [f64], y: &'a [f64], a: f64, b: f64, omega: f64) -> Option<Self> {
        let (from, to, mid) = super::window_span(t, a, b, 8)?;
        Some(Self { t, y, from, to, mid, omega })
    }

    fn row(&self, i: usize) -> nalgebra::Vector4<f64> {
        let tau = self.t[i] - self.mid;
        let (s, c) = (self.omega * tau).sin_cos();
        nalgebra::Vector4::new(1.0, tau, c, s)
    }

    /// The normal equations (AᵀA, Aᵀy) over the samples `keep` keeps.
    fn normal(&self, keep: &dyn Fn(usize) -> bool) -> (nalgebra::Matrix4<f64>, nalgebra::Vector4<f64>) {
        let mut ata = nalgebra::Matrix4::zeros();
        let mut aty = nalgebra::Vector4::zeros();
        for i in (self.from..self.to).filter(|&i| keep(i)) {
            let r = self.row(i);
            ata += r * r.transpose();
            aty += r * self.y[i];
        }
        (ata, aty)
    }

    /// The residual of sample `i` from the fit `sol`.
    fn residual(&self, i: usize, sol: &nalgebra::Vector4<f64>) -> f64 {
        self.y[i] - self.row(i).dot(sol)
    }

    /// The robust cut of the fit `sol`, 4 robust standard deviations (1.4826 × the median
    /// absolute residual); `None` where it would keep fewer than 8 samples.
    fn robust_cut(&self, sol: &nalgebra::Vector4<f64>) -> Option<f64> {
        let mut abs: Vec<f64> = (self.from..self.to).map(|i| self.residual(i, sol).abs()).collect();
        abs.sort_by(f64::total_cmp);
        let c = 4.0 * 1.4826 * abs[abs.len() / 2];
        ((self.from..self.to).filter(|&i| self.residual(i, sol).abs() <= c).count() >= 8).then_some(c)
    }
}

/// The amplitude of `y` over [a, b): the least-squares `c + s·τ + p cos ωτ + q sin ωτ`
/// (τ from the window's middle), `√(p² + q²)`. `None` with fewer than 8 samples or a singular fit.
#[must_use]
pub fn window_amplitude_sloped(t: &[f64], y: &[f64], a: f64, b: f64, omega: f64) -> Option<f64> {
    let w = SlopedWindow::new(t, y, a, b, omega)?;
    let (ata, aty) = w.normal(&|_| true);
    let sol = ata.lu().solve(&aty)?;
    let amp = sol[2].hypot(sol[3]);
    amp.is_finite().then_some(amp)
}

/// The least-squares `c + s·τ + p cos ωτ + q sin ωτ` over [a, b) (τ from the window's middle)
/// of `y` at `t`, robust or not: `(amplitude A = √(p² + q²), its standard error)`. Robust, the
/// fit is refitted twice without the samples whose residual exceeds 4 robust standard
/// deviations (1.4826 × the median absolute residual): an acceleration's impact spikes, a few
/// samples each, leave the window's sine. The standard error is the least-squares
/// one from the window's own residual, cov = s²·(AᵀA)⁻¹ with s² = RSS/(n − 4) over the samples
/// kept, carried to A by its first derivatives (p² var p + q² var q + 2pq cov(p, q))/A²: the
/// slope and the sine are correlated over one period, so this is larger than s·√(2/n).
#[must_use]
pub fn window_fit(t: &[f64], y: &[f64], a: f64, b: f64, omega: f64, robust: bool) -> Option<(f64, f64)> {
    let w = SlopedWindow::new(t, y, a, b, omega)?;
    let (ata, aty) = w.normal(&|_| true);
    let first = ata.lu().solve(&aty)?;
    let cut = if robust { w.robust_cut(&first).unwrap_or(f64::INFINITY) } else { f64::INFINITY };
    // A second pass from the fit without the first pass's outliers (spikes pull the first fit).
    let (first, cut) = if robust && cut.is_finite() {
        let (ata, aty) = w.normal(&|i| w.residual(i, &first).abs() <= cut);
        let second = ata.lu().solve(&aty).unwrap_or(first);
        w.robust_cut(&second).map_or((first, cut), |c| (second, c))
    } else {
        (first, cut)
    };
    let keep = |i: usize| w.residual(i, &first).abs() <= cut;
    let (ata, aty) = w.normal(&keep);
    let inv = ata.try_inverse()?;
    let sol = inv * aty;
    let kept: Vec<usize> = (w.from..w.to).filter(|&i| keep(i)).collect();
    let rss: f64 = kept.iter().map(|&i| w.residual(i, &sol).powi(2)).sum();
    let s2 = rss / (kept.len().saturating_sub(4).max(1)) as f64;
    let (p, q) = (sol[2], sol[3]);
    let amp = p.hypot(q);
    let var = if amp > 0.0 {
        s2 * (p * p * inv[(2, 2)] + q * q * inv[(3, 3)] + 2.0 * p * q * inv[(2, 3)]) / (amp * amp)
    } else {
        s2 * 0.5 * (inv[(2, 2)] + inv[(3, 3)])
    };
    (amp.is_finite() && var.is_finite()).then(|| (amp, var.max(0.0).sqrt()))
}

/// The envelope of `x` at times `t` (from 0): the amplitude over each of `periods` periods of
/// length `period_s` ([`window_amplitude_sloped`]; 0 for a window too thin to fit).
#[must_use]
pub fn envelope(t: &[f64], x: &[f64], period_s: f64, periods: usize) -> Vec<f64> {
    let om = 2.0 * PI / period_s;
    (0..periods)
        .map(|j| window_amplitude_sloped(t, x, j as f64 * period_s, (j + 1) as f64 * period_s, om).unwrap_or(0.0))
        .collect()
}

/// The statistic of an envelope over its first `periods` periods: mean ln(A_j/A_0), j ≥ 1.
fn statistic(env: &[f64], periods: usize) -> f64 {
    let a0 = env[0].max(f64::MIN_POSITIVE);
    let n = periods.min(env.len());
    env[1..n].iter().map(|a| (a.max(f64::MIN_POSITIVE) / a0).ln()).sum::<f64>() / (n - 1) as f64
}

/// The statistic's noise standard deviation from the amplitudes' (`sd[j]` for period j; the
/// delta method: A_0 enters every term).
fn statistic_noise(env: &[f64], periods: usize, sd: &[f64]) -> f64 {
    let n = periods.min(env.len());
    let k = (n - 1) as f64;
    let spread: f64 = env[1..n].iter().zip(&sd[1..n]).map(|(a, s)| (s / a).powi(2)).sum::<f64>() / (k * k);
    (spread + (sd[0] / env[0]).powi(2)).sqrt()
}

/// 5-sample running median (the ends keep their samples).
fn median5(y: &[f64]) -> Vec<f64> {
    let mut out = y.to_vec();
    for i in 2..y.len().saturating_sub(2) {
        let mut w = [y[i - 2], y[i - 1], y[i], y[i + 1], y[i + 2]];
        w.sort_by(f64::total_cmp);
        out[i] = w[2];
    }
    out
}

/// A record as the main mass's displacement and its envelope for design `d` (its K and M turn
/// an acceleration into displacement; its period sets the windows).
// Over 80 lines: one record read in order: its displacement, each period's amplitude and noise, the bias taken out.
pub fn observe(s: &Series, d: &Design) -> Result<Observed, ThudError> {
    let period = period_s(d)?;
    let t0 = s.t_s()[0];
    let t: Vec<f64> = s.t_s().iter().map(|&ti| ti - t0).collect();
    let y = s.values();
    let x: Vec<f64> = match s.quantity() {
        Quantity::Displacement => y.to_vec(),
        Quantity::Velocity => {
            let mut acc = 0.0;
            std::iter::once(0.0)
                .chain(t.windows(2).zip(y.windows(2)).map(|(tw, yw)| {
                    acc += 0.5 * (yw[0] + yw[1]) * (tw[1] - tw[0]);
                    acc
                }))
                .collect()
        }
        Quantity::Acceleration => {
            let scale = -d.damper.main_mass_kg / d.damper.stiffness_n_m;
            median5(y).into_iter().map(|a| a * scale).collect()
        }
    };
    let periods = (s.span_s() / period).floor() as usize;
    if (periods as f64) < super::MIN_CYCLES {
        return Err(bad(format!(
            "too short: {} s is {periods} periods of the structure ({} s); a fit needs at least {}",
            crate::units::sig(s.span_s(), 4),
            crate::units::sig(period, 4),
            super::MIN_CYCLES
        )));
    }
    // Each period's amplitude and its noise, from that window's own residual: the record's
    // noise and whatever else the window's sine does not follow (an impact's kink, the
    // noise of an accelerometer far above the structure's own motion) widen the band alike.
    let om = 2.0 * PI / period;
    let window = |j: usize| (j as f64 * period, (j + 1) as f64 * period);
    let (env, envelope_sd_m): (Vec<f64>, Vec<f64>) = (0..periods)
        .map(|j| {
            let (a, b) = window(j);
            match s.quantity() {
                Quantity::Displacement => {
                    window_fit(&t, &x, a, b, om, false).map_or((0.0, f64::INFINITY), |(amp, sd)| (amp, sd))
                }
                // The amplitude of the integrated displacement; its noise from the velocity's
                // own window (a sine of x' has ω times x's amplitude).
                Quantity::Velocity => {
                    let amp = window_amplitude_sloped(&t, &x, a, b, om).unwrap_or(0.0);
                    let sd = window_fit(&t, y, a, b, om, false).map_or(f64::INFINITY, |(_, sd)| sd / om);
                    (amp, sd)
                }
                // The raw record's window fitted robustly: the impacts' spikes stand far out of
                // its residual and leave it (in x: × M/K, in flight M·x'' = −K·x − C·x').
                Quantity::Acceleration => {
                    let scale = d.damper.main_mass_kg / d.damper.stiffness_n_m;
                    window_fit(&t, y, a, b, om, true)
                        .map_or((0.0, f64::INFINITY), |(amp, sd)| (amp * scale, sd * scale))
                }
            }
        })
        .unzip();
    // The white noise's share alone (second differences of the samples, robust): what tells a
    // record the ball was hit in from the structure's own decay, and which periods stand above
    // the noise.
    let noise = match s.quantity() {
        Quantity::Velocity => noise_sd(y) * period / (2.0 * PI),
        _ => noise_sd(&x),
    };
    let per_window = (s.len() as f64 / s.span_s() * period).max(8.0);
    let amplitude_noise_m = noise * (2.0 / per_window).sqrt();
    // A sine's amplitude from noisy samples is biased up: E[p² + q²] = A² + 2s² for noise s in
    // each of p and q (Rice 1944); the late periods of a noisy record would decay too little.
    // Taken out (never below the noise itself), with the white noise's s (an acceleration's
    // from its window's own fit: the samples' second differences see the spikes).
    let env: Vec<f64> = env
        .iter()
        .zip(&envelope_sd_m)
        .map(|(&a, &sd)| {
            let sd = if s.quantity() == Quantity::Acceleration { sd / 2f64.sqrt() } else { amplitude_noise_m };
            if sd.is_finite() {
                (a * a - 2.0 * sd * sd).max(sd * sd).sqrt().min(a)
            } else {
                a
            }
        })
        .collect();
    let usable = env.iter().take_while(|&&a| a >= 10.0 * amplitude_noise_m && a > 0.0).count();
    if usable < 3 {
        return Err(bad("too short: fewer than 3 periods stand above the noise; a fit needs at least 3"));
    }
    Ok(Observed { t_s: t, x_m: x, envelope_m: env, envelope_sd_m, amplitude_noise_m, usable })
}

/// Every member's envelope and first impact speed for each c1 of a grid: the ensemble the
/// records are compared with. Build once, compare any records of the same span.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub c1_n_s_m: Vec<f64>,
    /// `[c1][member]` → envelope (m, one a period).
    pub envelopes: Vec<Vec<Vec<f64>>>,
    /// `[c1][member]` → the first impact's incoming speed (m/s; 0 without an impact).
    pub first_impact_m_s: Vec<Vec<f64>>,
    pub period_s: f64,
}

impl Table {
    /// Runs `starts` members for each c1 of `c1_grid`, each `span_s` long, on rayon's pool.
    /// `Ok(None)` when `cancel` stopped it.
    pub fn build(
        d: &ValidDesign,
        c1_grid: &[f64],
        starts: usize,
        span_s: f64,
        cancel: Option<&AtomicBool>,
    ) -> Result<Option<Table>, ThudError> {
        let period = period_s(d)?;
        let periods = (span_s / period).floor() as usize;
        let samples = (span_s / period * SAMPLES_PER_PERIOD).ceil() as usize;
        let starts_m = crate::ensemble::ball_positions(d.damper.gap_m, starts);
        let jobs: Vec<(usize, f64)> =
            (0..c1_grid.len()).flat_map(|k| starts_m.iter().map(move |&y0| (k, y0))).collect();
        let runs: Vec<(Vec<f64>, f64, bool)> = jobs
            .into_par_iter()
            .map(|(k, y0)| {
                let mut p = d.damper;
                p.c1_n_s_m = c1_grid[k];
                p.ball_position_m = y0;
                p.duration_s = span_s;
                let run = damper::simulate(&p, d.solver, &RunOptions { history_samples: samples, cancel })?;
                let t: Vec<f64> = run.history.iter().map(|h| h.t_s).collect();
                let x: Vec<f64> = run.history.iter().map(|h| h.x_m).collect();
                let first = run.impacts.first().map_or(0.0, |i| i.u_in_m_s);
                Ok((envelope(&t, &x, period, periods), first, run.cancelled))
            })
            .collect::<Result<_, ThudError>>()?;
        if runs.iter().any(|r| r.2) {
            return Ok(None);
        }
        let mut envelopes = vec![Vec::with_capacity(starts); c1_grid.len()];
        let mut first_impact_m_s = vec![Vec::with_capacity(starts); c1_grid.len()];
        for ((k, _), (env, first, _)) in (0..c1_grid.len()).flat_map(|k| (0..starts).map(move |i| (k, i))).zip(runs) {
            envelopes[k].push(env);
            first_impact_m_s[k].push(first);
        }
        Ok(Some(Table { c1_n_s_m: c1_grid.to_vec(), envelopes, first_impact_m_s, period_s: period }))
    }
}

/// The members' quantile function at `u` ∈ [0, 1]: the sorted members at their plotting
/// positions (i + ½)/N — where the evenly spread starts sit — joined by straight lines, flat
/// beyond the first and last.
fn quantile(sorted: &[f64], u: f64) -> f64 {
    let n = sorted.len();
    let pos = u * n as f64 - 0.5;
    if pos <= 0.0 {
        return sorted[0];
    }
    if pos >= (n - 1) as f64 {
        return sorted[n - 1];
    }
    let i = pos.floor() as usize;
    sorted[i] + (sorted[i + 1] - sorted[i]) * (pos - i as f64)
}

/// The 95 % acceptance band [low, high] of the mean statistic of `records` records at one c1:
/// the 2.5 % and 97.5 % points of [`DRAWS`] means of `records` draws from the members'
/// distribution ([`quantile`] of a uniform number) plus the measurement's noise (normal, sd
/// `noise`), by a fixed generator.
fn band(members: &[f64], records: usize, noise: f64, tail: f64) -> (f64, f64) {
    let mut sorted = members.to_vec();
    sorted.sort_by(f64::total_cmp);
    let mut g = SplitMix64(0x5EED_0F17);
    let mut means: Vec<f64> = (0..DRAWS)
        .map(|_| {
            (0..records).map(|_| quantile(&sorted, g.uniform())).sum::<f64>() / records as f64 + noise * g.normal()
        })
        .collect();
    means.sort_by(f64::total_cmp);
    (quantile(&means, tail), quantile(&means, 1.0 - tail))
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    if s.is_empty() {
        return 0.0;
    }
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

/// `v` averaged over each point and its neighbours on the grid (the ends over two), skipping
/// NaN (a point without members): the members' median is a smooth function of c1 seen
/// through the chaos of 39 starts.
fn smoothed(v: &[f64]) -> Vec<f64> {
    (0..v.len())
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(v.len() - 1));
            let (sum, count) = v[a..=b].iter().filter(|x| !x.is_nan()).fold((0.0, 0usize), |(s, c), x| (s + x, c + 1));
            if count == 0 || v[k].is_nan() {
                f64::NAN
            } else {
                sum / count as f64
            }
        })
        .collect()
}

/// Fewest members (pooled over a grid point and its neighbours) the ball was hit in for a
/// band to be drawn at that c1.
const MIN_CLASS_MEMBERS: usize = 8;

/// Whether record `o`'s envelope over its first `periods` periods of `period_s` is the
/// structure alone's (Eq 25 without the ball, envelope ∝ e^{−σt}, σ = C/2M): every
/// ln(A_j/A_0) within 5 of its noise standard deviations (the delta method from the
/// amplitudes' noise) plus 0.02 of −σ·j·T. False when the ball was visibly hit.
fn structure_alone(d: &ValidDesign, o: &Observed, period_s: f64, periods: usize) -> bool {
    let sigma = d.damper.damping_n_s_m / (2.0 * d.damper.main_mass_kg);
    let env = &o.envelope_m;
    let a0 = env[0].max(f64::MIN_POSITIVE);
    let sd = o.amplitude_noise_m;
    (1..periods.min(env.len())).all(|j| {
        let a = env[j].max(f64::MIN_POSITIVE);
        let noise = ((sd / a).powi(2) + (sd / a0).powi(2)).sqrt();
        ((a / a0).ln() + sigma * j as f64 * period_s).abs() <= 5.0 * noise + 0.02
    })
}

/// Each grid point's members pooled with its neighbours', each moved by the difference of
/// the smoothed medians: the spread over the start changes slowly with c1, so three times
/// the members give its shape, and the band's edges do not jump with the chaos of one set.
fn pooled(members: &[Vec<f64>], raw_medians: &[f64], medians: &[f64]) -> Vec<Vec<f64>> {
    (0..members.len())
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(members.len() - 1));
            if medians[k].is_nan() {
                return Vec::new();
            }
            (a..=b)
                .filter(|&j| !raw_medians[j].is_nan())
                .flat_map(|j| members[j].iter().map(move |s| s - raw_medians[j] + medians[k]))
                .collect()
        })
        .collect()
}

/// The part [u0, u1] ⊆ [0, 1] of the segment from band `a` (u = 0) to band `b` (u = 1), the
/// edges straight between, where `low(u) ≤ stat ≤ high(u)`; `None` when empty.
fn segment(a: &(f64, f64), b: &(f64, f64), stat: f64) -> Option<(f64, f64)> {
    let (mut u0, mut u1) = (0.0f64, 1.0f64);
    // p + q·u ≤ 0 for each edge: low − stat ≤ 0 and stat − high ≤ 0.
    for (p, q) in [(a.0 - stat, b.0 - a.0), (stat - a.1, a.1 - b.1)] {
        if q == 0.0 {
            if p > 0.0 {
                return None;
            }
        } else if q > 0.0 {
            u1 = u1.min(-p / q);
        } else {
            u0 = u0.max(-p / q);
        }
    }
    (u0 <= u1).then_some((u0, u1))
}

/// Where a piecewise-linear function of ln c1 through the grid's points `(ln c1_k, f_k)` meets
/// `target` between grid points k and k+1: ln c1 there.
fn cross(lc: &[f64], f: &[f64], k: usize, target: f64) -> f64 {
    let (a, b) = (f[k] - target, f[k + 1] - target);
    if a == b {
        return 0.5 * (lc[k] + lc[k + 1]);
    }
    lc[k] + (lc[k + 1] - lc[k]) * a / (a - b)
}

/// 1 − the interval's confidence.
const TAIL: f64 = 0.05;

/// One statistic's Neyman construction.
struct Accepted {
    /// The records' mean statistic.
    stat: f64,
    /// The smoothed medians of the compared members at each c1.
    medians: Vec<f64>,
    /// The band [low, high] at each c1.
    bands: Vec<(f64, f64)>,
    /// The hull (ln c1) of the accepted c1, `None` when none is.
    hull: Option<(f64, f64)>,
}

/// The c1 whose band (2·`tail` outside it) of the mean statistic over the first `periods`
/// periods holds the records', compared with the members the ball was hit in.
fn accepted(table: &Table, observed: &[Observed], periods: usize, tail: f64) -> Accepted {
    let n = observed.len();
    let stat = observed.iter().map(|o| statistic(&o.envelope_m, periods)).sum::<f64>() / n as f64;
    let noise =
        (observed.iter().map(|o| statistic_noise(&o.envelope_m, periods, &o.envelope_sd_m).powi(2)).sum::<f64>()
            / (n * n) as f64)
            .sqrt();
    let lc: Vec<f64> = table.c1_n_s_m.iter().map(|c| c.ln()).collect();
    let members: Vec<Vec<f64>> = table
        .envelopes
        .iter()
        .zip(&table.first_impact_m_s)
        .map(|(ms, hit)| ms.iter().zip(hit).filter(|(_, &u)| u > 0.0).map(|(e, _)| statistic(e, periods)).collect())
        .collect();
    let raw_medians: Vec<f64> = members.iter().map(|m| if m.is_empty() { f64::NAN } else { median(m) }).collect();
    let medians = smoothed(&raw_medians);
    let pooled = pooled(&members, &raw_medians, &medians);
    // A c1 without members the ball was hit in (its own and its neighbours') cannot have
    // made the record: its band is put out of reach.
    let bands: Vec<(f64, f64)> = pooled
        .iter()
        .map(|m| if m.len() < MIN_CLASS_MEMBERS { (f64::MAX / 4.0, f64::MAX / 4.0) } else { band(m, n, noise, tail) })
        .collect();
    // The accepted set {c1 : low(c1) ≤ S ≤ high(c1)} with the band's edges straight in ln c1
    // between grid points (so a statistic between two narrow bands finds the c1 between
    // them), and its hull.
    let acc: Vec<(f64, f64)> = (0..lc.len() - 1)
        .filter_map(|k| {
            let (u0, u1) = segment(&bands[k], &bands[k + 1], stat)?;
            let at = |u: f64| lc[k] + u * (lc[k + 1] - lc[k]);
            Some((at(u0), at(u1)))
        })
        .collect();
    let hull = acc.iter().map(|a| a.0).min_by(f64::total_cmp).zip(acc.iter().map(|a| a.1).max_by(f64::total_cmp));
    Accepted { stat, medians, bands, hull }
}

/// The note of a fit none of whose records shows the ball (each is the structure's own decay
/// within its noise).
pub const NOT_IDENTIFIABLE: &str = "a decay is the structure's own within its noise (the ball was hardly hit): c1 is not identifiable from it; strike harder (a larger v0) or give several strikes (--data repeated)";

/// Compares `observed` records with `table`: the fitted c1, its interval and restitution.
///
/// One rule decides what a record can tell (docs/model.md §13.2), stated on the record alone
/// and not on its sample count: a record whose envelope is the structure's own decay within
/// its noise (`structure_alone`) was made by a start the ball was not (visibly) hit from.
/// Whether the ball is hit depends on where it sat, not on c1, so such a record says nothing
/// of c1: it is set aside. With no other record the interval is the whole grid (open at both
/// ends) with the note [`NOT_IDENTIFIABLE`], never a refusal and never a narrow interval made
/// of round-off between the record and the runs the ball missed. The records that show the
/// ball are compared with the members the ball was hit in (the band at each c1 is then the
/// distribution over those starts, so the 95 % coverage holds).
// Over 80 lines: the two statistics' intervals, where they meet, the estimate and the grid's resolution.
pub fn compare(d: &ValidDesign, table: &Table, observed: &[Observed]) -> Result<DamperFit, ThudError> {
    let periods = observed.iter().map(|o| o.usable).min().unwrap_or(0).min(table.envelopes[0][0].len());
    if periods < 3 {
        return Err(bad("too short: fewer than 3 periods to compare"));
    }
    let lc: Vec<f64> = table.c1_n_s_m.iter().map(|c| c.ln()).collect();
    let g = lc.len();
    let hit: Vec<Observed> =
        observed.iter().filter(|o| !structure_alone(d, o, table.period_s, periods)).cloned().collect();
    if hit.is_empty() {
        let stat = observed.iter().map(|o| statistic(&o.envelope_m, periods)).sum::<f64>() / observed.len() as f64;
        let mid = 0.5 * (lc[0] + lc[g - 1]);
        return finish(d, table, observed, periods, stat, (mid, lc[0], lc[g - 1]), Some(NOT_IDENTIFIABLE.to_string()));
    }
    let missed = observed.len() - hit.len();
    let observed = &hit[..];
    let periods = observed.iter().map(|o| o.usable).min().unwrap_or(0).min(table.envelopes[0][0].len());
    // Two statistics, each at 97.5 % (so both hold the truth at least 95 % of the time, by
    // Bonferroni's inequality): the whole decay's and its early part's (the first third, at
    // least 3 periods). Where the ball ends up riding a wall, the whole decay's statistic is
    // not monotone in c1 (the most damped contacts stop the rattle and leave a plateau) and
    // accepts c1 on both sides of the optimum; the early part, where the damper works, is.
    let early = (periods / 3).max(3).min(periods);
    let whole = accepted(table, observed, periods, 0.5 * TAIL);
    let first = accepted(table, observed, early, 0.5 * TAIL);
    let (Some((lo_w, hi_w)), Some((lo_e, hi_e))) = (whole.hull, first.hull) else {
        // No c1 of the grid's span explains the data: name the nearest band's c1.
        // No c1 of the grid's span explains the decay within its noise: the record follows
        // something the runs do not (a design value off, a contact unlike the model's). c1 is
        // then not bounded by it: the whole grid, open, with the note that says why.
        let w = if whole.hull.is_none() { &whole } else { &first };
        let dist = |k: usize| (w.bands[k].0 - w.stat).max(w.stat - w.bands[k].1);
        let k = (0..g).min_by(|&i, &j| dist(i).total_cmp(&dist(j))).unwrap_or(0);
        let note = format!(
            "no c1 explains the decay within its noise (its statistic {} is nearest the runs at c1 {} N·s/m): c1 is not bounded by it; check the design's values (M, K, C, m, d, v0) or give several strikes",
            crate::units::sig(w.stat, 4),
            crate::units::sig(table.c1_n_s_m[k], 4)
        );
        let mid = 0.5 * (lc[0] + lc[g - 1]);
        let fit = finish(d, table, observed, periods, whole.stat, (mid, lc[0], lc[g - 1]), Some(note))?;
        return Ok(DamperFit { records: missed + observed.len(), ..fit });
    };
    // The intersection; where the two do not meet (rarer than 5 %), their hull, and a note:
    // the record's early decay and its whole point at different c1, which no single c1's
    // runs do (the hull then holds c1 no better than the runs explain the record).
    let disjoint = lo_w.max(lo_e) > hi_w.min(hi_e);
    let (lo_ln, hi_ln) = if disjoint { (lo_w.min(lo_e), hi_w.max(hi_e)) } else { (lo_w.max(lo_e), hi_w.min(hi_e)) };
    let (stat, medians) = (whole.stat, whole.medians);
    // The point estimate: where the median meets the statistic, inside the interval.
    let best_ln = (0..g - 1)
        .filter(|&k| (medians[k] - stat) * (medians[k + 1] - stat) <= 0.0)
        .map(|k| cross(&lc, &medians, k, stat))
        .filter(|l| *l >= lo_ln - 1e-12 && *l <= hi_ln + 1e-12)
        .min_by(|a, b| (a - 0.5 * (lo_ln + hi_ln)).abs().total_cmp(&(b - 0.5 * (lo_ln + hi_ln)).abs()))
        .unwrap_or(0.5 * (lo_ln + hi_ln));
    // The table resolves c1 to one grid step each way, no finer: each band pools a point's
    // members with its two neighbours' and the medians are smoothed over three points, so the
    // band at a grid point stands for c1 from the point below to the point above. Where the
    // start hardly matters and the noise is small the Neyman set can be narrower than that
    // (seen: ±0.3 % at c1 300 N·s/m, 0.8 % from the truth of an independent integration; with
    // half a step, 8 % from the truth on a displacement record of the coverage test), so the
    // interval holds at least one step on each side of the estimate.
    let open = lo_ln <= lc[0] || hi_ln >= lc[g - 1];
    let step = (lc[g - 1] - lc[0]) / (g - 1) as f64;
    let lo_ln = lo_ln.min(best_ln - step).max(lc[0]);
    let hi_ln = hi_ln.max(best_ln + step).min(lc[g - 1]);
    let ratio = (hi_ln - lo_ln).exp();
    // Where the early decay's set cuts the whole decay's by more than the table's resolution
    // (one grid step), that end of the interval rests on the first periods alone, whose
    // statistic is the noisier (the first period's amplitude enters it whole) and changes
    // slowly with c1 there: in the 2.5 % of records whose early statistic falls in its tail,
    // the interval then misses by far (seen: an acceleration record, truth 80.1, the whole
    // decay's set [69, 188], the first three periods' [126, 616], the interval [111, 188]).
    let cut = !disjoint && (lo_ln - lo_w > step + 1e-9 || hi_w - hi_ln > step + 1e-9);
    let note = if open || ratio > 3.0 {
        Some(format!(
            "the data bound c1 only to a factor {} (high/low); give several strikes (--data repeated) to narrow it",
            crate::units::sig(ratio, 2)
        ))
    } else if disjoint {
        Some(format!(
            "the decay's first {early} periods and its whole point at different c1 ([{}, {}] and [{}, {}] N·s/m), as no single c1's runs do: the interval is their hull and may miss; check the design's values (M, K, C, m, d, v0) or give several strikes",
            crate::units::sig(lo_e.exp(), 3),
            crate::units::sig(hi_e.exp(), 3),
            crate::units::sig(lo_w.exp(), 3),
            crate::units::sig(hi_w.exp(), 3)
        ))
    } else if cut {
        Some(format!(
            "the whole decay allows c1 in [{}, {}] N·s/m, its first {early} periods only in [{}, {}]: the interval is where they meet and rests at one end on those few periods, so it may miss; give several strikes (--data repeated)",
            crate::units::sig(lo_w.exp(), 3),
            crate::units::sig(hi_w.exp(), 3),
            crate::units::sig(lo_e.exp(), 3),
            crate::units::sig(hi_e.exp(), 3)
        ))
    } else if missed > 0 {
        Some(format!(
            "{missed} of {} decays are the structure's own within their noise (the ball was hardly hit): they were set aside",
            missed + observed.len()
        ))
    } else {
        None
    };
    let fit = finish(d, table, observed, periods, stat, (best_ln, lo_ln, hi_ln), note)?;
    Ok(DamperFit { ci_open: open, records: missed + observed.len(), ..fit })
}

/// The fit's report from the estimate and interval `(best, low, high)` (ln c1) of the records
/// `observed` over their first `periods` periods, whose mean statistic is `stat`.
fn finish(
    d: &ValidDesign,
    table: &Table,
    observed: &[Observed],
    periods: usize,
    stat: f64,
    (best_ln, lo_ln, hi_ln): (f64, f64, f64),
    note: Option<String>,
) -> Result<DamperFit, ThudError> {
    let lc: Vec<f64> = table.c1_n_s_m.iter().map(|c| c.ln()).collect();
    let g = lc.len();
    let open = lo_ln <= lc[0] || hi_ln >= lc[g - 1];
    let (c1, lo, hi) = (best_ln.exp(), lo_ln.exp(), hi_ln.exp());
    let k_best = (0..g).min_by(|&i, &j| (lc[i] - best_ln).abs().total_cmp(&(lc[j] - best_ln).abs())).unwrap_or(0);
    let firsts: Vec<f64> = table.first_impact_m_s[k_best].iter().copied().filter(|&u| u > 0.0).collect();
    let u0 = if firsts.is_empty() { d.damper.v0_m_s.abs() } else { median(&firsts) };
    let r_at = |c: f64| -> Result<f64, ThudError> {
        let mut dd = d.design().clone();
        dd.damper.c1_n_s_m = c;
        let v = dd.check()?;
        Ok(design::restitution_curve(&v, &[v.damper.impact_mass_kg], u0)?[0].1)
    };
    let (r, r_lo, r_hi) = (r_at(c1)?, r_at(hi)?, r_at(lo)?);
    // The median member's envelope at the fitted c1 against the records', for the residual.
    let periods_all = table.envelopes[0][0].len();
    let model: Vec<f64> =
        (0..periods_all).map(|j| median(&table.envelopes[k_best].iter().map(|e| e[j]).collect::<Vec<_>>())).collect();
    let mut sq = 0.0;
    let mut count = 0usize;
    for o in observed {
        for (a, b) in o.envelope_m.iter().zip(&model).take(periods) {
            sq += (a - b).powi(2);
            count += 1;
        }
    }
    Ok(DamperFit {
        c1_n_s_m: c1,
        c1_n_s_m_stderr: (hi - lo) / (2.0 * 1.96),
        c1_n_s_m_ci: [lo, hi],
        ci_open: open,
        restitution: r,
        restitution_stderr: (r_hi - r_lo) / (2.0 * 1.96),
        restitution_ci: [r_lo, r_hi],
        first_impact_speed_m_s: u0,
        residual_rms: (sq / count.max(1) as f64).sqrt(),
        statistic: stat,
        periods,
        records: observed.len(),
        starts: table.envelopes[0].len(),
        grid_points: g,
        envelope_period_s: table.period_s,
        measured_envelope_m: observed[0].envelope_m.clone(),
        model_envelope_m: model,
        inputs: Vec::new(),
        v0_m_s_record: None,
        v0_m_s_record_stderr: None,
        note,
    })
}

/// The span (s) the runs cover for `records`: the shortest record's.
pub fn common_span_s(records: &[Series]) -> f64 {
    records.iter().map(Series::span_s).fold(f64::INFINITY, f64::min)
}

/// Fits c1 of design `d` to `records` (each starting at its strike): observes each, builds the
/// ensemble table over the shortest span and compares. `Ok(None)` when cancelled.
pub fn fit(d: &ValidDesign, records: &[Series], cancel: Option<&AtomicBool>) -> Result<Option<DamperFit>, ThudError> {
    if records.is_empty() {
        return Err(bad("no record; give at least one"));
    }
    let span = common_span_s(records);
    let mut observed = Vec::with_capacity(records.len());
    for r in records {
        let mut o = observe(r, d)?;
        let keep = o.t_s.partition_point(|&t| t <= span);
        o.t_s.truncate(keep);
        o.x_m.truncate(keep);
        observed.push(o);
    }
    let c1_grid = grid(d)?;
    let Some(table) = Table::build(d, &c1_grid, STARTS, span, cancel)? else { return Ok(None) };
    let mut f = compare(d, &table, &observed)?;
    let strikes: Vec<super::strike::Strike> =
        records.iter().filter_map(|r| super::strike::strike_speed(r, d.design()).ok()).collect();
    if let Some(st) = super::strike::combined(&strikes) {
        f.v0_m_s_record = Some(st.v0_m_s);
        f.v0_m_s_record_stderr = Some(st.stderr_m_s);
    }
    Ok(Some(f))
}

/// The design whose work a damper fit of records spanning `span_s` (s) costs: the design run
/// for that span ([`crate::limits::check_runs`] with [`GRID_POINTS`] cells of [`STARTS`] runs).
pub fn work_design(d: &ValidDesign, span_s: f64) -> Result<ValidDesign, ThudError> {
    let mut dd = d.design().clone();
    dd.damper.duration_s = span_s;
    dd.check().map_err(|e| e.renamed(super::DATA_PARAM))
}

/// A given value of the design known only to a relative standard uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Input {
    /// The main mass M.
    MainMass,
    /// The structure's stiffness K.
    K,
    /// The structure's damping C.
    C,
    /// The ball's mass m.
    Mass,
    /// The clearance d.
    Gap,
    /// The strike's speed v0.
    V0,
}

impl Input {
    /// The flag's name (`main-mass`, `k`, `c`, `mass`, `gap`, `v0`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Input::MainMass => "main-mass",
            Input::K => "k",
            Input::C => "c",
            Input::Mass => "mass",
            Input::Gap => "gap",
            Input::V0 => "v0",
        }
    }

    /// The input of a flag's name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Input> {
        [Input::MainMass, Input::K, Input::C, Input::Mass, Input::Gap, Input::V0].into_iter().find(|i| i.name() == name)
    }

    fn scale(self, d: &mut Design, factor: f64) {
        let p = &mut d.damper;
        match self {
            Input::MainMass => p.main_mass_kg *= factor,
            Input::K => p.stiffness_n_m *= factor,
            Input::C => p.damping_n_s_m *= factor,
            Input::Mass => p.impact_mass_kg *= factor,
            Input::Gap => p.gap_m *= factor,
            Input::V0 => p.v0_m_s *= factor,
        }
    }
}

/// One input's uncertainty carried into the interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct InputShift {
    pub input: Input,
    /// Its relative standard uncertainty.
    pub relative_sd: f64,
    /// |ln c1(value × (1 + u)) − ln c1(value)|: how far one standard uncertainty moves the
    /// fitted c1 (in ln c1).
    pub ln_c1_shift: f64,
}

/// [`fit`] with the given inputs' uncertainties carried into the interval (docs/model.md
/// §13.2): `given` holds relative standard uncertainties (as typed with `±`). Each is
/// propagated by GUM's law of propagation (JCGM 100:2008, §5.1) with its sensitivity found by
/// a second fit at the value × (1 + u): the input moves ln c1 by `s_i`, and each side of the
/// interval in ln c1 becomes `√(h² + Σ (1.96·s_i)²)` for its half-width h. An input whose
/// 1.96·u·2 is below a tenth of the smaller half-width (c1 moves less than twice as fast as any
/// input, measured: 1.2–1.4 for v0 and M) widens it by less than 0.5 % and is not refitted.
/// A design v0 that the records' own strike ([`super::strike`]) disagrees with beyond
/// [`super::strike::DISAGREE_SDS`] of their joint uncertainty is carried with the relative
/// uncertainty that covers the difference ([`super::strike::disagreement`]).
// Over 80 lines: the fit, then each input's uncertainty propagated in turn (GUM §5.1).
pub fn fit_with_inputs(
    d: &ValidDesign,
    records: &[Series],
    given: &[(Input, f64)],
    cancel: Option<&AtomicBool>,
) -> Result<Option<DamperFit>, ThudError> {
    // One entry an input (the last given), in a fixed order.
    let mut inputs: Vec<(Input, f64)> = Vec::new();
    for &(i, u) in given.iter().rev() {
        if u > 0.0 && u.is_finite() && !inputs.iter().any(|(j, _)| *j == i) {
            inputs.push((i, u));
        }
    }
    let base = d;
    let Some(mut f) = fit(base, records, cancel)? else { return Ok(None) };
    // A v0 the record's own strike disagrees with (beyond their joint uncertainty) is carried
    // with the uncertainty that covers the difference.
    if let (Some(v), Some(sd)) = (f.v0_m_s_record, f.v0_m_s_record_stderr) {
        // The record's v0 is read with the design's M, K, C, m and d: their stated
        // uncertainties move it too (each by a second reading at the value × (1 + u)).
        let mut var = sd * sd;
        for &(input, u) in inputs.iter().filter(|(i, _)| *i != Input::V0) {
            let mut moved = base.design().clone();
            input.scale(&mut moved, 1.0 + u);
            let strikes: Vec<super::strike::Strike> =
                records.iter().filter_map(|r| super::strike::strike_speed(r, &moved).ok()).collect();
            if let Some(st) = super::strike::combined(&strikes) {
                var += (st.v0_m_s - v).powi(2);
            }
        }
        let sd = var.sqrt();
        f.v0_m_s_record_stderr = Some(sd);
        let stated = inputs.iter().find(|(i, _)| *i == Input::V0).map_or(0.0, |(_, u)| *u);
        let strike = super::strike::Strike { v0_m_s: v, stderr_m_s: sd };
        if let Some(u) = super::strike::disagreement(base.damper.v0_m_s, stated, &strike) {
            inputs.retain(|(i, _)| *i != Input::V0);
            inputs.push((Input::V0, u.max(stated)));
        }
    }
    inputs.sort_by_key(|(i, _)| *i);
    let best = f.c1_n_s_m.ln();
    let (lo_h, hi_h) = (best - f.c1_n_s_m_ci[0].ln(), f.c1_n_s_m_ci[1].ln() - best);
    let mut extra = 0.0;
    for (input, u) in inputs {
        if 1.96 * u * 2.0 < 0.1 * lo_h.min(hi_h) {
            continue;
        }
        let mut moved = base.design().clone();
        input.scale(&mut moved, 1.0 + u);
        let shift = match moved.check().map_err(|e| e.renamed(input.name())).and_then(|m| fit(&m, records, cancel)) {
            Ok(Some(g)) => (g.c1_n_s_m.ln() - best).abs(),
            Ok(None) => return Ok(None),
            // No c1 explains the record with the input moved by one uncertainty: the data
            // bound c1 no better than the whole grid.
            Err(e) if e.param() == super::DATA_PARAM => f64::INFINITY,
            Err(e) => return Err(e),
        };
        extra += (1.96 * shift).powi(2);
        f.inputs.push(InputShift { input, relative_sd: u, ln_c1_shift: shift });
    }
    if extra > 0.0 {
        let grid = grid(base)?;
        let (g0, g1) = (grid[0].ln(), grid[grid.len() - 1].ln());
        let lo = (best - lo_h.hypot(extra.sqrt())).max(g0.min(best - lo_h));
        let hi = (best + hi_h.hypot(extra.sqrt())).min(g1.max(best + hi_h));
        let (lo, hi) = (if lo.is_finite() { lo } else { g0 }, if hi.is_finite() { hi } else { g1 });
        f.c1_n_s_m_ci = [lo.exp(), hi.exp()];
        f.c1_n_s_m_stderr = (hi.exp() - lo.exp()) / (2.0 * 1.96);
        f.ci_open = f.ci_open || lo <= g0 || hi >= g1;
        let r_at = |c: f64| -> Result<f64, ThudError> {
            let mut x = base.design().clone();
            x.damper.c1_n_s_m = c;
            let v = x.check()?;
            Ok(design::restitution_curve(&v, &[v.damper.impact_mass_kg], f.first_impact_speed_m_s)?[0].1)
        };
        let (r_lo, r_hi) = (r_at(hi.exp())?, r_at(lo.exp())?);
        f.restitution_ci = [r_lo, r_hi];
        f.restitution_stderr = (r_hi - r_lo) / (2.0 * 1.96);
        let ratio = (hi - lo).exp();
        if f.note.is_none() && (f.ci_open || ratio > 3.0) {
            f.note = Some(format!(
                "the data and the inputs' uncertainties bound c1 only to a factor {} (high/low); narrow the inputs' uncertainties or give several strikes (--data repeated)",
                crate::units::sig(ratio, 2)
            ));
        }
    }
    Ok(Some(f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::damper::DamperParams;
    use crate::fit::structure::tests::{measured, Noise};

    /// The main mass's displacement of `d` with c1 `c1` from a ball at rest at `y0`, sampled at
    /// about `rate_hz` (every sample kept with probability 2/3: uneven), made "measured".
    /// The heavy design: a 2 kg structure on 8 kN/m carrying a 100 g ball in a 2 cm gap, struck
    /// at 0.5 m/s.
    fn heavy() -> Design {
        let mut des = Design::default();
        des.damper.main_mass_kg = 2.0;
        des.damper.stiffness_n_m = 8000.0;
        des.damper.impact_mass_kg = 0.1;
        des.damper.gap_m = 0.02;
        des.damper.v0_m_s = 0.5;
        des
    }

    fn record(d: &ValidDesign, c1: f64, y0: f64, rate_hz: f64, noise: f64, g: &mut Noise) -> Series {
        let mut p = d.damper;
        p.c1_n_s_m = c1;
        p.ball_position_m = y0;
        let n = (p.duration_s * rate_hz * 1.5) as usize;
        let run = damper::simulate(&p, d.solver, &RunOptions { history_samples: n, cancel: None }).unwrap();
        let (t, x): (Vec<f64>, Vec<f64>) =
            run.history.iter().filter(|_| g.uniform() < 0.67).map(|h| (h.t_s, h.x_m)).unzip();
        let y = measured(&t, &x, noise, g);
        Series::new(t, y, Quantity::Displacement).unwrap()
    }

    /// The fit of one record of `d` with c1 `truth` (2 kHz, 1 % noise), the ball at rest at a
    /// random offset `y0` in the clearance: `(y0, the fit)`.
    fn fit_one_record(d: &ValidDesign, table: &Table, truth: f64, g: &mut Noise) -> (f64, DamperFit) {
        let y0 = (g.uniform() - 0.5) * d.damper.gap_m * 0.999;
        let s = record(d, truth, y0, 2000.0, 0.01, g);
        (y0, compare(d, table, &[observe(&s, d).unwrap()]).unwrap())
    }

    /// The interval is honest: over 60 synthetic records of one design, each from a ball start
    /// drawn at random (uniform in the clearance, at rest), with 1 % noise, an offset, a drift
    /// and uneven 2 kHz sampling, the truth falls inside the 95 % interval of at least 53 (57 measured;
    /// 196 of 200 with n = 200). For a
    /// correct 95 % interval the count is Binomial(60, 0.95): P(count ≤ 52) = 1.6 %, so this
    /// bound fails a correct method rarely while a 90 % interval (P(≥ 53) = 31 %) or worse
    /// mostly fails it. The intervals are at most a factor 3 wide (high/low) in the median.
    #[test]
    fn the_interval_covers_the_truth_about_95_percent_of_the_time() {
        let d = Design::default().check().unwrap();
        let truth = 40.0;
        let span = d.damper.duration_s;
        let table = Table::build(&d, &grid(&d).unwrap(), STARTS, span, None).unwrap().unwrap();
        let mut g = Noise(2023);
        let (mut covered, mut ratios) = (0, Vec::new());
        let n = 60;
        for _ in 0..n {
            let (_, fit) = fit_one_record(&d, &table, truth, &mut g);
            let [lo, hi] = fit.c1_n_s_m_ci;
            if lo <= truth && truth <= hi {
                covered += 1;
            }
            ratios.push(hi / lo);
        }
        ratios.sort_by(f64::total_cmp);
        eprintln!("covered {covered}/{n}, median width ratio {}", ratios[n / 2]);
        assert!(covered >= 53, "covered {covered} of {n}");
        assert!(ratios[n / 2] <= 3.0, "median width ratio {}", ratios[n / 2]);
    }

    /// Three strikes fitted together: the interval holds the truth and is narrower than one
    /// strike's (the full path, [`fit`]), on records noisy enough that one strike's interval is
    /// wider than the table's resolution.
    #[test]
    fn repeated_strikes_narrow_the_interval() {
        let mut design = Design::default();
        design.damper.c1_n_s_m = 5.0; // the fit does not read it
        let d = design.check().unwrap();
        let truth = 80.0;
        let mut g = Noise(99);
        let records: Vec<Series> =
            [-0.3, 0.1, 0.42].iter().map(|f| record(&d, truth, f * d.damper.gap_m, 3000.0, 0.06, &mut g)).collect();
        let one = fit(&d, &records[..1], None).unwrap().unwrap();
        let three = fit(&d, &records, None).unwrap().unwrap();
        for f in [&one, &three] {
            assert!(f.c1_n_s_m_ci[0] <= truth && truth <= f.c1_n_s_m_ci[1], "{:?}", f.c1_n_s_m_ci);
            assert!(f.c1_n_s_m_ci[0] <= f.c1_n_s_m && f.c1_n_s_m <= f.c1_n_s_m_ci[1]);
            assert!(f.restitution_ci[0] <= f.restitution && f.restitution <= f.restitution_ci[1]);
        }
        let width = |f: &DamperFit| f.c1_n_s_m_ci[1] / f.c1_n_s_m_ci[0];
        // Noise enough (6 % of the peak) that one strike's interval lies above the floor of one
        // grid step each side (the table's resolution), where narrowing can show.
        assert!(width(&three) < width(&one), "{} vs {}", width(&three), width(&one));
        assert_eq!(three.records, 3);
    }

    /// A record made by a second, independent integration — a fixed-step RK4 of Eqs 25–26
    /// written here (Hertz force K_HZ·δ^1.5 + c1·δ', no event location) — not thud's solver:
    /// the interval holds the truth and is at most a factor 3 wide.
    #[test]
    fn an_independent_rk4_record_is_fitted() {
        let d = Design::default().check().unwrap();
        let p = d.damper;
        let truth = 25.0;
        let dt = 5e-7;
        let every = 1000; // 2 kHz
        let (mut t, mut x) = (vec![], vec![]);
        let steps = (p.duration_s / dt).round() as usize;
        rk4(&p, truth, 0.37 * 0.5 * p.gap_m, dt, steps, |i, s| {
            if i % every == 0 {
                t.push(i as f64 * dt);
                x.push(s[0]);
            }
        });
        let mut g = Noise(4);
        let (t, x): (Vec<f64>, Vec<f64>) = t.into_iter().zip(x).filter(|_| g.uniform() < 0.75).unzip();
        let y = measured(&t, &x, 0.015, &mut g);
        let f = fit(&d, &[Series::new(t, y, Quantity::Displacement).unwrap()], None).unwrap().unwrap();
        let [lo, hi] = f.c1_n_s_m_ci;
        assert!(lo <= truth && truth <= hi, "[{lo}, {hi}]");
        assert!(hi / lo <= 3.0, "[{lo}, {hi}]");
    }

    /// One rule for what a record can tell, whatever its length: thud's own noise-free record
    /// of a strike that never reaches the ball (M 2 kg, K 8000 N/m, m 100 g, d 2 cm, struck
    /// at 0.5 m/s with the ball at rest in the middle, c1 30 N·s/m; 2 s) sampled with 5,000 to
    /// 20,000 samples gets the same answer every time: the whole grid as the interval (it holds
    /// the truth) and the note that c1 is not identifiable. (Before, 10,000 samples were
    /// refused and 9,899 gave [1.97, 3.51], excluding 30.)
    #[test]
    fn a_never_hit_record_gets_the_same_answer_at_every_length() {
        let mut des = heavy();
        des.damper.duration_s = 2.0;
        let d = des.check().unwrap();
        let truth = 30.0;
        let c1_grid = grid(&d).unwrap();
        let table = Table::build(&d, &c1_grid, STARTS, d.damper.duration_s, None).unwrap().unwrap();
        let mut answers = Vec::new();
        for n in [5000, 6001, 7919, 9899, 9989, 10_000, 10_001, 12_345, 15_000, 17_777, 20_000] {
            let mut p = d.damper;
            p.c1_n_s_m = truth;
            p.ball_position_m = 0.0;
            let run = damper::simulate(&p, d.solver, &RunOptions { history_samples: n, cancel: None }).unwrap();
            assert!(run.impacts.is_empty(), "{n}: the ball was hit");
            let (t, x): (Vec<f64>, Vec<f64>) = run.history.iter().map(|h| (h.t_s, h.x_m)).unzip();
            let s = Series::new(t, x, Quantity::Displacement).unwrap();
            let f = compare(&d, &table, &[observe(&s, &d).unwrap()]).unwrap_or_else(|e| panic!("{n}: {e}"));
            let [lo, hi] = f.c1_n_s_m_ci;
            assert!(lo <= truth && truth <= hi, "{n}: [{lo}, {hi}]");
            assert_eq!(f.note.as_deref(), Some(NOT_IDENTIFIABLE), "{n}");
            assert!(f.ci_open, "{n}");
            answers.push((n, f.c1_n_s_m_ci));
        }
        assert!(answers.iter().all(|a| a.1 == answers[0].1), "{answers:?}");
        let [lo, hi] = answers[0].1;
        assert!((lo / c1_grid[0] - 1.0).abs() < 1e-12 && (hi / c1_grid[GRID_POINTS - 1] - 1.0).abs() < 1e-12);
    }

    /// Two narrow bands that do not overlap: a statistic between them is accepted in between
    /// (where the straight edges pass it), not refused at both grid points.
    #[test]
    fn a_statistic_between_two_narrow_bands_is_accepted_between_them() {
        let (a, b) = ((-0.10, -0.09), (-0.20, -0.19));
        let (u0, u1) = segment(&a, &b, -0.15).unwrap();
        assert!((u0 - 0.5).abs() < 1e-12 && (u1 - 0.6).abs() < 1e-12, "{u0} {u1}");
        assert_eq!(segment(&a, &b, -0.05), None);
        assert_eq!(segment(&(-1.0, 1.0), &(-1.0, 1.0), 0.0), Some((0.0, 1.0)));
    }

    /// A record of design `d` with contact damping `c1` and the ball at rest at `y0` made by a
    /// second, independent integration (fixed-step RK4 of Eqs 25–26 with the Hertz force
    /// K_HZ·δ^1.5 + c1·δ', no event location; not thud's solver) in steps of 2 µs (about 75
    /// a contact): the main mass's displacement every 250 steps (2 kHz) and its acceleration
    /// every 50 (10 kHz), each sample kept with probability 3/4 (uneven): (times, displacement)
    /// and (times, acceleration).
    #[allow(clippy::type_complexity)]
    fn rk4_record(d: &ValidDesign, c1: f64, y0: f64, g: &mut Noise) -> ((Vec<f64>, Vec<f64>), (Vec<f64>, Vec<f64>)) {
        let p = d.damper;
        let dt = 2e-6;
        let (mut tx, mut x) = (vec![0.0], vec![0.0]);
        let (mut ta, mut a) = (vec![0.0], vec![]);
        let steps = (p.duration_s / dt).round() as usize;
        let accel = rates(&p, c1);
        rk4(&p, c1, y0, dt, steps, |i, s| {
            if i == 0 {
                a.push(accel(s)[1]);
                return;
            }
            if i % 250 == 0 && g.uniform() < 0.75 {
                tx.push(i as f64 * dt);
                x.push(s[0]);
            }
            if i % 50 == 0 && g.uniform() < 0.75 {
                ta.push(i as f64 * dt);
                a.push(accel(s)[1]);
            }
        });
        ((tx, x), (ta, a))
    }

    /// The rates `[x', x'', y', y'']` of Eqs 25–26 for the independent integration behind the
    /// records (Hertz force K_HZ·δ^1.5 + c1·δ' on the ball past either wall; not thud's solver)
    /// of design `p` with contact damping `c1` (N·s/m), at the state `[x, x', y, y']`.
    fn rates(p: &DamperParams, c1: f64) -> impl Fn([f64; 4]) -> [f64; 4] {
        let (big_m, m, k, c, khz, half) =
            (p.main_mass_kg, p.impact_mass_kg, p.stiffness_n_m, p.damping_n_s_m, p.k_hz, 0.5 * p.gap_m);
        move |s: [f64; 4]| {
            let [x, v, y, w] = s;
            let z = y - x;
            let delta = z.abs() - half;
            let f_ball = if delta > 0.0 {
                let sg = z.signum();
                -sg * (khz * delta.powf(1.5) + c1 * sg * (w - v))
            } else {
                0.0
            };
            [v, (-k * x - c * v - f_ball) / big_m, w, f_ball / m]
        }
    }

    /// A fixed-step RK4 of [`rates`] (no event location): design `p` with contact damping `c1`
    /// (N·s/m), struck at `p.v0_m_s` with the ball at rest at `y0` (m), `steps` steps of `dt`
    /// (s); `visit(i, [x, x', y, y'])` sees the start (`i = 0`) and the state after each step.
    fn rk4(p: &DamperParams, c1: f64, y0: f64, dt: f64, steps: usize, mut visit: impl FnMut(usize, [f64; 4])) {
        let accel = rates(p, c1);
        let add =
            |a: [f64; 4], b: [f64; 4], h: f64| [a[0] + h * b[0], a[1] + h * b[1], a[2] + h * b[2], a[3] + h * b[3]];
        let mut s = [0.0, p.v0_m_s, y0, 0.0];
        visit(0, s);
        for i in 1..=steps {
            let k1 = accel(s);
            let k2 = accel(add(s, k1, 0.5 * dt));
            let k3 = accel(add(s, k2, 0.5 * dt));
            let k4 = accel(add(s, k3, dt));
            for j in 0..4 {
                s[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
            }
            visit(i, s);
        }
    }

    /// Measured-style records over designs from light to heavy contact damping (the issue's
    /// acceptance): decays made by an independent RK4, displacement at about 2 kHz with 1 %
    /// noise and acceleration at about 10 kHz with 2 % noise (of the structure's own
    /// acceleration amplitude K/M·max|x|; the impacts' spikes stand far above it), each with an
    /// offset, a drift and uneven sampling. Every 95 % interval holds the truth and is at most a
    /// factor 3 wide (high/low). The heavy case is the issue's: M 2 kg, K 8000 N/m, m 100 g,
    /// d 2 cm, c1 100 N·s/m, struck at 0.5 m/s (its interval was [95, 710] N·s/m, open above,
    /// before the fit conditioned on the record's class, docs/model.md §13.2).
    #[test]
    fn measured_style_decays_from_light_to_heavy_damping_are_bracketed_within_a_factor_3() {
        let heavy = |c1: f64, v0: f64, y0_frac: f64| {
            let mut des = Design::default();
            des.damper.main_mass_kg = 2.0;
            des.damper.stiffness_n_m = 8000.0;
            des.damper.impact_mass_kg = 0.1;
            des.damper.gap_m = 0.02;
            des.damper.v0_m_s = v0;
            (des, c1, y0_frac)
        };
        let cases = [
            (Design::default(), 10.0, -0.61),
            (Design::default(), 80.0, 0.23),
            heavy(100.0, 0.5, 0.37),
            heavy(300.0, 2.0, -0.8),
        ];
        let mut g = Noise(2327);
        let mut failures = Vec::new();
        for (des, truth, y0_frac) in cases {
            let d = des.check().unwrap();
            let table = Table::build(&d, &grid(&d).unwrap(), STARTS, d.damper.duration_s, None).unwrap().unwrap();
            let half = 0.5 * d.damper.gap_m;
            let ((tx, x), (t, a)) = rk4_record(&d, truth, y0_frac * half, &mut g);
            // Acceleration at 10 kHz, 2 % noise of K/M·max|x|, offset and drift alike.
            let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs())) * d.damper.stiffness_n_m / d.damper.main_mass_kg;
            let y: Vec<f64> = t
                .iter()
                .zip(&a)
                .map(|(&ti, &ai)| ai + 0.02 * peak * g.normal() + 0.07 * peak + 0.02 * peak * ti)
                .collect();
            let sa = Series::new(t, y, Quantity::Acceleration).unwrap();
            // Displacement at 2 kHz, 1 % noise.
            let y = measured(&tx, &x, 0.01, &mut g);
            let sx = Series::new(tx, y, Quantity::Displacement).unwrap();
            for (kind, s) in [("x", sx), ("a", sa)] {
                let f = compare(&d, &table, &[observe(&s, &d).unwrap()]).unwrap();
                let [lo, hi] = f.c1_n_s_m_ci;
                eprintln!("c1 {truth} {kind}: {} [{lo:.4}, {hi:.4}] ×{:.2} {:?}", f.c1_n_s_m, hi / lo, f.note);
                if !(lo <= truth && truth <= hi && hi / lo <= 3.0) {
                    failures.push(format!("c1 {truth} {kind}: [{lo}, {hi}]"));
                }
            }
        }
        assert!(failures.is_empty(), "{failures:?}");
    }

    /// The conditioning on the ball's being hit keeps the interval honest where it matters:
    /// the heavy design (M 2 kg, K 8000 N/m, m 100 g, d 2 cm, c1 100 N·s/m, struck at
    /// 0.5 m/s), 40 records from starts drawn uniformly over the clearance — about a fifth of
    /// them never hit — with 1 % noise, an offset, a drift and uneven 2 kHz sampling. The truth
    /// falls inside at least 35 times (for a correct 95 % interval P(count ≤ 34) = 1.4 %; 95
    /// of 100 measured, and 93 of 100 at c1 40), and every interval wider than a factor 3
    /// carries the note that says so (the records the ball was hardly hit in).
    #[test]
    fn the_heavy_design_s_intervals_cover_and_the_wide_ones_say_so() {
        let d = heavy().check().unwrap();
        let truth = 100.0;
        let table = Table::build(&d, &grid(&d).unwrap(), STARTS, d.damper.duration_s, None).unwrap().unwrap();
        let mut g = Noise(77);
        let (mut covered, mut narrow) = (0, 0);
        let n = 40;
        for _ in 0..n {
            let (y0, fit) = fit_one_record(&d, &table, truth, &mut g);
            let [lo, hi] = fit.c1_n_s_m_ci;
            if lo <= truth && truth <= hi {
                covered += 1;
            }
            if hi / lo <= 3.0 {
                narrow += 1;
            } else {
                assert!(fit.note.is_some(), "y0 {y0}: [{lo}, {hi}] without a note");
            }
        }
        eprintln!("covered {covered}/{n}, at most a factor 3 wide {narrow}");
        assert!(covered >= 35, "covered {covered} of {n}");
    }

    /// The null distribution's noise term is the record's own: over 300 draws of white noise
    /// on one clean record of thud's (the default design, c1 40 N·s/m, the ball hit), the
    /// statistic's standard deviation predicted from each record's window residuals
    /// (`statistic_noise` of `observe`'s `envelope_sd_m`, the median over the draws) is at
    /// least 0.8 times the spread the draws show, and at most 1.5 times where the noise
    /// dominates the windows' residual (3 % of the peak), for a displacement at 2 kHz with
    /// noise of 0.3 % and 3 % of its peak and for an acceleration at 10 kHz with noise of 1 %
    /// and 3 % of its peak (an impact's spike; there the noise is about as large as the
    /// structure's own acceleration). It grows with the noise, and a noise-free record still
    /// gets a noise term above 0 (what the window's sine does not follow: at low noise the
    /// prediction is above the noise's own spread, by design).
    #[test]
    fn the_statistic_s_noise_is_the_record_s_own() {
        let d = Design::default().check().unwrap();
        let mut p = d.damper;
        p.c1_n_s_m = 40.0;
        p.ball_position_m = 0.3 * 0.5 * p.gap_m;
        let n = (p.duration_s * 50_000.0) as usize;
        let run = damper::simulate(&p, d.solver, &RunOptions { history_samples: n, cancel: None }).unwrap();
        assert!(!run.impacts.is_empty());
        let (t, x): (Vec<f64>, Vec<f64>) = run.history.iter().map(|h| (h.t_s, h.x_m)).unzip();
        let h = t[1] - t[0];
        let xs: (Vec<f64>, Vec<f64>) = (0..t.len()).step_by(25).map(|i| (t[i], x[i])).unzip();
        let acc: (Vec<f64>, Vec<f64>) =
            (5..t.len() - 1).step_by(5).map(|i| (t[i] - t[5], (x[i + 1] - 2.0 * x[i] + x[i - 1]) / (h * h))).unzip();
        let periods = 6;
        let mut g = Noise(31);
        let mut predicted_at = Vec::new();
        for (q, (tt, clean), levels) in
            [(Quantity::Displacement, &xs, [0.0, 0.003, 0.03]), (Quantity::Acceleration, &acc, [0.0, 0.01, 0.03])]
        {
            let peak = clean.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let mut last = 0.0;
            for level in levels {
                let draws: u32 = if level == 0.0 { 1 } else { 300 };
                let (mut stats, mut predicted) = (Vec::new(), Vec::new());
                for _ in 0..draws {
                    let y: Vec<f64> = clean.iter().map(|c| c + level * peak * g.normal()).collect();
                    let o = observe(&Series::new(tt.clone(), y, q).unwrap(), &d).unwrap();
                    stats.push(statistic(&o.envelope_m, periods));
                    predicted.push(statistic_noise(&o.envelope_m, periods, &o.envelope_sd_m));
                }
                let pred = median(&predicted);
                assert!(pred > last, "{q:?} {level}: {pred} after {last}");
                last = pred;
                if level == 0.0 {
                    continue;
                }
                let mean = stats.iter().sum::<f64>() / f64::from(draws);
                let sd = (stats.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / f64::from(draws - 1)).sqrt();
                eprintln!("{q:?} noise {level}: predicted {pred:.5}, drawn {sd:.5}, ratio {:.2}", pred / sd);
                predicted_at.push((q, level, pred / sd));
            }
        }
        // Never below the spread the noise makes; where the noise dominates the window's
        // residual (the higher level of each), close to it.
        for (q, level, ratio) in predicted_at {
            assert!(ratio >= 0.8, "{q:?} {level}: predicted/drawn {ratio}");
            if level >= 0.03 {
                assert!(ratio <= 1.5, "{q:?} {level}: predicted/drawn {ratio}");
            }
        }
    }
}
