//! The paper's reference solver: uniform Newmark-β with average acceleration (β = 1/4, γ = 1/2)
//! on paper Eqs 25–26, Newton iterations on the coupled `(x, y)` equations for the Hertz + c1
//! force (2×2 Jacobian solved with nalgebra), contact onset and exit located inside the step
//! (the step is split at the crossing of δ = 0). Units: SI.
//!
//! Each pass through the grid loop is one [`StepOutcome`]: a step to the next grid point, or a
//! substep to a contact onset or exit inside it. A run stops after [`NEWMARK_STEP_CAP`] grid
//! steps and says so in [`Run::truncated`]. The harmonic force of a forced run (docs/model.md
//! §6.1) enters the main mass's equation at each step's end time; without one the arithmetic is
//! the unforced method's, unchanged.

use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::{Matrix2, Vector2};

use super::contact::Sys;
use super::forced::Harmonic;
use super::record::Recorder;
use super::roots::{illinois, IllinoisStop};
use super::stepper::{Start, Stepper};
use super::{
    DamperParams, EnergyLedger, ImpactEvent, Run, RunOptions, SingleContact, Truncation, Wall, NEWMARK_FINISH_CAP,
    NEWMARK_STEP_CAP,
};

/// One Newmark state of both masses: positions `(x, y)` (m), velocities `(x', y')` (m/s) and
/// accelerations `(x'', y'')` (m/s²), main mass first; and the force on the main mass (N) at
/// its time (0 without one).
#[derive(Debug, Clone, Copy)]
struct St {
    pos: Vector2<f64>,
    vel: Vector2<f64>,
    acc: Vector2<f64>,
    load: f64,
}

impl St {
    /// Penetration `δ = s·(y − x) − d/2` (m) and its rate at wall `s`.
    #[inline]
    fn pen(&self, sys: &Sys, s: f64) -> (f64, f64) {
        (s * (self.pos[1] - self.pos[0]) - sys.half_gap, s * (self.vel[1] - self.vel[0]))
    }
}

/// Accelerations from the equations of motion, out of contact, with the force `load` (N) on the
/// main mass if there is one.
#[inline]
fn flight_accels(sys: &Sys, st: &mut St, load: Option<f64>) {
    let a = match load {
        None => (-sys.c * st.vel[0] - sys.k * st.pos[0]) / sys.big_m,
        Some(f) => (-sys.c * st.vel[0] - sys.k * st.pos[0] + f) / sys.big_m,
    };
    st.acc = Vector2::new(a, 0.0);
    st.load = load.unwrap_or(0.0);
}

/// Accelerations from the equations of motion, in contact with wall `s`, with the force `load`
/// (N) on the main mass if there is one.
#[inline]
fn contact_accels(sys: &Sys, s: f64, st: &mut St, load: Option<f64>) {
    let (d, dd) = st.pen(sys, s);
    let (f, _, _) = sys.bracket(d, dd);
    let a = match load {
        None => (-sys.c * st.vel[0] - sys.k * st.pos[0] + s * f) / sys.big_m,
        Some(l) => (-sys.c * st.vel[0] - sys.k * st.pos[0] + s * f + l) / sys.big_m,
    };
    st.acc = Vector2::new(a, -s * f / sys.m);
    st.load = load.unwrap_or(0.0);
}

/// The end state of a step of length `h` from `st` given the end accelerations `acc1` and the
/// force `load1` (N) at the end:
/// `q1 = q0 + h·q0' + h²/4·(q0'' + q1'')`, `q1' = q0' + h/2·(q0'' + q1'')` for `q = (x, y)`.
/// Written in accelerations, which keeps full precision however small `h` is.
#[inline]
fn advance(st: &St, h: f64, acc1: Vector2<f64>, load1: f64) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let sum = st.acc + acc1;
    St { pos: st.pos + st.vel * h + sum * q, vel: st.vel + sum * hh, acc: acc1, load: load1 }
}

