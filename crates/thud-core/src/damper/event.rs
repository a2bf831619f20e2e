//! The event-driven solver: exact flights (paper Eq 25 in closed form, forced or free), contact
//! instants by conservative advancement, and the adaptive in-contact integrator (Eq 26) between
//! them. Step-size free: the only numerical parameters are internal tolerances. Two work caps
//! bound a run ([`CONTACT_STEP_CAP`] in-contact steps, [`FLIGHT_SEARCH_CAP`] search
//! iterations); a run stopped by one says which in [`Run::truncated`].
//!
//! A run is an [`EventSim`] advanced to its end ([`EventSim::advance_to`]); a forced run that
//! settles is advanced further, window by window, and a contact cut by one stretch's end is
//! carried on by the next.

use std::sync::atomic::{AtomicBool, Ordering};

use super::contact::{
    resume, ContactEnd, ContactOutcome, ContactStart, Load, NoLoad, Observer, Resume, State, Stretch, Sys,
};
use super::dop853;
use super::flight::{FlightEvent, Oscillator};
use super::forced::{Forced, ForcedEvent, Harmonic};
use super::integrator::{ContactIntegrator, Reference, SundmanAdams};
#[cfg(feature = "research")]
use super::integrator::{SundmanDop853, SundmanTaylor};
use super::record::{hermite, Recorder};
use super::stepper::{Start, Stepper};
use super::sundman::{self, Span};
use super::{
    ContactScheme, DamperParams, EnergyLedger, ImpactEvent, Run, RunOptions, Truncation, Wall, CONTACT_STEP_CAP,
    FLIGHT_SEARCH_CAP,
};

/// Where the event solver's time goes, by phase (with the cargo feature `timing` only: the
/// clock reads cost about 25 ns each, a few per impact; without the feature there is no timing
/// code at all). Counted per thread over every run since the last [`timing::take`].
#[cfg(feature = "timing")]
pub mod timing {
    use std::cell::Cell;
    use std::time::Instant;

    /// Nanoseconds spent per phase, and the counts that go with them.
    #[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
    pub struct Breakdown {
        /// Contact search (conservative advancement on the closed-form flight).
        pub search_ns: u64,
        /// Recording flights: maxima, crossings, `|z'|` extrema, history and window probes.
        pub flight_record_ns: u64,
        /// Contacts: the adaptive integrator, with its own recording of each step.
        pub contact_ns: u64,
        /// Flights searched, contacts integrated.
        pub flights: u64,
        pub contacts: u64,
    }

    thread_local! {
        static NOW: Cell<Breakdown> = Cell::new(Breakdown::default());
    }

    /// The breakdown so far on this thread; starts a new one.
    pub fn take() -> Breakdown {
        NOW.with(|c| c.replace(Breakdown::default()))
    }

    pub(crate) fn add(f: impl FnOnce(&mut Breakdown)) {
        NOW.with(|c| {
            let mut b = c.get();
            f(&mut b);
            c.set(b);
        });
    }

    pub(crate) fn since(t: Instant) -> u64 {
        t.elapsed().as_nanos() as u64
    }
}

/// Outcome of the search for the next contact in one flight.
pub(crate) enum Search {
    /// Contact at this flight time (s) on this wall; the main mass's `(x, x')` there when the
    /// search evaluated the flight at it (flight time > 0), so the caller need not again.
    Contact(f64, Wall, Option<(f64, f64)>),
    /// No contact before the end of the interval; the search had reached this flight time (s),
    /// its last iterate, from which a longer search of the same flight goes on exactly as if it
    /// had never stopped.
    None(f64),
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

/// Where a flight starts: its time (s), the main mass's `(x, x')` and the ball's `(y, y')`
/// (m, m/s) there.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Launch {
    pub t0: f64,
    pub x0: f64,
    pub v0: f64,
    pub y0: f64,
    pub w: f64,
}

