//! The paper's reference solver: uniform Newmark-β with average acceleration (β = 1/4, γ = 1/2)
//! on paper Eqs 25–26, Newton iterations on the coupled `(x, y)` equations for the Hertz + c1
//! force (2×2 Jacobian solved with nalgebra), contact onset and exit located inside the step
//! (the step is split at the crossing of δ = 0). Units: SI.

use std::sync::atomic::Ordering;

use nalgebra::{Matrix2, Vector2};

use super::contact::Sys;
use super::record::Recorder;
use super::{DamperParams, EnergyLedger, ImpactEvent, Run, RunOptions, SingleContact};

/// One Newmark state: positions (m), velocities (m/s), accelerations (m/s²) of M and m.
#[derive(Debug, Clone, Copy)]
struct St {
    x: f64,
    v: f64,
    a: f64,
    y: f64,
    w: f64,
    b: f64,
}

impl St {
    /// Penetration `δ = s·(y − x) − d/2` (m) and its rate at wall `s`.
    #[inline]
    fn pen(&self, sys: &Sys, s: f64) -> (f64, f64) {
        (s * (self.y - self.x) - sys.half_gap, s * (self.w - self.v))
    }
}

/// Accelerations from the equations of motion, out of contact.
#[inline]
fn flight_accels(sys: &Sys, st: &mut St) {
    st.a = (-sys.c * st.v - sys.k * st.x) / sys.big_m;
    st.b = 0.0;
}

/// Accelerations from the equations of motion, in contact with wall `s`.
#[inline]
fn contact_accels(sys: &Sys, s: f64, st: &mut St) {
    let (d, dd) = st.pen(sys, s);
    let (f, _, _) = sys.bracket(d, dd);
    st.a = (-sys.c * st.v - sys.k * st.x + s * f) / sys.big_m;
    st.b = -s * f / sys.m;
}

/// The end state of a step of length `h` from `st` given the end accelerations `(a1, b1)`:
/// `x1 = x0 + h·v0 + h²/4·(a0 + a1)`, `v1 = v0 + h/2·(a0 + a1)` (and the same for the ball).
/// Written in accelerations, which keeps full precision however small `h` is.
#[inline]
fn advance(st: &St, h: f64, a1: f64, b1: f64) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    St {
        x: st.x + h * st.v + q * (st.a + a1),
        v: st.v + hh * (st.a + a1),
        a: a1,
        y: st.y + h * st.w + q * (st.b + b1),
        w: st.w + hh * (st.b + b1),
        b: b1,
    }
}

/// One free-flight step of length `h` (linear: solved directly for the end acceleration).
#[inline]
fn flight_step(sys: &Sys, st: &St, h: f64) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let meff = sys.big_m + sys.c * hh + sys.k * q;
    let a1 = -(sys.c * (st.v + hh * st.a) + sys.k * (st.x + h * st.v + q * st.a)) / meff;
    advance(st, h, a1, 0.0)
}

