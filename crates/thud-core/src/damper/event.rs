//! The event-driven solver: exact flights (paper Eq 25 in closed form), contact instants by
//! conservative advancement, and the adaptive in-contact integrator (Eq 26) between them.
//! Step-size free: the only numerical parameters are internal tolerances. Two work caps bound a
//! run ([`CONTACT_STEP_CAP`] in-contact steps, [`FLIGHT_SEARCH_CAP`] search iterations); a run
//! stopped by one says which in [`Run::truncated`].

use std::sync::atomic::Ordering;

use super::contact::{integrate, ContactOutcome, State, Sys};
use super::flight::{FlightEvent, Oscillator};
use super::record::{hermite, Recorder};
use super::{
    DamperParams, EnergyLedger, ImpactEvent, Run, RunOptions, Truncation, Wall, CONTACT_STEP_CAP, FLIGHT_SEARCH_CAP,
};

/// Outcome of the search for the next contact in one flight.
enum Search {
    /// Contact at this flight time (s) on this wall.
    Contact(f64, Wall),
    /// No contact before the end of the interval.
    None,
    /// The iteration budget ran out at this flight time.
    Exhausted(f64),
}

/// The safe step (s) on one wall's gap `g ≥ 0` (m) with rate `gd` (m/s) when `|g''| ≤ a`: the first
/// root of the lower-bound parabola `g + gd·s − a·s²/2`.
#[inline]
fn safe_step(g: f64, gd: f64, a: f64) -> f64 {
    let disc = (gd * gd + 2.0 * a * g).sqrt();
    if gd < 0.0 {
        2.0 * g / (disc - gd)
    } else if a > 0.0 {
        (gd + disc) / a
    } else {
        f64::INFINITY
    }
}

/// Finds the first contact within `(0, t_max]` of the flight from `(x0, v0, y0, w)` by
/// conservative advancement on both walls' gaps (never skips a grazing contact; converges
/// quadratically onto a transversal one, to a gap below `1e-13·d/2`).
#[allow(clippy::too_many_arguments)]
fn find_contact(osc: &Oscillator, hg: f64, x0: f64, v0: f64, y0: f64, w: f64, t_max: f64, iters: &mut usize) -> Search {
    let a = osc.accel_bound(x0, v0);
    let gtol = 1e-13 * hg;
    let s_min = 1e-15;
    let mut tau = 0.0;
    loop {
        let (x, v) = if tau == 0.0 { (x0, v0) } else { osc.advance(x0, v0, tau) };
        let z = y0 + w * tau - x;
        let zd = w - v;
        let gp = hg - z;
        let gm = hg + z;
        if gp <= gtol && zd > 0.0 {
            return Search::Contact(tau, Wall::Upper);
        }
        if gm <= gtol && zd < 0.0 {
            return Search::Contact(tau, Wall::Lower);
        }
        let st = safe_step(gp.max(0.0), -zd, a).min(safe_step(gm.max(0.0), zd, a)).max(s_min);
        if tau + st >= t_max {
            return Search::None;
        }
        tau += st;
        if *iters == 0 {
            return Search::Exhausted(tau);
        }
        *iters -= 1;
    }
}

/// Records a flight segment `[t0, t0 + tf]`: analytic maxima, crossings, `|z'|` extrema, history.
#[allow(clippy::too_many_arguments)]
fn record_flight(osc: &Oscillator, rec: &mut Recorder, t0: f64, x0: f64, v0: f64, y0: f64, w: f64, tf: f64, t1: f64) {
    osc.for_each_event(x0, v0, tf, |kind, tau| {
        let (x, v) = osc.advance(x0, v0, tau);
        match kind {
            FlightEvent::MaxX => rec.local_max(t0 + tau, x),
            FlightEvent::UpCross => rec.up_cross(),
            FlightEvent::ZeroAccel => rec.zdot(w - v),
        }
    });
    let (_, v1) = osc.advance(x0, v0, tf);
    rec.zdot(w - v1);
    rec.history_until(t1, |ts| {
        let tau = (ts - t0).clamp(0.0, tf);
        (osc.advance(x0, v0, tau).0, y0 + w * tau)
    });
}

