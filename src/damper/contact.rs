//! The in-contact integrator of the event solver: adaptive Dormand–Prince 5(4) on the coupled
//! equations of paper Eq 26 while the ball presses a wall.
//!
//! State `[x, x', δ, δ', E_contact, E_viscous]`: main-mass position (m) and velocity (m/s), the
//! penetration `δ = s·z − d/2` (m) and its rate (m/s) at wall `s = ±1`, and the energies (J)
//! dissipated so far by the contact damping and by the viscous damper. With the bracket
//! `F = K_HZ·δ₊^{3/2} + c1·δ'` (clamped at ≥ 0 under "no tension"), the force on the ball is
//! `−s·F`, on the main mass `+s·F`, so
//! `M·x'' = −C·x' − K·x + s·F` and `δ'' = −K*·F + s·(C·x' + K·x)/M`, `K* = (m+M)/(m·M)`.
//! The law is extended smoothly past the exit (`δ₊ = max(δ, 0)`) so the exit root is well posed.

use crate::contact::{contact_duration, peak_approach};

use super::DamperParams;

/// The physical constants of one design, in SI units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sys {
    pub big_m: f64,
    pub m: f64,
    pub k: f64,
    pub c: f64,
    /// d/2 (m).
    pub half_gap: f64,
    pub k_hz: f64,
    pub c1: f64,
    pub no_tension: bool,
    /// K* = (m+M)/(m·M) (1/kg).
    pub kstar: f64,
}

impl Sys {
    pub fn new(p: &DamperParams) -> Self {
        Sys {
            big_m: p.main_mass_kg,
            m: p.impact_mass_kg,
            k: p.stiffness_n_m,
            c: p.damping_n_s_m,
            half_gap: 0.5 * p.gap_m,
            k_hz: p.k_hz,
            c1: p.c1_n_s_m,
            no_tension: p.no_tension,
            kstar: (p.impact_mass_kg + p.main_mass_kg) / (p.impact_mass_kg * p.main_mass_kg),
        }
    }

    /// `(F, K_HZ·δ₊^{3/2}, clamped)`: the contact bracket (N) and its elastic part.
    #[inline]
    pub fn bracket(&self, del: f64, dd: f64) -> (f64, f64, bool) {
        let dp = del.max(0.0);
        let hz = self.k_hz * dp * dp.sqrt();
        let f = hz + self.c1 * dd;
        if self.no_tension && f < 0.0 {
            (0.0, hz, true)
        } else {
            (f, hz, false)
        }
    }
}

pub(crate) type State = [f64; 6];

#[inline]
fn rhs(sys: &Sys, s: f64, y: &State) -> State {
    let (x, v, del, dd) = (y[0], y[1], y[2], y[3]);
    let (f, hz, _) = sys.bracket(del, dd);
    let spring = -sys.c * v - sys.k * x;
    [v, (spring + s * f) / sys.big_m, dd, -sys.kstar * f - s * spring / sys.big_m, (f - hz) * dd, sys.c * v * v]
}

// Dormand–Prince 5(4) coefficients.
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const B1: f64 = 35.0 / 384.0;
const B3: f64 = 500.0 / 1113.0;
const B4: f64 = 125.0 / 192.0;
const B5: f64 = -2187.0 / 6784.0;
const B6: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

/// Relative tolerance of the contact integrator (on a state scaled by the contact's own sizes).
pub(crate) const RTOL: f64 = 1e-10;

