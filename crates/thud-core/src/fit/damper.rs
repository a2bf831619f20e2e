//! The damper's contact damping c1 from measured decays of the structure carrying it, struck
//! once, every other parameter of the design known (docs/model.md §11.2).
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
//! c1 of a grid (log-spaced between the c1 of restitution 0.99 and 0.05 at the strike speed
//! v0, [`grid`]) the N = 39 members give the statistic's spread over the start. The 95 %
//! interval is the Neyman construction: the c1 whose acceptance band holds the observed
//! statistic. One record is exchangeable with the 39 members at the true c1 when the ball's
//! start is spread like theirs, so it falls below all of them with probability 1/40 and above
//! all of them with 1/40: the band [min, max] of the members is a 95 % band (a conformal
//! prediction interval; Vovk, Gammerman & Shafer 2005), widened by twice the statistic's noise
//! from the measurement. Several records (repeated strikes) fit together: their mean
//! statistic against the 2.5 % and 97.5 % points of means of as many members drawn at random
//! (a fixed generator, so the answer is repeatable), which narrows the band as √n.
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
use crate::damper::{self, RunOptions};
use crate::design::{self, Design, ValidDesign};
use crate::error::ThudError;

/// Ensemble members (ball starts) per c1: with 39 the band [min, max] is a 95 % band.
pub const STARTS: usize = 39;
/// c1 values of the grid.
pub const GRID_POINTS: usize = 33;
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
}

/// A record turned into the main mass's displacement and its envelope.
#[derive(Debug, Clone, PartialEq)]
pub struct Observed {
    /// The displacement-equivalent signal (m) at the record's times from its start (s).
    pub t_s: Vec<f64>,
    pub x_m: Vec<f64>,
    /// The amplitude over each whole period from the start (m).
    pub envelope_m: Vec<f64>,
    /// The amplitude's noise standard deviation (m).
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
        Err(ThudError::invalid("k", "the structure has no free vibration (K = 0 or overdamped); a damper fit needs one"))
    }
}

/// The amplitude of `y` over [a, b): the least-squares `c + s·τ + p cos ωτ + q sin ωτ`
/// (τ from the window's middle), `√(p² + q²)`. `None` with fewer than 8 samples or a singular fit.
#[must_use]
pub fn window_amplitude_sloped(t: &[f64], y: &[f64], a: f64, b: f64, omega: f64) -> Option<f64> {
    let from = t.partition_point(|&ti| ti < a);
    let to = t.partition_point(|&ti| ti < b);
    if to < from + 8 {
        return None;
    }
    let mid = 0.5 * (a + b);
    let mut ata = nalgebra::Matrix4::zeros();
    let mut aty = nalgebra::Vector4::zeros();
    for i in from..to {
        let tau = t[i] - mid;
        let (s, c) = (omega * tau).sin_cos();
        let row = nalgebra::Vector4::new(1.0, tau, c, s);
        ata += row * row.transpose();
        aty += row * y[i];
    }
    let sol = ata.lu().solve(&aty)?;
    let amp = sol[2].hypot(sol[3]);
    amp.is_finite().then_some(amp)
}

/// The envelope of `x` at times `t` (from 0): the amplitude over each of `periods` periods of
/// length `period_s` ([`window_amplitude_sloped`]; 0 for a window too thin to fit).
#[must_use]
pub fn envelope(t: &[f64], x: &[f64], period_s: f64, periods: usize) -> Vec<f64> {
    let om = 2.0 * PI / period_s;
    (0..periods)
        .map(|j| {
            window_amplitude_sloped(t, x, j as f64 * period_s, (j + 1) as f64 * period_s, om).unwrap_or(0.0)
        })
        .collect()
}

/// The statistic of an envelope over its first `periods` periods: mean ln(A_j/A_0), j ≥ 1.
fn statistic(env: &[f64], periods: usize) -> f64 {
    let a0 = env[0].max(f64::MIN_POSITIVE);
    let n = periods.min(env.len());
    env[1..n].iter().map(|a| (a.max(f64::MIN_POSITIVE) / a0).ln()).sum::<f64>() / (n - 1) as f64
}

