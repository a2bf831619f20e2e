//! The paper's reference solver: uniform Newmark-β with average acceleration (β = 1/4, γ = 1/2)
//! on paper Eqs 25–26, Newton iterations on the coupled `(x, y)` equations for the Hertz + c1
//! force (2×2 Jacobian solved with nalgebra), contact onset and exit located inside the step
//! (the step is split at the crossing of δ = 0). Units: SI.
//!
//! Each pass through the grid loop is one [`StepOutcome`]: a step to the next grid point, or a
//! substep to a contact onset or exit inside it. A run stops after [`NEWMARK_STEP_CAP`] grid
//! steps and says so in [`Run::truncated`].

use std::sync::atomic::Ordering;

use nalgebra::{Matrix2, Vector2};

use super::contact::Sys;
use super::record::Recorder;
use super::{
    DamperParams, EnergyLedger, ImpactEvent, Run, RunOptions, SingleContact, Truncation, Wall, NEWMARK_STEP_CAP,
};

/// One Newmark state of both masses: positions `(x, y)` (m), velocities `(x', y')` (m/s) and
/// accelerations `(x'', y'')` (m/s²), main mass first.
#[derive(Debug, Clone, Copy)]
struct St {
    pos: Vector2<f64>,
    vel: Vector2<f64>,
    acc: Vector2<f64>,
}

impl St {
    /// Penetration `δ = s·(y − x) − d/2` (m) and its rate at wall `s`.
    #[inline]
    fn pen(&self, sys: &Sys, s: f64) -> (f64, f64) {
        (s * (self.pos[1] - self.pos[0]) - sys.half_gap, s * (self.vel[1] - self.vel[0]))
    }
}

/// Accelerations from the equations of motion, out of contact.
#[inline]
fn flight_accels(sys: &Sys, st: &mut St) {
    st.acc = Vector2::new((-sys.c * st.vel[0] - sys.k * st.pos[0]) / sys.big_m, 0.0);
}

/// Accelerations from the equations of motion, in contact with wall `s`.
#[inline]
fn contact_accels(sys: &Sys, s: f64, st: &mut St) {
    let (d, dd) = st.pen(sys, s);
    let (f, _, _) = sys.bracket(d, dd);
    st.acc = Vector2::new((-sys.c * st.vel[0] - sys.k * st.pos[0] + s * f) / sys.big_m, -s * f / sys.m);
}

/// The end state of a step of length `h` from `st` given the end accelerations `acc1`:
/// `q1 = q0 + h·q0' + h²/4·(q0'' + q1'')`, `q1' = q0' + h/2·(q0'' + q1'')` for `q = (x, y)`.
/// Written in accelerations, which keeps full precision however small `h` is.
#[inline]
fn advance(st: &St, h: f64, acc1: Vector2<f64>) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let sum = st.acc + acc1;
    St { pos: st.pos + st.vel * h + sum * q, vel: st.vel + sum * hh, acc: acc1 }
}

/// One free-flight step of length `h` (linear: solved directly for the end acceleration).
#[inline]
fn flight_step(sys: &Sys, st: &St, h: f64) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let (x, v, a) = (st.pos[0], st.vel[0], st.acc[0]);
    let meff = sys.big_m + sys.c * hh + sys.k * q;
    let a1 = -(sys.c * (v + hh * a) + sys.k * (x + h * v + q * a)) / meff;
    advance(st, h, Vector2::new(a1, 0.0))
}

/// One in-contact step of length `h` at wall `s`: Newton on the residuals
/// `M·x'' + C·x' + K·x − s·F = 0`, `m·y'' + s·F = 0` in the unknown end accelerations, with the
/// 2×2 Jacobian inverted by nalgebra.
#[inline]
fn contact_step(sys: &Sys, s: f64, st: &St, h: f64) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let mut acc = st.acc;
    let mut out = advance(st, h, acc);
    for _ in 0..30 {
        let n = advance(st, h, acc);
        let (del, dd) = n.pen(sys, s);
        let (f, _, clamped) = sys.bracket(del, dd);
        let residual =
            Vector2::new(sys.big_m * acc[0] + sys.c * n.vel[0] + sys.k * n.pos[0] - s * f, sys.m * acc[1] + s * f);
        out = n;
        let kt = if clamped { 0.0 } else { 1.5 * sys.k_hz * del.max(0.0).sqrt() * q + sys.c1 * hh };
        let jac = Matrix2::new(sys.big_m + sys.c * hh + sys.k * q + kt, -kt, -kt, sys.m + kt);
        let Some(inv) = jac.try_inverse() else { break };
        let delta = inv * -residual;
        acc += delta;
        if delta.abs().sum() <= 1e-13 * acc.abs().sum() + 1e-300 {
            out = advance(st, h, acc);
            break;
        }
    }
    out
}

