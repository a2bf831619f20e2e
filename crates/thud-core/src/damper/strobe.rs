//! Stroboscopic sampling of a forced run: the state at every half forcing period
//! after a transient, every impact, and the state at the end — what the bifurcation diagram,
//! the impact map and the basins of attraction ([`crate::dynamics`]) are drawn from. The run is
//! the event solver's ordinary forced run, stopped at each sample time and resumed
//! ([`Stepper::advance_to`]): a stop in flight carries the same flight on from its launch, and
//! a stop inside a contact resumes it where it stood, so sampling does not change the motion
//! (in flight, not by a bit).

use std::sync::atomic::AtomicBool;

use super::event::{EventSim, ForcedFlight};
use super::flight::Oscillator;
use super::forced::{Forced, Harmonic};
use super::record::{Recorder, Windows};
use super::stepper::{Start, Stepper};
use super::{DamperParams, ImpactEvent, RunOptions, Truncation};

/// What a stroboscopic run saw after its transient.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Strobed {
    /// `(x, x', z, z')` (m, m/s) at every half period `θ = π·j` of the force after the
    /// transient: even entries at the force's phase 0 (`x(kT)`), odd ones half a period later.
    pub samples: Vec<[f64; 4]>,
    /// The impacts whose onset lies in the sampled window, with the force's phase at onset
    /// (`θ mod 2π`, rad) and the period of the window it falls in (0, 1, …).
    pub impacts: Vec<(ImpactEvent, f64, u32)>,
    /// Largest `|x|` over the sampled window (m).
    pub amplitude_m: f64,
    /// The state at the end (a contact still open carried on to its end first).
    pub end: Start,
    /// Why the run stopped short, if it did (a work cap); `cancelled` if cancellation stopped it.
    pub truncated: Option<Truncation>,
    pub cancelled: bool,
}

/// Runs the forced design `p` (F0 > 0, f > 0) with the event solver from `start` for
/// `transient` forcing periods, then samples it over `periods` periods ([`Strobed`]). Periods
/// are counted from the first time after `t = 0` at which the force's phase `θ = Ω·t + φ` is a
/// whole turn, so that every sample of every run lies at the same phase of the force.
pub(crate) fn strobe(
    p: &DamperParams,
    start: &Start,
    transient: u32,
    periods: u32,
    cancel: Option<&AtomicBool>,
) -> Strobed {
    let tau = std::f64::consts::TAU;
    let omega = tau * p.freq_hz;
    let phase = start.phase.rem_euclid(tau);
    // θ = 2π·(k0 + j/2) at sample j.
    let k0 = (phase / tau).floor() + 1.0;
    let at = |half: f64| (tau * (k0 + half / 2.0) - phase) / omega;
    let first = 2.0 * f64::from(transient);
    let last = first + 2.0 * f64::from(periods);
    let end_t = at(last);
    let mut rec = Recorder::new(0, end_t);
    rec.windows = Some(Windows::new(end_t, 1.0 / p.freq_hz, periods.max(1) as usize));
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let load = Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, phase);
    let opts = RunOptions { history_samples: 0, cancel };
    let mut sim =
        EventSim::new(p, ForcedFlight(Forced::new(osc, load)), &opts, start, rec, super::ContactScheme::default());
    let t_window = at(first);
    sim.advance_to(t_window);
    let n = 2 * periods as usize;
    let mut samples = Vec::with_capacity(n);
    for j in 0..n {
        if sim.halted() {
            break;
        }
        if j > 0 {
            sim.advance_to(at(first + j as f64));
        }
        let (x, v, y, w) = sim.state();
        samples.push([x, v, y - x, w - v]);
    }
    if !sim.halted() {
        sim.advance_to(end_t);
    }
    let halted = sim.halted();
    let amplitude_m = {
        let w = sim.recorder().windows.as_mut();
        match w {
            Some(w) => {
                if halted {
                    w.close_open();
                }
                w.recent().last().map_or(0.0, |s| s.amplitude_m)
            }
            None => 0.0,
        }
    };
    let run = sim.finish();
    // A contact that began before the window's end and is still open there belongs to the
    // window (its onset does): the end state carries it on to its end, which completes it.
    // Without it every window of a periodic orbit whose contact straddles the force's phase 0
    // would hold one impact fewer than its periods do (the first period's contact began
    // before the window).
    let end = sim.end_state(|t| load.theta(t).rem_euclid(tau));
    let straddling = if halted { &[][..] } else { sim.impacts() };
    let impacts = run
        .impacts
        .iter()
        .chain(straddling)
        .filter(|i| i.t_s >= t_window && i.t_s < end_t)
        .map(|i| {
            let k = ((load.theta(i.t_s) - load.theta(t_window)) / tau).floor().max(0.0);
            (*i, load.theta(i.t_s).rem_euclid(tau), k as u32)
        })
        .collect();
    Strobed { samples, impacts, amplitude_m, end, truncated: run.truncated, cancelled: run.cancelled }
}
