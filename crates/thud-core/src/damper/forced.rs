//! The main mass's flight under a harmonic force: paper Eq 25 with the force of the forced
//! problem on its right-hand side (docs/model.md §6.1),
//! `M·x'' + C·x' + K·x = F0·cos θ(t)`, `θ(t) = Ω·t + φ`, in closed form in every damping regime.
//! The ball's flight is unchanged (`m·y'' = 0`).
//!
//! Per unit mass, `x'' + 2γ·x' + ω0²·x = f·cos θ(t)` with `f = F0/M`, `γ = C/(2M)`, `ω0² = K/M`.
//! With `D = ω0² − Ω² + 2iγΩ`:
//! - `D ≠ 0` and `γ > 0`, or `ω0 = 0` (every case but the undamped oscillator with a spring): the
//!   steady solution `x_p = a·cos θ + b·sin θ`, `a = f·(ω0² − Ω²)/|D|²`, `b = f·2γΩ/|D|²`; the motion
//!   from `(x0, v0)` at `t0` is the free motion ([`Oscillator`]) from `(x0 − x_p(t0), v0 − x_p'(t0))`
//!   plus `x_p(t0 + τ)`.
//! - `γ = 0 < ω0` (undamped, resonance `Ω = ω0` included): the free motion from `(x0, v0)` plus the
//!   zero-state response, written in beat form so that it stays exact at and near resonance:
//!   with `σ = (Ω + ω0)/2`, `δ = (Ω − ω0)/2` and `Q(τ) = ∫₀^τ sin(ω0(τ − s))/ω0 · e^{iΩs} ds`,
//!   `Re Q = τ·sinc(δτ)·sin(στ)/(2σ)`, `Im Q = −τ·sinc(δτ)·cos(στ)/(2σ) + sin(ω0τ)/(2σω0)`,
//!   `Re Q' = τ·sinc(δτ)·cos(στ)/2 + sin(στ)·cos(δτ)/(2σ)`, `Im Q' = Ω·τ·sinc(δτ)·sin(στ)/(2σ)`,
//!   and `x_f = f·(cos θ0·Re Q − sin θ0·Im Q)`, `θ0 = θ(t0)`. At `δ = 0` this is the secular
//!   `τ·sin(ω0τ)/(2ω0)` of exact resonance.
//!
//! Units: metres, seconds, radians.

use super::flight::{Oscillator, Regime};
use super::roots::{self, NewtonEnd};

/// A harmonic force on the main mass, per unit main mass: `f·cos(Ω·t + φ)` (m/s²), `t` the
/// run's time (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Harmonic {
    /// `f = F0/M` (m/s²).
    pub f: f64,
    /// `Ω = 2π·freq` (rad/s).
    pub omega: f64,
    /// Phase `φ` at `t = 0` (rad): 0 for a run from rest; a continuation carries it over.
    pub phase: f64,
}

impl Harmonic {
    /// The force `force_n` (N) at `freq_hz` (Hz) with phase `phase` (rad) on a main mass `big_m` (kg).
    pub fn new(force_n: f64, big_m: f64, freq_hz: f64, phase: f64) -> Self {
        Harmonic { f: force_n / big_m, omega: 2.0 * std::f64::consts::PI * freq_hz, phase }
    }

    /// The phase `θ(t) = Ω·t + φ` (rad).
    #[inline]
    pub fn theta(&self, t: f64) -> f64 {
        self.omega * t + self.phase
    }

    /// The force per unit mass `f·cos θ(t)` (m/s²).
    #[inline]
    pub fn accel(&self, t: f64) -> f64 {
        self.f * self.theta(t).cos()
    }
}

/// How the forced part of the motion is evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Particular {
    /// `x_p = a·cos θ + b·sin θ` (m).
    Steady { a: f64, b: f64 },
    /// The undamped zero-state response in beat form: `ω0`, `σ = (Ω + ω0)/2`, `δ = (Ω − ω0)/2` (rad/s).
    Beat { w0: f64, sigma: f64, delta: f64 },
}

