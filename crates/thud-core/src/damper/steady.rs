//! The steady state of a forced run (docs/model.md §6.2), and the one driver both solvers run
//! under.
//!
//! A forced run of duration `D` at forcing period `T` is judged over windows of `N` periods
//! (`L = N·T`, [`Windows`]): the last is `[D − L, D]`, and the two before it count too. Its
//! [`SteadyMotion`] is the last window's: the largest `|x|`, the impacts per period, whether `x`
//! repeats from period to period (within 1e-3 of the amplitude), and whether the run has
//! settled — the amplitudes of the last three windows agree within 1e-3 (relative), i.e. two
//! successive changes are that small (one alone can be a coincidence of a slowly decaying
//! beat). With `settle`, the run goes on past `D` one window at a time until it has settled, or
//! for at most [`SETTLE_PERIODS_MAX`] more periods (then `settled` is false); the steady state
//! is then the last window's.

use serde::{Deserialize, Serialize};

use super::event::{EventSim, Free, ForcedFlight};
use super::flight::Oscillator;
use super::forced::{Forced, Harmonic};
use super::newmark::NewmarkSim;
use super::record::{Recorder, WindowStats, Windows, PRE_WINDOWS};
use super::{DamperParams, ImpactEvent, Run, RunOptions, Solver};

/// The most forcing periods a settling run adds past its duration.
pub const SETTLE_PERIODS_MAX: u32 = 2000;

/// How much the amplitude of one window may differ from the one before for the run to count as
/// settled (relative).
const SETTLED_TOLERANCE: f64 = 1e-3;

/// The state a run starts from (m, m/s) and the phase of its force at `t = 0` (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Start {
    pub x: f64,
    pub v: f64,
    pub y: f64,
    pub w: f64,
    pub phase: f64,
}

impl Start {
    /// The design's own start: `x = 0`, `x' = v0`, `y = y0`, `y' = w0`, force in phase 0.
    pub fn of(p: &DamperParams) -> Self {
        Start { x: 0.0, v: p.v0_m_s, y: p.ball_position_m, w: p.ball_velocity_m_s, phase: 0.0 }
    }
}

/// The steady state of a forced run over its last window of `periods` forcing periods.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadyMotion {
    /// Forcing periods N in the window.
    pub periods: u32,
    /// The window (s).
    pub window_start_s: f64,
    pub window_end_s: f64,
    /// Largest |x| in the window (m).
    pub amplitude_m: f64,
    /// The same main mass without the ball, in its steady state:
    /// `F0/√((K − MΩ²)² + (CΩ)²)` (m); None where that is unbounded (C = 0 at resonance).
    pub amplitude_linear_m: Option<f64>,
    /// `20·log10(amplitude_linear/amplitude)` (dB): how much the damper cuts the amplitude.
    pub reduction_db: Option<f64>,
    /// Impacts whose onset lies in the window.
    pub impacts: usize,
    /// Those impacts per forcing period.
    pub impacts_per_period: f64,
    /// Whether x repeats from one forcing period to the next within 1e-3 of the amplitude.
    pub periodic: bool,
    /// Whether the amplitude of this window is within 1e-3 of the window before's.
    pub settled: bool,
    /// Whether a work cap (or cancellation) stopped the run before the window's end.
    pub truncated: bool,
    /// The amplitude of the window before (m), if the run holds it whole.
    pub previous_amplitude_m: Option<f64>,
}

/// The steady amplitude (m) of the design's main mass without the ball under its force:
/// `F0/√((K − MΩ²)² + (CΩ)²)`; None without a force or where it is unbounded.
pub fn linear_amplitude_m(p: &DamperParams) -> Option<f64> {
    if !p.forced() {
        return None;
    }
    let om = 2.0 * std::f64::consts::PI * p.freq_hz;
    let den = (p.stiffness_n_m - p.main_mass_kg * om * om).hypot(p.damping_n_s_m * om);
    let a = p.force_n / den;
    (den > 0.0 && a.is_finite()).then_some(a)
}

/// A run in progress that can be advanced stretch by stretch: both solvers.
pub(crate) trait Stepper {
    /// Runs on to time `t` (s), or until a work cap or cancellation stops the run.
    fn advance_to(&mut self, t: f64);
    /// Whether a work cap or cancellation has stopped the run.
    fn halted(&self) -> bool;
    fn recorder(&mut self) -> &mut Recorder;
    /// The completed impacts so far.
    fn impacts(&self) -> &[ImpactEvent];
    /// The run as it stands (the stepper is spent for recording afterwards).
    fn finish(&mut self) -> Run;
    /// The state at the end of the run, off the record: a contact still open is carried on to
    /// its end first. `phase_at(t)` is the force's phase at time `t`.
    fn end_state(&mut self, phase_at: impl Fn(f64) -> f64) -> Start;
}