/// One free-flight step of length `h` (linear: solved directly for the end acceleration), with
/// the force `load1` (N) at its end if there is one.
#[inline]
fn flight_step(sys: &Sys, st: &St, h: f64, load1: Option<f64>) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let (x, v, a) = (st.pos[0], st.vel[0], st.acc[0]);
    let meff = sys.big_m + sys.c * hh + sys.k * q;
    let a1 = match load1 {
        None => -(sys.c * (v + hh * a) + sys.k * (x + h * v + q * a)) / meff,
        Some(f) => (f - (sys.c * (v + hh * a) + sys.k * (x + h * v + q * a))) / meff,
    };
    advance(st, h, Vector2::new(a1, 0.0), load1.unwrap_or(0.0))
}

/// One in-contact step of length `h` at wall `s`: Newton on the residuals
/// `M·x'' + C·x' + K·x − s·F − F(t) = 0`, `m·y'' + s·F = 0` in the unknown end accelerations,
/// with the 2×2 Jacobian inverted by nalgebra; `load1` is `F(t)` (N) at the step's end, if any.
#[inline]
fn contact_step(sys: &Sys, s: f64, st: &St, h: f64, load1: Option<f64>) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let l1 = load1.unwrap_or(0.0);
    let mut acc = st.acc;
    let mut out = advance(st, h, acc, l1);
    for _ in 0..30 {
        let n = advance(st, h, acc, l1);
        let (del, dd) = n.pen(sys, s);
        let (f, _, clamped) = sys.bracket(del, dd);
        let r0 = match load1 {
            None => sys.big_m * acc[0] + sys.c * n.vel[0] + sys.k * n.pos[0] - s * f,
            Some(l) => sys.big_m * acc[0] + sys.c * n.vel[0] + sys.k * n.pos[0] - s * f - l,
        };
        let residual = Vector2::new(r0, sys.m * acc[1] + s * f);
        out = n;
        let kt = if clamped { 0.0 } else { 1.5 * sys.k_hz * del.max(0.0).sqrt() * q + sys.c1 * hh };
        let jac = Matrix2::new(sys.big_m + sys.c * hh + sys.k * q + kt, -kt, -kt, sys.m + kt);
        let Some(inv) = jac.try_inverse() else { break };
        let delta = inv * -residual;
        acc += delta;
        if delta.abs().sum() <= 1e-13 * acc.abs().sum() + 1e-300 {
            out = advance(st, h, acc, l1);
            break;
        }
    }
    out
}

/// The fraction `θ ∈ (0, 1]` of the step `h` at which `g(step(θ·h)) = 0`, given `g0 = g(0)` and
/// `g1 = g(step(h))` of opposite signs (Illinois regula falsi), and the substep state there.
fn split(g0: f64, g1: f64, st1: St, eval: impl FnMut(f64) -> (f64, St)) -> (f64, St) {
    // Stops once the bracket is under 1e-15 wide or |g| under 1e-17 (both strict).
    let stop = IllinoisStop { width: 1e-15_f64.next_down(), value: 1e-17_f64.next_down() };
    illinois((0.0, g0), (1.0, g1), stop, (1.0, st1), eval)
}

/// At most this many onset/exit splits per grid step; past that the mode switches at the step end.
const MAX_SPLITS: u32 = 8;

/// What one pass through the current grid step committed.
enum StepOutcome {
    /// The step up to the grid point (a contact may have begun or ended there, when the grid
    /// step is out of splits).
    ToGridPoint,
    /// A substep up to a contact onset or exit inside the grid step, at the fraction `theta`
    /// of it; the rest of the grid step follows in the new mode.
    ToSwitch { theta: f64 },
}

/// What a run has recorded so far: the recorder, the energy ledger and the completed impacts.
struct Ledger {
    rec: Recorder,
    energy: EnergyLedger,
    impacts: Vec<ImpactEvent>,
    /// Whether the run has a force (without one its work is 0 at every step and not summed).
    forced: bool,
}

