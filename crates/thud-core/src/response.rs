//! The forced response of a design (docs/model.md §6.2–6.4): its steady state under the
//! harmonic force with the level of its rattle ([`Steady`], with `Leq`), and the frequency
//! response with and without the damper ([`response`]), and the same from N ball offsets
//! ([`response_ensemble`]: p10/median/p90 of the steady figures per frequency).
//!
//! `Leq` over a window `[a, b]` is the energy-average level of the sound at the observer:
//! `Leq = 10·log10( ∫_a^b p(t)² dt / ((b − a)·p_ref²) )`, `p(t) = Σ_i p_i(t − t_i)`, where
//! `p_i` is the pulse (§3–4) of impact `i` at its incoming speed and `t_i` its onset. Every
//! impact of the run counts, also one before the window whose pulse reaches into it; pulses
//! that overlap add as pressures before squaring.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::damper::{self, RunOptions, Start};
pub use crate::design::{leq_db, steady, Steady};
use crate::design::{run_steady, Design, ValidDesign};
use crate::ensemble::Percentiles;
use crate::error::{check_positive, ThudError};
use crate::limits::{self, Estimate, Refusal, Remedy};
use crate::orbit::{self, PeriodicOrbit};
use crate::verdict::{Source, Verdict};

/// How the points of a frequency response start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Every frequency from the design's own start (at rest unless the design says otherwise).
    FromRest,
    /// Frequencies rising, each from the previous one's final state.
    Up,
    /// Frequencies falling, each from the previous one's final state (after the rising sweep).
    Down,
}

impl Direction {
    pub fn name(self) -> &'static str {
        match self {
            Direction::FromRest => "from rest",
            Direction::Up => "up",
            Direction::Down => "down",
        }
    }
}

/// One frequency of a response: the steady state there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ResponsePoint {
    pub freq_hz: f64,
    #[serde(flatten)]
    pub steady: Steady,
    /// Where the run ended (s): its duration, or later if it settled on.
    pub final_time_s: f64,
}

/// One sweep over the frequencies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResponseSweep {
    pub direction: Direction,
    pub points: Vec<ResponsePoint>,
}

/// The frequency response of a design under its force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Response {
    /// Force amplitude F0 (N).
    pub force_n: f64,
    /// One sweep from rest, or a rising and a falling sweep with continuation.
    pub sweeps: Vec<ResponseSweep>,
}

/// How a response is run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ResponseOptions {
    /// Each frequency from the previous one's final state, up then down (else each from rest).
    pub continuation: bool,
    /// Run each frequency on until its steady state settles (see [`damper::SETTLE_PERIODS_MAX`]).
    pub settle: bool,
}

impl Default for ResponseOptions {
    fn default() -> Self {
        Self { continuation: false, settle: true }
    }
}

/// Refuses a frequency response of `d` over `freqs_hz` (twice with `continuation`) with
/// `runs` runs a frequency whose work is over a cap ([`limits::response_work`]): the forcing
/// periods summed over the runs (blaming the runs when one run alone is inside the cap, else
/// the frequencies), the Newmark steps, and the main-mass cycles of one run at the highest
/// frequency.
pub fn check_response(d: &ValidDesign, freqs_hz: &[f64], continuation: bool, runs: usize) -> Result<(), Refusal> {
    let [one, one_steps] = limits::response_work(d, freqs_hz, continuation);
    let n = runs as f64;
    let (periods, steps) =
        (Estimate { value: n * one.value, ..one }, Estimate { value: n * one_steps.value, ..one_steps });
    if runs > 1 && !one.exceeded() {
        let max = (one.cap.max / one.value).floor();
        limits::over(periods, limits::RUNS_PARAM, Remedy::FewerRunsPerFrequency { max }, "")?;
    }
    limits::over(periods, limits::FREQS_PARAM, Remedy::FewerFrequencies, "")?;
    if let damper::Solver::Newmark { .. } = d.solver {
        limits::over(steps, "dt", Remedy::EventSolverOrLargerDt, "")?;
    }
    let f_max = freqs_hz.iter().copied().fold(0.0, f64::max);
    let cycles = limits::design_run(&at_frequency(d, f_max, true), 0)[1];
    limits::over(cycles, limits::FREQS_PARAM, Remedy::LowerFrequencies, "")
}

