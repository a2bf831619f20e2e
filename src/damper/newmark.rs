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

/// One free-flight step of length `h` (linear: solved directly).
#[inline]
fn flight_step(sys: &Sys, st: &St, h: f64) -> St {
    let (i1, i2) = (2.0 / h, 4.0 / (h * h));
    let keff = sys.big_m * i2 + sys.c * i1 + sys.k;
    let x = (sys.big_m * (i2 * st.x + 2.0 * i1 * st.v + st.a) + sys.c * (i1 * st.x + st.v)) / keff;
    let v = i1 * (x - st.x) - st.v;
    let a = i2 * (x - st.x - h * st.v) - st.a;
    let y = st.y + h * st.w + 0.25 * h * h * st.b;
    let w = st.w + 0.5 * h * st.b;
    St { x, v, a, y, w, b: 0.0 }
}

/// One in-contact step of length `h` at wall `s`: Newton on the residuals
/// `M·a + C·v + K·x − s·F = 0`, `m·b + s·F = 0` in the unknowns `(x, y)` at the step end.
#[inline]
fn contact_step(sys: &Sys, s: f64, st: &St, h: f64) -> St {
    let (i1, i2) = (2.0 / h, 4.0 / (h * h));
    let mut x = st.x + h * st.v + 0.5 * h * h * st.a;
    let mut y = st.y + h * st.w + 0.5 * h * h * st.b;
    let tol = 1e-15 * (st.x.abs() + st.y.abs() + sys.half_gap);
    let mut out = *st;
    for _ in 0..30 {
        let v = i1 * (x - st.x) - st.v;
        let a = i2 * (x - st.x - h * st.v) - st.a;
        let w = i1 * (y - st.y) - st.w;
        let b = i2 * (y - st.y - h * st.w) - st.b;
        let del = s * (y - x) - sys.half_gap;
        let dd = s * (w - v);
        let (f, _, clamped) = sys.bracket(del, dd);
        let r1 = sys.big_m * a + sys.c * v + sys.k * x - s * f;
        let r2 = sys.m * b + s * f;
        out = St { x, v, a, y, w, b };
        let kt = if clamped { 0.0 } else { 1.5 * sys.k_hz * del.max(0.0).sqrt() + sys.c1 * i1 };
        let jac = Matrix2::new(sys.big_m * i2 + sys.c * i1 + sys.k + kt, -kt, -kt, sys.m * i2 + kt);
        let Some(inv) = jac.try_inverse() else { break };
        let dx = inv * Vector2::new(-r1, -r2);
        x += dx[0];
        y += dx[1];
        if dx[0].abs() + dx[1].abs() <= tol {
            let v = i1 * (x - st.x) - st.v;
            let a = i2 * (x - st.x - h * st.v) - st.a;
            let w = i1 * (y - st.y) - st.w;
            let b = i2 * (y - st.y - h * st.w) - st.b;
            out = St { x, v, a, y, w, b };
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

/// Runs the Newmark solver with step `dt` (s). Parameters are assumed valid.
pub(crate) fn run(p: &DamperParams, dt: f64, opts: &RunOptions) -> Run {
    let sys = Sys::new(p);
    let t_end = p.duration_s;
    let mut rec = Recorder::new(opts.history_samples, t_end);
    let mut st = St { x: 0.0, v: p.v0_m_s, a: 0.0, y: 0.0, w: 0.0, b: 0.0 };
    flight_accels(&sys, &mut st);
    rec.zdot(st.w - st.v);
    let mut energy = EnergyLedger { initial_j: 0.5 * sys.big_m * st.v * st.v, ..Default::default() };
    let mut impacts: Vec<ImpactEvent> = Vec::new();
    let n_steps = (t_end / dt).ceil() as u64;
    let mut k_next: u64 = 1;
    let mut t = 0.0;
    let mut wall = 0.0; // 0 in flight, ±1 in contact
    let mut cur =
        ImpactEvent { t_s: 0.0, wall: 0, u_in_m_s: 0.0, u_out_m_s: 0.0, t_end_s: 0.0, penetration_max_m: 0.0 };
    let mut cancelled = false;
    let mut counter: u32 = 0;

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
        if counter % 4096 == 0 && opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            cancelled = true;
            break;
        }
        if wall == 0.0 {
            let n1 = flight_step(&sys, &st, h);
            let z1 = n1.y - n1.x;
            let d1 = z1.abs() - sys.half_gap;
            if d1 > 0.0 {
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
                cur = ImpactEvent {
                    t_s: t,
                    wall: s as i8,
                    u_in_m_s: st.pen(&sys, s).1,
                    u_out_m_s: 0.0,
                    t_end_s: 0.0,
                    penetration_max_m: 0.0,
                };
                if th >= 1.0 {
                    k_next += 1;
                }
                continue;
            }
            commit(&mut rec, &mut energy, 0.0, t, &st, t_next, &n1);
            st = n1;
        } else {
            let s = wall;
            let n1 = contact_step(&sys, s, &st, h);
            let d1 = n1.pen(&sys, s).0;
            if d1 < 0.0 {
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
                }
                continue;
            }
            commit(&mut rec, &mut energy, s, t, &st, t_next, &n1);
            cur.penetration_max_m = cur.penetration_max_m.max(d1);
            st = n1;
        }
        t = t_next;
        k_next += 1;
    }
    rec.finish();
    let del = if wall != 0.0 { st.pen(&sys, wall).0.max(0.0) } else { 0.0 };
    energy.final_mechanical_j = 0.5 * sys.big_m * st.v * st.v
        + 0.5 * sys.m * st.w * st.w
        + 0.5 * sys.k * st.x * st.x
        + 0.4 * sys.k_hz * del * del * del.sqrt();
    Run {
        impacts,
        maxima: rec.maxima,
        zdot_abs_max_m_s: rec.zdot_abs_max,
        energy,
        history: rec.history,
        final_time_s: if cancelled { t } else { t_end },
        cancelled,
    }
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