/// Runs the event-driven solver. Parameters are assumed valid.
pub(crate) fn run(p: &DamperParams, opts: &RunOptions) -> Run {
    let sys = Sys::new(p);
    let osc = Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let t_end = p.duration_s;
    let hg = sys.half_gap;
    let mut rec = Recorder::new(opts.history_samples, t_end);
    let (mut t, mut x, mut v, mut y, mut w) = (0.0, 0.0, p.v0_m_s, p.ball_position_m, 0.0);
    rec.zdot(w - v);
    let osc_energy = |x: f64, v: f64| 0.5 * sys.big_m * v * v + 0.5 * sys.k * x * x;
    let mut energy = EnergyLedger { initial_j: osc_energy(x, v), ..Default::default() };
    let mut impacts = Vec::new();
    let mut budget = CONTACT_STEP_CAP;
    let mut iters = FLIGHT_SEARCH_CAP;
    let mut cancelled = false;
    let mut truncated = None;
    let mut del_end = 0.0;
    while t < t_end {
        if opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            cancelled = true;
            break;
        }
        // Flight.
        let search = find_contact(&osc, hg, x, v, y, w, t_end - t, &mut iters);
        let (tf, wall) = match search {
            Search::Contact(tau, wall) => (tau, Some(wall)),
            Search::None => (t_end - t, None),
            Search::Exhausted(tau) => {
                truncated = Some(Truncation::FlightSearch);
                (tau, None)
            }
        };
        let t1 = if matches!(search, Search::None) { t_end } else { t + tf };
        record_flight(&osc, &mut rec, t, x, v, y, w, tf, t1);
        let (x1, v1) = osc.advance(x, v, tf);
        energy.dissipated_viscous_j += osc_energy(x, v) - osc_energy(x1, v1);
        x = x1;
        v = v1;
        t = t1;
        let Some(wall) = wall else { break };
        // Contact: start exactly at δ = 0.
        let s = wall.sign();
        let t_start = t;
        let u_in = s * (w - v);
        let y0 = State::new(x, v, 0.0, u_in, 0.0, 0.0);
        let a_bound = osc.accel_bound(x, v);
        let end = integrate(&sys, s, t, y0, t_end, &mut budget, a_bound, |ta, ya, ka, tb, yb, kb| {
            rec.step(ta, ya[0], ya[1], tb, yb[0], yb[1], s * yb[3]);
            rec.history_until(tb, |ts| {
                let (h, q) = (tb - ta, ts - ta);
                let xs = hermite(ya[0], ka[0], yb[0], kb[0], h, q);
                let ds = hermite(ya[2], ka[2], yb[2], kb[2], h, q);
                (xs, xs + s * (hg + ds))
            });
        });
        let ye = end.y;
        energy.dissipated_contact_j += ye[4];
        energy.dissipated_viscous_j += ye[5];
        x = ye[0];
        v = ye[1];
        y = x + s * (hg + ye[2]);
        w = v + s * ye[3];
        t = end.t;
        match end.outcome {
            ContactOutcome::Separated => {
                impacts.push(ImpactEvent::onset(t_start, wall, u_in, end.pen_max).ended(t, -ye[3]));
            }
            ContactOutcome::Grazed => {}
            ContactOutcome::EndOfRun => {
                del_end = ye[2].max(0.0);
                break;
            }
            ContactOutcome::WorkCap => {
                del_end = ye[2].max(0.0);
                truncated = Some(Truncation::ContactSteps);
                break;
            }
        }
    }
    energy.final_mechanical_j = sys.mechanical_energy(x, v, w, del_end);
    rec.into_run(impacts, energy, t, cancelled, truncated)
}