/// The main mass's damped natural frequency (Hz) of `d`: [`crate::damper::DamperParams::natural_frequency_hz`]
/// (Eq 25); 0 without a spring or when overdamped. The one definition the
/// explorer (a force switched on starts here) and the default response band use.
pub fn natural_frequency_hz(d: &Design) -> f64 {
    d.damper.natural_frequency_hz()
}

/// The band a response of `d` spans by default (Hz): 0.6 to 1.6 times its natural frequency
/// (the resonance and both flanks), or 1 to 10 Hz without one (no spring, or overdamped).
pub fn default_band_hz(d: &Design) -> (f64, f64) {
    let f = natural_frequency_hz(d);
    if f > 0.0 {
        (0.6 * f, 1.6 * f)
    } else {
        (1.0, 10.0)
    }
}

/// Points of a response over its default band ([`default_freqs_hz`]): what `thud response`,
/// `thud export … response`, Python's `thud.response()` and the explorer's export run when no
/// frequencies are given.
pub const DEFAULT_POINTS: usize = 101;

/// The frequencies a response of `d` runs by default (Hz): [`DEFAULT_POINTS`] evenly spaced
/// over [`default_band_hz`], 0.6 to 1.6 times the damped natural frequency (Eq 25). The one
/// default every front end uses; it depends on M, K and C only, so a design built at any
/// frequency gives the same band.
pub fn default_freqs_hz(d: &Design) -> Vec<f64> {
    let (from, to) = default_band_hz(d);
    crate::design::linspace(from, to, DEFAULT_POINTS)
}

/// The design `base` forced at `freq_hz`, run for at least two windows (its duration if longer).
pub fn at_frequency(base: &Design, freq_hz: f64, settle: bool) -> Design {
    let mut d = base.clone();
    let p = &mut d.damper;
    p.freq_hz = freq_hz;
    p.settle = settle;
    p.duration_s = p.duration_s.max(2.0 * f64::from(p.steady_periods) / freq_hz);
    d
}

/// One frequency from `start`: the point and the state it ended in. A settling point of the
/// event solver is first looked for as the periodic orbit the motion from `start` settles to
/// ([`on_orbit`]); only where there is none (chaotic, quasi-periodic, a longer period, a
/// ball resting on a wall, more impacts than the search allows) is the motion simulated on,
/// from where the search left it, until its windows settle.
fn point(d: &Design, start: &Start, want_end: bool) -> Result<(ResponsePoint, Option<Start>), ThudError> {
    if !(d.damper.settle && d.solver == damper::Solver::Event) {
        return simulated(d, start, 0.0, want_end);
    }
    if let Some(f) = damper::floating(&d.damper, start) {
        if let Some(on) = afloat(d, &f, 0.0, want_end)? {
            return Ok(on);
        }
    }
    let state = [start.x, start.v, start.y, start.w];
    let (found, reached) = orbit::settle_from(&d.damper, state, start.phase, limits::RESPONSE_SEARCH_PERIODS, None);
    match found {
        Ok(o) => {
            // The motion is on the orbit (to the search's tolerance) where the search left it.
            let offset_s = reached.map_or(o.periods_simulated.ceil() / d.damper.freq_hz, |r| r.time_s);
            if let Some(on) = on_orbit(d, &o, offset_s, want_end)? {
                return Ok(on);
            }
        }
        Err(ThudError::Cancelled) => return Err(ThudError::Cancelled),
        Err(_) => {}
    }
    match reached {
        Some(r) => {
            let [x, v, y, w] = r.state;
            let from = Start { x, v, y, w, phase: 0.0 };
            // A ball the search's motion never met may be proved never to be met from here on.
            if let Some(f) = damper::floating(&d.damper, &from) {
                if let Some(on) = afloat(d, &f, r.time_s, want_end)? {
                    return Ok(on);
                }
            }
            simulated(d, &from, r.time_s, want_end)
        }
        None => simulated(d, start, 0.0, want_end),
    }
}

