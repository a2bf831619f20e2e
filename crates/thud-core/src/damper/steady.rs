//! The steady state of a forced run (docs/model.md §6.2), and the one driver both solvers run
//! under.
//!
//! A forced run of duration `D` at forcing period `T` is judged over windows of `N` periods
//! (`L = N·T`, [`Windows`]) laid back from `D`: the last is `[D − L, D]`. Its [`SteadyMotion`]
//! is the last window's: the largest `|x|`, the impacts per period, whether `x` repeats from
//! period to period (within 1e-3 of the amplitude), and whether the run has settled: the
//! amplitude of each of the last three windows is within 1e-3 (relative) of the one before —
//! two successive changes that small, as one alone can be a coincidence of a slowly decaying
//! beat — and within 1e-3 of the window a third of the way back through the run (with four
//! windows or more), which a transient that decays slowly (light damping: a change of only γ·L
//! a window) cannot pass while it is more than about 1e-3 of the amplitude: a transient
//! `e^(−γt)` passes it once `e^(−2γt/3)·(1 − e^(−γt/3)) < 1e-3`, and is then below 1e-4 or so
//! (docs/model.md §6.2). With `settle`, the run goes on past `D` one window
//! at a time until it has settled, or for at most [`SETTLE_PERIODS_MAX`] more periods (then
//! `settled` is false); the steady state is then the last window's.

use serde::{Deserialize, Serialize};

use crate::verdict::{self, Verdict};

use super::event::{EventSim, ForcedFlight, Free};
use super::flight::Oscillator;
use super::forced::{Forced, Harmonic};
use super::newmark::NewmarkSim;
use super::record::{Recorder, WindowStats, Windows, PROBES_PER_PERIOD};
pub(crate) use super::stepper::{Start, Stepper};
use super::{ContactScheme, DamperParams, Run, RunOptions, Solver};

/// The most forcing periods a settling run adds past its duration.
pub const SETTLE_PERIODS_MAX: u32 = 2000;

/// How much the amplitude of one window may differ from the one before for the run to count as
/// settled (relative).
const SETTLED_TOLERANCE: f64 = 1e-3;

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
    /// Impacts whose onset lies in the window (0 in a design's [`crate::design::Steady`] read
    /// back from JSON, which does not write it).
    #[serde(default)]
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
    /// The verdict on the motion ([`crate::verdict`]): the last window's pattern (from its
    /// probes and impacts), the settling test, and whether the run was cut short.
    #[serde(default)]
    pub verdict: Verdict,
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

/// A motion whose ball no wall ever meets (docs/model.md §6.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Floating {
    /// The motion's limit at its start's time and phase: the structure on its steady solution,
    /// the ball where it is, at rest.
    pub on: Start,
    /// When (s after the start) the structure's free part has fallen to [`SETTLED_TOLERANCE`]
    /// of its steady amplitude.
    pub settled_s: f64,
}

/// Whether the ball of a forced motion from `start` is never met by a wall, proved in closed
/// form (docs/model.md §6.4): a ball at rest (`w = 0`) stays where it is while the structure
/// flies, and the structure's flight is `x = x_p + x_h` with `|x_p| ≤ X` and
/// `|x_h(t)| ≤ R·e^{−γt}` ([`Forced::envelope`]), so `|y − x(t)| ≤ |y| + X + R < d/2` for every
/// `t ≥ 0` keeps the flight from ever ending (1e-9 of the half gap is kept for round-off). The
/// motion then tends to the floating orbit: the structure's steady solution with the ball at
/// rest where it is. None where that is not proved (a moving ball, a bound that reaches a wall,
/// an undamped or overdamped structure, no force).
pub(crate) fn floating(p: &DamperParams, start: &Start) -> Option<Floating> {
    if !p.forced() || start.w != 0.0 {
        return None;
    }
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let forced = Forced::new(osc, Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, start.phase));
    let (x_s, r) = forced.envelope(0.0, start.x, start.v)?;
    // False for a NaN too.
    let clear = start.y.abs() + x_s + r < 0.5 * p.gap_m * (1.0 - 1e-9);
    if !clear || x_s <= 0.0 {
        return None;
    }
    let (x, v) = forced.steady_at(0.0)?;
    let settled_s = if r <= SETTLED_TOLERANCE * x_s { 0.0 } else { (r / (SETTLED_TOLERANCE * x_s)).ln() / osc.gamma };
    settled_s.is_finite().then_some(Floating { on: Start { x, v, y: start.y, w: 0.0, phase: start.phase }, settled_s })
}

/// Whether window `b` has settled after window `a`.
fn converged(a: &WindowStats, b: &WindowStats) -> bool {
    a.complete && b.complete && (b.amplitude_m - a.amplitude_m).abs() <= SETTLED_TOLERANCE * b.amplitude_m
}

/// Whether the run has settled by its closed windows (see the module documentation).
fn settled(w: &Windows) -> bool {
    let [a, b, c] = w.recent() else { return false };
    if !(converged(a, b) && converged(b, c)) {
        return false;
    }
    let n = w.closed();
    if n < 4 {
        return true;
    }
    // The window a third of the way back (before the last three); its amplitude is kept to
    // single precision, far below 1e-3.
    let r = (2 * n / 3).min(n - 4);
    w.starts_in_run(r) && (w.amplitude(r) - c.amplitude_m).abs() <= SETTLED_TOLERANCE * c.amplitude_m * (1.0 + 1e-6)
}