/// The contact search of one flight by conservative advancement on both walls' gaps: from
/// `from` (flight time 0), searched from flight time `tau0` (0, or where an earlier search of
/// the same flight stopped: [`Search::None`]), the first contact within flight time
/// `(0, t_max]` (s) where a gap
/// (m, to the walls `hg` either side of the centre) is below `1e-13·hg` and closing.
/// `flight(τ)` is the main mass's `(x, x')` at flight time `τ`; `bound(x, x')` bounds `|x''|`
/// (m/s²) over the step from there, which is no longer than `h_max` (s) if given. Never skips a
/// grazing contact; converges quadratically onto a transversal one. Each step spends one of
/// `iters`.
#[inline(always)]
fn conservative_advance(
    hg: f64,
    (from, tau0): (&Launch, f64),
    t_max: f64,
    iters: &mut usize,
    flight: impl Fn(f64) -> (f64, f64),
    mut bound: impl FnMut(f64, f64) -> f64,
    h_max: Option<f64>,
) -> Search {
    let Launch { x0, v0, y0, w, .. } = *from;
    let gtol = 1e-13 * hg;
    let s_min = 1e-15;
    let mut tau = tau0;
    loop {
        let at = (tau != 0.0).then(|| flight(tau));
        let (x, v) = at.unwrap_or((x0, v0));
        let z = y0 + w * tau - x;
        let zd = w - v;
        let gp = hg - z;
        let gm = hg + z;
        if gp <= gtol && zd > 0.0 {
            return Search::Contact(tau, Wall::Upper, at);
        }
        if gm <= gtol && zd < 0.0 {
            return Search::Contact(tau, Wall::Lower, at);
        }
        let a = bound(x, v);
        let mut st = safe_step(gp.max(0.0), -zd, a).min(safe_step(gm.max(0.0), zd, a));
        if let Some(h) = h_max {
            st = st.min(h);
        }
        let st = st.max(s_min);
        if tau + st >= t_max {
            return Search::None(tau);
        }
        tau += st;
        if *iters == 0 {
            return Search::Exhausted(tau);
        }
        *iters -= 1;
    }
}

/// The main mass's motion between contacts, as the event solver needs it: the closed form, the
/// contact search on it, what the recorder sees of it and its energy flows. [`Free`] is the
/// paper's free decay, [`ForcedFlight`] the forced one.
pub(crate) trait Flight: Copy {
    /// The force on the main mass (none for [`Free`]).
    type L: Load;
    fn load(&self) -> Self::L;
    /// `(x, x')` a time `tau` after `(x0, v0)` at time `t0`.
    fn advance(&self, t0: f64, x0: f64, v0: f64, tau: f64) -> (f64, f64);
    /// The first contact of the flight from `from` within flight time `(0, t_max]` (s), on
    /// walls `hg` (m) either side of the centre, searched from flight time `tau0` (see
    /// [`conservative_advance`]).
    fn find_contact(&self, hg: f64, from: &Launch, tau0: f64, t_max: f64, iters: &mut usize) -> Search;
    /// Records the flight segment from `from` over flight time `[0, tf]` (s), which ends at the
    /// main mass's `end = (x, x')` (m, m/s); history samples up to `t1`.
    fn record(&self, rec: &mut Recorder, from: &Launch, tf: f64, t1: f64, end: (f64, f64));
    /// A bound on the main mass's acceleration apart from the contact (m/s²), for the first
    /// step of a contact starting at `(x, v)`.
    fn contact_a_bound(&self, x: f64, v: f64) -> f64;
    /// The viscous dissipation and the work of the force (J) over the flight from `(x0, v0)` at
    /// `t0` to `(x1, v1)` at `t0 + tf`.
    #[allow(clippy::too_many_arguments)]
    fn energies(&self, sys: &Sys, t0: f64, x0: f64, v0: f64, tf: f64, x1: f64, v1: f64) -> (f64, f64);
}

/// The free flight of paper Eq 25.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Free(pub Oscillator);

