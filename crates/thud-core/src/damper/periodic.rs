//! The stroboscopic flow of a forced design, the map periodic orbits are fixed points of
//! (docs/model.md §6.7): from a state `(x, x', y, y')` at the force's phase `φ`, the event
//! solver's ordinary forced run over a given time, with its impacts and the largest `|x|` on
//! the way. [`crate::orbit`] solves `Pⁿ(s) = s` on it by Newton's method.

use std::sync::atomic::AtomicBool;

use nalgebra::{Matrix4, Vector4};

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

/// The transition matrix of the state `(x, x', y, y')` over `dt` (s) of flight: the
/// structure's own homogeneous motion (Eq 25 without the force: the force adds no dependence
/// on the state) beside the ball's straight line.
fn flight_transition(osc: &Oscillator, dt: f64) -> Matrix4<f64> {
    let (x1, v1) = osc.advance(1.0, 0.0, dt);
    let (x2, v2) = osc.advance(0.0, 1.0, dt);
    Matrix4::new(x1, x2, 0.0, 0.0, v1, v2, 0.0, 0.0, 0.0, 0.0, 1.0, dt, 0.0, 0.0, 0.0, 1.0)
}

/// The windows `[a, b]` (s) that hold the contacts of `impacts` over a flow of `span`, each
/// reaching a quarter of the flight on either side (at most [`WINDOW_MARGIN`] of a forcing
/// period) so that a perturbed contact still starts and ends inside its window; windows that
/// meet are merged.
fn contact_windows(impacts: &[ImpactEvent], span: f64, period: f64) -> Vec<(f64, f64)> {
    let mut windows: Vec<(f64, f64)> = Vec::with_capacity(impacts.len());
    for (i, imp) in impacts.iter().enumerate() {
        let before = imp.t_s - if i == 0 { 0.0 } else { impacts[i - 1].t_end_s };
        let after = impacts.get(i + 1).map_or(span, |n| n.t_s) - imp.t_end_s;
        let a = (imp.t_s - (0.25 * before).min(WINDOW_MARGIN * period)).max(0.0);
        let b = (imp.t_end_s + (0.25 * after).min(WINDOW_MARGIN * period)).min(span);
        match windows.last_mut() {
            Some(last) if a <= last.1 => last.1 = last.1.max(b),
            _ => windows.push((a, b)),
        }
    }
    windows
}

/// The largest margin of a contact's window on either side, as a fraction of a forcing period.
const WINDOW_MARGIN: f64 = 1e-3;

/// The Jacobian `∂s(span)/∂s(0)` of the flow of [`flow`] from `state` at `phase` over `span`
/// (s), whose completed contacts are `impacts` (from that flow), with the time (s) simulated to
/// find it (docs/model.md §6.7). A flight is linear in the state, so its factor is exact
/// ([`flight_transition`]); each contact's short window is differenced forward with the steps
/// `steps` (one per state component, m or m/s), so the Jacobian costs five runs over the
/// contacts alone, not over the whole span. `None` where a run stopped short or a perturbed
/// contact left its window.
pub(crate) fn chained_jacobian(
    p: &DamperParams,
    state: [f64; 4],
    phase: f64,
    span: f64,
    impacts: &[ImpactEvent],
    steps: [f64; 4],
    cancel: Option<&AtomicBool>,
) -> Option<(Matrix4<f64>, f64)> {
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let forced = Forced::new(osc, Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, phase));
    let omega = std::f64::consts::TAU * p.freq_hz;
    let fly = |s: [f64; 4], t0: f64, dt: f64| {
        let (x, v) = forced.advance(t0, s[0], s[1], dt);
        [x, v, s[2] + s[3] * dt, s[3]]
    };
    let mut jac = Matrix4::identity();
    let mut s = state;
    let mut t = 0.0;
    let mut simulated = 0.0;
    for (a, b) in contact_windows(impacts, span, 1.0 / p.freq_hz) {
        jac = flight_transition(&osc, a - t) * jac;
        s = fly(s, t, a - t);
        let run = |s0: [f64; 4]| {
            let f = flow(p, s0, phase + omega * a, &[b - a], cancel);
            (f.states.first().copied().filter(|_| !f.halted && !f.in_contact), f.impacts.len())
        };
        let (end, hits) = run(s);
        let end = end?;
        let mut w = Matrix4::zeros();
        for (k, &h) in steps.iter().enumerate() {
            let mut sk = s;
            sk[k] += h;
            let (e, n) = run(sk);
            if n != hits {
                return None;
            }
            let e = e?;
            w.set_column(k, &Vector4::from_fn(|i, _| (e[i] - end[i]) / h));
        }
        simulated += 5.0 * (b - a);
        jac = w * jac;
        s = end;
        t = b;
    }
    Some((flight_transition(&osc, span - t) * jac, simulated))
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
