//! The stroboscopic flow of a forced design, the map periodic orbits are fixed points of
//! (docs/model.md §6.7): from a state `(x, x', y, y')` at the force's phase `φ`, the event
//! solver's ordinary forced run over a given time, with its impacts and the largest `|x|` on
//! the way. [`crate::orbit`] solves `Pⁿ(s) = s` on it by Newton's method.

use std::sync::atomic::AtomicBool;

use super::event::{EventSim, ForcedFlight};
use super::flight::Oscillator;
use super::forced::{Forced, Harmonic};
use super::record::{Recorder, Windows};
use super::stepper::{Start, Stepper};
use super::{ContactScheme, DamperParams, ImpactEvent, RunOptions};

/// Where a flow ended and what it saw on the way.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Flowed {
    /// `(x, x', y, y')` (m, m/s) at each of the stop times asked for, in order.
    pub states: Vec<[f64; 4]>,
    /// The completed impacts, their times from the flow's start (s).
    pub impacts: Vec<ImpactEvent>,
    /// Largest `|x|` over the flow (m).
    pub amplitude_m: f64,
    /// Whether the flow ended inside a contact (a section must lie in flight).
    pub in_contact: bool,
    /// Whether a work cap or cancellation stopped the flow short.
    pub halted: bool,
}

/// Flows the forced design `p` from `state = (x, x', y, y')` at force phase `phase` (rad) to
/// each time of `stops` (s, increasing, the last the flow's end), by the default contact
/// scheme, and returns the states there. Sampling does not change the motion
/// ([`Stepper::advance_to`] carries a flight on from its launch).
pub(crate) fn flow(
    p: &DamperParams,
    state: [f64; 4],
    phase: f64,
    stops: &[f64],
    cancel: Option<&AtomicBool>,
) -> Flowed {
    let end_t = stops.last().copied().unwrap_or(0.0);
    let start = Start { x: state[0], v: state[1], y: state[2], w: state[3], phase };
    let mut rec = Recorder::new(0, end_t);
    // One window over the whole flow: its amplitude is the largest |x| on the way.
    rec.windows = Some(Windows::new(end_t, end_t, 1));
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let load = Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, phase);
    let opts = RunOptions { history_samples: 0, cancel };
    let mut sim = EventSim::new(p, ForcedFlight(Forced::new(osc, load)), &opts, &start, rec, ContactScheme::default());
    let mut states = Vec::with_capacity(stops.len());
    for &t in stops {
        sim.advance_to(t);
        if sim.halted() {
            break;
        }
        let (x, v, y, w) = sim.state();
        states.push([x, v, y, w]);
    }
    let halted = sim.halted();
    let in_contact = sim.in_contact();
    let amplitude_m = sim.recorder().windows.as_mut().map_or(0.0, |w| {
        if w.closed() == 0 {
            w.close_open();
        }
        w.recent().last().map_or(0.0, |s| s.amplitude_m)
    });
    let run = sim.finish();
    Flowed { states, impacts: run.impacts, amplitude_m, in_contact, halted }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without impacts (a gap far wider than the swing) the flow is the closed form of Eq 25
    /// under the force, and the ball flies in a straight line.
    #[test]
    fn a_flow_without_impacts_is_the_closed_form() {
        let p = DamperParams { gap_m: 10.0, force_n: 1.0, freq_hz: 3.0, ..DamperParams::table2() };
        let (x0, v0) = (0.001, -0.02);
        let t = 0.7;
        let f = flow(&p, [x0, v0, 0.1, 0.05], 0.3, &[t], None);
        assert!(f.impacts.is_empty() && !f.in_contact && !f.halted);
        let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
        let load = Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, 0.3);
        let (x, v) = Forced::new(osc, load).advance(0.0, x0, v0, t);
        let s = f.states[0];
        assert!((s[0] - x).abs() < 1e-15 && (s[1] - v).abs() < 1e-14, "{s:?} vs {x} {v}");
        assert!((s[2] - (0.1 + 0.05 * t)).abs() < 1e-15 && s[3] == 0.05);
        assert!(f.amplitude_m >= x.abs() && f.amplitude_m >= x0);
    }
}