impl Flight for Free {
    type L = NoLoad;

    #[inline]
    fn load(&self) -> NoLoad {
        NoLoad
    }

    #[inline]
    fn advance(&self, _t0: f64, x0: f64, v0: f64, tau: f64) -> (f64, f64) {
        self.0.advance(x0, v0, tau)
    }

    /// Conservative advancement on both walls' gaps (never skips a grazing contact; converges
    /// quadratically onto a transversal one, to a gap below `1e-13·d/2`), with one acceleration
    /// bound for the whole flight (the free oscillator's energy never grows).
    #[inline]
    fn find_contact(&self, hg: f64, from: &Launch, tau0: f64, t_max: f64, iters: &mut usize) -> Search {
        let osc = &self.0;
        let a = osc.accel_bound(from.x0, from.v0);
        conservative_advance(hg, (from, tau0), t_max, iters, |tau| osc.advance(from.x0, from.v0, tau), |_, _| a, None)
    }

    /// Analytic maxima, crossings, `|z'|` extrema, history.
    #[inline]
    fn record(&self, rec: &mut Recorder, from: &Launch, tf: f64, t1: f64, end: (f64, f64)) {
        let Launch { t0, x0, v0, y0, w } = *from;
        let osc = &self.0;
        osc.for_each_event(x0, v0, tf, |kind, tau| {
            let (x, v) = osc.advance(x0, v0, tau);
            match kind {
                FlightEvent::MaxX => rec.local_max(t0 + tau, x),
                FlightEvent::UpCross => rec.up_cross(),
                FlightEvent::ZeroAccel => rec.zdot(w - v),
            }
        });
        rec.zdot(w - end.1);
        rec.history_until(t1, |ts| {
            let tau = (ts - t0).clamp(0.0, tf);
            (osc.advance(x0, v0, tau).0, y0 + w * tau)
        });
    }

    #[inline]
    fn contact_a_bound(&self, x: f64, v: f64) -> f64 {
        self.0.accel_bound(x, v)
    }

    /// The free main mass loses to the damper what its energy drops; no force does work.
    #[inline]
    fn energies(&self, sys: &Sys, _t0: f64, x0: f64, v0: f64, _tf: f64, x1: f64, v1: f64) -> (f64, f64) {
        let osc_energy = |x: f64, v: f64| 0.5 * sys.big_m * v * v + 0.5 * sys.k * x * x;
        (osc_energy(x0, v0) - osc_energy(x1, v1), 0.0)
    }
}

/// The forced flight of paper Eq 25 with `F(t)` (docs/model.md §6.1).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ForcedFlight(pub Forced);

impl Flight for ForcedFlight {
    type L = Harmonic;

    #[inline]
    fn load(&self) -> Harmonic {
        self.0.load
    }

    #[inline]
    fn advance(&self, t0: f64, x0: f64, v0: f64, tau: f64) -> (f64, f64) {
        self.0.advance(t0, x0, v0, tau)
    }

    /// Conservative advancement as for the free flight, but the force can feed the motion, so
    /// the acceleration bound is taken afresh at each iterate and holds over the next
    /// [`Forced::horizon`] only; no step is longer than that.
    #[inline]
    fn find_contact(&self, hg: f64, from: &Launch, tau0: f64, t_max: f64, iters: &mut usize) -> Search {
        let fo = &self.0;
        let seg = fo.segment(from.t0, from.x0, from.v0);
        let h = fo.horizon();
        conservative_advance(hg, (from, tau0), t_max, iters, |tau| seg.at(tau), |x, v| fo.accel_bound(x, v, h), Some(h))
    }