/// The statistic's noise standard deviation from the amplitudes' (delta method: A_0 enters
/// every term).
fn statistic_noise(env: &[f64], periods: usize, sd: f64) -> f64 {
    let n = periods.min(env.len());
    let k = (n - 1) as f64;
    let spread: f64 = env[1..n].iter().map(|a| (sd / a).powi(2)).sum::<f64>() / (k * k);
    (spread + (sd / env[0]).powi(2)).sqrt()
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
    let env = envelope(&t, &x, period, periods);
    // The amplitude's noise: the displacement's white noise over a window's samples.
    let noise = match s.quantity() {
        Quantity::Velocity => noise_sd(y) * period / (2.0 * PI) ,
        _ => noise_sd(&x),
    };
    let per_window = (s.len() as f64 / s.span_s() * period).max(8.0);
    let amplitude_noise_m = noise * (2.0 / per_window).sqrt();
    let usable = env.iter().take_while(|&&a| a >= 10.0 * amplitude_noise_m && a > 0.0).count();
    if usable < 3 {
        return Err(bad("too short: fewer than 3 periods stand above the noise; a fit needs at least 3"));
    }
    Ok(Observed { t_s: t, x_m: x, envelope_m: env, amplitude_noise_m, usable })
}

/// The c1 grid (N·s/m): `GRID_POINTS` log-spaced from the c1 of restitution 0.99 to that of
/// 0.05, for one contact of the design's ball at the strike speed |v0|.
pub fn grid(d: &ValidDesign) -> Result<Vec<f64>, ThudError> {
    let u0 = d.damper.v0_m_s.abs();
    if u0 <= 0.0 {
        return Err(ThudError::invalid("v0", "0 m/s; a damper fit needs the strike's speed (give --v0)"));
    }
    let lo = design::c1_for_restitution(d, u0, 0.99)?.max(1e-6);
    let hi = design::c1_for_restitution(d, u0, 0.05)?.min(crate::limits::C1.max);
    Ok(design::linspace(lo.ln(), hi.ln(), GRID_POINTS).into_iter().map(f64::exp).collect())
}

/// Every member's envelope and first impact speed for each c1 of a grid: the ensemble the
/// records are compared with. Build once, compare any records of the same span.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub c1_n_s_m: Vec<f64>,
    /// [c1][member] → envelope (m, one a period).
    pub envelopes: Vec<Vec<Vec<f64>>>,
    /// [c1][member] → the first impact's incoming speed (m/s; 0 without an impact).
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
                p.ball_velocity_m_s = 0.0;
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