/// `sin(δ·τ)/δ` (s), exact as `δ → 0` (where it is `τ`).
#[inline]
fn sin_over(delta: f64, tau: f64) -> f64 {
    let u = delta * tau;
    if u.abs() < 1e-4 {
        let u2 = u * u;
        tau * (1.0 - u2 / 6.0 * (1.0 - u2 / 20.0))
    } else {
        u.sin() / delta
    }
}

/// Which zero of the flight the recorder needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ForcedEvent {
    /// A local maximum of `x` (`x'` from > 0 to ≤ 0).
    MaxX,
    /// A local minimum of `x` (`x'` from < 0 to ≥ 0).
    MinX,
    /// An upward zero crossing of `x`.
    UpCross,
    /// A zero of `x''` (an extremum of `x'`, hence of `z' = w − x'`).
    ZeroAccel,
}

/// The forced oscillator: the free [`Oscillator`], the load, and its forced part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Forced {
    pub osc: Oscillator,
    pub load: Harmonic,
    part: Particular,
    /// `ω0` (rad/s).
    w0: f64,
    /// The fastest angular frequency of the motion, `max(Ω, ω_d)` (rad/s); sets the sampling of
    /// the event search and the horizon of the acceleration bound.
    w_fast: f64,
}

impl Forced {
    /// The oscillator `osc` driven by `load`. `load.omega` must be > 0.
    pub fn new(osc: Oscillator, load: Harmonic) -> Self {
        let w0 = osc.w0sq.sqrt();
        let (om, g) = (load.omega, osc.gamma);
        let dr = osc.w0sq - om * om;
        let di = 2.0 * g * om;
        let den = dr * dr + di * di;
        let (a, b) = (load.f * dr / den, load.f * di / den);
        let steady_ok = den.is_normal() && a.is_finite() && b.is_finite();
        // γ = 0 with a spring: the beat form (exact at resonance). A γ > 0 so small that |D|²
        // underflows (2γΩ < 1e-154 1/s²) changes the forced motion by less than a rounding error
        // over any run in range, so it takes the beat form too.
        let part = if w0 > 0.0 && (g == 0.0 || !steady_ok) {
            Particular::Beat { w0, sigma: 0.5 * (om + w0), delta: 0.5 * (om - w0) }
        } else {
            Particular::Steady { a, b }
        };
        let wd = match osc.regime {
            Regime::Under { wd, .. } => wd,
            _ => 0.0,
        };
        Forced { osc, load, part, w0, w_fast: om.max(wd) }
    }

    /// The steady solution and its rate `(x_p, x_p')` at time `t` (steady form only).
    #[inline]
    fn particular(&self, a: f64, b: f64, t: f64) -> (f64, f64) {
        let (s, c) = self.load.theta(t).sin_cos();
        (a * c + b * s, self.load.omega * (b * c - a * s))
    }