    /// Maxima, minima, crossings and `|z'|` extrema found on the closed form; `|x|` at the ends
    /// for the steady windows; history and window probes.
    fn record(&self, rec: &mut Recorder, from: &Launch, tf: f64, t1: f64, end: (f64, f64)) {
        let Launch { t0, x0, v0, y0, w } = *from;
        let seg = self.0.segment(t0, x0, v0);
        rec.x_at(t0, x0);
        seg.for_each_event(tf, |kind, tau, x, v| match kind {
            ForcedEvent::MaxX => {
                rec.local_max(t0 + tau, x);
                rec.x_at(t0 + tau, x);
            }
            ForcedEvent::MinX => rec.x_at(t0 + tau, x),
            ForcedEvent::UpCross => rec.up_cross(),
            ForcedEvent::ZeroAccel => rec.zdot(w - v),
        });
        rec.zdot(w - end.1);
        rec.x_at(t0 + tf, end.0);
        rec.history_until(t1, |ts| {
            let tau = (ts - t0).clamp(0.0, tf);
            (seg.at(tau).0, y0 + w * tau)
        });
    }

    #[inline]
    fn contact_a_bound(&self, x: f64, v: f64) -> f64 {
        self.0.accel_bound(x, v, 0.0)
    }

    #[inline]
    fn energies(&self, sys: &Sys, t0: f64, x0: f64, v0: f64, tf: f64, x1: f64, v1: f64) -> (f64, f64) {
        self.0.flight_energies(sys.big_m, sys.k, t0, x0, v0, tf, x1, v1)
    }
}

/// What the recorder sees of a contact at wall `s` (±1) with the walls `hg` (m) either side of
/// the centre: each accepted step of the integrator, and history samples inside it (cubic
/// Hermite on the step's ends).
struct Track<'r> {
    rec: &'r mut Recorder,
    s: f64,
    hg: f64,
}

impl Observer for Track<'_> {
    #[inline(always)]
    fn step(&mut self, ta: f64, ya: &State, ka: &State, tb: f64, yb: &State, kb: &State) {
        let (s, hg) = (self.s, self.hg);
        self.rec.step(ta, ya[0], ya[1], tb, yb[0], yb[1], s * yb[3]);
        self.rec.history_until(tb, |ts| {
            let (h, q) = (tb - ta, ts - ta);
            let xs = hermite(ya[0], ka[0], yb[0], kb[0], h, q);
            let ds = hermite(ya[2], ka[2], yb[2], kb[2], h, q);
            (xs, xs + s * (hg + ds))
        });
    }
}

impl sundman::Observer for Track<'_> {
    /// Maxima of `x` and extrema of `|z'|` located on the step's series; history samples from
    /// them too.
    #[inline(always)]
    fn step(&mut self, sp: &Span<'_>) {
        let (s, hg) = (self.s, self.hg);
        let (a, b) = (sp.y0, sp.y1);
        let (t0, t1) = (sp.t0(), sp.t1());
        let zd_inside = sp.speed_extremum(self.rec.zdot_abs_max);
        self.rec.contact_step((t0, a[0], a[1]), (t1, b[0], b[1]), s * b[3], zd_inside, || sp.x_extremum());
        self.rec.history_until(t1, |ts| {
            let (xs, ds) = sp.sample(ts);
            (xs, xs + s * (hg + ds))
        });
    }
}

/// One contact from `start` by `scheme`, charged to `budget`, its steps shown to `obs`: the one
/// place a scheme picks its integrator (a run's contacts, and `damper::single_contact`'s
/// isolated one).
#[inline(always)]
pub(crate) fn onset_contact<L: Load, O: Observer + sundman::Observer>(
    scheme: ContactScheme,
    start: ContactStart<'_, L>,
    budget: &mut usize,
    obs: O,
) -> ContactEnd<Cut> {
    match scheme {
        ContactScheme::DormandPrince => Reference::integrate(start, budget, obs).map_resume(Cut::Reference),
        #[cfg(feature = "research")]
        ContactScheme::SundmanTaylor => SundmanTaylor::integrate(start, budget, obs).map_resume(Cut::Sundman),
        #[cfg(feature = "research")]
        ContactScheme::SundmanDop853 => SundmanDop853::integrate(start, budget, obs).map_resume(Cut::Dop853),
        // (A contact it cuts is carried on by DOP853.)
        ContactScheme::SundmanAdams => SundmanAdams::integrate(start, budget, obs).map_resume(Cut::Dop853),
    }
}