impl Ledger {
    /// Commits a step from `a` (time `t0`) to `b` (time `t1`), in contact with `wall` if any:
    /// maxima and `|z'|`, the viscous and contact dissipation and the force's work
    /// (trapezoidal), history samples.
    #[inline(always)]
    fn commit(&mut self, sys: &Sys, wall: Option<Wall>, t0: f64, a: &St, t1: f64, b: &St) {
        self.rec.step(t0, a.pos[0], a.vel[0], t1, b.pos[0], b.vel[0], b.vel[1] - b.vel[0]);
        let h = t1 - t0;
        let vm = 0.5 * (a.vel[0] + b.vel[0]);
        self.energy.dissipated_viscous_j += sys.c * vm * vm * h;
        if self.forced {
            self.energy.forcing_work_j += 0.5 * (a.load * a.vel[0] + b.load * b.vel[0]) * h;
        }
        if let Some(wall) = wall {
            let s = wall.sign();
            let (da, dda) = a.pen(sys, s);
            let (db, ddb) = b.pen(sys, s);
            let (fa, ha, _) = sys.bracket(da, dda);
            let (fb, hb, _) = sys.bracket(db, ddb);
            self.energy.dissipated_contact_j += 0.5 * ((fa - ha) + (fb - hb)) * (db - da);
        }
        if self.rec.next_sample_time().is_some_and(|ts| ts <= t1) {
            self.rec.history_until(t1, |ts| {
                let u = if h > 0.0 { ((ts - t0) / h).clamp(0.0, 1.0) } else { 1.0 };
                let p = a.pos + (b.pos - a.pos) * u;
                (p[0], p[1])
            });
        }
    }
}

/// A Newmark run in progress on the uniform grid `t_k = k·dt` (the design's constants, which
/// every step reads, are passed in).
struct Newmark {
    /// The force on the main mass, if any.
    load: Option<Harmonic>,
    /// The accepted state at time `t` (s).
    st: St,
    t: f64,
    /// The contact in progress (its wall, onset and peak so far); `None` in flight.
    open: Option<ImpactEvent>,
    /// Mode switches located inside the current grid step (a guard against endless re-splitting).
    splits: u32,
    out: Ledger,
}

impl Newmark {
    /// The force (N) on the main mass at time `t`, if there is one.
    #[inline]
    fn force(&self, sys: &Sys, t: f64) -> Option<f64> {
        self.load.map(|l| sys.big_m * l.accel(t))
    }

    /// One flight step up to `t_next` (`h` long), or up to the contact onset inside it.
    fn flight(&mut self, sys: &Sys, h: f64, t_next: f64) -> StepOutcome {
        let n1 = flight_step(sys, &self.st, h, self.force(sys, t_next));
        let z1 = n1.pos[1] - n1.pos[0];
        let d1 = z1.abs() - sys.half_gap;
        if d1 > 0.0 && self.splits < MAX_SPLITS {
            self.splits += 1;
            let wall = Wall::facing(z1);
            let s = wall.sign();
            let g0 = self.st.pen(sys, s).0;
            let st0 = self.st;
            let t0 = self.t;
            let (theta, mut sub) = split(g0, d1, n1, |th| {
                let q = flight_step(sys, &st0, th * h, self.force(sys, t0 + th * h));
                (q.pen(sys, s).0, q)
            });
            let t1 = self.t + theta * h;
            self.out.commit(sys, None, self.t, &self.st, t1, &sub);
            contact_accels(sys, s, &mut sub, self.force(sys, t1));
            self.st = sub;
            self.t = t1;
            self.open = Some(ImpactEvent::onset(t1, wall, sub.pen(sys, s).1, 0.0));
            return StepOutcome::ToSwitch { theta };
        }
        self.out.commit(sys, None, self.t, &self.st, t_next, &n1);
        self.st = n1;
        if d1 > 0.0 {
            // Out of splits: switch to contact at the step end.
            let wall = Wall::facing(z1);
            let load = self.force(sys, t_next);
            contact_accels(sys, wall.sign(), &mut self.st, load);
            self.open = Some(ImpactEvent::onset(t_next, wall, self.st.pen(sys, wall.sign()).1, d1));
        }
        StepOutcome::ToGridPoint
    }