/// The point of `d` on its stable periodic orbit `o` (docs/model.md §6.4): the steady window is
/// read off a run that starts on the orbit (its state at its section, in a flight), so its figures
/// are the orbit's own, free of any transient; the window is at least the design's N periods,
/// rounded up to whole orbits, and is placed `offset_s` (s) into the motion, where the orbit
/// search left it on the orbit. The verdict is the orbit's, found exactly. None if the orbit
/// has no impacts or the run on it does not bear it out (a work cap cut it).
fn on_orbit(
    d: &Design,
    o: &PeriodicOrbit,
    offset_s: f64,
    want_end: bool,
) -> Result<Option<(ResponsePoint, Option<Start>)>, ThudError> {
    // A floating ball (no impacts) is no attractor: its speed is neutral, and a ball that
    // drifts meets a wall (the motion is then another's). Those points are simulated.
    let (Some((phase, [x, v, y, w])), true) = (o.section, o.impacts_per_orbit > 0) else { return Ok(None) };
    let n = o.periods.max(1);
    let start = Start { x, v, y, w, phase };
    let Some((mut s, final_time_s, end)) = run_on(d, d.damper.steady_periods.div_ceil(n) * n, &start, want_end)? else {
        return Ok(None);
    };
    let m = &mut s.motion;
    m.periodic = true;
    m.settled = true;
    m.verdict = Verdict::Periodic {
        impacts: o.impacts_per_orbit,
        periods: o.periods,
        symmetric: o.symmetric,
        source: Source::Exact,
    };
    // The run starts at the section, a fraction of a period after the phase 0 the search
    // stopped at.
    let offset_s = offset_s + phase / (std::f64::consts::TAU * d.damper.freq_hz);
    Ok(Some((placed(d, s, final_time_s, offset_s), end)))
}

/// The point of `d` on the floating orbit `f` its motion tends to, `offset_s` (s) into the
/// motion (docs/model.md §6.4): the ball is proved never to be met ([`damper::floating`]), so
/// the motion is the structure's own under the force and tends to its steady solution with the
/// ball at rest. The window is read off a run that starts on that limit and is placed where
/// the motion's free part has fallen to 1e-3 of the steady amplitude (rounded up to whole
/// periods); the verdict, no impact in one period, is exact. None if the run does not bear it
/// out.
fn afloat(
    d: &Design,
    f: &damper::Floating,
    offset_s: f64,
    want_end: bool,
) -> Result<Option<(ResponsePoint, Option<Start>)>, ThudError> {
    let Some((mut s, final_time_s, end)) = run_on(d, d.damper.steady_periods, &f.on, want_end)? else {
        return Ok(None);
    };
    let m = &mut s.motion;
    let Verdict::Periodic { impacts: 0, periods: 1, symmetric, .. } = m.verdict else { return Ok(None) };
    if m.impacts > 0 {
        return Ok(None);
    }
    m.periodic = true;
    m.settled = true;
    m.verdict = Verdict::Periodic { impacts: 0, periods: 1, symmetric, source: Source::Exact };
    let period_s = 1.0 / d.damper.freq_hz;
    let settled_s = (f.settled_s / period_s).ceil() * period_s;
    Ok(Some((placed(d, s, final_time_s, offset_s + settled_s), end)))
}

/// The steady state of `d` over `periods` forcing periods of a run from `start` on a limit of
/// its motion (two windows long, not settled on): the steady state, the run's final time (s)
/// and, with `want_end`, its final state. None where the run holds no window or a work cap
/// cut it.
fn run_on(
    d: &Design,
    periods: u32,
    start: &Start,
    want_end: bool,
) -> Result<Option<(Steady, f64, Option<Start>)>, ThudError> {
    let mut on = d.clone();
    let p = &mut on.damper;
    p.steady_periods = periods;
    p.settle = false;
    // 2N·T as 2N·(1/f): the product as it was always taken, bit for bit.
    let period_s = 1.0 / p.freq_hz;
    p.duration_s = 2.0 * f64::from(periods) * period_s;
    let (run, end) = damper::run_from(&on.damper, on.solver, &RunOptions::default(), start, want_end)?;
    Ok(run_steady(&run, &on)?.filter(|s| !s.truncated).map(|s| (s, run.final_time_s, end)))
}