/// Where a cut contact stood, by the scheme that integrates it.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Cut {
    Reference(Resume),
    #[cfg(feature = "research")]
    Sundman(sundman::Resume),
    Dop853(dop853::Resume),
}

/// A contact cut by the end of a stretch of the run, to be carried on by the next.
#[derive(Debug, Clone, Copy)]
struct Open {
    wall: Wall,
    /// Onset time (s) and incoming speed (m/s).
    t_start: f64,
    u_in: f64,
    resume: Cut,
    /// The contact and viscous dissipation (J) already in the ledger.
    counted: (f64, f64),
}

/// An event-driven run in progress.
pub(crate) struct EventSim<'a, F: Flight> {
    sys: Sys,
    flight: F,
    /// Time (s) and state: main mass `(x, x')`, ball `(y, y')` (m, m/s).
    t: f64,
    x: f64,
    v: f64,
    y: f64,
    w: f64,
    rec: Recorder,
    energy: EnergyLedger,
    impacts: Vec<ImpactEvent>,
    budget: usize,
    iters: usize,
    /// The in-contact steps a run may take: [`CONTACT_STEP_CAP`], unlimited with `no_limit`.
    contact_cap: usize,
    cancelled: bool,
    truncated: Option<Truncation>,
    /// Penetration (m) where the run stands, if it stands inside a contact.
    del_end: f64,
    open: Option<Open>,
    /// The flight the run stands in, if a stretch ended in flight: its launch and the flight
    /// time its contact search had reached (s). The next stretch carries the same flight on
    /// from its launch, so the motion does not depend on where the run was stopped (a flight
    /// restarted from the stop would differ at round-off, which a rattle amplifies).
    flying: Option<(Launch, f64)>,
    cancel: Option<&'a AtomicBool>,
    scheme: ContactScheme,
}

impl<'a, F: Flight> EventSim<'a, F> {
    /// A run of `p` from `start` with the flight `flight`, recording into `rec`.
    pub fn new(
        p: &DamperParams,
        flight: F,
        opts: &RunOptions<'a>,
        start: &Start,
        mut rec: Recorder,
        scheme: ContactScheme,
    ) -> Self {
        let sys = Sys::new(p);
        let (x, v, y, w) = (start.x, start.v, start.y, start.w);
        rec.zdot(w - v);
        let energy = EnergyLedger { initial_j: sys.mechanical_energy(x, v, w, 0.0), ..Default::default() };
        EventSim {
            sys,
            flight,
            t: 0.0,
            x,
            v,
            y,
            w,
            rec,
            energy,
            impacts: Vec::new(),
            budget: if p.no_limit { usize::MAX } else { CONTACT_STEP_CAP },
            iters: if p.no_limit { usize::MAX } else { FLIGHT_SEARCH_CAP },
            contact_cap: if p.no_limit { usize::MAX } else { CONTACT_STEP_CAP },
            cancelled: false,
            truncated: None,
            del_end: 0.0,
            open: None,
            flying: None,
            cancel: opts.cancel,
            scheme: scheme.in_use(p.no_tension),
        }
    }