/// One in-contact step of length `h` at wall `s`: Newton on the residuals
/// `M·a + C·v + K·x − s·F = 0`, `m·b + s·F = 0` in the unknown end accelerations `(a, b)`.
#[inline]
fn contact_step(sys: &Sys, s: f64, st: &St, h: f64) -> St {
    let (hh, q) = (0.5 * h, 0.25 * h * h);
    let (mut a1, mut b1) = (st.a, st.b);
    let mut out = advance(st, h, a1, b1);
    for _ in 0..30 {
        let n = advance(st, h, a1, b1);
        let (del, dd) = n.pen(sys, s);
        let (f, _, clamped) = sys.bracket(del, dd);
        let r1 = sys.big_m * a1 + sys.c * n.v + sys.k * n.x - s * f;
        let r2 = sys.m * b1 + s * f;
        out = n;
        let kt = if clamped { 0.0 } else { 1.5 * sys.k_hz * del.max(0.0).sqrt() * q + sys.c1 * hh };
        let jac = Matrix2::new(sys.big_m + sys.c * hh + sys.k * q + kt, -kt, -kt, sys.m + kt);
        let Some(inv) = jac.try_inverse() else { break };
        let da = inv * Vector2::new(-r1, -r2);
        a1 += da[0];
        b1 += da[1];
        if da[0].abs() + da[1].abs() <= 1e-13 * (a1.abs() + b1.abs()) + 1e-300 {
            out = advance(st, h, a1, b1);
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

/// Runs the Newmark solver with step `dt` (s). Parameters are assumed valid.
pub(crate) fn run(p: &DamperParams, dt: f64, opts: &RunOptions) -> Run {
    let sys = Sys::new(p);
    let t_end = p.duration_s;
    let mut rec = Recorder::new(opts.history_samples, t_end);
    let mut st = St { x: 0.0, v: p.v0_m_s, a: 0.0, y: 0.0, w: 0.0, b: 0.0 };
    flight_accels(&sys, &mut st);
    rec.zdot(st.w - st.v);
    let mut energy = EnergyLedger { initial_j: sys.mechanical_energy(st.x, st.v, st.w, 0.0), ..Default::default() };
    let mut impacts: Vec<ImpactEvent> = Vec::new();
    let n_steps = (t_end / dt).ceil() as u64;
    let mut k_next: u64 = 1;
    let mut t = 0.0;
    let mut wall = 0.0; // 0 in flight, ±1 in contact
    let mut cur = ImpactEvent::onset(0.0, 0.0, 0.0, 0.0);
    let mut cancelled = false;
    let mut counter: u32 = 0;
    // Mode switches inside the current grid step (a guard against endless re-splitting).
    let mut splits = 0u32;

    // Commits a step from `a` (time t0) to `b` (time t1).
    let commit = |rec: &mut Recorder, energy: &mut EnergyLedger, s: f64, t0: f64, a: &St, t1: f64, b: &St| {
        rec.step(t0, a.x, a.v, t1, b.x, b.v, b.w - b.v);
        let h = t1 - t0;
        let vm = 0.5 * (a.v + b.v);
        energy.dissipated_viscous_j += sys.c * vm * vm * h;
        if s != 0.0 {
            let (da, dda) = a.pen(&sys, s);
            let (db, ddb) = b.pen(&sys, s);
            let (fa, ha, _) = sys.bracket(da, dda);
            let (fb, hb, _) = sys.bracket(db, ddb);
            energy.dissipated_contact_j += 0.5 * ((fa - ha) + (fb - hb)) * (db - da);
        }
        if rec.next_hist_time().is_some_and(|ts| ts <= t1) {
            rec.history_until(t1, |ts| {
                let u = if h > 0.0 { ((ts - t0) / h).clamp(0.0, 1.0) } else { 1.0 };
                (a.x + u * (b.x - a.x), a.y + u * (b.y - a.y))
            });
        }
    };

    while k_next <= n_steps {
        let t_next = if k_next == n_steps { t_end } else { k_next as f64 * dt };
        let h = t_next - t;
        if h <= 0.0 {
            k_next += 1;
            continue;
        }
        counter = counter.wrapping_add(1);
        if counter.is_multiple_of(4096) && opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            cancelled = true;
            break;
        }
        if wall == 0.0 {
            let n1 = flight_step(&sys, &st, h);
            let z1 = n1.y - n1.x;
            let d1 = z1.abs() - sys.half_gap;
            if d1 > 0.0 && splits < MAX_SPLITS {
                splits += 1;
                let s = z1.signum();
                let g0 = st.pen(&sys, s).0;
                let (th, mut sub) = split(g0, d1, n1, |th| {
                    let q = flight_step(&sys, &st, th * h);
                    (q.pen(&sys, s).0, q)
                });
                let t1 = t + th * h;
                commit(&mut rec, &mut energy, 0.0, t, &st, t1, &sub);
                contact_accels(&sys, s, &mut sub);
                st = sub;
                t = t1;
                wall = s;
                cur = ImpactEvent::onset(t, s, st.pen(&sys, s).1, 0.0);
                if th >= 1.0 {
                    k_next += 1;
                    splits = 0;
                }
                continue;
            }
            commit(&mut rec, &mut energy, 0.0, t, &st, t_next, &n1);
            st = n1;
            if d1 > 0.0 {
                // Out of splits: switch to contact at the step end.
                wall = z1.signum();
                contact_accels(&sys, wall, &mut st);
                cur = ImpactEvent::onset(t_next, wall, st.pen(&sys, wall).1, d1);
            }
        } else {
            let s = wall;
            let n1 = contact_step(&sys, s, &st, h);
            let d1 = n1.pen(&sys, s).0;
            if d1 < 0.0 && splits < MAX_SPLITS {
                splits += 1;
                let g0 = st.pen(&sys, s).0;
                let (th, mut sub) = split(g0, d1, n1, |th| {
                    let q = contact_step(&sys, s, &st, th * h);
                    (q.pen(&sys, s).0, q)
                });
                let t1 = t + th * h;
                commit(&mut rec, &mut energy, s, t, &st, t1, &sub);
                flight_accels(&sys, &mut sub);
                st = sub;
                t = t1;
                wall = 0.0;
                cur.u_out_m_s = -st.pen(&sys, s).1;
                cur.t_end_s = t;
                impacts.push(cur);
                if th >= 1.0 {
                    k_next += 1;
                    splits = 0;
                }
                continue;
            }
            commit(&mut rec, &mut energy, s, t, &st, t_next, &n1);
            cur.penetration_max_m = cur.penetration_max_m.max(d1);
            st = n1;
            if d1 < 0.0 {
                // Out of splits: leave the contact at the step end.
                flight_accels(&sys, &mut st);
                wall = 0.0;
                cur.u_out_m_s = -st.pen(&sys, s).1;
                cur.t_end_s = t_next;
                impacts.push(cur);
            }
        }
        t = t_next;
        k_next += 1;
        splits = 0;
    }
    let del = if wall != 0.0 { st.pen(&sys, wall).0.max(0.0) } else { 0.0 };
    energy.final_mechanical_j = sys.mechanical_energy(st.x, st.v, st.w, del);
    rec.into_run(impacts, energy, if cancelled { t } else { t_end }, cancelled)
}

/// One isolated contact (no spring, no viscous damper) at approach speed `u0` by Newmark steps of
/// `dt` (s), with the exit located inside the step.
pub(crate) fn single(sys: &Sys, u0: f64, dt: f64) -> SingleContact {
    let s = 1.0;
    let mut st = St { x: 0.0, v: 0.0, a: 0.0, y: sys.half_gap, w: u0, b: 0.0 };
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