/// Runs `p` from `start` with `solver`: to its duration, then (forced, with `settle`) on until
/// it settles. Returns the run and, if `want_end`, the state it ended in (for a continuation).
pub(crate) fn run(
    p: &DamperParams,
    solver: Solver,
    opts: &RunOptions,
    start: &Start,
    want_end: bool,
    scheme: ContactScheme,
) -> (Run, Option<Start>) {
    let mut rec = Recorder::new(opts.history_samples, p.duration_s);
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    if !p.forced() {
        return match solver {
            Solver::Event => drive(EventSim::new(p, Free(osc), opts, start, rec, scheme), p, None, want_end),
            Solver::Newmark { dt_s } => drive(NewmarkSim::new(p, dt_s, None, opts, start, rec), p, None, want_end),
        };
    }
    rec.windows = Some(Windows::new(p.duration_s, 1.0 / p.freq_hz, p.steady_periods as usize));
    let load = Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, start.phase);
    match solver {
        Solver::Event => drive(
            EventSim::new(p, ForcedFlight(Forced::new(osc, load)), opts, start, rec, scheme),
            p,
            Some(load),
            want_end,
        ),
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
        let cut = if run.cancelled { Some(None) } else { run.truncated.map(Some) };
        m.verdict = verdict::judge(cut, m.verdict, Some(m.settled));
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
    // Invariant: a forced run (F0 > 0, the only caller) is recorded with windows from its start.
    #[allow(clippy::expect_used)]
    fn windows<S: Stepper>(s: &mut S) -> &mut Windows {
        s.recorder().windows.as_mut().expect("a forced run has windows")
    }
    if s.halted() {
        windows(s).close_open();
    } else if p.settle {
        let max_windows = SETTLE_PERIODS_MAX.div_ceil(p.steady_periods);
        for _ in 0..max_windows {
            if settled(windows(s)) {
                break;
            }
            let next = windows(s).closed();
            let end = windows(s).bounds(next).1;
            s.advance_to(end);
            if s.halted() {
                windows(s).close_open();
                break;
            }
        }
    }
    let w = windows(s);
    let is_settled = settled(w);
    let recent = w.recent();
    // Invariant: the run reached its duration, so at least its first window is closed.
    #[allow(clippy::expect_used)]
    let last = *recent.last().expect("a forced run closes at least its last window");
    let prev = recent.len().checked_sub(2).map(|i| recent[i]);
    let period = 1.0 / p.freq_hz;
    // Impacts by onset: a contact still open at the window's end (where the run stands) began
    // in it and counts, as the one cut by the window's start does not.
    let in_window = |t: f64| t >= last.start_s && t < last.end_s;
    let open = s.open_onset().filter(|&t| !s.halted() && in_window(t));
    let impacts = s.impacts().iter().filter(|i| in_window(i.t_s)).count() + usize::from(open.is_some());
    let span = (last.end_s - last.start_s).max(0.0);
    let pattern = if last.complete {
        verdict::window_pattern(windows(s).last_probes(), PROBES_PER_PERIOD, impacts)
    } else {
        Verdict::NotSettled { k: None }
    };
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
        settled: is_settled,
        truncated: false,
        previous_amplitude_m: prev.filter(|p| p.complete).map(|p| p.amplitude_m),
        // The pattern until the run's end is known (see `drive`).
        verdict: pattern,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The floating proof never claims a ball that a wall meets: from starts drawn over the
    /// clearance, with the structure's motion of every size, every start it proves floats for
    /// a long run (200 s, past the free part's decay), and starts it does not prove include
    /// ones that are met. A moving ball is never proved.
    #[test]
    fn a_ball_proved_never_met_is_never_met() {
        let mut p = DamperParams::table2();
        p.force_n = 1.0;
        p.v0_m_s = 0.0;
        p.duration_s = 200.0;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut draw = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut proved, mut met) = (0, 0);
        for _ in 0..40 {
            p.freq_hz = 3.0 + 5.0 * draw();
            let h = 0.5 * p.gap_m;
            let start = Start {
                x: h * (draw() - 0.5),
                v: 0.3 * (draw() - 0.5),
                y: 1.6 * h * (draw() - 0.5),
                w: 0.0,
                phase: 6.0 * draw(),
            };
            let run = run(&p, Solver::Event, &RunOptions::default(), &start, false, ContactScheme::default()).0;
            match floating(&p, &start) {
                Some(f) => {
                    proved += 1;
                    assert!(run.impacts.is_empty(), "{} Hz {start:?}: proved, yet met", p.freq_hz);
                    assert_eq!((f.on.y, f.on.w, f.on.phase), (start.y, 0.0, start.phase));
                    assert!(f.settled_s.is_finite() && f.settled_s >= 0.0);
                }
                None => met += usize::from(!run.impacts.is_empty()),
            }
            assert!(floating(&p, &Start { w: 1e-9, ..start }).is_none(), "a moving ball drifts to a wall");
        }
        assert!(proved >= 5 && met >= 5, "both kinds drawn: {proved} proved, {met} met");
    }
}