    /// One contact at `wall` from onset `t_start` with incoming speed `u_in`, or the rest of a
    /// cut one (`open`), up to `t_stop`.
    fn contact(&mut self, wall: Wall, t_start: f64, u_in: f64, open: Option<Open>, t_stop: f64) {
        let sys = self.sys;
        let s = wall.sign();
        let hg = sys.half_gap;
        let obs = Track { rec: &mut self.rec, s, hg };
        let (x0, v0, w0) = (self.x, self.v, self.w);
        let load = self.flight.load();
        let (end, counted) = match (open, self.scheme) {
            (None, scheme) => {
                let y0 = State::new(self.x, self.v, 0.0, u_in, 0.0, 0.0);
                let a_bound = self.flight.contact_a_bound(self.x, self.v);
                let start = ContactStart { sys: &sys, load, s, t0: self.t, y0, t_limit: t_stop, a_bound };
                let end = onset_contact(scheme, start, &mut self.budget, obs);
                (end, (0.0, 0.0))
            }
            (Some(o), _) => {
                let at = Stretch { sys: &sys, load, t_limit: t_stop };
                let end = match &o.resume {
                    Cut::Reference(r) => resume(at, r, &mut self.budget, obs).map_resume(Cut::Reference),
                    #[cfg(feature = "research")]
                    Cut::Sundman(r) => sundman::resume(at, r, &mut self.budget, obs).map_resume(Cut::Sundman),
                    Cut::Dop853(r) => dop853::resume(at, r, &mut self.budget, obs).map_resume(Cut::Dop853),
                };
                (end, o.counted)
            }
        };
        let ye = end.y;
        if <F::L as Load>::ON {
            // The force's work during the contact is the balance of the energies the integrator
            // integrates: W = ΔE_mech + ΔE_contact + ΔE_viscous (in flight it is computed on its
            // own, by Forced::flight_energies).
            let e0 = sys.mechanical_energy(x0, v0, w0, self.del_end);
            let (x1, v1, w1) = (ye[0], ye[1], ye[1] + s * ye[3]);
            let e1 = sys.mechanical_energy(x1, v1, w1, ye[2].max(0.0));
            self.energy.forcing_work_j += e1 - e0 + (ye[4] - counted.0) + (ye[5] - counted.1);
        }
        self.energy.dissipated_contact_j += ye[4] - counted.0;
        self.energy.dissipated_viscous_j += ye[5] - counted.1;
        self.x = ye[0];
        self.v = ye[1];
        self.y = self.x + s * (hg + ye[2]);
        self.w = self.v + s * ye[3];
        self.t = end.t;
        self.del_end = 0.0;
        match end.outcome {
            ContactOutcome::Separated => {
                self.impacts.push(ImpactEvent::onset(t_start, wall, u_in, end.pen_max).ended(self.t, -ye[3]));
            }
            ContactOutcome::Grazed => {}
            ContactOutcome::EndOfRun => {
                self.del_end = ye[2].max(0.0);
                if let Some(resume) = end.resume {
                    self.open = Some(Open { wall, t_start, u_in, resume, counted: (ye[4], ye[5]) });
                }
            }
            ContactOutcome::WorkCap => {
                self.del_end = ye[2].max(0.0);
                self.truncated = Some(Truncation::ContactSteps);
            }
        }
    }
}

impl<F: Flight> EventSim<'_, F> {
    /// The state where the run stands: `(x, x', y, y')` (m, m/s); inside a contact, the
    /// contact's state at that instant (stroboscopic sampling, `strobe.rs`).
    pub(crate) fn state(&self) -> (f64, f64, f64, f64) {
        (self.x, self.v, self.y, self.w)
    }

    /// Whether the run stands inside a contact (one cut by the stretch's end, or stopped by a
    /// work cap inside one).
    pub(crate) fn in_contact(&self) -> bool {
        self.open.is_some() || self.del_end > 0.0
    }
}