/// The fraction `θ ∈ (0, 1]` of the step `h` at which `g(step(θ·h)) = 0`, given `g0 = g(0)` and
/// `g1 = g(step(h))` of opposite signs (Illinois regula falsi), and the substep state there.
fn split(g0: f64, g1: f64, st1: St, mut eval: impl FnMut(f64) -> (f64, St)) -> (f64, St) {
    let (mut lo, mut hi, mut glo, mut ghi) = (0.0, 1.0, g0, g1);
    let mut best = (1.0, st1);
    let mut side = 0;
    for _ in 0..60 {
        let th = (lo * ghi - hi * glo) / (ghi - glo);
        let th = if th > lo && th < hi { th } else { 0.5 * (lo + hi) };
        let (g, stt) = eval(th);
        best = (th, stt);
        if g == 0.0 || (hi - lo) < 1e-15 {
            break;
        }
        if (g > 0.0) == (glo > 0.0) {
            lo = th;
            glo = g;
            if side == -1 {
                ghi *= 0.5;
            }
            side = -1;
        } else {
            hi = th;
            ghi = g;
            if side == 1 {
                glo *= 0.5;
            }
            side = 1;
        }
        if g.abs() < 1e-17 {
            break;
        }
    }
    best
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
}

impl Ledger {
    /// Commits a step from `a` (time `t0`) to `b` (time `t1`), in contact with `wall` if any:
    /// maxima and `|z'|`, the viscous and contact dissipation (trapezoidal), history samples.
    fn commit(&mut self, sys: &Sys, wall: Option<Wall>, t0: f64, a: &St, t1: f64, b: &St) {
        self.rec.step(t0, a.pos[0], a.vel[0], t1, b.pos[0], b.vel[0], b.vel[1] - b.vel[0]);
        let h = t1 - t0;
        let vm = 0.5 * (a.vel[0] + b.vel[0]);
        self.energy.dissipated_viscous_j += sys.c * vm * vm * h;
        if let Some(wall) = wall {
            let s = wall.sign();
            let (da, dda) = a.pen(sys, s);
            let (db, ddb) = b.pen(sys, s);
            let (fa, ha, _) = sys.bracket(da, dda);
            let (fb, hb, _) = sys.bracket(db, ddb);
            self.energy.dissipated_contact_j += 0.5 * ((fa - ha) + (fb - hb)) * (db - da);
        }
        if self.rec.next_hist_time().is_some_and(|ts| ts <= t1) {
            self.rec.history_until(t1, |ts| {
                let u = if h > 0.0 { ((ts - t0) / h).clamp(0.0, 1.0) } else { 1.0 };
                let p = a.pos + (b.pos - a.pos) * u;
                (p[0], p[1])
            });
        }
    }
}

/// A Newmark run in progress on the uniform grid `t_k = k·dt`.
struct Newmark<'a> {
    sys: &'a Sys,
    /// The accepted state at time `t` (s).
    st: St,
    t: f64,
    /// The contact in progress (its wall, onset and peak so far); `None` in flight.
    open: Option<ImpactEvent>,
    /// Mode switches located inside the current grid step (a guard against endless re-splitting).
    splits: u32,
    out: Ledger,
}