/// The point of `d` with steady state `s` of a run that ended at `final_time_s` (s), its times
/// moved `offset_s` (s) on: counted from the start of the point's motion, not of its last run.
fn placed(d: &Design, mut s: Steady, final_time_s: f64, offset_s: f64) -> ResponsePoint {
    s.motion.window_start_s += offset_s;
    s.motion.window_end_s += offset_s;
    ResponsePoint { freq_hz: d.damper.freq_hz, steady: s, final_time_s: final_time_s + offset_s }
}

/// One frequency from `start`, `offset_s` (s) into the motion, simulated until its windows
/// settle (or its duration, without settling): the point (its times counted from the motion's
/// start) and the state it ended in.
fn simulated(
    d: &Design,
    start: &Start,
    offset_s: f64,
    want_end: bool,
) -> Result<(ResponsePoint, Option<Start>), ThudError> {
    let (run, end) = damper::run_from(&d.damper, d.solver, &RunOptions::default(), start, want_end)?;
    let s = run_steady(&run, d)?.ok_or_else(|| ThudError::invalid("force", "a response needs a force > 0"))?;
    Ok((placed(d, s, run.final_time_s, offset_s), end))
}

/// The frequency response of `base` (which must have a force) over `freqs_hz`: per frequency
/// the steady state with the damper, beside the closed-form steady amplitude without it. From
/// rest the frequencies run in parallel on rayon's pool; with continuation a rising sweep (each
/// from the previous final state) and then a falling one. `on_point` is called as each point
/// finishes; `cancel` stops between points (the response then holds what was done).
pub fn response(
    base: &ValidDesign,
    freqs_hz: &[f64],
    opts: &ResponseOptions,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn() + Sync),
) -> Result<Response, ThudError> {
    response_checked(base, freqs_hz, opts, cancel, on_point)
}

/// [`response`] of a checked design, or of one derived from it by a change that keeps it
/// valid and resolved (a response ensemble's ball offset inside the clearance). The design at
/// each frequency differs from `base` in its frequency (each checked > 0 here), its settling
/// and a duration of at least two windows: none of them bears on K_HZ or a cross-check, and
/// the work caps ([`check_response`]) bound them, so they are not checked again.
fn response_checked(
    base: &Design,
    freqs_hz: &[f64],
    opts: &ResponseOptions,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn() + Sync),
) -> Result<Response, ThudError> {
    for &f in freqs_hz {
        check_positive("freqs", f, "Hz")?;
    }
    if freqs_hz.is_empty() {
        return Ok(Response { force_n: base.damper.force_n, sweeps: vec![] });
    }
    check_positive("force", base.damper.force_n, "N")?;
    let cancelled = || cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let design_at = |f: f64| at_frequency(base, f, opts.settle);
    let start0 = Start::of(&base.damper);
    let sweeps = if opts.continuation {
        let mut up: Vec<f64> = freqs_hz.to_vec();
        up.sort_by(f64::total_cmp);
        let mut start = start0;
        let mut sweeps = Vec::new();
        for (direction, order) in [(Direction::Up, up.clone()), (Direction::Down, up.iter().rev().copied().collect())] {
            let mut points = Vec::new();
            for f in order {
                if cancelled() {
                    break;
                }
                let (pt, end) = point(&design_at(f), &start, true)?;
                start = end.unwrap_or(start);
                points.push(pt);
                on_point();
            }
            sweeps.push(ResponseSweep { direction, points });
        }
        sweeps
    } else {
        let results: Vec<Option<Result<ResponsePoint, ThudError>>> = freqs_hz
            .par_iter()
            .map(|&f| {
                if cancelled() {
                    return None;
                }
                let r = point(&design_at(f), &start0, false).map(|(p, _)| p);
                on_point();
                Some(r)
            })
            .collect();
        let points = results.into_iter().flatten().collect::<Result<Vec<_>, _>>()?;
        vec![ResponseSweep { direction: Direction::FromRest, points }]
    };
    Ok(Response { force_n: base.damper.force_n, sweeps })
}