impl<F: Flight> Stepper for EventSim<'_, F> {
    fn advance_to(&mut self, t_stop: f64) {
        while self.t < t_stop && self.truncated.is_none() {
            if self.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                self.cancelled = true;
                break;
            }
            if let Some(open) = self.open.take() {
                self.contact(open.wall, open.t_start, open.u_in, Some(open), t_stop);
                continue;
            }
            // Flight: a new one from where the run stands, or the one a stretch ended in.
            let (t, x, v, y, w) = (self.t, self.x, self.v, self.y, self.w);
            #[cfg(feature = "timing")]
            let clock = std::time::Instant::now();
            let carried = self.flying.take();
            let here = Launch { t0: t, x0: x, v0: v, y0: y, w };
            let (from, tau0) = carried.unwrap_or((here, 0.0));
            let search = self.flight.find_contact(self.sys.half_gap, &from, tau0, t_stop - from.t0, &mut self.iters);
            #[cfg(feature = "timing")]
            let (search_ns, clock) = (timing::since(clock), std::time::Instant::now());
            // Flight time from the launch to the flight's end here, and the wall hit there.
            let (tf, wall) = match search {
                Search::Contact(tau, wall, _) => (tau, Some(wall)),
                Search::None(reached) => {
                    self.flying = Some((from, reached));
                    (t_stop - from.t0, None)
                }
                Search::Exhausted(tau) => {
                    self.truncated = Some(Truncation::FlightSearch);
                    (tau, None)
                }
            };
            let t1 = if matches!(search, Search::None(_)) { t_stop } else { from.t0 + tf };
            // What the record and the ledger see runs from where the run stands (what came
            // before is in them already); the motion is the launch's.
            let seen = if carried.is_some() { t1 - t } else { tf };
            // The motion at the flight's end: the search's own evaluation where it found the
            // contact (the same closed form at the same flight time).
            let (x1, v1) = match search {
                Search::Contact(_, _, Some(end)) => end,
                _ => self.flight.advance(from.t0, from.x0, from.v0, tf),
            };
            self.flight.record(&mut self.rec, &here, seen, t1, (x1, v1));
            #[cfg(feature = "timing")]
            timing::add(|b| {
                b.search_ns += search_ns;
                b.flight_record_ns += timing::since(clock);
                b.flights += 1;
            });
            let (viscous, work) = self.flight.energies(&self.sys, t, x, v, seen, x1, v1);
            self.energy.dissipated_viscous_j += viscous;
            if <F::L as Load>::ON {
                self.energy.forcing_work_j += work;
            }
            self.x = x1;
            self.v = v1;
            self.y = from.y0 + w * tf;
            self.t = t1;
            let Some(wall) = wall else { break };
            // Contact: start exactly at δ = 0.
            let u_in = wall.sign() * (self.w - self.v);
            #[cfg(feature = "timing")]
            let clock = std::time::Instant::now();
            self.contact(wall, self.t, u_in, None, t_stop);
            #[cfg(feature = "timing")]
            timing::add(|b| {
                b.contact_ns += timing::since(clock);
                b.contacts += 1;
            });
        }
    }

    fn halted(&self) -> bool {
        self.cancelled || self.truncated.is_some()
    }

    fn recorder(&mut self) -> &mut Recorder {
        &mut self.rec
    }

    fn impacts(&self) -> &[ImpactEvent] {
        &self.impacts
    }

    fn open_onset(&self) -> Option<f64> {
        self.open.as_ref().map(|o| o.t_start)
    }

    fn finish(&mut self) -> Run {
        let mut energy = self.energy;
        energy.final_mechanical_j = self.sys.mechanical_energy(self.x, self.v, self.w, self.del_end);
        let rec = std::mem::replace(&mut self.rec, Recorder::new(0, 0.0));
        rec.into_run(std::mem::take(&mut self.impacts), energy, self.t, self.cancelled, self.truncated)
    }

    fn end_state(&mut self, phase_at: impl Fn(f64) -> f64) -> Start {
        if let Some(open) = self.open.take() {
            // Off the record: carry the contact on until the ball leaves the wall.
            self.rec = Recorder::new(0, 0.0);
            self.budget = self.contact_cap;
            let t_stop = self.t + 1e3;
            self.contact(open.wall, open.t_start, open.u_in, Some(open), t_stop);
        }
        Start { x: self.x, v: self.v, y: self.y, w: self.w, phase: phase_at(self.t) }
    }
}