/// One DOPRI5 step of length `h` from `y` (with `k1 = f(y)`): the new state, `f(new)` and the
/// scaled error norm (max norm over x, x', δ, δ' with scales `sc`).
#[inline]
fn step(sys: &Sys, s: f64, y: &State, k1: &State, h: f64, sc: &[f64; 4]) -> (State, State, f64) {
    let mut t = [0.0; 6];
    for i in 0..6 {
        t[i] = y[i] + h * A21 * k1[i];
    }
    let k2 = rhs(sys, s, &t);
    for i in 0..6 {
        t[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
    }
    let k3 = rhs(sys, s, &t);
    for i in 0..6 {
        t[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
    }
    let k4 = rhs(sys, s, &t);
    for i in 0..6 {
        t[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
    }
    let k5 = rhs(sys, s, &t);
    for i in 0..6 {
        t[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
    }
    let k6 = rhs(sys, s, &t);
    let mut yn = [0.0; 6];
    for i in 0..6 {
        yn[i] = y[i] + h * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i] + B6 * k6[i]);
    }
    let k7 = rhs(sys, s, &yn);
    let mut err: f64 = 0.0;
    for i in 0..4 {
        let e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
        let tol = RTOL * (sc[i] + y[i].abs().max(yn[i].abs()));
        err = err.max(e.abs() / tol);
    }
    (yn, k7, err)
}

/// How a contact integration ended.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactEnd {
    /// Time (s) and state at the end.
    pub t: f64,
    pub y: State,
    /// The ball left the wall (δ back to 0, set exactly).
    pub completed: bool,
    /// The "contact" never produced a positive penetration (a numerical graze): carry on in flight.
    pub grazed: bool,
    /// Peak penetration (m), refined where δ' = 0.
    pub pen_max: f64,
}

/// Integrates one contact at wall `s` from `y0` (δ = 0, δ' > 0) at time `t0` until the exit
/// (δ returns to 0), the time limit `t_limit`, or `budget` steps run out. `a_bound` (m/s²) bounds
/// the non-contact relative acceleration (used to size the first step of slow contacts).
/// `obs(t0, y0, k0, t1, y1, k1)` sees every accepted step (states and their derivatives).
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate(
    sys: &Sys,
    s: f64,
    t0: f64,
    y0: State,
    t_limit: f64,
    budget: &mut usize,
    a_bound: f64,
    mut obs: impl FnMut(f64, &State, &State, f64, &State, &State),
) -> ContactEnd {
    let u0 = y0[3].abs().max(1e-12);
    let amax = peak_approach(u0, sys.kstar, sys.k_hz);
    let tau = contact_duration(amax, u0);
    let sc = [2.0 * sys.half_gap + y0[0].abs(), y0[1].abs() + u0, amax, u0];
    let mut h = tau / 50.0;
    if a_bound > 0.0 {
        h = h.min(0.1 * u0 / a_bound);
    }
    let mut t = t0;
    let mut y = y0;
    let mut k1 = rhs(sys, s, &y);
    let mut had_pos = false;
    let mut pen: f64 = 0.0;
    let mut err_old: f64 = 1e-4;
    loop {
        if *budget == 0 {
            return ContactEnd { t, y, completed: false, grazed: false, pen_max: pen };
        }
        let last = t + h >= t_limit;
        if last {
            h = t_limit - t;
        }
        let (yn, k7, err) = step(sys, s, &y, &k1, h, &sc);
        *budget -= 1;
        if !(err <= 1.0) {
            let f = if err.is_finite() { (0.9 * err.powf(-0.2)).max(0.2) } else { 0.2 };
            h *= f;
            continue;
        }
        if !had_pos && yn[2] <= 0.0 {
            // The first step jumped over a (tiny) contact: shorten it, or call it a graze.
            if h <= 1e-14 * tau.max(1e-12) || last {
                obs(t, &y, &k1, t + h, &yn, &k7);
                let t1 = if last { t_limit } else { t + h };
                return ContactEnd { t: t1, y: yn, completed: false, grazed: true, pen_max: 0.0 };
            }
            h *= 0.25;
            continue;
        }
        had_pos = true;
        if y[3] > 0.0 && yn[3] <= 0.0 {
            pen = pen.max(refine_peak(sys, s, &y, &k1, h, &yn, &sc, budget));
        }
        pen = pen.max(yn[2]);
        if yn[2] <= 0.0 {
            let (he, mut ye) = refine_exit(sys, s, &y, &k1, h, &yn, &sc, budget);
            ye[2] = 0.0;
            let ke = rhs(sys, s, &ye);
            obs(t, &y, &k1, t + he, &ye, &ke);
            return ContactEnd { t: t + he, y: ye, completed: true, grazed: false, pen_max: pen };
        }
        obs(t, &y, &k1, if last { t_limit } else { t + h }, &yn, &k7);
        if last {
            return ContactEnd { t: t_limit, y: yn, completed: false, grazed: false, pen_max: pen };
        }
        t += h;
        y = yn;
        k1 = k7;
        // PI step-size control (Hairer's dopri5: α = 0.17, β = 0.04).
        let e = err.max(1e-10);
        let fac = (0.9 * e.powf(-0.17) * err_old.powf(0.04)).clamp(0.2, 5.0);
        err_old = e.max(1e-4);
        h *= fac;
    }
}

/// The peak penetration inside a step where δ' goes from > 0 to ≤ 0: Newton on the step length
/// for δ'(h*) = 0 (derivative δ'' from the equations of motion), safeguarded by bisection.
#[allow(clippy::too_many_arguments)]
fn refine_peak(sys: &Sys, s: f64, y: &State, k1: &State, h: f64, yn: &State, sc: &[f64; 4], budget: &mut usize) -> f64 {
    let (mut lo, mut hi) = (0.0, h);
    // Secant start.
    let mut hh = h * y[3] / (y[3] - yn[3]);
    let mut best = y[2].max(yn[2]);
    for _ in 0..8 {
        if !(hh > lo && hh < hi) {
            hh = 0.5 * (lo + hi);
        }
        let (ys, ks, _) = step(sys, s, y, k1, hh, sc);
        *budget = budget.saturating_sub(1);
        best = best.max(ys[2]);
        let g = ys[3];
        if g > 0.0 {
            lo = hh;
        } else {
            hi = hh;
        }
        let dg = ks[3];
        if g.abs() <= 1e-15 * sc[3] || dg == 0.0 {
            break;
        }
        let next = hh - g / dg;
        if (next - hh).abs() <= 1e-16 * h {
            break;
        }
        hh = next;
    }
    best
}

/// The exit inside a step where δ goes from > 0 to ≤ 0: Newton on the step length for
/// δ(h*) = 0 (derivative δ'), safeguarded by bisection. Returns `(h*, state)`.
#[allow(clippy::too_many_arguments)]
fn refine_exit(
    sys: &Sys,
    s: f64,
    y: &State,
    k1: &State,
    h: f64,
    yn: &State,
    sc: &[f64; 4],
    budget: &mut usize,
) -> (f64, State) {
    let (mut lo, mut hi) = (0.0, h);
    let mut hh = h * y[2] / (y[2] - yn[2]);
    let mut out = (h, *yn);
    for _ in 0..12 {
        if !(hh > lo && hh < hi) {
            hh = 0.5 * (lo + hi);
        }
        let (ys, _, _) = step(sys, s, y, k1, hh, sc);
        *budget = budget.saturating_sub(1);
        out = (hh, ys);
        let g = ys[2];
        if g > 0.0 {
            lo = hh;
        } else {
            hi = hh;
        }
        if g.abs() <= 1e-15 * sc[2] || ys[3] == 0.0 {
            break;
        }
        let next = hh - g / ys[3];
        if (next - hh).abs() <= 1e-16 * h {
            break;
        }
        hh = next;
    }
    out
}