/// One run of a response ensemble at one frequency: the ball's initial offset and the steady
/// state that run reached there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ResponseMember {
    /// Initial offset y0 of the ball from the enclosure's centre (m).
    pub ball_position_m: f64,
    #[serde(flatten)]
    pub steady: Steady,
    /// Where the run ended (s).
    pub final_time_s: f64,
}

/// The spread of the steady figures of a response ensemble at one frequency: p10, median and
/// p90 by nearest rank over the runs ([`crate::ensemble`]'s percentiles).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadySpread {
    /// Largest |x| in the window (m).
    pub amplitude_m: Percentiles,
    /// The cut of the damper (dB), of the same runs as the amplitude's percentiles (so that
    /// amplitude, amplitude without the ball and cut agree): the median is the cut of the run
    /// of median amplitude, p10 and p90 those of the amplitude's p90 and p10 runs. (The cut
    /// falls as the amplitude grows; with an even N its own nearest-rank median would be
    /// another run's.)
    pub reduction_db: Percentiles,
    pub impacts_per_period: Percentiles,
    /// Energy-average level at the observer (dB re 20 µPa).
    pub leq_db: Percentiles,
}

/// One frequency of a response ensemble.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnsemblePoint {
    pub freq_hz: f64,
    /// The main mass without the ball (m; the same for every run); None where unbounded.
    pub amplitude_linear_m: Option<f64>,
    pub spread: SteadySpread,
    /// Fractions of the runs whose steady state is periodic, and settled.
    pub periodic_fraction: f64,
    pub settled_fraction: f64,
    /// Whether a work cap stopped any run before its window's end.
    pub truncated: bool,
    /// Every run, in order of k (of the initial offset).
    pub ensemble: Vec<ResponseMember>,
}

impl EnsemblePoint {
    /// The point of `runs` (one per offset `y0`, all at the same frequency).
    fn of(offsets: &[f64], runs: &[&ResponsePoint]) -> Self {
        let pct = |f: &dyn Fn(&Steady) -> Option<f64>| Percentiles::of(runs.iter().map(|p| f(&p.steady)));
        let fraction = |f: &dyn Fn(&Steady) -> bool| {
            runs.iter().filter(|p| f(&p.steady)).count() as f64 / runs.len().max(1) as f64
        };
        let amplitude_m = pct(&|s| Some(s.amplitude_m));
        // The cut of the run with amplitude `a` (the run a percentile of the amplitude is):
        // cut falls as the amplitude grows, so its p10 is the amplitude's p90 run's.
        let cut_at = |a: Option<f64>| {
            let a = a?;
            runs.iter().find(|p| p.steady.amplitude_m.total_cmp(&a).is_eq())?.steady.reduction_db
        };
        EnsemblePoint {
            freq_hz: runs.first().map_or(0.0, |p| p.freq_hz),
            amplitude_linear_m: runs.first().and_then(|p| p.steady.amplitude_linear_m),
            spread: SteadySpread {
                amplitude_m,
                reduction_db: Percentiles {
                    p10: cut_at(amplitude_m.p90),
                    median: cut_at(amplitude_m.median),
                    p90: cut_at(amplitude_m.p10),
                },
                impacts_per_period: pct(&|s| Some(s.impacts_per_period)),
                leq_db: pct(&|s| s.leq_db),
            },
            periodic_fraction: fraction(&|s| s.periodic),
            settled_fraction: fraction(&|s| s.settled),
            truncated: runs.iter().any(|p| p.steady.truncated),
            ensemble: offsets
                .iter()
                .zip(runs)
                .map(|(&y0, p)| ResponseMember { ball_position_m: y0, steady: p.steady, final_time_s: p.final_time_s })
                .collect(),
        }
    }