    /// The undamped zero-state response and its rate a time `tau` after `t0`, where
    /// `θ(t0) = atan2(s0, c0)` (beat form).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn beat(&self, w0: f64, sigma: f64, delta: f64, s0: f64, c0: f64, tau: f64) -> (f64, f64) {
        let (ss, cs) = (sigma * tau).sin_cos();
        let ts = sin_over(delta, tau);
        let cd = (delta * tau).cos();
        let k = 0.5 / sigma;
        let re_q = ts * ss * k;
        let im_q = -ts * cs * k + (w0 * tau).sin() * k / w0;
        let re_qd = 0.5 * ts * cs + ss * cd * k;
        let im_qd = self.load.omega * ts * ss * k;
        let f = self.load.f;
        (f * (c0 * re_q - s0 * im_q), f * (c0 * re_qd - s0 * im_qd))
    }

    /// Position and velocity `(x, x')` a time `tau` (s) after the state `(x0, v0)` at time `t0`.
    #[inline]
    pub fn advance(&self, t0: f64, x0: f64, v0: f64, tau: f64) -> (f64, f64) {
        self.segment(t0, x0, v0).at(tau)
    }

    /// The flight from `(x0, v0)` at `t0`, with what stays the same along it computed once.
    #[inline]
    pub fn segment(&self, t0: f64, x0: f64, v0: f64) -> Segment<'_> {
        let (h0, trig0) = match self.part {
            Particular::Steady { a, b } => {
                let (xp0, vp0) = self.particular(a, b, t0);
                ((x0 - xp0, v0 - vp0), (0.0, 1.0))
            }
            Particular::Beat { .. } => ((x0, v0), self.load.theta(t0).sin_cos()),
        };
        Segment { fo: self, t0, h0, trig0 }
    }

    /// The steady solution and its rate `(x_p, x_p')` (m, m/s) at time `t`; None in beat form
    /// (undamped, where there is no steady solution to settle to).
    pub fn steady_at(&self, t: f64) -> Option<(f64, f64)> {
        match self.part {
            Particular::Steady { a, b } => Some(self.particular(a, b, t)),
            Particular::Beat { .. } => None,
        }
    }

    /// The envelope of the flight from `(x0, v0)` at `t0` (docs/model.md §6.4): the steady
    /// solution's amplitude `X = √(a² + b²)` (m), and `R` (m) with
    /// `|x(t0 + τ) − x_p(t0 + τ)| ≤ R·e^{−γτ}` for every `τ ≥ 0` the flight lasts. The free part
    /// is `e^{−γτ}·[h·cos ωd τ + (h' + γh)/ωd·sin ωd τ]` (flight.rs) with `(h, h')` its start, and
    /// the bracket is at most `√(h² + ((h' + γh)/ωd)²)`. Underdamped (`γ > 0`) in steady form
    /// only; None otherwise.
    pub fn envelope(&self, t0: f64, x0: f64, v0: f64) -> Option<(f64, f64)> {
        let (Particular::Steady { a, b }, Regime::Under { wd, .. }) = (self.part, self.osc.regime) else {
            return None;
        };
        let g = self.osc.gamma;
        if g <= 0.0 {
            return None;
        }
        let (xp, vp) = self.particular(a, b, t0);
        let (h, hd) = (x0 - xp, v0 - vp);
        let r = h.hypot((hd + g * h) / wd);
        let x = a.hypot(b);
        (x.is_finite() && r.is_finite()).then_some((x, r))
    }

    /// Acceleration `x''` (m/s²) at the state `(x, v)` at time `t`.
    #[inline]
    pub fn accel(&self, t: f64, x: f64, v: f64) -> f64 {
        self.osc.accel(x, v) + self.load.accel(t)
    }

    /// Jerk `x'''` (m/s³) at the state `(x, v)` with acceleration `a` at time `t`.
    #[inline]
    fn jerk(&self, t: f64, v: f64, a: f64) -> f64 {
        -2.0 * self.osc.gamma * a - self.osc.w0sq * v - self.load.f * self.load.omega * self.load.theta(t).sin()
    }

    /// The horizon (s) over which [`Forced::accel_bound`] is taken: an eighth of the fastest
    /// period of the motion.
    #[inline]
    pub fn horizon(&self) -> f64 {
        std::f64::consts::PI / (4.0 * self.w_fast)
    }

    /// A bound on `|x''|` over the next `h` seconds from the state `(x, v)`. With
    /// `E = x'² + ω0²·x²`, `dE/dt = 2x'·(f·cos θ − 2γx') ≤ 2f·√E`, so `√E` grows by at most
    /// `f·h`; and `|x''| ≤ 2γ|x'| + ω0²|x| + f ≤ (2γ + ω0)·√E + f` (m/s²).
    #[inline]
    pub fn accel_bound(&self, x: f64, v: f64, h: f64) -> f64 {
        let e = (v * v + self.osc.w0sq * x * x).sqrt();
        (2.0 * self.osc.gamma + self.w0) * (e + self.load.f * h) + self.load.f
    }

    /// The viscous dissipation and the work of the force (J) over a flight of `tf` (s) from
    /// `(x0, v0)` at `t0` to `(x1, v1)`, for a main mass `big_m` (kg) on stiffness `k` (N/m).
    ///
    /// The main mass's energy `E = ½Mx'² + ½Kx²` changes by `W − V` (work in, viscous out).
    /// Without damping `V = 0`. With damping `W = M·f·∫cos θ·x' dt` follows from boundary values
    /// alone (Green's identity with `cos θ` and `sin θ`, which solve `u'' = −Ω²u`; the 2×2 system
    /// has determinant `|D|²`); where `|D|²` is too small for that to be accurate (light damping
    /// at resonance) the integral is taken by Gauss–Legendre quadrature instead.
    #[allow(clippy::too_many_arguments)]
    pub fn flight_energies(
        &self,
        big_m: f64,
        k: f64,
        t0: f64,
        x0: f64,
        v0: f64,
        tf: f64,
        x1: f64,
        v1: f64,
    ) -> (f64, f64) {
        let e0 = 0.5 * big_m * v0 * v0 + 0.5 * k * x0 * x0;
        let e1 = 0.5 * big_m * v1 * v1 + 0.5 * k * x1 * x1;
        let g = self.osc.gamma;
        if g == 0.0 {
            return (0.0, e1 - e0);
        }
        let om = self.load.omega;
        let dp = om * om - self.osc.w0sq;
        let e = 2.0 * g * om;
        let den = dp * dp + e * e;
        let scale = om * om + self.osc.w0sq + e;
        let f = self.load.f;
        let work_per_kg = if den > 1e-6 * scale * scale {
            let (s0, c0) = self.load.theta(t0).sin_cos();
            let (s1, c1) = self.load.theta(t0 + tf).sin_cos();
            let cos2 = 0.5 * tf + (s1 * c1 - s0 * c0) / (2.0 * om);
            let sincos = (s1 * s1 - s0 * s0) / (2.0 * om);
            let cx = c1 * x1 - c0 * x0;
            let sx = s1 * x1 - s0 * x0;
            let r1 = (c1 * v1 - c0 * v0) + om * sx + 2.0 * g * cx - f * cos2;
            let r2 = (s1 * v1 - s0 * v0) - om * cx + 2.0 * g * sx - f * sincos;
            let j_s = (dp * r2 - e * r1) / den;
            f * (cx + om * j_s)
        } else {
            // Panels of a quarter of the integrand's fastest period (cos θ·x' carries Ω + ω_d).
            let n = ((tf * (om + self.w_fast) / std::f64::consts::FRAC_PI_2).ceil() as usize).max(1);
            crate::acoustics::gauss_legendre(0.0, tf, n, |s| self.load.accel(t0 + s) * self.advance(t0, x0, v0, s).1)
        };
        let work = big_m * work_per_kg;
        (e0 - e1 + work, work)
    }
}