/// Whether window `b` has settled after window `a`.
fn converged(a: &WindowStats, b: &WindowStats) -> bool {
    a.complete && b.complete && (b.amplitude_m - a.amplitude_m).abs() <= SETTLED_TOLERANCE * b.amplitude_m
}

/// Whether the last three windows agree (`w[0]` the oldest).
fn settled(w: &[WindowStats; 3]) -> bool {
    converged(&w[0], &w[1]) && converged(&w[1], &w[2])
}

/// Runs `p` from `start` with `solver`: to its duration, then (forced, with `settle`) on until
/// it settles. Returns the run and, if `want_end`, the state it ended in (for a continuation).
pub(crate) fn run(p: &DamperParams, solver: Solver, opts: &RunOptions, start: &Start, want_end: bool) -> (Run, Option<Start>) {
    let mut rec = Recorder::new(opts.history_samples, p.duration_s);
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    if !p.forced() {
        return match solver {
            Solver::Event => drive(EventSim::new(p, Free(osc), opts, start, rec), p, None, want_end),
            Solver::Newmark { dt_s } => drive(NewmarkSim::new(p, dt_s, None, opts, start, rec), p, None, want_end),
        };
    }
    rec.windows = Some(Windows::new(p.duration_s, 1.0 / p.freq_hz, p.steady_periods as usize));
    let load = Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, start.phase);
    match solver {
        Solver::Event => {
            drive(EventSim::new(p, ForcedFlight(Forced::new(osc, load)), opts, start, rec), p, Some(load), want_end)
        }
        Solver::Newmark { dt_s } => {
            drive(NewmarkSim::new(p, dt_s, Some(load), opts, start, rec), p, Some(load), want_end)
        }
    }
}

/// Drives one run to its end (see [`run`]); `load` is the force, if any.
fn drive<S: Stepper>(mut s: S, p: &DamperParams, load: Option<Harmonic>, want_end: bool) -> (Run, Option<Start>) {
    s.advance_to(p.duration_s);
    let steady = p.forced().then(|| settle(&mut s, p));
    let mut run = s.finish();
    run.steady = steady.map(|mut m| {
        m.truncated = run.truncated.is_some() || run.cancelled;
        if m.truncated {
            // The window ends where the run stopped.
            m.settled = false;
            m.periodic = false;
            m.window_end_s = m.window_end_s.min(run.final_time_s);
            let span = m.window_end_s - m.window_start_s;
            m.impacts_per_period = if span > 0.0 { m.impacts as f64 / (span * p.freq_hz) } else { 0.0 };
        }
        m
    });
    let tau = 2.0 * std::f64::consts::PI;
    let end = want_end.then(|| s.end_state(|t| load.map_or(0.0, |l| l.theta(t).rem_euclid(tau))));
    (run, end)
}

/// The steady state of a forced run that has reached its duration: windows 0 and 1, then (with
/// `settle`) further windows until two agree.
fn settle<S: Stepper>(s: &mut S, p: &DamperParams) -> SteadyMotion {
    fn windows<S: Stepper>(s: &mut S) -> &mut Windows {
        s.recorder().windows.as_mut().expect("a forced run has windows")
    }
    let mut w = [windows(s).close(0), windows(s).close(1), windows(s).close(2)];
    let mut k = PRE_WINDOWS - 1;
    if p.settle {
        let max_windows = SETTLE_PERIODS_MAX.div_ceil(p.steady_periods);
        for _ in 0..max_windows {
            if s.halted() || settled(&w) {
                break;
            }
            k += 1;
            let end = windows(s).bounds(k).1;
            s.advance_to(end);
            w = [w[1], w[2], windows(s).close(k)];
        }
    }
    let [_, prev, last] = w;
    let period = 1.0 / p.freq_hz;
    let impacts = s.impacts().iter().filter(|i| i.t_s >= last.start_s && i.t_s < last.end_s).count();
    let span = (last.end_s - last.start_s).max(0.0);
    let amplitude_linear_m = linear_amplitude_m(p);
    let reduction_db = match amplitude_linear_m {
        Some(lin) if last.amplitude_m > 0.0 => Some(20.0 * (lin / last.amplitude_m).log10()),
        _ => None,
    };
    SteadyMotion {
        periods: p.steady_periods,
        window_start_s: last.start_s,
        window_end_s: last.end_s,
        amplitude_m: last.amplitude_m,
        amplitude_linear_m,
        reduction_db,
        impacts,
        impacts_per_period: if span > 0.0 { impacts as f64 * period / span } else { 0.0 },
        periodic: last.complete && last.periodic,
        settled: settled(&w),
        truncated: false,
        previous_amplitude_m: prev.complete.then_some(prev.amplitude_m),
    }
}