    /// The run whose amplitude is the median (nearest rank: an actual run), as a point of a
    /// plain response: what a plot of the medians draws.
    #[must_use]
    pub fn median_run(&self) -> Option<ResponsePoint> {
        let median = self.spread.amplitude_m.median?;
        let m = self.ensemble.iter().find(|m| m.steady.amplitude_m.total_cmp(&median).is_eq())?;
        Some(ResponsePoint { freq_hz: self.freq_hz, steady: m.steady, final_time_s: m.final_time_s })
    }
}

/// One sweep of a response ensemble over the frequencies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnsembleSweep {
    pub direction: Direction,
    pub points: Vec<EnsemblePoint>,
}

/// The frequency response of a design from N ball offsets (`response --ensemble N`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResponseEnsemble {
    /// Force amplitude F0 (N).
    pub force_n: f64,
    /// Runs per frequency N.
    pub runs: usize,
    pub sweeps: Vec<EnsembleSweep>,
}

impl ResponseEnsemble {
    /// The response of the median runs ([`EnsemblePoint::median_run`]): what the text plot and
    /// the SVG draw for an ensemble.
    #[must_use]
    pub fn medians(&self) -> Response {
        let sweeps = self
            .sweeps
            .iter()
            .map(|s| ResponseSweep {
                direction: s.direction,
                points: s.points.iter().filter_map(EnsemblePoint::median_run).collect(),
            })
            .collect();
        Response { force_n: self.force_n, sweeps }
    }
}