/// One flight of the forced oscillator from `(x0, v0)` at `t0`, with the start of its free part
/// (and, in beat form, the force's phase there) computed once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Segment<'a> {
    fo: &'a Forced,
    t0: f64,
    /// The free part's start: `(x0 − x_p(t0), v0 − x_p'(t0))` in steady form, `(x0, v0)` in beat form.
    h0: (f64, f64),
    /// `(sin θ(t0), cos θ(t0))` (beat form only).
    trig0: (f64, f64),
}

impl Segment<'_> {
    /// `(x, x')` a time `tau` (s) into the flight.
    #[inline]
    pub fn at(&self, tau: f64) -> (f64, f64) {
        let fo = self.fo;
        let (xh, vh) = fo.osc.advance(self.h0.0, self.h0.1, tau);
        let (xf, vf) = match fo.part {
            Particular::Steady { a, b } => fo.particular(a, b, self.t0 + tau),
            Particular::Beat { w0, sigma, delta } => fo.beat(w0, sigma, delta, self.trig0.0, self.trig0.1, tau),
        };
        (xh + xf, vh + vf)
    }

    /// Calls `f(kind, τ, x, x')` in time order for the zeros of the flight over `τ ∈ (0, tf]`
    /// (see [`ForcedEvent`]). The flight is sampled at a sixteenth of its fastest period; each
    /// sign change is refined by safeguarded Newton to a few ulp. (Two zeros closer than a
    /// sample apart — a near-tangency — are passed over: at most a wiggle of `x` that small.)
    pub fn for_each_event(&self, tf: f64, mut f: impl FnMut(ForcedEvent, f64, f64, f64)) {
        if tf <= 0.0 {
            return;
        }
        let fo = self.fo;
        let t0 = self.t0;
        let n = ((tf / (fo.horizon() * 0.5)).ceil() as usize).max(1);
        let at = |tau: f64| {
            let (x, v) = self.at(tau);
            (x, v, fo.accel(t0 + tau, x, v))
        };
        let (x0, v0) = self.at(0.0);
        let (mut x_a, mut v_a, mut a_a) = (x0, v0, fo.accel(t0, x0, v0));
        let mut tau_a = 0.0;
        for j in 1..=n {
            let tau_b = if j == n { tf } else { tf * j as f64 / n as f64 };
            let (x_b, v_b, a_b) = at(tau_b);
            let mut evs: [(ForcedEvent, f64); 3] = [(ForcedEvent::MaxX, f64::INFINITY); 3];
            let rate = |tau: f64| {
                let (x, v) = self.at(tau);
                (v, fo.accel(t0 + tau, x, v))
            };
            if v_a > 0.0 && v_b <= 0.0 {
                evs[0] = (ForcedEvent::MaxX, root(tau_a, tau_b, v_a, v_b, rate));
            } else if v_a < 0.0 && v_b >= 0.0 {
                evs[0] = (ForcedEvent::MinX, root(tau_a, tau_b, v_a, v_b, rate));
            }
            if x_a <= 0.0 && x_b > 0.0 {
                evs[1] = (ForcedEvent::UpCross, root(tau_a, tau_b, x_a, x_b, |tau| self.at(tau)));
            }
            if (a_a > 0.0 && a_b < 0.0) || (a_a < 0.0 && a_b > 0.0) {
                let r = root(tau_a, tau_b, a_a, a_b, |tau| {
                    let (x, v) = self.at(tau);
                    let a = fo.accel(t0 + tau, x, v);
                    (a, fo.jerk(t0 + tau, v, a))
                });
                evs[2] = (ForcedEvent::ZeroAccel, r);
            }
            if evs.iter().any(|e| e.1.is_finite()) {
                evs.sort_by(|p, q| p.1.total_cmp(&q.1));
                for (kind, tau) in evs {
                    if tau.is_finite() {
                        let (x, v) = self.at(tau);
                        f(kind, tau, x, v);
                    }
                }
            }
            (x_a, v_a, a_a, tau_a) = (x_b, v_b, a_b, tau_b);
        }
    }
}