    /// One step in contact `cur` up to `t_next` (`h` long), or up to the exit inside it.
    fn contact(&mut self, sys: &Sys, mut cur: ImpactEvent, h: f64, t_next: f64) -> StepOutcome {
        let s = cur.wall.sign();
        let n1 = contact_step(sys, s, &self.st, h, self.force(sys, t_next));
        let d1 = n1.pen(sys, s).0;
        if d1 < 0.0 && self.splits < MAX_SPLITS {
            self.splits += 1;
            let g0 = self.st.pen(sys, s).0;
            let st0 = self.st;
            let t0 = self.t;
            let (theta, mut sub) = split(g0, d1, n1, |th| {
                let q = contact_step(sys, s, &st0, th * h, self.force(sys, t0 + th * h));
                (q.pen(sys, s).0, q)
            });
            let t1 = self.t + theta * h;
            self.out.commit(sys, Some(cur.wall), self.t, &self.st, t1, &sub);
            flight_accels(sys, &mut sub, self.force(sys, t1));
            self.st = sub;
            self.t = t1;
            self.close(sys, cur, t1);
            return StepOutcome::ToSwitch { theta };
        }
        self.out.commit(sys, Some(cur.wall), self.t, &self.st, t_next, &n1);
        cur.penetration_max_m = cur.penetration_max_m.max(d1);
        self.st = n1;
        if d1 < 0.0 {
            // Out of splits: leave the contact at the step end.
            let load = self.force(sys, t_next);
            flight_accels(sys, &mut self.st, load);
            self.close(sys, cur, t_next);
        } else {
            self.open = Some(cur);
        }
        StepOutcome::ToGridPoint
    }

    /// Ends the contact `cur` at time `t_end` (s) with the current state's exit speed.
    fn close(&mut self, sys: &Sys, cur: ImpactEvent, t_end: f64) {
        let u_out = -self.st.pen(sys, cur.wall.sign()).1;
        self.out.impacts.push(cur.ended(t_end, u_out));
        self.open = None;
    }
}

/// A Newmark run in progress, advanced stretch by stretch ([`Stepper`]).
pub(crate) struct NewmarkSim<'a> {
    sys: Sys,
    nm: Newmark,
    dt: f64,
    /// The next grid point to reach, `k_next·dt`.
    k_next: u64,
    /// The time a finished stretch ended at (s): the run's end time unless it was stopped.
    t_reached: f64,
    counter: u32,
    cancelled: bool,
    truncated: Option<Truncation>,
    cancel: Option<&'a AtomicBool>,
    /// The grid steps a run may take: [`NEWMARK_STEP_CAP`], unlimited with `no_limit`.
    step_cap: u64,
}

impl<'a> NewmarkSim<'a> {
    /// A run of `p` at step `dt` (s) from `start` under `load`, recording into `rec`. Parameters
    /// are assumed valid.
    pub fn new(
        p: &DamperParams,
        dt: f64,
        load: Option<Harmonic>,
        opts: &RunOptions<'a>,
        start: &Start,
        rec: Recorder,
    ) -> Self {
        let sys = Sys::new(p);
        let zero = Vector2::zeros();
        let mut st =
            St { pos: Vector2::new(start.x, start.y), vel: Vector2::new(start.v, start.w), acc: zero, load: 0.0 };
        flight_accels(&sys, &mut st, load.map(|l| sys.big_m * l.accel(0.0)));
        let mut rec = rec;
        rec.zdot(st.vel[1] - st.vel[0]);
        let energy = EnergyLedger {
            initial_j: sys.mechanical_energy(st.pos[0], st.vel[0], st.vel[1], 0.0),
            ..Default::default()
        };
        NewmarkSim {
            sys,
            nm: Newmark {
                load,
                st,
                t: 0.0,
                open: None,
                splits: 0,
                out: Ledger { rec, energy, impacts: Vec::new(), forced: load.is_some() },
            },
            dt,
            k_next: 1,
            t_reached: 0.0,
            counter: 0,
            cancelled: false,
            truncated: None,
            cancel: opts.cancel,
            step_cap: if p.no_limit { u64::MAX } else { NEWMARK_STEP_CAP },
        }
    }
}