/// The frequency response of `base` from `n` ball offsets ([`crate::ensemble::ball_positions`],
/// the only difference between the runs): run `k` is exactly [`response`] of `base` with
/// [`DamperParams::ball_position_m`](crate::damper::DamperParams::ball_position_m) = y0_k, and
/// each frequency reports the p10/median/p90 of the steady figures over the runs. Runs and
/// frequencies are spread over rayon's pool; `on_point` is called as each run's point
/// finishes; `cancel` stops between points (every sweep then holds the points all runs did).
pub fn response_ensemble(
    base: &ValidDesign,
    freqs_hz: &[f64],
    n: usize,
    opts: &ResponseOptions,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn() + Sync),
) -> Result<ResponseEnsemble, ThudError> {
    if n == 0 {
        return Err(ThudError::invalid("ensemble", "0 runs; an ensemble needs at least 1"));
    }
    let offsets = crate::ensemble::ball_positions(base.damper.gap_m, n);
    let runs: Vec<Response> = offsets
        .par_iter()
        .map(|&y0| {
            let mut d = base.design().clone();
            d.damper.ball_position_m = y0;
            response_checked(&d, freqs_hz, opts, cancel, on_point)
        })
        .collect::<Result<_, _>>()?;
    let n_sweeps = runs.iter().map(|r| r.sweeps.len()).min().unwrap_or(0);
    let sweeps = (0..n_sweeps)
        .map(|s| {
            // A cancelled run may lack points: keep those every run has, at the same frequency.
            let at = |i: usize| -> Option<Vec<&ResponsePoint>> {
                let first = runs[0].sweeps[s].points.get(i)?;
                runs.iter().map(|r| r.sweeps[s].points.get(i).filter(|p| p.freq_hz == first.freq_hz)).collect()
            };
            EnsembleSweep {
                direction: runs[0].sweeps[s].direction,
                points: (0..).map_while(at).map(|at| EnsemblePoint::of(&offsets, &at)).collect(),
            }
        })
        .collect();
    Ok(ResponseEnsemble { force_n: base.damper.force_n, runs: n, sweeps })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default design under 1 N at `freqs_hz` from its own start, the ball at `y0` (m).
    fn settled_response(freqs_hz: &[f64], y0: f64) -> Response {
        let mut d = Design::default();
        d.damper.force_n = 1.0;
        d.damper.freq_hz = freqs_hz[0];
        d.damper.ball_position_m = y0;
        let d = d.check().unwrap();
        response(&d, freqs_hz, &ResponseOptions::default(), None, &|| {}).unwrap()
    }

    /// A settling point on a periodic orbit with impacts is the orbit found by shooting: its
    /// verdict says so and its amplitude is the one `thud orbit` reports from its own run of
    /// the orbit. At 5.3 Hz the search's speculative Newton finds a floating orbit the motion
    /// does not keep: that point is the impacting 2/1 one. At 6.5 Hz the strike (v0) throws the
    /// ball against a wall and it drifts on: a floating ball that is no attractor (neutral in
    /// its speed), so the point is simulated, not shot.
    #[test]
    fn settling_points_are_the_orbits_found_by_shooting() {
        let freqs = [4.7, 5.2, 5.3, 6.5];
        let r = settled_response(&freqs, 0.0);
        let mut shot = vec![];
        for (p, &f) in r.sweeps[0].points.iter().zip(&freqs) {
            let Verdict::Periodic { impacts, periods, source: Source::Exact, .. } = p.steady.verdict else {
                continue;
            };
            shot.push(f);
            assert!(impacts > 0 && p.steady.periodic && p.steady.settled && !p.steady.truncated, "{f} Hz");
            let mut at = Design::default();
            at.damper.force_n = 1.0;
            at.damper.freq_hz = f;
            let o = orbit::find_damper(&at.damper, &orbit::Request::default(), None).unwrap();
            assert_eq!((o.impacts_per_orbit, o.periods), (impacts, periods), "{f} Hz");
            let rel = (p.steady.amplitude_m - o.amplitude_m).abs() / o.amplitude_m;
            assert!(rel <= 1e-9, "{f} Hz: {} vs the orbit's {} ({rel:e})", p.steady.amplitude_m, o.amplitude_m);
            let n = f64::from(p.steady.periods);
            assert!((p.steady.window_end_s - p.steady.window_start_s - n / f).abs() < 1e-9, "{f} Hz: N whole periods");
            assert!((p.steady.impacts_per_period * f64::from(periods) - f64::from(impacts)).abs() < 1e-9, "{f} Hz");
        }
        assert_eq!(shot, [4.7, 5.2, 5.3], "the impacting orbits are shot, the drifting ball is not");
        assert_eq!(r.sweeps[0].points[2].steady.verdict.label(), "2/1 sym", "5.3 Hz");
    }

    /// From rest (no strike) the ball of the default design under 1 N is never met below and
    /// above the impacting band: proved so ([`damper::floating`]), the point is the floating
    /// orbit, exact, its amplitude the closed form without the ball (to 1e-9), its window
    /// whole periods; and the settled simulation of the same design, an independent path,
    /// sees no impact and settles to that amplitude within its 1e-3.
    #[test]
    fn a_ball_never_met_is_the_steady_state_without_it() {
        let freqs = [3.5, 6.5];
        let mut d = Design::default();
        d.damper.force_n = 1.0;
        d.damper.v0_m_s = 0.0;
        d.damper.freq_hz = freqs[0];
        let d = d.check().unwrap();
        let r = response(&d, &freqs, &ResponseOptions::default(), None, &|| {}).unwrap();
        for (p, &f) in r.sweeps[0].points.iter().zip(&freqs) {
            let s = &p.steady;
            assert_eq!(s.verdict, Verdict::Periodic { impacts: 0, periods: 1, symmetric: true, source: Source::Exact });
            assert!(s.periodic && s.settled && !s.truncated && s.impacts_per_period == 0.0 && s.leq_db.is_none());
            let alone = s.amplitude_linear_m.unwrap();
            assert!((s.amplitude_m - alone).abs() <= 1e-9 * alone, "{f} Hz: {} vs {alone}", s.amplitude_m);
            let n = f64::from(s.periods);
            assert!((s.window_end_s - s.window_start_s - n / f).abs() < 1e-9, "{f} Hz: N whole periods");
            let mut at = at_frequency(&d, f, true);
            at.damper.duration_s = 10.0;
            let run = damper::simulate(&at.damper, at.solver, &RunOptions::default()).unwrap();
            let sim = run_steady(&run, &at).unwrap().unwrap();
            assert!(run.impacts.is_empty() && sim.settled, "{f} Hz: the simulation meets the ball or never settles");
            assert!(
                (sim.amplitude_m - alone).abs() <= 2e-3 * alone,
                "{f} Hz: simulated {} vs {alone}",
                sim.amplitude_m
            );
        }
    }

    /// The figures of a point found by shooting do not move with the transient that led to it:
    /// a start 1 nm away (another transient, other round-off) gives the same amplitude to
    /// 1e-9 relative.
    #[test]
    fn shot_points_do_not_move_with_the_transient() {
        let freqs = [4.7, 5.2];
        let (a, b) = (settled_response(&freqs, 0.0), settled_response(&freqs, 1e-9));
        for (p, q) in a.sweeps[0].points.iter().zip(&b.sweeps[0].points) {
            assert!(matches!(p.steady.verdict, Verdict::Periodic { source: Source::Exact, .. }), "{}", p.freq_hz);
            assert_eq!(p.steady.verdict, q.steady.verdict);
            let rel = (p.steady.amplitude_m - q.steady.amplitude_m).abs() / p.steady.amplitude_m;
            assert!(rel <= 1e-9, "{} Hz: {rel:e}", p.freq_hz);
        }
    }

    #[test]
    fn the_default_band_spans_the_resonance_of_table_2() {
        // Table 2: √(K/M − (C/2M)²)/2π with K 500 N/m, M 0.5 kg, C 0.05 N·s/m.
        let d = Design::default();
        let f = (1000.0f64 - 0.0025).sqrt() / (2.0 * std::f64::consts::PI);
        assert!((natural_frequency_hz(&d) - f).abs() < 1e-12);
        let (lo, hi) = default_band_hz(&d);
        assert!((lo - 0.6 * f).abs() < 1e-12 && (hi - 1.6 * f).abs() < 1e-12);
        let mut free = d.clone();
        free.damper.stiffness_n_m = 0.0;
        assert_eq!(default_band_hz(&free), (1.0, 10.0), "no spring: no natural frequency");
        let freqs = default_freqs_hz(&d);
        assert_eq!(freqs.len(), DEFAULT_POINTS);
        assert!((freqs[0] - 0.6 * f).abs() < 1e-12 && (freqs[100] - 1.6 * f).abs() < 1e-12);
        assert!((freqs[50] - 1.1 * f).abs() < 1e-12, "evenly spaced");
    }

    /// An even ensemble's amplitude, amplitude without the ball and cut are one run's: the
    /// cut shown is 20·log10(alone/amp) of the amplitude shown, its p10 and p90 those of the
    /// amplitude's p90 and p10 runs. (Each quantity's own nearest-rank median would take the
    /// 2nd largest amplitude and the 2nd smallest cut of 4: two different runs.)
    #[test]
    fn an_even_ensemble_s_amplitude_and_cut_are_one_run_s() {
        let alone = 0.5;
        let point = |amp: f64| {
            let motion = crate::damper::SteadyMotion {
                periods: 10,
                window_start_s: 0.0,
                window_end_s: 1.0,
                amplitude_m: amp,
                amplitude_linear_m: Some(alone),
                reduction_db: Some(20.0 * (alone / amp).log10()),
                impacts: 20,
                impacts_per_period: 2.0,
                periodic: false,
                settled: true,
                truncated: false,
                previous_amplitude_m: None,
                verdict: crate::verdict::Verdict::Settled,
            };
            let steady = Steady { motion, leq_db: Some(90.0) };
            ResponsePoint { freq_hz: 5.0, steady, final_time_s: 2.0 }
        };
        let runs: Vec<ResponsePoint> = [0.04, 0.01, 0.03, 0.02].into_iter().map(point).collect();
        let refs: Vec<&ResponsePoint> = runs.iter().collect();
        let e = EnsemblePoint::of(&[-0.015, -0.005, 0.005, 0.015], &refs);
        let (amp, cut) = (e.spread.amplitude_m, e.spread.reduction_db);
        let db = |a: Option<f64>| a.map(|a| 20.0 * (alone / a).log10());
        assert_eq!(amp.median, Some(0.02), "rank 2 of 4");
        assert_eq!(cut.median, db(amp.median), "the median run's cut");
        assert_eq!((cut.p10, cut.p90), (db(amp.p90), db(amp.p10)));
        assert!(cut.p10 < cut.median && cut.median < cut.p90);
    }
}