/// A small fixed generator (SplitMix64) for the draws of several records' means: repeatable.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The acceptance band [low, high] of the mean statistic of `records` records at one c1, from
/// its members' statistics (ascending not required), widened by `noise` each side.
fn band(members: &[f64], records: usize, noise: f64) -> (f64, f64) {
    if records == 1 {
        let lo = members.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = members.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        return (lo - 2.0 * noise, hi + 2.0 * noise);
    }
    let mut g = SplitMix(0x5EED_0F_F17);
    let mut means: Vec<f64> = (0..DRAWS)
        .map(|_| (0..records).map(|_| members[g.below(members.len())]).sum::<f64>() / records as f64)
        .collect();
    means.sort_by(f64::total_cmp);
    let lo = means[(0.025 * DRAWS as f64) as usize];
    let hi = means[(0.975 * DRAWS as f64) as usize - 1];
    (lo - 2.0 * noise, hi + 2.0 * noise)
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

/// Where a piecewise-linear function of ln c1 through the grid's points `(ln c1_k, f_k)` meets
/// `target` between grid points k and k+1: ln c1 there.
fn cross(lc: &[f64], f: &[f64], k: usize, target: f64) -> f64 {
    let (a, b) = (f[k] - target, f[k + 1] - target);
    if a == b {
        return 0.5 * (lc[k] + lc[k + 1]);
    }
    lc[k] + (lc[k + 1] - lc[k]) * a / (a - b)
}

/// Compares `observed` records with `table`: the fitted c1, its interval and restitution.
pub fn compare(d: &ValidDesign, table: &Table, observed: &[Observed]) -> Result<DamperFit, ThudError> {
    let periods = observed.iter().map(|o| o.usable).min().unwrap_or(0).min(table.envelopes[0][0].len());
    if periods < 3 {
        return Err(bad("too short: fewer than 3 periods to compare"));
    }
    let n = observed.len();
    let stat = observed.iter().map(|o| statistic(&o.envelope_m, periods)).sum::<f64>() / n as f64;
    let noise = (observed
        .iter()
        .map(|o| statistic_noise(&o.envelope_m, periods, o.amplitude_noise_m).powi(2))
        .sum::<f64>()
        / (n * n) as f64)
        .sqrt();
    let lc: Vec<f64> = table.c1_n_s_m.iter().map(|c| c.ln()).collect();
    let members: Vec<Vec<f64>> =
        table.envelopes.iter().map(|ms| ms.iter().map(|e| statistic(e, periods)).collect()).collect();
    let bands: Vec<(f64, f64)> = members.iter().map(|m| band(m, n, noise)).collect();
    let medians: Vec<f64> = members.iter().map(|m| median(m)).collect();
    // The accepted grid points; the interval runs from just below the first to just above the
    // last, where the band's edge meets the statistic (interpolated in ln c1).
    let inside: Vec<bool> = bands.iter().map(|&(lo, hi)| lo <= stat && stat <= hi).collect();
    let g = lc.len();
    let (lo_ln, hi_ln, open) = match (inside.iter().position(|&b| b), inside.iter().rposition(|&b| b)) {
        (Some(a), Some(b)) => {
            let lo_ln = if a == 0 {
                lc[0]
            } else {
                let (lo_edge, hi_edge): (Vec<f64>, Vec<f64>) = bands.iter().copied().unzip();
                // The edge the statistic left through between a−1 and a.
                let edge = if stat > bands[a - 1].1 { &hi_edge } else { &lo_edge };
                cross(&lc, edge, a - 1, stat)
            };
            let hi_ln = if b == g - 1 {
                lc[g - 1]
            } else {
                let (lo_edge, hi_edge): (Vec<f64>, Vec<f64>) = bands.iter().copied().unzip();
                let edge = if stat > bands[b + 1].1 { &hi_edge } else { &lo_edge };
                cross(&lc, edge, b, stat)
            };
            (lo_ln, hi_ln, a == 0 || b == g - 1)
        }
        _ => {
            // No c1 of the grid explains the data: the nearest band's point, said so.
            let k = (0..g)
                .min_by(|&i, &j| {
                    let dist = |k: usize| (bands[k].0 - stat).max(stat - bands[k].1);
                    dist(i).total_cmp(&dist(j))
                })
                .unwrap_or(0);
            return Err(bad(format!(
                "no c1 explains the decay: its statistic {} lies outside every band (nearest c1 {} N·s/m); check the design flags (M, K, C, m, d, v0)",
                crate::units::sig(stat, 4),
                crate::units::sig(table.c1_n_s_m[k], 4)
            )));
        }
    };
    // The point estimate: where the median meets the statistic, inside the interval.
    let best_ln = (0..g - 1)
        .filter(|&k| (medians[k] - stat) * (medians[k + 1] - stat) <= 0.0)
        .map(|k| cross(&lc, &medians, k, stat))
        .filter(|l| *l >= lo_ln - 1e-12 && *l <= hi_ln + 1e-12)
        .min_by(|a, b| (a - 0.5 * (lo_ln + hi_ln)).abs().total_cmp(&(b - 0.5 * (lo_ln + hi_ln)).abs()))
        .unwrap_or(0.5 * (lo_ln + hi_ln));
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
    // The median member's envelope at the fitted c1 against the first record's, for the residual.
    let periods_all = table.envelopes[0][0].len();
    let model: Vec<f64> =
        (0..periods_all).map(|j| median(&table.envelopes[k_best].iter().map(|e| e[j]).collect::<Vec<_>>())).collect();
    let mut sq = 0.0;
    let mut count = 0usize;
    for o in observed {
        for j in 0..periods {
            sq += (o.envelope_m[j] - model[j]).powi(2);
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
        records: n,
        starts: table.envelopes[0].len(),
        grid_points: g,
        envelope_period_s: table.period_s,
        measured_envelope_m: observed[0].envelope_m.clone(),
        model_envelope_m: model,
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
    compare(d, &table, &observed).map(Some)
}

/// The design whose work a damper fit of records spanning `span_s` (s) costs: the design run
/// for that span ([`crate::limits::check_runs`] with [`GRID_POINTS`] cells of [`STARTS`] runs).
pub fn work_design(d: &ValidDesign, span_s: f64) -> Result<ValidDesign, ThudError> {
    let mut dd = d.design().clone();
    dd.damper.duration_s = span_s;
    dd.check().map_err(|e| e.renamed(super::DATA_PARAM))
}