/// The zero of `g` in `[lo, hi]` given `g(lo) = g_lo` and `g(hi) = g_hi` of opposite signs
/// (or one of them 0); `g(τ)` returns the value and its derivative. Newton from the secant
/// point, kept inside the bracket by bisection, to a bracket of a few ulp.
fn root(lo: f64, hi: f64, g_lo: f64, g_hi: f64, g: impl Fn(f64) -> (f64, f64)) -> f64 {
    if g_lo == 0.0 {
        return lo;
    }
    if g_hi == 0.0 {
        return hi;
    }
    let start = lo + (hi - lo) * (g_lo / (g_lo - g_hi));
    roots::newton((lo, hi), g_lo < 0.0, start, NewtonEnd::Ulp, g)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: classical RK4 with a fine step on `x'' = −2γx' − ω0²x + f·cos(Ωt + φ)`,
    /// written here independently of the closed form, and Richardson-extrapolated from two steps.
    #[allow(clippy::too_many_arguments)]
    fn rk4(big_m: f64, k: f64, c: f64, load: Harmonic, t0: f64, x0: f64, v0: f64, tau: f64, n: usize) -> (f64, f64) {
        let acc = |t: f64, x: f64, v: f64| (-c * v - k * x) / big_m + load.f * (load.omega * t + load.phase).cos();
        let h = tau / n as f64;
        let (mut x, mut v) = (x0, v0);
        for i in 0..n {
            let t = t0 + i as f64 * h;
            let (k1x, k1v) = (v, acc(t, x, v));
            let (k2x, k2v) = (v + 0.5 * h * k1v, acc(t + 0.5 * h, x + 0.5 * h * k1x, v + 0.5 * h * k1v));
            let (k3x, k3v) = (v + 0.5 * h * k2v, acc(t + 0.5 * h, x + 0.5 * h * k2x, v + 0.5 * h * k2v));
            let (k4x, k4v) = (v + h * k3v, acc(t + h, x + h * k3x, v + h * k3v));
            x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
        (x, v)
    }

    #[allow(clippy::too_many_arguments)]
    fn reference(big_m: f64, k: f64, c: f64, load: Harmonic, t0: f64, x0: f64, v0: f64, tau: f64) -> (f64, f64) {
        let n = 40_000;
        let (x1, v1) = rk4(big_m, k, c, load, t0, x0, v0, tau, n);
        let (x2, v2) = rk4(big_m, k, c, load, t0, x0, v0, tau, 2 * n);
        // RK4's error falls as h⁴: one Richardson step leaves O(h⁵).
        (x2 + (x2 - x1) / 15.0, v2 + (v2 - v1) / 15.0)
    }

    /// The closed form against the ODE integrated numerically, to 1e-10 of the motion's size,
    /// in every regime the forced flight has.
    fn check(big_m: f64, k: f64, c: f64, force: f64, freq: f64, want: &str) {
        let osc = Oscillator::new(big_m, k, c);
        let load = Harmonic::new(force, big_m, freq, 0.3);
        let fo = Forced::new(osc, load);
        let kind = match fo.part {
            Particular::Steady { .. } => "steady",
            Particular::Beat { .. } => "beat",
        };
        assert_eq!(kind, want, "M {big_m} K {k} C {c} f {freq}");
        for &(t0, x0, v0, tau) in &[(0.0, 0.0, 0.0, 0.9), (1.7, 0.013, -0.7, 0.6), (0.05, -0.02, 0.1, 1.3)] {
            let (x, v) = fo.advance(t0, x0, v0, tau);
            let (xr, vr) = reference(big_m, k, c, load, t0, x0, v0, tau);
            let size = x.abs().max(xr.abs()).max(x0.abs()) + 1e-3;
            let vsize = v.abs().max(vr.abs()).max(v0.abs()) + 1e-3;
            assert!((x - xr).abs() < 1e-10 * size, "{want} x {x} vs {xr} (t0 {t0}, τ {tau})");
            assert!((v - vr).abs() < 1e-10 * vsize, "{want} v {v} vs {vr} (t0 {t0}, τ {tau})");
        }
    }

    #[test]
    fn forced_flight_matches_the_ode_in_every_regime() {
        let w0 = (500.0f64 / 0.5).sqrt();
        let f0 = w0 / (2.0 * std::f64::consts::PI);
        // Lightly damped (Table 2), off and at resonance.
        check(0.5, 500.0, 0.05, 1.0, 3.0, "steady");
        check(0.5, 500.0, 0.05, 1.0, f0, "steady");
        // Heavily underdamped, critically damped, overdamped, K = 0 < C.
        check(0.5, 500.0, 25.0, 2.0, 7.0, "steady");
        check(0.5, 2.0, 2.0, 1.0, 1.5, "steady");
        check(0.5, 500.0, 80.0, 3.0, 4.0, "steady");
        check(0.5, 0.0, 3.0, 1.0, 2.0, "steady");
        // K = C = 0: a free mass shaken.
        check(0.5, 0.0, 0.0, 1.0, 2.0, "steady");
        // Undamped off resonance, near it, and exactly at it (Ω = ω0 with C = 0: secular growth).
        check(0.5, 500.0, 0.0, 1.0, 3.0, "beat");
        check(0.5, 500.0, 0.0, 1.0, f0 * (1.0 + 1e-9), "beat");
        let exact = Forced::new(Oscillator::new(0.5, 500.0, 0.0), Harmonic { f: 2.0, omega: w0, phase: 0.0 });
        assert!(matches!(exact.part, Particular::Beat { delta, .. } if delta == 0.0));
        for &tau in &[0.1, 1.0, 10.0] {
            // From rest at t0 = 0 with φ = 0: x = f·τ·sin(ω0τ)/(2ω0), x' = f·(sin(ω0τ)/ω0 + τ·cos(ω0τ))/2.
            let (x, v) = exact.advance(0.0, 0.0, 0.0, tau);
            let f = 2.0;
            let xr = f * tau * (w0 * tau).sin() / (2.0 * w0);
            let vr = 0.5 * f * ((w0 * tau).sin() / w0 + tau * (w0 * tau).cos());
            assert!((x - xr).abs() < 1e-13 * (1.0 + tau), "{x} {xr}");
            assert!((v - vr).abs() < 1e-12 * (1.0 + tau) * w0, "{v} {vr}");
        }
    }

    #[test]
    fn flight_energies_balance_the_mechanical_energy() {
        for &(k, c, freq) in &[
            (500.0, 0.05, 3.0),
            (500.0, 0.05, 5.0329),
            (500.0, 0.001, 5.0329),
            (500.0, 25.0, 7.0),
            (0.0, 3.0, 2.0),
            (500.0, 0.0, 5.0),
        ] {
            let fo = Forced::new(Oscillator::new(0.5, k, c), Harmonic::new(1.0, 0.5, freq, 0.2));
            let (t0, x0, v0, tf) = (0.37, 0.004, -0.3, 0.8);
            let (x1, v1) = fo.advance(t0, x0, v0, tf);
            let (visc, work) = fo.flight_energies(0.5, k, t0, x0, v0, tf, x1, v1);
            // The energies the dissipation is the balance of (J).
            let e_scale = 0.25 * (v0 * v0 + v1 * v1) + 0.5 * k * (x0 * x0 + x1 * x1) + work.abs();
            // The work, by brute-force quadrature of F·x' on the closed form.
            let w_ref = 0.5
                * crate::acoustics::gauss_legendre(0.0, tf, 400, |s| {
                    fo.load.accel(t0 + s) * fo.advance(t0, x0, v0, s).1
                });
            let v_ref = c * crate::acoustics::gauss_legendre(0.0, tf, 400, |s| fo.advance(t0, x0, v0, s).1.powi(2));
            assert!((work - w_ref).abs() < 1e-10 * w_ref.abs().max(1e-6), "k {k} c {c} f {freq}: {work} vs {w_ref}");
            assert!((visc - v_ref).abs() < 1e-12 * e_scale, "k {k} c {c} f {freq}: {visc} vs {v_ref}");
        }
    }

    #[test]
    fn events_are_zeros_of_the_flight() {
        let fo = Forced::new(Oscillator::new(0.5, 500.0, 0.05), Harmonic::new(1.0, 0.5, 3.0, 0.0));
        let (t0, x0, v0) = (0.2, 0.0, 0.4);
        let mut seen = [0; 4];
        let mut last = 0.0;
        fo.segment(t0, x0, v0).for_each_event(1.5, |kind, tau, x, v| {
            assert!(tau >= last && tau <= 1.5);
            last = tau;
            match kind {
                ForcedEvent::MaxX => {
                    seen[0] += 1;
                    assert!(v.abs() < 1e-12, "v {v}");
                }
                ForcedEvent::MinX => {
                    seen[1] += 1;
                    assert!(v.abs() < 1e-12, "v {v}");
                }
                ForcedEvent::UpCross => {
                    seen[2] += 1;
                    assert!(x.abs() < 1e-15, "x {x}");
                }
                ForcedEvent::ZeroAccel => {
                    seen[3] += 1;
                    assert!(fo.accel(t0 + tau, x, v).abs() < 1e-9, "a");
                }
            }
        });
        assert!(seen.iter().all(|&n| n >= 3), "{seen:?}");
    }

    #[test]
    fn the_acceleration_bound_holds_over_its_horizon() {
        for &(k, c, freq) in &[(500.0, 0.05, 5.0329), (500.0, 0.0, 5.0329), (0.0, 0.0, 2.0), (500.0, 80.0, 9.0)] {
            let fo = Forced::new(Oscillator::new(0.5, k, c), Harmonic::new(3.0, 0.5, freq, 1.0));
            let h = fo.horizon();
            let (mut t, mut x, mut v) = (0.0, 0.01, -0.2);
            for _ in 0..200 {
                let bound = fo.accel_bound(x, v, h);
                for j in 1..=50 {
                    let s = h * f64::from(j) / 50.0;
                    let (xs, vs) = fo.advance(t, x, v, s);
                    assert!(fo.accel(t + s, xs, vs).abs() <= bound * (1.0 + 1e-12), "k {k} c {c}");
                }
                (x, v) = fo.advance(t, x, v, h);
                t += h;
            }
        }
    }

    /// The envelope bounds the free part of every flight: |x − x_p| ≤ R·e^{−γτ} at every sample
    /// of twenty periods, for starts of every size and phase; the steady amplitude is √(a² + b²)
    /// checked against the closed form F0/(M·|D|).
    #[test]
    fn the_envelope_bounds_the_free_part() {
        for &(k, c, freq) in &[(500.0, 0.05, 5.0329), (500.0, 1.5, 3.0), (500.0, 20.0, 8.0)] {
            let (big_m, f0) = (0.5, 3.0);
            let fo = Forced::new(Oscillator::new(big_m, k, c), Harmonic::new(f0, big_m, freq, 0.7));
            let om = std::f64::consts::TAU * freq;
            let d = ((k / big_m - om * om).powi(2) + (c / big_m * om).powi(2)).sqrt();
            for &(t0, x0, v0) in &[(0.0, 0.0, 0.0), (0.3, 0.02, -0.5), (1.1, -0.004, 2.0), (2.0, 1e-6, 0.0)] {
                let (x_s, r) = fo.envelope(t0, x0, v0).unwrap();
                assert!((x_s - f0 / big_m / d).abs() <= 1e-12 * x_s, "X {x_s}");
                let g = c / (2.0 * big_m);
                let mut touched = 0.0f64;
                for j in 0..=4000 {
                    let tau = 20.0 / freq * f64::from(j) / 4000.0;
                    let (x, _) = fo.advance(t0, x0, v0, tau);
                    let (xp, _) = fo.steady_at(t0 + tau).unwrap();
                    let free = (x - xp).abs();
                    let bound = r * (-g * tau).exp();
                    assert!(free <= bound * (1.0 + 1e-9) + 1e-15, "k {k} c {c}: {free} > {bound}");
                    touched = touched.max(free / bound.max(f64::MIN_POSITIVE));
                }
                assert!(touched > 0.99 || r < 1e-12, "the bound is reached (not loose): {touched}");
            }
        }
        let undamped = Forced::new(Oscillator::new(0.5, 500.0, 0.0), Harmonic::new(1.0, 0.5, 4.0, 0.0));
        assert!(undamped.envelope(0.0, 0.0, 0.0).is_none(), "no steady state to settle to");
    }
}