impl Stepper for NewmarkSim<'_> {
    fn advance_to(&mut self, t_end: f64) {
        if self.cancelled || self.truncated.is_some() {
            return;
        }
        let dt = self.dt;
        let (sys, nm) = (&self.sys, &mut self.nm);
        let n_steps = (t_end / dt).ceil() as u64;
        let mut k_next = self.k_next;
        while k_next <= n_steps {
            if k_next > self.step_cap {
                self.truncated = Some(Truncation::NewmarkSteps);
                break;
            }
            let t_next = if k_next == n_steps { t_end } else { k_next as f64 * dt };
            let h = t_next - nm.t;
            if h <= 0.0 {
                k_next += 1;
                continue;
            }
            self.counter = self.counter.wrapping_add(1);
            if self.counter.is_multiple_of(4096) && self.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                self.cancelled = true;
                break;
            }
            let outcome = match nm.open {
                None => nm.flight(sys, h, t_next),
                Some(cur) => nm.contact(sys, cur, h, t_next),
            };
            let next_grid_step = match outcome {
                StepOutcome::ToGridPoint => {
                    nm.t = t_next;
                    true
                }
                StepOutcome::ToSwitch { theta } => theta >= 1.0,
            };
            if next_grid_step {
                k_next += 1;
                nm.splits = 0;
            }
        }
        let halted = self.cancelled || self.truncated.is_some();
        if !halted && (n_steps as f64) * dt > t_end {
            // The last step was cut short at t_end: the grid point after it is still to come.
            k_next = n_steps;
        }
        self.k_next = k_next;
        self.t_reached = if halted { nm.t } else { t_end };
    }

    fn halted(&self) -> bool {
        self.cancelled || self.truncated.is_some()
    }

    fn recorder(&mut self) -> &mut Recorder {
        &mut self.nm.out.rec
    }

    fn impacts(&self) -> &[ImpactEvent] {
        &self.nm.out.impacts
    }

    fn open_onset(&self) -> Option<f64> {
        self.nm.open.map(|o| o.t_s)
    }

    fn finish(&mut self) -> Run {
        let sys = self.sys;
        let st = self.nm.st;
        let del = self.nm.open.map_or(0.0, |cur| st.pen(&sys, cur.wall.sign()).0.max(0.0));
        let out = std::mem::replace(&mut self.nm.out, Ledger::empty());
        let mut energy = out.energy;
        energy.final_mechanical_j = sys.mechanical_energy(st.pos[0], st.vel[0], st.vel[1], del);
        out.rec.into_run(out.impacts, energy, self.t_reached, self.cancelled, self.truncated)
    }

    fn end_state(&mut self, phase_at: impl Fn(f64) -> f64) -> Start {
        // Off the record: step on until a contact still open has ended.
        self.nm.out = Ledger::empty();
        let mut guard = 0;
        let finish_cap = if self.step_cap == u64::MAX { u64::MAX } else { NEWMARK_FINISH_CAP / 16 };
        while self.nm.open.is_some() && !self.halted() && guard < finish_cap {
            let t = self.nm.t + 16.0 * self.dt;
            self.advance_to(t);
            guard += 1;
        }
        let st = self.nm.st;
        Start { x: st.pos[0], v: st.vel[0], y: st.pos[1], w: st.vel[1], phase: phase_at(self.nm.t) }
    }
}

impl Ledger {
    fn empty() -> Self {
        Ledger { rec: Recorder::new(0, 0.0), energy: EnergyLedger::default(), impacts: Vec::new(), forced: false }
    }
}

/// One isolated contact (no spring, no viscous damper) at approach speed `u0` by Newmark steps of
/// `dt` (s), with the exit located inside the step.
pub(crate) fn single(sys: &Sys, u0: f64, dt: f64) -> SingleContact {
    let s = 1.0;
    let mut st =
        St { pos: Vector2::new(0.0, sys.half_gap), vel: Vector2::new(0.0, u0), acc: Vector2::zeros(), load: 0.0 };
    contact_accels(sys, s, &mut st, None);
    let mut t = 0.0;
    let mut pen: f64 = 0.0;
    let max_steps = 50_000_000u64;
    for _ in 0..max_steps {
        let n1 = contact_step(sys, s, &st, dt, None);
        let d1 = n1.pen(sys, s).0;
        if d1 < 0.0 {
            let g0 = st.pen(sys, s).0;
            let (th, sub) = split(g0, d1, n1, |th| {
                let q = contact_step(sys, s, &st, th * dt, None);
                (q.pen(sys, s).0, q)
            });
            return SingleContact { u_out_m_s: -sub.pen(sys, s).1, duration_s: t + th * dt, penetration_max_m: pen };
        }
        pen = pen.max(d1);
        st = n1;
        t += dt;
    }
    SingleContact { u_out_m_s: 0.0, duration_s: t, penetration_max_m: pen }
}