impl Newmark<'_> {
    /// One flight step up to `t_next` (`h` long), or up to the contact onset inside it.
    fn flight(&mut self, h: f64, t_next: f64) -> StepOutcome {
        let sys = self.sys;
        let n1 = flight_step(sys, &self.st, h);
        let z1 = n1.pos[1] - n1.pos[0];
        let d1 = z1.abs() - sys.half_gap;
        if d1 > 0.0 && self.splits < MAX_SPLITS {
            self.splits += 1;
            let wall = Wall::facing(z1);
            let s = wall.sign();
            let g0 = self.st.pen(sys, s).0;
            let st0 = self.st;
            let (theta, mut sub) = split(g0, d1, n1, |th| {
                let q = flight_step(sys, &st0, th * h);
                (q.pen(sys, s).0, q)
            });
            let t1 = self.t + theta * h;
            self.out.commit(sys, None, self.t, &self.st, t1, &sub);
            contact_accels(sys, s, &mut sub);
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
            contact_accels(sys, wall.sign(), &mut self.st);
            self.open = Some(ImpactEvent::onset(t_next, wall, self.st.pen(sys, wall.sign()).1, d1));
        }
        StepOutcome::ToGridPoint
    }

    /// One step in contact `cur` up to `t_next` (`h` long), or up to the exit inside it.
    fn contact(&mut self, mut cur: ImpactEvent, h: f64, t_next: f64) -> StepOutcome {
        let sys = self.sys;
        let s = cur.wall.sign();
        let n1 = contact_step(sys, s, &self.st, h);
        let d1 = n1.pen(sys, s).0;
        if d1 < 0.0 && self.splits < MAX_SPLITS {
            self.splits += 1;
            let g0 = self.st.pen(sys, s).0;
            let st0 = self.st;
            let (theta, mut sub) = split(g0, d1, n1, |th| {
                let q = contact_step(sys, s, &st0, th * h);
                (q.pen(sys, s).0, q)
            });
            let t1 = self.t + theta * h;
            self.out.commit(sys, Some(cur.wall), self.t, &self.st, t1, &sub);
            flight_accels(sys, &mut sub);
            self.st = sub;
            self.t = t1;
            self.close(cur, t1);
            return StepOutcome::ToSwitch { theta };
        }
        self.out.commit(sys, Some(cur.wall), self.t, &self.st, t_next, &n1);
        cur.penetration_max_m = cur.penetration_max_m.max(d1);
        self.st = n1;
        if d1 < 0.0 {
            // Out of splits: leave the contact at the step end.
            flight_accels(sys, &mut self.st);
            self.close(cur, t_next);
        } else {
            self.open = Some(cur);
        }
        StepOutcome::ToGridPoint
    }

    /// Ends the contact `cur` at time `t_end` (s) with the current state's exit speed.
    fn close(&mut self, cur: ImpactEvent, t_end: f64) {
        let u_out = -self.st.pen(self.sys, cur.wall.sign()).1;
        self.out.impacts.push(cur.ended(t_end, u_out));
        self.open = None;
    }
}

/// Runs the Newmark solver with step `dt` (s). Parameters are assumed valid.
pub(crate) fn run(p: &DamperParams, dt: f64, opts: &RunOptions) -> Run {
    let sys = Sys::new(p);
    let t_end = p.duration_s;
    let mut rec = Recorder::new(opts.history_samples, t_end);
    let zero = Vector2::zeros();
    let mut st = St { pos: Vector2::new(0.0, p.ball_position_m), vel: Vector2::new(p.v0_m_s, 0.0), acc: zero };
    flight_accels(&sys, &mut st);
    rec.zdot(st.vel[1] - st.vel[0]);
    let energy =
        EnergyLedger { initial_j: sys.mechanical_energy(st.pos[0], st.vel[0], st.vel[1], 0.0), ..Default::default() };
    let mut nm =
        Newmark { sys: &sys, st, t: 0.0, open: None, splits: 0, out: Ledger { rec, energy, impacts: Vec::new() } };
    let n_steps = (t_end / dt).ceil() as u64;
    let mut k_next: u64 = 1;
    let mut cancelled = false;
    let mut truncated = None;
    let mut counter: u32 = 0;
    while k_next <= n_steps {
        if k_next > NEWMARK_STEP_CAP {
            truncated = Some(Truncation::NewmarkSteps);
            break;
        }
        let t_next = if k_next == n_steps { t_end } else { k_next as f64 * dt };
        let h = t_next - nm.t;
        if h <= 0.0 {
            k_next += 1;
            continue;
        }
        counter = counter.wrapping_add(1);
        if counter.is_multiple_of(4096) && opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            cancelled = true;
            break;
        }
        let outcome = match nm.open {
            None => nm.flight(h, t_next),
            Some(cur) => nm.contact(cur, h, t_next),
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
    let st = nm.st;
    let del = nm.open.map_or(0.0, |cur| st.pen(&sys, cur.wall.sign()).0.max(0.0));
    let mut out = nm.out;
    out.energy.final_mechanical_j = sys.mechanical_energy(st.pos[0], st.vel[0], st.vel[1], del);
    let final_time = if cancelled || truncated.is_some() { nm.t } else { t_end };
    out.rec.into_run(out.impacts, out.energy, final_time, cancelled, truncated)
}

/// One isolated contact (no spring, no viscous damper) at approach speed `u0` by Newmark steps of
/// `dt` (s), with the exit located inside the step.
pub(crate) fn single(sys: &Sys, u0: f64, dt: f64) -> SingleContact {
    let s = 1.0;
    let mut st = St { pos: Vector2::new(0.0, sys.half_gap), vel: Vector2::new(0.0, u0), acc: Vector2::zeros() };
    contact_accels(sys, s, &mut st);
    let mut t = 0.0;
    let mut pen: f64 = 0.0;
    let max_steps = 50_000_000u64;
    for _ in 0..max_steps {
        let n1 = contact_step(sys, s, &st, dt);
        let d1 = n1.pen(sys, s).0;
        if d1 < 0.0 {
            let g0 = st.pen(sys, s).0;
            let (th, sub) = split(g0, d1, n1, |th| {
                let q = contact_step(sys, s, &st, th * dt);
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
